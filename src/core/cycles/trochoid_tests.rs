use super::*;
use crate::core::analysis::{analyze_with, StockRegion};
use crate::core::cycles::test_support::*;
use crate::core::engagement::concave_engagement_angle_rad;
use crate::core::progress::NoProgress;
use crate::core::stock::Rect;
use crate::core::tolerance::approx_eq;
use crate::core::toolpath::Motion;

fn straight(length: f64) -> Guide {
    Guide::polyline(&[Point::new(0.0, 0.0), Point::new(length, 0.0)]).unwrap()
}

fn params(loop_radius: LoopRadius, pitch: f64) -> TrochoidParams {
    TrochoidParams {
        tool_radius_mm: R10,
        loop_radius,
        pitch_mm: Some(pitch),
        z_mm: -5.0,
        direction: CutDirection::Climb,
        entry: Entry::Plunge,
    }
}

fn arcs(c: &Cycle) -> Vec<&crate::core::toolpath::Move> {
    c.moves.iter().filter(|m| matches!(m.motion, Motion::Arc { .. })).collect()
}

#[test]
fn loop_centres_are_spaced_exactly_one_pitch_along_the_line() {
    let plan = LoopPlan::new(&straight(60.0), &LoopRadius::Default, R10, 0.5, CutDirection::Climb).unwrap();
    assert_eq!(plan.loops(), 121);
    for w in plan.centres.windows(2) {
        assert!(approx_eq(w[0].distance_mm(w[1]), 0.5, 1e-9));
    }
    // A length that is not a whole number of pitches ends with a shorter step at the end.
    let plan = LoopPlan::new(&straight(10.2), &LoopRadius::Default, R10, 0.5, CutDirection::Climb).unwrap();
    assert_eq!(plan.loops(), 22);
    assert!(approx_eq(plan.s_mm[20], 10.0, 1e-12) && approx_eq(plan.s_mm[21], 10.2, 1e-12));
}

#[test]
fn centres_on_a_bent_guide_are_one_pitch_apart_by_arc_length() {
    let g = Guide::polyline(&[Point::new(0.0, 0.0), Point::new(10.0, 0.0), Point::new(10.0, 10.0)]).unwrap();
    let plan = LoopPlan::new(&g, &LoopRadius::Default, R10, 0.7, CutDirection::Climb).unwrap();
    for w in plan.s_mm.windows(2).take(plan.loops() - 2) {
        assert!(approx_eq(w[1] - w[0], 0.7, 1e-12));
    }
    for (s, c) in plan.s_mm.iter().zip(&plan.centres) {
        assert!(c.distance_mm(g.point_at(*s)) < 1e-12);
    }
}

#[test]
fn the_default_loop_radius_is_a_fifth_of_the_tool_radius_and_every_arc_has_it() {
    let c = trochoid_along(&straight(20.0), &params(LoopRadius::Default, 0.5), &grooving_setup()).unwrap();
    let rho = default_loop_radius_mm(R10);
    assert!(approx_eq(rho, 1.0, 1e-12));
    let arcs = arcs(&c);
    assert_eq!(arcs.len(), 2 * c.report.loops);
    for m in arcs {
        let (rs, re, _) = arc_radii(m).unwrap();
        assert!(approx_eq(rs, rho, 1e-9) && approx_eq(re, rho, 1e-9), "line {}: {rs} {re}", m.line);
    }
}

#[test]
fn the_trochoid_sweeps_a_band_two_rho_plus_r_wide_and_is_continuous_and_tangent() {
    let c = trochoid_along(&straight(20.0), &params(LoopRadius::Default, 0.5), &grooving_setup()).unwrap();
    assert_continuous(&c.moves);
    assert_tangent_at(&c.moves, -5.0, 1e-9);
    let pts: Vec<_> = feed_points(&c.moves, 64).into_iter().filter(|p| approx_eq(p.2, -5.0, 1e-9)).collect();
    let y_max = pts.iter().map(|p| p.1).fold(f64::MIN, f64::max);
    let y_min = pts.iter().map(|p| p.1).fold(f64::MAX, f64::min);
    let width = y_max - y_min + 2.0 * R10;
    assert!(approx_eq(width, 2.0 * (1.0 + R10), 1e-9), "{width}");
    let x_min = pts.iter().map(|p| p.0).fold(f64::MAX, f64::min);
    let x_max = pts.iter().map(|p| p.0).fold(f64::MIN, f64::max);
    assert!(approx_eq(x_min, -1.0, 1e-9) && approx_eq(x_max, 21.0, 1e-9));
}

