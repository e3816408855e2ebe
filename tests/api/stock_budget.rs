//! `--stock-memory-mb`: the memory each stock simulation of a job may take reaches the
//! jobs; a program that cuts more levels than the budget holds is simulated on merged
//! slices, and its result says so.

use crate::common::TestApp;
use serde_json::{json, Value};

/// Layers of the z-level roughing, 0.6 mm apart.
const LAYERS: usize = 30;
/// Its depth of cut, mm.
const AD_MM: f64 = 0.6;
/// Bytes in a MiB, the unit of the setting.
const MIB: u64 = 1024 * 1024;

/// A z-level roughing with the 6 mm end mill: in each layer a ramp along x, back, five
/// passes along x 3 mm apart, and back to the start.
fn z_level_roughing() -> String {
    let mut g = String::from("G21 G90 G17\nS9600 M3\nG0 X8 Y8 Z5\nG1 Z0 F1000\n");
    for k in 1..=LAYERS {
        let z = -AD_MM * k as f64;
        g += &format!("G1 X14 Z{z:.3}\nG1 X8\n");
        for j in 0..5 {
            let y = 8 + 3 * j;
            if j > 0 {
                g += &format!("G1 Y{y}\n");
            }
            g += if j % 2 == 0 { "G1 X32\n" } else { "G1 X8\n" };
        }
        g += "G1 X8 Y8\n";
    }
    g + "G0 Z5\nM30\n"
}

/// The request of an analysis or costing job of the roughing in a 40 × 30 mm block.
fn roughing() -> Value {
    let depth = AD_MM * LAYERS as f64;
    json!({
        "program": {"gcode": z_level_roughing()},
        "tool_type": "square", "diameter_mm": 6,
        "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -depth, "x_max": 40, "y_max": 30, "z_max": 0}}
    })
}

/// The summary's slices, budget and budget warning.
fn budget_of(summary: &Value) -> (usize, u64, Option<String>) {
    let slices = summary["slices"].as_array().map_or(0, Vec::len);
    let budget = summary["stock_memory_budget_bytes"].as_u64().unwrap_or(0);
    let warning = summary["warnings"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(Value::as_str)
        .find(|w| w.contains("stock memory budget"))
        .map(str::to_string);
    (slices, budget, warning)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_layer_of_a_z_level_roughing_is_a_slice_within_the_default_budget() {
    let app = TestApp::start().await;
    let a = app.post_wait("/v1/analysis", roughing()).await;
    assert_eq!(a.body["status"], "succeeded", "{}", &a.text[..a.text.len().min(2000)]);
    let (slices, budget, warning) = budget_of(&a.body["result"]["summary"]);
    assert_eq!(slices, LAYERS);
    assert_eq!(budget, 1024 * MIB);
    assert_eq!(warning, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_service_started_with_a_tiny_stock_memory_budget_merges_the_levels_of_its_jobs_and_says_so() {
    let app = TestApp::start_with(|c| c.stock_memory_mb = 1).await;
    let a = app.post_wait("/v1/analysis", roughing()).await;
    assert_eq!(a.body["status"], "succeeded", "{}", &a.text[..a.text.len().min(2000)]);
    let summary = &a.body["result"]["summary"];
    let (slices, budget, warning) = budget_of(summary);
    assert_eq!((slices, budget), (16, MIB), "{summary}");
    let warning = warning.expect("a budget warning");
    assert!(warning.starts_with(&format!("levels merged to 16 slices of the {LAYERS}")), "{warning}");
    assert!(warning.contains("(1 MiB)") && warning.contains("coarsened"), "{warning}");
    // A costing job of the same program runs on the same budget.
    let c = app.post_wait("/v1/costing", roughing()).await;
    assert_eq!(c.body["status"], "succeeded", "{}", &c.text[..c.text.len().min(2000)]);
    let costed = c.body["result"]["analysis"].to_string();
    assert!(costed.contains("levels merged to 16 slices"), "{costed}");
    app.stop().await;
}
