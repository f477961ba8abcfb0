// Included by `provenance.rs` (the revision of the tree a run reads) and by the command's build
// script, `experiments/build.rs` (the revision its binary was built from): one definition of
// what a revision is, for both ends.

/// `git describe`-like revision of the repository the current directory is in: the commit's
/// first 12 hexadecimal digits, with `+dirty` when a tracked source outside `results/` differs
/// from it (rewriting outputs does not make a build dirty), or `unknown` outside a repository.
fn git_revision() -> String {
    let run = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
    };
    match run(&["rev-parse", "--short=12", "HEAD"]) {
        Some(rev) => {
            // The whole repository's tracked files wherever in it the command runs (the build
            // script runs in its package's folder), results/ apart.
            let dirty = run(&[
                "status",
                "--porcelain",
                "--untracked-files=no",
                "--",
                ":(top)",
                ":(top,exclude)results",
            ])
            .is_some_and(|s| !s.is_empty());
            if dirty { format!("{rev}+dirty") } else { rev }
        }
        None => "unknown".to_owned(),
    }
}
