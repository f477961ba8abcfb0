//! Headless GPU tests of `zhang` (part 1) on a software rasteriser, and its comparison with
//! `reference` on the meadow.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use grassbench::metrics::{coverage_mask, downsample, flip, grass_coverage};
use grassbench::runner::Harness;
use grassbench::target::Size;
use grassbench::technique::NoGrass;
use grassbench::wind::WindConfig;
use grassbench_tests::{
    TEST_SIZE, gpu, level_blades, pixels_differing, render, render_record, render_with, repo_root,
    scene,
};

/// The meadow in Stam fluid wind (the test scene that exercises `model = "fluid"`).
fn fluid_scene() -> anyhow::Result<grassbench::Scene> {
    Ok(grassbench::Scene::load(
        &repo_root().join("tests/scenes/meadow_fluid.toml"),
    )?)
}

/// The size of the tests on the full meadow: large enough that the far billboards are a few
/// pixels tall, not one.
const SIZE: Size = Size {
    width: 640,
    height: 360,
};

/// The technique's counter `name` (0 when it has none).
fn counter(t: &dyn grassbench::GrassTechnique, name: &str) -> f64 {
    t.counters()
        .iter()
        .find(|(k, _)| *k == name)
        .map_or(0.0, |(_, v)| *v)
}

/// `scene` with the camera held still, so frames differ only through the wind.
fn still(scene: grassbench::Scene) -> anyhow::Result<grassbench::Scene> {
    let mut config = scene.config;
    config.camera.path = grassbench::camera::CameraPath::Fixed {
        eye: [0.0, 3.0, 0.0],
        look_at: [10.0, 1.0, 4.0],
    };
    Ok(grassbench::Scene::from_config(config, scene.base_dir)?)
}

#[test]
fn zhang_meadow_has_grass_below_and_sky_above() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let mut harness = Harness::new(&gpu, scene("meadow", 1.0)?, TEST_SIZE, false)?;
    let background = render_with(&mut harness, &mut NoGrass, 30)?;
    let entry = grassbench_cli::registry::find("zhang")?;
    let mut zhang = harness.create(entry, &toml::Table::new())?;
    let (image, culled_record) = render_record(&mut harness, zhang.as_mut(), 30)?;
    // Measured 0.478 (at 640x360 too, against the reference's 0.467: the same blades; 0.30
    // before issue 19, when zhang drew 41 of the meadow's 90 blades/m²). Nothing drawn gives
    // 0; more than 0.7 means grass (or garbage) in the sky.
    let coverage = grass_coverage(&image, &background, 6)?;
    eprintln!("measured: coverage {coverage:.3}");
    assert!((0.15..0.7).contains(&coverage), "coverage {coverage:.3}");
    // Eq. 10 blends the target's alpha like its colour (below 255 over most of the far grass
    // in results/default's meadow frames before the read-back made frames opaque): a saved
    // frame must not show the page behind it through the billboards.
    let translucent = image.pixels().filter(|p| p.0[3] != u8::MAX).count();
    assert_eq!(translucent, 0, "pixels with alpha below 255");
    let mask = coverage_mask(&image, &background, 6)?;
    let (w, h) = (TEST_SIZE.width as usize, TEST_SIZE.height as usize);
    assert!(
        mask[..w * h / 8].iter().all(|m| !m),
        "grass drawn in the sky"
    );
    let bottom = grassbench::metrics::mean_color(
        &grassbench::image::imageops::crop_imm(&image, 0, h as u32 - 20, w as u32, 20).to_image(),
    );
    assert!(
        bottom[1] > bottom[0] && bottom[1] > bottom[2],
        "foreground is not green: {bottom:?}"
    );
    // Grid culling (Sec. 5.3) draws part of the prairie; without it every blade, in one draw
    // for blades and one for flowers, and the same pixels where the culled grids were unseen.
    let culled = zhang.stats();
    let grids = |t: &dyn grassbench::GrassTechnique| {
        let c = t.counters();
        let count = |name: &str| c.iter().find(|(k, _)| *k == name).map_or(-1.0, |(_, v)| *v);
        (count("grids_drawn"), count("grids_culled"))
    };
    let (drawn, culled_grids) = grids(zhang.as_ref());
    let mut off = toml::Table::new();
    off.insert("culling".into(), false.into());
    let mut all = harness.create(entry, &off)?;
    let (unculled, every_record) = render_record(&mut harness, all.as_mut(), 30)?;
    let every = all.stats();
    // 256 grids, less those the covering map leaves without a blade.
    let (all_drawn, none_culled) = grids(all.as_ref());
    assert!(
        drawn > 0.0
            && culled_grids > 0.0
            && none_culled == 0.0
            && drawn + culled_grids == all_drawn
            && all_drawn <= 256.0,
        "with culling {drawn} drawn, {culled_grids} culled; without, {all_drawn} and {none_culled}"
    );
    eprintln!("measured: culling {culled:?}, without {every:?}");
    // Blades, flowers and wings of every grid (near blades in a few runs of grids).
    let (every_draws, culled_draws) = (every_record.draw_calls, culled_record.draw_calls);
    assert!(
        every.blades_shown() > 100_000 && every_draws >= 3,
        "{every:?}, {every_draws} draws"
    );
    assert!(
        culled.blades_shown() > 0
            && culled.blades_shown() < every.blades_shown()
            && culled_draws >= 2,
        "{culled:?} ({culled_draws} draws) against {every:?}"
    );
    assert_eq!(
        flip(&unculled, &image)?.mean,
        0.0,
        "culling changed the picture"
    );
    Ok(())
}

