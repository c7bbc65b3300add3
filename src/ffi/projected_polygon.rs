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

/// Prepares projected solid angle sampling (Peters 2021) of the polygon's part above the
/// horizon. Polygons under 1e-2 rad across and edge-on slivers take warped solid angle
/// sampling (its pdf within 1e-4 relative of cos θ / Φ). Returns `false` also when a
/// polygon of `SPHERA_MAX_POLYGON_VERTICES` crosses the horizon (a 9th vertex would be
/// needed), and when the projected solid angle above the horizon is zero.
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

/// Draws a direction with density cos θ / Φ inside the polygon; its pdf `dir.z / Φ` is
/// `sphera_projected_polygon_pdf` at `dir`, bit for bit. Small polygons (under 1e-2 rad)
/// follow `dir.z / Φ` within 0.2 s² relative (s: angular size); a clipped part w radians
/// wide has Φ within about 6e-8 / w relative. No sample for a draw exactly on the horizon.
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
