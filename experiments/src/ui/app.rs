//! The window: the side panel's sections ([`super::views`]) on the left, the panes in the
//! middle, one frame loop for all. The window holds one [`Stage`] (the world every pane shows)
//! and one clock; what the sections ask for is carried out here, on the stage.

use std::sync::{Arc, Mutex};

use eframe::egui;
use grassbench::GpuContext;
use grassbench::glam::Vec2;
use grassbench::target::Size;

use super::UiArgs;
use super::camera::CameraMode;
use super::clock::Clock;
use super::diff::DiffView;
use super::script::{Layout, Script};
use super::spawn::{self, SpawnKind};
use super::stage::Stage;
use super::views::wind::WindSettings;
use super::views::{self, Action};
use super::{grid, screenshot};
use crate::{registry, scenes};

/// A frame slower than this while the camera moves switches panes to half resolution.
const PREVIEW_THRESHOLD_MS: f64 = 80.0;

/// The application state.
pub struct App {
    args: UiArgs,
    /// The world and the panes.
    stage: Stage,
    clock: Clock,
    camera: CameraMode,
    wind: WindSettings,
    diff: DiffView,
    auto_preview: bool,
    script: Option<Script>,
    /// The command line's `--spawn`, `--sun` and `--point-light` are still to be applied.
    startup_pending: bool,
    pane_rects: Vec<egui::Rect>,
    camera_moving: bool,
    status: String,
    outcome: Arc<Mutex<Option<anyhow::Error>>>,
}

