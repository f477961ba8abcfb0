//! The ground every technique grows grass on: a heightmap, a density map (Boulanger Sec. 3.4)
//! and a covering map (Zhang Sec. 5.5.2), sampled bilinearly on the CPU and uploaded once to
//! the GPU for all techniques.
//!
//! World space: y is up, the terrain spans `[-size.x/2, size.x/2] x [-size.z/2, size.z/2]`.
//! Map sample `(0, 0)` lies at `(-size.x/2, -size.z/2)`, the last sample at the opposite corner.

pub mod chunks;
mod config;
mod gpu;
mod grid;
pub mod noise;
mod png;

use std::path::Path;

use glam::{Vec2, Vec3};

pub use config::{CoveringSource, MapSource, TerrainConfig};
pub use gpu::{
    COVERING_FORMAT, DENSITY_FORMAT, GroundVertex, HEIGHT_FORMAT, MAX_GROUND_SIDE, TerrainGpu,
};
pub use grid::Grid;

use crate::{Error, Result};

/// Covering-map IDs (Zhang Sec. 5.5.2).
pub mod covering {
    /// Nothing grows here.
    pub const NONE: u8 = 0;
    /// A tree stands here.
    pub const TREE: u8 = 253;
    /// A stone lies here.
    pub const STONE: u8 = 254;
    /// Grass grows here.
    pub const GRASS: u8 = 255;

    /// Whether `id` is one of the four IDs.
    pub fn is_valid(id: u8) -> bool {
        matches!(id, NONE | TREE | STONE | GRASS)
    }
}

/// Largest terrain side in metres.
pub const MAX_TERRAIN_SIZE: f32 = 100_000.0;
/// Largest procedural map side in samples.
pub const MAX_PROCEDURAL_SAMPLES: usize = 1024;

/// Heights (metres), density and covering over a rectangle of ground.
#[derive(Clone, Debug)]
pub struct Terrain {
    size: Vec2,
    heights: Grid<f32>,
    density: Grid<f32>,
    covering: Grid<u8>,
}

impl Terrain {
    /// Builds the terrain a scene describes. Paths are relative to `base_dir`.
    pub fn build(config: &TerrainConfig, seed: u64, base_dir: &Path) -> Result<Self> {
        validate(config)?;
        let size = Vec2::from(config.size);
        let samples = |s: f32| {
            ((s * config.samples_per_metre).ceil() as usize + 1).clamp(2, MAX_PROCEDURAL_SAMPLES)
        };
        let (w, h) = (samples(size.x), samples(size.y));
        let heights = scalar_map(
            &config.height,
            "terrain.height",
            seed ^ 0x4845_4947,
            size,
            w,
            h,
            base_dir,
        )?;
        let heights = Grid::from_fn(heights.width(), heights.height(), |i, j| {
            heights.get(i as isize, j as isize) * config.max_height
        });
        let density = scalar_map(
            &config.density,
            "terrain.density",
            seed ^ 0x4445_4e53,
            size,
            w,
            h,
            base_dir,
        )?;
        let covering = covering_map(&config.covering, seed ^ 0x434f_5645, size, w, h, base_dir)?;
        let terrain = Self {
            size,
            heights,
            density,
            covering,
        };
        for (name, map_w, map_h) in [
            (
                "terrain.height",
                terrain.heights.width(),
                terrain.heights.height(),
            ),
            (
                "terrain.density",
                terrain.density.width(),
                terrain.density.height(),
            ),
            (
                "terrain.covering",
                terrain.covering.width(),
                terrain.covering.height(),
            ),
        ] {
            check_aspect(name, map_w, map_h, size)?;
        }
        Ok(terrain)
    }

    /// A flat terrain of the given size with full density and grass everywhere.
    pub fn flat(size: Vec2) -> Self {
        Self {
            size,
            heights: Grid::filled(2, 2, 0.0),
            density: Grid::filled(2, 2, 1.0),
            covering: Grid::filled(2, 2, covering::GRASS),
        }
    }

