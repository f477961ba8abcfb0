//! The sky, the ground, the scene's props (trees and stones, [`super::props`]) and its moving
//! object, drawn the same way before every technique's grass, so differences between images
//! come from the grass alone.

use super::ground::{GroundDraws, GroundGpu};
use super::props::{PropVertex, PropsGpu};
use crate::shaders::{self, FragmentKind, PipelineCost, RenderPipeline};
use crate::target::{COLOR_FORMAT, DEPTH_FORMAT};
use crate::terrain::chunks::{ChunkInstance, Pattern};

/// Sky, ground, prop and object pipelines.
pub struct Background {
    sky: RenderPipeline,
    apron: RenderPipeline,
    ground: RenderPipeline,
    props: RenderPipeline,
    object: RenderPipeline,
}

impl Background {
    /// Builds the pipelines for `sample_count`.
    pub fn new(
        device: &wgpu::Device,
        scene_layout: &wgpu::BindGroupLayout,
        sample_count: u32,
    ) -> Self {
        let module = shaders::module(device, "background", shaders::BACKGROUND);
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("background"),
            bind_group_layouts: &[Some(scene_layout)],
            immediate_size: 0,
        });
        let pipeline = |label,
                        vs,
                        fs,
                        buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
                        depth_write,
                        compare,
                        topology| {
            let targets = [Some(COLOR_FORMAT.into())];
            let multisample = wgpu::MultisampleState {
                count: sample_count,
                ..Default::default()
            };
            let kind = FragmentKind::of(&targets, &multisample, module.discards(fs));
            let raw = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState {
                    topology,
                    cull_mode: Some(wgpu::Face::Back),
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(depth_write),
                    depth_compare: Some(compare),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample,
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(fs),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            });
            RenderPipeline::from_raw(raw, PipelineCost::of(kind, &module, (vs, fs), &[]))
        };
        let (list, strip) = (
            wgpu::PrimitiveTopology::TriangleList,
            wgpu::PrimitiveTopology::TriangleStrip,
        );
        Self {
            sky: pipeline(
                "sky",
                "vs_sky",
                "fs_sky",
                &[],
                false,
                wgpu::CompareFunction::Always,
                list,
            ),
            apron: pipeline(
                "apron",
                "vs_apron",
                "fs_apron",
                &[],
                true,
                wgpu::CompareFunction::Less,
                strip,
            ),
            ground: pipeline(
                "ground",
                "vs_ground",
                "fs_ground",
                &[Some(Pattern::LAYOUT), Some(ChunkInstance::LAYOUT)],
                true,
                wgpu::CompareFunction::Less,
                list,
            ),
            props: pipeline(
                "trees and stones",
                "vs_prop",
                "fs_prop",
                &[Some(PropVertex::LAYOUT)],
                true,
                wgpu::CompareFunction::Less,
                list,
            ),
            object: pipeline(
                "object",
                "vs_object",
                "fs_object",
                &[],
                true,
                wgpu::CompareFunction::Less,
                list,
            ),
        }
    }

    /// Draws the sky, the apron beyond the terrain, the ground (the chunks `ground_draws`
    /// names, [`GroundGpu::upload`]), the scene's trees and stones
    /// (Zhang Sec. 5.5.2: opaque and depth-tested, for every technique; none when the covering
    /// map has none), then the scene's moving object (a sphere ray-cast on a camera-facing
    /// quad; nothing when it has none). Bind group 0 must be set.
    pub fn draw(
        &self,
        pass: &mut crate::technique::RenderPass<'_>,
        ground: &GroundGpu,
        ground_draws: &GroundDraws,
        props: &PropsGpu,
    ) {
        pass.set_pipeline(&self.sky);
        pass.draw(0..3, 0..1);
        pass.set_pipeline(&self.apron);
        pass.draw(0..4, 0..1);
        pass.set_pipeline(&self.ground);
        ground.draw(pass, ground_draws);
        if let Some(vertices) = &props.vertices {
            pass.set_pipeline(&self.props);
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.draw(0..props.count, 0..1);
        }
        pass.set_pipeline(&self.object);
        pass.draw(0..6, 0..1);
    }
}
