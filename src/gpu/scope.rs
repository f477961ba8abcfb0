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
                s.lost = Some(if message.trim().is_empty() {
                    format!("{reason:?}")
                } else {
                    format!("{reason:?}: {message}")
                });
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

/// Maps a wgpu error to the matching [`Error`] variant. The message is wgpu's whole error
/// chain on one line ([`chain`]): which call, which resource (its label) and which rule or
/// limit, never a bare "Validation Error".
pub(crate) fn convert(e: wgpu::Error, during: &str) -> Error {
    let during = during.to_owned();
    let message = chain(&e);
    match e {
        wgpu::Error::OutOfMemory { .. } => Error::OutOfMemory { during, message },
        wgpu::Error::Validation { .. } => Error::Validation { during, message },
        wgpu::Error::Internal { .. } => Error::Validation {
            during,
            message: format!("internal error: {message}"),
        },
    }
}

/// `e`'s causes, found by walking [`std::error::Error::source`], joined with `: ` on one line
/// (each cause's whitespace collapsed), after `e`'s own text where that says more than a
/// heading: wgpu's validation errors display as "Validation Error" plus an indented tree of the
/// same causes, and the causes alone name the call, the resource's label and the limit.
pub(crate) fn chain(e: &(dyn std::error::Error + 'static)) -> String {
    let one_line = |text: String| text.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut parts: Vec<String> = Vec::new();
    let mut cause = e.source();
    while let Some(c) = cause {
        let text = one_line(c.to_string());
        // A wrapper repeating its cause word for word adds nothing.
        if !text.is_empty() && parts.last() != Some(&text) {
            parts.push(text);
        }
        cause = c.source();
    }
    let own = one_line(e.to_string());
    let heading = own
        .split(" Caused by:")
        .next()
        .unwrap_or_default()
        .to_owned();
    if parts.is_empty() {
        return own;
    }
    let mut text = parts.join(": ");
    if !heading.is_empty() && heading != "Validation Error" && heading != "Out of Memory" {
        text = format!("{heading}: {text}");
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An error with an optional cause.
    #[derive(Debug)]
    struct Layer(&'static str, Option<Box<Layer>>);

    impl std::fmt::Display for Layer {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str(self.0)
        }
    }

    impl std::error::Error for Layer {
        fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
            self.1.as_deref().map(|l| l as _)
        }
    }

    #[test]
    fn the_chain_names_every_cause_on_one_line_after_a_meaningful_heading() {
        let e = Layer(
            "Validation Error\n\nCaused by:\n  In Device::create_bind_group_layout\n",
            Some(Box::new(Layer(
                "In Device::create_bind_group_layout, label = 'slices'",
                Some(Box::new(Layer(
                    "Too many bindings of type StorageBuffers in Stage VERTEX,\n limit is 0, count was 1",
                    None,
                ))),
            ))),
        );
        assert_eq!(
            chain(&e),
            "In Device::create_bind_group_layout, label = 'slices': Too many bindings of type \
             StorageBuffers in Stage VERTEX, limit is 0, count was 1"
        );
        let plain = Layer("device lost", Some(Box::new(Layer("timeout", None))));
        assert_eq!(chain(&plain), "device lost: timeout");
        assert_eq!(chain(&Layer("alone", None)), "alone");
    }
}
