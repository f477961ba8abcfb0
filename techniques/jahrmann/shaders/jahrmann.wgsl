// jahrmann: Bezier blades simulated and culled on the GPU (Jahrmann & Wimmer 2017), drawn by
// vertex pulling with Ghost of Tsushima's two levels of detail. One module, two pipelines: the
// compute pass `cs_simulate` (forces, collision, validation, culling, compaction) and the blade
// draws `vs_near` / `vs_far` + `fs_blade`. See `techniques/jahrmann/src/lib.rs`; `sim.rs` and
// `cull.rs` are the CPU twins of `simulate`, `cull` and `width_scale`. Composed after the
// prelude.

// ---- shared ---------------------------------------------------------------------------------

struct Params {
    // The frustum planes of this frame's camera, (n, d) with n·p + d >= 0 inside, normalised.
    planes: array<vec4<f32>, 6>,
    // xyz: the eye (the frustum's apex); w: side of the tiles levels are chosen for (m; 0: per blade)
    eye: vec4<f32>,
    // rgb: root albedo; w: colour variation
    color_root: vec4<f32>,
    // rgb: tip albedo; w: translucency
    color_tip: vec4<f32>,
    // x: recovery (1/s per unit stiffness); y: gravity (m/s²); z: wind response; w: front gravity share
    forces: vec4<f32>,
    // x: orientation threshold; y: frustum tolerance (m); z: cull distance d_max (m); w: distance fade (m)
    cull: vec4<f32>,
    // x: lod distance (m); y: band (m); z: far widening; w: orientation fade
    lod: vec4<f32>,
    // x: thinning distance D (m; 0: off); yzw: unused
    thin: vec4<f32>,
    // x: switches (FLAG_*); y: distance buckets; z: far level keeps one blade in z; w: unused
    flags: vec4<u32>,
    // x: blades; y: workgroups along x; z: unused (the dispatched ranges are counted in
    // `block`); w: 1 when the pass runs over the ranges, 0 when over every blade
    counts: vec4<u32>,
}

const FLAG_ORIENTATION: u32 = 1u;
const FLAG_FRUSTUM: u32 = 2u;
const FLAG_DISTANCE: u32 = 4u;
const FLAG_LOD: u32 = 8u;
const FLAG_TRANSITIONS: u32 = 16u;

// Verdicts (cull.rs's `Verdict`).
const NEAR: u32 = 0u;
const FAR: u32 = 1u;
const REPRESENTED: u32 = 2u;
const CULLED_ORIENTATION: u32 = 3u;
const CULLED_FRUSTUM: u32 = 4u;
const CULLED_DISTANCE: u32 = 5u;
const VERDICTS: u32 = 6u;

// Segments of the two levels: 2·7 + 1 = 15 vertices near, 2·3 + 1 = 7 far (Ghost of Tsushima).
const NEAR_SEGMENTS: u32 = 7u;
const FAR_SEGMENTS: u32 = 3u;

const UP: vec3<f32> = vec3(0.0, 1.0, 0.0);
const SURVIVOR_SALT: u32 = 0x68bc21ebu;
const THIN_SALT: u32 = 0x2f6b9d45u;

@group(1) @binding(0) var<uniform> params: Params;
// Root xyz, orientation.
@group(1) @binding(1) var<storage, read> blade_v0: array<vec4<f32>>;
// Height, width, colour variation, the blade's scene index (its hashes' input).
@group(1) @binding(3) var<storage, read> blade_looks: array<vec4<f32>>;

fn has(flag: u32) -> bool {
    return (params.flags.x & flag) != 0u;
}

// Unit width direction of a blade of `orientation`.
fn width_dir(orientation: f32) -> vec3<f32> {
    return vec3(cos(orientation), 0.0, sin(orientation));
}

// The distance bucket of blade `id`.
fn bucket(id: u32) -> u32 {
    return hash_u32(id) % max(params.flags.y, 1u);
}

// Whether blade `id` is one the far level keeps.
fn survivor(id: u32) -> bool {
    return hash_u32(id ^ SURVIVOR_SALT) % max(params.flags.z, 1u) == 0u;
}

// Ground distance up to which the distance test keeps blade `id`: its bucket's, and D / √u
// beyond the thinning distance D (cull.rs's `distance_cutoff`).
fn distance_cutoff(id: u32) -> f32 {
    let n = max(params.flags.y, 1u);
    let cutoff = params.cull.z * (1.0 - f32(bucket(id)) / f32(n));
    // By `select`: a branch on the uniform alone can have lavapipe re-specialise the shader
    // whenever it is bound (`grassbench::shaders::uniform_branches`).
    let u = f32(hash_u32(id ^ THIN_SALT) >> 8u) / 16777216.0;
    return select(cutoff, min(cutoff, params.thin.x / sqrt(u)), params.thin.x > 0.0);
}

