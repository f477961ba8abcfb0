//! Pre-computed postures of one kind of blade (Perbet & Cani 2001, Sec. 3.2, Fig. 6 and 8).
//!
//! Perbet and Cani never simulate grass at run time. For each kind of grass (its height and
//! stiffness) they run, once, "a physically-based simulator which look\[s\] at the successive
//! 2D postures of the blade when a constant wind starts blowing", and keep two things:
//!
//! - **postures** (Fig. 6): K characteristic shapes indexed from −1 to 1, 0 being the rest
//!   state; receivers turn a primitive's index into blade geometry by looking them up;
//! - **the response** (Fig. 8): the posture index over time when a constant wind starts
//!   blowing and later suddenly stops; the gust primitive reads it along its strip.
//!
//! The simulator here is a planar chain of `segments` rigid segments, root clamped, with
//! angular springs `k = EI / l` and dampers between neighbours (a discretised cantilever) and
//! the blade's mass lumped at the segment tips. It is integrated in absolute segment angles
//! with the full (configuration-dependent) mass matrix of the chain, so large bends are exact
//! for the chain. Wind is quadratic drag on the air speed normal to each segment, relative to
//! the segment's own motion (so a blade in the wind is damped by the air too). Dampers are
//! proportional to the springs, scaled so that the chain's first mode (found by inverse
//! iteration at start-up) has the configured damping ratio. Springs, dampers and the drag's
//! dependence on the blade's speed are stepped implicitly (one small SPD solve per step), so
//! stiff grass is stable at any step. Gravity is left out: a real blade's weight is balanced by its rest shape, and the
//! straight rest pose stays the only equilibrium.
//!
//! Index convention: the signed tip displacement along the wind, divided by the largest one
//! seen while the wind blows (index 1, the overshoot peak) for forward bends, and by the
//! largest backswing after the wind stops (index −1) for backward ones. Positive postures are
//! taken from the rise (rest → peak) and negative ones from the backswing (release → trough),
//! so both families are real shapes of the blade; if the blade is so damped that it hardly
//! swings back (under 5 % of the peak), negative postures mirror the positive ones instead.
//! Tip displacement grows strictly with the index either way.

use glam::Vec2;
use serde::{Deserialize, Serialize};

use crate::params::{check, check_int};
use crate::{Error, Result};

/// Samples per second of a [`ResponseCurve`].
pub const RESPONSE_RATE: f32 = 120.0;

/// Longest simulated settling time after the wind stops, s; a response still moving then is
/// faded to rest over its last tenth.
const MAX_SETTLE: f64 = 30.0;

/// One kind of grass for the posture simulation: `[wind.blade]` of a `primitives` wind.
///
/// Defaults describe a 50 cm blade 1 cm wide; its simulated first bending mode is about 1.1 Hz.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct BladeConfig {
    /// Blade height, m.
    pub height: f32,
    /// Bending stiffness `EI`, N·m².
    pub stiffness: f32,
    /// Mass per metre of blade, kg/m.
    pub mass: f32,
    /// Drag per metre of blade, `½ ρ C_d w` (N·s²/m³): air moving at `u` (m/s) across the
    /// blade pushes each metre with `drag · u²` newtons.
    pub drag: f32,
    /// Damping ratio of the simulated chain's first bending mode (structural, stiffness
    /// proportional, so higher modes are damped more; the air adds its own).
    pub damping: f32,
    /// Rigid segments of the simulated chain, 2..=16.
    pub segments: u32,
    /// How many postures to extract, K: odd, 3..=65 (indices `−1, …, 0, …, 1`).
    pub postures: u32,
    /// Speed of the simulated constant wind, m/s. Also what a posture index of 1 stands for
    /// when primitives drive other techniques as a velocity field.
    pub wind_speed: f32,
    /// How long the simulated wind blows before it stops, s.
    pub hold: f32,
}

