//! [`UnitCosts`]: an adapter's cost per unit of work, as fitted by [`super::fit`], and the
//! prediction of a frame's GPU time from its [`Work`] ([`UnitCosts::predict`]).

use super::{FitSummary, Term, Work};

/// One fitted unit cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct UnitCost {
    /// The cost, in the unit its field in [`UnitCosts`] names.
    pub value: f64,
    /// Its standard error from the fit (same unit): the spread of the samples' residuals
    /// carried through the design, as for an unconstrained least-squares fit.
    pub standard_error: f64,
    /// Whether the fit held the cost at zero: the unconstrained optimum was negative, so the
    /// term costs less than the calibration can resolve against the others' noise.
    #[serde(default)]
    pub at_zero: bool,
}

#[cfg(test)]
impl UnitCost {
    /// A cost known exactly (no standard error), held at zero only where it is zero: the
    /// tests' fixtures.
    pub(crate) fn exact(value: f64) -> Self {
        Self {
            value,
            standard_error: 0.0,
            at_zero: value == 0.0,
        }
    }
}

/// An adapter's unit costs: what one unit of each kind of work adds to a frame's GPU time,
/// fitted jointly over the calibration's micro-workloads. Written to `meta.toml` under
/// `[unit_costs]` beside the adapter's provenance.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct UnitCosts {
    /// Target size the workloads drew at (`640x360`): the fixed cost clears and stores a
    /// target of this size, and fragment costs depend somewhat on tiling.
    pub size: String,
    /// Which clock timed the samples.
    pub clock: String,
    /// Whether the workloads drew into a multisampled target (4x MSAA, as
    /// [`crate::RenderTarget::new`] makes one; [`crate::cost::Options::msaa`]). A run drawn
    /// with MSAA does work a single-sampled calibration does not
    /// (per-sample coverage and depth tests, the resolve; lavapipe on the 2.6 GHz EPYC: the
    /// reference on the papers' meadows at 320x180 with 4x MSAA took 1.35-1.64 times the
    /// single-sampled model of its work, `results/papers/`, against 1.12-1.22 on the meadow
    /// single-sampled, `results/cost_model/epyc_zen4/`), so the model prices only
    /// runs drawn as its costs were ([`UnitCosts::prices`]). Files from before the field were
    /// single-sampled.
    #[serde(default)]
    pub msaa: bool,
    /// Cores other processes kept busy, on average, while the samples ran (0 on a quiet
    /// host): on a software rasteriser they slow every figure and widen the residuals.
    /// `None` where not measured (no `/proc`, or costs fitted elsewhere).
    #[serde(default)]
    pub host_other_cores: Option<f64>,
    /// Per submission (frame), ms.
    pub fixed_ms: UnitCost,
    /// Per vertex shader invocation, ns.
    pub vertex_ns: UnitCost,
    /// Per primitive reaching rasterisation, ns.
    pub primitive_ns: UnitCost,
    /// Per opaque depth-tested fragment shader invocation, ns.
    pub fragment_opaque_ns: UnitCost,
    /// Per fragment shader invocation of a pipeline that may discard, ns.
    pub fragment_alpha_tested_ns: UnitCost,
    /// Per blended fragment shader invocation, ns.
    pub fragment_blended_ns: UnitCost,
    /// Per draw call, ns.
    pub draw_ns: UnitCost,
    /// Per compute shader invocation, ns.
    pub compute_invocation_ns: UnitCost,
    /// Per megabyte (10⁶ bytes) uploaded with `queue.write_buffer`, ms.
    pub upload_ms_per_mb: UnitCost,
    /// Per texel read with `textureLoad`, ns (0 in calibrations made before the term).
    #[serde(default)]
    pub texture_load_ns: UnitCost,
    /// Per floating-point texel read with `textureLoad`, ns (0 in calibrations made before
    /// the term).
    #[serde(default)]
    pub float_texture_load_ns: UnitCost,
    /// Per texel a vertex shader reads with `textureLoad`, on top of `texture_load_ns`, ns
    /// (0 in calibrations made before the term).
    #[serde(default)]
    pub vertex_texture_load_ns: UnitCost,
    /// Per floating-point texel a vertex shader reads with `textureLoad`, on top of
    /// `float_texture_load_ns`, ns (0 in calibrations made before the term).
    #[serde(default)]
    pub vertex_float_texture_load_ns: UnitCost,
    /// Per filtered texture sample, ns (0 in calibrations made before the term).
    #[serde(default)]
    pub texture_sample_ns: UnitCost,
    /// Per filtered sample of a texture of floating-point texels, ns (0 in calibrations made before the
    /// term).
    #[serde(default)]
    pub float_texture_sample_ns: UnitCost,
    /// Per transcendental built-in evaluated by a vertex shader, ns (0 in calibrations made
    /// before the term).
    #[serde(default)]
    pub vertex_transcendental_ns: UnitCost,
    /// Per transcendental built-in evaluated by a fragment shader, ns (0 before the term).
    #[serde(default)]
    pub fragment_transcendental_ns: UnitCost,
    /// Per transcendental built-in evaluated by a compute shader, ns (0 before the term).
    #[serde(default)]
    pub compute_transcendental_ns: UnitCost,
    /// Per scalar arithmetic operation of a vertex shader, ns (0 in calibrations made before
    /// the term).
    #[serde(default)]
    pub vertex_arithmetic_ns: UnitCost,
    /// Per scalar arithmetic operation of a fragment shader, ns (0 before the term).
    #[serde(default)]
    pub fragment_arithmetic_ns: UnitCost,
    /// Per scalar arithmetic operation of a compute shader, ns (0 before the term).
    #[serde(default)]
    pub compute_arithmetic_ns: UnitCost,
    /// Per compute shader invocation reaching a workgroup barrier, ns (0 before the term).
    #[serde(default)]
    pub compute_barrier_ns: UnitCost,
    /// Per 32-bit word a compute shader reads from or writes to a storage buffer, ns (0
    /// before the term).
    #[serde(default)]
    pub compute_storage_ns: UnitCost,
    /// Per 32-bit word a vertex shader reads from a storage buffer, ns (0 before the term).
    #[serde(default)]
    pub vertex_storage_ns: UnitCost,
    /// Per integer division or remainder by a divisor the pipeline does not fix, in a compute
    /// shader, ns (0 before the term).
    #[serde(default)]
    pub compute_division_ns: UnitCost,
    /// Per filtered sample that may blend two mip levels, on top of its sample's cost, ns (0
    /// before the term).
    #[serde(default)]
    pub texture_mip_blend_ns: UnitCost,
    /// Per instance drawn, ns (0 before the term: calibrations made before it folded the
    /// instances into the vertex and primitive prices).
    #[serde(default)]
    pub instance_ns: UnitCost,
    /// Per fragment shader input slot of a primitive reaching rasterisation, on top of
    /// `primitive_ns`, ns (0 before the term: calibrations made before it priced their
    /// primitives with their calibration's five slots).
    #[serde(default)]
    pub primitive_input_ns: UnitCost,
    /// Per filtered sample at a level the shader gives each invocation, on top of its
    /// sample's cost, ns (0 before the term: calibrations made before it priced such samples
    /// as those whose level a quad picks).
    #[serde(default)]
    pub texture_explicit_level_ns: UnitCost,
    /// Per primitive among the first [`crate::technique::work::PASS_HEAD_PRIMITIVES`] of its
    /// segment, on top of `primitive_ns`, ns (0 before the term: calibrations made before it
    /// priced every primitive at a small pass's price, `primitive_ns` alone).
    #[serde(default)]
    pub head_primitive_ns: UnitCost,
    /// How well the costs explain the samples they were fitted to.
    pub fit: FitSummary,
    /// The coverage checks ([`super::checks`]), timed with the samples and priced with these
    /// costs: how far the prices hold for fragments unlike the fitted layers' (blades on
    /// screen, hidden layers). Empty in files from before them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub checks: Vec<super::checks::CheckResult>,
}

