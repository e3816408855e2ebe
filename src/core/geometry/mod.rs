//! 2-D geometry: contours of lines and arcs (polylines with bulge), pockets with islands,
//! and their import from DXF.
//!
//! Coordinates are in mm, angles in radians. A contour ([`Loop`]) is a closed polyline whose
//! vertices carry the DXF bulge of the segment leaving them; a [`Pocket`] is a validated outer
//! loop (counter-clockwise) with islands (clockwise). [`Pocket::row_intervals`] is the scanline
//! primitive the stock rasteriser calls once per raster row.

pub mod chain;
pub mod contour;
pub mod dxf;
mod dxf_groups;
pub mod intersect;
pub mod pocket;
pub mod point;
pub mod segment;
pub mod segment_index;
pub mod validate;

pub use contour::{Loop, Vertex};
pub use dxf::loops_from_dxf;
pub use intersect::{Intersection, Intersections};
pub use pocket::{pocket_from_loops, Pocket};
pub use point::{Bounds, Point};
pub use segment::{ArcGeometry, Segment};
pub use segment_index::SegmentIndex;

/// Points closer than this are the same point, and two segments closer than this touch (mm).
pub const POINT_EPS_MM: f64 = crate::core::tolerance::LENGTH_EPS_MM;

/// A segment shorter than this is a zero-length segment (mm); an intersection of two adjacent
/// segments closer than this to their shared vertex is that vertex.
pub const MIN_SEGMENT_LENGTH_MM: f64 = 1e-6;

/// A loop enclosing less than this has no area (mm²).
pub const MIN_LOOP_AREA_MM2: f64 = 1e-9;

/// Formats a length for an error message: at most 6 decimals, trailing zeros dropped.
pub(crate) fn fmt_mm(value: f64) -> String {
    let text = format!("{value:.6}");
    let text = if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.') } else { text.as_str() };
    if text == "-0" {
        "0".to_string()
    } else {
        text.to_string()
    }
}

/// Formats a point `(x, y)` for an error message.
pub(crate) fn fmt_point(p: Point) -> String {
    format!("({}, {})", fmt_mm(p.x), fmt_mm(p.y))
}

/// Comparisons with explicit tolerances, and shapes, for the tests of the crate.
#[cfg(test)]
pub(crate) mod test_support {
    use super::{Bounds, Loop, Pocket, Vertex};

    /// A 40 × 30 mm pocket whose right and left sides bulge out as arcs, with a 10 × 10 mm
    /// square island.
    pub fn rounded_ring() -> Pocket {
        let outer = Loop::new(vec![
            Vertex::new(0.0, 0.0, 0.0),
            Vertex::new(40.0, 0.0, 0.4),
            Vertex::new(40.0, 30.0, 0.0),
            Vertex::new(0.0, 30.0, -0.3),
        ]);
        let island = Loop::rectangle(15.0, 10.0, 25.0, 20.0).reversed();
        Pocket::new(outer, vec![island]).expect("valid")
    }

    /// `true` when every side of `a` is within `tol_mm` of the same side of `b`.
    pub fn bounds_near(a: &Bounds, b: &Bounds, tol_mm: f64) -> bool {
        (a.x_min - b.x_min).abs() <= tol_mm
            && (a.y_min - b.y_min).abs() <= tol_mm
            && (a.x_max - b.x_max).abs() <= tol_mm
            && (a.y_max - b.y_max).abs() <= tol_mm
    }

    /// `true` when the loops have as many vertices and each coordinate and bulge of one is
    /// within `tol` of the other's.
    pub fn loops_near(a: &Loop, b: &Loop, tol: f64) -> bool {
        a.vertices.len() == b.vertices.len()
            && a.vertices
                .iter()
                .zip(&b.vertices)
                .all(|(u, v)| (u.x - v.x).abs() <= tol && (u.y - v.y).abs() <= tol && (u.bulge - v.bulge).abs() <= tol)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_in_messages_drop_trailing_zeros() {
        assert_eq!(fmt_mm(5.0), "5");
        assert_eq!(fmt_mm(2.5), "2.5");
        assert_eq!(fmt_mm(-1e-12), "0");
        assert_eq!(fmt_point(Point::new(1.0 / 3.0, 10.0)), "(0.333333, 10)");
    }
}
