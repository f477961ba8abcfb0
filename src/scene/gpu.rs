//! What the core keeps on the GPU for a scene: bind group 0 (frame globals, terrain maps,
//! wind texture), the ground mesh, the props (trees and stones of the covering map) and the
//! background pipelines. Techniques borrow it.

use wgpu::util::DeviceExt as _;

use super::Background;
use super::ground::{GroundDraws, GroundGpu};
use super::props::PropsGpu;
use crate::frame::{FrameGlobals, FrameInputs};
use crate::terrain::TerrainGpu;
use crate::terrain::chunks::GroundLod;
use crate::wind::{WindField, WindTexture};
use crate::{GpuContext, Result, Scene};

/// Bind group 0 and the shared scene resources.
pub struct SceneGpu {
    /// Layout of bind group 0 (every technique's pipeline layout starts with it).
    pub layout: wgpu::BindGroupLayout,
    /// Bind group 0.
    pub bind_group: wgpu::BindGroup,
    /// The [`FrameGlobals`] uniform buffer.
    pub globals: wgpu::Buffer,
    /// Terrain maps and ground mesh.
    pub terrain: TerrainGpu,
    /// The ground's chunk patterns and per-frame instances.
    pub ground: GroundGpu,
    /// How coarse far chunks of the ground may be drawn ([`GroundLod::DEFAULT`];
    /// [`GroundLod::FINEST`] draws the mesh's own triangles in view).
    pub ground_lod: GroundLod,
    /// The baked wind.
    pub wind: WindTexture,
    /// The trees and stones of the covering map (Zhang Sec. 5.5.2), drawn with the
    /// background for every technique.
    pub props: PropsGpu,
    /// Sky, ground, prop and object pipelines.
    pub background: Background,
    /// Sample count the background pipelines were built for.
    pub sample_count: u32,
}

impl SceneGpu {
    /// Uploads a scene for targets with `sample_count` samples.
    pub fn new(gpu: &GpuContext, scene: &Scene, sample_count: u32) -> Result<Self> {
        gpu.scoped("uploading the scene", || {
            let device = &gpu.device;
            let texture = |binding, sample_type| wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Texture {
                    sample_type,
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            };
            let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("scene (group 0)"),
                entries: &[
                    wgpu::BindGroupLayoutEntry {
                        binding: 0,
                        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT
                            | wgpu::ShaderStages::COMPUTE,
                        ty: wgpu::BindingType::Buffer {
                            ty: wgpu::BufferBindingType::Uniform,
                            has_dynamic_offset: false,
                            min_binding_size: wgpu::BufferSize::new(
                                std::mem::size_of::<FrameGlobals>() as u64,
                            ),
                        },
                        count: None,
                    },
                    texture(1, unfilterable),
                    texture(2, unfilterable),
                    texture(3, wgpu::TextureSampleType::Uint),
                    texture(4, unfilterable),
                ],
            });
            let globals = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("frame globals"),
                contents: bytemuck::bytes_of(&bytemuck::Zeroable::zeroed() as &FrameGlobals),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            });
            let terrain = TerrainGpu::new(device, &gpu.queue, &scene.terrain);
            let wind = WindTexture::new(device, &scene.terrain);
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("scene (group 0)"),
                layout: &layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: globals.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&terrain.heights),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::TextureView(&terrain.density),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::TextureView(&terrain.covering),
                    },
                    wgpu::BindGroupEntry {
                        binding: 4,
                        resource: wgpu::BindingResource::TextureView(&wind.view),
                    },
                ],
            });
            let ground = GroundGpu::new(device, &terrain);
            let background = Background::new(device, &layout, sample_count);
            let props = PropsGpu::new(device, &scene.terrain, scene.config.seed);
            Self {
                layout,
                bind_group,
                globals,
                terrain,
                ground,
                ground_lod: GroundLod::DEFAULT,
                wind,
                props,
                background,
                sample_count,
            }
        })
    }

    /// CPU half of the frame's core work: samples the wind field into the wind texture.
    pub fn bake_wind(&mut self, wind: &dyn WindField, time: f32) {
        self.wind.bake(wind, time);
    }

    /// Upload half: the wind texture, the frame globals and the ground chunks this frame
    /// draws (returned, for [`Self::draw_background`]).
    pub fn upload(&self, gpu: &GpuContext, inputs: &FrameInputs<'_>) -> GroundDraws {
        self.wind.upload(gpu);
        let globals = inputs.globals(self.wind.max_speed());
        gpu.write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));
        self.ground.upload(
            gpu,
            &self.terrain,
            &inputs.camera,
            inputs.size.height,
            self.ground_lod,
        )
    }

    /// Draws the background (sky, ground, props, moving object; [`Background::draw`]) into
    /// `pass`, which must have bind group 0 set; `ground` is what [`Self::upload`] returned
    /// for this frame.
    pub fn draw_background(
        &self,
        pass: &mut crate::technique::RenderPass<'_>,
        ground: &GroundDraws,
    ) {
        self.background
            .draw(pass, &self.ground, ground, &self.props);
    }

    /// GPU memory held by the shared scene resources, bytes.
    pub fn bytes(&self) -> u64 {
        let (w, h) = self.wind.resolution();
        self.terrain.bytes()
            + self.ground.bytes()
            + u64::from(w * h * 16)
            + std::mem::size_of::<FrameGlobals>() as u64
            + self.props.bytes()
    }

    /// A pipeline layout with bind group 0 followed by a technique's own groups.
    pub fn pipeline_layout(
        &self,
        device: &wgpu::Device,
        label: &str,
        groups: &[&wgpu::BindGroupLayout],
    ) -> wgpu::PipelineLayout {
        let mut all: Vec<Option<&wgpu::BindGroupLayout>> = vec![Some(&self.layout)];
        all.extend(groups.iter().map(|g| Some(*g)));
        device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &all,
            immediate_size: 0,
        })
    }
}
