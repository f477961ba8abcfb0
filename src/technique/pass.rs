//! The passes a [`super::FrameEncoder`] hands out: wgpu's render and compute passes behind a
//! thin wrapper that counts every draw and dispatch as it is recorded, so the work a frame
//! submits is measured by the harness for every technique alike, never reported by the
//! technique about itself.
//!
//! Only the recording calls techniques use are forwarded; the wrapper deliberately has no
//! `Deref` to the wgpu pass, so a draw cannot bypass the count. Where the frame counts work
//! ([`super::work`]), the encoder begins the pass's statistics query as it opens the pass and
//! the wrapper ends it when dropped, so every draw of the pass is inside it.

use std::ops::Range;

use super::PassKind;
use super::work::{SegmentQueries, WorkCounter, end_render};
use crate::shaders::{ComputePipeline, PipelineCost, RenderPipeline};

/// Where a pass's segments are counted, and the pass's label for new segments.
pub(super) type Counting<'p> = Option<(&'p mut WorkCounter, String)>;

/// Gives the running segment of a pass of `kind` the pipeline `cost`, or, where it has another
/// (and the counter has room), starts the next segment: the queries to begin after ending the
/// running ones.
fn segment_for(
    work: &mut Counting<'_>,
    kind: PassKind,
    cost: PipelineCost,
) -> Option<SegmentQueries> {
    let (work, label) = work.as_mut()?;
    match work.current_pipeline() {
        None => {
            work.set_current_pipeline(cost);
            None
        }
        Some(current) if current == cost || !work.has_room() => None,
        Some(_) => work.next(label.clone(), kind, Some(cost)),
    }
}

/// What the passes of one frame recorded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PassCounts {
    /// Draw calls (direct, indexed and indirect).
    pub draws: u64,
    /// Compute dispatches (direct and indirect).
    pub dispatches: u64,
}

/// A render pass opened through the frame encoder (target attached, bind group 0 set).
pub struct RenderPass<'p> {
    pass: wgpu::RenderPass<'p>,
    counts: &'p mut PassCounts,
    /// A statistics query and an occlusion query are open on the pass (ended on drop).
    counting: bool,
    /// Where the pass's segments are counted, and the pass's label for new segments.
    work: Counting<'p>,
}

impl Drop for RenderPass<'_> {
    fn drop(&mut self) {
        if self.counting {
            end_render(&mut self.pass);
        }
    }
}

impl<'p> RenderPass<'p> {
    /// Wraps `pass`, beginning the queries of its first segment (`first`, where counted; the
    /// pass's descriptor must name the counter's occlusion query set).
    pub(super) fn new(
        mut pass: wgpu::RenderPass<'p>,
        counts: &'p mut PassCounts,
        work: Counting<'p>,
        first: Option<SegmentQueries>,
    ) -> Self {
        let counting = work.is_some() && first.is_some();
        if let Some(q) = first.filter(|_| counting) {
            q.begin_render(&mut pass);
        }
        Self {
            pass,
            counts,
            counting,
            work: if counting { work } else { None },
        }
    }

    /// See [`wgpu::RenderPass::set_pipeline`]. Only pipelines made by
    /// [`crate::shaders::render_pipeline`] (or classified with
    /// [`RenderPipeline::from_raw`]) can be set: where their cost differs from the running
    /// segment's (another fragment kind, other texture fetches), the statistics query is ended
    /// and the next begun, so work is counted by [`crate::shaders::PipelineCost`].
    pub fn set_pipeline(&mut self, pipeline: &RenderPipeline) {
        self.pass.set_pipeline(pipeline);
        if let Some(next) = segment_for(&mut self.work, PassKind::Render, pipeline.cost()) {
            end_render(&mut self.pass);
            next.begin_render(&mut self.pass);
        }
    }

    /// See [`wgpu::RenderPass::set_bind_group`].
    pub fn set_bind_group(&mut self, index: u32, bind_group: &wgpu::BindGroup, offsets: &[u32]) {
        self.pass.set_bind_group(index, bind_group, offsets);
    }

    /// See [`wgpu::RenderPass::set_vertex_buffer`].
    pub fn set_vertex_buffer(&mut self, slot: u32, buffer_slice: wgpu::BufferSlice<'_>) {
        self.pass.set_vertex_buffer(slot, buffer_slice);
    }

    /// See [`wgpu::RenderPass::set_index_buffer`].
    pub fn set_index_buffer(
        &mut self,
        buffer_slice: wgpu::BufferSlice<'_>,
        index_format: wgpu::IndexFormat,
    ) {
        self.pass.set_index_buffer(buffer_slice, index_format);
    }

    /// See [`wgpu::RenderPass::set_stencil_reference`].
    pub fn set_stencil_reference(&mut self, reference: u32) {
        self.pass.set_stencil_reference(reference);
    }

    /// See [`wgpu::RenderPass::set_viewport`].
    pub fn set_viewport(&mut self, x: f32, y: f32, w: f32, h: f32, min_depth: f32, max_depth: f32) {
        self.pass.set_viewport(x, y, w, h, min_depth, max_depth);
    }

