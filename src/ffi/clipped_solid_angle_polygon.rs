//! C ABI, `sphera_clipped_solid_angle_polygon_*`: solid angle sampling of the part of a
//! polygon above the horizon.
use super::polygon::prepare;
use super::types::{
    CommonAndRareSamples, SpheraSample, SpheraVec3, sample_common_or_rare, with_ref,
};
use crate::Sample;
use crate::polygon::ClippedSolidAnglePolygon;

/// Prepares clipped solid angle sampling for the convex polygon `vertices[0..count]` (not
/// normalised): the polygon is clipped to the upper hemisphere (z >= 0) and the part above
/// the horizon is sampled uniformly in solid angle.
///
/// Returns `false` also when nothing of the polygon lies above the horizon, when a polygon
/// of `SPHERA_MAX_POLYGON_VERTICES` vertices needs clipping (the result could have one
/// vertex more than the limit), or when the clipped polygon subtends no solid angle.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_clipped_solid_angle_polygon_prepare(
    out: *mut ClippedSolidAnglePolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, ClippedSolidAnglePolygon::prepare) }
}

/// Draws a direction uniformly distributed in the solid angle of the part of `polygon`
/// above the horizon from the random numbers `u0`, `u1` in [0, 1). The pdf of the sample is
/// 1 / (clipped solid angle) per steradian, and the direction has z >= 0.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_clipped_solid_angle_polygon_sample(
    polygon: *const ClippedSolidAnglePolygon,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { sample_common_or_rare(polygon, u0, u1) }
}

/// The density per steradian with which `sphera_clipped_solid_angle_polygon_sample`
/// produces the unit direction `dir`: 1 / (clipped solid angle) inside the part of the
/// polygon above the horizon, 0 elsewhere.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_clipped_solid_angle_polygon_pdf(
    polygon: *const ClippedSolidAnglePolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// The solid angle (in steradians) of the part of the polygon above the horizon.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_clipped_solid_angle_polygon_solid_angle(
    polygon: *const ClippedSolidAnglePolygon,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.solid_angle()) }
}

impl CommonAndRareSamples for ClippedSolidAnglePolygon {
    #[inline(always)]
    fn sample_common(&self, u: [f32; 2]) -> Option<Sample> {
        ClippedSolidAnglePolygon::sample_common(self, u)
    }

    #[inline(always)]
    fn sample_rare(&self, u: [f32; 2]) -> Sample {
        ClippedSolidAnglePolygon::sample_rare(self, u)
    }
}
