//! Shading with a VSGL (Tokuyoshi 2016, supplement Section 4): the incoming radiance as
//! an SG (Eq. 6–7), diffuse shading in the product-integral and the constant-cosine
//! forms, and specular shading through the ASG × SG product integral.
//!
//! Every function takes plain values: the VSGL's radiant-intensity lobe as an [`Sg`]
//! (`c_v` as its amplitude, the emission axis `ξ_v`, `λ_v`), its positional mean
//! relative to the shading point, its positional variance, the shading normal, the
//! view direction (toward the viewer), and the visibility `V(y_p, μ_v)` that the
//! caller found (a shadow-map lookup: a multiplier, clamped to `[0, 1]`, NaN to 0).
//! All vectors may be in any frame, as long as it is the same one. Every result is
//! finite and non-negative.
//!
//! # Incoming radiance (Eq. 6–7)
//!
//! `L_in(ω) ≈ c_v/(2πs²) · G(ω, −ξ_v, λ_v) · G(ω, ξ_μ, λ_σ)` with
//! `ξ_μ = μ/|μ|`, `λ_σ = |μ|²/s²`, the product of two SGs ([`Sg::product`]):
//! `λ_in = |λ_σ ξ_μ − λ_v ξ_v|`, `c_in = c_v/(2πs²) e^{λ_in − λ_v − λ_σ}`, all in log
//! space (the exponent without cancellation).
//!
//! **`s² = σ²/2`, not the paper's `σ²`** (derived again, issue 20). `variance` is the
//! VSGL's positional variance `σ_v² = E‖y − μ‖²` of Section 3.2 (the accumulator's), the
//! spread over all three axes. Eq. 3 models the cluster as the planar Gaussian
//! `γ(‖y − μ‖, s²)/(2πs²)`, whose spread is `E‖y − μ‖² = 2s²`: the Gaussian with the
//! cluster's own spread has `s² = σ_v²/2`. The paper puts `σ_v²` itself into Eq. 3 and 6,
//! which makes every VSGL √2 as wide as its cluster (twice its second moment); seen
//! from afar, the SG `G(ω, ξ_μ, λ_σ)` then has the angular spread `E|ω − ξ_μ|² = 2/λ_σ`
//! of the VPLs' directions only with `λ_σ = 2|μ|²/σ_v²` (tested). With the paper's
//! value the tracer's VSGLs lost a further 2–6 % of the image's light (README).
//!
//! Degenerate inputs:
//!
//! - `σ² → 0` (a point light): `λ_σ = |μ|²/s²` exceeds `MAX_SHARPNESS`. It is clamped
//!   there, and `1/(2πs²)` replaced by `λ_σ/(2π|μ|²)` with the clamped `λ_σ`, which
//!   keeps the limit `∫ G_σ/(2πs²) dω → 1/|μ|²` (inverse-square falloff) exact.
//!   A NaN or negative variance (the accumulator's `E|y|² − |μ|²` can round below 0)
//!   counts as 0.
//! - `|μ| → 0` (the shading point at the VSGL's mean): `λ_σ = 0` and `ξ_μ` is irrelevant;
//!   with `σ² > 0` the result is `c_v/(2πs²) G(ω, −ξ_v, λ_v)`. With `σ² = 0` too the
//!   radiance is that of a point light at the shading point, infinite: this returns
//!   [`Sg::ZERO`] (no contribution), as renderers skip a light at the shading point.
//! - a non-finite mean, an infinite variance or an invalid lobe give [`Sg::ZERO`].
//!
//! # Diffuse shading (Section 4.2)
//!
//! - [`diffuse_shading_product`]: `R_d ∫ L_in G(ω, n, λ_d)/A(λ_d) dω`, the SG inner
//!   product with the diffuse lobe of Eq. 1 (leaks light from below the horizon).
//! - [`diffuse_shading_constant_cosine`]: `(c_in R_d/π) A(λ_in) max(ξ_in·n, 0)`, the
//!   cosine pulled out of the integral at the lobe's axis (exact for a delta lobe).
//! - [`diffuse_shading_sharp_lobe`]: `(2 c_in R_d/λ_in) max(ξ_in·n, 0)`, the same with
//!   `A(λ_in) ≈ 2π/λ_in`: 2 % high at `λ_in = 2`, and wrong as `λ_in → 0` (it diverges;
//!   `λ_in` is clamped to at least 1e-20 so that it stays finite, `f32::MAX` at most).
//!
//! All three are approximations (biased); `docs/sg-error.md` measures them against
//! `∫ L_in max(ω·n, 0)/π dω`.
//!
//! # Specular shading (Section 4.2)
//!
//! GGX's `ρ_s cos = F D G2/(4 cos θ_o)` with `D = D̂/(πα²)` (`D̂` the NDF scaled to
//! maximum 1) splits into the lobe shape `D̂ ≈` SG or ASG of [`crate::sg::lobes`] /
//! [`Asg::from_ggx`], and
//!
//! ```text
//! C(ω) = F(ω_o·h) G2(ω_o, ω) / (4 π α² cos θ_o),
//! ```
//!
//! Schlick's Fresnel at the half vector `h` of `ω_o` and `ω`, the height-correlated
//! Smith term ([`GgxBrdf::lambda`]), and the normalisations. `C` is 0 when `ω` or the view
//! lies at or below the horizon. With either lobe fit the integral of `C(ξ_s) D̂` is
//! `F G2` for narrow lobes (`∫ D̂ ≈ 4πα² cos θ_o`). [`specular_shading`] is the boxed
//! formula `c_in C(ξ_in) ∫ G_in Ĝ dω` with the ASG fit; [`specular_shading_sg`] is
//! `C(ξ_in) ∫ L_in G(ω, ξ_s, λ_s) dω` with the isotropic SG fit. Roughness gives
//! `α = roughness²` as in [`GgxBrdf::new`], `α` clamped to `[MIN_LOBE_ALPHA, 1]`;
//! `f0` (one channel) is clamped to `[0, 1]`.
//!
//! Beckmann's BRDF splits the same way (its `D = D̂/(πα²)` has the same normalisation):
//! [`beckmann_specular_shading`] and [`beckmann_specular_shading_sg`] take the lobe fits
//! of [`crate::sg::lobes`] (`λ_h = 2/α²` for Beckmann too, the same functions) and
//! [`beckmann_lobe_factor`], whose `G2` has Beckmann's Smith `Λ` ([`beckmann_lambda`]).

