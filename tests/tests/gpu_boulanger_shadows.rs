//! Headless GPU tests of `boulanger`'s shadows projected on the ground (issue 9, Sec. 3.5,
//! Fig. 15): the blades' stencil shadows and the horizontal slices' shadows darken the ground by
//! exactly the sun's share of its light, never twice, never brighten anything, and vanish with
//! the sun. Small sizes, lavapipe.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use grassbench::camera::CameraPath;
use grassbench::color::srgb_decode;
use grassbench::glam;
use grassbench::runner::Harness;
use grassbench::scene::Scene;
use grassbench::terrain::MapSource;
use grassbench_boulanger::ground_shadow::shadow_factor;
use grassbench_tests::{TEST_SIZE, gpu, render_with, scene};

/// The pitch at a quarter of its grass (the ground shows between the blades), seen from 1.2 m
/// up looking 45° down, with the sun in `sun` and no wind.
fn sparse_pitch(sun: [f32; 3]) -> anyhow::Result<Scene> {
    let base = scene("football_field_human", 1.0)?;
    let mut config = base.config.clone();
    config.terrain.density = MapSource::Constant { value: 0.25 };
    config.lights.sun_direction = sun;
    config.camera.path = CameraPath::Fixed {
        eye: [0.0, 1.2, 1.2],
        look_at: [0.0, 0.0, 0.0],
    };
    config.wind = Default::default();
    Ok(Scene::from_config(config, base.base_dir)?)
}

/// Frame 0 of `boulanger` on `scene` with `ground_shadows` on and off, and the other overrides;
/// both images are written to the test output folder under `name`.
fn on_and_off(
    name: &str,
    scene: &Scene,
    overrides: &[(&str, toml::Value)],
) -> anyhow::Result<[image::RgbaImage; 2]> {
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("boulanger")?;
    let mut images = Vec::new();
    for on in [true, false] {
        let mut table: toml::Table = overrides
            .iter()
            .map(|(k, v)| ((*k).to_owned(), v.clone()))
            .collect();
        table.insert("blades_per_m2".into(), 2_000.0.into());
        table.insert("ground_shadows".into(), on.into());
        let mut harness = Harness::new(&gpu, scene.clone(), TEST_SIZE, false)?;
        let mut t = harness.create(entry, &table)?;
        images.push(render_with(&mut harness, t.as_mut(), 0)?);
    }
    let out = grassbench_tests::output_dir();
    std::fs::create_dir_all(&out)?;
    images[0].save(out.join(format!("boulanger-ground-shadows-{name}-on.png")))?;
    images[1].save(out.join(format!("boulanger-ground-shadows-{name}-off.png")))?;
    Ok([images.remove(0), images.remove(0)])
}

/// What the shadows did to an image: the pixels they darkened, the median ratio (linear light,
/// green channel) of those, and the violations of "darken by at most one shadow, never brighten".
#[derive(Debug)]
struct Darkening {
    darkened: f64,
    median_ratio: f32,
    brighter: usize,
    darker_than_one_shadow: usize,
}

fn darkening(on: &image::RgbaImage, off: &image::RgbaImage, factor: glam::Vec3) -> Darkening {
    let mut ratios = Vec::new();
    let (mut brighter, mut too_dark) = (0, 0);
    for (a, b) in on.pixels().zip(off.pixels()) {
        for c in 0..3 {
            let (lit, dark) = (b[c], a[c]);
            // 8-bit rounding of the blend's result: one level either way.
            if dark > lit.saturating_add(1) {
                brighter += 1;
            }
            // A pixel is at least `factor` x its unshadowed light: blades drawn over the
            // shadow only add light; a second shadow would give factor².
            let floor = grassbench::color::srgb_encode(srgb_decode(lit) * factor[c]);
            if dark.saturating_add(2) < floor {
                too_dark += 1;
            }
        }
        if a[1].saturating_add(3) <= b[1] && b[1] >= 30 {
            ratios.push(srgb_decode(a[1]) / srgb_decode(b[1]));
        }
    }
    let darkened = ratios.len() as f64 / f64::from(on.width() * on.height());
    ratios.sort_by(f32::total_cmp);
    Darkening {
        darkened,
        median_ratio: ratios.get(ratios.len() / 2).copied().unwrap_or(1.0),
        brighter,
        darker_than_one_shadow: too_dark,
    }
}

