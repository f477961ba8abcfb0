// Micro-workloads of the unit-cost calibration (see `cost/workloads.rs` and `cost/measure.rs`).
// Bind group 0 holds only the prelude's `globals` (a fixed camera and sun): the lighting here
// is the prelude's, as the techniques' blades use it. Group 1: the workload's parameters and
// the compute workload's buffer.

struct Params {
    // xy: target size in pixels; zw: 1 / size
    size: vec4<f32>,
}

@group(1) @binding(0) var<uniform> params: Params;
@group(1) @binding(1) var<storage, read_write> springs: array<vec4<f32>>;
// The texture workloads' mip-mapped 512x512 texture (hashed texels) and a trilinear sampler.
@group(1) @binding(2) var fetched: texture_2d<f32>;
@group(1) @binding(3) var trilinear: sampler;
// The same texels as floating-point numbers: `Rgba16Float` for the samples
// (`FLOAT_SAMPLE_FORMAT`), `R32Float` for the loads (`FLOAT_LOAD_FORMAT`, as the terrain maps).
@group(1) @binding(4) var fetched_float: texture_2d<f32>;
@group(1) @binding(5) var fetched_r32: texture_2d<f32>;
// Per-instance data the `vertex_storage` strips' vertices read (hashed `vec4`s, 4 MiB).
@group(1) @binding(6) var<storage, read> instance_data: array<vec4<f32>>;
// A sampler that filters one mip level, the nearer (mipmap filter `Nearest`, as bakay's for
// its custom levels): the `single_level_texture_samples` workload's.
@group(1) @binding(7) var single_level: sampler;

struct VsOut {
    @builtin(position) position: vec4<f32>,
    @location(0) albedo: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) world: vec3<f32>,
    @location(3) ao: f32,
    @location(4) @interpolate(flat) layer: u32,
}

// Vertex `v` of blade strip `i`, with the work of a blade vertex: a hashed root and facing, a
// wind-like sway bending the blade with height, its normal, albedo and ambient occlusion, and
// the projection to clip space. Positions on screen are set by the callers (the workloads
// decide where triangles land); the projected depth is kept, so no work is dead code.
fn blade_vertex(v: u32, i: u32) -> VsOut {
    let level = f32(v / 2u) / 5.0;
    let side = f32(v & 1u) - 0.5;
    let h = hash_f32(i);
    let root = vec3(f32(i % 512u), 0.0, f32(i / 512u)) * 0.1;
    let facing = h * 2.0 * PI;
    let dir = vec3(cos(facing), 0.0, sin(facing));
    let across = vec3(-dir.z, 0.0, dir.x);
    let sway = 0.3 * sin(globals.camera_pos.w * 2.0 + h * 6.0);
    let bend = sway * level * level;
    let world = root + across * side * 0.02 * (1.0 - level) + vec3(0.0, 0.5 * level, 0.0) + dir * bend;
    let tangent = normalize(vec3(0.0, 0.5, 0.0) + dir * (2.0 * sway * level));
    let clip = globals.view_proj * vec4(world, 1.0);
    var out: VsOut;
    out.position = vec4(0.0, 0.0, clamp(abs(clip.z / clip.w), 0.0, 1.0), 1.0);
    out.albedo = mix(vec3(0.10, 0.30, 0.05), vec3(0.40, 0.60, 0.20), level);
    out.normal = normalize(cross(across, tangent));
    out.world = world;
    out.ao = mix(0.3, 1.0, level);
    out.layer = i;
    return out;
}

// Clip-space x, y of pixel coordinates `p` (origin top left).
fn pixel_to_clip(p: vec2<f32>) -> vec2<f32> {
    return vec2(p.x * params.size.z * 2.0 - 1.0, 1.0 - p.y * params.size.w * 2.0);
}

// Vertex `v` of blade strip `i` far to the right of the screen, so the clipper rejects all
// its triangles.
fn offscreen_vertex(v: u32, i: u32) -> VsOut {
    var out = blade_vertex(v, i);
    let corner = vec2(f32(v & 1u), f32(v / 2u));
    out.position = vec4(vec2(3.0, 0.0) + corner * 0.01, out.position.z, 1.0);
    return out;
}

