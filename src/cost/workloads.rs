//! The calibration's micro-workloads: what each draws or dispatches, and the work it does,
//! known in advance from its shape and the target size (no GPU needed to say it; the GPU's
//! own counters are checked against it where it has them, see `measure`).
//!
//! Each workload isolates one [`Term`] and runs at four sizes in ratio 1 : 2 : 4 : 8 (the
//! fixed per-submission cost and the unit cost separate by the slope), times a scale that
//! `measure` raises on fast adapters until the largest size takes long enough to time:
//!
//! | workload | draws | isolates |
//! |---|---|---|
//! | `empty` | nothing: the target's clear | fixed |
//! | `vertices` | instanced 43-vertex strips (a 21-segment blade) of degenerate triangles: the clipper passes none | vertex |
//! | `instances` | the same strips cut to their first triangle, 3 vertices an instance | instance |
//! | `primitives` | the same strips folded into a quarter of a pixel each, one pixel apart: 9 triangles that cover no pixel centre, a fragment shader that reads no interpolated slot; passes of up to [`PASS_HEAD_PRIMITIVES`] | a primitive of a pass's head (with `large_primitives`) |
//! | `primitive_inputs` | the same strips with a fragment shader reading the blade's five interpolated slots | a fragment input slot of a primitive |
//! | `large_primitives`, `large_primitive_inputs` | the same two at eight times the instances: passes of 1x to 8x [`PASS_HEAD_PRIMITIVES`] | a primitive (and, with `primitives`, what a pass's head costs more); the slot at that scale |
//! | `fragments_*` | full-screen triangles layered, each nearer than the last, opaque / alpha-tested (half the pixels discarded) / blended | fragment by kind |
//! | `texture_loads`, `single_level_texture_samples` | the opaque layers with [`LOADS_PER_FRAGMENT`] `textureLoad`s / [`SAMPLES_PER_FRAGMENT`] `textureSample`s of one mip level (a `Nearest` mipmap filter, [`SINGLE_LEVEL_SAMPLER`]) of a mip-mapped 512² RGBA8 texture per fragment | texel load, texture sample |
//! | `texture_samples` | the same samples trilinear, minified between two levels | a sample's second mip level |
//! | `explicit_level_texture_samples` | the one-level samples with `textureSampleLevel` at a level each fragment gives | a sample's level picked lane by lane |
//! | `float_texture_loads`, `float_texture_samples` | the same loads of the texels in [`FLOAT_LOAD_FORMAT`], trilinear samples in [`FLOAT_SAMPLE_FORMAT`] | floating-point texel load, sample |
//! | `vertex_texture_loads`, `vertex_float_texture_loads` | the off-screen strips with [`LOADS_PER_VERTEX`] `textureLoad`s per vertex of the RGBA8 / floating-point texture | what a load costs a vertex shader more |
//! | `transcendentals_vertex`, `_fragment`, `_compute` | the off-screen strips / an opaque layer / the spring update with [`MATH_CHAIN`] more transcendentals (`sin`, `cos`, `pow`) per vertex / fragment / invocation | transcendental by stage |
//! | `arithmetic_vertex`, `_fragment`, `_compute` | the same with [`ARITHMETIC_CHAIN`] more scalar operations (multiply-adds and maxima of a `vec4`) | scalar arithmetic by stage |
//! | `vertex_storage` | the off-screen strips with [`STORAGE_CHAIN`] / 4 `vec4`s of the instance's data read from a storage buffer per vertex | a storage-buffer word of a vertex shader |
//! | `compute_storage` | the spring update reading [`STORAGE_CHAIN`] / 4 more elements, each a workgroup's width along (the next invocation reads the next element) | a storage-buffer word of a compute shader |
//! | `compute_divisions` | the spring update with [`DIVISION_CHAIN`] integer remainders by the buffer's length (a value the pipeline does not fix), each a hash step of the last | an integer division of a compute shader |
//! | `compute_barriers` | the spring update of the element [`BARRIER_CHAIN`] / 2 neighbours along, passed through workgroup memory with a barrier before and after each read | a compute invocation at a barrier |
//! | `draws` | one sub-pixel triangle per draw call | draw |
//! | `compute` | a spring update of a 16-byte element per invocation, 64-wide workgroups | compute |
//! | `upload` | `queue.write_buffer` of 1 to 64 MB | upload |
//!
//! Besides the families fitted, the coverage checks ([`super::checks`]) are timed with them
//! and not fitted: blades drawn on screen ([`Shape::OnscreenBlades`]) and layers hidden behind
//! the first ([`Shape::HiddenLayers`]), fragments unlike the layers' whole 4x4 blocks that
//! every fragment term is fitted on.
//!
//! Every sample is one submission holding one render pass that clears the target, plus the
//! workload: the fixed term is what a frame with nothing in it costs at this size.
//!
//! The transcendentals of each shader are constants checked against the shader; its scalar
//! arithmetic, a few dozen to a few hundred operations an entry point, is read off the
//! shader itself ([`SHADER`], `crate::shaders::entry_ops`), as the harness reads every
//! technique's.

use std::sync::OnceLock;

use super::{FragmentKind, Term, Work};
use crate::shaders::ShaderOps;
use crate::target::Size;
use crate::technique::work::PASS_HEAD_PRIMITIVES;

/// The workloads' shader (composed with the prelude when built).
pub const SHADER: &str = include_str!("../shaders/unit_costs.wgsl");

/// Format of the `texture_loads` and `texture_samples` workloads' texture (the shader's
/// `fetched`).
pub const FETCH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Format of the `float_texture_samples` workload's texture (the shader's `fetched_float`): the
/// format of boulanger's slice textures ([`crate::shaders::is_float`]).
pub const FLOAT_SAMPLE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Format of the `float_texture_loads` workload's texture (the shader's `fetched_r32`): the
/// format of the terrain's height and density maps, which every technique loads.
pub const FLOAT_LOAD_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// One of the shader's fetch textures: what the rig binds and the cost counter names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FetchTexture {
    /// The shader's global.
    pub name: &'static str,
    /// Its binding in group 1.
    pub binding: u32,
    /// The format bound there.
    pub format: wgpu::TextureFormat,
}

/// The shader's fetch textures (`tests` holds the names and bindings to the shader).
pub const FETCH_TEXTURES: [FetchTexture; 3] = [
    FetchTexture {
        name: "fetched",
        binding: 2,
        format: FETCH_FORMAT,
    },
    FetchTexture {
        name: "fetched_float",
        binding: 4,
        format: FLOAT_SAMPLE_FORMAT,
    },
    FetchTexture {
        name: "fetched_r32",
        binding: 5,
        format: FLOAT_LOAD_FORMAT,
    },
];

/// The shader's sampler that filters one mip level (binding 7 of group 1: mipmap filter
/// `Nearest`), as the shader's module is created with
/// ([`crate::shaders::module_with_bindings`]): its samples are not mip blends.
pub const SINGLE_LEVEL_SAMPLER: &str = "single_level";

