//! The wind field baked into a texture over the terrain, once per frame, for the GPU.

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
        let points = (0..height)
            .flat_map(|j| (0..width).map(move |i| (i, j)))
            .map(|(i, j)| {
                let uv = Vec2::new(
                    i as f32 / (width - 1) as f32,
                    j as f32 / (height - 1) as f32,
                );
                let xz = terrain.min_corner() + uv * terrain.size();
                terrain.point_at(xz) + Vec3::Y * SAMPLE_HEIGHT
            })
            .collect::<Vec<_>>();
        Self {
            view: texture.create_view(&Default::default()),
            texture,
            width,
            height,
            texels: vec![[0.0; 4]; points.len()],
            points,
        }
    }

    /// Samples `field` at every texel (CPU). `w` of each texel holds the speed.
    pub fn bake(&mut self, field: &dyn WindField, time: f32) {
        for (texel, p) in self.texels.iter_mut().zip(&self.points) {
            let v = field.velocity(*p, time);
            *texel = [v.x, v.y, v.z, v.length()];
        }
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
