//! `cargo bench --bench plans`: how long the planning jobs take, against one analysis of
//! `../shared/data/tiger.nc` measured in the same run (BENCHMARKS.md, "Plans").
//!
//! Every case is a job as the API runs it: the request is checked and resolved against a
//! freshly migrated and seeded database (`kinds::accept`, not timed), then the worker's
//! part is timed (`kinds::run`: the computation, the result, the program and the scene),
//! with the control of a job alone on the service (it claims the other cores while free).
//! The cases:
//! - `tiger`: tiger.nc analysed with the 6 mm square end mill at 0.05 mm in its stock of
//!   tiger.camotics (the yardstick; timed before and after the others, the faster counts);
//! - `case study`: the README's case-study cavity (90 × 70 mm, corners R8, a 12 mm slot,
//!   35 mm deep) with every default (six candidate diameters, sample spacing 0.05 mm);
//! - `readme plan`: the README's plan example (the same cavity, `diameters_mm: [10]`,
//!   sample spacing 0.1 mm);
//! - `slot box`: the README's trochoid example (an 80 × 60 mm box with a 12 mm slot, 10 mm
//!   deep, the 10 mm end mill);
//! - `cavity layer`: trochoids for the case-study cavity in one 10 mm layer, 10 mm end mill;
//! - `stair step`: a slanted floor in four layers, roughed with the 10 mm end mill, its steps
//!   taken off by the R5 ball (`"stair_step": {}`).
//!
//! Arguments: words that pick the cases whose label contains one (the yardstick always
//! runs), `--runs N` to time each case N times and keep the fastest, and `--alone` to
//! leave the yardstick out (for profiling one case; no ratios then).

use dieplan::core::analysis::geometry::SampleGeometry;
use dieplan::core::analysis::DEFAULT_STOCK_MEMORY_BYTES;
use dieplan::service::auth::Caller;
use dieplan::service::jobs::control::JobControl;
use dieplan::service::jobs::kind::Submission;
use dieplan::service::jobs::kinds;
use dieplan::service::jobs::model::JobKind;
use serde_json::{json, Value};
use sha2::{Digest, Sha256};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Instant;

mod fixtures;
use fixtures::{cavity_contour, data};

/// One job to time.
struct Case {
    label: &'static str,
    kind: JobKind,
    input: Value,
}

/// The plan's default sample spacing when the request names none, mm (the 10 mm tool's
/// D/200; the plans of the case study are all judged at it).
const DEFAULT_SAMPLE_SPACING_MM: f64 = 0.05;

fn cases() -> Vec<Case> {
    vec![
        Case {
            label: "case study, all defaults",
            kind: JobKind::Plan,
            input: json!({"contour": cavity_contour(), "z_top": 0, "z_bottom": -35}),
        },
        Case {
            label: "readme plan example (D10, 0.1 mm)",
            kind: JobKind::Plan,
            input: json!({"contour": cavity_contour(), "z_top": 0, "z_bottom": -35, "diameters_mm": [10],
                          "sample_spacing_mm": 0.1}),
        },
        Case { label: "stair step, slanted floor (D10, R5 ball)", kind: JobKind::Plan, input: slanted_floor() },
        Case {
            label: "trochoids, slot box",
            kind: JobKind::Trochoids,
            input: json!({"contour": {"outer": [[0, 0], [80, 0], [80, 24], [120, 24], [120, 36], [80, 36], [80, 60], [0, 60]]},
                          "z_top": 0, "z_bottom": -10, "tool_type": "square", "diameter_mm": 10}),
        },
        Case {
            label: "trochoids, cavity layer",
            kind: JobKind::Trochoids,
            input: json!({"contour": cavity_contour(), "z_top": 0, "z_bottom": -10, "tool_type": "square",
                          "diameter_mm": 10}),
        },
    ]
}

/// A 60 × 40 mm cavity whose floor slopes 1 in 3 from z −5 to −20, in four layers of Ad 5
/// (each the section at its bottom), roughed with the 10 mm tool and its steps taken off by
/// the R5 ball (`tests/api/stair_step.rs`), at the default sample spacing.
fn slanted_floor() -> Value {
    let layer = |x: f64, top: f64, bottom: f64| json!({"contour": {"outer": [[0, 0], [x, 0], [x, 40], [0, 40]]}, "z_top": top, "z_bottom": bottom});
    json!({
        "layers": [layer(60.0, 0.0, -5.0), layer(45.0, -5.0, -10.0), layer(30.0, -10.0, -15.0), layer(15.0, -15.0, -20.0)],
        "diameters_mm": [10], "baseline": false, "stair_step": {}
    })
}

