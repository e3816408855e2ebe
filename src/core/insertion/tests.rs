//! The planner on real contours: border.dxf and a box cavity with a narrow slot.

use super::*;
use crate::core::analysis::test_paths::sample_bits;
use crate::core::conditions::CuttingConditions;
use crate::core::geometry::{Loop, Vertex};
use crate::core::progress::NoProgress;
use crate::core::tool::{EndMill, ToolType};

fn tool() -> EndMill {
    EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 }
}

fn spec(z_bottom: f64) -> InsertionSpec {
    let roughing = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
    let grooving = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
    InsertionSpec::new(tool(), roughing, grooving, 0.0, z_bottom)
}

pub fn border_dxf() -> Pocket {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/border.dxf");
    let text = std::fs::read_to_string(path).unwrap();
    crate::core::geometry::pocket_from_loops(crate::core::geometry::loops_from_dxf(&text).unwrap()).unwrap()
}

/// An 80 × 60 mm box with a 12 mm wide, 40 mm long slot leaving its right wall.
pub fn box_with_slot(slot_width_mm: f64) -> Pocket {
    let h = slot_width_mm / 2.0;
    let outer = Loop::new(vec![
        Vertex::new(0.0, 0.0, 0.0),
        Vertex::new(80.0, 0.0, 0.0),
        Vertex::new(80.0, 30.0 - h, 0.0),
        Vertex::new(120.0, 30.0 - h, 0.0),
        Vertex::new(120.0, 30.0 + h, 0.0),
        Vertex::new(80.0, 30.0 + h, 0.0),
        Vertex::new(80.0, 60.0, 0.0),
        Vertex::new(0.0, 60.0, 0.0),
    ]);
    Pocket::new(outer, vec![]).unwrap()
}

fn show(name: &str, plan: &InsertionPlan) {
    println!(
        "{name}: base max α {:.1}° ({} overloaded), rounds {}",
        plan.base_max_alpha_deg, plan.base_overloaded_samples, plan.rounds
    );
    for t in &plan.treatments {
        println!("  {t:?}");
    }
    println!("  verification {:?}", plan.verification);
    println!("  trim {:?}, moves {}", plan.trim, plan.toolpath.moves.len());
    assert_overloads_are_listed_with_their_lines(plan);
    if let Some(o) = plan.verification.first_overload {
        let i = o.line as usize - 1;
        for m in &plan.toolpath.moves[i.saturating_sub(3)..(i + 2).min(plan.toolpath.moves.len())] {
            println!("    {m:?}");
        }
    }
}

/// Every overloaded sample outside the z-cut passes is in one of the listed stretches, each
/// named by its moves and peaking above the limit (issue 29: spikes are reported with their
/// lines).
fn assert_overloads_are_listed_with_their_lines(plan: &InsertionPlan) {
    let v = &plan.verification;
    let overloaded = v.outside_zcut.overloaded + v.crossing_zcut.overloaded;
    assert_eq!(v.overloads.is_empty(), overloaded == 0, "{v:?}");
    assert!(v.overloads.len() <= MAX_LISTED_OVERLOADS && v.overload_stretches >= v.overloads.len());
    if v.overload_stretches <= MAX_LISTED_OVERLOADS {
        assert_eq!(v.overloads.iter().map(|o| o.samples).sum::<usize>(), overloaded, "{v:?}");
    }
    if v.crossing_zcut.overloaded > 0 {
        assert!(v.overloads.iter().any(|o| o.in_zcut_region), "{v:?}");
        assert!(plan.warnings.iter().any(|w| w.contains("cross the z-cut regions")), "{:?}", plan.warnings);
    }
    for o in &v.overloads {
        assert!(o.line_from >= 1 && o.line_from <= o.line_to, "{o:?}");
        assert!((o.line_from..=o.line_to).contains(&o.peak.line), "{o:?}");
        assert!(o.peak.value > v.alpha_limit_deg && o.samples >= 1 && o.length_mm > 0.0, "{o:?}");
        assert!(o.line_to as usize <= plan.toolpath.moves.len(), "{o:?}");
    }
}

