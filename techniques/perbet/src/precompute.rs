//! The paper's pre-computation (Sec. 3.1, 4): the patches, their strip and 2D textures, the
//! postures of each kind of grass, and the counts that fix the GPU allocations — everything
//! built on the CPU before the GPU is touched.

use glam::Vec3;
use grassbench::gpu::GpuEstimate;
use grassbench::grass::GrassConfig;
use grassbench::wind::{BladeConfig, Postures, WindConfig};
use grassbench::{Result, Scene};

use crate::frame::Entry;
use crate::gpu::{self, BladeGpu, ParamsUniform};
use crate::paint;
use crate::params::Params;
use crate::patch::{self, Layout, Patch};
use crate::receiver;
use crate::tiling::Tiling;

/// Counts that fix the technique's allocations (shared by the technique's memory estimate and
/// its construction).
pub struct Sizes {
    blades: u64,
    segments: u64,
    strip_layers: u64,
    strip_texels: (u32, u32),
    flat_texels: u32,
    variants: u64,
    /// Patches of the tiling (one variant each on the GPU).
    patches: u64,
    /// Entries, blade receivers and edge receivers of the busiest frame.
    pub capacity: [u64; 3],
}

impl Sizes {
    /// The counts for `params` on `scene` with strips `strip_height` tall.
    pub fn new(scene: &Scene, params: &Params, strip_height: f32) -> Self {
        let (cols, rows) = Tiling::counts(scene.terrain.size(), params.patch_size);
        let patches = u64::from(cols) * u64::from(rows);
        let [from, to] = params.strips_from_to();
        let h = params.hysteresis;
        // Chebyshev discs around the camera's patch bound each level whatever the view.
        let disc = |r: u32| {
            let side = 2 * u64::from(r) + 1;
            side.saturating_mul(side).min(patches)
        };
        let geometry = disc(from.saturating_add(h));
        let strips = disc(to.saturating_add(h).saturating_add(1)).min(patches);
        let blades = u64::from(params.blades(scene.config.grass.density));
        let layout = layout(params, strip_height);
        Self {
            blades,
            segments: u64::from(params.blade_segments()),
            strip_layers: u64::from(params.variants) * 2 * u64::from(params.strips),
            strip_texels: paint::strip_size(&layout, params.strip_texels),
            flat_texels: params.flat_texels,
            variants: u64::from(params.variants),
            patches,
            capacity: [
                2 * patches,
                geometry * blades,
                strips * u64::from(params.strips) * u64::from(params.strip_edges()),
            ],
        }
    }

    /// The GPU memory these counts allocate.
    pub fn estimate(&self) -> GpuEstimate {
        let per_blade = std::mem::size_of::<BladeGpu>() as u64
            + self.segments * 8
            + 2 * (self.segments + 1) * 8;
        let chain = |w: u32, h: u32| {
            let (mut w, mut h, mut texels) = (u64::from(w), u64::from(h), 0);
            loop {
                texels += w * h;
                if w == 1 && h == 1 {
                    break texels;
                }
                w = (w / 2).max(1);
                h = (h / 2).max(1);
            }
        };
        let texel = gpu::texel_bytes(true) + gpu::texel_bytes(false);
        let (sw, sh) = self.strip_texels;
        let textures = self.strip_layers * chain(sw, sh) * texel
            + self.variants
                * paint::FLAT_ELEVATIONS.len() as u64
                * chain(self.flat_texels, self.flat_texels)
                * texel;
        let [entries, blade_receivers, edge_receivers] = self.capacity;
        GpuEstimate::buffer(self.variants * self.blades * per_blade)
            .plus(GpuEstimate::buffer(
                entries * std::mem::size_of::<Entry>() as u64,
            ))
            .plus(GpuEstimate::buffer((blade_receivers + edge_receivers) * 16))
            .plus(GpuEstimate::buffer(
                std::mem::size_of::<ParamsUniform>() as u64 + 64 * 64,
            ))
            .plus(GpuEstimate::buffer(4 * self.patches))
            .plus(GpuEstimate::textures(textures))
    }
}

fn layout(params: &Params, strip_height: f32) -> Layout {
    Layout {
        size: params.patch_size,
        segments: params.blade_segments(),
        strips: params.strips,
        columns: params.strip_columns,
        margin: params.strip_margin,
        strip_height,
    }
}

/// The postures of each kind of grass (Sec. 3.2: "for each kind of grass, we have
/// precomputed the range of possible bent postures"): the blade of the scene's primitives wind
/// (or a default blade under `wind_speed`) at each kind's mean height.
fn postures(scene: &Scene, params: &Params) -> Result<Vec<Postures>> {
    let base = match &scene.config.wind {
        WindConfig::Primitives(c) => c.blade.clone(),
        _ => BladeConfig {
            wind_speed: params.wind_speed,
            ..BladeConfig::default()
        },
    };
    let range = scene.config.grass.height;
    (0..params.kinds)
        .map(|k| {
            Postures::new(&BladeConfig {
                height: patch::kind_height(k, range, params.kinds),
                ..base.clone()
            })
        })
        .collect()
}

