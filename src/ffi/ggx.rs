//! C ABI, `sphera_ggx_*`: the GGX BRDF, its evaluation, visible-normal sampling and pdf.
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::brdf::GgxBrdf;
use crate::{Sample, Vec3};

/// The smallest GGX `α` (= roughness²) that `sphera_ggx_brdf_prepare` keeps; smaller
/// values are raised to it (see the Rust documentation of `brdf::ggx::MIN_ALPHA`).
pub const SPHERA_GGX_MIN_ALPHA: f32 = 1e-4;

const _: () = assert!(SPHERA_GGX_MIN_ALPHA == crate::brdf::ggx::MIN_ALPHA);

// ---- GGX ---------------------------------------------------------------------------

/// Prepares the GGX BRDF with perceptual roughness `roughness` (`α = roughness²`) and
/// Fresnel reflectance `f0` at normal incidence per RGB channel. `roughness` is clamped to
/// [0, 1] and `α` to [`SPHERA_GGX_MIN_ALPHA`, 1]; each channel of `f0` is clamped to [0,
/// 1]. Returns `false` when `out` is null, and when `roughness` or a channel of `f0` is NaN
/// or infinite; the latter still writes a usable BRDF (a NaN roughness counts as the
/// smoothest, NaN channels of `f0` as 0, infinities are clamped).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_brdf_prepare(
    out: *mut GgxBrdf,
    roughness: f32,
    f0: SpheraVec3,
) -> bool {
    if out.is_null() {
        return false;
    }
    let f0: Vec3 = f0.into();
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(GgxBrdf::new(roughness, f0)) };
    roughness.is_finite() && f0.is_finite()
}

/// The GGX BRDF `f(wo, wi) = F D G2 / (4 cos θo cos θi)` per RGB channel, without the
/// cosine `cos θi`. Symmetric in `wo` and `wi`.
///
/// Returns (0, 0, 0) when `brdf` is null, when either direction lies at or below the
/// horizon (z <= 0), is zero or is not finite. Never returns NaN or infinities.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_brdf_eval(
    brdf: *const GgxBrdf,
    wo: SpheraVec3,
    wi: SpheraVec3,
) -> SpheraVec3 {
    // SAFETY: the caller guarantees that a non-null `brdf` points to a prepared value.
    unsafe {
        with_ref(brdf, Vec3::ZERO.into(), |brdf| {
            brdf.eval(wo.into(), wi.into()).into()
        })
    }
}

/// `D G2 / (4 cos θo cos θi)`: `sphera_ggx_brdf_eval` with Fresnel F = 1 (a scalar).
///
/// Returns 0 in the cases where `sphera_ggx_brdf_eval` returns (0, 0, 0).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_brdf_eval_without_fresnel(
    brdf: *const GgxBrdf,
    wo: SpheraVec3,
    wi: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `brdf` points to a prepared value.
    unsafe {
        with_ref(brdf, 0.0, |brdf| {
            brdf.eval_without_fresnel(wo.into(), wi.into())
        })
    }
}

/// Draws `wi`: `wo` reflected on a normal drawn from GGX's visible normals (Dupuy and
/// Benyoub 2023), pdf `G1(wo) D(h) / (4 cos θo)` = `sphera_ggx_brdf_pdf(brdf, wo, dir)`.
/// No sample for a `wo` that is not finite, zero or at or below the horizon, and for a
/// reflection at or below the horizon (about half the draws at roughness 1 and normal
/// incidence: count it as a sample that contributes 0; do not renormalise the pdf).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_brdf_sample(
    brdf: *const GgxBrdf,
    wo: SpheraVec3,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `brdf` points to a prepared value.
    unsafe {
        with_ref(brdf, Sample::NONE.into(), |brdf| {
            brdf.sample(wo.into(), [u0, u1]).into()
        })
    }
}

/// The density per steradian with which `sphera_ggx_brdf_sample` draws `wi` given `wo`:
/// `G1(wo) D(h) / (4 cos θo)` with `h` the half vector of `wo` and `wi`.
///
/// Returns 0 when `brdf` is null, and when either direction lies at or below the
/// horizon, is zero or is not finite.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_brdf_pdf(
    brdf: *const GgxBrdf,
    wo: SpheraVec3,
    wi: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `brdf` points to a prepared value.
    unsafe { with_ref(brdf, 0.0, |brdf| brdf.pdf(wo.into(), wi.into())) }
}
