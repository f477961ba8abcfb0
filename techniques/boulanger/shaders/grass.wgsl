// Boulanger, Pattanaik & Bouatouch 2006: geometric blades (Sec. 3.2), the start-up bake of the
// horizontal slice (Sec. 3.3), and the horizontal slice drawn over cells and macro-cells with
// the patch orientation map (Sec. 4.1, Eq. 6-7). See `techniques/boulanger/src/lib.rs`.
// Composed after the prelude (group 0).

struct Params {
    color_root: vec4<f32>,  // rgb; w: colour variation
    color_tip: vec4<f32>,   // rgb; w: translucency
    // x: segments; y: gravity; z: wind response; w: ambient occlusion at the root
    blade: vec4<f32>,
    // x: min_geom; y: max_geom; z: omega (Eq. 5); w: alpha-test threshold
    lod: vec4<f32>,
    // x: patch size (m); y: slice height above ground (m); z: slice texture side; w: bake top (m)
    tile: vec4<f32>,
    // xyz: unit vector towards the scene's sun, for the slice bake; w: unused
    sun: vec4<f32>,
}

@group(1) @binding(0) var<uniform> params: Params;
@group(1) @binding(1) var blade_texture: texture_2d<f32>;
@group(1) @binding(2) var clamp_sampler: sampler;
@group(1) @binding(3) var repeat_sampler: sampler;

// One geometry cell's copy of the patch (Sec. 3.1). Instance `i` of a blade draw is blade
// `i % blade_count` of the cell in slot `i / blade_count` of this page of cells (the page is a
// dynamic offset), so runs of cells drawn whole merge into a single instanced draw.
struct Cell {
    // xy: world (x, z) of the patch centre; zw: mirror signs (-1 or 1) for x and z (Sec. 3.1)
    center_signs: vec4<f32>,
    // x: 1 when baking the slice (no terrain, wind, density or LOD); yzw: unused
    mode: vec4<f32>,
}
@group(2) @binding(0) var<storage, read> cells: array<Cell>;

// The patch's blades, sorted by block and, within a block, by density threshold.
struct Blade {
    root_azimuth_tilt: vec4<f32>,  // root (x, z) from the patch centre, azimuth, tilt
    shape: vec4<f32>,              // height, width, colour variation, density threshold
}
@group(2) @binding(4) var<storage, read> patch_blades: array<Blade>;

// The horizontal slice (slice pipeline only).
@group(2) @binding(1) var slice_color: texture_2d<f32>;   // albedo x coverage, coverage
@group(2) @binding(2) var slice_aux: texture_2d<f32>;     // (diffuse, 0, dth, ao) x coverage
@group(2) @binding(3) var orientation_map: texture_2d<u32>;

// ---- Level of detail (twins of src/lod.rs) ----

fn clamp01(x: f32) -> f32 {
    return clamp(x, 0.0, 1.0);
}

// Eq. 2: weight of geometry at distance d.
fn weight_geometry(d: f32) -> f32 {
    return clamp01((d - params.lod.y) / (params.lod.x - params.lod.y));
}

// Eq. 5 on `1 - t` with the weight stretched so weight 1 draws every blade fully.
fn geometry_opacity(w_g: f32, t: f32, omega: f32) -> f32 {
    let key = 1.0 - t;
    if (omega <= 0.0) {
        return select(0.0, 1.0, key <= w_g);
    }
    return clamp01((w_g * (1.0 + 2.0 * omega) - key) / (2.0 * omega));
}

fn on_grass(xz: vec2<f32>) -> bool {
    let uv = terrain_uv(xz);
    return all(uv >= vec2(0.0)) && all(uv <= vec2(1.0)) && terrain_covering(xz) == COVER_GRASS;
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
}

