use super::*;
use crate::core::conditions::CuttingConditions;
use crate::core::fixtures::{rounded_box, seed_001_ten_mm, ten_mm_life as life};
use crate::core::geometry::{Loop, Pocket, Vertex};
use crate::core::kinematics::MachineLimits;
use crate::core::nc::{parse_gcode, write_program, ParseOptions, WriterOptions};
use crate::core::progress::NoProgress;
use crate::core::tool::{EndMill, ToolType};
use crate::core::tool_life::ToolLifeModel;

/// The 10 mm straight end mill of seeds 001–004 with its database rows (MODEL.md §5), named
/// with `diameter_mm`.
pub(super) fn ten_mm(diameter_mm: f64) -> ToolCandidate {
    let c = |s: f64, ad: f64| CuttingConditions { spindle_rpm: s, fz_mm: 0.1, rd_mm: 0.5, ad_mm: ad };
    ToolCandidate {
        name: format!("square D{diameter_mm}"),
        tool: EndMill { tool_type: ToolType::Square, diameter_mm, flutes: 6, corner_radius_mm: 0.0 },
        roughing: c(4800.0, 10.0),
        intermediate: c(9600.0, 5.0),
        grooving: c(4800.0, 10.0),
        force_model: seed_001_ten_mm(),
        standard_force_n: 269.1,
        life: life(),
        min_feed_mm_min: 288.0,
        max_feed_mm_min: 11520.0,
        tool_price: 90.0,
    }
}

pub(super) fn options() -> ProcessOptions {
    ProcessOptions {
        alpha_limit_deg: 40.0,
        allowance_mm: 0.0,
        safe_z_mm: 5.0,
        sample_spacing_mm: Some(0.1),
        machine: MachineLimits {
            rapid_mm_min: 20000.0,
            max_feed_mm_min: 15000.0,
            accel_mm_s2: [2000.0, 2000.0, 1500.0],
            jerk_mm_s3: [50000.0, 50000.0, 40000.0],
            tool_change_s: 8.0,
        },
        machine_rate_per_hour: 60.0,
        currency: "USD".into(),
        target_consumption: DEFAULT_TARGET_CONSUMPTION,
        tune: true,
        max_force_factor: DEFAULT_MAX_FORCE_FACTOR,
        max_feed_change_per_mm: Some(1000.0),
        stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    }
}

fn ball() -> BaselineSpec {
    BaselineSpec {
        name: "ball D10 R5".into(),
        tool: EndMill { tool_type: ToolType::Ball, diameter_mm: 10.0, flutes: 2, corner_radius_mm: 5.0 },
        conditions: CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.05, rd_mm: 3.5, ad_mm: 0.6 },
        life: ToolLifeModel { standard_force_n: None, ..life() },
        tool_price: 85.0,
    }
}

