//! C ABI, `sphera_mis_*`: the MIS heuristics (Veach 1997; Peters 2021, supplement B).
use crate::mis;

/// The visibility estimate `v` that Peters 2021 uses for clamped optimal MIS.
pub const SPHERA_MIS_DEFAULT_VISIBILITY: f32 = 0.5;

const _: () = assert!(SPHERA_MIS_DEFAULT_VISIBILITY == mis::DEFAULT_VISIBILITY);

// ---- multiple importance sampling, two techniques -----------------------------------
//
// `p_this` is the density of the technique that drew the sample, `p_other` that of the
// other technique at the same direction; `c_this`, `c_other` their unoccluded
// contributions (Peters 2021). Shared conventions: NaN and negative pdfs count as 0; a
// technique whose pdf is 0 gets weight 0, and all weights are 0 when both pdfs are 0;
// infinite pdfs take the whole weight (shared when both are infinite); NaN, negative
// and infinite contributions count as 0; `v` is clamped to [0, 1] (NaN counts as 0); a
// contribution that is not finite is returned as 0. No function returns NaN or an
// infinity.

/// The balance heuristic `p_this / (p_this + p_other)`. The weights of the two
/// techniques sum to one wherever either pdf is positive.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_balance(p_this: f32, p_other: f32) -> f32 {
    mis::balance_heuristic(&[p_this, p_other], 0)
}

/// The power heuristic with exponent 2, `p_this² / (p_this² + p_other²)`, computed
/// without overflow. The weights sum to one wherever either pdf is positive.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_power(p_this: f32, p_other: f32) -> f32 {
    mis::power_heuristic(&[p_this, p_other], 0)
}

/// The weighted balance heuristic of Peters 2021,
/// `c_this p_this / (c_this p_this + c_other p_other)`, where `c_this`, `c_other` >= 0
/// are the techniques' unoccluded contributions. Falls back to the balance heuristic
/// where `c_this p_this + c_other p_other = 0`. The weights sum to one wherever either
/// pdf is positive.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_weighted_balance(
    p_this: f32,
    c_this: f32,
    p_other: f32,
    c_other: f32,
) -> f32 {
    mis::weighted_balance_heuristic(&[p_this, p_other], &[c_this, c_other], 0)
}

/// The contribution of a sample under optimal MIS as specialised by Peters 2021
/// (supplement B.1): `v c_this + (f - v (c_this p_this + c_other p_other)) /
/// (p_this + p_other)`, where `f` is the integrand at the sample and `v` in [0, 1] an
/// estimate of the visibility. This is already divided by the pdf: add the
/// contributions of one sample of each technique. It can be negative and is non-zero
/// where `f = 0`; the sum is unbiased for any `v`. A draw that failed (pdf 0)
/// contributes 0: do not call this for it.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_optimal_contribution(
    f: f32,
    p_this: f32,
    c_this: f32,
    p_other: f32,
    c_other: f32,
    v: f32,
) -> f32 {
    mis::optimal_mis_contribution(f, &[p_this, p_other], &[c_this, c_other], v, 0)
}

/// The contribution of a sample under clamped optimal MIS (Peters 2021, supplement
/// B.3): `f (v c_this / (c_this p_this + c_other p_other) + (1 - v) / (p_this +
/// p_other))`, already divided by the pdf; `v` = `SPHERA_MIS_DEFAULT_VISIBILITY` in
/// the paper. Equals `f * sphera_mis_clamped_optimal_weight(...) / p_this`. Unbiased
/// for any `v`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_clamped_optimal_contribution(
    f: f32,
    p_this: f32,
    c_this: f32,
    p_other: f32,
    c_other: f32,
    v: f32,
) -> f32 {
    mis::clamped_optimal_mis_contribution(f, &[p_this, p_other], &[c_this, c_other], v, 0)
}

/// The weight of clamped optimal MIS, `p_this (v c_this / (c_this p_this + c_other
/// p_other) + (1 - v) / (p_this + p_other))`: `v` times the weighted balance heuristic
/// plus `1 - v` times the balance heuristic. `v = 0` gives the balance heuristic,
/// `v = 1` the weighted balance heuristic. The weights sum to one wherever either pdf
/// is positive.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_mis_clamped_optimal_weight(
    p_this: f32,
    c_this: f32,
    p_other: f32,
    c_other: f32,
    v: f32,
) -> f32 {
    mis::clamped_optimal_mis_weight(&[p_this, p_other], &[c_this, c_other], v, 0)
}
