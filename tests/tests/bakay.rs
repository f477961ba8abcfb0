//! Headless GPU tests of `bakay` (animated transparent shells) on a software rasteriser, at
//! small size, and its CPU mirror of the shader's wind and bend.

use grassbench::glam::Vec3;
use grassbench::metrics::{downsample, flip, grass_coverage};
use grassbench::runner::Harness;
use grassbench::technique::NoGrass;
use grassbench::terrain::{CoveringSource, MapSource};
use grassbench::{Scene, camera::CameraPath};
use grassbench_bakay::{bend, wind};
use grassbench_tests::{TEST_SIZE, gpu, render, render_record, render_with, scene};

fn params(pairs: &[(&str, toml::Value)]) -> toml::Table {
    pairs
        .iter()
        .map(|(k, v)| ((*k).to_owned(), v.clone()))
        .collect()
}

/// The meadow seen from a fixed point, so two frames differ only through the wind.
fn still_meadow() -> anyhow::Result<Scene> {
    let mut s = scene("meadow", 0.5)?;
    s.config.camera.path = CameraPath::Fixed {
        eye: [0.0, 3.0, 0.0],
        look_at: [10.0, 1.0, 4.0],
    };
    Ok(Scene::from_config(s.config, s.base_dir)?)
}

#[test]
fn shells_keep_blade_length_and_bend_downwind_on_the_cpu_mirror() {
    // Eight vertices of a sloped ground in the meadow's wind: every shell segment keeps S, the
    // tips move along the wind's tangential direction, and without wind nothing moves.
    let s = 0.65 / 16.0;
    for k in 0..8 {
        let n = Vec3::new(0.05 * k as f32, 1.0, -0.03 * k as f32).normalize();
        let p = Vec3::new(k as f32, 0.2 * k as f32, -(k as f32));
        let v = Vec3::new(3.5, 0.0, 1.2) * (0.5 + 0.2 * k as f32);
        let w = wind::scene(v, n, 12.0, 1.0);
        let o = bend::offsets(16, s, w.intensity, 1.0);
        let shells: Vec<Vec3> = o
            .iter()
            .map(|&off| wind::shell_position(p, n, w, off))
            .collect();
        for pair in shells.windows(2) {
            assert!(((pair[1] - pair[0]).length() - s).abs() < 1e-5);
        }
        let tip = shells[15] - p;
        let tangential = tip - tip.dot(n) * n;
        assert!(tangential.normalize().dot((v - v.dot(n) * n).normalize()) > 0.999);
        let calm = wind::scene(Vec3::ZERO, n, 12.0, 1.0);
        let straight = bend::offsets(16, s, calm.intensity, 1.0);
        assert!(
            (wind::shell_position(p, n, calm, straight[15]) - (p + n * 15.0 * s)).length() < 1e-5
        );
    }
}

#[test]
fn more_shells_cover_more_at_a_grazing_view() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let mut harness = Harness::new(&gpu, scene("meadow", 0.5)?, TEST_SIZE, false)?;
    let background = render_with(&mut harness, &mut NoGrass, 3)?;
    let entry = grassbench_cli::registry::find("bakay")?;
    let mut coverage = Vec::new();
    for shells in [2, 16, 64] {
        let mut t = harness.create(entry, &params(&[("shells", shells.into())]))?;
        let image = render_with(&mut harness, t.as_mut(), 3)?;
        coverage.push(grass_coverage(&image, &background, 6)?);
    }
    eprintln!("measured: coverage with 2, 16, 64 shells {coverage:.4?}");
    // Measured 0.0182, 0.0357, 0.0904 (lavapipe, 320x180, frame 3, the scene's density: x1.96
    // and x2.53 from one to the next; 2 shells already show the roots and a half-height
    // section of every blade); 0.0182, 0.0358, 0.0876 with the level of detail (issue 20 §7:
    // far chunks draw fewer of the 64 shells). With the texture 9 times denser (the default before issue 19):
    // 0.162, 0.290, 0.533 (x1.79, x1.84). Shells that added nothing (all at one height, or
    // the alpha test ignoring the shell) would give x1.
    assert!(
        coverage[1] > 1.5 * coverage[0] && coverage[2] > 1.5 * coverage[1],
        "{coverage:?}"
    );
    // Grass stays on the ground: the top eighth (sky) is untouched.
    let mut t = harness.create(entry, &toml::Table::new())?;
    let image = render_with(&mut harness, t.as_mut(), 3)?;
    let mask = grassbench::metrics::coverage_mask(&image, &background, 6)?;
    let w = TEST_SIZE.width as usize;
    assert!(
        mask[..w * TEST_SIZE.height as usize / 8].iter().all(|m| !m),
        "grass in the sky"
    );
    Ok(())
}

