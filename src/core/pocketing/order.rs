//! The cutting order of the offset loops: each branch of the offset tree from its innermost
//! loop outwards, a region after all the branches inside it, the loops linked by straight
//! feed moves where these stay inside the region and entered from above where not.

use super::corners::{with_corner_loops, LoopedRing};
use super::emit::{PathWriter, MIN_MOVE_MM};
use super::offsets::{Component, OffsetTree};
use super::seam::{advance, nearest_on_loop, starting_at, Nearest};
use super::PocketingSpec;
use crate::core::geometry::{Loop, Point, Segment};
use crate::core::toolpath::Toolpath;

/// A link joins the next loop this many tool radii ahead of the point nearest to the tool
/// (the first that gives a link inside the region), so that it enters the new step-over at a
/// shallow angle (`atan(Rd / (k·r))`: under 6° for Rd ≤ r/10 and k ≥ 1) instead of straight
/// across it (MODEL.md §2: a sideways step of Rd engages the tool far more than a pass at Rd).
pub const LINK_ADVANCE_RADII: [f64; 5] = [2.0, 1.5, 1.0, 0.5, 0.25];

/// A link may touch the region's boundary this close to its ends (mm): that is where it
/// leaves one loop and reaches the next.
const LINK_END_TOL_MM: f64 = 1e-6;

/// The cut of an offset tree.
pub(super) struct Cut {
    pub toolpath: Toolpath,
    /// Closed loops cut.
    pub loops: usize,
    /// Corner loops cut (see [`super::corners`]).
    pub corner_loops: usize,
    /// XY of every plunge (mm).
    pub entries: Vec<(f64, f64)>,
}

/// What [`cut_component`] cut.
#[derive(Debug, Clone, Copy, Default)]
struct Counts {
    loops: usize,
    corner_loops: usize,
}

impl std::ops::AddAssign for Counts {
    fn add_assign(&mut self, other: Counts) {
        self.loops += other.loops;
        self.corner_loops += other.corner_loops;
    }
}

/// Cuts every region of `tree`, the nearest next, as `spec` says.
pub(super) fn cut(tree: &OffsetTree, spec: &PocketingSpec) -> Cut {
    let mut writer = PathWriter::new(spec);
    let mut counts = Counts::default();
    let mut roots = tree.roots.clone();
    while !roots.is_empty() {
        let root = take_nearest(&mut roots, tree, writer.position());
        counts += cut_branch(tree, root, spec, &mut writer);
    }
    let (toolpath, entries) = writer.finish();
    Cut { toolpath, loops: counts.loops, corner_loops: counts.corner_loops, entries }
}

/// Cuts the region `root` after everything inside it (post-order, iteratively: a tree can be
/// thousands of loops deep), choosing among sibling branches the one nearest to the tool.
fn cut_branch(tree: &OffsetTree, root: usize, spec: &PocketingSpec, writer: &mut PathWriter) -> Counts {
    let mut counts = Counts::default();
    let mut stack: Vec<(usize, Vec<usize>)> = vec![(root, tree.components[root].children.clone())];
    while let Some((component, remaining)) = stack.last_mut() {
        if remaining.is_empty() {
            let component = *component;
            stack.pop();
            counts += cut_component(&tree.components[component], spec, writer);
        } else {
            let next = take_nearest(remaining, tree, writer.position());
            stack.push((next, tree.components[next].children.clone()));
        }
    }
    counts
}

/// Removes from `candidates` and returns the component whose boundary is nearest to `here`
/// (the first when the tool has not moved yet).
fn take_nearest(candidates: &mut Vec<usize>, tree: &OffsetTree, here: Option<Point>) -> usize {
    let index = here
        .and_then(|p| {
            let distance = |c: usize| nearest_on_loop(&tree.components[c].loops[0], p).distance_mm;
            (0..candidates.len()).min_by(|&a, &b| distance(candidates[a]).total_cmp(&distance(candidates[b])))
        })
        .unwrap_or(0);
    candidates.remove(index)
}

