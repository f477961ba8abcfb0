//! The one grass texture every shell samples (Bakay Sec. 3, Fig. 3) and its mip levels
//! (Sec. 5), generated on the CPU from a seed.
//!
//! Two planes of the same size and mip chain:
//! - `color_height` (`Rgba8UnormSrgb`): the blade's colour in RGB, its *height* in alpha; the
//!   ground between blades has alpha 0. A texel's alpha is the height up to which that texel
//!   lies inside its blade: a blade of relative height `h` whose cross-section (an ellipse of the
//!   blade's width and `aspect` times that across) tapers as `(1 − s)^0.7` with relative height
//!   `s` (the `reference` blade's taper) gives the texel at elliptic radius `r` the alpha
//!   `h·(1 − r^(1/0.7))`, so shells higher up cut smaller sections and blades end in points.
//! - `blade` (`Rg8Unorm`): the blade's density threshold (drawn where the density map exceeds
//!   it, as the scene's blade field) and its facing angle over π (for the leaf normal).
//!
//! A tile holds `round(density · tile²)` blades ([`blades_per_tile`]), so the tiled texture
//! has the scene's density to within half a blade a tile. They are placed by stratified
//! jittered sampling, one per cell of the smallest square lattice with enough cells, as the
//! scene's blade field (`grassbench::grass`), on a torus so the texture tiles; the few cells
//! left over (fewer than two rows) stay empty, chosen by a seeded hash. At density 0 the
//! texture is bare ground. Ground texels take the attributes of
//! their nearest blade (a Voronoi dilation), so bilinear filtering at a blade's rim never mixes
//! in another blade's threshold or colour.
//!
//! Mip levels (Sec. 5: "lower level MIPmaps cannot be generated from the textures
//! automatically, as the high frequency details of the grass will become lost. Custom MIPmaps,
//! likely retaining representative blades from level to level"):
//! - [`Mipmaps::Box`]: the automatic 2x2 average. Heights are averaged with the ground, so a
//!   far level holds one uniform, low alpha: the upper shells pass nowhere and the lower ones
//!   everywhere, i.e. distant grass becomes a short felt;
//! - [`Mipmaps::Custom`]: representative blades. Each coarse texel copies one of its four
//!   children (both planes), so it is a texel of a real blade or of real ground. A level of
//!   `n` texels keeps the base level's share of blade texels: the coarse texels with the most
//!   blade children (ties in a seeded order) copy a blade child, the others a ground child
//!   (children picked by a seeded hash). Its blade texels then take, tallest first to the one
//!   whose child is tallest, the heights at the middle of the base level's `n` height
//!   quantiles (`level_heights`), so the fraction of texels at or above any height (each
//!   shell's coverage) is the base level's to half a texel, at every level. Picking each
//!   coarse texel's child by a hash alone (as before issue 19) keeps that only in
//!   expectation, and a tile repeats its one draw everywhere: at the scene's density a tile
//!   holds few blades, and a coarse level of a sparse tile often showed none.

use glam::Vec2;
use grassbench::color::{srgb_decode, srgb_encode};
use grassbench::rng::hash;

use crate::params::Mipmaps;

/// What to generate.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureSpec {
    /// Texels along a side (power of two).
    pub size: u32,
    /// World size of one tile, m.
    pub tile_size: f32,
    /// Blades per m² (a tile holds this times its area, rounded).
    pub density: f32,
    /// Blade height range relative to the tallest (`[min/max, 1]`).
    pub height: [f32; 2],
    /// Skew of the height distribution: `min + (max − min)·u^skew`.
    pub height_skew: f32,
    /// Blade width range, m.
    pub width: [f32; 2],
    /// Cross-section thickness over width.
    pub aspect: f32,
    /// Linear albedo at the tip.
    pub color_tip: [f32; 3],
    /// Per-blade brightness and hue variation, 0..1.
    pub color_variation: f32,
    /// Seed.
    pub seed: u64,
}

/// One mip level.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// Texels along a side.
    pub size: u32,
    /// sRGB colour and linear height per texel, row-major.
    pub color_height: Vec<[u8; 4]>,
    /// Density threshold and facing / π per texel.
    pub blade: Vec<[u8; 2]>,
}

