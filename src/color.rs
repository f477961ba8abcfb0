//! The sRGB transfer function, for techniques that store linear colours in 8-bit sRGB textures
//! (the GPU decodes them when sampling `*UnormSrgb` formats).

/// Linear `[0, 1]` to an 8-bit sRGB value (clamped).
pub fn srgb_encode(linear: f32) -> u8 {
    let l = linear.clamp(0.0, 1.0);
    let s = if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

/// An 8-bit sRGB value to linear `[0, 1]`.
pub fn srgb_decode(value: u8) -> f32 {
    let s = f32::from(value) / 255.0;
    if s <= 0.040_45 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips() {
        for v in 0..=255u8 {
            assert_eq!(srgb_encode(srgb_decode(v)), v);
        }
        assert_eq!((srgb_encode(0.0), srgb_encode(1.0)), (0, 255));
        assert_eq!(srgb_encode(f32::NAN), 0);
    }
}
