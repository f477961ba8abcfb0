//! wgpu validation errors become errors that fail the run, never just a log line.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use grassbench::gpu::GpuEstimate;
use grassbench::runner::Harness;
use grassbench::technique::{
    FrameEncoder, GrassTechnique, InitContext, NoParams, Technique, TechniqueEntry, TechniqueInfo,
    TechniqueStats, Variants,
};
use grassbench::{Scene, wgpu};
use grassbench_tests::{TEST_SIZE, gpu, scene};

/// A pipeline drawing with `source`'s `vs` and `fs` into the frame's colour target, with
/// `depth` state where the pass's depth attachment is to be used, classified as costing nothing.
fn test_pipeline(
    ctx: &InitContext<'_>,
    label: &str,
    source: &str,
    depth: Option<wgpu::DepthStencilState>,
) -> grassbench::shaders::RenderPipeline {
    let device = &ctx.gpu.device;
    let module = grassbench::shaders::module(device, label, source);
    let layout = ctx.scene_gpu.pipeline_layout(device, label, &[]);
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: depth,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[Some(grassbench::target::COLOR_FORMAT.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    grassbench::shaders::RenderPipeline::from_raw(
        pipeline,
        grassbench::shaders::PipelineCost::default(),
    )
}

/// A technique that draws with the pipeline it was given (none, or one whose shader reads a
/// binding its layout does not have).
struct BadDraw {
    pipeline: Option<grassbench::shaders::RenderPipeline>,
}

impl Technique for BadDraw {
    type Params = NoParams;
    const INFO: TechniqueInfo = TechniqueInfo {
        id: "broken",
        name: "broken",
        paper: "-",
        gpu_state: false,
        debug_views: &[],
    };
    const VARIANTS: Variants = Variants {
        finest: "",
        others: &[],
    };

    /// Builds a pipeline whose shader reads a binding its layout does not have.
    fn new(ctx: &InitContext<'_>, _params: NoParams) -> grassbench::Result<Self> {
        Ok(BadDraw {
            pipeline: Some(test_pipeline(
                ctx,
                "broken",
                "@group(1) @binding(0) var<uniform> missing: vec4<f32>;\n\
                 @vertex fn vs() -> @builtin(position) vec4<f32> { return missing; }\n\
                 @fragment fn fs() -> @location(0) vec4<f32> { return vec4(1.0); }",
                None,
            )),
        })
    }

    fn estimate(_: &Scene, _: &NoParams) -> grassbench::Result<GpuEstimate> {
        Ok(GpuEstimate::default())
    }

    fn params(&self) -> &NoParams {
        &NoParams {}
    }
}

/// A technique whose pipeline's shader reads a binding its layout does not have.
const BAD_PIPELINE: TechniqueEntry = grassbench::technique::entry::<BadDraw>();

impl GrassTechnique for BadDraw {
    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        let mut pass = encoder.render_pass("bad");
        if let Some(p) = &self.pipeline {
            pass.set_pipeline(p);
        }
        pass.draw(0..3, 0..1);
    }
    fn stats(&self) -> TechniqueStats {
        TechniqueStats::default()
    }
}

#[test]
fn invalid_pipeline_fails_technique_creation() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let harness = Harness::new(&gpu, scene("meadow", 0.01)?, TEST_SIZE, false)?;
    let err = harness
        .create(&BAD_PIPELINE, &toml::Table::new())
        .err()
        .expect("creation must fail");
    let text = err.to_string();
    assert!(
        matches!(err, grassbench::Error::Validation { .. }),
        "{text}"
    );
    assert!(text.contains("creating technique `broken`"), "{text}");
    Ok(())
}

#[test]
fn invalid_draw_fails_the_frame() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let mut harness = Harness::new(&gpu, scene("meadow", 0.01)?, TEST_SIZE, false)?;
    // No pipeline set at all: the draw is invalid.
    let mut bad = BadDraw { pipeline: None };
    let err = harness
        .frame(&mut bad, 0, false)
        .err()
        .expect("the frame must fail");
    assert!(err.to_string().contains("frame 0 of `broken`"), "{err}");
    // The harness keeps working afterwards.
    harness.frame(&mut grassbench::technique::NoGrass, 1, false)?;
    Ok(())
}

