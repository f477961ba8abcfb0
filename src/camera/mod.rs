//! The camera: a perspective view, its frustum, and deterministic paths through a scene.

mod frustum;
mod path;

use glam::{Mat4, Vec3};

pub use frustum::{Aabb, Frustum};
pub use path::{CameraConfig, CameraPath};

/// A perspective camera looking along `forward` with y up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position, world space.
    pub eye: Vec3,
    /// Unit view direction.
    pub forward: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Near plane distance, m.
    pub near: f32,
    /// Far plane distance, m.
    pub far: f32,
    /// Width over height.
    pub aspect: f32,
}

impl Camera {
    /// A camera at `eye` looking at `target`.
    pub fn look_at(eye: Vec3, target: Vec3, fov_y: f32, near: f32, far: f32, aspect: f32) -> Self {
        Self {
            eye,
            forward: (target - eye).normalize_or(Vec3::NEG_Z),
            fov_y,
            near,
            far,
            aspect,
        }
    }

    /// World-to-view matrix (right-handed, y up).
    pub fn view(&self) -> Mat4 {
        // Avoid a degenerate basis when looking straight up or down.
        let up = if self.forward.y.abs() > 0.999 {
            Vec3::Z
        } else {
            Vec3::Y
        };
        Mat4::look_to_rh(self.eye, self.forward, up)
    }

    /// View-to-clip matrix (wgpu depth range 0..1).
    pub fn projection(&self) -> Mat4 {
        Mat4::perspective_rh(self.fov_y, self.aspect, self.near, self.far)
    }

    /// World-to-clip matrix.
    pub fn view_projection(&self) -> Mat4 {
        self.projection() * self.view()
    }

    /// Unit direction of the ray from the eye through normalised device coordinates `ndc`
    /// (x right, y up, both in `[-1, 1]`): what a click on the picture points at.
    pub fn ray(&self, ndc: glam::Vec2) -> Vec3 {
        let inverse = self.view_projection().inverse();
        let far = inverse.project_point3(Vec3::new(ndc.x, ndc.y, 1.0));
        (far - self.eye).normalize_or(self.forward)
    }

    /// The six planes of the view volume.
    pub fn frustum(&self) -> Frustum {
        Frustum::from_matrix(self.view_projection())
    }
}
