//! Uniform sampling of the intersection of two spherical caps (Dupuy et al. 2017,
//! Sec. 4: SPTDs over sets of caps; the sampler behind an SPTD restricted to `C ∩ H`).
//!
//! For caps `A` (axis `a`, `t_A = 1 − cos θ_A`) and `B` (axis `b`, half-angle `θ_B`) at
//! axis angle `d`, the directions at `s = 1 − cos θ` from `a` form a circle, of which
//! the arc of azimuths `ψ ∈ [−φ(s), φ(s)]` about the direction of `b` lies in `B`:
//! `cos θ cos d + sin θ sin d cos ψ ≥ cos θ_B`, so
//!
//! `cos φ(s) = (cos θ_B − cos θ cos d) / (sin θ sin d)
//!           = (s + t_d − t_B − s t_d) / √(s (2 − s) t_d (2 − t_d))`
//!
//! (clamped to `[−1, 1]`; every term from the `t`s, no cancellation of cosines). The
//! area element is `dω = ds dψ`, so the radial marginal of the uniform distribution on
//! `A ∩ B` is `F(s) = Ω(cap(a, s) ∩ B) / Ω(A ∩ B)` with density `2 φ(s) / Ω(A ∩ B)`: the
//! closed-form two-cap solid angle ([`cap_intersection_solid_angle`]) is its CDF, and its
//! derivative is `2 φ(s)`. Sampling inverts `F(s) = u₀` by Newton's method safeguarded
//! by bisection (at most [`MAX_ITERATIONS`] steps), then draws `ψ = (2u₁ − 1) φ(s)`:
//! exact up to the rounding of `F`, with the inverse `u₀ = F(1 − a·ω)`,
//! `u₁ = (ψ/φ + 1)/2`.
//!
//! Hard cases (tested): nested caps, a lens between tangent caps, a tiny cap across a
//! large one's rim, caps wider than a hemisphere (whose intersection may be a ring-like
//! region around a hole), coaxial caps, disjoint caps (no sampler).

use super::cap::Cap;
use super::cap_intersection::{
    angle_of, cap_intersection_solid_angle, lens_and_half_arc_of_sides, max_ordered, min_ordered,
};
use crate::Sample;
use crate::math::orthonormal_basis;
use crate::sample::{INWARD_PULLS, clamp_inverted, clamp_random};
use core::f32::consts::{PI, TAU};
use glam::Vec3;

/// The most steps of the radial inversion. Newton's method converges quadratically from
/// the bisection's bracket; 40 bisection steps alone shrink any bracket in `[0, 2]` below
/// `f32` resolution, so the bound is never the limit of accuracy.
pub const MAX_ITERATIONS: u32 = 40;

/// `libm::acosf(−1.0)`, the half arc of a circle wholly inside `B` as
/// [`CapIntersection::half_arc`] computes it (`2 · PIO2_HI`, one ulp below `f32` π;
/// `the_whole_circle_half_arc_is_acos_of_minus_one`).
const WHOLE_CIRCLE_HALF_ARC: f32 = f32::from_bits(0x4049_0fda);

/// The smallest `f32` whose reciprocal is finite, `2⁻¹²⁸ (1 + 2⁻²¹)` (a denormal): `1/x`
/// rounds to infinity exactly when `x ≤ 1/(2¹²⁸ − 2¹⁰³)`, the reciprocal of the midpoint
/// between `f32::MAX` and `2¹²⁸` (a tie there goes to the even `2¹²⁸`, i.e. infinity). So
/// `Ω ≥ MIN_NORMALISER` is `Ω > 0 && (1/Ω).is_finite()` (`uniform_pdf`'s test) without
/// the division (`min_normaliser_is_where_the_reciprocal_is_finite`).
pub(crate) const MIN_NORMALISER: f32 = f32::from_bits(0x0020_0001);

