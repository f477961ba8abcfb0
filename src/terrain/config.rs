//! How a scene file describes its terrain.

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

/// `[terrain]` in a scene file.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TerrainConfig {
    /// Extent in metres along x and z; the terrain is centred on the origin.
    pub size: [f32; 2],
    /// Height in metres of a heightmap value of 1 (white).
    #[serde(default = "default_max_height")]
    pub max_height: f32,
    /// Samples per metre for procedural maps (capped at 1024 samples a side).
    #[serde(default = "default_samples_per_metre")]
    pub samples_per_metre: f32,
    /// The heightmap.
    #[serde(default)]
    pub height: MapSource,
    /// The density map (Boulanger Sec. 3.4): 0 = no grass, 1 = full density.
    #[serde(default = "MapSource::one")]
    pub density: MapSource,
    /// The covering map (Zhang Sec. 5.5.2).
    #[serde(default)]
    pub covering: CoveringSource,
}

fn default_max_height() -> f32 {
    1.0
}

fn default_samples_per_metre() -> f32 {
    1.0
}

/// Where a scalar map (height or density) comes from.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum MapSource {
    /// The same value everywhere, in `[0, 1]`.
    Constant {
        /// The value.
        value: f32,
    },
    /// Seeded fractal value noise.
    Procedural {
        /// Features per metre of the lowest octave (e.g. 0.03 = hills 33 m apart).
        frequency: f32,
        /// Number of octaves.
        #[serde(default = "default_octaves")]
        octaves: u32,
        /// Output range: noise in `[0, 1]` is mapped linearly onto `[min, max]`.
        #[serde(default = "default_range")]
        range: [f32; 2],
        /// Contrast: values are raised to this power before mapping (1 = unchanged).
        #[serde(default = "default_one")]
        power: f32,
    },
    /// An 8- or 16-bit grayscale PNG, relative to the scene file. Row 0 is at -z.
    Png {
        /// Path to the PNG.
        path: PathBuf,
    },
}

impl Default for MapSource {
    fn default() -> Self {
        Self::Constant { value: 0.0 }
    }
}

impl MapSource {
    /// A constant 1 (used as the default density).
    pub fn one() -> Self {
        Self::Constant { value: 1.0 }
    }
}

fn default_octaves() -> u32 {
    4
}

fn default_range() -> [f32; 2] {
    [0.0, 1.0]
}

fn default_one() -> f32 {
    1.0
}

/// Where the covering map (what grows where) comes from.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum CoveringSource {
    /// Grass everywhere.
    #[default]
    Grass,
    /// Seeded: gaps (bare ground) where low-frequency noise is under `gaps`, and isolated
    /// trees and stones with the given probabilities per map sample.
    Procedural {
        /// Fraction of the terrain left bare, `[0, 1)`.
        gaps: f32,
        /// Probability of a tree per map sample.
        #[serde(default)]
        trees: f32,
        /// Probability of a stone per map sample.
        #[serde(default)]
        stones: f32,
        /// Features per metre of the gap noise.
        #[serde(default = "default_gap_frequency")]
        frequency: f32,
    },
    /// An 8-bit grayscale PNG with the values 0, 253, 254, 255 only.
    Png {
        /// Path to the PNG.
        path: PathBuf,
    },
}

fn default_gap_frequency() -> f32 {
    0.05
}
