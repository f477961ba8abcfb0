//! Reads the revision the `grassbench` command is built from, for the `meta.toml` of every
//! result it writes (`grassbench::runner::Provenance::build_revision`): the figures are the
//! build's, whatever tree the command later runs in.

include!("../src/runner/git_revision.rs");

fn main() {
    // Read again when the binary's sources or the checked-out commit change (a folder is
    // scanned whole; the test crates are not in the binary, and an edit of theirs alone need
    // not rebuild it).
    for path in [
        "../src",
        "../techniques",
        "src",
        "build.rs",
        "Cargo.toml",
        "../Cargo.toml",
        "../Cargo.lock",
        "../.git/HEAD",
        "../.git/index",
        "../.git/packed-refs",
        "../.git/refs/heads",
    ] {
        // A path that does not exist would make Cargo run this script at every build.
        if std::path::Path::new(path).exists() {
            println!("cargo::rerun-if-changed={path}");
        }
    }
    println!(
        "cargo::rustc-env=GRASSBENCH_BUILD_REVISION={}",
        git_revision()
    );
}
