//! C ABI, `sphera_arvo_projected_polygon_*`: Arvo's projected solid angle sampling, a
//! baseline.
use super::polygon::prepare;
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::Sample;
use crate::polygon::baselines::ArvoProjectedPolygon;

/// Prepares Arvo's projected solid angle sampling (the baseline of Peters 2021: the same
/// sectors, with the azimuth found by Newton's method on the sector's area function) for
/// the convex polygon `vertices[0..count]`. Same input and contract as
/// `sphera_projected_polygon_prepare`, without the small-polygon alternative.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_projected_polygon_prepare(
    out: *mut ArvoProjectedPolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, ArvoProjectedPolygon::prepare) }
}

/// Draws a direction with density cos θ / Φ by Arvo's method from `u0`, `u1` in [0, 1); the
/// pdf is `dir.z / Φ`, as `sphera_arvo_projected_polygon_pdf` gives it for the direction.
/// No sample also for a draw exactly on the horizon, and when the f32 construction puts the
/// direction outside the polygon. A baseline: **unreliable for polygons below about 2e-3
/// rad across**, where such draws are many (measured on quads at distance 1: 0.06% of the
/// draws at 2e-3 rad across, 5.9% at 2e-4, 79% at 2e-5).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_projected_polygon_sample(
    polygon: *const ArvoProjectedPolygon,
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

/// `dir.z / Φ` inside the polygon and above the horizon, 0 otherwise (and 0 when
/// `polygon` is null or empty, or `dir` is zero or not finite).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_projected_polygon_pdf(
    polygon: *const ArvoProjectedPolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// The projected solid angle Φ in steradians (0 when `polygon` is null or empty).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_projected_polygon_projected_solid_angle(
    polygon: *const ArvoProjectedPolygon,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.projected_solid_angle()) }
}