    /// Extent in metres (x, z).
    pub fn size(&self) -> Vec2 {
        self.size
    }

    /// Lowest corner (x, z) in world space.
    pub fn min_corner(&self) -> Vec2 {
        -self.size * 0.5
    }

    /// Map coordinates in `[0, 1]^2` of a world position (x, z).
    pub fn uv(&self, xz: Vec2) -> Vec2 {
        (xz - self.min_corner()) / self.size
    }

    /// Whether (x, z) lies on the terrain.
    pub fn contains(&self, xz: Vec2) -> bool {
        let uv = self.uv(xz);
        (0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y)
    }

    /// Ground height in metres at (x, z), bilinear (Zhang Eq. 11-13).
    pub fn height_at(&self, xz: Vec2) -> f32 {
        let uv = self.uv(xz);
        self.heights.bilinear(uv.x, uv.y)
    }

    /// Unit surface normal at (x, z), from central differences of the bilinear height.
    pub fn normal_at(&self, xz: Vec2) -> Vec3 {
        let e = self.sample_spacing() * 0.5;
        let dx = self.height_at(xz + Vec2::X * e.x) - self.height_at(xz - Vec2::X * e.x);
        let dz = self.height_at(xz + Vec2::Y * e.y) - self.height_at(xz - Vec2::Y * e.y);
        Vec3::new(-dx / (2.0 * e.x), 1.0, -dz / (2.0 * e.y)).normalize()
    }

    /// Point on the ground at (x, z).
    pub fn point_at(&self, xz: Vec2) -> Vec3 {
        Vec3::new(xz.x, self.height_at(xz), xz.y)
    }

    /// Where the ray from `origin` along `direction` first meets the ground on the terrain,
    /// within `max_distance` metres: marched at a quarter of the heightmap's sample spacing,
    /// then refined by bisection. `None` when it misses (or starts under the ground).
    pub fn raycast(&self, origin: Vec3, direction: Vec3, max_distance: f32) -> Option<Vec3> {
        let dir = direction.try_normalize()?;
        let above = |t: f32| {
            let p = origin + dir * t;
            p.y - self.height_at(Vec2::new(p.x, p.z))
        };
        let step = (self.sample_spacing().min_element() * 0.25).max(1e-3);
        if !(max_distance.is_finite() && above(0.0) > 0.0) {
            return None;
        }
        let mut t0 = 0.0;
        while t0 < max_distance {
            let t1 = (t0 + step).min(max_distance);
            if above(t1) <= 0.0 {
                let (mut lo, mut hi) = (t0, t1);
                for _ in 0..24 {
                    let mid = 0.5 * (lo + hi);
                    if above(mid) > 0.0 { lo = mid } else { hi = mid }
                }
                let p = origin + dir * hi;
                return self.contains(Vec2::new(p.x, p.z)).then_some(p);
            }
            t0 = t1;
        }
        None
    }

    /// Grass density in `[0, 1]` at (x, z), bilinear.
    pub fn density_at(&self, xz: Vec2) -> f32 {
        let uv = self.uv(xz);
        self.density.bilinear(uv.x, uv.y)
    }

    /// Covering ID at (x, z), nearest sample.
    pub fn covering_at(&self, xz: Vec2) -> u8 {
        let uv = self.uv(xz);
        self.covering.nearest(uv.x, uv.y)
    }

    /// Metres between heightmap samples along x and z.
    pub fn sample_spacing(&self) -> Vec2 {
        self.size
            / Vec2::new(
                (self.heights.width() - 1) as f32,
                (self.heights.height() - 1) as f32,
            )
    }

    /// Lowest and highest ground height.
    pub fn height_range(&self) -> (f32, f32) {
        self.heights
            .data()
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    }

    /// The heightmap (metres).
    pub fn heights(&self) -> &Grid<f32> {
        &self.heights
    }

