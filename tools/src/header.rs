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
    let mut config = cbindgen::Config::from_file(&config_path)
        .unwrap_or_else(|error| panic!("cannot read {}: {error}", config_path.display()));
    // The version macros follow the includes (after anything `after_includes` of
    // cbindgen.toml adds), from the version in the core's Cargo.toml.
    let version = version_macros(&package_version());
    config.after_includes = Some(match config.after_includes.take() {
        Some(text) => format!("{text}\n{version}"),
        None => version,
    });
    let bindings = cbindgen::Builder::new()
        .with_crate(&root)
        .with_config(config)
        .generate()
        .unwrap_or_else(|error| panic!("cbindgen failed on {}: {error}", root.display()));
    let mut bytes = Vec::new();
    bindings.write(&mut bytes);
    String::from_utf8(bytes).expect("cbindgen writes UTF-8")
}

/// The `version` of the `[package]` section of the core's `Cargo.toml` (the repository
/// root's), e.g. `"0.1.0"`.
///
/// Panics when the file cannot be read or has no such line.
pub fn package_version() -> String {
    let path = repository_root().join("Cargo.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|error| panic!("cannot read {}: {error}", path.display()));
    let mut in_package = false;
    for line in text.lines().map(str::trim) {
        if line.starts_with('[') {
            in_package = line == "[package]";
            continue;
        }
        let value = line
            .strip_prefix("version")
            .map(str::trim_start)
            .and_then(|rest| rest.strip_prefix('='));
        if let (true, Some(value)) = (in_package, value) {
            return value.trim().trim_matches('"').to_string();
        }
    }
    panic!("{} has no version in [package]", path.display());
}

/// The header's version macros for `version` (`MAJOR.MINOR.PATCH`, optionally with a
/// pre-release or build suffix, which only the string keeps).
///
/// Panics when `version` does not start with three dot-separated numbers.
pub fn version_macros(version: &str) -> String {
    let core = version.split(['-', '+']).next().unwrap_or_default();
    let numbers: Vec<u32> = core
        .split('.')
        .map(|part| {
            part.parse()
                .unwrap_or_else(|_| panic!("version {version:?} is not MAJOR.MINOR.PATCH"))
        })
        .collect();
    let [major, minor, patch] = numbers[..] else {
        panic!("version {version:?} is not MAJOR.MINOR.PATCH");
    };
    format!(
        "
/*
 * The version of this header, from the library's Cargo.toml. The library says its own
 * with sphera_version(); check at start-up that the two agree with
 * sphera_check_version(SPHERA_VERSION_MAJOR, SPHERA_VERSION_MINOR).
 */
#define SPHERA_VERSION_MAJOR {major}
#define SPHERA_VERSION_MINOR {minor}
#define SPHERA_VERSION_PATCH {patch}
#define SPHERA_VERSION_STRING \"{version}\""
    )
}
