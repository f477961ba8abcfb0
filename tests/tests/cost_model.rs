//! The cost model on the GPU (issue 20 §2-§3): the calibration's micro-workloads do the work
//! they were designed to do (the GPU's own counters agree), the unit costs fitted to them
//! explain their times, and they predict a frame that mixes every kind of work, which no
//! calibration sample did.
//!
//! Bounds on times come from 24 runs on the shared 2-core lavapipe host while others built
//! and tested on it (load average 2.1-5, other processes busy on 0-1.3 cores during the
//! calibration): the residuals there are dominated by the host's load, not by the model. The
//! bounds are about twice the worst of those runs, and each says what was measured.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use anyhow::Context as _;
use grassbench::cost::checks::{self, coverage_checks};
use grassbench::cost::workloads::{self, Chain, Fetch, Shape, Workload};
use grassbench::cost::{
    COUNTED_TERMS, FragmentKind, MeasuredSample, Options, Term, UnitCosts, Work,
    calibrate_units_with,
};
use grassbench::target::Size;
use grassbench_tests::gpu;

const SIZE: Size = Size {
    width: 640,
    height: 360,
};

#[test]
fn calibration_counts_its_work_and_its_costs_predict_a_held_out_mix() -> anyhow::Result<()> {
    let gpu = gpu()?;
    assert!(
        gpu.has_pipeline_statistics(),
        "lavapipe has PIPELINE_STATISTICS_QUERY (shared/PLATFORM.md); this adapter ({}) does not",
        gpu.summary.name
    );
    // Timed on a shared host, one calibration in a noisy hour can leave one of its terms
    // unresolved (2 of 6 runs on the 2-vCPU EPYC, 2026-12-05 14:30-14:40 UTC:
    // fragment_arithmetic at 0.0095 ± 0.0049 ns, vertex_arithmetic at 0.0118 ± 0.0101; the
    // next four resolved every term): the test then calibrates once more and holds the
    // second calibration to every check.
    let calibrate = || {
        calibrate_units_with(&gpu, SIZE, Options::default(), &[held_out_mix()])
            .context("calibrating")
    };
    let mut cal = calibrate()?;
    let first = unresolved(&cal.unit_costs);
    if !first.is_empty() {
        eprintln!("unresolved in the first calibration, calibrating again: {first:?}");
        cal = calibrate()?;
    }
    let costs = &cal.unit_costs;
    eprint!("{}", costs.to_markdown());

    // The counters against the work known in advance, in every sample and in the mix.
    for s in cal.samples.iter().chain(&cal.held_out) {
        check_counts(
            &s.sample.workload,
            &s.known,
            &s.counted.context("counted work")?,
        );
    }
    let left = unresolved(costs);
    assert!(left.is_empty(), "unresolved: {left:?}");

    // The fit explains its own samples. Over 24 runs the overall RMS residual was 5.9-23%
    // and the worst workload's 33% (primitives, while the host's load moved).
    for w in &costs.fit.workloads {
        eprintln!(
            "{}: RMS {:.1}%, max {:.1}%",
            w.workload,
            100.0 * w.relative_rms_residual,
            100.0 * w.max_relative_residual
        );
        assert!(w.relative_rms_residual < 0.65, "{w:?}");
    }
    eprintln!(
        "overall RMS {:.1}%, max {:.1}%, other processes on {:?} cores",
        100.0 * costs.fit.relative_rms_residual,
        100.0 * costs.fit.max_relative_residual,
        costs.host_other_cores
    );
    assert!(costs.fit.relative_rms_residual < 0.35, "{:?}", costs.fit);
    // The reported residual is the samples' own under the fitted costs.
    let residuals: Vec<f64> = cal
        .samples
        .iter()
        .map(|s| s.sample.relative_residual(costs))
        .collect();
    let rms = (residuals.iter().map(|r| r * r).sum::<f64>() / residuals.len() as f64).sqrt();
    assert!((rms - costs.fit.relative_rms_residual).abs() < 1e-12);

    // A held-out frame with some of every kind of work, timed in the same rounds: predicted
    // within 50% (24 runs: −16% to +25%; the mix's own median ranged 82-118 ms over 5 runs
    // at one load).
    let m = &cal.held_out[0];
    let predicted = costs.predict(&m.sample.work);
    let error = predicted.total_ms / m.sample.measured_ms - 1.0;
    eprintln!(
        "mix: measured {:.1} ms (runs {:?}), predicted {:.1} ms ({:+.1}%), {predicted:?}",
        m.sample.measured_ms,
        m.runs_ms,
        predicted.total_ms,
        100.0 * error
    );
    assert!(error.abs() < 0.5, "{error}");
    check_coverage(costs, &cal.check_samples, SIZE, 1);
    Ok(())
}

