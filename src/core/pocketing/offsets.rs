//! The successive inward offsets of a pocket as a tree of connected regions, computed with
//! `cavalier_contours` shape offsets (lines and true arcs, islands, splitting).

use super::MAX_OFFSET_LEVELS;
use crate::core::geometry::{fmt_mm, Loop, Pocket, Point, Vertex};
use crate::core::CoreError;
use cavalier_contours::polyline::{PlineCreation, PlineSource, PlineSourceMut, Polyline};
use cavalier_contours::shape_algorithms::{Shape, ShapeOffsetOptions};

/// `cavalier_contours` takes arcs of at most a half circle (|bulge| ≤ 1): larger ones are
/// split in two.
const MAX_CAVALIER_BULGE: f64 = 1.0;

/// Offset loops enclosing less than this are slivers of the offset and dropped (mm²).
const MIN_OFFSET_AREA_MM2: f64 = 1e-6;

/// One connected region of one offset: a boundary and its holes.
#[derive(Debug, Clone)]
pub(super) struct Component {
    /// The boundary (counter-clockwise) followed by the holes (clockwise): the region lies on
    /// the left of every loop.
    pub loops: Vec<Loop>,
    /// The regions of the next offset that lie inside this one.
    pub children: Vec<usize>,
}

impl Component {
    /// `true` when `p` lies inside the boundary and inside none of the holes.
    pub fn contains(&self, p: Point) -> bool {
        let mut loops = self.loops.iter();
        loops.next().is_some_and(|outer| outer.contains(p.x, p.y)) && !loops.any(|hole| hole.contains(p.x, p.y))
    }
}

/// All offsets of a pocket: `components` indexed by the `roots` (the regions of the first
/// offset) and the `children` lists.
#[derive(Debug, Clone, Default)]
pub(super) struct OffsetTree {
    pub components: Vec<Component>,
    pub roots: Vec<usize>,
}

/// Offsets `pocket` by `first_mm` and then by `step_mm` more each time until nothing is left.
/// `roots` is empty when the first offset is. Each offset is taken from the pocket itself
/// (distance `first + k·step`), so errors do not build up from one loop to the next.
pub(super) fn offset_tree(pocket: &Pocket, first_mm: f64, step_mm: f64) -> Result<OffsetTree, CoreError> {
    let bounds = pocket.bounds();
    let largest_inradius_mm = 0.5 * bounds.width_mm().min(bounds.height_mm());
    let levels_bound = (largest_inradius_mm - first_mm) / step_mm;
    if levels_bound > MAX_OFFSET_LEVELS as f64 {
        return Err(CoreError::invalid(
            "radial_depth_mm",
            format!(
                "{} mm is too small for this pocket: it would take up to {levels_bound:.0} loops, at most {MAX_OFFSET_LEVELS}",
                fmt_mm(step_mm)
            ),
        ));
    }
    let shape = Shape::from_plines(std::iter::once(&pocket.outer).chain(&pocket.islands).map(to_polyline));
    let options = ShapeOffsetOptions::default();
    let mut tree = OffsetTree::default();
    let mut previous: Vec<usize> = Vec::new();
    for level in 0..=MAX_OFFSET_LEVELS {
        let distance_mm = first_mm + level as f64 * step_mm;
        let current = components_of(&shape.parallel_offset(distance_mm, &options))?;
        if current.is_empty() {
            return Ok(tree);
        }
        let mut indexes = Vec::with_capacity(current.len());
        for component in current {
            let index = tree.components.len();
            if level == 0 {
                tree.roots.push(index);
            } else {
                let parent = enclosing(&tree.components, &previous, &component.loops[0]).ok_or_else(|| {
                    CoreError::unsolvable(
                        "pocket",
                        format!("the offset by {} mm left a region outside the previous offset", fmt_mm(distance_mm)),
                    )
                })?;
                tree.components[parent].children.push(index);
            }
            tree.components.push(component);
            indexes.push(index);
        }
        previous = indexes;
    }
    Err(CoreError::invalid("radial_depth_mm", format!("the pocket needs more than {MAX_OFFSET_LEVELS} loops")))
}

/// The component among `candidates` that holds most of the points of `lp` (vertices and
/// segment midpoints); `None` when none holds any.
fn enclosing(components: &[Component], candidates: &[usize], lp: &Loop) -> Option<usize> {
    let points: Vec<Point> = lp.segments().flat_map(|s| [s.start, s.midpoint()]).collect();
    candidates
        .iter()
        .map(|&c| (c, points.iter().filter(|&&p| components[c].contains(p)).count()))
        .filter(|&(_, votes)| votes > 0)
        .max_by_key(|&(_, votes)| votes)
        .map(|(c, _)| c)
}

