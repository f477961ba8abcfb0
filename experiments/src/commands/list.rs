//! `grassbench list`: techniques, their parameters, and scenes.

use std::io::Write as _;

use crate::{registry, scenes};

/// Prints the registry and the built-in scenes to stdout: each technique's parameters with
/// their defaults, then on the next line their valid range or choices (with the unit, where the
/// description names one) and the first sentence of their description.
pub fn list() -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    writeln!(out, "techniques:")?;
    for e in registry::TECHNIQUES {
        writeln!(
            out,
            "  {:<12} {} — {}",
            e.info.id, e.info.name, e.info.paper
        )?;
        for p in e.describe() {
            writeln!(
                out,
                "      {} = {}",
                p.key,
                grassbench::params::format_value(&p.default)
            )?;
            let bounds = p.bounds_with_unit();
            let sep = if bounds.is_empty() { "" } else { "  " };
            writeln!(out, "          {bounds}{sep}{}", p.summary())?;
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
