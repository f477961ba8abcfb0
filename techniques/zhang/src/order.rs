//! Far-to-near order (Sec. 5.4): what blending (Eq. 10) needs, since a translucent texel only
//! shows what was drawn before it.
//!
//! - **Grids** (Sec. 5.4.2): by squared grid offset `Δx² + Δz²` from the camera grid,
//!   largest first, with a quicksort (`sort_unstable`, a pattern-defeating quicksort). A grid
//!   that can hide another lies between it and the camera, so it is no further in either axis
//!   and its squared offset is smaller: the order is exact between grids.
//! - **Sections** (Fig. 17): a grid's position relative to the camera grid, the signs of its
//!   offset `(sx, sz)`, one of nine. A grid in a side or corner section is drawn *line by
//!   line*: for `sz ≠ 0` rows of constant Z, farthest row first (`FORWARD`/`BACKWARD` and the
//!   corners of Table 1, which the thesis also draws along X or Z), for `sz = 0` columns of
//!   constant X, farthest first (`LEFT`/`RIGHT`). Seen from the camera's side, a cell can only
//!   hide cells of farther lines or of its own line, so line order is exact between lines.
//! - **Within a line** the cells go from the far end towards the camera's coordinate along the
//!   line. For billboards of grids two or more away that end is known in advance: in a corner
//!   section the camera is beyond one end; in a side section the line runs across the line of
//!   sight, which crosses a line within the block it aims at, so any walk will do. Their
//!   orders are therefore pre-computed once per section and level, as the thesis does
//!   ([`BlockOrders`]). For the single plants of the eight surrounding grids (Table 1) the
//!   camera can stand right beside a line and look along it: a fixed arrow cannot be
//!   far-to-near for every camera position, so each line of the pre-computed line order is
//!   walked from its far end towards the camera's lattice coordinate ([`line_order`]), which
//!   costs nothing beyond the walk itself.
//! - **The camera grid** (Sec. 5.4.1): its visible plants are quicksorted by squared distance
//!   to the eye, farthest first.
//!
//! The unit tests check all of these exhaustively over camera positions in the camera grid.

use grassbench::glam::{IVec2, Vec2};

/// The section (Fig. 17) of grid `grid` seen from camera grid `camera`: signs of the offset.
pub fn section(grid: IVec2, camera: IVec2) -> IVec2 {
    (grid - camera).signum()
}

/// Index `0..9` of a section.
pub fn section_index(s: IVec2) -> usize {
    ((s.y + 1) * 3 + (s.x + 1)) as usize
}

/// The cells of a `count x count` square (row-major indices `j·count + i`) in far-to-near
/// order for a grid in section `s`, walked line by line and, within a line, from its far end
/// towards `camera` (the camera's position in cell units of this square, any value), written
/// to `out` (cleared first). The centre section (the camera grid itself) falls back to rows.
pub fn line_order(count: u32, s: IVec2, camera: Vec2, out: &mut Vec<u32>) {
    out.clear();
    let n = count as i32;
    // Lines are rows (constant j) unless the grid lies straight along X.
    let rows = s.y != 0 || s.x == 0;
    let (line_sign, along) = if rows {
        (s.y, camera.x)
    } else {
        (s.x, camera.y)
    };
    for l in 0..n {
        // Farthest line first: for a positive sign, the largest index.
        let line = if line_sign > 0 { n - 1 - l } else { l };
        // Walk the line from its far end towards the camera's cell: two pointers.
        let (mut lo, mut hi) = (0, n - 1);
        let at = along - 0.5;
        while lo <= hi {
            let k = if at - lo as f32 >= hi as f32 - at {
                lo += 1;
                lo - 1
            } else {
                hi -= 1;
                hi + 1
            };
            let (i, j) = if rows { (k, line) } else { (line, k) };
            out.push((j * n + i) as u32);
        }
    }
}

