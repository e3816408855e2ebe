//! The segments of one or more loops in a static bounding-box tree, so that a question
//! about a row or a point visits only the segments whose boxes reach it: painting a stock
//! raster or checking a loop then costs about its size, not cells × segments or
//! segments².

use super::{Bounds, Loop, Point, Segment};
use static_aabb2d_index::{StaticAABB2DIndex, StaticAABB2DIndexBuilder};

/// Segments and the tree of their boxes (none for no segments).
pub struct SegmentIndex {
    segments: Vec<Segment>,
    boxes: Vec<Bounds>,
    tree: Option<StaticAABB2DIndex<f64>>,
    /// The x extent of all the boxes, mm.
    x_range: (f64, f64),
}

impl SegmentIndex {
    /// The segments of `loops`, in order (loop after loop), each box widened by `margin_mm`.
    pub fn new<'a>(loops: impl IntoIterator<Item = &'a Loop>, margin_mm: f64) -> SegmentIndex {
        let segments: Vec<Segment> = loops.into_iter().flat_map(Loop::segments).collect();
        let boxes: Vec<Bounds> = segments
            .iter()
            .map(|s| {
                let b = s.bounds();
                Bounds {
                    x_min: b.x_min - margin_mm,
                    y_min: b.y_min - margin_mm,
                    x_max: b.x_max + margin_mm,
                    y_max: b.y_max + margin_mm,
                }
            })
            .collect();
        let mut builder = StaticAABB2DIndexBuilder::new(boxes.len());
        for b in &boxes {
            builder.add(b.x_min, b.y_min, b.x_max, b.y_max);
        }
        // Building fails only for a count other than the boxes added, or none.
        let tree = builder.build().ok();
        let x_range =
            boxes.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |r, b| (r.0.min(b.x_min), r.1.max(b.x_max)));
        SegmentIndex { segments, boxes, tree, x_range }
    }

    /// The segments, in the order given.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// The (widened) box of segment `i`.
    pub fn bounds(&self, i: usize) -> &Bounds {
        &self.boxes[i]
    }

    /// Calls `visit(i)` for every segment whose box meets the box `b`.
    pub fn visit(&self, b: &Bounds, mut visit: impl FnMut(usize)) {
        if let Some(tree) = &self.tree {
            tree.visit_query(b.x_min, b.y_min, b.x_max, b.y_max, &mut |i: usize| visit(i));
        }
    }

    /// Calls `emit(x)` for each crossing of the row at `y` with the segments (in no
    /// particular order), under the half-open rule of [`Segment::row_crossings`], from `x`
    /// on (crossings left of `x_from` may be left out).
    pub fn row_crossings_from(&self, x_from: f64, y: f64, mut emit: impl FnMut(f64)) {
        let row = Bounds { x_min: x_from.max(self.x_range.0), y_min: y, x_max: self.x_range.1, y_max: y };
        // (Also nothing for a NaN bound, or no segments.)
        if row.x_min.partial_cmp(&row.x_max).is_none_or(|o| o == std::cmp::Ordering::Greater) {
            return;
        }
        self.visit(&row, |i| self.segments[i].row_crossings(y, &mut emit));
    }

    /// `true` when `(x, y)` lies inside the loops by the even–odd rule (for a validated
    /// pocket: inside the outer loop and inside no island, as [`super::Pocket::contains`]).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let mut inside = false;
        self.row_crossings_from(x, y, |xc| {
            if xc > x {
                inside = !inside;
            }
        });
        inside
    }

    /// Distance from `q` to the nearest segment, or `reach_mm` when none is nearer.
    pub fn distance_within(&self, q: Point, reach_mm: f64) -> f64 {
        let around =
            Bounds { x_min: q.x - reach_mm, y_min: q.y - reach_mm, x_max: q.x + reach_mm, y_max: q.y + reach_mm };
        let mut nearest = reach_mm;
        self.visit(&around, |i| nearest = nearest.min(self.segments[i].distance_mm(q)));
        nearest
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::test_support::rounded_ring;

    #[test]
    fn the_index_answers_as_the_pocket_does_inside_and_near_the_boundary() {
        let p = rounded_ring();
        let index = SegmentIndex::new(std::iter::once(&p.outer).chain(&p.islands), 0.0);
        let reach = 0.7;
        for i in 0..130 {
            for j in 0..110 {
                let (x, y) = (-10.0 + 0.4637 * f64::from(i), -10.0 + 0.4663 * f64::from(j));
                assert_eq!(index.contains(x, y), p.contains(x, y), "({x}, {y})");
                let q = Point::new(x, y);
                let every = p.outer.segments().chain(p.islands.iter().flat_map(Loop::segments));
                let exact = every.map(|s| s.distance_mm(q)).fold(f64::INFINITY, f64::min);
                let near = index.distance_within(q, reach);
                assert!((near - exact.min(reach)).abs() < 1e-12, "({x}, {y}): {near} vs {exact}");
            }
        }
    }
}