/// A frame's predicted GPU time, split by term.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Prediction {
    /// The sum of the terms, ms.
    pub total_ms: f64,
    /// The fixed per-submission cost, ms.
    pub fixed_ms: f64,
    /// Vertex invocations, ms.
    pub vertex_ms: f64,
    /// Primitives, ms.
    pub primitive_ms: f64,
    /// Opaque fragments, ms.
    pub fragment_opaque_ms: f64,
    /// Alpha-tested fragments, ms.
    pub fragment_alpha_tested_ms: f64,
    /// Blended fragments, ms.
    pub fragment_blended_ms: f64,
    /// Draw calls, ms.
    pub draw_ms: f64,
    /// Compute invocations, ms.
    pub compute_ms: f64,
    /// Uploads, ms.
    pub upload_ms: f64,
    /// Texel loads, ms.
    #[serde(default)]
    pub texture_load_ms: f64,
    /// Floating-point texel loads, ms.
    #[serde(default)]
    pub float_texture_load_ms: f64,
    /// Vertex shaders' texel loads, on top of their `texture_load_ms`, ms.
    #[serde(default)]
    pub vertex_texture_load_ms: f64,
    /// Vertex shaders' floating-point texel loads, on top of their `float_texture_load_ms`,
    /// ms.
    #[serde(default)]
    pub vertex_float_texture_load_ms: f64,
    /// Texture samples, ms.
    #[serde(default)]
    pub texture_sample_ms: f64,
    /// Samples of textures of floating-point texels, ms.
    #[serde(default)]
    pub float_texture_sample_ms: f64,
    /// Vertex shaders' transcendental built-ins, ms.
    #[serde(default)]
    pub vertex_transcendental_ms: f64,
    /// Fragment shaders' transcendental built-ins, ms.
    #[serde(default)]
    pub fragment_transcendental_ms: f64,
    /// Compute shaders' transcendental built-ins, ms.
    #[serde(default)]
    pub compute_transcendental_ms: f64,
    /// Vertex shaders' scalar arithmetic, ms.
    #[serde(default)]
    pub vertex_arithmetic_ms: f64,
    /// Fragment shaders' scalar arithmetic, ms.
    #[serde(default)]
    pub fragment_arithmetic_ms: f64,
    /// Compute shaders' scalar arithmetic, ms.
    #[serde(default)]
    pub compute_arithmetic_ms: f64,
    /// Compute shaders' workgroup barriers, ms.
    #[serde(default)]
    pub compute_barrier_ms: f64,
    /// Compute shaders' storage-buffer words, ms.
    #[serde(default)]
    pub compute_storage_ms: f64,
    /// Vertex shaders' storage-buffer words, ms.
    #[serde(default)]
    pub vertex_storage_ms: f64,
    /// Compute shaders' integer divisions, ms.
    #[serde(default)]
    pub compute_division_ms: f64,
    /// Filtered samples' second mip level, ms.
    #[serde(default)]
    pub texture_mip_blend_ms: f64,
    /// The draws' instances, ms.
    #[serde(default)]
    pub instance_ms: f64,
    /// The primitives' fragment input slots, ms.
    #[serde(default)]
    pub primitive_input_ms: f64,
    /// Samples' levels picked lane by lane, ms.
    #[serde(default)]
    pub texture_explicit_level_ms: f64,
    /// What the first primitives of each segment cost on top of the others', ms.
    #[serde(default)]
    pub head_primitive_ms: f64,
}

