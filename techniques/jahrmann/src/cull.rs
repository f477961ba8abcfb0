//! What the compute pass decides for each blade after simulating it, on the CPU: the twin of
//! the shader's `cull` (the paper's three culling tests, then Ghost of Tsushima's level), and
//! of the hand-over weights the vertex shader applies (`band_weight`, `width_scale`).
//!
//! Tests run in the paper's order, cheapest first, and a culled blade is counted by the first
//! test that culls it:
//! - **orientation**: culled when `|view · width| > threshold` (seen edge-on), the view
//!   direction running from the eye to the root;
//! - **frustum**: culled when the root, the midpoint `m = ¼v0 + ½v1 + ¼v2` and the tip all lie
//!   more than `frustum_tolerance` metres outside one of the frustum's planes (the planes of
//!   `grassbench::camera::Frustum`, normalised, so the tolerance is a distance);
//! - **distance**: blades fall into `n` buckets by a hash of their index; bucket `k` is kept
//!   up to the ground distance `D_k = d_max·(1 − k/n)`, so the first `d_max / n` metres keep
//!   every blade and density then falls by one bucket per `d_max / n` metres; beyond
//!   `thin_distance` `D` (not in the paper), blade `id` is also dropped beyond `D / √u(id)`,
//!   `u` a second hash in `[0, 1)`, so a fraction `(D / d)²` is kept at distance `d` (the
//!   blades per pixel stay about constant) and those kept widen by `(d / D)²`;
//! - **level**: the ground is cut into square tiles of `tile_size` metres (Ghost of Tsushima
//!   chooses levels per tile); a tile whose centre is nearer than `lod_distance` (plus the
//!   hand-over band with transitions) draws its blades at the near level; beyond, one blade in
//!   `far_keep` (by another hash) is drawn at the far level, widened, and stands for the
//!   others, which are not drawn. A tile size of 0 chooses per blade, by its root.

use grassbench::glam::{Vec2, Vec3, Vec4};
use grassbench::rng::hash_u32;

use crate::Params;
use crate::sim::width_dir;

/// What became of a blade this frame (the shader's verdict codes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[repr(u32)]
pub enum Verdict {
    /// Drawn at the near level (15 vertices).
    Near = 0,
    /// Drawn at the far level (7 vertices), standing for the far blades not drawn.
    Far = 1,
    /// Beyond the hand-over and not among the far level's survivors: stood for by them.
    Represented = 2,
    /// Culled as seen edge-on.
    Orientation = 3,
    /// Culled outside the view frustum.
    Frustum = 4,
    /// Dropped by distance.
    Distance = 5,
}

impl Verdict {
    /// The verdict of the shader's code `code`.
    pub fn from_code(code: u32) -> Option<Self> {
        Some(match code {
            0 => Self::Near,
            1 => Self::Far,
            2 => Self::Represented,
            3 => Self::Orientation,
            4 => Self::Frustum,
            5 => Self::Distance,
            _ => return None,
        })
    }
}

/// Salt that makes the far level's choice of survivors independent of the distance buckets.
pub const SURVIVOR_SALT: u32 = 0x68bc_21eb;
/// Salt of the hash that thins blades beyond `thin_distance`.
pub const THIN_SALT: u32 = 0x2f6b_9d45;

/// The culling and level settings of [`Params`], as the shader reads them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CullSettings {
    /// Orientation test on.
    pub orientation: bool,
    /// `|view · width|` above which a blade is culled.
    pub orientation_threshold: f32,
    /// Frustum test on.
    pub frustum: bool,
    /// Tolerance outside the planes, m.
    pub frustum_tolerance: f32,
    /// Distance test on.
    pub distance: bool,
    /// `d_max`, m.
    pub cull_distance: f32,
    /// `n`.
    pub buckets: u32,
    /// Where the distance test starts thinning as `(D / d)²`, m (0: never).
    pub thin_distance: f32,
    /// Two levels on.
    pub lod: bool,
    /// Side of the tiles levels are chosen for, m (0: per blade).
    pub tile_size: f32,
    /// Where the far level begins, m.
    pub lod_distance: f32,
    /// One far blade in `far_keep` is drawn.
    pub far_keep: u32,
    /// Hand-overs blended.
    pub transitions: bool,
    /// Depth of the near-to-far band, m.
    pub band: f32,
    /// Distance over which a blade narrows before distance culling drops it, m.
    pub distance_fade: f32,
    /// Range of `|view · width|` over which a blade narrows before orientation culling.
    pub orientation_fade: f32,
    /// Width factor of the far level.
    pub far_widen: f32,
}

