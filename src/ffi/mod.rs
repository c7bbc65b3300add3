//! The C ABI: thin wrappers over the safe core, one file per C prefix (`ggx.rs` holds
//! `sphera_ggx_*`, `solid_angle_polygon.rs` `sphera_solid_angle_polygon_*`, ...), no logic beyond
//! the null-pointer and count contract that C callers rely on.
//!
//! Every exported function is `extern "C"` with an unmangled `sphera_` name; the header
//! `include/sphera.h` is generated from these declarations by cbindgen
//! (`cargo run -p sphera-tools --bin generate_header`). The conventions shared by all
//! functions, which the header's preamble states and each function's documentation does
//! not repeat (a `# Safety` section that says only "Pointers as in the conventions" is left
//! out of the header):
//!
//! - directions are in a local shading frame whose z axis is the surface normal; light
//!   geometry is relative to the shading point; pdfs are per steradian;
//! - random numbers `u0`, `u1` lie in `[0, 1)`; they are passed through unchanged and the
//!   core clamps other values into it (NaN as 0);
//! - "no sample" is `{dir = (0, 0, 1), pdf = 0}`; a sampled `dir` is always a finite unit
//!   vector;
//! - pointers: no function crashes on a null pointer (each says what it does then); a
//!   non-null pointer points to one value of its type (`count` for an array), writable for
//!   an output, readable for an input, and inputs do not overlap the output; a prepared
//!   value was written by a function that prepares it (a failed prepare included);
//! - polygons: `vertices[0..count]` are convex, either winding, `3 <= count <=
//!   SPHERA_MAX_POLYGON_VERTICES`; a `prepare` returns `false` for a null `out` or
//!   `vertices`, a count out of range or a non-finite coordinate, and in the cases its
//!   documentation lists;
//! - a failed `prepare` still writes `*out` (unless null), whatever it held: the empty value,
//!   with no samples, pdf 0 and measures (solid angle, integral) 0; given a null or empty
//!   prepared value, samplers return no sample and the other functions 0 or `false`;
//! - no Rust panic crosses the boundary (the core does not panic, and the static
//!   library's panic handler aborts).

// The order of these modules matters to cbindgen (and each stands alone so that rustfmt
// keeps it): cbindgen emits a struct where a function first uses it, and it cannot see
// that the core's structs hold glam's `Vec3` (shown as `SpheraVec3`). The first
// function, `sphera_polygon_clip`, uses `SpheraVec3` before any function uses such a
// struct, so the header defines `SpheraVec3` first. The C ABI tests compile the header,
// which catches a wrong order.
mod types;

mod polygon;

mod solid_angle_polygon;

mod solid_angle_triangle;

mod solid_angle_quad;

mod turk_polygon;

mod arvo_polygon;

mod frame;

mod version;

mod hart;

mod clipped_solid_angle_polygon;

mod projected_polygon;

mod arvo_projected_polygon;

mod ggx;

mod lambert;

mod mis;

mod ltc;

mod polygon_light;

mod phase;

mod cap;

mod solid_angle_sphere;

mod cap_union;

mod pivot;

mod sptd;

mod sphere_light;

mod vsgl;

mod sg;

mod vmf;

mod asg;

mod sg_shading_point;

pub use arvo_polygon::*;
pub use arvo_projected_polygon::*;
pub use asg::*;
pub use cap::*;
pub use cap_union::*;
pub use clipped_solid_angle_polygon::*;
pub use frame::*;
pub use ggx::*;
pub use hart::*;
pub use lambert::*;
pub use ltc::*;
pub use mis::*;
pub use phase::*;
pub use pivot::*;
pub use polygon::*;
pub use polygon_light::*;
pub use projected_polygon::*;
pub use sg::*;
pub use sg_shading_point::*;
pub use solid_angle_polygon::*;
pub use solid_angle_quad::*;
pub use solid_angle_triangle::*;
pub use sphere_light::*;
pub use sptd::*;
pub use turk_polygon::*;
pub use types::*;
pub use version::*;
pub use vmf::*;
pub use vsgl::*;

/// The precompiled `core` of hosted targets is built with unwinding, and its object
/// file refers to `rust_eh_personality` (a `DW.ref.rust_eh_personality` data word), even
/// though this library is built with `panic = "abort"` and never unwinds. Rust's `std`
/// defines that symbol; a `no_std` static library has nothing that does, so a C program
/// linking `libsphera.a -lm` would fail with "undefined reference to
/// `rust_eh_personality`" (the crate types `staticlib` + `rlib` also keep Cargo from
/// running LTO, which could otherwise drop the reference). This definition satisfies
/// the linker. It is never called: nothing in the library unwinds, and an unwinder that
/// still reached a Rust frame gets a fatal error code back and terminates.
/// `tools/tests/c_abi.rs` checks that the archive leaves no such symbol undefined.
#[cfg(all(
    not(test),
    not(feature = "std"),
    panic = "abort",
    not(target_os = "none")
))]
mod personality {
    /// `_URC_FATAL_PHASE1_ERROR` of the Itanium C++ ABI's unwinder.
    const FATAL_ERROR: i32 = 3;

    /// cbindgen:ignore
    #[unsafe(no_mangle)]
    extern "C" fn rust_eh_personality() -> i32 {
        FATAL_ERROR
    }
}
