//! Radius-ratio classes along the medial axis (seed 004 §2.3, Figure 6; MODEL.md §7): with `R`
//! the clearance (the radius of the machined surface) and `r` the tool radius,
//!
//! | class | R/r | strategy |
//! |---|---|---|
//! | A | ≥ a (a in [2, 3], default 2) | contour-parallel paths |
//! | B | 1.1 … a | trochoidal grooving along the branch |
//! | C | < 1.1 | z-cut division |

use super::axis::{AxisPoint, MedialAxis};
use crate::core::error::{require_positive, CoreError};
use serde::Serialize;

/// Default lower bound of class A's R/r (seed 004 §2.3: "2.0~3.0 or larger").
pub const CLASS_A_RATIO_DEFAULT: f64 = 2.0;

/// Smallest accepted lower bound of class A's R/r (seed 004 §2.3).
pub const CLASS_A_RATIO_MIN: f64 = 2.0;

/// Largest accepted lower bound of class A's R/r (seed 004 §2.3).
pub const CLASS_A_RATIO_MAX: f64 = 3.0;

/// Below this R/r trochoids overload the tool: z-cut division, class C (seed 004 §2.3).
pub const CLASS_C_RATIO: f64 = 1.1;

/// Sub-intervals shorter than this carry no class of their own (mm).
const MIN_INTERVAL_MM: f64 = 1e-9;

/// The machining strategy class of a stretch of the medial axis (seed 004 §2.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, utoipa::ToSchema)]
pub enum RadiusClass {
    /// R/r ≥ a: keep the contour-parallel paths.
    A,
    /// 1.1 ≤ R/r < a: trochoidal grooving.
    B,
    /// R/r < 1.1: z-cut division.
    C,
}

/// One stretch of a branch in one class, by arc length from the branch's first point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, utoipa::ToSchema)]
pub struct ClassInterval {
    /// The class.
    pub class: RadiusClass,
    /// Where the stretch starts along the branch (mm).
    pub s_start_mm: f64,
    /// Where it ends (mm).
    pub s_end_mm: f64,
}

/// The class intervals of one branch, in order, covering it from 0 to its length.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BranchClasses {
    /// Index of the branch in [`MedialAxis::branches`].
    pub branch: usize,
    /// The stretches, in order along the branch.
    pub intervals: Vec<ClassInterval>,
}

/// The class of a radius ratio `R/r`.
pub fn class_of(ratio: f64, class_a_ratio: f64) -> RadiusClass {
    if ratio >= class_a_ratio {
        RadiusClass::A
    } else if ratio >= CLASS_C_RATIO {
        RadiusClass::B
    } else {
        RadiusClass::C
    }
}

/// Classifies every branch of `axis` for a tool of radius `tool_radius_mm`, class A starting
/// at `R/r = class_a_ratio` (in [2, 3]). R is interpolated linearly between the branch's
/// points, so a class boundary falls where the interpolated R crosses `1.1·r` or `a·r`.
pub fn classify(axis: &MedialAxis, tool_radius_mm: f64, class_a_ratio: f64) -> Result<Vec<BranchClasses>, CoreError> {
    let r = require_positive("tool_radius_mm", tool_radius_mm)?;
    if !(CLASS_A_RATIO_MIN..=CLASS_A_RATIO_MAX).contains(&class_a_ratio) {
        return Err(CoreError::invalid(
            "class_a_ratio",
            format!("must lie in [{CLASS_A_RATIO_MIN}, {CLASS_A_RATIO_MAX}] (seed 004 §2.3), got {class_a_ratio}"),
        ));
    }
    Ok(axis
        .branches
        .iter()
        .enumerate()
        .map(|(branch, b)| BranchClasses { branch, intervals: intervals(&b.points, r, class_a_ratio) })
        .collect())
}

