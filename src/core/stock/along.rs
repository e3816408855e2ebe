//! The state of every probe along a segment at once: a probe reads only the 2 × 2 cells
//! around its point ([`Raster::is_material_at`]), so when all the cells read along a
//! segment hold material (or none does), every probe on it gives the same answer; and
//! along a row (or column), when the two rows it reads hold the same value in every
//! column it passes, every probe on it reads the same values.

use super::{Raster, DECISIVE};

/// A segment no wider than this along x reads the same columns in every row, cells.
const NARROW_CELLS: f64 = 1.0;
/// [`Raster::constant_along`] widens the segment by this across (rounding of the probe
/// positions), cells.
const ACROSS_ROUNDING_CELLS: f64 = 1e-9;
/// Cells compared at once by [`all_equal`].
const ALL_EQUAL_STRETCH: usize = 32;
/// An interpolated value this close to zero is not decided by
/// [`Raster::constant_along`] (rounding of the interpolation), stored units.
const INTERPOLATION_ROUNDING: f64 = 1e-9;

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
                // Probes within the margin of the segment at these y lie within the margin
                // of its points within the margin of these y.
                let (s_lo, s_hi) = (g0.1.min(g1.1), g0.1.max(g1.1));
                let (ys, ye) = ((ya - margin).clamp(s_lo, s_hi), (yb + margin).clamp(s_lo, s_hi));
                let (p, q) = (g0.0 + (ys - g0.1) * slope, g0.0 + (ye - g0.1) * slope);
                let xa = (p.min(q) - margin).max(x_lo);
                (xa, (p.max(q) + margin).min(x_hi).max(xa))
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

    /// `Some(material)` when every probe within `margin` cells of the segment from grid
    /// position `g0` to `g1`, which runs along a row or a column, gives the answer
    /// `material`, because the two rows (columns) it reads hold one value each all along
    /// it: the probe then reads the same values wherever it is along the segment (near a
    /// boundary too, where [`Raster::uniform_along`] decides nothing).
    pub fn constant_along(&self, g0: (f64, f64), g1: (f64, f64), margin: f64) -> Option<bool> {
        let lo = |a: f64, b: f64| a.min(b) - margin;
        let hi = |a: f64, b: f64| a.max(b) + margin;
        let along_x = (g1.1 - g0.1).abs() <= (g1.0 - g0.0).abs();
        // Along x, the probe reads rows j, j + 1 over columns; along y, the reverse.
        let (along, across) = if along_x { ((g0.0, g1.0), (g0.1, g1.1)) } else { ((g0.1, g1.1), (g0.0, g1.0)) };
        let (n_along, n_across) = if along_x { (self.nx, self.ny) } else { (self.ny, self.nx) };
        let (a_lo, a_hi) = (lo(along.0, along.1), hi(along.0, along.1));
        let (c_lo, c_hi) =
            (lo(across.0, across.1) - ACROSS_ROUNDING_CELLS, hi(across.0, across.1) + ACROSS_ROUNDING_CELLS);
        if !(a_lo >= 0.0
            && c_lo >= 0.0
            && a_hi + 1.0 < f64::from(n_along as u32)
            && c_hi + 1.0 < f64::from(n_across as u32))
        {
            return None;
        }
        // The two lines read across: both ends of the range must read the same two.
        let line = c_lo as usize;
        if c_hi as usize != line {
            return None;
        }
        let (t_lo, t_hi) = (c_lo - line as f64, c_hi - line as f64);
        let (first, last) = (a_lo as usize, a_hi as usize + 1);
        let constant = if along_x {
            // Two stretches of rows.
            let (r0, r1) = (line * self.nx, (line + 1) * self.nx);
            all_equal(&self.f[r0 + first..=r0 + last]) && all_equal(&self.f[r1 + first..=r1 + last])
        } else {
            // The two columns are side by side in each row.
            let at = |k: usize| (self.f[k * self.nx + line], self.f[k * self.nx + line + 1]);
            let v = at(first);
            (first + 1..=last).all(|k| at(k) == v)
        };
        if !constant {
            return None;
        }
        let at = |k: usize, l: usize| if along_x { self.f[l * self.nx + k] } else { self.f[k * self.nx + l] };
        decide_between(at(first, line), at(first, line + 1), (t_lo, t_hi))
    }
}

