//! The built-in scenes (embedded, so the binary works from any folder) and scene lookup by
//! name or path.

use std::path::{Path, PathBuf};

use grassbench::{Error, Result, Scene};

/// Built-in scenes: (name, TOML text).
pub const BUILT_IN: &[(&str, &str)] = &[
    ("meadow", include_str!("../scenes/meadow.toml")),
    (
        "football_field",
        include_str!("../scenes/football_field.toml"),
    ),
    (
        "prairie_flyover",
        include_str!("../scenes/prairie_flyover.toml"),
    ),
    (
        "football_field_human",
        include_str!("../scenes/football_field_human.toml"),
    ),
    (
        "meadow_primitives",
        include_str!("../scenes/meadow_primitives.toml"),
    ),
];

/// The scenes the default comparison runs.
pub const DEFAULT_SCENES: &[&str] = &["meadow", "football_field", "prairie_flyover"];

/// Folder holding the built-in scene files (maps they name are resolved against it).
pub fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

/// Loads a scene by built-in name, or by path to a scene TOML.
pub fn load(name_or_path: &str) -> Result<Scene> {
    if let Some((name, text)) = BUILT_IN.iter().find(|(n, _)| *n == name_or_path) {
        return Scene::from_toml(text, &scenes_dir().join(format!("{name}.toml")));
    }
    let path = Path::new(name_or_path);
    if path.extension().is_some_and(|e| e == "toml") || path.exists() {
        return Scene::load(path);
    }
    Err(Error::UnknownName {
        kind: "scene",
        name: name_or_path.to_owned(),
        valid: format!("{}, or a path to a scene .toml file", names().join(", ")),
    })
}

/// Names of the built-in scenes.
pub fn names() -> Vec<&'static str> {
    BUILT_IN.iter().map(|(n, _)| *n).collect()
}
