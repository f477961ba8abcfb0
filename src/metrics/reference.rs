//! The harness's FLIP, PSNR and SSIM against independent implementations, on committed image
//! pairs (`tests/fixtures/metrics/`: identical, slightly and strongly different, fine and
//! coarse detail moved by a pixel). `make.py` there made the images and wrote
//! `expected.toml` with NVIDIA's `flip_evaluator` and scikit-image. Every value must lie
//! within a tolerance of the independent one on both sides, so a metric that drifts down
//! (a FLIP halved, an SSIM too close to 1) fails as surely as one that drifts up.
//! Checked by breaking each metric: FLIP's mean halved, PSNR plus 1 dB, SSIM's σ 1.4
//! instead of 1.5, FLIP at flip_evaluator's default 67.02 pixels a degree instead of
//! nv-flip's 67.0 (the fine-detail pair moves 1.4e-4): each fails this test.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::{flip, psnr, ssim};

// Differences measured over the six pairs (nv-flip 0.1.2 built here against flip-evaluator
// 1.7's wheel, scikit-image 0.26.0). The tolerances leave room for another compiler or
// platform and stay far below what a broken metric moves: the smallest nonzero expected FLIP
// is 0.023, the pairs' PSNRs lie dB apart.

/// FLIP mean: largest difference measured 0 (both are NVIDIA's code: bit-identical here) →
/// tolerance 1e-5, room for another compiler's floating point.
const FLIP_MEAN_TOL: f64 = 1e-5;
/// FLIP 95th percentile (the same element of the sorted error map): largest difference
/// measured 0 → tolerance 1e-5.
const FLIP_P95_TOL: f64 = 1e-5;
/// PSNR: the same formula on the same integers; largest difference measured 0 → tolerance
/// 1e-9 dB.
const PSNR_TOL: f64 = 1e-9;
/// SSIM against scikit-image on edge-padded images (the harness's clamped borders, every
/// pixel averaged): largest difference measured 3.9e-15 (`noise`) → tolerance 1e-9.
const SSIM_EDGE_TOL: f64 = 1e-9;
/// SSIM against scikit-image's plain call, which reflects at the borders and averages only
/// pixels at least 5 from them (a fifth of a 128x72 image left out): largest difference
/// measured 0.0129 (`technique`; 0.0085 `no_grass`, under 0.001 elsewhere) → tolerance 0.02.
/// Loose, but it ties the harness to the unmodified library call; `SSIM_EDGE_TOL` is the
/// tight check.
const SSIM_SKIMAGE_TOL: f64 = 0.02;

#[derive(Deserialize)]
struct Expected {
    pair: Vec<Pair>,
}

#[derive(Deserialize)]
struct Pair {
    name: String,
    a: String,
    b: String,
    size: [u32; 2],
    flip_mean: f64,
    flip_p95: f64,
    psnr: f64,
    ssim_skimage: f64,
    ssim_skimage_edge: f64,
}

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/metrics")
}

fn load(name: &str) -> image::RgbaImage {
    let path = fixtures().join(name);
    image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

/// `|ours - theirs| <= tol`, infinities equal only to themselves.
fn close(ours: f64, theirs: f64, tol: f64) -> bool {
    if ours.is_infinite() || theirs.is_infinite() {
        ours == theirs
    } else {
        (ours - theirs).abs() <= tol
    }
}

#[test]
fn metrics_match_independent_implementations() {
    let text = std::fs::read_to_string(fixtures().join("expected.toml")).unwrap();
    let expected: Expected = toml::from_str(&text).unwrap();
    assert!(expected.pair.len() >= 6, "fixture pairs missing");
    let mut failures = Vec::new();
    for p in &expected.pair {
        let (a, b) = (load(&p.a), load(&p.b));
        assert_eq!(a.dimensions(), (p.size[0], p.size[1]), "{}", p.name);
        let f = flip(&a, &b).unwrap();
        let checks = [
            ("FLIP mean", f64::from(f.mean), p.flip_mean, FLIP_MEAN_TOL),
            ("FLIP p95", f64::from(f.p95), p.flip_p95, FLIP_P95_TOL),
            ("PSNR", psnr(&a, &b).unwrap(), p.psnr, PSNR_TOL),
            (
                "SSIM (edge-padded)",
                ssim(&a, &b).unwrap(),
                p.ssim_skimage_edge,
                SSIM_EDGE_TOL,
            ),
            (
                "SSIM (skimage)",
                ssim(&a, &b).unwrap(),
                p.ssim_skimage,
                SSIM_SKIMAGE_TOL,
            ),
        ];
        for (metric, ours, theirs, tol) in checks {
            let ok = close(ours, theirs, tol);
            eprintln!(
                "{:<12} {metric:<18} ours {ours:<22} theirs {theirs:<22} diff {:.2e}{}",
                p.name,
                if ours == theirs {
                    0.0
                } else {
                    (ours - theirs).abs()
                },
                if ok { "" } else { "  FAIL" }
            );
            if !ok {
                failures.push(format!(
                    "{}: {metric} {ours} vs {theirs} (tolerance {tol})",
                    p.name
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
