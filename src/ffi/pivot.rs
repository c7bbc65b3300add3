//! C ABI, `sphera_pivot_*`: the pivot transformation (Dupuy et al. 2017, Eq. 2–4).
use super::types::SpheraVec3;
use crate::sphere::{Cap, pivot_cap, pivot_jacobian, pivot_transform};

/// The pivot transformation `g(dir)`: the second intersection with the unit sphere of
/// the line from `dir` (normalised) through `pivot`. `|pivot| ≥ 1` is clamped to
/// `1 − 2⁻²⁰`; a non-finite pivot counts as the origin (`g(dir) = −dir`); a zero or
/// non-finite `dir` gives `(0, 0, 1)`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_pivot_transform(dir: SpheraVec3, pivot: SpheraVec3) -> SpheraVec3 {
    pivot_transform(dir.into(), pivot.into()).into()
}

/// The Jacobian `((1 − |pivot|²) / |dir − pivot|²)²` of the pivot transformation at
/// `dir` (normalised); 0 for a zero or non-finite `dir`. Pivots as in
/// `sphera_pivot_transform`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_pivot_jacobian(dir: SpheraVec3, pivot: SpheraVec3) -> f32 {
    pivot_jacobian(dir.into(), pivot.into())
}

/// The image of a cap under the pivot transformation: a cap, which may be wider than a
/// hemisphere. Pivots as in `sphera_pivot_transform`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_pivot_transform_cap(cap: Cap, pivot: SpheraVec3) -> Cap {
    pivot_cap(&cap.sanitized(), pivot.into())
}
