//! The base grass patch and its four mirrored versions (Boulanger Sec. 3.1).
//!
//! One square patch of blades is generated once, with *stratified sampling*: the patch is cut
//! into `n x n` strata and one root is placed at a random point of each, so the roots are
//! uniform at every scale and no clump repeats visibly when the patch is tiled. Each blade gets
//! a density threshold drawn uniformly in `[0, 1)` (Sec. 3.4).
//!
//! The patch holds the scene's density exactly ([`PatchSpec`]): a whole number `N` of blades
//! (`ρ·size²` rounded) on the side that makes `N / side² = ρ`, and `N` need not be a square: the
//! roots take `N` of the `⌈√N⌉²` strata, chosen at random, so every stratum holds at most one
//! root. (Before issue 19 the patch held `round(√N)²` blades, a square: 4 for the 5 a 0.5 m
//! patch holds at 20 blades/m², 20 % short.) The blades are stored by
//! *block* (a `blocks x blocks` grid of square sub-patches, so the CPU can cull parts of a cell
//! that are out of view) and, within a block, sorted by threshold, so the blades a block can
//! need form one contiguous range (see [`Patch::threshold_range`]).
//!
//! Tiling is aperiodic by choosing, per grid cell, one of four mirrored versions of the patch
//! ([`Orientation`]); the data exist once and the mirroring is done on the GPU. Roots are kept
//! relative to the patch centre so a mirror is a sign flip: exact, and its own inverse.

use glam::Vec2;
use grassbench::grass::GrassConfig;
use grassbench::rng::{Rng, hash};

/// One blade of the base patch (vertex buffer, instance step), 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PatchBlade {
    /// Root (x, z) relative to the patch centre, m.
    pub root: [f32; 2],
    /// Launch azimuth of the particle (radians around y, 0 = +x).
    pub azimuth: f32,
    /// Launch angle from the vertical, radians.
    pub tilt: f32,
    /// Standing height, m.
    pub height: f32,
    /// Width, m.
    pub width: f32,
    /// Colour variation in `[-1, 1]` (age, degradation: Sec. 3.2).
    pub variation: f32,
    /// Density threshold in `[0, 1)` (Sec. 3.4).
    pub threshold: f32,
}

/// How blades are shaped, beyond the scene's height and width ranges.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BladeShape {
    /// Largest launch angle from the vertical, radians.
    pub max_tilt: f32,
}

/// The patch a density asks for (Sec. 3.1): a whole number of blades on a side near the one
/// asked for, so that the tiling holds exactly the density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchSpec {
    /// Side, m.
    pub side: f32,
    /// Blades in the patch.
    pub blades: u32,
}

impl PatchSpec {
    /// A patch of about `size` metres a side at `blades_per_m2` blades per square metre:
    /// `N = round(ρ·size²)` blades, at least one where `ρ > 0`, on the side `√(N / ρ)`, so
    /// the tiling holds `ρ` blades per square metre exactly rather than `N / size²` (at 14
    /// blades/m², 3.5 blades a 0.5 m patch: 4 blades on a 0.535 m patch rather than 4 on 0.5 m,
    /// 14 % too many). No blade where `ρ ≤ 0` (side `size`): the scene has no grass.
    pub fn for_density(size: f32, blades_per_m2: f32) -> Self {
        if blades_per_m2.is_nan() || blades_per_m2 <= 0.0 {
            return Self {
                side: size,
                blades: 0,
            };
        }
        let rho = f64::from(blades_per_m2);
        let n = (rho * f64::from(size).powi(2))
            .round()
            .clamp(1.0, f64::from(u32::MAX));
        Self {
            side: (n / rho).sqrt() as f32,
            blades: n as u32,
        }
    }
}

/// The base patch.
#[derive(Clone, Debug)]
pub struct Patch {
    /// Side, m.
    pub size: f32,
    /// Strata per side: `⌈√blades⌉`, each stratum holding at most one root.
    pub strata: u32,
    /// Blocks per side.
    pub blocks: u32,
    /// Blades by block (row-major, x fastest), each block sorted by density threshold.
    pub blades: Vec<PatchBlade>,
    /// The range of `blades` each block holds.
    pub block_ranges: Vec<std::ops::Range<u32>>,
}

