//! # grassbench — the shared core
//!
//! Everything the grass techniques have in common, so that the only difference between two
//! images is the technique that drew the grass:
//!
//! | module | concept |
//! |---|---|
//! | [`gpu`] | headless instance, adapter and device; error scopes that turn wgpu validation errors into [`Error`]s |
//! | [`target`] | the offscreen colour + depth render target (optional 4x MSAA) and its read-back to an image |
//! | [`terrain`] | heightmap, density map, covering map; bilinear sampling on the CPU and their GPU copies |
//! | [`camera`] | perspective camera, frustum, deterministic camera paths keyed by time |
//! | [`wind`] | the [`wind::WindField`] abstraction every wind model implements, and its GPU copy |
//! | [`grass`] | the scene's grass population: a deterministic field of blades every technique can draw from |
//! | [`scene`] | scene files (TOML): terrain + camera path + wind + lights + sky + grass + seed |
//! | [`files`] | result files written atomically (a crash never leaves half a file), CSV |
//! | [`keyframes`] | values keyed by scene time: paths of the moving object, blasts, lights |
//! | [`object`] | the scene's moving object (a sphere on a path) every technique sees |
//! | [`frame`] | [`frame::FrameInputs`] (time is passed in) and the per-frame GPU globals |
//! | [`technique`] | the [`technique::GrassTechnique`] trait, its contexts and the timed [`technique::FrameEncoder`] |
//! | [`runner`] | one technique x one scene x N frames, timed stage by stage, written as CSV |
//! | [`cost`] | the cost model: unit costs fitted from calibration micro-workloads, a frame's GPU time predicted from its measured work |
//! | [`metrics`] | FLIP, SSIM, PSNR, grass coverage and difference images |
//!
//! Techniques live in their own crates under `techniques/`, the `grassbench` command and the
//! registry of techniques under `experiments/`.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

pub mod calibration;
pub mod camera;
pub mod color;
pub mod compare;
pub mod cost;
pub mod error;
pub mod files;
pub mod frame;
pub mod gpu;
pub mod grass;
pub mod keyframes;
pub mod metrics;
pub mod object;
pub mod params;
pub mod rng;
pub mod runner;
pub mod scene;
pub mod shaders;
pub mod sweep;
pub mod target;
pub mod technique;
pub mod terrain;
pub mod wind;

pub use error::{Error, Result};
pub use frame::FrameInputs;
pub use gpu::GpuContext;
pub use scene::Scene;
pub use target::RenderTarget;
pub use technique::{FrameEncoder, GrassTechnique, InitContext, TechniqueInfo, TechniqueStats};

/// Re-exported so that technique crates and tests use exactly the core's versions.
pub use {bytemuck, glam, image, wgpu};
