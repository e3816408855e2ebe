//! Feeds a machine cannot run: a control runs a feed above its maximum at the maximum
//! (the kinematic time does the same, MODEL.md §10), so the chip thickness and force of
//! such a move come from the maximum, not from the programmed word (an `F9991300` used
//! as a "fast feed" would otherwise give chips of hundreds of millimetres).

use crate::core::toolpath::{Motion, Toolpath};

/// `path` with every feed above `max_feed_mm_min` lowered to it, and a warning naming
/// how many moves and the first line, when there are any.
pub fn cap_feeds(mut path: Toolpath, max_feed_mm_min: f64) -> (Toolpath, Option<String>) {
    let (mut count, mut first) = (0usize, None);
    for m in path.moves.iter_mut().filter(|m| !matches!(m.motion, Motion::Rapid)) {
        if let Some(f) = m.feed_mm_min.filter(|f| *f > max_feed_mm_min) {
            count += 1;
            first.get_or_insert((m.line, f));
            m.feed_mm_min = Some(max_feed_mm_min);
        }
    }
    let warning = first.map(|(line, f)| {
        format!(
            "{count} feed move(s) program more than the machine's maximum feed of {max_feed_mm_min} mm/min (the first F{f} on line {line}): their chip thickness, force and wear are computed at the maximum, as the machine runs them"
        )
    });
    (path, warning)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::toolpath::{Move, Units, P3};

    #[test]
    fn feeds_above_the_machine_maximum_are_lowered_to_it_and_named() {
        let mv = |feed: f64, line: u32| Move {
            motion: Motion::Linear,
            start: P3::new(0.0, 0.0, 0.0),
            end: P3::new(1.0, 0.0, 0.0),
            feed_mm_min: Some(feed),
            spindle_rpm: Some(9600.0),
            tool: None,
            line,
        };
        let path = Toolpath {
            moves: vec![mv(1000.0, 3), mv(9_991_300.0, 4), mv(20_000.0, 5)],
            events: vec![],
            source_units: Units::Mm,
            warnings: vec![],
        };
        let (capped, warning) = cap_feeds(path.clone(), 15_000.0);
        let feeds: Vec<f64> = capped.moves.iter().filter_map(|m| m.feed_mm_min).collect();
        assert_eq!(feeds, vec![1000.0, 15_000.0, 15_000.0]);
        let warning = warning.expect("a warning");
        assert!(warning.contains("2 feed move(s)") && warning.contains("line 4"), "{warning}");
        assert!(cap_feeds(path, 1e7).1.is_none());
    }
}