// The width factor making up for the thinning at ground distance `d` (cull.rs's `thin_widen`).
fn thin_widen(d: f32) -> f32 {
    if (has(FLAG_DISTANCE) && params.thin.x > 0.0 && d > params.thin.x) {
        let r = d / params.thin.x;
        return r * r;
    }
    return 1.0;
}

// Horizontal distance from the eye to the root (the paper's d_proj).
fn ground_distance(v0: vec3<f32>) -> f32 {
    let d = v0 - params.eye.xyz;
    return length(d - UP * dot(d, UP));
}

// |view · width|: 1 edge-on, 0 face-on; 0 at the eye.
fn edge_on(v0: vec3<f32>, orientation: f32) -> f32 {
    let d = v0 - params.eye.xyz;
    let len = length(d);
    if (len < 1e-6) {
        return 0.0;
    }
    return abs(dot(d / len, width_dir(orientation)));
}

// The distance that chooses a root's level: its tile's centre's (cull.rs's `level_distance`).
fn level_distance(v0: vec3<f32>) -> f32 {
    let tile = params.eye.w;
    let untiled = tile <= 0.0;
    // By `select`, like `distance_cutoff`; the unused side kept finite.
    let side = select(tile, 1.0, untiled);
    let centre = (floor(v0.xz / side) + 0.5) * side;
    return select(distance(vec3(centre.x, v0.y, centre.y), params.eye.xyz), distance(v0, params.eye.xyz), untiled);
}

// Where blades leave the near level.
fn far_start() -> f32 {
    return params.lod.x + select(0.0, params.lod.y, has(FLAG_TRANSITIONS));
}

// ---- simulation (sim.rs) --------------------------------------------------------------------

// Rest tip xyz, stiffness.
@group(1) @binding(2) var<storage, read> blade_rest: array<vec4<f32>>;
// The tips after the previous step.
@group(1) @binding(4) var<storage, read> v2_in: array<vec4<f32>>;
// The tips after this step.
@group(1) @binding(6) var<storage, read_write> v2_out: array<vec4<f32>>;

// Half of a visible blade's entry in the draw list: the blade's root (xyz, orientation) and
// looks, or this step's guide and tip. The compute pass appends the whole state the draw
// needs, so the draw reads its list slot after slot rather than blades by index out of arrays
// sized for the terrain; two bindings of 32 bytes a slot, so each stays within the storage
// binding limit up to as many blades as the per-blade arrays of 16.
struct DrawHalf {
    a: vec4<f32>,
    b: vec4<f32>,
}

// Visible blades: near level from the front, far level from the back, as roots and looks (7)
// and curves (5), slot for slot.
@group(1) @binding(7) var<storage, read_write> visible_roots: array<DrawHalf>;
@group(1) @binding(5) var<storage, read_write> visible_curves: array<DrawHalf>;

struct DrawArgs {
    vertex_count: u32,
    instance_count: atomic<u32>,
    first_vertex: u32,
    first_instance: u32,
}

// The indirect draws and what the pass counted (counts.rs's `GpuCounts`).
struct Counters {
    near: DrawArgs,
    far: DrawArgs,
    // Blades per verdict (NEAR .. CULLED_DISTANCE).
    verdicts: array<atomic<u32>, 6>,
    // Near-level blades inside the hand-over band.
    in_band: atomic<u32>,
    // Blades not dispatched this frame (written by the CPU, tiles.rs).
    skipped: u32,
    // Of those, far non-survivors counted as represented (tiles.rs).
    represented_untested: u32,
    // The frame's dispatched ranges (written by the CPU, tiles.rs): a storage value, as a
    // loop bound in a uniform is re-specialised by lavapipe at every bind.
    ranges: u32,
}

// The counters, then the frame's dispatched ranges of blades (tiles.rs: first invocation,
// first blade, end, 0), written by the CPU; one buffer, so the pass binds no more than the
// 8 storage buffers WebGPU guarantees.
struct CountBlock {
    counts: Counters,
    ranges: array<vec4<u32>>,
}

@group(1) @binding(8) var<storage, read_write> block: CountBlock;

