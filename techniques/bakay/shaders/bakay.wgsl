// Bakay, Lalonde, Heidrich 2002: animated transparent shells (see techniques/bakay/src/lib.rs).
// Composed after the prelude. Two entry points per frame:
// - `cs_bend` (compute) gives every ground vertex of the chunks drawn this frame its wind vector
//   V_w and intensity I and keeps the running sums (n_k, w_k) of every shell k (Sec. 3, Fig. 6;
//   mirrored on the CPU by src/wind.rs and src/bend.rs);
// - `vs_shell` / `fs_shell_*` draw the ground mesh once per shell (bottom to top), displaced by
//   N·n_k + V_w·w_k and alpha-tested against the shell's height (k/N, the paper's 255/N steps).
//   A far chunk's draw is at a level of detail L (src/lod.rs, a departure): its instances
//   L·LEVEL_INSTANCES + i draw every 2^L-th shell down from the top one, each alpha-tested
//   against the lowest shell it stands for.

struct Params {
    // x: shells N (the shader reads `SHELLS`); y: ground vertices; z: wind mode (0 = scene, 1 = point source);
    // w: ground vertices along x (a row of the mesh)
    counts: vec4<u32>,
    // x: inter-shell distance S (m); y: stiffness exponent p; z: max |I|; w: reference speed (m/s)
    shape: vec4<f32>,
    // xyz: point source position; w: period (s)
    source: vec4<f32>,
    // x: step length (m); y: step delay (s); z: bias; w: 1 / tile size (1/m)
    steps: vec4<f32>,
    // rgb: root albedo / tip albedo; w: translucency
    color_ratio: vec4<f32>,
}

@group(1) @binding(0) var<uniform> params: Params;

// Shells N, set when the pipelines are created: the bend pass loops over them, and a loop
// bounded by a uniform is re-specialised by lavapipe every time its pipeline is bound (5-6 ms
// a frame here; `grassbench::shaders::uniform_bound_loops`).
override SHELLS: u32;

// Cells a side of a chunk (`chunks::CHUNK`, set from it when the pipelines are created): the
// bend pass moves a chunk's (CHUNK + 1)² vertices, 64 a workgroup.
override CHUNK: u32 = 16u;

// Instance indices per level of detail (`lod::LEVEL_INSTANCES`).
const LEVEL_INSTANCES: u32 = 128u;
// Compute pass only: the shared ground mesh (GroundVertex = position xyz, normal xyz) and the
// per-vertex results.
@group(1) @binding(1) var<storage, read> ground: array<f32>;
@group(1) @binding(2) var<storage, read_write> wind_out: array<vec4<f32>>;
@group(1) @binding(3) var<storage, read_write> offsets_out: array<vec2<f32>>;
// The first cell (i, j) of every chunk drawn this frame (`chunks::Plan::bent`), in order.
@group(1) @binding(9) var<storage, read> bent_chunks: array<vec2<u32>>;
// Render pass only.
@group(1) @binding(4) var<storage, read> vertex_wind: array<vec4<f32>>;
@group(1) @binding(5) var<storage, read> offsets: array<vec2<f32>>;
@group(1) @binding(6) var color_height: texture_2d<f32>;
@group(1) @binding(7) var blade_attrs: texture_2d<f32>;
@group(1) @binding(8) var grass_sampler: sampler;

// Tilt of segment j: θ_j = I·(π/2)·(j/N)^p (Sec. 3: a constant increment per shell for p = 1;
// twin of `bend::tilt`).
fn tilt(j: u32, intensity: f32) -> f32 {
    let x = f32(j) / f32(SHELLS);
    let profile = select(pow(x, params.shape.y), 0.0, x <= 0.0);
    return intensity * 0.5 * PI * profile;
}

// V_w = W − (W·N)N, normalised; zero when W is along the normal or zero (twin of
// `wind::tangent_direction`).
fn tangent_direction(w: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let t = w - dot(w, n) * n;
    let l = length(t);
    return select(vec3(0.0), t / l, l > 1e-6);
}

