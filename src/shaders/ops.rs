//! What one shader invocation does that costs more than the invocation itself: its
//! `textureLoad`s (a texel, unfiltered) and `textureSample*`s (filtered: bilinear or
//! trilinear, mip level chosen), those of textures of floating-point texels apart
//! ([`is_float`]), its transcendental built-ins (`sin`, `cos`, `pow`, `exp`, ...) and its
//! scalar arithmetic (each operation once per vector component), counted in the
//! entry point's naga IR and in every function it calls. On a software
//! rasteriser each is a stretch of code per invocation (a transcendental is a polynomial
//! with range reduction, tens of instructions), and the pipeline statistics count
//! invocations, not what happens inside one; these counts let the cost model price that
//! (`crate::cost`): a blade's vertex shader that bends it segment by segment costs several
//! times a vertex that only projects.
//!
//! The count is static: a call counts its callee's operations once per call site, both sides
//! of a branch, and a loop's body as many times as the loop runs where that is known when the
//! pipeline is made (a counter against a constant or a pipeline-overridable constant:
//! [`super::trips`]), once where the data decide. So it is exact for straight-line shaders
//! and loops of fixed length (most of the harness's), an upper bound where a branch skips
//! work (debug views, early returns, a loop left early) and a lower bound where a loop whose
//! trips the data decide runs more than once (jahrmann's binary search over its ranges runs
//! the halvings its pipeline sets, so it is counted by them). A sine and a cosine of the same
//! value count as one transcendental ([`is_shared_cosine`]).
//! On lavapipe, whose SIMD shaders run both sides of a branch for a whole batch, a branch's
//! both sides are what is paid, so there the bound is the cost; and more: code after a return
//! or in a loop that some lanes of a batch may leave early runs masked, a cost of its own the
//! count does not hold (the reference's early return for blades its density test culled, none
//! of them uploaded, cost it 11-23 % of its frame: `results/reference_shader/`). That holds for
//! a branch on a uniform too, which every invocation takes the same way: bakay's fragments
//! branched on its level-of-detail mode, a lookup of each kind per texture, and dropping the
//! side no invocation took made its meadow frames 4-8 ms shorter on lavapipe (now an entry
//! point per mode: `techniques/bakay/src/lib.rs`).

use std::collections::HashMap;

/// The costly operations of one invocation of a shader entry point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
pub struct ShaderOps {
    /// `textureLoad` calls (one texel, no filtering) of textures of integer or normalised
    /// texels (`Rgba8Unorm`, `R8Uint`, ...).
    pub loads: u64,
    /// `textureLoad` calls of textures of floating-point texels ([`is_float`]: `R32Float`,
    /// `Rgba16Float`, ...), which the module's creator names ([`super::module_with_formats`];
    /// the prelude's terrain and wind maps always): WGSL's `texture_2d<f32>` is the same
    /// type for `Rgba8Unorm` and `R32Float`, the format is only known where the texture is
    /// bound, and the two cost differently. On lavapipe, 8-bit normalised texels take a fast
    /// path and floating-point ones a conversion per texel: a load 0.13 ns (`Rgba8Unorm`)
    /// against 0.59-0.63 (`R32Float`) and 0.93 (`Rgba16Float`); a trilinear sample 3.1-3.2 ns
    /// against 5.3-5.7 (`Rgba16Float`): `grassbench calibrate` at 320x180 and 640x360 with
    /// the fetch texture in each format, 2026-12-04. On GPUs 16- and 32-bit channels mean
    /// wider texels (half-rate filtering on most).
    pub float_loads: u64,
    /// `textureSample*` and `textureGather*` calls (filtered) of textures of integer or
    /// normalised texels.
    pub samples: u64,
    /// `textureSample*` and `textureGather*` calls of textures of floating-point texels
    /// ([`is_float`]; see [`ShaderOps::float_loads`]).
    pub float_samples: u64,
    /// Filtered samples (of [`ShaderOps::samples`] and [`ShaderOps::float_samples`]) that
    /// may read and blend two mip levels: all but a gather, a sample at a level the shader
    /// fixes to a whole number (`textureSampleLevel(t, s, uv, 0.0)`), and a sample through
    /// a texture or sampler the module's creator names as reading one level (a texture of
    /// one mip level, a sampler whose mipmap filter is `Nearest`:
    /// [`super::module_with_bindings`]). Whether a trilinear sample's level has a fraction is
    /// the data's, so this is an upper bound where a technique's samples magnify. Blending
    /// a second level is a second bilinear lookup and a blend: lavapipe runs it only where
    /// some lane of the batch needs it (a magnified `Rgba8Unorm` sample 2.6 ns against 4.4-4.6
    /// minified between two levels, `Rgba16Float` 3.2 against 5.1-5.3, `grassbench calibrate`
    /// at 320x180 with the samples' texture magnified, 2026-12-05); most GPUs' texture units
    /// filter trilinearly at half their bilinear rate.
    pub mip_blends: u64,
    /// Filtered samples (of [`ShaderOps::samples`] and [`ShaderOps::float_samples`]) whose
    /// mip level the shader gives each invocation: a `textureSampleLevel` at a level, a
    /// `textureSampleGrad` by derivatives, a `textureSampleBias` by a bias that is not known
    /// when the pipeline is made (a literal, a `const`, an override or arithmetic on them). A
    /// rasteriser picks a sample's level once for a 2x2 quad from its derivatives; given a
    /// level a lane, a SIMD rasteriser
    /// picks it lane by lane (lavapipe: bakay's two lookups a fragment at a level it computes
    /// cost 1.2-2.0 ns a sample more than the same lookups with `textureSample`, its meadow and
    /// flyover at 640x360, 2026-12-07, `results/cost_model/README.md`).
    pub explicit_levels: u64,
    /// Calls of transcendental built-ins (`is_transcendental`).
    pub transcendentals: u64,
    /// Scalar arithmetic operations: every arithmetic, comparison, logical, selection,
    /// conversion and non-transcendental built-in expression, once per component of the
    /// widest of its operands and result (a `vec3` sum is 3, a `mat4x4` times a `vec4` 16, a
    /// `dot` of two `vec3`s 3). What a SIMD rasteriser runs per invocation, one lane each
    /// (lavapipe keeps each component of a vector in a register of its own). Loads, stores,
    /// swizzles and constructors are not counted: they move values.
    pub arithmetic: u64,
    /// Workgroup barriers (compute shaders only): `workgroupBarrier`, `storageBarrier`,
    /// `textureBarrier` one each, `workgroupUniformLoad` two (a barrier before its load and
    /// one after, as every backend writes it). Every invocation of the workgroup waits at
    /// one for the others: a GPU's scheduler switches to another workgroup meanwhile, a CPU
    /// rasteriser suspends the batch of invocations it runs and resumes the next (lavapipe:
    /// 1.8 ns an invocation at a barrier, 40 % of a compute invocation's own cost,
    /// `grassbench calibrate` at 320x180, 2026-12-05).
    pub barriers: u64,
    /// 32-bit words read from or written to storage buffers: every load from and store to a
    /// `var<storage>` (a `vec4<f32>` 4, a `u32` 1), an atomic operation on one 2 (its read and
    /// its write). A SIMD rasteriser moves these one lane at a time where the index differs
    /// between invocations (lavapipe: a `vec4` read by each invocation of a compute shader
    /// from the next element, 1.6 ns an invocation against 4.9 the spring update's whole
    /// invocation, `grassbench calibrate` at 320x180 with 8 more reads, 2026-12-05; 5-6.5 ns
    /// read from elements scattered over 16 MB). Uniform-buffer, workgroup and private
    /// memory are not counted.
    pub storage: u64,
    /// Integer divisions and remainders (`/`, `%` of integers) by a divisor that is not a
    /// constant, one per component. Also counted in [`ShaderOps::arithmetic`]; priced apart
    /// because no SIMD processor divides integers in one instruction: a GPU runs a sequence of
    /// 20 to 40 (a reciprocal and its corrections), a CPU rasteriser one scalar `div` a lane
    /// (lavapipe: jahrmann's culling pass lost 13 ns an invocation, of 92, when its two
    /// remainders by a uniform's value were made remainders by a constant, 2026-12-05). A
    /// constant divisor, `const` or pipeline-overridable, is a multiply and a shift after
    /// the driver's compilation, and is arithmetic only.
    pub divisions: u64,
}

