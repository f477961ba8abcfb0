//! Blade counts that mean one thing (issue 19 §2): every technique's `blades_drawn` (as
//! geometry) and `blades_represented` (by impostors, each blade once) checked against an
//! independent count of the scene's blades, on a small lawn seen whole from above
//! (`tests/scenes/counts.toml`: 12 x 12 m at 20 blades/m², constant density map, all grass).
//!
//! The independent count is the scene's population, counted from `grass::BladeField` (the
//! module every technique is meant to take its population from) and checked against its
//! analytic value, density x area. Each technique's own count comes from its `stats()` after
//! a rendered frame, at its finest variant (the population drawn as finely as the technique
//! can) and at its defaults (levels of detail on: the population split between geometry and
//! impostors, but the same population).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use anyhow::Context as _;
use grassbench::runner::Harness;
use grassbench::{Scene, TechniqueStats};
use grassbench_tests::{TEST_SIZE, gpu, render_with, repo_root};

fn lawn() -> anyhow::Result<Scene> {
    let path = repo_root().join("tests/scenes/counts.toml");
    Scene::load(&path).with_context(|| format!("loading {}", path.display()))
}

/// The stats of frame 3 of technique `id` with `overrides`.
fn stats(
    gpu: &grassbench::GpuContext,
    scene: &Scene,
    id: &str,
    overrides: &toml::Table,
) -> anyhow::Result<TechniqueStats> {
    let entry = grassbench_cli::registry::find(id)?;
    let mut harness = Harness::new(gpu, scene.clone(), TEST_SIZE, false)?;
    let mut technique = harness.create(entry, overrides)?;
    render_with(&mut harness, technique.as_mut(), 3)?;
    Ok(technique.stats())
}

/// How far a technique's count may stray from the population, as a fraction of it.
///
/// Measured on this lawn (lavapipe, frame 3; `--nocapture` prints each "measured:" line):
/// the reference draws exactly the population; see each technique's line for its own margin.
fn tolerance(id: &str) -> f64 {
    match id {
        "reference" => 0.0,
        _ => 0.05,
    }
}

