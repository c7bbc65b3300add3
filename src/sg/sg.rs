//! Spherical Gaussians (SGs): evaluation, integral, product and inner product
//! (Tokuyoshi 2016, supplement Section 2).
//!
//! # The function
//!
//! An SG with unit axis `ξ`, sharpness `λ ≥ 0` and amplitude `a > 0` is
//!
//! ```text
//! G(ω) = a · e^{λ (ω·ξ − 1)} = a · e^{−λ/2 · |ω − ξ|²}          (Section 2)
//! ```
//!
//! (the two forms agree for unit `ω`, `ξ` because `|ω − ξ|² = 2 (1 − ω·ξ)`). It is
//! evaluated in the second form: near the axis `1 − ω·ξ` computed from the dot product
//! cancels (in `f32` it is 0 for every angle below ~3e-4 rad, and only a few bits
//! accurate up to ~1e-2 rad), while `|ω − ξ|²` is a sum of squares of small
//! differences and keeps full relative precision. For sharp lobes (`λ = 1e6`: width
//! ~1e-3 rad) that is the difference between a correct lobe and a staircase.
//!
//! The amplitude is stored as its logarithm, so that the products and the VSGL
//! incoming radiance (`c_v / (2πs²) · e^{λ_in − λ_v − λ_σ}`, Eq. 7) neither overflow
//! nor form `0 · ∞` for sharpness up to [`MAX_SHARPNESS`].
//!
//! # Integral and products
//!
//! `A(λ) = ∫ e^{λ(ω·ξ − 1)} dω = 2π/λ · (1 − e^{−2λ})` is evaluated as
//! `−2π · expm1(−2λ) / λ`, which tends to `4π` as `λ → 0` without cancellation.
//!
//! The product of two SGs is an SG: with `v = λ1 ξ1 + λ2 ξ2` and `λm = |v|`,
//!
//! ```text
//! G1 G2 = a1 a2 e^{λm − λ1 − λ2} · e^{λm (ω·v/λm − 1)}.
//! ```
//!
//! Both `λm` and the exponent `λm − λ1 − λ2 ≤ 0` are computed without cancellation:
//! `λm² = (λ1 − λ2)² + λ1 λ2 |ξ1 + ξ2|²` (all terms non-negative, accurate for nearly
//! opposite axes) and `λm − λ1 − λ2 = (λm² − (λ1 + λ2)²) / (λm + λ1 + λ2)
//! = −λ1 λ2 |ξ1 − ξ2|² / (λm + λ1 + λ2)` (accurate for nearly equal axes, where the
//! plain difference of `λ ~ 1e6` values would lose everything). When the axes cancel
//! (`λ1 = λ2`, `ξ1 = −ξ2`) the product is the constant `a1 a2 e^{−2λ1}`: sharpness 0
//! and the first factor's axis (any finite axis would do). The inner product is
//! `∫ G1 G2 dω = a1 a2 e^{λm − λ1 − λ2} A(λm)`, formed in log space.
//!
//! # Clamps
//!
//! Sharpness is clamped to `[0, MAX_SHARPNESS]` (NaN and negative values to 0, the
//! constant function). `MAX_SHARPNESS = 1e8` is a lobe of angular width
//! `1/√λ = 1e-4` rad, still ~1700 `f32` direction ulps (6e-8) wide, so evaluation and
//! sampling remain meaningful; sharper lobes would be a matter of rounding the axis.
//! Products add sharpness, so a product is clamped again. Log amplitudes are clamped to
//! `[MIN_LOG_AMPLITUDE, MAX_LOG_AMPLITUDE]`: the lower end stands for amplitude 0
//! (finite, so that sums of log amplitudes never form `−∞ + ∞`), the upper end is
//! `ln f32::MAX`, and every value leaving the module is clamped to `f32::MAX`.

use crate::Vec3;
use core::f32::consts::TAU;

/// The largest sharpness an SG may have (see the module documentation).
pub const MAX_SHARPNESS: f32 = 1e8;

/// The log amplitude that stands for amplitude 0: `e^{−1e30}` is 0, and the value is
/// finite so that adding log amplitudes never gives NaN.
pub const MIN_LOG_AMPLITUDE: f32 = -1e30;