/// Whether `fun` of `arg` is a cosine of a value whose sine the same function takes
/// (`sines`): the pair counts as one transcendental. Compilers share the two's range
/// reduction (a `sincos`); on lavapipe a cosine beside its sine costs next to nothing: the
/// reference's walk with its 5 cosines a vertex replaced by square roots ran no faster, and
/// with each cosine's argument made different from its sine's it ran 7-16 % slower, about
/// the calibrated price of the 5 (`results/reference_shader/`, *A sine and a cosine*). On a
/// GPU whose sine and cosine are separate instructions this counts one too few a pair.
fn is_shared_cosine(
    fun: naga::MathFunction,
    arg: naga::Handle<naga::Expression>,
    sines: &std::collections::HashSet<naga::Handle<naga::Expression>>,
) -> bool {
    fun == naga::MathFunction::Cos && sines.contains(&arg)
}

/// Whether `f` is a transcendental built-in: trigonometric and hyperbolic functions and
/// their inverses, exponentials, logarithms and `pow`. `sqrt`, `inverseSqrt`, `normalize`
/// and `length` are not: they are one or two instructions on every processor the harness
/// targets.
fn is_transcendental(f: naga::MathFunction) -> bool {
    use naga::MathFunction as M;
    matches!(
        f,
        M::Cos
            | M::Cosh
            | M::Sin
            | M::Sinh
            | M::Tan
            | M::Tanh
            | M::Acos
            | M::Asin
            | M::Atan
            | M::Atan2
            | M::Asinh
            | M::Acosh
            | M::Atanh
            | M::Exp
            | M::Exp2
            | M::Log
            | M::Log2
            | M::Pow
    )
}

impl ShaderOps {
    /// What `n` invocations do.
    pub fn times(self, n: u64) -> Self {
        Self {
            loads: self.loads * n,
            float_loads: self.float_loads * n,
            samples: self.samples * n,
            float_samples: self.float_samples * n,
            mip_blends: self.mip_blends * n,
            explicit_levels: self.explicit_levels * n,
            transcendentals: self.transcendentals * n,
            arithmetic: self.arithmetic * n,
            barriers: self.barriers * n,
            storage: self.storage * n,
            divisions: self.divisions * n,
        }
    }
}

impl std::ops::Add for ShaderOps {
    type Output = Self;

    fn add(self, o: Self) -> Self {
        Self {
            loads: self.loads + o.loads,
            float_loads: self.float_loads + o.float_loads,
            samples: self.samples + o.samples,
            float_samples: self.float_samples + o.float_samples,
            mip_blends: self.mip_blends + o.mip_blends,
            explicit_levels: self.explicit_levels + o.explicit_levels,
            transcendentals: self.transcendentals + o.transcendentals,
            arithmetic: self.arithmetic + o.arithmetic,
            barriers: self.barriers + o.barriers,
            storage: self.storage + o.storage,
            divisions: self.divisions + o.divisions,
        }
    }
}

/// Whether texels of `format` are floating-point numbers (16- or 32-bit channels, or packed
/// floats), whose fetches the cost model prices apart ([`ShaderOps::float_loads`],
/// [`ShaderOps::float_samples`]). Normalised and integer formats, sRGB, depth and
/// block-compressed formats are not.
pub fn is_float(format: wgpu::TextureFormat) -> bool {
    use wgpu::TextureFormat as F;
    matches!(
        format,
        F::R16Float
            | F::Rg16Float
            | F::Rgba16Float
            | F::R32Float
            | F::Rg32Float
            | F::Rgba32Float
            | F::Rg11b10Ufloat
            | F::Rgb9e5Ufloat
    )
}

