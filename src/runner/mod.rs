//! Running techniques on a scene: a [`World`] holds what every picture of a scene shares (the
//! scene, its GPU resources, the wind advanced and baked once per frame), a [`View`] what each
//! picture has of its own (target, pass timer, debug view, camera override), and
//! [`World::frame`] renders one frame of a technique into a view: the one code path of every
//! caller. A [`Harness`] is a world with one view, for the command line, the benches and the
//! tests; the UI holds one world and a view per pane. [`run`] measures one technique for W
//! warm-up and N measured frames, timing every stage on its own.
//!
//! Clocks, and which figure comes from which (see `shared/PLATFORM.md`):
//! - CPU stages (`wind_ms`, `update_ms`, `upload_ms`, `encode_ms`) are wall time on the CPU;
//! - `gpu_wall_ms` is wall time from `queue.submit` to the end of `poll(wait)`: the ground
//!   truth on software rasterisers, and an upper bound elsewhere;
//! - `gpu_ts_*_ms` come from timestamp queries around each pass, where the adapter has them;
//!   render and compute passes are kept apart because lavapipe's compute timestamps are wrong.

pub mod allocator;
pub mod bootstrap;
mod harness;
mod host;
mod provenance;
mod record;
mod stats;
mod view;
mod world;

use std::time::Instant;

pub use crate::files::{write_atomic, write_csv};
pub use harness::Harness;
pub use host::{HostLoad, HostSample};
pub use provenance::{Provenance, WGPU_VERSION, command_line, record_build_revision};
pub use record::{FrameRecord, LevelRow, RunSummary};
pub use stats::Percentiles;
pub use view::View;
pub use world::World;

use crate::technique::{
    FrameEncoder, GrassTechnique, InitContext, PassKind, PassWork, TechniqueEntry,
};
use crate::{Error, FrameInputs, Result};

/// What one frame produced.
pub struct FrameOutput {
    /// Timings and counts.
    pub record: FrameRecord,
    /// The image, when asked for.
    pub image: Option<image::RgbaImage>,
}