/// What the shader's texture and sampler globals are bound to, as its module is created with
/// ([`crate::shaders::module_with_bindings`]) and its operations are counted.
fn bound<R>(f: impl FnOnce(crate::shaders::Bound<'_>) -> R) -> R {
    let float = crate::shaders::float_textures(&texture_formats());
    f(crate::shaders::Bound {
        float: &float,
        single_level: &[SINGLE_LEVEL_SAMPLER],
    })
}

/// [`FETCH_TEXTURES`]' names and formats, as the shader's module is created with
/// ([`crate::shaders::module_with_bindings`]).
pub fn texture_formats() -> [(&'static str, wgpu::TextureFormat); FETCH_TEXTURES.len()] {
    FETCH_TEXTURES.map(|t| (t.name, t.format))
}

/// What one invocation of `entry` of [`SHADER`] does ([`ShaderOps`]; nothing for an entry
/// point it lacks: `tests` checks every one the workloads use is there).
pub fn shader_ops(entry: &str) -> ShaderOps {
    static OPS: OnceLock<Vec<(String, ShaderOps)>> = OnceLock::new();
    OPS.get_or_init(|| {
        module()
            .map(|m| bound(|b| crate::shaders::entry_ops(m, b, &[])))
            .unwrap_or_default()
    })
    .iter()
    .find(|(e, _)| e == entry)
    .map(|(_, o)| *o)
    .unwrap_or_default()
}

/// Scalar arithmetic of one invocation of `entry` of [`SHADER`], as a count.
fn arithmetic(entry: &str) -> f64 {
    shader_ops(entry).arithmetic as f64
}

/// The input slots fragment entry point `entry` of [`SHADER`] reads
/// ([`crate::shaders::fragment_inputs`]), as a count.
pub fn fragment_inputs(entry: &str) -> f64 {
    module().map_or(0.0, |m| {
        f64::from(crate::shaders::fragment_inputs(m, entry))
    })
}

/// [`SHADER`] composed and parsed, once (`None` if naga cannot parse it: `tests` parse it and
/// say why).
fn module() -> Option<&'static naga::Module> {
    static MODULE: OnceLock<Option<naga::Module>> = OnceLock::new();
    MODULE
        .get_or_init(|| naga::front::wgsl::parse_str(&crate::shaders::compose(SHADER)).ok())
        .as_ref()
}

/// The fragment entry point of the sub-pixel strips: `fs_opaque` (the blade's five slots) or,
/// where `interpolated` is false, `fs_bare` (none).
pub fn subpixel_fragment_entry(interpolated: bool) -> &'static str {
    if interpolated { "fs_opaque" } else { "fs_bare" }
}

/// Vertices of a blade strip (5 segments: `2 · 5 + 1`).
pub const STRIP_VERTICES: u32 = 11;
/// Triangles of a blade strip (`2 · 5 − 1`).
pub const STRIP_TRIANGLES: u32 = 9;
/// Vertices an instance of the `instances` workload draws: a blade strip's first triangle.
pub const SHORT_STRIP_VERTICES: u32 = 3;
/// Vertices an instance of the `vertices` workload draws: a blade strip of 21 segments (the
/// same vertex shader), so that the vertices' and the instances' costs come apart against
/// the `instances` workload's [`SHORT_STRIP_VERTICES`].
pub const LONG_STRIP_VERTICES: u32 = 43;
/// Vertices of a full-screen layer: one triangle twice the screen's size, so no edge crosses
/// the screen (a quad's diagonal would add helper invocations where both its triangles
/// shade partial 2x2 quads: lavapipe counted 1.25% more fragments than pixels).
pub const LAYER_VERTICES: u32 = 3;
/// Triangles of a full-screen layer.
pub const LAYER_TRIANGLES: u32 = 1;
/// Vertices of a draw call's triangle in the `draws` workload.
pub const DRAW_VERTICES: u32 = 3;
/// Invocations per compute workgroup (as bakay's bend pass).
pub const WORKGROUP_SIZE: u32 = 64;
/// Most workgroups along one dimension of a dispatch (wgpu's default limit).
pub const MAX_GROUPS_PER_DIMENSION: u32 = 65_535;
/// `textureLoad`s of one fragment of the `texture_loads` and `float_texture_loads` workloads: a load costs about a
/// tenth of a fragment on lavapipe (1 ns against 8 ns, quiet host), so it takes 32 of them to
/// stand out of the fragment's own cost by more than the noise.
pub const LOADS_PER_FRAGMENT: u32 = 32;
/// `textureLoad`s of one vertex of the `vertex_texture_loads` and
/// `vertex_float_texture_loads` workloads: the fragment workloads' loads, through the same
/// shader functions.
pub const LOADS_PER_VERTEX: u32 = LOADS_PER_FRAGMENT;
/// `textureSample`s of one fragment of the `texture_samples` and `float_texture_samples`
/// workloads.
pub const SAMPLES_PER_FRAGMENT: u32 = 8;
/// Transcendental built-ins of the `transcendentals_*` workloads' chain (`math_chain` in the
/// shader: 10 links of a `sin`, a `cos` and a `pow`, each fed by the last, so none is folded
/// away), on top of what their shaders do without it.
pub const MATH_CHAIN: u32 = 30;
/// Scalar operations the `arithmetic_*` workloads' chain adds (`arith_chain` in the shader:
/// 16 links of a `vec4` multiply-add, a `vec4` scaled and their maximum, 16 operations each,
/// each link fed by the last and mixing the components, so none is folded away).
pub const ARITHMETIC_CHAIN: u32 = 256;
/// Workgroup barriers of one invocation of the `compute_barriers` workload (`cs_barriers`:
/// four exchanges with the neighbour, two barriers each).
pub const BARRIER_CHAIN: u32 = 8;
/// Storage-buffer words the `compute_storage` workload reads an invocation beyond the spring
/// update's own (`cs_storage`: 8 more `vec4`s), and the `vertex_storage` strips a vertex
/// (`vs_storage`).
pub const STORAGE_CHAIN: u32 = 32;
/// Integer remainders by a divisor the pipeline does not fix the `compute_divisions` workload
/// takes an invocation (`cs_divisions`: a loop of 16); the other spring updates take none.
pub const DIVISION_CHAIN: u32 = 16;
/// Transcendentals of one invocation of the strips' vertex shader (`blade_vertex`: the
/// facing's `cos` and `sin`, one `sincos` as the op counter counts them, and the sway's
/// `sin`).
pub const STRIP_VERTEX_TRANSCENDENTALS: u32 = 2;
/// Transcendentals of one invocation of the layers' fragment shaders (`lit`: the fog's
/// `exp`).
pub const LIT_TRANSCENDENTALS: u32 = 1;
/// Height in pixels of a blade of the [`Shape::OnscreenBlades`] workloads (the shader's
/// `ONSCREEN_HEIGHT`, set from here: [`BladeWidth::constants`]).
pub const ONSCREEN_BLADE_HEIGHT: f64 = 40.0;
/// Size ratios of a workload's samples.
pub const SIZE_STEPS: [u32; 4] = [1, 2, 4, 8];

