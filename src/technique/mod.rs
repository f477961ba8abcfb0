//! The contract every grass technique implements.
//!
//! A technique owns only what it keeps across frames (pipelines, buffers, pre-computed
//! textures); the device, the queue, the scene's bind group 0 and the render target are
//! borrowed. The frame is split into stages the runner times separately:
//!
//! 1. [`GrassTechnique::update`]: CPU only (animation, culling, LOD choice, instance data);
//! 2. [`GrassTechnique::prepare`]: uploads to the GPU;
//! 3. [`GrassTechnique::encode`]: records passes, changing no state, so the same frame can be
//!    encoded again; passes are opened through the [`FrameEncoder`], which adds timestamp
//!    queries, so no technique can forget to be timed or be timed differently.

mod encoder;
mod no_grass;
pub mod ranges;

pub use encoder::{FrameEncoder, PassKind, PassTime, PassTimer};
pub use no_grass::NoGrass;

use crate::scene::SceneGpu;
use crate::target::Size;
use crate::{FrameInputs, GpuContext, Result, Scene};

/// Who a technique is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TechniqueInfo {
    /// Stable id used in files and on the command line, e.g. `reference`.
    pub id: &'static str,
    /// Display name.
    pub name: &'static str,
    /// The paper it follows.
    pub paper: &'static str,
    /// Whether the technique keeps simulation state on the GPU that every frame must advance
    /// (if not, the runner may skip encoding frames it does not show or measure).
    pub gpu_state: bool,
    /// Names of the debug views the technique offers; view `k` (1-based, passed in
    /// [`FrameInputs::debug_view`]) is `debug_views[k - 1]`. Empty when it offers none.
    pub debug_views: &'static [&'static str],
}

/// What a technique submitted in its last frame and what it holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct TechniqueStats {
    /// Blades represented (drawn as geometry or standing in an impostor).
    pub blades: u64,
    /// Triangles submitted.
    pub triangles: u64,
    /// Draw calls recorded.
    pub draw_calls: u64,
    /// GPU memory held by the technique, bytes.
    pub gpu_bytes: u64,
}

/// Blades drawn by each level of detail in the last frame (Boulanger Sec. 3.1's three levels;
/// other techniques map their own levels onto these three or report none).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct LodBlades {
    /// Blades drawn as geometry.
    pub geometry: u64,
    /// Blades represented by vertical (volume) slices.
    pub vertical_slices: u64,
    /// Blades represented by horizontal slices or other flat impostors.
    pub horizontal_slices: u64,
}

/// What a technique is created with.
pub struct InitContext<'a> {
    /// Device and queue (borrowed: techniques never store them).
    pub gpu: &'a GpuContext,
    /// The scene.
    pub scene: &'a Scene,
    /// The scene's GPU resources and bind group 0 layout.
    pub scene_gpu: &'a SceneGpu,
    /// Target size.
    pub size: Size,
    /// Target sample count (1 or 4): pipelines must match it.
    pub sample_count: u32,
}

/// A real-time grass technique. Object-safe: the registry holds `Box<dyn GrassTechnique>`.
pub trait GrassTechnique {
    /// Id, name and paper.
    fn info(&self) -> TechniqueInfo;

    /// The parameters in use, as recorded in result files.
    fn params(&self) -> toml::Table;

    /// The target changed size (pipelines stay valid: sample count changes recreate the
    /// technique).
    fn resize(&mut self, _gpu: &GpuContext, _size: Size) -> Result<()> {
        Ok(())
    }

    /// CPU work for a frame: animation, culling, LOD selection, instance generation.
    fn update(&mut self, inputs: &FrameInputs<'_>) -> Result<()>;

    /// Uploads what `update` produced.
    fn prepare(&mut self, gpu: &GpuContext, inputs: &FrameInputs<'_>) -> Result<()>;

    /// Records the frame's passes. Must not change state.
    fn encode(&self, encoder: &mut FrameEncoder<'_>);

    /// Counts for the last frame.
    fn stats(&self) -> TechniqueStats;

    /// Blades per level of detail in the last frame, for techniques that have levels (`None`
    /// leaves the CSV columns empty).
    fn lod_blades(&self) -> Option<LodBlades> {
        None
    }

    /// Technique-specific counts of the last frame (grids culled, impostors by size, sort
    /// time, ...), written to `frames.csv`'s `counters` column as `name=value;...`.
    fn counters(&self) -> Vec<(&'static str, f64)> {
        Vec::new()
    }
}

/// A named set of parameter overrides a technique offers to the comparison suite.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Variant {
    /// `finest` (its finest representation everywhere, for LOD fidelity) or
    /// `no_transitions` (LOD switches without blending, to show the popping metric works).
    pub name: &'static str,
    /// Parameter overrides, in TOML (`"shells = 128"`).
    pub params: &'static str,
}

/// Name of the variant that forces a technique's finest representation everywhere.
pub const FINEST: &str = "finest";
/// Name of the variant that switches levels of detail without transitions.
pub const NO_TRANSITIONS: &str = "no_transitions";

/// One line of the registry: how to make a technique.
#[derive(Clone, Copy)]
pub struct TechniqueEntry {
    /// Id, name and paper.
    pub info: TechniqueInfo,
    /// Parameter variants for the comparison suite (see [`FINEST`], [`NO_TRANSITIONS`]).
    pub variants: &'static [Variant],
    /// The defaults of its parameter struct.
    pub default_params: fn() -> toml::Table,
    /// Creates it with parameter overrides (unknown keys and bad values are errors).
    pub create: fn(&InitContext<'_>, &toml::Table) -> Result<Box<dyn GrassTechnique>>,
    /// What `create` with these overrides will allocate on the GPU, computed without any GPU
    /// work from the same numbers `create` uses; the harness checks it against the adapter
    /// ([`crate::gpu::memory`]) before creating anything.
    pub estimate: fn(&crate::Scene, &toml::Table) -> Result<crate::gpu::GpuEstimate>,
}

impl TechniqueEntry {
    /// The overrides of variant `name`, if the technique offers it.
    pub fn variant(&self, name: &str) -> Option<crate::Result<toml::Table>> {
        self.variants.iter().find(|v| v.name == name).map(|v| {
            v.params
                .parse::<toml::Table>()
                .map_err(|e| crate::Error::Technique {
                    technique: self.info.id.to_owned(),
                    message: format!("variant `{name}` is not valid TOML: {e}"),
                })
        })
    }
}

impl std::fmt::Debug for TechniqueEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TechniqueEntry")
            .field("info", &self.info)
            .finish_non_exhaustive()
    }
}
