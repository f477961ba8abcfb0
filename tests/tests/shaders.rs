//! Every WGSL shader in the repository parses and validates with naga (no GPU needed), and the
//! Rust mirrors of uniform structs have the sizes naga computes for the WGSL ones.

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

/// Size of the WGSL struct `name` as naga lays it out.
fn wgsl_size(module: &naga::Module, name: &str) -> u32 {
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    let (handle, _) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no struct {name}"));
    layouter[handle].size
}

#[test]
fn uniform_mirrors_match_wgsl_layouts() {
    let root = repo_root();
    let prelude = module_of(&root.join("src/shaders/prelude.wgsl"));
    assert_eq!(
        wgsl_size(&prelude, "Globals") as usize,
        std::mem::size_of::<grassbench::frame::FrameGlobals>()
    );
    let reference = module_of(&root.join("techniques/reference/shaders/blade.wgsl"));
    assert_eq!(
        wgsl_size(&reference, "Params") as usize,
        std::mem::size_of::<grassbench_reference::ParamsUniform>()
    );
    let zhang = module_of(&root.join("techniques/zhang/shaders/blade.wgsl"));
    assert_eq!(
        wgsl_size(&zhang, "Params") as usize,
        std::mem::size_of::<grassbench_zhang::ParamsUniform>()
    );
    let zhang_billboards = module_of(&root.join("techniques/zhang/shaders/billboard.wgsl"));
    assert_eq!(
        wgsl_size(&zhang_billboards, "Params") as usize,
        std::mem::size_of::<grassbench_zhang::ParamsUniform>()
    );
    let boulanger = module_of(&root.join("techniques/boulanger/shaders/grass.wgsl"));
    assert_eq!(
        wgsl_size(&boulanger, "Params") as usize,
        std::mem::size_of::<grassbench_boulanger::ParamsUniform>()
    );
    assert_eq!(
        wgsl_size(&boulanger, "Cell") as usize,
        std::mem::size_of::<grassbench_boulanger::CellRecord>()
    );
    assert_eq!(
        wgsl_size(&boulanger, "Blade") as usize,
        std::mem::size_of::<grassbench_boulanger::patch::PatchBlade>()
    );
    let bakay = module_of(&root.join("techniques/bakay/shaders/bakay.wgsl"));
    assert_eq!(
        wgsl_size(&bakay, "Params") as usize,
        std::mem::size_of::<grassbench_bakay::ParamsUniform>()
    );
    let perbet = module_of(&root.join("techniques/perbet/shaders/perbet.wgsl"));
    for (name, size) in [
        (
            "Params",
            std::mem::size_of::<grassbench_perbet::gpu::ParamsUniform>(),
        ),
        (
            "Entry",
            std::mem::size_of::<grassbench_perbet::frame::Entry>(),
        ),
        (
            "Blade",
            std::mem::size_of::<grassbench_perbet::gpu::BladeGpu>(),
        ),
    ] {
        assert_eq!(wgsl_size(&perbet, name) as usize, size, "perbet {name}");
    }
}

#[test]
fn shader_consts_in_crates_match_files() {
    let file = |p: &str| std::fs::read_to_string(repo_root().join(p)).unwrap();
    assert_eq!(
        grassbench_reference::SHADER,
        file("techniques/reference/shaders/blade.wgsl")
    );
    assert_eq!(
        grassbench_boulanger::SHADER,
        file("techniques/boulanger/shaders/grass.wgsl")
    );
    assert_eq!(
        grassbench_boulanger::btf::MIP_SHADER,
        file("techniques/boulanger/shaders/mip.wgsl")
    );
    assert_eq!(
        grassbench_zhang::SHADER,
        std::fs::read_to_string(repo_root().join("techniques/zhang/shaders/blade.wgsl")).unwrap()
    );
    assert_eq!(
        grassbench_zhang::PROPS_SHADER,
        std::fs::read_to_string(repo_root().join("techniques/zhang/shaders/props.wgsl")).unwrap()
    );
    assert_eq!(
        grassbench_zhang::BILLBOARD_SHADER,
        std::fs::read_to_string(repo_root().join("techniques/zhang/shaders/billboard.wgsl"))
            .unwrap()
    );
    assert_eq!(
        grassbench_bakay::SHADER,
        std::fs::read_to_string(repo_root().join("techniques/bakay/shaders/bakay.wgsl")).unwrap()
    );
    assert_eq!(
        grassbench_perbet::SHADER,
        file("techniques/perbet/shaders/perbet.wgsl")
    );
}
