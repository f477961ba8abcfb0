//! What a technique gets each frame. Time is passed in, never read from a clock, so a frame is
//! a pure function of (scene, seed, frame index).

use crate::Scene;
use crate::camera::Camera;
use crate::scene::{LightsConfig, SkyConfig};
use crate::target::Size;
use crate::wind::WindField;

/// Everything that varies from frame to frame, for [`crate::GrassTechnique::update`] and
/// [`crate::GrassTechnique::prepare`].
pub struct FrameInputs<'a> {
    /// Frame number, from 0.
    pub frame: u64,
    /// Scene time, s (`frame / fps`).
    pub time: f32,
    /// Time since the previous frame, s.
    pub dt: f32,
    /// The view.
    pub camera: Camera,
    /// The scene (terrain, grass, lights, sky, seed).
    pub scene: &'a Scene,
    /// The wind, already advanced to `time`.
    pub wind: &'a dyn WindField,
    /// Target size in pixels.
    pub size: Size,
    /// Debug view a person chose (0 = none); techniques document what they show.
    pub debug_view: u32,
}

impl FrameInputs<'_> {
    /// The scene's lights.
    pub fn lights(&self) -> &LightsConfig {
        &self.scene.config.lights
    }

    /// The scene's sky.
    pub fn sky(&self) -> &SkyConfig {
        &self.scene.config.sky
    }

    /// Centre and radius of the scene's moving object at this frame's time, if it has one.
    pub fn object(&self) -> Option<(glam::Vec3, f32)> {
        let o = self.scene.config.object.as_ref()?;
        Some((o.centre(&self.scene.terrain, self.time), o.radius))
    }

    /// The GPU copy of the frame constants.
    pub fn globals(&self, max_wind_speed: f32) -> FrameGlobals {
        let view_proj = self.camera.view_projection();
        let l = self.lights();
        let s = self.sky();
        let t = &self.scene.terrain;
        let v4 = |v: [f32; 3], w: f32| [v[0], v[1], v[2], w];
        let (lo, hi) = t.height_range();
        let state = l.at(self.time);
        let sun = state.sun_direction;
        let (point_position, point_color) = match state.point {
            Some((p, c, beta)) => (p.extend(beta).to_array(), c.extend(1.0).to_array()),
            None => ([0.0; 4], [0.0; 4]),
        };
        FrameGlobals {
            view_proj: view_proj.to_cols_array_2d(),
            inv_view_proj: view_proj.inverse().to_cols_array_2d(),
            camera_pos: self.camera.eye.extend(self.time).to_array(),
            camera_forward: self.camera.forward.extend(self.dt).to_array(),
            sun_direction: sun.extend(0.0).to_array(),
            sun_color: v4(l.sun_color, 0.0),
            ambient: v4(l.ambient, 0.0),
            sky_zenith: v4(s.zenith, 0.0),
            sky_horizon: v4(s.horizon, 0.0),
            ground_color: v4(s.ground, s.fog_density),
            terrain: [t.min_corner().x, t.min_corner().y, t.size().x, t.size().y],
            viewport: [
                self.size.width as f32,
                self.size.height as f32,
                1.0 / self.size.width as f32,
                1.0 / self.size.height as f32,
            ],
            frame: [
                self.frame as u32,
                self.scene.config.seed as u32,
                self.debug_view,
                0,
            ],
            wind_info: [max_wind_speed, 0.0, 0.0, 0.0],
            terrain_range: [lo, hi, self.camera.far, 0.0],
            object: self
                .object()
                .map_or([0.0; 4], |(c, r)| c.extend(r).to_array()),
            point_position,
            point_color,
        }
    }
}

/// Mirror of the prelude's `Globals` (bind group 0, binding 0). Every field is 16-byte
/// aligned, so the `#[repr(C)]` layout equals WGSL's uniform layout; a test checks the size
/// against naga's.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameGlobals {
    /// World to clip.
    pub view_proj: [[f32; 4]; 4],
    /// Clip to world.
    pub inv_view_proj: [[f32; 4]; 4],
    /// Eye position; w = time.
    pub camera_pos: [f32; 4],
    /// View direction; w = dt.
    pub camera_forward: [f32; 4],
    /// Towards the sun.
    pub sun_direction: [f32; 4],
    /// Sun irradiance.
    pub sun_color: [f32; 4],
    /// Ambient light.
    pub ambient: [f32; 4],
    /// Sky at the zenith.
    pub sky_zenith: [f32; 4],
    /// Sky at the horizon (and fog colour).
    pub sky_horizon: [f32; 4],
    /// Bare ground albedo; w = fog density.
    pub ground_color: [f32; 4],
    /// Terrain min corner (x, z) and size (x, z).
    pub terrain: [f32; 4],
    /// Target size and its reciprocal.
    pub viewport: [f32; 4],
    /// Frame index, seed, debug view.
    pub frame: [u32; 4],
    /// Largest wind speed.
    pub wind_info: [f32; 4],
    /// Lowest and highest ground height, camera far plane.
    pub terrain_range: [f32; 4],
    /// The scene's moving object: centre and radius (radius 0: none).
    pub object: [f32; 4],
    /// The point light's position; w = its attenuation β.
    pub point_position: [f32; 4],
    /// The point light's intensity; w = 1 when there is one, 0 otherwise.
    pub point_color: [f32; 4],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn globals_mirror_the_prelude() {
        assert_eq!(
            crate::shaders::struct_size("", "Globals").unwrap() as usize,
            std::mem::size_of::<FrameGlobals>()
        );
    }
}
