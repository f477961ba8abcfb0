//! View-frustum planes and the box and sphere tests culling uses (Zhang Sec. 5.3,
//! Boulanger Sec. 4.1).

use glam::{Mat4, Vec3, Vec4};

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The smallest box holding every point of `points`; `None` when there is none.
    pub fn around(points: impl IntoIterator<Item = Vec3>) -> Option<Self> {
        let mut points = points.into_iter();
        let first = points.next()?;
        let (min, max) = points.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)));
        Some(Self { min, max })
    }
}

/// Six planes `(n, d)` with `n·p + d >= 0` inside: left, right, bottom, top, near, far.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    /// Normalised planes.
    pub planes: [Vec4; 6],
}

impl Frustum {
    /// Extracts the planes of a world-to-clip matrix (Gribb & Hartmann), for wgpu's 0..1 depth.
    pub fn from_matrix(m: Mat4) -> Self {
        let (r0, r1, r2, r3) = (m.row(0), m.row(1), m.row(2), m.row(3));
        let planes = [r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2].map(|p| {
            let len = p.truncate().length();
            if len > 0.0 { p / len } else { p }
        });
        Self { planes }
    }

    /// Whether a point is inside all six planes.
    pub fn contains_point(&self, p: Vec3) -> bool {
        self.planes
            .iter()
            .all(|pl| pl.truncate().dot(p) + pl.w >= 0.0)
    }

    /// Whether a sphere touches the frustum (conservative).
    pub fn intersects_sphere(&self, center: Vec3, radius: f32) -> bool {
        self.planes
            .iter()
            .all(|pl| pl.truncate().dot(center) + pl.w >= -radius)
    }