impl Level {
    /// Fraction of texels whose height is at least `threshold` (in `[0, 1]`): what a shell
    /// with that alpha test keeps of this level.
    pub fn coverage(&self, threshold: f32) -> f64 {
        let t = (threshold * 255.0).round() as u8;
        let n = self
            .color_height
            .iter()
            .filter(|c| c[3] >= t.max(1))
            .count();
        n as f64 / self.color_height.len().max(1) as f64
    }

    /// Bytes on the GPU (both planes).
    pub fn bytes(&self) -> u64 {
        (self.color_height.len() * 4 + self.blade.len() * 2) as u64
    }
}

/// GPU memory of a texture of side `size` with or without its mip chain: 6 bytes a texel
/// (colour + height, threshold + facing), a chain at most 4/3 of its base.
pub fn bytes_bound(size: u32, mipmaps: bool) -> u64 {
    let base = u64::from(size).pow(2) * 6;
    if mipmaps { base * 4 / 3 + 64 } else { base }
}

/// A blade of the texture, for counting blades over the terrain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureBlade {
    /// Centre in tile coordinates `[0, 1)²`.
    pub uv: Vec2,
    /// Density threshold in `[0, 1)`.
    pub threshold: f32,
}

/// The texture: its mip chain (level 0 first) and its blades.
#[derive(Clone, Debug)]
pub struct GrassTexture {
    /// Levels, finest first.
    pub levels: Vec<Level>,
    /// The blades of one tile.
    pub blades: Vec<TextureBlade>,
}

impl GrassTexture {
    /// Generates the base level and the mip chain `mipmaps` asks for.
    pub fn new(spec: &TextureSpec, mipmaps: Mipmaps) -> Self {
        let (base, blades) = base_level(spec);
        // The base level's heights, tallest first: custom levels take theirs from it.
        let mut sorted: Vec<u8> = base.color_height.iter().map(|c| c[3]).collect();
        sorted.sort_unstable_by(|a, b| b.cmp(a));
        let mut levels = vec![base];
        if mipmaps != Mipmaps::None {
            while let Some(last) = levels.last().filter(|l| l.size > 1) {
                let heights = level_heights(&sorted, (last.size / 2).max(1));
                let next = downsample(last, mipmaps, spec.seed, levels.len() as i64, &heights);
                levels.push(next);
            }
        }
        Self { levels, blades }
    }

    /// Bytes on the GPU, all levels.
    pub fn bytes(&self) -> u64 {
        self.levels.iter().map(Level::bytes).sum()
    }
}

/// The non-zero heights of a level of `size`² texels whose heights are the quantiles of the
/// base level's (`sorted`, tallest first): the height at the middle of each of its texels'
/// ranks. So for every shell, the share of the level's texels that reach it is the base
/// level's, to half a texel.
fn level_heights(sorted: &[u8], size: u32) -> Vec<u8> {
    let texels = u64::from(size) * u64::from(size);
    let scale = sorted.len() as f64 / texels as f64;
    (0..texels)
        .map(|r| {
            let at = ((r as f64 + 0.5) * scale) as usize;
            sorted.get(at).copied().unwrap_or(0)
        })
        .take_while(|&h| h > 0)
        .collect()
}

/// Taper exponent of a blade's width with height (as `reference`'s `pow(1 − s, 0.7)`).
const TAPER: f32 = 0.7;

#[derive(Clone, Copy)]
struct Blade {
    centre: Vec2,
    axis: Vec2,
    half_width: f32,
    half_thickness: f32,
    height: f32,
    color: [u8; 3],
    threshold: u8,
    facing: u8,
    threshold_f: f32,
}

/// Blades one tile of `spec` holds: its density times the tile's area, rounded, so the tiled
/// texture's density is the scene's to within half a blade a tile (0 below half a blade).
pub fn blades_per_tile(spec: &TextureSpec) -> u32 {
    let n = f64::from(spec.density.max(0.0)) * f64::from(spec.tile_size).powi(2);
    n.round().min(f64::from(u32::MAX)) as u32
}

/// Side of the square lattice of sampling cells holding `blades` blades: the smallest whose
/// cells are at least as many (a cell per blade, the rest left empty).
fn lattice_side(blades: u32) -> i64 {
    let mut side = (f64::from(blades).sqrt().floor() as i64).max(1);
    while side * side < i64::from(blades) {
        side += 1;
    }
    side
}

/// Ground texel attributes where no blade is near: a threshold no density map reaches.
const NO_BLADE: [u8; 2] = [255, 0];