#[test]
fn border_dxf_gets_a_complete_gouge_free_program_within_the_engagement_limit() {
    let pocket = border_dxf();
    let plan = plan_insertion(&pocket, &spec(-10.0), None, &NoProgress).unwrap();
    show("border", &plan);
    assert!(plan.verification.passed, "{:?}", plan.verification);
}

#[test]
fn a_box_cavity_with_a_12_mm_slot_gets_a_complete_gouge_free_program_within_the_engagement_limit() {
    let pocket = box_with_slot(12.0);
    let plan = plan_insertion(&pocket, &spec(-10.0), None, &NoProgress).unwrap();
    show("box", &plan);
    assert!(plan.verification.passed, "{:?}", plan.verification);
    // What the wall pass still meets is short spikes where it turns the corners the z-cut
    // division cut first, each listed with its move.
    for o in &plan.verification.overloads {
        assert!(o.in_zcut_region && o.length_mm <= 0.5, "{o:?}");
    }
}

#[test]
fn a_slot_too_narrow_for_trochoids_is_cut_by_z_cut_division_and_reported_so() {
    // 10.8 mm wide: R/r = 1.08 < 1.1 (class C) for a 10 mm tool.
    let pocket = box_with_slot(10.8);
    let plan = plan_insertion(&pocket, &spec(-10.0), None, &NoProgress).unwrap();
    show("narrow slot", &plan);
    let zcut: Vec<_> = plan.treatments.iter().filter(|t| t.kind == TreatmentKind::ZCut).collect();
    let long = zcut.iter().find(|t| (t.s_to_mm.unwrap() - t.s_from_mm.unwrap()).abs() > 20.0);
    let long = long.expect("the slot is one long z-cut stretch");
    assert_eq!(long.class, Some(crate::core::medial::RadiusClass::C));
    assert_eq!(long.passes_per_level, 4, "10 mm in passes of at most 2.5 mm");
    assert!(long.area_mm2 > 0.9 * 10.0 * 30.0, "{long:?}");
    // The z-cut passes are judged apart from the full-depth moves crossing their regions.
    assert!(plan.verification.inside_zcut.samples > 0, "{:?}", plan.verification);
    assert!(plan.verification.passed, "{:?}", plan.verification);
}

#[test]
fn fixed_radius_trochoids_of_seed_004_figure_4_come_down_in_pitch_and_what_they_leave_is_reported() {
    let pocket = box_with_slot(12.0);
    let rho = crate::core::cycles::trochoid::default_loop_radius_mm(5.0);
    let fixed = InsertionSpec { loop_size: LoopSize::Fixed { rho_mm: rho }, ..spec(-10.0) };
    let plan = plan_insertion(&pocket, &fixed, None, &NoProgress).unwrap();
    // The long trochoids (the short ones shrink into corners, each loop inside the last).
    let trochoids: Vec<_> =
        plan.treatments.iter().filter(|t| t.kind == TreatmentKind::Trochoid && t.loops > 10).collect();
    assert!(!trochoids.is_empty());
    for t in &trochoids {
        assert!(t.loop_radius_max_mm.unwrap() <= rho + 1e-9, "{t:?}");
        // (ρ + r)/r = 1.2 at Rd 0.5 peaks near 65° (MODEL.md §7): the pitch comes down.
        assert!(t.pitch_min_mm.unwrap() < 0.3, "{t:?}");
    }
    let v = &plan.verification;
    assert!(v.gouges == 0 && v.uncleared_area_mm2 <= 0.0, "{v:?}");
    // A 12 mm band through a 60 mm wide box leaves the base path stepping onto its edge:
    // where that still exceeds the limit it is reported, not hidden.
    if v.outside_zcut.overloaded > 0 {
        assert!(!v.passed && v.first_overload.is_some());
        assert_eq!(v.overloads[0].line_from, v.first_overload.unwrap().line, "{v:?}");
        assert!(plan.warnings.iter().any(|w| w.contains("still exceed")), "{:?}", plan.warnings);
    }
}

