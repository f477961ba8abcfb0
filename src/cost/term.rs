//! The terms of the cost model: what a frame's GPU time is made of, one unit cost each.

/// One term of the cost model. A frame's predicted GPU time is `Σ cost(term) × amount(term)`
/// over [`Term::ALL`], the amounts read from a [`super::Work`] by [`super::Work::amount`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Term {
    /// What every submission pays whatever it draws: submitting, waking the driver, clearing
    /// and storing the target at the calibration size, waiting. One per frame.
    Fixed,
    /// A vertex shader invocation (with the culling test of the primitives it belongs to).
    Vertex,
    /// A triangle that reached rasterisation (the clipper's output): setup, binning and the
    /// coverage test. Not among the units issue 20 lists: on a software rasteriser triangle
    /// setup and binning are a large cost of their own, paid by a triangle that covers no
    /// pixel as much as by one that covers a few, so neither vertices nor fragments can stand
    /// for it (lavapipe: a sub-pixel triangle costs several vertex invocations). This is the
    /// price of a primitive in a large pass; the first
    /// [`crate::technique::work::PASS_HEAD_PRIMITIVES`] of each segment pay
    /// [`Term::HeadPrimitive`] on top.
    Primitive,
    /// A fragment shader invocation of an opaque, depth-tested pipeline (early depth test).
    FragmentOpaque,
    /// A fragment shader invocation of a pipeline that may discard (alpha test, or alpha to
    /// coverage): the depth test and write wait for the shader.
    FragmentAlphaTested,
    /// A fragment shader invocation of an alpha-blended pipeline (reads the target back).
    FragmentBlended,
    /// A draw call.
    Draw,
    /// A compute shader invocation.
    Compute,
    /// A megabyte (10⁶ bytes) written to a buffer with `queue.write_buffer` before the
    /// submission.
    Upload,
    /// A texel read with `textureLoad` by a vertex or fragment shader invocation (on top of the
    /// invocation's own cost; counted from the shader, `crate::shaders::ShaderOps`).
    TextureLoad,
    /// A texel of floating-point format (`R32Float`, `Rgba16Float`, ...) read with
    /// `textureLoad` (`crate::shaders::ShaderOps::float_loads`): the prelude's terrain and wind
    /// maps. Not among the units issue 20 lists: the load term is calibrated on an RGBA8
    /// texture, and lavapipe converts floating-point texels outside its 8-bit fast path (an
    /// `R32Float` load 0.59-0.63 ns against an `Rgba8Unorm` one's 0.13).
    FloatTextureLoad,
    /// A texel of normalised or integer format read with `textureLoad` by a vertex shader
    /// invocation: what it costs on top of [`Term::TextureLoad`], which every load pays. Not
    /// among the units issue 20 lists: the load terms are fitted on fragment shaders' loads,
    /// and lavapipe shades vertices in the thread that records the draws, one vertex at a
    /// time where a fragment shader runs on a worker thread over a block of pixels (timed as
    /// an unfitted probe on the 2-vCPU EPYC host before the term: 1.8-2.2 ns a load in the
    /// vertex stage against 0.9-1.2 fitted on fragments).
    VertexTextureLoad,
    /// A texel of floating-point format read with `textureLoad` by a vertex shader
    /// invocation, on top of [`Term::FloatTextureLoad`]: a blade's vertex reading the
    /// terrain's height and the wind at its root (the EPYC probe: 5.1-6.1 ns an `R32Float`
    /// load in the vertex stage against 2.1-2.8 fitted on fragments).
    VertexFloatTextureLoad,
    /// A filtered texture sample (`textureSample*`) by a vertex or fragment shader invocation,
    /// of one mip level: on a software rasteriser the filtering (the level, the bilinear taps)
    /// is code run per sample. Where a sample may blend two levels, the second is
    /// [`Term::TextureMipBlend`].
    TextureSample,
    /// A filtered sample of a texture of floating-point texels (`Rgba16Float`;
    /// `crate::shaders::ShaderOps::float_samples`). Not among the units issue 20 lists: the
    /// sample term is calibrated on an RGBA8 texture, and filtering floating-point texels
    /// costs more (lavapipe: 5.4-5.7 ns against 3.2 trilinear, 2.7-3.1 against 2.1-2.5 at one
    /// level, a conversion per texel outside its 8-bit fast path; half-rate filtering of
    /// 64-bit texels on most GPUs). boulanger's slices are `Rgba16Float`.
    FloatTextureSample,
    /// A transcendental built-in (`sin`, `cos`, `pow`, `exp`, ...) evaluated by a vertex
    /// shader invocation (counted from the shader, `crate::shaders::ShaderOps`). Not among
    /// the units issue 20 lists: the vertex term is calibrated on one vertex shader, and a
    /// blade's vertex shader that bends it segment by segment, a `pow`, `sin` and `cos` a
    /// segment, costs several times that one on a software rasteriser (lavapipe: 30 more
    /// transcendentals a vertex raised the vertex workload's fitted cost from 19 to 75 ns).
    VertexTranscendental,
    /// A transcendental built-in evaluated by a fragment shader invocation: priced apart from
    /// the vertex stage's, as the stages run their shaders differently (lavapipe: a
    /// fragment's cost a fraction of a vertex's; one term for both left the vertex
    /// workload 43 % under its fit).
    FragmentTranscendental,
    /// A transcendental built-in evaluated by a compute shader invocation.
    ComputeTranscendental,
    /// A scalar arithmetic operation (`crate::shaders::ShaderOps::arithmetic`) of a vertex
    /// shader invocation. Not among the units issue 20 lists: a vertex invocation's cost is
    /// calibrated on one small vertex shader, and a blade's vertex shader that bends, tapers
    /// and lights it does several times its arithmetic; what the vertex term leaves out.
    VertexArithmetic,
    /// A scalar arithmetic operation of a fragment shader invocation.
    FragmentArithmetic,
    /// A scalar arithmetic operation of a compute shader invocation. Calibrated on a chain of
    /// multiply-adds (lavapipe: 0.011-0.015 ns an operation; a chain of comparisons,
    /// selections, conversions and square roots priced the same in a probe, one 16 `vec4`s
    /// wide lower, a scalar chain whose every operation waits for the last 9-10 times
    /// higher). jahrmann's compute pass (772-796 operations an invocation) costs more than
    /// this prices, for reasons its longest dependent chain does not explain (a term priced on
    /// that chain was fitted and not landed: `results/cost_model/README.md`, *jahrmann's compute
    /// pass* and *Probes after this version*).
    ComputeArithmetic,
    /// A workgroup barrier reached by a compute shader invocation
    /// (`crate::shaders::ShaderOps::barriers`). Not among the units issue 20 lists: the
    /// compute term is calibrated on a spring update with no barrier, and a CPU rasteriser
    /// pays for each, suspending the workgroup's batch of invocations and resuming the next
    /// (lavapipe: 1.8 ± 0.16 ns an invocation at a barrier against 4.8 ns the invocation,
    /// `grassbench calibrate` at 320x180, 2026-12-05). jahrmann's culling pass has three
    /// (a `workgroupBarrier` and a `workgroupUniformLoad`) in each invocation.
    ComputeBarrier,
    /// A 32-bit word a compute shader invocation reads from or writes to a storage buffer
    /// (`crate::shaders::ShaderOps::storage`). Not among the units issue 20 lists: the
    /// compute term is calibrated on a spring update that reads and writes one `vec4`, and
    /// a SIMD rasteriser moves a storage buffer's words one lane at a time where the index
    /// differs between invocations (lavapipe: 8 more `vec4` reads an invocation, each from
    /// the next element, raised the spring update from 4.9 to 18 ns; `grassbench calibrate`
    /// at 320x180, 2026-12-05). jahrmann's culling pass reads four `vec4`s of each blade,
    /// writes two and searches the frame's ranges in its storage block.
    ComputeStorage,
    /// A 32-bit word a vertex shader invocation reads from a storage buffer
    /// (`crate::shaders::ShaderOps::storage`): a blade's or a patch's data pulled by its
    /// vertices rather than fed as vertex attributes. Not among the units issue 20 lists: the
    /// vertex term is calibrated on strips whose vertices read nothing from memory, and
    /// jahrmann's vertices read 17 words each (the blade's index, its root, looks and
    /// curve), perbet's 12-26 (its patch's and wind primitives' data).
    VertexStorage,
    /// An integer division or remainder by a divisor the pipeline does not fix, in a compute
    /// shader invocation (`crate::shaders::ShaderOps::divisions`), on top of its arithmetic
    /// operation. Not among the units issue 20 lists: the arithmetic term is calibrated on
    /// multiply-adds, and no SIMD processor divides integers in one instruction (a GPU runs a
    /// sequence of 20 to 40, a CPU rasteriser a scalar `div` a lane). jahrmann's culling pass
    /// takes two remainders by a uniform's value (a blade's distance bucket and whether the
    /// far level keeps it): making them remainders by a constant took 13 ns from its 92 ns
    /// an invocation on lavapipe (2026-12-05).
    ComputeDivision,
    /// What a filtered sample costs more where it may read and blend two mip levels
    /// (`crate::shaders::ShaderOps::mip_blends`), on top of [`Term::TextureSample`] or
    /// [`Term::FloatTextureSample`], which every sample pays. Not among the units issue 20
    /// lists: the sample terms were calibrated on samples minified between two levels, and a
    /// sample at a whole level (a sampler whose mipmap filter is `Nearest`, as bakay's custom
    /// mip levels need; a `textureSampleLevel` at level 0, as zhang's blades) filters one: a
    /// second bilinear lookup and a blend saved (lavapipe: an `Rgba8Unorm` sample 2.6 ns
    /// magnified against 4.4-4.6 between two levels, an `Rgba16Float` one 3.2 against 5.1-5.3,
    /// `grassbench calibrate` at 320x180, 2026-12-05; most GPUs filter trilinearly at half
    /// their bilinear rate).
    TextureMipBlend,
    /// An instance of a draw call: what a draw pays once per instance, whatever its vertices
    /// (`crate::technique::PassCounts`; an indirect draw's instance count is read back from
    /// its arguments). Not among the units issue 20 lists: the vertex and primitive terms
    /// were calibrated on instanced strips of one shape, which folds a per-instance cost into
    /// their prices, and a software rasteriser pays one (lavapipe's draw module runs each
    /// instance as a pass of its own over the instance's vertices, in SIMD batches the last
    /// of which is partly empty): the reference with 1 to 12 segments a blade cost about
    /// 150 ns a blade that no other count saw (`results/cost_model/segments_probe/`,
    /// 2026-12-06). Calibrated on strips of 3 vertices an instance beside the `vertices`
    /// workload's strips of 43 (`crate::cost::workloads`): 110-124 ns an instance there.
    Instance,
    /// An input slot of the fragment shader (`@location`), set up for a primitive that reached
    /// rasterisation: on top of [`Term::Primitive`], which every primitive pays. Not among the
    /// units issue 20 lists: a rasteriser computes a plane equation for each interpolated slot
    /// of every triangle it sets up, before it knows whether the triangle covers a pixel
    /// (lavapipe on the Xeon, sub-pixel strips covering no pixel centre: 68 ns a triangle whose
    /// fragment shader reads no slot, 73.5 with one `vec3`, 99.9 with three, 135 with the
    /// calibration's five; `grassbench calibrate` at 640x360, 2026-12-06). The primitive term
    /// alone, calibrated on five slots, over-priced a technique's triangles whose shader reads
    /// fewer (the reference's three). One price whatever the pass's size: fitted on strips at
    /// both the primitives' scales, the calibration cannot tell a small pass's slot from a large
    /// one's (a head's extra fitted on the Xeon at 0.6 ± 2.5 and 1.7 ± 2.2 ns a slot, on top
    /// of 7.3-7.5; 2026-12-07).
    PrimitiveInput,
    /// A filtered sample whose mip level the shader gives each invocation
    /// (`crate::shaders::ShaderOps::explicit_levels`: a `textureSampleLevel` at a level not
    /// known when the pipeline is made, a `textureSampleGrad`, a `textureSampleBias` by such a
    /// bias), on top of [`Term::TextureSample`] or [`Term::FloatTextureSample`], which every
    /// sample pays. Not among the units issue 20 lists: the sample terms are calibrated on
    /// `textureSample`, whose level a rasteriser picks once for a 2x2 quad, and a SIMD
    /// rasteriser picks a level lane by lane where the shader gives one a lane. lavapipe on the
    /// Xeon: bakay's two lookups a fragment at the level it computes (`lod = "minor_axis"`)
    /// cost 1.2-2.0 ns a sample more than the same lookups made `textureSample`s, its meadow
    /// and flyover at 640x360, medians of three rounds each way (2026-12-07): 20.7 ms of the
    /// 27.6 by which the model under-predicted its meadow. The calibration prices it at
    /// 0.75-1.07 ns (`results/cost_model/README.md`, *Samples at a level of their own*).
    TextureExplicitLevel,
    /// A primitive among the first [`crate::technique::work::PASS_HEAD_PRIMITIVES`] that
    /// reached rasterisation in its segment, on top of [`Term::Primitive`], which every
    /// primitive pays: a pass's price for its primitives in two parts. Not among the units
    /// issue 20 lists: lavapipe prices a primitive less the more its pass draws, as it
    /// rasterises a large pass on its worker threads while the recording thread still bins it,
    /// and a small pass mostly after (on the Xeon, the calibration's strips at its shipped
    /// scale, passes of up to 360 000 primitives: 74-81 ns a primitive; at 8x, passes of up to
    /// 2.88 M: 55-62 ns). One price fitted on small passes over-priced the reference's 2.5 M
    /// primitives a frame (its runs 0.67-0.79 of the prediction, 2026-12-07). Calibrated by
    /// the `primitives` workload beside `large_primitives` (`crate::cost::workloads`): on
    /// the Xeon 25.5-31.8 ns (standard errors 4.1-4.7) on top of a primitive's 44.8-48.9,
    /// and the reference within ±25 % on every cost-model run (0.82-0.94). One step at 360 000
    /// approximates a price that falls gradually: under 4x MSAA it fits the head strips worst
    /// of the workloads and prices small passes low (`results/cost_model/README.md`, *Two
    /// prices for a primitive*).
    HeadPrimitive,
}