impl UnitCosts {
    /// Whether these costs price a run drawn with `msaa` (4x MSAA) or without: only one
    /// drawn as the calibration drew ([`UnitCosts::msaa`]).
    pub fn prices(&self, msaa: bool) -> bool {
        self.msaa == msaa
    }

    /// Of `all` (one calibration's costs, one per target it drew), those calibrated at `size`
    /// (`640x360`) drawn as `msaa` says: the costs that price a run on that target.
    pub fn for_target<'a>(all: &'a [Self], size: &str, msaa: bool) -> Option<&'a Self> {
        all.iter().find(|c| c.size == size && c.prices(msaa))
    }

    /// Builds the record from one cost per term in **ms per unit** ([`Term::unit`]), in the
    /// order of [`Term::ALL`], converting each to the unit its field stores.
    pub fn from_ms_per_unit(
        size: String,
        clock: String,
        per_unit_ms: [UnitCost; Term::ALL.len()],
        fit: FitSummary,
    ) -> Self {
        let stored = |t: Term| {
            let c = per_unit_ms[t.index()];
            let k = t.ms_per_stored_unit();
            UnitCost {
                value: c.value / k,
                standard_error: c.standard_error / k,
                at_zero: c.at_zero,
            }
        };
        Self {
            size,
            clock,
            msaa: false,
            host_other_cores: None,
            fixed_ms: stored(Term::Fixed),
            vertex_ns: stored(Term::Vertex),
            primitive_ns: stored(Term::Primitive),
            fragment_opaque_ns: stored(Term::FragmentOpaque),
            fragment_alpha_tested_ns: stored(Term::FragmentAlphaTested),
            fragment_blended_ns: stored(Term::FragmentBlended),
            draw_ns: stored(Term::Draw),
            compute_invocation_ns: stored(Term::Compute),
            upload_ms_per_mb: stored(Term::Upload),
            texture_load_ns: stored(Term::TextureLoad),
            float_texture_load_ns: stored(Term::FloatTextureLoad),
            vertex_texture_load_ns: stored(Term::VertexTextureLoad),
            vertex_float_texture_load_ns: stored(Term::VertexFloatTextureLoad),
            texture_sample_ns: stored(Term::TextureSample),
            float_texture_sample_ns: stored(Term::FloatTextureSample),
            vertex_transcendental_ns: stored(Term::VertexTranscendental),
            fragment_transcendental_ns: stored(Term::FragmentTranscendental),
            compute_transcendental_ns: stored(Term::ComputeTranscendental),
            vertex_arithmetic_ns: stored(Term::VertexArithmetic),
            fragment_arithmetic_ns: stored(Term::FragmentArithmetic),
            compute_arithmetic_ns: stored(Term::ComputeArithmetic),
            compute_barrier_ns: stored(Term::ComputeBarrier),
            compute_storage_ns: stored(Term::ComputeStorage),
            vertex_storage_ns: stored(Term::VertexStorage),
            compute_division_ns: stored(Term::ComputeDivision),
            texture_mip_blend_ns: stored(Term::TextureMipBlend),
            instance_ns: stored(Term::Instance),
            primitive_input_ns: stored(Term::PrimitiveInput),
            texture_explicit_level_ns: stored(Term::TextureExplicitLevel),
            head_primitive_ns: stored(Term::HeadPrimitive),
            fit,
            checks: Vec::new(),
        }
    }

    /// The cost of `term` as stored (ns or ms, see the field).
    pub fn get(&self, term: Term) -> UnitCost {
        match term {
            Term::Fixed => self.fixed_ms,
            Term::Vertex => self.vertex_ns,
            Term::Primitive => self.primitive_ns,
            Term::FragmentOpaque => self.fragment_opaque_ns,
            Term::FragmentAlphaTested => self.fragment_alpha_tested_ns,
            Term::FragmentBlended => self.fragment_blended_ns,
            Term::Draw => self.draw_ns,
            Term::Compute => self.compute_invocation_ns,
            Term::Upload => self.upload_ms_per_mb,
            Term::TextureLoad => self.texture_load_ns,
            Term::FloatTextureLoad => self.float_texture_load_ns,
            Term::VertexTextureLoad => self.vertex_texture_load_ns,
            Term::VertexFloatTextureLoad => self.vertex_float_texture_load_ns,
            Term::TextureSample => self.texture_sample_ns,
            Term::FloatTextureSample => self.float_texture_sample_ns,
            Term::VertexTranscendental => self.vertex_transcendental_ns,
            Term::FragmentTranscendental => self.fragment_transcendental_ns,
            Term::ComputeTranscendental => self.compute_transcendental_ns,
            Term::VertexArithmetic => self.vertex_arithmetic_ns,
            Term::FragmentArithmetic => self.fragment_arithmetic_ns,
            Term::ComputeArithmetic => self.compute_arithmetic_ns,
            Term::ComputeBarrier => self.compute_barrier_ns,
            Term::ComputeStorage => self.compute_storage_ns,
            Term::VertexStorage => self.vertex_storage_ns,
            Term::ComputeDivision => self.compute_division_ns,
            Term::TextureMipBlend => self.texture_mip_blend_ns,
            Term::Instance => self.instance_ns,
            Term::PrimitiveInput => self.primitive_input_ns,
            Term::TextureExplicitLevel => self.texture_explicit_level_ns,
            Term::HeadPrimitive => self.head_primitive_ns,
        }
    }

    /// The cost of one unit of `term` ([`Term::unit`]) in ms.
    pub fn ms_per_unit(&self, term: Term) -> f64 {
        self.get(term).value * term.ms_per_stored_unit()
    }

    /// A frame's GPU time predicted from its work: `Σ cost × amount`, term by term.
    pub fn predict(&self, work: &Work) -> Prediction {
        let ms = |t: Term| self.ms_per_unit(t) * work.amount(t);
        let mut p = Prediction {
            total_ms: 0.0,
            fixed_ms: ms(Term::Fixed),
            vertex_ms: ms(Term::Vertex),
            primitive_ms: ms(Term::Primitive),
            fragment_opaque_ms: ms(Term::FragmentOpaque),
            fragment_alpha_tested_ms: ms(Term::FragmentAlphaTested),
            fragment_blended_ms: ms(Term::FragmentBlended),
            draw_ms: ms(Term::Draw),
            compute_ms: ms(Term::Compute),
            upload_ms: ms(Term::Upload),
            texture_load_ms: ms(Term::TextureLoad),
            float_texture_load_ms: ms(Term::FloatTextureLoad),
            vertex_texture_load_ms: ms(Term::VertexTextureLoad),
            vertex_float_texture_load_ms: ms(Term::VertexFloatTextureLoad),
            texture_sample_ms: ms(Term::TextureSample),
            float_texture_sample_ms: ms(Term::FloatTextureSample),
            vertex_transcendental_ms: ms(Term::VertexTranscendental),
            fragment_transcendental_ms: ms(Term::FragmentTranscendental),
            compute_transcendental_ms: ms(Term::ComputeTranscendental),
            vertex_arithmetic_ms: ms(Term::VertexArithmetic),
            fragment_arithmetic_ms: ms(Term::FragmentArithmetic),
            compute_arithmetic_ms: ms(Term::ComputeArithmetic),
            compute_barrier_ms: ms(Term::ComputeBarrier),
            compute_storage_ms: ms(Term::ComputeStorage),
            vertex_storage_ms: ms(Term::VertexStorage),
            compute_division_ms: ms(Term::ComputeDivision),
            texture_mip_blend_ms: ms(Term::TextureMipBlend),
            instance_ms: ms(Term::Instance),
            primitive_input_ms: ms(Term::PrimitiveInput),
            texture_explicit_level_ms: ms(Term::TextureExplicitLevel),
            head_primitive_ms: ms(Term::HeadPrimitive),
        };
        p.total_ms = Term::ALL.iter().map(|&t| p.ms(t)).sum();
        p
    }
}

