//! Engagement of the tool's leading half at one position (MODEL.md §6): the angle of
//! the tool circle, within ±90° of the feed direction, that lies in material.
//!
//! A coarse scan every [`COARSE_STEP`] probe steps finds the runs of material, and a
//! bisection places each change of state to one probe step. Coarse points need no probe
//! where an earlier one lies in a tile neighbourhood of one state, or far enough off the
//! raster (see [`crate::core::stock::Certified`]), that reaches them: the result is the
//! same as probing every coarse point.

use super::recent::{intruders, Corridor};
use super::scan_memory::{Line, ScanMemory, LATERAL_TOLERANCE_CELLS};
use crate::core::stock::{ArcSweep, Certified, Raster};
use std::f64::consts::PI;

/// Angular resolution of the probe: positions on the tool circle every 0.05°.
pub const PROBE_STEPS_PER_TURN: usize = 7200;
/// Coarse scan step, in probe steps (2°): finer features are found by bisection only
/// where the coarse scan sees a change.
pub const COARSE_STEP: usize = 40;
/// Probe steps across the leading half.
const HALF_TURN: usize = PROBE_STEPS_PER_TURN / 2;
/// Coarse intervals across the leading half.
pub const COARSE_POINTS: usize = HALF_TURN / COARSE_STEP;
/// A coarse point not in a uniform tile neighbourhood looks this far ahead along its
/// line for uniform cells, cells. (Measured on tiger.nc at 0.05 mm, in instructions:
/// 512 is 2.6 % below 128; 256 and 2048 lie between.)
const AHEAD_CELLS: f64 = 512.0;
/// A look ahead that fails is tried again this many times shorter (8 was dearer).
const SHORTER_LOOK: f64 = 4.0;
/// After a look ahead finds none, the next waits for this much travel, cells (8 is
/// 0.6 % below 4 on tiger.nc).
const RETRY_CELLS: f64 = 8.0;
/// Bisection of a coarse interval takes at most this many steps (2^6 > COARSE_STEP).
const MAX_BISECTION_STEPS: usize = 6;
/// Bisection intervals wider than this probe two levels at a time, probe steps.
const SPECULATE_ABOVE: usize = 3;
/// No look ahead for less than this, cells.
const MIN_LOOK_CELLS: f64 = 4.0;
/// Certified radii are shortened by this, cells (rounding of the probe positions).
const CERTIFY_MARGIN_CELLS: f64 = 1e-6;

/// Precomputed unit vectors of the probe directions, and how many coarse points a
/// certified probe decides.
pub struct AngleTable {
    radius_mm: f64,
    /// Two turns, so a half-turn scan starting anywhere needs no wrap-around.
    dirs: std::sync::Arc<[(f64, f64)]>,
    /// The probe offsets from the tool centre in raster cells, same order.
    offsets: Vec<(f64, f64)>,
    /// Per certification level: coarse points after a certified one that share its state.
    skips: Vec<usize>,
    /// Distance between coarse points n apart, cells.
    chord_cells: Vec<f64>,
    /// The coarse points probed first (bit m for point m): every one more than a level-1
    /// certificate reaches, and the last.
    anchors: u128,
}

/// The engaged part of the leading half.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Contact {
    /// Engagement angle α, rad (sum of the engaged arcs).
    pub alpha_rad: f64,
    /// First and last engaged angle from the feed direction, rad, positive to the left.
    pub entry_rad: f64,
    pub exit_rad: f64,
}

/// Where the tool is, which way it moves, and which recently swept discs can reach its
/// leading half.
#[derive(Debug, Clone, Default)]
pub struct ProbeSite {
    center: (f64, f64),
    radius: f64,
    /// The tool centre on the rasters' grid of cell centres, in cells.
    grid_center: (f64, f64),
    /// Probe index of the start of the leading half (−90° from the feed direction).
    first: usize,
    /// The straight stretch of path the tool is on, if any.
    line: Option<Line>,
    /// Tool centres swept since the raster was last updated whose disc can reach the
    /// leading half: a probe within the radius of one of them is not material.
    intruders: Vec<(f64, f64)>,
    /// Along an arc, the arc swept since the raster was last updated, when its area can
    /// reach the leading half (it stands for the recent centres): a probe within the
    /// radius of it is not material.
    arc: Option<ArcSweep>,
}

