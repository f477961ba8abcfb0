// Boulanger, Pattanaik & Bouatouch 2006: geometric blades (Sec. 3.2), the start-up BTF bake of
// the vertical and horizontal slices (Sec. 3.3, Fig. 6-7, 10), the vertical slices of the mid
// band, the horizontal slice drawn over cells and macro-cells with the patch orientation map
// (Sec. 4.1, Eq. 6-7), and the BTF's light interpolation (Appendix A, Eq. 8-13). See
// `techniques/boulanger/src/lib.rs`. Composed after the prelude (group 0).

struct Params {
    color_root: vec4<f32>,  // rgb; w: colour variation
    color_tip: vec4<f32>,   // rgb; w: translucency
    // x: segments; y: gravity; z: wind response; w: ambient occlusion at the root
    blade: vec4<f32>,
    // x: min_geom; y: max_geom; z: omega (Eq. 5); w: alpha-test threshold
    lod: vec4<f32>,
    // x: patch size (m); y: slice height above ground (m); z: slice texture side; w: bake top (m)
    tile: vec4<f32>,
    // x: vertical slices per axis (N); y: min_btf; z: max_btf; w: 1 with the shadow mask
    btf: vec4<f32>,
}

@group(1) @binding(0) var<uniform> params: Params;
@group(1) @binding(1) var blade_texture: texture_2d<f32>;
@group(1) @binding(2) var clamp_sampler: sampler;
@group(1) @binding(3) var repeat_sampler: sampler;
// The shadow mask (Sec. 3.5, src/shadow.rs): coverage of a slab of the patch in alpha.
@group(1) @binding(4) var shadow_mask: texture_2d_array<f32>;
// Sec. 3.5's ambient occlusion map (src/occlusion.rs): the sky's share left by trees and
// stones, one value per covering-map sample.
@group(1) @binding(5) var ao_map: texture_2d<f32>;

// The ambient visibility at `xz` (samples on the terrain's corners, like the other maps).
fn ambient_visibility(xz: vec2<f32>) -> f32 {
    let dims = vec2<f32>(textureDimensions(ao_map));
    let uv = clamp(terrain_uv(xz), vec2(0.0), vec2(1.0));
    return textureSampleLevel(ao_map, clamp_sampler, (uv * (dims - 1.0) + 0.5) / dims, 0.0).r;
}

// One geometry cell's copy of the patch (Sec. 3.1). Instance `i` of a blade draw is blade
// `i % blade_count` of the cell in slot `i / blade_count` of this page of cells (the page is a
// dynamic offset), so runs of cells drawn whole merge into a single instanced draw.
struct Cell {
    // xy: world (x, z) of the patch centre; zw: mirror signs (-1 or 1) for x and z (Sec. 3.1)
    center_signs: vec4<f32>,
    // x: 1 when baking a slice (no terrain, wind, density or LOD); when baking, y: projection
    // (0 top view of the horizontal slice, 1 slice across x, 2 slice across z), z: the slice's
    // coordinate along its axis (m, from the patch centre), w: side of the orthographic camera
    // (+1 on the + side of the axis, -1 on the other); otherwise yzw: the cell's weights
    // (`cell_weight_geometry`)
    mode: vec4<f32>,
}
@group(2) @binding(0) var<storage, read> cells: array<Cell>;

// The patch's blades, sorted by block and, within a block, by density threshold.
struct Blade {
    root_azimuth_tilt: vec4<f32>,  // root (x, z) from the patch centre, azimuth, tilt
    shape: vec4<f32>,              // height, width, colour variation, density threshold
}
@group(2) @binding(4) var<storage, read> patch_blades: array<Blade>;

// The BTFs (slice pipelines only), three arrays of layers, every channel premultiplied by
// coverage: colour = (K_d, coverage) (Fig. 7's ambient row and alpha), diffuse = the two-sided
// diffuse factor for the lights Y+, X+, Z+, X- (Fig. 7's five rows), extra = (the diffuse factor
// for Z-, density threshold (Fig. 10), ambient occlusion, 0). The horizontal slice is one layer;
// vertical slice `i` across axis `a` (0 x, 1 z) seen from the + side is layer 2 (a N + i), from
// the - side the next.
@group(2) @binding(1) var slice_color: texture_2d_array<f32>;
@group(2) @binding(2) var slice_diffuse: texture_2d_array<f32>;
@group(2) @binding(3) var orientation_map: texture_2d<u32>;
@group(2) @binding(5) var slice_extra: texture_2d_array<f32>;
@group(2) @binding(6) var vslice_color: texture_2d_array<f32>;
@group(2) @binding(7) var vslice_diffuse: texture_2d_array<f32>;
@group(2) @binding(8) var vslice_extra: texture_2d_array<f32>;

// The bake's blades (bake pipeline only): instance `k` draws the blade `bake_refs[k]` of the
// blade pipeline's numbering (cell x blade count + blade), so each slice draws only the blades
// that reach its slab.
@group(3) @binding(0) var<storage, read> bake_refs: array<u32>;

// ---- Level of detail (twins of src/lod.rs) ----

fn clamp01(x: f32) -> f32 {
    return clamp(x, 0.0, 1.0);
}

// Eq. 2: weight of geometry at distance d.
fn weight_geometry(d: f32) -> f32 {
    return clamp01((d - params.lod.y) / (params.lod.x - params.lod.y));
}

