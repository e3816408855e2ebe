//! The planning core stays pure: no HTTP, SQL, async runtime or middleware in `src/core/`;
//! utoipa only to describe its reports (`ToSchema` derives), which are the API's types.

use std::path::Path;

const FORBIDDEN: [&str; 4] = ["axum", "sqlx", "tokio", "tower"];

/// The one use of utoipa the core may make: deriving a type's schema.
const DESCRIBES: &str = "utoipa::ToSchema";

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("src/core exists") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn the_planning_core_imports_no_axum_sqlx_tokio_or_tower_and_utoipa_only_to_describe() {
    let mut files = Vec::new();
    rust_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src/core"), &mut files);
    assert!(files.len() > 3, "core files found");
    for file in files {
        let text = std::fs::read_to_string(&file).expect("readable");
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            for crate_name in FORBIDDEN {
                let used = code.contains(&format!("{crate_name}::")) || code.contains(&format!("use {crate_name}"));
                assert!(!used, "{}:{} names {crate_name}: the core must stay pure", file.display(), n + 1);
            }
            let other_utoipa = code.replace(DESCRIBES, "").contains("utoipa");
            assert!(!other_utoipa, "{}:{} uses utoipa beyond {DESCRIBES}", file.display(), n + 1);
        }
    }
}

#[test]
fn source_files_stay_under_the_size_limit() {
    let mut files = Vec::new();
    rust_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), &mut files);
    for file in files {
        let lines = std::fs::read_to_string(&file).expect("readable").lines().count();
        assert!(lines <= 600, "{} has {lines} lines: split it by concept", file.display());
    }
}
