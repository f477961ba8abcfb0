//! A pane's section: its technique, debug view and parameters (generated from the
//! technique's parameter table).

use eframe::egui;

use super::Action;
use crate::registry;
use crate::ui::display::PaneDisplay;
use crate::ui::editor::edit_described;

/// Draws the settings of pane `k`.
pub fn ui(ui: &mut egui::Ui, k: usize, pane: &PaneDisplay, actions: &mut Vec<Action>) {
    ui.collapsing(format!("pane {}: {}", k + 1, pane.technique_id), |ui| {
        egui::ComboBox::from_id_salt(("technique", k))
            .selected_text(&pane.technique_id)
            .show_ui(ui, |ui| {
                for e in registry::TECHNIQUES {
                    if ui
                        .selectable_label(pane.technique_id == e.info.id, e.info.name)
                        .clicked()
                    {
                        actions.push(Action::SetTechnique(k, e.info.id));
                    }
                }
            });
        if let Some(info) = pane.info.filter(|_| pane.alive) {
            ui.small(info.paper);
            let mut view = pane.debug_view;
            let name = |v: u32| {
                if v == 0 {
                    "none"
                } else {
                    info.debug_views.get(v as usize - 1).copied().unwrap_or("?")
                }
            };
            egui::ComboBox::from_id_salt(("debug", k))
                .selected_text(format!("debug view: {}", name(view)))
                .show_ui(ui, |ui| {
                    for v in 0..=info.debug_views.len() as u32 {
                        ui.selectable_value(&mut view, v, name(v));
                    }
                });
            if view != pane.debug_view {
                actions.push(Action::DebugView(k, view));
            }
            let mut params = pane.params.clone();
            // Each parameter's description and valid values on hover.
            let docs = registry::find(&pane.technique_id)
                .map(|e| e.describe())
                .unwrap_or_default();
            if edit_described(ui, &mut params, &[], &docs) {
                actions.push(Action::Recreate(k, params));
            }
        }
        if ui.button("reset parameters").clicked() {
            actions.push(Action::Recreate(k, toml::Table::new()));
        }
    });
}
