//! Writes `include/sphera.h` from the core crate's C ABI (see `cbindgen.toml`).
//!
//! Run with `cargo run -p sphera-tools --bin generate_header`.

fn main() {
    let path = sphera_tools::generators::header::header_path();
    let header = sphera_tools::generators::header::generate();
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)
            .unwrap_or_else(|error| panic!("cannot create {}: {error}", dir.display()));
    }
    std::fs::write(&path, header)
        .unwrap_or_else(|error| panic!("cannot write {}: {error}", path.display()));
    println!("wrote {}", path.display());
}
