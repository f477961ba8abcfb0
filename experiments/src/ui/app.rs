//! The window: the side panel's sections ([`super::views`]) on the left, the panes in the
//! middle, one frame loop for all. The panes render on the [`Worker`]'s thread; the window
//! holds what it shows of them ([`PaneDisplay`]), the clock, the camera and a copy of the
//! scene (for the camera path, the lights' sliders and clicks on the ground), and sends the
//! worker what changes. It never waits for the worker: each window frame shows each pane's
//! latest finished frame and answers input at once, however long the panes take.

use std::sync::{Arc, Mutex};
use std::time::Instant;

use eframe::egui;
use grassbench::Scene;
use grassbench::glam::Vec2;
use grassbench::gpu::{AdapterSummary, BackendChoice};
use grassbench::target::Size;

use super::UiArgs;
use super::camera::CameraMode;
use super::clock::Clock;
use super::diff::DiffView;
use super::display::PaneDisplay;
use super::grid;
use super::script::{Layout, Script, WipeLayout};
use super::spawn::{self, SpawnKind};
use super::views::scene::Setup;
use super::views::wind::WindSettings;
use super::views::{self, Action};
use super::wipe::{FLIP_KEY, Wipe};
use super::worker::{Command, Report, Request, Start, Want, Worker};
use crate::{registry, scenes};

/// A frame slower than this while the camera moves switches panes to half resolution.
const PREVIEW_THRESHOLD_MS: f64 = 80.0;

/// The application state.
pub struct App {
    args: UiArgs,
    /// Renders the panes on its own thread and device.
    worker: Worker,
    /// The worker's adapter, once it has its device.
    adapter: Option<AdapterSummary>,
    /// The scene as the window knows it (the worker holds its own copy, kept in step).
    scene: Scene,
    setup: Setup,
    /// What the window shows of each pane.
    panes: Vec<PaneDisplay>,
    /// The worker's rebuilds of the panes the window has taken.
    epoch: u64,
    /// Parameter edits sent so far (numbers them).
    edits: u64,
    clock: Clock,
    camera: CameraMode,
    wind: WindSettings,
    diff: DiffView,
    wipe: Wipe,
    /// The figures over the panes are unfolded.
    figures: bool,
    /// The side panel is unfolded.
    panel_open: bool,
    auto_preview: bool,
    script: Option<Script>,
    /// The command line's `--spawn`, `--sun`, `--point-light` and `--wipe` are still to be
    /// applied.
    startup_pending: bool,
    pane_rects: Vec<Option<egui::Rect>>,
    camera_moving: bool,
    status: String,
    /// When the last window frame began, and the time between frames since.
    last_frame: Option<Instant>,
    frame_ms: Vec<f64>,
    outcome: Arc<Mutex<Option<anyhow::Error>>>,
}

impl App {
    /// Starts the render worker on `backend` (its device requesting `limits`) with the panes
    /// the arguments ask for.
    pub fn new(
        cc: &eframe::CreationContext<'_>,
        backend: BackendChoice,
        limits: grassbench::wgpu::Limits,
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
        let ids: Vec<String> = registry::select(&args.techniques)?
            .iter()
            .map(|e| e.info.id.to_owned())
            .collect();
        let worker = Worker::start(
            Start {
                backend,
                limits,
                scene_name: args.scene.clone(),
                scene: scene.clone(),
                size,
                msaa: args.msaa,
                count: args.panes,
                ids,
            },
            cc.egui_ctx.clone(),
        )?;
        let diff = DiffView {
            b: 1.min(args.panes.saturating_sub(1)),
            ..DiffView::default()
        };
        Ok(Self {
            worker,
            adapter: None,
            setup: Setup {
                scene_name: args.scene.clone(),
                count: args.panes,
                size,
                msaa: args.msaa,
            },
            scene,
            panes: Vec::new(),
            epoch: 0,
            edits: 0,
            clock: Clock::default(),
            camera: CameraMode::Path,
            wind,
            diff,
            wipe: Wipe {
                enabled: args.wipe.is_some() && args.panes >= 2,
                ..Wipe::default()
            },
            figures: true,
            panel_open: !args.hide_panel,
            auto_preview: script.is_none(),
            script,
            startup_pending: args.spawn.is_some()
                || args.sun.is_some()
                || args.point_light.is_some()
                || args.wipe.is_some(),
            pane_rects: Vec::new(),
            camera_moving: false,
            status: "starting the render worker…".into(),
            last_frame: None,
            frame_ms: Vec::new(),
            outcome,
            args,
        })
    }

