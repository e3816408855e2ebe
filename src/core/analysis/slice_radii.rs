//! The radius each z slice takes the tool at (see [`super::profile`]), for a tool tip at a
//! given height, and the probe tables of those radii.
//!
//! A square end mill cuts every slice at its radius. A radius or ball end mill cuts the
//! slices within its corner above the tip at smaller radii; they change as the tip moves
//! in z. The radii are kept on a grid of [`RADIUS_STEPS_PER_CELL`] steps per raster cell:
//! a radius finer than that moves no boundary the raster can place, and a pass at one
//! height, or a ramp over a few cells, keeps the same radii (and their probe tables, made
//! once each) while it stays within a step.

use super::probe::AngleTable;
use super::profile::Profile;
use super::slices::Z_CONTACT_EPS_MM;
use super::stack::Stack;

/// Slice radii are rounded to this many steps per raster cell.
pub const RADIUS_STEPS_PER_CELL: f64 = 16.0;
/// Probe tables kept for the radii last used, at least (a ramp through a ball's corner uses
/// a few dozen at a time), and at least this many per slice in the corner: every sample
/// reads each of theirs, so fewer would be made again at every sample. (The corner's
/// slices are at least [`super::levels::MIN_SLICE_MM`] thick: a 16 mm ball has at most 161.)
const KEPT_TABLES: usize = 64;
const KEPT_TABLES_PER_CORNER_SLICE: usize = 2;

/// The radius of each slice for the tip the chunk was started at.
pub struct SliceRadii {
    profile: Profile,
    cell_mm: f64,
    /// Per slice, top first; slices below the tip keep the full radius (they are not cut).
    current: Vec<f64>,
    /// The radii wanted for the latest tip, before they are adopted.
    wanted: Vec<f64>,
    /// Probe tables by radius step, most recently used last.
    tables: Vec<(i64, AngleTable)>,
    /// The table of the full radius (every slice of a square end mill).
    full: AngleTable,
    /// The tip (its z's bits) and cut the wanted radii were last found for.
    found_for: Option<(u64, usize)>,
    /// The slices that may take less than the full radius in `current`, and in `wanted`
    /// (every other slice takes the full radius in both).
    band: std::ops::Range<usize>,
    wanted_band: std::ops::Range<usize>,
}

impl SliceRadii {
    /// The radii of a tool of `profile` over `slices` of rasters with cells of `cell_mm`,
    /// all at the full radius to begin with.
    pub fn new(profile: Profile, slices: usize, cell_mm: f64) -> SliceRadii {
        SliceRadii {
            profile,
            cell_mm,
            current: vec![profile.radius_mm; slices],
            wanted: vec![profile.radius_mm; slices],
            tables: Vec::new(),
            full: AngleTable::new(profile.radius_mm, cell_mm),
            found_for: None,
            band: 0..0,
            wanted_band: 0..0,
        }
    }

    /// `true` when every slice takes the full radius, wherever the tip is.
    pub fn cylinder(&self) -> bool {
        self.profile.is_cylinder()
    }

    /// The full radius, mm.
    pub fn full_mm(&self) -> f64 {
        self.profile.radius_mm
    }

    /// The radii of the slices, top first, mm.
    pub fn current(&self) -> &[f64] {
        &self.current
    }

    /// The table of the full radius.
    pub fn full_table(&self) -> &AngleTable {
        &self.full
    }

    /// `true` when slice `k` takes the full radius.
    pub fn is_full(&self, k: usize) -> bool {
        (self.current[k] - self.profile.radius_mm).abs() <= super::profile::SAME_RADIUS_MM
    }

    /// `true` when slices `a` and `b` take the same radius.
    pub fn same(&self, a: usize, b: usize) -> bool {
        (self.current[a] - self.current[b]).abs() <= super::profile::SAME_RADIUS_MM
    }

    /// Finds the radii of the `cut` top slices of `stack` for a tip at `tip_z`; `true` when
    /// any differs from the current ones (then [`SliceRadii::adopt`] takes them).
    pub fn differ_at(&mut self, stack: &Stack, cut: usize, tip_z: f64) -> bool {
        if self.cylinder() {
            return false;
        }
        if self.found_for == Some((tip_z.to_bits(), cut)) {
            // A pass at one height: the radii were adopted when it began.
            return false;
        }
        self.found_for = Some((tip_z.to_bits(), cut));
        let r = self.profile.radius_mm;
        let step = self.cell_mm / RADIUS_STEPS_PER_CELL;
        // The slices in the corner: a run of the cut ones from the deepest up.
        let slices = stack.slices();
        let cut = cut.min(slices.len());
        let in_corner = |k: usize| slices[k].z_bottom - tip_z < self.profile.corner_mm + Z_CONTACT_EPS_MM;
        let lo = (0..cut).rev().take_while(|&k| in_corner(k)).last().unwrap_or(cut);
        for k in self.wanted_band.clone() {
            self.wanted[k] = r;
        }
        for (wanted, s) in self.wanted[lo..cut].iter_mut().zip(&slices[lo..cut]) {
            let exact = self.profile.slice_radius_mm(tip_z, s.z_bottom, s.z_top);
            *wanted = ((exact / step).round() * step).min(r);
        }
        self.wanted_band = lo..cut;
        let seen = union(&self.band, &self.wanted_band);
        seen.into_iter().any(|k| (self.wanted[k] - self.current[k]).abs() > super::profile::SAME_RADIUS_MM)
    }

