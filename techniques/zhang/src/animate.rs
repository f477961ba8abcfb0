//! The per-frame CPU animation of every near blade and flower (Sec. 3.2, 3.4), writing the
//! instance data the vertex shader expands into quads.

use grassbench::glam::Vec3;
use grassbench::wind::WindField;

use crate::blade::{BladeState, Dynamics};
use crate::flower::FlowerState;
use crate::gpu::{BladeDynamic, FlowerInstance};
use crate::prairie::Planted;

/// Longest Verlet step, s: longer frames are sub-stepped so the damped spring stays stable
/// (`ω·dt` = 0.21 at the default spring and 30 fps).
pub const MAX_STEP: f32 = 1.0 / 30.0;
/// Most Verlet sub-steps per frame.
pub const MAX_SUBSTEPS: u32 = 8;

/// Every animated blade and flower, and the instance data of the last step.
#[derive(Clone, Debug)]
pub struct Animation {
    blades: Vec<BladeState>,
    flowers: Vec<FlowerState>,
    /// Per blade: `P1..P3` and the rotation θ (what the GPU reads).
    pub blade_out: Vec<BladeDynamic>,
    /// Per flower: petal centre, spin, stalk axis, texture layer.
    pub flower_out: Vec<FlowerInstance>,
    spins: Vec<(f32, u32)>,
    /// Sample points and wind of one frame (3 per blade, then 1 per flower), reused.
    points: Vec<Vec3>,
    winds: Vec<Vec3>,
    /// Threads the blade step may use (the machine's cores by default).
    threads: usize,
}

impl Animation {
    /// Rest state of the planted blades; flowers weigh `flower_mass`.
    pub fn new(planted: &[Planted], flower_mass: f32) -> Self {
        let blades: Vec<BladeState> = planted
            .iter()
            .map(|p| BladeState::new(p.root, p.height, p.facing, p.lean.x, p.lean.y, p.stiffness))
            .collect();
        let (flowers, spins): (Vec<_>, Vec<_>) = planted
            .iter()
            .filter_map(|p| {
                let (h, spin, layer) = p.flower?;
                Some((FlowerState::new(p.root, h, flower_mass), (spin, layer)))
            })
            .unzip();
        let mut a = Self {
            blade_out: vec![BladeDynamic::default(); blades.len()],
            flower_out: vec![FlowerInstance::default(); flowers.len()],
            blades,
            flowers,
            spins,
            points: Vec::new(),
            winds: Vec::new(),
            threads: std::thread::available_parallelism().map_or(1, |t| t.get()),
        };
        let samples = 3 * a.blades.len() + a.flowers.len();
        a.points = vec![Vec3::ZERO; samples];
        a.winds = vec![Vec3::ZERO; samples];
        a.write_out();
        a
    }

    /// Sets the threads the blade step may use (1 = on the caller's thread; at most 16).
    pub fn set_threads(&mut self, threads: usize) {
        self.threads = threads;
    }

    /// Blades animated.
    pub fn blade_count(&self) -> usize {
        self.blades.len()
    }

    /// Flowers animated.
    pub fn flower_count(&self) -> usize {
        self.flowers.len()
    }

    /// The blades' states.
    pub fn blades(&self) -> &[BladeState] {
        &self.blades
    }

    /// The flowers' states.
    pub fn flowers(&self) -> &[FlowerState] {
        &self.flowers
    }

    /// Advances every blade and flower by `dt` in `wind` at `time`: the wind is read once per
    /// frame at each moving control point (`P1..P3`; the root's wind is irrelevant, its
    /// inverse mass is 0) and at each petal, in batched [`WindField::velocities`] calls,
    /// then `ceil(dt / MAX_STEP)` Verlet steps follow. The blades are split into one chunk per
    /// core (scoped threads, at least `MIN_CHUNK` blades each); the sample buffers are reused,
    /// so nothing is allocated but the threads. The result does not depend on the split.
    /// A `dt` that is not positive and finite does nothing.
    pub fn step(
        &mut self,
        wind: &dyn WindField,
        time: f32,
        dt: f32,
        wind_response: f32,
        spring: f32,
        damping: f32,
    ) {
        if !(dt.is_finite() && dt > 0.0) {
            return;
        }
        let steps = ((dt / MAX_STEP).ceil() as u32).clamp(1, MAX_SUBSTEPS);
        let k = Dynamics::new(dt / steps as f32, wind_response, spring, damping);
        let n = self.blades.len();
        let (blade_points, flower_points) = self.points.split_at_mut(3 * n);
        let (blade_winds, flower_winds) = self.winds.split_at_mut(3 * n);
        // Blades are independent: split them into one contiguous chunk per core, each with
        // its own batched wind query. Same result for any number of threads.
        let chunk = n
            .div_ceil(self.threads.clamp(1, MAX_THREADS))
            .max(MIN_CHUNK);
        std::thread::scope(|scope| {
            let work = self
                .blades
                .chunks_mut(chunk)
                .zip(blade_points.chunks_mut(3 * chunk))
                .zip(blade_winds.chunks_mut(3 * chunk))
                .zip(self.blade_out.chunks_mut(chunk));
            for (((blades, points), winds), out) in work {
                let k = &k;
                scope.spawn(move || {
                    step_blades(blades, points, winds, out, wind, time, steps, k);
                });
            }
        });
        for (p, f) in flower_points.iter_mut().zip(&self.flowers) {
            *p = f.pos;
        }
        wind.velocities(flower_points, time, flower_winds);
        for (f, &w) in self.flowers.iter_mut().zip(flower_winds.iter()) {
            for _ in 0..steps {
                f.step(w, &k);
            }
        }
        self.write_flowers();
    }

