//! The fluid solver as a [`WindField`]: world positions mapped to grid coordinates (tiled per
//! grass grid as in Zhang Sec. 5.1, or stretched over the terrain), trilinear sampling
//! (Sec. 3.2.2) and sub-stepped advancing.

use glam::{Vec2, Vec3};

use super::config::{FluidConfig, FluidMapping, MAX_SUBSTEPS};
use super::solver::StamSolver;
use crate::Result;
use crate::rng::hash_f32;
use crate::terrain::{Grid, Terrain};
use crate::wind::WindField;

/// Stam's stable fluids over a terrain.
///
/// World `x`, height above the ground and world `z` map to grid axes `i`, `j` (up) and `k`.
/// Horizontally, [`FluidMapping::Tiled`] cuts the plane into `tile_size` squares from the
/// terrain's min corner; tile `(a, b)` reads the solution at its local position shifted by a
/// seeded offset of up to `tile_offset` tiles per axis, wrapped into the tile (Sec. 5.1: "we
/// offset the location of each grass grid by a random value"). [`FluidMapping::Stretched`]
/// spans the terrain with the one grid. Vertically the grid covers `height` metres above the
/// ground (terrain-following: the thesis' ground is flat). Positions outside the grid read
/// its wall cells. Velocity = grid velocity (domain lengths / s) × `speed_scale`.
///
/// The field depends on its step history, not on the `time` passed to
/// [`WindField::velocity`]: [`WindField::advance`] is what moves it on.
#[derive(Clone, Debug)]
pub struct FluidWind {
    config: FluidConfig,
    solver: StamSolver,
    ground: Grid<f32>,
    min_corner: Vec2,
    size: Vec2,
    seed: u64,
    /// Offsets of the tiles over the terrain (row-major, `tiles.0` per row), so sampling
    /// hashes only for tiles beyond it.
    offsets: Vec<Vec2>,
    tiles: (i64, i64),
}

impl FluidWind {
    /// A fluid at rest over `terrain`; `seed` drives the source and the tile offsets.
    pub fn new(config: FluidConfig, seed: u64, terrain: &Terrain) -> Result<Self> {
        config.validate()?;
        let solver = StamSolver::new(config.solver_params(seed ^ 0x46_4c55_4944))?;
        let (tiles, offsets) = match config.mapping {
            FluidMapping::Stretched => ((0, 0), Vec::new()),
            FluidMapping::Tiled => {
                let count = |s: f32| ((s / config.tile_size).ceil() as i64 + 1).clamp(1, 4096);
                let tiles = (count(terrain.size().x), count(terrain.size().y));
                let offsets = (0..tiles.1)
                    .flat_map(|b| (0..tiles.0).map(move |a| (a, b)))
                    .map(|(a, b)| tile_offset(seed, a, b, config.tile_offset))
                    .collect();
                (tiles, offsets)
            }
        };
        Ok(Self {
            offsets,
            tiles,
            config,
            solver,
            ground: terrain.heights().clone(),
            min_corner: terrain.min_corner(),
            size: terrain.size(),
            seed,
        })
    }

    /// The solver (read-only: for inspection and tests).
    pub fn solver(&self) -> &StamSolver {
        &self.solver
    }

    /// The configuration.
    pub fn config(&self) -> &FluidConfig {
        &self.config
    }

    /// Continuous grid coordinates of world point `p` (cell centres at integers `1..=N`).
    pub fn grid_coords(&self, p: Vec3) -> Vec3 {
        let c = &self.config;
        let xz = Vec2::new(p.x, p.z);
        let uv = (xz - self.min_corner) / self.size;
        let ground = self.ground.bilinear(uv.x, uv.y);
        let local = match c.mapping {
            FluidMapping::Stretched => uv,
            FluidMapping::Tiled => {
                let q = (xz - self.min_corner) / c.tile_size;
                let tile = q.floor();
                let (a, b) = (tile.x as i64, tile.y as i64);
                let offset = if (0..self.tiles.0).contains(&a) && (0..self.tiles.1).contains(&b) {
                    self.offsets[(b * self.tiles.0 + a) as usize]
                } else {
                    tile_offset(self.seed, a, b, c.tile_offset)
                };
                (q - tile + offset).fract_gl()
            }
        };
        let n = self.solver.n() as f32;
        let h = (p.y - ground) / c.height;
        Vec3::new(local.x, h, local.y) * n + Vec3::splat(0.5)
    }
}