use super::asg::Asg;
use super::lobes::{
    MIN_SPECULAR_COSINE, beckmann_lobe, clamp_lobe_alpha, diffuse_lobe_normalized, specular_lobe,
};
use super::sg::{
    LN_TAU, MAX_SHARPNESS, Sg, exp_finite, log_of_amplitude, log_sg_integral, unit_or_none,
};
use crate::Vec3;
use crate::brdf::ggx::GgxBrdf;
use core::f32::consts::PI;

/// `x` clamped to `[0, 1]`, NaN to 0.
#[inline(always)]
pub(super) fn clamp_unit(x: f32) -> f32 {
    x.max(0.0).min(1.0)
}

/// `x` clamped to `[0, f32::MAX]`, NaN to 0.
#[inline(always)]
pub(super) fn clamp_nonnegative(x: f32) -> f32 {
    x.max(0.0).min(f32::MAX)
}

/// The largest `|μ|²` and `s²` that [`spatial_lobe_linear`] takes: `2⁶⁰ ≈ 1.15e18`
/// (exact: a power of two converts without rounding).
pub(crate) const LINEAR_MAX: f32 = (1u64 << 60) as f32;

/// The smallest `|μ|²` and `s²` that [`spatial_lobe_linear`] takes: `2⁻⁶⁰ ≈ 8.7e-19`
/// (exact: the reciprocal of a power of two).
pub(crate) const LINEAR_MIN: f32 = 1.0 / LINEAR_MAX;

