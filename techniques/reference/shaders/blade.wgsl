// Reference grass: every blade of the scene as a curved strip, built in the vertex shader from
// a per-blade instance and the bend `cs_bend` gave it this frame (see
// `techniques/reference/src/lib.rs`). Composed after the prelude.

// The most segments a blade may have (`Params::segments`' range), plus one: the strip's levels.
const MAX_LEVELS: u32 = 16u;

struct Params {
    color_root: vec4<f32>,      // rgb; w: colour variation
    color_tip: vec4<f32>,       // rgb; w: translucency
    // x: segments (the shader reads `SEGMENTS`); y: wind response (rad per m/s); z: bend profile exponent; w: max bend (rad)
    shape: vec4<f32>,
    // x: flutter amount; yzw: unused
    motion: vec4<f32>,
    // Per level L = 0..segments of the strip, s = L / segments its relative height (tabulated
    // on the CPU, `levels` in lib.rs: they depend on the parameters only): x = s^profile (the
    // tilt's profile at the level), y = ((L + 0.5) / segments)^profile (at the mid-point of
    // segment L), z = 0.5 (1 - s)^0.7 (half the width's taper), w = s^0.8 (root-to-tip colour).
    levels: array<vec4<f32>, MAX_LEVELS>,
}

@group(1) @binding(0) var<uniform> params: Params;

// Segments per blade, set when the pipeline is created: the vertex shader walks up to its
// vertex's level, and a loop bounded by a uniform is re-specialised by lavapipe every time its
// pipeline is bound (`grassbench::shaders::uniform_bound_loops`).
override SEGMENTS: u32;

struct Blade {
    @location(0) root: vec4<f32>,            // root xyz; w unused
    @location(1) shape: vec4<f32>,           // height, width, stiffness, colour variation
    @location(2) side_lean: vec4<f32>,       // xy: unit side axis (x, z); zw: rest lean (x, z)
    @location(3) bent: vec4<f32>,            // this frame's bend (`blade_bend`)
}

// A blade as the bend pass reads it: `Blade`'s first three attributes, the same 48 bytes.
struct BladeData {
    root: vec4<f32>,
    shape: vec4<f32>,
    side_lean: vec4<f32>,
}

// The bend pass's chunk of the blades (bound a range at a time: the storage bindings stay
// within WebGPU's default size) and of their bends, blade for blade.
@group(1) @binding(1) var<storage, read> blades: array<BladeData>;
@group(1) @binding(2) var<storage, read_write> bends: array<vec4<f32>>;
// x: the chunk's first blade in the whole field; yzw: unused.
@group(1) @binding(3) var<uniform> chunk: vec4<u32>;

struct VsOut {
    @builtin(position) position: vec4<f32>,
    // xyz: world position; w: ambient occlusion. One slot, not two: on a software rasteriser
    // every triangle that touches a pixel pays the set-up of each interpolated slot.
    @location(0) world_ao: vec4<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
}

// Blue (0) through green to red (1), for debug views.
fn heat(t: f32) -> vec3<f32> {
    let x = clamp(t, 0.0, 1.0);
    return clamp(vec3(2.0 * x - 0.5, 1.0 - abs(2.0 * x - 1.0), 1.5 - 2.0 * x), vec3(0.0), vec3(1.0)) * 0.6;
}

// The bend of blade `index` rooted at `root_xz`: its rest lean plus the wind's push, scaled by
// its stiffness, plus a small per-blade flutter whose speed follows the wind. Time comes from
// the globals only. xy: the bend's unit direction (x, z); z: the bend at the tip (rad), at
// most `max_bend`; w: the wind speed (for the debug view).
fn blade_bend(root_xz: vec2<f32>, stiffness: f32, lean: vec2<f32>, index: u32) -> vec4<f32> {
    let wind = wind_at(root_xz);
    let speed = length(wind.xz);
    let phase = hash_f32(index) * 2.0 * PI;
    let flutter = params.motion.x * speed * sin(globals.camera_pos.w * (3.0 + speed) + phase);
    let push = wind.xz * (params.shape.y / stiffness) * (1.0 + flutter);
    let bend_vec = lean + push;
    let bend_len = length(bend_vec);
    let bend = min(bend_len, params.shape.w);
    let dir2 = select(vec2(1.0, 0.0), bend_vec / bend_len, bend_len > 1e-5);
    return vec4(dir2, bend, speed);
}

