//! C ABI, `sphera_sphere_light_*` and `sphera_ggx_pivot_*`: the joint BRDF–light
//! sampler of a sphere light, its real-time shading with specular occlusion (Dupuy et
//! al. 2017, Sec. 5–6), and the GGX pivot table behind both.
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::Vec3;
use crate::sphere::{Cap, GgxPivot, SphereLightSampler, SphereLightShading};

/// The uniform SPTD fitted to GGX `f cos θ` (the pivot table, 64×64, bilinear) for the
/// view `wo` (local frame, normalised) and roughness `r = √α` (clamped to [0, 1], NaN as
/// 0). Returns `false` (writing a zero pivot and albedo) when `wo` is not finite, zero
/// or at or below the horizon; does nothing for a null `out`.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_ggx_pivot_from_view(
    out: *mut GgxPivot,
    wo: SpheraVec3,
    roughness: f32,
) -> bool {
    if out.is_null() {
        return false;
    }
    let fit = GgxPivot::from_view(wo.into(), roughness);
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
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
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
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(prepared.unwrap_or(EMPTY_SHADING)) };
    prepared.is_some()
}

/// The shading that a failed preparation writes: every light shades to zero.
const EMPTY_SHADING: SphereLightShading = SphereLightShading {
    fit: GgxPivot {
        pivot: Vec3::ZERO,
        albedo: 0.0,
    },
    clip_image: Cap::EMPTY,
    specular_albedo: Vec3::ZERO,
};

/// `sphera_sphere_light_shading_prepare` with specular occlusion by the bent cone
/// `visibility` (Eq. 23, BIASED) prepared in: `_eval` of this shading then returns, for
/// every light, what `_eval_occluded` returns with this bent cone, bit for bit, at the cost
/// of `_eval` (the bent cone is pivoted once here instead of once per light). A bent cone
/// belongs to a shading point: prepare once per shading point, then call `_eval` per
/// light. An empty `visibility` (or one that is not finite) shades every light to zero.
/// Returns `false` (writing a shading that returns zero) as `_prepare`; does nothing for
/// a null `out`. `_eval_occluded` and `_eval_occluded_separable` of such a shading take
/// their own bent cone and ignore the prepared one.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_shading_prepare_occluded(
    out: *mut SphereLightShading,
    wo: SpheraVec3,
    roughness: f32,
    f0: SpheraVec3,
    visibility: Cap,
) -> bool {
    if out.is_null() {
        return false;
    }
    let prepared = SphereLightShading::new_occluded(wo.into(), roughness, f0.into(), &visibility);
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(prepared.unwrap_or(EMPTY_SHADING)) };
    prepared.is_some()
}

/// `∫_{C ∩ H} f cos θ dω ≈ albedo_F Ω(g(C) ∩ g(H))/4π` per unit radiance (Eq. 19,
/// BIASED), RGB, for the cap `light` of a sphere light; multiply by its radiance (with a
/// shading from `_prepare_occluded`: `albedo_F Ω(g(C) ∩ g(V))/4π`, Eq. 23). Zero for a
/// null pointer or an empty cap.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_shading_eval(
    shading: *const SphereLightShading,
    light: Cap,
) -> SpheraVec3 {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(shading, Vec3::ZERO, |s| s.eval(&light)) }.into()
}

/// Specular occlusion with a bent cone `visibility` (Eq. 23, BIASED):
/// `albedo_F Ω(g(C) ∩ g(V))/4π`; the bent cone replaces the upper hemisphere (pass the
/// hemisphere `(0, 0, 1)`, `cos θ = 0`, for an unoccluded point). Zero for a null
/// pointer. It pivots the bent cone at every call: for a bent cone of the shading point,
/// `_prepare_occluded` once and `_eval` per light cost less.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_shading_eval_occluded(
    shading: *const SphereLightShading,
    light: Cap,
    visibility: Cap,
) -> SpheraVec3 {
    // SAFETY: forwarded from the caller.
    unsafe {
        with_ref(shading, Vec3::ZERO, |s| {
            s.eval_occluded(&light, &visibility)
        })
    }
    .into()
}

/// Specular occlusion by the separable approximation (Eq. 21–22, BIASED; the baseline of
/// `_eval_occluded`): unoccluded shading times the lobe's fraction `Ω(g(V) ∩ g(H)) / Ω(g(H))`
/// inside the bent cone `V`; it leaks light through a cone that holds the lobe but not the light.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_shading_eval_occluded_separable(
    shading: *const SphereLightShading,
    light: Cap,
    visibility: Cap,
) -> SpheraVec3 {
    // SAFETY: forwarded from the caller.
    unsafe {
        with_ref(shading, Vec3::ZERO, |s| {
            s.eval_occluded_separable(&light, &visibility)
        })
    }
    .into()
}

/// Prepares joint BRDF–light sampling of a sphere light (Section 6.1): the fitted SPTD in
/// the light's cap above the horizon, or uniform cap sampling when the pivoted cap is under
/// 1e-3 sr (`_uses_sptd` tells which); combine with `sphera_ggx_brdf_sample` by MIS.
/// Returns `false` also for an empty cap (bad center or radius), a cap wholly below the
/// horizon, or a `wo` at or below it.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_sampler_prepare(
    out: *mut SphereLightSampler,
    center: SpheraVec3,
    radius: f32,
    wo: SpheraVec3,
    roughness: f32,
) -> bool {
    // SAFETY: the caller guarantees that a non-null `out` is writable.
    match unsafe { out.as_mut() } {
        Some(out) => out.prepare(center.into(), radius, wo.into(), roughness),
        None => false,
    }
}

/// `sphera_sphere_light_sampler_prepare` with the fit of the view computed by the caller,
/// `sphera_ggx_pivot_from_view(&fit, wo, roughness)`: the fit belongs to the shading point
/// and the material, not to the light, so fit once per shading point and prepare each
/// sphere light from it. The same sampler, bit for bit, as `_prepare` with that `wo` and
/// roughness; a pivot with a component that is not finite counts as zero, and one longer
/// than the fits' maximum length is shortened to it. Returns `false` (writing a sampler without samples) for a null `fit`, an empty
/// cap (bad center or radius) or a cap wholly below the horizon; does nothing for a null
/// `out`. A failed `sphera_ggx_pivot_from_view` writes a zero pivot, with which the
/// sampler draws uniformly in the cap's part above the horizon: check its result.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_sampler_prepare_with_fit(
    out: *mut SphereLightSampler,
    center: SpheraVec3,
    radius: f32,
    fit: *const GgxPivot,
) -> bool {
    // SAFETY: the caller guarantees that a non-null `out` is writable and that a
    // non-null `fit` is readable.
    match unsafe { (out.as_mut(), fit.as_ref()) } {
        (Some(out), Some(fit)) => out.prepare_with_fit(center.into(), radius, fit),
        (Some(out), None) => {
            *out = SphereLightSampler::EMPTY;
            false
        }
        (None, _) => false,
    }
}

/// Draws a direction in the light's cap above the horizon; its pdf is
/// `sphera_sphere_light_sampler_pdf` at
/// the direction, bit for bit (a draw that rounding puts just outside the cap is returned
/// as no sample). pdf 0 for null or a failed prepare.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
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
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
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
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sphere_light_sampler_uses_sptd(
    sampler: *const SphereLightSampler,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(sampler, false, |s| s.uses_sptd()) }
}
