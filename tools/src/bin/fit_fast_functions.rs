//! Writes the fast functions' polynomial coefficients
//! `src/math/fast_functions_generated.rs` (see `tools/src/fitters/fast_function_fitter.rs`), after
//! a table of the minimax errors for neighbouring coefficient counts.
//!
//! Run with `cargo run --release -p sphera-tools --bin fit_fast_functions`; with `--check`
//! it writes nothing and fails if the committed file differs from the fitter's output.
use sphera_tools::fitters::fast_function_fitter;

fn main() {
    let path = sphera_tools::repository_root().join("src/math/fast_functions_generated.rs");
    let check = std::env::args().any(|a| a == "--check");
    for problem in fast_function_fitter::problems() {
        for count in problem.count - 1..=problem.count + 1 {
            println!(
                "{}: {count} coefficients, relative minimax error {:.3e}{}",
                problem.name,
                fast_function_fitter::minimax_error_with(&problem, count),
                if count == problem.count {
                    " (used)"
                } else {
                    ""
                }
            );
        }
    }
    let fits = fast_function_fitter::problems().map(|p| fast_function_fitter::fit(&p));
    for f in &fits {
        println!(
            "{}: f32 coefficients {:?}, relative error {:.3e} ({:.3} f32 ulps of 2^-23)",
            f.problem.name,
            f.coefficients,
            f.error,
            f.error / f32::EPSILON as f64
        );
    }
    let text = fast_function_fitter::render(&fits);
    if check {
        let committed = std::fs::read_to_string(&path)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
        if committed != text {
            eprintln!("{} differs from the fitter's output", path.display());
            std::process::exit(1);
        }
        println!("{} is current", path.display());
    } else {
        std::fs::write(&path, text)
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
        println!("wrote {}", path.display());
    }
}
