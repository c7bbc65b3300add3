//! C ABI, `sphera_sg_shading_point_*`: a shading point prepared once for VSGL shading,
//! then shaded by any number of incoming-radiance SGs (Tokuyoshi 2016, supplement
//! Section 4.2; [`crate::sg::shading_point`]).
use super::types::{SpheraVec3, with_ref};
use crate::sg::sg::Sg;
use crate::sg::shading_point::{SgShading, SgShadingPoint};

/// Prepares a shading point for `sphera_sg_shading_point_shade`: what the constant-cosine
/// diffuse and the ASG specular terms need that does not depend on the lobe (the unit
/// normal and view, the ASG fit of the GGX lobe, `α`, `f0` and Smith's `Λ` of the view).
/// `view` points toward the viewer; normal and view are normalised here and may be in any
/// frame, the same as the incoming SGs'. `α = roughness²` (clamped to [1e-3, 1], NaN
/// roughness as 1); `f0` is Schlick's reflectance of one channel (clamped to [0, 1], NaN
/// as 0). Returns `false`, writing the empty point (which shades every lobe to zeros), for
/// a zero or non-finite normal or view; does nothing for a null `out`. A view at or below
/// the horizon is valid (the specular term is then 0). `SpheraSgShadingPoint` is 92
/// bytes.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sg_shading_point_prepare(
    out: *mut SgShadingPoint,
    normal: SpheraVec3,
    view: SpheraVec3,
    roughness: f32,
    f0: f32,
) -> bool {
    if out.is_null() {
        return false;
    }
    let mut point = SgShadingPoint::EMPTY;
    let prepared = point.prepare(normal.into(), view.into(), roughness, f0);
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(point) };
    prepared
}

/// The diffuse and specular shading of the incoming-radiance SG `incoming`
/// (`sphera_sg_incoming_radiance`) at a prepared point: bit for bit
/// `sphera_sg_diffuse_shading_constant_cosine(incoming, normal, r_d, visibility)` and
/// `sphera_sg_specular_shading(incoming, normal, view, roughness, f0, visibility)` with the
/// point's normal, view, roughness and `f0`. `r_d` is clamped to [0, FLT_MAX] and
/// `visibility` to [0, 1] (NaN to 0). Zeros for a null or empty point.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_sg_shading_point_shade(
    point: *const SgShadingPoint,
    incoming: Sg,
    r_d: f32,
    visibility: f32,
) -> SgShading {
    // SAFETY: forwarded from the caller.
    unsafe {
        with_ref(point, SgShading::ZERO, |p| {
            p.shade(&incoming, r_d, visibility)
        })
    }
}
