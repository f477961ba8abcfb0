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
            // Older records count no instances: their calibrations had no instance term (it
            // was folded into the vertex and primitive prices), so none is priced.
            instances: f(r.instances).unwrap_or(0.0) + f(r.background_instances).unwrap_or(0.0),
            // Likewise their primitives' input slots.
            primitive_inputs: f(r.primitive_inputs).unwrap_or(0.0)
                + f(r.background_primitive_inputs).unwrap_or(0.0),
            // Likewise their samples at a level of their own.
            texture_explicit_levels: f(r.texture_explicit_levels).unwrap_or(0.0)
                + f(r.background_texture_explicit_levels).unwrap_or(0.0),
            // Older records do not say how their primitives split among their segments: each
            // priced as a small pass's (as their calibrations priced all), head and all.
            head_primitives: f(r.head_primitives)
                .or(f(r.clipper_primitives_out))
                .unwrap_or(0.0)
                + f(r.background_head_primitives)
                    .or(f(r.background_primitives))
                    .unwrap_or(0.0),
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
/// have no counted work, and where the run was drawn with MSAA and the costs without, or the
/// other way round ([`UnitCosts::prices`]): no number rather than one that leaves out work.
pub fn apply_model(run: &mut RunSummary, costs: &UnitCosts, frames: &[FrameRecord]) {
    let p = if costs.prices(run.msaa) {
        predict_run(costs, frames)
    } else {
        None
    };
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
    run.model_instance_ms = p.map(|p| p.instance_ms);
    run.model_primitive_input_ms = p.map(|p| p.primitive_input_ms);
    run.model_texture_explicit_level_ms = p.map(|p| p.texture_explicit_level_ms);
    run.model_head_primitive_ms = p.map(|p| p.head_primitive_ms);
    run.model_ratio = run
        .gpu_wall_ms_median
        .zip(run.model_ms)
        .filter(|(_, m)| *m > 0.0)
        .map(|(w, m)| w / m);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cost::{FitSummary, Term, UnitCost};

    /// One frame of `msaa` whose technique's passes counted 1 000 vertices, 300 primitives
    /// and 20 000 opaque fragments, drawn in 10 ms.
    fn frame(msaa: bool) -> FrameRecord {
        toml::from_str(&format!(
            r#"
            run_id = "r"
            technique = "t"
            scene = "s"
            width = 320
            height = 180
            msaa = {msaa}
            frame = 0
            time_s = 0.0
            wind_ms = 0.0
            update_ms = 0.0
            upload_ms = 0.0
            encode_ms = 0.0
            gpu_wall_ms = 10.0
            triangles = 300
            draw_calls = 1
            gpu_bytes = 0
            vertex_invocations = 1000
            clipper_invocations = 300
            clipper_primitives_out = 300
            fragment_invocations = 20000
            fragments_opaque = 20000
            fragments_alpha_tested = 0
            fragments_blended = 0
            compute_invocations = 0
            background_vertex_invocations = 0
            background_primitives = 0
            background_fragment_invocations = 0
            background_draw_calls = 0
            upload_bytes = 0
            counters = ""
            levels = []
            "#
        ))
        .expect("a frame record")
    }

    /// Single-sampled costs at 320x180 of 1 µs a unit, every term.
    fn every_unit_a_microsecond() -> UnitCosts {
        UnitCosts::from_ms_per_unit(
            "320x180".into(),
            "test".into(),
            [UnitCost::exact(1e-3); Term::ALL.len()],
            FitSummary::default(),
        )
    }

    #[test]
    fn a_run_drawn_unlike_the_calibration_is_not_priced() {
        // Every unit 1 µs: a submission, a draw, 1 000 vertices, 300 primitives (each also
        // a head primitive: a record without the head's columns is priced as one small
        // pass) and 20 000 fragments are 0.001 + 0.001 + 1 + 0.3 + 0.3 + 20 ms.
        let costs = every_unit_a_microsecond();
        assert!(!costs.msaa, "the calibration draws single-sampled");
        let priced = |msaa: bool| {
            let frames = [frame(msaa)];
            let mut run = RunSummary::from_frames(&frames, &toml::Table::new());
            apply_model(&mut run, &costs, &frames);
            (run.msaa, run.model_ms, run.model_ratio)
        };
        let (msaa, model, ratio) = priced(false);
        assert!(!msaa);
        let model = model.expect("a single-sampled run is priced");
        assert!((model - 21.602).abs() < 1e-9, "{model}");
        assert!(ratio.is_some_and(|r| (r - 10.0 / 21.602).abs() < 1e-9));
        // With MSAA: no figure rather than one that leaves the per-sample work out.
        assert_eq!(priced(true), (true, None, None));
    }

    #[test]
    fn a_frame_counted_by_segments_prices_its_head_alone() {
        let costs = every_unit_a_microsecond();
        // The same frame, its segments' heads counted: 120 of its 300 primitives, 30 of the
        // background's 50; 600 slots.
        let mut r = frame(false);
        r.background_primitives = Some(50);
        r.primitive_inputs = Some(600);
        r.head_primitives = Some(120);
        r.background_head_primitives = Some(30);
        let w = Work::of_frame(&r).expect("counted work");
        assert_eq!((w.primitives, w.head_primitives), (350.0, 150.0));
        assert_eq!(w.primitive_inputs, 600.0);
        let frames = [r];
        let mut run = RunSummary::from_frames(&frames, &toml::Table::new());
        apply_model(&mut run, &costs, &frames);
        // 21.302 ms and the background's 50 primitives, the 150 head primitives and the 600
        // slots.
        let model = run.model_ms.expect("priced");
        assert!(
            (model - (21.302 + 0.05 + 0.15 + 0.6)).abs() < 1e-9,
            "{model}"
        );
        assert_eq!(run.head_primitives, Some(120));
        assert!(
            run.model_head_primitive_ms
                .is_some_and(|ms| (ms - 0.15).abs() < 1e-12)
        );
    }
}
