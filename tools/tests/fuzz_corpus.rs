//! Replays every committed fuzz input through the invariant checks of
//! `sphera_tools::invariants::abi_invariants`, the same code the fuzz targets in `fuzz/` run: the
//! minimised corpora (`fuzz/corpus/<target>/`) and the inputs that once broke an
//! invariant (`fuzz/regressions/<target>/`). A normal `cargo test`, no fuzzer needed.

use std::path::Path;

use sphera_tools::invariants::abi_invariants::{
    ltc_and_light_entry_points, polygon_entry_points, sg_entry_points, sphere_entry_points,
    sptd_entry_points, vsgl_entry_points,
};
use sphera_tools::repository_root;

/// The fuzz targets and the check each one runs (see `fuzz/fuzz_targets/`).
/// A target's check.
type Check = fn(&[u8]);

const TARGETS: [(&str, Check); 6] = [
    ("polygon", polygon_entry_points),
    ("ltc_light", ltc_and_light_entry_points),
    ("sphere", sphere_entry_points),
    ("sg", sg_entry_points),
    ("vsgl", vsgl_entry_points),
    ("sptd", sptd_entry_points),
];

/// Runs `check` on every file in `dir` (if it exists); returns (files, failures).
fn replay(dir: &Path, check: Check) -> (usize, Vec<String>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return (0, Vec::new());
    };
    let mut files: Vec<_> = entries
        .map(|e| e.expect("read the corpus").path())
        .collect();
    files.sort();
    let mut failures = Vec::new();
    for file in &files {
        let data = std::fs::read(file).expect("read a corpus file");
        if std::panic::catch_unwind(|| check(&data)).is_err() {
            failures.push(file.display().to_string());
        }
    }
    (files.len(), failures)
}

fn replay_target(name: &str) {
    let (_, check) = TARGETS
        .iter()
        .find(|(n, _)| *n == name)
        .expect("a known target");
    let root = repository_root().join("fuzz");
    let (corpus, mut failures) = replay(&root.join("corpus").join(name), *check);
    let (regressions, more) = replay(&root.join("regressions").join(name), *check);
    failures.extend(more);
    println!("{name}: {corpus} corpus files, {regressions} regression inputs replayed");
    assert!(
        failures.is_empty(),
        "{} inputs break an invariant (replay one with `cargo fuzz run --sanitizer none -O {name} <file>` in fuzz/):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn polygon_corpus() {
    replay_target("polygon");
}

#[test]
fn ltc_light_corpus() {
    replay_target("ltc_light");
}

#[test]
fn sphere_corpus() {
    replay_target("sphere");
}

/// Every directory under `fuzz/corpus/` and `fuzz/regressions/` is a target replayed
/// here, so that a new target's corpus cannot be committed without its replay.
#[test]
fn every_corpus_has_a_replay() {
    for kind in ["corpus", "regressions"] {
        let Ok(entries) = std::fs::read_dir(repository_root().join("fuzz").join(kind)) else {
            continue;
        };
        for entry in entries {
            let name = entry
                .expect("read fuzz/")
                .file_name()
                .to_string_lossy()
                .into_owned();
            assert!(
                TARGETS.iter().any(|(n, _)| *n == name),
                "fuzz/{kind}/{name} has no replay in tools/tests/fuzz_corpus.rs"
            );
        }
    }
}

#[test]
fn sg_corpus() {
    replay_target("sg");
}

#[test]
fn vsgl_corpus() {
    replay_target("vsgl");
}

#[test]
fn sptd_corpus() {
    replay_target("sptd");
}

/// Every input kept under `fuzz/findings/<target>/` (the open findings that
/// `docs/contract.md` lists) still breaks an invariant: one that passes has been fixed
/// and belongs in `fuzz/regressions/`, where it is replayed.
#[test]
fn open_findings_are_still_open() {
    let Ok(targets) = std::fs::read_dir(repository_root().join("fuzz").join("findings")) else {
        return;
    };
    let mut fixed = Vec::new();
    for target in targets {
        let target = target.expect("read fuzz/findings").path();
        let name = target.file_name().unwrap().to_string_lossy().into_owned();
        let (_, check) = TARGETS
            .iter()
            .find(|(n, _)| *n == name)
            .unwrap_or_else(|| panic!("fuzz/findings/{name} is not a fuzz target"));
        let (count, failures) = replay(&target, *check);
        let mut files: Vec<_> = std::fs::read_dir(&target)
            .expect("read findings")
            .map(|e| e.expect("entry").path().display().to_string())
            .collect();
        files.sort();
        println!("{name}: {} of {count} findings still fail", failures.len());
        fixed.extend(files.into_iter().filter(|f| !failures.contains(f)));
    }
    assert!(
        fixed.is_empty(),
        "{} findings pass now: move them to fuzz/regressions/ and update docs/contract.md:\n{}",
        fixed.len(),
        fixed.join("\n")
    );
}
