//! Fewer shells with distance: a departure from the paper (issue 20 §7), which names it future
//! work (Sec. 5: "in a multiple level of detail setup, it would be advantageous to reduce the
//! number of shells for far off portions of the landscape").
//!
//! A chunk's shells are `pixels` apart on screen or less: the `N` shells are `S = H / N` apart,
//! `S · f / z` pixels at depth `z` (`f` the focal length in pixels), so at depth `z` a chunk
//! draws every `m`-th shell, `m` the largest power of two with `m · S · f / z ≤ pixels` (level
//! `log2 m`). The top shell is always drawn (shell `N − 1`, then `N − 1 − m`, …), so the grass
//! keeps its height, and each drawn shell stands for the `m` shells from it down: it keeps the
//! texels whose blade reaches the lowest of them, the widest of their sections (alpha falls
//! from a blade's centre to its rim), so thinning the shells thins the grass less. Where the
//! whole stack is `pixels` tall or less on screen, `H · f / z ≤ pixels`, a chunk draws no
//! shell: the grass there is the core's ground. The depth is the chunk box's nearest corner
//! along the view direction, so every part of a chunk is at least as far as its level assumes.
//! `pixels = 0` turns the level of detail off: every chunk in view gets all `N` shells (the
//! paper's behaviour).

/// Instance indices a level owns: a draw at level `L` uses instances `L · LEVEL_INSTANCES`
/// onwards (the shader splits an instance index into level and shell). At least the largest
/// number of shells the parameters allow.
pub const LEVEL_INSTANCES: u32 = 128;
// `shells` goes up to 128 (its schema's range).
const _: () = assert!(LEVEL_INSTANCES >= 128);

/// The per-chunk shell plan of one set of parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShellLod {
    /// Shells `N` at full detail.
    pub shells: u32,
    /// Height of the shell stack (the tallest blade), m.
    pub height: f32,
    /// Most pixels between neighbouring drawn shells; 0 = off (all shells everywhere).
    pub pixels: f32,
}

impl ShellLod {
    /// The level (`log2` of the stride between drawn shells) of a chunk whose nearest point is
    /// `depth` metres in front of the eye, with a focal length of `focal` pixels (target
    /// height over `2 tan(fov_y / 2)`); `None` when it draws no shell.
    pub fn level(&self, depth: f32, focal: f32) -> Option<u32> {
        if self.shells == 0 {
            return None;
        }
        if self.pixels <= 0.0 {
            return Some(0);
        }
        // Pixels per metre at the chunk's nearest depth (a chunk around the eye: no limit).
        let per_metre = focal / depth.max(1e-3);
        if !per_metre.is_finite() {
            return Some(0);
        }
        if self.height * per_metre <= self.pixels {
            return None;
        }
        let spacing = self.height / self.shells as f32 * per_metre;
        let mut level = 0;
        while (1u32 << (level + 1)) < 2 * self.shells
            && (1u32 << (level + 1)) as f32 * spacing <= self.pixels
        {
            level += 1;
        }
        Some(level)
    }

    /// Shells drawn at `level`: every `2^level`-th from the top one down.
    pub fn shells_at(&self, level: u32) -> u32 {
        if self.shells == 0 {
            return 0;
        }
        (self.shells - 1) / stride(level) + 1
    }

    /// The shell `k` (0 = ground, `N − 1` = top) drawn as the `i`-th (from the bottom) at
    /// `level`, and the lowest shell it stands for (its alpha test's height): the shader's
    /// `level_shell` (its twin).
    pub fn shell(&self, level: u32, i: u32) -> (u32, u32) {
        let m = stride(level);
        let k = (self.shells - 1) - (self.shells_at(level) - 1 - i) * m;
        (k, (k + 1).saturating_sub(m))
    }
}

/// Shells between neighbouring drawn shells at `level`.
fn stride(level: u32) -> u32 {
    1u32 << level.min(31)
}

#[cfg(test)]
mod tests {
    use super::*;

    const LOD: ShellLod = ShellLod {
        shells: 16,
        height: 0.7,
        pixels: 1.0,
    };

    #[test]
    fn shells_halve_with_distance_then_end_at_the_ground() {
        let focal = 259.0;
        let mut last = (0, LOD.shells);
        let mut seen = Vec::new();
        for d in 1..=400 {
            let depth = d as f32;
            match LOD.level(depth, focal) {
                Some(level) => {
                    // Neighbouring drawn shells at most a pixel apart, and no coarser level
                    // would keep them so (unless only the top shell is left).
                    let spacing = LOD.height / 16.0 * focal / depth;
                    assert!((1u32 << level) as f32 * spacing <= 1.0 || level == 0);
                    let n = LOD.shells_at(level);
                    assert!(n == 1 || (2u32 << level) as f32 * spacing > 1.0);
                    assert!(level >= last.0 && n <= last.1, "{depth} m: level {level}");
                    last = (level, n);
                    seen.push(n);
                }
                None => {
                    // Only once the whole blade is a pixel tall or less, and for good.
                    assert!(LOD.height * focal / depth <= 1.0);
                    last = (u32::MAX, 0);
                }
            }
        }
        seen.dedup();
        assert_eq!(seen, vec![16, 8, 4, 2]);
        assert_eq!(LOD.level(400.0, focal), None);
        // Near the eye every shell.
        assert_eq!(LOD.level(5.0, focal), Some(0));
        assert_eq!(LOD.level(0.0, focal), Some(0));
        assert_eq!(LOD.level(-3.0, focal), Some(0));
    }

    #[test]
    fn off_draws_every_shell_everywhere() {
        let off = ShellLod { pixels: 0.0, ..LOD };
        for depth in [0.5, 50.0, 5_000.0] {
            assert_eq!(off.level(depth, 259.0), Some(0));
        }
        assert_eq!(off.shells_at(0), 16);
        for i in 0..16 {
            assert_eq!(off.shell(0, i), (i, i));
        }
    }

    #[test]
    fn the_top_shell_stays_and_each_shell_stands_for_those_below_it() {
        for shells in [1, 5, 16, 17, 64, 128] {
            let lod = ShellLod { shells, ..LOD };
            for level in 0..8 {
                let n = lod.shells_at(level);
                assert!(n >= 1 && n <= shells);
                let drawn: Vec<_> = (0..n).map(|i| lod.shell(level, i)).collect();
                assert_eq!(drawn.last().unwrap().0, shells - 1, "top shell kept");
                // Bottom to top; together they stand for every shell once.
                assert_eq!(drawn[0].1, 0);
                for w in drawn.windows(2) {
                    assert_eq!(w[1].1, w[0].0 + 1);
                    assert!(w[1].0 > w[0].0);
                }
            }
        }
    }
}
