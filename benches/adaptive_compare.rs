//! `cargo bench --bench adaptive_compare -- DIR`: dieplan's trochoid plan against FreeCAD's
//! Adaptive clearing on the pockets of `benches/adaptive/pockets.json`, both judged by
//! dieplan's own simulator. Run through `benches/adaptive_compare.sh`, which installs FreeCAD
//! when it is missing and writes the Adaptive programs (`DIR/adaptive_<pocket>_so<step-over>.nc`)
//! first.
//!
//! For each pocket it plans the trochoid insertion (the 10 mm end mill, seed 004's conditions,
//! default options), writes its program (`DIR/dieplan_<pocket>.nc`) and reads it back, then
//! judges every program of the pocket the same way: the full stock simulation at 0.05 mm
//! (largest engagement of the horizontal cuts and of the ramps, samples above 40°), the
//! feed length that cuts and the feed length in the air, and the nominal and kinematic
//! times on the seeded OKK VM-4. Last it compares dieplan's kinematic time with that of the
//! Adaptive program of the largest step-over whose horizontal cuts stay at or under 40°, or,
//! when none does, of the one whose largest engagement is lowest.
//!
//! Engagement is counted apart for the ramps and the bottom circle of each approach hole
//! (the slice simulation cannot see a ramp's sloped floor, so that circle looks like a slot)
//! and for dieplan's z-cut division passes (reduced axial depth, told by their comments).
//! `ADAPTIVE_COMPARE_FULL_LOOPS=1` also plans dieplan's loops in full, for reference: their
//! returns and the links at the cutting feed, the pitch at most the grooving Rd.

use dieplan::core::analysis::{analyze_with, AnalysisSpec, StockRegion};
use dieplan::core::conditions::CuttingConditions;
use dieplan::core::geometry::{Loop, Pocket, Vertex};
use dieplan::core::insertion::{plan_insertion, InsertionSpec};
use dieplan::core::kinematics::{machining_time, MachineLimits, TimeOptions};
use dieplan::core::nc::{parse_gcode, write_program, ParseOptions, WriterOptions};
use dieplan::core::progress::NoProgress;
use dieplan::core::tool::{EndMill, ToolType};
use dieplan::core::toolpath::move_length;
use dieplan::core::toolpath::{Motion, Toolpath};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The engagement limit both programs are held to, deg.
const LIMIT_DEG: f64 = 40.0;

/// Sample spacing of the judging simulation, mm (the analysis default for plans).
const SPACING_MM: f64 = 0.05;

/// A move whose height changes by more than this is a ramp or a plunge, mm.
const LEVEL_TOLERANCE_MM: f64 = 1e-6;

/// The seeded OKK VM-4 row.
fn vm4() -> MachineLimits {
    MachineLimits::SEEDED_OKK_VM4
}

fn number(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("pockets.json: {key} must be a number"))
}

struct Case {
    name: String,
    pocket: Pocket,
    z_top: f64,
    z_bottom: f64,
}

struct Setup {
    tool: EndMill,
    conditions: CuttingConditions,
    safe_z_mm: f64,
    cases: Vec<Case>,
}

fn setup(file: &Path) -> Setup {
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let json: Value = serde_json::from_str(&text).expect("pockets.json parses");
    let tool = EndMill {
        tool_type: ToolType::Square,
        diameter_mm: number(&json["tool"], "diameter_mm"),
        flutes: json["tool"]["flutes"].as_u64().expect("flutes") as u32,
        corner_radius_mm: 0.0,
    };
    let c = &json["conditions"];
    let conditions = CuttingConditions {
        spindle_rpm: number(c, "spindle_rpm"),
        fz_mm: number(c, "fz_mm"),
        rd_mm: number(c, "rd_mm"),
        ad_mm: number(c, "ad_mm"),
    };
    let cases = json["pockets"]
        .as_array()
        .expect("pockets")
        .iter()
        .map(|p| {
            let vertices = p["outer"]
                .as_array()
                .expect("outer")
                .iter()
                .map(|v| Vertex::new(v[0].as_f64().unwrap(), v[1].as_f64().unwrap(), v[2].as_f64().unwrap()))
                .collect();
            Case {
                name: p["name"].as_str().expect("name").to_string(),
                pocket: Pocket::new(Loop::new(vertices), vec![]).expect("pocket"),
                z_top: number(p, "z_top"),
                z_bottom: number(p, "z_bottom"),
            }
        })
        .collect();
    Setup { tool, conditions, safe_z_mm: number(&json, "safe_z_mm"), cases }
}

