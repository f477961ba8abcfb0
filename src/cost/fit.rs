//! Fitting [`UnitCosts`] to timed workloads whose work is known: weighted, non-negative least
//! squares over every term jointly.
//!
//! Each sample is one submission: its measured time `t` and its work `w`. The model is
//! `t ≈ Σ_k c_k · w_k` over [`Term::ALL`] (the fixed term's amount is 1). Every workload
//! isolates one term but also does a little of others (a full-screen layer has vertices,
//! primitives and a draw; every sample has its submission), so all costs are fitted at once
//! rather than one workload at a time.
//!
//! - **Relative errors.** Noise in wall time grows with the time (a busy host stretches a
//!   long sample more), and samples span 1-100 ms: the fit minimises
//!   `Σ ((predicted − measured) / measured)²`, i.e. weights each row by `1 / measured`, so a
//!   1 ms sample counts as much as a 100 ms one. Residuals are reported in the same terms.
//! - **Non-negative costs.** Work cannot save time, but noise can make a small cost come out
//!   negative; a negative cost would predict negative time for a frame doing mostly that.
//!   The fit is Lawson and Hanson's NNLS (see `lstsq`): a term whose unconstrained optimum is
//!   negative is held at zero (`at_zero`) and the others refitted without it.
//! - **Identifiability.** A term never exercised by any sample, or exercised only in fixed
//!   proportion to others (no sample tells them apart), has no cost to find: the fit refuses
//!   with [`Error::CostFit`] naming the terms, never a NaN.

use super::lstsq::{self, qr_solve};
use super::{Term, UnitCost, UnitCosts, Work};
use crate::{Error, Result};

/// One timed submission whose work is known.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Sample {
    /// Which workload (`vertices`, `fragments_opaque`, ...).
    pub workload: String,
    /// Its measured time, ms.
    pub measured_ms: f64,
    /// Its work.
    pub work: Work,
}

/// How well fitted costs explain the samples.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FitSummary {
    /// Samples fitted.
    pub samples: usize,
    /// RMS over all samples of `(predicted − measured) / measured`.
    pub relative_rms_residual: f64,
    /// The largest `|predicted − measured| / measured`.
    pub max_relative_residual: f64,
    /// The same per workload, in the order the samples came.
    pub workloads: Vec<WorkloadResidual>,
}

/// The residuals of one workload's samples.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WorkloadResidual {
    /// Workload name.
    pub workload: String,
    /// Its samples (sizes).
    pub samples: usize,
    /// RMS of `(predicted − measured) / measured` over them.
    pub relative_rms_residual: f64,
    /// The largest `|predicted − measured| / measured` among them.
    pub max_relative_residual: f64,
}

impl Sample {
    /// `(predicted − measured) / measured` under `costs`.
    pub fn relative_residual(&self, costs: &UnitCosts) -> f64 {
        (costs.predict(&self.work).total_ms - self.measured_ms) / self.measured_ms
    }
}

