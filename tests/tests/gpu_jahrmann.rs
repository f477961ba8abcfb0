//! Headless GPU tests of the `jahrmann` technique on a software rasteriser, at small size. Its
//! compute step and culling are checked against their CPU twins in `tests/tests/twins.rs`;
//! its CPU twins against the paper's rules in the crate (`cargo test -p grassbench-jahrmann`).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use anyhow::Context as _;
use grassbench::compare;
use grassbench::runner::Harness;
use grassbench::wind::WindConfig;
use grassbench::{Scene, TechniqueStats};
use grassbench_jahrmann::cull::{self, CullSettings, Verdict};
use grassbench_jahrmann::tiles::TileGrid;
use grassbench_jahrmann::{Params, blades};
use grassbench_tests::{TEST_SIZE, gpu, render_record, render_with, scene};

/// The comparison suite's scenes, density and frame.
const SCENES: [&str; 3] = ["meadow", "football_field", "prairie_flyover"];
const DENSITY: f32 = 0.25;
const FRAME: u64 = 30;

fn calm(scene: &Scene) -> anyhow::Result<Scene> {
    let mut config = scene.config.clone();
    config.wind = WindConfig::Calm;
    Ok(Scene::from_config(config, scene.base_dir.clone())?)
}

/// With culling and levels off, jahrmann draws the reference's blades, in the reference's
/// wind: per-pixel FLIP against the reference is meaningful, and small. What remains is the
/// blade model: the paper's Bezier curve (validated from the same rest tip) against the
/// reference's segment walk, and its simulated bend against the reference's instant one.
#[test]
fn finest_matches_the_reference_per_pixel() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let reference = grassbench_cli::registry::find("reference")?;
    let jahrmann = grassbench_cli::registry::find("jahrmann")?;
    let finest = jahrmann.finest()?;
    let mut failures = Vec::new();
    for (name, limit) in SCENES.iter().zip(FINEST_FLIP) {
        let windy = scene(name, DENSITY)?;
        for (wind, sc) in [("wind", windy.clone()), ("calm", calm(&windy)?)] {
            let r = compare::render(&gpu, &sc, reference, &toml::Table::new(), FRAME, TEST_SIZE)?;
            let j = compare::render(&gpu, &sc, jahrmann, &finest, FRAME, TEST_SIZE)?;
            let flip = compare::scores(&r, &j)?.flip_mean;
            eprintln!("measured: jahrmann finest vs reference on {name} ({wind}): FLIP {flip:.4}");
            if flip > limit {
                failures.push(format!("{name} ({wind}): FLIP {flip:.4} > {limit}"));
            }
        }
    }
    // The metric tells blades apart: another population (the scene's seed changed) scores far
    // worse on the meadow than the same blades drawn by the other model.
    let meadow = calm(&scene("meadow", DENSITY)?)?;
    let mut other = meadow.config.clone();
    other.seed += 1;
    let other = Scene::from_config(other, meadow.base_dir.clone())?;
    let r = compare::render(
        &gpu,
        &meadow,
        reference,
        &toml::Table::new(),
        FRAME,
        TEST_SIZE,
    )?;
    let j = compare::render(&gpu, &other, jahrmann, &finest, FRAME, TEST_SIZE)?;
    let flip = compare::scores(&r, &j)?.flip_mean;
    eprintln!(
        "measured: jahrmann finest with another seed vs reference on the meadow: FLIP {flip:.4}"
    );
    if flip < OTHER_BLADES_FLIP {
        failures.push(format!(
            "another population scores only {flip:.4} on the meadow"
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

/// Limits of the finest rendering's FLIP against the reference (meadow, football field,
/// prairie). Measured on lavapipe at 320x180, a quarter of the blades, frame 30, in the
/// scene's wind / in calm air: 0.0699 / 0.0706, 0.0050 / 0.0052, 0.0209 / 0.0219; the limits
/// are about 25 % above the worst. For scale: the reference against itself with 7 segments
/// instead of 5 scores 0.021 on the meadow, with a circular bend profile instead of its
/// stiff-based one 0.067 (the same blades, another shape: the size of the difference here).
const FINEST_FLIP: [f64; 3] = [0.09, 0.0066, 0.028];

/// Least FLIP of another population against the reference on the meadow: measured 0.161,
/// 2.3 times the same blades' 0.070.
const OTHER_BLADES_FLIP: f64 = 0.1;

/// The simulation is a function of the frame: encoding the same frame again (the temporal
/// suite's camera moves, a benchmark's re-encode) draws the same picture, frames rendered
/// twice from a fresh start are the same, and going back to frame 0 (the window's restart)
/// starts again from rest.
#[test]
fn the_state_follows_the_frame() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let sc = scene("meadow", DENSITY)?;
    let entry = grassbench_cli::registry::find("jahrmann")?;
    let defaults = toml::Table::new();
    let mut harness = Harness::new(&gpu, sc.clone(), TEST_SIZE, false)?;
    let mut t = harness.create(entry, &defaults)?;
    let first = render_with(&mut harness, t.as_mut(), 12)?;
    let again = harness.frame(t.as_mut(), 12, true)?.image.unwrap();
    let fresh = compare::render(&gpu, &sc, entry, &defaults, 12, TEST_SIZE)?;
    let frame0 = compare::render(&gpu, &sc, entry, &defaults, 0, TEST_SIZE)?;
    let restarted = harness.frame(t.as_mut(), 0, true)?.image.unwrap();
    let differing = |a: &grassbench::image::RgbaImage, b: &grassbench::image::RgbaImage| {
        a.pixels().zip(b.pixels()).filter(|(x, y)| x != y).count()
    };
    let (same_frame, same_start, restart) = (
        differing(&first, &again),
        differing(&first, &fresh),
        differing(&frame0, &restarted),
    );
    eprintln!(
        "measured: pixels differing: frame 12 encoded again {same_frame}, from a fresh start {same_start}, frame 0 after a restart {restart}"
    );
    // The draw list's order changes run to run (atomics), so two blades at exactly equal
    // depth may swap: measured 0, 0 and 0 differing pixels of 57 600. A step that advanced
    // the simulation again (or did not reset) changes thousands.
    let limit = TEST_SIZE.width as usize * TEST_SIZE.height as usize / 1000;
    assert!(
        same_frame <= limit && same_start <= limit && restart <= limit,
        "{same_frame} / {same_start} / {restart} pixels differ (limit {limit})"
    );
    // And the wind moves the blades: frame 12 is not frame 0.
    assert!(differing(&first, &frame0) > 100 * limit.max(1));
    Ok(())
}

/// Counts are the GPU's own, one frame late: after frame `f` they are frame `f − 1`'s, they
/// add up to the population, and they are the CPU mirror's verdicts (`cull::verdict` on the
/// rest curves: exact for every test but the frustum's, which sees the simulated curve; a
/// blade straddling the frustum's side may differ).
#[test]
fn counts_are_the_gpus_and_follow_the_cull() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let sc = calm(&scene("meadow", DENSITY)?)?;
    let population = sc.blades.all_blades(&sc.terrain);
    let entry = grassbench_cli::registry::find("jahrmann")?;
    let mut harness = Harness::new(&gpu, sc.clone(), TEST_SIZE, false)?;
    let mut t = harness.create(entry, &toml::Table::new())?;
    let (_, record) = render_record(&mut harness, t.as_mut(), 8)?;
    let counters: std::collections::BTreeMap<_, _> = t.counters().into_iter().collect();
    let stats: TechniqueStats = t.stats();
    assert_eq!(counters["count_lag_frames"], 1.0);
    assert_eq!(counters["considered"], population.len() as f64);
    let sum: f64 = [
        "culled_orientation",
        "culled_frustum",
        "culled_distance",
        "drawn_near",
        "drawn_far",
        "represented_far",
    ]
    .iter()
    .map(|k| counters[k])
    .sum();
    assert_eq!(sum, population.len() as f64);
    assert_eq!(
        stats.blades_drawn as f64,
        counters["drawn_near"] + counters["drawn_far"]
    );
    assert_eq!(stats.blades_represented as f64, counters["represented_far"]);
    assert_eq!(record.blades_drawn, Some(stats.blades_drawn));
    // The frame encoder counts the instances of the two indirect draws from their arguments,
    // copied out at the end of the frame: frame 8's are what the technique's own counts of
    // frame 8 say, once they arrive a frame later.
    let instances = record.instances.context("instances counted")?;
    harness.frame(t.as_mut(), 9, false)?;
    let next: std::collections::BTreeMap<_, _> = t.counters().into_iter().collect();
    assert_eq!(
        instances as f64,
        next["drawn_near"] + next["drawn_far"],
        "frame 8's instances against its counts {next:?}"
    );
    assert!(instances > 0);

    // The CPU mirror of frame 7's cull (the camera path moves: frame 7's camera): the tile
    // selection's verdicts on the blades it does not dispatch, `cull::verdict` on the others.
    let camera = harness.camera(7);
    let planes = camera.frustum().planes;
    let params = Params::default();
    let s = CullSettings::of(&params);
    let skipped = TileGrid::new(&population, params.dispatch_tile, &s)
        .skipped_verdicts(camera.eye, &planes, &s);
    let not_dispatched = skipped.iter().filter(|v| v.is_some()).count();
    assert_eq!(
        counters["simulated"],
        (population.len() - not_dispatched) as f64
    );
    let arrays = blades::BladeArrays::new(&population);
    let mut cpu = std::collections::BTreeMap::new();
    for (i, skip) in skipped.iter().enumerate().take(arrays.len()) {
        let rest = arrays.rest_of(i).unwrap();
        let curve = blades::rest_curve(&rest);
        let v = skip.unwrap_or_else(|| {
            cull::verdict(
                i as u32,
                (rest.v0, curve.v1, curve.v2),
                rest.orientation,
                camera.eye,
                &planes,
                &s,
            )
        });
        *cpu.entry(v).or_insert(0u64) += 1;
    }
    eprintln!(
        "measured: {not_dispatched} of {} blades not dispatched at frame 7",
        population.len()
    );
    let name = |v: Verdict| match v {
        Verdict::Near => "drawn_near",
        Verdict::Far => "drawn_far",
        Verdict::Represented => "represented_far",
        Verdict::Orientation => "culled_orientation",
        Verdict::Frustum => "culled_frustum",
        Verdict::Distance => "culled_distance",
    };
    let mut moved = 0.0;
    for (v, n) in &cpu {
        let gpu_count = counters[name(*v)];
        eprintln!("measured: {}: GPU {gpu_count}, CPU mirror {n}", name(*v));
        moved += (gpu_count - *n as f64).abs();
    }
    // Only the frustum test sees the simulated curve: measured 0 blades counted differently
    // at this frame (of 108 540; in calm air the curve is its rest curve drooped by a few
    // millimetres); 0.1 % allows blades whose midpoint sits on the frustum's side.
    assert!(
        moved <= population.len() as f64 / 1000.0,
        "{moved} blades counted differently from the CPU mirror"
    );
    Ok(())
}

/// Every wind model of the shared module drives the simulated blades: the compute pass reads
/// the wind texture the core bakes from whichever model the scene has, so the meadow's breeze,
/// the prairie's point source, the fluid and Perbet's primitives each move the blades away from
/// where calm air leaves them (the primitives with their scene's flying object, which the
/// blast follows and which pushes the blades it skims).
#[test]
fn every_wind_model_moves_the_blades() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let meadow = calm(&scene("meadow", 0.1)?)?;
    let fluid = Scene::load(&grassbench_tests::repo_root().join("tests/scenes/meadow_fluid.toml"))?;
    let primitives = scene("meadow_primitives", 0.1)?;
    let winds = [
        ("breeze", scene("meadow", 0.1)?.config.wind, None),
        (
            "point_source",
            scene("prairie_flyover", 0.1)?.config.wind,
            None,
        ),
        ("fluid", fluid.config.wind, None),
        (
            "primitives",
            primitives.config.wind,
            primitives.config.object,
        ),
    ];
    let entry = grassbench_cli::registry::find("jahrmann")?;
    let finest = entry.finest()?;
    let still = compare::render(&gpu, &meadow, entry, &finest, 20, TEST_SIZE)?;
    let mut failures = Vec::new();
    for (name, wind, object) in winds {
        let mut config = meadow.config.clone();
        config.wind = wind;
        config.object = object;
        let windy = Scene::from_config(config, meadow.base_dir.clone())?;
        let moved = compare::render(&gpu, &windy, entry, &finest, 20, TEST_SIZE)?;
        let differing = still
            .pixels()
            .zip(moved.pixels())
            .filter(|(a, b)| a != b)
            .count();
        eprintln!("measured: jahrmann under {name}: {differing} pixels differ from calm air");
        if differing < MOVED_PIXELS {
            failures.push(format!("{name} moved only {differing} pixels"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

/// Least number of pixels (of 57 600) a wind must change at frame 20 against calm air.
/// Measured on lavapipe: breeze 7 632, point source 7 182, fluid 3 819, primitives 6 272; a
/// wind that does not reach the blades changes none (the same frame renders the same bytes:
/// `the_state_follows_the_frame`).
const MOVED_PIXELS: usize = 1000;

/// The compute pass run only over the tiles in view (`tiles.rs`) draws the picture the pass
/// over every blade draws (`dispatch_tile = 0`): the blades it skips are ones the per-blade
/// tests would not draw, and the ones it runs are the scene's, in another order, with the
/// scene's hashes. FLIP between the two, and for scale between the default and the same
/// without the far thinning (`thin_distance = 0`), which changes what is drawn.
#[test]
fn tile_selection_draws_the_picture_of_every_blade() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("jahrmann")?;
    let defaults = toml::Table::new();
    let every: toml::Table = "dispatch_tile = 0.0".parse()?;
    let unthinned: toml::Table = "thin_distance = 0.0".parse()?;
    let mut failures = Vec::new();
    for name in SCENES {
        let sc = scene(name, DENSITY)?;
        let tiled = compare::render(&gpu, &sc, entry, &defaults, FRAME, TEST_SIZE)?;
        let all = compare::render(&gpu, &sc, entry, &every, FRAME, TEST_SIZE)?;
        let thick = compare::render(&gpu, &sc, entry, &unthinned, FRAME, TEST_SIZE)?;
        let flip = compare::scores(&all, &tiled)?.flip_mean;
        let thin_flip = compare::scores(&thick, &tiled)?.flip_mean;
        eprintln!(
            "measured: jahrmann on {name}: FLIP tiles vs every blade {flip:.5}, thinning vs none {thin_flip:.5}"
        );
        if flip > TILES_FLIP {
            failures.push(format!("{name}: FLIP {flip:.5} > {TILES_FLIP}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

/// Limit of FLIP between the tiled and the untiled compute pass (see the test above): the
/// same blades are drawn, so only blades at exactly equal depth swapping order can differ.
/// Measured on lavapipe at 320x180, a quarter of the blades, frame 30: 0.00000 on each of
/// the three scenes (the same bytes). The limit sits below the smallest change that draws
/// other blades measured there: the thinning's 0.00148 / 0.00345 / 0.01317 (meadow, football
/// field, prairie fly-over).
const TILES_FLIP: f64 = 0.001;