/// What a move is, for the engagement figures.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Rapid,
    /// A move down (a helix or a plunge): the slice simulation cannot see its sloped floor.
    Ramp,
    /// The horizontal moves right after a ramp, up to one turn of it: the bottom of the
    /// approach hole, which the simulation sees as a slot because it missed the ramp's floor.
    Hole,
    Level,
}

/// Each move's kind: after every ramp (a run of feed moves down), the horizontal feed moves
/// whose XY length makes up one turn of its circle (radius: half the ramp's XY extent) are
/// the bottom of the approach hole.
fn kinds(path: &Toolpath) -> Vec<Kind> {
    let mut kinds = Vec::with_capacity(path.moves.len());
    let (mut hole_left, mut ramp_box): (f64, Option<[f64; 4]>) = (0.0, None);
    for m in &path.moves {
        let kind = if matches!(m.motion, Motion::Rapid) {
            Kind::Rapid
        } else if m.end.z < m.start.z - LEVEL_TOLERANCE_MM {
            let b = ramp_box.get_or_insert([m.start.x, m.start.y, m.start.x, m.start.y]);
            for p in [m.start, m.end] {
                *b = [b[0].min(p.x), b[1].min(p.y), b[2].max(p.x), b[3].max(p.y)];
            }
            if let Motion::Arc { center, .. } = m.motion {
                let radius = (m.start.x - center.x).hypot(m.start.y - center.y);
                *b = [
                    b[0].min(center.x - radius),
                    b[1].min(center.y - radius),
                    b[2].max(center.x + radius),
                    b[3].max(center.y + radius),
                ];
            }
            Kind::Ramp
        } else {
            if let Some(b) = ramp_box.take() {
                hole_left = std::f64::consts::TAU * 0.5 * (b[2] - b[0]).max(b[3] - b[1]);
            }
            if (m.end.z - m.start.z).abs() > LEVEL_TOLERANCE_MM {
                Kind::Ramp
            } else if hole_left > LEVEL_TOLERANCE_MM {
                hole_left -= move_length(m);
                Kind::Hole
            } else {
                Kind::Level
            }
        };
        if kind == Kind::Rapid {
            ramp_box = None;
            hole_left = 0.0;
        }
        kinds.push(kind);
    }
    kinds
}

/// The engagement of one kind of sample.
#[derive(Default)]
struct Engagement {
    max_deg: f64,
    over: usize,
    /// The NC line and α of the first sample above the limit.
    first_over: Option<(u32, f64)>,
}

impl Engagement {
    fn add(&mut self, alpha_deg: f64, line: u32) {
        self.max_deg = self.max_deg.max(alpha_deg);
        if alpha_deg > LIMIT_DEG {
            self.over += 1;
            self.first_over = self.first_over.or(Some((line, alpha_deg)));
        }
    }
}

/// What the simulator says of one program.
struct Judged {
    /// Horizontal cuts.
    full_depth: Engagement,
    /// dieplan's z-cut division (passes of a reduced axial depth where the tool does not fit
    /// a trochoid: slots, by design), told by the program's comments.
    shallow: Engagement,
    /// Ramps and the bottoms of the approach holes.
    entries: Engagement,
    cutting_m: f64,
    air_m: f64,
    nominal_min: f64,
    kinematic_min: f64,
    seconds: f64,
}

