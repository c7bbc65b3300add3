//! C ABI, `sphera_solid_angle_polygon_*`: solid angle sampling of polygons (Peters 2021,
//! supplement C).
use super::polygon::prepare;
use super::types::{
    CommonAndRareSamples, SpheraSample, SpheraVec3, sample_common_or_rare, with_ref,
};
use crate::Sample;
use crate::polygon::{SolidAngleFan, SolidAnglePolygon};

/// Prepares the solid angle sampler (Peters 2021) for the convex polygon
/// `vertices[0..count]` (not normalised). The polygon need not be clipped; clip it first
/// with `sphera_polygon_clip` to sample only the part above the horizon.
///
/// Returns `false` also when the polygon subtends no solid angle, in particular when its
/// vertices lie exactly in a plane through the shading point (decided exactly, at any
/// tilt).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_polygon_prepare(
    out: *mut SolidAnglePolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, SolidAnglePolygon::prepare) }
}

/// Draws a direction uniformly distributed in the solid angle of `polygon` from the random
/// numbers `u0`, `u1` in [0, 1). The pdf of the sample is 1 / solid angle per steradian.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_polygon_sample(
    polygon: *const SolidAnglePolygon,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { sample_common_or_rare(polygon, u0, u1) }
}

/// The density per steradian with which `sphera_solid_angle_polygon_sample` produces
/// the direction `dir` (need not be normalised): 1 / solid angle inside the polygon
/// (boundary included, and up to a slack outside it where rounding puts samples drawn
/// next to an edge: the smaller of 16 ulps, 1.9e-6 rad, and 2e-5 of the polygon's width,
/// solid angle over perimeter), 0 outside it. Every sample's pdf is this function's
/// value at its direction, bit for bit.
///
/// Returns 0 also for a zero or non-finite `dir`.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_polygon_pdf(
    polygon: *const SolidAnglePolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// The solid angle (in steradians) that the polygon subtends.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_polygon_solid_angle(
    polygon: *const SolidAnglePolygon,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.solid_angle()) }
}

/// Inverts `sphera_solid_angle_polygon_sample`: finds the random numbers `*u0`, `*u1`
/// in [0, 1] for which the sampler produces the unit direction `dir`.
///
/// Returns `false` when `polygon`, `u0` or `u1` is null, when the polygon is empty, or
/// when `dir` does not point into the polygon; `*u0` and `*u1` are then set to 0 where
/// they are non-null.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_polygon_invert(
    polygon: *const SolidAnglePolygon,
    dir: SpheraVec3,
    u0: *mut f32,
    u1: *mut f32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { invert(polygon, dir, u0, u1) }
}

/// The shared body of the `invert` entry points of the three sizes.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[inline(always)]
pub(super) unsafe fn invert<const N: usize, const T: usize>(
    polygon: *const SolidAngleFan<N, T>,
    dir: SpheraVec3,
    u0: *mut f32,
    u1: *mut f32,
) -> bool {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    let inverted = match unsafe { polygon.as_ref() } {
        Some(polygon) if !u0.is_null() && !u1.is_null() => polygon.invert(dir.into()),
        _ => None,
    };
    let [v0, v1] = inverted.unwrap_or([0.0, 0.0]);
    if !u0.is_null() {
        // SAFETY: non-null, and the caller guarantees it is writable.
        unsafe { u0.write(v0) };
    }
    if !u1.is_null() {
        // SAFETY: non-null, and the caller guarantees it is writable.
        unsafe { u1.write(v1) };
    }
    inverted.is_some()
}

impl<const N: usize, const T: usize> CommonAndRareSamples for SolidAngleFan<N, T> {
    #[inline(always)]
    fn sample_common(&self, u: [f32; 2]) -> Option<Sample> {
        SolidAngleFan::sample_common(self, u)
    }

    #[inline(always)]
    fn sample_rare(&self, u: [f32; 2]) -> Sample {
        SolidAngleFan::sample_rare(self, u)
    }
}
