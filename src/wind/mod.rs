//! Wind: one abstraction, every model, every technique.
//!
//! A [`WindField`] gives the wind velocity (m/s) at any world position and time. Every
//! technique can sample it on the CPU, and the core bakes it each frame into a texture over
//! the terrain ([`WindTexture`]) that every shader reads through the prelude's `wind_at`, so
//! any wind model drives any technique.
//!
//! Models here: [`Breeze`] (a steady wind with travelling gusts), [`PointSource`] (Bakay et al.
//! Sec. 3: wind vectors towards a source, intensity waves travelling outwards in animation
//! steps), [`FluidWind`] (Stam's stable fluids, Zhang Ch. 2 and Sec. 5.1; stateful, stepped by
//! [`WindField::advance`]), [`PrimitiveSet`] (Perbet & Cani Sec. 3: wind primitives — breeze,
//! gust, whirlwind, blast — given as bending directions and posture indices, mixed by priority
//! or summed, and read as a velocity `direction × index × wind_speed`) and calm air.
//!
//! [`posture`] pre-computes, per kind of blade, Perbet's postures and the posture-index
//! response to a wind that starts and stops (their Fig. 6 and 8) with a small simulation of one
//! blade; the gust primitive plays that response, and a Perbet receiver turns indices into
//! blade shapes with it.

mod breeze;
mod config;
pub mod fluid;
mod point_source;
pub mod posture;
pub mod primitives;
mod texture;

use glam::Vec3;

pub use breeze::Breeze;
pub use config::{BreezeConfig, PointSourceConfig, WindConfig};
pub use fluid::{FluidConfig, FluidMapping, FluidWind};
pub use point_source::PointSource;
pub use posture::{BladeConfig, Postures, ResponseCurve};
pub use primitives::{Mixing, PrimitiveConfig, PrimitiveSet, PrimitivesConfig, WindSample};
pub use texture::{FORMAT as TEXTURE_FORMAT, SAMPLE_HEIGHT, WindTexture};

use crate::Result;
use crate::object::ObjectConfig;
use crate::terrain::Terrain;

/// A wind model: velocity in m/s at a position and time.
///
/// Fields are `Sync`, so techniques may sample one from several threads at once.
///
/// Fields with state (fluid solvers) advance in [`WindField::advance`]; procedural fields are
/// pure functions of `(position, time)` and leave `advance` empty. Either way, stepping a
/// fresh field through frames `0..=n` gives the same field at frame `n`: wind is reproducible.
///
/// Every technique reads a field through this trait alone. A technique that can use more of
/// one model than its velocities (Perbet's receivers read [`PrimitiveSet::sample`]'s bending
/// directions and posture indices) asks for that model by type: a field is [`std::any::Any`],
/// so `(wind as &dyn Any).downcast_ref::<PrimitiveSet>()` finds it.
pub trait WindField: Send + Sync + std::any::Any {
    /// Short name for result files and the UI.
    fn name(&self) -> &'static str;

    /// Advances the model's state to `time` (seconds), `dt` after the previous call.
    fn advance(&mut self, time: f32, dt: f32);

    /// Wind velocity (m/s) at world position `p` at `time`.
    fn velocity(&self, p: Vec3, time: f32) -> Vec3;

    /// Whether the field depends only on `(position, time)` (no state to step).
    fn is_stateless(&self) -> bool {
        true
    }

    /// [`WindField::velocity`] at every point of `points`, written to `out` (the shorter of
    /// the two sets the count). One virtual call for many samples: techniques that animate
    /// many points per frame use it; models may override it with a faster loop.
    fn velocities(&self, points: &[Vec3], time: f32, out: &mut [Vec3]) {
        for (o, p) in out.iter_mut().zip(points) {
            *o = self.velocity(*p, time);
        }
    }
}

/// No wind at all.
#[derive(Clone, Copy, Debug, Default)]
pub struct Calm;

impl WindField for Calm {
    fn name(&self) -> &'static str {
        "calm"
    }

    fn advance(&mut self, _time: f32, _dt: f32) {}

    fn velocity(&self, _p: Vec3, _time: f32) -> Vec3 {
        Vec3::ZERO
    }
}

/// Builds the field a scene's `[wind]` section describes over `terrain` (the fluid model maps
/// its grid onto the terrain and follows the ground); blasts may follow the scene's `object`.
pub fn build(
    config: &WindConfig,
    seed: u64,
    terrain: &Terrain,
    object: Option<&ObjectConfig>,
) -> Result<Box<dyn WindField>> {
    config.validate()?;
    Ok(match config {
        WindConfig::Calm => Box::new(Calm),
        WindConfig::Breeze(c) => Box::new(Breeze::new(c.clone(), seed)),
        WindConfig::PointSource(c) => Box::new(PointSource::new(c.clone())),
        WindConfig::Fluid(c) => Box::new(FluidWind::new(c.clone(), seed, terrain)?),
        WindConfig::Primitives(c) => Box::new(PrimitiveSet::new(c, seed, object)?),
    })
}
