//! Fade transitions between billboards and single plants (Sec. 6.1).
//!
//! The level of detail of Sec. 5.2 changes when the camera crosses a grid border: grids turn
//! from billboards into single plants and back at once. The thesis puts a *transition sphere*
//! of radius `r0` around the camera; when it touches a grid border along X or Z, the grids
//! about to switch are drawn both ways, the fading-in one with alpha `1 − r1/r0` and the
//! fading-out one with `r1/r0`, `r1` the distance from the camera to the border.
//!
//! As written, the fade-in alpha reaches 1 at the border itself, so which side fades depends
//! on where the camera is going (the four cases of Fig. 20); a camera that stops, turns or
//! starts at a border pops. Here the same linear ramp is spread symmetrically over the band of
//! half-width `r0` on both sides of the border: the representation of the other side gets
//! alpha `½·(1 − r1/r0)`, its own `1 − ½·(1 − r1/r0)`; at the border both are ½ from either
//! side, so the picture is continuous for any motion and nothing depends on the previous
//! frame. Near a corner the two axes combine bilinearly: a grid's single-plant alpha is the
//! weighted share of the four camera grids around the corner that would draw it as single
//! plants.

use grassbench::glam::{IVec2, Vec2, Vec3};

use crate::lod::{Level, camera_grid, grid_offset};
use crate::prairie::Layout;

/// The camera grids a frame blends between, with their weights (summing to 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transition {
    /// Candidate camera grids and weights: own, across X, across Z, across both.
    pub cameras: [(IVec2, f32); 4],
}

impl Transition {
    /// No fading: the camera grid only.
    pub fn none(camera: IVec2) -> Self {
        Self {
            cameras: [(camera, 1.0), (camera, 0.0), (camera, 0.0), (camera, 0.0)],
        }
    }

    /// The transition seen from `eye` with a transition sphere of `radius` grid sizes
    /// (0 = no fading).
    pub fn new(layout: &Layout, eye: Vec3, radius: f32) -> Self {
        let camera = camera_grid(layout, eye);
        if radius <= 0.0 {
            return Self::none(camera);
        }
        let local = (Vec2::new(eye.x, eye.z) - layout.origin) / layout.grid_size - camera.as_vec2();
        // Per axis: the nearer border, its side and the weight of the grid beyond it.
        let axis = |t: f32| {
            let (side, r1) = if t < 0.5 { (-1, t) } else { (1, 1.0 - t) };
            (side, 0.5 * (1.0 - r1 / radius).max(0.0))
        };
        let ((sx, wx), (sz, wz)) = (axis(local.x), axis(local.y));
        let (dx, dz) = (IVec2::new(sx, 0), IVec2::new(0, sz));
        Self {
            cameras: [
                (camera, (1.0 - wx) * (1.0 - wz)),
                (camera + dx, wx * (1.0 - wz)),
                (camera + dz, (1.0 - wx) * wz),
                (camera + dx + dz, wx * wz),
            ],
        }
    }

    /// The camera grid the eye stands over.
    pub fn camera(&self) -> IVec2 {
        self.cameras[0].0
    }

    /// Alpha of grid `grid`'s single plants (its billboards get `1 −` it): the weight of the
    /// camera grids that would draw it as single plants.
    pub fn single_alpha(&self, layout: &Layout, grid: u32, lod: bool) -> f32 {
        self.cameras
            .iter()
            .filter(|(c, _)| Level::at(grid_offset(layout, grid, *c), lod) == Level::Single)
            .map(|(_, w)| w)
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout() -> Layout {
        Layout {
            grids: grassbench::glam::UVec2::splat(16),
            per_side: 32,
            grid_size: Vec2::splat(5.0),
            origin: Vec2::splat(-40.0),
            extent: grassbench::glam::UVec2::splat(16 * 32),
            lattice: crate::prairie::Lattice::Thesis,
        }
    }

    /// Grid (gx, gz) as an index.
    fn id(gx: u32, gz: u32) -> u32 {
        gz * 16 + gx
    }

    #[test]
    fn alphas_follow_the_ramp_and_are_continuous_across_a_border() {
        let l = layout();
        // Border between camera grids 7 and 8 along X at x = −40 + 8·5 = 0.
        let at = |x: f32| Transition::new(&l, Vec3::new(x, 1.6, -40.0 + 8.5 * 5.0), 0.25);
        // Grid 9 is two away from grid 7 (billboards) and one from grid 8 (single plants).
        let alpha = |x: f32| at(x).single_alpha(&l, id(9, 8), true);
        assert_eq!(alpha(-2.5), 0.0); // mid-grid, outside the 1.25 m band
        assert_eq!(alpha(2.5), 1.0);
        // r1 = 0.5 m of r0 = 1.25 m: the far side's alpha is ½·(1 − 0.4) = 0.3.
        assert!((alpha(-0.5) - 0.3).abs() < 1e-5, "{}", alpha(-0.5));
        assert!((alpha(0.5) - 0.7).abs() < 1e-5, "{}", alpha(0.5));
        // Continuous at the border, monotonic through the band.
        assert!((alpha(-1e-4) - alpha(1e-4)).abs() < 1e-3);
        let mut last = 0.0;
        for k in 0..=100 {
            let a = alpha(-2.0 + 4.0 * k as f32 / 100.0);
            assert!(a >= last - 1e-6 && (0.0..=1.0).contains(&a));
            last = a;
        }
        // Grids that keep their level do not fade; no radius, no fade.
        assert_eq!(at(-0.5).single_alpha(&l, id(8, 8), true), 1.0);
        assert_eq!(at(-0.5).single_alpha(&l, id(12, 8), true), 0.0);
        let off = Transition::new(&l, Vec3::new(-0.5, 1.6, 2.5), 0.0);
        assert_eq!(off.single_alpha(&l, id(9, 8), true), 0.0);
        // Without LOD everything is single plants.
        assert_eq!(at(-0.5).single_alpha(&l, id(12, 8), false), 1.0);
    }

    #[test]
    fn weights_sum_to_one_near_a_corner() {
        let l = layout();
        let t = Transition::new(&l, Vec3::new(0.3, 1.0, 0.4), 0.25);
        let sum: f32 = t.cameras.iter().map(|(_, w)| w).sum();
        assert!((sum - 1.0).abs() < 1e-6);
        assert!(t.cameras.iter().all(|(_, w)| *w > 0.0));
        assert_eq!(t.camera(), IVec2::new(8, 8));
    }
}