impl CullSettings {
    /// The settings of `params`.
    pub fn of(params: &Params) -> Self {
        Self {
            orientation: params.orientation_culling,
            orientation_threshold: params.orientation_threshold,
            frustum: params.frustum_culling,
            frustum_tolerance: params.frustum_tolerance,
            distance: params.distance_culling,
            cull_distance: params.cull_distance,
            buckets: params.buckets,
            thin_distance: params.thin_distance,
            lod: params.lod,
            tile_size: params.tile_size,
            lod_distance: params.lod_distance,
            far_keep: params.far_keep,
            transitions: params.transitions,
            band: params.band,
            distance_fade: params.distance_fade,
            orientation_fade: params.orientation_fade,
            far_widen: params.far_widen,
        }
    }

    /// Distance from the eye where blades leave the near level, m.
    pub fn far_start(&self) -> f32 {
        self.lod_distance + if self.transitions { self.band } else { 0.0 }
    }

    /// Ground distance within which the distance test keeps every blade (the first bucket).
    pub fn first_bucket(&self) -> f32 {
        self.cull_distance / self.buckets.max(1) as f32
    }

    /// Ground distance within which the distance test keeps every blade: the first bucket,
    /// and not beyond the thinning distance.
    pub fn keeps_every_blade_within(&self) -> f32 {
        if self.thin_distance > 0.0 {
            self.first_bucket().min(self.thin_distance)
        } else {
            self.first_bucket()
        }
    }
}

/// The distance bucket of blade `id`.
pub fn bucket(id: u32, buckets: u32) -> u32 {
    hash_u32(id) % buckets.max(1)
}

/// Whether blade `id` is one the far level keeps.
pub fn survivor(id: u32, far_keep: u32) -> bool {
    hash_u32(id ^ SURVIVOR_SALT).is_multiple_of(far_keep.max(1))
}

/// Ground distance up to which the distance test keeps blade `id`, m: its bucket's, and
/// `D / √u` beyond the thinning distance `D` (`u` the blade's [`thin_hash`]).
pub fn distance_cutoff(id: u32, s: &CullSettings) -> f32 {
    let n = s.buckets.max(1);
    let cutoff = s.cull_distance * (1.0 - bucket(id, n) as f32 / n as f32);
    if s.thin_distance > 0.0 {
        cutoff.min(s.thin_distance / thin_hash(id).sqrt())
    } else {
        cutoff
    }
}

/// Blade `id`'s thinning hash in `[0, 1)` (exact in `f32`: the top 24 bits).
pub fn thin_hash(id: u32) -> f32 {
    (hash_u32(id ^ THIN_SALT) >> 8) as f32 / (1u32 << 24) as f32
}

/// The width factor that makes up for the thinning at ground distance `d`: `(d / D)²`
/// beyond `D`, 1 nearer (and without the distance test or thinning).
pub fn thin_widen(d: f32, s: &CullSettings) -> f32 {
    if s.distance && s.thin_distance > 0.0 && d > s.thin_distance {
        (d / s.thin_distance).powi(2)
    } else {
        1.0
    }
}

/// Horizontal distance from the eye to the root (the paper's `d_proj`, up being vertical).
pub fn ground_distance(v0: Vec3, eye: Vec3) -> f32 {
    let d = v0 - eye;
    (d - Vec3::Y * d.dot(Vec3::Y)).length()
}

