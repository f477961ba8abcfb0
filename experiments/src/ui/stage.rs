//! The stage: ONE world (the scene, its GPU resources and the wind) and the panes that show
//! it, each a technique drawn into its own view (target, timer, debug view).
//!
//! The world is advanced once per frame for every pane: frames skipped by a fast time scale
//! and the warm-up of a rebuilt technique are simulated in step, frame by frame, every pane
//! in turn, so a stateful wind (the fluid solver) takes one step per frame, not one per pane.
//! Lights edited in the panel are written into the one scene, so every pane sees them.

use grassbench::glam::Vec3;
use grassbench::runner::World;
use grassbench::scene::PointLight;
use grassbench::target::Size;
use grassbench::wind::WindConfig;
use grassbench::{GpuContext, Scene};

use super::pane::{CATCH_UP_FRAMES, Pane};

/// The shared world and its panes.
pub struct Stage {
    /// Built-in scene name (or path) the scene was loaded by.
    pub scene_name: String,
    /// The scene, its GPU resources and the wind: one for all panes.
    pub world: World<'static>,
    /// The panes, in order.
    pub panes: Vec<Pane>,
    /// Size of every pane at full resolution.
    pub size: Size,
    /// 4x MSAA in every pane.
    pub msaa: bool,
}

/// Samples per pixel of targets with or without MSAA (as `RenderTarget::new` makes them).
fn sample_count(msaa: bool) -> u32 {
    if msaa { 4 } else { 1 }
}

impl Stage {
    /// A stage showing `scene` (loaded as `scene_name`), with no pane yet.
    pub fn new(
        gpu: &'static GpuContext,
        scene_name: &str,
        scene: Scene,
        size: Size,
        msaa: bool,
    ) -> anyhow::Result<Self> {
        Ok(Self {
            scene_name: scene_name.to_owned(),
            world: World::new(gpu, scene, sample_count(msaa))?,
            panes: Vec::new(),
            size,
            msaa,
        })
    }

    /// Replaces the scene with `scene` (loaded as `name`): a new world; the panes are to be
    /// rebuilt ([`Stage::build_panes`]).
    pub fn set_scene(&mut self, name: &str, scene: Scene) -> anyhow::Result<()> {
        self.world = World::new(self.world.gpu, scene, sample_count(self.msaa))?;
        self.scene_name = name.to_owned();
        self.panes.clear();
        Ok(())
    }

    /// (Re)creates `count` panes with techniques from `ids` (cycled), caught up to `frame`.
    /// The world is kept (with its edited lights and wind) unless the MSAA setting changed,
    /// which its GPU resources depend on.
    pub fn build_panes(&mut self, count: usize, ids: &[String], frame: u64) -> anyhow::Result<()> {
        if self.world.scene_gpu.sample_count != sample_count(self.msaa) {
            let scene = self.world.scene.clone();
            self.world = World::new(self.world.gpu, scene, sample_count(self.msaa))?;
        }
        self.panes.clear();
        for k in 0..count {
            let id = ids
                .get(k % ids.len().max(1))
                .map_or("reference", |s| s.as_str());
            self.panes
                .push(Pane::new(&self.world, id, self.size, self.msaa)?);
        }
        self.recreate(&(0..count).collect::<Vec<_>>(), frame);
        Ok(())
    }

    /// Rebuilds the techniques of panes `which` with their overrides and catches them up to
    /// `frame` together: the world steps through the warm-up frames once for all of them.
    pub fn recreate(&mut self, which: &[usize], frame: u64) {
        for &k in which {
            if let Some(p) = self.panes.get_mut(k) {
                p.create(&self.world);
            }
        }
        for g in frame.saturating_sub(CATCH_UP_FRAMES)..frame {
            for &k in which {
                let Some(p) = self.panes.get_mut(k) else {
                    continue;
                };
                if let Err(e) = p.catch_up(&mut self.world, g) {
                    p.error = Some(format!("{e:#}"));
                    p.technique = None;
                }
            }
        }
    }

