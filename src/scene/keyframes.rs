//! Keyframed values over scene time, shared by everything a scene moves along a path (the
//! moving object, blasts of wind, lights).

use glam::Vec3;

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
}
