//! The real programs of `shared/data` on the seeded OKK VM-4 (the figures: `benches/kinematics.rs`).

use super::tests::vm4;
use super::*;
use crate::core::nc::{parse_gcode, ParseOptions};

fn data(name: &str) -> Toolpath {
    let path = format!("{}/../shared/data/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    parse_gcode(&text, &ParseOptions::default()).expect("parses")
}

fn check(name: &str) -> MachiningTime {
    let t = machining_time(&data(name), &vm4(), &TimeOptions::default()).unwrap();
    println!(
        "{name}: nominal {:.3} min, kinematic {:.3} min, ratio {:.4}",
        t.nominal_min, t.kinematic_min, t.kinematic_ratio
    );
    assert!(t.kinematic_min > t.nominal_min, "{t:?}");
    let b = &t.breakdown;
    let parts = b.feed_clamp_min + b.arc_limit_min + b.acceleration_min + b.jerk_min;
    assert!((t.nominal_min + parts - t.kinematic_min).abs() < 1e-9 * t.kinematic_min);
    t
}

#[test]
fn tiger_takes_longer_than_nominal_mostly_in_its_short_rapids() {
    let t = check("tiger.nc");
    // G1 at F150/F300: its 90° corners allow 8 mm/s, above the feed; its 2241 rapids, 31 mm
    // long on average, never reach 333 mm/s and each ends in an exact stop.
    assert!(t.feed_kinematic_min < t.feed_nominal_min * 1.01);
    assert!(t.rapid_kinematic_min > 2.0 * t.rapid_nominal_min);
}

#[test]
fn trochoidal_takes_longer_than_nominal() {
    let t = check("trochoidal.ngc");
    assert!(t.kinematic_ratio > 1.0 && t.kinematic_ratio < 1.5);
}
