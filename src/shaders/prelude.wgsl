// grassbench shared WGSL prelude: prepended to every technique shader (see `shaders::compose`).
// Bind group 0 is owned by the core and set by the runner before a technique's passes begin;
// techniques bind their own resources at groups 1 and up.

struct Globals {
    view_proj: mat4x4<f32>,
    inv_view_proj: mat4x4<f32>,
    // xyz: eye position; w: time (s)
    camera_pos: vec4<f32>,
    // xyz: unit view direction; w: dt (s)
    camera_forward: vec4<f32>,
    // xyz: unit vector towards the sun; w: unused
    sun_direction: vec4<f32>,
    // rgb: sun irradiance (linear); w: unused
    sun_color: vec4<f32>,
    // rgb: ambient (linear); w: unused
    ambient: vec4<f32>,
    sky_zenith: vec4<f32>,
    sky_horizon: vec4<f32>,
    // rgb: bare ground albedo; w: fog density (1/m)
    ground_color: vec4<f32>,
    // xy: terrain min corner (x, z); zw: terrain size (x, z)
    terrain: vec4<f32>,
    // xy: target size in pixels; zw: 1 / size
    viewport: vec4<f32>,
    // x: frame index; y: seed (low 32 bits); z: debug view; w: unused
    frame: vec4<u32>,
    // x: largest wind speed in the wind texture (m/s); yzw: unused
    wind_info: vec4<f32>,
    // x: lowest ground height (m); y: highest; z: camera far plane (m); w: unused
    terrain_range: vec4<f32>,
    // The scene's moving object: xyz centre, w radius (0: none)
    object: vec4<f32>,
    // xyz: the point light's position (m); w: its attenuation beta (1/m^2)
    point_position: vec4<f32>,
    // rgb: the point light's intensity; w: 1 when there is a point light, else 0
    point_color: vec4<f32>,
}

@group(0) @binding(0) var<uniform> globals: Globals;
@group(0) @binding(1) var height_map: texture_2d<f32>;
@group(0) @binding(2) var density_map: texture_2d<f32>;
@group(0) @binding(3) var covering_map: texture_2d<u32>;
@group(0) @binding(4) var wind_map: texture_2d<f32>;

const PI: f32 = 3.14159265358979;
const COVER_NONE: u32 = 0u;
const COVER_TREE: u32 = 253u;
const COVER_STONE: u32 = 254u;
const COVER_GRASS: u32 = 255u;

// Map coordinates in [0, 1]^2 of a world position (x, z).
fn terrain_uv(xz: vec2<f32>) -> vec2<f32> {
    return (xz - globals.terrain.xy) / globals.terrain.zw;
}

// Bilinear lookup in an unfilterable map, matching the CPU's `Grid::bilinear` (Zhang Eq. 11-13).
fn bilinear_r(map: texture_2d<f32>, uv: vec2<f32>) -> f32 {
    let dims = vec2<f32>(textureDimensions(map));
    let p = clamp(uv, vec2(0.0), vec2(1.0)) * (dims - 1.0);
    let p0 = floor(p);
    let f = p - p0;
    let i0 = vec2<i32>(p0);
    let i1 = min(i0 + 1, vec2<i32>(dims) - 1);
    let a = textureLoad(map, i0, 0).r;
    let b = textureLoad(map, vec2(i1.x, i0.y), 0).r;
    let c = textureLoad(map, vec2(i0.x, i1.y), 0).r;
    let d = textureLoad(map, i1, 0).r;
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

// Ground height (m) at (x, z).
fn terrain_height(xz: vec2<f32>) -> f32 {
    return bilinear_r(height_map, terrain_uv(xz));
}

// Unit ground normal at (x, z), central differences over one map sample.
fn terrain_normal(xz: vec2<f32>) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(height_map));
    let e = globals.terrain.zw / max(dims - 1.0, vec2(1.0)) * 0.5;
    let dx = terrain_height(xz + vec2(e.x, 0.0)) - terrain_height(xz - vec2(e.x, 0.0));
    let dz = terrain_height(xz + vec2(0.0, e.y)) - terrain_height(xz - vec2(0.0, e.y));
    return normalize(vec3(-dx / (2.0 * e.x), 1.0, -dz / (2.0 * e.y)));
}

// Grass density in [0, 1] at (x, z) (Boulanger Sec. 3.4).
fn terrain_density(xz: vec2<f32>) -> f32 {
    return bilinear_r(density_map, terrain_uv(xz));
}

// Covering ID at (x, z), nearest sample (Zhang Sec. 5.5.2).
fn terrain_covering(xz: vec2<f32>) -> u32 {
    let dims = vec2<f32>(textureDimensions(covering_map));
    let p = vec2<i32>(round(clamp(terrain_uv(xz), vec2(0.0), vec2(1.0)) * (dims - 1.0)));
    return textureLoad(covering_map, p, 0).r;
}

