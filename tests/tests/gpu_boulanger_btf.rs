//! Headless GPU tests of `boulanger`'s issue 9 (the bake's determinism, time and cache are in
//! `gpu_boulanger_bake.rs`): the cache keys follow every bake parameter, a vertical slice at a
//! sampled light and view direction matches the geometric patch, moving lights change the
//! image continuously, popping across the LOD bands with and without the seamless transition,
//! the shadow mask, the occlusion map and the wind's shear. Small sizes, lavapipe.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use anyhow::Context as _;
use grassbench::camera::CameraPath;
use grassbench::metrics::{downsample, flip};
use grassbench::runner::Harness;
use grassbench::scene::Scene;
use grassbench::target::Size;
use grassbench_boulanger::Boulanger;
use grassbench_tests::{TEST_SIZE, gpu, render_with, scene};

fn params(pairs: &[(&str, toml::Value)]) -> toml::Table {
    pairs
        .iter()
        .map(|(k, v)| ((*k).to_owned(), v.clone()))
        .collect()
}

#[test]
fn cache_keys_follow_every_bake_parameter_and_only_those() -> anyhow::Result<()> {
    let base_scene = scene("football_field", 1.0)?;
    let base = Boulanger::bake_keys(&base_scene, &toml::Table::new())?;
    // (parameter, value, which keys must change: horizontal, vertical)
    let changes: [(&str, toml::Value, [bool; 2]); 12] = [
        ("patch_size", 0.6.into(), [true, true]),
        ("blades_per_m2", 1000.0.into(), [true, true]),
        ("segments", 4.into(), [true, true]),
        ("max_tilt", 0.3.into(), [true, true]),
        ("gravity", 0.5.into(), [true, true]),
        ("translucency", 0.2.into(), [true, true]),
        ("ao_root", 0.5.into(), [true, true]),
        ("slice_resolution", 256.into(), [true, true]),
        ("vertical_slices", 8.into(), [true, true]),
        ("vslice_width", 128.into(), [false, true]),
        ("vslice_height", 32.into(), [false, true]),
        ("min_geom", 2.0.into(), [false, false]),
    ];
    for (name, value, expected) in changes {
        let keys = Boulanger::bake_keys(&base_scene, &params(&[(name, value)]))?;
        for k in 0..2 {
            assert_eq!(keys[k] != base[k], expected[k], "{name}: BTF {k}");
        }
    }
    for (name, value) in [
        ("omega", toml::Value::from(0.2)),
        ("max_btf", 40.0.into()),
        ("alpha_threshold", 0.2.into()),
        ("wind_response", 0.3.into()),
        ("btf_cache", "off".into()),
    ] {
        let keys = Boulanger::bake_keys(&base_scene, &params(&[(name, value)]))?;
        assert_eq!(keys, base, "{name} does not change the bake");
    }
    // The scene's blades and colours: seed, heights, colours.
    let edit = |f: &dyn Fn(&mut grassbench::scene::SceneConfig)| -> anyhow::Result<[u64; 2]> {
        let mut config = base_scene.config.clone();
        f(&mut config);
        let s = Scene::from_config(config, base_scene.base_dir.clone())?;
        Ok(Boulanger::bake_keys(&s, &toml::Table::new())?)
    };
    for (what, keys) in [
        ("seed", edit(&|c| c.seed += 1)?),
        ("height", edit(&|c| c.grass.height[1] += 0.01)?),
        ("colour", edit(&|c| c.grass.color_tip[1] += 0.01)?),
    ] {
        assert!(keys[0] != base[0] && keys[1] != base[1], "{what}");
    }
    Ok(())
}

/// The pitch seen from a fixed eye 0.8 m up, looking along −z (across the z slices, which
/// face it) and a little down, with the sun in `sun`.
fn fixed_view(sun: [f32; 3]) -> anyhow::Result<Scene> {
    let base = scene("football_field_human", 1.0)?;
    let mut config = base.config.clone();
    config.lights.sun_direction = sun;
    config.camera.path = CameraPath::Fixed {
        eye: [0.13, 0.8, 8.0],
        look_at: [0.13, 0.0, -6.0],
    };
    config.wind = Default::default();
    Ok(Scene::from_config(config, base.base_dir)?)
}

fn render_fixed(
    sun: [f32; 3],
    size: Size,
    overrides: &toml::Table,
) -> anyhow::Result<image::RgbaImage> {
    let gpu = gpu()?;
    let mut harness = Harness::new(&gpu, fixed_view(sun)?, size, false)?;
    let entry = grassbench_cli::registry::find("boulanger")?;
    let mut t = harness.create(entry, overrides)?;
    render_with(&mut harness, t.as_mut(), 0)
}

