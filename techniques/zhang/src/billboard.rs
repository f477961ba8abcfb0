//! Billboards of far plants (Sec. 4.1-4.2, 5.5.2).
//!
//! A grid drawn at billboard step `s = l' − 1` (Eq. 8) is cut into `n' x n'` blocks of
//! `s x s` lattice spacings (Eq. 9; the last block of a row ends at the grid's last plant, so
//! it is shorter). Each block's billboard is six rectangles ("wings") joined at a vertical
//! middle line standing on the block's centre plant: two along X to the middles of the left
//! and right edges, two along Z to the middles of the near and far edges, and two along the
//! diagonal to two opposite corners (Fig. 10, 12). Every wing corner is a lattice point, so,
//! as Sec. 4.2 asks, a wing is "the segment points of two single plants" joined: its bottom
//! vertices are the two plants' roots, its top vertices their top points, animated like any
//! blade (only bottom and top: the middle segment points are not needed far away).
//!
//! Those plants are the *anchors*: the lattice points whose X and Z indices are multiples of
//! `s/2` (or the grid's last index). The anchors of step `2s` are a subset of those of `s`, so
//! each grid's anchors are stored coarsest first and a grid at step `s` animates a prefix of
//! them. Anchors are planted with [`crate::prairie::candidate`] whether their blade grows or
//! not (a thinned-out plant still moves the billboard that stands for its neighbours).
//!
//! Gaps (Sec. 5.5.2): a wing is dropped when the covering map is not grass at its two ends or
//! its middle, so gaps, trees and stones "separate the billboard into several parts". The
//! density map thins the texture's blades with the shared threshold rule (see
//! [`crate::billboard_texture`]).

use std::ops::Range;

use grassbench::glam::{Vec2, Vec3};
use grassbench::grass::GrassConfig;
use grassbench::rng::hash_f32;
use grassbench::terrain::{Terrain, covering};

use crate::billboard_texture::SPAN;
use crate::params::Params;
use crate::prairie::{Layout, Planted, candidate};
use crate::wing_trim::{Cut, Skyline};

/// One wing (rectangle) of a billboard: anchor indices and texture span.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wing {
    /// Anchor at the middle line.
    pub centre: u32,
    /// Anchor at the outer edge.
    pub outer: u32,
    /// Texture `u` at the middle line and at the outer edge (repeats every [`SPAN`] spacings).
    pub u: [f32; 2],
    /// Mean of the density map over the wing (texture blades above it are not drawn).
    pub density: f32,
    /// The part drawn ([`crate::wing_trim`]); `None` when it can show nothing.
    pub cut: Option<Cut>,
}

/// Wings and anchors of one grid at one step.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GridLevel {
    /// Anchors animated at this step: a prefix of the grid's anchor range.
    pub anchors: Range<u32>,
    /// Its wings.
    pub wings: Vec<Wing>,
    /// Billboards with at least one wing.
    pub billboards: u32,
    /// Wing range of each billboard block, row-major (`bz·n' + bx`), for the pre-computed
    /// far-to-near orders of Sec. 5.4.2.
    pub blocks: Vec<Range<u32>>,
}

/// Every grid's billboards at every step.
#[derive(Clone, Debug)]
pub struct Billboards {
    /// The anchor plants, grid by grid, coarsest class first within a grid.
    pub anchors: Vec<Planted>,
    /// Per grid index (`gz·grids + gx`), per level `k` (step `4·2^k`).
    pub grids: Vec<Vec<GridLevel>>,
    /// Steps of the levels (`4, 8, ...` up to the power of two covering a grid).
    pub steps: Vec<u32>,
}

/// Whether lattice index `i` (of `0..n`) belongs to the anchors of half-step `t`.
fn on(i: u32, t: u32, n: u32) -> bool {
    i.is_multiple_of(t) || i + 1 == n
}

/// The billboard steps a prairie of `n` plants per grid side and `grids` grids per side uses:
/// `4, 8, ...` (Eq. 8 for `g = 2, 4, ...`), the last one the first to span a whole grid.
pub fn steps(n: u32, grids: u32) -> Vec<u32> {
    let most = crate::lod::billboard_length(crate::lod::DEFAULT_LENGTH, grids.max(2) - 1) - 1;
    let cap = n.saturating_sub(1).next_power_of_two().max(4);
    let mut out = vec![4];
    while let Some(&s) = out.last() {
        if s >= most.min(cap) {
            break;
        }
        out.push(2 * s);
    }
    out
}

