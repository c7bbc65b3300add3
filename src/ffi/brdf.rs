//! BRDFs (GGX with visible-normal sampling, Lambert) and multiple importance sampling
//! heuristics.
//!
//! Directions are in the local shading frame (z = normal), `wo` towards the viewer and
//! `wi` towards the light; they need not be normalised. BRDF values exclude the cosine
//! `cos θi`; pdfs are per steradian of `wi`.

use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::brdf::{GgxBrdf, Lambert};
use crate::{Sample, Vec3, mis};

/// The smallest GGX `α` (= roughness²) that `sphera_ggx_brdf_prepare` keeps; smaller
/// values are raised to it (see the Rust documentation of `brdf::ggx::MIN_ALPHA`).
pub const SPHERA_GGX_MIN_ALPHA: f32 = 1e-4;

/// The visibility estimate `v` that Peters 2021 uses for clamped optimal MIS.
pub const SPHERA_MIS_DEFAULT_VISIBILITY: f32 = 0.5;

const _: () = assert!(SPHERA_GGX_MIN_ALPHA == crate::brdf::ggx::MIN_ALPHA);
const _: () = assert!(SPHERA_MIS_DEFAULT_VISIBILITY == mis::DEFAULT_VISIBILITY);

// ---- GGX ---------------------------------------------------------------------------

/// Prepares the GGX microfacet BRDF (Trowbridge–Reitz distribution, height-correlated
/// Smith masking-shadowing, Schlick Fresnel) with perceptual roughness `roughness`
/// (`α = roughness²`) and Fresnel reflectance `f0` at normal incidence per RGB channel.
///
/// `roughness` is clamped to [0, 1] and `α` to the range from `SPHERA_GGX_MIN_ALPHA`
/// to 1; each channel of `f0` is clamped to [0, 1]. Returns `false` when `out` is null,
/// and when `roughness` or a channel of `f0` is NaN or infinite; the latter still
/// writes a usable BRDF into `*out` (a NaN roughness counts as the smoothest,
/// `α = SPHERA_GGX_MIN_ALPHA`; NaN channels of `f0` count as 0; infinities are
/// clamped).
///
/// # Safety
///
/// `out` must be null or point to writable memory for one `SpheraGgxBrdf`.
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
/// `brdf` must be null or point to a `SpheraGgxBrdf` written by
/// `sphera_ggx_brdf_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_eval(
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

/// `D G2 / (4 cos θo cos θi)`: `sphera_ggx_eval` with Fresnel F = 1 (a scalar).
///
/// Returns 0 in the cases where `sphera_ggx_eval` returns (0, 0, 0).
///
/// # Safety
///
/// `brdf` must be null or point to a `SpheraGgxBrdf` written by
/// `sphera_ggx_brdf_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_eval_without_fresnel(
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

/// Draws `wi` by sampling the GGX distribution of normals visible from `wo` (Heitz
/// 2018) and reflecting `wo` on the sampled normal, from the random numbers `u0`, `u1`
/// in [0, 1) (values outside are clamped by the library, NaN counts as 0). The pdf is
/// `G1(wo) D(h) / (4 cos θo)` per steradian and equals `sphera_ggx_pdf(brdf, wo, dir)`.
///
/// Returns `{dir = (0, 0, 1), pdf = 0}` (no sample) when `brdf` is null, when `wo`
/// lies at or below the horizon, is zero or is not finite, and when the reflected
/// direction lies at or below the horizon. The last case happens with positive
/// probability (about half the draws for roughness 1 at normal incidence): the pdf
/// then integrates to less than 1 over the upper hemisphere. Count such a draw as a
/// sample that contributes 0; do not renormalise the pdf.
///
/// # Safety
///
/// `brdf` must be null or point to a `SpheraGgxBrdf` written by
/// `sphera_ggx_brdf_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_sample(
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

/// The density per steradian with which `sphera_ggx_sample` draws `wi` given `wo`:
/// `G1(wo) D(h) / (4 cos θo)` with `h` the half vector of `wo` and `wi`.
///
/// Returns 0 when `brdf` is null, and when either direction lies at or below the
/// horizon, is zero or is not finite.
///
/// # Safety
///
/// `brdf` must be null or point to a `SpheraGgxBrdf` written by
/// `sphera_ggx_brdf_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_pdf(
    brdf: *const GgxBrdf,
    wo: SpheraVec3,
    wi: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `brdf` points to a prepared value.
    unsafe { with_ref(brdf, 0.0, |brdf| brdf.pdf(wo.into(), wi.into())) }
}

// ---- Lambert -------------------------------------------------------------------------

/// The Lambertian BRDF `albedo / π` per RGB channel (each channel of `albedo` clamped
/// to [0, 1], NaN to 0), without the cosine `cos θi`.
///
/// Returns (0, 0, 0) when either direction lies at or below the horizon (z <= 0), is
/// zero or is not finite.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_lambert_eval(
    albedo: SpheraVec3,
    wo: SpheraVec3,
    wi: SpheraVec3,
) -> SpheraVec3 {
    Lambert::new(albedo.into())
        .eval(wo.into(), wi.into())
        .into()
}