/// A technique that draws one off-screen triangle indirectly, from arguments in a buffer with
/// `COPY_SRC` usage where `COPYABLE`, without it where not.
struct IndirectDraw<const COPYABLE: bool> {
    pipeline: grassbench::shaders::RenderPipeline,
    args: wgpu::Buffer,
}

impl<const COPYABLE: bool> Technique for IndirectDraw<COPYABLE> {
    type Params = NoParams;
    const INFO: TechniqueInfo = TechniqueInfo {
        id: "indirect",
        name: "indirect",
        paper: "-",
        gpu_state: false,
        debug_views: &[],
    };
    const VARIANTS: Variants = Variants {
        finest: "",
        others: &[],
    };

    fn new(ctx: &InitContext<'_>, _params: NoParams) -> grassbench::Result<Self> {
        let device = &ctx.gpu.device;
        let pipeline = test_pipeline(
            ctx,
            "indirect",
            "@vertex fn vs() -> @builtin(position) vec4<f32> { return vec4(2.0, 2.0, 0.5, 1.0); }\n\
             @fragment fn fs() -> @location(0) vec4<f32> { return vec4(1.0); }",
            Some(wgpu::DepthStencilState {
                format: grassbench::target::DEPTH_FORMAT,
                depth_write_enabled: Some(false),
                depth_compare: Some(wgpu::CompareFunction::Always),
                stencil: Default::default(),
                bias: Default::default(),
            }),
        );
        let usage = if COPYABLE {
            wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_SRC
        } else {
            wgpu::BufferUsages::INDIRECT
        };
        let args = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("indirect args"),
            size: 16,
            usage,
            mapped_at_creation: true,
        });
        // 3 vertices, 7 instances, from vertex 0 and instance 0.
        let bytes: Vec<u8> = [3u32, 7, 0, 0]
            .iter()
            .flat_map(|w| w.to_le_bytes())
            .collect();
        args.slice(..)
            .get_mapped_range_mut()
            .map_err(|e| grassbench::Error::Technique {
                technique: "indirect".into(),
                message: format!("{e:?}"),
            })?
            .copy_from_slice(&bytes);
        args.unmap();
        Ok(Self { pipeline, args })
    }

    fn estimate(_: &Scene, _: &NoParams) -> grassbench::Result<GpuEstimate> {
        Ok(GpuEstimate::default())
    }

    fn params(&self) -> &NoParams {
        &NoParams {}
    }
}

impl<const COPYABLE: bool> GrassTechnique for IndirectDraw<COPYABLE> {
    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        let mut pass = encoder.render_pass("indirect");
        pass.set_pipeline(&self.pipeline);
        pass.draw_indirect(&self.args, 0);
    }
    fn stats(&self) -> TechniqueStats {
        TechniqueStats::default()
    }
}

#[test]
fn an_indirect_draw_counts_its_instances_or_fails_the_frame_saying_why() -> anyhow::Result<()> {
    let gpu = gpu()?;
    assert!(gpu.has_pipeline_statistics(), "{}", gpu.summary.name);
    let mut harness = Harness::new(&gpu, scene("meadow", 0.01)?, TEST_SIZE, false)?;
    // Arguments the harness can copy: the frame counts the 7 instances they hold.
    let entry = grassbench::technique::entry::<IndirectDraw<true>>();
    let mut copyable = harness.create(&entry, &toml::Table::new())?;
    let record = harness.frame(copyable.as_mut(), 0, false)?.record;
    assert_eq!(record.instances, Some(7));
    assert_eq!(record.vertex_invocations, Some(21));
    // Arguments it cannot copy: no frame whose work leaves out the instances, an error that
    // names the fix.
    let entry = grassbench::technique::entry::<IndirectDraw<false>>();
    let mut uncopyable = harness.create(&entry, &toml::Table::new())?;
    let err = harness
        .frame(uncopyable.as_mut(), 1, false)
        .err()
        .expect("the frame must fail");
    let text = err.to_string();
    assert!(text.contains("frame 1 of `indirect`"), "{text}");
    assert!(text.contains("wgpu::BufferUsages::COPY_SRC"), "{text}");
    // The harness keeps working afterwards.
    harness.frame(copyable.as_mut(), 2, false)?;
    Ok(())
}
