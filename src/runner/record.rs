//! Rows of `frames.csv` and `runs.csv`: flat structs (the csv crate cannot flatten), with
//! technique parameters recorded separately in long format.
//!
//! Both are read back by name (`report`, `merge`), including files written by older builds:
//! columns added since (`run_id`, `repetition`, `status`, `error`, `scene_variant`,
//! `counters`, the levels of detail, the comparisons with the reference) are optional there,
//! and a `runs.csv` row without `status` is a run that finished (older builds wrote no rows
//! for failed runs).

use super::Percentiles;
use crate::technique::LevelBlades;

/// One measured frame (a row of `frames.csv`).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FrameRecord {
    /// Run this frame belongs to (empty outside sweeps).
    #[serde(default)]
    pub run_id: String,
    /// Technique id.
    pub technique: String,
    /// Scene name.
    pub scene: String,
    /// Target width.
    pub width: u32,
    /// Target height.
    pub height: u32,
    /// 4x MSAA on.
    pub msaa: bool,
    /// Frame index.
    pub frame: u64,
    /// Scene time, s.
    pub time_s: f32,
    /// CPU: advancing and baking the wind (core work, the same for every technique; done once
    /// per frame by the world, and reported to every view drawing that frame), ms.
    pub wind_ms: f64,
    /// CPU: `update`, ms.
    pub update_ms: f64,
    /// CPU: core + technique uploads (`prepare`), ms.
    pub upload_ms: f64,
    /// CPU: recording commands (background + technique `encode`), ms.
    pub encode_ms: f64,
    /// Wall time from submit to the end of `poll(wait)`, ms (background included).
    pub gpu_wall_ms: f64,
    /// Timestamp-query time of the core's background pass, ms (empty without timestamps).
    pub gpu_ts_background_ms: Option<f64>,
    /// Timestamp-query time of the technique's render passes, ms.
    pub gpu_ts_render_ms: Option<f64>,
    /// Timestamp-query time of compute passes, ms (wrong on lavapipe: cross-check with wall).
    pub gpu_ts_compute_ms: Option<f64>,
    /// Blades drawn as geometry ([`TechniqueStats::blades_drawn`]); empty in files written
    /// before the count was split (their `blades` column mixed drawn and represented blades).
    ///
    /// [`TechniqueStats::blades_drawn`]: crate::TechniqueStats::blades_drawn
    #[serde(default)]
    pub blades_drawn: Option<u64>,
    /// Blades an impostor stands for, each once ([`TechniqueStats::blades_represented`]);
    /// empty in older files.
    ///
    /// [`TechniqueStats::blades_represented`]: crate::TechniqueStats::blades_represented
    #[serde(default)]
    pub blades_represented: Option<u64>,
    /// Triangles submitted.
    pub triangles: u64,
    /// Draw calls.
    pub draw_calls: u64,
    /// GPU memory held by the technique, bytes.
    pub gpu_bytes: u64,
    /// Vertex shader invocations of the technique's passes, counted by the GPU's
    /// pipeline-statistics queries ([`crate::technique::work`]); empty where the adapter has
    /// none (see `pipeline_statistics` in `meta.toml`) and in older files.
    #[serde(default)]
    pub vertex_invocations: Option<u64>,
    /// Primitives the technique's passes assembled (clipper invocations).
    #[serde(default)]
    pub clipper_invocations: Option<u64>,
    /// Primitives of the technique's passes that reached rasterisation (clipper output).
    #[serde(default)]
    pub clipper_primitives_out: Option<u64>,
    /// Fragment shader invocations of the technique's passes.
    #[serde(default)]
    pub fragment_invocations: Option<u64>,
    /// Of `fragment_invocations`, those of pipelines whose fragments are opaque
    /// ([`crate::shaders::FragmentKind`]: no discard, no blending).
    #[serde(default)]
    pub fragments_opaque: Option<u64>,
    /// Of `fragment_invocations`, those of alpha-tested pipelines (discard, alpha to coverage).
    #[serde(default)]
    pub fragments_alpha_tested: Option<u64>,
    /// Of `fragment_invocations`, those of blended pipelines.
    #[serde(default)]
    pub fragments_blended: Option<u64>,
    /// Samples of the technique's render passes that passed the depth and stencil tests and
    /// were not discarded (occlusion queries around the counted segments; one a pixel without
    /// MSAA). Against `fragment_invocations`: the fragments hidden, discarded or only counted
    /// (lavapipe counts whole 4x4 blocks, before its early depth test).
    #[serde(default)]
    pub fragments_passed: Option<u64>,
    /// Compute shader invocations of the technique's passes.
    #[serde(default)]
    pub compute_invocations: Option<u64>,
    /// Vertex shader invocations of the core's background pass (sky, ground, props, object).
    #[serde(default)]
    pub background_vertex_invocations: Option<u64>,
    /// Primitives of the core's background pass that reached rasterisation.
    #[serde(default)]
    pub background_primitives: Option<u64>,
    /// Fragment shader invocations of the core's background pass.
    #[serde(default)]
    pub background_fragment_invocations: Option<u64>,
    /// Draw calls of the core's background pass.
    #[serde(default)]
    pub background_draw_calls: Option<u64>,
    /// Instances the technique's draws drew: direct draws' instance ranges, indirect draws'
    /// instance counts read back from their arguments ([`crate::technique::work`]). Counted
    /// with the pipeline statistics: empty where the adapter has none and in older files.
    #[serde(default)]
    pub instances: Option<u64>,
    /// Instances the core's background pass drew.
    #[serde(default)]
    pub background_instances: Option<u64>,
    /// Fragment shader input slots set up for the technique's primitives that reached
    /// rasterisation: each counted segment's primitives times its fragment shader's slots
    /// ([`crate::shaders::PipelineCost::fragment_inputs`]).
    #[serde(default)]
    pub primitive_inputs: Option<u64>,
    /// The same for the core's background pass.
    #[serde(default)]
    pub background_primitive_inputs: Option<u64>,
    /// Of the technique's rasterised primitives, those among the first
    /// [`crate::technique::work::PASS_HEAD_PRIMITIVES`] of their counted segment, summed over
    /// its segments (the cost model prices them as a small pass's,
    /// [`crate::cost::Term::HeadPrimitive`]).
    #[serde(default)]
    pub head_primitives: Option<u64>,
    /// The same head primitives of the core's background pass.
    #[serde(default)]
    pub background_head_primitives: Option<u64>,
    /// Texels of normalised or integer formats the technique's shaders read with
    /// `textureLoad`: each counted segment's invocations times the loads of one invocation of
    /// its pipeline's entry points ([`crate::shaders::PipelineCost`], a static count).
    #[serde(default)]
    pub texture_loads: Option<u64>,
    /// Texels of floating-point formats (`R32Float`, `Rgba16Float`, ...:
    /// [`crate::shaders::ShaderOps::float_loads`]) the technique's shaders read with
    /// `textureLoad`, counted the same way.
    #[serde(default)]
    pub float_texture_loads: Option<u64>,
    /// Of `texture_loads`, those of the technique's vertex shaders.
    #[serde(default)]
    pub vertex_texture_loads: Option<u64>,
    /// Of `float_texture_loads`, those of the technique's vertex shaders.
    #[serde(default)]
    pub vertex_float_texture_loads: Option<u64>,
    /// Filtered texture samples (`textureSample*`) the technique's shaders took of textures
    /// of normalised or integer texels, counted the same way.
    #[serde(default)]
    pub texture_samples: Option<u64>,
    /// Filtered texture samples of textures of floating-point texels
    /// ([`crate::shaders::ShaderOps::float_samples`]), counted the same way.
    #[serde(default)]
    pub float_texture_samples: Option<u64>,
    /// Of both kinds of samples, those that may blend two mip levels
    /// ([`crate::shaders::ShaderOps::mip_blends`]), counted the same way.
    #[serde(default)]
    pub texture_mip_blends: Option<u64>,
    /// Of both kinds of samples, those at a level the shader gives each invocation
    /// ([`crate::shaders::ShaderOps::explicit_levels`]), counted the same way.
    #[serde(default)]
    pub texture_explicit_levels: Option<u64>,
    /// Texels of normalised or integer formats the core's background shaders read with
    /// `textureLoad`.
    #[serde(default)]
    pub background_texture_loads: Option<u64>,
    /// Texels of floating-point formats the core's background shaders read with
    /// `textureLoad` (the terrain's heights and density).
    #[serde(default)]
    pub background_float_texture_loads: Option<u64>,
    /// Of `background_texture_loads`, those of the core's background vertex shaders.
    #[serde(default)]
    pub background_vertex_texture_loads: Option<u64>,
    /// Of `background_float_texture_loads`, those of the core's background vertex shaders
    /// (the ground's heights).
    #[serde(default)]
    pub background_vertex_float_texture_loads: Option<u64>,
    /// Filtered texture samples the core's background shaders took.
    #[serde(default)]
    pub background_texture_samples: Option<u64>,
    /// Filtered samples of textures of floating-point texels the core's background shaders
    /// took.
    #[serde(default)]
    pub background_float_texture_samples: Option<u64>,
    /// Of the background's samples, those that may blend two mip levels.
    #[serde(default)]
    pub background_texture_mip_blends: Option<u64>,
    /// Of the background's samples, those at a level the shader gives each invocation.
    #[serde(default)]
    pub background_texture_explicit_levels: Option<u64>,
    /// Transcendental built-ins (`sin`, `cos`, `pow`, `exp`, ...) the technique's vertex
    /// shaders evaluated, counted the same way ([`crate::shaders::ShaderOps`]: a loop's body
    /// once).
    #[serde(default)]
    pub vertex_transcendentals: Option<u64>,
    /// Transcendental built-ins the technique's fragment shaders evaluated.
    #[serde(default)]
    pub fragment_transcendentals: Option<u64>,
    /// Transcendental built-ins the technique's compute shaders evaluated.
    #[serde(default)]
    pub compute_transcendentals: Option<u64>,
    /// Transcendental built-ins the core's background vertex shaders evaluated.
    #[serde(default)]
    pub background_vertex_transcendentals: Option<u64>,
    /// Transcendental built-ins the core's background fragment shaders evaluated.
    #[serde(default)]
    pub background_fragment_transcendentals: Option<u64>,
    /// Scalar arithmetic operations of the technique's vertex shaders, counted the same way
    /// ([`crate::shaders::ShaderOps::arithmetic`]: a loop's body once per trip where its
    /// pipeline fixes the trips, once where the data decide).
    #[serde(default)]
    pub vertex_arithmetic: Option<u64>,
    /// Scalar arithmetic operations of the technique's fragment shaders.
    #[serde(default)]
    pub fragment_arithmetic: Option<u64>,
    /// Scalar arithmetic operations of the technique's compute shaders.
    #[serde(default)]
    pub compute_arithmetic: Option<u64>,
    /// Scalar arithmetic operations of the core's background vertex shaders.
    #[serde(default)]
    pub background_vertex_arithmetic: Option<u64>,
    /// Scalar arithmetic operations of the core's background fragment shaders.
    #[serde(default)]
    pub background_fragment_arithmetic: Option<u64>,
    /// Workgroup barriers reached by the technique's compute shader invocations, one per
    /// invocation at each ([`crate::shaders::ShaderOps::barriers`]).
    #[serde(default)]
    pub compute_barriers: Option<u64>,
    /// 32-bit words the technique's compute shader invocations read from or wrote to storage
    /// buffers ([`crate::shaders::ShaderOps::storage`]).
    #[serde(default)]
    pub compute_storage: Option<u64>,
    /// 32-bit words the technique's vertex shader invocations read from storage buffers
    /// ([`crate::shaders::ShaderOps::storage`]; the core's background shaders read none).
    #[serde(default)]
    pub vertex_storage: Option<u64>,
    /// Integer divisions and remainders by divisors the pipeline does not fix, of the
    /// technique's compute shader invocations ([`crate::shaders::ShaderOps::divisions`]).
    #[serde(default)]
    pub compute_divisions: Option<u64>,
    /// Bytes the frame uploaded (the core's wind texture and frame globals, and the
    /// technique's `prepare`), counted by [`crate::GpuContext::write_buffer`] and
    /// [`crate::GpuContext::write_texture`].
    #[serde(default)]
    pub upload_bytes: Option<u64>,
    /// The technique's fragment invocations per target pixel: its overdraw.
    #[serde(default)]
    pub overdraw: Option<f64>,
    /// Pixels the technique's grass covers (differing from the grassless frame), for frames
    /// whose image was captured and compared with one (`run`); empty otherwise.
    #[serde(default)]
    pub grass_pixels: Option<u64>,
    /// The technique's fragment invocations per grass-covered pixel (where both are known).
    #[serde(default)]
    pub fragments_per_grass_pixel: Option<f64>,
    /// The technique's own counts ([`GrassTechnique::counters`]), `name=value;...`.
    ///
    /// [`GrassTechnique::counters`]: crate::GrassTechnique::counters
    #[serde(default)]
    pub counters: String,
    /// Blades per level of detail, in the technique's own levels (written to `levels.csv` in
    /// long format, not to `frames.csv`).
    #[serde(skip)]
    pub levels: Vec<LevelBlades>,
}

