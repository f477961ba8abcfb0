// Zhang 2006, Sec. 5.5.2: the simple trees and stones standing where the covering map holds
// IDs 253 and 254, baked into one static triangle list (`props.rs`), flat-shaded and fogged.
// Composed after the prelude. See `techniques/zhang/src/lib.rs`.

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