impl ProbeSite {
    /// Places the tool of `table` at `center` (`grid_center` on the rasters' grid, see
    /// [`Raster::grid_position`]) moving along the unit vector `heading`; `recent` are the
    /// centres swept since the raster was last updated, laid out along `corridor`; `line`
    /// is the straight stretch of path the tool is on, if any.
    #[allow(clippy::too_many_arguments)]
    pub fn set(
        &mut self,
        table: &AngleTable,
        center: (f64, f64),
        grid_center: (f64, f64),
        heading: (f64, f64),
        recent: &[(f64, f64)],
        corridor: &Corridor,
        line: Option<Line>,
    ) {
        let radius = table.radius_mm;
        self.line = line;
        let step = 2.0 * PI / PROBE_STEPS_PER_TURN as f64;
        let h = ((heading.1.atan2(heading.0) / step).round() as i64).rem_euclid(PROBE_STEPS_PER_TURN as i64);
        let quarter = (PROBE_STEPS_PER_TURN / 4) as i64;
        self.first = (h - quarter).rem_euclid(PROBE_STEPS_PER_TURN as i64) as usize;
        self.center = center;
        self.grid_center = grid_center;
        self.radius = radius;
        // The leading half is the closed half circle about the probe direction h.
        intruders(recent, corridor, center, radius, table.dirs[h as usize], &mut self.intruders);
        self.arc = None;
    }

    /// Where the tool follows an arc: `arc` is the area swept along it since the raster was
    /// last updated, when it can reach the leading half (after [`ProbeSite::set`] with no
    /// recent centres).
    pub fn set_swept_arc(&mut self, arc: Option<ArcSweep>) {
        self.arc = arc;
    }

    /// `true` when nothing swept since the raster was last updated reaches the leading half.
    #[inline]
    fn unswept(&self) -> bool {
        self.intruders.is_empty() && self.arc.is_none()
    }
}

impl AngleTable {
    /// The probe directions, with the coarse points a certified probe decides for a tool
    /// of radius `radius_mm` on rasters with cells of `cell_mm`.
    pub fn new(radius_mm: f64, cell_mm: f64) -> AngleTable {
        let dirs: std::sync::Arc<[(f64, f64)]> = (0..2 * PROBE_STEPS_PER_TURN)
            .map(|k| {
                let a = k as f64 * 2.0 * PI / PROBE_STEPS_PER_TURN as f64;
                (a.cos(), a.sin())
            })
            .collect();
        AngleTable::of_dirs(dirs, radius_mm, cell_mm)
    }

    /// The table of the same probe directions for a tool of radius `radius_mm` (a slice
    /// that takes a radius or ball end mill at a smaller radius, see [`super::profile`]).
    pub fn with_radius(&self, radius_mm: f64, cell_mm: f64) -> AngleTable {
        AngleTable::of_dirs(std::sync::Arc::clone(&self.dirs), radius_mm, cell_mm)
    }

    /// The tool radius the table probes at, mm.
    pub fn radius_mm(&self) -> f64 {
        self.radius_mm
    }

    /// The table of the probe directions `dirs` (shared by the tables of one simulation)
    /// for a tool of radius `radius_mm`.
    fn of_dirs(dirs: std::sync::Arc<[(f64, f64)]>, radius_mm: f64, cell_mm: f64) -> AngleTable {
        let coarse_rad = COARSE_STEP as f64 * 2.0 * PI / PROBE_STEPS_PER_TURN as f64;
        // Coarse points n steps apart are a chord 2r·sin(n·step/2) apart.
        let skips: Vec<usize> = Certified::levels()
            .map(|level| {
                let reach_mm = (level.cells() - CERTIFY_MARGIN_CELLS) * cell_mm;
                (0..COARSE_POINTS)
                    .take_while(|&n| 2.0 * radius_mm * (n as f64 * coarse_rad / 2.0).sin() <= reach_mm)
                    .last()
                    .unwrap_or(0)
            })
            .collect();
        let offsets = dirs.iter().map(|&(c, s)| (radius_mm * c / cell_mm, radius_mm * s / cell_mm)).collect();
        let chord_cells =
            (0..=COARSE_POINTS).map(|n| 2.0 * radius_mm * (n as f64 * coarse_rad / 2.0).sin() / cell_mm).collect();
        let anchors = (0..=COARSE_POINTS).step_by(skips[0] + 1).fold(1u128 << COARSE_POINTS, |s, m| s | 1 << m);
        AngleTable { radius_mm, dirs, offsets, skips, chord_cells, anchors }
    }

    /// Coarse points after a probe certified at `level` that share its state.
    pub(super) fn skip(&self, level: Certified) -> usize {
        match level {
            Certified::No => 0,
            Certified::Level(l) => self.skips[l - 1],
        }
    }

