//! Headless GPU tests of the `boulanger` technique on a software rasteriser, at small size.
//! Property tests of its CPU parts (LOD shares, stratified patch, mirrors, quadtree culling,
//! density) live in the crate (`cargo test -p grassbench-boulanger`).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use grassbench::metrics::{coverage_mask, downsample, flip, grass_coverage, mean_color};
use grassbench::runner::Harness;
use grassbench::target::Size;
use grassbench::technique::NoGrass;
use grassbench_tests::{TEST_SIZE, gpu, level_blades, render_with, scene};

/// Patch density for tests: at the default 87 800 blades/m² the geometric band of a walker
/// view submits several hundred thousand blades, too slow for a test on lavapipe.
const TEST_BLADES_PER_M2: f64 = 5_000.0;

fn overrides(blades_per_m2: f64) -> toml::Table {
    let mut t = toml::Table::new();
    t.insert("blades_per_m2".into(), blades_per_m2.into());
    t
}

struct Frame {
    image: grassbench::image::RgbaImage,
    background: grassbench::image::RgbaImage,
    lod: Lod,
}

/// Blades per level (Sec. 3.1's three), as boulanger reports them.
#[derive(Debug)]
struct Lod {
    geometry: u64,
    vertical_slices: u64,
    horizontal_slices: u64,
}

fn render(
    scene_name: &str,
    frame: u64,
    size: Size,
    params: &toml::Table,
    debug_view: u32,
) -> anyhow::Result<Frame> {
    let gpu = gpu()?;
    let mut harness = Harness::new(&gpu, scene(scene_name, 1.0)?, size, false)?;
    let background = render_with(&mut harness, &mut NoGrass, frame)?;
    harness.view.debug_view = debug_view;
    let entry = grassbench_cli::registry::find("boulanger")?;
    let mut t = harness.create(entry, params)?;
    let image = render_with(&mut harness, t.as_mut(), frame)?;
    let lod = Lod {
        geometry: level_blades(t.as_ref(), "geometry")?,
        vertical_slices: level_blades(t.as_ref(), "vertical_slices")?,
        horizontal_slices: level_blades(t.as_ref(), "horizontal_slices")?,
    };
    Ok(Frame {
        image,
        background,
        lod,
    })
}

fn bottom_rows(img: &grassbench::image::RgbaImage, rows: u32) -> [f64; 3] {
    mean_color(
        &grassbench::image::imageops::crop_imm(img, 0, img.height() - rows, img.width(), rows)
            .to_image(),
    )
}

#[test]
fn draws_a_believable_field_on_football_field_and_meadow() -> anyhow::Result<()> {
    // (scene, frame, patch density, coverage range). Coverage measured on lavapipe at
    // 320x180: football_field frame 3 0.379 (the pitch seen from the stands is 38 % of the
    // frame; the reference's sparse 40 blades/m² measure 0.035 there, too thin to differ from
    // the ground at this size), meadow frame 30 0.694 (reference 0.469). Less means parts of
    // the field are missing; the pitch cannot cover more than ~0.42, and the meadow's sky is
    // 30 % of the frame, so more means grass where there is none.
    for (name, frame, density, range) in [
        ("football_field", 3, 87_800.0, 0.30..0.46),
        ("meadow", 30, TEST_BLADES_PER_M2, 0.60..0.78),
    ] {
        let f = render(name, frame, TEST_SIZE, &overrides(density), 0)?;
        let coverage = grass_coverage(&f.image, &f.background, 6)?;
        assert!(
            range.contains(&coverage),
            "{name}: grass covers {coverage:.3} of the image"
        );
        let (w, h) = (TEST_SIZE.width as usize, TEST_SIZE.height as usize);
        let mask = coverage_mask(&f.image, &f.background, 6)?;
        assert!(
            mask[..w * h / 8].iter().all(|m| !m),
            "{name}: grass drawn in the sky"
        );
        let c = bottom_rows(&f.image, 20);
        assert!(
            c[1] > c[0] && c[1] > c[2],
            "{name}: foreground is not green: {c:?}"
        );
        // Far grass is drawn by the horizontal slice: hundreds of millions of virtual blades
        // (the whole pitch is 626 M at the default density).
        assert!(f.lod.horizontal_slices > 1_000_000, "{name}: {:?}", f.lod);
        assert!(
            f.lod.geometry <= 100_000,
            "{name}: test too big: {:?}",
            f.lod
        );
        if name == "meadow" {
            assert!(
                f.lod.geometry > 1_000,
                "meadow: no geometry near the walker"
            );
        }
    }
    Ok(())
}

