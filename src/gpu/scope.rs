//! Turning wgpu's errors into [`Error`]s.
//!
//! wgpu reports validation and out-of-memory errors asynchronously, either to an error scope
//! or, outside any scope, to the device's uncaptured-error handler, whose default *panics*.
//! grassbench installs an [`ErrorSink`] as that handler (so nothing panics) and wraps every
//! unit of work in [`GpuContext::scoped`](super::GpuContext::scoped), which pops its scopes and
//! also drains the sink: an error anywhere fails the unit of work that caused it.

use std::sync::{Arc, Mutex};

use crate::Error;

/// Collects errors that reached no error scope, and the device-lost message if any.
#[derive(Clone, Default, Debug)]
pub struct ErrorSink {
    inner: Arc<Mutex<SinkState>>,
}

#[derive(Default, Debug)]
struct SinkState {
    errors: Vec<wgpu::Error>,
    lost: Option<String>,
}

impl ErrorSink {
    /// Installs this sink as `device`'s uncaptured-error handler and device-lost callback.
    pub fn install(&self, device: &wgpu::Device) {
        let sink = self.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| sink.push(e)));
        let sink = self.clone();
        device.set_device_lost_callback(move |reason, message| {
            if let Ok(mut s) = sink.inner.lock() {
                s.lost = Some(format!("{reason:?}: {message}"));
            }
        });
    }

    fn push(&self, e: wgpu::Error) {
        if let Ok(mut s) = self.inner.lock() {
            s.errors.push(e);
        }
    }

    /// The first error collected since the last call, as an [`Error`] about `during`.
    pub fn take(&self, during: &str) -> Option<Error> {
        let mut s = self.inner.lock().ok()?;
        if let Some(message) = s.lost.clone() {
            return Some(Error::DeviceLost {
                during: during.to_owned(),
                message,
            });
        }
        let first = s.errors.drain(..).next()?;
        Some(convert(first, during))
    }
}

/// Maps a wgpu error to the matching [`Error`] variant.
pub(crate) fn convert(e: wgpu::Error, during: &str) -> Error {
    let during = during.to_owned();
    match e {
        wgpu::Error::OutOfMemory { source } => Error::OutOfMemory {
            during,
            message: source.to_string(),
        },
        wgpu::Error::Validation { description, .. } => Error::Validation {
            during,
            message: description,
        },
        wgpu::Error::Internal { description, .. } => Error::Validation {
            during,
            message: format!("internal error: {description}"),
        },
    }
}
