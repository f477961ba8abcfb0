//! The empty technique: the core's background only (sky, ground, the covering map's trees and
//! stones, the moving object). Coverage is measured against it.

use serde::{Deserialize, Serialize};

use super::Variants;
use super::{FrameEncoder, GrassTechnique, InitContext, Technique, TechniqueInfo, TechniqueStats};
use crate::gpu::GpuEstimate;
use crate::params::TechniqueParams;
use crate::{Result, Scene};

/// Draws nothing, so a frame shows the core's background alone.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoGrass;

/// [`NoGrass`] has no parameters.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct NoParams {}

impl TechniqueParams for NoParams {
    fn validate(&self) -> Result<()> {
        Ok(())
    }
}

impl Technique for NoGrass {
    type Params = NoParams;
    const INFO: TechniqueInfo = TechniqueInfo {
        id: "none",
        name: "No grass (background only)",
        paper: "-",
        gpu_state: false,
        debug_views: &[],
    };
    const VARIANTS: Variants = Variants {
        finest: "",
        others: &[],
    };

    fn new(_ctx: &InitContext<'_>, _params: NoParams) -> Result<Self> {
        Ok(Self)
    }

    fn estimate(_scene: &Scene, _params: &NoParams) -> Result<GpuEstimate> {
        Ok(GpuEstimate::default())
    }

    fn params(&self) -> &NoParams {
        &NoParams {}
    }
}

impl GrassTechnique for NoGrass {
    fn encode(&self, _encoder: &mut FrameEncoder<'_>) {}

    fn stats(&self) -> TechniqueStats {
        TechniqueStats::default()
    }
}
