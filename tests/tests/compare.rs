//! The image-difference suite over every registered technique and canonical scene: snapshot
//! regression, LOD fidelity and cross-technique agreement with the reference at reduced scales
//! (temporal change, popping and blur, is `tests/tests/temporal.rs`). A new technique is covered by these loops without new test
//! code; its thresholds default to the loose ceilings of `Thresholds::default`, and tighter
//! ones are listed in `thresholds()` with the measurement they came from.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use grassbench::compare;
use grassbench::runner::Harness;
use grassbench::technique::{NoGrass, TechniqueEntry};
use grassbench_tests::{TEST_SIZE, check_snapshot_flip, gpu, scene};

/// The canonical scenes, at a quarter of their blades (tests run on a software rasteriser).
const SCENES: [&str; 3] = ["meadow", "football_field", "prairie_flyover"];
const DENSITY: f32 = 0.25;
const FRAME: u64 = 30;

/// Per-technique limits; every number says where it came from.
#[derive(Clone, Copy, Debug)]
struct Thresholds {
    /// Mean FLIP against the committed snapshot. On lavapipe the same build renders the same
    /// bytes (measured 0.0); the margin is for other drivers' rasterisation of thin blades,
    /// which could not be measured here.
    snapshot_mean: f32,
    /// 95th-percentile FLIP against the snapshot (same reasoning; a moved blade edge flips a
    /// few pixels to ~0.5 without moving the mean).
    snapshot_p95: f32,
    /// Mean FLIP of the default rendering against the technique's finest representation.
    lod_flip: f64,
    /// Mean FLIP against the reference after 16x downsampling (colour and coverage agree).
    cross_flip_sixteenth: f64,
    /// Mean difference of grass coverage per screen tile against the reference.
    cross_coverage: f64,
}

impl Default for Thresholds {
    /// Ceilings for a technique nobody has measured yet: they catch a broken technique (blank
    /// image: FLIP 1/16 ≈ 0.5, coverage error ≈ 0.5), not a mediocre one. Measure and list it.
    fn default() -> Self {
        Self {
            snapshot_mean: 0.02,
            snapshot_p95: 0.25,
            lod_flip: 0.35,
            cross_flip_sixteenth: 0.3,
            cross_coverage: 0.3,
        }
    }
}