@vertex
fn vs_blade(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> BladeOut {
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
            opacity = geometry_opacity(weight_geometry(d), dth / density, params.lod.z);
        }
        // Under the alpha-test threshold every fragment would be discarded: skip the blade.
        if (opacity <= 0.0 || opacity < params.lod.w) {
            out.position = vec4(0.0, 0.0, 2.0, 1.0);
            return out;
        }
        // The shared wind pushes the particle sideways, with a little per-blade flutter.
        let wind = wind_at(root_xz).xz;
        let speed = length(wind);
        let phase = hash_f32(index) * 2.0 * PI;
        let flutter = 1.0 + 0.2 * sin(globals.camera_pos.w * (3.0 + speed) + phase);
        push = wind * params.blade.z * flutter;
        let p = length(push);
        if (p > 1.5) {
            push *= 1.5 / p;
        }
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
    if (!baking && globals.frame.z == 1u) {
        albedo = vec3(0.55, 0.04, 0.03); // Fig. 12: geometry in red
    } else if (!baking && globals.frame.z == 2u) {
        albedo = orientation_color(signs);
    }

    if (baking) {
        // Orthographic top view of the patch: x and z to the texture, the highest point wins.
        let top = params.tile.w;
        out.position = vec4(
            2.0 * world.x / params.tile.x,
            -2.0 * world.z / params.tile.x,
            (top - world.y) / (top + 0.1),
            1.0,
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
    return out;
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
    let lit = shade_leaf(albedo, normalize(in.normal), in.world, in.ao_opacity.x, params.color_tip.w);
    return vec4(apply_fog(lit, in.world), alpha);
}

struct BakeOut {
    @location(0) color: vec4<f32>,
    @location(1) aux: vec4<f32>,
}

// The bake of the horizontal slice (Sec. 3.3): colour without lighting (the ambient row of
// Fig. 7), the two-sided diffuse factor of the blade seen from above for the scene's sun (one
// row of Fig. 7's diffuse part; part 2 bakes the five light directions), its density threshold
// (Fig. 10) and its occlusion. MSAA resolve turns the binary coverage into alpha with soft
// borders, every channel premultiplied by it; averaging the diffuse factor (not the normal)
// keeps far grass as dark as its blades.
@fragment
fn fs_bake(in: BladeOut) -> BakeOut {
    let tex = textureSample(blade_texture, clamp_sampler, in.uv);
    if (tex.a < 0.5) {
        discard;
    }
    var out: BakeOut;
    // The same two-sided Lambert as the prelude's `shade_leaf`, for a viewer above the patch.
    var n = normalize(in.normal);
    if (n.y < 0.0) {
        n = -n;
    }
    let ndl = dot(n, params.sun.xyz);
    let diffuse = max(ndl, 0.0) + max(-ndl, 0.0) * params.color_tip.w;
    out.color = vec4(in.albedo * tex.rgb * 2.0, 1.0);
    out.aux = vec4(diffuse, 0.0, in.threshold, in.ao_opacity.x);
    return out;
}

// ---- The horizontal slice over cells and macro-cells (Sec. 3.3, 4.1) ----

struct SliceQuad {
    @location(0) rect: vec4<f32>,   // world min (x, z), size (x, z)
    @location(1) cells: vec4<f32>,  // first cell (i, j), cells covered (ni, nj)
    @location(2) tess: vec4<f32>,   // x: quads per side (follows the terrain); yzw: unused
}

struct SliceOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    // patchSize · (u, v) of Eq. 6: position in cells from the macro-cell's first cell.
    @location(1) cell_coord: vec2<f32>,
    @location(2) @interpolate(flat) first_cell: vec2<i32>,
}

@vertex
fn vs_slice(@builtin(vertex_index) vertex: u32, quad: SliceQuad) -> SliceOut {
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
    return out;
}

@fragment
fn fs_slice(in: SliceOut) -> @location(0) vec4<f32> {
    // Patch orientation map (Sec. 4.1): one unfiltered texel per cell, bit 0 = mirror x, bit 1 =
    // mirror z; Eq. 7: u' = (patchSize · orientation · u) mod 1.
    let local = in.cell_coord;
    let dims = vec2<i32>(textureDimensions(orientation_map));
    let index = clamp(in.first_cell + vec2<i32>(floor(local)), vec2(0), dims - 1);
    let bits = textureLoad(orientation_map, index, 0).r;
    let signs = vec2(select(1.0, -1.0, (bits & 1u) != 0u), select(1.0, -1.0, (bits & 2u) != 0u));
    let uv = fract(signs * local);
    // Gradients of the unwrapped coordinates, so the mip level does not jump at cell borders.
    let gx = dpdx(local) * signs;
    let gy = dpdy(local) * signs;
    let color = textureSampleGrad(slice_color, repeat_sampler, uv, gx, gy);
    let aux = textureSampleGrad(slice_aux, repeat_sampler, uv, gx, gy);
    let coverage = color.a;
    if (coverage < 1e-3) {
        discard;
    }
    let albedo_in = color.rgb / coverage;
    let diffuse = aux.x / coverage;
    let dth = aux.z / coverage;
    let ao = aux.w / coverage;

    let xz = in.world.xz;
    let ground = vec3(xz.x, in.world.y - params.tile.y, xz.y);
    let w_g = weight_geometry(distance(globals.camera_pos.xyz, ground));
    let density = terrain_density(xz);
    let omega = params.lod.z;
    // Per texel (Sec. 3.4, Fig. 11): the texel's blade exists if its threshold is under the
    // local density, and the slice draws what geometry does not.
    var fine = 0.0;
    if (dth < density) {
        fine = 1.0 - geometry_opacity(w_g, dth / density, omega);
    }
    // A pixel far away covers many blades, their thresholds spread uniformly (the patch is
    // built so): draw the expected fraction instead of testing one averaged threshold.
    var mean = 0.0;
    for (var k = 0u; k < 8u; k++) {
        mean += 1.0 - geometry_opacity(w_g, (f32(k) + 0.5) / 8.0, omega);
    }
    let expected = density * mean / 8.0;
    let texels = max(length(gx), length(gy)) * params.tile.z;
    let far = clamp(log2(max(texels, 1e-6)) - 0.5, 0.0, 1.0);
    let share = mix(fine, expected, far) * f32(on_grass(xz));
    let alpha = coverage * share;
    if (alpha < max(params.lod.w, 1e-3)) {
        discard;
    }
    var albedo = albedo_in;
    if (globals.frame.z == 1u) {
        albedo = vec3(0.04, 0.4, 0.05); // Fig. 12: horizontal slices in green
    } else if (globals.frame.z == 2u) {
        albedo = orientation_color(signs);
    }
    // `shade_leaf` with the baked, texel-averaged diffuse factor in place of one normal's.
    let light = globals.ambient.rgb * ao + globals.sun_color.rgb * diffuse * mix(0.5, 1.0, ao);
    let lit = albedo * light;
    return vec4(apply_fog(lit, in.world), alpha);
}
