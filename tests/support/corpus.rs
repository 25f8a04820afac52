//! Corpora of bad inputs (`tests/bad_scenes/`, `tests/bad_lenses/`): each file's header
//! promises its error with `# expect: TEXT` lines (substrings the message must contain),
//! `# not: TEXT` lines (substrings it must not), and a line marked `# <-- error` where the
//! error must point.

use std::path::Path;

/// Checks one corpus file: runs `load` (which must fail, without panicking, with a message
/// starting `file:line:`) and returns the message, or what is wrong with it.
pub fn check(
    path: &Path,
    load: impl FnOnce() -> Result<(), String> + std::panic::UnwindSafe,
) -> Result<String, Vec<String>> {
    let text = std::fs::read_to_string(path).expect("readable");
    let expects: Vec<&str> = text
        .lines()
        .filter_map(|l| l.strip_prefix("# expect: "))
        .collect();
    assert!(
        !expects.is_empty(),
        "{} has no `# expect:` line",
        path.display()
    );
    let rejects: Vec<&str> = text
        .lines()
        .filter_map(|l| l.strip_prefix("# not: "))
        .collect();
    let marker = text
        .lines()
        .position(|l| l.contains("# <-- error"))
        .map(|i| i + 1);
    let msg = match std::panic::catch_unwind(load) {
        Err(_) => return Err(vec![format!("{}: PANICKED", path.display())]),
        Ok(Ok(())) => return Err(vec![format!("{}: loaded without error", path.display())]),
        Ok(Err(m)) => m,
    };
    let mut failures = Vec::new();
    let prefix = format!("{}:", path.display());
    if !msg.starts_with(&prefix) {
        failures.push(format!(
            "{}: message does not start with the file name: {msg}",
            path.display()
        ));
    }
    for e in &expects {
        if !msg.contains(e) {
            failures.push(format!("{}: message lacks \"{e}\": {msg}", path.display()));
        }
    }
    for r in &rejects {
        if msg.contains(r) {
            failures.push(format!(
                "{}: message contains \"{r}\": {msg}",
                path.display()
            ));
        }
    }
    if let Some(line) = marker
        && !msg.starts_with(&format!("{prefix}{line}:"))
    {
        failures.push(format!("{}: expected line {line}: {msg}", path.display()));
    }
    if failures.is_empty() {
        Ok(msg)
    } else {
        Err(failures)
    }
}
