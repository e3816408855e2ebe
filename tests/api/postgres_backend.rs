//! The API tests where the backend matters, run again against a real PostgreSQL: this
//! test runs the test binary itself with `DIEPLAN_TEST_BACKEND=postgres` and the modules
//! below, so every one of their tests starts the real app on a database of its own on the
//! test PostgreSQL (`postgres.rs`).
//!
//! Chosen: every module that reads or writes through the store (the database's CRUD,
//! PATCH and ETags, jobs and their blobs, cancel, purge, the fair queue, restarts, keys,
//! tool defaults, errors, drawings, conditions, costing, feeds). Left to SQLite alone: the
//! modules whose work is the core's (analysis, trochoids, plans: the same SQL as the jobs
//! above, minutes of computation), the spec and page tests (the backend does not show
//! there; Schemathesis runs once, on SQLite), and the tests that open the SQLite file
//! itself (listed in [`SQLITE_ONLY`]).

use super::postgres::BACKEND_VARIABLE;

/// The modules run against PostgreSQL.
const MODULES: [&str; 14] = [
    "concurrency::",
    "conditions::",
    "costing::",
    "database::",
    "drawings::",
    "errors::",
    "fair_queue::",
    "feeds::",
    "fit::",
    "jobs::",
    "keys::",
    "restarts::",
    "tool_defaults::",
    "replicas::",
];

/// Tests of those modules that read or write the SQLite file directly.
const SQLITE_ONLY: [&str; 4] = [
    "database::a_shops_edit_of_a_seeded_row_is_marked_and_survives_restarts_and_later_seed_corrections",
    "jobs::a_job_left_running_by_a_crash_is_queued_again_and_finishes_at_the_next_start",
    "keys::the_keys_command_makes_a_key_the_service_accepts",
    "tool_defaults::the_database_itself_refuses_two_defaults_of_one_type_and_diameter",
];

#[test]
fn the_api_tests_where_the_backend_matters_pass_against_postgresql() {
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
