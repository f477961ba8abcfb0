//! The window: settings on the left, panes in the middle, one frame loop for all.

use std::sync::{Arc, Mutex};

use anyhow::Context as _;
use eframe::egui;
use grassbench::glam::Vec2;
use grassbench::target::{Size, save_png};
use grassbench::wind::WindConfig;
use grassbench::{GpuContext, Scene};

use super::UiArgs;
use super::camera::CameraMode;
use super::diff::{DiffMode, DiffView};
use super::editor::edit_table;
use super::pane::Pane;
use super::script::{Layout, Script};
use super::spawn::{self, SpawnKind};
use crate::{registry, scenes};

/// Pane sizes offered (16:9).
const SIZES: &[&str] = &["320x180", "480x270", "640x360", "960x540", "1280x720"];
/// A frame slower than this while the camera moves switches panes to half resolution.
const PREVIEW_THRESHOLD_MS: f64 = 80.0;

/// The application state.
pub struct App {
    gpu: &'static GpuContext,
    args: UiArgs,
    scene_name: String,
    scene: Scene,
    panes: Vec<Pane>,
    size: Size,
    msaa: bool,
    frame: f64,
    playing: bool,
    time_scale: f64,
    camera: CameraMode,
    wind: toml::Table,
    wind_error: Option<String>,
    /// What a click on a pane adds to the wind.
    spawn: SpawnKind,
    /// The scripted `--spawn` is still to be placed.
    spawn_pending: bool,
    diff: DiffView,
    auto_preview: bool,
    script: Option<Script>,
    screenshot: Arc<Mutex<Option<Arc<egui::ColorImage>>>>,
    pane_rects: Vec<egui::Rect>,
    camera_moving: bool,
    status: String,
    outcome: Arc<Mutex<Option<anyhow::Error>>>,
}

impl App {
    /// Builds the panes the arguments ask for.
    pub fn new(
        cc: &eframe::CreationContext<'_>,
        gpu: &'static GpuContext,
        args: UiArgs,
        outcome: Arc<Mutex<Option<anyhow::Error>>>,
    ) -> anyhow::Result<Self> {
        cc.egui_ctx.set_visuals(egui::Visuals::dark());
        let scene = scenes::load(&args.scene)?;
        let size = Size::parse(&args.size)?;
        let script = match (args.frames, &args.screenshot) {
            (Some(frames), Some(path)) => Some(Script {
                frames,
                screenshot: path.clone(),
                requested: false,
            }),
            (None, None) => None,
            _ => anyhow::bail!("scripted mode needs both --frames and --screenshot"),
        };
        let wind = toml::Table::try_from(&scene.config.wind).context("wind settings")?;
        let mut app = Self {
            gpu,
            scene_name: args.scene.clone(),
            scene,
            panes: Vec::new(),
            size,
            msaa: args.msaa,
            frame: 0.0,
            playing: true,
            time_scale: 1.0,
            camera: CameraMode::Path,
            wind,
            wind_error: None,
            spawn: SpawnKind::Off,
            spawn_pending: args.spawn.is_some() || args.sun.is_some() || args.point_light.is_some(),
            diff: DiffView::default(),
            auto_preview: script.is_none(),
            script,
            screenshot: Arc::new(Mutex::new(None)),
            pane_rects: Vec::new(),
            camera_moving: false,
            status: String::new(),
            outcome,
            args,
        };
        let ids: Vec<String> = registry::select(&app.args.techniques)?
            .iter()
            .map(|e| e.info.id.to_owned())
            .collect();
        app.build_panes(app.args.panes, &ids)?;
        Ok(app)
    }

    fn frame_index(&self) -> u64 {
        self.frame.max(0.0) as u64
    }

