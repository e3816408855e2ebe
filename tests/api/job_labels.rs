//! A job's name and tags (given on submit, returned, searched), and a program sent as a
//! multipart file upload.

use crate::common::{assert_problem, multipart, upload, Answer, TestApp};
use reqwest::StatusCode;
use serde_json::{json, Value};

const CUT: &str = "G21 G90 G17\nS9600 M3\nG0 X-10 Y4.5 Z5\nG1 Z-10 F1000\nG1 X110 F5760\nG0 Z5\nM30\n";

fn stock() -> Value {
    json!({"box": {"x_min": 0, "y_min": -40, "z_min": -10, "x_max": 100, "y_max": 0, "z_max": 0}})
}

fn analysis(name: &str, tags: &[&str]) -> Value {
    json!({"program": {"gcode": CUT}, "tool_type": "square", "diameter_mm": 10, "stock": stock(),
        "series_points": 10, "name": name, "tags": tags})
}

fn conditions(name: &str, tags: &[&str]) -> Value {
    json!({"kind": "conditions", "input": {"tool_type": "square", "diameter_mm": 10}, "name": name, "tags": tags})
}

fn fields(a: &Answer) -> Vec<String> {
    a.body["errors"].as_array().into_iter().flatten().filter_map(|e| e["field"].as_str().map(String::from)).collect()
}

fn names(page: &Value) -> Vec<&str> {
    page["items"].as_array().unwrap().iter().filter_map(|j| j["name"].as_str()).collect()
}