fn base_level(spec: &TextureSpec) -> (Level, Vec<TextureBlade>) {
    let size = spec.size.max(1);
    let n = (size * size) as usize;
    let count = blades_per_tile(spec);
    if count == 0 {
        // No grass: bare ground everywhere.
        let level = Level {
            size,
            color_height: vec![[0, 0, 0, 0]; n],
            blade: vec![NO_BLADE; n],
        };
        return (level, Vec::new());
    }
    let px = size as f32 / spec.tile_size;
    // The tile holds exactly `count` blades: stratified jittered sampling on a `cells` x
    // `cells` lattice (as the scene's blade field), with the `cells² − count` cells that
    // come last in a seeded order left empty (fewer than `2 · cells`). A lattice of
    // `round(tile · √density)` cells a side would quantise the density to squares: at
    // 8 blades/m² on a 2 m tile, 36 blades instead of 32 (+12.5 %).
    let cells = lattice_side(count);
    let cell = size as f32 / cells as f32;
    let lerp = |r: [f32; 2], t: f32| r[0] + (r[1] - r[0]) * t;
    // The blades' random attributes (facing, size, width, colour, threshold) are stratified
    // over the tile: blade `k` of the tile draws attribute `d` from the `rank_d(k)`-th of
    // `count` equal intervals, `rank_d` a seeded permutation. Every tile repeats the same few
    // blades, so independent draws would leave the tile's mean height, width or share under
    // a density map off by chance, and every tile with it (with 32 blades a tile, the grass
    // shown at 8 and 16 blades/m² differed by 1.7 to 2.7 times over seven seeds instead of
    // about 2).
    let count_usize = count as usize;
    let ranks = |d: i64| -> Vec<u32> {
        let mut perm: Vec<usize> = (0..count_usize).collect();
        perm.sort_by_key(|&k| hash(spec.seed ^ 0x5354_5241, &[d, k as i64]));
        let mut rank = vec![0; count_usize];
        for (r, &k) in perm.iter().enumerate() {
            rank[k] = r as u32;
        }
        rank
    };
    let strata: Vec<Vec<u32>> = (2..=6).map(ranks).collect();
    let make = |i: i64, j: i64, k: usize| -> Blade {
        let h = |d: i64| (hash(spec.seed, &[i, j, d]) >> 40) as f32 / (1u64 << 24) as f32;
        // Attribute `d` (2..=6) of blade `k`: jittered in its stratum.
        let u = |d: i64| (strata[(d - 2) as usize][k] as f32 + h(d)) / count as f32;
        let facing = u(2) * std::f32::consts::PI;
        let size_draw = u(3);
        let half_width = 0.5 * lerp(spec.width, 0.5 * size_draw + 0.5 * u(4)) * px;
        let v = (u(5) * 2.0 - 1.0) * spec.color_variation;
        let c = spec.color_tip;
        let tip = [
            c[0] * (1.0 + v) * (1.0 + 0.6 * v.max(0.0)),
            c[1] * (1.0 + v),
            c[2] * (1.0 + v),
        ];
        let threshold = u(6);
        Blade {
            centre: Vec2::new((i as f32 + h(0)) * cell, (j as f32 + h(1)) * cell),
            axis: Vec2::from_angle(facing),
            // Thinner than a texel would vanish from the base level altogether.
            half_width: half_width.max(0.75),
            half_thickness: (half_width * spec.aspect).max(0.75),
            height: lerp(spec.height, size_draw.powf(spec.height_skew)).clamp(0.0, 1.0),
            color: tip.map(|x| srgb_encode(x.clamp(0.0, 1.0))),
            threshold: (threshold * 255.0).round() as u8,
            facing: (facing / std::f32::consts::PI * 255.0).round() as u8,
            threshold_f: threshold,
        }
    };
    let mut order: Vec<(i64, i64)> = (0..cells)
        .flat_map(|j| (0..cells).map(move |i| (i, j)))
        .collect();
    order.sort_by_key(|&(i, j)| hash(spec.seed ^ 0x4B45_4550, &[i, j]));
    let mut all: Vec<Option<Blade>> = vec![None; (cells * cells) as usize];
    for (k, &(i, j)) in order.iter().take(count_usize).enumerate() {
        all[(j * cells + i) as usize] = Some(make(i, j, k));
    }
    let blade_of =
        |i: i64, j: i64| all[(j.rem_euclid(cells) * cells + i.rem_euclid(cells)) as usize];
    let reach = ((spec.width[1] * 0.5 * px).max(0.75) / cell).ceil() as i64 + 1;
    let reach = reach.max(2);
    let mut color_height = Vec::with_capacity(n);
    let mut blade = Vec::with_capacity(n);
    let half = size as f32 * 0.5;
    let wrap = |d: f32| (d + half).rem_euclid(size as f32) - half;
    for y in 0..size {
        for x in 0..size {
            let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let (ci, cj) = ((p.x / cell) as i64, (p.y / cell) as i64);
            // Tallest blade covering the texel; else the nearest blade (dilation).
            let mut best: Option<(f32, Blade)> = None;
            let mut nearest: Option<(f32, Blade)> = None;
            for dj in -reach..=reach {
                for di in -reach..=reach {
                    let Some(b) = blade_of(ci + di, cj + dj) else {
                        continue;
                    };
                    let d = Vec2::new(wrap(p.x - b.centre.x), wrap(p.y - b.centre.y));
                    let across = d.dot(b.axis) / b.half_width;
                    let through = d.perp_dot(b.axis) / b.half_thickness;
                    let r = across.hypot(through);
                    let alpha = if r < 1.0 {
                        b.height * (1.0 - r.powf(1.0 / TAPER))
                    } else {
                        0.0
                    };
                    let dist = d.length();
                    if alpha > 0.0 && best.is_none_or(|(a, _)| alpha > a) {
                        best = Some((alpha, b));
                    }
                    if nearest.is_none_or(|(d, _)| dist < d) {
                        nearest = Some((dist, b));
                    }
                }
            }
            match best.or(nearest.map(|(_, b)| (0.0, b))) {
                Some((alpha, owner)) => {
                    let [r, g, b] = owner.color;
                    color_height.push([r, g, b, (alpha * 255.0).round() as u8]);
                    blade.push([owner.threshold, owner.facing]);
                }
                // Only where every cell in reach is empty (a rare hole in a sparse lattice).
                None => {
                    color_height.push([0, 0, 0, 0]);
                    blade.push(NO_BLADE);
                }
            }
        }
    }
    let blades = all
        .iter()
        .flatten()
        .map(|b| TextureBlade {
            uv: b.centre / size as f32,
            threshold: b.threshold_f,
        })
        .collect();
    (
        Level {
            size,
            color_height,
            blade,
        },
        blades,
    )
}

