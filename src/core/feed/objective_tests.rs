//! The objectives on cuts whose answer is known (MODEL.md §3 and §9).

use super::objective::*;
use super::rule::{FeedReason, FeedRule, FeedStrategy, SampleCut};
use crate::core::costing::cost::Rates;
use crate::core::costing::estimate::CostModel;
use crate::core::engagement::{engagement, Contour};
use crate::core::fixtures::{seed_001_ten_mm, ten_mm_life};
use crate::core::kinematics::MachineLimits;
use proptest::prelude::*;

const F_STAR: f64 = 269.1;

pub(super) fn rule() -> FeedRule {
    FeedRule {
        strategy: FeedStrategy::ConstantForce,
        force_model: Some(seed_001_ten_mm()),
        target_force_n: F_STAR,
        flutes: 6,
        min_feed_mm_min: 288.0,
        max_feed_mm_min: 11520.0,
        air_feed_mm_min: 11520.0,
    }
}

pub(super) fn model() -> CostModel {
    CostModel {
        life: ten_mm_life(),
        machine: MachineLimits {
            rapid_mm_min: 20000.0,
            max_feed_mm_min: 15000.0,
            accel_mm_s2: [2000.0; 3],
            jerk_mm_s3: [50000.0; 3],
            tool_change_s: 8.0,
        },
        rates: Rates { machine_rate_per_hour: 60.0, tool_price: 80.0, currency: "USD".into() },
    }
}

fn spec(objective: Objective, max_force_n: f64) -> ObjectiveSpec {
    ObjectiveSpec { objective, max_force_n, cost: Some(model()) }
}

/// A cut of the 10 mm tool (Ad 10, S 9600) on `contour` at Rd 0.5, programmed at `feed`.
fn cut(contour: Contour, feed: f64) -> SampleCut {
    let e = engagement(contour, 5.0, 0.5).unwrap();
    SampleCut {
        alpha_rad: e.angle_rad,
        arc_length_mm: e.arc_length_mm,
        ad_mm: 10.0,
        cutting_point_ratio: e.cutting_point_feed_ratio,
        centre_radius_mm: match contour {
            Contour::Concave { surface_radius_mm } => surface_radius_mm - 5.0,
            _ => f64::INFINITY,
        },
        tool_radius_mm: 5.0,
        programmed_feed_mm_min: feed,
        spindle_rpm: Some(9600.0),
        plunge: false,
        in_material: true,
    }
}

/// A full slot (α 180°, L = π·r) at Ad 1, programmed at `feed`: no feed reaches F*.
fn full_slot(feed: f64) -> SampleCut {
    SampleCut {
        alpha_rad: std::f64::consts::PI,
        arc_length_mm: std::f64::consts::PI * 5.0,
        ad_mm: 1.0,
        cutting_point_ratio: 1.0,
        centre_radius_mm: f64::INFINITY,
        tool_radius_mm: 5.0,
        programmed_feed_mm_min: feed,
        spindle_rpm: Some(9600.0),
        plunge: false,
        in_material: true,
    }
}

fn feed_of(spec: &ObjectiveSpec, c: &SampleCut) -> (f64, FeedReason) {
    spec.feed(&rule(), c, None, rule().feed(c))
}

fn cost_at(c: &SampleCut, feed: f64) -> f64 {
    let force = ForceCurve::new(seed_001_ten_mm(), c, 6, 9600.0, None).force_n(feed);
    cost_per_mm(&model(), c, 6, 9600.0, feed, Some(force))
}

#[test]
fn at_the_default_limit_min_cost_and_min_time_hold_the_model_section_3_feeds() {
    // The force limit defaults to the target: both hold the constant force where it can
    // be held, as the papers' rule does (MODEL.md §3's table).
    for (contour, feed) in [
        (Contour::Straight, 5760.0),
        (Contour::Concave { surface_radius_mm: 15.0 }, 2340.0),
        (Contour::Concave { surface_radius_mm: 10.0 }, 1160.0),
        (Contour::Concave { surface_radius_mm: 8.0 }, 513.0),
    ] {
        for objective in [Objective::MinCost, Objective::MinTime, Objective::ConstantForce] {
            let (f, _) = feed_of(&spec(objective, F_STAR), &cut(contour, 5760.0));
            assert!((f - feed).abs() / feed < 0.02, "{objective:?} on {contour:?}: {f}");
        }
    }
}

