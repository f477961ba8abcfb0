//! `grassbench ui`: an eframe window comparing techniques live, side by side.
//!
//! Techniques render offscreen through the same [`World`](grassbench::runner::World),
//! [`View`](grassbench::runner::View) and frame function as headless runs; the UI only
//! displays the resulting images, so what it shows is what sweeps measure. They render on a
//! worker thread with a device of its own, which holds ONE world (scene, its GPU resources,
//! the wind, advanced once per frame) and each pane's technique and view (target, timer,
//! debug view); the window holds the clock, the camera and each pane's latest finished frame,
//! and stays responsive however long the panes take.
//!
//! | file | concept |
//! |---|---|
//! | `app.rs` | the window: the panel's sections, the panes, the frame loop |
//! | `worker.rs` | the render thread (own device): the stage, commands in, finished frames out |
//! | `stage.rs` | the one world and its panes, stepped together frame by frame |
//! | `pane.rs` | one pane on the worker: a technique, its view, its figures |
//! | `display.rs` | one pane in the window: its latest finished frame (texture) and figures |
//! | `clock.rs` | the frame shown, play, pause, time scale |
//! | `views/` | the side panel's sections, one small view each |
//! | `grid.rs` | the panes in the grid that fits them largest: pictures, overlays, pointer |
//! | `wipe.rs` | the wipe view: two panes in one picture split by a divider, flipped by a key |
//! | `overlay.rs` | figures, plot and errors drawn over a pane |
//! | `camera.rs` | the shared camera: scene path, walker, orbit |
//! | `editor.rs` | widgets generated from parameter tables (technique parameters, wind) |
//! | `diff.rs` | the difference view between two panes: its state and measure |
//! | `spawn.rs` | placing Perbet's wind primitives with a click |
//! | `screenshot.rs` | the screenshot button: every pane and a composite saved |
//! | `script.rs` | scripted mode: play N frames, save screenshots, exit |

mod app;
mod camera;
mod clock;
mod diff;
mod display;
mod editor;
mod grid;
mod overlay;
mod pane;
mod screenshot;
mod script;
mod spawn;
mod stage;
mod views;
mod wipe;
mod worker;

use std::path::PathBuf;
use std::sync::Arc;

use grassbench::GpuContext;
use grassbench::gpu::BackendChoice;
pub use spawn::SpawnKind;

pub use script::Layout;

/// Arguments of `grassbench ui`.
#[derive(Clone, Debug, clap::Args)]
pub struct UiArgs {
    /// Built-in scene name or path to a scene TOML.
    #[arg(long, short, default_value = "meadow")]
    pub scene: String,
    /// Number of panes: 1, 2 or 4.
    #[arg(long, default_value_t = 2)]
    pub panes: usize,
    /// Techniques of the panes, comma-separated (repeated to fill the panes).
    #[arg(long, short, default_value = "reference")]
    pub techniques: String,
    /// Render size of each pane, WxH.
    #[arg(long, default_value = "480x270")]
    pub size: String,
    /// 4x MSAA.
    #[arg(long)]
    pub msaa: bool,
    /// Graphics backend for the window and the renders (default: $GRASSBENCH_BACKEND or auto).
    #[arg(long)]
    pub backend: Option<String>,
    /// Scripted mode: play this many frames, save screenshots to `--screenshot`, exit.
    #[arg(long)]
    pub frames: Option<u64>,
    /// Scripted mode: where to save the window screenshot (PNG); pane images and the layout
    /// (`<name>.layout.toml`) go beside it.
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// Folder the screenshot button saves into.
    #[arg(long, default_value = "screenshots")]
    pub screenshot_dir: PathBuf,
    /// Scripted mode: after the first frame, add this wind primitive (Perbet Sec. 3.3) at the
    /// ground under the centre of pane 1, as a click with the panel's spawn tool would.
    #[arg(long, value_enum)]
    pub spawn: Option<SpawnKind>,
    /// Scripted mode: after the first frame, put the sun at `AZIMUTH,ELEVATION` (degrees), as
    /// the panel's sun sliders would.
    #[arg(long, value_parser = parse_sun, allow_hyphen_values = true)]
    pub sun: Option<[f32; 2]>,
    /// Scripted mode: after the first frame, switch on a point light at `X,Y,Z` (m, world), as
    /// the panel's point-light controls would.
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true)]
    pub point_light: Option<[f32; 3]>,
    /// Wipe view of panes 1 and 2 (needs 2 panes or more); scripted mode: after the first
    /// frame, drag its divider from the middle to SPLIT (0 = left edge, 1 = right edge), as the
    /// mouse would.
    #[arg(long, value_parser = parse_split)]
    pub wipe: Option<f32>,
    /// Scripted mode, with `--wipe`: after the drag, press the key that swaps the two sides.
    #[arg(long, requires = "wipe")]
    pub flip: bool,
    /// Start with the side panel folded away (the panes take the whole window).
    #[arg(long)]
    pub hide_panel: bool,
}

