//! What the window holds of a pane: the technique's name, parameters and error as the worker
//! ([`super::worker`]) last reported them, the latest finished frame's image (in an egui
//! texture) and its figures. The technique itself and its target live on the worker.

use std::collections::VecDeque;

use eframe::egui;
use grassbench::runner::FrameRecord;
use grassbench::target::Size;
use grassbench::technique::TechniqueInfo;

use super::pane::HISTORY;
use super::worker::PaneSummary;

/// A pane as the window shows it.
pub struct PaneDisplay {
    /// Technique id shown.
    pub technique_id: String,
    /// Who the technique is, once created.
    pub info: Option<TechniqueInfo>,
    /// Its parameters in use (edited in the panel, then sent to the worker).
    pub params: toml::Table,
    /// Debug view shown (0 = none).
    pub debug_view: u32,
    /// The last error, shown in the pane instead of a picture.
    pub error: Option<String>,
    /// Whether the technique exists (not failed).
    pub alive: bool,
    /// Figures of the last frames.
    pub history: VecDeque<FrameRecord>,
    /// The latest finished frame's image (screenshots, the difference view).
    pub last_image: Option<image::RgbaImage>,
    /// The image before it (the difference view's temporal mode).
    pub previous_image: Option<image::RgbaImage>,
    /// Frame of the latest finished image.
    pub shown_frame: Option<u64>,
    /// Size at full resolution.
    pub full_size: Size,
    /// Frames received so far (the difference view recomputes when it changes).
    pub received: u64,
    /// The number of the last parameter edit sent: older summaries' parameters are stale.
    pub edit: u64,
    /// The latest image is at half resolution (camera moving, frames slow).
    pub preview: bool,
    texture: Option<egui::TextureHandle>,
}

impl PaneDisplay {
    /// A pane of `size` showing what `summary` says, with no frame yet.
    pub fn new(summary: PaneSummary, size: Size) -> Self {
        let mut pane = Self {
            technique_id: String::new(),
            info: None,
            params: toml::Table::new(),
            debug_view: 0,
            error: None,
            alive: false,
            history: VecDeque::with_capacity(HISTORY),
            last_image: None,
            previous_image: None,
            shown_frame: None,
            full_size: size,
            received: 0,
            edit: 0,
            preview: false,
            texture: None,
        };
        pane.update(summary);
        pane
    }

    /// Takes the worker's new summary; a new technique starts with no figures.
    pub fn update(&mut self, summary: PaneSummary) {
        if summary.technique_id != self.technique_id {
            self.history.clear();
            self.debug_view = 0;
        }
        self.technique_id = summary.technique_id;
        self.info = summary.info;
        // While an edit is on its way, the panel keeps showing it.
        if summary.edit >= self.edit {
            self.params = summary.params;
        }
        self.error = summary.error;
        self.alive = summary.alive;
    }

    /// Shows parameter edit number `edit`, `overrides`, until the worker reports it applied
    /// (empty overrides, a reset, show the defaults once it reports them).
    pub fn edited(&mut self, overrides: &toml::Table, edit: u64) {
        self.edit = edit;
        if !overrides.is_empty() {
            self.params = overrides.clone();
        }
    }

    /// Takes a finished frame: its figures, its image (copied into the texture).
    pub fn finished(
        &mut self,
        ctx: &egui::Context,
        frame: u64,
        record: FrameRecord,
        image: image::RgbaImage,
        preview: bool,
    ) {
        if self.history.len() == HISTORY {
            self.history.pop_front();
        }
        self.history.push_back(record);
        // Opaque: the picture is the frame, whatever alpha the target holds.
        let rgb: Vec<u8> = image
            .pixels()
            .flat_map(|p| [p.0[0], p.0[1], p.0[2]])
            .collect();
        let color =
            egui::ColorImage::from_rgb([image.width() as usize, image.height() as usize], &rgb);
        match &mut self.texture {
            Some(t) => t.set(color, egui::TextureOptions::LINEAR),
            None => {
                self.texture = Some(ctx.load_texture("pane", color, egui::TextureOptions::LINEAR));
            }
        }
        self.previous_image = self.last_image.replace(image);
        self.shown_frame = Some(frame);
        self.preview = preview;
        self.received += 1;
    }

    /// The texture of the latest finished frame, if any.
    pub fn texture(&self) -> Option<egui::TextureId> {
        self.texture.as_ref().map(|t| t.id())
    }

    /// Whether the pane shows `frame` already, or never will (failed).
    pub fn caught_up(&self, frame: u64) -> bool {
        !self.alive || self.shown_frame == Some(frame)
    }
}
