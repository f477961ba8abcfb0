//! The device every part of grassbench shares.

use super::{BackendChoice, ErrorSink, scope::convert};
use crate::{Error, Result};

/// What was measured on: recorded in every `meta.toml` next to the figures.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize, PartialEq)]
pub struct AdapterSummary {
    /// Adapter name, e.g. `llvmpipe (LLVM 15.0.6, 256 bits)`.
    pub name: String,
    /// Driver name, e.g. `llvmpipe`.
    pub driver: String,
    /// Driver version string.
    pub driver_info: String,
    /// Backend, e.g. `Vulkan`.
    pub backend: String,
    /// Device type: `Cpu` for software rasterisers.
    pub device_type: String,
    /// Whether render passes can be timed with timestamp queries.
    pub timestamps: bool,
    /// Nanoseconds per timestamp tick.
    pub timestamp_period_ns: f32,
    /// Whether passes count their work with pipeline-statistics queries (vertex, clipper,
    /// fragment and compute invocations). Where `false` (Metal, GL, some drivers), the work
    /// columns of `frames.csv` and `runs.csv` stay empty. Files written before it read `false`.
    #[serde(default)]
    pub pipeline_statistics: bool,
    /// Sample counts the adapter offers for the render target's colour and depth formats
    /// together (1 always). The harness's `--msaa` renders 4, the count WebGPU guarantees;
    /// this says where a paper asks for more (Boulanger Sec. 4.2: at least 6) what the adapter
    /// could give. Files written before it read `[]`.
    #[serde(default)]
    pub msaa_sample_counts: Vec<u32>,
}

/// Instance, adapter, device and queue, plus the error sink. Created once and borrowed by
/// everything else: techniques never own a device.
pub struct GpuContext {
    /// The wgpu instance the adapter came from.
    pub instance: wgpu::Instance,
    /// The chosen adapter.
    pub adapter: wgpu::Adapter,
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Adapter facts for result files.
    pub summary: AdapterSummary,
    sink: ErrorSink,
    /// Bytes written through [`Self::write_buffer`] and [`Self::write_texture`] since the last
    /// [`Self::take_uploaded_bytes`].
    uploaded: std::sync::atomic::AtomicU64,
}

/// Features grassbench uses when the adapter has them; none is required.
const OPTIONAL_FEATURES: wgpu::Features =
    wgpu::Features::TIMESTAMP_QUERY.union(wgpu::Features::PIPELINE_STATISTICS_QUERY);

impl GpuContext {
    /// Creates a headless context on the requested backend, with a device that requests
    /// [`wgpu::Limits::default`] (the limits WebGPU guarantees on any GPU; see
    /// [`Self::for_needs`]).
    ///
    /// Adapters are ranked discrete > integrated > virtual > software; with
    /// [`BackendChoice::Auto`] Vulkan, Metal and DX12 come before GL at equal rank.
    pub fn new(choice: BackendChoice) -> Result<Self> {
        Self::for_needs(choice, &wgpu::Limits::default())
    }

    /// As [`Self::new`], with a device that requests `needs` (the field-wise maximum of what
    /// the techniques a run will create need: [`super::limits::needed_by`]), lowered to what
    /// the adapter offers where it offers less ([`Self::request_limits`]); a technique the
    /// device then cannot serve is refused when it is created, naming the limit.
    pub fn for_needs(choice: BackendChoice, needs: &wgpu::Limits) -> Result<Self> {
        let (instance, adapter) = Self::adapter(choice)?;
        let limits = Self::request_limits(&adapter, needs);
        Self::from_adapter_with_limits(instance, adapter, limits)
    }

    /// As [`Self::new`], with the device's limits exactly: `None` requests everything the
    /// adapter offers (the tests compare pictures under it with pictures under the defaults);
    /// `Some(limits)` requests exactly `limits`. An adapter offering less than `limits` is
    /// refused with the limit it lacks.
    pub fn with_limits(choice: BackendChoice, limits: Option<wgpu::Limits>) -> Result<Self> {
        let (instance, adapter) = Self::adapter(choice)?;
        let limits = limits.unwrap_or_else(|| adapter.limits());
        Self::from_adapter_with_limits(instance, adapter, limits)
    }

    /// The limits a device on `adapter` requests for a run that needs `needs`: `needs` (never
    /// less than [`wgpu::Limits::default`] when made by [`super::limits::needed_by`]), lowered
    /// to the adapter's own value wherever it offers less. The one rule for every device
    /// grassbench creates: the headless commands' and the window's.
    pub fn request_limits(adapter: &wgpu::Adapter, needs: &wgpu::Limits) -> wgpu::Limits {
        super::limits::request(needs, &adapter.limits())
    }