/// Mean FLIP against `reference`, meadow frame 30 at its 640x360, at full, 1/4 and 1/16 scale
/// (`metrics::downsample`). Blade placement differs by design, so per-pixel FLIP is high at
/// full scale and falls as blades average into texture. Measured on lavapipe:
///
/// | zhang parameters | 1/1 | 1/4 | 1/16 | coverage (ref 0.467) |
/// |---|---|---|---|---|
/// | defaults (the scene's blades, billboards beyond the 3 x 3 near grids, sorted, fades) | 0.157 | 0.094 | 0.077 | 0.478 |
/// | `blades_per_side = 32` (the thesis' lattice, 41 blades/m² here), same | 0.166 | 0.115 | 0.097 | 0.328 |
///
/// Before issue 19 the defaults were the thesis' lattice (the second row; then 0.165, 0.114,
/// 0.097, coverage 0.329) and `blades_per_side = 47` gave as many candidates as the
/// reference on a lattice of its own (0.165, 0.104, 0.076, coverage 0.473); without sorting or
/// fades 0.167, 0.117, 0.104 and 0.168, 0.105, 0.081; with `lod = false` 0.162, 0.108, 0.091
/// and 0.165, 0.095, 0.067: the billboards (Ch. 4) cost 0.01-0.015 of FLIP at the reduced
/// scales. Thresholds sit ~20 % above the measurements: they catch a broken picture (missing
/// blades, wrong colours, black frames), not the placement difference. The defaults stand
/// their single plants where the reference's blades stand, so they must also cover the same
/// share of the image as the reference (±0.05).
#[test]
fn zhang_compares_with_reference_on_the_meadow() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let none = toml::Table::new();
    let reference = render(&gpu, "reference", scene("meadow", 1.0)?, 30, SIZE, &none)?;
    let mut thesis = toml::Table::new();
    thesis.insert("blades_per_side".into(), 32.into());
    let mut harness = Harness::new(&gpu, scene("meadow", 1.0)?, SIZE, false)?;
    let background = render_with(&mut harness, &mut NoGrass, 30)?;
    let ref_coverage = grass_coverage(&reference, &background, 6)?;
    for (overrides, limits) in [
        (&none, [0.19, 0.115, 0.095]),
        (&thesis, [0.20, 0.14, 0.125]),
    ] {
        let z = render(&gpu, "zhang", scene("meadow", 1.0)?, 30, SIZE, overrides)?;
        for (factor, limit) in [1u32, 4, 16].into_iter().zip(limits) {
            let mean = flip(&downsample(&reference, factor), &downsample(&z, factor))?.mean;
            eprintln!("measured: {overrides:?} at 1/{factor}: FLIP {mean:.4}");
            assert!(
                mean < limit,
                "{overrides:?} at 1/{factor}: FLIP {mean:.4} ≥ {limit}"
            );
        }
        let c = grass_coverage(&z, &background, 6)?;
        eprintln!("measured: {overrides:?} coverage {c:.3} (reference {ref_coverage:.3})");
        if overrides == &none {
            assert!(
                (c - ref_coverage).abs() < 0.05,
                "coverage {c:.3} vs {ref_coverage:.3}"
            );
        }
    }
    Ok(())
}

