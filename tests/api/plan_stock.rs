//! A plan keeps the stock its chosen program leaves in the cavity (issue 32 item 3): the rest
//! material in the corners its tool cannot reach, for a smaller tool to start from.

use crate::common::{close, TestApp};
use serde_json::{json, Value};

/// Area a tool of radius `r_mm` cannot reach in one sharp 90° corner, mm².
fn corner_mm2(r_mm: f64) -> f64 {
    r_mm * r_mm * (1.0 - std::f64::consts::FRAC_PI_4)
}

/// A sharp 40 × 30 rectangle, 6 mm deep, planned with the 10 mm square end mill.
fn sharp_cavity() -> Value {
    json!({
        "contour": {"outer": [[0, 0], [40, 0], [40, 30], [0, 30]]},
        "z_top": 0, "z_bottom": -6, "diameters_mm": [10], "sample_spacing_mm": 0.2, "baseline": false
    })
}

/// The 6 mm tool into the corner at the origin at the cavity's floor, and back out.
fn corner_cleanup(from: &str) -> Value {
    let gcode = "G21 G90 G17\nS12000 M3\nG0 X10 Y10 Z5\nG1 Z-6 F500\nG1 X3 Y3 F1000\nG1 X10 Y10\nG0 Z5\nM30\n";
    json!({"program": {"gcode": gcode}, "tool_type": "square", "diameter_mm": 6, "stock": {"from_job": from}})
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_plan_keeps_the_corners_its_tool_leaves_and_a_smaller_tool_starts_from_them() {
    let app = TestApp::start().await;
    let plan = app.send(reqwest::Method::POST, "/v1/plans", Some(sharp_cavity()), &[("prefer", "wait=300")]).await;
    assert_eq!(plan.body["status"], "succeeded", "{}", &plan.text[..plan.text.len().min(3000)]);
    let id = plan.body["id"].as_str().unwrap().to_string();
    let rest = &plan.body["result"]["rest_material"];
    let expected = 4.0 * corner_mm2(5.0) * 6.0;
    assert!(close(&rest["volume_mm3"], expected, 0.3 * expected), "{rest}");
    let levels = rest["levels"].as_array().unwrap();
    assert!(
        close(&levels[0]["z_top"], 0.0, 1e-9) && close(&levels[levels.len() - 1]["z_bottom"], -6.0, 1e-9),
        "{rest}"
    );

    // The 3-D view's height map of it.
    let map = app.get(&format!("/v1/jobs/{id}/stock")).await;
    assert_eq!(map.status, 200, "{}", map.text);

    // The 6 mm tool removes what it can reach of one corner: 25 − 9 times (1 − π/4) mm² over
    // the 6 mm depth.
    let corner = app.post_wait("/v1/analysis", corner_cleanup(&id)).await;
    assert_eq!(corner.body["status"], "succeeded", "{}", corner.text);
    let s = &corner.body["result"]["summary"];
    assert_eq!(corner.body["result"]["stock_from_job"], json!(id));
    let removed = (corner_mm2(5.0) - corner_mm2(3.0)) * 6.0;
    assert!(close(&s["removed_volume_mm3"], removed, 0.4 * removed), "{s}");
    let left = rest["volume_mm3"].as_f64().unwrap() - s["removed_volume_mm3"].as_f64().unwrap();
    assert!(close(&s["rest_material"]["volume_mm3"], left, 0.05 * expected), "{s}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_stepped_cavity_keeps_its_stock_on_one_grid_with_each_layers_corners() {
    // A 40 × 30 rectangle 6 mm deep over a 30 × 20 one 5 mm deep: each layer is simulated
    // on a grid of its own outline, and the plan keeps one stock over both.
    let app = TestApp::start().await;
    let body = json!({
        "layers": [
            {"contour": {"outer": [[0, 0], [40, 0], [40, 30], [0, 30]]}, "z_top": 0, "z_bottom": -6},
            {"contour": {"outer": [[5, 5], [35, 5], [35, 25], [5, 25]]}, "z_top": -6, "z_bottom": -11}
        ],
        "diameters_mm": [10], "sample_spacing_mm": 0.2, "baseline": false
    });
    let plan = app.send(reqwest::Method::POST, "/v1/plans", Some(body), &[("prefer", "wait=300")]).await;
    assert_eq!(plan.body["status"], "succeeded", "{}", &plan.text[..plan.text.len().min(3000)]);
    let rest = &plan.body["result"]["rest_material"];
    let corners = 4.0 * corner_mm2(5.0);
    let levels =
        rest["levels"].as_array().unwrap_or_else(|| panic!("no rest material: {}", plan.body["result"]["warnings"]));
    for level in levels {
        assert!(close(&level["area_mm2"], corners, 0.3 * corners), "{level}");
    }
    assert!(close(&rest["volume_mm3"], corners * 11.0, 0.3 * corners * 11.0), "{rest}");
    let id = plan.body["id"].as_str().unwrap();
    assert_eq!(app.get(&format!("/v1/jobs/{id}/stock")).await.status, 200);
    app.stop().await;
}