/// Two caps prepared for uniform sampling of their intersection.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CapIntersection {
    /// The cap whose axis the radial coordinate `s` is measured from (sanitized).
    pub radial: Cap,
    /// The other cap (sanitized).
    pub other: Cap,
    /// `Ω(A ∩ B)` in steradians (0 for the empty intersection).
    pub solid_angle: f32,
    /// Unit tangent at `a` towards `b` (any tangent when the axes coincide).
    e1: Vec3,
    /// `a × e1`.
    e2: Vec3,
    /// `t_d = 1 − a·b`.
    t_d: f32,
    /// The cap that `cumulative`'s lens formula pairs with `cap(a, s)`: `B`, or its
    /// complement when `B` is wider than a hemisphere, as `[1 − cos, 1 − a·axis, w, cos(d/2)]`
    /// with `w = √(2 (1 − a·axis))` and `cos(d/2) = √(1 − (1 − a·axis)/2)`, `d` the angle
    /// between the axes (the constants of `lens_and_half_arc_of_sides`).
    lens_partner: [f32; 4],
    /// The range of `s` that meets `B`: `[s_low, s_high]` within `[0, t_A]`.
    s_low: f32,
    s_high: f32,
    /// `s_nested`: up to it `cap(a, s)` lies inside `B` (surely: with a margin for the
    /// rounding), so that the radial CDF is `Ω(cap(a, s)) = 2πs` and is inverted in
    /// closed form ([`invert_radial_counting`](Self::invert_radial_counting)); 0 when `a` is not inside `B`.
    nested: f32,
    /// Unused: keeps the size of the C ABI's opaque `SpheraSphereLightSampler`, which
    /// holds this struct (the inner point towards which a sample that rounding put just
    /// outside is pulled was stored here with `nested`; it is computed where that rare
    /// case happens, `inner_point`). Written as zeros.
    reserved: [f32; 2],
}

impl CapIntersection {
    /// The empty intersection: no samples, pdf 0.
    ///
    /// cbindgen:ignore
    pub const EMPTY: CapIntersection = CapIntersection {
        radial: Cap::EMPTY,
        other: Cap::EMPTY,
        solid_angle: 0.0,
        e1: Vec3::X,
        e2: Vec3::Y,
        t_d: 0.0,
        lens_partner: [0.0; 4],
        s_low: 0.0,
        s_high: 0.0,
        nested: 0.0,
        reserved: [0.0; 2],
    };

    /// Prepares uniform sampling of `a ∩ b` (both sanitized here). `None` when the
    /// intersection is empty (or `1 / Ω` is not finite). The narrower cap is the radial
    /// one.
    #[must_use]
    pub fn new(a: &Cap, b: &Cap) -> Option<CapIntersection> {
        let mut prepared = CapIntersection::EMPTY;
        prepared.prepare(a, b).then_some(prepared)
    }

    /// [`CapIntersection::new`] written in place into `self` (no copy of the prepared
    /// value); `false` and [`CapIntersection::EMPTY`] written where `new` gives `None`.
    pub fn prepare(&mut self, a: &Cap, b: &Cap) -> bool {
        self.prepare_sanitized(&a.sanitized(), &b.sanitized())
    }

    /// [`CapIntersection::prepare`] of caps that are valid already (`sanitized` returns
    /// them as they are: every constructor's cap and every pivoted image), without
    /// sanitizing them again: the same bits, for the sphere light sampler, whose caps are
    /// images from `pivot_cap_fast`.
    pub(crate) fn prepare_sanitized(&mut self, a: &Cap, b: &Cap) -> bool {
        self.prepare_sanitized_inlined(*a, *b)
    }

