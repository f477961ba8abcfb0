//! The ambient occlusion map over the terrain (Boulanger Sec. 3.5, Fig. 18): external
//! occluders, the trees and stones of the covering map, take part of the sky from the grass
//! around them. Computed once at start-up (it does not depend on the lights), one value per
//! covering-map sample: the fraction of the hemisphere of directions above the ground that
//! the occluders hide. The blades multiply their ambient light by it at their root, the slices
//! per pixel (`ambient_visibility` in `shaders/grass.wgsl`).
//!
//! The covering map says where trees and stones stand but not how tall they are:
//! `tree_height` and `stone_height` say it. A sample of occluder of side `s` at distance `d`
//! and height `h` hides the solid angle `(s/d) · sin(atan(h/d))` (its azimuth width times the
//! band of elevations under its top); the contributions within `3·tree_height` (at most 24 m)
//! are summed and divided by the hemisphere's `2π`, clamped to 1. Summing overcounts where
//! occluders stand behind one another (a clump of trees hides at most what its front does), so
//! clumps come out darker than an exact visibility test would make them.

use glam::Vec2;
use grassbench::terrain::{Grid, Terrain, covering};

/// Ambient visibility (1 − occlusion) per covering-map sample, same size and convention.
pub fn visibility_map(terrain: &Terrain, tree_height: f32, stone_height: f32) -> Grid<f32> {
    let cover = terrain.covering();
    let (w, h) = (cover.width(), cover.height());
    let spacing = terrain.size() / Vec2::new((w.max(2) - 1) as f32, (h.max(2) - 1) as f32);
    let side = spacing.x.min(spacing.y);
    let reach = (3.0 * tree_height.max(stone_height)).min(24.0);
    let (ri, rj) = (
        (reach / spacing.x).ceil() as isize,
        (reach / spacing.y).ceil() as isize,
    );
    let mut hidden = vec![0.0f32; w * h];
    for (k, id) in cover.data().iter().enumerate() {
        let height = match *id {
            covering::TREE => tree_height,
            covering::STONE => stone_height,
            _ => continue,
        };
        if height <= 0.0 {
            continue;
        }
        let (oi, oj) = ((k % w) as isize, (k / w) as isize);
        for j in (oj - rj).max(0)..=(oj + rj).min(h as isize - 1) {
            for i in (oi - ri).max(0)..=(oi + ri).min(w as isize - 1) {
                let offset = Vec2::new((i - oi) as f32, (j - oj) as f32) * spacing;
                // At least one sample away: an occluder's own sample is not grass.
                let d = offset.length().max(side);
                if d > reach {
                    continue;
                }
                let azimuth = (side / d).min(std::f32::consts::PI);
                let elevation = (height / d).atan();
                hidden[j as usize * w + i as usize] += azimuth * elevation.sin();
            }
        }
    }
    let data = hidden
        .iter()
        .map(|a| 1.0 - (a / std::f32::consts::TAU).min(1.0))
        .collect();
    Grid::from_vec(w, h, data).unwrap_or_else(|| Grid::filled(w, h, 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use grassbench::terrain::{CoveringSource, MapSource, TerrainConfig};

    fn terrain_with(trees: f32, stones: f32) -> Terrain {
        let config = TerrainConfig {
            size: [60.0, 60.0],
            max_height: 0.0,
            samples_per_metre: 1.0,
            height: MapSource::default(),
            density: MapSource::Constant { value: 1.0 },
            covering: CoveringSource::Procedural {
                gaps: 0.0,
                trees,
                stones,
                frequency: 0.05,
            },
        };
        Terrain::build(&config, 3, std::path::Path::new(".")).unwrap()
    }

    #[test]
    fn open_ground_sees_the_whole_sky_and_occluders_take_some_of_it() {
        let open = visibility_map(&terrain_with(0.0, 0.0), 6.0, 0.5);
        assert!(open.data().iter().all(|v| *v == 1.0));
        let t = terrain_with(0.01, 0.01);
        let map = visibility_map(&t, 6.0, 0.5);
        assert!(map.data().iter().all(|v| (0.0..=1.0).contains(v)));
        let cover = t.covering();
        let w = cover.width();
        // Next to a tree is darker than the mean, and taller trees hide more.
        let tree = cover
            .data()
            .iter()
            .position(|id| *id == covering::TREE)
            .expect("some tree");
        let beside = map.data()[(tree + 1).min(map.data().len() - 1)];
        let mean = map.data().iter().sum::<f32>() / map.data().len() as f32;
        assert!(
            beside < mean && beside < 0.95,
            "beside {beside}, mean {mean}"
        );
        let taller = visibility_map(&t, 12.0, 0.5);
        let next = (tree + 1).min(map.data().len() - 1);
        assert!(taller.data()[next] < map.data()[next]);
        // Far from every occluder (beyond 3 x 6 m) nothing is hidden.
        let far = (0..map.data().len()).find(|&k| {
            let (i, j) = ((k % w) as isize, (k / w) as isize);
            cover.data().iter().enumerate().all(|(o, id)| {
                !matches!(*id, covering::TREE | covering::STONE)
                    || ((o % w) as isize - i).pow(2) + ((o / w) as isize - j).pow(2) > 19 * 19
            })
        });
        if let Some(k) = far {
            assert_eq!(map.data()[k], 1.0);
        }
    }
}
