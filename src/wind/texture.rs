//! The wind field baked into a texture over the terrain, once per frame, for the GPU.
//!
//! The bake is the core's CPU work in every frame of every technique (`wind_ms`), and it grows
//! with the terrain up to the texture's largest size (256 x 256 texels, a 255 m terrain). It
//! samples through [`WindField::velocities`], the models' batched path (one set of per-time
//! constants, a noise lattice cell remembered from texel to texel), in bands of rows spread
//! over the host's cores: the same values, bit for bit, as sampling texel by texel with
//! [`WindField::velocity`] (`bake_matches_single_samples`).

use glam::{Vec2, Vec3};

use super::WindField;
use crate::terrain::Terrain;

/// Height above the ground (m) at which the texture samples the field: mid-blade.
pub const SAMPLE_HEIGHT: f32 = 0.4;

/// Format of the wind texture: a velocity (m/s) in `xyz`.
pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// An `Rgba32Float` texture covering the terrain; texel `(i, j)` holds the velocity (m/s) at
/// the matching ground point, `SAMPLE_HEIGHT` above the ground. Shaders read it with the
/// prelude's `wind_at(xz)` (bilinear).
pub struct WindTexture {
    /// The texture.
    pub texture: wgpu::Texture,
    /// Its view, bound at group 0.
    pub view: wgpu::TextureView,
    width: u32,
    height: u32,
    texels: Vec<[f32; 4]>,
    points: Vec<Vec3>,
    /// The last bake's velocities, before they become texels (kept to spare an allocation a
    /// frame).
    velocities: Vec<Vec3>,
    /// Threads a bake spreads over ([`bake_threads`], asked once: the host's core count comes
    /// from the scheduler and the cgroup files).
    threads: usize,
}

/// Fewest texels one thread of the bake samples: below it a thread costs more to start than
/// it saves (a texel takes tens of nanoseconds; starting a thread, tens of microseconds).
const TEXELS_PER_THREAD: usize = 8192;

/// Most threads the bake spreads over (a 256 x 256 texture in bands of 8 192 texels).
const MAX_BAKE_THREADS: usize = 8;

/// Threads to bake `texels` texels with on this host: one per core, at most
/// [`MAX_BAKE_THREADS`], each with at least [`TEXELS_PER_THREAD`].
fn bake_threads(texels: usize) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get);
    cores
        .min(MAX_BAKE_THREADS)
        .min(texels / TEXELS_PER_THREAD)
        .max(1)
}

/// Samples `field` at `time` at every point of `points` into `texels` (`xyz` the velocity, `w`
/// its length), through `velocities` (as long as `points`), split into `threads` bands of
/// consecutive points sampled at once.
fn sample_texels(
    field: &dyn WindField,
    time: f32,
    points: &[Vec3],
    velocities: &mut [Vec3],
    texels: &mut [[f32; 4]],
    threads: usize,
) {
    let band = points.len().div_ceil(threads.max(1)).max(1);
    let sample = |points: &[Vec3], velocities: &mut [Vec3], texels: &mut [[f32; 4]]| {
        field.velocities(points, time, velocities);
        for (texel, v) in texels.iter_mut().zip(velocities.iter()) {
            *texel = [v.x, v.y, v.z, v.length()];
        }
    };
    let bands = points
        .chunks(band)
        .zip(velocities.chunks_mut(band))
        .zip(texels.chunks_mut(band));
    if threads <= 1 {
        for ((p, v), t) in bands {
            sample(p, v, t);
        }
        return;
    }
    std::thread::scope(|scope| {
        let mut bands = bands;
        // The calling thread takes the first band itself.
        let first = bands.next();
        for ((p, v), t) in bands {
            scope.spawn(move || sample(p, v, t));
        }
        if let Some(((p, v), t)) = first {
            sample(p, v, t);
        }
    });
}

/// The ground points a `width` x `height` wind texture over `terrain` samples, row by row:
/// texel `(i, j)` at the matching ground point, [`SAMPLE_HEIGHT`] above the ground.
fn sample_points(terrain: &Terrain, width: u32, height: u32) -> Vec<Vec3> {
    (0..height)
        .flat_map(|j| (0..width).map(move |i| (i, j)))
        .map(|(i, j)| {
            let uv = Vec2::new(
                i as f32 / (width - 1) as f32,
                j as f32 / (height - 1) as f32,
            );
            let xz = terrain.min_corner() + uv * terrain.size();
            terrain.point_at(xz) + Vec3::Y * SAMPLE_HEIGHT
        })
        .collect()
}

