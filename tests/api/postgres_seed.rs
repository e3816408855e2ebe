//! The two migration sets agree: a database migrated by `migrations_pg/` on the test
//! PostgreSQL holds the same seeded rows as one migrated by `migrations/` on SQLite, and
//! PostgreSQL applies the same `edited` rule (a shop's edit marks the row, and a migration
//! correcting seed data leaves it alone).

use super::common::TestApp;
use super::postgres;
use dieplan::service::store::Location;
use serde_json::Value;

/// Every table of the cutting-condition database, by its collection.
const COLLECTIONS: [&str; 7] = [
    "/v1/materials",
    "/v1/tools",
    "/v1/conditions/standard",
    "/v1/force-models",
    "/v1/tool-life",
    "/v1/machines",
    "/v1/cost-rates",
];

/// The rows of a collection without the times they were written.
async fn rows(app: &TestApp, collection: &str) -> Vec<Value> {
    let page = app.get(&format!("{collection}?limit=500")).await;
    assert_eq!(page.status, 200, "{}", page.text);
    let mut items = page.body["items"].as_array().expect("items").clone();
    for item in &mut items {
        let object = item.as_object_mut().expect("a row");
        object.remove("created_at");
        object.remove("updated_at");
    }
    items
}

/// Equal JSON, numbers to 1e-12 relative: PostgreSQL computes the seed's expressions
/// (`0.05 * fz`) in exact numeric and SQLite in double, a last bit apart.
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap_or(f64::NAN), y.as_f64().unwrap_or(f64::NAN));
            (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1.0)
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
        }
        (Value::Array(x), Value::Array(y)) => x.len() == y.len() && x.iter().zip(y).all(|(v, w)| same(v, w)),
        _ => a == b,
    }
}

async fn start_on_postgres() -> TestApp {
    let url = postgres::fresh_database().await;
    TestApp::start_with(|c| c.database = Location::Postgres(url)).await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn postgresql_is_seeded_with_the_same_rows_as_sqlite() {
    if postgres::selected() {
        return; // runs once, from the SQLite run
    }
    let sqlite = TestApp::start().await;
    let pg = start_on_postgres().await;
    for collection in COLLECTIONS {
        let (expected, actual) = (rows(&sqlite, collection).await, rows(&pg, collection).await);
        assert!(!expected.is_empty(), "{collection} is seeded");
        assert_eq!(actual.len(), expected.len(), "{collection}: as many rows");
        for (a, e) in actual.iter().zip(&expected) {
            assert!(same(a, e), "{collection}: the same row\n{a}\n{e}");
        }
    }
    sqlite.stop().await;
    pg.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_shops_edit_on_postgresql_marks_the_row_and_a_seed_correction_leaves_it_alone() {
    if postgres::selected() {
        return;
    }
    let url = postgres::fresh_database().await;
    let pg = TestApp::start_with(|c| c.database = Location::Postgres(url.clone())).await;
    let machines = rows(&pg, "/v1/machines").await;
    let id = machines[0]["id"].as_i64().expect("seeded machine");
    assert_eq!(machines[0]["edited"], false);
    let edited = pg.patch(&format!("/v1/machines/{id}"), serde_json::json!({"rapid_mm_min": 12345})).await;
    assert_eq!(edited.status, 200, "{}", edited.text);
    assert_eq!(edited.body["edited"], true);
    pg.stop().await;

    // A later correction of seed data, written as the migrations write them.
    use sqlx::Connection;
    let mut conn = sqlx::PgConnection::connect(&url).await.expect("database");
    let corrected = sqlx::query("UPDATE machines SET rapid_mm_min = 1 WHERE seed_key IS NOT NULL AND edited = 0")
        .execute(&mut conn)
        .await
        .expect("update");
    assert_eq!(corrected.rows_affected(), machines.len() as u64 - 1, "every seeded machine but the edited one");
    let rapid: f64 = sqlx::query_scalar("SELECT rapid_mm_min FROM machines WHERE id = $1")
        .bind(id)
        .fetch_one(&mut conn)
        .await
        .expect("row");
    assert!((rapid - 12345.0).abs() < 1e-9, "the shop's edit stays: {rapid}");
}
