//! Generation of the C header `include/sphera.h` with cbindgen, used as a library.

use std::path::PathBuf;

use crate::repository_root;

/// Where the committed header lives.
pub fn header_path() -> PathBuf {
    repository_root().join("include").join("sphera.h")
}

/// The header that cbindgen generates from the core crate with `cbindgen.toml`.
///
/// Panics when the configuration cannot be read or the crate cannot be parsed; this is
/// a development tool, and the panic message says what went wrong.
pub fn generate() -> String {
    let root = repository_root();
    let config_path = root.join("cbindgen.toml");
    let config = cbindgen::Config::from_file(&config_path)
        .unwrap_or_else(|error| panic!("cannot read {}: {error}", config_path.display()));
    let bindings = cbindgen::Builder::new()
        .with_crate(&root)
        .with_config(config)
        .generate()
        .unwrap_or_else(|error| panic!("cbindgen failed on {}: {error}", root.display()));
    let mut bytes = Vec::new();
    bindings.write(&mut bytes);
    String::from_utf8(bytes).expect("cbindgen writes UTF-8")
}
