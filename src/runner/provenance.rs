//! What made a result: written as `meta.toml` next to every CSV, and as a paragraph of
//! Markdown ([`Provenance::to_markdown`]) at the top of the README of `grassbench run` and the
//! report of a sweep.

use crate::gpu::AdapterSummary;

/// The wgpu version this build uses (a test checks it against `Cargo.lock`).
pub const WGPU_VERSION: &str = "30.0.1";

/// The revision the running program was built from, once its `main` has said it
/// ([`record_build_revision`]).
static BUILD_REVISION: std::sync::OnceLock<&'static str> = std::sync::OnceLock::new();

/// Records the revision this program was built from, for every [`Provenance`] it collects
/// after (`grassbench`'s `main` passes what its build script read: `experiments/build.rs`).
/// The first call holds; later ones are ignored.
pub fn record_build_revision(revision: &'static str) {
    let _ = BUILD_REVISION.set(revision);
}

/// Command, adapter, revision, build and machine behind a set of figures.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize, PartialEq)]
pub struct Provenance {
    /// The command line that produced the results, the program by its name
    /// (`grassbench run ...`, not the path it was started from).
    pub command: String,
    /// `git describe`-like revision of the working tree (`+dirty` when sources outside `results/`
    /// are modified), or `unknown`.
    pub revision: String,
    /// The revision the running program was built from, as [`Provenance::revision`] reads
    /// it (`+dirty` when its sources differed from the commit), where the program says
    /// ([`record_build_revision`]: the `grassbench` command does); empty in files from before
    /// it was recorded and from programs that do not say. Where it is not the revision of the
    /// tree the run read, the figures are the build's: a binary built before a change, or
    /// from an uncommitted one, and run in a tree that has moved on.
    #[serde(default)]
    pub build_revision: String,
    /// `release` or `debug`.
    pub build_profile: String,
    /// grassbench version.
    pub grassbench_version: String,
    /// wgpu version.
    pub wgpu_version: String,
    /// CPU model.
    pub cpu: String,
    /// The CPU told apart from others of its name (`CpuId`'s text: vendor, family, model,
    /// stepping, the kernel's clock reading and the widest vector extension), where virtual
    /// machines name every model alike (`Intel(R) Xeon(R) Processor`): a software rasteriser's
    /// unit costs, and the last bit of its pictures, follow the instructions the CPU has. Empty
    /// in files from before it was recorded, or where the system does not say.
    #[serde(default)]
    pub cpu_id: String,
    /// Logical CPUs.
    pub cpu_count: usize,
    /// Operating system.
    pub os: String,
    /// When, UTC (RFC 3339, from the system clock).
    pub date: String,
    /// The process's memory allocator and its settings ([`super::allocator`]); empty in files
    /// from before it was recorded.
    #[serde(default)]
    pub allocator: String,
    /// The environment variables set for the process that change how a software driver
    /// works (`DRIVER_VARIABLES`: `LP_NUM_THREADS`, `GALLIUM_DRIVER` and the like), as
    /// `NAME=value`, comma-separated; empty where none is set and in files from before it was
    /// recorded. `LP_NUM_THREADS=0` makes llvmpipe and lavapipe
    /// rasterise in the submitting thread, after its vertices, rather than in threads of their
    /// own beside it: the same work, a different time (`results/cost_model/README.md`).
    #[serde(default)]
    pub driver_environment: String,
    /// The adapter.
    pub adapter: AdapterSummary,
}

/// The environment variables [`Provenance::driver_environment`] records: those that change
/// how Mesa's software rasterisers (llvmpipe, lavapipe) run, and which one runs. None takes
/// a path, so a record names no folder of the machine it was made on.
pub const DRIVER_VARIABLES: [&str; 6] = [
    "LP_NUM_THREADS",
    "LP_NATIVE_VECTOR_WIDTH",
    "LP_DEBUG",
    "LP_PERF",
    "GALLIUM_DRIVER",
    "MESA_LOADER_DRIVER_OVERRIDE",
];

/// [`Provenance::driver_environment`]'s text: each of [`DRIVER_VARIABLES`] that `lookup` finds
/// set, as `NAME=value`, in the list's order, comma-separated.
pub fn driver_environment(lookup: impl Fn(&str) -> Option<String>) -> String {
    DRIVER_VARIABLES
        .iter()
        .filter_map(|name| lookup(name).map(|value| format!("{name}={value}")))
        .collect::<Vec<_>>()
        .join(", ")
}

