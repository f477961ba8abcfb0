//! [`Work`]: what one frame (one submission) made the GPU do, in the units of the cost model.

use super::Term;
use crate::technique::work::PassWork;

/// Bytes in the megabyte the upload term counts (decimal: 10⁶).
pub const BYTES_PER_MB: f64 = 1e6;

/// The measured work of one frame: one submission's counts, as plain numbers (f64: sums and
/// averages over frames stay exact enough and need no casts). The GPU-side counts come from
/// the pipeline-statistics counters (`crate::technique::work`), the fragments split by the
/// kind of pipeline that shaded them; draws and uploads from the harness.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Work {
    /// Vertex shader invocations.
    pub vertex_invocations: f64,
    /// Triangles that reached rasterisation: the clipper's output (`CLIPPER_PRIMITIVES_OUT`).
    pub primitives: f64,
    /// Fragment shader invocations of opaque, depth-tested pipelines.
    pub fragments_opaque: f64,
    /// Fragment shader invocations of pipelines that may discard (alpha test, alpha to
    /// coverage).
    pub fragments_alpha_tested: f64,
    /// Fragment shader invocations of alpha-blended pipelines.
    pub fragments_blended: f64,
    /// Draw calls (direct, indexed, indirect).
    pub draw_calls: f64,
    /// Compute shader invocations.
    pub compute_invocations: f64,
    /// Bytes written with `GpuContext::write_buffer` (or `write_texture`) before the
    /// submission.
    pub upload_bytes: f64,
    /// Texels of normalised or integer formats read with `textureLoad` (every stage).
    #[serde(default)]
    pub texture_loads: f64,
    /// Texels of floating-point formats read with `textureLoad`
    /// (`crate::shaders::ShaderOps::float_loads`).
    #[serde(default)]
    pub float_texture_loads: f64,
    /// Of [`Work::texture_loads`], those of vertex shaders (priced again, by
    /// [`Term::VertexTextureLoad`]).
    #[serde(default)]
    pub vertex_texture_loads: f64,
    /// Of [`Work::float_texture_loads`], those of vertex shaders (priced again, by
    /// [`Term::VertexFloatTextureLoad`]).
    #[serde(default)]
    pub vertex_float_texture_loads: f64,
    /// Filtered texture samples of normalised or integer texels (vertex and fragment stages).
    #[serde(default)]
    pub texture_samples: f64,
    /// Filtered texture samples of floating-point texels
    /// (`crate::shaders::ShaderOps::float_samples`).
    #[serde(default)]
    pub float_texture_samples: f64,
    /// Transcendental built-ins evaluated by vertex shaders ([`crate::shaders::ShaderOps`]).
    #[serde(default)]
    pub vertex_transcendentals: f64,
    /// Transcendental built-ins evaluated by fragment shaders.
    #[serde(default)]
    pub fragment_transcendentals: f64,
    /// Transcendental built-ins evaluated by compute shaders.
    #[serde(default)]
    pub compute_transcendentals: f64,
    /// Scalar arithmetic operations of vertex shaders ([`crate::shaders::ShaderOps`]).
    #[serde(default)]
    pub vertex_arithmetic: f64,
    /// Scalar arithmetic operations of fragment shaders.
    #[serde(default)]
    pub fragment_arithmetic: f64,
    /// Scalar arithmetic operations of compute shaders.
    #[serde(default)]
    pub compute_arithmetic: f64,
    /// Workgroup barriers reached by compute shader invocations, one per invocation at each
    /// ([`crate::shaders::ShaderOps::barriers`]).
    #[serde(default)]
    pub compute_barriers: f64,
    /// 32-bit words compute shader invocations read from or wrote to storage buffers
    /// ([`crate::shaders::ShaderOps::storage`]).
    #[serde(default)]
    pub compute_storage: f64,
    /// 32-bit words vertex shader invocations read from storage buffers
    /// ([`crate::shaders::ShaderOps::storage`]).
    #[serde(default)]
    pub vertex_storage: f64,
    /// Integer divisions and remainders by divisors the pipeline does not fix, of compute
    /// shader invocations ([`crate::shaders::ShaderOps::divisions`]).
    #[serde(default)]
    pub compute_divisions: f64,
    /// Filtered samples, of any stage and format, that may blend two mip levels
    /// ([`crate::shaders::ShaderOps::mip_blends`]).
    #[serde(default)]
    pub texture_mip_blends: f64,
    /// Instances drawn: each direct draw's instance range, each indirect draw's instance
    /// count as its arguments held when the frame ended (`crate::technique::work`).
    #[serde(default)]
    pub instances: f64,
    /// Fragment shader input slots set up for the primitives that reached rasterisation: each
    /// segment's primitives times its fragment shader's slots
    /// ([`crate::shaders::PipelineCost::fragment_inputs`]).
    #[serde(default)]
    pub primitive_inputs: f64,
    /// Filtered samples, of any stage and format, whose mip level the shader gives each
    /// invocation ([`crate::shaders::ShaderOps::explicit_levels`]).
    #[serde(default)]
    pub texture_explicit_levels: f64,
    /// Of [`Work::primitives`], those among the first
    /// [`crate::technique::work::PASS_HEAD_PRIMITIVES`] of their segment, summed over the
    /// segments ([`crate::technique::work::PassWork::head_primitives`]).
    #[serde(default)]
    pub head_primitives: f64,
}

