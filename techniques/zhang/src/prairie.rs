//! The prairie of Sec. 5.1 fitted over the scene's terrain: grass grids of `n x n` lattice
//! points (Sec. 3.1.2), one candidate plant per point, roots on the terrain, gaps where the
//! covering map says no grass, thinned by the density map with the shared per-blade threshold
//! rule (`grassbench::grass`).
//!
//! By default the lattice *is* the scene's blade population: lattice point `(i, j)` is the
//! stratum (cell) `first + (i, j)` of the scene's [`BladeField`], and its plant is that
//! stratum's candidate blade (position, size, facing, lean, stiffness, colour variation,
//! density threshold), growing exactly when [`BladeField::grows`] says so. So zhang's single
//! plants stand where the reference's blades stand, its population follows `grass.density`
//! (and the density and covering maps) like every technique's, and comparisons between them
//! measure the rendering, not a different number of blades. The grids are square, `n`
//! strata a side: the whole number nearest `grid_size` metres (ours, so the grids near the
//! camera keep their size on any terrain; [`strata_per_grid`]), or with `grid_size = 0` the
//! thesis' count, `grids` along the terrain's longer side (16 x 16 on a square terrain,
//! Sec. 5.1), `n = ⌈cells / grids⌉`; they tile the terrain (the last row and column of grids
//! partly beyond it, with fewer plants). Flowers, the thesis' own addition, are hashed by zhang per
//! lattice point.
//!
//! `blades_per_side > 0` lays out the thesis' own lattice instead (`grids x grids` grids fitted
//! over the terrain, `blades_per_side²` jittered candidates each, whatever the scene's density:
//! Sec. 3.1.2 and 5.1's 32 x 32), for paper-like figures.

use grassbench::glam::{UVec2, Vec2, Vec3};
use grassbench::grass::BladeField;
use grassbench::rng::hash;
use grassbench::terrain::{Terrain, covering};

use crate::params::Params;

/// Flowers sit at this fraction of their blade's height (Sec. 3.3).
pub const FLOWER_HEIGHT: f32 = 0.65;
/// Number of procedural petal textures (Sec. 3.3, Fig. 9).
pub const PETAL_TEXTURES: u32 = 6;

/// A planted blade (before animation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Planted {
    /// Root on the ground.
    pub root: Vec3,
    /// Height, m.
    pub height: f32,
    /// Width, m.
    pub width: f32,
    /// Width-axis direction, radians around y (the "angle rotation offset" of Sec. 3.1.2).
    pub facing: f32,
    /// Rest lean: direction (radians around y), amount (radians).
    pub lean: Vec2,
    /// Stiffness (1 = typical).
    pub stiffness: f32,
    /// Colour variation in `[-1, 1]`.
    pub variation: f32,
    /// The flower beside this blade, if any: (petal height, spin, texture layer).
    pub flower: Option<(f32, f32, u32)>,
    /// The grass grid it grows in, `gz · grids.x + gx` (Sec. 5.1).
    pub grid: u32,
    /// Its lattice point within the grid, `j · n + i` (the pre-computed orders of Sec. 5.4
    /// are over lattice points).
    pub cell: u32,
}

/// What the lattice points are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lattice {
    /// The scene's strata: lattice point `(i, j)` is cell `(first[0] + i, first[1] + j)` of
    /// the scene's [`BladeField`].
    Strata {
        /// The blade-field cell of lattice point `(0, 0)`.
        first: [i64; 2],
    },
    /// The thesis' lattice: `per_side` jittered points per grid side (`Params::jitter`).
    Thesis,
}

/// Where the grass grids lie.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// Grids along x and z; grid `(gx, gz)` has index `gz · grids.x + gx`.
    pub grids: UVec2,
    /// Lattice points per grid side.
    pub per_side: u32,
    /// Size of one grass grid, m.
    pub grid_size: Vec2,
    /// Corner of grid `(0, 0)`, m.
    pub origin: Vec2,
    /// Lattice points per axis that hold a candidate (`grids · per_side` or fewer: on the
    /// scene's strata, those covering the terrain; beyond them nothing grows).
    pub extent: UVec2,
    /// What the lattice points are.
    pub lattice: Lattice,
}

