//! The NC lines a drawing names (`GET /v1/jobs/{id}/trace`, the hover read-out, the
//! regions) are lines of the program the user can download for that path, for every kind
//! of job: each vertex lies on a move of the line it names, read from that program with our
//! own parser.

use crate::common::TestApp;
use dieplan::core::nc::{parse_gcode, ParseOptions};
use dieplan::core::toolpath::{Motion, Move, Toolpath};
use serde_json::Value;
use std::collections::HashMap;

/// Most a job may take here while the rest of the suite runs, s.
const DEADLINE_S: u64 = 900;
/// How far a vertex may lie from the move of its line, mm (the vertices are points of the
/// path; this is the rounding of the written program).
const ON_MOVE_MM: f64 = 0.01;

/// Runs the built-in example `id` and returns the finished job.
async fn example(app: &TestApp, id: &str) -> Value {
    let list = app.get("/v1/examples").await.body;
    let example = list["items"].as_array().unwrap().iter().find(|e| e["id"] == id).unwrap().clone();
    let a = app.post("/v1/jobs", serde_json::json!({"kind": example["kind"], "input": example["input"]})).await;
    assert!(a.status == 201 || a.status == 202, "{}", a.text);
    let job = app.wait_for_job_within(a.body["id"].as_str().unwrap(), DEADLINE_S).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    job
}

