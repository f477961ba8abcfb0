//! The scene section: which scene, how many panes, their size, MSAA.

use eframe::egui;

use super::Action;
use crate::scenes;
use grassbench::target::Size;

/// Pane sizes offered (16:9).
const SIZES: &[&str] = &["320x180", "480x270", "640x360", "960x540", "1280x720"];

/// What the scene section edits.
pub struct Setup {
    /// Built-in scene name (or path) the scene was loaded by.
    pub scene_name: String,
    /// Number of panes.
    pub count: usize,
    /// Size of every pane at full resolution.
    pub size: Size,
    /// 4x MSAA in every pane.
    pub msaa: bool,
}

/// Draws the scene and layout settings `setup`.
pub fn ui(ui: &mut egui::Ui, setup: &mut Setup, actions: &mut Vec<Action>) {
    let count = setup.count;
    egui::ComboBox::from_label("scene")
        .selected_text(&setup.scene_name)
        .show_ui(ui, |ui| {
            for name in scenes::names() {
                if ui
                    .selectable_label(setup.scene_name == name, name)
                    .clicked()
                    && setup.scene_name != name
                {
                    actions.push(Action::LoadScene(name));
                }
            }
        });
    ui.horizontal(|ui| {
        ui.label("panes");
        for n in [1, 2, 4] {
            if ui.selectable_label(count == n, n.to_string()).clicked() && count != n {
                actions.push(Action::Rebuild(n));
            }
        }
    });
    let current = setup.size.to_string();
    egui::ComboBox::from_label("pane size")
        .selected_text(&current)
        .show_ui(ui, |ui| {
            for s in SIZES {
                if ui.selectable_label(current == *s, *s).clicked()
                    && current != *s
                    && let Ok(size) = Size::parse(s)
                {
                    setup.size = size;
                    actions.push(Action::Rebuild(count));
                }
            }
        });
    if ui.checkbox(&mut setup.msaa, "4x MSAA").changed() {
        actions.push(Action::Rebuild(count));
    }
}
