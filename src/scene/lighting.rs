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
    /// Keyframes of the direction towards the sun (`[[lights.sun_keys]]`, by time): the sun
    /// moves through them at run time, `sun_direction` is ignored when there are any.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sun_keys: Vec<LightKey>,
    /// An omnidirectional point light (`[lights.point]`), absent by default.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub point: Option<PointLight>,
}

/// One keyframe of a moving light: where it is (or, for the sun, the direction towards it)
/// from `time` on, interpolated linearly to the next keyframe and held after the last.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LightKey {
    /// Scene time, s.
    pub time: f32,
    /// Direction (the sun) or position (a point light), m.
    pub value: [f32; 3],
}

/// A point light with the attenuation `1 / (1 + β d²)` (Boulanger Sec. 3.3).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PointLight {
    /// Position, m (ignored when `keys` are given).
    #[serde(default)]
    pub position: [f32; 3],
    /// Intensity `I_d` (linear RGB).
    pub color: [f32; 3],
    /// β, 1/m².
    #[serde(default = "default_attenuation")]
    pub attenuation: f32,
    /// Keyframes of the position (`[[lights.point.keys]]`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub keys: Vec<LightKey>,
}

fn default_attenuation() -> f32 {
    0.05
}

/// The lights at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightState {
    /// Unit vector towards the sun.
    pub sun_direction: glam::Vec3,
    /// The point light's position, intensity and β, if there is one.
    pub point: Option<(glam::Vec3, glam::Vec3, f32)>,
}

/// The value of light keyframes (sorted by time, validated) at `time`.
fn sample_keys(keys: &[LightKey], time: f32) -> Option<glam::Vec3> {
    crate::keyframes::sample(keys, time, |k| (k.time, k.value.into()))
}

impl Default for LightsConfig {
    fn default() -> Self {
        Self {
            sun_direction: [0.45, 0.75, 0.35],
            sun_color: [1.6, 1.45, 1.2],
            ambient: [0.30, 0.36, 0.45],
            sun_keys: Vec::new(),
            point: None,
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
        check_color("lights.ambient", self.ambient, 100.0)?;
        check_keys("lights.sun_keys", &self.sun_keys)?;
        for (k, key) in self.sun_keys.iter().enumerate() {
            if glam::Vec3::from(key.value).length() < 1e-6 {
                return Err(crate::Error::param(
                    format!("lights.sun_keys[{k}].value"),
                    format!("{:?}", key.value),
                    "a non-zero direction",
                ));
            }
        }
        if let Some(p) = &self.point {
            for (k, v) in p.position.iter().enumerate() {
                check(&format!("lights.point.position[{k}]"), *v, -1e6..=1e6)?;
            }
            check_color("lights.point.color", p.color, 1e4)?;
            check("lights.point.attenuation", p.attenuation, 0.0..=1e4)?;
            check_keys("lights.point.keys", &p.keys)?;
        }
        Ok(())
    }

    /// The lights at scene time `time`: keyframes interpolated, the sun's direction
    /// normalised.
    pub fn at(&self, time: f32) -> LightState {
        let sun = sample_keys(&self.sun_keys, time).unwrap_or(self.sun_direction.into());
        LightState {
            sun_direction: sun.normalize_or(glam::Vec3::Y),
            point: self.point.as_ref().map(|p| {
                (
                    sample_keys(&p.keys, time).unwrap_or(p.position.into()),
                    glam::Vec3::from(p.color),
                    p.attenuation,
                )
            }),
        }
    }
}

/// Keyframes: finite values, times increasing.
fn check_keys(name: &str, keys: &[LightKey]) -> Result<()> {
    for (k, key) in keys.iter().enumerate() {
        check(&format!("{name}[{k}].time"), key.time, 0.0..=1e6)?;
        for (j, v) in key.value.iter().enumerate() {
            check(&format!("{name}[{k}].value[{j}]"), *v, -1e6..=1e6)?;
        }
        if k > 0 && key.time <= keys[k - 1].time {
            return Err(crate::Error::param(
                format!("{name}[{k}].time"),
                key.time,
                format!("later than the previous keyframe ({})", keys[k - 1].time),
            ));
        }
    }
    Ok(())
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keyframes_interpolate_and_hold() {
        let mut l = LightsConfig {
            sun_keys: vec![
                LightKey {
                    time: 1.0,
                    value: [1.0, 0.0, 0.0],
                },
                LightKey {
                    time: 3.0,
                    value: [0.0, 0.0, 1.0],
                },
            ],
            ..Default::default()
        };
        l.validate().unwrap();
        assert_eq!(l.at(0.0).sun_direction, glam::Vec3::X);
        let mid = l.at(2.0).sun_direction;
        assert!((mid - glam::Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6);
        assert_eq!(l.at(9.0).sun_direction, glam::Vec3::Z);
        assert!(l.at(2.0).point.is_none());
        l.sun_keys[1].time = 0.5;
        let e = l.validate().unwrap_err().to_string();
        assert!(e.contains("lights.sun_keys[1].time"), "{e}");
        let p = LightsConfig {
            point: Some(PointLight {
                position: [0.0, 2.0, 0.0],
                color: [4.0; 3],
                attenuation: f32::NAN,
                keys: Vec::new(),
            }),
            ..Default::default()
        };
        assert!(
            p.validate()
                .unwrap_err()
                .to_string()
                .contains("lights.point.attenuation")
        );
    }
}