#[test]
fn a_climb_trochoid_runs_its_loops_counter_clockwise_with_the_links_right_of_the_guide() {
    let c = trochoid_along(&straight(5.0), &params(LoopRadius::Default, 0.5), &grooving_setup()).unwrap();
    for m in &c.moves {
        match m.motion {
            Motion::Arc { clockwise, .. } => assert!(!clockwise),
            Motion::Linear if approx_eq(m.start.z, m.end.z, 1e-12) => {
                assert!(approx_eq(m.start.y, -1.0, 1e-12) && m.end.x > m.start.x, "link {}", m.line)
            }
            _ => {}
        }
    }
    let conventional = TrochoidParams { direction: CutDirection::Conventional, ..params(LoopRadius::Default, 0.5) };
    let c = trochoid_along(&straight(5.0), &conventional, &grooving_setup()).unwrap();
    for m in &c.moves {
        match m.motion {
            Motion::Arc { clockwise, .. } => assert!(clockwise),
            Motion::Linear if approx_eq(m.start.z, m.end.z, 1e-12) => assert!(approx_eq(m.start.y, 1.0, 1e-12)),
            _ => {}
        }
    }
    assert_tangent_at(&c.moves, -5.0, 1e-9);
}

#[test]
fn the_pass_plunges_from_the_retract_height_and_ends_at_the_clearance_height() {
    let setup = grooving_setup();
    let c = trochoid_along(&straight(5.0), &params(LoopRadius::Default, 0.5), &setup).unwrap();
    let first = c.moves[0];
    assert!(matches!(first.motion, Motion::Rapid) && approx_eq(first.start.z, CLEARANCE_Z, 0.0));
    assert!(approx_eq(first.end.z, RETRACT_Z, 0.0));
    let plunge = c.moves[1];
    assert!(matches!(plunge.motion, Motion::Linear) && approx_eq(plunge.end.z, -5.0, 0.0));
    assert!(approx_eq(plunge.feed_mm_min.unwrap(), setup.plunge_feed_mm_min(), 1e-12));
    assert!(approx_eq(c.moves[2].feed_mm_min.unwrap(), 0.1 * 6.0 * 4800.0, 1e-9));
    let last = c.moves.last().unwrap();
    assert!(matches!(last.motion, Motion::Rapid) && approx_eq(last.end.z, CLEARANCE_Z, 0.0));
    assert_eq!(c.report.levels, 1);
    assert!(c.report.time_min > 0.0 && c.report.feed_length_mm > 11.0 * 2.0 * std::f64::consts::PI);
}

#[test]
fn a_helical_entry_ramps_down_whole_turns_on_the_first_loop() {
    let p = TrochoidParams { entry: Entry::Helix { pitch_mm: 1.0 }, ..params(LoopRadius::Default, 0.5) };
    let c = trochoid_along(&straight(5.0), &p, &grooving_setup()).unwrap();
    let helix = c.moves[1];
    let Motion::Arc { turns, center, clockwise, .. } = helix.motion else { panic!("not a helix") };
    // From the retract height 2 down to −5: 7 mm at ≤ 1 mm per turn = 7 turns.
    assert_eq!(turns, 6);
    assert!(!clockwise && approx_eq(center.x, 0.0, 1e-12) && approx_eq(center.y, 0.0, 1e-12));
    assert!(approx_eq(helix.end.z, -5.0, 0.0) && approx_eq(helix.end.x, helix.start.x, 0.0));
    assert!(approx_eq(c.report.turns, 7.0, 0.0));
    assert_continuous(&c.moves);
}