impl App {
    /// Builds the world and the panes the arguments ask for.
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
            (Some(frames), Some(path)) => Some(Script::new(frames, path.clone())),
            (None, None) => None,
            _ => anyhow::bail!("scripted mode needs both --frames and --screenshot"),
        };
        let wind = WindSettings::new(&scene.config.wind)?;
        let mut stage = Stage::new(gpu, &args.scene, scene, size, args.msaa)?;
        let ids: Vec<String> = registry::select(&args.techniques)?
            .iter()
            .map(|e| e.info.id.to_owned())
            .collect();
        stage.build_panes(args.panes, &ids, 0)?;
        let diff = DiffView {
            b: 1.min(args.panes.saturating_sub(1)),
            ..DiffView::default()
        };
        Ok(Self {
            stage,
            clock: Clock::default(),
            camera: CameraMode::Path,
            wind,
            diff,
            auto_preview: script.is_none(),
            script,
            startup_pending: args.spawn.is_some()
                || args.sun.is_some()
                || args.point_light.is_some(),
            pane_rects: Vec::new(),
            camera_moving: false,
            status: String::new(),
            outcome,
            args,
        })
    }

    /// Rebuilds the panes, `count` of them, keeping their techniques.
    fn rebuild(&mut self, frame: &eframe::Frame, count: usize) {
        if let Some(rs) = frame.wgpu_render_state() {
            self.stage.release(rs);
        }
        let ids: Vec<String> = self
            .stage
            .panes
            .iter()
            .map(|p| p.technique_id.clone())
            .collect();
        if let Err(e) = self.stage.build_panes(count, &ids, self.clock.index()) {
            self.status = format!("{e:#}");
        }
        self.diff.a = 0;
        self.diff.b = 1.min(count.saturating_sub(1));
    }

    fn side_panel(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        let gpu = self.stage.world.gpu;
        ui.heading("grassbench");
        ui.label(format!("{} · {}", gpu.summary.name, gpu.summary.backend));
        ui.separator();
        let mut actions = Vec::new();
        views::scene::ui(ui, &mut self.stage, &mut actions);
        ui.separator();
        views::playback::ui(ui, &mut self.clock, self.stage.scene(), &mut actions);
        ui.separator();
        let f = self.clock.index();
        let scene = &self.stage.world.scene;
        views::camera::ui(ui, &mut self.camera, &mut self.auto_preview, scene, f);
        ui.separator();
        if self.wind.ui(ui) {
            actions.push(Action::ApplyWind);
        }
        // Open from the start when the command line set the light.
        let (sun, point) = (self.args.sun.is_some(), self.args.point_light.is_some());
        views::lights::ui(ui, self.stage.scene(), sun, point, &mut actions);
        views::difference::ui(ui, &mut self.diff, self.stage.panes.len());
        for (k, pane) in self.stage.panes.iter_mut().enumerate() {
            views::pane::ui(ui, k, pane, &mut actions);
        }
        ui.separator();
        if ui.button("save screenshot").clicked() {
            let pose = self.camera.pose(self.stage.scene());
            match screenshot::save(&mut self.stage, f, pose, &self.args.screenshot_dir) {
                Ok(dir) => self.status = format!("saved to {}", dir.display()),
                Err(e) => self.status = format!("{e:#}"),
            }
        }
        if !self.status.is_empty() {
            ui.small(&self.status);
        }
        for action in actions {
            self.apply(action, frame);
        }
    }

    /// Carries out what a section of the panel asked for.
    fn apply(&mut self, action: Action, frame: &eframe::Frame) {
        let f = self.clock.index();
        match action {
            Action::LoadScene(name) => match scenes::load(name) {
                Ok(scene) => {
                    self.wind.table = toml::Table::try_from(&scene.config.wind).unwrap_or_default();
                    self.camera = CameraMode::Path;
                    let count = self.stage.panes.len();
                    let ids: Vec<String> = self
                        .stage
                        .panes
                        .iter()
                        .map(|p| p.technique_id.clone())
                        .collect();
                    if let Some(rs) = frame.wgpu_render_state() {
                        self.stage.release(rs);
                    }
                    match self.stage.set_scene(name, scene) {
                        Ok(()) => {
                            if let Err(e) = self.stage.build_panes(count, &ids, f) {
                                self.status = format!("{e:#}");
                            }
                        }
                        Err(e) => self.status = format!("{e:#}"),
                    }
                }
                Err(e) => self.status = e.to_string(),
            },
            Action::Rebuild(count) => self.rebuild(frame, count),
            Action::Restart => {
                self.clock.frame = 0.0;
                self.stage.recreate_all(0);
            }
            Action::ApplyWind => self.apply_wind(),
            Action::SetSun(direction) => self.stage.set_sun(direction),
            Action::SetPointLight(light) => self.stage.set_point_light(light),
            Action::SetTechnique(k, id) => self.stage.set_technique(k, id, f),
            Action::Recreate(k) => self.stage.recreate(&[k], f),
        }
    }

    /// Adds a `kind` primitive at the ground under `ndc` of pane `k`'s picture.
    fn spawn_at(&mut self, k: usize, ndc: Vec2, kind: SpawnKind) {
        let Some(pane) = self.stage.panes.get(k) else {
            return;
        };
        let f = self.clock.index();
        let world = &self.stage.world;
        let camera = world.camera(&pane.view, f);
        let time = world.scene.time_of(f);
        let hit = world
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
        match spawn::add(&mut self.wind.table, &primitive) {
            Ok(n) => {
                self.status = format!(
                    "{} at ({:.1}, {:.1}): {n} wind primitives",
                    kind.label(),
                    hit.x,
                    hit.z
                );
                self.apply_wind();
            }
            Err(e) => self.wind.error = Some(format!("{e:#}")),
        }
    }

    /// Gives the world the wind settings of the panel.
    fn apply_wind(&mut self) {
        match self.wind.config() {
            Ok(config) => {
                self.wind.error = None;
                if let Err(e) = self.stage.set_wind(config) {
                    self.wind.error = Some(e.to_string());
                }
            }
            Err(e) => self.wind.error = Some(format!("{e:#}")),
        }
    }

    /// The command line's `--spawn`, `--sun` and `--point-light`, applied after the first
    /// frame as the panel's controls would.
    fn apply_startup(&mut self) {
        if !self.startup_pending || self.clock.index() == 0 || self.stage.panes.is_empty() {
            return;
        }
        self.startup_pending = false;
        if let Some(kind) = self.args.spawn {
            self.spawn_at(0, Vec2::ZERO, kind);
        }
        if let Some(sun) = self.args.sun {
            self.stage.set_sun(super::sun_direction(sun));
        }
        if let Some(position) = self.args.point_light {
            let light = grassbench::scene::PointLight {
                position,
                ..views::lights::default_point_light(self.stage.scene())
            };
            self.stage.set_point_light(Some(light));
        }
    }

    /// Renders the panes that need it, then draws them in a grid ([`grid::show`]) and acts on
    /// the pointer there (camera, spawn tool) and the walker's keys.
    fn central(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        let Some(render_state) = frame.wgpu_render_state() else {
            ui.label("no wgpu renderer");
            return;
        };
        let f = self.clock.index();
        let capture = self.diff.enabled
            || self
                .script
                .as_ref()
                .is_some_and(|s| self.clock.frame >= s.frames as f64);
        let moving = self.auto_preview && (self.camera_moving || self.clock.playing);
        let pose = self.camera.pose(self.stage.scene());
        self.stage.render(f, pose, capture, |pane| {
            moving
                && pane
                    .history
                    .back()
                    .is_some_and(|r| r.gpu_wall_ms > PREVIEW_THRESHOLD_MS)
        });

        let dt = ui.input(|i| i.stable_dt).min(0.1);
        let grid = grid::show(
            ui,
            render_state,
            &mut self.stage.panes,
            &mut self.camera,
            self.wind.spawn,
            dt,
        );
        self.pane_rects = grid.pictures;
        let mut moved = grid.moved;
        let spawns = grid.spawns;
        self.apply_startup();
        for (k, at, kind) in spawns {
            self.spawn_at(k, at, kind);
        }
        // Keys move the walker even when the pointer is elsewhere.
        if !moved && matches!(self.camera, CameraMode::Walker { .. }) {
            moved |= ui.input(|i| self.camera.control(i, egui::Vec2::ZERO, 0.0, dt));
        }
        self.camera_moving = moved;
        if moved {
            self.stage.invalidate();
        }
    }

    /// Where the panes lie in the window, for the script's screenshot.
    fn layout(&self, pixels_per_point: f32) -> Layout {
        let lights = &self.stage.scene().config.lights;
        Layout {
            techniques: self
                .stage
                .panes
                .iter()
                .map(|p| p.technique_id.clone())
                .collect(),
            rects: self
                .pane_rects
                .iter()
                .map(|r| {
                    [
                        (r.min.x * pixels_per_point) as u32,
                        (r.min.y * pixels_per_point) as u32,
                        (r.width() * pixels_per_point) as u32,
                        (r.height() * pixels_per_point) as u32,
                    ]
                })
                .collect(),
            frame: self.clock.index(),
            wind: self.wind.table.clone(),
            sun: Some(lights.sun_direction),
            point_light: lights.point.as_ref().map(|l| l.position),
        }
    }

    /// Scripted mode: saves and closes the window once the last frame is shown.
    fn run_script(&mut self, ctx: &egui::Context) {
        let Some(mut script) = self.script.take() else {
            return;
        };
        let outcome = script.poll(ctx, &self.stage, self.clock.index(), |ppp| self.layout(ppp));
        self.script = Some(script);
        let Some(result) = outcome else {
            return;
        };
        if let Err(e) = result
            && let Ok(mut o) = self.outcome.lock()
        {
            *o = Some(e);
        }
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }
}

impl eframe::App for App {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.clock.tick(self.script.as_ref().map(|s| s.frames));
        egui::Panel::left("settings")
            .resizable(true)
            .default_size(300.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| self.side_panel(ui, frame));
            });
        egui::CentralPanel::default().show(ui, |ui| self.central(ui, frame));
        if self.diff.enabled {
            views::difference::window(ui.ctx(), &mut self.diff, &self.stage.panes);
        }
        self.run_script(ui.ctx());
        ui.ctx().request_repaint();
    }
}