/// `ln f32::MAX`: the largest log amplitude whose exponential is finite.
pub const MAX_LOG_AMPLITUDE: f32 = 88.722_83;

/// `ln(2π)`.
pub(crate) const LN_TAU: f32 = 1.837_877_1;

/// A spherical Gaussian `G(ω) = exp(log_amplitude) · exp(λ(ω·ξ − 1))` with unit axis
/// `ξ = axis` and sharpness `λ = sharpness`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sg {
    /// Unit lobe axis `ξ`.
    pub axis: Vec3,
    /// Sharpness `λ` in `[0, 1e8]` (`MAX_SHARPNESS`).
    pub sharpness: f32,
    /// Natural logarithm of the amplitude (the value at the axis), in
    /// `[−1e30, 88.72283]` (`MIN_LOG_AMPLITUDE`, `ln FLT_MAX`); −1e30 means amplitude 0.
    pub log_amplitude: f32,
}

/// `x` clamped to `[0, MAX_SHARPNESS]`; NaN (and negative values) give 0.
#[inline(always)]
pub(crate) fn clamp_sharpness(x: f32) -> f32 {
    x.max(0.0).min(MAX_SHARPNESS)
}

/// `x` clamped to `[MIN_LOG_AMPLITUDE, MAX_LOG_AMPLITUDE]`; NaN gives
/// `MIN_LOG_AMPLITUDE` (amplitude 0).
#[inline(always)]
pub(crate) fn clamp_log_amplitude(x: f32) -> f32 {
    x.max(MIN_LOG_AMPLITUDE).min(MAX_LOG_AMPLITUDE)
}

/// `ln x` for an amplitude: `MIN_LOG_AMPLITUDE` for `x ≤ 0` or NaN, clamped above.
#[inline(always)]
pub(crate) fn log_of_amplitude(x: f32) -> f32 {
    if x > 0.0 {
        clamp_log_amplitude(libm::logf(x))
    } else {
        MIN_LOG_AMPLITUDE
    }
}

/// `e^x`, finite for every input: at most `f32::MAX`, and 0 for NaN.
#[inline(always)]
pub(crate) fn exp_finite(x: f32) -> f32 {
    if x.is_nan() {
        return 0.0;
    }
    libm::expf(x.min(MAX_LOG_AMPLITUDE)).min(f32::MAX)
}

/// A unit vector along `v`, or `None` for a zero or non-finite `v`: the shared helper
/// [`crate::math::unit`].
pub(crate) use crate::math::unit as unit_or_none;

/// `A(λ) = ∫ e^{λ(ω·ξ − 1)} dω = 2π/λ (1 − e^{−2λ})` (Section 2), evaluated as
/// `−2π expm1(−2λ)/λ`: `4π` at `λ = 0` (and the limit as `λ → 0`), `2π/λ` to full
/// precision for large `λ`. Sharpness is clamped to `[0, MAX_SHARPNESS]` (NaN to 0).
#[inline]
pub fn sg_integral(sharpness: f32) -> f32 {
    let l = clamp_sharpness(sharpness);
    if !(l > 1e-20) {
        return 2.0 * TAU;
    }
    -TAU * libm::expm1f(-2.0 * l) / l
}

/// `ln A(λ)`, for integrals formed in log space.
#[inline]
pub fn log_sg_integral(sharpness: f32) -> f32 {
    libm::logf(sg_integral(sharpness))
}

/// `(1 − e^{−2λ}) / λ` for `λ ≥ 0` (2 at `λ = 0`): `A(λ)/(2π)`, the normaliser of the
/// vMF density.
#[inline(always)]
pub(crate) fn one_minus_exp_over(l: f32) -> f32 {
    if !(l > 1e-20) {
        return 2.0;
    }
    -libm::expm1f(-2.0 * l) / l
}

impl Sg {
    /// The constant function 0 (axis `z`, sharpness 0, amplitude 0).
    ///
    /// cbindgen:ignore
    pub const ZERO: Sg = Sg {
        axis: Vec3::Z,
        sharpness: 0.0,
        log_amplitude: MIN_LOG_AMPLITUDE,
    };

