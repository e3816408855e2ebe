//! `POST /v1/analysis`: a tool path in a layer of stock.

use crate::common::{assert_problem, close, TestApp};
use serde_json::json;

fn shared(name: &str) -> String {
    let path = format!("{}/../shared/data/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A straight side cut of the 10 mm tool at its standard conditions: Rd 0.5, Ad 10.
const STANDARD_CUT: &str = "%\n(standard straight cut)\nG21 G90 G17\nT1 M6\nS9600 M3\nG0 X-10 Y4.5 Z5\nG1 Z-10 F1000\nG1 X110 F5760\nG0 Z5\nM30\n%\n";

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_standard_straight_cut_engages_25_8_degrees_with_the_model_force_beta0() {
    let app = TestApp::start().await;
    let body = json!({
        "program": {"gcode": STANDARD_CUT},
        "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": -40, "z_min": -10, "x_max": 100, "y_max": 0, "z_max": 0}},
        "series_points": 100
    });
    let a = app.post_wait("/v1/analysis", body).await;
    assert_eq!(a.status, 201, "{}", a.text);
    assert_eq!(a.body["status"], "succeeded", "{}", a.text);
    let r = &a.body["result"];
    let s = &r["summary"];
    assert!(close(&s["alpha_deg"]["max"], 25.84, 0.5), "{s}");
    assert!(close(&s["t_m_um"]["max"], 43.6, 0.5), "{s}");
    assert!(close(&s["force_n"]["max"], 269.1, 1.0), "{s}");
    assert!(close(&s["cutting_length_mm"], 100.0 + 5.0, 5.0), "{s}");
    assert_eq!(r["critical_regions"].as_array().unwrap().len(), 0);
    let series = &r["series"];
    let alpha = series["alpha_deg"].as_array().unwrap();
    let peak =
        (0..alpha.len()).max_by(|&i, &j| alpha[i].as_f64().unwrap().total_cmp(&alpha[j].as_f64().unwrap())).unwrap();
    assert_eq!(series["line"][peak], 8, "the cut is line 8 of the program");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_full_slot_is_reported_as_a_critical_region_with_its_nc_lines() {
    let app = TestApp::start().await;
    let gcode = "G21 G90\nS9600 M3\nG0 X-10 Y20 Z5\nG1 Z-10 F1000\nG1 X50 F2000\nG1 Y-5\nM30\n";
    let body = json!({
        "program": {"gcode": gcode}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -10, "x_max": 100, "y_max": 40, "z_max": 0}}
    });
    let a = app.post_wait("/v1/analysis", body).await;
    let regions = a.body["result"]["critical_regions"].as_array().unwrap().clone();
    assert!(!regions.is_empty(), "{}", a.text);
    assert_eq!(regions[0]["kind"], "full_slotting");
    assert_eq!(regions[0]["start"]["line"], 5);
    assert!(close(&regions[0]["max_alpha_deg"], 180.0, 0.5));
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn both_real_programs_analyse_through_the_api() {
    let app = TestApp::start().await;
    let tiger = json!({
        "program": {"gcode": shared("tiger.nc")},
        "tool_id": app.tool_id("square", 6.0).await,
        "stock": {"box": {"x_min": -2, "y_min": -1, "z_min": -32, "x_max": 92, "y_max": 89, "z_max": 0}},
        "sample_spacing_mm": 0.1
    });
    let a = app.send(reqwest::Method::POST, "/v1/analysis", Some(tiger), &[("prefer", "wait=50")]).await;
    assert_eq!(a.body["status"], "succeeded", "{}", &a.text[..a.text.len().min(2000)]);
    assert!(a.body["result"]["summary"]["cutting_length_mm"].as_f64().unwrap() > 1000.0);

    let trochoidal = json!({
        "program": {"gcode": shared("trochoidal.ngc")},
        "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": -60, "y_min": -10, "z_min": -10, "x_max": 40, "y_max": 90, "z_max": 0}}
    });
    let a = app.send(reqwest::Method::POST, "/v1/analysis", Some(trochoidal), &[("prefer", "wait=50")]).await;
    assert_eq!(a.body["status"], "succeeded", "{}", &a.text[..a.text.len().min(2000)]);
    assert!(a.body["result"]["summary"]["samples"].as_u64().unwrap() > 10_000);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn curvature_radius_centre_and_turn_come_with_every_series_point() {
    let app = TestApp::start().await;
    // A counter-clockwise circle of radius 20 about (50, 50), as CAM writes it: minute G1 segments.
    let mut gcode = String::from("G21 G90\nS9600 M3\nG0 X70 Y50 Z5\nG1 Z-5 F500\n");
    for i in 1..=720 {
        let a = i as f64 / 720.0 * std::f64::consts::TAU;
        gcode.push_str(&format!("G1 X{:.4} Y{:.4} F2000\n", 50.0 + 20.0 * a.cos(), 50.0 + 20.0 * a.sin()));
    }
    let body = json!({
        "program": {"gcode": gcode}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -10, "x_max": 100, "y_max": 100, "z_max": 0}},
        "series_points": 40
    });
    let a = app.post_wait("/v1/analysis", body).await;
    let series = &a.body["result"]["series"];
    let n = series["s_mm"].as_array().unwrap().len();
    let mut checked = 0;
    for i in 0..n {
        if series["line"][i].as_u64().unwrap() < 100 || series["line"][i].as_u64().unwrap() > 700 {
            continue;
        }
        assert!(close(&series["curvature_radius_mm"][i], 20.0, 0.2), "{}", series["curvature_radius_mm"][i]);
        assert!(
            close(&series["curvature_center"][i][0], 50.0, 0.2) && close(&series["curvature_center"][i][1], 50.0, 0.2)
        );
        assert_eq!(series["turn"][i], 1);
        checked += 1;
    }
    assert!(checked > 10, "{checked}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_dxf_pocket_is_a_stock() {
    let app = TestApp::start().await;
    let body = json!({
        "program": {"gcode": "G21 G90\nS9600 M3\nG0 X0 Y0 Z5\nG1 Z-2 F500\nG1 X10 F1000\nM30\n"},
        "tool_type": "square", "diameter_mm": 6,
        "stock": {"dxf": shared("border.dxf"), "z_top": 0, "z_bottom": -5}
    });
    let a = app.post_wait("/v1/analysis", body).await;
    assert_eq!(a.status, 201, "{}", a.text);
    assert_eq!(a.body["status"], "succeeded", "{}", a.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_nc_and_bad_contours_are_refused_naming_the_line_or_vertex() {
    let app = TestApp::start().await;
    let stock = json!({"box": {"x_min": 0, "y_min": 0, "z_min": -10, "x_max": 100, "y_max": 40, "z_max": 0}});
    let bad_nc = json!({"program": {"gcode": "G21\nG1 X1 F100\nG1 X2 Q7\n"}, "tool_type": "square", "diameter_mm": 10, "stock": stock});
    let a = app.post("/v1/analysis", bad_nc).await;
    assert_problem(&a, 422, Some("program.gcode"));
    assert!(a.body["detail"].as_str().unwrap().contains("line 3"), "{}", a.text);

    let bowtie = json!({"outer": [[0, 0], [10, 10], [10, 0], [0, 10]]});
    let bad_contour = json!({"program": {"gcode": "G1 X1 F100\n"}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"contour": bowtie, "z_top": 0, "z_bottom": -5}});
    let a = app.post("/v1/analysis", bad_contour).await;
    assert_eq!(a.status, 422, "{}", a.text);
    assert!(a.body["errors"][0]["field"].as_str().unwrap().starts_with("stock.contour.outer"), "{}", a.text);

    let endless = json!({"program": {"gcode": "G1 X99999 F100\nG1 X-99999\nG1 X99999\nG1 X-99999\n"}, "tool_type": "square", "diameter_mm": 10,
        "stock": stock.clone(), "sample_spacing_mm": 0.0001});
    assert_problem(&app.post("/v1/analysis", endless).await, 422, Some("sample_spacing_mm"));
    let far = json!({"program": {"gcode": "G1 X1e9 F100\n"}, "tool_type": "square", "diameter_mm": 10, "stock": stock.clone()});
    assert_eq!(app.post("/v1/analysis", far).await.status, 422);

    let no_stock = json!({"program": {"gcode": "G1 X1 F100\n"}, "tool_type": "square", "diameter_mm": 10, "stock": {}});
    assert_problem(&app.post("/v1/analysis", no_stock).await, 422, Some("stock"));

    // A tool id with the diameter or type of another tool.
    let six = app.tool_id("square", 6.0).await;
    let program = json!({"gcode": "G1 X1 F100\n"});
    let other = json!({"program": program, "tool_id": six, "diameter_mm": 10, "stock": stock.clone()});
    let a = app.post("/v1/analysis", other).await;
    assert_problem(&a, 422, Some("diameter_mm"));
    assert!(a.body["detail"].as_str().unwrap().contains("square end mill of 6 mm"), "{}", a.text);
    let ball = json!({"program": program, "tool_id": six, "tool_type": "ball", "stock": stock.clone()});
    assert_problem(&app.post("/v1/analysis", ball).await, 422, Some("tool_type"));
    assert_eq!(app.get("/v1/jobs").await.body["total"], 0);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_f9991300_slot_is_analysed_at_the_machines_maximum_feed_and_its_overload_is_named_by_line() {
    let app = TestApp::start().await;
    let gcode = "G21 G90 G17\nS9600 M3\nG0 X-10 Y20 Z5\nG1 Z-10 F1000\nG1 X110 F9991300\nM30\n";
    let body = json!({
        "program": {"gcode": gcode}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -10, "x_max": 100, "y_max": 40, "z_max": 0}}
    });
    let a = app.post_wait("/v1/analysis", body).await;
    assert_eq!(a.body["status"], "succeeded", "{}", a.text);
    let s = &a.body["result"]["summary"];
    // The seeded machine runs at most 15000 mm/min: fz = 15000 / (6 · 9600) = 260 µm.
    assert!(close(&s["t_m_um"]["max"], 260.4, 0.5), "{}", s["t_m_um"]);
    assert!(s["force_n"]["max"].as_f64().unwrap() < 20_000.0, "{}", s["force_n"]);
    assert_eq!(s["force_extrapolated"], true);
    let outside = &s["outside_model"];
    assert!(outside["length_mm"].as_f64().unwrap() > 90.0, "{outside}");
    assert!(outside["max_coded_radius"].as_f64().unwrap() > outside["design_coded_radius"].as_f64().unwrap());
    assert!(close(&outside["design_t_m_um"]["max"], 43.6 + 15.0 * 2f64.sqrt(), 0.1), "{outside}");
    assert_eq!(s["force_overload"]["lines"][0]["line"], 5);
    assert!(close(&s["force_overload"]["threshold_n"], 3.0 * 269.1, 0.5), "{}", s["force_overload"]);
    let warnings: Vec<&str> = s["warnings"].as_array().unwrap().iter().filter_map(|w| w.as_str()).collect();
    assert!(warnings.iter().any(|w| w.contains("maximum feed of 15000") && w.contains("line 5")), "{warnings:?}");
    assert!(
        warnings.iter().any(|w| w.contains("3 × the tool's standard force") && w.contains("line 5")),
        "{warnings:?}"
    );
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_standard_cut_reports_its_forces_inside_the_models_experiments() {
    let app = TestApp::start().await;
    let body = json!({
        "program": {"gcode": STANDARD_CUT}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": -40, "z_min": -10, "x_max": 100, "y_max": 0, "z_max": 0}}
    });
    let a = app.post_wait("/v1/analysis", body).await;
    let s = &a.body["result"]["summary"];
    let outside = &s["outside_model"];
    assert!(outside["x1"]["max"].as_f64().unwrap() < 0.1 && outside["x2"]["max"].as_f64().unwrap() < 0.1, "{outside}");
    assert!(outside["share"].as_f64().unwrap() < 0.05, "only the entry is lighter than the experiments: {outside}");
    assert_eq!(s["force_overload"]["line_count"], 0);
    app.stop().await;
}