#[test]
fn fluid_wind_animates_the_blades_and_calm_air_leaves_them_at_rest() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let none = toml::Table::new();
    let fluid = still(fluid_scene()?)?;
    assert!(matches!(fluid.config.wind, WindConfig::Fluid(_)));
    let f0 = render(&gpu, "zhang", fluid.clone(), 0, TEST_SIZE, &none)?;
    let f30 = render(&gpu, "zhang", fluid, 30, TEST_SIZE, &none)?;
    let psnr = grassbench::metrics::psnr(&f0, &f30)?;
    assert!(
        psnr.is_finite() && psnr < 40.0,
        "fluid wind did not move the grass ({psnr:.1} dB)"
    );
    // Calm air: blades start at rest and stay there, bit for bit.
    let mut calm = still(fluid_scene()?)?.config;
    calm.wind = WindConfig::Calm;
    let calm = grassbench::Scene::from_config(calm, repo_root().join("tests/scenes"))?;
    let c0 = render(&gpu, "zhang", calm.clone(), 0, TEST_SIZE, &none)?;
    let c30 = render(&gpu, "zhang", calm, 30, TEST_SIZE, &none)?;
    assert!(c0.as_raw() == c30.as_raw(), "blades moved in calm air");
    Ok(())
}

#[test]
fn catching_up_gives_the_same_frame_as_running_through() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("zhang")?;
    let mut params = toml::Table::new();
    params.insert("grids".into(), 8.into());
    let mut harness = Harness::new(&gpu, fluid_scene()?, TEST_SIZE, false)?;
    let mut t = harness.create(entry, &params)?;
    let mut last = None;
    for f in 0..=6 {
        last = harness.frame(t.as_mut(), f, f == 6)?.image;
    }
    let direct = render(&gpu, "zhang", fluid_scene()?, 6, TEST_SIZE, &params)?;
    assert!(last.is_some_and(|img| img.as_raw() == direct.as_raw()));
    Ok(())
}

#[test]
fn bad_parameters_are_refused_naming_the_key() -> anyhow::Result<()> {
    let gpu = gpu()?;
    for (key, value) in [
        ("backbone_points", toml::Value::from(1)),
        ("flower_fraction", toml::Value::from(f64::NAN)),
        ("grids", toml::Value::from(0)),
    ] {
        let mut bad = toml::Table::new();
        bad.insert(key.into(), value);
        let e = render(&gpu, "zhang", scene("meadow", 0.1)?, 0, TEST_SIZE, &bad)
            .unwrap_err()
            .to_string();
        assert!(e.contains(&format!("zhang.{key}")), "{e}");
    }
    Ok(())
}

