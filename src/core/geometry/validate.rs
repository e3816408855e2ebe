//! Validation of loops: enough vertices, finite numbers, no zero-length segment, no
//! self-intersection, a real area; and the contact test between two loops.

use super::contour::Loop;
use super::point::{Bounds, Point};
use super::segment::{Segment, STRAIGHT_BULGE};
use super::segment_index::SegmentIndex;
use super::{fmt_point, MIN_LOOP_AREA_MM2, MIN_SEGMENT_LENGTH_MM, POINT_EPS_MM};
use crate::core::error::CoreError;

/// Checks that `lp` is a simple closed contour; errors name vertex i `{field}[i]` (the
/// loop's JSON array of vertices is `field`), or `field` for the loop as a whole.
///
/// At least 2 vertices (2 only with a bulge), finite coordinates and bulges, no segment
/// shorter than [`MIN_SEGMENT_LENGTH_MM`], no two segments meeting other than adjacent ones
/// at their shared vertex (adjacent ones must not overlap or fold back), and an area of at
/// least [`MIN_LOOP_AREA_MM2`].
pub fn validate_loop(lp: &Loop, field: &str) -> Result<(), CoreError> {
    let n = lp.vertices.len();
    let at = |i: usize| format!("{field}[{i}]");
    if n < 2 {
        return Err(CoreError::invalid(field.to_string(), format!("a loop needs at least 2 vertices, got {n}")));
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
                    "segment {i} from vertex {i} to vertex {} has zero length ({chord:e} mm < {MIN_SEGMENT_LENGTH_MM:e} mm)",
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
                "the loop intersects itself: segment {i} (vertex {i} → vertex {}) and segment {j} (vertex {j} → vertex {}) {how} at {}",
                (i + 1) % n,
                (j + 1) % n,
                fmt_point(point)
            ),
        ));
    }
    let area = lp.signed_area();
    if area.abs() < MIN_LOOP_AREA_MM2 {
        return Err(CoreError::invalid(field.to_string(), format!("the loop encloses no area ({area:e} mm²)")));
    }
    Ok(())
}

/// The first pair `(i, j)`, `i < j`, of segments of `lp` that meet where they should not,
/// with the meeting point and whether they overlap. Only pairs whose boxes come within
/// [`POINT_EPS_MM`] are tested, found through a tree of the boxes.
pub fn first_self_intersection(lp: &Loop) -> Option<(usize, usize, Point, bool)> {
    let n = lp.vertices.len();
    // Boxes widened by the margin on each side meet whenever the boxes come within it.
    let index = SegmentIndex::new(std::iter::once(lp), POINT_EPS_MM);
    let segs = index.segments();
    let boxes: Vec<Bounds> = segs.iter().map(Segment::bounds).collect();
    let mut worst: Option<(usize, usize, Point, bool)> = None;
    for i in 0..segs.len() {
        if worst.is_some() {
            // Pairs are visited by their first segment: none later comes first.
            break;
        }
        index.visit(index.bounds(i), |j| {
            if j <= i || !boxes[i].overlaps(&boxes[j], POINT_EPS_MM) {
                return;
            }
            if worst.is_some_and(|(_, wj, _, _)| wj <= j) {
                return;
            }
            if let Some((point, overlap)) = pair_problem(n, i, j, &segs[i], &segs[j]) {
                worst = Some((i, j, point, overlap));
            }
        });
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
    // Boxes of b widened by the margin meet a's box whenever they come within it.
    let index = SegmentIndex::new(std::iter::once(b), POINT_EPS_MM);
    let b_segs = index.segments();
    for (i, sa) in a.segments().enumerate() {
        let box_a = sa.bounds();
        // The first segment of b (in order) that a's segment meets.
        let mut first: Option<(usize, Point)> = None;
        index.visit(&box_a, |j| {
            if first.is_some_and(|(k, _)| k <= j) || !box_a.overlaps(&b_segs[j].bounds(), POINT_EPS_MM) {
                return;
            }
            if let Some(h) = sa.intersections(&b_segs[j]).points.first() {
                first = Some((j, h.point));
            }
        });
        if let Some((j, point)) = first {
            return Some((i, j, point));
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

    /// A comb of `teeth` teeth 99 mm long and 0.5 mm wide, 0.5 mm apart (4 vertices a tooth):
    /// every long edge spans the same x range.
    fn comb(teeth: usize) -> Vec<(f64, f64, f64)> {
        let mut v = Vec::with_capacity(4 * teeth + 2);
        for k in 0..teeth {
            let y = k as f64;
            v.extend([(100.0, y, 0.0), (100.0, y + 0.5, 0.0), (1.0, y + 0.5, 0.0), (1.0, y + 1.0, 0.0)]);
        }
        v.extend([(0.0, teeth as f64, 0.0), (0.0, 0.0, 0.0)]);
        v
    }

    #[test]
    fn a_comb_of_forty_thousand_vertices_is_checked_and_a_crossing_in_it_is_found() {
        let mut points = comb(10_000);
        assert!(lp(&points).validate("outer").is_ok());
        // Tooth 7 000's tip rises through the next tooth's lower edge.
        points[4 * 7_000 + 1].1 += 1.2;
        let (field, reason) = field_and_reason(lp(&points).validate("outer").unwrap_err());
        assert_eq!(field, "outer[28000]");
        assert!(reason.contains("segment 28000 "), "{reason}");
    }

    #[test]
    fn a_bow_tie_is_refused_naming_the_two_crossing_segments_and_the_point() {
        let bow = lp(&[(0.0, 0.0, 0.0), (10.0, 10.0, 0.0), (10.0, 0.0, 0.0), (0.0, 10.0, 0.0)]);
        let (field, reason) = field_and_reason(bow.validate("outer").unwrap_err());
        assert_eq!(field, "outer[0]");
        assert!(reason.contains("segment 0 (vertex 0 → vertex 1)"), "{reason}");
        assert!(reason.contains("segment 2 (vertex 2 → vertex 3)"), "{reason}");
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
        assert_eq!(field, "islands[1]");
        let two_lines = lp(&[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)]);
        let (field, reason) = field_and_reason(two_lines.validate("outer").unwrap_err());
        assert_eq!(field, "outer[0]");
        assert!(reason.contains("bulge"), "{reason}");
        let nan = lp(&[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, f64::NAN, 0.0)]);
        assert_eq!(field_and_reason(nan.validate("outer").unwrap_err()).0, "outer[2]");
        let dup = lp(&[(0.0, 0.0, 0.0), (5.0, 0.0, 0.0), (5.0, 0.0, 0.0), (0.0, 5.0, 0.0)]);
        let (field, reason) = field_and_reason(dup.validate("islands[0]").unwrap_err());
        assert_eq!(field, "islands[0][1]");
        assert!(reason.contains("zero length"), "{reason}");
    }

    #[test]
    fn an_edge_folding_back_onto_the_previous_one_is_refused_as_an_overlap() {
        let spike = lp(&[(0.0, 0.0, 0.0), (10.0, 0.0, 0.0), (5.0, 0.0, 0.0), (5.0, 5.0, 0.0)]);
        let (field, reason) = field_and_reason(spike.validate("outer").unwrap_err());
        assert_eq!(field, "outer[0]");
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
