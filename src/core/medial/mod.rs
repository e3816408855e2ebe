//! The medial axis of a pocket and its radius-ratio classes (seed 004 §2.1 and §2.3;
//! MODEL.md §7).
//!
//! Critical cutting regions lie on the medial axis of the pocket contour (seed 004 §2.1); the
//! clearance `R` along it, against the tool radius `r`, decides between contour-parallel paths,
//! trochoidal grooving and z-cut division (seed 004 §2.3, see
//! [`classify`](crate::core::medial::classify)).
//!
//! [`medial_axis`](crate::core::medial::medial_axis) approximates the axis from the Voronoi
//! diagram of boundary samples, as the first report cited by seed 004 does:
//!
//! 1. the outer loop and the islands are sampled at most `step` apart (arcs also by angle);
//! 2. spade's constrained Delaunay triangulation of the samples, the boundary pieces as
//!    constraints; pieces an inside triangle encroaches on (sees under an obtuse angle) or that
//!    cross another piece are split along the true line or arc and the triangulation redone;
//! 3. the circumcentres of the triangles inside the pocket (inside the outer loop, outside the
//!    islands), joined through shared interior edges, are the approximate axis; coincident ones
//!    are merged;
//! 4. the graph is cut into branches between nodes (ends, junctions), the spurious twigs of the
//!    sampling are pruned (the rule is in [`prune`](crate::core::medial::prune)), and branches
//!    meeting at degree 2 are joined;
//! 5. each remaining point is moved by Newton's method onto the true axis (equally far from its
//!    two nearest contacts with the lines and arcs, three at a junction), its `R` is its exact
//!    distance to the boundary ([`crate::core::geometry::Segment::distance_mm`]), and each
//!    branch is simplified (Douglas–Peucker in position and `R`).
//!
//! A circle's axis is its centre: one isolated node and no branch. The axis around an island is
//! a closed branch (a cycle in the graph). A branch into a sharp convex corner ends about half a
//! sampling step short of the corner, where `R` is about that much.

mod axis;
mod boundary;
mod build;
mod classes;
mod critical;
mod graph;
pub mod prune;
mod refine;
mod sampling;
mod simplify;
pub(crate) use simplify::douglas_peucker;
mod triangulation;

#[cfg(test)]
mod accuracy_tests;
#[cfg(test)]
mod axis_tests;
#[cfg(test)]
mod proptests;
#[cfg(test)]
mod test_shapes;

pub use axis::{AxisBranch, AxisNode, AxisPoint, MedialAxis, MedialOptions, NodeKind};
pub(crate) use boundary::Boundary;
pub use classes::{
    class_of, classify, BranchClasses, ClassInterval, RadiusClass, CLASS_A_RATIO_DEFAULT, CLASS_A_RATIO_MAX,
    CLASS_A_RATIO_MIN, CLASS_C_RATIO,
};
pub use critical::{critical_branches, CriticalBranches, CriticalInterval};

use crate::core::error::{require_positive, CoreError};
use crate::core::geometry::{Pocket, Point};
use build::{assemble, Context};
use sampling::Sampling;
use std::collections::BTreeMap;
use std::f64::consts::PI;
use triangulation::{triangulate, Pass, VoronoiGraph};

/// Default sampling step as a fraction of the pocket's diagonal.
pub const DEFAULT_STEP_FRACTION: f64 = 1.0 / 200.0;

/// Default largest sweep of an arc between two samples (rad): 5°.
pub const DEFAULT_MAX_ARC_ANGLE_RAD: f64 = 5.0 * PI / 180.0;

/// Default pruning threshold `δ` in sampling steps (see [`prune`]).
pub const DEFAULT_PRUNE_STEPS: f64 = 1.0;

/// Default Douglas–Peucker tolerance in sampling steps.
pub const DEFAULT_SIMPLIFY_STEPS: f64 = 0.05;

/// Voronoi vertices closer than this many sampling steps are one point.
const MERGE_STEPS: f64 = 1e-6;

/// A point of the axis moves at most this many sampling steps onto the true axis.
const MAX_MOVE_STEPS: f64 = 0.5;

/// A boundary piece shorter than this many sampling steps is not split further.
const MIN_PIECE_STEPS: f64 = 1.0 / 256.0;

/// At most this many rounds of splitting encroached pieces.
const MAX_SPLIT_PASSES: usize = 12;

/// At most this many boundary samples (a step far too small for the pocket is refused).
pub const MAX_SAMPLES: usize = 1_000_000;

