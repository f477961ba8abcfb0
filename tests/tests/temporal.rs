//! Temporal fidelity (issue 19 §3): along slow camera motions every technique's frame-to-frame
//! change is compared with the reference's, pixel by pixel, as spurious change (the technique
//! changes where the reference does not: popping, shimmer) and missing change (the reference
//! changes where the technique does not: blur, frozen impostors). A picture that loses detail
//! must score as missing change, never as "steadier than the reference"; a technique switching
//! levels without transitions must never show less spurious change than with them.

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
/// `no_transitions` variant never shows less spurious change than the default. (Where the
/// transition is meant to hide a switch, the switch must show: boulanger's seamless LOD is
/// tested on the pitch's dolly, whose bands sweep through the view, in
/// `gpu_boulanger_btf.rs`. On the meadow's short motions the levels of perbet and jahrmann
/// change in few pixels, and against their own finest representation perbet's morphs — blades
/// sliding to their painted places — add more change than the switch they replace (dolly,
/// 1/4 scale: spurious mean 0.086 with transitions, 0.050 without), jahrmann's blend about as
/// much (0.072 against 0.068): reported here and in `results/compare/`, not bounded.)
#[test]
fn spurious_and_missing_change_of_every_technique() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let scene = scene("meadow", DENSITY)?;
    let reference = grassbench_cli::registry::find("reference")?;
    let mut failures = Vec::new();
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
                let off = off?;
                let frames_off =
                    compare::motion_frames(&gpu, &scene, entry, &off, motion, STEPS, TEST_SIZE)?;
                let p = compare::temporal_change(motion, Scale::Quarter, &frames_off, &base)?;
                show(id, NO_TRANSITIONS, &p);
                // Switching without transitions never shows less spurious change against the
                // reference (2 % for rounding: levels that follow the camera's position do not
                // change on a pan, where both are equal).
                if p.spurious.mean < c.spurious.mean * 0.98 {
                    failures.push(format!(
                        "{id}: without transitions the {} spurious mean is {:.3}, below {:.3} with them",
                        c.motion, p.spurious.mean, c.spurious.mean
                    ));
                }
                // The same two against the technique's own finest representation: what is left
                // is the change its levels of detail add, without the blade placement it does
                // not share with the reference. Reported, not bounded: see the test's docs.
                let finest = compare::motion_frames(
                    &gpu,
                    &scene,
                    entry,
                    &entry.finest()?,
                    motion,
                    STEPS,
                    TEST_SIZE,
                )?;
                for (name, f) in [("default", &frames), (NO_TRANSITIONS, &frames_off)] {
                    let own = compare::temporal_change(motion, Scale::Quarter, f, &finest)?;
                    show(id, &format!("{name} against its finest"), &own);
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

/// Bounds on a technique's temporal figures at 1/4 scale.
struct Limits {
    /// 95th percentile over the steps of the spurious change.
    spurious_p95: f64,
    /// Mean over the steps of the missing change.
    missing_mean: f64,
}

/// Measured on lavapipe (meadow at a quarter of its blades, 320x180, 6 steps of each motion,
/// 1/4 scale; dolly / pan): each limit about 25 % above the larger of the two, for other
/// rasterisers. Missing change cannot exceed 1 (it is at most the reference's own change).
fn limits(id: &str) -> Limits {
    match id {
        // The reference against itself: zero, exactly.
        "reference" => Limits {
            spurious_p95: 0.0,
            missing_mean: 0.0,
        },
        // Its blades stand where the reference's stand (issue 19); what differs is their
        // shape and sway and the far billboards: spurious p95 0.385 / 0.359, missing mean
        // 0.351 / 0.384.
        "zhang" => Limits {
            spurious_p95: 0.48,
            missing_mean: 0.48,
        },
        // Slices softer and brighter than the blades they replace: spurious p95 0.461 /
        // 0.288, missing mean 0.566 / 0.676.
        "boulanger" => Limits {
            spurious_p95: 0.58,
            missing_mean: 0.85,
        },
        // Shells at the scene's density show little of the walker's grazing view: it misses
        // most of the reference's change and adds little (spurious p95 0.092 / 0.096, missing
        // mean 0.812 / 0.846): the figure that would have scored it "steadiest" before.
        "bakay" => Limits {
            spurious_p95: 0.12,
            missing_mean: 0.95,
        },
        // Strips and the 2D texture: spurious p95 0.302 / 0.305, missing mean 0.625 / 0.639.
        "perbet" => Limits {
            spurious_p95: 0.38,
            missing_mean: 0.80,
        },
        // The reference's blades as Bezier curves, culled and thinned with distance: spurious
        // p95 0.334 / 0.339, missing mean 0.243 / 0.262.
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