#[test]
fn a_small_box_cavity_is_planned_with_the_tool_that_reaches_its_corners_and_compared_with_the_ball_baseline() {
    let input = CavityInput::Depth { pocket: rounded_box(40.0, 30.0, 6.0), z_top_mm: 0.0, z_bottom_mm: -12.0 };
    let cavity = input.whole();
    let candidates = [ten_mm(10.0), ten_mm(16.0)];
    let plan = plan_process(&input, &candidates, &options(), Some(&ball()), None, &NoProgress).unwrap();

    // The 16 mm tool cannot reach the R6 corners; the 10 mm one is chosen.
    assert_eq!(plan.candidates[1].status, CandidateStatus::CannotReach);
    assert_eq!(plan.candidates[0].status, CandidateStatus::Chosen);
    assert_eq!(plan.chosen, 0);

    // Two layers: 7 mm rough, then 5 mm intermediate-rough; each checked by the simulation.
    assert_eq!(plan.layers.len(), 2);
    assert_eq!(plan.layers[1].role, LayerRole::IntermediateRough);
    assert!(plan.layers.iter().all(|l| l.gouges == 0 && l.uncleared_area_mm2 <= 1.0), "{:?}", plan.layers);
    let steps: Vec<Step> = plan.layers[1].figures.steps.iter().map(|s| s.step).collect();
    assert!(steps.contains(&Step::IntermediateRoughSideCutting), "{steps:?}");

    // Time, wear and cost are consistent.
    let e = &plan.evaluation;
    assert!(e.time.kinematic_min >= e.time.nominal_min);
    assert!(e.consumption.ratio > 0.0 && e.cost.total > 0.0);
    let by_layer: f64 = plan.layers.iter().map(|l| l.figures.figures.consumption).sum();
    assert!((by_layer - e.consumption.ratio).abs() < 1e-9);
    assert!(
        (e.removed_volume_mm3 - cavity.volume_mm3()).abs() / cavity.volume_mm3() < 0.02,
        "{}",
        e.removed_volume_mm3
    );

    // So small a job uses little of a tool: the tuning raises the force to its limit, which
    // shortens the job and uses more of the tool.
    assert_eq!(plan.tuning.outcome, TuningOutcome::LimitedByMaxForce);
    assert!(plan.tuning.time_min < plan.tuning.time_at_standard_min);
    assert!(plan.tuning.consumption > plan.tuning.consumption_at_standard);

    // The program parses and cuts every feed move of the plan.
    let text = write_program(&e.program, &WriterOptions::default());
    let parsed = parse_gcode(&text, &ParseOptions::default()).unwrap();
    let length = |p: &crate::core::toolpath::Toolpath| {
        let feed = p.moves.iter().filter(|m| !matches!(m.motion, crate::core::toolpath::Motion::Rapid));
        feed.map(crate::core::toolpath::move_length).sum::<f64>()
    };
    assert!((length(&parsed) - length(&e.program)).abs() < 1e-3 * length(&e.program));

    // The baseline: 20 levels of 0.6 mm with the R5 ball, slower than the proposed plan.
    let b = plan.baseline.as_ref().unwrap();
    assert_eq!(b.levels, 20);
    assert!(
        b.figures.kinematic_time_min > e.time.kinematic_min,
        "{} vs {}",
        b.figures.kinematic_time_min,
        e.time.kinematic_min
    );
    assert!(plan.comparison.unwrap().kinematic_time_ratio < 1.0);
}

#[test]
fn a_cavity_no_candidate_can_reach_is_refused_with_every_reason() {
    // A 12 mm slot with round ends: the 16 mm tool cannot enter it at all.
    let slot = Loop::new(vec![
        Vertex::new(0.0, 0.0, 0.0),
        Vertex::new(40.0, 0.0, 1.0),
        Vertex::new(40.0, 12.0, 0.0),
        Vertex::new(0.0, 12.0, 1.0),
    ]);
    let cavity =
        CavityInput::Layers(layers_by_depth(&Pocket::new(slot, vec![]).unwrap(), 0.0, -5.0, 10.0, 5.0).unwrap());
    let e = plan_process(&cavity, &[ten_mm(16.0)], &options(), None, None, &NoProgress);
    // Alone, it is the smallest candidate: it is planned, and its plan cannot cut the slot.
    let message = e.map(|p| p.candidates.len()).unwrap_err().to_string();
    assert!(message.starts_with("diameters_mm") && message.contains("square D16: "), "{message}");
}

#[test]
fn bad_options_are_refused_naming_the_field() {
    let cavity = CavityInput::Layers(layers_by_depth(&rounded_box(40.0, 30.0, 6.0), 0.0, -12.0, 10.0, 5.0).unwrap());
    let mut o = options();
    o.target_consumption = 1.5;
    let e = check_process(&cavity, &[ten_mm(10.0)], &o).unwrap_err();
    assert!(e.to_string().starts_with("target_consumption"), "{e}");
    let mut o = options();
    o.safe_z_mm = -1.0;
    assert!(check_process(&cavity, &[ten_mm(10.0)], &o).unwrap_err().to_string().starts_with("safe_z"));
    assert!(check_process(&cavity, &[], &options()).is_err());
}