    /// Whether a box touches the frustum (conservative: the positive vertex test).
    pub fn intersects_aabb(&self, b: &Aabb) -> bool {
        self.planes.iter().all(|pl| {
            let n = pl.truncate();
            let p = Vec3::select(n.cmpge(Vec3::ZERO), b.max, b.min);
            n.dot(p) + pl.w >= 0.0
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn click_rays_go_through_the_picture() {
        let cam = Camera::look_at(
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(4.0, 1.0, -5.0),
            1.0,
            0.1,
            100.0,
            1.5,
        );
        assert!((cam.ray(glam::Vec2::ZERO) - cam.forward).length() < 1e-4);
        // A ray through a corner of the picture projects back onto that corner.
        for ndc in [
            glam::Vec2::new(1.0, 1.0),
            glam::Vec2::new(-1.0, -0.5),
            glam::Vec2::new(0.3, -1.0),
        ] {
            let p = cam.eye + cam.ray(ndc) * 10.0;
            let clip = cam.view_projection().project_point3(p);
            assert!((clip.truncate() - ndc).length() < 1e-3, "{ndc} -> {clip}");
        }
    }
    use crate::camera::Camera;

    fn camera() -> Camera {
        Camera::look_at(
            Vec3::ZERO,
            Vec3::NEG_Z,
            60f32.to_radians(),
            0.1,
            100.0,
            16.0 / 9.0,
        )
    }

    #[test]
    fn points_in_front_are_inside_behind_are_not() {
        let f = camera().frustum();
        assert!(f.contains_point(Vec3::new(0.0, 0.0, -10.0)));
        assert!(!f.contains_point(Vec3::new(0.0, 0.0, 10.0)));
        assert!(!f.contains_point(Vec3::new(0.0, 0.0, -200.0)));
        assert!(!f.contains_point(Vec3::new(0.0, 0.0, -0.05)));
        assert!(!f.contains_point(Vec3::new(100.0, 0.0, -10.0)));
        assert!(!f.contains_point(Vec3::new(0.0, 50.0, -10.0)));
    }

    #[test]
    fn boxes_and_spheres() {
        let f = camera().frustum();
        let inside = Aabb {
            min: Vec3::new(-1.0, -1.0, -11.0),
            max: Vec3::new(1.0, 1.0, -9.0),
        };
        let behind = Aabb {
            min: Vec3::new(-1.0, -1.0, 5.0),
            max: Vec3::new(1.0, 1.0, 7.0),
        };
        let straddling = Aabb {
            min: Vec3::new(-100.0, -1.0, -11.0),
            max: Vec3::new(-5.0, 1.0, -9.0),
        };
        let left_out = Aabb {
            min: Vec3::new(-100.0, -1.0, -11.0),
            max: Vec3::new(-50.0, 1.0, -9.0),
        };
        assert!(f.intersects_aabb(&inside));
        assert!(!f.intersects_aabb(&behind));
        assert!(f.intersects_aabb(&straddling));
        assert!(!f.intersects_aabb(&left_out));
        assert!(f.intersects_sphere(Vec3::new(0.0, 0.0, 1.0), 2.0));
        assert!(!f.intersects_sphere(Vec3::new(0.0, 0.0, 5.0), 2.0));
    }

    #[test]
    fn nearest_depth_is_the_nearest_corner_and_focal_sizes_objects() {
        let cam = Camera::look_at(Vec3::ZERO, Vec3::X, 1.0, 0.1, 100.0, 1.0);
        let b = Aabb {
            min: Vec3::new(10.0, -1.0, -5.0),
            max: Vec3::new(26.0, 1.0, 5.0),
        };
        assert!((cam.nearest_depth(&b) - 10.0).abs() < 1e-5);
        // A box behind the eye has a negative depth.
        let behind = Aabb {
            min: Vec3::new(-6.0, -1.0, -1.0),
            max: Vec3::new(-4.0, 1.0, 1.0),
        };
        assert!((cam.nearest_depth(&behind) + 6.0).abs() < 1e-5);
        // An object as tall as the view volume's half height at depth d, tan(fov/2)·d, spans
        // half of a 180-pixel screen.
        let focal = cam.focal_pixels(180);
        let d = 7.0;
        let half_height = (0.5f32).tan() * d;
        assert!((half_height * focal / d - 90.0).abs() < 1e-3);
    }

    #[test]
    fn nearest_visible_depth_bounds_every_visible_point() {
        let mut rng = crate::rng::Rng::new(17);
        let mut beside = 0;
        for _ in 0..300 {
            let eye = Vec3::new(
                rng.range(-5.0, 5.0),
                rng.range(0.5, 5.0),
                rng.range(-5.0, 5.0),
            );
            let look = Vec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-0.6, 0.2),
                rng.range(-1.0, 1.0),
            );
            let cam = Camera::look_at(
                eye,
                eye + look,
                rng.range(0.5, 1.5),
                0.1,
                200.0,
                rng.range(1.0, 2.0),
            );
            let frustum = cam.frustum();
            let lo = Vec3::new(
                rng.range(-12.0, 8.0),
                rng.range(-1.0, 1.0),
                rng.range(-12.0, 8.0),
            );
            let b = Aabb {
                min: lo,
                max: lo + Vec3::new(rng.range(0.5, 6.0), 1.0, rng.range(0.5, 6.0)),
            };
            let bound = cam.nearest_visible_depth(&b);
            assert!(bound >= cam.nearest_depth(&b));
            beside += usize::from(cam.nearest_depth(&b) < bound);
            for _ in 0..200 {
                let p = b.min
                    + (b.max - b.min) * Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
                if frustum.contains_point(p) {
                    let depth = (p - cam.eye).dot(cam.forward);
                    assert!(
                        depth >= bound - 1e-4,
                        "visible point at depth {depth} < bound {bound}"
                    );
                }
            }
        }
        // The bound is tighter than the nearest corner's depth for many boxes.
        assert!(beside > 30, "{beside}");
    }

    #[test]
    fn around_holds_every_point_and_no_more() {
        assert_eq!(Aabb::around(std::iter::empty()), None);
        let points = [
            Vec3::new(1.0, -2.0, 3.0),
            Vec3::new(-4.0, 5.0, 0.5),
            Vec3::new(2.0, 0.0, -6.0),
        ];
        let b = Aabb::around(points).unwrap();
        assert_eq!(b.min, Vec3::new(-4.0, -2.0, -6.0));
        assert_eq!(b.max, Vec3::new(2.0, 5.0, 3.0));
    }
}
