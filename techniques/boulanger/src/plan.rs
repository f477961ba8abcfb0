//! The frame plan (Boulanger Sec. 4.1-4.2): what `update` decides each frame from the quadtree
//! walk, for `prepare` to upload and `encode` to draw. Rebuilt every frame in the same vectors,
//! so a frame allocates little once the field has been seen.
//!
//! Cells within `max_geom` get geometry: per visible block of the patch, the blades whose
//! thresholds can pass there, a contiguous range since each block is sorted by threshold;
//! [`crate::cells`] pages them into instanced draws. Cells where geometry's weight is under 1
//! get a horizontal slice quad, those within `max_btf` the vertical slices too, and macro-cells
//! farther away one horizontal slice quad, tessellated to follow the ground. Everything is drawn
//! far to near. Without transitions (`transitions = false`) each cell instead gets one level by
//! the distance to its centre ([`lod::LodDistances::abrupt_level`]) and its draws carry fixed
//! weights ([`lod::CellWeights`]).
//!
//! ## Counting each blade once
//! The counts are of blades that grow ([`crate::population`]): a cell's copy of the patch
//! holds `n_c` of them, and a macro-cell its cells' sum. Geometry counts, as
//! [`grassbench::TechniqueStats::blades_drawn`], the growing blades of the ranges it submits
//! (whatever opacity Eq. 5 gives them there). A cell with slices counts, as
//! `blades_represented`, the rest of its `n_c`: the slices stand for every growing blade whose
//! geometry was not submitted, once however many of them show it (the vertical slices show
//! blades the horizontal slice under them shows too). In a transition a blade submitted as
//! geometry is therefore counted as drawn only, though the slices show Eq. 5's complementary
//! share of it: every growing blade of a selected cell is counted exactly once, on the side of
//! its geometry when that was submitted. A cell drawn only as geometry (nearer than `min_geom`
//! throughout, or switched to geometry without transitions) counts the growing blades of the
//! blocks it submits, so blocks culled out of view count nothing. Nothing grows on an empty
//! patch (`grass.density = 0`): the plan is then empty, and nothing at all is drawn.

use std::ops::Range;

use glam::{Vec2, Vec3};
use grassbench::camera::{Aabb, Camera};
use grassbench::terrain::Terrain;

use crate::cells::{Page, Paging};
use crate::lod::{self, CellWeights};
use crate::patch::Orientation;
use crate::quadtree::{self, Selected, Selection, Walk};
use crate::shader::{CellRecord, SliceQuad};
use crate::tiling::{BLOCKS, Tiling};

