//! The lights section: the sun's azimuth and elevation, and the point light.

use eframe::egui;
use grassbench::Scene;
use grassbench::glam::Vec3;
use grassbench::scene::PointLight;

use super::Action;

/// Draws the sun and point-light controls for `scene`'s lights; the headers start open when
/// the command line set that light (`open_sun`, `open_point`).
pub fn ui(
    ui: &mut egui::Ui,
    scene: &Scene,
    open_sun: bool,
    open_point: bool,
    actions: &mut Vec<Action>,
) {
    egui::CollapsingHeader::new("sun")
        .default_open(open_sun)
        .show(ui, |ui| sun(ui, scene, actions));
    egui::CollapsingHeader::new("point light")
        .default_open(open_point)
        .show(ui, |ui| point(ui, scene, actions));
}

fn sun(ui: &mut egui::Ui, scene: &Scene, actions: &mut Vec<Action>) {
    let d = Vec3::from(scene.config.lights.sun_direction).normalize_or(Vec3::Y);
    let mut azimuth = d.z.atan2(d.x).to_degrees();
    let mut elevation = d.y.clamp(-1.0, 1.0).asin().to_degrees();
    let mut changed = ui
        .add(egui::Slider::new(&mut azimuth, -180.0..=180.0).text("azimuth °"))
        .changed();
    changed |= ui
        .add(egui::Slider::new(&mut elevation, 2.0..=90.0).text("elevation °"))
        .changed();
    if !scene.config.lights.sun_keys.is_empty() {
        ui.label("the scene moves the sun on keyframes; a slider takes over");
    }
    if changed {
        actions.push(Action::SetSun(crate::ui::sun_direction([
            azimuth, elevation,
        ])));
    }
}

fn point(ui: &mut egui::Ui, scene: &Scene, actions: &mut Vec<Action>) {
    let current = scene.config.lights.point.clone();
    let mut on = current.is_some();
    let mut light = current.unwrap_or_else(|| default_point_light(scene));
    let mut changed = ui
        .checkbox(&mut on, "on (Lambert, 1 / (1 + β d²))")
        .changed();
    if on {
        let min = scene.terrain.min_corner();
        let max = min + scene.terrain.size();
        let (low, high) = scene.terrain.height_range();
        let ranges = [min.x..=max.x, low..=high + 30.0, min.y..=max.y];
        for ((value, range), text) in light
            .position
            .iter_mut()
            .zip(ranges)
            .zip(["x m", "y m", "z m"])
        {
            changed |= ui.add(egui::Slider::new(value, range).text(text)).changed();
        }
        let mut intensity = light.color.iter().copied().fold(0.0, f32::max);
        if ui
            .add(egui::Slider::new(&mut intensity, 0.0..=40.0).text("intensity"))
            .changed()
        {
            let peak = light.color.iter().copied().fold(0.0, f32::max);
            light.color = if peak > 0.0 {
                light.color.map(|c| c * intensity / peak)
            } else {
                [intensity; 3]
            };
            changed = true;
        }
        changed |= ui
            .add(
                egui::Slider::new(&mut light.attenuation, 0.0..=2.0)
                    .logarithmic(true)
                    .text("β 1/m²"),
            )
            .changed();
        if !light.keys.is_empty() {
            ui.label("the scene moves the light on keyframes; a slider takes over");
        }
    }
    if changed {
        light.keys.clear();
        actions.push(Action::SetPointLight(on.then_some(light)));
    }
}

/// A warm point light 3 m above the middle of the terrain: where a newly switched-on light
/// starts.
pub fn default_point_light(scene: &Scene) -> PointLight {
    let terrain = &scene.terrain;
    let centre = terrain.min_corner() + 0.5 * terrain.size();
    PointLight {
        position: (terrain.point_at(centre) + Vec3::Y * 3.0).to_array(),
        color: [6.0, 5.0, 3.5],
        attenuation: 0.05,
        keys: Vec::new(),
    }
}