impl Billboards {
    /// Plants the anchors and cuts every grid into billboards at every step.
    pub fn new(
        layout: &Layout,
        params: &Params,
        grass: &GrassConfig,
        terrain: &Terrain,
        seed: u64,
    ) -> Self {
        let n = layout.per_side;
        let steps = steps(n, layout.grids);
        let mut anchors = Vec::new();
        let mut grids = Vec::with_capacity((layout.grids * layout.grids) as usize);
        let spacing = layout.spacing().x.min(layout.spacing().y);
        let grass_at = |p: Vec3| {
            let xz = Vec2::new(p.x, p.z);
            terrain.contains(xz) && terrain.covering_at(xz) == covering::GRASS
        };
        for grid in 0..layout.grids * layout.grids {
            let (gx, gz) = (grid % layout.grids, grid / layout.grids);
            // Anchor classes: the largest half-step t (2, 4, ...) whose lattice holds the point.
            let halves: Vec<u32> = steps.iter().map(|s| s / 2).collect();
            let class = |i: u32, j: u32| halves.iter().rposition(|&t| on(i, t, n) && on(j, t, n));
            let mut points: Vec<(usize, u32, u32)> = (0..n * n)
                .filter_map(|k| {
                    let (i, j) = (k % n, k / n);
                    class(i, j).map(|c| (c, i, j))
                })
                .collect();
            points.sort_by_key(|&(c, i, j)| (std::cmp::Reverse(c), j, i));
            let first = anchors.len() as u32;
            let mut local = vec![u32::MAX; (n * n) as usize];
            for &(_, i, j) in &points {
                local[(j * n + i) as usize] = anchors.len() as u32;
                let mut plant = candidate(
                    layout,
                    params,
                    grass,
                    terrain,
                    seed,
                    grid,
                    (gx * n + i, gz * n + j),
                )
                .plant;
                plant.flower = None;
                anchors.push(plant);
            }
            let levels = steps
                .iter()
                .enumerate()
                .map(|(level, &s)| {
                    let needed = points.iter().filter(|&&(c, ..)| c >= level).count() as u32;
                    let mut wings = Vec::new();
                    let mut billboards = 0;
                    let mut block_ranges = Vec::new();
                    let blocks = crate::lod::billboards_per_side(n, s + 1);
                    for bz in 0..blocks {
                        for bx in 0..blocks {
                            let (i0, j0) = (bx * s, bz * s);
                            let (i1, j1) = ((i0 + s).min(n - 1), (j0 + s).min(n - 1));
                            let (ci, cj) = ((i0 + s / 2).min(n - 1), (j0 + s / 2).min(n - 1));
                            let at = |i: u32, j: u32| local[(j * n + i) as usize];
                            let centre = at(ci, cj);
                            let before = wings.len();
                            for (oi, oj) in
                                [(i0, cj), (i1, cj), (ci, j0), (ci, j1), (i0, j0), (i1, j1)]
                            {
                                if (oi, oj) == (ci, cj) {
                                    continue;
                                }
                                let outer = at(oi, oj);
                                let (a, b) =
                                    (anchors[centre as usize].root, anchors[outer as usize].root);
                                let mid = (a + b) * 0.5;
                                if !(grass_at(a) && grass_at(b) && grass_at(mid)) {
                                    continue;
                                }
                                let density = [a, mid, b]
                                    .iter()
                                    .map(|p| terrain.density_at(Vec2::new(p.x, p.z)))
                                    .sum::<f32>()
                                    / 3.0;
                                let length = Vec2::new(b.x - a.x, b.z - a.z).length();
                                let u0 = hash_f32(
                                    seed,
                                    &[i64::from(grid), i64::from(level as u32), i64::from(outer)],
                                );
                                wings.push(Wing {
                                    centre,
                                    outer,
                                    u: [u0, u0 + length / (SPAN * spacing)],
                                    density,
                                    cut: Some(Cut::WHOLE),
                                });
                            }
                            billboards += u32::from(wings.len() > before);
                            block_ranges.push(before as u32..wings.len() as u32);
                        }
                    }
                    GridLevel {
                        anchors: first..first + needed,
                        wings,
                        billboards,
                        blocks: block_ranges,
                    }
                })
                .collect();
            grids.push(levels);
        }
        Self {
            anchors,
            grids,
            steps,
        }
    }

