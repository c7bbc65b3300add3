//! The solid angle of the intersection of two spherical caps (Dupuy et al. 2017,
//! Appendix B; Tovchigrechko and Vakser 2001; Oat and Sander 2007).
//!
//! Caps `C₁, C₂` with half-angles `θ₁, θ₂` and axes `a₁, a₂` at angle `d`. Writing
//! `tᵢ = 1 − cos θᵢ` and `t_d = 1 − cos d = |a₁ − a₂|²/2` (no cancellation):
//!
//! - `d ≥ θ₁ + θ₂`: disjoint, 0;
//! - `d ≤ |θ₁ − θ₂|`: one inside the other, the smaller solid angle;
//! - `d ≥ 2π − θ₁ − θ₂`: the complements are disjoint, so the union is the sphere and
//!   the intersection is `Ω₁ + Ω₂ − 4π` (a case that Eq. 35 of the paper omits; it
//!   happens only when both caps are wider than a hemisphere);
//! - otherwise the boundary circles cross at two points `P, P'` and the intersection
//!   is a lens. By Gauss–Bonnet (the geodesic curvature of a circle of angular radius
//!   `θ` is `cot θ`, so an arc spanning azimuth `2φ` contributes `2φ cos θ`) its area
//!   is `2(π − γ) − 2φ₁ cos θ₁ − 2φ₂ cos θ₂`, where `φᵢ` is the angle at `aᵢ` and `γ`
//!   the angle at `P` of the spherical triangle `(a₁, a₂, P)` (this is Eq. 36 with
//!   `acos(−x) = π − acos(x)`). The triangle's angles add up to `π + E` with `E` its
//!   area, so the lens area is `2φ₁ t₁ + 2φ₂ t₂ − 2E`: every term uses `tᵢ`, not
//!   `cos θᵢ`. With `Nᵢ = cos θⱼ − cos θᵢ cos d = tᵢ + t_d − tⱼ − tᵢ t_d` and
//!   `Y = |a₁·(a₂ × P)| = √(sin²θ₁ sin²d − N₁²)` (the same for both caps),
//!   `φᵢ = atan2(Y, Nᵢ)` and, by Van Oosterom and Strackee,
//!   `E = 2 atan2(Y, 1 + cos d + cos θ₁ + cos θ₂) = 2 atan2(Y, 4 − t_d − t₁ − t₂)`:
//!   no `acos` anywhere, so nothing is lost near ±1.
//!
//! The case boundaries compare the angles `θ = 2 asin(√(t/2))` (accurate for small
//! angles); the lens formula is continuous with every case at its boundary (`Y = 0`),
//! and the result is clamped to `[max(0, Ω₁ + Ω₂ − 4π), min(Ω₁, Ω₂)]`. Caps wider
//! than a hemisphere are first replaced by their complements (see
//! [`cap_intersection_solid_angle`]), which also takes care of the union case.
//!
//! # The Oat–Sander approximation
//!
//! Eq. 37–38 replace the lens by `2π(1 − cos θ₁) P((θ₁ + θ₂ − d) / (2θ₁))` with
//! `θ₁ ≤ θ₂` and the smoothstep `P(x) = 3x² − 2x³`, which is exact at both ends of the
//! lens case. Error against the exact formula over a grid of `θ₁ ≤ θ₂` and `d`
//! (half-angles `θ₁ ≤ θ₂` at the centers of 128 steps of `[0, π]`, axis angles at the
//! centers of 256 steps, lens cases only, i.e. `θ₂ − θ₁ < d < θ₁ + θ₂`; the relative
//! error is over the exact area, for areas above 1e-3 sr), from
//! `oat_sander_error_table` in the tests (`cargo test -p sphera --lib oat_sander --
//! --nocapture`):
//!
//! | half-angles        | mean abs (sr) | max abs (sr) | mean rel | max rel |
//! |--------------------|---------------|--------------|----------|---------|
//! | θ₂ ≤ π/8          | 9.39e-3       | 7.04e-2      | 1.49e-1  | 6.30e-1 |
//! | π/8 < θ₂ ≤ π/4    | 3.61e-2       | 2.58e-1      | 1.52e-1  | 7.70e-1 |
//! | π/4 < θ₂ ≤ π/2    | 1.08e-1       | 6.03e-1      | 1.68e-1  | 9.86e-1 |
//! | π/2 < θ₂ ≤ π      | 1.06          | 6.83         | 2.18e-1  | 9.94e-1 |
//!
//! (Rows by the larger half-angle `θ₂`.) The relative error is largest near tangency
//! (the smoothstep has zero slope at `x = 0` where the true lens area grows like
//! `x^{3/2}`), so even small caps see relative errors of tens of percent at the rim
//! of the overlap while the mean stays near 15%; the absolute error grows with the
//! caps, and the formula breaks down for caps wider than a hemisphere, where it
//! ignores the case in which the union covers the sphere and misses the exact value
//! by up to 6.8 sr. Use it only for caps up to about a hemisphere and where a
//! smooth, cheap estimate is enough.