    /// See [`wgpu::RenderPass::set_scissor_rect`].
    pub fn set_scissor_rect(&mut self, x: u32, y: u32, width: u32, height: u32) {
        self.pass.set_scissor_rect(x, y, width, height);
    }

    /// Counts a direct draw of `instances` (and its instances, where the frame counts work).
    fn count_direct(&mut self, instances: &Range<u32>) {
        self.counts.draws += 1;
        if let Some((work, _)) = self.work.as_mut() {
            work.add_instances(u64::from(instances.end.saturating_sub(instances.start)));
        }
    }

    /// Counts an indirect draw whose arguments are at `offset` in `buffer`: where the frame
    /// counts work, their instance count is read back with the frame's queries.
    fn count_indirect(&mut self, buffer: &wgpu::Buffer, offset: u64) {
        self.counts.draws += 1;
        if let Some((work, _)) = self.work.as_mut() {
            work.add_indirect(buffer, offset);
        }
    }

    /// See [`wgpu::RenderPass::draw`]; counted, with its instances.
    pub fn draw(&mut self, vertices: Range<u32>, instances: Range<u32>) {
        self.count_direct(&instances);
        self.pass.draw(vertices, instances);
    }

    /// See [`wgpu::RenderPass::draw_indexed`]; counted, with its instances.
    pub fn draw_indexed(&mut self, indices: Range<u32>, base_vertex: i32, instances: Range<u32>) {
        self.count_direct(&instances);
        self.pass.draw_indexed(indices, base_vertex, instances);
    }

    /// See [`wgpu::RenderPass::draw_indirect`]; counted. Where the frame counts work, the
    /// instance count in the arguments is copied out at the end of the frame's commands, so
    /// `indirect_buffer` needs `COPY_SRC` usage besides `INDIRECT` (without it the frame's
    /// work is not read, and the runner says why).
    pub fn draw_indirect(&mut self, indirect_buffer: &wgpu::Buffer, indirect_offset: u64) {
        self.count_indirect(indirect_buffer, indirect_offset);
        self.pass.draw_indirect(indirect_buffer, indirect_offset);
    }

    /// See [`wgpu::RenderPass::draw_indexed_indirect`]; counted as
    /// [`RenderPass::draw_indirect`] is.
    pub fn draw_indexed_indirect(&mut self, indirect_buffer: &wgpu::Buffer, indirect_offset: u64) {
        self.count_indirect(indirect_buffer, indirect_offset);
        self.pass
            .draw_indexed_indirect(indirect_buffer, indirect_offset);
    }
}

/// A compute pass opened through the frame encoder (bind group 0 set).
pub struct ComputePass<'p> {
    pass: wgpu::ComputePass<'p>,
    counts: &'p mut PassCounts,
    /// A statistics query is open on the pass (ended on drop).
    counting: bool,
    /// Where the pass's segments are counted, and the pass's label for new segments.
    work: Counting<'p>,
}

impl Drop for ComputePass<'_> {
    fn drop(&mut self) {
        if self.counting {
            self.pass.end_pipeline_statistics_query();
        }
    }
}

impl<'p> ComputePass<'p> {
    pub(super) fn new(
        pass: wgpu::ComputePass<'p>,
        counts: &'p mut PassCounts,
        work: Counting<'p>,
    ) -> Self {
        Self {
            pass,
            counts,
            counting: work.is_some(),
            work,
        }
    }

    /// See [`wgpu::ComputePass::set_pipeline`]. Only pipelines made by
    /// [`crate::shaders::compute_pipeline`] can be set: where their cost (their texture
    /// fetches) differs from the running segment's, the statistics query is ended and the next
    /// begun, as in a render pass.
    pub fn set_pipeline(&mut self, pipeline: &ComputePipeline) {
        self.pass.set_pipeline(pipeline);
        if let Some(next) = segment_for(&mut self.work, PassKind::Compute, pipeline.cost()) {
            self.pass.end_pipeline_statistics_query();
            next.begin_compute(&mut self.pass);
        }
    }

    /// See [`wgpu::ComputePass::set_bind_group`].
    pub fn set_bind_group(&mut self, index: u32, bind_group: &wgpu::BindGroup, offsets: &[u32]) {
        self.pass.set_bind_group(index, bind_group, offsets);
    }

    /// See [`wgpu::ComputePass::dispatch_workgroups`]; counted.
    pub fn dispatch_workgroups(&mut self, x: u32, y: u32, z: u32) {
        self.counts.dispatches += 1;
        self.pass.dispatch_workgroups(x, y, z);
    }

    /// See [`wgpu::ComputePass::dispatch_workgroups_indirect`]; counted.
    pub fn dispatch_workgroups_indirect(
        &mut self,
        indirect_buffer: &wgpu::Buffer,
        indirect_offset: u64,
    ) {
        self.counts.dispatches += 1;
        self.pass
            .dispatch_workgroups_indirect(indirect_buffer, indirect_offset);
    }
}