    /// The density map.
    pub fn density(&self) -> &Grid<f32> {
        &self.density
    }

    /// The covering map.
    pub fn covering(&self) -> &Grid<u8> {
        &self.covering
    }
}

fn validate(c: &TerrainConfig) -> Result<()> {
    for (k, v) in [
        ("terrain.size[0]", c.size[0]),
        ("terrain.size[1]", c.size[1]),
    ] {
        if !(v.is_finite() && v > 0.0 && v <= MAX_TERRAIN_SIZE) {
            return Err(Error::param(
                k,
                v,
                format!("metres in (0, {MAX_TERRAIN_SIZE}]"),
            ));
        }
    }
    if !(c.max_height.is_finite() && (0.0..=10_000.0).contains(&c.max_height)) {
        return Err(Error::param(
            "terrain.max_height",
            c.max_height,
            "metres in [0, 10000]",
        ));
    }
    if !(c.samples_per_metre.is_finite()
        && c.samples_per_metre > 0.0
        && c.samples_per_metre <= 100.0)
    {
        return Err(Error::param(
            "terrain.samples_per_metre",
            c.samples_per_metre,
            "a number in (0, 100]",
        ));
    }
    for (name, src) in [
        ("terrain.height", &c.height),
        ("terrain.density", &c.density),
    ] {
        match src {
            MapSource::Constant { value }
                if !(value.is_finite() && (0.0..=1.0).contains(value)) =>
            {
                return Err(Error::param(
                    format!("{name}.value"),
                    value,
                    "a number in [0, 1]",
                ));
            }
            MapSource::Procedural {
                frequency,
                octaves,
                range,
                power,
            } => {
                if !(frequency.is_finite() && *frequency > 0.0 && *frequency <= 100.0) {
                    return Err(Error::param(
                        format!("{name}.frequency"),
                        frequency,
                        "features per metre in (0, 100]",
                    ));
                }
                if !(1..=16).contains(octaves) {
                    return Err(Error::param(format!("{name}.octaves"), octaves, "1..=16"));
                }
                if !range
                    .iter()
                    .all(|v| v.is_finite() && (0.0..=1.0).contains(v))
                    || range[0] > range[1]
                {
                    return Err(Error::param(
                        format!("{name}.range"),
                        format!("{range:?}"),
                        "[min, max] with 0 <= min <= max <= 1",
                    ));
                }
                if !(power.is_finite() && *power > 0.0 && *power <= 16.0) {
                    return Err(Error::param(
                        format!("{name}.power"),
                        power,
                        "a number in (0, 16]",
                    ));
                }
            }
            _ => {}
        }
    }
    if let CoveringSource::Procedural {
        gaps,
        trees,
        stones,
        frequency,
    } = &c.covering
    {
        for (k, v) in [("gaps", gaps), ("trees", trees), ("stones", stones)] {
            if !(v.is_finite() && (0.0..1.0).contains(v)) {
                return Err(Error::param(
                    format!("terrain.covering.{k}"),
                    v,
                    "a fraction in [0, 1)",
                ));
            }
        }
        if !(frequency.is_finite() && *frequency > 0.0 && *frequency <= 100.0) {
            return Err(Error::param(
                "terrain.covering.frequency",
                frequency,
                "features per metre in (0, 100]",
            ));
        }
    }
    Ok(())
}

/// Maps whose aspect ratio differs from the terrain's by more than 2 % would stretch: refuse.
fn check_aspect(name: &str, w: usize, h: usize, size: Vec2) -> Result<()> {
    if w <= 2 && h <= 2 {
        return Ok(()); // constant maps
    }
    let map = (w - 1) as f32 / (h - 1) as f32;
    let terrain = size.x / size.y;
    if (map / terrain - 1.0).abs() > 0.02 {
        return Err(Error::param(
            name,
            format!("a {w}x{h} map"),
            format!(
                "a map with the terrain's aspect ratio ({:.3}, terrain {} x {} m): resize the map or change terrain.size",
                terrain, size.x, size.y
            ),
        ));
    }
    Ok(())
}