impl Layout {
    /// The grids of `params` over `terrain`: on the scene's strata `field` by default, the
    /// thesis' lattice when `params.blades_per_side > 0`.
    pub fn new(params: &Params, field: &BladeField, terrain: &Terrain) -> Self {
        if params.blades_per_side > 0 {
            return Self::thesis(params, terrain);
        }
        let min = terrain.min_corner();
        let (is, js) = field.cells_in(min, min + terrain.size());
        let len = |r: std::ops::Range<i64>| u32::try_from(r.end - r.start).unwrap_or(0);
        let cells = UVec2::new(len(is.clone()), len(js.clone()));
        if cells.min_element() == 0 {
            // No grass (`grass.density = 0`): no grids at all.
            return Self {
                grids: UVec2::ZERO,
                per_side: 1,
                grid_size: Vec2::splat(terrain.size().max_element()),
                origin: min,
                extent: UVec2::ZERO,
                lattice: Lattice::Strata { first: [0, 0] },
            };
        }
        // Square grids (the strata are) of `grid_size` metres, or `grids` of them along the
        // longer side (the thesis' count), never wider than the shorter side, so the grids
        // hold about as many lattice points as there are strata on the terrain whatever its
        // shape.
        let cell = field.cell_size();
        let n = strata_per_grid(params, cells, cell);
        Self {
            grids: UVec2::new(cells.x.div_ceil(n), cells.y.div_ceil(n)),
            per_side: n,
            grid_size: Vec2::splat(n as f32 * cell),
            origin: Vec2::new(is.start as f32, js.start as f32) * cell,
            extent: cells,
            lattice: Lattice::Strata {
                first: [is.start, js.start],
            },
        }
    }

    /// The thesis' lattice: `grids x grids` grids fitted over the terrain (grid size = terrain
    /// size / grids), `blades_per_side` points a side.
    fn thesis(params: &Params, terrain: &Terrain) -> Self {
        let grids = UVec2::splat(params.grids);
        Self {
            grids,
            per_side: params.blades_per_side,
            grid_size: terrain.size() / params.grids as f32,
            origin: terrain.min_corner(),
            extent: grids * params.blades_per_side,
            lattice: Lattice::Thesis,
        }
    }

    /// Number of grids.
    pub fn grid_count(&self) -> u32 {
        self.grids.x * self.grids.y
    }

    /// Lattice spacing, m.
    pub fn spacing(&self) -> Vec2 {
        self.grid_size / self.per_side as f32
    }

    /// Candidate blades (lattice points holding one, before the covering and density tests)
    /// over the whole prairie.
    pub fn candidates(&self) -> u64 {
        u64::from(self.extent.x) * u64::from(self.extent.y)
    }

    /// The lattice points `(i, j)` of the whole prairie inside grid `grid` that hold a
    /// candidate, row by row.
    pub fn points(&self, grid: u32) -> impl Iterator<Item = (u32, u32)> + use<> {
        let n = self.per_side;
        let (gx, gz) = (grid % self.grids.x.max(1), grid / self.grids.x.max(1));
        let (i0, j0) = (gx * n, gz * n);
        let (i1, j1) = (
            (i0 + n).min(self.extent.x.max(i0)),
            (j0 + n).min(self.extent.y.max(j0)),
        );
        (j0..j1).flat_map(move |j| (i0..i1).map(move |i| (i, j)))
    }
}

/// Strata per grid side on a terrain of `cells` strata of `cell` metres: the whole number
/// nearest `params.grid_size` metres (at least 1) when it is above 0, else `⌈cells/grids⌉`
/// along the longer side (the thesis' count of grids, Sec. 5.1); never more than the shorter
/// side holds.
pub fn strata_per_grid(params: &Params, cells: UVec2, cell: f32) -> u32 {
    let n = if params.grid_size > 0.0 && cell > 0.0 {
        ((params.grid_size / cell).round() as u32).max(1)
    } else {
        cells.max_element().div_ceil(params.grids.max(1))
    };
    n.min(cells.min_element()).max(1)
}