    /// The probe position `k` steps into the leading half, on the rasters' grid.
    #[inline]
    fn grid_point(&self, site: &ProbeSite, k: usize) -> (f64, f64) {
        let (ox, oy) = self.offsets[site.first + k];
        (site.grid_center.0 + ox, site.grid_center.1 + oy)
    }

    /// `true` when a recent centre has swept the probe position `k` steps into the
    /// leading half.
    #[inline]
    fn swept(&self, site: &ProbeSite, k: usize) -> bool {
        let (c, s) = self.dirs[site.first + k];
        let (x, y) = (site.center.0 + site.radius * c, site.center.1 + site.radius * s);
        if let Some(arc) = &site.arc {
            return arc.distance((x, y)) < site.radius;
        }
        let r2 = site.radius * site.radius;
        site.intruders.iter().any(|c| (x - c.0) * (x - c.0) + (y - c.1) * (y - c.1) < r2)
    }

    #[inline]
    fn material(&self, raster: &Raster, site: &ProbeSite, k: usize) -> bool {
        raster.is_material_at(self.grid_point(site, k)) && (site.unswept() || !self.swept(site, k))
    }

    /// As `material`, with how far the state is known to hold; material is certified
    /// only when no recent disc reaches the leading half.
    #[inline]
    pub(super) fn certified_material(&self, raster: &Raster, site: &ProbeSite, k: usize) -> (bool, Certified) {
        let (material, level) = raster.probe_at(self.grid_point(site, k));
        if !material {
            return (false, level);
        }
        if site.unswept() {
            return (true, level);
        }
        (!self.swept(site, k), Certified::No)
    }

