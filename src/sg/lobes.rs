//! SG fits of reflection lobes (Tokuyoshi 2016, supplement Section 2.1): the diffuse
//! lobe (Eq. 1) and the GGX specular lobe by spherical warping (Eq. 2, after Wang et al.
//! 2009).
//!
//! # Diffuse lobe (Eq. 1)
//!
//! `max(ω·n, 0)/π ≈ G(ω, n, λ_d)/A(λ_d)`. Both sides integrate to 1 over the sphere
//! (energy is kept for every `λ_d`); `λ_d` minimises the L2 distance over the sphere,
//!
//! ```text
//! E(λ) = ∫_{S²} (max(ω·n, 0)/π − e^{λ(ω·n − 1)}/A(λ))² dω
//!      = 2π ∫_{−1}^{1} (max(c, 0)/π − e^{λ(c − 1)}/A(λ))² dc.
//! ```
//!
//! Minimised in f64 (golden section on the 1D integral, checked by the test
//! `diffuse_sharpness_minimises_the_l2_error` in `lobes_tests.rs`): **λ_d = 2.2925**
//! (the paper's "≈ 2"). At the optimum the L2 error is `√E = 0.0862`, **18.7 %** of the
//! L2 norm `√(2π/3)/π = 0.4607` of `cos/π`, and the L1 error
//! `∫|max(ω·n,0)/π − G/A| dω` is **0.258** (relative to `∫ cos/π = 1`). With `λ = 2`
//! they are 20.8 % and 0.295. The SG puts 9.2 % of its mass below the horizon
//! (`(e^{−λ} − e^{−2λ})/(1 − e^{−2λ})`) and peaks 16 % above `1/π` at the normal
//! (`1/A(λ_d) = 0.369`): the light leak the paper mentions.
//!
//! # Specular lobe (Eq. 2)
//!
//! GGX's normal distribution without its normalisation, `D̂(h) = πα² D(h)` (maximum 1 at
//! `h = n`), is approximated by `G(h, n, λ_h)` with `λ_h = 2/α²` as the paper gives for
//! Beckmann and GGX. For GGX this value keeps energy rather than shape: the projected
//! integral of `D̂` is exactly `∫ D̂(h) cos θ_h dh = πα²`, and that of the SG is
//! `≈ 2π/λ_h` for narrow lobes, equal for `λ_h = 2/α²`. Matching the curvature of GGX at
//! its peak would instead give `4/α²` (`(1 + s²/α²)^{−2} ≈ 1 − 2s²/α²` against
//! `1 − λ_h s²/2`), half the energy. The price is the shape: GGX's peak is narrower and
//! its tail heavier than the Gaussian's; `docs/sg-error.md` measures the L1 distance of
//! the normalised lobes (0.5–1.15) and the resulting shading error.
//! Warping from half vectors to directions around the reflection vector
//! `ξ_s = 2(ω'·n)n − ω'` with the Jacobian `|dω_h/dω| = 1/(4 |ξ_s·n|)` of the
//! half-vector map at `ω = ξ_s` gives `λ_s = λ_h / (4|ξ_s·n|)`. `|ξ_s·n|` is clamped to
//! at least [`MIN_SPECULAR_COSINE`] (1e-4): at grazing views the warp makes the lobe
//! arbitrarily sharp, and the clamp bounds `λ_s` by `λ_h · 2500`, itself clamped to
//! `MAX_SHARPNESS`. `α` is clamped to `[MIN_LOBE_ALPHA, 1]` (NaN to 1).
//!
//! [`specular_lobe_normalized`] is Eq. 2 without `R_s` (amplitude `1/A(λ_s)`);
//! [`specular_lobe`] is the unnormalised `G(ω, ξ_s, λ_s)` (amplitude 1) that multiplies
//! `C(ω)` of [`crate::sg::shading`].
//!
//! # Beckmann lobe
//!
//! The paper gives the same `λ_h = 2/α²` for Beckmann's NDF
//! `D(h) = e^{−tan²θ_h/α²}/(πα² cos⁴θ_h)`, whose unnormalised form is
//! `D̂(h) = πα² D(h) = e^{−tan²θ_h/α²}/cos⁴θ_h` (1 at `h = n`; for `α > 1/√2` Beckmann
//! peaks off the normal, at `tan²θ_h = 2α² − 1`). Here the value does both jobs: its
//! projected integral is exactly `πα²` (Beckmann is normalised), which the SG's
//! `≈ 2π/λ_h` matches, and near the peak `ln D̂ ≈ −θ²(1/α² − 2)` against the SG's
//! `−λ_h θ²/2`, the curvature of `λ_h = 2/α² − 4`, within `2α²` relative of the energy
//! value (Beckmann is a Gaussian of the slope, without GGX's heavy tail). So the
//! Beckmann lobes [`beckmann_lobe`] and [`beckmann_lobe_normalized`] are the GGX lobes'
//! functions with the same `α` (and so is the ASG fit
//! [`Asg::from_beckmann`](crate::sg::asg::Asg::from_beckmann)); no constant is fitted.
//! What differs is `C(ω)` (Beckmann's Smith term,
//! [`beckmann_lobe_factor`](crate::sg::shading::beckmann_lobe_factor)) and the error:
//! `docs/sg-error.md` measures the lobe against an f64 Beckmann BRDF: along the normal
//! the L1 distance of the normalised lobes is 1.1e-4 at roughness 0.1 (GGX: 0.41), at
//! 45° and 75° the isotropic warp's own error dominates (0.22 and 0.80; GGX 0.45, 0.87).

