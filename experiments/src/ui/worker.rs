//! The render worker: a thread with its own device that owns the [`Stage`] (the world, the
//! panes' techniques and targets) and renders what the window last asked for, so the window
//! answers input within its own frame however long the panes take.
//!
//! The window sends [`Command`]s: a [`Request`] (frame, camera, which panes, at which
//! resolution) whenever it changes, and every setting changed in the panel. The worker
//! applies every waiting command, keeps only the latest request, renders it, and sends each
//! pane's finished frame back as a [`Report::Frame`] with its image read back; the window
//! copies that into an egui texture. A device of its own (not eframe's) keeps the panes' long
//! submissions off the queue the window presents with: on a software rasteriser one queue
//! runs its submissions in order, so sharing it would make every window frame wait for the
//! panes.

use std::path::PathBuf;
use std::sync::mpsc::{self, Receiver, Sender};
use std::time::{Duration, Instant};

use eframe::egui;
use grassbench::glam::Vec3;
use grassbench::gpu::{AdapterSummary, BackendChoice};
use grassbench::runner::FrameRecord;
use grassbench::scene::PointLight;
use grassbench::target::Size;
use grassbench::technique::TechniqueInfo;
use grassbench::wind::WindConfig;
use grassbench::{GpuContext, Scene};

use super::stage::Stage;

/// How the window wants one pane drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Want {
    /// Not at all (hidden, e.g. by the wipe view).
    Skip,
    /// At full resolution.
    Full,
    /// At half resolution (the camera moves and frames are slow).
    Half,
}

/// What the window shows now: the worker brings the panes there.
#[derive(Clone, Debug, PartialEq)]
pub struct Request {
    /// Scene frame.
    pub frame: u64,
    /// Eye and view direction, or `None` for the scene's path.
    pub camera: Option<(Vec3, Vec3)>,
    /// Each pane's want, in order (missing panes are skipped).
    pub panes: Vec<Want>,
}

/// What the window asks of the worker.
#[derive(Debug)]
pub enum Command {
    /// Bring the panes to this frame and camera.
    Render(Request),
    /// Show `scene` (loaded as `name`) with `count` panes of techniques `ids`, caught up to
    /// `frame`.
    LoadScene {
        /// Name the scene was loaded by.
        name: String,
        /// The scene.
        scene: Box<Scene>,
        /// Panes.
        count: usize,
        /// Techniques, cycled over the panes.
        ids: Vec<String>,
        /// Frame to catch up to.
        frame: u64,
    },
    /// Rebuild `count` panes of techniques `ids` at `size`, with MSAA or not, caught up to
    /// `frame`.
    BuildPanes {
        /// Panes.
        count: usize,
        /// Techniques, cycled over the panes.
        ids: Vec<String>,
        /// Size of each pane at full resolution.
        size: Size,
        /// 4x MSAA.
        msaa: bool,
        /// Frame to catch up to.
        frame: u64,
    },
    /// Rebuild every pane's technique at this frame (restart).
    RecreateAll(u64),
    /// Switch a pane to a technique (default parameters) at `frame`.
    SetTechnique {
        /// Pane.
        pane: usize,
        /// Technique id.
        id: String,
        /// Frame to catch up to.
        frame: u64,
    },
    /// Rebuild a pane's technique with these parameter overrides at `frame`.
    Recreate {
        /// Pane.
        pane: usize,
        /// Parameter overrides.
        overrides: toml::Table,
        /// Frame to catch up to.
        frame: u64,
        /// The window's number of this edit (reported back in [`PaneSummary::edit`]).
        edit: u64,
    },
    /// Show a pane's debug view (0 = none).
    SetDebugView {
        /// Pane.
        pane: usize,
        /// Debug view.
        view: u32,
    },
    /// Replace the wind (restarted from time 0).
    SetWind(WindConfig),
    /// Point the sun this way (unit vector towards it).
    SetSun([f32; 3]),
    /// Switch the point light on (with these settings) or off.
    SetPointLight(Option<PointLight>),
    /// Save every pane at full resolution, and their composite, into a new folder under
    /// `root`.
    Screenshot {
        /// Frame.
        frame: u64,
        /// Camera.
        camera: Option<(Vec3, Vec3)>,
        /// Folder the new folder goes into.
        root: PathBuf,
    },
}

