//! Slices that hold the same cells under the tool. A slice's material lies inside the
//! material of the slice below it (see [`super::slices`]), and over much of a layered
//! or relief program the two are still alike where the tool is: then the upper slice's
//! engagement is the lower one's, found without probing it. Rasters change only when a
//! chunk is applied, so an agreement found over a stretch ahead of the tool holds until
//! either raster changes.

use super::slices::SliceStock;
use super::stack::Stack;
use crate::core::stock::CellRect;

/// An agreement is checked this far ahead of the tool along its heading, cells.
const AHEAD_CELLS: f64 = 64.0;

/// What is known of one slice and the slice below it, while neither changes.
#[derive(Debug, Clone, Copy, Default)]
struct Pair {
    /// The rasters' versions this is known for.
    versions: (u64, u64),
    /// The cells are the same over this rectangle …
    same_over: Option<CellRect>,
    /// … and differ at this cell.
    differ_at: Option<(usize, usize)>,
}

/// For each slice but the last, what is known of it and the slice below.
pub struct SameBelow {
    pairs: Vec<Pair>,
}

impl SameBelow {
    pub fn new(slices: usize) -> SameBelow {
        SameBelow { pairs: vec![Pair::default(); slices.saturating_sub(1)] }
    }

    /// `true` when slice `k` and the slice below it hold the same cells wherever a probe
    /// of a tool of `radius_mm` at `center` reads; `heading`, the tool's unit direction,
    /// says where to look ahead.
    pub fn same(&mut self, slices: &Stack, k: usize, center: (f64, f64), heading: (f64, f64), radius_mm: f64) -> bool {
        if slices.alike_below(k) {
            // One stock for both.
            return true;
        }
        let (upper, lower) = (slices.raster(k), slices.raster(k + 1));
        let pair = &mut self.pairs[k];
        let versions = (upper.version(), lower.version());
        if pair.versions != versions {
            *pair = if both_took_one_capsule_since(pair.versions, slices.stock(k), slices.stock(k + 1)) {
                // Cells the same in both stay the same; cells that differed may not.
                Pair { versions, same_over: pair.same_over, differ_at: None }
            } else {
                Pair { versions, ..Pair::default() }
            };
        }
        let read = upper.cells_read_near(center, radius_mm, heading, 0.0);
        if pair.same_over.is_some_and(|r| r.contains(&read)) {
            return true;
        }
        if pair.differ_at.is_some_and(|c| read.holds(c)) {
            return false;
        }
        // The slices differed nearby: most often they still do, along the same row or
        // column (edges of earlier cuts run along the path), so those are looked at first.
        if let Some(c) = pair.differ_at.and_then(|c| upper.first_difference_across(lower, read, c)) {
            pair.differ_at = Some(c);
            return false;
        }
        // A stretch ahead alike spares the checks of the next samples; where a known
        // difference lies in it, it is not looked at. Only cells beyond those known alike
        // are compared.
        let ahead = upper.cells_read_near(center, radius_mm, heading, AHEAD_CELLS);
        if !pair.differ_at.is_some_and(|c| ahead.holds(c)) {
            match upper.first_difference_beyond(lower, ahead, pair.same_over) {
                None => {
                    pair.same_over = Some(ahead);
                    return true;
                }
                Some(c) => {
                    pair.differ_at = Some(c);
                    if read.holds(c) {
                        return false;
                    }
                }
            }
        }
        match upper.first_difference_beyond(lower, read, pair.same_over) {
            None => {
                pair.same_over = Some(read);
                true
            }
            Some(c) => {
                pair.differ_at = Some(c);
                false
            }
        }
    }
}