    /// First probe index in (a, b] whose state differs from index `a`'s, by bisection,
    /// and the probe indices it read.
    /// With a `hint` (where the boundary was at the previous sample), the midpoints the
    /// bisection visits on its way there are probed first, all at once; without one, each
    /// round probes the midpoint and both midpoints of the next round at once. Either way
    /// the probes overlap in the processor, and the same probes decide as in plain
    /// bisection, so the same boundary is found.
    fn boundary(
        &self,
        raster: &Raster,
        site: &ProbeSite,
        (a, b): (usize, usize),
        state_a: bool,
        hint: usize,
    ) -> (usize, Probed) {
        let mut probed = Probed::default();
        let mut probe = |k: usize| {
            probed.push(k);
            self.material(raster, site, k)
        };
        let mut ready = [(usize::MAX, false); MAX_BISECTION_STEPS];
        if a < hint && hint <= b {
            let (mut lo, mut hi, mut n) = (a, b, 0);
            while hi - lo > 1 && n < MAX_BISECTION_STEPS {
                let mid = (lo + hi) / 2;
                ready[n].0 = mid;
                n += 1;
                (lo, hi) = if mid < hint { (mid, hi) } else { (lo, mid) };
            }
            for slot in &mut ready[..n] {
                slot.1 = probe(slot.0);
            }
        }
        let (mut lo, mut hi) = (a, b);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            let known = ready.iter().find(|r| r.0 == mid).map(|r| r.1);
            if known.is_some() || hi - lo <= SPECULATE_ABOVE {
                let state = known.unwrap_or_else(|| probe(mid));
                (lo, hi) = if state == state_a { (mid, hi) } else { (lo, mid) };
                continue;
            }
            let (below, above) = ((lo + mid) / 2, (mid + hi) / 2);
            let at = [mid, below, above].map(|k| probe(k) == state_a);
            (lo, hi) = match at {
                [true, _, true] => (above, hi),
                [true, _, false] => (mid, above),
                [false, true, _] => (below, mid),
                [false, false, _] => (lo, below),
            };
        }
        (hi, probed)
    }

    /// How far (`look_ahead` or, failing that, a shorter look) every probe of `probed`
    /// at `site` keeps its answer while the tool moves along `dir`, cells (see
    /// [`Raster::constant_along`]).
    fn settled_ahead(
        &self,
        raster: &Raster,
        site: &ProbeSite,
        probed: &Probed,
        dir: (f64, f64),
        look_ahead: f64,
    ) -> Option<f64> {
        let indices = probed.indices()?;
        longest_hold(look_ahead, |length| {
            indices.iter().all(|&k| {
                let g = self.grid_point(site, k);
                let ahead = (g.0 + dir.0 * length, g.1 + dir.1 * length);
                raster.constant_along(g, ahead, LATERAL_TOLERANCE_CELLS).is_some()
            })
        })
    }

    /// The material state of every coarse point (bit m for point m): those of `known_air`
    /// are in air, then those `memory` still holds, then the anchors, then the rest that
    /// no certified probe decided. The probes of each pass are independent of each other,
    /// so they overlap in the processor.
    fn coarse_states(
        &self,
        raster: &Raster,
        site: &ProbeSite,
        mut memory: Option<(&mut ScanMemory, f64)>,
        known_air: u128,
    ) -> u128 {
        let (mut known, mut state) = match memory.as_mut() {
            Some((mem, travel)) => mem.recall(*travel),
            None => (0, 0),
        };
        known |= known_air;
        state &= !known_air;
        let mut unknown = !known & points(0, COARSE_POINTS);
        let look_ahead = site.line.map_or(0.0, |l| l.ahead_cells.min(AHEAD_CELLS));
        for pass in [unknown & self.anchors, unknown] {
            // The points of the pass not known yet, lowest first: a probe certified far from
            // the boundary decides its neighbours, which drop out at once (not passed over
            // one by one).
            let mut todo = pass & !known;
            while todo != 0 {
                let m = todo.trailing_zeros() as usize;
                let (material, level) = self.certified_material(raster, site, m * COARSE_STEP);
                let reach = self.skip(level);
                let (lo, hi) = (m.saturating_sub(reach), (m + reach).min(COARSE_POINTS));
                // (Point m among them: it was not known.)
                let decided = points(lo, hi) & !known;
                known |= decided;
                todo &= !known;
                state = if material { state | decided } else { state & !decided };
                let Some((mem, travel)) = memory.as_mut() else {
                    continue;
                };
                if level != Certified::No {
                    mem.hold_disc(m, (lo, hi), *travel, material, level.cells(), &self.chord_cells);
                    if look_ahead >= MIN_LOOK_CELLS {
                        let g = self.grid_point(site, m * COARSE_STEP);
                        let held = certified_ahead(
                            raster,
                            g,
                            (mem.dir(), mem.travel_per_cell()),
                            (material, level),
                            look_ahead,
                        );
                        mem.hold_ahead(m, *travel, material, held);
                    }
                } else if look_ahead >= MIN_LOOK_CELLS && mem.should_look(m, *travel) {
                    let g = self.grid_point(site, m * COARSE_STEP);
                    let d = mem.dir();
                    let holds = |length: f64| {
                        let ahead = (g.0 + d.0 * length, g.1 + d.1 * length);
                        raster
                            .uniform_along(g, ahead, LATERAL_TOLERANCE_CELLS)
                            .or_else(|| raster.constant_along(g, ahead, LATERAL_TOLERANCE_CELLS))
                            == Some(material)
                    };
                    match longest_hold(look_ahead, holds) {
                        Some(length) => mem.hold_ahead(m, *travel, material, length),
                        None => mem.not_found(m, *travel, RETRY_CELLS),
                    }
                }
            }
            unknown = !known & points(0, COARSE_POINTS);
        }
        debug_assert!(unknown == 0);
        state
    }

    /// Measures the engagement of the leading half at `site`; `memory` (one per raster)
    /// carries coarse states from sample to sample along a straight stretch of path.
    pub fn contact(&self, raster: &Raster, site: &ProbeSite, memory: Option<&mut ScanMemory>) -> Contact {
        self.contact_and_states(raster, site, memory, 0).0
    }

    /// As [`AngleTable::contact`], with the material state of every coarse point (bit m
    /// for point m). The coarse points of `known_air` are known to be in air at `site`
    /// (they are in a raster whose material holds this one's): they are not probed.
    pub fn contact_and_states(
        &self,
        raster: &Raster,
        site: &ProbeSite,
        mut memory: Option<&mut ScanMemory>,
        known_air: u128,
    ) -> (Contact, u128) {
        let step = 2.0 * PI / PROBE_STEPS_PER_TURN as f64;
        // States are remembered along a line when no recent disc reaches the leading half:
        // the travel along it.
        let travel = match (memory.as_deref_mut(), site.line) {
            (Some(mem), Some(line)) if site.unswept() => {
                Some(mem.travel(raster.version(), site.first, line, site.grid_center))
            }
            _ => None,
        };
        let state = self.coarse_states(raster, site, memory.as_deref_mut().zip(travel), known_air);
        let look_ahead = site.line.map_or(0.0, |l| l.ahead_cells.min(AHEAD_CELLS));
        // Coarse interval m runs from point m to point m + 1.
        let intervals = points(0, COARSE_POINTS - 1);
        let both = state & (state >> 1) & intervals;
        let mut engaged = both.count_ones() as usize * COARSE_STEP;
        let (mut entry, mut exit) = match both {
            0 => (usize::MAX, 0),
            _ => (both.trailing_zeros() as usize * COARSE_STEP, (128 - both.leading_zeros() as usize) * COARSE_STEP),
        };
        let mut changes = (state ^ (state >> 1)) & intervals;
        while changes != 0 {
            let m = changes.trailing_zeros() as usize;
            changes &= changes - 1;
            let prev = state & (1 << m) != 0;
            let (a, b) = (m * COARSE_STEP, (m + 1) * COARSE_STEP);
            let settled = memory.as_ref().zip(travel).and_then(|(mem, t)| mem.settled_boundary(m, t, prev));
            let at = match settled {
                Some(steps) => a + steps,
                None => {
                    let hint = memory.as_ref().map_or(0, |mem| a + mem.boundary_hint(m));
                    let (at, probed) = self.boundary(raster, site, (a, b), prev, hint);
                    if let Some(mem) = memory.as_deref_mut() {
                        mem.set_boundary_hint(m, at - a);
                        if let Some(t) = travel.filter(|&t| look_ahead >= MIN_LOOK_CELLS && mem.should_settle(m, t)) {
                            let length = self.settled_ahead(raster, site, &probed, mem.dir(), look_ahead);
                            mem.settle(m, t, prev, length, RETRY_CELLS);
                        }
                    }
                    at
                }
            };
            // A run narrower than one coarse step at an edge of the leading half is a wall
            // the tool circle touches tangentially (a pass along cut ground), not engagement.
            let tangent_wall = (prev && a == 0) || (!prev && b == HALF_TURN);
            let run = if prev { (a, at) } else { (at, b) };
            if !tangent_wall {
                engaged += run.1 - run.0;
                entry = entry.min(run.0);
                exit = exit.max(run.1);
            }
        }
        let to_rad = |k: usize| k as f64 * step - PI / 2.0;
        let engaged_somewhere = entry != usize::MAX;
        let contact = Contact {
            alpha_rad: engaged as f64 * step,
            entry_rad: if engaged_somewhere { to_rad(entry) } else { 0.0 },
            exit_rad: if engaged_somewhere { to_rad(exit) } else { 0.0 },
        };
        (contact, state)
    }
}

