// Zhang 2006, far plants: billboards of six rectangles joined at a vertical middle line
// (Sec. 4.1, Fig. 10-12). One instance is one rectangle ("wing"): its bottom vertices are the
// roots of two plants, its top vertices their animated top points (Sec. 4.2). The texture
// (Fig. 11, composed at start-up: `billboard_texture.rs`) holds per texel the blade's
// luminance, density threshold, colour variation (or petal layer) and alpha. Composed after
// the prelude; shares group 1 with `blade.wgsl`. See `techniques/zhang/src/lib.rs`.

struct Params {
    color_root: vec4<f32>,   // rgb; w: colour variation
    color_tip: vec4<f32>,    // rgb; w: translucency
    // x: backbone points n; y: alpha cut-off; z: petal size (m); w: billboard height (m)
    shape: vec4<f32>,
    // x: 1 when blending (fading blades scale their alpha), 0 otherwise (they dissolve)
    modes: vec4<f32>,
}

@group(1) @binding(0) var<uniform> params: Params;
@group(1) @binding(2) var petal_textures: texture_2d_array<f32>;
@group(1) @binding(4) var billboard_texture: texture_2d_array<f32>;

const PETAL_CODE: f32 = 0.8;

struct WingIn {
    @location(0) centre_root: vec4<f32>,  // xyz; w: texture u at the middle line
    @location(1) outer_root: vec4<f32>,   // xyz; w: texture u at the outer edge
    @location(2) centre_top: vec4<f32>,   // xyz; w: texture layer
    @location(3) outer_top: vec4<f32>,    // xyz; w: kept fraction of the blades (density)
    @location(4) fade: vec4<f32>,         // x: fade alpha (Sec. 6.1); y: cut height (v at top)
}

struct WingOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    // The wing's normal, turned to the eye.
    @location(1) @interpolate(flat) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) @interpolate(flat) layer: u32,
    @location(4) @interpolate(flat) keep: f32,
    @location(5) @interpolate(flat) alpha: f32,
    // `leaf_irradiance` of the ambient and the sun (affine in `uv.y`, so exact per vertex).
    @location(6) light: vec3<f32>,
    // `fog_factor` (per vertex: see the essay).
    @location(7) fog: f32,
}

// Ambient occlusion at height v of a wing: darker near the ground, like `vs_blade`'s.
fn wing_ao(v: f32) -> f32 {
    return mix(0.3, 1.0, v);
}

// A 4-vertex strip: centre bottom, outer bottom, centre top, outer top. The instance is a
// wing cut down (`wing_trim.rs`): its top edge at fraction `fade.y` of the wing's height.
@vertex
fn vs_wing(@builtin(vertex_index) vertex: u32, w: WingIn) -> WingOut {
    var out: WingOut;
    let outer = (vertex & 1u) == 1u;
    let top = vertex >= 2u;
    let bottom = select(w.centre_root.xyz, w.outer_root.xyz, outer);
    let upper = select(w.centre_top.xyz, w.outer_top.xyz, outer);
    let world = select(bottom, mix(bottom, upper, w.fade.y), top);
    let along = w.outer_root.xyz - w.centre_root.xyz;
    let across = normalize(vec3(-along.z, 0.0, along.x) + vec3(0.0, 1e-6, 0.0));
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    // Lit like the single blades it stands for: their faces are near-vertical, so the wing's
    // face normal, tilted a little up (blades lean and bend), turned to the eye from the
    // middle of the wing's foot (the same side at all four corners).
    let normal = normalize(across + vec3(0.0, 0.5, 0.0));
    out.normal = facing_viewer(normal, 0.5 * (w.centre_root.xyz + w.outer_root.xyz));
    out.uv = vec2(select(w.centre_root.w, w.outer_root.w, outer), select(0.0, w.fade.y, top));
    // `shade_leaf` split: the ambient and the sun are the same over the whole wing but for
    // the ambient occlusion, which is affine in v, so their sum is too and interpolates
    // exactly; the point light, which falls off with distance, is added per pixel
    // (`fs_wing_point_lit`).
    let sun = globals.sun_color.rgb * leaf_lambert(out.normal, globals.sun_direction.xyz, params.color_tip.w);
    out.light = leaf_irradiance(sun, wing_ao(out.uv.y));
    out.fog = fog_factor(world);
    out.layer = u32(w.centre_top.w);
    // Fading (Sec. 6.1): blended, the alpha scales the output; otherwise the wing's blades
    // dissolve with their density thresholds.
    let blend = params.modes.x > 0.5;
    out.keep = w.outer_top.w * select(w.fade.x, 1.0, blend);
    out.alpha = select(1.0, w.fade.x, blend);
    return out;
}

