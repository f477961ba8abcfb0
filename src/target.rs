//! The offscreen render target: colour (optionally 4x multisampled, then resolved) plus depth,
//! and the read-back of the resolved colour into an [`image::RgbaImage`].
//!
//! A frame is an opaque picture. The target's alpha channel is not part of it: blending and
//! alpha to coverage leave there whatever their alpha factors compute (zhang's Eq. 10 blends
//! alpha like colour; alpha to coverage writes each fragment's alpha to its samples), so the
//! read-back sets alpha to 255 everywhere, as the window shows the frame. Every metric reads
//! the colour channels only.
//!
//! One target type serves the runner, the tests, the sweeps and the UI, so what the UI shows
//! is what the sweeps measure.

use std::path::Path;

use crate::{Error, GpuContext, Result};

/// Colour format of every target: 8-bit sRGB, so shaders write linear light.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// Format of [`RenderTarget::display_view`]: the colour bytes without sRGB decoding.
pub const DISPLAY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// Depth-stencil format of every target. Depth24PlusStencil8 is the one stencil format every
/// backend must support (WebGPU's guarantee); techniques use the stencil for per-frame masks
/// (Boulanger's projected ground shadows, Sec. 3.5), cleared with the depth each frame.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth24PlusStencil8;
/// Largest side accepted, in pixels (wgpu's default `max_texture_dimension_2d`).
pub const MAX_SIDE: u32 = 8192;

/// Width and height in pixels, validated non-zero and at most [`MAX_SIDE`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Size {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Size {
    /// A checked size.
    pub fn new(width: u32, height: u32) -> Result<Self> {
        for (name, v) in [("width", width), ("height", height)] {
            if v == 0 || v > MAX_SIDE {
                return Err(Error::param(
                    format!("resolution.{name}"),
                    v,
                    format!("1..={MAX_SIDE} pixels"),
                ));
            }
        }
        Ok(Self { width, height })
    }

    /// Parses `WxH`, e.g. `640x360`.
    pub fn parse(s: &str) -> Result<Self> {
        let bad = || Error::param("size", s, "WIDTHxHEIGHT, e.g. 640x360");
        let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
        Self::new(
            w.trim().parse().map_err(|_| bad())?,
            h.trim().parse().map_err(|_| bad())?,
        )
    }

    /// Width over height.
    pub fn aspect(self) -> f32 {
        self.width as f32 / self.height as f32
    }

    fn extent(self) -> wgpu::Extent3d {
        wgpu::Extent3d {
            width: self.width,
            height: self.height,
            depth_or_array_layers: 1,
        }
    }
}

impl std::fmt::Display for Size {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}x{}", self.width, self.height)
    }
}

/// Colour + depth attachments. With MSAA, `color` is the 4x texture and `resolve` the
/// single-sample one; without, `color` is rendered to directly and `resolve` is `None`.
pub struct RenderTarget {
    /// Size in pixels.
    pub size: Size,
    /// 1 or 4.
    pub sample_count: u32,
    /// Texture passes render into.
    pub color: wgpu::Texture,
    /// View of `color`.
    pub color_view: wgpu::TextureView,
    /// Single-sample resolve texture when multisampled.
    pub resolve: Option<(wgpu::Texture, wgpu::TextureView)>,
    /// View of the output in `Rgba8Unorm`: the stored sRGB bytes, undecoded, for UIs that
    /// composite in gamma space (egui). On adapters that cannot reinterpret texture formats
    /// (downlevel GL: no `VIEW_FORMATS`) it is the plain sRGB view, and a gamma-space UI shows
    /// the image somewhat darker; readback and PNGs are unaffected.
    pub display_view: wgpu::TextureView,
    /// Depth texture.
    pub depth: wgpu::Texture,
    /// View of `depth`.
    pub depth_view: wgpu::TextureView,
}

