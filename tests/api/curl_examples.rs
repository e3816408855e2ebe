//! Runs `tests/curl_examples.sh`: starts the binary built with these tests (the release
//! binary under `cargo test --release`) and drives it with the README's curl examples.

#[test]
fn the_readme_curl_examples_work_against_the_binary() {
    let root = env!("CARGO_MANIFEST_DIR");
    let status = std::process::Command::new("bash")
        .arg(format!("{root}/tests/curl_examples.sh"))
        .env("DIEPLAN_BIN", env!("CARGO_BIN_EXE_dieplan"))
        .current_dir(root)
        .status()
        .expect("bash runs");
    assert!(status.success(), "tests/curl_examples.sh failed");
}