/// The seeded sampling offset of tile `(a, b)`, in tiles.
fn tile_offset(seed: u64, a: i64, b: i64, max: f32) -> Vec2 {
    Vec2::new(hash_f32(seed, &[a, b, 0]), hash_f32(seed, &[a, b, 1])) * max
}

impl WindField for FluidWind {
    fn name(&self) -> &'static str {
        "fluid"
    }

    /// Steps the solver by `dt` (in up to [`MAX_SUBSTEPS`] steps of at most `max_substep`);
    /// a `dt` that is not a positive finite number leaves the field unchanged.
    fn advance(&mut self, _time: f32, dt: f32) {
        if !(dt.is_finite() && dt > 0.0) {
            return;
        }
        let steps = ((dt / self.config.max_substep).ceil() as u32).clamp(1, MAX_SUBSTEPS);
        let h = dt / steps as f32;
        for _ in 0..steps {
            self.solver.step(h);
        }
    }

    fn velocity(&self, p: Vec3, _time: f32) -> Vec3 {
        self.solver.velocity_at(self.grid_coords(p)) * self.config.speed_scale
    }

    fn is_stateless(&self) -> bool {
        false
    }

    fn velocities(&self, points: &[Vec3], _time: f32, out: &mut [Vec3]) {
        for (o, p) in out.iter_mut().zip(points) {
            *o = self.solver.velocity_at(self.grid_coords(*p)) * self.config.speed_scale;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn terrain() -> Terrain {
        Terrain::flat(Vec2::new(80.0, 80.0))
    }

    fn field(f: impl FnOnce(&mut FluidConfig)) -> FluidWind {
        let mut c = FluidConfig::default();
        f(&mut c);
        FluidWind::new(c, 7, &terrain()).unwrap()
    }

    /// Mean and largest speed (m/s) over a 40 x 40 lattice of ground points at three heights
    /// in the grass layer.
    fn speeds(w: &FluidWind) -> (f32, f32) {
        let (mut sum, mut max, mut k) = (0.0, 0.0f32, 0);
        for i in 0..40 {
            for j in 0..40 {
                for y in [0.1f32, 0.3, 0.5] {
                    let p = Vec3::new(i as f32 * 2.0 - 39.0, y, j as f32 * 2.0 - 39.0);
                    let v = w.velocity(p, 0.0).length();
                    sum += v;
                    max = max.max(v);
                    k += 1;
                }
            }
        }
        (sum / k as f32, max)
    }

    /// The defaults (viscosity 0.5, source 500 grid units/s², speed scale 30) give a breeze:
    /// measured mean / max speed in the grass layer every 100 frames over 30 s at 30 fps:
    /// mean 0.40 … 2.83 m/s, max 1.9 … 6.1 m/s. The bounds leave ~2x room and catch a field
    /// that stays at rest or blows up.
    #[test]
    fn defaults_give_a_breeze_and_stay_bounded() {
        let mut w = field(|_| {});
        assert!(!w.is_stateless());
        assert_eq!(speeds(&w), (0.0, 0.0));
        let mut means = Vec::new();
        for frame in 0..900 {
            w.advance(frame as f32 / 30.0, 1.0 / 30.0);
            if frame % 100 == 99 {
                let (mean, max) = speeds(&w);
                assert!(max < 15.0, "frame {frame}: max {max}");
                means.push(mean);
            }
        }
        let avg = means.iter().sum::<f32>() / means.len() as f32;
        assert!((0.5..5.0).contains(&avg), "mean speeds {means:?}");
    }

    #[test]
    fn same_seed_same_field_and_long_frames_are_substepped() {
        let run = |dt: f32, frames: u32, seed: u64| {
            let mut w = FluidWind::new(FluidConfig::default(), seed, &terrain()).unwrap();
            for f in 0..frames {
                w.advance(f as f32 * dt, dt);
            }
            w.velocity(Vec3::new(1.0, 0.3, 2.0), 0.0)
        };
        assert_eq!(run(1.0 / 30.0, 60, 1), run(1.0 / 30.0, 60, 1));
        assert_ne!(run(1.0 / 30.0, 60, 1), run(1.0 / 30.0, 60, 2));
        // One 0.2 s frame = 6 solver steps, like six 1/30 s frames (same sources, same dt up
        // to rounding).
        let long = run(0.2, 1, 1);
        let short = run(1.0 / 30.0, 6, 1);
        assert!(
            (long - short).length() <= 1e-3 * short.length().max(1e-3),
            "{long} {short}"
        );
        // Bad dt: no change.
        let mut w = field(|_| {});
        w.advance(0.0, 0.1);
        let v = w.velocity(Vec3::ZERO, 0.0);
        for dt in [f32::NAN, -1.0, 0.0, f32::INFINITY] {
            w.advance(0.0, dt);
        }
        assert_eq!(v, w.velocity(Vec3::ZERO, 0.0));
    }

    #[test]
    fn tiles_repeat_the_solution_with_their_offsets() {
        let mut same = field(|c| c.tile_offset = 0.0);
        let mut shifted = field(|_| {});
        for f in 0..30 {
            same.advance(f as f32 / 30.0, 1.0 / 30.0);
            shifted.advance(f as f32 / 30.0, 1.0 / 30.0);
        }
        let p = Vec3::new(-38.2, 0.3, -36.9);
        let next = p + Vec3::new(5.0, 0.0, 10.0); // one tile right, two tiles on
        // Equal up to the rounding of world coordinates (f32 at 40 m: ~4e-6 m).
        let (a, b) = (same.velocity(p, 0.0), same.velocity(next, 0.0));
        assert!((a - b).length() < 1e-5 * a.length().max(1.0), "{a} {b}");
        assert!((same.grid_coords(p) - same.grid_coords(next)).length() < 1e-4);
        let d = (shifted.grid_coords(p) - shifted.grid_coords(next)).length();
        assert!(d > 0.1, "offset tiles read the same cell ({d})");
        // Within a tile, local coordinates span the grid: cell centres 1..=N at the tile's
        // (unshifted) cell centres, height measured from the ground.
        let g = same.grid_coords(Vec3::new(-40.0 + 5.0 / 16.0, 0.0, -40.0));
        assert!((g - Vec3::new(1.0, 0.5, 0.5)).length() < 1e-4, "{g}");
        let top = same.grid_coords(Vec3::new(-40.0, 1.0, -40.0));
        assert!((top.y - 8.5).abs() < 1e-4);
    }

    #[test]
    fn stretched_spans_the_terrain() {
        let w = field(|c| c.mapping = FluidMapping::Stretched);
        let lo = w.grid_coords(Vec3::new(-40.0, 0.0, -40.0));
        let hi = w.grid_coords(Vec3::new(40.0, 1.0, 40.0));
        assert!((lo - Vec3::splat(0.5)).length() < 1e-4, "{lo}");
        assert!((hi - Vec3::splat(8.5)).length() < 1e-4, "{hi}");
    }

    #[test]
    fn scene_toml_selects_the_fluid_and_bad_keys_are_named() {
        let ok: crate::wind::WindConfig =
            toml::from_str("model = \"fluid\"\nn = 16\nmapping = \"stretched\"").unwrap();
        ok.validate().unwrap();
        let built = crate::wind::build(&ok, 1, &terrain(), None).unwrap();
        assert_eq!(built.name(), "fluid");
        assert!(!built.is_stateless());
        for (text, key) in [
            ("n = 0", "wind.n"),
            ("n = 4\nsource_cell = [1, 5, 1]", "wind.source_cell[1]"),
            ("viscosity = nan", "wind.viscosity"),
            ("speed_scale = -1.0", "wind.speed_scale"),
            ("tile_size = inf", "wind.tile_size"),
            ("max_substep = 0.0", "wind.max_substep"),
            ("iterations = 0", "wind.iterations"),
        ] {
            let c: crate::wind::WindConfig =
                toml::from_str(&format!("model = \"fluid\"\n{text}")).unwrap();
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains(&format!("`{key}`")), "{text}: {e}");
        }
        assert!(toml::from_str::<crate::wind::WindConfig>("model = \"fluid\"\nnn = 3").is_err());
        assert!(
            toml::from_str::<crate::wind::WindConfig>("model = \"fluid\"\nmapping = \"tilted\"")
                .is_err()
        );
    }
}
