//! `cargo bench --bench kept_stock`: how large a kept stock is and how long encoding and
//! decoding it take, as ratios to the analysis that kept it, measured in the same run
//! (BENCHMARKS.md, "Kept stocks"; issue 32 item 3).
//!
//! Every case is an analysis job as the API runs it: the request is checked and resolved
//! against a freshly migrated and seeded database (`kinds::accept`, not timed), then the
//! worker's part is timed (`kinds::run`: the simulation, the result, the scene, the kept
//! stock with its footprint, and its encoding). The stock it kept is then decoded and
//! encoded again on its own, `--runs N` times each (default 3), the fastest counting.
//! The cases:
//! - `tiger`: `../shared/data/tiger.nc` analysed with the 6 mm square end mill at 0.05 mm in
//!   its stock of tiger.camotics (a box);
//! - `case study`: the README's case-study cavity (90 × 70 mm, corners R8, a 12 mm slot,
//!   35 mm deep) as a pocket stock, analysed with the 10 mm end mill along the program the
//!   README's plan example writes for it (planned first, not timed).

use dieplan::core::analysis::DEFAULT_STOCK_MEMORY_BYTES;
use dieplan::core::progress::NoProgress;
use dieplan::service::auth::Caller;
use dieplan::service::jobs::kept_stock::{decode, encode};
use dieplan::service::jobs::kind::Submission;
use dieplan::service::jobs::kinds;
use dieplan::service::jobs::model::JobKind;
use serde_json::{json, Value};
use std::time::Instant;

mod fixtures;
use fixtures::{cavity_contour, data};

/// The fastest of `runs` runs of `work`, s, and its last answer.
fn fastest<T>(runs: usize, mut work: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..runs {
        let start = Instant::now();
        out = Some(work());
        best = best.min(start.elapsed().as_secs_f64());
    }
    (best, out.expect("at least one run"))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| a != "--bench").collect();
    let runs = args
        .iter()
        .position(|a| a == "--runs")
        .and_then(|i| args.get(i + 1))
        .and_then(|n| n.parse().ok())
        .unwrap_or(3usize)
        .max(1);
    let dir = tempfile::tempdir().expect("a temporary directory");
    let runtime = tokio::runtime::Runtime::new().expect("a tokio runtime");
    let pool =
        runtime.block_on(dieplan::service::store::open(&dir.path().join("bench.sqlite").into())).expect("database");
    let accept = |kind: JobKind, input: Value| {
        let submission =
            Submission { pool: &pool, caller: &Caller::Open, stock_memory_bytes: DEFAULT_STOCK_MEMORY_BYTES };
        runtime.block_on(kinds::accept(&submission, kind, input, "")).unwrap_or_else(|e| panic!("{kind:?}: {e:?}"))
    };
    // The case study's program: the README's plan example, planned once (not timed).
    let plan = accept(
        JobKind::Plan,
        json!({"contour": cavity_contour(), "z_top": 0, "z_bottom": -35, "diameters_mm": [10], "sample_spacing_mm": 0.1}),
    );
    let planned =
        kinds::run(JobKind::Plan, &plan.input, &plan.prepared, &NoProgress, DEFAULT_STOCK_MEMORY_BYTES).expect("plans");
    let program = planned.program.expect("a plan writes a program");
    let cases = [
        (
            "tiger.nc, D6 at 0.05 mm, box",
            json!({"program": {"gcode": data("tiger.nc")}, "tool_type": "square", "diameter_mm": 6,
                   "stock": {"box": {"x_min": -2, "y_min": -1, "z_min": -32, "x_max": 92, "y_max": 89, "z_max": 0}},
                   "sample_spacing_mm": 0.05}),
        ),
        (
            "case study, D10 plan program, pocket",
            json!({"program": {"gcode": program}, "tool_type": "square", "diameter_mm": 10,
                   "stock": {"contour": cavity_contour(), "z_top": 0, "z_bottom": -35}}),
        ),
    ];
    for (label, input) in cases {
        let job = accept(JobKind::Analysis, input);
        let (analysis_s, out) = fastest(runs, || {
            kinds::run(JobKind::Analysis, &job.input, &job.prepared, &NoProgress, DEFAULT_STOCK_MEMORY_BYTES)
                .expect("analyses")
        });
        let stored = out.stock.expect("an analysis keeps its stock");
        let (decode_s, kept) =
            fastest(runs, || decode(stored.format, &stored.body, DEFAULT_STOCK_MEMORY_BYTES).expect("decodes"));
        let (encode_s, again) = fastest(runs, || encode(&kept));
        assert_eq!(again.body.len(), stored.body.len(), "{label}: encoding again gives the same size");
        let s = &out.result["summary"];
        let g = kept.grid;
        println!(
            "{label}: analysis {analysis_s:.2} s ({} samples; {} slices, {} rasters and the footprint of {} × {} cells of {:.3} mm)",
            s["samples"],
            kept.slices.len(),
            kept.rasters.len(),
            g.nx,
            g.ny,
            g.cell_mm
        );
        println!(
            "  stock {:.1} MB raw, {:.0} kB stored ({:.0} ×); encode {:.3} s ({:.3} × the analysis), decode {:.3} s ({:.3} ×)",
            stored.raw_bytes as f64 / 1e6,
            stored.body.len() as f64 / 1e3,
            stored.raw_bytes as f64 / stored.body.len() as f64,
            encode_s,
            encode_s / analysis_s,
            decode_s,
            decode_s / analysis_s
        );
    }
}
