//! The coverage checks: workloads timed with the calibration's samples but not fitted, whose
//! fragments are unlike the ones every fragment term is fitted on.
//!
//! Each fragment term is fitted on full-screen layers ([`super::workloads`]): every 4x4 block
//! covered whole, every fragment passing the depth test. A technique's fragments are not like
//! that. Its blades cover the blocks they touch in part (lavapipe counts a fragment for each of
//! the 16 pixels of a block a triangle touches: a run's counted fragments are blocks, not
//! covered pixels), and most of them fail the depth test or are discarded (the runs keep 0.2-33
//! % of them: `fragments_passed` over `fragment_invocations`). The checks draw both cases on
//! their own and report measured over predicted time, so a calibration says where its fragment
//! prices hold and by how much they miss where they do not:
//!
//! - `blades_*`: [`Shape::OnscreenBlades`] 1.5 pixels wide at the root, 40 tall: a near blade;
//! - `slivers_*`: the same 0.3 pixels wide: a far blade, a few samples of each block it touches;
//! - `hidden_*`: an opaque layer, then [`Shape::HiddenLayers`] of the kind behind it: fragments
//!   an early depth test rejects (opaque, blended) or a late one after the shader ran
//!   (alpha-tested).
//!
//! Each at two sizes, 1 : 4, so a check that does not grow with its work shows as such. The
//! share of samples kept per counted fragment ([`CheckResult::kept_per_fragment`], as a run's
//! `fragments_passed` over `fragment_invocations`) places each check beside the runs.

use super::workloads::{BladeWidth, Shape, Workload};
use super::{FragmentKind, MeasuredSample, Term, UnitCosts};

/// Blades of the smaller size of each `blades_*` and `slivers_*` check.
pub const BLADES: u32 = 4_000;
/// Layers of the smaller size of each `hidden_*` check.
pub const HIDDEN_LAYERS: u32 = 4;
/// Ratio of each check's larger size to its smaller.
pub const LARGER: u32 = 4;

/// One check: its name and the workloads it submits together.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// `blades_opaque`, `slivers_alpha_tested`, `hidden_blended`, ...
    pub name: &'static str,
    /// What one submission does.
    pub mix: Vec<Workload>,
}

/// What a check draws: blades of a width on screen, or layers hidden behind an opaque one.
#[derive(Clone, Copy)]
enum Family {
    Onscreen(BladeWidth),
    Hidden,
}

/// The name of the check of `family` shaded as `kind`.
fn name(family: Family, kind: FragmentKind) -> &'static str {
    use BladeWidth::{Blade, Sliver};
    use FragmentKind::{AlphaTested, Blended, Opaque};
    match (family, kind) {
        (Family::Onscreen(Blade), Opaque) => "blades_opaque",
        (Family::Onscreen(Blade), AlphaTested) => "blades_alpha_tested",
        (Family::Onscreen(Blade), Blended) => "blades_blended",
        (Family::Onscreen(Sliver), Opaque) => "slivers_opaque",
        (Family::Onscreen(Sliver), AlphaTested) => "slivers_alpha_tested",
        (Family::Onscreen(Sliver), Blended) => "slivers_blended",
        (Family::Hidden, Opaque) => "hidden_opaque",
        (Family::Hidden, AlphaTested) => "hidden_alpha_tested",
        (Family::Hidden, Blended) => "hidden_blended",
    }
}

