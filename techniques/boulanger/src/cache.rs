//! The BTF disk cache (Boulanger Sec. 3.3: "this pre-processing step has to be done only once
//! since the resulting slices data are stored on the hard drive").
//!
//! A baked set of layers ([`crate::btf::BtfTextures`], every mip level of its three textures)
//! is stored in one file named by a 64-bit key: an FNV-1a hash of everything the bake reads
//! ([`bake_key`]: the format version, both shaders' source, the blade texture, the patch's
//! blades, the bake's uniforms and the texture sizes) and of the adapter that renders it
//! ([`for_adapter`]: backend, name, driver: a bake is a render, and GL's llvmpipe bakes these
//! layers differently from Vulkan's lavapipe on the same machine), so any parameter, code or
//! adapter change that alters the bake picks another file. The folder is the `btf_cache` parameter: empty (the
//! default) means `$XDG_CACHE_HOME/grassbench/boulanger` (else `$HOME/.cache/...`, else the
//! system temporary folder), `off` disables the cache; it is never inside the repository.
//!
//! File layout (little-endian): the magic `GBBTF\x01\0\0`, the key (u64), width, height,
//! layers, levels (u32 each), the payload length (u64), the payload (for each texture, each
//! level, all layers' rows without padding) and its FNV-1a hash (u64). A file that is missing,
//! short, of another key or size, or whose hash does not match is baked again and rewritten;
//! a failure to write is reported, not fatal.

use std::path::{Path, PathBuf};

use grassbench::{Error, GpuContext, Result, bytemuck, wgpu};

use crate::btf::{self, BtfTextures};

/// Bumped when the file layout or the meaning of the channels changes.
pub const VERSION: u32 = 1;

const MAGIC: [u8; 8] = *b"GBBTF\x01\0\0";

/// FNV-1a over a sequence of byte strings, each prefixed by its length (so moving bytes from
/// one part to the next changes the hash).
pub fn fnv1a(parts: &[&[u8]]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for b in bytes {
            h ^= u64::from(*b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    for p in parts {
        eat(&(p.len() as u64).to_le_bytes());
        eat(p);
    }
    h
}

/// The size of a set of layers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dims {
    /// Texels across.
    pub width: u32,
    /// Texels down.
    pub height: u32,
    /// Layers.
    pub layers: u32,
}

impl Dims {
    fn levels(&self) -> u32 {
        btf::levels(self.width, self.height)
    }

    fn level_extent(&self, level: u32) -> (u32, u32) {
        ((self.width >> level).max(1), (self.height >> level).max(1))
    }

    /// Payload bytes: 8 bytes a texel, three textures, every level and layer.
    pub fn payload_bytes(&self) -> u64 {
        btf::texture_bytes(self.width, self.height, self.layers)
    }
}

/// The key of one bake: everything it reads. `uniform` is the bake's uniform block with the
/// fields the bake does not read zeroed by the caller, `blades` the patch.
pub fn bake_key(kind: &str, dims: Dims, uniform: &[u8], blades: &[u8]) -> u64 {
    let texture: Vec<[u8; 4]> = crate::texture::texels();
    fnv1a(&[
        &VERSION.to_le_bytes(),
        kind.as_bytes(),
        crate::shader::SHADER.as_bytes(),
        btf::MIP_SHADER.as_bytes(),
        bytemuck::cast_slice(&texture),
        &dims.width.to_le_bytes(),
        &dims.height.to_le_bytes(),
        &dims.layers.to_le_bytes(),
        uniform,
        blades,
    ])
}

/// The key of a bake `key` rendered by `adapter`: a bake is a render, so a file baked by one
/// adapter or backend is never loaded by another (a GL bake loaded by Vulkan once made the
/// meadow's snapshot test fail with FLIP 0.05 on identical code).
pub fn for_adapter(key: u64, adapter: &wgpu::AdapterInfo) -> u64 {
    let who = format!(
        "{:?}|{}|{}|{}|{}|{}",
        adapter.backend,
        adapter.name,
        adapter.vendor,
        adapter.device,
        adapter.driver,
        adapter.driver_info
    );
    fnv1a(&[&key.to_le_bytes(), who.as_bytes()])
}

/// Where cache files go for the `btf_cache` parameter (`None`: disabled).
pub fn folder(setting: &str) -> Option<PathBuf> {
    match setting {
        "off" => None,
        "" => {
            let base = std::env::var_os("XDG_CACHE_HOME")
                .filter(|v| !v.is_empty())
                .map(PathBuf::from)
                .or_else(|| {
                    std::env::var_os("HOME")
                        .filter(|v| !v.is_empty())
                        .map(|h| PathBuf::from(h).join(".cache"))
                })
                .unwrap_or_else(std::env::temp_dir);
            Some(base.join("grassbench").join("boulanger"))
        }
        path => Some(PathBuf::from(path)),
    }
}

/// The file of `key` in `folder`.
pub fn file(folder: &Path, key: u64) -> PathBuf {
    folder.join(format!("btf-{key:016x}.bin"))
}

/// What happened to one set of layers at start-up.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Loaded from the cache file.
    Loaded,
    /// Baked and written to the cache (`Some(reason)` when a file existed but was unusable).
    Baked {
        /// Why an existing file was not used.
        rejected: Option<String>,
        /// Why the new file could not be written, if it could not.
        write_error: Option<String>,
    },
    /// Baked; the cache is off.
    Disabled,
}

