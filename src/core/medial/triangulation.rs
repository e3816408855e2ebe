//! The constrained Delaunay triangulation of the boundary samples (spade) and its dual inside
//! the pocket: the Voronoi vertices (circumcentres) of the triangles that lie in the material-free
//! region, joined through the triangles' shared interior edges (seed 004 §2.1, after its first
//! report: the medial axis from the Voronoi diagram of the contour).
//!
//! The samples' boundary pieces are constraint edges. A triangle is inside when a path from the
//! triangulation's outer face to it crosses the constraints an odd number of times (the
//! even–odd rule, so islands come out as holes). A piece that an inside triangle sees under an
//! obtuse angle is *encroached*: that triangle's circumcentre lies beyond the piece, outside
//! the pocket, so the piece is reported for splitting instead (as in Delaunay refinement).

use super::boundary::Boundary;
use super::sampling::Sampling;
use crate::core::error::CoreError;
use crate::core::geometry::Point;
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};
use std::collections::{BTreeSet, VecDeque};

/// An inside triangle whose angle opposite a boundary piece has a cosine below this is
/// encroaching on that piece (an obtuse angle, with a margin for right angles that are obtuse
/// only by rounding, as in a rectangle's evenly sampled sides).
const ENCROACHING_COS: f64 = -1e-9;

/// A boundary sample as a triangulation vertex.
#[derive(Debug, Clone, Copy)]
struct SampleVertex {
    position: Point2<f64>,
    /// Index of the loop in [`Sampling::loops`].
    loop_index: usize,
    /// Index of the sample in its loop.
    sample_index: usize,
}

impl HasPosition for SampleVertex {
    type Scalar = f64;

    fn position(&self) -> Point2<f64> {
        self.position
    }
}

/// The approximate medial axis as a graph of Voronoi vertices.
#[derive(Debug, Clone, Default)]
pub(crate) struct VoronoiGraph {
    /// One point per inside triangle: its circumcentre (mm).
    pub points: Vec<Point>,
    /// Per point: the boundary segments its triangle's samples lie on (sorted, no repeats).
    pub generators: Vec<Vec<usize>>,
    /// Pairs of points whose triangles share an interior edge.
    pub edges: Vec<[usize; 2]>,
}

/// What one triangulation pass produced.
#[derive(Debug)]
pub(crate) enum Pass {
    /// The samples were fine enough: the graph.
    Graph(VoronoiGraph),
    /// These boundary pieces `(loop, sample)` must be split first: they cross another piece or
    /// an inside triangle encroaches on them.
    Split(BTreeSet<(usize, usize)>),
}

type Cdt = ConstrainedDelaunayTriangulation<SampleVertex>;

/// Triangulates the samples and returns the Voronoi graph of the inside triangles, or the
/// pieces to split (crossing pieces always, encroached ones unless `accept_encroached`).
pub(crate) fn triangulate(
    boundary: &Boundary,
    sampling: &Sampling,
    pocket_contains: impl Fn(Point) -> bool,
    accept_encroached: bool,
) -> Result<Pass, CoreError> {
    let mut vertices = Vec::with_capacity(sampling.len());
    let mut edges = Vec::with_capacity(sampling.len());
    for (loop_index, samples) in sampling.loops.iter().enumerate() {
        let first = vertices.len();
        let n = samples.len();
        for (sample_index, s) in samples.iter().enumerate() {
            let position = spade::mitigate_underflow(Point2::new(s.point.x, s.point.y));
            vertices.push(SampleVertex { position, loop_index, sample_index });
            edges.push([first + sample_index, first + (sample_index + 1) % n]);
        }
    }
    let mut conflicts = Vec::new();
    let cdt = Cdt::try_bulk_load_cdt(vertices.clone(), edges, |e| conflicts.push(e))
        .map_err(|e| CoreError::unsolvable("pocket", format!("the boundary cannot be triangulated: {e:?}")))?;
    if cdt.num_vertices() != vertices.len() {
        return Err(CoreError::unsolvable("pocket", "two boundary samples coincide: loops touch each other"));
    }
    if !conflicts.is_empty() {
        let pieces = conflicts.iter().map(|&[a, _]| (vertices[a].loop_index, vertices[a].sample_index)).collect();
        return Ok(Pass::Split(pieces));
    }
    let inside = inside_faces(&cdt);
    if !accept_encroached {
        let encroached = encroached_pieces(&cdt, &inside, sampling);
        if !encroached.is_empty() {
            return Ok(Pass::Split(encroached));
        }
    }
    Ok(Pass::Graph(voronoi_graph(&cdt, &inside, boundary, sampling, pocket_contains)))
}

