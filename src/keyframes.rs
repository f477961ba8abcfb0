//! Keyframed values over scene time, shared by everything a scene moves along a path (the
//! moving object, blasts of wind, lights). A ground-floor module: it imports nothing of the
//! scene or the wind, so both can use it.

use glam::{Vec2, Vec3};

use crate::params::check;
use crate::{Error, Result};

/// The value at `time` of keyframes sorted by time: linear between the two around it, held
/// before the first and after the last; `None` without keyframes. `key` gives a keyframe's
/// time and value.
pub fn sample<K>(keys: &[K], time: f32, key: impl Fn(&K) -> (f32, Vec3)) -> Option<Vec3> {
    let (first_time, first) = key(keys.first()?);
    if time <= first_time {
        return Some(first);
    }
    for w in keys.windows(2) {
        let ((t0, a), (t1, b)) = (key(&w[0]), key(&w[1]));
        if time < t1 {
            let f = (time - t0) / (t1 - t0).max(1e-6);
            return Some(a.lerp(b, f));
        }
    }
    keys.last().map(|k| key(k).1)
}

/// A ground position along a path: piecewise linear through `keyframes` (`[time, x, z]`,
/// held before the first and after the last), or `start + velocity · time` without any.
pub fn track(start: [f32; 2], velocity: [f32; 2], keyframes: &[[f32; 3]], time: f32) -> Vec2 {
    sample(keyframes, time, |k| (k[0], Vec3::new(k[1], 0.0, k[2])))
        .map_or(Vec2::from(start) + Vec2::from(velocity) * time, |p| {
            Vec2::new(p.x, p.z)
        })
}

/// Checks a path's numbers; errors name `prefix.<key>`.
pub fn validate_track(
    prefix: &str,
    start: [f32; 2],
    velocity: [f32; 2],
    keyframes: &[[f32; 3]],
) -> Result<()> {
    for (c, v) in start.iter().enumerate() {
        check(&format!("{prefix}.start[{c}]"), *v, -1e6..=1e6)?;
    }
    for (c, v) in velocity.iter().enumerate() {
        check(&format!("{prefix}.velocity[{c}]"), *v, -1e4..=1e4)?;
    }
    for (k, f) in keyframes.iter().enumerate() {
        for (c, v) in f.iter().enumerate() {
            check(&format!("{prefix}.keyframes[{k}][{c}]"), *v, -1e6..=1e6)?;
        }
        if k > 0 && f[0] <= keyframes[k - 1][0] {
            return Err(Error::param(
                format!("{prefix}.keyframes[{k}][0]"),
                f[0],
                "times that increase from one keyframe to the next",
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keyframes_interpolate_and_hold() {
        let keys = [(1.0, Vec3::ZERO), (3.0, Vec3::new(2.0, 4.0, -2.0))];
        let at = |t| sample(&keys, t, |k| *k);
        assert_eq!(at(0.0), Some(Vec3::ZERO));
        assert_eq!(at(2.0), Some(Vec3::new(1.0, 2.0, -1.0)));
        assert_eq!(at(9.0), Some(Vec3::new(2.0, 4.0, -2.0)));
        assert_eq!(sample(&[] as &[(f32, Vec3)], 1.0, |k| *k), None);
    }

    #[test]
    fn tracks_follow_keyframes_or_a_velocity() {
        let keys = [[0.0, 0.0, 0.0], [10.0, 10.0, -20.0]];
        assert_eq!(track([0.0; 2], [0.0; 2], &keys, -1.0), Vec2::ZERO);
        assert_eq!(track([0.0; 2], [0.0; 2], &keys, 5.0), Vec2::new(5.0, -10.0));
        assert_eq!(
            track([0.0; 2], [0.0; 2], &keys, 99.0),
            Vec2::new(10.0, -20.0)
        );
        assert_eq!(track([1.0, 2.0], [3.0, 0.0], &[], 2.0), Vec2::new(7.0, 2.0));
    }
}
