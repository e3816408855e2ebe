//! Helpers of the pocketing tests: specs, the path's cutting moves as segments, distances to
//! the wall, continuity.

use super::PocketingSpec;
use crate::core::geometry::{Loop, Pocket, Point, Segment};
use crate::core::toolpath::{Motion, Move, Toolpath};
use std::f64::consts::TAU;

/// The cutting level of the tests (mm): a 5 mm deep layer from z = 0.
pub const Z_MM: f64 = -5.0;
/// Moves closer than this in z are at the same level, and points closer than this are the
/// same point (mm).
pub const SAME_MM: f64 = 1e-9;
/// Spacing of the points sampled along the moves (mm).
pub const SAMPLE_MM: f64 = 0.02;

/// A spec for a tool of radius `r_mm` at step-over `rd_mm`, climb, no allowance.
pub fn spec(r_mm: f64, rd_mm: f64) -> PocketingSpec {
    PocketingSpec {
        tool_radius_mm: r_mm,
        radial_depth_mm: rd_mm,
        allowance_mm: 0.0,
        z_mm: Z_MM,
        safe_z_mm: 5.0,
        feed_mm_min: 1000.0,
        plunge_feed_mm_min: 300.0,
        spindle_rpm: 9600.0,
        climb: true,
        corner_loops: false,
    }
}

/// The pocket of `loops` (validated).
pub fn pocket(outer: Loop, islands: Vec<Loop>) -> Pocket {
    Pocket::new(outer, islands).unwrap()
}

/// The `border.dxf` drawing of the shared data as a pocket.
pub fn border_dxf() -> Pocket {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/border.dxf");
    let text = std::fs::read_to_string(path).unwrap();
    crate::core::geometry::pocket_from_loops(crate::core::geometry::loops_from_dxf(&text).unwrap()).unwrap()
}

/// A feed move in the XY plane at the cutting level as a segment (an arc with its bulge).
pub fn segment_of(m: &Move) -> Segment {
    let (s, e) = (Point::new(m.start.x, m.start.y), Point::new(m.end.x, m.end.y));
    match m.motion {
        Motion::Arc { center, clockwise, .. } => {
            let (a0, a1) = ((s.y - center.y).atan2(s.x - center.x), (e.y - center.y).atan2(e.x - center.x));
            let sweep = if clockwise { -(a0 - a1).rem_euclid(TAU) } else { (a1 - a0).rem_euclid(TAU) };
            Segment::new(s, e, (sweep / 4.0).tan())
        }
        _ => Segment::line(s, e),
    }
}

/// The feed moves at the cutting level (loops and links), in path order, with their moves.
pub fn cutting_moves(path: &Toolpath) -> Vec<(&Move, Segment)> {
    path.moves
        .iter()
        .filter(|m| {
            !matches!(m.motion, Motion::Rapid) && (m.start.z - Z_MM).abs() < SAME_MM && (m.end.z - Z_MM).abs() < SAME_MM
        })
        .map(|m| (m, segment_of(m)))
        .collect()
}

/// Points along `seg` no further than [`SAMPLE_MM`] apart, both ends included.
pub fn samples(seg: &Segment) -> impl Iterator<Item = Point> + '_ {
    let n = (seg.length_mm() / SAMPLE_MM).ceil().max(1.0) as usize;
    (0..=n).map(move |k| seg.point_at(k as f64 / n as f64))
}

/// Distance from `p` to the nearest wall of `pocket` (outer loop or island) (mm).
pub fn wall_distance_mm(pocket: &Pocket, p: Point) -> f64 {
    walls(pocket).map(|s| s.distance_mm(p)).fold(f64::INFINITY, f64::min)
}

/// The nearest point of the walls of `pocket` to `p`.
pub fn nearest_wall_point(pocket: &Pocket, p: Point) -> Point {
    walls(pocket)
        .map(|s| s.point_at(s.parameter_of(p)))
        .min_by(|a, b| a.distance_mm(p).total_cmp(&b.distance_mm(p)))
        .unwrap()
}

fn walls(pocket: &Pocket) -> impl Iterator<Item = Segment> + '_ {
    std::iter::once(&pocket.outer).chain(&pocket.islands).flat_map(Loop::segments)
}

/// The smallest distance from the wall of any point sampled along the cutting moves (mm),
/// after checking that every such point lies inside the pocket.
pub fn min_wall_distance_mm(pocket: &Pocket, path: &Toolpath) -> f64 {
    let mut least = f64::INFINITY;
    for (m, seg) in cutting_moves(path) {
        for p in samples(&seg) {
            assert!(pocket.contains(p.x, p.y), "line {}: {p:?} is outside the pocket", m.line);
            least = least.min(wall_distance_mm(pocket, p));
        }
    }
    least
}

/// Panics unless every move starts where the one before ended and every arc's centre is as
/// far from its start as from its end.
pub fn assert_continuous(path: &Toolpath) {
    for pair in path.moves.windows(2) {
        let (a, b) = (pair[0].end, pair[1].start);
        let gap = (a.x - b.x).hypot(a.y - b.y).hypot(a.z - b.z);
        assert!(gap < SAME_MM, "line {} starts {gap} mm from where line {} ended", pair[1].line, pair[0].line);
    }
    for m in &path.moves {
        if let Motion::Arc { center, .. } = m.motion {
            let rs = (m.start.x - center.x).hypot(m.start.y - center.y);
            let re = (m.end.x - center.x).hypot(m.end.y - center.y);
            assert!((rs - re).abs() < 1e-6, "line {}: radii {rs} and {re}", m.line);
        }
    }
}

/// The direction of travel of `seg` at its midpoint (unit vector).
pub fn direction_at_midpoint(seg: &Segment) -> (f64, f64) {
    match seg.circle() {
        Some((c, _)) => {
            let (dx, dy) = c.vector_to(seg.midpoint());
            let len = dx.hypot(dy);
            // Counter-clockwise travel turns the radius vector a quarter left.
            if seg.bulge > 0.0 {
                (-dy / len, dx / len)
            } else {
                (dy / len, -dx / len)
            }
        }
        None => {
            let (dx, dy) = seg.start.vector_to(seg.end);
            let len = dx.hypot(dy);
            (dx / len, dy / len)
        }
    }
}
