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
];

/// The entry with id `id`.
pub fn find(id: &str) -> Result<&'static TechniqueEntry> {
    TECHNIQUES
        .iter()
        .find(|e| e.info.id == id)
        .ok_or_else(|| Error::UnknownName {
            kind: "technique",
            name: id.to_owned(),
            valid: ids().join(", "),
        })
}

/// All ids.
pub fn ids() -> Vec<&'static str> {
    TECHNIQUES.iter().map(|e| e.info.id).collect()
}

/// Entries for a comma-separated list of ids, or every entry for `all`.
pub fn select(spec: &str) -> Result<Vec<&'static TechniqueEntry>> {
    if spec.trim() == "all" {
        return Ok(TECHNIQUES.iter().collect());
    }
    spec.split(',').map(|s| find(s.trim())).collect()
}