    /// [`prepare_sanitized`](Self::prepare_sanitized) of caps by value, always inlined: the
    /// sphere light sampler's clipped preparation, whose pivoted images are then not
    /// passed through memory (issue 18, stop 45: with `SphereLightSampler::prepare`'s cap
    /// no longer copied, 12 instructions per preparation and sample of `sptd`, 15 of
    /// `sptd_fit`, callgrind, light bench). The other callers keep the out-of-line call.
    #[inline(always)]
    pub(crate) fn prepare_sanitized_inlined(&mut self, a: Cap, b: Cap) -> bool {
        let (radial, other) = if a.one_minus_cos <= b.one_minus_cos {
            (a, b)
        } else {
            (b, a)
        };
        let axis = radial.axis;
        let t_d = (0.5 * (other.axis - axis).length_squared()).min(2.0);
        // The tangent towards b: b's component perpendicular to a, from a basis of the
        // tangent plane (as in `SptdInCap`, accurate when b is within ulps of a).
        let (t, bt) = orthonormal_basis(axis);
        let (x, y) = (other.axis.dot(t), other.axis.dot(bt));
        let sin_d = crate::math::sqrtf(x * x + y * y);
        let e1 = if sin_d > 1e-18 {
            t * (x / sin_d) + bt * (y / sin_d)
        } else {
            t
        };
        let e2 = axis.cross(e1);
        // Along the great circle from a towards b, the points at angle θ from a lie in
        // B for |θ − d| ≤ θ_B (d ≤ π, so also θ ≥ d − θ_B and θ ≤ d + θ_B): the radial
        // range that meets B is `s ∈ [1 − cos max(0, d − θ_B), 1 − cos min(d + θ_B, θ_A)]`
        // (`1 − cos` increases on `[0, π]`), all of `[0, t_A]` past `d + θ_B ≥ π`, where
        // the circle at θ wraps. Without the angles (three `asin` and two `sin` fewer):
        // `1 − cos x = 2 sin²(x/2)`, and the half-angles' sines and cosines are
        // `sin(x/2) = √(t/2)`, `cos(x/2) = √(h/2)` (`h = 1 + cos x`; for the axes
        // `h_d = |a + b|²/2`, exact where `t_d` is near 2), so that
        // `sin((d ∓ θ_B)/2) = sin(d/2) cos(θ_B/2) ∓ cos(d/2) sin(θ_B/2)` (whose sign is
        // that of `d ∓ θ_B`, the half-angles lying in `[0, π/2]`) and `d + θ_B ≥ π` exactly
        // when `cos((d + θ_B)/2) = cos(d/2) cos(θ_B/2) − sin(d/2) sin(θ_B/2) ≤ 0`. Near
        // `d = θ_B` the difference of products has an absolute error of a few 1e-8, as
        // `d − θ_B` of the rounded angles had; the bound is only the Newton iteration's
        // bracket and start, the CDF is the lens formula's either way.
        let h_d = (0.5 * (other.axis + axis).length_squared()).min(2.0);
        let half = |t: f32| crate::math::sqrtf(0.5 * t);
        let (sin_half_d, cos_half_d) = (half(t_d), half(h_d));
        let (sin_half_b, cos_half_b) = (half(other.one_minus_cos), half(other.one_plus_cos));
        let t_a = radial.one_minus_cos;
        // The clamps to `t_A` below and `s_high.max(s_low)` as compares and selects
        // (`min_ordered`, `max_ordered`; `f32::min`'s NaN test and blend were 6 instructions
        // each): the caps are valid, so no operand is NaN (the half sines and cosines are
        // square roots of sides in `[0, 2]`), and `2x²` is +0 or positive, so that the zeros
        // that meet are +0 but where `t_A = −0`, whose intersection is empty (`new` gives
        // `None` there whatever the bounds).
        let below = sin_half_d * cos_half_b - cos_half_d * sin_half_b;
        let s_low = if below > 0.0 {
            min_ordered(2.0 * below * below, t_a)
        } else {
            0.0
        };
        let above = sin_half_d * cos_half_b + cos_half_d * sin_half_b;
        let s_high = if cos_half_d * cos_half_b - sin_half_d * sin_half_b <= 0.0 {
            t_a
        } else {
            min_ordered(2.0 * above * above, t_a)
        };
        // `cap(a, s)` lies inside B while θ + d ≤ θ_B: up to `1 − cos(θ_B − d)` =
        // `2 sin²((θ_B − d)/2)`, the half sine being `−below`. Its rounding (the half
        // sines' and cosines' of a few ulps, and the products') is below 4e-7: taken 4e-6
        // short of it, the lens formula surely says "inside" up to `s_nested`.
        let inside = -below - 4e-6;
        let nested = if inside > 0.0 {
            min_ordered(2.0 * inside * inside, t_a)
        } else {
            0.0
        };
        // (No angles: `lens_and_half_arc_of_sides` takes the sides, and its two constants
        // as it would compute them, `√(2 t_d)` and `√(1 − t_d/2)`: the same bits.)
        let (partner_t, partner_t_d) = if other.one_minus_cos <= 1.0 {
            (other.one_minus_cos, t_d)
        } else {
            // The complement: axis `−b`, `1 − cos = h_B`; `1 − a·(−b) = |a + b|²/2 = h_d`.
            (other.one_plus_cos, h_d)
        };
        let lens_partner = [
            partner_t,
            partner_t_d,
            crate::math::sqrtf(2.0 * partner_t_d),
            crate::math::sqrtf((1.0 - 0.5 * partner_t_d).max(0.0)),
        ];
        *self = CapIntersection {
            radial,
            other,
            solid_angle: 0.0,
            e1,
            e2,
            t_d,
            lens_partner,
            s_low,
            s_high: max_ordered(s_high, s_low),
            nested,
            reserved: [0.0; 2],
        };
        let solid_angle = self.whole_solid_angle();
        // `Ω > 0` with `1/Ω` finite, without the division ([`MIN_NORMALISER`]; issue 18:
        // the division was on the path of every preparation of a light across the horizon).
        if !(solid_angle >= MIN_NORMALISER) {
            *self = CapIntersection::EMPTY;
            return false;
        }
        self.solid_angle = solid_angle;
        true
    }