#[test]
fn every_technique_counts_the_scenes_blades_once() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let scene = lawn()?;
    let population = scene.blades.all_blades(&scene.terrain).len() as f64;
    // The shared population is density x area: 20 blades/m² over 144 m², one blade a stratum
    // of 0.224 m; the strata do not line up with the lawn's edges, so the edge strata hold a
    // blade or not by chance (measured 2 875, 0.17 % under 2 880). 1 % is 29 blades: about
    // four times the edge's own spread.
    assert!(
        (population / 2880.0 - 1.0).abs() < 0.01,
        "the lawn holds {population} blades, not about 2 880"
    );
    let mut failures = Vec::new();
    for entry in grassbench_cli::registry::TECHNIQUES {
        let id = entry.info.id;
        for (variant, overrides) in [("finest", entry.finest()?), ("default", toml::Table::new())] {
            let s = stats(&gpu, &scene, id, &overrides)?;
            let shown = s.blades_shown() as f64;
            eprintln!(
                "measured: {id} {variant}: {} drawn + {} represented = {shown} of {population} ({:+.2} %)",
                s.blades_drawn,
                s.blades_represented,
                (shown / population - 1.0) * 100.0
            );
            if (shown / population - 1.0).abs() > tolerance(id) {
                failures.push(format!(
                    "{id} {variant}: {} drawn + {} represented = {shown}, the lawn has {population}",
                    s.blades_drawn, s.blades_represented
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

/// The lawn at `density` blades/m².
fn lawn_at(density: f32) -> anyhow::Result<Scene> {
    let base = lawn()?;
    let mut config = base.config.clone();
    config.grass.density = density;
    Ok(Scene::from_config(config, base.base_dir.clone())?)
}

/// Frame 3 of technique `id` (its defaults) on `scene` at 640x360, with its stats.
fn frame(
    gpu: &grassbench::GpuContext,
    scene: &Scene,
    id: &str,
) -> anyhow::Result<(image::RgbaImage, TechniqueStats)> {
    let entry = grassbench_cli::registry::find(id)?;
    let mut harness = Harness::new(gpu, scene.clone(), POPULATION_SIZE, false)?;
    let mut technique = harness.create(entry, &toml::Table::new())?;
    let image = render_with(&mut harness, technique.as_mut(), 3)?;
    Ok((image, technique.stats()))
}

/// Larger than the usual test size, so a blade of the lawn covers a few pixels.
const POPULATION_SIZE: grassbench::target::Size = grassbench::target::Size {
    width: 640,
    height: 360,
};

/// How much grass an image shows: the summed absolute RGB difference from the grassless
/// frame, in 8-bit levels.
fn grass_signal(image: &image::RgbaImage, grassless: &image::RgbaImage) -> f64 {
    image
        .pixels()
        .zip(grassless.pixels())
        .map(|(a, b)| {
            (0..3)
                .map(|c| f64::from(a.0[c].abs_diff(b.0[c])))
                .sum::<f64>()
        })
        .sum()
}

/// Every technique takes its population from the scene (issue 19 §1): with
/// `grass.density = 0` its image is the grassless frame, byte for byte, and it counts no
/// blade; doubling the density doubles the blades it stands for and about doubles the grass
/// its image shows.
#[test]
fn every_technique_follows_the_scenes_density() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let mut failures = Vec::new();
    let (grassless, _) = frame(&gpu, &lawn_at(0.0)?, "reference")?;
    {
        // The grassless frame is the background alone.
        let mut harness = Harness::new(&gpu, lawn_at(0.0)?, POPULATION_SIZE, false)?;
        let background = render_with(&mut harness, &mut grassbench::technique::NoGrass, 3)?;
        assert!(
            background == grassless,
            "the reference draws something on a lawn without grass"
        );
    }
    let (sparse, dense) = (lawn_at(8.0)?, lawn_at(16.0)?);
    for entry in grassbench_cli::registry::TECHNIQUES {
        let id = entry.info.id;
        let (bare, bare_stats) = frame(&gpu, &lawn_at(0.0)?, id)?;
        if bare != grassless {
            let differing = bare
                .pixels()
                .zip(grassless.pixels())
                .filter(|(a, b)| a != b)
                .count();
            failures.push(format!(
                "{id}: at grass.density = 0 its image differs from the grassless frame in {differing} pixels"
            ));
        }
        if bare_stats.blades_shown() != 0 {
            failures.push(format!(
                "{id}: at grass.density = 0 it counts {} blades",
                bare_stats.blades_shown()
            ));
        }
        let (a, sa) = frame(&gpu, &sparse, id)?;
        let (b, sb) = frame(&gpu, &dense, id)?;
        let count_ratio = sb.blades_shown() as f64 / (sa.blades_shown() as f64).max(1.0);
        let signal_ratio = grass_signal(&b, &grassless) / grass_signal(&a, &grassless).max(1.0);
        eprintln!(
            "measured: {id}: blades {} -> {} (x{count_ratio:.3}), grass signal x{signal_ratio:.3}",
            sa.blades_shown(),
            sb.blades_shown()
        );
        // 8 -> 16 blades/m²: the population doubles (to within the lawn's edge strata, 1 %;
        // 5 % leaves room for techniques whose units of population are coarser). Measured:
        // reference x1.997, zhang x2.019, boulanger and bakay x2.000, perbet x1.974.
        if (count_ratio - 2.0).abs() > 0.1 {
            failures.push(format!(
                "{id}: doubling the density took its blades from {} to {} (x{count_ratio:.3})",
                sa.blades_shown(),
                sb.blades_shown()
            ));
        }
        // The picture's grass grows with the population, less than in proportion where blades
        // overlap. Bounds: see `SIGNAL_RATIO`.
        if !SIGNAL_RATIO.contains(&signal_ratio) {
            failures.push(format!(
                "{id}: doubling the density scaled the grass its image shows by x{signal_ratio:.3}, outside {SIGNAL_RATIO:?}"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

/// How much more grass an image may show at 16 than at 8 blades/m² (the grass signal's ratio).
/// Blades seen from above rarely overlap at these densities, so the signal should about
/// double. Measured (lavapipe, 640x360, frame 3): reference x1.951, zhang x1.750, boulanger
/// x1.757, bakay x1.960, perbet x2.046 (before issue 19 zhang's image did not change at all,
/// x1.0, and boulanger's went x11.9 from a patch of one blade to four). The range keeps a
/// margin of about 0.2 either side of what was measured.
const SIGNAL_RATIO: std::ops::RangeInclusive<f64> = 1.5..=2.3;
