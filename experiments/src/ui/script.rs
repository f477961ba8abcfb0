//! Scripted mode (`--frames N --screenshot FILE`): play N frames, save the window, every pane's
//! image and the pane layout, exit. CI runs it under Xvfb and checks each pane of the window.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use anyhow::Context as _;
use eframe::egui;
use grassbench::target::save_png;
use serde::{Deserialize, Serialize};

use super::stage::Stage;

/// Where each pane lies in the window screenshot, in physical pixels.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
pub struct Layout {
    /// Technique of each pane.
    pub techniques: Vec<String>,
    /// `[x, y, width, height]` of each pane's picture.
    pub rects: Vec<[u32; 4]>,
    /// Frame shown.
    pub frame: u64,
    /// The wind settings in use (with any primitives placed by clicks or `--spawn`).
    #[serde(default)]
    pub wind: toml::Table,
    /// The direction towards the sun in the scene every pane shows (moved by the sliders or
    /// `--sun`).
    #[serde(default)]
    pub sun: Option<[f32; 3]>,
    /// The point light's position in the scene every pane shows, if one is on (the panel's
    /// controls or `--point-light`).
    #[serde(default)]
    pub point_light: Option<[f32; 3]>,
}

impl Layout {
    /// `<screenshot>.layout.toml` beside a screenshot.
    pub fn path_for(screenshot: &Path) -> PathBuf {
        screenshot.with_extension("layout.toml")
    }
}

/// Progress of a script.
pub struct Script {
    /// Frames to play before the screenshot.
    pub frames: u64,
    /// Window screenshot file.
    pub screenshot: PathBuf,
    /// Screenshot requested, waiting for it.
    pub requested: bool,
    /// Where the screenshot arrives.
    slot: Arc<Mutex<Option<Arc<egui::ColorImage>>>>,
}

impl Script {
    /// A script playing `frames` frames, then saving the window to `screenshot`.
    pub fn new(frames: u64, screenshot: PathBuf) -> Self {
        Self {
            frames,
            screenshot,
            requested: false,
            slot: Arc::new(Mutex::new(None)),
        }
    }

    /// Once every pane shows the last frame: asks for the window's screenshot, then saves it
    /// with the layout `layout(pixels_per_point)` and every pane's image. Returns `None` while
    /// waiting, then the outcome (the window is then to be closed).
    pub fn poll(
        &mut self,
        ctx: &egui::Context,
        stage: &Stage,
        frame: u64,
        layout: impl FnOnce(f32) -> Layout,
    ) -> Option<anyhow::Result<()>> {
        if frame < self.frames {
            return None;
        }
        let ready = stage
            .panes
            .iter()
            .all(|p| p.shown_frame == Some(self.frames) || p.technique.is_none());
        if !ready {
            return None;
        }
        if !self.requested {
            self.requested = true;
            let slot = self.slot.clone();
            let ctx2 = ctx.clone();
            ctx.request_screenshot(move |img| {
                if let Ok(mut s) = slot.lock() {
                    *s = Some(img);
                }
                ctx2.request_repaint();
            });
            return None;
        }
        let img = self.slot.lock().ok().and_then(|mut s| s.take())?;
        let path = &self.screenshot;
        Some((|| -> anyhow::Result<()> {
            let [w, h] = img.size;
            let rgba: Vec<u8> = img.pixels.iter().flat_map(|c| c.to_array()).collect();
            let window =
                image::RgbaImage::from_raw(w as u32, h as u32, rgba).context("screenshot size")?;
            save_png(&window, path)?;
            let layout = layout(ctx.pixels_per_point());
            std::fs::write(Layout::path_for(path), toml::to_string(&layout)?)?;
            for (k, pane) in stage.panes.iter().enumerate() {
                if let Some(img) = &pane.last_image {
                    save_png(img, &path.with_extension(format!("pane{}.png", k + 1)))?;
                }
                if let Some(e) = &pane.error {
                    anyhow::bail!("pane {} ({}) failed: {e}", k + 1, pane.technique_id);
                }
            }
            Ok(())
        })())
    }
}
