//! Virtual spherical Gaussian lights (Tokuyoshi 2015, 2016): `sphera_vsgl_*`.
//!
//! A `SpheraVsglAccumulator` sums VPLs (`SpheraVpl`), pre-summed texels
//! (`SpheraVsglTexel`) or other accumulators into one `SpheraVsgl`;
//! `sphera_vsgl_fis_select` picks one of `N` clusters from a mip pyramid of texels by
//! filtered importance sampling. The Rust documentation of `sphera::vsgl` states the
//! maths; each function below states its contract. A VPL or texel that is rejected
//! leaves the accumulator unchanged; `finish` never returns NaN (an empty cluster has
//! zero powers).

use super::types::{SpheraVec3, with_ref};
use crate::vsgl::{Vpl, Vsgl, VsglAccumulator, VsglPyramid, VsglTexel, fis_select};

/// Writes an empty accumulator whose sums are taken relative to `origin` (a
/// non-finite origin counts as the world origin; choose a point near the VPLs, such as
/// the centre of the scene, to keep the variance precise). `false` when `accumulator`
/// is null.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_vsgl_accumulator_new(
    accumulator: *mut VsglAccumulator,
    origin: SpheraVec3,
) -> bool {
    if accumulator.is_null() {
        return false;
    }
    // SAFETY: non-null, and writable by the caller's guarantee.
    unsafe { accumulator.write(VsglAccumulator::new(origin.into())) };
    true
}

/// Adds one VPL. `false` (nothing added) when a pointer is null or the VPL has a
/// non-finite position, normal, direction or roughness, a zero normal or direction, or
/// sums that overflow; negative or NaN power and reflectance channels count as 0.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_vsgl_accumulator_add_vpl(
    accumulator: *mut VsglAccumulator,
    vpl: *const Vpl,
) -> bool {
    // SAFETY: forwarded from the caller.
    let (Some(accumulator), Some(vpl)) = (unsafe { accumulator.as_mut() }, unsafe { vpl.as_ref() })
    else {
        return false;
    };
    accumulator.add_vpl(vpl)
}

/// Adds a texel of sums taken relative to the accumulator's origin (a mip texel).
/// `false` (nothing added) when a pointer is null or a sum is not finite.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_vsgl_accumulator_add_texel(
    accumulator: *mut VsglAccumulator,
    texel: *const VsglTexel,
) -> bool {
    // SAFETY: forwarded from the caller.
    let (Some(accumulator), Some(texel)) =
        (unsafe { accumulator.as_mut() }, unsafe { texel.as_ref() })
    else {
        return false;
    };
    accumulator.add_texel(texel)
}

/// Adds the sums of `other` (moved to the accumulator's origin). `false` (nothing
/// added) when a pointer is null or the moved sums are not finite. `other` may equal
/// `accumulator` (the sums then double).
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_vsgl_accumulator_merge(
    accumulator: *mut VsglAccumulator,
    other: *const VsglAccumulator,
) -> bool {
    if accumulator.is_null() || other.is_null() {
        return false;
    }
    // SAFETY: both non-null and valid; `other` is copied before `accumulator` is
    // borrowed mutably, so the two may alias.
    let other = unsafe { other.read() };
    let accumulator = unsafe { &mut *accumulator };
    accumulator.merge(&other)
}

/// The VSGL of the sums: normalised diffuse and specular SGs (Toksvig), RGB powers,
/// mean and variance (0 for a single VPL: treat as a point light). An empty VSGL (zero
/// powers, mean at the origin) for a null pointer, no power or non-finite sums.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_vsgl_accumulator_finish(
    accumulator: *const VsglAccumulator,
) -> Vsgl {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(accumulator, Vsgl::EMPTY, VsglAccumulator::finish) }
}

/// Writes the sums of one VPL relative to `origin` into `*texel` (a level-0 texel of a
/// pyramid). `false`, with the zero texel written when `texel` is non-null, when `vpl`
/// is null or rejected (see `sphera_vsgl_accumulator_add_vpl`) or `origin` is not
/// finite.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_vsgl_texel_from_vpl(
    vpl: *const Vpl,
    origin: SpheraVec3,
    texel: *mut VsglTexel,
) -> bool {
    // SAFETY: forwarded from the caller.
    let result = unsafe { with_ref(vpl, None, |vpl| VsglTexel::from_vpl(vpl, origin.into())) };
    if texel.is_null() {
        return false;
    }
    // SAFETY: non-null and writable by the caller's guarantee.
    unsafe { texel.write(result.unwrap_or(VsglTexel::ZERO)) };
    result.is_some()
}

/// The number of texels of the mip pyramid of a `size × size` map, `(4 size² − 1)/3`,
/// or 0 when `size` is not a power of two in `1..=16384`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_vsgl_pyramid_texel_count(size: u32) -> usize {
    VsglPyramid::texel_count(size)
}

/// Cluster `i` of `cluster_count` by filtered importance sampling (Tokuyoshi 2016, Sec. 3.3,
/// Algorithm 1) from `(u0, u1)`: a position drawn in proportion to the texels' `weight`, the
/// mip level where the kernel holds `kernel_scale / cluster_count` of the weight (`iterations`
/// bisection steps, at most 32), the filtered sums there, weighted so that the VSGLs carry the
/// map's luminance exactly. `texels`: the pyramid (level 0 `size × size` row-major, then each
/// coarser level to 1×1, sums of four children, relative to `origin`), at least
/// `sphera_vsgl_pyramid_texel_count(size)` of them. An empty VSGL for bad arguments or no weight.
///
/// # Safety
///
/// `texels` null or pointing to `texel_count` readable, initialised texels.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sphera_vsgl_fis_select(
    texels: *const VsglTexel,
    texel_count: usize,
    size: u32,
    origin: SpheraVec3,
    cluster_count: u32,
    kernel_scale: f32,
    iterations: u32,
    u0: f32,
    u1: f32,
) -> Vsgl {
    let needed = VsglPyramid::texel_count(size);
    if texels.is_null() || needed == 0 || texel_count < needed {
        return Vsgl::EMPTY;
    }
    // SAFETY: non-null, and `needed ≤ texel_count` readable texels by the caller's
    // guarantee.
    let slice = unsafe { core::slice::from_raw_parts(texels, needed) };
    match VsglPyramid::new(slice, size, origin.into()) {
        Some(pyramid) => fis_select(&pyramid, cluster_count, kernel_scale, iterations, [u0, u1]),
        None => Vsgl::EMPTY,
    }
}
