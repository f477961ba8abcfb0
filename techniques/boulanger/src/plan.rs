//! The frame plan (Boulanger Sec. 4.1-4.2): what `update` decides each frame from the quadtree
//! walk, for `prepare` to upload and `encode` to draw. Rebuilt every frame in the same vectors,
//! so a frame allocates little once the field has been seen.
//!
//! Cells within `max_geom` get geometry: per visible block of the patch, the blades whose
//! thresholds can pass there, a contiguous range since each block is sorted by threshold;
//! [`crate::cells`] pages them into instanced draws. Cells where geometry's weight is under 1
//! get a horizontal slice quad, those within `max_btf` the vertical slices too, and macro-cells
//! farther away one horizontal slice quad, tessellated to follow the ground. Everything is drawn
//! far to near.

use std::ops::Range;

use glam::{Vec2, Vec3};
use grassbench::camera::{Aabb, Camera};

use crate::cells::{Page, Paging};
use crate::lod;
use crate::patch::Orientation;
use crate::quadtree::{self, Selected, Selection, Walk};
use crate::shader::{CellRecord, SliceQuad};
use crate::tiling::{BLOCKS, Tiling};

/// Blades each of Sec. 3.1's three levels drew or stood for in a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BandBlades {
    /// Blades drawn as geometry.
    pub geometry: u64,
    /// Blades represented by vertical (volume) slices.
    pub vertical_slices: u64,
    /// Blades represented by the horizontal slice.
    pub horizontal_slices: u64,
}

/// Tessellations of slice quads (quads per side), one draw each.
const TESS_LEVELS: [u32; 4] = [1, 2, 4, 8];

/// A cell drawn with geometry this frame: its record and one blade range per visible block.
#[derive(Clone, Debug)]
pub struct GeometryCell {
    /// The cell as the shader reads it.
    pub record: CellRecord,
    /// The blades to draw, one range of the patch per visible block.
    pub ranges: Vec<Range<u32>>,
    /// Distance from the eye to the cell, m.
    pub near: f32,
}

/// One frame's draws, refilled by [`FramePlan::update`] (update → prepare → encode).
#[derive(Default)]
pub struct FramePlan {
    /// The quadtree walk's output (kept for its allocations).
    selection: Selection,
    /// Cells with geometric blades, far to near.
    pub geometry: Vec<GeometryCell>,
    /// Horizontal slice quads, by tessellation.
    pub slice_quads: Vec<SliceQuad>,
    /// Cells with vertical slices with their nearest distance (sorted far to near).
    vslice_cells: Vec<(CellRecord, f32)>,
    /// Cells with vertical slices, far to near: the instances of their draw.
    pub vslice_records: Vec<CellRecord>,
    /// Per tessellation of `slice_quads` (quads per side), its instance range.
    pub quad_groups: Vec<(u32, Range<u32>)>,
    /// The blade draws, per page of geometry cells.
    pub pages: Vec<Page>,
    /// Blades drawn by each representation.
    pub lod_blades: BandBlades,
}

