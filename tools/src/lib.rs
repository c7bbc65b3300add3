//! Shared code of sphera's std tools: paths of the repository.
use std::path::PathBuf;

/// The repository root (the directory holding the core's Cargo.toml).
pub fn repository_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tools/ has a parent")
        .to_path_buf()
}
pub mod abi_invariants;
pub mod bench;
pub mod clipping_generator;
pub mod determinism;
pub mod fast_function_fitter;
pub mod header;
pub mod ltc_fitter;
pub mod pivot_fitter;
pub mod sg_error;
pub mod sorting_network_generator;
pub mod sphere_shading_error;
pub mod vsgl_kmeans;
pub mod vsgl_pyramid;