    /// `Ω(A ∩ B)` = `cap_intersection_solid_angle(radial, other)`, bit for bit, for a
    /// prepared value (`solid_angle` aside): where the radial CDF's fast path covers the
    /// whole radial cap (`0 < t_A ≤ 1`, `t_A < t_B`, and for `B` wider than a hemisphere a
    /// hole `h_B > 0`), `F(t_A)` from the prepared lens partner. There the general call
    /// takes the same steps on the same numbers: its canonical order puts the radial cap
    /// first (`t_A < t_B`), its `at_most_hemispheres` against `B` or its complement
    /// `(−b, h_B)` computes `t_d = |a ∓ b|²/2`, `√(2 t_d)` and `√(1 − t_d/2)` as the
    /// partner stores them (`|a − b|²` and `|b − a|²`, `|a + b|²` and `|b + a|²` round
    /// alike), and its clamps (`Ω(C̄ ∩ A) = 2π t_A − lens` between `max(0, 2π t_A + 2π t_B −
    /// 4π)` and `2π min(t_A, t_B)`) are `cumulative_and_slope`'s, written the same way
    /// (`the_prepared_solid_angle_is_the_general_one`). Elsewhere the general call. (Issue
    /// 18: the general call re-derived the partner's constants, sorted the caps and went
    /// through memory: 30 instructions per preparation and sample of the SPTD sphere light
    /// sampler on the light bench, about 60 per clipped one, measured.)
    #[inline(always)]
    fn whole_solid_angle(&self) -> f32 {
        let (t_a, t_b) = (self.radial.one_minus_cos, self.other.one_minus_cos);
        if t_a > 0.0 && t_a <= 1.0 && t_a < t_b && (t_b <= 1.0 || self.other.one_plus_cos > 0.0) {
            self.cumulative_and_slope(t_a)[0]
        } else {
            cap_intersection_solid_angle(&self.radial, &self.other)
        }
    }

    /// A direction inside both caps (on the arc from `a` towards `b`, at the middle of
    /// the radial range that meets `B`), towards which a sample that rounding put just
    /// outside is pulled. Only that rare case needs it: computed there, not prepared
    /// (a sine and cosine, a normalisation and two containment tests per preparation).
    #[cold]
    #[inline(never)]
    fn inner_point(&self) -> Vec3 {
        let (radial, other) = (&self.radial, &self.other);
        let axis = radial.axis;
        let (theta_a, theta_b, d) = (
            angle_of(radial.one_minus_cos),
            angle_of(other.one_minus_cos),
            angle_of(self.t_d),
        );
        let low = (d - theta_b).max(0.0);
        let high = (d + theta_b).min(theta_a).max(low);
        let middle = 0.5 * (low + high);
        // `middle` lies in `[0, θ_A] ⊂ [0, π]`.
        let (sin_m, cos_m) = crate::math::sin_cos_0_to_pi(middle);
        let inner = crate::math::normalize_or(axis * cos_m + self.e1 * sin_m, axis);
        if radial.contains(inner) && other.contains(inner) {
            inner
        } else if other.contains(axis) {
            // (A ring around a hole, where the arc's middle may lie in the hole.)
            axis
        } else {
            other.axis
        }
    }