fn yardstick() -> Case {
    Case {
        label: "tiger.nc analysis, D6 at 0.05 mm",
        kind: JobKind::Analysis,
        input: json!({
            "program": {"gcode": data("tiger.nc")}, "tool_type": "square", "diameter_mm": 6,
            "stock": {"box": {"x_min": -2, "y_min": -1, "z_min": -32, "x_max": 92, "y_max": 89, "z_max": 0}},
            "sample_spacing_mm": 0.05
        }),
    }
}

/// A case resolved against the database, ready to run.
struct Prepared {
    label: &'static str,
    kind: JobKind,
    input: String,
    prepared: String,
}

/// The fastest of `runs` runs of the job, s, its result, and a fingerprint of its program
/// (to see at a glance that a speed-up left the program as it was).
fn time(case: &Prepared, runs: usize) -> (f64, Value, String) {
    let mut best = f64::INFINITY;
    let mut result = Value::Null;
    let mut program = None;
    for _ in 0..runs {
        // The control of a job alone on the service: it claims the machine's other cores
        // as the queue's worker lets it.
        let busy_cores = Arc::new(AtomicUsize::new(1));
        let control = JobControl::new(false, Arc::new(AtomicBool::new(false)), None).counted_in(busy_cores);
        let start = Instant::now();
        let out = kinds::run(case.kind, &case.input, &case.prepared, &control, DEFAULT_STOCK_MEMORY_BYTES)
            .unwrap_or_else(|e| panic!("{}: {e}", case.label));
        best = best.min(start.elapsed().as_secs_f64());
        result = out.result;
        program = out.program;
    }
    (best, result, program.map_or_else(|| "no program".to_string(), |p| fingerprint(&p)))
}

/// The system allocator, counting the bytes allocated now and at the peak, so that each
/// case's peak of live heap memory is measured alone (the process's resident peak keeps
/// what earlier cases left to the allocator).
struct Counting;

