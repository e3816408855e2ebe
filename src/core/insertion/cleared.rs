//! Where the trochoids have already removed the material, and the contour-parallel path cut
//! there and re-linked (seed 004 §2.2: trochoids are inserted *on* the contour-parallel
//! paths, which then skip what the trochoids removed).
//!
//! A trochoid loop of radius `ρ ≤ r` about `c` sweeps the whole disc of radius `ρ + r`; the
//! tool is wholly in cleared space wherever its centre lies within `ρ` of a loop centre. The
//! base path's horizontal feed moves at a treated level are split into air and material
//! pieces by that test; a run of air longer than [`MIN_AIR_RUN_RADII`] tool radii is replaced
//! by a straight feed move where that chord is itself in the air, by a hop over it (retract,
//! rapid, plunge in the air) where that is quicker than feeding along it, and kept otherwise.
//! Whatever is fed through the air (kept runs and straight links) goes at the air feed.

use super::cleared_zone::{AirLookup, ClearedZone};
use crate::core::feed::split::sub_move;
use crate::core::geometry::Point;
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Move, P3};

/// Spacing of the air test along a move, mm.
pub const AIR_TEST_STEP_MM: f64 = 0.1;

/// Air runs shorter than this many tool radii are left as they are.
pub const MIN_AIR_RUN_RADII: f64 = 2.0;

/// Heights closer than this are the same level, mm.
pub const SAME_LEVEL_MM: f64 = 1e-6;

/// How the trimmed path moves between the pieces it keeps.
#[derive(Debug, Clone, Copy)]
pub struct Relink {
    /// The level the trimming applies to, mm.
    pub z_mm: f64,
    /// Height of the hops, mm.
    pub hop_z_mm: f64,
    pub rapid_mm_min: f64,
    pub plunge_feed_mm_min: f64,
    /// Feed of the moves kept or written in the air, mm/min.
    pub air_feed_mm_min: f64,
    pub tool_radius_mm: f64,
}

/// What the trimming did.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct TrimReport {
    /// Length of the base path's feed moves left out, mm.
    pub removed_mm: f64,
    /// Straight links and hops written in their place.
    pub links: usize,
    pub hops: usize,
}

fn xy(p: P3) -> Point {
    Point::new(p.x, p.y)
}

fn same_point(a: P3, b: P3) -> bool {
    (a.x - b.x).abs() <= SAME_LEVEL_MM && (a.y - b.y).abs() <= SAME_LEVEL_MM && (a.z - b.z).abs() <= SAME_LEVEL_MM
}

fn is_level_feed(m: &Move, z: f64) -> bool {
    !matches!(m.motion, Motion::Rapid)
        && (m.start.z - z).abs() <= SAME_LEVEL_MM
        && (m.end.z - z).abs() <= SAME_LEVEL_MM
        && !matches!(m.motion, Motion::Arc { plane, .. } if plane != crate::core::toolpath::Plane::Xy)
}

/// `true` when every point of the segment `a`–`b` is air in `zone` (tested every
/// [`AIR_TEST_STEP_MM`]).
fn chord_is_air(zone: &ClearedZone, a: Point, b: Point) -> bool {
    let n = (a.distance_mm(b) / AIR_TEST_STEP_MM).ceil().max(1.0) as usize;
    let mut lookup = AirLookup::new(zone);
    (0..=n).all(|i| {
        let t = i as f64 / n as f64;
        lookup.is_air(Point::new(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t))
    })
}

/// Splits a level feed move into pieces, each tagged `true` when it is all air.
fn split_by_air(m: &Move, zone: &ClearedZone) -> Vec<(Move, bool)> {
    let len = move_length(m);
    let n = (len / AIR_TEST_STEP_MM).ceil().max(1.0) as usize;
    let points = crate::core::analysis::sampling::MovePoints::of(m);
    let mut lookup = AirLookup::new(zone);
    let air: Vec<bool> = (0..=n)
        .map(|i| {
            let (p, _) = points.at(i as f64 / n as f64);
            lookup.is_air(xy(p))
        })
        .collect();
    // Step j (from sample j to j + 1) is air when both its ends are; a piece is a run of
    // steps of one kind.
    let step_air = |j: usize| air[j] && air[j + 1];
    let mut pieces = Vec::new();
    let mut start = 0;
    for j in 1..=n {
        if j == n || step_air(j) != step_air(start) {
            pieces.push((sub_move(m, start as f64 / n as f64, j as f64 / n as f64), step_air(start)));
            start = j;
        }
    }
    pieces
}