/// Cuts the loops of one region, each from its point nearest to the tool, climb or
/// conventional, with corner loops when `spec` asks for them and the region has been cut
/// inside (a leaf region is slotted: its corners are no deeper than its sides). A leaf
/// region is entered from above; the other loops are reached by a straight link when
/// [`link_stays_inside`] allows it. A loop never starts on a corner loop or between it and
/// its corner (the start moves back to where the corner loop begins).
fn cut_component(component: &Component, spec: &PocketingSpec, writer: &mut PathWriter) -> Counts {
    let climb = spec.climb;
    let looped = spec.corner_loops && !component.children.is_empty();
    let mut remaining: Vec<LoopedRing> = component
        .loops
        .iter()
        .map(|lp| {
            let ring = if climb { lp.clone() } else { lp.reversed() };
            if looped {
                with_corner_loops(&ring, component, spec.radial_depth_mm, climb)
            } else {
                LoopedRing::plain(ring)
            }
        })
        .collect();
    let mut may_link = !component.children.is_empty();
    let mut counts = Counts::default();
    while !remaining.is_empty() {
        let here = writer.position();
        let (index, at) = match here {
            Some(p) => remaining
                .iter()
                .enumerate()
                .map(|(i, ring)| (i, nearest_on_loop(&ring.lp, p)))
                .min_by(|a, b| a.1.distance_mm.total_cmp(&b.1.distance_mm))
                .unwrap_or((0, first_vertex(&remaining[0].lp))),
            None => (0, first_vertex(&remaining[0].lp)),
        };
        let chosen = remaining.swap_remove(index);
        let linkable = |to: Point| {
            here.is_some_and(|p| may_link && writer.at_cutting_depth() && link_stays_inside(component, p, to))
        };
        // A gentle link: onto the next loop a little ahead, so the tool takes the new step-over
        // gradually instead of plunging sideways into it; the nearest point if that fails.
        let r = writer.tool_radius_mm();
        let ahead = LINK_ADVANCE_RADII
            .iter()
            .map(|k| chosen.snapped(advance(&chosen.lp, &at, k * r)))
            .find(|a| linkable(a.point));
        let at = chosen.snapped(at);
        let (at, linked) = match ahead {
            Some(a) => (a, true),
            None => (at, linkable(at.point)),
        };
        let lp = starting_at(&chosen.lp, &at);
        let start = lp.vertices[0].point();
        if linked {
            writer.feed_to(start);
        } else {
            writer.enter_at(start);
        }
        writer.cut_loop(&lp);
        counts += Counts { loops: 1, corner_loops: chosen.corner_loops };
        may_link = true;
    }
    counts
}

/// The start of `lp` as a [`Nearest`].
fn first_vertex(lp: &Loop) -> Nearest {
    Nearest { segment: 0, t: 0.0, point: lp.vertices[0].point(), distance_mm: 0.0 }
}

/// `true` when the straight link from `from` to `to` (a point of one of the region's loops)
/// stays in the region: it meets the loops only within [`LINK_END_TOL_MM`] of its ends and
/// its midpoint is inside. The region lies within the first offset, so such a link gouges no
/// wall and crosses no island.
pub(super) fn link_stays_inside(component: &Component, from: Point, to: Point) -> bool {
    let link = Segment::line(from, to);
    let length_mm = link.length_mm();
    if length_mm <= MIN_MOVE_MM {
        return true;
    }
    let end_t = LINK_END_TOL_MM / length_mm;
    let crosses = component.loops.iter().flat_map(Loop::segments).any(|seg| {
        let meet = link.intersections(&seg);
        meet.overlap || meet.points.iter().any(|x| x.t_self > end_t && x.t_self < 1.0 - end_t)
    });
    !crosses && component.contains(link.midpoint())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::{Loop, Vertex};

    fn square_with_hole() -> Component {
        let hole = Loop::circle(50.0, 50.0, 10.0).reversed();
        Component { loops: vec![Loop::rectangle(0.0, 0.0, 100.0, 100.0), hole], children: vec![] }
    }

    #[test]
    fn a_link_across_a_hole_of_the_region_is_refused() {
        let c = square_with_hole();
        assert!(!link_stays_inside(&c, Point::new(30.0, 50.0), Point::new(70.0, 50.0)));
        assert!(link_stays_inside(&c, Point::new(30.0, 20.0), Point::new(70.0, 20.0)));
        // From the boundary to the hole: touching at both ends only.
        assert!(link_stays_inside(&c, Point::new(0.0, 50.0), Point::new(40.0, 50.0)));
    }

    #[test]
    fn a_link_leaving_the_region_is_refused() {
        let l_shape = Loop::new(vec![
            Vertex::new(0.0, 0.0, 0.0),
            Vertex::new(100.0, 0.0, 0.0),
            Vertex::new(100.0, 20.0, 0.0),
            Vertex::new(20.0, 20.0, 0.0),
            Vertex::new(20.0, 100.0, 0.0),
            Vertex::new(0.0, 100.0, 0.0),
        ]);
        let c = Component { loops: vec![l_shape], children: vec![] };
        assert!(!link_stays_inside(&c, Point::new(90.0, 10.0), Point::new(10.0, 90.0)));
        assert!(link_stays_inside(&c, Point::new(90.0, 10.0), Point::new(10.0, 10.0)));
    }
}
