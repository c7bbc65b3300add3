//! sphera's std tools, by purpose: generators, fitters, measurements, invariants; and
//! the paths of the repository.
use std::path::PathBuf;

/// The repository root (the directory holding the core's Cargo.toml).
pub fn repository_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tools/ has a parent")
        .to_path_buf()
}

/// What writes committed files: the generated clipping code and sorting networks, the C
/// header, the determinism table.
pub mod generators {
    pub mod clipping_generator;
    pub mod determinism;
    pub mod header;
    pub mod sorting_network_generator;
}

/// What fits committed tables: the LTC and GGX pivot tables, the fast functions'
/// coefficients.
pub mod fitters {
    pub mod fast_function_fitter;
    pub mod ltc_fitter;
    pub mod pivot_fitter;
}

/// What measures: the error tables (SGs, sphere-light shading), the benchmarks' timer,
/// the VSGL references the benchmarks and the tracer compare with.
pub mod measurements {
    pub mod bench;
    pub mod sg_error;
    pub mod sphere_shading_error;
    pub mod vsgl_kmeans;
    pub mod vsgl_pyramid;
}

/// What must always hold: the C ABI's invariants, checked by the fuzz targets and by
/// the replay of their corpora.
pub mod invariants {
    pub mod abi_invariants;
}