    /// (Re)creates `count` panes with techniques from `ids` (cycled).
    fn build_panes(&mut self, count: usize, ids: &[String]) -> anyhow::Result<()> {
        let mut panes = Vec::with_capacity(count);
        for k in 0..count {
            let id = ids
                .get(k % ids.len().max(1))
                .cloned()
                .unwrap_or_else(|| "reference".to_owned());
            let mut pane = Pane::new(self.gpu, self.scene.clone(), &id, self.size, self.msaa)?;
            if let Ok(config) = wind_from_table(&self.wind) {
                let _ = pane.harness.set_wind(config);
            }
            pane.recreate(self.frame_index());
            panes.push(pane);
        }
        self.panes = panes;
        self.diff.a = 0;
        self.diff.b = 1.min(count.saturating_sub(1));
        Ok(())
    }

    fn rebuild(&mut self, frame: &eframe::Frame, count: usize) {
        if let Some(rs) = frame.wgpu_render_state() {
            for p in &mut self.panes {
                p.release(rs);
            }
        }
        let ids: Vec<String> = self.panes.iter().map(|p| p.technique_id.clone()).collect();
        if let Err(e) = self.build_panes(count, &ids) {
            self.status = format!("{e:#}");
        }
    }

    fn side_panel(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        ui.heading("grassbench");
        ui.label(format!(
            "{} · {}",
            self.gpu.summary.name, self.gpu.summary.backend
        ));
        ui.separator();

        // Scene and layout.
        let mut rebuild = None;
        egui::ComboBox::from_label("scene")
            .selected_text(&self.scene_name)
            .show_ui(ui, |ui| {
                for name in scenes::names() {
                    if ui.selectable_label(self.scene_name == name, name).clicked()
                        && self.scene_name != name
                    {
                        match scenes::load(name) {
                            Ok(scene) => {
                                self.wind =
                                    toml::Table::try_from(&scene.config.wind).unwrap_or_default();
                                self.scene = scene;
                                self.scene_name = name.to_owned();
                                self.camera = CameraMode::Path;
                                rebuild = Some(self.panes.len());
                            }
                            Err(e) => self.status = e.to_string(),
                        }
                    }
                }
            });
        ui.horizontal(|ui| {
            ui.label("panes");
            for n in [1, 2, 4] {
                if ui
                    .selectable_label(self.panes.len() == n, n.to_string())
                    .clicked()
                    && self.panes.len() != n
                {
                    rebuild = Some(n);
                }
            }
        });
        let current = self.size.to_string();
        egui::ComboBox::from_label("pane size")
            .selected_text(&current)
            .show_ui(ui, |ui| {
                for s in SIZES {
                    if ui.selectable_label(current == *s, *s).clicked()
                        && current != *s
                        && let Ok(size) = Size::parse(s)
                    {
                        self.size = size;
                        rebuild = Some(self.panes.len());
                    }
                }
            });
        if ui.checkbox(&mut self.msaa, "4x MSAA").changed() {
            rebuild = Some(self.panes.len());
        }
        if let Some(n) = rebuild {
            self.rebuild(frame, n);
        }
        ui.separator();

        // Playback.
        ui.horizontal(|ui| {
            if ui
                .button(if self.playing { "pause" } else { "play" })
                .clicked()
            {
                self.playing = !self.playing;
            }
            if ui.button("step").clicked() {
                self.playing = false;
                self.frame = self.frame.floor() + 1.0;
            }
            if ui
                .button("restart")
                .on_hover_text("back to frame 0")
                .clicked()
            {
                self.frame = 0.0;
                for p in &mut self.panes {
                    p.recreate(0);
                }
            }
        });
        ui.add(
            egui::Slider::new(&mut self.time_scale, 0.1..=8.0)
                .logarithmic(true)
                .text("time scale"),
        );
        ui.label(format!(
            "frame {} · t = {:.2} s",
            self.frame_index(),
            self.scene.time_of(self.frame_index())
        ));
        ui.separator();

        // Camera.
        ui.label(format!("camera: {}", self.camera.name()));
        ui.horizontal(|ui| {
            let f = self.frame_index();
            if ui
                .selectable_label(self.camera == CameraMode::Path, "path")
                .clicked()
            {
                self.camera = CameraMode::Path;
            }
            if ui
                .selectable_label(matches!(self.camera, CameraMode::Walker { .. }), "walker")
                .clicked()
            {
                self.camera = CameraMode::walker_from(&self.scene, f);
            }
            if ui
                .selectable_label(matches!(self.camera, CameraMode::Orbit { .. }), "orbit")
                .clicked()
            {
                self.camera = CameraMode::orbit_from(&self.scene, f);
            }
        });
        if let CameraMode::Walker { eye_height, .. } = &mut self.camera {
            ui.add(
                egui::Slider::new(eye_height, 0.1..=50.0)
                    .logarithmic(true)
                    .text("eye height m"),
            );
            ui.small("drag a pane to look, WASD to walk (shift: run), Q/E down/up");
        }
        if matches!(self.camera, CameraMode::Orbit { .. }) {
            ui.small("drag a pane to turn, scroll to zoom");
        }
        ui.checkbox(
            &mut self.auto_preview,
            "half resolution while moving if slow",
        );
        ui.separator();

        // Wind.
        ui.collapsing("wind", |ui| {
            let model = self
                .wind
                .get("model")
                .and_then(|v| v.as_str())
                .unwrap_or("calm")
                .to_owned();
            let mut changed = false;
            egui::ComboBox::from_label("model")
                .selected_text(&model)
                .show_ui(ui, |ui| {
                    for m in WindConfig::MODELS {
                        if ui.selectable_label(model == *m, *m).clicked()
                            && model != *m
                            && let Some(c) = WindConfig::default_for(m)
                        {
                            self.wind = toml::Table::try_from(&c).unwrap_or_default();
                            changed = true;
                        }
                    }
                });
            changed |= edit_table(ui, &mut self.wind, &["model"]);
            if changed {
                self.apply_wind();
            }
            if let Some(e) = &self.wind_error {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
            }
            ui.label("click a pane to add (Perbet's primitives):");
            ui.horizontal(|ui| {
                for kind in SpawnKind::ALL {
                    ui.radio_value(&mut self.spawn, kind, kind.label());
                }
            });
        });

        // Lights.
        // Open from the start when the command line set the light.
        let open_sun = self.args.sun.is_some();
        egui::CollapsingHeader::new("sun")
            .default_open(open_sun)
            .show(ui, |ui| {
                let d = grassbench::glam::Vec3::from(self.scene.config.lights.sun_direction)
                    .normalize_or(grassbench::glam::Vec3::Y);
                let mut azimuth = d.z.atan2(d.x).to_degrees();
                let mut elevation = d.y.clamp(-1.0, 1.0).asin().to_degrees();
                let mut changed = ui
                    .add(egui::Slider::new(&mut azimuth, -180.0..=180.0).text("azimuth °"))
                    .changed();
                changed |= ui
                    .add(egui::Slider::new(&mut elevation, 2.0..=90.0).text("elevation °"))
                    .changed();
                if !self.scene.config.lights.sun_keys.is_empty() {
                    ui.label("the scene moves the sun on keyframes; a slider takes over");
                }
                if changed {
                    self.set_sun(super::sun_direction([azimuth, elevation]));
                }
            });
        let open_point = self.args.point_light.is_some();
        egui::CollapsingHeader::new("point light")
            .default_open(open_point)
            .show(ui, |ui| {
                let current = self.scene.config.lights.point.clone();
                let mut on = current.is_some();
                let mut light = current.unwrap_or_else(|| self.default_point_light());
                let mut changed = ui
                    .checkbox(&mut on, "on (Lambert, 1 / (1 + β d²))")
                    .changed();
                if on {
                    let min = self.scene.terrain.min_corner();
                    let max = min + self.scene.terrain.size();
                    let (low, high) = self.scene.terrain.height_range();
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
                    self.set_point_light(on.then_some(light));
                }
            });

        // Difference view.
        ui.collapsing("difference view", |ui| {
            ui.checkbox(&mut self.diff.enabled, "show difference of two panes");
            let n = self.panes.len();
            for (label, slot) in [("pane A", &mut self.diff.a), ("pane B", &mut self.diff.b)] {
                egui::ComboBox::from_label(label)
                    .selected_text(format!("{}", *slot + 1))
                    .show_ui(ui, |ui| {
                        for k in 0..n {
                            ui.selectable_value(slot, k, format!("{}", k + 1));
                        }
                    });
            }
            ui.horizontal(|ui| {
                ui.radio_value(&mut self.diff.mode, DiffMode::Flip, "FLIP");
                ui.radio_value(&mut self.diff.mode, DiffMode::Absolute, "absolute x4");
            });
        });

        // Per-pane settings.
        let f = self.frame_index();
        for (k, pane) in self.panes.iter_mut().enumerate() {
            ui.collapsing(format!("pane {}: {}", k + 1, pane.technique_id), |ui| {
                let mut switch = None;
                egui::ComboBox::from_id_salt(("technique", k))
                    .selected_text(&pane.technique_id)
                    .show_ui(ui, |ui| {
                        for e in registry::TECHNIQUES {
                            if ui
                                .selectable_label(pane.technique_id == e.info.id, e.info.name)
                                .clicked()
                            {
                                switch = Some(e.info.id);
                            }
                        }
                    });
                if let Some(id) = switch {
                    pane.set_technique(id, f);
                }
                if let Some((info, params)) =
                    pane.technique.as_ref().map(|t| (t.info(), t.param_table()))
                {
                    ui.small(info.paper);
                    let mut view = pane.harness.debug_view;
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
                    if view != pane.harness.debug_view {
                        pane.harness.debug_view = view;
                        pane.invalidate();
                    }
                    let mut params = params;
                    if edit_table(ui, &mut params, &[]) {
                        pane.overrides = params;
                        pane.recreate(f);
                    }
                }
                if ui.button("reset parameters").clicked() {
                    pane.overrides.clear();
                    pane.recreate(f);
                }
            });
        }
        ui.separator();
        if ui.button("save screenshot").clicked() {
            match self.save_screenshots() {
                Ok(dir) => self.status = format!("saved to {}", dir.display()),
                Err(e) => self.status = format!("{e:#}"),
            }
        }
        if !self.status.is_empty() {
            ui.small(&self.status);
        }
    }