/// Plants every blade that grows: the lattice's candidates kept where the covering map says
/// grass and the blade's density threshold is below the density map, exactly the rule of
/// `grassbench::grass::BladeField::grows`; on the scene's strata (the default) they are the
/// scene's blades, the reference's. Grid by grid, so each grass grid's blades are contiguous
/// (culled and drawn per grid, Sec. 5.3); a blade depends only on its lattice point.
pub fn plant(
    params: &Params,
    field: &BladeField,
    terrain: &Terrain,
    seed: u64,
) -> (Layout, Vec<Planted>) {
    let layout = Layout::new(params, field, terrain);
    let out = (0..layout.grid_count())
        .flat_map(|grid| layout.points(grid).map(move |p| (grid, p)))
        .filter_map(|(grid, p)| {
            let c = candidate(&layout, params, field, terrain, seed, grid, p);
            c.grows.then_some(c.plant)
        })
        .collect();
    (layout, out)
}

/// The plant of one lattice point, and whether it grows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    /// The plant as it would stand there.
    pub plant: Planted,
    /// Whether it grows: inside the terrain, on grass (covering), and its hashed threshold
    /// below the density map.
    pub grows: bool,
}

/// The plant at lattice point `(i, j)` of the whole prairie (`grid` is the grass grid it lies
/// in), grown or not: [`plant`] keeps the ones that grow, the billboards of far grids
/// ([`crate::billboard`]) animate the ones standing at their corners (Sec. 4.2) whether they
/// grow or not. Everything is hashed from the lattice point, so both agree. On the scene's
/// strata the blade is `field`'s candidate of that cell; `seed` (the scene's) hashes the
/// flowers, and on the thesis' lattice the blades too (sizes from `field`'s `[grass]` ranges).
pub fn candidate(
    layout: &Layout,
    params: &Params,
    field: &BladeField,
    terrain: &Terrain,
    seed: u64,
    grid: u32,
    (i, j): (u32, u32),
) -> Candidate {
    let seed = seed ^ 0x5a_4841_4e47;
    let n = layout.per_side;
    let cell = (j % n) * n + i % n;
    let (blade, grows, key) = match layout.lattice {
        Lattice::Strata { first } => {
            let (ci, cj) = (first[0] + i64::from(i), first[1] + i64::from(j));
            let blade = field.candidate(ci, cj, terrain);
            // The reference's test (`BladeField::blades_in` over the terrain): inside the
            // half-open terrain rectangle, then `grows`.
            let min = terrain.min_corner();
            let xz = Vec2::new(blade.root.x, blade.root.z);
            let inside = xz.cmpge(min).all() && xz.cmplt(min + terrain.size()).all();
            (blade, inside && field.grows(&blade, terrain), [ci, cj])
        }
        Lattice::Thesis => {
            let (i, j) = (i64::from(i), i64::from(j));
            let h = |k: i64| (hash(seed, &[i, j, k]) >> 40) as f32 / (1u64 << 24) as f32;
            let grass = field.config();
            let lerp = |r: [f32; 2], t: f32| r[0] + (r[1] - r[0]) * t;
            let jitter = Vec2::new(h(0) - 0.5, h(1) - 0.5) * params.jitter;
            let xz =
                layout.origin + (Vec2::new(i as f32, j as f32) + 0.5 + jitter) * layout.spacing();
            let grows = terrain.contains(xz)
                && terrain.covering_at(xz) == covering::GRASS
                && h(9) < terrain.density_at(xz);
            let size = h(3);
            let blade = grassbench::grass::Blade {
                root: terrain.point_at(xz),
                facing: h(2) * std::f32::consts::TAU,
                height: lerp(grass.height, size),
                width: lerp(grass.width, 0.5 * size + 0.5 * h(4)),
                stiffness: lerp(grass.stiffness, h(5)),
                lean: Vec2::new(h(6) * std::f32::consts::TAU, grass.lean * h(7).sqrt()),
                variation: h(8) * 2.0 - 1.0,
                threshold: h(9),
            };
            (blade, grows, [i, j])
        }
    };
    let h = |k: i64| (hash(seed, &[key[0], key[1], k]) >> 40) as f32 / (1u64 << 24) as f32;
    let flower = (h(10) < params.flower_fraction).then(|| {
        let layer = ((h(11) * PETAL_TEXTURES as f32) as u32).min(PETAL_TEXTURES - 1);
        // "0.65 times the height of blade with a little random offset" (Sec. 3.3).
        let petal = blade.height * FLOWER_HEIGHT * (0.9 + 0.2 * h(12));
        (petal, h(13) * std::f32::consts::TAU, layer)
    });
    let plant = Planted {
        root: blade.root,
        height: blade.height,
        width: blade.width,
        facing: blade.facing,
        lean: blade.lean,
        stiffness: blade.stiffness,
        variation: blade.variation,
        flower,
        grid,
        cell,
    };
    Candidate { plant, grows }
}