/// `true` when every cell of `cells` (at least one) holds the first one's value; tested a
/// stretch at a time without stopping inside it, so each stretch is compared at once.
fn all_equal(cells: &[i8]) -> bool {
    let v = cells[0];
    cells.chunks(ALL_EQUAL_STRETCH).all(|stretch| stretch.iter().fold(true, |same, &c| same & (c == v)))
}

/// The answer of every probe that reads the value `v0` on one line and `v1` on the next,
/// at a fraction of the way between them within `t` (as [`Raster::is_material_at`]
/// decides it), when all give the same.
fn decide_between(v0: i8, v1: i8, (t_lo, t_hi): (f64, f64)) -> Option<bool> {
    if v0 > 0 && v1 > 0 {
        return Some(true);
    }
    if v0 <= 0 && v1 <= 0 {
        return Some(false);
    }
    // The nearest line decides alone when it is far from the boundary.
    let nearest = if t_hi <= 0.5 {
        v0
    } else if t_lo > 0.5 {
        v1
    } else {
        return None;
    };
    if nearest.unsigned_abs() >= DECISIVE {
        return Some(nearest > 0);
    }
    let (a, b) = (f64::from(v0), f64::from(v1));
    let (p, q) = (a + (b - a) * t_lo, a + (b - a) * t_hi);
    if p > INTERPOLATION_ROUNDING && q > INTERPOLATION_ROUNDING {
        Some(true)
    } else if p < -INTERPOLATION_ROUNDING && q < -INTERPOLATION_ROUNDING {
        Some(false)
    } else {
        None
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
            r.paint(true, |y, out| if (0.0..20.0).contains(&y) { out.push((0.0, 20.0)) }, |x, y, _| rect_signed_distance(&rect, x, y));
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

        #[test]
        fn a_constant_row_or_column_gives_every_probe_along_it_the_same_answer(
            holes in prop::collection::vec((1.0..19.0f64, 1.0..19.0f64, 0.05..1.5f64), 1..6),
            slots in prop::collection::vec((1.0..19.0f64, 0.3..3.0f64, any::<bool>()), 1..4),
            g0 in (20.0..180.0f64, 20.0..180.0f64),
            length in -60.0..60.0f64,
            along_x in any::<bool>(),
        ) {
            let rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 20.0, y_max: 20.0 };
            let mut r = Raster::new(rect, 0.1);
            r.paint(true, |y, out| if (0.0..20.0).contains(&y) { out.push((0.0, 20.0)) }, |x, y, _| rect_signed_distance(&rect, x, y));
            // Slots along the axes leave walls that are constant along them.
            for (at, half, horizontal) in slots {
                let (a, b) = if horizontal { ((-5.0, at), (25.0, at)) } else { ((at, -5.0), (at, 25.0)) };
                r.clear_capsule(a, b, half);
            }
            for (x, y, radius) in holes {
                r.clear_capsule((x, y), (x, y), radius);
            }
            let g1 = if along_x { (g0.0 + length, g0.1) } else { (g0.0, g0.1 + length) };
            let margin = 1e-6;
            if let Some(state) = r.constant_along(g0, g1, margin) {
                for k in 0..=400 {
                    let t = f64::from(k) / 400.0;
                    for off in [(0.0, 0.0), (margin, 0.0), (-margin, 0.0), (0.0, margin), (0.0, -margin)] {
                        let at = (g0.0 + (g1.0 - g0.0) * t + off.0, g0.1 + (g1.1 - g0.1) * t + off.1);
                        prop_assert_eq!(r.is_material_at(at), state, "at {:?}", at);
                    }
                }
            }
        }
    }
}