// The wind vector V_w (xyz) and intensity I (w) of the ground vertex at `p` with unit normal
// `n` (Sec. 3; twin of `wind::point_source` and `wind::scene` in src/wind.rs).
fn ground_wind(p: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    let max_i = params.shape.z;
    var dir = vec3(0.0);
    var intensity = 0.0;
    if (params.counts.z == 1u) {
        // The paper's point source: W towards the source, the animation step by distance, and
        // the periodic intensity delayed by the step (waves across the field, Fig. 8).
        let to_source = params.source.xyz - p;
        let d = length(to_source);
        dir = tangent_direction(select(vec3(0.0), to_source / d, d > 0.0), n);
        let step = u32(d / params.steps.x);
        let phase = (globals.camera_pos.w - f32(step) * params.steps.y) / params.source.w;
        intensity = clamp(sin(2.0 * PI * phase) + params.steps.z, -max_i, max_i);
    } else {
        // The scene's wind field: only its tangential part bends the grass (Sec. 3).
        let wind = wind_at(p.xz);
        let tangential = wind - dot(wind, n) * n;
        dir = tangent_direction(wind, n);
        intensity = min(length(tangential) / params.shape.w, max_i);
    }
    return vec4(dir, intensity);
}

// Segment `k` of a blade at intensity I, one inter-shell distance S long: what it adds to the
// running totals (n, w) along the normal and the wind vector (Fig. 6; twin of
// `bend::segment` in src/bend.rs).
fn shell_segment(k: u32, intensity: f32) -> vec2<f32> {
    let a = tilt(k, intensity);
    return params.shape.x * vec2(cos(a), sin(a));
}

// Workgroup g moves vertices 64·(g % per_chunk) .. of chunk g / per_chunk, row by row
// (`gpu::BEND_WORKGROUPS_PER_CHUNK` workgroups a chunk; the dispatch has exactly that many a
// chunk); a chunk's vertices past the mesh's edges are skipped. Vertices on an edge two drawn
// chunks share are moved by both, to the same values.
@compute @workgroup_size(64)
fn cs_bend(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let side = CHUNK + 1u;
    let per_chunk = (side * side + 63u) / 64u;
    let local = (group.x % per_chunk) * 64u + lane;
    let origin = bent_chunks[group.x / per_chunk];
    let i = origin.x + local % side;
    let j = origin.y + local / side;
    let nx = params.counts.w;
    let v = j * nx + i;
    if (local >= side * side || i >= nx || v >= params.counts.y) {
        return;
    }
    let p = vec3(ground[6u * v], ground[6u * v + 1u], ground[6u * v + 2u]);
    let n = vec3(ground[6u * v + 3u], ground[6u * v + 4u], ground[6u * v + 5u]);
    let wind = ground_wind(p, n);
    wind_out[v] = wind;
    // Running totals up the blade, one segment of length S per shell (`bend::offsets`).
    var nw = vec2(0.0);
    for (var k = 0u; k < SHELLS; k++) {
        offsets_out[k * params.counts.y + v] = nw;
        nw += shell_segment(k, wind.w);
    }
}

struct ShellOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) tangent: vec3<f32>,
    // x: density map; y: 1 where the covering map says grass
    @location(3) grows: vec2<f32>,
    // x: the shell k drawn; y: the lowest shell it stands for (its alpha test)
    @location(4) @interpolate(flat) shell: vec2<u32>,
}

// The shell drawn by `instance` (level L = instance / LEVEL_INSTANCES, i-th from the bottom)
// and the lowest shell it stands for: every 2^L-th shell down from the top one, each standing
// for the 2^L - 1 below it too (twin of `lod::ShellLod::shell`).
fn level_shell(instance: u32) -> vec2<u32> {
    let n = SHELLS;
    let m = 1u << (instance / LEVEL_INSTANCES);
    let i = instance % LEVEL_INSTANCES;
    let drawn = (n - 1u) / m + 1u;
    let k = (n - 1u) - (drawn - 1u - i) * m;
    return vec2(k, select(0u, k + 1u - m, k + 1u >= m));
}

