//! The committed `include/sphera.h` must be what cbindgen generates from the sources.

#[test]
fn committed_header_matches_a_fresh_generation() {
    let path = sphera_tools::header::header_path();
    let fresh = sphera_tools::header::generate();
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed != fresh {
        let first_difference = committed
            .lines()
            .zip(fresh.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| committed.lines().count().min(fresh.lines().count()));
        panic!(
            "{} is not current (first difference at line {}); \
             run `cargo run -p sphera-tools --bin generate_header` to refresh it",
            path.display(),
            first_difference + 1
        );
    }
}
