//! The one error type of the core library.
//!
//! Every variant says what went wrong *and* how to fix it, because these messages end up in
//! front of a person running a sweep at 3 a.m. Binaries wrap them with `anyhow::Context`.

use std::path::PathBuf;

/// Result alias used throughout the core.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in the core library.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// No GPU adapter matched the requested backend.
    #[error(
        "no GPU adapter found for backend `{backend}` (adapters seen: {seen}). Fix: install a GPU driver, \
         or Mesa's software Vulkan driver (Debian/Ubuntu package `mesa-vulkan-drivers`), or try \
         `--backend gl` / GRASSBENCH_BACKEND=gl"
    )]
    NoAdapter {
        /// The backend that was asked for.
        backend: String,
        /// Adapters that were found but rejected, or "none".
        seen: String,
    },
    /// The adapter refused to create a device.
    #[error("the adapter `{adapter}` could not create a device: {reason}")]
    RequestDevice {
        /// Adapter name.
        adapter: String,
        /// wgpu's reason.
        reason: String,
    },
    /// A wgpu validation error caught by an error scope or the uncaptured-error handler.
    #[error("GPU validation error during {during}: {message}")]
    Validation {
        /// What the harness was doing ("frame 3 of reference", "creating pipelines", ...).
        during: String,
        /// wgpu's message.
        message: String,
    },
    /// The GPU ran out of memory.
    #[error(
        "the GPU ran out of memory during {during}: {message}. Fix: lower the resolution, the \
         blade density or the technique's parameters"
    )]
    OutOfMemory {
        /// What the harness was doing.
        during: String,
        /// wgpu's message.
        message: String,
    },
    /// The device was lost (driver reset, hang, or the device was dropped).
    #[error("the GPU device was lost during {during}: {message}")]
    DeviceLost {
        /// What the harness was doing.
        during: String,
        /// wgpu's message.
        message: String,
    },
    /// The adapter lacks a feature or limit a technique needs.
    #[error("the adapter `{adapter}` cannot run `{what}`: {missing}")]
    Unsupported {
        /// Adapter name.
        adapter: String,
        /// Technique or operation.
        what: String,
        /// What is missing.
        missing: String,
    },
    /// Reading or writing a file failed.
    #[error("{action} `{path}`: {error}")]
    Io {
        /// "cannot read", "cannot write", ...
        action: &'static str,
        /// The file.
        path: PathBuf,
        /// The OS error, already in the message: not a `source`, so an error chain printed
        /// cause by cause (`{:#}` in anyhow) says it once.
        error: std::io::Error,
    },
    /// A scene, sweep or map file is malformed.
    #[error("{path}: {message}")]
    InvalidFile {
        /// The file.
        path: PathBuf,
        /// What is wrong and how to fix it.
        message: String,
    },
    /// A parameter is out of range, NaN, or otherwise unusable.
    #[error("invalid parameter `{name}` = {value}: expected {expected}")]
    InvalidParameter {
        /// Dotted parameter name, e.g. `grass.density`.
        name: String,
        /// The offending value as text.
        value: String,
        /// What would have been accepted.
        expected: String,
    },
    /// A name (scene, technique, path kind, ...) that is not known.
    #[error("unknown {kind} `{name}`; valid: {valid}")]
    UnknownName {
        /// What kind of name.
        kind: &'static str,
        /// The name given.
        name: String,
        /// The names that exist.
        valid: String,
    },
    /// Encoding or decoding an image failed.
    #[error("image `{path}`: {message}")]
    Image {
        /// The file (or a description of the in-memory image).
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// Writing CSV output failed.
    #[error("writing CSV `{path}`: {message}")]
    Csv {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// The cost model's unit costs cannot be fitted to the calibration's samples.
    #[error("cannot fit the unit costs: {message}")]
    CostFit {
        /// The terms the samples cannot identify (never exercised, or not independent of
        /// the others), by [`crate::cost::Term::name`]; empty when the problem is elsewhere.
        unidentifiable: Vec<String>,
        /// What is wrong and how to fix it.
        message: String,
    },
    /// Anything a technique reports that has no better variant.
    #[error("technique `{technique}`: {message}")]
    Technique {
        /// Technique id.
        technique: String,
        /// What went wrong.
        message: String,
    },
}

impl Error {
    /// Whether this is a fault the device reported while working (a validation error, running
    /// out of memory, a lost device), after which a run's device is not trusted again, as
    /// opposed to a refusal before any GPU work or a file or parameter error.
    pub fn is_device_fault(&self) -> bool {
        matches!(
            self,
            Self::Validation { .. } | Self::OutOfMemory { .. } | Self::DeviceLost { .. }
        )
    }

    /// Shorthand for an [`Error::InvalidParameter`].
    pub fn param(
        name: impl Into<String>,
        value: impl std::fmt::Display,
        expected: impl Into<String>,
    ) -> Self {
        Self::InvalidParameter {
            name: name.into(),
            value: value.to_string(),
            expected: expected.into(),
        }
    }

    /// Shorthand for an [`Error::Io`].
    pub fn io(action: &'static str, path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io {
            action,
            path: path.into(),
            error: source,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The message and its causes joined the way anyhow's `{:#}` prints a chain.
    fn chain(e: &dyn std::error::Error) -> String {
        let mut text = e.to_string();
        let mut cause = e.source();
        while let Some(c) = cause {
            text.push_str(&format!(": {c}"));
            cause = c.source();
        }
        text
    }

    #[test]
    fn an_io_error_chain_names_its_cause_once() {
        let e = Error::io(
            "cannot write",
            "out/runs.csv",
            std::io::Error::from(std::io::ErrorKind::AlreadyExists),
        );
        let text = chain(&e);
        assert!(text.starts_with("cannot write `out/runs.csv`: "), "{text}");
        assert_eq!(text.matches("exists").count(), 1, "{text}");
    }
}
