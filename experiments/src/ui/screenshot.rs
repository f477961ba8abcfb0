//! The screenshot button: every pane re-rendered at full resolution and saved, with a
//! composite of them all, in a new folder.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use grassbench::glam::Vec3;
use grassbench::target::save_png;

use super::stage::Stage;

/// Saves each pane's image of `frame` (seen from `camera`) at full resolution and their
/// composite into a new folder under `root`; returns the folder.
pub fn save(
    stage: &mut Stage,
    frame: u64,
    camera: Option<(Vec3, Vec3)>,
    root: &Path,
) -> anyhow::Result<PathBuf> {
    let stamp = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let dir = root.join(format!("{}-f{frame:05}-{stamp}", stage.scene_name));
    stage.invalidate();
    stage.render(frame, camera, true, |_, _| Some(false), |_, _| {}, || None);
    let mut images = Vec::new();
    for (k, pane) in stage.panes.iter().enumerate() {
        let img = pane.last_image.clone().with_context(|| {
            format!(
                "pane {} has no image: {}",
                k + 1,
                pane.error.clone().unwrap_or_default()
            )
        })?;
        save_png(
            &img,
            &dir.join(format!("pane{}_{}.png", k + 1, pane.technique_id)),
        )?;
        images.push(img);
    }
    save_png(&composite(&images), &dir.join("composite.png"))?;
    Ok(dir)
}

/// Pane images tiled as in the window (2 columns when more than one).
fn composite(images: &[image::RgbaImage]) -> image::RgbaImage {
    let cols = if images.len() == 1 { 1 } else { 2 };
    let rows = images.len().div_ceil(cols) as u32;
    let (w, h) = images.first().map_or((1, 1), |i| i.dimensions());
    let mut out = image::RgbaImage::new(w * cols as u32, h * rows);
    for (k, img) in images.iter().enumerate() {
        let (x, y) = ((k % cols) as u32 * w, (k / cols) as u32 * h);
        image::imageops::overlay(&mut out, img, i64::from(x), i64::from(y));
    }
    out
}
