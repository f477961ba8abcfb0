//! Geometry cells on the GPU: one storage buffer of [`CellRecord`]s and the instanced draws
//! that cover them.
//!
//! Instance `i` of a blade draw is blade `i % n` of the patch (`n` blades) in the cell at slot
//! `i / n` of the bound *page* of cells (`shaders/grass.wgsl`, `vs_blade`). Blade ranges of
//! consecutive cells that meet therefore merge into one draw: a cell drawn whole is the range
//! `slot·n .. slot·n + n`, and a run of such cells is one draw. With geometry everywhere (the
//! `finest` variant on the 240 m prairie: 230 000 cells of 16 blocks) that is a handful of
//! draws where one per visible block of every cell took minutes a frame on lavapipe. A page
//! holds at most `u32::MAX / n` cells, so instance indices never overflow; pages are bound with
//! a dynamic offset.

use std::ops::Range;

use grassbench::technique::ranges::push_merged;
use grassbench::wgpu;

use crate::shader::CellRecord;

/// Bytes of one cell in the storage buffer.
pub const CELL_BYTES: u64 = std::mem::size_of::<CellRecord>() as u64;

/// The draws of one page of cells.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Page {
    /// Index of the page's first cell in the cell buffer.
    pub first_cell: u32,
    /// Instance ranges, one draw each.
    pub draws: Vec<Range<u32>>,
}

/// How cells are paged for a patch of `blades` blades on a device.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Paging {
    /// Blades in the patch (`n`).
    pub blades: u32,
    /// Cells per page: a multiple of the storage offset alignment, with `cells · n` under 2³².
    pub page_cells: u32,
}

impl Paging {
    /// Paging for `blades` blades a patch within `limits`.
    pub fn new(blades: u32, limits: &wgpu::Limits) -> Self {
        let blades = blades.max(1);
        let align = (u64::from(limits.min_storage_buffer_offset_alignment) / CELL_BYTES).max(1);
        let by_index = u64::from(u32::MAX) / u64::from(blades);
        let by_binding = limits.max_storage_buffer_binding_size / CELL_BYTES;
        let cells = by_index.min(by_binding) / align * align;
        Self {
            blades,
            page_cells: cells.clamp(align, u64::from(u32::MAX)) as u32,
        }
    }

    /// Cells the buffer must hold for `len` cells: a power of two (at least 64) while one page
    /// suffices, else whole pages, so every page's binding lies inside the buffer.
    pub fn capacity(&self, len: usize) -> usize {
        let page = self.page_cells as usize;
        let c = len.next_power_of_two().max(64);
        if c <= page {
            c
        } else {
            len.div_ceil(page) * page
        }
    }

    /// Cells visible through one binding of a buffer of `capacity` cells.
    pub fn binding_cells(&self, capacity: usize) -> u64 {
        (capacity as u64).min(u64::from(self.page_cells))
    }

    /// The draws for cells whose blade ranges (into the patch) are `ranges`, in buffer order:
    /// each range becomes instances of its cell's slot, and ranges that meet are merged.
    pub fn draws<'a>(&self, ranges: impl IntoIterator<Item = &'a [Range<u32>]>) -> Vec<Page> {
        let mut pages: Vec<Page> = Vec::new();
        for (k, cell) in ranges.into_iter().enumerate() {
            let k = k as u32;
            let first_cell = k / self.page_cells * self.page_cells;
            if pages.last().is_none_or(|p| p.first_cell != first_cell) {
                pages.push(Page {
                    first_cell,
                    draws: Vec::new(),
                });
            }
            let Some(page) = pages.last_mut() else {
                continue;
            };
            let base = (k - first_cell) * self.blades;
            for r in cell {
                push_merged(&mut page.draws, base + r.start..base + r.end);
            }
        }
        pages
    }
}

/// Layout of group 2 of the blade pipelines: the cells (binding 0, one page at a dynamic
/// offset) and the patch's blades (binding 4), both read in the vertex shader.
pub fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let storage = |binding, dynamic, min| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: dynamic,
            min_binding_size: wgpu::BufferSize::new(min),
        },
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("boulanger cells (group 2)"),
        entries: &[
            storage(0, true, CELL_BYTES),
            storage(
                4,
                false,
                std::mem::size_of::<crate::patch::PatchBlade>() as u64,
            ),
        ],
    })
}

/// A cell buffer of `capacity` cells and its bind group (pages of `binding_cells`).
pub fn buffer(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    blades: &wgpu::Buffer,
    capacity: usize,
    binding_cells: u64,
) -> (wgpu::Buffer, wgpu::BindGroup) {
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("boulanger geometry cells"),
        size: capacity as u64 * CELL_BYTES,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let group = group(device, layout, &buffer, binding_cells, blades);
    (buffer, group)
}

/// The bind group of `cells` (seen `binding_cells` at a time) and `blades`.
pub fn group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    cells: &wgpu::Buffer,
    binding_cells: u64,
    blades: &wgpu::Buffer,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("boulanger cells (group 2)"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: cells,
                    offset: 0,
                    size: wgpu::BufferSize::new(binding_cells * CELL_BYTES),
                }),
            },
            wgpu::BindGroupEntry {
                binding: 4,
                resource: blades.as_entire_binding(),
            },
        ],
    })
}

#[cfg(test)]
#[allow(clippy::single_range_in_vec_init)]
mod tests {
    use super::*;

    fn paging(blades: u32, page_cells: u32) -> Paging {
        Paging { blades, page_cells }
    }

    #[test]
    fn whole_cells_in_a_row_are_one_draw() {
        let p = paging(10, 1024);
        let full = [0..4, 4..10];
        let pages = p.draws([&full[..], &full[..], &full[..]]);
        assert_eq!(
            pages,
            vec![Page {
                first_cell: 0,
                draws: vec![0..30]
            }]
        );
    }

    #[test]
    fn partial_ranges_keep_their_cells_and_gaps() {
        let p = paging(10, 1024);
        let pages = p.draws([&[0..3, 5..10][..], &[0..2][..], &[][..], &[4..6][..]]);
        assert_eq!(pages[0].draws, vec![0..3, 5..12, 34..36]);
    }

    #[test]
    fn pages_restart_slots_and_never_overflow() {
        let limits = wgpu::Limits::default();
        let p = Paging::new(262_144, &limits);
        assert!(u64::from(p.page_cells) * 262_144 <= u64::from(u32::MAX));
        assert_eq!(
            u64::from(p.page_cells) * CELL_BYTES
                % u64::from(limits.min_storage_buffer_offset_alignment),
            0
        );
        let q = paging(10, 8);
        let full = [0..10];
        let pages = q.draws(std::iter::repeat_n(&full[..], 20));
        let firsts: Vec<u32> = pages.iter().map(|p| p.first_cell).collect();
        assert_eq!(firsts, vec![0, 8, 16]);
        assert_eq!(pages[2].draws, vec![0..40]);
        assert_eq!(q.capacity(20), 24);
        assert_eq!(q.binding_cells(24), 8);
        assert_eq!(paging(10, 1 << 20).capacity(20), 64);
    }
}