impl RenderTarget {
    /// Creates a target; `msaa` asks for 4 samples.
    pub fn new(gpu: &GpuContext, size: Size, msaa: bool) -> Result<Self> {
        let sample_count = if msaa { 4 } else { 1 };
        let limit = gpu.device.limits().max_texture_dimension_2d;
        if size.width > limit || size.height > limit {
            return Err(Error::param(
                "size",
                size,
                format!("at most {limit} pixels a side on this adapter"),
            ));
        }
        let reinterpret = gpu
            .adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::VIEW_FORMATS);
        gpu.scoped("creating the render target", || {
            let texture = |label, format, samples, usage| {
                let single = reinterpret && samples == 1 && format == COLOR_FORMAT;
                gpu.device.create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: size.extent(),
                    mip_level_count: 1,
                    sample_count: samples,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage,
                    view_formats: if single { &[DISPLAY_FORMAT] } else { &[] },
                })
            };
            let single = wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING;
            let color = texture(
                "target colour",
                COLOR_FORMAT,
                sample_count,
                if msaa {
                    wgpu::TextureUsages::RENDER_ATTACHMENT
                } else {
                    single
                },
            );
            let resolve = msaa.then(|| {
                let t = texture("target resolve", COLOR_FORMAT, 1, single);
                let v = t.create_view(&Default::default());
                (t, v)
            });
            let depth = texture(
                "target depth",
                DEPTH_FORMAT,
                sample_count,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            );
            let output = resolve.as_ref().map_or(&color, |(t, _)| t);
            let display_view = output.create_view(&wgpu::TextureViewDescriptor {
                label: Some("target display"),
                format: reinterpret.then_some(DISPLAY_FORMAT),
                ..Default::default()
            });
            Self {
                size,
                sample_count,
                display_view,
                color_view: color.create_view(&Default::default()),
                color,
                resolve,
                depth_view: depth.create_view(&Default::default()),
                depth,
            }
        })
    }

    /// GPU memory of the colour, resolve and depth textures.
    pub fn estimate(&self) -> crate::gpu::GpuEstimate {
        let pixels = u64::from(self.size.width) * u64::from(self.size.height);
        let samples = u64::from(self.sample_count);
        let resolve = if self.resolve.is_some() { 4 } else { 0 };
        crate::gpu::GpuEstimate::textures(pixels * (samples * (4 + 4) + resolve))
    }

    /// The single-sample texture holding the final image.
    pub fn output(&self) -> &wgpu::Texture {
        self.resolve.as_ref().map_or(&self.color, |(t, _)| t)
    }

    /// View of [`Self::output`] (what the UI displays).
    pub fn output_view(&self) -> &wgpu::TextureView {
        self.resolve.as_ref().map_or(&self.color_view, |(_, v)| v)
    }

    /// Colour attachment for a pass: loads or clears, resolves when multisampled.
    pub fn color_attachment(
        &self,
        clear: Option<wgpu::Color>,
    ) -> wgpu::RenderPassColorAttachment<'_> {
        wgpu::RenderPassColorAttachment {
            view: &self.color_view,
            depth_slice: None,
            resolve_target: self.resolve.as_ref().map(|(_, v)| v),
            ops: wgpu::Operations {
                load: clear.map_or(wgpu::LoadOp::Load, wgpu::LoadOp::Clear),
                store: wgpu::StoreOp::Store,
            },
        }
    }

    /// Depth-stencil attachment for a pass: loads both, or clears depth to 1.0 (far) and the
    /// stencil to 0.
    pub fn depth_attachment(&self, clear: bool) -> wgpu::RenderPassDepthStencilAttachment<'_> {
        wgpu::RenderPassDepthStencilAttachment {
            view: &self.depth_view,
            depth_ops: Some(wgpu::Operations {
                load: if clear {
                    wgpu::LoadOp::Clear(1.0)
                } else {
                    wgpu::LoadOp::Load
                },
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: Some(wgpu::Operations {
                load: if clear {
                    wgpu::LoadOp::Clear(0)
                } else {
                    wgpu::LoadOp::Load
                },
                store: wgpu::StoreOp::Store,
            }),
        }
    }

    /// Records a copy of the output into a new read-back buffer.
    pub fn encode_readback(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Readback {
        let padded = padded_row_bytes(self.size.width);
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("target readback"),
            size: u64::from(padded) * u64::from(self.size.height),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        encoder.copy_texture_to_buffer(
            self.output().as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: None,
                },
            },
            self.size.extent(),
        );
        Readback {
            buffer,
            size: self.size,
        }
    }

    /// Copies the output to the CPU (submits and waits).
    pub fn read_image(&self, gpu: &GpuContext) -> Result<image::RgbaImage> {
        let readback = gpu.scoped("reading back the render target", || {
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            let readback = self.encode_readback(gpu, &mut encoder);
            gpu.queue.submit([encoder.finish()]);
            readback
        })?;
        readback.finish(gpu)
    }
}

/// A pending copy of a target's output; [`Readback::finish`] maps it after submission.
pub struct Readback {
    buffer: wgpu::Buffer,
    size: Size,
}

impl Readback {
    /// Waits for the copy and returns the image, opaque (alpha 255).
    pub fn finish(self, gpu: &GpuContext) -> Result<image::RgbaImage> {
        let slice = self.buffer.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        gpu.wait_idle("reading back the render target")?;
        let lost = |message: String| Error::DeviceLost {
            during: "reading back the render target".into(),
            message,
        };
        rx.recv()
            .map_err(|e| lost(e.to_string()))?
            .map_err(|e| lost(e.to_string()))?;
        let data = slice.get_mapped_range().map_err(|e| lost(e.to_string()))?;
        let padded = padded_row_bytes(self.size.width) as usize;
        let row = self.size.width as usize * 4;
        let mut pixels = Vec::with_capacity(row * self.size.height as usize);
        for chunk in data.chunks(padded) {
            pixels.extend_from_slice(&chunk[..row]);
        }
        // The picture is opaque (see the module's documentation).
        for alpha in pixels.iter_mut().skip(3).step_by(4) {
            *alpha = u8::MAX;
        }
        drop(data);
        self.buffer.unmap();
        image::RgbaImage::from_raw(self.size.width, self.size.height, pixels).ok_or_else(|| {
            Error::Image {
                path: "render target".into(),
                message: "read-back size does not match the target".into(),
            }
        })
    }
}

/// Bytes per row padded to wgpu's copy alignment (256).
fn padded_row_bytes(width: u32) -> u32 {
    let unpadded = width * 4;
    unpadded.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
}

/// Writes a PNG atomically (temporary file, then rename), creating parent folders.
pub fn save_png(image: &image::RgbaImage, path: &Path) -> Result<()> {
    crate::files::write_atomic(path, |file| {
        image::codecs::png::PngEncoder::new(file)
            .write_image(
                image.as_raw(),
                image.width(),
                image.height(),
                image::ExtendedColorType::Rgba8,
            )
            .map_err(std::io::Error::other)
    })
}

use image::ImageEncoder as _;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn size_parsing_and_limits() {
        assert_eq!(
            Size::parse("640x360").ok(),
            Some(Size {
                width: 640,
                height: 360
            })
        );
        assert!(Size::parse("640").is_err());
        assert!(Size::parse("0x10").is_err());
        assert!(Size::parse("100000x100000").is_err());
        assert!(Size::parse("axb").is_err());
    }

    #[test]
    fn rows_are_padded_to_256_bytes() {
        assert_eq!(padded_row_bytes(64), 256);
        assert_eq!(padded_row_bytes(65), 512);
        assert_eq!(padded_row_bytes(320), 1280);
    }
}