/// Fits one cost per [`Term`] to `samples`, drawn at target `size` and timed with `clock`
/// (both recorded in the result).
///
/// Errors ([`Error::CostFit`]): a sample with a non-positive or non-finite time or invalid
/// work; no more samples than terms; terms the samples cannot identify.
pub fn fit(samples: &[Sample], size: &str, clock: &str) -> Result<UnitCosts> {
    let fail = |message: String| Error::CostFit {
        unidentifiable: Vec::new(),
        message,
    };
    for s in samples {
        let positive = s.measured_ms.is_finite() && s.measured_ms > 0.0;
        if !positive || !s.work.is_valid() {
            return Err(fail(format!(
                "sample of workload `{}` has time {} ms and work {:?}: times must be positive and work finite and non-negative",
                s.workload, s.measured_ms, s.work
            )));
        }
    }
    let n_terms = Term::ALL.len();
    if samples.len() <= n_terms {
        return Err(fail(format!(
            "{} samples for {n_terms} unit costs: the fit needs more samples than costs to estimate their errors (the calibration runs several sizes of every workload)",
            samples.len()
        )));
    }
    // Weighted design: row i divided by its measured time, target 1.
    let mut columns: Vec<Vec<f64>> = Term::ALL
        .iter()
        .map(|&t| {
            samples
                .iter()
                .map(|s| s.work.amount(t) / s.measured_ms)
                .collect()
        })
        .collect();
    let b = vec![1.0; samples.len()];
    check_identifiable(&columns, &b)?;
    // Unit-norm columns: costs span 10 orders of magnitude (ns per vertex against ms per MB).
    let scales: Vec<f64> = columns
        .iter()
        .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
        .collect();
    for (c, s) in columns.iter_mut().zip(&scales) {
        c.iter_mut().for_each(|x| *x /= s);
    }
    let scaled = lstsq::nnls(&columns, &b).ok_or_else(|| {
        fail(
            "the non-negative least-squares iteration did not settle (an ill-conditioned design)"
                .into(),
        )
    })?;
    let refs: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
    let gram_inv = qr_solve(&refs, &b)
        .map_err(|j| fail(format!("`{}` became dependent after scaling", Term::ALL[j])))?
        .inverse_gram();
    let fitted = lstsq::apply(&columns, &scaled);
    let rss: f64 = fitted.iter().map(|f| (f - 1.0) * (f - 1.0)).sum();
    let variance = rss / (samples.len() - n_terms) as f64;
    let per_unit: Vec<UnitCost> = (0..n_terms)
        .map(|j| UnitCost {
            value: scaled[j] / scales[j],
            standard_error: (variance * gram_inv[j][j]).sqrt() / scales[j],
            at_zero: scaled[j] == 0.0,
        })
        .collect();
    let per_unit: [UnitCost; Term::ALL.len()] = per_unit
        .try_into()
        .map_err(|_| fail("internal: one cost per term".into()))?;
    let mut costs = UnitCosts::from_ms_per_unit(
        size.to_owned(),
        clock.to_owned(),
        per_unit,
        FitSummary::default(),
    );
    costs.fit = summarise(samples, &costs);
    Ok(costs)
}

/// Residuals of `samples` under `costs`, overall and per workload.
pub fn summarise(samples: &[Sample], costs: &UnitCosts) -> FitSummary {
    let residuals: Vec<f64> = samples.iter().map(|s| s.relative_residual(costs)).collect();
    let rms = |r: &[f64]| (r.iter().map(|x| x * x).sum::<f64>() / r.len().max(1) as f64).sqrt();
    let max = |r: &[f64]| r.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
    let mut names: Vec<&str> = Vec::new();
    for s in samples {
        if !names.contains(&s.workload.as_str()) {
            names.push(&s.workload);
        }
    }
    let workloads = names
        .iter()
        .map(|name| {
            let r: Vec<f64> = samples
                .iter()
                .zip(&residuals)
                .filter(|(s, _)| s.workload == *name)
                .map(|(_, r)| *r)
                .collect();
            WorkloadResidual {
                workload: (*name).to_owned(),
                samples: r.len(),
                relative_rms_residual: rms(&r),
                max_relative_residual: max(&r),
            }
        })
        .collect();
    FitSummary {
        samples: samples.len(),
        relative_rms_residual: rms(&residuals),
        max_relative_residual: max(&residuals),
        workloads,
    }
}

