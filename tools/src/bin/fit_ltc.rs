//! Fits the LTC table of the GGX BRDF and writes `src/brdf/ltc_table.rs`.
//!
//! Run with `cargo run --release -p sphera-tools --bin fit_ltc [-- --threads N]` (default:
//! all cores; the output does not depend on the thread count). With `--render-only` it
//! keeps the committed cells and only re-measures their errors and rewrites the
//! documentation (for changes of the renderer, not of the fit).
use sphera_tools::fitters::ltc_fitter::{self, TABLE_SIZE};
use std::time::Instant;

fn main() {
    let (threads, render_only) = ltc_fitter::fitter_arguments();
    let path = sphera_tools::repository_root().join("src/brdf/ltc_table.rs");
    let table = if render_only {
        let text = std::fs::read_to_string(&path)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
        ltc_fitter::parse_table(&text)
    } else {
        let start = Instant::now();
        let (table, evaluations) = ltc_fitter::fit_table(threads);
        let fit_time = start.elapsed();
        println!(
            "fitted {} cells on {threads} thread(s) in {fit_time:.2?} \
             ({evaluations} objective evaluations)",
            table.len()
        );
        table
    };
    let start = Instant::now();
    let errors = ltc_fitter::table_l1(&table, threads);
    println!("measured the L1 errors in {:.2?}", start.elapsed());
    print!("{}", ltc_fitter::error_summary(&errors).replace("//! ", ""));
    println!("L1 per row (mean over the columns) and per column (mean over the rows):");
    for (name, index) in [
        (
            "row",
            &(|k: usize| k / TABLE_SIZE) as &dyn Fn(usize) -> usize,
        ),
        ("column", &|k: usize| k % TABLE_SIZE),
    ] {
        let mut sums = vec![0.0; TABLE_SIZE];
        for (k, e) in errors.iter().enumerate() {
            sums[index(k)] += e / TABLE_SIZE as f64;
        }
        let line: Vec<String> = sums.iter().map(|s| format!("{s:.3}")).collect();
        println!("  {name}: {}", line.join(" "));
    }
    std::fs::create_dir_all(path.parent().expect("a parent directory"))
        .unwrap_or_else(|e| panic!("cannot create the directory of {}: {e}", path.display()));
    std::fs::write(&path, ltc_fitter::render(&table, &errors))
        .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    println!("wrote {}", path.display());
}
