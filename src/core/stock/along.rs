//! The state of every probe along a segment at once: a probe reads only the 2 × 2 cells
//! around its point ([`Raster::is_material_at`]), so when all the cells read along a
//! segment hold material (or none does), every probe on it gives the same answer.

use super::Raster;

/// A segment no wider than this along x reads the same columns in every row, cells.
const NARROW_CELLS: f64 = 1.0;

impl Raster {
    /// `Some(material)` when every probe within `margin` cells of the segment from grid
    /// position `g0` to `g1` (see [`Raster::grid_position`]) reads only cells inside the
    /// raster that all hold material (`true`) or none (`false`).
    pub fn uniform_along(&self, g0: (f64, f64), g1: (f64, f64), margin: f64) -> Option<bool> {
        let (x_lo, x_hi) = (g0.0.min(g1.0) - margin, g0.0.max(g1.0) + margin);
        let (y_lo, y_hi) = (g0.1.min(g1.1) - margin, g0.1.max(g1.1) + margin);
        if !(x_lo >= 0.0
            && y_lo >= 0.0
            && x_hi + 1.0 < f64::from(self.nx as u32)
            && y_hi + 1.0 < f64::from(self.ny as u32))
        {
            return None;
        }
        let (dx, dy) = (g1.0 - g0.0, g1.1 - g0.1);
        let (mut all_in, mut all_out) = (true, true);
        let rows = (y_lo as usize)..=(y_hi as usize + 1);
        if x_hi - x_lo <= NARROW_CELLS {
            // Every row reads the same few columns.
            let (c0, c1) = (x_lo as usize, x_hi as usize + 1);
            for j in rows {
                let row = &self.f[j * self.nx + c0..=j * self.nx + c1];
                all_in &= row.iter().all(|&v| v > 0);
                all_out &= row.iter().all(|&v| v <= 0);
                if !(all_in || all_out) {
                    return None;
                }
            }
            return Some(all_in);
        }
        // x along the segment as a function of y (the whole x range when it runs along
        // the rows).
        let steep = dy.abs() > f64::EPSILON;
        let slope = if steep { dx / dy } else { 0.0 };
        // Cell row j is read by the points with y in [j − 1, j + 1).
        for j in rows {
            let (ya, yb) = ((j as f64 - 1.0).max(y_lo), (j as f64 + 1.0).min(y_hi));
            if ya > yb {
                continue;
            }
            let (xa, xb) = if steep {
                let (p, q) = (g0.0 + (ya - g0.1) * slope, g0.0 + (yb - g0.1) * slope);
                ((p.min(q) - margin).max(x_lo), (p.max(q) + margin).min(x_hi))
            } else {
                (x_lo, x_hi)
            };
            let k = j * self.nx;
            let row = &self.f[k + xa as usize..=k + xb as usize + 1];
            let (inside, outside) = row.iter().fold((true, true), |(i, o), &v| (i & (v > 0), o & (v <= 0)));
            all_in &= inside;
            all_out &= outside;
            if !(all_in || all_out) {
                return None;
            }
        }
        Some(all_in)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{rect_signed_distance, Rect};
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn a_uniform_segment_gives_every_probe_on_it_the_same_answer(
            holes in prop::collection::vec((1.0..19.0f64, 1.0..19.0f64, 0.05..1.5f64), 1..12),
            g0 in (20.0..180.0f64, 20.0..180.0f64),
            d in (-8.0..8.0f64, -8.0..8.0f64),
        ) {
            let rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 20.0, y_max: 20.0 };
            let mut r = Raster::new(rect, 0.1);
            r.paint(true, |y, out| if (0.0..20.0).contains(&y) { out.push((0.0, 20.0)) }, |x, y| rect_signed_distance(&rect, x, y));
            for (x, y, radius) in holes {
                r.clear_capsule((x, y), (x, y), radius);
            }
            let g1 = (g0.0 + d.0, g0.1 + d.1);
            let margin = 0.01;
            if let Some(state) = r.uniform_along(g0, g1, margin) {
                for k in 0..=400 {
                    let t = f64::from(k) / 400.0;
                    for off in [(0.0, 0.0), (margin, 0.0), (-margin, 0.0), (0.0, margin), (0.0, -margin)] {
                        let at = (g0.0 + d.0 * t + off.0, g0.1 + d.1 * t + off.1);
                        prop_assert_eq!(r.is_material_at(at), state, "at {:?}", at);
                    }
                }
            }
        }
    }
}