    /// Adds a `kind` primitive at the ground under `ndc` of pane `k`'s picture.
    fn spawn_at(&mut self, k: usize, ndc: Vec2, kind: SpawnKind) {
        let Some(pane) = self.panes.get(k) else {
            return;
        };
        let f = self.frame_index();
        let camera = pane.harness.camera(f);
        let time = self.scene.time_of(f);
        let hit = self
            .scene
            .terrain
            .raycast(camera.eye, camera.ray(ndc), camera.far);
        let Some(hit) = hit else {
            self.status = "no ground under the pointer".into();
            return;
        };
        let Some(primitive) = kind.primitive(Vec2::new(hit.x, hit.z), time, camera.forward) else {
            return;
        };
        match spawn::add(&mut self.wind, &primitive) {
            Ok(n) => {
                self.status = format!(
                    "{} at ({:.1}, {:.1}): {n} wind primitives",
                    kind.label(),
                    hit.x,
                    hit.z
                );
                self.apply_wind();
            }
            Err(e) => self.wind_error = Some(format!("{e:#}")),
        }
    }

    /// Points the sun along `direction` (towards the sun) in every pane, replacing the scene's
    /// sun keyframes: techniques that light per frame (boulanger's BTF slices, every shader's
    /// Lambert term) follow at once.
    fn set_sun(&mut self, direction: [f32; 3]) {
        for lights in std::iter::once(&mut self.scene.config.lights).chain(
            self.panes
                .iter_mut()
                .map(|p| &mut p.harness.scene.config.lights),
        ) {
            lights.sun_direction = direction;
            lights.sun_keys.clear();
        }
        for p in &mut self.panes {
            p.invalidate();
        }
    }

