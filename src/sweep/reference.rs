//! Runs measured against their group's reference: a group is one scene variant at one size,
//! MSAA setting and repetition, and every run of it is divided by the `reference` technique's
//! run of the same group. The sweep computes the ratio as each run finishes; the report fills
//! in the ratios a sweep could not (a run written before its group's reference, in another
//! shard joined by `merge`). Both use [`ratio_to_reference`].

use std::collections::HashMap;

use crate::runner::RunSummary;

/// The technique every other is measured against (ratio and FLIP in a sweep's `runs.csv`).
pub const REFERENCE: &str = "reference";

/// `run`'s median GPU wall time over `reference`'s: below 1, the run is faster; `None`
/// when either has no measured time (a failed run).
pub fn ratio_to_reference(run: &RunSummary, reference: &RunSummary) -> Option<f64> {
    Some(run.gpu_wall_ms_median? / reference.gpu_wall_ms_median?)
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

/// Gives every finished run without a ratio its ratio to the finished reference run of its
/// group (the last such row when a group holds several, as in the sweep, where each reference
/// run replaces the one before); runs whose group has none keep none.
pub fn fill_ratios(rows: &mut [RunSummary]) {
    let references: HashMap<GroupKey<'_>, &RunSummary> = rows
        .iter()
        .filter(|r| r.technique == REFERENCE && r.is_ok())
        .map(|r| (group_of(r), r))
        .collect();
    let ratios: Vec<Option<f64>> = rows
        .iter()
        .map(|r| match r.gpu_wall_ratio_to_reference {
            Some(ratio) => Some(ratio),
            None if r.is_ok() => references
                .get(&group_of(r))
                .and_then(|reference| ratio_to_reference(r, reference)),
            None => None,
        })
        .collect();
    for (row, ratio) in rows.iter_mut().zip(ratios) {
        row.gpu_wall_ratio_to_reference = ratio;
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
        fill_ratios(&mut rows);
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
        fill_ratios(&mut rows);
        assert_eq!(rows[2].gpu_wall_ratio_to_reference, Some(0.25));
        let mut rows = vec![row(REFERENCE, "", 0, 10.0), row("zhang", "", 0, 5.0)];
        rows[0].status = "failed".to_owned();
        fill_ratios(&mut rows);
        assert_eq!(rows[1].gpu_wall_ratio_to_reference, None);
    }
}