/// The NC lines (1-based) that belong to a z-cut division part of `text`: from its comment
/// `(LAYER … Z-CUT DIVISION …)` to the next part's.
fn zcut_lines(text: &str) -> Vec<bool> {
    let mut inside = false;
    let mut lines = vec![false];
    for line in text.lines() {
        if line.starts_with("(LAYER") {
            inside = line.contains("Z-CUT DIVISION");
        }
        lines.push(inside);
    }
    lines
}

fn judge(file: &Path, case: &Case, s: &Setup) -> Judged {
    let start = Instant::now();
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let path = parse_gcode(&text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let zcut = zcut_lines(&text);
    let spec = AnalysisSpec {
        tool: s.tool,
        stock: vec![StockRegion::Pocket(case.pocket.clone())],
        open: Vec::new(),
        z_top: case.z_top,
        z_bottom: case.z_bottom,
        force_model: None,
        default_spindle_rpm: Some(s.conditions.spindle_rpm),
        rapid_mm_min: vm4().rapid_mm_min,
        sample_spacing_mm: Some(SPACING_MM),
        cell_mm: None,
        alpha_limit_deg: LIMIT_DEG,
        series_points: 0,
        stock_memory_bytes: dieplan::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    };
    let kinds = kinds(&path);
    let (mut full_depth, mut shallow, mut entries) =
        (Engagement::default(), Engagement::default(), Engagement::default());
    let analysis = analyze_with(&path, &spec, &NoProgress, |r| {
        let alpha = r.contact.alpha_rad.to_degrees();
        match kinds[r.sample.move_index] {
            Kind::Rapid => {}
            Kind::Ramp | Kind::Hole => entries.add(alpha, r.sample.line),
            Kind::Level if zcut.get(r.sample.line as usize).copied().unwrap_or(false) => {
                shallow.add(alpha, r.sample.line)
            }
            Kind::Level => full_depth.add(alpha, r.sample.line),
        }
    })
    .expect("analysis");
    let time = machining_time(&path, &vm4(), &TimeOptions::default()).expect("time");
    Judged {
        full_depth,
        shallow,
        entries,
        cutting_m: analysis.summary.cutting_length_mm / 1e3,
        air_m: analysis.summary.air_cut_length_mm / 1e3,
        nominal_min: time.nominal_min,
        kinematic_min: time.kinematic_min,
        seconds: start.elapsed().as_secs_f64(),
    }
}

fn print_row(label: &str, j: &Judged) {
    println!(
        "  {label:<26} max α {:>5.1}° ({:>5} samples > {LIMIT_DEG}°; z-cut division {:>5.1}°, {:>4} > {LIMIT_DEG}°; entries {:>5.1}°)  \
         cutting {:>5.2} m  air {:>5.2} m  nominal {:>5.2} min  kinematic {:>5.2} min  ({:.1} s)",
        j.full_depth.max_deg,
        j.full_depth.over,
        j.shallow.max_deg,
        j.shallow.over,
        j.entries.max_deg,
        j.cutting_m,
        j.air_m,
        j.nominal_min,
        j.kinematic_min,
        j.seconds
    );
    if let Some((line, alpha)) = j.full_depth.first_over {
        println!("  {:<26} first full-depth sample above {LIMIT_DEG}°: {alpha:.1}° on NC line {line}", "");
    }
}

/// The Adaptive programs of `case` in `dir`, by step-over (percent of the diameter).
fn adaptive_programs(dir: &Path, case: &Case) -> Vec<(f64, PathBuf)> {
    let prefix = format!("adaptive_{}_so", case.name);
    let mut found: Vec<(f64, PathBuf)> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok())
                .filter_map(|e| {
                    let name = e.file_name().to_string_lossy().to_string();
                    let stepover = name.strip_prefix(&prefix)?.strip_suffix(".nc")?.parse::<f64>().ok()?;
                    Some((stepover, e.path()))
                })
                .collect()
        })
        .unwrap_or_default();
    found.sort_by(|a, b| b.0.total_cmp(&a.0));
    found
}