    /// The SG with lobe axis `axis` (normalised here), sharpness `sharpness` (clamped to
    /// `[0, MAX_SHARPNESS]`, NaN to 0) and amplitude `amplitude` (its value on the axis;
    /// `≤ 0` or NaN gives amplitude 0, `+∞` is clamped to `f32::MAX`). A zero or
    /// non-finite axis gives [`Sg::ZERO`].
    pub fn new(axis: Vec3, sharpness: f32, amplitude: f32) -> Sg {
        Sg::from_log_amplitude(axis, sharpness, log_of_amplitude(amplitude))
    }

    /// As [`Sg::new`], with the amplitude given by its natural logarithm (clamped to
    /// `[MIN_LOG_AMPLITUDE, MAX_LOG_AMPLITUDE]`, NaN to amplitude 0).
    pub fn from_log_amplitude(axis: Vec3, sharpness: f32, log_amplitude: f32) -> Sg {
        match unit_or_none(axis) {
            Some(axis) => Sg {
                axis,
                sharpness: clamp_sharpness(sharpness),
                log_amplitude: clamp_log_amplitude(log_amplitude),
            },
            None => Sg::ZERO,
        }
    }

    /// The same SG with every field made valid: the axis normalised (a zero or
    /// non-finite axis gives [`Sg::ZERO`]), sharpness and log amplitude clamped. Values
    /// built by [`Sg::new`] are returned unchanged; the C ABI sanitises every SG it
    /// receives.
    pub fn sanitized(&self) -> Sg {
        Sg::from_log_amplitude(self.axis, self.sharpness, self.log_amplitude)
    }

    /// The amplitude `e^{log_amplitude}` (the value on the axis), at most `f32::MAX`.
    #[inline]
    pub fn amplitude(&self) -> f32 {
        exp_finite(self.log_amplitude)
    }

    /// `G(dir) = a e^{−λ/2 |dir − ξ|²}` (see the module documentation for why this form).
    /// `dir` is normalised first; a zero or non-finite `dir` gives 0.
    #[inline]
    pub fn eval(&self, dir: Vec3) -> f32 {
        match unit_or_none(dir) {
            Some(w) => exp_finite(
                self.log_amplitude - 0.5 * self.sharpness * (w - self.axis).length_squared(),
            ),
            None => 0.0,
        }
    }

    /// `∫ G dω = a A(λ)`.
    #[inline]
    pub fn integral(&self) -> f32 {
        exp_finite(self.log_amplitude + log_sg_integral(self.sharpness))
    }

    /// The product `G1 G2`, an SG (see the module documentation).
    pub fn product(&self, other: &Sg) -> Sg {
        let (l1, l2) = (self.sharpness, other.sharpness);
        let sum = self.axis + other.axis;
        let difference = self.axis - other.axis;
        let lm2 = (l1 - l2) * (l1 - l2) + l1 * l2 * sum.length_squared();
        let lm = crate::math::sqrtf(lm2);
        // λm − λ1 − λ2 ≤ 0 without cancellation; the denominator is 0 only when both
        // sharpnesses are 0.
        let denominator = lm + l1 + l2;
        let exponent = if denominator > 0.0 {
            -(l1 * l2 * difference.length_squared()) / denominator
        } else {
            0.0
        };
        let v = self.axis * l1 + other.axis * l2;
        // The axis of a lobe of sharpness below 1e-20 has no effect on any f32 value.
        let (axis, sharpness) = match unit_or_none(v) {
            Some(axis) if lm > 1e-20 => (axis, lm),
            _ => (self.axis, 0.0),
        };
        Sg {
            axis,
            sharpness: clamp_sharpness(sharpness),
            log_amplitude: clamp_log_amplitude(self.log_amplitude + other.log_amplitude + exponent),
        }
    }

    /// `∫ G1 G2 dω = a1 a2 e^{λm − λ1 − λ2} A(λm)` (the integral of the product), in
    /// log space: 0 (not `0 · ∞`) for opposite sharp lobes, `f32::MAX` at most.
    pub fn inner_product(&self, other: &Sg) -> f32 {
        self.product(other).integral()
    }
}

/// `∫ G1 G2 dω` for two SGs; see [`Sg::inner_product`].
#[inline]
pub fn sg_inner_product(a: &Sg, b: &Sg) -> f32 {
    a.inner_product(b)
}

/// The product of two SGs; see [`Sg::product`].
#[inline]
pub fn sg_product(a: &Sg, b: &Sg) -> Sg {
    a.product(b)
}