    /// Takes what the worker reported since the last window frame.
    fn receive(&mut self, ctx: &egui::Context) {
        let reports: Vec<Report> = self.worker.reports().collect();
        for report in reports {
            match report {
                Report::Ready(adapter) => {
                    self.adapter = Some(adapter);
                    self.status.clear();
                }
                Report::Failed(e) => {
                    self.status = format!("no panes: {e}");
                    if self.script.is_some() {
                        self.fail(ctx, anyhow::anyhow!("the render worker failed: {e}"));
                    }
                }
                Report::Panes { epoch, panes } => {
                    if epoch != self.epoch || panes.len() != self.panes.len() {
                        self.epoch = epoch;
                        let size = self.setup.size;
                        self.panes = panes
                            .into_iter()
                            .map(|s| PaneDisplay::new(s, size))
                            .collect();
                        self.worker.forget_request();
                    } else {
                        for (pane, summary) in self.panes.iter_mut().zip(panes) {
                            pane.update(summary);
                        }
                    }
                }
                Report::Frame {
                    epoch,
                    pane,
                    technique_id,
                    frame,
                    record,
                    image,
                    preview,
                } => {
                    if let Some(p) = self.panes.get_mut(pane)
                        && epoch == self.epoch
                        && p.technique_id == technique_id
                    {
                        p.finished(ctx, frame, *record, image, preview);
                    }
                }
                Report::Wind(error) => self.wind.error = error,
                Report::Status(line) => self.status = line,
            }
        }
    }

    /// Ends a script with `error`.
    fn fail(&mut self, ctx: &egui::Context, error: anyhow::Error) {
        if let Ok(mut o) = self.outcome.lock() {
            *o = Some(error);
        }
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }

    /// The panes shown: both of the wipe view's, or all.
    fn shown(&self, k: usize) -> bool {
        !self.wipe_on() || k == self.wipe.a || k == self.wipe.b
    }

    fn wipe_on(&self) -> bool {
        self.wipe.enabled && self.wipe.a < self.panes.len() && self.wipe.b < self.panes.len()
    }

    /// Whether every pane shown shows the clock's frame (or has failed).
    fn caught_up(&self) -> bool {
        let f = self.clock.index();
        !self.panes.is_empty()
            && self
                .panes
                .iter()
                .enumerate()
                .all(|(k, p)| !self.shown(k) || p.caught_up(f))
    }

    fn technique_ids(&self) -> Vec<String> {
        self.panes.iter().map(|p| p.technique_id.clone()).collect()
    }

    /// Rebuilds the panes, `count` of them, keeping their techniques.
    fn rebuild(&mut self, count: usize) {
        self.setup.count = count;
        self.worker.send(Command::BuildPanes {
            count,
            ids: self.technique_ids(),
            size: self.setup.size,
            msaa: self.setup.msaa,
            frame: self.clock.index(),
        });
        self.diff.a = 0;
        self.diff.b = 1.min(count.saturating_sub(1));
        self.wipe.a = 0;
        self.wipe.b = 1.min(count.saturating_sub(1));
    }

