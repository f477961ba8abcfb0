//! The wipe section: which two panes share one picture, where the divider stands, and which
//! side each is on.

use eframe::egui;

use crate::ui::wipe::{FLIP_KEY, Wipe};

/// Draws the wipe settings for `panes` panes.
pub fn ui(ui: &mut egui::Ui, wipe: &mut Wipe, panes: usize) {
    let key = FLIP_KEY.name();
    egui::CollapsingHeader::new("wipe view")
        .default_open(wipe.enabled)
        .show(ui, |ui| {
            ui.add_enabled(
                panes >= 2,
                egui::Checkbox::new(&mut wipe.enabled, "two panes in one picture"),
            );
            for (label, slot) in [("left", &mut wipe.a), ("right", &mut wipe.b)] {
                egui::ComboBox::from_label(label)
                    .selected_text(format!("pane {}", *slot + 1))
                    .show_ui(ui, |ui| {
                        for k in 0..panes {
                            ui.selectable_value(slot, k, format!("pane {}", k + 1));
                        }
                    });
            }
            ui.add(egui::Slider::new(&mut wipe.split, 0.0..=1.0).text("divider"));
            ui.checkbox(&mut wipe.flipped, format!("sides swapped ({key} key)"));
            ui.small(format!(
                "drag the divider; {key} swaps the sides, so the same pixels flip \
                 between the two techniques"
            ));
        });
}
