//! The level-of-detail choice (Sec. 5.2) and the billboard sizes of Sec. 4.1.
//!
//! The *camera grid* is the grass grid the eye stands over; the *grid offset* `g` of another
//! grid is the larger of its X and Z distances from it, in grids. The camera grid and its eight
//! neighbours (`g ≤ 1`) draw single plants; every other grid draws billboards of length
//! `l' = l·2^⌊log2 g⌋ + 1` plants (Eq. 8, `l = 2`), `n' = ⌈(n−1)/(l'−1)⌉` of them per grid
//! side (Eq. 9), the last of a row shorter.

use grassbench::glam::{IVec2, Vec2, Vec3};

use crate::prairie::Layout;

/// The thesis' default billboard length `l` of Eq. (8).
pub const DEFAULT_LENGTH: u32 = 2;

/// Billboard length `l'` (plants per billboard side, both ends included) of a grid `g` grids
/// away from the camera grid: `l' = l·2^⌊log2 g⌋ + 1`, Eq. (8). `g = 0` counts as 1.
pub fn billboard_length(l: u32, g: u32) -> u32 {
    // ⌊log2 g⌋ by the bit position of the highest set bit, as the thesis suggests.
    l * (1 << g.max(1).ilog2()) + 1
}

/// Billboards per grid side `n' = ⌈(n−1)/(l'−1)⌉` for `n` plants per side, Eq. (9).
pub fn billboards_per_side(n: u32, length: u32) -> u32 {
    (n.saturating_sub(1))
        .div_ceil(length.saturating_sub(1).max(1))
        .max(1)
}

/// How a grass grid is drawn this frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    /// Every plant individually (the camera grid and its neighbours, Sec. 5.2).
    Single,
    /// Billboards of `step = l' − 1` lattice spacings (Eq. 8).
    Billboard {
        /// Lattice spacings between a billboard's first and last plant, `l' − 1`.
        step: u32,
    },
}

impl Level {
    /// The level of a grid at offset `g`; `lod = false` draws single plants everywhere.
    pub fn at(g: u32, lod: bool) -> Self {
        if !lod || g <= 1 {
            Self::Single
        } else {
            Self::Billboard {
                step: billboard_length(DEFAULT_LENGTH, g) - 1,
            }
        }
    }
}

/// The grid `(gx, gz)` over which `eye` stands, in grid units; outside the prairie it lies
/// beyond `0..grids` (every grid is then at least one away and may be drawn as billboards).
pub fn camera_grid(layout: &Layout, eye: Vec3) -> IVec2 {
    let cell = (Vec2::new(eye.x, eye.z) - layout.origin) / layout.grid_size;
    IVec2::new(cell.x.floor() as i32, cell.y.floor() as i32)
}

/// Grid offset `g = max(|Δx|, |Δz|)` of grid `grid` (index `gz·grids.x + gx`) from `camera`.
pub fn grid_offset(layout: &Layout, grid: u32, camera: IVec2) -> u32 {
    let g = grid_coords(layout, grid);
    (g - camera).abs().max_element() as u32
}

/// `(gx, gz)` of grid index `grid`.
pub fn grid_coords(layout: &Layout, grid: u32) -> IVec2 {
    let columns = layout.grids.x.max(1);
    IVec2::new((grid % columns) as i32, (grid / columns) as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The worked examples of Sec. 4.1 (32 plants per grid side, camera in grid [2, 2]).
    #[test]
    fn equations_8_and_9_reproduce_the_worked_examples() {
        // Grid [5, 4]: g = max(5−2, 4−2) = 3 → l' = 5, n' = 8, 64 billboards.
        let g = 3;
        let l = billboard_length(DEFAULT_LENGTH, g);
        assert_eq!(l, 5);
        assert_eq!(billboards_per_side(32, l), 8);
        assert_eq!(billboards_per_side(32, l).pow(2), 64);
        // Grid [6, 7]: g = 5 → l' = 9, n' = 4, 16 billboards.
        let l = billboard_length(DEFAULT_LENGTH, 5);
        assert_eq!(l, 9);
        assert_eq!(billboards_per_side(32, l), 4);
        // Sec. 5.2 / Fig. 13: lengths 5, 9 and 17 (g in 2..4, 4..8, 8..16), "4 billboards
        // with length of 17".
        assert_eq!(billboard_length(DEFAULT_LENGTH, 2), 5);
        assert_eq!(billboard_length(DEFAULT_LENGTH, 7), 9);
        assert_eq!(billboard_length(DEFAULT_LENGTH, 8), 17);
        assert_eq!(billboards_per_side(32, 17).pow(2), 4);
        // "the range from 2^(n−1) to 2^n − 1 ... the same length".
        for g in 4..8 {
            assert_eq!(billboard_length(DEFAULT_LENGTH, g), 9);
        }
    }

    #[test]
    fn near_grids_are_single_plants_and_offsets_are_chebyshev() {
        let layout = Layout {
            grids: grassbench::glam::UVec2::splat(16),
            per_side: 32,
            grid_size: Vec2::splat(5.0),
            origin: Vec2::splat(-40.0),
            extent: grassbench::glam::UVec2::splat(16 * 32),
            lattice: crate::prairie::Lattice::Thesis,
        };
        // Camera grid (7, 8), as in Fig. 13.
        let cam = camera_grid(
            &layout,
            Vec3::new(-40.0 + 7.5 * 5.0, 1.6, -40.0 + 8.2 * 5.0),
        );
        assert_eq!(cam, IVec2::new(7, 8));
        let offset = |gx: u32, gz: u32| grid_offset(&layout, gz * 16 + gx, cam);
        assert_eq!(offset(7, 8), 0);
        assert_eq!(offset(6, 9), 1);
        assert_eq!(offset(1, 9), 6);
        assert_eq!(Level::at(1, true), Level::Single);
        assert_eq!(Level::at(2, true), Level::Billboard { step: 4 });
        assert_eq!(Level::at(6, true), Level::Billboard { step: 8 });
        assert_eq!(Level::at(6, false), Level::Single);
        let singles = (0..256u32)
            .filter(|&k| Level::at(grid_offset(&layout, k, cam), true) == Level::Single)
            .count();
        assert_eq!(singles, 9);
    }
}
