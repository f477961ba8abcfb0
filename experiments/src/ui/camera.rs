//! The camera every pane shares: the scene's scripted path, a walker, or an orbit.

use eframe::egui;
use grassbench::Scene;
use grassbench::glam::{Vec2, Vec3};

/// How the shared camera moves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraMode {
    /// The scene file's camera path, played with scene time.
    Path,
    /// WASD + mouse look, eyes `eye_height` above the ground.
    Walker {
        /// Position on the ground (x, z).
        position: Vec2,
        /// Heading, radians from +x towards +z.
        yaw: f32,
        /// Radians above the horizon.
        pitch: f32,
        /// Eye height above the ground, m.
        eye_height: f32,
    },
    /// Circling a point; drag to turn, scroll to zoom.
    Orbit {
        /// Point looked at.
        center: Vec3,
        /// Angle around the centre, radians.
        yaw: f32,
        /// Angle above the ground, radians.
        pitch: f32,
        /// Distance, m.
        distance: f32,
    },
}

impl CameraMode {
    /// Short name for the UI.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Path => "scene path",
            Self::Walker { .. } => "walker",
            Self::Orbit { .. } => "orbit",
        }
    }

    /// A walker standing where the scene camera is at `frame`, looking the same way.
    pub fn walker_from(scene: &Scene, frame: u64) -> Self {
        let cam = scene.camera_at(frame, scene.resolution());
        let ground = scene.terrain.height_at(Vec2::new(cam.eye.x, cam.eye.z));
        Self::Walker {
            position: Vec2::new(cam.eye.x, cam.eye.z),
            yaw: cam.forward.z.atan2(cam.forward.x),
            pitch: cam.forward.y.asin(),
            eye_height: (cam.eye.y - ground).clamp(0.3, 50.0),
        }
    }

    /// An orbit around the terrain's centre, seen from where the scene camera is at `frame`.
    pub fn orbit_from(scene: &Scene, frame: u64) -> Self {
        let cam = scene.camera_at(frame, scene.resolution());
        let center = scene.terrain.point_at(Vec2::ZERO);
        let d = cam.eye - center;
        Self::Orbit {
            center,
            yaw: d.z.atan2(d.x),
            pitch: (d.y / d.length().max(1e-3)).asin().clamp(0.02, 1.5),
            distance: d.length().clamp(2.0, 2000.0),
        }
    }

    /// Eye and view direction, or `None` to follow the scene path.
    pub fn pose(&self, scene: &Scene) -> Option<(Vec3, Vec3)> {
        match *self {
            Self::Path => None,
            Self::Walker {
                position,
                yaw,
                pitch,
                eye_height,
            } => {
                let eye = scene.terrain.point_at(position) + Vec3::Y * eye_height;
                Some((eye, direction(yaw, pitch)))
            }
            Self::Orbit {
                center,
                yaw,
                pitch,
                distance,
            } => {
                let eye = center
                    + Vec3::new(
                        yaw.cos() * pitch.cos(),
                        pitch.sin(),
                        yaw.sin() * pitch.cos(),
                    ) * distance;
                Some((eye, (center - eye).normalize_or(Vec3::NEG_Z)))
            }
        }
    }

    /// Applies keyboard input (walker: WASD, Q/E down/up) over `dt` seconds and a pointer drag
    /// and scroll on a pane. Returns whether the camera moved.
    pub fn control(
        &mut self,
        input: &egui::InputState,
        drag: egui::Vec2,
        scroll: f32,
        dt: f32,
    ) -> bool {
        let before = *self;
        match self {
            Self::Path => {}
            Self::Walker {
                position,
                yaw,
                pitch,
                eye_height,
            } => {
                *yaw += drag.x * 0.005;
                *pitch = (*pitch - drag.y * 0.005).clamp(-1.4, 1.4);
                let speed = if input.modifiers.shift { 8.0 } else { 2.0 };
                let forward = Vec2::new(yaw.cos(), yaw.sin());
                let right = Vec2::new(-forward.y, forward.x);
                let key = |k| if input.key_down(k) { 1.0 } else { 0.0 };
                let step = forward * (key(egui::Key::W) - key(egui::Key::S))
                    + right * (key(egui::Key::D) - key(egui::Key::A));
                *position += step * speed * dt;
                *eye_height = (*eye_height + (key(egui::Key::E) - key(egui::Key::Q)) * speed * dt)
                    .clamp(0.1, 500.0);
            }
            Self::Orbit {
                yaw,
                pitch,
                distance,
                ..
            } => {
                *yaw += drag.x * 0.005;
                *pitch = (*pitch + drag.y * 0.005).clamp(0.02, 1.5);
                *distance = (*distance * (1.0 - scroll * 0.001)).clamp(1.0, 5000.0);
            }
        }
        *self != before
    }
}

fn direction(yaw: f32, pitch: f32) -> Vec3 {
    Vec3::new(
        yaw.cos() * pitch.cos(),
        pitch.sin(),
        yaw.sin() * pitch.cos(),
    )
}
