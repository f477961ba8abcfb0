//! One pane: a technique drawn into its own view of the shared world, and its live figures.
//! The scene, its GPU resources and the wind are the world's ([`super::stage::Stage`]); a pane
//! holds only what differs between panes: the technique, its target, timer and debug view.

use std::collections::VecDeque;

use grassbench::glam::Vec3;
use grassbench::runner::{FrameRecord, View, World};
use grassbench::target::Size;
use grassbench::technique::GrassTechnique;

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
    /// Target, timer, debug view and camera of this pane.
    pub view: View,
    /// The technique, or `None` when creating it failed.
    pub technique: Option<Box<dyn GrassTechnique>>,
    /// The last error, shown in the pane instead of a picture.
    pub error: Option<String>,
    /// Figures of the last frames.
    pub history: VecDeque<FrameRecord>,
    /// The last image read back (for screenshots and the difference view).
    pub last_image: Option<image::RgbaImage>,
    /// The image read back before `last_image` (the difference view's temporal mode compares
    /// the change between the two with another pane's).
    pub previous_image: Option<image::RgbaImage>,
    /// Frame last rendered.
    pub shown_frame: Option<u64>,
    /// Size at full resolution.
    pub full_size: Size,
    /// Rendering at reduced resolution (camera moving, frames slow).
    pub preview: bool,
    /// The window's number of the last parameter edit applied (0: none).
    pub edit: u64,
    dirty: bool,
}

impl Pane {
    /// A pane that will show `technique_id` on `world` (created by [`Pane::create`]).
    pub fn new(
        world: &World<'_>,
        technique_id: &str,
        size: Size,
        msaa: bool,
    ) -> anyhow::Result<Self> {
        Ok(Self {
            technique_id: technique_id.to_owned(),
            overrides: toml::Table::new(),
            view: View::new(world.gpu, size, msaa)?,
            technique: None,
            error: None,
            history: VecDeque::with_capacity(HISTORY),
            last_image: None,
            previous_image: None,
            shown_frame: None,
            full_size: size,
            preview: false,
            edit: 0,
            dirty: true,
        })
    }

    /// Rebuilds the technique with the current overrides, not yet caught up (the stage catches
    /// every rebuilt pane up in step, see [`super::stage::Stage::recreate`]).
    pub fn create(&mut self, world: &World<'_>) {
        self.technique = None;
        let result = registry::find(&self.technique_id)
            .map_err(anyhow::Error::from)
            .and_then(|entry| Ok(world.create(&self.view, entry, &self.overrides)?));
        match result {
            Ok(t) => {
                self.technique = Some(t);
                self.error = None;
            }
            Err(e) => self.error = Some(format!("{e:#}")),
        }
        self.dirty = true;
    }

    /// Runs frame `frame` of the technique without showing it (update only; techniques with
    /// GPU state also draw it).
    pub fn catch_up(&mut self, world: &mut World<'_>, frame: u64) -> grassbench::Result<()> {
        match self.technique.as_mut() {
            Some(technique) => world.catch_up(&mut self.view, technique.as_mut(), frame, frame + 1),
            None => Ok(()),
        }
    }

    /// Marks the pane for re-rendering (camera or settings changed).
    pub fn invalidate(&mut self) {
        self.dirty = true;
    }

    /// Gets the pane ready to draw `frame` if anything changed: the target sized for `preview`,
    /// the camera set. Returns the first frame it must catch up from (`frame` when none is
    /// skipped), or `None` when it need not draw.
    pub fn plan(
        &mut self,
        world: &World<'_>,
        frame: u64,
        camera: Option<(Vec3, Vec3)>,
        capture: bool,
        preview: bool,
    ) -> Option<u64> {
        let technique = self.technique.as_mut()?;
        if !self.dirty
            && self.shown_frame == Some(frame)
            && preview == self.preview
            && (!capture || self.last_image.is_some())
        {
            return None;
        }
        let size = if preview {
            Size {
                width: (self.full_size.width / 2).max(1),
                height: (self.full_size.height / 2).max(1),
            }
        } else {
            self.full_size
        };
        if let Err(e) = self.view.resize(world.gpu, technique.as_mut(), size) {
            self.error = Some(e.to_string());
            return None;
        }
        self.preview = preview;
        self.view.camera_override = camera;
        // Frames skipped by a fast time scale are still simulated (update only).
        Some(
            self.shown_frame
                .filter(|s| *s < frame)
                .map_or(frame, |s| s + 1),
        )
    }

    /// Renders `frame` of the world; reads the image back when `capture`. Returns whether it
    /// drew (not when the technique is missing or failed now).
    pub fn draw(&mut self, world: &mut World<'_>, frame: u64, capture: bool) -> bool {
        let Some(technique) = self.technique.as_mut() else {
            return false;
        };
        match world.frame(&mut self.view, technique.as_mut(), frame, capture) {
            Ok(out) => {
                if self.history.len() == HISTORY {
                    self.history.pop_front();
                }
                self.history.push_back(out.record);
                if out.image.is_some() {
                    self.previous_image = self.last_image.take();
                    self.last_image = out.image;
                } else if !capture {
                    self.last_image = None;
                    self.previous_image = None;
                }
                self.shown_frame = Some(frame);
                self.error = None;
                self.dirty = false;
                true
            }
            Err(e) => {
                self.error = Some(e.to_string());
                // A failed technique stays failed until changed: no retry every frame.
                self.technique = None;
                false
            }
        }
    }
}
