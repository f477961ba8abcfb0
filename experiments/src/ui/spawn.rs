//! Placing Perbet's wind primitives (Sec. 3.3) at a clicked point of a pane: a whirlwind
//! centred there, or a gust whose front starts there and travels away from the viewer. The
//! primitive joins the scene's `[wind]` as one more `[[wind.primitives]]` entry (switching the
//! model to `primitives`, with its default breeze, if it was another), so every pane's
//! technique feels it, and the wind panel lists it for editing.

use anyhow::Context as _;
use eframe::egui;
use grassbench::glam::{Vec2, Vec3};
use grassbench::wind::primitives::{GustParams, WhirlwindParams};
use grassbench::wind::{PrimitiveConfig, WindConfig};

/// What a click on a pane adds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum SpawnKind {
    /// Nothing: clicks and drags steer the camera.
    #[default]
    Off,
    /// A gust front starting at the point, travelling away from the viewer.
    Gust,
    /// A whirlwind centred on the point.
    Whirlwind,
}

impl SpawnKind {
    /// Every kind, for the panel.
    pub const ALL: [Self; 3] = [Self::Off, Self::Gust, Self::Whirlwind];

    /// Name shown in the panel.
    pub fn label(self) -> &'static str {
        match self {
            Self::Off => "none",
            Self::Gust => "gust",
            Self::Whirlwind => "whirlwind",
        }
    }

    /// The primitive this kind puts at `at` (x, z) at scene time `time`, for a viewer looking
    /// along `forward`; `None` for [`SpawnKind::Off`].
    pub fn primitive(self, at: Vec2, time: f32, forward: Vec3) -> Option<PrimitiveConfig> {
        match self {
            Self::Off => None,
            Self::Gust => {
                let away = Vec2::new(forward.x, forward.z)
                    .try_normalize()
                    .unwrap_or(Vec2::X);
                Some(PrimitiveConfig::Gust(GustParams {
                    direction: away.to_array(),
                    origin: at.to_array(),
                    start: time,
                    priority: 1,
                    ..GustParams::default()
                }))
            }
            Self::Whirlwind => {
                let w = WhirlwindParams::default();
                // The centre moves with `velocity` from time 0: be at `at` now.
                let centre = at - Vec2::from(w.velocity) * time;
                Some(PrimitiveConfig::Whirlwind(WhirlwindParams {
                    centre: centre.to_array(),
                    priority: 2,
                    ..w
                }))
            }
        }
    }
}

/// Adds `primitive` to the wind settings `wind` (the UI's `[wind]` table), switching the
/// model to `primitives` first if needed. Returns how many primitives the wind now has.
pub fn add(wind: &mut toml::Table, primitive: &PrimitiveConfig) -> anyhow::Result<usize> {
    if wind.get("model").and_then(|v| v.as_str()) != Some("primitives") {
        let config = WindConfig::default_for("primitives").context("the primitives model")?;
        *wind = toml::Table::try_from(&config).context("primitives settings")?;
    }
    let value = toml::Value::try_from(primitive).context("the new primitive")?;
    let list = wind
        .entry("primitives")
        .or_insert_with(|| toml::Value::Array(Vec::new()));
    let toml::Value::Array(list) = list else {
        anyhow::bail!("`wind.primitives` is not a list");
    };
    list.push(value);
    Ok(list.len())
}

/// Normalised device coordinates (x right, y up) of `pos` inside `rect`.
pub fn ndc(rect: egui::Rect, pos: egui::Pos2) -> Vec2 {
    Vec2::new(
        2.0 * (pos.x - rect.min.x) / rect.width() - 1.0,
        1.0 - 2.0 * (pos.y - rect.min.y) / rect.height(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spawning_switches_to_primitives_and_keeps_what_was_added() {
        let mut wind = toml::Table::try_from(WindConfig::default()).unwrap();
        let whirl = SpawnKind::Whirlwind
            .primitive(Vec2::new(3.0, -4.0), 2.0, Vec3::X)
            .unwrap();
        let n = add(&mut wind, &whirl).unwrap();
        let gust = SpawnKind::Gust
            .primitive(Vec2::new(1.0, 1.0), 2.5, Vec3::new(0.0, -0.5, -1.0))
            .unwrap();
        assert_eq!(add(&mut wind, &gust).unwrap(), n + 1);
        // The table is a valid wind that contains both, where they were put.
        let config: WindConfig = wind.clone().try_into().unwrap();
        config.validate().unwrap();
        let WindConfig::Primitives(p) = config else {
            panic!("not primitives: {wind:?}")
        };
        let whirl_centre = match &p.primitives[n - 1] {
            PrimitiveConfig::Whirlwind(w) => Vec2::from(w.centre) + Vec2::from(w.velocity) * 2.0,
            other => panic!("{other:?}"),
        };
        assert!((whirl_centre - Vec2::new(3.0, -4.0)).length() < 1e-5);
        match &p.primitives[n] {
            PrimitiveConfig::Gust(g) => {
                assert_eq!((g.origin, g.start), ([1.0, 1.0], 2.5));
                assert_eq!(g.direction, [0.0, -1.0]);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(SpawnKind::Off.primitive(Vec2::ZERO, 0.0, Vec3::X), None);
    }

    #[test]
    fn ndc_of_the_picture_corners() {
        let r = egui::Rect::from_min_size(egui::pos2(10.0, 20.0), egui::vec2(200.0, 100.0));
        assert_eq!(ndc(r, r.min), Vec2::new(-1.0, 1.0));
        assert_eq!(ndc(r, r.max), Vec2::new(1.0, -1.0));
        assert_eq!(ndc(r, r.center()), Vec2::ZERO);
    }
}
