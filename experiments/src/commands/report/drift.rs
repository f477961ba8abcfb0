//! The calibration after the runs (issue 20 §3): a sweep fits the adapter's unit costs before
//! its runs and again once they are done. On a shared host the two can differ by more than the
//! model's tolerance (on the 2.6 GHz EPYC, 2026-12-06: a primitive priced 1.76 and a vertex
//! shader's storage word 1.53 times as dear by a sweep calibrated 27 minutes after another), and
//! every run's measured / model ratio moves with them. This section prices each run's counted
//! work with both, so a reader sees how far the host moved while the sweep measured and whether a
//! run's distance from its model is more than that movement.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use grassbench::cost::drift::{self, Drift};
use grassbench::cost::{Term, UnitCosts};

use super::configs::{Config, label, median};

/// One run priced with the costs from before and from after its sweep's runs.
struct Priced<'a> {
    config: &'a Config,
    measured_ms: f64,
    before_ms: f64,
    after_ms: f64,
}

/// Writes the section, where `after` holds costs for some target `before` has too.
pub(super) fn drift(
    md: &mut String,
    configs: &BTreeMap<String, Config>,
    before: &[UnitCosts],
    after: &[UnitCosts],
) {
    let pairs: Vec<(&UnitCosts, &UnitCosts)> = after
        .iter()
        .filter_map(|a| Some((UnitCosts::for_target(before, &a.size, a.msaa)?, a)))
        .collect();
    if pairs.is_empty() {
        return;
    }
    let _ = writeln!(md, "\n## The calibration after the runs\n");
    let _ = writeln!(
        md,
        "The unit costs were fitted again once the runs were done, with the same workloads. On a shared host the two fits differ by how far the host's speed moved while the sweep measured; each run's measured / model ratio moves with them. Below, each term's price after the runs over its price before, then each run's counted work priced with both.\n"
    );
    let _ = write!(md, "| term |");
    for (b, _) in &pairs {
        let _ = write!(md, " {}{} after / before |", b.size, msaa_label(b.msaa));
    }
    let _ = writeln!(md, "\n|---|{}", "---|".repeat(pairs.len()));
    // The terms either fit priced (a term held at zero by both has nothing to compare).
    let priced_terms = Term::ALL.into_iter().filter(|&t| {
        pairs
            .iter()
            .any(|(b, a)| b.get(t).value > 0.0 || a.get(t).value > 0.0)
    });
    for term in priced_terms {
        let _ = write!(md, "| {term} |");
        for (b, a) in &pairs {
            let (b, a) = (b.get(term).value, a.get(term).value);
            let cell = if b > 0.0 {
                format!("{:.2}", a / b)
            } else if a > 0.0 {
                "(0 before)".to_owned()
            } else {
                "(0 both)".to_owned()
            };
            let _ = write!(md, " {cell} |");
        }
        let _ = writeln!(md);
    }
    let priced: Vec<Priced<'_>> = configs
        .values()
        .filter_map(|c| {
            let work = c.work.as_ref()?;
            let (b, a) = pairs
                .iter()
                .find(|(b, _)| b.size == c.size && b.msaa == c.msaa)?;
            Some(Priced {
                config: c,
                measured_ms: median(&c.gpu_wall)?,
                before_ms: b.predict(work).total_ms,
                after_ms: a.predict(work).total_ms,
            })
        })
        .filter(|p| p.before_ms > 0.0 && p.after_ms > 0.0)
        .collect();
    let Some(d) = Drift::of(
        priced
            .iter()
            .map(|p| (p.measured_ms, p.before_ms, p.after_ms)),
    ) else {
        let _ = writeln!(
            md,
            "\nNo run here has counted work on a target both fits priced, so no run is priced with both.\n"
        );
        return;
    };
    let (n, tolerance) = (d.runs, drift::TOLERANCE * 100.0);
    let _ = writeln!(
        md,
        "\nThe costs after the runs price these runs' work at {:.2}-{:.2} times the costs before (median {:.2}). Measured / model: with the costs before, **{} of {n} runs within ±{tolerance:.0} %** ({:.2}-{:.2}); with the costs after, **{} of {n}** ({:.2}-{:.2}); within ±{tolerance:.0} % of one or the other, {} of {n}. A run out with both is further from its model than the host moved.\n",
        d.moved.0,
        d.moved.2,
        d.moved.1,
        d.within_before,
        d.before.0,
        d.before.1,
        d.within_after,
        d.after.0,
        d.after.1,
        d.within_either,
    );
    let _ = writeln!(
        md,
        "| scene | size | technique | params | GPU ms | model before, ms | model after, ms | measured / model before | measured / model after |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|");
    for p in &priced {
        let c = p.config;
        let _ = writeln!(
            md,
            "| {} | {}{} | {} | {} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} |",
            c.scene,
            c.size,
            msaa_label(c.msaa),
            c.technique,
            label(c).trim_start_matches(&c.technique).trim(),
            p.measured_ms,
            p.before_ms,
            p.after_ms,
            p.measured_ms / p.before_ms,
            p.measured_ms / p.after_ms,
        );
    }
}