    /// Sets (or removes) the point light in every pane; techniques read it per frame.
    fn set_point_light(&mut self, light: Option<grassbench::scene::PointLight>) {
        for lights in std::iter::once(&mut self.scene.config.lights).chain(
            self.panes
                .iter_mut()
                .map(|p| &mut p.harness.scene.config.lights),
        ) {
            lights.point = light.clone();
        }
        for p in &mut self.panes {
            p.invalidate();
        }
    }

    /// A warm point light 3 m above the middle of the terrain: where a newly switched-on light
    /// starts.
    fn default_point_light(&self) -> grassbench::scene::PointLight {
        let terrain = &self.scene.terrain;
        let centre = terrain.min_corner() + 0.5 * terrain.size();
        grassbench::scene::PointLight {
            position: (terrain.point_at(centre) + grassbench::glam::Vec3::Y * 3.0).to_array(),
            color: [6.0, 5.0, 3.5],
            attenuation: 0.05,
            keys: Vec::new(),
        }
    }

    fn apply_wind(&mut self) {
        match wind_from_table(&self.wind) {
            Ok(config) => {
                self.wind_error = None;
                for p in &mut self.panes {
                    if let Err(e) = p.harness.set_wind(config.clone()) {
                        self.wind_error = Some(e.to_string());
                    }
                    p.invalidate();
                }
            }
            Err(e) => self.wind_error = Some(format!("{e:#}")),
        }
    }