impl Provenance {
    /// Collects everything for `adapter` and the current process.
    pub fn collect(adapter: &AdapterSummary) -> Self {
        // Linux's description of the CPUs (elsewhere absent: the architecture stands for it).
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        Self {
            command: command_line(std::env::args()),
            revision: git_revision(),
            build_revision: BUILD_REVISION.get().copied().unwrap_or_default().to_owned(),
            build_profile: if cfg!(debug_assertions) {
                "debug"
            } else {
                "release"
            }
            .to_owned(),
            grassbench_version: env!("CARGO_PKG_VERSION").to_owned(),
            wgpu_version: WGPU_VERSION.to_owned(),
            cpu: Some(cpuinfo_field(&cpuinfo, "model name"))
                .filter(|name| !name.is_empty())
                .unwrap_or_else(|| std::env::consts::ARCH.to_owned()),
            cpu_id: CpuId::parse(&cpuinfo).to_string(),
            cpu_count: std::thread::available_parallelism().map_or(1, |n| n.get()),
            os: format!("{} {}", std::env::consts::OS, std::env::consts::ARCH),
            date: utc_now(),
            allocator: super::allocator::this_process(),
            driver_environment: driver_environment(|name| std::env::var(name).ok()),
            adapter: adapter.clone(),
        }
    }

    /// As TOML text.
    pub fn to_toml(&self) -> String {
        toml::to_string_pretty(self).unwrap_or_default()
    }

    /// As a Markdown paragraph: adapter, CPU, revision and date, then the command followed by
    /// `after_command` (e.g. `; shard: all`). Ends with a newline.
    pub fn to_markdown(&self, after_command: &str) -> String {
        let a = &self.adapter;
        let allocator = if self.allocator.is_empty() {
            String::new()
        } else {
            format!("; allocator: {}", self.allocator)
        };
        let environment = if self.driver_environment.is_empty() {
            String::new()
        } else {
            format!("; driver environment: `{}`", self.driver_environment)
        };
        let cpu_id = if self.cpu_id.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.cpu_id)
        };
        // A binary built from other sources than the tree it ran in says so.
        let build = if self.build_revision.is_empty() || self.build_revision == self.revision {
            format!("{} build", self.build_profile)
        } else {
            format!("{} build of `{}`", self.build_profile, self.build_revision)
        };
        format!(
            "Measured on `{}` ({}, {}; driver {} {}), CPU {}{cpu_id} x{}, revision `{}` ({build}), {}{allocator}{environment}.  \n\
             Command: `{}`{after_command}.\n",
            a.name,
            a.backend,
            a.device_type,
            a.driver,
            a.driver_info,
            self.cpu,
            self.cpu_count,
            self.revision,
            self.date,
            self.command,
        )
    }
}

/// A command line as recorded: the program by its file name without the platform's suffix
/// (`grassbench`, wherever it was built or installed), then the arguments.
pub fn command_line(args: impl IntoIterator<Item = String>) -> String {
    let mut args = args.into_iter();
    let program = args.next().map(|p| {
        let name = std::path::Path::new(&p)
            .file_name()
            .map_or_else(|| p.clone(), |n| n.to_string_lossy().into_owned());
        match name.strip_suffix(std::env::consts::EXE_SUFFIX) {
            Some(stem) if !stem.is_empty() => stem.to_owned(),
            _ => name,
        }
    });
    program
        .into_iter()
        .chain(args)
        .collect::<Vec<_>>()
        .join(" ")
}

include!("git_revision.rs");

/// What tells one CPU from another of the same name, read from Linux's `/proc/cpuinfo`
/// (its first processor): each field empty where the file does not give it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CpuId {
    /// `vendor_id` (`GenuineIntel`, `AuthenticAMD`).
    pub vendor: String,
    /// `cpu family`, `model` and `stepping`, as `6/167/1`.
    pub family_model_stepping: String,
    /// `cpu MHz`, rounded to the megahertz (a virtual machine's nominal clock).
    pub mhz: String,
    /// The widest SIMD extension among the flags: `avx512f`, `avx2`, `avx`, `sse4_2`, or empty.
    pub simd: String,
}

