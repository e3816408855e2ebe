//! Feeds per NC block (issue: "each block gets one feed"): a move whose required feed
//! changes inside it is split where it changes, pieces shorter than a minimum block
//! length are merged, feeds are rounded down to a step, and equal neighbours are merged.
//! A piece's feed is the lowest required feed inside it, so a block never runs faster
//! than any of its samples allows.

use serde::{Deserialize, Serialize};

/// Pieces shorter than this are merged with a neighbour by default, mm (assumed: long
/// enough that a control runs each block at its feed; short enough to follow a corner).
pub const DEFAULT_MIN_BLOCK_MM: f64 = 1.0;
/// A piece is split when its required feed varies by more than this fraction.
pub const DEFAULT_FEED_TOLERANCE: f64 = 0.01;
/// Feeds are rounded down to a multiple of this by default, mm/min.
pub const DEFAULT_FEED_STEP_MM_MIN: f64 = 1.0;
/// Slack when rounding a feed that is already a multiple of the step.
const ROUNDING_SLACK: f64 = 1e-9;

/// How moves are cut into blocks.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BlockOptions {
    /// Shortest piece a move is split into, mm.
    pub min_block_mm: f64,
    /// Relative variation of the required feed inside one piece before it is split.
    pub tolerance: f64,
    /// Feeds are rounded down to a multiple of this, mm/min.
    pub feed_step_mm_min: f64,
}

impl Default for BlockOptions {
    fn default() -> Self {
        BlockOptions {
            min_block_mm: DEFAULT_MIN_BLOCK_MM,
            tolerance: DEFAULT_FEED_TOLERANCE,
            feed_step_mm_min: DEFAULT_FEED_STEP_MM_MIN,
        }
    }
}

/// A piece of a move, between fractions `t0` and `t1` of its length, with its feed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    pub t0: f64,
    pub t1: f64,
    pub feed_mm_min: f64,
}

/// `feed` rounded down to the step, but not below `min_feed_mm_min`.
pub fn round_feed(feed_mm_min: f64, min_feed_mm_min: f64, step_mm_min: f64) -> f64 {
    let rounded = if step_mm_min > 0.0 {
        (feed_mm_min / step_mm_min + ROUNDING_SLACK).floor() * step_mm_min
    } else {
        feed_mm_min
    };
    rounded.max(min_feed_mm_min).min(feed_mm_min.max(min_feed_mm_min))
}