/// The coverage checks (`timed`, in [`coverage_checks`]' order, on a `size` target
/// of `samples` samples a pixel) counted as drawn: the blades' vertices exactly, their
/// triangles all rasterised, more fragments than the pixels they cover (a rasteriser shades
/// whole blocks) and fewer samples kept per fragment for the slivers than for the blades, half
/// of them for the alpha-tested kind (it discards half its pixels); the hidden layers every
/// fragment counted and only the occluder's samples kept. Each is priced (a finite, positive
/// time either way); what the ratios are is the calibration's finding, not a test's.
fn check_coverage(costs: &UnitCosts, timed: &[MeasuredSample], size: Size, samples: u64) {
    let checks = coverage_checks();
    assert_eq!(timed.len(), checks.len());
    let results = &costs.checks;
    assert_eq!(results, &checks::results(costs, &checks, timed));
    eprint!("{}", checks::to_markdown(results));
    let pixels = u64::from(size.width * size.height);
    let kept = |name: &str, i: usize| {
        results
            .iter()
            .enumerate()
            .filter(|(_, r)| r.check == name)
            .nth(i)
            .and_then(|(_, r)| r.kept_per_fragment)
            .unwrap_or(f64::NAN)
    };
    for ((check, m), r) in checks.iter().zip(timed).zip(results) {
        let counted = m.counted.expect("counted work");
        let known = &m.known;
        let what = format!("{}: counted {counted:?}, known {known:?}", check.name);
        assert!(r.ratio.is_finite() && r.ratio > 0.0, "{what}");
        assert_eq!(
            counted.vertex_invocations, known.vertex_invocations,
            "{what}"
        );
        let fragments =
            |w: &Work| w.fragments_opaque + w.fragments_alpha_tested + w.fragments_blended;
        if check.name.starts_with("hidden") {
            // Every layer's fragments counted (lavapipe: 1.0125 times the pixels at 640x360,
            // the blocks on the seams of a clipped layer shading twice; 1.031 at 320x180 with
            // 4x MSAA), and the occluder's samples alone kept.
            assert!(
                fragments(known) <= fragments(&counted)
                    && fragments(&counted) <= 1.04 * fragments(known),
                "{what}"
            );
            assert_eq!(m.samples_passed, Some(pixels * samples), "{what}");
        } else {
            // Blades rooted near the top edge are clipped: a few triangles more or fewer.
            let p = counted.primitives / known.primitives;
            assert!((0.9..=1.1).contains(&p), "{what}");
            assert!(fragments(&counted) > fragments(known), "{what}");
            let k = r.kept_per_fragment.unwrap_or(f64::NAN);
            assert!(k > 0.0 && k <= samples as f64, "{what}");
        }
    }
    for i in 0..2 {
        for kind in ["opaque", "alpha_tested", "blended"] {
            let (blades, slivers) = (
                kept(&format!("blades_{kind}"), i),
                kept(&format!("slivers_{kind}"), i),
            );
            assert!(
                slivers < blades,
                "{kind}: slivers keep {slivers}, blades {blades}"
            );
        }
        for width in ["blades", "slivers"] {
            let half =
                kept(&format!("{width}_alpha_tested"), i) / kept(&format!("{width}_opaque"), i);
            assert!(
                (0.4..0.6).contains(&half),
                "{width}: alpha-tested keep {half} of opaque's"
            );
        }
    }
}