/// What a module's WGSL does not say about the textures and samplers bound to it, and its
/// fetches' count needs: WGSL's `texture_2d<f32>` is the same type for `Rgba8Unorm` and
/// `R32Float` texels and for one mip level or ten, `sampler` the same for every filter.
#[derive(Clone, Copy, Debug, Default)]
pub struct Bound<'a> {
    /// Texture globals bound to textures of floating-point texels ([`is_float`]): their
    /// fetches count as [`ShaderOps::float_loads`] and [`ShaderOps::float_samples`].
    pub float: &'a [&'a str],
    /// Texture and sampler globals through which a filtered sample reads one mip level (a
    /// texture of one level, a sampler whose mipmap filter is `Nearest`): their samples are
    /// not [`ShaderOps::mip_blends`].
    pub single_level: &'a [&'a str],
}

/// The costly operations of every entry point of `module` (a parsed, composed shader), by
/// name; the fetches of the textures and samplers `bound` names counted as it says
/// ([`Bound`]); the loops bounded by pipeline-overridable constants run as
/// many times as `constants` (the pipeline's values, by name: [`super::PipelineSpec::constants`])
/// or the constants' defaults say (`shaders::trips`).
pub fn entry_ops(
    module: &naga::Module,
    bound: Bound<'_>,
    constants: &[(&str, f64)],
) -> Vec<(String, ShaderOps)> {
    count_entries(module, validate(module).as_ref(), bound, constants, None)
}

/// `module`'s expressions' types, which say how many components each operates on; `None` for a
/// module the validator rejects (the device will say why; the op counter then counts one
/// component an expression).
pub(super) fn validate(module: &naga::Module) -> Option<naga::valid::ModuleInfo> {
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(module)
    .ok()
}

/// [`entry_ops`] for a module already validated (`info`: [`validate`]'s answer), of the entry
/// points `only` names (every one where `only` is `None`).
pub(super) fn count_entries(
    module: &naga::Module,
    info: Option<&naga::valid::ModuleInfo>,
    bound: Bound<'_>,
    constants: &[(&str, f64)],
    only: Option<&str>,
) -> Vec<(String, ShaderOps)> {
    let types = Types {
        module,
        info,
        bound,
        constants,
    };
    let mut memo = HashMap::new();
    module
        .entry_points
        .iter()
        .enumerate()
        .filter(|(_, e)| only.is_none_or(|name| e.name == name))
        .map(|(i, e)| {
            let function_info = info.map(|m| m.get_entry_point(i));
            (
                e.name.clone(),
                function_ops(
                    &types,
                    &e.function,
                    function_info,
                    &mut memo,
                    0,
                    Args::default(),
                ),
            )
        })
        .collect()
}

/// The names of `module`'s texture globals, sorted: what a module's creator names with their
/// formats ([`super::module_with_formats`]), for a test to check against.
pub fn texture_globals(module: &naga::Module) -> Vec<String> {
    let mut names: Vec<String> = module
        .global_variables
        .iter()
        .filter(|(_, g)| {
            let inner = match module.types[g.ty].inner {
                naga::TypeInner::BindingArray { base, .. } => &module.types[base].inner,
                ref other => other,
            };
            matches!(inner, naga::TypeInner::Image { .. })
        })
        .filter_map(|(_, g)| g.name.clone())
        .collect();
    names.sort();
    names
}

/// A module, where it validated its expressions' types, what is bound to its textures and
/// samplers and the values of its pipeline-overridable constants.
struct Types<'a> {
    module: &'a naga::Module,
    info: Option<&'a naga::valid::ModuleInfo>,
    bound: Bound<'a>,
    constants: &'a [(&'a str, f64)],
}

/// Which arguments of a function are textures and samplers [`Bound`] names (bit `i`: argument
/// `i`), as its caller passed them: its fetches' count depends on them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
struct Args {
    /// Textures of floating-point texels ([`Bound::float`]).
    float: u64,
    /// Textures and samplers that read one mip level ([`Bound::single_level`]).
    single_level: u64,
}

impl Types<'_> {
    /// Whether texture or sampler expression `e` of `function` is a global among `names`, an
    /// argument whose bit is set in `args` (the caller passed one), or an element of either (a
    /// binding array).
    fn is_named(
        &self,
        function: &naga::Function,
        e: naga::Handle<naga::Expression>,
        names: &[&str],
        args: u64,
    ) -> bool {
        match &function.expressions[e] {
            naga::Expression::GlobalVariable(g) => self.module.global_variables[*g]
                .name
                .as_deref()
                .is_some_and(|n| names.contains(&n)),
            naga::Expression::FunctionArgument(i) => *i < 64 && args >> i & 1 == 1,
            naga::Expression::Access { base, .. } | naga::Expression::AccessIndex { base, .. } => {
                self.is_named(function, *base, names, args)
            }
            _ => false,
        }
    }

    /// Whether image expression `image` of `function` is one of the textures of
    /// floating-point texels ([`Bound::float`]; `args`: what the caller passed).
    fn is_float(
        &self,
        function: &naga::Function,
        image: naga::Handle<naga::Expression>,
        args: Args,
    ) -> bool {
        self.is_named(function, image, self.bound.float, args.float)
    }

    /// Whether texture or sampler expression `e` of `function` reads one mip level
    /// ([`Bound::single_level`]; `args`: what the caller passed).
    fn is_single_level(
        &self,
        function: &naga::Function,
        e: naga::Handle<naga::Expression>,
        args: Args,
    ) -> bool {
        self.is_named(function, e, self.bound.single_level, args.single_level)
    }

    /// The [`Args`] of a call of `function`'s callee with `arguments`.
    fn args_of(
        &self,
        function: &naga::Function,
        arguments: &[naga::Handle<naga::Expression>],
        args: Args,
    ) -> Args {
        let mask = |test: &dyn Fn(naga::Handle<naga::Expression>) -> bool| {
            arguments
                .iter()
                .take(64)
                .enumerate()
                .filter(|(_, a)| test(**a))
                .fold(0u64, |m, (i, _)| m | 1 << i)
        };
        Args {
            float: mask(&|a| self.is_float(function, a, args)),
            single_level: mask(&|a| self.is_single_level(function, a, args)),
        }
    }
}

