//! `POST /v1/trochoids`: trochoids and z-cut division inserted where a pocket's path
//! overloads the tool, checked by the full simulation, written as G-code our parser reads.

use crate::common::{assert_problem, many_sided, TestApp};
use dieplan::core::nc::{parse_gcode, toolpath_from_json, ParseOptions};
use dieplan::core::toolpath::move_length;
use dieplan::core::toolpath::Motion;
use serde_json::{json, Value};

fn shared(name: &str) -> String {
    let path = format!("{}/../shared/data/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// An 80 × 60 mm box cavity with a 12 mm wide, 40 mm long slot out of its right wall.
fn box_with_slot() -> Value {
    json!({"outer": [[0, 0], [80, 0], [80, 24], [120, 24], [120, 36], [80, 36], [80, 60], [0, 60]]})
}

/// Most a plan may take in these tests, s: a few seconds alone, much longer while the rest
/// of the suite runs on two cores.
const PLAN_DEADLINE_S: u64 = 300;

async fn finished(app: &TestApp, body: Value) -> Value {
    let a = app.post("/v1/trochoids", body).await;
    assert!(a.status == 201 || a.status == 202, "{}", a.text);
    let job = app.wait_for_job_within(a.body["id"].as_str().unwrap(), PLAN_DEADLINE_S).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    job
}

/// The checks every plan must pass, and a program our parser reads with the same moves as
/// the JSON path.
async fn assert_complete_and_gouge_free(app: &TestApp, job: &Value) {
    let r = &job["result"];
    let v = &r["verification"];
    assert_eq!(v["passed"], true, "{v}");
    assert_eq!(v["outside_zcut"]["overloaded"], 0, "{v}");
    assert!(v["outside_zcut"]["max_alpha_deg"].as_f64().unwrap() <= 40.0, "{v}");
    assert_eq!(v["gouges"], 0, "{v}");
    assert!(v["uncleared_area_mm2"].as_f64().unwrap() <= 0.0, "{v}");
    // The treatments share out the pocket's area.
    let total: f64 = r["treatments"].as_array().unwrap().iter().map(|t| t["area_mm2"].as_f64().unwrap()).sum();
    let pocket = r["pocket_area_mm2"].as_f64().unwrap();
    assert!(total > 0.97 * pocket && total <= pocket + 1e-6, "{total} of {pocket}");
    let a = app.get(&format!("/v1/jobs/{}/program", job["id"].as_str().unwrap())).await;
    assert_eq!(a.status, 200, "{}", a.text);
    let gcode = parse_gcode(&a.text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e:?}"));
    let json = toolpath_from_json(&serde_json::from_value(r["path"].clone()).unwrap()).unwrap();
    assert_eq!(r["program"]["moves_out"].as_u64().unwrap() as usize, json.moves.len());
    // The same path: Fanuc has no turns word, so the writer spells a helix of several turns
    // as several blocks; the cutting lengths and the end agree (the G-code's first rapid
    // starts from the origin).
    let length = |p: &dieplan::core::toolpath::Toolpath| -> f64 {
        p.moves.iter().filter(|m| !matches!(m.motion, Motion::Rapid)).map(move_length).sum()
    };
    assert!((length(&gcode) - length(&json)).abs() < 1e-3 * length(&json), "{} vs {}", length(&gcode), length(&json));
    let (a, b) = (gcode.moves.last().unwrap().end, json.moves.last().unwrap().end);
    assert!((a.x - b.x).abs() < 1e-3 && (a.y - b.y).abs() < 1e-3 && (a.z - b.z).abs() < 1e-3);
    // Whatever still spikes above the limit (where the wall pass crosses a z-cut region) is
    // listed with the lines of the served program, each a motion block there.
    let overloads = v["overloads"].as_array().unwrap();
    assert_eq!(overloads.is_empty(), v["crossing_zcut"]["overloaded"] == 0, "{v}");
    for o in overloads {
        assert_eq!(o["in_zcut_region"], true, "{o}");
        let lines = o["program_lines"].as_array().unwrap_or_else(|| panic!("{o}"));
        let (first, last) = (lines[0].as_u64().unwrap() as u32, lines[1].as_u64().unwrap() as u32);
        assert!(first <= last, "{o}");
        for line in [first, last] {
            assert!(gcode.moves.iter().any(|m| m.line == line), "{o}: line {line} is no motion block");
        }
        assert!(o["max_alpha_deg"].as_f64().unwrap() > 40.0, "{o}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn border_dxf_gets_a_complete_gouge_free_program_with_trochoids_where_the_path_overloaded() {
    let app = TestApp::start().await;
    let job = finished(
        &app,
        json!({"dxf": shared("border.dxf"), "z_top": 0, "z_bottom": -10, "tool_type": "square", "diameter_mm": 10}),
    )
    .await;
    let r = &job["result"];
    assert_eq!(r["base_path"], "generated");
    assert!(r["base_max_alpha_deg"].as_f64().unwrap() > 170.0, "the innermost loop slots: {r}");
    assert!(r["roughing"]["source"].as_str().unwrap().contains("rough_side_cutting"), "{}", r["roughing"]);
    assert!(r["axis"]["branches"].as_array().unwrap().iter().all(|b| !b["classes"].as_array().unwrap().is_empty()));
    let kinds: Vec<&str> = r["treatments"].as_array().unwrap().iter().map(|t| t["kind"].as_str().unwrap()).collect();
    assert!(kinds.contains(&"trochoid") && kinds.contains(&"kept"), "{kinds:?}");
    assert!(r["trimmed_mm"].as_f64().unwrap() > 0.0);
    assert_complete_and_gouge_free(&app, &job).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_box_cavity_with_a_narrow_slot_gets_trochoids_along_the_slot() {
    let app = TestApp::start().await;
    let job = finished(
        &app,
        json!({"contour": box_with_slot(), "z_top": 0, "z_bottom": -10, "tool_type": "square", "diameter_mm": 10}),
    )
    .await;
    let r = &job["result"];
    // The slot's axis runs along y = 30 from the box into the slot: a trochoid of class B
    // loops (ρ = 6 − 5 − gap) reaches x ≥ 110.
    let slot = r["treatments"].as_array().unwrap().iter().find(|t| {
        t["kind"] == "trochoid" && t["loop_radius_min_mm"].as_f64().unwrap() < 1.0 && t["loops"].as_u64().unwrap() > 100
    });
    assert!(slot.is_some(), "{}", r["treatments"]);
    assert_complete_and_gouge_free(&app, &job).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_given_slotting_path_gets_trochoids_along_its_slot() {
    let app = TestApp::start().await;
    // A 24 × 80 mm slot cut by one pass down its middle: full slotting.
    let gcode = "G21 G90 G17\nS4800 M3\nG0 X12 Y12 Z5\nG1 Z-5 F500\nG1 Y68 F2880\nG0 Z5\nM30\n";
    let job = finished(
        &app,
        json!({"contour": {"outer": [[0, 0], [24, 0], [24, 80], [0, 80]]}, "z_top": 0, "z_bottom": -5,
               "program": {"gcode": gcode}, "tool_type": "square", "diameter_mm": 10}),
    )
    .await;
    let r = &job["result"];
    assert_eq!(r["base_path"], "given");
    assert!(r["base_max_alpha_deg"].as_f64().unwrap() > 170.0, "{r}");
    let v = &r["verification"];
    assert_eq!(v["outside_zcut"]["overloaded"], 0, "{v}");
    assert_eq!(v["gouges"], 0, "{v}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_trochoid_requests_are_refused_naming_the_field() {
    let app = TestApp::start().await;
    let base =
        json!({"contour": box_with_slot(), "z_top": 0, "z_bottom": -10, "tool_type": "square", "diameter_mm": 10});
    let with = |k: &str, v: Value| {
        let mut b = base.clone();
        b[k] = v;
        b
    };
    let cases = [
        (with("alpha_limit_deg", json!(200)), "alpha_limit_deg"),
        (with("class_a_ratio", json!(5)), "class_a_ratio"),
        (with("z_bottom", json!(3)), "z_bottom"),
        (with("dxf", json!("0\nEOF\n")), "contour"),
        (with("contour", json!({"outer": [[0, 0], [10, 10], [10, 0], [0, 10]]})), "contour.outer"),
        (with("contour", json!({"outer": [[0, 0], [8, 0], [8, 8], [0, 8]]})), "tool_radius_mm"),
        (with("contour", json!({"outer": many_sided(10_001)})), "contour"),
        (with("roughing", json!({"spindle_rpm": 4800, "fz_mm": 0.1, "rd_mm": -1, "ad_mm": 10})), "roughing.rd_mm"),
        (with("diameter_mm", json!(-3)), "diameter_mm"),
        (with("loop_radius_mm", json!(1)), "loop_radius_mm"),
        // 3 m × 3 m at 0.05 mm is far more than one analysis may take.
        (with("contour", json!({"outer": [[0, 0], [3000, 0], [3000, 3000], [0, 3000]]})), "sample_spacing_mm"),
        // Steps so small the plan would never end.
        (with("pitch_mm", json!(1e-9)), "pitch_mm"),
        (with("grooving", json!({"spindle_rpm": 4800, "fz_mm": 0.1, "rd_mm": 1e-9, "ad_mm": 10})), "grooving.rd_mm"),
        (with("zcut_ad_mm", json!(1e-9)), "zcut_ad_mm"),
        (with("ramp_pitch_mm", json!(1e-9)), "ramp_pitch_mm"),
        // Beyond the machine (20 000 min⁻¹, 15 000 mm/min).
        (
            with("roughing", json!({"spindle_rpm": 1e12, "fz_mm": 0.1, "rd_mm": 0.5, "ad_mm": 5})),
            "roughing.spindle_rpm",
        ),
        (with("grooving", json!({"spindle_rpm": 9600, "fz_mm": 1000, "rd_mm": 0.5, "ad_mm": 5})), "grooving.fz_mm"),
        // Numbers no control reads.
        (with("output", json!({"tool_number": 4294967295u32})), "output.tool_number"),
        (with("output", json!({"line_numbers": {"start": 4294967295u32, "step": 10}})), "output.line_numbers.start"),
        (with("output", json!({"line_numbers": {"step": 100000}})), "output.line_numbers.step"),
    ];
    for (body, field) in cases {
        let a = app.post("/v1/trochoids", body).await;
        assert_eq!(a.status, 422, "{field}: {}", a.text);
        let fields: Vec<&str> =
            a.body["errors"].as_array().unwrap().iter().map(|e| e["field"].as_str().unwrap()).collect();
        assert!(fields.iter().any(|f| f.starts_with(field)), "{field}: {}", a.text);
    }
    // A layer too thin to cut, named by the request's field.
    let thin = app.post("/v1/trochoids", with("z_bottom", json!(-1e-9))).await;
    assert_problem(&thin, 422, Some("z_bottom"));
    assert!(thin.text.contains("thinner"), "{}", thin.text);
    let ball = app.post("/v1/trochoids", with("tool_type", json!("ball"))).await;
    assert_problem(&ball, 422, None);
    let jobs = app.get("/v1/jobs").await;
    assert!(jobs.text.contains("[]") || !jobs.text.contains("trochoids"), "no job was created: {}", jobs.text);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_figures_before_and_after_give_air_cut_tool_use_and_the_cost_of_seed_002_eq_4() {
    let app = TestApp::start().await;
    let job = finished(
        &app,
        json!({"contour": box_with_slot(), "z_top": 0, "z_bottom": -10, "tool_type": "square", "diameter_mm": 10}),
    )
    .await;
    let f = &job["result"]["figures"];
    let rates = app.get(&format!("/v1/cost-rates/{}", f["cost_rates"]["id"])).await.body;
    let tool = app.get(&format!("/v1/tools/{}", job["result"]["tool"]["id"])).await.body;
    let price = tool["price"].as_f64().unwrap_or_else(|| rates["default_tool_price"].as_f64().unwrap());
    for side in ["before", "after"] {
        let s = &f[side];
        let (consumption, air) = (s["consumption"].as_f64().unwrap(), s["air_cut_length_mm"].as_f64().unwrap());
        assert!(consumption > 0.0 && air >= 0.0 && air < s["feed_length_mm"].as_f64().unwrap(), "{side}: {s}");
        // C = c_m · T_m + c_t · L_t / L_f, with the kinematic time.
        let machine =
            rates["machine_rate_per_hour"].as_f64().unwrap() / 60.0 * s["kinematic_time_min"].as_f64().unwrap();
        let expected = machine + price * consumption;
        let total = s["cost"]["total"].as_f64().unwrap();
        assert!((total - expected).abs() < 1e-6 * expected, "{side}: {total} vs {expected}");
        assert_eq!(s["cost"]["currency"], rates["currency"]);
    }
    // The slot's trochoids cut less of the tool's life per mm than the full-width slotting.
    let per_mm = |s: &Value| s["consumption"].as_f64().unwrap() / s["feed_length_mm"].as_f64().unwrap();
    assert!(per_mm(&f["after"]) < per_mm(&f["before"]), "{f}");
    // The drawn paths name the lines of the programs served: every line of a cut is a
    // motion block there.
    let id = job["id"].as_str().unwrap();
    for (path, part) in [("planned", "main"), ("base", "base")] {
        let program = app.get(&format!("/v1/jobs/{id}/program?part={part}")).await.text;
        let text: Vec<&str> = program.lines().collect();
        let trace = app.get(&format!("/v1/jobs/{id}/trace?path={path}")).await.body;
        let cuts = trace["runs"].as_array().unwrap().iter().filter(|r| r["rapid"] == false);
        for line in cuts.flat_map(|r| r["lines"].as_array().unwrap().iter().skip(1)).map(|l| l.as_u64().unwrap()) {
            let block = text.get(line as usize - 1).unwrap_or_else(|| panic!("{path}: no line {line}"));
            assert!(
                block.contains('X') || block.contains('Y') || block.contains('Z'),
                "{path}: line {line} is {block:?}"
            );
        }
    }
    app.stop().await;
}