// Eq. 5 on `1 - t` with the weight stretched so weight 1 draws every blade fully; omega 0 is
// the hard switch. Both sides and a `select`, not a branch: omega is a uniform, and a branch
// on a uniform alone had lavapipe re-specialise the blade vertex shaders every frame
// (`grassbench::shaders::uniform_branches`).
fn geometry_opacity(w_g: f32, t: f32, omega: f32) -> f32 {
    let key = 1.0 - t;
    let hard = omega <= 0.0;
    let soft = clamp01((w_g * (1.0 + 2.0 * omega) - key) / (2.0 * select(omega, 1.0, hard)));
    return select(soft, select(0.0, 1.0, key <= w_g), hard);
}

fn on_grass(xz: vec2<f32>) -> bool {
    let uv = terrain_uv(xz);
    return all(uv >= vec2(0.0)) && all(uv <= vec2(1.0)) && terrain_covering(xz) == COVER_GRASS;
}

// The far fade of the vertical slices: the second factor of Eq. 3.
fn vertical_fade(d: f32) -> f32 {
    return clamp01((d - params.btf.z) / (params.btf.y - params.btf.z));
}

// The weights a cell's draws use (twins of src/lod.rs `CellWeights`): `cell_w` = (0, 0, 0) by
// distance, Eq. 2 and Eq. 3's far fade per blade and per pixel (the seamless transitions); or
// (1, w_g, fade), one pair for the whole cell (levels switched per cell, without transitions).
fn cell_weight_geometry(cell_w: vec3<f32>, d: f32) -> f32 {
    return select(weight_geometry(d), cell_w.y, cell_w.x > 0.5);
}

fn cell_vertical_fade(cell_w: vec3<f32>, d: f32) -> f32 {
    return select(vertical_fade(d), cell_w.z, cell_w.x > 0.5);
}

// Eq. 5 for the far fade of the vertical slices: the blades with the lowest normalised
// thresholds stay longest (weight 1 keeps every blade, 0 none; see src/lod.rs).
fn fade_opacity(f: f32, t: f32, omega: f32) -> f32 {
    if (omega <= 0.0) {
        return select(0.0, 1.0, t <= f);
    }
    return clamp01((f * (1.0 + 2.0 * omega) - t) / (2.0 * omega));
}

// The share of a slice texel with threshold `dth` (Sec. 3.4, Fig. 11): the blade exists under
// the local density, the slices draw what geometry does not (times the vertical slices' far
// fade `f`, 1 for the horizontal slice). Where a pixel covers many texels (`texels` per pixel)
// the one averaged threshold means nothing: the expected fraction of the uniformly spread
// thresholds is drawn instead.
fn slice_share(dth: f32, density: f32, w_g: f32, f: f32, texels: f32) -> f32 {
    let omega = params.lod.z;
    var fine = 0.0;
    if (dth < density) {
        let t = dth / density;
        fine = (1.0 - geometry_opacity(w_g, t, omega)) * fade_opacity(f, t, omega);
    }
    var mean = 0.0;
    for (var k = 0u; k < 8u; k++) {
        let t = (f32(k) + 0.5) / 8.0;
        mean += (1.0 - geometry_opacity(w_g, t, omega)) * fade_opacity(f, t, omega);
    }
    let expected = density * mean / 8.0;
    let far = clamp(log2(max(texels, 1e-6)) - 0.5, 0.0, 1.0);
    return mix(fine, expected, far);
}

// ---- BTF light interpolation (Appendix A; twin of src/barycentric.rs) ----

// The five weights, Y+, X+, Z+, X- in `a` and Z- in `b`.
struct Weights {
    a: vec4<f32>,
    b: f32,
}

// Eq. 10-13: area of the spherical triangle L P Q, P and Q orthogonal axes, lp = l.P, lq = l.Q.
// A degenerate triangle (L on P or Q) has none. Chosen by `select`, not by an early return: the
// horizontal slices' vertex shaders call this with the sun's direction, a uniform, and a branch
// on it alone had lavapipe rebuild both of them every frame (`grassbench::shaders::uniform_branches`).
fn right_triangle_area(lp: f32, lq: f32) -> f32 {
    let sin_p = sqrt(max(1.0 - lp * lp, 0.0));
    let sin_q = sqrt(max(1.0 - lq * lq, 0.0));
    let degenerate = (sin_p < 1e-6) | (sin_q < 1e-6);
    // Finite on the unused side.
    let sp = select(sin_p, 1.0, degenerate);
    let sq = select(sin_q, 1.0, degenerate);
    let at_p = acos(clamp(lq / sp, -1.0, 1.0));
    let at_q = acos(clamp(lp / sq, -1.0, 1.0));
    let at_l = acos(clamp(-lp * lq / (sp * sq), -1.0, 1.0));
    return select(max(at_p + at_q + at_l - PI, 0.0), 0.0, degenerate);
}

// Eq. 8-9: the weights of the sampled directions for the light direction `light` (in the
// patch's own frame); a light below the horizon is taken at the horizon.
fn btf_weights(light: vec3<f32>) -> Weights {
    var l = vec3(light.x, max(light.y, 0.0), light.z);
    let len = length(l);
    l = select(vec3(0.0, 1.0, 0.0), l / len, len > 1e-6);
    let ax = abs(l.x);
    let az = abs(l.z);
    let quarter = 0.5 * PI;
    let wa = right_triangle_area(l.y, az) / quarter;
    let wb = right_triangle_area(az, ax) / quarter;
    let wc = right_triangle_area(ax, l.y) / quarter;
    var w: Weights;
    let px = select(0.0, 1.0, l.x >= 0.0);
    let pz = select(0.0, 1.0, l.z >= 0.0);
    w.a = vec4(wb, wa * px, wc * pz, wa * (1.0 - px));
    w.b = wc * (1.0 - pz);
    return w;
}

