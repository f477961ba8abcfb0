//! Every shader function an essay calls a mirror of Rust code, checked against its Rust twin on
//! the GPU (issue 19): a test kernel ([`grassbench_tests::twin`]) appended to the real shader
//! text calls the WGSL function over a few thousand seeded inputs, edge cases listed among
//! them, and the results are compared with the Rust function within a stated tolerance. The
//! Rust twins are tested against the papers' equations in their crates.
//!
//! Covered: the prelude's `terrain_height`, `terrain_density`, `terrain_normal` and `wind_at`
//! (against `Terrain` and the wind field the texture was baked from); zhang's `bezier` and
//! `bezier_tangent`; bakay's `tilt` and `shell_segment`, and `cs_bend` itself; boulanger's LOD
//! weights and opacities (Eq. 1-5) and the patch orientation map (Eq. 6-7); perbet's posture
//! lookup, segment directions and the morph onto the animated strips; the prelude's
//! `hash_u32`; the background's `ground_vertex` (the ground's chunks); jahrmann's `simulate` (property test over random winds and spheres), `cull`
//! (property test against the core's CPU frustum) and its whole compute pass `cs_simulate`.
//!
//! Tolerances: both sides compute in f32, mostly the same operations in the same order; what
//! differs is the GPU's own rounding (fused multiply-adds, `sin`/`cos`/`pow` within a few ulps,
//! division within 2.5 ulps on Vulkan). Each limit says what it was measured at on lavapipe.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use grassbench::glam::{IVec2, Vec2, Vec3, Vec4};
use grassbench::rng::Rng;
use grassbench::scene::SceneGpu;
use grassbench::shaders::{PRELUDE, compose};
use grassbench::terrain::GroundVertex;
use grassbench::wind::{Calm, WindField};
use grassbench::{FrameInputs, GpuContext, Scene, bytemuck};
use grassbench_tests::twin::{self, Bindings, Resource, Worst};
use grassbench_tests::{TEST_SIZE, gpu, scene};

/// The scene's bind group 0 with `wind` baked into its wind texture at `time`, and the frame
/// globals of a frame at `time`.
fn scene_gpu(
    gpu: &GpuContext,
    scene: &Scene,
    wind: &dyn WindField,
    time: f32,
) -> anyhow::Result<SceneGpu> {
    let mut scene_gpu = SceneGpu::new(gpu, scene, 1)?;
    scene_gpu.bake_wind(wind, time);
    let inputs = FrameInputs {
        frame: 0,
        time,
        dt: scene.dt(),
        camera: scene.camera_at(0, TEST_SIZE),
        scene,
        wind,
        size: TEST_SIZE,
        debug_view: 0,
    };
    scene_gpu.upload(gpu, &inputs);
    Ok(scene_gpu)
}

/// A wind affine in (x, z) (and the same at every height): the bilinear lookup of a texture
/// baked from it gives it back exactly, between texels too, up to rounding.
struct Affine {
    base: Vec3,
    along_x: Vec3,
    along_z: Vec3,
}

impl WindField for Affine {
    fn name(&self) -> &'static str {
        "affine"
    }
    fn advance(&mut self, _time: f32, _dt: f32) {}
    fn velocity(&self, p: Vec3, _time: f32) -> Vec3 {
        self.base + self.along_x * p.x + self.along_z * p.z
    }
}

/// An affine wind that is zero at (5, -3) and reaches about 7 m/s over the meadow.
fn affine_wind() -> Affine {
    let along_x = Vec3::new(0.09, 0.02, -0.04);
    let along_z = Vec3::new(0.05, -0.01, 0.07);
    Affine {
        base: -(along_x * 5.0 - along_z * 3.0),
        along_x,
        along_z,
    }
}

fn v4(v: Vec3, w: f32) -> [f32; 4] {
    v.extend(w).to_array()
}

/// Ground points (x, z) over a terrain of `size` centred on the origin: its corners, edges
/// and centre, sample nodes and the points half-way between them (`spacing` apart), points
/// outside it (the lookups clamp), then seeded random points over and a little past it.
fn ground_points(size: Vec2, spacing: Vec2, count: usize, seed: u64) -> Vec<Vec2> {
    let h = size * 0.5;
    let mut points = vec![
        Vec2::ZERO,
        -h,
        h,
        Vec2::new(-h.x, h.y),
        Vec2::new(h.x, -h.y),
        Vec2::new(0.0, h.y),
        Vec2::new(-h.x, 0.0),
        Vec2::new(h.x * 1.5, 0.0),
        Vec2::new(0.0, -h.y * 2.5),
        Vec2::new(-h.x - 7.0, h.y + 3.0),
    ];
    let cells = (size / spacing).round().as_uvec2() + 1;
    for k in 0..40 {
        let node = -h + spacing * Vec2::new((k * 7 % cells.x) as f32, (k * 13 % cells.y) as f32);
        points.push(node.min(h));
        points.push((node + spacing * 0.5).min(h));
    }
    let mut rng = Rng::new(seed);
    while points.len() < count {
        points.push(Vec2::new(
            rng.range(-h.x * 1.1, h.x * 1.1),
            rng.range(-h.y * 1.1, h.y * 1.1),
        ));
    }
    points
}

/// The prelude's terrain lookups are `Terrain`'s bilinear sampling, and `wind_at` gives back
/// the wind the texture was baked from: exactly for an affine wind (which bilinear
/// interpolation reproduces), at the texels for the scene's gusty breeze, and zero in calm
/// air.
#[test]
fn prelude_terrain_and_wind_lookups_are_the_cpus() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let meadow = scene("meadow", 0.05)?;
    let terrain = &meadow.terrain;
    let points = ground_points(terrain.size(), terrain.sample_spacing(), 3000, 19);
    let inputs: Vec<[[f32; 4]; 1]> = points.iter().map(|p| [[p.x, p.y, 0.0, 0.0]]).collect();
    let body = "    let xz = x.v[0].xy;
    y.v[0] = vec4(terrain_height(xz), terrain_density(xz), 0.0, 0.0);
    y.v[1] = vec4(terrain_normal(xz), 0.0);
    y.v[2] = vec4(wind_at(xz), 0.0);";
    let clamp = |p: Vec2| p.clamp(terrain.min_corner(), terrain.min_corner() + terrain.size());

    let wind = affine_wind();
    let scene_gpu = scene_gpu(&gpu, &meadow, &wind, 0.0)?;
    let out: Vec<[[f32; 4]; 3]> = twin::map(
        &gpu,
        PRELUDE,
        body,
        Bindings::new().scene(&scene_gpu),
        &inputs,
    )?;
    let (mut height, mut density, mut normal, mut affine) = Default::default();
    for (p, o) in points.iter().zip(&out) {
        let h = terrain.height_at(*p);
        Worst::record(&mut height, (o[0][0] - h).abs(), || {
            format!("{p}: GPU {} CPU {h}", o[0][0])
        });
        let d = terrain.density_at(*p);
        Worst::record(&mut density, (o[0][1] - d).abs(), || {
            format!("{p}: GPU {} CPU {d}", o[0][1])
        });
        let n = terrain.normal_at(*p);
        let gn = Vec3::from_slice(&o[1]);
        Worst::record(&mut normal, gn.distance(n), || {
            format!("{p}: GPU {gn} CPU {n}")
        });
        let c = clamp(*p);
        let w = wind.velocity(Vec3::new(c.x, 0.0, c.y), 0.0);
        let gw = Vec3::from_slice(&o[2]);
        Worst::record(&mut affine, gw.distance(w), || {
            format!("{p}: GPU {gw} field {w}")
        });
    }
    // Measured on lavapipe: 0 for the height and the density (the same f32 bilinear blend on
    // both sides), 2.7e-7 for the unit normal, 9.6e-7 m/s for the affine wind (up to 7 m/s).
    // The limits allow about ten ulps at these magnitudes (heights up to 4 m: an ulp is
    // 4.8e-7) for a GPU that fuses the blend's multiply-adds; a bilinear blend with two
    // neighbours swapped is off by 0.16 m, `wind_at` with f.x and f.y swapped by 0.12 m/s.
    height.check("terrain_height", 5e-6)?;
    density.check("terrain_density", 1e-6)?;
    normal.check("terrain_normal", 2e-6)?;
    affine.check("wind_at (affine wind)", 1e-5)?;

    // The scene's breeze, at the texels the texture was baked at (about one a metre).
    let breeze = meadow.wind()?;
    let time = 2.7;
    let scene_gpu = self::scene_gpu(&gpu, &meadow, breeze.as_ref(), time)?;
    let (nx, nz) = scene_gpu.wind.resolution();
    let nodes: Vec<Vec2> = (0..nz)
        .flat_map(|j| (0..nx).map(move |i| (i, j)))
        .map(|(i, j)| {
            let uv = Vec2::new(i as f32 / (nx - 1) as f32, j as f32 / (nz - 1) as f32);
            terrain.min_corner() + uv * terrain.size()
        })
        .collect();
    let inputs: Vec<[[f32; 4]; 1]> = nodes.iter().map(|p| [[p.x, p.y, 0.0, 0.0]]).collect();
    let out: Vec<[[f32; 4]; 3]> = twin::map(
        &gpu,
        PRELUDE,
        body,
        Bindings::new().scene(&scene_gpu),
        &inputs,
    )?;
    let mut at_texels = Worst::default();
    for (p, o) in nodes.iter().zip(&out) {
        let at = terrain.point_at(*p) + Vec3::Y * grassbench::wind::SAMPLE_HEIGHT;
        let w = breeze.velocity(at, time);
        let gw = Vec3::from_slice(&o[2]);
        at_texels.record(gw.distance(w), || format!("{p}: GPU {gw} field {w}"));
    }
    // Measured 0 (every node's uv lands on its texel's centre); the limit allows a uv an ulp
    // off it (6e-8 of the 80 m terrain, 5e-6 m, where the breeze changes by under 4 m/s a
    // metre).
    at_texels.check("wind_at (breeze at its texels)", 2e-5)?;

    let scene_gpu = self::scene_gpu(&gpu, &meadow, &Calm, 0.0)?;
    let out: Vec<[[f32; 4]; 3]> = twin::map(
        &gpu,
        PRELUDE,
        body,
        Bindings::new().scene(&scene_gpu),
        &inputs[..500],
    )?;
    assert!(out.iter().all(|o| o[2] == [0.0; 4]), "calm air blows");
    Ok(())
}

