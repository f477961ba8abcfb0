//! Camera paths keyed by time: the same time gives the same view, so every technique is seen
//! from exactly the same places.

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::Camera;
use crate::params::check;
use crate::terrain::Terrain;
use crate::{Error, Result};

/// `[camera]` in a scene file.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CameraConfig {
    /// Vertical field of view, degrees.
    #[serde(default = "default_fov")]
    pub fov_y: f32,
    /// Near plane, m.
    #[serde(default = "default_near")]
    pub near: f32,
    /// Far plane, m.
    #[serde(default = "default_far")]
    pub far: f32,
    /// Where the camera goes.
    pub path: CameraPath,
}

fn default_fov() -> f32 {
    55.0
}
fn default_near() -> f32 {
    0.05
}
fn default_far() -> f32 {
    1000.0
}

/// `[camera.path]`: `kind = "walker" | "orbit" | "flyover" | "dolly" | "fixed"`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum CameraPath {
    /// A person walking along waypoints (x, z) at `speed`, eyes `eye_height` above the ground,
    /// looking `pitch` degrees below the horizon; walks back along the path after the last
    /// waypoint.
    Walker {
        /// Points (x, z) visited in order.
        waypoints: Vec<[f32; 2]>,
        /// Walking speed, m/s.
        #[serde(default = "default_walk_speed")]
        speed: f32,
        /// Eye height above the ground, m.
        #[serde(default = "default_eye_height")]
        eye_height: f32,
        /// Degrees below the horizon.
        #[serde(default = "default_pitch")]
        pitch: f32,
    },
    /// Circling `center` at `radius`, `height` above it, once every `period` seconds.
    Orbit {
        /// Point looked at.
        center: [f32; 3],
        /// Horizontal distance, m.
        radius: f32,
        /// Height above `center`, m.
        height: f32,
        /// Seconds per revolution.
        period: f32,
        /// Angle at time 0, degrees from +x towards +z.
        #[serde(default)]
        start_angle: f32,
    },
    /// Flying from `from` to `to` in `duration` seconds (and back), looking along the flight
    /// direction `pitch` degrees below the horizon.
    Flyover {
        /// Start point.
        from: [f32; 3],
        /// End point.
        to: [f32; 3],
        /// Seconds from `from` to `to`.
        duration: f32,
        /// Degrees below the horizon.
        pitch: f32,
    },
    /// Moving from `from` to `to` in `duration` seconds (and back) while looking at `look_at`.
    Dolly {
        /// Start point.
        from: [f32; 3],
        /// End point.
        to: [f32; 3],
        /// Seconds from `from` to `to`.
        duration: f32,
        /// Point looked at.
        look_at: [f32; 3],
    },
    /// A still camera.
    Fixed {
        /// Eye position.
        eye: [f32; 3],
        /// Point looked at.
        look_at: [f32; 3],
    },
}

fn default_walk_speed() -> f32 {
    1.2
}
fn default_eye_height() -> f32 {
    1.7
}
fn default_pitch() -> f32 {
    10.0
}

