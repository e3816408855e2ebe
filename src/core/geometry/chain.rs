//! Chaining open contour pieces (DXF LINE, ARC, open polylines) end to end into closed loops.

use super::contour::{Loop, Vertex};
use super::fmt_point;
use super::point::Point;
use crate::core::error::CoreError;
use std::fmt;

/// Where a piece of geometry came from in the DXF file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Source {
    /// Entity type, e.g. `LINE`.
    pub kind: String,
    /// 1-based line of the DXF file holding the entity's type name.
    pub line: usize,
    /// The entity's handle (group 5), if it has one.
    pub handle: Option<String>,
}

impl fmt::Display for Source {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} at line {}", self.kind, self.line)?;
        match &self.handle {
            Some(h) => write!(f, " (handle {h})"),
            None => write!(f, " (no handle)"),
        }
    }
}

/// An open run of segments: `vertices[i].bulge` shapes the segment to `vertices[i + 1]`; the
/// last vertex is the end point (its bulge is unused).
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// At least 2 vertices.
    pub vertices: Vec<Vertex>,
    /// The entity it came from.
    pub source: Source,
}

impl Piece {
    fn start(&self) -> Point {
        self.vertices[0].point()
    }

    fn end(&self) -> Point {
        self.vertices[self.vertices.len() - 1].point()
    }

    /// The same run traversed backwards.
    fn reversed_vertices(&self) -> Vec<Vertex> {
        let m = self.vertices.len() - 1;
        (0..=m)
            .map(|k| {
                let v = self.vertices[m - k];
                let bulge = if k < m { -self.vertices[m - k - 1].bulge } else { 0.0 };
                Vertex::new(v.x, v.y, bulge)
            })
            .collect()
    }
}

/// One end of a piece, for the search by x.
#[derive(Debug, Clone, Copy)]
struct End {
    point: Point,
    piece: usize,
    is_end: bool,
}

