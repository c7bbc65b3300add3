//! Spherical caps: the set of directions that a sphere light subtends, and sampling
//! uniformly in solid angle inside it.
//!
//! A cap is the set `{ω ∈ S² : ω·a ≥ cos θ}` for a unit axis `a` and half-angle
//! `θ ∈ [0, π]`; its solid angle is `Ω = 2π (1 − cos θ)`. A sphere of radius `r` whose
//! center lies at distance `d > r` from the shading point subtends the cap with
//! `sin θ = r / d`; a shading point inside (or on) the sphere sees every direction.
//!
//! The cap stores `t = 1 − cos θ` computed as `sin²θ / (1 + cos θ)`, which keeps full
//! relative precision for tiny caps: `1 − cos θ` evaluated by subtraction in `f32`
//! rounds to zero below `sin²θ ≈ 1e-7` (and is only a few bits accurate near 1e-6),
//! while the quotient is accurate to a few ulps down to `sin²θ` at the bottom of the
//! normal range. Every other quantity (solid angle, sampling, containment, inversion)
//! is derived from `t` without forming `1 − cos` again:
//!
//! - sampling: `t' = u₀ t` is uniform in `[0, t]` (uniform in solid angle, since
//!   `dΩ = d(1 − cos) dφ`), and the direction is built from `sin θ' = √(t'(2 − t'))`,
//!   `cos θ' = 1 − t'`, `φ = 2π u₁`;
//! - containment and inversion: for unit vectors `|ω − a|² = 2 (1 − ω·a)`, which gives
//!   `1 − cos` of a direction without cancellation.
//!
//! Hard cases: tiny caps (`sin²θ` down to 1e-12 and below), caps wider than a
//! hemisphere (`θ > π/2`, `cos θ < 0`), the whole sphere (shading point inside the
//! sphere, `t = 2`), the shading point on the sphere (`d = r`, the whole sphere; just
//! outside it, nearly a hemisphere), distant spheres (`d = 1e6 r`), huge or tiny
//! coordinates (the center and radius are rescaled by a power of two before squaring),
//! and invalid input (non-finite center, non-finite, zero or negative radius), which
//! gives [`Cap::EMPTY`], a cap of solid angle 0 from which no sample is drawn.

use crate::Sample;
use crate::math::orthonormal_basis;
use crate::sample::{INWARD_PULLS, ONE_MINUS_ULP, clamp_random};
use core::f32::consts::{PI, TAU};
use glam::Vec3;

/// A spherical cap `{ω : ω·axis ≥ cos}` with `1 − cos` stored to full relative
/// precision.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cap {
    /// Unit axis (direction of the cap's center).
    pub axis: Vec3,
    /// `1 − cos θ` in `[0, 2]`: 0 for an empty cap, 1 for a hemisphere, 2 for the whole
    /// sphere.
    pub one_minus_cos: f32,
    /// `cos θ` in `[−1, 1]`.
    pub cos: f32,
    /// `sin²θ = (1 − cos θ)(1 + cos θ)` in `[0, 1]`.
    pub sin2: f32,
}

/// `2^k` for `k` in `[−126, 127]`.
#[inline(always)]
fn power_of_two(k: i32) -> f32 {
    f32::from_bits(((127 + k) as u32) << 23)
}

/// A power of two `s` such that `m s` lies in `[1, 2)` for a normal finite positive
/// `m` (and is at least `2^-23` for a subnormal one), returned as two factors so that
/// each stays representable.
#[inline(always)]
fn rescaling(m: f32) -> (f32, f32) {
    let biased = ((m.to_bits() >> 23) & 0xff) as i32;
    let k = 127 - biased;
    let k1 = k / 2;
    (power_of_two(k1), power_of_two(k - k1))
}

impl Cap {
    /// The empty cap: solid angle 0, contains nothing, draws no sample.
    ///
    /// cbindgen:ignore
    pub const EMPTY: Cap = Cap {
        axis: Vec3::Z,
        one_minus_cos: 0.0,
        cos: 1.0,
        sin2: 0.0,
    };

    /// The whole sphere around the axis `z`.
    ///
    /// cbindgen:ignore
    pub const WHOLE_SPHERE: Cap = Cap {
        axis: Vec3::Z,
        one_minus_cos: 2.0,
        cos: -1.0,
        sin2: 0.0,
    };