#[test]
fn the_unreachable_area_of_a_sharp_rectangle_is_its_four_corners() {
    let p = Pocket::new(Loop::rectangle(0.0, 0.0, 50.0, 40.0), vec![]).unwrap();
    let a = crate::core::pocketing::unreachable_area_mm2(&p, 5.0);
    let corners = 4.0 * 25.0 * (1.0 - std::f64::consts::FRAC_PI_4);
    assert!((a - corners).abs() < 0.05 * corners, "{a} vs {corners}");
    assert!(crate::core::pocketing::unreachable_area_mm2(&rounded_box(50.0, 40.0, 6.0), 5.0) < 1e-3);
}

#[test]
fn a_plan_keeps_the_stock_its_layers_leave_with_the_corners_the_tool_cannot_reach_as_rest_material() {
    // A sharp 40 × 30 rectangle 24 mm deep: two rough layers (the second a copy of the
    // first, moved down) and an intermediate-rough one, each leaving the four corners the
    // 10 mm tool cannot reach, 25 (1 − π/4) mm² each.
    let sharp = Pocket::new(Loop::rectangle(0.0, 0.0, 40.0, 30.0), vec![]).unwrap();
    let input = CavityInput::Depth { pocket: sharp, z_top_mm: 0.0, z_bottom_mm: -24.0 };
    let plan = plan_process(&input, &[ten_mm(10.0)], &options(), None, None, &NoProgress).unwrap();
    assert!(plan.layers.iter().any(|l| l.copy_of.is_some()), "{:?}", plan.layers);
    let kept = plan.stock.as_ref().expect("the plan keeps its stock");
    let stock = &kept.stock;
    stock.validate().unwrap();
    assert!(stock.cavity);
    assert!((stock.z_top() - 0.0).abs() < 1e-9 && (stock.z_bottom() + 24.0).abs() < 1e-9, "{:?}", stock.slices);
    assert_eq!(stock.floor(), Some(crate::core::analysis::kept::Floor::Unbounded));

    // Every slice holds the four corners, and nothing above a place a lower layer cleared.
    let corners_mm2 = 4.0 * 25.0 * (1.0 - std::f64::consts::FRAC_PI_4);
    for level in &kept.rest.levels {
        assert!((level.area_mm2 - corners_mm2).abs() < 0.25 * corners_mm2, "{level:?}");
    }
    let expected_mm3 = corners_mm2 * 24.0;
    assert!((kept.rest.volume_mm3 - expected_mm3).abs() < 0.25 * expected_mm3, "{}", kept.rest.volume_mm3);
    for pair in stock.slices.windows(2) {
        let (upper, lower) = (&stock.rasters[pair[0].raster], &stock.rasters[pair[1].raster]);
        assert!(upper.iter().zip(lower).all(|(&u, &l)| u <= 0 || l > 0), "{:?} over {:?}", pair[0], pair[1]);
    }
    // What the cavity lost and what is left make the cavity.
    let removed = plan.evaluation.removed_volume_mm3;
    let cavity = 40.0 * 30.0 * 24.0;
    assert!((removed + kept.rest.volume_mm3 - cavity).abs() < 0.01 * cavity, "{removed} + {}", kept.rest.volume_mm3);
}

