//! The committed sorting networks must be exactly what the generator produces (this
//! re-runs the whole search, a dozen seconds at opt-level 3).

#[test]
fn committed_sorting_networks_are_the_generator_output() {
    let path = sphera_tools::repository_root().join("src/polygon/sorting_networks_generated.rs");
    let committed = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let generated = sphera_tools::generators::sorting_network_generator::generate();
    assert!(
        committed == generated,
        "{} is stale: refresh it with \
         `cargo run --release -p sphera-tools --bin generate_sorting_networks` \
         (never edit it by hand)",
        path.display()
    );
}
