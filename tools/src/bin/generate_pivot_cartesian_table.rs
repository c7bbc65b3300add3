//! Writes `src/brdf/pivot_cartesian_table.rs`, the pivot table `src/brdf/pivot_table.rs` in
//! Cartesian form (`pivot_fitter::render_cartesian`): `cargo run --release -p sphera-tools
//! --bin generate_pivot_cartesian_table`. Run it after `fit_pivot`.
use sphera_tools::fitters::pivot_fitter;

fn main() {
    let root = sphera_tools::repository_root();
    let source = root.join("src/brdf/pivot_table.rs");
    let path = root.join("src/brdf/pivot_cartesian_table.rs");
    let text = std::fs::read_to_string(&source)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", source.display()));
    let table = pivot_fitter::parse_table(&text);
    std::fs::write(&path, pivot_fitter::render_cartesian(&table))
        .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    println!("wrote {}", path.display());
}