struct Curve {
    v1: vec3<f32>,
    v2: vec3<f32>,
}

// The blade's front: horizontal, perpendicular to its width, on the side it leans to at rest.
fn front_dir(orientation: f32, rest_offset: vec3<f32>) -> vec3<f32> {
    let f = vec3(-sin(orientation), 0.0, cos(orientation));
    return select(f, -f, dot(f, rest_offset) < 0.0);
}

// The wind's force on the tip: the wind times the alignment f_d·f_r (Sec. 5.1), times
// wind_response·h.
fn wind_force(v0: vec3<f32>, v2: vec3<f32>, height: f32, wind: vec3<f32>) -> vec3<f32> {
    let speed = length(wind);
    let d = v2 - v0;
    let len = length(d);
    if (speed < 1e-6 || len < 1e-6) {
        return vec3(0.0);
    }
    let f_d = 1.0 - abs(dot(wind / speed, d / len));
    let f_r = max(dot(d, UP) / height, 0.0);
    return wind * (params.forces.z * height * f_d * f_r);
}

// The tip after one step's forces: Hooke's recovery towards the rest tip (implicit), gravity
// with the front gravity, wind.
fn apply_forces(v0: vec3<f32>, orientation: f32, rest_tip: vec3<f32>, stiffness: f32, height: f32, v2: vec3<f32>, wind: vec3<f32>, dt: f32) -> vec3<f32> {
    let s = params.forces.x * stiffness;
    let g_e = vec3(0.0, -params.forces.y, 0.0);
    let g_f = front_dir(orientation, rest_tip - v0) * (params.forces.w * params.forces.y);
    let w = wind_force(v0, v2, height, wind);
    return (v2 + (rest_tip * s + g_e + g_f + w) * dt) / (1.0 + s * dt);
}

// The translation that moves `p` out of `sphere` (centre, radius; radius 0: none).
fn push_out(p: vec3<f32>, sphere: vec4<f32>) -> vec3<f32> {
    let d = p - sphere.xyz;
    let dist = length(d);
    if (sphere.w <= 0.0 || dist >= sphere.w) {
        return vec3(0.0);
    }
    let dir = select(UP, d / dist, dist > 1e-6);
    return dir * (sphere.w - dist);
}

// Shortest chord |v2 − v0| as a fraction of the height (sim.rs's MIN_CHORD).
const MIN_CHORD: f32 = 0.5;

// The tip moved out horizontally, keeping its rise, until the chord is MIN_CHORD of the
// height: a blade pushed down folds over instead of into a hairpin (sim.rs's `keep_chord`).
fn keep_chord(v0: vec3<f32>, v2: vec3<f32>, height: f32, front: vec3<f32>) -> vec3<f32> {
    let d = v2 - v0;
    let least = MIN_CHORD * height;
    if (length(d) >= least) {
        return v2;
    }
    let flat = vec3(d.x, 0.0, d.z);
    let flat_len = length(flat);
    let dir = select(front, flat / flat_len, flat_len > 1e-6 * height);
    let rise = min(d.y, least);
    return v0 + dir * sqrt(max(least * least - rise * rise, 0.0)) + UP * rise;
}

// The guide point placed from the tip (Sec. 5.2).
fn place_v1(v0: vec3<f32>, v2: vec3<f32>, height: f32) -> vec3<f32> {
    let d = v2 - v0;
    let l_proj = length(d - UP * dot(d, UP));
    let ratio = l_proj / height;
    return v0 + UP * (height * max(1.0 - ratio, 0.05 * max(ratio, 1.0)));
}

// The curve scaled about v0 so that the paper's length estimate is the blade's height.
fn correct_length(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, height: f32) -> Curve {
    let l0 = distance(v2, v0);
    let l1 = distance(v1, v0) + distance(v2, v1);
    let l = (2.0 * l0 + l1) / 3.0;
    let r = height / max(l, 1e-6);
    let c1 = v0 + (v1 - v0) * r;
    return Curve(c1, c1 + (v2 - v1) * r);
}

// One step of one blade: forces, collision with `sphere`, validation (sim.rs's `step`).
fn simulate(v0: vec3<f32>, orientation: f32, rest_tip: vec3<f32>, stiffness: f32, height: f32, v2_prev: vec3<f32>, wind: vec3<f32>, sphere: vec4<f32>, dt: f32) -> Curve {
    var v2 = apply_forces(v0, orientation, rest_tip, stiffness, height, v2_prev, wind, dt);
    v2 += push_out(v2, sphere);
    let m = v0 * 0.25 + place_v1(v0, v2, height) * 0.5 + v2 * 0.25;
    v2 += push_out(m, sphere) * 4.0;
    v2.y = max(v2.y, terrain_height(v2.xz));
    v2 = keep_chord(v0, v2, height, front_dir(orientation, rest_tip - v0));
    let v1 = place_v1(v0, v2, height);
    var c = correct_length(v0, v1, v2, height);
    c.v2.y = max(c.v2.y, terrain_height(c.v2.xz));
    return c;
}