impl UnitCosts {
    /// A Markdown table of the costs with their standard errors, then a line with the fit's
    /// residuals overall and per workload. Ends with a newline.
    pub fn to_markdown(&self) -> String {
        let mut md = String::from("| term | cost | standard error | unit |\n|---|---|---|---|\n");
        for t in Term::ALL {
            let c = self.get(t);
            let unit = if t.ms_per_stored_unit() == 1.0 {
                format!("ms per {}", t.unit())
            } else {
                format!("ns per {}", t.unit())
            };
            md.push_str(&format!(
                "| {t} | {}{} | {} | {unit} |\n",
                significant(c.value),
                if c.at_zero { " (held at 0)" } else { "" },
                significant(c.standard_error),
            ));
        }
        let workloads: Vec<String> = self
            .fit
            .workloads
            .iter()
            .map(|w| format!("{} {:.1}%", w.workload, 100.0 * w.relative_rms_residual))
            .collect();
        let host = self.host_other_cores.map_or(String::new(), |c| {
            format!(", other processes busy on {c:.1} cores")
        });
        md.push_str(&format!(
            "\nFit over {} samples ({}, {}{host}): relative RMS residual {:.1}% (largest {:.1}%); per workload: {}.\n",
            self.fit.samples,
            self.size,
            self.clock,
            100.0 * self.fit.relative_rms_residual,
            100.0 * self.fit.max_relative_residual,
            workloads.join(", ")
        ));
        if !self.checks.is_empty() {
            md.push_str(&format!(
                "\nCoverage checks, timed with the samples and not fitted (measured over predicted: where the prices hold for a technique's fragments; `grassbench calibrate` and `results/cost_model/README.md`, *Coverage checks*):\n\n{}",
                super::checks::to_markdown(&self.checks)
            ));
        }
        md
    }
}

