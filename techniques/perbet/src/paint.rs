//! Start-up rendering of the coarser representations from the 3D blades (Sec. 2.2): the 2.5D
//! strip textures ("2D images of the 3D blades included in a slice of the 3D patch") and the 2D
//! terrain texture ("coarse images of the 3D patch taken from different viewing angles",
//! mipmapped).
//!
//! The images are rasterised on the CPU, so they are identical on every adapter and need no GPU
//! at all (tests check them without one): each blade's segments become quads of its tapering
//! width, projected orthographically, with a depth test, supersampled 2 x 2 and box-filtered.
//! Every texel keeps the linear albedo of the nearest blade, the coverage in alpha, and an
//! auxiliary triple: that blade's density threshold (so the density map thins strips and the 2D
//! texture like the 3D blades, Boulanger's per-texel test), the relative height along the
//! blade (for the same root-darkening as the 3D blades) and the direction its face looks
//! (so strips are lit blade by blade like the 3D blades they stand for).

use glam::{Vec2, Vec3};
use grassbench::grass::GrassConfig;

use crate::patch::{Layout, Patch, PatchBlade};

/// Supersampling per axis.
const SUPERSAMPLE: u32 = 2;

/// Elevations (radians above the horizon) of the views the 2D textures are rendered from: one
/// texture per elevation ("coarse images of the 3D patch taken from different viewing angles",
/// Sec. 2.2), blended by the angle each pixel is seen at. Far patches of a walker's view are
/// seen from a few degrees up, where standing grass covers everything; a flyover sees them
/// from higher, where the ground shows between blades.
pub const FLAT_ELEVATIONS: [f32; 3] = [
    10.0 * std::f32::consts::PI / 180.0,
    30.0 * std::f32::consts::PI / 180.0,
    60.0 * std::f32::consts::PI / 180.0,
];

/// One texture level.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width, texels.
    pub width: u32,
    /// Height, texels.
    pub height: u32,
    /// Linear albedo (rgb, straight) and coverage (a), row-major, top row first.
    pub color: Vec<[f32; 4]>,
    /// Density threshold, relative height along the blade, and the angle of the blade's face
    /// normal around y over π (in `[0, 1)`; the normal is `(−sin, 0, cos)` of it).
    pub aux: Vec<[f32; 3]>,
}

impl Image {
    fn empty(width: u32, height: u32) -> Self {
        let n = (width * height) as usize;
        Self {
            width,
            height,
            color: vec![[0.0; 4]; n],
            aux: vec![[1.0, 0.0, 0.0]; n],
        }
    }

    /// Mean coverage.
    pub fn coverage(&self) -> f32 {
        self.color.iter().map(|c| c[3]).sum::<f32>() / self.color.len().max(1) as f32
    }

    /// Gives transparent texels the mean colour of the covered ones, so filtering never pulls
    /// black into blade edges.
    fn fill_transparent(&mut self) {
        let (mut sum, mut weight) = (Vec3::ZERO, 0.0);
        for c in &self.color {
            sum += Vec3::new(c[0], c[1], c[2]) * c[3];
            weight += c[3];
        }
        let mean = if weight > 0.0 {
            sum / weight
        } else {
            Vec3::ZERO
        };
        for c in &mut self.color {
            if c[3] <= 0.0 {
                *c = [mean.x, mean.y, mean.z, 0.0];
            }
        }
    }

    /// The next mip level: 2 x 2 boxes, colour weighted by coverage.
    pub fn half(&self) -> Self {
        let (w, h) = ((self.width / 2).max(1), (self.height / 2).max(1));
        let mut out = Self::empty(w, h);
        for y in 0..h {
            for x in 0..w {
                let (mut c, mut a, mut aux, mut n) = (Vec3::ZERO, 0.0, [0.0f32; 3], 0.0);
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let (sx, sy) = (
                        (2 * x + dx).min(self.width - 1),
                        (2 * y + dy).min(self.height - 1),
                    );
                    let i = (sy * self.width + sx) as usize;
                    let t = self.color[i];
                    c += Vec3::new(t[0], t[1], t[2]) * t[3];
                    a += t[3];
                    for (sum, v) in aux.iter_mut().zip(self.aux[i]) {
                        *sum += v * t[3];
                    }
                    n += 1.0;
                }
                let i = (y * w + x) as usize;
                if a > 0.0 {
                    let c = c / a;
                    out.color[i] = [c.x, c.y, c.z, a / n];
                    out.aux[i] = aux.map(|v| v / a);
                }
            }
        }
        out.fill_transparent();
        out
    }

    /// This level and every smaller one down to 1 x 1.
    pub fn mip_chain(self) -> Vec<Self> {
        let mut levels = vec![self];
        while let Some(last) = levels.last()
            && (last.width > 1 || last.height > 1)
        {
            let next = last.half();
            levels.push(next);
        }
        levels
    }
}