// ---- culling (cull.rs) ----------------------------------------------------------------------

fn in_frustum(p: vec3<f32>) -> bool {
    let tolerance = params.cull.y;
    for (var k = 0u; k < 6u; k++) {
        let plane = params.planes[k];
        if (dot(plane.xyz, p) + plane.w < -tolerance) {
            return false;
        }
    }
    return true;
}

// The verdict on blade `id` with curve v0, v1, v2 (cull.rs's `verdict`).
fn cull(id: u32, v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, orientation: f32) -> u32 {
    if (has(FLAG_ORIENTATION) && edge_on(v0, orientation) > params.cull.x) {
        return CULLED_ORIENTATION;
    }
    if (has(FLAG_FRUSTUM)) {
        let m = v0 * 0.25 + v1 * 0.5 + v2 * 0.25;
        if (!(in_frustum(v0) || in_frustum(m) || in_frustum(v2))) {
            return CULLED_FRUSTUM;
        }
    }
    if (has(FLAG_DISTANCE) && ground_distance(v0) > distance_cutoff(id)) {
        return CULLED_DISTANCE;
    }
    if (has(FLAG_LOD) && level_distance(v0) >= far_start()) {
        return select(REPRESENTED, FAR, survivor(id));
    }
    return NEAR;
}

// ---- the compute pass -----------------------------------------------------------------------

const WORKGROUP: u32 = 64u;

var<workgroup> wg_verdicts: array<atomic<u32>, 6>;
var<workgroup> wg_in_band: atomic<u32>;
var<workgroup> wg_near: atomic<u32>;
var<workgroup> wg_far: atomic<u32>;
var<workgroup> wg_base: vec2<u32>;

// Halvings of the binary search over the dispatched ranges: ⌈log₂⌉ of the most ranges a frame
// can hold, set by the pipeline (`gpu.rs`), so every invocation runs the same trips and the
// op counter counts them.
override SEARCH_STEPS: u32;

// The blade of invocation `lid` of flat workgroup `w`, and whether there is one: over the
// ranges, invocation g = w·64 + lid falls in the last range starting at or before g (a
// binary search of SEARCH_STEPS halvings, each keeping the upper half where its first range
// starts at or before g); else it is blade g.
fn blade_of(w: u32, lid: u32) -> vec2<u32> {
    let g = w * WORKGROUP + lid;
    if (params.counts.w == 0u) {
        return vec2(g, u32(g < params.counts.x));
    }
    var lo = 0u;
    var len = block.counts.ranges;
    if (len == 0u) {
        return vec2(0u, 0u);
    }
    for (var step = 0u; step < SEARCH_STEPS; step++) {
        let half = len / 2u;
        let mid = lo + half;
        lo = select(lo, mid, half > 0u && block.ranges[mid].x <= g);
        len -= half;
    }
    let r = block.ranges[lo];
    let i = r.y + (g - r.x);
    return vec2(i, u32(g >= r.x && i < r.z));
}