/// Rendering a world's frames into views: creating techniques for a view, catching them up,
/// and the frame itself, the one code path every caller renders through.
impl<'g> World<'g> {
    /// What a technique drawing into `view` is created with.
    pub fn init_context<'a>(&'a self, view: &View) -> InitContext<'a> {
        InitContext {
            gpu: self.gpu,
            scene: &self.scene,
            scene_gpu: &self.scene_gpu,
            size: view.target.size,
            sample_count: view.target.sample_count,
        }
    }

    /// Creates a technique drawing into `view`: its defaults, overlaid with the scene file's
    /// `[techniques.<id>]`, overlaid with `overrides`. Before any GPU work, a technique that
    /// needs device limits the device lacks ([`crate::gpu::limits::check`]) or more memory than
    /// the adapter has ([`crate::gpu::memory::check`]) is refused with the numbers.
    pub fn create(
        &self,
        view: &View,
        entry: &TechniqueEntry,
        overrides: &toml::Table,
    ) -> Result<Box<dyn GrassTechnique>> {
        if view.target.sample_count != self.scene_gpu.sample_count {
            return Err(Error::param(
                "msaa",
                view.target.sample_count,
                format!("the world's {} samples", self.scene_gpu.sample_count),
            ));
        }
        let params = self.scene.technique_params(entry.info.id, overrides);
        let needs = entry.required_limits(&self.scene, &params)?;
        crate::gpu::limits::check(
            entry.info.id,
            &needs,
            &self.gpu.device.limits(),
            &self.gpu.adapter.limits(),
            &self.gpu.summary.name,
        )?;
        let estimate = entry
            .estimate(&self.scene, &params)?
            .plus(view.target.estimate());
        crate::gpu::memory::check(self.gpu, entry.info.id, estimate)?;
        let during = format!("creating technique `{}`", entry.info.id);
        let ctx = self.init_context(view);
        self.gpu.scoped(&during, || entry.create(&ctx, &params))?
    }

    /// The camera of `frame` in `view` (the scene's path, or [`View::camera_override`]).
    pub fn camera(&self, view: &View, frame: u64) -> crate::camera::Camera {
        self.inputs(view, frame).camera
    }

    fn inputs(&self, view: &View, frame: u64) -> FrameInputs<'_> {
        let mut camera = self.scene.camera_at(frame, view.target.size);
        if let Some((eye, forward)) = view.camera_override {
            camera.eye = eye;
            camera.forward = forward.normalize_or(camera.forward);
        }
        FrameInputs {
            frame,
            time: self.scene.time_of(frame),
            dt: self.scene.dt(),
            camera,
            scene: &self.scene,
            wind: self.wind(),
            size: view.target.size,
            debug_view: view.debug_view,
        }
    }

    /// Runs `technique.update` for frames `from..to` without drawing them (techniques with GPU
    /// state also draw them), so a later frame sees the same history as in a full run.
    pub fn catch_up(
        &mut self,
        view: &mut View,
        technique: &mut dyn GrassTechnique,
        from: u64,
        to: u64,
    ) -> Result<()> {
        for frame in from..to {
            if technique.info().gpu_state {
                self.frame(view, technique, frame, false)?;
            } else {
                self.advance_wind(frame)?;
                let inputs = self.inputs(view, frame);
                technique.update(&inputs)?;
            }
        }
        Ok(())
    }

    /// Uploads and records frame `frame` of `technique` without submitting it (for benchmarks
    /// of `prepare` + `encode`); `update` must have run for this frame.
    pub fn record(
        &mut self,
        view: &View,
        technique: &mut dyn GrassTechnique,
        frame: u64,
    ) -> Result<wgpu::CommandBuffer> {
        self.advance_wind(frame)?;
        let gpu = self.gpu;
        let prefix = format!("{}.", technique.info().id);
        gpu.scoped("recording a frame", || -> Result<_> {
            let inputs = self.inputs(view, frame);
            // Uploads what a measured frame uploads; the background itself is not recorded.
            let _ground = self.scene_gpu.upload(gpu, &inputs);
            technique.prepare(gpu, &inputs)?;
            let mut enc =
                FrameEncoder::new(gpu, &view.target, &self.scene_gpu, None, None, &prefix);
            technique.encode(&mut enc);
            Ok(enc.finish().finish())
        })?
    }

    /// Runs only `technique.update` for `frame` (for benchmarks of the CPU stage).
    pub fn update_only(
        &mut self,
        view: &View,
        technique: &mut dyn GrassTechnique,
        frame: u64,
    ) -> Result<()> {
        self.advance_wind(frame)?;
        let inputs = self.inputs(view, frame);
        technique.update(&inputs)
    }

    /// Renders one frame of `technique` into `view` and measures it; returns the image if
    /// `capture`. The wind stage ([`World::prepare_wind`]) runs once per frame whatever the
    /// number of views; the scene's per-frame uniforms (camera, size, lights) are uploaded
    /// before each view's submit.
    pub fn frame(
        &mut self,
        view: &mut View,
        technique: &mut dyn GrassTechnique,
        frame: u64,
        capture: bool,
    ) -> Result<FrameOutput> {
        let info = technique.info();
        let during = format!(
            "frame {frame} of `{}` on scene `{}`",
            info.id,
            self.scene.name()
        );
        let wind_ms = self.prepare_wind(frame)?;
        let time = self.scene.time_of(frame);

        let gpu = self.gpu;
        let prefix = format!("{}.", info.id);
        let (
            (update_ms, upload_ms, encode_ms),
            submit_at,
            readback,
            (core_draws, draw_calls),
            upload_bytes,
        ) = gpu.scoped(&during, || -> Result<_> {
            let inputs = self.inputs(view, frame);
            let t = Instant::now();
            technique.update(&inputs)?;
            let update_ms = ms(t);

            let t = Instant::now();
            gpu.take_uploaded_bytes();
            let ground = self.scene_gpu.upload(gpu, &inputs);
            technique.prepare(gpu, &inputs)?;
            let upload_ms = ms(t);
            let upload_bytes = gpu.take_uploaded_bytes();

            let t = Instant::now();
            let mut enc = FrameEncoder::new(
                gpu,
                &view.target,
                &self.scene_gpu,
                view.timer.as_mut(),
                view.work.as_mut(),
                "core.",
            );
            {
                let mut pass = enc.render_pass_with("background", Some(wgpu::Color::BLACK), true);
                self.scene_gpu.draw_background(&mut pass, &ground);
            }
            enc.set_label_prefix(&prefix);
            let core_draws = enc.counts().draws;
            technique.encode(&mut enc);
            let draw_calls = enc.counts().draws - core_draws;
            let mut encoder = enc.finish();
            let readback = capture.then(|| view.target.encode_readback(gpu, &mut encoder));
            let command_buffer = encoder.finish();
            let encode_ms = ms(t);

            let submit_at = Instant::now();
            gpu.queue.submit([command_buffer]);
            Ok((
                (update_ms, upload_ms, encode_ms),
                submit_at,
                readback,
                (core_draws, draw_calls),
                upload_bytes,
            ))
        })??;
        gpu.wait_idle(&during)?;
        let gpu_wall_ms = ms(submit_at);

        let passes = view.timer.as_mut().map(|t| t.read(gpu)).unwrap_or_default();
        // Sum of the timestamp times of the passes `f` selects; empty when none was timed.
        let sum = |f: &dyn Fn(&crate::technique::PassTime) -> bool| -> Option<f64> {
            let mut selected = passes.iter().filter(|p| f(p)).peekable();
            selected
                .peek()
                .is_some()
                .then(|| selected.map(|p| p.ms).sum())
        };
        // GPU-counted work, the technique's passes apart from the core's background.
        let work = match view.work.as_mut() {
            Some(counter) => counter.read(gpu).map_err(|e| Error::Technique {
                technique: info.id.to_owned(),
                message: format!("{during}: {e}"),
            })?,
            None => None,
        };
        let work_of = |core: bool| -> Option<PassWork> {
            work.as_ref().map(|w| {
                w.iter()
                    .filter(|p| p.label.starts_with("core.") == core)
                    .map(|p| p.work)
                    .sum()
            })
        };
        let (grass, background) = (work_of(false), work_of(true));
        // The technique's fragment invocations of one kind (its segments of that kind).
        let fragments_of = |kind: crate::shaders::FragmentKind| -> Option<u64> {
            work.as_ref().map(|w| {
                w.iter()
                    .filter(|p| {
                        !p.label.starts_with("core.")
                            && p.pipeline.map(|c| c.fragments) == Some(kind)
                    })
                    .map(|p| p.work.fragment_invocations)
                    .sum()
            })
        };
        // Costly operations (texture fetches, transcendentals) of the technique's (or the
        // core's) segments: invocations times what one invocation of the segment's pipeline
        // does.
        let ops_of = |core: bool| -> Option<crate::shaders::PassOps> {
            work.as_ref().map(|w| {
                w.iter()
                    .filter(|p| p.label.starts_with("core.") == core)
                    .filter_map(|p| Some(p.pipeline?.ops(&p.work)))
                    .fold(Default::default(), |a, b| a + b)
            })
        };
        let (ops, background_ops) = (ops_of(false), ops_of(true));
        // Fragment input slots set up for the technique's (or the core's) primitives: each
        // segment's primitives times its fragment shader's slots.
        let inputs_of = |core: bool| -> Option<u64> {
            work.as_ref().map(|w| {
                w.iter()
                    .filter(|p| p.label.starts_with("core.") == core)
                    .filter_map(|p| Some(p.pipeline?.primitive_inputs(&p.work)))
                    .sum()
            })
        };
        // Of the primitives, the segments' heads, taken segment by segment.
        let heads_of = |core: bool| -> Option<u64> {
            work.as_ref().map(|w| {
                w.iter()
                    .filter(|p| p.label.starts_with("core.") == core)
                    .map(|p| p.work.head_primitives())
                    .sum()
            })
        };
        let (heads, background_heads) = (heads_of(false), heads_of(true));
        // Texture fetches are summed over the stages (the vertex stage's are priced again
        // apart).
        let (fetches, background_fetches) = (ops.map(|o| o.all()), background_ops.map(|o| o.all()));
        let pixels = f64::from(view.target.size.width * view.target.size.height);
        let image = readback.map(|r| r.finish(gpu)).transpose()?;
        let stats = technique.stats();
        let record = FrameRecord {
            run_id: String::new(),
            technique: info.id.to_owned(),
            scene: self.scene.name().to_owned(),
            width: view.target.size.width,
            height: view.target.size.height,
            msaa: view.target.sample_count > 1,
            frame,
            time_s: time,
            wind_ms,
            update_ms,
            upload_ms,
            encode_ms,
            gpu_wall_ms,
            gpu_ts_background_ms: sum(&|p| p.label.starts_with("core.")),
            gpu_ts_render_ms: sum(&|p| !p.label.starts_with("core.") && p.kind == PassKind::Render),
            gpu_ts_compute_ms: sum(&|p| p.kind == PassKind::Compute),
            blades_drawn: Some(stats.blades_drawn),
            blades_represented: Some(stats.blades_represented),
            triangles: stats.triangles,
            draw_calls,
            gpu_bytes: stats.gpu_bytes,
            vertex_invocations: grass.map(|w| w.vertex_invocations),
            clipper_invocations: grass.map(|w| w.clipper_invocations),
            clipper_primitives_out: grass.map(|w| w.clipper_primitives_out),
            fragment_invocations: grass.map(|w| w.fragment_invocations),
            fragments_opaque: fragments_of(crate::shaders::FragmentKind::Opaque),
            fragments_alpha_tested: fragments_of(crate::shaders::FragmentKind::AlphaTested),
            fragments_blended: fragments_of(crate::shaders::FragmentKind::Blended),
            fragments_passed: grass.map(|w| w.samples_passed),
            compute_invocations: grass.map(|w| w.compute_invocations),
            background_vertex_invocations: background.map(|w| w.vertex_invocations),
            background_primitives: background.map(|w| w.clipper_primitives_out),
            background_fragment_invocations: background.map(|w| w.fragment_invocations),
            background_draw_calls: Some(core_draws),
            instances: grass.map(|w| w.instances),
            background_instances: background.map(|w| w.instances),
            primitive_inputs: inputs_of(false),
            background_primitive_inputs: inputs_of(true),
            head_primitives: heads,
            background_head_primitives: background_heads,
            texture_loads: fetches.map(|f| f.loads),
            float_texture_loads: fetches.map(|f| f.float_loads),
            vertex_texture_loads: ops.map(|o| o.vertex.loads),
            vertex_float_texture_loads: ops.map(|o| o.vertex.float_loads),
            texture_samples: fetches.map(|f| f.samples),
            float_texture_samples: fetches.map(|f| f.float_samples),
            texture_mip_blends: fetches.map(|f| f.mip_blends),
            texture_explicit_levels: fetches.map(|f| f.explicit_levels),
            background_texture_loads: background_fetches.map(|f| f.loads),
            background_float_texture_loads: background_fetches.map(|f| f.float_loads),
            background_vertex_texture_loads: background_ops.map(|o| o.vertex.loads),
            background_vertex_float_texture_loads: background_ops.map(|o| o.vertex.float_loads),
            background_texture_samples: background_fetches.map(|f| f.samples),
            background_float_texture_samples: background_fetches.map(|f| f.float_samples),
            background_texture_mip_blends: background_fetches.map(|f| f.mip_blends),
            background_texture_explicit_levels: background_fetches.map(|f| f.explicit_levels),
            vertex_transcendentals: ops.map(|f| f.vertex.transcendentals),
            fragment_transcendentals: ops.map(|f| f.fragment.transcendentals),
            compute_transcendentals: ops.map(|f| f.compute.transcendentals),
            background_vertex_transcendentals: background_ops.map(|f| f.vertex.transcendentals),
            background_fragment_transcendentals: background_ops.map(|f| f.fragment.transcendentals),
            vertex_arithmetic: ops.map(|f| f.vertex.arithmetic),
            fragment_arithmetic: ops.map(|f| f.fragment.arithmetic),
            compute_arithmetic: ops.map(|f| f.compute.arithmetic),
            background_vertex_arithmetic: background_ops.map(|f| f.vertex.arithmetic),
            background_fragment_arithmetic: background_ops.map(|f| f.fragment.arithmetic),
            compute_barriers: ops.map(|f| f.compute.barriers),
            compute_storage: ops.map(|f| f.compute.storage),
            vertex_storage: ops.map(|f| f.vertex.storage),
            compute_divisions: ops.map(|f| f.compute.divisions),
            upload_bytes: Some(upload_bytes),
            overdraw: grass.map(|w| w.fragment_invocations as f64 / pixels),
            grass_pixels: None,
            fragments_per_grass_pixel: None,
            counters: record::format_counters(&technique.counters()),
            levels: technique.levels(),
        };
        Ok(FrameOutput { record, image })
    }
}

