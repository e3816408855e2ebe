//! Corner loops: a circle inserted before each sharp corner of a ring so that the corner is
//! cut in two steps, first to about half its radial depth, then along the ring (seed 004
//! §3.3 and Fig. 11, after Iwabe et al. 1989, seed 004 ref. [5]).
//!
//! # Why
//!
//! Cut from the inside out, ring `k` removes the band between itself and the swept region
//! of ring `k + 1`, cut before it. Along a side that band is `Rd` deep; at a corner where
//! the ring turns towards its region by `θ`, the previous ring's corner `Q` lies on the
//! bisector `|PQ| = Rd / cos(θ/2)` from the ring's corner `P` (1.41·Rd at a right angle),
//! and the material wraps round the tool: its engagement angle jumps from the side's
//! `α = acos(1 − Rd/r)` to about `α + θ` (MODEL.md §2). The expert's CAM of seed 004 cut
//! such corners "with the half radial depth of cut" first, on a circle, "and then … again
//! along the original path".
//!
//! # The circle
//!
//! The circle is inscribed in the corner: tangent to the incoming side at `T`, `ρ·tan(θ/2)`
//! before `P`, and (for straight sides) to the outgoing side, its centre `ρ / cos(θ/2)`
//! from `P` on the bisector. Its point nearest to the corner, the apex, lies
//! `ρ·(1/cos(θ/2) − 1)` from `P`; putting it halfway between `P` and `Q` (the circle cuts
//! the corner to half its depth, the ring the other half) gives
//!
//! ```text
//! ρ = Rd / (2·(1 − cos(θ/2)))        (ρ = 1.71·Rd at a right angle, = Rd at θ = 120°)
//! ```
//!
//! The tool reaches `T` along the ring, runs the whole circle in the ring's own sense (it
//! leaves and rejoins the ring tangentially: the path stays smooth), and goes on along the
//! ring into the corner. The rest of the circle lies inside the ring, over material the
//! inner rings have already cut. Where a side is an arc, `T` is `ρ·tan(θ/2)` back along it
//! and the circle is tangent to it there: the apex is then about halfway.
//!
//! A circle is inserted only where it lies wholly inside the ring's region (the offset
//! region the ring bounds, within the first offset): it can then gouge no wall or island
//! and leaves the allowance. Where it does not fit (a ring narrower than `2ρ` near the
//! corner, a side shorter than `ρ·tan(θ/2)`), the corner is cut as before.

use super::offsets::Component;
use super::seam::{split_bulges, Nearest, MIN_SPLIT_MM};
use crate::core::geometry::{Loop, Point, Segment, Vertex};

/// Least turn of a ring, towards its region, that gets a corner loop (degrees; `assumed`).
/// At a turn `θ` the corner is `1/cos(θ/2)` times as deep as the sides and the engagement
/// rises by about `θ`: at 45° that is 8 % deeper and 45° more engagement, over the 40° by
/// which seed 004 (Fig. 10) marks a cutting region critical. Below it the half-depth circle
/// grows past `6.5·Rd` (`ρ = Rd / (2·(1 − cos 22.5°))`), longer than the rise is worth, and
/// the many small turns of a contour drawn as short chords would each get a loop.
pub const CORNER_LOOP_MIN_TURN_DEG: f64 = 45.0;

/// A corner circle is tangent to the ring: it may come this much closer to the region's
/// boundary than its radius and still count as inside (mm).
const TANGENCY_TOL_MM: f64 = 1e-6;

/// Bulge of a half circle, `tan(π/4)`: a corner circle is written as two.
const HALF_CIRCLE_BULGE: f64 = 1.0;

/// The radius of the corner loop at a turn of `turn_rad` (0 < θ < π) of a ring cut at the
/// radial depth `rd_mm` (mm): `Rd / (2·(1 − cos(θ/2)))`, the circle inscribed in the corner
/// whose apex lies halfway between the ring's corner and the previous ring's (see the module
/// documentation; seed 004 §3.3).
pub fn corner_loop_radius_mm(rd_mm: f64, turn_rad: f64) -> f64 {
    rd_mm / (2.0 * (1.0 - (0.5 * turn_rad).cos()))
}

/// One corner loop: the circle the tool runs from `start`, in the ring's sense.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerLoop {
    /// Where it leaves and rejoins the ring (mm).
    pub start: Point,
    /// Its centre (mm).
    pub center: Point,
    /// Its radius (mm).
    pub radius_mm: f64,
}

/// A ring with its corner loops written in.
#[derive(Debug, Clone)]
pub(super) struct LoopedRing {
    /// The ring; each corner loop is two half circles from and back to its start, followed
    /// by the ring's side into the corner.
    pub lp: Loop,
    /// For each segment of `lp`, the vertex where its corner loop starts, for the segments
    /// of a loop and the side from it into the corner: a cut of the ring must not start
    /// there, or the corner would be cut before its loop.
    pub approach_of: Vec<Option<usize>>,
    /// Corner loops written in.
    pub corner_loops: usize,
}

impl LoopedRing {
    /// The ring as it is, without loops.
    pub fn plain(lp: Loop) -> LoopedRing {
        let approach_of = vec![None; lp.vertices.len()];
        LoopedRing { lp, approach_of, corner_loops: 0 }
    }

