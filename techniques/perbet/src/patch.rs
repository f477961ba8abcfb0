//! The pre-computed patches of grass (Sec. 2.2): built procedurally from the finest
//! representation down. This module makes the 3D blades and records, for each of the two strip
//! orientations, which strip paints each blade and where (the morph targets of Sec. 4.2, Fig.
//! 14); [`crate::paint`] then renders the strip and terrain textures from these blades.
//!
//! Coordinates are patch-local: x and z in `[0, patch_size)`, y up from the ground. Strips of
//! orientation 0 are vertical planes of constant z running along x (normal +z); orientation 1
//! planes of constant x running along z (normal +x). Strip `k` of `S` holds the blades whose
//! root lies in the slab `[k, k + 1) · size / S` along the normal ("the 3D grass that lie
//! between two given planes", Sec. 4.2), so every blade is painted exactly once per
//! orientation and the 3D and 2.5D representations show the same blades.

use glam::{Vec2, Vec3};
use grassbench::grass::GrassConfig;
use grassbench::rng::Rng;

/// One 3D blade of a patch: a chain of line segments (Fig. 2) with seeded segment
/// orientations.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchBlade {
    /// Root in the patch (x, z), m.
    pub root: Vec2,
    /// Height (length of the chain), m.
    pub height: f32,
    /// Width at the root, m.
    pub width: f32,
    /// Direction of the blade's width, radians around y.
    pub facing: f32,
    /// Colour variation in `[-1, 1]`.
    pub variation: f32,
    /// Density threshold in `[0, 1)` (drawn where the density map exceeds it).
    pub threshold: f32,
    /// Its kind of grass (which postures it bends with), `0..kinds`, shortest first.
    pub kind: u32,
    /// Rest tilt of each segment from the vertical, as a horizontal vector (direction of the
    /// tilt, length the angle in radians), root segment first.
    pub tilts: Vec<Vec2>,
    /// The strip that paints this blade, per orientation.
    pub strips: [u32; 2],
}

/// One pre-computed patch: its blades.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    /// The 3D blades.
    pub blades: Vec<PatchBlade>,
}

/// The shape of every patch and strip (shared by all variants).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// Side of a patch, m.
    pub size: f32,
    /// Segments per blade.
    pub segments: u32,
    /// Strips per orientation.
    pub strips: u32,
    /// Polygons along a strip.
    pub columns: u32,
    /// Reach of a strip past the patch on each side, as a fraction of the patch.
    pub margin: f32,
    /// Height of a strip, m: the tallest blade.
    pub strip_height: f32,
}

impl Layout {
    /// Length of a strip, m.
    pub fn strip_length(&self) -> f32 {
        self.size * (1.0 + 2.0 * self.margin)
    }

    /// Patch-local (along, across) of texture coordinate `u` on strip `k`: `along` runs with
    /// the strip, `across` is the strip plane's position along its normal.
    pub fn strip_point(&self, k: u32, u: f32) -> (f32, f32) {
        let along = (u * (1.0 + 2.0 * self.margin) - self.margin) * self.size;
        let across = (k as f32 + 0.5) * self.size / self.strips as f32;
        (along, across)
    }

    /// Patch-local ground point (x, z) of texture coordinate `u` on strip `k` of
    /// `orientation`.
    pub fn strip_xz(&self, orientation: u32, k: u32, u: f32) -> Vec2 {
        let (along, across) = self.strip_point(k, u);
        if orientation == 0 {
            Vec2::new(along, across)
        } else {
            Vec2::new(across, along)
        }
    }

    /// Texture coordinates (u along the strip, v up) of a patch-local point painted on a strip
    /// of `orientation` (orthographic along the strip's normal).
    pub fn painted_uv(&self, orientation: u32, p: Vec3) -> Vec2 {
        let along = if orientation == 0 { p.x } else { p.z };
        Vec2::new(
            (along / self.size + self.margin) / (1.0 + 2.0 * self.margin),
            p.y / self.strip_height,
        )
    }

