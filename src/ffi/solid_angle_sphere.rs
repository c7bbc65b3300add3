//! C ABI, `sphera_solid_angle_sphere_*`: a sphere light prepared for uniform sampling of
//! the cap it subtends (Dupuy et al. 2017, Sec. 3), its frame and density computed once.
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::Sample;
use crate::sphere::{Cap, SolidAngleSphere};

/// Prepares uniform sampling of the cap of `sphera_cap_from_sphere(center, radius)` (the
/// whole sphere from inside; exact down to 1e-12 sr). Returns `false` also for a
/// non-finite `center` or a `radius` that is not finite and positive.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
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

/// Prepares uniform sampling of any cap (made valid first). Returns `false` also for an
/// empty cap.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
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

/// A direction uniform in solid angle inside the cap, pdf 1 / solid angle: bit for bit
/// the sample of `sphera_cap_sample_uniform` for the same cap.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_sphere_sample(
    sphere: *const SolidAngleSphere,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `sphere` points to a prepared value.
    unsafe { with_ref(sphere, Sample::NONE.into(), |s| s.sample([u0, u1]).into()) }
}

/// The density of `sphera_solid_angle_sphere_sample` at `dir`: 1 / solid angle inside the
/// cap (boundary included), 0 outside; bit for bit every sample's pdf.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_sphere_pdf(
    sphere: *const SolidAngleSphere,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `sphere` points to a prepared value.
    unsafe { with_ref(sphere, 0.0, |s| s.pdf(dir.into())) }
}

/// The solid angle of the prepared cap in steradians.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_sphere_solid_angle(
    sphere: *const SolidAngleSphere,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `sphere` points to a prepared value.
    unsafe { with_ref(sphere, 0.0, |s| s.solid_angle()) }
}
