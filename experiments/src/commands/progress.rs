//! One progress bar for every long command (`run`, `sweep`, `compare`): position, total and an
//! estimate of the time left, drawn on stderr where it is a terminal and hidden elsewhere (CI
//! logs keep the commands' own one-line messages).

/// A bar over `total` steps counted in `unit` (frames, runs, steps), labelled `prefix`.
pub fn bar(total: u64, unit: &str, prefix: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(total);
    if let Ok(style) = indicatif::ProgressStyle::with_template(&format!(
        "{{prefix:>28}} [{{elapsed_precise}}] [{{bar:30}}] {{pos}}/{{len}} {unit}, ETA {{eta}} {{msg}}"
    )) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_prefix(prefix.to_owned());
    bar
}

#[cfg(test)]
mod tests {
    #[test]
    fn counts_and_labels() {
        let b = super::bar(7, "steps", "meadow");
        b.inc(3);
        assert_eq!((b.position(), b.length()), (3, Some(7)));
        assert_eq!(b.prefix(), "meadow");
    }
}
