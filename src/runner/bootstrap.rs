//! Confidence intervals for speed-ups, by the percentile bootstrap.
//!
//! A speed-up is the reference's median frame time over a technique's, measured in the same
//! group (scene, size, repetition). Frame times scatter, and on a shared host the scatter
//! moves between repetitions, so one ratio of medians says less than it seems to. The
//! bootstrap resamples what was measured — the frames of each run, and where a configuration
//! was repeated, the repetitions first and then the frames within each — recomputes the
//! ratio of medians each time and reports the 2.5th and 97.5th percentiles of those ratios: a
//! 95 % interval. Two techniques are called faster or slower than each other only where their
//! intervals do not overlap ([`Interval::separated_from`]).
//!
//! Resampling is driven by [`crate::rng::Rng`] from a fixed seed, so an interval is a pure
//! function of the samples: the same results folder always reports the same intervals.

use super::Percentiles;
use crate::rng::Rng;

/// Resamples drawn for an interval: enough that the 2.5th / 97.5th percentiles of the ratio
/// move by well under 1 % between seeds (checked in the tests).
pub const RESAMPLES: usize = 2000;

/// A 95 % interval.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Interval {
    /// 2.5th percentile of the bootstrap distribution.
    pub low: f64,
    /// 97.5th percentile.
    pub high: f64,
}

impl Interval {
    /// Whether the two intervals do not overlap (one lies wholly above the other).
    pub fn separated_from(&self, other: &Interval) -> bool {
        self.low > other.high || other.low > self.high
    }
}

/// The median of `values` (`None` when empty).
fn median(values: &mut [f64]) -> Option<f64> {
    Percentiles::of(values.iter().copied()).map(|p| p.median)
}

/// Draws `n` values from `sample` with replacement, appending them to `out`.
fn resample_into(sample: &[f64], n: usize, rng: &mut Rng, out: &mut Vec<f64>) {
    for _ in 0..n {
        let k = (rng.next_u64() % sample.len() as u64) as usize;
        out.push(sample[k]);
    }
}

/// The 95 % bootstrap interval of `median(reference) / median(technique)` from repeated,
/// paired measurements: `reference[r]` and `technique[r]` are the frame times of repetition
/// `r` of the reference and of the technique in the same group. Each resample draws
/// repetitions with replacement (pairs kept together: a slow host slows both), then frames
/// with replacement within each drawn repetition, and pools them. `None` when a side has no
/// samples or the counts of repetitions differ.
pub fn speedup_interval(reference: &[Vec<f64>], technique: &[Vec<f64>]) -> Option<Interval> {
    interval_seeded(reference, technique, 0x5eed_b007)
}

fn interval_seeded(reference: &[Vec<f64>], technique: &[Vec<f64>], seed: u64) -> Option<Interval> {
    let pairs: Vec<(&Vec<f64>, &Vec<f64>)> = reference
        .iter()
        .zip(technique)
        .filter(|(r, t)| !r.is_empty() && !t.is_empty())
        .collect();
    if pairs.is_empty() || reference.len() != technique.len() {
        return None;
    }
    let mut rng = Rng::new(seed);
    let mut ratios = Vec::with_capacity(RESAMPLES);
    let (mut r, mut t) = (Vec::new(), Vec::new());
    for _ in 0..RESAMPLES {
        r.clear();
        t.clear();
        for _ in 0..pairs.len() {
            let (rs, ts) = pairs[(rng.next_u64() % pairs.len() as u64) as usize];
            resample_into(rs, rs.len(), &mut rng, &mut r);
            resample_into(ts, ts.len(), &mut rng, &mut t);
        }
        if let (Some(mr), Some(mt)) = (median(&mut r), median(&mut t))
            && mt > 0.0
        {
            ratios.push(mr / mt);
        }
    }
    let q = |p: f64| -> Option<f64> {
        let mut v = ratios.clone();
        v.sort_by(f64::total_cmp);
        let pos = p * (v.len().checked_sub(1)?) as f64;
        let (lo, hi) = (pos.floor() as usize, pos.ceil() as usize);
        Some(v[lo] + (v[hi] - v[lo]) * (pos - lo as f64))
    };
    Some(Interval {
        low: q(0.025)?,
        high: q(0.975)?,
    })
}

/// [`speedup_interval`] of one repetition: the frames of one reference run and one technique
/// run.
pub fn speedup_interval_of_runs(reference: &[f64], technique: &[f64]) -> Option<Interval> {
    speedup_interval(&[reference.to_vec()], &[technique.to_vec()])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frame times around `centre` with a spread of ±`spread` (deterministic).
    fn frames(centre: f64, spread: f64, n: usize, seed: u64) -> Vec<f64> {
        let mut rng = Rng::new(seed);
        (0..n)
            .map(|_| centre + spread * (2.0 * f64::from(rng.next_f32()) - 1.0))
            .collect()
    }

    #[test]
    fn the_interval_holds_the_true_ratio_and_narrows_with_more_frames() {
        let reference = frames(100.0, 10.0, 20, 1);
        let technique = frames(25.0, 2.5, 20, 2);
        let i = speedup_interval_of_runs(&reference, &technique).unwrap();
        assert!(i.low < 4.0 && 4.0 < i.high, "{i:?}");
        assert!(i.high - i.low < 0.8, "{i:?}");
        let wide = speedup_interval_of_runs(&reference[..5], &technique[..5]).unwrap();
        assert!(wide.high - wide.low > i.high - i.low, "{wide:?} vs {i:?}");
    }

    #[test]
    fn repetitions_that_disagree_widen_the_interval() {
        // Three repetitions on a host whose speed moved between them: within each the ratio
        // is 4, but the technique's second repetition ran on a busier host.
        let reference = vec![frames(100.0, 1.0, 20, 1); 3];
        let steady = vec![frames(25.0, 0.25, 20, 2); 3];
        let mut moved = steady.clone();
        moved[1] = frames(40.0, 0.4, 20, 3);
        let a = speedup_interval(&reference, &steady).unwrap();
        let b = speedup_interval(&reference, &moved).unwrap();
        assert!(a.high - a.low < 0.2, "{a:?}");
        assert!(b.high - b.low > 5.0 * (a.high - a.low), "{b:?} vs {a:?}");
    }

    #[test]
    fn enough_resamples_that_the_seed_hardly_matters() {
        let reference = vec![frames(100.0, 10.0, 20, 1)];
        let technique = vec![frames(25.0, 2.5, 20, 2)];
        let a = interval_seeded(&reference, &technique, 1).unwrap();
        let b = interval_seeded(&reference, &technique, 2).unwrap();
        for (x, y) in [(a.low, b.low), (a.high, b.high)] {
            assert!((x / y - 1.0).abs() < 0.01, "{a:?} vs {b:?}");
        }
    }

    #[test]
    fn overlap_decides_faster() {
        let a = Interval {
            low: 2.0,
            high: 3.0,
        };
        let b = Interval {
            low: 2.9,
            high: 4.0,
        };
        let c = Interval {
            low: 3.1,
            high: 4.0,
        };
        assert!(!a.separated_from(&b) && !b.separated_from(&a));
        assert!(a.separated_from(&c) && c.separated_from(&a));
    }

    #[test]
    fn nothing_to_resample_gives_none() {
        assert_eq!(speedup_interval(&[], &[]), None);
        assert_eq!(speedup_interval_of_runs(&[], &[1.0]), None);
        assert_eq!(
            speedup_interval(&[vec![1.0]], &[vec![1.0], vec![2.0]]),
            None
        );
    }
}