    fn side_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("grassbench");
        match &self.adapter {
            Some(a) => ui.label(format!("{} · {}", a.name, a.backend)),
            None => ui.label("render worker starting…"),
        };
        ui.separator();
        let mut actions = Vec::new();
        views::scene::ui(ui, &mut self.setup, &mut actions);
        ui.separator();
        views::playback::ui(ui, &mut self.clock, &self.scene, &mut actions);
        ui.separator();
        let f = self.clock.index();
        views::camera::ui(ui, &mut self.camera, &mut self.auto_preview, &self.scene, f);
        ui.separator();
        if self.wind.ui(ui) {
            actions.push(Action::ApplyWind);
        }
        // Open from the start when the command line set the light.
        let (sun, point) = (self.args.sun.is_some(), self.args.point_light.is_some());
        views::lights::ui(ui, &self.scene, sun, point, &mut actions);
        views::difference::ui(ui, &mut self.diff, self.panes.len());
        views::wipe::ui(ui, &mut self.wipe, self.panes.len());
        ui.checkbox(&mut self.figures, "figures over the panes");
        for (k, pane) in self.panes.iter().enumerate() {
            views::pane::ui(ui, k, pane, &mut actions);
        }
        ui.separator();
        if ui.button("save screenshot").clicked() {
            self.worker.send(Command::Screenshot {
                frame: f,
                camera: self.camera.pose(&self.scene),
                root: self.args.screenshot_dir.clone(),
            });
            self.status = "saving…".into();
        }
        if !self.status.is_empty() {
            ui.small(&self.status);
        }
        for action in actions {
            self.apply(action);
        }
    }

    /// Carries out what a section of the panel asked for.
    fn apply(&mut self, action: Action) {
        let f = self.clock.index();
        match action {
            Action::LoadScene(name) => match scenes::load(name) {
                Ok(scene) => {
                    self.wind.table = toml::Table::try_from(&scene.config.wind).unwrap_or_default();
                    self.camera = CameraMode::Path;
                    self.setup.scene_name = name.to_owned();
                    self.worker.send(Command::LoadScene {
                        name: name.to_owned(),
                        scene: Box::new(scene.clone()),
                        count: self.panes.len(),
                        ids: self.technique_ids(),
                        frame: f,
                    });
                    self.scene = scene;
                }
                Err(e) => self.status = e.to_string(),
            },
            Action::Rebuild(count) => self.rebuild(count),
            Action::Restart => {
                self.clock.frame = 0.0;
                self.worker.send(Command::RecreateAll(0));
            }
            Action::ApplyWind => self.apply_wind(),
            Action::SetSun(direction) => self.set_sun(direction),
            Action::SetPointLight(light) => self.set_point_light(light),
            Action::SetTechnique(k, id) => self.worker.send(Command::SetTechnique {
                pane: k,
                id: id.to_owned(),
                frame: f,
            }),
            Action::Recreate(k, overrides) => {
                self.edits += 1;
                if let Some(p) = self.panes.get_mut(k) {
                    p.edited(&overrides, self.edits);
                }
                self.worker.send(Command::Recreate {
                    pane: k,
                    overrides,
                    frame: f,
                    edit: self.edits,
                });
            }
            Action::DebugView(k, view) => {
                if let Some(p) = self.panes.get_mut(k) {
                    p.debug_view = view;
                }
                self.worker.send(Command::SetDebugView { pane: k, view });
            }
        }
    }

    /// Points the sun along `direction` in the window's scene and the worker's.
    fn set_sun(&mut self, direction: [f32; 3]) {
        let lights = &mut self.scene.config.lights;
        lights.sun_direction = direction;
        lights.sun_keys.clear();
        self.worker.send(Command::SetSun(direction));
    }

    /// Sets (or removes) the point light in the window's scene and the worker's.
    fn set_point_light(&mut self, light: Option<grassbench::scene::PointLight>) {
        self.scene.config.lights.point = light.clone();
        self.worker.send(Command::SetPointLight(light));
    }

    /// Adds a `kind` primitive at the ground under `ndc` of pane `k`'s picture.
    fn spawn_at(&mut self, k: usize, ndc: Vec2, kind: SpawnKind) {
        let Some(pane) = self.panes.get(k) else {
            return;
        };
        let f = self.clock.index();
        // The camera the worker draws pane `k` with (as `World::camera` makes it).
        let mut camera = self.scene.camera_at(f, pane.full_size);
        if let Some((eye, forward)) = self.camera.pose(&self.scene) {
            camera.eye = eye;
            camera.forward = forward.normalize_or(camera.forward);
        }
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

    /// Gives the worker's world the wind settings of the panel.
    fn apply_wind(&mut self) {
        match self.wind.config() {
            Ok(config) => {
                self.wind.error = None;
                self.scene.config.wind = config.clone();
                self.worker.send(Command::SetWind(config));
            }
            Err(e) => self.wind.error = Some(format!("{e:#}")),
        }
    }

    /// The command line's `--spawn`, `--sun`, `--point-light` and `--wipe`, applied after the
    /// first frame as the panel's controls, the mouse and the keys would.
    fn apply_startup(&mut self) {
        if !self.startup_pending || self.clock.index() == 0 || self.panes.is_empty() {
            return;
        }
        self.startup_pending = false;
        if let Some(kind) = self.args.spawn {
            self.spawn_at(0, Vec2::ZERO, kind);
        }
        if let Some(sun) = self.args.sun {
            self.set_sun(super::sun_direction(sun));
        }
        if let Some(position) = self.args.point_light {
            let light = grassbench::scene::PointLight {
                position,
                ..views::lights::default_point_light(&self.scene)
            };
            self.set_point_light(Some(light));
        }
        // The wipe view was switched on at the start; its picture is laid out now: drag its
        // divider from the middle to where `--wipe` says, then press the flip key if asked.
        if let (Some(split), Some(script)) = (self.args.wipe, self.script.as_mut())
            && let Some(Some(pic)) = self.pane_rects.first()
        {
            let y = pic.center().y + pic.height() * 0.2;
            let from = egui::pos2(self.wipe.divider_x(*pic), y);
            let to = egui::pos2(pic.min.x + split * pic.width(), y);
            script.drag(from, to);
            if self.args.flip {
                script.key(FLIP_KEY);
            }
        }
    }

    /// Asks the worker for the clock's frame of every pane shown, draws the panes' latest
    /// finished frames in a grid ([`grid::show`]) and acts on the pointer there (camera,
    /// spawn tool, the wipe view's divider) and the keys.
    fn central(&mut self, ui: &mut egui::Ui) {
        let f = self.clock.index();
        let moving = self.auto_preview && (self.camera_moving || self.clock.playing);
        let wants = (0..self.panes.len())
            .map(|k| {
                let slow = self.panes[k]
                    .history
                    .back()
                    .is_some_and(|r| r.gpu_wall_ms > PREVIEW_THRESHOLD_MS);
                match (self.shown(k), moving && slow) {
                    (false, _) => Want::Skip,
                    (true, true) => Want::Half,
                    (true, false) => Want::Full,
                }
            })
            .collect();
        self.worker.request(Request {
            frame: f,
            camera: self.camera.pose(&self.scene),
            panes: wants,
        });

        let dt = ui.input(|i| i.stable_dt).min(0.1);
        let grid = grid::show(
            ui,
            &self.panes,
            grid::Controls {
                camera: &mut self.camera,
                spawn: self.wind.spawn,
                dt,
                figures: &mut self.figures,
                wipe: &mut self.wipe,
            },
        );
        self.pane_rects = grid.pictures;
        let mut moved = grid.moved;
        self.apply_startup();
        for (k, at, kind) in grid.spawns {
            self.spawn_at(k, at, kind);
        }
        let typing = ui.ctx().egui_wants_keyboard_input();
        if self.wipe_on() && !typing && ui.input(|i| i.key_pressed(FLIP_KEY)) {
            self.wipe.flipped = !self.wipe.flipped;
        }
        // Keys move the walker even when the pointer is elsewhere.
        if !moved && !typing && matches!(self.camera, CameraMode::Walker { .. }) {
            moved |= ui.input(|i| self.camera.control(i, egui::Vec2::ZERO, 0.0, dt));
        }
        self.camera_moving = moved;
    }

    /// Where the panes lie in the window, for the script's screenshot.
    fn layout(&self, pixels_per_point: f32) -> Layout {
        let lights = &self.scene.config.lights;
        let physical = |r: &egui::Rect| {
            [
                (r.min.x * pixels_per_point).round() as u32,
                (r.min.y * pixels_per_point).round() as u32,
                (r.width() * pixels_per_point) as u32,
                (r.height() * pixels_per_point) as u32,
            ]
        };
        let wipe = self.wipe_on().then(|| {
            let (left, right) = self.wipe.sides();
            WipeLayout {
                left,
                right,
                split: self.wipe.split,
                flipped: self.wipe.flipped,
                rect: self
                    .pane_rects
                    .get(left)
                    .copied()
                    .flatten()
                    .map_or([0; 4], |r| physical(&r)),
            }
        });
        Layout {
            techniques: self.technique_ids(),
            rects: self
                .pane_rects
                .iter()
                .map(|r| r.as_ref().map_or([0; 4], physical))
                .collect(),
            frame: self.clock.index(),
            wind: self.wind.table.clone(),
            sun: Some(lights.sun_direction),
            point_light: lights.point.as_ref().map(|l| l.position),
            wipe,
            window_frame_ms: self.frame_ms.clone(),
            pane_gpu_wall_ms: self
                .panes
                .iter()
                .map(|p| p.history.iter().map(|r| r.gpu_wall_ms).collect())
                .collect(),
        }
    }

    /// Scripted mode: saves and closes the window once the last frame is shown.
    fn run_script(&mut self, ctx: &egui::Context) {
        let Some(mut script) = self.script.take() else {
            return;
        };
        let ready = self.caught_up();
        let f = self.clock.index();
        let outcome = script.poll(ctx, &self.panes, ready, f, |ppp| self.layout(ppp));
        self.script = Some(script);
        let Some(result) = outcome else {
            return;
        };
        match result {
            Err(e) => self.fail(ctx, e),
            Ok(()) => ctx.send_viewport_cmd(egui::ViewportCommand::Close),
        }
    }
}

