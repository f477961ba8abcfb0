//! Makes saved frames opaque: sets alpha to 255 in every PNG under the folders given whose
//! alpha is not 255 everywhere, colour untouched, written by the harness's own encoder
//! (`grassbench::target::save_png`).
//!
//! Frames saved before the read-back made them opaque (`src/target.rs`) carry the target's
//! alpha channel: zhang's Eq. 10 blending and boulanger's alpha to coverage left values below
//! 255 there, and an image viewer shows the page through them (a pale field). No metric read
//! that channel, so the figures beside those images stand; this mends the images in place, and
//! gives byte for byte what the fixed read-back writes for the same frame.
//!
//! ```sh
//! cargo run --release -p grassbench-cli --example opaque_images -- results/papers results/winds
//! ```

use std::path::{Path, PathBuf};

use anyhow::Context as _;

fn main() -> anyhow::Result<()> {
    let roots: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    anyhow::ensure!(
        !roots.is_empty(),
        "usage: opaque_images FOLDER... (the results folders whose PNGs to make opaque)"
    );
    let mut pngs = Vec::new();
    for root in &roots {
        collect_pngs(root, &mut pngs).with_context(|| format!("listing {}", root.display()))?;
    }
    pngs.sort();
    let mut mended = 0;
    for path in &pngs {
        if make_opaque(path)? {
            eprintln!("{}", path.display());
            mended += 1;
        }
    }
    eprintln!("{mended} of {} PNGs made opaque", pngs.len());
    Ok(())
}

/// Every `.png` under `dir`, recursively.
fn collect_pngs(dir: &Path, out: &mut Vec<PathBuf>) -> anyhow::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.is_dir() {
            collect_pngs(&path, out)?;
        } else if path.extension().is_some_and(|e| e == "png") {
            out.push(path);
        }
    }
    Ok(())
}

/// Rewrites `path` with alpha 255 if any pixel's alpha is below it; returns whether it did.
fn make_opaque(path: &Path) -> anyhow::Result<bool> {
    let mut image = image::open(path)
        .with_context(|| format!("reading {}", path.display()))?
        .to_rgba8();
    let mut changed = false;
    for pixel in image.pixels_mut() {
        if pixel.0[3] != u8::MAX {
            pixel.0[3] = u8::MAX;
            changed = true;
        }
    }
    if changed {
        grassbench::target::save_png(&image, path)
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(changed)
}
