//! The work a pass did, measured by the GPU: pipeline-statistics queries (vertex shader,
//! clipper, fragment shader and compute invocations) around every pass the
//! [`super::FrameEncoder`] opens, for every technique alike. A technique cannot forget them
//! nor report them about itself: the pass wrappers begin the query when the pass opens and end
//! it when the pass is dropped.
//!
//! Within a pass, the counting follows the pipelines: whenever a pipeline of another
//! [`PipelineCost`] is set (its fragments of another [`crate::shaders::FragmentKind`]:
//! opaque, alpha-tested, blended; or its shaders, compute shaders too, fetching other numbers
//! of texels), the wrapper
//! ends the running query and begins the next, so each query — a *segment* — holds the work of
//! pipelines that cost alike, and the cost model can price fragments by kind and texture
//! fetches by invocation. (Past [`MAX_COUNTED_PASSES`] segments in a frame, the last segment
//! goes on counting whatever is drawn, under its own cost.)
//!
//! Each render segment also runs an occlusion query: the samples that passed the depth and
//! stencil tests and were not discarded ([`PassWork::samples_passed`]). Set against the
//! fragment invocations, it tells the fragments a pass kept from those it counted: lavapipe
//! counts every pixel of each 4x4 block a triangle touches, before its early depth test, so a
//! thin blade's counted fragments are mostly lanes it does not cover, and a hidden block's are
//! counted though they skip the shader (`results/cost_model/README.md`, *A counted fragment
//! need not be a shaded one* and *Fragments kept against fragments counted*).
//!
//! Beside the queries, each segment counts the instances its draws drew
//! ([`PassWork::instances`]): a direct draw's from its instance range as the pass wrapper
//! records it, an indirect draw's from its arguments, copied out at the end of the frame's
//! commands (the arguments' buffer needs `COPY_SRC`). A CPU rasteriser pays a cost per
//! instance that no counter sees (lavapipe: 110-124 ns, `results/cost_model/README.md`,
//! *Instances and interpolated inputs*).
//!
//! Where the adapter lacks `PIPELINE_STATISTICS_QUERY` (Metal, GL, some drivers) nothing is
//! recorded and the figures are `None`, never zeros.

use super::PassKind;
use crate::GpuContext;
use crate::shaders::PipelineCost;

/// What the statistics queries count, in the order their results are laid out (wgpu writes
/// one u64 per set flag, lowest bit first).
const TYPES: wgpu::PipelineStatisticsTypes =
    wgpu::PipelineStatisticsTypes::VERTEX_SHADER_INVOCATIONS
        .union(wgpu::PipelineStatisticsTypes::CLIPPER_INVOCATIONS)
        .union(wgpu::PipelineStatisticsTypes::CLIPPER_PRIMITIVES_OUT)
        .union(wgpu::PipelineStatisticsTypes::FRAGMENT_SHADER_INVOCATIONS)
        .union(wgpu::PipelineStatisticsTypes::COMPUTE_SHADER_INVOCATIONS);
/// Counters per query.
const COUNTERS: u64 = 5;
/// Most segments (passes, split where the fragment kind changes) a frame can count.
pub const MAX_COUNTED_PASSES: u32 = 512;

/// The primitives of a segment priced as a small pass's ([`crate::cost::Term::HeadPrimitive`]):
/// the largest pass the calibration's `primitives` workload draws (5 000 instances of 9
/// triangles, 8x). lavapipe prices a primitive less the more its pass draws (it rasterises a
/// large pass on its worker threads while the recording thread is still binning it, a small
/// one mostly after): on the Xeon 74-81 ns a primitive in passes of up to 360 000, 55-62 ns in
/// passes of 360 000 to 2.88 M (`results/cost_model/README.md`, *The reference's primitives*).
pub const PASS_HEAD_PRIMITIVES: u64 = 360_000;

/// Work counted by the GPU over one or more passes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct PassWork {
    /// Vertex shader invocations (the vertex cache may save some for indexed draws).
    pub vertex_invocations: u64,
    /// Primitives that reached the clipper (triangles assembled).
    pub clipper_invocations: u64,
    /// Primitives the clipper let through to rasterisation (on screen, not culled).
    pub clipper_primitives_out: u64,
    /// Fragment shader invocations (helper invocations of 2x2 quads included).
    pub fragment_invocations: u64,
    /// Compute shader invocations (workgroups dispatched x workgroup size).
    pub compute_invocations: u64,
    /// Samples that passed the depth and stencil tests and were not discarded (an occlusion
    /// query; one a pixel without MSAA). 0 for compute passes.
    pub samples_passed: u64,
    /// Instances drawn: the harness's count, not a GPU counter (statistics queries count
    /// none). A direct draw's instance range as recorded; an indirect draw's instance count
    /// as its arguments held at the end of the frame's commands, copied out beside the
    /// queries' results (`WorkCounter::resolve`). 0 for compute passes.
    pub instances: u64,
}

