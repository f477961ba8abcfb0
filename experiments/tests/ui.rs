//! The UI in scripted mode under a virtual X display: four panes play a few frames, the window
//! is saved, and every pane of the saved window shows a rendered scene.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;

use grassbench_cli::ui::Layout;

/// Standard deviation of the luma in a rectangle of the screenshot.
fn luma_stats(img: &image::RgbaImage, [x, y, w, h]: [u32; 4]) -> (f64, f64) {
    let mut values = Vec::new();
    for yy in y..(y + h).min(img.height()) {
        for xx in x..(x + w).min(img.width()) {
            let p = img.get_pixel(xx, yy).0;
            values.push(
                0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]),
            );
        }
    }
    let n = values.len().max(1) as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    (mean, var.sqrt())
}

fn crop(img: &image::RgbaImage, [x, y, w, h]: [u32; 4]) -> image::RgbaImage {
    image::imageops::crop_imm(img, x, y, w, h).to_image()
}

#[test]
fn scripted_ui_shows_a_scene_in_every_pane() {
    let xvfb = Command::new("sh")
        .args(["-c", "command -v xvfb-run"])
        .output()
        .unwrap();
    assert!(
        xvfb.status.success(),
        "xvfb-run is missing: install package `xvfb` (`make setup` does)"
    );
    let dir = std::env::temp_dir().join(format!("grassbench-ui-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.join("window.png");
    let out = Command::new("xvfb-run")
        .args([
            "-a",
            "-s",
            "-screen 0 1280x800x24",
            env!("CARGO_BIN_EXE_grassbench"),
            "ui",
        ])
        .args([
            "--scene",
            "football_field",
            "--panes",
            "4",
            "--techniques",
            "all",
            "--size",
            "320x180",
        ])
        .args(["--frames", "2", "--screenshot", shot.to_str().unwrap()])
        // As a click with the spawn tool on the middle of pane 1 would (Perbet Sec. 3.3).
        .args(["--spawn", "whirlwind"])
        // As the sun sliders would (lights move at run time, issue 9).
        .args(["--sun", "-60,25"])
        // As the point-light controls would (boulanger Sec. 3.3's light, every shader's).
        .args(["--point-light", "4,3,-2"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "ui failed: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");

    let window = image::open(&shot).unwrap().to_rgba8();
    let layout: Layout =
        toml::from_str(&std::fs::read_to_string(Layout::path_for(&shot)).unwrap()).unwrap();
    assert_eq!(layout.rects.len(), 4);
    assert_eq!(layout.frame, 2);
    // The spawned whirlwind joined the wind, which switched to Perbet's primitives.
    let wind = &layout.wind;
    assert_eq!(
        wind.get("model").and_then(|v| v.as_str()),
        Some("primitives"),
        "{wind:?}"
    );
    let kinds: Vec<&str> = wind
        .get("primitives")
        .and_then(|v| v.as_array())
        .map(|a| a.iter().filter_map(|p| p.get("kind")?.as_str()).collect())
        .unwrap_or_default();
    assert_eq!(kinds.last(), Some(&"whirlwind"), "{wind:?}");
    // The panes' scenes have the sun where `--sun` put it.
    let sun = layout.sun.expect("the layout records the sun");
    let want = grassbench_cli::ui::sun_direction([-60.0, 25.0]);
    assert!(
        sun.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-5),
        "{sun:?} against {want:?}"
    );
    assert_eq!(layout.point_light, Some([4.0, 3.0, -2.0]));
    // The pane images the UI displayed, as rendered (the window shows them rescaled).
    let panes: Vec<image::RgbaImage> = (1..=4)
        .map(|k| {
            image::open(shot.with_extension(format!("pane{k}.png")))
                .unwrap()
                .to_rgba8()
        })
        .collect();
    for (k, rect) in layout.rects.iter().enumerate() {
        // A rendered scene has sky above and ground below: clearly varied luma. A blank or
        // single-colour pane has a deviation near 0 (the window background is uniform grey).
        let (mean, dev) = luma_stats(&window, *rect);
        assert!(
            dev > 15.0 && mean > 20.0,
            "pane {} looks blank: mean {mean:.1}, deviation {dev:.1}",
            k + 1
        );
        // Sky on top: the top rows are brighter and bluer than the bottom rows.
        let [x, y, w, h] = *rect;
        let top = luma_stats(&window, [x, y + h / 10, w, h / 10]).0;
        let bottom = luma_stats(&window, [x, y + h * 8 / 10, w, h / 10]).0;
        assert!(
            top > bottom,
            "pane {}: no sky above the ground ({top:.1} vs {bottom:.1})",
            k + 1
        );
    }
    // Panes showing the same technique at the same frame are the same picture; panes showing
    // different techniques are not. And the window shows what was rendered: each pane's crop,
    // shrunk to the rendered size, is close to the rendered image.
    for (k, rect) in layout.rects.iter().enumerate() {
        let shown = image::imageops::resize(
            &crop(&window, *rect),
            panes[k].width(),
            panes[k].height(),
            image::imageops::FilterType::Triangle,
        );
        // The band between the figures (top) and the plot (bottom) has no overlay.
        let (w, h) = panes[k].dimensions();
        let band = |i: &image::RgbaImage| {
            grassbench::metrics::downsample(&crop(i, [0, h * 3 / 10, w, h * 2 / 5]), 4)
        };
        let psnr = grassbench::metrics::psnr(&band(&shown), &band(&panes[k])).unwrap();

        // Measured 40.6 dB (only the rescaling differs); a pane showing another frame, another
        // scene or a blank scores far lower (16 dB with the overlay text alone included).
        assert!(
            psnr > 30.0,
            "pane {} on screen differs from its render ({psnr:.1} dB)",
            k + 1
        );
    }
    for a in 0..4 {
        for b in a + 1..4 {
            let same = layout.techniques[a] == layout.techniques[b];
            // Rendering is deterministic: the same technique at the same frame gives the same
            // bytes, and two techniques never do (their pictures may still be close: seen from
            // the stands, a lawn is a lawn however it is drawn).
            let identical = panes[a].as_raw() == panes[b].as_raw();
            assert_eq!(
                same,
                identical,
                "panes {} ({}) and {} ({}): same technique {same}, identical pictures {identical}",
                a + 1,
                layout.techniques[a],
                b + 1,
                layout.techniques[b]
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