    /// The strip of `orientation` whose slab holds a root at `root`.
    pub fn strip_of(&self, orientation: u32, root: Vec2) -> u32 {
        let across = if orientation == 0 { root.y } else { root.x };
        ((across / self.size * self.strips as f32).floor() as i64).clamp(0, self.strips as i64 - 1)
            as u32
    }
}

/// Direction of a segment tilted by `tilt` (direction of the tilt, length the angle from the
/// vertical): unit length whatever the tilt, so chains never stretch.
pub fn segment_direction(tilt: Vec2) -> Vec3 {
    let angle = tilt.length();
    if angle < 1e-6 {
        return Vec3::Y;
    }
    let h = tilt / angle * angle.sin();
    Vec3::new(h.x, angle.cos(), h.y)
}

/// The `tilts.len() + 1` points of a chain of segments of length `segment` from `root`, each
/// segment tilted by its rest tilt plus `bend[i]` radians towards `direction` (a unit
/// horizontal vector): Sec. 3.2's receiver turning a posture into a shape.
pub fn chain_points(
    root: Vec3,
    segment: f32,
    tilts: &[Vec2],
    bend: &[f32],
    direction: Vec2,
) -> Vec<Vec3> {
    let mut points = Vec::with_capacity(tilts.len() + 1);
    let mut p = root;
    points.push(p);
    for (i, t) in tilts.iter().enumerate() {
        let a = bend.get(i).copied().unwrap_or(0.0);
        p += segment * segment_direction(*t + direction * a);
        points.push(p);
    }
    points
}

impl PatchBlade {
    /// The blade's points at rest, patch-local.
    pub fn rest_points(&self, segments: u32) -> Vec<Vec3> {
        chain_points(
            Vec3::new(self.root.x, 0.0, self.root.y),
            self.height / segments as f32,
            &self.tilts,
            &[],
            Vec2::X,
        )
    }
}

/// The kind of a blade of `height` among `kinds` equal classes of the scene's height range.
pub fn kind_of(height: f32, range: [f32; 2], kinds: u32) -> u32 {
    let span = (range[1] - range[0]).max(1e-6);
    let k = ((height - range[0]) / span * kinds as f32).floor();
    (k.max(0.0) as u32).min(kinds.saturating_sub(1))
}

/// The mean height of kind `k` of `kinds` over the height range.
pub fn kind_height(k: u32, range: [f32; 2], kinds: u32) -> f32 {
    range[0] + (k as f32 + 0.5) / kinds.max(1) as f32 * (range[1] - range[0])
}

/// Builds `variants` patches of `blades` blades each with `layout.segments` segments, from the
/// scene's grass ranges, in `kinds` kinds by height; `jitter` is the largest random turn of a
/// segment from its predecessor (radians). Deterministic in `seed`.
pub fn build(
    grass: &GrassConfig,
    layout: &Layout,
    (variants, blades, kinds): (u32, u32, u32),
    jitter: f32,
    seed: u64,
) -> Vec<Patch> {
    (0..variants)
        .map(|v| {
            let mut rng = Rng::new(grassbench::rng::hash(seed ^ 0x5045_5242, &[i64::from(v)]));
            let blades = (0..blades)
                .map(|_| blade(grass, layout, jitter, kinds, &mut rng))
                .collect();
            Patch { blades }
        })
        .collect()
}

fn blade(
    grass: &GrassConfig,
    layout: &Layout,
    jitter: f32,
    kinds: u32,
    rng: &mut Rng,
) -> PatchBlade {
    let root = Vec2::new(rng.range(0.0, layout.size), rng.range(0.0, layout.size));
    let height = rng.range(grass.height[0], grass.height[1]);
    let width = rng.range(grass.width[0], grass.width[1]);
    let facing = rng.range(0.0, std::f32::consts::TAU);
    let variation = rng.range(-1.0, 1.0);
    let threshold = rng.next_f32();
    // A rest lean that grows along the blade (a curved blade), plus a random turn of every
    // segment from its predecessor (Sec. 2.2).
    let lean_angle = rng.range(0.0, std::f32::consts::TAU);
    let lean = Vec2::from_angle(lean_angle) * rng.range(0.0, grass.lean);
    let n = layout.segments as usize;
    let mut turn = Vec2::ZERO;
    let tilts = (0..n)
        .map(|i| {
            turn +=
                Vec2::from_angle(rng.range(0.0, std::f32::consts::TAU)) * rng.range(0.0, jitter);
            lean * ((i as f32 + 0.5) / n as f32) + turn
        })
        .collect();
    let strips = [0, 1].map(|o| layout.strip_of(o, root));
    PatchBlade {
        root,
        height,
        width,
        facing,
        variation,
        threshold,
        kind: kind_of(height, grass.height, kinds),
        tilts,
        strips,
    }
}