impl Patch {
    /// Generates the patch: `count` blades sized from `grass`, one in each of `count` of the
    /// `⌈√count⌉²` strata (all of them when `count` is a square), stored in `blocks x blocks`
    /// blocks. `count = 0` gives an empty patch.
    pub fn new(
        size: f32,
        count: u32,
        blocks: u32,
        grass: &GrassConfig,
        shape: BladeShape,
        seed: u64,
    ) -> Self {
        let mut rng = Rng::new(hash(seed, &[0x5041_5443])); // "PATC"
        let n = strata_for(count);
        let occupied = occupied_strata(n, count, seed);
        let cell = size / n as f32;
        let lerp = |r: [f32; 2], t: f32| r[0] + (r[1] - r[0]) * t;
        // Jitter within the stratum, a thousandth of it away from its edges so that rounding
        // can never move a root (or its mirror image) into the next stratum.
        let jitter = |rng: &mut Rng| 1e-3 + 0.998 * rng.next_f32();
        let mut blades = Vec::with_capacity(count as usize);
        for j in 0..n {
            for i in 0..n {
                if !occupied.as_ref().is_none_or(|o| o[(j * n + i) as usize]) {
                    continue;
                }
                let x = (i as f32 + jitter(&mut rng)) * cell - 0.5 * size;
                let z = (j as f32 + jitter(&mut rng)) * cell - 0.5 * size;
                let size_draw = rng.next_f32();
                blades.push(PatchBlade {
                    root: [x, z],
                    azimuth: rng.next_f32() * std::f32::consts::TAU,
                    // sqrt: most blades lean a little, few a lot.
                    tilt: shape.max_tilt * rng.next_f32().sqrt(),
                    height: lerp(grass.height, size_draw),
                    width: lerp(grass.width, 0.5 * size_draw + 0.5 * rng.next_f32()),
                    variation: rng.next_f32() * 2.0 - 1.0,
                    threshold: rng.next_f32(),
                });
            }
        }
        let k = blocks.max(1);
        let block_of = |b: &PatchBlade| {
            let q = |c: f32| (((c / size + 0.5) * k as f32) as u32).min(k - 1);
            q(b.root[1]) * k + q(b.root[0])
        };
        blades.sort_by(|a, b| {
            block_of(a)
                .cmp(&block_of(b))
                .then(a.threshold.total_cmp(&b.threshold))
        });
        let block_ranges = (0..k * k)
            .map(|blk| {
                let a = blades.partition_point(|b| block_of(b) < blk) as u32;
                let e = blades.partition_point(|b| block_of(b) <= blk) as u32;
                a..e
            })
            .collect();
        Self {
            size,
            strata: n,
            blocks: k,
            blades,
            block_ranges,
        }
    }

    /// Centre of block `k` relative to the patch centre, and its half side.
    pub fn block_center(&self, k: u32) -> (Vec2, f32) {
        let side = self.size / self.blocks as f32;
        let (bx, bz) = (k % self.blocks, k / self.blocks);
        let c = (Vec2::new(bx as f32, bz as f32) + 0.5) * side - Vec2::splat(0.5 * self.size);
        (c, 0.5 * side)
    }

    /// Blades per square metre of the tiling.
    pub fn blades_per_m2(&self) -> f64 {
        self.blades.len() as f64 / f64::from(self.size * self.size)
    }

    /// The stratum `(i, j)` a root (relative to the patch centre) lies in.
    pub fn stratum_of(&self, root: Vec2) -> (u32, u32) {
        let cell = self.size / self.strata as f32;
        let k = ((root + Vec2::splat(0.5 * self.size)) / cell).floor();
        let max = (self.strata - 1) as f32;
        (k.x.clamp(0.0, max) as u32, k.y.clamp(0.0, max) as u32)
    }

    /// Indices of the blades of block `k` whose threshold lies in `[lo, hi)`.
    pub fn threshold_range(&self, k: u32, lo: f32, hi: f32) -> std::ops::Range<u32> {
        let r = self.block_ranges[k as usize].clone();
        let blades = &self.blades[r.start as usize..r.end as usize];
        let a = blades.partition_point(|b| b.threshold < lo) as u32;
        let b = blades.partition_point(|b| b.threshold < hi) as u32;
        r.start + a..r.start + b.max(a)
    }
}

/// Strata per side for `count` blades: the smallest `n` with `n² ≥ count` (at least 1).
fn strata_for(count: u32) -> u32 {
    let mut n = (f64::from(count).sqrt().ceil() as u32).max(1);
    while u64::from(n) * u64::from(n) < u64::from(count) {
        n += 1;
    }
    n
}

