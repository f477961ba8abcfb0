//! The camera section: the scene's path, a walker or an orbit, and preview at half resolution.

use eframe::egui;

use crate::ui::camera::CameraMode;
use grassbench::Scene;

/// Draws the camera controls; a new walker or orbit starts where the scene camera is at
/// `frame`.
pub fn ui(
    ui: &mut egui::Ui,
    camera: &mut CameraMode,
    auto_preview: &mut bool,
    scene: &Scene,
    frame: u64,
) {
    ui.label(format!("camera: {}", camera.name()));
    ui.horizontal(|ui| {
        if ui
            .selectable_label(*camera == CameraMode::Path, "path")
            .clicked()
        {
            *camera = CameraMode::Path;
        }
        if ui
            .selectable_label(matches!(camera, CameraMode::Walker { .. }), "walker")
            .clicked()
        {
            *camera = CameraMode::walker_from(scene, frame);
        }
        if ui
            .selectable_label(matches!(camera, CameraMode::Orbit { .. }), "orbit")
            .clicked()
        {
            *camera = CameraMode::orbit_from(scene, frame);
        }
    });
    if let CameraMode::Walker { eye_height, .. } = camera {
        ui.add(
            egui::Slider::new(eye_height, 0.1..=50.0)
                .logarithmic(true)
                .text("eye height m"),
        );
        ui.small("drag a pane to look, WASD to walk (shift: run), Q/E down/up");
    }
    if matches!(camera, CameraMode::Orbit { .. }) {
        ui.small("drag a pane to turn, scroll to zoom");
    }
    ui.checkbox(auto_preview, "half resolution while moving if slow");
}
