//! Heightmaps, density and covering maps from PNG files: 8- and 16-bit grayscale accepted,
//! everything else refused with a message naming the file and the fix.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::{Path, PathBuf};

use grassbench::glam::Vec2;
use grassbench::terrain::{CoveringSource, MapSource, Terrain, TerrainConfig, covering};

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("grassbench-maps-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn config(height: &str, size: [f32; 2]) -> TerrainConfig {
    TerrainConfig {
        size,
        max_height: 10.0,
        samples_per_metre: 1.0,
        height: MapSource::Png {
            path: height.into(),
        },
        density: MapSource::one(),
        covering: CoveringSource::Grass,
    }
}

fn build(c: &TerrainConfig, base: &Path) -> Result<Terrain, String> {
    Terrain::build(c, 0, base).map_err(|e| e.to_string())
}

#[test]
fn sixteen_bit_heightmap_keeps_its_precision() {
    let d = dir();
    // A ramp along x from 0 to 65535 over 257 pixels: steps of 1/256 m * 10.
    let img = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(257, 129, |x, _| {
        image::Luma([(x * 65535 / 256) as u16])
    });
    img.save(d.join("ramp16.png")).unwrap();
    let t = build(&config("ramp16.png", [256.0, 128.0]), &d).unwrap();
    assert!((t.height_at(Vec2::new(-128.0, 0.0)) - 0.0).abs() < 1e-4);
    assert!((t.height_at(Vec2::new(128.0, 0.0)) - 10.0).abs() < 1e-4);
    assert!((t.height_at(Vec2::new(0.5, 0.0)) - 10.0 * 128.5 / 256.0).abs() < 1e-3);
    let n = t.normal_at(Vec2::new(10.0, 3.0));
    assert!(
        n.x < 0.0 && n.y > 0.9,
        "normal of an upward ramp along +x: {n}"
    );
}

#[test]
fn eight_bit_density_and_covering_maps_load() {
    let d = dir();
    image::GrayImage::from_fn(64, 64, |x, _| image::Luma([if x < 32 { 0 } else { 255 }]))
        .save(d.join("half.png"))
        .unwrap();
    image::GrayImage::from_fn(64, 64, |_, y| {
        image::Luma([if y < 32 {
            covering::NONE
        } else {
            covering::GRASS
        }])
    })
    .save(d.join("cover.png"))
    .unwrap();
    let mut c = config("half.png", [63.0, 63.0]);
    c.height = MapSource::default();
    c.density = MapSource::Png {
        path: "half.png".into(),
    };
    c.covering = CoveringSource::Png {
        path: "cover.png".into(),
    };
    let t = build(&c, &d).unwrap();
    assert_eq!(t.density_at(Vec2::new(-20.0, 0.0)), 0.0);
    assert_eq!(t.density_at(Vec2::new(20.0, 0.0)), 1.0);
    assert_eq!(t.covering_at(Vec2::new(0.0, -20.0)), covering::NONE);
    assert_eq!(t.covering_at(Vec2::new(0.0, 20.0)), covering::GRASS);
}

#[test]
fn bad_maps_are_refused_with_the_fix() {
    let d = dir();
    image::RgbImage::new(16, 16)
        .save(d.join("rgb.png"))
        .unwrap();
    let e = build(&config("rgb.png", [15.0, 15.0]), &d).unwrap_err();
    assert!(e.contains("rgb.png") && e.contains("grayscale"), "{e}");

    image::GrayImage::new(64, 16)
        .save(d.join("wide.png"))
        .unwrap();
    let e = build(&config("wide.png", [50.0, 50.0]), &d).unwrap_err();
    assert!(e.contains("terrain.height") && e.contains("aspect"), "{e}");

    image::GrayImage::new(1, 1)
        .save(d.join("tiny.png"))
        .unwrap();
    let e = build(&config("tiny.png", [50.0, 50.0]), &d).unwrap_err();
    assert!(e.contains("tiny.png") && e.contains("2..="), "{e}");

    std::fs::write(d.join("corrupt.png"), b"\x89PNG\r\n\x1a\nnot really").unwrap();
    let e = build(&config("corrupt.png", [50.0, 50.0]), &d).unwrap_err();
    assert!(e.contains("corrupt.png") && e.contains("PNG"), "{e}");

    let e = build(&config("absent.png", [50.0, 50.0]), &d).unwrap_err();
    assert!(e.contains("absent.png"), "{e}");

    image::GrayImage::from_pixel(8, 8, image::Luma([7]))
        .save(d.join("cover7.png"))
        .unwrap();
    let mut c = config("cover7.png", [7.0, 7.0]);
    c.height = MapSource::default();
    c.covering = CoveringSource::Png {
        path: "cover7.png".into(),
    };
    let e = build(&c, &d).unwrap_err();
    assert!(e.contains("covering ID 7") && e.contains("253"), "{e}");
}
