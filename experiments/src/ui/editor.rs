//! Widgets generated from parameter tables: every technique's parameters and every wind
//! model's keys are edited the same way, with no per-technique UI code.

use eframe::egui;
use grassbench::params::ParamDoc;

/// Draws one widget per value of `table` (numbers as drag values, booleans as checkboxes,
/// strings as text fields, number arrays as rows of drag values); returns whether anything
/// changed. Keys listed in `skip` are left out.
pub fn edit_table(ui: &mut egui::Ui, table: &mut toml::Table, skip: &[&str]) -> bool {
    edit_described(ui, table, skip, &[])
}

/// [`edit_table`] where each key's name and widget show, on hover, what `docs` says of it (a
/// technique's [`grassbench::technique::TechniqueEntry::describe`]): its description and its
/// valid range or choices, with the unit.
pub fn edit_described(
    ui: &mut egui::Ui,
    table: &mut toml::Table,
    skip: &[&str],
    docs: &[ParamDoc],
) -> bool {
    let mut changed = false;
    egui::Grid::new(ui.next_auto_id())
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            for (key, value) in table.iter_mut() {
                if skip.contains(&key.as_str()) {
                    continue;
                }
                let tip = docs.iter().find(|d| d.key == *key).map(ParamDoc::tooltip);
                let label = ui.label(key);
                let widget = ui.scope(|ui| edit_value(ui, value));
                changed |= widget.inner;
                if let Some(tip) = tip {
                    label.on_hover_text(&tip);
                    widget.response.on_hover_text(tip);
                }
                ui.end_row();
            }
        });
    changed
}

fn edit_value(ui: &mut egui::Ui, value: &mut toml::Value) -> bool {
    match value {
        toml::Value::Float(f) => {
            let speed = (f.abs() * 0.01).max(0.001);
            ui.add(egui::DragValue::new(f).speed(speed).max_decimals(4))
                .changed()
        }
        toml::Value::Integer(i) => ui.add(egui::DragValue::new(i).speed(0.1)).changed(),
        toml::Value::Boolean(b) => ui.checkbox(b, "").changed(),
        toml::Value::String(s) => ui.text_edit_singleline(s).lost_focus(),
        toml::Value::Array(items) => {
            let mut changed = false;
            ui.horizontal(|ui| {
                for item in items.iter_mut() {
                    changed |= edit_value(ui, item);
                }
            });
            changed
        }
        other => {
            ui.label(other.to_string());
            false
        }
    }
}
