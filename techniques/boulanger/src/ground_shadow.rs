//! Shadows projected on the ground (Boulanger Sec. 3.5, Fig. 15): the ground's darkening by the
//! grass, as opposed to the blade-to-blade shadows of the shadow mask ([`crate::shadow`]).
//!
//! The paper's method, one render pass before the grass (`shaders/grass.wgsl`, "Shadows
//! projected on the ground"):
//! 1. the geometric blades are drawn with the planar projection matrix of the ground plane and
//!    the light, without lighting, into the stencil only: a pixel is marked where a projected
//!    blade passes the depth test against the ground (nothing else is drawn yet, so the grass
//!    cannot shadow itself this way);
//! 2. a screen-covering triangle, stencil-tested, multiplies the marked pixels by the ground's
//!    shadowed-to-lit ratio (the paper's "black quadrilateral with blending"; here the ratio the
//!    core's ground shading gives, so the shadow removes exactly the sun's direct light from
//!    flat ground): overlapping blade shadows darken once, and shadows are hard;
//! 3. the horizontal slice of every cell and macro-cell with a slice is projected likewise and
//!    multiplies the ground by its opacity there, without stencil since slice shadows do not
//!    overlap (and only where no blade shadow was, so the two do not darken twice in the band
//!    where a cell has both). The vertical slices cast none: "the projected shadows would cover
//!    the whole ground".
//!
//! The light is the sun (a directional light: `M = (n·l) I − l nᵀ`); the core's ground is lit
//! by the sun alone, so the point light casts no ground shadow. On uneven terrain each blade is
//! projected on the plane tangent to the ground at its root, each slice vertex on the plane
//! under it. Blades fading out (Eq. 5) stop casting when their opacity falls under one half, and
//! the slices' shadows carry their complementary share, so the transition between the two
//! kinds of shadow follows the grass's own.
//!
//! Cost: the geometric blades' vertices a second time plus the fill of their shadows, one
//! screen of fill for the cover (stencil-rejected outside shadows on real GPUs), and the
//! horizontal slices' fill a second time.

use glam::Vec3;
use grassbench::shaders::{PipelineSpec, render_pipeline};
use grassbench::{target, wgpu};

use crate::shader::SliceQuad;

/// The stencil value blade shadows write and the cover tests for.
pub const STENCIL_MARK: u32 = 1;

/// The lowest sun, as the sine of its elevation over the ground plane, that casts projected
/// shadows (the shader's `SHADOW_MIN_SINE`).
pub const MIN_SINE: f32 = 0.05;

/// The three pipelines of the ground-shadow pass.
pub struct GroundShadows {
    /// Projected blades into the stencil (blade layout).
    pub blades: grassbench::shaders::RenderPipeline,
    /// The darkening cover, where the stencil is marked (group 0 only).
    pub cover: grassbench::shaders::RenderPipeline,
    /// Projected horizontal slices, multiplied in where the stencil is not marked (slice
    /// layout).
    pub slices: grassbench::shaders::RenderPipeline,
}

/// The same stencil test on both faces (blades are two-sided).
fn stencil(compare: wgpu::CompareFunction, write: bool) -> wgpu::StencilState {
    let face = wgpu::StencilFaceState {
        compare,
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op: wgpu::StencilOperation::Keep,
        pass_op: if write {
            wgpu::StencilOperation::Replace
        } else {
            wgpu::StencilOperation::Keep
        },
    };
    wgpu::StencilState {
        front: face,
        back: face,
        read_mask: 0xff,
        write_mask: if write { 0xff } else { 0 },
    }
}

/// Depth tested with `compare` (never written) and the stencil `stencil`.
fn depth_stencil(
    compare: wgpu::CompareFunction,
    stencil: wgpu::StencilState,
) -> Option<wgpu::DepthStencilState> {
    Some(wgpu::DepthStencilState {
        format: target::DEPTH_FORMAT,
        depth_write_enabled: Some(false),
        depth_compare: Some(compare),
        stencil,
        bias: Default::default(),
    })
}

/// Colour multiplied into the target: destination x source, alpha kept.
const MULTIPLY: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::Zero,
        dst_factor: wgpu::BlendFactor::Src,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::Zero,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
};

