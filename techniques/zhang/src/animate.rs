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
        };
        let samples = 3 * a.blades.len() + a.flowers.len();
        a.points = vec![Vec3::ZERO; samples];
        a.winds = vec![Vec3::ZERO; samples];
        a.write_out();
        a
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
    /// inverse mass is 0) and at each petal, in one batched [`WindField::velocities`] call,
    /// then `ceil(dt / MAX_STEP)` Verlet steps follow. No allocation.
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
        // One batched wind query for every sample point of the frame.
        let (blade_points, flower_points) = self.points.split_at_mut(3 * self.blades.len());
        for (p, b) in blade_points.chunks_exact_mut(3).zip(&self.blades) {
            p.copy_from_slice(&b.pos[1..]);
        }
        for (p, f) in flower_points.iter_mut().zip(&self.flowers) {
            *p = f.pos;
        }
        wind.velocities(&self.points, time, &mut self.winds);
        let (blade_winds, flower_winds) = self.winds.split_at(3 * self.blades.len());
        for (b, w) in self.blades.iter_mut().zip(blade_winds.chunks_exact(3)) {
            let w = [w[0], w[1], w[2]];
            let ground = b.pos[0].y;
            for _ in 0..steps {
                b.step(&w, &k, ground);
            }
        }
        for (f, &w) in self.flowers.iter_mut().zip(flower_winds) {
            for _ in 0..steps {
                f.step(w, &k);
            }
        }
        self.write_out();
    }

    fn write_out(&mut self) {
        for (out, b) in self.blade_out.iter_mut().zip(&self.blades) {
            let rot = b.rotation();
            let v = |p: Vec3, w: f32| [p.x, p.y, p.z, w];
            *out = BladeDynamic {
                p1_rotation: v(b.pos[1], rot),
                p2: v(b.pos[2], 0.0),
                p3: v(b.pos[3], 0.0),
            };
        }
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
