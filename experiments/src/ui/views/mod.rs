//! The side panel's sections, one small view each, in the manner of egui's demo windows: each
//! draws its section from the state it is given and reports what the user asked for as
//! [`Action`]s, which the window ([`super::app`]) carries out (through the render worker).
//!
//! | file | section |
//! |---|---|
//! | `scene.rs` | scene, number of panes, pane size, MSAA |
//! | `playback.rs` | play, pause, step, restart, time scale |
//! | `camera.rs` | scene path, walker or orbit |
//! | `wind.rs` | wind model and its settings, the spawn tool |
//! | `lights.rs` | the sun and the point light |
//! | `difference.rs` | the difference view: its settings and its window |
//! | `wipe.rs` | the wipe view: which two panes, the divider, flipped or not |
//! | `pane.rs` | one pane: technique, debug view, parameters |

pub mod camera;
pub mod difference;
pub mod lights;
pub mod pane;
pub mod playback;
pub mod scene;
pub mod wind;
pub mod wipe;

use grassbench::scene::PointLight;

/// What a section asks the window to do.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// Show the built-in scene of this name.
    LoadScene(&'static str),
    /// Rebuild the panes, this many (their size or MSAA may have changed too).
    Rebuild(usize),
    /// Back to frame 0.
    Restart,
    /// The wind settings were edited.
    ApplyWind,
    /// Point the sun this way (unit vector towards it).
    SetSun([f32; 3]),
    /// Switch the point light on (with these settings) or off.
    SetPointLight(Option<PointLight>),
    /// Switch pane `.0` to technique `.1`.
    SetTechnique(usize, &'static str),
    /// Rebuild pane `.0`'s technique with parameter overrides `.1` (empty: the defaults).
    Recreate(usize, toml::Table),
    /// Show debug view `.1` (0 = none) in pane `.0`.
    DebugView(usize, u32),
}
