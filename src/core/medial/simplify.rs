//! Douglas–Peucker simplification of a branch, in position and clearance together, so that the
//! kept points still give `R` along the branch by linear interpolation (seed 004 §2.3 reads the
//! R/r classes off the branch).

use crate::core::geometry::Point;

/// Indices of the points of the polyline `(points, clearance_mm)` to keep: the first, the last,
/// and enough others that every dropped point lies within `tol_mm` of the chord between its
/// kept neighbours, and its R within `tol_mm` of R interpolated along that chord.
pub(crate) fn douglas_peucker(points: &[Point], clearance_mm: &[f64], tol_mm: f64) -> Vec<usize> {
    let n = points.len();
    if n <= 2 {
        return (0..n).collect();
    }
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0, n - 1)];
    while let Some((a, b)) = stack.pop() {
        let mut worst = (0.0, a);
        for i in a + 1..b {
            let d =
                deviation_mm((points[a], clearance_mm[a]), (points[b], clearance_mm[b]), (points[i], clearance_mm[i]));
            if d > worst.0 {
                worst = (d, i);
            }
        }
        if worst.0 > tol_mm {
            keep[worst.1] = true;
            stack.push((a, worst.1));
            stack.push((worst.1, b));
        }
    }
    (0..n).filter(|&i| keep[i]).collect()
}

/// How far `p` (with its R) lies from the chord `a`–`b` (with R interpolated along it): the
/// larger of the distance in the plane and the difference in R (mm).
fn deviation_mm(a: (Point, f64), b: (Point, f64), p: (Point, f64)) -> f64 {
    let (dx, dy) = a.0.vector_to(b.0);
    let (px, py) = a.0.vector_to(p.0);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 { ((px * dx + py * dy) / len2).clamp(0.0, 1.0) } else { 0.0 };
    let foot = a.0.offset(t * dx, t * dy);
    let r = a.1 + t * (b.1 - a.1);
    foot.distance_mm(p.0).max((p.1 - r).abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_on_a_straight_branch_with_linear_clearance_are_dropped() {
        let points: Vec<Point> = (0..11).map(|i| Point::new(i as f64, 0.0)).collect();
        let clearance: Vec<f64> = (0..11).map(|i| 5.0 + 0.1 * i as f64).collect();
        assert_eq!(douglas_peucker(&points, &clearance, 1e-6), vec![0, 10]);
    }

    #[test]
    fn a_bend_in_position_or_in_clearance_is_kept() {
        let points: Vec<Point> = (0..11).map(|i| Point::new(i as f64, if i == 5 { 1.0 } else { 0.0 })).collect();
        let flat = vec![5.0; 11];
        assert_eq!(douglas_peucker(&points, &flat, 0.1), vec![0, 4, 5, 6, 10]);
        let straight: Vec<Point> = (0..11).map(|i| Point::new(i as f64, 0.0)).collect();
        let peaked: Vec<f64> = (0..11).map(|i| 5.0 - (i as f64 - 5.0).abs()).collect();
        assert_eq!(douglas_peucker(&straight, &peaked, 0.1), vec![0, 5, 10]);
    }
}