/// Refuses designs that cannot identify every term: names the terms no sample exercises,
/// then, one at a time, those whose amounts are a combination of the others'.
fn check_identifiable(columns: &[Vec<f64>], b: &[f64]) -> Result<()> {
    let mut problems = Vec::new();
    let mut unidentifiable = Vec::new();
    let mut kept: Vec<usize> = Vec::new();
    for (j, c) in columns.iter().enumerate() {
        if c.iter().all(|&x| x == 0.0) {
            problems.push(format!(
                "`{}` is never exercised by any sample",
                Term::ALL[j]
            ));
            unidentifiable.push(Term::ALL[j].name().to_owned());
        } else {
            kept.push(j);
        }
    }
    // Drop dependent columns one by one until the rest is independent.
    loop {
        let refs: Vec<&[f64]> = kept.iter().map(|&j| columns[j].as_slice()).collect();
        match qr_solve(&refs, b) {
            Ok(_) => break,
            Err(i) if i < kept.len() => {
                let j = kept.remove(i);
                let others: Vec<&str> = kept[..i].iter().map(|&k| Term::ALL[k].name()).collect();
                problems.push(format!(
                    "`{}` is a linear combination of {} over the samples (no sample tells them apart)",
                    Term::ALL[j],
                    others.join(", ")
                ));
                unidentifiable.push(Term::ALL[j].name().to_owned());
            }
            Err(_) => {
                return Err(Error::CostFit {
                    unidentifiable,
                    message: "fewer samples than terms".into(),
                });
            }
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(Error::CostFit {
            unidentifiable,
            message: format!(
                "{}. Fix: add workloads that vary these terms on their own",
                problems.join("; ")
            ),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cost::workloads::{families, sizes};
    use crate::rng::Rng;
    use crate::target::Size;

    const SIZE: Size = Size {
        width: 640,
        height: 360,
    };

    /// Lavapipe-like costs in ms per unit, in the order of `Term::ALL`: fixed 0.5 ms,
    /// vertex 20 ns, primitive 75 ns, fragments 5 / 8 / 6 ns, draw 5 µs, compute 5 ns, upload
    /// 2 ms per MB, texel load 3 ns (8 ns floating-point; 3 and 10 ns more in a vertex
    /// shader), texture sample 6 ns (13 ns floating-point; 4 ns more blending two mip levels),
    /// transcendentals 2 / 0.6 / 0.6 ns (vertex, fragment, compute), scalar operations 0.2 /
    /// 0.03 / 0.1 ns, a compute invocation at a barrier 15 ns, a compute shader's storage word
    /// 0.4 ns, a vertex shader's 1 ns, a compute shader's integer division 3 ns, an instance
    /// 150 ns, a primitive's fragment input slot 13 ns, a sample's level picked lane by lane
    /// 3 ns, a primitive among its pass's first 360 000 25 ns more.
    const TRUE_MS: [f64; Term::ALL.len()] = [
        0.5, 2e-5, 7.5e-5, 5e-6, 8e-6, 6e-6, 5e-3, 5e-6, 2.0, 3e-6, 8e-6, 3e-6, 1e-5, 6e-6, 1.3e-5,
        2e-6, 6e-7, 6e-7, 2e-7, 3e-8, 1e-7, 1.5e-5, 4e-7, 1e-6, 3e-6, 4e-6, 1.5e-4, 1.3e-5, 3e-6,
        2.5e-5,
    ];

    fn time(costs: &[f64; Term::ALL.len()], w: &Work) -> f64 {
        Term::ALL
            .iter()
            .map(|&t| costs[t.index()] * w.amount(t))
            .sum()
    }

    /// The calibration's samples (every family at every size, at 640x360) timed with `costs`,
    /// each time multiplied by `1 + noise · u`, `u` uniform in [−1, 1).
    fn synthetic(costs: &[f64; Term::ALL.len()], noise: f64, seed: u64) -> Vec<Sample> {
        let mut rng = Rng::new(seed);
        families()
            .iter()
            .flat_map(|f| sizes(f, 1))
            .map(|w| {
                let work = w.work(SIZE);
                let u = f64::from(rng.range(-1.0, 1.0));
                Sample {
                    workload: w.name.to_owned(),
                    measured_ms: time(costs, &work) * (1.0 + noise * u),
                    work,
                }
            })
            .collect()
    }

    fn fitted_ms(c: &UnitCosts) -> Vec<f64> {
        Term::ALL.iter().map(|&t| c.ms_per_unit(t)).collect()
    }

    #[test]
    fn noiseless_samples_give_back_the_costs() {
        let c = fit(&synthetic(&TRUE_MS, 0.0, 1), "640x360", "synthetic").unwrap();
        for (t, (got, want)) in Term::ALL.iter().zip(fitted_ms(&c).iter().zip(TRUE_MS)) {
            // Rounding only (QR on unit-norm columns, a few dozen rows).
            assert!((got / want - 1.0).abs() < 1e-9, "{t}: {got} against {want}");
        }
        assert!(c.fit.relative_rms_residual < 1e-12, "{:?}", c.fit);
        assert_eq!(c.fit.samples, 124);
        assert_eq!(c.fit.workloads.len(), 31);
        assert_eq!(c.size, "640x360");
    }

    #[test]
    fn noisy_samples_give_costs_within_their_standard_errors() {
        // ±10% uniform noise on every time: about what the busy 2-core host adds to a
        // median of 5 (RMS of the noise: 10% / √3 = 5.8%).
        for seed in 1..=20 {
            let samples = synthetic(&TRUE_MS, 0.10, seed);
            let c = fit(&samples, "640x360", "synthetic").unwrap();
            for (t, (got, want)) in Term::ALL.iter().zip(fitted_ms(&c).iter().zip(TRUE_MS)) {
                let se = c.get(*t).standard_error * t.ms_per_stored_unit();
                // Within 5 standard errors: the largest error over 200 seeds (6000 costs)
                // was 4.0 SE.
                assert!(
                    (got - want).abs() < 5.0 * se,
                    "seed {seed}, {t}: {got} against {want}, SE {se}"
                );
                // And each cost is back within 25%; those fitted from what is left of a
                // workload once other terms take their share within 35%, the compute
                // invocation's, the vertex's, the vertex stage's RGBA8 load's and a sample's
                // level picked lane by lane within 50%. The worst over 200 seeds (30 costs):
                // 37.9% for the vertex (every vertex workload's arithmetic and instances move
                // with its vertices but the chain's), 35.7% for a sample's level picked lane
                // by lane and 29.2% for the sample's second mip level (each the difference of
                // two workloads whose fragments cost more than their samples), 35.2% for the
                // vertex stage's RGBA8 load and 34.6% for its storage word (their strips also
                // pay their vertices' and instances' cost), 30.4% for the compute invocation
                // (every compute workload also reads and writes 8 storage words, more than
                // the invocation's own cost here), 28.9% for the compute shader's storage
                // word, 24.5% for the primitive's input slot and 23.9% for the primitive (the
                // large passes' price, shared with the head's), 21.7% for the opaque
                // fragment, 7.9-21.9% for the others (20.7% for the instance, its strips'
                // three vertices a third of its cost; 10.0% for the compute barrier, 14.1%
                // for the compute division). A pass head's extra on its own is the difference
                // of two slopes, each with its noise (worst 79.7%): its standard error says
                // so, and what a small pass is priced with, the head's and the large pass's
                // price together, is checked below.
                let bound = match *t {
                    Term::HeadPrimitive => continue,
                    Term::Vertex
                    | Term::Compute
                    | Term::VertexTextureLoad
                    | Term::TextureExplicitLevel => 0.50,
                    Term::Primitive
                    | Term::PrimitiveInput
                    | Term::VertexStorage
                    | Term::ComputeStorage
                    | Term::FragmentOpaque
                    | Term::TextureMipBlend => 0.35,
                    _ => 0.25,
                };
                assert!(
                    (got / want - 1.0).abs() < bound,
                    "seed {seed}, {t}: {got} against {want}"
                );
            }
            // A small pass's price of a primitive, the large pass's and the head's together:
            // within 25% (the worst over 200 seeds: 10.7%).
            let fitted = fitted_ms(&c);
            let (large, head) = (Term::Primitive.index(), Term::HeadPrimitive.index());
            let small = (fitted[large] + fitted[head]) / (TRUE_MS[large] + TRUE_MS[head]);
            assert!(
                (small - 1.0).abs() < 0.25,
                "seed {seed}: a small pass's primitive {small}x"
            );
            // The residual reports the noise: its RMS is 5.8%, of which the fit absorbs
            // some (30 costs from 124 samples); over 200 seeds it read 4.3% to 5.7%.
            let r = c.fit.relative_rms_residual;
            assert!((0.02..0.08).contains(&r), "seed {seed}: residual {r}");
        }
    }

    #[test]
    fn a_held_out_mix_is_predicted_from_noisy_costs() {
        // A grass-like frame: 100k blades of 11 vertices (9 triangles of 3 fragment input
        // slots), an instance each, 2 M fragments of
        // each kind, 20 draws, 500k compute invocations, 2 MB uploaded, 8 M texel loads,
        // 12.8 M of floating-point texels (8 a vertex, a blade's height and wind, and 4 M in
        // fragments), 6 M texture samples and 2 M of floating-point texels (7 M of the 8 M
        // blending two mip levels, 2 M at a level each fragment gives),
        // 10 transcendentals a vertex, 1 a fragment and 4 a compute
        // invocation, 200 scalar operations a vertex, 100 a fragment and 500 a compute
        // invocation, 3 barriers, 20 storage words and 2 integer divisions a compute
        // invocation, 10 storage words a vertex.
        let mix = Work {
            vertex_invocations: 1.1e6,
            primitives: 9e5,
            fragments_opaque: 2e6,
            fragments_alpha_tested: 2e6,
            fragments_blended: 2e6,
            draw_calls: 20.0,
            compute_invocations: 5e5,
            upload_bytes: 2e6,
            texture_loads: 8e6,
            float_texture_loads: 1.28e7,
            vertex_texture_loads: 0.0,
            vertex_float_texture_loads: 8.8e6,
            texture_samples: 6e6,
            float_texture_samples: 2e6,
            vertex_transcendentals: 1.1e7,
            fragment_transcendentals: 6e6,
            compute_transcendentals: 2e6,
            vertex_arithmetic: 2.2e8,
            fragment_arithmetic: 6e8,
            compute_arithmetic: 2.5e8,
            compute_barriers: 1.5e6,
            compute_storage: 1e7,
            vertex_storage: 1.1e7,
            compute_divisions: 1e6,
            texture_mip_blends: 7e6,
            instances: 1e5,
            primitive_inputs: 2.7e6,
            texture_explicit_levels: 2e6,
            // In one segment: its first 360 000 priced as a small pass's.
            head_primitives: 3.6e5,
        };
        let truth = time(&TRUE_MS, &mix);
        for seed in 1..=20 {
            let c = fit(&synthetic(&TRUE_MS, 0.10, seed), "640x360", "synthetic").unwrap();
            let p = c.predict(&mix);
            // Within 10%: the worst over 200 seeds was 3.5%, against ±10% noise on each
            // sample (the costs' errors partly cancel in a mix).
            assert!(
                (p.total_ms / truth - 1.0).abs() < 0.10,
                "seed {seed}: {} ms against {truth} ms",
                p.total_ms
            );
        }
    }

    #[test]
    fn a_free_term_is_held_at_zero_not_negative() {
        let mut costs = TRUE_MS;
        costs[Term::FragmentBlended.index()] = 0.0;
        let mut zeros = 0;
        for seed in 1..=20 {
            let c = fit(&synthetic(&costs, 0.10, seed), "640x360", "synthetic").unwrap();
            for t in Term::ALL {
                let u = c.get(t);
                assert!(
                    u.value >= 0.0 && (!u.at_zero || u.value == 0.0),
                    "{t}: {u:?}"
                );
            }
            zeros += usize::from(c.fragment_blended_ns.at_zero);
        }
        // Unconstrained, the estimate of a zero cost is negative about half the time: some
        // of the 20 fits must have pinned it (none would be as likely as 20 heads in a row).
        assert!(zeros > 0);
    }

    #[test]
    fn a_term_no_sample_exercises_is_named_not_nan() {
        let samples: Vec<Sample> = synthetic(&TRUE_MS, 0.0, 1)
            .into_iter()
            .filter(|s| !s.workload.contains("compute"))
            .collect();
        match fit(&samples, "640x360", "synthetic") {
            Err(Error::CostFit {
                unidentifiable,
                message,
            }) => {
                assert_eq!(
                    unidentifiable,
                    [
                        "compute",
                        "compute_transcendental",
                        "compute_arithmetic",
                        "compute_barrier",
                        "compute_storage",
                        "compute_division"
                    ]
                );
                assert!(
                    message.contains("`compute` is never exercised"),
                    "{message}"
                );
                assert!(
                    message.contains("`compute_transcendental` is never exercised"),
                    "{message}"
                );
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn terms_that_move_together_are_named() {
        // Only strips of 11 vertices and 9 triangles: vertices and primitives always in the
        // ratio 11 : 9, so no sample tells their costs apart. The other terms are exercised
        // by constant multiples of nothing, i.e. never.
        let samples: Vec<Sample> = synthetic(&TRUE_MS, 0.0, 1)
            .into_iter()
            .filter(|s| s.workload == "primitives" || s.workload == "empty")
            .chain(
                synthetic(&TRUE_MS, 0.0, 2)
                    .into_iter()
                    .filter(|s| s.workload == "primitives" || s.workload == "upload"),
            )
            // More samples than the 31 costs.
            .chain(
                [3, 4, 5, 6]
                    .into_iter()
                    .flat_map(|seed| synthetic(&TRUE_MS, 0.0, seed))
                    .filter(|s| s.workload == "primitives"),
            )
            .collect();
        match fit(&samples, "640x360", "synthetic") {
            Err(Error::CostFit {
                unidentifiable,
                message,
            }) => {
                assert!(
                    unidentifiable.contains(&"primitive".to_owned()),
                    "{message}"
                );
                assert!(!unidentifiable.contains(&"vertex".to_owned()), "{message}");
                assert!(
                    message.contains("`primitive` is a linear combination of"),
                    "{message}"
                );
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn bad_samples_are_refused() {
        let mut samples = synthetic(&TRUE_MS, 0.0, 1);
        assert!(fit(&samples[..9], "640x360", "synthetic").is_err());
        samples[3].measured_ms = f64::NAN;
        assert!(fit(&samples, "640x360", "synthetic").is_err());
        samples[3].measured_ms = 0.0;
        assert!(fit(&samples, "640x360", "synthetic").is_err());
    }
}