/// The spatial SG `G(ω, ξ_μ, λ_σ)/(2πs²)` of Eq. 6 (`ξ_μ = μ/|μ|`, `λ_σ = |μ|²/s²`,
/// log amplitude `−ln 2π − ln s²`) formed in linear space, the fast path of
/// [`incoming_radiance`]; `None` outside the range where it is as accurate as the log-space
/// path, which then decides. `s2` is `s² = σ²/2`.
///
/// The range: `|μ|²` and `s²` in `[2⁻⁶⁰, 2⁶⁰]` and `λ_σ ≤ MAX_SHARPNESS`. There
/// - `|μ|² = μ·μ` cannot overflow (every component is below `2³⁰`), and a component whose
///   square is subnormal (`< 2⁻¹²⁶`) changes `|μ|² ≥ 2⁻⁶⁰` by less than `2⁻⁶⁶` relative,
///   so `|μ|²` keeps the 1.5 ulp of a sum of three squares;
/// - `λ_σ = |μ|²/s²` lies in `[2⁻¹²⁰, 1e8]`, a normal number: one more rounding (2 ulp
///   in all), where the log-space path's `exp(ln|μ|² − ln s²)` carries the rounding of its
///   argument amplified by its size (`|ln λ_σ|` up to 18: up to ~20 ulp);
/// - `ξ_μ = μ/|μ|` with `|μ| ≥ 2⁻³⁰`: each component within 1.5 ulp, a unit vector to the
///   `UNIT_TOLERANCE` that `Sg::sanitized` accepts as it is;
/// - the log amplitude is the log-space path's own `−ln 2π − ln s²` (the same bits).
///
/// Outside it (a point light, `λ_σ` clamped at `MAX_SHARPNESS`, or distances and variances
/// beyond `2^±30`) the log-space code of [`incoming_radiance`] runs as before; at the
/// clamp boundary both give `λ_σ = MAX_SHARPNESS` with the same energy, so the switch is
/// continuous. Test: `linear_spatial_lobe_agrees_with_f64_and_the_log_space_path`.
#[inline(always)]
pub(crate) fn spatial_lobe_linear(mean: Vec3, s2: f32) -> Option<Sg> {
    let d2 = mean.length_squared();
    // NaN fails every comparison, and s² = 0 (a point light) is below LINEAR_MIN.
    let range = LINEAR_MIN..=LINEAR_MAX;
    if !(range.contains(&d2) && range.contains(&s2)) {
        return None;
    }
    let sharpness = d2 / s2;
    if !(sharpness <= MAX_SHARPNESS) {
        return None;
    }
    let distance = crate::math::sqrtf(d2);
    Some(Sg {
        axis: mean / distance,
        sharpness,
        log_amplitude: -LN_TAU - libm::logf(s2),
    })
}

/// The incoming radiance `c_in G(ω, ξ_in, λ_in)` of Eq. 7 from the VSGL lobe
/// `lobe` (`c_v`, `ξ_v`, `λ_v`), its positional mean `mean` relative to the shading point
/// and its positional variance `variance` (`σ_v² = E‖y − μ‖²`, as [`crate::vsgl::Vsgl`]
/// holds it; the planar Gaussian gets `s² = σ_v²/2`, see the module documentation, also
/// for the degenerate cases).
pub fn incoming_radiance(lobe: &Sg, mean: Vec3, variance: f32) -> Sg {
    incoming_radiance_paths(lobe, mean, variance, true)
}

/// [`incoming_radiance`], with the linear-space fast path [`spatial_lobe_linear`] where it
/// applies when `linear` (always, outside tests), or the log-space path alone (the
/// reference of the fast path's test).
#[inline(always)]
pub(crate) fn incoming_radiance_paths(lobe: &Sg, mean: Vec3, variance: f32, linear: bool) -> Sg {
    let lobe = lobe.sanitized();
    if lobe == Sg::ZERO || !mean.is_finite() || variance == f32::INFINITY {
        return Sg::ZERO;
    }
    // s² = σ²/2: the planar Gaussian with the cluster's spread (module documentation).
    let variance = if variance > 0.0 { 0.5 * variance } else { 0.0 };
    let emitted = Sg {
        axis: -lobe.axis,
        ..lobe
    };
    if linear {
        if let Some(spatial) = spatial_lobe_linear(mean, variance) {
            return emitted.product(&spatial.sanitized());
        }
    }
    let largest = mean.abs().max_element();
    let spatial = if largest > 0.0 {
        let scaled = mean / largest;
        let scaled_length = crate::math::length(scaled);
        let axis = scaled / scaled_length;
        // ln |μ|², without overflow or underflow of |μ|².
        let log_distance2 = 2.0 * (libm::logf(largest) + libm::logf(scaled_length));
        let log_variance = if variance > 0.0 {
            libm::logf(variance)
        } else {
            f32::NEG_INFINITY
        };
        let log_sharpness = log_distance2 - log_variance;
        if log_sharpness <= libm::logf(MAX_SHARPNESS) {
            Sg {
                axis,
                sharpness: libm::expf(log_sharpness).min(MAX_SHARPNESS),
                log_amplitude: -LN_TAU - log_variance,
            }
        } else {
            // σ² → 0: keep ∫ G_σ/(2πσ²) = 1/|μ|² with the clamped sharpness.
            Sg {
                axis,
                sharpness: MAX_SHARPNESS,
                log_amplitude: libm::logf(MAX_SHARPNESS) - LN_TAU - log_distance2,
            }
        }
    } else if variance > 0.0 {
        Sg::from_log_amplitude(Vec3::Z, 0.0, -LN_TAU - libm::logf(variance))
    } else {
        return Sg::ZERO;
    };
    let spatial = spatial.sanitized();
    emitted.product(&spatial)
}

