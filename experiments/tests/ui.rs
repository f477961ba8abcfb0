//! The UI in scripted mode under a virtual X display: four panes play a few frames, the window
//! is saved, and every pane of the saved window shows a rendered scene; and the wipe view,
//! driven by mouse and key events, while a slow pane renders and the window keeps its pace.

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

/// `grassbench ui` under Xvfb at 1280x800, writing into a fresh folder named after `name`.
fn xvfb_ui(name: &str) -> (std::path::PathBuf, Command) {
    let xvfb = Command::new("sh")
        .args(["-c", "command -v xvfb-run"])
        .output()
        .unwrap();
    assert!(
        xvfb.status.success(),
        "xvfb-run is missing: install package `xvfb` (`make setup` does)"
    );
    let dir = std::env::temp_dir().join(format!("grassbench-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut command = Command::new("xvfb-run");
    command.args([
        "-a",
        "-s",
        "-screen 0 1280x800x24",
        env!("CARGO_BIN_EXE_grassbench"),
        "ui",
    ]);
    (dir, command)
}

/// PSNR of the window's crop `rect` (shrunk to `band`'s size) against `band` of a pane image,
/// both averaged over 4 x 4 blocks (blades are thinner than the rescaling's error).
fn psnr_of(
    window: &image::RgbaImage,
    rect: [u32; 4],
    pane: &image::RgbaImage,
    band: [u32; 4],
) -> f64 {
    let want = crop(pane, band);
    let shown = image::imageops::resize(
        &crop(window, rect),
        want.width(),
        want.height(),
        image::imageops::FilterType::Triangle,
    );
    let blocks = |i: &image::RgbaImage| grassbench::metrics::downsample(i, 4);
    grassbench::metrics::psnr(&blocks(&shown), &blocks(&want)).unwrap()
}

/// One window at a time: the wipe test measures the window's pace, which a second window
/// rendering beside it on the same cores would slow.
static XVFB: std::sync::Mutex<()> = std::sync::Mutex::new(());

#[test]
fn scripted_ui_shows_a_scene_in_every_pane() {
    let _one = XVFB.lock().unwrap_or_else(|e| e.into_inner());
    let (dir, mut command) = xvfb_ui("ui");
    let shot = dir.join("window.png");
    let out = command
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
    // The four pictures are one 2 x 2 block, a few pixels apart: no band of empty window
    // between the rows (the grid that fits 16:9 pictures largest in the window).
    let [r1, r2, r3, _] = [
        layout.rects[0],
        layout.rects[1],
        layout.rects[2],
        layout.rects[3],
    ];
    assert!(
        i64::from(r2[0]) - i64::from(r1[0] + r1[2]) < 10
            && i64::from(r3[1]) - i64::from(r1[1] + r1[3]) < 10,
        "pictures apart: {:?}",
        layout.rects
    );
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

/// The wipe view while a slow pane renders: pane 1 is the reference on the meadow (about
/// half a second a frame here), pane 2 zhang; the script drags the divider to 0.3 and presses
/// the flip key, as the mouse and keyboard would, while the panes render on their thread.
#[test]
fn scripted_wipe_answers_input_while_a_slow_pane_renders() {
    let _one = XVFB.lock().unwrap_or_else(|e| e.into_inner());
    let (dir, mut command) = xvfb_ui("wipe");
    let shot = dir.join("wipe.png");
    let out = command
        .args([
            "--scene",
            "meadow",
            "--panes",
            "2",
            "--techniques",
            "reference,zhang",
        ])
        .args(["--size", "320x180", "--frames", "3"])
        .args(["--screenshot", shot.to_str().unwrap()])
        .args(["--wipe", "0.3", "--flip"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "ui failed: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let window = image::open(&shot).unwrap().to_rgba8();
    let layout: Layout =
        toml::from_str(&std::fs::read_to_string(Layout::path_for(&shot)).unwrap()).unwrap();
    assert_eq!(layout.frame, 3);

    // The drag moved the divider to 0.3, and the key swapped the sides: zhang on the left.
    let wipe = layout.wipe.clone().expect("the wipe view is on");
    assert!((wipe.split - 0.3).abs() < 0.01, "divider at {}", wipe.split);
    assert!(wipe.flipped);
    assert_eq!((wipe.left, wipe.right), (1, 0));
    // Each side of the divider shows its pane's picture: left of it pane 2's, right of it
    // pane 1's (a band clear of the figures, the plot and the divider).
    let panes: Vec<image::RgbaImage> = (1..=2)
        .map(|k| {
            image::open(shot.with_extension(format!("pane{k}.png")))
                .unwrap()
                .to_rgba8()
        })
        .collect();
    let [x, y, w, h] = wipe.rect;
    let (pw, ph) = panes[0].dimensions();
    let split = (wipe.split * w as f32) as u32;
    let band_y = (y + h * 4 / 10, h / 4);
    let left = [x, band_y.0, split - 8, band_y.1];
    let right = [x + split + 8, band_y.0, w - split - 8, band_y.1];
    let in_pane = |[rx, ry, rw, rh]: [u32; 4]| {
        [
            (rx - x) * pw / w,
            (ry - y) * ph / h,
            rw * pw / w,
            rh * ph / h,
        ]
    };
    let (l_own, l_other) = (
        psnr_of(&window, left, &panes[1], in_pane(left)),
        psnr_of(&window, left, &panes[0], in_pane(left)),
    );
    let (r_own, r_other) = (
        psnr_of(&window, right, &panes[0], in_pane(right)),
        psnr_of(&window, right, &panes[1], in_pane(right)),
    );
    // Measured: left 37.9 dB against its own pane, 30.1 against the other; right 36.3 / 31.8
    // (seen over 4 x 4 blocks, the two techniques' meadows are alike; rendering is
    // deterministic, so these repeat).
    assert!(
        l_own > 33.0 && l_own > l_other + 3.0 && r_own > 33.0 && r_own > r_other + 3.0,
        "left {l_own:.1} dB (other {l_other:.1}), right {r_own:.1} dB (other {r_other:.1})"
    );

    // The window kept its pace while the reference took its time: its frames are answered
    // well within one of the slow pane's frames.
    let reference = &layout.pane_gpu_wall_ms[0];
    let pane_ms = percentile(reference, 0.5);
    // The first window frames start the window and the worker's device: not in the measure.
    let frames = &layout.window_frame_ms[5.min(layout.window_frame_ms.len())..];
    let (p95, slowest) = (percentile(frames, 0.95), percentile(frames, 1.0));
    eprintln!(
        "reference pane: {pane_ms:.0} ms a frame (median of {}); window: {} frames, median \
         {:.0} ms, 95th percentile {p95:.0} ms, slowest {slowest:.0} ms",
        reference.len(),
        frames.len(),
        percentile(frames, 0.5)
    );
    // On this 2-core machine the reference takes 0.5 s a frame and more; where it is much
    // faster (many cores) there is no slow pane to measure the window against.
    if pane_ms < 400.0 {
        eprintln!("the reference pane renders too fast here ({pane_ms:.0} ms): pace not checked");
    } else {
        // Measured here, on 2 cores shared with builds and a sweep: the reference 1.7-3.9 s a
        // frame; the window's frames 160-380 ms, medians 135-194 ms, 95th percentiles 237-379
        // ms, slowest 194-388 ms (once 1.2 s against a reference at 3.3 s). With nothing else
        // running, at `ea625af` (the reference's vertex shader 1.6 times as fast as before
        // `59a14de`): the reference 524 ms, the window's 95th percentile 111 ms, slowest 134. Before the panes
        // had a thread of their own, every window frame lasted as long as the panes' frames
        // together.
        assert!(
            p95 < pane_ms / 2.0 && slowest < pane_ms && frames.len() > 10,
            "the window waited for the panes: 95th percentile {p95:.0} ms, slowest \
             {slowest:.0} ms against the reference's {pane_ms:.0} ms, {} frames",
            frames.len()
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The `q` quantile of `values` (nearest rank; 1 is the largest), NaN when empty.
fn percentile(values: &[f64], q: f64) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let rank = ((v.len() as f64 - 1.0) * q).round() as usize;
    v.get(rank).copied().unwrap_or(f64::NAN)
}
