//! Ball and radius end mills work with the database's defaults (migrations/0004): every
//! seeded one has a standard side cut, a force model carried over from the square end mill
//! of its diameter by the engaged cutting-edge length, and tool-life data, so costing and
//! feeds of their programs need no extra fields; a ball created without a corner radius
//! takes D/2.

use crate::common::{assert_problem, close, TestApp};
use dieplan::core::costing::calibration::{gamma_table, moved_gamma_table, FITTED_FORCE_EXPONENT, FITTED_GAMMA_AT_40};
use dieplan::core::force_model::{Coefficients, ForceModel};
use dieplan::core::nc::{parse_gcode, ParseOptions};
use dieplan::service::store::MIGRATOR;
use serde_json::{json, Value};
use sqlx::sqlite::{SqliteConnectOptions, SqlitePoolOptions};
use std::str::FromStr;

/// The seeded diameters, mm.
const DIAMETERS: [f64; 6] = [6.0, 8.0, 10.0, 12.0, 13.0, 16.0];
/// The last migration before the one under test.
const BEFORE_BALL_DEFAULTS: i64 = 3;

/// The tool's row in the database.
async fn tool(app: &TestApp, tool_type: &str, d: f64) -> Value {
    let a = app.get(&format!("/v1/tools?tool_type={tool_type}&diameter_mm={d}")).await;
    assert_eq!(a.body["total"], 1, "{tool_type} D{d}: {}", a.text);
    a.body["items"][0].clone()
}

/// The one row of `path` (a per-tool table) for the tool.
async fn one_row(app: &TestApp, path: &str, tool_id: i64) -> Value {
    let a = app.get(&format!("{path}tool_id={tool_id}")).await;
    assert_eq!(a.body["total"], 1, "{path} of tool {tool_id}: {}", a.text);
    a.body["items"][0].clone()
}

async fn standard(app: &TestApp, tool_id: i64) -> Value {
    one_row(app, "/v1/conditions/standard?operation=standard_side_cutting&", tool_id).await
}

