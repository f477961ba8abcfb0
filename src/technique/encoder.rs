//! Recording a frame: passes opened here get bind group 0 set, timestamp queries and
//! pipeline-statistics queries (the work they did, [`super::work`]) added.

use super::pass::{ComputePass, Counting, PassCounts, RenderPass};
use super::work::{SegmentQueries, WorkCounter};
use crate::scene::SceneGpu;
use crate::{GpuContext, RenderTarget};

/// Whether a pass rasterises or computes (lavapipe's compute timestamps are wrong, so the two
/// are reported in separate columns).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PassKind {
    /// A render pass.
    Render,
    /// A compute pass.
    Compute,
}

/// GPU time of one pass from its timestamps.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PassTime {
    /// Pass label.
    pub label: String,
    /// Render or compute.
    pub kind: PassKind,
    /// Milliseconds between the pass's begin and end timestamps.
    pub ms: f64,
}

/// Most passes a frame can time (2 queries each).
pub const MAX_TIMED_PASSES: u32 = 64;

/// A query set and the buffers to read it back, reused frame after frame.
pub struct PassTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    passes: Vec<(String, PassKind)>,
    period_ns: f64,
}

impl PassTimer {
    /// A timer, or `None` when the device has no timestamp queries.
    pub fn new(gpu: &GpuContext) -> Option<Self> {
        if !gpu.has_timestamps() {
            return None;
        }
        let count = MAX_TIMED_PASSES * 2;
        let size = u64::from(count) * 8;
        Some(Self {
            queries: gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamp resolve"),
                size,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            readback: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamp readback"),
                size,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            }),
            passes: Vec::new(),
            period_ns: f64::from(gpu.summary.timestamp_period_ns),
        })
    }

    /// Reads the last frame's pass times. Call after the frame's submission completed.
    pub fn read(&mut self, gpu: &GpuContext) -> Vec<PassTime> {
        let n = self.passes.len() as u64;
        if n == 0 {
            return Vec::new();
        }
        let slice = self.readback.slice(..n * 16);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        if gpu.wait_idle("reading timestamps").is_err() || !matches!(rx.recv(), Ok(Ok(()))) {
            return Vec::new();
        }
        let times = match slice.get_mapped_range() {
            Ok(data) => {
                let ticks: &[u64] = bytemuck::cast_slice(&data);
                self.passes
                    .iter()
                    .zip(ticks.chunks_exact(2))
                    .map(|((label, kind), t)| PassTime {
                        label: label.clone(),
                        kind: *kind,
                        ms: t[1].saturating_sub(t[0]) as f64 * self.period_ns / 1e6,
                    })
                    .collect()
            }
            Err(_) => Vec::new(),
        };
        self.readback.unmap();
        times
    }
}

/// Records one frame into a command encoder. Techniques open passes with
/// [`FrameEncoder::render_pass`] and [`FrameEncoder::compute_pass`]: bind group 0 is already set
/// in them, the render target is attached (loaded, never cleared), and each pass is timed.
pub struct FrameEncoder<'a> {
    /// Device and queue.
    pub gpu: &'a GpuContext,
    /// The target being drawn into.
    pub target: &'a RenderTarget,
    /// The scene's GPU resources (ground mesh, bind group 0).
    pub scene: &'a SceneGpu,
    encoder: wgpu::CommandEncoder,
    timer: Option<&'a mut PassTimer>,
    work: Option<&'a mut WorkCounter>,
    label_prefix: &'a str,
    counts: PassCounts,
}

