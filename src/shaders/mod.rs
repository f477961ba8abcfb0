//! WGSL shared by every shader: the prelude (bind group 0, terrain and wind lookups, lighting,
//! fog) and the background (sky, ground, props, moving object); and [`pipeline`], the one
//! description of a render pipeline every technique builds on.
//!
//! Technique shaders are stored without the prelude and composed at load time, so one copy of
//! the terrain lookup, the wind sampling and the lighting serves every technique.

mod branches;
mod kind;
mod layout;
mod loops;
mod ops;
pub mod pipeline;
mod trips;
mod walk;

pub use branches::{UniformBranch, uniform_branches};
pub use kind::{FragmentKind, Module, discarding_fragment_entries, fragment_inputs};
pub use layout::struct_size;
pub use loops::uniform_bound_loops;
pub use ops::{Bound, ShaderOps, entry_ops, is_float, texture_globals};
pub use pipeline::{
    ComputePipeline, PassOps, PipelineCost, PipelineSpec, RenderPipeline, buffer_entry,
    compute_pipeline, depth_less, depth_test, render_pipeline,
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
/// [`FragmentKind`]) and what each entry point does beyond its invocation (texture fetches, transcendentals:
/// [`ShaderOps`]).
pub fn module(device: &wgpu::Device, label: &str, source: &str) -> Module {
    module_with_formats(device, label, source, &[])
}

/// The prelude's textures (bind group 0) with the formats the core binds there: every
/// module's fetches of them are priced by their format ([`module_with_formats`]).
pub const PRELUDE_TEXTURES: [(&str, wgpu::TextureFormat); 4] = [
    ("height_map", crate::terrain::HEIGHT_FORMAT),
    ("density_map", crate::terrain::DENSITY_FORMAT),
    ("covering_map", crate::terrain::COVERING_FORMAT),
    ("wind_map", crate::wind::TEXTURE_FORMAT),
];

/// [`module`] for a shader that fetches textures of its own: `formats` names the module's
/// texture globals with the format of what is bound to them, so the loads and samples of
/// floating-point ones ([`is_float`]) are counted as [`ShaderOps::float_loads`] and
/// [`ShaderOps::float_samples`] (WGSL's texture types do not say the format; a texture not
/// named is counted as normalised, and the prelude's are always named: [`PRELUDE_TEXTURES`]).
/// Name a texture by the same constant its creation uses, so the count follows a change of
/// format.
pub fn module_with_formats(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    formats: &[(&str, wgpu::TextureFormat)],
) -> Module {
    module_with_bindings(device, label, source, formats, &[])
}

/// [`module_with_formats`] for a shader some of whose filtered samples read one mip level
/// however their level falls: `single_level` names the texture globals bound to textures of
/// one level and the sampler globals bound to samplers whose mipmap filter is `Nearest`, so
/// their samples are not counted as [`ShaderOps::mip_blends`] (WGSL's types say neither). Name
/// them where the texture or sampler is made the way they are, so the count follows a change.
pub fn module_with_bindings(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    formats: &[(&str, wgpu::TextureFormat)],
    single_level: &[&str],
) -> Module {
    let composed = compose(source);
    let (discarding, parsed) = analyse(&composed);
    Module {
        raw: device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(composed.into()),
        }),
        discarding,
        parsed,
        float: float_textures(formats)
            .into_iter()
            .map(String::from)
            .collect(),
        single_level: single_level.iter().map(|n| String::from(*n)).collect(),
    }
}

/// A parsed shader and its validation ([`ops::validate`]).
type Parsed = (naga::Module, Option<naga::valid::ModuleInfo>);

/// What [`module`] reads off a composed shader, naga parsing it once: the fragment entry points
/// that can discard, and the parsed and validated module its pipelines' operations are
/// counted in ([`Module::ops`]). A source naga cannot parse has neither: the device reports
/// its errors when the module is created.
fn analyse(wgsl: &str) -> (Vec<String>, Option<Parsed>) {
    match naga::front::wgsl::parse_str(wgsl) {
        Ok(parsed) => {
            let info = ops::validate(&parsed);
            (discarding_fragment_entries(&parsed), Some((parsed, info)))
        }
        Err(_) => (Vec::new(), None),
    }
}

/// The names among [`PRELUDE_TEXTURES`] and `formats` whose texels are floating-point.
pub fn float_textures<'a>(formats: &[(&'a str, wgpu::TextureFormat)]) -> Vec<&'a str> {
    PRELUDE_TEXTURES
        .iter()
        .chain(formats)
        .filter(|(_, f)| is_float(*f))
        .map(|(n, _)| *n)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The discarding entries and every entry's operations of `wgsl` (none where it does not
    /// parse), the textures named in `float` floating-point.
    fn analysed(wgsl: &str, float: &[&str]) -> (Vec<String>, Vec<(String, ShaderOps)>) {
        let (discarding, parsed) = analyse(wgsl);
        let ops = parsed
            .map(|(m, info)| {
                ops::count_entries(
                    &m,
                    info.as_ref(),
                    Bound {
                        float,
                        single_level: &[],
                    },
                    &[],
                    None,
                )
            })
            .unwrap_or_default();
        (discarding, ops)
    }

    #[test]
    fn a_shader_is_read_once_for_discards_and_ops() {
        let (discarding, ops) = analysed(
            &compose(
                "@group(1) @binding(0) var t: texture_2d<f32>;
             @fragment fn cut(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
                 let c = textureLoad(t, vec2<i32>(p.xy), 0) * exp(p.x);
                 if (c.a < 0.5) { discard; }
                 return c;
             }",
            ),
            &[],
        );
        assert_eq!(discarding, ["cut"]);
        let cut = ops.iter().find(|(e, _)| e == "cut").map(|(_, f)| *f);
        assert_eq!(
            cut,
            Some(ShaderOps {
                loads: 1,
                float_loads: 0,
                samples: 0,
                float_samples: 0,
                mip_blends: 0,
                explicit_levels: 0,
                transcendentals: 1,
                // `p.xy`'s conversion to `vec2<i32>` (2), the product with `exp` (4), the
                // alpha test (1).
                arithmetic: 7,
                barriers: 0,
                storage: 0,
                divisions: 0,
            })
        );
        // An unparsable source has neither.
        assert_eq!(analysed("fn broken(", &[]), (Vec::new(), Vec::new()));
    }

    #[test]
    fn the_prelude_names_every_texture_it_fetches_with_its_format() {
        let prelude = naga::front::wgsl::parse_str(PRELUDE).unwrap();
        let mut named: Vec<&str> = PRELUDE_TEXTURES.iter().map(|(n, _)| *n).collect();
        named.sort_unstable();
        assert_eq!(texture_globals(&prelude), named);
        // The terrain's heights and density and the wind are floating-point; the covering
        // IDs are not. A module's own floating-point textures join them.
        assert_eq!(
            float_textures(&[
                ("blades", wgpu::TextureFormat::Rgba16Float),
                ("mask", wgpu::TextureFormat::R8Unorm),
            ]),
            ["height_map", "density_map", "wind_map", "blades"]
        );
        // A prelude function's bilinear height: four loads of floating-point texels.
        let (_, ops) = analysed(
            &compose(
                "@vertex fn vs() -> @builtin(position) vec4<f32> {
                     return vec4(terrain_height(vec2(1.0, 2.0)));
                 }",
            ),
            &float_textures(&[]),
        );
        let vs = ops.iter().find(|(e, _)| e == "vs").map(|(_, f)| *f);
        assert_eq!(vs.map(|o| (o.loads, o.float_loads)), Some((0, 4)));
    }
}
