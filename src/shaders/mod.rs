//! WGSL shared by every shader: the prelude (bind group 0, terrain and wind lookups, lighting,
//! fog) and the background (sky, ground, props, moving object); and [`pipeline`], the one
//! description of a render pipeline every technique builds on.
//!
//! Technique shaders are stored without the prelude and composed at load time, so one copy of
//! the terrain lookup, the wind sampling and the lighting serves every technique.

mod fetches;
mod kind;
mod layout;
pub mod pipeline;

pub use fetches::{TextureFetches, entry_fetches};
pub use kind::{FragmentKind, Module, discarding_fragment_entries};
pub use layout::struct_size;
pub use pipeline::{
    PipelineCost, PipelineSpec, RenderPipeline, depth_less, depth_test, render_pipeline,
};

/// The prelude: `Globals`, bind group 0, `terrain_height`, `terrain_normal`, `terrain_density`,
/// `terrain_covering`, `wind_at`, `shade`, `shade_leaf` (and its parts `facing_viewer`,
/// `leaf_lambert`, `leaf_irradiance`, `direct_occlusion`, `point_light`), `sky_color`,
/// `apply_fog` (`fog_factor`), hashes.
pub const PRELUDE: &str = include_str!("prelude.wgsl");

/// The core's background shader: sky, ground, props (trees and stones) and moving object
/// (without the prelude).
pub const BACKGROUND: &str = include_str!("background.wgsl");

/// Prelude + `source`.
pub fn compose(source: &str) -> String {
    format!("{PRELUDE}\n{source}")
}

/// Creates a shader module from a technique's WGSL (composed with the prelude), noting which
/// of its fragment entry points can `discard` (what makes a pipeline's fragments alpha-tested,
/// [`FragmentKind`]) and what each entry point fetches from textures ([`TextureFetches`]).
pub fn module(device: &wgpu::Device, label: &str, source: &str) -> Module {
    let composed = compose(source);
    let discarding = discarding_fragment_entries(&composed);
    let fetches = entry_fetches(&composed);
    Module {
        raw: device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(composed.into()),
        }),
        discarding,
        fetches,
    }
}