/// Pre-computed billboard orders: per level (blocks per side) and section, the blocks of a
/// grid far to near (Sec. 5.4.2, Fig. 16-17).
#[derive(Clone, Debug, Default)]
pub struct BlockOrders {
    /// `orders[level][section_index]`.
    orders: Vec<[Vec<u32>; 9]>,
}

impl BlockOrders {
    /// Orders for grids of `per_side[level]` blocks per side.
    pub fn new(per_side: &[u32]) -> Self {
        let orders = per_side
            .iter()
            .map(|&count| {
                std::array::from_fn(|k| {
                    let s = IVec2::new(k as i32 % 3 - 1, k as i32 / 3 - 1);
                    let mut out = Vec::new();
                    // The camera lies on the grid's near side along each axis where the
                    // section has a sign; along a line straight at it (sign 0) any walk is
                    // far-to-near two grids away (see the module notes): from the middle.
                    let side = |sign: i32| {
                        if sign == 0 {
                            count as f32 * 0.5
                        } else {
                            -sign as f32 * 1e6
                        }
                    };
                    line_order(count, s, Vec2::new(side(s.x), side(s.y)), &mut out);
                    out
                })
            })
            .collect();
        Self { orders }
    }

    /// The blocks of a grid at `level` in section `s`, far to near.
    pub fn get(&self, level: usize, s: IVec2) -> &[u32] {
        self.orders
            .get(level)
            .map_or(&[], |o| o[section_index(s)].as_slice())
    }
}

