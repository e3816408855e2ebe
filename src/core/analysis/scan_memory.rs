//! What the probe of one slice remembers while the tool moves along a straight line over
//! an unchanged raster with the same leading half: each coarse point then slides along
//! a line of its own, and a state found to hold over a stretch of that line (a uniform
//! tile neighbourhood, a chain of them along it, or uniform cells along it) needs no
//! probe until the stretch ends.

use super::probe::{points, COARSE_POINTS};

/// Positions may stray this far from the remembered line, cells (rounding).
pub const LATERAL_TOLERANCE_CELLS: f64 = 1e-6;
/// When a remembered state expires, those that would within this much more travel are
/// dropped too, cells: the remembered states are then reviewed only every so often.
const EXPIRY_SLACK_CELLS: f64 = 2.0;

/// The straight stretch of path a sample lies on: an identifier, its unit direction and
/// how much of it lies ahead of the sample, in raster cells.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    pub id: usize,
    pub dir: (f64, f64),
    pub ahead_cells: f64,
}

/// Coarse states remembered along a line.
#[derive(Debug, Clone)]
pub struct ScanMemory {
    /// Raster version, first probe index of the leading half, line.
    key: Option<(u64, usize, usize)>,
    /// The tool centre on the raster's grid where the memory started, cells.
    origin: (f64, f64),
    dir: (f64, f64),
    /// Travel along `dir` per cell of displacement along either axis.
    travel_per_cell: f64,
    /// Coarse points (bit m for point m) whose state is remembered, and those states.
    held: u128,
    state: u128,
    /// Per coarse point: the travel (cells from `origin`) up to which its state holds
    /// (also after it is dropped from `held` a little early), and the travel before
    /// which no uniform stretch is looked for again.
    until: [f64; COARSE_POINTS + 1],
    retry: [f64; COARSE_POINTS + 1],
    /// No remembered state expires before this travel.
    first_expiry: f64,
    /// Per coarse interval, where the last boundary found in it lay, probe steps into it
    /// (0: none); a hint for the next bisection, whatever the line or raster.
    hints: [u8; COARSE_POINTS],
    /// Per coarse interval: the travel up to which every probe of the bisection that
    /// found its hint gives the same answer (so the bisection finds the same boundary
    /// again), and the travel before which that is not looked for again.
    settled: [f64; COARSE_POINTS],
    settle_retry: [f64; COARSE_POINTS],
    /// Per coarse interval (bit m): the state of its first point when it was settled.
    settled_from: u128,
}

impl Default for ScanMemory {
    fn default() -> Self {
        ScanMemory {
            key: None,
            origin: (0.0, 0.0),
            dir: (1.0, 0.0),
            travel_per_cell: 1.0,
            held: 0,
            state: 0,
            until: [f64::NEG_INFINITY; COARSE_POINTS + 1],
            retry: [f64::NEG_INFINITY; COARSE_POINTS + 1],
            first_expiry: f64::INFINITY,
            hints: [0; COARSE_POINTS],
            settled: [f64::NEG_INFINITY; COARSE_POINTS],
            settle_retry: [f64::NEG_INFINITY; COARSE_POINTS],
            settled_from: 0,
        }
    }
}

impl ScanMemory {
    /// The travel of the tool centre `grid_center` along `line` since the memory started,
    /// forgetting everything first when the raster `version`, the leading half (`first`)
    /// or the line changed or the centre left the line.
    pub fn travel(&mut self, version: u64, first: usize, line: Line, grid_center: (f64, f64)) -> f64 {
        let key = Some((version, first, line.id));
        let rel = (grid_center.0 - self.origin.0, grid_center.1 - self.origin.1);
        let lateral = (rel.0 * self.dir.1 - rel.1 * self.dir.0).abs();
        if self.key != key || lateral > LATERAL_TOLERANCE_CELLS {
            self.key = key;
            self.origin = grid_center;
            self.dir = line.dir;
            self.travel_per_cell = 1.0 / line.dir.0.abs().max(line.dir.1.abs());
            self.held = 0;
            self.until.fill(f64::NEG_INFINITY);
            self.retry.fill(f64::NEG_INFINITY);
            self.settled.fill(f64::NEG_INFINITY);
            self.settle_retry.fill(f64::NEG_INFINITY);
            self.first_expiry = f64::INFINITY;
            return 0.0;
        }
        rel.0 * self.dir.0 + rel.1 * self.dir.1
    }

    /// Forgets every remembered state (the probe's circle changed: a slice that takes a
    /// radius or ball end mill at another radius); the next [`ScanMemory::travel`] starts
    /// afresh. The bisection hints stay: they are hints whatever the line or raster.
    pub fn forget(&mut self) {
        self.key = None;
    }

    /// The direction of the remembered line.
    pub fn dir(&self) -> (f64, f64) {
        self.dir
    }

    /// Travel along the line per cell of displacement along either axis.
    pub fn travel_per_cell(&self) -> f64 {
        self.travel_per_cell
    }

