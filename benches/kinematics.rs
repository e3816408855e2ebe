//! `cargo bench --bench kinematics`: nominal and kinematic machining time (MODEL.md §10) of the
//! real programs of ../shared/data on the seeded OKK VM-4. Prints its figures.

use dieplan::core::kinematics::{machining_time, MachineLimits, MachiningTime, TimeOptions};
use dieplan::core::nc::{parse_gcode, ParseOptions};
use dieplan::core::toolpath::Toolpath;
use std::time::Instant;

/// Runs per figure; the fastest is reported.
const RUNS: usize = 20;

fn data(name: &str) -> Toolpath {
    let path = format!("{}/../shared/data/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    parse_gcode(&text, &ParseOptions::default()).expect("parses")
}

/// The seeded OKK VM-4 row.
fn vm4() -> MachineLimits {
    MachineLimits::SEEDED_OKK_VM4
}

fn fastest(path: &Toolpath, options: &TimeOptions) -> (MachiningTime, f64) {
    let mut best = f64::INFINITY;
    let mut result = None;
    for _ in 0..RUNS {
        let start = Instant::now();
        let t = machining_time(path, &vm4(), options).expect("times");
        best = best.min(start.elapsed().as_secs_f64() * 1e3);
        result = Some(t);
    }
    (result.expect("at least one run"), best)
}

fn report(name: &str, label: &str, path: &Toolpath, options: &TimeOptions) {
    let (t, ms) = fastest(path, options);
    let b = &t.breakdown;
    println!(
        "{name:<15} {label:<22} moves {:>6}  nominal {:>9.3} min  kinematic {:>9.3} min  ratio {:.4}  \
         ({:.2} ms)",
        path.moves.len(),
        t.nominal_min,
        t.kinematic_min,
        t.kinematic_ratio,
        ms
    );
    println!(
        "{:<38} feed {:.3} -> {:.3} min, rapid {:.3} -> {:.3} min; lost: accel {:.3}, jerk {:.3}, arcs {:.3}, \
         clamp {:.3} min; slowed corners {}, exact stops {}",
        "",
        t.feed_nominal_min,
        t.feed_kinematic_min,
        t.rapid_nominal_min,
        t.rapid_kinematic_min,
        b.acceleration_min,
        b.jerk_min,
        b.arc_limit_min,
        b.feed_clamp_min,
        b.slowed_corners,
        b.exact_stops
    );
}

fn main() {
    // `cargo bench --bench kinematics -- tiger` times only the files whose name contains "tiger".
    let filter: Option<String> = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    for name in
        ["tiger.nc", "trochoidal.ngc"].into_iter().filter(|n| filter.as_ref().is_none_or(|f| n.contains(f.as_str())))
    {
        let path = data(name);
        report(name, "default (200 blocks)", &path, &TimeOptions::default());
        report(
            name,
            "whole-program look-ahead",
            &path,
            &TimeOptions { look_ahead_blocks: None, ..TimeOptions::default() },
        );
        report(name, "with per-move times", &path, &TimeOptions { per_move: true, ..TimeOptions::default() });
    }
}
