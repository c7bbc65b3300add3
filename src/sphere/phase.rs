//! The pivot phase function (Dupuy et al. 2017, Sec. 6.2) and the Henyey–Greenstein
//! phase function it approximates.
//!
//! The pivot phase function is the pivot transformation of the uniform distribution on
//! the sphere with the pivot `r_p = g_p ω_o` on the axis of the incident direction
//! (Eq. 25):
//!
//! `f_pivot(μ) = 1/(4π) · ((1 − g²) / (1 + g² − 2gμ))²`, `μ = ω_o·ω`, `g = g_p ∈ (−1, 1)`,
//!
//! evaluated with `1 + g² − 2gμ = (1 − g)² + 2g(1 − μ)` (for `g ≥ 0`, else
//! `(1 + g)² − 2g(1 + μ)`), a sum of non-negative terms, and `1 − g² = (1 − g)(1 + g)`,
//! so that the forward peak of a strongly forward-scattering medium keeps its precision
//! (relative error ~1e-6 up to `|g| = 1 − 2⁻²⁰`, not `ε/(1 − |g|)`). It is sampled exactly by
//! transforming a uniform direction through the pivot: `ω = u − 2 (u·d)/|d|² d` with
//! `d = r_p − u` maps the sphere to itself (the second intersection of the line from `u`
//! through `r_p`), with density `f_pivot(μ)` (the Jacobian of Eq. 4 over `4π`).
//!
//! Its mean cosine is not `g`. Integrating `μ f_pivot` over the sphere (substituting
//! `s = 1 + g² − 2gμ`) gives
//!
//! `⟨μ⟩ = [g(1 + g²) − (1 − g²)² artanh g] / (2g²) = 4g/3 − Σ_{k≥2} 4 g^(2k−1) / ((2k+1)(2k−1)(2k−3))`
//!
//! (`= 4g/3 − 4g³/15 − 4g⁵/105 − …`, and `→ 1` as `g → 1`): the closed form cancels like
//! `ε / g²` for small `g`, so the series is used below `|g| = 1/2`.
//!
//! Henyey–Greenstein (Eq. 26): `f_HG(μ) = 1/(4π) (1 − g²) / (1 + g² − 2gμ)^(3/2)`, mean
//! cosine `g`, sampled by inverting its CDF. The fit of Eq. 27–28,
//! `g_p = sign(g) Q(|g|)`, `Q(u) = (0.7489u − 0.6121u²) / (1 − 0.8409u + 0.0223u²)`, maps
//! an HG parameter to a pivot parameter with a similar appearance.
//!
//! The fit matches appearance, not the mean cosine: `⟨μ⟩` of `g_p = Q(g)` equals `g` to
//! within 2e-3 up to `g = 0.3` (where `Q(g) ≈ 3g/4` cancels the `4/3`), then falls behind:
//! 0.490 at `g = 0.5`, 0.667 at 0.7, 0.818 at 0.9, 0.874 at 0.99 (the HG mean cosine is
//! `g`).
//!
//! Hard cases: `g = 0` (uniform), `|g|` up to `1 − 2⁻²⁰` (peaks of 1e12 sr⁻¹), `μ = ±1`,
//! `g` negative (back scattering), NaN and out-of-range `g` (clamped to `(−1, 1)`, NaN as
//! 0), `u` outside `[0, 1)`.
use super::cap::Cap;
use super::sptd::{Sptd, SptdInCap};
use crate::math::Frame;
use crate::sample::clamp_random;
use crate::{Sample, Vec3};
use core::f32::consts::PI;

const INV_4PI: f32 = 0.25 / PI;

/// The largest `|g|` the phase functions accept, `1 − 2⁻²⁰`: beyond it the peak density
/// `(1 + g)² / (4π (1 − g)²)` of the pivot phase function leaves f32's comfortable range.
pub const MAX_ANISOTROPY: f32 = 1.0 - 1.0 / 1_048_576.0;

