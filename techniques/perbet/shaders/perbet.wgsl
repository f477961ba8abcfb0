// Perbet & Cani 2001: a prairie of patches, each drawn as 3D blades (chains of segments),
// 2.5D strips (vertical polygon strips with semi-transparent textures) or a 2D texture on a
// surface offset above the ground; see `techniques/perbet/src/lib.rs`. Composed after the
// prelude. Three pipelines: `vs_flat`, `vs_strip`, `vs_blade` (drawn in that order: far to near).

struct Params {
    // x: patch size (m); y: strip height (m); z: strip margin (fraction of the patch);
    // w: height of the 2D surface above the ground (m)
    sizes: vec4<f32>,
    // x: blades per patch; y: segments per blade (= strip rows; the shader reads `SEGMENTS`);
    // z: strips per orientation; w: polygons along a strip
    counts: vec4<u32>,
    // x: postures K per kind; y: variants; z: 2D grid cells per patch side; w: the kind strip
    // edges bend as
    more: vec4<u32>,
    color_root: vec4<f32>,  // rgb; w: colour variation
    color_tip: vec4<f32>,   // rgb; w: translucency
    // x: index of the first strips entry; y: index of the first 2D entry
    bases: vec4<u32>,
    // xyz: elevations (radians) the three 2D textures of a variant were rendered from
    flat_elevations: vec4<f32>,
    // x, y: patches of the tiling along x and z (its corner is the terrain's, `globals.terrain.xy`)
    tiling: vec4<u32>,
}

// Segments per blade (= strip rows), set when the pipelines are created: the blades' and the
// strip edges' walks loop over them, and a loop bounded by a uniform is re-specialised by
// lavapipe every time its pipeline is bound (`grassbench::shaders::uniform_bound_loops`).
override SEGMENTS: u32;

// One drawn patch in one representation (`Entry` in `src/frame.rs`).
struct Entry {
    origin: vec2<f32>,  // world xz of the patch's corner
    variant: u32,
    flags: u32,         // bit 0: strip orientation (0: planes of constant z); bit 1: strips far to near reversed
    opacity: f32,
    morph: f32,         // 3D blades: 0 at their own shape, 1 at their painted target (Sec. 4.2)
    grow: f32,          // strips: 1 standing, 0 sunk into the ground (Sec. 4.3)
    link: u32,          // 3D blades in a morph: the entry of the same patch's strips; 2D: patches spanned along x (low 16 bits) and z (high 16 bits)
}

struct Blade {
    root_facing: vec4<f32>,  // root x, z in the patch; facing; height
    shape: vec4<f32>,        // width, colour variation, density threshold, -
    strips: vec4<u32>,       // the strip painting it, per orientation; its kind of grass
}

@group(1) @binding(0) var<uniform> params: Params;
@group(1) @binding(1) var<storage, read> entries: array<Entry>;
@group(1) @binding(2) var<storage, read> blades: array<Blade>;
@group(1) @binding(3) var<storage, read> tilts: array<vec2<f32>>;
@group(1) @binding(4) var<storage, read> painted: array<vec2<f32>>;
@group(1) @binding(5) var<storage, read> postures: array<f32>;
@group(1) @binding(6) var<storage, read> blade_receivers: array<vec4<f32>>;
@group(1) @binding(7) var<storage, read> edge_receivers: array<vec4<f32>>;
@group(1) @binding(8) var strip_color: texture_2d_array<f32>;
@group(1) @binding(9) var strip_aux: texture_2d_array<f32>;
@group(1) @binding(10) var flat_color: texture_2d_array<f32>;
@group(1) @binding(11) var flat_aux: texture_2d_array<f32>;
@group(1) @binding(12) var clamp_sampler: sampler;
@group(1) @binding(13) var repeat_sampler: sampler;
// The pre-computed patch each patch of the tiling shows, row-major (2D fragments look theirs up).
@group(1) @binding(14) var<storage, read> variants: array<u32>;

const UP: vec3<f32> = vec3(0.0, 1.0, 0.0);
const HIDDEN: vec4<f32> = vec4(0.0, 0.0, 2.0, 1.0);
// The two triangles of a quad, as (column, row) offsets.
const QUAD: array<vec2<u32>, 6> = array(
    vec2(0u, 0u), vec2(1u, 0u), vec2(0u, 1u), vec2(0u, 1u), vec2(1u, 0u), vec2(1u, 1u),
);

