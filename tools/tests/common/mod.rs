//! What the tests of the two C benchmarks (`polygon_bench.rs`, `light_bench.rs`) share:
//! running a benchmark's quick form and reading its tables.

use std::process::Command;

use sphera_tools::repository_root;

/// Runs `bash bench/NAME-bench/run.sh --quick --default-only` from the repository
/// root and returns its stdout and stderr, after asserting that it succeeded and ran the
/// default build only.
pub fn run_quick(name: &str) -> (String, String) {
    let root = repository_root();
    let script = format!("bench/{name}-bench/run.sh");
    let output = Command::new("bash")
        .arg(root.join(&script))
        .args(["--quick", "--default-only"])
        .current_dir(&root)
        .env("CARGO", env!("CARGO"))
        .env_remove("CARGO_BUILD_TARGET")
        .output()
        .unwrap_or_else(|e| panic!("run bash {script}: {e}"));
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(
        output.status.success(),
        "{script} failed with {}\nstdout:\n{stdout}\nstderr:\n{stderr}",
        output.status
    );
    assert!(stdout.contains("== default build"), "{stdout}");
    assert!(!stdout.contains("== target-cpu=native"), "{stdout}");
    (stdout, stderr)
}

/// The table rows of the pool whose title starts with `title` (the text before ` (`):
/// (technique, cells after the name).
pub fn pool_rows<'a>(output: &'a str, title: &str) -> Option<Vec<(&'a str, Vec<&'a str>)>> {
    let heading = format!("### {title} (");
    let start = output.find(&heading)?;
    let section = &output[start + heading.len()..];
    let section = &section[..section.find("\n### ").unwrap_or(section.len())];
    let rows = section
        .lines()
        .filter(|line| line.starts_with("| ") && !line.starts_with("| technique"))
        .map(|line| {
            let mut cells = line.trim_matches('|').split('|').map(str::trim);
            let name = cells.next().unwrap_or("");
            (name, cells.collect())
        })
        .collect();
    Some(rows)
}