impl eframe::App for App {
    fn raw_input_hook(&mut self, _ctx: &egui::Context, raw_input: &mut egui::RawInput) {
        if let Some(script) = self.script.as_mut() {
            script.feed(raw_input);
        }
    }

    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let now = Instant::now();
        if let Some(last) = self.last_frame.replace(now)
            && self.script.is_some()
        {
            self.frame_ms.push((now - last).as_secs_f64() * 1e3);
        }
        self.receive(ui.ctx());
        // The scene's clock moves on once the panes show its frame: every frame is drawn (or,
        // at a fast time scale, simulated), as before the panes had a thread of their own.
        if self.caught_up() || !self.clock.playing {
            self.clock.tick(self.script.as_ref().map(|s| s.frames));
        }
        // The side panel folds away to a narrow strip, leaving the panes the window.
        let mut toggle = false;
        egui::Panel::show_switched(
            ui,
            &mut self.panel_open.clone(),
            egui::Panel::left("settings folded")
                .resizable(false)
                .exact_size(30.0),
            egui::Panel::left("settings")
                .resizable(true)
                .default_size(280.0),
            |ui, expanded| {
                if expanded {
                    egui::ScrollArea::vertical().show(ui, |ui| {
                        toggle = ui.small_button("< fold the panel").clicked();
                        self.side_panel(ui);
                    });
                } else {
                    ui.add_space(4.0);
                    toggle = ui.button(">").on_hover_text("unfold the panel").clicked();
                }
            },
        );
        if toggle {
            self.panel_open = !self.panel_open;
        }
        egui::CentralPanel::default().show(ui, |ui| self.central(ui));
        if self.diff.enabled {
            views::difference::window(ui.ctx(), &mut self.diff, &self.panes);
        }
        self.run_script(ui.ctx());
        ui.ctx().request_repaint();
    }
}
