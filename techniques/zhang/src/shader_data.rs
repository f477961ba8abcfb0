//! The plain data the CPU writes for the shaders: per-instance records of blades, flowers and
//! billboard wings, the trees' and stones' vertex, and the parameter uniform. Each mirrors a
//! struct of `shaders/*.wgsl` byte for byte (`#[repr(C)]`, `bytemuck::Pod`); the vertex layouts
//! that bind them are in [`pipelines`](super::pipelines). A leaf module: it imports nothing of
//! the crate.

use grassbench::bytemuck;

/// Static per-blade data (vertex buffer 0 of the blade pipeline, instance step).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BladeStatic {
    /// Root `P0` xyz, facing angle (width axis, radians around y).
    pub root_facing: [f32; 4],
    /// Height, width, colour variation, unused.
    pub shape: [f32; 4],
}

/// Per-frame per-blade data (vertex buffer 1, instance step): the moving control points.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BladeDynamic {
    /// `P1` xyz; w = rotation θ of the top segment points (Sec. 3.2.5).
    pub p1_rotation: [f32; 4],
    /// `P2` xyz; w = how far the blade has faded out (Sec. 6.1; 0 = opaque).
    pub p2: [f32; 4],
    /// `P3` xyz; w unused.
    pub p3: [f32; 4],
}

/// Per-frame per-flower data (instance step).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FlowerInstance {
    /// Petal centre xyz; w = spin around the petal normal.
    pub pos_spin: [f32; 4],
    /// Petal normal (the stalk direction) xyz; w = petal texture layer.
    pub axis_layer: [f32; 4],
}

/// Per-frame data of one wing (instance step): a rectangle of a billboard (Sec. 4.1-4.2), or
/// the part of it that `wing_trim` keeps. "Centre" is its edge towards the billboard's
/// middle line, "outer" the other.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct WingInstance {
    /// Root (ground point) of the edge towards the middle line xyz; w = texture `u` there.
    pub centre_root: [f32; 4],
    /// Root of the outer edge xyz; w = texture `u` there.
    pub outer_root: [f32; 4],
    /// The whole wing's top above `centre_root` xyz; w = billboard texture layer.
    pub centre_top: [f32; 4],
    /// The whole wing's top above `outer_root` xyz; w = kept fraction of the texture's blades
    /// (the density).
    pub outer_top: [f32; 4],
    /// x = the grid's fade alpha (Sec. 6.1; 1 unless fading); y = the cut's height as a
    /// fraction of the wing's (texture `v` at its top edge); zw unused.
    pub fade: [f32; 4],
}

/// Mirror of the shader's `Params` uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ParamsUniform {
    /// Root colour; w = colour variation.
    pub color_root: [f32; 4],
    /// Tip colour; w = translucency.
    pub color_tip: [f32; 4],
    /// Backbone points, alpha cut-off, petal size (m), billboard height (m).
    pub shape: [f32; 4],
    /// x: 1 when blending (a fading blade's alpha scales its output alpha), 0 otherwise (a
    /// fading blade dissolves); yzw unused.
    pub modes: [f32; 4],
}
