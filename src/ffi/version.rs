//! C ABI: the library's version and build (`sphera_version`, `sphera_check_version`,
//! `sphera_has_hardware_fma`).
use crate::math::HAS_HARDWARE_FMA;

/// Whether the library was compiled to use hardware fused multiply-add instructions
/// (otherwise the error-free products are emulated, which is slower but as accurate).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_has_hardware_fma() -> bool {
    HAS_HARDWARE_FMA
}

/// The library's version and build as a NUL-terminated string in static storage (never free
/// it): `Cargo.toml`'s `MAJOR.MINOR.PATCH`, followed by `+fma` in a build that uses
/// hardware fused multiply-add, e.g. `"0.1.0+fma"`. The two builds differ in the last bits,
/// so a cache of results must key on this whole string.
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

/// Whether this library serves a program built against header `major.minor` (call once with
/// `SPHERA_VERSION_MAJOR, SPHERA_VERSION_MINOR`): same major, and before 1.0 the same minor,
/// from 1.0 on a minor at most the library's. The patch number is not compared.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_check_version(major: u32, minor: u32) -> bool {
    major == VERSION_MAJOR
        && if VERSION_MAJOR == 0 {
            minor == VERSION_MINOR
        } else {
            minor <= VERSION_MINOR
        }
}
