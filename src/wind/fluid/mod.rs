//! Stam's stable fluids as a wind model (Zhang 2006, Ch. 2 and Sec. 5.1): [`StamSolver`] is
//! the 3D solver on an `(N+2)³` grid, [`FluidWind`] the [`super::WindField`] that maps it onto
//! the terrain (tiled per grass grid, or stretched over the whole terrain) and samples it
//! trilinearly (Sec. 3.2.2).

mod config;
mod field;
mod solver;

pub use config::{FluidConfig, FluidMapping, MAX_SUBSTEPS};
pub use field::FluidWind;
pub use solver::{MAX_ITERATIONS, MAX_N, MIN_N, Poisson, StamParams, StamSolver};
