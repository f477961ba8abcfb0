//! Receivers (Sec. 3.2): every animated object — each 3D blade, each vertical edge of a 2.5D
//! strip — asks the wind each frame for a bending direction and a posture index, and is drawn
//! in the pre-computed posture that index names.
//!
//! Under a `primitives` wind the receiver reads [`PrimitiveSet::sample`] directly (direction
//! and signed index, backswing included). Any other wind model drives Perbet too, through the
//! shared velocity interface: the index is the horizontal wind speed over the speed an index of
//! 1 stands for (the inverse of `PrimitiveSet`'s own velocity), in the wind's direction.

use glam::{Vec2, Vec3};
use grassbench::wind::{Postures, PrimitiveSet, WindField, WindSample};

/// What a receiver stores: `[direction.x, direction.z, index, 0]` (the GPU layout).
pub type Received = [f32; 4];

/// Reads the wind for receivers.
pub struct Receivers<'a> {
    wind: &'a dyn WindField,
    primitives: Option<&'a PrimitiveSet>,
    speed: f32,
    time: f32,
}

impl<'a> Receivers<'a> {
    /// Receivers of `wind` at `time`; `speed` (m/s) is what index 1 stands for when the wind is
    /// not made of primitives.
    pub fn new(wind: &'a dyn WindField, speed: f32, time: f32) -> Self {
        Self {
            wind,
            primitives: (wind as &dyn std::any::Any).downcast_ref::<PrimitiveSet>(),
            speed: speed.max(1e-3),
            time,
        }
    }

    /// Direction and index for an object standing at `ground` with height `height`.
    pub fn sample(&self, ground: Vec3, height: f32) -> WindSample {
        if let Some(set) = self.primitives {
            return set.sample(Vec2::new(ground.x, ground.z), self.time);
        }
        let v = self
            .wind
            .velocity(ground + Vec3::Y * (0.5 * height), self.time);
        from_velocity(Vec2::new(v.x, v.z), self.speed)
    }

    /// [`Receivers::sample`] in the GPU layout.
    pub fn receive(&self, ground: Vec3, height: f32) -> Received {
        let s = self.sample(ground, height);
        [s.direction.x, s.direction.y, s.posture, 0.0]
    }
}

/// A horizontal wind velocity as a receiver sample: its direction, index `|v| / speed`
/// (clamped to 1).
pub fn from_velocity(v: Vec2, speed: f32) -> WindSample {
    let length = v.length();
    if !length.is_finite() || length < 1e-6 {
        return WindSample::REST;
    }
    WindSample {
        direction: v / length,
        posture: (length / speed).min(1.0),
    }
}

/// The posture table of `postures` resampled to chains of `segments` segments: `K` rows of
/// `segments` bend angles (radians towards the bending direction), row `k` for index
/// `postures.index_of(k)`. Each segment takes the angle of the simulated chain at its middle,
/// so blades with any segment count follow the same simulated shapes.
pub fn posture_table(postures: &Postures, segments: u32) -> Vec<f32> {
    let k = postures.count();
    let simulated = postures.segments();
    let mut table = Vec::with_capacity(k * segments as usize);
    for row in 0..k {
        let angles = postures.angles(row);
        for i in 0..segments {
            let s = (i as f32 + 0.5) / segments as f32 * simulated as f32 - 0.5;
            let j = (s.floor().max(0.0) as usize).min(simulated.saturating_sub(1));
            let next = (j + 1).min(simulated.saturating_sub(1));
            let f = (s - j as f32).clamp(0.0, 1.0);
            let a = angles.get(j).copied().unwrap_or(0.0);
            let b = angles.get(next).copied().unwrap_or(a);
            table.push(a + (b - a) * f);
        }
    }
    table
}

/// The bend angles at `index` from a [`posture_table`] of `k` rows (linear between the two
/// nearest postures), as the shaders compute them.
pub fn angles_at(table: &[f32], k: usize, segments: usize, index: f32, out: &mut [f32]) {
    if k < 2 {
        out.iter_mut().for_each(|o| *o = 0.0);
        return;
    }
    let half = (k - 1) as f32 / 2.0;
    let u = (index.clamp(-1.0, 1.0) + 1.0) * half;
    let row = (u.floor() as usize).min(k - 2);
    let f = u - row as f32;
    for (i, o) in out.iter_mut().enumerate().take(segments) {
        let a = table.get(row * segments + i).copied().unwrap_or(0.0);
        let b = table.get((row + 1) * segments + i).copied().unwrap_or(0.0);
        *o = a + (b - a) * f;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use grassbench::wind::BladeConfig;

    #[test]
    fn velocities_become_directions_and_indices() {
        let s = from_velocity(Vec2::new(3.0, 4.0), 10.0);
        assert!((s.direction - Vec2::new(0.6, 0.8)).length() < 1e-6);
        assert!((s.posture - 0.5).abs() < 1e-6);
        assert_eq!(from_velocity(Vec2::new(30.0, 40.0), 10.0).posture, 1.0);
        assert_eq!(from_velocity(Vec2::ZERO, 10.0), WindSample::REST);
        assert_eq!(
            from_velocity(Vec2::new(f32::NAN, 0.0), 10.0),
            WindSample::REST
        );
    }

    #[test]
    fn resampled_postures_keep_rest_straight_and_bend_with_the_index() {
        let postures = Postures::new(&BladeConfig::default()).unwrap();
        let k = postures.count();
        for segments in [3u32, 4, 8] {
            let table = posture_table(&postures, segments);
            assert_eq!(table.len(), k * segments as usize);
            let mut a = vec![0.0; segments as usize];
            angles_at(&table, k, segments as usize, 0.0, &mut a);
            assert!(a.iter().all(|x| x.abs() < 1e-6), "{a:?}");
            // The tip bends further as the index grows.
            let mut tips = Vec::new();
            for index in [0.0, 0.25, 0.5, 0.75, 1.0] {
                angles_at(&table, k, segments as usize, index, &mut a);
                tips.push(a.iter().map(|x| x.sin()).sum::<f32>());
            }
            assert!(tips.windows(2).all(|w| w[1] > w[0]), "{tips:?}");
        }
    }
}
