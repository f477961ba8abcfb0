//! Temporal fidelity (issue 19 §3): along slow camera motions every technique's frame-to-frame
//! change is compared with the reference's, pixel by pixel, as spurious change (the technique
//! changes where the reference does not: popping, shimmer) and missing change (the reference
//! changes where the technique does not: blur, frozen impostors). A picture that loses detail
//! must score as missing change, never as "steadier than the reference"; a technique switching
//! levels without transitions must show more spurious change than with them.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use grassbench::compare::{self, CameraMotion, Scale, TemporalChange};
use grassbench::technique::NO_TRANSITIONS;
use grassbench_tests::{TEST_SIZE, gpu, scene};

/// The comparison suite's meadow, at a quarter of its blades (software rasteriser).
const DENSITY: f32 = 0.25;
/// Steps along each motion.
const STEPS: u32 = 6;
/// The motions of `grassbench compare`.
const MOTIONS: [CameraMotion; 2] = [CameraMotion::Dolly(0.25), CameraMotion::Pan(0.6)];

fn show(id: &str, what: &str, c: &TemporalChange) {
    eprintln!(
        "measured: {id} {what}: {} {}: change {:.3}, spurious mean {:.3} p95 {:.3} peak {:.3}, missing mean {:.3} p95 {:.3} peak {:.3}",
        c.motion,
        c.scale.name(),
        c.technique_change,
        c.spurious.mean,
        c.spurious.p95,
        c.spurious.peak,
        c.missing.mean,
        c.missing.p95,
        c.missing.peak
    );
}

/// The reference's own frames, blurred, stand in for a technique that loses detail. The old
/// metric (the technique's total change over the reference's) called it steadier than the
/// reference; the new one calls it missing change.
///
/// Measured on lavapipe (meadow, quarter density, 320x180, 6 steps, Gaussian σ = 1.5 px):
/// see the "measured:" lines of `--nocapture`; the bounds sit well inside them.
#[test]
fn blur_scores_as_missing_change_not_as_steadiness() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let scene = scene("meadow", DENSITY)?;
    let reference = grassbench_cli::registry::find("reference")?;
    for motion in MOTIONS {
        let frames = compare::motion_frames(
            &gpu,
            &scene,
            reference,
            &toml::Table::new(),
            motion,
            STEPS,
            TEST_SIZE,
        )?;
        let blurred: Vec<_> = frames
            .iter()
            .map(|f| image::imageops::blur(f, 1.5))
            .collect();
        for scale in Scale::ALL {
            let c = compare::temporal_change(motion, scale, &blurred, &frames)?;
            show("reference blurred", "", &c);
            if scale == Scale::Full {
                // What fooled the old metric: the blurred picture changes less.
                assert!(
                    c.technique_change < BLUR_CHANGE,
                    "blur changed {:.3} of the reference's change",
                    c.technique_change
                );
            }
            assert!(
                c.missing.mean > BLUR_MISSING_OVER_SPURIOUS * c.spurious.mean,
                "{} {}: blur scores missing {:.3} against spurious {:.3}",
                motion.name(),
                scale.name(),
                c.missing.mean,
                c.spurious.mean
            );
        }
    }
    Ok(())
}

/// Blur must lower the total change (else it could not have fooled the old ratio).
const BLUR_CHANGE: f64 = 0.8;
/// How far missing change must exceed spurious change for blur.
const BLUR_MISSING_OVER_SPURIOUS: f64 = 3.0;

/// Per technique: spurious and missing change at 1/4 scale stay under measured bounds, and a
/// `no_transitions` variant never pops less than the default and pops more on some motion.
#[test]
fn spurious_and_missing_change_of_every_technique() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let scene = scene("meadow", DENSITY)?;
    let reference = grassbench_cli::registry::find("reference")?;
    let mut failures = Vec::new();
    let mut caught = std::collections::BTreeMap::new();
    for motion in MOTIONS {
        let base = compare::motion_frames(
            &gpu,
            &scene,
            reference,
            &toml::Table::new(),
            motion,
            STEPS,
            TEST_SIZE,
        )?;
        for entry in grassbench_cli::registry::TECHNIQUES {
            let id = entry.info.id;
            let frames = compare::motion_frames(
                &gpu,
                &scene,
                entry,
                &toml::Table::new(),
                motion,
                STEPS,
                TEST_SIZE,
            )?;
            let mut quarter = None;
            for scale in Scale::ALL {
                let c = compare::temporal_change(motion, scale, &frames, &base)?;
                show(id, "default", &c);
                if scale == Scale::Quarter {
                    quarter = Some(c);
                }
            }
            let c = quarter.expect("Scale::ALL holds the quarter scale");
            let limits = limits(id);
            if c.spurious.p95 > limits.spurious_p95 || c.missing.mean > limits.missing_mean {
                failures.push(format!(
                    "{id}: {} at 1/4: spurious p95 {:.3} (limit {}), missing mean {:.3} (limit {})",
                    c.motion,
                    c.spurious.p95,
                    limits.spurious_p95,
                    c.missing.mean,
                    limits.missing_mean
                ));
            }
            if let Some(off) = entry.variant(NO_TRANSITIONS) {
                let frames =
                    compare::motion_frames(&gpu, &scene, entry, &off?, motion, STEPS, TEST_SIZE)?;
                let p = compare::temporal_change(motion, Scale::Quarter, &frames, &base)?;
                show(id, NO_TRANSITIONS, &p);
                // Switching without transitions never pops less (levels that follow the camera's
                // position do not change on a pan: equal there, to rounding).
                if p.spurious.peak < c.spurious.peak * 0.99 {
                    failures.push(format!(
                        "{id}: without transitions the {} spurious peak is {:.3}, below {:.3} with them",
                        c.motion, p.spurious.peak, c.spurious.peak
                    ));
                }
                let ratio = p.spurious.peak / c.spurious.peak.max(1e-9);
                let best = caught.entry(id).or_insert(0.0f64);
                *best = best.max(ratio);
            }
        }
    }
    for (id, ratio) in caught {
        if ratio < NO_TRANSITIONS_PEAK_RATIO {
            failures.push(format!(
                "{id}: no motion's spurious peak without transitions exceeds the default's by x{NO_TRANSITIONS_PEAK_RATIO} (best x{ratio:.3})"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

/// How much higher the spurious peak without transitions must be, on the motion that shows it
/// best.
const NO_TRANSITIONS_PEAK_RATIO: f64 = 1.1;

/// Bounds on a technique's temporal figures at 1/4 scale.
struct Limits {
    /// 95th percentile over the steps of the spurious change.
    spurious_p95: f64,
    /// Mean over the steps of the missing change.
    missing_mean: f64,
}

fn limits(id: &str) -> Limits {
    match id {
        // The reference against itself: zero, exactly.
        "reference" => Limits {
            spurious_p95: 0.0,
            missing_mean: 0.0,
        },
        // jahrmann: measured at 1/4 scale, dolly / pan: spurious p95 0.334 / 0.339, missing
        // mean 0.243 / 0.262 (the same blades as the reference's drawn by another blade model:
        // most of its spurious change is the Bezier shapes' parallax, not popping); limits
        // about 25 % above. Without transitions: 0.336 / 0.346 and 0.241 / 0.257.
        "jahrmann" => Limits {
            spurious_p95: 0.42,
            missing_mean: 0.33,
        },
        // Ceilings for a technique nobody has measured: a blank or frozen picture misses all
        // of the reference's change (missing about 1), a flickering one adds more than it.
        _ => Limits {
            spurious_p95: 1.0,
            missing_mean: 1.0,
        },
    }
}