/// Blades each of Sec. 3.1's three levels drew or stood for in a frame, each growing blade once
/// in `geometry + horizontal_slices` (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BandBlades {
    /// Growing blades whose geometry was submitted.
    pub geometry: u64,
    /// Of the blades the slices stand for, those the vertical slices show too (weighted by
    /// Eq. 3's far fade at the cell's middle distance).
    pub vertical_slices: u64,
    /// Blades the slices stand for: under every cell with slices and every macro-cell lies a
    /// horizontal slice, so it stands for all of them.
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
    /// into draws, `terrain` (the tiling's) tells which blades grow for the counts.
    pub fn update(&mut self, tiling: &Tiling, terrain: &Terrain, camera: &Camera, paging: &Paging) {
        self.geometry.clear();
        self.slice_quads.clear();
        self.vslice_cells.clear();
        self.vslice_records.clear();
        self.pages.clear();
        self.quad_groups.clear();
        self.lod_blades = BandBlades::default();
        if tiling.patch.blades.is_empty() {
            // No grass (`grass.density = 0`): no geometry, no slice, nothing.
            return;
        }
        let walk = Walk {
            frustum: camera.frustum(),
            eye: camera.eye,
            // Cells (not macro-cells) wherever geometry or vertical slices may be drawn.
            cell_distance: tiling.lod.max_geom.max(tiling.lod.max_btf),
            macro_factor: tiling.macro_factor,
        };
        let mut selection = std::mem::take(&mut self.selection);
        tiling.tree.select(&walk, &mut selection);
        let grid = *tiling.tree.grid();
        let (omega, lod) = (tiling.omega, tiling.lod);
        let mut geometry_blades = 0u64;
        let mut slice_blades = 0u64;
        let mut vertical_blades = 0.0f64;
        for s in &selection.cells {
            let (i, j) = (s.rect.i0, s.rect.j0);
            let centre = grid.cell_min(i, j) + Vec2::splat(0.5 * grid.cell);
            let orientation = Orientation::of_cell(tiling.seed, i, j);
            let signs = orientation.signs();
            let d = 0.5 * (s.near + s.far);
            // Which representations draw the cell, and with which weights.
            let (weights, geometry, slices, vertical) = if tiling.transitions {
                (
                    CellWeights::ByDistance,
                    s.near < lod.max_geom,
                    s.far > lod.min_geom,
                    s.far > lod.min_geom && s.near < lod.max_btf,
                )
            } else {
                let ground = Vec3::new(centre.x, 0.5 * (s.ground_y[0] + s.ground_y[1]), centre.y);
                let level = lod.abrupt_level(camera.eye.distance(ground));
                (
                    CellWeights::of_level(level),
                    level == lod::Level::Geometry,
                    level != lod::Level::Geometry,
                    level == lod::Level::VerticalSlices,
                )
            };
            let [fixed, w_fixed, fade_fixed] = weights.encode();
            let mode = [0.0, fixed, w_fixed, fade_fixed];
            let mut drawn = 0u64;
            if geometry {
                let mut ranges = Vec::new();
                // Whether every block was submitted whole: then the cell's count is its
                // population's, without counting block by block.
                let mut complete = true;
                let mut blocks = Vec::new();
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
                    let by_distance = weights == CellWeights::ByDistance;
                    if (by_distance && near >= lod.max_geom)
                        || !walk.frustum.intersects_aabb(&bounds)
                    {
                        complete = false;
                        continue;
                    }
                    // The blades Eq. 5 can give visible opacity here: normalised thresholds
                    // from `geometry_min_t` of the largest weight in the block, under the
                    // density.
                    // A cell wholly at full weight draws whole blocks (the shader still
                    // tests each threshold), so runs of such cells merge into one draw.
                    let t_min =
                        lod::geometry_min_t(lod.w_g(near), omega, tiling.alpha_floor).max(0.0);
                    let whole = !by_distance || s.far <= lod.min_geom;
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
                    complete &= r == tiling.patch.block_ranges[k as usize];
                    if !r.is_empty() {
                        blocks.push(k);
                        ranges.push(r);
                    }
                }
                drawn = if complete {
                    u64::from(tiling.population.cell(i, j))
                } else {
                    blocks
                        .iter()
                        .zip(&ranges)
                        .map(|(&k, r)| {
                            let p = &tiling.population;
                            u64::from(p.growing_in(terrain, &tiling.patch, (i, j), k, r.clone()))
                        })
                        .sum()
                };
                if !ranges.is_empty() {
                    self.geometry.push(GeometryCell {
                        record: CellRecord {
                            center_signs: [centre.x, centre.y, signs.x, signs.y],
                            mode,
                        },
                        ranges,
                        near: s.near,
                    });
                }
            }
            geometry_blades += drawn;
            if slices {
                self.slice_quads.push(slice_quad(tiling, s, 1, weights));
                // The slices stand for every growing blade whose geometry was not submitted.
                let rest = u64::from(tiling.population.cell(i, j)).saturating_sub(drawn);
                slice_blades += rest;
                // The vertical slices where Eq. 3 can give them a share (Sec. 3.3).
                if vertical {
                    self.vslice_cells.push((
                        CellRecord {
                            center_signs: [centre.x, centre.y, signs.x, signs.y],
                            mode,
                        },
                        s.near,
                    ));
                    vertical_blades += rest as f64 * f64::from(weights.fade(&lod, d));
                }
            }
        }
        let far_weights = if tiling.transitions {
            CellWeights::ByDistance
        } else {
            CellWeights::of_level(lod::Level::HorizontalSlice)
        };
        for s in &selection.macro_cells {
            let side = s.rect.ni.max(s.rect.nj).next_power_of_two();
            self.slice_quads
                .push(slice_quad(tiling, s, side.min(8), far_weights));
            slice_blades += s.blades;
        }
        self.selection = selection;
        // Far to near. Blades are not sorted (Sec. 4.2), but cells are, for free: Eq. 5 leaves
        // many blades of the transition semi-transparent, and with cells drawn near to far
        // (18 % faster here, thanks to early depth rejection) faint near blades hid whole
        // cells drawn after them, which showed as cell-sized blotches.
        self.geometry.sort_by(|a, b| b.near.total_cmp(&a.near));
        self.vslice_cells.sort_by(|a, b| b.1.total_cmp(&a.1));
        self.vslice_records
            .extend(self.vslice_cells.iter().map(|c| c.0));
        self.pages = paging.draws(self.geometry.iter().map(|c| c.ranges.as_slice()));
        self.slice_quads
            .sort_by(|a, b| a.tess[0].total_cmp(&b.tess[0]));
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
            horizontal_slices: slice_blades,
        };
    }
}