/// What the window knows of one pane's technique.
#[derive(Clone, Debug)]
pub struct PaneSummary {
    /// Technique id.
    pub technique_id: String,
    /// Who the technique is, once created.
    pub info: Option<TechniqueInfo>,
    /// Its parameters in use.
    pub params: toml::Table,
    /// The last error.
    pub error: Option<String>,
    /// Whether the technique exists (not failed).
    pub alive: bool,
    /// The window's number of the last parameter edit applied ([`Command::Recreate`]).
    pub edit: u64,
}

/// What the worker tells the window.
#[derive(Debug)]
pub enum Report {
    /// The worker's device is ready.
    Ready(AdapterSummary),
    /// The worker could not start (no device): nothing will be rendered.
    Failed(String),
    /// The panes now (after building, switching or a failure). `epoch` counts the times the
    /// panes were rebuilt: frames of older epochs are stale.
    Panes {
        /// Rebuilds so far.
        epoch: u64,
        /// Every pane.
        panes: Vec<PaneSummary>,
    },
    /// A pane finished a frame.
    Frame {
        /// Rebuilds so far.
        epoch: u64,
        /// Pane.
        pane: usize,
        /// Technique that drew it.
        technique_id: String,
        /// Scene frame.
        frame: u64,
        /// Its figures.
        record: Box<FrameRecord>,
        /// Its picture.
        image: image::RgbaImage,
        /// Drawn at half resolution.
        preview: bool,
    },
    /// The wind was replaced (`None`) or refused (why).
    Wind(Option<String>),
    /// A line for the panel's status (screenshot saved, a failure).
    Status(String),
}

/// The window's end of the worker.
pub struct Worker {
    /// `None` once dropped (the worker then stops after its current frame).
    commands: Option<Sender<Command>>,
    reports: Receiver<Report>,
    last: Option<Request>,
}

/// What the worker starts with.
pub struct Start {
    /// Backend of its device.
    pub backend: BackendChoice,
    /// The limits its device requests (what the techniques need: `commands::needs`), lowered
    /// to what the adapter offers.
    pub limits: grassbench::wgpu::Limits,
    /// Scene name.
    pub scene_name: String,
    /// Scene.
    pub scene: Scene,
    /// Pane size.
    pub size: Size,
    /// 4x MSAA.
    pub msaa: bool,
    /// Panes.
    pub count: usize,
    /// Their techniques, cycled.
    pub ids: Vec<String>,
}

impl Worker {
    /// Starts the worker thread; `ctx` is woken whenever it reports.
    pub fn start(start: Start, ctx: egui::Context) -> anyhow::Result<Self> {
        let (commands, inbox) = mpsc::channel();
        let (outbox, reports) = mpsc::channel();
        std::thread::Builder::new()
            .name("grassbench panes".into())
            .spawn(move || {
                let out = Outbox { tx: outbox, ctx };
                run(start, &inbox, &out);
            })?;
        Ok(Self {
            commands: Some(commands),
            reports,
            last: None,
        })
    }

    /// Sends a command (lost if the worker has stopped: it reported why).
    pub fn send(&self, command: Command) {
        if let Some(commands) = &self.commands {
            let _ = commands.send(command);
        }
    }

    /// Sends `request` unless it is the one sent last.
    pub fn request(&mut self, request: Request) {
        if self.last.as_ref() != Some(&request) {
            self.last = Some(request.clone());
            self.send(Command::Render(request));
        }
    }

    /// Forgets the last request, so the next is sent even if equal (after a rebuild).
    pub fn forget_request(&mut self) {
        self.last = None;
    }

    /// Reports waiting, without blocking.
    pub fn reports(&self) -> impl Iterator<Item = Report> + '_ {
        self.reports.try_iter()
    }
}

/// The longest the window waits, when it closes, for the worker to finish its frame.
const STOP_WAIT: Duration = Duration::from_secs(20);

impl Drop for Worker {
    /// Stops the worker and waits (at most [`STOP_WAIT`]) for it to finish the frame it is
    /// drawing: the process must not exit, tearing the driver down, while its device works.
    fn drop(&mut self) {
        self.commands = None;
        let deadline = Instant::now() + STOP_WAIT;
        // The reports' channel closes when the worker's thread ends.
        while let Some(left) = deadline.checked_duration_since(Instant::now()) {
            match self.reports.recv_timeout(left) {
                Ok(_) => {}
                Err(_) => break,
            }
        }
    }
}

/// The worker's end: reports, each waking the window.
struct Outbox {
    tx: Sender<Report>,
    ctx: egui::Context,
}

