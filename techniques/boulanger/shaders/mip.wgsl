// Mip chain of the BTF layers (Boulanger Sec. 3.3: trilinear filtering of far grass): each
// level is the 2x2 box average of the one above, of premultiplied channels, so coverage,
// colour, diffuse factors, threshold and occlusion stay consistent. Composed after the prelude.

@group(1) @binding(0) var src_color: texture_2d<f32>;
@group(1) @binding(1) var src_diffuse: texture_2d<f32>;
@group(1) @binding(3) var src_extra: texture_2d<f32>;
@group(1) @binding(2) var src_sampler: sampler;

struct MipVertex {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn vs_mip(@builtin(vertex_index) vertex: u32) -> MipVertex {
    // One triangle covering the target.
    let p = vec2(f32((vertex << 1u) & 2u), f32(vertex & 2u));
    var out: MipVertex;
    out.position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
    out.uv = vec2(p.x, 1.0 - p.y);
    return out;
}

struct MipOut {
    @location(0) color: vec4<f32>,
    @location(1) diffuse: vec4<f32>,
    @location(2) extra: vec4<f32>,
}

@fragment
fn fs_mip(in: MipVertex) -> MipOut {
    // The centre of a target texel is the corner of four source texels: bilinear = box filter.
    var out: MipOut;
    out.color = textureSampleLevel(src_color, src_sampler, in.uv, 0.0);
    out.diffuse = textureSampleLevel(src_diffuse, src_sampler, in.uv, 0.0);
    out.extra = textureSampleLevel(src_extra, src_sampler, in.uv, 0.0);
    return out;
}
