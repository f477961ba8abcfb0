// Zhang 2006, near plants: blades of grass built from four animated control points (cubic
// Bezier backbone, Eq. 5; segment points rotated towards the wind, Sec. 3.2.5; textured quads
// with alpha, Fig. 5b) and flower petals (Sec. 3.3). Composed after the prelude. See
// `techniques/zhang/src/lib.rs`.

struct Params {
    color_root: vec4<f32>,   // rgb; w: colour variation
    color_tip: vec4<f32>,    // rgb; w: translucency
    // x: backbone points n; y: alpha cut-off; z: petal size (m); w: billboard height (m)
    shape: vec4<f32>,
    // x: 1 when blending (fading blades scale their alpha), 0 otherwise (they dissolve)
    modes: vec4<f32>,
}

@group(1) @binding(0) var<uniform> params: Params;
@group(1) @binding(1) var blade_texture: texture_2d<f32>;
@group(1) @binding(2) var petal_textures: texture_2d_array<f32>;
@group(1) @binding(3) var texture_sampler: sampler;

struct BladeIn {
    @location(0) root_facing: vec4<f32>,  // P0 xyz, facing angle
    @location(1) shape: vec4<f32>,        // height, width, colour variation, -
    @location(2) p1_rotation: vec4<f32>,  // P1 xyz, rotation of the top segment points
    @location(3) p2: vec4<f32>,           // P2 xyz, faded-out fraction (Sec. 6.1)
    @location(4) p3: vec4<f32>,
}

struct PlantOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
    @location(3) uv: vec2<f32>,
    @location(4) ao: f32,
    @location(5) @interpolate(flat) layer: u32,
    // Fade alpha (Sec. 6.1) and a per-blade threshold in [0, 1) for the dissolve.
    @location(6) @interpolate(flat) fade: vec2<f32>,
}

// Eq. (5): p = P0(1-t)^3 + 3 P1 t(1-t)^2 + 3 P2 t^2(1-t) + P3 t^3 (same as `blade::bezier`).
fn bezier(p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, p3: vec3<f32>, t: f32) -> vec3<f32> {
    let s = 1.0 - t;
    return p0 * (s * s * s) + p1 * (3.0 * t * s * s) + p2 * (3.0 * t * t * s) + p3 * (t * t * t);
}

// dp/dt of Eq. (5).
fn bezier_tangent(p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, p3: vec3<f32>, t: f32) -> vec3<f32> {
    let s = 1.0 - t;
    return 3.0 * s * s * (p1 - p0) + 6.0 * s * t * (p2 - p1) + 3.0 * t * t * (p3 - p2);
}

// One triangle strip per blade: 2n vertices, two segment points per backbone point (Fig. 5).
@vertex
fn vs_blade(@builtin(vertex_index) vertex: u32, b: BladeIn) -> PlantOut {
    var out: PlantOut;
    let n = max(u32(params.shape.x), 2u);
    let i = min(vertex / 2u, n - 1u);
    let t = f32(i) / f32(n - 1u);
    let p0 = b.root_facing.xyz;
    let backbone = bezier(p0, b.p1_rotation.xyz, b.p2.xyz, b.p3.xyz, t);
    let d = bezier_tangent(p0, b.p1_rotation.xyz, b.p2.xyz, b.p3.xyz, t);
    let tangent = select(vec3(0.0, 1.0, 0.0), normalize(d), length(d) > 1e-6);
    // Sec. 3.2.5: the segment points of backbone point i turn by theta * i / (n - 1) around
    // the upward direction; they stay horizontal ("always perpendicular to the upward direction").
    let facing = b.root_facing.w + b.p1_rotation.w * t;
    let side_axis = vec3(cos(facing), 0.0, sin(facing));
    let side = select(-1.0, 1.0, (vertex & 1u) == 1u);
    let world = backbone + side_axis * (0.5 * b.shape.y * side);
    let face = normalize(cross(side_axis, tangent));

    let variation = b.shape.z * params.color_root.w;
    var albedo = mix(params.color_root.rgb, params.color_tip.rgb, pow(t, 0.8));
    albedo *= 1.0 + variation;
    albedo.r *= 1.0 + 0.6 * max(variation, 0.0);

    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    out.normal = normalize(face + side_axis * side * 0.35);
    out.albedo = albedo;
    out.uv = vec2(0.5 + 0.5 * side, t);
    // Darker near the root: neighbouring blades hide the sky.
    out.ao = mix(0.3, 1.0, t);
    out.layer = 0u;
    out.fade = vec2(1.0 - b.p2.w, fract(sin(dot(p0.xz, vec2(12.9898, 78.233))) * 43758.547));
    return out;
}

@fragment
fn fs_blade(in: PlantOut) -> @location(0) vec4<f32> {
    // Level 0 only: a cut-out's alpha must not blur away with distance (see the essay).
    let texel = textureSampleLevel(blade_texture, texture_sampler, in.uv, 0.0);
    // Fading (Sec. 6.1): blended, the alpha scales; otherwise the blade dissolves.
    let blend = params.modes.x > 0.5;
    let alpha = texel.a * select(1.0, in.fade.x, blend);
    if (alpha < params.shape.y || (!blend && in.fade.y >= in.fade.x)) {
        discard;
    }
    // The texture holds a luminance around 0.85: lift it so the mean matches the plain colours.
    let albedo = in.albedo * texel.rgb * 1.15;
    let lit = shade_leaf(albedo, normalize(in.normal), in.world, in.ao, params.color_tip.w);
    return vec4(apply_fog(lit, in.world), alpha);
}

struct FlowerIn {
    @location(0) pos_spin: vec4<f32>,     // petal centre, spin
    @location(1) axis_layer: vec4<f32>,   // petal normal (stalk direction), texture layer
}

// A square petal quad (4-vertex strip) perpendicular to the stalk: horizontal at rest
// (Sec. 3.3), tilting as the petal point is blown aside.
@vertex
fn vs_flower(@builtin(vertex_index) vertex: u32, f: FlowerIn) -> PlantOut {
    var out: PlantOut;
    let corner = vec2(f32(vertex & 1u), f32((vertex >> 1u) & 1u));
    let normal = normalize(f.axis_layer.xyz);
    let helper = select(vec3(1.0, 0.0, 0.0), vec3(0.0, 0.0, 1.0), abs(normal.x) > 0.9);
    let t0 = normalize(cross(normal, helper));
    let t1 = cross(normal, t0);
    let spin = f.pos_spin.w;
    let a = cos(spin) * t0 + sin(spin) * t1;
    let b = cross(normal, a);
    let offset = (corner * 2.0 - 1.0) * 0.5 * params.shape.z;
    let world = f.pos_spin.xyz + a * offset.x + b * offset.y;
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    out.normal = normal;
    out.albedo = vec3(1.0);
    out.uv = corner;
    out.ao = 1.0;
    out.layer = u32(f.axis_layer.w);
    out.fade = vec2(1.0, 0.0);
    return out;
}

@fragment
fn fs_flower(in: PlantOut) -> @location(0) vec4<f32> {
    let texel = textureSampleLevel(petal_textures, texture_sampler, in.uv, in.layer, 0.0);
    if (texel.a < params.shape.y) {
        discard;
    }
    let lit = shade_leaf(texel.rgb, normalize(in.normal), in.world, in.ao, params.color_tip.w);
    return vec4(apply_fog(lit, in.world), texel.a);
}
