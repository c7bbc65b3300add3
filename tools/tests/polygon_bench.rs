//! The C benchmark of the polygon techniques (`bench/polygon-bench`) in its quick
//! form, default build only: it builds, runs and exits 0, and prints a table row for
//! every technique in every pool it runs on, each with valid samples (pdf > 0). The
//! benchmark itself exits 1 when a technique yields no valid sample in a pool, or when
//! its C Turk baseline disagrees with `sphera_turk_polygon_pdf`; no timing is asserted.

mod common;

use common::pool_rows;

/// The techniques of the benchmark and whether they run on the straddling pools (those
/// that clip internally, and the C Turk baseline).
const TECHNIQUES: [(&str, bool); 10] = [
    ("c_turk", true),
    ("turk", false),
    ("solid_angle", false),
    ("clipped_solid_angle", true),
    ("projected", true),
    ("projected_fast", true),
    ("arvo", false),
    ("hart_bilinear", false),
    ("hart_biquadratic", false),
    ("arvo_projected", true),
];

const SHAPES: [&str; 4] = ["triangles", "quads", "hexagons", "heptagons"];
const KINDS: [&str; 3] = ["central", "decentral", "straddling"];

#[test]
fn quick_polygon_bench_runs_every_technique_in_every_pool() {
    let (stdout, stderr) = common::run_quick("polygon");
    for kind in KINDS {
        for shape in SHAPES {
            let title = format!("{shape}, {kind}");
            let rows = pool_rows(&stdout, &title)
                .unwrap_or_else(|| panic!("no table for {title}:\n{stdout}"));
            for (technique, straddling_too) in TECHNIQUES {
                if kind == "straddling" && !straddling_too {
                    continue;
                }
                let cells = rows
                    .iter()
                    .find(|(name, _)| *name == technique)
                    .map(|(_, cells)| cells)
                    .unwrap_or_else(|| panic!("no row for {technique} in {title}:\n{stdout}"));
                // ns prepare+1 sample, ns per sample, two ratios, valid share.
                assert_eq!(cells.len(), 5, "{technique} in {title}: {cells:?}");
                for cell in &cells[..4] {
                    let value: f64 = cell
                        .parse()
                        .unwrap_or_else(|_| panic!("{technique} in {title}: {cells:?}"));
                    assert!(value > 0.0, "{technique} in {title}: {cells:?}");
                }
                let valid: f64 = cells[4]
                    .trim_end_matches('%')
                    .trim()
                    .parse()
                    .unwrap_or_else(|_| panic!("{technique} in {title}: {cells:?}"));
                assert!(valid > 0.0, "{technique} yields no sample in {title}");
            }
        }
    }
    assert!(stdout.contains("checksum"), "{stdout}");
    assert!(!stderr.contains("FAILED"), "{stderr}");
}
