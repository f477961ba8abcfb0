//! GPU-against-CPU twin tests, in vello's style: a WGSL function is called by a test compute
//! kernel over generated inputs, the results are read back, and a test compares them with the
//! Rust function the shader mirrors.
//!
//! The kernel is appended to the real shader text (the prelude and a technique's WGSL as
//! [`grassbench::shaders::compose`] builds it, from the crate's exported constant), never to a
//! copy of the function under test, so a shader that drifts from its twin fails its test.
//!
//! A kernel maps records to records: input `i` is `x: TwinIn` (`x.v[0]`, `x.v[1]`, … are
//! `vec4<f32>`s; small integers travel as floats, exact below 2²⁴), the body writes
//! `y: TwinOut` the same way. Both arrays sit at group [`GROUP`], bindings [`INPUT_BINDING`]
//! and [`OUTPUT_BINDING`], numbers no shader here uses; whatever else the function reads
//! (bind group 0 from [`SceneGpu`], a technique's uniform, buffers and textures) is bound
//! through [`Bindings`] with explicit layouts, so only what the test provides is bound.
//! [`dispatch`] runs any entry point of a shader the same way (a technique's own compute pass
//! over generated data) and reads back its writable buffers.

use anyhow::{Context as _, bail, ensure};
use grassbench::GpuContext;
use grassbench::bytemuck;
use grassbench::scene::SceneGpu;
use grassbench::wgpu;
use grassbench::wgpu::util::DeviceExt as _;

/// Bind group of a test kernel's inputs and outputs.
pub const GROUP: u32 = 3;
/// Binding of the input records in [`GROUP`].
pub const INPUT_BINDING: u32 = 100;
/// Binding of the output records in [`GROUP`].
pub const OUTPUT_BINDING: u32 = 101;
/// Workgroup size of the test kernel.
const WORKGROUP: u32 = 64;

/// A resource a shader reads or writes at one (group, binding).
pub enum Resource<'a> {
    /// A uniform buffer holding these bytes.
    Uniform(Vec<u8>),
    /// A read-only storage buffer holding these bytes.
    Storage(Vec<u8>),
    /// A read-write storage buffer holding these bytes, read back after the dispatch.
    Output(Vec<u8>),
    /// A texture view of this sample type and dimension (not multisampled).
    Texture(
        &'a wgpu::TextureView,
        wgpu::TextureSampleType,
        wgpu::TextureViewDimension,
    ),
}

/// What a dispatch binds: optionally the scene's bind group 0, and resources at groups 1 and
/// up; and the values of the shader's pipeline-overridable constants.
#[derive(Default)]
pub struct Bindings<'a> {
    scene: Option<&'a SceneGpu>,
    entries: Vec<(u32, u32, Resource<'a>)>,
    constants: Vec<(&'a str, f64)>,
}

impl<'a> Bindings<'a> {
    /// Nothing bound.
    pub fn new() -> Self {
        Self::default()
    }

    /// Binds the scene's bind group 0 (globals, terrain maps, wind texture).
    pub fn scene(mut self, scene: &'a SceneGpu) -> Self {
        self.scene = Some(scene);
        self
    }

    /// Sets the pipeline-overridable constant `name` (WGSL `override`) to `value`.
    pub fn constant(mut self, name: &'a str, value: f64) -> Self {
        self.constants.push((name, value));
        self
    }

    /// Binds `resource` at (`group`, `binding`); group 0 is the scene's.
    pub fn bind(mut self, group: u32, binding: u32, resource: Resource<'a>) -> Self {
        self.entries.push((group, binding, resource));
        self
    }

    /// [`Bindings::bind`] of a uniform holding `value`.
    pub fn uniform<T: bytemuck::Pod>(self, group: u32, binding: u32, value: &T) -> Self {
        self.bind(
            group,
            binding,
            Resource::Uniform(bytemuck::bytes_of(value).to_vec()),
        )
    }

    /// [`Bindings::bind`] of a read-only storage buffer holding `values`.
    pub fn storage<T: bytemuck::Pod>(self, group: u32, binding: u32, values: &[T]) -> Self {
        self.bind(
            group,
            binding,
            Resource::Storage(bytemuck::cast_slice(values).to_vec()),
        )
    }
}

/// The test kernel appended to `shader` (a whole shader, prelude included): `twin_main` calls
/// `body` on every input record. `inputs` and `outputs` are the `vec4<f32>`s per record.
pub fn kernel_source(shader: &str, inputs: usize, outputs: usize, body: &str) -> String {
    format!(
        "{shader}

// ---- test kernel (grassbench-tests, twin.rs) ----
struct TwinIn {{ v: array<vec4<f32>, {inputs}> }}
struct TwinOut {{ v: array<vec4<f32>, {outputs}> }}
@group({GROUP}) @binding({INPUT_BINDING}) var<storage, read> twin_in: array<TwinIn>;
@group({GROUP}) @binding({OUTPUT_BINDING}) var<storage, read_write> twin_out: array<TwinOut>;

@compute @workgroup_size({WORKGROUP})
fn twin_main(@builtin(global_invocation_id) id: vec3<u32>) {{
    let i = id.x;
    if (i >= arrayLength(&twin_in)) {{
        return;
    }}
    let x = twin_in[i];
    var y: TwinOut;
{body}
    twin_out[i] = y;
}}
"
    )
}

/// Runs `body` (WGSL statements reading `x`, writing `y`; see the module docs) over every
/// record of `inputs` in a kernel appended to `shader`, with `bindings` bound, and returns the
/// output records in the same order.
pub fn map<const I: usize, const O: usize>(
    gpu: &GpuContext,
    shader: &str,
    body: &str,
    bindings: Bindings<'_>,
    inputs: &[[[f32; 4]; I]],
) -> anyhow::Result<Vec<[[f32; 4]; O]>> {
    ensure!(!inputs.is_empty(), "a twin kernel needs at least one input");
    let source = kernel_source(shader, I, O, body);
    let count = u32::try_from(inputs.len()).context("too many inputs for one dispatch")?;
    let bindings = bindings
        .bind(
            GROUP,
            INPUT_BINDING,
            Resource::Storage(bytemuck::cast_slice(inputs).to_vec()),
        )
        .bind(
            GROUP,
            OUTPUT_BINDING,
            Resource::Output(vec![0; inputs.len() * O * 16]),
        );
    let outputs = dispatch(
        gpu,
        &source,
        "twin_main",
        &bindings,
        [count.div_ceil(WORKGROUP), 1, 1],
    )?;
    let out = outputs
        .last()
        .context("the kernel's output was not read back")?;
    Ok(bytemuck::pod_collect_to_vec(out))
}

/// Validates `source` with naga, so a kernel that does not compile says where.
fn validate(source: &str) -> anyhow::Result<()> {
    let module = naga::front::wgsl::parse_str(source)
        .map_err(|e| anyhow::anyhow!("test kernel: {}", e.emit_to_string(source)))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|e| anyhow::anyhow!("test kernel: {}", e.emit_to_string(source)))?;
    Ok(())
}

