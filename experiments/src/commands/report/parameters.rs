//! The report's "Parameters" section: each technique parameter that varies in the sweep, with
//! the values it took and what its parameter struct says of it (description, valid range or
//! choices, unit), so a reader of a table labelled `fade_radius=0.1` knows what was changed.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

use grassbench::params::ParamDoc;
use grassbench::technique::VARIANT_KEY;

use super::configs::Config;

/// Technique → key → the values it takes, for every key with more than one value among the
/// technique's configurations (the named operating point, [`VARIANT_KEY`], left out).
pub(super) fn varying(
    configs: &BTreeMap<String, Config>,
) -> BTreeMap<String, BTreeMap<String, BTreeSet<String>>> {
    let mut values: BTreeMap<String, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for c in configs.values() {
        for (k, v) in c.params.split(';').filter_map(|kv| kv.split_once('=')) {
            if k != VARIANT_KEY {
                values
                    .entry(c.technique.clone())
                    .or_default()
                    .entry(k.to_owned())
                    .or_default()
                    .insert(v.to_owned());
            }
        }
    }
    for keys in values.values_mut() {
        keys.retain(|_, v| v.len() > 1);
    }
    values.retain(|_, keys| !keys.is_empty());
    values
}

/// Appends the "Parameters" section (nothing when no technique parameter varies).
pub(super) fn section(md: &mut String, configs: &BTreeMap<String, Config>) {
    let varying = varying(configs);
    if varying.is_empty() {
        return;
    }
    let _ = writeln!(md, "\n## Parameters\n");
    let _ = writeln!(
        md,
        "The technique parameters that vary in this sweep, as their parameter structs describe them (`grassbench list` shows every parameter).\n"
    );
    let _ = writeln!(
        md,
        "| technique | parameter | values | default | valid | unit | description |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|");
    for (technique, keys) in &varying {
        let docs: BTreeMap<String, ParamDoc> = crate::registry::find(technique)
            .map(|e| {
                e.describe()
                    .into_iter()
                    .map(|d| (d.key.clone(), d))
                    .collect()
            })
            .unwrap_or_default();
        for (key, values) in keys {
            let mut values: Vec<&str> = values.iter().map(|v| v.trim_matches('"')).collect();
            // Numbers in numeric order (9 before 17), anything else as text.
            values.sort_by(|a, b| match (a.parse::<f64>(), b.parse::<f64>()) {
                (Ok(x), Ok(y)) => x.total_cmp(&y),
                _ => a.cmp(b),
            });
            let values = values.join(", ");
            let row = match docs.get(key) {
                Some(d) => format!(
                    "| {technique} | `{key}` | {values} | {} | {} | {} | {} |",
                    grassbench::params::format_value(&d.default),
                    cell(&d.bounds()),
                    d.unit.as_deref().unwrap_or("–"),
                    cell(&d.description)
                ),
                None => format!(
                    "| {technique} | `{key}` | {values} | – | – | – | (not a parameter of this build's `{technique}`) |"
                ),
            };
            let _ = writeln!(md, "{row}");
        }
    }
}

/// `text` for a Markdown table cell: pipes escaped, `–` for nothing.
fn cell(text: &str) -> String {
    if text.is_empty() {
        "–".to_owned()
    } else {
        text.replace('|', "\\|")
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    fn config(technique: &str, params: &str) -> Config {
        Config {
            technique: technique.to_owned(),
            params: params.to_owned(),
            ..Config::default()
        }
    }

    #[test]
    fn the_section_describes_each_varying_key_with_its_range_unit_and_values() {
        let configs: BTreeMap<String, Config> = [
            config(
                "zhang",
                "variant=paper;grids=16;petal_size=0.07;sorting=\"sort\"",
            ),
            config(
                "zhang",
                "grids=16;petal_size=0.1;sorting=\"alpha_to_coverage\"",
            ),
            config("reference", "segments=5"),
            config("reference", "segments=5"),
            config("bakay", "shells=9"),
            config("bakay", "shells=17"),
            config("perbet", "retired=1"),
            config("perbet", "retired=2"),
        ]
        .into_iter()
        .enumerate()
        .map(|(i, c)| (i.to_string(), c))
        .collect();
        let v = varying(&configs);
        assert_eq!(
            v.keys().collect::<Vec<_>>(),
            ["bakay", "perbet", "zhang"],
            "reference varies nothing"
        );
        assert_eq!(
            v["zhang"].keys().collect::<Vec<_>>(),
            ["petal_size", "sorting"],
            "grids and the variant do not vary"
        );
        let mut md = String::new();
        section(&mut md, &configs);
        assert!(md.contains("## Parameters"), "{md}");
        assert!(
            md.contains("| zhang | `petal_size` | 0.07, 0.1 | 0.07 | [0.001, 10] | m | Petal quad side, m. |"),
            "{md}"
        );
        assert!(
            md.contains(
                "| zhang | `sorting` | alpha_to_coverage, sort | sort | \"sort\" \\| \"alpha_to_coverage\" | – | Far-to-near sorting"
            ),
            "{md}"
        );
        assert!(
            md.contains("(not a parameter of this build's `perbet`)"),
            "{md}"
        );
        assert!(
            md.contains("| bakay | `shells` | 9, 17 | 16 | [1, 128] |"),
            "{md}"
        );
        let mut none = String::new();
        section(
            &mut none,
            &[("a".to_owned(), config("reference", "segments=5"))].into(),
        );
        assert!(none.is_empty());
    }
}