/// A supersampled canvas with a depth buffer (larger depth = nearer the viewer).
struct Canvas {
    width: u32,
    height: u32,
    wrap: bool,
    depth: Vec<f32>,
    texels: Vec<Option<Texel>>,
}

/// What a sample of the canvas keeps: albedo, threshold, relative height, face angle / π.
type Texel = ([f32; 3], f32, f32, f32);

/// What is drawn: the blade's albedo along its height, its threshold and face angle / π.
struct Paint<'a> {
    albedo: &'a dyn Fn(f32) -> [f32; 3],
    threshold: f32,
    face: f32,
}

/// A projected vertex: pixel position, depth, relative height along the blade.
#[derive(Clone, Copy)]
struct Vertex {
    pixel: Vec2,
    depth: f32,
    s: f32,
}

impl Canvas {
    fn new(width: u32, height: u32, wrap: bool) -> Self {
        let n = (width * height) as usize;
        Self {
            width,
            height,
            wrap,
            depth: vec![f32::NEG_INFINITY; n],
            texels: vec![None; n],
        }
    }

    /// Fills triangle `t` (pixel centres inside it), keeping the nearest blade per sample.
    fn triangle(&mut self, t: [Vertex; 3], paint: &Paint<'_>) {
        let [a, b, c] = t;
        let area = (b.pixel - a.pixel).perp_dot(c.pixel - a.pixel);
        if area.abs() < 1e-9 {
            return;
        }
        let min = a.pixel.min(b.pixel).min(c.pixel).floor();
        let max = a.pixel.max(b.pixel).max(c.pixel).ceil();
        let (x0, x1, y0, y1) = (min.x as i64, max.x as i64, min.y as i64, max.y as i64);
        if !self.wrap
            && (x1 < 0 || y1 < 0 || x0 >= i64::from(self.width) || y0 >= i64::from(self.height))
        {
            return;
        }
        for y in y0..=y1 {
            for x in x0..=x1 {
                let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                let wa = (b.pixel - p).perp_dot(c.pixel - p) / area;
                let wb = (c.pixel - p).perp_dot(a.pixel - p) / area;
                let wc = 1.0 - wa - wb;
                if wa < 0.0 || wb < 0.0 || wc < 0.0 {
                    continue;
                }
                let Some(i) = self.index(x, y) else { continue };
                let depth = wa * a.depth + wb * b.depth + wc * c.depth;
                if depth <= self.depth[i] {
                    continue;
                }
                let s = (wa * a.s + wb * b.s + wc * c.s).clamp(0.0, 1.0);
                self.depth[i] = depth;
                self.texels[i] = Some(((paint.albedo)(s), paint.threshold, s, paint.face));
            }
        }
    }

    fn index(&self, x: i64, y: i64) -> Option<usize> {
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        let (x, y) = if self.wrap {
            (x.rem_euclid(w), y.rem_euclid(h))
        } else if (0..w).contains(&x) && (0..h).contains(&y) {
            (x, y)
        } else {
            return None;
        };
        Some((y * w + x) as usize)
    }

    /// Box-filters the supersamples into an image.
    fn resolve(&self) -> Image {
        let (w, h) = (self.width / SUPERSAMPLE, self.height / SUPERSAMPLE);
        let mut out = Image::empty(w, h);
        let per = (SUPERSAMPLE * SUPERSAMPLE) as f32;
        for y in 0..h {
            for x in 0..w {
                let (mut c, mut n, mut aux) = (Vec3::ZERO, 0.0, [0.0f32; 3]);
                for sy in 0..SUPERSAMPLE {
                    for sx in 0..SUPERSAMPLE {
                        let i =
                            ((y * SUPERSAMPLE + sy) * self.width + x * SUPERSAMPLE + sx) as usize;
                        if let Some((albedo, threshold, s, face)) = self.texels[i] {
                            c += Vec3::from(albedo);
                            aux[0] += threshold;
                            aux[1] += s;
                            aux[2] += face;
                            n += 1.0;
                        }
                    }
                }
                if n > 0.0 {
                    let i = (y * w + x) as usize;
                    let c = c / n;
                    out.color[i] = [c.x, c.y, c.z, n / per];
                    out.aux[i] = aux.map(|v| v / n);
                }
            }
        }
        out.fill_transparent();
        out
    }
}

/// The albedo of a blade at relative height `s`: root to tip colour with the blade's
/// variation, the same formula as the 3D blades' vertex shader.
pub fn albedo(grass: &GrassConfig, variation: f32, s: f32) -> [f32; 3] {
    let root = Vec3::from(grass.color_root);
    let tip = Vec3::from(grass.color_tip);
    let v = variation * grass.color_variation;
    let mut c = root.lerp(tip, s.max(0.0).powf(0.8)) * (1.0 + v);
    c.x *= 1.0 + 0.6 * v.max(0.0);
    c.to_array()
}