    /// No billboards (level of detail off).
    pub fn empty() -> Self {
        Self {
            anchors: Vec::new(),
            grids: Vec::new(),
            steps: Vec::new(),
        }
    }

    /// Level index of billboard step `step` (the nearest coarser one the prairie has).
    pub fn level(&self, step: u32) -> usize {
        self.steps
            .iter()
            .position(|&s| s >= step)
            .unwrap_or(self.steps.len().saturating_sub(1))
    }

    /// Billboards per grid side at each level (Eq. 9).
    pub fn per_side(&self, n: u32) -> Vec<u32> {
        self.steps
            .iter()
            .map(|&s| crate::lod::billboards_per_side(n, s + 1))
            .collect()
    }

    /// Cuts every wing down to the texels it can show ([`crate::wing_trim`]).
    pub fn cut_wings(&mut self, skyline: &Skyline) {
        for levels in &mut self.grids {
            for (k, level) in levels.iter_mut().enumerate() {
                for w in &mut level.wings {
                    w.cut = skyline.cut(k as u32, w.u, w.density);
                }
            }
        }
    }

    /// Wings of every grid at its finest level (an upper bound on the wings of a frame).
    pub fn max_wings(&self) -> usize {
        self.grids
            .iter()
            .map(|levels| levels.first().map_or(0, |l| l.wings.len()))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn prairie(grids: u32, n: u32) -> (Layout, Billboards) {
        let terrain = Terrain::flat(Vec2::new(80.0, 80.0));
        let params = Params {
            grids,
            blades_per_side: n,
            ..Params::default()
        };
        let layout = Layout::new(&params, &terrain);
        let b = Billboards::new(&layout, &params, &GrassConfig::default(), &terrain, 7);
        (layout, b)
    }

    #[test]
    fn steps_follow_equation_8_up_to_a_whole_grid() {
        assert_eq!(steps(32, 16), vec![4, 8, 16]); // g ≤ 15: l' = 5, 9, 17
        assert_eq!(steps(32, 64), vec![4, 8, 16, 32]);
        assert_eq!(steps(6, 16), vec![4, 8]);
    }

    #[test]
    fn billboards_per_grid_match_equation_9_and_anchors_nest() {
        let (_, b) = prairie(8, 32);
        for levels in &b.grids {
            // Step 4 (l' = 5): 8 x 8 billboards; step 8 (l' = 9): 4 x 4 (Sec. 4.1). Six wings
            // each on flat grass without gaps.
            assert_eq!(levels[0].wings.len(), 64 * 6);
            assert_eq!(levels[1].wings.len(), 16 * 6);
            // 17 x 17 anchors (multiples of 2 and index 31) for step 4, 9 x 9 for step 8.
            assert_eq!(levels[0].anchors.len(), 17 * 17);
            assert_eq!(levels[1].anchors.len(), 9 * 9);
            for (k, l) in levels.iter().enumerate() {
                assert_eq!(l.anchors.start, levels[0].anchors.start);
                for w in &l.wings {
                    assert!(l.anchors.contains(&w.centre) && l.anchors.contains(&w.outer));
                    assert!(
                        w.u[1] > w.u[0] && (w.density - 1.0).abs() < 1e-6,
                        "level {k}"
                    );
                }
            }
        }
    }

    #[test]
    fn wings_join_lattice_plants_of_their_grid() {
        let (layout, b) = prairie(8, 32);
        let size = layout.grid_size;
        for (grid, levels) in b.grids.iter().enumerate() {
            let min = layout.origin
                + Vec2::new((grid as u32 % 8) as f32, (grid as u32 / 8) as f32) * size;
            for w in &levels[1].wings {
                for a in [w.centre, w.outer] {
                    let p = b.anchors[a as usize];
                    assert_eq!(p.grid as usize, grid);
                    let xz = Vec2::new(p.root.x, p.root.z) - min;
                    assert!(xz.cmpge(Vec2::ZERO).all() && xz.cmple(size).all(), "{xz}");
                }
            }
        }
    }
}
