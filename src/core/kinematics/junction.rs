//! The speed allowed where two segments meet, from their change of direction.
//!
//! - **Junction deviation** (GRBL 1.1 `planner.c`, after S. Jeon's 2011 derivation; Marlin's
//!   `JUNCTION_DEVIATION` reuses it): the corner is replaced by the circle tangent to both
//!   segments that passes `δ` from the corner; its radius is `R = δ·s/(1 − s)` with
//!   `s = cos(turn/2)`, and the speed is `v = sqrt(a·R)`. As in GRBL, `a` is the acceleration
//!   along the corner's velocity change `u₂ − u₁` limited per axis (`a_i/|n_i|`), so each axis'
//!   share of the change stays within its own limit.
//! - **Dense polylines** (Marlin 2 `planner.cpp`, `JD_HANDLE_SMALL_SEGMENTS`: "for small moves
//!   with >135° junction (octagon) find speed for approximate arc"): where two straight
//!   segments turn by at most [`ARC_LIKE_MAX_TURN_DEG`], they are read as chords of a curve of
//!   radius `R = L/(2·sin(turn/2))` (`L` the shorter segment), and the centripetal limit
//!   `v ≤ sqrt(a·R)` and its jerk counterpart `v ≤ cbrt(j·R²)` (as on arcs) apply. This is what
//!   slows the small trochoid loops that CAM systems write as fine G1 segments.

use super::segments::{along, Segment, SegmentKind};
use super::MachineLimits;

/// Largest turn (deg) at which two straight segments are read as chords of a curve (Marlin:
/// junctions above 135°).
pub const ARC_LIKE_MAX_TURN_DEG: f64 = 45.0;

/// `|cos(turn)|` above this is straight on (no limit) or a reversal (stop), as in GRBL
/// (`junction_cos_theta` beyond ±0.999999).
const COLLINEAR_COSINE: f64 = 0.999_999;

/// Speed (mm/s) allowed where `prev` meets `next`: `cap_mm_s` (the lower of their caps)
/// unless their change of direction asks for less. Roots are taken only when they bind.
pub(super) fn junction_limit_mm_s(
    prev: &Segment,
    next: &Segment,
    machine: &MachineLimits,
    deviation_mm: f64,
    cap_mm_s: f64,
) -> f64 {
    let (u1, u2) = (prev.u_end, next.u_start);
    let cos_turn = u1[0] * u2[0] + u1[1] * u2[1] + u1[2] * u2[2];
    if cos_turn > COLLINEAR_COSINE {
        return cap_mm_s;
    }
    if cos_turn < -COLLINEAR_COSINE {
        return 0.0;
    }
    let change = [u2[0] - u1[0], u2[1] - u1[1], u2[2] - u1[2]];
    let change_norm = (change[0] * change[0] + change[1] * change[1] + change[2] * change[2]).sqrt();
    let n = [change[0] / change_norm, change[1] / change_norm, change[2] / change_norm];
    let accel_mm_s2 = along(machine.accel_mm_s2, n);
    let mut limit = cap_mm_s;
    // v² ≤ a·R: the centripetal limit on a circle of radius R through the junction.
    let centripetal = |radius_mm: f64, limit: &mut f64| {
        let v_sq = accel_mm_s2 * radius_mm;
        if v_sq < *limit * *limit {
            *limit = v_sq.sqrt();
        }
    };
    let cos_half_turn = (0.5 * (1.0 + cos_turn)).sqrt();
    centripetal(deviation_mm * cos_half_turn / (1.0 - cos_half_turn), &mut limit);
    let straight = |s: &Segment| s.kind != SegmentKind::Arc;
    if straight(prev) && straight(next) && cos_turn >= ARC_LIKE_MAX_TURN_DEG.to_radians().cos() {
        let sin_half_turn = (0.5 * (1.0 - cos_turn)).sqrt();
        let radius_mm = prev.length_mm.min(next.length_mm) / (2.0 * sin_half_turn);
        centripetal(radius_mm, &mut limit);
        // v³ ≤ j·R²: the steady jerk of circular motion.
        let v_cubed = along(machine.jerk_mm_s3, n) * radius_mm * radius_mm;
        if v_cubed < limit * limit * limit {
            limit = v_cubed.cbrt();
        }
    }
    limit
}