// The texel a wing fragment shows, coloured like the blades it stands for (or discarded).
fn wing_albedo(in: WingOut) -> vec4<f32> {
    let size = textureDimensions(billboard_texture);
    let texel_xy = vec2<i32>(
        i32(fract(in.uv.x) * f32(size.x)) % i32(size.x),
        min(i32(in.uv.y * f32(size.y)), i32(size.y) - 1),
    );
    // Nearest texel: G and B are ids, not colours, and must not be filtered.
    let texel = textureLoad(billboard_texture, texel_xy, in.layer, 0);
    // Alpha test, then the shared density rule: a blade stays where its threshold is below
    // the density map (and below the fade alpha of Sec. 6.1).
    let alpha = texel.a * in.alpha;
    if (alpha < params.shape.y || texel.g >= in.keep) {
        discard;
    }
    var albedo: vec3<f32>;
    if (texel.b >= PETAL_CODE - 0.01) {
        // A petal: the colour of its petal texture half-way out.
        let layer = u32(round((texel.b - PETAL_CODE) / 0.03));
        albedo = textureLoad(petal_textures, vec2<i32>(48, 32), layer, 0).rgb;
    } else {
        // Like `vs_blade`: root-to-tip colour, per-blade variation, textured luminance.
        let variation = (texel.b / 0.75 * 2.0 - 1.0) * params.color_root.w;
        albedo = mix(params.color_root.rgb, params.color_tip.rgb, pow(in.uv.y, 0.8));
        albedo *= 1.0 + variation;
        albedo.r *= 1.0 + 0.6 * max(variation, 0.0);
        albedo *= texel.r * 1.15;
    }
    return vec4(albedo, alpha);
}

// Lit by `light`, hazed by the fog. Alpha blends with Eq. (10) when sorting, drives coverage
// under MSAA otherwise.
fn wing_color(albedo: vec4<f32>, light: vec3<f32>, fog: f32) -> vec4<f32> {
    return vec4(mix(albedo.rgb * light, globals.sky_horizon.rgb, fog), albedo.a);
}

// Ambient and sun only (the frame has no point light): no per-pixel lighting at all.
@fragment
fn fs_wing(in: WingOut) -> @location(0) vec4<f32> {
    return wing_color(wing_albedo(in), in.light, in.fog);
}

// With the point light, whose fall-off with distance does not interpolate, added per pixel.
@fragment
fn fs_wing_point_lit(in: WingOut) -> @location(0) vec4<f32> {
    let albedo = wing_albedo(in);
    let to_light = normalize(globals.point_position.xyz - in.world);
    let direct = point_light(in.world) * leaf_lambert(in.normal, to_light, params.color_tip.w);
    let light = in.light + direct * direct_occlusion(wing_ao(in.uv.y));
    return wing_color(albedo, light, in.fog);
}

// `wing_lighting = "pixel"`: the thesis's way, every light per pixel with the blades'
// `shade_leaf` and fog (the picture of `fs_wing` / `fs_wing_point_lit` to rounding, at the
// cost of a full lighting evaluation per fragment).
@fragment
fn fs_wing_pixel_lit(in: WingOut) -> @location(0) vec4<f32> {
    let albedo = wing_albedo(in);
    let lit = shade_leaf(albedo.rgb, in.normal, in.world, wing_ao(in.uv.y), params.color_tip.w);
    return vec4(apply_fog(lit, in.world), albedo.a);
}
