//! What a command says about the adapter before it measures anything: which adapter, backend
//! and driver the figures will come from, and what that adapter cannot record.
//!
//! A machine without a Vulkan driver runs `--backend auto` on GL without complaint, and GL has
//! no pipeline statistics under wgpu: the run's work columns and cost model stay empty, its
//! times are another rasteriser's and its pictures differ from Vulkan's in edge pixels. The
//! `meta.toml` records it; these lines say it while there is still time to stop the run.

use super::{AdapterSummary, BackendChoice};

impl AdapterSummary {
    /// One line naming the adapter, its backend and its driver, e.g. `adapter: llvmpipe (LLVM
    /// 15.0.6, 256 bits) on Vulkan, Mesa 22.3.6 (LLVM 15.0.6), a software rasteriser`.
    pub fn describe(&self) -> String {
        let driver = if self.driver_info.is_empty() {
            self.driver.clone()
        } else {
            self.driver_info.clone()
        };
        let mut line = format!("adapter: {} on {}", self.name, self.backend);
        if !driver.is_empty() {
            line.push_str(&format!(", {driver}"));
        }
        if self.device_type == "Cpu" {
            line.push_str(", a software rasteriser");
        }
        line
    }

    /// What the figures of a run on this adapter, chosen by `choice`, will lack, and how to
    /// get it where that is in the user's hands: one note a line, none when nothing is missing.
    pub fn notes(&self, choice: BackendChoice) -> Vec<String> {
        let mut notes = Vec::new();
        if choice == BackendChoice::Auto && self.backend == "Gl" {
            notes.push(
                "note: no Vulkan, Metal or DX12 adapter was found, so this runs on GL; on \
                 Linux without a GPU, Mesa's lavapipe gives Vulkan (`apt-get install \
                 mesa-vulkan-drivers`, which `make setup` runs), or pass `--backend gl` to \
                 choose GL on purpose"
                    .to_owned(),
            );
        }
        if !self.pipeline_statistics {
            notes.push(
                "note: no pipeline statistics on this adapter: the work columns of frames.csv \
                 and runs.csv stay empty and no run is priced by the cost model"
                    .to_owned(),
            );
        }
        if !self.timestamps {
            notes.push(
                "note: no timestamp queries on this adapter: GPU times are submit-to-poll \
                 wall time only, with no per-pass split"
                    .to_owned(),
            );
        }
        notes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lavapipe() -> AdapterSummary {
        AdapterSummary {
            name: "llvmpipe (LLVM 15.0.6, 256 bits)".to_owned(),
            driver: "llvmpipe".to_owned(),
            driver_info: "Mesa 22.3.6 (LLVM 15.0.6)".to_owned(),
            backend: "Vulkan".to_owned(),
            device_type: "Cpu".to_owned(),
            timestamps: true,
            timestamp_period_ns: 1.0,
            pipeline_statistics: true,
            msaa_sample_counts: vec![1, 4],
        }
    }

    /// GL's llvmpipe as wgpu reports it: no driver name, the version in `driver_info`,
    /// timestamps but no pipeline statistics.
    fn gl() -> AdapterSummary {
        AdapterSummary {
            driver: String::new(),
            driver_info: "4.5 (Core Profile) Mesa 22.3.6".to_owned(),
            backend: "Gl".to_owned(),
            pipeline_statistics: false,
            ..lavapipe()
        }
    }

    #[test]
    fn the_line_names_adapter_backend_and_driver() {
        assert_eq!(
            lavapipe().describe(),
            "adapter: llvmpipe (LLVM 15.0.6, 256 bits) on Vulkan, Mesa 22.3.6 (LLVM 15.0.6), \
             a software rasteriser"
        );
        let gpu = AdapterSummary {
            name: "NVIDIA H100".to_owned(),
            driver: "NVIDIA".to_owned(),
            driver_info: String::new(),
            device_type: "DiscreteGpu".to_owned(),
            ..lavapipe()
        };
        assert_eq!(gpu.describe(), "adapter: NVIDIA H100 on Vulkan, NVIDIA");
    }

    #[test]
    fn a_full_adapter_needs_no_note() {
        for choice in [BackendChoice::Auto, BackendChoice::Vulkan] {
            assert!(lavapipe().notes(choice).is_empty());
        }
    }

    #[test]
    fn gl_by_default_is_called_out_and_gl_by_choice_is_not() {
        let auto = gl().notes(BackendChoice::Auto);
        assert_eq!(auto.len(), 2, "{auto:?}");
        assert!(auto[0].contains("mesa-vulkan-drivers") && auto[0].contains("--backend gl"));
        assert!(auto[1].contains("pipeline statistics") && auto[1].contains("cost model"));
        let chosen = gl().notes(BackendChoice::Gl);
        assert_eq!(chosen.len(), 1, "{chosen:?}");
        assert!(chosen[0].contains("pipeline statistics"));
    }

    #[test]
    fn an_adapter_without_timestamps_says_which_clock_is_left() {
        let untimed = AdapterSummary {
            timestamps: false,
            ..lavapipe()
        };
        let notes = untimed.notes(BackendChoice::Vulkan);
        assert_eq!(notes.len(), 1, "{notes:?}");
        assert!(notes[0].contains("submit-to-poll"));
    }
}
