//! How a scene file describes its wind.

use serde::{Deserialize, Serialize};

use super::fluid::FluidConfig;
use super::primitives::PrimitivesConfig;
use crate::params::check;
use crate::{Error, Result};

/// `[wind]` in a scene file: `model = "breeze" | "point_source" | "fluid" | "primitives" |
/// "calm"` plus the model's keys.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum WindConfig {
    /// No wind.
    Calm,
    /// A steady breeze with travelling gusts.
    Breeze(BreezeConfig),
    /// Bakay et al.'s point source.
    PointSource(PointSourceConfig),
    /// Stam's stable fluids (Zhang Ch. 2), tiled or stretched over the terrain.
    Fluid(FluidConfig),
    /// Perbet & Cani's wind primitives (Sec. 3.3), with `[[wind.primitives]]`.
    Primitives(PrimitivesConfig),
}

impl Default for WindConfig {
    fn default() -> Self {
        Self::Breeze(BreezeConfig::default())
    }
}

/// A steady wind along `direction` with gust fronts travelling downwind.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct BreezeConfig {
    /// Direction the wind blows towards, in the ground plane (x, z); normalised.
    pub direction: [f32; 2],
    /// Mean speed, m/s.
    pub speed: f32,
    /// Gust amplitude as a fraction of the mean speed.
    pub gust_strength: f32,
    /// Distance between gust fronts, m.
    pub gust_wavelength: f32,
    /// Speed at which gust fronts travel downwind, m/s.
    pub gust_speed: f32,
    /// Small-scale turbulence as a fraction of the mean speed.
    pub turbulence: f32,
}

impl Default for BreezeConfig {
    fn default() -> Self {
        Self {
            direction: [1.0, 0.35],
            speed: 3.0,
            gust_strength: 0.7,
            gust_wavelength: 18.0,
            gust_speed: 5.0,
            turbulence: 0.25,
        }
    }
}

/// Bakay et al. 2002, Sec. 3: every vertex's wind vector points to a source; the world is cut
/// into animation steps by distance from the source, and each step sees the periodic intensity
/// function delayed by its step, so gusts travel outwards as waves (their Fig. 8).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct PointSourceConfig {
    /// World position of the source.
    pub position: [f32; 3],
    /// Wind speed (m/s) at intensity 1.
    pub speed: f32,
    /// Period of the intensity function, s.
    pub period: f32,
    /// Width of one animation step (distance band), m.
    pub step_length: f32,
    /// Delay between neighbouring steps, s: gusts travel at `step_length / step_delay` m/s.
    pub step_delay: f32,
    /// Constant added to the intensity, so the grass leans on average (0 = swings both ways).
    pub bias: f32,
}

impl Default for PointSourceConfig {
    fn default() -> Self {
        Self {
            position: [0.0, 0.0, 0.0],
            speed: 4.0,
            period: 4.0,
            step_length: 2.0,
            step_delay: 0.35,
            bias: 0.3,
        }
    }
}

impl WindConfig {
    /// The `model` names, in the order the UI lists them.
    pub const MODELS: &'static [&'static str] =
        &["calm", "breeze", "point_source", "fluid", "primitives"];

    /// The `model` name of this configuration.
    pub fn model(&self) -> &'static str {
        match self {
            Self::Calm => "calm",
            Self::Breeze(_) => "breeze",
            Self::PointSource(_) => "point_source",
            Self::Fluid(_) => "fluid",
            Self::Primitives(_) => "primitives",
        }
    }

    /// The default configuration of model `name`.
    pub fn default_for(name: &str) -> Option<Self> {
        match name {
            "calm" => Some(Self::Calm),
            "breeze" => Some(Self::Breeze(BreezeConfig::default())),
            "point_source" => Some(Self::PointSource(PointSourceConfig::default())),
            "fluid" => Some(Self::Fluid(FluidConfig::default())),
            "primitives" => Some(Self::Primitives(PrimitivesConfig::default())),
            _ => None,
        }
    }

    /// Rejects NaN, infinities and absurd values.
    pub fn validate(&self) -> Result<()> {
        match self {
            Self::Calm => Ok(()),
            Self::Breeze(c) => {
                let [x, z] = c.direction;
                check("wind.direction[0]", x, -1e6..=1e6)?;
                check("wind.direction[1]", z, -1e6..=1e6)?;
                if x.hypot(z) < 1e-6 {
                    return Err(Error::param(
                        "wind.direction",
                        format!("{:?}", c.direction),
                        "a non-zero 2D vector",
                    ));
                }
                check("wind.speed", c.speed, 0.0..=100.0)?;
                check("wind.gust_strength", c.gust_strength, 0.0..=5.0)?;
                check("wind.gust_wavelength", c.gust_wavelength, 0.1..=10_000.0)?;
                check("wind.gust_speed", c.gust_speed, 0.0..=200.0)?;
                check("wind.turbulence", c.turbulence, 0.0..=5.0)
            }
            Self::PointSource(c) => {
                for (k, v) in c.position.iter().enumerate() {
                    check(&format!("wind.position[{k}]"), *v, -1e6..=1e6)?;
                }
                check("wind.speed", c.speed, 0.0..=100.0)?;
                check("wind.period", c.period, 0.01..=10_000.0)?;
                check("wind.step_length", c.step_length, 0.01..=10_000.0)?;
                check("wind.step_delay", c.step_delay, 0.0..=10_000.0)?;
                check("wind.bias", c.bias, -2.0..=2.0)
            }
            Self::Fluid(c) => c.validate(),
            Self::Primitives(c) => c.validate(),
        }
    }
}
