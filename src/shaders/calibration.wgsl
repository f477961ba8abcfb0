// Micro-workloads measuring an adapter's raw limits (see `calibration.rs`). They use no
// scene resources: bind group 0 is declared by the prelude but not read here.

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) color: vec4<f32>,
}

// Triangle throughput: per instance, a blade-like strip of 11 vertices (9 triangles) about 2
// pixels wide and 10 tall, scattered over the screen at hashed positions, depth-tested like
// grass blades: the least a rasteriser can spend on a reference blade's triangles. Strips are
// laid out in scan order over the screen (as a blade field is, cell by cell), jittered.
@vertex
fn vs_tiny(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> Out {
    let cols = u32(calib.grid.x);
    let cell = vec2(f32(i % cols), f32(i / cols)) + vec2(hash_f32(i * 2u), hash_f32(i * 2u + 1u));
    let center = cell / calib.grid * 2.0 - 1.0;
    let px = 2.0 * calib.inv_size;
    let level = f32(v / 2u);
    let side = f32(v & 1u);
    let corner = vec2(side * 2.0 * (1.0 - level / 5.0), level * 2.0);
    var out: Out;
    out.position = vec4(center + corner * px, hash_f32(i * 7u + 3u), 1.0);
    out.color = vec4(0.2, 0.6, 0.1, 1.0);
    return out;
}

// Fill rate: full-screen triangles blended over each other.
@vertex
fn vs_full(@builtin(vertex_index) v: u32) -> Out {
    let uv = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    var out: Out;
    out.position = vec4(uv * 2.0 - 1.0, 0.5, 1.0);
    out.color = vec4(0.3, 0.5, 0.2, 0.25);
    return out;
}

@fragment
fn fs_color(in: Out) -> @location(0) vec4<f32> {
    return in.color;
}

struct Calib {
    inv_size: vec2<f32>,
    // strips per row and rows
    grid: vec2<f32>,
}

@group(1) @binding(0) var<uniform> calib: Calib;
@group(1) @binding(1) var<storage, read> src: array<vec4<f32>>;
@group(1) @binding(2) var<storage, read_write> dst: array<vec4<f32>>;

// Memory bandwidth: copy one buffer into another, 16 bytes per invocation.
@compute @workgroup_size(256)
fn cs_copy(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * 65535u * 256u;
    if (i < arrayLength(&src)) {
        dst[i] = src[i];
    }
}