/// The moves of `path` with the air runs at `relink.z_mm` left out and re-linked.
pub fn trim_path(path: &[Move], zone: &ClearedZone, relink: &Relink) -> (Vec<Move>, TrimReport) {
    let mut out: Vec<Move> = Vec::with_capacity(path.len());
    let mut report = TrimReport::default();
    let mut run: Vec<Move> = Vec::new();
    let flush = |run: &mut Vec<Move>, out: &mut Vec<Move>, report: &mut TrimReport, at_end: bool| {
        if run.is_empty() {
            return;
        }
        let length: f64 = run.iter().map(move_length).sum();
        let (a, b) = (run[0].start, run[run.len() - 1].end);
        let template = run[0];
        let feed = relink.air_feed_mm_min;
        // What stays of the run cuts nothing: it goes at the air feed.
        run.iter_mut().for_each(|m| m.feed_mm_min = Some(feed));
        if length < MIN_AIR_RUN_RADII * relink.tool_radius_mm && !at_end {
            out.append(run);
            return;
        }
        report.removed_mm += length;
        if at_end {
            run.clear();
            return;
        }
        let chord = xy(a).distance_mm(xy(b));
        let hop_time = 2.0 * (relink.hop_z_mm - relink.z_mm) / relink.rapid_mm_min
            + chord / relink.rapid_mm_min
            + (relink.hop_z_mm - relink.z_mm) / relink.plunge_feed_mm_min;
        if chord_is_air(zone, xy(a), xy(b)) && chord / feed <= hop_time {
            out.push(Move { motion: Motion::Linear, start: a, end: b, feed_mm_min: Some(feed), ..template });
            report.links += 1;
            report.removed_mm -= chord;
        } else if hop_time < length / feed {
            let up = P3::new(a.x, a.y, relink.hop_z_mm);
            let over = P3::new(b.x, b.y, relink.hop_z_mm);
            out.push(Move { motion: Motion::Rapid, start: a, end: up, feed_mm_min: template.feed_mm_min, ..template });
            out.push(Move { motion: Motion::Rapid, start: up, end: over, ..template });
            out.push(Move {
                motion: Motion::Linear,
                start: over,
                end: b,
                feed_mm_min: Some(relink.plunge_feed_mm_min),
                ..template
            });
            report.hops += 1;
        } else {
            report.removed_mm -= length;
            out.append(run);
        }
        run.clear();
    };
    for m in path {
        if !is_level_feed(m, relink.z_mm) {
            // A run ending in a retract is air to the end of the cut.
            let at_end = matches!(m.motion, Motion::Rapid) && m.end.z > m.start.z;
            flush(&mut run, &mut out, &mut report, at_end);
            match out.last().map(|l| l.end) {
                Some(here) if !same_point(here, m.start) => {
                    // The run before the retract was left out: retract where the cut ended.
                    let up = P3::new(here.x, here.y, m.end.z);
                    out.push(Move { motion: Motion::Rapid, start: here, end: up, ..*m });
                    out.push(Move { motion: Motion::Rapid, start: up, end: m.end, ..*m });
                }
                _ => out.push(*m),
            }
            continue;
        }
        for (piece, air) in split_by_air(m, zone) {
            if air {
                run.push(piece);
            } else {
                flush(&mut run, &mut out, &mut report, false);
                out.push(piece);
            }
        }
    }
    flush(&mut run, &mut out, &mut report, true);
    (out, report)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A feed fast enough that feeding 40 mm through the air beats a hop.
    const FAST_FEED_MM_MIN: f64 = 5000.0;

    fn line(a: (f64, f64), b: (f64, f64), z: f64) -> Move {
        Move {
            motion: Motion::Linear,
            start: P3::new(a.0, a.1, z),
            end: P3::new(b.0, b.1, z),
            feed_mm_min: Some(FAST_FEED_MM_MIN),
            spindle_rpm: Some(9600.0),
            tool: None,
            line: 1,
        }
    }

    fn relink() -> Relink {
        Relink {
            z_mm: -5.0,
            hop_z_mm: 1.0,
            rapid_mm_min: 20_000.0,
            plunge_feed_mm_min: 300.0,
            air_feed_mm_min: FAST_FEED_MM_MIN,
            tool_radius_mm: 5.0,
        }
    }

    #[test]
    fn a_move_through_a_cleared_disc_loses_the_part_inside_and_is_relinked_straight() {
        let mut zone = ClearedZone::new(5.0);
        zone.add(Point::new(50.0, 0.0), 20.0);
        let path = [line((0.0, 0.0), (100.0, 0.0), -5.0)];
        let (out, report) = trim_path(&path, &zone, &relink());
        // Cut to 30, a straight link 30 → 70 through the air (it is the same line), cut on.
        let total: f64 = out.iter().map(move_length).sum();
        assert!((total - 100.0).abs() < 1e-6, "{out:?}");
        assert_eq!(report.links, 1);
        assert!(out.iter().all(|m| m.start.z == -5.0));
    }

    #[test]
    fn a_detour_through_the_air_is_replaced_by_its_chord() {
        let mut zone = ClearedZone::new(5.0);
        zone.add(Point::new(0.0, 0.0), 30.0);
        let path = [
            line((-40.0, 0.0), (-20.0, 0.0), -5.0),
            line((-20.0, 0.0), (0.0, 20.0), -5.0),
            line((0.0, 20.0), (20.0, 0.0), -5.0),
            line((20.0, 0.0), (40.0, 0.0), -5.0),
        ];
        let (out, report) = trim_path(&path, &zone, &relink());
        let total: f64 = out.iter().map(move_length).sum();
        assert!(total < 80.0 + 1e-6 && report.links == 1 && report.removed_mm > 0.0, "{out:?}");
        for w in out.windows(2) {
            assert!(w[0].end.x == w[1].start.x && w[0].end.y == w[1].start.y && w[0].end.z == w[1].start.z);
        }
    }

    #[test]
    fn a_long_air_run_at_a_slow_air_feed_is_hopped_over() {
        let mut zone = ClearedZone::new(5.0);
        zone.add(Point::new(50.0, 0.0), 20.0);
        let slow = Move { feed_mm_min: Some(500.0), ..line((0.0, 0.0), (100.0, 0.0), -5.0) };
        let (out, report) = trim_path(&[slow], &zone, &Relink { air_feed_mm_min: 500.0, ..relink() });
        assert_eq!(report.hops, 1);
        assert!(out.iter().any(|m| matches!(m.motion, Motion::Rapid) && m.end.z == 1.0));
        let last = out.last().unwrap();
        assert!(last.end.x == 100.0 && last.feed_mm_min == Some(500.0), "{out:?}");
    }

    #[test]
    fn what_is_fed_through_the_air_goes_at_the_air_feed_and_the_cut_at_its_own() {
        let mut zone = ClearedZone::new(5.0);
        zone.add(Point::new(50.0, 0.0), 20.0);
        let cut = Move { feed_mm_min: Some(1000.0), ..line((0.0, 0.0), (100.0, 0.0), -5.0) };
        let (out, report) = trim_path(&[cut], &zone, &relink());
        assert_eq!(report.links, 1);
        let feed_at = |x: f64| out.iter().find(|m| m.start.x <= x && x < m.end.x).and_then(|m| m.feed_mm_min);
        assert_eq!(feed_at(10.0), Some(1000.0));
        assert_eq!(feed_at(50.0), Some(FAST_FEED_MM_MIN));
        assert_eq!(feed_at(90.0), Some(1000.0));
    }

    #[test]
    fn moves_at_another_level_are_kept() {
        let mut zone = ClearedZone::new(5.0);
        zone.add(Point::new(50.0, 0.0), 20.0);
        let path = [line((0.0, 0.0), (100.0, 0.0), -10.0)];
        let (out, report) = trim_path(&path, &zone, &relink());
        assert_eq!(out.len(), 1);
        assert_eq!(report, TrimReport::default());
    }
}