/// Splits a move of `length_mm` whose required feeds are `feeds` at equally spaced
/// fractions `k / (feeds.len() − 1)` of its length (`feeds[0]` at its start).
pub fn split_feeds(length_mm: f64, feeds: &[f64], min_feed_mm_min: f64, options: &BlockOptions) -> Vec<Piece> {
    let round = |f: f64| round_feed(f, min_feed_mm_min, options.feed_step_mm_min);
    let intervals = feeds.len().saturating_sub(1);
    if intervals == 0 {
        let f = feeds.first().copied().unwrap_or(min_feed_mm_min);
        return vec![Piece { t0: 0.0, t1: 1.0, feed_mm_min: round(f) }];
    }
    // The feed over an interval is the lower of its ends.
    let lows: Vec<f64> = feeds.windows(2).map(|w| w[0].min(w[1])).collect();
    let interval_mm = length_mm / intervals as f64;
    let at = |i: usize| i as f64 / intervals as f64;
    let mut raw: Vec<(usize, usize, f64)> = Vec::new();
    let (mut first, mut lo, mut hi) = (0, lows[0], lows[0]);
    for (i, &c) in lows.iter().enumerate().skip(1) {
        let (new_lo, new_hi) = (lo.min(c), hi.max(c));
        let long_enough = (i - first) as f64 * interval_mm >= options.min_block_mm;
        if new_hi > new_lo * (1.0 + options.tolerance) && long_enough {
            raw.push((first, i, lo));
            (first, lo, hi) = (i, c, c);
        } else {
            (lo, hi) = (new_lo, new_hi);
        }
    }
    raw.push((first, intervals, lo));
    // A short last piece takes intervals from the one before it (whose feed is then
    // the lowest of what it keeps), or joins it when that one would be too short.
    let min_intervals = (options.min_block_mm / interval_mm).ceil() as usize;
    if raw.len() > 1 && raw[raw.len() - 1].1 - raw[raw.len() - 1].0 < min_intervals {
        let last = raw.pop().expect("two pieces");
        let prev = raw.pop().expect("one piece");
        let boundary = intervals.saturating_sub(min_intervals);
        if boundary >= prev.0 + min_intervals {
            let low = |a: usize, b: usize| lows[a..b].iter().copied().fold(f64::INFINITY, f64::min);
            raw.push((prev.0, boundary, low(prev.0, boundary)));
            raw.push((boundary, last.1, low(boundary, last.1)));
        } else {
            raw.push((prev.0, last.1, prev.2.min(last.2)));
        }
    }
    let mut pieces: Vec<Piece> = Vec::with_capacity(raw.len());
    for (a, b, f) in raw {
        let feed = round(f);
        match pieces.last_mut() {
            Some(p) if (p.feed_mm_min - feed).abs() <= f64::EPSILON * feed.abs().max(1.0) => p.t1 = at(b),
            _ => pieces.push(Piece { t0: at(a), t1: at(b), feed_mm_min: feed }),
        }
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn options(min_block_mm: f64) -> BlockOptions {
        BlockOptions { min_block_mm, tolerance: 0.01, feed_step_mm_min: 10.0 }
    }

    #[test]
    fn a_constant_feed_is_one_block() {
        let pieces = split_feeds(20.0, &[1234.0; 101], 100.0, &options(1.0));
        assert_eq!(pieces, vec![Piece { t0: 0.0, t1: 1.0, feed_mm_min: 1230.0 }]);
    }

    #[test]
    fn a_move_is_split_where_its_feed_steps_down_and_back_up() {
        // 10 mm at 0.1 mm: 5760 until 4 mm, 1160 until 6 mm, 5760 after.
        let feeds: Vec<f64> = (0..=100).map(|k| if (40..=60).contains(&k) { 1160.0 } else { 5760.0 }).collect();
        let pieces = split_feeds(10.0, &feeds, 100.0, &options(0.5));
        let feeds: Vec<f64> = pieces.iter().map(|p| p.feed_mm_min).collect();
        assert_eq!(feeds, vec![5760.0, 1160.0, 5760.0]);
        // The slow block covers every slow sample (the interval ends are conservative).
        assert!(pieces[1].t0 <= 0.4 + 1e-12 && pieces[1].t1 >= 0.6 - 1e-12, "{pieces:?}");
    }

    #[test]
    fn pieces_shorter_than_the_minimum_block_are_merged_at_the_lower_feed() {
        let feeds: Vec<f64> = (0..=100).map(|k| if k == 50 { 500.0 } else { 5000.0 }).collect();
        let pieces = split_feeds(2.0, &feeds, 100.0, &options(5.0));
        assert_eq!(pieces, vec![Piece { t0: 0.0, t1: 1.0, feed_mm_min: 500.0 }]);
    }

    #[test]
    fn a_slow_end_takes_a_minimum_block_from_the_piece_before_it() {
        // 10 mm at 0.1 mm, slow only at the very end.
        let feeds: Vec<f64> = (0..=100).map(|k| if k == 100 { 300.0 } else { 5000.0 }).collect();
        let pieces = split_feeds(10.0, &feeds, 100.0, &options(1.0));
        assert_eq!(pieces.len(), 2, "{pieces:?}");
        assert!((pieces[0].feed_mm_min - 5000.0).abs() < 1e-9 && (pieces[1].feed_mm_min - 300.0).abs() < 1e-9);
        assert!((pieces[1].t0 - 0.9).abs() < 1e-9, "{pieces:?}");
    }

    #[test]
    fn feeds_are_rounded_down_to_the_step_but_not_below_the_minimum() {
        assert!((round_feed(2347.9, 100.0, 10.0) - 2340.0).abs() < 1e-9);
        assert!((round_feed(2340.0, 100.0, 10.0) - 2340.0).abs() < 1e-9);
        assert!((round_feed(31.7, 28.8, 10.0) - 30.0).abs() < 1e-9);
        assert!((round_feed(28.9, 28.8, 10.0) - 28.8).abs() < 1e-9);
    }

    proptest! {
        #[test]
        fn pieces_cover_the_move_and_never_run_faster_than_a_sample_inside(
            feeds in proptest::collection::vec(50.0f64..10_000.0, 1..300),
            length in 0.1f64..50.0,
            min_block in 0.0f64..5.0,
        ) {
            let pieces = split_feeds(length, &feeds, 20.0, &options(min_block));
            prop_assert!((pieces[0].t0).abs() < 1e-12);
            prop_assert!((pieces[pieces.len() - 1].t1 - 1.0).abs() < 1e-12);
            let n = (feeds.len() - 1).max(1) as f64;
            for w in pieces.windows(2) {
                prop_assert!((w[0].t1 - w[1].t0).abs() < 1e-12);
            }
            for p in &pieces {
                prop_assert!(p.t1 > p.t0);
                for (k, f) in feeds.iter().enumerate() {
                    let t = k as f64 / n;
                    if t > p.t0 - 1e-12 && t < p.t1 + 1e-12 {
                        prop_assert!(p.feed_mm_min <= f.max(20.0) + 1e-9, "{p:?} above sample {k} = {f}");
                    }
                }
            }
        }
    }
}
