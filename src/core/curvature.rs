//! Curvature of a tool-centre path made of minute line segments: a local polynomial fit
//! in arc length at every vertex (seed 000 §2: "a series of minute line segments ... is
//! approximated by a polynomial curve. Then, the curvature radius and the curvature
//! centre are computed at each interpolation point").

use serde::Serialize;

/// Widest half-width of the fitting window along the path, mm (tighter curves get
/// narrower windows, see `WINDOW_PER_RADIUS`).
pub const DEFAULT_FIT_HALF_WIDTH_MM: f64 = 5.0;
/// A direction change above this between consecutive segments is a sharp corner, not
/// curvature: fitting windows stop there.
pub const CORNER_ANGLE_DEG: f64 = 30.0;
/// Curvatures below this (1/mm) are straight.
pub const STRAIGHT_CURVATURE: f64 = 1e-9;
/// Segments shorter than this (mm) carry no direction.
const MIN_SEGMENT_MM: f64 = 1e-9;

/// Curvature at one point of a path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PointCurvature {
    /// Signed curvature, 1/mm: positive when the path turns left (counter-clockwise).
    pub kappa: f64,
    /// `true` at a sharp corner (direction change above [`CORNER_ANGLE_DEG`]).
    pub corner: bool,
}

impl PointCurvature {
    pub const STRAIGHT: PointCurvature = PointCurvature { kappa: 0.0, corner: false };

    /// Radius of curvature, mm (infinite on a straight path, 0 at a sharp corner).
    pub fn radius_mm(&self) -> f64 {
        if self.corner {
            0.0
        } else if self.kappa.abs() < STRAIGHT_CURVATURE {
            f64::INFINITY
        } else {
            1.0 / self.kappa.abs()
        }
    }

    /// Turn direction: +1 left (counter-clockwise), −1 right, 0 straight or a sharp corner.
    pub fn turn(&self) -> i8 {
        if self.corner || self.kappa.abs() < STRAIGHT_CURVATURE {
            0
        } else if self.kappa > 0.0 {
            1
        } else {
            -1
        }
    }

    /// Centre of curvature of the point `p` moving along unit tangent `t`.
    pub fn center(&self, p: (f64, f64), t: (f64, f64)) -> Option<(f64, f64)> {
        if self.corner || self.kappa.abs() < STRAIGHT_CURVATURE {
            return None;
        }
        let inv = 1.0 / self.kappa;
        Some((p.0 - t.1 * inv, p.1 + t.0 * inv))
    }
}