pub use crate::shaders::FragmentKind;
use crate::shaders::PipelineCost;

impl Work {
    /// The fragments of `kind`, to set.
    pub fn fragments_mut(&mut self, kind: FragmentKind) -> &mut f64 {
        match kind {
            FragmentKind::Opaque => &mut self.fragments_opaque,
            FragmentKind::AlphaTested => &mut self.fragments_alpha_tested,
            FragmentKind::Blended => &mut self.fragments_blended,
        }
    }

    /// The work the GPU's pipeline-statistics counters measured over some passes, all drawn
    /// with pipelines of `pipeline`'s cost: fragments of its kind, texture fetches and
    /// transcendentals its shaders' per invocation times the invocations counted, and the
    /// instances the harness counted into the segments. Draw calls and uploads are not among
    /// the counters: they are 0 here, for the caller to set from the harness's counts.
    pub fn from_counters(counted: &PassWork, pipeline: PipelineCost) -> Self {
        let ops = pipeline.ops(counted);
        let fetches = ops.all();
        let mut work = Self {
            vertex_invocations: counted.vertex_invocations as f64,
            primitives: counted.clipper_primitives_out as f64,
            fragments_opaque: 0.0,
            fragments_alpha_tested: 0.0,
            fragments_blended: 0.0,
            draw_calls: 0.0,
            compute_invocations: counted.compute_invocations as f64,
            upload_bytes: 0.0,
            texture_loads: fetches.loads as f64,
            float_texture_loads: fetches.float_loads as f64,
            vertex_texture_loads: ops.vertex.loads as f64,
            vertex_float_texture_loads: ops.vertex.float_loads as f64,
            texture_samples: fetches.samples as f64,
            float_texture_samples: fetches.float_samples as f64,
            vertex_transcendentals: ops.vertex.transcendentals as f64,
            fragment_transcendentals: ops.fragment.transcendentals as f64,
            compute_transcendentals: ops.compute.transcendentals as f64,
            vertex_arithmetic: ops.vertex.arithmetic as f64,
            fragment_arithmetic: ops.fragment.arithmetic as f64,
            compute_arithmetic: ops.compute.arithmetic as f64,
            compute_barriers: ops.compute.barriers as f64,
            compute_storage: ops.compute.storage as f64,
            vertex_storage: ops.vertex.storage as f64,
            compute_divisions: ops.compute.divisions as f64,
            texture_mip_blends: fetches.mip_blends as f64,
            instances: counted.instances as f64,
            primitive_inputs: pipeline.primitive_inputs(counted) as f64,
            texture_explicit_levels: fetches.explicit_levels as f64,
            head_primitives: counted.head_primitives() as f64,
        };
        *work.fragments_mut(pipeline.fragments) = counted.fragment_invocations as f64;
        work
    }

