//! Writes the bitonic sorting networks `src/polygon/sorting_networks_generated.rs`
//! (supplement A.6).
//!
//! Run with `cargo run --release -p sphera-tools --bin generate_sorting_networks`.
use sphera_tools::generators::sorting_network_generator;
use std::time::Instant;

fn main() {
    let path = sphera_tools::repository_root().join("src/polygon/sorting_networks_generated.rs");
    let mut networks = Vec::new();
    for n in 1..=sorting_network_generator::MAX_ELEMENTS {
        let start = Instant::now();
        let network = sorting_network_generator::optimal_network(n);
        println!(
            "{n} elements: {} comparisons, depth {}, {} states, {:.2?}: {:?}",
            network.comparators.len(),
            network.depth,
            network.visited_states,
            start.elapsed(),
            network.comparators
        );
        networks.push(network);
    }
    std::fs::write(&path, sorting_network_generator::render(&networks))
        .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    println!("wrote {}", path.display());
}
