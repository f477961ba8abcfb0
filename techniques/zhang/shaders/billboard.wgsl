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
    @location(4) fade: vec4<f32>,         // x: fade alpha (Sec. 6.1)
}

struct WingOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) @interpolate(flat) layer: u32,
    @location(4) @interpolate(flat) keep: f32,
    @location(5) @interpolate(flat) alpha: f32,
}

// A 4-vertex strip: centre bottom, outer bottom, centre top, outer top.
@vertex
fn vs_wing(@builtin(vertex_index) vertex: u32, w: WingIn) -> WingOut {
    var out: WingOut;
    let outer = (vertex & 1u) == 1u;
    let top = vertex >= 2u;
    let bottom = select(w.centre_root.xyz, w.outer_root.xyz, outer);
    let upper = select(w.centre_top.xyz, w.outer_top.xyz, outer);
    let world = select(bottom, upper, top);
    let along = w.outer_root.xyz - w.centre_root.xyz;
    let across = normalize(vec3(-along.z, 0.0, along.x) + vec3(0.0, 1e-6, 0.0));
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    // Lit like the single blades it stands for: their faces are near-vertical, so the wing's
    // face normal, tilted a little up (blades lean and bend).
    out.normal = normalize(across + vec3(0.0, 0.5, 0.0));
    out.uv = vec2(select(w.centre_root.w, w.outer_root.w, outer), select(0.0, 1.0, top));
    out.layer = u32(w.centre_top.w);
    // Fading (Sec. 6.1): blended, the alpha scales the output; otherwise the wing's blades
    // dissolve with their density thresholds.
    let blend = params.modes.x > 0.5;
    out.keep = w.outer_top.w * select(w.fade.x, 1.0, blend);
    out.alpha = select(1.0, w.fade.x, blend);
    return out;
}

@fragment
fn fs_wing(in: WingOut) -> @location(0) vec4<f32> {
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
    let v = in.uv.y;
    var albedo: vec3<f32>;
    if (texel.b >= PETAL_CODE - 0.01) {
        // A petal: the colour of its petal texture half-way out.
        let layer = u32(round((texel.b - PETAL_CODE) / 0.03));
        albedo = textureLoad(petal_textures, vec2<i32>(48, 32), layer, 0).rgb;
    } else {
        // Like `vs_blade`: root-to-tip colour, per-blade variation, textured luminance.
        let variation = (texel.b / 0.75 * 2.0 - 1.0) * params.color_root.w;
        albedo = mix(params.color_root.rgb, params.color_tip.rgb, pow(v, 0.8));
        albedo *= 1.0 + variation;
        albedo.r *= 1.0 + 0.6 * max(variation, 0.0);
        albedo *= texel.r * 1.15;
    }
    let ao = mix(0.3, 1.0, v);
    let lit = shade_leaf(albedo, normalize(in.normal), in.world, ao, params.color_tip.w);
    // Alpha blends with Eq. (10) when sorting, drives coverage under MSAA otherwise.
    return vec4(apply_fog(lit, in.world), alpha);
}
