//! How a scene file describes Perbet's wind primitives: `[wind] model = "primitives"`, a blade
//! kind for the posture simulation and a list of `[[wind.primitives]]`.

use serde::{Deserialize, Serialize};

use crate::params::check;
use crate::wind::posture::BladeConfig;
use crate::{Error, Result};

/// How several primitives covering the same point combine.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Mixing {
    /// The paper's rule: the highest-priority primitive whose mask covers a point decides its
    /// direction and index. Masks with soft edges are layered in priority order with the mask
    /// as opacity, so a fully covering mask hides everything below it; equal priorities stack
    /// in list order (later on top).
    #[default]
    Priority,
    /// Every covering primitive contributes its vector (direction × index) weighted by its
    /// mask value; the sum's length is clamped to 1.
    Sum,
}

/// `[wind]` with `model = "primitives"`: Perbet & Cani's wind primitives (Sec. 3.3).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct PrimitivesConfig {
    /// `"priority"` (the paper) or `"sum"`.
    pub mixing: Mixing,
    /// The grass kind whose pre-computed response the gusts play (Sec. 3.2); its
    /// `wind_speed` converts posture indices into m/s for other techniques.
    pub blade: BladeConfig,
    /// The primitives, `[[wind.primitives]]` with `kind = "breeze" | "gust" | "whirlwind" |
    /// "blast"`; at least one.
    pub primitives: Vec<PrimitiveConfig>,
}

impl Default for PrimitivesConfig {
    fn default() -> Self {
        Self {
            mixing: Mixing::Priority,
            blade: BladeConfig::default(),
            primitives: vec![
                PrimitiveConfig::Breeze(BreezeParams::default()),
                PrimitiveConfig::Gust(GustParams::default()),
            ],
        }
    }
}

/// One `[[wind.primitives]]` entry, tagged by `kind`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum PrimitiveConfig {
    /// The gentle breeze: infinite mask, slowly drifting bend plus small oscillations.
    Breeze(BreezeParams),
    /// A gust of wind: a strip translating across the terrain.
    Gust(GustParams),
    /// A whirlwind: a moving disc, bending tangentially, most near its centre.
    Whirlwind(WhirlwindParams),
    /// A blast of air around a moving object: bending radially away from it.
    Blast(BlastParams),
}

/// The small stochastic oscillations every primitive adds around its prescribed posture
/// (Sec. 3.3): the direction turns by up to `angle` and the index is scaled by up to
/// `1 ± index`, following value noise of feature size `scale` changing `frequency` times a
/// second. Written inline, e.g. `jitter = { angle = 0.2, index = 0.15 }`.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct JitterParams {
    /// Largest turn of the bending direction, radians.
    pub angle: f32,
    /// Largest relative change of the posture index.
    pub index: f32,
    /// How fast the oscillations change, Hz.
    pub frequency: f32,
    /// Feature size of the oscillations over the ground, m.
    pub scale: f32,
}

impl Default for JitterParams {
    fn default() -> Self {
        Self {
            angle: 0.15,
            index: 0.15,
            frequency: 1.5,
            scale: 1.5,
        }
    }
}

impl JitterParams {
    /// No oscillations at all.
    pub const NONE: Self = Self {
        angle: 0.0,
        index: 0.0,
        frequency: 0.0,
        scale: 1.0,
    };
}

/// `kind = "breeze"`: the gentle breeze (Sec. 3.3) — an infinite mask; each blade oscillates
/// around a rest direction and bend that drift slowly in space and time.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct BreezeParams {
    /// Priority for `mixing = "priority"` (higher wins).
    pub priority: i32,
    /// Mean bending direction in the ground plane (x, z); normalised.
    pub direction: [f32; 2],
    /// Mean posture index, in `[−1, 1]`.
    pub bend: f32,
    /// Largest slow drift of the direction, radians.
    pub drift_angle: f32,
    /// Largest slow drift of the index.
    pub drift_bend: f32,
    /// Time over which the drift changes, s.
    pub drift_period: f32,
    /// Feature size of the drift over the ground, m.
    pub drift_scale: f32,
    /// The small fast oscillations.
    pub jitter: JitterParams,
}