    /// The cap that a sphere of radius `radius` centered at `center` (relative to the
    /// shading point) subtends: `sin θ = r / d`, `cos θ = √((d − r)(d + r)) / d`,
    /// `1 − cos θ = sin²θ / (1 + cos θ)`. The whole sphere when `d ≤ r` (axis `z` when
    /// the center is the shading point); [`Cap::EMPTY`] for a non-finite center or a
    /// radius that is not finite and positive.
    pub fn from_sphere(center: Vec3, radius: f32) -> Cap {
        if !center.is_finite() || !(radius > 0.0) || !radius.is_finite() {
            return Cap::EMPTY;
        }
        // Rescale by a power of two (exact) so that squaring neither overflows nor
        // underflows.
        let m = center.abs().max_element().max(radius);
        let (s1, s2) = rescaling(m);
        let c = center * s1 * s2;
        let r = radius * s1 * s2;
        let d = c.length();
        if !(d > r) {
            let axis = if d > 0.0 { c / d } else { Vec3::Z };
            return Cap {
                axis,
                ..Cap::WHOLE_SPHERE
            };
        }
        let axis = c / d;
        let sin = r / d;
        let sin2 = sin * sin;
        let cos = libm::sqrtf((d - r) * (d + r)) / d;
        Cap {
            axis,
            one_minus_cos: (sin2 / (1.0 + cos)).min(1.0),
            cos,
            sin2,
        }
    }

    /// The cap around `axis` (normalised here) with `cos θ = cos` (clamped to
    /// `[−1, 1]`). [`Cap::EMPTY`] for a non-finite or zero axis or a NaN `cos`. Tiny caps
    /// lose precision in `1 − cos`; prefer [`Cap::from_axis_one_minus_cos`] for them.
    pub fn from_axis_cos(axis: Vec3, cos: f32) -> Cap {
        if cos.is_nan() {
            return Cap::EMPTY;
        }
        let cos = cos.max(-1.0).min(1.0);
        Cap::from_axis_one_minus_cos(axis, 1.0 - cos)
    }

    /// The cap around `axis` (normalised here) with `1 − cos θ = one_minus_cos`
    /// (clamped to `[0, 2]`). [`Cap::EMPTY`] for a non-finite or zero axis or a NaN
    /// `one_minus_cos`.
    pub fn from_axis_one_minus_cos(axis: Vec3, one_minus_cos: f32) -> Cap {
        // Normalised by the largest component first: a huge axis overflowed `length`,
        // and a tiny one (components of 1e-23) normalised through denormal squares to
        // length 1.006 (found by fuzzing).
        let unit = crate::sample::normalize_scaled(axis);
        if unit == Vec3::ZERO || one_minus_cos.is_nan() {
            return Cap::EMPTY;
        }
        let t = one_minus_cos.max(0.0).min(2.0);
        Cap {
            axis: unit,
            one_minus_cos: t,
            cos: 1.0 - t,
            sin2: (t * (2.0 - t)).max(0.0),
        }
    }

    /// This cap with every field made valid: a non-finite or zero axis or a NaN
    /// `one_minus_cos` gives [`Cap::EMPTY`]; otherwise the axis is normalised,
    /// `one_minus_cos` clamped to `[0, 2]`, and `cos` and `sin2` recomputed from it. Used
    /// by the C ABI, where a caller may build a cap by hand.
    pub fn sanitized(self) -> Cap {
        Cap::from_axis_one_minus_cos(self.axis, self.one_minus_cos)
    }

    /// The half-angle `θ = 2 asin(√(t/2))` (accurate for tiny caps, unlike `acos`).
    #[inline]
    pub fn half_angle(&self) -> f32 {
        2.0 * libm::asinf(libm::sqrtf((0.5 * self.one_minus_cos).max(0.0).min(1.0)))
    }

    /// The solid angle `2π (1 − cos θ)`, in `[0, 4π]`.
    #[inline]
    pub fn solid_angle(&self) -> f32 {
        TAU * self.one_minus_cos
    }

    /// `1 − ω·axis` for a direction `dir` (normalised here), computed as
    /// `|ω − axis|² / 2`; `None` for a non-finite or zero `dir`.
    #[inline]
    fn one_minus_cos_of(&self, dir: Vec3) -> Option<f32> {
        let unit = crate::math::unit(dir)?;
        Some(0.5 * (unit - self.axis).length_squared())
    }

