//! The scene's grass population.
//!
//! A scene says how dense, tall, wide, stiff and green its grass is ([`GrassConfig`]); the
//! [`BladeField`] turns that into concrete blades with stratified jittered sampling: the ground
//! is cut into square cells of area `1 / density`, one candidate blade per cell, placed and
//! sized by a hash of the cell's coordinates. A blade is kept where the covering map says grass
//! and its density threshold is below the density map (Boulanger Sec. 3.4), so techniques that
//! manage density themselves can reproduce exactly the same blades.

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use crate::params::check;
use crate::rng::hash;
use crate::terrain::{Terrain, covering};
use crate::{Error, Result};

/// Most blades a scene may ask for: beyond this no technique can be compared with the reference
/// on one GPU (48 bytes each is already 2.4 GB of instance data).
pub const MAX_BLADES: f64 = 50e6;

/// `[grass]` in a scene file.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct GrassConfig {
    /// Blades per square metre where the density map is 1.
    pub density: f32,
    /// Blade height range, m.
    pub height: [f32; 2],
    /// Blade width at the root, m.
    pub width: [f32; 2],
    /// Stiffness range: 1 = a typical blade; bend under wind scales with 1 / stiffness.
    pub stiffness: [f32; 2],
    /// Largest bend at rest (no wind), radians.
    pub lean: f32,
    /// Linear RGB albedo at the root.
    pub color_root: [f32; 3],
    /// Linear RGB albedo at the tip.
    pub color_tip: [f32; 3],
    /// Per-blade brightness and hue variation, 0..1.
    pub color_variation: f32,
}

impl Default for GrassConfig {
    fn default() -> Self {
        Self {
            density: 80.0,
            height: [0.25, 0.55],
            width: [0.02, 0.035],
            stiffness: [0.7, 1.3],
            lean: 0.35,
            color_root: [0.03, 0.09, 0.015],
            color_tip: [0.30, 0.45, 0.10],
            color_variation: 0.25,
        }
    }
}

impl GrassConfig {
    /// Rejects NaN, negatives and absurd values.
    pub fn validate(&self, terrain_area: f32) -> Result<()> {
        check("grass.density", self.density, 0.0..=100_000.0)?;
        let blades = f64::from(self.density) * f64::from(terrain_area);
        if blades > MAX_BLADES {
            return Err(Error::param(
                "grass.density",
                self.density,
                format!(
                    "at most {MAX_BLADES:.0} blades over the terrain; {} blades/m² over {terrain_area:.0} m² is {blades:.3e}",
                    self.density
                ),
            ));
        }
        for (name, r, lo, hi) in [
            ("grass.height", self.height, 0.001, 100.0),
            ("grass.width", self.width, 0.0001, 10.0),
            ("grass.stiffness", self.stiffness, 0.01, 100.0),
        ] {
            check(&format!("{name}[0]"), r[0], lo..=hi)?;
            check(&format!("{name}[1]"), r[1], lo..=hi)?;
            if r[0] > r[1] {
                return Err(Error::param(
                    name,
                    format!("{r:?}"),
                    "[min, max] with min <= max",
                ));
            }
        }
        check("grass.lean", self.lean, 0.0..=1.5)?;
        for (name, c) in [
            ("grass.color_root", self.color_root),
            ("grass.color_tip", self.color_tip),
        ] {
            for (k, v) in c.iter().enumerate() {
                check(&format!("{name}[{k}]"), *v, 0.0..=1.0)?;
            }
        }
        check("grass.color_variation", self.color_variation, 0.0..=1.0)
    }
}

/// One blade of grass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blade {
    /// Root position on the ground.
    pub root: Vec3,
    /// Direction the blade's flat side faces, radians around y.
    pub facing: f32,
    /// Height, m.
    pub height: f32,
    /// Width at the root, m.
    pub width: f32,
    /// Stiffness (1 = typical).
    pub stiffness: f32,
    /// Rest bend: direction (radians around y) and amount (radians).
    pub lean: Vec2,
    /// Colour variation in `[-1, 1]`.
    pub variation: f32,
    /// Density threshold in `[0, 1)`: drawn where the density map exceeds it.
    pub threshold: f32,
}

/// Deterministic blades for a terrain.
#[derive(Clone, Debug)]
pub struct BladeField {
    config: GrassConfig,
    seed: u64,
    cell: f32,
}

impl BladeField {
    /// The blades of `config` with `seed`.
    pub fn new(config: GrassConfig, seed: u64) -> Self {
        let cell = if config.density > 0.0 {
            config.density.recip().sqrt()
        } else {
            f32::INFINITY
        };
        Self { config, seed, cell }
    }

    /// Side of one sampling cell, m.
    pub fn cell_size(&self) -> f32 {
        self.cell
    }

    /// The candidate blade of cell `(i, j)` (cell `(0, 0)` starts at the world origin), before
    /// the density and covering tests.
    pub fn candidate(&self, i: i64, j: i64, terrain: &Terrain) -> Blade {
        let c = &self.config;
        let h = |k: i64| (hash(self.seed, &[i, j, k]) >> 40) as f32 / (1u64 << 24) as f32;
        let xz = Vec2::new((i as f32 + h(0)) * self.cell, (j as f32 + h(1)) * self.cell);
        let lerp = |r: [f32; 2], t: f32| r[0] + (r[1] - r[0]) * t;
        // Taller blades are also a little wider: heights and widths share part of their draw.
        let size = h(3);
        Blade {
            root: terrain.point_at(xz),
            facing: h(2) * std::f32::consts::TAU,
            height: lerp(c.height, size),
            width: lerp(c.width, 0.5 * size + 0.5 * h(4)),
            stiffness: lerp(c.stiffness, h(5)),
            lean: Vec2::new(h(6) * std::f32::consts::TAU, c.lean * h(7).sqrt()),
            variation: h(8) * 2.0 - 1.0,
            threshold: h(9),
        }
    }

