//! The model applied to measured runs: a frame's [`Work`] read from its record, and a run's
//! predicted GPU time written beside its measured one.

use super::{Prediction, UnitCosts, Work};
use crate::runner::{FrameRecord, RunSummary};

impl Work {
    /// The whole frame's work from its record: the technique's passes and the core's
    /// background together (the measured `gpu_wall_ms` covers both). The background's
    /// fragments are counted as opaque (its sky, ground and props are; the moving object's
    /// alpha-tested quad covers a few hundred pixels). `None` where the adapter counted no
    /// work (no pipeline statistics) or the record predates the columns.
    pub fn of_frame(r: &FrameRecord) -> Option<Self> {
        let f = |v: Option<u64>| v.map(|n| n as f64);
        Some(Self {
            vertex_invocations: f(r.vertex_invocations)? + f(r.background_vertex_invocations)?,
            primitives: f(r.clipper_primitives_out)? + f(r.background_primitives)?,
            fragments_opaque: f(r.fragments_opaque)? + f(r.background_fragment_invocations)?,
            fragments_alpha_tested: f(r.fragments_alpha_tested)?,
            fragments_blended: f(r.fragments_blended)?,
            draw_calls: r.draw_calls as f64 + f(r.background_draw_calls)?,
            compute_invocations: f(r.compute_invocations)?,
            upload_bytes: f(r.upload_bytes)?,
            // Older records have no operation counts: none priced.
            texture_loads: f(r.texture_loads).unwrap_or(0.0)
                + f(r.background_texture_loads).unwrap_or(0.0),
            float_texture_loads: f(r.float_texture_loads).unwrap_or(0.0)
                + f(r.background_float_texture_loads).unwrap_or(0.0),
            // Older records do not say which loads were the vertex stage's: priced as any.
            vertex_texture_loads: f(r.vertex_texture_loads).unwrap_or(0.0)
                + f(r.background_vertex_texture_loads).unwrap_or(0.0),
            vertex_float_texture_loads: f(r.vertex_float_texture_loads).unwrap_or(0.0)
                + f(r.background_vertex_float_texture_loads).unwrap_or(0.0),
            texture_samples: f(r.texture_samples).unwrap_or(0.0)
                + f(r.background_texture_samples).unwrap_or(0.0),
            float_texture_samples: f(r.float_texture_samples).unwrap_or(0.0)
                + f(r.background_float_texture_samples).unwrap_or(0.0),
            vertex_transcendentals: f(r.vertex_transcendentals).unwrap_or(0.0)
                + f(r.background_vertex_transcendentals).unwrap_or(0.0),
            fragment_transcendentals: f(r.fragment_transcendentals).unwrap_or(0.0)
                + f(r.background_fragment_transcendentals).unwrap_or(0.0),
            compute_transcendentals: f(r.compute_transcendentals).unwrap_or(0.0),
            vertex_arithmetic: f(r.vertex_arithmetic).unwrap_or(0.0)
                + f(r.background_vertex_arithmetic).unwrap_or(0.0),
            fragment_arithmetic: f(r.fragment_arithmetic).unwrap_or(0.0)
                + f(r.background_fragment_arithmetic).unwrap_or(0.0),
            compute_arithmetic: f(r.compute_arithmetic).unwrap_or(0.0),
            compute_barriers: f(r.compute_barriers).unwrap_or(0.0),
            compute_storage: f(r.compute_storage).unwrap_or(0.0),
            vertex_storage: f(r.vertex_storage).unwrap_or(0.0),
            compute_divisions: f(r.compute_divisions).unwrap_or(0.0),
            texture_mip_blends: f(r.texture_mip_blends).unwrap_or(0.0)
                + f(r.background_texture_mip_blends).unwrap_or(0.0),
        })
    }

    /// The mean work of `frames` (`None` when any frame has none).
    pub fn mean_of(frames: &[FrameRecord]) -> Option<Self> {
        if frames.is_empty() {
            return None;
        }
        let sum = frames
            .iter()
            .map(Self::of_frame)
            .try_fold(Self::default(), |acc, w| Some(acc + w?))?;
        Some(sum.scaled(1.0 / frames.len() as f64))
    }
}

/// The model's prediction for a run's frames: its mean frame's work priced by `costs` (the
/// prediction is linear in the work, so this is the mean of the frames' predictions).
pub fn predict_run(costs: &UnitCosts, frames: &[FrameRecord]) -> Option<Prediction> {
    Some(costs.predict(&Work::mean_of(frames)?))
}

/// Writes the model's prediction for `frames` into `run`: `model_ms`, each term's share and
/// `model_ratio` (measured median GPU wall time over predicted). Left empty where the frames
/// have no counted work.
pub fn apply_model(run: &mut RunSummary, costs: &UnitCosts, frames: &[FrameRecord]) {
    let p = predict_run(costs, frames);
    run.model_ms = p.map(|p| p.total_ms);
    run.model_fixed_ms = p.map(|p| p.fixed_ms);
    run.model_vertex_ms = p.map(|p| p.vertex_ms);
    run.model_primitive_ms = p.map(|p| p.primitive_ms);
    run.model_fragment_opaque_ms = p.map(|p| p.fragment_opaque_ms);
    run.model_fragment_alpha_tested_ms = p.map(|p| p.fragment_alpha_tested_ms);
    run.model_fragment_blended_ms = p.map(|p| p.fragment_blended_ms);
    run.model_draw_ms = p.map(|p| p.draw_ms);
    run.model_compute_ms = p.map(|p| p.compute_ms);
    run.model_upload_ms = p.map(|p| p.upload_ms);
    run.model_texture_load_ms = p.map(|p| p.texture_load_ms);
    run.model_float_texture_load_ms = p.map(|p| p.float_texture_load_ms);
    run.model_vertex_texture_load_ms = p.map(|p| p.vertex_texture_load_ms);
    run.model_vertex_float_texture_load_ms = p.map(|p| p.vertex_float_texture_load_ms);
    run.model_texture_sample_ms = p.map(|p| p.texture_sample_ms);
    run.model_float_texture_sample_ms = p.map(|p| p.float_texture_sample_ms);
    run.model_vertex_transcendental_ms = p.map(|p| p.vertex_transcendental_ms);
    run.model_fragment_transcendental_ms = p.map(|p| p.fragment_transcendental_ms);
    run.model_compute_transcendental_ms = p.map(|p| p.compute_transcendental_ms);
    run.model_vertex_arithmetic_ms = p.map(|p| p.vertex_arithmetic_ms);
    run.model_fragment_arithmetic_ms = p.map(|p| p.fragment_arithmetic_ms);
    run.model_compute_arithmetic_ms = p.map(|p| p.compute_arithmetic_ms);
    run.model_compute_barrier_ms = p.map(|p| p.compute_barrier_ms);
    run.model_compute_storage_ms = p.map(|p| p.compute_storage_ms);
    run.model_vertex_storage_ms = p.map(|p| p.vertex_storage_ms);
    run.model_compute_division_ms = p.map(|p| p.compute_division_ms);
    run.model_texture_mip_blend_ms = p.map(|p| p.texture_mip_blend_ms);
    run.model_ratio = run
        .gpu_wall_ms_median
        .zip(run.model_ms)
        .filter(|(_, m)| *m > 0.0)
        .map(|(w, m)| w / m);
}
