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
    /// particular order), under the half-open rule of [`Segment::row_crossings`].
    pub fn row_crossings(&self, y: f64, mut emit: impl FnMut(f64)) {
        let row = Bounds { x_min: self.x_range.0, y_min: y, x_max: self.x_range.1, y_max: y };
        // (Also nothing for a NaN bound, or no segments.)
        if row.x_min.partial_cmp(&row.x_max).is_none_or(|o| o == std::cmp::Ordering::Greater) {
            return;
        }
        self.visit(&row, |i| self.segments[i].row_crossings(y, &mut emit));
    }

    /// A query of the distance to the nearest segment within `reach_mm`, fastest for
    /// points asked for row after row along x (as a raster is painted).
    pub fn nearest_within(&self, reach_mm: f64) -> NearestWithin<'_> {
        NearestWithin {
            index: self,
            reach_mm,
            row_y_bits: None,
            near: Vec::new(),
            next: 0,
            active: Vec::new(),
            last_x: 0.0,
        }
    }
}

/// Distances to the nearest segment of an index, up to a reach. The segments near the
/// row of the last point are gathered once and slid through in order of x, so a point
/// costs the segments within reach of it, not a search of the tree: on a contour with
/// tens of thousands of segments crossing every row, painting's band cells cost a few
/// segments each.
pub struct NearestWithin<'a> {
    index: &'a SegmentIndex,
    reach_mm: f64,
    /// The row gathered (the bits of its y), if any.
    row_y_bits: Option<u64>,
    /// The segments whose boxes reach the row's band, by the left edge of their box.
    near: Vec<(f64, usize)>,
    /// The first of `near` not yet entered.
    next: usize,
    /// Entered segments whose box may still reach the points ahead.
    active: Vec<usize>,
    /// The x of the last point of the row.
    last_x: f64,
}

impl NearestWithin<'_> {
    /// Distance from `q` to the nearest segment, or the reach when none is nearer.
    pub fn distance(&mut self, q: Point) -> f64 {
        let reach = self.reach_mm;
        // A point on another row, or back along this one, gathers its row afresh.
        if self.row_y_bits != Some(q.y.to_bits()) || q.x < self.last_x {
            self.gather_row(q.y);
        }
        self.last_x = q.x;
        let boxes = &self.index.boxes;
        while let Some(&(x_min, i)) = self.near.get(self.next) {
            if x_min > q.x + reach {
                break;
            }
            self.active.push(i);
            self.next += 1;
        }
        // A box wholly left of the reach stays so for every point ahead on the row.
        self.active.retain(|&i| boxes[i].x_max >= q.x - reach);
        // Segments outside the reach's box are farther than the reach: leaving them out
        // changes no minimum.
        self.active.iter().fold(reach, |nearest, &i| nearest.min(self.index.segments[i].distance_mm(q)))
    }

    fn gather_row(&mut self, y: f64) {
        let reach = self.reach_mm;
        let (index, near) = (self.index, &mut self.near);
        near.clear();
        let band = Bounds { x_min: index.x_range.0, y_min: y - reach, x_max: index.x_range.1, y_max: y + reach };
        index.visit(&band, |i| near.push((index.boxes[i].x_min, i)));
        near.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        self.next = 0;
        self.active.clear();
        self.row_y_bits = Some(y.to_bits());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::test_support::rounded_ring;

    #[test]
    fn the_nearest_segment_within_reach_is_found_as_among_all_segments_row_after_row() {
        let p = rounded_ring();
        let index = SegmentIndex::new(std::iter::once(&p.outer).chain(&p.islands), 0.0);
        let reach = 0.7;
        let mut nearest = index.nearest_within(reach);
        for j in 0..110 {
            for i in 0..130 {
                let (x, y) = (-10.0 + 0.4637 * f64::from(i), -10.0 + 0.4663 * f64::from(j));
                let q = Point::new(x, y);
                let every = p.outer.segments().chain(p.islands.iter().flat_map(Loop::segments));
                let exact = every.map(|s| s.distance_mm(q)).fold(f64::INFINITY, f64::min);
                let near = nearest.distance(q);
                assert!((near - exact.min(reach)).abs() < 1e-12, "({x}, {y}): {near} vs {exact}");
            }
        }
    }

    #[test]
    fn points_asked_in_any_order_get_the_same_distances() {
        let p = rounded_ring();
        let index = SegmentIndex::new(std::iter::once(&p.outer).chain(&p.islands), 0.0);
        let reach = 0.7;
        let (nx, ny) = (60, 50);
        let point = |k: usize| Point::new(-10.0 + 1.01 * (k % nx) as f64, -10.0 + 1.03 * (k / nx) as f64);
        let mut rows = index.nearest_within(reach);
        let along_rows: Vec<f64> = (0..nx * ny).map(|k| rows.distance(point(k))).collect();
        let mut columns = index.nearest_within(reach);
        let mut along_columns = vec![0.0; nx * ny];
        for i in 0..nx {
            for j in 0..ny {
                along_columns[j * nx + i] = columns.distance(point(j * nx + i));
            }
        }
        let mut backwards = index.nearest_within(reach);
        let mut from_the_end = vec![0.0; nx * ny];
        for k in (0..nx * ny).rev() {
            from_the_end[k] = backwards.distance(point(k));
        }
        assert_eq!(along_rows, along_columns);
        assert_eq!(along_rows, from_the_end);
    }
}
