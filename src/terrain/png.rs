//! Loading heightmaps, density maps and covering maps from grayscale PNGs.

use std::path::Path;

use super::Grid;
use crate::{Error, Result};

/// Largest map side accepted.
pub const MAX_MAP_SIDE: u32 = 8192;

/// Loads an 8- or 16-bit grayscale PNG as values in `[0, 1]`.
pub fn load_scalar(path: &Path) -> Result<Grid<f32>> {
    let img = open(path)?;
    let (w, h) = (img.width(), img.height());
    let data: Vec<f32> = match img {
        image::DynamicImage::ImageLuma8(g) => g
            .into_raw()
            .into_iter()
            .map(|v| f32::from(v) / 255.0)
            .collect(),
        image::DynamicImage::ImageLuma16(g) => g
            .into_raw()
            .into_iter()
            .map(|v| f32::from(v) / 65535.0)
            .collect(),
        other => return Err(not_gray(path, &other)),
    };
    grid(path, w, h, data)
}

/// Loads an 8-bit grayscale PNG of covering IDs, rejecting values other than the four IDs.
pub fn load_covering(path: &Path) -> Result<Grid<u8>> {
    let img = open(path)?;
    let (w, h) = (img.width(), img.height());
    let image::DynamicImage::ImageLuma8(g) = img else {
        return Err(Error::InvalidFile {
            path: path.to_owned(),
            message: format!(
                "a covering map must be an 8-bit grayscale PNG, this one is {:?}; save it as 8-bit grayscale",
                img.color()
            ),
        });
    };
    let data = g.into_raw();
    if let Some((k, v)) = data
        .iter()
        .enumerate()
        .find(|(_, v)| !super::covering::is_valid(**v))
    {
        return Err(Error::InvalidFile {
            path: path.to_owned(),
            message: format!(
                "pixel ({}, {}) has covering ID {v}; valid IDs are 0 (nothing), 253 (tree), 254 (stone), 255 (grass)",
                k % w as usize,
                k / w as usize
            ),
        });
    }
    grid(path, w, h, data)
}

fn open(path: &Path) -> Result<image::DynamicImage> {
    let bytes = std::fs::read(path).map_err(|e| Error::io("cannot read map", path, e))?;
    let img =
        image::load_from_memory_with_format(&bytes, image::ImageFormat::Png).map_err(|e| {
            Error::InvalidFile {
                path: path.to_owned(),
                message: format!("not a readable PNG ({e}); maps must be PNG files"),
            }
        })?;
    let (w, h) = (img.width(), img.height());
    if w < 2 || h < 2 || w > MAX_MAP_SIDE || h > MAX_MAP_SIDE {
        return Err(Error::InvalidFile {
            path: path.to_owned(),
            message: format!("map is {w}x{h}; each side must be 2..={MAX_MAP_SIDE} pixels"),
        });
    }
    Ok(img)
}

fn not_gray(path: &Path, img: &image::DynamicImage) -> Error {
    Error::InvalidFile {
        path: path.to_owned(),
        message: format!(
            "expected an 8- or 16-bit grayscale PNG, found {:?}; convert it to grayscale (e.g. `convert in.png -colorspace Gray out.png`)",
            img.color()
        ),
    }
}

fn grid<T: Copy>(path: &Path, w: u32, h: u32, data: Vec<T>) -> Result<Grid<T>> {
    Grid::from_vec(w as usize, h as usize, data).ok_or_else(|| Error::InvalidFile {
        path: path.to_owned(),
        message: "decoded pixel count does not match the image size".into(),
    })
}