/// Runs entry point `entry` of `source` (a whole shader) as `workgroups` workgroups with
/// `bindings` bound (explicit layouts: every binding the entry point uses must be there) and
/// returns the contents of every [`Resource::Output`], in the order they were bound.
pub fn dispatch(
    gpu: &GpuContext,
    source: &str,
    entry: &str,
    bindings: &Bindings<'_>,
    workgroups: [u32; 3],
) -> anyhow::Result<Vec<Vec<u8>>> {
    validate(source)?;
    let device = &gpu.device;
    let during = format!("running the test kernel `{entry}`");
    let (readbacks, sizes) = gpu.scoped(&during, || -> anyhow::Result<_> {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("twin kernel"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let top = bindings
            .entries
            .iter()
            .map(|e| e.0)
            .max()
            .unwrap_or(0)
            .max(u32::from(bindings.scene.is_some()));
        let mut layouts = Vec::new();
        let mut groups = Vec::new();
        let mut outputs = Vec::new();
        for group in 0..=top {
            if group == 0
                && let Some(scene) = bindings.scene
            {
                layouts.push(Some(scene.layout.clone()));
                groups.push(Some(scene.bind_group.clone()));
                continue;
            }
            let mine: Vec<_> = bindings.entries.iter().filter(|e| e.0 == group).collect();
            if mine.is_empty() {
                layouts.push(None);
                groups.push(None);
                continue;
            }
            let (layout, group, written) = bind_group(device, &mine)?;
            layouts.push(Some(layout));
            groups.push(Some(group));
            outputs.extend(written);
        }
        let layout_refs: Vec<Option<&wgpu::BindGroupLayout>> =
            layouts.iter().map(Option::as_ref).collect();
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("twin kernel"),
            bind_group_layouts: &layout_refs,
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("twin kernel"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &bindings.constants,
                ..Default::default()
            },
            cache: None,
        });
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
            pass.set_pipeline(&pipeline);
            for (index, group) in groups.iter().enumerate() {
                if let Some(group) = group {
                    pass.set_bind_group(index as u32, group, &[]);
                }
            }
            pass.dispatch_workgroups(workgroups[0], workgroups[1], workgroups[2]);
        }
        let mut readbacks = Vec::new();
        let mut sizes = Vec::new();
        for (buffer, size) in &outputs {
            let readback = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("twin readback"),
                size: *size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            encoder.copy_buffer_to_buffer(buffer, 0, &readback, 0, *size);
            readbacks.push(readback);
            sizes.push(*size);
        }
        gpu.queue.submit([encoder.finish()]);
        Ok((readbacks, sizes))
    })??;
    let mut results = Vec::new();
    for (readback, size) in readbacks.iter().zip(sizes) {
        let slice = readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        gpu.wait_idle(&during)?;
        rx.recv()
            .context("the read-back callback never ran")?
            .context("mapping the kernel's output")?;
        let data = slice
            .get_mapped_range()
            .context("reading the kernel's output")?;
        ensure!(data.len() as u64 == size, "short read-back");
        results.push(data.to_vec());
    }
    Ok(results)
}