#[test]
fn wind_animates_shells_and_zero_wind_leaves_them_still() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let windy = toml::Table::new();
    let f0 = render(&gpu, "bakay", still_meadow()?, 0, TEST_SIZE, &windy)?;
    let f20 = render(&gpu, "bakay", still_meadow()?, 20, TEST_SIZE, &windy)?;
    let psnr = grassbench::metrics::psnr(&f0, &f20)?;
    eprintln!("measured: frames 0 and 20 in the scene's wind, PSNR {psnr:.2} dB");
    // Measured 45.6 dB at the scene's density (605 of 57 600 pixels differ; 33.8 dB with the
    // texture 9 times denser, the default before issue 19): the grass is sparse, so the wind
    // moves few pixels. Still shells give identical frames (infinite PSNR, as the calm case
    // below checks byte for byte).
    assert!(
        psnr.is_finite() && psnr < 50.0,
        "scene wind did not move the shells (PSNR {psnr:.1} dB)"
    );
    // With the intensity clamped to 0 the shells stand straight: only the wind depends on time.
    let calm = params(&[("max_intensity", 0.0.into())]);
    let c0 = render(&gpu, "bakay", still_meadow()?, 0, TEST_SIZE, &calm)?;
    let c20 = render(&gpu, "bakay", still_meadow()?, 20, TEST_SIZE, &calm)?;
    assert!(c0.as_raw() == c20.as_raw(), "calm shells moved");
    // The paper's own point source animates too, differently from the scene's wind.
    let point = params(&[
        ("wind", "point_source".into()),
        (
            "source_position",
            toml::Value::Array(vec![5.0.into(), 0.0.into(), 5.0.into()]),
        ),
    ]);
    let p0 = render(&gpu, "bakay", still_meadow()?, 0, TEST_SIZE, &point)?;
    let p20 = render(&gpu, "bakay", still_meadow()?, 20, TEST_SIZE, &point)?;
    assert!(p0.as_raw() != p20.as_raw() && p20.as_raw() != f20.as_raw());
    // Same seed, same frame: same bytes.
    let again = render(&gpu, "bakay", still_meadow()?, 20, TEST_SIZE, &windy)?;
    assert!(
        again.as_raw() == f20.as_raw(),
        "two renders of the same frame differ"
    );
    Ok(())
}

#[test]
fn density_and_covering_maps_are_respected() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let base = scene("meadow", 0.5)?;
    let with_maps = |density: MapSource, covering: CoveringSource| -> anyhow::Result<Scene> {
        let mut c = base.config.clone();
        c.terrain.density = density;
        c.terrain.covering = covering;
        Ok(Scene::from_config(c, base.base_dir.clone())?)
    };
    let none = toml::Table::new();
    let coverage = |s: Scene| -> anyhow::Result<f64> {
        let mut harness = Harness::new(&gpu, s, TEST_SIZE, false)?;
        let background = render_with(&mut harness, &mut NoGrass, 3)?;
        let mut t = harness.create(grassbench_cli::registry::find("bakay")?, &none)?;
        let image = render_with(&mut harness, t.as_mut(), 3)?;
        Ok(grass_coverage(&image, &background, 6)?)
    };
    let full = coverage(with_maps(
        MapSource::Constant { value: 1.0 },
        CoveringSource::Grass,
    )?)?;
    let half = coverage(with_maps(
        MapSource::Constant { value: 0.5 },
        CoveringSource::Grass,
    )?)?;
    let zero = coverage(with_maps(
        MapSource::Constant { value: 0.0 },
        CoveringSource::Grass,
    )?)?;
    let bare = coverage(with_maps(
        MapSource::Constant { value: 1.0 },
        CoveringSource::Procedural {
            gaps: 0.999,
            trees: 0.0,
            stones: 0.0,
            frequency: 0.05,
        },
    )?)?;
    eprintln!(
        "measured: coverage at density maps 1, 0.5, 0: {full:.4}, {half:.4}, {zero:.4}; bare covering {bare:.4}"
    );
    // Measured at density maps 1, 0.5 and 0 and on bare covering: 0.0391, 0.0218 (0.56 of
    // full), 0 and 0 (meadow at half the scene's density, constant density map, TEST_SIZE,
    // lavapipe; full was 0.272 with the texture 9 times denser, the default before issue
    // 19). The first bound only asks for visible grass: half of 0.039.
    assert!(full > 0.02, "full density covers only {full}");
    assert!(
        half < 0.9 * full && half > 0.3 * full,
        "half density: {half} vs {full}"
    );
    assert!(zero < 1e-3, "zero density still covers {zero}");
    assert!(bare < 0.02, "bare ground still covers {bare}");
    Ok(())
}

