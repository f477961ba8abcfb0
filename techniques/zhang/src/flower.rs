//! A near flower (Sec. 3.3-3.4): a petal quad on an invisible stalk. Only the petal point is
//! animated, like the top backbone point of a blade, with a heavier mass so it moves slower
//! and less in the same wind.

use grassbench::glam::Vec3;

use crate::blade::{Dynamics, slack};

/// The petal point of one flower.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlowerState {
    /// The stalk's root on the ground (immovable).
    pub root: Vec3,
    /// Current petal centre.
    pub pos: Vec3,
    /// Petal centre one step ago.
    pub old: Vec3,
    /// Petal centre at rest.
    pub rest: Vec3,
    /// Stalk length (kept by the length constraint of Sec. 3.2.4).
    pub length: f32,
    /// `1 / mass` (Sec. 3.4: velocity is scaled in proportion to the inverse mass).
    pub inv_mass: f32,
}

impl FlowerState {
    /// A flower at `root` whose petal rests `length` above it.
    pub fn new(root: Vec3, length: f32, mass: f32) -> Self {
        let rest = root + Vec3::Y * length;
        Self {
            root,
            pos: rest,
            old: rest,
            rest,
            length,
            inv_mass: 1.0 / mass,
        }
    }

    /// One Verlet step (Eq. 7) in wind `wind`, then the stalk-length constraint and the ground.
    /// The wind push is scaled by the inverse mass (Sec. 3.4); the pull back to rest is not,
    /// so a heavier flower both bends less and accelerates slower.
    #[inline]
    pub fn step(&mut self, wind: Vec3, k: &Dynamics) {
        let x = self.pos;
        let a = wind * (k.wind_response * self.length * self.inv_mass) + (self.rest - x) * k.spring;
        let mut next = x + (x - self.old) * k.keep + a * (k.dt * k.dt);
        if next.y < self.root.y {
            next.y = 2.0 * self.root.y - next.y;
        }
        let d = next - self.root;
        let len = d.length();
        if len > 1e-9 && (len - self.length).abs() > slack(self.length, self.root, next) {
            next = self.root + d * (self.length / len);
        }
        self.old = x;
        self.pos = next;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::blade::BladeState;

    #[test]
    fn flowers_move_slower_and_less_than_blades() {
        let k = Dynamics::new(1.0 / 30.0, 5.0, 40.0, 4.0);
        let h = 0.5;
        let mut blade = BladeState::new(Vec3::ZERO, h, 0.0, 0.0, 0.0, 1.0);
        let mut flower = FlowerState::new(Vec3::ZERO, h, 4.0);
        let w = Vec3::X * 4.0;
        let (mut b_first, mut f_first) = (0.0, 0.0);
        for step in 0..90 {
            blade.step(&[w; 3], &k, 0.0);
            flower.step(w, &k);
            if step == 2 {
                b_first = blade.pos[3].x;
                f_first = flower.pos.x;
            }
            assert!((flower.pos - flower.root).length() - h < 1e-5);
        }
        assert!(
            f_first < 0.5 * b_first,
            "flower not slower: {f_first} vs {b_first}"
        );
        assert!(
            flower.pos.x < 0.5 * blade.pos[3].x,
            "flower not bending less"
        );
        assert!(flower.pos.x > 0.0);
        // Calm: stays at rest.
        let mut still = FlowerState::new(Vec3::ONE, 0.3, 4.0);
        for _ in 0..100 {
            still.step(Vec3::ZERO, &k);
        }
        assert_eq!(still.pos, still.rest);
    }
}