static LIVE_BYTES: AtomicUsize = AtomicUsize::new(0);
static PEAK_BYTES: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is passed on to the system allocator unchanged; only counts are kept.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc(layout);
        if !p.is_null() {
            let live = LIVE_BYTES.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK_BYTES.fetch_max(live, Ordering::Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout);
        LIVE_BYTES.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = System.realloc(ptr, layout, new_size);
        if !p.is_null() {
            LIVE_BYTES.fetch_sub(layout.size(), Ordering::Relaxed);
            let live = LIVE_BYTES.fetch_add(new_size, Ordering::Relaxed) + new_size;
            PEAK_BYTES.fetch_max(live, Ordering::Relaxed);
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Starts a new peak of live heap memory at what is live now.
fn reset_peak_memory() {
    PEAK_BYTES.store(LIVE_BYTES.load(Ordering::Relaxed), Ordering::Relaxed);
}

/// The peak of live heap memory since the last [`reset_peak_memory`], MB.
fn peak_memory_mb() -> f64 {
    PEAK_BYTES.load(Ordering::Relaxed) as f64 / (1024.0 * 1024.0)
}

/// For a plan: the memory of one candidate's samples as the plan keeps them (the chosen
/// program's feed length at the sample spacing, one `SampleGeometry` each), MB.
fn one_candidates_samples_mb(kind: JobKind, input: &str, result: &Value) -> Option<f64> {
    if kind != JobKind::Plan {
        return None;
    }
    let input: Value = serde_json::from_str(input).ok()?;
    let spacing = input["sample_spacing_mm"].as_f64().unwrap_or(DEFAULT_SAMPLE_SPACING_MM);
    let feed_mm = result["totals"]["feed_length_mm"].as_f64()?;
    let bytes = feed_mm / spacing * std::mem::size_of::<SampleGeometry>() as f64;
    Some(bytes / (1024.0 * 1024.0))
}

/// The program's length and the first 8 bytes of its SHA-256, in hex.
fn fingerprint(program: &str) -> String {
    format!("program {} bytes, {}", program.len(), hex::encode(&Sha256::digest(program.as_bytes())[..8]))
}

/// The key figures of a job's result, to see that speed did not change them.
fn figures(kind: JobKind, r: &Value) -> String {
    match kind {
        JobKind::Plan => {
            let chosen = r["candidates"]
                .as_array()
                .and_then(|c| c.iter().find(|c| c["status"] == "chosen"))
                .map_or("none".to_string(), |c| c["name"].as_str().unwrap_or("?").to_string());
            let fates: Vec<String> = r["candidates"]
                .as_array()
                .map(|c| {
                    c.iter()
                        .map(|c| {
                            format!(
                                "D{} {}{}{}",
                                c["diameter_mm"],
                                c["status"].as_str().unwrap_or("?"),
                                c["cost"].as_f64().map_or(String::new(), |v| format!(" {v:.2}")),
                                c["estimated_cost"].as_f64().map_or(String::new(), |v| format!(" (estimated {v:.2})"))
                            )
                        })
                        .collect()
                })
                .unwrap_or_default();
            let t = &r["totals"];
            let step = &r["stair_step"];
            let step = if step.is_null() {
                String::new()
            } else {
                format!(
                    "; stair step {} levels, removed {:.1} of {:.1} cm³, {:.1} min",
                    step["levels"].as_array().map_or(0, Vec::len),
                    step["removed_volume_mm3"].as_f64().unwrap_or(0.0) / 1000.0,
                    step["step_volume_mm3"].as_f64().unwrap_or(0.0) / 1000.0,
                    step["kinematic_time_min"].as_f64().unwrap_or(0.0)
                )
            };
            format!(
                "chosen {chosen}; {} layers; removed {:.1} cm³; cut {:.1} m; {:.1} min kinematic; cost {:.2}; tuning {} × F*; [{}]",
                r["layers"].as_array().map_or(0, Vec::len),
                t["removed_volume_mm3"].as_f64().unwrap_or(0.0) / 1000.0,
                t["cutting_length_mm"].as_f64().unwrap_or(0.0) / 1000.0,
                t["kinematic_time_min"].as_f64().unwrap_or(0.0),
                t["cost"].as_f64().unwrap_or(0.0),
                r["tuning"]["force_factor"],
                fates.join(", ")
            ) + &step
        }
        JobKind::Trochoids => format!(
            "{} treatments, α max {} → {}, verification passed {}",
            r["treatments"].as_array().map_or(0, Vec::len),
            r["base_max_alpha_deg"],
            r["verification"]["outside_zcut"]["max_alpha_deg"],
            r["verification"]["passed"]
        ),
        _ => format!("{} samples, α max {}", r["summary"]["samples"], r["summary"]["alpha_deg"]["max"]),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| a != "--bench").collect();
    let mut runs = 1;
    let mut alone = false;
    let mut words = Vec::new();
    let mut it = args.into_iter();
    while let Some(a) = it.next() {
        if a == "--runs" {
            runs = it.next().and_then(|n| n.parse().ok()).unwrap_or(1).max(1);
        } else if a == "--alone" {
            alone = true;
        } else {
            words.push(a.to_lowercase());
        }
    }
    let wanted = |label: &str| words.is_empty() || words.iter().any(|w| label.to_lowercase().contains(w.as_str()));

    let dir = tempfile::tempdir().expect("a temporary directory");
    let runtime = tokio::runtime::Runtime::new().expect("a tokio runtime");
    let pool =
        runtime.block_on(dieplan::service::store::open(&dir.path().join("bench.sqlite").into())).expect("database");
    let prepare = |case: Case| -> Prepared {
        let submission =
            Submission { pool: &pool, caller: &Caller::Open, stock_memory_bytes: DEFAULT_STOCK_MEMORY_BYTES };
        let accepted = runtime
            .block_on(kinds::accept(&submission, case.kind, case.input.clone(), ""))
            .unwrap_or_else(|e| panic!("{}: {e:?}", case.label));
        Prepared { label: case.label, kind: case.kind, input: accepted.input, prepared: accepted.prepared }
    };
    let tiger = prepare(yardstick());
    let chosen: Vec<Prepared> = cases().into_iter().filter(|c| wanted(c.label)).map(prepare).collect();

    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let mut timed = Vec::new();
    let mut run_cases = || {
        for case in &chosen {
            reset_peak_memory();
            let (secs, result, program) = time(case, runs);
            println!("{}: {secs:.3} s ({}; {program})", case.label, figures(case.kind, &result));
            let samples = one_candidates_samples_mb(case.kind, &case.input, &result)
                .map_or(String::new(), |mb| format!("; one candidate's samples {mb:.0} MB, {cores} cores"));
            println!("  peak heap memory {:.0} MB{samples}", peak_memory_mb());
            timed.push((case.label, secs));
        }
    };
    if alone {
        run_cases();
        return;
    }
    let (before, result, _) = time(&tiger, runs);
    println!("{}: {before:.3} s ({})", tiger.label, figures(tiger.kind, &result));
    run_cases();
    let (after, _, _) = time(&tiger, runs);
    println!("{} again: {after:.3} s", tiger.label);
    let unit = before.min(after);
    println!("ratios to one tiger.nc analysis ({unit:.3} s, the faster of the two):");
    for (label, secs) in timed {
        println!("  {label}: {:.3} ×", secs / unit);
    }
}