// Sum of alpha_i C_i with the weights renormalised per pixel (Appendix A).
fn btf_diffuse(d_a: vec4<f32>, d_b: f32, w: Weights) -> f32 {
    let sum = max(dot(w.a, vec4(1.0)) + w.b, 1e-6);
    return (dot(w.a, d_a) + w.b * d_b) / sum;
}

// Sec. 3.3's Lambert for a BTF texel at `world`: K_d I_a + (sum of alpha_i C_i) I_d for the sun
// and, if the scene has one, for the point light with I_d / (1 + beta d^2), each with its own
// weights; the ambient term darkened by the occlusion like the blades' `shade_leaf`.
fn btf_light(albedo: vec3<f32>, d_a: vec4<f32>, d_b: f32, sun: Weights, point: Weights, world: vec3<f32>, ao: f32) -> vec3<f32> {
    var direct = globals.sun_color.rgb * btf_diffuse(d_a, d_b, sun);
    if (globals.point_color.w > 0.0) {
        direct += point_light(world) * btf_diffuse(d_a, d_b, point);
    }
    // The occlusion map (Sec. 3.5) per pixel, below the texel.
    let sky = ambient_visibility(world.xz);
    return albedo * (globals.ambient.rgb * ao * sky + direct * direct_occlusion(ao));
}

// A cell mirrored in x (z) sees the light mirrored: X+ and X- (Z+ and Z-) swap weights.
fn mirror_weights(w: Weights, signs: vec2<f32>) -> Weights {
    var m: Weights;
    m.a = vec4(w.a.x, select(w.a.y, w.a.w, signs.x < 0.0), select(w.a.z, w.b, signs.y < 0.0), select(w.a.w, w.a.y, signs.x < 0.0));
    m.b = select(w.b, w.a.z, signs.y < 0.0);
    return m;
}

// The wind's sideways push on a blade's particle at `xz` (m/s x wind response, clamped so the
// particle model stays sane; 0 when animation is off).
fn wind_push(xz: vec2<f32>) -> vec2<f32> {
    let push = wind_at(xz).xz * params.blade.z;
    let p = length(push);
    return select(push, push * (1.5 / p), p > 1.5);
}

// ---- Geometric blades (Sec. 3.2) ----

struct BladeOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
    @location(3) uv: vec2<f32>,
    @location(4) ao_opacity: vec2<f32>,
    @location(5) threshold: f32,
    // Baking only: unit vector towards the slice's orthographic camera.
    @location(6) bake_view: vec3<f32>,
    // The blade's root (world) and the azimuth of its inclination (mirror applied).
    @location(7) @interpolate(flat) root: vec4<f32>,
    // The ambient visibility at the root (Sec. 3.5); 1 when baking.
    @location(8) @interpolate(flat) sky: f32,
}

