//! The scene's moving object: a sphere flying over the grass along a path. Perbet & Cani's
//! blast of air follows "a flying object" (Sec. 3.3, Fig. 12: a teapot two metres above the
//! prairie) and Zhang's interaction sphere pushes blades aside (Sec. 6.2); one object in the
//! shared scene serves both, so every technique sees (and can react to) the same one. The core
//! draws it; techniques read its centre with [`ObjectConfig::centre`].
//!
//! ```toml
//! [object]
//! radius = 0.5
//! height = 2.0                      # centre above the ground, m
//! keyframes = [[0.0, -30.0, -10.0], [20.0, 0.0, 0.0], [40.0, 30.0, 10.0]]   # [time, x, z]
//! ```

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use crate::Result;
use crate::params::check;
use crate::terrain::Terrain;

/// `[object]` in a scene file.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct ObjectConfig {
    /// Radius of the sphere, m.
    pub radius: f32,
    /// Height of its centre above the ground under it, m.
    pub height: f32,
    /// Ground position (x, z) at time 0 (without keyframes).
    pub start: [f32; 2],
    /// Velocity over the ground, m/s (without keyframes).
    pub velocity: [f32; 2],
    /// `[time, x, z]` points of its path, times increasing; held before the first and after
    /// the last. Empty: `start` and `velocity` are used.
    pub keyframes: Vec<[f32; 3]>,
}

impl Default for ObjectConfig {
    fn default() -> Self {
        Self {
            radius: 0.5,
            height: 2.0,
            start: [0.0, 0.0],
            velocity: [0.0, 0.0],
            keyframes: Vec::new(),
        }
    }
}

impl ObjectConfig {
    /// Rejects NaN, negative or absurd sizes and paths whose times do not increase.
    pub fn validate(&self) -> Result<()> {
        check("object.radius", self.radius, 0.01..=100.0)?;
        check("object.height", self.height, -100.0..=1000.0)?;
        crate::keyframes::validate_track("object", self.start, self.velocity, &self.keyframes)
    }

    /// Ground position (x, z) of the object at `time`.
    pub fn ground_position(&self, time: f32) -> Vec2 {
        crate::keyframes::track(self.start, self.velocity, &self.keyframes, time)
    }

    /// Centre of the sphere at `time`, `height` above the ground of `terrain`.
    pub fn centre(&self, terrain: &Terrain, time: f32) -> Vec3 {
        let xz = self.ground_position(time);
        Vec3::new(xz.x, terrain.height_at(xz) + self.height, xz.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_centre_flies_above_the_ground() {
        let terrain = Terrain::flat(Vec2::new(50.0, 50.0));
        let o = ObjectConfig {
            velocity: [1.0, 0.0],
            ..Default::default()
        };
        let c = o.centre(&terrain, 3.0);
        assert_eq!(
            c,
            Vec3::new(3.0, terrain.height_at(Vec2::new(3.0, 0.0)) + 2.0, 0.0)
        );
    }

    #[test]
    fn bad_objects_name_the_key() {
        let mut o = ObjectConfig {
            radius: f32::NAN,
            ..Default::default()
        };
        assert!(
            o.validate()
                .unwrap_err()
                .to_string()
                .contains("object.radius")
        );
        o.radius = 1.0;
        o.keyframes = vec![[1.0, 0.0, 0.0], [1.0, 1.0, 1.0]];
        assert!(
            o.validate()
                .unwrap_err()
                .to_string()
                .contains("object.keyframes[1][0]")
        );
    }
}