/// The terms whose fitted cost is not a resolved number: every term's own workload must
/// resolve a positive cost, its standard error under half its value (11 runs: 4.7-18.3 %,
/// growing with the residual). The vertex stage's loads are priced on top of every load's
/// price, and what they add may be next to nothing on a faster host (an RGBA8 load in the
/// vertex stage: 0.24 ± 0.14 ns more than the 0.24 ns fitted for a load at 320x180 on the
/// 2-vCPU EPYC; an `R32Float` one 1.21 ± 0.23 more than 0.81): resolved to within the load's
/// own price. A compute invocation's own cost, beyond the 8 storage words and the arithmetic
/// of the spring update it runs, may be next to nothing too (at 320x180 on the 2-vCPU EPYC:
/// 0.25 ± 0.75 and 2.0 ± 0.85 ns in two calibrations, 2026-12-05, against 4.3 ns for its
/// words): resolved to within half the spring update's whole price an invocation. Likewise a
/// vertex invocation's own cost beyond its shader's operations, since the instances are priced
/// apart (on the Xeon: 0-0.33 ± 0.49-0.74 ns, 2026-12-06, against about 5 ns for the strips'
/// vertex shader's operations): resolved to within half the strips' whole price a vertex.
fn unresolved(costs: &grassbench::cost::UnitCosts) -> Vec<String> {
    let spring = grassbench::cost::workloads::shader_ops("cs_springs");
    let spring_update_ns = costs.get(Term::Compute).value
        + costs.get(Term::ComputeStorage).value * spring.storage as f64
        + costs.get(Term::ComputeArithmetic).value * spring.arithmetic as f64;
    let strip = grassbench::cost::workloads::shader_ops("vs_offscreen");
    let strip_vertex_ns = costs.get(Term::Vertex).value
        + costs.get(Term::VertexTranscendental).value * strip.transcendentals as f64
        + costs.get(Term::VertexArithmetic).value * strip.arithmetic as f64;
    Term::ALL
        .into_iter()
        .filter(|&t| {
            let c = costs.get(t);
            eprintln!(
                "{t}: relative SE {:.1}%",
                100.0 * c.standard_error / c.value
            );
            let base = match t {
                Term::VertexTextureLoad => Some(Term::TextureLoad),
                Term::VertexFloatTextureLoad => Some(Term::FloatTextureLoad),
                _ => None,
            };
            let resolved = match base {
                Some(b) => c.value >= 0.0 && c.standard_error < costs.get(b).value,
                None if t == Term::Compute => {
                    c.value >= 0.0 && c.standard_error < 0.5 * spring_update_ns
                }
                None if t == Term::Vertex => {
                    c.value >= 0.0 && c.standard_error < 0.5 * strip_vertex_ns
                }
                None => c.value > 0.0 && c.standard_error < 0.5 * c.value,
            };
            !(c.value.is_finite() && resolved)
        })
        .map(|t| format!("{t}: {:?}", costs.get(t)))
        .collect()
}

