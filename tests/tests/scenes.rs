//! Built-in scenes load, camera paths stay over the terrain, and recorded versions are right.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use grassbench::glam::{Vec2, Vec3};
use grassbench_tests::repo_root;

#[test]
fn built_in_scenes_load_and_cameras_stay_above_ground() {
    for name in grassbench_cli::scenes::names() {
        let scene = grassbench_cli::scenes::load(name).unwrap();
        let size = scene.resolution();
        for frame in (0..600).step_by(37) {
            let cam = scene.camera_at(frame, size);
            let ground = scene.terrain.height_at(Vec2::new(cam.eye.x, cam.eye.z));
            assert!(
                cam.eye.y > ground + 0.5,
                "{name} frame {frame}: eye {} under ground {ground}",
                cam.eye
            );
            assert!(cam.forward.is_normalized());
        }
        let blades = scene.blades.all_blades(&scene.terrain).len();
        assert!(blades > 10_000, "{name}: only {blades} blades");
    }
}

#[test]
fn primitives_scene_loads_and_drives_a_finite_wind() {
    let scene = grassbench_cli::scenes::load("meadow_primitives").unwrap();
    let wind = scene.wind().unwrap();
    assert_eq!(wind.name(), "primitives");
    assert!(wind.is_stateless());
    let mut moving = 0;
    for k in 0..400 {
        let p = Vec3::new(
            (k % 20) as f32 * 4.0 - 40.0,
            1.0,
            (k / 20) as f32 * 4.0 - 40.0,
        );
        let v = wind.velocity(p, k as f32 * 0.1);
        assert!(
            v.is_finite() && v.y == 0.0 && v.length() <= 5.0 + 1e-3,
            "{v}"
        );
        moving += usize::from(v.length() > 0.1);
    }
    assert!(moving > 100, "{moving} of 400 points in the wind");
}

#[test]
fn the_blast_follows_the_scenes_flying_object() {
    let scene = grassbench_cli::scenes::load("meadow_primitives").unwrap();
    let object = scene
        .config
        .object
        .clone()
        .expect("meadow_primitives has an object");
    let wind = scene.wind().unwrap();
    let set = (wind.as_ref() as &dyn std::any::Any)
        .downcast_ref::<grassbench::wind::PrimitiveSet>()
        .expect("a primitives wind");
    for time in [0.0, 7.5, 20.0, 31.0] {
        // Next to the object the blast (highest priority) bends grass radially away from it.
        let under = object.ground_position(time);
        for offset in [
            Vec2::new(1.5, 0.0),
            Vec2::new(0.0, -2.0),
            Vec2::new(-1.0, 1.0),
        ] {
            let s = set.sample(under + offset, time);
            assert!(
                s.direction.dot(offset.normalize()) > 0.8 && s.posture > 0.3,
                "t {time}, offset {offset}: {s:?}"
            );
        }
    }
    // Without an object to follow, the scene is refused with the key named.
    let mut config = scene.config.clone();
    config.object = None;
    let e = grassbench::Scene::from_config(config, scene.base_dir.clone())
        .and_then(|s| s.wind().map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(e.contains("follow_object"), "{e}");
}

#[test]
fn unknown_scene_lists_the_valid_ones() {
    let e = grassbench_cli::scenes::load("medow")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("medow") && e.contains("meadow") && e.contains("football_field"),
        "{e}"
    );
}

#[test]
fn malformed_scene_file_names_file_and_line() {
    let dir = std::env::temp_dir().join(format!("grassbench-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.toml");
    std::fs::write(&path, "name = \"bad\"\n[terrain]\nsize = [10.0, 10.0]\nsizee = 3\n[camera.path]\nkind = \"fixed\"\neye = [0.0, 2.0, 0.0]\nlook_at = [1.0, 0.0, 0.0]\n").unwrap();
    let e = grassbench::Scene::load(&path).unwrap_err().to_string();
    assert!(
        e.contains("bad.toml") && e.contains("sizee") && e.contains("line 4"),
        "{e}"
    );
    std::fs::write(&path, "name = \"bad\"\n[terrain]\nsize = [10.0, -1.0]\n[camera.path]\nkind = \"fixed\"\neye = [0.0, 2.0, 0.0]\nlook_at = [1.0, 0.0, 0.0]\n").unwrap();
    let e = grassbench::Scene::load(&path).unwrap_err().to_string();
    assert!(e.contains("terrain.size[1]"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn recorded_wgpu_version_matches_the_lock_file() {
    let lock = std::fs::read_to_string(repo_root().join("Cargo.lock")).unwrap();
    let needle = format!(
        "name = \"wgpu\"\nversion = \"{}\"",
        grassbench::runner::WGPU_VERSION
    );
    assert!(
        lock.contains(&needle),
        "Cargo.lock has a different wgpu than {}",
        grassbench::runner::WGPU_VERSION
    );
}