#[test]
fn a_variable_radius_follows_the_clearance_and_keeps_the_links_tangent() {
    // Clearance 7 → 9 mm over 20 mm: ρ = R − r − 0.2 grows from 1.8 to 3.8 mm.
    let g = straight(20.0);
    let radius = LoopRadius::Clearance { clearance_mm: vec![7.0, 9.0], allowance_mm: 0.2 };
    let plan = LoopPlan::new(&g, &radius, R10, 0.5, CutDirection::Climb).unwrap();
    for (s, rho) in plan.s_mm.iter().zip(&plan.rho_mm) {
        assert!(approx_eq(*rho, 1.8 + 0.1 * s, 1e-12));
    }
    let c = trochoid_along(&g, &params(radius, 0.5), &grooving_setup()).unwrap();
    assert_continuous(&c.moves);
    assert_tangent_at(&c.moves, -5.0, 1e-9);
    for m in arcs(&c) {
        let (rs, re, centre) = arc_radii(m).unwrap();
        let k = plan.centres.iter().position(|p| p.distance_mm(Point::new(centre.0, centre.1)) < 1e-12).unwrap();
        assert!(approx_eq(rs, plan.rho_mm[k], 1e-9) && approx_eq(re, plan.rho_mm[k], 1e-9));
    }
}

#[test]
fn loops_on_a_turning_guide_turn_more_on_the_outside_and_stay_tangent() {
    let g = Guide::polyline(&[Point::new(0.0, 0.0), Point::new(10.0, 0.0), Point::new(10.0, 10.0)]).unwrap();
    let c = trochoid_along(&g, &params(LoopRadius::Default, 0.5), &grooving_setup()).unwrap();
    assert_continuous(&c.moves);
    assert_tangent_at(&c.moves, -5.0, 1e-9);
    // The loops turn 2π each, plus the guide's 90° left turn in all.
    let sweep: f64 = arcs(&c).iter().map(|m| crate::core::toolpath::move_length(m) / 1.0).sum();
    let expected = (c.report.loops as f64 * 2.0 + 0.5) * std::f64::consts::PI;
    assert!(approx_eq(sweep, expected, 1e-6), "{sweep} vs {expected}");
}

#[test]
fn impossible_trochoids_are_refused_naming_the_field() {
    let setup = grooving_setup();
    let err = |p: TrochoidParams, g: &Guide| trochoid_along(g, &p, &setup).unwrap_err().to_string();
    assert!(err(params(LoopRadius::Fixed { rho_mm: 0.0 }, 0.5), &straight(5.0)).starts_with("rho_mm"));
    assert!(err(params(LoopRadius::Default, 0.0), &straight(5.0)).starts_with("pitch_mm"));
    assert!(err(TrochoidParams { z_mm: 3.0, ..params(LoopRadius::Default, 0.5) }, &straight(5.0)).starts_with("z_mm"));
    let narrow = LoopRadius::Clearance { clearance_mm: vec![5.2, 5.0], allowance_mm: 0.1 };
    assert!(err(params(narrow, 0.5), &straight(5.0)).starts_with("loop_radius"));
    let hairpin = Guide::polyline(&[Point::new(0.0, 0.0), Point::new(10.0, 0.0), Point::new(0.0, 0.2)]).unwrap();
    assert!(err(params(LoopRadius::Default, 0.5), &hairpin).starts_with("guide"));
    let short = LoopRadius::Clearance { clearance_mm: vec![7.0], allowance_mm: 0.0 };
    assert!(err(params(short, 0.5), &straight(5.0)).starts_with("clearance_mm"));
}

#[test]
fn loops_narrower_than_class_b_are_flagged_for_z_cut_division() {
    let p = params(LoopRadius::Fixed { rho_mm: 0.3 }, 0.5);
    let c = trochoid_along(&straight(5.0), &p, &grooving_setup()).unwrap();
    assert_eq!(c.report.warnings.len(), 1);
    assert!(c.report.warnings[0].contains("z-cut division"));
}

/// α statistics of a trochoid along a 60 mm straight slot cut from a solid box, starting
/// in an approach hole of the slot's width (seed 004 Table 1 steps 1–3): the largest α,
/// and the cut length with the material on the right and on the left.
fn slot_engagement(rho: f64, pitch: f64) -> (f64, f64, f64) {
    let c =
        trochoid_along(&straight(60.0), &params(LoopRadius::Fixed { rho_mm: rho }, pitch), &grooving_setup()).unwrap();
    let box_ = StockRegion::Rect(Rect { x_min: -20.0, y_min: -20.0, x_max: 80.0, y_max: 20.0 });
    let hole = StockRegion::Circle { cx: 0.0, cy: 0.0, r: rho + R10 };
    let (mut alpha_max, mut right, mut left) = (0.0f64, 0.0, 0.0);
    let a = analyze_with(&c.toolpath(), &spec(vec![box_], vec![hole], 0.0, -10.0), &NoProgress, |s| {
        if s.contact.alpha_rad > 0.0 {
            alpha_max = alpha_max.max(s.contact.alpha_rad.to_degrees());
            if s.contact.entry_rad + s.contact.exit_rad < 0.0 {
                right += s.sample.step_mm;
            } else {
                left += s.sample.step_mm;
            }
        }
    })
    .unwrap();
    let expected_area = 60.0 * 2.0 * (rho + R10);
    let removed = a.summary.slices[0].removed_area_mm2;
    assert!((removed - expected_area).abs() / expected_area < 0.01, "{removed} vs {expected_area}");
    (alpha_max, right, left)
}