#[test]
fn a_slice_at_its_own_light_and_view_matches_the_geometric_patch() -> anyhow::Result<()> {
    // Slices only (geometry's weight is 0 from 1 cm, vertical slices at full weight to 1 km)
    // against geometry everywhere, the sun straight up (Y+, a sampled direction: weight 1, no
    // interpolation) and the camera looking along the z slices' normal. Both images are the
    // same patch, so what differs is what slices cannot keep: parallax inside a slab, depth
    // order between slices (blended unsorted), mip-mapped coverage and the per-pixel
    // threshold test. Measured on lavapipe at 320x180: mean FLIP 0.182 full scale, 0.166 at
    // 1/4 with issue 19's patch of 1 250 blades (0.181 / 0.168 with the square 35² = 1 225
    // before it, 0.185 / 0.170 before the shadow mask); the bare ground (no grass) against the
    // same geometry 0.336 / 0.332. Bounds: the measurement plus 0.03-0.04, and under 0.6x the
    // control.
    let blades = ("blades_per_m2", toml::Value::from(5_000.0));
    let slices = params(&[
        blades.clone(),
        ("min_geom", 0.0.into()),
        ("max_geom", 0.01.into()),
        ("min_btf", 1000.0.into()),
        ("max_btf", 2000.0.into()),
    ]);
    let geometry = params(&[
        blades,
        ("min_geom", 9000.0.into()),
        ("max_geom", 9001.0.into()),
        ("min_btf", 9001.0.into()),
        ("max_btf", 9002.0.into()),
    ]);
    let sun = [0.0, 1.0, 0.0];
    let s = render_fixed(sun, TEST_SIZE, &slices)?;
    let g = render_fixed(sun, TEST_SIZE, &geometry)?;
    let blank = {
        let gpu = gpu()?;
        let mut harness = Harness::new(&gpu, fixed_view(sun)?, TEST_SIZE, false)?;
        render_with(&mut harness, &mut grassbench::technique::NoGrass, 0)?
    };
    let full = flip(&g, &s)?.mean;
    let quarter = flip(&downsample(&g, 4), &downsample(&s, 4))?.mean;
    let control = flip(&g, &blank)?.mean;
    let control_quarter = flip(&downsample(&g, 4), &downsample(&blank, 4))?.mean;
    eprintln!("measured: slices vs geometry FLIP {full:.3}, 1/4 {quarter:.3}");
    eprintln!("measured: control (bare ground) vs geometry {control:.3}, 1/4 {control_quarter:.3}");
    let out = grassbench_tests::output_dir();
    std::fs::create_dir_all(&out)?;
    s.save(out.join("boulanger-slices-y.png"))?;
    g.save(out.join("boulanger-geometry-y.png"))?;
    assert!(full < 0.22, "full-scale FLIP {full:.3}");
    assert!(quarter < 0.20, "quarter-scale FLIP {quarter:.3}");
    assert!(full < 0.6 * control && quarter < 0.6 * control_quarter);
    Ok(())
}

/// Mean absolute change between consecutive images, in 8-bit levels.
fn steps(images: &[image::RgbaImage]) -> Vec<f64> {
    images
        .windows(2)
        .map(|w| {
            let (a, b) = (&w[0], &w[1]);
            a.as_raw()
                .iter()
                .zip(b.as_raw())
                .map(|(x, y)| (f64::from(*x) - f64::from(*y)).abs())
                .sum::<f64>()
                / a.as_raw().len() as f64
        })
        .collect()
}

/// Frames 0-7 of the fixed view with `lights` edited, in one harness (lights move at run time
/// through their keyframes; the scene runs at 30 fps), wind calm.
fn frames_with(
    edit: &dyn Fn(&mut grassbench::scene::LightsConfig),
    overrides: &toml::Table,
) -> anyhow::Result<Vec<image::RgbaImage>> {
    let base = fixed_view([0.5, 0.7, 0.3])?;
    let mut config = base.config.clone();
    edit(&mut config.lights);
    let gpu = gpu()?;
    let mut harness = Harness::new(
        &gpu,
        Scene::from_config(config, base.base_dir)?,
        TEST_SIZE,
        false,
    )?;
    let entry = grassbench_cli::registry::find("boulanger")?;
    let mut t = harness.create(entry, overrides)?;
    (0..8)
        .map(|f| render_with(&mut harness, t.as_mut(), f))
        .collect()
}