/// What a workload records.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// Nothing but the target's clear.
    Empty,
    /// `instances` off-screen blade strips of `vertices` vertices each, in one instanced
    /// draw (every triangle degenerate: the clipper passes none).
    OffscreenStrips {
        /// Vertices of a strip ([`STRIP_VERTICES`] for a 5-segment blade).
        vertices: u32,
        /// Instances.
        instances: u32,
    },
    /// `instances` off-screen blade strips whose vertex shader also evaluates
    /// [`MATH_CHAIN`] transcendentals, in one instanced draw.
    MathStrips {
        /// Instances.
        instances: u32,
    },
    /// `instances` off-screen blade strips whose vertex shader also does
    /// [`ARITHMETIC_CHAIN`] scalar operations, in one instanced draw.
    ArithmeticStrips {
        /// Instances.
        instances: u32,
    },
    /// `instances` off-screen blade strips whose vertex shader also does [`LOADS_PER_VERTEX`]
    /// `textureLoad`s of the RGBA8 texture, or of the floating-point one
    /// ([`FLOAT_LOAD_FORMAT`]) where `float`, in one instanced draw.
    LoadStrips {
        /// Whether the texels loaded are of the floating-point texture.
        float: bool,
        /// Instances.
        instances: u32,
    },
    /// `instances` off-screen blade strips whose vertex shader also reads [`STORAGE_CHAIN`]
    /// words of its instance's data from a storage buffer, in one instanced draw.
    StorageStrips {
        /// Instances.
        instances: u32,
    },
    /// `instances` sub-pixel blade strips in one instanced draw.
    SubpixelStrips {
        /// Instances.
        instances: u32,
        /// Whether their fragment shader reads the blade's interpolated slots
        /// ([`subpixel_fragment_entry`]): the rasteriser sets each up for every triangle.
        interpolated: bool,
    },
    /// `layers` full-screen triangles in one instanced draw.
    Layers {
        /// How they are shaded.
        kind: FragmentKind,
        /// Layers.
        layers: u32,
    },
    /// `instances` blade strips on screen, each rooted at a hashed pixel,
    /// [`ONSCREEN_BLADE_HEIGHT`] pixels tall and `width` wide at the root, tapering to the tip
    /// and leaning, each nearer than the last (every one passes the depth test), shaded as
    /// `kind`, in one instanced draw: the thin, partly covered 4x4 blocks of a meadow's blades,
    /// where a layer covers its blocks whole.
    OnscreenBlades {
        /// How they are shaded.
        kind: FragmentKind,
        /// How wide they are.
        width: BladeWidth,
        /// Instances.
        instances: u32,
    },
    /// `layers` full-screen triangles shaded as `kind` far behind every other layer
    /// (`vs_hidden_layer`), in one instanced draw: drawn after a layer, every fragment fails
    /// the depth test.
    HiddenLayers {
        /// How they are shaded.
        kind: FragmentKind,
        /// Layers.
        layers: u32,
    },
    /// `layers` opaque full-screen triangles whose fragments each fetch texels ([`Fetch`]).
    FetchLayers {
        /// What each fragment fetches.
        fetch: Fetch,
        /// Layers.
        layers: u32,
    },
    /// `layers` opaque full-screen triangles whose fragments each also evaluate
    /// [`MATH_CHAIN`] transcendentals.
    MathLayers {
        /// Layers.
        layers: u32,
    },
    /// `layers` opaque full-screen triangles whose fragments each also do
    /// [`ARITHMETIC_CHAIN`] scalar operations.
    ArithmeticLayers {
        /// Layers.
        layers: u32,
    },
    /// `draws` draw calls of one sub-pixel triangle each.
    Draws {
        /// Draw calls.
        draws: u32,
    },
    /// A dispatch of `groups` workgroups of [`WORKGROUP_SIZE`].
    Compute {
        /// Workgroups wanted (the dispatch may round up, see [`dispatch_grid`]).
        groups: u32,
        /// What each invocation does beyond the spring update.
        chain: Chain,
    },
    /// `bytes` written with `queue.write_buffer`.
    Upload {
        /// Bytes.
        bytes: u64,
    },
}

/// What each fragment of a [`Shape::FetchLayers`] workload fetches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fetch {
    /// [`LOADS_PER_FRAGMENT`] plain loads (`textureLoad`) of the RGBA8 texture.
    Loads,
    /// [`SAMPLES_PER_FRAGMENT`] trilinear samples (`textureSample`) of the RGBA8 texture.
    Samples,
    /// The same samples of one mip level ([`SINGLE_LEVEL_SAMPLER`]).
    SingleLevelSamples,
    /// The same one-level samples with `textureSampleLevel`, at a level each fragment gives
    /// (a fraction that differs between neighbouring pixels): the level picked lane by lane.
    ExplicitLevelSamples,
    /// The same loads of the texture of floating-point texels ([`FLOAT_LOAD_FORMAT`]).
    FloatLoads,
    /// The same samples of the texture of floating-point texels ([`FLOAT_SAMPLE_FORMAT`]).
    FloatSamples,
}

impl Fetch {
    /// Every fetch, in declaration order (`fetch as usize` is its position).
    pub const ALL: [Self; 6] = [
        Self::Loads,
        Self::Samples,
        Self::SingleLevelSamples,
        Self::ExplicitLevelSamples,
        Self::FloatLoads,
        Self::FloatSamples,
    ];

    /// The fragment entry point that fetches so.
    pub fn fragment_entry(self) -> &'static str {
        match self {
            Self::Loads => "fs_loads",
            Self::Samples => "fs_samples",
            Self::SingleLevelSamples => "fs_single_level_samples",
            Self::ExplicitLevelSamples => "fs_explicit_level_samples",
            Self::FloatLoads => "fs_float_loads",
            Self::FloatSamples => "fs_float_samples",
        }
    }
}

/// The vertex entry point of the [`Shape::OnscreenBlades`] workloads (its size set by
/// [`BladeWidth::constants`]).
pub const ONSCREEN_BLADE_VERTEX: &str = "vs_onscreen_blade";

/// Width at the root of the blades of a [`Shape::OnscreenBlades`] workload.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BladeWidth {
    /// 1.5 pixels: a near blade, a third of the pixels of each 4x4 block it touches covered.
    Blade,
    /// 0.3 pixels: a far blade, a sliver that covers a few samples of each block it touches.
    Sliver,
}

impl BladeWidth {
    /// Both widths, widest first.
    pub const ALL: [Self; 2] = [Self::Blade, Self::Sliver];

    /// Width at the root, pixels.
    pub fn pixels(self) -> f64 {
        match self {
            Self::Blade => 1.5,
            Self::Sliver => 0.3,
        }
    }

    /// The values of the shader's overridable constants that draw blades of this width with
    /// [`ONSCREEN_BLADE_VERTEX`].
    pub fn constants(self) -> [(&'static str, f64); 2] {
        [
            ("ONSCREEN_HEIGHT", ONSCREEN_BLADE_HEIGHT),
            ("ONSCREEN_WIDTH", self.pixels()),
        ]
    }
}

/// What a workload's shaders do beyond their plain version.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Chain {
    /// Nothing.
    None,
    /// [`MATH_CHAIN`] transcendentals.
    Transcendental,
    /// [`ARITHMETIC_CHAIN`] scalar operations.
    Arithmetic,
    /// [`BARRIER_CHAIN`] workgroup barriers.
    Barriers,
    /// [`STORAGE_CHAIN`] more words read from the storage buffer.
    Storage,
    /// [`DIVISION_CHAIN`] more integer remainders.
    Divisions,
}

/// One sample's workload.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Workload {
    /// Name of its family (`vertices`, `fragments_opaque`, ...), as in the fit's residuals.
    pub name: &'static str,
    /// The term it isolates.
    pub term: Term,
    /// What it records.
    pub shape: Shape,
}

/// The `(x, y)` workgroup grid of a dispatch of at least `groups` workgroups: `x` at most
/// [`MAX_GROUPS_PER_DIMENSION`]; `x · y ≥ groups` (equal when `groups` fits in one row).
pub fn dispatch_grid(groups: u32) -> (u32, u32) {
    let y = groups.div_ceil(MAX_GROUPS_PER_DIMENSION).max(1);
    (groups.div_ceil(y), y)
}

impl Chain {
    /// Every chain, in declaration order (`chain as usize` is its position).
    pub const ALL: [Self; 6] = [
        Self::None,
        Self::Transcendental,
        Self::Arithmetic,
        Self::Barriers,
        Self::Storage,
        Self::Divisions,
    ];

    /// The compute entry point of the spring update with this chain.
    pub fn compute_entry(self) -> &'static str {
        match self {
            Self::None => "cs_springs",
            Self::Transcendental => "cs_math",
            Self::Arithmetic => "cs_arithmetic",
            Self::Barriers => "cs_barriers",
            Self::Storage => "cs_storage",
            Self::Divisions => "cs_divisions",
        }
    }
}

impl Workload {
    /// The work this workload does on a `size` target, known in advance: one segment's (one
    /// render pass drawn with one pipeline), its head primitives the first
    /// [`crate::technique::work::PASS_HEAD_PRIMITIVES`].
    pub fn work(&self, size: Size) -> Work {
        self.counts(size).as_one_segment()
    }

