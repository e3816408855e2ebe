//! Where the tool is in air at one level: the discs of a [`ClearedZone`] (a trochoid's loops,
//! a z-cut stretch's steps), looked up by a grid of cells, and [`AirLookup`], which asks for
//! points that follow each other along a path.
//!
//! A z-cut stretch's zone holds a disc every [`super::cleared::AIR_TEST_STEP_MM`] along it,
//! each as wide as the pocket there, so a lookup cell holds a hundred and more: a point in
//! air of none of them tests them all, and a verification asks at every sample (about 6 ms
//! of the slot box's). Along a path the answer rarely changes from one point to the next:
//! [`AirLookup`] tests the disc that held the last point first, and takes a point closer to
//! the last one measured in the open than that one's distance to every disc of the cell as
//! in the open too. Its answers are [`ClearedZone::is_air`]'s.

use crate::core::geometry::Point;
use rustc_hash::FxHashMap;

/// Discs known to be cleared at one level: the tool is in the air when its centre lies in
/// one of them.
#[derive(Debug, Default, Clone)]
pub struct ClearedZone {
    /// Lookup cells per millimetre (a disc is listed in every cell its bounding box
    /// touches, and a point looked up in its own: any mapping does that keeps the order).
    cells_per_mm: f64,
    /// (Looked up at every sample of a verification: hashed by the fast hash of the
    /// compiler, not a hash that resists chosen keys; the keys are the zone's own cells.)
    cells: FxHashMap<(i64, i64), Vec<(Point, f64)>>,
    count: usize,
}

impl ClearedZone {
    /// An empty zone whose lookup grid has cells of `cell_mm`.
    pub fn new(cell_mm: f64) -> ClearedZone {
        ClearedZone { cells_per_mm: 1.0 / cell_mm, cells: FxHashMap::default(), count: 0 }
    }

    fn key(&self, x: f64, y: f64) -> (i64, i64) {
        (floor_index(x * self.cells_per_mm), floor_index(y * self.cells_per_mm))
    }

    /// Adds the disc of centre `c` and radius `radius_mm` (positions where the tool is in air).
    pub fn add(&mut self, c: Point, radius_mm: f64) {
        if radius_mm <= 0.0 {
            return;
        }
        let (x0, y0) = self.key(c.x - radius_mm, c.y - radius_mm);
        let (x1, y1) = self.key(c.x + radius_mm, c.y + radius_mm);
        for i in x0..=x1 {
            for j in y0..=y1 {
                self.cells.entry((i, j)).or_default().push((c, radius_mm));
            }
        }
        self.count += 1;
    }

    /// Number of discs.
    pub fn len(&self) -> usize {
        self.count
    }

    /// `true` when no disc was added.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// `true` when a tool centred at `p` touches no material.
    pub fn is_air(&self, p: Point) -> bool {
        self.discs_at(p).1.iter().any(|&(c, r)| within(c, p, r))
    }

    /// The lookup cell of `p` and the discs (centre, radius) that may hold it: every disc
    /// that holds a point of the cell.
    fn discs_at(&self, p: Point) -> ((i64, i64), &[(Point, f64)]) {
        let key = self.key(p.x, p.y);
        (key, self.discs_in(key))
    }

    /// The discs that may hold a point of lookup cell `key`.
    fn discs_in(&self, key: (i64, i64)) -> &[(Point, f64)] {
        self.cells.get(&key).map_or(&[][..], Vec::as_slice)
    }
}

/// `t.floor() as i64`, without a call to the mathematics library (a lookup at every sample
/// of a verification takes two).
fn floor_index(t: f64) -> i64 {
    let i = t as i64;
    // (Truncation rounds negative values up.)
    if (i as f64) > t {
        i - 1
    } else {
        i
    }
}

/// Squared distances this close (relatively) to a squared radius are compared by the distance
/// itself: far above the rounding of either.
const SQUARED_MARGIN: f64 = 1e-9;

/// `true` when `p` lies within `r_mm` of `c` (`c.distance_mm(p) <= r_mm`), told by the
/// squared distance wherever it decides beyond rounding: a cell of a zone holds dozens of
/// overlapping discs (a trochoid's loops, a z-cut stretch's steps), and every sample of a
/// verification asks.
fn within(c: Point, p: Point, r_mm: f64) -> bool {
    let (dx, dy) = (p.x - c.x, p.y - c.y);
    let (d2, r2) = (dx * dx + dy * dy, r_mm * r_mm);
    if d2 < r2 * (1.0 - SQUARED_MARGIN) {
        return true;
    }
    if d2 > r2 * (1.0 + SQUARED_MARGIN) {
        return false;
    }
    c.distance_mm(p) <= r_mm
}

/// Share of a distance to the discs given up for rounding before a nearer point is taken as
/// being in the open too (far above the rounding of distances, far below their changes
/// between samples).
const GAP_ROUNDING_SHARE: f64 = 1e-9;

/// Distance to the discs given up for rounding besides [`GAP_ROUNDING_SHARE`], mm.
const GAP_ROUNDING_MM: f64 = 1e-12;