fn scalar_map(
    src: &MapSource,
    name: &str,
    seed: u64,
    size: Vec2,
    w: usize,
    h: usize,
    base: &Path,
) -> Result<Grid<f32>> {
    Ok(match src {
        MapSource::Constant { value } => Grid::filled(2, 2, *value),
        MapSource::Procedural {
            frequency,
            octaves,
            range,
            power,
        } => Grid::from_fn(w, h, |i, j| {
            let x = i as f32 / (w - 1) as f32 * size.x;
            let z = j as f32 / (h - 1) as f32 * size.y;
            let n = noise::fbm(seed, x * frequency, z * frequency, *octaves, 0.5).powf(*power);
            range[0] + (range[1] - range[0]) * n
        }),
        MapSource::Png { path } => png::load_scalar(&base.join(path)).map_err(|e| match e {
            Error::InvalidFile { path, message } => Error::InvalidFile {
                path,
                message: format!("{name}: {message}"),
            },
            e => e,
        })?,
    })
}

fn covering_map(
    src: &CoveringSource,
    seed: u64,
    size: Vec2,
    w: usize,
    h: usize,
    base: &Path,
) -> Result<Grid<u8>> {
    Ok(match src {
        CoveringSource::Grass => Grid::filled(2, 2, covering::GRASS),
        CoveringSource::Procedural {
            gaps,
            trees,
            stones,
            frequency,
        } => Grid::from_fn(w, h, |i, j| {
            let x = i as f32 / (w - 1) as f32 * size.x;
            let z = j as f32 / (h - 1) as f32 * size.y;
            let r = crate::rng::hash_f32(seed, &[i as i64, j as i64]);
            if noise::fbm(seed, x * frequency, z * frequency, 3, 0.5) < gap_threshold(*gaps) {
                covering::NONE
            } else if r < *trees {
                covering::TREE
            } else if r < trees + stones {
                covering::STONE
            } else {
                covering::GRASS
            }
        }),
        CoveringSource::Png { path } => png::load_covering(&base.join(path))?,
    })
}

