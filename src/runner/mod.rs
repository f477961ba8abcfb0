//! Running techniques on a scene: one [`Harness`] per (scene, size, MSAA) holds the shared GPU
//! state; [`run`] measures one technique for W warm-up and N measured frames, timing every
//! stage on its own.
//!
//! Clocks, and which figure comes from which (see `shared/PLATFORM.md`):
//! - CPU stages (`wind_ms`, `update_ms`, `upload_ms`, `encode_ms`) are wall time on the CPU;
//! - `gpu_wall_ms` is wall time from `queue.submit` to the end of `poll(wait)`: the ground
//!   truth on software rasterisers, and an upper bound elsewhere;
//! - `gpu_ts_*_ms` come from timestamp queries around each pass, where the adapter has them;
//!   render and compute passes are kept apart because lavapipe's compute timestamps are wrong.

mod provenance;
mod record;
mod stats;

use std::time::Instant;

pub use crate::files::{write_atomic, write_csv};
pub use provenance::{Provenance, WGPU_VERSION, command_line};
pub use record::{FrameRecord, LevelRow, RunSummary};
pub use stats::Percentiles;

use crate::scene::SceneGpu;
use crate::target::Size;
use crate::technique::{
    FrameEncoder, GrassTechnique, InitContext, PassKind, PassTimer, TechniqueEntry,
};
use crate::wind::WindField;
use crate::{Error, FrameInputs, GpuContext, RenderTarget, Result, Scene};

/// Shared state for rendering one scene at one size: the scene's GPU resources, the target,
/// the wind (advanced frame by frame) and the pass timer.
pub struct Harness<'g> {
    /// Device and queue.
    pub gpu: &'g GpuContext,
    /// The scene.
    pub scene: Scene,
    /// Bind group 0, terrain, wind texture, background.
    pub scene_gpu: SceneGpu,
    /// Where frames are drawn.
    pub target: RenderTarget,
    /// Debug view passed to techniques (0 = none).
    pub debug_view: u32,
    /// Eye and unit view direction replacing the scene's camera path (the UI's free camera).
    pub camera_override: Option<(glam::Vec3, glam::Vec3)>,
    wind: Box<dyn WindField>,
    wind_frame: Option<u64>,
    timer: Option<PassTimer>,
}

/// What one frame produced.
pub struct FrameOutput {
    /// Timings and counts.
    pub record: FrameRecord,
    /// The image, when asked for.
    pub image: Option<image::RgbaImage>,
}

impl<'g> Harness<'g> {
    /// Sets up a scene for targets of `size`, with 4x MSAA when `msaa`.
    pub fn new(gpu: &'g GpuContext, scene: Scene, size: Size, msaa: bool) -> Result<Self> {
        let target = RenderTarget::new(gpu, size, msaa)?;
        let scene_gpu = SceneGpu::new(gpu, &scene, target.sample_count)?;
        let wind = scene.wind()?;
        Ok(Self {
            gpu,
            scene_gpu,
            target,
            wind,
            wind_frame: None,
            timer: PassTimer::new(gpu),
            scene,
            debug_view: 0,
            camera_override: None,
        })
    }

    /// Changes the target size (same sample count) and tells `technique`.
    pub fn resize(&mut self, technique: &mut dyn GrassTechnique, size: Size) -> Result<()> {
        if size != self.target.size {
            self.target = RenderTarget::new(self.gpu, size, self.target.sample_count > 1)?;
            technique.resize(self.gpu, size)?;
        }
        Ok(())
    }

    /// Replaces the scene's wind (validated) and restarts it from time 0.
    pub fn set_wind(&mut self, config: crate::wind::WindConfig) -> Result<()> {
        let wind = crate::wind::build(
            &config,
            self.scene.config.seed,
            &self.scene.terrain,
            self.scene.config.object.as_ref(),
        )?;
        self.scene.config.wind = config;
        self.wind = wind;
        self.wind_frame = None;
        Ok(())
    }

