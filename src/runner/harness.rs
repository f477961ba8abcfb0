//! A harness: a [`World`] with one [`View`], the shape the command line (`run`, `render`,
//! `compare`, sweeps), the benches and the tests render through. Every method hands over to
//! the world with the one view, so a harness draws exactly what the UI's panes draw.

use super::{FrameOutput, View, World};
use crate::target::Size;
use crate::technique::{GrassTechnique, TechniqueEntry};
use crate::wind::{WindConfig, WindField};
use crate::{GpuContext, Result, Scene};

/// One scene rendered at one size: the shared world and a single view of it.
pub struct Harness<'g> {
    /// The scene, its GPU resources and the wind.
    pub world: World<'g>,
    /// The target, pass timer, debug view and camera override.
    pub view: View,
}

impl<'g> Harness<'g> {
    /// Sets up a scene for targets of `size`, with 4x MSAA when `msaa`.
    pub fn new(gpu: &'g GpuContext, scene: Scene, size: Size, msaa: bool) -> Result<Self> {
        let view = View::new(gpu, size, msaa)?;
        let world = World::new(gpu, scene, view.target.sample_count)?;
        Ok(Self { world, view })
    }

    /// Changes the target size (same sample count) and tells `technique`.
    pub fn resize(&mut self, technique: &mut dyn GrassTechnique, size: Size) -> Result<()> {
        self.view.resize(self.world.gpu, technique, size)
    }

    /// Replaces the scene's wind (validated) and restarts it from time 0.
    pub fn set_wind(&mut self, config: WindConfig) -> Result<()> {
        self.world.set_wind(config)
    }

    /// The wind as it stands after the last frame.
    pub fn wind(&self) -> &dyn WindField {
        self.world.wind()
    }

    /// What a technique is created with on this harness's scene and target.
    pub fn init_context(&self) -> crate::technique::InitContext<'_> {
        self.world.init_context(&self.view)
    }

    /// Creates a technique: its defaults, overlaid with the scene file's `[techniques.<id>]`,
    /// overlaid with `overrides`.
    pub fn create(
        &self,
        entry: &TechniqueEntry,
        overrides: &toml::Table,
    ) -> Result<Box<dyn GrassTechnique>> {
        self.world.create(&self.view, entry, overrides)
    }

    /// The camera of `frame` (the scene's path, or [`View::camera_override`]).
    pub fn camera(&self, frame: u64) -> crate::camera::Camera {
        self.world.camera(&self.view, frame)
    }

    /// Runs `technique.update` for frames `from..to` without drawing them (techniques with GPU
    /// state also draw them), so a later frame sees the same history as in a full run.
    pub fn catch_up(
        &mut self,
        technique: &mut dyn GrassTechnique,
        from: u64,
        to: u64,
    ) -> Result<()> {
        self.world.catch_up(&mut self.view, technique, from, to)
    }

    /// Uploads and records frame `frame` of `technique` without submitting it (for benchmarks
    /// of `prepare` + `encode`); `update` must have run for this frame.
    pub fn record(
        &mut self,
        technique: &mut dyn GrassTechnique,
        frame: u64,
    ) -> Result<wgpu::CommandBuffer> {
        self.world.record(&self.view, technique, frame)
    }

    /// Runs only `technique.update` for `frame` (for benchmarks of the CPU stage).
    pub fn update_only(&mut self, technique: &mut dyn GrassTechnique, frame: u64) -> Result<()> {
        self.world.update_only(&self.view, technique, frame)
    }

    /// Renders one frame of `technique` and measures it; returns the image if `capture`.
    pub fn frame(
        &mut self,
        technique: &mut dyn GrassTechnique,
        frame: u64,
        capture: bool,
    ) -> Result<FrameOutput> {
        self.world.frame(&mut self.view, technique, frame, capture)
    }
}