/// `R_d ∫ L_in(ω) G(ω, n, λ_d)/A(λ_d) dω · V`: diffuse shading by the SG product
/// integral with the diffuse lobe of Eq. 1. `r_d` is clamped to `[0, f32::MAX]`.
pub fn diffuse_shading_product(incoming: &Sg, normal: Vec3, r_d: f32, visibility: f32) -> f32 {
    let incoming = incoming.sanitized();
    let lobe = diffuse_lobe_normalized(normal);
    let scale = clamp_nonnegative(r_d) * clamp_unit(visibility);
    if !(scale > 0.0) || lobe == Sg::ZERO {
        return 0.0;
    }
    let lobe = Sg {
        log_amplitude: lobe.log_amplitude + libm::logf(scale),
        ..lobe
    };
    incoming.inner_product(&lobe)
}

/// `max(ξ_in·n, 0)` for a sanitised SG, or 0 for an invalid normal.
#[inline(always)]
fn axis_cosine(incoming: &Sg, normal: Vec3) -> f32 {
    match unit_or_none(normal) {
        Some(n) => incoming.axis.dot(n).max(0.0),
        None => 0.0,
    }
}

/// `(c_in R_d/π) A(λ_in) max(ξ_in·n, 0) · V`: diffuse shading with the cosine taken
/// at the lobe's axis (Section 4.2).
pub fn diffuse_shading_constant_cosine(
    incoming: &Sg,
    normal: Vec3,
    r_d: f32,
    visibility: f32,
) -> f32 {
    let incoming = incoming.sanitized();
    let factor = clamp_nonnegative(r_d) * clamp_unit(visibility) * axis_cosine(&incoming, normal);
    exp_finite(
        incoming.log_amplitude + log_sg_integral(incoming.sharpness) - libm::logf(PI)
            + log_of_amplitude(factor),
    )
}

/// `(2 c_in R_d/λ_in) max(ξ_in·n, 0) · V`: [`diffuse_shading_constant_cosine`] with
/// `A(λ_in) ≈ 2π/λ_in` (Section 4.2, after Iwasaki et al. 2012); only for
/// `λ_in ≳ 2` (see the module documentation).
pub fn diffuse_shading_sharp_lobe(incoming: &Sg, normal: Vec3, r_d: f32, visibility: f32) -> f32 {
    let incoming = incoming.sanitized();
    let factor = clamp_nonnegative(r_d) * clamp_unit(visibility) * axis_cosine(&incoming, normal);
    let sharpness = incoming.sharpness.max(1e-20);
    exp_finite(
        incoming.log_amplitude + core::f32::consts::LN_2 - libm::logf(sharpness)
            + log_of_amplitude(factor),
    )
}

/// `C(ω) = F(ω_o·h) G2(ω_o, ω)/(4πα² cos θ_o)`: the factor of GGX's `ρ_s cos` left
/// once the unnormalised NDF `D̂` is taken out (see the module documentation). 0 for
/// `dir` or `view` at or below the horizon of `normal`, or for invalid vectors.
pub fn ggx_lobe_factor(normal: Vec3, view: Vec3, dir: Vec3, alpha: f32, f0: f32) -> f32 {
    lobe_factor(normal, view, dir, alpha, f0, |alpha, cos| {
        GgxBrdf::from_alpha(alpha, Vec3::ONE).lambda(cos)
    })
}