impl FramePlan {
    /// Walks the quadtree from `camera` and refills the plan; `paging` cuts the geometry cells
    /// into draws.
    pub fn update(&mut self, tiling: &Tiling, camera: &Camera, paging: &Paging) {
        let walk = Walk {
            frustum: camera.frustum(),
            eye: camera.eye,
            // Cells (not macro-cells) wherever geometry or vertical slices may be drawn.
            cell_distance: tiling.lod.max_geom.max(tiling.lod.max_btf),
            macro_factor: tiling.macro_factor,
        };
        let mut selection = std::mem::take(&mut self.selection);
        tiling.tree.select(&walk, &mut selection);
        self.geometry.clear();
        self.slice_quads.clear();
        self.vslice_cells.clear();
        let grid = *tiling.tree.grid();
        let per_patch = f64::from(tiling.blades_per_patch());
        let (omega, lod) = (tiling.omega, tiling.lod);
        let mut geometry_blades = 0u64;
        let mut slice_blades = 0.0f64;
        let mut vertical_blades = 0.0f64;
        for s in &selection.cells {
            let (i, j) = (s.rect.i0, s.rect.j0);
            if s.near < lod.max_geom {
                let centre = grid.cell_min(i, j) + Vec2::splat(0.5 * grid.cell);
                let orientation = Orientation::of_cell(tiling.seed, i, j);
                let mut ranges = Vec::new();
                for k in 0..BLOCKS * BLOCKS {
                    // The block where this cell's mirror puts it, with the blades' reach.
                    let (c, half) = tiling.patch.block_center(k);
                    let c = centre + orientation.apply(c);
                    let reach = half + tiling.overhang;
                    let ground = Aabb {
                        min: Vec3::new(c.x - half, s.ground_y[0], c.y - half),
                        max: Vec3::new(c.x + half, s.ground_y[1], c.y + half),
                    };
                    let bounds = Aabb {
                        min: Vec3::new(c.x - reach, s.ground_y[0], c.y - reach),
                        max: Vec3::new(c.x + reach, s.ground_y[1] + tiling.reach_up, c.y + reach),
                    };
                    let near = quadtree::distance_to_box(camera.eye, &ground);
                    if near >= lod.max_geom || !walk.frustum.intersects_aabb(&bounds) {
                        continue;
                    }
                    // The blades Eq. 5 can give visible opacity here: normalised thresholds
                    // from `geometry_min_t` of the largest weight in the block, under the
                    // density.
                    // A cell wholly at full weight draws whole blocks (the shader still
                    // tests each threshold), so runs of such cells merge into one draw.
                    let t_min =
                        lod::geometry_min_t(lod.w_g(near), omega, tiling.alpha_floor).max(0.0);
                    let whole = s.far <= lod.min_geom;
                    let lo = if whole {
                        0.0
                    } else {
                        (t_min * s.density_range[0] - 1e-4).max(0.0)
                    };
                    let hi = if whole || s.density_range[1] >= 1.0 {
                        f32::INFINITY
                    } else {
                        s.density_range[1] + 1e-4
                    };
                    let r = tiling.patch.threshold_range(k, lo, hi);
                    if !r.is_empty() {
                        geometry_blades += u64::from(r.end - r.start);
                        ranges.push(r);
                    }
                }
                if !ranges.is_empty() {
                    let signs = orientation.signs();
                    self.geometry.push(GeometryCell {
                        record: CellRecord {
                            center_signs: [centre.x, centre.y, signs.x, signs.y],
                            mode: [0.0; 4],
                        },
                        ranges,
                        near: s.near,
                    });
                }
            }
            if s.far > lod.min_geom {
                self.slice_quads.push(slice_quad(tiling, s, 1));
                let d = 0.5 * (s.near + s.far);
                slice_blades += f64::from(s.density) * per_patch * f64::from(lod.w_hs(d));
                // The vertical slices where Eq. 3 can give them a share (Sec. 3.3).
                if s.near < lod.max_btf {
                    let centre = grid.cell_min(i, j) + Vec2::splat(0.5 * grid.cell);
                    let signs = Orientation::of_cell(tiling.seed, i, j).signs();
                    self.vslice_cells.push((
                        CellRecord {
                            center_signs: [centre.x, centre.y, signs.x, signs.y],
                            mode: [0.0; 4],
                        },
                        s.near,
                    ));
                    vertical_blades += f64::from(s.density) * per_patch * f64::from(lod.w_vs(d));
                }
            }
        }
        for s in &selection.macro_cells {
            let side = s.rect.ni.max(s.rect.nj).next_power_of_two();
            self.slice_quads.push(slice_quad(tiling, s, side.min(8)));
            slice_blades += f64::from(s.density) * per_patch;
        }
        self.selection = selection;
        // Far to near. Blades are not sorted (Sec. 4.2), but cells are, for free: Eq. 5 leaves
        // many blades of the transition semi-transparent, and with cells drawn near to far
        // (18 % faster here, thanks to early depth rejection) faint near blades hid whole
        // cells drawn after them, which showed as cell-sized blotches.
        self.geometry.sort_by(|a, b| b.near.total_cmp(&a.near));
        self.vslice_cells.sort_by(|a, b| b.1.total_cmp(&a.1));
        self.vslice_records.clear();
        self.vslice_records
            .extend(self.vslice_cells.iter().map(|c| c.0));
        self.pages = paging.draws(self.geometry.iter().map(|c| c.ranges.as_slice()));
        self.slice_quads
            .sort_by(|a, b| a.tess[0].total_cmp(&b.tess[0]));
        self.quad_groups.clear();
        let mut start = 0u32;
        for tess in TESS_LEVELS {
            let n = self
                .slice_quads
                .iter()
                .filter(|q| q.tess[0] as u32 == tess)
                .count() as u32;
            if n > 0 {
                self.quad_groups.push((tess, start..start + n));
            }
            start += n;
        }
        self.lod_blades = BandBlades {
            geometry: geometry_blades,
            vertical_slices: vertical_blades.round() as u64,
            horizontal_slices: slice_blades.round() as u64,
        };
    }
}

/// The horizontal slice quad over `s`'s cells, `tess` quads a side.
fn slice_quad(tiling: &Tiling, s: &Selected, tess: u32) -> SliceQuad {
    let grid = tiling.tree.grid();
    let min = grid.cell_min(s.rect.i0, s.rect.j0);
    SliceQuad {
        rect: [
            min.x,
            min.y,
            s.rect.ni as f32 * grid.cell,
            s.rect.nj as f32 * grid.cell,
        ],
        cells: [
            s.rect.i0 as f32,
            s.rect.j0 as f32,
            s.rect.ni as f32,
            s.rect.nj as f32,
        ],
        tess: [tess as f32, 0.0, 0.0, 0.0],
    }
}
