//! The feed that holds the cutting force at a target (MODEL.md §3, "constant cutting
//! force (feed-forward)"; seed 002 §2.3; seed 001).

use crate::core::engagement::{tooth_chip_thickness_mm, ToothCut};
use crate::core::force_model::{ForceModel, DESIGN_REGION_CODED_RADIUS};
use std::f64::consts::FRAC_PI_2;

/// Micrometres per millimetre.
const UM_PER_MM: f64 = 1000.0;
/// A bounded chip this much thinner than the one solved for means a bound holds it.
const BOUND_SLACK: f64 = 1e-9;

/// The engagement and cut at one point of the path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cut {
    /// Engagement angle, cutting-point ratio and what bounds the chip (MODEL.md §2).
    pub tooth: ToothCut,
    /// Engagement arc length L, mm.
    pub arc_length_mm: f64,
    /// Axial depth of cut, mm.
    pub ad_mm: f64,
}

/// The spindle and the feed limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeedLimits {
    pub flutes: u32,
    pub spindle_rpm: f64,
    pub min_feed_mm_min: f64,
    pub max_feed_mm_min: f64,
}

/// The constant-force feed at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceFeed {
    /// The feed, clamped to the limits, mm/min.
    pub feed_mm_min: f64,
    /// The unclamped feed, when a positive chip thickness reaches the target.
    pub unclamped_mm_min: Option<f64>,
    /// `false` where no positive chip thickness reaches the target (the region needs a
    /// trochoid or a z-cut division): the feed is then the minimum.
    pub feasible: bool,
}

/// Solves the force model for the chip thickness that gives `target_force_n` at this
/// cut, then `t_m → fz_p → fz_c → F = fz_c·z·S`, clamped to the limits (MODEL.md §3).
pub fn constant_force_feed(model: &ForceModel, target_force_n: f64, cut: Cut, limits: FeedLimits) -> ForceFeed {
    let clamp = |f: f64| f.clamp(limits.min_feed_mm_min, limits.max_feed_mm_min);
    let infeasible = ForceFeed { feed_mm_min: limits.min_feed_mm_min, unclamped_mm_min: None, feasible: false };
    let alpha_rad = cut.tooth.alpha_rad;
    if alpha_rad <= 0.0 {
        return ForceFeed { feed_mm_min: limits.max_feed_mm_min, unclamped_mm_min: None, feasible: true };
    }
    // Below the experiments' range of arc lengths the quadratic model turns upwards again
    // (it would predict a large force on a light cut): solve at the range's lower edge,
    // which overestimates the force there and so errs on the safe side.
    let lowest_modelled_mm = model.l0_mm - DESIGN_REGION_CODED_RADIUS * model.dl_mm;
    let arc_length_mm = cut.arc_length_mm.max(lowest_modelled_mm);
    let Some(t_m_um) = model.chip_thickness_for_force_um(target_force_n, arc_length_mm, cut.ad_mm) else {
        return infeasible;
    };
    // t_m = fz_p · sin α for α ≤ 90°, else fz_p (MODEL.md §2).
    let fz_p_mm = if alpha_rad <= FRAC_PI_2 { t_m_um / UM_PER_MM / alpha_rad.sin() } else { t_m_um / UM_PER_MM };
    let fz_c_mm = fz_p_mm / cut.tooth.cutting_point_ratio;
    // Where the material between successive tooth paths bounds the chip below t_m, no
    // feed makes the chip that thick: the force stays under the target at any feed.
    let bounded = tooth_chip_thickness_mm(fz_c_mm, &cut.tooth) * UM_PER_MM;
    let feed = if bounded < t_m_um * (1.0 - BOUND_SLACK) {
        f64::INFINITY
    } else {
        fz_c_mm * f64::from(limits.flutes) * limits.spindle_rpm
    };
    ForceFeed { feed_mm_min: clamp(feed), unclamped_mm_min: Some(feed), feasible: true }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::engagement::{engagement, Contour};
    use crate::core::fixtures::seed_001_ten_mm;

    fn limits() -> FeedLimits {
        FeedLimits { flutes: 6, spindle_rpm: 9600.0, min_feed_mm_min: 1.0, max_feed_mm_min: 2.0 * 5760.0 }
    }

    fn straight(alpha_rad: f64) -> ToothCut {
        ToothCut { alpha_rad, cutting_point_ratio: 1.0, centre_radius_mm: f64::INFINITY, tool_radius_mm: 5.0 }
    }

    fn cut(contour: Contour) -> Cut {
        let e = engagement(contour, 5.0, 0.5).unwrap();
        let centre_radius_mm = match contour {
            Contour::Concave { surface_radius_mm } => surface_radius_mm - 5.0,
            _ => f64::INFINITY,
        };
        let tooth = ToothCut {
            alpha_rad: e.angle_rad,
            cutting_point_ratio: e.cutting_point_feed_ratio,
            centre_radius_mm,
            tool_radius_mm: 5.0,
        };
        Cut { tooth, arc_length_mm: e.arc_length_mm, ad_mm: 10.0 }
    }

    #[test]
    fn the_standard_straight_cut_at_beta0_gives_the_standard_feed() {
        let f = constant_force_feed(&seed_001_ten_mm(), 269.1, cut(Contour::Straight), limits());
        assert!((f.feed_mm_min - 5760.0).abs() < 1e-6, "{f:?}");
    }

    #[test]
    fn concave_arcs_get_the_feeds_of_model_section_3() {
        for (ratio, feed, tolerance) in [(3.0, 2340.0, 0.02), (2.0, 1160.0, 0.02), (1.6, 513.0, 0.02), (1.3, 32.0, 0.1)]
        {
            let f = constant_force_feed(
                &seed_001_ten_mm(),
                269.1,
                cut(Contour::Concave { surface_radius_mm: 5.0 * ratio }),
                limits(),
            );
            assert!(f.feasible);
            assert!((f.feed_mm_min - feed).abs() / feed < tolerance, "R/r {ratio}: {f:?}");
        }
    }

    #[test]
    fn r_over_r_1_2_cannot_reach_the_target_and_gets_the_minimum_feed() {
        let f =
            constant_force_feed(&seed_001_ten_mm(), 269.1, cut(Contour::Concave { surface_radius_mm: 6.0 }), limits());
        assert!(!f.feasible);
        assert!((f.feed_mm_min - limits().min_feed_mm_min).abs() < 1e-12);
    }

    #[test]
    fn a_cut_lighter_than_the_experiments_is_solved_at_their_edge_and_not_called_infeasible() {
        for alpha_deg in [2.0f64, 8.0, 15.0] {
            let a = alpha_deg.to_radians();
            let light = Cut { tooth: straight(a), arc_length_mm: 5.0 * a, ad_mm: 10.0 };
            let f = constant_force_feed(&seed_001_ten_mm(), 269.1, light, limits());
            assert!(f.feasible && f.feed_mm_min > 5760.0, "α {alpha_deg}°: {f:?}");
        }
    }

    #[test]
    fn a_light_cut_is_clamped_to_the_maximum_feed() {
        let light = Cut { tooth: straight(0.1), arc_length_mm: 0.5, ad_mm: 10.0 };
        let f = constant_force_feed(&seed_001_ten_mm(), 269.1, light, limits());
        assert!((f.feed_mm_min - limits().max_feed_mm_min).abs() < 1e-9);
        assert!(f.unclamped_mm_min.unwrap() > limits().max_feed_mm_min);
    }
}