/// `g` clamped to `[−MAX_ANISOTROPY, MAX_ANISOTROPY]`, NaN to 0.
#[inline]
fn clamp_g(g: f32) -> f32 {
    if g.is_nan() {
        0.0
    } else {
        g.max(-MAX_ANISOTROPY).min(MAX_ANISOTROPY)
    }
}

/// `1 + g² − 2gμ` without cancellation near the peak (`μ → sign(g)`).
#[inline]
fn denominator(g: f32, mu: f32) -> f32 {
    let mu = mu.max(-1.0).min(1.0);
    if g >= 0.0 {
        (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu)
    } else {
        (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + mu)
    }
}

/// `1 − g²` as `(1 − g)(1 + g)`: for `|g| ≥ 1/2` the factor `1 ∓ g` is exact, so the
/// product keeps a relative error of an ulp or two, where `1 − g²` from the rounded
/// `g²` cancels to `ε/(1 − |g|)` (1.7e-4 at `g = 0.99983` after squaring; issue 17, 4).
#[inline]
fn one_minus_g2(g: f32) -> f32 {
    (1.0 - g) * (1.0 + g)
}

/// The pivot phase function `f_pivot(μ)` of Eq. 25, per steradian.
pub fn pivot_phase(mu: f32, g: f32) -> f32 {
    let g = clamp_g(g);
    let ratio = one_minus_g2(g) / denominator(g, mu);
    INV_4PI * ratio * ratio
}

/// The Henyey–Greenstein phase function of Eq. 26, per steradian.
pub fn henyey_greenstein(mu: f32, g: f32) -> f32 {
    let g = clamp_g(g);
    let d = denominator(g, mu);
    INV_4PI * one_minus_g2(g) / (d * crate::math::sqrtf(d))
}

/// The pivot parameter that approximates Henyey–Greenstein with parameter `g`
/// (Eq. 27–28): `sign(g) Q(|g|)`.
pub fn pivot_from_henyey_greenstein(g: f32) -> f32 {
    let u = clamp_g(g).abs();
    let q = (0.7489 * u - 0.6121 * u * u) / (1.0 - 0.8409 * u + 0.0223 * u * u);
    if g < 0.0 { -q } else { q }
}

/// The mean cosine `⟨μ⟩` of the pivot phase function with parameter `g` (see the module
/// documentation; not `g`).
pub fn pivot_mean_cosine(g: f32) -> f32 {
    let g = clamp_g(g);
    let a = g.abs();
    let mean = if a < 0.5 {
        // 4a/3 − Σ_{k≥2} 4 a^(2k−1) / ((2k+1)(2k−1)(2k−3)); at a = 1/2 the k = 12 term is
        // 2e-11 of the sum, below f32's resolution.
        let a2 = a * a;
        let mut power = a * a2; // a^(2k−1) for k = 2
        let mut sum = 4.0 * a / 3.0;
        for k in 2..13 {
            let k = k as f32;
            sum -= 4.0 * power / ((2.0 * k + 1.0) * (2.0 * k - 1.0) * (2.0 * k - 3.0));
            power *= a2;
        }
        sum
    } else {
        let artanh = 0.5 * libm::logf((1.0 + a) / (1.0 - a));
        let one_minus = one_minus_g2(a);
        (a * (1.0 + a * a) - one_minus * one_minus * artanh) / (2.0 * a * a)
    };
    if g < 0.0 { -mean } else { mean }
}

/// A direction `u` uniform on the sphere from `u0, u1`: `z = 1 − 2u0`.
#[inline]
fn uniform_sphere(u0: f32, u1: f32) -> Vec3 {
    let z = 1.0 - 2.0 * u0;
    // sin θ from (1 − z)(1 + z) = 4 u0 (1 − u0), exact near the poles.
    let r = crate::math::sqrtf((4.0 * u0 * (1.0 - u0)).max(0.0));
    let phi = 2.0 * PI * u1;
    Vec3::new(r * libm::cosf(phi), r * libm::sinf(phi), z)
}