    /// Takes the radii [`SliceRadii::differ_at`] found; `changed` is called with each slice
    /// whose radius changes.
    pub fn adopt(&mut self, mut changed: impl FnMut(usize)) {
        for k in union(&self.band, &self.wanted_band) {
            if (self.current[k] - self.wanted[k]).abs() > super::profile::SAME_RADIUS_MM {
                self.current[k] = self.wanted[k];
                changed(k);
            }
        }
        self.band = self.wanted_band.clone();
    }

    /// The probe table of slice `k`'s radius (made on first use, kept for the latest
    /// [`KEPT_TABLES`] radii).
    pub fn table(&mut self, k: usize) -> &AngleTable {
        if self.is_full(k) {
            return &self.full;
        }
        let rho = self.current[k];
        let key = (rho / (self.cell_mm / RADIUS_STEPS_PER_CELL)).round() as i64;
        match self.tables.iter().position(|(at, _)| *at == key) {
            Some(i) => {
                let kept = self.tables.remove(i);
                self.tables.push(kept);
            }
            None => {
                if self.tables.len() >= KEPT_TABLES.max(KEPT_TABLES_PER_CORNER_SLICE * self.band.len()) {
                    self.tables.remove(0);
                }
                self.tables.push((key, self.full.with_radius(rho, self.cell_mm)));
            }
        }
        &self.tables.last().expect("a table was just pushed").1
    }
}

/// The slices of either run (and those between them).
fn union(a: &std::ops::Range<usize>, b: &std::ops::Range<usize>) -> std::ops::Range<usize> {
    match (a.is_empty(), b.is_empty()) {
        (true, _) => b.clone(),
        (_, true) => a.clone(),
        _ => a.start.min(b.start)..a.end.max(b.end),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::region::{paint, StockRegion};
    use crate::core::progress::NoProgress;
    use crate::core::stock::Rect;

    fn stack(levels: &[f64]) -> Stack {
        let rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 10.0, y_max: 10.0 };
        Stack::build(levels, rect, 0.1, |raster| paint(raster, &[StockRegion::Rect(rect)], &[], &NoProgress))
            .expect("nothing cancels the painting")
    }

    #[test]
    fn a_square_end_mill_takes_its_radius_in_every_slice_wherever_the_tip_is() {
        let slices = stack(&[0.0, -1.0, -2.0]);
        let mut radii = SliceRadii::new(Profile::cylinder(5.0), slices.len(), 0.1);
        assert!(!radii.differ_at(&slices, 2, -2.0));
        assert!(radii.current().iter().all(|&r| (r - 5.0).abs() < 1e-12));
    }

    #[test]
    fn a_ball_cuts_the_slices_within_its_corner_at_their_mean_radius_on_the_step_grid() {
        let slices = stack(&[0.0, -0.5, -5.5, -6.0]);
        let ball = Profile { radius_mm: 5.0, corner_mm: 5.0 };
        let mut radii = SliceRadii::new(ball, slices.len(), 0.1);
        assert!(radii.differ_at(&slices, 3, -6.0));
        let mut changed = Vec::new();
        radii.adopt(|k| changed.push(k));
        assert_eq!(changed, vec![1, 2], "the top slice lies above the corner");
        let step = 0.1 / RADIUS_STEPS_PER_CELL;
        for k in 1..3 {
            let s = &slices.slices()[k];
            let exact = ball.slice_radius_mm(-6.0, s.z_bottom, s.z_top);
            assert!((radii.current()[k] - exact).abs() <= step / 2.0 + 1e-12);
        }
        assert!(radii.is_full(0) && !radii.is_full(2));
        // The same tip again changes nothing.
        assert!(!radii.differ_at(&slices, 3, -6.0));
        let table = radii.table(2).radius_mm();
        assert!((table - radii.current()[2]).abs() < 1e-12);
    }
}
