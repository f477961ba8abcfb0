//! The solver: Stam's "stable fluids" on a 3D collocated grid, following Zhang Xia's MSc
//! thesis (grass animation), Chapter 2, which itself extends Stam's *Real-Time Fluid Dynamics
//! for Games* (thesis ref. \[8\]) from 2D to 3D.
//!
//! # Grid and units
//!
//! * Thesis Sec. 2.2: an N³ "computational cube" of cells surrounded by a one-cell "boundary
//!   wall", i.e. `(N+2)³` cells. Default `N = 8` (Sec. 2.2 and Sec. 5.1: one 10×10×10 grid is
//!   simulated and tiled over all 16×16 grass grids).
//! * Cell `(i, j, k)` is stored at `ix(i, j, k) = i + (N+2)·(j + (N+2)·k)`, so `i` is the
//!   fastest axis; every sweep below runs `k` outermost and `i` innermost to walk memory
//!   linearly.
//! * As in Stam's reference code the domain is the unit cube, cell size `h = 1/N`; velocities
//!   are therefore in *domain lengths per second*. Advection back-traces `dt·N` cells per unit
//!   of velocity. [`super::FluidWind`] maps grid units to metres and m/s.
//!
//! # Per-step pipeline (thesis Figure 2, Sec. 2.3.4, Sec. 2.3.5)
//!
//! [`StamSolver::step`] = inject seeded random velocity + density into the source cell
//! (Sec. 2.2, 2.3.1) → `vel_step` → `dens_step`, with
//!
//! ```text
//! vel_step : add_source ×3 → diffuse ×3 (Eq. 4) → project → advect ×3 → project
//! dens_step: add_source     → diffuse    (Eq. 4) → advect
//! ```
//!
//! No heap allocation happens after construction: all work arrays, the "previous" arrays that
//! the thesis' `SWAP` macro exchanges, a one-row scratch buffer for the Gauss–Seidel sweep and
//! the neighbour table of the consistent Poisson solve are allocated in [`StamSolver::new`].
//!
//! # Deviation: the Poisson operator of the projection ([`Poisson`])
//!
//! The thesis (Sec. 2.3.6, after Stam) computes the divergence and the pressure gradient with
//! central differences (stencil `2h`) but solves the Poisson equation with the compact 7-point
//! Laplacian (stencil `h`). The two are not consistent: even an exact solve leaves, for a
//! Fourier mode of wavenumber `θ` per axis, a fraction `sin²(θ/2)` of its central-difference
//! divergence. Measured on this code (tests below): white noise loses only 1.5–1.6x of its
//! divergence at *any* sweep count (20 … 1000), the smoothest wall-compatible field at most
//! `1/sin²(π/2N)` = 26.3x for N = 8 — the 100x reduction the project asks for is impossible
//! with that scheme at the thesis' N.
//!
//! By default ([`Poisson::Consistent`]) the projection therefore solves the Poisson equation
//! with the operator the central divergence and gradient actually compose to, `div∘grad`
//! *including the walls*: per axis `(p[i+2] − 2p[i] + p[i−2]) / 4` where the indices beyond
//! the walls mirror about the wall face (`p[−1] = p[2]`, `p[0] = p[1]`; derived from
//! `set_bound`'s reflected normal velocity and zero-gradient pressure). That operator is
//! `−GᵀG` (symmetric, only constants in its null space), so Gauss–Seidel converges and the
//! projected field's central divergence goes to zero with the sweep count. Still the thesis'
//! 20 sweeps; measured divergence reduction on white noise with 20 sweeps: see
//! `projection_reduces_divergence_100x` below. The price: the wide stencil is the textbook
//! collocated projection that does not see odd-even (checkerboard) velocity modes, which the
//! compact Laplacian damps; diffusion and advection still smooth them. The thesis' compact
//! scheme stays available as [`Poisson::Compact`] (`poisson = "compact"` in the scene's
//! `[wind]`), and its measured discretisation limit is asserted by a test too.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::rng::Rng;
use crate::{Error, Result};

// ---------------------------------------------------------------------------
// Parameters
// ---------------------------------------------------------------------------

/// Largest accepted interior resolution `n` (a 130³ grid is ~8.8 MB per array).
pub const MAX_N: usize = 128;
/// Smallest accepted interior resolution `n`.
pub const MIN_N: usize = 2;
/// Largest accepted Gauss–Seidel sweep count.
pub const MAX_ITERATIONS: u32 = 1000;
/// Largest accepted viscosity / diffusion coefficient.
pub const MAX_COEFFICIENT: f32 = 1.0e3;
/// Largest accepted source magnitude (velocity or density rate).
pub const MAX_SOURCE: f32 = 1.0e6;

/// Which Laplacian the projection's Poisson solve uses (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Poisson {
    /// `div∘grad` of the central differences, walls included (default): the projection
    /// removes the central-difference divergence as the Gauss–Seidel sweeps converge.
    #[default]
    Consistent,
    /// The thesis' (and Stam's) compact 7-point Laplacian: discretisation-limited, see above.
    Compact,
}

/// Parameters of a [`StamSolver`]. Field names match the keys of `[wind]` with
/// `model = "fluid"`, and validation errors name them as `wind.<key>`.
///
/// Nothing here is given numerically by the thesis except `n = 8` and the 20 Gauss–Seidel
/// sweeps of the `linear_solver` pseudo-code (Sec. 2.3.2); the other defaults are small values
/// in the spirit of Stam's demo.
#[derive(Debug, Clone, PartialEq)]
pub struct StamParams {
    /// Interior cells per axis, `N` (thesis Sec. 2.2 uses 8). Accepted: `2..=128`.
    pub n: usize,
    /// Kinematic viscosity `ν` of Eq. (2). Accepted: finite, `0..=1000`.
    pub viscosity: f32,
    /// Density diffusion rate `k` of Eq. (1). Accepted: finite, `0..=1000`.
    pub diffusion: f32,
    /// The "source grid" cell (Sec. 2.2), interior indices `(i, j, k)`, each in `1..=n`.
    pub source_cell: [usize; 3],
    /// Maximum magnitude of the random velocity source written into the source cell each
    /// step. Like every source in the thesis it goes through `add_source` (`x += dt·x0`), so it
    /// is a rate: at most `dt · source_strength` of velocity is added per step.
    /// Accepted: finite, `0..=1e6`.
    pub source_strength: f32,
    /// Maximum density source (rate) written into the source cell each step; the actual value
    /// is uniform in `[0, source_density)`. Accepted: finite, `0..=1e6`.
    pub source_density: f32,
    /// Gauss–Seidel sweeps per linear solve (Eq. 4 and the Poisson solve of Sec. 2.3.6).
    /// Thesis value: 20. Accepted: `1..=1000`.
    pub iterations: u32,
    /// The projection's Poisson operator.
    pub poisson: Poisson,
    /// Seed of the deterministic source PRNG (same seed → bit-identical run).
    pub seed: u64,
}

impl Default for StamParams {
    fn default() -> Self {
        Self {
            n: 8,
            viscosity: 1.0e-4,
            diffusion: 1.0e-4,
            source_cell: [4, 4, 4],
            source_strength: 5.0,
            source_density: 100.0,
            iterations: 20,
            poisson: Poisson::Consistent,
            seed: 0x5EED_6A55,
        }
    }
}