/// The pre-computed patches as the shader reads them (`Statics` without the textures).
pub struct Arrays {
    /// Blades of every variant, variant-major (the shader's `blades`).
    pub blades: Vec<BladeGpu>,
    /// Rest tilt of every segment of every blade (`tilts`).
    pub tilts: Vec<[f32; 2]>,
    /// Painted texture coordinates of every point of every blade, per orientation, blade
    /// after blade (`painted`: the morph targets of Sec. 4.2, Fig. 14).
    pub painted: Vec<[f32; 2]>,
    /// The posture table of every kind, kind after kind (`postures`).
    pub postures: Vec<f32>,
}

/// What the technique computes on the CPU before touching the GPU (the paper's
/// pre-computation: patches, strip and 2D textures, postures).
pub struct Precomputed {
    /// The shape of patches and strips.
    pub layout: Layout,
    /// The pre-computed patches.
    pub patches: Vec<Patch>,
    /// The postures of each kind of grass, shortest first.
    pub postures: Vec<Postures>,
    /// Strip textures: for variant `v`, orientation `o`, strip `k`, layer
    /// `(v · 2 + o) · strips + k`, each a mip chain.
    pub strip_layers: Vec<Vec<paint::Image>>,
    /// 2D textures: for variant `v` and elevation `e` of [`paint::FLAT_ELEVATIONS`], layer
    /// `v · 3 + e`, each a mip chain.
    pub flat_layers: Vec<Vec<paint::Image>>,
}

impl Precomputed {
    /// Everything the technique pre-computes for `scene` with `params`.
    pub fn new(scene: &Scene, params: &Params) -> Result<Self> {
        let grass = &scene.config.grass;
        let mut layout = layout(params, grass.height[1]);
        let patches = patch::build(
            grass,
            &layout,
            (params.variants, params.blades(grass.density), params.kinds),
            params.segment_jitter,
            scene.config.seed,
        );
        layout.strip_height = patch::tallest(&patches, layout.segments, grass.height[1]);
        let postures = postures(scene, params)?;
        let strip_layers = patches
            .iter()
            .flat_map(|p| paint::strips(p, &layout, grass, params.strip_texels))
            .map(paint::Image::mip_chain)
            .collect();
        let flat_layers = patches
            .iter()
            .flat_map(|p| {
                paint::FLAT_ELEVATIONS
                    .map(|e| paint::flat(p, &layout, grass, params.flat_texels, e).mip_chain())
            })
            .collect();
        Ok(Self {
            layout,
            patches,
            postures,
            strip_layers,
            flat_layers,
        })
    }

    /// The patches, their painted coordinates and the posture tables resampled to the
    /// blades' segments, as the GPU reads them.
    pub fn arrays(&self) -> Arrays {
        let layout = &self.layout;
        let mut arrays = Arrays {
            blades: Vec::new(),
            tilts: Vec::new(),
            painted: Vec::new(),
            postures: self
                .postures
                .iter()
                .flat_map(|p| receiver::posture_table(p, layout.segments))
                .collect(),
        };
        for b in self.patches.iter().flat_map(|p| &p.blades) {
            arrays.blades.push(BladeGpu {
                root_facing: [b.root.x, b.root.y, b.facing, b.height],
                shape: [b.width, b.variation, b.threshold, 0.0],
                strips: [b.strips[0], b.strips[1], b.kind, 0],
            });
            arrays.tilts.extend(b.tilts.iter().map(|t| t.to_array()));
            let points = b.rest_points(layout.segments);
            for o in 0..2 {
                arrays
                    .painted
                    .extend(points.iter().map(|p| layout.painted_uv(o, *p).to_array()));
            }
        }
        debug_assert_eq!(
            arrays.tilts.len(),
            arrays.blades.len() * layout.segments as usize
        );
        arrays
    }

    /// The shader's `Params` for `params` and the scene's `grass` (`bases` zero: each frame
    /// sets where its strips and 2D entries start; `tiling` zero: the technique sets it).
    pub fn uniform(&self, params: &Params, grass: &GrassConfig) -> ParamsUniform {
        let layout = &self.layout;
        let blades_per_patch = params.blades(grass.density);
        let posture_count = self.postures.first().map_or(0, Postures::count) as u32;
        ParamsUniform {
            sizes: [
                params.patch_size,
                layout.strip_height,
                params.strip_margin,
                0.5 * layout.strip_height,
            ],
            counts: [
                blades_per_patch,
                layout.segments,
                params.strips,
                params.strip_columns,
            ],
            // Strip edges bend like the middle kind.
            more: [
                posture_count,
                params.variants,
                gpu::FLAT_CELLS,
                params.kinds / 2,
            ],
            color_root: Vec3::from(grass.color_root)
                .extend(grass.color_variation)
                .to_array(),
            color_tip: Vec3::from(grass.color_tip)
                .extend(params.translucency)
                .to_array(),
            bases: [0; 4],
            flat_elevations: [
                paint::FLAT_ELEVATIONS[0],
                paint::FLAT_ELEVATIONS[1],
                paint::FLAT_ELEVATIONS[2],
                0.0,
            ],
            tiling: [0; 4],
        }
    }
}
