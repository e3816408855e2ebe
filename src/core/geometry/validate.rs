//! Validation of loops: enough vertices, finite numbers, no zero-length segment, no
//! self-intersection, a real area; and the contact test between two loops.

use super::contour::Loop;
use super::point::{Bounds, Point};
use super::segment::{Segment, STRAIGHT_BULGE};
use super::{fmt_point, MIN_LOOP_AREA_MM2, MIN_SEGMENT_LENGTH_MM, POINT_EPS_MM};
use crate::core::error::CoreError;

/// Checks that `lp` is a simple closed contour; errors name `{field}.vertices[i]`.
///
/// At least 2 vertices (2 only with a bulge), finite coordinates and bulges, no segment
/// shorter than [`MIN_SEGMENT_LENGTH_MM`], no two segments meeting other than adjacent ones
/// at their shared vertex (adjacent ones must not overlap or fold back), and an area of at
/// least [`MIN_LOOP_AREA_MM2`].
pub fn validate_loop(lp: &Loop, field: &str) -> Result<(), CoreError> {
    let n = lp.vertices.len();
    let at = |i: usize| format!("{field}.vertices[{i}]");
    if n < 2 {
        return Err(CoreError::invalid(
            format!("{field}.vertices"),
            format!("a loop needs at least 2 vertices, got {n}"),
        ));
    }
    for (i, v) in lp.vertices.iter().enumerate() {
        if !(v.x.is_finite() && v.y.is_finite() && v.bulge.is_finite()) {
            return Err(CoreError::invalid(
                at(i),
                format!("x, y and bulge must be finite, got ({}, {}, {})", v.x, v.y, v.bulge),
            ));
        }
    }
    if n == 2 && lp.vertices.iter().all(|v| v.bulge.abs() <= STRAIGHT_BULGE) {
        return Err(CoreError::invalid(
            at(0),
            "a loop of 2 vertices encloses no area unless a bulge makes one of its segments an arc",
        ));
    }
    for (i, seg) in lp.segments().enumerate() {
        let chord = seg.chord_mm();
        if chord < MIN_SEGMENT_LENGTH_MM {
            return Err(CoreError::invalid(
                at(i),
                format!(
                    "segment {i} from vertices[{i}] to vertices[{}] has zero length ({chord:e} mm < {MIN_SEGMENT_LENGTH_MM:e} mm)",
                    (i + 1) % n
                ),
            ));
        }
    }
    if let Some((i, j, point, overlap)) = first_self_intersection(lp) {
        let how = if overlap { "overlap" } else { "intersect" };
        return Err(CoreError::invalid(
            at(i),
            format!(
                "the loop intersects itself: segment {i} (vertices[{i}] → vertices[{}]) and segment {j} (vertices[{j}] → vertices[{}]) {how} at {}",
                (i + 1) % n,
                (j + 1) % n,
                fmt_point(point)
            ),
        ));
    }
    let area = lp.signed_area();
    if area.abs() < MIN_LOOP_AREA_MM2 {
        return Err(CoreError::invalid(
            format!("{field}.vertices"),
            format!("the loop encloses no area ({area:e} mm²)"),
        ));
    }
    Ok(())
}

/// The first pair `(i, j)`, `i < j`, of segments of `lp` that meet where they should not,
/// with the meeting point and whether they overlap. Pairs whose boxes are apart are skipped
/// (sweep over the boxes sorted by `x_min`).
pub fn first_self_intersection(lp: &Loop) -> Option<(usize, usize, Point, bool)> {
    let n = lp.vertices.len();
    let segs: Vec<Segment> = lp.segments().collect();
    let boxes: Vec<Bounds> = segs.iter().map(Segment::bounds).collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_unstable_by(|&a, &b| boxes[a].x_min.total_cmp(&boxes[b].x_min));
    let mut worst: Option<(usize, usize, Point, bool)> = None;
    for (k, &a) in order.iter().enumerate() {
        for &b in &order[k + 1..] {
            if boxes[b].x_min > boxes[a].x_max + POINT_EPS_MM {
                break;
            }
            if !boxes[a].overlaps(&boxes[b], POINT_EPS_MM) {
                continue;
            }
            let (i, j) = (a.min(b), a.max(b));
            if worst.is_some_and(|(wi, wj, _, _)| (wi, wj) <= (i, j)) {
                continue;
            }
            if let Some((point, overlap)) = pair_problem(n, i, j, &segs[i], &segs[j]) {
                worst = Some((i, j, point, overlap));
            }
        }
    }
    worst
}

/// Where segments `i < j` of an `n`-loop meet illegally: anywhere for non-adjacent ones,
/// anywhere but their shared vertex for adjacent ones.
fn pair_problem(n: usize, i: usize, j: usize, a: &Segment, b: &Segment) -> Option<(Point, bool)> {
    let hits = a.intersections(b);
    if hits.overlap {
        return Some((hits.points.first().map_or(a.end, |h| h.point), true));
    }
    let mut shared: [Option<Point>; 2] = [None, None];
    if j == i + 1 {
        shared[0] = Some(a.end);
    }
    if i == 0 && j == n - 1 {
        shared[1] = Some(a.start);
    }
    hits.points
        .iter()
        .find(|h| shared.iter().flatten().all(|v| !h.point.near(*v, MIN_SEGMENT_LENGTH_MM)))
        .map(|h| (h.point, false))
}