/// Whether a sample at `level` reads one mip level whatever the texture and sampler: level 0
/// (`SampleLevel::Zero`) or a literal whole number (`textureSampleLevel(t, s, uv, 0.0)`).
fn is_whole_level(function: &naga::Function, level: &naga::SampleLevel) -> bool {
    let naga::SampleLevel::Exact(e) = level else {
        return matches!(level, naga::SampleLevel::Zero);
    };
    let naga::Expression::Literal(literal) = function.expressions[*e] else {
        return false;
    };
    match literal {
        naga::Literal::F32(x) => x.fract() == 0.0,
        naga::Literal::F64(x) | naga::Literal::AbstractFloat(x) => x.fract() == 0.0,
        naga::Literal::I16(_)
        | naga::Literal::U16(_)
        | naga::Literal::I32(_)
        | naga::Literal::U32(_)
        | naga::Literal::I64(_)
        | naga::Literal::U64(_)
        | naga::Literal::AbstractInt(_) => true,
        _ => false,
    }
}

/// Whether a sample at `level` takes its level from each invocation rather than from its
/// quad's derivatives: an explicit level, a bias or derivatives that are not constants
/// ([`ShaderOps::explicit_levels`]).
fn is_explicit_level(function: &naga::Function, level: &naga::SampleLevel) -> bool {
    match level {
        naga::SampleLevel::Exact(e) | naga::SampleLevel::Bias(e) => !is_constant(function, *e),
        naga::SampleLevel::Gradient { x, y } => {
            !(is_constant(function, *x) && is_constant(function, *y))
        }
        naga::SampleLevel::Auto | naga::SampleLevel::Zero => false,
    }
}

/// Scalar components of expression `e`'s value (1 for scalars, and where its type is unknown).
fn components(
    types: &Types<'_>,
    info: Option<&naga::valid::FunctionInfo>,
    e: naga::Handle<naga::Expression>,
) -> u64 {
    let Some(info) = info else { return 1 };
    match info[e].ty.inner_with(&types.module.types) {
        naga::TypeInner::Vector { size, .. } => *size as u64,
        naga::TypeInner::Matrix { columns, rows, .. } => *columns as u64 * *rows as u64,
        _ => 1,
    }
}

/// Whether pointer expression `pointer` points into a storage buffer (unknown types: no).
fn is_storage(
    types: &Types<'_>,
    info: Option<&naga::valid::FunctionInfo>,
    pointer: naga::Handle<naga::Expression>,
) -> bool {
    let Some(info) = info else { return false };
    matches!(
        info[pointer].ty.inner_with(&types.module.types),
        naga::TypeInner::Pointer {
            space: naga::AddressSpace::Storage { .. },
            ..
        } | naga::TypeInner::ValuePointer {
            space: naga::AddressSpace::Storage { .. },
            ..
        }
    )
}

/// 32-bit words of expression `e`'s value (its type's size, at least 1).
fn words(
    types: &Types<'_>,
    info: Option<&naga::valid::FunctionInfo>,
    e: naga::Handle<naga::Expression>,
) -> u64 {
    let Some(info) = info else { return 1 };
    let bytes = info[e]
        .ty
        .inner_with(&types.module.types)
        .size(types.module.to_ctx());
    u64::from(bytes / 4).max(1)
}

/// Scalar operations of expression `e` of `function` ([`ShaderOps::arithmetic`]).
fn arithmetic_of(
    types: &Types<'_>,
    function: &naga::Function,
    info: Option<&naga::valid::FunctionInfo>,
    e: naga::Handle<naga::Expression>,
) -> u64 {
    use naga::Expression as E;
    let width = |operands: &[naga::Handle<naga::Expression>]| {
        operands
            .iter()
            .map(|&o| components(types, info, o))
            .chain([components(types, info, e)])
            .max()
            .unwrap_or(1)
    };
    match &function.expressions[e] {
        E::Binary { left, right, .. } => width(&[*left, *right]),
        E::Unary { expr, .. } | E::As { expr, .. } => width(&[*expr]),
        E::Select {
            condition,
            accept,
            reject,
        } => width(&[*condition, *accept, *reject]),
        E::Relational { argument, .. } => width(&[*argument]),
        E::Math {
            fun,
            arg,
            arg1,
            arg2,
            arg3,
        } if !is_transcendental(*fun) => {
            let operands: Vec<_> = [Some(*arg), *arg1, *arg2, *arg3]
                .into_iter()
                .flatten()
                .collect();
            width(&operands)
        }
        _ => 0,
    }
}

/// Whether expression `e` of `function` is an integer division or remainder by a divisor that
/// is not a constant ([`ShaderOps::divisions`]; as many as its [`arithmetic_of`] components).
fn divides_by_a_variable(
    types: &Types<'_>,
    function: &naga::Function,
    info: Option<&naga::valid::FunctionInfo>,
    e: naga::Handle<naga::Expression>,
) -> bool {
    use naga::BinaryOperator as B;
    let naga::Expression::Binary {
        op: B::Divide | B::Modulo,
        right,
        ..
    } = function.expressions[e]
    else {
        return false;
    };
    info.is_some_and(|info| {
        matches!(
            info[e].ty.inner_with(&types.module.types).scalar_kind(),
            Some(naga::ScalarKind::Sint | naga::ScalarKind::Uint)
        )
    }) && !is_constant(function, right)
}