/// `|view · width|`: 1 when the blade is seen exactly edge-on, 0 face-on; 0 at the eye.
pub fn edge_on(v0: Vec3, orientation: f32, eye: Vec3) -> f32 {
    let d = v0 - eye;
    let len = d.length();
    if len < 1e-6 {
        return 0.0;
    }
    (d / len).dot(width_dir(orientation)).abs()
}

/// Whether `p` lies inside every plane of `planes` (inside: `n·p + d ≥ 0`), give or take
/// `tolerance`.
pub fn in_frustum(p: Vec3, planes: &[Vec4; 6], tolerance: f32) -> bool {
    planes
        .iter()
        .all(|pl| pl.truncate().dot(p) + pl.w >= -tolerance)
}

/// The distance from the eye that chooses a root's level: that of its tile's centre (at the
/// root's height), or of the root itself when tiles are off.
pub fn level_distance(v0: Vec3, eye: Vec3, tile_size: f32) -> f32 {
    if tile_size <= 0.0 {
        return v0.distance(eye);
    }
    let centre = ((Vec2::new(v0.x, v0.z) / tile_size).floor() + 0.5) * tile_size;
    Vec3::new(centre.x, v0.y, centre.y).distance(eye)
}

/// The curve's midpoint the frustum test uses.
pub fn midpoint(v0: Vec3, v1: Vec3, v2: Vec3) -> Vec3 {
    v0 * 0.25 + v1 * 0.5 + v2 * 0.25
}

/// The verdict on blade `id` with curve `v0, v1, v2` and width direction `orientation`, seen
/// from `eye` through `planes`.
pub fn verdict(
    id: u32,
    (v0, v1, v2): (Vec3, Vec3, Vec3),
    orientation: f32,
    eye: Vec3,
    planes: &[Vec4; 6],
    s: &CullSettings,
) -> Verdict {
    if s.orientation && edge_on(v0, orientation, eye) > s.orientation_threshold {
        return Verdict::Orientation;
    }
    if s.frustum {
        let tol = s.frustum_tolerance;
        let m = midpoint(v0, v1, v2);
        if !(in_frustum(v0, planes, tol)
            || in_frustum(m, planes, tol)
            || in_frustum(v2, planes, tol))
        {
            return Verdict::Frustum;
        }
    }
    if s.distance && ground_distance(v0, eye) > distance_cutoff(id, s) {
        return Verdict::Distance;
    }
    if s.lod && level_distance(v0, eye, s.tile_size) >= s.far_start() {
        return if survivor(id, s.far_keep) {
            Verdict::Far
        } else {
            Verdict::Represented
        };
    }
    Verdict::Near
}

/// How far through the near-to-far band a root whose level distance
/// ([`level_distance`]) is `distance` is: 0 before it, 1 at its end (smoothstep); 0
/// everywhere without levels or transitions.
pub fn band_weight(distance: f32, s: &CullSettings) -> f32 {
    if !(s.lod && s.transitions) {
        return 0.0;
    }
    smoothstep(s.lod_distance, s.lod_distance + s.band, distance)
}

