//! A view: one picture of a [`World`](super::World). The render target, the camera override,
//! the debug view and the pass timer: what each of the UI's panes has of its own, while the
//! scene, its GPU resources and the wind are the world's, shared.

use crate::target::Size;
use crate::technique::{GrassTechnique, PassTimer, WorkCounter};
use crate::{GpuContext, RenderTarget, Result};

/// Where one technique's frames of a world are drawn, and how they are looked at.
pub struct View {
    /// Where frames are drawn.
    pub target: RenderTarget,
    /// Debug view passed to techniques (0 = none).
    pub debug_view: u32,
    /// Eye and unit view direction replacing the scene's camera path (the UI's free camera).
    pub camera_override: Option<(glam::Vec3, glam::Vec3)>,
    /// Timestamp queries around each pass, where the adapter has them.
    pub(super) timer: Option<PassTimer>,
    /// Pipeline-statistics queries around each pass, where the adapter has them.
    pub(super) work: Option<WorkCounter>,
}

impl View {
    /// A target of `size`, with 4x MSAA when `msaa`.
    pub fn new(gpu: &GpuContext, size: Size, msaa: bool) -> Result<Self> {
        Ok(Self {
            target: RenderTarget::new(gpu, size, msaa)?,
            debug_view: 0,
            camera_override: None,
            timer: PassTimer::new(gpu),
            work: WorkCounter::new(gpu),
        })
    }

    /// Changes the target size (same sample count) and tells `technique`.
    pub fn resize(
        &mut self,
        gpu: &GpuContext,
        technique: &mut dyn GrassTechnique,
        size: Size,
    ) -> Result<()> {
        if size != self.target.size {
            self.target = RenderTarget::new(gpu, size, self.target.sample_count > 1)?;
            technique.resize(gpu, size)?;
        }
        Ok(())
    }
}
