//! Order statistics for frame times.

/// Median and the 5th / 95th percentiles of a sample.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Percentiles {
    /// 50th percentile.
    pub median: f64,
    /// 5th percentile.
    pub p5: f64,
    /// 95th percentile.
    pub p95: f64,
}

impl Percentiles {
    /// Percentiles of `values` (linear interpolation between order statistics); NaNs ignored;
    /// `None` when nothing is left.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Option<Self> {
        let mut v: Vec<f64> = values.into_iter().filter(|x| !x.is_nan()).collect();
        if v.is_empty() {
            return None;
        }
        v.sort_by(f64::total_cmp);
        let q = |p: f64| {
            let pos = p * (v.len() - 1) as f64;
            let (lo, hi) = (pos.floor() as usize, pos.ceil() as usize);
            v[lo] + (v[hi] - v[lo]) * (pos - lo as f64)
        };
        Some(Self {
            median: q(0.5),
            p5: q(0.05),
            p95: q(0.95),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_of_a_ramp() {
        let p = Percentiles::of((0..=100).map(f64::from)).unwrap();
        assert_eq!((p.median, p.p5, p.p95), (50.0, 5.0, 95.0));
        let p = Percentiles::of([3.0, f64::NAN, 1.0, 2.0]).unwrap();
        assert_eq!(p.median, 2.0);
        assert!(Percentiles::of([]).is_none());
    }
}