#[test]
fn a_ball_end_mill_or_an_unordered_layer_is_refused_naming_the_field() {
    let ball = EndMill { tool_type: ToolType::Ball, ..tool() };
    let err = plan_insertion(&box_with_slot(12.0), &InsertionSpec { tool: ball, ..spec(-10.0) }, None, &NoProgress)
        .unwrap_err();
    assert!(err.to_string().starts_with("tool:"), "{err}");
    let err = plan_insertion(&box_with_slot(12.0), &spec(3.0), None, &NoProgress).unwrap_err();
    assert!(err.to_string().starts_with("z_bottom_mm:"), "{err}");
}

#[test]
fn steps_so_small_the_plan_would_never_end_are_refused_before_planning_naming_the_field() {
    let tiny = 1e-9;
    let grooving = CuttingConditions { rd_mm: tiny, ..spec(-10.0).grooving };
    let roughing = CuttingConditions { ad_mm: tiny, ..spec(-10.0).roughing };
    let cases = [
        (InsertionSpec { pitch_mm: Some(tiny), ..spec(-10.0) }, "pitch_mm:"),
        (InsertionSpec { grooving, ..spec(-10.0) }, "grooving.rd_mm:"),
        // A limit so low that a straight cut at it is thinner than the smallest pitch.
        (InsertionSpec { alpha_limit_deg: 1.5, ..spec(-10.0) }, "alpha_limit_deg:"),
        (InsertionSpec { zcut_ad_mm: tiny, ..spec(-10.0) }, "zcut_ad_mm:"),
        (InsertionSpec { roughing, ..spec(-10.0) }, "roughing.ad_mm:"),
        (InsertionSpec { ramp_pitch_mm: Some(tiny), ..spec(-10.0) }, "ramp_pitch_mm:"),
    ];
    for (spec, field) in cases {
        let err = check_plan(&box_with_slot(12.0), &spec, None).unwrap_err().to_string();
        assert!(err.starts_with(field), "{field} {err}");
    }
    let thin = check_plan(&box_with_slot(12.0), &spec(-1e-9), None).unwrap_err().to_string();
    assert!(thin.starts_with("z_bottom_mm: the layer from 0 mm down to") && thin.contains("thinner"), "{thin}");
    // The smallest pitch the planner writes is accepted.
    let smallest = InsertionSpec { pitch_mm: Some(pitch::MIN_PITCH_MM), ..spec(-10.0) };
    assert!(smallest.validate().is_ok());
}

#[test]
fn a_pocket_with_an_island_is_cleared_round_it_within_the_limit_widening_the_trochoids_where_needed() {
    let island = Loop::rectangle(35.0, 30.0, 65.0, 50.0).reversed();
    let ring = Pocket::new(Loop::rectangle(0.0, 0.0, 100.0, 80.0), vec![island]).unwrap();
    let plan = plan_insertion(&ring, &spec(-10.0), None, &NoProgress).unwrap();
    show("ring", &plan);
    // The first round's capped trochoids leave band edges the base path steps onto; the
    // second widens those trochoids to the walls.
    assert_eq!(plan.rounds, 2);
    assert!(plan.verification.passed, "{:?}", plan.verification);
}

#[test]
fn a_circular_pocket_is_opened_from_its_centre_by_a_helix_and_a_limit_keeping_spiral() {
    let circle = Pocket::new(Loop::circle(0.0, 0.0, 30.0), vec![]).unwrap();
    let plan = plan_insertion(&circle, &spec(-10.0), None, &NoProgress).unwrap();
    show("circle", &plan);
    let opening = plan.treatments.iter().find(|t| t.kind == TreatmentKind::Opening).expect("an opening");
    // Steps grow from about 0.2 mm near the centre (machined radius close to r), never above
    // a straight cut's depth at the limit.
    let most = spec(-10.0).max_pitch_mm();
    assert!(opening.pitch_min_mm.unwrap() < 0.3 && opening.pitch_max_mm.unwrap() <= most + 1e-12, "{opening:?}");
    assert!(plan.verification.passed, "{:?}", plan.verification);
}

/// A polygon of `n` vertices on a circle of radius 40 mm.
fn polygon(n: usize) -> Pocket {
    let vertices = (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            Vertex::new(40.0 * a.cos(), 40.0 * a.sin(), 0.0)
        })
        .collect();
    Pocket::new(Loop::new(vertices), vec![]).expect("a convex polygon is a valid pocket")
}

