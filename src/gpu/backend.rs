//! Which graphics API to run on.

use std::fmt;
use std::str::FromStr;

use crate::Error;

/// Environment variable consulted when no `--backend` is given.
pub const BACKEND_ENV: &str = "GRASSBENCH_BACKEND";

/// The backend a person asked for. `Auto` prefers a hardware adapter on any native API and
/// falls back to a software one (lavapipe, llvmpipe, WARP).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BackendChoice {
    /// Any backend; hardware adapters first.
    #[default]
    Auto,
    /// Vulkan (lavapipe on a machine without a GPU).
    Vulkan,
    /// OpenGL / GLES through EGL (llvmpipe on a machine without a GPU).
    Gl,
    /// Metal (macOS).
    Metal,
    /// Direct3D 12 (Windows).
    Dx12,
}

impl BackendChoice {
    /// All names accepted on the command line.
    pub const NAMES: &'static str = "auto, vulkan, gl, metal, dx12";

    /// The choice in the `GRASSBENCH_BACKEND` environment variable, or `Auto` when unset.
    pub fn from_env() -> Result<Self, Error> {
        match std::env::var(BACKEND_ENV) {
            Ok(s) if !s.trim().is_empty() => s.parse(),
            _ => Ok(Self::Auto),
        }
    }

    /// The wgpu backend set this choice enumerates.
    pub fn backends(self) -> wgpu::Backends {
        match self {
            Self::Auto => wgpu::Backends::all(),
            Self::Vulkan => wgpu::Backends::VULKAN,
            Self::Gl => wgpu::Backends::GL,
            Self::Metal => wgpu::Backends::METAL,
            Self::Dx12 => wgpu::Backends::DX12,
        }
    }
}

impl FromStr for BackendChoice {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self, Error> {
        match s.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(Self::Auto),
            "vulkan" | "vk" => Ok(Self::Vulkan),
            "gl" | "gles" | "opengl" => Ok(Self::Gl),
            "metal" | "mtl" => Ok(Self::Metal),
            "dx12" | "d3d12" => Ok(Self::Dx12),
            other => Err(Error::UnknownName {
                kind: "backend",
                name: other.to_owned(),
                valid: Self::NAMES.to_owned(),
            }),
        }
    }
}

impl fmt::Display for BackendChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Auto => "auto",
            Self::Vulkan => "vulkan",
            Self::Gl => "gl",
            Self::Metal => "metal",
            Self::Dx12 => "dx12",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_names_and_rejects_others() {
        assert_eq!(
            "Vulkan".parse::<BackendChoice>().ok(),
            Some(BackendChoice::Vulkan)
        );
        assert_eq!("gl".parse::<BackendChoice>().ok(), Some(BackendChoice::Gl));
        let err = "directx9"
            .parse::<BackendChoice>()
            .err()
            .map(|e| e.to_string());
        assert!(err.is_some_and(|e| e.contains("directx9") && e.contains("vulkan")));
    }
}