/// A row of `levels.csv`: blades one level of detail drew or stood for in one frame (long
/// format, since every technique names its own levels).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LevelRow {
    /// Run id.
    pub run_id: String,
    /// Technique id.
    pub technique: String,
    /// Frame number.
    pub frame: u64,
    /// The technique's name for the level.
    pub level: String,
    /// Blades.
    pub blades: u64,
}

impl FrameRecord {
    /// Records `grass_pixels` (from the frame's captured image) and the fragments per
    /// grass-covered pixel it gives with the measured fragment invocations.
    pub fn set_grass_pixels(&mut self, pixels: u64) {
        self.grass_pixels = Some(pixels);
        self.fragments_per_grass_pixel = self
            .fragment_invocations
            .filter(|_| pixels > 0)
            .map(|f| f as f64 / pixels as f64);
    }
}

impl LevelRow {
    /// The level rows of measured frames, in frame order.
    pub fn of(frames: &[FrameRecord]) -> Vec<Self> {
        frames
            .iter()
            .flat_map(|f| {
                f.levels.iter().map(|l| Self {
                    run_id: f.run_id.clone(),
                    technique: f.technique.clone(),
                    frame: f.frame,
                    level: l.level.to_owned(),
                    blades: l.blades,
                })
            })
            .collect()
    }
}