@vertex
fn vs_blade(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> BladeOut {
    return blade_vertex(vertex, instance);
}

// The BTF bake: the blades listed for this slice only.
@vertex
fn vs_bake(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> BladeOut {
    return blade_vertex(vertex, bake_refs[instance]);
}

fn blade_vertex(vertex: u32, instance: u32) -> BladeOut {
    var out: BladeOut;
    let count = arrayLength(&patch_blades);
    let index = instance % count;
    let cell = cells[instance / count];
    let blade = patch_blades[index];
    let baking = cell.mode.x > 0.5;
    // The cell's mirrored version of the patch: a sign flip about the patch centre.
    let signs = cell.center_signs.zw;
    let root_xz = cell.center_signs.xy + blade.root_azimuth_tilt.xy * signs;
    let azimuth = blade.root_azimuth_tilt.z;
    let dir = vec2(cos(azimuth), sin(azimuth)) * signs;
    let tilt = blade.root_azimuth_tilt.w;
    let height = blade.shape.x;
    let dth = blade.shape.w;

    var ground = 0.0;
    var opacity = 1.0;
    var push = vec2(0.0);
    if (!baking) {
        // Sec. 3.4: the blade exists on grass where its threshold is under the local density;
        // Eq. 2 and 5 give geometry's share of it, the slices draw the rest.
        ground = terrain_height(root_xz);
        let density = terrain_density(root_xz);
        let d = distance(globals.camera_pos.xyz, vec3(root_xz.x, ground, root_xz.y));
        opacity = 0.0;
        if (on_grass(root_xz) && dth < density) {
            opacity = geometry_opacity(cell_weight_geometry(cell.mode.yzw, d), dth / density, params.lod.z);
        }
        // Under the alpha-test threshold every fragment would be discarded: skip the blade.
        if (opacity <= 0.0 || opacity < params.lod.w) {
            out.position = vec4(0.0, 0.0, 2.0, 1.0);
            return out;
        }
        // The shared wind pushes the particle sideways, with a little per-blade flutter.
        let speed = length(wind_at(root_xz).xz);
        let phase = hash_f32(index) * 2.0 * PI;
        let flutter = 1.0 + 0.2 * sin(globals.camera_pos.w * (3.0 + speed) + phase);
        push = wind_push(root_xz) * flutter;
    }

    // The particle: launched from the root almost vertically (unit speed, `tilt` from the
    // vertical towards `dir`), under gravity and the wind's push; its positions at n + 1
    // evenly spaced times are the strip's reference points.
    let n = u32(params.blade.x);
    let level = min(vertex / 2u, n);
    let s = f32(level) / f32(n);
    let g = params.blade.y;
    let v0 = vec3(sin(tilt) * dir.x, cos(tilt), sin(tilt) * dir.y);
    let accel = vec3(push.x, -g, push.y);
    // Scaled so that the standing blade (no wind) peaks at its height.
    let vy = v0.y;
    let peak = select(vy - 0.5 * g, vy * vy / (2.0 * g), g > vy);
    let scale = height / max(peak, 1e-3);
    let centre = (v0 * s + 0.5 * accel * s * s) * scale;
    let tangent = normalize(v0 + accel * s);
    let side_axis = vec3(-dir.y, 0.0, dir.x);
    let side = select(-1.0, 1.0, (vertex & 1u) == 1u);
    let local = centre + side_axis * (0.5 * blade.shape.y * side);
    let world = vec3(root_xz.x, ground, root_xz.y) + local;

    let variation = blade.shape.z * params.color_root.w;
    var albedo = mix(params.color_root.rgb, params.color_tip.rgb, pow(s, 0.8));
    albedo *= 1.0 + variation;
    albedo.r *= 1.0 + 0.6 * max(variation, 0.0);
    // Debug views, by `select` (`&` does not short-circuit into a branch on the uniform).
    albedo = select(albedo, vec3(0.55, 0.04, 0.03), !baking & (globals.frame.z == 1u)); // Fig. 12: geometry in red
    albedo = select(albedo, orientation_color(signs), !baking & (globals.frame.z == 2u));

    if (baking) {
        out.position = bake_position(world, cell.mode);
        out.bake_view = select(
            select(vec3(0.0, 0.0, cell.mode.w), vec3(cell.mode.w, 0.0, 0.0), cell.mode.y < 1.5),
            vec3(0.0, 1.0, 0.0),
            cell.mode.y < 0.5,
        );
    } else {
        out.position = globals.view_proj * vec4(world, 1.0);
    }
    out.world = world;
    out.normal = normalize(cross(side_axis, tangent));
    out.albedo = albedo;
    out.uv = vec2(0.5 + 0.5 * side, s);
    // Ambient occlusion: linear in the height of the vertex above the ground (Sec. 3.2).
    out.ao_opacity = vec2(mix(params.blade.w, 1.0, clamp01(local.y / max(height, 1e-4))), opacity);
    out.threshold = dth;
    out.root = vec4(root_xz.x, ground, root_xz.y, atan2(dir.y, dir.x));
    out.sky = 1.0;
    if (!baking) {
        out.sky = ambient_visibility(root_xz);
    }
    return out;
}

// Sec. 3.5's shadow mask: the light reaching point `p` (relative to the blade's root) of a
// blade inclined towards `azimuth`, from the direction `l`. The ray towards the light leaves
// the cylinder around the blade (radius: patch side / 2 pi, src/shadow.rs) through its side or
// its top; below the top, the mask's texel there (bilinear: anti-aliased) is the shadow.
fn blade_shadow(p: vec3<f32>, azimuth: f32, l: vec3<f32>) -> f32 {
    if (params.btf.w < 0.5) {
        return 1.0;
    }
    let r = params.tile.x / (2.0 * PI);
    let top = params.tile.w;
    let a = dot(l.xz, l.xz);
    if (a < 1e-6) {
        return 1.0;
    }
    let b = dot(p.xz, l.xz);
    let c = dot(p.xz, p.xz) - r * r;
    let t = max((-b + sqrt(max(b * b - a * c, 0.0))) / a, 0.0);
    let h = p + t * l;
    if (h.y >= top) {
        return 1.0;
    }
    let u = fract((atan2(h.z, h.x) - azimuth) / (2.0 * PI));
    let v = 1.0 - clamp(h.y / top, 0.0, 1.0);
    return 1.0 - textureSampleLevel(shadow_mask, repeat_sampler, vec2(u, v), 0, 0.0).a;
}

// `shade_leaf` with the shadow mask on the sun's and the point light's light.
fn shade_blade(albedo: vec3<f32>, normal: vec3<f32>, world: vec3<f32>, root: vec4<f32>, ao: f32, sky: f32, translucency: f32) -> vec3<f32> {
    let to_eye = normalize(globals.camera_pos.xyz - world);
    let n = select(-normal, normal, dot(normal, to_eye) >= 0.0);
    let p = world - root.xyz;
    let sun = globals.sun_direction.xyz;
    var direct = globals.sun_color.rgb * leaf_lambert(n, sun, translucency) * blade_shadow(p, root.w, sun);
    if (globals.point_color.w > 0.0) {
        let l = normalize(globals.point_position.xyz - world);
        direct += point_light(world) * leaf_lambert(n, l, translucency) * blade_shadow(p, root.w, l);
    }
    return albedo * (globals.ambient.rgb * ao * sky + direct * direct_occlusion(ao));
}

// The orthographic cameras of the bake (Sec. 3.3, Fig. 6), in the patch's frame (the patch
// centre at the origin).
fn bake_position(world: vec3<f32>, mode: vec4<f32>) -> vec4<f32> {
    let size = params.tile.x;
    let top = params.tile.w;
    if (mode.y < 0.5) {
        // The horizontal slice: a top view, x and z to the texture, the highest point wins.
        return vec4(2.0 * world.x / size, -2.0 * world.z / size, (top - world.y) / (top + 0.1), 1.0);
    }
    // A vertical slice: the in-plane coordinate (z across x, x across z) and the height to the
    // texture; the near and far planes are the bounds of the slice's slab (its share of the
    // patch, N slices an axis), nearest to the camera's side first.
    // (3: the shadow mask's slab across x, as thick as the mask's cylinder, src/shadow.rs.)
    let across_x = mode.y < 1.5 || mode.y > 2.5;
    let along = select(world.x, world.z, across_x);
    let depth_axis = select(world.z, world.x, across_x);
    let half = select(0.5 * size / params.btf.x, size / (2.0 * PI), mode.y > 2.5);
    let depth = (half - mode.w * (depth_axis - mode.z)) / (2.0 * half);
    return vec4(2.0 * along / size, 2.0 * world.y / top - 1.0, depth, 1.0);
}

// Debug view 2: one colour per mirrored version of the patch.
fn orientation_color(signs: vec2<f32>) -> vec3<f32> {
    return vec3(0.15 + 0.4 * step(signs.x, 0.0), 0.15, 0.15 + 0.4 * step(signs.y, 0.0));
}

@fragment
fn fs_blade(in: BladeOut) -> @location(0) vec4<f32> {
    // The blade texture: colour modulation and the blade's shape in alpha (Fig. 5).
    let tex = textureSample(blade_texture, clamp_sampler, in.uv);
    let alpha = tex.a * in.ao_opacity.y;
    // Sec. 4.2: alpha test with a low threshold (blending smooths what is left); with alpha to
    // coverage the threshold is one 8-bit step.
    if (alpha < params.lod.w) {
        discard;
    }
    let albedo = in.albedo * tex.rgb * 2.0;
    // Two-sided Lambert + ambient darkened towards the root (Sec. 3.2).
    let lit = shade_blade(albedo, normalize(in.normal), in.world, in.root, in.ao_opacity.x, in.sky, params.color_tip.w);
    return vec4(apply_fog(lit, in.world), alpha);
}

struct BakeOut {
    @location(0) color: vec4<f32>,
    @location(1) diffuse: vec4<f32>,
    @location(2) extra: vec4<f32>,
}

// The BTF bake (Sec. 3.3, Fig. 7 and 10): the colour without lighting (K_d, the ambient row),
// the two-sided diffuse factor of the blade seen by the slice's camera for each of the five
// light directions (the rows of Fig. 7), its density threshold (Fig. 10) and its occlusion.
// MSAA resolve turns the binary coverage into alpha with soft borders (Fig. 7's alpha), every
// channel premultiplied by it.
@fragment
fn fs_bake(in: BladeOut) -> BakeOut {
    let tex = textureSample(blade_texture, clamp_sampler, in.uv);
    if (tex.a < 0.5) {
        discard;
    }
    var out: BakeOut;
    // The same two-sided Lambert as the prelude's `shade_leaf`, for the slice's viewer.
    var n = normalize(in.normal);
    if (dot(n, in.bake_view) < 0.0) {
        n = -n;
    }
    let tr = params.color_tip.w;
    let lights = array(vec3(0.0, 1.0, 0.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 0.0, 1.0), vec3(-1.0, 0.0, 0.0), vec3(0.0, 0.0, -1.0));
    var d: array<f32, 5>;
    let p = in.world - in.root.xyz;
    for (var k = 0u; k < 5u; k++) {
        // Lit through the shadow mask (Sec. 3.5), so the slices carry blade-to-blade shadows.
        d[k] = leaf_lambert(n, lights[k], tr) * blade_shadow(p, in.root.w, lights[k]);
    }
    out.color = vec4(in.albedo * tex.rgb * 2.0, 1.0);
    out.diffuse = vec4(d[0], d[1], d[2], d[3]);
    out.extra = vec4(d[4], in.threshold, in.ao_opacity.x, 0.0);
    return out;
}

// ---- The horizontal slice over cells and macro-cells (Sec. 3.3, 4.1) ----

struct SliceQuad {
    @location(0) rect: vec4<f32>,   // world min (x, z), size (x, z)
    @location(1) cells: vec4<f32>,  // first cell (i, j), cells covered (ni, nj)
    @location(2) tess: vec4<f32>,   // x: quads per side (follows the terrain); yzw: its weights
}

struct SliceOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    // patchSize · (u, v) of Eq. 6: position in cells from the macro-cell's first cell.
    @location(1) cell_coord: vec2<f32>,
    @location(2) @interpolate(flat) first_cell: vec2<i32>,
    // Appendix A's light weights (Y+, X+, Z+, X-; Z-) per vertex, for the unmirrored patch:
    // the sun's, then the point light's.
    @location(3) w_a: vec4<f32>,
    @location(4) w_b: f32,
    @location(5) p_a: vec4<f32>,
    @location(6) p_b: f32,
    // The quad's weights (`cell_weight_geometry`).
    @location(7) @interpolate(flat) cell_w: vec3<f32>,
}

@vertex
fn vs_slice(@builtin(vertex_index) vertex: u32, quad: SliceQuad) -> SliceOut {
    return slice_vertex(vertex, quad);
}

// Vertex `vertex` of a slice quad: quad `vertex / 6` of its `tess x tess` tessellation.
fn slice_vertex(vertex: u32, quad: SliceQuad) -> SliceOut {
    let n = u32(quad.tess.x);
    let k = vertex / 6u;
    let corner = vertex % 6u;
    var offsets = array(vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(0.0, 1.0), vec2(1.0, 0.0), vec2(1.0, 1.0), vec2(0.0, 1.0));
    let g = (vec2(f32(k % n), f32(k / n)) + offsets[corner]) / f32(n);
    let xz = quad.rect.xy + g * quad.rect.zw;
    // Close to the bottom of the patch, following the ground.
    let world = vec3(xz.x, terrain_height(xz) + params.tile.y, xz.y);
    var out: SliceOut;
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    out.cell_coord = g * quad.cells.zw;
    out.first_cell = vec2<i32>(quad.cells.xy);
    out.cell_w = quad.tess.yzw;
    let w = btf_weights(globals.sun_direction.xyz);
    out.w_a = w.a;
    out.w_b = w.b;
    let p = btf_weights(globals.point_position.xyz - world);
    out.p_a = p.a;
    out.p_b = p.b;
    return out;
}

// Where a horizontal-slice fragment reads its BTF texel.
struct SliceTexel {
    // The cell's mirror signs (x, z).
    signs: vec2<f32>,
    uv: vec2<f32>,
    // Screen gradients of the unwrapped coordinates, so the mip level does not jump at cell
    // borders.
    gx: vec2<f32>,
    gy: vec2<f32>,
}

// The patch orientation map (Sec. 4.1) at `local` (in cells from `first_cell`): one unfiltered
// texel per cell, bit 0 = mirror x, bit 1 = mirror z. Returns the cell's mirror signs (xy) and,
// by Eq. 7, u' = (patchSize · orientation · u) mod 1, the texture coordinates (zw). Twin of
// `slice::orientation_texel` in src/slice.rs.
fn orientation_texel(local: vec2<f32>, first_cell: vec2<i32>) -> vec4<f32> {
    let dims = vec2<i32>(textureDimensions(orientation_map));
    let index = clamp(first_cell + vec2<i32>(floor(local)), vec2(0), dims - 1);
    let bits = textureLoad(orientation_map, index, 0).r;
    let signs = vec2(select(1.0, -1.0, (bits & 1u) != 0u), select(1.0, -1.0, (bits & 2u) != 0u));
    return vec4(signs, fract(signs * local));
}

// The texel at `local` (in cells from `first_cell`) through the patch orientation map, with the
// screen gradients. Call in uniform control flow (screen derivatives).
fn slice_texel(local: vec2<f32>, first_cell: vec2<i32>) -> SliceTexel {
    let o = orientation_texel(local, first_cell);
    var t: SliceTexel;
    t.signs = o.xy;
    t.uv = o.zw;
    t.gx = dpdx(local) * t.signs;
    t.gy = dpdy(local) * t.signs;
    return t;
}

// The horizontal slice's opacity at `world` (a point of the slice) for a texel of `coverage`
// and density threshold `dth`: its share of the blades there (Sec. 3.4, Fig. 11), with the
// quad's weights `cell_w`.
fn slice_alpha(t: SliceTexel, coverage: f32, dth: f32, world: vec3<f32>, cell_w: vec3<f32>) -> f32 {
    let xz = world.xz;
    let ground = vec3(xz.x, world.y - params.tile.y, xz.y);
    let w_g = cell_weight_geometry(cell_w, distance(globals.camera_pos.xyz, ground));
    let texels = max(length(t.gx), length(t.gy)) * params.tile.z;
    return coverage * slice_share(dth, terrain_density(xz), w_g, 1.0, texels) * f32(on_grass(xz));
}

@fragment
fn fs_slice(in: SliceOut) -> @location(0) vec4<f32> {
    let t = slice_texel(in.cell_coord, in.first_cell);
    let signs = t.signs;
    let color = textureSampleGrad(slice_color, repeat_sampler, t.uv, 0, t.gx, t.gy);
    let coverage = color.a;
    if (coverage < 1e-3) {
        discard;
    }
    let diffuse = textureSampleGrad(slice_diffuse, repeat_sampler, t.uv, 0, t.gx, t.gy) / coverage;
    let extra = textureSampleGrad(slice_extra, repeat_sampler, t.uv, 0, t.gx, t.gy) / coverage;
    let ao = extra.z;
    let alpha = slice_alpha(t, coverage, extra.y, in.world, in.cell_w);
    if (alpha < max(params.lod.w, 1e-3)) {
        discard;
    }
    var albedo = color.rgb / coverage;
    if (globals.frame.z == 1u) {
        albedo = vec3(0.04, 0.4, 0.05); // Fig. 12: horizontal slices in green
    } else if (globals.frame.z == 2u) {
        albedo = orientation_color(signs);
    }
    var sun: Weights;
    sun.a = in.w_a;
    sun.b = in.w_b;
    var point: Weights;
    point.a = in.p_a;
    point.b = in.p_b;
    let lit = btf_light(albedo, diffuse, extra.x, mirror_weights(sun, signs), mirror_weights(point, signs), in.world, ao);
    return vec4(apply_fog(lit, in.world), alpha);
}

// ---- Shadows projected on the ground (Sec. 3.5, Fig. 15) ----
//
// One render pass before the grass, with the stencil: (1) the geometric blades, projected along
// the sun onto the ground, mark the stencil where they pass the depth test against the ground
// (no colour, no depth written); (2) a screen-covering triangle multiplies the marked pixels by
// the ground's shadowed-to-lit ratio (the paper's "black quadrilateral with blending"); (3) each
// horizontal slice, projected likewise, multiplies the ground by its own opacity, where no blade
// shadow was (slice shadows do not overlap one another, so they need no stencil of their own).
// The vertical slices cast none (the paper: they would cover the whole ground).

// The lowest sun, as the sine of its elevation over the ground, that casts projected shadows:
// below it a shadow would stretch beyond 20 blade heights, and the sun gives the ground under 5 %
// of its direct light there.
const SHADOW_MIN_SINE: f32 = 0.05;

// Sec. 3.5's projection matrix applied to one point: `p` moved along `l` (unit, towards a
// directional light) onto the plane through `origin` with unit normal `n`, i.e. M = (n·l) I −
// l nᵀ in homogeneous form. The plane is the ground at the caster's root: the paper's ground
// plane, and uneven terrain becomes planar per blade.
fn planar_projection(p: vec3<f32>, origin: vec3<f32>, n: vec3<f32>, l: vec3<f32>) -> vec3<f32> {
    return p - l * (dot(p - origin, n) / dot(n, l));
}

// Clip position of a shadow point on the ground, moved towards the eye along its view ray (its
// pixel does not change) by 5 cm plus 0.3 % of the distance, so it passes the depth test against
// the ground it lies on: more than the 24-bit depth's step (d² / (near · 2²⁴): 0.19 m at 400 m
// with the meadow's 0.05 m near plane, against a lift of 1.25 m there) and than the gap between
// the terrain mesh and the bilinear heightmap the projection lands on.
fn shadow_clip(p: vec3<f32>) -> vec4<f32> {
    let to_eye = globals.camera_pos.xyz - p;
    let d = max(length(to_eye), 1e-3);
    let lifted = p + to_eye * min((0.05 + 0.003 * d) / d, 0.5);
    return globals.view_proj * vec4(lifted, 1.0);
}

// How much of the ground's light a blade shadow leaves: the core lights the ground with
// ambient + sun (n·l) (the prelude's `shade`), a shadow keeps the ambient term. Evaluated for the
// paper's flat ground (n = Y+), per colour channel.
fn ground_shadow_factor() -> vec3<f32> {
    let a = globals.ambient.rgb;
    return a / max(a + globals.sun_color.rgb * max(globals.sun_direction.y, 0.0), vec3(1e-4));
}

// (1) A geometric blade (the same blade, opacity and wind as `vs_blade`) projected on the ground.
@vertex
fn vs_ground_shadow(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> BladeOut {
    var out = blade_vertex(vertex, instance);
    let root = out.root.xyz;
    let n = terrain_normal(root.xz);
    let l = globals.sun_direction.xyz;
    // Blades `blade_vertex` skips come back with zero opacity.
    if (out.ao_opacity.y <= 0.0 || dot(n, l) < SHADOW_MIN_SINE) {
        out.position = vec4(0.0, 0.0, 2.0, 1.0);
        return out;
    }
    out.position = shadow_clip(planar_projection(out.world, root, n, l));
    return out;
}

// The 4 x 4 ordered-dither (Bayer) threshold of a pixel, in (0, 1).
fn bayer4(pixel: vec2<f32>) -> f32 {
    var m = array<f32, 16>(0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);
    let p = vec2<u32>(pixel) % 4u;
    return (m[p.y * 4u + p.x] + 0.5) / 16.0;
}

// The blade's shape marks the stencil (no colour is written) where its texture alpha times its
// Eq. 5 opacity passes an ordered dither: an opaque blade's shadow is whole, and a blade fading
// out of geometry leaves a shadow thinning with it rather than one that vanishes at once, while
// the slices' shadows take the complementary share.
@fragment
fn fs_ground_shadow(in: BladeOut) -> @location(0) vec4<f32> {
    let alpha = textureSample(blade_texture, clamp_sampler, in.uv).a * in.ao_opacity.y;
    if (alpha < bayer4(in.position.xy)) {
        discard;
    }
    return vec4(0.0);
}

// (2) One triangle over the screen; only the stencil's marked pixels pass.
@vertex
fn vs_shadow_cover(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}

// Multiplied into the target (blend: destination x source).
@fragment
fn fs_shadow_cover() -> @location(0) vec4<f32> {
    return vec4(ground_shadow_factor(), 1.0);
}

// (3) A horizontal slice quad projected on the ground; it carries the slice's own texture
// coordinates and position, so the fragment reads the slice's texel.
@vertex
fn vs_slice_shadow(@builtin(vertex_index) vertex: u32, quad: SliceQuad) -> SliceOut {
    var out = slice_vertex(vertex, quad);
    let ground = out.world - vec3(0.0, params.tile.y, 0.0);
    let l = globals.sun_direction.xyz;
    // Decided for the whole quad (a vertex dropped alone would tear its triangles): the sun
    // over flat ground; on a slope facing away from it the projection is stretched instead.
    // A sun too low drops the quad by `select`, not by a branch on the uniform alone
    // (`grassbench::shaders::uniform_branches`).
    var n = terrain_normal(ground.xz);
    if (dot(n, l) < SHADOW_MIN_SINE) {
        n = vec3(0.0, 1.0, 0.0);
    }
    let q = planar_projection(out.world, ground, n, l);
    let projected = shadow_clip(vec3(q.x, terrain_height(q.xz), q.z));
    out.position = select(projected, vec4(0.0, 0.0, 2.0, 1.0), l.y < SHADOW_MIN_SINE);
    return out;
}

// The ground darkened by the slice's opacity there (its share of the blades, Sec. 3.4), so the
// slices' shadows take over from the blades' through the same weights.
@fragment
fn fs_slice_shadow(in: SliceOut) -> @location(0) vec4<f32> {
    let t = slice_texel(in.cell_coord, in.first_cell);
    let color = textureSampleGrad(slice_color, repeat_sampler, t.uv, 0, t.gx, t.gy);
    let extra = textureSampleGrad(slice_extra, repeat_sampler, t.uv, 0, t.gx, t.gy);
    var alpha = 0.0;
    if (color.a >= 1e-3) {
        alpha = slice_alpha(t, color.a, extra.y / color.a, in.world, in.cell_w);
    }
    return vec4(mix(vec3(1.0), ground_shadow_factor(), alpha), 1.0);
}

// ---- Vertical slices (Sec. 3.3): N across x and N across z in each cell of the mid band ----

// One cell with vertical slices (instance step): the cell's `Cell` as vertex attributes.
struct VCell {
    @location(0) center_signs: vec4<f32>,
    @location(1) mode: vec4<f32>,
}

struct VSliceOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) @interpolate(flat) layer: u32,
    @location(3) w_a: vec4<f32>,
    @location(4) w_b: f32,
    @location(5) p_a: vec4<f32>,
    @location(6) p_b: f32,
    // The cell's weights (`cell_weight_geometry`).
    @location(7) @interpolate(flat) cell_w: vec3<f32>,
}