impl StamParams {
    /// Checks every field; the error names the key (`wind.<key>`), its value and the accepted
    /// range.
    pub fn validate(&self) -> Result<()> {
        if !(MIN_N..=MAX_N).contains(&self.n) {
            return Err(Error::param(
                "wind.n",
                self.n,
                format!("an integer in [{MIN_N}, {MAX_N}]"),
            ));
        }
        check_f32("wind.viscosity", self.viscosity, MAX_COEFFICIENT)?;
        check_f32("wind.diffusion", self.diffusion, MAX_COEFFICIENT)?;
        check_f32("wind.source_strength", self.source_strength, MAX_SOURCE)?;
        check_f32("wind.source_density", self.source_density, MAX_SOURCE)?;
        for (axis, &c) in self.source_cell.iter().enumerate() {
            if !(1..=self.n).contains(&c) {
                return Err(Error::param(
                    format!("wind.source_cell[{axis}]"),
                    c,
                    format!("an interior cell index in [1, {}] (n = {})", self.n, self.n),
                ));
            }
        }
        if !(1..=MAX_ITERATIONS).contains(&self.iterations) {
            return Err(Error::param(
                "wind.iterations",
                self.iterations,
                format!("an integer in [1, {MAX_ITERATIONS}]"),
            ));
        }
        Ok(())
    }
}

fn check_f32(key: &str, value: f32, max: f32) -> Result<()> {
    crate::params::check(key, value, 0.0..=max)
}

// ---------------------------------------------------------------------------
// Grid indexing and the boundary flag `b`
// ---------------------------------------------------------------------------

/// Index arithmetic for an `(n+2)³` grid.
#[derive(Debug, Clone, Copy)]
struct Grid {
    /// Interior cells per axis.
    n: usize,
    /// Cells per axis including the two walls, `n + 2`.
    s: usize,
    /// Cells per `k`-plane, `s²`.
    plane: usize,
}

impl Grid {
    fn new(n: usize) -> Self {
        let s = n + 2;
        Self { n, s, plane: s * s }
    }

    #[inline(always)]
    fn ix(self, i: usize, j: usize, k: usize) -> usize {
        i + self.s * j + self.plane * k
    }

    fn len(self) -> usize {
        self.plane * self.s
    }
}

/// The `b` argument of the thesis' `set_bound(N, b, x)` (Sec. 2.3.7):
/// which velocity component (if any) the array holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Bound {
    /// `b = 0`: scalar (density, pressure): copied into the walls.
    Scalar,
    /// `b = 1`: `u`, negated on the `i = 0` / `i = N+1` walls.
    U,
    /// `b = 2`: `v`, negated on the `j` walls.
    V,
    /// `b = 3`: `w`, negated on the `k` walls.
    W,
}

// ---------------------------------------------------------------------------
// Solver
// ---------------------------------------------------------------------------

/// 3D stable-fluids solver of thesis Ch. 2 on an `(N+2)³` grid with walls.
///
/// ```
/// use grassbench::wind::fluid::{StamParams, StamSolver};
/// let mut fluid = StamSolver::new(StamParams::default())?;
/// for _ in 0..10 {
///     fluid.step(0.1);
/// }
/// let wind = fluid.velocity_at([4.5, 2.0, 4.5]);
/// assert!(wind.is_finite());
/// # Ok::<(), grassbench::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct StamSolver {
    params: StamParams,
    grid: Grid,
    u: Vec<f32>,
    v: Vec<f32>,
    w: Vec<f32>,
    u_prev: Vec<f32>,
    v_prev: Vec<f32>,
    w_prev: Vec<f32>,
    dens: Vec<f32>,
    dens_prev: Vec<f32>,
    /// One grid row, reused by every Gauss–Seidel sweep.
    row_scratch: Vec<f32>,
    /// Per coordinate `c` in `1..=N`: the interior indices standing for `c − 2` and `c + 2`
    /// in the consistent Poisson stencil (mirrored about the wall faces).
    wide: Vec<(usize, usize)>,
    rng: Rng,
}

impl StamSolver {
    /// Validates `params` and allocates every array (all fields start at
    /// zero, Sec. 2.2 "In the initial time ...").
    pub fn new(params: StamParams) -> Result<Self> {
        params.validate()?;
        let grid = Grid::new(params.n);
        let len = grid.len();
        let zeros = || vec![0.0_f32; len];
        Ok(Self {
            rng: Rng::new(params.seed),
            params,
            grid,
            u: zeros(),
            v: zeros(),
            w: zeros(),
            u_prev: zeros(),
            v_prev: zeros(),
            w_prev: zeros(),
            dens: zeros(),
            dens_prev: zeros(),
            row_scratch: vec![0.0; grid.s],
            wide: wide_neighbours(grid.n),
        })
    }

    /// Zeroes every field and re-seeds the PRNG: afterwards the solver
    /// replays exactly the same sequence as a freshly constructed one.
    pub fn reset(&mut self) {
        for a in [
            &mut self.u,
            &mut self.v,
            &mut self.w,
            &mut self.u_prev,
            &mut self.v_prev,
            &mut self.w_prev,
            &mut self.dens,
            &mut self.dens_prev,
        ] {
            a.fill(0.0);
        }
        self.rng = Rng::new(self.params.seed);
    }

    /// Interior cells per axis, `N`.
    pub fn n(&self) -> usize {
        self.grid.n
    }

    /// Cells per axis including the walls, `N + 2`.
    pub fn size(&self) -> usize {
        self.grid.s
    }

    /// The (validated) parameters the solver was built with.
    pub fn params(&self) -> &StamParams {
        &self.params
    }

    /// Flat index of cell `(i, j, k)`, each in `0..=N+1`:
    /// `i + (N+2)·(j + (N+2)·k)` (`i` fastest).
    #[inline]
    pub fn ix(&self, i: usize, j: usize, k: usize) -> usize {
        self.grid.ix(i, j, k)
    }

    /// x velocity component, `(N+2)³` values indexed by [`Self::ix`].
    pub fn u(&self) -> &[f32] {
        &self.u
    }

    /// y velocity component (y is up in the thesis' scene, Sec. 5.1).
    pub fn v(&self) -> &[f32] {
        &self.v
    }

    /// z velocity component.
    pub fn w(&self) -> &[f32] {
        &self.w
    }

    /// Density ρ of Eq. (1).
    pub fn density(&self) -> &[f32] {
        &self.dens
    }

    /// The "previous" arrays `[u0, v0, w0, dens0]` of the thesis. After a
    /// step they hold solver scratch (pressure, divergence, pre-advection
    /// fields); they are cleared and refilled with sources at each step.
    pub fn prev_fields(&self) -> [&[f32]; 4] {
        [&self.u_prev, &self.v_prev, &self.w_prev, &self.dens_prev]
    }

    /// Mutable access to `[u, v, w]`, e.g. to set initial conditions.
    /// Wall cells are overwritten by the next boundary pass.
    pub fn velocity_mut(&mut self) -> [&mut [f32]; 3] {
        [&mut self.u, &mut self.v, &mut self.w]
    }

    /// Mutable access to the density, e.g. to set initial conditions.
    pub fn density_mut(&mut self) -> &mut [f32] {
        &mut self.dens
    }