fn thresholds(id: &str) -> Thresholds {
    match id {
        // The reference's finest representation is its default: identical images (measured
        // FLIP 0.0 on all three scenes), and its own change divided by itself is 1.
        "reference" => Thresholds {
            lod_flip: 1e-6,
            ..Default::default()
        },
        // The limits below sit about 25 % above the worst of the three scenes as measured on
        // lavapipe at 320x180 and a quarter of the blades (`cargo test --release --test compare
        // -- --nocapture` prints every "measured:" line); the margin is for other rasterisers.
        //
        // zhang (part 2: billboards beyond the 3 x 3 near grids, sorted and blended, fades;
        // since issue 19 the scene's blades, the reference's, and the trees and stones drawn
        // by the core for everyone): LOD FLIP against `lod = false` 0.029 / 0.010 / 0.030
        // (meadow / football field / prairie). Against the reference FLIP 1/16 0.047 / 0.006 /
        // 0.010 and coverage per tile 0.029 / 0.002 / 0.014. (Before issue 19, on the thesis'
        // 32 x 32 lattice, 41 of the meadow's 90 blades/m², with zhang alone drawing the
        // prairie's trees: LOD 0.039 / 0.022 / 0.036, FLIP 1/16 0.055 / 0.012 / 0.016,
        // coverage 0.116 / 0.016 / 0.019; part 1, single plants everywhere: 0.053 / 0.011 /
        // 0.015 and 0.088 / 0.024 / 0.019.) (Temporal figures: `tests/tests/temporal.rs`.)
        "zhang" => Thresholds {
            lod_flip: 0.037,
            cross_flip_sixteenth: 0.059,
            cross_coverage: 0.036,
            ..Default::default()
        },
        // boulanger, since issue 19 (the patch holds the scenes' density: at a quarter of it 6,
        // 3 and 1 blades a patch on sides of 0.516, 0.548 and 0.535 m, where the square patches
        // before held 4, 4 and 1 on 0.5 m): LOD FLIP 0.123 / 0.015 / 0.095, FLIP 1/16 0.072 /
        // 0.005 / 0.043, coverage per tile 0.194 / 0.008 / 0.093; the limits below, set before
        // it, still hold (the meadow's LOD FLIP now 14 % under its limit rather than 25 %).
        // Before issue 19 (issue 9: vertical BTF slices, shadow mask, occlusion map, sheared
        // slices, ground shadows): LOD FLIP 0.115 / 0.021 / 0.106 (before the ground shadows
        // 0.105 / 0.017 / 0.074: the finest variant's ground is shadowed by blades, the
        // default's mostly by slices); FLIP 1/16 0.071 / 0.005 / 0.046, coverage per tile 0.199 / 0.008 / 0.141
        // (without ground shadows 0.087 / 0.006 / 0.025 and 0.161 / 0.008 / 0.055: the shadows
        // darken ground the reference leaves lit, which the coverage classifier partly counts
        // as grass; at these scenes' own sparse densities a patch holds a handful of blades, so
        // the slices change little; the flyover sees the field from above, where only the
        // horizontal slice shows); popping 0.59 (dolly), 0.52 (pan), before the ground shadows
        // 0.45 / 0.42, part 1 0.42 / 0.34 (the pan changes no level of detail yet rose as
        // much: shadowed ground has more contrast, so the same motion changes more pixels).
        "boulanger" => Thresholds {
            lod_flip: 0.14,
            cross_flip_sixteenth: 0.11,
            cross_coverage: 0.25,
            ..Default::default()
        },
        // bakay (issue 19: the texture holds the scene's density, no longer 9 times it): LOD
        // FLIP 0.047 / 0.005 / 0.022 (16 shells on the custom mip chain against its finest: 64
        // shells on the base level; at 9 times the density 0.157 / 0.024 / 0.091); FLIP 1/16
        // 0.051 / 0.006 / 0.023 (before 0.043 / 0.004 / 0.015), coverage per tile 0.195 /
        // 0.008 / 0.056 (before 0.089 / 0.007 / 0.032: shells show the scene's blades only
        // where they cut them, so the walker's grazing view of the meadow shows much less grass
        // than the reference's blades, see the crate's essay); popping 1.23 (dolly), 1.21
        // (pan), measured before issue 19.
        "bakay" => Thresholds {
            lod_flip: 0.06,
            cross_flip_sixteenth: 0.06,
            cross_coverage: 0.245,
            ..Default::default()
        },
        // perbet (scene density, medium preset's levels): LOD FLIP 0.041 / 0.007 / 0.028
        // (strips and 2D textures against 3D blades everywhere); FLIP 1/16 0.046 / 0.007 /
        // 0.018, coverage per tile 0.052 / 0.008 / 0.051; popping 0.56 (dolly; 0.61 without
        // transitions), 0.57 (pan; the same without transitions: levels follow position).
        "perbet" => Thresholds {
            lod_flip: 0.055,
            cross_flip_sixteenth: 0.06,
            cross_coverage: 0.07,
            ..Default::default()
        },
        // jahrmann (GPU culling; levels per 4 m tile, the far level from 15 m keeping one blade
        // in four, widened 4x, blended over 5 m; thinned as (40 m / d)² beyond 40 m): LOD FLIP
        // 0.020 / 0.008 / 0.032 against its finest (culling and levels off); FLIP 1/16 0.044 /
        // 0.004 / 0.013, coverage per tile 0.015 / 0.002 / 0.019 (the reference's blades drawn
        // by another blade model; distance culling thins the prairie's far field; before the
        // thinning 0.020 / 0.008 / 0.031, 0.044 / 0.005 / 0.013, 0.015 / 0.002 / 0.017).
        "jahrmann" => Thresholds {
            lod_flip: 0.038,
            cross_flip_sixteenth: 0.055,
            cross_coverage: 0.022,
            ..Default::default()
        },
        _ => Thresholds::default(),
    }
}

