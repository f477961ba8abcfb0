//! `grassbench validate FILE…`: checks scene and sweep files without rendering anything.

use std::path::PathBuf;

use anyhow::{Context as _, bail};
use grassbench::Scene;
use grassbench::sweep::SweepSpec;

use crate::registry;

/// Arguments of `validate`.
#[derive(Clone, Debug, clap::Args)]
pub struct ValidateArgs {
    /// Scene or sweep files (TOML); a file with a `scenes` key is a sweep.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
}

/// Validates every file, reporting each problem; fails if any file is invalid.
pub fn validate(args: &ValidateArgs) -> anyhow::Result<()> {
    let mut bad = 0;
    for path in &args.files {
        match check(path) {
            Ok(what) => eprintln!("ok: {} ({what})", path.display()),
            Err(e) => {
                bad += 1;
                eprintln!("invalid: {e:#}");
            }
        }
    }
    if bad > 0 {
        bail!("{bad} of {} files are invalid", args.files.len());
    }
    Ok(())
}

fn check(path: &std::path::Path) -> anyhow::Result<String> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read `{}`", path.display()))?;
    let is_sweep = text
        .parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("scenes"));
    if !is_sweep {
        let scene = Scene::from_toml(&text, path)?;
        for id in scene.config.techniques.keys() {
            registry::find(id)
                .and_then(|entry| entry.check(&scene.technique_overrides(id)))
                .with_context(|| format!("{}: [techniques.{id}]", path.display()))?;
        }
        return Ok(format!(
            "scene `{}`, {} blades",
            scene.name(),
            scene.blades.all_blades(&scene.terrain).len()
        ));
    }
    let spec = SweepSpec::from_toml(&text, path)?;
    let (plan, _) = super::sweep::load_plan(&spec, path, registry::TECHNIQUES)?;
    Ok(format!("sweep `{}`, {} runs", spec.name, plan.len()))
}
