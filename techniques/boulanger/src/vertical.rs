//! The vertical slices of a patch (Boulanger Sec. 3.3, Fig. 2 middle and Fig. 6): `N` slices
//! across x and `N` across z, each in the middle of its slab (its `1/N` share of the patch
//! side), as high as the bake's top; static geometry for any camera.
//!
//! Each slice has two BTF layers, one per side it is seen from: the orthographic camera on the
//! `+` side of the axis (the *front*, Fig. 7's left column) or on the `−` side. Layer of slice
//! `i` across axis `a` (0 = x, 1 = z) seen from the `+` side: `2 (a N + i)`; from the `−` side
//! the next one (`shaders/grass.wgsl`, `vs_vslice`, computes the same). This module lays out
//! the layers' cameras and lists, per layer, the blades of the patch and its eight neighbours
//! that reach the layer's slab, for [`crate::btf::bake`].

use std::ops::Range;

use glam::Vec2;

use crate::patch::PatchBlade;
use crate::shader::CellRecord;

/// The vertical slices of one patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliceLayout {
    /// Slices across each axis (`N`).
    pub per_axis: u32,
    /// Patch side, m.
    pub patch_size: f32,
}

/// Axis a vertical slice is across.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// The slice is the plane `x = c`.
    X,
    /// The slice is the plane `z = c`.
    Z,
}

impl SliceLayout {
    /// BTF layers: two per slice, `2N` slices.
    pub fn layers(&self) -> u32 {
        4 * self.per_axis
    }

    /// Coordinate of slice `i` along its axis, from the patch centre, m.
    pub fn coordinate(&self, i: u32) -> f32 {
        self.patch_size * ((i as f32 + 0.5) / self.per_axis as f32 - 0.5)
    }

    /// Half the thickness of a slice's slab, m.
    pub fn half_thickness(&self) -> f32 {
        0.5 * self.patch_size / self.per_axis as f32
    }

    /// Layer of slice `i` across `axis` seen from the `+` side (`front`) or the `−` side.
    pub fn layer(&self, axis: Axis, i: u32, front: bool) -> u32 {
        let a = match axis {
            Axis::X => 0,
            Axis::Z => 1,
        };
        2 * (a * self.per_axis + i) + u32::from(!front)
    }

    /// Every layer as (axis, slice, front), in layer order.
    pub fn each_layer(&self) -> impl Iterator<Item = (Axis, u32, bool)> + '_ {
        [Axis::X, Axis::Z].into_iter().flat_map(move |axis| {
            (0..self.per_axis).flat_map(move |i| [(axis, i, true), (axis, i, false)])
        })
    }

    /// The bake's cells: for each layer (in order) the patch and its eight unmirrored
    /// neighbours, each carrying the layer's camera in `mode` (`shaders/grass.wgsl`,
    /// `bake_position`).
    pub fn bake_cells(&self) -> Vec<CellRecord> {
        self.each_layer()
            .flat_map(|(axis, i, front)| {
                let mode = [
                    1.0,
                    match axis {
                        Axis::X => 1.0,
                        Axis::Z => 2.0,
                    },
                    self.coordinate(i),
                    if front { 1.0 } else { -1.0 },
                ];
                neighbours(self.patch_size).map(move |c| CellRecord {
                    center_signs: [c.x, c.y, 1.0, 1.0],
                    mode,
                })
            })
            .collect()
    }

    /// Per layer, the blades of its nine cells ([`Self::bake_cells`]) whose horizontal extent
    /// ([`blade_extent`]) meets the slice's slab, as `cell x blade count + blade` (the blade
    /// pipeline's instance numbering), and each layer's range of the list.
    pub fn bake_refs(&self, blades: &[PatchBlade], gravity: f32) -> (Vec<u32>, Vec<Range<u32>>) {
        let count = blades.len() as u32;
        let extents: Vec<(Vec2, Vec2)> = blades.iter().map(|b| blade_extent(b, gravity)).collect();
        let half = self.half_thickness();
        let side = 0.5 * self.patch_size;
        let mut refs = Vec::new();
        let mut ranges = Vec::new();
        for (layer, (axis, i, front)) in self.each_layer().enumerate() {
            let start = refs.len() as u32;
            let c = self.coordinate(i);
            // (depth key, ref): nearest to the layer's camera first, so the depth test rejects
            // the blades behind before they are shaded.
            let mut keyed: Vec<(f32, u32)> = Vec::new();
            for (k, offset) in neighbours(self.patch_size).enumerate() {
                let cell = (layer * 9 + k) as u32;
                for (b, (lo, hi)) in extents.iter().enumerate() {
                    let (lo, hi) = (*lo + offset, *hi + offset);
                    // (across, along): the slab's axis, then the slice's own width.
                    let (across, along) = match axis {
                        Axis::X => ((lo.x, hi.x), (lo.y, hi.y)),
                        Axis::Z => ((lo.y, hi.y), (lo.x, hi.x)),
                    };
                    if across.1 >= c - half
                        && across.0 <= c + half
                        && along.1 >= -side
                        && along.0 <= side
                    {
                        let mid = 0.5 * (across.0 + across.1);
                        keyed.push((if front { -mid } else { mid }, cell * count + b as u32));
                    }
                }
            }
            keyed.sort_by(|a, b| a.0.total_cmp(&b.0));
            refs.extend(keyed.into_iter().map(|(_, r)| r));
            ranges.push(start..refs.len() as u32);
        }
        (refs, ranges)
    }
}