/// Plans `case`, writes the program to `dir` (named with `suffix`), reads it back and judges it.
fn plan_and_judge(dir: &Path, case: &Case, s: &Setup, spec: &InsertionSpec, suffix: &str) -> Judged {
    let start = Instant::now();
    let plan = plan_insertion(&case.pocket, spec, None, &NoProgress).expect("plan");
    let planned_s = start.elapsed().as_secs_f64();
    let program = write_program(&plan.toolpath, &WriterOptions::default());
    let file = dir.join(format!("dieplan_{}{suffix}.nc", case.name));
    std::fs::write(&file, &program).expect("write program");
    let judged = judge(&file, case, s);
    println!(
        "  dieplan{suffix}: planned in {planned_s:.1} s, {} treatments, verification {} (max α outside z-cut {:.1}°, {} overloaded)",
        plan.treatments.len(),
        if plan.verification.passed { "passed" } else { "failed" },
        plan.verification.outside_zcut.max_alpha_deg,
        plan.verification.outside_zcut.overloaded
    );
    print_row(&format!("dieplan{suffix}"), &judged);
    judged
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    let dir = PathBuf::from(args.first().cloned().unwrap_or_else(|| "target/adaptive".to_string()));
    let filter = args.get(1).cloned();
    std::fs::create_dir_all(&dir).expect("output directory");
    let s = setup(&Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/adaptive/pockets.json"));
    for case in s.cases.iter().filter(|c| filter.as_ref().is_none_or(|f| c.name.contains(f.as_str()))) {
        println!(
            "{} (tool D{}, S{} fz{}, programs in {}):",
            case.name,
            s.tool.diameter_mm,
            s.conditions.spindle_rpm,
            s.conditions.fz_mm,
            dir.display()
        );
        let spec = InsertionSpec {
            safe_z_mm: case.z_top + s.safe_z_mm,
            sample_spacing_mm: Some(SPACING_MM),
            ..InsertionSpec::new(s.tool, s.conditions, s.conditions, case.z_top, case.z_bottom)
        };
        let ours = plan_and_judge(&dir, case, &s, &spec, "");
        if std::env::var_os("ADAPTIVE_COMPARE_FULL_LOOPS").is_some() {
            // Full loops, for reference: the return halves and the links at the cutting feed,
            // the pitch at most the grooving Rd.
            let feed =
                dieplan::core::conditions::feed_mm_min(s.conditions.fz_mm, s.tool.flutes, s.conditions.spindle_rpm);
            let full =
                InsertionSpec { air_feed_mm_min: Some(feed), pitch_mm: Some(s.conditions.rd_mm), ..spec.clone() };
            plan_and_judge(&dir, case, &s, &full, "_full_loops");
        }
        // The Adaptive program to compare with: the largest step-over whose horizontal cuts
        // stay at or under the limit, else the one whose largest engagement is lowest.
        let mut best: Option<(f64, Judged)> = None;
        for (stepover, file) in adaptive_programs(&dir, case) {
            let j = judge(&file, case, &s);
            print_row(&format!("adaptive, step-over {stepover}%"), &j);
            println!(
                "  {:<26} dieplan / this: kinematic {:.3}, nominal {:.3}",
                "",
                ours.kinematic_min / j.kinematic_min,
                ours.nominal_min / j.nominal_min
            );
            let better = match &best {
                None => true,
                Some((_, b)) => b.full_depth.max_deg > LIMIT_DEG && j.full_depth.max_deg < b.full_depth.max_deg,
            };
            if better {
                best = Some((stepover, j));
            }
        }
        match best {
            Some((stepover, a)) => println!(
                "  → against adaptive at step-over {stepover}% ({}, max α {:.1}°): dieplan's kinematic time {:.3} ×, nominal {:.3} ×, air {:.2} m vs {:.2} m",
                if a.full_depth.max_deg <= LIMIT_DEG { "the largest at or under the limit" } else { "none stays under the limit: the lowest maximum" },
                a.full_depth.max_deg,
                ours.kinematic_min / a.kinematic_min,
                ours.nominal_min / a.nominal_min,
                ours.air_m,
                a.air_m
            ),
            None => println!("  → no Adaptive program of this pocket in {}: run benches/adaptive_compare.sh", dir.display()),
        }
    }
}
