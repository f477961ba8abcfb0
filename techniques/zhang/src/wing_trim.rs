//! Wings cut down to the texels they can show (an addition: the thesis draws each wing as the
//! whole rectangle between its two plants' roots and tops).
//!
//! A wing of the finest billboards (`l' = 5`) shows two or three blades of the texture of
//! Fig. 11 in a rectangle as tall as the tallest blade of the scene: most of its area is clear
//! texels that the fragment shader discards. A GPU with a hardware rasteriser hardly notices;
//! a software one (lavapipe) pays for every covered pixel, and on the meadow's walk the wings
//! cover the screen five times over, most of it in the nearest billboards.
//!
//! So each wing is cut once, at start-up, to the part of its rectangle that holds every texel a
//! fragment of it could keep: alpha at or above the cut-off and a density threshold below the
//! wing's density (the two tests of `fs_wing`). Its ends move in to the first and last texel
//! columns holding one, its top down to the highest such texel; a wing that can show nothing
//! is not drawn. The cut keeps a texel column of margin at both ends and a row above
//! (nearest-texel lookups of interpolated coordinates can land one texel off). Its corners
//! are the wing's corners interpolated along its length and up its height, with the texture
//! coordinates, so on a planar wing the image is the same; a swaying wing's two tops need not
//! lie in one plane with its roots, and there the cut rectangle's diagonal is not the whole
//! one's (a texel off here and there). `trim_wings = false` draws whole wings.
//!
//! Cutting a wing into several strips of different heights saves more fill (measured over the
//! first frames of the meadow's walk: 46 % of the wings' projected area, against 24 % for one
//! rectangle) but costs an instance per strip; on lavapipe, with the wings lit per vertex, up
//! to four strips per wing were no faster than one rectangle (`results/zhang_lod/README.md`).

/// The part of a wing that is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cut {
    /// Where it starts and ends along the wing, as fractions of the wing's length from the
    /// middle line (0) to the outer edge (1).
    pub along: [f32; 2],
    /// Its height as a fraction of the wing's (texture `v` at its top edge).
    pub top: f32,
}

impl Cut {
    /// The whole wing.
    pub const WHOLE: Self = Self {
        along: [0.0, 1.0],
        top: 1.0,
    };
}

/// Threshold buckets: `k` in `0..=256`.
const BUCKETS: usize = 257;

/// For every texture layer and column, the rows that hold every texel a wing of a given
/// density could show.
#[derive(Clone, Debug)]
pub struct Skyline {
    /// Layer size in texels (columns, rows).
    size: (u32, u32),
    /// `rows[(layer·columns + x)·257 + k]`: one plus the highest row of column `x` holding a
    /// texel with alpha at or above the cut-off and a threshold below `k` (0 when none).
    rows: Vec<u16>,
}

impl Skyline {
    /// Scans `layers` RGBA8 layers of `size` texels (rows from the ground up, as
    /// [`crate::billboard_texture::billboard_texture`] writes them) for texels that pass an
    /// alpha test at `alpha_cutoff`.
    pub fn new(texels: &[[u8; 4]], size: (u32, u32), layers: u32, alpha_cutoff: f32) -> Self {
        let (w, h) = size;
        let mut rows = vec![0u16; (layers * w) as usize * BUCKETS];
        let shown = |a: u8| f32::from(a) / 255.0 >= alpha_cutoff - 1e-4;
        for layer in 0..layers {
            for x in 0..w {
                let column = &mut rows[((layer * w + x) as usize) * BUCKETS..][..BUCKETS];
                for y in 0..h {
                    let Some(t) = texels.get(((layer * h + y) * w + x) as usize) else {
                        continue;
                    };
                    if shown(t[3]) {
                        // Kept by every density whose bucket exceeds the threshold.
                        let k = usize::from(t[1]) + 1;
                        column[k] = column[k].max((y + 1) as u16);
                    }
                }
                for k in 1..BUCKETS {
                    column[k] = column[k].max(column[k - 1]);
                }
            }
        }
        Self { size, rows }
    }

    /// The bucket of a wing of density `density`: the shader keeps a texel when
    /// `g / 255 < density` (times a fade alpha at most 1), so thresholds `g < k`, with a
    /// little room for rounding.
    fn bucket(density: f32) -> usize {
        ((255.0 * density.clamp(0.0, 1.0) + 1e-3).floor() as usize + 1).min(BUCKETS - 1)
    }

    /// Rows needed at texel column `x` (any integer: the texture repeats along `u`).
    fn rows(&self, layer: u32, x: i64, bucket: usize) -> u16 {
        let x = x.rem_euclid(i64::from(self.size.0)) as usize;
        self.rows[(layer as usize * self.size.0 as usize + x) * BUCKETS + bucket]
    }