/// Reads every level of the three textures back to the CPU (submits and waits).
pub fn read_back(gpu: &GpuContext, btf: &BtfTextures, dims: Dims) -> Result<Vec<u8>> {
    let device = &gpu.device;
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("boulanger BTF read-back"),
    });
    let mut copies = Vec::new();
    for texture in &btf.textures {
        for level in 0..dims.levels() {
            let (w, h) = dims.level_extent(level);
            let row = w * 8;
            let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
                * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("boulanger BTF read-back"),
                size: u64::from(padded) * u64::from(h) * u64::from(dims.layers),
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            // Layer by layer through a one-layer texture: wgpu's GL backend copies an array
            // texture to a buffer as zeros (gfx-rs/wgpu#10015, wgpu 30), which the cache would
            // then serve as a black BTF; a texture-to-texture copy and a 2D texture's read-back
            // work on every backend.
            let scratch = device.create_texture(&wgpu::TextureDescriptor {
                label: Some("boulanger BTF read-back layer"),
                size: wgpu::Extent3d {
                    width: w,
                    height: h,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: btf::FORMAT,
                usage: wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            });
            let extent = wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            };
            for layer in 0..dims.layers {
                encoder.copy_texture_to_texture(
                    wgpu::TexelCopyTextureInfo {
                        texture,
                        mip_level: level,
                        origin: wgpu::Origin3d {
                            x: 0,
                            y: 0,
                            z: layer,
                        },
                        aspect: wgpu::TextureAspect::All,
                    },
                    scratch.as_image_copy(),
                    extent,
                );
                encoder.copy_texture_to_buffer(
                    scratch.as_image_copy(),
                    wgpu::TexelCopyBufferInfo {
                        buffer: &buffer,
                        layout: wgpu::TexelCopyBufferLayout {
                            offset: u64::from(padded) * u64::from(h) * u64::from(layer),
                            bytes_per_row: Some(padded),
                            rows_per_image: Some(h),
                        },
                    },
                    extent,
                );
            }
            copies.push((buffer, row as usize, padded as usize));
        }
    }
    gpu.queue.submit([encoder.finish()]);
    let lost = |message: String| Error::DeviceLost {
        during: "reading back the BTF".into(),
        message,
    };
    let mut out = Vec::with_capacity(dims.payload_bytes() as usize);
    for (buffer, row, padded) in copies {
        let slice = buffer.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        gpu.wait_idle("reading back the BTF")?;
        rx.recv()
            .map_err(|e| lost(e.to_string()))?
            .map_err(|e| lost(e.to_string()))?;
        let data = slice.get_mapped_range().map_err(|e| lost(e.to_string()))?;
        for chunk in data.chunks(padded) {
            out.extend_from_slice(&chunk[..row]);
        }
        drop(data);
        buffer.unmap();
    }
    Ok(out)
}

