//! Constant feedrate at the cutting point (seed 000, Eq. 1; MODEL.md §4).

/// Which side of the tool-centre path the machined surface is on, relative to the centre
/// of curvature of the path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceSide {
    /// The surface lies on the far side from the centre of curvature: a concave surface
    /// (inner corner), `|PO| = Rc + r`.
    Concave,
    /// The surface lies between the tool centre and the centre of curvature: a convex
    /// surface (outer corner), `|PO| = Rc − r`.
    Convex,
}

/// Distance from the cutting point P to the centre of curvature O, mm (MODEL.md §4).
pub fn cutting_point_distance_mm(centre_path_radius_mm: f64, tool_radius_mm: f64, side: SurfaceSide) -> f64 {
    match side {
        SurfaceSide::Concave => centre_path_radius_mm + tool_radius_mm,
        SurfaceSide::Convex => centre_path_radius_mm - tool_radius_mm,
    }
}

/// The feed at the tool centre that moves the cutting point at `cutting_point_feed`:
/// `F_c = R · F_p / |PO|` (seed 000, Eq. 1), with `R` the curvature radius of the
/// tool-centre path. `None` where the cutting point does not move (`|PO| ≤ 0`, a convex
/// path tighter than the tool). A straight path (`R` infinite) gives `F_p`.
pub fn centre_feed_for_cutting_point_feed(
    cutting_point_feed_mm_min: f64,
    centre_path_radius_mm: f64,
    tool_radius_mm: f64,
    side: SurfaceSide,
) -> Option<f64> {
    if !centre_path_radius_mm.is_finite() {
        return Some(cutting_point_feed_mm_min);
    }
    let po = cutting_point_distance_mm(centre_path_radius_mm, tool_radius_mm, side);
    (po > 0.0).then(|| centre_path_radius_mm * cutting_point_feed_mm_min / po)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_path_keeps_the_feed() {
        let f = centre_feed_for_cutting_point_feed(1200.0, f64::INFINITY, 3.0, SurfaceSide::Concave);
        assert_eq!(f, Some(1200.0));
    }

    #[test]
    fn seed_000_ratios_3_2_convex_and_0_61_concave_are_reproduced() {
        // Convex: F_c/F_p = R/(R − r) = 3.2 → R = 3.2 r / 2.2; concave: R/(R + r) = 0.61.
        let r = 3.0;
        let convex_r = 3.2 * r / 2.2;
        let concave_r = 0.61 * r / 0.39;
        let convex = centre_feed_for_cutting_point_feed(1.0, convex_r, r, SurfaceSide::Convex).unwrap();
        let concave = centre_feed_for_cutting_point_feed(1.0, concave_r, r, SurfaceSide::Concave).unwrap();
        assert!((convex - 3.2).abs() < 1e-12, "{convex}");
        assert!((concave - 0.61).abs() < 1e-12, "{concave}");
    }

    #[test]
    fn a_convex_path_tighter_than_the_tool_has_no_cutting_point_feed() {
        assert_eq!(centre_feed_for_cutting_point_feed(1000.0, 2.0, 3.0, SurfaceSide::Convex), None);
    }
}
