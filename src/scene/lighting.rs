//! Lights and sky: every technique is lit by these, and the core draws the same sky and
//! ground for all.

use serde::{Deserialize, Serialize};

use crate::Result;
use crate::params::check;

/// `[lights]` in a scene file. Colours are linear RGB.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct LightsConfig {
    /// Direction towards the sun (normalised when used).
    pub sun_direction: [f32; 3],
    /// Sun irradiance.
    pub sun_color: [f32; 3],
    /// Ambient (sky) light.
    pub ambient: [f32; 3],
}

impl Default for LightsConfig {
    fn default() -> Self {
        Self {
            sun_direction: [0.45, 0.75, 0.35],
            sun_color: [1.6, 1.45, 1.2],
            ambient: [0.30, 0.36, 0.45],
        }
    }
}

/// `[sky]` in a scene file. Colours are linear RGB.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct SkyConfig {
    /// Sky straight up.
    pub zenith: [f32; 3],
    /// Sky at the horizon; also the fog colour.
    pub horizon: [f32; 3],
    /// Bare ground albedo.
    pub ground: [f32; 3],
    /// Fog density, 1/m (0 = clear air).
    pub fog_density: f32,
}

impl Default for SkyConfig {
    fn default() -> Self {
        Self {
            zenith: [0.12, 0.25, 0.55],
            horizon: [0.55, 0.65, 0.75],
            ground: [0.16, 0.12, 0.07],
            fog_density: 0.002,
        }
    }
}

fn check_color(name: &str, c: [f32; 3], max: f32) -> Result<()> {
    for (k, v) in c.iter().enumerate() {
        check(&format!("{name}[{k}]"), *v, 0.0..=max)?;
    }
    Ok(())
}

impl LightsConfig {
    /// Rejects NaN, negative and absurd values.
    pub fn validate(&self) -> Result<()> {
        for (k, v) in self.sun_direction.iter().enumerate() {
            check(&format!("lights.sun_direction[{k}]"), *v, -1e3..=1e3)?;
        }
        if glam::Vec3::from(self.sun_direction).length() < 1e-6 {
            return Err(crate::Error::param(
                "lights.sun_direction",
                format!("{:?}", self.sun_direction),
                "a non-zero vector",
            ));
        }
        check_color("lights.sun_color", self.sun_color, 100.0)?;
        check_color("lights.ambient", self.ambient, 100.0)
    }
}

impl SkyConfig {
    /// Rejects NaN, negative and absurd values.
    pub fn validate(&self) -> Result<()> {
        check_color("sky.zenith", self.zenith, 100.0)?;
        check_color("sky.horizon", self.horizon, 100.0)?;
        check_color("sky.ground", self.ground, 1.0)?;
        check("sky.fog_density", self.fog_density, 0.0..=10.0)
    }
}