/// A divider position in [0, 1].
fn parse_split(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!(
            "{text}: expected a position from 0 (left) to 1 (right), e.g. 0.3"
        )),
    }
}

/// `X,Y,Z` in metres, finite.
fn parse_point(text: &str) -> Result<[f32; 3], String> {
    let bad = |why: String| format!("{text}: {why}; expected X,Y,Z in metres, e.g. 0,3,-2");
    let parts: Vec<f32> = text
        .split(',')
        .map(|p| p.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|e| bad(e.to_string()))?;
    match parts[..] {
        [x, y, z] if parts.iter().all(|v| v.is_finite()) => Ok([x, y, z]),
        _ => Err(bad("three finite numbers needed".into())),
    }
}

/// `AZIMUTH,ELEVATION` in degrees, elevation in [2, 90].
fn parse_sun(text: &str) -> Result<[f32; 2], String> {
    let parts: Vec<f32> = text
        .split(',')
        .map(|p| p.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{text}: {e}; expected AZIMUTH,ELEVATION in degrees, e.g. 30,20"))?;
    match parts[..] {
        [a, e] if a.is_finite() && (2.0..=90.0).contains(&e) => Ok([a, e]),
        _ => Err(format!(
            "{text}: expected AZIMUTH,ELEVATION in degrees with the elevation in [2, 90], e.g. 30,20"
        )),
    }
}

/// The unit vector towards a sun at `azimuth` and `elevation` (degrees; azimuth from +x
/// towards +z).
pub fn sun_direction([azimuth, elevation]: [f32; 2]) -> [f32; 3] {
    let (a, e) = (azimuth.to_radians(), elevation.to_radians());
    [a.cos() * e.cos(), e.sin(), a.sin() * e.cos()]
}

/// Opens the window and runs until it is closed (or the script ends).
pub fn run(args: &UiArgs) -> anyhow::Result<()> {
    // Validate everything that can be validated before opening a window.
    crate::scenes::load(&args.scene)?;
    crate::registry::select(&args.techniques)?;
    grassbench::target::Size::parse(&args.size)?;
    if ![1, 2, 4].contains(&args.panes) {
        anyhow::bail!("--panes must be 1, 2 or 4 (got {})", args.panes);
    }
    if args.wipe.is_some() && args.panes < 2 {
        anyhow::bail!("--wipe shows panes 1 and 2: it needs --panes 2 or 4");
    }
    let choice = match &args.backend {
        Some(b) => b.parse::<BackendChoice>()?,
        None => BackendChoice::from_env()?,
    };
    // The device requests what any registered technique needs on this scene (a pane can switch
    // to any of them), the same way the headless commands request theirs.
    let scene = crate::scenes::load(&args.scene)?;
    let none = toml::Table::new();
    let needs = crate::commands::needs(
        crate::registry::TECHNIQUES
            .iter()
            .map(|entry| (entry, &scene, &none)),
    )?;
    // The panes render on the worker's device: it requests the same.
    let worker_needs = needs.clone();
    let mut setup = eframe::egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.instance_descriptor.backends = choice.backends();
    let setup = eframe::egui_wgpu::WgpuSetupCreateNew {
        device_descriptor: Arc::new(move |adapter: &eframe::wgpu::Adapter| {
            eframe::wgpu::DeviceDescriptor {
                label: Some("grassbench ui"),
                required_features: adapter.features() & eframe::wgpu::Features::TIMESTAMP_QUERY,
                required_limits: GpuContext::request_limits(adapter, &needs),
                ..Default::default()
            }
        }),
        ..setup
    };
    let options = eframe::NativeOptions {
        viewport: eframe::egui::ViewportBuilder::default()
            .with_inner_size([1280.0, 800.0])
            .with_title("grassbench"),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: eframe::egui_wgpu::WgpuConfiguration {
            wgpu_setup: eframe::egui_wgpu::WgpuSetup::CreateNew(setup),
            ..Default::default()
        },
        ..Default::default()
    };
    let args = args.clone();
    let outcome = Arc::new(std::sync::Mutex::new(None::<anyhow::Error>));
    let outcome_app = outcome.clone();
    eframe::run_native(
        "grassbench",
        options,
        Box::new(move |cc| {
            // The panes render on the worker's own device (on `choice`), not on eframe's.
            let app = app::App::new(cc, choice, worker_needs, args, outcome_app)?;
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| anyhow::anyhow!("the window could not be opened: {e}. On a machine without a display run it under Xvfb: `xvfb-run -a grassbench ui ...`"))?;
    if let Some(e) = outcome.lock().ok().and_then(|mut o| o.take()) {
        return Err(e);
    }
    Ok(())
}