#[test]
fn a_pocket_of_more_segments_than_the_planners_take_is_refused_naming_the_field() {
    assert!(check_pocket_size(&polygon(MAX_PLANNED_SEGMENTS), "contour").is_ok());
    let e = check_pocket_size(&polygon(MAX_PLANNED_SEGMENTS + 1), "layers[2].contour").unwrap_err().to_string();
    assert!(e.starts_with("layers[2].contour") && e.contains("10001 segments"), "{e}");
}

/// The gouge check measuring every test point (what [`verify::check_gouges`] must equal).
fn gouges_measured_everywhere(
    path: &Toolpath,
    pocket: &Pocket,
    r_mm: f64,
    z_top_mm: f64,
) -> (usize, f64, Option<Spot>) {
    let boundary = Boundary::of_pocket(pocket);
    let (mut count, mut min_margin, mut first) = (0, f64::INFINITY, None);
    for m in path.moves.iter().filter(|m| m.start.z < z_top_mm || m.end.z < z_top_mm) {
        let n = (crate::core::toolpath::move_length(m) / verify::GOUGE_STEP_MM).ceil().max(1.0) as usize;
        for k in 0..=n {
            let (p, _) = crate::core::analysis::sampling::point_on(m, k as f64 / n as f64);
            if p.z >= z_top_mm {
                continue;
            }
            let c = boundary.clearance_mm(crate::core::geometry::Point::new(p.x, p.y));
            let margin = if pocket.contains(p.x, p.y) { c } else { -c } - r_mm;
            min_margin = min_margin.min(margin);
            if margin < -verify::GOUGE_TOLERANCE_MM {
                count += 1;
                first.get_or_insert(Spot { x_mm: p.x, y_mm: p.y, z_mm: p.z, line: m.line, value: margin });
            }
        }
    }
    (count, min_margin, first)
}

#[test]
fn the_gouge_check_passing_over_points_far_from_the_walls_finds_what_measuring_every_point_finds() {
    let pocket = box_with_slot(12.0);
    let plan = plan_insertion(&pocket, &spec(-10.0), None, &NoProgress).unwrap();
    let mut shifted = plan.toolpath.clone();
    for m in &mut shifted.moves {
        m.start.x += 3.0;
        m.end.x += 3.0;
        if let crate::core::toolpath::Motion::Arc { center, .. } = &mut m.motion {
            center.x += 3.0;
        }
    }
    for path in [&plan.toolpath, &shifted] {
        let (count, margin, first) = verify::check_gouges(path, &pocket, &Boundary::of_pocket(&pocket), 5.0, 0.0, 0.0);
        let (all_count, all_margin, all_first) = gouges_measured_everywhere(path, &pocket, 5.0, 0.0);
        assert_eq!(count, all_count);
        assert!(crate::core::tolerance::approx_eq(margin, all_margin, 1e-12), "{margin} {all_margin}");
        assert_eq!(first.map(|s| s.line), all_first.map(|s| s.line));
    }
    let (gouges, margin, _) = verify::check_gouges(&shifted, &pocket, &Boundary::of_pocket(&pocket), 5.0, 0.0, 0.0);
    assert!(gouges > 100 && margin < -2.9, "{gouges} {margin}");
}

/// Counts what the base check and the last verification hand an observer: samples and
/// their cutting length.
#[derive(Default)]
struct Tally {
    base: (usize, f64),
    verified: (usize, f64),
    restarts: usize,
}

/// A sample's step where it cuts.
fn cut_mm(sample: &crate::core::analysis::engine::SampleResult) -> f64 {
    if sample.sample.rapid || sample.plunge || sample.contact.alpha_rad <= 0.0 {
        0.0
    } else {
        sample.sample.step_mm
    }
}

impl SampleObserver for Tally {
    fn base(&mut self, sample: &crate::core::analysis::engine::SampleResult) {
        self.base = (self.base.0 + 1, self.base.1 + cut_mm(sample));
    }