impl Term {
    /// Every term, in the order of the model's columns.
    pub const ALL: [Self; 30] = [
        Self::Fixed,
        Self::Vertex,
        Self::Primitive,
        Self::FragmentOpaque,
        Self::FragmentAlphaTested,
        Self::FragmentBlended,
        Self::Draw,
        Self::Compute,
        Self::Upload,
        Self::TextureLoad,
        Self::FloatTextureLoad,
        Self::VertexTextureLoad,
        Self::VertexFloatTextureLoad,
        Self::TextureSample,
        Self::FloatTextureSample,
        Self::VertexTranscendental,
        Self::FragmentTranscendental,
        Self::ComputeTranscendental,
        Self::VertexArithmetic,
        Self::FragmentArithmetic,
        Self::ComputeArithmetic,
        Self::ComputeBarrier,
        Self::ComputeStorage,
        Self::VertexStorage,
        Self::ComputeDivision,
        Self::TextureMipBlend,
        Self::Instance,
        Self::PrimitiveInput,
        Self::TextureExplicitLevel,
        Self::HeadPrimitive,
    ];

    /// Short name, as in files and messages (`fragment_opaque`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Fixed => "fixed",
            Self::Vertex => "vertex",
            Self::Primitive => "primitive",
            Self::FragmentOpaque => "fragment_opaque",
            Self::FragmentAlphaTested => "fragment_alpha_tested",
            Self::FragmentBlended => "fragment_blended",
            Self::Draw => "draw",
            Self::Compute => "compute",
            Self::Upload => "upload",
            Self::TextureLoad => "texture_load",
            Self::FloatTextureLoad => "float_texture_load",
            Self::VertexTextureLoad => "vertex_texture_load",
            Self::VertexFloatTextureLoad => "vertex_float_texture_load",
            Self::TextureSample => "texture_sample",
            Self::FloatTextureSample => "float_texture_sample",
            Self::VertexTranscendental => "vertex_transcendental",
            Self::FragmentTranscendental => "fragment_transcendental",
            Self::ComputeTranscendental => "compute_transcendental",
            Self::VertexArithmetic => "vertex_arithmetic",
            Self::FragmentArithmetic => "fragment_arithmetic",
            Self::ComputeArithmetic => "compute_arithmetic",
            Self::ComputeBarrier => "compute_barrier",
            Self::ComputeStorage => "compute_storage",
            Self::VertexStorage => "vertex_storage",
            Self::ComputeDivision => "compute_division",
            Self::TextureMipBlend => "texture_mip_blend",
            Self::Instance => "instance",
            Self::PrimitiveInput => "primitive_input",
            Self::TextureExplicitLevel => "texture_explicit_level",
            Self::HeadPrimitive => "head_primitive",
        }
    }

    /// What one unit of the term is (the amount [`super::Work::amount`] counts).
    pub fn unit(self) -> &'static str {
        match self {
            Self::Fixed => "submission",
            Self::Vertex => "vertex invocation",
            Self::Primitive => "primitive",
            Self::FragmentOpaque | Self::FragmentAlphaTested | Self::FragmentBlended => {
                "fragment invocation"
            }
            Self::Draw => "draw call",
            Self::Compute => "compute invocation",
            Self::Upload => "MB",
            Self::TextureLoad => "texel load",
            Self::FloatTextureLoad => "float texel load",
            Self::VertexTextureLoad => "vertex texel load",
            Self::VertexFloatTextureLoad => "vertex float texel load",
            Self::TextureSample => "texture sample",
            Self::FloatTextureSample => "float texture sample",
            Self::VertexTranscendental
            | Self::FragmentTranscendental
            | Self::ComputeTranscendental => "transcendental",
            Self::VertexArithmetic | Self::FragmentArithmetic | Self::ComputeArithmetic => {
                "scalar operation"
            }
            Self::ComputeBarrier => "invocation at a barrier",
            Self::ComputeStorage | Self::VertexStorage => "storage word",
            Self::ComputeDivision => "integer division",
            Self::TextureMipBlend => "sample blending two mip levels",
            Self::Instance => "instance",
            Self::PrimitiveInput => "input slot of a primitive",
            Self::TextureExplicitLevel => "sample at a level of its own",
            Self::HeadPrimitive => "primitive of a pass's head",
        }
    }

    /// Milliseconds per unit of the figure [`super::UnitCosts`] stores for the term: 1 for
    /// the terms stored in ms (fixed, upload), 10⁻⁶ for those stored in ns.
    pub fn ms_per_stored_unit(self) -> f64 {
        match self {
            Self::Fixed | Self::Upload => 1.0,
            _ => 1e-6,
        }
    }

    /// The fragment term of fragments of `kind`.
    pub fn fragment(kind: super::FragmentKind) -> Self {
        match kind {
            super::FragmentKind::Opaque => Self::FragmentOpaque,
            super::FragmentKind::AlphaTested => Self::FragmentAlphaTested,
            super::FragmentKind::Blended => Self::FragmentBlended,
        }
    }

    /// Position in [`Term::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }
}

impl std::fmt::Display for Term {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_is_the_position_in_all() {
        for (i, t) in Term::ALL.iter().enumerate() {
            assert_eq!(t.index(), i, "{t}");
        }
    }
}