/// Billboards (Ch. 4) stand in for the far grids (Sec. 5.2): the counters say what was drawn,
/// far fewer triangles are submitted, and the picture stays close to single plants everywhere
/// (`lod = false`, the `finest` variant). Measured on the meadow, frame 30 at 640x360 on
/// lavapipe (sorted and blended, the default): FLIP against the finest 0.0433 at full scale,
/// 0.0353 at 1/4, 0.0353 at 1/16; frame 30 stands in a fade band (Sec. 6.1: 4 grids drawn
/// both ways, their single plants and billboards blended into each other). Without fades
/// (`fade_radius = 0`) 0.0402, 0.0255, 0.0270 (the near grids are the same blades).
/// Thresholds ~25 % above. (On the thesis' lattice, before issue 19, the grids lay elsewhere
/// and held 32 x 32 plants: 0.042, 0.031, 0.029 and without fades 0.028, 0.0195, 0.023.)
/// On the scene's population (issue 19: the meadow's 90 blades/m², grids of
/// 48 x 48 strata) 7 061 single plants (those of the near grids left by culling single
/// plants) and 4 972 billboards (29 683 wings) represent 232 k blades: 116 k triangles
/// against 1.77 M (before, on the thesis' 32 x 32 lattice: 3 232 single plants and 2 224
/// billboards for 114 k blades, 53 k triangles against 803 k).
#[test]
fn billboards_stand_in_for_far_grids() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("zhang")?;
    let finest_params = entry
        .variant(grassbench::technique::FINEST)
        .expect("finest")?;
    let mut harness = Harness::new(&gpu, scene("meadow", 1.0)?, SIZE, false)?;
    let mut lod = harness.create(entry, &toml::Table::new())?;
    let image = render_with(&mut harness, lod.as_mut(), 30)?;
    let mut finest = harness.create(entry, &finest_params)?;
    let fine = render_with(&mut harness, finest.as_mut(), 30)?;
    let (s, f) = (lod.stats(), finest.stats());
    eprintln!(
        "measured: LOD {s:?} {:?}; finest {f:?} {:?}",
        lod.counters(),
        lod.levels()
    );
    let singles = counter(lod.as_ref(), "single_plants");
    let billboards = counter(lod.as_ref(), "billboards_l5")
        + counter(lod.as_ref(), "billboards_l9")
        + counter(lod.as_ref(), "billboards_l17");
    // At most the 4 x 4 grids around a border corner (fading, Sec. 6.1) are single plants:
    // the meadow's grids are 48 x 48 strata.
    assert!(
        singles > 1000.0 && singles <= 16.0 * 48.0 * 48.0,
        "{singles} single plants"
    );
    assert!(billboards > 100.0, "{billboards} billboards");
    assert_eq!(counter(finest.as_ref(), "billboards_l5"), 0.0);
    // zhang reports both of its levels (what they hold is the counters' and stats' own
    // arithmetic, so equating them here would hold by construction).
    assert!(level_blades(lod.as_ref(), "billboards")? > 0);
    assert!(level_blades(lod.as_ref(), "single_plants")? > 0);
    // The same grids drawn, far fewer triangles. The boxes the grids are culled with hold
    // their billboards' anchors too with LOD (lattice points whether their blade grows or
    // not), so LOD may keep a grid whose blades alone are just out of view: measured 145
    // grids drawn against the finest's 144 (equal before issue 19's lattice).
    let (lod_grids, finest_grids) = (
        counter(lod.as_ref(), "grids_drawn"),
        counter(finest.as_ref(), "grids_drawn"),
    );
    assert!(
        lod_grids >= finest_grids && lod_grids <= finest_grids + 2.0,
        "{lod_grids} grids drawn with LOD, {finest_grids} without"
    );
    assert!(s.triangles * 5 < f.triangles, "{s:?} against {f:?}");
    let mut no_fade_params = toml::Table::new();
    no_fade_params.insert("fade_radius".into(), 0.0.into());
    let mut no_fade = harness.create(entry, &no_fade_params)?;
    let switched = render_with(&mut harness, no_fade.as_mut(), 30)?;
    let mut failures = Vec::new();
    for (what, image, limits) in [
        ("LOD", &image, [0.054, 0.044, 0.044]),
        ("LOD without fades", &switched, [0.050, 0.032, 0.034]),
    ] {
        for (factor, limit) in [1u32, 4, 16].into_iter().zip(limits) {
            let mean = flip(&downsample(&fine, factor), &downsample(image, factor))?.mean;
            eprintln!("measured: {what} against finest at 1/{factor}: FLIP {mean:.4}");
            if mean >= limit {
                failures.push(format!("{what} at 1/{factor}: FLIP {mean:.4} ≥ {limit}"));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
    Ok(())
}

/// `scene` with its walker starting at the corner of zhang's grass grids nearest its first
/// waypoint (the grids lie on the scene's strata: `grassbench_zhang::prairie::Layout`): a
/// tenth of a millimetre inside it along x, a quarter of a millimetre before the border along
/// z, so a dolly of 1 mm a frame towards the next waypoint (+x, −z on the meadow) crosses the
/// z border at the first step, within the fade band of the x border.
fn on_a_grid_corner(scene: grassbench::Scene) -> anyhow::Result<grassbench::Scene> {
    use grassbench::glam::Vec2;
    use grassbench_zhang::prairie::Layout;
    let layout = Layout::new(
        &grassbench_zhang::Params::default(),
        &scene.blades,
        &scene.terrain,
    );
    let mut config = scene.config.clone();
    let grassbench::camera::CameraPath::Walker { waypoints, .. } = &mut config.camera.path else {
        anyhow::bail!("the meadow's camera is not a walker");
    };
    let k = ((Vec2::from(waypoints[0]) - layout.origin) / layout.grid_size).round();
    let corner = layout.origin + k * layout.grid_size;
    waypoints[0] = [corner.x + 1e-4, corner.y + 2.5e-4];
    Ok(grassbench::Scene::from_config(config, scene.base_dir)?)
}

/// Across a grid border: the meadow's walker starts beside a grid corner
/// ([`on_a_grid_corner`]), and a dolly of 1 mm per frame (so parallax changes little) crosses
/// the border at the first step. Without fades (`fade_radius = 0`) billboards and single
/// plants switch there; with them (Sec. 6.1) both sides draw each representation at alpha ½
/// at the border. Measured on lavapipe at 320x180, quarter density, calm air (mean absolute
/// change per colour channel, 0-255, frames read back opaque): at the crossing 1.48 without
/// fades, 2.4 times the largest other step (0.58-0.63), against 0.73 with them, 1.3 times
/// theirs (0.54-0.57): the fades take four fifths of the switch's spike away. (Before the
/// frames were opaque the change counted zhang's blended alpha too: 1.40 against 0.84, other
/// steps 0.69-0.76; on the thesis' lattice, before issue 19: 2.07 against 1.26, 1.1-1.2.) (At
/// the comparison suite's 0.25 m per frame the switch drowns in parallax: 7.6 without against
/// 8.3 with, the fade band's two layers adding change; see `ENTRY`.)
#[test]
fn fades_soften_the_switch_at_a_grid_crossing() -> anyhow::Result<()> {
    use grassbench::compare::{CameraMotion, frame_differences};
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("zhang")?;
    let scene = on_a_grid_corner(scene("meadow", 0.25)?)?;
    let mut no_fade = toml::Table::new();
    no_fade.insert("fade_radius".into(), 0.0.into());
    let motion = CameraMotion::Dolly(0.001);
    let with = frame_differences(
        &gpu,
        &scene,
        entry,
        &toml::Table::new(),
        motion,
        8,
        TEST_SIZE,
    )?;
    let without = frame_differences(&gpu, &scene, entry, &no_fade, motion, 8, TEST_SIZE)?;
    eprintln!("measured: frame-to-frame change with fades {with:.3?}, without {without:.3?}");
    // The switch is a spike over the steady steps without fades (its excess over the largest
    // other step measured 1.4), and the fades take most of it away (0.3: under half).
    let steady = |d: &[f64]| d[1..].iter().copied().fold(0.0, f64::max);
    let spike = |d: &[f64]| d[0] / steady(d) - 1.0;
    assert!(spike(&without) > 0.8, "no switch seen: {without:?}");
    assert!(
        spike(&with) < 0.5 * spike(&without),
        "fades did not soften it: {with:?} against {without:?}"
    );
    Ok(())
}

/// Wings cut down to their texels (`trim_wings`, `techniques/zhang/src/wing_trim.rs`) draw what
/// whole wings draw. In calm air with upright blades every wing is planar (its two tops are its
/// roots raised by the same height), and the cut keeps every texel the whole wing shows.
/// Measured on lavapipe (640x360, full meadow, the scene's population): calm, frame 0, 56 of
/// 230 400 pixels differ by more than 2 levels (texel lookups along the cut's edges), FLIP
/// 0.00032; 290 of 25 177 wings can show nothing and are not drawn. In the wind (frame 30) a
/// wing's two tops sway apart, the wing is no longer planar, and the cut rectangle's diagonal
/// is not the whole one's: 8.2 % of the pixels differ (nearest-texel lookups shifted), FLIP
/// 0.0167 between the two, but both are about as far from the finest image (`lod = false`):
/// FLIP 0.0433 cut against 0.0436 whole. (On the thesis' lattice, before issue 19: 26 pixels,
/// FLIP 0.00022, 226 of 12 140 wings; 8.6 %, 0.0178, 0.0422 against 0.0420.)
#[test]
fn trimmed_wings_draw_what_whole_wings_draw() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("zhang")?;
    let mut whole_params = toml::Table::new();
    whole_params.insert("trim_wings".into(), false.into());
    let meadow = scene("meadow", 1.0)?;
    let mut calm = meadow.config.clone();
    calm.wind = WindConfig::Calm;
    calm.grass.lean = 0.0;
    let calm = grassbench::Scene::from_config(calm, meadow.base_dir.clone())?;
    for (what, scene, frame) in [("calm", calm, 0), ("wind", meadow, 30)] {
        let mut harness = Harness::new(&gpu, scene, SIZE, false)?;
        let mut trimmed = harness.create(entry, &toml::Table::new())?;
        let cut = render_with(&mut harness, trimmed.as_mut(), frame)?;
        let mut whole = harness.create(entry, &whole_params)?;
        let full = render_with(&mut harness, whole.as_mut(), frame)?;
        // Wings that can show nothing are not drawn at all.
        let (drawn, wings) = (
            counter(trimmed.as_ref(), "wings"),
            counter(whole.as_ref(), "wings"),
        );
        assert!(
            wings > 1000.0 && drawn <= wings,
            "{drawn} of {wings} wings drawn"
        );
        let differ = pixels_differing(&cut, &full, 2);
        let mean = flip(&full, &cut)?.mean;
        let finest_params = entry
            .variant(grassbench::technique::FINEST)
            .expect("finest")?;
        let mut finest = harness.create(entry, &finest_params)?;
        let fine = render_with(&mut harness, finest.as_mut(), frame)?;
        let (to_cut, to_full) = (flip(&fine, &cut)?.mean, flip(&fine, &full)?.mean);
        eprintln!(
            "measured: {what}: {drawn} of {wings} wings drawn; {differ} pixels differ, FLIP {mean:.5}; against finest: trimmed {to_cut:.5}, whole {to_full:.5}"
        );
        if what == "calm" {
            // Limits: about 4x the measured differences (rounding along the cut's edges).
            assert!(
                differ < 230 && mean < 0.0015,
                "{differ} pixels, FLIP {mean}"
            );
        } else {
            // Limits: the measured FLIP plus half, and one part in twenty of the fidelity.
            assert!(mean < 0.03, "trimmed against whole: FLIP {mean}");
            assert!(
                to_cut < 1.05 * to_full,
                "against finest: {to_cut} trimmed, {to_full} whole"
            );
        }
    }
    Ok(())
}

/// The billboards' point light (`fs_wing_point_lit`, per pixel; the ambient and the sun are
/// per vertex): a light 0.5 m above the grass 17 m away, among the billboards (the camera grid
/// and its neighbours end within 10 m), brightens the wings around it and not those across
/// the field. The ground is lit by the sun alone, so what brightens there is the billboards.
/// Measured on lavapipe (320x180, still camera, quarter density; sum of the RGB means in a
/// 24 x 16 window, 8-bit levels): +6.2 around the light, +0.9 110 pixels to the side (on the
/// thesis' lattice, before issue 19: +7.4 and +1.2; with the sun-only wing pipeline drawn
/// instead, +0.2).
#[test]
fn a_point_light_lights_the_billboards_around_it() -> anyhow::Result<()> {
    use grassbench::glam::{Vec2, Vec3};
    let gpu = gpu()?;
    let dark = still(scene("meadow", 0.25)?)?;
    let target = Vec2::new(16.0, 6.4);
    let light = Vec3::new(target.x, dark.terrain.height_at(target) + 0.5, target.y);
    let mut lit = dark.config.clone();
    lit.lights.point = Some(grassbench::scene::PointLight {
        position: light.to_array(),
        color: [6.0, 5.2, 4.0],
        attenuation: 1.0,
        keys: Vec::new(),
    });
    let lit = grassbench::Scene::from_config(lit, dark.base_dir.clone())?;
    let none = toml::Table::new();
    let camera = dark.config.camera.camera_at(
        0.0,
        &dark.terrain,
        TEST_SIZE.width as f32 / TEST_SIZE.height as f32,
    );
    let a = render(&gpu, "zhang", dark, 0, TEST_SIZE, &none)?;
    let b = render(&gpu, "zhang", lit, 0, TEST_SIZE, &none)?;
    let clip = camera.view_projection() * light.extend(1.0);
    let (px, py) = (
        ((clip.x / clip.w * 0.5 + 0.5) * TEST_SIZE.width as f32) as i64,
        ((0.5 - clip.y / clip.w * 0.5) * TEST_SIZE.height as f32) as i64,
    );
    // Mean brightening (sum of RGB, 8-bit levels) in a 24 x 16 window around a pixel.
    let gain = |cx: i64, cy: i64| {
        let mut sum = 0.0;
        let mut n = 0.0;
        for y in (cy - 8).max(0)..(cy + 8).min(i64::from(TEST_SIZE.height)) {
            for x in (cx - 12).max(0)..(cx + 12).min(i64::from(TEST_SIZE.width)) {
                let (p, q) = (
                    a.get_pixel(x as u32, y as u32),
                    b.get_pixel(x as u32, y as u32),
                );
                sum += (0..3)
                    .map(|c| f64::from(q[c]) - f64::from(p[c]))
                    .sum::<f64>();
                n += 1.0;
            }
        }
        sum / n
    };
    let side = if px < i64::from(TEST_SIZE.width) / 2 {
        110
    } else {
        -110
    };
    let (near, across) = (gain(px, py), gain(px + side, py));
    eprintln!(
        "measured: light at pixel ({px}, {py}): brightening {near:.1} there, {across:.1} across the field"
    );
    // Limits: 3.7, about half the measured brightening (6.2; 7.4 before issue 19); the
    // fall-off with twice the measured room.
    assert!(
        near > 3.7,
        "the point light does not light the billboards: {near:.1}"
    );
    assert!(
        across < 0.3 * near,
        "no fall-off: {near:.1} near, {across:.1} across"
    );
    Ok(())
}

/// `wing_lighting = "pixel"` (the thesis's: every light per fragment) and our per-vertex
/// ambient and sun draw the same wings: over a wing only the ambient occlusion varies, affinely
/// in height, so the per-vertex sum interpolates exactly, and the fog's curve departs from a
/// line by under 1e-5 across a wing. What differs is the side a wing shows: per vertex it is
/// turned to the eye once, from the middle of its foot, per pixel `shade_leaf` turns it at
/// every fragment, so a wing seen nearly edge-on is lit from the other side in a few pixels.
/// Measured (meadow, frame 30, 320x180, lavapipe): 62 of 57 600 pixels differ by more than 2
/// of 255, FLIP 0.00038; limits about 4x that.
#[test]
fn wings_lit_per_vertex_draw_what_wings_lit_per_pixel_draw() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("zhang")?;
    let mut harness = Harness::new(&gpu, scene("meadow", 1.0)?, SIZE, false)?;
    let mut vertex = harness.create(entry, &toml::Table::new())?;
    let a = render_with(&mut harness, vertex.as_mut(), 30)?;
    let mut pixel = harness.create(entry, &"wing_lighting = \"pixel\"".parse()?)?;
    let b = render_with(&mut harness, pixel.as_mut(), 30)?;
    assert!(counter(vertex.as_ref(), "wings") > 1000.0);
    let differ = pixels_differing(&a, &b, 2);
    let mean = flip(&a, &b)?.mean;
    eprintln!("measured: {differ} pixels differ by more than 2, FLIP {mean:.6}");
    assert!(
        differ < 250 && mean < 0.0015,
        "{differ} pixels, FLIP {mean}"
    );
    Ok(())
}