// Vertex `v` of a cell: quad `v / 6` (2N of them, across x and across z alternately, each axis
// drawn back to front for the eye, since the slices are blended unsorted like the blades).
@vertex
fn vs_vslice(@builtin(vertex_index) vertex: u32, cell: VCell) -> VSliceOut {
    let n = u32(params.btf.x);
    let size = params.tile.x;
    let top = params.tile.w;
    let k = vertex / 6u;
    let corner = vertex % 6u;
    var offsets = array(vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(0.0, 1.0), vec2(1.0, 0.0), vec2(1.0, 1.0), vec2(0.0, 1.0));
    let g = offsets[corner];
    let signs = cell.center_signs.zw;
    // The eye in the patch's own frame (the mirror is its own inverse).
    let eye = (globals.camera_pos.xz - cell.center_signs.xy) * signs;
    let axis = k % 2u;  // 0: across x, 1: across z
    let j = k / 2u;
    let eye_along = select(eye.y, eye.x, axis == 0u);
    let i = select(n - 1u - j, j, eye_along >= 0.0);
    let c = size * ((f32(i) + 0.5) / f32(n) - 0.5);
    let along = size * (g.x - 0.5);
    let local = select(vec2(along, c), vec2(c, along), axis == 0u);
    let base = cell.center_signs.xy + local * signs;
    // Beyond the paper: the slice's top is sheared with the wind that bends the geometric
    // blades, by the displacement of a windless-standing blade's tip at that height (the
    // particle of `blade_vertex` moves 0.5 push scale at its tip, scale = height / peak), so
    // the slices sway with the blades they replace. Per vertex, so neighbouring cells agree.
    let push = wind_push(base);
    let g_acc = params.blade.y;
    let peak = select(1.0 - 0.5 * g_acc, 1.0 / (2.0 * g_acc), g_acc > 1.0);
    let xz = base + 0.5 * push * (g.y * top) / max(peak, 1e-3);
    let world = vec3(xz.x, terrain_height(base) + g.y * top, xz.y);
    var out: VSliceOut;
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    out.uv = vec2(g.x, 1.0 - g.y);
    // Front (camera on the + side of the slice, Fig. 7's left column) or back.
    let front = eye_along >= c;
    out.layer = 2u * (axis * n + i) + select(1u, 0u, front);
    // Appendix A per vertex, in the patch's frame.
    let mirror = vec3(signs.x, 1.0, signs.y);
    let w = btf_weights(globals.sun_direction.xyz * mirror);
    out.w_a = w.a;
    out.w_b = w.b;
    let p = btf_weights((globals.point_position.xyz - world) * mirror);
    out.p_a = p.a;
    out.p_b = p.b;
    out.cell_w = cell.mode.yzw;
    return out;
}

