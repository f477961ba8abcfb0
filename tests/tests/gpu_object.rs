//! The scene's moving object (`[object]`) on the GPU: the core draws it for every technique,
//! where its path says it is, and grass does not hide what is in front of it.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use grassbench::runner::Harness;
use grassbench::target::save_png;
use grassbench::technique::NoGrass;
use grassbench_tests::{TEST_SIZE, gpu, output_dir, render_with, scene};

#[test]
fn the_flying_object_is_drawn_where_its_path_puts_it() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let scene = scene("meadow_primitives", 0.25)?;
    let object = scene
        .config
        .object
        .clone()
        .expect("meadow_primitives has an object");
    // At 10 s the object crosses the walker's view (about 9 m ahead, 14° to the right).
    let frame = 300;
    let time = scene.time_of(frame);
    let centre = object.centre(&scene.terrain, time);
    let mut harness = Harness::new(&gpu, scene, TEST_SIZE, false)?;
    let camera = harness.camera(frame);
    let ndc = camera.view_projection().project_point3(centre);
    assert!(
        ndc.x.abs() < 0.9 && ndc.y.abs() < 0.9,
        "object off screen at {ndc}"
    );
    let (w, h) = (TEST_SIZE.width as f32, TEST_SIZE.height as f32);
    let (x, y) = (
        ((ndc.x + 1.0) * 0.5 * w) as u32,
        ((1.0 - ndc.y) * 0.5 * h) as u32,
    );
    let reddish = |img: &grassbench::image::RgbaImage| {
        let p = img.get_pixel(x, y).0;
        f32::from(p[0]) > 1.5 * f32::from(p[1]) && f32::from(p[0]) > 1.5 * f32::from(p[2])
    };
    let background = render_with(&mut harness, &mut NoGrass, frame)?;
    assert!(reddish(&background), "no object at pixel ({x}, {y})");
    // Its centre is 0.9 m up, above the tallest blade: nothing hides it, whatever the
    // technique.
    for id in ["reference", "zhang", "perbet"] {
        let entry = grassbench_cli::registry::find(id)?;
        let mut t = harness.create(entry, &toml::Table::new())?;
        let image = render_with(&mut harness, t.as_mut(), frame)?;
        save_png(&image, &output_dir().join(format!("object-{id}.png")))?;
        assert!(reddish(&image), "{id}: object hidden at pixel ({x}, {y})");
    }
    // A moment later it has moved on.
    let later = render_with(&mut harness, &mut NoGrass, frame + 90)?;
    assert!(
        !reddish(&later),
        "object still at pixel ({x}, {y}) 3 s later"
    );
    Ok(())
}