/// The shader's `ground_shadow_factor` for `scene`'s lights.
fn factor_of(scene: &Scene) -> glam::Vec3 {
    let lights = &scene.config.lights;
    let sun = glam::Vec3::from(lights.sun_direction).normalize();
    shadow_factor(lights.ambient.into(), lights.sun_color.into(), sun)
}

#[test]
fn blade_shadows_darken_the_ground_by_the_suns_share_once() -> anyhow::Result<()> {
    // Geometry everywhere: only the blades' stencil shadows. Measured on lavapipe at 320x180
    // (sun 45° up from +x): 27.6 % of the pixels darkened, median ratio 0.2598 (green) against
    // the factor 0.2599. Bounds: at least 2 % darkened; median within 0.03 of the factor (pure
    // ground pixels hit it to 8-bit rounding, blade-covered edges are lighter); no channel of
    // any pixel brighter by more than 8-bit rounding, none darker than one shadow.
    let scene = sparse_pitch([0.7, 0.7, 0.0])?;
    let factor = factor_of(&scene);
    let [on, off] = on_and_off(
        "geometry",
        &scene,
        &[
            ("min_geom", 9000.0.into()),
            ("max_geom", 9001.0.into()),
            ("min_btf", 9001.0.into()),
            ("max_btf", 9002.0.into()),
        ],
    )?;
    let d = darkening(&on, &off, factor);
    eprintln!("measured: blades, factor {factor}: {d:?}");
    assert!(d.darkened > 0.02, "{d:?}");
    assert!((d.median_ratio - factor.y).abs() < 0.03, "{d:?}");
    assert_eq!((d.brighter, d.darker_than_one_shadow), (0, 0), "{d:?}");
    Ok(())
}

#[test]
fn slice_shadows_darken_the_ground_and_never_twice_where_blades_cast_too() -> anyhow::Result<()> {
    // Horizontal slices only (geometry's weight 0 from 1 cm, no vertical slices): the slices'
    // projected shadows, weighted by their opacity. Then the default bands, where cells within
    // max_geom have both blades and a slice: the stencil keeps the two from darkening a pixel
    // twice. Measured on lavapipe at 320x180: slices 92.9 % darkened, median ratio 0.884 (a
    // slice's opacity is partial); default bands 34.0 %, 0.730. Bounds: at least 2 % darkened,
    // the median between the full shadow's factor and 0.97; no pixel brighter, none darker than
    // one shadow.
    let scene = sparse_pitch([0.7, 0.7, 0.0])?;
    let factor = factor_of(&scene);
    let slices = [
        ("min_geom", 0.0.into()),
        ("max_geom", 0.01.into()),
        ("min_btf", 0.01.into()),
        ("max_btf", 0.02.into()),
    ];
    for (what, overrides) in [("slices", &slices[..]), ("bands", &[][..])] {
        let [on, off] = on_and_off(what, &scene, overrides)?;
        let d = darkening(&on, &off, factor);
        eprintln!("measured: {what}, factor {factor}: {d:?}");
        assert!(d.darkened > 0.02, "{what}: {d:?}");
        assert!(
            d.median_ratio >= factor.y - 0.02 && d.median_ratio < 0.97,
            "{what}: {d:?}"
        );
        assert_eq!(
            (d.brighter, d.darker_than_one_shadow),
            (0, 0),
            "{what}: {d:?}"
        );
    }
    Ok(())
}

#[test]
fn no_ground_shadows_without_the_sun() -> anyhow::Result<()> {
    // The sun 1° over the horizon is under the 0.05 sine the projection needs: shadows would
    // stretch over 20 blade heights while the sun gives the ground almost nothing to take away.
    let scene = sparse_pitch([1.0, 0.017, 0.0])?;
    let [on, off] = on_and_off("low-sun", &scene, &[])?;
    assert!(on == off, "shadows cast by a sun on the horizon");
    Ok(())
}
