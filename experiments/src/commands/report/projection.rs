//! Projection to another adapter (issue 20 §4): each run's measured work priced with the unit
//! costs another adapter was calibrated with, so a reader can see what the same frames would
//! cost there. Everything it prints is labelled *predicted*. Where the calibration is the
//! `meta.toml` of a sweep of the same configurations run on that adapter (its `runs.csv`
//! beside it), the prediction is checked against what was measured there, run by run.

use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context as _, bail};
use grassbench::cost::UnitCosts;
use grassbench::runner::Provenance;
use grassbench::sweep::REFERENCE;

use super::configs::{Config, label, median};

/// Another adapter's calibration: its unit costs (one per size it was calibrated at) and
/// where they were measured.
pub(super) struct Calibration {
    /// The unit costs.
    pub(super) costs: Vec<UnitCosts>,
    /// The adapter's name and backend, as its file records them.
    pub(super) adapter: String,
    /// The file.
    pub(super) path: String,
    /// The configurations measured on that adapter, where the file is a sweep's `meta.toml`
    /// with its `runs.csv` beside it (keyed like this folder's: the same sweep file gives the
    /// same configuration ids on any adapter).
    pub(super) measured: Option<BTreeMap<String, Config>>,
}

/// How far a projection may miss what was measured there and still count as a transfer
/// (issue 20 §4: ±25 %).
pub(super) const TRANSFER_TOLERANCE: f64 = 0.25;

impl Calibration {
    /// Reads `path`: a results folder's `meta.toml` (`[[unit_costs]]`, from `run` or
    /// `sweep`) or the file `grassbench calibrate -o` writes (`[unit_costs]`).
    pub(super) fn load(path: &Path) -> anyhow::Result<Self> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read the calibration `{}`", path.display()))?;
        let value: toml::Table =
            toml::from_str(&text).with_context(|| format!("`{}` is not TOML", path.display()))?;
        let costs: Vec<UnitCosts> = match value.get("unit_costs") {
            Some(toml::Value::Array(a)) => a
                .iter()
                .map(|v| v.clone().try_into())
                .collect::<Result<_, _>>()
                .with_context(|| format!("`{}`: [[unit_costs]]", path.display()))?,
            Some(v @ toml::Value::Table(_)) => vec![
                v.clone()
                    .try_into()
                    .with_context(|| format!("`{}`: [unit_costs]", path.display()))?,
            ],
            _ => bail!(
                "`{}` holds no unit costs: pass the meta.toml of a `run` or `sweep` made with calibration, or a file from `grassbench calibrate -o FILE`",
                path.display()
            ),
        };
        if costs.is_empty() {
            bail!("`{}` holds an empty list of unit costs", path.display());
        }
        let adapter = value
            .get("provenance")
            .or(Some(&toml::Value::Table(value.clone())))
            .and_then(|p| p.clone().try_into::<Provenance>().ok())
            .map_or_else(
                || "the other adapter".to_owned(),
                |p| format!("{} ({})", p.adapter.name, p.adapter.backend),
            );
        let runs = path.with_file_name("runs.csv");
        let measured = match path.parent() {
            Some(dir) if runs.exists() => Some(
                super::configs::load(dir)
                    .with_context(|| format!("the runs beside `{}`", path.display()))?,
            ),
            _ => None,
        };
        Ok(Self {
            costs,
            adapter,
            path: path.display().to_string(),
            measured,
        })
    }

    /// The costs calibrated at `size` drawn as `msaa` says, else the first drawn so (the
    /// fixed cost per frame then belongs to another size: flagged in the table, `false`);
    /// `None` where none was drawn so (with MSAA or without: [`UnitCosts::prices`]).
    fn for_target(&self, size: &str, msaa: bool) -> Option<(&UnitCosts, bool)> {
        UnitCosts::for_target(&self.costs, size, msaa)
            .map(|c| (c, true))
            .or_else(|| {
                self.costs
                    .iter()
                    .find(|c| c.prices(msaa))
                    .map(|c| (c, false))
            })
    }
}