#[test]
fn below_the_standard_force_a_slower_feed_wears_the_tool_more_per_millimetre() {
    // MODEL.md §9: a tooth passes 1/fz_p times per millimetre and φ = 1 below F*.
    let c = cut(Contour::Straight, 5760.0);
    let wear = |feed: f64| {
        let force = ForceCurve::new(seed_001_ten_mm(), &c, 6, 9600.0, None).force_n(feed);
        let w = crate::core::tool_life::WearCut::at_centre_feed(
            c.alpha_rad.to_degrees(),
            c.arc_length_mm,
            feed,
            6.0,
            9600.0,
            1.0,
            Some(force),
        );
        ten_mm_life().wear_mm(1.0, &w)
    };
    assert!((wear(2880.0) / wear(5760.0) - 2.0).abs() < 1e-9);
    assert!(wear(288.0) > 19.0 * wear(5760.0));
}

#[test]
fn where_no_feed_holds_the_force_min_cost_does_not_drop_to_the_minimum_feed() {
    let c = full_slot(3600.0);
    let (constant, why) = rule().feed(&c);
    assert_eq!((constant, why), (288.0, FeedReason::Infeasible));
    let (f, why) = feed_of(&spec(Objective::MinCost, F_STAR), &c);
    assert_eq!(why, FeedReason::Infeasible);
    assert!(f > 288.0 && f <= 3600.0 + 1e-9, "{f}");
    assert!(cost_at(&c, f) < cost_at(&c, 288.0), "{} ≥ {}", cost_at(&c, f), cost_at(&c, 288.0));
    assert!(cost_at(&c, f) <= cost_at(&c, 3600.0) + 1e-15);
    // min_time never runs faster than programmed there.
    let (t, _) = feed_of(&spec(Objective::MinTime, F_STAR), &c);
    assert!(t <= 3600.0 + 1e-9 && t >= f - 1e-9, "{t}");
}

#[test]
fn a_higher_force_limit_lets_min_time_run_faster_and_min_cost_no_dearer() {
    let c = cut(Contour::Concave { surface_radius_mm: 10.0 }, 5760.0);
    let (held, _) = feed_of(&spec(Objective::MinTime, F_STAR), &c);
    let (fast, _) = feed_of(&spec(Objective::MinTime, 2.0 * F_STAR), &c);
    assert!(fast > 1.5 * held, "{held} → {fast}");
    let (cheap, _) = feed_of(&spec(Objective::MinCost, 2.0 * F_STAR), &c);
    assert!(cheap <= fast + 1e-9 && cost_at(&c, cheap) <= cost_at(&c, held) + 1e-15);
}

#[test]
fn the_cheapest_feed_is_found_on_a_known_curve() {
    // a/F + b·F has its minimum at √(a/b).
    let f = cheapest_feed(100.0, 10_000.0, |f| 4.0e6 / f + f);
    assert!((f - 2000.0).abs() < 0.1, "{f}");
    assert!((cheapest_feed(100.0, 1000.0, |f| 4.0e6 / f + f) - 1000.0).abs() < 1e-9);
}

proptest! {
    #[test]
    fn min_cost_is_never_dearer_per_millimetre_than_any_admissible_feed(
        ratio in 1.25f64..6.0,
        rd in 0.1f64..4.0,
        ad in 1.0f64..10.0,
        programmed in 300.0f64..11_000.0,
        limit_factor in 1.0f64..3.0,
    ) {
        let e = engagement(Contour::Concave { surface_radius_mm: 5.0 * ratio }, 5.0, rd).unwrap();
        let c = SampleCut {
            ad_mm: ad,
            alpha_rad: e.angle_rad,
            arc_length_mm: e.arc_length_mm,
            cutting_point_ratio: e.cutting_point_feed_ratio,
            centre_radius_mm: 5.0 * ratio - 5.0,
            ..cut(Contour::Straight, programmed)
        };
        let s = spec(Objective::MinCost, limit_factor * F_STAR);
        let (f, _) = feed_of(&s, &c);
        let curve = ForceCurve::new(seed_001_ten_mm(), &c, 6, 9600.0, None);
        prop_assert!((288.0 - 1e-9..=11_520.0 + 1e-9).contains(&f));
        let under_limit = curve.force_n(288.0) <= limit_factor * F_STAR;
        let safe = curve.fastest_under(3.0 * F_STAR, 288.0, 11_520.0).unwrap_or(11_520.0);
        for k in 0..=40 {
            let g = 288.0 * (11_520.0f64 / 288.0).powf(f64::from(k) / 40.0);
            let admissible = if under_limit {
                curve.force_n(g) <= limit_factor * F_STAR
            } else {
                g <= programmed.min(safe).max(288.0)
            };
            if admissible {
                prop_assert!(cost_at(&c, f) <= cost_at(&c, g) * (1.0 + 1e-6), "F {f} dearer than {g}");
            }
        }
    }
}
