//! Spherical pivot-transformed distributions and sphere lights over GGX surfaces
//! (Dupuy et al. 2017, Sections 4–6): `sphera_sptd_*` and `sphera_sphere_light_*`.
//!
//! An SPTD is passed as its pivot, a base number (`SPHERA_SPTD_UNIFORM` or
//! `SPHERA_SPTD_CLAMPED_COSINE`; any other number is an error, which the functions
//! report as density 0, no sample, integral 0 or a failed prepare) and the cosine
//! base's axis (ignored for the uniform base; normalised, a zero or non-finite axis
//! becomes `(0, 0, 1)`). Pivots with `|r_p| ≥ 1` are clamped to `1 − 2⁻²⁰`, non-finite
//! ones count as the origin. Caps are sanitized as in `sphera_cap_*`.
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::sphere::phase::pivot_phase_in_cap;
use crate::sphere::{Cap, Sptd, SptdBase, SptdInCap};

/// The uniform base distribution `1/4π` (Eq. 16).
pub const SPHERA_SPTD_UNIFORM: u32 = 0;

/// The clamped-cosine base distribution `max(0, ω·a)/π`.
pub const SPHERA_SPTD_CLAMPED_COSINE: u32 = 1;

const _: () = {
    assert!(SPHERA_SPTD_UNIFORM == SptdBase::Uniform as u32);
    assert!(SPHERA_SPTD_CLAMPED_COSINE == SptdBase::ClampedCosine as u32);
};

/// The SPTD of the C arguments, or `None` for a base number that is not a
/// `SPHERA_SPTD_*` constant.
fn sptd(pivot: SpheraVec3, base: u32, cosine_axis: SpheraVec3) -> Option<Sptd> {
    Some(match SptdBase::from_u32(base)? {
        SptdBase::ClampedCosine => Sptd::clamped_cosine(pivot.into(), cosine_axis.into()),
        SptdBase::Uniform => Sptd::uniform(pivot.into()),
    })
}

/// The SPTD density `D(ω) = D_std(g(ω)) J(ω)` (Eq. 8) at `dir` (normalised); 0 for a
/// zero or non-finite `dir`, and 0 when `base` is not `SPHERA_SPTD_UNIFORM` or
/// `SPHERA_SPTD_CLAMPED_COSINE`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sptd_eval(
    pivot: SpheraVec3,
    base: u32,
    cosine_axis: SpheraVec3,
    dir: SpheraVec3,
) -> f32 {
    sptd(pivot, base, cosine_axis).map_or(0.0, |d| d.eval(dir.into()))
}

/// Draws `g(ω_i)` with `ω_i` from the base over the whole sphere; the pdf is
/// `sphera_sptd_eval` at the returned direction, bit for bit. pdf 0 (no sample) where
/// the density underflows, and when `base` is not `SPHERA_SPTD_UNIFORM` or
/// `SPHERA_SPTD_CLAMPED_COSINE`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sptd_sample(
    pivot: SpheraVec3,
    base: u32,
    cosine_axis: SpheraVec3,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    sptd(pivot, base, cosine_axis)
        .map_or(crate::Sample::NONE, |d| d.sample([u0, u1]))
        .into()
}

/// `∫_C D = ∫_{g(C)} D_std` (Eq. 10), in [0, 1], exact; 0 when `base` is not
/// `SPHERA_SPTD_UNIFORM` or `SPHERA_SPTD_CLAMPED_COSINE`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sptd_integral_over_cap(
    pivot: SpheraVec3,
    base: u32,
    cosine_axis: SpheraVec3,
    cap: Cap,
) -> f32 {
    sptd(pivot, base, cosine_axis).map_or(0.0, |d| d.integral_over_cap(&cap))
}

/// `∫_{A ∩ B} D = ∫_{g(A) ∩ g(B)} D_std` (Eq. 11), in [0, 1], exact; 0 when `base` is
/// not `SPHERA_SPTD_UNIFORM` or `SPHERA_SPTD_CLAMPED_COSINE`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sptd_integral_over_cap_intersection(
    pivot: SpheraVec3,
    base: u32,
    cosine_axis: SpheraVec3,
    a: Cap,
    b: Cap,
) -> f32 {
    sptd(pivot, base, cosine_axis).map_or(0.0, |d| d.integral_over_cap_intersection(&a, &b))
}