#[cfg(test)]
mod tests {
    use super::*;
    use grassbench::grass::GrassConfig;
    use grassbench::terrain::{CoveringSource, MapSource, TerrainConfig};

    fn field(density: f32, seed: u64) -> BladeField {
        BladeField::new(
            GrassConfig {
                density,
                ..GrassConfig::default()
            },
            seed,
        )
    }

    #[test]
    fn the_thesis_lattice_fills_the_terrain_and_density_thins() {
        let terrain = Terrain::flat(Vec2::new(80.0, 40.0));
        let params = Params {
            grids: 4,
            blades_per_side: 10,
            ..Params::default()
        };
        let (layout, blades) = plant(&params, &field(80.0, 1), &terrain, 1);
        assert_eq!(layout.grid_size, Vec2::new(20.0, 10.0));
        assert_eq!(layout.lattice, Lattice::Thesis);
        assert_eq!(blades.len() as u64, layout.candidates()); // flat terrain: density 1
        assert_eq!(layout.candidates(), 1600);
        assert!(
            blades
                .iter()
                .all(|b| terrain.contains(Vec2::new(b.root.x, b.root.z)))
        );
        let flowers = blades.iter().filter(|b| b.flower.is_some()).count();
        assert!(flowers > 0 && flowers < 80, "{flowers} flowers");
        assert_eq!(blades, plant(&params, &field(80.0, 1), &terrain, 1).1);
        assert_ne!(blades, plant(&params, &field(80.0, 1), &terrain, 2).1);
        // The thesis' lattice ignores the scene's density.
        assert_eq!(
            blades.len(),
            plant(&params, &field(5.0, 1), &terrain, 1).1.len()
        );
    }

    /// A rectangular terrain with a thinning density map and gaps.
    fn rolling() -> Terrain {
        let config = TerrainConfig {
            size: [30.0, 18.0],
            max_height: 2.0,
            samples_per_metre: 1.0,
            height: MapSource::Procedural {
                frequency: 0.05,
                octaves: 3,
                range: [0.0, 1.0],
                power: 1.0,
            },
            density: MapSource::Constant { value: 0.6 },
            covering: CoveringSource::Procedural {
                gaps: 0.1,
                trees: 0.01,
                stones: 0.01,
                frequency: 0.1,
            },
        };
        Terrain::build(&config, 4, std::path::Path::new(".")).unwrap()
    }