@fragment
fn fs_vslice(in: VSliceOut) -> @location(0) vec4<f32> {
    let color = textureSample(vslice_color, clamp_sampler, in.uv, in.layer);
    let coverage = color.a;
    if (coverage < 1e-3) {
        discard;
    }
    let diffuse = textureSample(vslice_diffuse, clamp_sampler, in.uv, in.layer) / coverage;
    let extra = textureSample(vslice_extra, clamp_sampler, in.uv, in.layer) / coverage;
    let xz = in.world.xz;
    let d = distance(globals.camera_pos.xyz, vec3(xz.x, terrain_height(xz), xz.y));
    let dims = vec2<f32>(textureDimensions(vslice_color));
    let texels = max(length(dpdx(in.uv) * dims), length(dpdy(in.uv) * dims));
    // Per pixel (Sec. 3.4, Fig. 11): the texel's threshold against the density below it.
    let share = slice_share(extra.y, terrain_density(xz), cell_weight_geometry(in.cell_w, d), cell_vertical_fade(in.cell_w, d), texels)
        * f32(on_grass(xz));
    let alpha = coverage * share;
    if (alpha < max(params.lod.w, 1e-3)) {
        discard;
    }
    var albedo = color.rgb / coverage;
    if (globals.frame.z == 1u) {
        albedo = vec3(0.03, 0.08, 0.55); // Fig. 12: vertical slices in blue
    } else if (globals.frame.z == 2u) {
        albedo = vec3(0.3);
    }
    var sun: Weights;
    sun.a = in.w_a;
    sun.b = in.w_b;
    var point: Weights;
    point.a = in.p_a;
    point.b = in.p_b;
    let lit = btf_light(albedo, diffuse, extra.x, sun, point, in.world, extra.z);
    return vec4(apply_fog(lit, in.world), alpha);
}
