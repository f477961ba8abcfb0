//! The blades that grow on each patch of the tiling: counted once at start-up, so a frame's
//! blade counts are sums over the patches it draws.
//!
//! A tiled patch shows the blades of its pre-computed variant, but not all of them grow: a
//! blade grows where its root (patch corner + its root in the variant) lies on the terrain, on
//! ground the covering map calls grass, and where the density map exceeds its threshold — the
//! rule the vertex shader applies to every 3D blade (`grass_density` in `shaders/perbet.wgsl`),
//! the one the scene's blade field applies (`grassbench::grass::BladeField::grows`). Strips
//! and the 2D texture test the same threshold per texel, so they show the same blades up to
//! where their texels are looked up. Patches that overhang the terrain's edge therefore count
//! only the blades rooted on it.

use glam::Vec2;
use grassbench::terrain::{Terrain, covering};

use crate::patch::Patch;
use crate::tiling::Tiling;

/// Blades that grow on each patch of `tiling` (row-major, as the tiling), from the variants
/// `patches` it shows.
pub fn growing(tiling: &Tiling, patches: &[Patch], terrain: &Terrain) -> Vec<u32> {
    (0..tiling.len())
        .map(|i| {
            let corner = tiling.corner(i);
            let variant = tiling.variants.get(i).copied().unwrap_or(0) as usize;
            patches.get(variant).map_or(0, |p| {
                p.blades
                    .iter()
                    .filter(|b| grows(corner + b.root, b.threshold, terrain))
                    .count() as u32
            })
        })
        .collect()
}

/// Whether a blade rooted at world `xz` with density threshold `threshold` grows.
pub fn grows(xz: Vec2, threshold: f32, terrain: &Terrain) -> bool {
    terrain.contains(xz)
        && terrain.covering_at(xz) == covering::GRASS
        && threshold < terrain.density_at(xz)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::patch::{self, tests::layout};
    use grassbench::grass::GrassConfig;
    use grassbench::terrain::{CoveringSource, MapSource, TerrainConfig};

    fn terrain(density: f32) -> Terrain {
        let config = TerrainConfig {
            size: [12.0, 12.0],
            max_height: 0.0,
            samples_per_metre: 1.0,
            height: MapSource::default(),
            density: MapSource::Constant { value: density },
            covering: CoveringSource::Grass,
        };
        Terrain::build(&config, 1, std::path::Path::new(".")).unwrap()
    }

    #[test]
    fn overhanging_patches_count_the_blades_on_the_terrain_and_the_density_map_thins() {
        // 12 m tiled by 2.5 m patches: 5 x 5 patches over 12.5 m, the last row and column
        // half a metre off the terrain.
        let l = layout();
        let patches = patch::build(&GrassConfig::default(), &l, (3, 400, 1), 0.1, 2);
        let full = terrain(1.0);
        let tiling = Tiling::new(&full, l.size, 3, 7, 0.1, 0.7);
        assert_eq!(tiling.len(), 25);
        let n = growing(&tiling, &patches, &full);
        // Inner patches keep every blade; edge ones lose those rooted past the edge.
        for (i, &count) in n.iter().enumerate() {
            let (x, z) = tiling.coords(i);
            let variant = &patches[tiling.variants[i] as usize];
            let on = variant
                .blades
                .iter()
                .filter(|b| {
                    let p = tiling.corner(i) + b.root;
                    p.x <= 6.0 && p.y <= 6.0
                })
                .count() as u32;
            assert_eq!(count, on);
            if x < 4 && z < 4 {
                assert_eq!(count, 400);
            } else {
                assert!(count < 400);
            }
        }
        // In all, the terrain's share of the tiling's area: 144 / 156.25 of 10 000 blades,
        // 9 216. Measured 9 206 (−0.1 %). The edge patches' blades fall off by chance: each of
        // the 9 loses a binomial share of its 400 (σ 8 blades), so the total's σ is 24 blades
        // (0.26 %) for independent patches and 72 (0.8 %) were they all one variant: 2 % is
        // 2.5 of the worst case.
        let total: u32 = n.iter().sum();
        assert!((f64::from(total) / 9216.0 - 1.0).abs() < 0.02, "{total}");
        // A density map of 0.5 keeps the blades whose threshold is below it: about half.
        // Measured 4 568 of 9 206 (0.496); 1 200 distinct blades give σ 0.014, the bound is
        // four of those.
        let half: u32 = growing(&tiling, &patches, &terrain(0.5)).iter().sum();
        assert!(
            (f64::from(half) / f64::from(total) - 0.5).abs() < 0.06,
            "{half}"
        );
        assert_eq!(
            growing(&tiling, &patches, &terrain(0.0))
                .iter()
                .sum::<u32>(),
            0
        );
    }
}
