//! Drawings and charts of finished jobs: `GET /v1/jobs/{id}/views`, `drawing.svg` and
//! `charts/{chart}`, and `trace`.

use crate::common::{assert_problem, TestApp};
use serde_json::{json, Value};

/// Most a job may take in these tests while the rest of the suite runs, s.
const DEADLINE_S: u64 = 300;

/// A full slot across a box of stock: the analysis finds one critical region.
fn slotting_analysis() -> Value {
    json!({
        "program": {"gcode": "G21 G90\nS9600 M3\nG0 X-10 Y20 Z5\nG1 Z-10 F1000\nG1 X50 F2000\nG1 Y-5\nG0 Z5\nM30\n"},
        "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -10, "x_max": 100, "y_max": 40, "z_max": 0}}
    })
}

async fn finished(app: &TestApp, endpoint: &str, body: Value) -> String {
    let a = app.post(endpoint, body).await;
    assert!(a.status == 201 || a.status == 202, "{}", a.text);
    let id = a.body["id"].as_str().unwrap().to_string();
    let job = app.wait_for_job_within(&id, DEADLINE_S).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    assert_eq!(job["links"]["views"], format!("/v1/jobs/{id}/views"));
    assert_eq!(job["links"]["drawing"], format!("/v1/jobs/{id}/drawing.svg"));
    id
}

