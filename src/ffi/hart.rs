//! C ABI, `sphera_hart_bilinear_polygon_*` and `sphera_hart_biquadratic_polygon_*`: the
//! bilinear and biquadratic cosine warps of solid angle sampling (Hart et al. 2020).
use super::polygon::prepare;
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::Sample;
use crate::polygon::baselines::{HartBilinearPolygon, HartBiquadraticPolygon};

/// Prepares the bilinear warp of Hart et al. 2020 for the convex polygon
/// `vertices[0..count]`: solid angle sampling whose primary square is warped by the
/// bilinear density through the cosine at its four corners, which approximates
/// cosine-weighted sampling (the pdf is exact for the samples drawn). The polygon is not
/// clipped: samples below the horizon are no sample, and when the cosine is 0 at all four
/// corners the warp is uniform.
///
/// Returns `false` also when the polygon subtends no solid angle.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_hart_bilinear_polygon_prepare(
    out: *mut HartBilinearPolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, HartBilinearPolygon::prepare) }
}

/// Draws a direction with the bilinear warp from the random numbers `u0`, `u1` in [0, 1).
/// The pdf is the warp's density divided by the solid angle, per steradian.
///
/// No sample also when the direction lies at or below the horizon (z <= 0).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_hart_bilinear_polygon_sample(
    polygon: *const HartBilinearPolygon,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe {
        with_ref(polygon, Sample::NONE.into(), |polygon| {
            polygon.sample([u0, u1]).into()
        })
    }
}

/// The density per steradian with which `sphera_hart_bilinear_polygon_sample` produces
/// the direction `dir` (need not be normalised); 0 outside the polygon and at or below
/// the horizon (z <= 0).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_hart_bilinear_polygon_pdf(
    polygon: *const HartBilinearPolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// Prepares Hart et al. 2020's biquadratic warp of solid angle sampling (the cosine at the
/// 3×3 grid {0, 1/2, 1}², negative control points clamped), close to cosine-weighted sampling;
/// its pdf is exact. Not clipped: samples below the horizon are no sample.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_hart_biquadratic_polygon_prepare(
    out: *mut HartBiquadraticPolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, HartBiquadraticPolygon::prepare) }
}

/// Draws a direction with the biquadratic warp from the random numbers `u0`, `u1` in [0,
/// 1). The pdf is the warp's density divided by the solid angle, per steradian.
///
/// No sample also when the direction lies at or below the horizon (z <= 0).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_hart_biquadratic_polygon_sample(
    polygon: *const HartBiquadraticPolygon,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe {
        with_ref(polygon, Sample::NONE.into(), |polygon| {
            polygon.sample([u0, u1]).into()
        })
    }
}

/// The density per steradian with which `sphera_hart_biquadratic_polygon_sample`
/// produces the direction `dir` (need not be normalised); 0 outside the polygon and at
/// or below the horizon (z <= 0).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_hart_biquadratic_polygon_pdf(
    polygon: *const HartBiquadraticPolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}
