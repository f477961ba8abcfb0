//! The animated 2.5D strips and the 3D ↔ 2.5D morph (Sec. 3.2, 4.2, 4.3) on the CPU: the twins
//! of `edge_point`, `strip_surface` and `morphed` in `shaders/perbet.wgsl`, which draw them
//! (tests/tests/twins.rs runs the shader's functions against these).
//!
//! A strip's vertical edges carry receivers (Sec. 3.2): edge `j` of strip `k` is a chain of
//! `segments` segments of `strip_height / segments` standing on the ground at the strip's
//! `j`-th column, each segment tilted by its posture angle towards the receiver's direction,
//! and the whole edge sunk `(1 − grow) · strip_height` into the ground during a 2.5D ↔ 2D
//! transition (Sec. 4.3). Between two edges the surface is their linear blend, so the painted
//! texture moves with them. A blade point painted at texture coordinates `(u, v)` (Fig. 14,
//! [`crate::patch::Layout::painted_uv`]) lies on that surface; during a 3D ↔ 2.5D transition
//! each point of a 3D blade is drawn the fraction `morph` of the way from its own animated
//! position to that place ("a mere linear interpolation", Sec. 4.2).

use glam::{Vec2, Vec3};
use grassbench::terrain::Terrain;

use crate::patch::Layout;
use crate::receiver::{self, Received};

/// One patch's strips of one orientation as a frame animates them (a strips entry).
#[derive(Clone, Copy, Debug)]
pub struct AnimatedStrips<'a> {
    /// The strips' shape.
    pub layout: &'a Layout,
    /// World (x, z) of the patch's corner.
    pub origin: Vec2,
    /// Strip orientation (0: planes of constant z, 1: planes of constant x).
    pub orientation: u32,
    /// 1 standing, 0 sunk into the ground (Sec. 4.3).
    pub grow: f32,
    /// The entry's edge receivers, strip after strip, `columns + 1` edges a strip; a missing
    /// one stands at rest.
    pub receivers: &'a [Received],
    /// The posture table of the kind of grass strip edges bend as
    /// ([`receiver::posture_table`]): `postures` rows of `layout.segments` angles.
    pub table: &'a [f32],
    /// Rows of `table`.
    pub postures: usize,
}

impl AnimatedStrips<'_> {
    /// The point at height `level` (in segments, fractional) of edge `j` of strip `k`, on
    /// `terrain`'s ground.
    pub fn edge_point(&self, terrain: &Terrain, k: u32, j: u32, level: f32) -> Vec3 {
        let l = self.layout;
        let n = l.segments as usize;
        let xz = self.origin + l.strip_xz(self.orientation, k, j as f32 / l.columns as f32);
        let r = self
            .receivers
            .get((k * (l.columns + 1) + j) as usize)
            .copied()
            .unwrap_or_default();
        let direction = Vec3::new(r[0], 0.0, r[1]);
        let segment = l.strip_height / n as f32;
        let mut angles = vec![0.0; n];
        receiver::angles_at(self.table, self.postures, n, r[2], &mut angles);
        let mut p = Vec3::new(
            xz.x,
            terrain.height_at(xz) - (1.0 - self.grow) * l.strip_height,
            xz.y,
        );
        for (i, a) in angles.iter().enumerate() {
            let t = (level - i as f32).clamp(0.0, 1.0);
            p += segment * t * (a.sin() * direction + a.cos() * Vec3::Y);
        }
        p
    }

    /// The animated surface of strip `k` at texture coordinates `uv` (u along the strip, v
    /// up, both clamped to `[0, 1]`): the blend of the two edges around `u`.
    pub fn surface(&self, terrain: &Terrain, k: u32, uv: Vec2) -> Vec3 {
        let l = self.layout;
        let x = uv.x.clamp(0.0, 1.0) * l.columns as f32;
        let j = (x.floor() as u32).min(l.columns - 1);
        let level = uv.y.clamp(0.0, 1.0) * l.segments as f32;
        let a = self.edge_point(terrain, k, j, level);
        let b = self.edge_point(terrain, k, j + 1, level);
        a.lerp(b, x - j as f32)
    }
}