fn key(frame: f32, value: [f32; 3]) -> grassbench::scene::LightKey {
    grassbench::scene::LightKey {
        time: frame / 30.0,
        value,
    }
}

#[test]
fn a_moving_light_changes_the_image_continuously() -> anyhow::Result<()> {
    // The sun's keyframes take it from 27° to 62° above the horizon over frames 0-7, in the
    // plane l_z = 0 (the border between the Z+ and Z− quadrants), past 45° where the nearest
    // sample switches from X+ to Y+; the view is mostly vertical slices. Appendix A's
    // interpolation makes the image change by about the same amount at every frame; picking
    // the nearest sample instead would jump at 45°. Measured mean absolute change per frame
    // on lavapipe (320x180, 8-bit levels): 1.25, 1.26, 1.25, 1.23, 1.21, 1.16, 1.12, the
    // largest 1.03x the median. Bound: the largest step under 2x the median.
    let overrides = params(&[("blades_per_m2", 5_000.0.into())]);
    let (lo, hi) = (27f32.to_radians(), 62f32.to_radians());
    let images = frames_with(
        &|l| {
            l.sun_keys = vec![
                key(0.0, [lo.cos(), lo.sin(), 0.0]),
                key(7.0, [hi.cos(), hi.sin(), 0.0]),
            ]
        },
        &overrides,
    )?;
    let steps = steps(&images);
    let mut sorted = steps.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    let max = sorted[sorted.len() - 1];
    eprintln!(
        "measured: sun, change per frame {steps:.3?}, max / median {:.2}",
        max / median
    );
    assert!(median > 0.0, "the light does not change the image");
    assert!(max < 2.0 * median, "a jump: {steps:?}");
    Ok(())
}

#[test]
fn a_point_light_lights_the_slices_with_attenuation_and_moves_smoothly() -> anyhow::Result<()> {
    // A point light 0.6 m above the mid band (3 m in front of the eye, vertical slices from
    // 3.5 m), β = 1, crossing the view from x = -2 to 2 m over frames 0-7. Against the same
    // frames without it: the grass brightens most in the rows nearest the light (image rows
    // 110-160) and little on the far field (rows 90-100, 15-40 m away, where 1/(1 + βd²) is
    // under 1/100); frame to frame it moves without jumps. Measured on lavapipe (sum of the
    // RGB means, 8-bit levels): near rows +23.0, far rows +0.9 (+38.0 and +6.4 before the
    // shadow mask); change per frame 1.28-1.51, the largest 1.1x the median.
    let overrides = params(&[("blades_per_m2", 5_000.0.into())]);
    let lit = frames_with(
        &|l| {
            l.point = Some(grassbench::scene::PointLight {
                position: [0.0; 3],
                color: [3.0, 2.6, 2.0],
                attenuation: 1.0,
                keys: vec![key(0.0, [-1.87, 0.6, 5.0]), key(7.0, [2.13, 0.6, 5.0])],
            })
        },
        &overrides,
    )?;
    let dark = frames_with(&|_| {}, &overrides)?;
    let rows = |img: &image::RgbaImage, y0: u32, y1: u32| {
        grassbench::metrics::mean_color(
            &image::imageops::crop_imm(img, 0, y0, img.width(), y1 - y0).to_image(),
        )
        .iter()
        .sum::<f64>()
    };
    let near = rows(&lit[3], 110, 160) - rows(&dark[3], 110, 160);
    let far = rows(&lit[3], 90, 100) - rows(&dark[3], 90, 100);
    let steps = steps(&lit);
    let mut sorted = steps.clone();
    sorted.sort_by(f64::total_cmp);
    let (median, max) = (sorted[sorted.len() / 2], sorted[sorted.len() - 1]);
    eprintln!(
        "measured: point light brightens near rows by {near:.1}, far rows by {far:.1}; change per frame {steps:.3?}"
    );
    assert!(
        near > 10.0,
        "the point light does not light the grass: {near:.1}"
    );
    assert!(
        far < 0.25 * near,
        "no attenuation: near {near:.1}, far {far:.1}"
    );
    assert!(median > 0.0 && max < 2.0 * median, "a jump: {steps:?}");
    Ok(())
}