    /// Rebuilds every pane's technique at `frame`.
    pub fn recreate_all(&mut self, frame: u64) {
        self.recreate(&(0..self.panes.len()).collect::<Vec<_>>(), frame);
    }

    /// Switches pane `k` to technique `id` (default parameters), keeping camera, time and
    /// scene.
    pub fn set_technique(&mut self, k: usize, id: &str, frame: u64) {
        if let Some(p) = self.panes.get_mut(k) {
            p.technique_id = id.to_owned();
            p.overrides.clear();
            p.history.clear();
        }
        self.recreate(&[k], frame);
    }

    /// Marks every pane for re-rendering.
    pub fn invalidate(&mut self) {
        for p in &mut self.panes {
            p.invalidate();
        }
    }

    /// Brings every pane that needs it to `frame` (seen from `camera`, read back when
    /// `capture`); `want` says for pane `k` whether to draw it at all (`None`: not now) and at
    /// half resolution (`Some(true)`). Frames skipped since a pane last drew are simulated
    /// first, frame by frame with every pane in turn, then each pane draws and is handed to
    /// `done`. The world's wind thus advances once per frame, whatever the number of panes.
    /// Before each pane but the first, `moved` may give a newer camera: the remaining panes
    /// draw from it, and those already drawn are left marked to draw again.
    pub fn render(
        &mut self,
        frame: u64,
        camera: Option<(Vec3, Vec3)>,
        capture: bool,
        want: impl Fn(usize, &Pane) -> Option<bool>,
        mut done: impl FnMut(usize, &Pane),
        mut moved: impl FnMut() -> Option<Option<(Vec3, Vec3)>>,
    ) {
        let world = &self.world;
        let mut plans: Vec<Option<u64>> = self
            .panes
            .iter_mut()
            .enumerate()
            .map(|(k, p)| {
                let preview = want(k, p)?;
                p.plan(world, frame, camera, capture, preview)
            })
            .collect();
        let start = plans.iter().flatten().min().copied().unwrap_or(frame);
        for g in start..frame {
            for (p, plan) in self.panes.iter_mut().zip(&mut plans) {
                if plan.is_some_and(|from| from <= g)
                    && let Err(e) = p.catch_up(&mut self.world, g)
                {
                    p.error = Some(e.to_string());
                    *plan = None;
                }
            }
        }
        let mut drawn = false;
        for (k, plan) in plans.into_iter().enumerate() {
            if plan.is_none() {
                continue;
            }
            if drawn && let Some(newer) = moved() {
                // The camera moved meanwhile: the panes drawn so far are stale (drawn again next
                // time), the others draw from where it is now.
                for p in &mut self.panes {
                    p.invalidate();
                    p.view.camera_override = newer;
                }
            }
            let Some(p) = self.panes.get_mut(k) else {
                continue;
            };
            if p.draw(&mut self.world, frame, capture) {
                done(k, p);
            }
            drawn = true;
        }
    }

    /// Points the sun along `direction` (towards the sun), replacing the scene's sun
    /// keyframes: techniques that light per frame (boulanger's BTF slices, every shader's
    /// Lambert term) follow at once, in every pane.
    pub fn set_sun(&mut self, direction: [f32; 3]) {
        let lights = &mut self.world.scene.config.lights;
        lights.sun_direction = direction;
        lights.sun_keys.clear();
        self.invalidate();
    }

    /// Sets (or removes) the point light; techniques read it per frame.
    pub fn set_point_light(&mut self, light: Option<PointLight>) {
        self.world.scene.config.lights.point = light;
        self.invalidate();
    }

    /// Replaces the wind (restarted from time 0) for every pane.
    pub fn set_wind(&mut self, config: WindConfig) -> grassbench::Result<()> {
        let result = self.world.set_wind(config);
        self.invalidate();
        result
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    /// A context on the backend `GRASSBENCH_BACKEND` names, for the life of the test binary.
    fn gpu() -> &'static GpuContext {
        let choice = grassbench::gpu::BackendChoice::from_env().unwrap();
        Box::leak(Box::new(GpuContext::new(choice).unwrap()))
    }

