//! The C benchmark of the sphere-light, BRDF, LTC polygon-light and VSGL techniques
//! (`bench/light-bench`) in its quick form, default build only: it builds, runs and
//! exits 0, and prints a table row for every technique of every pool, each with valid
//! samples. The benchmark itself exits 1 when a technique yields no valid sample, or
//! when one of its C baselines (cone sampling, GGX visible-normal sampling,
//! cosine-weighted sampling, VSGL shading, vMF sampling) fails its checks against the
//! library's pdfs, shading values and sample means; no timing is asserted.

mod common;

use common::pool_rows;

/// The pools (by the first word of their title) and their techniques.
const POOLS: [(&str, &[&str]); 4] = [
    (
        "spheres",
        &[
            "c_cone",
            "cap",
            "solid_angle_sphere",
            "c_cone_vndf",
            "sptd",
            "sptd_fit",
            "rt_shade",
            "rt_shade_bent",
            "rt_shade_occluded",
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
    (
        "vsgls",
        &[
            "c_vsgl",
            "vsgl_shade",
            "c_vsgl_point",
            "vsgl_point",
            "c_vmf",
            "vmf",
        ],
    ),
];

#[test]
fn quick_light_bench_runs_every_technique_in_every_pool() {
    let (stdout, stderr) = common::run_quick("light");
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