    /// Whether a candidate grows: on grass-covered ground, under the density map.
    pub fn grows(&self, blade: &Blade, terrain: &Terrain) -> bool {
        let xz = Vec2::new(blade.root.x, blade.root.z);
        terrain.contains(xz)
            && terrain.covering_at(xz) == covering::GRASS
            && blade.threshold < terrain.density_at(xz)
    }

    /// Range of cell indices covering the axis-aligned rectangle `[min, max]` (x, z).
    pub fn cells_in(&self, min: Vec2, max: Vec2) -> (std::ops::Range<i64>, std::ops::Range<i64>) {
        if !self.cell.is_finite() {
            return (0..0, 0..0);
        }
        let lo = (min / self.cell).floor();
        let hi = (max / self.cell).ceil();
        (lo.x as i64..hi.x as i64, lo.y as i64..hi.y as i64)
    }

    /// Every blade that grows inside `[min, max]`, in cell order.
    pub fn blades_in(&self, min: Vec2, max: Vec2, terrain: &Terrain) -> Vec<Blade> {
        self.grown_in(min, max, terrain).collect()
    }

    /// The blades that grow inside `[min, max]`, in cell order, one at a time.
    fn grown_in<'a>(
        &'a self,
        min: Vec2,
        max: Vec2,
        terrain: &'a Terrain,
    ) -> impl Iterator<Item = Blade> + 'a {
        let (is, js) = self.cells_in(min, max);
        js.flat_map(move |j| is.clone().map(move |i| (i, j)))
            .map(|(i, j)| self.candidate(i, j, terrain))
            .filter(move |b| {
                let xz = Vec2::new(b.root.x, b.root.z);
                xz.cmpge(min).all() && xz.cmplt(max).all() && self.grows(b, terrain)
            })
    }

    /// How many blades grow on the terrain ([`Self::all_blades`]'s length), without holding
    /// them: for limits and estimates that need the exact count.
    pub fn count(&self, terrain: &Terrain) -> u64 {
        self.grown_in(
            terrain.min_corner(),
            terrain.min_corner() + terrain.size(),
            terrain,
        )
        .count() as u64
    }

    /// Candidates over the whole terrain: an upper bound of [`Self::all_blades`]'s length,
    /// without generating them (for memory estimates).
    pub fn candidate_count(&self, terrain: &Terrain) -> u64 {
        let (is, js) = self.cells_in(terrain.min_corner(), terrain.min_corner() + terrain.size());
        let len = |r: std::ops::Range<i64>| u64::try_from(r.end - r.start).unwrap_or(0);
        len(is) * len(js)
    }

    /// Every blade on the terrain.
    pub fn all_blades(&self, terrain: &Terrain) -> Vec<Blade> {
        self.blades_in(
            terrain.min_corner(),
            terrain.min_corner() + terrain.size(),
            terrain,
        )
    }

    /// The grass parameters.
    pub fn config(&self) -> &GrassConfig {
        &self.config
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::{CoveringSource, MapSource, TerrainConfig};

    #[test]
    fn count_matches_density_and_field_is_deterministic() {
        let t = Terrain::flat(Vec2::new(20.0, 10.0));
        let f = BladeField::new(
            GrassConfig {
                density: 50.0,
                ..Default::default()
            },
            3,
        );
        let blades = f.all_blades(&t);
        assert_eq!(f.count(&t), blades.len() as u64);
        let expected = 50.0 * 200.0;
        assert!(
            (blades.len() as f32 - expected).abs() < expected * 0.03,
            "{}",
            blades.len()
        );
        assert_eq!(blades, f.all_blades(&t));
        assert!(
            blades
                .iter()
                .all(|b| t.contains(Vec2::new(b.root.x, b.root.z)))
        );
        // Sub-rectangles partition the field exactly.
        let left = f
            .blades_in(Vec2::new(-10.0, -5.0), Vec2::new(0.0, 5.0), &t)
            .len();
        let right = f
            .blades_in(Vec2::new(0.0, -5.0), Vec2::new(10.0, 5.0), &t)
            .len();
        assert_eq!(left + right, blades.len());
    }

    #[test]
    fn density_map_thins_the_field() {
        let config = TerrainConfig {
            size: [20.0, 20.0],
            max_height: 0.0,
            samples_per_metre: 1.0,
            height: MapSource::default(),
            density: MapSource::Constant { value: 0.25 },
            covering: CoveringSource::Grass,
        };
        let t = Terrain::build(&config, 1, std::path::Path::new(".")).unwrap();
        let f = BladeField::new(
            GrassConfig {
                density: 40.0,
                ..Default::default()
            },
            3,
        );
        let n = f.all_blades(&t).len() as f32;
        assert!((n / (40.0 * 400.0) - 0.25).abs() < 0.03, "{n}");
    }

    #[test]
    fn rejects_absurd_blade_counts() {
        let c = GrassConfig {
            density: 10_000.0,
            ..Default::default()
        };
        let e = c.validate(1e6).unwrap_err().to_string();
        assert!(e.contains("grass.density") && e.contains("blades"), "{e}");
        assert!(
            GrassConfig {
                density: f32::NAN,
                ..Default::default()
            }
            .validate(1.0)
            .is_err()
        );
    }
}
