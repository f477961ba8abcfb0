//! The blade texture (Boulanger Sec. 3.2, Fig. 5), generated procedurally instead of scanned:
//! the alpha channel gives the strip its blade shape (parallel edges tapering to a pointed
//! tip), the colour channels modulate the scene's root-to-tip colour (a lighter midrib, faint
//! veins, darker edges, a drier tip).

use grassbench::rng::hash_f32;
use grassbench::wgpu;
use grassbench::wgpu::util::DeviceExt as _;

/// Texture width (across the blade), texels.
pub const WIDTH: u32 = 32;
/// Texture height (root to tip), texels.
pub const HEIGHT: u32 = 128;
/// The blade texture's format.
pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Half-width of the blade shape at relative height `v` (0 root, 1 tip), in texture widths.
pub fn half_width(v: f32) -> f32 {
    // Parallel edges, then a taper to a point over the top 40 %.
    let taper = ((1.0 - v) / 0.4).clamp(0.0, 1.0);
    0.47 * taper.powf(0.7)
}

/// RGBA8 texels of mip level 0, row 0 at the root. Colour is a modulation stored halved
/// (0.5 = unchanged), alpha the shape with a one-texel soft border.
pub fn texels() -> Vec<[u8; 4]> {
    let mut out = Vec::with_capacity((WIDTH * HEIGHT) as usize);
    for y in 0..HEIGHT {
        let v = (y as f32 + 0.5) / HEIGHT as f32;
        for x in 0..WIDTH {
            let u = (x as f32 + 0.5) / WIDTH as f32;
            let across = (u - 0.5).abs();
            let edge = half_width(v) - across;
            let alpha = (edge * WIDTH as f32 + 0.5).clamp(0.0, 1.0);
            let midrib = 0.12 * (-((u - 0.5) / 0.05).powi(2)).exp();
            let veins = 0.05 * (u * std::f32::consts::PI * 12.0).sin();
            let rim = -0.18 * (across / 0.47).powi(4);
            let fleck = 0.06 * (hash_f32(17, &[i64::from(x), i64::from(y / 3)]) - 0.5);
            let k = 1.0 + midrib + veins + rim + fleck;
            // Drier, yellower tip.
            let dry = ((v - 0.8) / 0.2).clamp(0.0, 1.0);
            let rgb = [k * (1.0 + 0.15 * dry), k, k * (1.0 - 0.25 * dry)];
            let q = |c: f32| ((c * 0.5).clamp(0.0, 1.0) * 255.0).round() as u8;
            out.push([q(rgb[0]), q(rgb[1]), q(rgb[2]), q(alpha * 2.0)]);
        }
    }
    out
}

/// Box-filtered mip levels (level 0 first).
pub fn mip_chain(level0: Vec<[u8; 4]>) -> Vec<Vec<[u8; 4]>> {
    let mut levels = vec![level0];
    let (mut w, mut h) = (WIDTH, HEIGHT);
    while w > 1 || h > 1 {
        let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
        let Some(prev) = levels.last() else { break };
        let mut next = Vec::with_capacity((nw * nh) as usize);
        for y in 0..nh {
            for x in 0..nw {
                let mut sum = [0u32; 4];
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let sx = (2 * x + dx).min(w - 1);
                    let sy = (2 * y + dy).min(h - 1);
                    let p = prev[(sy * w + sx) as usize];
                    for c in 0..4 {
                        sum[c] += u32::from(p[c]);
                    }
                }
                next.push(sum.map(|s| ((s + 2) / 4) as u8));
            }
        }
        levels.push(next);
        (w, h) = (nw, nh);
    }
    levels
}

/// GPU memory of the texture, an upper bound: a mip chain holds at most 4/3 of its base.
pub const BYTES_BOUND: u64 = (WIDTH * HEIGHT * 4) as u64 * 4 / 3 + 64;

/// Uploads the texture with its mip chain; returns the view and the bytes held.
pub fn upload(device: &wgpu::Device, queue: &wgpu::Queue) -> (wgpu::TextureView, u64) {
    let levels = mip_chain(texels());
    let data: Vec<u8> = levels
        .iter()
        .flat_map(|l| l.iter().flatten().copied())
        .collect();
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some("boulanger blade texture"),
            size: wgpu::Extent3d {
                width: WIDTH,
                height: HEIGHT,
                depth_or_array_layers: 1,
            },
            mip_level_count: levels.len() as u32,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::MipMajor,
        &data,
    );
    (texture.create_view(&Default::default()), data.len() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_is_a_blade_with_a_pointed_tip() {
        let t = texels();
        let alpha_at = |x: u32, y: u32| t[(y * WIDTH + x) as usize][3];
        let row_cover = |y: u32| (0..WIDTH).filter(|&x| alpha_at(x, y) > 127).count();
        assert!(row_cover(0) >= WIDTH as usize * 8 / 10);
        assert!(row_cover(HEIGHT / 2) >= WIDTH as usize * 8 / 10);
        assert!(row_cover(HEIGHT - 1) <= 2);
        assert!((1..HEIGHT).all(|y| row_cover(y) <= row_cover(y - 1)));
        assert_eq!(alpha_at(0, HEIGHT - 1), 0);
        let levels = mip_chain(t);
        assert_eq!(levels.len(), 8);
        assert_eq!(levels.last().map(Vec::len), Some(1));
    }
}