#[test]
fn lod_false_colours_put_geometry_near_vertical_slices_mid_and_the_slice_far() -> anyhow::Result<()>
{
    // Fig. 12's debug view on the walker view of the pitch at 320x180: the bottom rows
    // (2.5-3.5 m away) are geometry (red), the middle of the image (4-30 m) the vertical slices
    // (blue), the band just under the horizon (beyond max_btf = 30 m) the horizontal slice
    // (green). Row means measured on lavapipe: rows 172-179 (65, 72, 143) with red blades over
    // blue, rows 100-119 (40, 66, 159), rows 62-67 (64, 158, 72).
    let f = render(
        "football_field_human",
        3,
        TEST_SIZE,
        &overrides(TEST_BLADES_PER_M2),
        1,
    )?;
    let rows = |y0: u32, n: u32| {
        mean_color(
            &grassbench::image::imageops::crop_imm(&f.image, 0, y0, TEST_SIZE.width, n).to_image(),
        )
    };
    let near = bottom_rows(&f.image, 8);
    assert!(near[0] > 55.0, "near: no geometry (red): {near:?}");
    let mid = rows(100, 20);
    assert!(mid[2] > mid[0] && mid[2] > mid[1], "mid: {mid:?}");
    let far = rows(62, 6);
    assert!(far[1] > far[0] && far[1] > far[2], "far: {far:?}");
    assert!(f.lod.geometry > 0 && f.lod.vertical_slices > 0 && f.lod.horizontal_slices > 0);
    assert!(
        f.lod.horizontal_slices > f.lod.vertical_slices,
        "the horizontal slice holds the far field: {:?}",
        f.lod
    );
    Ok(())
}

#[test]
fn flip_against_the_reference_at_full_and_reduced_scale() -> anyhow::Result<()> {
    // Measured on lavapipe at 320x180 (mean FLIP, full / 1/4 scale), with issue 19's patch
    // holding the density exactly (before it, with issue 9's square patches, in the first
    // brackets; part 1's horizontal slice alone in the second):
    // - at the paper's density (87 800 blades/m² on the pitch; 5 000 on the meadow to keep the
    //   test small): football_field f3 0.259 / 0.285 (0.259 / 0.286; 0.323 / 0.356), meadow
    //   f30 0.326 / 0.333 (0.323 / 0.328; 0.509 / 0.540: the vertical slices stand up where
    //   the flat slice lay, and the shadow mask darkens the dense lawn towards the
    //   reference's). A dense lawn against the reference's sparse blades with ground between
    //   them: the colours differ, so downsampling does not help.
    // - at the scene's own density (40 and 90 blades/m², like for like): football_field
    //   0.018 / 0.011 (0.015 / 0.014), meadow 0.199 / 0.168 (0.216 / 0.205; 0.203 / 0.190: at
    //   90 blades/m² a patch holds 23 blades on 0.506 m, 22 on 0.5 m before, and slices of so
    //   few blades, mip-mapped, are fainter than the reference's blades).
    // Bounds: the measurement plus 0.03-0.05, to catch regressions, not to reward changes.
    let gpu = gpu()?;
    for (name, frame, density, full_max, quarter_max) in [
        ("football_field", 3, 87_800.0, 0.30, 0.33),
        ("meadow", 30, TEST_BLADES_PER_M2, 0.36, 0.37),
        ("football_field", 3, 40.0, 0.04, 0.04),
        ("meadow", 30, 90.0, 0.25, 0.24),
    ] {
        let b = render(name, frame, TEST_SIZE, &overrides(density), 0)?;
        let mut harness = Harness::new(&gpu, scene(name, 1.0)?, TEST_SIZE, false)?;
        let entry = grassbench_cli::registry::find("reference")?;
        let mut r = harness.create(entry, &toml::Table::new())?;
        let reference = render_with(&mut harness, r.as_mut(), frame)?;
        let full = flip(&reference, &b.image)?.mean;
        let quarter = flip(&downsample(&reference, 4), &downsample(&b.image, 4))?.mean;
        eprintln!("{name} at {density} blades/m²: FLIP vs reference {full:.3}, 1/4 {quarter:.3}");
        assert!(full < full_max, "{name}: full-scale FLIP {full:.3}");
        assert!(
            quarter < quarter_max,
            "{name}: quarter-scale FLIP {quarter:.3}"
        );
    }
    Ok(())
}

#[test]
fn alpha_to_coverage_needs_msaa_and_renders_with_it() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let mut params = overrides(TEST_BLADES_PER_M2);
    params.insert("transparency".into(), "alpha_to_coverage".into());
    let entry = grassbench_cli::registry::find("boulanger")?;
    let single = Harness::new(&gpu, scene("football_field_human", 1.0)?, TEST_SIZE, false)?;
    let e = single
        .create(entry, &params)
        .err()
        .expect("refused without MSAA");
    assert!(e.to_string().contains("boulanger.transparency"), "{e}");
    let mut msaa = Harness::new(&gpu, scene("football_field_human", 1.0)?, TEST_SIZE, true)?;
    let background = render_with(&mut msaa, &mut NoGrass, 3)?;
    let mut t = msaa.create(entry, &params)?;
    let image = render_with(&mut msaa, t.as_mut(), 3)?;
    let coverage = grass_coverage(&image, &background, 6)?;
    // Measured 0.664: the ground below the horizon is all grass.
    assert!(coverage > 0.6, "a2c coverage {coverage:.3}");
    // Alpha to coverage writes each fragment's alpha to the target (as low as 98 of 255 under
    // the vertical slices before the read-back made frames opaque: the saved field looked pale
    // over a white page). The frame is an opaque picture.
    let translucent = image.pixels().filter(|p| p.0[3] != u8::MAX).count();
    assert_eq!(translucent, 0, "pixels with alpha below 255");
    Ok(())
}