/// Checks what the GPU counted against the work known in advance.
fn check_counts(name: &str, known: &Work, counted: &Work) {
    // Each full-screen layer shades every pixel once: the known fragments count the layers.
    let pixels = f64::from(SIZE.width * SIZE.height);
    let layers =
        (known.fragments_opaque + known.fragments_alpha_tested + known.fragments_blended) / pixels;
    for t in COUNTED_TERMS {
        let (k, c) = (known.amount(t), counted.amount(t));
        let what = format!("{name} {t}: counted {c}, known {k}");
        match t {
            // A full-screen layer is one triangle twice the screen's size: the clipper may
            // cut it at the guard band into pieces (lavapipe: 3, i.e. 2 more per layer).
            // So may the head's, where the pass is within it.
            Term::Primitive | Term::HeadPrimitive => {
                assert!(k <= c && c <= k + 2.0 * layers, "{what}")
            }
            // Those pieces set up the layers' fragment input slots too.
            Term::PrimitiveInput => {
                let slots = workloads::fragment_inputs(workloads::layer_fragment_entry(
                    FragmentKind::Opaque,
                ));
                assert!(k <= c && c <= k + 2.0 * layers * slots, "{what}")
            }
            // lavapipe counts fragment invocations in whole 4x4 blocks, and blocks on the
            // seams between the clipped pieces shade twice: 1.25% more than the pixels at
            // 640x360 (2 columns of blocks per layer). No fragment from the sub-pixel or
            // off-screen triangles.
            // Texture fetches and fragment transcendentals and arithmetic are the fragments
            // times the shader's: the same.
            Term::FragmentOpaque
            | Term::FragmentAlphaTested
            | Term::FragmentBlended
            | Term::TextureLoad
            | Term::FloatTextureLoad
            | Term::TextureSample
            | Term::FloatTextureSample
            | Term::TextureMipBlend
            | Term::TextureExplicitLevel
            | Term::FragmentTranscendental
            | Term::FragmentArithmetic => {
                assert!(k <= c && c <= 1.02 * k, "{what}")
            }
            // Vertex and compute invocations exactly.
            _ => assert_eq!(c, k, "{what}"),
        }
    }
}

/// A grass-frame-like mix: 30k off-screen and 10k on-screen blade strips, 3 layers of each
/// fragment kind, a layer loading 32 texels a fragment, one sampling 8 times between two mip
/// levels, one 8 times at one level and one 8 times at a level each fragment gives, the loads and the first samples of floating-point
/// texels, 5k strips loading 32 floating-point texels a vertex, 5k strips, a
/// layer and 65k compute invocations with 30 more transcendentals each, the same with 256
/// more scalar operations each, 16k compute invocations reaching 8 barriers each, 32k reading
/// 32 more storage words each, 5k strips reading 32 storage words a vertex, 300 draws,
/// 1M compute invocations, 8 MiB uploaded.
fn held_out_mix() -> Vec<Workload> {
    let w = |name, term, shape| Workload { name, term, shape };
    let layers = |kind| Shape::Layers { kind, layers: 3 };
    vec![
        w(
            "vertices",
            Term::Vertex,
            Shape::OffscreenStrips {
                vertices: workloads::STRIP_VERTICES,
                instances: 30_000,
            },
        ),
        w(
            "primitives",
            Term::Primitive,
            Shape::SubpixelStrips {
                instances: 10_000,
                interpolated: true,
            },
        ),
        w("opaque", Term::FragmentOpaque, layers(FragmentKind::Opaque)),
        w(
            "alpha",
            Term::FragmentAlphaTested,
            layers(FragmentKind::AlphaTested),
        ),
        w(
            "blended",
            Term::FragmentBlended,
            layers(FragmentKind::Blended),
        ),
        w(
            "loads",
            Term::TextureLoad,
            Shape::FetchLayers {
                fetch: Fetch::Loads,
                layers: 1,
            },
        ),
        w(
            "samples",
            Term::TextureMipBlend,
            Shape::FetchLayers {
                fetch: Fetch::Samples,
                layers: 1,
            },
        ),
        w(
            "single-level samples",
            Term::TextureSample,
            Shape::FetchLayers {
                fetch: Fetch::SingleLevelSamples,
                layers: 1,
            },
        ),
        w(
            "explicit-level samples",
            Term::TextureExplicitLevel,
            Shape::FetchLayers {
                fetch: Fetch::ExplicitLevelSamples,
                layers: 1,
            },
        ),
        w(
            "float loads",
            Term::FloatTextureLoad,
            Shape::FetchLayers {
                fetch: Fetch::FloatLoads,
                layers: 1,
            },
        ),
        w(
            "float samples",
            Term::FloatTextureSample,
            Shape::FetchLayers {
                fetch: Fetch::FloatSamples,
                layers: 1,
            },
        ),
        w(
            "vertex float loads",
            Term::VertexFloatTextureLoad,
            Shape::LoadStrips {
                float: true,
                instances: 5_000,
            },
        ),
        w(
            "vertex transcendentals",
            Term::VertexTranscendental,
            Shape::MathStrips { instances: 5_000 },
        ),
        w(
            "fragment transcendentals",
            Term::FragmentTranscendental,
            Shape::MathLayers { layers: 1 },
        ),
        w(
            "compute transcendentals",
            Term::ComputeTranscendental,
            Shape::Compute {
                groups: 1_024,
                chain: Chain::Transcendental,
            },
        ),
        w(
            "vertex arithmetic",
            Term::VertexArithmetic,
            Shape::ArithmeticStrips { instances: 5_000 },
        ),
        w(
            "fragment arithmetic",
            Term::FragmentArithmetic,
            Shape::ArithmeticLayers { layers: 1 },
        ),
        w(
            "compute arithmetic",
            Term::ComputeArithmetic,
            Shape::Compute {
                groups: 1_024,
                chain: Chain::Arithmetic,
            },
        ),
        w(
            "compute barriers",
            Term::ComputeBarrier,
            Shape::Compute {
                groups: 256,
                chain: Chain::Barriers,
            },
        ),
        w(
            "compute storage",
            Term::ComputeStorage,
            Shape::Compute {
                groups: 512,
                chain: Chain::Storage,
            },
        ),
        w(
            "vertex storage",
            Term::VertexStorage,
            Shape::StorageStrips { instances: 5_000 },
        ),
        w("draws", Term::Draw, Shape::Draws { draws: 300 }),
        w(
            "compute",
            Term::Compute,
            Shape::Compute {
                groups: 16_384,
                chain: Chain::None,
            },
        ),
        w("upload", Term::Upload, Shape::Upload { bytes: 8 << 20 }),
    ]
}