/// Most probes one bisection may record (its rounds read at most 14).
const MAX_BISECTION_PROBES: usize = 16;

/// The probe indices one bisection read.
#[derive(Default)]
struct Probed {
    indices: [usize; MAX_BISECTION_PROBES],
    len: usize,
    overflow: bool,
}

impl Probed {
    fn push(&mut self, k: usize) {
        match self.indices.get_mut(self.len) {
            Some(slot) => {
                *slot = k;
                self.len += 1;
            }
            None => self.overflow = true,
        }
    }

    /// The indices read, unless there were too many to record.
    fn indices(&self) -> Option<&[usize]> {
        (!self.overflow).then(|| &self.indices[..self.len])
    }
}

/// The longest of `look_ahead`, then ever shorter looks (down to [`MIN_LOOK_CELLS`]),
/// over which `holds`: a state that changes ahead is still remembered up to there.
fn longest_hold(look_ahead: f64, holds: impl Fn(f64) -> bool) -> Option<f64> {
    let mut length = look_ahead;
    while length >= MIN_LOOK_CELLS {
        if holds(length) {
            return Some(length);
        }
        length /= SHORTER_LOOK;
    }
    None
}

/// How far along its line (travel, cells; at most a step past `look_ahead`) the state
/// `material` of a probe at grid position `g`, certified at `level`, holds. The next probe
/// is placed at the edge of the disc certified so far; while it has the same state,
/// certified, its disc extends the stretch. `line` is the line's unit direction and its
/// travel per cell of displacement along either axis (certificates reach a distance along
/// both axes).
pub(super) fn certified_ahead(
    raster: &Raster,
    g: (f64, f64),
    line: ((f64, f64), f64),
    (material, level): (bool, Certified),
    look_ahead: f64,
) -> f64 {
    let ((dx, dy), travel_per_cell) = line;
    let reach = |level: Certified| (level.cells() - CERTIFY_MARGIN_CELLS - LATERAL_TOLERANCE_CELLS) * travel_per_cell;
    let mut held = reach(level);
    while held > 0.0 && held < look_ahead {
        let at = (g.0 + dx * held, g.1 + dy * held);
        let next = if material {
            match raster.probe_at(at) {
                (true, level) => level,
                (false, _) => Certified::No,
            }
        } else {
            raster.certified_air_at(at)
        };
        match next {
            Certified::Level(_) => held += reach(next),
            Certified::No => break,
        }
    }
    held.max(0.0)
}

/// Coarse points lo..=hi as bits.
pub(super) fn points(lo: usize, hi: usize) -> u128 {
    (u128::MAX >> (127 - hi)) & (u128::MAX << lo)
}