    /// `Ω(cap(a, s) ∩ B)`, the unnormalised radial CDF.
    ///
    /// Fast path, for `cap(a, s)` at most a hemisphere and narrower than `B`: there
    /// [`cap_intersection_solid_angle`] takes the lens formula with `cap(a, s)` first,
    /// against `B` itself or, for `B` wider than a hemisphere, against its complement
    /// (`Ω(A ∩ B) = Ω(A) − Ω(A ∩ B̄)`; the usual case of a sphere light across the
    /// horizon, whose pivoted hemisphere is wide). The lens partner's `1 − cos`, `t_d`,
    /// `√(2 t_d)` and `√(1 − t_d/2)` do not depend on `s` and come from `new`, and the
    /// lens is [`lens_and_half_arc_of_sides`]: per Newton step no `asin` (the case is
    /// decided from the sides, the angles only near a case's boundary) and, where the
    /// Gram form of `Y²` cancels (58% of the steps of the SPTD sphere light sampler on
    /// the light bench), the spherical Heron form by square roots instead of two `sin`;
    /// no cap is built (whose axis normalisation cost a division, a square root and a
    /// division). The values are the general call's up to the last bits of `t_d` (the
    /// general call's cap normalises the unit axis once more). (Issue 18: 19 instructions
    /// fewer per sample and 55 per preparation and sample of that sampler than the angles'
    /// form, `asin` of `s` per step and of the partner's sides in `new`, measured; the
    /// case from the sides alone, without the Heron form's change, had cost 30 more.)
    #[inline]
    fn cumulative(&self, s: f32) -> f32 {
        self.cumulative_and_slope(s)[0]
    }

    /// [`cumulative`](Self::cumulative) and its derivative `2 φ(s)`
    /// ([`half_arc`](Self::half_arc)): on the fast path, `φ` is the lens formula's own
    /// half arc (`π − φ` of the circle in the complement when `B` is wide, as
    /// `Ω(cap ∩ B) = 2πs − Ω(cap ∩ B̄)`); elsewhere `half_arc` computes it. Always
    /// inlined into the Newton iteration (out of line: its call and spills, about 6
    /// instructions per evaluation, measured).
    #[inline(always)]
    fn cumulative_and_slope(&self, s: f32) -> [f32; 2] {
        let t_b = self.other.one_minus_cos;
        if s > 0.0 && s <= 1.0 && s < t_b {
            let [t, t_d, w, cos_half_d] = self.lens_partner;
            let [lens, phi] = lens_and_half_arc_of_sides(s, t, t_d, w, || cos_half_d);
            if t_b <= 1.0 {
                return [lens, 2.0 * phi];
            }
            // `f32::max` and `f32::min` as compares and selects (`max_ordered`,
            // `min_ordered`; their NaN tests and blends were about 6 instructions per
            // evaluation, measured): no operand is NaN here, as `s ∈ (0, 1]` and `t_B > s` (so
            // `2π t_B` is finite or +∞, `low` finite or +∞) and the lens is not NaN (its
            // area is clamped by `max(0)`, then by `2π min(s, t)` with `s` not NaN; the
            // other cases return 0, π or `2π min(s, t)`) and at most `2π s`, so that
            // `2π s − lens` is finite. No operand is −0 (`s > 0`; a sum or difference of
            // non-zero terms that cancels gives +0), so the zeros that meet are equal.
            let omega_s = 2.0 * PI * s;
            let low = max_ordered(omega_s + 2.0 * PI * t_b - 4.0 * PI, 0.0);
            let value = min_ordered(
                max_ordered(omega_s - lens, low),
                min_ordered(omega_s, 2.0 * PI * t_b),
            );
            return [value, 2.0 * (PI - phi)];
        }
        self.cumulative_and_slope_general(s)
    }

