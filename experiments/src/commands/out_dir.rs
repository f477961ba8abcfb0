//! The output folder of a command that writes a fresh set of results (`run`, `compare`,
//! `merge`): new results are never mixed into an old folder's.

use std::path::Path;

use anyhow::{Context as _, bail};

/// Creates `dir`, refusing a non-empty one unless `force`, which empties it first.
pub fn prepare_out_dir(dir: &Path, force: bool) -> anyhow::Result<()> {
    let non_empty = std::fs::read_dir(dir)
        .map(|mut d| d.next().is_some())
        .unwrap_or(false);
    if non_empty {
        if !force {
            bail!(
                "output folder `{}` is not empty; choose another --out or pass --force to replace it",
                dir.display()
            );
        }
        std::fs::remove_dir_all(dir)
            .with_context(|| format!("cannot clear `{}`", dir.display()))?;
    }
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create `{}`", dir.display()))
}