impl Default for BreezeParams {
    fn default() -> Self {
        Self {
            priority: 0,
            direction: [1.0, 0.35],
            bend: 0.25,
            drift_angle: 0.35,
            drift_bend: 0.12,
            drift_period: 6.0,
            drift_scale: 25.0,
            jitter: JitterParams::default(),
        }
    }
}

/// `kind = "gust"`: a gust of wind (Sec. 3.3, Fig. 7–9) — a strip, perpendicular to
/// `direction`, translating along it at `speed`. A point the front crossed `τ` seconds ago
/// bends along `direction` with the blade's response index at `τ` to a wind lasting
/// `width / speed` seconds (Fig. 8 read along the strip); the mask runs from the front back to
/// where that response has settled.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct GustParams {
    /// Priority for `mixing = "priority"` (higher wins).
    pub priority: i32,
    /// Direction of travel, which is also the bending direction (x, z); normalised.
    pub direction: [f32; 2],
    /// A ground point (x, z) the front crosses at time `start`; the centre of the strip's
    /// length when `length` is set.
    pub origin: [f32; 2],
    /// When the front crosses `origin`, s (the front is upwind of it before).
    pub start: f32,
    /// Speed of the strip over the ground, m/s.
    pub speed: f32,
    /// Depth of the windy part of the strip, m: each point feels wind for `width / speed` s.
    pub width: f32,
    /// Length of the strip across its travel, m; absent = endless.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length: Option<f32>,
    /// Width of the soft falloff at the strip's ends, m (with `length`).
    pub feather: f32,
    /// Scale of the response index, in `[0, 1]`.
    pub strength: f32,
    /// Time between successive gusts, s; absent = a single gust. A new front cuts short what
    /// is left of the previous gust's tail.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interval: Option<f32>,
    /// The small oscillations around the prescribed posture.
    pub jitter: JitterParams,
}

impl Default for GustParams {
    fn default() -> Self {
        Self {
            priority: 1,
            direction: [1.0, 0.2],
            origin: [-40.0, 0.0],
            start: 0.0,
            speed: 8.0,
            width: 12.0,
            length: None,
            feather: 3.0,
            strength: 1.0,
            interval: Some(12.0),
            jitter: JitterParams::default(),
        }
    }
}

/// `kind = "whirlwind"`: a whirlwind (Sec. 3.3, Fig. 11) — a disc of `radius` whose centre
/// moves at `velocity`; blades bend tangentially, more near the centre, and the index varies
/// slightly in a pattern turning around the centre.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct WhirlwindParams {
    /// Priority for `mixing = "priority"` (higher wins).
    pub priority: i32,
    /// Centre (x, z) at time 0.
    pub centre: [f32; 2],
    /// Velocity of the centre over the ground, m/s.
    pub velocity: [f32; 2],
    /// Radius of the mask, m.
    pub radius: f32,
    /// Posture index at the centre; falls linearly to 0 at the rim.
    pub strength: f32,
    /// Angular speed of the index pattern, rad/s; its sign is the sense of rotation (positive
    /// turns from +x towards +z).
    pub spin: f32,
    /// Relative amplitude of the turning index pattern.
    pub swirl: f32,
    /// Width of the soft edge of the mask, m.
    pub feather: f32,
    /// The small oscillations around the prescribed posture.
    pub jitter: JitterParams,
}

impl Default for WhirlwindParams {
    fn default() -> Self {
        Self {
            priority: 2,
            centre: [0.0, 0.0],
            velocity: [0.8, 0.3],
            radius: 8.0,
            strength: 0.9,
            spin: 1.5,
            swirl: 0.2,
            feather: 1.5,
            jitter: JitterParams::default(),
        }
    }
}