    fn write_out(&mut self) {
        write_blades(&self.blades, &mut self.blade_out);
        self.write_flowers();
    }

    fn write_flowers(&mut self) {
        for ((out, f), &(spin, layer)) in self
            .flower_out
            .iter_mut()
            .zip(&self.flowers)
            .zip(&self.spins)
        {
            let axis = (f.pos - f.root).normalize_or(Vec3::Y);
            *out = FlowerInstance {
                pos_spin: [f.pos.x, f.pos.y, f.pos.z, spin],
                axis_layer: [axis.x, axis.y, axis.z, layer as f32],
            };
        }
    }
}

/// Most threads the blade step uses.
const MAX_THREADS: usize = 16;
/// Fewest blades a thread takes (below that, spawning costs more than it saves).
const MIN_CHUNK: usize = 2048;

/// One chunk of the frame's blade step: gather the moving control points, one batched wind
/// query, `steps` Verlet steps per blade, then the instance data.
#[allow(clippy::too_many_arguments)]
fn step_blades(
    blades: &mut [BladeState],
    points: &mut [Vec3],
    winds: &mut [Vec3],
    out: &mut [BladeDynamic],
    wind: &dyn WindField,
    time: f32,
    steps: u32,
    k: &Dynamics,
) {
    for (p, b) in points.chunks_exact_mut(3).zip(blades.iter()) {
        p.copy_from_slice(&b.pos[1..]);
    }
    wind.velocities(points, time, winds);
    for (b, w) in blades.iter_mut().zip(winds.chunks_exact(3)) {
        let w = [w[0], w[1], w[2]];
        let ground = b.pos[0].y;
        for _ in 0..steps {
            b.step(&w, k, ground);
        }
    }
    write_blades(blades, out);
}

/// `P1..P3` and the rotation θ of each blade, as the GPU reads them.
fn write_blades(blades: &[BladeState], out: &mut [BladeDynamic]) {
    for (out, b) in out.iter_mut().zip(blades) {
        let rot = b.rotation();
        let v = |p: Vec3, w: f32| [p.x, p.y, p.z, w];
        *out = BladeDynamic {
            p1_rotation: v(b.pos[1], rot),
            p2: v(b.pos[2], 0.0),
            p3: v(b.pos[3], 0.0),
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Params;
    use crate::prairie::plant;
    use grassbench::glam::Vec2;
    use grassbench::grass::GrassConfig;
    use grassbench::terrain::Terrain;
    use grassbench::wind::{Breeze, BreezeConfig};

    #[test]
    fn the_split_over_threads_does_not_change_the_result() {
        let terrain = Terrain::flat(Vec2::new(40.0, 40.0));
        let params = Params {
            grids: 4,
            blades_per_side: 24,
            flower_fraction: 0.1,
            ..Params::default()
        };
        let planted = plant(&params, &GrassConfig::default(), &terrain, 5).1;
        assert!(planted.len() > 3 * MIN_CHUNK, "too few blades to split");
        let wind = Breeze::new(BreezeConfig::default(), 5);
        let run = |threads| {
            let mut a = Animation::new(&planted, params.flower_mass);
            a.set_threads(threads);
            for f in 0..20 {
                a.step(&wind, f as f32 / 30.0, 1.0 / 30.0, 2.5, 40.0, 4.0);
            }
            (a.blade_out.clone(), a.flower_out.clone())
        };
        let one = run(1);
        assert_eq!(one, run(3));
        assert_eq!(one, run(16));
        // And the blades did move.
        let rest = Animation::new(&planted, params.flower_mass);
        assert_ne!(one.0, rest.blade_out);
    }
}
