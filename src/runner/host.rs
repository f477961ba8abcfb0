//! What the rest of the host did while a run measured: the CPU time other processes took, and
//! the time the hypervisor took away (steal); and how much of this process's own time went to
//! the kernel. On a software rasteriser the GPU is the CPU, so
//! a compile or a second benchmark on the same cores slows every figure by up to the share of
//! the cores it takes; recording it beside the figures tells a reader when a time moved for a
//! reason outside the run (issue 19 §8: the same boulanger frame measured 60 ms in one run and
//! 190-200 ms in others, with identical images). The process's own kernel time is time its
//! frames paid the operating system rather than their work: a heap trimmed and grown again
//! every frame zeroing fresh pages (`super::allocator`: the reference's pitch at 640x360 spent
//! 0.18 cores in the kernel during its measured frames in that state, 0.009 with the heaps
//! kept), and on frames of a few milliseconds the rasteriser threads' wake-ups (up to 0.2).
//!
//! Read from Linux's `/proc/stat` (every CPU's ticks by state) and `/proc/self/stat` (this
//! process's user and system ticks, its rasteriser threads included); both count in the same
//! clock ticks. Elsewhere nothing is read and the figures stay empty.

/// A reading of the host's and this process's CPU counters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HostSample {
    /// Ticks of all CPUs in every state.
    total: u64,
    /// Ticks of all CPUs neither idle nor waiting for I/O (steal excluded).
    busy: u64,
    /// Ticks the hypervisor ran something else on our CPUs.
    steal: u64,
    /// This process's user + system ticks.
    own: u64,
    /// This process's system ticks.
    own_system: u64,
    /// CPUs counted.
    cpus: u64,
}

/// What other work did during an interval, from two [`HostSample`]s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HostLoad {
    /// Cores other processes kept busy, on average (0 on a quiet host; 1 = a whole core).
    pub other_cores: f64,
    /// Share of the CPUs' time the hypervisor gave to other machines, 0..1.
    pub steal: f64,
    /// Cores this process (its rasteriser threads included) spent in the kernel, on average.
    pub own_kernel_cores: f64,
}

impl HostSample {
    /// Reads the counters now; `None` where `/proc` is missing or unreadable.
    pub fn now() -> Option<Self> {
        let stat = std::fs::read_to_string("/proc/stat").ok()?;
        let own = std::fs::read_to_string("/proc/self/stat").ok()?;
        Self::parse(&stat, &own)
    }

    /// Parses the text of `/proc/stat` and `/proc/self/stat`.
    pub fn parse(stat: &str, own: &str) -> Option<Self> {
        let cpu = stat.lines().find(|l| l.starts_with("cpu "))?;
        let ticks: Vec<u64> = cpu
            .split_whitespace()
            .skip(1)
            .map(str::parse)
            .collect::<Result<_, _>>()
            .ok()?;
        // user nice system idle iowait irq softirq steal [guest guest_nice: inside user].
        let field = |k: usize| ticks.get(k).copied().unwrap_or(0);
        let total: u64 = (0..8).map(field).sum();
        let (idle, steal) = (field(3) + field(4), field(7));
        let cpus = stat
            .lines()
            .filter(|l| l.starts_with("cpu") && l.as_bytes().get(3).is_some_and(u8::is_ascii_digit))
            .count() as u64;
        // The command name (field 2) is in parentheses and may hold spaces: count from the
        // last ')'. utime and stime are fields 14 and 15, the 12th and 13th after it.
        let after = own.get(own.rfind(')')? + 1..)?;
        let mut rest = after.split_whitespace().skip(11);
        let utime: u64 = rest.next()?.parse().ok()?;
        let stime: u64 = rest.next()?.parse().ok()?;
        Some(Self {
            total,
            busy: total - idle - steal,
            steal,
            own: utime + stime,
            own_system: stime,
            cpus: cpus.max(1),
        })
    }

    /// The load between `self` (earlier) and `later`; `None` when no tick passed.
    pub fn load_until(&self, later: &Self) -> Option<HostLoad> {
        let total = later.total.checked_sub(self.total)?;
        if total == 0 {
            return None;
        }
        let busy = later.busy.saturating_sub(self.busy);
        let own = later.own.saturating_sub(self.own);
        let steal = later.steal.saturating_sub(self.steal);
        let own_system = later.own_system.saturating_sub(self.own_system);
        // Ticks elapsed per CPU: the interval's length in ticks.
        let per_cpu = total as f64 / self.cpus as f64;
        Some(HostLoad {
            other_cores: (busy.saturating_sub(own) as f64 / per_cpu).max(0.0),
            steal: steal as f64 / total as f64,
            own_kernel_cores: own_system as f64 / per_cpu,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const OWN: &str = "4242 (grass bench) R 1 2 3 4 5 6 7 8 9 10 {u} {s} 0 0 20 0 9 0 100";

    fn stat(user: u64, idle: u64, steal: u64) -> String {
        format!(
            "cpu  {user} 0 0 {idle} 0 0 0 {steal} 0 0\ncpu0 1 0 0 1 0 0 0 0 0 0\ncpu1 1 0 0 1 0 0 0 0 0 0\nintr 5\n"
        )
    }

    fn own(u: u64, s: u64) -> String {
        OWN.replace("{u}", &u.to_string())
            .replace("{s}", &s.to_string())
    }

    #[test]
    fn another_process_on_one_of_two_cores_is_one_other_core() {
        // 100 ticks per CPU pass on 2 CPUs: 200 ticks. We used one core (100 ticks), another
        // process the other (100 more busy ticks).
        let a = HostSample::parse(&stat(1000, 5000, 0), &own(300, 50)).unwrap();
        let b = HostSample::parse(&stat(1200, 5000, 0), &own(380, 70)).unwrap();
        let load = a.load_until(&b).unwrap();
        assert!((load.other_cores - 1.0).abs() < 1e-12, "{load:?}");
        assert_eq!(load.steal, 0.0);
        // Of our core, 20 ticks in 100 were the kernel's.
        assert!((load.own_kernel_cores - 0.2).abs() < 1e-12, "{load:?}");
        // Alone: we took one core, the other idled.
        let c = HostSample::parse(&stat(1100, 5100, 0), &own(400, 50)).unwrap();
        assert_eq!(a.load_until(&c).unwrap().other_cores, 0.0);
        // The hypervisor took a quarter of the time.
        let d = HostSample::parse(&stat(1100, 5050, 50), &own(400, 50)).unwrap();
        let load = a.load_until(&d).unwrap();
        assert_eq!((load.other_cores, load.steal), (0.0, 0.25));
        assert_eq!(load.own_kernel_cores, 0.0);
        // No tick passed: nothing to say.
        assert_eq!(a.load_until(&a), None);
    }

    #[test]
    fn malformed_counters_are_no_reading() {
        assert_eq!(HostSample::parse("intr 5\n", &own(1, 1)), None);
        assert_eq!(HostSample::parse(&stat(1, 1, 0), "4242 (x) R 1"), None);
        assert!(HostSample::now().is_some() || !std::path::Path::new("/proc/stat").exists());
    }
}
