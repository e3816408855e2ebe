//! F is modal: after the edits, which blocks need an F word of their own. The program is
//! followed in the order it runs (loops and calls included), with the F in effect after
//! each line; a block whose feed is not the one in effect gets an F word. A block that
//! runs several times needs one as soon as any of its runs would; since adding one can
//! only settle what follows, the pass repeats until nothing changes.

use std::collections::{HashMap, HashSet};

use super::{FeedValue, Plan, Program};
use crate::core::nc::words::{Fixed, LineWords};
use crate::core::nc::FeedMode;
use crate::core::toolpath::Units;

/// G codes that change how F is read (ten times their numbers).
const FEED_MODE_CODES: [(u32, FeedMode); 3] =
    [(930, FeedMode::InverseTime), (940, FeedMode::PerMinute), (950, FeedMode::PerRevolution)];
const INCH: u32 = 200;
const MM: u32 = 210;

/// What the tracker knows of a line.
struct Known {
    words: LineWords,
    has_f: bool,
}

/// The lines (1-based) that need an F word of their own after the edits of `plans`.
pub(crate) fn missing_feeds(
    text: &str,
    lines: &[(usize, usize, usize)],
    program: Program,
    plans: &HashMap<u32, Plan>,
) -> HashSet<u32> {
    let order: Vec<u32> = match &program.map.order {
        Some(order) => order.clone(),
        None => (1..=lines.len() as u32).filter(|&l| program.map.line(l).is_some()).collect(),
    };
    let mut known: HashMap<u32, Known> = HashMap::new();
    for &l in &order {
        known.entry(l).or_insert_with(|| {
            let (s, e, _) = lines[l as usize - 1];
            let words = LineWords::read(&text.as_bytes()[s..e]);
            let has_f = words.get(b'F').is_some();
            Known { words, has_f }
        });
    }
    let mut inserted = HashSet::new();
    loop {
        let mut changed = false;
        let mut in_effect: Option<FeedValue> = None;
        let (mut mode, mut units) = (FeedMode::PerMinute, Units::Mm);
        for &l in &order {
            let k = &known[&l];
            for (code, m) in FEED_MODE_CODES {
                if k.words.has_g(code) {
                    mode = m;
                    in_effect = None;
                }
            }
            if k.words.has_g(INCH) {
                units = Units::Inch;
            } else if k.words.has_g(MM) {
                units = Units::Mm;
            }
            match plans.get(&l) {
                Some(plan) => {
                    let own = k.has_f || matches!(plan, Plan::Split { .. }) || inserted.contains(&l);
                    if !own && !in_effect.is_some_and(|f| same(f, plan.first())) {
                        inserted.insert(l);
                        changed = true;
                    }
                    in_effect = Some(plan.last());
                }
                None => {
                    if let Some(f) = k.words.get(b'F') {
                        in_effect = f.value.is_finite().then(|| FeedValue { mode, units, value: exact(f.value) });
                    }
                }
            }
        }
        if !changed {
            return inserted;
        }
    }
}

/// Whether two F words run the same feed.
fn same(a: FeedValue, b: FeedValue) -> bool {
    a.mode == b.mode && a.units == b.units && (a.value.value() - b.value.value()).abs() < 1e-9
}

/// A value as written, exactly enough to compare with the editor's feeds.
fn exact(value: f64) -> Fixed {
    Fixed::round(value, 6)
}