fn assert_svg(a: &crate::common::Answer) {
    assert_eq!(a.status, 200, "{}", a.text);
    assert!(a.content_type().starts_with("image/svg+xml"), "{}", a.content_type());
    assert!(a.text.contains("<svg") && a.text.trim_end().ends_with("</svg>"), "{}", &a.text[..a.text.len().min(300)]);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_analysis_draws_its_path_by_engagement_with_the_overload_marked() {
    let app = TestApp::start().await;
    let id = finished(&app, "/v1/analysis", slotting_analysis()).await;
    let views = app.get(&format!("/v1/jobs/{id}/views")).await;
    assert_eq!(views.status, 200, "{}", views.text);
    assert_eq!(views.body["paths"][0]["name"], "input");
    let quantities = views.body["paths"][0]["quantities"].as_array().unwrap();
    assert!(quantities.contains(&json!("alpha")) && quantities.contains(&json!("force")), "{}", views.text);
    assert_eq!(views.body["critical_regions"], 1);
    let charts: Vec<&str> =
        views.body["charts"].as_array().unwrap().iter().map(|c| c["id"].as_str().unwrap()).collect();
    assert!(charts.contains(&"alpha") && charts.contains(&"force"), "{charts:?}");

    let drawing = app.get(&format!("/v1/jobs/{id}/drawing.svg")).await;
    assert_svg(&drawing);
    assert!(drawing.text.contains("class=\"region"), "the full slot is marked");
    assert!(drawing.text.contains("class=\"rapid"), "rapids are drawn");
    let by_force = app.get(&format!("/v1/jobs/{id}/drawing.svg?color=force&rapids=false&width=600")).await;
    assert_svg(&by_force);
    assert!(!by_force.text.contains("class=\"rapid\""), "rapids can be left out");
    for chart in charts {
        assert_svg(&app.get(&format!("/v1/jobs/{id}/charts/{chart}?width=640&height=300")).await);
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_drawing_requests_are_refused_naming_the_parameter() {
    let app = TestApp::start().await;
    let id = finished(&app, "/v1/analysis", slotting_analysis()).await;
    for (query, status, field) in [
        ("color=heat", 422, Some("color")),
        ("color=wear", 422, Some("color")),
        ("path=planned", 422, Some("path")),
        ("layer=7", 422, Some("layer")),
        ("width=10", 422, Some("width")),
        ("width=wide", 400, None),
        ("zoom=2", 400, None),
        ("x_min=0&y_min=0&x_max=10", 422, Some("x_min")),
        ("x_min=10&y_min=0&x_max=5&y_max=10", 422, Some("x_min")),
        ("x_min=0&y_min=0&x_max=10&y_max=abc", 400, None),
    ] {
        assert_problem(&app.get(&format!("/v1/jobs/{id}/drawing.svg?{query}")).await, status, field);
    }
    assert_problem(&app.get(&format!("/v1/jobs/{id}/charts/nothing")).await, 404, None);
    assert_problem(&app.get(&format!("/v1/jobs/{id}/charts/alpha?height=5000")).await, 422, Some("height"));
    assert_problem(&app.get("/v1/jobs/00000000-0000-4000-8000-000000000000/drawing.svg").await, 404, None);

    let conditions = app.post_wait("/v1/conditions", json!({"tool_type": "square", "diameter_mm": 10})).await;
    let cid = conditions.body["id"].as_str().unwrap();
    assert!(conditions.body["links"]["drawing"].is_null(), "{}", conditions.text);
    assert_problem(&app.get(&format!("/v1/jobs/{cid}/views")).await, 409, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_queued_job_has_no_drawing_yet() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let a = app.post("/v1/analysis", slotting_analysis()).await;
    assert_eq!(a.status, 202, "{}", a.text);
    let id = a.body["id"].as_str().unwrap();
    assert!(a.body["links"]["views"].is_null());
    assert_problem(&app.get(&format!("/v1/jobs/{id}/drawing.svg")).await, 409, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_trochoid_insertion_draws_the_base_path_overloaded_and_the_planned_one_with_its_trochoids() {
    let app = TestApp::start().await;
    let body = json!({"contour": {"outer": [[0, 0], [80, 0], [80, 24], [120, 24], [120, 36], [80, 36], [80, 60], [0, 60]]},
        "z_top": 0, "z_bottom": -10, "tool_type": "square", "diameter_mm": 10});
    let id = finished(&app, "/v1/trochoids", body).await;
    let views = app.get(&format!("/v1/jobs/{id}/views")).await;
    let names: Vec<&str> =
        views.body["paths"].as_array().unwrap().iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["base", "planned"], "{}", views.text);
    assert!(views.body["trochoids"].as_u64().unwrap() > 0, "{}", views.text);
    assert!(!views.body["layers"].as_array().unwrap().is_empty());

    let base = app.get(&format!("/v1/jobs/{id}/drawing.svg?path=base")).await;
    assert_svg(&base);
    assert!(base.text.contains("class=\"region"), "the base path overloads the slot");
    assert!(base.text.contains("class=\"medial"), "the medial axis is drawn");
    let planned = app.get(&format!("/v1/jobs/{id}/drawing.svg?path=planned&layer=0")).await;
    assert_svg(&planned);
    assert!(planned.text.contains("class=\"trochoid"), "the trochoids are marked");
    assert_svg(&app.get(&format!("/v1/jobs/{id}/charts/alpha")).await);

    // A window is drawn anew at its own scale, clipped to it.
    let zoomed = app.get(&format!("/v1/jobs/{id}/drawing.svg?path=planned&x_min=90&y_min=20&x_max=120&y_max=40")).await;
    assert_svg(&zoomed);
    assert!(zoomed.text.contains("data-windowed=\"true\"") && zoomed.text.contains("clip-path"), "not a window");

    // The base program is served; the overloads of the base path name its lines, and
    // the result says what the insertion costs in time and length.
    let base_program = app.get(&format!("/v1/jobs/{id}/program?part=base")).await;
    assert_eq!(base_program.status, 200, "{}", base_program.text);
    let lines = base_program.text.lines().count() as u64;
    let label = base.text.split("class=\"region-label\"").nth(1).expect("a labelled overload");
    let last: u64 = label.split("data-lines=\"").nth(1).unwrap().split(['-', '"']).nth(1).unwrap().parse().unwrap();
    assert!(last <= lines, "the overload names line {last} of a base program of {lines} lines");
    let job = app.get(&format!("/v1/jobs/{id}")).await;
    let figures = &job.body["result"]["figures"];
    for side in ["before", "after"] {
        for field in ["feed_length_mm", "rapid_length_mm", "nominal_time_min", "kinematic_time_min"] {
            assert!(figures[side][field].as_f64().is_some_and(|v| v > 0.0), "{side}.{field}: {figures}");
        }
    }
    assert_problem(&app.get(&format!("/v1/jobs/{id}/program?part=baseline")).await, 404, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_feed_optimisation_charts_feed_and_force_before_and_after() {
    let app = TestApp::start().await;
    let body = json!({
        "program": {"gcode": "%\nO0100\nG21 G90 G17\nT1 M6\nS9600 M3\nG0 X0 Y0 Z5\nG1 Z-10 F1000\nG1 X5 F5760\nG3 X5 Y0 I-5 J0\nG0 Z5\nM30\n%\n"},
        "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": -30, "y_min": -30, "z_min": -10, "x_max": 30, "y_max": 30, "z_max": 0},
                  "open": [{"circle": {"cx": 0, "cy": 0, "r": 9.5}}]}
    });
    let id = finished(&app, "/v1/feeds", body).await;
    let views = app.get(&format!("/v1/jobs/{id}/views")).await;
    let charts: Vec<&str> =
        views.body["charts"].as_array().unwrap().iter().map(|c| c["id"].as_str().unwrap()).collect();
    assert!(charts.contains(&"feed") && charts.contains(&"force"), "{charts:?}");
    let feed = app.get(&format!("/v1/jobs/{id}/charts/feed")).await;
    assert_svg(&feed);
    assert!(feed.text.contains("programmed") && feed.text.contains("optimised"), "both lines are labelled");
    assert_svg(&app.get(&format!("/v1/jobs/{id}/drawing.svg?path=optimised&color=feed")).await);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_costing_draws_where_the_tool_life_is_spent_and_charts_time_and_cost() {
    let app = TestApp::start().await;
    let id = finished(&app, "/v1/costing", slotting_analysis()).await;
    let views = app.get(&format!("/v1/jobs/{id}/views")).await;
    let quantities = views.body["paths"][0]["quantities"].as_array().unwrap();
    assert!(quantities.contains(&json!("wear")), "{}", views.text);
    assert_svg(&app.get(&format!("/v1/jobs/{id}/drawing.svg?color=wear")).await);
    for chart in ["time", "cost"] {
        let a = app.get(&format!("/v1/jobs/{id}/charts/{chart}")).await;
        assert_svg(&a);
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_trace_gives_every_vertex_its_height_line_distance_and_values_and_charts_come_in_inches() {
    let app = TestApp::start().await;
    let id = finished(&app, "/v1/analysis", slotting_analysis()).await;
    let trace = app.get(&format!("/v1/jobs/{id}/trace")).await;
    assert_eq!(trace.status, 200, "{}", trace.text);
    assert_eq!(trace.body["path"], "input");
    let runs = trace.body["runs"].as_array().unwrap();
    let mut cut_lines = Vec::new();
    for run in runs {
        let n = run["points"].as_array().unwrap().len();
        for list in ["z", "lines", "s_mm"] {
            assert_eq!(run[list].as_array().unwrap().len(), n, "{list} of {run}");
        }
        if run["rapid"] == false {
            assert!(run["z"].as_array().unwrap().iter().all(|z| z.as_f64().unwrap() >= -10.0 - 1e-3), "{run}");
            cut_lines.extend(run["lines"].as_array().unwrap().iter().map(|l| l.as_u64().unwrap()));
            assert_eq!(run["values"]["alpha"].as_array().unwrap().len(), n);
        }
        let s: Vec<f64> = run["s_mm"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        assert!(s.windows(2).all(|w| w[1] >= w[0] - 1e-9), "path distance runs forward: {s:?}");
    }
    // The slot (line 5 of the program) is drawn at full engagement.
    assert!(cut_lines.contains(&5), "{cut_lines:?}");
    assert_problem(&app.get(&format!("/v1/jobs/{id}/trace?path=nope")).await, 404, None);
    // Charts in inches: the path distance axis says so.
    let mm = app.get(&format!("/v1/jobs/{id}/charts/alpha")).await;
    let inch = app.get(&format!("/v1/jobs/{id}/charts/alpha?units=inch")).await;
    assert_svg(&inch);
    assert!(mm.text.contains("path distance, mm") && inch.text.contains("path distance, in"), "{}", inch.text);
    let x_max = |svg: &str| -> f64 {
        let at = svg.find("data-x-max=\"").unwrap() + 12;
        svg[at..].split('"').next().unwrap().parse().unwrap()
    };
    assert!(x_max(&inch.text) < x_max(&mm.text) / 10.0, "{} vs {}", x_max(&inch.text), x_max(&mm.text));
    app.stop().await;
}