    /// The instance for `choice` and its best adapter.
    fn adapter(choice: BackendChoice) -> Result<(wgpu::Instance, wgpu::Adapter)> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = choice.backends();
        let instance = wgpu::Instance::new(desc);
        let adapters = pollster::block_on(instance.enumerate_adapters(choice.backends()));
        let seen = if adapters.is_empty() {
            "none".to_owned()
        } else {
            adapters
                .iter()
                .map(|a| {
                    let i = a.get_info();
                    format!("{} ({:?})", i.name, i.backend)
                })
                .collect::<Vec<_>>()
                .join(", ")
        };
        let adapter = adapters
            .into_iter()
            .min_by_key(rank)
            .ok_or_else(|| Error::NoAdapter {
                backend: choice.to_string(),
                seen,
            })?;
        Ok((instance, adapter))
    }

    /// Creates the device on a given adapter, requesting `needs` as [`Self::for_needs`] does.
    pub fn from_adapter(
        instance: wgpu::Instance,
        adapter: wgpu::Adapter,
        needs: &wgpu::Limits,
    ) -> Result<Self> {
        let limits = Self::request_limits(&adapter, needs);
        Self::from_adapter_with_limits(instance, adapter, limits)
    }

    /// Creates the device on a given adapter with `limits`.
    fn from_adapter_with_limits(
        instance: wgpu::Instance,
        adapter: wgpu::Adapter,
        limits: wgpu::Limits,
    ) -> Result<Self> {
        let info = adapter.get_info();
        let features = adapter.features() & OPTIONAL_FEATURES;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("grassbench"),
            required_features: features,
            required_limits: limits,
            ..Default::default()
        }))
        .map_err(|e| Error::RequestDevice {
            adapter: info.name.clone(),
            reason: super::scope::chain(&e),
        })?;
        Ok(Self::from_device(instance, adapter, device, queue))
    }

    /// Wraps a device somebody else created (eframe's, in the UI).
    pub fn from_device(
        instance: wgpu::Instance,
        adapter: wgpu::Adapter,
        device: wgpu::Device,
        queue: wgpu::Queue,
    ) -> Self {
        let info = adapter.get_info();
        let sink = ErrorSink::default();
        sink.install(&device);
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let summary = AdapterSummary {
            name: info.name,
            driver: info.driver,
            driver_info: info.driver_info,
            backend: format!("{:?}", info.backend),
            device_type: format!("{:?}", info.device_type),
            timestamps,
            timestamp_period_ns: queue.get_timestamp_period(),
            pipeline_statistics: device
                .features()
                .contains(wgpu::Features::PIPELINE_STATISTICS_QUERY),
            msaa_sample_counts: sample_counts(&adapter),
        };
        Self {
            instance,
            adapter,
            device,
            queue,
            summary,
            sink,
            uploaded: std::sync::atomic::AtomicU64::new(0),
        }
    }

    /// Writes `data` into `buffer` at `offset` (see [`wgpu::Queue::write_buffer`]), counting
    /// the bytes: every per-frame upload of a technique goes through here (or
    /// [`Self::write_texture`]), so the harness measures what each frame uploads
    /// (`upload_bytes`) for every technique alike.
    pub fn write_buffer(&self, buffer: &wgpu::Buffer, offset: wgpu::BufferAddress, data: &[u8]) {
        self.count_upload(data.len());
        self.queue.write_buffer(buffer, offset, data);
    }

    /// Writes `data` into `texture` (see [`wgpu::Queue::write_texture`]), counting the bytes.
    pub fn write_texture(
        &self,
        texture: wgpu::TexelCopyTextureInfo<'_>,
        data: &[u8],
        layout: wgpu::TexelCopyBufferLayout,
        size: wgpu::Extent3d,
    ) {
        self.count_upload(data.len());
        self.queue.write_texture(texture, data, layout, size);
    }

    fn count_upload(&self, bytes: usize) {
        self.uploaded
            .fetch_add(bytes as u64, std::sync::atomic::Ordering::Relaxed);
    }

    /// Bytes uploaded through [`Self::write_buffer`] and [`Self::write_texture`] since the
    /// last call, and starts counting again.
    pub fn take_uploaded_bytes(&self) -> u64 {
        self.uploaded.swap(0, std::sync::atomic::Ordering::Relaxed)
    }

    /// Runs `f` inside validation, out-of-memory and internal error scopes and returns the first
    /// error any of them (or the uncaptured-error sink) caught, described as `during`.
    pub fn scoped<T>(&self, during: &str, f: impl FnOnce() -> T) -> Result<T> {
        let internal = self.device.push_error_scope(wgpu::ErrorFilter::Internal);
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let out = f();
        let v = pollster::block_on(validation.pop());
        let o = pollster::block_on(oom.pop());
        let i = pollster::block_on(internal.pop());
        if let Some(e) = v.or(o).or(i) {
            return Err(convert(e, during));
        }
        self.check(during)?;
        Ok(out)
    }

    /// Returns an error that reached no scope (or a lost device) since the last check.
    pub fn check(&self, during: &str) -> Result<()> {
        match self.sink.take(during) {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Blocks until the GPU has finished all submitted work.
    pub fn wait_idle(&self, during: &str) -> Result<()> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| Error::DeviceLost {
                during: during.to_owned(),
                message: e.to_string(),
            })?;
        self.check(during)
    }

    /// Whether render passes can carry timestamp queries.
    pub fn has_timestamps(&self) -> bool {
        self.summary.timestamps
    }

    /// Whether passes can count their work with pipeline-statistics queries.
    pub fn has_pipeline_statistics(&self) -> bool {
        self.summary.pipeline_statistics
    }
}

/// Ranking key: lower is better.
fn rank(adapter: &wgpu::Adapter) -> (u8, u8) {
    let info = adapter.get_info();
    let kind = match info.device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Cpu => 3,
        wgpu::DeviceType::Other => 4,
    };
    let api = match info.backend {
        wgpu::Backend::Vulkan | wgpu::Backend::Metal | wgpu::Backend::Dx12 => 0,
        _ => 1,
    };
    (kind, api)
}

/// Sample counts `adapter` supports for both of the render target's formats.
fn sample_counts(adapter: &wgpu::Adapter) -> Vec<u32> {
    let flags = |format| adapter.get_texture_format_features(format).flags;
    let (color, depth) = (
        flags(crate::target::COLOR_FORMAT),
        flags(crate::target::DEPTH_FORMAT),
    );
    [1, 2, 4, 8, 16]
        .into_iter()
        .filter(|&n| n == 1 || (color.sample_count_supported(n) && depth.sample_count_supported(n)))
        .collect()
}