/// `∫_{A ∪ B} D` (Eq. 11) as `∫_A D + ∫_B D − ∫_{A ∩ B} D`, in [0, 1]. 0 for an unknown
/// `base` and a malformed cap (non-finite or zero axis, NaN `one_minus_cos`).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sptd_integral_over_cap_union(
    pivot: SpheraVec3,
    base: u32,
    cosine_axis: SpheraVec3,
    a: Cap,
    b: Cap,
) -> f32 {
    sptd(pivot, base, cosine_axis).map_or(0.0, |d| d.integral_over_cap_union(&a, &b))
}

/// `∫ D` over the complement of `cap` (Eq. 11), `1 − ∫_C D` computed over the complement
/// cap (a small hole keeps its precision); 1 for the empty cap, 0 as for the union.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sptd_integral_over_cap_complement(
    pivot: SpheraVec3,
    base: u32,
    cosine_axis: SpheraVec3,
    cap: Cap,
) -> f32 {
    sptd(pivot, base, cosine_axis).map_or(0.0, |d| d.integral_over_cap_complement(&cap))
}

/// Prepares the SPTD restricted to `cap` and normalised there: `g(ω_i)` with `ω_i` from the
/// base in `g(C)` (for the clamped cosine, in `g(C) ∩ H_a`, also across the base's horizon
/// or wider than a hemisphere), density `D(ω)/∫_C D` in `C`. Returns `false` also for a
/// `base` that is not a `SPHERA_SPTD_*` value, and when `∫_C D` is 0 or overflows.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sptd_in_cap_prepare(
    out: *mut SptdInCap,
    pivot: SpheraVec3,
    base: u32,
    cosine_axis: SpheraVec3,
    cap: Cap,
) -> bool {
    // SAFETY: the caller guarantees that a non-null `out` is writable.
    let Some(out) = (unsafe { out.as_mut() }) else {
        return false;
    };
    match sptd(pivot, base, cosine_axis) {
        Some(d) => out.prepare(&d, &cap),
        None => {
            *out = SptdInCap::EMPTY;
            false
        }
    }
}

/// Draws a direction of a prepared SPTD in a cap (`u0`, `u1` clamped into [0, 1)).
/// pdf 0 for a null pointer, a failed prepare, or a sample that rounding moved out of
/// the cap.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sptd_in_cap_sample(
    prepared: *const SptdInCap,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(prepared, crate::Sample::NONE, |p| p.sample([u0, u1])) }.into()
}

/// The density of `sphera_sptd_in_cap_sample` at `dir`: 0 outside the cap, where the
/// clamped-cosine base is 0 at `g(dir)`, and for a null pointer.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sptd_in_cap_pdf(
    prepared: *const SptdInCap,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(prepared, 0.0, |p| p.pdf(dir.into())) }
}

/// `∫_C D` of a prepared SPTD in a cap (for the pivot phase function, `∫_C f_pivot`:
/// the zero-variance estimate of an unoccluded light of unit radiance); 0 for null.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sptd_in_cap_integral(prepared: *const SptdInCap) -> f32 {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(prepared, 0.0, |p| p.integral) }
}

/// The pivot phase function (pivot `g·wo`, `wo` normalised, `g` clamped as in
/// `sphera_phase_pivot`) restricted to a sphere light's cap (Section 6.2): sample and
/// evaluate it with `sphera_sptd_in_cap_*`. Returns `false` (writing a sampler without
/// samples) for a zero or non-finite `wo` or an empty cap; does nothing for a null
/// `out`.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sptd_in_cap_prepare_pivot_phase(
    out: *mut SptdInCap,
    wo: SpheraVec3,
    g: f32,
    cap: Cap,
) -> bool {
    if out.is_null() {
        return false;
    }
    let prepared = pivot_phase_in_cap(wo.into(), g, &cap);
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(prepared.unwrap_or(SptdInCap::EMPTY)) };
    prepared.is_some()
}
