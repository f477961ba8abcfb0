// The sky, the ground, the scene's props (trees and stones) and its moving object, drawn
// identically for every technique before its grass. (Prepended with the prelude by
// `shaders::compose`.)

struct SkyOut {
    @builtin(position) position: vec4<f32>,
    @location(0) ndc: vec2<f32>,
}

@vertex
fn vs_sky(@builtin(vertex_index) index: u32) -> SkyOut {
    // One triangle covering the screen, at the far plane.
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    let ndc = uv * 2.0 - 1.0;
    var out: SkyOut;
    out.position = vec4(ndc, 1.0, 1.0);
    out.ndc = ndc;
    return out;
}

@fragment
fn fs_sky(in: SkyOut) -> @location(0) vec4<f32> {
    let far = globals.inv_view_proj * vec4(in.ndc, 1.0, 1.0);
    let dir = normalize(far.xyz / far.w - globals.camera_pos.xyz);
    return vec4(sky_color(dir), 1.0);
}

// Albedo of the soil under grass: litter and shadow.
const UNDER_GRASS: vec3<f32> = vec3(0.035, 0.06, 0.015);

struct GroundOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
}

// Cells along a chunk's side (`terrain::chunks::CHUNK_CELLS`).
const CHUNK_CELLS: u32 = 8u;

// The mesh vertex (column, row) the pattern's local vertex (i, j) stands on for a chunk
// instance (`chunk`: first mesh column and row, mesh vertices along x and z): turned onto the
// skirt's `edge` (0 west, 1 east, 2 south, 3 north; skirt patterns are built along the west
// edge; 4 = a surface, left as it is), then clamped to the mesh.
// Rust twin: `terrain::chunks::ChunkInstance::vertex`.
fn ground_vertex(chunk: vec4<u32>, edge: u32, local: vec2<u32>) -> vec2<u32> {
    var ij = local;
    switch edge {
        case 0u: { ij = vec2(0u, local.y); }
        case 1u: { ij = vec2(CHUNK_CELLS, local.y); }
        case 2u: { ij = vec2(local.y, 0u); }
        case 3u: { ij = vec2(local.y, CHUNK_CELLS); }
        default: {}
    }
    return min(chunk.xy + ij, chunk.zw - 1u);
}

// A chunk of the ground at one level (`src/terrain/chunks.rs`): the pattern's local vertex
// (`local`: i, j in mesh cells from the chunk's corner, 1 for a skirt's lowered copy), the
// instance's chunk (`chunk`: first mesh column and row, mesh vertices along x and z), the
// edge a skirt hangs from and how far. The vertex is the ground mesh's (`TerrainGpu::
// ground_mesh`): its xz spread evenly over the terrain, its height and normal read from the
// height map as the CPU's `Terrain::point_at` / `normal_at` do (their twins), so no storage
// buffer is bound to the vertex stage (adapters with WebGL2's limits have none there).
@vertex
fn vs_ground(
    @location(0) local: vec3<u32>,
    @location(1) chunk: vec4<u32>,
    @location(2) edge: u32,
    @location(3) depth: f32,
) -> GroundOut {
    let vertex = ground_vertex(chunk, edge, local.xy);
    let uv = vec2<f32>(vertex) / vec2<f32>(max(chunk.zw, vec2(2u)) - 1u);
    let xz = globals.terrain.xy + uv * globals.terrain.zw;
    let position = vec3(xz.x, terrain_height(xz) - depth * f32(local.z), xz.y);
    var out: GroundOut;
    out.position = globals.view_proj * vec4(position, 1.0);
    out.world = position;
    out.normal = terrain_normal(xz);
    return out;
}

@fragment
fn fs_ground(in: GroundOut) -> @location(0) vec4<f32> {
    let xz = in.world.xz;
    // Ground under grass is darker and greener (litter, shadow), bare ground is soil.
    let density = terrain_density(xz) * f32(terrain_covering(xz) == COVER_GRASS);
    let albedo = mix(globals.ground_color.rgb, UNDER_GRASS, clamp(density, 0.0, 1.0));
    let lit = shade(albedo, normalize(in.normal), 1.0);
    return vec4(apply_fog(lit, in.world), 1.0);
}

