//! The base grass patch and its four mirrored versions (Boulanger Sec. 3.1).
//!
//! One square patch of blades is generated once, with *stratified sampling*: the patch is cut
//! into `n x n` strata and one root is placed at a random point of each, so the roots are
//! uniform at every scale and no clump repeats visibly when the patch is tiled. Each blade gets
//! a density threshold drawn uniformly in `[0, 1)` (Sec. 3.4). The blades are stored by
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

/// The base patch.
#[derive(Clone, Debug)]
pub struct Patch {
    /// Side, m.
    pub size: f32,
    /// Strata per side (`strata²` blades).
    pub strata: u32,
    /// Blocks per side.
    pub blocks: u32,
    /// Blades by block (row-major, x fastest), each block sorted by density threshold.
    pub blades: Vec<PatchBlade>,
    /// The range of `blades` each block holds.
    pub block_ranges: Vec<std::ops::Range<u32>>,
}

impl Patch {
    /// Generates the patch: `strata²` blades, one per stratum, sized from `grass`, stored in
    /// `blocks x blocks` blocks.
    pub fn new(
        size: f32,
        strata: u32,
        blocks: u32,
        grass: &GrassConfig,
        shape: BladeShape,
        seed: u64,
    ) -> Self {
        let mut rng = Rng::new(hash(seed, &[0x5041_5443])); // "PATC"
        let n = strata.max(1);
        let cell = size / n as f32;
        let lerp = |r: [f32; 2], t: f32| r[0] + (r[1] - r[0]) * t;
        // Jitter within the stratum, a thousandth of it away from its edges so that rounding
        // can never move a root (or its mirror image) into the next stratum.
        let jitter = |rng: &mut Rng| 1e-3 + 0.998 * rng.next_f32();
        let mut blades = Vec::with_capacity((n * n) as usize);
        for j in 0..n {
            for i in 0..n {
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

    /// Number of strata per side giving about `blades_per_m2` blades per square metre.
    pub fn strata_for(size: f32, blades_per_m2: f32) -> u32 {
        ((blades_per_m2 * size * size).sqrt().round() as u32).max(1)
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

    fn patch(strata: u32) -> Patch {
        Patch::new(
            0.5,
            strata,
            4,
            &GrassConfig::default(),
            BladeShape { max_tilt: 0.4 },
            9,
        )
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