impl PassWork {
    /// Of this segment's rasterised primitives, those among its first
    /// [`PASS_HEAD_PRIMITIVES`]: the primitives priced as a small pass's. Only meaningful for
    /// one segment's work: summed work must sum its segments' heads.
    pub fn head_primitives(&self) -> u64 {
        self.clipper_primitives_out.min(PASS_HEAD_PRIMITIVES)
    }

    fn from_counters(c: &[u64], samples_passed: u64, instances: u64) -> Self {
        Self {
            vertex_invocations: c[0],
            clipper_invocations: c[1],
            clipper_primitives_out: c[2],
            fragment_invocations: c[3],
            compute_invocations: c[4],
            samples_passed,
            instances,
        }
    }
}

impl std::ops::Add for PassWork {
    type Output = Self;

    fn add(self, o: Self) -> Self {
        Self {
            vertex_invocations: self.vertex_invocations + o.vertex_invocations,
            clipper_invocations: self.clipper_invocations + o.clipper_invocations,
            clipper_primitives_out: self.clipper_primitives_out + o.clipper_primitives_out,
            fragment_invocations: self.fragment_invocations + o.fragment_invocations,
            compute_invocations: self.compute_invocations + o.compute_invocations,
            samples_passed: self.samples_passed + o.samples_passed,
            instances: self.instances + o.instances,
        }
    }
}

impl std::iter::Sum for PassWork {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::default(), |a, b| a + b)
    }
}

/// The work of one segment of a pass of the last frame (a whole pass, or the part of a
/// render pass drawn with pipelines of one [`PipelineCost`]).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PassWorkRecord {
    /// Pass label (prefixed, like [`super::PassTime::label`]).
    pub label: String,
    /// Render or compute.
    pub kind: PassKind,
    /// The cost of the pipelines drawn or dispatched in the segment (`None` for a pass that
    /// set no pipeline).
    pub pipeline: Option<PipelineCost>,
    /// What it did.
    pub work: PassWork,
}

/// Why an indirect draw's instances cannot be counted (`WorkCounter::add_indirect`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum UncountedIndirect {
    /// The arguments' buffer cannot be copied from.
    #[error(
        "an indirect draw's arguments are in a buffer without `COPY_SRC` usage, so the harness \
         cannot read its instance count: create the buffer with `wgpu::BufferUsages::COPY_SRC`"
    )]
    NotCopyable,
    /// The frame drew more indirect draws than the counter has room for.
    #[error(
        "a frame drew more than {MAX_COUNTED_INDIRECT_DRAWS} indirect draws, the most whose \
         instances the harness counts: raise `MAX_COUNTED_INDIRECT_DRAWS`"
    )]
    TooMany,
}

/// A statistics query set, an occlusion query set and the buffers to read them back, reused
/// frame after frame.
pub struct WorkCounter {
    queries: wgpu::QuerySet,
    occlusion: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    passes: Vec<Segment>,
    /// Occlusion queries begun this frame (one for each render segment, numbered apart from
    /// the statistics queries, so every query resolved was written).
    occlusions: u32,
    /// The frame's indirect draws whose instance counts are copied out, in order: the
    /// buffer, the offset of the instance count's word in it, the segment drawn in.
    indirect: Vec<IndirectDraw>,
    /// Why an indirect draw of this frame could not be counted, if one could not.
    uncounted: Option<UncountedIndirect>,
}

/// An indirect draw whose instance count is read back with the frame's queries.
struct IndirectDraw {
    buffer: wgpu::Buffer,
    /// Offset of the arguments' instance count (the second word of both layouts,
    /// `DrawIndirectArgs` and `DrawIndexedIndirectArgs`).
    offset: u64,
    /// Index of the segment it was drawn in.
    segment: usize,
}

/// A segment of the frame: what its queries count and how to read them back.
struct Segment {
    /// Pass label (prefixed).
    label: String,
    kind: PassKind,
    /// The cost of its pipelines (`None` until its first pipeline is set).
    pipeline: Option<PipelineCost>,
    /// Its occlusion query's index (render segments only).
    occlusion: Option<u32>,
    /// Instances of its direct draws.
    instances: u64,
}

/// The queries of one segment: its statistics query (set, index) and, in a render pass, the
/// index of its occlusion query in [`WorkCounter::occlusion_set`]. A render segment's two
/// queries begin and end together ([`SegmentQueries::begin_render`], [`end_render`]).
pub(crate) struct SegmentQueries {
    statistics: (wgpu::QuerySet, u32),
    occlusion: Option<u32>,
}

