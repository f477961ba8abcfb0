//! One pane: a technique rendered offscreen by its own harness, and its live figures.

use std::collections::VecDeque;

use eframe::{egui, egui_wgpu};
use grassbench::runner::{FrameRecord, Harness};
use grassbench::target::Size;
use grassbench::technique::GrassTechnique;
use grassbench::{GpuContext, Scene};

use crate::registry;

/// Frames of figures kept for the rolling plot.
pub const HISTORY: usize = 120;

/// A switched-in technique simulates this many frames before the current one, so stateful
/// animation (Verlet blades, fluids) is warmed up without replaying the whole session.
pub const CATCH_UP_FRAMES: u64 = 60;

/// A pane of the window.
pub struct Pane {
    /// Technique id shown.
    pub technique_id: String,
    /// Parameter overrides edited in the UI.
    pub overrides: toml::Table,
    /// Scene, target, wind and timer of this pane.
    pub harness: Harness<'static>,
    /// The technique, or `None` when creating it failed.
    pub technique: Option<Box<dyn GrassTechnique>>,
    /// The last error, shown in the pane instead of a picture.
    pub error: Option<String>,
    /// Figures of the last frames.
    pub history: VecDeque<FrameRecord>,
    /// The last image read back (for screenshots and the difference view).
    pub last_image: Option<image::RgbaImage>,
    /// Frame last rendered.
    pub shown_frame: Option<u64>,
    /// Size at full resolution.
    pub full_size: Size,
    /// Rendering at reduced resolution (camera moving, frames slow).
    pub preview: bool,
    texture: Option<egui::TextureId>,
    dirty: bool,
}

impl Pane {
    /// A pane showing `technique_id` on `scene`.
    pub fn new(
        gpu: &'static GpuContext,
        scene: Scene,
        technique_id: &str,
        size: Size,
        msaa: bool,
    ) -> anyhow::Result<Self> {
        let harness = Harness::new(gpu, scene, size, msaa)?;
        let mut pane = Self {
            technique_id: technique_id.to_owned(),
            overrides: toml::Table::new(),
            harness,
            technique: None,
            error: None,
            history: VecDeque::with_capacity(HISTORY),
            last_image: None,
            shown_frame: None,
            full_size: size,
            preview: false,
            texture: None,
            dirty: true,
        };
        pane.recreate(0);
        Ok(pane)
    }

    /// Switches to another technique, keeping camera, time and scene.
    pub fn set_technique(&mut self, id: &str, frame: u64) {
        self.technique_id = id.to_owned();
        self.overrides.clear();
        self.history.clear();
        self.recreate(frame);
    }

    /// Rebuilds the technique with the current overrides and catches it up to `frame`.
    pub fn recreate(&mut self, frame: u64) {
        self.technique = None;
        let result = registry::find(&self.technique_id)
            .map_err(anyhow::Error::from)
            .and_then(|entry| {
                let mut t = self.harness.create(entry, &self.overrides)?;
                self.harness
                    .catch_up(t.as_mut(), frame.saturating_sub(CATCH_UP_FRAMES), frame)?;
                Ok(t)
            });
        match result {
            Ok(t) => {
                self.technique = Some(t);
                self.error = None;
            }
            Err(e) => self.error = Some(format!("{e:#}")),
        }
        self.dirty = true;
    }

    /// Marks the pane for re-rendering (camera or settings changed).
    pub fn invalidate(&mut self) {
        self.dirty = true;
    }

    /// Renders `frame` if anything changed; reads the image back when `capture`.
    pub fn render(
        &mut self,
        frame: u64,
        camera: Option<(grassbench::glam::Vec3, grassbench::glam::Vec3)>,
        capture: bool,
        preview: bool,
    ) {
        let Some(technique) = self.technique.as_mut() else {
            return;
        };
        if !self.dirty
            && self.shown_frame == Some(frame)
            && preview == self.preview
            && (!capture || self.last_image.is_some())
        {
            return;
        }
        let size = if preview {
            Size {
                width: (self.full_size.width / 2).max(1),
                height: (self.full_size.height / 2).max(1),
            }
        } else {
            self.full_size
        };
        if let Err(e) = self.harness.resize(technique.as_mut(), size) {
            self.error = Some(e.to_string());
            return;
        }
        self.preview = preview;
        self.harness.camera_override = camera;
        // Frames skipped by a fast time scale are still simulated (update only).
        if let Some(shown) = self.shown_frame.filter(|s| *s < frame)
            && let Err(e) = self.harness.catch_up(technique.as_mut(), shown + 1, frame)
        {
            self.error = Some(e.to_string());
            return;
        }
        match self.harness.frame(technique.as_mut(), frame, capture) {
            Ok(out) => {
                if self.history.len() == HISTORY {
                    self.history.pop_front();
                }
                self.history.push_back(out.record);
                if out.image.is_some() {
                    self.last_image = out.image;
                } else if !capture {
                    self.last_image = None;
                }
                self.shown_frame = Some(frame);
                self.error = None;
                self.dirty = false;
            }
            Err(e) => {
                self.error = Some(e.to_string());
                // A failed technique stays failed until changed: no retry every frame.
                self.technique = None;
            }
        }
    }

    /// The egui texture showing this pane's target (registered or updated after resizes).
    pub fn texture(&mut self, render_state: &egui_wgpu::RenderState) -> egui::TextureId {
        // egui composites in gamma space: give it the sRGB bytes undecoded.
        let view = &self.harness.target.display_view;
        let mut renderer = render_state.renderer.write();
        match self.texture {
            Some(id) => {
                renderer.update_egui_texture_from_wgpu_texture(
                    &render_state.device,
                    view,
                    eframe::wgpu::FilterMode::Linear,
                    id,
                );
                id
            }
            None => {
                let id = renderer.register_native_texture(
                    &render_state.device,
                    view,
                    eframe::wgpu::FilterMode::Linear,
                );
                self.texture = Some(id);
                id
            }
        }
    }

    /// Frees the egui texture.
    pub fn release(&mut self, render_state: &egui_wgpu::RenderState) {
        if let Some(id) = self.texture.take() {
            render_state.renderer.write().free_texture(&id);
        }
    }
}
