//! Assembling the returned [`MedialAxis`] from the pruned skeleton: nodes with their kinds,
//! simplified branches, and each point's nearest boundary points (seed 004 §2.1).

use super::axis::{AxisBranch, AxisNode, AxisPoint, MedialAxis, NodeKind};
use super::boundary::Boundary;
use super::graph::{PointGraph, Skeleton};
use super::refine::contacts;
use super::simplify::douglas_peucker;
use crate::core::geometry::Point;
use std::collections::BTreeMap;

/// What [`assemble`] needs besides the skeleton.
pub(crate) struct Context<'a> {
    /// The boundary, for the nearest points.
    pub boundary: &'a Boundary,
    /// The merged Voronoi graph (positions, generators).
    pub graph: &'a PointGraph,
    /// R per point of `graph` (mm).
    pub clearance_mm: &'a [f64],
    /// Douglas–Peucker tolerance (mm); 0 keeps every point.
    pub simplify_tol_mm: f64,
    /// The sampling step (mm).
    pub step_mm: f64,
}

/// Turns the skeleton into nodes and branches.
pub(crate) fn assemble(skeleton: &Skeleton, ctx: &Context<'_>) -> MedialAxis {
    let mut nodes: Vec<AxisNode> = Vec::new();
    let mut node_of: BTreeMap<usize, usize> = BTreeMap::new();
    let mut degree: Vec<usize> = Vec::new();
    let mut node_index = |point: usize, nodes: &mut Vec<AxisNode>, degree: &mut Vec<usize>| -> usize {
        *node_of.entry(point).or_insert_with(|| {
            nodes.push(AxisNode { point: axis_point(point, ctx), kind: NodeKind::Isolated, branches: Vec::new() });
            degree.push(0);
            nodes.len() - 1
        })
    };
    let mut branches = Vec::new();
    for path in skeleton.branches.iter().flatten() {
        let (first, last) = (path[0], path[path.len() - 1]);
        let start_node = node_index(first, &mut nodes, &mut degree);
        let end_node = node_index(last, &mut nodes, &mut degree);
        let index = branches.len();
        degree[start_node] += 1;
        degree[end_node] += 1;
        nodes[start_node].branches.push(index);
        if end_node != start_node {
            nodes[end_node].branches.push(index);
        }
        branches.push(branch(path, start_node, end_node, ctx));
    }
    for &point in &skeleton.isolated {
        node_index(point, &mut nodes, &mut degree);
    }
    for (node, d) in nodes.iter_mut().zip(degree) {
        node.kind = match d {
            0 => NodeKind::Isolated,
            1 => NodeKind::End,
            2 => NodeKind::CycleStart,
            _ => NodeKind::Junction,
        };
    }
    MedialAxis { step_mm: ctx.step_mm, nodes, branches }
}

/// One branch: its points simplified, with R and nearest points.
fn branch(path: &[usize], start_node: usize, end_node: usize, ctx: &Context<'_>) -> AxisBranch {
    let positions: Vec<Point> = path.iter().map(|&i| ctx.graph.points[i]).collect();
    let clearance: Vec<f64> = path.iter().map(|&i| ctx.clearance_mm[i]).collect();
    let kept = if ctx.simplify_tol_mm > 0.0 {
        douglas_peucker(&positions, &clearance, ctx.simplify_tol_mm)
    } else {
        (0..path.len()).collect()
    };
    let points: Vec<AxisPoint> = kept.iter().map(|&k| axis_point(path[k], ctx)).collect();
    let length_mm = points.windows(2).map(|w| w[0].point.distance_mm(w[1].point)).sum();
    AxisBranch { start_node, end_node, closed: start_node == end_node, points, length_mm }
}

/// The point `index` of the graph with R and its nearest boundary points: its contacts with
/// its generating segments (see [`contacts`]), or the nearest boundary point if it has none.
fn axis_point(index: usize, ctx: &Context<'_>) -> AxisPoint {
    let point = ctx.graph.points[index];
    let mut nearest: Vec<Point> =
        contacts(ctx.boundary, &ctx.graph.generators[index], point).iter().map(|c| c.point).collect();
    if nearest.is_empty() {
        nearest.push(ctx.boundary.nearest_point(point));
    }
    AxisPoint { point, clearance_mm: ctx.clearance_mm[index], nearest }
}
