//! Writes `ffi-tests/determinism_table.txt`: every sampler over fixed inputs, outputs as
//! f32 bit patterns (see `sphera_tools::generators::determinism`).
//!
//! Run with `cargo run -p sphera-tools --bin generate_determinism_table`.

fn main() {
    let path = sphera_tools::repository_root().join("ffi-tests/determinism_table.txt");
    std::fs::write(&path, sphera_tools::generators::determinism::table())
        .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    println!("wrote {}", path.display());
}