impl CpuId {
    /// The SIMD extensions looked for, widest first.
    const SIMD: [&'static str; 4] = ["avx512f", "avx2", "avx", "sse4_2"];

    /// Reads the first processor's block of `/proc/cpuinfo`'s text.
    pub fn parse(cpuinfo: &str) -> Self {
        let field = |key: &str| cpuinfo_field(cpuinfo, key);
        let fms = [field("cpu family"), field("model"), field("stepping")];
        let flags = field("flags");
        let flags: Vec<&str> = flags.split_whitespace().collect();
        Self {
            vendor: field("vendor_id"),
            family_model_stepping: if fms.iter().all(String::is_empty) {
                String::new()
            } else {
                fms.join("/")
            },
            mhz: field("cpu MHz")
                .parse::<f64>()
                .ok()
                .filter(|mhz| mhz.is_finite() && *mhz > 0.0)
                .map(|mhz| format!("{mhz:.0} MHz"))
                .unwrap_or_default(),
            simd: Self::SIMD
                .iter()
                .find(|s| flags.contains(s))
                .map(|s| (*s).to_owned())
                .unwrap_or_default(),
        }
    }
}

impl std::fmt::Display for CpuId {
    /// `GenuineIntel 6/167/1, 2600 MHz, avx512f`: the fields that are known, in that order.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let rest: Vec<&str> = [&self.family_model_stepping, &self.mhz, &self.simd]
            .into_iter()
            .map(String::as_str)
            .filter(|s| !s.is_empty())
            .collect();
        // The vendor names the rest: `GenuineIntel 6/167/1, ...`.
        let gap = if self.vendor.is_empty() || rest.is_empty() {
            ""
        } else {
            " "
        };
        write!(f, "{}{gap}{}", self.vendor, rest.join(", "))
    }
}

/// The value of `key` in the first processor's block of `/proc/cpuinfo`'s text, or empty.
fn cpuinfo_field(cpuinfo: &str, key: &str) -> String {
    cpuinfo
        .lines()
        .take_while(|l| !l.trim().is_empty())
        .filter_map(|l| l.split_once(':'))
        .find(|(k, _)| k.trim() == key)
        .map(|(_, v)| v.trim().to_owned())
        .unwrap_or_default()
}

