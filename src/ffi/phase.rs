//! Phase functions for participating media (`sphera_phase_*`): the pivot phase function
//! of Dupuy et al. 2017 (Sec. 6.2) and Henyey–Greenstein. `mu` is the cosine between the
//! direction the light travels in and the scattered direction; `g` is clamped to
//! (−1, 1) (|g| ≤ 1 − 2⁻²⁰, NaN counts as 0); `mu` is clamped to [−1, 1].
use super::types::{SpheraSample, SpheraVec3};
use crate::sphere::phase;

/// The pivot phase function `1/(4π) ((1 − g²)/(1 + g² − 2g mu))²` (Eq. 25), per
/// steradian, with `1 − g² = (1 − g)(1 + g)` and the denominator as a sum of
/// non-negative terms (relative error about 1e-6 up to |g| = 1 − 2⁻²⁰). `g` is clamped
/// to [−(1 − 2⁻²⁰), 1 − 2⁻²⁰] (NaN counts as 0): beyond, the function is that of
/// ±(1 − 2⁻²⁰), whose peak at mu = ±1 is 2⁴⁰/π ≈ 3.5e11 per steradian. `mu` is clamped
/// to [−1, 1]. Always finite.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_phase_pivot(mu: f32, g: f32) -> f32 {
    phase::pivot_phase(mu, g)
}

/// The Henyey–Greenstein phase function `1/(4π) (1 − g²)/(1 + g² − 2g mu)^(3/2)`
/// (Eq. 26), per steradian. Always finite.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_phase_henyey_greenstein(mu: f32, g: f32) -> f32 {
    phase::henyey_greenstein(mu, g)
}

/// The pivot parameter whose phase function looks like Henyey–Greenstein with parameter
/// `g` (the rational fit of Eq. 27–28). In (−1, 1).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_phase_pivot_from_henyey_greenstein(g: f32) -> f32 {
    phase::pivot_from_henyey_greenstein(g)
}

/// The mean cosine of the pivot phase function with parameter `g`: 4g/3 for small g,
/// → ±1 as g → ±1; not g. Always finite.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_phase_pivot_mean_cosine(g: f32) -> f32 {
    phase::pivot_mean_cosine(g)
}

/// Samples the pivot phase function around the direction `wo` (normalised here) with
/// `u0`, `u1` in [0, 1) (clamped); the pdf is the phase function's value. No sample
/// (pdf 0, dir (0, 0, 1)) for a zero or non-finite `wo`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_phase_pivot_sample(
    wo: SpheraVec3,
    g: f32,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    phase::sample_pivot_phase(wo.into(), g, [u0, u1]).into()
}

/// Samples Henyey–Greenstein around `wo`; as `sphera_phase_pivot_sample`. For |g| < 1e-4
/// the direction is uniform (relative deviation from HG below 3e-4).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_phase_henyey_greenstein_sample(
    wo: SpheraVec3,
    g: f32,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    phase::sample_henyey_greenstein(wo.into(), g, [u0, u1]).into()
}