    /// [`cumulative_and_slope`](Self::cumulative_and_slope) off its fast path: the cap at
    /// `s` built and the general two-cap solid angle. Out of line and cold: in line, the
    /// compiler hoisted the cap's axis normalisation (loop-invariant: three divisions and
    /// a square root) out of the Newton loop, so that every sample beyond the nested part
    /// paid for it although the fast path takes nearly all of them (issue 18, stop 40:
    /// about 80 instructions per such sample of the SPTD sphere light sampler).
    #[cold]
    #[inline(never)]
    fn cumulative_and_slope_general(&self, s: f32) -> [f32; 2] {
        let cap = Cap::from_axis_one_minus_cos(self.radial.axis, s);
        [
            cap_intersection_solid_angle(&cap, &self.other),
            2.0 * self.half_arc(s),
        ]
    }

    /// `φ(s)`, the half-width in azimuth of the circle at `s` inside `B`.
    #[inline]
    fn half_arc(&self, s: f32) -> f32 {
        let t_b = self.other.one_minus_cos;
        let numerator = s + self.t_d - t_b - s * self.t_d;
        let denominator =
            crate::math::sqrtf((s * (2.0 - s)).max(0.0) * (self.t_d * (2.0 - self.t_d)).max(0.0));
        if !(denominator > 0.0) {
            // Coaxial (or the pole of a): the whole circle or none of it.
            return if numerator <= 0.0 { PI } else { 0.0 };
        }
        libm::acosf((numerator / denominator).max(-1.0).min(1.0))
    }