impl Default for BladeConfig {
    fn default() -> Self {
        Self {
            height: 0.5,
            stiffness: 4.5e-3,
            mass: 0.01,
            drag: 7.2e-3,
            damping: 0.1,
            segments: 6,
            postures: 9,
            wind_speed: 5.0,
            hold: 2.0,
        }
    }
}

impl BladeConfig {
    /// Rejects NaN, infinities and absurd values; error keys are `<prefix>.<key>`.
    pub fn validate(&self, prefix: &str) -> Result<()> {
        check(&format!("{prefix}.height"), self.height, 0.02..=5.0)?;
        check(&format!("{prefix}.stiffness"), self.stiffness, 1e-7..=10.0)?;
        check(&format!("{prefix}.mass"), self.mass, 1e-5..=10.0)?;
        check(&format!("{prefix}.drag"), self.drag, 1e-6..=10.0)?;
        check(&format!("{prefix}.damping"), self.damping, 0.01..=2.0)?;
        check_int(&format!("{prefix}.segments"), self.segments, 2..=16)?;
        if !(3..=65).contains(&self.postures) || self.postures.is_multiple_of(2) {
            return Err(Error::param(
                format!("{prefix}.postures"),
                self.postures,
                "an odd integer in [3, 65], so that index 0 (rest) is one of them",
            ));
        }
        check(
            &format!("{prefix}.wind_speed"),
            self.wind_speed,
            0.1..=100.0,
        )?;
        check(&format!("{prefix}.hold"), self.hold, 0.1..=120.0)
    }
}

/// The posture index over time when a constant wind starts blowing at `t = 0` and stops at
/// [`ResponseCurve::wind_duration`] (Fig. 8), sampled at [`RESPONSE_RATE`] and ending at rest.
#[derive(Clone, Debug, PartialEq)]
pub struct ResponseCurve {
    wind_duration: f32,
    samples: Vec<f32>,
}

impl ResponseCurve {
    /// Posture index `t` seconds after the wind started (linear between samples; 0 before the
    /// start and after the end).
    pub fn index_at(&self, t: f32) -> f32 {
        let u = t * RESPONSE_RATE;
        if u.is_nan() || u < 0.0 {
            return 0.0;
        }
        let i = u.floor() as usize;
        match (self.samples.get(i), self.samples.get(i + 1)) {
            (Some(a), Some(b)) => a + (b - a) * (u - i as f32),
            _ => 0.0,
        }
    }

    /// Time from the wind's start until the blade is back at rest, s.
    pub fn duration(&self) -> f32 {
        self.samples.len().saturating_sub(1) as f32 / RESPONSE_RATE
    }

    /// How long the wind blew, s.
    pub fn wind_duration(&self) -> f32 {
        self.wind_duration
    }

    /// The samples, one every `1 / RESPONSE_RATE` s from the wind's start.
    pub fn samples(&self) -> &[f32] {
        &self.samples
    }
}

/// The K postures of one kind of blade and its response curve, computed at start-up (a few
/// milliseconds).
#[derive(Clone, Debug)]
pub struct Postures {
    config: BladeConfig,
    /// Segment angles from the vertical (radians, positive towards the bending direction),
    /// `segments` per posture, postures ordered from index −1 to 1.
    angles: Vec<f32>,
    /// Tip displacement of index 1 and of index −1 (its magnitude), m.
    forward: f32,
    backward: f32,
    response: ResponseCurve,
}