    /// Saves each pane's image at full resolution and a composite, in a new folder.
    fn save_screenshots(&mut self) -> anyhow::Result<std::path::PathBuf> {
        let f = self.frame_index();
        let camera = self.camera.pose(&self.scene);
        let stamp = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
        let dir = self
            .args
            .screenshot_dir
            .join(format!("{}-f{f:05}-{stamp}", self.scene_name));
        let mut images = Vec::new();
        for (k, pane) in self.panes.iter_mut().enumerate() {
            pane.invalidate();
            pane.render(f, camera, true, false);
            let img = pane.last_image.clone().with_context(|| {
                format!(
                    "pane {} has no image: {}",
                    k + 1,
                    pane.error.clone().unwrap_or_default()
                )
            })?;
            save_png(
                &img,
                &dir.join(format!("pane{}_{}.png", k + 1, pane.technique_id)),
            )?;
            images.push(img);
        }
        save_png(&composite(&images), &dir.join("composite.png"))?;
        Ok(dir)
    }

    fn central(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        let Some(render_state) = frame.wgpu_render_state() else {
            ui.label("no wgpu renderer");
            return;
        };
        let n = self.panes.len();
        let cols = if n == 1 { 1 } else { 2 };
        let rows = n.div_ceil(cols);
        let area = ui.available_rect_before_wrap();
        let cell = egui::vec2(area.width() / cols as f32, area.height() / rows as f32);
        let f = self.frame_index();
        let capture = self.diff.enabled
            || self
                .script
                .as_ref()
                .is_some_and(|s| self.frame >= s.frames as f64);
        let dt = ui.input(|i| i.stable_dt).min(0.1);
        let mut moved = false;
        let mut spawns = Vec::new();
        self.pane_rects.clear();
        for k in 0..n {
            let (col, row) = (k % cols, k / cols);
            let rect = egui::Rect::from_min_size(
                area.min + egui::vec2(col as f32 * cell.x, row as f32 * cell.y),
                cell,
            )
            .shrink(4.0);
            let slow = self.panes[k]
                .history
                .back()
                .is_some_and(|r| r.gpu_wall_ms > PREVIEW_THRESHOLD_MS);
            let preview = self.auto_preview && slow && (self.camera_moving || self.playing);
            let pose = self.camera.pose(&self.scene);
            let pane = &mut self.panes[k];
            pane.render(f, pose, capture, preview);
            // Fit the picture into the cell, keeping its aspect ratio.
            let aspect = pane.full_size.width as f32 / pane.full_size.height as f32;
            let fit = if rect.width() / rect.height() > aspect {
                egui::vec2(rect.height() * aspect, rect.height())
            } else {
                egui::vec2(rect.width(), rect.width() / aspect)
            };
            let pic = egui::Rect::from_center_size(rect.center(), fit);
            self.pane_rects.push(pic);
            let response = ui.interact(
                pic,
                ui.scope_id().with(("pane", k)),
                egui::Sense::click_and_drag(),
            );
            if self.spawn != SpawnKind::Off
                && response.clicked()
                && let Some(pos) = response.interact_pointer_pos()
            {
                spawns.push((k, spawn::ndc(pic, pos), self.spawn));
            }
            if pane.error.is_none() || pane.technique.is_some() {
                let id = pane.texture(render_state);
                ui.painter().image(
                    id,
                    pic,
                    egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
                    egui::Color32::WHITE,
                );
            }
            if response.hovered() || response.dragged() {
                let scroll = ui.input(|i| i.smooth_scroll_delta.y);
                moved |= ui.input(|i| self.camera.control(i, response.drag_delta(), scroll, dt));
            }
            overlay(ui, pane, pic, k);
        }
        if self.spawn_pending && self.frame_index() > 0 && !self.panes.is_empty() {
            self.spawn_pending = false;
            if let Some(kind) = self.args.spawn {
                spawns.push((0, Vec2::ZERO, kind));
            }
            if let Some(sun) = self.args.sun {
                self.set_sun(super::sun_direction(sun));
            }
            if let Some(position) = self.args.point_light {
                let light = grassbench::scene::PointLight {
                    position,
                    ..self.default_point_light()
                };
                self.set_point_light(Some(light));
            }
        }
        for (k, at, kind) in spawns {
            self.spawn_at(k, at, kind);
        }
        // Keys move the walker even when the pointer is elsewhere.
        if !moved && matches!(self.camera, CameraMode::Walker { .. }) {
            moved |= ui.input(|i| self.camera.control(i, egui::Vec2::ZERO, 0.0, dt));
        }
        self.camera_moving = moved;
        if moved {
            for p in &mut self.panes {
                p.invalidate();
            }
        }
    }
}

