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
//!    queries and counts every draw and dispatch, so no technique can forget to be timed or
//!    counted, or be timed or counted differently.
//!
//! What a technique *is* (parameters, identity, variants, construction, memory estimate) is
//! the typed [`Technique`] trait; [`entry`] turns it into the registry's [`TechniqueEntry`].

mod definition;
mod encoder;
mod no_grass;
mod pass;
pub mod ranges;
pub mod work;

pub use definition::{
    DEFAULT_VARIANT, Describe, FINEST, NO_TRANSITIONS, PAPER, Technique, TechniqueEntry,
    VARIANT_KEY, Variant, Variants, entry, label_params, overlay, variant_differences, variant_of,
};
pub use encoder::{FrameEncoder, PassKind, PassTime, PassTimer};
pub use no_grass::{NoGrass, NoParams};
pub use pass::{ComputePass, PassCounts, RenderPass};
pub use work::{PassWork, PassWorkRecord, WorkCounter};

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

/// What a technique submitted in its last frame and what it holds. Draw calls are not here:
/// the [`FrameEncoder`] counts them as they are recorded.
///
/// Blades are counted two ways:
/// - [`Self::blades_drawn`]: blades whose own geometry was submitted this frame (instances of
///   a blade mesh, a Bezier blade's strip, ...), whatever opacity the shader gives them;
/// - [`Self::blades_represented`]: the scene's blades that impostors stand for instead (a
///   billboard, texture slices, shells, a 2D texture), each blade once however many impostor
///   layers show it: a cell's vertical and horizontal slices together stand for its blades
///   once. An impostor that shows only a share of a blade (a transition band, where the
///   blade's geometry fades out as the impostor fades in) counts that share; shares are summed
///   and rounded to whole blades.
///
/// So `blades_drawn + blades_represented` ([`Self::blades_shown`]) is the population the frame
/// stands for: the blades in view, less what the technique dropped (culling, density falling
/// with distance), plus at most the blades of its transition bands counted twice in part
/// (drawn, and by the impostor's share). Both are tested per technique against an
/// independent count of the scene's blades on a small scene (`tests/tests/counts.rs`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct TechniqueStats {
    /// Blades drawn as geometry.
    pub blades_drawn: u64,
    /// Blades an impostor stands for (each blade once; none of those in `blades_drawn`).
    pub blades_represented: u64,
    /// Triangles submitted.
    pub triangles: u64,
    /// GPU memory held by the technique, bytes.
    pub gpu_bytes: u64,
}

impl TechniqueStats {
    /// Every blade the frame shows, drawn or represented.
    pub fn blades_shown(&self) -> u64 {
        self.blades_drawn + self.blades_represented
    }
}

/// Blades one of a technique's own levels of detail drew or stood for in the last frame
/// (written to `levels.csv` in long format: run, frame, level, blades).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct LevelBlades {
    /// The level's name, as the technique's essay calls it (`geometry`, `billboards`, ...).
    pub level: &'static str,
    /// Blades it drew or stood for.
    pub blades: u64,
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

/// A real-time grass technique's per-frame work. Object-safe: the registry creates
/// `Box<dyn GrassTechnique>`. Its identity and parameters come from [`Describe`], which every
/// [`Technique`] has without writing anything.
pub trait GrassTechnique: Describe {
    /// The target changed size (pipelines stay valid: sample count changes recreate the
    /// technique).
    fn resize(&mut self, _gpu: &GpuContext, _size: Size) -> Result<()> {
        Ok(())
    }

    /// CPU work for a frame: animation, culling, LOD selection, instance generation. Nothing
    /// by default (a technique whose state is static or computed on the GPU).
    fn update(&mut self, _inputs: &FrameInputs<'_>) -> Result<()> {
        Ok(())
    }

    /// Uploads what `update` produced. Nothing by default.
    fn prepare(&mut self, _gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        Ok(())
    }

    /// Records the frame's passes. Must not change state.
    fn encode(&self, encoder: &mut FrameEncoder<'_>);

    /// Counts for the last frame.
    fn stats(&self) -> TechniqueStats;

    /// Blades per level of detail in the last frame, in the technique's own levels, finest
    /// first (empty for techniques without levels).
    fn levels(&self) -> Vec<LevelBlades> {
        Vec::new()
    }

    /// Technique-specific counts of the last frame (grids culled, impostors by size, sort
    /// time, ...), written to `frames.csv`'s `counters` column as `name=value;...`.
    fn counters(&self) -> Vec<(&'static str, f64)> {
        Vec::new()
    }
}