/// The next level of `fine` (level number `level`). Custom levels hand out `heights` (the
/// alphas of their blade texels, tallest first; see [`level_heights`]) to as many texels.
fn downsample(fine: &Level, mode: Mipmaps, seed: u64, level: i64, heights: &[u8]) -> Level {
    let size = (fine.size / 2).max(1);
    let at = |x: u32, y: u32| (y.min(fine.size - 1) * fine.size + x.min(fine.size - 1)) as usize;
    let children = |x: u32, y: u32| {
        [
            at(2 * x, 2 * y),
            at(2 * x + 1, 2 * y),
            at(2 * x, 2 * y + 1),
            at(2 * x + 1, 2 * y + 1),
        ]
    };
    let n = (size * size) as usize;
    let mut color_height = Vec::with_capacity(n);
    let mut blade = Vec::with_capacity(n);
    match mode {
        Mipmaps::Box => {
            for y in 0..size {
                for x in 0..size {
                    let children = children(x, y);
                    // Colour averaged in linear light; height and attributes as stored.
                    let mean = |f: &dyn Fn(usize) -> f32| -> f32 {
                        children.iter().map(|&c| f(c)).sum::<f32>() * 0.25
                    };
                    let rgb =
                        |k: usize| srgb_encode(mean(&|c| srgb_decode(fine.color_height[c][k])));
                    let raw =
                        |k: usize| mean(&|c| f32::from(fine.color_height[c][k])).round() as u8;
                    let attr = |k: usize| mean(&|c| f32::from(fine.blade[c][k])).round() as u8;
                    color_height.push([rgb(0), rgb(1), rgb(2), raw(3)]);
                    blade.push([attr(0), attr(1)]);
                }
            }
        }
        Mipmaps::Custom | Mipmaps::None => {
            let salt = seed ^ 0x4D49_5053;
            let is_blade = |c: usize| fine.color_height[c][3] > 0;
            let blade_children =
                |x: u32, y: u32| children(x, y).into_iter().filter(|&c| is_blade(c)).count();
            // The coarse texels with the most blade children become blade texels, ties in a
            // seeded order, as many as there are heights to hand out.
            let mut order: Vec<(u32, u32)> = (0..size)
                .flat_map(|y| (0..size).map(move |x| (x, y)))
                .collect();
            order.sort_by_cached_key(|&(x, y)| {
                (
                    std::cmp::Reverse(blade_children(x, y)),
                    hash(salt, &[level, i64::from(x), i64::from(y), 1]),
                )
            });
            let mut chosen = vec![false; n];
            for &(x, y) in order.iter().take(heights.len()) {
                chosen[(y * size + x) as usize] = blade_children(x, y) > 0;
            }
            let mut picked = Vec::with_capacity(n);
            for y in 0..size {
                for x in 0..size {
                    let children = children(x, y);
                    // One child of the wanted kind, picked by a seeded hash (any child if the
                    // texel has none of that kind).
                    let wanted = chosen[(y * size + x) as usize];
                    let pool: Vec<usize> = children
                        .into_iter()
                        .filter(|&c| is_blade(c) == wanted)
                        .collect();
                    let pool = if pool.is_empty() {
                        children.to_vec()
                    } else {
                        pool
                    };
                    let pick =
                        hash(salt, &[level, i64::from(x), i64::from(y)]) as usize % pool.len();
                    let c = pool[pick];
                    picked.push(c);
                    color_height.push(fine.color_height[c]);
                    blade.push(fine.blade[c]);
                }
            }
            // The blade texels take the level's heights, tallest to the texel whose picked
            // child is tallest, so every shell keeps the base level's coverage.
            let mut ranked: Vec<usize> = (0..n)
                .filter(|&i| color_height[i][3] > 0 && chosen[i])
                .collect();
            ranked.sort_by_cached_key(|&i| {
                (
                    std::cmp::Reverse(fine.color_height[picked[i]][3]),
                    hash(salt, &[level, i as i64, 2]),
                )
            });
            for (&i, &h) in ranked.iter().zip(heights) {
                color_height[i][3] = h;
            }
        }
    }
    Level {
        size,
        color_height,
        blade,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> TextureSpec {
        TextureSpec {
            size: 256,
            tile_size: 2.0,
            density: 60.0,
            height: [0.46, 1.0],
            height_skew: 1.0,
            width: [0.025, 0.045],
            aspect: 0.5,
            color_tip: [0.30, 0.45, 0.10],
            color_variation: 0.25,
            seed: 7,
        }
    }

    #[test]
    fn texture_is_seeded_and_holds_blades_on_bare_ground() {
        let a = GrassTexture::new(&spec(), Mipmaps::Custom);
        let b = GrassTexture::new(&spec(), Mipmaps::Custom);
        assert_eq!(a.levels, b.levels);
        let c = GrassTexture::new(&TextureSpec { seed: 8, ..spec() }, Mipmaps::Custom);
        assert_ne!(a.levels[0], c.levels[0]);
        assert_eq!(a.levels.len(), 9);
        assert_eq!(GrassTexture::new(&spec(), Mipmaps::None).levels.len(), 1);
        // 2 m tile at 60 blades/m²: 240 blades on 16 x 16 cells.
        assert_eq!(a.blades.len(), 240);
        let base = &a.levels[0];
        // Some ground, some blades, and the tallest blades reach near the top.
        let ground = 1.0 - base.coverage(1.0 / 255.0);
        assert!((0.5..0.99).contains(&ground), "ground {ground}");
        assert!(base.coverage(0.9) > 0.0);
        assert_eq!(base.coverage(1.01), 0.0);
    }

    #[test]
    fn density_and_height_skew_are_honoured() {
        let dense = GrassTexture::new(
            &TextureSpec {
                density: 240.0,
                ..spec()
            },
            Mipmaps::None,
        );
        assert_eq!(dense.blades.len(), 960);
        let sparse = GrassTexture::new(&spec(), Mipmaps::None);
        assert!(dense.levels[0].coverage(0.1) > 2.5 * sparse.levels[0].coverage(0.1));
        let short = GrassTexture::new(
            &TextureSpec {
                height_skew: 4.0,
                ..spec()
            },
            Mipmaps::None,
        );
        assert!(short.levels[0].coverage(0.7) < 0.6 * sparse.levels[0].coverage(0.7));
    }

    #[test]
    fn a_tile_holds_its_density_times_its_area_and_none_at_density_zero() {
        // 2 m tiles: a square lattice alone (round(2·√d)² blades) would give 36, 81 and 196
        // blades at 8, 20 and 50 blades/m² (+12.5 %, +1.3 %, −2 %); the tile holds 32, 80
        // and 200, every blade in its own cell, all distinct.
        for (density, blades) in [(8.0, 32u32), (16.0, 64), (20.0, 80), (50.0, 200), (0.1, 0)] {
            let t = GrassTexture::new(
                &TextureSpec {
                    density,
                    size: 128,
                    ..spec()
                },
                Mipmaps::None,
            );
            assert_eq!(t.blades.len(), blades as usize, "{density} blades/m²");
            let cells = lattice_side(blades) as f32;
            let mut seen = std::collections::BTreeSet::new();
            for b in &t.blades {
                assert!(b.uv.cmpge(Vec2::ZERO).all() && b.uv.cmplt(Vec2::ONE).all());
                let cell = (b.uv * cells).floor();
                assert!(
                    seen.insert((cell.x as i64, cell.y as i64)),
                    "two blades in {cell}"
                );
            }
        }
        let bare = GrassTexture::new(
            &TextureSpec {
                density: 0.0,
                ..spec()
            },
            Mipmaps::Custom,
        );
        assert!(bare.blades.is_empty());
        assert!(bare.levels.iter().all(|l| l.coverage(1.0 / 255.0) == 0.0));
    }

    #[test]
    fn custom_levels_keep_every_shells_coverage_to_half_a_texel() {
        // A sparse tile (32 blades, 8 blades/m² on 2 m) and a dense one: at every level and
        // for every shell of 16, the level's texels at or above the shell's height are the
        // base level's share of them to half a texel (a hash pick per texel kept that only in
        // expectation: the 8 blades/m² lawn of `tests/scenes/counts.toml`, seen from 25 m,
        // showed no grass at all).
        for density in [8.0, 60.0] {
            let t = GrassTexture::new(
                &TextureSpec {
                    size: 512,
                    density,
                    ..spec()
                },
                Mipmaps::Custom,
            );
            for level in &t.levels[1..] {
                let texels = f64::from(level.size).powi(2);
                for k in 0..16 {
                    let h = k as f32 / 16.0;
                    let want = t.levels[0].coverage(h) * texels;
                    let got = level.coverage(h) * texels;
                    assert!(
                        (got - want).abs() <= 0.5 + 1e-9,
                        "{density}/m², level of {} texels, shell {k}: {got} blade texels, base share {want:.2}",
                        level.size
                    );
                }
            }
        }
    }

    #[test]
    fn custom_mips_keep_more_alpha_coverage_far_away_than_box_mips() {
        // 512 texels over 2 m at 200 blades/m²; level 4 has 32x32 texels of 6.25 cm, wider
        // than any blade. Measured coverage at shells 4 and 8 of 16 (base / custom / box):
        // 0.055 / 0.066 / 0.000 and 0.021 / 0.023 / 0.000 (800 blades a tile; with the
        // earlier 28 x 28 = 784: 0.054 / 0.061 / 0.000 and 0.021 / 0.017 / 0.000).
        let spec = TextureSpec {
            size: 512,
            density: 200.0,
            ..spec()
        };
        let custom = GrassTexture::new(&spec, Mipmaps::Custom);
        let boxed = GrassTexture::new(&spec, Mipmaps::Box);
        let far = 4;
        for shell in [4u32, 8] {
            let t = shell as f32 / 16.0;
            let base = custom.levels[0].coverage(t);
            let c = custom.levels[far].coverage(t);
            let b = boxed.levels[far].coverage(t);
            assert!(c > b, "shell {shell}: custom {c} <= box {b}");
            assert!(
                (c - base).abs() < 0.4 * base,
                "shell {shell}: custom {c} vs base {base}"
            );
        }
        // Box averaging turns blades into felt: the upper shells lose every blade.
        assert_eq!(boxed.levels[far].coverage(0.5), 0.0);
        // Over all shells of a 16-shell stack, custom stays closer to the base level.
        let error = |t: &GrassTexture| -> f64 {
            (1..16)
                .map(|k| {
                    (t.levels[far].coverage(k as f32 / 16.0)
                        - t.levels[0].coverage(k as f32 / 16.0))
                    .abs()
                })
                .sum()
        };
        assert!(
            error(&custom) < 0.5 * error(&boxed),
            "{} vs {}",
            error(&custom),
            error(&boxed)
        );
    }
}
