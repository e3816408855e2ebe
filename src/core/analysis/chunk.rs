//! The stretch of path swept since the rasters were last updated (MODEL.md §6). Its
//! tool centres are checked exactly by the probe; when it is applied, one capsule (its
//! chord swept by the tool) stands for it, so a chunk ends before the path turns or bows
//! away from its chord. Along an arc move in XY a chunk follows the arc instead: the area
//! swept along it stands for the chunk, and the probe tests that area (see
//! [`Chunk::swept`]), so a tight arc, a trochoid's loop, is applied a quarter turn at a
//! time instead of every few samples.

use super::arcs::ArcGuide;
use super::profile::SAME_RADIUS_MM;
use super::recent::Corridor;
use super::sampling::has_heading;
use super::stack::Stack;
use crate::core::stock::{ArcRows, ArcSweep, CapsuleRows, MAX_ARC_SWEEP_RAD};

/// A chunk holds at most this many steps: straight stretches are applied in capsules
/// this long (the search for recent centres that reach the leading half stops early on
/// them, see [`super::recent`]). Long capsules spare the per-row work of each update
/// and keep the raster, and so what the probes remember, unchanged for longer.
pub const MAX_CHUNK_STEPS: usize = 4096;
/// A sample whose heading turns by more than this from the chunk's first heading starts
/// a new chunk, deg.
pub const CHUNK_TURN_DEG: f64 = 5.0;
/// A chunk's chord strays at most this far from its path, in raster cells.
pub const CHORD_DEVIATION_CELLS: f64 = 0.05;
/// A chord strays from a path that turns by θ (rad) over a length L by at most L·θ/4 (a
/// kink halfway; L·θ/8 on an arc).
const KINK_DEVIATION_PER_TURN: f64 = 4.0;

/// Centres closer than this in x and in y are one XY point, mm.
const SAME_XY_MM: f64 = 1e-9;
/// A chunk follows an arc from a start this close to the arc's circle, mm.
const ON_CIRCLE_MM: f64 = 1e-6;
/// Along an arc of a radius below the tool's plus this, the discs swept since the start
/// of the chunk reach the tool's leading half (see [`Chunk::swept`]), mm.
const ARC_REACH_MARGIN_MM: f64 = 1e-6;

/// What stands for the area a chunk swept, for the probe (see [`Chunk::swept`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Swept {
    /// The discs about the recent centres.
    Centres,
    /// The arc the chunk follows, when it can reach the leading half.
    Arc(Option<ArcSweep>),
}

/// The centres swept since the last update of the rasters.
pub struct Chunk {
    /// Where the chunk starts: the end of the previous one, or its first centre.
    start: Option<(f64, f64)>,
    /// Heading of the chunk's first sample.
    heading: (f64, f64),
    /// Slices the chunk cuts (from the top).
    pub cut: usize,
    /// Centres from `start` on.
    recent: Vec<(f64, f64)>,
    /// Path length from `start` to the last centre, mm.
    length_mm: f64,
    /// Largest distance of a centre from the line through `start` along `heading`, mm.
    lateral_mm: f64,
    /// The centres' distances along that line never decrease; the last one's, mm.
    ordered: bool,
    last_along_mm: f64,
    /// The disc about `start` is already in the rasters (a previous flush ended there).
    start_cleared: bool,
    cos_turn: f64,
    max_deviation_mm: f64,
    /// Capsules applied so far (numbers them for [`super::slices::SliceStock::take_capsule`]).
    capsules: u64,
    /// The rows of the capsule last applied (kept to reuse its memory).
    rows: Option<CapsuleRows>,
    /// The arc the chunk follows, if it does, and the angle swept along it so far, rad.
    arc: Option<(ArcGuide, f64)>,
    /// The rows of the arc last applied (kept to reuse its memory).
    arc_rows: Option<ArcRows>,
}

