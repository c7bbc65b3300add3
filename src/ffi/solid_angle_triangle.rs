//! C ABI, `sphera_solid_angle_triangle_*`: solid angle sampling of a triangle (Peters 2021,
//! supplement C), the sampler of `sphera_solid_angle_polygon_*` in the storage of 3
//! vertices (172 bytes in place of 532).
use super::polygon::prepare;
use super::solid_angle_polygon::invert;
use super::types::{SpheraSample, SpheraVec3, sample_common_or_rare, with_ref};
use crate::polygon::SolidAngleTriangle;

/// Prepares the solid angle sampler (Peters 2021) for the triangle `vertices[0..3]` (not
/// normalised, either winding): `sphera_solid_angle_polygon_prepare` with `count = 3`,
/// the same samples and densities bit for bit, in a struct sized for 3 vertices.
///
/// `vertices` points to 3 vertices. Returns `false` for a null `out` or `vertices`, a
/// non-finite coordinate, and when the
/// triangle subtends no solid angle (in particular when its vertices lie exactly in a plane
/// through the shading point).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_triangle_prepare(
    out: *mut SolidAngleTriangle,
    vertices: *const SpheraVec3,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, 3, SolidAngleTriangle::prepare) }
}

/// Draws a direction uniformly distributed in the solid angle of `triangle` from the random
/// numbers `u0`, `u1` in [0, 1), as `sphera_solid_angle_polygon_sample`. The pdf of the
/// sample is 1 / solid angle per steradian.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_triangle_sample(
    triangle: *const SolidAngleTriangle,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `triangle` points to a prepared value.
    unsafe { sample_common_or_rare(triangle, u0, u1) }
}

/// The density per steradian with which `sphera_solid_angle_triangle_sample` produces the
/// direction `dir` (need not be normalised), as `sphera_solid_angle_polygon_pdf`: 1 /
/// solid angle inside (up to the same slack), 0 outside and for a zero or non-finite
/// `dir`. Every sample's pdf is this function's value at its direction, bit for bit.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_triangle_pdf(
    triangle: *const SolidAngleTriangle,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `triangle` points to a prepared value.
    unsafe { with_ref(triangle, 0.0, |triangle| triangle.pdf(dir.into())) }
}

/// The solid angle (in steradians) that the triangle subtends.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_triangle_solid_angle(
    triangle: *const SolidAngleTriangle,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `triangle` points to a prepared value.
    unsafe { with_ref(triangle, 0.0, |triangle| triangle.solid_angle()) }
}

/// Inverts `sphera_solid_angle_triangle_sample`, as `sphera_solid_angle_polygon_invert`:
/// the random numbers `*u0`, `*u1` in [0, 1] for which the sampler produces `dir`;
/// `false` (and 0 written where non-null) for a null pointer, an empty triangle, or a
/// `dir` outside it.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_triangle_invert(
    triangle: *const SolidAngleTriangle,
    dir: SpheraVec3,
    u0: *mut f32,
    u1: *mut f32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { invert(triangle, dir, u0, u1) }
}