/// Groups the loops of an offset shape into connected regions: each counter-clockwise loop
/// with the clockwise loops inside it.
fn components_of(shape: &Shape<f64>) -> Result<Vec<Component>, CoreError> {
    let kept = |pline: &Polyline<f64>| pline.vertex_count() > 1 && pline.area().abs() >= MIN_OFFSET_AREA_MM2;
    let mut components: Vec<Component> = shape
        .ccw_plines
        .iter()
        .filter(|p| kept(&p.polyline))
        .map(|p| Component { loops: vec![to_loop(&p.polyline)], children: Vec::new() })
        .collect();
    let all: Vec<usize> = (0..components.len()).collect();
    for hole in shape.cw_plines.iter().filter(|p| kept(&p.polyline)) {
        let hole = to_loop(&hole.polyline);
        // Holes are disjoint, so the holes already placed do not change where this one goes.
        let owner = enclosing(&components, &all, &hole).ok_or_else(|| {
            CoreError::unsolvable("pocket", "an offset island lies outside every offset region".to_string())
        })?;
        components[owner].loops.push(hole);
    }
    Ok(components)
}

/// The area of `pocket` a tool centre kept `reach_mm` from every wall cannot sweep with a
/// disc of radius `reach_mm`, mm²: the pocket less its morphological opening (offset in by
/// `reach_mm`, then out by as much). Sharp concave corners, necks narrower than `2·reach_mm`
/// and concave arcs tighter than `reach_mm` are what it holds.
pub fn unreachable_area_mm2(pocket: &Pocket, reach_mm: f64) -> f64 {
    let shape = Shape::from_plines(std::iter::once(&pocket.outer).chain(&pocket.islands).map(to_polyline));
    let options = ShapeOffsetOptions::default();
    let opened = shape.parallel_offset(reach_mm, &options).parallel_offset(-reach_mm, &options);
    let signed: f64 = opened.ccw_plines.iter().chain(&opened.cw_plines).map(|p| p.polyline.area()).sum();
    (pocket.area() - signed).max(0.0)
}

/// The loop as a `cavalier_contours` closed polyline, arcs beyond a half circle split in two.
pub(super) fn to_polyline(lp: &Loop) -> Polyline<f64> {
    let mut pline = Polyline::with_capacity(lp.vertices.len(), true);
    for seg in lp.segments() {
        if seg.bulge.abs() > MAX_CAVALIER_BULGE {
            // tan(θ/8) from b = tan(θ/4): the half-angle formula.
            let half = seg.bulge / (1.0 + (1.0 + seg.bulge * seg.bulge).sqrt());
            let mid = seg.midpoint();
            pline.add(seg.start.x, seg.start.y, half);
            pline.add(mid.x, mid.y, half);
        } else {
            pline.add(seg.start.x, seg.start.y, seg.bulge);
        }
    }
    pline
}

/// The closed polyline as a loop.
pub(super) fn to_loop(pline: &Polyline<f64>) -> Loop {
    Loop::new(pline.iter_vertexes().map(|v| Vertex::new(v.x, v.y, v.bulge)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tolerance of offset coordinates (mm).
    const TOL_MM: f64 = 1e-9;

    #[test]
    fn arcs_beyond_a_half_circle_are_split_into_two_equal_halves() {
        // Three quarters of a circle of radius 1 about the origin, closed by a chord.
        let b = (3.0 * std::f64::consts::FRAC_PI_2 / 4.0).tan();
        let lp = Loop::new(vec![Vertex::new(1.0, 0.0, b), Vertex::new(0.0, -1.0, 0.0)]);
        let pline = to_polyline(&lp);
        assert_eq!(pline.vertex_count(), 3);
        let back = to_loop(&pline);
        assert!((back.signed_area() - lp.signed_area()).abs() < TOL_MM);
        let mid = back.vertices[1];
        assert!((mid.x + 2f64.sqrt() / 2.0).abs() < TOL_MM && (mid.y - 2f64.sqrt() / 2.0).abs() < TOL_MM, "{mid:?}");
    }

    #[test]
    fn a_rectangle_shrinks_into_nested_rectangles_of_one_branch() {
        let pocket = Pocket::new(Loop::rectangle(0.0, 0.0, 60.0, 40.0), vec![]).unwrap();
        let tree = offset_tree(&pocket, 5.0, 2.0).unwrap();
        // Half the height less the first offset: (20 − 5) / 2 → offsets 5, 7, …, 19.
        assert_eq!(tree.components.len(), 8);
        assert_eq!(tree.roots, vec![0]);
        for (k, c) in tree.components.iter().enumerate() {
            assert_eq!(c.loops.len(), 1);
            assert!(c.loops[0].is_ccw());
            let expected: Vec<usize> = if k + 1 < 8 { vec![k + 1] } else { vec![] };
            assert_eq!(c.children, expected);
        }
        let first = tree.components[0].loops[0].bounds();
        assert!((first.x_min - 5.0).abs() < TOL_MM && (first.x_max - 55.0).abs() < TOL_MM);
        assert!((first.y_min - 5.0).abs() < TOL_MM && (first.y_max - 35.0).abs() < TOL_MM);
    }
}