    /// [`Self::work`] before its head is taken.
    fn counts(&self, size: Size) -> Work {
        let pixels = f64::from(size.width) * f64::from(size.height);
        let none = Work::default();
        match self.shape {
            Shape::Empty => none,
            Shape::OffscreenStrips {
                vertices,
                instances,
            } => {
                let vertices = f64::from(instances) * f64::from(vertices);
                Work {
                    vertex_invocations: vertices,
                    draw_calls: 1.0,
                    instances: f64::from(instances),
                    vertex_transcendentals: vertices * f64::from(STRIP_VERTEX_TRANSCENDENTALS),
                    vertex_arithmetic: vertices * arithmetic("vs_offscreen"),
                    ..none
                }
            }
            Shape::MathStrips { instances } => {
                let base = self.offscreen_strips(instances, size);
                Work {
                    vertex_transcendentals: base.vertex_invocations
                        * f64::from(STRIP_VERTEX_TRANSCENDENTALS + MATH_CHAIN),
                    vertex_arithmetic: base.vertex_invocations * arithmetic("vs_math"),
                    ..base
                }
            }
            Shape::ArithmeticStrips { instances } => {
                let base = self.offscreen_strips(instances, size);
                Work {
                    vertex_arithmetic: base.vertex_invocations * arithmetic("vs_arithmetic"),
                    ..base
                }
            }
            Shape::LoadStrips { float, instances } => {
                let base = self.offscreen_strips(instances, size);
                let loads = base.vertex_invocations * f64::from(LOADS_PER_VERTEX);
                let (normalised, float) = if float { (0.0, loads) } else { (loads, 0.0) };
                Work {
                    vertex_arithmetic: base.vertex_invocations
                        * arithmetic(load_strips_entry(float > 0.0)),
                    texture_loads: normalised,
                    float_texture_loads: float,
                    vertex_texture_loads: normalised,
                    vertex_float_texture_loads: float,
                    ..base
                }
            }
            Shape::StorageStrips { instances } => {
                let base = self.offscreen_strips(instances, size);
                let ops = shader_ops("vs_storage");
                Work {
                    vertex_arithmetic: base.vertex_invocations * ops.arithmetic as f64,
                    vertex_storage: base.vertex_invocations * ops.storage as f64,
                    ..base
                }
            }
            Shape::SubpixelStrips {
                instances,
                interpolated,
            } => {
                let vertices = f64::from(instances) * f64::from(STRIP_VERTICES);
                let primitives = f64::from(instances) * f64::from(STRIP_TRIANGLES);
                Work {
                    vertex_invocations: vertices,
                    primitives,
                    primitive_inputs: primitives
                        * fragment_inputs(subpixel_fragment_entry(interpolated)),
                    draw_calls: 1.0,
                    instances: f64::from(instances),
                    vertex_transcendentals: vertices * f64::from(STRIP_VERTEX_TRANSCENDENTALS),
                    vertex_arithmetic: vertices * arithmetic("vs_subpixel"),
                    ..none
                }
            }
            Shape::Layers { kind, layers } => {
                let fragments = pixels * f64::from(layers);
                let vertices = f64::from(layers) * f64::from(LAYER_VERTICES);
                let fragment_entry = layer_fragment_entry(kind);
                let mut work = Work {
                    vertex_invocations: vertices,
                    primitives: f64::from(layers) * f64::from(LAYER_TRIANGLES),
                    primitive_inputs: f64::from(layers)
                        * f64::from(LAYER_TRIANGLES)
                        * fragment_inputs(fragment_entry),
                    draw_calls: 1.0,
                    instances: f64::from(layers),
                    fragment_transcendentals: fragments * f64::from(LIT_TRANSCENDENTALS),
                    vertex_arithmetic: vertices * arithmetic("vs_layer"),
                    fragment_arithmetic: fragments * arithmetic(fragment_entry),
                    ..none
                };
                *work.fragments_mut(kind) = fragments;
                work
            }
            Shape::HiddenLayers { kind, layers } => {
                let base = Workload {
                    shape: Shape::Layers { kind, layers },
                    ..*self
                }
                .work(size);
                Work {
                    vertex_arithmetic: base.vertex_invocations * arithmetic("vs_hidden_layer"),
                    ..base
                }
            }
            Shape::OnscreenBlades {
                kind,
                width,
                instances,
            } => {
                // The fragments known in advance are the pixels the blades cover (a triangle
                // of the blade's height and width); a rasteriser shading whole 4x4 blocks
                // counts several times more (the GPU's counters, where it has them, are what
                // the checks price).
                let vertices = f64::from(instances) * f64::from(STRIP_VERTICES);
                let fragments = f64::from(instances) * ONSCREEN_BLADE_HEIGHT * width.pixels() / 2.0;
                let mut work = Work {
                    vertex_invocations: vertices,
                    primitives: f64::from(instances) * f64::from(STRIP_TRIANGLES),
                    primitive_inputs: f64::from(instances)
                        * f64::from(STRIP_TRIANGLES)
                        * fragment_inputs(layer_fragment_entry(kind)),
                    draw_calls: 1.0,
                    instances: f64::from(instances),
                    vertex_transcendentals: vertices * f64::from(STRIP_VERTEX_TRANSCENDENTALS),
                    vertex_arithmetic: vertices * arithmetic(ONSCREEN_BLADE_VERTEX),
                    fragment_transcendentals: fragments * f64::from(LIT_TRANSCENDENTALS),
                    fragment_arithmetic: fragments * arithmetic(layer_fragment_entry(kind)),
                    ..none
                };
                *work.fragments_mut(kind) = fragments;
                work
            }
            Shape::MathLayers { layers } => {
                let base = self.opaque_layers(layers, size);
                Work {
                    fragment_transcendentals: base.fragments_opaque
                        * f64::from(LIT_TRANSCENDENTALS + MATH_CHAIN),
                    fragment_arithmetic: base.fragments_opaque * arithmetic("fs_math"),
                    ..base
                }
            }
            Shape::ArithmeticLayers { layers } => {
                let base = self.opaque_layers(layers, size);
                Work {
                    fragment_arithmetic: base.fragments_opaque * arithmetic("fs_arithmetic"),
                    ..base
                }
            }
            Shape::FetchLayers { fetch, layers } => {
                // The opaque layers' work, plus each fragment's fetches.
                let base = self.opaque_layers(layers, size);
                let per = |n: u32, of: Fetch| {
                    if fetch == of {
                        base.fragments_opaque * f64::from(n)
                    } else {
                        0.0
                    }
                };
                let ops = shader_ops(fetch.fragment_entry());
                Work {
                    fragment_arithmetic: base.fragments_opaque * ops.arithmetic as f64,
                    texture_loads: per(LOADS_PER_FRAGMENT, Fetch::Loads),
                    float_texture_loads: per(LOADS_PER_FRAGMENT, Fetch::FloatLoads),
                    texture_samples: per(SAMPLES_PER_FRAGMENT, Fetch::Samples)
                        + per(SAMPLES_PER_FRAGMENT, Fetch::SingleLevelSamples)
                        + per(SAMPLES_PER_FRAGMENT, Fetch::ExplicitLevelSamples),
                    float_texture_samples: per(SAMPLES_PER_FRAGMENT, Fetch::FloatSamples),
                    // Read off the shader: the trilinear samples' (tested below).
                    texture_mip_blends: base.fragments_opaque * ops.mip_blends as f64,
                    // Likewise (the explicit-level samples', tested below).
                    texture_explicit_levels: base.fragments_opaque * ops.explicit_levels as f64,
                    ..base
                }
            }
            Shape::Draws { draws } => {
                let vertices = f64::from(draws) * f64::from(DRAW_VERTICES);
                Work {
                    vertex_invocations: vertices,
                    primitives: f64::from(draws),
                    primitive_inputs: f64::from(draws)
                        * fragment_inputs(subpixel_fragment_entry(true)),
                    draw_calls: f64::from(draws),
                    instances: f64::from(draws),
                    vertex_transcendentals: vertices * f64::from(STRIP_VERTEX_TRANSCENDENTALS),
                    vertex_arithmetic: vertices * arithmetic("vs_subpixel"),
                    ..none
                }
            }
            Shape::Compute { groups, chain } => {
                let (x, y) = dispatch_grid(groups);
                let invocations = f64::from(x) * f64::from(y) * f64::from(WORKGROUP_SIZE);
                let ops = shader_ops(chain.compute_entry());
                Work {
                    compute_invocations: invocations,
                    compute_transcendentals: if chain == Chain::Transcendental {
                        invocations * f64::from(MATH_CHAIN)
                    } else {
                        0.0
                    },
                    compute_arithmetic: invocations * arithmetic(chain.compute_entry()),
                    compute_barriers: invocations * ops.barriers as f64,
                    compute_storage: invocations * ops.storage as f64,
                    compute_divisions: invocations * ops.divisions as f64,
                    ..none
                }
            }
            Shape::Upload { bytes } => Work {
                upload_bytes: bytes as f64,
                ..none
            },
        }
    }

