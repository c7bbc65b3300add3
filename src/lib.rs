//! # sphera
//!
//! Sampling and shading of area lights for renderers written in C, C++ and Rust:
//! polygonal lights (Peters 2021), sphere lights (Dupuy et al. 2017) and virtual
//! spherical Gaussian lights (Tokuyoshi 2016).
//!
//! The core is `no_std`, allocates nothing and computes in `f32`. Every technique has
//! the same shape: a prepared `repr(C)` value built once per shading point and light,
//! `sample(u) -> Sample`, `pdf(dir)` and, where the maths allows, `invert(dir)`.
//!
//! Conventions: directions are unit vectors in a local shading frame whose z axis is the
//! surface normal; light geometry is given relative to the shading point; pdfs are per
//! steradian; random numbers lie in `[0, 1)`; `pdf == 0` means "no sample".
#![cfg_attr(not(any(test, feature = "std")), no_std)]
#![deny(unsafe_op_in_unsafe_fn)]
// Bad input must never produce NaN, so comparisons are written to be false for NaN on
// purpose (`!(x > 0.0)` rejects NaN, `x.max(0.0).min(1.0)` maps NaN to 0 where `clamp`
// would propagate it).
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::manual_clamp)]
// glam's `length` / `normalize` family is disallowed in the library (clippy.toml: its
// square root is libm's legacy-SSE `sqrtss`; src/math/length.rs has the same bits on
// `math::sqrtf`); the tests use glam's as their references.
#![cfg_attr(test, allow(clippy::disallowed_methods))]

pub mod brdf;
pub mod ffi;
pub mod math;
pub mod mis;
pub mod polygon;
mod sample;
pub mod sg;
pub mod sphere;
pub mod vsgl;

#[cfg(test)]
pub(crate) mod testing;

#[cfg(all(test, target_arch = "x86_64"))]
mod float_environment_tests;

#[cfg(test)]
mod direction_scale_tests;

pub use glam::Vec3;
pub use sample::Sample;

/// The most vertices a polygon may have after clipping to the upper hemisphere.
pub const MAX_POLYGON_VERTICES: usize = 8;

/// The static library must not unwind into C, and a `no_std` staticlib has no panic
/// handler of its own. The core is written not to panic on any input (the C ABI tests
/// drive it with adversarial values); should a panic still happen, the process aborts
/// instead of unwinding across the C boundary (hosted targets), or halts (bare metal,
/// where no `abort` exists).
#[cfg(not(any(test, feature = "std")))]
#[panic_handler]
fn panic(_info: &core::panic::PanicInfo) -> ! {
    #[cfg(not(target_os = "none"))]
    {
        unsafe extern "C" {
            fn abort() -> !;
        }
        // SAFETY: `abort` from the C library takes no arguments and never returns.
        unsafe { abort() }
    }
    #[cfg(target_os = "none")]
    loop {
        core::hint::spin_loop();
    }
}