/// `C(ω) = F(ω_o·h) G2(ω_o, ω)/(4πα² cos θ_o)` of Beckmann's `ρ_s cos`: as
/// [`ggx_lobe_factor`] (Beckmann's `D = D̂/(πα²)` has the same normalisation) with
/// Beckmann's Smith term [`beckmann_lambda`] in the height-correlated
/// `G2 = 1/(1 + Λ(ω_o) + Λ(ω))`.
pub fn beckmann_lobe_factor(normal: Vec3, view: Vec3, dir: Vec3, alpha: f32, f0: f32) -> f32 {
    lobe_factor(normal, view, dir, alpha, f0, beckmann_lambda)
}

/// Smith's `Λ` of Beckmann's NDF for a direction at `cos θ` from the normal (Walter et
/// al. 2007, from the Gaussian slope distribution): with `a = cos θ/(α sin θ)`,
/// `Λ = (e^{−a²}/(a√π) − erfc(a))/2`. 0 along the normal (`a = ∞`), growing without
/// bound towards the horizon (`a → 0`, where `G2 → 0`).
pub fn beckmann_lambda(alpha: f32, cos: f32) -> f32 {
    let sin = crate::math::sqrtf(((1.0 - cos) * (1.0 + cos)).max(0.0));
    let a = cos / (alpha * sin);
    let value =
        0.5 * (libm::expf(-a * a) * (0.5 * core::f32::consts::FRAC_2_SQRT_PI) / a - libm::erfcf(a));
    // Cancellation for large `a` can round below 0 (the true value is positive).
    value.max(0.0)
}

/// `F(ω_o·h) G2/(4πα² cos θ_o)` with `G2 = 1/(1 + Λ(α, cos θ_o) + Λ(α, cos θ))`.
#[inline(always)]
fn lobe_factor(
    normal: Vec3,
    view: Vec3,
    dir: Vec3,
    alpha: f32,
    f0: f32,
    lambda: impl Fn(f32, f32) -> f32,
) -> f32 {
    let (Some(n), Some(wo), Some(wi)) =
        (unit_or_none(normal), unit_or_none(view), unit_or_none(dir))
    else {
        return 0.0;
    };
    let (co, ci) = (wo.dot(n), wi.dot(n));
    if !(co > 0.0) || !(ci > 0.0) {
        return 0.0;
    }
    let Some(h) = unit_or_none(wo + wi) else {
        return 0.0;
    };
    let alpha = clamp_lobe_alpha(alpha);
    let f0 = clamp_unit(f0);
    let m = (1.0 - wo.dot(h)).max(0.0).min(1.0);
    let m2 = m * m;
    let fresnel = f0 + (1.0 - f0) * (m2 * m2 * m);
    let g2 = 1.0 / (1.0 + lambda(alpha, co) + lambda(alpha, ci));
    let value = fresnel * g2 / (4.0 * PI * alpha * alpha * co.max(MIN_SPECULAR_COSINE));
    if value.is_finite() { value } else { 0.0 }
}

/// The factor `C(ω)` of a microfacet lobe: [`ggx_lobe_factor`] or [`beckmann_lobe_factor`].
type LobeFactor = fn(Vec3, Vec3, Vec3, f32, f32) -> f32;

/// What both specular forms share: the sanitized incoming SG, `α` and the factor
/// `V C(ξ_in)` of the lobe towards the incoming axis; `None` where that factor is
/// not positive (the shading is 0 there).
#[inline(always)]
fn specular_factor(
    incoming: &Sg,
    normal: Vec3,
    view: Vec3,
    roughness: f32,
    f0: f32,
    visibility: f32,
    factor: LobeFactor,
) -> Option<(Sg, f32, f32)> {
    let incoming = incoming.sanitized();
    let alpha = roughness_to_alpha(roughness);
    let c = factor(normal, view, incoming.axis, alpha, f0) * clamp_unit(visibility);
    (c > 0.0).then_some((incoming, alpha, c))
}

