//! The difference view: its settings in the panel, and its window comparing two panes.

use eframe::egui;

use crate::ui::diff::{DiffMode, DiffView};
use crate::ui::display::PaneDisplay;

/// Draws the difference settings (which panes, which measure) for `panes` panes.
pub fn ui(ui: &mut egui::Ui, diff: &mut DiffView, panes: usize) {
    ui.collapsing("difference view", |ui| {
        ui.checkbox(&mut diff.enabled, "show difference of two panes");
        for (label, slot) in [("pane A", &mut diff.a), ("pane B", &mut diff.b)] {
            egui::ComboBox::from_label(label)
                .selected_text(format!("{}", *slot + 1))
                .show_ui(ui, |ui| {
                    for k in 0..panes {
                        ui.selectable_value(slot, k, format!("{}", k + 1));
                    }
                });
        }
        ui.horizontal(|ui| {
            ui.radio_value(&mut diff.mode, DiffMode::Flip, "FLIP");
            ui.radio_value(&mut diff.mode, DiffMode::Absolute, "absolute x4");
            ui.radio_value(&mut diff.mode, DiffMode::Temporal, "temporal")
                .on_hover_text(
                    "each pane's change since its previous frame, pane B as the reference: \
                     spurious change (A changed, B did not: popping) red, \
                     missing change (B changed, A did not: blur) cyan, x4",
                );
        });
    });
}

/// The difference window: the two panes' last images compared, the mean and the map.
pub fn window(ctx: &egui::Context, diff: &mut DiffView, panes: &[PaneDisplay]) {
    let (a, b) = (diff.a, diff.b);
    // Measured again only when a pane has a new frame or the settings changed: FLIP takes a
    // good part of a second on large panes, and the window must not wait for it every frame.
    let received = |k: usize| panes.get(k).map_or(0, |p| p.received);
    let key = (a, b, diff.mode, received(a), received(b));
    let stale = diff.measured != Some(key);
    diff.measured = Some(key);
    let step = |k: usize| {
        panes
            .get(k)
            .and_then(|p| Some((p.previous_image.as_ref()?, p.last_image.as_ref()?)))
    };
    if stale {
        if diff.mode == DiffMode::Temporal {
            if let (Some(sa), Some(sb)) = (step(a), step(b)) {
                diff.update_temporal(ctx, sa, sb);
            }
        } else if let (Some(ia), Some(ib)) = (
            panes.get(a).and_then(|p| p.last_image.as_ref()),
            panes.get(b).and_then(|p| p.last_image.as_ref()),
        ) {
            diff.update(ctx, ia, ib);
        }
    }
    egui::Window::new("difference")
        .default_width(420.0)
        .show(ctx, |ui| {
            let what = match diff.mode {
                DiffMode::Flip => "mean FLIP",
                DiffMode::Absolute => "mean |Δ| / 255",
                DiffMode::Temporal => "spurious change",
            };
            match (&diff.error, diff.mean) {
                (Some(e), _) => {
                    ui.colored_label(egui::Color32::LIGHT_RED, e);
                }
                (None, Some(s)) if diff.mode == DiffMode::Temporal => {
                    ui.label(format!(
                        "pane {} against pane {} over their last step: {what} {s:.3}, missing change {:.3} (of pane {}'s change)",
                        a + 1,
                        b + 1,
                        diff.missing.unwrap_or(0.0),
                        b + 1
                    ));
                }
                (None, Some(m)) => {
                    let m = if diff.mode == DiffMode::Absolute {
                        m / 255.0
                    } else {
                        m
                    };
                    ui.label(format!("pane {} vs pane {}: {what} = {m:.4}", a + 1, b + 1));
                }
                _ => {
                    ui.label("waiting for both panes…");
                }
            }
            if let Some(t) = &diff.texture {
                let w = ui.available_width();
                let size = t.size_vec2();
                ui.image((t.id(), egui::vec2(w, w * size.y / size.x.max(1.0))));
            }
        });
}