/// `true` when the only change to the pair of slices since their rasters had `versions`
/// is one capsule applied to both. A capsule sets each cell from that cell's value alone
/// (see [`crate::core::stock::Raster::clear_capsule_after`]), so cells the same in both
/// rasters before are the same after.
fn both_took_one_capsule_since(versions: (u64, u64), upper: &SliceStock, lower: &SliceStock) -> bool {
    match (upper.last_capsule(), lower.last_capsule()) {
        (Some(u), Some(l)) => u.serial == l.serial && (u.version_before, l.version_before) == versions,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::region::{paint, StockRegion};
    use crate::core::progress::NoProgress;
    use crate::core::stock::{CapsuleRows, Rect};

    const RADIUS: f64 = 2.0;

    /// Capsule number `serial` of radius RADIUS from `a` to `b`, applied to slice `s`.
    fn take(s: &mut SliceStock, serial: u64, a: (f64, f64), b: (f64, f64), disc_at_a_cleared: bool) -> bool {
        let mut rows = CapsuleRows::new(&s.raster, a, b, RADIUS, disc_at_a_cleared);
        s.take_capsule(serial, &mut rows)
    }

    /// Two slices, each with its own stock (so that their cells are compared).
    fn two_slices() -> Stack {
        let rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 40.0, y_max: 40.0 };
        let mut slices = Stack::build(&[0.0, -5.0, -10.0], rect, 0.1, |raster| {
            paint(raster, &[StockRegion::Rect(rect)], &[], &NoProgress)
        })
        .expect("nothing cancels the painting");
        slices.separate(0);
        slices
    }

    #[test]
    fn slices_cut_alike_are_the_same_under_the_tool() {
        let mut slices = two_slices();
        for k in 0..2 {
            slices.own(k).raster.clear_capsule((0.0, 20.0), (20.0, 20.0), RADIUS);
        }
        let mut same = SameBelow::new(slices.len());
        assert!(same.same(&slices, 0, (21.0, 20.0), (1.0, 0.0), RADIUS));
        // Further along, the agreement found ahead is reused.
        assert!(same.same(&slices, 0, (24.0, 20.0), (1.0, 0.0), RADIUS));
    }

    #[test]
    fn one_capsule_taken_by_both_slices_keeps_them_known_alike_and_any_other_change_does_not() {
        let mut slices = two_slices();
        let versions = (slices.raster(0).version(), slices.raster(1).version());
        for k in 0..2 {
            assert!(take(slices.own(k), 1, (0.0, 20.0), (20.0, 20.0), false));
        }
        assert!(both_took_one_capsule_since(versions, slices.stock(0), slices.stock(1)));
        // A second capsule since the versions, or one the upper slice alone took.
        for k in 0..2 {
            take(slices.own(k), 2, (20.0, 20.0), (25.0, 20.0), true);
        }
        assert!(!both_took_one_capsule_since(versions, slices.stock(0), slices.stock(1)));
        let versions = (slices.raster(0).version(), slices.raster(1).version());
        take(slices.own(0), 3, (25.0, 20.0), (30.0, 20.0), true);
        assert!(!both_took_one_capsule_since(versions, slices.stock(0), slices.stock(1)));
        // A raster changed other than by a capsule.
        let versions = (slices.raster(0).version(), slices.raster(1).version());
        for k in 0..2 {
            take(slices.own(k), 4, (30.0, 20.0), (35.0, 20.0), true);
        }
        slices.own(1).raster.clear_capsule((5.0, 5.0), (5.0, 5.0), RADIUS);
        assert!(!both_took_one_capsule_since(versions, slices.stock(0), slices.stock(1)));
    }

    #[test]
    fn what_is_kept_across_capsules_taken_by_both_slices_agrees_with_a_fresh_comparison() {
        let mut slices = two_slices();
        // The upper slice alone was cut along y = 14: the slices differ there.
        slices.own(0).raster.clear_capsule((0.0, 14.0), (40.0, 14.0), RADIUS);
        let mut kept = SameBelow::new(slices.len());
        let mut at = (2.0, 20.0);
        let mut answers = [false; 2];
        for step in 0..60u32 {
            let next = (at.0 + 0.6, 20.0 - 0.1 * f64::from(step));
            for k in 0..2 {
                take(slices.own(k), u64::from(step) + 1, at, next, step > 0);
            }
            at = next;
            let fresh = SameBelow::new(slices.len()).same(&slices, 0, at, (1.0, 0.0), RADIUS);
            assert_eq!(kept.same(&slices, 0, at, (1.0, 0.0), RADIUS), fresh, "at step {step}");
            answers[usize::from(fresh)] = true;
        }
        assert_eq!(answers, [true, true], "the path meets both alike and differing cells");
    }

    #[test]
    fn a_cut_in_the_upper_slice_alone_makes_them_differ_near_it_and_only_there() {
        let mut slices = two_slices();
        let mut same = SameBelow::new(slices.len());
        assert!(same.same(&slices, 0, (10.0, 10.0), (1.0, 0.0), RADIUS));
        slices.own(0).raster.clear_capsule((13.0, 10.0), (13.0, 10.0), RADIUS);
        // The upper raster changed: what was found ahead no longer counts.
        assert!(!same.same(&slices, 0, (10.0, 10.0), (1.0, 0.0), RADIUS));
        assert!(!same.same(&slices, 0, (10.1, 10.0), (1.0, 0.0), RADIUS));
        assert!(same.same(&slices, 0, (13.0, 30.0), (1.0, 0.0), RADIUS));
        assert!(same.same(&slices, 0, (5.0, 10.0), (-1.0, 0.0), RADIUS));
    }
}
