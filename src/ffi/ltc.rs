//! Linearly transformed cosines fitted to GGX (Heitz et al. 2016) and their sampling
//! inside polygonal lights (Peters 2021): `sphera_ltc_*`.

use super::polygon::prepare;
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::brdf::Ltc;
use crate::polygon::LtcPolygon;
use crate::{Sample, Vec3};

/// Looks up the LTC fitted to GGX `f(wo, ω) cos θ` (Fresnel 1, `α = roughness²`) for the
/// view `wo` (towards the viewer, need not be normalised) and `roughness` in [0, 1]
/// (clamped; NaN counts as 0), interpolated bilinearly in `roughness` and `√(1 − cos θ)`
/// and rotated to the view's azimuth.
///
/// Returns `false` when `out` is null, or when `wo` is not finite, zero, or at or below the
/// horizon; in the second case `*out` is set to the plain cosine (`M = I`, albedo 1,
/// fresnel 0).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ltc_prepare(out: *mut Ltc, wo: SpheraVec3, roughness: f32) -> bool {
    if out.is_null() {
        return false;
    }
    // Each arm writes its value (where `unwrap_or` went through a copy on the stack).
    match Ltc::from_ggx(wo.into(), roughness) {
        Some(ltc) => {
            // SAFETY: `out` is non-null and the caller guarantees it is writable.
            unsafe { out.write(ltc) };
            true
        }
        None => {
            // SAFETY: as above.
            unsafe { out.write(Ltc::IDENTITY) };
            false
        }
    }
}

/// The LTC's density per steradian at `dir` over the whole sphere (`dir` is normalised
/// first): `D(ω) = max(0, (M⁻¹ω)_z) det M⁻¹ / (π |M⁻¹ω|⁴)`. 0 for a null `ltc` and for
/// zero or non-finite `dir`.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ltc_eval(ltc: *const Ltc, dir: SpheraVec3) -> f32 {
    // SAFETY: the caller guarantees that a non-null `ltc` points to a valid value.
    unsafe { with_ref(ltc, 0.0, |ltc| ltc.density(dir.into())) }
}

/// GGX's directional albedo with Schlick's Fresnel for `f0` (per channel, clamped as in
/// `sphera_ggx_brdf_prepare`): `f0 (albedo − fresnel) + fresnel`; always finite, (0, 0, 0)
/// for a null `ltc`. Unshadowed GGX shading of a polygonal light of radiance `L` is
/// `L × sphera_ltc_specular_albedo(ltc, f0) × sphera_ltc_polygon_integral(polygon)`.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ltc_specular_albedo(ltc: *const Ltc, f0: SpheraVec3) -> SpheraVec3 {
    // SAFETY: the caller guarantees that a non-null `ltc` points to a valid value.
    unsafe {
        with_ref(ltc, Vec3::ZERO.into(), |ltc| {
            // Infinite or NaN channels gave non-finite albedos (found by the adversarial
            // C test): clamp as every other reflectance of the C ABI is clamped.
            let clamp = |c: f32| c.max(0.0).min(1.0);
            let f0 = Vec3::new(clamp(f0.x), clamp(f0.y), clamp(f0.z));
            ltc.specular_albedo(f0).into()
        })
    }
}

/// Prepares the LTC `*ltc` in the polygon: transformed by `M⁻¹`, clipped to that space's horizon,
/// prepared for projected solid angle sampling. Returns `false` also for a null `ltc` and when the
/// transformed polygon has no mass above its horizon (or needs a 9th vertex).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ltc_polygon_prepare(
    out: *mut LtcPolygon,
    ltc: *const Ltc,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    if ltc.is_null() {
        if !out.is_null() {
            // SAFETY: `out` is non-null and the caller guarantees it is writable.
            unsafe { out.write(LtcPolygon::EMPTY) };
        }
        return false;
    }
    // SAFETY: `ltc` is non-null and the caller guarantees it points to a valid value.
    let ltc = unsafe { &*ltc };
    // SAFETY: forwarded from the caller.
    unsafe {
        prepare(out, vertices, count, |out: &mut LtcPolygon, v: &[Vec3]| {
            out.prepare(ltc, v)
        })
    }
}

/// Draws a direction with density `D(ω) / ∫_P D` in the polygon, `sphera_ltc_polygon_pdf` at it
/// bit for bit (a draw that rounding throws outside is pulled inward). One at or below the
/// horizon contributes nothing and must not be redrawn.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ltc_polygon_sample(
    polygon: *const LtcPolygon,
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

/// The density of `sphera_ltc_polygon_sample` at `dir`: `D(ω) / ∫_P D` inside the polygon, up to
/// a slack in the LTC's cosine space (the smaller of 1e-5 rad and 2e-5 of the polygon's width)
/// where rounding puts samples; 0 outside.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ltc_polygon_pdf(
    polygon: *const LtcPolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// `∫_P D dω`, the LTC's mass inside the polygon, in [0, 1]: the projected solid angle
/// of the transformed polygon over π (Heitz et al. 2016), clamped to 1. 0 for a null or
/// empty `polygon`.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ltc_polygon_integral(polygon: *const LtcPolygon) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.integral()) }
}
