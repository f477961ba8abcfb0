//! Runs measured against their group's reference: a group is one scene variant at one size,
//! MSAA setting and repetition, and every run of it is divided by the `reference` technique's
//! run of the same group. The sweep computes the ratio as each run finishes; the report fills
//! in the ratios a sweep could not (a run written before its group's reference, in another
//! shard joined by `merge`). Both use [`ratio_to_reference`].

use std::collections::HashMap;

use crate::runner::RunSummary;
use crate::runner::bootstrap::speedup_interval_of_runs;

/// The technique every other is measured against (ratio and FLIP in a sweep's `runs.csv`).
pub const REFERENCE: &str = "reference";

/// `run`'s median GPU wall time over `reference`'s: below 1, the run is faster; `None`
/// when either has no measured time (a failed run).
pub fn ratio_to_reference(run: &RunSummary, reference: &RunSummary) -> Option<f64> {
    Some(run.gpu_wall_ms_median? / reference.gpu_wall_ms_median?)
}

/// Compares `run` with its group's `reference` run: sets the ratio, the speed-up and the
/// speed-up's 95 % bootstrap interval from both runs' per-frame GPU wall times
/// (`run_frames`, `reference_frames`; the interval stays empty without them, and for the
/// reference itself, whose speed-up is 1 by definition).
pub fn compare_with_reference(
    run: &mut RunSummary,
    reference: &RunSummary,
    run_frames: &[f64],
    reference_frames: &[f64],
) {
    run.gpu_wall_ratio_to_reference = ratio_to_reference(run, reference);
    run.speedup = run.gpu_wall_ratio_to_reference.map(f64::recip);
    let interval = if run.technique == REFERENCE {
        None
    } else {
        speedup_interval_of_runs(reference_frames, run_frames)
    };
    run.speedup_ci_low = interval.map(|i| i.low);
    run.speedup_ci_high = interval.map(|i| i.high);
}

/// What a row's group is known by in `runs.csv`: scene, scene variant, size, MSAA, repetition.
type GroupKey<'a> = (&'a str, &'a str, u32, u32, bool, u32);

fn group_of(run: &RunSummary) -> GroupKey<'_> {
    (
        &run.scene,
        &run.scene_variant,
        run.width,
        run.height,
        run.msaa,
        run.repetition,
    )
}

/// Gives every finished run without a ratio its ratio (and speed-up, with its interval where
/// `frames` holds both runs' per-frame GPU wall times, by run id) to the finished reference run
/// of its group (the last such row when a group holds several, as in the sweep, where each
/// reference run replaces the one before); runs whose group has none keep none.
pub fn fill_ratios(rows: &mut [RunSummary], frames: &HashMap<String, Vec<f64>>) {
    let references: HashMap<GroupKey<'_>, usize> = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| r.technique == REFERENCE && r.is_ok())
        .map(|(k, r)| (group_of(r), k))
        .collect();
    let pairs: Vec<(usize, usize)> = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| r.gpu_wall_ratio_to_reference.is_none() && r.is_ok())
        .filter_map(|(k, r)| Some((k, *references.get(&group_of(r))?)))
        .collect();
    let empty = Vec::new();
    for (k, reference) in pairs {
        let reference_row = rows[reference].clone();
        let run_frames = frames.get(&rows[k].run_id).unwrap_or(&empty);
        let reference_frames = frames.get(&reference_row.run_id).unwrap_or(&empty);
        compare_with_reference(&mut rows[k], &reference_row, run_frames, reference_frames);
    }
    for row in rows.iter_mut() {
        if row.speedup.is_none() {
            row.speedup = row.gpu_wall_ratio_to_reference.map(f64::recip);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(technique: &str, variant: &str, repetition: u32, ms: f64) -> RunSummary {
        let mut r = RunSummary::from_frames(&[], &toml::Table::new());
        r.technique = technique.to_owned();
        r.scene = "meadow".to_owned();
        r.scene_variant = variant.to_owned();
        r.repetition = repetition;
        r.gpu_wall_ms_median = Some(ms);
        r
    }

    #[test]
    fn ratios_come_from_the_reference_of_the_same_group() {
        let mut rows = vec![
            row("zhang", "d=1", 0, 5.0),
            row(REFERENCE, "d=1", 0, 20.0),
            row(REFERENCE, "d=2", 0, 40.0),
            row("zhang", "d=2", 0, 10.0),
            // Another repetition, with no reference: no ratio.
            row("zhang", "d=1", 1, 5.0),
            // Already known: kept.
            row("bakay", "d=1", 0, 1.0),
            // Failed: none.
            row("perbet", "d=1", 0, 0.0),
        ];
        rows[5].gpu_wall_ratio_to_reference = Some(0.5);
        rows[6].status = "failed".to_owned();
        fill_ratios(&mut rows, &HashMap::new());
        let ratios: Vec<Option<f64>> = rows.iter().map(|r| r.gpu_wall_ratio_to_reference).collect();
        assert_eq!(
            ratios,
            [
                Some(0.25),
                Some(1.0),
                Some(1.0),
                Some(0.25),
                None,
                Some(0.5),
                None
            ]
        );
        assert_eq!(ratio_to_reference(&rows[0], &rows[1]), Some(0.25));
    }

    #[test]
    fn a_failed_reference_gives_no_ratio_and_the_last_reference_counts() {
        let mut rows = vec![
            row(REFERENCE, "", 0, 10.0),
            row(REFERENCE, "", 0, 20.0),
            row("zhang", "", 0, 5.0),
        ];
        fill_ratios(&mut rows, &HashMap::new());
        assert_eq!(rows[2].gpu_wall_ratio_to_reference, Some(0.25));
        let mut rows = vec![row(REFERENCE, "", 0, 10.0), row("zhang", "", 0, 5.0)];
        rows[0].status = "failed".to_owned();
        fill_ratios(&mut rows, &HashMap::new());
        assert_eq!(rows[1].gpu_wall_ratio_to_reference, None);
    }
}