impl Postures {
    /// Simulates one blade of kind `config` (validated, keys named `wind.blade.*`) and
    /// extracts its postures and response.
    pub fn new(config: &BladeConfig) -> Result<Self> {
        config.validate("wind.blade")?;
        let n = config.segments as usize;
        let half = (config.postures as usize - 1) / 2;
        let run = simulate(config, f64::from(config.hold), None, true);
        if !run.tips.iter().all(|t| t.is_finite()) {
            return Err(Error::param(
                "wind.blade",
                format!("{config:?}"),
                "a blade whose simulation stays finite (less extreme stiffness, mass, drag or \
                 wind_speed)",
            ));
        }
        let stop = run.stop;
        let (peak, forward) = extreme(&run.tips[..=stop], 1.0);
        let (trough, backswing) = extreme(&run.tips[stop..], -1.0);
        let forward = forward.max(1e-6);
        let mirrored = -backswing < 0.05 * forward;
        let backward = if mirrored { forward } else { -backswing };

        let mut positive = Vec::with_capacity(half * n);
        for j in 1..=half {
            let target = j as f32 / half as f32 * forward;
            positive.extend(run.angles_where(0, peak, target, 1.0));
        }
        let mut negative = Vec::with_capacity(half * n);
        for j in 1..=half {
            if mirrored {
                negative.extend(positive[(j - 1) * n..j * n].iter().map(|a| -a));
            } else {
                let target = -(j as f32) / half as f32 * backward;
                negative.extend(run.angles_where(stop, stop + trough, target, -1.0));
            }
        }
        let mut angles = Vec::with_capacity(config.postures as usize * n);
        for j in (0..half).rev() {
            angles.extend_from_slice(&negative[j * n..(j + 1) * n]);
        }
        angles.extend(std::iter::repeat_n(0.0, n));
        angles.extend_from_slice(&positive);

        let mut postures = Self {
            config: config.clone(),
            angles,
            forward,
            backward,
            response: ResponseCurve {
                wind_duration: config.hold,
                samples: Vec::new(),
            },
        };
        postures.response = postures.curve(&run, config.hold);
        Ok(postures)
    }

    /// The blade kind these postures were simulated for.
    pub fn config(&self) -> &BladeConfig {
        &self.config
    }

    /// Number of postures, K.
    pub fn count(&self) -> usize {
        self.config.postures as usize
    }

    /// Segments per posture.
    pub fn segments(&self) -> usize {
        self.config.segments as usize
    }

    /// Length of one segment, m.
    pub fn segment_length(&self) -> f32 {
        self.config.height / self.config.segments as f32
    }

    /// The index of posture `k` (`k = 0` is −1, `k = K / 2` is 0 the rest pose, `k = K − 1` is
    /// 1).
    pub fn index_of(&self, k: usize) -> f32 {
        let half = (self.count() - 1) as f32 / 2.0;
        (k as f32 - half) / half
    }

    /// Segment angles of posture `k` (radians from the vertical, positive towards the bending
    /// direction, root first); empty if `k` is out of range.
    pub fn angles(&self, k: usize) -> &[f32] {
        let n = self.segments();
        self.angles.get(k * n..(k + 1) * n).unwrap_or(&[])
    }

    /// Segment angles at any `index` in `[−1, 1]` (clamped), interpolated linearly between the
    /// two nearest postures, written to `out` (the shorter of `out` and the segments).
    pub fn angles_at(&self, index: f32, out: &mut [f32]) {
        let half = (self.count() - 1) as f32 / 2.0;
        let u = (index.clamp(-1.0, 1.0) + 1.0) * half;
        let k = (u.floor() as usize).min(self.count() - 2);
        let f = u - k as f32;
        for ((o, a), b) in out.iter_mut().zip(self.angles(k)).zip(self.angles(k + 1)) {
            *o = a + (b - a) * f;
        }
    }

    /// The blade's `segments + 1` points at `index` (m; x along the bending direction, y up,
    /// root at the origin).
    pub fn points_at(&self, index: f32) -> Vec<Vec2> {
        let mut angles = vec![0.0; self.segments()];
        self.angles_at(index, &mut angles);
        chain_points(&angles, self.segment_length())
    }

    /// Signed tip displacement along the bending direction of posture `k`, m.
    pub fn tip_displacement(&self, k: usize) -> f32 {
        chain_points(self.angles(k), self.segment_length())
            .last()
            .map_or(0.0, |p| p.x)
    }

    /// The response to the simulated wind of [`BladeConfig::hold`] seconds (Fig. 8).
    pub fn response(&self) -> &ResponseCurve {
        &self.response
    }