/// A 3D blade point at `own` (its own animated shape) drawn `morph` of the way to `target`,
/// where its painted copy is on the animated strip (Sec. 4.2); `morph ≤ 0` leaves it alone.
pub fn morphed(own: Vec3, target: Vec3, morph: f32) -> Vec3 {
    if morph <= 0.0 {
        return own;
    }
    own.lerp(target, morph)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::patch::tests::layout;
    use grassbench::grass::GrassConfig;
    use grassbench::wind::{BladeConfig, Postures};

    fn table(layout: &Layout) -> (Vec<f32>, usize) {
        let postures = Postures::new(&BladeConfig::default()).unwrap();
        (
            receiver::posture_table(&postures, layout.segments),
            postures.count(),
        )
    }

    /// At rest (index 0 everywhere, standing) every painted point of every blade is, on the
    /// strip surface, the blade's point projected along the strip's normal onto the strip's
    /// plane (Sec. 4.2: the texture is the orthographic image of the blades between two
    /// planes), at its own height and along-strip position: the morph target of a resting
    /// blade is its own shape flattened onto its strip. Interior points: the blades' middle
    /// points, none at a root or tip.
    #[test]
    fn at_rest_painted_points_are_the_blades_projected_on_their_strip() {
        let l = layout();
        let (table, postures) = table(&l);
        let terrain = Terrain::flat(Vec2::splat(40.0));
        let patches = crate::patch::build(&GrassConfig::default(), &l, (1, 200, 1), 0.12, 5);
        let receivers = vec![[0.3, 0.95, 0.0, 0.0]; (l.strips * (l.columns + 1)) as usize];
        let origin = Vec2::new(-3.0, 4.5);
        for orientation in 0..2 {
            let strips = AnimatedStrips {
                layout: &l,
                origin,
                orientation,
                grow: 1.0,
                receivers: &receivers,
                table: &table,
                postures,
            };
            for b in &patches[0].blades {
                let points = b.rest_points(l.segments);
                for p in &points[1..points.len() - 1] {
                    let k = b.strips[orientation as usize];
                    let at = strips.surface(&terrain, k, l.painted_uv(orientation, *p));
                    let plane = l.strip_xz(orientation, k, 0.0);
                    let expected = if orientation == 0 {
                        Vec3::new(origin.x + p.x, p.y, origin.y + plane.y)
                    } else {
                        Vec3::new(origin.x + plane.x, p.y, origin.y + p.z)
                    };
                    // Measured 4.8e-7 m (an ulp of a 5 m coordinate); limit 4x above.
                    assert!(at.distance(expected) < 2e-6, "{p}: {at} vs {expected}");
                }
            }
        }
    }

    /// Bent by its receiver, an edge stays a chain of segments of `strip_height / segments`
    /// (Sec. 3.2: receivers turn a posture into a shape, they do not stretch it), leans towards
    /// the receiver's direction further with a larger index, and a fractional level lies on
    /// its segment; sunk (`grow = 0`), its top is at the ground.
    #[test]
    fn bent_edges_keep_their_length_and_lean_with_the_index() {
        let l = layout();
        let (table, postures) = table(&l);
        let terrain = Terrain::flat(Vec2::splat(40.0));
        let direction = Vec2::new(0.6, -0.8);
        let mut leans = Vec::new();
        for index in [0.0, 0.3, 0.7, 1.0] {
            let receivers =
                vec![[direction.x, direction.y, index, 0.0]; (l.strips * (l.columns + 1)) as usize];
            let strips = AnimatedStrips {
                layout: &l,
                origin: Vec2::ZERO,
                orientation: 1,
                grow: 1.0,
                receivers: &receivers,
                table: &table,
                postures,
            };
            let segment = l.strip_height / l.segments as f32;
            let points: Vec<Vec3> = (0..=l.segments)
                .map(|i| strips.edge_point(&terrain, 3, 2, i as f32))
                .collect();
            // Measured: segments within 1.5e-8 m of their 0.175 m (an ulp), half-way points
            // 1.7e-7 m off their segment's middle, the sunk top 3e-8 m off; limits 6-7x above.
            for (i, w) in points.windows(2).enumerate() {
                assert!(
                    (w[0].distance(w[1]) - segment).abs() < 1e-7,
                    "index {index}: segment {i}"
                );
                let half = strips.edge_point(&terrain, 3, 2, i as f32 + 0.5);
                assert!(half.distance(w[0].lerp(w[1], 0.5)) < 1e-6);
            }
            let tip = points[l.segments as usize] - points[0];
            leans.push(Vec2::new(tip.x, tip.z).dot(direction));
            let sunk = AnimatedStrips {
                grow: 0.0,
                ..strips
            };
            let top = sunk.edge_point(&terrain, 3, 2, l.segments as f32);
            assert!((top.y - (points[l.segments as usize].y - l.strip_height)).abs() < 2e-7);
        }
        // Measured leans 0, 0.146, 0.341, 0.487 m at indices 0, 0.3, 0.7, 1.
        assert!(leans[0].abs() < 1e-6, "rest leans {}", leans[0]);
        assert!(leans.windows(2).all(|w| w[1] > w[0] + 1e-3), "{leans:?}");
    }

    /// Sec. 4.2's "mere linear interpolation": a blade point drawn `m` of the way from its own
    /// position to its target.
    #[test]
    fn morphing_is_linear_between_the_blade_and_its_target() {
        let own = Vec3::new(1.0, 0.2, -2.0);
        let target = Vec3::new(1.4, 0.5, -1.5);
        assert_eq!(morphed(own, target, 0.0), own);
        // Measured 1.2e-7 and 6e-8 m (an ulp of these coordinates); limits 8x above.
        for m in [0.1f32, 0.35, 0.8] {
            let p = morphed(own, target, m);
            assert!((p - (own + (target - own) * m)).length() < 1e-6);
            // On the segment from own to target, m of its length along.
            assert!((p.distance(own) - m * own.distance(target)).abs() < 1e-6);
        }
        assert!(morphed(own, target, 1.0).distance(target) < 1e-6);
    }
}
