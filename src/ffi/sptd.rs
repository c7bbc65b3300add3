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
use crate::Vec3;
use crate::sphere::phase::pivot_phase_in_cap;
use crate::sphere::{
    Cap, GgxPivot, SphereLightSampler, SphereLightShading, Sptd, SptdBase, SptdInCap,
};

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

/// Prepares the SPTD restricted to `cap` and normalised there: samples `g(ω_i)` with
/// `ω_i` from the base inside `g(C)`, density `D(ω)/∫_C D` inside `C`. For the
/// clamped-cosine base this holds for every cap, also when `g(C)` crosses the base's
/// horizon or is wider than a hemisphere: `ω_i` is drawn from the clamped cosine in
/// `g(C) ∩ H_a` (exactly, through its orthographic projection), and the pdf is 0 where
/// `g(ω)` is below the horizon. Returns `false` (and writes a sampler without samples,
/// pdf 0) when `base` is not `SPHERA_SPTD_UNIFORM` or `SPHERA_SPTD_CLAMPED_COSINE`, and
/// when `∫_C D` is 0 or its inverse overflows. Does nothing and returns
/// `false` when `out` is null.
///
/// # Safety
///
/// `out` must be null or point to writable memory for one `SpheraSptdInCap`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sptd_in_cap_prepare(
    out: *mut SptdInCap,
    pivot: SpheraVec3,
    base: u32,
    cosine_axis: SpheraVec3,
    cap: Cap,
) -> bool {
    if out.is_null() {
        return false;
    }
    let prepared = sptd(pivot, base, cosine_axis).and_then(|d| SptdInCap::new(&d, &cap));
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(prepared.unwrap_or(SptdInCap::EMPTY)) };
    prepared.is_some()
}

/// Draws a direction of a prepared SPTD in a cap (`u0`, `u1` clamped into [0, 1)).
/// pdf 0 for a null pointer, a failed prepare, or a sample that rounding moved out of
/// the cap.
///
/// # Safety
///
/// `prepared` must be null or point to a `SpheraSptdInCap` written by
/// `sphera_sptd_in_cap_prepare` or `sphera_phase_pivot_in_cap_prepare`.
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
/// As for `sphera_sptd_in_cap_sample`.
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
/// As for `sphera_sptd_in_cap_sample`.
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
/// `out` must be null or point to writable memory for one `SpheraSptdInCap`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_phase_pivot_in_cap_prepare(
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

/// The uniform SPTD fitted to GGX `f cos θ` (the pivot table, 64×64, bilinear) for the
/// view `wo` (local frame, normalised) and roughness `r = √α` (clamped to [0, 1], NaN as
/// 0). Returns `false` (writing a zero pivot and albedo) when `wo` is not finite, zero
/// or at or below the horizon; does nothing for a null `out`.
///
/// # Safety
///
/// `out` must be null or point to writable memory for one `SpheraGgxPivot`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_pivot_lookup(
    out: *mut GgxPivot,
    wo: SpheraVec3,
    roughness: f32,
) -> bool {
    if out.is_null() {
        return false;
    }
    let fit = GgxPivot::lookup(wo.into(), roughness);
    let empty = GgxPivot {
        pivot: Vec3::ZERO,
        albedo: 0.0,
    };
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(fit.unwrap_or(empty)) };
    fit.is_some()
}

/// Prepares real-time GGX shading of sphere lights (BIASED: the fitted SPTD
/// approximates GGX; errors are tabulated in docs/sphere-lights.md) for the view `wo`, roughness
/// `r = √α` and Fresnel `f0` (each channel clamped to [0, 1], NaN as 0). Returns
/// `false` (writing a shading that returns zero) when `wo` is not finite, zero, or at
/// or below the horizon; does nothing for a null `out`.
///
/// # Safety
///
/// `out` must be null or point to writable memory for one `SpheraSphereLightShading`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_shading_prepare(
    out: *mut SphereLightShading,
    wo: SpheraVec3,
    roughness: f32,
    f0: SpheraVec3,
) -> bool {
    if out.is_null() {
        return false;
    }
    let prepared = SphereLightShading::new(wo.into(), roughness, f0.into());
    let empty = SphereLightShading {
        fit: GgxPivot {
            pivot: Vec3::ZERO,
            albedo: 0.0,
        },
        horizon_image: Cap::EMPTY,
        specular_albedo: Vec3::ZERO,
    };
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(prepared.unwrap_or(empty)) };
    prepared.is_some()
}