/// `V c_in C(ξ_in) ∫ G(ω, ξ_in, λ_in) Ĝ(ω) dω`: specular shading by the boxed formula of
/// Section 4.2 with the ASG fit [`Asg::from_ggx`] of the GGX lobe at the shading point.
pub fn specular_shading(
    incoming: &Sg,
    normal: Vec3,
    view: Vec3,
    roughness: f32,
    f0: f32,
    visibility: f32,
) -> f32 {
    let factor = specular_factor(
        incoming,
        normal,
        view,
        roughness,
        f0,
        visibility,
        ggx_lobe_factor,
    );
    asg_shading(factor, normal, view, Asg::from_ggx)
}

/// [`specular_shading`] for Beckmann's NDF: the ASG fit [`Asg::from_beckmann`] and
/// [`beckmann_lobe_factor`].
pub fn beckmann_specular_shading(
    incoming: &Sg,
    normal: Vec3,
    view: Vec3,
    roughness: f32,
    f0: f32,
    visibility: f32,
) -> f32 {
    let factor = specular_factor(
        incoming,
        normal,
        view,
        roughness,
        f0,
        visibility,
        beckmann_lobe_factor,
    );
    asg_shading(factor, normal, view, Asg::from_beckmann)
}

/// `c ∫ G_in Ĝ dω` for the ASG fit `lobe` at the shading point (0 without a factor).
#[inline(always)]
fn asg_shading(
    factor: Option<(Sg, f32, f32)>,
    normal: Vec3,
    view: Vec3,
    lobe: fn(Vec3, Vec3, f32) -> Asg,
) -> f32 {
    let Some((incoming, alpha, c)) = factor else {
        return 0.0;
    };
    let lobe = lobe(normal, view, alpha);
    let value = c * lobe.convolve_sg(&incoming);
    if value.is_finite() {
        value.min(f32::MAX)
    } else {
        f32::MAX
    }
}

/// `V C(ξ_in) ∫ L_in G(ω, ξ_s, λ_s) dω`: specular shading with the isotropic SG fit of
/// Eq. 2 ([`specular_lobe`], amplitude 1) instead of the ASG.
pub fn specular_shading_sg(
    incoming: &Sg,
    normal: Vec3,
    view: Vec3,
    roughness: f32,
    f0: f32,
    visibility: f32,
) -> f32 {
    let factor = specular_factor(
        incoming,
        normal,
        view,
        roughness,
        f0,
        visibility,
        ggx_lobe_factor,
    );
    sg_shading(factor, normal, view, specular_lobe)
}

/// [`specular_shading_sg`] for Beckmann's NDF: the SG fit [`beckmann_lobe`] and
/// [`beckmann_lobe_factor`].
pub fn beckmann_specular_shading_sg(
    incoming: &Sg,
    normal: Vec3,
    view: Vec3,
    roughness: f32,
    f0: f32,
    visibility: f32,
) -> f32 {
    let factor = specular_factor(
        incoming,
        normal,
        view,
        roughness,
        f0,
        visibility,
        beckmann_lobe_factor,
    );
    sg_shading(factor, normal, view, beckmann_lobe)
}

/// `∫ L_in c G(ω, ξ_s, λ_s) dω` for the SG fit `lobe` (0 without a factor).
#[inline(always)]
fn sg_shading(
    factor: Option<(Sg, f32, f32)>,
    normal: Vec3,
    view: Vec3,
    lobe: fn(Vec3, Vec3, f32) -> Sg,
) -> f32 {
    let Some((incoming, alpha, c)) = factor else {
        return 0.0;
    };
    let lobe = lobe(normal, view, alpha);
    let lobe = Sg {
        log_amplitude: libm::logf(c),
        ..lobe
    };
    incoming.inner_product(&lobe)
}

/// `α = roughness²` with roughness clamped to `[0, 1]` (NaN to 1, the roughest).
#[inline(always)]
pub fn roughness_to_alpha(roughness: f32) -> f32 {
    let r = if roughness.is_nan() {
        1.0
    } else {
        clamp_unit(roughness)
    };
    clamp_lobe_alpha(r * r)
}