impl Chunk {
    /// An empty chunk cutting `cut` slices whose rasters have cells of `cell_mm`.
    pub fn new(cut: usize, cell_mm: f64) -> Chunk {
        Chunk {
            start: None,
            heading: (0.0, 0.0),
            cut,
            recent: Vec::with_capacity(MAX_CHUNK_STEPS + 1),
            length_mm: 0.0,
            lateral_mm: 0.0,
            ordered: true,
            last_along_mm: 0.0,
            start_cleared: false,
            cos_turn: CHUNK_TURN_DEG.to_radians().cos(),
            max_deviation_mm: CHORD_DEVIATION_CELLS * cell_mm,
            capsules: 0,
            rows: None,
            arc: None,
            arc_rows: None,
        }
    }

    /// Makes the chunk follow the arc of the next sample's move, `guide` (None: that move
    /// is no arc in XY), before the sample is probed. A chunk along another arc, or along
    /// a line, is applied first; a chunk follows an arc only from a start on its circle
    /// (otherwise the sample joins the line chunk, and the arc is followed from it on).
    pub fn follow(&mut self, stack: &mut Stack, radii: &[f64], guide: Option<&ArcGuide>) {
        let same = matches!((&self.arc, guide), (Some((a, _)), Some(g)) if a.move_index == g.move_index);
        if same {
            return;
        }
        if self.arc.is_some() || (guide.is_some() && self.recent.len() > 1) {
            self.flush(stack, radii);
            self.arc = None;
        }
        let Some(g) = guide else {
            return;
        };
        let on_circle =
            |p: (f64, f64)| ((p.0 - g.center.0).hypot(p.1 - g.center.1) - g.radius_mm).abs() <= ON_CIRCLE_MM;
        if self.start.is_none_or(on_circle) {
            self.arc = Some((*g, 0.0));
        }
    }

    /// What the probe tests for the area swept since the rasters were last updated: the
    /// recent centres' discs, or where the chunk follows an arc, the arc swept since the
    /// chunk's start (none when no disc swept along it can reach the leading half of a
    /// tool further along the arc).
    ///
    /// A disc about a point of the circle of radius ρ a turn δ behind the tool lies
    /// √(r² + 2ρ(1 − cos δ)(ρ − r)) from the inner end of the leading half: all reach it
    /// when ρ < r, and none reaches the leading half when ρ ≥ r.
    pub fn swept(&self, radius: f64) -> Swept {
        let Some((guide, _)) = self.arc else {
            return Swept::Centres;
        };
        match (self.start, self.recent.last()) {
            (Some(a), Some(&b)) if guide.radius_mm < radius + ARC_REACH_MARGIN_MM => {
                Swept::Arc(Some(ArcSweep::new(guide.center, a, b, guide.ccw)))
            }
            _ => Swept::Arc(None),
        }
    }

    /// The centres swept since the rasters were last updated.
    pub fn recent(&self) -> &[(f64, f64)] {
        &self.recent
    }

    /// Where the recent centres lie.
    pub fn corridor(&self) -> Corridor {
        match self.start {
            Some(start) => Corridor { start, dir: self.heading, half_width: self.lateral_mm, ordered: self.ordered },
            None => Corridor::UNKNOWN,
        }
    }

    /// Applies the chunk and starts an empty one cutting `cut` slices (along the same arc,
    /// if it follows one).
    pub fn restart(&mut self, stack: &mut Stack, radii: &[f64], cut: usize) {
        self.flush(stack, radii);
        if let Some((_, swept)) = self.arc.as_mut() {
            *swept = 0.0;
        }
        self.start = None;
        self.recent.clear();
        self.reset_line();
        self.start_cleared = false;
        self.cut = cut;
    }