/// The class intervals along one polyline.
fn intervals(points: &[AxisPoint], r: f64, a: f64) -> Vec<ClassInterval> {
    let mut out: Vec<ClassInterval> = Vec::new();
    let mut push = |class: RadiusClass, s_start_mm: f64, s_end_mm: f64| match out.last_mut() {
        Some(last) if last.class == class => last.s_end_mm = s_end_mm,
        _ => out.push(ClassInterval { class, s_start_mm, s_end_mm }),
    };
    let Some(first) = points.first() else { return Vec::new() };
    let thresholds_mm = [CLASS_C_RATIO * r, a * r];
    let mut s0 = 0.0;
    for w in points.windows(2) {
        let (r0, r1) = (w[0].clearance_mm, w[1].clearance_mm);
        let s1 = s0 + w[0].point.distance_mm(w[1].point);
        let mut cuts = vec![s0];
        for t in thresholds_mm {
            if (r0 >= t) != (r1 >= t) {
                cuts.push(s0 + (t - r0) / (r1 - r0) * (s1 - s0));
            }
        }
        cuts.push(s1);
        cuts.sort_by(f64::total_cmp);
        for c in cuts.windows(2) {
            let (sa, sb) = (c[0], c[1]);
            if sb - sa <= MIN_INTERVAL_MM {
                continue;
            }
            let f = (0.5 * (sa + sb) - s0) / (s1 - s0);
            push(class_of((r0 + f * (r1 - r0)) / r, a), sa, sb);
        }
        s0 = s1;
    }
    if let Some(first_interval) = out.first_mut() {
        first_interval.s_start_mm = 0.0;
    }
    match out.last_mut() {
        Some(last) => last.s_end_mm = s0,
        None => out.push(ClassInterval { class: class_of(first.clearance_mm / r, a), s_start_mm: 0.0, s_end_mm: s0 }),
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::Point;

    /// Tolerance of exact results (mm).
    const TOL_MM: f64 = 1e-9;

    fn branch(samples: &[(f64, f64)]) -> Vec<AxisPoint> {
        samples
            .iter()
            .map(|&(x, r)| AxisPoint { point: Point::new(x, 0.0), clearance_mm: r, nearest: vec![] })
            .collect()
    }

    #[test]
    fn a_narrowing_slot_passes_from_a_to_b_to_c_at_the_interpolated_crossings() {
        // R falls linearly from 12 to 4 over 8 mm; tool r = 5: A until R = 10 (s = 2),
        // B until R = 5.5 (s = 6.5), then C.
        let points = branch(&[(0.0, 12.0), (8.0, 4.0)]);
        let got = intervals(&points, 5.0, CLASS_A_RATIO_DEFAULT);
        assert_eq!(got.len(), 3);
        assert_eq!((got[0].class, got[1].class, got[2].class), (RadiusClass::A, RadiusClass::B, RadiusClass::C));
        assert!(got[0].s_start_mm.abs() < TOL_MM && (got[0].s_end_mm - 2.0).abs() < TOL_MM);
        assert!((got[1].s_start_mm - 2.0).abs() < TOL_MM && (got[1].s_end_mm - 6.5).abs() < TOL_MM);
        assert!((got[2].s_start_mm - 6.5).abs() < TOL_MM && (got[2].s_end_mm - 8.0).abs() < TOL_MM);
    }

    #[test]
    fn a_branch_of_constant_clearance_is_one_interval_over_its_length() {
        let points = branch(&[(0.0, 6.0), (10.0, 6.0), (30.0, 6.0)]);
        let got = intervals(&points, 5.0, 3.0);
        assert_eq!(got, vec![ClassInterval { class: RadiusClass::B, s_start_mm: 0.0, s_end_mm: 30.0 }]);
    }

    #[test]
    fn the_class_a_ratio_must_lie_between_two_and_three_and_the_tool_radius_be_positive() {
        let axis = MedialAxis { step_mm: 1.0, nodes: vec![], branches: vec![] };
        assert!(classify(&axis, 5.0, 1.9).is_err());
        assert!(classify(&axis, 5.0, 3.1).is_err());
        assert!(classify(&axis, 0.0, 2.0).is_err());
        assert!(classify(&axis, 5.0, 2.5).unwrap().is_empty());
        assert_eq!(class_of(2.0, 2.0), RadiusClass::A);
        assert_eq!(class_of(1.1, 2.0), RadiusClass::B);
        assert_eq!(class_of(1.0999, 2.0), RadiusClass::C);
    }
}
