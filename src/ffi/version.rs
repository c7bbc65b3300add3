//! C ABI: the library's version and build (`sphera_version`, `sphera_check_version`,
//! `sphera_has_hardware_fma`).
use crate::math::HAS_HARDWARE_FMA;

/// Whether the library was compiled to use hardware fused multiply-add instructions
/// (otherwise the error-free products are emulated, which is slower but as accurate).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_has_hardware_fma() -> bool {
    HAS_HARDWARE_FMA
}

/// The library's version and build as a NUL-terminated string: the `version` of its
/// `Cargo.toml` (`MAJOR.MINOR.PATCH`), followed by `+fma` in a build that uses hardware
/// fused multiply-add (`sphera_has_hardware_fma()`), e.g. `"0.1.0"` or `"0.1.0+fma"`.
/// The two builds give results that differ in the last bits (the determinism table,
/// `ffi-tests/determinism_table.txt`, records the default build), so a cache of images
/// or values computed with the library must key on this whole string, not on the
/// version alone. The pointer is to static storage: never free it.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_version() -> *const core::ffi::c_char {
    // `concat!` appends the terminating NUL at compile time, so the bytes form a
    // valid C string with no interior NUL (a version string has none).
    #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
    let version = concat!(env!("CARGO_PKG_VERSION"), "+fma\0");
    #[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
    let version = concat!(env!("CARGO_PKG_VERSION"), "\0");
    version.as_ptr().cast()
}

/// A decimal number of `Cargo.toml`'s version (`CARGO_PKG_VERSION_MAJOR`, ...), parsed
/// at compile time; a non-digit fails the build.
const fn parse_version_number(text: &str) -> u32 {
    let bytes = text.as_bytes();
    assert!(!bytes.is_empty(), "empty version number");
    let mut value: u32 = 0;
    let mut i = 0;
    while i < bytes.len() {
        assert!(bytes[i].is_ascii_digit(), "version number with a non-digit");
        value = value * 10 + (bytes[i] - b'0') as u32;
        i += 1;
    }
    value
}

/// The library's major version (the first number of `Cargo.toml`'s `version`).
const VERSION_MAJOR: u32 = parse_version_number(env!("CARGO_PKG_VERSION_MAJOR"));

/// The library's minor version.
const VERSION_MINOR: u32 = parse_version_number(env!("CARGO_PKG_VERSION_MINOR"));

/// Whether this library serves a program compiled against the header of version
/// `major.minor`; call it as
/// `sphera_check_version(SPHERA_VERSION_MAJOR, SPHERA_VERSION_MINOR)` once at start-up
/// to catch a header and a library from different releases (the `SPHERA_VERSION_*`
/// macros are the header's version, `sphera_version()` the library's).
///
/// Returns `true` when `major` equals the library's major version and either the
/// major version is 0 and `minor` equals the library's minor version (before 1.0 every
/// minor release may change the prepared structs and the functions), or the major
/// version is 1 or more and `minor` is at most the library's minor version (a later
/// minor release only adds). The patch number is not compared: patch releases change
/// neither layouts nor contracts. `false` otherwise.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_check_version(major: u32, minor: u32) -> bool {
    major == VERSION_MAJOR
        && if VERSION_MAJOR == 0 {
            minor == VERSION_MINOR
        } else {
            minor <= VERSION_MINOR
        }
}