/// ` 4x` for a multisampled target.
fn msaa_label(msaa: bool) -> &'static str {
    if msaa { " 4x" } else { "" }
}

#[cfg(test)]
mod tests {
    use grassbench::cost::{FitSummary, UnitCost, Work};

    use super::*;

    /// Costs at `size` where a vertex costs `vertex_ns` and a primitive 100 ns, nothing else.
    fn costs(size: &str, vertex_ns: f64) -> UnitCosts {
        let exact = |value| UnitCost {
            value,
            standard_error: 0.0,
            at_zero: false,
        };
        let mut per_unit = [exact(0.0); Term::ALL.len()];
        per_unit[Term::Vertex.index()] = exact(vertex_ns * 1e-6);
        per_unit[Term::Primitive.index()] = exact(100.0 * 1e-6);
        UnitCosts::from_ms_per_unit(size.into(), "test".into(), per_unit, FitSummary::default())
    }

    /// A run at 640x360 measured at `measured_ms` whose frames counted 1 M vertices and
    /// 100 k primitives.
    fn run(technique: &str, measured_ms: f64) -> Config {
        Config {
            technique: technique.into(),
            scene: "meadow".into(),
            size: "640x360".into(),
            gpu_wall: vec![measured_ms],
            work: Some(Work {
                vertex_invocations: 1e6,
                primitives: 1e5,
                ..Work::default()
            }),
            ..Config::default()
        }
    }

    #[test]
    fn every_run_is_priced_with_the_costs_before_and_after() {
        // Before: 10 ns a vertex, so 10 + 10 = 20 ms of work; after: 14 ns, 24 ms.
        let before = [costs("640x360", 10.0)];
        let after = [costs("640x360", 14.0)];
        let configs: BTreeMap<String, Config> = [
            ("a".to_owned(), run("near_both", 22.0)),
            ("b".to_owned(), run("only_before", 16.0)),
            ("c".to_owned(), run("only_after", 30.0)),
            ("d".to_owned(), run("neither", 40.0)),
        ]
        .into();
        let mut md = String::new();
        drift(&mut md, &configs, &before, &after);
        // The vertex term moved 1.4x, the primitive's not at all; a term both priced at 0 has
        // no row.
        assert!(md.contains("| vertex | 1.40 |"), "{md}");
        assert!(md.contains("| primitive | 1.00 |"), "{md}");
        assert!(!md.contains("| draw |"), "{md}");
        // 22 ms: 1.10 and 0.92, within with both; 16: 0.80 before, 0.67 after; 30: 1.50
        // before, 1.25 after; 40: 2.00 and 1.67, out with both.
        assert!(md.contains("at 1.20-1.20 times the costs before"), "{md}");
        assert!(
            md.contains("**2 of 4 runs within ±25 %** (0.80-2.00)"),
            "{md}"
        );
        assert!(md.contains("**2 of 4** (0.67-1.67)"), "{md}");
        assert!(md.contains("one or the other, 3 of 4"), "{md}");
        assert!(
            md.contains("| meadow | 640x360 | neither |  | 40.0 | 20.0 | 24.0 | 2.00 | 1.67 |"),
            "{md}"
        );
    }

    #[test]
    fn nothing_is_written_without_costs_for_the_same_target() {
        let configs: BTreeMap<String, Config> = [("a".to_owned(), run("x", 20.0))].into();
        let mut md = String::new();
        drift(
            &mut md,
            &configs,
            &[costs("320x180", 10.0)],
            &[costs("640x360", 10.0)],
        );
        assert!(md.is_empty(), "{md}");
        drift(&mut md, &configs, &[costs("640x360", 10.0)], &[]);
        assert!(md.is_empty(), "{md}");
    }
}