    /// The response to the same wind blowing for `wind_duration` seconds instead (a gust's
    /// strip width over its speed), indexed like the postures; simulated anew (milliseconds).
    pub fn response_for(&self, wind_duration: f32) -> ResponseCurve {
        let hold = f64::from(wind_duration.clamp(0.0, 600.0));
        let run = simulate(&self.config, hold, Some(self.forward), false);
        self.curve(&run, wind_duration)
    }

    /// A posture index for a signed tip displacement `d` (m), clamped to `[−1, 1]`.
    fn index_for(&self, d: f32) -> f32 {
        if !d.is_finite() {
            return 0.0;
        }
        let scale = if d >= 0.0 {
            self.forward
        } else {
            self.backward
        };
        (d / scale).clamp(-1.0, 1.0)
    }

    /// Resamples a run's tip displacements into a response curve.
    fn curve(&self, run: &Run, wind_duration: f32) -> ResponseCurve {
        let end = (run.tips.len() - 1) as f64 * run.dt;
        let count = (end * f64::from(RESPONSE_RATE)).floor() as usize + 1;
        let mut samples: Vec<f32> = (0..count)
            .map(|i| {
                let u = i as f64 / f64::from(RESPONSE_RATE) / run.dt;
                let s = (u.floor() as usize).min(run.tips.len() - 1);
                let next = (s + 1).min(run.tips.len() - 1);
                let f = (u - s as f64) as f32;
                self.index_for(run.tips[s] + (run.tips[next] - run.tips[s]) * f)
            })
            .collect();
        // Whatever is left of the motion fades out over the last tenth: the curve must end at
        // rest, since a gust's mask ends where it does.
        let fade = (count / 10).max(2);
        for (k, s) in samples.iter_mut().rev().take(fade).enumerate() {
            let x = k as f32 / fade as f32;
            *s *= x * x * (3.0 - 2.0 * x);
        }
        ResponseCurve {
            wind_duration,
            samples,
        }
    }
}

/// Points of a chain of segments of length `l` at absolute `angles` from the vertical.
fn chain_points(angles: &[f32], l: f32) -> Vec<Vec2> {
    let mut p = Vec2::ZERO;
    let mut points = vec![p];
    for a in angles {
        p += Vec2::new(a.sin(), a.cos()) * l;
        points.push(p);
    }
    points
}

/// Position and value of the largest `sign · x` in `xs`.
fn extreme(xs: &[f32], sign: f32) -> (usize, f32) {
    xs.iter().enumerate().fold((0, 0.0), |(bi, bv), (i, &v)| {
        if sign * v > sign * bv {
            (i, v)
        } else {
            (bi, bv)
        }
    })
}

/// One simulation: tip displacement at every step (step 0 is the rest state at `t = 0`) and,
/// if kept, every step's segment angles.
struct Run {
    dt: f64,
    /// Step at which the wind stopped.
    stop: usize,
    tips: Vec<f32>,
    angles: Vec<f32>,
    segments: usize,
}