#[test]
fn a_trochoid_in_a_12_mm_slot_engages_far_less_than_a_full_slot_and_cuts_on_its_right() {
    // The front of each loop is a concave arc of machined radius R = ρ + r whose previous
    // surface (the last loop's) lies one pitch further in: the concave case of MODEL.md §2
    // with Rd = p, α = 64.8° at R/r = 1.2 and p = 0.5 (MODEL.md §3 table). Far below a full
    // slot (180°), but above the 40° limit: why the papers reserve trochoids for class B.
    let (alpha_max, right, left) = slot_engagement(1.0, 0.5);
    let expected = concave_engagement_angle_rad(6.0, 0.5, R10).to_degrees();
    eprintln!("ρ = 1, p = 0.5: α max {alpha_max:.1}° (concave formula {expected:.1}°), cut right {right:.1} mm, left {left:.1} mm");
    assert!(alpha_max < 90.0 && (alpha_max - expected).abs() < 1.0, "{alpha_max} vs {expected}");
    assert!(right > 20.0 * left.max(1e-9));
}

#[test]
fn a_trochoid_in_a_20_mm_slot_engages_as_a_concave_arc_of_twice_the_tool_radius() {
    let (alpha_max, _, _) = slot_engagement(5.0, 0.5);
    let expected = concave_engagement_angle_rad(10.0, 0.5, R10).to_degrees();
    eprintln!("ρ = 5, p = 0.5: α max {alpha_max:.1}° (concave formula {expected:.1}°)");
    assert!((alpha_max - expected).abs() < 1.0, "{alpha_max} vs {expected}");
}

#[test]
fn a_variable_trochoid_along_a_medial_axis_branch_keeps_the_allowance_to_the_walls() {
    use crate::core::geometry::{Loop, Pocket, Vertex};
    use crate::core::medial::{medial_axis, MedialOptions};
    // A channel tapering from 12 to 20 mm wide over 80 mm (seed 004 Figure 5, variable radius).
    let outer = Loop::new(
        [(0.0, -6.0), (80.0, -10.0), (80.0, 10.0), (0.0, 6.0)].iter().map(|&(x, y)| Vertex::new(x, y, 0.0)).collect(),
    );
    let pocket = Pocket::new(outer, vec![]).unwrap();
    let axis = medial_axis(&pocket, &MedialOptions::default()).unwrap();
    let branch = axis
        .branches
        .iter()
        .max_by(|a, b| {
            let low = |br: &crate::core::medial::AxisBranch| {
                br.points.iter().map(|p| p.clearance_mm).fold(f64::MAX, f64::min)
            };
            low(a).total_cmp(&low(b))
        })
        .unwrap();
    let (guide, clearance) = Guide::of_axis_branch(branch).unwrap();
    let allowance = 0.2;
    let radius = LoopRadius::Clearance { clearance_mm: clearance, allowance_mm: allowance };
    let c = trochoid_along(&guide, &params(radius, 0.5), &grooving_setup()).unwrap();
    assert_continuous(&c.moves);
    assert_tangent_at(&c.moves, -5.0, 1e-9);
    let region = StockRegion::Pocket(pocket);
    let closest = feed_points(&c.moves, 32)
        .iter()
        .filter(|p| approx_eq(p.2, -5.0, 1e-9))
        .map(|p| region.signed_distance(p.0, p.1))
        .fold(f64::MAX, f64::min);
    eprintln!("medial-axis trochoid: {} loops, closest tool centre to a wall {closest:.3} mm", c.report.loops);
    assert!(closest >= R10 + allowance - 0.05 && closest <= R10 + allowance + 0.05, "{closest}");
}