/// A group's layout, its bind group, and its writable buffers with their sizes.
type Group = (
    wgpu::BindGroupLayout,
    wgpu::BindGroup,
    Vec<(wgpu::Buffer, u64)>,
);

/// The layout and bind group of one group's resources, and the writable buffers among them.
fn bind_group(
    device: &wgpu::Device,
    entries: &[&(u32, u32, Resource<'_>)],
) -> anyhow::Result<Group> {
    let buffer_type = |ty| wgpu::BindingType::Buffer {
        ty,
        has_dynamic_offset: false,
        min_binding_size: None,
    };
    let mut layout_entries = Vec::new();
    let mut bound = Vec::new();
    let mut written = Vec::new();
    for (_, binding, resource) in entries {
        let (ty, bytes, usage) = match resource {
            Resource::Texture(view, sample_type, view_dimension) => {
                let ty = wgpu::BindingType::Texture {
                    sample_type: *sample_type,
                    view_dimension: *view_dimension,
                    multisampled: false,
                };
                layout_entries.push(layout_entry(*binding, ty));
                bound.push((*binding, Bound::View(view)));
                continue;
            }
            Resource::Uniform(bytes) => (
                buffer_type(wgpu::BufferBindingType::Uniform),
                bytes,
                wgpu::BufferUsages::UNIFORM,
            ),
            Resource::Storage(bytes) => (
                buffer_type(wgpu::BufferBindingType::Storage { read_only: true }),
                bytes,
                wgpu::BufferUsages::STORAGE,
            ),
            Resource::Output(bytes) => (
                buffer_type(wgpu::BufferBindingType::Storage { read_only: false }),
                bytes,
                wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            ),
        };
        if bytes.is_empty() {
            bail!(
                "binding {binding}: an empty buffer cannot be bound; give it at least one element"
            );
        }
        layout_entries.push(layout_entry(*binding, ty));
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("twin binding"),
            contents: bytes,
            usage,
        });
        if matches!(resource, Resource::Output(_)) {
            written.push((buffer.clone(), bytes.len() as u64));
        }
        bound.push((*binding, Bound::Buffer(buffer)));
    }
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("twin group"),
        entries: &layout_entries,
    });
    let group_entries: Vec<wgpu::BindGroupEntry<'_>> = bound
        .iter()
        .map(|(binding, b)| wgpu::BindGroupEntry {
            binding: *binding,
            resource: match b {
                Bound::Buffer(buffer) => buffer.as_entire_binding(),
                Bound::View(view) => wgpu::BindingResource::TextureView(view),
            },
        })
        .collect();
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("twin group"),
        layout: &layout,
        entries: &group_entries,
    });
    Ok((layout, group, written))
}

/// What one binding of a group holds.
enum Bound<'v> {
    Buffer(wgpu::Buffer),
    View(&'v wgpu::TextureView),
}

/// A compute-stage layout entry.
fn layout_entry(binding: u32, ty: wgpu::BindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty,
        count: None,
    }
}

/// The largest difference found between the GPU and its twin, and the input it came from.
#[derive(Clone, Debug, Default)]
pub struct Worst {
    /// Largest error seen.
    pub error: f32,
    /// What was compared there (inputs, both results).
    pub detail: String,
    /// Comparisons made.
    pub count: usize,
}

impl Worst {
    /// Records one comparison with `error`; `detail` is made only when it is the worst so far.
    /// A NaN error counts as infinitely bad.
    pub fn record(&mut self, error: f32, detail: impl FnOnce() -> String) {
        self.count += 1;
        let error = if error.is_nan() { f32::INFINITY } else { error };
        if error > self.error || self.detail.is_empty() {
            self.error = self.error.max(error);
            self.detail = detail();
        }
    }

    /// Fails unless every recorded error is within `limit` (and something was compared),
    /// naming the worst case.
    /// The worst case is written to stderr either way, so `--nocapture` shows the measurement
    /// a limit comes from.
    pub fn check(&self, what: &str, limit: f32) -> anyhow::Result<()> {
        ensure!(self.count > 0, "{what}: nothing compared");
        eprintln!(
            "{what}: worst {:e} over {} comparisons (limit {limit:e}), at {}",
            self.error, self.count, self.detail
        );
        ensure!(
            self.error <= limit,
            "{what}: GPU and twin differ by {} (limit {limit}) over {} comparisons; worst at {}",
            self.error,
            self.count,
            self.detail
        );
        Ok(())
    }
}