// Simulates every blade dispatched, then culls it and appends the survivors of each level, with their state, to the draw lists:
// slots are handed out per workgroup (one global atomic per level and workgroup), so the draw
// lists are compact and their counts are the indirect draws' instance counts.
@compute @workgroup_size(64)
fn cs_simulate(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>) {
    let n = params.counts.x;
    let w = wid.y * params.counts.y + wid.x;
    if (w == 0u && lid == 0u) {
        block.counts.near.vertex_count = 2u * NEAR_SEGMENTS + 1u;
        block.counts.far.vertex_count = 2u * FAR_SEGMENTS + 1u;
    }
    let blade = blade_of(w, lid);
    let i = blade.x;
    var verdict = VERDICTS;
    var slot = 0u;
    var root = vec4(0.0);
    var looks = vec4(0.0);
    var curve = DrawHalf(vec4(0.0), vec4(0.0));
    if (blade.y == 1u) {
        root = blade_v0[i];
        let rest = blade_rest[i];
        looks = blade_looks[i];
        let v0 = root.xyz;
        let c = simulate(v0, root.w, rest.xyz, rest.w, looks.x, v2_in[i].xyz, wind_at(v0.xz), globals.object, globals.camera_forward.w);
        v2_out[i] = vec4(c.v2, 0.0);
        curve = DrawHalf(vec4(c.v1, 0.0), vec4(c.v2, 0.0));
        verdict = cull(u32(looks.w), v0, c.v1, c.v2, root.w);
        atomicAdd(&wg_verdicts[verdict], 1u);
        if (verdict == NEAR) {
            slot = atomicAdd(&wg_near, 1u);
            if (has(FLAG_LOD) && has(FLAG_TRANSITIONS) && level_distance(v0) > params.lod.x) {
                atomicAdd(&wg_in_band, 1u);
            }
        } else if (verdict == FAR) {
            slot = atomicAdd(&wg_far, 1u);
        }
    }
    workgroupBarrier();
    if (lid == 0u) {
        let near = atomicLoad(&wg_near);
        let far = atomicLoad(&wg_far);
        wg_base = vec2(atomicAdd(&block.counts.near.instance_count, near), atomicAdd(&block.counts.far.instance_count, far));
        for (var k = 0u; k < VERDICTS; k++) {
            let count = atomicLoad(&wg_verdicts[k]);
            if (count > 0u) {
                atomicAdd(&block.counts.verdicts[k], count);
            }
        }
        let band = atomicLoad(&wg_in_band);
        if (band > 0u) {
            atomicAdd(&block.counts.in_band, band);
        }
    }
    let base = workgroupUniformLoad(&wg_base);
    var at = n;
    if (verdict == NEAR) {
        at = base.x + slot;
    } else if (verdict == FAR) {
        at = n - 1u - (base.y + slot);
    }
    if (at < n) {
        visible_roots[at] = DrawHalf(root, looks);
        visible_curves[at] = curve;
    }
}

// ---- drawing --------------------------------------------------------------------------------

// The draw lists the compute pass wrote this frame (read-only views of bindings 7 and 5).
@group(1) @binding(11) var<storage, read> draw_roots: array<DrawHalf>;
@group(1) @binding(12) var<storage, read> draw_curves: array<DrawHalf>;

struct VsOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
    @location(3) ao: f32,
}

// What a vertex of the strip carries at parameter t along the curve.
struct StripPoint {
    center: vec3<f32>,
    half_width: f32,
    face: vec3<f32>,
    albedo: vec3<f32>,
    ao: f32,
}

fn bezier(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, t: f32) -> vec3<f32> {
    let u = 1.0 - t;
    return v0 * (u * u) + v1 * (2.0 * u * t) + v2 * (t * t);
}

fn bezier_tangent(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, t: f32) -> vec3<f32> {
    return (v1 - v0) * (2.0 * (1.0 - t)) + (v2 - v1) * (2.0 * t);
}

// The strip at t: the curve's point, the half width tapering to the tip as `reference`'s
// blades do, the face normal, and `reference`'s colour and ambient occlusion.
fn strip_point(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, side_axis: vec3<f32>, width: f32, variation: f32, t: f32) -> StripPoint {
    var p: StripPoint;
    p.center = bezier(v0, v1, v2, t);
    p.half_width = 0.5 * width * pow(1.0 - t, 0.7) * f32(t < 1.0);
    let tangent = bezier_tangent(v0, v1, v2, t);
    let face = cross(side_axis, tangent);
    p.face = select(vec3(0.0, 0.0, 1.0), normalize(face), length(face) > 1e-12);
    let v = variation * params.color_root.w;
    var albedo = mix(params.color_root.rgb, params.color_tip.rgb, pow(t, 0.8));
    albedo *= 1.0 + v;
    albedo.r *= 1.0 + 0.6 * max(v, 0.0);
    p.albedo = albedo;
    p.ao = mix(0.3, 1.0, t);
    return p;
}

fn mix_points(a: StripPoint, b: StripPoint, f: f32) -> StripPoint {
    var p: StripPoint;
    p.center = mix(a.center, b.center, f);
    p.half_width = mix(a.half_width, b.half_width, f);
    p.face = mix(a.face, b.face, f);
    p.albedo = mix(a.albedo, b.albedo, f);
    p.ao = mix(a.ao, b.ao, f);
    return p;
}