/// Zhang's backbone (Eq. 5) and its tangent in the vertex shader are `blade::bezier` and
/// `blade::bezier_tangent`, at the shader's own parameters `i/(n−1)` and anywhere between.
#[test]
fn zhang_bezier_is_blade_bezier() -> anyhow::Result<()> {
    use grassbench_zhang::blade::{BladeState, bezier, bezier_tangent};
    let gpu = gpu()?;
    let mut rng = Rng::new(6);
    let mut curves: Vec<[Vec3; 4]> = Vec::new();
    // Animated blades, resting and blown over, far from the origin too.
    for k in 0..40 {
        let root = Vec3::new(
            rng.range(-300.0, 300.0),
            rng.range(-2.0, 30.0),
            rng.range(-300.0, 300.0),
        );
        let mut b = BladeState::new(
            root,
            rng.range(0.05, 1.5),
            0.3,
            rng.range(0.0, 6.3),
            rng.range(0.0, 1.2),
            1.0,
        );
        let wind = Vec3::new(
            rng.range(-9.0, 9.0),
            rng.range(-3.0, 1.0),
            rng.range(-9.0, 9.0),
        );
        let k_dyn = grassbench_zhang::blade::Dynamics::new(1.0 / 30.0, 5.0, 40.0, 4.0);
        for _ in 0..k % 25 {
            b.step(&[wind; 3], &k_dyn, root.y);
        }
        curves.push(b.pos);
    }
    // Degenerate curves: all points equal, a straight line, a cusp (P1 = P2 far out).
    curves.push([Vec3::splat(2.0); 4]);
    curves.push([Vec3::ZERO, Vec3::X, Vec3::X * 2.0, Vec3::X * 3.0]);
    curves.push([Vec3::ZERO, Vec3::Y * 5.0, Vec3::Y * 5.0, Vec3::X]);
    while curves.len() < 200 {
        curves.push([(); 4].map(|_| {
            Vec3::new(
                rng.range(-20.0, 20.0),
                rng.range(-20.0, 20.0),
                rng.range(-20.0, 20.0),
            )
        }));
    }
    let mut inputs = Vec::new();
    for (c, p) in curves.iter().enumerate() {
        let n = 2 + c % 9;
        let mut ts: Vec<f32> = (0..n).map(|i| i as f32 / (n - 1) as f32).collect();
        ts.extend([0.5, 1e-4, 0.9999]);
        ts.extend((0..6).map(|_| rng.next_f32()));
        for t in ts {
            inputs.push([v4(p[0], t), v4(p[1], 0.0), v4(p[2], 0.0), v4(p[3], 0.0)]);
        }
    }
    let body = "    let t = x.v[0].w;
    y.v[0] = vec4(bezier(x.v[0].xyz, x.v[1].xyz, x.v[2].xyz, x.v[3].xyz, t), 0.0);
    y.v[1] = vec4(bezier_tangent(x.v[0].xyz, x.v[1].xyz, x.v[2].xyz, x.v[3].xyz, t), 0.0);";
    let out: Vec<[[f32; 4]; 2]> = twin::map(
        &gpu,
        &compose(grassbench_zhang::SHADER),
        body,
        Bindings::new(),
        &inputs,
    )?;
    let (mut point, mut tangent) = (Worst::default(), Worst::default());
    for (x, o) in inputs.iter().zip(&out) {
        let p = [0, 1, 2, 3].map(|k| Vec3::from_slice(&x[k]));
        let t = x[0][3];
        let scale = p.iter().map(|q| q.abs().max_element()).fold(1.0, f32::max);
        let (cpu, gpu_p) = (bezier(&p, t), Vec3::from_slice(&o[0]));
        point.record(cpu.distance(gpu_p) / scale, || {
            format!("t {t} {p:?}: GPU {gpu_p} CPU {cpu}")
        });
        let (cpu, gpu_t) = (bezier_tangent(&p, t), Vec3::from_slice(&o[1]));
        tangent.record(cpu.distance(gpu_t) / scale, || {
            format!("t {t} {p:?}: GPU {gpu_t} CPU {cpu}")
        });
    }
    // Relative to the largest coordinate (up to 300 m): measured 0 and 0 on lavapipe (the
    // same operations in the same order, unfused); the limits allow 16 and 32 ulps of fused
    // multiply-adds elsewhere. P1 and P2 swapped in the shader is off by 0.74 of the scale.
    point.check("zhang bezier", 2e-6)?;
    tangent.check("zhang bezier_tangent", 4e-6)?;
    Ok(())
}

/// Bakay's bend: the shader's `tilt` and `shell_segment` are `bend::tilt` and
/// `bend::segment`, for any number of shells, stiffness and intensity.
#[test]
fn bakay_tilt_and_segment_are_bend_tilt_and_segment() -> anyhow::Result<()> {
    use grassbench_bakay::bend;
    let gpu = gpu()?;
    let meadow = scene("meadow", 0.05)?;
    let shader = compose(grassbench_bakay::SHADER);
    let mut rng = Rng::new(2);
    let (mut tilt, mut segment) = (Worst::default(), Worst::default());
    // (shells, stiffness): one shell, the default, many; limp, linear, stiff.
    for (shells, stiffness) in [
        (1, 1.0),
        (16, 1.0),
        (16, 0.1),
        (33, 3.0),
        (65, 8.0),
        (128, 0.6),
    ] {
        let params = grassbench_bakay::Params {
            shells,
            stiffness,
            max_intensity: 1.5,
            ..Default::default()
        };
        let uniform = grassbench_bakay::uniform(&params, &meadow, (1, 1));
        let spacing = uniform.shape[0];
        let mut inputs = Vec::new();
        for k in 0..shells {
            let mut intensities = vec![0.0, 1.0, -1.0, 1.5, -1.5, 1e-6];
            intensities.extend((0..8).map(|_| rng.range(-1.5, 1.5)));
            for i in intensities {
                inputs.push([[k as f32, i, 0.0, 0.0]]);
            }
        }
        let body = "    let k = u32(x.v[0].x);
    y.v[0] = vec4(shell_segment(k, x.v[0].y), tilt(k, x.v[0].y), 0.0);";
        let out: Vec<[[f32; 4]; 1]> = twin::map(
            &gpu,
            &shader,
            body,
            Bindings::new()
                .constant("SHELLS", f64::from(shells))
                .uniform(1, 0, &uniform),
            &inputs,
        )?;
        for (x, o) in inputs.iter().zip(&out) {
            let (k, i) = (x[0][0] as u32, x[0][1]);
            let a = bend::tilt(k, shells, i, stiffness);
            tilt.record((o[0][2] - a).abs(), || {
                format!(
                    "N {shells} p {stiffness} k {k} I {i}: GPU {} CPU {a}",
                    o[0][2]
                )
            });
            let (n, w) = bend::segment(k, shells, spacing, i, stiffness);
            let e = (o[0][0] - n).hypot(o[0][1] - w) / spacing;
            segment.record(e, || {
                format!(
                    "N {shells} p {stiffness} k {k} I {i}: GPU {:?} CPU {:?}",
                    &o[0][..2],
                    (n, w)
                )
            });
        }
    }
    // Radians, up to 3π/4 at |I| = 1.5: measured 7.2e-7 (`pow` within a few ulps, at N 65,
    // p 8); relative to the segment length 7.4e-7; limits 2.7x above. A segment whose `sin`
    // takes the next shell's tilt (the paper's misprinted index) is off by a whole S.
    tilt.check("bakay tilt", 2e-6)?;
    segment.check("bakay shell_segment", 2e-6)?;
    Ok(())
}