/// How many frames to run and which to keep as images.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Frames run before measuring (first-frame shader compilation, caches).
    pub warmup: u64,
    /// Frames measured.
    pub frames: u64,
    /// Frame indices whose images to return.
    pub capture: Vec<u64>,
    /// Run id written into every record.
    pub run_id: String,
}

/// A measured run.
pub struct RunResult {
    /// One record per measured frame.
    pub frames: Vec<FrameRecord>,
    /// Medians and percentiles.
    pub summary: RunSummary,
    /// Captured images by frame index.
    pub images: Vec<(u64, image::RgbaImage)>,
}

/// Runs `technique` for `warmup + frames` frames from frame 0; `progress(done, total)` is
/// called after each frame.
pub fn run(
    harness: &mut Harness<'_>,
    technique: &mut dyn GrassTechnique,
    options: &RunOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<RunResult> {
    let mut results = run_interleaved(harness, &mut [technique], options, progress)?;
    results
        .pop()
        .unwrap_or_else(|| Err(Error::param("techniques", 0, "one technique")))
}

/// Runs several techniques on one harness with their frames interleaved: frame 0 of each in
/// turn, then frame 1 of each, and so on, so that every technique is measured under the same
/// conditions at the same moments. A ratio between two techniques then no longer depends on
/// how the machine's speed drifts between one technique's frames and the next one's (a shared
/// or throttling host). Each technique sees exactly the frame sequence of [`run`], so its
/// images are the same. Returns one result per technique, in order; a technique that fails is
/// dropped from the rotation and its error returned in its slot, the others go on.
/// `progress(done, total)` counts frames of all techniques.
pub fn run_interleaved(
    harness: &mut Harness<'_>,
    techniques: &mut [&mut dyn GrassTechnique],
    options: &RunOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Vec<Result<RunResult>>> {
    if options.frames == 0 {
        return Err(Error::param("frames", 0, "at least 1 measured frame"));
    }
    let total = options.warmup + options.frames;
    let n = techniques.len();
    let mut frames: Vec<Vec<FrameRecord>> = (0..n)
        .map(|_| Vec::with_capacity(options.frames as usize))
        .collect();
    let mut images: Vec<Vec<(u64, image::RgbaImage)>> = (0..n).map(|_| Vec::new()).collect();
    let mut errors: Vec<Option<Error>> = (0..n).map(|_| None).collect();
    let mut done = 0;
    let mut host_start = None;
    for frame in 0..total {
        if frame == options.warmup {
            host_start = HostSample::now();
        }
        for (k, technique) in techniques.iter_mut().enumerate() {
            if errors[k].is_some() {
                continue;
            }
            match harness.frame(&mut **technique, frame, options.capture.contains(&frame)) {
                Ok(mut out) => {
                    if frame >= options.warmup {
                        out.record.run_id.clone_from(&options.run_id);
                        frames[k].push(out.record);
                    }
                    if let Some(image) = out.image {
                        images[k].push((frame, image));
                    }
                }
                Err(e) => errors[k] = Some(e),
            }
            done += 1;
            progress(done, total * n as u64);
        }
    }
    let host = host_start
        .zip(HostSample::now())
        .and_then(|(a, b)| a.load_until(&b));
    Ok(techniques
        .iter()
        .zip(frames.into_iter().zip(images))
        .zip(errors)
        .map(|((technique, (frames, images)), error)| match error {
            Some(e) => Err(e),
            None => {
                let mut summary = RunSummary::from_frames(&frames, &technique.param_table());
                summary.host_other_cores = host.map(|h| h.other_cores);
                summary.host_steal = host.map(|h| h.steal);
                summary.host_own_kernel_cores = host.map(|h| h.own_kernel_cores);
                Ok(RunResult {
                    summary,
                    frames,
                    images,
                })
            }
        })
        .collect())
}

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}
