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

/// Every finding of `find` in every shader, named `file: finding`.
fn findings(find: impl Fn(&naga::Module) -> Vec<String>) -> Vec<String> {
    all_shaders()
        .iter()
        .flat_map(|f| {
            let file = f
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            find(&module_of(f))
                .into_iter()
                .map(move |finding| format!("{file}: {finding}"))
        })
        .collect()
}

/// No shader loops as many times as a uniform buffer says: lavapipe re-specialises such a
/// shader every time its pipeline is bound, on the CPU and outside every timestamped pass
/// (5-6 ms a frame for bakay's bend pass; `grassbench::shaders::uniform_bound_loops`), a cost
/// no GPU pays and the cost model cannot see.
#[test]
fn no_loop_is_bounded_by_a_uniform() {
    let offenders = findings(|module| {
        shaders::uniform_bound_loops(module)
            .into_iter()
            .map(|function| format!("`{function}`"))
            .collect()
    });
    assert!(
        offenders.is_empty(),
        "loops bounded by a uniform-buffer value: {offenders:?}; make a count fixed at \
         creation a pipeline-overridable constant (`override`, `PipelineSpec::constants`) and \
         one that changes every frame a storage-buffer value"
    );
}

/// No vertex shader branches on uniform-buffer values alone: lavapipe can re-specialise such a
/// shader every time its pipeline is bound, on the CPU inside the pass (one LLVM module a frame
/// for the reference's vertex shader and two for boulanger's slices while they had one;
/// `grassbench::shaders::uniform_branches`), a cost no GPU pays and the cost model cannot see.
#[test]
fn no_vertex_shader_branches_on_a_uniform_alone() {
    let offenders = findings(|module| {
        shaders::uniform_branches(module)
            .into_iter()
            .filter(|b| b.stage == naga::ShaderStage::Vertex)
            .map(|b| format!("`{}` in `{}`", b.function, b.entry))
            .collect()
    });
    assert!(
        offenders.is_empty(),
        "vertex shaders branching on uniform-buffer values alone: {offenders:?}; make a flag \
         fixed at creation a pipeline-overridable constant (`override`, \
         `PipelineSpec::constants`), and one that may change a `select` (with `&` and `|`, \
         which do not short-circuit into branches) or a storage-buffer value"
    );
}