// Vertices without primitives.
@vertex
fn vs_offscreen(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VsOut {
    return offscreen_vertex(v, i);
}

// 30 transcendentals (MATH_CHAIN): 10 links of a `sin`, a `cos` and a `pow`, each link fed
// by the last, so none can be folded away or left as dead code.
fn math_link(x: f32) -> f32 {
    return sin(x * 1.3 + 0.1) + cos(x * 0.7) + pow(abs(x) + 0.5, 0.9);
}

fn math_chain(x: f32) -> f32 {
    return math_link(math_link(math_link(math_link(math_link(
        math_link(math_link(math_link(math_link(math_link(x))))))))));
}

// The off-screen strips with a heavier vertex shader: the same vertex plus the chain, whose
// result sets the depth (clamped into the clip volume: still off screen, still rejected).
@vertex
fn vs_math(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VsOut {
    var out = offscreen_vertex(v, i);
    out.position.z = clamp(math_chain(out.position.z + f32(v) * 1e-3) * 0.01, 0.0, 1.0);
    return out;
}

// 256 scalar operations (ARITHMETIC_CHAIN): 16 links of a `vec4` multiply-add, the `vec4`
// rotated and scaled, and the maximum of the two (4 + 4 + 4 + 4), each link fed by the last
// and mixing its components, so none can be folded away. Four call sites of four: the cost
// model counts a call's operations once per call site, as it runs.
fn arith_link(v: vec4<f32>) -> vec4<f32> {
    return max(v * vec4(1.0001, 0.9999, 1.0002, 0.9998) + vec4(0.001, -0.002, 0.003, -0.001), v.yzwx * 0.999);
}

fn arith4(v: vec4<f32>) -> vec4<f32> {
    return arith_link(arith_link(arith_link(arith_link(v))));
}

fn arith_chain(v: vec4<f32>) -> vec4<f32> {
    return arith4(arith4(arith4(arith4(v))));
}

// The off-screen strips with the arithmetic chain, whose result sets the depth (clamped into
// the clip volume: still off screen, still rejected).
@vertex
fn vs_arithmetic(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VsOut {
    var out = offscreen_vertex(v, i);
    let a = arith_chain(vec4(out.position.z, f32(v), 0.5, 0.25));
    out.position.z = clamp(a.x * 0.01, 0.0, 1.0);
    return out;
}

// Primitives without fragments: the strip folded into [0.1, 0.4]^2 of pixel i (in scan
// order), so its 9 triangles (none degenerate) cover no pixel centre (at 0.5, 0.5).
@vertex
fn vs_subpixel(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VsOut {
    var out = blade_vertex(v, i);
    let w = u32(params.size.x);
    let pixels = w * u32(params.size.y);
    let k = i % pixels;
    let corner = vec2(0.1 + 0.3 * f32(v & 1u), 0.1 + 0.06 * f32(v / 2u));
    out.position = vec4(pixel_to_clip(vec2(f32(k % w), f32(k / w)) + corner), out.position.z, 1.0);
    return out;
}

// Fragments: layer i is a full-screen triangle (twice the screen's size: no edge crosses the
// screen, so no 2x2 quad is shaded twice) at depth 1 / (i + 2), nearer than every layer before
// it, so each passes a `LessEqual` test and shades every pixel. Its varyings are those of a
// blade (a ground-level patch 20 m across).
fn layer_at(v: u32, i: u32, depth: f32) -> VsOut {
    let uv = vec2(f32((v << 1u) & 2u), f32(v & 2u));
    var out: VsOut;
    out.position = vec4(uv * 2.0 - 1.0, depth, 1.0);
    out.albedo = mix(vec3(0.10, 0.30, 0.05), vec3(0.40, 0.60, 0.20), uv.y);
    out.normal = normalize(vec3(uv.x - 0.5, 1.0, 0.3));
    out.world = vec3(uv.x * 20.0, 0.3 + f32(i) * 0.01, uv.y * 20.0);
    out.ao = mix(0.3, 1.0, uv.y);
    out.layer = i;
    return out;
}

@vertex
fn vs_layer(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VsOut {
    return layer_at(v, i, 1.0 / f32(i + 2u));
}

// Hidden layers (the coverage checks' `hidden_*`): the same full-screen triangle far behind
// every layer above (depth 0.99 and a little nearer for each), so where a layer was drawn
// before, every fragment fails the depth test.
@vertex
fn vs_hidden_layer(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VsOut {
    return layer_at(v, i, 0.99 - f32(i % 1024u) * 1e-5);
}

// Blades on screen (the coverage checks, `cost/checks.rs`): strip i is a blade rooted at a
// hashed pixel, ONSCREEN_HEIGHT pixels tall and ONSCREEN_WIDTH wide at its root, tapering to
// its tip and leaning by up to a third of its height, at depth 1 / (i + 2): nearer than every
// strip before it, so each passes a `LessEqual` test. Nearly every 4x4 block it touches it
// covers in part, as a meadow's blades do, where a full-screen layer covers every block whole.
// The rig sets both (`workloads::ONSCREEN_BLADE_HEIGHT`, `workloads::BladeWidth::pixels`).
override ONSCREEN_HEIGHT: f32 = 0.0;
override ONSCREEN_WIDTH: f32 = 0.0;

@vertex
fn vs_onscreen_blade(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VsOut {
    var out = blade_vertex(v, i);
    let level = f32(v / 2u) / 5.0;
    let side = f32(v & 1u) - 0.5;
    let root = vec2(hash_f32(i ^ 0x68e31da4u), hash_f32(i ^ 0xb5297a4du)) * params.size.xy;
    let lean = (hash_f32(i ^ 0x1b56c4e9u) - 0.5) * 0.66 * ONSCREEN_HEIGHT;
    let tip = vec2(lean * level * level, -ONSCREEN_HEIGHT * level);
    let p = root + vec2(side * ONSCREEN_WIDTH * (1.0 - level), 0.0) + tip;
    out.position = vec4(pixel_to_clip(p), 1.0 / f32(i + 2u), 1.0);
    return out;
}

// A lit blade fragment, as the reference blade's: two-sided leaf lighting and fog.
fn lit(in: VsOut) -> vec3<f32> {
    let c = shade_leaf(in.albedo, normalize(in.normal), in.world, in.ao, 0.3);
    return apply_fog(c, in.world);
}

@fragment
fn fs_opaque(in: VsOut) -> @location(0) vec4<f32> {
    return vec4(lit(in), 1.0);
}

// Alpha-tested: half the pixels of each layer (hashed per pixel and layer) are discarded
// before shading, as a texture's alpha would.
@fragment
fn fs_alpha_tested(in: VsOut) -> @location(0) vec4<f32> {
    let p = vec2<u32>(in.position.xy);
    if (hash_f32(p.x + p.y * 8192u + in.layer * 0x9E3779B9u) < 0.5) {
        discard;
    }
    return vec4(lit(in), 1.0);
}

@fragment
fn fs_blended(in: VsOut) -> @location(0) vec4<f32> {
    return vec4(lit(in), 0.5);
}

// An opaque fragment with the chain of 30 transcendentals, fed by its position, added to the
// lit colour.
@fragment
fn fs_math(in: VsOut) -> @location(0) vec4<f32> {
    let x = math_chain(in.position.x * 0.01 + in.position.y * 1e-4);
    return vec4(lit(in) + 0.001 * x, 1.0);
}

// The opaque layer with the arithmetic chain, fed by the pixel.
@fragment
fn fs_arithmetic(in: VsOut) -> @location(0) vec4<f32> {
    let a = arith_chain(vec4(in.position.xy * 0.01, 0.5, 0.25));
    return vec4(lit(in) + 0.001 * a.x, 1.0);
}

// Texel loads: 32 `textureLoad`s of `t` per fragment (LOADS_PER_FRAGMENT, each its own call
// site: the cost model counts fetches per call site), at the pixel's texel and neighbours of
// level 0, added to the lit colour so none is dead code.
fn load_at(t: texture_2d<f32>, p: vec2<i32>, k: i32) -> vec4<f32> {
    return textureLoad(t, (p + vec2(k * 3, k * 5)) & vec2(511), 0);
}

// 8 loads of `t` from `p`'s texel on.
fn load8(t: texture_2d<f32>, p: vec2<i32>, k: i32) -> vec4<f32> {
    return load_at(t, p, k) + load_at(t, p, k + 1) + load_at(t, p, k + 2) + load_at(t, p, k + 3)
        + load_at(t, p, k + 4) + load_at(t, p, k + 5) + load_at(t, p, k + 6)
        + load_at(t, p, k + 7);
}

// 32 loads of `t` around the fragment's pixel, lit.
fn loads32(in: VsOut, t: texture_2d<f32>) -> vec4<f32> {
    let p = vec2<i32>(in.position.xy);
    let s = load8(t, p, 0) + load8(t, p, 8) + load8(t, p, 16) + load8(t, p, 24);
    return vec4(lit(in) + 0.002 * s.rgb, 1.0);
}

@fragment
fn fs_loads(in: VsOut) -> @location(0) vec4<f32> {
    return loads32(in, fetched);
}

// The same loads of floating-point texels (the `float_texture_loads` workload).
@fragment
fn fs_float_loads(in: VsOut) -> @location(0) vec4<f32> {
    return loads32(in, fetched_r32);
}

// Texel loads in the vertex stage (the probes of `workloads::probes`, timed with the
// calibration but not fitted): the off-screen strip whose vertex also does 32 `textureLoad`s
// of `t` (LOADS_PER_FRAGMENT) around the strip's texel (i % 512, i / 512), as a blade's vertex
// reads the terrain maps at its root (the strip's 11 vertices read the same texels), their sum
// setting the depth (clamped into the clip volume: still off screen, still rejected).
fn vertex_loads32(v: u32, i: u32, t: texture_2d<f32>) -> VsOut {
    var out = offscreen_vertex(v, i);
    let p = vec2(i32(i % 512u), i32((i / 512u) % 512u));
    let s = load8(t, p, 0) + load8(t, p, 8) + load8(t, p, 16) + load8(t, p, 24);
    out.position.z = clamp(out.position.z + 1e-3 * s.x, 0.0, 1.0);
    return out;
}

@vertex
fn vs_loads(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VsOut {
    return vertex_loads32(v, i, fetched);
}

// The same loads of floating-point texels (`R32Float`, as the terrain's maps).
@vertex
fn vs_float_loads(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VsOut {
    return vertex_loads32(v, i, fetched_r32);
}

// Storage reads in the vertex stage: the off-screen strip whose vertex also reads 8 `vec4`s
// of its instance's data (STORAGE_CHAIN words), from 8 arrays of 32 768 elements laid end to
// end, as a pulled blade's vertex reads its blade's root, looks and curve; their sum sets the
// depth (clamped into the clip volume: still off screen, still rejected).
fn instance_word(i: u32, j: u32) -> vec4<f32> {
    return instance_data[(i % 32768u + j * 32768u) % arrayLength(&instance_data)];
}

@vertex
fn vs_storage(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> VsOut {
    var out = offscreen_vertex(v, i);
    let s = instance_word(i, 0u) + instance_word(i, 1u) + instance_word(i, 2u) + instance_word(i, 3u)
        + instance_word(i, 4u) + instance_word(i, 5u) + instance_word(i, 6u) + instance_word(i, 7u);
    out.position.z = clamp(out.position.z + 1e-3 * s.x, 0.0, 1.0);
    return out;
}

// Filtered samples: 8 `textureSample`s of `t` through `s` per fragment (SAMPLES_PER_FRAGMENT),
// the texture minified 2.5:1 at any target size (2.5 x 512 texels over the screen's width,
// the layer's world x spanning 20 m: between mip levels 1 and 2, as far grass textures are),
// each at its own offset. Through `trilinear` each blends levels 1 and 2; through
// `single_level` each filters level 1 alone.
fn sample_at(t: texture_2d<f32>, s: sampler, uv: vec2<f32>, k: f32) -> vec4<f32> {
    return textureSample(t, s, uv + vec2(k * 0.013, k * 0.029));
}

// The 8 samples of `t` through `s` at the fragment, lit.
fn samples8(in: VsOut, t: texture_2d<f32>, s: sampler) -> vec4<f32> {
    let uv = in.world.xz / 20.0 * 2.5 * params.size.x / 512.0;
    let c = sample_at(t, s, uv, 0.0) + sample_at(t, s, uv, 1.0) + sample_at(t, s, uv, 2.0)
        + sample_at(t, s, uv, 3.0) + sample_at(t, s, uv, 4.0) + sample_at(t, s, uv, 5.0)
        + sample_at(t, s, uv, 6.0) + sample_at(t, s, uv, 7.0);
    return vec4(lit(in) + 0.01 * c.rgb, 1.0);
}

@fragment
fn fs_samples(in: VsOut) -> @location(0) vec4<f32> {
    return samples8(in, fetched, trilinear);
}

// The same samples of one mip level (the `single_level_texture_samples` workload).
@fragment
fn fs_single_level_samples(in: VsOut) -> @location(0) vec4<f32> {
    return samples8(in, fetched, single_level);
}

// The same samples of one mip level at a level each fragment gives (the
// `explicit_level_texture_samples` workload): `textureSampleLevel` at the level the
// minification puts them at (log2 2.5 = 1.32) plus a fraction that differs between
// neighbouring pixels, so the rasteriser cannot pick one level for a 2x2 quad; through
// `single_level` each filters the level nearest its own.
fn sample_level_at(t: texture_2d<f32>, s: sampler, uv: vec2<f32>, k: f32, lod: f32) -> vec4<f32> {
    return textureSampleLevel(t, s, uv + vec2(k * 0.013, k * 0.029), lod);
}

@fragment
fn fs_explicit_level_samples(in: VsOut) -> @location(0) vec4<f32> {
    let uv = in.world.xz / 20.0 * 2.5 * params.size.x / 512.0;
    let lod = 1.32 + 0.25 * fract(in.position.x * 0.37 + in.position.y * 0.61);
    let c = sample_level_at(fetched, single_level, uv, 0.0, lod)
        + sample_level_at(fetched, single_level, uv, 1.0, lod)
        + sample_level_at(fetched, single_level, uv, 2.0, lod)
        + sample_level_at(fetched, single_level, uv, 3.0, lod)
        + sample_level_at(fetched, single_level, uv, 4.0, lod)
        + sample_level_at(fetched, single_level, uv, 5.0, lod)
        + sample_level_at(fetched, single_level, uv, 6.0, lod)
        + sample_level_at(fetched, single_level, uv, 7.0, lod);
    return vec4(lit(in) + 0.01 * c.rgb, 1.0);
}

// The same samples of floating-point texels (the `float_texture_samples` workload).
@fragment
fn fs_float_samples(in: VsOut) -> @location(0) vec4<f32> {
    return samples8(in, fetched_float, trilinear);
}

// Compute: one spring step per invocation towards a hashed rest state, read-modify-write of
// 16 bytes (as a blade's simulation step). Invocations beyond the buffer wrap around it: its
// length is a power of two (`SPRING_COUNT`), so a mask wraps the index, and no spring update
// divides but the `compute_divisions` workload's.
fn wrap(i: u32) -> u32 {
    return i & (arrayLength(&springs) - 1u);
}

@compute @workgroup_size(64)
fn cs_springs(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * 64u;
    let k = wrap(i);
    let rest = vec4(hash_f32(i), hash_f32(i ^ 0x5bd1e995u), 0.0, 1.0);
    let p = springs[k];
    springs[k] = p + (rest - p) * 0.1;
}

// The `compute_barriers` workload's exchange: each invocation's element, read back by its
// neighbour.
// Element `k`'s `j`-th neighbour a workgroup's width along: invocation after invocation reads
// element after element, as jahrmann's culling pass reads each blade's arrays.
fn neighbour(k: u32, j: u32) -> vec4<f32> {
    return springs[wrap(k + j * 64u)];
}

// The spring update pulled towards the mean of 8 more elements' states: 8 more `vec4` reads
// from the storage buffer an invocation.
@compute @workgroup_size(64)
fn cs_storage(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * 64u;
    let k = wrap(i);
    let rest = vec4(hash_f32(i), hash_f32(i ^ 0x5bd1e995u), 0.0, 1.0);
    let near = neighbour(k, 1u) + neighbour(k, 2u) + neighbour(k, 3u) + neighbour(k, 4u);
    let far = neighbour(k, 5u) + neighbour(k, 6u) + neighbour(k, 7u) + neighbour(k, 8u);
    let p = springs[k];
    springs[k] = p + (rest + (near + far) * 0.125 - 2.0 * p) * 0.05;
}

var<workgroup> exchanged: array<vec4<f32>, 64>;

// One exchange between neighbours: every invocation stores its value, waits for the whole
// workgroup, takes its neighbour's, and waits again before the next exchange overwrites it: two
// barriers.
fn exchange(lid: u32, p: vec4<f32>) -> vec4<f32> {
    exchanged[lid] = p;
    workgroupBarrier();
    let q = exchanged[(lid + 1u) % 64u];
    workgroupBarrier();
    return q;
}

// The spring step of the element four neighbours along (`BARRIER_CHAIN`: 8 barriers), as a
// culling pass's workgroup waits for its counts.
@compute @workgroup_size(64)
fn cs_barriers(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) lid: u32, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * 64u;
    let k = wrap(i);
    let rest = vec4(hash_f32(i), hash_f32(i ^ 0x5bd1e995u), 0.0, 1.0);
    var p = springs[k];
    p = exchange(lid, p);
    p = exchange(lid, p);
    p = exchange(lid, p);
    p = exchange(lid, p);
    springs[k] = p + (rest - p) * 0.1;
}

// The spring step with the chain of 30 transcendentals, fed by the element, in its rest state.
@compute @workgroup_size(64)
fn cs_math(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * 64u;
    let k = wrap(i);
    let p = springs[k];
    let rest = vec4(hash_f32(i), math_chain(p.x) * 0.01, 0.0, 1.0);
    springs[k] = p + (rest - p) * 0.1;
}

// The spring step with the arithmetic chain, fed by the element, in its rest state.
@compute @workgroup_size(64)
fn cs_arithmetic(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * 64u;
    let k = wrap(i);
    let p = springs[k];
    let rest = vec4(hash_f32(i), hash_f32(i ^ 0x5bd1e995u) + arith_chain(p).x * 0.01, 0.0, 1.0);
    springs[k] = p + (rest - p) * 0.1;
}

// The spring step with a chain of integer remainders (DIVISION_CHAIN: 16) by the buffer's
// length, a value the pipeline does not fix, as a culling pass buckets a blade by a count
// its uniforms hold: each link a hash step of the last link's remainder, so none is folded
// away; the last nudges the rest state.
@compute @workgroup_size(64)
fn cs_divisions(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * 64u;
    let n = arrayLength(&springs);
    let k = wrap(i);
    var h = i;
    for (var link = 0u; link < 16u; link++) {
        h = (h * 747796405u + 2891336453u) % (n + link);
    }
    let p = springs[k];
    let rest = vec4(hash_f32(i), hash_f32(i ^ 0x5bd1e995u) + f32(h) * 1e-9, 0.0, 1.0);
    springs[k] = p + (rest - p) * 0.1;
}

// The sub-pixel strips of the `primitives` workload: a fragment shader reading no interpolated
// slot, so the rasteriser sets none up for their triangles (`primitive_inputs` draws the same
// strips with `fs_opaque`, which reads the blade's five). No fragment is shaded either way.
@fragment
fn fs_bare(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4(p.z, 0.5, 0.2, 1.0);
}