    /// Advances the simulation by `dt` seconds: writes this step's random
    /// sources into the source cell (Sec. 2.2, 2.3.1), then runs
    /// [`Self::vel_step`] and [`Self::dens_step`] (the same order as Stam's
    /// demo loop: velocity first, so density is advected by the new field).
    ///
    /// A `dt` that is negative or not finite would make the implicit solves
    /// meaningless; such a call leaves the solver untouched.
    pub fn step(&mut self, dt: f32) {
        if !(dt.is_finite() && dt >= 0.0) {
            return;
        }
        self.inject_sources();
        self.vel_step(dt);
        self.dens_step(dt);
    }

    /// Clears the "previous" arrays and writes the seeded random sources of
    /// this step into the source cell: a velocity uniform in the cube
    /// `[-1,1)³`, radially clamped to the unit ball, times `source_strength`;
    /// a density uniform in `[0, source_density)`. Exactly four PRNG draws.
    fn inject_sources(&mut self) {
        for a in [
            &mut self.u_prev,
            &mut self.v_prev,
            &mut self.w_prev,
            &mut self.dens_prev,
        ] {
            a.fill(0.0);
        }
        let mut dir = Vec3::new(
            self.rng.range(-1.0, 1.0),
            self.rng.range(-1.0, 1.0),
            self.rng.range(-1.0, 1.0),
        );
        let len = dir.length();
        if len > 1.0 {
            dir /= len;
        }
        let dir = dir * self.params.source_strength;
        let d = self.rng.next_f32() * self.params.source_density;
        let [i, j, k] = self.params.source_cell;
        let c = self.grid.ix(i, j, k);
        self.u_prev[c] = dir.x;
        self.v_prev[c] = dir.y;
        self.w_prev[c] = dir.z;
        self.dens_prev[c] = d;
    }

    /// Velocity step, thesis Sec. 2.3.5 (`vel_step`): forces from the
    /// "previous" arrays, viscous diffusion (Eq. 4), projection (Sec. 2.3.6),
    /// self-advection (Sec. 2.3.3), projection again. The `SWAP` macro of the
    /// thesis is a pointer swap of the two `Vec`s (no copy, no allocation).
    pub fn vel_step(&mut self, dt: f32) {
        let g = self.grid;
        let iters = self.params.iterations;
        let visc = self.params.viscosity;

        // add force
        add_source(&mut self.u, &self.u_prev, dt);
        add_source(&mut self.v, &self.v_prev, dt);
        add_source(&mut self.w, &self.w_prev, dt);
        // viscous diffusion
        std::mem::swap(&mut self.u_prev, &mut self.u);
        let t = &mut self.row_scratch;
        diffuse(g, Bound::U, &mut self.u, &self.u_prev, visc, dt, iters, t);
        std::mem::swap(&mut self.v_prev, &mut self.v);
        diffuse(g, Bound::V, &mut self.v, &self.v_prev, visc, dt, iters, t);
        std::mem::swap(&mut self.w_prev, &mut self.w);
        diffuse(g, Bound::W, &mut self.w, &self.w_prev, visc, dt, iters, t);
        // mass conserving (u0 = pressure, v0 = divergence scratch)
        self.project_with_iterations(iters);
        std::mem::swap(&mut self.u_prev, &mut self.u);
        std::mem::swap(&mut self.v_prev, &mut self.v);
        std::mem::swap(&mut self.w_prev, &mut self.w);
        // self-advection by the (projected) previous field
        let vel0 = [&self.u_prev[..], &self.v_prev[..], &self.w_prev[..]];
        advect(g, Bound::U, &mut self.u, &self.u_prev, vel0, dt);
        advect(g, Bound::V, &mut self.v, &self.v_prev, vel0, dt);
        advect(g, Bound::W, &mut self.w, &self.w_prev, vel0, dt);
        // mass conserving
        self.project_with_iterations(iters);
    }

    /// Density step, thesis Sec. 2.3.4 (`dens_step`): add source (2.3.1),
    /// diffuse (2.3.2, Eq. 4), advect along the current velocity (2.3.3).
    pub fn dens_step(&mut self, dt: f32) {
        let g = self.grid;
        let iters = self.params.iterations;
        let diff = self.params.diffusion;
        add_source(&mut self.dens, &self.dens_prev, dt);
        std::mem::swap(&mut self.dens_prev, &mut self.dens);
        diffuse(
            g,
            Bound::Scalar,
            &mut self.dens,
            &self.dens_prev,
            diff,
            dt,
            iters,
            &mut self.row_scratch,
        );
        std::mem::swap(&mut self.dens_prev, &mut self.dens);
        let vel = [&self.u[..], &self.v[..], &self.w[..]];
        advect(g, Bound::Scalar, &mut self.dens, &self.dens_prev, vel, dt);
    }

    /// Projects the current velocity onto its divergence-free part
    /// (Sec. 2.3.6) with `iterations` Gauss–Seidel sweeps for the Poisson
    /// solve (clamped to `1..=1000`). Uses `u0`/`v0` as pressure/divergence
    /// scratch; `vel_step` calls it twice with the configured sweep count.
    pub fn project_with_iterations(&mut self, iterations: u32) {
        project(
            self.grid,
            [&mut self.u, &mut self.v, &mut self.w],
            &mut self.u_prev,
            &mut self.v_prev,
            Solve {
                iters: iterations.clamp(1, MAX_ITERATIONS),
                poisson: self.params.poisson,
                wide: &self.wide,
                scratch: &mut self.row_scratch,
            },
        );
    }

    /// Trilinearly interpolated velocity (Sec. 3.2.2) at continuous grid
    /// coordinates `p`: cell `(i, j, k)` has its centre at `p = (i, j, k)`,
    /// so interior centres are `1..=N` and the walls sit at `0` and `N+1`.
    /// Coordinates are clamped into `[0, N+1]`; a NaN coordinate yields NaN.
    /// Units: domain lengths per second (see module docs).
    pub fn velocity_at(&self, p: impl Into<Vec3>) -> Vec3 {
        let p = p.into();
        let c = self.sample_coords(p);
        let (corner, weights) = trilerp_weights(self.grid, c);
        Vec3::new(
            trilerp_with(self.grid, &self.u, corner, weights),
            trilerp_with(self.grid, &self.v, corner, weights),
            trilerp_with(self.grid, &self.w, corner, weights),
        )
    }

    /// Trilinearly interpolated density at `p`; same conventions as
    /// [`Self::velocity_at`].
    pub fn density_at(&self, p: impl Into<Vec3>) -> f32 {
        trilerp(self.grid, &self.dens, self.sample_coords(p.into()))
    }

    fn sample_coords(&self, p: Vec3) -> Vec3 {
        let hi = (self.grid.n + 1) as f32;
        // `f32::clamp` propagates NaN instead of panicking (bounds are valid).
        Vec3::new(p.x.clamp(0.0, hi), p.y.clamp(0.0, hi), p.z.clamp(0.0, hi))
    }

    /// Largest |∇·u| over the interior cells, central differences with the
    /// wall values (the quantity `project` drives to zero), in 1/s.
    pub fn divergence_max_abs(&self) -> f32 {
        let mut m = 0.0_f32;
        self.for_each_divergence(|d| m = m.max(d.abs()));
        m
    }

    /// Euclidean norm `sqrt(Σ (∇·u)²)` over the interior cells (1/s).
    pub fn divergence_l2(&self) -> f32 {
        let mut s = 0.0_f64;
        self.for_each_divergence(|d| s += f64::from(d) * f64::from(d));
        s.sqrt() as f32
    }