struct VsOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
    @location(3) uv: vec2<f32>,
    @location(4) opacity: f32,
    @location(5) ao: f32,
    @location(6) @interpolate(flat) layer: u32,
    // Impostors: the density the grass grows at under the vertex (0 where none grows), so the
    // fragments test their texels' thresholds without reading the maps themselves.
    @location(7) density: f32,
}

// --- Receivers and postures (Sec. 3.2) ------------------------------------------------------

// Bend angle of segment `i` of a blade of `kind` at posture `index`: linear between the two
// nearest pre-computed postures of its kind (twin of `receiver::angles_at`).
fn bend_angle(kind: u32, index: f32, i: u32) -> f32 {
    let k = params.more.x;
    let n = SEGMENTS;
    let u = (clamp(index, -1.0, 1.0) + 1.0) * f32(k - 1u) * 0.5;
    let row = min(u32(floor(u)), k - 2u);
    let at = (kind * k + row) * n + i;
    return mix(postures[at], postures[at + n], u - f32(row));
}

// Unit direction of a segment tilted by `t` (direction of the tilt, length the angle; twin of
// `patch::segment_direction`).
fn segment_direction(t: vec2<f32>) -> vec3<f32> {
    let a = length(t);
    if (a < 1e-6) {
        return UP;
    }
    let h = t / a * sin(a);
    return vec3(h.x, cos(a), h.y);
}

fn in_terrain(xz: vec2<f32>) -> bool {
    let uv = terrain_uv(xz);
    return all(uv >= vec2(0.0)) && all(uv <= vec2(1.0));
}

// The density map at `xz` where the covering map says grass, 0 elsewhere and off the terrain: a
// blade (or texel) of density threshold t grows where t < grass_density.
fn grass_density(xz: vec2<f32>) -> f32 {
    if (!in_terrain(xz) || terrain_covering(xz) != COVER_GRASS) {
        return 0.0;
    }
    return terrain_density(xz);
}

// --- Strips (Sec. 2.1, Fig. 3) ---------------------------------------------------------------

// World xz of texture coordinate `u` on strip `k` of entry `e` (`Layout::strip_xz`).
fn strip_xz(e: Entry, k: u32, u: f32) -> vec2<f32> {
    let size = params.sizes.x;
    let m = params.sizes.z;
    let along = (u * (1.0 + 2.0 * m) - m) * size;
    let across = (f32(k) + 0.5) * size / f32(params.counts.z);
    return e.origin + select(vec2(across, along), vec2(along, across), (e.flags & 1u) == 0u);
}

// Point at height `level` (in segments, fractional) of edge `j` of strip `k` of the strips
// entry `e`, the `slot`-th strips entry: the edge's receiver bends it like a blade (twin of
// `morph::edge_point`).
fn edge_point(e: Entry, slot: u32, k: u32, j: u32, level: f32) -> vec3<f32> {
    let n = SEGMENTS;
    let xz = strip_xz(e, k, f32(j) / f32(params.counts.w));
    let r = edge_receivers[(slot * params.counts.z + k) * (params.counts.w + 1u) + j];
    let d = vec3(r.x, 0.0, r.y);
    let segment = params.sizes.y / f32(n);
    // Sec. 4.3: strips grow from (sink into) the ground.
    var p = vec3(xz.x, terrain_height(xz) - (1.0 - e.grow) * params.sizes.y, xz.y);
    for (var i = 0u; i < n; i++) {
        let t = clamp(level - f32(i), 0.0, 1.0);
        let a = bend_angle(params.more.w, r.z, i);
        p += segment * t * (sin(a) * d + cos(a) * UP);
    }
    return p;
}

// The animated strip surface at texture coordinates `uv` (v up): between its two edges (twin of
// `morph::strip_surface`).
fn strip_surface(e: Entry, slot: u32, k: u32, uv: vec2<f32>) -> vec3<f32> {
    let c = params.counts.w;
    let x = clamp(uv.x, 0.0, 1.0) * f32(c);
    let j = min(u32(floor(x)), c - 1u);
    let level = clamp(uv.y, 0.0, 1.0) * f32(SEGMENTS);
    return mix(edge_point(e, slot, k, j, level), edge_point(e, slot, k, j + 1u, level), x - f32(j));
}

// The face normal of the blade painted on a texel, from its stored angle (`paint::Image::aux`):
// strips are lit blade by blade like the 3D blades (`shade_leaf` turns it to the eye).
fn painted_normal(face: f32) -> vec3<f32> {
    let a = face * PI;
    return vec3(-sin(a), 0.0, cos(a));
}

