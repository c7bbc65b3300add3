//! C ABI, `sphera_turk_polygon_*`: Turk's area sampling, the baseline.
use super::polygon::prepare;
use super::types::{
    CommonAndRareSamples, SpheraSample, SpheraVec3, sample_common_or_rare, with_ref,
};
use crate::Sample;
use crate::polygon::baselines::TurkPolygon;

/// Prepares Turk's baseline for the convex polygon `vertices[0..count]`: points
/// uniformly distributed over the polygon's area, with the density converted to solid
/// angle.
///
/// Returns `false` also when a coordinate exceeds about 1e18 (2^60) (so that the edge
/// planes that `sphera_turk_polygon_pdf` computes stay finite), or when the polygon is
/// degenerate.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_turk_polygon_prepare(
    out: *mut TurkPolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, TurkPolygon::prepare) }
}

/// Draws a direction towards a point uniformly distributed over the polygon's area from the
/// random numbers `u0`, `u1` in [0, 1). The pdf is distance² / (area · |cos θ|) per
/// steradian, with θ the angle between the direction and the polygon's normal, computed as
/// `sphera_turk_polygon_pdf` computes it: equal to it bit for bit wherever that finds the
/// direction inside the polygon.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_turk_polygon_sample(
    polygon: *const TurkPolygon,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { sample_common_or_rare(polygon, u0, u1) }
}

/// The density per steradian with which `sphera_turk_polygon_sample` produces the unit
/// direction `dir`; 0 when `dir` misses the polygon.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_turk_polygon_pdf(
    polygon: *const TurkPolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// The area of the polygon (in squared units of the vertex coordinates).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_turk_polygon_area(polygon: *const TurkPolygon) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.area()) }
}

impl CommonAndRareSamples for TurkPolygon {
    #[inline(always)]
    fn sample_common(&self, u: [f32; 2]) -> Option<Sample> {
        TurkPolygon::sample_common(self, u)
    }

    #[inline(always)]
    fn sample_rare(&self, u: [f32; 2]) -> Sample {
        TurkPolygon::sample_rare(self, u)
    }
}
