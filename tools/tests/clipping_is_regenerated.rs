//! The committed clipping code must be exactly what the generator produces.

#[test]
fn committed_clipping_code_is_the_generator_output() {
    let path = sphera_tools::repository_root().join("src/polygon/clip_generated.rs");
    let committed = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let generated = sphera_tools::generators::clipping_generator::generate();
    assert!(
        committed == generated,
        "{} is stale: refresh it with `cargo run -p sphera-tools --bin generate_clipping` \
         (never edit it by hand)",
        path.display()
    );
}