impl Run {
    /// Angles where the tip displacement first reaches `target` (in the direction `sign`)
    /// between steps `from` and `to`, interpolated between the two steps around it.
    fn angles_where(&self, from: usize, to: usize, target: f32, sign: f32) -> Vec<f32> {
        let n = self.segments;
        let at = |s: usize| self.angles.get(s * n..(s + 1) * n).unwrap_or(&[]);
        let s = (from + 1..=to)
            .find(|&s| sign * self.tips[s] >= sign * target)
            .unwrap_or(to.max(from + 1).min(self.tips.len() - 1));
        let (a, b) = (self.tips[s - 1], self.tips[s]);
        let f = if (b - a).abs() > 1e-12 {
            ((target - a) / (b - a)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        at(s - 1)
            .iter()
            .zip(at(s))
            .map(|(x, y)| x + (y - x) * f)
            .collect()
    }
}

/// Runs the blade from rest under a wind of `config.wind_speed` for `hold` seconds, then
/// without wind until it has settled (tip within 0.5 % of `scale` — or of the largest loaded
/// displacement if `None` — for 1.5 periods of the first mode) or [`MAX_SETTLE`] seconds.
fn simulate(config: &BladeConfig, hold: f64, scale: Option<f32>, keep_angles: bool) -> Run {
    let mut chain = Chain::new(config);
    let dt = chain.dt();
    let n = chain.n;
    let hold_steps = (hold / dt).round() as usize;
    let period = std::f64::consts::TAU / chain.omega1;
    let quiet_steps = ((1.5 * period).clamp(0.2, 5.0) / dt).ceil() as usize;
    let max_steps = hold_steps + (MAX_SETTLE / dt).ceil() as usize;
    let mut run = Run {
        dt,
        stop: hold_steps,
        tips: vec![0.0],
        angles: vec![0.0; if keep_angles { n } else { 0 }],
        segments: n,
    };
    let wind = f64::from(config.wind_speed);
    let mut threshold = scale.map(|s| 0.005 * f64::from(s));
    let mut quiet = 0;
    for step in 1..=max_steps {
        let blowing = step <= hold_steps;
        chain.step(if blowing { wind } else { 0.0 }, dt);
        let tip = chain.tip_x();
        run.tips.push(tip as f32);
        if keep_angles {
            run.angles.extend(chain.theta.iter().map(|&a| a as f32));
        }
        if blowing {
            continue;
        }
        let limit = *threshold.get_or_insert_with(|| {
            let peak = run.tips.iter().fold(0.0f32, |m, t| m.max(*t));
            0.005 * f64::from(peak.max(1e-6))
        });
        quiet = if tip.abs() < limit { quiet + 1 } else { 0 };
        if quiet >= quiet_steps {
            break;
        }
    }
    run
}

/// The planar chain: `n` rigid segments of length `l` with point masses `m` at their tips,
/// angular springs `k` and dampers `c` between neighbours (and the ground), absolute angles
/// `theta` from the vertical and their rates `omega`.
struct Chain {
    n: usize,
    l: f64,
    m: f64,
    k: f64,
    /// First bending frequency at rest, rad/s.
    omega1: f64,
    c: f64,
    /// Drag of one segment, N·s²/m².
    drag: f64,
    theta: Vec<f64>,
    omega: Vec<f64>,
    matrix: Vec<f64>,
    rhs: Vec<f64>,
    /// Per mass point: drag force along the segment normal, its derivative with respect to
    /// the point's normal speed (negated), and one row of the normal-speed Jacobian.
    force: Vec<f64>,
    slope: Vec<f64>,
    row: Vec<f64>,
}

impl Chain {
    fn new(config: &BladeConfig) -> Self {
        let n = config.segments as usize;
        let l = f64::from(config.height) / n as f64;
        let k = f64::from(config.stiffness) / l;
        let m = f64::from(config.mass) * l;
        let omega1 = first_mode(n, l, m, k);
        Self {
            n,
            l,
            m,
            k,
            omega1,
            // Stiffness-proportional damping: ratio `damping` on the first mode.
            c: 2.0 * f64::from(config.damping) / omega1 * k,
            drag: f64::from(config.drag) * l,
            theta: vec![0.0; n],
            omega: vec![0.0; n],
            matrix: vec![0.0; n * n],
            rhs: vec![0.0; n],
            force: vec![0.0; n],
            slope: vec![0.0; n],
            row: vec![0.0; n],
        }
    }

    /// Simulation step, s: 200 per period of the first mode, within `[1/2000, 1/600]`.
    fn dt(&self) -> f64 {
        (std::f64::consts::TAU / self.omega1 / 200.0).clamp(1.0 / 2000.0, 1.0 / 600.0)
    }

    fn tip_x(&self) -> f64 {
        self.theta.iter().map(|a| a.sin()).sum::<f64>() * self.l
    }

    /// `(K θ)_i` of the spring potential `½ k Σ (θ_i − θ_{i−1})²` (θ_{−1} = 0).
    fn spring(&self, i: usize) -> f64 {
        let x = &self.theta;
        let below = if i == 0 { 0.0 } else { x[i - 1] };
        let mut f = x[i] - below;
        if i + 1 < self.n {
            f -= x[i + 1] - x[i];
        }
        self.k * f
    }

    /// One step of `dt` under a wind of `wind` m/s along +x.
    ///
    /// Lagrange's equations of the chain in absolute angles:
    /// `M(θ) θ̈ + h(θ, θ̇) = Jᵀ f − Kθ − Cθ̇` with `M_ij = m l² (n − max(i, j)) cos(θ_i − θ_j)`,
    /// `h_i = m l² Σ_j (n − max(i, j)) sin(θ_i − θ_j) θ̇_j²`, `f_k` the drag on mass point `k`
    /// along its segment's normal and `J_ki = l cos(θ_k − θ_i)` (`i ≤ k`) the map from angle
    /// rates to the points' normal speeds. Springs, dampers and the drag's dependence on the
    /// blade's own speed are implicit (linearised):
    /// `(M + dt C + dt² K + dt JᵀGJ) θ̇' = M θ̇ + dt (Jᵀf + JᵀGJ θ̇ − h − Kθ)`, `θ' = θ + dt θ̇'`,
    /// `G` the drag's slopes; one small SPD solve per step.
    fn step(&mut self, wind: f64, dt: f64) {
        let n = self.n;
        let ml2 = self.m * self.l * self.l;
        // Air speed across each segment at its tip, relative to the moving blade.
        let (mut vx, mut vy) = (0.0, 0.0);
        for k in 0..n {
            let (s, c) = self.theta[k].sin_cos();
            vx += self.l * self.omega[k] * c;
            vy -= self.l * self.omega[k] * s;
            let un = (wind - vx) * c + vy * s;
            self.force[k] = self.drag * un * un.abs();
            self.slope[k] = 2.0 * self.drag * un.abs();
        }
        let implicit = dt * self.c / self.k + dt * dt;
        for i in 0..n {
            let mut h = 0.0;
            let mut m_omega = 0.0;
            for j in 0..n {
                let w = ml2 * (n - i.max(j)) as f64;
                let (s, c) = (self.theta[i] - self.theta[j]).sin_cos();
                h += w * s * self.omega[j] * self.omega[j];
                m_omega += w * c * self.omega[j];
                self.matrix[i * n + j] = w * c;
            }
            self.rhs[i] = m_omega - dt * (h + self.spring(i));
        }
        // + (dt c/k + dt²) K, K tridiagonal (once M is complete).
        for i in 0..n {
            let diag = if i + 1 < n { 2.0 } else { 1.0 };
            self.matrix[i * n + i] += implicit * self.k * diag;
            if i + 1 < n {
                self.matrix[i * n + i + 1] -= implicit * self.k;
                self.matrix[(i + 1) * n + i] -= implicit * self.k;
            }
        }
        for k in 0..n {
            for i in 0..=k {
                self.row[i] = self.l * (self.theta[k] - self.theta[i]).cos();
            }
            let speed: f64 = (0..=k).map(|i| self.row[i] * self.omega[i]).sum();
            let g = dt * self.slope[k];
            for i in 0..=k {
                self.rhs[i] += self.row[i] * (dt * self.force[k] + g * speed);
                for j in 0..=k {
                    self.matrix[i * n + j] += g * self.row[i] * self.row[j];
                }
            }
        }
        solve_spd(&mut self.matrix, &mut self.rhs, n);
        self.omega.copy_from_slice(&self.rhs);
        for (t, w) in self.theta.iter_mut().zip(&self.omega) {
            *t += dt * w;
        }
    }
}

/// The first bending frequency (rad/s) at rest of a chain of `n` segments of length `l`,
/// tip masses `m` and joint springs `k`: inverse iteration on `K x = ω² M x`.
fn first_mode(n: usize, l: f64, m: f64, k: f64) -> f64 {
    let mass = |i: usize, j: usize| m * l * l * (n - i.max(j)) as f64;
    let stiffness = |a: &mut [f64]| {
        a.fill(0.0);
        for i in 0..n {
            a[i * n + i] = if i + 1 < n { 2.0 * k } else { k };
            if i + 1 < n {
                a[i * n + i + 1] = -k;
                a[(i + 1) * n + i] = -k;
            }
        }
    };
    let mut a = vec![0.0; n * n];
    let mut x = vec![1.0; n];
    for _ in 0..40 {
        let mut y: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| mass(i, j) * x[j]).sum())
            .collect();
        stiffness(&mut a);
        solve_spd(&mut a, &mut y, n);
        let norm = y.iter().map(|v| v * v).sum::<f64>().sqrt().max(1e-300);
        x = y.into_iter().map(|v| v / norm).collect();
    }
    stiffness(&mut a);
    let (mut kx, mut mx) = (0.0, 0.0);
    for i in 0..n {
        for j in 0..n {
            kx += x[i] * a[i * n + j] * x[j];
            mx += x[i] * mass(i, j) * x[j];
        }
    }
    (kx / mx.max(1e-300)).sqrt()
}

