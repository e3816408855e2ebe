use super::*;
use crate::core::fixtures::seed_001_ten_mm;

/// Every row must hold within this share (MODEL.md §9).
const TOLERANCE: f64 = 0.2;

fn bench() -> Bench {
    Bench::seed_003(seed_001_ten_mm())
}

/// The row named `case` as the stored (fitted) values reproduce it.
fn stored(case_starts: &str) -> RowCheck {
    let b = bench();
    let rows = calibration_rows(&b).unwrap();
    check(&b, &rows, FITTED_GAMMA_AT_40, FITTED_FORCE_EXPONENT)
        .unwrap()
        .into_iter()
        .find(|r| r.case.starts_with(case_starts))
        .unwrap_or_else(|| panic!("no row {case_starts}"))
}

fn assert_within_tolerance(row: &RowCheck) {
    assert!(
        row.relative_error().abs() <= TOLERANCE,
        "{}: predicted {:.2}, measured {} ({:+.0} %)",
        row.case,
        row.predicted,
        row.measured,
        100.0 * row.relative_error()
    );
}

#[test]
fn the_fit_finds_the_stored_gamma_at_40_and_force_exponent() {
    let fit = fit(&bench()).unwrap();
    assert!((fit.gamma_at_40 - FITTED_GAMMA_AT_40).abs() < 0.005, "{fit:#?}");
    assert!((fit.force_exponent - FITTED_FORCE_EXPONENT).abs() < 0.005, "{fit:#?}");
    for row in &fit.rows {
        assert_within_tolerance(row);
    }
}

#[test]
fn the_standard_straight_cut_lasts_320_m() {
    let row = stored("straight");
    assert!((row.predicted - 320.0).abs() < 1e-6, "{row:?}");
}

#[test]
fn a_concave_arc_of_r_over_r_2_at_f4320_lasts_15_m_of_centre_path_within_20_percent() {
    assert_within_tolerance(&stored("concave R/r = 2 at fixed F4320"));
}

#[test]
fn the_same_arc_at_constant_force_lasts_55_m_of_centre_path_within_20_percent() {
    assert_within_tolerance(&stored("concave R/r = 2 at constant force"));
}

#[test]
fn constant_force_makes_wave_path_a_last_5_times_as_long_within_20_percent() {
    assert_within_tolerance(&stored("wave path (A)"));
}

#[test]
fn constant_force_makes_wave_path_b_last_2_times_as_long_within_20_percent() {
    assert_within_tolerance(&stored("wave path (B)"));
}

#[test]
fn on_the_arc_of_r_over_r_2_the_machined_surface_is_twice_the_centre_path_30_m_and_110_m_within_20_percent() {
    let b = bench();
    let model = b.model(FITTED_GAMMA_AT_40, FITTED_FORCE_EXPONENT).unwrap();
    let arc = Piece { contour: Contour::Concave { surface_radius_mm: 10.0 }, rd_mm: 0.5, length_mm: 1.0 };
    for (feed, surface_m) in [(Feed::Fixed(4320.0), 30.0), (Feed::ConstantForce, 110.0)] {
        let life = b.life(&model, &[arc], feed).unwrap();
        assert!((life.machined_surface_m / life.centre_path_m - 2.0).abs() < 1e-9, "{life:?}");
        assert!((life.machined_surface_m / surface_m - 1.0).abs() <= TOLERANCE, "{feed:?}: {life:?}");
    }
}

#[test]
fn the_wave_paths_are_built_from_seed_003_table_2() {
    let b = bench();
    // (A): the run at the cap is a light cut; the arc is the R/r 1.6 of MODEL.md §3.
    let [run, arc] = WAVE_A.pieces(&b).unwrap();
    assert!((run.rd_mm - 0.27).abs() < 0.02 && (run.length_mm - 34.3).abs() < 1e-12, "{run:?}");
    let Contour::Concave { surface_radius_mm } = arc.contour else { panic!("{arc:?}") };
    assert!((surface_radius_mm / 5.0 - 1.6).abs() < 0.05, "{arc:?}");
    assert!((b.feed_of(&arc, Feed::ConstantForce).unwrap() - 547.9).abs() < 0.1);
    // (B): a deeper run at F8689.9 and a gentler arc (R/r about 2.3) at F1583.6.
    let [run, arc] = WAVE_B.pieces(&b).unwrap();
    assert!((run.rd_mm - 0.35).abs() < 0.02, "{run:?}");
    assert!((b.feed_of(&run, Feed::ConstantForce).unwrap() - 8689.9).abs() < 0.1);
    let Contour::Concave { surface_radius_mm } = arc.contour else { panic!("{arc:?}") };
    assert!((surface_radius_mm / 5.0 - 2.3).abs() < 0.05, "{arc:?}");
}

#[test]
fn gamma_is_1_at_the_standard_engagement_and_keeps_the_steep_shape_of_seed_002_above_40_degrees() {
    let model = bench().model(FITTED_GAMMA_AT_40, FITTED_FORCE_EXPONENT).unwrap();
    let alpha0 = bench().standard_alpha_deg().unwrap();
    assert!((alpha0 - 25.84).abs() < 0.01, "{alpha0}");
    assert!((model.gamma(alpha0) - 1.0).abs() < 1e-12 && (model.gamma(10.0) - 1.0).abs() < 1e-12);
    assert!(model.gamma(36.4) > 1.0 && model.gamma(36.4) < FITTED_GAMMA_AT_40);
    for (a, g) in SEED_002_GAMMA_SHAPE {
        assert!((model.gamma(a) / model.gamma(40.0) - g).abs() < 1e-12, "{a}°");
    }
}

#[test]
fn a_table_moved_to_the_balls_standard_engagement_is_1_there_and_ends_at_180_degrees() {
    let flat = gamma_table(25.84, FITTED_GAMMA_AT_40);
    let ball = moved_gamma_table(&flat, 25.84, 78.46);
    assert!((table_value(&ball, 78.46) - 1.0).abs() < 1e-12 && (table_value(&ball, 60.0) - 1.0).abs() < 1e-12);
    assert!((table_value(&ball, 78.46 + 14.16) - FITTED_GAMMA_AT_40).abs() < 1e-9);
    let last = ball.last().unwrap();
    assert!((last.0 - 180.0).abs() < 1e-12);
    assert!((last.1 - table_value(&flat, 180.0 - 52.62)).abs() < 1e-9, "{ball:?}");
    assert!(ball.windows(2).all(|w| w[1].0 > w[0].0), "{ball:?}");
}