/// Technique name, figures, rolling plot and errors drawn over a pane.
fn overlay(ui: &egui::Ui, pane: &Pane, pic: egui::Rect, k: usize) {
    let painter = ui.painter_at(pic);
    let font = egui::FontId::monospace(11.0);
    let shadow = egui::Color32::from_black_alpha(160);
    let mut lines = vec![format!("{} {}", k + 1, pane.technique_id)];
    if let Some(r) = pane.history.back() {
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
        lines.push(format!(
            "{} blades · {} tris · {:.1} MB",
            r.blades,
            r.triangles,
            r.gpu_bytes as f64 / 1e6
        ));
    }
    if pane.preview {
        lines.push("moving: half resolution".to_owned());
    }
    let text = lines.join("\n");
    let galley = painter.layout_no_wrap(text, font, egui::Color32::WHITE);
    let bg = egui::Rect::from_min_size(pic.min, galley.size() + egui::vec2(8.0, 6.0));
    painter.rect_filled(bg, 2.0, shadow);
    painter.galley(pic.min + egui::vec2(4.0, 3.0), galley, egui::Color32::WHITE);

    // Rolling plot of GPU wall time.
    if pane.history.len() > 1 {
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
                let x = plot.min.x + plot.width() * i as f32 / (super::pane::HISTORY - 1) as f32;
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

/// Pane images tiled as in the window (2 columns when more than one).
fn composite(images: &[image::RgbaImage]) -> image::RgbaImage {
    let cols = if images.len() == 1 { 1 } else { 2 };
    let rows = images.len().div_ceil(cols) as u32;
    let (w, h) = images.first().map_or((1, 1), |i| i.dimensions());
    let mut out = image::RgbaImage::new(w * cols as u32, h * rows);
    for (k, img) in images.iter().enumerate() {
        let (x, y) = ((k % cols) as u32 * w, (k / cols) as u32 * h);
        image::imageops::overlay(&mut out, img, i64::from(x), i64::from(y));
    }
    out
}

fn wind_from_table(table: &toml::Table) -> anyhow::Result<WindConfig> {
    let config: WindConfig = toml::Value::Table(table.clone())
        .try_into()
        .context("wind settings")?;
    config.validate()?;
    Ok(config)
}

impl eframe::App for App {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if self.playing {
            self.frame += self.time_scale;
        }
        if let Some(script) = &self.script
            && self.frame >= script.frames as f64
        {
            self.frame = script.frames as f64;
            self.playing = false;
        }
        egui::Panel::left("settings")
            .resizable(true)
            .default_size(300.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| self.side_panel(ui, frame));
            });
        egui::CentralPanel::default().show(ui, |ui| self.central(ui, frame));
        if self.diff.enabled {
            self.difference_window(ui.ctx());
        }
        self.run_script(ui.ctx());
        ui.ctx().request_repaint();
    }
}