/// Half the width of a blade at relative height `s` (tapering to a point at the tip), as in
/// the 3D blades' vertex shader.
pub fn half_width(width: f32, s: f32) -> f32 {
    0.5 * width * (1.0 - s).max(0.0).powf(0.7)
}

/// Draws `blade` (at rest) with `project` (patch-local point → pixel and depth).
fn draw_blade(
    canvas: &mut Canvas,
    blade: &PatchBlade,
    segments: u32,
    grass: &GrassConfig,
    project: &dyn Fn(Vec3) -> (Vec2, f32),
) {
    let points = blade.rest_points(segments);
    let side = Vec3::new(blade.facing.cos(), 0.0, blade.facing.sin());
    let albedo = |s: f32| albedo(grass, blade.variation, s);
    let paint = Paint {
        albedo: &albedo,
        threshold: blade.threshold,
        face: blade.facing.rem_euclid(std::f32::consts::PI) / std::f32::consts::PI,
    };
    let n = points.len() - 1;
    let corner = |i: usize, sign: f32| {
        let s = i as f32 / n as f32;
        let (pixel, depth) = project(points[i] + side * sign * half_width(blade.width, s));
        Vertex { pixel, depth, s }
    };
    for i in 0..n {
        let (a, b, c, d) = (
            corner(i, -1.0),
            corner(i, 1.0),
            corner(i + 1, -1.0),
            corner(i + 1, 1.0),
        );
        canvas.triangle([a, b, c], &paint);
        canvas.triangle([c, b, d], &paint);
    }
}

/// Size in texels of one strip texture for `layout` with `texels` along the strip.
pub fn strip_size(layout: &Layout, texels: u32) -> (u32, u32) {
    let height = (texels as f32 * layout.strip_height / layout.strip_length()).ceil() as u32;
    (texels, height.max(4))
}

/// The strip textures of `patch`: `2 · strips` images, orientation-major (layer
/// `orientation · strips + k`), each the orthographic image, along the strip's normal seen from
/// its + side, of the blades of its slab.
pub fn strips(patch: &Patch, layout: &Layout, grass: &GrassConfig, texels: u32) -> Vec<Image> {
    let (w, h) = strip_size(layout, texels);
    let mut out = Vec::with_capacity(2 * layout.strips as usize);
    for orientation in 0..2u32 {
        for k in 0..layout.strips {
            let mut canvas = Canvas::new(w * SUPERSAMPLE, h * SUPERSAMPLE, false);
            let (cw, ch) = (canvas.width as f32, canvas.height as f32);
            let project = |p: Vec3| {
                let uv = layout.painted_uv(orientation, p);
                let depth = if orientation == 0 { p.z } else { p.x };
                (Vec2::new(uv.x * cw, (1.0 - uv.y) * ch), depth)
            };
            for blade in patch
                .blades
                .iter()
                .filter(|b| b.strips[orientation as usize] == k)
            {
                draw_blade(&mut canvas, blade, layout.segments, grass, &project);
            }
            out.push(canvas.resolve());
        }
    }
    out
}

/// The 2D texture of `patch` (`texels` square, tiling) seen from `elevation` (radians above the
/// horizon): the average of four views at azimuths 0°, 90°, 180° and 270°, each projected
/// along its view direction onto the plane at half the strip height, the surface the 2D
/// representation is drawn on (Sec. 4.3).
pub fn flat(
    patch: &Patch,
    layout: &Layout,
    grass: &GrassConfig,
    texels: u32,
    elevation: f32,
) -> Image {
    let side = texels * SUPERSAMPLE;
    let plane = 0.5 * layout.strip_height;
    let scale = side as f32 / layout.size;
    let views: Vec<Image> = (0..4)
        .map(|a| {
            let azimuth = Vec2::from_angle(a as f32 * std::f32::consts::FRAC_PI_2);
            let (c, s) = (elevation.cos(), elevation.sin());
            let view = Vec3::new(azimuth.x * c, -s, azimuth.y * c);
            let mut canvas = Canvas::new(side, side, true);
            let project = |p: Vec3| {
                let t = (plane - p.y) / view.y;
                let q = Vec2::new(p.x + t * view.x, p.z + t * view.z);
                (q * scale, -p.dot(view))
            };
            for blade in &patch.blades {
                draw_blade(&mut canvas, blade, layout.segments, grass, &project);
            }
            canvas.resolve()
        })
        .collect();
    average(&views)
}

