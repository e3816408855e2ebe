//! Points and axis-aligned bounds in the plane (mm).

use serde::{Deserialize, Serialize};

/// A point in the plane (mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// x coordinate (mm).
    pub x: f64,
    /// y coordinate (mm).
    pub y: f64,
}

impl Point {
    /// The point `(x, y)` (mm).
    pub const fn new(x: f64, y: f64) -> Point {
        Point { x, y }
    }

    /// Euclidean distance to `other` (mm).
    pub fn distance_mm(self, other: Point) -> f64 {
        (self.x - other.x).hypot(self.y - other.y)
    }

    /// `self + (dx, dy)`.
    pub fn offset(self, dx: f64, dy: f64) -> Point {
        Point::new(self.x + dx, self.y + dy)
    }

    /// The vector from `self` to `other`, as `(dx, dy)` (mm).
    pub fn vector_to(self, other: Point) -> (f64, f64) {
        (other.x - self.x, other.y - self.y)
    }

    /// `true` when `self` and `other` are closer than `tol_mm`.
    pub fn near(self, other: Point, tol_mm: f64) -> bool {
        self.distance_mm(other) <= tol_mm
    }
}

/// z-component of the cross product of `(ax, ay)` and `(bx, by)`.
pub(crate) fn cross(a: (f64, f64), b: (f64, f64)) -> f64 {
    a.0 * b.1 - a.1 * b.0
}

/// Dot product of `(ax, ay)` and `(bx, by)`.
pub(crate) fn dot(a: (f64, f64), b: (f64, f64)) -> f64 {
    a.0 * b.0 + a.1 * b.1
}

/// An axis-aligned bounding box (mm). [`Bounds::EMPTY`] contains nothing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Bounds {
    /// Smallest x (mm).
    pub x_min: f64,
    /// Smallest y (mm).
    pub y_min: f64,
    /// Largest x (mm).
    pub x_max: f64,
    /// Largest y (mm).
    pub y_max: f64,
}

impl Bounds {
    /// The empty box: the neutral element of [`Bounds::union`].
    pub const EMPTY: Bounds =
        Bounds { x_min: f64::INFINITY, y_min: f64::INFINITY, x_max: f64::NEG_INFINITY, y_max: f64::NEG_INFINITY };

    /// The box of a single point.
    pub fn of_point(p: Point) -> Bounds {
        Bounds { x_min: p.x, y_min: p.y, x_max: p.x, y_max: p.y }
    }

    /// `true` when the box contains no point.
    pub fn is_empty(&self) -> bool {
        self.x_min > self.x_max || self.y_min > self.y_max
    }

    /// Grows the box to contain `p`.
    pub fn include(&mut self, p: Point) {
        self.x_min = self.x_min.min(p.x);
        self.y_min = self.y_min.min(p.y);
        self.x_max = self.x_max.max(p.x);
        self.y_max = self.y_max.max(p.y);
    }

    /// The smallest box containing both boxes.
    pub fn union(self, other: Bounds) -> Bounds {
        Bounds {
            x_min: self.x_min.min(other.x_min),
            y_min: self.y_min.min(other.y_min),
            x_max: self.x_max.max(other.x_max),
            y_max: self.y_max.max(other.y_max),
        }
    }

    /// Width (mm); 0 for an empty box.
    pub fn width_mm(&self) -> f64 {
        (self.x_max - self.x_min).max(0.0)
    }

    /// Height (mm); 0 for an empty box.
    pub fn height_mm(&self) -> f64 {
        (self.y_max - self.y_min).max(0.0)
    }

    /// Length of the diagonal (mm); 0 for an empty box.
    pub fn diagonal_mm(&self) -> f64 {
        self.width_mm().hypot(self.height_mm())
    }

    /// `true` when the boxes, each grown by `margin_mm`, share a point.
    pub fn overlaps(&self, other: &Bounds, margin_mm: f64) -> bool {
        self.x_min <= other.x_max + margin_mm
            && other.x_min <= self.x_max + margin_mm
            && self.y_min <= other.y_max + margin_mm
            && other.y_min <= self.y_max + margin_mm
    }

    /// `true` when `p` lies in the box grown by `margin_mm`.
    pub fn contains_point(&self, p: Point, margin_mm: f64) -> bool {
        self.overlaps(&Bounds::of_point(p), margin_mm)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tolerance of exact results (mm).
    const TOL: f64 = 1e-12;

    #[test]
    fn the_union_with_the_empty_box_is_the_box_itself() {
        let b = Bounds::of_point(Point::new(1.0, 2.0)).union(Bounds::of_point(Point::new(3.0, -1.0)));
        assert!(crate::core::geometry::test_support::bounds_near(&b.union(Bounds::EMPTY), &b, TOL));
        assert!(Bounds::EMPTY.is_empty());
        assert!(!b.is_empty());
        assert!((b.width_mm() - 2.0).abs() < TOL);
        assert!((b.height_mm() - 3.0).abs() < TOL);
    }

    #[test]
    fn boxes_apart_by_less_than_the_margin_overlap() {
        let a = Bounds::of_point(Point::new(0.0, 0.0));
        let b = Bounds::of_point(Point::new(1.0, 0.0));
        assert!(!a.overlaps(&b, 0.5));
        assert!(a.overlaps(&b, 1.0));
        assert!(a.contains_point(Point::new(0.1, 0.1), 0.2));
    }
}
