//! The C benchmark of the sphere-light, BRDF and LTC polygon-light techniques
//! (`c-examples/light-bench`) in its quick form, default build only: it builds, runs and
//! exits 0, and prints a table row for every technique of every pool, each with valid
//! samples. The benchmark itself exits 1 when a technique yields no valid sample, or
//! when one of its C baselines (cone sampling, GGX visible-normal sampling,
//! cosine-weighted sampling) fails its checks against the library's pdfs and sample
//! means; no timing is asserted.

use std::process::Command;

use sphera_tools::repository_root;

/// The pools (by the first word of their title) and their techniques.
const POOLS: [(&str, &[&str]); 3] = [
    (
        "spheres",
        &[
            "c_cone",
            "cap",
            "c_cone_vndf",
            "sptd",
            "rt_shade",
            "rt_shade_bent",
        ],
    ),
    (
        "brdf",
        &[
            "c_vndf",
            "ggx",
            "c_vndf_pdf",
            "ggx_pdf",
            "c_cosine",
            "lambert",
        ],
    ),
    (
        "polygons",
        &[
            "projected",
            "ltc_polygon",
            "light_balance",
            "light_weighted_balance",
            "light_clamped_optimal",
            "light_optimal",
        ],
    ),
];

/// The table rows of the pool whose title starts with `id`: (technique, cells after
/// the name).
fn pool_rows<'a>(output: &'a str, id: &str) -> Option<Vec<(&'a str, Vec<&'a str>)>> {
    let heading = format!("### {id} (");
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

#[test]
fn quick_light_bench_runs_every_technique_in_every_pool() {
    let root = repository_root();
    let output = Command::new("bash")
        .arg(root.join("c-examples/light-bench/run.sh"))
        .args(["--quick", "--default-only"])
        .current_dir(&root)
        .env("CARGO", env!("CARGO"))
        .env_remove("CARGO_BUILD_TARGET")
        .output()
        .expect("run bash c-examples/light-bench/run.sh");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "run.sh failed with {}\nstdout:\n{stdout}\nstderr:\n{stderr}",
        output.status
    );
    assert!(stdout.contains("== default build"), "{stdout}");
    assert!(!stdout.contains("== target-cpu=native"), "{stdout}");
    for (pool, techniques) in POOLS {
        let rows =
            pool_rows(&stdout, pool).unwrap_or_else(|| panic!("no table for {pool}:\n{stdout}"));
        assert_eq!(rows.len(), techniques.len(), "{pool}: {rows:?}");
        for technique in techniques {
            let cells = rows
                .iter()
                .find(|(name, _)| name == technique)
                .map(|(_, cells)| cells)
                .unwrap_or_else(|| panic!("no row for {technique} in {pool}:\n{stdout}"));
            // baseline, ns prepare+1 sample, ns per sample, two ratios, valid share.
            assert_eq!(cells.len(), 6, "{technique} in {pool}: {cells:?}");
            assert!(
                rows.iter().any(|(name, _)| *name == cells[0]),
                "{technique} in {pool}: baseline {} has no row",
                cells[0]
            );
            for cell in &cells[1..5] {
                let value: f64 = cell
                    .parse()
                    .unwrap_or_else(|_| panic!("{technique} in {pool}: {cells:?}"));
                assert!(value > 0.0, "{technique} in {pool}: {cells:?}");
            }
            let valid: f64 = cells[5]
                .trim_end_matches('%')
                .trim()
                .parse()
                .unwrap_or_else(|_| panic!("{technique} in {pool}: {cells:?}"));
            assert!(valid > 0.0, "{technique} yields no sample in {pool}");
        }
    }
    assert!(stdout.contains("checksum"), "{stdout}");
    assert!(!stderr.contains("FAILED"), "{stderr}");
}