/// Height of the strips for `patches`: their tallest blade at rest, or `fallback` when there
/// are no blades.
pub fn tallest(patches: &[Patch], segments: u32, fallback: f32) -> f32 {
    patches
        .iter()
        .flat_map(|p| &p.blades)
        .flat_map(|b| b.rest_points(segments))
        .map(|p| p.y)
        .fold(None, |m: Option<f32>, y| Some(m.map_or(y, |m| m.max(y))))
        .unwrap_or(fallback)
        .max(1e-3)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A small medium-preset layout the crate's tests share.
    pub(crate) fn layout() -> Layout {
        Layout {
            size: 2.5,
            segments: 4,
            strips: 8,
            columns: 4,
            margin: 0.12,
            strip_height: 0.7,
        }
    }

    #[test]
    fn chains_keep_their_segment_length_however_they_bend() {
        let tilts = [
            Vec2::new(0.1, 0.05),
            Vec2::new(0.3, -0.2),
            Vec2::new(0.0, 0.9),
        ];
        for bend in [[0.0; 3], [0.5, 1.0, 1.4], [-0.4, -0.8, -1.2]] {
            let p = chain_points(Vec3::ZERO, 0.2, &tilts, &bend, Vec2::new(0.6, 0.8));
            for w in p.windows(2) {
                assert!((w[0].distance(w[1]) - 0.2).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn every_blade_is_in_the_slab_of_its_strip() {
        let l = layout();
        let patches = build(&GrassConfig::default(), &l, (2, 300, 1), 0.12, 9);
        assert_eq!(patches.len(), 2);
        for b in patches.iter().flat_map(|p| &p.blades) {
            for o in 0..2 {
                let k = b.strips[o as usize];
                let across = if o == 0 { b.root.y } else { b.root.x };
                let slab = l.size / l.strips as f32;
                assert!(across >= k as f32 * slab - 1e-5 && across <= (k + 1) as f32 * slab + 1e-5);
            }
        }
    }

    #[test]
    fn kinds_split_the_height_range_evenly() {
        let range = [0.3, 0.7];
        assert_eq!(kind_of(0.3, range, 2), 0);
        assert_eq!(kind_of(0.49, range, 2), 0);
        assert_eq!(kind_of(0.51, range, 2), 1);
        assert_eq!(kind_of(0.7, range, 2), 1);
        assert_eq!(kind_of(0.9, range, 3), 2);
        assert!((kind_height(1, range, 2) - 0.6).abs() < 1e-6);
        let blades = build(&GrassConfig::default(), &layout(), (1, 400, 2), 0.1, 1);
        let tall = blades[0].blades.iter().filter(|b| b.kind == 1).count();
        assert!(
            (150..250).contains(&tall),
            "{tall} of 400 in the taller kind"
        );
    }

    #[test]
    fn painted_coordinates_invert_strip_points() {
        let l = layout();
        for o in 0..2 {
            for u in [0.0, 0.3, 1.0] {
                let xz = l.strip_xz(o, 3, u);
                let uv = l.painted_uv(o, Vec3::new(xz.x, 0.35, xz.y));
                assert!((uv.x - u).abs() < 1e-5 && (uv.y - 0.5).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn patches_are_deterministic_and_seeded() {
        let l = layout();
        let g = GrassConfig::default();
        assert_eq!(
            build(&g, &l, (1, 50, 2), 0.1, 3),
            build(&g, &l, (1, 50, 2), 0.1, 3)
        );
        assert_ne!(
            build(&g, &l, (1, 50, 2), 0.1, 3),
            build(&g, &l, (1, 50, 2), 0.1, 4)
        );
    }
}