/// Mean FLIP of bakay against reference on the meadow, frame 30, 320x180, lavapipe. At the
/// scene's density (the default since issue 19): 0.113 at full scale, 0.071 at 1/4, 0.063 at
/// 1/16 (bare ground against reference at 1/16: 0.067). With the texture 9 times denser (the
/// default before): 0.132, 0.071, 0.052. Blades stand in different places by design, so
/// full-scale FLIP says little. Bounds: the first measurements (0.149, 0.088 on an earlier,
/// sparser meadow) plus ~20 %.
const FLIP_FULL: f32 = 0.18;
/// See [`FLIP_FULL`].
const FLIP_QUARTER: f32 = 0.105;

#[test]
fn image_is_close_to_reference_at_reduced_scale() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let none = toml::Table::new();
    let reference = render(
        &gpu,
        "reference",
        scene("meadow", 0.5)?,
        30,
        TEST_SIZE,
        &none,
    )?;
    let bakay = render(&gpu, "bakay", scene("meadow", 0.5)?, 30, TEST_SIZE, &none)?;
    let dense = render(
        &gpu,
        "bakay",
        scene("meadow", 0.5)?,
        30,
        TEST_SIZE,
        &params(&[("density_scale", 9.0.into())]),
    )?;
    let mut harness = Harness::new(&gpu, scene("meadow", 0.5)?, TEST_SIZE, false)?;
    let bare = render_with(&mut harness, &mut NoGrass, 30)?;
    let full = flip(&reference, &bakay)?.mean;
    let quarter = flip(&downsample(&reference, 4), &downsample(&bakay, 4))?.mean;
    let sixteenth = flip(&downsample(&reference, 16), &downsample(&bakay, 16))?.mean;
    let bare_sixteenth = flip(&downsample(&reference, 16), &downsample(&bare, 16))?.mean;
    eprintln!(
        "measured: bakay vs reference, meadow frame 30: FLIP {full:.4} full, {quarter:.4} at 1/4, {sixteenth:.4} at 1/16 (bare ground {bare_sixteenth:.4})"
    );
    assert!(full < FLIP_FULL, "FLIP {full}");
    assert!(quarter < FLIP_QUARTER, "FLIP at 1/4 scale {quarter}");
    // The walker's grazing view of the scene's population: shells show a blade only where
    // they cut it, so bakay shows little grass (coverage 0.036 against the reference's 0.323
    // at frame 3) and is only a little nearer the reference than bare ground at 1/16
    // (measured 0.063 against 0.067). Wrong colours or grass off the ground would put it
    // farther.
    assert!(
        sixteenth < bare_sixteenth,
        "at 1/16 bakay {sixteenth} is farther from the reference than bare ground {bare_sixteenth}"
    );
    // The mean colour is nearer the reference's than bare ground's is: measured 3.28 against
    // 3.90 (8-bit levels). A texture 9 times denser than the scene's (`density_scale`, the
    // departure the paper suggests for such views, Sec. 5) brings it to 1.10: more than
    // halves bare ground's distance. With the level of detail (issue 20 §7, the default):
    // 3.32 and 0.97.
    let m = grassbench::metrics::mean_color;
    let dist = |a: [f64; 3], b: [f64; 3]| (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt();
    let (ours, denser, ground) = (
        dist(m(&bakay), m(&reference)),
        dist(m(&dense), m(&reference)),
        dist(m(&bare), m(&reference)),
    );
    eprintln!(
        "measured: mean colour from the reference's: bakay {ours:.2}, 9x denser texture {denser:.2}, bare ground {ground:.2}"
    );
    assert!(
        ours < ground,
        "mean colour {ours:.2} vs bare ground {ground:.2}"
    );
    assert!(
        denser < 0.5 * ground,
        "9x denser texture: mean colour {denser:.2} vs bare ground {ground:.2}"
    );
    Ok(())
}

