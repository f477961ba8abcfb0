//! `[wind]` with `model = "fluid"`: the solver's parameters and how its grid maps onto the
//! terrain.

use serde::{Deserialize, Serialize};

use super::solver::{Poisson, StamParams};
use crate::params::check;
use crate::{Error, Result};

/// Most solver steps one [`crate::wind::WindField::advance`] call may take: a frame longer than
/// `MAX_SUBSTEPS · max_substep` is stepped in `MAX_SUBSTEPS` longer steps (the solver is
/// unconditionally stable, only less accurate).
pub const MAX_SUBSTEPS: u32 = 64;

/// How the one simulated grid covers the terrain.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FluidMapping {
    /// Zhang Sec. 5.1: one solution repeated on every `tile_size` square (one per grass grid),
    /// each tile reading it with its own seeded offset so neighbours do not move in step.
    #[default]
    Tiled,
    /// One grid stretched over the whole terrain (no repetition, coarser cells).
    Stretched,
}

/// Stam's stable fluids (Zhang Ch. 2) as the scene's wind. Keys of `[wind]`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct FluidConfig {
    /// Interior cells per axis, `N` (thesis: 8). 2..=128.
    pub n: u32,
    /// Kinematic viscosity of Eq. (2).
    pub viscosity: f32,
    /// Density diffusion rate of Eq. (1) (density is simulated as in the thesis, not used as
    /// wind).
    pub diffusion: f32,
    /// The source cell `(i, j, k)` (interior indices, 1..=n; `j` is up). Default: the centre.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub source_cell: Option<[u32; 3]>,
    /// Largest random velocity injected into the source cell per second (grid units).
    pub source_strength: f32,
    /// Largest density injected into the source cell per second.
    pub source_density: f32,
    /// Gauss–Seidel sweeps per linear solve (thesis: 20).
    pub iterations: u32,
    /// The projection's Poisson operator: `"consistent"` (default) or the thesis' `"compact"`.
    pub poisson: Poisson,
    /// `"tiled"` (Sec. 5.1) or `"stretched"`.
    pub mapping: FluidMapping,
    /// Side of one tile (one grass grid), metres, when tiled.
    pub tile_size: f32,
    /// Largest per-tile offset of the sampling position, as a fraction of a tile (0 = every
    /// tile identical), when tiled.
    pub tile_offset: f32,
    /// Height above the ground the grid's vertical extent covers, metres (the thesis makes
    /// blades as tall as the grid, Sec. 3.1.2).
    pub height: f32,
    /// Metres per second per grid unit of velocity (the solver works in domain lengths per
    /// second).
    pub speed_scale: f32,
    /// Longest solver step, s: longer frames are sub-stepped.
    pub max_substep: f32,
}

impl Default for FluidConfig {
    fn default() -> Self {
        let p = StamParams::default();
        Self {
            n: p.n as u32,
            viscosity: 0.5,
            diffusion: p.diffusion,
            source_cell: None,
            source_strength: 500.0,
            source_density: p.source_density,
            iterations: p.iterations,
            poisson: p.poisson,
            mapping: FluidMapping::Tiled,
            tile_size: 5.0,
            tile_offset: 0.5,
            height: 1.0,
            speed_scale: 30.0,
            max_substep: 1.0 / 30.0,
        }
    }
}

impl FluidConfig {
    /// The solver parameters (`seed` drives the random source).
    pub fn solver_params(&self, seed: u64) -> StamParams {
        let n = self.n as usize;
        let centre = (n / 2).max(1);
        StamParams {
            n,
            viscosity: self.viscosity,
            diffusion: self.diffusion,
            source_cell: self
                .source_cell
                .map_or([centre; 3], |c| c.map(|c| c as usize)),
            source_strength: self.source_strength,
            source_density: self.source_density,
            iterations: self.iterations,
            poisson: self.poisson,
            seed,
        }
    }

    /// Rejects NaN, infinities and absurd values, naming the key (`wind.<key>`).
    pub fn validate(&self) -> Result<()> {
        self.solver_params(0).validate()?;
        check("wind.tile_size", self.tile_size, 0.01..=100_000.0)?;
        check("wind.tile_offset", self.tile_offset, 0.0..=1.0)?;
        check("wind.height", self.height, 0.01..=1000.0)?;
        check("wind.speed_scale", self.speed_scale, 0.0..=10_000.0)?;
        if !(self.max_substep.is_finite() && self.max_substep > 0.0 && self.max_substep <= 10.0) {
            return Err(Error::param(
                "wind.max_substep",
                self.max_substep,
                "seconds in (0, 10]",
            ));
        }
        Ok(())
    }
}