/// Draws a direction with density `cos θ / π` (cosine-weighted, by the concentric disk
/// mapping) from the random numbers `u0`, `u1` in [0, 1) (values outside are clamped by
/// the library, NaN counts as 0). Every draw lies strictly above the horizon and its
/// pdf equals `sphera_lambert_pdf(dir)`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_lambert_sample(u0: f32, u1: f32) -> SpheraSample {
    Lambert::default().sample([u0, u1]).into()
}

/// The density `max(0, cos θ) / π` per steradian with which `sphera_lambert_sample`
/// draws `wi`. Returns 0 when `wi` is zero or not finite.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_lambert_pdf(wi: SpheraVec3) -> f32 {
    Lambert::default().pdf(wi.into())
}

// ---- multiple importance sampling, two techniques -----------------------------------
//
// `p_this` is the density of the technique that drew the sample, `p_other` that of the
// other technique at the same direction; `c_this`, `c_other` their unoccluded
// contributions (Peters 2021). Shared conventions: NaN and negative pdfs count as 0; a
// technique whose pdf is 0 gets weight 0, and all weights are 0 when both pdfs are 0;
// infinite pdfs take the whole weight (shared when both are infinite); NaN, negative
// and infinite contributions count as 0; `v` is clamped to [0, 1] (NaN counts as 0); a
// contribution that is not finite is returned as 0. No function returns NaN or an
// infinity.

/// The balance heuristic `p_this / (p_this + p_other)`. The weights of the two
/// techniques sum to one wherever either pdf is positive.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_balance(p_this: f32, p_other: f32) -> f32 {
    mis::balance_heuristic(&[p_this, p_other], 0)
}

/// The power heuristic with exponent 2, `p_this² / (p_this² + p_other²)`, computed
/// without overflow. The weights sum to one wherever either pdf is positive.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_power(p_this: f32, p_other: f32) -> f32 {
    mis::power_heuristic(&[p_this, p_other], 0)
}

/// The weighted balance heuristic of Peters 2021,
/// `c_this p_this / (c_this p_this + c_other p_other)`, where `c_this`, `c_other` >= 0
/// are the techniques' unoccluded contributions. Falls back to the balance heuristic
/// where `c_this p_this + c_other p_other = 0`. The weights sum to one wherever either
/// pdf is positive.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_weighted_balance(
    p_this: f32,
    c_this: f32,
    p_other: f32,
    c_other: f32,
) -> f32 {
    mis::weighted_balance_heuristic(&[p_this, p_other], &[c_this, c_other], 0)
}

/// The contribution of a sample under optimal MIS as specialised by Peters 2021
/// (supplement B.1): `v c_this + (f - v (c_this p_this + c_other p_other)) /
/// (p_this + p_other)`, where `f` is the integrand at the sample and `v` in [0, 1] an
/// estimate of the visibility. This is already divided by the pdf: add the
/// contributions of one sample of each technique. It can be negative and is non-zero
/// where `f = 0`; the sum is unbiased for any `v`. A draw that failed (pdf 0)
/// contributes 0: do not call this for it.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_optimal_contribution(
    f: f32,
    p_this: f32,
    c_this: f32,
    p_other: f32,
    c_other: f32,
    v: f32,
) -> f32 {
    mis::optimal_mis_contribution(f, &[p_this, p_other], &[c_this, c_other], v, 0)
}

/// The contribution of a sample under clamped optimal MIS (Peters 2021, supplement
/// B.3): `f (v c_this / (c_this p_this + c_other p_other) + (1 - v) / (p_this +
/// p_other))`, already divided by the pdf; `v` = `SPHERA_MIS_DEFAULT_VISIBILITY` in
/// the paper. Equals `f * sphera_mis_clamped_optimal_weight(...) / p_this`. Unbiased
/// for any `v`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_clamped_optimal_contribution(
    f: f32,
    p_this: f32,
    c_this: f32,
    p_other: f32,
    c_other: f32,
    v: f32,
) -> f32 {
    mis::clamped_optimal_mis_contribution(f, &[p_this, p_other], &[c_this, c_other], v, 0)
}

/// The weight of clamped optimal MIS, `p_this (v c_this / (c_this p_this + c_other
/// p_other) + (1 - v) / (p_this + p_other))`: `v` times the weighted balance heuristic
/// plus `1 - v` times the balance heuristic. `v = 0` gives the balance heuristic,
/// `v = 1` the weighted balance heuristic. The weights sum to one wherever either pdf
/// is positive.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_clamped_optimal_weight(
    p_this: f32,
    c_this: f32,
    p_other: f32,
    c_other: f32,
    v: f32,
) -> f32 {
    mis::clamped_optimal_mis_weight(&[p_this, p_other], &[c_this, c_other], v, 0)
}