    /// The amount of `term` in this frame, in the term's unit ([`Term::unit`]): the fixed term
    /// counts one submission, the upload term megabytes.
    pub fn amount(&self, term: Term) -> f64 {
        match term {
            Term::Fixed => 1.0,
            Term::Vertex => self.vertex_invocations,
            Term::Primitive => self.primitives,
            Term::FragmentOpaque => self.fragments_opaque,
            Term::FragmentAlphaTested => self.fragments_alpha_tested,
            Term::FragmentBlended => self.fragments_blended,
            Term::Draw => self.draw_calls,
            Term::Compute => self.compute_invocations,
            Term::Upload => self.upload_bytes / BYTES_PER_MB,
            Term::TextureLoad => self.texture_loads,
            Term::FloatTextureLoad => self.float_texture_loads,
            Term::VertexTextureLoad => self.vertex_texture_loads,
            Term::VertexFloatTextureLoad => self.vertex_float_texture_loads,
            Term::TextureSample => self.texture_samples,
            Term::FloatTextureSample => self.float_texture_samples,
            Term::VertexTranscendental => self.vertex_transcendentals,
            Term::FragmentTranscendental => self.fragment_transcendentals,
            Term::ComputeTranscendental => self.compute_transcendentals,
            Term::VertexArithmetic => self.vertex_arithmetic,
            Term::FragmentArithmetic => self.fragment_arithmetic,
            Term::ComputeArithmetic => self.compute_arithmetic,
            Term::ComputeBarrier => self.compute_barriers,
            Term::ComputeStorage => self.compute_storage,
            Term::VertexStorage => self.vertex_storage,
            Term::ComputeDivision => self.compute_divisions,
            Term::TextureMipBlend => self.texture_mip_blends,
            Term::Instance => self.instances,
            Term::PrimitiveInput => self.primitive_inputs,
            Term::TextureExplicitLevel => self.texture_explicit_levels,
            Term::HeadPrimitive => self.head_primitives,
        }
    }

    /// This work with its head taken as one segment's: [`Work::head_primitives`] the first
    /// [`crate::technique::work::PASS_HEAD_PRIMITIVES`] of its primitives (work known in
    /// advance, such as a calibration workload's; counted work takes its heads segment by
    /// segment, [`Work::from_counters`]).
    pub fn as_one_segment(self) -> Self {
        Self {
            head_primitives: self
                .primitives
                .min(crate::technique::work::PASS_HEAD_PRIMITIVES as f64),
            ..self
        }
    }

    /// Every count multiplied by `k`.
    pub fn scaled(self, k: f64) -> Self {
        Self {
            vertex_invocations: self.vertex_invocations * k,
            primitives: self.primitives * k,
            fragments_opaque: self.fragments_opaque * k,
            fragments_alpha_tested: self.fragments_alpha_tested * k,
            fragments_blended: self.fragments_blended * k,
            draw_calls: self.draw_calls * k,
            compute_invocations: self.compute_invocations * k,
            upload_bytes: self.upload_bytes * k,
            texture_loads: self.texture_loads * k,
            float_texture_loads: self.float_texture_loads * k,
            vertex_texture_loads: self.vertex_texture_loads * k,
            vertex_float_texture_loads: self.vertex_float_texture_loads * k,
            texture_samples: self.texture_samples * k,
            float_texture_samples: self.float_texture_samples * k,
            vertex_transcendentals: self.vertex_transcendentals * k,
            fragment_transcendentals: self.fragment_transcendentals * k,
            compute_transcendentals: self.compute_transcendentals * k,
            vertex_arithmetic: self.vertex_arithmetic * k,
            fragment_arithmetic: self.fragment_arithmetic * k,
            compute_arithmetic: self.compute_arithmetic * k,
            compute_barriers: self.compute_barriers * k,
            compute_storage: self.compute_storage * k,
            vertex_storage: self.vertex_storage * k,
            compute_divisions: self.compute_divisions * k,
            texture_mip_blends: self.texture_mip_blends * k,
            instances: self.instances * k,
            primitive_inputs: self.primitive_inputs * k,
            texture_explicit_levels: self.texture_explicit_levels * k,
            head_primitives: self.head_primitives * k,
        }
    }

    /// Whether every count is finite and non-negative.
    pub fn is_valid(&self) -> bool {
        Term::ALL
            .iter()
            .all(|&t| self.amount(t).is_finite() && self.amount(t) >= 0.0)
    }
}

impl std::ops::Add for Work {
    type Output = Self;