// The apron: ground beyond the terrain out to the far plane, just below the lowest terrain
// point, so the world does not end at the terrain's edge. Its colour is the soil of a sparse
// field, so distant terrain edges blend in rather than draw a line at the horizon.
@vertex
fn vs_apron(@builtin(vertex_index) index: u32) -> GroundOut {
    let corner = vec2<f32>(f32((index >> 1u) & 1u), f32(index & 1u)) * 2.0 - 1.0;
    let center = globals.terrain.xy + 0.5 * globals.terrain.zw;
    let reach = globals.terrain_range.z + max(globals.terrain.z, globals.terrain.w);
    let world = vec3(center.x + corner.x * reach, globals.terrain_range.x - 0.02, center.y + corner.y * reach);
    var out: GroundOut;
    out.position = globals.view_proj * vec4(world, 1.0);
    out.world = world;
    out.normal = vec3(0.0, 1.0, 0.0);
    return out;
}

@fragment
fn fs_apron(in: GroundOut) -> @location(0) vec4<f32> {
    let lit = shade(mix(globals.ground_color.rgb, UNDER_GRASS, 0.6), in.normal, 1.0);
    return vec4(apply_fog(lit, in.world), 1.0);
}

// The scene's props (Zhang 2006, Sec. 5.5.2): the simple trees and stones standing where the
// covering map holds IDs 253 and 254, baked into one static triangle list
// (`src/scene/props.rs`), flat-shaded and fogged.
struct PropIn {
    @location(0) position: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) color: vec4<f32>,
}

struct PropOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec3<f32>,
}

@vertex
fn vs_prop(v: PropIn) -> PropOut {
    var out: PropOut;
    out.position = globals.view_proj * vec4(v.position.xyz, 1.0);
    out.world = v.position.xyz;
    out.normal = v.normal.xyz;
    out.color = v.color.rgb;
    return out;
}

@fragment
fn fs_prop(in: PropOut) -> @location(0) vec4<f32> {
    let lit = shade(in.color, normalize(in.normal), 1.0);
    return vec4(apply_fog(lit, in.world), 1.0);
}

// The scene's moving object (`scene::ObjectConfig`): a sphere, ray-cast on a quad that faces
// the eye and holds its silhouette, writing its true depth so grass hides it and it hides grass.
const OBJECT_ALBEDO: vec3<f32> = vec3(0.55, 0.12, 0.08);

struct ObjectOut {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
}

@vertex
fn vs_object(@builtin(vertex_index) index: u32) -> ObjectOut {
    var out: ObjectOut;
    let centre = globals.object.xyz;
    let r = globals.object.w;
    let to_centre = centre - globals.camera_pos.xyz;
    let d = length(to_centre);
    // No object, or the eye inside it: every corner outside the clip volume. Chosen with
    // `select`s rather than branches, which decide on uniforms alone and would have lavapipe
    // re-specialise the shader whenever it is bound (`grassbench::shaders::uniform_branches`);
    // the clamps keep the unused side finite.
    let hidden = (r <= 0.0) | (d <= r * 1.01);
    let forward = to_centre / max(d, 1e-6);
    let across = cross(forward, vec3(0.0, 1.0, 0.0));
    let right = normalize(select(across, vec3(1.0, 0.0, 0.0), length(across) < 1e-4));
    let up = cross(right, forward);
    // Seen from the eye, the sphere's silhouette fits in a square of half side r·d/√(d²−r²) in
    // the plane through its centre.
    let half = 1.05 * r * d / sqrt(max(d * d - r * r, 1e-12));
    var corners = array(
        vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),
        vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0),
    );
    let k = corners[index % 6u];
    let world = centre + (right * k.x + up * k.y) * half;
    out.position = select(globals.view_proj * vec4(world, 1.0), vec4(0.0, 0.0, 2.0, 1.0), hidden);
    out.world = world;
    return out;
}

struct ObjectFragment {
    @location(0) color: vec4<f32>,
    @builtin(frag_depth) depth: f32,
}

@fragment
fn fs_object(in: ObjectOut) -> ObjectFragment {
    let eye = globals.camera_pos.xyz;
    let dir = normalize(in.world - eye);
    let oc = eye - globals.object.xyz;
    let b = dot(oc, dir);
    let h = b * b - (dot(oc, oc) - globals.object.w * globals.object.w);
    if (h < 0.0) {
        discard;
    }
    let p = eye + dir * (-b - sqrt(h));
    let n = normalize(p - globals.object.xyz);
    let clip = globals.view_proj * vec4(p, 1.0);
    var out: ObjectFragment;
    out.color = vec4(apply_fog(shade(OBJECT_ALBEDO, n, 1.0), p), 1.0);
    out.depth = clip.z / clip.w;
    return out;
}