    /// Σ density over the interior cells (f64 accumulation).
    pub fn total_density(&self) -> f64 {
        let g = self.grid;
        let mut s = 0.0_f64;
        for k in 1..=g.n {
            for j in 1..=g.n {
                let r = g.ix(1, j, k);
                s += self.dens[r..r + g.n]
                    .iter()
                    .map(|&d| f64::from(d))
                    .sum::<f64>();
            }
        }
        s
    }

    /// Largest velocity magnitude over all cells (walls included).
    pub fn max_speed(&self) -> f32 {
        self.u
            .iter()
            .zip(&self.v)
            .zip(&self.w)
            .map(|((&u, &v), &w)| (u * u + v * v + w * w).sqrt())
            .fold(0.0, f32::max)
    }

    fn for_each_divergence(&self, mut f: impl FnMut(f32)) {
        let g = self.grid;
        let (s, p) = (g.s, g.plane);
        // (∂u/∂x + ∂v/∂y + ∂w/∂z) with central differences, h = 1/N.
        let scale = 0.5 * g.n as f32;
        for k in 1..=g.n {
            for j in 1..=g.n {
                for i in 1..=g.n {
                    let c = g.ix(i, j, k);
                    let d = (self.u[c + 1] - self.u[c - 1])
                        + (self.v[c + s] - self.v[c - s])
                        + (self.w[c + p] - self.w[c - p]);
                    f(scale * d);
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------
// The building blocks of Ch. 2 (free functions so disjoint fields can be
// borrowed independently, mirroring the C signatures of the thesis)
// ---------------------------------------------------------------------------

/// `add_source(N, x, s, dt)`: `x += dt · s` (Sec. 2.3.1, the `S` / `f` terms
/// of Eqs. 1–2).
fn add_source(x: &mut [f32], s: &[f32], dt: f32) {
    for (x, &s) in x.iter_mut().zip(s) {
        *x += dt * s;
    }
}

/// `diffuse(N, b, x, x0, diff, dt)`, Sec. 2.3.2: the implicit (backward
/// Euler) diffusion of Eq. (4), `x0 = x - a·(Σ₆ neighbours - 6x)`, solved by
/// Gauss–Seidel.
///
/// `a = dt · diff · LENGTH·HEIGHT·DEPTH` in the thesis' pseudo-code, i.e.
/// `dt·diff·N³`. (The dimensionally consistent `dt·diff/h²` would be
/// `dt·diff·N²`; the thesis' choice only rescales the coefficient by `N`, so
/// it is kept verbatim for reproducibility.)
#[allow(clippy::too_many_arguments)]
fn diffuse(
    g: Grid,
    b: Bound,
    x: &mut [f32],
    x0: &[f32],
    diff: f32,
    dt: f32,
    iters: u32,
    scratch: &mut [f32],
) {
    let n = g.n as f32;
    let a = dt * diff * n * n * n;
    lin_solve(g, b, x, x0, a, 1.0 + 6.0 * a, iters, scratch);
}

/// `linear_solver(N, b, x, x0, a, c)`, Sec. 2.3.2: `iters` lexicographic
/// Gauss–Seidel sweeps of
/// `x[i,j,k] = (x0[i,j,k] + a·(x[i±1,j,k] + x[i,j±1,k] + x[i,j,k±1])) / c`,
/// followed by `set_bound` after each sweep.
///
/// Each row is done in two passes so the compiler can vectorise the bulk of
/// the work: pass 1 gathers the five neighbours that are already final for
/// this update (`i+1` is not yet updated in lexicographic order, `j-1`/`k-1`
/// already are, `j+1`/`k+1` are not) — all independent, SIMD-friendly; pass 2
/// is the inherently sequential `i-1` recurrence. This is still exactly the
/// Gauss–Seidel iteration of the thesis; only the floating-point summation
/// order differs.
#[allow(clippy::too_many_arguments)]
fn lin_solve(
    g: Grid,
    b: Bound,
    x: &mut [f32],
    x0: &[f32],
    a: f32,
    c: f32,
    iters: u32,
    scratch: &mut [f32],
) {
    let (n, s, p) = (g.n, g.s, g.plane);
    let inv_c = 1.0 / c;
    let t = &mut scratch[..n];
    for _ in 0..iters {
        for k in 1..=n {
            for j in 1..=n {
                let base = g.ix(0, j, k);
                // Split the array so the current row is mutable while its four
                // off-row neighbours are read (no unsafe aliasing needed).
                let (lo, rest) = x.split_at_mut(base);
                let (row, hi) = rest.split_at_mut(s);
                let y_lo = &lo[base - s + 1..base - s + 1 + n];
                let z_lo = &lo[base - p + 1..base - p + 1 + n];
                let y_hi = &hi[1..1 + n];
                let z_hi = &hi[p - s + 1..p - s + 1 + n];
                let src = &x0[base + 1..base + 1 + n];
                let x_hi = &row[2..2 + n];
                for i in 0..n {
                    t[i] = src[i] + a * (x_hi[i] + y_lo[i] + y_hi[i] + z_lo[i] + z_hi[i]);
                }
                let mut left = row[0];
                for (xi, &ti) in row[1..=n].iter_mut().zip(t.iter()) {
                    left = (ti + a * left) * inv_c;
                    *xi = left;
                }
            }
        }
        set_bound(g, b, x);
    }
}

/// `advect(N, b, d, d0, u, v, w, dt)`, Sec. 2.3.3: semi-Lagrangian advection.
/// Each cell centre is traced back one step, `x = i - dt·N·u`, the back-trace
/// is clamped into `[0.5, N+0.5]` (Stam's clamp; it keeps all eight samples
/// inside the grid including walls), and `d0` is trilinearly interpolated
/// there. Unconditionally stable: every new value is a convex combination of
/// old ones.
fn advect(g: Grid, b: Bound, d: &mut [f32], d0: &[f32], vel: [&[f32]; 3], dt: f32) {
    let n = g.n;
    let dt0 = dt * n as f32;
    let (lo, hi) = (0.5_f32, n as f32 + 0.5);
    let [u, v, w] = vel;
    for k in 1..=n {
        for j in 1..=n {
            let r = g.ix(0, j, k);
            for i in 1..=n {
                let c = r + i;
                let x = (i as f32 - dt0 * u[c]).clamp(lo, hi);
                let y = (j as f32 - dt0 * v[c]).clamp(lo, hi);
                let z = (k as f32 - dt0 * w[c]).clamp(lo, hi);
                d[c] = trilerp(g, d0, Vec3::new(x, y, z));
            }
        }
    }
    set_bound(g, b, d);
}

/// Trilinear interpolation of `f` at grid coordinates `p`, which the caller
/// has clamped into `[0, N+1]³`. A NaN coordinate casts to index 0 (no
/// out-of-bounds access) and propagates NaN through the weights.
#[inline(always)]
fn trilerp(g: Grid, f: &[f32], p: Vec3) -> f32 {
    let (corner, weights) = trilerp_weights(g, p);
    trilerp_with(g, f, corner, weights)
}

/// The lower corner cell and the fractional weights `(r1, s1, t1)` of `p` (see [`trilerp`]),
/// computed once when several fields are sampled at the same point.
#[inline(always)]
fn trilerp_weights(g: Grid, p: Vec3) -> (usize, Vec3) {
    let top = g.n; // lower corner index at most N, so +1 stays in the wall
    let i0 = (p.x as usize).min(top);
    let j0 = (p.y as usize).min(top);
    let k0 = (p.z as usize).min(top);
    let w = Vec3::new(p.x - i0 as f32, p.y - j0 as f32, p.z - k0 as f32);
    (g.ix(i0, j0, k0), w)
}

#[inline(always)]
fn trilerp_with(g: Grid, f: &[f32], c: usize, w: Vec3) -> f32 {
    let (r1, s1, t1) = (w.x, w.y, w.z);
    let (r0, s0, t0) = (1.0 - r1, 1.0 - s1, 1.0 - t1);
    let (dy, dz) = (g.s, g.plane);
    let lerp_x = |c: usize| r0 * f[c] + r1 * f[c + 1];
    let plane = |c: usize| s0 * lerp_x(c) + s1 * lerp_x(c + dy);
    t0 * plane(c) + t1 * plane(c + dz)
}

/// How `project` solves its Poisson equation.
struct Solve<'a> {
    iters: u32,
    poisson: Poisson,
    /// [`wide_neighbours`] of the grid.
    wide: &'a [(usize, usize)],
    scratch: &'a mut [f32],
}

/// `project(N, u, v, w, p, div)`, Sec. 2.3.6: Helmholtz–Hodge projection.
///
/// 1. `div = -½ (Δᵢu + Δⱼv + Δₖw)` (central differences, wall cells from `set_bound`),
/// 2. Poisson solve by Gauss–Seidel: with [`Poisson::Compact`] the thesis'
///    `linear_solver(N, 0, p, div, 1, 6)`, i.e. `Σ₆ p_nb − 6p = −div`; with
///    [`Poisson::Consistent`] the `div∘grad` operator `(Σ₆ p_nb2 − 6p)/4 = −div` over the
///    neighbours two cells away, mirrored at the walls (module docs),
/// 3. `u -= ½ Δᵢp`, `v -= ½ Δⱼp`, `w -= ½ Δₖp`, then `set_bound` per axis.
///
/// Written with unit cell length, exactly the thesis pseudo-code with `gridCellLength = 1`.
/// For any consistent cell size `h` (Stam: `div` scaled by `h`, gradient by `1/h`) the `h`
/// factors cancel, so this is also exactly Stam's unit-cube projection.
fn project(g: Grid, vel: [&mut [f32]; 3], p: &mut [f32], div: &mut [f32], solve: Solve<'_>) {
    let [u, v, w] = vel;
    let (n, s, pl) = (g.n, g.s, g.plane);
    // The consistent operator is the compact one's divided by 4: fold the 4 into the source.
    let scale = match solve.poisson {
        Poisson::Compact => -0.5,
        Poisson::Consistent => -2.0,
    };
    for k in 1..=n {
        for j in 1..=n {
            let r = g.ix(0, j, k);
            for c in r + 1..=r + n {
                div[c] = scale
                    * ((u[c + 1] - u[c - 1]) + (v[c + s] - v[c - s]) + (w[c + pl] - w[c - pl]));
                p[c] = 0.0;
            }
        }
    }
    set_bound(g, Bound::Scalar, div);
    set_bound(g, Bound::Scalar, p);
    match solve.poisson {
        Poisson::Compact => lin_solve(
            g,
            Bound::Scalar,
            p,
            div,
            1.0,
            6.0,
            solve.iters,
            solve.scratch,
        ),
        Poisson::Consistent => lin_solve_wide(g, p, div, solve.iters, solve.wide, solve.scratch),
    }
    for k in 1..=n {
        for j in 1..=n {
            let r = g.ix(0, j, k);
            for c in r + 1..=r + n {
                u[c] -= 0.5 * (p[c + 1] - p[c - 1]);
                v[c] -= 0.5 * (p[c + s] - p[c - s]);
                w[c] -= 0.5 * (p[c + pl] - p[c - pl]);
            }
        }
    }
    set_bound(g, Bound::U, u);
    set_bound(g, Bound::V, v);
    set_bound(g, Bound::W, w);
}

/// For every interior coordinate `c` in `1..=n` (index `c`; index 0 and `n+1` unused): the
/// interior coordinates that stand for `c − 2` and `c + 2` in the `div∘grad` stencil. Beyond a
/// wall the index mirrors about the wall face at `½` (resp. `n + ½`): `c − 2 < 1` becomes
/// `3 − c`, `c + 2 > n` becomes `2n − 1 − c`. (With `set_bound`'s `p[0] = p[1]` and
/// `u[0] = −u[1]`, the central divergence of the central gradient at `c = 1` is
/// `(p[3] + p[2] − 2p[1]) / 4` and at `c = 2` it is `(p[4] − 2p[2] + p[1]) / 4`: exactly
/// this mirror rule.) For `n = 2` both neighbours of either cell are the other cell.
fn wide_neighbours(n: usize) -> Vec<(usize, usize)> {
    (0..n + 2)
        .map(|c| {
            if c == 0 || c > n {
                return (c, c);
            }
            let lo = if c >= 3 { c - 2 } else { 3 - c };
            let hi = if c + 2 <= n { c + 2 } else { 2 * n - 1 - c };
            (lo.clamp(1, n), hi.clamp(1, n))
        })
        .collect()
}

/// Gauss–Seidel sweeps of the consistent Poisson equation
/// `p = (x0 + Σ₆ p_nb2) / 6` (see [`project`]), lexicographic order, `set_bound` after
/// each sweep. Per row, pass 1 gathers the four off-row neighbours (other rows, so their
/// values are those lexicographic Gauss–Seidel sees), pass 2 runs the in-row `i ± 2`
/// recurrence in order.
fn lin_solve_wide(
    g: Grid,
    x: &mut [f32],
    x0: &[f32],
    iters: u32,
    wide: &[(usize, usize)],
    scratch: &mut [f32],
) {
    let n = g.n;
    let inv_c = 1.0 / 6.0;
    let t = &mut scratch[..n];
    for _ in 0..iters {
        for k in 1..=n {
            let (k_lo, k_hi) = wide[k];
            for j in 1..=n {
                let (j_lo, j_hi) = wide[j];
                let base = g.ix(0, j, k);
                let (y_lo, y_hi) = (g.ix(0, j_lo, k), g.ix(0, j_hi, k));
                let (z_lo, z_hi) = (g.ix(0, j, k_lo), g.ix(0, j, k_hi));
                for (i, ti) in t.iter_mut().enumerate() {
                    let c = i + 1;
                    *ti = x0[base + c] + x[y_lo + c] + x[y_hi + c] + x[z_lo + c] + x[z_hi + c];
                }
                for (i, &ti) in t.iter().enumerate() {
                    let c = i + 1;
                    let (lo, hi) = wide[c];
                    x[base + c] = (ti + x[base + lo] + x[base + hi]) * inv_c;
                }
            }
        }
        set_bound(g, Bound::Scalar, x);
    }
}

/// `set_bound(N, b, x)`, Sec. 2.3.7, Stam's 2D routine extended to 3D:
///
/// * faces: copy the adjacent interior cell, negated when the array is the
///   velocity component normal to that wall (`b = 1, 2, 3` for the `i`, `j`,
///   `k` walls) so the normal velocity vanishes on the wall; scalars
///   (`b = 0`) get a zero-gradient (Neumann) wall;
/// * the 12 edges: average of the two face cells next to them (this is what
///   Stam's 2D corner rule `x[0,0] = ½(x[1,0] + x[0,1])` becomes per edge);
/// * the 8 corners: average of the three edge cells next to them.
fn set_bound(g: Grid, b: Bound, x: &mut [f32]) {
    let n = g.n;
    let e = n + 1;
    let sign = |wall: Bound| if b == wall { -1.0_f32 } else { 1.0 };
    let (sx, sy, sz) = (sign(Bound::U), sign(Bound::V), sign(Bound::W));

    // Faces. Loops keep i innermost wherever the face allows it.
    for k in 1..=n {
        for j in 1..=n {
            x[g.ix(0, j, k)] = sx * x[g.ix(1, j, k)];
            x[g.ix(e, j, k)] = sx * x[g.ix(n, j, k)];
        }
        for i in 1..=n {
            x[g.ix(i, 0, k)] = sy * x[g.ix(i, 1, k)];
            x[g.ix(i, e, k)] = sy * x[g.ix(i, n, k)];
        }
    }
    for j in 1..=n {
        for i in 1..=n {
            x[g.ix(i, j, 0)] = sz * x[g.ix(i, j, 1)];
            x[g.ix(i, j, e)] = sz * x[g.ix(i, j, n)];
        }
    }

    // (wall index, its interior neighbour) along one axis.
    let walls = [(0, 1), (e, n)];

    // Edges.
    for &(j, jn) in &walls {
        for &(k, kn) in &walls {
            for i in 1..=n {
                x[g.ix(i, j, k)] = 0.5 * (x[g.ix(i, jn, k)] + x[g.ix(i, j, kn)]);
            }
        }
    }
    for &(i, inn) in &walls {
        for &(k, kn) in &walls {
            for j in 1..=n {
                x[g.ix(i, j, k)] = 0.5 * (x[g.ix(inn, j, k)] + x[g.ix(i, j, kn)]);
            }
        }
    }
    for &(i, inn) in &walls {
        for &(j, jn) in &walls {
            for k in 1..=n {
                x[g.ix(i, j, k)] = 0.5 * (x[g.ix(inn, j, k)] + x[g.ix(i, jn, k)]);
            }
        }
    }

    // Corners.
    for &(i, inn) in &walls {
        for &(j, jn) in &walls {
            for &(k, kn) in &walls {
                x[g.ix(i, j, k)] =
                    (x[g.ix(inn, j, k)] + x[g.ix(i, jn, k)] + x[g.ix(i, j, kn)]) * (1.0 / 3.0);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solver(n: usize, f: impl FnOnce(&mut StamParams)) -> StamSolver {
        let mut p = StamParams {
            n,
            source_cell: [n / 2, n / 2, n / 2].map(|c| c.max(1)),
            ..StamParams::default()
        };
        f(&mut p);
        StamSolver::new(p).expect("valid params")
    }

    /// Random divergent velocity: uniform in [-1, 1) per component at every
    /// interior cell, walls via set_bound.
    fn randomize_velocity(s: &mut StamSolver, seed: u64) {
        let g = s.grid;
        let mut rng = Rng::new(seed);
        for a in [&mut s.u, &mut s.v, &mut s.w] {
            for k in 1..=g.n {
                for j in 1..=g.n {
                    for i in 1..=g.n {
                        a[g.ix(i, j, k)] = rng.range(-1.0, 1.0);
                    }
                }
            }
        }
        set_bound(g, Bound::U, &mut s.u);
        set_bound(g, Bound::V, &mut s.v);
        set_bound(g, Bound::W, &mut s.w);
    }

    /// Random smooth *potential* (pure-gradient, maximally divergent) field
    /// that already satisfies the walls: u = ∂φ/∂x etc. with
    /// φ = Σ a·cos(mx·π(i−½)/N)·cos(my·π(j−½)/N)·cos(mz·π(k−½)/N), 1 ≤ |m|, m ≤ mmax,
    /// differentiated analytically, so the normal component vanishes on the
    /// wall faces (i = ½, N + ½).
    fn potential_velocity(s: &mut StamSolver, seed: u64, mmax: u32) {
        let g = s.grid;
        let mut rng = Rng::new(seed);
        let h = std::f32::consts::PI / g.n as f32;
        for a in [&mut s.u, &mut s.v, &mut s.w] {
            a.fill(0.0);
        }
        for mx in 0..=mmax {
            for my in 0..=mmax {
                for mz in 0..=mmax {
                    if mx + my + mz == 0 {
                        continue;
                    }
                    let amp = rng.range(-1.0, 1.0);
                    let m = [mx, my, mz].map(|m| m as f32 * h);
                    for k in 1..=g.n {
                        for j in 1..=g.n {
                            for i in 1..=g.n {
                                let x = [i, j, k].map(|c| c as f32 - 0.5);
                                let (cx, cy, cz) = (
                                    (m[0] * x[0]).cos(),
                                    (m[1] * x[1]).cos(),
                                    (m[2] * x[2]).cos(),
                                );
                                let (sx, sy, sz) = (
                                    (m[0] * x[0]).sin(),
                                    (m[1] * x[1]).sin(),
                                    (m[2] * x[2]).sin(),
                                );
                                let c = g.ix(i, j, k);
                                s.u[c] += -amp * m[0] * sx * cy * cz;
                                s.v[c] += -amp * m[1] * cx * sy * cz;
                                s.w[c] += -amp * m[2] * cx * cy * sz;
                            }
                        }
                    }
                }
            }
        }
        set_bound(g, Bound::U, &mut s.u);
        set_bound(g, Bound::V, &mut s.v);
        set_bound(g, Bound::W, &mut s.w);
    }

    /// ‖div − (6p − Σ₆ p_nb)‖₂ over the interior after a projection: the
    /// residual of the Poisson equation that the Gauss–Seidel sweeps solve.
    fn poisson_residual(s: &StamSolver) -> (f64, f64) {
        let g = s.grid;
        let (p, div) = (&s.u_prev, &s.v_prev);
        let (mut r2, mut d2) = (0.0f64, 0.0f64);
        for k in 1..=g.n {
            for j in 1..=g.n {
                for i in 1..=g.n {
                    let c = g.ix(i, j, k);
                    let lap = 6.0 * p[c]
                        - p[c - 1]
                        - p[c + 1]
                        - p[c - g.s]
                        - p[c + g.s]
                        - p[c - g.plane]
                        - p[c + g.plane];
                    let r = f64::from(div[c] - lap);
                    r2 += r * r;
                    d2 += f64::from(div[c]) * f64::from(div[c]);
                }
            }
        }
        (r2.sqrt(), d2.sqrt())
    }

    /// N = 16, no sources, a 7³ block of unit density in the middle and
    /// (optionally) a rigid swirl about the vertical axis (divergence-free in
    /// the continuum) with peak speed `speed` (domain lengths / s).
    fn closed_box(speed: f32) -> StamSolver {
        let mut s = solver(16, |p| {
            p.source_strength = 0.0;
            p.source_density = 0.0;
        });
        let g = s.grid;
        let c = (g.n as f32 + 1.0) * 0.5;
        let half = g.n as f32 * 0.5;
        for k in 1..=g.n {
            for j in 1..=g.n {
                for i in 1..=g.n {
                    let x = g.ix(i, j, k);
                    if (5..=11).contains(&i) && (5..=11).contains(&j) && (5..=11).contains(&k) {
                        s.dens[x] = 1.0;
                    }
                    s.u[x] = -speed * (k as f32 - c) / half;
                    s.w[x] = speed * (i as f32 - c) / half;
                }
            }
        }
        set_bound(g, Bound::U, &mut s.u);
        set_bound(g, Bound::W, &mut s.w);
        set_bound(g, Bound::Scalar, &mut s.dens);
        s
    }

    // -- 1. Projection --------------------------------------------------------

    fn compact(p: &mut StamParams) {
        p.poisson = Poisson::Compact;
    }

    /// Divergence before / after one projection with the default parameters (consistent
    /// Poisson operator, the thesis' 20 Gauss–Seidel sweeps), measured with central
    /// differences, L2 and max norms.
    fn reduction(n: usize, iters: u32, smooth: bool, f: fn(&mut StamParams)) -> (f32, f32) {
        let mut s = solver(n, f);
        if smooth {
            potential_velocity(&mut s, 3, 1);
        } else {
            randomize_velocity(&mut s, 7);
        }
        let (l0, m0) = (s.divergence_l2(), s.divergence_max_abs());
        s.project_with_iterations(iters);
        (l0 / s.divergence_l2(), m0 / s.divergence_max_abs())
    }

    /// The issue's criterion: projection reduces the divergence at least 100x. White-noise
    /// velocity (every mode present), default parameters, 20 sweeps. Measured (L2 / max):
    /// N = 8: 1478x / 762x; N = 16: 379x / 248x; N = 32: 339x / 323x. The thesis' compact
    /// operator gives ~1.5x here at any sweep count (next test), so this fails if the
    /// projection is not consistent with the divergence it is measured by, or if the sweeps
    /// do not converge (5 sweeps give 64x / 41x at N = 8).
    #[test]
    fn projection_reduces_divergence_100x() {
        for n in [8, 16, 32] {
            let (l2, max) = reduction(n, 20, false, |_| {});
            assert!(l2 >= 100.0 && max >= 100.0, "n={n}: {l2:.1}x / {max:.1}x");
        }
        // Known limit, asserted so it is not forgotten: Gauss–Seidel is slow on the smoothest
        // mode, so a pure lowest-mode field drops 78x (N = 8) and 3.9x (N = 16) in 20 sweeps
        // (more sweeps help: 4755x and 11.5x at 40). Bounds sit below those measurements.
        let (smooth8, _) = reduction(8, 20, true, |_| {});
        assert!(smooth8 > 50.0, "{smooth8}");
        let (smooth16, _) = reduction(16, 20, true, |_| {});
        assert!(smooth16 > 3.0, "{smooth16}");
    }

    /// With the sweeps converged, the consistent operator removes the central divergence to
    /// rounding: measured 1.2e7x (white, N = 8) and 2.6e6x / 7.2e5x (smooth, N = 8 / 16)
    /// after 1000 sweeps. A mistake in the wall mirroring would leave O(1) divergence in the
    /// wall cells (like the compact operator's 26x limit below).
    #[test]
    fn consistent_operator_removes_divergence_exactly_when_converged() {
        for (n, smooth) in [(8, false), (8, true), (16, true)] {
            let (l2, _) = reduction(n, 1000, smooth, |_| {});
            assert!(l2 > 1.0e5, "n={n} smooth={smooth}: {l2:.3e}x");
        }
    }

    /// The part of the compact (thesis) `project` that the iteration count controls: the
    /// Gauss–Seidel solve of its Poisson equation. On a white-noise divergent field the
    /// residual drops ≥100x with these *minimal* sweep counts (measured by scanning
    /// 1..=1500): 29 sweeps for N = 8, 23 for N = 16. The thesis' 20 sweeps give only 69x
    /// (N = 8) and 90x (N = 16).
    #[test]
    fn compact_poisson_solve_reaches_100x() {
        for (n, iters) in [(8, 29), (16, 23)] {
            let mut s = solver(n, compact);
            randomize_velocity(&mut s, 1);
            s.project_with_iterations(iters);
            let (r, d) = poisson_residual(&s);
            assert!(d / r >= 100.0, "n={n}: residual only reduced {:.1}x", d / r);
        }
    }

    /// Divergence reduction of the thesis' compact projection. On a collocated grid the
    /// divergence is measured with central differences (stencil 2h) but the compact Poisson
    /// matrix is the 7-point Laplacian, so even an exact solve leaves
    /// `div_after = (L_compact − L_wide) p`. For a Fourier mode of wavenumber θ per axis this
    /// leaves exactly a fraction sin²(θ/2) of the divergence. Consequences (measured, and
    /// asserted below):
    ///
    /// * white noise: only ~1.5x at any sweep count (20 … 1000);
    /// * smoothest wall-compatible potential field (θ = π/N): at most 1/sin²(π/2N) = 26.3x
    ///   for N = 8 — 100x is impossible for N = 8 with this scheme — and 104.1x for N = 16,
    ///   which first reaches 100x after 483 Gauss–Seidel sweeps (20 sweeps give 1.1x–1.6x).
    #[test]
    fn compact_divergence_reduction_matches_collocated_theory() {
        // White noise: reduced, but discretisation-limited (measured 1.6x / 1.5x).
        for n in [8, 16] {
            let (ratio, _) = reduction(n, 20, false, compact);
            assert!(
                ratio > 1.4 && ratio < 2.0,
                "n={n}: white-noise ratio {ratio}"
            );
            let (converged, _) = reduction(n, 1000, false, compact);
            assert!(converged < 2.0, "n={n}: converged ratio {converged}");
        }
        // Smooth field, converged solve: matches 1/sin²(π/2N) to 1 %.
        for n in [8usize, 16] {
            let mut s = solver(n, compact);
            potential_velocity(&mut s, 3, 1);
            let (m0, l0) = (s.divergence_max_abs(), s.divergence_l2());
            s.project_with_iterations(1000);
            let theory = 1.0 / (std::f32::consts::PI / (2 * n) as f32).sin().powi(2);
            for ratio in [m0 / s.divergence_max_abs(), l0 / s.divergence_l2()] {
                assert!(
                    (ratio / theory - 1.0).abs() < 0.01,
                    "n={n}: {ratio} vs {theory}"
                );
            }
        }
        // 100x reachable for N = 16 only, on the smoothest field: minimal sweeps 483.
        let mut s = solver(16, compact);
        potential_velocity(&mut s, 1, 1);
        let (m0, l0) = (s.divergence_max_abs(), s.divergence_l2());
        s.project_with_iterations(483);
        assert!(m0 / s.divergence_max_abs() >= 100.0);
        assert!(l0 / s.divergence_l2() >= 100.0);
    }

    // -- 2. Stability -----------------------------------------------------------

    /// 10 000 steps at dt = 1 and dt = 10 (N = 8, default sources) stay finite
    /// and bounded by `dt · source_strength`, the largest velocity that one
    /// step can inject. Justification: diffusion and advection are convex
    /// combinations (discrete maximum principle), and the projection removes
    /// about a third of a point impulse, so an unconditionally stable scheme
    /// should never accumulate more than about one step's injection; an
    /// explicit scheme at these dt blows up exponentially. Measured peaks over
    /// the 10 000 steps, as fractions of the bound: 0.36 (dt = 1) and 0.12
    /// (dt = 10) with the consistent projection (0.57 and 0.21 with the compact
    /// one; 0.79 at dt = 0.1).
    #[test]
    fn stable_for_large_time_steps() {
        for dt in [1.0_f32, 10.0] {
            let mut s = solver(8, |_| {});
            let bound = dt * s.params.source_strength;
            for step in 0..10_000 {
                s.step(dt);
                let m = s.max_speed();
                assert!(
                    m.is_finite() && m <= bound,
                    "dt={dt} step {step}: |u| = {m} > {bound}"
                );
                assert!(s.dens.iter().all(|d| d.is_finite() && *d >= 0.0));
            }
        }
    }

    // -- 3. Density conservation -------------------------------------------------

    /// N = 16, no sources, 7³ block of unit density.
    ///
    /// * Still fluid (pure diffusion, walls with zero-gradient density): the
    ///   implicit solve conserves mass only once converged; with 20 sweeps the
    ///   measured drift is 4.9e-6 (dt = 0.1, 100 steps) and 9.7e-4 (dt = 1,
    ///   100 steps, diffusion number a = 0.41). Tolerances: 2x margin.
    /// * Rigid swirl about the vertical axis (peak 0.05 domain/s, i.e. one
    ///   radian in 10 s), full `step`: semi-Lagrangian advection is not
    ///   conservative (trilinear back-trace interpolation, back-traces clamped to
    ///   `[0.5, N + 0.5]` at the walls). Measured worst drift over 1000 steps of
    ///   0.01 s: 6.22 % with the consistent projection at 20 and at 100 sweeps,
    ///   6.16 % with the compact one (the colleague's standalone measurements:
    ///   5.7 % with diffusion off; pure advection by the analytic, un-projected
    ///   swirl 0.24 %). The projection's operator and sweep count do not matter,
    ///   so the loss is the advection of the projected, wall-bounded flow.
    ///   Tolerance 8 % (~30 % margin over the measurement).
    #[test]
    fn density_conserved_without_sources() {
        for (dt, steps, tol) in [(0.1_f32, 100, 1.0e-5_f64), (1.0, 100, 2.0e-3)] {
            let mut s = closed_box(0.0);
            let m0 = s.total_density();
            for _ in 0..steps {
                s.step(dt);
                let drift = ((s.total_density() - m0) / m0).abs();
                assert!(drift < tol, "still fluid dt={dt}: drift {drift:e}");
            }
        }
        let mut s = closed_box(0.05);
        let m0 = s.total_density();
        let mut worst = 0.0_f64;
        for _ in 0..1000 {
            s.step(0.01);
            worst = worst.max(((s.total_density() - m0) / m0).abs());
        }
        assert!(worst < 0.08, "swirl drift {worst}");
        // And the density did move (the test is not vacuous).
        assert!(s.dens[s.ix(3, 8, 8)] > 1.0e-3);
    }

    // -- 4. Determinism ------------------------------------------------------------

    fn snapshot(s: &StamSolver) -> Vec<u32> {
        [
            &s.u,
            &s.v,
            &s.w,
            &s.dens,
            &s.u_prev,
            &s.v_prev,
            &s.w_prev,
            &s.dens_prev,
        ]
        .iter()
        .flat_map(|a| a.iter().map(|x| x.to_bits()))
        .collect()
    }

    #[test]
    fn same_seed_is_bit_exact_different_seed_differs() {
        let run = |seed: u64| {
            let mut s = solver(8, |p| p.seed = seed);
            for _ in 0..200 {
                s.step(0.1);
            }
            s
        };
        let (a, b, c) = (run(42), run(42), run(43));
        assert_eq!(snapshot(&a), snapshot(&b));
        assert_ne!(a.u, c.u);
        assert_ne!(a.dens, c.dens);
        // reset() replays the same sequence.
        let mut d = a.clone();
        d.reset();
        for _ in 0..200 {
            d.step(0.1);
        }
        assert_eq!(snapshot(&a), snapshot(&d));
    }

    // -- 5. Grid sizes -----------------------------------------------------------------

    #[test]
    fn n64_step_is_finite() {
        let mut s = solver(64, |_| {});
        s.step(0.1);
        s.step(10.0);
        assert!(
            s.u.iter()
                .chain(&s.v)
                .chain(&s.w)
                .chain(&s.dens)
                .all(|x| x.is_finite())
        );
        assert!(s.max_speed() > 0.0);
    }

    #[test]
    fn n2_works() {
        let mut s = solver(2, |_| {});
        for _ in 0..100 {
            s.step(1.0);
        }
        assert!(s.max_speed().is_finite() && s.total_density() > 0.0);
    }

    // -- 6. Validation -----------------------------------------------------------------

    #[test]
    fn validate_rejects_bad_values_naming_the_key() {
        let bad = |f: fn(&mut StamParams), key: &str| {
            let mut p = StamParams::default();
            f(&mut p);
            let e = p.validate().expect_err(key).to_string();
            assert!(e.contains(&format!("`{key}`")), "{e}");
            assert!(e.contains("expected"), "{e}");
            assert!(StamSolver::new(p).is_err());
        };
        bad(|p| p.viscosity = f32::NAN, "wind.viscosity");
        bad(|p| p.n = 0, "wind.n");
        bad(|p| p.n = 100_000, "wind.n");
        bad(|p| p.diffusion = -1.0, "wind.diffusion");
        bad(
            |p| p.source_strength = f32::INFINITY,
            "wind.source_strength",
        );
        bad(|p| p.source_density = 1.0e30, "wind.source_density");
        bad(|p| p.iterations = 0, "wind.iterations");
        bad(|p| p.iterations = 1001, "wind.iterations");
        bad(|p| p.source_cell = [0, 4, 4], "wind.source_cell[0]");
        bad(|p| p.source_cell = [4, 4, 9], "wind.source_cell[2]");
        assert!(StamParams::default().validate().is_ok());
        let e = StamParams {
            n: 0,
            ..Default::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("[2, 128]"), "{e}");
    }

    // -- Sampling and input handling ---------------------------------------------------

    #[test]
    fn sampling_hits_cell_centres_and_clamps() {
        let mut s = solver(8, |_| {});
        for _ in 0..20 {
            s.step(0.1);
        }
        let c = s.ix(3, 4, 5);
        let at = s.velocity_at([3.0, 4.0, 5.0]);
        assert_eq!(at, Vec3::new(s.u[c], s.v[c], s.w[c]));
        assert_eq!(s.density_at([3.0, 4.0, 5.0]), s.dens[c]);
        // Midpoint along x is the average of the two centres.
        let mid = s.density_at([3.5, 4.0, 5.0]);
        let avg = 0.5 * (s.dens[c] + s.dens[c + 1]);
        assert!((mid - avg).abs() <= 1e-6 * avg.abs().max(1.0));
        // Outside the grid clamps to the faces / far corner.
        assert_eq!(s.density_at([-5.0, 4.0, 5.0]), s.dens[s.ix(0, 4, 5)]);
        assert_eq!(s.density_at([99.0, 99.0, 99.0]), s.dens[s.ix(9, 9, 9)]);
        assert!(s.velocity_at([f32::NAN, 1.0, 1.0]).x.is_nan());
    }

    #[test]
    fn invalid_dt_is_a_no_op() {
        let mut s = solver(8, |_| {});
        s.step(0.1);
        let snap = snapshot(&s);
        s.step(f32::NAN);
        s.step(-1.0);
        s.step(f32::INFINITY);
        assert_eq!(snap, snapshot(&s));
    }
}