/// The coverage-weighted average of equally sized images.
fn average(images: &[Image]) -> Image {
    let Some(first) = images.first() else {
        return Image::empty(1, 1);
    };
    let mut out = Image::empty(first.width, first.height);
    for i in 0..out.color.len() {
        let (mut c, mut a, mut aux) = (Vec3::ZERO, 0.0, [0.0f32; 3]);
        for img in images {
            let t = img.color[i];
            c += Vec3::new(t[0], t[1], t[2]) * t[3];
            a += t[3];
            for (sum, v) in aux.iter_mut().zip(img.aux[i]) {
                *sum += v * t[3];
            }
        }
        if a > 0.0 {
            let c = c / a;
            out.color[i] = [c.x, c.y, c.z, a / images.len() as f32];
            out.aux[i] = aux.map(|v| v / a);
        }
    }
    out.fill_transparent();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::patch;

    fn setup() -> (Layout, Vec<Patch>, GrassConfig) {
        let grass = GrassConfig::default();
        let mut layout = Layout {
            size: 2.5,
            segments: 4,
            strips: 8,
            columns: 4,
            margin: 0.12,
            strip_height: 1.0,
        };
        let patches = patch::build(&grass, &layout, (1, 320, 2), 0.12, 5);
        layout.strip_height = patch::tallest(&patches, layout.segments, 0.5);
        (layout, patches, grass)
    }

    #[test]
    fn every_painted_blade_is_on_its_strip_where_its_coordinates_say() {
        let (layout, patches, grass) = setup();
        let images = strips(&patches[0], &layout, &grass, 256);
        assert_eq!(images.len(), 16);
        let (w, h) = (images[0].width as f32, images[0].height as f32);
        // The morph target of every blade's middle point (Sec. 4.2, Fig. 14) lies on painted
        // texels of its strip (allowing one texel for the blade's width).
        let mut hits = 0;
        let mut total = 0;
        for blade in &patches[0].blades {
            let points = blade.rest_points(layout.segments);
            for o in 0..2u32 {
                let image = &images[(o * layout.strips + blade.strips[o as usize]) as usize];
                let uv = layout.painted_uv(o, points[1]);
                let (x, y) = ((uv.x * w) as i64, ((1.0 - uv.y) * h) as i64);
                let covered = (-1..=1).any(|dy| {
                    (-1..=1).any(|dx| {
                        let (x, y) = (x + dx, y + dy);
                        x >= 0
                            && y >= 0
                            && x < w as i64
                            && y < h as i64
                            && image.color[(y * w as i64 + x) as usize][3] > 0.0
                    })
                });
                hits += usize::from(covered);
                total += 1;
            }
        }
        // Edge-on blades project to nothing; nearly all others must be found.
        assert!(hits as f32 > 0.9 * total as f32, "{hits} of {total}");
    }

    #[test]
    fn strips_of_an_orientation_show_every_blade_once() {
        let (layout, patches, grass) = setup();
        let images = strips(&patches[0], &layout, &grass, 128);
        // Emptying one slab empties only its strip.
        let mut thinned = patches[0].clone();
        thinned.blades.retain(|b| b.strips[0] != 2);
        let after = strips(&thinned, &layout, &grass, 128);
        for k in 0..layout.strips as usize {
            if k == 2 {
                assert_eq!(after[k].coverage(), 0.0);
                assert!(images[k].coverage() > 0.0);
            } else {
                assert_eq!(after[k], images[k]);
            }
        }
    }

    #[test]
    fn the_flat_texture_tiles_and_mipmaps_down_to_one_texel() {
        let (layout, patches, grass) = setup();
        let low = flat(&patches[0], &layout, &grass, 64, FLAT_ELEVATIONS[0]);
        let high = flat(&patches[0], &layout, &grass, 64, FLAT_ELEVATIONS[2]);
        // Grass seen from near the horizon covers more than seen from above.
        assert!(low.coverage() > 0.5, "{}", low.coverage());
        assert!(
            high.coverage() < 0.8 * low.coverage(),
            "{} {}",
            high.coverage(),
            low.coverage()
        );
        let chain = low.clone().mip_chain();
        assert_eq!(chain.len(), 7);
        let last = chain.last().unwrap();
        assert_eq!((last.width, last.height), (1, 1));
        // Box filtering keeps the mean coverage.
        assert!((last.coverage() - low.coverage()).abs() < 1e-3);
        // Seamless: texels on opposite borders are both painted about as often.
        let w = low.width as usize;
        let col = |x: usize| (0..w).map(|y| low.color[y * w + x][3]).sum::<f32>() / w as f32;
        assert!((col(0) - col(w - 1)).abs() < 0.25);
    }

    #[test]
    fn albedo_matches_the_blade_shader_formula() {
        let g = GrassConfig::default();
        assert_eq!(albedo(&g, 0.0, 0.0), g.color_root);
        let tip = albedo(&g, 0.0, 1.0);
        for (a, b) in tip.iter().zip(g.color_tip) {
            assert!((a - b).abs() < 1e-6);
        }
    }
}