/// The seeded tool and its standard side cut.
async fn tool_and_standard(app: &TestApp, tool_type: &str, d: f64) -> (Value, Value) {
    let t = tool(app, tool_type, d).await;
    let c = standard(app, t["id"].as_i64().unwrap()).await;
    (t, c)
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The force model of a `/v1/force-models` row, for a tool of corner radius `rc`.
fn model(row: &Value, rc: f64) -> ForceModel {
    ForceModel {
        t0_um: f(&row["t0_um"]),
        dt_um: f(&row["dt_um"]),
        l0_mm: f(&row["l0_mm"]),
        dl_mm: f(&row["dl_mm"]),
        coefficients: Coefficients {
            b0: f(&row["b0"]),
            b1: f(&row["b1"]),
            b2: f(&row["b2"]),
            b11: f(&row["b11"]),
            b22: f(&row["b22"]),
            b12: f(&row["b12"]),
        },
        ad_ref_mm: f(&row["ad_ref_mm"]),
        corner_radius_mm: rc,
    }
}

/// 60 mm of the tool's standard straight side cut (its Rd and Ad, S and F) along a block.
fn standard_cut(d: f64, conditions: &Value, flutes: f64) -> (String, Value) {
    let (s, fz, rd, ad) =
        (f(&conditions["spindle_rpm"]), f(&conditions["fz_mm"]), f(&conditions["rd_mm"]), f(&conditions["ad_mm"]));
    let y = d / 2.0 - rd;
    let gcode = format!(
        "G21 G90 G17\nS{s} M3\nG0 X{x0} Y{y} Z5\nG1 Z{z} F1000\nG1 X{x1} F{feed}\nG0 Z5\nM30\n",
        x0 = -d,
        z = -ad,
        x1 = 60.0 + d,
        feed = (fz * flutes * s).round()
    );
    let stock = json!({"box": {"x_min": 0, "y_min": -30, "z_min": -ad, "x_max": 60, "y_max": 0, "z_max": 0}});
    (gcode, stock)
}

/// A 3-D finishing pass: down a valley in the XZ plane and out again (seed 000's test).
const VALLEY: &str =
    "G21 G90 G18\nG0 X-2.25 Y0 Z0.578\nG1 X-2.249 F1200\nG3 X2.249 Z0.578 I2.249 K4.114\nG1 X2.25\nM30\n";

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_seeded_ball_and_radius_end_mill_has_its_conditions_a_force_model_and_tool_life_with_sources() {
    let app = TestApp::start().await;
    for (tool_type, operations) in [
        ("ball", &["standard_side_cutting", "helical_boring", "conventional_ball_roughing"][..]),
        (
            "radius",
            &[
                "standard_side_cutting",
                "spiral_hole_expansion",
                "trochoidal_grooving",
                "rough_side_cutting",
                "intermediate_rough_side_cutting",
            ][..],
        ),
    ] {
        for d in DIAMETERS {
            let id = tool(&app, tool_type, d).await["id"].as_i64().unwrap();
            for op in operations {
                let row = one_row(&app, &format!("/v1/conditions/standard?operation={op}&"), id).await;
                assert!(!row["reference"].as_str().unwrap().is_empty(), "{tool_type} D{d} {op}");
            }
            let m = one_row(&app, "/v1/force-models?", id).await;
            assert_eq!(m["source"], "extrapolated", "{tool_type} D{d}: {m}");
            assert!(m["reference"].as_str().unwrap().contains("engaged cutting-edge length"), "{m}");
            let life = one_row(&app, "/v1/tool-life?", id).await;
            assert!(close(&life["life_m"], 320.0, 1e-9), "{life}");
            assert_eq!(life["source"], "assumed");
            // γ is 1 up to the engagement of the tool's standard cut, 25.84° for a radius end
            // mill as for the square (Rd 0.05 D) and 78.46° for a ball (Rd 0.4 D), then the
            // table fitted to MODEL.md §9 (migrations/0006): the ball's is the same moved along α.
            let flat = gamma_table(25.842, FITTED_GAMMA_AT_40);
            let expected = if tool_type == "ball" { moved_gamma_table(&flat, 25.842, 78.464) } else { flat };
            let stored: Vec<(f64, f64)> = serde_json::from_value(life["gamma_table"].clone()).unwrap();
            assert_eq!(stored.len(), expected.len(), "{tool_type} D{d}: {stored:?}");
            for (s, e) in stored.iter().zip(&expected) {
                // The migration writes the angles to 3 decimals.
                assert!(
                    (s.0 - e.0).abs() < 2e-3 && (s.1 - e.1).abs() < 2e-3,
                    "{tool_type} D{d}: {stored:?} vs {expected:?}"
                );
            }
            assert!(close(&life["force_exponent"], FITTED_FORCE_EXPONENT, 1e-12), "{life}");
        }
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_r5_balls_side_cut_is_seed_004_table_7_and_the_other_balls_are_scaled_at_equal_cutting_speed() {
    let app = TestApp::start().await;
    for d in DIAMETERS {
        let (_, c) = tool_and_standard(&app, "ball", d).await;
        let k = d / 10.0;
        // seed 004 Table 7: S 10000, fz 0.3, Rd 4.0, Ad 0.6 for the R5 ball; S × 10/D and
        // fz, Rd, Ad × D/10 for the others (S to 0.1 min⁻¹), fz_min 0.05 fz.
        assert!(close(&c["spindle_rpm"], 10_000.0 / k, 0.05), "D{d}: {c}");
        for (field, v) in [("fz_mm", 0.3 * k), ("fz_min_mm", 0.015 * k), ("rd_mm", 4.0 * k), ("ad_mm", 0.6 * k)] {
            assert!(close(&c[field], v, 1e-9), "D{d} {field}: {c}");
        }
        assert_eq!(c["source"], if d == 10.0 { "paper" } else { "assumed" }, "D{d}");
        assert!(c["reference"].as_str().unwrap().contains("seed 004 Table 7"), "{c}");
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ball_and_radius_force_models_are_the_square_models_carried_over_by_flutes_and_engaged_edge_length() {
    let app = TestApp::start().await;
    for d in DIAMETERS {
        let square = tool(&app, "square", d).await;
        let square_model = model(&one_row(&app, "/v1/force-models?", square["id"].as_i64().unwrap()).await, 0.0);
        let z = |t: &Value| t["flutes"].as_u64().unwrap() as u32;
        for tool_type in ["ball", "radius"] {
            let t = tool(&app, tool_type, d).await;
            let id = t["id"].as_i64().unwrap();
            let rc = f(&t["corner_radius_mm"]);
            let row = one_row(&app, "/v1/force-models?", id).await;
            // The ball's reference depth is its standard Ad, the radius end mill's D.
            let ad_ref = f(&standard(&app, id).await["ad_mm"]);
            assert!(close(&row["ad_ref_mm"], ad_ref, 1e-12), "{tool_type} D{d}: {row}");
            let expected = square_model.carried_over(z(&square), z(&t), rc, ad_ref);
            let stored = model(&row, rc);
            assert_eq!(
                (stored.t0_um, stored.dt_um, stored.l0_mm, stored.dl_mm),
                (expected.t0_um, expected.dt_um, expected.l0_mm, expected.dl_mm)
            );
            let (a, b) = (stored.coefficients, expected.coefficients);
            for (name, s, e) in [
                ("b0", a.b0, b.b0),
                ("b1", a.b1, b.b1),
                ("b2", a.b2, b.b2),
                ("b11", a.b11, b.b11),
                ("b22", a.b22, b.b22),
                ("b12", a.b12, b.b12),
            ] {
                assert!(
                    (s - e).abs() <= 1e-7 * e.abs().max(1.0),
                    "{tool_type} D{d} {name}: {s} stored, {e} by the rule"
                );
            }
        }
    }
    // The README's figures: the R5 ball's β0 22.2 N, the D10 R1 radius end mill's 284.5 N.
    for (tool_type, b0) in [("ball", 22.198), ("radius", 284.460)] {
        let id = tool(&app, tool_type, 10.0).await["id"].as_i64().unwrap();
        assert!(close(&one_row(&app, "/v1/force-models?", id).await["b0"], b0, 5e-4), "{tool_type}");
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn costing_and_feeds_of_ball_and_radius_programs_need_no_extra_fields_for_every_seeded_diameter() {
    let app = TestApp::start().await;
    for tool_type in ["ball", "radius"] {
        for d in DIAMETERS {
            let (t, c) = tool_and_standard(&app, tool_type, d).await;
            let flutes = f(&t["flutes"]);
            let (gcode, stock) = standard_cut(d, &c, flutes);
            let what = format!("{tool_type} D{d}");
            let body = json!({"program": {"gcode": gcode}, "tool_type": tool_type, "diameter_mm": d, "stock": stock});

            // Along the block (the engagement band of most of the cut; entry and exit wear
            // less) the tool's standard cut wears it at the rate of its 320 m life: within 2 %,
            // since the fitted γ rises from the standard engagement and the simulation's α
            // scatters a little about it.
            let costing = app.post_wait("/v1/costing", body.clone()).await;
            assert_eq!(costing.body["status"], "succeeded", "{what}: {}", costing.text);
            let life = &costing.body["result"]["tool_life"];
            let steady = life["by_alpha"]
                .as_array()
                .unwrap()
                .iter()
                .max_by(|a, b| f(&a["cutting_length_mm"]).total_cmp(&f(&b["cutting_length_mm"])))
                .unwrap();
            let worn_mm = f(&steady["share"]) * f(&life["worn_edge_arc_mm"]);
            let life_m = f(&steady["cutting_length_mm"]) / worn_mm * f(&life["life_edge_arc_mm"]) / 1000.0;
            assert!((life_m - 320.0).abs() < 320.0 * 0.02, "{what}: {life_m} m at {steady}");
            assert!(f(&costing.body["result"]["cost"]["total"]) > 0.0, "{what}");

            // Constant force: the target is the model's force at the standard cut, which
            // along the cut keeps the standard feed.
            let feeds = app.post_wait("/v1/feeds", body).await;
            assert_eq!(feeds.body["status"], "succeeded", "{what}: {}", feeds.text);
            let r = &feeds.body["result"];
            assert_eq!(r["strategy"], "constant_force", "{what}");
            let standard_feed = f(&c["fz_mm"]) * flutes * f(&c["spindle_rpm"]);
            assert!(
                close(&r["limits"]["max_feed_mm_min"], (2.0 * standard_feed).min(15_000.0), 0.5),
                "{what}: {}",
                r["limits"]
            );
            let program = app.get(&format!("/v1/jobs/{}/program", feeds.body["id"].as_str().unwrap())).await;
            assert_eq!(program.status, 200, "{what}");
            let path = parse_gcode(&program.text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{what}: {e:?}"));
            let nearest = path
                .moves
                .iter()
                .filter_map(|m| m.feed_mm_min)
                .map(|feed| (feed - standard_feed).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest < 0.02 * standard_feed,
                "{what}: no block near the standard feed {standard_feed}\n{}",
                program.text
            );
        }
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_r5_balls_standard_force_is_the_carried_over_model_where_its_profile_engages_42_n() {
    let app = TestApp::start().await;
    let (_, c) = tool_and_standard(&app, "ball", 10.0).await;
    let (gcode, stock) = standard_cut(10.0, &c, 2.0);
    let body = json!({"program": {"gcode": gcode}, "tool_type": "ball", "diameter_mm": 10, "stock": stock});
    let feeds = app.post_wait("/v1/feeds", body).await;
    // The ball at Ad 0.6 is 2.4 mm in radius at the surface: its slices engage about 62° over
    // L ≈ 2.35 mm, not the cylinder's 78.5° over 6.85 mm (417.9 N).
    assert!(close(&feeds.body["result"]["target_force_n"], 42.02, 0.05), "{}", feeds.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn surface_finishing_with_every_seeded_ball_takes_its_feed_limits_from_the_database() {
    let app = TestApp::start().await;
    for d in DIAMETERS {
        let (_, c) = tool_and_standard(&app, "ball", d).await;
        let body =
            json!({"program": {"gcode": VALLEY}, "tool_type": "ball", "diameter_mm": d, "mode": "surface_finishing"});
        let a = app.post_wait("/v1/feeds", body).await;
        assert_eq!(a.body["status"], "succeeded", "ball D{d}: {}", a.text);
        let r = &a.body["result"];
        assert_eq!(r["strategy"], "cutting_point");
        let (s, fz_min) = (f(&c["spindle_rpm"]), f(&c["fz_min_mm"]));
        assert!(close(&r["limits"]["min_feed_mm_min"], fz_min * 2.0 * s, 1e-6), "ball D{d}: {}", r["limits"]);
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_ball_created_without_a_corner_radius_takes_d_over_2_and_a_radius_end_mill_must_give_its_own() {
    let app = TestApp::start().await;
    let created = app
        .post("/v1/tools", json!({"name": "shop ball D10", "tool_type": "ball", "diameter_mm": 10, "flutes": 2}))
        .await;
    assert_eq!(created.status, 201, "{}", created.text);
    assert!(close(&created.body["corner_radius_mm"], 5.0, 1e-12), "{}", created.text);
    let id = created.body["id"].as_i64().unwrap();
    let replaced = app
        .put(
            &format!("/v1/tools/{id}"),
            json!({"name": "shop ball D12", "tool_type": "ball", "diameter_mm": 12, "flutes": 2}),
        )
        .await;
    assert!(close(&replaced.body["corner_radius_mm"], 6.0, 1e-12), "{}", replaced.text);
    // A patch of the diameter alone keeps the old radius, which no longer fits; removing it takes D/2.
    assert_problem(
        &app.patch(&format!("/v1/tools/{id}"), json!({"diameter_mm": 8})).await,
        422,
        Some("corner_radius_mm"),
    );
    let patched = app.patch(&format!("/v1/tools/{id}"), json!({"diameter_mm": 8, "corner_radius_mm": null})).await;
    assert!(close(&patched.body["corner_radius_mm"], 4.0, 1e-12), "{}", patched.text);

    let wrong = json!({"name": "b", "tool_type": "ball", "diameter_mm": 10, "flutes": 2, "corner_radius_mm": 4});
    let a = app.post("/v1/tools", wrong).await;
    assert_problem(&a, 422, Some("corner_radius_mm"));
    assert!(a.body["detail"].as_str().unwrap().contains("D/2 = 5"), "{}", a.text);
    let radius =
        app.post("/v1/tools", json!({"name": "r", "tool_type": "radius", "diameter_mm": 10, "flutes": 4})).await;
    assert_problem(&radius, 422, Some("corner_radius_mm"));
    assert!(radius.body["detail"].as_str().unwrap().contains("required"), "{}", radius.text);
    let square =
        app.post("/v1/tools", json!({"name": "s", "tool_type": "square", "diameter_mm": 10, "flutes": 4})).await;
    assert!(close(&square.body["corner_radius_mm"], 0.0, 0.0), "{}", square.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_ball_and_radius_defaults_leave_a_shops_own_rows_and_edits_alone() {
    // A shop's database as it was before the migration: it has given the R5 ball its own
    // standard cut, edited the D10 radius end mill's force model and retired the D16 ball.
    let dir = std::sync::Arc::new(tempfile::tempdir().unwrap());
    let path = dir.path().join("shop.sqlite");
    let options =
        SqliteConnectOptions::from_str(&format!("sqlite://{}", path.display())).unwrap().create_if_missing(true);
    let pool = SqlitePoolOptions::new().max_connections(1).connect_with(options).await.unwrap();
    MIGRATOR.run_to(BEFORE_BALL_DEFAULTS, &pool).await.unwrap();
    for sql in [
        "INSERT INTO standard_conditions (tool_id, material_id, operation, spindle_rpm, fz_mm, fz_min_mm, rd_mm, ad_mm, source, reference)
         SELECT id, 1, 'standard_side_cutting', 9000, 0.2, 0.01, 3, 0.5, 'user', 'shop trial' FROM tools WHERE seed_key = 'tool:ball-10'",
        "UPDATE force_models SET b0 = 300, source = 'user', edited = 1 WHERE seed_key = 'force_model:radius-10:skd61'",
        "DELETE FROM standard_conditions WHERE tool_id = (SELECT id FROM tools WHERE seed_key = 'tool:ball-16')",
        "DELETE FROM tool_life WHERE tool_id = (SELECT id FROM tools WHERE seed_key = 'tool:ball-16')",
        "DELETE FROM tools WHERE seed_key = 'tool:ball-16'",
    ] {
        sqlx::query(sql).execute(&pool).await.unwrap();
    }
    pool.close().await;

    let app = TestApp::start_in(dir, |c| c.database = path.into()).await;
    let ball = tool(&app, "ball", 10.0).await["id"].as_i64().unwrap();
    let own = standard(&app, ball).await;
    assert_eq!((own["source"].as_str(), f(&own["spindle_rpm"])), (Some("user"), 9000.0), "{own}");
    // Its force model is still added: the shop had none.
    assert_eq!(one_row(&app, "/v1/force-models?", ball).await["source"], "extrapolated");
    let radius = tool(&app, "radius", 10.0).await["id"].as_i64().unwrap();
    let edited = one_row(&app, "/v1/force-models?", radius).await;
    assert_eq!((edited["source"].as_str(), f(&edited["b0"])), (Some("user"), 300.0), "{edited}");
    assert_eq!(app.get("/v1/tools?tool_type=ball&diameter_mm=16").await.body["total"], 0);
    let twelve = tool(&app, "radius", 12.0).await["id"].as_i64().unwrap();
    assert_eq!(one_row(&app, "/v1/force-models?", twelve).await["source"], "extrapolated");
    app.stop().await;
}
