//! The start-up bakes, in their order (Boulanger Sec. 3.3, 3.5): the shadow mask first, since
//! the blades and the BTFs are lit through it, then the horizontal slice's and the vertical
//! slices' BTFs, each loaded from the disk cache ([`crate::cache`]) when a file of its key is
//! there. Every bake is [`crate::btf::bake`] of its layers.

use grassbench::{InitContext, Result, bytemuck};

use crate::btf::{self, BakeInputs, BtfTextures, Layers};
use crate::cache;
use crate::params::Params;
use crate::patch::Patch;
use crate::shader::ParamsUniform;
use crate::shadow;
use crate::slice;
use crate::vertical;

/// The shadow mask (Sec. 3.5): a one-layer bake of the slab around the patch's centre. `inputs`
/// draws without a shadow mask.
pub fn shadow_mask(
    ctx: &InitContext<'_>,
    inputs: &BakeInputs<'_>,
    params: &Params,
    patch: &Patch,
) -> Result<BtfTextures> {
    let (cells, refs, range) = shadow::bake_layer(params.patch_size, &patch.blades, params.gravity);
    btf::bake(
        ctx,
        inputs,
        shadow::WIDTH,
        shadow::HEIGHT,
        &Layers {
            cells: &cells,
            refs: &refs,
            ranges: std::slice::from_ref(&range),
        },
    )
}

/// How the BTFs were obtained at start-up.
#[derive(Clone, Debug)]
pub struct BakeReport {
    /// Loaded or baked (horizontal, vertical).
    pub outcome: [cache::Outcome; 2],
    /// Wall time of both, from the cache keys to the GPU's last bake, s.
    pub seconds: f64,
}

/// The two BTFs the slices draw, and how they were obtained.
pub struct SliceBtfs {
    /// The horizontal slice's one layer.
    pub horizontal: BtfTextures,
    /// The vertical slices' `4N` layers.
    pub verticals: BtfTextures,
    /// How they were obtained.
    pub report: BakeReport,
}

/// The horizontal and vertical BTFs (Sec. 3.3), from the cache or baked with `inputs` (whose
/// group 1 holds the shadow mask), waiting for the GPU to finish them.
pub fn slice_btfs(
    ctx: &InitContext<'_>,
    inputs: &BakeInputs<'_>,
    params: &Params,
    uniform: &ParamsUniform,
    patch: &Patch,
) -> Result<SliceBtfs> {
    let started = std::time::Instant::now();
    let [h_key, v_key] = keys(params, uniform, patch);
    let [h_dims, v_dims] = dims(params);
    let folder = cache::folder(&params.btf_cache);
    let (horizontal, h_outcome) =
        cache::load_or_bake(ctx.gpu, folder.as_deref(), h_key, h_dims, || {
            let (cells, refs, range) =
                slice::bake_layer(params.patch_size, &patch.blades, params.gravity);
            btf::bake(
                ctx,
                inputs,
                h_dims.width,
                h_dims.height,
                &Layers {
                    cells: &cells,
                    refs: &refs,
                    ranges: std::slice::from_ref(&range),
                },
            )
        })?;
    let (verticals, v_outcome) =
        cache::load_or_bake(ctx.gpu, folder.as_deref(), v_key, v_dims, || {
            let layout = vertical::SliceLayout {
                per_axis: params.vertical_slices,
                patch_size: params.patch_size,
            };
            let (refs, ranges) = layout.bake_refs(&patch.blades, params.gravity);
            btf::bake(
                ctx,
                inputs,
                v_dims.width,
                v_dims.height,
                &Layers {
                    cells: &layout.bake_cells(),
                    refs: &refs,
                    ranges: &ranges,
                },
            )
        })?;
    ctx.gpu.wait_idle("baking the BTFs")?;
    Ok(SliceBtfs {
        horizontal,
        verticals,
        report: BakeReport {
            outcome: [h_outcome, v_outcome],
            seconds: started.elapsed().as_secs_f64(),
        },
    })
}

/// Sizes of the two BTFs: the horizontal slice's one layer, the vertical slices' `4N`.
pub fn dims(params: &Params) -> [cache::Dims; 2] {
    [
        cache::Dims {
            width: params.slice_resolution,
            height: params.slice_resolution,
            layers: 1,
        },
        cache::Dims {
            width: params.vslice_width,
            height: params.vslice_height,
            layers: 4 * params.vertical_slices,
        },
    ]
}

/// Cache keys of the two bakes (horizontal, vertical): the uniform block with what the bake
/// does not read (LOD distances, alpha threshold, wind response, slice height) zeroed, and the
/// patch.
pub fn keys(params: &Params, uniform: &ParamsUniform, patch: &Patch) -> [u64; 2] {
    let mut u = *uniform;
    u.lod = [0.0; 4];
    u.blade[2] = 0.0;
    u.tile[1] = 0.0;
    u.btf[1] = 0.0;
    u.btf[2] = 0.0;
    let blades = bytemuck::cast_slice(&patch.blades);
    let [h, v] = dims(params);
    [
        cache::bake_key("horizontal", h, bytemuck::bytes_of(&u), blades),
        cache::bake_key("vertical", v, bytemuck::bytes_of(&u), blades),
    ]
}
