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

    /// Focal length in pixels on a target `height` pixels tall: an object `s` metres across at
    /// depth `d` covers about `s · focal / d` pixels.
    pub fn focal_pixels(&self, height: u32) -> f32 {
        height as f32 / (2.0 * (self.fov_y * 0.5).tan())
    }

    /// Depth along the view direction of the nearest corner of `b` (negative when a corner is
    /// behind the eye): the depth at which a level of detail for `b` must be chosen so that
    /// none of `b` is drawn coarser than its nearest point allows.
    pub fn nearest_depth(&self, b: &Aabb) -> f32 {
        let mut depth = f32::INFINITY;
        for c in 0..8 {
            let corner = Vec3::new(
                if c & 1 == 0 { b.min.x } else { b.max.x },
                if c & 2 == 0 { b.min.y } else { b.max.y },
                if c & 4 == 0 { b.min.z } else { b.max.z },
            );
            depth = depth.min((corner - self.eye).dot(self.forward));
        }
        depth
    }

    /// A lower bound on the depth of every point of `b` that the camera can see: the
    /// [nearest depth](Self::nearest_depth) of the box, or, where a corner lies behind or
    /// beside the eye, the box's distance from the eye times the cosine of the angle between
    /// the view direction and the view volume's corner rays (no visible point is nearer in
    /// depth than that). A level of detail chosen at this depth is conservative for what is
    /// seen of `b`, and not needlessly fine for boxes beside the eye.
    pub fn nearest_visible_depth(&self, b: &Aabb) -> f32 {
        let tan_y = (self.fov_y * 0.5).tan();
        let tan_x = tan_y * self.aspect;
        let corner_cos = 1.0 / (1.0 + tan_x * tan_x + tan_y * tan_y).sqrt();
        let distance = (self.eye.clamp(b.min, b.max) - self.eye).length();
        self.nearest_depth(b).max(distance * corner_cos)
    }
}