// Debug view 1: blue 2D, green strips, red 3D.
fn lod_tint(albedo: vec3<f32>, lod: vec3<f32>) -> vec3<f32> {
    return select(albedo, lod * 0.3, globals.frame.z == 1u);
}

@vertex
fn vs_strip(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> VsOut {
    var out: VsOut;
    let s = params.counts.z;
    let slot = instance / s;
    let e = entries[params.bases.x + slot];
    if (e.opacity <= 0.0 || e.grow <= 0.0) {
        out.position = HIDDEN;
        return out;
    }
    // Far strips first (Sec. 2.2: back to front, no polygon sorting).
    let order = instance % s;
    let k = select(order, s - 1u - order, (e.flags & 2u) != 0u);
    let c = params.counts.w;
    let q = vertex / 6u;
    let corner = QUAD[vertex % 6u];
    let j = q % c + corner.x;
    let row = q / c + corner.y;
    let world = edge_point(e, slot, k, j, f32(row));
    let o = e.flags & 1u;
    out.density = grass_density(strip_xz(e, k, f32(j) / f32(c)));
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    out.uv = vec2(f32(j) / f32(c), 1.0 - f32(row) / f32(SEGMENTS));
    out.opacity = e.opacity;
    out.layer = (e.variant * 2u + o) * s + k;
    out.albedo = lod_tint(vec3(1.0), vec3(0.0, 1.0, 0.0));
    return out;
}

@fragment
fn fs_strip(in: VsOut) -> @location(0) vec4<f32> {
    let c = textureSample(strip_color, clamp_sampler, in.uv, in.layer);
    let aux = textureSample(strip_aux, clamp_sampler, in.uv, in.layer);
    let alpha = c.a * in.opacity;
    // Patches are drawn far to near, so even faint texels may write depth: keep them all.
    if (alpha < 0.004 || aux.x >= in.density) {
        discard;
    }
    let albedo = select(c.rgb, in.albedo, globals.frame.z == 1u);
    let lit = shade_leaf(albedo, painted_normal(aux.z), in.world, mix(0.3, 1.0, aux.y), params.color_tip.w);
    return vec4(apply_fog(lit, in.world), alpha);
}

// --- 2D (Sec. 2.1, 4.3) ----------------------------------------------------------------------

// A 2D entry is a block of patches (one patch near the camera, up to 8 x 8 far away,
// `src/blocks.rs`): one terrain-following grid over the block, whose fragments find their own
// patch, its variant and its texture coordinates, so a block draws what its patches would.
@vertex
fn vs_flat(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> VsOut {
    var out: VsOut;
    let e = entries[params.bases.y + instance];
    if (e.opacity <= 0.0) {
        out.position = HIDDEN;
        return out;
    }
    let g = params.more.z;
    let q = vertex / 6u;
    let corner = QUAD[vertex % 6u];
    let cell = vec2(q % g + corner.x, q / g + corner.y);
    let extent = vec2(f32(e.link & 0xffffu), f32(e.link >> 16u));
    let xz = e.origin + vec2<f32>(cell) / f32(g) * extent * params.sizes.x;
    // The texture lies on an offset of the terrain at mid-blade height (Sec. 4.3).
    let world = vec3(xz.x, terrain_height(xz) + params.sizes.w, xz.y);
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    // In patches from the tiling's corner: the integer part is the patch, the texture repeats.
    out.uv = (xz - globals.terrain.xy) / params.sizes.x;
    out.opacity = e.opacity;
    out.albedo = lod_tint(vec3(1.0), vec3(0.0, 0.0, 1.0));
    return out;
}

// The two 2D texture layers of `variant` nearest the elevation `world` is seen at, and the
// weight of the second.
fn flat_layers(variant: u32, world: vec3<f32>) -> vec3<f32> {
    let to_eye = normalize(globals.camera_pos.xyz - world);
    let elevation = asin(clamp(to_eye.y, 0.0, 1.0));
    let e = params.flat_elevations;
    var t = 0.0;
    if (elevation <= e.y) {
        t = clamp((elevation - e.x) / (e.y - e.x), 0.0, 1.0);
    } else {
        t = 1.0 + clamp((elevation - e.y) / (e.z - e.y), 0.0, 1.0);
    }
    let first = min(floor(t), 1.0);
    return vec3(f32(variant * 3u) + first, f32(variant * 3u) + first + 1.0, t - first);
}

@fragment
fn fs_flat(in: VsOut) -> @location(0) vec4<f32> {
    let tile = clamp(vec2<i32>(floor(in.uv)), vec2(0), vec2<i32>(params.tiling.xy) - 1);
    let variant = variants[u32(tile.y) * params.tiling.x + u32(tile.x)];
    let layers = flat_layers(variant, in.world);
    let a = u32(layers.x);
    let b = u32(layers.y);
    let c = mix(textureSample(flat_color, repeat_sampler, in.uv, a), textureSample(flat_color, repeat_sampler, in.uv, b), layers.z);
    let aux = mix(textureSample(flat_aux, repeat_sampler, in.uv, a), textureSample(flat_aux, repeat_sampler, in.uv, b), layers.z);
    let alpha = c.a * in.opacity;
    // The density per fragment: a block's vertices are too far apart to carry it.
    if (alpha < 0.004 || aux.x >= grass_density(in.world.xz)) {
        discard;
    }
    let albedo = select(c.rgb, in.albedo, globals.frame.z == 1u);
    // Blades of every facing are averaged in a texel: lit as blades facing the viewer.
    let to_eye = globals.camera_pos.xyz - in.world;
    let n = normalize(vec3(to_eye.x, 0.0, to_eye.z) + vec3(0.0, 1e-4, 0.0));
    let lit = shade_leaf(albedo, n, in.world, mix(0.3, 1.0, aux.y), params.color_tip.w);
    return vec4(apply_fog(lit, in.world), alpha);
}

// --- 3D blades (Sec. 2.1, Fig. 2; morphing Sec. 4.2) ------------------------------------------

// Sec. 4.2: during a 3D <-> 2.5D transition, point `level` of blade `b` of the 3D entry `e`,
// at `p` in its own animated shape, moves linearly (`e.morph` of the way) towards the place its
// painted copy has on the animated strip of the same patch (twin of `morph::morphed`).
fn morphed(p: vec3<f32>, e: Entry, b: u32, level: u32) -> vec3<f32> {
    if (e.morph <= 0.0) {
        return p;
    }
    let o = e.flags & 1u;
    let uv = painted[(b * 2u + o) * (SEGMENTS + 1u) + level];
    let strips = entries[e.link];
    let painted_at = strip_surface(strips, e.link - params.bases.x, blades[b].strips[o], uv);
    return mix(p, painted_at, e.morph);
}

@vertex
fn vs_blade(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> VsOut {
    var out: VsOut;
    let count = params.counts.x;
    let n = SEGMENTS;
    let e = entries[instance / count];
    let b = e.variant * count + instance % count;
    let blade = blades[b];
    let root_xz = e.origin + blade.root_facing.xy;
    if (e.opacity <= 0.0 || blade.shape.z >= grass_density(root_xz)) {
        out.position = HIDDEN;
        return out;
    }
    // The receiver's direction and posture index bend every segment on top of its rest tilt.
    let r = blade_receivers[instance];
    let height = blade.root_facing.w;
    let segment = height / f32(n);
    let level = min(vertex / 2u, n);
    var p = vec3(root_xz.x, terrain_height(root_xz), root_xz.y);
    var tangent = UP;
    for (var i = 0u; i < n; i++) {
        let dir = segment_direction(tilts[b * n + i] + r.xy * bend_angle(blade.strips.z, r.z, i));
        if (i < level) {
            p += segment * dir;
        }
        if (i == min(level, n - 1u)) {
            tangent = dir;
        }
    }
    p = morphed(p, e, b, level);
    let s = f32(level) / f32(n);
    let facing = blade.root_facing.z;
    let side_axis = vec3(cos(facing), 0.0, sin(facing));
    let half = 0.5 * blade.shape.x * pow(1.0 - s, 0.7);
    let side = select(-1.0, 1.0, (vertex & 1u) == 1u);
    let world = p + side_axis * half * side;
    let face = normalize(cross(side_axis, tangent));

    let v = blade.shape.y * params.color_root.w;
    var albedo = mix(params.color_root.rgb, params.color_tip.rgb, pow(s, 0.8)) * (1.0 + v);
    albedo.r *= 1.0 + 0.6 * max(v, 0.0);
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    out.normal = normalize(face + side_axis * side * 0.35);
    out.albedo = lod_tint(albedo, vec3(1.0, 0.0, 0.0));
    out.opacity = e.opacity;
    out.ao = mix(0.3, 1.0, s);
    return out;
}

@fragment
fn fs_blade(in: VsOut) -> @location(0) vec4<f32> {
    let lit = shade_leaf(in.albedo, normalize(in.normal), in.world, in.ao, params.color_tip.w);
    return vec4(apply_fog(lit, in.world), in.opacity);
}