/// Sorts `grids` (with their offsets from the camera grid) far to near: squared grid offset,
/// largest first (Sec. 5.4.2).
pub fn sort_grids<T>(grids: &mut [T], offset: impl Fn(&T) -> IVec2) {
    grids.sort_unstable_by_key(|g| std::cmp::Reverse(offset(g).length_squared()));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether the segment from `eye` to `target` passes through the open box `[lo, hi]`
    /// (slab test; touching an edge does not count).
    fn segment_hits_box(eye: Vec2, target: Vec2, lo: Vec2, hi: Vec2) -> bool {
        let d = target - eye;
        let (mut t0, mut t1) = (0.0f32, 1.0f32);
        for k in 0..2 {
            let (o, dk, l, h) = (eye[k], d[k], lo[k], hi[k]);
            if dk.abs() < 1e-12 {
                if o <= l || o >= h {
                    return false;
                }
            } else {
                let (a, b) = ((l - o) / dk, (h - o) / dk);
                t0 = t0.max(a.min(b));
                t1 = t1.min(a.max(b));
            }
        }
        t1 - t0 > 1e-6
    }

    /// Camera positions over the camera grid `[0, 1)²` (in grid units), edges included.
    fn eyes() -> impl Iterator<Item = Vec2> {
        (0..=16).flat_map(|a| (0..=16).map(move |b| Vec2::new(a as f32, b as f32) / 16.0 * 0.999))
    }

    /// Panics if, in `order` of cells (`lo`, `hi` boxes), some cell drawn earlier hides the
    /// centre of a cell drawn later from `eye` (the later one would be painted over it).
    fn check(eye: Vec2, cells: &[(Vec2, Vec2)], what: &str) {
        for (a, &(alo, ahi)) in cells.iter().enumerate() {
            for &(blo, bhi) in &cells[a + 1..] {
                let centre = (blo + bhi) * 0.5;
                assert!(
                    !segment_hits_box(eye, centre, alo, ahi),
                    "{what}: from {eye} the cell at {alo}..{ahi}, drawn first, hides {centre}"
                );
            }
        }
    }

    #[test]
    fn grids_sorted_by_squared_offset_are_far_to_near() {
        let camera = IVec2::new(3, 3);
        let mut grids: Vec<IVec2> = (0..49).map(|k| IVec2::new(k % 7, k / 7)).collect();
        sort_grids(&mut grids, |g| *g - camera);
        let cells: Vec<(Vec2, Vec2)> = grids
            .iter()
            .map(|g| (g.as_vec2(), g.as_vec2() + 1.0))
            .collect();
        for eye in eyes() {
            check(eye + camera.as_vec2(), &cells, "grids");
        }
    }

    /// The pre-computed billboard orders of every section, for grids two and three away
    /// (the nearest billboards; farther ones see their lines at shallower angles).
    #[test]
    fn precomputed_billboard_orders_are_far_to_near_in_every_section() {
        let orders = BlockOrders::new(&[8, 4]);
        for level in 0..2 {
            let count = [8, 4][level];
            for gx in -3..=3 {
                for gz in -3..=3 {
                    let g = IVec2::new(gx, gz);
                    if g.abs().max_element() < 2 {
                        continue;
                    }
                    let size = 1.0 / count as f32;
                    let cells: Vec<(Vec2, Vec2)> = orders
                        .get(level, section(g, IVec2::ZERO))
                        .iter()
                        .map(|&b| {
                            let lo = g.as_vec2()
                                + Vec2::new((b % count) as f32, (b / count) as f32) * size;
                            (lo, lo + size)
                        })
                        .collect();
                    assert_eq!(cells.len() as u32, count * count);
                    for eye in eyes() {
                        check(
                            eye,
                            &cells,
                            &format!("billboards of grid {g}, {count} per side"),
                        );
                    }
                }
            }
        }
    }

    /// Table 1: the plants of the eight surrounding grids, as boxes of 0.9 spacings on their
    /// lattice (wider than any blade's footprint at rest), for every camera position in the
    /// camera grid.
    #[test]
    fn surrounding_grid_orders_are_far_to_near_for_every_camera_position() {
        let n = 8u32;
        let spacing = 1.0 / n as f32;
        let mut order = Vec::new();
        for gx in -1..=1 {
            for gz in -1..=1 {
                let g = IVec2::new(gx, gz);
                if g == IVec2::ZERO {
                    continue;
                }
                for eye in eyes() {
                    let local = (eye - g.as_vec2()) / spacing;
                    line_order(n, section(g, IVec2::ZERO), local, &mut order);
                    let mut seen = order.clone();
                    seen.sort_unstable();
                    assert_eq!(seen, (0..n * n).collect::<Vec<_>>());
                    let cells: Vec<(Vec2, Vec2)> = order
                        .iter()
                        .map(|&c| {
                            let centre = g.as_vec2()
                                + (Vec2::new((c % n) as f32, (c / n) as f32) + 0.5) * spacing;
                            (centre - 0.45 * spacing, centre + 0.45 * spacing)
                        })
                        .collect();
                    check(eye, &cells, &format!("plants of grid {g}"));
                }
            }
        }
    }

    /// The fixed arrows of the thesis' Fig. 16 (one in-line direction per section) are not
    /// far-to-near for every camera position: the check finds it (so it can fail).
    #[test]
    fn a_fixed_in_line_order_fails_the_check_beside_the_camera() {
        let n = 8u32;
        let spacing = 1.0 / n as f32;
        let g = IVec2::new(0, 1);
        let mut order = Vec::new();
        // Camera near the grid's border, at the left end of its rows, rows walked left to right
        // (as if the camera were far to the right).
        line_order(
            n,
            section(g, IVec2::ZERO),
            Vec2::new(100.0, -0.1),
            &mut order,
        );
        let eye = Vec2::new(0.02, 0.999);
        let cells: Vec<(Vec2, Vec2)> = order
            .iter()
            .map(|&c| {
                let centre =
                    g.as_vec2() + (Vec2::new((c % n) as f32, (c / n) as f32) + 0.5) * spacing;
                (centre - 0.45 * spacing, centre + 0.45 * spacing)
            })
            .collect();
        let failed = std::panic::catch_unwind(|| check(eye, &cells, "fixed arrows")).is_err();
        assert!(
            failed,
            "the check accepted an order that paints near plants first"
        );
    }
}
