//! The medial axis as returned: nodes, branches of points with their clearance, and the
//! options it was built with (seed 004 §2.1, MODEL.md §7).

use crate::core::geometry::Point;
use serde::{Deserialize, Serialize};

/// One point of the medial axis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisPoint {
    /// Position (mm).
    pub point: Point,
    /// Clearance radius `R` (mm): the exact distance to the pocket's boundary (lines and arcs),
    /// the radius of the largest inscribed circle centred here.
    pub clearance_mm: f64,
    /// The boundary points nearest to `point` on the segments that generate it (two along a
    /// branch, three or more at a junction; one on a circle's centre), nearest first. Each lies
    /// within the sampling error of `clearance_mm` from `point`.
    pub nearest: Vec<Point>,
}

/// What a node is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, utoipa::ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum NodeKind {
    /// Degree 1: a branch ends here (in a convex corner, or at the centre of an arc).
    End,
    /// Degree ≥ 3: branches meet.
    Junction,
    /// Degree 2 on a closed branch that meets nothing else: where that cycle starts and ends.
    CycleStart,
    /// Degree 0: the whole axis is this point (a circular pocket's centre).
    Isolated,
}

/// A node of the axis graph.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisNode {
    /// The node's point.
    pub point: AxisPoint,
    /// End, junction, start of a lone cycle, or isolated point.
    pub kind: NodeKind,
    /// Indices of the branches that start or end here (a closed branch is listed once).
    pub branches: Vec<usize>,
}

/// A branch: the polyline between two nodes (the same node for a closed branch).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisBranch {
    /// Index of the node at `points[0]`.
    pub start_node: usize,
    /// Index of the node at the last point.
    pub end_node: usize,
    /// `true` when the branch is a cycle (around an island): `start_node == end_node`.
    pub closed: bool,
    /// The points from start to end, both nodes included.
    pub points: Vec<AxisPoint>,
    /// Length of the polyline (mm).
    pub length_mm: f64,
}

/// Options of [`super::medial_axis`].
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct MedialOptions {
    /// Largest distance between boundary samples (mm); default
    /// [`super::DEFAULT_STEP_FRACTION`] of the pocket's diagonal.
    pub step_mm: Option<f64>,
    /// Largest angle an arc sweeps between two samples (rad); default
    /// [`super::DEFAULT_MAX_ARC_ANGLE_RAD`].
    pub max_arc_angle_rad: Option<f64>,
    /// `δ` of the pruning rule (mm, see [`super::prune`]); default
    /// [`super::DEFAULT_PRUNE_STEPS`] sampling steps.
    pub prune_threshold_mm: Option<f64>,
    /// Tolerance of the Douglas–Peucker simplification of the branches (mm, position and R);
    /// default [`super::DEFAULT_SIMPLIFY_STEPS`] sampling steps; 0 keeps every point.
    pub simplify_tolerance_mm: Option<f64>,
}

/// The medial axis of a pocket: a graph of nodes and branches.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MedialAxis {
    /// The sampling step used (mm).
    pub step_mm: f64,
    /// The nodes.
    pub nodes: Vec<AxisNode>,
    /// The branches.
    pub branches: Vec<AxisBranch>,
}

impl MedialAxis {
    /// Every point of the axis: the branches' points, then the isolated nodes.
    pub fn points(&self) -> impl Iterator<Item = &AxisPoint> {
        self.branches
            .iter()
            .flat_map(|b| b.points.iter())
            .chain(self.nodes.iter().filter(|n| n.kind == NodeKind::Isolated).map(|n| &n.point))
    }

    /// The largest clearance on the axis (mm): the radius of the pocket's largest inscribed
    /// circle; 0 for an empty axis.
    pub fn max_clearance_mm(&self) -> f64 {
        self.points().map(|p| p.clearance_mm).fold(0.0, f64::max)
    }
}
