// Mip chain of the horizontal slice (Boulanger Sec. 3.3: trilinear filtering of far grass):
// each level is the 2x2 box average of the one above, of premultiplied channels, so coverage,
// colour, normal, threshold and occlusion stay consistent. Composed after the prelude.

@group(1) @binding(0) var src_color: texture_2d<f32>;
@group(1) @binding(1) var src_aux: texture_2d<f32>;
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
    @location(1) aux: vec4<f32>,
}

@fragment
fn fs_mip(in: MipVertex) -> MipOut {
    // The centre of a target texel is the corner of four source texels: bilinear = box filter.
    var out: MipOut;
    out.color = textureSampleLevel(src_color, src_sampler, in.uv, 0.0);
    out.aux = textureSampleLevel(src_aux, src_sampler, in.uv, 0.0);
    return out;
}