#[test]
fn a_plan_of_layers_with_different_contours_keeps_what_the_upper_layer_leaves_outside_the_lower() {
    // A 40 × 30 rectangle 6 mm deep over an L, the quadrant x > 20, y > 15 not cut below:
    // the upper layer's corner there lies outside the lower layer's pocket, which does not
    // cut it away. Both contours have the same bounds, so the layers share one grid.
    let rectangle = Pocket::new(Loop::rectangle(0.0, 0.0, 40.0, 30.0), vec![]).unwrap();
    let l_shape = Pocket::new(
        Loop::new(
            [(0.0, 0.0), (40.0, 0.0), (40.0, 15.0), (20.0, 15.0), (20.0, 30.0), (0.0, 30.0)]
                .into_iter()
                .map(|(x, y)| Vertex::new(x, y, 0.0))
                .collect(),
        ),
        vec![],
    )
    .unwrap();
    let layer = |pocket: Pocket, z_top_mm: f64, z_bottom_mm: f64| CavityLayer { pocket, z_top_mm, z_bottom_mm };
    let cavity = Cavity { layers: vec![layer(rectangle, 0.0, -6.0), layer(l_shape, -6.0, -11.0)] };
    let plan =
        plan_process(&CavityInput::Layers(cavity), &[ten_mm(10.0)], &options(), None, None, &NoProgress).unwrap();
    let kept = plan.stock.as_ref().expect("the plan keeps its stock");
    kept.stock.validate().unwrap();
    let corners_mm2 = 4.0 * 25.0 * (1.0 - std::f64::consts::FRAC_PI_4);
    for level in kept.rest.levels.iter().filter(|l| l.z_bottom > -6.0 - 1e-9) {
        assert!((level.area_mm2 - corners_mm2).abs() < 0.25 * corners_mm2, "upper layer: {level:?}");
    }
    assert!(kept.rest.levels.iter().any(|l| l.z_top < -6.0 + 1e-9), "{:?}", kept.rest.levels);
}

#[test]
fn a_stepped_cavity_keeps_its_stock_on_the_grid_covering_every_layer() {
    // A 40 × 30 rectangle 6 mm deep over a 30 × 20 one 5 mm deep: each layer is simulated on
    // a grid of its own outline; the kept stock lies on one grid covering both, each layer
    // with the four corners the 10 mm tool leaves in it.
    let big = Pocket::new(Loop::rectangle(0.0, 0.0, 40.0, 30.0), vec![]).unwrap();
    let small = Pocket::new(Loop::rectangle(5.0, 5.0, 35.0, 25.0), vec![]).unwrap();
    let layer = |pocket: Pocket, z_top_mm: f64, z_bottom_mm: f64| CavityLayer { pocket, z_top_mm, z_bottom_mm };
    let cavity = Cavity { layers: vec![layer(big, 0.0, -6.0), layer(small, -6.0, -11.0)] };
    let plan =
        plan_process(&CavityInput::Layers(cavity), &[ten_mm(10.0)], &options(), None, None, &NoProgress).unwrap();
    let kept = plan.stock.as_ref().unwrap_or_else(|| panic!("no stock: {:?}", plan.warnings));
    kept.stock.validate().unwrap();
    let g = kept.stock.grid;
    assert!(g.x0_mm <= 0.0 && g.y0_mm <= 0.0, "{g:?}");
    assert!(g.x0_mm + g.nx as f64 * g.cell_mm >= 40.0 && g.y0_mm + g.ny as f64 * g.cell_mm >= 30.0, "{g:?}");
    let corners_mm2 = 4.0 * 25.0 * (1.0 - std::f64::consts::FRAC_PI_4);
    for level in &kept.rest.levels {
        assert!((level.area_mm2 - corners_mm2).abs() < 0.25 * corners_mm2, "{level:?}");
    }
    let inside = |[x, y]: [f64; 2], (x0, y0, x1, y1): (f64, f64, f64, f64)| x0 <= x && x <= x1 && y0 <= y && y <= y1;
    for level in &kept.rest.levels {
        let point = level.point.expect("rest material");
        let bounds = if level.z_top > -6.0 + 1e-9 { (0.0, 0.0, 40.0, 30.0) } else { (5.0, 5.0, 35.0, 25.0) };
        assert!(inside(point, bounds), "{level:?}");
    }
}
