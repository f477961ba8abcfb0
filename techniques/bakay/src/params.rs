//! The technique's parameters (`[techniques.bakay]` in scene files, `--param` on the command
//! line) and their validation.

use grassbench::Result;
use grassbench::params::{TechniqueParams, check_ranges};
use grassbench::wind::PointSourceConfig;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How the coarser levels of the grass texture are made (Bakay Sec. 5: automatic mipmaps lose
/// the high-frequency blades).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Mipmaps {
    /// Representative blades: each coarse texel is one of its four children, so every level
    /// keeps real blades; as many coarse texels as the base level's coverage asks for are
    /// blade texels, with the base level's height quantiles, so every level keeps every
    /// shell's coverage to half a texel a tile.
    Custom,
    /// The automatic kind: 2x2 box averages of colour, height and blade attributes.
    Box,
    /// The base level only (sharp, aliases at a distance).
    None,
}

/// How a texture lookup picks its mip level.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Lod {
    /// The sampler's isotropic choice, from the footprint's major axis: at grazing angles many
    /// levels too coarse (box mips blur to felt, custom ones to blotches).
    Hardware,
    /// The level matching the footprint's minor axis (the level anisotropic filtering picks),
    /// with a single tap: sharp at grazing angles, at the cost of aliasing along the major axis.
    MinorAxis,
}

/// Where the wind that bends the shells comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum WindSource {
    /// The scene's `WindField`, read per vertex through the prelude's `wind_at`, so bakay runs
    /// in the same wind as every other technique.
    Scene,
    /// The technique's own point source (Bakay Sec. 3), computed per vertex in the shader.
    PointSource,
}

/// Parameters of the shell technique.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// Number of shells `N`, the ground shell included (Bakay Table 2 counts it too).
    #[schemars(range(min = 1, max = 128))]
    pub shells: u32,
    /// Level of detail (a departure: the paper names it future work, Sec. 5): the most pixels
    /// between neighbouring drawn shells at a chunk's nearest depth. Far chunks draw every
    /// second, fourth, … shell down from the top one (each keeping the texels of the shells it
    /// stands for), and none where the whole stack is this many pixels tall or less (the
    /// ground alone). 0 = every shell everywhere (the paper).
    #[schemars(range(min = 0.0, max = 64.0))]
    pub shell_lod_pixels: f32,
    /// Texels along each side of the grass texture (a power of two).
    #[schemars(range(min = 16, max = 4096))]
    pub texture_size: u32,
    /// World size of one texture tile, m.
    #[schemars(range(min = 0.1, max = 64.0))]
    pub tile_size: f32,
    /// Blades in the texture per m², relative to the scene's `grass.density`: 1 (the default)
    /// is the scene's population, which every technique shows. Anything else is a departure
    /// from the scene, for looks only: shells show a blade only where a shell cuts it, so at
    /// a walker's grazing view the scene's own density looks sparser than blade geometry
    /// (Sec. 5: "making the grass more dense on textures"). Before issue 19 the default was 9,
    /// measured to give `reference`'s grass coverage on the meadow (frame 3, 640x360: coverage
    /// 0.344 at 6, 0.432 at 8, 0.458 at 9, 0.484 at 10, 0.531 at 12; reference 0.463); the
    /// blade counts then reported 9 times the scene's blades.
    #[schemars(range(min = 0.01, max = 16.0))]
    pub density_scale: f32,
    /// Blade heights are `min + (max − min)·u^height_skew` for uniform `u` over the scene's
    /// height range: 1 = uniform (as the scene's blade field), > 1 = mostly short blades.
    #[schemars(range(min = 0.1, max = 10.0))]
    pub height_skew: f32,
    /// Thickness of a blade's cross-section relative to its width (1 = round stalks).
    #[schemars(range(min = 0.05, max = 1.0))]
    pub blade_aspect: f32,
    /// How the texture's mip levels are made: `custom`, `box` or `none`.
    pub mipmaps: Mipmaps,
    /// How lookups pick a mip level: `minor_axis` or `hardware`.
    pub lod: Lod,
    /// Anisotropic filtering clamp (1 = off; 2, 4, 8 or 16). On lavapipe 16x costs 18x the
    /// frame (meadow 640x360: 3.8 s against 0.21 s), hence `lod = "minor_axis"`.
    #[schemars(range(min = 1, max = 16))]
    pub anisotropy: u16,
    /// Exponent `p` of the tilt profile `θ_j = I·(π/2)·(j/N)^p`: 1 = the paper's constant
    /// increment, < 1 = floppy (bends low), > 1 = stiff (bends near the tip).
    #[schemars(range(min = 0.1, max = 8.0))]
    pub stiffness: f32,
    /// Largest wind intensity `|I|` (the paper's intensity lives in `[-1, 1]`; more over-bends).
    #[schemars(range(min = 0.0, max = 4.0))]
    pub max_intensity: f32,
    /// Wind model: `scene` or `point_source`.
    pub wind: WindSource,
    /// `scene` wind: speed (m/s) at which the intensity reaches 1.
    #[schemars(range(min = 0.01, max = 100.0))]
    pub reference_speed: f32,
    /// `point_source` wind: world position of the source.
    #[schemars(inner(range(min = -1e6, max = 1e6)))]
    pub source_position: [f32; 3],
    /// `point_source` wind: period of the intensity function, s.
    #[schemars(range(min = 0.01, max = 10_000.0))]
    pub source_period: f32,
    /// `point_source` wind: width of one animation step (distance band), m.
    #[schemars(range(min = 0.01, max = 10_000.0))]
    pub source_step_length: f32,
    /// `point_source` wind: delay between neighbouring animation steps, s.
    #[schemars(range(min = 0.0, max = 10_000.0))]
    pub source_step_delay: f32,
    /// `point_source` wind: constant added to the intensity (0 = swings both ways).
    #[schemars(range(min = -2.0, max = 2.0))]
    pub source_bias: f32,
    /// Fraction of back-side sunlight passing through a blade (as `reference`).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub translucency: f32,
}