// Workgroup width of the bend pass (`WORKGROUP` in src/bend.rs).
const BEND_WORKGROUP: u32 = 64u;

// The bend pass: each blade's bend once a frame, not at each of its vertices (the flutter's
// phase hashes the blade's index in the whole field, not in its chunk).
@compute @workgroup_size(BEND_WORKGROUP)
fn cs_bend(@builtin(global_invocation_id) id: vec3<u32>) {
    let b = id.x;
    if (b >= arrayLength(&blades)) {
        return;
    }
    let blade = blades[b];
    bends[b] = blade_bend(blade.root.xz, blade.shape.z, blade.side_lean.zw, chunk.x + b);
}

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32, blade: Blade) -> VsOut {
    var out: VsOut;
    let root = blade.root.xyz;
    let height = blade.shape.x;
    let width = blade.shape.y;
    let dir = vec3(blade.bent.x, 0.0, blade.bent.y);
    let bend = blade.bent.z;
    let speed = blade.bent.w;

    // Walk up the blade segment by segment: each segment keeps its length (height / n), so the
    // blade never stretches however far it bends. The tilt from vertical at relative height s
    // is bend * s^profile: a large profile keeps the base stiff and bends the top (Bakay
    // Sec. 3's "stiffness"); the powers come from the level table. The walk runs all
    // `SEGMENTS` steps and adds those below the vertex's level: a loop bounded by the level
    // would differ between the lanes of a SIMD batch, and lavapipe runs such a loop masked,
    // slower than the fixed one it unrolls (the same sums, so the same picture).
    let n = SEGMENTS;
    let level = min(min(vertex / 2u, n), MAX_LEVELS - 1u);
    let seg = height / f32(n);
    var p = root;
    for (var i = 0u; i < SEGMENTS; i++) {
        let a = bend * params.levels[i].y;
        p += select(vec3(0.0), seg * (sin(a) * dir + cos(a) * vec3(0.0, 1.0, 0.0)), i < level);
    }
    let s = f32(level) / f32(n);
    let at = params.levels[level];
    let a = bend * at.x;
    let tangent = sin(a) * dir + cos(a) * vec3(0.0, 1.0, 0.0);
    let side_axis = vec3(blade.side_lean.x, 0.0, blade.side_lean.y);

    // Width tapers to a point at the tip; vertices alternate left (even) and right (odd).
    let half = width * at.z;
    let side = select(-1.0, 1.0, (vertex & 1u) == 1u);
    let world = p + side_axis * half * side * f32(level < n);
    // Normal of the blade's face, rounded a little across the width.
    let face = normalize(cross(side_axis, tangent));
    let normal = normalize(face + side_axis * side * 0.35);

    let variation = blade.shape.w * params.color_root.w;
    var albedo = mix(params.color_root.rgb, params.color_tip.rgb, at.w);
    albedo *= 1.0 + variation;
    albedo.r *= 1.0 + 0.6 * max(variation, 0.0);

    // Debug views (`TechniqueInfo::debug_views`): 1 = wind speed, 2 = bend, blue to red. A
    // `select`, not a branch on the uniform alone: lavapipe re-specialised this shader every
    // frame for that (`grassbench::shaders::uniform_branches`).
    albedo = select(albedo, heat(speed / max(globals.wind_info.x, 0.1)), globals.frame.z == 1u);
    albedo = select(albedo, heat(bend / max(params.shape.w, 1e-3)), globals.frame.z == 2u);

    out.position = globals.view_proj * vec4(world, 1.0);
    // Darker near the root: neighbouring blades hide the sky (ambient occlusion).
    out.world_ao = vec4(world, mix(0.3, 1.0, s));
    out.normal = normal;
    out.albedo = albedo;
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    let world = in.world_ao.xyz;
    let lit = shade_leaf(in.albedo, normalize(in.normal), world, in.world_ao.w, params.color_tip.w);
    return vec4(apply_fog(lit, world), 1.0);
}