impl CameraConfig {
    /// Rejects NaN, infinities and impossible values.
    pub fn validate(&self) -> Result<()> {
        check("camera.fov_y", self.fov_y, 1.0..=170.0)?;
        check("camera.near", self.near, 1e-4..=1e3)?;
        check("camera.far", self.far, 1e-2..=1e7)?;
        if self.far <= self.near {
            return Err(Error::param(
                "camera.far",
                self.far,
                format!("greater than camera.near ({})", self.near),
            ));
        }
        let v3 = |name: &str, v: &[f32; 3]| -> Result<()> {
            for (k, x) in v.iter().enumerate() {
                check(&format!("camera.path.{name}[{k}]"), *x, -1e6..=1e6)?;
            }
            Ok(())
        };
        match &self.path {
            CameraPath::Walker {
                waypoints,
                speed,
                eye_height,
                pitch,
            } => {
                if waypoints.is_empty() {
                    return Err(Error::param(
                        "camera.path.waypoints",
                        "[]",
                        "at least one [x, z] point",
                    ));
                }
                for (k, w) in waypoints.iter().enumerate() {
                    check(&format!("camera.path.waypoints[{k}][0]"), w[0], -1e6..=1e6)?;
                    check(&format!("camera.path.waypoints[{k}][1]"), w[1], -1e6..=1e6)?;
                }
                check("camera.path.speed", *speed, 0.0..=1000.0)?;
                check("camera.path.eye_height", *eye_height, 0.01..=1e4)?;
                check("camera.path.pitch", *pitch, -89.0..=89.0)
            }
            CameraPath::Orbit {
                center,
                radius,
                height,
                period,
                start_angle,
            } => {
                v3("center", center)?;
                check("camera.path.radius", *radius, 0.01..=1e6)?;
                check("camera.path.height", *height, -1e6..=1e6)?;
                check("camera.path.period", *period, 0.01..=1e7)?;
                check("camera.path.start_angle", *start_angle, -1e4..=1e4)
            }
            CameraPath::Flyover {
                from,
                to,
                duration,
                pitch,
            } => {
                v3("from", from)?;
                v3("to", to)?;
                check("camera.path.duration", *duration, 0.01..=1e7)?;
                check("camera.path.pitch", *pitch, -89.0..=89.0)?;
                if Vec2::new(to[0] - from[0], to[2] - from[2]).length() < 1e-3 {
                    return Err(Error::param(
                        "camera.path.to",
                        format!("{to:?}"),
                        "a point horizontally away from `from`",
                    ));
                }
                Ok(())
            }
            CameraPath::Dolly {
                from,
                to,
                duration,
                look_at,
            } => {
                v3("from", from)?;
                v3("to", to)?;
                v3("look_at", look_at)?;
                check("camera.path.duration", *duration, 0.01..=1e7)
            }
            CameraPath::Fixed { eye, look_at } => {
                v3("eye", eye)?;
                v3("look_at", look_at)?;
                if Vec3::from(*eye).distance(Vec3::from(*look_at)) < 1e-4 {
                    return Err(Error::param(
                        "camera.path.look_at",
                        format!("{look_at:?}"),
                        "a point away from `eye`",
                    ));
                }
                Ok(())
            }
        }
    }

    /// The camera at `time` seconds, for a target of aspect `aspect`.
    pub fn camera_at(&self, time: f32, terrain: &Terrain, aspect: f32) -> Camera {
        let (eye, forward) = self.path.pose(time, terrain);
        Camera {
            eye,
            forward,
            fov_y: self.fov_y.to_radians(),
            near: self.near,
            far: self.far,
            aspect,
        }
    }
}

impl CameraPath {
    /// Eye position and unit view direction at `time`.
    pub fn pose(&self, time: f32, terrain: &Terrain) -> (Vec3, Vec3) {
        match self {
            Self::Walker {
                waypoints,
                speed,
                eye_height,
                pitch,
            } => {
                let points: Vec<Vec2> = waypoints.iter().map(|w| Vec2::from(*w)).collect();
                let (xz, dir) = along_polyline(&points, speed * time);
                let eye = terrain.point_at(xz) + Vec3::Y * eye_height;
                (eye, pitched(dir, *pitch))
            }
            Self::Orbit {
                center,
                radius,
                height,
                period,
                start_angle,
            } => {
                let a = start_angle.to_radians() + std::f32::consts::TAU * time / period;
                let c = Vec3::from(*center);
                let eye = c + Vec3::new(radius * a.cos(), *height, radius * a.sin());
                (eye, (c - eye).normalize_or(Vec3::NEG_Z))
            }
            Self::Flyover {
                from,
                to,
                duration,
                pitch,
            } => {
                let (from, to) = (Vec3::from(*from), Vec3::from(*to));
                let (s, outward) = ping_pong(time / duration);
                let eye = from.lerp(to, s);
                let d = if outward { to - from } else { from - to };
                (
                    eye,
                    pitched(Vec2::new(d.x, d.z).normalize_or(Vec2::X), *pitch),
                )
            }
            Self::Dolly {
                from,
                to,
                duration,
                look_at,
            } => {
                let (s, _) = ping_pong(time / duration);
                let eye = Vec3::from(*from).lerp(Vec3::from(*to), s);
                (eye, (Vec3::from(*look_at) - eye).normalize_or(Vec3::NEG_Z))
            }
            Self::Fixed { eye, look_at } => {
                let eye = Vec3::from(*eye);
                (eye, (Vec3::from(*look_at) - eye).normalize_or(Vec3::NEG_Z))
            }
        }
    }
}

/// A horizontal direction tilted `pitch` degrees down.
fn pitched(dir: Vec2, pitch: f32) -> Vec3 {
    let p = pitch.to_radians();
    Vec3::new(dir.x * p.cos(), -p.sin(), dir.y * p.cos())
}