/// `kind = "blast"`: a blast of air around a flying object (Sec. 3.3, Fig. 12) — a disc around
/// the object's ground position; blades bend radially away from it, more near it. The scene
/// has no flying object, so the centre's path is configured: `start + velocity · t`, or
/// piecewise linear through `keyframes` when there are any.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct BlastParams {
    /// Priority for `mixing = "priority"` (higher wins).
    pub priority: i32,
    /// Centre (x, z) at time 0 (without keyframes).
    pub start: [f32; 2],
    /// Velocity of the centre, m/s (without keyframes).
    pub velocity: [f32; 2],
    /// `[time, x, z]` points of the centre's path, times increasing; held before the first
    /// and after the last. Empty: `start` and `velocity` are used.
    pub keyframes: Vec<[f32; 3]>,
    /// Follow the scene's moving object (`[object]`) instead of `start`, `velocity` and
    /// `keyframes`: the paper's blast around a flying object.
    pub follow_object: bool,
    /// Radius of the mask, m.
    pub radius: f32,
    /// Posture index next to the object; falls linearly to 0 at the rim.
    pub strength: f32,
    /// Width of the soft edge of the mask, m.
    pub feather: f32,
    /// The small oscillations around the prescribed posture.
    pub jitter: JitterParams,
}

impl Default for BlastParams {
    fn default() -> Self {
        Self {
            priority: 3,
            start: [-20.0, 0.0],
            velocity: [2.0, 0.0],
            keyframes: Vec::new(),
            follow_object: false,
            radius: 5.0,
            strength: 1.0,
            feather: 1.0,
            jitter: JitterParams::default(),
        }
    }
}

/// Most seconds of wind a gust may blow on one point (`width / speed`): its response is
/// simulated at start-up.
pub const MAX_GUST_WIND: f32 = 120.0;

impl PrimitiveConfig {
    /// The `kind` name.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Breeze(_) => "breeze",
            Self::Gust(_) => "gust",
            Self::Whirlwind(_) => "whirlwind",
            Self::Blast(_) => "blast",
        }
    }

    /// The priority for `mixing = "priority"`.
    pub fn priority(&self) -> i32 {
        match self {
            Self::Breeze(p) => p.priority,
            Self::Gust(p) => p.priority,
            Self::Whirlwind(p) => p.priority,
            Self::Blast(p) => p.priority,
        }
    }

    /// Rejects NaN, infinities and absurd values; error keys start with `prefix`, e.g.
    /// `wind.primitives[1]`.
    pub fn validate(&self, prefix: &str) -> Result<()> {
        let key = |k: &str| format!("{prefix}.{k}");
        match self {
            Self::Breeze(p) => {
                direction(&key("direction"), p.direction)?;
                check(&key("bend"), p.bend, -1.0..=1.0)?;
                check(
                    &key("drift_angle"),
                    p.drift_angle,
                    0.0..=std::f32::consts::PI,
                )?;
                check(&key("drift_bend"), p.drift_bend, 0.0..=1.0)?;
                check(&key("drift_period"), p.drift_period, 0.01..=10_000.0)?;
                check(&key("drift_scale"), p.drift_scale, 0.01..=100_000.0)?;
                jitter(&key("jitter"), &p.jitter)
            }
            Self::Gust(p) => {
                direction(&key("direction"), p.direction)?;
                point(&key("origin"), p.origin)?;
                check(&key("start"), p.start, -1e6..=1e6)?;
                check(&key("speed"), p.speed, 0.01..=200.0)?;
                check(&key("width"), p.width, 0.01..=100_000.0)?;
                if p.width / p.speed > MAX_GUST_WIND {
                    return Err(Error::param(
                        key("width"),
                        p.width,
                        format!(
                            "at most {MAX_GUST_WIND} s of wind on a point: width / speed ≤ {MAX_GUST_WIND}"
                        ),
                    ));
                }
                if let Some(length) = p.length {
                    check(&key("length"), length, 0.01..=1e6)?;
                }
                check(&key("feather"), p.feather, 0.0..=100_000.0)?;
                check(&key("strength"), p.strength, 0.0..=1.0)?;
                if let Some(interval) = p.interval {
                    check(&key("interval"), interval, 0.01..=1e6)?;
                }
                jitter(&key("jitter"), &p.jitter)
            }
            Self::Whirlwind(p) => {
                point(&key("centre"), p.centre)?;
                velocity(&key("velocity"), p.velocity)?;
                check(&key("radius"), p.radius, 0.01..=100_000.0)?;
                check(&key("strength"), p.strength, 0.0..=1.0)?;
                check(&key("spin"), p.spin, -100.0..=100.0)?;
                check(&key("swirl"), p.swirl, 0.0..=1.0)?;
                check(&key("feather"), p.feather, 0.0..=100_000.0)?;
                jitter(&key("jitter"), &p.jitter)
            }
            Self::Blast(p) => {
                crate::keyframes::validate_track(prefix, p.start, p.velocity, &p.keyframes)?;
                check(&key("radius"), p.radius, 0.01..=100_000.0)?;
                check(&key("strength"), p.strength, 0.0..=1.0)?;
                check(&key("feather"), p.feather, 0.0..=100_000.0)?;
                jitter(&key("jitter"), &p.jitter)
            }
        }
    }
}