/// `hidden_half_rate = false` (the thesis: every animated blade stepped every frame with the
/// wind at each control point) and ours (blades animated but not drawn this frame stepped
/// every other frame with one wind sample) draw nearly the same frame: a hidden blade coming
/// into view is within 2 % of its height of where full steps put it. Measured (meadow, frame
/// 30, 320x180, lavapipe): 2 981 of 57 600 pixels differ by more than 2 of 255 (blades
/// that came into view a little apart), FLIP 0.0035; the bound is twice that. The two must
/// differ at all: otherwise the setting did not reach the stepping.
#[test]
fn hidden_blades_at_half_rate_draw_what_full_steps_draw() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("zhang")?;
    let mut harness = Harness::new(&gpu, scene("meadow", 1.0)?, SIZE, false)?;
    let mut half = harness.create(entry, &toml::Table::new())?;
    let a = render_with(&mut harness, half.as_mut(), 30)?;
    let mut full = harness.create(entry, &"hidden_half_rate = false".parse()?)?;
    let b = render_with(&mut harness, full.as_mut(), 30)?;
    let differ = pixels_differing(&a, &b, 2);
    let mean = flip(&a, &b)?.mean;
    eprintln!("measured: {differ} pixels differ by more than 2, FLIP {mean:.6}");
    assert!(differ > 0, "hidden_half_rate changed nothing");
    assert!(mean < 0.007, "{differ} pixels, FLIP {mean}");
    Ok(())
}

