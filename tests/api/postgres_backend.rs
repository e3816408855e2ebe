//! The API tests run again against a real PostgreSQL: this test runs the test binary
//! itself with `DIEPLAN_TEST_BACKEND=postgres` and the modules below, so every one of their
//! tests starts the real app on a database of its own on the test PostgreSQL
//! (`postgres.rs`).
//!
//! Chosen: every module whose behaviour touches the store: the database's CRUD, PATCH and
//! ETags, the seeded rows the jobs read (ball tools, recalibration), every job kind
//! (analysis, trochoids, plans, feeds, costing, conditions, drawings, programs), jobs and
//! their blobs, cancel, purge and retention, the fair queue, restarts, keys and their rate
//! limits, tool defaults, errors, and the built-in examples. Left to SQLite alone: the
//! tests that do not touch the store (the architecture, the spec and the page's assets),
//! the tests that run once whatever the backend (Schemathesis, the browser test and the
//! curl examples, which drive the app from outside; the PostgreSQL seed test, which
//! compares the two backends itself), and the tests listed in [`SQLITE_ONLY`].

use super::postgres::BACKEND_VARIABLE;

/// The modules (or tests) run against PostgreSQL: test-name filters.
const MODULES: [&str; 27] = [
    "analysis::",
    "ball_tools::",
    "concurrency::",
    "conditions::",
    "costing::",
    "database::",
    "drawings::",
    "errors::",
    "fair_queue::",
    "feeds::",
    "fit::",
    "job_blobs::",
    "job_labels::",
    "jobs::",
    "keys::",
    "nc_programs::",
    "plans::",
    "programs::",
    "rate_limits::",
    "recalibration::",
    "replicas::",
    "restarts::",
    "retention::",
    "stock_carry::",
    "tool_defaults::",
    "trochoids::",
    "web::every_built_in_example",
];

/// Tests of those modules that hold for SQLite alone: a shop's database from before a
/// migration (PostgreSQL support came with migration 0014, so no PostgreSQL database
/// predates the migrations they test), and the SQLite file shrinking after a purge
/// (PostgreSQL's autovacuum reuses the space of deleted rows instead).
const SQLITE_ONLY: [&str; 4] = [
    "ball_tools::the_ball_and_radius_defaults_leave_a_shops_own_rows_and_edits_alone",
    "job_blobs::jobs_stored_before_the_blobs_moved_out_are_read_as_before",
    "recalibration::the_recalibration_leaves_a_shops_own_rows_edits_and_jobs_alone",
    "retention::purging_a_finished_job_removes_it_and_the_file_shrinks",
];

#[test]
fn the_api_tests_that_touch_the_store_pass_against_postgresql() {
    if super::postgres::selected() {
        return; // already the run against PostgreSQL
    }
    let mut command = std::process::Command::new(std::env::current_exe().expect("the test binary"));
    command.env(BACKEND_VARIABLE, "postgres").args(MODULES);
    for test in SQLITE_ONLY {
        command.args(["--skip", test]);
    }
    let output = command.output().expect("the test binary runs");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "the API tests failed against PostgreSQL:\n{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let summary = stdout.lines().filter(|l| l.starts_with("test result")).collect::<Vec<_>>().join("\n");
    println!("{summary}");
}
