//! A raster of the pocket at the bottom of the layer: which treatment removed each cell first,
//! and which cells the tool can reach at all (the pocket "opened" by the tool: within `r` of a
//! centre position whose clearance is at least `r + allowance`). It gives the area each
//! treatment removes and the check that nothing reachable is left.

use super::distance_transform::squared_distance_transform;
use crate::core::analysis::sampling::{point_on, MovePoints};
use crate::core::geometry::{Pocket, Point};
use crate::core::medial::Boundary;
use crate::core::stock::{ArcSweep, Capsule, MAX_ARC_SWEEP_RAD};
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Move, Plane};
use std::f64::consts::{PI, TAU};

/// Cells per tool radius of the coverage raster.
pub const CELLS_PER_RADIUS: f64 = 25.0;

/// Most cells of the coverage raster; beyond it the cell grows.
pub const MAX_CELLS: usize = 4_000_000;

/// The chords that sweep an arc depart from it by at most this share of a cell.
pub const CHORD_SAGITTA_CELLS: f64 = 0.25;

/// Cells per side of the blocks whose clearances are measured against the same few boundary
/// segments (see [`Coverage::new`]).
const CLEARANCE_BLOCK_CELLS: usize = 16;

/// Slack on the reach within which a block's boundary segments are gathered, for rounding, mm.
const CLEARANCE_REACH_MARGIN_MM: f64 = 1e-9;

/// Owner of a cell nothing removed.
pub const NOBODY: u16 = u16::MAX;

/// The pocket's raster.
#[derive(Clone)]
pub struct Coverage {
    x0: f64,
    y0: f64,
    pub cell_mm: f64,
    w: usize,
    h: usize,
    inside: Vec<bool>,
    /// Clearance of each cell centre (0 outside the pocket), mm.
    clearance: Vec<f64>,
    pub owner: Vec<u16>,
}

impl Coverage {
    /// The raster of `pocket` for a tool of radius `r_mm`.
    pub fn new(pocket: &Pocket, boundary: &Boundary, r_mm: f64) -> Coverage {
        let b = pocket.bounds();
        let mut cell = r_mm / CELLS_PER_RADIUS;
        while (b.width_mm() / cell).ceil() * (b.height_mm() / cell).ceil() > MAX_CELLS as f64 {
            cell *= 1.25;
        }
        let (w, h) = ((b.width_mm() / cell).ceil() as usize + 1, (b.height_mm() / cell).ceil() as usize + 1);
        let mut c = Coverage {
            x0: b.x_min,
            y0: b.y_min,
            cell_mm: cell,
            w,
            h,
            inside: vec![false; w * h],
            clearance: vec![0.0; w * h],
            owner: vec![NOBODY; w * h],
        };
        c.mark_inside(pocket);
        c.measure_clearance(boundary);
        c
    }

    /// Marks the cells whose centres lie inside the pocket, a row at a time: a centre lies
    /// inside a loop when an odd number of the row's crossings with it lie beyond it, as
    /// [`crate::core::geometry::Loop::contains`] counts them.
    fn mark_inside(&mut self, pocket: &Pocket) {
        let mut crossings = Vec::new();
        let mut parity = vec![false; self.w];
        for j in 0..self.h {
            let y = self.centre(0, j).y;
            let row = &mut self.inside[j * self.w..(j + 1) * self.w];
            for (k, lp) in std::iter::once(&pocket.outer).chain(&pocket.islands).enumerate() {
                crossings.clear();
                lp.row_crossings(y, &mut crossings);
                crossings.sort_unstable_by(f64::total_cmp);
                let mut at_or_before = 0;
                for (i, odd) in parity.iter_mut().enumerate() {
                    let x = self.x0 + (i as f64 + 0.5) * self.cell_mm;
                    while at_or_before < crossings.len() && crossings[at_or_before] <= x {
                        at_or_before += 1;
                    }
                    *odd = (crossings.len() - at_or_before) % 2 == 1;
                }
                for (cell, odd) in row.iter_mut().zip(&parity) {
                    // Inside the outer loop and outside every island.
                    *cell = if k == 0 { *odd } else { *cell && !*odd };
                }
            }
        }
    }