// Near-to-far band weight of a root at `d` from the eye (cull.rs's `band_weight`).
fn band_weight(d: f32) -> f32 {
    if (!(has(FLAG_LOD) && has(FLAG_TRANSITIONS))) {
        return 0.0;
    }
    return smoothstep(params.lod.x, params.lod.x + params.lod.y, d);
}

// The factor on the blade's width (cull.rs's `width_scale`).
fn width_scale(id: u32, v0: vec3<f32>, orientation: f32, far: bool) -> f32 {
    var scale = params.lod.z;
    if (!far) {
        let b = band_weight(level_distance(v0));
        scale = select(1.0 - b, 1.0 + (params.lod.z - 1.0) * b, survivor(id));
    }
    scale *= thin_widen(ground_distance(v0));
    if (has(FLAG_TRANSITIONS)) {
        if (has(FLAG_DISTANCE) && params.cull.w > 0.0) {
            let left = distance_cutoff(id) - ground_distance(v0);
            scale *= clamp(left / params.cull.w, 0.0, 1.0);
        }
        if (has(FLAG_ORIENTATION) && params.lod.w > 0.0) {
            let left = params.cull.x - edge_on(v0, orientation);
            scale *= clamp(left / params.lod.w, 0.0, 1.0);
        }
    }
    return scale;
}

// Blue (0) through green to red (1), for debug views.
fn heat(t: f32) -> vec3<f32> {
    let x = clamp(t, 0.0, 1.0);
    return clamp(vec3(2.0 * x - 0.5, 1.0 - abs(2.0 * x - 1.0), 1.5 - 2.0 * x), vec3(0.0), vec3(1.0)) * 0.6;
}

// Vertex `vertex` of the blade in slot `slot` of the draw lists, drawn with `segments` segments (the far level when `far`).
// Vertices alternate left (even) and right (odd) up the blade; the last is the tip. In the
// hand-over band the near level's vertices move onto the far level's strip (a geomorph), so
// the switch at the band's end changes nothing on screen.
fn blade_vertex(slot: u32, vertex: u32, segments: u32, far: bool) -> VsOut {
    var out: VsOut;
    let blade = draw_roots[slot];
    let curve = draw_curves[slot];
    let root = blade.a;
    let looks = blade.b;
    let id = u32(looks.w);
    let v0 = root.xyz;
    let v1 = curve.a.xyz;
    let v2 = curve.b.xyz;
    let side_axis = width_dir(root.w);
    let level = min(vertex / 2u, segments);
    let t = f32(level) / f32(segments);
    var p = strip_point(v0, v1, v2, side_axis, looks.y, looks.z, t);
    var morph = select(0.0, 1.0, far);
    if (!far) {
        morph = band_weight(level_distance(v0));
        if (morph > 0.0) {
            let coarse = t * f32(FAR_SEGMENTS);
            let j = min(floor(coarse), f32(FAR_SEGMENTS - 1u));
            let a = strip_point(v0, v1, v2, side_axis, looks.y, looks.z, j / f32(FAR_SEGMENTS));
            let b = strip_point(v0, v1, v2, side_axis, looks.y, looks.z, (j + 1.0) / f32(FAR_SEGMENTS));
            p = mix_points(p, mix_points(a, b, coarse - j), morph);
        }
    }
    let side = select(-1.0, 1.0, (vertex & 1u) == 1u);
    let half_width = p.half_width * width_scale(id, v0, root.w, far);
    let world = p.center + side_axis * (half_width * side);
    var albedo = p.albedo;
    // Debug views (`TechniqueInfo::debug_views`): 1 = level (near blue, band green, far red),
    // 2 = tilt of the tip from the vertical.
    albedo = select(albedo, heat(select(0.1 + 0.8 * morph, 1.0, far)), globals.frame.z == 1u);
    albedo = select(albedo, heat(1.0 - dot(normalize(v2 - v0), UP)), globals.frame.z == 2u);
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    out.normal = normalize(p.face + side_axis * side * 0.35);
    out.albedo = albedo;
    out.ao = p.ao;
    return out;
}

@vertex
fn vs_near(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> VsOut {
    return blade_vertex(instance, vertex, NEAR_SEGMENTS, false);
}

@vertex
fn vs_far(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> VsOut {
    return blade_vertex(params.counts.x - 1u - instance, vertex, FAR_SEGMENTS, true);
}

@fragment
fn fs_blade(in: VsOut) -> @location(0) vec4<f32> {
    let lit = shade_leaf(in.albedo, normalize(in.normal), in.world, in.ao, params.color_tip.w);
    return vec4(apply_fog(lit, in.world), 1.0);
}