/// Every check: blades and slivers, and an opaque layer with layers hidden behind it, of
/// every fragment kind, each at [`BLADES`] blades or [`HIDDEN_LAYERS`] hidden layers and at
/// [`LARGER`] times that.
pub fn coverage_checks() -> Vec<Check> {
    let mut checks = Vec::new();
    for k in [1, LARGER] {
        for width in BladeWidth::ALL {
            for kind in FragmentKind::ALL {
                let shape = Shape::OnscreenBlades {
                    kind,
                    width,
                    instances: BLADES * k,
                };
                let name = name(Family::Onscreen(width), kind);
                checks.push(Check {
                    name,
                    mix: vec![Workload {
                        name,
                        term: Term::fragment(kind),
                        shape,
                    }],
                });
            }
        }
        for kind in FragmentKind::ALL {
            let name = name(Family::Hidden, kind);
            let occluder = Workload {
                name: "occluder",
                term: Term::FragmentOpaque,
                shape: Shape::Layers {
                    kind: FragmentKind::Opaque,
                    layers: 1,
                },
            };
            let hidden = Workload {
                name,
                term: Term::fragment(kind),
                shape: Shape::HiddenLayers {
                    kind,
                    layers: HIDDEN_LAYERS * k,
                },
            };
            checks.push(Check {
                name,
                mix: vec![occluder, hidden],
            });
        }
    }
    checks
}

/// One check, timed and priced.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CheckResult {
    /// The check's name (`slivers_blended`).
    pub check: String,
    /// Its work, counted by the GPU where it counts.
    pub fragments: f64,
    /// Primitives rasterised.
    pub primitives: f64,
    /// Samples kept (passed the depth test, not discarded) per counted fragment, as a run's
    /// `fragments_passed` over `fragment_invocations` (up to 4 with 4x MSAA); `None` without
    /// counters.
    pub kept_per_fragment: Option<f64>,
    /// Median time, ms.
    pub measured_ms: f64,
    /// The costs' prediction of its work, ms.
    pub predicted_ms: f64,
    /// Measured over predicted.
    pub ratio: f64,
}

/// `checks` as timed by [`super::calibrate_units_with`] (`held_out`: their mixes, in order,
/// as its held-out mixes), priced with `costs`.
pub fn results(
    costs: &UnitCosts,
    checks: &[Check],
    held_out: &[MeasuredSample],
) -> Vec<CheckResult> {
    checks
        .iter()
        .zip(held_out)
        .map(|(check, m)| {
            let w = &m.sample.work;
            let fragments = w.fragments_opaque + w.fragments_alpha_tested + w.fragments_blended;
            let predicted_ms = costs.predict(w).total_ms;
            CheckResult {
                check: check.name.to_owned(),
                fragments,
                primitives: w.primitives,
                kept_per_fragment: m
                    .samples_passed
                    .filter(|_| fragments > 0.0)
                    .map(|k| k as f64 / fragments),
                measured_ms: m.sample.measured_ms,
                predicted_ms,
                ratio: m.sample.measured_ms / predicted_ms,
            }
        })
        .collect()
}

