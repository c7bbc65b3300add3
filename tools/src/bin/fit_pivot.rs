//! Fits the pivot (uniform SPTD) table of the GGX BRDF and writes `src/brdf/pivot_table.rs`.
//!
//! Run with `cargo run --release -p sphera-tools --bin fit_pivot [-- --threads N]`
//! (default: all cores; the output does not depend on the thread count). With
//! `--render-only` it keeps the committed cells and runtime line and only re-measures the
//! errors and rewrites the documentation.
use sphera_tools::fitters::{ltc_fitter, pivot_fitter};
use std::time::Instant;

fn main() {
    let (threads, render_only) = ltc_fitter::fitter_arguments();
    let root = sphera_tools::repository_root();
    let path = root.join("src/brdf/pivot_table.rs");
    let ltc_path = root.join("src/brdf/ltc_table.rs");
    let read = |p: &std::path::Path| {
        std::fs::read_to_string(p).unwrap_or_else(|e| panic!("cannot read {}: {e}", p.display()))
    };
    let (table, runtime) = if render_only {
        let text = read(&path);
        (
            pivot_fitter::parse_table(&text),
            pivot_fitter::runtime_line(&text),
        )
    } else {
        let start = Instant::now();
        let (table, evaluations) = pivot_fitter::fit_table(threads);
        let fit_time = start.elapsed();
        println!(
            "fitted {} cells on {threads} thread(s) in {fit_time:.2?} \
             ({evaluations} objective evaluations)",
            table.len()
        );
        let runtime = format!(
            "{}{:.0} s on {threads} thread(s) of the author's machine ({evaluations} objective \
             evaluations).",
            pivot_fitter::RUNTIME_PREFIX,
            fit_time.as_secs_f64()
        );
        (table, runtime)
    };
    let start = Instant::now();
    let (l1, leak) = pivot_fitter::table_errors(&table, threads);
    let ltc_l1 = ltc_fitter::table_l1(&ltc_fitter::parse_table(&read(&ltc_path)), threads);
    println!("measured the L1 errors in {:.2?}", start.elapsed());
    println!("| cells | SPTD mean | SPTD max | at | LTC mean | LTC max | SPTD leak |");
    print!(
        "{}",
        pivot_fitter::error_summary(&l1, &leak, &ltc_l1).replace("//! ", "")
    );
    std::fs::write(
        &path,
        pivot_fitter::render(&table, &l1, &leak, &ltc_l1, &runtime),
    )
    .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    println!("wrote {}", path.display());
}
