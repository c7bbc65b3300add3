//! Writes the in-situ clipping code `src/polygon/clip_generated.rs` (supplement A.1).
//!
//! Run with `cargo run -p sphera-tools --bin generate_clipping`.
use sphera_tools::generators::clipping_generator;

fn main() {
    let path = sphera_tools::repository_root().join("src/polygon/clip_generated.rs");
    std::fs::write(&path, clipping_generator::generate())
        .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    let stats = clipping_generator::statistics();
    println!("wrote {}", path.display());
    println!("{stats:#?}");
}
