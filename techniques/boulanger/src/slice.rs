//! The horizontal slice (Boulanger Sec. 3.3, last paragraphs): one BTF layer of the geometric
//! patch seen from above ([`crate::btf`]), and the patch orientation map (Sec. 4.1) that lets
//! macro-cells repeat it with each cell's mirror.
//!
//! Its bake is an orthographic top view of the patch and its eight neighbours over the whole
//! height of the blades; the shaders draw it close to the bottom of the patch (Sec. 3.3), so
//! it shows mostly from high viewpoints.

use std::ops::Range;

use grassbench::wgpu;
use grassbench::wgpu::util::DeviceExt as _;

use crate::patch::Orientation;
use crate::patch::PatchBlade;
use crate::quadtree::CellGrid;
use crate::shader::CellRecord;
use crate::vertical::box_layer;
use glam::Vec2;

/// GPU memory of the horizontal slice's BTF of side `resolution` with its mip chain.
pub fn texture_bytes(resolution: u32) -> u64 {
    crate::btf::texture_bytes(resolution, resolution, 1)
}

/// The horizontal slice's one layer for [`crate::btf::bake`]: nine cells with the top-view
/// camera (`mode.y = 0`) and, of their blades, those reaching over the centre patch (the
/// view's bounds): about 1.5 patches' worth instead of nine, which matters since the bake is
/// bound by vertex work on lavapipe.
pub fn bake_layer(
    patch_size: f32,
    blades: &[PatchBlade],
    gravity: f32,
) -> (Vec<CellRecord>, Vec<u32>, Range<u32>) {
    let side = 0.5 * patch_size;
    box_layer(
        patch_size,
        blades,
        gravity,
        [1.0, 0.0, 0.0, 0.0],
        Vec2::splat(side),
    )
}

/// The patch orientation map (Sec. 4.1, Fig. 20a): one `R8Uint` texel per cell, bit 0 = mirror
/// x, bit 1 = mirror z; the same hash as the CPU's [`Orientation::of_cell`].
pub fn orientation_map(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    grid: &CellGrid,
    seed: u64,
) -> (wgpu::TextureView, u64) {
    let data: Vec<u8> = (0..grid.nz)
        .flat_map(|j| (0..grid.nx).map(move |i| Orientation::of_cell(seed, i, j).bits()))
        .collect();
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some("boulanger patch orientation map"),
            size: wgpu::Extent3d {
                width: grid.nx,
                height: grid.nz,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R8Uint,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &data,
    );
    (texture.create_view(&Default::default()), data.len() as u64)
}