    /// Adds the centre `p` of a sample reached by a step of `step_mm` along `heading`;
    /// when `p` would turn the chunk or bow it away from its chord, or it is full, the
    /// chunk is first applied, so it ends at the previous centre.
    pub fn push(&mut self, stack: &mut Stack, radii: &[f64], p: (f64, f64), heading: (f64, f64), step_mm: f64) {
        let last = self.recent.last().copied();
        if last.is_some_and(|q| (p.0 - q.0).abs() <= SAME_XY_MM && (p.1 - q.1).abs() <= SAME_XY_MM) {
            // A move along z only: the tool sweeps nothing new in XY.
            return;
        }
        if let Some((guide, swept)) = self.arc {
            // Along an arc: applied a quarter turn at a time.
            let step_rad = step_mm / guide.radius_mm;
            let mut swept = swept + step_rad;
            if swept > MAX_ARC_SWEEP_RAD || self.recent.len() > MAX_CHUNK_STEPS {
                self.flush(stack, radii);
                swept = step_rad;
            }
            self.arc = Some((guide, swept));
            if self.start.is_none() {
                self.start = Some(p);
            }
            self.recent.push(p);
            return;
        }
        if self.start.is_some() && !has_heading(self.heading) {
            // The chunk so far is one XY point (the foot of a plunge): its line starts here.
            self.heading = heading;
        }
        if self.start.is_some() {
            let (h, c) = (self.heading, heading);
            let turn = (h.0 * c.1 - h.1 * c.0).abs();
            let turned = h.0 * c.0 + h.1 * c.1 < self.cos_turn;
            let bowed = (self.length_mm + step_mm) * turn / KINK_DEVIATION_PER_TURN > self.max_deviation_mm;
            if turned || bowed || self.recent.len() > MAX_CHUNK_STEPS {
                self.flush(stack, radii);
                self.heading = heading;
            }
        }
        match self.start {
            None => {
                self.start = Some(p);
                self.heading = heading;
            }
            Some(start) => {
                self.length_mm += step_mm;
                let (dx, dy) = (p.0 - start.0, p.1 - start.1);
                let along = dx * self.heading.0 + dy * self.heading.1;
                self.lateral_mm = self.lateral_mm.max((dx * self.heading.1 - dy * self.heading.0).abs());
                self.ordered &= along >= self.last_along_mm;
                self.last_along_mm = along;
            }
        }
        self.recent.push(p);
    }

    /// The chunk's line restarts at its start.
    fn reset_line(&mut self) {
        self.length_mm = 0.0;
        self.lateral_mm = 0.0;
        self.ordered = true;
        self.last_along_mm = 0.0;
    }