    /// The work of `instances` off-screen strips: what the strips that evaluate more per
    /// vertex add to.
    fn offscreen_strips(&self, instances: u32, size: Size) -> Work {
        Workload {
            shape: Shape::OffscreenStrips {
                vertices: STRIP_VERTICES,
                instances,
            },
            ..*self
        }
        .work(size)
    }

    /// The work of `layers` opaque layers on a `size` target: what the layers that fetch or
    /// evaluate more per fragment add to.
    fn opaque_layers(&self, layers: u32, size: Size) -> Work {
        Workload {
            shape: Shape::Layers {
                kind: FragmentKind::Opaque,
                layers,
            },
            ..*self
        }
        .work(size)
    }

    /// The largest factor [`Self::scaled`] may apply. Uploads do not scale (64 MB is already
    /// more than a frame uploads); draw calls only 16x, to 64 k (each is recorded on the CPU,
    /// outside the clock but inside the calibration's time, and every run records its
    /// submission anew).
    pub fn max_scale(&self) -> u32 {
        match self.shape {
            Shape::Empty | Shape::Upload { .. } => 1,
            Shape::Draws { .. } => 16,
            // Strips that price a pass's head keep their largest pass within it: past it,
            // their primitives would be priced as a large pass's.
            Shape::SubpixelStrips { instances, .. }
                if largest_strips_pass(instances) <= PASS_HEAD_PRIMITIVES =>
            {
                u32::try_from(PASS_HEAD_PRIMITIVES / largest_strips_pass(instances).max(1))
                    .unwrap_or(u32::MAX)
                    .clamp(1, 1024)
            }
            _ => 1024,
        }
    }

    /// The same workload `k` times larger (instances, layers, draws or workgroups), `k`
    /// clamped to `1..=max_scale()`.
    pub fn scaled(&self, k: u32) -> Self {
        self.times(k.clamp(1, self.max_scale()))
    }

    /// `k` times larger, unclamped (uploads and the empty workload stay as they are).
    fn times(&self, k: u32) -> Self {
        let shape = match self.shape {
            Shape::OffscreenStrips {
                vertices,
                instances,
            } => Shape::OffscreenStrips {
                vertices,
                instances: instances.saturating_mul(k),
            },
            Shape::SubpixelStrips {
                instances,
                interpolated,
            } => Shape::SubpixelStrips {
                instances: instances.saturating_mul(k),
                interpolated,
            },
            Shape::MathStrips { instances } => Shape::MathStrips {
                instances: instances.saturating_mul(k),
            },
            Shape::ArithmeticStrips { instances } => Shape::ArithmeticStrips {
                instances: instances.saturating_mul(k),
            },
            Shape::LoadStrips { float, instances } => Shape::LoadStrips {
                float,
                instances: instances.saturating_mul(k),
            },
            Shape::StorageStrips { instances } => Shape::StorageStrips {
                instances: instances.saturating_mul(k),
            },
            Shape::MathLayers { layers } => Shape::MathLayers {
                layers: layers.saturating_mul(k),
            },
            Shape::ArithmeticLayers { layers } => Shape::ArithmeticLayers {
                layers: layers.saturating_mul(k),
            },
            Shape::Layers { kind, layers } => Shape::Layers {
                kind,
                layers: layers.saturating_mul(k),
            },
            Shape::OnscreenBlades {
                kind,
                width,
                instances,
            } => Shape::OnscreenBlades {
                kind,
                width,
                instances: instances.saturating_mul(k),
            },
            Shape::HiddenLayers { kind, layers } => Shape::HiddenLayers {
                kind,
                layers: layers.saturating_mul(k),
            },
            Shape::FetchLayers { fetch, layers } => Shape::FetchLayers {
                fetch,
                layers: layers.saturating_mul(k),
            },
            Shape::Draws { draws } => Shape::Draws {
                draws: draws.saturating_mul(k),
            },
            Shape::Compute { groups, chain } => Shape::Compute {
                groups: groups.saturating_mul(k),
                chain,
            },
            other @ (Shape::Empty | Shape::Upload { .. }) => other,
        };
        Self { shape, ..*self }
    }
}

/// The triangles of the largest size ([`SIZE_STEPS`]) of `instances` sub-pixel strips.
fn largest_strips_pass(instances: u32) -> u64 {
    u64::from(instances) * u64::from(STRIP_TRIANGLES) * u64::from(SIZE_STEPS[SIZE_STEPS.len() - 1])
}