use super::sg::{Sg, log_sg_integral, unit_or_none};
use crate::Vec3;

/// The least-squares sharpness of the SG fit of the clamped cosine `max(ω·n, 0)/π`
/// (Eq. 1): relative L2 error 18.7 %, L1 error 0.258 (see the module documentation).
pub const DIFFUSE_LOBE_SHARPNESS: f32 = 2.292_504;

/// The smallest `|ξ_s·n|` in the warp of the specular lobe.
pub const MIN_SPECULAR_COSINE: f32 = 1e-4;

/// The smallest GGX `α` of the lobe fits: `λ_h = 2/α² = 2e6`.
pub const MIN_LOBE_ALPHA: f32 = 1e-3;

/// `G(ω, n, λ_d)/A(λ_d)`: the diffuse lobe of Eq. 1 without `R_d`. A zero or non-finite
/// normal gives [`Sg::ZERO`].
pub fn diffuse_lobe_normalized(normal: Vec3) -> Sg {
    Sg::from_log_amplitude(
        normal,
        DIFFUSE_LOBE_SHARPNESS,
        -log_sg_integral(DIFFUSE_LOBE_SHARPNESS),
    )
}

/// GGX `α` clamped to `[MIN_LOBE_ALPHA, 1]`, NaN to 1.
#[inline(always)]
pub(crate) fn clamp_lobe_alpha(alpha: f32) -> f32 {
    if alpha.is_nan() {
        return 1.0;
    }
    alpha.max(MIN_LOBE_ALPHA).min(1.0)
}

/// The sharpness `λ_h = 2/α²` of the SG fit of GGX's unnormalised NDF (Section 2.1).
#[inline]
pub fn ndf_sharpness(alpha: f32) -> f32 {
    let a = clamp_lobe_alpha(alpha);
    2.0 / (a * a)
}

/// The reflection vector `ξ_s = 2(ω'·n)n − ω'` and `|ξ_s·n| = |ω'·n|` clamped to at
/// least [`MIN_SPECULAR_COSINE`], or `None` for a zero or non-finite input.
#[inline]
pub(crate) fn reflection(normal: Vec3, toward_incoming: Vec3) -> Option<(Vec3, Vec3, f32)> {
    let n = unit_or_none(normal)?;
    let w = unit_or_none(toward_incoming)?;
    let c = w.dot(n);
    let xi = unit_or_none(n * (2.0 * c) - w)?;
    Some((n, xi, c.abs().max(MIN_SPECULAR_COSINE)))
}

/// `G(ω, ξ_s, λ_s)` with amplitude 1: the spherical warp of `G(ω_h, n, 2/α²)`,
/// `ξ_s = 2(ω'·n)n − ω'`, `λ_s = (2/α²)/(4|ξ_s·n|)`. `toward_incoming` is `ω'` (the
/// direction toward where light comes from, or toward the viewer at a shading point).
/// A zero or non-finite input gives [`Sg::ZERO`].
pub fn specular_lobe(normal: Vec3, toward_incoming: Vec3, alpha: f32) -> Sg {
    match reflection(normal, toward_incoming) {
        Some((_, xi, cos)) => Sg::from_log_amplitude(xi, ndf_sharpness(alpha) / (4.0 * cos), 0.0),
        None => Sg::ZERO,
    }
}

/// `G(ω, ξ_s, λ_s)/A(λ_s)`: Eq. 2 without `R_s` (see [`specular_lobe`]).
pub fn specular_lobe_normalized(normal: Vec3, toward_incoming: Vec3, alpha: f32) -> Sg {
    let lobe = specular_lobe(normal, toward_incoming, alpha);
    if lobe == Sg::ZERO {
        return lobe;
    }
    Sg {
        log_amplitude: -log_sg_integral(lobe.sharpness),
        ..lobe
    }
}

/// `G(ω, ξ_s, λ_s)` with amplitude 1 for Beckmann's NDF: the paper's `λ_h = 2/α²`
/// warped as for GGX (`ξ_s = 2(ω'·n)n − ω'`, `λ_s = λ_h/(4|ξ_s·n|)`), the same function
/// as [`specular_lobe`] (see the module documentation). [`Sg::ZERO`] for a zero or
/// non-finite input.
pub fn beckmann_lobe(normal: Vec3, toward_incoming: Vec3, alpha: f32) -> Sg {
    specular_lobe(normal, toward_incoming, alpha)
}

/// `G(ω, ξ_s, λ_s)/A(λ_s)`: Eq. 2 without `R_s` for Beckmann's NDF (see
/// [`beckmann_lobe`]).
pub fn beckmann_lobe_normalized(normal: Vec3, toward_incoming: Vec3, alpha: f32) -> Sg {
    specular_lobe_normalized(normal, toward_incoming, alpha)
}