/// Samples the pivot phase function around the unit direction `wo` (the direction the
/// light travels in, `μ = wo·ω`): a uniform direction pivoted through `r_p = g wo`. The
/// pdf is `f_pivot(μ)`. `Sample::NONE` for a zero or non-finite `wo`.
pub fn sample_pivot_phase(wo: Vec3, g: f32, u: [f32; 2]) -> Sample {
    let Some(frame) = Frame::from_normal(crate::math::normalize_scaled(wo)) else {
        return Sample::NONE;
    };
    let g = clamp_g(g);
    let uniform = uniform_sphere(clamp_random(u[0]), clamp_random(u[1]));
    // The second intersection of the line from `uniform` through the pivot (0, 0, g).
    let d = Vec3::new(0.0, 0.0, g) - uniform;
    let length2 = d.length_squared();
    let local = if length2 > 0.0 {
        uniform - d * (2.0 * uniform.dot(d) / length2)
    } else {
        uniform
    };
    let local = crate::math::normalize_or_zero(local);
    if local == Vec3::ZERO {
        return Sample::NONE;
    }
    Sample {
        dir: frame.to_world(local),
        pdf: pivot_phase(local.z, g),
    }
}

/// The pivot phase function restricted to a sphere light's cap and normalised there
/// (Section 6.2, joint phase function and light sampling): the uniform SPTD with pivot
/// `g ω_o` (`ω_o` normalised here, `g` clamped as for [`pivot_phase`]) in the cap. Its
/// density is `f_pivot(μ) / ∫_C f_pivot` with `∫_C f_pivot = Ω(g(C))/4π`
/// ([`SptdInCap::integral`]), so the estimate `L f_pivot / pdf = L ∫_C f_pivot` of a
/// uniformly bright, unoccluded light has zero variance. `None` for a zero or
/// non-finite `ω_o` or an empty cap.
pub fn pivot_phase_in_cap(wo: Vec3, g: f32, cap: &Cap) -> Option<SptdInCap> {
    // Scaled first: a tiny `wo` has a denormal |ω_o|² and would not come out unit.
    let wo = crate::math::normalize_scaled(wo);
    if wo == Vec3::ZERO {
        return None;
    }
    SptdInCap::new(&Sptd::uniform(wo * clamp_g(g)), cap)
}

/// Samples Henyey–Greenstein around the unit direction `wo` by inverting its CDF in `μ`:
/// `μ = (1 + g² − ((1 − g²)/(1 − g + 2gξ))²) / (2g)`, uniform `μ` for `|g| < 1e-4`
/// (where the inversion cancels; the density then differs from uniform by `< 3e-4`
/// relative, and the returned pdf is the HG density, so the bias is below that). The
/// pdf is `f_HG(μ)`.
pub fn sample_henyey_greenstein(wo: Vec3, g: f32, u: [f32; 2]) -> Sample {
    let Some(frame) = Frame::from_normal(crate::math::normalize_scaled(wo)) else {
        return Sample::NONE;
    };
    let g = clamp_g(g);
    let (xi, u1) = (clamp_random(u[0]), clamp_random(u[1]));
    let mu = if g.abs() < 1e-4 {
        1.0 - 2.0 * xi
    } else {
        let s = one_minus_g2(g) / (1.0 - g + 2.0 * g * xi);
        ((1.0 + g * g - s * s) / (2.0 * g)).max(-1.0).min(1.0)
    };
    let r = crate::math::sqrtf(((1.0 - mu) * (1.0 + mu)).max(0.0));
    let phi = 2.0 * PI * u1;
    let local = Vec3::new(r * libm::cosf(phi), r * libm::sinf(phi), mu);
    Sample {
        dir: frame.to_world(local),
        pdf: henyey_greenstein(mu, g),
    }
}

#[cfg(test)]
#[path = "phase_tests.rs"]
mod tests;