impl SegmentQueries {
    /// Begins the segment's queries on a render pass whose descriptor names the counter's
    /// occlusion query set ([`WorkCounter::occlusion_set`]).
    pub(crate) fn begin_render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let (queries, index) = &self.statistics;
        pass.begin_pipeline_statistics_query(queries, *index);
        if let Some(occlusion) = self.occlusion {
            pass.begin_occlusion_query(occlusion);
        }
    }

    /// Begins the segment's statistics query on a compute pass.
    pub(crate) fn begin_compute(&self, pass: &mut wgpu::ComputePass<'_>) {
        let (queries, index) = &self.statistics;
        pass.begin_pipeline_statistics_query(queries, *index);
    }
}

/// Ends the queries a render segment began ([`SegmentQueries::begin_render`]; every render
/// segment has an occlusion query, [`WorkCounter::next`]).
pub(crate) fn end_render(pass: &mut wgpu::RenderPass<'_>) {
    pass.end_pipeline_statistics_query();
    pass.end_occlusion_query();
}

/// Bytes of the statistics results in the resolve and read-back buffers; the occlusion
/// results follow (a multiple of 256, as `resolve_query_set` requires of an offset).
const STATISTICS_BYTES: u64 = MAX_COUNTED_PASSES as u64 * COUNTERS * 8;
const _: () = assert!(STATISTICS_BYTES.is_multiple_of(wgpu::QUERY_RESOLVE_BUFFER_ALIGNMENT));
/// Bytes of the occlusion results, which follow the statistics results.
const OCCLUSION_BYTES: u64 = MAX_COUNTED_PASSES as u64 * 8;
/// Most indirect draws a frame can count the instances of: their instance counts, one
/// 32-bit word each, follow the occlusion results in the read-back buffer.
pub const MAX_COUNTED_INDIRECT_DRAWS: u32 = 256;
/// Size of a draw's instance count in its indirect arguments (a `u32`).
const INSTANCE_COUNT_BYTES: u64 = 4;

