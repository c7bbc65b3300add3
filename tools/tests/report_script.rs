//! The report script (`bench/report.py`) against its mock tracer
//! (`bench/mock_tracer.py`, same command line as `sphera-trace`, no rendering):
//! the quick report is written and its mean check passes, and the check fails when an
//! unbiased technique's mean is shifted (the mock's `MOCK_BIAS`), so that the check
//! that `.ci/run` relies on can fail.

use std::path::PathBuf;
use std::process::{Command, Output};

use sphera_tools::repository_root;

/// Runs the quick report with the mock tracer into a fresh directory; `bias` sets the
/// mock's `MOCK_BIAS`.
fn quick_report(name: &str, bias: bool) -> (Output, PathBuf) {
    let root = repository_root();
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&out);
    let mock = root.join("bench").join("mock_tracer.py");
    let mut command = Command::new("python3");
    command
        .arg(root.join("bench").join("report.py"))
        .args([
            "--quick",
            "--no-indirect",
            "--scenes",
            "cornell,polygons",
            "--tracer",
        ])
        .arg(format!("python3 {}", mock.display()))
        .arg("--out")
        .arg(&out)
        .env_remove("MOCK_BIAS")
        .env_remove("MOCK_FAIL");
    if bias {
        command.env("MOCK_BIAS", "1");
    }
    let output = command.output().expect("run python3 bench/report.py");
    (output, out)
}

fn describe(output: &Output) -> String {
    format!(
        "status {}\nstdout:\n{}\nstderr:\n{}",
        output.status,
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

#[test]
fn quick_report_is_written_and_its_check_passes() {
    let (output, out) = quick_report("report-unbiased", false);
    assert!(output.status.success(), "{}", describe(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("unbiased technique means agree"),
        "{stdout}"
    );
    for file in [
        "index.html",
        "report.md",
        "rmse-cornell.svg",
        "rmse-polygons.svg",
    ] {
        let path = out.join(file);
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        assert!(size > 0, "{} is missing or empty", path.display());
    }
}

#[test]
fn quick_report_check_fails_on_a_biased_mean() {
    let (output, _) = quick_report("report-biased", true);
    assert_eq!(output.status.code(), Some(1), "{}", describe(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("check FAILED: cornell/solid_angle"),
        "{stdout}"
    );
}

/// Issue 16 (8): every bad argument gets a message and a non-zero exit, never a
/// traceback, a run without end or a silent success: infinite and huge budgets, a
/// non-number, an empty scene list, an unwritable output directory.
#[test]
fn bad_arguments_get_a_message_and_a_non_zero_exit() {
    let root = repository_root();
    let mock = root.join("bench").join("mock_tracer.py");
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("report-bad-arguments");
    let out = out.to_string_lossy().into_owned();
    for bad in [
        vec!["--budget-ms", "inf"],
        vec!["--budget-ms", "1e300"],
        vec!["--budget-ms", "abc"],
        vec!["--spp", "0"],
        vec!["--scenes", ""],
        vec!["--out", "/proc/sphera-cannot-write-here/report"],
    ] {
        let mut command = Command::new("python3");
        command
            .arg(root.join("bench").join("report.py"))
            .args(["--quick", "--no-indirect", "--tracer"])
            .arg(format!("python3 {}", mock.display()));
        if bad[0] != "--out" {
            command.args(["--out", &out]);
        }
        let output = command
            .args(&bad)
            .output()
            .expect("run python3 bench/report.py");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            !output.status.success(),
            "{bad:?} succeeded:\n{}",
            describe(&output)
        );
        assert!(
            !stderr.contains("Traceback"),
            "{bad:?} printed a traceback:\n{stderr}"
        );
        assert!(!stderr.trim().is_empty(), "{bad:?} printed no message");
    }
}