    /// The cut of a wing showing texture `u` from `u[0]` (middle line) to `u[1]` (outer edge)
    /// of `layer` at `density`; `None` when it can show nothing.
    pub fn cut(&self, layer: u32, u: [f32; 2], density: f32) -> Option<Cut> {
        let (w, h) = (self.size.0 as f32, self.size.1 as f32);
        let (x0, x1) = (u[0] * w, u[1] * w);
        if !(x0.is_finite() && x1.is_finite() && x1 > x0) {
            return Some(Cut::WHOLE);
        }
        let bucket = Self::bucket(density);
        let columns = x0.floor() as i64..=x1.floor() as i64;
        let shown = || columns.clone().filter(|&x| self.rows(layer, x, bucket) > 0);
        let (first, last) = (shown().next()?, shown().next_back()?);
        let rows = shown().map(|x| self.rows(layer, x, bucket)).max()?;
        // A column of margin each side, a row above.
        let along = |x: i64| ((x as f32 - x0) / (x1 - x0)).clamp(0.0, 1.0);
        Some(Cut {
            along: [along(first - 1), along(last + 2)],
            top: ((f32::from(rows) + 1.0) / h).min(1.0),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::billboard_texture::{Look, SIZE, SPAN, billboard_texture};
    use grassbench::grass::GrassConfig;
    use proptest::prelude::*;

    fn texture() -> (Vec<[u8; 4]>, Vec<u32>) {
        let grass = GrassConfig::default();
        let look = Look {
            grass: &grass,
            spacing: 5.0 / 32.0,
            flower_fraction: 0.02,
            petal_size: 0.07,
        };
        let steps = vec![4, 8, 16];
        (billboard_texture(&look, &steps, 3), steps)
    }

    /// Whether `fs_wing` could keep the texel at wing fraction `s`, height `v`.
    fn kept(t: &[[u8; 4]], layer: u32, u: [f32; 2], density: f32, s: f32, v: f32) -> bool {
        let (w, h) = SIZE;
        let uu = u[0] + (u[1] - u[0]) * s;
        let x = ((uu.fract() * w as f32) as u32) % w;
        let y = ((v * h as f32) as u32).min(h - 1);
        let texel = t[((layer * h + y) * w + x) as usize];
        f32::from(texel[3]) / 255.0 >= 0.05 && f32::from(texel[1]) / 255.0 < density
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Every texel the shader could keep is inside the cut, and the cut inside the wing.
        #[test]
        fn the_cut_holds_every_texel_a_wing_can_show(
            u0 in 0.0f32..1.0,
            layer in 0u32..3,
            diagonal in any::<bool>(),
            density in 0.0f32..1.0,
        ) {
            let (t, steps) = texture();
            let sky = Skyline::new(&t, SIZE, 3, 0.05);
            let spacings = steps[layer as usize] as f32 / 2.0 * if diagonal { 2f32.sqrt() } else { 1.0 };
            let u = [u0, u0 + spacings / SPAN];
            let cut = sky.cut(layer, u, density);
            if let Some(c) = cut {
                prop_assert!(0.0 <= c.along[0] && c.along[0] < c.along[1] && c.along[1] <= 1.0);
                prop_assert!(c.top > 0.0 && c.top <= 1.0);
            }
            for i in 0..400 {
                for j in 0..SIZE.1 {
                    let (s, v) = ((i as f32 + 0.5) / 400.0, (j as f32 + 0.5) / SIZE.1 as f32);
                    if kept(&t, layer, u, density, s, v) {
                        prop_assert!(
                            cut.is_some_and(|c| c.along[0] <= s && s <= c.along[1] && v <= c.top),
                            "texel at s {s}, v {v} outside {cut:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn the_nearest_wings_keep_a_third_of_their_area() {
        let (t, steps) = texture();
        let sky = Skyline::new(&t, SIZE, 3, 0.05);
        let mut kept_area = 0.0;
        let n = 200;
        for k in 0..n {
            let u0 = (k as f32 * 0.618_034).fract();
            let u = [u0, u0 + steps[0] as f32 / 2.0 / SPAN];
            kept_area += sky
                .cut(0, u, 1.0)
                .map_or(0.0, |c| (c.along[1] - c.along[0]) * c.top);
        }
        let fraction = kept_area / n as f32;
        // Measured 0.325 with the default grass (0.72 on the meadow's walk, whose blade
        // heights vary more); whole wings would be 1.
        eprintln!("measured: kept {fraction:.3} of the nearest wings' area");
        assert!(fraction > 0.2 && fraction < 0.5, "{fraction}");
    }

    #[test]
    fn empty_and_thinned_wings_draw_nothing() {
        let (w, h) = SIZE;
        let mut t = vec![[0u8; 4]; (w * h) as usize];
        let sky = Skyline::new(&t, SIZE, 1, 0.05);
        assert_eq!(sky.cut(0, [0.1, 0.35], 1.0), None);
        // One blade, 40 rows tall, at column 50 (u = 0.197), threshold 200 of 255.
        for y in 0..40 {
            t[(y * w + 50) as usize] = [128, 200, 0, 255];
        }
        let sky = Skyline::new(&t, SIZE, 1, 0.05);
        assert_eq!(sky.cut(0, [0.1, 0.35], 0.7), None, "thinned away");
        let c = sky.cut(0, [0.1, 0.35], 0.8).expect("kept");
        // Column 50 with one of margin each side: texels 49..52 of the wing's 25.6..89.6.
        let along = |x: f32| (x - 25.6) / 64.0;
        assert!((c.along[0] - along(49.0)).abs() < 1e-4, "{c:?}");
        assert!((c.along[1] - along(52.0)).abs() < 1e-4, "{c:?}");
        // 40 rows and one of margin.
        assert_eq!(c.top, 41.0 / h as f32);
    }
}
