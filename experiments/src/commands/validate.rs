//! `grassbench validate FILE…`: checks scene and sweep files without rendering anything.

use std::path::PathBuf;

use anyhow::{Context as _, bail};
use grassbench::Scene;
use grassbench::sweep::{SweepSpec, apply_overrides};

use crate::{registry, scenes};

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
            let entry = registry::find(id)
                .with_context(|| format!("{}: [techniques.{id}]", path.display()))?;
            let defaults = (entry.default_params)();
            for key in scene.technique_overrides(id).keys() {
                if !defaults.contains_key(key) {
                    bail!(
                        "{}: unknown parameter `{id}.{key}` in [techniques.{id}]",
                        path.display()
                    );
                }
            }
        }
        return Ok(format!(
            "scene `{}`, {} blades",
            scene.name(),
            scene.blades.all_blades(&scene.terrain).len()
        ));
    }
    let spec = SweepSpec::from_toml(&text, path)?;
    let ids: Vec<&str> = if spec.techniques.iter().any(|t| t == "all") {
        registry::ids()
    } else {
        spec.techniques
            .iter()
            .map(|t| registry::find(t).map(|e| e.info.id))
            .collect::<Result<_, _>>()?
    };
    let plan = spec.expand(&ids)?;
    for run in &plan {
        let base = scenes::load(&run.scene)?;
        let config = apply_overrides(&base.config, &run.scene_overrides)
            .with_context(|| format!("{}: scene `{}`", path.display(), run.scene))?;
        Scene::from_config(config, base.base_dir).with_context(|| {
            format!(
                "{}: scene `{}` with {}",
                path.display(),
                run.scene,
                run.scene_variant()
            )
        })?;
    }
    for (technique, grid) in &spec.params {
        let entry = registry::find(technique)?;
        let defaults = (entry.default_params)();
        for key in grid
            .as_table()
            .map(|t| t.keys().collect::<Vec<_>>())
            .unwrap_or_default()
        {
            if !defaults.contains_key(key) {
                bail!("{}: unknown parameter `{technique}.{key}`", path.display());
            }
        }
    }
    Ok(format!("sweep `{}`, {} runs", spec.name, plan.len()))
}
