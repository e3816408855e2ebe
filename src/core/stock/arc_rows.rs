//! The rows of cells an arc update touches (the area a disc sweeps along a circular arc),
//! found once for every raster of one grid, as [`super::CapsuleRows`] are for a capsule.

use super::arc_sweep::ArcSweep;
use super::{Raster, SDF_CLAMP_CELLS};

/// The cells of each row one arc update touches, found when first needed; one value
/// serves arc after arc without allocating again ([`ArcRows::set`]).
pub struct ArcRows {
    arc: ArcSweep,
    r: f64,
    grid: (f64, f64, f64, usize, usize),
    /// Where material near the arc is looked for: centre and reach, mm.
    near: ((f64, f64), f64),
    rows: (usize, usize),
    spans: Vec<RowSpan>,
    found: bool,
}

/// Cells [from, to) of row `j`: inside the swept area by the clamp width (cleared), or in
/// the band about its edge (each takes its distance).
struct RowSpan {
    j: usize,
    from: usize,
    to: usize,
    inside: bool,
}

impl ArcRows {
    /// The rows of the area a disc of radius `r` sweeps along `arc` on the grid of `grid`.
    pub fn new(grid: &Raster, arc: ArcSweep, r: f64) -> ArcRows {
        ArcRows::with_spans(grid, arc, r, Vec::new())
    }

    /// Makes these the rows of another arc, keeping the memory of the spans.
    pub fn set(&mut self, grid: &Raster, arc: ArcSweep, r: f64) {
        let mut spans = std::mem::take(&mut self.spans);
        spans.clear();
        *self = ArcRows::with_spans(grid, arc, r, spans);
    }

    fn with_spans(grid: &Raster, arc: ArcSweep, r: f64, spans: Vec<RowSpan>) -> ArcRows {
        let reach = SDF_CLAMP_CELLS * grid.cell_mm;
        let ((x_lo, x_hi), (y_lo, y_hi)) = arc.bounds(r + reach);
        let rows = grid.index_range(y_lo, y_hi, grid.y0, grid.ny);
        let near = (((x_lo + x_hi) / 2.0, (y_lo + y_hi) / 2.0), ((x_hi - x_lo) / 2.0).max((y_hi - y_lo) / 2.0));
        ArcRows { arc, r, grid: grid.grid(), near, rows, spans, found: false }
    }

    /// Finds the rows' spans on `grid`, unless they are already found.
    fn find_rows(&mut self, grid: &Raster) {
        if self.found {
            return;
        }
        self.found = true;
        let reach = SDF_CLAMP_CELLS * grid.cell_mm;
        let (arc, outer, inner) = (&self.arc, self.r + reach, self.r - reach);
        let x_range = arc.bounds(outer).0;
        for j in self.rows.0..self.rows.1 {
            let y = grid.row_y(j);
            let inside = arc.row_inside(y, inner);
            for (lo, hi) in arc.row_cover_within(y, outer, x_range).iter() {
                let (from, to) = grid.cell_range(lo, hi);
                let mut at = from;
                for (l, h) in inside.iter() {
                    // The inside lies within the cover (a smaller distance).
                    let (in_from, in_to) = grid.cell_range(l, h);
                    let (in_from, in_to) = (in_from.clamp(at, to), in_to.clamp(at, to));
                    if in_from >= in_to {
                        continue;
                    }
                    if at < in_from {
                        self.spans.push(RowSpan { j, from: at, to: in_from, inside: false });
                    }
                    self.spans.push(RowSpan { j, from: in_from, to: in_to, inside: true });
                    at = in_to;
                }
                if at < to {
                    self.spans.push(RowSpan { j, from: at, to, inside: false });
                }
            }
        }
    }
}

impl Raster {
    /// Removes the area a disc of radius `r` sweeps along an arc, with its rows found for a
    /// raster of the same grid: cells deep inside lose their material, cells in the band
    /// about its edge take their distance to it. Air that no probe can read beside
    /// material is left as it is, as by [`Raster::clear_capsule_rows`]. Returns `false`
    /// when no material lies near the arc (nothing changed).
    pub fn clear_arc_rows(&mut self, rows: &mut ArcRows) -> bool {
        debug_assert!(rows.grid == self.grid(), "an arc's rows found on another grid");
        self.end_disc_cleared = false;
        let ((x, y), reach) = rows.near;
        if rows.rows.1 == 0 || !self.any_material_near(x, y, reach) {
            return false;
        }
        rows.find_rows(self);
        for span in &rows.spans {
            if span.inside {
                self.clear_cells(span.j, span.from, span.to);
            } else {
                self.band_cells(span.j, span.from, span.to, &rows.arc, rows.r, false);
            }
        }
        // The disc about the arc's end is inside the swept area: cleared.
        self.end_disc_cleared = true;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_blocks::{block, counts_of_the_cells, shares_a_probe_with_material};
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        #[test]
        fn an_arc_update_gives_every_cell_a_probe_reads_its_distance_to_the_swept_area(
            center in (5.0..35.0f64, 5.0..35.0f64),
            arcs in prop::collection::vec((0.2..12.0f64, 0.0..std::f64::consts::TAU, -1.5..1.5f64), 1..6),
            radius in 0.3..6.0f64,
        ) {
            let mut raster = block();
            let mut reference = block();
            for &(rho, start, sweep) in &arcs {
                let at = |t: f64| (center.0 + rho * t.cos(), center.1 + rho * t.sin());
                let arc = ArcSweep::new(center, at(start), at(start + sweep), sweep > 0.0);
                raster.clear_arc_rows(&mut ArcRows::new(&raster, arc, radius));
                // Every cell, one by one.
                for j in 0..reference.ny {
                    for i in 0..reference.nx {
                        let k = j * reference.nx + i;
                        let d = arc.distance((reference.col_x(i), reference.row_y(j)));
                        reference.f[k] = reference.encode(d - radius).min(reference.f[k]);
                    }
                }
            }
            let worst = (0..reference.f.len())
                .filter(|&k| shares_a_probe_with_material(&reference, k))
                .map(|k| (i16::from(raster.f[k]) - i16::from(reference.f[k])).abs())
                .max();
            prop_assert!(worst.unwrap_or(0) == 0, "cells differ by {:?}", worst);
            let differing_sign = raster.f.iter().zip(&reference.f).filter(|(p, q)| (**p > 0) != (**q > 0)).count();
            prop_assert!(differing_sign == 0, "{} cells change side", differing_sign);
            let (blocks, tiles) = counts_of_the_cells(&raster);
            prop_assert!(blocks, "block counts differ");
            prop_assert!(tiles, "tile counts differ");
        }
    }
}
