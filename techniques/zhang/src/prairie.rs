//! The prairie of Sec. 5.1 fitted over the scene's terrain: `grids x grids` grass grids, each
//! with `n x n` blades (Sec. 3.1.2) on a jittered lattice, roots on the terrain, gaps where
//! the covering map says no grass, thinned by the density map with the shared per-blade
//! threshold rule (`grassbench::grass`).

use grassbench::glam::{Vec2, Vec3};
use grassbench::grass::GrassConfig;
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
    /// The grass grid it grows in, `gz · grids + gx` (Sec. 5.1).
    pub grid: u32,
    /// Its lattice point within the grid, `j · n + i` (the pre-computed orders of Sec. 5.4
    /// are over lattice points).
    pub cell: u32,
}

/// Where the grass grids lie.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// Grids per side.
    pub grids: u32,
    /// Blades per grid side.
    pub per_side: u32,
    /// Size of one grass grid (terrain size / grids), m.
    pub grid_size: Vec2,
    /// Terrain min corner.
    pub origin: Vec2,
}

impl Layout {
    /// The grids of `params` over `terrain`.
    pub fn new(params: &Params, terrain: &Terrain) -> Self {
        Self {
            grids: params.grids,
            per_side: params.blades_per_side,
            grid_size: terrain.size() / params.grids as f32,
            origin: terrain.min_corner(),
        }
    }

    /// Blade spacing, m.
    pub fn spacing(&self) -> Vec2 {
        self.grid_size / self.per_side as f32
    }

    /// Candidate blades (before the covering and density tests) over the whole prairie.
    pub fn candidates(&self) -> u64 {
        u64::from(self.grids * self.per_side).pow(2)
    }
}

/// Plants every blade that grows: candidates on the jittered lattice, kept where the covering
/// map says grass and the blade's density threshold (uniform in `[0, 1)`, hashed per blade)
/// is below the density map, exactly the rule of `grassbench::grass::BladeField::grows`. So
/// `zhang` keeps the same *fraction* of its candidates as `reference` keeps of its own; the
/// counts differ by the candidate densities, `(grids·n)² / area` blades/m² here against the
/// scene's `grass.density` there.
pub fn plant(
    params: &Params,
    grass: &GrassConfig,
    terrain: &Terrain,
    seed: u64,
) -> (Layout, Vec<Planted>) {
    let layout = Layout::new(params, terrain);
    let n = layout.per_side;
    let grids = layout.grids;
    // Grid by grid, so each grass grid's blades are contiguous (culled and drawn per grid,
    // Sec. 5.3); a blade's draw depends only on its lattice point (i, j), not on the order.
    let lattice = (0..grids * grids).flat_map(move |g| {
        let (gx, gz) = (g % grids, g / grids);
        (0..n * n).map(move |k| (g, gx * n + k % n, gz * n + k / n))
    });
    let out = lattice
        .filter_map(|(grid, i, j)| {
            let c = candidate(&layout, params, grass, terrain, seed, grid, (i, j));
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
/// grow or not. Everything is hashed from the lattice point, so both agree.
pub fn candidate(
    layout: &Layout,
    params: &Params,
    grass: &GrassConfig,
    terrain: &Terrain,
    seed: u64,
    grid: u32,
    (i, j): (u32, u32),
) -> Candidate {
    let seed = seed ^ 0x5a_4841_4e47;
    let lerp = |r: [f32; 2], t: f32| r[0] + (r[1] - r[0]) * t;
    let (i, j) = (i64::from(i), i64::from(j));
    let h = |k: i64| (hash(seed, &[i, j, k]) >> 40) as f32 / (1u64 << 24) as f32;
    let jitter = Vec2::new(h(0) - 0.5, h(1) - 0.5) * params.jitter;
    let xz = layout.origin + (Vec2::new(i as f32, j as f32) + 0.5 + jitter) * layout.spacing();
    let grows = terrain.contains(xz)
        && terrain.covering_at(xz) == covering::GRASS
        && h(9) < terrain.density_at(xz);
    let size = h(3);
    let height = lerp(grass.height, size);
    let flower = (h(10) < params.flower_fraction).then(|| {
        let layer = ((h(11) * PETAL_TEXTURES as f32) as u32).min(PETAL_TEXTURES - 1);
        // "0.65 times the height of blade with a little random offset" (Sec. 3.3).
        let petal = height * FLOWER_HEIGHT * (0.9 + 0.2 * h(12));
        (petal, h(13) * std::f32::consts::TAU, layer)
    });
    let plant = Planted {
        root: terrain.point_at(xz),
        height,
        width: lerp(grass.width, 0.5 * size + 0.5 * h(4)),
        facing: h(2) * std::f32::consts::TAU,
        lean: Vec2::new(h(6) * std::f32::consts::TAU, grass.lean * h(7).sqrt()),
        stiffness: lerp(grass.stiffness, h(5)),
        variation: h(8) * 2.0 - 1.0,
        flower,
        grid,
        cell: (j as u32 % layout.per_side) * layout.per_side + i as u32 % layout.per_side,
    };
    Candidate { plant, grows }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_fill_the_terrain_and_density_thins() {
        let terrain = Terrain::flat(Vec2::new(80.0, 40.0));
        let params = Params {
            grids: 4,
            blades_per_side: 10,
            ..Params::default()
        };
        let (layout, blades) = plant(&params, &GrassConfig::default(), &terrain, 1);
        assert_eq!(layout.grid_size, Vec2::new(20.0, 10.0));
        assert_eq!(blades.len() as u64, layout.candidates()); // flat terrain: density 1
        assert!(
            blades
                .iter()
                .all(|b| terrain.contains(Vec2::new(b.root.x, b.root.z)))
        );
        let flowers = blades.iter().filter(|b| b.flower.is_some()).count();
        assert!(flowers > 0 && flowers < 40, "{flowers} flowers");
        assert_eq!(
            blades,
            plant(&params, &GrassConfig::default(), &terrain, 1).1
        );
        assert_ne!(
            blades,
            plant(&params, &GrassConfig::default(), &terrain, 2).1
        );
    }
}
