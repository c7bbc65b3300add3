//! The committed determinism table is what the Rust entry points compute now: a change
//! in numerics must come with the regenerated table
//! (`cargo run -p sphera-tools --bin generate_determinism_table`), so that it shows in
//! review. `ffi-tests/test_determinism.c` checks the same table through the C ABI.

#[test]
fn determinism_table_is_current() {
    let path = sphera_tools::repository_root().join("ffi-tests/determinism_table.txt");
    let committed = std::fs::read_to_string(&path).expect("read the determinism table");
    let now = sphera_tools::generators::determinism::table();
    if committed != now {
        let first = committed
            .lines()
            .zip(now.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(committed.lines().count().min(now.lines().count()));
        panic!(
            "ffi-tests/determinism_table.txt differs from the samplers' output from line {} on \
             (regenerate it with `cargo run -p sphera-tools --bin generate_determinism_table` \
             if the change in numerics is intended):\ncommitted: {:?}\nnow:       {:?}",
            first + 1,
            committed.lines().nth(first),
            now.lines().nth(first)
        );
    }
    assert!(now.lines().count() > 400, "the table is too small");
}