/// `x` with three significant digits (plain decimals, no exponent, for a table).
fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.digits$}")
}

impl Prediction {
    /// The time of `term`, ms.
    pub fn ms(&self, term: Term) -> f64 {
        match term {
            Term::Fixed => self.fixed_ms,
            Term::Vertex => self.vertex_ms,
            Term::Primitive => self.primitive_ms,
            Term::FragmentOpaque => self.fragment_opaque_ms,
            Term::FragmentAlphaTested => self.fragment_alpha_tested_ms,
            Term::FragmentBlended => self.fragment_blended_ms,
            Term::Draw => self.draw_ms,
            Term::Compute => self.compute_ms,
            Term::Upload => self.upload_ms,
            Term::TextureLoad => self.texture_load_ms,
            Term::FloatTextureLoad => self.float_texture_load_ms,
            Term::VertexTextureLoad => self.vertex_texture_load_ms,
            Term::VertexFloatTextureLoad => self.vertex_float_texture_load_ms,
            Term::TextureSample => self.texture_sample_ms,
            Term::FloatTextureSample => self.float_texture_sample_ms,
            Term::VertexTranscendental => self.vertex_transcendental_ms,
            Term::FragmentTranscendental => self.fragment_transcendental_ms,
            Term::ComputeTranscendental => self.compute_transcendental_ms,
            Term::VertexArithmetic => self.vertex_arithmetic_ms,
            Term::FragmentArithmetic => self.fragment_arithmetic_ms,
            Term::ComputeArithmetic => self.compute_arithmetic_ms,
            Term::ComputeBarrier => self.compute_barrier_ms,
            Term::ComputeStorage => self.compute_storage_ms,
            Term::VertexStorage => self.vertex_storage_ms,
            Term::ComputeDivision => self.compute_division_ms,
            Term::TextureMipBlend => self.texture_mip_blend_ms,
            Term::Instance => self.instance_ms,
            Term::PrimitiveInput => self.primitive_input_ms,
            Term::TextureExplicitLevel => self.texture_explicit_level_ms,
            Term::HeadPrimitive => self.head_primitive_ms,
        }
    }

