//! Per-vertex wind of Bakay Sec. 3 on the CPU: the mirror of what `ground_wind` in
//! `shaders/bakay.wgsl` computes for every vertex of the ground mesh in `cs_bend`
//! (tests/tests/twins.rs runs `cs_bend` against these functions).
//!
//! Each vertex gets a wind vector `V_w` in its tangent plane and an intensity `I`:
//! - **point source** (the paper's): `W` = unit vector from the vertex to the source,
//!   `V_w = normalize(W − (W·N)N)`; the vertex's animation step is `⌊|source − p| / step⌋`, and
//!   its intensity the periodic function delayed by its step,
//!   `I = sin(2π (t − step·delay) / period) + bias`, so gusts travel outwards as waves (their
//!   Fig. 8). This is exactly [`grassbench::wind::PointSource`]'s math (a test checks it);
//! - **scene**: the scene's wind velocity `v` (any [`grassbench::wind::WindField`], read from the
//!   core's wind texture), projected on the tangent plane; `V_w` is its direction and
//!   `I = |v_t| / reference_speed` (only the tangential part bends grass, Sec. 3).
//!
//! Either way `|I|` is clamped to `max_intensity`.

use glam::Vec3;
use std::f32::consts::TAU;

use grassbench::wind::PointSourceConfig;

/// Wind vector and intensity of one vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexWind {
    /// Unit wind vector in the tangent plane (zero where there is no wind direction).
    pub vector: Vec3,
    /// Intensity `I`: the bend grows with it; negative bends away from `vector`.
    pub intensity: f32,
}

/// Tangential parts shorter than this have no direction: the shader's cut-off in
/// `tangent_direction`, where the rounding of `W − (W·N)N` for `W` along `N` would give a
/// random one.
pub const NO_DIRECTION: f32 = 1e-6;

/// `V_w = normalize(W − (W·N)N)`, or zero when `W` is (nearly) along the normal or zero:
/// the twin of `tangent_direction` in `shaders/bakay.wgsl`.
pub fn tangent_direction(w: Vec3, normal: Vec3) -> Vec3 {
    let t = w - w.dot(normal) * normal;
    let length = t.length();
    if length > NO_DIRECTION {
        t / length
    } else {
        Vec3::ZERO
    }
}

/// Animation step of a point (distance band from the source).
pub fn step(source: &PointSourceConfig, p: Vec3) -> u32 {
    let d = (Vec3::from(source.position) - p).length();
    (d / source.step_length) as u32
}

/// Intensity of an animation step at `time`.
pub fn step_intensity(source: &PointSourceConfig, step: u32, time: f32) -> f32 {
    let phase = (time - step as f32 * source.step_delay) / source.period;
    (TAU * phase).sin() + source.bias
}

/// The point source's wind at a vertex (`p` on the ground, unit `normal`).
pub fn point_source(
    source: &PointSourceConfig,
    p: Vec3,
    normal: Vec3,
    time: f32,
    max_intensity: f32,
) -> VertexWind {
    let w = (Vec3::from(source.position) - p).normalize_or_zero();
    VertexWind {
        vector: tangent_direction(w, normal),
        intensity: step_intensity(source, step(source, p), time)
            .clamp(-max_intensity, max_intensity),
    }
}

/// The scene's wind `velocity` (m/s) at a vertex with unit `normal`.
pub fn scene(velocity: Vec3, normal: Vec3, reference_speed: f32, max_intensity: f32) -> VertexWind {
    let tangential = velocity - velocity.dot(normal) * normal;
    VertexWind {
        vector: tangent_direction(velocity, normal),
        intensity: (tangential.length() / reference_speed).min(max_intensity),
    }
}

