//! Perbet & Cani 2001 ("Animating Prairies in Real-Time", Sec. 3): wind primitives.
//!
//! Perbet and Cani do not model the air. A *wind primitive* (Sec. 3.3) is a 2D **mask** over
//! the terrain (its extent, which may move) and an **action**: for every blade under the mask,
//! a bending direction and a *posture index* in `[−1, 1]` (0 rest; the sign says whether the
//! blade bends along the direction or, swinging back, against it), as functions of position
//! and time. Receivers (the blades, Sec. 3.2) turn that index into a shape with pre-computed
//! postures ([`crate::wind::posture`]). Every action adds "small oscillation\[s\] of random
//! direction and intensity around the prescribed position" (seeded here, so wind is
//! reproducible).
//!
//! | `kind` | mask | action | paper |
//! |---|---|---|---|
//! | `breeze` | infinite | slowly drifting direction and bend, small fast oscillations | Sec. 3.3 |
//! | `gust` | strip translating along its normal | the blade's response curve (Fig. 8) read along the strip | Sec. 3.3, Fig. 7–9 |
//! | `whirlwind` | moving disc | tangential, stronger near the centre, index pattern turning around it | Sec. 3.3, Fig. 11 |
//! | `blast` | disc around a moving object | radial away from the object | Sec. 3.3, Fig. 12 |
//!
//! Where masks overlap, [`Mixing::Priority`] lets the highest-priority primitive decide, as
//! the paper does; [`Mixing::Sum`] adds their vectors (Fig. 10) weighted by mask values.
//!
//! [`PrimitiveSet::sample`] is what a Perbet receiver asks for. So that every other technique
//! can be driven by primitives too, [`PrimitiveSet`] is also a [`crate::wind::WindField`]:
//! velocity = direction × index × the blade kind's `wind_speed` (the constant wind the
//! postures were simulated under), horizontal, zero where no mask covers.
//!
//! ```toml
//! [wind]
//! model = "primitives"
//! mixing = "priority"            # or "sum"
//! blade = { height = 0.5, stiffness = 0.0045, wind_speed = 5.0 }
//!
//! [[wind.primitives]]
//! kind = "breeze"
//! direction = [1.0, 0.3]
//! bend = 0.2
//!
//! [[wind.primitives]]
//! kind = "gust"
//! priority = 1
//! direction = [1.0, 0.0]
//! origin = [-40.0, 0.0]
//! speed = 8.0
//! width = 12.0
//! interval = 15.0
//! jitter = { angle = 0.2, index = 0.1 }
//! ```

mod blast;
mod breeze;
mod config;
mod gust;
mod jitter;
mod set;
mod whirlwind;

use glam::Vec2;

pub use config::{
    BlastParams, BreezeParams, GustParams, JitterParams, MAX_GUST_WIND, Mixing, PrimitiveConfig,
    PrimitivesConfig, WhirlwindParams,
};
pub use set::PrimitiveSet;

/// What primitives tell a receiver (Sec. 3.2): a bending direction and a posture index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WindSample {
    /// Bending direction over the ground (x, z), unit length.
    pub direction: Vec2,
    /// Posture index in `[−1, 1]`: 0 rest, 1 the most bent along `direction`, negative bent
    /// against it.
    pub posture: f32,
}

impl WindSample {
    /// At rest (the direction is arbitrary: +x).
    pub const REST: Self = Self {
        direction: Vec2::X,
        posture: 0.0,
    };

    /// The sample as one vector (Fig. 10): direction × index.
    pub fn vector(&self) -> Vec2 {
        self.direction * self.posture
    }
}

/// The mask of a disc of `radius` around `centre` (whirlwinds, blasts): 1 inside, fading to 0
/// over the outer `feather` metres (a hard edge when `feather` is 0).
fn disc_mask(centre: Vec2, radius: f32, feather: f32, xz: Vec2) -> f32 {
    let r = xz.distance(centre);
    if r > radius {
        0.0
    } else if feather <= 0.0 {
        1.0
    } else {
        1.0 - gust::smoothstep(radius - feather, radius, r)
    }
}
