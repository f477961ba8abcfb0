//! Instance ranges merged into as few draws as possible.

use std::ops::Range;

/// Appends `r` to `ranges`, extending the last range instead when `r` starts where it ends;
/// empty ranges are skipped. Techniques that draw many pieces of one instance buffer (cells,
/// grids) build their draw lists with it, so pieces that meet cost one draw.
pub fn push_merged(ranges: &mut Vec<Range<u32>>, r: Range<u32>) {
    if r.is_empty() {
        return;
    }
    match ranges.last_mut() {
        Some(last) if last.end == r.start => last.end = r.end,
        _ => ranges.push(r),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn touching_ranges_merge_and_gaps_stay() {
        let mut v = Vec::new();
        for r in [0..3, 3..5, 5..5, 7..9, 9..10, 12..12] {
            push_merged(&mut v, r);
        }
        assert_eq!(v, vec![0..5, 7..10]);
    }
}
