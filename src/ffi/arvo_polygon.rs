//! C ABI, `sphera_arvo_polygon_*`: Arvo 1995's solid angle sampling, a baseline.
use super::polygon::prepare;
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::Sample;
use crate::polygon::baselines::ArvoPolygon;

/// Prepares Arvo's 1995 baseline for the convex polygon `vertices[0..count]`: uniform
/// sampling of the solid angle, triangle by triangle.
///
/// Returns `false` also when the polygon subtends no solid angle, in particular when its
/// vertices lie exactly in a plane through the shading point (decided exactly, at any
/// tilt).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_polygon_prepare(
    out: *mut ArvoPolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, ArvoPolygon::prepare) }
}

/// Draws a direction uniform in solid angle by Arvo's method, pdf 1 / solid angle. A baseline:
/// **unreliable below about 1e-2 rad across**, where its f32 construction puts many draws outside
/// the polygon (no sample: 7.6% of draws at 2e-3 rad) and its solid angle is inaccurate.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_polygon_sample(
    polygon: *const ArvoPolygon,
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

/// The density per steradian with which `sphera_arvo_polygon_sample` produces the unit
/// direction `dir`: 1 / solid angle inside the polygon, 0 outside it.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_polygon_pdf(
    polygon: *const ArvoPolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// The solid angle (in steradians) that the polygon subtends, as Arvo's method computes
/// it.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_polygon_solid_angle(polygon: *const ArvoPolygon) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.solid_angle()) }
}