@vertex
fn vs_shell(
    @builtin(vertex_index) v: u32,
    @builtin(instance_index) instance: u32,
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
) -> ShellOut {
    let shell = level_shell(instance);
    let k = shell.x;
    let wind = vertex_wind[v];
    let nw = offsets[k * params.counts.y + v];
    let world = position + normal * nw.x + wind.xyz * nw.y;
    let a = tilt(k, wind.w);
    var out: ShellOut;
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    // The texture is attached to the ground point the blade grows from, so a blade's sections
    // move together with their shells.
    out.uv = position.xz * params.steps.w;
    out.tangent = normal * cos(a) + wind.xyz * sin(a);
    out.grows = vec2(terrain_density(position.xz), f32(terrain_covering(position.xz) == COVER_GRASS));
    out.shell = shell;
    return out;
}

// The fragment stage, one entry point for each way of picking the texture's mip level (the
// `lod` parameter picks one when the pipeline is made). Not one entry point branching on a
// uniform: a SIMD rasteriser runs both sides of such a branch, a lookup of each kind per
// texture (lavapipe: 7-9 ms of 54 on the meadow at 320x180 for a lookup no pixel keeps).

// `lod = "minor_axis"`: the mip level whose texels match the footprint's minor axis (the level
// anisotropic filtering picks), sampled once. At grazing angles the sampler's own choice, from
// the major axis, is many levels too coarse and blurs blades into felt (box mips) or blotches
// (custom mips). The footprint is taken before any discard (derivatives need uniform control
// flow).
@fragment
fn fs_shell_minor_axis(in: ShellOut) -> @location(0) vec4<f32> {
    let size = vec2<f32>(textureDimensions(color_height));
    let dx = dpdx(in.uv);
    let dy = dpdy(in.uv);
    let lod = max(log2(max(min(length(dx * size), length(dy * size)), 1e-6)), 0.0);
    let texel = textureSampleLevel(color_height, grass_sampler, in.uv, lod);
    if (shell_cut(in, texel)) {
        discard;
    }
    return shell_color(in, texel, textureSampleLevel(blade_attrs, grass_sampler, in.uv, lod));
}

// `lod = "hardware"`: the sampler picks the level (and filters anisotropically where the
// sampler's clamp allows) from the footprint, taken before any discard.
@fragment
fn fs_shell_hardware(in: ShellOut) -> @location(0) vec4<f32> {
    let dx = dpdx(in.uv);
    let dy = dpdy(in.uv);
    let texel = textureSampleGrad(color_height, grass_sampler, in.uv, dx, dy);
    if (shell_cut(in, texel)) {
        discard;
    }
    return shell_color(in, texel, textureSampleGrad(blade_attrs, grass_sampler, in.uv, dx, dy));
}

// The alpha test: shell k keeps the texels whose blade reaches its height k/N (a far chunk's
// shell: the lowest shell it stands for). Shell 0 is the ground, which the core draws: here it
// keeps the blades' roots only (alpha > 0). Grass grows only where the covering map says so.
// Tested first: most fragments of a shell end here, before the second lookup and the shading.
fn shell_cut(in: ShellOut, texel: vec4<f32>) -> bool {
    let lowest = f32(in.shell.y) / f32(SHELLS);
    return texel.a < max(lowest, 1.0 / 255.0) || in.grows.y < 0.5;
}

// A kept texel's colour, from its blade's attributes (`attrs`); discards it where the density
// map thins blades as the scene's blade field does (threshold < density).
fn shell_color(in: ShellOut, texel: vec4<f32>, attrs: vec4<f32>) -> vec4<f32> {
    if (attrs.r >= in.grows.x) {
        discard;
    }
    let height = f32(in.shell.x) / f32(SHELLS);
    // Relative height along this texel's blade: root colour below, tip colour above.
    let s = clamp(height / max(texel.a, 1e-3), 0.0, 1.0);
    let albedo = texel.rgb * mix(params.color_ratio.rgb, vec3(1.0), pow(s, 0.8));
    // A flat blade: its width runs along its facing angle, its face is normal to that and to
    // the (bent) blade direction.
    let t = normalize(in.tangent);
    let facing = attrs.g * PI;
    let side = vec3(cos(facing), 0.0, sin(facing));
    let face = cross(side, t);
    let normal = select(t, normalize(face), length(face) > 1e-4);
    let lit = shade_leaf(albedo, normal, in.world, mix(0.3, 1.0, s), params.color_ratio.w);
    return vec4(apply_fog(lit, in.world), 1.0);
}
