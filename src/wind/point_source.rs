//! Bakay, Lalonde and Heidrich 2002, Sec. 3: wind from a point source, in animation steps.

use glam::Vec3;

use super::{PointSourceConfig, WindField};

/// Wind vector `W` = unit vector from a point towards the source; intensity
/// `I = sin(2π (t − step·delay) / period) + bias` where `step = ⌊distance / step_length⌋`
/// is the point's animation step, so steps near the source feel a gust before distant ones
/// (the travelling waves of Bakay's Fig. 8). Velocity = `W · I · speed`.
///
/// Bakay projects `W` onto each vertex's tangent plane (`V_w = W − (W·N)N`); the field returns
/// the unprojected vector and techniques project it with their own surface normal.
#[derive(Clone, Debug)]
pub struct PointSource {
    config: PointSourceConfig,
}

impl PointSource {
    /// A point source.
    pub fn new(config: PointSourceConfig) -> Self {
        Self { config }
    }

    /// The animation step of a point (Bakay Sec. 3, "animation step").
    pub fn step(&self, p: Vec3) -> u32 {
        let d = (Vec3::from(self.config.position) - p).length();
        (d / self.config.step_length) as u32
    }

    /// The wind intensity of a step at `time`: periodic, continuous, in `[-1, 1]` plus bias.
    pub fn intensity(&self, step: u32, time: f32) -> f32 {
        let c = &self.config;
        let phase = (time - step as f32 * c.step_delay) / c.period;
        (std::f32::consts::TAU * phase).sin() + c.bias
    }
}

impl WindField for PointSource {
    fn name(&self) -> &'static str {
        "point_source"
    }

    fn advance(&mut self, _time: f32, _dt: f32) {}

    fn velocity(&self, p: Vec3, time: f32) -> Vec3 {
        let w = (Vec3::from(self.config.position) - p).normalize_or_zero();
        w * self.intensity(self.step(p), time) * self.config.speed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_to_source_and_waves_travel_outwards() {
        let c = PointSourceConfig {
            position: [0.0, 0.0, 0.0],
            bias: 0.0,
            ..Default::default()
        };
        let s = PointSource::new(c.clone());
        let p = Vec3::new(10.0, 0.0, 0.0);
        let v = s.velocity(p, 1.0);
        assert!(v.normalize().dot(-Vec3::X).abs() > 0.999);
        // A step further out sees the same intensity `step_delay` seconds later.
        let near = s.intensity(2, 1.0);
        let far = s.intensity(3, 1.0 + c.step_delay);
        assert!((near - far).abs() < 1e-5);
        assert_eq!(s.step(Vec3::new(4.5, 0.0, 0.0)), 2);
    }
}