/// Per face index: `true` for the triangles inside the pocket (even–odd rule over the
/// constraint edges, starting outside at the outer face).
fn inside_faces(cdt: &Cdt) -> Vec<bool> {
    let mut parity: Vec<Option<bool>> = vec![None; cdt.num_all_faces()];
    let mut queue = VecDeque::new();
    for edge in cdt.directed_edges() {
        if !edge.face().is_outer() {
            continue;
        }
        if let Some(face) = edge.rev().face().as_inner() {
            let index = face.fix().index();
            if parity[index].is_none() {
                parity[index] = Some(edge.is_constraint_edge());
                queue.push_back(face.fix());
            }
        }
    }
    while let Some(fixed) = queue.pop_front() {
        let face = cdt.face(fixed);
        let own = parity[fixed.index()].unwrap_or(false);
        for edge in face.adjacent_edges() {
            if let Some(other) = edge.rev().face().as_inner() {
                let index = other.fix().index();
                if parity[index].is_none() {
                    parity[index] = Some(own != edge.is_constraint_edge());
                    queue.push_back(other.fix());
                }
            }
        }
    }
    parity.into_iter().map(|p| p.unwrap_or(false)).collect()
}

/// The boundary pieces `(loop, sample)` an inside triangle sees under an obtuse angle.
fn encroached_pieces(cdt: &Cdt, inside: &[bool], sampling: &Sampling) -> BTreeSet<(usize, usize)> {
    let mut pieces = BTreeSet::new();
    for face in cdt.inner_faces().filter(|f| inside[f.fix().index()]) {
        for edge in face.adjacent_edges() {
            if !edge.is_constraint_edge() {
                continue;
            }
            let (a, b) = (edge.from().position(), edge.to().position());
            let Some(c) = edge.opposite_position() else { continue };
            let (u, v) = ((a.x - c.x, a.y - c.y), (b.x - c.x, b.y - c.y));
            let cos = (u.0 * v.0 + u.1 * v.1) / (u.0.hypot(u.1) * v.0.hypot(v.1));
            if cos < ENCROACHING_COS {
                pieces.insert(piece_of(edge.from().data(), edge.to().data(), sampling));
            }
        }
    }
    pieces
}

/// The piece `(loop, k)` joining two consecutive samples of a loop.
fn piece_of(a: &SampleVertex, b: &SampleVertex, sampling: &Sampling) -> (usize, usize) {
    let n = sampling.loops[a.loop_index].len();
    if (a.sample_index + 1) % n == b.sample_index {
        (a.loop_index, a.sample_index)
    } else {
        (b.loop_index, b.sample_index)
    }
}

/// The circumcentres of the inside triangles, their generating segments and their adjacency.
/// A circumcentre that still falls outside the pocket (possible only where the splitting gave
/// up) is replaced by its triangle's centroid, which always lies inside the sampled region.
fn voronoi_graph(
    cdt: &Cdt,
    inside: &[bool],
    boundary: &Boundary,
    sampling: &Sampling,
    pocket_contains: impl Fn(Point) -> bool,
) -> VoronoiGraph {
    let mut graph = VoronoiGraph::default();
    let mut point_of_face: Vec<Option<usize>> = vec![None; cdt.num_all_faces()];
    for face in cdt.inner_faces().filter(|f| inside[f.fix().index()]) {
        let c = face.circumcenter();
        let mut point = Point::new(c.x, c.y);
        if !(point.x.is_finite() && point.y.is_finite() && pocket_contains(point)) {
            let m = face.center();
            point = Point::new(m.x, m.y);
        }
        let mut generators = Vec::with_capacity(4);
        for v in face.vertices() {
            let d = v.data();
            let sample = sampling.loops[d.loop_index][d.sample_index];
            generators.push(sample.segment);
            if sample.at_vertex {
                generators.push(boundary.previous(sample.segment));
            }
        }
        generators.sort_unstable();
        generators.dedup();
        point_of_face[face.fix().index()] = Some(graph.points.len());
        graph.points.push(point);
        graph.generators.push(generators);
    }
    for face in cdt.inner_faces() {
        let Some(a) = point_of_face[face.fix().index()] else { continue };
        for edge in face.adjacent_edges() {
            if edge.is_constraint_edge() {
                continue;
            }
            let other = edge.rev().face().as_inner().map(|f| f.fix().index());
            if let Some(b) = other.and_then(|f| point_of_face[f]) {
                if a < b {
                    graph.edges.push([a, b]);
                }
            }
        }
    }
    graph
}
