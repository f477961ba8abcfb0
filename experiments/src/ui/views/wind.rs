//! The wind section: the model, its settings (edited as a table), and the spawn tool that
//! places Perbet's primitives with a click on a pane.

use anyhow::Context as _;
use eframe::egui;
use grassbench::wind::WindConfig;

use crate::ui::editor::edit_table;
use crate::ui::spawn::SpawnKind;

/// The wind settings as edited in the panel.
pub struct WindSettings {
    /// The scene's `[wind]`, as a table (with any primitives placed by clicks or `--spawn`).
    pub table: toml::Table,
    /// Why the table is not a valid wind, if it is not.
    pub error: Option<String>,
    /// What a click on a pane adds to the wind.
    pub spawn: SpawnKind,
}

impl WindSettings {
    /// The settings of `config`.
    pub fn new(config: &WindConfig) -> anyhow::Result<Self> {
        Ok(Self {
            table: toml::Table::try_from(config).context("wind settings")?,
            error: None,
            spawn: SpawnKind::Off,
        })
    }

    /// The table as a validated wind.
    pub fn config(&self) -> anyhow::Result<WindConfig> {
        let config: WindConfig = toml::Value::Table(self.table.clone())
            .try_into()
            .context("wind settings")?;
        config.validate()?;
        Ok(config)
    }

    /// Draws the section; returns whether the settings changed (to be applied).
    pub fn ui(&mut self, ui: &mut egui::Ui) -> bool {
        let mut changed = false;
        ui.collapsing("wind", |ui| {
            let model = self
                .table
                .get("model")
                .and_then(|v| v.as_str())
                .unwrap_or("calm")
                .to_owned();
            egui::ComboBox::from_label("model")
                .selected_text(&model)
                .show_ui(ui, |ui| {
                    for m in WindConfig::MODELS {
                        if ui.selectable_label(model == *m, *m).clicked()
                            && model != *m
                            && let Some(c) = WindConfig::default_for(m)
                        {
                            self.table = toml::Table::try_from(&c).unwrap_or_default();
                            changed = true;
                        }
                    }
                });
            changed |= edit_table(ui, &mut self.table, &["model"]);
            if let Some(e) = &self.error {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
            }
            ui.label("click a pane to add (Perbet's primitives):");
            ui.horizontal(|ui| {
                for kind in SpawnKind::ALL {
                    ui.radio_value(&mut self.spawn, kind, kind.label());
                }
            });
        });
        changed
    }
}