/// Position along `0 → 1 → 0` for a phase that grows by 1 per leg, and whether on the way out.
fn ping_pong(phase: f32) -> (f32, bool) {
    let p = phase.rem_euclid(2.0);
    if p <= 1.0 {
        (p, true)
    } else {
        (2.0 - p, false)
    }
}

/// Point and walking direction at arc length `s` along the polyline, there and back again.
/// The direction looks 2 m ahead so corners turn the head smoothly.
fn along_polyline(points: &[Vec2], s: f32) -> (Vec2, Vec2) {
    let length: f32 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
    let Some(&first) = points.first() else {
        return (Vec2::ZERO, Vec2::X);
    };
    if length < 1e-6 {
        return (first, Vec2::X);
    }
    let (t, outward) = ping_pong(s / length);
    let at = |d: f32| -> Vec2 {
        let mut d = d.clamp(0.0, length);
        for w in points.windows(2) {
            let seg = w[0].distance(w[1]);
            if d <= seg {
                return w[0].lerp(w[1], if seg > 0.0 { d / seg } else { 0.0 });
            }
            d -= seg;
        }
        *points.last().unwrap_or(&first)
    };
    let d = t * length;
    let here = at(d);
    let ahead = if outward { at(d + 2.0) } else { at(d - 2.0) };
    let dir = (ahead - here).normalize_or_zero();
    let dir = if dir == Vec2::ZERO {
        // At an end of the path: keep the heading of the last stretch walked.
        let behind = if outward { at(d - 2.0) } else { at(d + 2.0) };
        (here - behind).normalize_or(Vec2::X)
    } else {
        dir
    };
    (here, dir)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat() -> Terrain {
        Terrain::flat(Vec2::splat(100.0))
    }

    #[test]
    fn walker_walks_at_eye_height_and_turns_back() {
        let path = CameraPath::Walker {
            waypoints: vec![[0.0, 0.0], [10.0, 0.0]],
            speed: 2.0,
            eye_height: 1.7,
            pitch: 0.0,
        };
        let (eye, fwd) = path.pose(2.5, &flat());
        assert!((eye - Vec3::new(5.0, 1.7, 0.0)).length() < 1e-4);
        assert!((fwd - Vec3::X).length() < 1e-4);
        let (eye, fwd) = path.pose(7.5, &flat());
        assert!((eye - Vec3::new(5.0, 1.7, 0.0)).length() < 1e-4);
        assert!((fwd + Vec3::X).length() < 1e-4);
    }

    #[test]
    fn orbit_keeps_radius_and_looks_at_center() {
        let path = CameraPath::Orbit {
            center: [1.0, 0.0, 2.0],
            radius: 10.0,
            height: 5.0,
            period: 8.0,
            start_angle: 0.0,
        };
        for k in 0..16 {
            let (eye, fwd) = path.pose(k as f32 * 0.7, &flat());
            let h = Vec2::new(eye.x - 1.0, eye.z - 2.0).length();
            assert!((h - 10.0).abs() < 1e-3 && (eye.y - 5.0).abs() < 1e-5);
            let to_center = (Vec3::new(1.0, 0.0, 2.0) - eye).normalize();
            assert!(fwd.dot(to_center) > 0.9999);
        }
    }

    #[test]
    fn same_time_same_pose() {
        let path = CameraPath::Flyover {
            from: [-50.0, 30.0, 0.0],
            to: [50.0, 30.0, 10.0],
            duration: 20.0,
            pitch: 30.0,
        };
        assert_eq!(path.pose(3.3, &flat()), path.pose(3.3, &flat()));
        let (_, fwd) = path.pose(3.3, &flat());
        assert!(fwd.y < 0.0 && (fwd.length() - 1.0).abs() < 1e-5);
    }

    #[test]
    fn validation_names_the_field() {
        let c = CameraConfig {
            fov_y: f32::NAN,
            near: 0.1,
            far: 10.0,
            path: CameraPath::Fixed {
                eye: [0.0; 3],
                look_at: [1.0, 0.0, 0.0],
            },
        };
        assert!(
            c.validate()
                .unwrap_err()
                .to_string()
                .contains("camera.fov_y")
        );
        let c = CameraConfig {
            fov_y: 50.0,
            near: 1.0,
            far: 0.5,
            path: CameraPath::Fixed {
                eye: [0.0; 3],
                look_at: [1.0, 0.0, 0.0],
            },
        };
        assert!(c.validate().unwrap_err().to_string().contains("camera.far"));
    }
}