    /// The wind as it stands after the last frame.
    pub fn wind(&self) -> &dyn WindField {
        self.wind.as_ref()
    }

    /// What a technique is created with on this harness's scene and target.
    pub fn init_context(&self) -> InitContext<'_> {
        InitContext {
            gpu: self.gpu,
            scene: &self.scene,
            scene_gpu: &self.scene_gpu,
            size: self.target.size,
            sample_count: self.target.sample_count,
        }
    }

    /// Creates a technique: its defaults, overlaid with the scene file's `[techniques.<id>]`,
    /// overlaid with `overrides`; its GPU memory estimate is checked against the adapter first.
    pub fn create(
        &self,
        entry: &TechniqueEntry,
        overrides: &toml::Table,
    ) -> Result<Box<dyn GrassTechnique>> {
        let params = self.scene.technique_params(entry.info.id, overrides);
        let estimate = entry
            .estimate(&self.scene, &params)?
            .plus(self.target.estimate());
        crate::gpu::memory::check(self.gpu, entry.info.id, estimate)?;
        let during = format!("creating technique `{}`", entry.info.id);
        let ctx = self.init_context();
        self.gpu.scoped(&during, || entry.create(&ctx, &params))?
    }

    /// Advances the wind to `frame` (stateful fields are rebuilt and replayed when going back).
    fn advance_wind(&mut self, frame: u64) -> Result<()> {
        if self.wind.is_stateless() {
            self.wind_frame = Some(frame);
            return Ok(());
        }
        if self.wind_frame.is_some_and(|f| f > frame) {
            self.wind = self.scene.wind()?;
            self.wind_frame = None;
        }
        let start = self.wind_frame.map_or(0, |f| f + 1);
        for f in start..=frame {
            self.wind.advance(self.scene.time_of(f), self.scene.dt());
        }
        self.wind_frame = Some(frame);
        Ok(())
    }

    /// The camera of `frame` (the scene's path, or [`Self::camera_override`]).
    pub fn camera(&self, frame: u64) -> crate::camera::Camera {
        self.inputs(frame).camera
    }

    fn inputs(&self, frame: u64) -> FrameInputs<'_> {
        let mut camera = self.scene.camera_at(frame, self.target.size);
        if let Some((eye, forward)) = self.camera_override {
            camera.eye = eye;
            camera.forward = forward.normalize_or(camera.forward);
        }
        FrameInputs {
            frame,
            time: self.scene.time_of(frame),
            dt: self.scene.dt(),
            camera,
            scene: &self.scene,
            wind: self.wind.as_ref(),
            size: self.target.size,
            debug_view: self.debug_view,
        }
    }

    /// Runs `technique.update` for frames `from..to` without drawing them (techniques with GPU
    /// state also draw them), so a later frame sees the same history as in a full run.
    pub fn catch_up(
        &mut self,
        technique: &mut dyn GrassTechnique,
        from: u64,
        to: u64,
    ) -> Result<()> {
        for frame in from..to {
            if technique.info().gpu_state {
                self.frame(technique, frame, false)?;
            } else {
                self.advance_wind(frame)?;
                let inputs = self.inputs(frame);
                technique.update(&inputs)?;
            }
        }
        Ok(())
    }

    /// Uploads and records frame `frame` of `technique` without submitting it (for benchmarks
    /// of `prepare` + `encode`); `update` must have run for this frame.
    pub fn record(
        &mut self,
        technique: &mut dyn GrassTechnique,
        frame: u64,
    ) -> Result<wgpu::CommandBuffer> {
        self.advance_wind(frame)?;
        let gpu = self.gpu;
        let prefix = format!("{}.", technique.info().id);
        gpu.scoped("recording a frame", || -> Result<_> {
            let inputs = self.inputs(frame);
            self.scene_gpu.upload(&gpu.queue, &inputs);
            technique.prepare(gpu, &inputs)?;
            let mut enc = FrameEncoder::new(gpu, &self.target, &self.scene_gpu, None, &prefix);
            technique.encode(&mut enc);
            Ok(enc.finish().finish())
        })?
    }

    /// Runs only `technique.update` for `frame` (for benchmarks of the CPU stage).
    pub fn update_only(&mut self, technique: &mut dyn GrassTechnique, frame: u64) -> Result<()> {
        self.advance_wind(frame)?;
        let inputs = self.inputs(frame);
        technique.update(&inputs)
    }

    /// Renders one frame of `technique` and measures it; returns the image if `capture`.
    pub fn frame(
        &mut self,
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
        let t0 = Instant::now();
        self.advance_wind(frame)?;
        let time = self.scene.time_of(frame);
        self.scene_gpu.bake_wind(self.wind.as_ref(), time);
        let wind_ms = ms(t0);

        let gpu = self.gpu;
        let prefix = format!("{}.", info.id);
        let (update_ms, upload_ms, encode_ms, submit_at, readback, draw_calls) =
            gpu.scoped(&during, || -> Result<_> {
                let inputs = self.inputs(frame);
                let t = Instant::now();
                technique.update(&inputs)?;
                let update_ms = ms(t);

                let t = Instant::now();
                self.scene_gpu.upload(&gpu.queue, &inputs);
                technique.prepare(gpu, &inputs)?;
                let upload_ms = ms(t);

                let t = Instant::now();
                let mut enc = FrameEncoder::new(
                    gpu,
                    &self.target,
                    &self.scene_gpu,
                    self.timer.as_mut(),
                    "core.",
                );
                {
                    let mut pass =
                        enc.render_pass_with("background", Some(wgpu::Color::BLACK), true);
                    self.scene_gpu
                        .background
                        .draw(&mut pass, &self.scene_gpu.terrain);
                }
                enc.set_label_prefix(&prefix);
                let core_draws = enc.counts().draws;
                technique.encode(&mut enc);
                let draw_calls = enc.counts().draws - core_draws;
                let mut encoder = enc.finish();
                let readback = capture.then(|| self.target.encode_readback(gpu, &mut encoder));
                let command_buffer = encoder.finish();
                let encode_ms = ms(t);

                let submit_at = Instant::now();
                gpu.queue.submit([command_buffer]);
                Ok((
                    update_ms, upload_ms, encode_ms, submit_at, readback, draw_calls,
                ))
            })??;
        gpu.wait_idle(&during)?;
        let gpu_wall_ms = ms(submit_at);

        let passes = self.timer.as_mut().map(|t| t.read(gpu)).unwrap_or_default();
        // Sum of the timestamp times of the passes `f` selects; empty when none was timed.
        let sum = |f: &dyn Fn(&crate::technique::PassTime) -> bool| -> Option<f64> {
            let mut selected = passes.iter().filter(|p| f(p)).peekable();
            selected
                .peek()
                .is_some()
                .then(|| selected.map(|p| p.ms).sum())
        };
        let image = readback.map(|r| r.finish(gpu)).transpose()?;
        let stats = technique.stats();
        let record = FrameRecord {
            run_id: String::new(),
            technique: info.id.to_owned(),
            scene: self.scene.name().to_owned(),
            width: self.target.size.width,
            height: self.target.size.height,
            msaa: self.target.sample_count > 1,
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
            blades: stats.blades,
            triangles: stats.triangles,
            draw_calls,
            gpu_bytes: stats.gpu_bytes,
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
    for frame in 0..total {
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
    Ok(techniques
        .iter()
        .zip(frames.into_iter().zip(images))
        .zip(errors)
        .map(|((technique, (frames, images)), error)| match error {
            Some(e) => Err(e),
            None => Ok(RunResult {
                summary: RunSummary::from_frames(&frames, &technique.param_table()),
                frames,
                images,
            }),
        })
        .collect())
}

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}