#[test]
fn popping_across_the_lod_bands_with_and_without_the_seamless_transition() -> anyhow::Result<()> {
    // A dolly of 0.25 m a frame from the walker's first view of the pitch: every LOD band
    // (geometry to 3.5 m, vertical slices to 30 m, the horizontal slice beyond) slides
    // towards the camera, so blades change representation in every frame. Each technique's
    // change is compared with the reference's (`compare::temporal_change`): spurious change
    // is change the reference does not have. The seamless transition (Sec. 3.4, ω = 0.4)
    // must show less of it than the hard switch (`no_transitions`: no blend, no density
    // split, every cell wholly one level). Measured on lavapipe at 320x180, 8 steps, the
    // scene's own density: at 1/4 scale spurious peak 0.599 seamless against 0.729 hard
    // (x1.22; means 0.578 and 0.701), at full scale 0.853 against 0.918 (blade placement
    // differs from the reference's there, which both share). Before issue 19 the hard switch
    // kept the density split and the two differed by 2 % in the old ratio metric.
    use grassbench::compare::{self, CameraMotion, Scale};
    let gpu = gpu()?;
    let scene = scene("football_field_human", 1.0)?;
    let motion = CameraMotion::Dolly(0.25);
    let reference = grassbench_cli::registry::find("reference")?;
    let base = compare::motion_frames(
        &gpu,
        &scene,
        reference,
        &toml::Table::new(),
        motion,
        8,
        TEST_SIZE,
    )?;
    let entry = grassbench_cli::registry::find("boulanger")?;
    let hard = entry
        .variant(grassbench::technique::NO_TRANSITIONS)
        .context("boulanger has a no_transitions variant")??;
    let mut peaks = Vec::new();
    for (name, overrides) in [("seamless", toml::Table::new()), ("hard switch", hard)] {
        let frames = compare::motion_frames(&gpu, &scene, entry, &overrides, motion, 8, TEST_SIZE)?;
        for scale in Scale::ALL {
            let c = compare::temporal_change(motion, scale, &frames, &base)?;
            eprintln!(
                "measured: boulanger {name} at {}: spurious mean {:.3} p95 {:.3} peak {:.3}, missing mean {:.3}",
                scale.name(),
                c.spurious.mean,
                c.spurious.p95,
                c.spurious.peak,
                c.missing.mean
            );
            if scale == Scale::Quarter {
                peaks.push(c.spurious.peak);
            }
        }
    }
    let (seamless, hard) = (peaks[0], peaks[1]);
    assert!(
        hard > HARD_OVER_SEAMLESS * seamless,
        "without the transition the spurious peak {hard:.3} is not x{HARD_OVER_SEAMLESS} above {seamless:.3}"
    );
    Ok(())
}

/// How much more spurious change (peak over the steps, 1/4 scale) the hard switch must show:
/// half the measured x1.22, so a seamless transition that stopped working (x1.0) fails.
const HARD_OVER_SEAMLESS: f64 = 1.1;

#[test]
fn wind_shears_the_slices_and_animate_false_keeps_the_papers_static_grass() -> anyhow::Result<()> {
    // The fixed view with the pitch's own breeze (2.5 m/s, gusts): between frames 0 and 20
    // (0.67 s) the mid band (image rows 95-140, vertical slices 4-20 m away) changes when the
    // grass is animated, and nothing changes with `animate = false` (camera and lights fixed).
    // Measured on lavapipe (mean absolute change of those rows, 8-bit levels): 1.12 animated
    // (geometry is off, so it is the slices' shear alone), exactly 0 with `animate = false`.
    let base = scene("football_field_human", 1.0)?;
    let mut config = base.config.clone();
    config.camera.path = CameraPath::Fixed {
        eye: [0.13, 0.8, 8.0],
        look_at: [0.13, 0.0, -6.0],
    };
    let windy = Scene::from_config(config, base.base_dir)?;
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("boulanger")?;
    let mut changes = Vec::new();
    for animate in [true, false] {
        let mut harness = Harness::new(&gpu, windy.clone(), TEST_SIZE, false)?;
        let overrides = params(&[
            ("blades_per_m2", 5_000.0.into()),
            ("animate", animate.into()),
            // Slices only, so the change is the slices' own.
            ("min_geom", 0.0.into()),
            ("max_geom", 0.01.into()),
        ]);
        let mut t = harness.create(entry, &overrides)?;
        let a = render_with(&mut harness, t.as_mut(), 0)?;
        let b = render_with(&mut harness, t.as_mut(), 20)?;
        let crop = |img: &image::RgbaImage| {
            image::imageops::crop_imm(img, 0, 95, img.width(), 45).to_image()
        };
        let change = steps(&[crop(&a), crop(&b)])[0];
        eprintln!("measured: animate = {animate}: mid-band change over 20 frames {change:.3}");
        changes.push(change);
    }
    assert!(changes[0] > 0.2, "the slices do not sway: {changes:?}");
    assert_eq!(changes[1], 0.0, "animate = false still moves: {changes:?}");
    Ok(())
}