    /// The share of `term` in the total, in [0, 1] (0 when the total is 0).
    pub fn share(&self, term: Term) -> f64 {
        if self.total_ms > 0.0 {
            self.ms(term) / self.total_ms
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_prediction_is_the_sum_of_its_terms_in_their_units() {
        // ms per unit: fixed 1 ms, vertex 10 ns, primitive 100 ns, fragments 2 / 3 / 4 ns,
        // draw 1 µs, compute 5 ns, upload 0.5 ms per MB, texel load 1 ns (4 ns floating-point;
        // 2 and 8 ns more in a vertex shader), sample 6 ns (10 ns floating-point),
        // transcendentals 2 / 0.5 / 1 ns (vertex, fragment, compute), scalar operations 0.2 /
        // 0.05 / 0.1 ns, a compute invocation at a barrier 20 ns, a compute shader's storage word 0.5 ns,
        // a vertex shader's 1 ns, a compute shader's integer division 4 ns, a sample's second
        // mip level 2 ns, an instance 200 ns, a primitive's input slot 20 ns, a sample's level
        // picked lane by lane 3 ns, a pass's head primitive 50 ns more.
        let per_unit = [
            1.0, 1e-5, 1e-4, 2e-6, 3e-6, 4e-6, 1e-3, 5e-6, 0.5, 1e-6, 4e-6, 2e-6, 8e-6, 6e-6, 1e-5,
            2e-6, 5e-7, 1e-6, 2e-7, 5e-8, 1e-7, 2e-5, 5e-7, 1e-6, 4e-6, 2e-6, 2e-4, 2e-5, 3e-6,
            5e-5,
        ]
        .map(UnitCost::exact);
        let costs = UnitCosts::from_ms_per_unit(
            "640x360".into(),
            "test".into(),
            per_unit,
            FitSummary::default(),
        );
        assert!((costs.vertex_ns.value - 10.0).abs() < 1e-9);
        assert!((costs.draw_ns.value - 1000.0).abs() < 1e-9);
        assert_eq!(costs.upload_ms_per_mb.value, 0.5);
        let work = Work {
            vertex_invocations: 1e5,
            primitives: 1e4,
            fragments_opaque: 1e6,
            fragments_alpha_tested: 0.0,
            fragments_blended: 1e5,
            draw_calls: 10.0,
            compute_invocations: 2e5,
            upload_bytes: 4e6,
            texture_loads: 5e5,
            float_texture_loads: 2.5e5,
            vertex_texture_loads: 1e5,
            vertex_float_texture_loads: 2.5e5,
            texture_samples: 2e5,
            float_texture_samples: 5e4,
            vertex_transcendentals: 1e6,
            fragment_transcendentals: 4e6,
            compute_transcendentals: 0.0,
            vertex_arithmetic: 5e6,
            fragment_arithmetic: 2e7,
            compute_arithmetic: 0.0,
            compute_barriers: 4e5,
            compute_storage: 6e6,
            vertex_storage: 2e6,
            compute_divisions: 5e5,
            texture_mip_blends: 1.5e6,
            instances: 2.5e4,
            primitive_inputs: 5e4,
            texture_explicit_levels: 1e5,
            head_primitives: 8e3,
        };
        let p = costs.predict(&work);
        // 1 + 1 + 1 + 2 + 0 + 0.4 + 0.01 + 1 + 2 + 0.5 + 1 + 0.2 + 2 + 1.2 + 0.5 + 2 + 2 + 0
        // + 1 + 1 + 0 + 8 + 3 + 2 + 2 + 3 + 5 + 1 + 0.3 + 0.4 ms.
        let expected = [
            1.0, 1.0, 1.0, 2.0, 0.0, 0.4, 0.01, 1.0, 2.0, 0.5, 1.0, 0.2, 2.0, 1.2, 0.5, 2.0, 2.0,
            0.0, 1.0, 1.0, 0.0, 8.0, 3.0, 2.0, 2.0, 3.0, 5.0, 1.0, 0.3, 0.4,
        ];
        for (t, e) in Term::ALL.iter().zip(expected) {
            assert!((p.ms(*t) - e).abs() < 1e-9, "{t}: {} ms", p.ms(*t));
        }
        assert!((p.total_ms - 44.51).abs() < 1e-9);
        let shares: f64 = Term::ALL.iter().map(|&t| p.share(t)).sum();
        assert!((shares - 1.0).abs() < 1e-12);
        assert_eq!(Prediction::default().share(Term::Vertex), 0.0);
        let md = costs.to_markdown();
        assert!(
            md.contains("| vertex | 10.0 | 0 | ns per vertex invocation |"),
            "{md}"
        );
        assert!(md.contains("| upload | 0.500 | 0 | ms per MB |"), "{md}");
        assert!(
            md.contains("| draw | 1000 | 0 | ns per draw call |"),
            "{md}"
        );
    }

    #[test]
    fn a_run_is_priced_by_the_costs_of_its_size_drawn_as_it_was() {
        let costs = |size: &str, msaa| UnitCosts {
            msaa,
            ..UnitCosts::from_ms_per_unit(
                size.into(),
                "test".into(),
                [UnitCost::exact(1e-6); Term::ALL.len()],
                FitSummary::default(),
            )
        };
        let all = [
            costs("320x180", false),
            costs("640x360", false),
            costs("320x180", true),
        ];
        let found =
            |size, msaa| UnitCosts::for_target(&all, size, msaa).map(|c| (c.size.as_str(), c.msaa));
        assert_eq!(found("640x360", false), Some(("640x360", false)));
        assert_eq!(found("320x180", true), Some(("320x180", true)));
        assert_eq!(found("320x180", false), Some(("320x180", false)));
        // No costs of that size drawn so: none, not another target's.
        assert_eq!(found("640x360", true), None);
        assert_eq!(found("1280x720", false), None);
    }

    #[test]
    fn unit_costs_round_trip_through_toml_and_older_files_read() {
        let per_unit = [
            1.0, 1e-5, 1e-4, 2e-6, 3e-6, 4e-6, 1e-3, 5e-6, 0.5, 1e-6, 4e-6, 2e-6, 8e-6, 6e-6, 1e-5,
            2e-6, 5e-7, 1e-6, 2e-7, 5e-8, 1e-7, 2e-5, 5e-7, 1e-6, 4e-6, 2e-6, 2e-4, 2e-5, 3e-6,
            5e-5,
        ]
        .map(UnitCost::exact);
        let mut costs = UnitCosts::from_ms_per_unit(
            "640x360".into(),
            "test".into(),
            per_unit,
            FitSummary::default(),
        );
        costs.host_other_cores = Some(0.5);
        let text = toml::to_string_pretty(&costs).unwrap();
        assert_eq!(toml::from_str::<UnitCosts>(&text).unwrap(), costs);
        // Without the fields that may be absent (the host's load, `at_zero`, the texture and
        // transcendental terms of calibrations made before them).
        let mut older = String::new();
        let mut skipping = false;
        for l in text.lines() {
            if l.starts_with('[') {
                skipping = l.starts_with("[texture_")
                    || l.starts_with("[float_texture_")
                    || l.starts_with("[vertex_texture_")
                    || l.starts_with("[vertex_float_texture_")
                    || l.contains("_transcendental_ns]")
                    || l.contains("_arithmetic_ns]")
                    || l.starts_with("[compute_barrier_")
                    || l.starts_with("[compute_storage_")
                    || l.starts_with("[vertex_storage_")
                    || l.starts_with("[compute_division_")
                    || l.starts_with("[texture_mip_blend_")
                    || l.starts_with("[instance_")
                    || l.starts_with("[primitive_input_")
                    || l.starts_with("[head_primitive");
            }
            if !skipping
                && !l.starts_with("host_other_cores")
                && !l.starts_with("at_zero")
                && !l.starts_with("msaa")
            {
                older.push_str(l);
                older.push('\n');
            }
        }
        let read = toml::from_str::<UnitCosts>(&older).unwrap();
        assert_eq!(
            (read.host_other_cores, read.vertex_ns.at_zero),
            (None, false)
        );
        // Files from before the field were calibrated single-sampled.
        assert!(!read.msaa && !older.contains("msaa"), "{older}");
        assert_eq!(read.texture_sample_ns, UnitCost::default());
        assert_eq!(read.float_texture_sample_ns, UnitCost::default());
        assert_eq!(read.float_texture_load_ns, UnitCost::default());
        assert_eq!(read.vertex_float_texture_load_ns, UnitCost::default());
        assert!(!older.contains("vertex_float_texture_load_ns"), "{older}");
        assert_eq!(read.vertex_transcendental_ns, UnitCost::default());
        assert!(!older.contains("texture_sample_ns"), "{older}");
        assert!(!older.contains("transcendental_ns"), "{older}");
        assert_eq!(read.compute_arithmetic_ns, UnitCost::default());
        assert!(!older.contains("arithmetic_ns"), "{older}");
        assert_eq!(read.compute_barrier_ns, UnitCost::default());
        assert!(!older.contains("barrier_ns"), "{older}");
        assert_eq!(read.compute_storage_ns, UnitCost::default());
        assert_eq!(read.vertex_storage_ns, UnitCost::default());
        assert!(!older.contains("storage_ns"), "{older}");
        assert_eq!(read.compute_division_ns, UnitCost::default());
        assert!(!older.contains("division_ns"), "{older}");
        assert_eq!(read.texture_mip_blend_ns, UnitCost::default());
        assert!(!older.contains("mip_blend_ns"), "{older}");
        assert_eq!(read.instance_ns, UnitCost::default());
        assert!(!older.contains("instance_ns"), "{older}");
        assert_eq!(read.primitive_input_ns, UnitCost::default());
        assert!(!older.contains("primitive_input_ns"), "{older}");
        assert_eq!(read.texture_explicit_level_ns, UnitCost::default());
        assert!(!older.contains("explicit_level_ns"), "{older}");
        assert_eq!(read.head_primitive_ns, UnitCost::default());
        assert!(!older.contains("head_primitive"), "{older}");
    }
}