use super::cap::Cap;
use crate::math::{atan2_upper_half_plane4, sqrt4};
use core::f32::consts::{FRAC_PI_2, PI};
use glam::Vec4;

/// The half-angle `θ = 2 asin(√(t/2))` of `t = 1 − cos θ`.
#[inline(always)]
pub(crate) fn angle_of(t: f32) -> f32 {
    2.0 * libm::asinf(crate::math::sqrtf((0.5 * t).max(0.0).min(1.0)))
}

/// `1 − a·b` of two unit axes, as `|a − b|²/2`, in `[0, 2]`.
#[inline(always)]
pub(crate) fn one_minus_dot(a: crate::Vec3, b: crate::Vec3) -> f32 {
    // `x.min(2.0)` as a compare and select: the same value for every `x` (NaN gives 2,
    // as `f32::min` does, and 2 has no signed twin), one `minss` instead of `f32::min`'s
    // NaN handling.
    let x = 0.5 * (a - b).length_squared();
    if x < 2.0 { x } else { 2.0 }
}

/// `a.min(b)` as a compare and select, for operands that are not NaN and not both zero:
/// then the same bits as `f32::min` (which otherwise costs a NaN test and a blend on
/// x86), since the smaller of two distinct ordered values, or either of two equal
/// nonzero ones, is one value.
#[inline(always)]
pub(crate) fn min_ordered(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// `a.max(b)` as a compare and select, under the conditions of [`min_ordered`] (neither
/// operand NaN, not zeros of opposite signs): the same bits as `f32::max`.
#[inline(always)]
pub(crate) fn max_ordered(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

/// The exact solid angle of `a ∩ b` (see the module documentation). The caps must be
/// valid (unit axes, `one_minus_cos` in `[0, 2]`; see [`Cap::sanitized`]).
///
/// A cap wider than a hemisphere is replaced by its complement `(−axis, 1 + cos θ)`,
/// with the stored hole `1 + cos θ` (issue 17, 6: `2 − t` is exact for `t ∈ [1, 2]`,
/// but `t` itself kept only `ulp(2)` of a small hole): `Ω(C₁ ∩ C₂) = Ω₂ − Ω(C̄₁ ∩ C₂)`. The lens
/// formula then only sees caps up to a hemisphere, where `t_d` near 2 (nearly
/// antipodal axes, which the complement brings close together) cannot occur with an
/// overlap, so `|a₁ − a₂|²/2` never has to resolve `2 − t_d`.
pub fn cap_intersection_solid_angle(a: &Cap, b: &Cap) -> f32 {
    // The caps in a canonical order (by `t`, then by the hole and the axes' bits), so
    // that the rounding is the same either way round: Ω(a ∩ b) = Ω(b ∩ a) bit for bit.
    let key = |c: &Cap| {
        (
            c.one_minus_cos.to_bits(),
            c.one_plus_cos.to_bits(),
            c.axis.x.to_bits(),
            c.axis.y.to_bits(),
            c.axis.z.to_bits(),
        )
    };
    let (a, b) = if key(a) <= key(b) { (a, b) } else { (b, a) };
    let (t1, t2) = (a.one_minus_cos, b.one_minus_cos);
    let (h1, h2) = (a.one_plus_cos, b.one_plus_cos);
    if !(t1 > 0.0) || !(t2 > 0.0) {
        return 0.0;
    }
    let omega = |t: f32| 2.0 * PI * t;
    let result = match (t1 > 1.0, t2 > 1.0) {
        (false, false) => at_most_hemispheres(a.axis, t1, b.axis, t2),
        (true, false) => omega(t2) - at_most_hemispheres(-a.axis, h1, b.axis, t2),
        (false, true) => omega(t1) - at_most_hemispheres(a.axis, t1, -b.axis, h2),
        (true, true) => {
            // C₁ ∩ C₂ is the complement of C̄₁ ∪ C̄₂.
            4.0 * PI - omega(h1) - omega(h2) + at_most_hemispheres(-a.axis, h1, -b.axis, h2)
        }
    };
    let low = (omega(t1) + omega(t2) - 4.0 * PI).max(0.0);
    result.max(low).min(omega(t1).min(omega(t2)))
}

/// The intersection of two caps with `tᵢ ∈ [0, 1]` (at most hemispheres).
#[inline(always)]
fn at_most_hemispheres(a1: crate::Vec3, t1: f32, a2: crate::Vec3, t2: f32) -> f32 {
    if !(t1 > 0.0) || !(t2 > 0.0) {
        return 0.0;
    }
    let td = one_minus_dot(a1, a2);
    // (Inlined: the half arc `φ₁` beside the area is left out by the compiler.)
    lens_and_half_arc_of_sides(t1, t2, td, crate::math::sqrtf(2.0 * td), || {
        crate::math::sqrtf((1.0 - 0.5 * td).max(0.0))
    })[0]
}

/// The intersection of two caps with `tᵢ ∈ (0, 1]` from their sides `t₁, t₂` and the
/// axes' `t_d`, and the half-width `φ₁` in azimuth of the first cap's circle inside the
/// second, as [`lens_and_half_arc`] gives them, without the angles `θᵢ = angle_of(tᵢ)`,
/// `d = angle_of(t_d)` except near the cases' boundaries (three `asin`): `w = √(2t_d)` and
/// `cos(d/2) = √(1 − t_d/2)` (needed only by the spherical Heron form, hence a closure)
/// are the caller's, so that the radial inversion of a cap intersection, which evaluates
/// this for many `t₁` against one cap, computes them once (issue 18: an `asin` of `t₁`
/// per Newton step, and the two `sin` of the Heron form, fewer).
///
/// The same bits as `lens_and_half_arc([t₁, θ₁], [t₂, θ₂], [t_d, d])` except where the
/// Gram form of `Y²` cancels: there the spherical Heron form from the half-angles' sines
/// and cosines (`heron_y2_from_roots`) in place of [`lens_and_half_arc`]'s sines of half-angle
/// sums (tested against an `f64` reference: `the_sides_form_of_the_lens_is_as_accurate`).
/// The nested case's `φ₁` (π for the first cap inside the second, 0 for the second inside
/// the first): `θ₁ ≤ θ₂` there exactly when `t₁ ≤ t₂` (`1 − cos` increases on `[0, π]`;
/// nested with the margin below, the sides differ by far more than their rounding).
#[inline(always)]
pub(crate) fn lens_and_half_arc_of_sides(
    t1: f32,
    t2: f32,
    td: f32,
    w: f32,
    cos_half_d: impl FnOnce() -> f32,
) -> [f32; 2] {
    // (The Heron form's `p = √(h₁h₂)`, `q = √(t₁t₂)` packed with `u`, `v` in one `sqrt4`:
    // 4 instructions more per evaluation of the SPTD sphere light sampler's radial CDF,
    // measured, for roots that the Gram form does not need.)
    let (h1, h2) = (2.0 - t1, 2.0 - t2);
    let (u, v) = (crate::math::sqrtf(t1 * h2), crate::math::sqrtf(t2 * h1));
    let margin = 1e-5 * (u + v);
    if w >= u + v + margin {
        return [0.0, 0.0];
    }
    if w <= (u - v).abs() - margin {
        return [2.0 * PI * t1.min(t2), if t1 <= t2 { PI } else { 0.0 }];
    }
    if w >= (u - v).abs() + margin && w <= u + v - margin {
        // Surely the lens: the angles are needed only by the spherical Heron form of
        // `Y²` (see below), which the well-conditioned Gram form rarely leaves to.
        let (gram, plain, n1) = lens_gram(t1, t2, td);
        // The smaller side as a compare and select (`min_ordered`: `f32::min`'s NaN test
        // and blend were 6 instructions per evaluation of the lens): `t₁, t₂ > 0` (this
        // function's contract; the case's tests also fail for a NaN side, and for a zero
        // side beside a positive one), so `f32::min`'s bits.
        let smaller = min_ordered(t1, t2);
        if plain >= 0.5 * gram {
            return lens_area(t1, t2, td, n1, plain, smaller);
        }
        let (p, q) = (crate::math::sqrtf(h1 * h2), crate::math::sqrtf(t1 * t2));
        let y2 = heron_y2_from_roots([u, v, w], [cos_half_d(), p, q]);
        return lens_area(t1, t2, td, n1, y2, smaller);
    }
    lens_and_half_arc_of_angles(t1, t2, td)
}

/// [`lens_and_half_arc_of_sides`] near a case's boundary (the margins of its tests), where
/// the case is decided from the angles: [`lens_and_half_arc`] of `θᵢ = angle_of(tᵢ)`, `d =
/// angle_of(t_d)`. Out of line and cold: in line, the compiler hoisted the part of the
/// loop-invariant angles it could (the square roots of `angle_of(t₂)` and `angle_of(t_d)`,
/// their clamps and the spills) out of the radial inversion's Newton loop of a cap
/// intersection, so that every inversion paid for them although nearly no evaluation
/// takes this path (issue 18: 17 instructions per clipped sample of the SPTD sphere light
/// sampler, 805.4 -> 788.7, callgrind, light bench `sptd`).
#[cold]
#[inline(never)]
fn lens_and_half_arc_of_angles(t1: f32, t2: f32, td: f32) -> [f32; 2] {
    let (theta1, theta2, d) = (angle_of(t1), angle_of(t2), angle_of(td));
    lens_and_half_arc([t1, theta1], [t2, theta2], [td, d])
}

// The spherical Heron form of `Y²` (see [`at_most_hemispheres`]) from the half-angles'
// sines and cosines instead of the angles: with `A = θ₁/2`, `B = θ₂/2`, `D = d/2` and
// `s = A + B + D`, `Y² = 4 sin s sin(s − θ₁) sin(s − θ₂) sin(s − d)` where
// `s − θ₁ = D + (B − A)`, `s − θ₂ = D − (B − A)`, `s − d = (A + B) − D`, and
// `2 sin(A ± B) = √(t₁h₂) ± √(t₂h₁)` (`u ± v`), `2 cos(A ± B) = √(h₁h₂) ∓ √(t₁t₂)`,
// `sin D = √(t_d/2)`, `cos D = √(1 − t_d/2)`. Each factor is a sum of two products of
// such terms: its rounding is a few ulps of 1 where a difference of angles (of order 1,
// rounded by `asin`) had the same, with no `asin` or `sin`
// (`lens_and_half_arc_of_sides`, `heron_y2_fast`, `heron_y2_from_roots`).

/// The spherical Heron form of `Y²` from `t₁, t₂, t_d` and `u = √(t₁h₂)`, `v = √(t₂h₁)`,
/// `w = √(2t_d)`, its other roots one by one: the scalar reference of [`heron_y2_fast`]
/// in the tests (`lens_and_half_arc_of_sides` computes the same roots the same way).
#[cfg(test)]
fn heron_y2([t1, t2, td]: [f32; 3], [u, v, w]: [f32; 3]) -> f32 {
    let (h1, h2) = (2.0 - t1, 2.0 - t2);
    let cos_d = crate::math::sqrtf((1.0 - 0.5 * td).max(0.0));
    let (p, q) = (crate::math::sqrtf(h1 * h2), crate::math::sqrtf(t1 * t2));
    heron_y2_from_roots([u, v, w], [cos_d, p, q])
}

/// The spherical Heron form of `Y²` from `t₁, t₂, t_d` and the squares `u², v², w²` of
/// [`at_most_hemispheres_fast`], its six square roots as two packed ones (`sqrt4`: one
/// `sqrtps` each on x86-64, where six `sqrtss` queued on the one square-root unit;
/// correctly rounded either way, so the same bits as six `sqrtf`).
#[inline(always)]
fn heron_y2_fast([t1, t2, td]: [f32; 3], [uu, vv, ww]: [f32; 3]) -> f32 {
    let (h1, h2) = (2.0 - t1, 2.0 - t2);
    // `1 − t_d/2 ≥ 0` without the clamp of `at_most_hemispheres`: the shading's `t_d` is in `[0, 2]`.
    let [u, v, w, cos_d] = sqrt4(Vec4::new(uu, vv, ww, 1.0 - 0.5 * td)).to_array();
    let [p, q, _, _] = sqrt4(Vec4::new(h1 * h2, t1 * t2, 0.0, 0.0)).to_array();
    heron_y2_from_roots([u, v, w], [cos_d, p, q])
}

/// The spherical Heron form of `Y²` (see above) from the roots `u, v, w` and `cos(d/2) =
/// √(1 − t_d/2)`, `p = √(h₁h₂)`, `q = √(t₁t₂)`.
#[inline(always)]
fn heron_y2_from_roots([u, v, w]: [f32; 3], [cos_d, p, q]: [f32; 3]) -> f32 {
    let sin_d = 0.5 * w;
    let (sin_sum, sin_diff) = (0.5 * (u + v), 0.5 * (v - u));
    let (cos_sum, cos_diff) = (0.5 * (p - q), 0.5 * (p + q));
    let sin_s = sin_sum * cos_d + cos_sum * sin_d;
    let f1 = sin_d * cos_diff + cos_d * sin_diff;
    let f2 = sin_d * cos_diff - cos_d * sin_diff;
    let fd = sin_sum * cos_d - cos_sum * sin_d;
    4.0 * sin_s.max(0.0) * f1.max(0.0) * f2.max(0.0) * fd.max(0.0)
}

/// [`at_most_hemispheres`] with the half-angles `θᵢ = angle_of(tᵢ)` and the axes' angle
/// `d = angle_of(t_d)` given (`tᵢ ∈ (0, 1]`): the uniform sampler of an intersection
/// evaluates it for many `t₁` against one cap, whose `θ₂`, `t_d` and `d` it computes
/// once ([`CapIntersection`](super::CapIntersection)'s radial inversion).
#[cfg(test)]
#[inline(always)]
pub(crate) fn at_most_hemispheres_with_angles(
    first: [f32; 2],
    second: [f32; 2],
    axes: [f32; 2],
) -> f32 {
    lens_and_half_arc(first, second, axes)[0]
}

/// [`at_most_hemispheres_with_angles`] and, beside it, the half-width `φ₁` in azimuth of
/// the first cap's boundary circle inside the second cap: 0 for disjoint caps and for
/// the second inside the first, π for the first inside the second, and in the lens case
/// the formula's own `φ₁ = atan2(Y, N₁)` (`cos φ₁ = N₁ / (sin θ₁ sin d)`, the spherical
/// law of cosines in the triangle of the two axes and a point of the circle). `2 φ₁` is
/// `dΩ/dt₁`, the slope that the radial inversion of a cap intersection needs: no second
/// evaluation (an `acos`, a square root and a division) per Newton step.
#[inline(always)]
pub(crate) fn lens_and_half_arc(
    [t1, theta1]: [f32; 2],
    [t2, theta2]: [f32; 2],
    [td, d]: [f32; 2],
) -> [f32; 2] {
    if d >= theta1 + theta2 {
        return [0.0, 0.0];
    }
    if d <= (theta1 - theta2).abs() {
        let first_inside = theta1 <= theta2;
        return [2.0 * PI * t1.min(t2), if first_inside { PI } else { 0.0 }];
    }
    let (gram, plain, n1) = lens_gram(t1, t2, td);
    // Y² = sin²θ₁ sin²d − N₁², the Gram determinant of (a₁, a₂, P). Where the two terms
    // nearly cancel (Y² below half of them: a tiny cap across a large one's boundary,
    // where both are of order 1 and Y of the order of the tiny cap) their difference
    // has lost its precision. With `P = sin θ₁ sin d`, `Y² = (P − N₁)(P + N₁)`, and by
    // the law of cosines (`N₁ = cos θ₂ − cos θ₁ cos d`) the factors are differences of
    // cosines: `P − N₁ = cos(θ₁ − d) − cos θ₂ = 2 sin((θ₁ + θ₂ − d)/2) sin((θ₂ + d − θ₁)/2)`
    // and `P + N₁ = cos θ₂ − cos(θ₁ + d) = 2 sin((θ₁ + θ₂ + d)/2) sin((θ₁ + d − θ₂)/2)`
    // (together the spherical Heron formula; issue 16, 4: the plain form gave the whole
    // tiny cap or 0, 85% off). Only the factor with `N₁`'s sign opposed cancels: it takes
    // the sines of the sides' differences, the other `P + |N₁|` as it is (above `1.7 P`),
    // so two `sin` in place of Heron's four. All factors are non-negative in the lens
    // case.
    let y2 = if plain >= 0.5 * gram {
        plain
    } else {
        let half_sine = |x: f32| libm::sinf((0.5 * x).max(0.0));
        let cancelling = if n1 >= 0.0 {
            2.0 * half_sine(theta1 + theta2 - d) * half_sine(theta2 + d - theta1)
        } else {
            2.0 * half_sine(theta1 + theta2 + d) * half_sine(theta1 + d - theta2)
        };
        cancelling * (crate::math::sqrtf(gram) + n1.abs())
    };
    lens_area(t1, t2, td, n1, y2, t1.min(t2))
}

/// `sin²θ₁ sin²d`, `Y² = sin²θ₁ sin²d − N₁²` and `N₁ = t₁ + t_d − t₂ − t₁t_d` of the
/// lens case (module documentation).
#[inline(always)]
fn lens_gram(t1: f32, t2: f32, td: f32) -> (f32, f32, f32) {
    let sin2_1 = (t1 * (2.0 - t1)).max(0.0);
    let sin2_d = (td * (2.0 - td)).max(0.0);
    let n1 = t1 + td - t2 - t1 * td;
    let gram = sin2_1 * sin2_d;
    (gram, gram - n1 * n1, n1)
}

/// [`lens_gram`] without its clamps of `sin²θ₁ = t₁(2 − t₁)` and `sin²d = t_d(2 − t_d)` at
/// 0, for [`at_most_hemispheres_fast`], whose `t₁ ∈ [0, 1]` and `t_d ∈ [0, 2]` (not NaN)
/// make both products at least 0 already: the same values (up to the sign of a zero
/// product, which does not reach the area), without the NaN tests of `f32::max` (five
/// instructions).
#[inline(always)]
fn lens_gram_fast(t1: f32, t2: f32, td: f32) -> (f32, f32, f32) {
    let sin2_1 = t1 * (2.0 - t1);
    let sin2_d = td * (2.0 - td);
    let n1 = t1 + td - t2 - t1 * td;
    let gram = sin2_1 * sin2_d;
    (gram, gram - n1 * n1, n1)
}

/// The lens area `2φ₁ t₁ + 2φ₂ t₂ − 2E` (module documentation) from `N₁` and `Y²`, clamped
/// to `[0, 2π min(t₁, t₂)]` (`smaller = t₁.min(t₂)`, the caller's), and `φ₁`.
#[inline(always)]
fn lens_area(t1: f32, t2: f32, td: f32, n1: f32, y2: f32, smaller: f32) -> [f32; 2] {
    let n2 = t2 + td - t1 - t2 * td;
    let y = crate::math::sqrtf(y2.max(0.0));
    // `Y >= 0`: one `atan` of a ratio per angle, without `atan2f`'s quadrant logic. The
    // three (two azimuths and the excess) are independent: gathered in one call of
    // `atan2_upper_half_plane4`, whose lanes give `atan2_upper_half_plane`'s bits (its
    // test), so that a packed evaluation there serves the two-cap solid angle and each
    // evaluation of the radial CDF of a cap intersection at once (the fourth lane idle).
    let angles = atan2_upper_half_plane4(
        Vec4::splat(y),
        Vec4::new(n1, n2, 4.0 - td - t1 - t2, 0.0),
        3,
    );
    let (phi1, phi2, excess) = (angles.x, angles.y, 2.0 * angles.z);
    let area = 2.0 * (phi1 * t1 + phi2 * t2 - excess);
    [area.max(0.0).min(2.0 * PI * smaller), phi1]
}

/// [`at_most_hemispheres`] for the real-time shading (issue 18, 1), from `t₁, t₂ ∈ (0, 1]`
/// and `t_d`: the case decided without square roots, the lens's arc tangents by
/// [`atan_unit_estrin`](crate::math::atan_unit_estrin) without a branch on the data;
/// `None` where the case is not clear (then the caller takes the careful path).
///
/// The case without angles: with `u = √(t₁h₂)`, `v = √(t₂h₁)`, `w = √(2t_d)` (see
/// [`at_most_hemispheres`]) the caps are disjoint when `w ≥ u + v`, nested when
/// `w ≤ |u − v|` and cross otherwise, i.e. with `X = w² − u² − v² = 2t_d − t₁h₂ − t₂h₁`:
/// they cross exactly when `X² < 4u²v² = 4 t₁h₁ t₂h₂` (`4u²v² − X² = 4Y²`, the spherical
/// Heron formula), are disjoint when `X ≥ 0` and nested when `X < 0` otherwise. `X` is a
/// sum of three terms with one rounding each (and `t_d` comes with a relative error of a
/// few 1e-7), so its error is below `ε_X = 1e-6` times their magnitudes' sum; the case is
/// taken only when `(|X| ± ε_X)²` is on the same side of `4u²v²` with a relative margin of
/// `1e-5` (the rounding of the squares is a few 1e-7). The lens's `Y²` is the Gram form or
/// the spherical Heron form as in [`at_most_hemispheres`]. (The shading's `t₁` can also be
/// 0, where its `sin²θ` underflows; `t₂ > 0`, so [`min_ordered`] is `f32::min` here.)
#[inline(always)]
pub(crate) fn at_most_hemispheres_fast(t1: f32, t2: f32, td: f32) -> Option<f32> {
    let (h1, h2) = (2.0 - t1, 2.0 - t2);
    let (uu, vv, ww) = (t1 * h2, t2 * h1, 2.0 * td);
    let x = ww - uu - vv;
    let error = 1e-6 * (ww + uu + vv);
    let four_uv2 = 4.0 * (t1 * h1) * (t2 * h2);
    let (near, far) = (x.abs() - error, x.abs() + error);
    // One branch: the clamp folds `near > 0` into the square's test (`0 > 4u²v²` is
    // false; NaN becomes 0). The branch itself follows the light (a light across the
    // horizon is a lens, one above it nested), so it is mispredicted often either way.
    let near = near.max(0.0);
    if near * near > four_uv2 * (1.0 + 1e-5) {
        // Disjoint (X > 0) or nested (X < 0).
        return Some(if x > 0.0 {
            0.0
        } else {
            2.0 * PI * min_ordered(t1, t2)
        });
    }
    if !(far * far <= four_uv2 * (1.0 - 1e-5)) {
        return None;
    }
    // Surely the lens.
    let (gram, plain, n1) = lens_gram_fast(t1, t2, td);
    let y2 = if plain >= 0.5 * gram {
        plain
    } else {
        heron_y2_fast([t1, t2, td], [uu, vv, ww])
    };
    let n2 = t2 + td - t1 - t2 * td;
    let y2 = y2.max(0.0);
    let y = crate::math::sqrtf(y2);
    // The three arc tangents in one packed evaluation (the fourth lane is idle).
    let angles = atan2_upper_half_plane_fast4(y, y2, Vec4::new(n1, n2, 4.0 - td - t1 - t2, 1.0));
    let (phi1, phi2, excess) = (angles.x, angles.y, 2.0 * angles.z);
    let area = 2.0 * (phi1 * t1 + phi2 * t2 - excess);
    Some(area.max(0.0).min(2.0 * PI * min_ordered(t1, t2)))
}

/// [`atan2_upper_half_plane`](crate::math::atan2_upper_half_plane) of `(y, x)` with
/// `y = √y2 ≥ 0` by [`atan_unit_estrin`](crate::math::atan_unit_estrin): `atan` of
/// `min(y, |x|) / max(y, |x|)`, then `π/2 −` it where `y > |x|` and `π −` it where
/// `x < 0`. The ratio is `y` times `1/|x|` or `|x|/y²`, whose division does not wait for
/// the square root `y` (the case is decided by `y² > x²`): two roundings instead of one,
/// so about one ulp more than the ratio of `atan2_upper_half_plane`. Clamped to `[0, 1]`
/// (where `x²` underflows the case can be wrong) and 0 for `y = x = 0` and NaN.
///
/// The scalar form, the reference of [`atan2_upper_half_plane_fast4`] (which the shading
/// uses) in the tests.
#[cfg(test)]
#[inline(always)]
fn atan2_upper_half_plane_fast(y: f32, y2: f32, x: f32) -> f32 {
    let ax = x.abs();
    let steep = y2 > x * x;
    let scale = if steep { ax / y2 } else { 1.0 / ax };
    // NaN (0 · ∞ for y = x = 0) becomes 0.
    let ratio = (y * scale).max(0.0).min(1.0);
    let angle = crate::math::atan_unit_estrin(ratio);
    let angle = if steep { FRAC_PI_2 - angle } else { angle };
    let angle = if x < 0.0 { PI - angle } else { angle };
    angle.max(0.0)
}

/// [`atan2_upper_half_plane_fast`] of `(y, xᵢ)` in each lane of `x` (one `y = √y2 ≥ 0`
/// for all): the lens's three arc tangents at once. The same operations per lane, with two
/// changes that keep the bits: one division per lane, of the operands that the scalar
/// form's select would pick after dividing both ways (`|x|/y²` where steep, else `1/|x|`),
/// and the clamps as compare-and-select: `max(0)` of the ratio as `r > 0 ? r : 0` (NaN,
/// from `0 · ∞` at `y = x = 0`, becomes 0), `min(1)` as `r < 1 ? r : 1`. The scalar form's
/// final `max(0)` is then a no-op (the ratio is in `[0, 1]`, so the arc tangent is at
/// least 0, `π/2 −` it at least `π/4`) and is left out. The one difference: a ratio of
/// `−0` (only from `y = −0`, which `√` of a clamped `Y²` does not give) comes out `+0`.
/// Tested lane for lane against the scalar form, bit for bit
/// (`the_packed_atan2_gives_the_scalar_bits`).
#[inline(always)]
fn atan2_upper_half_plane_fast4(y: f32, y2: f32, x: Vec4) -> Vec4 {
    let ax = x.abs();
    let y2 = Vec4::splat(y2);
    let steep = y2.cmpgt(x * x);
    let scale = Vec4::select(steep, ax, Vec4::ONE) / Vec4::select(steep, y2, ax);
    let ratio = Vec4::splat(y) * scale;
    let ratio = Vec4::select(ratio.cmpgt(Vec4::ZERO), ratio, Vec4::ZERO);
    let ratio = Vec4::select(ratio.cmplt(Vec4::ONE), ratio, Vec4::ONE);
    let angle = crate::math::atan_unit_estrin4(ratio);
    let angle = Vec4::select(steep, Vec4::splat(FRAC_PI_2) - angle, angle);
    Vec4::select(x.cmplt(Vec4::ZERO), Vec4::splat(PI) - angle, angle)
}

/// The Oat–Sander approximation of [`cap_intersection_solid_angle`] (Eq. 37–38):
/// the exact value in the disjoint and nested cases, and
/// `2π(1 − cos θ₁) P((θ₁ + θ₂ − d) / (2θ₁))` (`θ₁ ≤ θ₂`, `P(x) = 3x² − 2x³`) in
/// between. Meant for caps smaller than a hemisphere; see the module documentation
/// for its error.
pub fn cap_intersection_solid_angle_oat_sander(a: &Cap, b: &Cap) -> f32 {
    let (mut t1, mut t2) = (a.one_minus_cos, b.one_minus_cos);
    if !(t1 > 0.0) || !(t2 > 0.0) {
        return 0.0;
    }
    if t1 > t2 {
        core::mem::swap(&mut t1, &mut t2);
    }
    let td = one_minus_dot(a.axis, b.axis);
    let (theta1, theta2, d) = (angle_of(t1), angle_of(t2), angle_of(td));
    if d >= theta1 + theta2 {
        return 0.0;
    }
    let omega1 = 2.0 * PI * t1;
    if d <= theta2 - theta1 {
        return omega1;
    }
    let x = ((theta1 + theta2 - d) / (2.0 * theta1)).max(0.0).min(1.0);
    omega1 * x * x * (3.0 - 2.0 * x)
}

#[cfg(test)]
#[path = "cap_intersection_tests.rs"]
mod tests;