impl App {
    fn difference_window(&mut self, ctx: &egui::Context) {
        let (a, b) = (self.diff.a, self.diff.b);
        if let (Some(ia), Some(ib)) = (
            self.panes.get(a).and_then(|p| p.last_image.as_ref()),
            self.panes.get(b).and_then(|p| p.last_image.as_ref()),
        ) {
            let (ia, ib) = (ia.clone(), ib.clone());
            self.diff.update(ctx, &ia, &ib);
        }
        egui::Window::new("difference")
            .default_width(420.0)
            .show(ctx, |ui| {
                let what = match self.diff.mode {
                    DiffMode::Flip => "mean FLIP",
                    DiffMode::Absolute => "mean |Δ| / 255",
                };
                match (&self.diff.error, self.diff.mean) {
                    (Some(e), _) => {
                        ui.colored_label(egui::Color32::LIGHT_RED, e);
                    }
                    (None, Some(m)) => {
                        let m = if self.diff.mode == DiffMode::Absolute {
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
                if let Some(t) = &self.diff.texture {
                    let w = ui.available_width();
                    let size = t.size_vec2();
                    ui.image((t.id(), egui::vec2(w, w * size.y / size.x.max(1.0))));
                }
            });
    }

    fn run_script(&mut self, ctx: &egui::Context) {
        let Some(script) = &mut self.script else {
            return;
        };
        if self.frame < script.frames as f64 {
            return;
        }
        let ready = self
            .panes
            .iter()
            .all(|p| p.shown_frame == Some(script.frames) || p.technique.is_none());
        if !ready {
            return;
        }
        if !script.requested {
            script.requested = true;
            let slot = self.screenshot.clone();
            let ctx2 = ctx.clone();
            ctx.request_screenshot(move |img| {
                if let Ok(mut s) = slot.lock() {
                    *s = Some(img);
                }
                ctx2.request_repaint();
            });
            return;
        }
        let Some(img) = self.screenshot.lock().ok().and_then(|mut s| s.take()) else {
            return;
        };
        let path = script.screenshot.clone();
        let result = (|| -> anyhow::Result<()> {
            let [w, h] = img.size;
            let rgba: Vec<u8> = img.pixels.iter().flat_map(|c| c.to_array()).collect();
            let window =
                image::RgbaImage::from_raw(w as u32, h as u32, rgba).context("screenshot size")?;
            save_png(&window, &path)?;
            let ppp = ctx.pixels_per_point();
            let layout = Layout {
                techniques: self.panes.iter().map(|p| p.technique_id.clone()).collect(),
                rects: self
                    .pane_rects
                    .iter()
                    .map(|r| {
                        [
                            (r.min.x * ppp) as u32,
                            (r.min.y * ppp) as u32,
                            (r.width() * ppp) as u32,
                            (r.height() * ppp) as u32,
                        ]
                    })
                    .collect(),
                frame: self.frame_index(),
                wind: self.wind.clone(),
                sun: self
                    .panes
                    .first()
                    .map(|p| p.harness.scene.config.lights.sun_direction),
                point_light: self.panes.first().and_then(|p| {
                    let lights = &p.harness.scene.config.lights;
                    lights.point.as_ref().map(|l| l.position)
                }),
            };
            std::fs::write(Layout::path_for(&path), toml::to_string(&layout)?)?;
            for (k, pane) in self.panes.iter().enumerate() {
                if let Some(img) = &pane.last_image {
                    save_png(img, &path.with_extension(format!("pane{}.png", k + 1)))?;
                }
                if let Some(e) = &pane.error {
                    anyhow::bail!("pane {} ({}) failed: {e}", k + 1, pane.technique_id);
                }
            }
            Ok(())
        })();
        if let Err(e) = result
            && let Ok(mut o) = self.outcome.lock()
        {
            *o = Some(e);
        }
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }
}