/// Distance from `p` to the move, mm (an arc: to its circle, within its heights).
fn off_move(m: &Move, p: [f64; 3]) -> f64 {
    match m.motion {
        Motion::Arc { center, .. } => {
            let r = (m.start.x - center.x).hypot(m.start.y - center.y);
            let radial = ((p[0] - center.x).hypot(p[1] - center.y) - r).abs();
            let (lo, hi) = (m.start.z.min(m.end.z), m.start.z.max(m.end.z));
            radial.max(lo - p[2]).max(p[2] - hi).max(0.0)
        }
        _ => {
            let d = [m.end.x - m.start.x, m.end.y - m.start.y, m.end.z - m.start.z];
            let w = [p[0] - m.start.x, p[1] - m.start.y, p[2] - m.start.z];
            let len2 = d.iter().map(|v| v * v).sum::<f64>();
            let t = if len2 > 0.0 {
                (w.iter().zip(&d).map(|(a, b)| a * b).sum::<f64>() / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (0..3).map(|i| (w[i] - t * d[i]).powi(2)).sum::<f64>().sqrt()
        }
    }
}

/// The moves of the block on `line` and, when it ends an arc the writer split into blocks
/// (a helix of several turns: the move is named by its last block), of the blocks before
/// it that continue the same arc.
fn written_from(by_line: &HashMap<u32, Vec<Move>>, line: u32) -> Option<Vec<Move>> {
    let mut moves = by_line.get(&line)?.clone();
    let centre = |m: &Move| match m.motion {
        Motion::Arc { center, .. } => Some((center.x, center.y)),
        _ => None,
    };
    let Some(c) = moves.first().and_then(centre) else { return Some(moves) };
    let same = |m: &Move| centre(m).is_some_and(|d| (d.0 - c.0).hypot(d.1 - c.1) < 1e-6);
    let mut before = line - 1;
    while let Some(earlier) = by_line.get(&before).filter(|list| list.iter().all(same)) {
        moves.extend(earlier);
        before -= 1;
    }
    Some(moves)
}

/// Checks that every cutting vertex of path `path` of job `id` lies on a move of the line
/// it names in `program`; returns how many vertices were checked.
async fn check_path(app: &TestApp, id: &str, path: &str, program: &str) -> usize {
    let parsed: Toolpath = parse_gcode(program, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e:?}"));
    let mut by_line: HashMap<u32, Vec<Move>> = HashMap::new();
    for m in &parsed.moves {
        by_line.entry(m.line).or_default().push(*m);
    }
    let trace = app.get(&format!("/v1/jobs/{id}/trace?path={path}")).await;
    assert_eq!(trace.status, 200, "{}", trace.text);
    let mut checked = 0;
    for run in trace.body["runs"].as_array().unwrap().iter().filter(|r| r["rapid"] == false) {
        let points = run["points"].as_array().unwrap();
        for (i, line) in run["lines"].as_array().unwrap().iter().enumerate() {
            let line = line.as_u64().unwrap() as u32;
            let p = [points[i][0].as_f64().unwrap(), points[i][1].as_f64().unwrap(), run["z"][i].as_f64().unwrap()];
            let moves = written_from(&by_line, line).unwrap_or_else(|| {
                let text = program.lines().nth(line as usize - 1).unwrap_or("(past the end)");
                panic!("{path} of job {id}: vertex {p:?} names line {line}, which moves nothing: {text:?}")
            });
            let off = moves.iter().map(|m| off_move(m, p)).fold(f64::INFINITY, f64::min);
            assert!(
                off <= ON_MOVE_MM,
                "{path}: vertex {p:?} is {off} mm off line {line}: {:?}",
                program.lines().nth(line as usize - 1)
            );
            checked += 1;
        }
    }
    assert!(checked > 0, "{path} of job {id} has no cutting vertex");
    checked
}

async fn text(app: &TestApp, href: &str) -> String {
    let a = app.get(href).await;
    assert_eq!(a.status, 200, "{href}: {}", a.text);
    a.text
}

/// The G-code a job was sent.
async fn sent(app: &TestApp, id: &str) -> String {
    app.get(&format!("/v1/jobs/{id}/input")).await.body["program"]["gcode"].as_str().unwrap().to_string()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_analysis_and_a_costing_name_the_lines_of_the_program_sent() {
    let app = TestApp::start().await;
    for kind in ["slot-analysis", "pocket-wall-costing"] {
        let id = example(&app, kind).await["id"].as_str().unwrap().to_string();
        check_path(&app, &id, "input", &sent(&app, &id).await).await;
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_feeds_job_names_the_lines_of_the_program_sent_before_and_of_the_edited_program_after() {
    let app = TestApp::start().await;
    let job = example(&app, "pocket-wall-feeds").await;
    let id = job["id"].as_str().unwrap();
    let input = sent(&app, id).await;
    check_path(&app, id, "input", &input).await;
    let edited = text(&app, &format!("/v1/jobs/{id}/program")).await;
    // Blocks were split where the feed changes inside them: the lines after them moved down.
    assert!(edited.lines().count() > input.lines().count(), "{edited}");
    check_path(&app, id, "optimised", &edited).await;
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_trochoids_job_names_the_lines_of_its_base_program_and_of_its_program() {
    let app = TestApp::start().await;
    let id = example(&app, "pocket-slot-trochoids").await["id"].as_str().unwrap().to_string();
    check_path(&app, &id, "base", &text(&app, &format!("/v1/jobs/{id}/program?part=base")).await).await;
    check_path(&app, &id, "planned", &text(&app, &format!("/v1/jobs/{id}/program")).await).await;
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_plan_names_the_lines_of_its_program_in_every_layer_and_of_its_baseline() {
    let app = TestApp::start().await;
    let id = example(&app, "cavity-plan").await["id"].as_str().unwrap().to_string();
    let views = app.get(&format!("/v1/jobs/{id}/views")).await.body;
    let paths: Vec<&str> = views["paths"].as_array().unwrap().iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(paths, ["baseline", "program"], "{views}");
    let program = text(&app, &format!("/v1/jobs/{id}/program")).await;
    check_path(&app, &id, "program", &program).await;
    // Every layer of the plan is in its program: each layer's vertices name its lines.
    let trace = app.get(&format!("/v1/jobs/{id}/trace?path=program")).await.body;
    let layers: std::collections::BTreeSet<u64> =
        trace["runs"].as_array().unwrap().iter().filter_map(|r| r["layer"].as_u64()).collect();
    assert_eq!(layers.len(), views["layers"].as_array().unwrap().len(), "{layers:?}");
    check_path(&app, &id, "baseline", &text(&app, &format!("/v1/jobs/{id}/program?part=baseline")).await).await;
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_plans_stair_step_is_drawn_and_names_its_lines_in_the_plans_program() {
    let app = TestApp::start().await;
    let body = crate::stair_step::slanted_floor(Some(serde_json::json!({})));
    let job = app.send(reqwest::Method::POST, "/v1/plans", Some(body), &[("prefer", "wait=300")]).await;
    assert_eq!(job.body["status"], "succeeded", "{}", &job.text[..job.text.len().min(2000)]);
    let id = job.body["id"].as_str().unwrap().to_string();
    let views = app.get(&format!("/v1/jobs/{id}/views")).await.body;
    let paths: Vec<&str> = views["paths"].as_array().unwrap().iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(paths, ["program", "stair_step"], "{views}");
    let program = text(&app, &format!("/v1/jobs/{id}/program")).await;
    check_path(&app, &id, "stair_step", &program).await;
    check_path(&app, &id, "program", &program).await;
    app.stop().await;
}
