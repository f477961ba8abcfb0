//! The playback section: play, pause, step, restart, time scale.

use eframe::egui;

use super::Action;
use crate::ui::clock::Clock;
use grassbench::Scene;

/// Draws the playback controls of `clock` (times read from `scene`).
pub fn ui(ui: &mut egui::Ui, clock: &mut Clock, scene: &Scene, actions: &mut Vec<Action>) {
    ui.horizontal(|ui| {
        if ui
            .button(if clock.playing { "pause" } else { "play" })
            .clicked()
        {
            clock.playing = !clock.playing;
        }
        if ui.button("step").clicked() {
            clock.step();
        }
        if ui
            .button("restart")
            .on_hover_text("back to frame 0")
            .clicked()
        {
            actions.push(Action::Restart);
        }
    });
    ui.add(
        egui::Slider::new(&mut clock.time_scale, 0.1..=8.0)
            .logarithmic(true)
            .text("time scale"),
    );
    let f = clock.index();
    ui.label(format!("frame {f} · t = {:.2} s", scene.time_of(f)));
}
