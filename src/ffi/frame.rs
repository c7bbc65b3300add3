//! Local shading frames, CPU capabilities and the library version (`sphera_version`,
//! `sphera_check_version`).
use super::types::{SpheraVec3, with_ref};
use crate::Vec3;
use crate::math::Frame;

/// The frame whose axes are the world axes; written by a failing
/// `sphera_frame_from_normal`.
const IDENTITY: Frame = Frame {
    tangent: Vec3::X,
    bitangent: Vec3::Y,
    normal: Vec3::Z,
};

/// Builds the orthonormal shading frame (tangent, bitangent, normal) around a unit
/// `normal`.
///
/// Returns `false` when `out` is null, or when `normal` is not finite or not of unit
/// length (|n|² outside 1 ± 1e-3); in the second case `*out` is set to the identity
/// frame (tangent = x axis, bitangent = y axis, normal = z axis).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_frame_from_normal(out: *mut Frame, normal: SpheraVec3) -> bool {
    if out.is_null() {
        return false;
    }
    let frame = Frame::from_normal(normal.into());
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(frame.unwrap_or(IDENTITY)) };
    frame.is_some()
}

/// Expresses the world-space vector `v` in `frame` (x = tangent, y = bitangent,
/// z = normal). A null `frame` acts as the identity frame: `v` is returned unchanged.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_frame_to_local(frame: *const Frame, v: SpheraVec3) -> SpheraVec3 {
    // SAFETY: the caller guarantees that a non-null `frame` points to a valid frame.
    unsafe { with_ref(frame, v, |frame| frame.to_local(v.into()).into()) }
}

/// Expresses the local vector `v` (x = tangent, y = bitangent, z = normal) in world
/// space. A null `frame` acts as the identity frame: `v` is returned unchanged.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_frame_to_world(frame: *const Frame, v: SpheraVec3) -> SpheraVec3 {
    // SAFETY: the caller guarantees that a non-null `frame` points to a valid frame.
    unsafe { with_ref(frame, v, |frame| frame.to_world(v.into()).into()) }
}
