//! Sampling the normalised SG, the von Mises–Fisher (vMF) distribution (Tokuyoshi 2016,
//! supplement Section 2): density, sampling and its inverse.
//!
//! The density of the SG with axis `ξ` and sharpness `λ`, normalised over the sphere, is
//!
//! ```text
//! p(ω) = G(ω)/A(λ) = λ e^{−λ t} / (2π (1 − e^{−2λ})),   t = 1 − ω·ξ ∈ [0, 2].
//! ```
//!
//! With `dω = dt dφ` the variable `t` has the density `λ e^{−λt}/(1 − e^{−2λ})` on
//! `[0, 2]` and `φ` is uniform, so the inverse of the CDF
//! `F(t) = (1 − e^{−λt})/(1 − e^{−2λ}) = expm1(−λt)/expm1(−2λ)` gives
//!
//! ```text
//! t = −log1p(u₀ · expm1(−2λ)) / λ,   φ = 2π u₁,
//! ω = (1 − t) ξ + √(t (2 − t)) (cos φ T + sin φ B).
//! ```
//!
//! Sampling `t = 1 − cos θ` rather than `cos θ` is what keeps sharp lobes accurate: for
//! `λ = 1e6` every `t` lies below ~2e-5, where `cos θ` in `f32` has only a few
//! distinct values, while `t` and `sin θ = √(t(2 − t))` keep full relative precision.
//! The `expm1`/`log1p` forms are exact in the limits: for `λ → 0` they give
//! `t = 2u₀` (uniform on the sphere) without `0/0`, for large `λ` `expm1(−2λ) = −1`
//! and `t = −log1p(−u₀)/λ`. The density and the inverse take `t = |ω − ξ|²/2`, which
//! has no cancellation near the axis.
//!
//! Hard cases (tested in `vmf_tests.rs`): `λ` from 1e-4 to 1e6 (chi-square tests at
//! 1e-4, 0.1, 1, 10, 1e3, 1e5), `λ = 0` (uniform sphere), `u` at both ends of `[0, 1)`,
//! outside it and NaN, and a zero or non-finite axis in a hand-made SG (no sample).

use super::sg::{Sg, clamp_sharpness, one_minus_exp_over, unit_or_none};
use crate::Sample;
use crate::math::orthonormal_basis;
use crate::sample::clamp_random;
use core::f32::consts::TAU;
use glam::Vec3;

/// The vMF density of `t = 1 − ω·ξ` per steradian for a sanitised sharpness.
#[inline(always)]
fn density(sharpness: f32, t: f32) -> f32 {
    libm::expf(-sharpness * t) / (TAU * one_minus_exp_over(sharpness))
}

/// Draws a direction from the normalised SG `G/A(λ)` of `sg` (its amplitude is
/// ignored). `u` is clamped to `[0, 1)` (NaN to 0). A zero or non-finite axis gives
/// [`Sample::NONE`]; sharpness is clamped as in [`Sg::new`].
pub fn vmf_sample(sg: &Sg, u: [f32; 2]) -> Sample {
    let Some(axis) = unit_or_none(sg.axis) else {
        return Sample::NONE;
    };
    let l = clamp_sharpness(sg.sharpness);
    let (u0, u1) = (clamp_random(u[0]), clamp_random(u[1]));
    // `e^{−2λ} − 1`, computed once for the inverse CDF and the density's normaliser
    // `A(λ)/(2π) = −expm1(−2λ)/λ` (`one_minus_exp_over`, whose operations these are, so
    // the pdf keeps its bits: `samples_follow_the_vmf_chi_square` asserts it equal to
    // `vmf_pdf` of the sample).
    let (t, normaliser) = if l > 1e-20 {
        let e = libm::expm1f(-2.0 * l);
        (-libm::log1pf(u0 * e) / l, -e / l)
    } else {
        (2.0 * u0, 2.0)
    };
    let t = t.max(0.0).min(2.0);
    let sin_theta = crate::math::sqrtf((t * (2.0 - t)).max(0.0));
    let (sin_phi, cos_phi) = crate::math::sin_cos_of_turn(u1);
    let (tangent, bitangent) = orthonormal_basis(axis);
    let dir = axis * (1.0 - t) + (tangent * cos_phi + bitangent * sin_phi) * sin_theta;
    let t_dir = 0.5 * (dir - axis).length_squared();
    Sample {
        dir,
        pdf: libm::expf(-l * t_dir) / (TAU * normaliser),
    }
}

/// The density for a unit `axis`, a clamped sharpness and a unit `dir`.
#[inline(always)]
fn vmf_pdf_unit(axis: Vec3, sharpness: f32, dir: Vec3) -> f32 {
    let t = 0.5 * (dir - axis).length_squared();
    density(sharpness, t)
}

/// The density per steradian of [`vmf_sample`] at `dir` (normalised first):
/// `λ e^{−λ(1 − ω·ξ)} / (2π(1 − e^{−2λ}))`. 0 for a zero or non-finite `dir` or axis.
pub fn vmf_pdf(sg: &Sg, dir: Vec3) -> f32 {
    match (unit_or_none(sg.axis), unit_or_none(dir)) {
        (Some(axis), Some(dir)) => vmf_pdf_unit(axis, clamp_sharpness(sg.sharpness), dir),
        _ => 0.0,
    }
}

/// The random numbers that [`vmf_sample`] maps to `dir` (normalised first):
/// `u₀ = expm1(−λt)/expm1(−2λ)` with `t = |ω − ξ|²/2` (`t/2` for `λ → 0`) and
/// `u₁ = φ/(2π)` in the axis' tangent frame. `None` for a zero or non-finite `dir` or
/// axis. On the axis itself (where `φ` is undefined) `u₁ = 0`.
pub fn vmf_invert(sg: &Sg, dir: Vec3) -> Option<[f32; 2]> {
    let axis = unit_or_none(sg.axis)?;
    let dir = unit_or_none(dir)?;
    let l = clamp_sharpness(sg.sharpness);
    let t = (0.5 * (dir - axis).length_squared()).min(2.0);
    let u0 = if l > 1e-20 {
        libm::expm1f(-l * t) / libm::expm1f(-2.0 * l)
    } else {
        0.5 * t
    };
    let (tangent, bitangent) = orthonormal_basis(axis);
    let phi = libm::atan2f(dir.dot(bitangent), dir.dot(tangent));
    let mut u1 = phi / TAU;
    if u1 < 0.0 {
        u1 += 1.0;
    }
    Some([
        u0.max(0.0).min(crate::sample::ONE_MINUS_ULP),
        u1.max(0.0).min(crate::sample::ONE_MINUS_ULP),
    ])
}