    /// Removes the area the chunk swept from the rasters of the slices it cuts, each at its
    /// radius in `radii` (top first): its capsule or, along an arc, the area swept along the
    /// arc. The next chunk starts at its last centre.
    pub fn flush(&mut self, stack: &mut Stack, radii: &[f64]) {
        let (Some(a), Some(&b)) = (self.start, self.recent.last()) else {
            return;
        };
        let arc = self.arc.map(|(guide, _)| ArcSweep::new(guide.center, a, b, guide.ccw));
        if arc.is_some() && self.recent.len() < 2 && self.start_cleared {
            // Only the start, whose disc a previous update already removed.
            return;
        }
        let cut = self.cut.min(stack.len());
        self.capsules += 1;
        let same = |i: usize, j: usize| (radii[i] - radii[j]).abs() <= SAME_RADIUS_MM;
        if cut > 0 {
            // The deepest slice cut is cut apart from the one below, and so is a slice cut at
            // another radius than the one below; a slice above that is alike with the one
            // below, at its radius, takes the update with it, and one that no probe tells
            // from it shares its stock again (from the deepest up, so a run of such slices
            // shares one).
            stack.separate(cut - 1);
            for k in (0..cut - 1).rev() {
                if !same(k, k + 1) {
                    stack.separate(k);
                } else {
                    stack.rejoin_when_alike(k);
                }
            }
        }
        // From the deepest slice cut up: above a slice with no material near the capsule,
        // none cut at the same radius has any (see [`super::slices`]). The rows are found
        // once per radius: all slices share one grid.
        let mut material_near = true;
        let mut rows_for: Option<usize> = None;
        for k in (0..cut).rev() {
            if stack.alike_below(k) {
                continue;
            }
            if rows_for.is_none_or(|j| !same(j, k)) {
                rows_for = Some(k);
                material_near = true;
                let (grid, radius) = (stack.raster(0), radii[k]);
                match (arc, self.rows.as_mut(), self.arc_rows.as_mut()) {
                    (Some(arc), _, Some(rows)) => rows.set(grid, arc, radius),
                    (Some(arc), _, None) => self.arc_rows = Some(ArcRows::new(grid, arc, radius)),
                    (None, Some(rows), _) => rows.set(grid, a, b, radius, self.start_cleared),
                    (None, None, _) => self.rows = Some(CapsuleRows::new(grid, a, b, radius, self.start_cleared)),
                }
            }
            let s = stack.own(k);
            material_near = match (material_near, arc.is_some(), self.rows.as_mut(), self.arc_rows.as_mut()) {
                (true, true, _, Some(rows)) => s.take_arc(self.capsules, rows),
                (true, false, Some(rows), _) => s.take_capsule(self.capsules, rows),
                _ => {
                    s.raster.skip_capsule();
                    false
                }
            };
        }
        self.start = Some(b);
        self.start_cleared = true;
        self.recent.clear();
        self.recent.push(b);
        self.reset_line();
        if arc.is_some() {
            // A line chunk from here takes the heading of its first move.
            self.heading = (0.0, 0.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::region::{paint, StockRegion};
    use crate::core::progress::NoProgress;
    use crate::core::stock::{Raster, Rect};

    const RADIUS: f64 = 5.0;
    const CELL: f64 = 0.1;

    /// One slice of a 40 × 40 mm block.
    fn block() -> Stack {
        let rect = Rect { x_min: -20.0, y_min: -20.0, x_max: 20.0, y_max: 20.0 };
        let mut raster = Raster::new(rect, CELL);
        paint(&mut raster, &[StockRegion::Rect(rect)], &[], &NoProgress).expect("nothing cancels the painting");
        Stack::new(&[0.0, -10.0], raster)
    }

    #[test]
    fn a_move_along_z_only_sweeps_nothing_new_and_applies_nothing() {
        let mut slices = block();
        let mut chunk = Chunk::new(1, CELL);
        chunk.push(&mut slices, &[RADIUS], (0.0, 0.0), (1.0, 0.0), 0.05);
        chunk.push(&mut slices, &[RADIUS], (0.05, 0.0), (1.0, 0.0), 0.05);
        let version = slices.raster(0).version();
        for _ in 0..100 {
            chunk.push(&mut slices, &[RADIUS], (0.05, 0.0), (0.0, 0.0), 0.05);
        }
        assert_eq!(slices.raster(0).version(), version, "a plunge in place applied a capsule");
        assert_eq!(chunk.recent().len(), 2);
    }

    #[test]
    fn a_chunk_that_starts_with_a_plunge_takes_the_heading_of_the_first_move_in_xy() {
        let mut slices = block();
        let version = slices.raster(0).version();
        let mut chunk = Chunk::new(1, CELL);
        for _ in 0..10 {
            chunk.push(&mut slices, &[RADIUS], (0.0, 0.0), (0.0, 0.0), 0.05);
        }
        chunk.push(&mut slices, &[RADIUS], (0.0, 0.05), (0.0, 1.0), 0.05);
        chunk.push(&mut slices, &[RADIUS], (0.0, 0.10), (0.0, 1.0), 0.05);
        assert_eq!(slices.raster(0).version(), version, "the plunge's foot was applied on its own");
        let corridor = chunk.corridor();
        assert!(corridor.ordered && corridor.dir.1 > 1.0 - 1e-12);
        // The chunk, when applied, clears the plunge's foot and the move.
        chunk.flush(&mut slices, &[RADIUS]);
        assert!(!slices.raster(0).is_material(0.0, -RADIUS + 0.5));
        assert!(!slices.raster(0).is_material(0.0, RADIUS + 0.05));
        assert!(slices.raster(0).is_material(0.0, -RADIUS - 0.5));
    }
}
