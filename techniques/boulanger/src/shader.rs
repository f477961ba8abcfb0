//! The blade, bake and slice shader (`shaders/grass.wgsl`) and the Rust mirrors of the structs
//! it reads: plain `#[repr(C)]` records, shared by every module that fills a buffer for it. A
//! leaf: nothing here depends on the rest of the crate.

use grassbench::{bytemuck, wgpu};

/// The blade, bake and slice shader (without the prelude).
pub const SHADER: &str = include_str!("../shaders/grass.wgsl");

/// Mirror of the shader's `Params` uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ParamsUniform {
    /// Root colour; w = colour variation.
    pub color_root: [f32; 4],
    /// Tip colour; w = translucency.
    pub color_tip: [f32; 4],
    /// Segments, gravity, wind response, ambient occlusion at the root.
    pub blade: [f32; 4],
    /// min_geom, max_geom, omega, alpha-test threshold.
    pub lod: [f32; 4],
    /// Patch size, slice height (m), slice texture side, bake top (m).
    pub tile: [f32; 4],
    /// Vertical slices per axis, min_btf, max_btf; w = 1 with the shadow mask (Sec. 3.5).
    pub btf: [f32; 4],
}

/// Mirror of the shader's `Cell`: one cell's copy of the patch. A record of the geometry
/// cells' storage buffer (`cells.rs`) and of the bake's, and an instance of the vertical
/// slices' vertex buffer.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CellRecord {
    /// World (x, z) of the patch centre, mirror signs for x and z.
    pub center_signs: [f32; 4],
    /// x = 1 when baking; then y = projection (0 top, 1 across x, 2 across z), z = the
    /// slice's coordinate on its axis (m from the patch centre), w = side of the camera (±1).
    /// Otherwise yzw = the cell's weights ([`crate::lod::CellWeights::encode`]): `(0, 0, 0)`
    /// by distance, `(1, w_g, far fade)` fixed for the cell.
    pub mode: [f32; 4],
}

impl CellRecord {
    /// As instance attributes (the vertical slices' vertex buffer).
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Self>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4],
    };
}

/// One horizontal slice quad (instance of the slice pipelines).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SliceQuad {
    /// World min (x, z) and size (x, z), m.
    pub rect: [f32; 4],
    /// First cell (i, j) and cells covered (ni, nj).
    pub cells: [f32; 4],
    /// Quads per side; yzw = the weights of its cells ([`crate::lod::CellWeights::encode`]).
    pub tess: [f32; 4],
}

impl SliceQuad {
    /// As instance attributes (the slice quads' vertex buffer).
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Self>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4, 2 => Float32x4],
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_mirror_the_shader() {
        for (name, size) in [
            ("Params", std::mem::size_of::<ParamsUniform>()),
            ("Cell", std::mem::size_of::<CellRecord>()),
        ] {
            assert_eq!(
                grassbench::shaders::struct_size(SHADER, name).unwrap() as usize,
                size,
                "boulanger {name}"
            );
        }
    }
}