/// Looks up points of one zone one after the other (see the module).
pub struct AirLookup<'a> {
    zone: &'a ClearedZone,
    /// The lookup cell of the last point, and its discs.
    cell: Option<(i64, i64)>,
    discs: &'a [(Point, f64)],
    /// The disc of `discs` that held the last point in air.
    holder: Option<usize>,
    /// The last point measured in the open, and how far around it every point is in the
    /// open too: its distance to every disc of `discs`, less rounding (mm; none: nothing
    /// measured in this cell, or too near a disc).
    open: Option<(Point, f64)>,
}

impl<'a> AirLookup<'a> {
    pub fn new(zone: &'a ClearedZone) -> AirLookup<'a> {
        AirLookup { zone, cell: None, discs: &[], holder: None, open: None }
    }

    /// [`ClearedZone::is_air`] at `p`.
    pub fn is_air(&mut self, p: Point) -> bool {
        if self.zone.is_empty() {
            return false;
        }
        let cell = self.zone.key(p.x, p.y);
        if self.cell != Some(cell) {
            let discs = self.zone.discs_in(cell);
            *self = AirLookup { cell: Some(cell), discs, ..AirLookup::new(self.zone) };
        }
        if let Some(&(c, r)) = self.holder.and_then(|k| self.discs.get(k)) {
            if within(c, p, r) {
                return true;
            }
        }
        if let Some((at, reach)) = self.open {
            // (Squared: the reach gives up far more than the rounding of either side.)
            let (dx, dy) = (p.x - at.x, p.y - at.y);
            if dx * dx + dy * dy < reach * reach {
                return false;
            }
        }
        let mut gap = f64::INFINITY;
        for (k, &(c, r)) in self.discs.iter().enumerate() {
            if within(c, p, r) {
                self.holder = Some(k);
                self.open = None;
                return true;
            }
            let (dx, dy) = (p.x - c.x, p.y - c.y);
            gap = gap.min((dx * dx + dy * dy).sqrt() - r);
        }
        self.holder = None;
        // How far from `p` every point is in the open too, rounding given up.
        let reach = gap * (1.0 - GAP_ROUNDING_SHARE) - GAP_ROUNDING_MM;
        self.open = (reach > 0.0).then_some((p, reach));
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn a_point_is_within_a_disc_exactly_when_its_distance_is_at_most_the_radius() {
        let c = Point::new(1.25, -3.5);
        for k in 0..2000 {
            let angle = f64::from(k) * 0.137;
            for r in [0.3, 2.0, 5.0] {
                // Points at the radius, and a rounding either side of it.
                for d in [r, r * (1.0 - 1e-15), r * (1.0 + 1e-15), r * 0.5, r * 1.5] {
                    let p = Point::new(c.x + d * angle.cos(), c.y + d * angle.sin());
                    assert_eq!(within(c, p, r), c.distance_mm(p) <= r, "{p:?} against {r}");
                }
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Discs along a line with a changing radius (a z-cut stretch's), and a walk of small
        /// steps through and past them, crossing lookup cells.
        #[test]
        fn points_along_a_path_are_in_air_exactly_where_the_zone_says(
            start in (-5.0..5.0f64, -5.0..5.0f64),
            heading in 0.0..std::f64::consts::TAU,
            radii in (0.5..6.0f64, 0.5..6.0f64),
            walk in prop::collection::vec((0.0..0.3f64, -0.4..0.4f64), 200..600),
        ) {
            let mut zone = ClearedZone::new(5.0);
            for k in 0..=300 {
                let t = f64::from(k) / 300.0;
                let c = Point::new(start.0 + 30.0 * t * heading.cos(), start.1 + 30.0 * t * heading.sin());
                zone.add(c, radii.0 + (radii.1 - radii.0) * t);
            }
            let mut lookup = AirLookup::new(&zone);
            let (mut p, mut turn) = (Point::new(start.0 - 8.0, start.1 + 1.0), heading);
            for &(step, bend) in &walk {
                turn += bend;
                p = Point::new(p.x + step * turn.cos(), p.y + step * turn.sin());
                prop_assert_eq!(lookup.is_air(p), zone.is_air(p), "at {:?}", p);
            }
        }
    }

    #[test]
    fn a_lookup_cell_index_is_the_floor_of_the_position_in_cells() {
        for t in [0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 2.999_999, -2.000_001, 1e12, -1e12, -7.0, 7.25] {
            assert_eq!(floor_index(t), t.floor() as i64, "{t}");
        }
    }

    #[test]
    fn points_on_a_disc_s_edge_and_just_beyond_it_are_told_apart() {
        let mut zone = ClearedZone::new(5.0);
        zone.add(Point::new(0.0, 0.0), 2.0);
        let mut lookup = AirLookup::new(&zone);
        for x in [0.0, 1.9, 2.0, 2.0 + 1e-12, 2.1, 3.0, 2.000_000_001, 2.0, 1.0] {
            let p = Point::new(x, 0.0);
            assert_eq!(lookup.is_air(p), zone.is_air(p), "at {x}");
        }
        assert!(!AirLookup::new(&ClearedZone::new(5.0)).is_air(Point::new(0.0, 0.0)));
    }
}
