//! Headless GPU access: choosing a backend and adapter, creating the device, and catching
//! wgpu errors so that a validation error fails a run instead of scrolling past in a log.

mod announce;
mod backend;
mod context;
pub mod limits;
pub mod memory;
mod scope;

pub use backend::BackendChoice;
pub use context::{AdapterSummary, GpuContext};
pub use memory::GpuEstimate;
pub use scope::ErrorSink;
