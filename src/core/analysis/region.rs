//! Stock regions of an analysis: painted into the slices' rasters.

use crate::core::geometry::contour::pair_crossings;
use crate::core::geometry::{Pocket, Point, SegmentIndex};
use crate::core::progress::Progress;
use crate::core::stock::{rect_signed_distance, Raster, Rect, SDF_CLAMP_CELLS};
use crate::core::CoreError;

/// A region of the XY plane.
#[derive(Debug, Clone, PartialEq)]
pub enum StockRegion {
    Rect(Rect),
    Circle {
        cx: f64,
        cy: f64,
        r: f64,
    },
    /// A validated pocket: its outer loop minus its islands.
    Pocket(Pocket),
}

impl StockRegion {
    pub fn bounds(&self) -> Rect {
        match *self {
            StockRegion::Rect(r) => r,
            StockRegion::Circle { cx, cy, r } => Rect { x_min: cx - r, y_min: cy - r, x_max: cx + r, y_max: cy + r },
            StockRegion::Pocket(ref p) => {
                let b = p.bounds();
                Rect { x_min: b.x_min, y_min: b.y_min, x_max: b.x_max, y_max: b.y_max }
            }
        }
    }

    /// The x-intervals inside the region on the line at `y`.
    pub fn row_intervals(&self, y: f64, out: &mut Vec<(f64, f64)>) {
        match *self {
            StockRegion::Rect(r) => {
                if y >= r.y_min && y < r.y_max {
                    out.push((r.x_min, r.x_max));
                }
            }
            StockRegion::Circle { cx, cy, r } => {
                let h2 = r * r - (y - cy) * (y - cy);
                if h2 > 0.0 {
                    let h = h2.sqrt();
                    out.push((cx - h, cx + h));
                }
            }
            StockRegion::Pocket(ref p) => p.row_intervals(y, out),
        }
    }
}

impl StockRegion {
    /// Signed distance to the region's boundary, positive inside.
    pub fn signed_distance(&self, x: f64, y: f64) -> f64 {
        match *self {
            StockRegion::Rect(r) => rect_signed_distance(&r, x, y),
            StockRegion::Circle { cx, cy, r } => r - (x - cx).hypot(y - cy),
            StockRegion::Pocket(ref p) => {
                let q = Point::new(x, y);
                let d = std::iter::once(&p.outer)
                    .chain(&p.islands)
                    .flat_map(|l| l.segments())
                    .map(|s| s.distance_mm(q))
                    .fold(f64::INFINITY, f64::min);
                if p.contains(x, y) {
                    d
                } else {
                    -d
                }
            }
        }
    }
}

/// Bounds of the union of `regions`.
pub fn union_bounds(regions: &[StockRegion]) -> Rect {
    regions.iter().map(StockRegion::bounds).fold(
        Rect { x_min: f64::INFINITY, y_min: f64::INFINITY, x_max: f64::NEG_INFINITY, y_max: f64::NEG_INFINITY },
        |a, b| Rect {
            x_min: a.x_min.min(b.x_min),
            y_min: a.y_min.min(b.y_min),
            x_max: a.x_max.max(b.x_max),
            y_max: a.y_max.max(b.y_max),
        },
    )
}

/// Paints `stock` as material and clears `open`, reporting the share of the regions'
/// rows painted to `progress`; stops (`Err(Cancelled)`) as soon as `progress` is
/// cancelled, since a contour of many segments on a large raster takes seconds.
pub fn paint(
    raster: &mut Raster,
    stock: &[StockRegion],
    open: &[StockRegion],
    progress: &dyn Progress,
) -> Result<(), CoreError> {
    let regions = stock.iter().map(|r| (true, r)).chain(open.iter().map(|r| (false, r)));
    let count = (stock.len() + open.len()) as f64;
    for (n, (add, region)) in regions.enumerate() {
        let stopped = |done: f64| {
            progress.report((n as f64 + done) / count);
            progress.cancelled()
        };
        let painted = match region {
            StockRegion::Pocket(p) => paint_pocket(raster, add, p, stopped),
            _ => raster.paint_until(
                add,
                |y, out| region.row_intervals(y, out),
                |x, y, _| region.signed_distance(x, y),
                stopped,
            ),
        };
        if !painted {
            return Err(CoreError::Cancelled);
        }
    }
    Ok(())
}

