//! Uniform sampling of the union of two spherical caps (Dupuy et al. 2017, Sec. 4: sets
//! of caps): `sphera_cap_union_*`. `A ∪ B` is sampled as the disjoint `A` and `B ∩ Ā`;
//! the pdf is `1 / Ω(A ∪ B)` inside either cap. Caps are sanitized as in
//! `sphera_cap_*`.
use super::types::{SpheraSample, SpheraVec3, with_ref};
use crate::sphere::{Cap, CapUnion};

/// Prepares uniform sampling of `a ∪ b` (two lights' caps, for example). Returns `false`
/// also when the union is empty or `1 / Ω(A ∪ B)` overflows.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_cap_union_prepare(out: *mut CapUnion, a: Cap, b: Cap) -> bool {
    if out.is_null() {
        return false;
    }
    let prepared = CapUnion::new(&a, &b);
    // SAFETY: `out` is non-null and the caller guarantees it is writable.
    unsafe { out.write(prepared.unwrap_or(CapUnion::EMPTY)) };
    prepared.is_some()
}

/// A direction uniform in `A ∪ B`, pdf `1 / Ω(A ∪ B)`.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_cap_union_sample(
    prepared: *const CapUnion,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: forwarded from the caller.
    unsafe {
        with_ref(prepared, crate::Sample::NONE, |p| {
            p.sample_uniform([u0, u1])
        })
    }
    .into()
}

/// The density of `sphera_cap_union_sample` at `dir`: `1 / Ω(A ∪ B)` inside either cap,
/// 0 outside.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_cap_union_pdf(prepared: *const CapUnion, dir: SpheraVec3) -> f32 {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(prepared, 0.0, |p| p.pdf(dir.into())) }
}

/// `Ω(A ∪ B)` in steradians, in [0, 4π].
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_cap_union_solid_angle(prepared: *const CapUnion) -> f32 {
    // SAFETY: forwarded from the caller.
    unsafe { with_ref(prepared, 0.0, |p| p.solid_angle()) }
}