    /// The exact clearance of every cell centre inside the pocket, a block of cells at a
    /// time: only the boundary segments that can be nearest to some cell of the block (see
    /// [`Boundary::segments_within`]) are measured.
    fn measure_clearance(&mut self, boundary: &Boundary) {
        let mut near = Vec::new();
        for bj in (0..self.h).step_by(CLEARANCE_BLOCK_CELLS) {
            let rows = bj..(bj + CLEARANCE_BLOCK_CELLS).min(self.h);
            for bi in (0..self.w).step_by(CLEARANCE_BLOCK_CELLS) {
                let columns = bi..(bi + CLEARANCE_BLOCK_CELLS).min(self.w);
                if !rows
                    .clone()
                    .any(|j| self.inside[j * self.w + columns.start..j * self.w + columns.end].contains(&true))
                {
                    continue;
                }
                let (first, last) = (self.centre(bi, bj), self.centre(columns.end - 1, rows.end - 1));
                let middle = Point::new(0.5 * (first.x + last.x), 0.5 * (first.y + last.y));
                let half_diagonal = 0.5 * (last.x - first.x).hypot(last.y - first.y);
                let reach = boundary.clearance_mm(middle) + 2.0 * half_diagonal + CLEARANCE_REACH_MARGIN_MM;
                boundary.segments_within(middle, reach, &mut near);
                for j in rows.clone() {
                    for i in columns.clone() {
                        if self.inside[j * self.w + i] {
                            self.clearance[j * self.w + i] =
                                boundary.clearance_among(self.centre(i, j), near.iter().copied());
                        }
                    }
                }
            }
        }
    }

    fn centre(&self, i: usize, j: usize) -> Point {
        Point::new(self.x0 + (i as f64 + 0.5) * self.cell_mm, self.y0 + (j as f64 + 0.5) * self.cell_mm)
    }

    /// Marks the cells within `r_mm` of `c` as removed by `owner` unless already removed (the
    /// reference the swept capsules are tested against).
    #[cfg(test)]
    pub fn stamp(&mut self, c: Point, r_mm: f64, owner: u16) {
        let j0 = (((c.y - r_mm - self.y0) / self.cell_mm).floor().max(0.0)) as usize;
        let j1 = (((c.y + r_mm - self.y0) / self.cell_mm).ceil().max(0.0) as usize).min(self.h);
        for j in j0..j1 {
            let y = self.y0 + (j as f64 + 0.5) * self.cell_mm;
            let dy = y - c.y;
            let half2 = r_mm * r_mm - dy * dy;
            if half2 < 0.0 {
                continue;
            }
            let half = half2.sqrt();
            let i0 = ((c.x - half - self.x0) / self.cell_mm - 0.5).ceil().max(0.0) as usize;
            let i1 = (((c.x + half - self.x0) / self.cell_mm - 0.5).floor() + 1.0).max(0.0) as usize;
            for o in &mut self.owner[j * self.w + i0.min(self.w)..j * self.w + i1.min(self.w)] {
                if *o == NOBODY {
                    *o = owner;
                }
            }
        }
    }

    /// Marks the cells whose centres lie within `r_mm` of the segment `a`–`b` (the tool swept
    /// along it) as removed by `owner` unless already removed.
    pub fn stamp_capsule(&mut self, a: Point, b: Point, r_mm: f64, owner: u16) {
        let capsule = Capsule::new((a.x, a.y), (b.x, b.y), r_mm);
        for j in self.rows_between(a.y.min(b.y) - r_mm, a.y.max(b.y) + r_mm) {
            let y = self.y0 + (j as f64 + 0.5) * self.cell_mm;
            if let Some((x_lo, x_hi)) = capsule.row_interval(y) {
                self.fill_row(j, x_lo, x_hi, owner);
            }
        }
    }

    /// Marks the cells whose centres lie within `r_mm` of the arc of `sweep` (the tool swept
    /// along it; at most [`MAX_ARC_SWEEP_RAD`] of it) as removed by `owner` unless already
    /// removed.
    fn stamp_arc(&mut self, sweep: &ArcSweep, r_mm: f64, owner: u16) {
        let (_, (y_lo, y_hi)) = sweep.bounds(r_mm);
        for j in self.rows_between(y_lo, y_hi) {
            let y = self.y0 + (j as f64 + 0.5) * self.cell_mm;
            for (x_lo, x_hi) in sweep.row_inside(y, r_mm).iter() {
                self.fill_row(j, x_lo, x_hi, owner);
            }
        }
    }