    fn restart(&mut self) {
        self.verified = (0, 0.0);
        self.restarts += 1;
    }

    fn verified(&mut self, sample: &crate::core::analysis::engine::SampleResult) {
        self.verified = (self.verified.0 + 1, self.verified.1 + cut_mm(sample));
    }
}

#[test]
fn an_observer_sees_the_samples_an_analysis_of_the_base_path_and_of_the_finished_program_has() {
    let (pocket, spec) = (box_with_slot(12.0), spec(-10.0));
    let mut tally = Tally::default();
    let plan = plan_insertion_observed(&pocket, &spec, None, &mut tally, &NoProgress).expect("plans");
    assert_eq!(tally.restarts, plan.rounds);
    let analysis = analysis_spec(&pocket, &spec);
    let cases = [
        (&plan.drawing.base_path, tally.base, plan.base_air_cut_length_mm),
        (&plan.toolpath, tally.verified, plan.air_cut_length_mm),
    ];
    for (path, (samples, cut_mm), air_cut_mm) in cases {
        let alone = crate::core::analysis::analyze(path, &analysis, &NoProgress).expect("analyses");
        assert_eq!(samples, alone.summary.samples);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * a.max(1.0);
        assert!(close(cut_mm, alone.summary.cutting_length_mm), "{cut_mm}");
        assert!(close(air_cut_mm, alone.summary.air_cut_length_mm), "{air_cut_mm}");
    }
    assert!(tally.verified.1 > 0.0 && plan.air_cut_length_mm > 0.0 && tally.base.0 > 0);
}

/// Every sample the base check and the last verification hand an observer, bit for bit.
#[derive(Default)]
struct Recorder {
    base: Vec<[u64; 9]>,
    verified: Vec<[u64; 9]>,
}

impl SampleObserver for Recorder {
    fn base(&mut self, sample: &crate::core::analysis::engine::SampleResult) {
        self.base.push(sample_bits(sample));
    }

    fn restart(&mut self) {
        self.verified.clear();
    }

    fn verified(&mut self, sample: &crate::core::analysis::engine::SampleResult) {
        self.verified.push(sample_bits(sample));
    }
}

#[test]
fn the_plans_checks_on_two_cores_give_every_sample_an_analysis_on_one_core_gives() {
    for pocket in [box_with_slot(12.0), border_dxf()] {
        let spec = spec(-10.0);
        let mut seen = Recorder::default();
        let plan = plan_insertion_observed(&pocket, &spec, None, &mut seen, &NoProgress).expect("plans");
        let analysis = analysis_spec(&pocket, &spec);
        for (path, samples) in [(&plan.drawing.base_path, &seen.base), (&plan.toolpath, &seen.verified)] {
            let mut alone = Vec::new();
            crate::core::analysis::analyze_with(path, &analysis, &NoProgress, |r| alone.push(sample_bits(r)))
                .expect("analyses");
            // Long enough to be split over two threads.
            assert!(samples.len() > crate::core::analysis::split::MIN_SPLIT_SAMPLES, "{} samples", samples.len());
            assert!(*samples == alone, "the plan's samples differ from one core's analysis");
        }
    }
}

/// Every fraction reported.
struct Reports(std::sync::Mutex<Vec<f64>>);

impl Progress for Reports {
    fn report(&self, fraction: f64) {
        self.0.lock().expect("not poisoned").push(fraction);
    }
    fn cancelled(&self) -> bool {
        false
    }
}

#[test]
fn a_plans_progress_rises_through_its_base_check_and_verification_and_never_goes_back() {
    let reports = Reports(std::sync::Mutex::new(Vec::new()));
    plan_insertion(&box_with_slot(12.0), &spec(-10.0), None, &reports).expect("plans");
    let reports = reports.0.into_inner().expect("not poisoned");
    assert!(reports.windows(2).all(|w| w[0] <= w[1]), "the progress went back");
    assert!(reports.iter().all(|f| (0.0..=1.0).contains(f)));
    assert!(reports.iter().any(|&f| f > 0.0 && f < BASE_CHECK_PROGRESS), "the base check reports");
    assert!(reports.iter().any(|&f| f > 0.5), "the verification reports");
}
