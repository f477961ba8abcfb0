//! The reference against the adapter's raw blade rate (issue 20 §6): what one reference blade
//! costs in a frame, against what its nine triangles cost in the calibration's triangle
//! workload (tiny depth-tested strips, nothing else drawn). The share says how close the
//! brute-force baseline runs to the rasteriser's own limit; the target is 70 %.

use std::fmt::Write as _;

use grassbench::calibration::Calibration;
use grassbench::sweep::REFERENCE;

use super::configs::{Config, median};

/// The share of the raw rate the reference should reach on the canonical scenes.
pub(super) const TARGET_SHARE: f64 = 0.7;

/// The reference's measured cost per drawn blade (median GPU wall time over blades drawn), ns.
pub(super) fn ns_per_blade(c: &Config) -> Option<f64> {
    let blades = c.blades_drawn.filter(|b| *b > 0.0)?;
    Some(median(&c.gpu_wall)? * 1e6 / blades)
}

/// Writes the section: one row per reference configuration with drawn blades, its share of
/// the raw rate measured before the runs and, where the sweep measured it again after them
/// (`after`), of that one too: on a shared host the one reading moves the share as much as the
/// reference's frames do.
pub(super) fn raw_rate(
    md: &mut String,
    configs: &[&Config],
    calibration: &Calibration,
    after: Option<&Calibration>,
) {
    let rows: Vec<(&Config, f64)> = configs
        .iter()
        .filter(|c| c.technique == REFERENCE)
        .filter_map(|c| Some((*c, ns_per_blade(c)?)))
        .collect();
    if rows.is_empty() || calibration.raw_blade_cost_ns <= 0.0 {
        return;
    }
    let after = after.filter(|a| a.raw_blade_cost_ns > 0.0);
    let _ = writeln!(md, "\n## The reference against the raw blade rate\n");
    let _ = write!(
        md,
        "The calibration drew tiny depth-tested 9-triangle strips at {:.1} M triangles/s ({}): {:.0} ns for a reference blade's triangles with nothing else in the frame. Below, what a reference blade costs in each frame (median GPU wall time over blades drawn, sky, ground and props included) and the share of the raw rate that is (raw ns / measured ns; target {:.0} %).",
        calibration.triangles_per_s / 1e6,
        calibration.size,
        calibration.raw_blade_cost_ns,
        TARGET_SHARE * 100.0
    );
    if let Some(a) = after {
        let _ = write!(
            md,
            " Measured again once the runs were done: {:.0} ns ({:.2} times the first reading), the share against it in the last column.",
            a.raw_blade_cost_ns,
            a.raw_blade_cost_ns / calibration.raw_blade_cost_ns
        );
    }
    let _ = writeln!(md, "\n");
    let (extra_head, extra_rule) = if after.is_some() {
        (" share of raw rate after |", "---|")
    } else {
        ("", "")
    };
    let _ = writeln!(
        md,
        "| scene | variant | size | params | GPU ms | blades drawn | ns per blade | share of raw rate |{extra_head}"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|{extra_rule}");
    let share = |raw: &Calibration, ns: f64| {
        let share = raw.raw_blade_cost_ns / ns;
        let flag = if share >= TARGET_SHARE {
            ""
        } else {
            " (below target)"
        };
        format!("{:.0} %{flag}", share * 100.0)
    };
    for (c, ns) in rows {
        let extra = after.map_or(String::new(), |a| format!(" {} |", share(a, ns)));
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {:.1} | {:.0} | {:.0} | {} |{extra}",
            c.scene,
            c.variant,
            c.size,
            c.label,
            median(&c.gpu_wall).unwrap_or(f64::NAN),
            c.blades_drawn.unwrap_or(0.0),
            ns,
            share(calibration, ns),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cost_per_blade_is_time_over_blades_drawn() {
        let c = Config {
            technique: REFERENCE.into(),
            gpu_wall: vec![2.0, 4.0, 3.0],
            blades_drawn: Some(1.5e6),
            ..Config::default()
        };
        // 3 ms over 1.5 M blades: 2 ns.
        assert!((ns_per_blade(&c).unwrap() - 2.0).abs() < 1e-12);
        let none = Config {
            blades_drawn: Some(0.0),
            ..c.clone()
        };
        assert_eq!(ns_per_blade(&none), None);
    }

    #[test]
    fn rows_name_the_share_and_flag_a_miss() {
        let calibration = Calibration {
            size: "640x360".into(),
            triangles_per_s: 9e9,
            fill_pixels_per_s: 1.0,
            compute_bytes_per_s: 1.0,
            raw_blade_cost_ns: 1.0,
            clock: "wall".into(),
        };
        let fast = Config {
            technique: REFERENCE.into(),
            scene: "meadow".into(),
            gpu_wall: vec![1.0],
            blades_drawn: Some(1e6),
            ..Config::default()
        };
        let slow = Config {
            scene: "pitch".into(),
            gpu_wall: vec![4.0],
            ..fast.clone()
        };
        let other = Config {
            technique: "zhang".into(),
            ..fast.clone()
        };
        let mut md = String::new();
        raw_rate(&mut md, &[&fast, &slow, &other], &calibration, None);
        assert!(
            md.contains("| meadow |") && md.contains("| 100 % |"),
            "{md}"
        );
        assert!(md.contains("| 25 % (below target) |"), "{md}");
        assert!(!md.contains("zhang"), "{md}");
        assert!(!md.contains("after"), "{md}");
        // The raw path measured again after the runs, 1.5 times as slow: the shares against it
        // in a last column, the reading named.
        let after = Calibration {
            raw_blade_cost_ns: 1.5,
            ..calibration.clone()
        };
        let mut md = String::new();
        raw_rate(&mut md, &[&fast, &slow], &calibration, Some(&after));
        assert!(
            md.contains("again once the runs were done: 2 ns (1.50 times"),
            "{md}"
        );
        assert!(md.contains("| 100 % | 150 % |"), "{md}");
        assert!(
            md.contains("| 25 % (below target) | 38 % (below target) |"),
            "{md}"
        );
    }
}