/// Centres of the patch and its eight neighbours, rows of z then x (the order of the bake's
/// cells).
pub fn neighbours(patch_size: f32) -> impl Iterator<Item = Vec2> {
    (-1..=1)
        .flat_map(move |dz| (-1..=1).map(move |dx| Vec2::new(dx as f32, dz as f32) * patch_size))
}

/// One bake layer seeing an axis-aligned box around the patch centre (`half`: half sizes in x
/// and z): the nine cells carrying the layer's camera `mode`, and the blades of those cells
/// whose horizontal extent ([`blade_extent`]) meets the box, as `cell x blade count + blade`
/// (the blade pipeline's instance numbering) with their range (the whole list). The shadow
/// mask's slab and the horizontal slice's top view are such layers.
pub fn box_layer(
    patch_size: f32,
    blades: &[PatchBlade],
    gravity: f32,
    mode: [f32; 4],
    half: Vec2,
) -> (Vec<CellRecord>, Vec<u32>, Range<u32>) {
    let cells: Vec<CellRecord> = neighbours(patch_size)
        .map(|c| CellRecord {
            center_signs: [c.x, c.y, 1.0, 1.0],
            mode,
        })
        .collect();
    let count = blades.len() as u32;
    let extents: Vec<(Vec2, Vec2)> = blades.iter().map(|b| blade_extent(b, gravity)).collect();
    let mut refs = Vec::new();
    for (k, offset) in neighbours(patch_size).enumerate() {
        for (b, (lo, hi)) in extents.iter().enumerate() {
            let (lo, hi) = (*lo + offset, *hi + offset);
            if hi.x >= -half.x && lo.x <= half.x && hi.y >= -half.y && lo.y <= half.y {
                refs.push(k as u32 * count + b as u32);
            }
        }
    }
    let range = 0..refs.len() as u32;
    (cells, refs, range)
}

/// Horizontal bounding box (min, max of x and z, from the patch centre) of a blade standing
/// without wind, as `shaders/grass.wgsl` builds it: its particle moves horizontally only with
/// its launch velocity, from the root to `root + dir · sin(tilt) · scale`, and the strip is
/// half its width to either side; a millimetre of margin covers rounding.
pub fn blade_extent(b: &PatchBlade, gravity: f32) -> (Vec2, Vec2) {
    let dir = Vec2::new(b.azimuth.cos(), b.azimuth.sin());
    let vy = b.tilt.cos();
    let peak = if gravity > vy {
        vy * vy / (2.0 * gravity)
    } else {
        vy - 0.5 * gravity
    };
    let scale = b.height / peak.max(1e-3);
    let root = Vec2::from(b.root);
    let tip = root + dir * b.tilt.sin() * scale;
    let margin = Vec2::splat(0.5 * b.width + 1e-3);
    (root.min(tip) - margin, root.max(tip) + margin)
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAYOUT: SliceLayout = SliceLayout {
        per_axis: 10,
        patch_size: 0.5,
    };

    #[test]
    fn layers_and_slabs_tile_the_patch() {
        assert_eq!(LAYOUT.layers(), 40);
        let order: Vec<u32> = LAYOUT
            .each_layer()
            .map(|(a, i, f)| LAYOUT.layer(a, i, f))
            .collect();
        assert_eq!(order, (0..40).collect::<Vec<_>>());
        // The slabs cover [-size/2, size/2] edge to edge.
        let h = LAYOUT.half_thickness();
        assert!((LAYOUT.coordinate(0) - h + 0.25).abs() < 1e-6);
        assert!((LAYOUT.coordinate(9) + h - 0.25).abs() < 1e-6);
        for i in 1..10 {
            let gap = LAYOUT.coordinate(i) - LAYOUT.coordinate(i - 1);
            assert!((gap - 2.0 * h).abs() < 1e-6);
        }
        assert_eq!(LAYOUT.bake_cells().len(), 40 * 9);
    }

    /// Every blade lands in the list of the slab its root is in (for both axes and sides),
    /// and a thin slab lists far fewer blades than the nine patches hold.
    #[test]
    fn refs_hold_every_blade_whose_root_is_in_the_slab() {
        let blades: Vec<PatchBlade> = (0..400)
            .map(|k| {
                let r = grassbench::rng::hash(7, &[k]);
                PatchBlade {
                    root: [
                        ((r & 0xffff) as f32 / 65535.0 - 0.5) * 0.5,
                        (((r >> 16) & 0xffff) as f32 / 65535.0 - 0.5) * 0.5,
                    ],
                    azimuth: ((r >> 32) & 0xff) as f32 * 0.0245,
                    tilt: 0.3,
                    height: 0.3,
                    width: 0.006,
                    variation: 0.0,
                    threshold: 0.5,
                }
            })
            .collect();
        let (refs, ranges) = LAYOUT.bake_refs(&blades, 0.6);
        assert_eq!(ranges.len(), 40);
        let h = LAYOUT.half_thickness();
        for (layer, (axis, i, _)) in LAYOUT.each_layer().enumerate() {
            let list = &refs[ranges[layer].start as usize..ranges[layer].end as usize];
            let c = LAYOUT.coordinate(i);
            for (b, blade) in blades.iter().enumerate() {
                let across = match axis {
                    Axis::X => blade.root[0],
                    Axis::Z => blade.root[1],
                };
                if (across - c).abs() < h {
                    // The centre cell of this layer is cell 4 of its nine.
                    let id = (layer as u32 * 9 + 4) * 400 + b as u32;
                    assert!(list.contains(&id), "layer {layer}: blade {b} missing");
                }
            }
            assert!(
                list.len() < 9 * 400 / 3,
                "layer {layer}: {} blades",
                list.len()
            );
        }
    }
}
