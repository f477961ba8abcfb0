//! The empty technique: sky and ground only. Coverage is measured against it.

use super::{FrameEncoder, GrassTechnique, TechniqueInfo, TechniqueStats};
use crate::{FrameInputs, GpuContext, Result};

/// Draws nothing, so a frame shows the core's background alone.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoGrass;

impl GrassTechnique for NoGrass {
    fn info(&self) -> TechniqueInfo {
        TechniqueInfo {
            id: "none",
            name: "No grass (background only)",
            paper: "-",
            gpu_state: false,
            debug_views: &[],
        }
    }

    fn params(&self) -> toml::Table {
        toml::Table::new()
    }

    fn update(&mut self, _inputs: &FrameInputs<'_>) -> Result<()> {
        Ok(())
    }

    fn prepare(&mut self, _gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        Ok(())
    }

    fn encode(&self, _encoder: &mut FrameEncoder<'_>) {}

    fn stats(&self) -> TechniqueStats {
        TechniqueStats::default()
    }
}
