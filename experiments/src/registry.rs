//! Every technique grassbench knows. Adding one is one line here plus its crate under
//! `techniques/` (and a dependency line in `experiments/Cargo.toml`).

use grassbench::technique::TechniqueEntry;
use grassbench::{Error, Result};

/// The registry, in the order techniques appear in tables and the UI.
pub const TECHNIQUES: &[TechniqueEntry] = &[
    grassbench_reference::ENTRY,
    grassbench_zhang::ENTRY,
    grassbench_boulanger::ENTRY,
    grassbench_bakay::ENTRY,
    grassbench_perbet::ENTRY,
    grassbench_jahrmann::ENTRY,
];

/// The entry with id `id`.
pub fn find(id: &str) -> Result<&'static TechniqueEntry> {
    find_in(TECHNIQUES, id)
}

/// All ids.
pub fn ids() -> Vec<&'static str> {
    ids_in(TECHNIQUES)
}

/// The entry with id `id` in `entries` (the registry, or the registry extended by a test with
/// techniques of its own, as `commands::sweep_with` takes it).
pub fn find_in<'a>(entries: &'a [TechniqueEntry], id: &str) -> Result<&'a TechniqueEntry> {
    entries
        .iter()
        .find(|e| e.info.id == id)
        .ok_or_else(|| Error::UnknownName {
            kind: "technique",
            name: id.to_owned(),
            valid: ids_in(entries).join(", "),
        })
}

/// The ids of `entries`.
pub fn ids_in(entries: &[TechniqueEntry]) -> Vec<&'static str> {
    entries.iter().map(|e| e.info.id).collect()
}

/// Entries for a comma-separated list of ids, or every entry for `all`.
pub fn select(spec: &str) -> Result<Vec<&'static TechniqueEntry>> {
    if spec.trim() == "all" {
        return Ok(TECHNIQUES.iter().collect());
    }
    spec.split(',').map(|s| find(s.trim())).collect()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::panic)]

    use super::*;

    /// Every parameter of every registered technique has a description, each numeric one a
    /// range (or its type's), and the technique's check accepts each range's ends and refuses
    /// the values just past them: the schema and `validate` are one source of truth.
    #[test]
    fn every_parameter_is_described_and_checked_by_its_schema_range() {
        // Fig. 13's ordering and the blades a patch may hold narrow these.
        let narrowed = [
            "boulanger.blades_per_m2",
            "boulanger.max_geom",
            "boulanger.min_btf",
            "boulanger.max_btf",
        ];
        let mut problems = Vec::new();
        for e in TECHNIQUES {
            let docs = e.describe();
            assert_eq!(
                docs.iter()
                    .map(|d| d.key.clone())
                    .collect::<std::collections::BTreeSet<_>>(),
                e.default_params().keys().cloned().collect(),
                "{}: described keys are the parameter keys",
                e.info.id
            );
            for d in &docs {
                if d.description.trim().is_empty() {
                    problems.push(format!("{}.{}: no description", e.info.id, d.key));
                }
                let numeric = matches!(
                    d.default,
                    toml::Value::Float(_) | toml::Value::Integer(_) | toml::Value::Array(_)
                );
                if numeric && d.range.is_none() {
                    problems.push(format!("{}.{}: no range in the schema", e.info.id, d.key));
                }
            }
            let check = |o: &toml::Table| e.check(o);
            problems.extend(grassbench::params::range_disagreements(
                e.info.id, &docs, &check, &narrowed,
            ));
        }
        assert!(problems.is_empty(), "{problems:#?}");
    }

    #[test]
    fn ids_are_unique_and_every_variant_passes_its_technique_check() {
        let mut ids = ids();
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(ids.len(), TECHNIQUES.len(), "two techniques share an id");
        for e in TECHNIQUES {
            e.check(&toml::Table::new())
                .unwrap_or_else(|err| panic!("{}: defaults rejected: {err}", e.info.id));
            for v in e.variants.iter() {
                let overrides = e
                    .variant(v.name)
                    .unwrap()
                    .unwrap_or_else(|err| panic!("{}: {err}", e.info.id));
                e.check(&overrides).unwrap_or_else(|err| {
                    panic!("{}: variant `{}` rejected: {err}", e.info.id, v.name)
                });
            }
        }
    }
}
