//! Property tests: no input reachable from the command line makes the parsers panic. Scene and
//! sweep files are mutated byte by byte, map files are random or truncated PNGs, parameter
//! assignments are arbitrary text; every case must end in `Ok` or a clear `Err`.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;

use grassbench::Scene;
use grassbench::sweep::SweepSpec;
use grassbench::terrain::{CoveringSource, MapSource, Terrain, TerrainConfig};
use proptest::prelude::*;

const MEADOW: &str = include_str!("../../experiments/scenes/meadow.toml");
const SWEEP: &str = include_str!("../../experiments/scaling.toml");

/// A mutation: replace, delete or insert at a position with a character that often matters
/// in TOML (digits, signs, quotes, brackets, dots, `=`, newlines, letters, exponent marks).
fn mutate(text: &str, edits: &[(usize, u8, u8)]) -> String {
    const CHARS: &[u8] = b"0123456789-+.eE\"'[]{}=,\n #xnaif_";
    let mut bytes = text.as_bytes().to_vec();
    for &(pos, kind, c) in edits {
        if bytes.is_empty() {
            break;
        }
        let p = pos % bytes.len();
        let c = CHARS[c as usize % CHARS.len()];
        match kind % 3 {
            0 => bytes[p] = c,
            1 => {
                bytes.remove(p);
            }
            _ => bytes.insert(p, c),
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn mutated_scene_files_never_panic(edits in proptest::collection::vec((any::<usize>(), any::<u8>(), any::<u8>()), 1..6)) {
        let text = mutate(MEADOW, &edits);
        if let Err(e) = Scene::from_toml(&text, Path::new("mutated.toml")) {
            let msg = e.to_string();
            prop_assert!(msg.contains("mutated.toml") || msg.contains("invalid parameter"), "message does not name the file or key: {msg}");
        }
    }

    #[test]
    fn mutated_sweep_files_never_panic(edits in proptest::collection::vec((any::<usize>(), any::<u8>(), any::<u8>()), 1..6)) {
        let text = mutate(SWEEP, &edits);
        if let Ok(spec) = SweepSpec::from_toml(&text, Path::new("mutated.toml")) {
            let _ = spec.expand(&["reference"]);
        }
    }

    #[test]
    fn parameter_assignments_never_panic(text in ".{0,40}") {
        if let Ok((k, v)) = grassbench::params::parse_assignment(&text) {
            let mut t = toml::Table::new();
            t.insert(k, v);
            let _ = grassbench::params::resolve::<grassbench_reference::Params>("reference", &t);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn random_and_truncated_pngs_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..256), cut in 0usize..400, w in 1u32..40, h in 1u32..40, sixteen in any::<bool>()) {
        let dir = std::env::temp_dir().join(format!("grassbench-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let config = |name: &str| TerrainConfig {
            size: [10.0, 10.0],
            max_height: 1.0,
            samples_per_metre: 1.0,
            height: MapSource::Png { path: name.into() },
            density: MapSource::one(),
            covering: CoveringSource::Png { path: name.into() },
        };
        // Random bytes behind a PNG signature.
        let mut data = b"\x89PNG\r\n\x1a\n".to_vec();
        data.extend_from_slice(&bytes);
        std::fs::write(dir.join("random.png"), &data).unwrap();
        prop_assert!(Terrain::build(&config("random.png"), 0, &dir).is_err());
        // A valid PNG of any size and depth, truncated anywhere.
        let mut png = Vec::new();
        if sixteen {
            image::ImageBuffer::<image::Luma<u16>, _>::from_pixel(w, h, image::Luma([40000])).write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png).unwrap();
        } else {
            image::GrayImage::from_pixel(w, h, image::Luma([255])).write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png).unwrap();
        }
        let cut = cut.min(png.len());
        std::fs::write(dir.join("cut.png"), &png[..cut]).unwrap();
        let _ = Terrain::build(&config("cut.png"), 0, &dir);
        std::fs::write(dir.join("whole.png"), &png).unwrap();
        let _ = Terrain::build(&config("whole.png"), 0, &dir);
    }
}