/// Turn of the direction from segment (a→b) to (b→c), radians, in (−π, π].
fn turn_angle(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> Option<f64> {
    let (u, v) = ((b.0 - a.0, b.1 - a.1), (c.0 - b.0, c.1 - b.1));
    let (lu, lv) = (u.0.hypot(u.1), v.0.hypot(v.1));
    if lu < MIN_SEGMENT_MM || lv < MIN_SEGMENT_MM {
        return None;
    }
    Some((u.0 * v.1 - u.1 * v.0).atan2(u.0 * v.0 + u.1 * v.1))
}

/// Degree of the local polynomial fits: quartic, so that the fitted second derivative
/// of a circular path is unbiased to O((w/R)⁴) for a window half-width w.
const FIT_DEGREE: usize = 4;
/// Degree of the first, narrower fit that estimates the radius.
const COARSE_DEGREE: usize = 2;
/// The fitting window never spans more than this fraction of the radius estimated
/// from a first, narrower fit (tight loops need narrow windows).
const WINDOW_PER_RADIUS: f64 = 0.6;

/// Least-squares polynomials of degree `DEGREE` (at most [`FIT_DEGREE`]) through the
/// `(s, x)` and the `(s, y)` pairs (with `s` scaled by `scale`): returns the first and
/// second derivatives of each at s = 0, in unscaled units. Both fits share the normal matrix, solved once with the
/// two right-hand sides. (The degree is a constant so that the loops over it unroll.)
fn polynomial_derivatives<const DEGREE: usize>(
    s: &[f64],
    (x, y): (&[f64], &[f64]),
    scale: f64,
) -> Option<[(f64, f64); 2]> {
    const { assert!(DEGREE <= FIT_DEGREE) };
    let m = DEGREE + 1;
    // The normal matrix, then the right-hand sides of x and of y.
    let mut a = [[0.0f64; FIT_DEGREE + 3]; FIT_DEGREE + 1];
    for ((&si, &xi), &yi) in s.iter().zip(x).zip(y) {
        let t = si / scale;
        let mut pw = [0.0f64; FIT_DEGREE + 1];
        let mut p = 1.0;
        for slot in pw.iter_mut().take(m) {
            *slot = p;
            p *= t;
        }
        for r in 0..m {
            for c in 0..m {
                a[r][c] += pw[r] * pw[c];
            }
            a[r][m] += pw[r] * xi;
            a[r][m + 1] += pw[r] * yi;
        }
    }
    // Gaussian elimination with partial pivoting on the m × (m+2) system.
    for col in 0..m {
        let pivot = (col..m).max_by(|&p, &q| a[p][col].abs().total_cmp(&a[q][col].abs()))?;
        if a[pivot][col].abs() < 1e-12 * a[0][0].abs().max(f64::MIN_POSITIVE) {
            return None;
        }
        a.swap(col, pivot);
        let pivot_row = a[col];
        for (r, row) in a.iter_mut().enumerate().take(m) {
            if r != col {
                let f = row[col] / pivot_row[col];
                for (v, p) in row.iter_mut().zip(pivot_row.iter()).take(m + 2).skip(col) {
                    *v -= f * p;
                }
            }
        }
    }
    let derivatives = |rhs: usize| {
        let coef = |k: usize| a[k][rhs] / a[k][k];
        (coef(1) / scale, 2.0 * coef(2) / (scale * scale))
    };
    Some([derivatives(m), derivatives(m + 1)])
}

/// Curvature from fits of degree `DEGREE` over `lo..=hi` about vertex `i`.
fn fit_at<const DEGREE: usize>(
    points: &[(f64, f64)],
    s: &[f64],
    i: usize,
    lo: usize,
    hi: usize,
    buf: &mut FitBuffers,
) -> PointCurvature {
    buf.ss.clear();
    buf.xs.clear();
    buf.ys.clear();
    for k in lo..=hi {
        buf.ss.push(s[k] - s[i]);
        buf.xs.push(points[k].0 - points[i].0);
        buf.ys.push(points[k].1 - points[i].1);
    }
    let scale = (s[hi] - s[i]).max(s[i] - s[lo]).max(MIN_SEGMENT_MM);
    match polynomial_derivatives::<DEGREE>(&buf.ss, (&buf.xs, &buf.ys), scale) {
        Some([(x1, x2), (y1, y2)]) => {
            let speed2 = x1 * x1 + y1 * y1;
            if speed2 < MIN_SEGMENT_MM {
                return PointCurvature::STRAIGHT;
            }
            PointCurvature { kappa: (x1 * y2 - y1 * x2) / speed2.powf(1.5), corner: false }
        }
        None => PointCurvature::STRAIGHT,
    }
}

#[derive(Default)]
struct FitBuffers {
    ss: Vec<f64>,
    xs: Vec<f64>,
    ys: Vec<f64>,
}

/// The vertices within `half_width` of vertex `i` along the path, not past a corner.
fn window(s: &[f64], corners: &[bool], i: usize, half_width: f64) -> (usize, usize) {
    let n = s.len();
    let mut lo = i;
    while lo > 0 && s[i] - s[lo - 1] <= half_width {
        lo -= 1;
        if corners[lo] {
            break;
        }
    }
    let mut hi = i;
    while hi + 1 < n && s[hi + 1] - s[i] <= half_width {
        hi += 1;
        if corners[hi] {
            break;
        }
    }
    (lo, hi)
}

/// Curvature at every vertex of a polyline of tool-centre positions (seed 000 §2):
/// quadratic fits of x(s) and y(s) in arc length over the vertices within
/// `half_width_mm` along the path, not reaching past a sharp corner.
pub fn polyline_curvature(points: &[(f64, f64)], half_width_mm: f64) -> Vec<PointCurvature> {
    let n = points.len();
    let mut s = Vec::with_capacity(n);
    let mut acc = 0.0;
    for i in 0..n {
        if i > 0 {
            acc += (points[i].0 - points[i - 1].0).hypot(points[i].1 - points[i - 1].1);
        }
        s.push(acc);
    }
    let corner_rad = CORNER_ANGLE_DEG.to_radians();
    let corners: Vec<bool> = (0..n)
        .map(|i| {
            i > 0
                && i + 1 < n
                && turn_angle(points[i - 1], points[i], points[i + 1]).is_some_and(|t| t.abs() > corner_rad)
        })
        .collect();

    let mut buf = FitBuffers::default();
    (0..n)
        .map(|i| {
            if corners[i] {
                return PointCurvature { kappa: 0.0, corner: true };
            }
            // A first, narrow quadratic fit estimates the radius; the final quartic fit
            // uses a window no wider than WINDOW_PER_RADIUS of it.
            let (lo, hi) = window(&s, &corners, i, half_width_mm / 2.0);
            if hi - lo < 2 {
                return PointCurvature::STRAIGHT;
            }
            let coarse = fit_at::<COARSE_DEGREE>(points, &s, i, lo, hi, &mut buf);
            let width = half_width_mm.min(WINDOW_PER_RADIUS * coarse.radius_mm());
            let (lo, hi) = window(&s, &corners, i, width);
            if hi - lo < FIT_DEGREE {
                return coarse;
            }
            fit_at::<FIT_DEGREE>(points, &s, i, lo, hi, &mut buf)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic ±1 µm "noise" (no RNG dependency needed).
    fn noise(i: usize) -> f64 {
        let h = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 11;
        ((h as f64 / (1u64 << 53) as f64) * 2.0 - 1.0) * 0.001
    }

    fn circle(radius: f64, spacing: f64, ccw: bool) -> Vec<(f64, f64)> {
        let n = (2.0 * std::f64::consts::PI * radius / spacing) as usize;
        (0..n)
            .map(|i| {
                let a = i as f64 / n as f64 * 2.0 * std::f64::consts::PI * if ccw { 1.0 } else { -1.0 };
                let r = radius + noise(i);
                (r * a.cos(), r * a.sin())
            })
            .collect()
    }

    #[test]
    fn points_on_a_circle_with_1_um_noise_give_its_radius_within_1_percent() {
        for (radius, spacing) in [(5.0, 0.05), (10.0, 0.1), (50.0, 0.2), (3.0, 0.02)] {
            let pts = circle(radius, spacing, true);
            let k = polyline_curvature(&pts, DEFAULT_FIT_HALF_WIDTH_MM);
            for (i, c) in k.iter().enumerate().skip(30).take(pts.len() - 60) {
                let err = (c.radius_mm() - radius).abs() / radius;
                assert!(err < 0.01, "R {radius}, point {i}: {} ({err})", c.radius_mm());
            }
        }
    }

    #[test]
    fn the_centre_of_curvature_of_a_circle_is_its_centre_and_the_sign_gives_the_turn() {
        let pts = circle(10.0, 0.1, false);
        let k = polyline_curvature(&pts, DEFAULT_FIT_HALF_WIDTH_MM);
        let i = 100;
        assert!(k[i].kappa < 0.0, "clockwise turns right");
        let t = {
            let (a, b) = (pts[i - 1], pts[i + 1]);
            let l = (b.0 - a.0).hypot(b.1 - a.1);
            ((b.0 - a.0) / l, (b.1 - a.1) / l)
        };
        let c = k[i].center(pts[i], t).unwrap();
        assert!(c.0.hypot(c.1) < 0.05, "{c:?}");
    }

    #[test]
    fn a_straight_line_is_straight_and_a_square_corner_is_a_corner() {
        let mut pts: Vec<(f64, f64)> = (0..=50).map(|i| (i as f64 * 0.1, 0.0)).collect();
        pts.extend((1..=50).map(|i| (5.0, i as f64 * 0.1)));
        let k = polyline_curvature(&pts, DEFAULT_FIT_HALF_WIDTH_MM);
        assert!(k[20].radius_mm().is_infinite());
        assert!(k[50].corner && k[50].radius_mm() < 1e-12);
        assert!(k[80].radius_mm().is_infinite(), "windows stop at the corner");
    }
}
