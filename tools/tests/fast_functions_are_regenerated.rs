//! The committed polynomial coefficients of the fast functions must be exactly what the
//! fitter produces (this re-runs every fit, a few seconds at opt-level 3).

#[test]
fn committed_fast_function_coefficients_are_the_fitter_output() {
    let path = sphera_tools::repository_root().join("src/math/fast_functions_generated.rs");
    let committed = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let generated = sphera_tools::fitters::fast_function_fitter::generate();
    assert!(
        committed == generated,
        "{} is stale: refresh it with \
         `cargo run --release -p sphera-tools --bin fit_fast_functions` \
         (never edit it by hand)",
        path.display()
    );
}