/// Which of the `n x n` strata hold a root when `count` blades share them: `None` when all do
/// (`count = n²`), else `count` strata drawn without replacement (a partial Fisher-Yates
/// shuffle on its own stream, so the blades' draws do not depend on it).
fn occupied_strata(n: u32, count: u32, seed: u64) -> Option<Vec<bool>> {
    let total = n as usize * n as usize;
    if count as usize >= total {
        return None;
    }
    let mut rng = Rng::new(hash(seed, &[0x5354_5241])); // "STRA"
    let mut order: Vec<u32> = (0..total as u32).collect();
    for k in 0..count as usize {
        let pick = k + (rng.next_u64() % (total - k) as u64) as usize;
        order.swap(k, pick);
    }
    let mut occupied = vec![false; total];
    for &s in &order[..count as usize] {
        occupied[s as usize] = true;
    }
    Some(occupied)
}

/// Which of the four mirrored versions of the patch a cell uses (Sec. 3.1; the red and green
/// channels of the patch orientation map of Sec. 4.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Orientation {
    /// Mirrored across the patch's x axis (x → −x).
    pub flip_x: bool,
    /// Mirrored across its z axis (z → −z).
    pub flip_z: bool,
}

impl Orientation {
    /// The orientation of grid cell `(i, j)`: a hash of the seed and the cell, so the CPU (for
    /// geometry) and the orientation map (for slices) agree.
    pub fn of_cell(seed: u64, i: u32, j: u32) -> Self {
        let h = hash(seed, &[0x4f52_4945, i64::from(i), i64::from(j)]); // "ORIE"
        Self::from_bits((h >> 33) as u8)
    }

    /// From the two low bits (bit 0: flip x, bit 1: flip z), as stored in the map.
    pub fn from_bits(bits: u8) -> Self {
        Self {
            flip_x: bits & 1 != 0,
            flip_z: bits & 2 != 0,
        }
    }

    /// The two low bits of the map texel.
    pub fn bits(self) -> u8 {
        u8::from(self.flip_x) | (u8::from(self.flip_z) << 1)
    }

    /// Symmetry factors (−1 or 1) for x and z, as in Eq. 7.
    pub fn signs(self) -> Vec2 {
        Vec2::new(
            if self.flip_x { -1.0 } else { 1.0 },
            if self.flip_z { -1.0 } else { 1.0 },
        )
    }

