//! The compute pass's own counts, brought to the CPU without stalling it.
//!
//! The pass counts its verdicts (blades drawn per level, stood for, culled by each test) in
//! the same buffer that holds the two indirect draws, so the instance counts the GPU draws are
//! the counts reported: nothing is estimated. They are never waited for: each frame copies the
//! 72-byte block into the next of three small read-back buffers, and the next frame's `update`
//! asks for the previous frame's buffer to be mapped; the mapping completes during whatever
//! wait for the GPU comes next (the harness waits for every frame), so `stats()` after frame
//! `f` reports frame `f − 1`'s counts, and the counts of frame `f` are never read during frame
//! `f` (no read-back in the frame: the draws take their counts from the GPU directly). A
//! driver that keeps frames in flight would see them later still; [`Readback::latest`] says how
//! many frames old the reported counts are, and `counters()` reports it beside them.

use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};

use grassbench::{bytemuck, wgpu};

use crate::cull::Verdict;

/// Mirror of the shader's `Counters`: the two indirect draws, then the counts.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuCounts {
    /// Near level: vertex count, instance count (blades drawn near), first vertex, first
    /// instance (`wgpu::util::DrawIndirectArgs`'s layout).
    pub near: [u32; 4],
    /// Far level: as `near`.
    pub far: [u32; 4],
    /// Blades per verdict, in [`Verdict`]'s order.
    pub verdicts: [u32; 6],
    /// Near-level blades inside the hand-over band (narrowing or widening).
    pub in_band: u32,
    /// Blades the frame did not dispatch (`tiles.rs`): set by the CPU before the pass, like
    /// the verdicts it gives them (culled by the frustum or the distance, or represented).
    pub skipped: u32,
    /// Of the skipped blades, those counted as represented: far tiles' non-survivors that no
    /// per-blade test saw (some would have been culled by orientation or the frustum).
    pub represented_untested: u32,
    /// The frame's dispatched ranges (`tiles.rs`), set by the CPU: what the compute pass's
    /// binary search runs over (its halvings fixed by the pipeline for the most ranges a
    /// frame holds). A storage value, not a uniform, so lavapipe does not
    /// re-specialise the shader every frame (`grassbench::shaders::uniform_bound_loops`).
    pub ranges: u32,
}

impl GpuCounts {
    /// Bytes of the block.
    pub const SIZE: u64 = std::mem::size_of::<Self>() as u64;
    /// Byte offset of the near level's indirect draw.
    pub const NEAR_ARGS: u64 = 0;
    /// Byte offset of the far level's indirect draw.
    pub const FAR_ARGS: u64 = 16;

    /// Blades with verdict `v`.
    pub fn of(&self, v: Verdict) -> u32 {
        self.verdicts[v as usize]
    }

    /// Blades the pass looked at (every verdict).
    pub fn considered(&self) -> u64 {
        self.verdicts.iter().map(|&c| u64::from(c)).sum()
    }
}

/// Mapping states of a read-back buffer.
const IDLE: u8 = 0;
const PENDING: u8 = 1;
const READY: u8 = 2;
const FAILED: u8 = 3;

/// Read-back buffers in the ring: one being written by this frame, one being mapped for the
/// previous frame, one free.
const RING: usize = 3;

struct Slot {
    buffer: wgpu::Buffer,
    state: Arc<AtomicU8>,
    /// The step (update call) whose counts the buffer holds.
    step: u64,
}

/// Three small buffers the frame's counts are copied into, mapped one frame later.
pub struct Readback {
    slots: Vec<Slot>,
    /// Updates so far; the current frame writes slot `step % RING`.
    step: u64,
    /// The slot asked to be mapped in the last update, if any.
    mapping: Option<usize>,
    /// The newest counts read so far, and their step.
    latest: Option<(GpuCounts, u64)>,
}

impl Readback {
    /// The ring's buffers.
    pub fn new(device: &wgpu::Device) -> Self {
        let slots = (0..RING)
            .map(|k| Slot {
                buffer: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(&format!("jahrmann counts read-back {k}")),
                    size: GpuCounts::SIZE,
                    usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                    mapped_at_creation: false,
                }),
                state: Arc::new(AtomicU8::new(IDLE)),
                step: 0,
            })
            .collect();
        Self {
            slots,
            step: 0,
            mapping: None,
            latest: None,
        }
    }

    /// GPU memory held, bytes.
    pub fn bytes() -> u64 {
        RING as u64 * GpuCounts::SIZE
    }

    /// Starts a frame (call from `update`): keeps what the previous mapping brought, frees its
    /// buffer, and asks for the previous frame's buffer to be mapped.
    pub fn begin_frame(&mut self) {
        if let Some(k) = self.mapping.take() {
            if let Some(counts) = self.mapped(k) {
                self.latest = Some((counts, self.slots[k].step));
            }
            // Unmapping also cancels a mapping still pending.
            self.slots[k].buffer.unmap();
            self.slots[k].state.store(IDLE, Ordering::Release);
        }
        if self.step > 0 {
            let k = ((self.step - 1) % RING as u64) as usize;
            let state = Arc::clone(&self.slots[k].state);
            state.store(PENDING, Ordering::Release);
            self.slots[k]
                .buffer
                .slice(..)
                .map_async(wgpu::MapMode::Read, move |result| {
                    let next = if result.is_ok() { READY } else { FAILED };
                    state.store(next, Ordering::Release);
                });
            self.mapping = Some(k);
        }
        let k = (self.step % RING as u64) as usize;
        self.slots[k].step = self.step;
        self.step += 1;
    }

    /// The buffer this frame's counts are copied into.
    pub fn target(&self) -> &wgpu::Buffer {
        let k = ((self.step.max(1) - 1) % RING as u64) as usize;
        &self.slots[k].buffer
    }

    /// The counts of slot `k` if its mapping has completed.
    fn mapped(&self, k: usize) -> Option<GpuCounts> {
        let slot = &self.slots[k];
        if slot.state.load(Ordering::Acquire) != READY {
            return None;
        }
        let data = slot.buffer.slice(..).get_mapped_range().ok()?;
        bytemuck::try_pod_read_unaligned(&data).ok()
    }

    /// The newest counts the GPU has delivered, and how many frames before the current one
    /// they were counted (1 once the harness has waited for the previous frame).
    pub fn latest(&self) -> Option<(GpuCounts, u64)> {
        let fresh = self
            .mapping
            .and_then(|k| self.mapped(k).map(|c| (c, self.slots[k].step)));
        fresh
            .or(self.latest)
            .map(|(c, step)| (c, self.step.saturating_sub(1).saturating_sub(step)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_lay_out_as_two_indirect_draws_then_the_verdicts() {
        assert_eq!(GpuCounts::SIZE, 72);
        assert_eq!(
            GpuCounts::FAR_ARGS as usize,
            std::mem::size_of::<wgpu::util::DrawIndirectArgs>()
        );
        let c = GpuCounts {
            verdicts: [5, 4, 3, 2, 1, 0],
            ..Default::default()
        };
        assert_eq!(c.of(Verdict::Represented), 3);
        assert_eq!(c.considered(), 15);
    }
}