impl WorkCounter {
    /// A counter, or `None` when the device has no pipeline-statistics queries.
    pub fn new(gpu: &GpuContext) -> Option<Self> {
        if !gpu.has_pipeline_statistics() {
            return None;
        }
        let size = STATISTICS_BYTES + OCCLUSION_BYTES;
        Some(Self {
            queries: gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass work"),
                ty: wgpu::QueryType::PipelineStatistics(TYPES),
                count: MAX_COUNTED_PASSES,
            }),
            occlusion: gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass work occlusion"),
                ty: wgpu::QueryType::Occlusion,
                count: MAX_COUNTED_PASSES,
            }),
            resolve: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("pass work resolve"),
                size,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            readback: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("pass work readback"),
                size: size + u64::from(MAX_COUNTED_INDIRECT_DRAWS) * INSTANCE_COUNT_BYTES,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            }),
            passes: Vec::new(),
            occlusions: 0,
            indirect: Vec::new(),
            uncounted: None,
        })
    }

    /// The occlusion query set, for a render pass's descriptor.
    pub(crate) fn occlusion_set(&self) -> &wgpu::QuerySet {
        &self.occlusion
    }

    /// Forgets the passes of the last frame (their queries are reused).
    pub(crate) fn begin_frame(&mut self) {
        self.passes.clear();
        self.occlusions = 0;
        self.indirect.clear();
        self.uncounted = None;
    }

    /// The queries of the next segment (`None` once [`MAX_COUNTED_PASSES`] are taken): a
    /// render segment's occlusion query too, which the caller begins and ends with the
    /// statistics query (every query resolved must have been written).
    pub(crate) fn next(
        &mut self,
        label: String,
        kind: PassKind,
        pipeline: Option<PipelineCost>,
    ) -> Option<SegmentQueries> {
        let index = self.passes.len() as u32;
        if index >= MAX_COUNTED_PASSES {
            return None;
        }
        let occlusion = (kind == PassKind::Render).then(|| {
            self.occlusions += 1;
            self.occlusions - 1
        });
        self.passes.push(Segment {
            label,
            kind,
            pipeline,
            occlusion,
            instances: 0,
        });
        Some(SegmentQueries {
            statistics: (self.queries.clone(), index),
            occlusion,
        })
    }

    /// Whether another segment can be counted this frame.
    pub(super) fn has_room(&self) -> bool {
        (self.passes.len() as u32) < MAX_COUNTED_PASSES
    }

    /// The pipeline cost of the segment being counted (`None` before its first pipeline).
    pub(super) fn current_pipeline(&self) -> Option<PipelineCost> {
        self.passes.last().and_then(|s| s.pipeline)
    }

    /// Gives the segment being counted its pipeline cost (its first pipeline's).
    pub(super) fn set_current_pipeline(&mut self, cost: PipelineCost) {
        if let Some(s) = self.passes.last_mut() {
            s.pipeline = Some(cost);
        }
    }

    /// Counts `instances` drawn directly in the segment being counted.
    pub(crate) fn add_instances(&mut self, instances: u64) {
        if let Some(s) = self.passes.last_mut() {
            s.instances += instances;
        }
    }

    /// Counts the instances of an indirect draw in the segment being counted: the instance
    /// count of the arguments at `offset` in `buffer` is copied out when the frame's queries
    /// are resolved. Where it cannot be (the buffer lacks `COPY_SRC`, or the frame drew more
    /// than [`MAX_COUNTED_INDIRECT_DRAWS`] indirectly), the frame's work is not read: the
    /// reason is kept for [`WorkCounter::read`].
    pub(crate) fn add_indirect(&mut self, buffer: &wgpu::Buffer, offset: u64) {
        let why = if !buffer.usage().contains(wgpu::BufferUsages::COPY_SRC) {
            Some(UncountedIndirect::NotCopyable)
        } else if self.indirect.len() >= MAX_COUNTED_INDIRECT_DRAWS as usize {
            Some(UncountedIndirect::TooMany)
        } else {
            None
        };
        match (why, self.passes.len().checked_sub(1)) {
            (Some(why), _) => {
                self.uncounted.get_or_insert(why);
            }
            (None, Some(segment)) => self.indirect.push(IndirectDraw {
                buffer: buffer.clone(),
                offset: offset + INSTANCE_COUNT_BYTES,
                segment,
            }),
            (None, None) => {}
        }
    }

    /// Resolves the frame's queries into the read-back buffer (at the end of its encoding),
    /// and copies its indirect draws' instance counts beside them.
    pub(crate) fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        for (k, d) in self.indirect.iter().enumerate() {
            encoder.copy_buffer_to_buffer(
                &d.buffer,
                d.offset,
                &self.readback,
                STATISTICS_BYTES + OCCLUSION_BYTES + k as u64 * INSTANCE_COUNT_BYTES,
                INSTANCE_COUNT_BYTES,
            );
        }
        let n = self.passes.len() as u32;
        if n > 0 {
            encoder.resolve_query_set(&self.queries, 0..n, &self.resolve, 0);
            encoder.copy_buffer_to_buffer(
                &self.resolve,
                0,
                &self.readback,
                0,
                u64::from(n) * COUNTERS * 8,
            );
        }
        let m = self.occlusions;
        if m > 0 {
            encoder.resolve_query_set(&self.occlusion, 0..m, &self.resolve, STATISTICS_BYTES);
            encoder.copy_buffer_to_buffer(
                &self.resolve,
                STATISTICS_BYTES,
                &self.readback,
                STATISTICS_BYTES,
                u64::from(m) * 8,
            );
        }
    }

    /// Reads the last frame's work per pass. Call after the frame's submission completed;
    /// `Ok(None)` when the read-back failed, `Err` when an indirect draw's instances could not
    /// be counted (nothing is read: a frame's work is counted whole or not at all).
    pub fn read(
        &mut self,
        gpu: &GpuContext,
    ) -> Result<Option<Vec<PassWorkRecord>>, UncountedIndirect> {
        if let Some(why) = self.uncounted {
            return Err(why);
        }
        Ok(self.read_counted(gpu))
    }

    fn read_counted(&mut self, gpu: &GpuContext) -> Option<Vec<PassWorkRecord>> {
        let n = self.passes.len() as u64;
        if n == 0 {
            return Some(Vec::new());
        }
        let slice = self.readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        if gpu.wait_idle("reading pass statistics").is_err() || !matches!(rx.recv(), Ok(Ok(()))) {
            return None;
        }
        let records = slice.get_mapped_range().ok().map(|data| {
            let (queries, indirect) = data.split_at((STATISTICS_BYTES + OCCLUSION_BYTES) as usize);
            let all: &[u64] = bytemuck::cast_slice(queries);
            let (counters, passed) = all.split_at((STATISTICS_BYTES / 8) as usize);
            let counts: &[u32] = bytemuck::cast_slice(indirect);
            self.passes
                .iter()
                .enumerate()
                .zip(counters.chunks_exact(COUNTERS as usize))
                .map(|((i, s), c)| {
                    let indirect: u64 = self
                        .indirect
                        .iter()
                        .zip(counts)
                        .filter(|(d, _)| d.segment == i)
                        .map(|(_, &n)| u64::from(n))
                        .sum();
                    PassWorkRecord {
                        label: s.label.clone(),
                        kind: s.kind,
                        pipeline: s.pipeline,
                        work: PassWork::from_counters(
                            c,
                            s.occlusion
                                .and_then(|i| passed.get(i as usize).copied())
                                .unwrap_or(0),
                            s.instances + indirect,
                        ),
                    }
                })
                .collect()
        });
        self.readback.unmap();
        records
    }
}
