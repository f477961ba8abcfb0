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
    ("meadow_fluid", include_str!("../scenes/meadow_fluid.toml")),
    (
        "meadow_point_source",
        include_str!("../scenes/meadow_point_source.toml"),
    ),
];

/// The scenes the default comparison runs (`--scene default`).
pub const DEFAULT_SCENES: &[&str] = &["meadow", "football_field", "prairie_flyover"];

/// Loads the scenes a `--scene` argument names: `default` for [`DEFAULT_SCENES`], otherwise
/// comma-separated built-in names or paths.
pub fn select(list: &str) -> Result<Vec<Scene>> {
    if list.trim() == "default" {
        DEFAULT_SCENES.iter().map(|n| load(n)).collect()
    } else {
        list.split(',').map(|n| load(n.trim())).collect()
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_names_the_default_comparison_and_lists_are_split() {
        let names = |list: &str| -> Vec<String> {
            select(list)
                .unwrap()
                .iter()
                .map(|s| s.name().to_owned())
                .collect()
        };
        assert_eq!(names("default"), DEFAULT_SCENES);
        assert_eq!(names(" default "), DEFAULT_SCENES);
        assert_eq!(
            names("meadow, football_field"),
            ["meadow", "football_field"]
        );
        let e = select("meadow,nowhere").unwrap_err().to_string();
        assert!(e.contains("nowhere"), "{e}");
    }
}