impl<'a> FrameEncoder<'a> {
    /// Starts a frame. Passes are timed with `timer` and their work counted with `work` where
    /// given; labels are prefixed with `label_prefix` (e.g. `reference.`).
    pub fn new(
        gpu: &'a GpuContext,
        target: &'a RenderTarget,
        scene: &'a SceneGpu,
        mut timer: Option<&'a mut PassTimer>,
        mut work: Option<&'a mut WorkCounter>,
        label_prefix: &'a str,
    ) -> Self {
        if let Some(t) = timer.as_deref_mut() {
            t.passes.clear();
        }
        if let Some(w) = work.as_deref_mut() {
            w.begin_frame();
        }
        Self {
            gpu,
            target,
            scene,
            encoder: gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("frame"),
                }),
            timer,
            work,
            label_prefix,
            counts: PassCounts::default(),
        }
    }

    /// Sets the prefix for the labels of passes opened from now on.
    pub fn set_label_prefix(&mut self, prefix: &'a str) {
        self.label_prefix = prefix;
    }

    fn next_queries(&mut self, label: &str, kind: PassKind) -> Option<(&wgpu::QuerySet, u32)> {
        let full = format!("{}{}", self.label_prefix, label);
        let timer = self.timer.as_deref_mut()?;
        let index = timer.passes.len() as u32;
        if index >= MAX_TIMED_PASSES {
            return None;
        }
        timer.passes.push((full, kind));
        Some((&timer.queries, index * 2))
    }

    /// Opens a render pass on the target (colour and depth loaded), with bind group 0 set.
    pub fn render_pass(&mut self, label: &str) -> RenderPass<'_> {
        self.render_pass_with(label, None, false)
    }

    /// Opens a render pass that clears colour to `clear` and depth to far (the core's first
    /// pass of a frame).
    pub fn render_pass_with(
        &mut self,
        label: &str,
        clear: Option<wgpu::Color>,
        clear_depth: bool,
    ) -> RenderPass<'_> {
        let full = format!("{}{}", self.label_prefix, label);
        let target = self.target;
        let scene = self.scene;
        let timestamp_writes = self
            .next_queries(label, PassKind::Render)
            .map(|(q, i)| (q.clone(), i));
        let occlusion = self.work.as_deref().map(|w| w.occlusion_set().clone());
        let mut pass = self.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(&full),
            color_attachments: &[Some(target.color_attachment(clear))],
            depth_stencil_attachment: Some(target.depth_attachment(clear_depth)),
            timestamp_writes: timestamp_writes.as_ref().map(|(q, i)| {
                wgpu::RenderPassTimestampWrites {
                    query_set: q,
                    beginning_of_pass_write_index: Some(*i),
                    end_of_pass_write_index: Some(i + 1),
                }
            }),
            occlusion_query_set: occlusion.as_ref(),
            multiview_mask: None,
        });
        pass.set_bind_group(0, &scene.bind_group, &[]);
        let (work, queries) = start_counting(self.work.as_deref_mut(), full, PassKind::Render);
        RenderPass::new(pass, &mut self.counts, work, queries)
    }

    /// Opens a compute pass with bind group 0 set.
    pub fn compute_pass(&mut self, label: &str) -> ComputePass<'_> {
        let full = format!("{}{}", self.label_prefix, label);
        let scene = self.scene;
        let timestamp_writes = self
            .next_queries(label, PassKind::Compute)
            .map(|(q, i)| (q.clone(), i));
        let mut pass = self
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(&full),
                timestamp_writes: timestamp_writes.as_ref().map(|(q, i)| {
                    wgpu::ComputePassTimestampWrites {
                        query_set: q,
                        beginning_of_pass_write_index: Some(*i),
                        end_of_pass_write_index: Some(i + 1),
                    }
                }),
            });
        pass.set_bind_group(0, &scene.bind_group, &[]);
        let (work, queries) = start_counting(self.work.as_deref_mut(), full, PassKind::Compute);
        if let Some(q) = queries {
            q.begin_compute(&mut pass);
        }
        ComputePass::new(pass, &mut self.counts, work)
    }

    /// The raw command encoder, for copies and clears outside passes.
    pub fn command_encoder(&mut self) -> &mut wgpu::CommandEncoder {
        &mut self.encoder
    }

    /// Draws and dispatches recorded so far through this encoder's passes.
    pub fn counts(&self) -> PassCounts {
        self.counts
    }

    /// Resolves the timestamp and statistics queries and returns the finished command encoder.
    pub fn finish(mut self) -> wgpu::CommandEncoder {
        if let Some(work) = self.work.as_deref() {
            work.resolve(&mut self.encoder);
        }
        if let Some(timer) = self.timer.as_deref() {
            let n = timer.passes.len() as u32 * 2;
            if n > 0 {
                self.encoder
                    .resolve_query_set(&timer.queries, 0..n, &timer.resolve, 0);
                self.encoder.copy_buffer_to_buffer(
                    &timer.resolve,
                    0,
                    &timer.readback,
                    0,
                    u64::from(n) * 8,
                );
            }
        }
        self.encoder
    }
}

/// The counter and label a pass labelled `full` counts its segments with, and the query of its
/// first segment, to begin as the pass opens (`None` where nothing is counted, or the counter
/// is full).
fn start_counting(
    work: Option<&mut WorkCounter>,
    full: String,
    kind: PassKind,
) -> (Counting<'_>, Option<SegmentQueries>) {
    let Some(work) = work else {
        return (None, None);
    };
    match work.next(full.clone(), kind, None) {
        Some(query) => (Some((work, full)), Some(query)),
        None => (None, None),
    }
}