impl PrimitivesConfig {
    /// Rejects an empty list and every bad value, naming the key (`wind.primitives[i].<key>`,
    /// `wind.blade.<key>`).
    pub fn validate(&self) -> Result<()> {
        self.blade.validate("wind.blade")?;
        if self.primitives.is_empty() {
            return Err(Error::param(
                "wind.primitives",
                "[]",
                "at least one [[wind.primitives]] (kind = \"breeze\", \"gust\", \"whirlwind\" or \"blast\")",
            ));
        }
        for (i, p) in self.primitives.iter().enumerate() {
            p.validate(&format!("wind.primitives[{i}]"))?;
        }
        Ok(())
    }
}

/// A non-zero, finite direction in the ground plane.
fn direction(name: &str, d: [f32; 2]) -> Result<()> {
    check(&format!("{name}[0]"), d[0], -1e6..=1e6)?;
    check(&format!("{name}[1]"), d[1], -1e6..=1e6)?;
    if d[0].hypot(d[1]) < 1e-6 {
        return Err(Error::param(name, format!("{d:?}"), "a non-zero 2D vector"));
    }
    Ok(())
}

/// A finite ground position.
fn point(name: &str, p: [f32; 2]) -> Result<()> {
    check(&format!("{name}[0]"), p[0], -1e6..=1e6)?;
    check(&format!("{name}[1]"), p[1], -1e6..=1e6)
}

/// A finite ground velocity, m/s.
fn velocity(name: &str, v: [f32; 2]) -> Result<()> {
    check(&format!("{name}[0]"), v[0], -1000.0..=1000.0)?;
    check(&format!("{name}[1]"), v[1], -1000.0..=1000.0)
}

