//! Every WGSL shader in the repository parses and validates with naga (no GPU needed). The Rust
//! mirrors of uniform and storage structs are checked against their WGSL layouts in the crate
//! that owns both (`grassbench::shaders::struct_size`); the core's `Globals` here.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::{Path, PathBuf};

use grassbench::shaders;
use grassbench_tests::repo_root;

/// `src/shaders/*.wgsl` and `techniques/*/shaders/*.wgsl`.
fn all_shaders() -> Vec<PathBuf> {
    let root = repo_root();
    let mut dirs = vec![root.join("src/shaders")];
    for entry in std::fs::read_dir(root.join("techniques")).unwrap() {
        dirs.push(entry.unwrap().path().join("shaders"));
    }
    let mut files: Vec<PathBuf> = dirs
        .iter()
        .filter_map(|d| std::fs::read_dir(d).ok())
        .flatten()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "wgsl"))
        .collect();
    files.sort();
    files
}

fn module_of(path: &Path) -> naga::Module {
    let text = std::fs::read_to_string(path).unwrap();
    // The prelude is standalone; every other shader is composed after it.
    let source = if path.ends_with("prelude.wgsl") {
        text
    } else {
        shaders::compose(&text)
    };
    let module = naga::front::wgsl::parse_str(&source)
        .unwrap_or_else(|e| panic!("{}: {}", path.display(), e.emit_to_string(&source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{}: {}", path.display(), e.emit_to_string(&source)));
    module
}

#[test]
fn every_shader_validates() {
    let files = all_shaders();
    assert!(files.len() >= 3, "found only {files:?}");
    for f in &files {
        module_of(f);
    }
}