/// Bakay's level of detail: the shader's `level_shell` (an instance index to the shell drawn
/// and the lowest shell it stands for) is `lod::ShellLod::shell`, at every level and instance
/// of several shell counts, and the instance stride is `lod::LEVEL_INSTANCES`.
#[test]
fn bakay_level_shell_is_shell_lod_shell() -> anyhow::Result<()> {
    use grassbench_bakay::lod::{LEVEL_INSTANCES, ShellLod};
    let gpu = gpu()?;
    let meadow = scene("meadow", 0.05)?;
    let shader = compose(grassbench_bakay::SHADER);
    let mut wrong = Vec::new();
    for shells in [1, 5, 16, 17, 64, 128] {
        let params = grassbench_bakay::Params {
            shells,
            ..Default::default()
        };
        let uniform = grassbench_bakay::uniform(&params, &meadow, (1, 1));
        let lod = ShellLod {
            shells,
            height: 1.0,
            pixels: 1.0,
        };
        let mut inputs = Vec::new();
        for level in 0..8 {
            for i in 0..lod.shells_at(level) {
                inputs.push([[(level * LEVEL_INSTANCES + i) as f32, 0.0, 0.0, 0.0]]);
            }
        }
        let body = "    let s = level_shell(u32(x.v[0].x));
    y.v[0] = vec4(f32(s.x), f32(s.y), 0.0, 0.0);";
        let out: Vec<[[f32; 4]; 1]> = twin::map(
            &gpu,
            &shader,
            body,
            Bindings::new()
                .constant("SHELLS", f64::from(shells))
                .uniform(1, 0, &uniform),
            &inputs,
        )?;
        for (x, o) in inputs.iter().zip(&out) {
            let instance = x[0][0] as u32;
            let cpu = lod.shell(instance / LEVEL_INSTANCES, instance % LEVEL_INSTANCES);
            let gpu = (o[0][0] as u32, o[0][1] as u32);
            if gpu != cpu {
                wrong.push(format!(
                    "N {shells} instance {instance}: GPU {gpu:?} CPU {cpu:?}"
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "{wrong:?}");
    Ok(())
}

/// Bakay's bend pass itself over generated ground vertices: each vertex's wind vector and
/// intensity are `wind::point_source` / `wind::scene` (the paper's point source at several
/// times, periods and biases; the scene's wind), its shell offsets `bend::offsets`, and every
/// segment the GPU leaves between two shells is one inter-shell distance long.
#[test]
fn bakay_cs_bend_is_the_wind_and_bend_twins() -> anyhow::Result<()> {
    use grassbench_bakay::chunks::CHUNK;
    use grassbench_bakay::{WindSource, bend, wind};
    let gpu = gpu()?;
    let meadow = scene("meadow", 0.05)?;
    let terrain = &meadow.terrain;
    let shader = compose(grassbench_bakay::SHADER);
    let field = affine_wind();
    let mut rng = Rng::new(31);
    let (mut vector, mut intensity, mut offsets, mut lengths) = Default::default();
    struct Case {
        wind: WindSource,
        shells: u32,
        stiffness: f32,
        max_intensity: f32,
        bias: f32,
        time: f32,
    }
    let cases = [
        Case {
            wind: WindSource::PointSource,
            shells: 16,
            stiffness: 1.0,
            max_intensity: 1.0,
            bias: 0.15,
            time: 1.234,
        },
        Case {
            wind: WindSource::PointSource,
            shells: 65,
            stiffness: 2.5,
            max_intensity: 1.4,
            bias: 0.6,
            time: 0.0,
        },
        Case {
            wind: WindSource::PointSource,
            shells: 1,
            stiffness: 0.3,
            max_intensity: 1.0,
            bias: -0.2,
            time: 7.9,
        },
        Case {
            wind: WindSource::Scene,
            shells: 33,
            stiffness: 1.0,
            max_intensity: 1.0,
            bias: 0.0,
            time: 0.5,
        },
        Case {
            wind: WindSource::Scene,
            shells: 16,
            stiffness: 0.2,
            max_intensity: 0.3,
            bias: 0.0,
            time: 0.5,
        },
    ];
    for case in &cases {
        let params = grassbench_bakay::Params {
            wind: case.wind,
            shells: case.shells,
            stiffness: case.stiffness,
            max_intensity: case.max_intensity,
            source_position: [3.0, 0.5, -7.0],
            source_period: 2.7,
            source_step_length: 1.3,
            source_step_delay: 0.21,
            source_bias: case.bias,
            reference_speed: 6.0,
            ..Default::default()
        };
        let source = params.point_source();
        let scene_gpu = scene_gpu(&gpu, &meadow, &field, case.time)?;
        // Ground vertices: the edge cases first (at the source, straight under it with the
        // wind along the normal, where the scene's wind is zero, a flat normal), then random
        // points on the terrain with random normals.
        let at_source = Vec3::from(source.position);
        let under = Vec3::new(
            at_source.x,
            terrain.height_at(Vec2::new(at_source.x, at_source.z)),
            at_source.z,
        );
        let along = (at_source - under).normalize();
        let zero_wind = Vec3::new(5.0, terrain.height_at(Vec2::new(5.0, -3.0)), -3.0);
        let mut ground = vec![
            (at_source, Vec3::Y),
            (under, along),
            (zero_wind, Vec3::Y),
            (
                Vec3::new(0.0, 1.0, 0.0),
                field.velocity(Vec3::new(0.0, 1.0, 0.0), 0.0).normalize(),
            ),
            (terrain.point_at(Vec2::new(40.0, 40.0)), Vec3::Y),
        ];
        while ground.len() < 3000 {
            let xz = Vec2::new(rng.range(-40.0, 40.0), rng.range(-40.0, 40.0));
            let n = Vec3::new(rng.range(-0.8, 0.8), 1.0, rng.range(-0.8, 0.8)).normalize();
            ground.push((terrain.point_at(xz), n));
        }
        let count = ground.len() as u32;
        let vertices: Vec<GroundVertex> = ground
            .iter()
            .map(|(p, n)| GroundVertex {
                position: p.to_array(),
                normal: n.to_array(),
            })
            .collect();
        // The vertices as a mesh 50 wide and 60 deep, bent as the chunks of a checkerboard
        // over it (every other chunk, those at the mesh's edges cut): each bent chunk must
        // move all of its (CHUNK + 1)² vertices itself, and no vertex outside them moves.
        let side = (50, 60);
        assert_eq!(count, side.0 * side.1);
        let uniform = grassbench_bakay::uniform(&params, &meadow, side);
        let bent: Vec<[u32; 2]> = (0..side.1 - 1)
            .step_by(CHUNK as usize)
            .flat_map(|j| (0..side.0 - 1).step_by(CHUNK as usize).map(move |i| [i, j]))
            .filter(|[i, j]| (i / CHUNK + j / CHUNK).is_multiple_of(2))
            .collect();
        let moved = |v: u32| {
            let (i, j) = (v % side.0, v / side.0);
            bent.iter()
                .any(|&[ci, cj]| (ci..=ci + CHUNK).contains(&i) && (cj..=cj + CHUNK).contains(&j))
        };
        let spacing = uniform.shape[0];
        let shells = case.shells as usize;
        let bindings = Bindings::new()
            .constant("SHELLS", f64::from(case.shells))
            .constant("CHUNK", f64::from(CHUNK))
            .scene(&scene_gpu)
            .uniform(1, 0, &uniform)
            .storage(1, 1, &vertices)
            .bind(1, 2, Resource::Output(vec![0; ground.len() * 16]))
            .bind(1, 3, Resource::Output(vec![0; ground.len() * shells * 8]))
            .storage(1, 9, &bent);
        let out = twin::dispatch(
            &gpu,
            &shader,
            "cs_bend",
            &bindings,
            [
                bent.len() as u32 * grassbench_bakay::BEND_WORKGROUPS_PER_CHUNK,
                1,
                1,
            ],
        )?;
        let wind_out: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&out[0]);
        let offsets_out: Vec<[f32; 2]> = bytemuck::pod_collect_to_vec(&out[1]);
        let name = format!("{:?} N {} p {}", case.wind, case.shells, case.stiffness);
        let mut untouched = 0;
        for (v, (p, n)) in ground.iter().enumerate() {
            if !moved(v as u32) {
                let outside = wind_out[v] == [0.0; 4]
                    && (0..shells).all(|k| offsets_out[k * ground.len() + v] == [0.0; 2]);
                anyhow::ensure!(outside, "{name}: vertex {v}, in no bent chunk, was moved");
                untouched += 1;
                continue;
            }
            let cpu = match case.wind {
                WindSource::PointSource => {
                    wind::point_source(&source, *p, *n, case.time, case.max_intensity)
                }
                WindSource::Scene => wind::scene(
                    field.velocity(*p, case.time),
                    *n,
                    params.reference_speed,
                    case.max_intensity,
                ),
            };
            let g = wind_out[v];
            let gv = Vec3::from_slice(&g);
            Worst::record(&mut vector, gv.distance(cpu.vector), || {
                format!("{name} at {p} n {n}: GPU {gv} CPU {}", cpu.vector)
            });
            Worst::record(&mut intensity, (g[3] - cpu.intensity).abs(), || {
                format!("{name} at {p}: GPU {} CPU {}", g[3], cpu.intensity)
            });
            let expected = bend::offsets(case.shells, spacing, cpu.intensity, case.stiffness);
            for k in 0..shells {
                let o = offsets_out[k * ground.len() + v];
                let e = (o[0] - expected[k].0).hypot(o[1] - expected[k].1);
                Worst::record(&mut offsets, e, || {
                    format!("{name} at {p} shell {k}: GPU {o:?} CPU {:?}", expected[k])
                });
                if k > 0 {
                    let q = offsets_out[(k - 1) * ground.len() + v];
                    let l = (o[0] - q[0]).hypot(o[1] - q[1]);
                    Worst::record(&mut lengths, (l - spacing).abs(), || {
                        format!("{name} at {p} segment {k}: {l} vs S = {spacing}")
                    });
                }
            }
        }
        // The checkerboard leaves some vertices out and bends the rest: 1 010 of 3 000 stay.
        anyhow::ensure!(
            untouched > 0 && untouched < ground.len() / 2,
            "{name}: {untouched} of {count} vertices in no bent chunk"
        );
    }
    // Measured 2.8e-7 (unit vectors) and 1.8e-7 (intensities up to 1.4: `sin` and the
    // step's distance); segments within 7.5e-8 m of S (S = 0.044 m at N 16), offsets 1.8e-7 m
    // on blades up to 0.7 m; limits 4-10x above. A `cs_bend` whose segments stretch by
    // 1 + 0.3 I along the wind is off by 0.13 m, one whose `sin` takes the next shell's tilt
    // by 0.044 m.
    vector.check("bakay wind vector", 2e-6)?;
    intensity.check("bakay intensity", 2e-6)?;
    lengths.check("bakay segment lengths (m)", 3e-7)?;
    offsets.check("bakay shell offsets (m)", 2e-6)?;
    Ok(())
}

/// Boulanger's LOD in the shader (Eq. 1-5 and the slices' share of a texel) is `lod.rs`: the
/// weights from the real uniform for several sets of the four distances of Fig. 13, the
/// opacities for any weight, threshold and ω (the hard test ω = 0 too, away from its steps),
/// and the slices' share for texels from one a pixel to many.
#[test]
fn boulanger_lod_weights_are_lod_rs() -> anyhow::Result<()> {
    use grassbench_boulanger::lod::{self, LodDistances};
    let gpu = gpu()?;
    let grass = scene("meadow", 0.05)?.config.grass;
    let shader = compose(grassbench_boulanger::SHADER);
    let mut rng = Rng::new(8);
    let (mut weights, mut opacity, mut share) =
        (Worst::default(), Worst::default(), Worst::default());
    let sets = [
        (2.5, 3.5, 12.0, 30.0, 0.4),
        (0.5, 1.0, 1.0, 200.0, 0.05),
        (5.0, 30.0, 30.0, 60.0, 0.8),
        (0.0, 0.1, 0.1, 0.2, 0.25),
    ];
    for (min_geom, max_geom, min_btf, max_btf, omega) in sets {
        let params = grassbench_boulanger::Params {
            min_geom,
            max_geom,
            min_btf,
            max_btf,
            omega,
            ..Default::default()
        };
        let uniform = grassbench_boulanger::params_uniform(&params, &grass);
        let distances = LodDistances {
            min_geom,
            max_geom,
            min_btf,
            max_btf,
        };
        let mut inputs = Vec::new();
        let mut edges = vec![
            0.0,
            min_geom,
            max_geom,
            min_btf,
            max_btf,
            0.5 * (min_geom + max_geom),
            2.0 * max_btf,
            1e4,
        ];
        edges.extend((0..3000 - edges.len()).map(|_| rng.range(0.0, 1.3 * max_btf)));
        for (k, d) in edges.into_iter().enumerate() {
            let w_g = distances.w_g(d);
            let f = distances.vertical_fade(d);
            let t = rng.next_f32();
            // One input in five takes the hard test, and its threshold is kept 1e-4 from the
            // step (there, which side f32 rounding falls on is a coin toss).
            let hard = k % 5 == 0;
            let t = if hard && ((1.0 - t - w_g).abs() < 1e-4 || (t - f).abs() < 1e-4) {
                (t + 0.37) % 1.0
            } else {
                t
            };
            let o = if hard { 0.0 } else { rng.range(0.01, 1.0) };
            let texels = [0.0, 1.0, 2f32.sqrt(), 2.0, 8f32.sqrt(), 40.0][k % 6]
                * if k % 7 == 0 { rng.range(0.5, 2.0) } else { 1.0 };
            let density = if k % 11 == 0 {
                0.0
            } else {
                rng.range(0.05, 1.0)
            };
            let dth = rng.next_f32();
            let x = rng.range(-0.5, 1.5);
            inputs.push([
                [d, x, 0.0, 0.0],
                [w_g, t, f, o],
                [dth, density, texels, 0.0],
            ]);
        }
        let body = "    let d = x.v[0].x;
    y.v[0] = vec4(weight_geometry(d), vertical_fade(d), clamp01(x.v[0].y), 0.0);
    let w_g = x.v[1].x;
    let t = x.v[1].y;
    let f = x.v[1].z;
    let omega = x.v[1].w;
    y.v[1] = vec4(geometry_opacity(w_g, t, omega), fade_opacity(f, t, omega), 0.0, 0.0);
    y.v[2] = vec4(slice_share(x.v[2].x, x.v[2].y, w_g, f, x.v[2].z), 0.0, 0.0, 0.0);";
        let out: Vec<[[f32; 4]; 3]> = twin::map(
            &gpu,
            &shader,
            body,
            Bindings::new().uniform(1, 0, &uniform),
            &inputs,
        )?;
        for (x, o) in inputs.iter().zip(&out) {
            let d = x[0][0];
            let [w_g, t, f, om] = x[1];
            let [dth, density, texels, _] = x[2];
            let cpu = [
                distances.w_g(d),
                distances.vertical_fade(d),
                lod::clamp01(x[0][1]),
            ];
            for (k, c) in cpu.iter().enumerate() {
                weights.record((o[0][k] - c).abs(), || format!("set {min_geom}/{max_geom}/{min_btf}/{max_btf} d {d} x {}: output {k} GPU {} CPU {c}", x[0][1], o[0][k]));
            }
            let cpu = [
                lod::geometry_opacity(w_g, t, om),
                lod::fade_opacity(f, t, om),
            ];
            for (k, c) in cpu.iter().enumerate() {
                opacity.record((o[1][k] - c).abs(), || {
                    format!(
                        "w_g {w_g} t {t} f {f} ω {om}: output {k} GPU {} CPU {c}",
                        o[1][k]
                    )
                });
            }
            let c = lod::slice_share(dth, density, w_g, f, texels, omega);
            share.record((o[2][0] - c).abs(), || format!("dth {dth} ρ {density} w_g {w_g} f {f} texels {texels} ω {omega}: GPU {} CPU {c}", o[2][0]));
        }
    }
    // Weights and opacities in [0, 1]: measured 0 and 0 on lavapipe (the same f32 ramps),
    // shares 1.2e-7 (the sum of eight opacities, an ulp); the limits allow a few ulps of a
    // ramp's division elsewhere. A coefficient changed (1 + ω for 1 + 2ω in Eq. 5) moves an
    // opacity by 0.5, min_geom and max_geom swapped in Eq. 1 a weight by 1.
    weights.check("boulanger weights (Eq. 1-4)", 2e-6)?;
    opacity.check("boulanger opacities (Eq. 5)", 2e-6)?;
    share.check("boulanger slice_share", 2e-6)?;
    Ok(())
}

/// Boulanger's patch orientation map read through the shader (Sec. 4.1, Eq. 7) gives the
/// mirror and texture coordinates `slice::orientation_texel` does, over macro-cells of every
/// size, on cell borders and past the grid (clamped).
#[test]
fn boulanger_orientation_map_is_slice_orientation_texel() -> anyhow::Result<()> {
    use grassbench_boulanger::{CellGrid, slice};
    let gpu = gpu()?;
    let shader = compose(grassbench_boulanger::SHADER);
    let grid = CellGrid {
        origin: Vec2::new(-9.0, -5.5),
        cell: 0.5,
        nx: 37,
        nz: 23,
    };
    let mut rng = Rng::new(4);
    let mut sign = Worst::default();
    let mut uv = Worst::default();
    for seed in [7, 2024] {
        let (view, _) = slice::orientation_map(&gpu.device, &gpu.queue, &grid, seed);
        let mut inputs = vec![
            [[0.0, 0.0, 0.0, 0.0]],
            [[1.0, 1.0, 0.0, 0.0]],
            [[3.0, 2.0, 4.0, 8.0]],
            [[0.5, 0.5, 36.0, 22.0]],
            [[2.25, 1.75, 36.0, 22.0]],
            [[0.3, 0.6, -2.0, -1.0]],
            [[15.999, 0.001, 16.0, 0.0]],
        ];
        while inputs.len() < 3000 {
            let side = [1u32, 2, 4, 8, 16][inputs.len() % 5];
            let first =
                (rng.next_u64() % u64::from(grid.nx) / u64::from(side) * u64::from(side)) as f32;
            let first_z =
                (rng.next_u64() % u64::from(grid.nz) / u64::from(side) * u64::from(side)) as f32;
            let local = if inputs.len() % 9 == 0 {
                // On a cell border.
                Vec2::new(
                    (rng.next_u64() % u64::from(side)) as f32,
                    rng.range(0.0, side as f32),
                )
            } else {
                Vec2::new(rng.range(0.0, side as f32), rng.range(0.0, side as f32))
            };
            inputs.push([[local.x, local.y, first, first_z]]);
        }
        let body = "    y.v[0] = orientation_texel(x.v[0].xy, vec2<i32>(x.v[0].zw));";
        let bindings = Bindings::new().bind(
            2,
            3,
            Resource::Texture(
                &view,
                grassbench::wgpu::TextureSampleType::Uint,
                grassbench::wgpu::TextureViewDimension::D2,
            ),
        );
        let out: Vec<[[f32; 4]; 1]> = twin::map(&gpu, &shader, body, bindings, &inputs)?;
        for (x, o) in inputs.iter().zip(&out) {
            let local = Vec2::new(x[0][0], x[0][1]);
            let first = IVec2::new(x[0][2] as i32, x[0][3] as i32);
            let (orientation, cpu) = slice::orientation_texel(&grid, seed, local, first);
            let signs = orientation.signs();
            sign.record(
                (o[0][0] - signs.x).abs().max((o[0][1] - signs.y).abs()),
                || {
                    format!(
                        "seed {seed} local {local} first {first}: GPU {:?} CPU {signs}",
                        &o[0][..2]
                    )
                },
            );
            let g = Vec2::new(o[0][2], o[0][3]);
            // u' and 1 − ε are the same place of a repeating texture.
            let d = (g - cpu).abs();
            let d = d.min(Vec2::ONE - d);
            uv.record(d.max_element(), || {
                format!("seed {seed} local {local} first {first}: GPU {g} CPU {cpu}")
            });
        }
    }
    // Signs exactly; texture coordinates measured 0 (the same f32 operations); 1e-6 allows an
    // ulp of `fract` (coordinates below 16). Eq. 7 without the mirror is off by 0.5.
    sign.check("boulanger orientation signs", 0.0)?;
    uv.check("boulanger orientation uv (Eq. 7)", 1e-6)?;
    Ok(())
}

/// The perbet scene's pre-computation (patches, postures, uniform) at the test's density.
fn perbet_setup() -> anyhow::Result<(
    Scene,
    grassbench_perbet::Params,
    grassbench_perbet::precompute::Precomputed,
)> {
    let meadow = scene("meadow", 0.05)?;
    let params = grassbench_perbet::Params::default();
    let pre = grassbench_perbet::precompute::Precomputed::new(&meadow, &params)?;
    Ok((meadow, params, pre))
}

/// Perbet's posture lookup (Sec. 3.2) in the shader, `bend_angle`, is `receiver::angles_at`
/// on the real posture tables of every kind of grass, at every segment, for indices at the
/// pre-computed postures, between them and past ±1 (clamped); `segment_direction` is
/// `patch::segment_direction` for tilts from none (below its cut-off) to 1.5 rad.
#[test]
fn perbet_posture_lookup_is_receiver_angles_at() -> anyhow::Result<()> {
    use grassbench_perbet::{patch, receiver};
    let gpu = gpu()?;
    let (meadow, params, pre) = perbet_setup()?;
    let arrays = pre.arrays();
    let uniform = pre.uniform(&params, &meadow.config.grass);
    let k = uniform.more[0] as usize;
    let n = uniform.counts[1] as usize;
    let kinds = params.kinds as usize;
    assert_eq!(
        arrays.postures.len(),
        kinds * k * n,
        "posture tables of every kind"
    );
    let mut rng = Rng::new(12);
    let mut inputs = Vec::new();
    for kind in 0..kinds {
        let mut indices: Vec<f32> = vec![-1.5, -1.0, 0.0, 1.0, 1.2, 0.999, -0.999, 1e-7];
        indices.extend((0..k).map(|row| pre.postures[kind].index_of(row)));
        while indices.len() < 3000 / kinds / n {
            indices.push(rng.range(-1.2, 1.2));
        }
        for index in indices {
            for i in 0..n {
                let angle = if inputs.len() % 10 == 0 {
                    [1e-7, 0.0, 1e-3, 1.5][inputs.len() / 10 % 4]
                } else {
                    rng.range(0.0, 1.5)
                };
                let t = Vec2::from_angle(rng.range(0.0, 6.3)) * angle;
                inputs.push([[kind as f32, index, i as f32, 0.0], [t.x, t.y, 0.0, 0.0]]);
            }
        }
    }
    let body = "    y.v[0] = vec4(bend_angle(u32(x.v[0].x), x.v[0].y, u32(x.v[0].z)), segment_direction(x.v[1].xy));";
    let bindings = Bindings::new()
        .constant("SEGMENTS", f64::from(uniform.counts[1]))
        .uniform(1, 0, &uniform)
        .storage(1, 5, &arrays.postures);
    let out: Vec<[[f32; 4]; 1]> = twin::map(
        &gpu,
        &compose(grassbench_perbet::SHADER),
        body,
        bindings,
        &inputs,
    )?;
    let (mut angle, mut direction) = (Worst::default(), Worst::default());
    let mut angles = vec![0.0; n];
    for (x, o) in inputs.iter().zip(&out) {
        let (kind, index, i) = (x[0][0] as usize, x[0][1], x[0][2] as usize);
        receiver::angles_at(
            &arrays.postures[kind * k * n..(kind + 1) * k * n],
            k,
            n,
            index,
            &mut angles,
        );
        angle.record((o[0][0] - angles[i]).abs(), || {
            format!(
                "kind {kind} index {index} segment {i}: GPU {} CPU {}",
                o[0][0], angles[i]
            )
        });
        let t = Vec2::new(x[1][0], x[1][1]);
        let cpu = patch::segment_direction(t);
        let g = Vec3::new(o[0][1], o[0][2], o[0][3]);
        direction.record(g.distance(cpu), || format!("tilt {t}: GPU {g} CPU {cpu}"));
    }
    // Radians (postures up to about 1.8 rad): measured 1.2e-7 (the same interpolation, an
    // ulp); unit directions 1.0e-7 (`sin`, `cos`); limits 8-10x above. Reading the next
    // segment instead of the next posture is off by 0.93 rad.
    angle.check("perbet bend_angle", 1e-6)?;
    direction.check("perbet segment_direction", 1e-6)?;
    Ok(())
}

/// Perbet's morph (Sec. 4.2) in the shader, `morphed`, is `morph::morphed` towards
/// `morph::AnimatedStrips::surface`: the point of a 3D blade at its painted place on its
/// patch's animated strips, for strips bent by their edge receivers, sunk into hilly ground,
/// of both orientations, at every point of every blade and every stage of a transition.
#[test]
fn perbet_morph_is_the_morph_twin() -> anyhow::Result<()> {
    use grassbench_perbet::frame::Entry;
    use grassbench_perbet::morph::{self, AnimatedStrips};
    let gpu = gpu()?;
    let (meadow, params, pre) = perbet_setup()?;
    let terrain = &meadow.terrain;
    let arrays = pre.arrays();
    let mut uniform = pre.uniform(&params, &meadow.config.grass);
    let layout = pre.layout;
    let (n, strips, columns) = (layout.segments, layout.strips, layout.columns);
    let k_postures = uniform.more[0] as usize;
    let kind = uniform.more[3] as usize;
    let table =
        &arrays.postures[kind * k_postures * n as usize..(kind + 1) * k_postures * n as usize];
    // Strips entries start after five other entries, as a frame lists 3D entries first.
    let base = 5u32;
    uniform.bases[0] = base;
    let mut rng = Rng::new(44);
    let mut entries = vec![Entry::default(); base as usize];
    let slots = 8u32;
    for slot in 0..slots {
        let origin = Vec2::new(rng.range(-38.0, 35.0), rng.range(-38.0, 35.0));
        entries.push(Entry {
            origin: origin.to_array(),
            variant: slot % params.variants,
            flags: (slot % 2) | if slot % 3 == 0 { 2 } else { 0 },
            opacity: 1.0,
            morph: 0.0,
            grow: [1.0, 0.0, 0.5, rng.next_f32()][slot as usize % 4],
            link: 0,
        });
    }
    let edges = (strips * (columns + 1)) as usize;
    let receivers: Vec<[f32; 4]> = (0..slots as usize * edges)
        .map(|e| {
            let d = Vec2::from_angle(rng.range(0.0, 6.3));
            let index = if e % 7 == 0 {
                [0.0, 1.0, -1.0, 1.3][e / 7 % 4]
            } else {
                rng.range(-1.0, 1.0)
            };
            [d.x, d.y, index, 0.0]
        })
        .collect();
    let blade_count = arrays.blades.len() as u32;
    let mut inputs = Vec::new();
    while inputs.len() < 3000 {
        let slot = rng.next_u64() as u32 % slots;
        let link = base + slot;
        let e = entries[link as usize];
        let b = e.variant * (blade_count / params.variants)
            + rng.next_u64() as u32 % (blade_count / params.variants);
        let level = inputs.len() as u32 % (n + 1);
        let morph = [0.0, 1.0, 0.5, rng.next_f32()][inputs.len() % 4];
        let own = Vec3::new(
            e.origin[0] + rng.range(0.0, 2.5),
            rng.range(0.0, 5.0),
            e.origin[1] + rng.range(0.0, 2.5),
        );
        inputs.push([
            v4(own, morph),
            [b as f32, level as f32, (e.flags & 1) as f32, link as f32],
        ]);
    }
    let scene_gpu = scene_gpu(&gpu, &meadow, &Calm, 0.0)?;
    let body = "    var e: Entry;
    e.flags = u32(x.v[1].z);
    e.opacity = 1.0;
    e.morph = x.v[0].w;
    e.link = u32(x.v[1].w);
    y.v[0] = vec4(morphed(x.v[0].xyz, e, u32(x.v[1].x), u32(x.v[1].y)), 0.0);";
    let bindings = Bindings::new()
        .constant("SEGMENTS", f64::from(uniform.counts[1]))
        .scene(&scene_gpu)
        .uniform(1, 0, &uniform)
        .storage(1, 1, &entries)
        .storage(1, 2, &arrays.blades)
        .storage(1, 4, &arrays.painted)
        .storage(1, 5, &arrays.postures)
        .storage(1, 7, &receivers);
    let out: Vec<[[f32; 4]; 1]> = twin::map(
        &gpu,
        &compose(grassbench_perbet::SHADER),
        body,
        bindings,
        &inputs,
    )?;
    let mut worst = Worst::default();
    let mut moved = 0usize;
    for (x, o) in inputs.iter().zip(&out) {
        let own = Vec3::from_slice(&x[0]);
        let m = x[0][3];
        let (b, level, o_flag, link) = (
            x[1][0] as u32,
            x[1][1] as u32,
            x[1][2] as u32,
            x[1][3] as u32,
        );
        let e = entries[link as usize];
        let slot = (link - base) as usize;
        let animated = AnimatedStrips {
            layout: &layout,
            origin: Vec2::from(e.origin),
            orientation: e.flags & 1,
            grow: e.grow,
            receivers: &receivers[slot * edges..(slot + 1) * edges],
            table,
            postures: k_postures,
        };
        let uv = Vec2::from(arrays.painted[((b * 2 + o_flag) * (n + 1) + level) as usize]);
        let target = animated.surface(
            terrain,
            arrays.blades[b as usize].strips[o_flag as usize],
            uv,
        );
        let cpu = morph::morphed(own, target, m);
        let g = Vec3::from_slice(&o[0]);
        moved += usize::from(g.distance(own) > 1e-3);
        worst.record(g.distance(cpu), || {
            format!("blade {b} level {level} slot {slot} morph {m} uv {uv}: GPU {g} CPU {cpu}")
        });
    }
    // Metres, points up to 40 m from the origin on hills up to 4 m: measured 2.4e-7 (an ulp
    // of a coordinate near 3 m); the limit is five ulps of a 40 m coordinate (3.8e-6 each).
    // A strip edge bent the other way moves targets by 0.86 m.
    worst.check("perbet morph", 2e-5)?;
    assert!(
        moved > inputs.len() / 2,
        "only {moved} points moved: the morph was not exercised"
    );
    Ok(())
}

/// The prelude's `hash_u32` is `rng::hash_u32`, bit for bit: it picks which blades jahrmann's
/// far level keeps and which distance bucket a blade is in, on both sides.
#[test]
fn prelude_hash_is_rng_hash_u32() -> anyhow::Result<()> {
    use grassbench::rng::hash_u32;
    let gpu = gpu()?;
    let mut rng = Rng::new(41);
    // Words travel as the bits of finite floats (NaN and infinity patterns left out).
    let mut words: Vec<u32> = vec![1, 2, 0x68bc_21eb, 1 << 23, (1 << 24) - 1, 0x7f7f_ffff];
    while words.len() < 4000 {
        let w = (rng.next_u64() >> 32) as u32;
        if f32::from_bits(w).is_finite() && f32::from_bits(w) != 0.0 {
            words.push(w);
        }
    }
    let inputs: Vec<[[f32; 4]; 1]> = words
        .iter()
        .map(|&w| [[f32::from_bits(w), 0.0, 0.0, 0.0]])
        .collect();
    // The hash's two halves as floats (exact below 2^24).
    let body = "    let h = hash_u32(bitcast<u32>(x.v[0].x));
    y.v[0] = vec4(f32(h >> 16u), f32(h & 0xffffu), 0.0, 0.0);";
    let out: Vec<[[f32; 4]; 1]> = twin::map(&gpu, PRELUDE, body, Bindings::new(), &inputs)?;
    let mut worst = Worst::default();
    for (w, o) in words.iter().zip(&out) {
        let g = ((o[0][0] as u32) << 16) | o[0][1] as u32;
        let c = hash_u32(*w);
        worst.record(if g == c { 0.0 } else { 1.0 }, || {
            format!("{w:#x}: GPU {g:#x} CPU {c:#x}")
        });
    }
    // Integer arithmetic: equal on every word, or it is not the same hash.
    worst.check("prelude hash_u32", 0.0)
}

/// A population of `count` blades over `scene`'s terrain for jahrmann's twins: roots on the
/// ground, heights, leans (rest tips as `blades::rest_tip` makes them), stiffness, and tips
/// anywhere around the root (states the validation must repair, as well as valid ones).
fn jahrmann_blades(
    scene: &Scene,
    count: usize,
    rng: &mut Rng,
) -> Vec<grassbench_jahrmann::sim::BladeRest> {
    let terrain = &scene.terrain;
    let h = terrain.size() * 0.5;
    (0..count)
        .map(|_| {
            let xz = Vec2::new(rng.range(-h.x, h.x), rng.range(-h.y, h.y));
            let blade = grassbench::grass::Blade {
                root: terrain.point_at(xz),
                facing: rng.range(0.0, std::f32::consts::TAU),
                height: rng.range(0.1, 1.0),
                width: 0.02,
                stiffness: rng.range(0.3, 3.0),
                lean: Vec2::new(rng.range(0.0, std::f32::consts::TAU), rng.range(0.0, 1.2)),
                variation: 0.0,
                threshold: 0.0,
            };
            grassbench_jahrmann::sim::BladeRest {
                v0: blade.root,
                orientation: blade.facing,
                rest_tip: grassbench_jahrmann::blades::rest_tip(&blade),
                stiffness: blade.stiffness,
                height: blade.height,
            }
        })
        .collect()
}

/// jahrmann's compute step: the shader's `simulate` is `sim::step` (forces, collision with a
/// sphere, validation), and over random winds and spheres its tip never ends below the
/// ground and its curve keeps the blade's length, on a flat lawn and on the meadow's hills.
#[test]
fn jahrmann_simulate_is_sim_step() -> anyhow::Result<()> {
    use grassbench_jahrmann::{Params, sim};
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};
    let gpu = gpu()?;
    let params = Params::default();
    let forces = sim::Forces {
        recovery: params.stiffness,
        gravity: params.gravity,
        wind_response: params.wind_response,
    };
    let shader = compose(grassbench_jahrmann::SHADER);
    let body = "    let c = simulate(x.v[0].xyz, x.v[0].w, x.v[1].xyz, x.v[1].w, x.v[2].x, x.v[3].xyz, x.v[4].xyz, x.v[5], x.v[2].y);
    y.v[0] = vec4(c.v1, 0.0);
    y.v[1] = vec4(c.v2, 0.0);";
    // Recorded from inside the property runner's closure (a `Fn`).
    let worst = std::cell::RefCell::new([Worst::default(), Worst::default(), Worst::default()]);
    for name in ["counts", "meadow"] {
        let scene = if name == "counts" {
            Scene::load(&grassbench_tests::repo_root().join("tests/scenes/counts.toml"))?
        } else {
            scene("meadow", 0.05)?
        };
        let terrain = &scene.terrain;
        let scene_gpu = scene_gpu(&gpu, &scene, &Calm, 0.0)?;
        let uniform = grassbench_jahrmann::gpu::uniform(
            &params,
            &scene.config.grass,
            &scene.camera_at(0, TEST_SIZE),
            0,
            1,
        );
        // A fixed generator: the measurements quoted below are this test's own.
        let mut runner = TestRunner::new_with_rng(
            Config {
                cases: 6,
                ..Config::default()
            },
            TestRng::deterministic_rng(RngAlgorithm::ChaCha),
        );
        let result = runner.run(
            &(any::<u64>(), 0.0f32..20.0, 0.0f32..1.0, 0.001f32..0.1),
            |(seed, wind_speed, sphere_size, dt)| {
                let mut rng = grassbench::rng::Rng::new(seed);
                let blades = jahrmann_blades(&scene, 1500, &mut rng);
                let cases: Vec<_> = blades
                    .into_iter()
                    .map(|b| {
                        let tip = b.v0
                            + Vec3::new(
                                rng.range(-1.2, 1.2),
                                rng.range(-0.5, 1.2),
                                rng.range(-1.2, 1.2),
                            ) * b.height;
                        let wind = Vec3::new(
                            rng.range(-1.0, 1.0),
                            rng.range(-0.2, 0.2),
                            rng.range(-1.0, 1.0),
                        ) * wind_speed;
                        // A sphere about the blade (none for a quarter of them).
                        let centre = b.v0
                            + Vec3::new(
                                rng.range(-1.0, 1.0),
                                rng.range(0.0, 1.5),
                                rng.range(-1.0, 1.0),
                            ) * b.height;
                        let radius = if rng.next_f32() < 0.25 {
                            0.0
                        } else {
                            rng.range(0.0, 1.0) * sphere_size * b.height * 2.0
                        };
                        (b, tip, wind, centre.extend(radius))
                    })
                    .collect();
                let inputs: Vec<[[f32; 4]; 6]> = cases
                    .iter()
                    .map(|(b, tip, wind, sphere)| {
                        [
                            v4(b.v0, b.orientation),
                            v4(b.rest_tip, b.stiffness),
                            [b.height, dt, 0.0, 0.0],
                            v4(*tip, 0.0),
                            v4(*wind, 0.0),
                            sphere.to_array(),
                        ]
                    })
                    .collect();
                let out: Vec<[[f32; 4]; 2]> = twin::map(
                    &gpu,
                    &shader,
                    body,
                    Bindings::new().scene(&scene_gpu).uniform(1, 0, &uniform),
                    &inputs,
                )
                .map_err(|e| TestCaseError::fail(format!("{e:#}")))?;
                let mut worst = worst.borrow_mut();
                let [state, ground, length] = &mut *worst;
                for ((b, tip, wind, sphere), o) in cases.iter().zip(&out) {
                    let c = sim::step(b, *tip, *wind, *sphere, dt, &forces, |p| {
                        terrain.height_at(p)
                    });
                    let (g1, g2) = (Vec3::from_slice(&o[0]), Vec3::from_slice(&o[1]));
                    let e = g1.distance(c.v1).max(g2.distance(c.v2)) / b.v0.abs().max_element().max(1.0);
                    state.record(e, || {
                        format!(
                            "{name}: blade {b:?} tip {tip} wind {wind} sphere {sphere} dt {dt}: GPU {g1} {g2} CPU {} {}",
                            c.v1, c.v2
                        )
                    });
                    let floor = terrain.height_at(Vec2::new(g2.x, g2.z));
                    ground.record((floor - g2.y).max(0.0), || {
                        format!("{name}: tip {g2} below the ground at {floor}")
                    });
                    let len = sim::arc_length(b.v0, g1, g2, 256) / b.height - 1.0;
                    length.record(len.abs(), || {
                        format!("{name}: blade {b:?} from tip {tip}: length {len:+} of h")
                    });
                }
                prop_assert!(!out.is_empty());
                Ok(())
            },
        );
        result.map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
    }
    let [state, ground, length] = worst.into_inner();
    // Relative to the largest coordinate of the root (up to 40 m here): measured 5.4e-7 on
    // lavapipe with this generator, 7.7e-7 at worst over earlier random seeds (a few ulps of
    // the coordinate: sqrt, division, sin and cos rounded differently from the CPU's, through
    // the validation); limit 2.6x the worst seen. A step that forgets the midpoint's
    // push is off by up to 0.3 of a blade's height (1e-3 of a 26 m coordinate and more).
    state.check("jahrmann simulate (relative to the coordinates)", 2e-6)?;
    // The tip is on or above the ground: the final check uses the same bilinear height the
    // CPU measures with (identical on both sides: `prelude_terrain_and_wind_lookups`).
    ground.check("jahrmann tip below the ground (m)", 0.0)?;
    // The paper's length estimate: `sim`'s property test measured 7.26 % at worst over
    // 200 000 states; here measured 7.19 % over these 18 000 (the same worst case: a tip
    // pushed down over its root).
    length.check("jahrmann curve length (relative)", 0.075)?;
    Ok(())
}

/// jahrmann's culling: the shader's `cull` is `cull::verdict`, and it never drops a blade
/// whose root, midpoint or tip the core's CPU frustum (`Camera::frustum`) contains and whose
/// root is nearer than the first distance bucket, unless the orientation test culled it
/// (property test over random cameras, blades and switches).
#[test]
fn jahrmann_cull_is_cull_verdict_and_keeps_what_the_frustum_sees() -> anyhow::Result<()> {
    use grassbench::camera::Camera;
    use grassbench_jahrmann::Params;
    use grassbench_jahrmann::cull::{self, CullSettings, Verdict};
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};
    let gpu = gpu()?;
    let shader = compose(grassbench_jahrmann::SHADER);
    let body = "    let blade = u32(x.v[0].w);
    y.v[0] = vec4(f32(cull(blade, x.v[0].xyz, x.v[1].xyz, x.v[2].xyz, x.v[1].w)), 0.0, 0.0, 0.0);";
    let grass = grassbench::grass::GrassConfig::default();
    // Counted from inside the property runner's closure (a `Fn`).
    let tally = std::cell::Cell::new((0usize, 0usize, 0usize));
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 12,
            ..Config::default()
        },
        TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    );
    let result = runner.run(&(any::<u64>(), any::<[bool; 5]>()), |(seed, switches)| {
        let mut rng = grassbench::rng::Rng::new(seed);
        let params = Params::random_culling(&mut rng, switches);
        let eye = Vec3::new(
            rng.range(-50.0, 50.0),
            rng.range(0.5, 40.0),
            rng.range(-50.0, 50.0),
        );
        let forward = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-0.8, 0.3),
            rng.range(-1.0, 1.0),
        );
        let camera = Camera::look_at(
            eye,
            eye + forward,
            rng.range(0.5, 1.3),
            rng.range(0.05, 0.5),
            rng.range(60.0, 400.0),
            rng.range(1.0, 2.2),
        );
        let uniform = grassbench_jahrmann::gpu::uniform(&params, &grass, &camera, 0, 1);
        let planes = camera.frustum().planes;
        let s = CullSettings::of(&params);
        // Blades on the ground around the eye, half of them within 25 m, every kind of curve.
        let blades: Vec<(u32, Vec3, Vec3, Vec3, f32)> = (0..2000)
            .map(|k| {
                let reach = if k % 2 == 0 { 25.0 } else { 150.0 };
                let v0 = Vec3::new(
                    eye.x + rng.range(-reach, reach),
                    rng.range(-2.0, 2.0),
                    eye.z + rng.range(-reach, reach),
                );
                let h = rng.range(0.1, 1.0);
                let v1 = v0 + Vec3::Y * h * rng.range(0.05, 1.1);
                let v2 = v0
                    + Vec3::new(
                        rng.range(-0.8, 0.8),
                        rng.range(0.0, 1.0),
                        rng.range(-0.8, 0.8),
                    ) * h;
                let id = (rng.next_u64() % (1 << 24)) as u32;
                (id, v0, v1, v2, rng.range(0.0, std::f32::consts::TAU))
            })
            .collect();
        let inputs: Vec<[[f32; 4]; 3]> = blades
            .iter()
            .map(|(id, v0, v1, v2, o)| [v4(*v0, *id as f32), v4(*v1, *o), v4(*v2, 0.0)])
            .collect();
        let out: Vec<[[f32; 4]; 1]> = twin::map(
            &gpu,
            &shader,
            body,
            Bindings::new().uniform(1, 0, &uniform),
            &inputs,
        )
        .map_err(|e| TestCaseError::fail(format!("{e:#}")))?;
        let (mut mismatches, mut compared, mut kept_in_view) = tally.get();
        for ((id, v0, v1, v2, o), g) in blades.iter().zip(&out) {
            let gpu_verdict = Verdict::from_code(g[0][0] as u32);
            prop_assert!(gpu_verdict.is_some(), "code {}", g[0][0]);
            let cpu_verdict = cull::verdict(*id, (*v0, *v1, *v2), *o, camera.eye, &planes, &s);
            compared += 1;
            mismatches += usize::from(gpu_verdict != Some(cpu_verdict));
            let m = cull::midpoint(*v0, *v1, *v2);
            let frustum = camera.frustum();
            let seen = frustum.contains_point(*v0)
                || frustum.contains_point(m)
                || frustum.contains_point(*v2);
            let near = cull::ground_distance(*v0, camera.eye) < s.keeps_every_blade_within();
            if seen && near && gpu_verdict != Some(Verdict::Orientation) {
                kept_in_view += 1;
                prop_assert!(
                    !matches!(gpu_verdict, Some(Verdict::Frustum | Verdict::Distance)),
                    "blade {id} at {v0} in view and {:.1} m away culled: {gpu_verdict:?}",
                    cull::ground_distance(*v0, camera.eye)
                );
            }
            if !params.orientation_culling {
                prop_assert!(gpu_verdict != Some(Verdict::Orientation));
            }
        }
        tally.set((mismatches, compared, kept_in_view));
        Ok(())
    });
    result.map_err(|e| anyhow::anyhow!("{e}"))?;
    let (mismatches, compared, kept_in_view) = tally.get();
    eprintln!(
        "jahrmann cull: {mismatches} of {compared} verdicts differ from the CPU's; {kept_in_view} blades in view and near"
    );
    // Measured 0 of 24 000 on lavapipe (1 255 blades in view and near exercised the property):
    // the tests compare distances and dot products that the random blades rarely put within
    // an ulp of a threshold; a few would be rounding, not a different test, hence 0.1 %.
    assert!(
        mismatches <= compared / 1000,
        "{mismatches} of {compared} verdicts differ"
    );
    assert!(
        kept_in_view > 500,
        "only {kept_in_view} blades exercised the property"
    );
    Ok(())
}

