//! The shadow mask (Boulanger Sec. 3.5, Fig. 17): blade-to-blade shadows without projecting
//! neighbours onto each blade.
//!
//! The neighbourhood of a blade is approximated by one grayscale image mapped on a vertical
//! cylinder around it, its origin turned to the blade's inclination direction. The image is
//! a slice of the patch seen from the side with blades black on white (here: the coverage of a
//! one-layer bake, [`crate::btf`], of a slab as thick as the cylinder's diameter through the
//! patch centre; shadow = 1 − coverage). The cylinder's circumference is the patch side, so the
//! slab's width wraps once around it. For a point of a blade the ray towards the light is
//! intersected with the cylinder (`blade_shadow` in `shaders/grass.wgsl`); where it leaves
//! through the side below the top, the mask's bilinear lookup there (anti-aliased, as the paper
//! says) scales the light. The geometric blades use it for the sun and the point light, and
//! the BTF bake for its five light directions, so the slices carry the same shadows (Sec. 3.5:
//! "the BTF images are generated while using the shadow mask algorithm").

use std::ops::Range;

use crate::patch::PatchBlade;
use crate::shader::CellRecord;
use crate::vertical::box_layer;
use glam::Vec2;

/// Mask texels around the cylinder.
pub const WIDTH: u32 = 128;
/// Mask texels up the cylinder (the bake's height).
pub const HEIGHT: u32 = 64;

/// Radius of the cylinder: its circumference is the patch side.
pub fn radius(patch_size: f32) -> f32 {
    patch_size / std::f32::consts::TAU
}

/// The mask's one layer for [`crate::btf::bake`]: the nine cells with the mask's camera
/// (`mode.y = 3`: across x, a slab of half-thickness [`radius`] through the centre) and the
/// blades reaching that slab.
pub fn bake_layer(
    patch_size: f32,
    blades: &[PatchBlade],
    gravity: f32,
) -> (Vec<CellRecord>, Vec<u32>, Range<u32>) {
    let (r, side) = (radius(patch_size), 0.5 * patch_size);
    box_layer(
        patch_size,
        blades,
        gravity,
        [1.0, 3.0, 0.0, 1.0],
        Vec2::new(r, side),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_slab_holds_the_blades_rooted_in_it_and_wraps_the_patch() {
        let size = 0.5;
        assert!((std::f32::consts::TAU * radius(size) - size).abs() < 1e-6);
        let blade = |x: f32, z: f32| PatchBlade {
            root: [x, z],
            azimuth: 0.0,
            tilt: 0.0,
            height: 0.1,
            width: 0.01,
            variation: 0.0,
            threshold: 0.5,
        };
        let blades = [blade(0.0, 0.0), blade(0.2, 0.0), blade(-0.05, 0.24)];
        let (cells, refs, range) = bake_layer(size, &blades, 0.6);
        assert_eq!(cells.len(), 9);
        assert_eq!(range, 0..refs.len() as u32);
        // Centre cell (4): blades 0 and 2 are within the radius (8 cm), blade 1 is not.
        assert!(refs.contains(&(4 * 3)));
        assert!(!refs.contains(&(4 * 3 + 1)));
        assert!(refs.contains(&(4 * 3 + 2)));
    }
}