/// Whether expression `e` of `function` is known when the pipeline is created: a literal, a
/// `const`, a pipeline-overridable constant, a vector built of them, or arithmetic on them
/// (the driver folds `CHUNK + 1u` once the pipeline fixes `CHUNK`).
fn is_constant(function: &naga::Function, e: naga::Handle<naga::Expression>) -> bool {
    use naga::Expression as E;
    match &function.expressions[e] {
        E::Literal(_) | E::Constant(_) | E::Override(_) | E::ZeroValue(_) => true,
        E::Splat { value, .. } => is_constant(function, *value),
        E::Compose { components, .. } => components.iter().all(|&c| is_constant(function, c)),
        E::AccessIndex { base, .. } => is_constant(function, *base),
        E::Unary { expr, .. } | E::As { expr, .. } => is_constant(function, *expr),
        E::Binary { left, right, .. } => {
            is_constant(function, *left) && is_constant(function, *right)
        }
        _ => false,
    }
}

/// Deepest call chain followed (WGSL forbids recursion; this only bounds a malformed IR).
const MAX_CALL_DEPTH: u32 = 64;

/// A function and what its texture and sampler arguments are bound to: its operations depend
/// on both.
type CallKey = (naga::Handle<naga::Function>, Args);

/// The operations of `function`: its own image and math expressions plus its callees', once
/// per call site. `args` says which arguments are textures of floating-point texels (the
/// prelude's `bilinear_r(height_map, uv)`) and which textures or samplers read one level.
fn function_ops(
    types: &Types<'_>,
    function: &naga::Function,
    info: Option<&naga::valid::FunctionInfo>,
    memo: &mut HashMap<CallKey, ShaderOps>,
    depth: u32,
    args: Args,
) -> ShaderOps {
    let is_float = |image| types.is_float(function, image, args);
    let blends = |image, sampler, gather: &Option<_>, level: &naga::SampleLevel| {
        gather.is_none()
            && !is_whole_level(function, level)
            && !types.is_single_level(function, image, args)
            && !types.is_single_level(function, sampler, args)
    };
    let module = types.module;
    let trips = super::trips::Trips::new(module, function, types.constants);
    let trips = |s: &naga::Statement| trips.of(s);
    // How many times each expression is evaluated an invocation: those a statement emits as
    // often as that statement runs, the rest (constants, arguments, globals) once.
    let mut weights = vec![1; function.expressions.len()];
    super::walk::for_each_weighted(&function.body, 1, &trips, &mut |s, weight| {
        if let naga::Statement::Emit(range) = s {
            for h in range.clone() {
                if let Some(w) = weights.get_mut(h.index()) {
                    *w = weight;
                }
            }
        }
    });
    // The values this function takes the sine of: a cosine of one of them is not counted (a
    // sine and a cosine of the same value are one `sincos`, [`is_shared_cosine`]).
    let sines: std::collections::HashSet<_> = function
        .expressions
        .iter()
        .filter_map(|(_, e)| match e {
            naga::Expression::Math {
                fun: naga::MathFunction::Sin,
                arg,
                ..
            } => Some(*arg),
            _ => None,
        })
        .collect();
    let one = |h: naga::Handle<naga::Expression>, e: &naga::Expression| {
        let none = ShaderOps::default();
        let fetched = match e {
            naga::Expression::Load { pointer } if is_storage(types, info, *pointer) => ShaderOps {
                storage: words(types, info, h),
                ..none
            },
            naga::Expression::ImageSample {
                image,
                sampler,
                gather,
                level,
                ..
            } => {
                let float = is_float(*image);
                ShaderOps {
                    samples: u64::from(!float),
                    float_samples: u64::from(float),
                    mip_blends: u64::from(blends(*image, *sampler, gather, level)),
                    explicit_levels: u64::from(
                        gather.is_none() && is_explicit_level(function, level),
                    ),
                    ..none
                }
            }
            naga::Expression::ImageLoad { image, .. } if is_float(*image) => ShaderOps {
                float_loads: 1,
                ..none
            },
            naga::Expression::ImageLoad { .. } => ShaderOps { loads: 1, ..none },
            naga::Expression::Math { fun, arg, .. } if is_transcendental(*fun) => ShaderOps {
                transcendentals: u64::from(!is_shared_cosine(*fun, *arg, &sines)),
                ..none
            },
            _ => none,
        };
        let arithmetic = arithmetic_of(types, function, info, h);
        ShaderOps {
            arithmetic,
            divisions: if divides_by_a_variable(types, function, info, h) {
                arithmetic
            } else {
                0
            },
            ..fetched
        }
    };
    // Each expression's operations, as many times as it is evaluated.
    let own = function
        .expressions
        .iter()
        .fold(ShaderOps::default(), |acc, (h, e)| {
            acc + one(h, e).times(weights[h.index()])
        });
    let mut calls: Vec<(CallKey, u64)> = Vec::new();
    let mut barriers = 0;
    let mut storage = own.storage;
    super::walk::for_each_weighted(&function.body, 1, &trips, &mut |s, weight| {
        barriers += weight
            * match s {
                naga::Statement::ControlBarrier(_) => 1,
                naga::Statement::WorkGroupUniformLoad { .. } => 2,
                _ => 0,
            };
        storage += weight
            * match s {
                naga::Statement::Store { pointer, value } if is_storage(types, info, *pointer) => {
                    words(types, info, *value)
                }
                naga::Statement::Atomic { pointer, .. } if is_storage(types, info, *pointer) => 2,
                _ => 0,
            };
        if let naga::Statement::Call {
            function: callee,
            arguments,
            ..
        } = s
        {
            calls.push(((*callee, types.args_of(function, arguments, args)), weight));
        }
    });
    let own = ShaderOps {
        barriers,
        storage,
        ..own
    };
    calls.into_iter().fold(own, |acc, (key, times)| {
        let ops = match memo.get(&key) {
            Some(f) => *f,
            None if depth < MAX_CALL_DEPTH => {
                let (callee, callee_args) = key;
                let callee_info = types.info.map(|m| &m[callee]);
                let f = function_ops(
                    types,
                    &module.functions[callee],
                    callee_info,
                    memo,
                    depth + 1,
                    callee_args,
                );
                memo.insert(key, f);
                f
            }
            None => ShaderOps::default(),
        };
        acc + ops.times(times)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SOURCE: &str = "
        @group(0) @binding(0) var t: texture_2d<f32>;
        @group(0) @binding(1) var s: sampler;
        fn height(p: vec2<i32>) -> f32 {
            return textureLoad(t, p, 0).r + textureLoad(t, p + vec2(1, 0), 0).r;
        }
        fn tint(uv: vec2<f32>) -> vec4<f32> {
            return textureSample(t, s, uv) * height(vec2(0, 0)) * pow(uv.x, 2.2);
        }
        @vertex fn vs(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
            let h = height(vec2(i32(v), 0)) + height(vec2(0, i32(v)));
            let a = f32(v);
            return vec4(h, sin(a), cos(a), sqrt(a) + length(vec2(a)));
        }
        @fragment fn fs(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {
            var c = tint(uv);
            if (uv.x > 0.5) {
                c += textureSampleLevel(t, s, uv, 1.0);
            }
            for (var i = 0; i < 4; i++) {
                c += textureSampleGrad(t, s, uv, vec2(0.1), vec2(0.1)) * exp2(uv.y);
            }
            return c;
        }
        @fragment fn plain(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {
            return vec4(uv, 0.0, 1.0);
        }
        @group(0) @binding(2) var u: texture_2d<f32>;
        fn load_from(m: texture_2d<f32>, p: vec2<i32>) -> f32 {
            return textureLoad(m, p, 0).r;
        }
        @fragment fn passes(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {
            return vec4(load_from(t, vec2(0)) + load_from(u, vec2(1)) + load_from(t, vec2(2)));
        }
    ";

    fn of(name: &str) -> ShaderOps {
        of_with(name, &[])
    }

    fn of_with(name: &str, float: &[&str]) -> ShaderOps {
        let bound = Bound {
            float,
            single_level: &[],
        };
        entry_ops(&naga::front::wgsl::parse_str(SOURCE).unwrap(), bound, &[])
            .into_iter()
            .find(|(n, _)| n == name)
            .map(|(_, f)| f)
            .unwrap_or_else(|| panic!("no entry {name}"))
    }

    /// A cosine counts nothing beside a sine of the same value, in the same function; of
    /// another value, or alone, or beside a sine in another function, it counts one.
    #[test]
    fn a_sine_and_a_cosine_of_one_value_count_once() {
        let source = "
            fn sine(x: f32) -> f32 { return sin(x); }
            @vertex fn pair(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
                let a = f32(v);
                return vec4(sin(a), cos(a), 0.0, 1.0);
            }
            @vertex fn apart(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
                let a = f32(v);
                return vec4(sin(a), cos(a + 1.0), cos(a * 2.0), 1.0);
            }
            @vertex fn across(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
                let a = f32(v);
                return vec4(sine(a), cos(a), 0.0, 1.0);
            }
        ";
        let module = naga::front::wgsl::parse_str(source).unwrap();
        let bound = Bound {
            float: &[],
            single_level: &[],
        };
        let transcendentals: HashMap<String, u64> = entry_ops(&module, bound, &[])
            .into_iter()
            .map(|(name, ops)| (name, ops.transcendentals))
            .collect();
        assert_eq!(transcendentals["pair"], 1);
        assert_eq!(transcendentals["apart"], 3);
        assert_eq!(transcendentals["across"], 2);
    }

    #[test]
    fn calls_count_per_call_site_branches_once_and_loops_per_trip() {
        // Two calls of a two-load function; `sin` and `cos` of the same value, one `sincos`
        // (`sqrt` and `length` are not transcendental). Arithmetic: each `height` call's `vec2<i32>` sum (2) and scalar
        // sum (1), the two `i32` and one `f32` conversions, the heights' sum, `sqrt`,
        // `length` of a `vec2` (2) and their sum.
        assert_eq!(
            of("vs"),
            ShaderOps {
                loads: 4,
                float_loads: 0,
                samples: 0,
                float_samples: 0,
                mip_blends: 0,
                explicit_levels: 0,
                transcendentals: 1,
                arithmetic: 6 + 3 + 1 + 1 + 2 + 1,
                barriers: 0,
                storage: 0,
                divisions: 0,
            }
        );
        // tint: 1 sample + height's 2 loads + a `pow`; the branch's sample; the loop body's
        // sample and `exp2` four times (its trips). Arithmetic: tint's two `vec4` products (8)
        // and height's 3; the branch's test (1) and `vec4` sum (4); the loop's test and step
        // (2) and its body's `vec4` product and sum (8), four times.
        assert_eq!(
            of("fs"),
            ShaderOps {
                loads: 2,
                float_loads: 0,
                samples: 1 + 1 + 4,
                float_samples: 0,
                // tint's and the loop's; the branch's is at level 1, a whole one.
                mip_blends: 1 + 4,
                explicit_levels: 0,
                transcendentals: 1 + 4,
                arithmetic: 11 + 5 + 4 * (2 + 8),
                barriers: 0,
                storage: 0,
                divisions: 0,
            }
        );
        assert_eq!(of("plain"), ShaderOps::default());
    }

    #[test]
    fn loops_bounded_by_overrides_count_the_pipelines_trips_and_data_bound_ones_once() {
        let module = naga::front::wgsl::parse_str(
            "override SHELLS: u32 = 4u;
             @group(0) @binding(0) var<storage, read_write> out: array<vec4<f32>>;
             @group(0) @binding(1) var<storage, read> bounds: array<u32>;
             fn shell(k: u32) -> f32 { return sin(f32(k)); }
             @compute @workgroup_size(64)
             fn cs(@builtin(global_invocation_id) id: vec3<u32>) {
                 for (var k = 0u; k < SHELLS; k++) {
                     out[k] = vec4(shell(k));
                 }
                 for (var k = 0u; k < bounds[id.x]; k++) {
                     out[id.x] = vec4(cos(f32(k)));
                 }
             }",
        )
        .unwrap();
        let cs = |constants: &[(&str, f64)]| {
            entry_ops(&module, Bound::default(), constants)
                .into_iter()
                .find(|(n, _)| n == "cs")
                .map(|(_, o)| o)
                .unwrap_or_default()
        };
        // Each trip of the first loop: its test and step, and a call of `shell` (a
        // conversion and a `sin`), a `vec4` stored. The second loop's trips are the data's:
        // counted once, its test, step, conversion and `cos`, its bound's word and its `vec4`.
        let of_shells = |shells: u64| ShaderOps {
            transcendentals: shells + 1,
            arithmetic: 3 * shells + 3,
            storage: 4 * shells + 1 + 4,
            ..ShaderOps::default()
        };
        assert_eq!(cs(&[]), of_shells(4), "the override's default");
        assert_eq!(cs(&[("SHELLS", 16.0)]), of_shells(16));
        assert_eq!(
            cs(&[("SHELLS", 0.0)]),
            of_shells(1),
            "the exit test still runs"
        );
    }

    #[test]
    fn barriers_count_per_call_site_and_a_uniform_load_twice() {
        let module = naga::front::wgsl::parse_str(
            "var<workgroup> cells: array<u32, 64>;
             var<workgroup> total: u32;
             fn exchange(lid: u32) -> u32 {
                 workgroupBarrier();
                 return cells[(lid + 1u) % 64u];
             }
             @compute @workgroup_size(64)
             fn cs(@builtin(local_invocation_index) lid: u32) {
                 cells[lid] = lid;
                 let a = exchange(lid) + exchange(lid);
                 for (var k = 0u; k < 4u; k++) { storageBarrier(); }
                 let t = workgroupUniformLoad(&total);
                 cells[lid] = a + t;
             }
             @compute @workgroup_size(64)
             fn plain(@builtin(local_invocation_index) lid: u32) { cells[lid] = lid; }",
        )
        .unwrap();
        let ops = entry_ops(&module, Bound::default(), &[]);
        let barriers = |name: &str| ops.iter().find(|(n, _)| n == name).map(|(_, o)| o.barriers);
        // Two calls of a one-barrier function, a loop's body four times, and a uniform
        // load's barrier before and after it.
        assert_eq!(barriers("cs"), Some(2 + 4 + 2));
        assert_eq!(barriers("plain"), Some(0));
    }

    #[test]
    fn storage_words_count_loads_stores_and_atomics_of_storage_buffers_alone() {
        let module = naga::front::wgsl::parse_str(
            "struct Block { count: atomic<u32>, n: u32, items: array<vec4<f32>> }
             @group(0) @binding(0) var<storage, read_write> block: Block;
             @group(0) @binding(1) var<storage, read> ids: array<u32>;
             @group(0) @binding(2) var<uniform> u: vec4<f32>;
             var<workgroup> cells: array<u32, 64>;
             fn item(i: u32) -> vec4<f32> { return block.items[i]; }
             @compute @workgroup_size(64)
             fn cs(@builtin(local_invocation_index) lid: u32) {
                 let i = ids[lid];
                 let a = item(i) + item(i + 1u);
                 cells[lid] = i;
                 var p = a * u.x;
                 block.items[i] = p;
                 atomicAdd(&block.count, 1u);
                 block.items[i].x = f32(block.n) + f32(arrayLength(&block.items));
                 let c = atomicLoad(&block.count) + cells[0];
                 block.items[c] = vec4(0.0);
             }
             @compute @workgroup_size(64)
             fn plain(@builtin(local_invocation_index) lid: u32) { cells[lid] = lid; }",
        )
        .unwrap();
        let ops = entry_ops(&module, Bound::default(), &[]);
        let storage = |name: &str| ops.iter().find(|(n, _)| n == name).map(|(_, o)| o.storage);
        // `ids[lid]` 1; `item` twice, a `vec4` each, 8; the `vec4` stored 4; the atomic add 2
        // (read and write); the component stored 1 and `block.n` read 1; the atomic load 1;
        // the last `vec4` stored 4. The workgroup cells, the uniform, the local `p` and
        // `arrayLength` (the binding's size, no memory read) count nothing.
        assert_eq!(storage("cs"), Some(1 + 8 + 4 + 2 + 1 + 1 + 1 + 4));
        assert_eq!(storage("plain"), Some(0));
    }

    #[test]
    fn integer_divisions_by_values_unknown_to_the_pipeline_count_apart() {
        let module = naga::front::wgsl::parse_str(
            "const FOUR: u32 = 4u;
             override lanes: u32 = 8u;
             @group(0) @binding(0) var<uniform> u: vec4<u32>;
             @group(0) @binding(1) var<storage, read_write> out: array<vec2<u32>>;
             fn bucket(id: u32) -> u32 { return id % max(u.y, 1u); }
             @compute @workgroup_size(64)
             fn cs(@builtin(global_invocation_id) id: vec3<u32>) {
                 let a = bucket(id.x) + bucket(id.y);
                 let b = vec2(id.x, id.y) / vec2(u.x, u.z);
                 let side = lanes + 1u;
                 let c = id.x / 3u + id.y % FOUR + id.z / lanes + id.x / vec2(2u, 5u).y
                     + id.y % side + id.z / ((side * side + 63u) / 64u) + id.x / (u.x + 1u);
                 let d = i32(id.z) / -2;
                 let f = f32(id.x) / f32(u.w);
                 for (var k = 0u; k < 3u; k++) {
                     out[k] = b + vec2(a + c + u32(d) + u32(f) + k % u.w);
                 }
             }
             @compute @workgroup_size(64)
             fn plain(@builtin(global_invocation_id) id: vec3<u32>) {
                 out[id.x] = id.xy / 2u;
             }",
        )
        .unwrap();
        let ops = entry_ops(&module, Bound::default(), &[]);
        let divisions = |name: &str| {
            ops.iter()
                .find(|(n, _)| n == name)
                .map(|(_, o)| o.divisions)
        };
        // `bucket`'s remainder by a uniform's value at two call sites (2), a `vec2` divided
        // by a `vec2` read from the uniform (2), a division by the uniform's value plus one
        // (1), the loop's remainder by `u.w` three times (3). Divisions by a literal, a
        // `const`, an override, arithmetic on an override, a component of a constant vector
        // and a negative literal are a multiply and a shift; the `f32` one is arithmetic.
        assert_eq!(divisions("cs"), Some(2 + 2 + 1 + 3));
        assert_eq!(divisions("plain"), Some(0));
    }

    #[test]
    fn samples_at_a_level_of_their_own_are_told_from_those_a_quad_picks() {
        let module = naga::front::wgsl::parse_str(
            "@group(0) @binding(0) var t: texture_2d<f32>;
             @group(0) @binding(1) var s: sampler;
             const LEVEL: f32 = 1.5;
             override BIAS: f32 = 0.5;
             @fragment fn fs(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {
                 let lod = log2(length(dpdx(uv)) * 512.0);
                 return textureSample(t, s, uv)                         // the quad's level
                     + textureSampleLevel(t, s, uv, 0.0)                // level 0
                     + textureSampleLevel(t, s, uv, LEVEL * 2.0)        // known when made
                     + textureSampleLevel(t, s, uv, lod)                // a lane's own level
                     + textureSampleLevel(t, s, uv, uv.x)               // a lane's own level
                     + textureSampleGrad(t, s, uv, dpdx(uv), dpdy(uv))  // a lane's derivatives
                     + textureSampleGrad(t, s, uv, vec2(0.1), vec2(0.2)) // known when made
                     + textureSampleBias(t, s, uv, BIAS)                // known when made
                     + textureSampleBias(t, s, uv, uv.y)                // a lane's own bias
                     + textureGather(0, t, s, uv);                      // no level to pick
             }",
        )
        .unwrap();
        let fs = entry_ops(&module, Bound::default(), &[])
            .into_iter()
            .find(|(e, _)| e == "fs")
            .map(|(_, o)| (o.samples, o.explicit_levels));
        assert_eq!(fs, Some((10, 4)));
    }

    #[test]
    fn samples_blend_two_mip_levels_unless_their_level_or_binding_says_one() {
        let module = naga::front::wgsl::parse_str(
            "@group(0) @binding(0) var t: texture_2d<f32>;
             @group(0) @binding(1) var one: texture_2d<f32>;
             @group(0) @binding(2) var s: sampler;
             @group(0) @binding(3) var nearest: sampler;
             fn through(tex: texture_2d<f32>, smp: sampler, uv: vec2<f32>) -> vec4<f32> {
                 return textureSample(tex, smp, uv);
             }
             @fragment fn fs(@location(0) uv: vec2<f32>) -> @location(0) vec4<f32> {
                 return textureSample(t, s, uv)                 // blends
                     + textureSampleLevel(t, s, uv, 2.0)        // a whole level
                     + textureSampleLevel(t, s, uv, uv.x)       // the data's level: blends
                     + textureSampleLevel(t, s, uv, 0.5)        // between two levels
                     + textureSampleBias(t, s, uv, 1.0)         // blends
                     + textureGather(0, t, s, uv)               // four texels of one level
                     + textureSample(one, s, uv)                // a texture of one level
                     + textureSample(t, nearest, uv)            // a `Nearest` mipmap filter
                     + through(t, s, uv)                        // blends
                     + through(t, nearest, uv)                  // the caller's sampler
                     + through(one, s, uv);                     // the caller's texture
             }",
        )
        .unwrap();
        let fs = |single_level: &[&str]| {
            let bound = Bound {
                float: &[],
                single_level,
            };
            entry_ops(&module, bound, &[])
                .into_iter()
                .find(|(e, _)| e == "fs")
                .map(|(_, o)| (o.samples, o.mip_blends))
        };
        assert_eq!(fs(&["one", "nearest"]), Some((11, 5)));
        // Nothing named: every sample but the whole level's and the gather's may blend.
        assert_eq!(fs(&[]), Some((11, 9)));
    }

    #[test]
    fn fetches_of_textures_named_float_are_counted_apart() {
        // `t` bound to floating-point texels: its loads and samples move (in the callees
        // too); a name that is not a global changes nothing.
        let normalised = of("fs");
        assert_eq!(
            of_with("fs", &["t"]),
            ShaderOps {
                loads: 0,
                float_loads: 2,
                samples: 0,
                float_samples: 6,
                ..normalised
            }
        );
        assert_eq!(of_with("fs", &["s", "uv"]), normalised);
        assert_eq!(
            of_with("vs", &["t"]),
            ShaderOps {
                loads: 0,
                float_loads: 4,
                ..of("vs")
            }
        );
        // A texture passed to a function is the caller's: `t` twice, `u` once.
        let passes = |float: &[&str]| {
            let o = of_with("passes", float);
            (o.loads, o.float_loads)
        };
        assert_eq!(passes(&[]), (3, 0));
        assert_eq!(passes(&["t"]), (1, 2));
        assert_eq!(passes(&["u"]), (2, 1));
        assert_eq!(passes(&["t", "u"]), (0, 3));
        // The module's textures (`s` is a sampler).
        let module = naga::front::wgsl::parse_str(SOURCE).unwrap();
        assert_eq!(texture_globals(&module), ["t", "u"]);
    }

    #[test]
    fn float_texels_are_16_or_32_bit_floats() {
        use wgpu::TextureFormat as F;
        for f in [
            F::Rgba16Float,
            F::Rgba32Float,
            F::Rg32Float,
            F::R32Float,
            F::Rg16Float,
            F::Rg11b10Ufloat,
        ] {
            assert!(is_float(f), "{f:?}");
        }
        for f in [
            F::Rgba8Unorm,
            F::Rgba8UnormSrgb,
            F::Rgba16Unorm,
            F::R8Uint,
            F::R32Uint,
            F::Depth32Float,
            F::Bc1RgbaUnorm,
            F::Bc6hRgbUfloat,
        ] {
            assert!(!is_float(f), "{f:?}");
        }
    }
}