impl Outbox {
    fn send(&self, report: Report) {
        let _ = self.tx.send(report);
        self.ctx.request_repaint();
    }
}

/// The worker's state.
struct State {
    stage: Stage,
    epoch: u64,
    request: Option<Request>,
    camera: Option<Option<(Vec3, Vec3)>>,
    /// Commands taken from the channel while drawing, to apply next.
    waiting: Vec<Command>,
}

/// The worker thread: its device, then commands until the window goes.
fn run(start: Start, inbox: &Receiver<Command>, out: &Outbox) {
    let setup = || -> anyhow::Result<Stage> {
        let gpu = GpuContext::for_needs(start.backend, &start.limits)?;
        // The worker lives as long as the process: leak the context so the world can borrow it.
        let gpu: &'static GpuContext = Box::leak(Box::new(gpu));
        out.send(Report::Ready(gpu.summary.clone()));
        let mut stage = Stage::new(gpu, &start.scene_name, start.scene, start.size, start.msaa)?;
        stage.build_panes(start.count, &start.ids, 0)?;
        Ok(stage)
    };
    let stage = match setup() {
        Ok(stage) => stage,
        Err(e) => {
            out.send(Report::Failed(format!("{e:#}")));
            return;
        }
    };
    let mut state = State {
        stage,
        epoch: 0,
        request: None,
        camera: None,
        waiting: Vec::new(),
    };
    state.summarise(out);
    // Block for a command, apply every one waiting (less those a later one replaces), render
    // the latest request; again.
    loop {
        let mut waiting = std::mem::take(&mut state.waiting);
        if waiting.is_empty() {
            match inbox.recv() {
                Ok(command) => waiting.push(command),
                // The window has gone.
                Err(_) => return,
            }
        }
        waiting.extend(inbox.try_iter());
        for command in coalesce(waiting) {
            state.apply(command, out);
        }
        state.render(out, inbox);
    }
}

/// What a later command of the same kind replaces (dragging a parameter sends one edit a
/// window frame: only the last waiting one is worth a rebuild).
#[derive(PartialEq)]
enum Slot {
    Render,
    Recreate(usize),
    DebugView(usize),
    Wind,
    Sun,
    PointLight,
}

fn slot(command: &Command) -> Option<Slot> {
    Some(match command {
        Command::Render(_) => Slot::Render,
        Command::Recreate { pane, .. } => Slot::Recreate(*pane),
        Command::SetDebugView { pane, .. } => Slot::DebugView(*pane),
        Command::SetWind(_) => Slot::Wind,
        Command::SetSun(_) => Slot::Sun,
        Command::SetPointLight(_) => Slot::PointLight,
        _ => return None,
    })
}

/// `commands` less each one a later command of the same slot replaces, in order.
fn coalesce(commands: Vec<Command>) -> Vec<Command> {
    let slots: Vec<Option<Slot>> = commands.iter().map(slot).collect();
    commands
        .into_iter()
        .enumerate()
        .filter(|(i, _)| {
            slots[*i]
                .as_ref()
                .is_none_or(|s| !slots[i + 1..].iter().any(|t| t.as_ref() == Some(s)))
        })
        .map(|(_, c)| c)
        .collect()
}

impl State {
    /// Sends the panes' summaries.
    fn summarise(&self, out: &Outbox) {
        let panes = self
            .stage
            .panes
            .iter()
            .map(|p| PaneSummary {
                technique_id: p.technique_id.clone(),
                info: p.technique.as_ref().map(|t| t.info()),
                params: p
                    .technique
                    .as_ref()
                    .map(|t| t.param_table())
                    .unwrap_or_default(),
                error: p.error.clone(),
                alive: p.technique.is_some(),
                edit: p.edit,
            })
            .collect();
        out.send(Report::Panes {
            epoch: self.epoch,
            panes,
        });
    }