    /// The rows whose centres lie between `y_lo` and `y_hi`.
    fn rows_between(&self, y_lo: f64, y_hi: f64) -> std::ops::Range<usize> {
        let j0 = (((y_lo - self.y0) / self.cell_mm - 0.5).ceil().max(0.0)) as usize;
        let j1 = ((((y_hi - self.y0) / self.cell_mm - 0.5).floor() + 1.0).max(0.0) as usize).min(self.h);
        j0..j1.max(j0)
    }

    /// Marks the cells of row `j` whose centres lie between `x_lo` and `x_hi` as removed by
    /// `owner` unless already removed.
    fn fill_row(&mut self, j: usize, x_lo: f64, x_hi: f64, owner: u16) {
        let i0 = ((x_lo - self.x0) / self.cell_mm - 0.5).ceil().max(0.0) as usize;
        let i1 = (((x_hi - self.x0) / self.cell_mm - 0.5).floor() + 1.0).max(0.0) as usize;
        let (i0, i1) = (i0.min(self.w), i1.min(self.w));
        // (A select, not a branch: it runs many cells a step.)
        for o in &mut self.owner[j * self.w + i0..j * self.w + i1.max(i0)] {
            *o = if *o == NOBODY { owner } else { *o };
        }
    }

    /// Stamps the tool along the moves of `moves` that reach down to `z_max_mm`. One owner
    /// takes them all, so their order does not matter: a straight move at the level is swept
    /// as one capsule, an arc in XY at the level as the exact area swept along it (a quarter
    /// turn at a time), other arcs in chords whose sagitta is at most [`CHORD_SAGITTA_CELLS`]
    /// of a cell, and a move crossing the level as capsules every half cell where it is below.
    pub fn stamp_moves(&mut self, moves: &[Move], r_mm: f64, z_max_mm: f64, owner: u16) {
        let fine = 0.5 * self.cell_mm;
        let mut k = 0;
        while k < moves.len() {
            // A trochoid loop (its cutting and return halves about one centre) closes a
            // circle: the tool sweeps the ring about it, stamped row by row at once.
            if let Some((circle, moves_taken)) = closed_circle(&moves[k..], z_max_mm) {
                self.stamp_ring(circle, r_mm, owner);
                k += moves_taken;
                continue;
            }
            let m = &moves[k];
            k += 1;
            let (start_below, end_below) = (m.start.z <= z_max_mm, m.end.z <= z_max_mm);
            if !start_below && !end_below {
                continue;
            }
            let length = move_length(m);
            let step = match m.motion {
                _ if !(start_below && end_below) => fine,
                Motion::Arc { center, clockwise, plane: Plane::Xy, turns } => {
                    // The turn, bounded by the whole turns the move may make.
                    let radius = (m.start.x - center.x).hypot(m.start.y - center.y);
                    let sweep_rad = (length / radius).min(TAU * f64::from(turns.saturating_add(1)));
                    self.stamp_arc_move(m, (center.x, center.y), !clockwise, sweep_rad, r_mm, owner);
                    continue;
                }
                Motion::Arc { center, .. } => {
                    let radius = (m.start.x - center.x).hypot(m.start.y - center.y);
                    (8.0 * radius * CHORD_SAGITTA_CELLS * self.cell_mm).sqrt().max(fine)
                }
                _ => f64::INFINITY,
            };
            let n = (length / step).ceil().max(1.0) as usize;
            let mut previous: Option<Point> = None;
            let points = MovePoints::of(m);
            for k in 0..=n {
                let (p, _) = points.at(k as f64 / n as f64);
                let here = Point::new(p.x, p.y);
                if p.z > z_max_mm {
                    previous = None;
                    continue;
                }
                self.stamp_capsule(previous.unwrap_or(here), here, r_mm, owner);
                previous = Some(here);
            }
        }
    }

    /// Marks the cells whose centres lie within `r_mm` of the circle `(centre, radius)` (the
    /// ring the tool sweeps going round it) as removed by `owner` unless already removed.
    fn stamp_ring(&mut self, ((cx, cy), radius): Circle, r_mm: f64, owner: u16) {
        let (outer, inner) = (radius + r_mm, radius - r_mm);
        for j in self.rows_between(cy - outer, cy + outer) {
            let dy = self.y0 + (j as f64 + 0.5) * self.cell_mm - cy;
            let half = (outer * outer - dy * dy).max(0.0).sqrt();
            // The hole in the ring's middle, where the circle is wider than the tool.
            let hole = if inner > 0.0 && dy.abs() < inner { (inner * inner - dy * dy).sqrt() } else { 0.0 };
            if hole > 0.0 {
                self.fill_row(j, cx - half, cx - hole, owner);
                self.fill_row(j, cx + hole, cx + half, owner);
            } else {
                self.fill_row(j, cx - half, cx + half, owner);
            }
        }
    }