#[test]
fn from_solid_stock_only_the_first_loop_slots_and_the_others_engage_as_in_an_open_start() {
    // No approach hole: the plunge and the first loop bore the start (a full slot, 180°);
    // from the second loop on, the engagement is the steady one of the 12 mm slot.
    let c = trochoid_along(&straight(20.0), &params(LoopRadius::Default, 0.5), &grooving_setup()).unwrap();
    let second_loop = c.moves.iter().filter(|m| matches!(m.motion, Motion::Arc { .. })).nth(2).unwrap().line as usize;
    let box_ = StockRegion::Rect(Rect { x_min: -20.0, y_min: -20.0, x_max: 40.0, y_max: 20.0 });
    let (mut first, mut rest) = (0.0f64, 0.0f64);
    analyze_with(&c.toolpath(), &spec(vec![box_], vec![], 0.0, -10.0), &NoProgress, |s| {
        let alpha = s.contact.alpha_rad.to_degrees();
        if s.sample.move_index + 1 < second_loop {
            first = first.max(alpha);
        } else {
            rest = rest.max(alpha);
        }
    })
    .unwrap();
    eprintln!("solid start: α max {first:.1}° on the first loop, {rest:.1}° after");
    assert!(first > 175.0 && (rest - concave_engagement_angle_rad(6.0, 0.5, R10).to_degrees()).abs() < 1.0);
}

#[test]
fn the_return_half_of_every_loop_after_the_first_runs_at_the_air_feed_and_cuts_nothing() {
    let air = 5760.0;
    let setup = CycleSetup { air_feed_mm_min: Some(air), ..grooving_setup() };
    let (rho, pitch) = (1.0, 0.2);
    let c = trochoid_along(&straight(30.0), &params(LoopRadius::Fixed { rho_mm: rho }, pitch), &setup).unwrap();
    let feed = setup.feed_mm_min();
    // Per loop: the front half at the cutting feed, the return half at the air feed (but the
    // first loop's, which cleans the floor after the entry), the link at the cutting feed.
    let arcs = arcs(&c);
    assert_eq!(arcs[0].feed_mm_min, Some(feed));
    assert_eq!(arcs[1].feed_mm_min, Some(feed));
    for pair in arcs[2..].chunks(2) {
        assert_eq!((pair[0].feed_mm_min, pair[1].feed_mm_min), (Some(feed), Some(air)));
    }
    // In a slot already open at the start (the approach hole), the simulation finds the air
    // moves in the air: at most the slivers the front half leaves at the tips of its crescent.
    let box_ = StockRegion::Rect(Rect { x_min: -20.0, y_min: -20.0, x_max: 60.0, y_max: 20.0 });
    let hole = StockRegion::Circle { cx: 0.0, cy: 0.0, r: rho + R10 };
    let spec = spec(vec![box_], vec![hole], 0.0, -10.0);
    let (mut air_alpha, mut air_length, mut cut_alpha) = (0.0_f64, 0.0, 0.0_f64);
    analyze_with(&c.toolpath(), &spec, &NoProgress, |s| {
        let alpha = s.contact.alpha_rad.to_degrees();
        if s.sample.feed_mm_min > feed {
            air_alpha = air_alpha.max(alpha);
            air_length += s.sample.step_mm;
        } else {
            cut_alpha = cut_alpha.max(alpha);
        }
    })
    .unwrap();
    eprintln!("air moves: {air_length:.0} mm, α max {air_alpha:.2}°; cutting moves α max {cut_alpha:.1}°");
    assert!(air_length > 0.45 * std::f64::consts::PI * rho * c.report.loops as f64);
    assert!(air_alpha < 2.0 && cut_alpha > 30.0, "{air_alpha} {cut_alpha}");
}

#[test]
fn a_loop_larger_than_the_one_before_or_than_the_tool_cuts_on_its_return() {
    let g = straight(10.0);
    let plan =
        LoopPlan::from_stations(&g, vec![0.0, 1.0, 2.0, 3.0], vec![1.0, 1.0, 1.5, 1.4], R10, CutDirection::Climb)
            .unwrap();
    let air: Vec<bool> = (0..plan.loops()).map(|k| plan.return_in_air(k)).collect();
    assert_eq!(air, [false, true, false, true]);
    let wide = LoopPlan::from_stations(&g, vec![0.0, 1.0, 2.0], vec![6.0, 6.0, 6.0], R10, CutDirection::Climb).unwrap();
    assert!(!wide.return_in_air(1) && !wide.return_in_air(2));
}
