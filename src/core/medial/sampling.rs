//! Boundary samples: the points whose Delaunay triangulation approximates the medial axis
//! (seed 004 §2.1 and its first report: the medial axis from the Voronoi diagram of the contour).
//!
//! Every segment is divided evenly into pieces no longer than the step and, for arcs, sweeping
//! no more than the maximal angle; the vertices of the loops are always samples. A piece can be
//! split later (at its middle along the true line or arc) when the triangulation shows it is too
//! coarse there.

use super::boundary::Boundary;
use crate::core::geometry::Point;
use std::collections::BTreeSet;

/// One boundary sample.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sample {
    /// Where it lies (mm).
    pub point: Point,
    /// The segment it lies on (index into [`Boundary::segments`]).
    pub segment: usize,
    /// Its fraction of the segment's length, in [0, 1).
    pub t: f64,
    /// `true` at the segment's start vertex, which the previous segment shares.
    pub at_vertex: bool,
}

/// The samples of each loop, in the loop's order (the last one joins the first).
#[derive(Debug, Clone)]
pub(crate) struct Sampling {
    /// Samples per loop, outer loop first.
    pub loops: Vec<Vec<Sample>>,
}

impl Sampling {
    /// Samples every segment of `boundary` at most `step_mm` apart and, on arcs, at most
    /// `max_arc_angle_rad` apart.
    pub fn new(boundary: &Boundary, step_mm: f64, max_arc_angle_rad: f64) -> Sampling {
        let loops = boundary
            .loops
            .iter()
            .map(|range| {
                let mut samples = Vec::new();
                for index in range.clone() {
                    let segment = &boundary.segments[index];
                    let by_length = (segment.length_mm() / step_mm).ceil();
                    let by_angle = (segment.sweep_rad().abs() / max_arc_angle_rad).ceil();
                    // Both counts are small positive integers stored as floats.
                    let pieces = by_length.max(by_angle).max(1.0) as usize;
                    for k in 0..pieces {
                        let t = k as f64 / pieces as f64;
                        samples.push(Sample { point: segment.point_at(t), segment: index, t, at_vertex: k == 0 });
                    }
                }
                samples
            })
            .collect();
        Sampling { loops }
    }

    /// Total number of samples.
    pub fn len(&self) -> usize {
        self.loops.iter().map(Vec::len).sum()
    }

    /// Splits the pieces `(loop, k)` (from sample `k` to the next one of that loop) at their
    /// middle along the true segment, unless a piece is already shorter than `min_piece_mm`.
    /// Returns how many pieces were split.
    pub fn split(&mut self, boundary: &Boundary, pieces: &BTreeSet<(usize, usize)>, min_piece_mm: f64) -> usize {
        let mut split = 0;
        for (l, samples) in self.loops.iter_mut().enumerate() {
            let marked: Vec<usize> = pieces.range((l, 0)..(l + 1, 0)).map(|&(_, k)| k).collect();
            if marked.is_empty() {
                continue;
            }
            let n = samples.len();
            let mut out = Vec::with_capacity(n + marked.len());
            let mut next_marked = marked.iter().peekable();
            for k in 0..n {
                let a = samples[k];
                out.push(a);
                if next_marked.peek() != Some(&&k) {
                    continue;
                }
                next_marked.next();
                let b = samples[(k + 1) % n];
                let t_end = if b.segment == a.segment && !b.at_vertex { b.t } else { 1.0 };
                let segment = &boundary.segments[a.segment];
                if (t_end - a.t) * segment.length_mm() < min_piece_mm {
                    continue;
                }
                let t = 0.5 * (a.t + t_end);
                out.push(Sample { point: segment.point_at(t), segment: a.segment, t, at_vertex: false });
                split += 1;
            }
            *samples = out;
        }
        split
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::{Loop, Pocket};
    use std::f64::consts::PI;

    /// Tolerance of exact results (mm).
    const TOL_MM: f64 = 1e-9;

    #[test]
    fn sides_are_divided_evenly_and_vertices_are_samples() {
        let pocket = Pocket::new(Loop::rectangle(0.0, 0.0, 60.0, 40.0), vec![]).unwrap();
        let boundary = Boundary::of_pocket(&pocket);
        let sampling = Sampling::new(&boundary, 7.0, PI);
        // 60 / 7 → 9 pieces, 40 / 7 → 6 pieces.
        assert_eq!(sampling.len(), 2 * 9 + 2 * 6);
        let s = &sampling.loops[0];
        assert!(s[0].at_vertex && s[0].point.near(Point::new(0.0, 0.0), TOL_MM));
        assert!(s[1].point.near(Point::new(60.0 / 9.0, 0.0), TOL_MM));
        assert!(s[9].at_vertex && s[9].point.near(Point::new(60.0, 0.0), TOL_MM));
    }

    #[test]
    fn arcs_are_divided_by_angle_as_well_as_by_length() {
        let pocket = Pocket::new(Loop::circle(0.0, 0.0, 1.0), vec![]).unwrap();
        let boundary = Boundary::of_pocket(&pocket);
        let sampling = Sampling::new(&boundary, 100.0, PI / 8.0);
        assert_eq!(sampling.len(), 16);
        for s in &sampling.loops[0] {
            assert!((s.point.distance_mm(Point::new(0.0, 0.0)) - 1.0).abs() < TOL_MM);
        }
    }

    #[test]
    fn a_split_piece_gets_its_middle_on_the_true_arc() {
        let pocket = Pocket::new(Loop::circle(0.0, 0.0, 1.0), vec![]).unwrap();
        let boundary = Boundary::of_pocket(&pocket);
        let mut sampling = Sampling::new(&boundary, 100.0, PI / 2.0);
        let last = sampling.loops[0].len() - 1;
        let pieces = BTreeSet::from([(0, 0), (0, last)]);
        assert_eq!(sampling.split(&boundary, &pieces, 1e-3), 2);
        let s = &sampling.loops[0];
        assert_eq!(s.len(), 6);
        assert!(s[1].point.near(Point::new((PI / 4.0).cos(), (PI / 4.0).sin()), TOL_MM));
        assert!(s[5].point.near(Point::new((PI / 4.0).cos(), -(PI / 4.0).sin()), TOL_MM));
    }
}
