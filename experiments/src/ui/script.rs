//! Scripted mode (`--frames N --screenshot FILE`): play N frames, save the window, every pane's
//! image and the pane layout, exit. CI runs it under Xvfb and checks each pane of the window.
//! What the user would do with the mouse and keys (drag the wipe view's divider, flip it) the
//! script does by feeding egui the same input events, one group per window frame
//! ([`Script::feed`]), so the window's own handling of them is what is tested.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use anyhow::Context as _;
use eframe::egui;
use grassbench::target::save_png;
use serde::{Deserialize, Serialize};

use super::display::PaneDisplay;

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
    /// The wipe view, when on.
    #[serde(default)]
    pub wipe: Option<WipeLayout>,
    /// Wall time between successive window frames while the script played, ms.
    #[serde(default)]
    pub window_frame_ms: Vec<f64>,
    /// Each pane's GPU wall time of every frame the window received, ms.
    #[serde(default)]
    pub pane_gpu_wall_ms: Vec<Vec<f64>>,
}

/// The wipe view in a window screenshot.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
pub struct WipeLayout {
    /// Pane shown left of the divider (0-based).
    pub left: usize,
    /// Pane shown right of the divider.
    pub right: usize,
    /// The divider's position across the picture, 0 to 1.
    pub split: f32,
    /// Whether the sides were swapped.
    pub flipped: bool,
    /// `[x, y, width, height]` of the picture, in physical pixels.
    pub rect: [u32; 4],
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
    /// Input still to feed egui, one group per window frame.
    input: VecDeque<Vec<egui::Event>>,
}

impl Script {
    /// A script playing `frames` frames, then saving the window to `screenshot`.
    pub fn new(frames: u64, screenshot: PathBuf) -> Self {
        Self {
            frames,
            screenshot,
            requested: false,
            slot: Arc::new(Mutex::new(None)),
            input: VecDeque::new(),
        }
    }

    /// Queues a drag with the primary button from `from` to `to` (points), over a few frames.
    pub fn drag(&mut self, from: egui::Pos2, to: egui::Pos2) {
        let button = |pos, pressed| egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        };
        self.input.push_back(vec![egui::Event::PointerMoved(from)]);
        self.input.push_back(vec![button(from, true)]);
        for t in [0.25, 0.5, 0.75, 1.0] {
            self.input
                .push_back(vec![egui::Event::PointerMoved(from.lerp(to, t))]);
        }
        self.input.push_back(vec![button(to, false)]);
    }

    /// Queues a press and release of `key`.
    pub fn key(&mut self, key: egui::Key) {
        let event = |pressed| egui::Event::Key {
            key,
            physical_key: None,
            pressed,
            repeat: false,
            modifiers: egui::Modifiers::NONE,
        };
        self.input.push_back(vec![event(true)]);
        self.input.push_back(vec![event(false)]);
    }

    /// Feeds this frame's queued input to egui.
    pub fn feed(&mut self, raw: &mut egui::RawInput) {
        if let Some(events) = self.input.pop_front() {
            raw.events.extend(events);
        }
    }

    /// Whether queued input remains.
    pub fn feeding(&self) -> bool {
        !self.input.is_empty()
    }

    /// Once every pane shown shows the last frame (`ready`) and the queued input is fed: asks
    /// for the window's screenshot, then saves it with the layout `layout(pixels_per_point)`
    /// and every pane's image. Returns `None` while waiting, then the outcome (the window is
    /// then to be closed).
    pub fn poll(
        &mut self,
        ctx: &egui::Context,
        panes: &[PaneDisplay],
        ready: bool,
        frame: u64,
        layout: impl FnOnce(f32) -> Layout,
    ) -> Option<anyhow::Result<()>> {
        if frame < self.frames || !ready || self.feeding() {
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
            for (k, pane) in panes.iter().enumerate() {
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