/// The medial axis of `pocket` (see the module documentation for the method and
/// [`prune`] for the pruning rule).
///
/// Errors: an option that is not finite and positive, a step giving more than
/// [`MAX_SAMPLES`] samples, or a boundary the triangulation cannot take.
pub fn medial_axis(pocket: &Pocket, options: &MedialOptions) -> Result<MedialAxis, CoreError> {
    let boundary = Boundary::of_pocket(pocket);
    let step_mm = match options.step_mm {
        Some(step) => require_positive("step_mm", step)?,
        None => require_positive("pocket", pocket.bounds().diagonal_mm() * DEFAULT_STEP_FRACTION)?,
    };
    let max_angle_rad = match options.max_arc_angle_rad {
        Some(angle) => require_positive("max_arc_angle_rad", angle)?,
        None => DEFAULT_MAX_ARC_ANGLE_RAD,
    };
    let delta_mm = match options.prune_threshold_mm {
        Some(delta) => require_positive("prune_threshold_mm", delta)?,
        None => DEFAULT_PRUNE_STEPS * step_mm,
    };
    let simplify_tol_mm = match options.simplify_tolerance_mm {
        Some(tol) if tol.is_finite() && tol >= 0.0 => tol,
        Some(tol) => return Err(CoreError::invalid("simplify_tolerance_mm", format!("must be ≥ 0, got {tol}"))),
        None => DEFAULT_SIMPLIFY_STEPS * step_mm,
    };
    let expected = boundary.segments.iter().map(|s| s.length_mm()).sum::<f64>() / step_mm
        + boundary.segments.iter().map(|s| s.sweep_rad().abs()).sum::<f64>() / max_angle_rad;
    if expected.is_nan() || expected > MAX_SAMPLES as f64 {
        return Err(CoreError::invalid(
            "step_mm",
            format!("{step_mm} mm would sample the boundary at about {expected:.0} points (at most {MAX_SAMPLES})"),
        ));
    }
    let contains = |p: Point| pocket.contains(p.x, p.y);
    let voronoi = conforming_voronoi(&boundary, Sampling::new(&boundary, step_mm, max_angle_rad), contains, step_mm)?;
    let mut graph = graph::contract(voronoi, MERGE_STEPS * step_mm);
    if graph.points.is_empty() {
        return Err(CoreError::unsolvable("pocket", "no triangle of the boundary samples lies inside the pocket"));
    }
    let mut clearance_mm: Vec<f64> = graph.points.iter().map(|&p| boundary.clearance_mm(p)).collect();
    let mut skeleton = graph::decompose(&graph);
    prune::prune(&mut skeleton, &graph.points, &clearance_mm, delta_mm);
    for (point, degree) in skeleton_degrees(&skeleton) {
        let wanted = if degree >= 3 { 3 } else { 2 };
        let generators = &graph.generators[point];
        let moved =
            refine::refine(&boundary, generators, graph.points[point], wanted, MAX_MOVE_STEPS * step_mm, contains);
        graph.points[point] = moved;
        clearance_mm[point] = boundary.clearance_mm(moved);
    }
    let ctx = Context { boundary: &boundary, graph: &graph, clearance_mm: &clearance_mm, simplify_tol_mm, step_mm };
    Ok(assemble(&skeleton, &ctx))
}

/// Triangulates the samples, splitting the pieces that cross or are encroached on until none
/// is (at most [`MAX_SPLIT_PASSES`] rounds; encroached pieces left then are accepted, crossing
/// ones are an error), and returns the Voronoi graph of the inside triangles.
fn conforming_voronoi(
    boundary: &Boundary,
    mut sampling: Sampling,
    contains: impl Fn(Point) -> bool + Copy,
    step_mm: f64,
) -> Result<VoronoiGraph, CoreError> {
    let mut passes = 0;
    let mut accept_encroached = false;
    loop {
        match triangulate(boundary, &sampling, contains, accept_encroached)? {
            Pass::Graph(graph) => return Ok(graph),
            Pass::Split(pieces) => {
                passes += 1;
                let split = if passes <= MAX_SPLIT_PASSES {
                    sampling.split(boundary, &pieces, MIN_PIECE_STEPS * step_mm)
                } else {
                    0
                };
                if split == 0 && accept_encroached {
                    return Err(CoreError::unsolvable(
                        "pocket",
                        "boundary pieces still cross after splitting: the loops nearly touch",
                    ));
                }
                accept_encroached = split == 0;
            }
        }
    }
}

/// Every point used by the skeleton with its degree: 2 inside a branch, the number of branch
/// ends at a node (a closed branch counts twice at its start), 0 for an isolated point.
fn skeleton_degrees(skeleton: &graph::Skeleton) -> BTreeMap<usize, usize> {
    let mut degree = BTreeMap::new();
    for path in skeleton.branches.iter().flatten() {
        for &inner in &path[1..path.len() - 1] {
            degree.insert(inner, 2);
        }
    }
    for path in skeleton.branches.iter().flatten() {
        *degree.entry(path[0]).or_insert(0) += 1;
        *degree.entry(path[path.len() - 1]).or_insert(0) += 1;
    }
    for &point in &skeleton.isolated {
        degree.entry(point).or_insert(0);
    }
    degree
}
