//! Runs `tests/browser/run.sh`: starts the binary built with these tests (the release
//! binary under `cargo test --release`) and drives the web page in headless chromium
//! (playwright-core; chromium and the npm packages are installed when missing).

#[test]
fn the_web_page_works_in_a_browser() {
    let root = env!("CARGO_MANIFEST_DIR");
    let output = std::process::Command::new("bash")
        .arg(format!("{root}/tests/browser/run.sh"))
        .env("DIEPLAN_BIN", env!("CARGO_BIN_EXE_dieplan"))
        .current_dir(root)
        .output()
        .expect("bash runs");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "tests/browser/run.sh failed:\n{stdout}\n{stderr}");
    println!("{stdout}");
}