/// POSTs `body` in chunks (`Transfer-Encoding: chunked`, no `Content-Length`, as a client
/// streaming a file sends it) and returns the raw answer.
async fn chunked_post(app: &TestApp, path: &str, content_type: &str, body: &[u8]) -> String {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    const CHUNK: usize = 256;
    let url = reqwest::Url::parse(&app.url(path)).unwrap();
    let mut stream = tokio::net::TcpStream::connect((url.host_str().unwrap(), url.port().unwrap())).await.unwrap();
    let head = format!(
        "POST {path} HTTP/1.1\r\nHost: {}\r\nContent-Type: {content_type}\r\nTransfer-Encoding: chunked\r\nConnection: close\r\n\r\n",
        url.host_str().unwrap()
    );
    stream.write_all(head.as_bytes()).await.unwrap();
    for chunk in body.chunks(CHUNK) {
        // The service may answer and close before the whole body is sent.
        if stream.write_all(format!("{:x}\r\n", chunk.len()).as_bytes()).await.is_err()
            || stream.write_all(chunk).await.is_err()
            || stream.write_all(b"\r\n").await.is_err()
        {
            break;
        }
    }
    let _ = stream.write_all(b"0\r\n\r\n").await;
    let mut answer = Vec::new();
    let _ = stream.read_to_end(&mut answer).await;
    String::from_utf8_lossy(&answer).into_owned()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_name_and_tags_given_on_submit_come_back_in_the_job_and_in_the_list() {
    let app = TestApp::start().await;
    let a = app.post_wait("/v1/analysis", analysis("Die 4711 roughing", &["die:4711", "rough"])).await;
    assert_eq!(a.status, 201, "{}", a.text);
    assert_eq!(
        (a.body["name"].as_str(), a.body["tags"].clone()),
        (Some("Die 4711 roughing"), json!(["die:4711", "rough"]))
    );
    let id = a.body["id"].as_str().unwrap();
    let input = app.get(&format!("/v1/jobs/{id}/input")).await.body;
    assert!(input.get("name").is_none() && input.get("tags").is_none(), "labels are not the input: {input}");
    let b = app.post("/v1/jobs", conditions("Conditions for the D10", &[])).await;
    assert_eq!(b.status, 202, "{}", b.text);
    assert_eq!((b.body["name"].as_str(), b.body["tags"].clone()), (Some("Conditions for the D10"), json!([])));
    let list = app.get("/v1/jobs").await.body;
    assert_eq!(names(&list), ["Conditions for the D10", "Die 4711 roughing"]);
    assert_eq!(list["items"][1]["tags"], json!(["die:4711", "rough"]));
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn jobs_are_found_by_a_part_of_their_name_in_any_case_and_by_every_tag_named() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    for (name, tags) in [
        ("Cavity A — Ébauche", &["die:4711", "rough"][..]),
        ("Cavity B finish", &["die:4711", "finish"][..]),
        ("Core 100% done_1", &["die:9"][..]),
    ] {
        assert_eq!(app.post("/v1/jobs", conditions(name, tags)).await.status, 202);
    }
    let a = &app;
    let found = |q: &'static str| async move { a.get(&format!("/v1/jobs?{q}")).await.body };
    assert_eq!(names(&found("name=cavity").await), ["Cavity B finish", "Cavity A — Ébauche"]);
    assert_eq!(names(&found("name=%C3%89BAUCHE").await), ["Cavity A — Ébauche"]);
    assert_eq!(names(&found("name=100%25").await), ["Core 100% done_1"], "% is a character, not a wildcard");
    assert_eq!(found("name=y_a").await["total"], 0, "_ is a character, not a wildcard");
    assert_eq!(names(&found("tag=die:4711").await), ["Cavity B finish", "Cavity A — Ébauche"]);
    assert_eq!(names(&found("tag=die:4711&tag=rough").await), ["Cavity A — Ébauche"]);
    assert_eq!(found("tag=die:4711&tag=die:9").await["total"], 0);
    assert_eq!(names(&found("tag=die:4711&name=FINISH&kind=conditions&status=queued").await), ["Cavity B finish"]);
    assert_eq!(found("tag=die").await["total"], 0, "a tag matches whole");
    assert_problem(&app.get("/v1/jobs?tag=has%20space").await, 400, None);
    assert_problem(&app.get("/v1/jobs?name=&limit=5").await, 400, None);
    assert_problem(&app.get("/v1/jobs?limit=").await, 400, None);
    assert_problem(&app.get(&format!("/v1/jobs?name={}", "n".repeat(201))).await, 400, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn faults_of_the_name_and_tags_come_with_those_of_the_input_in_one_problem_and_store_nothing() {
    let app = TestApp::start().await;
    let mut tags: Vec<String> = (0..21).map(|i| format!("t{i}")).collect();
    tags[2] = "bad tag".into();
    let mut body = analysis(&"n".repeat(201), &[]);
    body["tags"] = json!(tags);
    body["diameter_mm"] = json!(-1);
    let a = app.post("/v1/analysis", body).await;
    assert_problem(&a, 422, Some("name"));
    let f = fields(&a);
    for field in ["diameter_mm", "name", "tags", "tags[2]"] {
        assert!(f.contains(&field.to_string()), "{field} in {f:?}");
    }
    let b = app.post("/v1/jobs", json!({"kind": "conditions", "input": {"tool_type": "square", "diameter_mm": 10}, "tags": ["a", "a", ""], "name": 3})).await;
    assert_problem(&b, 422, Some("name"));
    let c = app
        .post(
            "/v1/jobs",
            json!({"kind": "conditions", "input": {"tool_type": "square", "diameter_mm": 10}, "tags": ["a", "a", ""]}),
        )
        .await;
    assert_eq!(fields(&c), ["tags[1]", "tags[2]"], "{}", c.text);
    assert_eq!(app.get("/v1/jobs").await.body["total"], 0);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_program_sent_as_a_file_part_runs_as_if_sent_in_the_json() {
    let app = TestApp::start().await;
    let request = json!({"tool_type": "square", "diameter_mm": 10, "stock": stock(), "series_points": 10,
        "program": {"control": "linux_cnc"}, "name": "uploaded", "tags": ["upload"]});
    let request = request.to_string();
    let a = upload(
        &app,
        "/v1/analysis",
        &[("program", Some("cut.nc"), CUT.as_bytes()), ("request", None, request.as_bytes())],
    )
    .await;
    assert_eq!(a.status, StatusCode::CREATED, "{}", a.text);
    assert_eq!((a.body["status"].as_str(), a.body["name"].as_str()), (Some("succeeded"), Some("uploaded")));
    let mut json_body = analysis("x", &[]);
    json_body["program"]["control"] = json!("linux_cnc");
    let b = app.post_wait("/v1/analysis", json_body).await;
    assert_eq!(a.body["result"]["summary"], b.body["result"]["summary"]);
    let input = app.get(&format!("/v1/jobs/{}/input", a.body["id"].as_str().unwrap())).await.body;
    assert_eq!(input["program"], json!({"control": "linux_cnc", "gcode": CUT}));
    // Feeds, costing and trochoids take uploads too: their faults name the fields of the request part.
    for path in ["/v1/feeds", "/v1/costing", "/v1/trochoids"] {
        let a = upload(&app, path, &[("program", Some("cut.nc"), CUT.as_bytes())]).await;
        assert_eq!(a.status, StatusCode::UNPROCESSABLE_ENTITY, "{path}: {}", a.text);
        assert!(!fields(&a).iter().any(|f| f.starts_with("program")), "{path}: {}", a.text);
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_bad_upload_is_refused_naming_the_part() {
    let app = TestApp::start().await;
    let no_program = upload(&app, "/v1/analysis", &[("request", None, b"{}")]).await;
    assert_problem(&no_program, 422, Some("program"));
    let not_utf8 = upload(&app, "/v1/analysis", &[("program", Some("cut.nc"), b"G1 X\xff\xfe")]).await;
    assert_problem(&not_utf8, 422, Some("program"));
    let all =
        upload(&app, "/v1/analysis", &[("program", None, b"G1 X1"), ("request", None, b"[1]"), ("extra", None, b"")])
            .await;
    assert_eq!(fields(&all), ["request", "extra"], "{}", all.text);
    let twice = upload(
        &app,
        "/v1/analysis",
        &[("program", None, b"G1 X1"), ("request", None, br#"{"program": {"gcode": "G0"}}"#)],
    )
    .await;
    assert_problem(&twice, 422, Some("request.program"));
    let small = TestApp::start_with(|c| c.body_limit = 1024).await;
    let big = "G1 X1\n".repeat(400);
    // Refused up front by its declared length: said plainly, with the limit and the setting.
    let too_large = upload(&small, "/v1/analysis", &[("program", Some("big.nc"), big.as_bytes())]).await;
    assert_problem(&too_large, 413, None);
    let detail = too_large.body["detail"].as_str().unwrap();
    assert!(
        detail.contains("Content-Length")
            && detail.contains("limit of 1024 bytes")
            && detail.contains("DIEPLAN_BODY_LIMIT"),
        "{detail}"
    );
    // Streamed without a length: the part it grew past the limit in is named.
    let request = br#"{"tool_type": "square", "diameter_mm": 10}"#;
    let (content_type, body) = multipart(&[("request", None, request), ("program", Some("big.nc"), big.as_bytes())]);
    let streamed = chunked_post(&small, "/v1/analysis", &content_type, &body).await;
    assert!(streamed.starts_with("HTTP/1.1 413"), "{streamed}");
    assert!(
        streamed.contains("part program")
            && streamed.contains("limit of 1024 bytes")
            && streamed.contains("--body-limit"),
        "{streamed}"
    );
    let broken = app
        .client
        .post(app.url("/v1/analysis"))
        .header("content-type", "multipart/form-data")
        .body("not multipart")
        .send()
        .await
        .unwrap();
    assert_eq!(broken.status(), StatusCode::BAD_REQUEST);
    let plan = upload(&app, "/v1/plans", &[("program", None, b"G1 X1")]).await;
    assert_problem(&plan, 415, None);
    assert_eq!(app.get("/v1/jobs").await.body["total"], 0);
    small.stop().await;
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_is_renamed_and_retagged_with_the_rules_of_a_submit_and_found_by_its_new_labels() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let id = app.post("/v1/jobs", conditions("Cavity A", &["die:4711", "rough"])).await.body["id"]
        .as_str()
        .unwrap()
        .to_string();
    let job = format!("/v1/jobs/{id}");
    // A field left out stays; the list and the search follow the new labels.
    let renamed = app.patch(&job, json!({"name": "Cavity A, finishing"})).await;
    assert_eq!(renamed.status, 200, "{}", renamed.text);
    assert_eq!(
        (renamed.body["name"].as_str(), renamed.body["tags"].clone()),
        (Some("Cavity A, finishing"), json!(["die:4711", "rough"]))
    );
    let retagged = app.patch(&job, json!({"tags": ["die:4711", "finish"]})).await;
    assert_eq!(
        (retagged.body["name"].as_str(), retagged.body["tags"].clone()),
        (Some("Cavity A, finishing"), json!(["die:4711", "finish"]))
    );
    assert_eq!(names(&app.get("/v1/jobs?tag=finish&name=FINISHING").await.body), ["Cavity A, finishing"]);
    assert_eq!(app.get("/v1/jobs?tag=rough").await.body["total"], 0, "the old tag is gone");
    // Every fault at once, and a refused patch changes nothing.
    let bad = app.patch(&job, json!({"name": "", "tags": ["ok", "bad tag", "ok"], "kind": "plan"})).await;
    assert_problem(&bad, 422, Some("name"));
    assert_eq!(fields(&bad), ["kind", "name", "tags[1]", "tags[2]"], "{}", bad.text);
    let too_many: Vec<String> = (0..21).map(|i| format!("t{i}")).collect();
    assert_eq!(fields(&app.patch(&job, json!({"tags": too_many, "name": 3})).await), ["name", "tags"]);
    assert_eq!(app.get(&job).await.body["tags"], json!(["die:4711", "finish"]));
    // null removes the name, [] the tags.
    let cleared = app.patch(&job, json!({"name": null, "tags": []})).await;
    assert_eq!(cleared.status, 200, "{}", cleared.text);
    assert!(cleared.body["name"].is_null() && cleared.body["tags"] == json!([]), "{}", cleared.text);
    assert_problem(&app.patch("/v1/jobs/00000000-0000-4000-8000-000000000000", json!({"name": "x"})).await, 404, None);
    assert_problem(&app.patch("/v1/jobs/nope", json!({"name": "x"})).await, 400, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn whoever_may_submit_jobs_may_relabel_their_own_and_no_one_elses() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let admin = app.make_key(None, "admin", "admin").await;
    let alice = app.make_key(Some(&admin), "planner", "station A").await;
    let bob = app.make_key(Some(&admin), "planner", "station B").await;
    let reader = app.make_key(Some(&admin), "reader", "viewer").await;
    let made = app.send_as(&alice, reqwest::Method::POST, "/v1/jobs", Some(conditions("A's job", &[]))).await;
    let job = format!("/v1/jobs/{}", made.body["id"].as_str().unwrap());
    for (key, status) in [(&alice, 200), (&bob, 404), (&reader, 403), (&admin, 200)] {
        let a = app.send_as(key, reqwest::Method::PATCH, &job, Some(json!({"tags": ["mine"]}))).await;
        assert_eq!(a.status, status, "{}", a.text);
    }
    app.stop().await;
}
