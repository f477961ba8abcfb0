//! How far a host moved while runs were measured (issue 20 §3): each run's measured time set
//! against the cost model's prediction with the unit costs fitted before the runs and with
//! those fitted again after them. On a shared host the two fits differ by the host's drift, and
//! every measured / model ratio moves with them; a run out of the model's tolerance with both
//! is further from its model than that drift. `grassbench run` and `sweep` fit twice; their
//! reports summarise with [`Drift`].

/// How far measured / model may stray from 1 and the model still hold (issue 20 §3: ±25 %).
pub const TOLERANCE: f64 = 0.25;

/// Whether `measured` is within [`TOLERANCE`] of `model` (both ms, `model` > 0).
pub fn within(measured: f64, model: f64) -> bool {
    (measured / model - 1.0).abs() <= TOLERANCE
}

/// Runs priced with the fits before and after: how many the model holds for with each, and
/// how far the fit after moved the prediction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drift {
    /// Runs priced with both fits.
    pub runs: usize,
    /// Of those, within [`TOLERANCE`] with the fit before.
    pub within_before: usize,
    /// Within with the fit after.
    pub within_after: usize,
    /// Within with one or the other.
    pub within_either: usize,
    /// The fit after's prediction over the fit before's: lowest, median, highest.
    pub moved: (f64, f64, f64),
    /// Measured / model with the fit before: lowest, highest.
    pub before: (f64, f64),
    /// Measured / model with the fit after: lowest, highest.
    pub after: (f64, f64),
}

impl Drift {
    /// The summary of `runs`, each `(measured, model before, model after)` in ms; `None`
    /// where no run has both models above zero.
    pub fn of(runs: impl IntoIterator<Item = (f64, f64, f64)>) -> Option<Self> {
        let runs: Vec<(f64, f64, f64)> = runs
            .into_iter()
            .filter(|&(m, b, a)| m.is_finite() && b > 0.0 && a > 0.0)
            .collect();
        if runs.is_empty() {
            return None;
        }
        let range = |f: &dyn Fn(&(f64, f64, f64)) -> f64| {
            runs.iter()
                .map(f)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), r| {
                    (l.min(r), h.max(r))
                })
        };
        let count = |f: &dyn Fn(&(f64, f64, f64)) -> bool| runs.iter().filter(|r| f(r)).count();
        let (low, high) = range(&|&(_, b, a)| a / b);
        let mut moved: Vec<f64> = runs.iter().map(|&(_, b, a)| a / b).collect();
        moved.sort_by(f64::total_cmp);
        let mid = moved.len() / 2;
        let median = if moved.len() % 2 == 1 {
            moved[mid]
        } else {
            0.5 * (moved[mid - 1] + moved[mid])
        };
        Some(Self {
            runs: runs.len(),
            within_before: count(&|&(m, b, _)| within(m, b)),
            within_after: count(&|&(m, _, a)| within(m, a)),
            within_either: count(&|&(m, b, a)| within(m, b) || within(m, a)),
            moved: (low, median, high),
            before: range(&|&(m, b, _)| m / b),
            after: range(&|&(m, _, a)| m / a),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_are_counted_with_each_fit_and_either() {
        // Before 20 ms each, after 24: 22 ms within with both, 16 before only (0.80, 0.67),
        // 30 after only (1.50, 1.25: the tolerance's edge counts as within), 40 with neither.
        let d = Drift::of([
            (22.0, 20.0, 24.0),
            (16.0, 20.0, 24.0),
            (30.0, 20.0, 24.0),
            (40.0, 20.0, 24.0),
            (40.0, 0.0, 24.0),
        ])
        .unwrap();
        assert_eq!(
            (d.runs, d.within_before, d.within_after, d.within_either),
            (4, 2, 2, 3)
        );
        assert_eq!(d.moved, (1.2, 1.2, 1.2));
        assert_eq!(d.before, (0.8, 2.0));
        assert!((d.after.0 - 16.0 / 24.0).abs() < 1e-12 && (d.after.1 - 40.0 / 24.0).abs() < 1e-12);
        // The median of an even count is the mean of the middle two.
        let d = Drift::of([(1.0, 1.0, 0.9), (1.0, 1.0, 1.1)]).unwrap();
        assert!((d.moved.1 - 1.0).abs() < 1e-12, "{d:?}");
        assert_eq!(Drift::of([(1.0, 0.0, 1.0)]), None);
    }
}