/// The horizontal slice quad over `s`'s cells, `tess` quads a side, drawn with `weights`.
fn slice_quad(tiling: &Tiling, s: &Selected, tess: u32, weights: CellWeights) -> SliceQuad {
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
        tess: {
            let [fixed, w_g, fade] = weights.encode();
            [tess as f32, fixed, w_g, fade]
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Params;
    use crate::quadtree::CellGrid;
    use crate::tiling::scene_patch;
    use grassbench::Scene;
    use grassbench::technique::{NO_TRANSITIONS, Technique as _};

    /// `tests/scenes/counts.toml`'s lawn: 12 x 12 m at 20 blades/m², seen whole from 25 m;
    /// `terrain` replaces its `[terrain]` table's maps and size.
    fn lawn(terrain: &str) -> Scene {
        let text = format!(
            r#"name = "lawn"
description = "the counts lawn"
seed = 5
resolution = [320, 180]
[terrain]
max_height = 0.0
height = {{ kind = "constant", value = 0.0 }}
{terrain}
[grass]
density = 20.0
height = [0.25, 0.45]
width = [0.02, 0.03]
[camera]
fov_y = 50.0
near = 0.1
far = 200.0
[camera.path]
kind = "fixed"
eye = [0.0, 18.0, -18.0]
look_at = [0.0, 0.0, 0.0]
[wind]
model = "calm"
"#
        );
        Scene::from_toml(&text, std::path::Path::new("lawn.toml")).unwrap()
    }

    const UNIFORM: &str = r#"size = [12.0, 12.0]
density = { kind = "constant", value = 1.0 }
covering = { kind = "grass" }"#;

    /// Uneven ground: a density map, gaps and trees in the covering, and a side that is not a
    /// whole number of cells (the last row and column of cells stick out of the terrain).
    const UNEVEN: &str = r#"size = [12.3, 12.3]
samples_per_metre = 2.0
density = { kind = "procedural", frequency = 0.2, octaves = 2, range = [0.2, 1.0] }
covering = { kind = "procedural", gaps = 0.2, trees = 0.02, stones = 0.02, frequency = 0.3 }"#;

    /// LOD distances that put the lawn's 21.6-30.6 m in the transition bands.
    const BANDS: &str = "min_geom = 20.0\nmax_geom = 26.0\nmin_btf = 26.0\nmax_btf = 40.0";

    /// The tiling of `scene` with `overrides`, as `Boulanger::new` builds it.
    fn tiling(scene: &Scene, overrides: &str) -> Tiling {
        let table: toml::Table = toml::from_str(overrides).unwrap();
        let given: Params = grassbench::params::resolve("boulanger", &table).unwrap();
        let params = given.for_scene(&scene.config.grass).unwrap();
        let grid = CellGrid::new(&scene.terrain, params.patch_size);
        let patch = scene_patch(&params, scene);
        let uniform = crate::gpu::params_uniform(&params, &scene.config.grass);
        Tiling::new(&params, scene, grid, patch, uniform.lod[3])
    }

    /// The lawn's fixed view.
    fn camera() -> Camera {
        Camera::look_at(
            Vec3::new(0.0, 18.0, -18.0),
            Vec3::ZERO,
            50f32.to_radians(),
            0.1,
            200.0,
            16.0 / 9.0,
        )
    }

    fn plan(scene: &Scene, tiling: &Tiling) -> FramePlan {
        let paging = Paging::new(
            tiling.blades_per_patch(),
            &grassbench::wgpu::Limits::default(),
        );
        let mut plan = FramePlan::default();
        plan.update(tiling, &scene.terrain, &camera(), &paging);
        plan
    }

    /// Issue 19: the frame counts every growing blade in view once, drawn or represented. The
    /// lawn is seen whole, so at the finest variant (geometry everywhere), at the defaults
    /// (slices only at 21-31 m) and with the transition bands across it (geometry, vertical
    /// and horizontal slices sharing cells) drawn + represented is the whole population:
    /// 576 cells x 5 blades = 2 880 on the uniform lawn, and on uneven ground exactly the
    /// blades the population finds growing (a test of each blade against the maps, in
    /// `population`), though the cells there hold from none to all of the patch's blades.
    #[test]
    fn every_growing_blade_in_view_is_counted_once() {
        for (ground, total) in [(UNIFORM, Some(2_880)), (UNEVEN, None)] {
            let scene = lawn(ground);
            for (name, overrides) in [
                ("finest", crate::Boulanger::VARIANTS.finest),
                ("default", ""),
                ("bands", BANDS),
                ("bands, hard", &format!("{BANDS}\nomega = 0.0")),
                (
                    "bands, no transitions",
                    &format!("{BANDS}\ntransitions = false"),
                ),
            ] {
                let t = tiling(&scene, overrides);
                let population = t.population.total();
                if let Some(total) = total {
                    assert_eq!(population, total);
                }
                let p = plan(&scene, &t);
                let b = p.lod_blades;
                assert_eq!(
                    b.geometry + b.horizontal_slices,
                    population,
                    "{name}: {b:?}"
                );
                assert!(b.vertical_slices <= b.horizontal_slices, "{name}: {b:?}");
                match name {
                    "finest" => assert_eq!(b.horizontal_slices, 0, "{name}: {b:?}"),
                    "default" => assert_eq!(b.geometry, 0, "{name}: {b:?}"),
                    _ => assert!(
                        b.geometry > 0 && b.vertical_slices > 0 && b.horizontal_slices > 0,
                        "{name}: {b:?}"
                    ),
                }
            }
        }
    }

    /// A scene without grass (`grass.density = 0`) plans no draw at all and counts nothing.
    #[test]
    fn no_grass_plans_nothing() {
        let mut config = lawn(UNIFORM).config;
        config.grass.density = 0.0;
        let scene = Scene::from_config(config, ".".into()).unwrap();
        let t = tiling(&scene, "");
        assert_eq!(t.blades_per_patch(), 0);
        let p = plan(&scene, &t);
        assert!(p.geometry.is_empty() && p.slice_quads.is_empty() && p.vslice_records.is_empty());
        assert!(p.pages.is_empty() && p.quad_groups.is_empty());
        assert_eq!(p.lod_blades, BandBlades::default());
    }

    /// Per selected cell, the share of its growing blades drawn as geometry, by the CPU twins
    /// of the shaders (`vs_blade`: Eq. 5 at the cell's weights, skipped under the alpha-test
    /// threshold), with the distance from the eye to the cell's centre, and the cell's
    /// horizontal slice quad if it has one.
    fn geometric_shares(
        scene: &Scene,
        t: &Tiling,
        p: &FramePlan,
    ) -> Vec<(f32, f32, Option<SliceQuad>)> {
        let grid = *t.tree.grid();
        let eye = camera().eye;
        let mut out = Vec::new();
        for j in 0..grid.nz {
            for i in 0..grid.nx {
                let centre = grid.cell_min(i, j) + Vec2::splat(0.5 * grid.cell);
                let grown = t.population.cell(i, j);
                if grown == 0 {
                    continue;
                }
                let geometry = p.geometry.iter().find(|c| {
                    Vec2::new(c.record.center_signs[0], c.record.center_signs[1]) == centre
                });
                let mut drawn = 0.0;
                if let Some(c) = geometry {
                    let signs = Vec2::new(c.record.center_signs[2], c.record.center_signs[3]);
                    let mode = c.record.mode;
                    for r in &c.ranges {
                        for b in &t.patch.blades[r.start as usize..r.end as usize] {
                            let xz = centre + Vec2::from(b.root) * signs;
                            if !crate::population::grows(&scene.terrain, xz, b.threshold) {
                                continue;
                            }
                            let d = eye.distance(scene.terrain.point_at(xz));
                            let w = if mode[1] > 0.5 { mode[2] } else { t.lod.w_g(d) };
                            let rho = scene.terrain.density_at(xz);
                            let o = lod::geometry_opacity(w, b.threshold / rho, t.omega);
                            if o > 0.0 && o >= t.alpha_floor {
                                drawn += o;
                            }
                        }
                    }
                }
                let quad = p.slice_quads.iter().copied().find(|q| {
                    q.cells[2] == 1.0 && q.cells[3] == 1.0 && q.cells[..2] == [i as f32, j as f32]
                });
                let d = eye.distance(Vec3::new(centre.x, 0.0, centre.y));
                out.push((d, drawn / grown as f32, quad));
            }
        }
        out
    }

    /// Issue 19 §3: without transitions the levels switch abruptly, per cell, at the middle of
    /// the transition band: every cell's blades are all geometry (a geometry cell at weight 1,
    /// no slice) or none (slices at geometry weight 0, the vertical slices in full or not at
    /// all), and the geometric share jumps from 1 to 0 at (min_geom + max_geom) / 2 = 23 m of
    /// the cell's centre. The seamless variant splits cells across the band — and so did the
    /// `no_transitions` variant before issue 19 (ω = 0 only made Eq. 5 a hard test on the
    /// same density split), which this test fails.
    #[test]
    fn without_transitions_each_cell_is_entirely_geometry_or_entirely_slices() {
        let scene = lawn(UNIFORM);
        let variant = crate::Boulanger::VARIANTS.get(NO_TRANSITIONS).unwrap();
        let t = tiling(&scene, &format!("{BANDS}\n{variant}"));
        let p = plan(&scene, &t);
        let shares = geometric_shares(&scene, &t, &p);
        assert_eq!(shares.len(), 576);
        let border = 0.5 * (t.lod.min_geom + t.lod.max_geom);
        let (mut last_geometry, mut first_slices) = (0.0f32, f32::INFINITY);
        for &(d, share, quad) in &shares {
            assert!(
                share == 0.0 || share == 1.0,
                "a cell {d} m away is split: {share}"
            );
            if share == 1.0 {
                last_geometry = last_geometry.max(d);
                assert!(quad.is_none(), "a geometry cell {d} m away has a slice");
            } else {
                first_slices = first_slices.min(d);
                let q = quad.expect("a slice cell without its slice");
                // Fixed weights: geometry 0 (the slices take every blade), the vertical slices
                // in full up to the middle of their fade (33 m), none beyond.
                assert_eq!(q.tess[1..3], [1.0, 0.0], "{d} m: {q:?}");
                assert!(q.tess[3] == 0.0 || q.tess[3] == 1.0, "{d} m: {q:?}");
            }
        }
        assert!(last_geometry < border && border <= first_slices);
        assert!(last_geometry > border - 0.5 && first_slices < border + 0.5);
        assert!(
            p.geometry
                .iter()
                .all(|c| c.record.mode == [0.0, 1.0, 1.0, 0.0])
        );
        assert!(
            p.vslice_records
                .iter()
                .all(|c| c.mode == [0.0, 1.0, 0.0, 1.0])
        );
        assert!(!p.vslice_records.is_empty());
        // The seamless defaults, and the hard test of the variant before issue 19, split the
        // cells of the band between geometry and slices.
        for old in ["", "omega = 0.0"] {
            let t = tiling(&scene, &format!("{BANDS}\n{old}"));
            let p = plan(&scene, &t);
            let split = geometric_shares(&scene, &t, &p)
                .iter()
                .filter(|s| s.1 > 0.0 && s.1 < 1.0)
                .count();
            eprintln!("measured: {old:?}: {split} cells split");
            // Measured 284 (ω = 0.4) and 289 (ω = 0) of the 576: the band crosses half the
            // lawn. More than 20 leaves no doubt the seamless split is there.
            assert!(split > 20, "{old:?}: {split} cells split");
        }
    }
}