/// The meadow's terrain at `size` metres a side at 20 blades/m², as `experiments/scaling.toml`
/// has it.
fn meadow_sized(size: f32) -> anyhow::Result<grassbench::Scene> {
    let base = scene("meadow", 1.0)?;
    let mut config = base.config;
    config.terrain.size = [size, size];
    config.grass.density = 20.0;
    Ok(grassbench::Scene::from_config(config, base.base_dir)?)
}

/// Issue 20 §7: grass grids of a fixed size in metres (`grid_size`) and far groups of grids
/// (`far_groups`) keep zhang's cost from growing with the terrain, and the picture where
/// they change it stays close.
///
/// At 80 m (the scaling sweep's first saturated size) the meadow has 16 x 16 grids either
/// way and no group: the frame is the thesis count's, pixel for pixel (measured 0 pixels
/// differing). At 400 m, frame 5 at 480x270 on lavapipe: far groups (148 drawn, 342 culled)
/// against every grid on its own measured FLIP 0.0029 at full scale and 0.0026 at 1/4,
/// 27 332 triangles against 41 730 (and 393 k with the thesis' 16 x 16 grids of 25 m, the
/// scaling sweep's); the thresholds are about twice the FLIPs, and the triangles must stay
/// within 1.3x of the 80 m frame's 26 586 (measured 1.03x).
#[test]
fn fixed_grids_and_far_groups_bound_the_cost_of_a_large_terrain() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let size = Size {
        width: 480,
        height: 270,
    };
    let entry = grassbench_cli::registry::find("zhang")?;
    let thesis_count: toml::Table = toml::from_str("grid_size = 0.0\nfar_groups = 0")?;
    let ungrouped: toml::Table = toml::from_str("far_groups = 0")?;
    // 80 m: the same grids as the thesis' count, no group.
    let mut harness = Harness::new(&gpu, meadow_sized(80.0)?, size, false)?;
    let mut small = harness.create(entry, &toml::Table::new())?;
    let small_image = render_with(&mut harness, small.as_mut(), 5)?;
    let mut small_thesis = harness.create(entry, &thesis_count)?;
    let small_thesis_image = render_with(&mut harness, small_thesis.as_mut(), 5)?;
    let differing = pixels_differing(&small_image, &small_thesis_image, 0);
    eprintln!("measured: 80 m, {differing} pixels differ from the thesis' count");
    assert_eq!(differing, 0);
    assert_eq!(counter(small.as_ref(), "groups_drawn"), 0.0);
    let small_triangles = small.stats().triangles;
    drop(harness);
    // 400 m.
    let mut harness = Harness::new(&gpu, meadow_sized(400.0)?, size, false)?;
    let mut grouped = harness.create(entry, &toml::Table::new())?;
    let grouped_image = render_with(&mut harness, grouped.as_mut(), 5)?;
    let mut grids = harness.create(entry, &ungrouped)?;
    let grids_image = render_with(&mut harness, grids.as_mut(), 5)?;
    let (g, u) = (grouped.stats(), grids.stats());
    eprintln!(
        "measured: 400 m grouped {g:?} {:?}; every grid {u:?}; 80 m {small_triangles} triangles",
        grouped.counters()
    );
    assert!(counter(grouped.as_ref(), "groups_drawn") > 10.0);
    assert_eq!(counter(grids.as_ref(), "groups_drawn"), 0.0);
    // The same single plants; the groups stand for at least the blades the grids' billboards
    // did (the grids' drop wings at gaps).
    assert_eq!(g.blades_drawn, u.blades_drawn);
    assert!(g.blades_represented >= u.blades_represented);
    assert!(g.triangles * 4 < u.triangles * 3, "{g:?} against {u:?}");
    assert!(
        g.triangles * 10 < small_triangles * 13,
        "{} triangles at 400 m against {small_triangles} at 80 m",
        g.triangles
    );
    let mut failures = Vec::new();
    for (factor, limit) in [(1u32, 0.006), (4, 0.005)] {
        let mean = flip(
            &downsample(&grids_image, factor),
            &downsample(&grouped_image, factor),
        )?
        .mean;
        eprintln!("measured: 400 m far groups against every grid at 1/{factor}: FLIP {mean:.4}");
        if mean >= limit {
            failures.push(format!("1/{factor}: FLIP {mean:.4} ≥ {limit}"));
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
    Ok(())
}