/// Chains `pieces` into closed loops: each loop's pieces meet end to end within `tol_mm`
/// (either piece may be reversed; the joint takes the earlier piece's end point). Pieces
/// whose points all lie within `tol_mm` of their start are dropped as degenerate. Returns
/// each loop with the source of its first piece. A piece left dangling, or a point where more
/// than two piece ends meet, is an error naming the entity's line and handle.
pub fn chain_pieces(pieces: Vec<Piece>, tol_mm: f64) -> Result<Vec<(Source, Loop)>, CoreError> {
    let pieces: Vec<Piece> = pieces
        .into_iter()
        .filter(|p| p.vertices.len() >= 2 && p.vertices.iter().any(|v| !v.point().near(p.start(), tol_mm)))
        .collect();
    let mut ends: Vec<End> = Vec::with_capacity(2 * pieces.len());
    for (k, p) in pieces.iter().enumerate() {
        ends.push(End { point: p.start(), piece: k, is_end: false });
        ends.push(End { point: p.end(), piece: k, is_end: true });
    }
    ends.sort_unstable_by(|a, b| a.point.x.total_cmp(&b.point.x));
    let mut used = vec![false; pieces.len()];
    let mut loops = Vec::new();
    for first in 0..pieces.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let mut chain = pieces[first].vertices.clone();
        let mut last = first;
        loop {
            let start = chain[0].point();
            let end = chain[chain.len() - 1].point();
            if chain.len() > 2 && end.near(start, tol_mm) {
                chain.pop();
                loops.push((pieces[first].source.clone(), Loop::new(chain)));
                break;
            }
            let lo = ends.partition_point(|e| e.point.x < end.x - tol_mm);
            let mut found: Option<End> = None;
            for e in ends[lo..].iter().take_while(|e| e.point.x <= end.x + tol_mm) {
                if used[e.piece] || !e.point.near(end, tol_mm) {
                    continue;
                }
                if let Some(other) = found {
                    return Err(CoreError::invalid(
                        "dxf",
                        format!(
                            "{}: more than two contour ends meet at {}: also {} and {}",
                            pieces[last].source,
                            fmt_point(end),
                            pieces[other.piece].source,
                            pieces[e.piece].source
                        ),
                    ));
                }
                found = Some(*e);
            }
            let Some(next) = found else {
                let mut reason = format!(
                    "{} cannot be chained into a closed loop: its end at {} meets no other contour end within {:e} mm",
                    pieces[last].source,
                    fmt_point(end),
                    tol_mm
                );
                if last != first {
                    reason.push_str(&format!(" (the open chain starts with {})", pieces[first].source));
                }
                return Err(CoreError::invalid("dxf", reason));
            };
            used[next.piece] = true;
            last = next.piece;
            let mut more =
                if next.is_end { pieces[next.piece].reversed_vertices() } else { pieces[next.piece].vertices.clone() };
            chain.pop();
            more[0].x = end.x;
            more[0].y = end.y;
            chain.extend(more);
        }
    }
    Ok(loops)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::test_support::loops_near;

    /// Chaining tolerance of the tests (mm).
    const TOL_MM: f64 = 1e-6;

    /// Tolerance of exact results (mm, mm²).
    const EXACT: f64 = 1e-12;

    fn piece(points: &[(f64, f64, f64)], line: usize) -> Piece {
        Piece {
            vertices: points.iter().map(|&(x, y, b)| Vertex::new(x, y, b)).collect(),
            source: Source { kind: "LINE".into(), line, handle: Some(format!("H{line}")) },
        }
    }

    #[test]
    fn pieces_in_any_order_and_direction_chain_into_one_loop() {
        let pieces = vec![
            piece(&[(0.0, 0.0, 0.0), (10.0, 0.0, 0.0)], 1),
            piece(&[(0.0, 10.0, 0.0), (10.0, 10.0 + TOL_MM / 10.0, 0.0)], 2),
            piece(&[(10.0, 10.0, 0.0), (10.0, 0.0, 0.0)], 3),
            piece(&[(0.0, 10.0, 0.0), (0.0, 0.0, 0.0)], 4),
        ];
        let loops = chain_pieces(pieces, TOL_MM).unwrap();
        assert_eq!(loops.len(), 1);
        assert_eq!(loops[0].0.line, 1);
        let lp = &loops[0].1;
        assert_eq!(lp.vertices.len(), 4);
        assert!((lp.signed_area().abs() - 100.0).abs() < TOL_MM);
    }

    #[test]
    fn a_reversed_arc_piece_keeps_its_shape() {
        let arc = piece(&[(1.0, 0.0, 1.0), (-1.0, 0.0, 0.0)], 1);
        let rev = arc.reversed_vertices();
        let expected = Loop::new(vec![Vertex::new(-1.0, 0.0, -1.0), Vertex::new(1.0, 0.0, 0.0)]);
        assert!(loops_near(&Loop::new(rev), &expected, EXACT));
        let chord = piece(&[(-1.0, 0.0, 0.0), (1.0, 0.0, 0.0)], 2);
        let loops = chain_pieces(vec![arc, chord], TOL_MM).unwrap();
        assert!((loops[0].1.signed_area() - std::f64::consts::FRAC_PI_2).abs() < EXACT);
    }

    #[test]
    fn a_dangling_piece_is_named_with_its_line_and_handle() {
        let pieces =
            vec![piece(&[(0.0, 0.0, 0.0), (10.0, 0.0, 0.0)], 7), piece(&[(10.0, 0.0, 0.0), (10.0, 10.0, 0.0)], 9)];
        let err = chain_pieces(pieces, TOL_MM).unwrap_err().to_string();
        assert!(err.contains("LINE at line 9 (handle H9) cannot be chained"), "{err}");
        assert!(err.contains("starts with LINE at line 7"), "{err}");
    }

    #[test]
    fn three_ends_at_one_point_are_refused_and_degenerate_pieces_dropped() {
        let pieces = vec![
            piece(&[(0.0, 0.0, 0.0), (10.0, 0.0, 0.0)], 1),
            piece(&[(10.0, 0.0, 0.0), (10.0, 10.0, 0.0)], 2),
            piece(&[(10.0, 0.0, 0.0), (20.0, 0.0, 0.0)], 3),
        ];
        let err = chain_pieces(pieces, TOL_MM).unwrap_err().to_string();
        assert!(err.contains("more than two contour ends meet at (10, 0)"), "{err}");
        let dot = vec![piece(&[(5.0, 5.0, 0.0), (5.0, 5.0, 0.0)], 1)];
        assert!(chain_pieces(dot, TOL_MM).unwrap().is_empty());
    }
}
