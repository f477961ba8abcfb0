//! What is drawn over each pane: technique name, live figures, a rolling plot of GPU time,
//! and the error when the technique failed. A click on the name folds the figures and the
//! plot away (in every pane) or unfolds them.

use eframe::egui;

use super::display::PaneDisplay;
use super::pane::HISTORY;

/// Technique name, figures (when `figures`, which a click on the name toggles), rolling plot
/// and errors drawn over pane `k`'s picture `pic`.
pub fn draw(ui: &egui::Ui, pane: &PaneDisplay, pic: egui::Rect, k: usize, figures: &mut bool) {
    let painter = ui.painter_at(pic);
    let font = egui::FontId::monospace(11.0);
    let shadow = egui::Color32::from_black_alpha(160);
    let fold = if *figures { "[-]" } else { "[+]" };
    let mut lines = vec![format!("{} {} {fold}", k + 1, pane.technique_id)];
    if let Some(r) = pane.history.back().filter(|_| *figures) {
        lines.push(format!(
            "cpu update {:.2} upload {:.2} encode {:.2} ms",
            r.update_ms, r.upload_ms, r.encode_ms
        ));
        let ts = r
            .gpu_ts_render_ms
            .map_or("-".to_owned(), |v| format!("{v:.1}"));
        lines.push(format!(
            "gpu wall {:.1} ms · timestamps {ts} ms",
            r.gpu_wall_ms
        ));
        let count = |v: Option<u64>| v.map_or("-".to_owned(), |n| n.to_string());
        lines.push(format!(
            "{} drawn + {} represented blades · {} tris · {:.1} MB",
            count(r.blades_drawn),
            count(r.blades_represented),
            r.triangles,
            r.gpu_bytes as f64 / 1e6
        ));
        // GPU-counted work (pipeline statistics), where the adapter counts it.
        if let (Some(vs), Some(fs), Some(overdraw)) =
            (r.vertex_invocations, r.fragment_invocations, r.overdraw)
        {
            let mega = |n: u64| n as f64 / 1e6;
            // Two lines: the geometry, then the fragments (one line overflowed a 480-pixel
            // pane).
            lines.push(format!(
                "work {:.2} M vertices{}{}",
                mega(vs),
                // In how many instances of the technique's draws.
                r.instances
                    .map_or(String::new(), |n| format!(" in {n} instances")),
                r.compute_invocations
                    .filter(|&c| c > 0)
                    .map_or(String::new(), |c| format!(" · {:.2} M compute", mega(c)))
            ));
            lines.push(format!(
                "{:.2} M fragments ({}) · overdraw {overdraw:.2}",
                mega(fs),
                // Of them, the samples kept: passed the depth test, not discarded.
                r.fragments_passed
                    .map_or("-".to_owned(), |p| format!("{:.2} M kept", mega(p))),
            ));
        }
    }
    if pane.preview {
        lines.push("moving: half resolution".to_owned());
    }
    let text = lines.join("\n");
    let galley = painter.layout_no_wrap(text, font, egui::Color32::WHITE);
    let bg = egui::Rect::from_min_size(pic.min, galley.size() + egui::vec2(8.0, 6.0));
    painter.rect_filled(bg, 2.0, shadow);
    painter.galley(pic.min + egui::vec2(4.0, 3.0), galley, egui::Color32::WHITE);
    // The name's line folds and unfolds the figures.
    let title = egui::Rect::from_min_size(bg.min, egui::vec2(bg.width(), 17.0)).intersect(pic);
    if title.is_positive()
        && ui
            .interact(
                title,
                ui.scope_id().with(("figures", k)),
                egui::Sense::click(),
            )
            .on_hover_cursor(egui::CursorIcon::PointingHand)
            .clicked()
    {
        *figures = !*figures;
    }

    // Rolling plot of GPU wall time.
    if *figures && pane.history.len() > 1 {
        let plot = egui::Rect::from_min_size(
            egui::pos2(pic.min.x + 4.0, pic.max.y - 44.0),
            egui::vec2(160.0, 40.0),
        );
        painter.rect_filled(plot, 2.0, shadow);
        let max = pane
            .history
            .iter()
            .map(|r| r.gpu_wall_ms)
            .fold(1.0, f64::max);
        let points: Vec<egui::Pos2> = pane
            .history
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let x = plot.min.x + plot.width() * i as f32 / (HISTORY - 1) as f32;
                let y = plot.max.y - plot.height() * (r.gpu_wall_ms / max) as f32;
                egui::pos2(x, y)
            })
            .collect();
        painter.add(egui::Shape::line(
            points,
            egui::Stroke::new(1.5, egui::Color32::LIGHT_GREEN),
        ));
        painter.text(
            plot.right_top() + egui::vec2(-2.0, 1.0),
            egui::Align2::RIGHT_TOP,
            format!("{max:.0} ms"),
            egui::FontId::monospace(9.0),
            egui::Color32::WHITE,
        );
    }
    if let Some(e) = &pane.error {
        painter.rect_filled(
            pic.shrink(pic.width() * 0.1),
            4.0,
            egui::Color32::from_rgba_unmultiplied(90, 0, 0, 220),
        );
        painter.text(
            pic.center(),
            egui::Align2::CENTER_CENTER,
            e,
            egui::FontId::proportional(13.0),
            egui::Color32::WHITE,
        );
    }
}
