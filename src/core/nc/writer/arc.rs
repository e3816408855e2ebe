//! Arcs on the written grid: the centre as incremental I/J/K chosen so that the control's
//! radius check passes, full circles and turns, and the arcs too small to write as arcs.

use std::f64::consts::PI;

use super::format::Fixed;
use super::{Writer, CENTRE_LETTERS, G_CLOCKWISE, G_COUNTER_CLOCKWISE};
use crate::core::nc::arcs::{arc_radius_tolerance_mm, check_arc, coord, plane_axes, with_coord};
use crate::core::toolpath::arc_sweep;
use crate::core::toolpath::{Motion, Move, Plane, P3};

/// G codes of the planes.
const G_PLANE_XY: u32 = 17;
const G_PLANE_ZX: u32 = 18;
const G_PLANE_YZ: u32 = 19;

impl Writer<'_> {
    /// A G2/G3 move with no turns for Fanuc (see [`split_turns`]).
    pub(super) fn arc(&mut self, m: &Move) {
        let Motion::Arc { center, clockwise, plane, turns } = m.motion else {
            return;
        };
        let [a, b, n] = plane_axes(plane);
        let start_units = self.units_of(m.start);
        let start: [i64; 3] = std::array::from_fn(|axis| self.position[axis].unwrap_or(start_units[axis]));
        let end = self.units_of(m.end);
        let closes = end[a] == start[a] && end[b] == start[b];
        // Where the ends meet on the grid, the arc is whole circles: as many as it turns,
        // plus one if its plain part is more than a half turn (a full circle, or nearly).
        let circles = if closes {
            let flat = |p: P3| (coord(p, a), coord(p, b), coord(p, n));
            let plain = arc_sweep(flat(m.start), flat(m.end), flat(center), clockwise, 0).abs();
            turns + u32::from(plain > PI)
        } else {
            0
        };
        if closes && circles == 0 {
            return self.straight(m);
        }
        let (ca, cb) = self.centre_units(center, plane, start, end);
        let point = |units: [i64; 3]| P3::new(self.mm(units[0]), self.mm(units[1]), self.mm(units[2]));
        let written_centre = with_coord(with_coord(point(start), a, self.mm(ca)), b, self.mm(cb));
        if check_arc(point(start), written_centre, point(end), plane).is_err() {
            return self.straight(m);
        }
        if plane != self.plane {
            self.code('G', plane_code(plane));
            self.plane = plane;
        }
        self.motion_code(if clockwise { G_CLOCKWISE } else { G_COUNTER_CLOCKWISE });
        self.axes(end);
        // I before J before K, whatever the plane.
        let mut offsets = [(a, ca - start[a]), (b, cb - start[b])];
        offsets.sort_by_key(|&(axis, _)| axis);
        for (axis, units) in offsets {
            self.number(CENTRE_LETTERS[axis], Fixed { units, decimals: self.decimals });
        }
        let p = if closes { circles } else { turns + 1 };
        if p > 1 {
            self.code('P', p);
        }
        self.feed_and_speed(m);
        self.end_line();
    }

    /// The arc centre's in-plane coordinates on the written grid, within one unit of the
    /// true centre on each axis: the nearest grid point if its radii to the written start
    /// and end agree to half the control's tolerance, else the one where they agree best.
    fn centre_units(&self, center: P3, plane: Plane, start: [i64; 3], end: [i64; 3]) -> (i64, i64) {
        let [a, b, _] = plane_axes(plane);
        let scale = 1.0 / self.mm(1);
        let (ta, tb) = (coord(center, a) * scale, coord(center, b) * scale);
        let radius = |ca: i64, cb: i64, p: [i64; 3]| ((p[a] - ca) as f64).hypot((p[b] - cb) as f64);
        let mismatch = |&(ca, cb): &(i64, i64)| (radius(ca, cb, start) - radius(ca, cb, end)).abs();
        let (ra, rb) = (self.fixed(coord(center, a)).units, self.fixed(coord(center, b)).units);
        let tolerance = arc_radius_tolerance_mm(self.mm(1) * radius(ra, rb, start)) * scale;
        let mut candidates = vec![(ra, rb)];
        for ca in [ta.floor() as i64, ta.ceil() as i64] {
            for cb in [tb.floor() as i64, tb.ceil() as i64] {
                if !candidates.contains(&(ca, cb)) {
                    candidates.push((ca, cb));
                }
            }
        }
        if mismatch(&candidates[0]) <= tolerance / 2.0 {
            return candidates[0];
        }
        candidates.into_iter().min_by(|p, q| mismatch(p).total_cmp(&mismatch(q))).unwrap_or((ra, rb))
    }
}

/// G17, G18 or G19.
fn plane_code(plane: Plane) -> u32 {
    match plane {
        Plane::Xy => G_PLANE_XY,
        Plane::Zx => G_PLANE_ZX,
        Plane::Yz => G_PLANE_YZ,
    }
}