    #[test]
    fn by_default_the_plants_are_the_scenes_blades() {
        let terrain = rolling();
        // The thesis' count of grids (16 along the longer side).
        let params = Params {
            grid_size: 0.0,
            ..Params::default()
        };
        for density in [7.0, 40.0, 90.0] {
            let field = field(density, 9);
            let (layout, planted) = plant(&params, &field, &terrain, 9);
            let blades = field.all_blades(&terrain);
            assert!(blades.len() > 1000, "{}", blades.len());
            // The same blades, one for one (grid by grid here, cell order there).
            assert_eq!(planted.len(), blades.len());
            let key = |p: Vec3| (p.x.to_bits(), p.z.to_bits());
            let mut ours: Vec<_> = planted
                .iter()
                .map(|p| (key(p.root), p.height.to_bits(), p.facing.to_bits()))
                .collect();
            let mut theirs: Vec<_> = blades
                .iter()
                .map(|b| (key(b.root), b.height.to_bits(), b.facing.to_bits()))
                .collect();
            ours.sort_unstable();
            theirs.sort_unstable();
            assert_eq!(ours, theirs, "density {density}");
            // 16 grids along the longer side, square, tiling the terrain.
            let cell = field.cell_size();
            assert_eq!(layout.grids.x, 16, "density {density}");
            assert!(layout.grids.y < 16 && layout.grids.y * layout.per_side >= layout.extent.y);
            assert!((layout.grid_size.x - layout.per_side as f32 * cell).abs() < 1e-4);
            assert_eq!(layout.grid_size.x, layout.grid_size.y);
            let far = layout.origin + layout.grids.as_vec2() * layout.grid_size;
            assert!(layout.origin.cmple(terrain.min_corner()).all());
            assert!(far.cmpge(terrain.min_corner() + terrain.size()).all());
            // Each plant lies in its grid.
            for p in &planted {
                let (gx, gz) = (p.grid % layout.grids.x, p.grid / layout.grids.x);
                let lo = layout.origin + Vec2::new(gx as f32, gz as f32) * layout.grid_size;
                let xz = Vec2::new(p.root.x, p.root.z) - lo;
                assert!(
                    xz.cmpge(Vec2::splat(-1e-3)).all() && xz.cmple(layout.grid_size + 1e-3).all(),
                    "{xz} outside grid {}",
                    p.grid
                );
            }
        }
    }

    #[test]
    fn metric_grids_keep_the_meadows_grids_at_80_m() {
        let params = Params::default();
        // The meadow at 80 m: 760 strata a side at 90 blades/m², 358 at 20; both 16 grids.
        for (density, cells, n) in [(90.0f32, 760u32, 48u32), (20.0, 358, 23)] {
            let cell = 1.0 / density.sqrt();
            let got = strata_per_grid(&params, UVec2::splat(cells), cell);
            assert_eq!(got, n, "{density} blades/m²");
            assert_eq!(cells.div_ceil(got), 16);
            let count = Params {
                grid_size: 0.0,
                ..Params::default()
            };
            assert_eq!(strata_per_grid(&count, UVec2::splat(cells), cell), n);
        }
        // 400 m at 20 blades/m²: the same 23 strata, 78 grids; the thesis' count 112 (25 m).
        let cell = 1.0 / 20f32.sqrt();
        assert_eq!(strata_per_grid(&params, UVec2::splat(1789), cell), 23);
        let count = Params {
            grid_size: 0.0,
            ..Params::default()
        };
        assert_eq!(strata_per_grid(&count, UVec2::splat(1789), cell), 112);
    }

    proptest::proptest! {
        /// A metric grid is the whole number of strata nearest `grid_size` (at least one),
        /// unless the terrain's shorter side holds fewer.
        #[test]
        fn metric_grids_are_the_nearest_whole_number_of_strata(
            size in 0.05f32..100.0,
            cell in 0.02f32..2.0,
            cells in (1u32..5000, 1u32..5000),
        ) {
            let params = Params {
                grid_size: size,
                ..Params::default()
            };
            let cells = UVec2::new(cells.0, cells.1);
            let n = strata_per_grid(&params, cells, cell);
            proptest::prop_assert!(n >= 1 && n <= cells.min_element().max(1));
            if n < cells.min_element() && n > 1 {
                proptest::prop_assert!((n as f32 * cell - size).abs() <= 0.5 * cell + 1e-3);
            }
            if n == 1 && cells.min_element() > 1 {
                proptest::prop_assert!(size <= 1.5 * cell + 1e-3);
            }
        }
    }

    #[test]
    fn no_density_no_grids() {
        let terrain = rolling();
        let (layout, planted) = plant(&Params::default(), &field(0.0, 9), &terrain, 9);
        assert_eq!(layout.grid_count(), 0);
        assert!(planted.is_empty());
        assert!(layout.spacing().is_finite());
    }
}