impl WindTexture {
    /// Texels a side for `terrain`: about one per metre, between 16 and 256.
    pub fn resolution_for(terrain: &Terrain) -> (u32, u32) {
        let side = |s: f32| (s.ceil() as u32 + 1).clamp(16, 256);
        (side(terrain.size().x), side(terrain.size().y))
    }

    /// A texture of [`Self::resolution_for`] `terrain`.
    pub fn new(device: &wgpu::Device, terrain: &Terrain) -> Self {
        let (width, height) = Self::resolution_for(terrain);
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("wind"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let points = sample_points(terrain, width, height);
        Self {
            view: texture.create_view(&Default::default()),
            texture,
            width,
            height,
            texels: vec![[0.0; 4]; points.len()],
            velocities: vec![Vec3::ZERO; points.len()],
            threads: bake_threads(points.len()),
            points,
        }
    }

    /// Samples `field` at every texel (CPU), over the host's cores. `w` of each texel holds
    /// the speed.
    pub fn bake(&mut self, field: &dyn WindField, time: f32) {
        sample_texels(
            field,
            time,
            &self.points,
            &mut self.velocities,
            &mut self.texels,
            self.threads,
        );
    }

    /// Uploads the last bake.
    pub fn upload(&self, gpu: &crate::GpuContext) {
        gpu.write_texture(
            self.texture.as_image_copy(),
            bytemuck::cast_slice(&self.texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(self.width * 16),
                rows_per_image: None,
            },
            wgpu::Extent3d {
                width: self.width,
                height: self.height,
                depth_or_array_layers: 1,
            },
        );
    }

    /// Largest speed in the last bake.
    pub fn max_speed(&self) -> f32 {
        self.texels.iter().fold(0.0, |m, t| m.max(t[3]))
    }

    /// Texels along x and z.
    pub fn resolution(&self) -> (u32, u32) {
        (self.width, self.height)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wind::{
        BreezeConfig, FluidConfig, PointSourceConfig, PrimitivesConfig, WindConfig, build,
    };

    /// Every model's bake, in one band or several, is texel for texel what sampling each
    /// point alone gives, bit for bit: spreading the bake over threads cannot change a
    /// picture.
    #[test]
    fn bake_matches_single_samples() -> crate::Result<()> {
        let terrain = Terrain::flat(Vec2::new(60.0, 40.0));
        let (width, height) = WindTexture::resolution_for(&terrain);
        let points = sample_points(&terrain, width, height);
        assert_eq!(points.len(), 61 * 41);
        let configs = [
            WindConfig::Breeze(BreezeConfig::default()),
            WindConfig::PointSource(PointSourceConfig::default()),
            WindConfig::Primitives(PrimitivesConfig::default()),
            WindConfig::Fluid(FluidConfig::default()),
        ];
        for config in &configs {
            let mut field = build(config, 5, &terrain, None)?;
            for frame in 0..4u32 {
                let time = frame as f32 * 0.7 + 0.1;
                field.advance(time, 0.7);
                let single: Vec<[u32; 4]> = points
                    .iter()
                    .map(|p| {
                        let v = field.velocity(*p, time);
                        [v.x, v.y, v.z, v.length()].map(f32::to_bits)
                    })
                    .collect();
                assert!(
                    single.iter().any(|t| t[3] != 0),
                    "{}: no wind at {time} s",
                    field.name()
                );
                for threads in [1, 2, 3, 7] {
                    let mut velocities = vec![Vec3::NAN; points.len()];
                    let mut texels = vec![[f32::NAN; 4]; points.len()];
                    sample_texels(
                        field.as_ref(),
                        time,
                        &points,
                        &mut velocities,
                        &mut texels,
                        threads,
                    );
                    let baked: Vec<[u32; 4]> = texels.iter().map(|t| t.map(f32::to_bits)).collect();
                    assert!(
                        baked == single,
                        "{} at {time} s in {threads} bands: the bake differs from single samples",
                        field.name()
                    );
                }
            }
        }
        Ok(())
    }

    #[test]
    fn threads_follow_the_texels() {
        // A small texture bakes on the calling thread alone.
        assert_eq!(bake_threads(16 * 16), 1);
        assert_eq!(bake_threads(TEXELS_PER_THREAD * 2 - 1), 1);
        // The largest spreads over at most eight, each with its fill of texels.
        let n = bake_threads(256 * 256);
        assert!((1..=MAX_BAKE_THREADS).contains(&n), "{n} threads");
        assert!(n * TEXELS_PER_THREAD <= 256 * 256, "{n} threads");
    }
}