/// The families of workloads at their smallest size, sized so that on lavapipe at 640x360
/// the largest size (8x) of each takes some 30-250 ms on the shared 2-core host with another
/// core's worth of work on it (vertices 100 ms, primitives 240, each fragment kind 200-230,
/// draws 30, compute 40-65; uploads of 64 MB 14 ms), and all of it (five rounds, warm-up
/// and scaling probes) 10-15 s. Halving primitives and layers saved 2 s, and the fit's
/// residual rose (8 runs each: RMS 12-20% against 9-18%, though at a host load average of
/// 4-5 against 3.5, so not a clean comparison). A faster adapter scales them up.
pub fn families() -> Vec<Workload> {
    let layers = |name, kind| Workload {
        name,
        term: Term::fragment(kind),
        shape: Shape::Layers { kind, layers: 2 },
    };
    vec![
        Workload {
            name: "empty",
            term: Term::Fixed,
            shape: Shape::Empty,
        },
        Workload {
            name: "vertices",
            term: Term::Vertex,
            shape: Shape::OffscreenStrips {
                vertices: LONG_STRIP_VERTICES,
                instances: 5_000,
            },
        },
        // Eight times the vertices' instances, each of 3 vertices to their 43: an instance
        // costs several vertices on a CPU rasteriser (lavapipe on the Xeon: about 150 ns an
        // instance against 12 ns a vertex, `results/cost_model/segments_probe/`).
        Workload {
            name: "instances",
            term: Term::Instance,
            shape: Shape::OffscreenStrips {
                vertices: SHORT_STRIP_VERTICES,
                instances: 40_000,
            },
        },
        // The same strips twice: with a fragment shader reading none of their slots, then
        // the blade's five, which a rasteriser sets up for each triangle (none covers a pixel
        // centre: no fragment is shaded either way). Both pairs at two scales: passes within
        // the head that a small pass's price covers (5 000 instances, 45 000 to 360 000
        // triangles), and eight times larger (360 000 to 2.88 M, the reference's scale),
        // where lavapipe prices a triangle a third less (`Term::HeadPrimitive`).
        Workload {
            name: "primitives",
            term: Term::HeadPrimitive,
            shape: Shape::SubpixelStrips {
                instances: 5_000,
                interpolated: false,
            },
        },
        Workload {
            name: "primitive_inputs",
            term: Term::PrimitiveInput,
            shape: Shape::SubpixelStrips {
                instances: 5_000,
                interpolated: true,
            },
        },
        Workload {
            name: "large_primitives",
            term: Term::Primitive,
            shape: Shape::SubpixelStrips {
                instances: 40_000,
                interpolated: false,
            },
        },
        Workload {
            name: "large_primitive_inputs",
            term: Term::PrimitiveInput,
            shape: Shape::SubpixelStrips {
                instances: 40_000,
                interpolated: true,
            },
        },
        layers("fragments_opaque", FragmentKind::Opaque),
        layers("fragments_alpha_tested", FragmentKind::AlphaTested),
        layers("fragments_blended", FragmentKind::Blended),
        Workload {
            name: "texture_loads",
            term: Term::TextureLoad,
            shape: Shape::FetchLayers {
                fetch: Fetch::Loads,
                layers: 1,
            },
        },
        Workload {
            name: "single_level_texture_samples",
            term: Term::TextureSample,
            shape: Shape::FetchLayers {
                fetch: Fetch::SingleLevelSamples,
                layers: 1,
            },
        },
        Workload {
            name: "explicit_level_texture_samples",
            term: Term::TextureExplicitLevel,
            shape: Shape::FetchLayers {
                fetch: Fetch::ExplicitLevelSamples,
                layers: 1,
            },
        },
        Workload {
            name: "texture_samples",
            term: Term::TextureMipBlend,
            shape: Shape::FetchLayers {
                fetch: Fetch::Samples,
                layers: 1,
            },
        },
        Workload {
            name: "float_texture_loads",
            term: Term::FloatTextureLoad,
            shape: Shape::FetchLayers {
                fetch: Fetch::FloatLoads,
                layers: 1,
            },
        },
        Workload {
            name: "vertex_texture_loads",
            term: Term::VertexTextureLoad,
            shape: Shape::LoadStrips {
                float: false,
                instances: 5_000,
            },
        },
        Workload {
            name: "vertex_float_texture_loads",
            term: Term::VertexFloatTextureLoad,
            shape: Shape::LoadStrips {
                float: true,
                instances: 5_000,
            },
        },
        Workload {
            name: "float_texture_samples",
            term: Term::FloatTextureSample,
            shape: Shape::FetchLayers {
                fetch: Fetch::FloatSamples,
                layers: 1,
            },
        },
        Workload {
            name: "transcendentals_vertex",
            term: Term::VertexTranscendental,
            shape: Shape::MathStrips { instances: 5_000 },
        },
        Workload {
            name: "transcendentals_fragment",
            term: Term::FragmentTranscendental,
            shape: Shape::MathLayers { layers: 1 },
        },
        Workload {
            name: "transcendentals_compute",
            term: Term::ComputeTranscendental,
            shape: Shape::Compute {
                groups: 4_096,
                chain: Chain::Transcendental,
            },
        },
        Workload {
            name: "arithmetic_vertex",
            term: Term::VertexArithmetic,
            shape: Shape::ArithmeticStrips { instances: 5_000 },
        },
        Workload {
            name: "arithmetic_fragment",
            term: Term::FragmentArithmetic,
            shape: Shape::ArithmeticLayers { layers: 1 },
        },
        Workload {
            name: "arithmetic_compute",
            term: Term::ComputeArithmetic,
            shape: Shape::Compute {
                groups: 4_096,
                chain: Chain::Arithmetic,
            },
        },
        // An eighth of the other compute workloads' invocations: each reaches 8 barriers.
        Workload {
            name: "compute_barriers",
            term: Term::ComputeBarrier,
            shape: Shape::Compute {
                groups: 512,
                chain: Chain::Barriers,
            },
        },
        Workload {
            name: "vertex_storage",
            term: Term::VertexStorage,
            shape: Shape::StorageStrips { instances: 5_000 },
        },
        // Each invocation reads 8 more `vec4`s: about 4 invocations' cost of the spring update.
        Workload {
            name: "compute_storage",
            term: Term::ComputeStorage,
            shape: Shape::Compute {
                groups: 1_024,
                chain: Chain::Storage,
            },
        },
        // Each invocation takes 16 more remainders.
        Workload {
            name: "compute_divisions",
            term: Term::ComputeDivision,
            shape: Shape::Compute {
                groups: 1_024,
                chain: Chain::Divisions,
            },
        },
        Workload {
            name: "draws",
            term: Term::Draw,
            shape: Shape::Draws { draws: 500 },
        },
        Workload {
            name: "compute",
            term: Term::Compute,
            shape: Shape::Compute {
                groups: 4_096,
                chain: Chain::None,
            },
        },
        Workload {
            name: "upload",
            term: Term::Upload,
            shape: Shape::Upload { bytes: 1 << 20 },
        },
    ]
}

/// The fragment entry point of the layers (and the on-screen blades) shaded as `kind`.
pub fn layer_fragment_entry(kind: FragmentKind) -> &'static str {
    match kind {
        FragmentKind::Opaque => "fs_opaque",
        FragmentKind::AlphaTested => "fs_alpha_tested",
        FragmentKind::Blended => "fs_blended",
    }
}

/// The vertex entry point of the strips that load texels (`float`: of the floating-point
/// texture).
pub fn load_strips_entry(float: bool) -> &'static str {
    if float { "vs_float_loads" } else { "vs_loads" }
}