    /// Stamps the tool along the arc move `m` in XY about `center`, counter-clockwise when
    /// `ccw`, in pieces of at most [`MAX_ARC_SWEEP_RAD`] (`sweep_rad` bounds its turn from
    /// above: a helix's length over its radius).
    fn stamp_arc_move(&mut self, m: &Move, center: (f64, f64), ccw: bool, sweep_rad: f64, r_mm: f64, owner: u16) {
        let pieces = if sweep_rad.is_finite() { (sweep_rad / MAX_ARC_SWEEP_RAD).ceil().max(1.0) as usize } else { 1 };
        let mut previous = (m.start.x, m.start.y);
        for k in 1..=pieces {
            let (p, _) = point_on(m, k as f64 / pieces as f64);
            let here = (p.x, p.y);
            self.stamp_arc(&ArcSweep::new(center, previous, here, ccw), r_mm, owner);
            previous = here;
        }
    }

    /// Area of the pocket removed by `owner`, mm².
    pub fn area_of(&self, owner: u16) -> f64 {
        let n = self.owner.iter().zip(&self.inside).filter(|(o, i)| **i && **o == owner).count();
        n as f64 * self.cell_mm * self.cell_mm
    }

    /// Area of the pocket, mm² (by cells).
    pub fn pocket_area(&self) -> f64 {
        self.inside.iter().filter(|i| **i).count() as f64 * self.cell_mm * self.cell_mm
    }

    /// Cells the tool can reach (`r_mm`, `allowance_mm`) that are farther than the allowance
    /// plus `tol_mm` from the walls and that nothing removed: their area (mm²) and the centre
    /// of one of them.
    pub fn left_over(&self, r_mm: f64, allowance_mm: f64, tol_mm: f64) -> (f64, Option<Point>) {
        let sources: Vec<bool> =
            self.clearance.iter().zip(&self.inside).map(|(c, i)| *i && *c >= r_mm + allowance_mm).collect();
        let d2 = squared_distance_transform(&sources, self.w, self.h);
        let reach = (r_mm - tol_mm) / self.cell_mm;
        let mut area = 0.0;
        let mut example = None;
        for j in 0..self.h {
            for i in 0..self.w {
                let k = j * self.w + i;
                if self.inside[k]
                    && self.owner[k] == NOBODY
                    && self.clearance[k] > allowance_mm + tol_mm
                    && d2[k] <= reach * reach
                {
                    area += self.cell_mm * self.cell_mm;
                    example.get_or_insert(self.centre(i, j));
                }
            }
        }
        (area, example)
    }
}

/// A circle in XY: its centre and radius, mm.
type Circle = ((f64, f64), f64);

/// Ends of arcs closing a circle may lie this far apart, and their centres and radii
/// differ by this much, mm (a program's rounding of a loop's coordinates is coarser).
const CLOSED_CIRCLE_TOLERANCE_MM: f64 = 1e-9;

