//! Scripted mode (`--frames N --screenshot FILE`): play N frames, save the window, every pane's
//! image and the pane layout, exit. CI runs it under Xvfb and checks each pane of the window.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

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
    /// The direction towards the sun in the first pane's scene (moved by the sliders or
    /// `--sun`).
    #[serde(default)]
    pub sun: Option<[f32; 3]>,
    /// The point light's position in the first pane's scene, if one is on (the panel's
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
}
