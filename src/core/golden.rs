//! Golden files of the NC writer's output (`src/core/nc/golden/`): the small hand-made path
//! (`nc/writer/tests.rs`), and the programs the planners write
//! (`insertion/program_tests.rs`, `process/program_tests.rs`). After a deliberate change of
//! the output, regenerate them with `DIEPLAN_UPDATE_GOLDEN=1 cargo test --release --lib
//! golden` and review the diff before committing it.

/// The environment variable that rewrites the golden files instead of comparing.
const UPDATE_GOLDEN: &str = "DIEPLAN_UPDATE_GOLDEN";

/// Lines of context printed around the first difference from a golden file.
const DIFF_CONTEXT_LINES: usize = 3;

/// Compares `text` with golden file `name`, or rewrites it under [`UPDATE_GOLDEN`].
pub(crate) fn check_golden(name: &str, text: &str) {
    let path = format!("{}/src/core/nc/golden/{name}", env!("CARGO_MANIFEST_DIR"));
    if std::env::var_os(UPDATE_GOLDEN).is_some() {
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{path}: {e}"));
        return;
    }
    let expected = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{path}: {e} (create it with {UPDATE_GOLDEN}=1 cargo test --release --lib golden)"));
    if expected == text {
        return;
    }
    let (old, new): (Vec<&str>, Vec<&str>) = (expected.lines().collect(), text.lines().collect());
    let first = old.iter().zip(&new).position(|(a, b)| a != b).unwrap_or(old.len().min(new.len()));
    let from = first.saturating_sub(DIFF_CONTEXT_LINES);
    let show = |lines: &[&str]| {
        let end = (first + DIFF_CONTEXT_LINES + 1).min(lines.len());
        lines[from.min(end)..end].iter().map(|l| format!("    {l}\n")).collect::<String>()
    };
    panic!(
        "{name} differs from the writer's output at line {} ({} lines expected, {} written)\n\
         expected:\n{}written:\n{}if the change is intended, run {UPDATE_GOLDEN}=1 cargo test --release --lib golden",
        first + 1,
        old.len(),
        new.len(),
        show(&old),
        show(&new)
    );
}

/// Writes `path` as golden files `fanuc` (Fanuc, no N numbers) and `linuxcnc` (LinuxCNC,
/// numbered) with `title`, and checks that our parser reads both.
pub(crate) fn check_program_goldens(path: &crate::core::toolpath::Toolpath, title: &str, fanuc: &str, linuxcnc: &str) {
    use crate::core::nc::{parse_gcode, write_program, Dialect, LineNumbers, ParseOptions, WriterOptions};
    for (name, dialect, numbered) in [(fanuc, Dialect::Fanuc, false), (linuxcnc, Dialect::LinuxCnc, true)] {
        let options = WriterOptions {
            dialect,
            title: Some(title.to_string()),
            line_numbers: numbered.then(LineNumbers::default),
            ..WriterOptions::default()
        };
        let text = write_program(path, &options);
        check_golden(name, &text);
        parse_gcode(&text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}