    /// `at`, or the start of its corner loop when it lies on a loop or on the side after it.
    pub fn snapped(&self, at: Nearest) -> Nearest {
        match self.approach_of.get(at.segment).copied().flatten() {
            Some(v) => Nearest { segment: v, t: 0.0, point: self.lp.vertices[v].point(), distance_mm: at.distance_mm },
            None => at,
        }
    }
}

/// `ring` (in the direction it is cut, its region on the left when `region_on_left`) with
/// a corner loop before every corner that turns towards the region by at least
/// [`CORNER_LOOP_MIN_TURN_DEG`] and whose circle lies inside `region`.
pub(super) fn with_corner_loops(ring: &Loop, region: &Component, rd_mm: f64, region_on_left: bool) -> LoopedRing {
    let side = if region_on_left { 1.0 } else { -1.0 };
    let n = ring.vertices.len();
    // The loop before vertex `i` lies on segment `i − 1`.
    let loops: Vec<Option<(f64, CornerLoop)>> =
        (0..n).map(|i| corner_loop(ring, (i + n - 1) % n, region, rd_mm, side)).collect();
    let mut vertices = Vec::with_capacity(n + 3 * loops.iter().flatten().count());
    let mut approach_of = Vec::with_capacity(vertices.capacity());
    for (j, v) in ring.vertices.iter().enumerate() {
        let Some((t, lp)) = loops[(j + 1) % n] else {
            vertices.push(*v);
            approach_of.push(None);
            continue;
        };
        let (before, after) = split_bulges(&ring.segment(j), t);
        let first = vertices.len() + 1;
        let across = lp.start.offset(2.0 * (lp.center.x - lp.start.x), 2.0 * (lp.center.y - lp.start.y));
        vertices.extend([
            Vertex::new(v.x, v.y, before),
            Vertex::new(lp.start.x, lp.start.y, side * HALF_CIRCLE_BULGE),
            Vertex::new(across.x, across.y, side * HALF_CIRCLE_BULGE),
            Vertex::new(lp.start.x, lp.start.y, after),
        ]);
        approach_of.extend([None, Some(first), Some(first), Some(first)]);
    }
    let corner_loops = loops.iter().flatten().count();
    LoopedRing { lp: Loop::new(vertices), approach_of, corner_loops }
}

/// The corner loop on segment `j` of `ring`, before the corner at its end, with the fraction
/// of the segment where it starts; `None` when the corner is not sharp enough towards the
/// region (`side` +1 on the left, −1 on the right) or the circle does not fit.
fn corner_loop(ring: &Loop, j: usize, region: &Component, rd_mm: f64, side: f64) -> Option<(f64, CornerLoop)> {
    let n = ring.vertices.len();
    let (into, out) = (ring.segment(j), ring.segment((j + 1) % n));
    let (a, b) = (direction_at(&into, 1.0), direction_at(&out, 0.0));
    let turn_rad = side * (a.0 * b.1 - a.1 * b.0).atan2(a.0 * b.0 + a.1 * b.1);
    if turn_rad.is_nan() || turn_rad < CORNER_LOOP_MIN_TURN_DEG.to_radians() {
        return None;
    }
    let radius_mm = corner_loop_radius_mm(rd_mm, turn_rad);
    let back_mm = radius_mm * (0.5 * turn_rad).tan();
    let length_mm = into.length_mm();
    if back_mm > length_mm - MIN_SPLIT_MM {
        return None;
    }
    let t = 1.0 - back_mm / length_mm;
    let start = into.point_at(t);
    let (dx, dy) = direction_at(&into, t);
    let center = start.offset(-side * dy * radius_mm, side * dx * radius_mm);
    let fits = region.contains(center)
        && region.loops.iter().flat_map(Loop::segments).all(|s| s.distance_mm(center) >= radius_mm - TANGENCY_TOL_MM);
    fits.then_some((t, CornerLoop { start, center, radius_mm }))
}

/// The unit direction of travel along `seg` at the fraction `t` of its length.
fn direction_at(seg: &Segment, t: f64) -> (f64, f64) {
    let (dx, dy) = match seg.circle() {
        Some((c, _)) => {
            let (rx, ry) = c.vector_to(seg.point_at(t));
            // Counter-clockwise travel turns the radius a quarter left, clockwise a quarter right.
            let s = seg.bulge.signum();
            (-s * ry, s * rx)
        }
        None => seg.start.vector_to(seg.end),
    };
    let len = dx.hypot(dy);
    (dx / len, dy / len)
}

/// The corner loops of `lp` (as [`with_corner_loops`] writes them), for the tests.
#[cfg(test)]
pub(super) fn loops_of(lp: &Loop) -> Vec<CornerLoop> {
    lp.segments()
        .collect::<Vec<_>>()
        .windows(2)
        .filter(|w| (w[0].bulge.abs() - HALF_CIRCLE_BULGE).abs() < 1e-12 && w[0].start.near(w[1].end, 1e-9))
        .filter_map(|w| w[0].circle().map(|(center, radius_mm)| CornerLoop { start: w[0].start, center, radius_mm }))
        .collect()
}

#[cfg(test)]
#[path = "corners_tests.rs"]
mod tests;