fn entries() -> &'static [TechniqueEntry] {
    grassbench_cli::registry::TECHNIQUES
}

#[test]
fn snapshots_and_lod_fidelity_of_every_technique_and_scene() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let mut failures = Vec::new();
    for name in SCENES {
        let scene = scene(name, DENSITY)?;
        for entry in entries() {
            let id = entry.info.id;
            let t = thresholds(id);
            let image =
                compare::render(&gpu, &scene, entry, &toml::Table::new(), FRAME, TEST_SIZE)?;
            if let Err(e) = check_snapshot_flip(
                &format!("{id}_{name}"),
                &image,
                t.snapshot_mean,
                t.snapshot_p95,
            ) {
                failures.push(format!("{e:#}"));
            }
            let lod =
                compare::lod_fidelity(&gpu, &scene, entry, &toml::Table::new(), FRAME, TEST_SIZE)?;
            eprintln!(
                "measured: {id} on {name}: LOD fidelity FLIP mean {:.4} p95 {:.4}",
                lod.scores.flip_mean, lod.scores.flip_p95
            );
            if lod.scores.flip_mean > t.lod_flip {
                failures.push(format!(
                    "{id} on {name}: LOD fidelity FLIP {:.4} > {}",
                    lod.scores.flip_mean, t.lod_flip
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

#[test]
fn every_technique_agrees_with_the_reference_at_reduced_scale() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let reference = grassbench_cli::registry::find("reference")?;
    let mut failures = Vec::new();
    for name in SCENES {
        let scene = scene(name, DENSITY)?;
        let background = {
            let mut h = Harness::new(&gpu, scene.clone(), TEST_SIZE, false)?;
            compare::render_in(&mut h, &mut NoGrass, FRAME)?
        };
        let mut images = vec![(
            "reference".to_owned(),
            compare::render(
                &gpu,
                &scene,
                reference,
                &toml::Table::new(),
                FRAME,
                TEST_SIZE,
            )?,
        )];
        for entry in entries().iter().filter(|e| e.info.id != "reference") {
            images.push((
                entry.info.id.to_owned(),
                compare::render(&gpu, &scene, entry, &toml::Table::new(), FRAME, TEST_SIZE)?,
            ));
        }
        // Sanity of the metric itself: the reference against itself scores zero everywhere.
        let same = compare::cross_compare(&[images[0].clone(), images[0].clone()], &background)?;
        assert_eq!(
            (
                same[0].flip_full,
                same[0].coverage_tile_error,
                same[0].silhouette_error
            ),
            (0.0, 0.0, 0.0)
        );
        for pair in compare::cross_compare(&images, &background)?
            .into_iter()
            .filter(|p| p.a == "reference")
        {
            let t = thresholds(&pair.b);
            eprintln!(
                "measured: {} on {name}: FLIP full {:.3} 1/4 {:.3} 1/16 {:.3}, colour {:.1}, coverage per tile {:.3}, silhouette {:.3}",
                pair.b,
                pair.flip_full,
                pair.flip_quarter,
                pair.flip_sixteenth,
                pair.color_error_quarter,
                pair.coverage_tile_error,
                pair.silhouette_error
            );
            if pair.flip_sixteenth > t.cross_flip_sixteenth
                || pair.coverage_tile_error > t.cross_coverage
            {
                failures.push(format!(
                    "{} on {name}: FLIP at 1/16 {:.3} (limit {}), coverage per tile {:.3} (limit {})",
                    pair.b, pair.flip_sixteenth, t.cross_flip_sixteenth, pair.coverage_tile_error, t.cross_coverage
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}
