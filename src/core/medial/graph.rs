//! From the Voronoi graph to branches: coincident points are merged, then the graph is cut into
//! branches at its nodes (points of degree ≠ 2); a cycle without any node (the axis around an
//! island far from everything else) becomes one closed branch (seed 004 §2.1: the medial axis
//! as branches, each a candidate for trochoid insertion).

use super::triangulation::VoronoiGraph;
use crate::core::geometry::Point;
use std::collections::BTreeSet;

/// The Voronoi graph after merging coincident points.
#[derive(Debug, Clone, Default)]
pub(crate) struct PointGraph {
    /// Positions (mm).
    pub points: Vec<Point>,
    /// Per point: the boundary segments its triangles' samples lie on (sorted, no repeats).
    pub generators: Vec<Vec<usize>>,
    /// Per point: its neighbours (sorted, no repeats, never itself).
    pub adjacency: Vec<Vec<usize>>,
}

/// Branches as lists of point indices: the first and the last point are nodes, the others have
/// degree 2. A closed branch starts and ends at the same point.
#[derive(Debug, Clone, Default)]
pub(crate) struct Skeleton {
    /// The branches; `None` once removed.
    pub branches: Vec<Option<Vec<usize>>>,
    /// Points that stand alone (the whole axis of a circle is its centre).
    pub isolated: Vec<usize>,
}

/// Merges the points joined by an edge no longer than `merge_tol_mm` (e.g. the circumcentres
/// of triangles whose samples lie on one circle, which all are the circle's centre). Only
/// points joined by edges are merged, so no cycle is created.
pub(crate) fn contract(graph: VoronoiGraph, merge_tol_mm: f64) -> PointGraph {
    let n = graph.points.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for &[a, b] in &graph.edges {
        if graph.points[a].distance_mm(graph.points[b]) <= merge_tol_mm {
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            if ra != rb {
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    let mut index_of_root = vec![usize::MAX; n];
    let mut out = PointGraph::default();
    let mut new_index = Vec::with_capacity(n);
    for (i, generators) in graph.generators.iter().enumerate() {
        let r = root(&mut parent, i);
        if index_of_root[r] == usize::MAX {
            index_of_root[r] = out.points.len();
            out.points.push(graph.points[r]);
            out.generators.push(Vec::new());
            out.adjacency.push(Vec::new());
        }
        new_index.push(index_of_root[r]);
        out.generators[index_of_root[r]].extend_from_slice(generators);
    }
    for &[a, b] in &graph.edges {
        let (a, b) = (new_index[a], new_index[b]);
        if a != b {
            out.adjacency[a].push(b);
            out.adjacency[b].push(a);
        }
    }
    for list in out.generators.iter_mut().chain(out.adjacency.iter_mut()) {
        list.sort_unstable();
        list.dedup();
    }
    out
}

/// Cuts the graph into branches between its nodes (degree ≠ 2); each cycle of degree-2 points
/// becomes a closed branch anchored at its first point; points of degree 0 are isolated.
pub(crate) fn decompose(graph: &PointGraph) -> Skeleton {
    let adjacency = &graph.adjacency;
    let mut used: BTreeSet<(usize, usize)> = BTreeSet::new();
    let mut skeleton = Skeleton::default();
    let key = |a: usize, b: usize| (a.min(b), a.max(b));
    let walk = |start: usize, first: usize, used: &mut BTreeSet<(usize, usize)>| -> Vec<usize> {
        let mut path = vec![start, first];
        used.insert(key(start, first));
        let (mut prev, mut cur) = (start, first);
        while adjacency[cur].len() == 2 && cur != start {
            let next = if adjacency[cur][0] == prev { adjacency[cur][1] } else { adjacency[cur][0] };
            used.insert(key(cur, next));
            path.push(next);
            (prev, cur) = (cur, next);
        }
        path
    };
    for (node, neighbours) in adjacency.iter().enumerate() {
        if neighbours.is_empty() {
            skeleton.isolated.push(node);
        }
        if neighbours.len() == 2 {
            continue;
        }
        for &next in neighbours {
            if !used.contains(&key(node, next)) {
                skeleton.branches.push(Some(walk(node, next, &mut used)));
            }
        }
    }
    for (start, neighbours) in adjacency.iter().enumerate() {
        if neighbours.len() == 2 && !used.contains(&key(start, neighbours[0])) {
            skeleton.branches.push(Some(walk(start, neighbours[0], &mut used)));
        }
    }
    skeleton
}

/// Length of the polyline through `path` (mm).
pub(crate) fn path_length_mm(points: &[Point], path: &[usize]) -> f64 {
    path.windows(2).map(|w| points[w[0]].distance_mm(points[w[1]])).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graph(points: &[(f64, f64)], edges: &[[usize; 2]]) -> VoronoiGraph {
        VoronoiGraph {
            points: points.iter().map(|&(x, y)| Point::new(x, y)).collect(),
            generators: points.iter().enumerate().map(|(i, _)| vec![i]).collect(),
            edges: edges.to_vec(),
        }
    }

    #[test]
    fn points_joined_by_a_short_edge_merge_and_keep_both_generators() {
        let g = contract(graph(&[(0.0, 0.0), (1e-12, 0.0), (1.0, 0.0)], &[[0, 1], [1, 2]]), 1e-9);
        assert_eq!(g.points.len(), 2);
        assert_eq!(g.generators[0], vec![0, 1]);
        assert_eq!(g.adjacency, vec![vec![1], vec![0]]);
    }

    #[test]
    fn a_y_shaped_graph_has_three_branches_and_a_ring_one_closed_branch() {
        let y = contract(
            graph(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 1.0), (3.0, -1.0)], &[[0, 1], [1, 2], [2, 3], [2, 4]]),
            1e-9,
        );
        let s = decompose(&y);
        let branches: Vec<_> = s.branches.iter().flatten().collect();
        assert_eq!(branches.len(), 3);
        assert!(branches.iter().any(|b| b.len() == 3));
        let ring =
            contract(graph(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)], &[[0, 1], [1, 2], [2, 3], [0, 3]]), 1e-9);
        let s = decompose(&ring);
        let branches: Vec<_> = s.branches.iter().flatten().collect();
        assert_eq!(branches.len(), 1);
        assert_eq!(branches[0].len(), 5);
        assert_eq!(branches[0].first(), branches[0].last());
    }
}