/// Creates the textures of `dims` from a payload read back by [`read_back`].
pub fn upload(gpu: &GpuContext, dims: Dims, payload: &[u8]) -> Result<BtfTextures> {
    if payload.len() as u64 != dims.payload_bytes() {
        return Err(Error::Technique {
            technique: "boulanger".into(),
            message: "BTF payload of the wrong size".into(),
        });
    }
    let textures = btf::create_textures(&gpu.device, dims.width, dims.height, dims.layers);
    let mut offset = 0usize;
    for texture in &textures {
        for level in 0..dims.levels() {
            let (w, h) = dims.level_extent(level);
            let bytes = (w * 8 * h * dims.layers) as usize;
            gpu.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture,
                    mip_level: level,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                &payload[offset..offset + bytes],
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(w * 8),
                    rows_per_image: Some(h),
                },
                wgpu::Extent3d {
                    width: w,
                    height: h,
                    depth_or_array_layers: dims.layers,
                },
            );
            offset += bytes;
        }
    }
    Ok(btf::wrap(textures, dims.width, dims.height, dims.layers))
}

/// Serialises a payload with its header and hash.
pub fn encode(key: u64, dims: Dims, payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(payload.len() + 48);
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&key.to_le_bytes());
    for v in [dims.width, dims.height, dims.layers, dims.levels()] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(payload);
    out.extend_from_slice(&fnv1a(&[payload]).to_le_bytes());
    out
}

/// The payload of a cache file, or why it cannot be used.
pub fn decode(bytes: &[u8], key: u64, dims: Dims) -> std::result::Result<&[u8], String> {
    let header = 8 + 8 + 16 + 8;
    if bytes.len() < header + 8 {
        return Err("file too short".into());
    }
    if bytes[..8] != MAGIC {
        return Err("not a BTF cache file".into());
    }
    let u64_at = |o: usize| {
        let mut b = [0u8; 8];
        b.copy_from_slice(&bytes[o..o + 8]);
        u64::from_le_bytes(b)
    };
    let u32_at = |o: usize| {
        let mut b = [0u8; 4];
        b.copy_from_slice(&bytes[o..o + 4]);
        u32::from_le_bytes(b)
    };
    if u64_at(8) != key {
        return Err("key mismatch".into());
    }
    let stored = [u32_at(16), u32_at(20), u32_at(24), u32_at(28)];
    if stored != [dims.width, dims.height, dims.layers, dims.levels()] {
        return Err(format!("size mismatch: {stored:?}"));
    }
    let len = u64_at(32);
    if len != dims.payload_bytes() || bytes.len() as u64 != header as u64 + len + 8 {
        return Err("length mismatch".into());
    }
    let payload = &bytes[header..header + len as usize];
    if u64_at(header + len as usize) != fnv1a(&[payload]) {
        return Err("hash mismatch (corrupt file)".into());
    }
    Ok(payload)
}

/// The layers of `key` from the cache in `folder`, or baked by `bake` (and then stored).
pub fn load_or_bake(
    gpu: &GpuContext,
    folder: Option<&Path>,
    key: u64,
    dims: Dims,
    bake: impl FnOnce() -> Result<BtfTextures>,
) -> Result<(BtfTextures, Outcome)> {
    let Some(folder) = folder else {
        return Ok((bake()?, Outcome::Disabled));
    };
    let key = for_adapter(key, &gpu.adapter.get_info());
    let path = file(folder, key);
    let rejected = match std::fs::read(&path) {
        Ok(bytes) => match decode(&bytes, key, dims) {
            Ok(payload) => return Ok((upload(gpu, dims, payload)?, Outcome::Loaded)),
            Err(reason) => Some(reason),
        },
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
        Err(e) => Some(e.to_string()),
    };
    let baked = bake()?;
    let payload = read_back(gpu, &baked, dims)?;
    let write_error = write_atomically(&path, &encode(key, dims, &payload)).err();
    Ok((
        baked,
        Outcome::Baked {
            rejected,
            write_error,
        },
    ))
}