    /// The solid angle of the intersection, `Ω(A ∩ B)`.
    #[inline]
    #[must_use]
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle
    }

    /// `1 / Ω(A ∩ B)`, or 0 for the empty intersection.
    #[inline]
    fn uniform_pdf(&self) -> f32 {
        if !(self.solid_angle > 0.0) {
            return 0.0;
        }
        let pdf = 1.0 / self.solid_angle;
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// Whether `dir` lies in both caps.
    #[inline]
    #[must_use]
    pub fn contains(&self, dir: Vec3) -> bool {
        self.contains_inlined(dir)
    }

    /// [`contains`](Self::contains), always inlined (the per-sample test of
    /// [`sample_uniform`](Self::sample_uniform)).
    #[inline(always)]
    fn contains_inlined(&self, dir: Vec3) -> bool {
        // One length test for both caps where `dir` is unit (the samples), else each cap's.
        if crate::math::is_unit(dir) {
            return self.radial.contains_unit(dir) && self.other.contains_unit(dir);
        }
        self.radial.contains(dir) && self.other.contains(dir)
    }

    /// The closed-form part of the radial inversion: `Some(s)` with `s = target / 2π` where
    /// the target lies in the nested part (`target ≤ 2π s_nested`, see
    /// [`invert_radial_counting`](Self::invert_radial_counting)), `None` beyond it.
    #[inline(always)]
    fn invert_nested(&self, target: f32) -> Option<f32> {
        (target <= TAU * self.nested).then(|| (target / TAU).max(self.s_low).min(self.s_high))
    }

    /// `s` with `Ω(cap(a, s) ∩ B) = target`, by Newton's method in the bracket
    /// `[s_low, s_high]`, bisecting where a step leaves it, and the number of evaluations
    /// of `F` it took (for the tests; the sampler takes the two parts apart).
    #[cfg(test)]
    fn invert_radial_counting(&self, target: f32) -> (f32, u32) {
        // Where `cap(a, s)` lies inside B, `F(s) = Ω(cap(a, s)) = 2πs` (the lens formula's
        // value there, bit for bit, on its fast path): `s = target / 2π` without an
        // evaluation. For a sphere light across the horizon this is the part of its
        // pivoted image well inside the pivoted upper hemisphere's (issue 18: 52% of the
        // SPTD sampler's clipped samples as the light bench draws them,
        // `the_nested_part_inverts_in_closed_form`).
        if let Some(s) = self.invert_nested(target) {
            return (s, 0);
        }
        self.invert_beyond_nested_counting(target)
    }

    /// The Newton part of [`invert_radial_counting`](Self::invert_radial_counting), for a
    /// target beyond the nested part.
    #[inline(always)]
    fn invert_beyond_nested(&self, target: f32) -> f32 {
        self.invert_beyond_nested_counting(target).0
    }

    /// [`invert_beyond_nested`](Self::invert_beyond_nested) and the number of evaluations.
    #[inline(always)]
    fn invert_beyond_nested_counting(&self, target: f32) -> (f32, u32) {
        // Beyond `s_nested` (where `F = 2π s_nested`, below the target) F rises to `Ω` at
        // `s_high`: the bracket starts there, and the start is the chord's point, in
        // proportion to the rest of the target (exact for coaxial caps, where F is linear
        // in s). Without a nested part, the chord over `[s_low, s_high]`.
        let nested_area = TAU * self.nested;
        let (mut low, mut high) = (self.s_low.max(self.nested), self.s_high);
        let span = (high - low).max(0.0);
        let fraction = (target - nested_area) / (self.solid_angle - nested_area);
        let mut s = low + span * fraction.max(0.0).min(1.0);
        // The last Newton step's length, for the error estimate below (0 at the start
        // and after a bisection, which say nothing of the convergence: no estimate).
        let mut previous_newton_step = 0.0f32;
        for evaluations in 1..=MAX_ITERATIONS {
            let [value, slope] = self.cumulative_and_slope(s);
            let f = value - target;
            let next = crate::math::safeguarded_newton_step(s, f, slope, &mut low, &mut high);
            let step = (next - s).abs();
            let tolerance = 1e-7 * s.max(1e-30);
            // Newton's method converges quadratically: after a step of length δₖ from an
            // error eₖ ≈ δₖ the error is about K δₖ², with K ≈ δₖ / δₖ₋₁² from the
            // last two Newton steps. Where that estimate, δₖ³ / δₖ₋₁², is below a
            // sixteenth of the tolerance, the step just taken is the last one: the
            // evaluations that would confirm it (a step below the tolerance; with the
            // f32 CDF's rounding noise often several) are saved, 28% of a sample of
            // the SPTD sphere light sampler. Near a kink of `F` (where the arc begins)
            // the steps shrink slowly, K is large, and the estimate keeps the loop
            // going. Measured: `the_radial_inversion_inverts_the_cdf`.
            if step <= tolerance
                || step * step * step
                    <= (tolerance / 16.0) * previous_newton_step * previous_newton_step
                || !(high > low)
            {
                return (next.max(self.s_low).min(self.s_high), evaluations);
            }
            // A bisection lands on the bracket's midpoint.
            previous_newton_step = if next == 0.5 * (low + high) {
                0.0
            } else {
                step
            };
            s = next;
        }
        (s.max(self.s_low).min(self.s_high), MAX_ITERATIONS)
    }

    /// The direction at radial coordinate `s` and azimuth `psi` about `a` from `e1`.
    /// Always inlined (into `sample_direction`, its caller on the sampling path): out of
    /// line, its call, the arguments' moves and the frame's loads were 8 instructions per
    /// clipped sample of the SPTD sphere light sampler (callgrind, light bench `sptd`:
    /// 860 -> 852 per clipped sample; the same bits, it is the same code).
    #[inline(always)]
    fn direction(&self, s: f32, psi: f32) -> Vec3 {
        let sin_theta = crate::math::sqrtf((s * (2.0 - s)).max(0.0));
        // `psi` lies in `[−φ, φ] ⊂ [−π, π]`: the sine is odd, the cosine even.
        let (sin_psi, cos_psi) = crate::math::sin_cos_0_to_pi(psi.abs());
        let sin_psi = sin_psi.copysign(psi);
        let axis = self.radial.axis;
        // (`normalize_or`'s bits by a predicted branch: the sample's chain does not wait
        // for the test of the reciprocal.)
        crate::math::normalize_or_predicted(
            axis * (1.0 - s) + (self.e1 * cos_psi + self.e2 * sin_psi) * sin_theta,
            axis,
        )
    }

    /// Draws a direction uniformly (in solid angle) in `A ∩ B`, pdf `1 / Ω(A ∩ B)`; no
    /// sample from the empty intersection. `u` is clamped to `[0, 1 − ulp]`.
    pub fn sample_uniform(&self, u: [f32; 2]) -> Sample {
        self.sample_uniform_inlined(u)
    }

    /// [`sample_uniform`](Self::sample_uniform), always inlined (the sphere light
    /// sampler's clipped samples: 22 instructions a clipped sample fewer than the call,
    /// measured).
    #[inline(always)]
    pub(crate) fn sample_uniform_inlined(&self, u: [f32; 2]) -> Sample {
        let pdf = self.uniform_pdf();
        if pdf == 0.0 {
            return Sample::NONE;
        }
        self.sample_direction(u)
            .map_or(Sample::NONE, |dir| Sample { dir, pdf })
    }

    /// The direction of [`sample_uniform_inlined`](Self::sample_uniform_inlined) (the same
    /// bits, `None` where it gives no sample) without its pdf, for a caller that computes
    /// its own density and tests `Ω > 0` itself (the clipped sphere light sampler, whose
    /// density is `J(ω)/Ω`: the `1/Ω` here was a division per sample for a zero test
    /// only; [`MIN_NORMALISER`] is that test without the division).
    #[inline(always)]
    pub(crate) fn sample_direction(&self, u: [f32; 2]) -> Option<Vec3> {
        let dir = self.sample_direction_unchecked(u);
        if self.contains_inlined(dir) {
            return Some(dir);
        }
        // Rounding put a sample from the boundary just outside, where `pdf` is 0:
        // pulled towards the inner point until inside (`INWARD_PULLS`).
        let inner = self.inner_point();
        INWARD_PULLS
            .iter()
            .map(|&pull| crate::math::normalize_or(dir * (1.0 - pull) + inner * pull, inner))
            .find(|&pulled| self.contains(pulled))
    }

    /// The direction that [`sample_direction`](Self::sample_direction) tests for
    /// containment in both caps (and returns where it passes): the inverted radial
    /// coordinate and the azimuth, without the test, for a caller that tests its own
    /// image of it (the clipped sphere light sampler tests `g(ω)` in `C ∩ H`).
    #[inline(always)]
    pub(crate) fn sample_direction_unchecked(&self, u: [f32; 2]) -> Vec3 {
        let target = clamp_random(u[0]) * self.solid_angle;
        // In the nested part the whole circle at `s` lies in `B`: `half_arc(s)` clamps its
        // cosine to −1 and returns `acos(−1)`, the constant below, without the square root,
        // the division and the `acos` (`the_nested_part_inverts_in_closed_form`; at
        // `s = 0`, where `half_arc` gives `PI`, the direction is the axis whatever `ψ`).
        let (s, phi) = match self.invert_nested(target) {
            Some(s) => (s, WHOLE_CIRCLE_HALF_ARC),
            None => {
                let s = self.invert_beyond_nested(target);
                (s, self.half_arc(s))
            }
        };
        let psi = (2.0 * clamp_random(u[1]) - 1.0) * phi;
        self.direction(s, psi)
    }

    /// The density of [`sample_uniform`](Self::sample_uniform): `1 / Ω(A ∩ B)` in both
    /// caps, 0 outside.
    #[inline]
    #[must_use]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        if self.contains(dir) {
            self.uniform_pdf()
        } else {
            0.0
        }
    }

    /// The random numbers that [`sample_uniform`](Self::sample_uniform) maps to `dir`
    /// (up to rounding): `u₀ = F(1 − a·ω)`, `u₁ = (ψ/φ + 1)/2`; `None` outside.
    #[must_use]
    pub fn invert(&self, dir: Vec3) -> Option<[f32; 2]> {
        if !self.contains(dir) || !(self.solid_angle > 0.0) {
            return None;
        }
        let w = crate::math::normalize_scaled(dir);
        let s = (0.5 * (w - self.radial.axis).length_squared()).min(2.0);
        let u0 = self.cumulative(s) / self.solid_angle;
        let psi = libm::atan2f(w.dot(self.e2), w.dot(self.e1));
        let phi = self.half_arc(s);
        let u1 = if phi > 0.0 {
            0.5 * (psi / phi + 1.0)
        } else {
            0.5
        };
        Some([clamp_inverted(u0), clamp_inverted(u1)])
    }
}

#[cfg(test)]
#[path = "cap_intersection_sampling_tests.rs"]
mod tests;