/// fBm values concentrate around 0.5; this maps a wanted bare fraction to a noise threshold
/// (measured: the fraction of 3-octave fBm samples under t is close to a smoothstep around 0.5).
fn gap_threshold(fraction: f32) -> f32 {
    if fraction <= 0.0 {
        return -1.0;
    }
    0.5 + (fraction - 0.5) * 0.45
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_hit_the_ground_where_it_is() {
        let terrain = hills();
        // Straight down onto every kind of slope: the hit is the ground under the origin.
        // The terrain is centred on the origin: 60 x 40 m spans x in [-30, 30], z in [-20, 20].
        for xz in [
            Vec2::new(-25.0, -13.0),
            Vec2::new(1.5, 2.25),
            Vec2::new(25.0, 18.0),
        ] {
            let origin = Vec3::new(xz.x, 50.0, xz.y);
            let hit = terrain.raycast(origin, Vec3::NEG_Y, 100.0).unwrap();
            assert!(
                (hit - terrain.point_at(xz)).length() < 1e-3,
                "{hit} vs {xz}"
            );
        }
        // A slanted ray ends on the ground, and nothing above the ground lies before it.
        let origin = Vec3::new(-20.0, 8.0, -10.0);
        let dir = Vec3::new(1.0, -0.2, 0.6).normalize();
        let hit = terrain.raycast(origin, dir, 200.0).unwrap();
        assert!((hit.y - terrain.height_at(Vec2::new(hit.x, hit.z))).abs() < 1e-3);
        let d = (hit - origin).length();
        for k in 0..100 {
            let p = origin + dir * (d * k as f32 / 100.0);
            assert!(
                p.y >= terrain.height_at(Vec2::new(p.x, p.z)) - 1e-3,
                "under ground at {p}"
            );
        }
        // Misses: looking up, too short, starting underground, leaving the terrain.
        assert_eq!(terrain.raycast(origin, Vec3::Y, 100.0), None);
        assert_eq!(terrain.raycast(origin, dir, 0.5), None);
        assert_eq!(
            terrain.raycast(Vec3::new(5.0, -10.0, 5.0), Vec3::NEG_Y, 100.0),
            None
        );
        assert_eq!(
            terrain.raycast(origin, Vec3::new(-1.0, -0.01, 0.0), 100.0),
            None
        );
        assert_eq!(
            terrain.raycast(Vec3::new(40.0, 10.0, 0.0), Vec3::NEG_Y, 100.0),
            None
        );
    }

    fn hills() -> Terrain {
        let config = TerrainConfig {
            size: [60.0, 40.0],
            max_height: 3.0,
            samples_per_metre: 1.0,
            height: MapSource::Procedural {
                frequency: 0.05,
                octaves: 3,
                range: [0.0, 1.0],
                power: 1.0,
            },
            density: MapSource::one(),
            covering: CoveringSource::Procedural {
                gaps: 0.1,
                trees: 0.01,
                stones: 0.01,
                frequency: 0.05,
            },
        };
        Terrain::build(&config, 42, Path::new(".")).unwrap()
    }

    #[test]
    fn height_matches_samples_and_interpolates() {
        let t = hills();
        let spacing = t.sample_spacing();
        let corner = t.min_corner();
        let h = t.heights();
        assert_eq!(t.height_at(corner), h.get(0, 0));
        let p = corner + spacing * Vec2::new(3.0, 2.0);
        assert!((t.height_at(p) - h.get(3, 2)).abs() < 1e-4);
        let mid = corner + spacing * Vec2::new(3.5, 2.0);
        assert!((t.height_at(mid) - 0.5 * (h.get(3, 2) + h.get(4, 2))).abs() < 1e-4);
        let (lo, hi) = t.height_range();
        assert!(lo >= 0.0 && hi <= 3.0 && hi > lo);
    }

    #[test]
    fn normals_are_unit_and_tilt_downhill() {
        let t = hills();
        for k in 0..50 {
            let xz = Vec2::new(-25.0 + k as f32, -15.0 + 0.5 * k as f32);
            let n = t.normal_at(xz);
            assert!((n.length() - 1.0).abs() < 1e-5 && n.y > 0.5);
            // Moving a little along the normal's horizontal part goes downhill.
            let step = Vec2::new(n.x, n.z) * 0.05;
            if step.length() > 1e-3 {
                assert!(t.height_at(xz + step) <= t.height_at(xz) + 1e-4);
            }
        }
        let flat = Terrain::flat(Vec2::splat(10.0));
        assert_eq!(flat.normal_at(Vec2::ZERO), Vec3::Y);
    }

    #[test]
    fn covering_has_gaps_and_only_valid_ids() {
        let t = hills();
        let data = t.covering().data();
        assert!(data.iter().all(|&v| covering::is_valid(v)));
        let bare = data.iter().filter(|&&v| v == covering::NONE).count() as f32 / data.len() as f32;
        assert!(bare > 0.0 && bare < 0.4, "bare fraction {bare}");
    }

    #[test]
    fn rejects_nan_and_absurd_sizes() {
        let mut c = TerrainConfig {
            size: [f32::NAN, 10.0],
            max_height: 1.0,
            samples_per_metre: 1.0,
            height: MapSource::default(),
            density: MapSource::one(),
            covering: CoveringSource::Grass,
        };
        let e = Terrain::build(&c, 0, Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.contains("terrain.size[0]"), "{e}");
        c.size = [1e9, 10.0];
        assert!(Terrain::build(&c, 0, Path::new(".")).is_err());
        c.size = [10.0, 10.0];
        c.density = MapSource::Constant { value: 2.0 };
        let e = Terrain::build(&c, 0, Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.contains("terrain.density.value"), "{e}");
    }
}