/// The first segments `(i of a, j of b)` of two loops that meet (cross, touch or overlap),
/// with a meeting point.
pub fn first_contact(a: &Loop, b: &Loop) -> Option<(usize, usize, Point)> {
    if !a.bounds().overlaps(&b.bounds(), POINT_EPS_MM) {
        return None;
    }
    let b_segs: Vec<(Segment, Bounds)> = b.segments().map(|s| (s, s.bounds())).collect();
    for (i, sa) in a.segments().enumerate() {
        let box_a = sa.bounds();
        for (j, (sb, box_b)) in b_segs.iter().enumerate() {
            if !box_a.overlaps(box_b, POINT_EPS_MM) {
                continue;
            }
            let hits = sa.intersections(sb);
            if let Some(h) = hits.points.first() {
                return Some((i, j, h.point));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::Vertex;

    fn field_and_reason(err: CoreError) -> (String, String) {
        match err {
            CoreError::InvalidInput { field, reason } => (field, reason),
            other => panic!("unexpected error {other:?}"),
        }
    }

    fn lp(points: &[(f64, f64, f64)]) -> Loop {
        Loop::new(points.iter().map(|&(x, y, b)| Vertex::new(x, y, b)).collect())
    }

    #[test]
    fn a_bow_tie_is_refused_naming_the_two_crossing_segments_and_the_point() {
        let bow = lp(&[(0.0, 0.0, 0.0), (10.0, 10.0, 0.0), (10.0, 0.0, 0.0), (0.0, 10.0, 0.0)]);
        let (field, reason) = field_and_reason(bow.validate("outer").unwrap_err());
        assert_eq!(field, "outer.vertices[0]");
        assert!(reason.contains("segment 0 (vertices[0] → vertices[1])"), "{reason}");
        assert!(reason.contains("segment 2 (vertices[2] → vertices[3])"), "{reason}");
        assert!(reason.contains("at (5, 5)"), "{reason}");
    }

    #[test]
    fn simple_loops_with_tangent_arcs_and_two_vertex_circles_are_accepted() {
        Loop::circle(0.0, 0.0, 5.0).validate("outer").unwrap();
        Loop::rectangle(0.0, 0.0, 3.0, 2.0).validate("outer").unwrap();
        let slot = lp(&[(0.0, 0.0, 0.0), (10.0, 0.0, 1.0), (10.0, 4.0, 0.0), (0.0, 4.0, 1.0)]);
        slot.validate("outer").unwrap();
        let crescent = lp(&[(0.0, 0.0, 1.0), (10.0, 0.0, -0.5)]);
        crescent.validate("outer").unwrap();
    }

    #[test]
    fn too_few_vertices_non_finite_values_and_zero_length_segments_are_refused() {
        let (field, _) = field_and_reason(lp(&[(0.0, 0.0, 0.0)]).validate("islands[1]").unwrap_err());
        assert_eq!(field, "islands[1].vertices");
        let two_lines = lp(&[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)]);
        let (field, reason) = field_and_reason(two_lines.validate("outer").unwrap_err());
        assert_eq!(field, "outer.vertices[0]");
        assert!(reason.contains("bulge"), "{reason}");
        let nan = lp(&[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, f64::NAN, 0.0)]);
        assert_eq!(field_and_reason(nan.validate("outer").unwrap_err()).0, "outer.vertices[2]");
        let dup = lp(&[(0.0, 0.0, 0.0), (5.0, 0.0, 0.0), (5.0, 0.0, 0.0), (0.0, 5.0, 0.0)]);
        let (field, reason) = field_and_reason(dup.validate("islands[0]").unwrap_err());
        assert_eq!(field, "islands[0].vertices[1]");
        assert!(reason.contains("zero length"), "{reason}");
    }

    #[test]
    fn an_edge_folding_back_onto_the_previous_one_is_refused_as_an_overlap() {
        let spike = lp(&[(0.0, 0.0, 0.0), (10.0, 0.0, 0.0), (5.0, 0.0, 0.0), (5.0, 5.0, 0.0)]);
        let (field, reason) = field_and_reason(spike.validate("outer").unwrap_err());
        assert_eq!(field, "outer.vertices[0]");
        assert!(reason.contains("overlap"), "{reason}");
    }

    #[test]
    fn an_arc_curling_back_across_its_neighbour_is_refused() {
        // The big clockwise arc from (10,0) to (10,5) swings below y = 0 across the bottom edge.
        let curl = lp(&[(0.0, 0.0, 0.0), (10.0, 0.0, -3.0), (10.0, 5.0, 0.0), (0.0, 5.0, 0.0)]);
        let (_, reason) = field_and_reason(curl.validate("outer").unwrap_err());
        assert!(reason.contains("intersect"), "{reason}");
    }

    #[test]
    fn a_figure_eight_touching_itself_at_one_vertex_is_refused() {
        let eight = lp(&[
            (0.0, 0.0, 0.0),
            (5.0, 5.0, 0.0),
            (10.0, 0.0, 0.0),
            (10.0, 10.0, 0.0),
            (5.0, 5.0, 0.0),
            (0.0, 10.0, 0.0),
        ]);
        let (_, reason) = field_and_reason(eight.validate("outer").unwrap_err());
        assert!(reason.contains("(5, 5)"), "{reason}");
    }
}