/// A family's samples: its workload at [`SIZE_STEPS`] times `scale`; `empty` four times
/// (it is the fixed cost alone, and one short sample is easily hit by a hiccup of a busy
/// host: four spread over the round cost under 3 ms); uploads at 1, 4, 16 and 64 MiB,
/// steps of 4, as they do not scale.
pub fn sizes(family: &Workload, scale: u32) -> Vec<Workload> {
    match family.shape {
        Shape::Empty => vec![*family; SIZE_STEPS.len()],
        Shape::Upload { bytes } => [1u64, 4, 16, 64]
            .iter()
            .map(|k| Workload {
                shape: Shape::Upload { bytes: bytes * k },
                ..*family
            })
            .collect(),
        _ => SIZE_STEPS
            .iter()
            .map(|&k| family.scaled(scale).times(k))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SIZE: Size = Size {
        width: 640,
        height: 360,
    };

    #[test]
    fn each_family_isolates_its_term() {
        for f in families() {
            let w = sizes(&f, 1).last().copied().unwrap().work(SIZE);
            if f.term == Term::Fixed {
                assert_eq!(w, Work::default());
                continue;
            }
            // Its term is exercised (whether the family tells it apart from the others is the
            // fit's test: `fit::tests`).
            assert!(w.amount(f.term) > 0.0, "{}", f.name);
        }
        // Layers: 1 triangle of 3 vertices per layer (an instance each), every pixel shaded
        // once per layer.
        let w = Workload {
            name: "x",
            term: Term::FragmentBlended,
            shape: Shape::Layers {
                kind: FragmentKind::Blended,
                layers: 3,
            },
        }
        .work(SIZE);
        assert_eq!(
            w,
            Work {
                vertex_invocations: 9.0,
                primitives: 3.0,
                fragments_blended: 3.0 * 640.0 * 360.0,
                draw_calls: 1.0,
                instances: 3.0,
                // Each triangle sets up the five slots `fs_blended` reads; all three triangles
                // are among the pass's first.
                primitive_inputs: 15.0,
                head_primitives: 3.0,
                fragment_transcendentals: 3.0 * 640.0 * 360.0 * f64::from(LIT_TRANSCENDENTALS),
                vertex_arithmetic: 9.0 * shader_ops("vs_layer").arithmetic as f64,
                fragment_arithmetic: 3.0
                    * 640.0
                    * 360.0
                    * shader_ops("fs_blended").arithmetic as f64,
                ..Work::default()
            }
        );
    }

    #[test]
    fn the_shaders_do_what_the_workloads_count() {
        // The cost model counts a pipeline's fetches and transcendentals from its shader
        // (`shaders::ops`): the calibration's own shaders must count to the work known in
        // advance.
        let wgsl = crate::shaders::compose(SHADER);
        let module = naga::front::wgsl::parse_str(&wgsl).unwrap();
        let ops = bound(|b| crate::shaders::entry_ops(&module, b, &[]));
        // Every texture the shader declares is named with its format (the prelude's by the
        // core), at the binding the rig binds it to.
        let mut named: Vec<&str> = texture_formats()
            .iter()
            .chain(&crate::shaders::PRELUDE_TEXTURES)
            .map(|(n, _)| *n)
            .collect();
        named.sort_unstable();
        assert_eq!(crate::shaders::texture_globals(&module), named);
        for t in FETCH_TEXTURES {
            let binding = module
                .global_variables
                .iter()
                .find(|(_, g)| g.name.as_deref() == Some(t.name))
                .and_then(|(_, g)| g.binding);
            assert_eq!(
                binding,
                Some(naga::ResourceBinding {
                    group: 1,
                    binding: t.binding
                }),
                "{}",
                t.name
            );
        }
        // The fetches and transcendentals (the arithmetic is read off the shader: below).
        let of = |entry: &str| {
            ops.iter().find(|(e, _)| e == entry).map(|(_, f)| {
                (
                    f.loads + f.float_loads,
                    f.samples + f.float_samples,
                    f.transcendentals,
                )
            })
        };
        let count = |loads: u32, samples: u32, transcendentals: u32| {
            Some((
                u64::from(loads),
                u64::from(samples),
                u64::from(transcendentals),
            ))
        };
        let lit = LIT_TRANSCENDENTALS;
        assert_eq!(of("fs_loads"), count(LOADS_PER_FRAGMENT, 0, lit));
        assert_eq!(of("fs_samples"), count(0, SAMPLES_PER_FRAGMENT, lit));
        assert_eq!(
            of("fs_single_level_samples"),
            count(0, SAMPLES_PER_FRAGMENT, lit)
        );
        // The trilinear samples blend two mip levels; through the `Nearest` mipmap filter
        // (`SINGLE_LEVEL_SAMPLER`, passed to the shader's functions) none does.
        let blends = |entry: &str| shader_ops(entry).mip_blends;
        assert_eq!(blends("fs_samples"), u64::from(SAMPLES_PER_FRAGMENT));
        assert_eq!(blends("fs_float_samples"), u64::from(SAMPLES_PER_FRAGMENT));
        assert_eq!(blends("fs_single_level_samples"), 0);
        assert_eq!(
            ShaderOps {
                mip_blends: 0,
                ..shader_ops("fs_samples")
            },
            shader_ops("fs_single_level_samples")
        );
        // The explicit-level workload: the one-level samples, each at a level the fragment
        // gives; no other workload's samples pick their level lane by lane.
        assert_eq!(
            of("fs_explicit_level_samples"),
            count(0, SAMPLES_PER_FRAGMENT, lit)
        );
        let explicit = |entry: &str| shader_ops(entry).explicit_levels;
        assert_eq!(
            explicit("fs_explicit_level_samples"),
            u64::from(SAMPLES_PER_FRAGMENT)
        );
        assert_eq!(blends("fs_explicit_level_samples"), 0);
        for f in Fetch::ALL {
            if f != Fetch::ExplicitLevelSamples {
                assert_eq!(explicit(f.fragment_entry()), 0, "{f:?}");
            }
        }
        assert_eq!(of("fs_float_samples"), count(0, SAMPLES_PER_FRAGMENT, lit));
        assert_eq!(of("fs_float_loads"), count(LOADS_PER_FRAGMENT, 0, lit));
        for float in [false, true] {
            assert_eq!(
                of(load_strips_entry(float)),
                count(LOADS_PER_VERTEX, 0, STRIP_VERTEX_TRANSCENDENTALS),
                "{float}"
            );
        }
        // Which fetches are of floating-point texels: the texture's, as its format says,
        // through the functions it is passed to.
        let float = |entry: &str| {
            let o = shader_ops(entry);
            (o.float_loads, o.float_samples)
        };
        assert_eq!(float("fs_loads"), (0, 0));
        assert_eq!(float("vs_loads"), (0, 0));
        assert_eq!(float("vs_float_loads"), (u64::from(LOADS_PER_VERTEX), 0));
        assert_eq!(float("fs_samples"), (0, 0));
        assert_eq!(float("fs_float_loads"), (u64::from(LOADS_PER_FRAGMENT), 0));
        assert_eq!(
            float("fs_float_samples"),
            (0, u64::from(SAMPLES_PER_FRAGMENT))
        );
        for (float, normalised) in [
            ("fs_float_samples", "fs_samples"),
            ("fs_float_loads", "fs_loads"),
            ("vs_float_loads", "vs_loads"),
        ] {
            assert_eq!(
                shader_ops(float).arithmetic,
                shader_ops(normalised).arithmetic
            );
        }
        for fetch in Fetch::ALL {
            assert_eq!(Fetch::ALL[fetch as usize], fetch);
        }
        assert_eq!(of("fs_math"), count(0, 0, lit + MATH_CHAIN));
        assert_eq!(
            of("vs_math"),
            count(0, 0, STRIP_VERTEX_TRANSCENDENTALS + MATH_CHAIN)
        );
        assert_eq!(of("vs_layer"), count(0, 0, 0));
        assert_eq!(of("cs_springs"), count(0, 0, 0));
        assert_eq!(of("cs_math"), count(0, 0, MATH_CHAIN));
        for entry in ["vs_subpixel", "vs_offscreen"] {
            assert_eq!(
                of(entry),
                count(0, 0, STRIP_VERTEX_TRANSCENDENTALS),
                "{entry}"
            );
        }
        for entry in ["fs_opaque", "fs_alpha_tested", "fs_blended"] {
            assert_eq!(of(entry), count(0, 0, lit), "{entry}");
        }
        // The arithmetic chains add what they say, and nothing else costly: the workloads
        // read the rest of each shader's arithmetic off it (`shader_ops`), so every entry
        // point they use must be there.
        assert_eq!(of("vs_arithmetic"), of("vs_offscreen"));
        assert_eq!(of("fs_arithmetic"), of("fs_opaque"));
        assert_eq!(of("cs_arithmetic"), of("cs_springs"));
        for (chain, base) in [
            ("vs_arithmetic", "vs_offscreen"),
            ("fs_arithmetic", "fs_opaque"),
            ("cs_arithmetic", "cs_springs"),
        ] {
            // The chain, and the few operations that feed it and use its result.
            let added = shader_ops(chain).arithmetic - shader_ops(base).arithmetic;
            let chain_ops = u64::from(ARITHMETIC_CHAIN);
            assert!(
                (chain_ops..chain_ops + 16).contains(&added),
                "{chain}: {added} more operations than {base}"
            );
        }
        for entry in [
            "vs_offscreen",
            "vs_subpixel",
            "vs_math",
            "vs_layer",
            "fs_opaque",
            "fs_alpha_tested",
            "fs_blended",
            "fs_math",
            "fs_loads",
            "fs_samples",
            "fs_single_level_samples",
            "fs_float_loads",
            "fs_float_samples",
            "vs_loads",
            "vs_float_loads",
            "cs_springs",
            "cs_math",
            "cs_barriers",
            "cs_storage",
            "cs_divisions",
            "vs_storage",
        ] {
            assert!(shader_ops(entry).arithmetic > 0, "{entry}");
        }
        // The vertex storage strips read their chain and nothing else costly more than the
        // plain off-screen strips (each read's index a remainder by the buffer's length, a
        // division the model prices as arithmetic in a vertex shader); no other vertex or
        // fragment shader reads storage.
        assert_eq!(shader_ops("vs_storage").storage, u64::from(STORAGE_CHAIN));
        assert_eq!(
            shader_ops("vs_storage").divisions,
            u64::from(STORAGE_CHAIN / 4)
        );
        assert_eq!(
            ShaderOps {
                arithmetic: 0,
                storage: 0,
                divisions: 0,
                ..shader_ops("vs_storage")
            },
            ShaderOps {
                arithmetic: 0,
                ..shader_ops("vs_offscreen")
            }
        );
        for entry in [
            "vs_offscreen",
            "vs_subpixel",
            "vs_layer",
            "vs_loads",
            "fs_opaque",
            "fs_loads",
        ] {
            assert_eq!(shader_ops(entry).storage, 0, "{entry}");
        }
        // The barriers' workload reaches its barriers, and it alone: its exchanges' few
        // operations (the neighbour's index) are counted as any. Every spring update reads
        // and writes its element's `vec4` (8 words), found by masking its index (no
        // division); the storage workload reads its chain more, the division workload takes
        // its chain of remainders.
        for (i, chain) in Chain::ALL.iter().enumerate() {
            let ops = shader_ops(chain.compute_entry());
            let (barriers, storage, divisions) = match chain {
                Chain::Barriers => (BARRIER_CHAIN, 8, 0),
                Chain::Storage => (0, 8 + STORAGE_CHAIN, 0),
                Chain::Divisions => (0, 8, DIVISION_CHAIN),
                _ => (0, 8, 0),
            };
            assert_eq!(
                (ops.barriers, ops.storage, ops.divisions),
                (
                    u64::from(barriers),
                    u64::from(storage),
                    u64::from(divisions)
                ),
                "chain {i}"
            );
        }
        assert_eq!(
            ShaderOps {
                arithmetic: 0,
                barriers: 0,
                ..shader_ops("cs_barriers")
            },
            ShaderOps {
                arithmetic: 0,
                ..shader_ops("cs_springs")
            }
        );
        // The storage and division workloads do nothing else costly more than the spring
        // update.
        for entry in ["cs_storage", "cs_divisions"] {
            assert_eq!(
                ShaderOps {
                    arithmetic: 0,
                    storage: 0,
                    divisions: 0,
                    ..shader_ops(entry)
                },
                ShaderOps {
                    arithmetic: 0,
                    storage: 0,
                    divisions: 0,
                    ..shader_ops("cs_springs")
                },
                "{entry}"
            );
        }
    }

    #[test]
    fn vertex_load_strips_load_texels_in_the_vertex_stage_alone() {
        for f in families()
            .into_iter()
            .filter(|f| matches!(f.shape, Shape::LoadStrips { .. }))
        {
            let Shape::LoadStrips { float, instances } = f.shape else {
                unreachable!()
            };
            let w = f.work(SIZE);
            let vertices = f64::from(instances) * f64::from(STRIP_VERTICES);
            let loads = vertices * f64::from(LOADS_PER_VERTEX);
            // The off-screen strips' work (no primitive, no fragment), plus the loads: of the
            // family's format, each counted as a load and as a vertex shader's load.
            assert_eq!(w.vertex_invocations, vertices, "{}", f.name);
            assert_eq!(w.amount(f.term), loads, "{}", f.name);
            let (all, other) = if float {
                (
                    w.float_texture_loads,
                    w.texture_loads + w.vertex_texture_loads,
                )
            } else {
                (
                    w.texture_loads,
                    w.float_texture_loads + w.vertex_float_texture_loads,
                )
            };
            assert_eq!((all, other), (loads, 0.0), "{}", f.name);
            assert_eq!(
                w.primitives + w.fragments_opaque + w.texture_samples + w.float_texture_samples,
                0.0
            );
            assert_eq!(
                (w.draw_calls, w.vertex_transcendentals),
                (1.0, vertices * f64::from(STRIP_VERTEX_TRANSCENDENTALS))
            );
            // The loads and the sum feeding the depth: more arithmetic than the plain strip's.
            assert!(
                w.vertex_arithmetic > vertices * arithmetic("vs_offscreen"),
                "{}",
                f.name
            );
        }
        // Both formats are fitted, and only these strips load in the vertex stage: the
        // fragment workloads' loads are not the vertex stage's.
        let vertex_loaders: Vec<&str> = families()
            .iter()
            .filter(|f| {
                let w = sizes(f, 1)[0].work(SIZE);
                w.vertex_texture_loads + w.vertex_float_texture_loads > 0.0
            })
            .map(|f| f.name)
            .collect();
        assert_eq!(
            vertex_loaders,
            ["vertex_texture_loads", "vertex_float_texture_loads"]
        );
    }

    #[test]
    fn onscreen_blades_are_drawn_as_their_work_counts_them() {
        // The shader's overridable size, set from the workloads' constants.
        let source = crate::shaders::compose(SHADER);
        for (name, _) in BladeWidth::Blade.constants() {
            assert!(source.contains(&format!("override {name}: f32")), "{name}");
        }
        // A blade vertex and its placement: the strips' transcendentals, more arithmetic.
        let ops = shader_ops(ONSCREEN_BLADE_VERTEX);
        assert_eq!(ops.transcendentals, u64::from(STRIP_VERTEX_TRANSCENDENTALS));
        assert!(ops.arithmetic > shader_ops("vs_subpixel").arithmetic / 2);
        for (i, width) in BladeWidth::ALL.iter().enumerate() {
            // The rig's pipelines are indexed by width, then by kind.
            assert_eq!(*width as usize, i);
        }
        for (i, kind) in FragmentKind::ALL.iter().enumerate() {
            assert_eq!(*kind as usize, i);
        }
        assert_eq!(shader_ops("vs_hidden_layer").transcendentals, 0);
    }

    #[test]
    fn chains_are_listed_in_their_order_with_their_entry_points() {
        for (i, chain) in Chain::ALL.iter().enumerate() {
            assert_eq!(*chain as usize, i);
            assert!(
                shader_ops(chain.compute_entry()).arithmetic > 0,
                "{chain:?}"
            );
        }
    }

    #[test]
    fn dispatches_round_up_to_whole_rows() {
        assert_eq!(dispatch_grid(4096), (4096, 1));
        assert_eq!(dispatch_grid(65_535), (65_535, 1));
        assert_eq!(dispatch_grid(65_536), (32_768, 2));
        assert_eq!(dispatch_grid(200_000), (50_000, 4));
        assert_eq!(dispatch_grid(200_001), (50_001, 4));
        let w = Workload {
            name: "compute",
            term: Term::Compute,
            shape: Shape::Compute {
                groups: 200_001,
                chain: Chain::None,
            },
        };
        assert_eq!(w.work(SIZE).compute_invocations, 50_001.0 * 4.0 * 64.0);
    }

    #[test]
    fn sizes_double_and_scaling_is_clamped() {
        let draws = families().into_iter().find(|f| f.name == "draws").unwrap();
        let counts: Vec<f64> = sizes(&draws, 1)
            .iter()
            .map(|w| w.work(SIZE).draw_calls)
            .collect();
        assert_eq!(counts, [500.0, 1000.0, 2000.0, 4000.0]);
        // Draws scale at most 16x; uploads never.
        assert_eq!(sizes(&draws, 1000)[0].work(SIZE).draw_calls, 8000.0);
        let upload = families().into_iter().find(|f| f.name == "upload").unwrap();
        let mb: Vec<f64> = sizes(&upload, 64)
            .iter()
            .map(|w| w.work(SIZE).upload_bytes / f64::from(1u32 << 20))
            .collect();
        assert_eq!(mb, [1.0, 4.0, 16.0, 64.0]);
        assert_eq!(sizes(&families()[0], 8), vec![families()[0]; 4]);
        // The strips that price a pass's head do not scale past it; the large ones draw
        // passes of 1x to 8x the head and scale freely.
        let family = |name| families().into_iter().find(|f| f.name == name).unwrap();
        let head = PASS_HEAD_PRIMITIVES as f64;
        for name in ["primitives", "primitive_inputs"] {
            let f = family(name);
            assert_eq!(f.max_scale(), 1, "{name}");
            let primitives: Vec<f64> = sizes(&f, 64)
                .iter()
                .map(|w| w.work(SIZE).primitives)
                .collect();
            assert_eq!(
                primitives,
                [head / 8.0, head / 4.0, head / 2.0, head],
                "{name}"
            );
            for w in sizes(&f, 64) {
                let w = w.work(SIZE);
                assert_eq!(w.head_primitives, w.primitives, "{name}");
            }
        }
        for name in ["large_primitives", "large_primitive_inputs"] {
            let f = family(name);
            assert_eq!(f.max_scale(), 1024, "{name}");
            let works: Vec<Work> = sizes(&f, 1).iter().map(|w| w.work(SIZE)).collect();
            let primitives: Vec<f64> = works.iter().map(|w| w.primitives).collect();
            assert_eq!(
                primitives,
                [head, 2.0 * head, 4.0 * head, 8.0 * head],
                "{name}"
            );
            for w in works {
                assert_eq!(w.head_primitives, head, "{name}");
            }
        }
        // Strips whose largest pass is an eighth of the head may scale 8x, no more.
        let small = Workload {
            shape: Shape::SubpixelStrips {
                instances: 625,
                interpolated: false,
            },
            ..family("primitives")
        };
        assert_eq!(small.max_scale(), 8);
    }
}