/// The results as a Markdown table.
pub fn to_markdown(results: &[CheckResult]) -> String {
    let mut text = String::from(
        "| check | fragments | primitives | kept per fragment | measured ms | predicted ms | measured / predicted |\n|---|---|---|---|---|---|---|\n",
    );
    for r in results {
        let kept = r
            .kept_per_fragment
            .map_or_else(|| "-".to_owned(), |k| format!("{k:.3}"));
        text.push_str(&format!(
            "| {} | {:.0} | {:.0} | {kept} | {:.2} | {:.2} | {:.2} |\n",
            r.check, r.fragments, r.primitives, r.measured_ms, r.predicted_ms, r.ratio
        ));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cost::Work;
    use crate::target::Size;

    const SIZE: Size = Size {
        width: 320,
        height: 180,
    };

    fn fragments(w: &Work) -> f64 {
        w.fragments_opaque + w.fragments_alpha_tested + w.fragments_blended
    }

    /// A check's work, known in advance.
    fn work(check: &Check) -> Work {
        check
            .mix
            .iter()
            .fold(Work::default(), |a, w| a + w.work(SIZE))
    }

    #[test]
    fn every_check_has_a_name_and_two_sizes() {
        let checks = coverage_checks();
        assert_eq!(checks.len(), 2 * 9);
        let (small, large) = checks.split_at(9);
        for (a, b) in small.iter().zip(large) {
            assert_eq!(a.name, b.name);
            let last = |c: &Check| c.mix.last().copied();
            let (Some(wa), Some(wb)) = (last(a), last(b)) else {
                panic!("{} has no workload", a.name)
            };
            // The check's own workload grows 4x; its fragments are of its kind alone.
            let (fa, fb) = (wa.work(SIZE), wb.work(SIZE));
            assert!(fragments(&fa) > 0.0, "{}", a.name);
            assert_eq!(fragments(&fb), f64::from(LARGER) * fragments(&fa));
            assert_eq!(fa.amount(wa.term), fragments(&fa), "{}", a.name);
        }
        let mut names: Vec<&str> = small.iter().map(|c| c.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), 9);
    }

    #[test]
    fn a_hidden_check_is_an_opaque_layer_and_the_layers_of_its_kind() {
        let pixels = f64::from(SIZE.width * SIZE.height);
        for check in coverage_checks()
            .iter()
            .filter(|c| c.name.starts_with("hidden"))
        {
            let w = work(check);
            let Some(Shape::HiddenLayers { kind, layers }) = check.mix.last().map(|w| w.shape)
            else {
                panic!("{}", check.name)
            };
            let hidden = pixels * f64::from(layers);
            let opaque = if kind == FragmentKind::Opaque {
                pixels + hidden
            } else {
                pixels
            };
            assert_eq!(w.fragments_opaque, opaque, "{}", check.name);
            assert_eq!(fragments(&w), pixels + hidden, "{}", check.name);
            assert_eq!(w.draw_calls, 2.0);
        }
    }

    #[test]
    fn slivers_cover_a_fifth_of_the_blades_pixels() {
        let work = |width| {
            Workload {
                name: "blades",
                term: Term::FragmentOpaque,
                shape: Shape::OnscreenBlades {
                    kind: FragmentKind::Opaque,
                    width,
                    instances: 10,
                },
            }
            .work(SIZE)
        };
        let (blade, sliver) = (work(BladeWidth::Blade), work(BladeWidth::Sliver));
        // 40 x 1.5 / 2 and 40 x 0.3 / 2 pixels a blade.
        assert_eq!(blade.fragments_opaque, 300.0);
        assert_eq!(sliver.fragments_opaque, 60.0);
        assert_eq!(blade.primitives, sliver.primitives);
        assert_eq!(blade.vertex_invocations, 110.0);
    }

    #[test]
    fn a_result_prices_the_counted_work_and_keeps_samples_per_fragment() {
        let costs = UnitCosts::from_ms_per_unit(
            SIZE.to_string(),
            "test".into(),
            [super::super::UnitCost::exact(1e-6); Term::ALL.len()],
            super::super::FitSummary::default(),
        );
        let checks = coverage_checks();
        let work = work(&checks[0]);
        let predicted = costs.predict(&work).total_ms;
        let held_out = [MeasuredSample {
            sample: super::super::Sample {
                workload: "blades_opaque".into(),
                measured_ms: 2.0 * predicted,
                work,
            },
            known: work,
            counted: Some(work),
            samples_passed: Some(600_000),
            runs_ms: vec![2.0 * predicted],
        }];
        let r = &results(&costs, &checks[..1], &held_out)[0];
        assert_eq!(r.check, "blades_opaque");
        assert_eq!(r.ratio, 2.0);
        assert_eq!(r.kept_per_fragment, Some(600_000.0 / work.fragments_opaque));
        assert!(to_markdown(std::slice::from_ref(r)).contains("| blades_opaque |"));
        // Kept with the costs they were priced with: in their table and their files.
        let with = UnitCosts {
            checks: vec![r.clone()],
            ..costs.clone()
        };
        assert!(with.to_markdown().contains("Coverage checks"));
        assert!(!costs.to_markdown().contains("Coverage checks"));
        let text = toml::to_string(&with).unwrap_or_default();
        assert_eq!(toml::from_str::<UnitCosts>(&text).ok(), Some(with));
    }
}