/// WGSL's `smoothstep` (a band of zero width is a step at `high`).
pub fn smoothstep(low: f32, high: f32, x: f32) -> f32 {
    if high <= low {
        return if x < high { 0.0 } else { 1.0 };
    }
    let t = ((x - low) / (high - low)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The factor on blade `id`'s width as drawn at the near level (`far = false`) or the far
/// level: the survivors widen and the others narrow across the band, and with transitions
/// every blade narrows to nothing before the distance or orientation test drops it.
pub fn width_scale(
    id: u32,
    v0: Vec3,
    orientation: f32,
    eye: Vec3,
    far: bool,
    s: &CullSettings,
) -> f32 {
    let mut scale = thin_widen(ground_distance(v0, eye), s);
    scale *= if far {
        s.far_widen
    } else {
        let b = band_weight(level_distance(v0, eye, s.tile_size), s);
        if survivor(id, s.far_keep) {
            1.0 + (s.far_widen - 1.0) * b
        } else {
            1.0 - b
        }
    };
    if s.transitions {
        if s.distance && s.distance_fade > 0.0 {
            let left = distance_cutoff(id, s) - ground_distance(v0, eye);
            scale *= (left / s.distance_fade).clamp(0.0, 1.0);
        }
        if s.orientation && s.orientation_fade > 0.0 {
            let left = s.orientation_threshold - edge_on(v0, orientation, eye);
            scale *= (left / s.orientation_fade).clamp(0.0, 1.0);
        }
    }
    scale
}

#[cfg(test)]
mod tests {
    use super::*;
    use grassbench::camera::Camera;

    fn settings() -> CullSettings {
        CullSettings::of(&Params::default())
    }

    #[test]
    fn buckets_thin_density_linearly_and_keep_the_first_bucket_whole() {
        let s = CullSettings {
            thin_distance: 0.0,
            ..settings()
        };
        let ids = 0..40_000u32;
        let kept_at = |d: f32| {
            ids.clone()
                .filter(|&id| d <= distance_cutoff(id, &s))
                .count() as f32
                / 40_000.0
        };
        assert_eq!(kept_at(s.first_bucket() * 0.99), 1.0);
        // Half-way to d_max, buckets 0..=n/2 (5 of 8) are kept; a hash fills each bucket
        // with an eighth of the blades give or take its spread (40 000 blades: a bucket holds
        // 5 000 ± 70, so the share is within 0.01).
        assert!((kept_at(s.cull_distance * 0.5) - 5.0 / 8.0).abs() < 0.01);
        assert!((kept_at(s.cull_distance * 0.99) - 1.0 / 8.0).abs() < 0.01);
        assert_eq!(kept_at(s.cull_distance * 1.01), 0.0);
        // One blade in far_keep survives the far level (measured 0.2489 over 40 000).
        let survivors = (0..40_000u32).filter(|&id| survivor(id, 4)).count() as f32 / 40_000.0;
        assert!((survivors - 0.25).abs() < 0.01, "{survivors}");
    }

    /// Beyond `thin_distance` the kept share falls as `(D / d)²` (on top of the buckets) and
    /// the kept blades widen by its inverse, so the expected width drawn per blade of the
    /// buckets holds.
    #[test]
    fn thinning_keeps_d_squared_and_widens_by_its_inverse() {
        let s = settings();
        let plain = CullSettings {
            thin_distance: 0.0,
            ..s
        };
        let ids = 0..100_000u32;
        let share = |d: f32, s: &CullSettings| {
            ids.clone()
                .filter(|&id| d <= distance_cutoff(id, s))
                .count() as f64
        };
        assert_eq!(
            share(s.thin_distance * 0.99, &s),
            share(s.thin_distance * 0.99, &plain)
        );
        for d in [60.0, 100.0, 200.0] {
            let kept = share(d, &s) / share(d, &plain);
            let expected = f64::from((s.thin_distance / d).powi(2));
            // 100 000 blades: at 200 m about 1 700 bucket survivors, 4 % of them kept (68,
            // ± 8): within 25 % of the share; measured within 6 % at each distance.
            assert!(
                (kept / expected - 1.0).abs() < 0.25,
                "{d} m: kept {kept}, expected {expected}"
            );
            assert!((thin_widen(d, &s) * expected as f32 - 1.0).abs() < 1e-5);
        }
        assert_eq!(thin_widen(200.0, &plain), 1.0);
    }

    #[test]
    fn the_band_hands_over_without_a_jump() {
        // Per blade (the tiles' hand-over is the same, a tile's blades at once).
        let s = CullSettings {
            tile_size: 0.0,
            ..settings()
        };
        let eye = Vec3::ZERO;
        let orientation = 0.0;
        // Just before the far level: near-level survivors are as wide as far-level ones, the
        // others have narrowed to nothing.
        let v0 = Vec3::new(0.0, 0.0, s.far_start() - 1e-3);
        let (mut seen_survivor, mut seen_other) = (false, false);
        for id in 0..64 {
            let near = width_scale(id, v0, orientation, eye, false, &s);
            if survivor(id, s.far_keep) {
                let far = width_scale(id, v0, orientation, eye, true, &s);
                assert!((near - far).abs() < 1e-3, "{near} {far}");
                seen_survivor = true;
            } else {
                assert!(near < 1e-3, "{near}");
                seen_other = true;
            }
        }
        assert!(seen_survivor && seen_other);
        // Without transitions nothing narrows or widens at the near level.
        let hard = CullSettings {
            transitions: false,
            ..s
        };
        assert_eq!(width_scale(3, v0, orientation, eye, false, &hard), 1.0);
    }

    #[test]
    fn a_tiles_blades_change_level_together() {
        let s = settings();
        let eye = Vec3::new(0.3, 1.6, -0.7);
        // Two roots in one 4 m tile, one nearer than the far start and one beyond it by their
        // own distances, share the tile centre's distance.
        let tile = |x: f32, z: f32| level_distance(Vec3::new(x, 0.0, z), eye, s.tile_size);
        assert_eq!(tile(16.1, 20.2), tile(19.9, 23.9));
        assert!(Vec3::new(16.1, 0.0, 20.2).distance(eye) < 27.0);
        assert!(Vec3::new(19.9, 0.0, 23.9).distance(eye) > 30.0);
        // Without tiles, each root's own distance.
        assert_eq!(
            level_distance(Vec3::new(3.0, 0.0, 4.0), Vec3::ZERO, 0.0),
            5.0
        );
    }

    #[test]
    fn verdicts_follow_the_tests_in_order() {
        let s = settings();
        let camera = Camera::look_at(
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(0.0, 0.0, 10.0),
            1.0,
            0.1,
            500.0,
            1.6,
        );
        let planes = camera.frustum().planes;
        let eye = camera.eye;
        let curve = |x: f32, z: f32| {
            let v0 = Vec3::new(x, 0.0, z);
            (v0, v0 + Vec3::Y * 0.2, v0 + Vec3::Y * 0.4)
        };
        // Width across the view (orientation 0: along x), ahead, near: drawn near.
        let along_view = std::f32::consts::FRAC_PI_2;
        assert_eq!(
            verdict(1, curve(0.0, 5.0), 0.0, eye, &planes, &s),
            Verdict::Near
        );
        // Edge-on (width along the view): culled by orientation first, even if behind.
        assert_eq!(
            verdict(1, curve(0.0, 5.0), along_view, eye, &planes, &s),
            Verdict::Orientation
        );
        // Behind the eye: frustum.
        assert_eq!(
            verdict(1, curve(0.0, -5.0), 0.0, eye, &planes, &s),
            Verdict::Frustum
        );
        // Beyond d_max ahead: distance.
        assert_eq!(
            verdict(1, curve(0.0, 300.0), 0.0, eye, &planes, &s),
            Verdict::Distance
        );
        // Beyond the band: far level or represented, depending on the blade.
        let far: Vec<_> = (0..32)
            .map(|id| verdict(id, curve(0.0, 25.0), 0.0, eye, &planes, &s))
            .collect();
        assert!(far.contains(&Verdict::Far) && far.contains(&Verdict::Represented));
        // Everything off: every blade is drawn near, wherever it is.
        let off = CullSettings {
            orientation: false,
            frustum: false,
            distance: false,
            lod: false,
            ..s
        };
        for (x, z) in [(0.0, -5.0), (0.0, 300.0), (100.0, 25.0)] {
            assert_eq!(
                verdict(7, curve(x, z), along_view, eye, &planes, &off),
                Verdict::Near
            );
        }
    }
}