/// jahrmann's compute pass itself (`cs_simulate`) over a small meadow population with a wind
/// and the scene's sphere among the blades: every blade's new curve is `sim::step`'s, the draw
/// lists hold exactly the blades `cull::verdict` draws at each level (each once), and the
/// counters, which are the indirect draws' instance counts, count them.
#[test]
fn jahrmann_cs_simulate_is_the_step_cull_and_compaction() -> anyhow::Result<()> {
    use grassbench_jahrmann::blades::BladeArrays;
    use grassbench_jahrmann::counts::GpuCounts;
    use grassbench_jahrmann::cull::{self, CullSettings, Verdict};
    use grassbench_jahrmann::{Params, sim};
    let gpu = gpu()?;
    let base = scene("meadow", 0.04)?;
    let mut config = base.config.clone();
    let camera0 = base.camera_at(0, TEST_SIZE);
    // The sphere sits in the grass 6 m in front of the walker.
    let ahead =
        camera0.eye + Vec3::new(camera0.forward.x, 0.0, camera0.forward.z).normalize() * 6.0;
    config.object = Some(grassbench::object::ObjectConfig {
        radius: 1.5,
        height: 0.6,
        start: [ahead.x, ahead.z],
        ..Default::default()
    });
    let meadow = Scene::from_config(config, base.base_dir.clone())?;
    let terrain = &meadow.terrain;
    let field = affine_wind();
    let scene_gpu = scene_gpu(&gpu, &meadow, &field, 0.0)?;
    let camera = meadow.camera_at(0, TEST_SIZE);
    let (centre, radius) = {
        let o = meadow.config.object.as_ref().expect("set above");
        (o.centre(terrain, 0.0), o.radius)
    };
    let sphere = centre.extend(radius);
    let dt = meadow.dt();
    let params = Params::default();
    let forces = sim::Forces {
        recovery: params.stiffness,
        gravity: params.gravity,
        wind_response: params.wind_response,
    };
    let blades = meadow.blades.all_blades(terrain);
    let arrays = BladeArrays::new(&blades);
    let n = arrays.len();
    let (gx, gy) = grassbench_jahrmann::gpu::workgroups(n as u32, 65_535);
    let uniform =
        grassbench_jahrmann::gpu::uniform(&params, &meadow.config.grass, &camera, n as u32, gx);
    let bindings = Bindings::new()
        .scene(&scene_gpu)
        // One range's room: the search's halvings for it (none run over every blade).
        .constant(
            "SEARCH_STEPS",
            f64::from(grassbench_jahrmann::gpu::search_steps(1)),
        )
        .uniform(1, 0, &uniform)
        .storage(1, 1, &arrays.v0)
        .storage(1, 2, &arrays.rest)
        .storage(1, 3, &arrays.looks)
        .storage(1, 4, &arrays.rest)
        .bind(1, 5, Resource::Output(vec![0; n * 32]))
        .bind(1, 6, Resource::Output(vec![0; n * 16]))
        .bind(1, 7, Resource::Output(vec![0; n * 32]))
        .bind(
            1,
            8,
            // The counts, then room for one dispatched range (unused: the pass runs over
            // every blade, `counts.w = 0`).
            Resource::Output(vec![
                0;
                grassbench_jahrmann::gpu::RANGES_OFFSET as usize + 16
            ]),
        );
    let out = twin::dispatch(
        &gpu,
        &compose(grassbench_jahrmann::SHADER),
        "cs_simulate",
        &bindings,
        [gx, gy, 1],
    )?;
    // The draw list, slot for slot: curves (guide, tip) and roots (root, looks).
    let curves: Vec<[[f32; 4]; 2]> = bytemuck::pod_collect_to_vec(&out[0]);
    let v2s: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&out[1]);
    let roots: Vec<[[f32; 4]; 2]> = bytemuck::pod_collect_to_vec(&out[2]);
    let counts: GpuCounts = bytemuck::pod_read_unaligned(&out[3][..GpuCounts::SIZE as usize]);
    let near_count = counts.near[1] as usize;
    let far_count = counts.far[1] as usize;
    // Each listed slot carries its blade's root and looks exactly (the blade is its looks'
    // scene index, here its index in the arrays) and the curve the pass wrote for it.
    let listed = (0..near_count).chain(n - far_count..n);
    let mut visible = vec![u32::MAX; n];
    let mut v1s = vec![None; n];
    for slot in listed {
        let [root, looks] = roots[slot];
        let i = looks[3] as usize;
        assert!(i < n, "slot {slot}: blade {i} of {n}");
        assert_eq!(
            (root, looks),
            (arrays.v0[i], arrays.looks[i]),
            "slot {slot}: blade {i}'s root and looks"
        );
        assert_eq!(curves[slot][1], v2s[i], "slot {slot}: blade {i}'s tip");
        visible[slot] = i as u32;
        v1s[i] = Some(curves[slot][0]);
    }
    let s = CullSettings::of(&params);
    let mut state = Worst::default();
    let mut expected = [0u32; 6];
    let (mut near, mut far) = (
        std::collections::BTreeSet::new(),
        std::collections::BTreeSet::new(),
    );
    let mut pushed = 0;
    for i in 0..n {
        let b = arrays.rest_of(i).expect("in range");
        let clamped = Vec2::new(b.v0.x, b.v0.z)
            .clamp(terrain.min_corner(), terrain.min_corner() + terrain.size());
        let wind = field.velocity(Vec3::new(clamped.x, 0.0, clamped.y), 0.0);
        let c = sim::step(&b, b.rest_tip, wind, sphere, dt, &forces, |p| {
            terrain.height_at(p)
        });
        let calm = sim::step(&b, b.rest_tip, wind, Vec4::ZERO, dt, &forces, |p| {
            terrain.height_at(p)
        });
        pushed += usize::from(c.v2.distance(calm.v2) > 0.05 * b.height);
        // The guide reaches memory only for the blades the pass lists (the draw's); the tip
        // for every blade.
        let g2 = Vec3::from_slice(&v2s[i]);
        let g1 = v1s[i].map_or(c.v1, |v| Vec3::from_slice(&v));
        state.record(
            g1.distance(c.v1).max(g2.distance(c.v2)) / b.v0.abs().max_element().max(1.0),
            || format!("blade {i}: GPU {g1} {g2} CPU {} {}", c.v1, c.v2),
        );
        let v = cull::verdict(
            i as u32,
            (b.v0, c.v1, c.v2),
            b.orientation,
            camera.eye,
            &camera.frustum().planes,
            &s,
        );
        expected[v as usize] += 1;
        match v {
            Verdict::Near => near.insert(i as u32),
            Verdict::Far => far.insert(i as u32),
            _ => false,
        };
    }
    // The same measure as `jahrmann_simulate_is_sim_step`, here with the wind sampled by the
    // pass itself (an affine wind, which the texture gives back to 1e-6 m/s): measured 2.0e-7.
    state.check(
        "jahrmann cs_simulate state (relative to the coordinates)",
        2e-6,
    )?;
    // Measured 24 blades pushed more than 5 % of their height by the sphere.
    assert!(
        pushed >= 10,
        "the sphere pushed only {pushed} blades: collision not exercised"
    );
    assert_eq!((counts.near[0], counts.far[0]), (15, 7), "vertex counts");
    assert_eq!(counts.considered(), n as u64);
    let gpu_near: std::collections::BTreeSet<u32> = visible[..near_count].iter().copied().collect();
    let gpu_far: std::collections::BTreeSet<u32> =
        visible[n - far_count..].iter().copied().collect();
    assert_eq!(
        gpu_near.len(),
        near_count,
        "a blade listed twice at the near level"
    );
    assert_eq!(
        gpu_far.len(),
        far_count,
        "a blade listed twice at the far level"
    );
    assert_eq!(counts.of(Verdict::Near) as usize, near_count);
    assert_eq!(counts.of(Verdict::Far) as usize, far_count);
    // Verdicts on curves equal to rounding: measured identical lists and counts on lavapipe
    // (17 350 blades: 717 near, 888 far, 2 683 stood for, 4 802 / 6 087 / 2 173 culled by
    // orientation / frustum / distance, the far thinning from 40 m included); a blade whose midpoint sits within rounding of a
    // frustum plane could move between lists, so 0.1 % is allowed for rounding.
    let differ =
        gpu_near.symmetric_difference(&near).count() + gpu_far.symmetric_difference(&far).count();
    eprintln!(
        "jahrmann cs_simulate: {n} blades, near {near_count} far {far_count}, GPU verdicts {:?} CPU {expected:?}, {differ} listed differently, {pushed} pushed by the sphere",
        counts.verdicts
    );
    assert!(
        differ <= n / 1000,
        "{differ} blades listed differently from the CPU's verdicts"
    );
    for (k, (&g, &c)) in counts.verdicts.iter().zip(&expected).enumerate() {
        assert!(
            g.abs_diff(c) as usize <= n / 1000,
            "verdict {k}: GPU {g}, CPU {c}"
        );
    }
    Ok(())
}