#[test]
fn bad_parameters_are_refused_with_the_key() -> anyhow::Result<()> {
    let gpu = gpu()?;
    for (key, value) in [
        ("shells", toml::Value::from(0)),
        ("shells", 129.into()),
        ("stiffness", f64::NAN.into()),
    ] {
        let e = render(
            &gpu,
            "bakay",
            scene("meadow", 0.01)?,
            0,
            TEST_SIZE,
            &params(&[(key, value.clone())]),
        )
        .err()
        .map(|e| e.to_string())
        .ok_or_else(|| anyhow::anyhow!("bakay.{key} = {value} was accepted"))?;
        assert!(e.contains(&format!("bakay.{key}")), "{e}");
    }
    Ok(())
}

/// The level of detail (issue 20 §7, `shell_lod_pixels`) on the scaling sweep's far point: the
/// meadow grown to 400 m a side at 20 blades/m², walker frame 6, 320x180. Measured (lavapipe):
/// 614 k triangles with every shell everywhere, 90 k with the level of detail; mean FLIP
/// between the two 0.0001, while a level of detail of 8 pixels is 0.0025 from every shell and
/// bare ground (no shells at all) 0.0163 (on the 257-wide mesh of before `MAX_GROUND_SIDE` =
/// 241: 696 k, 91 k, 0.0003, 0.0025 and 0.0153).
#[test]
fn far_chunks_draw_fewer_shells_and_the_picture_holds() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let mut config = scene("meadow", 20.0 / 90.0)?.config;
    config.terrain.size = [400.0, 400.0];
    let base = scene("meadow", 1.0)?.base_dir;
    let entry = grassbench_cli::registry::find("bakay")?;
    let mut harness = Harness::new(&gpu, Scene::from_config(config, base)?, TEST_SIZE, false)?;
    let bare = render_with(&mut harness, &mut NoGrass, 6)?;
    let mut run = |pixels: f64| -> anyhow::Result<(image::RgbaImage, u64)> {
        let mut t = harness.create(entry, &params(&[("shell_lod_pixels", pixels.into())]))?;
        let (image, record) = render_record(&mut harness, t.as_mut(), 6)?;
        Ok((image, record.triangles))
    };
    let (all, all_triangles) = run(0.0)?;
    let (lod, lod_triangles) = run(1.0)?;
    let (coarse, _) = run(8.0)?;
    let change = flip(&all, &lod)?.mean;
    let coarse_change = flip(&all, &coarse)?.mean;
    let grass = flip(&all, &bare)?.mean;
    eprintln!(
        "measured: triangles {all_triangles} with every shell, {lod_triangles} with the level of detail; FLIP against every shell: level of detail {change:.4}, 8 pixels {coarse_change:.4}, bare ground {grass:.4}"
    );
    assert!(
        lod_triangles * 4 < all_triangles,
        "{lod_triangles} of {all_triangles} triangles"
    );
    // The level of detail changes a small part of what the shells add to the ground, less
    // than a coarser level does (which shows the comparison sees thinned shells).
    assert!(change < 0.1 * grass, "FLIP {change} vs bare ground {grass}");
    assert!(
        change < coarse_change,
        "FLIP {change} vs 8 pixels {coarse_change}"
    );
    Ok(())
}
