//! The scene section: which scene, how many panes, their size, MSAA.

use eframe::egui;

use super::Action;
use crate::scenes;
use crate::ui::stage::Stage;
use grassbench::target::Size;

/// Pane sizes offered (16:9).
const SIZES: &[&str] = &["320x180", "480x270", "640x360", "960x540", "1280x720"];

/// Draws the scene and layout settings of `stage`.
pub fn ui(ui: &mut egui::Ui, stage: &mut Stage, actions: &mut Vec<Action>) {
    let count = stage.panes.len();
    egui::ComboBox::from_label("scene")
        .selected_text(&stage.scene_name)
        .show_ui(ui, |ui| {
            for name in scenes::names() {
                if ui
                    .selectable_label(stage.scene_name == name, name)
                    .clicked()
                    && stage.scene_name != name
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
    let current = stage.size.to_string();
    egui::ComboBox::from_label("pane size")
        .selected_text(&current)
        .show_ui(ui, |ui| {
            for s in SIZES {
                if ui.selectable_label(current == *s, *s).clicked()
                    && current != *s
                    && let Ok(size) = Size::parse(s)
                {
                    stage.size = size;
                    actions.push(Action::Rebuild(count));
                }
            }
        });
    if ui.checkbox(&mut stage.msaa, "4x MSAA").changed() {
        actions.push(Action::Rebuild(count));
    }
}