/// Paints a pocket through an index of its segments: each row and each band cell visits
/// only the segments near it. The same cells as [`StockRegion::signed_distance`] gives:
/// distances beyond the raster's clamp are stored as the clamp either way.
fn paint_pocket(raster: &mut Raster, add: bool, p: &Pocket, stopped: impl FnMut(f64) -> bool) -> bool {
    let index = SegmentIndex::new(std::iter::once(&p.outer).chain(&p.islands), 0.0);
    let reach_mm = (SDF_CLAMP_CELLS + 1.0) * raster.cell_mm();
    let intervals = |y: f64, out: &mut Vec<(f64, f64)>| {
        out.clear();
        index.row_crossings(y, |x| out.push((x, x)));
        pair_crossings(out);
    };
    // Inside or outside comes from the row's crossings, which the painter has: a ray
    // cast per band cell would cross every segment to its right on the row.
    let mut nearest = index.nearest_within(reach_mm);
    let distance = |x: f64, y: f64, inside: bool| {
        let d = nearest.distance(Point::new(x, y));
        if inside {
            d
        } else {
            -d
        }
    };
    raster.paint_until(add, intervals, distance, stopped)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::{Loop, Vertex};
    use crate::core::progress::NoProgress;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Cancelled once it has been asked `after` times.
    struct CancelledAfter {
        asked: AtomicUsize,
        after: usize,
    }

    impl Progress for CancelledAfter {
        fn report(&self, _fraction: f64) {}
        fn cancelled(&self) -> bool {
            self.asked.fetch_add(1, Ordering::Relaxed) >= self.after
        }
    }

    #[test]
    fn painting_stops_part_of_the_way_when_the_job_is_cancelled() {
        let p = crate::core::geometry::test_support::rounded_ring();
        let mut raster = raster_over(&p, 0.05);
        let cancel = CancelledAfter { asked: AtomicUsize::new(0), after: 10 };
        let stopped = paint(&mut raster, &[StockRegion::Pocket(p.clone())], &[], &cancel);
        assert!(matches!(stopped, Err(CoreError::Cancelled)), "{stopped:?}");
        assert_eq!(cancel.asked.load(Ordering::Relaxed), 11, "asked once a row until cancelled");
        let mut whole = raster_over(&p, 0.05);
        paint(&mut whole, &[StockRegion::Pocket(p.clone())], &[], &NoProgress).expect("nothing cancels it");
        assert!((whole.material_area_mm2() - p.area()).abs() < 0.01 * p.area());
    }

    fn raster_over(p: &Pocket, cell_mm: f64) -> Raster {
        let b = p.bounds();
        Raster::new(Rect { x_min: b.x_min, y_min: b.y_min, x_max: b.x_max, y_max: b.y_max }, cell_mm)
    }

    #[test]
    fn a_pocket_painted_through_its_segment_index_has_the_cells_of_the_pocket_itself() {
        let ring = crate::core::geometry::test_support::rounded_ring();
        let border = crate::core::pocketing::test_support::border_dxf();
        for (p, cell) in [(ring, 0.1), (border, 0.2)] {
            let region = StockRegion::Pocket(p.clone());
            let mut indexed = raster_over(&p, cell);
            paint(&mut indexed, std::slice::from_ref(&region), &[], &NoProgress).expect("nothing cancels it");
            let mut direct = raster_over(&p, cell);
            direct.paint(true, |y, out| region.row_intervals(y, out), |x, y, _| region.signed_distance(x, y));
            assert!(indexed.cell_values() == direct.cell_values(), "cells differ");
            assert!(indexed.material_area_mm2() > 0.0);
        }
    }

    #[test]
    fn a_contour_of_twenty_thousand_vertices_paints_its_area() {
        // A comb: 5 000 teeth 19 mm long, 0.5 mm wide, 0.5 mm apart.
        let teeth = 5_000;
        let mut v = Vec::with_capacity(4 * teeth + 2);
        for k in 0..teeth {
            let y = f64::from(k as u32);
            v.extend([(20.0, y), (20.0, y + 0.5), (1.0, y + 0.5), (1.0, y + 1.0)]);
        }
        let top = f64::from(teeth as u32);
        v.extend([(0.0, top), (0.0, 0.0)]);
        let outer = Loop::new(v.into_iter().map(|(x, y)| Vertex::new(x, y, 0.0)).collect());
        let comb = Pocket::new(outer, vec![]).expect("valid");
        let mut raster = raster_over(&comb, 0.25);
        paint(&mut raster, &[StockRegion::Pocket(comb.clone())], &[], &NoProgress).expect("nothing cancels it");
        let (painted, exact) = (raster.material_area_mm2(), comb.area());
        assert!((painted - exact).abs() < 0.01 * exact, "{painted} vs {exact} mm²");
    }
}