// Wind velocity (m/s) at (x, z), bilinear in the wind texture the core bakes every frame.
fn wind_at(xz: vec2<f32>) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(wind_map));
    let p = clamp(terrain_uv(xz), vec2(0.0), vec2(1.0)) * (dims - 1.0);
    let p0 = floor(p);
    let f = p - p0;
    let i0 = vec2<i32>(p0);
    let i1 = min(i0 + 1, vec2<i32>(dims) - 1);
    let a = textureLoad(wind_map, i0, 0).xyz;
    let b = textureLoad(wind_map, vec2(i1.x, i0.y), 0).xyz;
    let c = textureLoad(wind_map, vec2(i0.x, i1.y), 0).xyz;
    let d = textureLoad(wind_map, i1, 0).xyz;
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

// Lambert + ambient with the scene's lights; `ao` darkens the ambient term only.
fn shade(albedo: vec3<f32>, normal: vec3<f32>, ao: f32) -> vec3<f32> {
    let ndl = max(dot(normal, globals.sun_direction.xyz), 0.0);
    return albedo * (globals.ambient.rgb * ao + globals.sun_color.rgb * ndl);
}

// Two-sided shading for thin leaves: the normal faces the viewer, and light from behind
// passes through (`translucency` of the back-side irradiance).
fn shade_leaf(albedo: vec3<f32>, normal: vec3<f32>, world_pos: vec3<f32>, ao: f32, translucency: f32) -> vec3<f32> {
    let n = facing_viewer(normal, world_pos);
    var direct = globals.sun_color.rgb * leaf_lambert(n, globals.sun_direction.xyz, translucency);
    if (globals.point_color.w > 0.0) {
        direct += point_light(world_pos) * leaf_lambert(n, normalize(globals.point_position.xyz - world_pos), translucency);
    }
    return albedo * leaf_irradiance(direct, ao);
}

// `normal` or its opposite, whichever faces the eye from `world_pos` (a leaf has two sides).
fn facing_viewer(normal: vec3<f32>, world_pos: vec3<f32>) -> vec3<f32> {
    let to_eye = normalize(globals.camera_pos.xyz - world_pos);
    return select(-normal, normal, dot(normal, to_eye) >= 0.0);
}

// What `shade_leaf` multiplies the albedo by, from the direct light on the leaf: the ambient
// term darkened by `ao`, the direct one by `direct_occlusion(ao)`. Affine in `ao`.
fn leaf_irradiance(direct: vec3<f32>, ao: f32) -> vec3<f32> {
    return globals.ambient.rgb * ao + direct * direct_occlusion(ao);
}

// How much of the direct light reaches a leaf point whose ambient occlusion is `ao`: half as
// much darkening as the ambient light gets.
fn direct_occlusion(ao: f32) -> f32 {
    return mix(0.5, 1.0, ao);
}

// Two-sided Lambert factor of a leaf whose normal `n` faces the viewer, for the unit vector
// `l` towards a light.
fn leaf_lambert(n: vec3<f32>, l: vec3<f32>, translucency: f32) -> f32 {
    return max(dot(n, l), 0.0) + max(dot(-n, l), 0.0) * translucency;
}

// The point light's irradiance at `p`: I_d / (1 + beta d^2) (Boulanger Sec. 3.3); zero when the
// scene has none.
fn point_light(p: vec3<f32>) -> vec3<f32> {
    let d = distance(globals.point_position.xyz, p);
    return globals.point_color.rgb * globals.point_color.w / (1.0 + globals.point_position.w * d * d);
}

// Sky colour in a view direction: horizon to zenith gradient with a sun glow.
fn sky_color(dir: vec3<f32>) -> vec3<f32> {
    let up = clamp(dir.y, 0.0, 1.0);
    let base = mix(globals.sky_horizon.rgb, globals.sky_zenith.rgb, pow(up, 0.6));
    let sun = pow(max(dot(dir, globals.sun_direction.xyz), 0.0), 256.0);
    return base + globals.sun_color.rgb * sun * 0.5;
}

// Aerial perspective: the same haze over every technique's grass and the ground.
fn apply_fog(color: vec3<f32>, world_pos: vec3<f32>) -> vec3<f32> {
    return mix(color, globals.sky_horizon.rgb, fog_factor(world_pos));
}

// How much haze lies between the eye and `world_pos`, in [0, 1).
fn fog_factor(world_pos: vec3<f32>) -> f32 {
    let d = distance(world_pos, globals.camera_pos.xyz);
    return 1.0 - exp(-d * globals.ground_color.w);
}

// Integer hash (PCG), for per-instance variation in shaders.
fn hash_u32(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn hash_f32(v: u32) -> f32 {
    return f32(hash_u32(v)) / 4294967295.0;
}