/// Writes the projection section: per configuration with measured work, its time here
/// (measured) and on the other adapter (predicted), and the predicted speed-up over its
/// group's reference there.
pub(super) fn projection(
    md: &mut String,
    configs: &BTreeMap<String, Config>,
    other: &Calibration,
) -> anyhow::Result<()> {
    let _ = writeln!(md, "\n## Predicted on {} (projection)\n", other.adapter);
    let _ = writeln!(
        md,
        "Each run's measured work (per frame, from frames.csv) priced with the unit costs of `{}`: **predicted** times on that adapter, not measurements. A size marked * was priced with costs calibrated at another size (its fixed cost per frame differs).\n",
        other.path
    );
    // Only runs drawn as some of the other adapter's costs were (with MSAA or without).
    let unpriced = configs
        .values()
        .filter(|c| c.work.is_some() && other.for_target(&c.size, c.msaa).is_none())
        .count();
    if unpriced > 0 {
        let _ = writeln!(
            md,
            "{unpriced} configuration(s) are not priced: drawn with MSAA or without, where every cost in that file was calibrated the other way (MSAA's per-sample coverage, depth tests and resolve are work a single-sampled calibration does not do).\n"
        );
    }
    let predicted: HashMap<String, f64> = configs
        .iter()
        .filter_map(|(id, c)| {
            let (costs, _) = other.for_target(&c.size, c.msaa)?;
            Some((id.clone(), costs.predict(&c.work?).total_ms))
        })
        .collect();
    if predicted.is_empty() {
        let _ = writeln!(
            md,
            "No run here has counted work (the adapter had no pipeline statistics), so nothing can be projected.\n"
        );
        return Ok(());
    }
    let group = |c: &Config| (c.scene.clone(), c.variant.clone(), c.size.clone(), c.msaa);
    let reference: HashMap<_, f64> = configs
        .iter()
        .filter(|(_, c)| c.technique == REFERENCE)
        .filter_map(|(id, c)| Some((group(c), *predicted.get(id)?)))
        .collect();
    // Measured there, for the configurations the other folder ran.
    let there: HashMap<&String, f64> = other
        .measured
        .iter()
        .flatten()
        .filter_map(|(id, c)| Some((id, median(&c.gpu_wall)?)))
        .collect();
    let checked: Vec<f64> = predicted
        .iter()
        .filter_map(|(id, p)| Some(p / there.get(id)?))
        .collect();
    if !checked.is_empty() {
        let (low, high) = checked
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), r| (l.min(*r), h.max(*r)));
        let within = checked
            .iter()
            .filter(|r| (**r - 1.0).abs() <= TRANSFER_TOLERANCE)
            .count();
        let _ = writeln!(
            md,
            "**Checked against what was measured there** (the `runs.csv` beside that file, the same configurations): predicted / measured from {low:.2} to {high:.2}; {within} of {} within ±{:.0} %.\n",
            checked.len(),
            TRANSFER_TOLERANCE * 100.0
        );
    }
    let _ = writeln!(
        md,
        "| scene | size | technique | params | measured here, GPU ms | predicted there, GPU ms | measured there, GPU ms | predicted / measured there | predicted speed-up there | measured speed-up here |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|---|");
    for (id, c) in configs {
        let Some(p) = predicted.get(id) else { continue };
        let exact = other
            .for_target(&c.size, c.msaa)
            .is_some_and(|(_, exact)| exact);
        let measured_there = there.get(id).copied();
        let _ = writeln!(
            md,
            "| {} | {}{} | {} | {} | {} | {:.2} | {} | {} | {} | {} |",
            c.scene,
            c.size,
            if exact { "" } else { "*" },
            c.technique,
            label(c).trim_start_matches(&c.technique).trim(),
            super::fmt(median(&c.gpu_wall), 1),
            p,
            super::fmt(measured_there, 1),
            super::fmt(measured_there.map(|m| p / m), 2),
            super::fmt(reference.get(&group(c)).map(|r| r / p), 2),
            super::fmt(median(&c.ratio).map(|r| 1.0 / r), 2),
        );
    }
    Ok(())
}