impl Default for Params {
    fn default() -> Self {
        let source = PointSourceConfig::default();
        Self {
            shells: 16,
            shell_lod_pixels: 1.0,
            texture_size: 512,
            tile_size: 2.0,
            density_scale: 1.0,
            height_skew: 1.0,
            blade_aspect: 0.5,
            mipmaps: Mipmaps::Custom,
            lod: Lod::MinorAxis,
            anisotropy: 1,
            stiffness: 1.0,
            max_intensity: 1.0,
            wind: WindSource::Scene,
            reference_speed: 12.0,
            source_position: source.position,
            source_period: source.period,
            source_step_length: source.step_length,
            source_step_delay: source.step_delay,
            source_bias: source.bias,
            translucency: 0.35,
        }
    }
}

impl Params {
    /// The point source these parameters describe, as the core's wind model would take it
    /// (`speed` is unused by the shells: the intensity bends them directly).
    pub fn point_source(&self) -> PointSourceConfig {
        PointSourceConfig {
            position: self.source_position,
            period: self.source_period,
            step_length: self.source_step_length,
            step_delay: self.source_step_delay,
            bias: self.source_bias,
            ..PointSourceConfig::default()
        }
    }
}

impl TechniqueParams for Params {
    fn validate(&self) -> Result<()> {
        check_ranges("bakay", self)?;
        if !self.texture_size.is_power_of_two() {
            return Err(grassbench::Error::param(
                "bakay.texture_size",
                self.texture_size,
                "a power of two in [16, 4096]",
            ));
        }
        if ![1, 2, 4, 8, 16].contains(&self.anisotropy) {
            return Err(grassbench::Error::param(
                "bakay.anisotropy",
                self.anisotropy,
                "1, 2, 4, 8 or 16",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use grassbench::params::resolve;

    fn with(key: &str, value: toml::Value) -> Result<Params> {
        let mut t = toml::Table::new();
        t.insert(key.into(), value);
        resolve::<Params>("bakay", &t)
    }

    #[test]
    fn defaults_are_valid_and_bad_values_name_the_key() {
        Params::default().validate().unwrap();
        for (key, value) in [
            ("shells", toml::Value::from(0)),
            ("shells", toml::Value::from(129)),
            ("texture_size", toml::Value::from(300)),
            ("anisotropy", toml::Value::from(3)),
            ("tile_size", toml::Value::from(f64::NAN)),
            ("stiffness", toml::Value::from(-1.0)),
            ("reference_speed", toml::Value::from(0.0)),
        ] {
            let e = with(key, value).unwrap_err().to_string();
            assert!(e.contains(&format!("bakay.{key}")), "{e}");
        }
        assert_eq!(with("mipmaps", "box".into()).unwrap().mipmaps, Mipmaps::Box);
        assert_eq!(
            with("wind", "point_source".into()).unwrap().wind,
            WindSource::PointSource
        );
        assert!(with("mipmaps", "auto".into()).is_err());
        assert!(with("shellz", 3.into()).is_err());
    }

    /// Every key has a description, and `validate` accepts each end of the schema's ranges
    /// and refuses the values just past them (the schema is where the ranges are written).
    #[test]
    fn the_schema_describes_every_key_and_validate_keeps_its_ranges() {
        assert_eq!(
            grassbench::params::schema_problems::<Params>("bakay", &[]),
            Vec::<String>::new()
        );
    }
}