/// `name=value;...` of a technique's counters.
pub fn format_counters(counters: &[(&'static str, f64)]) -> String {
    counters
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect::<Vec<_>>()
        .join(";")
}

/// A run summarised (a row of `runs.csv`).
///
/// Every measured figure is an `Option`: a failed run (`status = failed`) has none, and its
/// cells are left empty, never 0, so no reader can average a failure in as a fast run.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RunSummary {
    /// Run id (`<configuration>-r<repetition>` in sweeps, empty otherwise).
    #[serde(default)]
    pub run_id: String,
    /// Repetition, from 0.
    #[serde(default)]
    pub repetition: u32,
    /// `ok`, or `failed` (then `error` says why and the figures are empty).
    #[serde(default = "status_ok")]
    pub status: String,
    /// Why the run failed.
    #[serde(default)]
    pub error: String,
    /// Scene overrides of this configuration (`key=value;...`).
    #[serde(default)]
    pub scene_variant: String,
    /// Technique id.
    pub technique: String,
    /// Scene name.
    pub scene: String,
    /// Target width.
    pub width: u32,
    /// Target height.
    pub height: u32,
    /// 4x MSAA on.
    pub msaa: bool,
    /// Measured frames.
    pub frames: usize,
    /// Median CPU update, ms.
    pub update_ms_median: Option<f64>,
    /// Median CPU upload, ms.
    pub upload_ms_median: Option<f64>,
    /// Median CPU encode, ms.
    pub encode_ms_median: Option<f64>,
    /// Median GPU wall time, ms.
    pub gpu_wall_ms_median: Option<f64>,
    /// 5th percentile GPU wall time, ms.
    pub gpu_wall_ms_p5: Option<f64>,
    /// 95th percentile GPU wall time, ms.
    pub gpu_wall_ms_p95: Option<f64>,
    /// Median timestamp time of the technique's render passes, ms.
    pub gpu_ts_render_ms_median: Option<f64>,
    /// Median timestamp time of compute passes, ms.
    pub gpu_ts_compute_ms_median: Option<f64>,
    /// Median timestamp time of the background, ms.
    pub gpu_ts_background_ms_median: Option<f64>,
    /// Median CPU + GPU wall time of a frame, ms.
    pub frame_ms_median: Option<f64>,
    /// 5th percentile frame time, ms.
    pub frame_ms_p5: Option<f64>,
    /// 95th percentile frame time, ms.
    pub frame_ms_p95: Option<f64>,
    /// Median blades drawn as geometry (empty in files written before the count was split).
    #[serde(default)]
    pub blades_drawn: Option<u64>,
    /// Median blades an impostor stands for, each once (empty in older files).
    #[serde(default)]
    pub blades_represented: Option<u64>,
    /// Median triangles.
    pub triangles: Option<u64>,
    /// Median draw calls.
    pub draw_calls: Option<u64>,
    /// Median instances the technique's draws drew (counted with the pipeline statistics;
    /// empty without them and in older files).
    #[serde(default)]
    pub instances: Option<u64>,
    /// Median fragment input slots set up for the technique's primitives.
    #[serde(default)]
    pub primitive_inputs: Option<u64>,
    /// Median of the technique's primitives among the first
    /// [`crate::technique::work::PASS_HEAD_PRIMITIVES`] of their segment.
    #[serde(default)]
    pub head_primitives: Option<u64>,
    /// Largest GPU memory held, bytes.
    pub gpu_bytes: Option<u64>,
    /// Median vertex shader invocations of the technique's passes (GPU-counted; empty without
    /// pipeline statistics).
    #[serde(default)]
    pub vertex_invocations: Option<u64>,
    /// Median primitives the technique's passes sent to rasterisation (clipper output).
    #[serde(default)]
    pub clipper_primitives_out: Option<u64>,
    /// Median fragment shader invocations of the technique's passes.
    #[serde(default)]
    pub fragment_invocations: Option<u64>,
    /// Median compute shader invocations of the technique's passes.
    #[serde(default)]
    pub compute_invocations: Option<u64>,
    /// Median opaque fragment invocations of the technique's passes.
    #[serde(default)]
    pub fragments_opaque: Option<u64>,
    /// Median alpha-tested fragment invocations of the technique's passes.
    #[serde(default)]
    pub fragments_alpha_tested: Option<u64>,
    /// Median blended fragment invocations of the technique's passes.
    #[serde(default)]
    pub fragments_blended: Option<u64>,
    /// Median samples of the technique's render passes that passed the depth and stencil
    /// tests and were not discarded (occlusion queries).
    #[serde(default)]
    pub fragments_passed: Option<u64>,
    /// Median bytes uploaded per frame (core and technique).
    #[serde(default)]
    pub upload_bytes: Option<u64>,
    /// Median fragment invocations of the core's background pass.
    #[serde(default)]
    pub background_fragment_invocations: Option<u64>,
    /// Median texels of normalised or integer formats read with `textureLoad` by the
    /// technique's shaders.
    #[serde(default)]
    pub texture_loads: Option<u64>,
    /// Median texels of floating-point formats read with `textureLoad` by the technique's
    /// shaders.
    #[serde(default)]
    pub float_texture_loads: Option<u64>,
    /// Median of `texture_loads`' vertex shaders' share.
    #[serde(default)]
    pub vertex_texture_loads: Option<u64>,
    /// Median of `float_texture_loads`' vertex shaders' share.
    #[serde(default)]
    pub vertex_float_texture_loads: Option<u64>,
    /// Median filtered texture samples of the technique's shaders (normalised or integer
    /// texels).
    #[serde(default)]
    pub texture_samples: Option<u64>,
    /// Median filtered samples of textures of floating-point texels of the technique's
    /// shaders.
    #[serde(default)]
    pub float_texture_samples: Option<u64>,
    /// Median of both kinds of samples that may blend two mip levels.
    #[serde(default)]
    pub texture_mip_blends: Option<u64>,
    /// Median of both kinds of samples at a level the shader gives each invocation.
    #[serde(default)]
    pub texture_explicit_levels: Option<u64>,
    /// Median transcendental built-ins evaluated by the technique's vertex shaders.
    #[serde(default)]
    pub vertex_transcendentals: Option<u64>,
    /// Median transcendental built-ins evaluated by the technique's fragment shaders.
    #[serde(default)]
    pub fragment_transcendentals: Option<u64>,
    /// Median transcendental built-ins evaluated by the technique's compute shaders.
    #[serde(default)]
    pub compute_transcendentals: Option<u64>,
    /// Median scalar arithmetic operations of the technique's vertex shaders.
    #[serde(default)]
    pub vertex_arithmetic: Option<u64>,
    /// Median scalar arithmetic operations of the technique's fragment shaders.
    #[serde(default)]
    pub fragment_arithmetic: Option<u64>,
    /// Median scalar arithmetic operations of the technique's compute shaders.
    #[serde(default)]
    pub compute_arithmetic: Option<u64>,
    /// Median workgroup barriers reached by the technique's compute shader invocations.
    #[serde(default)]
    pub compute_barriers: Option<u64>,
    /// Median 32-bit words the technique's compute shader invocations read from or wrote to
    /// storage buffers.
    #[serde(default)]
    pub compute_storage: Option<u64>,
    /// Median 32-bit words the technique's vertex shader invocations read from storage
    /// buffers.
    #[serde(default)]
    pub vertex_storage: Option<u64>,
    /// Median integer divisions and remainders by divisors the pipeline does not fix, of the
    /// technique's compute shader invocations.
    #[serde(default)]
    pub compute_divisions: Option<u64>,
    /// Median overdraw: the technique's fragment invocations per target pixel.
    #[serde(default)]
    pub overdraw: Option<f64>,
    /// Median fragments per grass-covered pixel, over the frames where coverage was measured.
    #[serde(default)]
    pub fragments_per_grass_pixel: Option<f64>,
    /// GPU time the cost model predicts from the run's measured work
    /// ([`crate::cost::apply_model`]: the adapter's unit costs times the mean frame's work),
    /// ms; empty without unit costs or counted work.
    #[serde(default)]
    pub model_ms: Option<f64>,
    /// Measured median GPU wall time over `model_ms`: 1 where the model explains the time.
    #[serde(default)]
    pub model_ratio: Option<f64>,
    /// The model's fixed per-frame cost, ms.
    #[serde(default)]
    pub model_fixed_ms: Option<f64>,
    /// The model's time for vertex invocations, ms.
    #[serde(default)]
    pub model_vertex_ms: Option<f64>,
    /// The model's time for primitives (triangle setup), ms.
    #[serde(default)]
    pub model_primitive_ms: Option<f64>,
    /// The model's time for opaque fragments, ms.
    #[serde(default)]
    pub model_fragment_opaque_ms: Option<f64>,
    /// The model's time for alpha-tested fragments, ms.
    #[serde(default)]
    pub model_fragment_alpha_tested_ms: Option<f64>,
    /// The model's time for blended fragments, ms.
    #[serde(default)]
    pub model_fragment_blended_ms: Option<f64>,
    /// The model's time for draw calls, ms.
    #[serde(default)]
    pub model_draw_ms: Option<f64>,
    /// The model's time for compute invocations, ms.
    #[serde(default)]
    pub model_compute_ms: Option<f64>,
    /// The model's time for uploads, ms.
    #[serde(default)]
    pub model_upload_ms: Option<f64>,
    /// The model's time for texels read with `textureLoad`, ms.
    #[serde(default)]
    pub model_texture_load_ms: Option<f64>,
    /// The model's time for floating-point texels read with `textureLoad`, ms.
    #[serde(default)]
    pub model_float_texture_load_ms: Option<f64>,
    /// What the model adds for texels read with `textureLoad` in vertex shaders, ms.
    #[serde(default)]
    pub model_vertex_texture_load_ms: Option<f64>,
    /// What the model adds for floating-point texels read with `textureLoad` in vertex
    /// shaders, ms.
    #[serde(default)]
    pub model_vertex_float_texture_load_ms: Option<f64>,
    /// The model's time for filtered texture samples, ms.
    #[serde(default)]
    pub model_texture_sample_ms: Option<f64>,
    /// The model's time for filtered samples of textures of floating-point texels, ms.
    #[serde(default)]
    pub model_float_texture_sample_ms: Option<f64>,
    /// Predicted ms of vertex shaders' transcendental built-ins.
    #[serde(default)]
    pub model_vertex_transcendental_ms: Option<f64>,
    /// Predicted ms of fragment shaders' transcendental built-ins.
    #[serde(default)]
    pub model_fragment_transcendental_ms: Option<f64>,
    /// Predicted ms of compute shaders' transcendental built-ins.
    #[serde(default)]
    pub model_compute_transcendental_ms: Option<f64>,
    /// Predicted ms of vertex shaders' scalar arithmetic.
    #[serde(default)]
    pub model_vertex_arithmetic_ms: Option<f64>,
    /// Predicted ms of fragment shaders' scalar arithmetic.
    #[serde(default)]
    pub model_fragment_arithmetic_ms: Option<f64>,
    /// Predicted ms of compute shaders' scalar arithmetic.
    #[serde(default)]
    pub model_compute_arithmetic_ms: Option<f64>,
    /// Predicted ms of compute shader invocations at workgroup barriers.
    #[serde(default)]
    pub model_compute_barrier_ms: Option<f64>,
    /// Predicted ms of compute shaders' storage-buffer words.
    #[serde(default)]
    pub model_compute_storage_ms: Option<f64>,
    /// Predicted ms of vertex shaders' storage-buffer words.
    #[serde(default)]
    pub model_vertex_storage_ms: Option<f64>,
    /// Predicted ms of compute shaders' integer divisions.
    #[serde(default)]
    pub model_compute_division_ms: Option<f64>,
    /// Predicted ms of filtered samples' second mip level.
    #[serde(default)]
    pub model_texture_mip_blend_ms: Option<f64>,
    /// Predicted ms of the draws' instances.
    #[serde(default)]
    pub model_instance_ms: Option<f64>,
    /// Predicted ms of the primitives' fragment input slots.
    #[serde(default)]
    pub model_primitive_input_ms: Option<f64>,
    /// Predicted ms of samples' levels picked lane by lane.
    #[serde(default)]
    pub model_texture_explicit_level_ms: Option<f64>,
    /// Predicted ms the segments' head primitives cost on top of the others' price.
    #[serde(default)]
    pub model_head_primitive_ms: Option<f64>,
    /// Technique parameters, `key=value;...` (also in long format in `params.csv`).
    pub params: String,
    /// Median GPU wall time over the reference's in the same configuration and repetition.
    pub gpu_wall_ratio_to_reference: Option<f64>,
    /// Speed-up over the reference in the same configuration and repetition: the reference's
    /// median GPU wall time over this run's (1 / `gpu_wall_ratio_to_reference`).
    #[serde(default)]
    pub speedup: Option<f64>,
    /// 2.5th percentile of the speed-up's bootstrap distribution over both runs' frames
    /// ([`super::bootstrap`]): with `speedup_ci_high`, a 95 % interval.
    #[serde(default)]
    pub speedup_ci_low: Option<f64>,
    /// 97.5th percentile of the speed-up's bootstrap distribution.
    #[serde(default)]
    pub speedup_ci_high: Option<f64>,
    /// Mean FLIP of the last frame against the reference's, full resolution.
    pub flip_vs_reference: Option<f64>,
    /// Mean FLIP against the reference after 4x downsampling (placement-insensitive).
    pub flip_vs_reference_quarter: Option<f64>,
    /// Median GPU wall time per blade shown (drawn or represented), ns.
    pub blade_cost_ns: Option<f64>,
    /// CPU cores other processes kept busy, on average, while the run's frames were measured
    /// ([`super::HostLoad`]; empty off Linux and in older files). On a software rasteriser
    /// every such core is taken from the GPU: a run beside a compile measures the compile too.
    #[serde(default)]
    pub host_other_cores: Option<f64>,
    /// Share of the CPUs' time the hypervisor gave to other machines meanwhile, 0..1.
    #[serde(default)]
    pub host_steal: Option<f64>,
    /// Cores this process spent in the kernel (system time), on average, meanwhile
    /// ([`super::HostLoad::own_kernel_cores`]; empty off Linux and in older files): time the
    /// frames paid the operating system rather than their work, the rasteriser threads'
    /// wake-ups on frames of a few milliseconds, fresh pages where the process returns memory
    /// and takes it again every frame.
    #[serde(default)]
    pub host_own_kernel_cores: Option<f64>,
}

/// The status of a finished run, and of a row written before runs had a status.
fn status_ok() -> String {
    "ok".to_owned()
}

impl RunSummary {
    /// Whether the run finished (its figures are measurements).
    pub fn is_ok(&self) -> bool {
        self.status == "ok"
    }

    /// Blades drawn and represented: every blade the run's median frame showed (empty when
    /// either count is missing).
    pub fn blades_shown(&self) -> Option<u64> {
        Some(self.blades_drawn? + self.blades_represented?)
    }

    /// Summarises measured frames; with none, every figure is empty.
    pub fn from_frames(frames: &[FrameRecord], params: &toml::Table) -> Self {
        let pct = |f: &dyn Fn(&FrameRecord) -> f64| Percentiles::of(frames.iter().map(f));
        let median = |f: &dyn Fn(&FrameRecord) -> Option<f64>| {
            Percentiles::of(frames.iter().filter_map(f)).map(|p| p.median)
        };
        let median_u64 = |f: &dyn Fn(&FrameRecord) -> Option<u64>| {
            median(&|r| f(r).map(|v| v as f64)).map(|m| m.round() as u64)
        };
        let wall = pct(&|r| r.gpu_wall_ms);
        let total = pct(&|r| r.wind_ms + r.update_ms + r.upload_ms + r.encode_ms + r.gpu_wall_ms);
        let first = frames.first();
        let shown = median_u64(&|r| Some(r.blades_drawn? + r.blades_represented?));
        Self {
            run_id: first.map(|r| r.run_id.clone()).unwrap_or_default(),
            repetition: 0,
            status: status_ok(),
            error: String::new(),
            scene_variant: String::new(),
            technique: first.map(|r| r.technique.clone()).unwrap_or_default(),
            scene: first.map(|r| r.scene.clone()).unwrap_or_default(),
            width: first.map_or(0, |r| r.width),
            height: first.map_or(0, |r| r.height),
            msaa: first.is_some_and(|r| r.msaa),
            frames: frames.len(),
            update_ms_median: median(&|r| Some(r.update_ms)),
            upload_ms_median: median(&|r| Some(r.upload_ms)),
            encode_ms_median: median(&|r| Some(r.encode_ms)),
            gpu_wall_ms_median: wall.map(|p| p.median),
            gpu_wall_ms_p5: wall.map(|p| p.p5),
            gpu_wall_ms_p95: wall.map(|p| p.p95),
            gpu_ts_render_ms_median: median(&|r| r.gpu_ts_render_ms),
            gpu_ts_compute_ms_median: median(&|r| r.gpu_ts_compute_ms),
            gpu_ts_background_ms_median: median(&|r| r.gpu_ts_background_ms),
            frame_ms_median: total.map(|p| p.median),
            frame_ms_p5: total.map(|p| p.p5),
            frame_ms_p95: total.map(|p| p.p95),
            blades_drawn: median_u64(&|r| r.blades_drawn),
            blades_represented: median_u64(&|r| r.blades_represented),
            triangles: median_u64(&|r| Some(r.triangles)),
            draw_calls: median_u64(&|r| Some(r.draw_calls)),
            instances: median_u64(&|r| r.instances),
            primitive_inputs: median_u64(&|r| r.primitive_inputs),
            head_primitives: median_u64(&|r| r.head_primitives),
            gpu_bytes: frames.iter().map(|r| r.gpu_bytes).max(),
            vertex_invocations: median_u64(&|r| r.vertex_invocations),
            clipper_primitives_out: median_u64(&|r| r.clipper_primitives_out),
            fragment_invocations: median_u64(&|r| r.fragment_invocations),
            fragments_opaque: median_u64(&|r| r.fragments_opaque),
            fragments_alpha_tested: median_u64(&|r| r.fragments_alpha_tested),
            fragments_blended: median_u64(&|r| r.fragments_blended),
            fragments_passed: median_u64(&|r| r.fragments_passed),
            upload_bytes: median_u64(&|r| r.upload_bytes),
            compute_invocations: median_u64(&|r| r.compute_invocations),
            background_fragment_invocations: median_u64(&|r| r.background_fragment_invocations),
            texture_loads: median_u64(&|r| r.texture_loads),
            float_texture_loads: median_u64(&|r| r.float_texture_loads),
            vertex_texture_loads: median_u64(&|r| r.vertex_texture_loads),
            vertex_float_texture_loads: median_u64(&|r| r.vertex_float_texture_loads),
            texture_samples: median_u64(&|r| r.texture_samples),
            float_texture_samples: median_u64(&|r| r.float_texture_samples),
            texture_mip_blends: median_u64(&|r| r.texture_mip_blends),
            texture_explicit_levels: median_u64(&|r| r.texture_explicit_levels),
            vertex_transcendentals: median_u64(&|r| r.vertex_transcendentals),
            fragment_transcendentals: median_u64(&|r| r.fragment_transcendentals),
            compute_transcendentals: median_u64(&|r| r.compute_transcendentals),
            vertex_arithmetic: median_u64(&|r| r.vertex_arithmetic),
            fragment_arithmetic: median_u64(&|r| r.fragment_arithmetic),
            compute_arithmetic: median_u64(&|r| r.compute_arithmetic),
            compute_barriers: median_u64(&|r| r.compute_barriers),
            compute_storage: median_u64(&|r| r.compute_storage),
            vertex_storage: median_u64(&|r| r.vertex_storage),
            compute_divisions: median_u64(&|r| r.compute_divisions),
            overdraw: median(&|r| r.overdraw),
            fragments_per_grass_pixel: median(&|r| r.fragments_per_grass_pixel),
            params: params
                .iter()
                .map(|(k, v)| format!("{k}={}", crate::params::format_value(v)))
                .collect::<Vec<_>>()
                .join(";"),
            gpu_wall_ratio_to_reference: None,
            model_ms: None,
            model_ratio: None,
            model_fixed_ms: None,
            model_vertex_ms: None,
            model_primitive_ms: None,
            model_fragment_opaque_ms: None,
            model_fragment_alpha_tested_ms: None,
            model_fragment_blended_ms: None,
            model_draw_ms: None,
            model_compute_ms: None,
            model_upload_ms: None,
            model_texture_load_ms: None,
            model_float_texture_load_ms: None,
            model_vertex_texture_load_ms: None,
            model_vertex_float_texture_load_ms: None,
            model_texture_sample_ms: None,
            model_float_texture_sample_ms: None,
            model_vertex_transcendental_ms: None,
            model_fragment_transcendental_ms: None,
            model_compute_transcendental_ms: None,
            model_vertex_arithmetic_ms: None,
            model_fragment_arithmetic_ms: None,
            model_compute_arithmetic_ms: None,
            model_compute_barrier_ms: None,
            model_compute_storage_ms: None,
            model_vertex_storage_ms: None,
            model_compute_division_ms: None,
            model_texture_mip_blend_ms: None,
            model_instance_ms: None,
            model_primitive_input_ms: None,
            model_head_primitive_ms: None,
            model_texture_explicit_level_ms: None,
            speedup: None,
            speedup_ci_low: None,
            speedup_ci_high: None,
            flip_vs_reference: None,
            flip_vs_reference_quarter: None,
            blade_cost_ns: wall
                .zip(shown.filter(|&n| n > 0))
                .map(|(w, n)| w.median * 1e6 / n as f64),
            host_other_cores: None,
            host_steal: None,
            host_own_kernel_cores: None,
        }
    }

    /// The row of a run that failed: no figure, only why.
    pub fn failed(run_id: &str, technique: &str, scene: &str, error: &str) -> Self {
        let mut row = Self::from_frames(&[], &toml::Table::new());
        row.run_id = run_id.to_owned();
        row.technique = technique.to_owned();
        row.scene = scene.to_owned();
        row.status = "failed".to_owned();
        row.error = error.to_owned();
        row
    }
}

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use super::*;

    /// Every file under `dir` whose name ends with `suffix`, sorted.
    fn files(dir: &Path, suffix: &str) -> Vec<PathBuf> {
        let mut found = Vec::new();
        let mut stack = vec![dir.to_owned()];
        while let Some(d) = stack.pop() {
            for entry in std::fs::read_dir(&d).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    stack.push(path);
                } else if path.to_string_lossy().ends_with(suffix) {
                    found.push(path);
                }
            }
        }
        found.sort();
        found
    }

    /// The committed result files named `*<suffix>`, and the test fixtures'.
    fn committed(suffix: &str) -> Vec<PathBuf> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut all = files(&root.join("results"), suffix);
        all.extend(files(&root.join("experiments/tests/fixtures"), suffix));
        all
    }

    /// Reads `path` into typed rows, checks none is lost, and, when the file has today's
    /// columns, that writing the rows again gives back the file byte for byte.
    fn read_back<T: serde::Serialize + serde::de::DeserializeOwned>(path: &Path) -> Vec<T> {
        let bytes = std::fs::read(path).unwrap();
        let rows: Vec<T> = csv::Reader::from_reader(bytes.as_slice())
            .deserialize()
            .collect::<Result<_, _>>()
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let records = csv::Reader::from_reader(bytes.as_slice()).records().count();
        assert_eq!(rows.len(), records, "{}", path.display());
        let mut w = csv::Writer::from_writer(Vec::new());
        for row in &rows {
            w.serialize(row).unwrap();
        }
        let again = w.into_inner().unwrap();
        let header = |b: &[u8]| b.split(|&c| c == b'\n').next().map(<[u8]>::to_vec);
        if !rows.is_empty() && header(&again) == header(&bytes) {
            assert!(
                again == bytes,
                "{} changes when read and written",
                path.display()
            );
        }
        rows
    }

    #[test]
    fn every_committed_runs_csv_reads_back_into_its_type() {
        let paths = committed("runs.csv");
        assert!(!paths.is_empty());
        for path in &paths {
            let rows: Vec<RunSummary> = read_back(path);
            assert!(!rows.is_empty(), "{}", path.display());
        }
        // Today's columns, from a sweep.
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("results");
        let rows: Vec<RunSummary> = read_back(&root.join("zhang_target/runs.csv"));
        let (reference, zhang) = (&rows[0], &rows[1]);
        assert_eq!(
            (reference.technique.as_str(), reference.gpu_wall_ms_median),
            ("reference", Some(259.068133))
        );
        // The newest columns: instances drawn (the reference's, one a blade) and the input slots
        // its primitives set up (its fragment shader reads 3).
        assert_eq!(reference.instances, Some(433_720));
        assert_eq!(
            reference.primitive_inputs,
            reference.clipper_primitives_out.map(|p| 3 * p)
        );
        assert!(reference.model_instance_ms.is_some_and(|ms| ms > 0.0));
        // Its one pass draws more primitives than a pass's head: the head is the whole head,
        // and the model prices it.
        assert!(reference.clipper_primitives_out > Some(360_000));
        assert_eq!(reference.head_primitives, Some(360_000));
        assert!(reference.model_head_primitive_ms.is_some_and(|ms| ms > 0.0));
        // Texel loads by stage. The reference reads its wind map (4
        // floating-point texels a blade) in its bend pass, once a blade, and nothing in its
        // vertex stage since `68eb6f4`.
        assert_eq!(reference.compute_invocations, Some(433_728));
        assert_eq!(reference.float_texture_loads, Some(4 * 433_728));
        assert_eq!(reference.vertex_float_texture_loads, Some(0));
        assert_eq!(reference.vertex_texture_loads, Some(0));
        assert!(
            reference
                .model_float_texture_load_ms
                .is_some_and(|ms| ms > 0.0)
        );
        assert_eq!(reference.gpu_wall_ratio_to_reference, Some(1.0));
        // A compute pass is timed (lavapipe's compute timestamps read low: a column to read
        // beside the wall time, never alone).
        assert!(reference.gpu_ts_compute_ms_median.is_some());
        assert_eq!(zhang.run_id, "4bf71ea71ee3-r0");
        assert_eq!(zhang.technique, "zhang");
        assert!(zhang.is_ok());
        // Samples at a level of their own: bakay's paper point looks its texels up with
        // `textureSampleGrad`, every sample of its shells one.
        let rows: Vec<RunSummary> = read_back(&root.join("bakay_table2/runs.csv"));
        let bakay = &rows[1];
        assert_eq!(bakay.technique, "bakay");
        assert!(bakay.texture_samples.is_some_and(|n| n > 0));
        assert_eq!(bakay.texture_explicit_levels, bakay.texture_samples);
        assert!(
            bakay
                .model_texture_explicit_level_ms
                .is_some_and(|ms| ms > 0.0)
        );
        assert_eq!(reference.texture_explicit_levels, Some(0));
        // The oldest columns: no run id, status, levels of detail or comparisons.
        let rows: Vec<RunSummary> = read_back(&root.join("bakay_vs_reference/runs.csv"));
        assert_eq!(rows[1].technique, "bakay");
        assert!(rows[1].is_ok() && rows[1].run_id.is_empty() && rows[1].repetition == 0);
        assert_eq!(rows[1].gpu_wall_ratio_to_reference, None);
        assert!(rows[1].params.contains("lod=\"minor_axis\""));
    }

    #[test]
    fn every_committed_frames_csv_reads_back_into_its_type() {
        let paths = committed("frames.csv");
        assert!(!paths.is_empty());
        for path in &paths {
            let _: Vec<FrameRecord> = read_back(path);
        }
    }

    #[test]
    fn failed_rows_are_not_ok_and_leave_every_figure_empty() {
        let row = RunSummary::failed("x-r0", "reference", "meadow", "boom");
        assert!(!row.is_ok());
        assert!(RunSummary::from_frames(&[], &toml::Table::new()).is_ok());
        let mut w = csv::Writer::from_writer(Vec::new());
        w.serialize(&row).unwrap();
        let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
        let mut lines = text.lines();
        let (header, cells) = (lines.next().unwrap(), lines.next().unwrap());
        let both = format!("{header}\n{cells}\n");
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .from_reader(both.as_bytes());
        let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.unwrap()).collect();
        let measured = [
            "gpu_wall_ms_median",
            "frame_ms_median",
            "update_ms_median",
            "blades_drawn",
            "triangles",
            "draw_calls",
            "gpu_bytes",
            "blade_cost_ns",
        ];
        for name in measured {
            let k = rows[0].iter().position(|h| h == name).unwrap();
            assert_eq!(&rows[1][k], "", "{name} of a failed run must be empty");
        }
        // Read back, the figures stay missing (not zero).
        let back: RunSummary = csv::Reader::from_reader(text.as_bytes())
            .deserialize()
            .next()
            .unwrap()
            .unwrap();
        assert_eq!((back.gpu_wall_ms_median, back.triangles), (None, None));
        assert_eq!(back.error, "boom");
    }

    #[test]
    fn a_summary_counts_blades_drawn_and_represented_apart() {
        let frame = |drawn, represented, wall| FrameRecord {
            run_id: String::new(),
            technique: "t".into(),
            scene: "s".into(),
            width: 4,
            height: 4,
            msaa: false,
            frame: 0,
            time_s: 0.0,
            wind_ms: 0.0,
            update_ms: 1.0,
            upload_ms: 0.0,
            encode_ms: 0.0,
            gpu_wall_ms: wall,
            gpu_ts_background_ms: None,
            gpu_ts_render_ms: None,
            gpu_ts_compute_ms: None,
            blades_drawn: Some(drawn),
            blades_represented: Some(represented),
            triangles: 10,
            draw_calls: 1,
            gpu_bytes: 5,
            vertex_invocations: None,
            clipper_invocations: None,
            clipper_primitives_out: None,
            fragment_invocations: None,
            fragments_opaque: None,
            fragments_alpha_tested: None,
            fragments_blended: None,
            fragments_passed: None,
            compute_invocations: None,
            background_vertex_invocations: None,
            background_primitives: None,
            background_fragment_invocations: None,
            background_draw_calls: None,
            instances: None,
            background_instances: None,
            primitive_inputs: None,
            background_primitive_inputs: None,
            head_primitives: None,
            background_head_primitives: None,
            texture_loads: None,
            float_texture_loads: None,
            vertex_texture_loads: None,
            vertex_float_texture_loads: None,
            texture_samples: None,
            float_texture_samples: None,
            texture_mip_blends: None,
            texture_explicit_levels: None,
            vertex_transcendentals: None,
            fragment_transcendentals: None,
            compute_transcendentals: None,
            background_texture_loads: None,
            background_float_texture_loads: None,
            background_vertex_texture_loads: None,
            background_vertex_float_texture_loads: None,
            background_texture_samples: None,
            background_float_texture_samples: None,
            background_texture_mip_blends: None,
            background_texture_explicit_levels: None,
            background_vertex_transcendentals: None,
            background_fragment_transcendentals: None,
            vertex_arithmetic: None,
            fragment_arithmetic: None,
            compute_arithmetic: None,
            background_vertex_arithmetic: None,
            background_fragment_arithmetic: None,
            compute_barriers: None,
            compute_storage: None,
            vertex_storage: None,
            compute_divisions: None,
            upload_bytes: None,
            overdraw: None,
            grass_pixels: None,
            fragments_per_grass_pixel: None,
            counters: String::new(),
            levels: Vec::new(),
        };
        let frames = [
            frame(100, 300, 2.0),
            frame(200, 200, 4.0),
            frame(300, 100, 6.0),
        ];
        let s = RunSummary::from_frames(&frames, &toml::Table::new());
        assert_eq!(
            (s.blades_drawn, s.blades_represented),
            (Some(200), Some(200))
        );
        assert_eq!(s.blades_shown(), Some(400));
        // 4 ms over the 400 blades of the median frame.
        assert_eq!(s.blade_cost_ns, Some(4.0 * 1e6 / 400.0));
    }
}