    /// Mirrors a point or direction given relative to the patch centre.
    pub fn apply(self, p: Vec2) -> Vec2 {
        p * self.signs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blade_records_mirror_the_shader() {
        assert_eq!(
            grassbench::shaders::struct_size(crate::shader::SHADER, "Blade").unwrap() as usize,
            std::mem::size_of::<PatchBlade>()
        );
    }
    use proptest::prelude::*;

    /// A 0.5 m patch of `count` blades.
    fn patch_of(count: u32) -> Patch {
        Patch::new(
            0.5,
            count,
            4,
            &GrassConfig::default(),
            BladeShape { max_tilt: 0.4 },
            9,
        )
    }

    /// A 0.5 m patch with a blade in each of `strata x strata` strata.
    fn patch(strata: u32) -> Patch {
        patch_of(strata * strata)
    }

    /// Issue 19: the patch holds the density asked for. On the counts lawn (20 blades/m²) a
    /// 0.5 m patch holds 5 blades, not the square 4 it held before (20 % short); where
    /// `ρ·size²` is not whole the side moves so the tiled density is still `ρ`; no grass
    /// gives an empty patch.
    #[test]
    fn the_patch_holds_the_density_asked_for() {
        let spec = PatchSpec::for_density(0.5, 20.0);
        assert_eq!(
            spec,
            PatchSpec {
                side: 0.5,
                blades: 5
            }
        );
        for (size, rho) in [
            (0.5, 14.0),
            (0.5, 22.5),
            (0.5, 87_800.0),
            (0.5, 0.7),
            (0.3, 9.0),
        ] {
            let s = PatchSpec::for_density(size, rho);
            let tiled = s.blades as f32 / (s.side * s.side);
            assert!((tiled / rho - 1.0).abs() < 1e-5, "{size} m at {rho}: {s:?}");
            assert!(s.blades >= 1);
            // Within half a blade of the side asked for (a single blade may stretch it more).
            let asked = rho * size * size;
            assert!(
                (s.blades as f32 - asked).abs() <= 0.5 || asked < 1.0,
                "{s:?}"
            );
        }
        assert_eq!(PatchSpec::for_density(0.5, 87_800.0).blades, 21_950);
        assert_eq!(PatchSpec::for_density(0.5, 0.0).blades, 0);
        for count in [0, 2, 5, 21_950] {
            assert_eq!(patch_of(count).blades.len(), count as usize);
        }
        let empty = patch_of(0);
        assert!(empty.block_ranges.iter().all(|r| r.is_empty()));
        assert_eq!(empty.threshold_range(3, 0.0, 1.0), 0..0);
    }

    /// A count that is not a square takes that many strata of the `⌈√N⌉²`, at most one root
    /// each, and the drawn strata differ from one seed to another.
    #[test]
    fn a_non_square_count_leaves_strata_empty_but_never_doubles_one() {
        for count in [2, 5, 10, 21_950] {
            let p = patch_of(count);
            let n = p.strata;
            assert_eq!(n, (f64::from(count).sqrt().ceil()) as u32);
            let mut seen = vec![0u32; (n * n) as usize];
            for b in &p.blades {
                let (i, j) = p.stratum_of(Vec2::from(b.root));
                seen[(j * n + i) as usize] += 1;
            }
            assert!(seen.iter().all(|&c| c <= 1), "{count}: {seen:?}");
            assert_eq!(seen.iter().sum::<u32>(), count);
        }
        let strata = |seed| occupied_strata(3, 5, seed).unwrap();
        assert!((0..8).any(|seed| strata(seed) != strata(0)));
    }

    #[test]
    fn stratified_sampling_puts_one_root_in_each_stratum() {
        for n in [1, 7, 64, 148] {
            let p = patch(n);
            let mut seen = vec![0u32; (n * n) as usize];
            for b in &p.blades {
                let (i, j) = p.stratum_of(Vec2::from(b.root));
                seen[(j * n + i) as usize] += 1;
                assert!(b.root.iter().all(|c| c.abs() <= 0.25));
            }
            assert!(seen.iter().all(|&c| c == 1), "{n}x{n}: counts {seen:?}");
        }
    }

    #[test]
    fn blocks_partition_the_patch_and_thresholds_are_uniform() {
        let p = patch(100);
        let mut thresholds: Vec<f32> = p.blades.iter().map(|b| b.threshold).collect();
        thresholds.sort_by(f32::total_cmp);
        // Kolmogorov-Smirnov distance to the uniform distribution; 1.63/sqrt(n) is the 1 %
        // critical value for n = 10 000.
        let n = thresholds.len() as f32;
        let ks = thresholds
            .iter()
            .enumerate()
            .map(|(k, t)| (t - k as f32 / n).abs())
            .fold(0.0f32, f32::max);
        assert!(ks < 1.63 / n.sqrt(), "KS distance {ks}");
        let mut covered = 0;
        for k in 0..16 {
            let r = p.block_ranges[k as usize].clone();
            assert_eq!(r.start, covered);
            covered = r.end;
            let (c, h) = p.block_center(k);
            let blades = &p.blades[r.start as usize..r.end as usize];
            assert!(blades.windows(2).all(|w| w[0].threshold <= w[1].threshold));
            assert!(
                blades
                    .iter()
                    .all(|b| (Vec2::from(b.root) - c).abs().max_element() <= h)
            );
            assert_eq!(blades.len(), 625); // 25 x 25 strata a block
            let q = p.threshold_range(k, 0.25, 0.5);
            assert!(
                q.clone()
                    .all(|i| (0.25..0.5).contains(&p.blades[i as usize].threshold))
            );
            assert!((q.len() as f32 / 625.0 - 0.25).abs() < 0.1);
        }
        assert_eq!(covered as usize, p.blades.len());
    }

    proptest! {
        /// Mirrored tiling is an involution: each version mirrored twice is the patch itself,
        /// exactly, and mirroring keeps every root inside the patch and in a distinct stratum.
        #[test]
        fn mirroring_is_an_involution(x in -0.25f32..0.25, z in -0.25f32..0.25, bits in 0u8..4) {
            let o = Orientation::from_bits(bits);
            let p = Vec2::new(x, z);
            prop_assert_eq!(o.apply(o.apply(p)), p);
            prop_assert!(o.apply(p).abs().cmple(Vec2::splat(0.25)).all());
            prop_assert_eq!(Orientation::from_bits(o.bits()), o);
        }

        #[test]
        fn mirrored_patch_keeps_one_root_per_stratum(bits in 0u8..4, n in 1u32..40) {
            let p = patch(n);
            let o = Orientation::from_bits(bits);
            let mut seen = vec![false; (n * n) as usize];
            for b in &p.blades {
                let (i, j) = p.stratum_of(o.apply(Vec2::from(b.root)));
                let k = (j * n + i) as usize;
                prop_assert!(!seen[k], "two roots in stratum ({i}, {j})");
                seen[k] = true;
            }
        }
    }

    #[test]
    fn orientations_use_all_four_versions() {
        let mut counts = [0u32; 4];
        for j in 0..40 {
            for i in 0..40 {
                counts[Orientation::of_cell(3, i, j).bits() as usize] += 1;
            }
        }
        assert!(counts.iter().all(|&c| c > 300), "{counts:?}");
    }
}