impl GroundShadows {
    /// The pipelines, from the technique's shader module and its `[blade, slice, group 0 only]`
    /// pipeline layouts.
    pub fn new(
        device: &wgpu::Device,
        module: &grassbench::shaders::Module,
        [blade_layout, slice_layout, cover_layout]: [&wgpu::PipelineLayout; 3],
        sample_count: u32,
    ) -> Self {
        use wgpu::CompareFunction::{Always, Equal, LessEqual, NotEqual};
        let target = |blend, write_mask| {
            [Some(wgpu::ColorTargetState {
                format: target::COLOR_FORMAT,
                blend,
                write_mask,
            })]
        };
        let stencil_only = target(None, wgpu::ColorWrites::empty());
        let multiply = target(Some(MULTIPLY), wgpu::ColorWrites::ALL);
        let no_cull = |topology| wgpu::PrimitiveState {
            topology,
            cull_mode: None,
            ..Default::default()
        };
        let spec = |label, layout, entries, buffers, topology, depth, targets| PipelineSpec {
            primitive: no_cull(topology),
            depth,
            targets,
            ..PipelineSpec::new(label, layout, module, entries, buffers, sample_count)
        };
        let quad = [Some(SliceQuad::LAYOUT)];
        Self {
            blades: render_pipeline(
                device,
                &spec(
                    "boulanger blade shadows",
                    blade_layout,
                    ("vs_ground_shadow", "fs_ground_shadow"),
                    &[],
                    wgpu::PrimitiveTopology::TriangleStrip,
                    depth_stencil(LessEqual, stencil(Always, true)),
                    &stencil_only,
                ),
            ),
            cover: render_pipeline(
                device,
                &spec(
                    "boulanger shadow cover",
                    cover_layout,
                    ("vs_shadow_cover", "fs_shadow_cover"),
                    &[],
                    wgpu::PrimitiveTopology::TriangleList,
                    depth_stencil(Always, stencil(Equal, false)),
                    &multiply,
                ),
            ),
            slices: render_pipeline(
                device,
                &spec(
                    "boulanger slice shadows",
                    slice_layout,
                    ("vs_slice_shadow", "fs_slice_shadow"),
                    &quad,
                    wgpu::PrimitiveTopology::TriangleList,
                    depth_stencil(LessEqual, stencil(NotEqual, false)),
                    &multiply,
                ),
            ),
        }
    }
}

/// CPU twin of the shader's `planar_projection`: `p` moved along `l` (unit, towards the light)
/// onto the plane through `origin` with unit normal `n`; `None` when the light is under
/// [`MIN_SINE`] over the plane.
pub fn planar_projection(p: Vec3, origin: Vec3, n: Vec3, l: Vec3) -> Option<Vec3> {
    let nl = n.dot(l);
    (nl >= MIN_SINE).then(|| p - l * ((p - origin).dot(n) / nl))
}

/// CPU twin of the shader's `ground_shadow_factor`: per channel, the share of a flat ground's
/// light (ambient + sun · l.y) a shadow leaves (the ambient).
pub fn shadow_factor(ambient: Vec3, sun_color: Vec3, sun_direction: Vec3) -> Vec3 {
    ambient / (ambient + sun_color * sun_direction.y.max(0.0)).max(Vec3::splat(1e-4))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn unit(v: [f32; 3]) -> Vec3 {
        Vec3::from(v).normalize()
    }

    proptest! {
        /// The projection lands on the plane, on the line through the point along the light,
        /// and leaves points of the plane where they are.
        #[test]
        fn projection_lands_on_the_plane_along_the_light(
            p in prop::array::uniform3(-5.0f32..5.0),
            origin in prop::array::uniform3(-5.0f32..5.0),
            n in (-0.5f32..0.5, 0.6f32..1.0, -0.5f32..0.5),
            l in (-1.0f32..1.0, 0.1f32..1.0, -1.0f32..1.0),
        ) {
            let (p, origin) = (Vec3::from(p), Vec3::from(origin));
            let n = unit([n.0, n.1, n.2]);
            let l = unit([l.0, l.1, l.2]);
            let Some(q) = planar_projection(p, origin, n, l) else {
                prop_assume!(false);
                unreachable!();
            };
            let scale = 1.0 + (p - origin).length() / n.dot(l);
            prop_assert!((q - origin).dot(n).abs() < 1e-4 * scale);
            prop_assert!((q - p).cross(l).length() < 1e-4 * scale);
            let on = planar_projection(q, origin, n, l).unwrap_or(Vec3::NAN);
            prop_assert!((on - q).length() < 1e-4 * scale);
        }
    }

    /// A blade 0.5 m tall under a sun 45° up casts a shadow 0.5 m long away from the sun.
    #[test]
    fn a_45_degree_sun_casts_a_shadow_as_long_as_the_blade() {
        let l = unit([1.0, 1.0, 0.0]);
        let tip = Vec3::new(2.0, 0.5, 3.0);
        let q = planar_projection(tip, Vec3::new(2.0, 0.0, 3.0), Vec3::Y, l).unwrap_or(Vec3::NAN);
        assert!((q - Vec3::new(1.5, 0.0, 3.0)).length() < 1e-6, "{q}");
        assert!(planar_projection(tip, Vec3::ZERO, Vec3::Y, unit([1.0, 0.01, 0.0])).is_none());
    }

    /// Shadowed ground keeps its ambient light: the factor times the lit ground is the ambient
    /// term, and no sun (below the horizon) leaves the ground as it is.
    #[test]
    fn the_shadow_keeps_the_ambient_term() {
        let (ambient, sun) = (Vec3::new(0.3, 0.36, 0.45), Vec3::new(1.6, 1.45, 1.2));
        let l = unit([0.45, 0.75, 0.35]);
        let f = shadow_factor(ambient, sun, l);
        let lit = ambient + sun * l.y;
        assert!((f * lit - ambient).abs().max_element() < 1e-6);
        assert!(f.max_element() < 1.0);
        assert_eq!(
            shadow_factor(ambient, sun, unit([1.0, -0.2, 0.0])),
            Vec3::ONE
        );
    }
}