    /// Whether `dir` (any non-zero finite vector) points into the cap (boundary
    /// included). The empty cap contains nothing; the whole sphere contains every
    /// valid direction.
    #[inline]
    pub fn contains(&self, dir: Vec3) -> bool {
        if !(self.one_minus_cos > 0.0) {
            return false;
        }
        if self.one_minus_cos >= 2.0 {
            return dir.is_finite() && dir != Vec3::ZERO;
        }
        // The shared helper: `dir / |dir|` overflowed or underflowed for long and short
        // directions (issue 17, 5).
        let Some(unit) = crate::math::unit(dir) else {
            return false;
        };
        if self.one_minus_cos > 1.0 {
            // Wider than a hemisphere: the boundary is near the antipode, where
            // `|ω − a|²/2` is close to 2 and has lost the absolute precision that the
            // excluded disk needs (found by fuzzing: a sample 2e-4 rad inside a cap with
            // `1 − cos θ = 2 − ulp` was outside). Compared in the complement instead:
            // `1 + ω·a = |ω + a|²/2 >= 1 + cos θ = 2 − (1 − cos θ)`, which is exact.
            0.5 * (unit + self.axis).length_squared() >= 2.0 - self.one_minus_cos
        } else {
            0.5 * (unit - self.axis).length_squared() <= self.one_minus_cos
        }
    }

    /// Draws a direction uniformly (in solid angle) inside the cap:
    /// `1 − cos θ' = u₀ (1 − cos θ)`, `φ = 2π u₁`, pdf `1 / Ω`. No sample (pdf 0) from
    /// an empty cap or one whose pdf would overflow.
    #[inline]
    pub fn sample_uniform(&self, u: [f32; 2]) -> Sample {
        let pdf = self.uniform_pdf();
        if pdf == 0.0 {
            return Sample::NONE;
        }
        let t = clamp_random(u[0]) * self.one_minus_cos;
        let phi = TAU * clamp_random(u[1]);
        let sin = libm::sqrtf((t * (2.0 - t)).max(0.0));
        let (sin_phi, cos_phi) = libm::sincosf(phi);
        let (tangent, bitangent) = orthonormal_basis(self.axis);
        let dir = tangent * (sin * cos_phi) + bitangent * (sin * sin_phi) + self.axis * (1.0 - t);
        let dir = dir.normalize_or(self.axis);
        if self.contains(dir) {
            return Sample { dir, pdf };
        }
        // Rounding put a sample from the rim just outside (for small caps the rounding
        // of a unit vector, 6e-8, is a large part of the radius: 10 of 16 draws at
        // u0 = 1 - 1e-5 for a 1e-7 sr cap), where `pdf` is 0 (issue 16, 4): pulled
        // towards the axis until inside (`INWARD_PULLS`; a cap below about 1e-6 rad,
        // which `f32` directions do not resolve, gets its axis).
        INWARD_PULLS
            .iter()
            .map(|&pull| (dir * (1.0 - pull) + self.axis * pull).normalize_or(self.axis))
            .find(|&pulled| self.contains(pulled))
            .map_or(Sample::NONE, |dir| Sample { dir, pdf })
    }

    /// `1 / Ω`, or 0 when the cap is empty or `1/Ω` is not finite.
    #[inline]
    fn uniform_pdf(&self) -> f32 {
        if !(self.one_minus_cos > 0.0) {
            return 0.0;
        }
        let pdf = 1.0 / (TAU * self.one_minus_cos);
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// The density of [`Cap::sample_uniform`]: `1 / Ω` inside the cap, 0 outside.
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        if self.contains(dir) {
            self.uniform_pdf()
        } else {
            0.0
        }
    }

    /// The random numbers that [`Cap::sample_uniform`] maps to `dir`:
    /// `u₀ = (1 − dir·axis) / (1 − cos θ)`, `u₁ = φ / 2π`; `None` outside the cap.
    pub fn invert(&self, dir: Vec3) -> Option<[f32; 2]> {
        if !self.contains(dir) || self.uniform_pdf() == 0.0 {
            return None;
        }
        let t = self.one_minus_cos_of(dir)?;
        let u0 = (t / self.one_minus_cos).min(ONE_MINUS_ULP);
        let (tangent, bitangent) = orthonormal_basis(self.axis);
        let mut phi = libm::atan2f(dir.dot(bitangent), dir.dot(tangent));
        if phi < 0.0 {
            phi += TAU;
        }
        let u1 = (phi * (0.5 / PI)).max(0.0).min(ONE_MINUS_ULP);
        Some([u0, u1])
    }
}

#[cfg(test)]
#[path = "cap_tests.rs"]
mod tests;