/// Oscillation amplitudes and rates.
fn jitter(name: &str, j: &JitterParams) -> Result<()> {
    check(
        &format!("{name}.angle"),
        j.angle,
        0.0..=std::f32::consts::PI,
    )?;
    check(&format!("{name}.index"), j.index, 0.0..=1.0)?;
    check(&format!("{name}.frequency"), j.frequency, 0.0..=100.0)?;
    check(&format!("{name}.scale"), j.scale, 0.01..=100_000.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wind::WindConfig;

    #[derive(Debug, Deserialize)]
    struct File {
        wind: WindConfig,
    }

    const SNIPPET: &str = r#"
[wind]
model = "primitives"
mixing = "sum"
blade = { height = 0.6, stiffness = 0.006, postures = 11 }

[[wind.primitives]]
kind = "breeze"
direction = [1.0, 0.3]
bend = 0.2

[[wind.primitives]]
kind = "gust"
priority = 1
direction = [1, 0]
origin = [-40.0, 0.0]
speed = 8.0
width = 12.0
length = 30.0
interval = 15.0
jitter = { angle = 0.2, index = 0.1 }

[[wind.primitives]]
kind = "whirlwind"
priority = 2
centre = [5.0, 5.0]
velocity = [0.5, 0.0]
radius = 6.0

[[wind.primitives]]
kind = "blast"
priority = 3
keyframes = [[0.0, -10.0, 0.0], [10.0, 10.0, 0.0]]
radius = 4.0
"#;

    fn parse(text: &str) -> std::result::Result<WindConfig, String> {
        toml::from_str::<File>(text)
            .map(|f| f.wind)
            .map_err(|e| e.to_string())
    }

    fn primitives(text: &str) -> PrimitivesConfig {
        match parse(text).unwrap() {
            WindConfig::Primitives(c) => c,
            other => panic!("not primitives: {other:?}"),
        }
    }

    #[test]
    fn parses_a_scene_snippet() {
        let c = primitives(SNIPPET);
        assert_eq!(c.mixing, Mixing::Sum);
        assert_eq!(c.blade.height, 0.6);
        assert_eq!(c.blade.postures, 11);
        assert_eq!(c.blade.segments, BladeConfig::default().segments);
        let kinds: Vec<_> = c.primitives.iter().map(PrimitiveConfig::kind).collect();
        assert_eq!(kinds, ["breeze", "gust", "whirlwind", "blast"]);
        let PrimitiveConfig::Gust(g) = &c.primitives[1] else {
            panic!("{:?}", c.primitives[1]);
        };
        assert_eq!(g.direction, [1.0, 0.0]);
        assert_eq!(g.length, Some(30.0));
        assert_eq!(g.jitter.angle, 0.2);
        assert_eq!(g.jitter.frequency, JitterParams::default().frequency);
        assert_eq!(c.primitives[3].priority(), 3);
        c.validate().unwrap();
        WindConfig::Primitives(c.clone()).validate().unwrap();
        // Through a TOML table and back (what the UI does) without loss.
        let config = WindConfig::Primitives(c);
        let table = toml::Table::try_from(&config).unwrap();
        assert_eq!(table["model"].as_str(), Some("primitives"));
        let back: WindConfig = toml::Value::Table(table).try_into().unwrap();
        assert_eq!(back, config);
        let default = WindConfig::default_for("primitives").unwrap();
        assert!(WindConfig::MODELS.contains(&default.model()));
        default.validate().unwrap();
    }

    #[test]
    fn errors_name_the_key() {
        let err = |text: &str| primitives(text).validate().unwrap_err().to_string();
        let nan = SNIPPET.replace("radius = 6.0", "radius = nan");
        let e = err(&nan);
        assert!(
            e.contains("wind.primitives[2].radius") && e.contains("NaN"),
            "{e}"
        );
        let e = err(&SNIPPET.replace("radius = 4.0", "radius = -4.0"));
        assert!(e.contains("wind.primitives[3].radius"), "{e}");
        let e = err(&SNIPPET.replace("speed = 8.0", "speed = -8.0"));
        assert!(e.contains("wind.primitives[1].speed"), "{e}");
        let e = err(&SNIPPET.replace("index = 0.1", "index = 3.0"));
        assert!(e.contains("wind.primitives[1].jitter.index"), "{e}");
        let e = err(&SNIPPET.replace("direction = [1.0, 0.3]", "direction = [0.0, 0.0]"));
        assert!(e.contains("wind.primitives[0].direction"), "{e}");
        let e = err(&SNIPPET.replace("stiffness = 0.006", "stiffness = -1.0"));
        assert!(e.contains("wind.blade.stiffness"), "{e}");
        let e = err(&SNIPPET.replace("[10.0, 10.0", "[0.0, 10.0"));
        assert!(e.contains("wind.primitives[3].keyframes[1][0]"), "{e}");
        let e = err(&SNIPPET.replace("width = 12.0", "width = 5000.0"));
        assert!(e.contains("wind.primitives[1].width"), "{e}");
        let e = err("[wind]\nmodel = \"primitives\"\nprimitives = []\n");
        assert!(
            e.contains("wind.primitives") && e.contains("at least one"),
            "{e}"
        );
        // Unknown kinds, keys and mixings are parse errors that say what is valid.
        let e = parse(&SNIPPET.replace("\"whirlwind\"", "\"tornado\"")).unwrap_err();
        assert!(e.contains("tornado") && e.contains("whirlwind"), "{e}");
        let e = parse(&SNIPPET.replace("radius = 6.0", "radiu = 6.0")).unwrap_err();
        assert!(e.contains("radiu") && e.contains("radius"), "{e}");
        let e = parse(&SNIPPET.replace("\"sum\"", "\"average\"")).unwrap_err();
        assert!(e.contains("average") && e.contains("priority"), "{e}");
    }
}
