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
use glam::{IVec2, Vec2};

/// GPU memory of the horizontal slice's BTF of side `resolution` with its mip chain.
pub fn texture_bytes(resolution: u32) -> u64 {
    crate::btf::texture_bytes(resolution, resolution, crate::btf::array_layers(1))
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

/// The patch orientation map read at `local`, a position in cells from the first cell
/// `first_cell` of a macro-cell (`local = patchSize · (u, v)` of Eq. 6, `patchSize` the
/// macro-cell's side in cells), on the cells of `grid` with the scene's `seed`: the
/// orientation of the cell there (clamped to the grid, as the map's unfiltered texel is) and,
/// by Eq. 7, the horizontal slice's texture coordinates `u' = (patchSize · orientation · u)
/// mod 1`. The twin of `orientation_texel` in `shaders/grass.wgsl`.
pub fn orientation_texel(
    grid: &CellGrid,
    seed: u64,
    local: Vec2,
    first_cell: IVec2,
) -> (Orientation, Vec2) {
    let max = IVec2::new(grid.nx as i32 - 1, grid.nz as i32 - 1);
    let cell = (first_cell + local.floor().as_ivec2()).clamp(IVec2::ZERO, max.max(IVec2::ZERO));
    let orientation = Orientation::of_cell(seed, cell.x as u32, cell.y as u32);
    let mirrored = orientation.signs() * local;
    // `mod 1` into [0, 1) for negative coordinates too (WGSL's `fract`, not Rust's).
    (orientation, mirrored - mirrored.floor())
}

/// Format of the patch orientation map.
pub const ORIENTATION_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Uint;

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
            format: ORIENTATION_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &data,
    );
    (texture.create_view(&Default::default()), data.len() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Eq. 7 through the map shows, at every interior point of a macro-cell, the texel of the
    /// mirrored patch that geometry draws there (Sec. 3.1: the cell's copy is the patch
    /// mirrored about its centre, so the point `w` of a cell shows the patch point
    /// `orientation.apply(w − centre)`, at texture coordinates `point / size + 1/2` in the
    /// top view), and it is Eq. 7's `(patchSize · orientation · u) mod 1` as printed.
    #[test]
    fn eq_7_shows_the_mirrored_patch_that_geometry_draws() {
        let grid = CellGrid {
            origin: Vec2::new(-10.0, -6.0),
            cell: 0.5,
            nx: 40,
            nz: 24,
        };
        let mut mirrored = [0u32; 4];
        for seed in [1, 7] {
            for (first, side) in [
                (IVec2::new(0, 0), 1),
                (IVec2::new(4, 8), 4),
                (IVec2::new(16, 8), 8),
            ] {
                for a in 0..37 {
                    for b in 0..29 {
                        // Interior points of the macro-cell, u in (0, 1)², none on a cell border.
                        let u = Vec2::new((a as f32 + 0.37) / 37.0, (b as f32 + 0.61) / 29.0);
                        let local = u * side as f32;
                        let (o, uv) = orientation_texel(&grid, seed, local, first);
                        let cell = first + local.floor().as_ivec2();
                        let expected = Orientation::of_cell(seed, cell.x as u32, cell.y as u32);
                        assert_eq!(o, expected);
                        mirrored[o.bits() as usize] += 1;
                        let w = grid.origin + (first.as_vec2() + local) * grid.cell;
                        let centre = grid.cell_min(cell.x as u32, cell.y as u32) + 0.5 * grid.cell;
                        let patch_uv = expected.apply((w - centre) / grid.cell) + 0.5;
                        // Measured 9.5e-7 (the world position's rounding, coordinates up
                        // to 10 m, over a 0.5 m cell); limit 4x above.
                        assert!(
                            (uv - patch_uv).abs().max_element() < 4e-6,
                            "{local}: {uv} vs {patch_uv}"
                        );
                        let printed =
                            (side as f32 * expected.signs() * u).map(|c| c.rem_euclid(1.0));
                        // Measured 0 (the same operations); 1e-6 allows an ulp of `mod 1`.
                        assert!(
                            (uv - printed).abs().max_element() < 1e-6,
                            "{local}: {uv} vs {printed}"
                        );
                    }
                }
            }
        }
        // Every mirror was seen, so the signs were exercised both ways.
        assert!(mirrored.iter().all(|&c| c > 100), "{mirrored:?}");
        // Past the grid, the map's last texel is read (clamped), as the GPU's textureLoad.
        let (o, _) = orientation_texel(&grid, 1, Vec2::new(3.5, 0.2), IVec2::new(39, -2));
        assert_eq!(o, Orientation::of_cell(1, 39, 0));
    }
}
