//! Scenes: everything shared by the techniques being compared. A scene file (TOML) names the
//! terrain, the grass, the camera path, the wind, the lights, the sky, the seed and the
//! resolution; the same scene and seed give the same frames.

mod background;
mod gpu;
mod ground;
mod lighting;
pub mod props;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

pub use crate::object::ObjectConfig;
pub use background::Background;
pub use gpu::SceneGpu;
pub use ground::{GroundDraws, GroundGpu};
pub use lighting::{LightKey, LightState, LightsConfig, PointLight, SkyConfig};

use crate::camera::{Camera, CameraConfig};
use crate::grass::{BladeField, GrassConfig};
use crate::params::check;
use crate::target::Size;
use crate::terrain::{Terrain, TerrainConfig};
use crate::wind::{self, WindConfig, WindField};
use crate::{Error, Result};

/// A scene file.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SceneConfig {
    /// Short name, used for result folders.
    pub name: String,
    /// One line saying what the scene is for.
    #[serde(default)]
    pub description: String,
    /// Seed for everything random in the scene.
    #[serde(default)]
    pub seed: u64,
    /// Default resolution `[width, height]`.
    #[serde(default = "default_resolution")]
    pub resolution: [u32; 2],
    /// Frames per second of scene time.
    #[serde(default = "default_fps")]
    pub fps: f32,
    /// The ground.
    pub terrain: TerrainConfig,
    /// The grass population.
    #[serde(default)]
    pub grass: GrassConfig,
    /// The camera and its path.
    pub camera: CameraConfig,
    /// The wind model.
    #[serde(default)]
    pub wind: WindConfig,
    /// Sun and ambient light.
    #[serde(default)]
    pub lights: LightsConfig,
    /// Sky, ground colour and fog.
    #[serde(default)]
    pub sky: SkyConfig,
    /// A moving object over the grass, if any: blasts of wind follow it, techniques may react
    /// to it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub object: Option<ObjectConfig>,
    /// Per-technique parameter overrides: `[techniques.<id>]`.
    #[serde(default)]
    pub techniques: toml::Table,
}

fn default_resolution() -> [u32; 2] {
    [640, 360]
}

fn default_fps() -> f32 {
    30.0
}

/// A loaded scene: its file plus the terrain and blade field built from it.
#[derive(Clone, Debug)]
pub struct Scene {
    /// What the file said.
    pub config: SceneConfig,
    /// The ground.
    pub terrain: Terrain,
    /// The grass population.
    pub blades: BladeField,
    /// Folder relative paths in the file are resolved against.
    pub base_dir: PathBuf,
}

impl Scene {
    /// Parses and builds a scene from TOML text; `origin` names the file in messages and its
    /// folder resolves relative map paths.
    pub fn from_toml(text: &str, origin: &Path) -> Result<Self> {
        let config: SceneConfig = toml::from_str(text).map_err(|e| Error::InvalidFile {
            path: origin.to_owned(),
            message: format!("not a valid scene file: {e}"),
        })?;
        let base = origin.parent().map(Path::to_owned).unwrap_or_default();
        Self::from_config(config, base).map_err(|e| match e {
            Error::InvalidParameter { .. } | Error::UnknownName { .. } => Error::InvalidFile {
                path: origin.to_owned(),
                message: e.to_string(),
            },
            e => e,
        })
    }

    /// Reads and builds a scene file.
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::io("cannot read scene file", path, e))?;
        Self::from_toml(&text, path)
    }

    /// Builds a scene from a parsed file (tests edit configs this way).
    pub fn from_config(config: SceneConfig, base_dir: PathBuf) -> Result<Self> {
        check("fps", config.fps, 1.0..=10_000.0)?;
        Size::new(config.resolution[0], config.resolution[1])?;
        config.camera.validate()?;
        config.wind.validate()?;
        config.lights.validate()?;
        config.sky.validate()?;
        if let Some(o) = &config.object {
            o.validate()?;
        }
        let terrain = Terrain::build(&config.terrain, config.seed, &base_dir)?;
        config.grass.validate(terrain.size().x * terrain.size().y)?;
        for (id, value) in &config.techniques {
            if !value.is_table() {
                return Err(Error::param(
                    format!("techniques.{id}"),
                    value,
                    "a table of parameters, e.g. [techniques.reference]",
                ));
            }
        }
        let blades = BladeField::new(config.grass.clone(), config.seed);
        Ok(Self {
            config,
            terrain,
            blades,
            base_dir,
        })
    }

    /// The scene's name.
    pub fn name(&self) -> &str {
        &self.config.name
    }

    /// The scene's default resolution.
    pub fn resolution(&self) -> Size {
        Size {
            width: self.config.resolution[0],
            height: self.config.resolution[1],
        }
    }

    /// Scene time of a frame, s.
    pub fn time_of(&self, frame: u64) -> f32 {
        frame as f32 / self.config.fps
    }

    /// Time between frames, s.
    pub fn dt(&self) -> f32 {
        1.0 / self.config.fps
    }

    /// The camera at a frame.
    pub fn camera_at(&self, frame: u64, size: Size) -> Camera {
        self.config
            .camera
            .camera_at(self.time_of(frame), &self.terrain, size.aspect())
    }

    /// A fresh wind field at time 0.
    pub fn wind(&self) -> Result<Box<dyn WindField>> {
        wind::build(
            &self.config.wind,
            self.config.seed,
            &self.terrain,
            self.config.object.as_ref(),
        )
    }

    /// The scene file's overrides for technique `id` (empty when none).
    pub fn technique_overrides(&self, id: &str) -> toml::Table {
        self.config
            .techniques
            .get(id)
            .and_then(|v| v.as_table())
            .cloned()
            .unwrap_or_default()
    }

    /// The parameter overrides technique `id` runs with on this scene: the scene file's
    /// `[techniques.<id>]`, overlaid with `overrides` (from a sweep grid or the command line).
    pub fn technique_params(&self, id: &str, overrides: &toml::Table) -> toml::Table {
        crate::technique::overlay(&self.technique_overrides(id), overrides)
    }
}
