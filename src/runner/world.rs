//! The world: what every view of one scene shares. The scene, its GPU resources (bind group 0,
//! terrain, wind texture, background) and the wind, with the wind's clock: the wind is advanced
//! and baked into the wind texture once per frame, however many views draw that frame.
//!
//! A stateful wind (the fluid solver) is thereby stepped once per frame, not once per view: the
//! UI's panes and an interleaved run's techniques all see the one wind. Views
//! ([`View`](super::View)) hold what differs between pictures of the same world: the target,
//! the camera override, the debug view and the pass timer. The frame itself, the one code path
//! every caller renders through, is [`World::frame`].

use std::time::Instant;

use crate::scene::SceneGpu;
use crate::wind::{WindConfig, WindField};
use crate::{GpuContext, Result, Scene};

/// The scene, its GPU resources and its wind, shared by every view that draws it.
pub struct World<'g> {
    /// Device and queue.
    pub gpu: &'g GpuContext,
    /// The scene (lights edited at run time are written here, and every view sees them).
    pub scene: Scene,
    /// Bind group 0, terrain, wind texture, background.
    pub scene_gpu: SceneGpu,
    wind: Box<dyn WindField>,
    /// Frame the wind stands at.
    wind_frame: Option<u64>,
    /// Frame the wind texture holds, and the CPU time its wind stage took.
    baked: Option<(u64, f64)>,
    /// Steps taken by a stateful wind since the world was made.
    wind_steps: u64,
}

impl<'g> World<'g> {
    /// Sets up `scene`'s GPU resources for targets of `sample_count` samples, and its wind.
    pub fn new(gpu: &'g GpuContext, scene: Scene, sample_count: u32) -> Result<Self> {
        let scene_gpu = SceneGpu::new(gpu, &scene, sample_count)?;
        let wind = scene.wind()?;
        Ok(Self {
            gpu,
            scene,
            scene_gpu,
            wind,
            wind_frame: None,
            baked: None,
            wind_steps: 0,
        })
    }

    /// Replaces the scene's wind (validated) and restarts it from time 0.
    pub fn set_wind(&mut self, config: WindConfig) -> Result<()> {
        let wind = crate::wind::build(
            &config,
            self.scene.config.seed,
            &self.scene.terrain,
            self.scene.config.object.as_ref(),
        )?;
        self.scene.config.wind = config;
        self.wind = wind;
        self.wind_frame = None;
        self.baked = None;
        Ok(())
    }

    /// The wind as it stands after the last frame.
    pub fn wind(&self) -> &dyn WindField {
        self.wind.as_ref()
    }

    /// How many times a stateful wind has been stepped since the world was made (replays
    /// after going back in time included; a stateless wind is never stepped).
    pub fn wind_steps(&self) -> u64 {
        self.wind_steps
    }

    /// Advances the wind to `frame` (stateful fields are rebuilt and replayed when going back;
    /// a wind already at `frame` is left as it is).
    pub fn advance_wind(&mut self, frame: u64) -> Result<()> {
        if self.wind.is_stateless() {
            self.wind_frame = Some(frame);
            return Ok(());
        }
        if self.wind_frame.is_some_and(|f| f > frame) {
            self.wind = self.scene.wind()?;
            self.wind_frame = None;
        }
        let start = self.wind_frame.map_or(0, |f| f + 1);
        for f in start..=frame {
            self.wind.advance(self.scene.time_of(f), self.scene.dt());
            self.wind_steps += 1;
        }
        self.wind_frame = Some(frame);
        Ok(())
    }

    /// The wind stage of `frame`: advances the wind to it and bakes it into the wind texture,
    /// once per frame (a second view drawing the same frame finds both done). Returns the CPU
    /// time the stage took when it was done, so every view drawing the frame reports the same
    /// cost.
    pub fn prepare_wind(&mut self, frame: u64) -> Result<f64> {
        let t0 = Instant::now();
        self.advance_wind(frame)?;
        match self.baked {
            Some((baked, ms)) if baked == frame => Ok(ms),
            _ => {
                let time = self.scene.time_of(frame);
                self.scene_gpu.bake_wind(self.wind.as_ref(), time);
                let ms = t0.elapsed().as_secs_f64() * 1e3;
                self.baked = Some((frame, ms));
                Ok(ms)
            }
        }
    }
}
