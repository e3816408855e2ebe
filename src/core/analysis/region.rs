//! Stock regions of an analysis: painted into the slices' rasters.

use crate::core::geometry::{Pocket, Point};
use crate::core::stock::{rect_signed_distance, Raster, Rect};

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

/// Paints `stock` as material and clears `open`.
pub fn paint(raster: &mut Raster, stock: &[StockRegion], open: &[StockRegion]) {
    for region in stock {
        raster.paint(true, |y, out| region.row_intervals(y, out), |x, y| region.signed_distance(x, y));
    }
    for region in open {
        raster.paint(false, |y, out| region.row_intervals(y, out), |x, y| region.signed_distance(x, y));
    }
}