#[test]
fn the_shadow_mask_darkens_blades_and_slices() -> anyhow::Result<()> {
    // Sec. 3.5's blade-to-blade shadows on the walker's view at 5 000 blades/m²: with the
    // mask the rows of geometry (bottom, 160-180) and of vertical slices (middle, 90-130)
    // lose part of their sunlight. Measured on lavapipe at 320x180 (mean of the RGB means,
    // 8-bit levels, mask on / off): bottom 73.8 / 83.6, middle 69.4 / 79.6, 12-13 % darker
    // (the ambient term is not shadowed). Bounds: 3-25 % darker in both bands.
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("boulanger")?;
    let mut bands = Vec::new();
    for on in [true, false] {
        let mut harness =
            Harness::new(&gpu, scene("football_field_human", 1.0)?, TEST_SIZE, false)?;
        let overrides = params(&[
            ("blades_per_m2", 5_000.0.into()),
            ("shadow_mask", on.into()),
        ]);
        let mut t = harness.create(entry, &overrides)?;
        let img = render_with(&mut harness, t.as_mut(), 3)?;
        let band = |y0: u32, y1: u32| {
            grassbench::metrics::mean_color(
                &image::imageops::crop_imm(&img, 0, y0, img.width(), y1 - y0).to_image(),
            )
            .iter()
            .sum::<f64>()
                / 3.0
        };
        bands.push([band(160, 180), band(90, 130)]);
    }
    eprintln!(
        "measured: shadow mask on {:.1?}, off {:.1?}",
        bands[0], bands[1]
    );
    for (k, (on, off)) in bands[0].iter().zip(&bands[1]).enumerate() {
        let ratio = on / off;
        assert!(
            (0.75..0.97).contains(&ratio),
            "band {k}: on / off = {ratio:.3}"
        );
    }
    Ok(())
}

#[test]
fn trees_and_stones_darken_the_ambient_light_of_the_grass_around_them() -> anyhow::Result<()> {
    // Sec. 3.5's ambient occlusion map. On the pitch (no trees, no stones) it changes no
    // pixel; on the meadow with a covering map of 5 % trees and 5 % stones the grass loses
    // part of its sky light. Measured on lavapipe at 320x180, 5 000 blades/m², frame 30
    // (mean of the RGB means of the lower half, 8-bit levels, map on / off): 87.9 / 100.9,
    // 13 % darker. Bounds: 1-30 % darker.
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("boulanger")?;
    let render = |scene: Scene, on: bool| -> anyhow::Result<image::RgbaImage> {
        let mut harness = Harness::new(&gpu, scene, TEST_SIZE, false)?;
        let overrides = params(&[
            ("blades_per_m2", 5_000.0.into()),
            ("external_ao", on.into()),
        ]);
        let mut t = harness.create(entry, &overrides)?;
        render_with(&mut harness, t.as_mut(), 30)
    };
    let pitch = scene("football_field_human", 1.0)?;
    assert!(
        render(pitch.clone(), true)? == render(pitch, false)?,
        "the map changes a field without occluders"
    );
    let meadow = scene("meadow", 1.0)?;
    let mut config = meadow.config.clone();
    config.terrain.covering = grassbench::terrain::CoveringSource::Procedural {
        gaps: 0.05,
        trees: 0.05,
        stones: 0.05,
        frequency: 0.05,
    };
    let wooded = Scene::from_config(config, meadow.base_dir)?;
    let lower = |img: &image::RgbaImage| {
        grassbench::metrics::mean_color(
            &image::imageops::crop_imm(img, 0, 90, img.width(), 90).to_image(),
        )
        .iter()
        .sum::<f64>()
            / 3.0
    };
    let (on, off) = (
        lower(&render(wooded.clone(), true)?),
        lower(&render(wooded, false)?),
    );
    eprintln!("measured: wooded meadow, lower half {on:.1} with the map, {off:.1} without");
    assert!(
        (0.70..0.99).contains(&(on / off)),
        "on / off = {:.3}",
        on / off
    );
    Ok(())
}
