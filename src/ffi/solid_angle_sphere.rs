//! C ABI, `sphera_solid_angle_sphere_*`: a sphere light prepared for uniform sampling
//! of the cap it subtends (Dupuy et al. 2017, Sec. 3), with its frame and density
//! computed once.
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::Sample;
use crate::sphere::{Cap, SolidAngleSphere};

/// Prepares uniform sampling of the cap that the sphere of radius `radius` centred at
/// `center` (relative to the shading point) subtends; the whole sphere of directions
/// when the shading point is inside or on the sphere. The cap is that of
/// `sphera_cap_from_sphere`, exact to a few ulps down to 1e-12 sr and below.
///
/// Returns `false` when `out` is null, when a coordinate of `center` is NaN or
/// infinite, or when `radius` is not finite and positive; unless `out` is null, a
/// `false` return writes the empty value into `*out` (no sample, pdf 0, solid angle 0).
///
/// # Safety
///
/// `out` must be null or point to writable memory for one `SpheraSolidAngleSphere`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_sphere_prepare(
    out: *mut SolidAngleSphere,
    center: SpheraVec3,
    radius: f32,
) -> bool {
    // SAFETY: the caller guarantees that a non-null `out` is writable.
    match unsafe { out.as_mut() } {
        Some(out) => out.prepare(center.into(), radius),
        None => false,
    }
}

/// Prepares uniform sampling of any cap (made valid first, as every `sphera_cap_*`
/// function does). Returns `false` when `out` is null or the cap is empty; unless
/// `out` is null, a `false` return writes the empty value into `*out`.
///
/// # Safety
///
/// `out` must be null or point to writable memory for one `SpheraSolidAngleSphere`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_sphere_prepare_cap(
    out: *mut SolidAngleSphere,
    cap: Cap,
) -> bool {
    // SAFETY: the caller guarantees that a non-null `out` is writable.
    match unsafe { out.as_mut() } {
        Some(out) => out.prepare_cap(cap),
        None => false,
    }
}

/// Draws a direction uniformly in solid angle inside the prepared cap from `u0`, `u1`
/// in [0, 1) (clamped by the library); its pdf is 1 / solid angle. Bit for bit the
/// sample of `sphera_cap_sample_uniform` for the same cap.
///
/// Returns `{dir = (0, 0, 1), pdf = 0}` (no sample) when `sphere` is null or empty.
///
/// # Safety
///
/// `sphere` must be null or point to a `SpheraSolidAngleSphere` written by a
/// `sphera_solid_angle_sphere_prepare*` function.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_sphere_sample(
    sphere: *const SolidAngleSphere,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `sphere` points to a prepared value.
    unsafe { with_ref(sphere, Sample::NONE.into(), |s| s.sample([u0, u1]).into()) }
}

/// The density per steradian of `sphera_solid_angle_sphere_sample` at `dir` (need not
/// be normalised): 1 / solid angle inside the cap (boundary included), 0 outside; every
/// sample's pdf is this value at its direction, bit for bit. Returns 0 when `sphere` is
/// null or empty and for a zero or non-finite `dir`.
///
/// # Safety
///
/// `sphere` must be null or point to a `SpheraSolidAngleSphere` written by a
/// `sphera_solid_angle_sphere_prepare*` function.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_sphere_pdf(
    sphere: *const SolidAngleSphere,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `sphere` points to a prepared value.
    unsafe { with_ref(sphere, 0.0, |s| s.pdf(dir.into())) }
}

/// The solid angle in steradians of the prepared cap; 0 when `sphere` is null or empty.
///
/// # Safety
///
/// `sphere` must be null or point to a `SpheraSolidAngleSphere` written by a
/// `sphera_solid_angle_sphere_prepare*` function.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_sphere_solid_angle(
    sphere: *const SolidAngleSphere,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `sphere` points to a prepared value.
    unsafe { with_ref(sphere, 0.0, |s| s.solid_angle()) }
}