    fn add(self, o: Self) -> Self {
        Self {
            vertex_invocations: self.vertex_invocations + o.vertex_invocations,
            primitives: self.primitives + o.primitives,
            fragments_opaque: self.fragments_opaque + o.fragments_opaque,
            fragments_alpha_tested: self.fragments_alpha_tested + o.fragments_alpha_tested,
            fragments_blended: self.fragments_blended + o.fragments_blended,
            draw_calls: self.draw_calls + o.draw_calls,
            compute_invocations: self.compute_invocations + o.compute_invocations,
            upload_bytes: self.upload_bytes + o.upload_bytes,
            texture_loads: self.texture_loads + o.texture_loads,
            float_texture_loads: self.float_texture_loads + o.float_texture_loads,
            vertex_texture_loads: self.vertex_texture_loads + o.vertex_texture_loads,
            vertex_float_texture_loads: self.vertex_float_texture_loads
                + o.vertex_float_texture_loads,
            texture_samples: self.texture_samples + o.texture_samples,
            float_texture_samples: self.float_texture_samples + o.float_texture_samples,
            vertex_transcendentals: self.vertex_transcendentals + o.vertex_transcendentals,
            fragment_transcendentals: self.fragment_transcendentals + o.fragment_transcendentals,
            compute_transcendentals: self.compute_transcendentals + o.compute_transcendentals,
            vertex_arithmetic: self.vertex_arithmetic + o.vertex_arithmetic,
            fragment_arithmetic: self.fragment_arithmetic + o.fragment_arithmetic,
            compute_arithmetic: self.compute_arithmetic + o.compute_arithmetic,
            compute_barriers: self.compute_barriers + o.compute_barriers,
            compute_storage: self.compute_storage + o.compute_storage,
            vertex_storage: self.vertex_storage + o.vertex_storage,
            compute_divisions: self.compute_divisions + o.compute_divisions,
            texture_mip_blends: self.texture_mip_blends + o.texture_mip_blends,
            instances: self.instances + o.instances,
            primitive_inputs: self.primitive_inputs + o.primitive_inputs,
            texture_explicit_levels: self.texture_explicit_levels + o.texture_explicit_levels,
            head_primitives: self.head_primitives + o.head_primitives,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn amounts_are_in_the_terms_units() {
        let w = Work {
            vertex_invocations: 11.0,
            primitives: 9.0,
            fragments_opaque: 1.0,
            fragments_alpha_tested: 2.0,
            fragments_blended: 3.0,
            draw_calls: 4.0,
            compute_invocations: 5.0,
            upload_bytes: 2.5e6,
            texture_loads: 6.0,
            float_texture_loads: 6.5,
            vertex_texture_loads: 3.0,
            vertex_float_texture_loads: 3.5,
            texture_samples: 7.0,
            float_texture_samples: 7.5,
            vertex_transcendentals: 8.0,
            fragment_transcendentals: 9.5,
            compute_transcendentals: 10.0,
            vertex_arithmetic: 11.5,
            fragment_arithmetic: 12.0,
            compute_arithmetic: 13.0,
            compute_barriers: 14.0,
            compute_storage: 15.0,
            vertex_storage: 16.0,
            compute_divisions: 17.0,
            texture_mip_blends: 18.0,
            instances: 19.0,
            primitive_inputs: 20.0,
            texture_explicit_levels: 21.0,
            head_primitives: 8.0,
        };
        let amounts: Vec<f64> = Term::ALL.iter().map(|&t| w.amount(t)).collect();
        assert_eq!(
            amounts,
            [
                1.0, 11.0, 9.0, 1.0, 2.0, 3.0, 4.0, 5.0, 2.5, 6.0, 6.5, 3.0, 3.5, 7.0, 7.5, 8.0,
                9.5, 10.0, 11.5, 12.0, 13.0, 14.0, 15.0, 16.0, 17.0, 18.0, 19.0, 20.0, 21.0, 8.0,
            ]
        );
        // A sum of frames counts each frame's work, not its submission (the fixed term is per
        // frame: predict frame by frame).
        assert_eq!((w + w).amount(Term::Vertex), 22.0);
        assert_eq!(w.scaled(2.0), w + w);
        assert!(w.is_valid());
        assert!(
            !Work {
                primitives: f64::NAN,
                ..w
            }
            .is_valid()
        );
        assert!(
            !Work {
                draw_calls: -1.0,
                ..w
            }
            .is_valid()
        );
    }

    #[test]
    fn counters_fill_the_fragments_of_their_pipelines_kind_and_its_ops() {
        use crate::shaders::ShaderOps;
        let counted = PassWork {
            vertex_invocations: 11,
            clipper_invocations: 9,
            clipper_primitives_out: 7,
            fragment_invocations: 100,
            compute_invocations: 64,
            samples_passed: 40,
            instances: 3,
        };
        let kind = |fragments| PipelineCost {
            fragments,
            ..PipelineCost::default()
        };
        // 11 vertices fetching 8 floating-point texels each (a bilinear height and wind) with
        // 5 transcendentals and 40 scalar operations, 100 fragments sampling 3 textures (and
        // 2 of floating-point texels, 4 of the 5 blending two mip levels, 2 at a level each fragment
        // gives) and loading 1 texel with 1 transcendental and 20
        // operations, 64 compute invocations loading 4 with 2 and 3 reaching 2 barriers,
        // moving 10 words of storage and taking 3 integer divisions.
        let fetching = PipelineCost {
            fragments: FragmentKind::AlphaTested,
            vertex_ops: ShaderOps {
                loads: 0,
                float_loads: 8,
                samples: 0,
                float_samples: 0,
                mip_blends: 0,
                explicit_levels: 0,
                transcendentals: 5,
                arithmetic: 40,
                barriers: 0,
                storage: 0,
                divisions: 0,
            },
            fragment_ops: ShaderOps {
                loads: 1,
                float_loads: 0,
                samples: 3,
                float_samples: 2,
                mip_blends: 4,
                explicit_levels: 2,
                transcendentals: 1,
                arithmetic: 20,
                barriers: 0,
                storage: 0,
                divisions: 0,
            },
            compute_ops: ShaderOps {
                loads: 4,
                float_loads: 0,
                samples: 0,
                float_samples: 0,
                mip_blends: 0,
                explicit_levels: 0,
                transcendentals: 2,
                arithmetic: 3,
                barriers: 2,
                storage: 10,
                divisions: 3,
            },
            fragment_inputs: 4,
        };
        assert_eq!(
            Work::from_counters(&counted, fetching),
            Work {
                vertex_invocations: 11.0,
                primitives: 7.0,
                fragments_alpha_tested: 100.0,
                compute_invocations: 64.0,
                texture_loads: 100.0 + 256.0,
                float_texture_loads: 88.0,
                vertex_float_texture_loads: 88.0,
                texture_samples: 300.0,
                float_texture_samples: 200.0,
                texture_mip_blends: 400.0,
                texture_explicit_levels: 200.0,
                vertex_transcendentals: 55.0,
                fragment_transcendentals: 100.0,
                compute_transcendentals: 128.0,
                vertex_arithmetic: 440.0,
                fragment_arithmetic: 2000.0,
                compute_arithmetic: 192.0,
                compute_barriers: 128.0,
                compute_storage: 640.0,
                compute_divisions: 192.0,
                instances: 3.0,
                // 7 primitives, 4 input slots each, all among the segment's first 360 000.
                primitive_inputs: 28.0,
                head_primitives: 7.0,
                ..Work::default()
            }
        );
        assert_eq!(
            Work::from_counters(&counted, kind(FragmentKind::Blended)).fragments_blended,
            100.0
        );
        let opaque = Work::from_counters(&counted, kind(FragmentKind::Opaque));
        assert_eq!(opaque.fragments_opaque, 100.0);
        assert_eq!((opaque.texture_loads, opaque.texture_samples), (0.0, 0.0));
    }

    #[test]
    fn a_segments_head_stops_at_the_pass_head() {
        use crate::technique::work::PASS_HEAD_PRIMITIVES as S;
        let cost = PipelineCost {
            fragment_inputs: 3,
            ..PipelineCost::default()
        };
        let segment = |primitives| PassWork {
            clipper_primitives_out: primitives,
            ..PassWork::default()
        };
        // Below, at and past the head: the head is the segment's primitives up to S; the
        // primitives (and every primitive's slots) past it are counted, not headed.
        for (n, head) in [(0, 0), (S - 1, S - 1), (S, S), (S + 1, S), (7 * S, S)] {
            let w = Work::from_counters(&segment(n), cost);
            assert_eq!(w.primitives, n as f64, "{n}");
            assert_eq!(w.head_primitives, head as f64, "{n}");
            assert_eq!(w.primitive_inputs, (3 * n) as f64, "{n}");
        }
        // Two large segments each have a head: segments are summed after their heads are
        // taken, not before.
        let two =
            Work::from_counters(&segment(2 * S), cost) + Work::from_counters(&segment(3 * S), cost);
        assert_eq!(two.head_primitives, (2 * S) as f64);
        let summed = segment(2 * S) + segment(3 * S);
        assert_eq!(Work::from_counters(&summed, cost).head_primitives, S as f64);
    }
}