/// Solves `A x = b` in place (`b` becomes `x`) for a symmetric positive-definite `n × n`
/// matrix `a` (row-major), by Cholesky factorisation. A non-positive pivot (impossible for a
/// mass matrix, but no panics here) is replaced by a tiny positive one.
fn solve_spd(a: &mut [f64], b: &mut [f64], n: usize) {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        let d = d.max(1e-300).sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= a[i * n + k] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= a[k * n + i] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn postures_are_ordered_by_bend_and_zero_is_rest() {
        let p = Postures::new(&BladeConfig::default()).unwrap();
        assert_eq!(p.count(), 9);
        let rest = p.count() / 2;
        assert_eq!(p.index_of(rest), 0.0);
        assert_eq!(p.index_of(0), -1.0);
        assert_eq!(p.index_of(p.count() - 1), 1.0);
        assert!(p.angles(rest).iter().all(|a| *a == 0.0));
        let tips: Vec<f32> = (0..p.count()).map(|k| p.tip_displacement(k)).collect();
        assert!(tips.windows(2).all(|w| w[0] < w[1]), "{tips:?}");
        assert!(tips[rest].abs() < 1e-6);
        // A real bend: the tip moves by a good part of the height, and the blade keeps its
        // length (rigid segments).
        assert!(tips[p.count() - 1] > 0.1, "{tips:?}");
        let pts = p.points_at(1.0);
        let len: f32 = pts.windows(2).map(|w| w[0].distance(w[1])).sum();
        assert!((len - 0.5).abs() < 1e-4);
        // Interpolation passes through the postures.
        let mid = p.points_at(p.index_of(rest + 1));
        assert!((mid[6].x - tips[rest + 1]).abs() < 1e-5);
    }

    #[test]
    fn response_rises_while_blowing_and_settles_after() {
        let p = Postures::new(&BladeConfig::default()).unwrap();
        let r = p.response();
        assert_eq!(r.index_at(-0.1), 0.0);
        assert!(r.index_at(0.0).abs() < 1e-3);
        // Rises: reaches its peak (index 1) while the wind blows, and is well bent at the end.
        let blowing: Vec<f32> = (0..=(r.wind_duration() * 100.0) as usize)
            .map(|i| r.index_at(i as f32 / 100.0))
            .collect();
        assert!(blowing[5] > 0.0 && blowing[5] < blowing[20], "{blowing:?}");
        assert!(blowing.iter().cloned().fold(0.0, f32::max) > 0.98);
        assert!(*blowing.last().unwrap() > 0.4);
        // After it stops: swings back (negative indices), then settles at rest.
        let after = r.wind_duration() + 0.05;
        let min = (0..200)
            .map(|i| r.index_at(after + i as f32 / 100.0))
            .fold(0.0, f32::min);
        assert!(min < -0.5, "backswing {min}");
        assert!(r.duration() > r.wind_duration() + 1.0);
        assert!(r.duration() < r.wind_duration() + MAX_SETTLE as f32);
        let tail = r.samples()[r.samples().len() - 30..].iter();
        assert!(tail.clone().all(|s| s.abs() < 0.02));
        assert_eq!(r.index_at(r.duration() + 0.1), 0.0);
        assert!(r.samples().iter().all(|s| s.is_finite() && s.abs() <= 1.0));
    }

    #[test]
    fn shorter_winds_bend_less_and_stiffer_grass_bends_less() {
        let p = Postures::new(&BladeConfig::default()).unwrap();
        let short = p.response_for(0.03);
        let peak = |r: &ResponseCurve| r.samples().iter().cloned().fold(0.0, f32::max);
        assert!(peak(&short) < 0.6 * peak(p.response()), "{}", peak(&short));
        assert!((short.wind_duration() - 0.03).abs() < 1e-6);
        let stiff = Postures::new(&BladeConfig {
            stiffness: 0.05,
            ..Default::default()
        })
        .unwrap();
        assert!(stiff.tip_displacement(8) < p.tip_displacement(8));
    }

    #[test]
    fn deterministic_and_validated() {
        let a = Postures::new(&BladeConfig::default()).unwrap();
        let b = Postures::new(&BladeConfig::default()).unwrap();
        assert_eq!(a.angles, b.angles);
        assert_eq!(a.response, b.response);
        let e = Postures::new(&BladeConfig {
            postures: 8,
            ..Default::default()
        })
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("wind.blade.postures") && e.contains("odd"),
            "{e}"
        );
        let e = Postures::new(&BladeConfig {
            height: f32::NAN,
            ..Default::default()
        })
        .unwrap_err()
        .to_string();
        assert!(e.contains("wind.blade.height"), "{e}");
    }

    #[test]
    fn first_mode_matches_a_single_pendulum_and_damping_is_the_configured_ratio() {
        // One segment: a rod with its mass at the tip, ω² = k / (m l²).
        assert!((first_mode(1, 0.5, 0.2, 0.3) - (0.3f64 / (0.2 * 0.25)).sqrt()).abs() < 1e-9);
        // Free vibration of the default blade: period 2π/ω₁ and a logarithmic decrement of
        // about 2πζ (air drag adds a little).
        let config = BladeConfig {
            drag: 1e-6,
            ..Default::default()
        };
        let mut chain = Chain::new(&config);
        chain
            .theta
            .iter_mut()
            .enumerate()
            .for_each(|(i, t)| *t = 0.01 * (i + 1) as f64);
        let dt = chain.dt();
        let mut tips = Vec::new();
        for _ in 0..(3.0 / dt) as usize {
            chain.step(0.0, dt);
            tips.push(chain.tip_x());
        }
        let peaks: Vec<(usize, f64)> = (1..tips.len() - 1)
            .filter(|&i| tips[i] > tips[i - 1] && tips[i] >= tips[i + 1] && tips[i] > 0.0)
            .map(|i| (i, tips[i]))
            .collect();
        let period = (peaks[1].0 - peaks[0].0) as f64 * dt;
        let expected = std::f64::consts::TAU / chain.omega1;
        assert!(
            (period / expected - 1.0).abs() < 0.05,
            "{period} vs {expected}"
        );
        let zeta = (peaks[0].1 / peaks[1].1).ln() / std::f64::consts::TAU;
        assert!((zeta - 0.1).abs() < 0.03, "damping ratio {zeta}");
    }

    #[test]
    fn spd_solver_solves() {
        let mut a = vec![4.0, 1.0, 0.0, 1.0, 3.0, 1.0, 0.0, 1.0, 2.0];
        let m = a.clone();
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| m[i * 3 + j] * x[j]).sum())
            .collect();
        solve_spd(&mut a, &mut b, 3);
        for (u, v) in b.iter().zip(x) {
            assert!((u - v).abs() < 1e-12);
        }
    }
}
