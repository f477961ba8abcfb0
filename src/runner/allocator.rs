//! The process's memory allocator, as a measurement condition.
//!
//! On Linux with glibc, Mesa's lavapipe allocates the bins of every frame's scene in blocks of
//! 64 KiB on its queue thread and frees them when the frame is drawn. glibc's malloc hands that
//! thread's heap back to the kernel once its free top passes the *trim threshold* (128 KiB by
//! default, raised only when the process happens to free a large `mmap`ped block first), so a
//! process may grow the heap a block at a time with `mprotect` and shrink it again in every
//! frame, the kernel zeroing each fresh page: measured on the reference's pitch at 640x360
//! (`results/run_to_run/README.md`, *The reference's other state, found*), 571-616 ms a frame
//! and 1.85-2.11 s of system time in five processes against 418-493 ms and 0.17-0.22 s with the
//! heaps kept. Which of the two a process fell into depended on what it had freed before, so the
//! same work read 1.2-1.3 times as slow (medians of three processes each way on the pitch and
//! the flyover) from one process to the next.
//!
//! The `grassbench` binary therefore starts itself again with [`STEADY_TUNABLES`] in
//! `GLIBC_TUNABLES` (glibc reads its tunables only at start-up) unless the environment already
//! sets malloc tunables of its own or `GRASSBENCH_ALLOCATOR=system` asks for the platform's
//! default; [`describe`] says in `meta.toml` which allocator a result was measured with. Other
//! platforms' allocators are left as they are.

/// glibc malloc tunables that keep freed memory in the process: heaps are never trimmed below
/// 1 GiB, they grow 64 MiB at a time, and blocks up to 32 MiB (glibc's largest threshold) come
/// from the heaps instead of being mapped and unmapped each time.
pub const STEADY_TUNABLES: &str = "glibc.malloc.trim_threshold=1073741824:\
glibc.malloc.top_pad=67108864:glibc.malloc.mmap_threshold=33554432";

/// The environment variable that opts out: `GRASSBENCH_ALLOCATOR=system`.
pub const OPT_OUT_VARIABLE: &str = "GRASSBENCH_ALLOCATOR";

/// Whether this build's C library reads [`STEADY_TUNABLES`] (Linux with glibc).
pub const TUNABLE: bool = cfg!(all(target_os = "linux", target_env = "gnu"));

/// The `GLIBC_TUNABLES` value to start again with, given the current `GLIBC_TUNABLES` and
/// [`OPT_OUT_VARIABLE`]; `None` when the process should go on as it is: opted out, or its
/// tunables already name a malloc setting (ours after the restart, or the user's own, which
/// win).
pub fn tunables_to_set(current: Option<&str>, opt_out: Option<&str>) -> Option<String> {
    if opt_out.is_some_and(|v| v.trim().eq_ignore_ascii_case("system")) {
        return None;
    }
    match current.map(str::trim).filter(|c| !c.is_empty()) {
        Some(c) if c.contains("glibc.malloc.") => None,
        Some(c) => Some(format!("{c}:{STEADY_TUNABLES}")),
        None => Some(STEADY_TUNABLES.to_owned()),
    }
}

/// What `meta.toml` records as the allocator, from the same two variables: the malloc tunables
/// in effect, or the platform's default (and why).
pub fn describe(tunable: bool, current: Option<&str>, opt_out: Option<&str>) -> String {
    if !tunable {
        return "the platform's default".to_owned();
    }
    let malloc: Vec<&str> = current
        .unwrap_or_default()
        .split(':')
        .map(str::trim)
        .filter(|t| t.starts_with("glibc.malloc."))
        .collect();
    if malloc.is_empty() {
        let why = opt_out.map_or(String::new(), |v| format!(" ({OPT_OUT_VARIABLE}={v})"));
        format!("glibc malloc, its defaults{why}")
    } else {
        let set = malloc.join(", ");
        if set == STEADY_TUNABLES.replace(':', ", ") {
            format!("glibc malloc, heaps kept (set by grassbench: {set})")
        } else {
            format!("glibc malloc, GLIBC_TUNABLES: {set}")
        }
    }
}

/// [`describe`] for this process.
pub fn this_process() -> String {
    describe(
        TUNABLE,
        std::env::var("GLIBC_TUNABLES").ok().as_deref(),
        std::env::var(OPT_OUT_VARIABLE).ok().as_deref(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_process_without_malloc_tunables_starts_again_with_ours() {
        assert_eq!(
            tunables_to_set(None, None).as_deref(),
            Some(STEADY_TUNABLES)
        );
        assert_eq!(
            tunables_to_set(Some(""), Some("steady")).as_deref(),
            Some(STEADY_TUNABLES)
        );
        // Other tunables are kept, ours appended.
        assert_eq!(
            tunables_to_set(Some("glibc.rtld.nns=2"), None),
            Some(format!("glibc.rtld.nns=2:{STEADY_TUNABLES}"))
        );
    }

    #[test]
    fn ours_once_set_the_users_own_or_an_opt_out_end_the_restarts() {
        // After the restart: no second one.
        assert_eq!(tunables_to_set(Some(STEADY_TUNABLES), None), None);
        // The user's own malloc setting wins.
        assert_eq!(
            tunables_to_set(Some("glibc.malloc.arena_max=1"), None),
            None
        );
        assert_eq!(tunables_to_set(None, Some("system")), None);
        assert_eq!(tunables_to_set(None, Some(" System ")), None);
    }

    #[test]
    fn the_record_names_the_setting_in_effect() {
        assert_eq!(
            describe(true, Some(STEADY_TUNABLES), None),
            "glibc malloc, heaps kept (set by grassbench: glibc.malloc.trim_threshold=1073741824, \
             glibc.malloc.top_pad=67108864, glibc.malloc.mmap_threshold=33554432)"
        );
        assert_eq!(
            describe(
                true,
                Some("glibc.rtld.nns=2:glibc.malloc.arena_max=1"),
                None
            ),
            "glibc malloc, GLIBC_TUNABLES: glibc.malloc.arena_max=1"
        );
        assert_eq!(
            describe(true, None, Some("system")),
            "glibc malloc, its defaults (GRASSBENCH_ALLOCATOR=system)"
        );
        assert_eq!(describe(true, None, None), "glibc malloc, its defaults");
        assert_eq!(
            describe(false, Some(STEADY_TUNABLES), None),
            "the platform's default"
        );
    }
}