    /// The coarse points whose state still holds at `travel`, and the states.
    pub fn recall(&mut self, travel: f64) -> (u128, u128) {
        if travel > self.first_expiry {
            self.first_expiry = f64::INFINITY;
            let horizon = travel + EXPIRY_SLACK_CELLS;
            let mut held = self.held;
            while held != 0 {
                let m = held.trailing_zeros() as usize;
                held &= held - 1;
                if horizon > self.until[m] {
                    self.held &= !(1 << m);
                } else {
                    self.first_expiry = self.first_expiry.min(self.until[m]);
                }
            }
        }
        (self.held, self.state)
    }

    /// The coarse points of `mask` have `state` up to the travels in `until` (set by the
    /// caller), the earliest of them `earliest`.
    fn hold(&mut self, mask: u128, state: bool, earliest: f64) {
        self.held |= mask;
        self.state = if state { self.state | mask } else { self.state & !mask };
        self.first_expiry = self.first_expiry.min(earliest);
    }

    /// A probe of coarse point `centre` at `travel` found `state` over every position
    /// within `cells` (along either axis): it holds for the points `lo..=hi` around it as
    /// long as they stay inside, `chord_cells[n]` being the distance between points n
    /// apart (increasing with n).
    pub fn hold_disc(
        &mut self,
        centre: usize,
        (lo, hi): (usize, usize),
        travel: f64,
        state: bool,
        cells: f64,
        chord_cells: &[f64],
    ) {
        // The chords increase with the distance from the centre: the points that stay
        // inside are a run around it.
        let (mut first, mut last, mut earliest) = (usize::MAX, 0, f64::INFINITY);
        for k in lo..=hi {
            let reach = (cells - chord_cells[k.abs_diff(centre)] - LATERAL_TOLERANCE_CELLS) * self.travel_per_cell;
            if reach > 0.0 {
                debug_assert!(first == usize::MAX || last + 1 == k, "the points that hold are not a run");
                // A longer hold of the same state may remain from an earlier probe.
                self.until[k] = self.until[k].max(travel + reach);
                earliest = earliest.min(self.until[k]);
                first = first.min(k);
                last = k;
            }
        }
        if first <= last {
            self.hold(points(first, last), state, earliest);
        }
    }

    /// Coarse point `m` has `state` from `travel` over the next `length` cells of travel.
    pub fn hold_ahead(&mut self, m: usize, travel: f64, state: bool, length: f64) {
        self.until[m] = self.until[m].max(travel + length - LATERAL_TOLERANCE_CELLS);
        self.hold(1 << m, state, self.until[m]);
    }

    /// Where the last boundary found in coarse interval `m` lay, probe steps into it.
    pub fn boundary_hint(&self, m: usize) -> usize {
        usize::from(self.hints[m])
    }

    /// A boundary was found `steps` probe steps into coarse interval `m` (by a bisection:
    /// the interval is no longer settled).
    pub fn set_boundary_hint(&mut self, m: usize, steps: usize) {
        self.hints[m] = u8::try_from(steps).unwrap_or(0);
        self.settled[m] = f64::NEG_INFINITY;
    }

    /// The boundary in coarse interval `m` (probe steps into it) when the bisection from
    /// a first point of state `from` is known to find it again at `travel`.
    pub fn settled_boundary(&self, m: usize, travel: f64, from: bool) -> Option<usize> {
        let same_from = (self.settled_from >> m) & 1 == u128::from(from);
        (travel <= self.settled[m] && same_from).then(|| self.boundary_hint(m))
    }

    /// `true` when it is worth checking at `travel` whether the probes of the bisection in
    /// coarse interval `m` keep their answers ahead.
    pub fn should_settle(&self, m: usize, travel: f64) -> bool {
        travel >= self.settle_retry[m]
    }

    /// The probes of the bisection in coarse interval `m` from a first point of state
    /// `from`, at `travel`, keep their answers over the next `length` cells of travel
    /// (`Some`), or not (`None`: the next check waits for `wait` cells of travel).
    pub fn settle(&mut self, m: usize, travel: f64, from: bool, length: Option<f64>, wait: f64) {
        match length {
            Some(length) => {
                self.settled[m] = travel + length - LATERAL_TOLERANCE_CELLS;
                self.settled_from = (self.settled_from & !(1 << m)) | (u128::from(from) << m);
            }
            None => self.settle_retry[m] = travel + wait,
        }
    }

    /// `true` when a uniform stretch ahead of coarse point `m` is worth looking for at
    /// `travel`.
    pub fn should_look(&self, m: usize, travel: f64) -> bool {
        travel >= self.retry[m]
    }

    /// No uniform stretch was found ahead of coarse point `m` at `travel`: the next look
    /// waits for `wait` cells of travel.
    pub fn not_found(&mut self, m: usize, travel: f64, wait: f64) {
        self.retry[m] = travel + wait;
    }
}