/// Position of shell `k` of a vertex: `p + N·n_k + V_w·w_k` (Bakay Sec. 3, Fig. 6).
pub fn shell_position(p: Vec3, normal: Vec3, wind: VertexWind, offset: (f32, f32)) -> Vec3 {
    p + normal * offset.0 + wind.vector * offset.1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bend;
    use grassbench::wind::{PointSource, WindField};

    #[test]
    fn mirror_agrees_with_the_cores_point_source() {
        let config = PointSourceConfig {
            position: [3.0, 1.0, -7.0],
            period: 2.7,
            step_length: 1.3,
            step_delay: 0.21,
            bias: 0.15,
            ..Default::default()
        };
        let core = PointSource::new(config.clone());
        for k in 0..500 {
            let p = Vec3::new(
                (k as f32 * 0.731).sin() * 40.0,
                (k % 7) as f32 * 0.3,
                (k as f32 * 0.377).cos() * 40.0,
            );
            let t = k as f32 * 0.093;
            let s = step(&config, p);
            assert_eq!(s, core.step(p));
            assert_eq!(step_intensity(&config, s, t), core.intensity(s, t));
            // Unclamped, the mirror's W·I points where the core's velocity does.
            let mirror = point_source(&config, p, Vec3::Y, t, f32::INFINITY);
            let v = core.velocity(p, t);
            let w = Vec3::from(config.position) - p;
            let expected =
                tangent_direction(w.normalize(), Vec3::Y) * v.dot(w.normalize()).signum();
            let ours = mirror.vector * mirror.intensity.signum();
            if mirror.intensity.abs() > 1e-3 {
                assert!(ours.dot(expected) > 0.999, "{ours} vs {expected}");
            }
        }
    }

    #[test]
    fn wind_vector_is_tangent_and_unit() {
        let n = Vec3::new(0.3, 1.0, -0.2).normalize();
        let v = tangent_direction(Vec3::new(0.2, 0.9, 0.4), n);
        assert!(v.dot(n).abs() < 1e-6 && (v.length() - 1.0).abs() < 1e-6);
        assert_eq!(tangent_direction(n * 3.0, n), Vec3::ZERO);
        assert_eq!(scene(Vec3::ZERO, n, 10.0, 1.0).intensity, 0.0);
    }

    #[test]
    fn wind_moves_blade_tips_towards_the_wind_vector() {
        let (p, n) = (
            Vec3::new(2.0, 0.5, 1.0),
            Vec3::new(0.1, 1.0, 0.05).normalize(),
        );
        let velocity = Vec3::new(4.0, 0.0, 1.5);
        let wind = scene(velocity, n, 8.0, 1.0);
        let calm = scene(Vec3::ZERO, n, 8.0, 1.0);
        let offsets = bend::offsets(16, 0.04, wind.intensity, 1.0);
        let rest = bend::offsets(16, 0.04, calm.intensity, 1.0);
        let tip = shell_position(p, n, wind, offsets[15]);
        let rest_tip = shell_position(p, n, calm, rest[15]);
        // The tip moved downwind and lower, the root did not move.
        let moved = tip - rest_tip;
        assert!(moved.dot(velocity.normalize()) > 0.05, "{moved}");
        let tangential = moved - moved.dot(n) * n;
        assert!(
            tangential.normalize().dot(wind.vector) > 0.999,
            "{tangential}"
        );
        assert!((tip - p).dot(n) < (rest_tip - p).dot(n));
        assert_eq!(shell_position(p, n, wind, offsets[0]), p);
        // Stronger wind moves it further.
        let gale = scene(velocity * 2.0, n, 8.0, 1.0);
        let gale_tip = shell_position(p, n, gale, bend::offsets(16, 0.04, gale.intensity, 1.0)[15]);
        assert!((gale_tip - rest_tip).dot(wind.vector) > moved.dot(wind.vector));
    }

    #[test]
    fn intensity_is_clamped() {
        let config = PointSourceConfig {
            bias: 1.5,
            ..Default::default()
        };
        let w = point_source(&config, Vec3::new(5.0, 0.0, 0.0), Vec3::Y, 1.0, 1.0);
        assert!(w.intensity <= 1.0);
        assert_eq!(scene(Vec3::X * 100.0, Vec3::Y, 10.0, 0.7).intensity, 0.7);
    }
}