    fn apply(&mut self, command: Command, out: &Outbox) {
        let stage = &mut self.stage;
        let status = |r: anyhow::Result<()>| {
            if let Err(e) = r {
                out.send(Report::Status(format!("{e:#}")));
            }
        };
        match command {
            Command::Render(request) => {
                if self.camera != Some(request.camera) {
                    self.camera = Some(request.camera);
                    stage.invalidate();
                }
                self.request = Some(request);
                return;
            }
            Command::LoadScene {
                name,
                scene,
                count,
                ids,
                frame,
            } => {
                status(
                    stage
                        .set_scene(&name, *scene)
                        .and_then(|()| stage.build_panes(count, &ids, frame)),
                );
                self.epoch += 1;
            }
            Command::BuildPanes {
                count,
                ids,
                size,
                msaa,
                frame,
            } => {
                stage.size = size;
                stage.msaa = msaa;
                status(stage.build_panes(count, &ids, frame));
                self.epoch += 1;
            }
            Command::RecreateAll(frame) => stage.recreate_all(frame),
            Command::SetTechnique { pane, id, frame } => stage.set_technique(pane, &id, frame),
            Command::Recreate {
                pane,
                overrides,
                frame,
                edit,
            } => {
                if let Some(p) = stage.panes.get_mut(pane) {
                    p.overrides = overrides;
                    p.edit = edit;
                }
                stage.recreate(&[pane], frame);
            }
            Command::SetDebugView { pane, view } => {
                if let Some(p) = stage.panes.get_mut(pane) {
                    p.view.debug_view = view;
                    p.invalidate();
                }
                return;
            }
            Command::SetWind(config) => {
                let result = stage.set_wind(config);
                out.send(Report::Wind(result.err().map(|e| e.to_string())));
                return;
            }
            Command::SetSun(direction) => {
                stage.set_sun(direction);
                return;
            }
            Command::SetPointLight(light) => {
                stage.set_point_light(light);
                return;
            }
            Command::Screenshot {
                frame,
                camera,
                root,
            } => {
                let line = match super::screenshot::save(stage, frame, camera, &root) {
                    Ok(dir) => format!("saved to {}", dir.display()),
                    Err(e) => format!("{e:#}"),
                };
                out.send(Report::Status(line));
                // The panes now hold full-resolution frames the window has not seen.
                stage.invalidate();
                return;
            }
        }
        self.summarise(out);
    }

    /// Brings the panes the latest request wants to its frame, sending each finished frame.
    /// Between panes it looks at what the window sent meanwhile: a camera moved at the same
    /// frame is drawn from by the panes still to draw (the window's pictures follow a drag
    /// within one pane's frame, not all of theirs); the rest waits for the next round.
    fn render(&mut self, out: &Outbox, inbox: &Receiver<Command>) {
        let Some(request) = &self.request else {
            return;
        };
        let epoch = self.epoch;
        let failed_before = self.failed();
        let waiting = &mut self.waiting;
        let mut camera = request.camera;
        self.stage.render(
            request.frame,
            request.camera,
            true,
            |k, _| match request.panes.get(k).copied().unwrap_or(Want::Skip) {
                Want::Skip => None,
                Want::Full => Some(false),
                Want::Half => Some(true),
            },
            |k, pane| {
                let (Some(record), Some(image)) = (pane.history.back(), &pane.last_image) else {
                    return;
                };
                out.send(Report::Frame {
                    epoch,
                    pane: k,
                    technique_id: pane.technique_id.clone(),
                    frame: request.frame,
                    record: Box::new(record.clone()),
                    image: image.clone(),
                    preview: pane.preview,
                });
            },
            || {
                waiting.extend(inbox.try_iter());
                let newest = waiting.iter().rev().find_map(|c| match c {
                    Command::Render(r) => Some(r),
                    _ => None,
                })?;
                let moved = newest.frame == request.frame && newest.camera != camera;
                moved.then(|| {
                    camera = newest.camera;
                    camera
                })
            },
        );
        // The panes stand at this camera now (those drawn before it moved are marked stale).
        self.camera = Some(camera);
        if self.failed() != failed_before {
            self.summarise(out);
        }
    }