/// The unit costs calibrated on a 4x multisampled target price runs drawn with MSAA (and only
/// those: `UnitCosts::prices`). A single-sampled calibration leaves out MSAA's per-sample
/// coverage, depth tests and resolve (on lavapipe a multisampled calibration at 320x180
/// priced a frame's fixed cost at 0.68-0.74 ms against 0.17-0.20, a primitive at 199-220 ns
/// against 105-130, an opaque fragment at 13.2-14.3 ns against 8.1-9.9; 2026-12-05). The
/// held-out mix, drawn multisampled too, is predicted within 50 % as the single-sampled one is.
#[test]
fn an_msaa_calibration_predicts_a_held_out_mix_drawn_with_msaa() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let size = Size {
        width: 320,
        height: 180,
    };
    let options = Options {
        msaa: true,
        ..Options::default()
    };
    let cal = calibrate_units_with(&gpu, size, options, &[held_out_mix()])
        .context("calibrating on a multisampled target")?;
    let costs = &cal.unit_costs;
    eprint!("{}", costs.to_markdown());
    assert!(costs.prices(true) && !costs.prices(false));
    assert!(costs.fit.relative_rms_residual < 0.35, "{:?}", costs.fit);
    let m = &cal.held_out[0];
    let error = costs.predict(&m.sample.work).total_ms / m.sample.measured_ms - 1.0;
    eprintln!(
        "mix with MSAA: measured {:.1} ms, predicted {:+.1}%",
        m.sample.measured_ms,
        100.0 * error
    );
    assert!(error.abs() < 0.5, "{error}");
    check_coverage(costs, &cal.check_samples, size, 4);
    Ok(())
}