/// The circle (centre and radius) that the first moves of `moves` go round, and how many
/// moves they are: arcs in XY one after the other, about one centre with one radius in one
/// direction, all at one height at `z_max_mm` or below, that turn a whole turn or more
/// together, or end where the first starts having turned more than half a turn (then a
/// whole one: they go round one way). Along them the tool sweeps the ring about the circle,
/// as along its pieces one by one. `None` when the first moves go round no circle.
fn closed_circle(moves: &[Move], z_max_mm: f64) -> Option<(Circle, usize)> {
    let first = moves.first()?;
    let Motion::Arc { center, clockwise, plane: Plane::Xy, .. } = first.motion else {
        return None;
    };
    let near = |a: f64, b: f64| (a - b).abs() <= CLOSED_CIRCLE_TOLERANCE_MM;
    let radius = (first.start.x - center.x).hypot(first.start.y - center.y);
    let level = first.start.z;
    let on_circle = |m: &Move| match m.motion {
        Motion::Arc { center: c, clockwise: cw, plane: Plane::Xy, .. } => {
            cw == clockwise
                && near(c.x, center.x)
                && near(c.y, center.y)
                && near((m.start.x - c.x).hypot(m.start.y - c.y), radius)
                && near(m.start.z, level)
                && near(m.end.z, level)
        }
        _ => false,
    };
    // (NaN is no radius.)
    if level > z_max_mm || radius.is_nan() || radius <= 0.0 {
        return None;
    }
    let closes = |m: &Move| near(m.end.x, first.start.x) && near(m.end.y, first.start.y);
    let mut turned_rad = 0.0;
    for (n, m) in moves.iter().enumerate() {
        if !on_circle(m) {
            return None;
        }
        turned_rad += move_length(m) / radius;
        if turned_rad >= TAU || (closes(m) && turned_rad > PI) {
            return Some((((center.x, center.y), radius), n + 1));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::Loop;

    #[test]
    fn cells_inside_and_their_clearances_are_exactly_those_of_the_pocket_point_by_point() {
        use crate::core::geometry::Vertex;
        let outer = crate::core::fixtures::case_study_pocket().outer;
        let island = Loop::new(vec![Vertex::new(32.0, 35.0, 1.0), Vertex::new(48.0, 35.0, 1.0)]);
        let square = Loop::rectangle(60.0, 20.0, 70.0, 50.0);
        let pocket = Pocket::new(outer, vec![island, square]).expect("a valid pocket");
        let boundary = Boundary::of_pocket(&pocket);
        for r in [3.0, 5.0, 8.0] {
            let c = Coverage::new(&pocket, &boundary, r);
            let mut inside = 0;
            for j in 0..c.h {
                for i in 0..c.w {
                    let (p, k) = (c.centre(i, j), j * c.w + i);
                    assert_eq!(c.inside[k], pocket.contains(p.x, p.y), "cell ({i}, {j})");
                    if c.inside[k] {
                        inside += 1;
                        assert_eq!(c.clearance[k].to_bits(), boundary.clearance_mm(p).to_bits(), "cell ({i}, {j})");
                    }
                }
            }
            assert!(inside > c.w * c.h / 2, "{inside} of {} cells inside", c.w * c.h);
        }
    }

    #[test]
    fn moves_swept_as_capsules_cover_what_discs_stamped_every_half_cell_cover() {
        use crate::core::toolpath::P3;
        let pocket = crate::core::fixtures::rounded_box(40.0, 30.0, 6.0);
        let boundary = Boundary::of_pocket(&pocket);
        let r = 5.0;
        let arc = |start: P3, end: P3, center: P3| Move {
            motion: Motion::Arc { center, clockwise: false, plane: crate::core::toolpath::Plane::Xy, turns: 1 },
            start,
            end,
            feed_mm_min: Some(1000.0),
            spindle_rpm: None,
            tool: None,
            line: 0,
        };
        let line = |start: P3, end: P3| Move { motion: Motion::Linear, ..arc(start, end, start) };
        let moves = vec![
            line(P3::new(6.0, 6.0, 5.0), P3::new(6.0, 6.0, -5.0)),
            line(P3::new(6.0, 6.0, -5.0), P3::new(30.0, 8.0, -5.0)),
            arc(P3::new(30.0, 8.0, -5.0), P3::new(31.0, 9.0, -5.0), P3::new(30.0, 9.0, -5.0)),
            arc(P3::new(31.0, 9.0, -5.0), P3::new(20.0, 20.0, -5.0), P3::new(20.0, 9.0, -5.0)),
            line(P3::new(20.0, 20.0, -5.0), P3::new(12.0, 24.0, -2.0)),
        ];
        let mut swept = Coverage::new(&pocket, &boundary, r);
        swept.stamp_moves(&moves, r, -5.0 + 1e-6, 0);
        let mut stamped = Coverage::new(&pocket, &boundary, r);
        for m in &moves {
            let n = (move_length(m) / (0.5 * stamped.cell_mm)).ceil().max(1.0) as usize;
            for k in 0..=n {
                let (p, _) = point_on(m, k as f64 / n as f64);
                if p.z <= -5.0 + 1e-6 {
                    stamped.stamp(Point::new(p.x, p.y), r, 0);
                }
            }
        }
        let cells = |c: &Coverage| c.owner.iter().filter(|o| **o == 0).count();
        let differ = swept.owner.iter().zip(&stamped.owner).filter(|(a, b)| a != b).count();
        assert!(cells(&stamped) > 10_000, "{}", cells(&stamped));
        assert!((differ as f64) < 0.01 * cells(&stamped) as f64, "{differ} of {} cells differ", cells(&stamped));
    }

    /// Arcs about `(cx, cy)` at z −5, counter-clockwise, from angle to angle (degrees).
    fn arcs_about(cx: f64, cy: f64, rho: f64, angles_deg: &[f64]) -> Vec<Move> {
        use crate::core::toolpath::P3;
        let at = |deg: f64| P3::new(cx + rho * deg.to_radians().cos(), cy + rho * deg.to_radians().sin(), -5.0);
        angles_deg
            .windows(2)
            .map(|w| Move {
                motion: Motion::Arc { center: P3::new(cx, cy, -5.0), clockwise: false, plane: Plane::Xy, turns: 0 },
                start: at(w[0]),
                end: at(w[1]),
                feed_mm_min: Some(1000.0),
                spindle_rpm: None,
                tool: None,
                line: 0,
            })
            .collect()
    }

    #[test]
    fn arcs_that_go_round_a_circle_stamp_the_ring_their_pieces_sweep_one_by_one() {
        let pocket = crate::core::fixtures::rounded_box(40.0, 30.0, 6.0);
        let boundary = Boundary::of_pocket(&pocket);
        let r = 5.0;
        // A trochoid loop's two halves, wider and narrower than the tool; a circle of three
        // arcs that goes round twice; arcs that stop short of a turn.
        let cases = [
            (arcs_about(20.0, 15.0, 7.3, &[-90.0, 90.0, 270.0]), true),
            (arcs_about(21.1, 14.2, 1.37, &[0.0, 180.0, 360.0]), true),
            (arcs_about(19.0, 16.0, 3.1, &[10.0, 250.0, 490.0, 730.0]), true),
            (arcs_about(20.0, 15.0, 6.0, &[0.0, 120.0, 300.0]), false),
        ];
        for (moves, closes) in cases {
            assert_eq!(closed_circle(&moves, -5.0 + 1e-6).is_some(), closes);
            let mut ring = Coverage::new(&pocket, &boundary, r);
            ring.stamp_moves(&moves, r, -5.0 + 1e-6, 0);
            let mut pieces = Coverage::new(&pocket, &boundary, r);
            for m in &moves {
                pieces.stamp_moves(std::slice::from_ref(m), r, -5.0 + 1e-6, 0);
            }
            let removed = ring.owner.iter().filter(|o| **o == 0).count();
            assert!(removed > 2_000, "{removed} cells removed");
            assert!(ring.owner == pieces.owner, "the ring's cells are not the pieces'");
        }
        // Above the level, or rising, they are no ring.
        assert!(closed_circle(&arcs_about(20.0, 15.0, 7.3, &[-90.0, 90.0, 270.0]), -6.0).is_none());
        let mut helix = arcs_about(20.0, 15.0, 7.3, &[-90.0, 90.0, 270.0]);
        helix[1].end.z = -4.0;
        assert!(closed_circle(&helix, -3.0).is_none());
    }

    #[test]
    fn a_square_swept_by_a_disc_path_leaves_only_its_corners() {
        let pocket = Pocket::new(Loop::rectangle(0.0, 0.0, 20.0, 20.0), vec![]).unwrap();
        let boundary = Boundary::of_pocket(&pocket);
        let mut c = Coverage::new(&pocket, &boundary, 5.0);
        assert!((c.pocket_area() - 400.0).abs() < 4.0);
        // Nothing cut: everything the tool can reach is left: the square but its four
        // corners beyond the tool's reach (4·(1 − π/4)·r²) and a band of the tolerance.
        let (left, _) = c.left_over(5.0, 0.0, 0.05);
        let reachable = 400.0 - 4.0 * (1.0 - std::f64::consts::PI / 4.0) * 25.0;
        assert!(left > 0.95 * reachable && left < reachable, "{left}");
        // The tool centre around the square 5 mm from the walls and through the middle.
        for k in 0..=100 {
            let t = k as f64 / 100.0 * 10.0;
            for p in [(5.0 + t, 5.0), (15.0, 5.0 + t), (15.0 - t, 15.0), (5.0, 15.0 - t), (5.0 + t, 10.0)] {
                c.stamp(Point::new(p.0, p.1), 5.0, 0);
            }
        }
        let (left, at) = c.left_over(5.0, 0.0, 0.05);
        assert!(left < 0.5, "{left} {at:?} removed {}", c.area_of(0));
        // The corners the tool cannot reach are not counted, but are not removed either.
        assert!(c.area_of(0) < 400.0 - 4.0 * (25.0 - 25.0 * std::f64::consts::PI / 4.0) + 2.0);
    }
}
