//! Projected solid angle sampling of polygons (Peters 2021, Algorithms 1–4): directions
//! distributed in proportion to cos θ inside a polygonal light, and Arvo's method, the
//! paper's baseline for it.
//!
//! Vertices are given relative to the shading point in the local frame (z = normal),
//! convex, in either winding, 3 to `SPHERA_MAX_POLYGON_VERTICES` of them. The part
//! below the horizon is clipped away internally.
use super::polygon::prepare;
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::Sample;
use crate::polygon::ProjectedPolygon;

/// Prepares projected solid angle sampling (Peters 2021) for the convex polygon
/// `vertices[0..count]` (not normalised). The part below the horizon is clipped away.
/// Polygons smaller than 1e-2 rad across, and nearly edge-on slivers, are sampled by warped
/// solid angle sampling instead (exact for its own pdf, which deviates from cos θ / Φ by
/// less than 1e-4 relative).
///
/// Returns `false` also when `count` is `SPHERA_MAX_POLYGON_VERTICES` and the polygon
/// crosses the horizon (a 9th vertex would be needed), when nothing of the polygon lies
/// above the horizon, and when its projected solid angle is zero (for example when the
/// shading point lies in the polygon's plane).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_projected_polygon_prepare(
    out: *mut ProjectedPolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, ProjectedPolygon::prepare) }
}

/// `sphera_projected_polygon_prepare` for the biased variant: the sector areas use a
/// fast `atan` (relative error below 1.4e-4 per sector, amplified where inner and outer
/// sector areas nearly cancel), so the projected solid angle and with it every pdf is
/// off by about that much. **Biased.** Same contract as
/// `sphera_projected_polygon_prepare`. Use with `sphera_projected_polygon_sample_fast`.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_projected_polygon_prepare_fast(
    out: *mut ProjectedPolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, ProjectedPolygon::prepare_fast_biased) }
}

/// Draws a direction with density cos θ / Φ inside the polygon from the random numbers
/// `u0`, `u1` in [0, 1). The pdf is per steradian, `dir.z / Φ`, equal to
/// `sphera_projected_polygon_pdf(polygon, dir)` bit for bit wherever that finds the
/// direction inside the polygon. For polygons under 1e-2 rad (the small-polygon sampler)
/// the draws follow `dir.z / Φ` within 0.2 s² relative (2e-5; s is the polygon's angular
/// size). Where a polygon crosses the horizon, its clipped part is accurate to the f32
/// rounding of the horizon points: Φ within about 6e-8 / w relative for a clipped part w
/// radians wide (solid angle over perimeter).
///
/// No sample also for a draw that lands exactly on the horizon (`cos θ = 0`, possible only
/// for polygons that touch it).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_projected_polygon_sample(
    polygon: *const ProjectedPolygon,
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

/// The biased variant of `sphera_projected_polygon_sample`: no refinement iterations
/// (the azimuth is the closed-form initial guess of Peters' Proposition 3, within a few
/// hundredths of a radian of the exact one). **Biased**: the returned pdf is that of the
/// exact distribution, `dir.z / Φ`, not the density with which this function actually
/// places its samples; the bias is the distance between the two. Same contract as
/// `sphera_projected_polygon_sample`.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_projected_polygon_sample_fast(
    polygon: *const ProjectedPolygon,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe {
        with_ref(polygon, Sample::NONE.into(), |polygon| {
            polygon.sample_fast([u0, u1]).into()
        })
    }
}

/// The density per steradian with which `sphera_projected_polygon_sample` produces the
/// direction `dir` (need not be normalised): `dir.z / Φ` inside the polygon, 0 outside
/// it, at or below the horizon, and for a zero or non-finite `dir`. For polygons under
/// 1e-2 rad (the small-polygon sampler) directions outside by at most the smaller of 16
/// ulps (1.9e-6 rad) and 2e-5 of the polygon's width count as inside.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_projected_polygon_pdf(
    polygon: *const ProjectedPolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// The projected solid angle Φ = ∫ cos θ dω of the polygon's part above the horizon, in
/// steradians (the irradiance from a unit-radiance polygon).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_projected_polygon_projected_solid_angle(
    polygon: *const ProjectedPolygon,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.projected_solid_angle()) }
}