/// Writes through a temporary file and a rename, so a crash never leaves a half file under the
/// final name (a half file would be rejected anyway by its hash).
fn write_atomically(path: &Path, bytes: &[u8]) -> std::result::Result<(), String> {
    let dir = path.parent().ok_or("no parent folder")?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let tmp = path.with_extension(format!("tmp{}", std::process::id()));
    std::fs::write(&tmp, bytes).map_err(|e| format!("{}: {e}", tmp.display()))?;
    std::fs::rename(&tmp, path).map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    const DIMS: Dims = Dims {
        width: 16,
        height: 8,
        layers: 2,
    };

    #[test]
    fn files_round_trip_and_damage_is_detected() {
        let payload: Vec<u8> = (0..DIMS.payload_bytes()).map(|k| (k * 7) as u8).collect();
        let bytes = encode(42, DIMS, &payload);
        assert_eq!(decode(&bytes, 42, DIMS).unwrap(), payload.as_slice());
        assert!(decode(&bytes, 43, DIMS).is_err(), "other key");
        let other = Dims { layers: 3, ..DIMS };
        assert!(decode(&bytes, 42, other).is_err(), "other size");
        assert!(
            decode(&bytes[..bytes.len() - 1], 42, DIMS).is_err(),
            "short"
        );
        assert!(decode(&[], 42, DIMS).is_err(), "empty");
        let mut flipped = bytes.clone();
        flipped[100] ^= 1;
        assert!(decode(&flipped, 42, DIMS).is_err(), "flipped payload bit");
    }

    #[test]
    fn keys_separate_their_parts() {
        assert_ne!(fnv1a(&[b"ab", b"c"]), fnv1a(&[b"a", b"bc"]));
        let k = |kind, dims, u: &[u8], b: &[u8]| bake_key(kind, dims, u, b);
        let base = k("v", DIMS, &[1, 2], &[3]);
        assert_eq!(base, k("v", DIMS, &[1, 2], &[3]));
        assert_ne!(base, k("h", DIMS, &[1, 2], &[3]));
        assert_ne!(base, k("v", Dims { width: 32, ..DIMS }, &[1, 2], &[3]));
        assert_ne!(base, k("v", DIMS, &[1, 3], &[3]));
        assert_ne!(base, k("v", DIMS, &[1, 2], &[4]));
    }

    #[test]
    fn another_adapter_or_backend_picks_another_file() {
        let lavapipe = wgpu::AdapterInfo {
            name: "llvmpipe (LLVM 15.0.6, 256 bits)".into(),
            driver: "llvmpipe".into(),
            driver_info: "Mesa 22.3.6 (LLVM 15.0.6)".into(),
            ..wgpu::AdapterInfo::new(wgpu::DeviceType::Cpu, wgpu::Backend::Vulkan)
        };
        let gl = wgpu::AdapterInfo {
            backend: wgpu::Backend::Gl,
            ..lavapipe.clone()
        };
        let newer = wgpu::AdapterInfo {
            driver_info: "Mesa 24.2.8".into(),
            ..lavapipe.clone()
        };
        assert_eq!(for_adapter(7, &lavapipe), for_adapter(7, &lavapipe));
        assert_ne!(for_adapter(7, &lavapipe), for_adapter(8, &lavapipe));
        assert_ne!(for_adapter(7, &lavapipe), for_adapter(7, &gl));
        assert_ne!(for_adapter(7, &lavapipe), for_adapter(7, &newer));
    }

    #[test]
    fn off_disables_and_a_path_is_taken_as_is() {
        assert_eq!(folder("off"), None);
        assert_eq!(folder("/tmp/x"), Some(PathBuf::from("/tmp/x")));
        let default = folder("").unwrap();
        assert!(default.ends_with("grassbench/boulanger"), "{default:?}");
    }
}