    /// Which panes have failed.
    fn failed(&self) -> Vec<bool> {
        self.stage
            .panes
            .iter()
            .map(|p| p.technique.is_none())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    /// Reports until `done` says enough (panics after a minute).
    fn until(worker: &Worker, mut done: impl FnMut(&Report) -> bool) -> Vec<Report> {
        let start = Instant::now();
        let mut seen = Vec::new();
        loop {
            for report in worker.reports() {
                if let Report::Failed(e) = &report {
                    panic!("the worker failed: {e}");
                }
                let enough = done(&report);
                seen.push(report);
                if enough {
                    return seen;
                }
            }
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "waited: {seen:?}"
            );
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    fn frame_of(report: &Report) -> Option<(usize, u64)> {
        match report {
            Report::Frame { pane, frame, .. } => Some((*pane, *frame)),
            _ => None,
        }
    }

    fn image_of(reports: &[Report], k: usize) -> image::RgbaImage {
        reports
            .iter()
            .rev()
            .find_map(|r| match r {
                Report::Frame { pane, image, .. } if *pane == k => Some(image.clone()),
                _ => None,
            })
            .unwrap()
    }

    #[test]
    fn the_worker_draws_the_panes_asked_for_and_reports_each_frame() {
        let base = crate::scenes::load("meadow").unwrap();
        let mut config = base.config.clone();
        config.grass.density *= 0.02;
        let scene = Scene::from_config(config, base.base_dir.clone()).unwrap();
        let mut worker = Worker::start(
            Start {
                backend: BackendChoice::from_env().unwrap(),
                limits: grassbench::wgpu::Limits::default(),
                scene_name: "meadow".into(),
                scene,
                size: Size {
                    width: 96,
                    height: 54,
                },
                msaa: false,
                count: 2,
                ids: vec!["reference".into(), "zhang".into()],
            },
            egui::Context::default(),
        )
        .unwrap();
        let panes = until(&worker, |r| matches!(r, Report::Panes { .. }));
        match panes.last() {
            Some(Report::Panes { epoch: 0, panes }) => {
                assert_eq!(panes.len(), 2);
                assert!(
                    panes.iter().all(|p| p.alive && p.info.is_some()),
                    "{panes:?}"
                );
                assert_eq!(panes[1].technique_id, "zhang");
            }
            other => panic!("{other:?}"),
        }
        let request = |frame, panes: &[Want]| Request {
            frame,
            camera: None,
            panes: panes.to_vec(),
        };
        // Both panes drawn, each reported with its picture.
        worker.request(request(3, &[Want::Full, Want::Full]));
        let mut drawn = Vec::new();
        let first = until(&worker, |r| {
            drawn.extend(frame_of(r));
            drawn.len() == 2
        });
        assert_eq!(drawn, [(0, 3), (1, 3)]);
        assert_eq!(image_of(&first, 0).dimensions(), (96, 54));
        // Pane 2 hidden: only pane 1 draws frame 4.
        worker.request(request(4, &[Want::Full, Want::Skip]));
        until(&worker, |r| frame_of(r) == Some((0, 4)));
        // A new sun, then both wanted: pane 1 redraws frame 4 in the new light, pane 2 catches
        // up, and the window's last request is the one drawn.
        worker.send(Command::SetSun(crate::ui::sun_direction([-60.0, 25.0])));
        worker.request(request(4, &[Want::Full, Want::Full]));
        let mut drawn = Vec::new();
        let lit = until(&worker, |r| {
            drawn.extend(frame_of(r));
            drawn.len() == 2
        });
        assert_eq!(drawn, [(0, 4), (1, 4)]);
        assert_ne!(image_of(&lit, 0), image_of(&first, 0));
        // Rebuilt with one pane: a new epoch.
        worker.send(Command::BuildPanes {
            count: 1,
            ids: vec!["reference".into()],
            size: Size {
                width: 96,
                height: 54,
            },
            msaa: false,
            frame: 4,
        });
        let rebuilt = until(&worker, |r| matches!(r, Report::Panes { .. }));
        assert!(matches!(
            rebuilt.last(),
            Some(Report::Panes { epoch: 1, panes }) if panes.len() == 1
        ));
    }

    #[test]
    fn only_the_last_of_each_kind_of_waiting_edit_is_applied() {
        let recreate = |pane, edit| Command::Recreate {
            pane,
            overrides: toml::Table::new(),
            frame: 0,
            edit,
        };
        let kept = coalesce(vec![
            recreate(0, 1),
            Command::SetSun([0.0, 1.0, 0.0]),
            recreate(1, 2),
            Command::RecreateAll(0),
            recreate(0, 3),
            Command::SetSun([1.0, 0.0, 0.0]),
            Command::RecreateAll(0),
        ]);
        let names: Vec<String> = kept
            .iter()
            .map(|c| match c {
                Command::Recreate { pane, edit, .. } => format!("recreate {pane} #{edit}"),
                Command::SetSun(d) => format!("sun {d:?}"),
                Command::RecreateAll(_) => "all".into(),
                other => format!("{other:?}"),
            })
            .collect();
        assert_eq!(
            names,
            [
                "recreate 1 #2",
                "all",
                "recreate 0 #3",
                "sun [1.0, 0.0, 0.0]",
                "all"
            ]
        );
    }
}
