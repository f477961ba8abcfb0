//! `grassbench list`: techniques, their parameters, and scenes.

use std::io::Write as _;

use crate::{registry, scenes};

/// Prints the registry and the built-in scenes to stdout.
pub fn list() -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    writeln!(out, "techniques:")?;
    for e in registry::TECHNIQUES {
        writeln!(
            out,
            "  {:<12} {} — {}",
            e.info.id, e.info.name, e.info.paper
        )?;
        for (k, v) in e.default_params() {
            writeln!(out, "      {k} = {}", grassbench::params::format_value(&v))?;
        }
        for v in e.variants.iter() {
            let sets = v.params.lines().collect::<Vec<_>>().join(", ");
            let sets = if sets.is_empty() {
                "(the defaults)"
            } else {
                &sets
            };
            writeln!(out, "    variant {:<15} {sets}", v.name)?;
        }
    }
    writeln!(out, "scenes:")?;
    for name in scenes::names() {
        let scene = scenes::load(name)?;
        writeln!(out, "  {:<16} {}", name, scene.config.description)?;
    }
    Ok(())
}