/// `∫_{C ∩ H} f cos θ dω ≈ albedo_F Ω(g(C) ∩ g(H))/4π` per unit radiance (Eq. 19,
/// BIASED), RGB, for the cap `light` of a sphere light; multiply by its radiance. Zero
/// for a null pointer or an empty cap.
///
/// # Safety
///
/// `shading` must be null or point to a `SpheraSphereLightShading` written by
/// `sphera_sphere_light_shading_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_shade(
    shading: *const SphereLightShading,
    light: Cap,
) -> SpheraVec3 {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(shading, Vec3::ZERO, |s| s.shade(&light)) }.into()
}

/// Specular occlusion with a bent cone `visibility` (Eq. 23, BIASED):
/// `albedo_F Ω(g(C) ∩ g(V))/4π`; the bent cone replaces the upper hemisphere (pass the
/// hemisphere `(0, 0, 1)`, `cos θ = 0`, for an unoccluded point). Zero for a null
/// pointer.
///
/// # Safety
///
/// As for `sphera_sphere_light_shade`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_shade_occluded(
    shading: *const SphereLightShading,
    light: Cap,
    visibility: Cap,
) -> SpheraVec3 {
    // SAFETY: forwarded from the caller.
    unsafe {
        with_ref(shading, Vec3::ZERO, |s| {
            s.shade_occluded(&light, &visibility)
        })
    }
    .into()
}

/// Specular occlusion by the separable approximation (Eq. 21–22, BIASED; the baseline
/// of `sphera_sphere_light_shade_occluded`): the unoccluded shading
/// `sphera_sphere_light_shade` times the fraction of the BRDF lobe inside the bent cone,
/// `Ω(g(V) ∩ g(H)) / Ω(g(H))`. It lets light through a cone that holds the lobe but not
/// the light (shadow leaking). Equals `sphera_sphere_light_shade` for the hemisphere
/// `(0, 0, 1)`, `cos θ = 0`. Zero for a null pointer.
///
/// # Safety
///
/// As for `sphera_sphere_light_shade`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_shade_occluded_separable(
    shading: *const SphereLightShading,
    light: Cap,
    visibility: Cap,
) -> SpheraVec3 {
    // SAFETY: forwarded from the caller.
    unsafe {
        with_ref(shading, Vec3::ZERO, |s| {
            s.shade_occluded_separable(&light, &visibility)
        })
    }
    .into()
}

/// Prepares joint BRDF–light sampling of a sphere light (Section 6.1): the fitted SPTD
/// restricted to the light's cap, or uniform cap sampling when the pivoted cap is
/// smaller than 1e-3 sr (`sphera_sphere_light_sampler_uses_sptd` tells which). A cap
/// that crosses the horizon is sampled above it only (the SPTD over the cap's part above
/// the horizon, through the intersection of the two caps' images): no sample is wasted
/// below the horizon. Combine with `sphera_ggx_sample` by MIS. `center` is relative to
/// the shading point, `wo` points to the viewer, roughness as in
/// `sphera_ggx_pivot_lookup`. Returns `false` (writing a sampler without samples) for an
/// empty cap (non-finite center, radius not finite and positive), a cap wholly below the
/// horizon, or a `wo` at or below the horizon; does nothing for null `out`.
///
/// # Safety
///
/// `out` must be null or point to writable memory for one `SpheraSphereLightSampler`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_sampler_prepare(
    out: *mut SphereLightSampler,
    center: SpheraVec3,
    radius: f32,
    wo: SpheraVec3,
    roughness: f32,
) -> bool {
    if out.is_null() {
        return false;
    }
    let prepared = SphereLightSampler::new(center.into(), radius, wo.into(), roughness);
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(prepared.unwrap_or(SphereLightSampler::EMPTY)) };
    prepared.is_some()
}

/// Draws a direction in the light's cap above the horizon; its pdf is
/// `sphera_sphere_light_sampler_pdf` at
/// the direction, bit for bit (a draw that rounding puts just outside the cap is returned
/// as no sample). pdf 0 for null or a failed prepare.
///
/// # Safety
///
/// `sampler` must be null or point to a `SpheraSphereLightSampler` written by
/// `sphera_sphere_light_sampler_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_sampler_sample(
    sampler: *const SphereLightSampler,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(sampler, crate::Sample::NONE, |s| s.sample([u0, u1])) }.into()
}

/// The density of `sphera_sphere_light_sampler_sample` at `dir`; 0 outside the cap and
/// for null.
///
/// # Safety
///
/// As for `sphera_sphere_light_sampler_sample`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_sampler_pdf(
    sampler: *const SphereLightSampler,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(sampler, 0.0, |s| s.pdf(dir.into())) }
}

/// Whether the sampler draws from the SPTD (`true`) or uniformly in the cap (the
/// fallback for pivoted caps under 1e-3 sr); `false` for null.
///
/// # Safety
///
/// As for `sphera_sphere_light_sampler_sample`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_sampler_uses_sptd(
    sampler: *const SphereLightSampler,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(sampler, false, |s| s.uses_sptd()) }
}