    /// The meadow with few blades and the fluid wind (stateful: one solver step per frame).
    fn fluid_meadow() -> Scene {
        let base = crate::scenes::load("meadow").unwrap();
        let mut config = base.config.clone();
        config.grass.density *= 0.02;
        config.wind = WindConfig::default_for("fluid").unwrap();
        Scene::from_config(config, base.base_dir.clone()).unwrap()
    }

    const SIZE: Size = Size {
        width: 96,
        height: 54,
    };

    fn stage(gpu: &'static GpuContext, panes: usize) -> Stage {
        let mut stage = Stage::new(gpu, "meadow", fluid_meadow(), SIZE, false).unwrap();
        stage
            .build_panes(panes, &["reference".to_owned()], 0)
            .unwrap();
        stage
    }

    /// Plays frames 0..=`to` as the window does at time scale `step`.
    fn play(stage: &mut Stage, to: u64, step: usize) {
        for f in (0..=to).step_by(step) {
            stage.render(f, None, true, |_, _| Some(false), |_, _| {}, || None);
        }
        stage.render(to, None, true, |_, _| Some(false), |_, _| {}, || None);
    }

    #[test]
    fn panes_share_one_world_advanced_once_per_frame() {
        let gpu = gpu();
        let mut two = stage(gpu, 2);
        let mut one = stage(gpu, 1);
        // Time scale 3: two of every three frames are only simulated.
        play(&mut two, 9, 3);
        play(&mut one, 9, 3);
        // Frames 0..=9: ten solver steps, whatever the number of panes.
        assert_eq!(two.world.wind_steps(), 10);
        assert_eq!(one.world.wind_steps(), 10);
        // The wind stands where a single pane's does, and every pane shows the same picture.
        let probe = Vec3::new(3.0, 0.5, -2.0);
        let t = two.world.scene.time_of(9);
        assert_eq!(
            two.world.wind().velocity(probe, t),
            one.world.wind().velocity(probe, t)
        );
        let image = |s: &Stage, k: usize| s.panes[k].last_image.clone().unwrap();
        assert_eq!(image(&two, 0), image(&one, 0));
        assert_eq!(image(&two, 1), image(&one, 0));

        // A sun moved in the panel reaches every pane: both redraw, alike, and differently.
        let before = image(&two, 0);
        two.set_sun(crate::ui::sun_direction([-60.0, 25.0]));
        two.render(9, None, true, |_, _| Some(false), |_, _| {}, || None);
        assert_eq!(two.world.wind_steps(), 10, "a redraw steps no wind");
        let (a, b) = (image(&two, 0), image(&two, 1));
        assert_eq!(a, b);
        assert_ne!(a, before, "the sun did not reach the panes");
    }

    #[test]
    fn a_camera_moved_while_panes_draw_reaches_the_panes_still_to_draw() {
        let gpu = gpu();
        let mut stage = stage(gpu, 2);
        let scene = stage.world.scene.clone();
        let cam = scene.camera_at(3, SIZE);
        let turned = Some((
            cam.eye,
            (cam.forward + Vec3::new(0.4, 0.0, 0.0)).normalize(),
        ));
        let mut order = Vec::new();
        // The window turns the camera while pane 1 draws.
        let mut asked = 0;
        stage.render(
            3,
            None,
            true,
            |_, _| Some(false),
            |k, _| order.push(k),
            || {
                asked += 1;
                Some(turned)
            },
        );
        assert_eq!((order, asked), (vec![0, 1], 1));
        let image = |s: &Stage, k: usize| s.panes[k].last_image.clone().unwrap();
        let (first, second) = (image(&stage, 0), image(&stage, 1));
        assert_ne!(first, second, "pane 2 did not draw from the turned camera");
        // Next time pane 1 draws again, from the turned camera; pane 2 is up to date.
        let mut order = Vec::new();
        stage.render(
            3,
            turned,
            true,
            |_, _| Some(false),
            |k, _| order.push(k),
            || None,
        );
        assert_eq!(order, [0]);
        assert_eq!(image(&stage, 0), second);
    }
}