/// Current UTC time as RFC 3339, computed from the Unix epoch (no date crate needed).
fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rem) = (secs / 86_400, secs % 86_400);
    // Civil-from-days (Howard Hinnant's algorithm).
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(a: &[&str]) -> Vec<String> {
        a.iter().map(|s| (*s).to_owned()).collect()
    }

    #[test]
    fn the_command_names_the_program_not_its_path() {
        assert_eq!(
            command_line(args(&[
                "/work/lead-target/release/grassbench",
                "run",
                "-o",
                "/tmp/x"
            ])),
            "grassbench run -o /tmp/x"
        );
        assert_eq!(
            command_line(args(&["./grassbench", "report", "results/a"])),
            "grassbench report results/a"
        );
        assert_eq!(command_line(args(&["grassbench"])), "grassbench");
        let exe = format!("target/release/grassbench{}", std::env::consts::EXE_SUFFIX);
        assert_eq!(command_line(args(&[&exe, "list"])), "grassbench list");
        assert_eq!(command_line(Vec::new()), "");
    }

    #[test]
    fn markdown_names_adapter_revision_and_command() {
        let adapter = AdapterSummary {
            name: "llvmpipe".into(),
            backend: "Vulkan".into(),
            device_type: "Cpu".into(),
            driver: "llvmpipe".into(),
            driver_info: "Mesa 22.3.6".into(),
            timestamps: false,
            timestamp_period_ns: 1.0,
            pipeline_statistics: false,
            msaa_sample_counts: vec![1, 4],
        };
        let p = Provenance {
            command: "grassbench sweep s.toml".into(),
            revision: "abc".into(),
            build_revision: "abc".into(),
            build_profile: "release".into(),
            grassbench_version: "0.1.0".into(),
            wgpu_version: WGPU_VERSION.into(),
            cpu: "EPYC".into(),
            cpu_id: String::new(),
            cpu_count: 2,
            os: "linux x86_64".into(),
            date: "2026-12-02T00:00:00Z".into(),
            allocator: "glibc malloc, its defaults".into(),
            driver_environment: String::new(),
            adapter,
        };
        assert_eq!(
            p.to_markdown("; shard: all"),
            "Measured on `llvmpipe` (Vulkan, Cpu; driver llvmpipe Mesa 22.3.6), CPU EPYC x2, \
             revision `abc` (release build), 2026-12-02T00:00:00Z; allocator: glibc malloc, its \
             defaults.  \n\
             Command: `grassbench sweep s.toml`; shard: all.\n"
        );
        assert!(
            p.to_markdown("")
                .ends_with("Command: `grassbench sweep s.toml`.\n")
        );
        // A CPU told apart by its identity, beside its name.
        let identified = Provenance {
            cpu_id: "AuthenticAMD 25/17/0, 2600 MHz, avx512f".into(),
            ..p.clone()
        };
        assert!(
            identified
                .to_markdown("")
                .contains("CPU EPYC (AuthenticAMD 25/17/0, 2600 MHz, avx512f) x2,"),
            "{}",
            identified.to_markdown("")
        );
        // A binary built from other sources than the tree it ran in names them.
        let moved = Provenance {
            build_revision: "9f0+dirty".into(),
            ..p.clone()
        };
        assert!(
            moved
                .to_markdown("")
                .contains("revision `abc` (release build of `9f0+dirty`),"),
            "{}",
            moved.to_markdown("")
        );
        // A file from before the build's revision was recorded reads as it did.
        let mut table: toml::Table = toml::from_str(&p.to_toml()).expect("provenance TOML parses");
        table.remove("build_revision");
        let before: Provenance = toml::Value::Table(table)
            .try_into()
            .expect("provenance without a build revision parses");
        assert_eq!(before.build_revision, "");
        assert_eq!(before.to_markdown(""), p.to_markdown(""));
        // Rasterisation moved into the submitting thread is said; a file from before the
        // driver's environment was recorded reads as it did.
        let serial = Provenance {
            driver_environment: driver_environment(|name| {
                (name == "LP_NUM_THREADS").then(|| "0".to_owned())
            }),
            ..p.clone()
        };
        assert!(
            serial
                .to_markdown("")
                .contains("its defaults; driver environment: `LP_NUM_THREADS=0`.  \n"),
            "{}",
            serial.to_markdown("")
        );
        let mut table: toml::Table =
            toml::from_str(&serial.to_toml()).expect("provenance TOML parses");
        table.remove("driver_environment");
        let before: Provenance = toml::Value::Table(table)
            .try_into()
            .expect("provenance without a driver environment parses");
        assert_eq!(before.to_markdown(""), p.to_markdown(""));
        // A file from before the allocator was recorded says nothing of it.
        let older = Provenance {
            allocator: String::new(),
            ..p
        };
        assert!(
            older.to_markdown("").contains("2026-12-02T00:00:00Z.  \n"),
            "{}",
            older.to_markdown("")
        );
    }

    #[test]
    fn driver_environment_lists_the_variables_set_in_order() {
        assert_eq!(driver_environment(|_| None), "");
        let set = |name: &str| match name {
            "GALLIUM_DRIVER" => Some("llvmpipe".to_owned()),
            "LP_NUM_THREADS" => Some("0".to_owned()),
            "HOME" => Some("/root".to_owned()),
            _ => None,
        };
        assert_eq!(
            driver_environment(set),
            "LP_NUM_THREADS=0, GALLIUM_DRIVER=llvmpipe"
        );
    }

    /// Two virtual machines' `/proc/cpuinfo` as this project's hosts gave them (abridged), and
    /// the file's second processor, which must not be read.
    #[test]
    fn cpu_id_tells_hosts_of_one_name_apart() {
        let xeon = "processor\t: 0\nvendor_id\t: GenuineIntel\ncpu family\t: 6\nmodel\t\t: 167\n\
                    model name\t: Intel(R) Xeon(R) Processor\nstepping\t: 1\ncpu MHz\t\t: 2600.000\n\
                    flags\t\t: fpu sse4_2 avx avx2 avx512f avx512vl\n\n\
                    processor\t: 1\nvendor_id\t: OtherVendor\nflags\t\t: fpu\n";
        let id = CpuId::parse(xeon);
        assert_eq!(id.family_model_stepping, "6/167/1");
        assert_eq!(id.to_string(), "GenuineIntel 6/167/1, 2600 MHz, avx512f");
        let epyc = "vendor_id\t: AuthenticAMD\ncpu family\t: 25\nmodel\t\t: 17\nstepping\t: 0\n\
                    cpu MHz\t\t: 2595.124\nflags\t\t: fpu sse4_2 avx avx2\n";
        assert_eq!(
            CpuId::parse(epyc).to_string(),
            "AuthenticAMD 25/17/0, 2595 MHz, avx2"
        );
        // Another system's text (or none): nothing invented.
        assert_eq!(CpuId::parse("").to_string(), "");
        assert_eq!(CpuId::parse("cpu MHz : NaN\n"), CpuId::default());
        let no_vendor = CpuId::parse("flags : sse4_2\n");
        assert_eq!(no_vendor.to_string(), "sse4_2");
        assert_eq!(
            CpuId::parse("vendor_id : GenuineIntel\n").to_string(),
            "GenuineIntel"
        );
        assert_eq!(
            cpuinfo_field(xeon, "model name"),
            "Intel(R) Xeon(R) Processor"
        );
    }
}