/// The background shader's `ground_vertex` (which mesh vertex a ground chunk's pattern vertex
/// stands on: turned onto a skirt's edge, clamped to the mesh) is
/// `ChunkInstance::vertex`, exactly, over every edge and random chunks, meshes and locals.
#[test]
fn ground_vertex_is_chunk_instance_vertex() -> anyhow::Result<()> {
    use grassbench::terrain::chunks::{CHUNK_CELLS, ChunkInstance, EDGES};
    let gpu = gpu()?;
    let mut rng = Rng::new(43);
    let mut cases = Vec::new();
    while cases.len() < 4000 {
        let side = [
            2 + (rng.next_u64() % 256) as u32,
            2 + (rng.next_u64() % 256) as u32,
        ];
        let cells = |n: u32| (n - 1).div_ceil(CHUNK_CELLS);
        let origin = [
            (rng.next_u64() % u64::from(cells(side[0]))) as u32 * CHUNK_CELLS,
            (rng.next_u64() % u64::from(cells(side[1]))) as u32 * CHUNK_CELLS,
        ];
        let instance = ChunkInstance {
            origin,
            side,
            edge: (rng.next_u64() % u64::from(EDGES + 1)) as u32,
            depth: 0.0,
        };
        let local = (
            (rng.next_u64() % u64::from(CHUNK_CELLS + 1)) as u32,
            (rng.next_u64() % u64::from(CHUNK_CELLS + 1)) as u32,
        );
        cases.push((instance, local));
    }
    let inputs: Vec<[[f32; 4]; 2]> = cases
        .iter()
        .map(|(c, (i, j))| {
            let f = |v: u32| v as f32;
            [
                [f(c.origin[0]), f(c.origin[1]), f(c.side[0]), f(c.side[1])],
                [f(c.edge), f(*i), f(*j), 0.0],
            ]
        })
        .collect();
    let body = "    let v = ground_vertex(vec4<u32>(x.v[0]), u32(x.v[1].x), vec2<u32>(x.v[1].yz));
    y.v[0] = vec4(f32(v.x), f32(v.y), 0.0, 0.0);";
    let shader = compose(grassbench::shaders::BACKGROUND);
    let out: Vec<[[f32; 4]; 1]> = twin::map(&gpu, &shader, body, Bindings::new(), &inputs)?;
    let mut worst = Worst::default();
    for ((c, (i, j)), o) in cases.iter().zip(&out) {
        let (col, row) = c.vertex(*i, *j);
        let same = o[0][0] == col as f32 && o[0][1] == row as f32;
        worst.record(if same { 0.0 } else { 1.0 }, || {
            format!(
                "{c:?} at ({i}, {j}): GPU {:?}, CPU ({col}, {row})",
                &o[0][..2]
            )
        });
    }
    worst.check("ground_vertex", 0.0)
}
