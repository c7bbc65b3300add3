//! The pivot transformation (Dupuy et al. 2017, Section 3): for a pivot point `r_p`
//! inside the unit sphere, `g(ω)` is the second intersection with the sphere of the
//! line from `ω` through `r_p`.
//!
//! Derivation (first principles, equivalent to Eq. 2): the points `ω + s(r_p − ω)`
//! lie on the sphere for `s = 0` and
//! `s = 2(1 − ω·r_p) / |ω − r_p|²`, so `g(ω) = ω − s (ω − r_p)`. Since
//! `|r_p| < 1`, `1 − ω·r_p > 0` and `|ω − r_p| > 0`: no division by zero. `g` is an
//! involution (`g(g(ω)) = ω`: the same line through the same pivot), and its Jacobian
//! on the sphere is `|dg/dω| = ((1 − |r_p|²) / |ω − r_p|²)²` (Eq. 4).
//!
//! # The image of a cap
//!
//! `g` maps circles to circles, so the image of a cap is a cap. Eq. 6–7 take the two
//! boundary points `ω₁, ω₂` of the cap in the plane of its axis `ω_c` and `r_p`, and
//! return the cap centered on the normalised mean of `g(ω₁), g(ω₂)` with
//! `cos ψ' = ω'_c·g(ω₁)`. That cap is never wider than a hemisphere
//! (`ω'_c·g(ω₁) = |g(ω₁) + g(ω₂)|/2 ≥ 0`), but the true image can be: the circle
//! through `g(ω₁), g(ω₂)` bounds two caps, and `g(C)` is the one that contains
//! `g(ω_c)`. In the plane, the projection through an interior point preserves the
//! orientation of the circle (it is a continuous deformation of the rotation by `π`
//! that the pivot at the origin gives), so the arc `ω₁ → ω_c → ω₂` (counterclockwise)
//! maps to the arc `g(ω₁) → g(ω_c) → g(ω₂)` (counterclockwise). Its length `L` is the image
//! cap's full aperture `2ψ'`, which exceeds `π` exactly when the image is wider than
//! a hemisphere, where Eq. 6–7 return the complement of the true image. This happens
//! for wide caps under a weak pivot (near the origin `g` is close to the antipodal
//! map, which preserves the aperture), and for some caps that contain `r_p/|r_p|`, the
//! point nearest to the pivot, whose neighbourhood `g` magnifies by
//! `((1 + |r_p|)/(1 − |r_p|))²` (its image contains `−r_p/|r_p|`). Containing that
//! point is not sufficient: a small cap around it under a moderate pivot has a small
//! image; the arc length `L` decides.
//!
//! The implementation measures the two halves `g(ω₁) → g(ω_c)` and `g(ω_c) → g(ω₂)` with `atan2` of 2D cross and dot
//! products in that plane, and rotates `g(ω₁)` by `L/2` to get the axis. An image up to
//! a hemisphere (`L ≤ π`) stores `1 − cos ψ' = 2 sin²(L/4)`. A wider image stores its
//! hole `1 + cos ψ' = 2 cos²(L/4) = 2 sin²(L̄/4)` from the complementary arc
//! `L̄ = 2π − L`, the arc `g(ω₂) → g(ω₁)` (counterclockwise) measured directly with
//! its own `atan2` (issue 17, 6): `L` near `2π` is known only to `ulp(2π)`, and
//! `2 − (1 − cos ψ')` only to `ulp(2)`, while a hole of 3.3e-4 (`L̄ = 0.051`) is
//! resolved to the rounding of the two image points, a few 1e-6 of it.
//!
//! Degenerate cases: a cap axis parallel to the pivot (any plane through the axis
//! works; a fixed tangent is used); the pivot at the origin (`g(ω) = −ω`, the
//! antipodal map, as Eq. 2 gives for `r_p = 0`: not the identity); `|r_p| ≥ 1` is
//! clamped to `|r_p| = 1 − 2⁻²⁰` (same direction), so results stay finite; a
//! non-finite pivot is treated as the origin. The empty cap maps to the empty cap and
//! the whole sphere to the whole sphere.
//!
//! Precision: directions are `f32`, so image caps smaller than about `1e-6` rad keep
//! only a few digits of `ψ'`.

use super::cap::Cap;
use crate::math::orthonormal_basis;
use core::f32::consts::PI;
use glam::{Vec2, Vec3};

/// The largest pivot length used: `1 − 2⁻²⁰`.
const MAX_PIVOT_LENGTH: f32 = 1.0 - 1.0 / 1_048_576.0;

/// The pivot made valid: non-finite → origin, `|r_p|` clamped to `MAX_PIVOT_LENGTH`.
///
/// A pivot whose length `√(p·p)` is at most `MAX_PIVOT_LENGTH` is returned as it is,
/// without the six finiteness tests of its components ([`valid_pivot_careful`] for the
/// others, the same bits): the comparison holds only for a finite pivot, since an
/// infinite component makes `p·p` infinite and a NaN one makes it NaN, and both fail it;
/// `valid_pivot_careful` (the former body) returns a finite pivot of such a length unchanged
/// (`the_valid_pivot_s_short_path_is_the_careful_one`). Every fitted pivot takes the short
/// path (`light_tests::fitted_pivots_are_valid_as_they_stand`). (Issue 18: the finiteness
/// tests were 14 instructions per preparation of the SPTD sphere light sampler, in
/// `GgxPivot::from_view`, callgrind, light bench `sptd`.)
#[inline(always)]
pub(crate) fn valid_pivot(pivot: Vec3) -> Vec3 {
    if is_valid_as_it_stands(pivot) {
        pivot
    } else {
        valid_pivot_careful(pivot)
    }
}

/// [`valid_pivot`] of a pivot that is not finite or longer than `MAX_PIVOT_LENGTH` (and
/// of any pivot, for the tests). In line: out of line and cold, its call cost 5.6
/// instructions more per preparation of the SPTD sphere light sampler and about 5 ns more
/// per preparation and sample (light bench `sptd`, callgrind and interleaved timings).
#[inline(always)]
pub(crate) fn valid_pivot_careful(pivot: Vec3) -> Vec3 {
    if !pivot.is_finite() {
        return Vec3::ZERO;
    }
    let length = crate::math::length(pivot);
    if !length.is_finite() {
        // Huge finite components: the direction survives a rescale.
        return crate::math::normalize_or_zero(pivot * 5.421_011e-20) * MAX_PIVOT_LENGTH;
    }
    if length > MAX_PIVOT_LENGTH {
        pivot * (MAX_PIVOT_LENGTH / length)
    } else {
        pivot
    }
}

/// Whether [`valid_pivot`] returns `pivot` as it is, bit for bit: finite and
/// `|r_p| ≤ MAX_PIVOT_LENGTH` (its length as `valid_pivot` computes it; a finite pivot of
/// infinite length fails the comparison, as it fails `valid_pivot`'s). The comparison
/// alone: it fails for every pivot that is not finite (see [`valid_pivot`]).
#[inline(always)]
pub(crate) fn is_valid_as_it_stands(pivot: Vec3) -> bool {
    crate::math::length(pivot) <= MAX_PIVOT_LENGTH
}

/// `g(ω)` for a unit `dir` and a valid pivot, as `r_p − (1 − |r_p|²)(ω − r_p)/|ω − r_p|²`
/// with `1 − |r_p|² = (1 − ρ)(1 + ρ)`, `ρ = |r_p|`.
///
/// Equal in exact arithmetic to `ω − 2(1 − ω·r_p)(ω − r_p)/|ω − r_p|²` (the second
/// intersection of the line with the sphere), but the rounding of the step is relative to
/// `|g − r_p|` instead of to 2, and `1 − |r_p|²` does not cancel: `g(g(ω))` comes back
/// to within 1.2e-5 rad of `ω` for `|r_p| ≤ 0.99` where the other form was 4e-5 off
/// (issue 16, 4; the round trip's conditioning, `(1 + ρ)/(1 − ρ) = 199` times the
/// rounding of a unit vector, is 1.2e-5 there).
#[inline(always)]
pub(crate) fn transform(dir: Vec3, pivot: Vec3) -> Vec3 {
    transform_of_numerator(dir, pivot, transform_numerator(pivot))
}

/// `(1 − ρ)(1 + ρ) = 1 − |r_p|²` (`ρ = |r_p|`) as [`transform`] computes it (without the
/// cancellation of `1 − ρ²` near `ρ = 1`).
#[inline(always)]
pub(crate) fn transform_numerator(pivot: Vec3) -> f32 {
    let rho = crate::math::length(pivot);
    (1.0 - rho) * (1.0 + rho)
}

/// [`transform`] with its numerator `k = transform_numerator(pivot)` given: for a caller
/// that holds the pivot for many directions (the clipped sphere light sampler computes it
/// in its preparation, not per sample). The same bits.
#[inline(always)]
pub(crate) fn transform_of_numerator(dir: Vec3, pivot: Vec3, k: f32) -> Vec3 {
    let e = dir - pivot;
    let scale = k / e.length_squared();
    // (`normalize_or`'s bits by a predicted branch: the samplers' chain does not wait for
    // the test of the reciprocal.)
    crate::math::normalize_or_predicted(pivot - e * scale, -dir)
}

/// The pivot transformation `g(ω; r_p)` (Eq. 2): the second intersection with the
/// unit sphere of the line from `dir` (normalised here) through `pivot`. See the
/// module documentation for invalid pivots; a zero or non-finite `dir` gives `+z`.
pub fn pivot_transform(dir: Vec3, pivot: Vec3) -> Vec3 {
    let Some(dir) = crate::math::unit(dir) else {
        return Vec3::Z;
    };
    transform(dir, valid_pivot(pivot))
}

/// The Jacobian `|dg/dω| = ((1 − |r_p|²) / |ω − r_p|²)²` (Eq. 4) at a unit `dir`
/// (normalised here): the ratio of the solid angle of `g(dω)` to that of `dω`. Zero
/// for a zero or non-finite `dir`.
pub fn pivot_jacobian(dir: Vec3, pivot: Vec3) -> f32 {
    let Some(dir) = crate::math::unit(dir) else {
        return 0.0;
    };
    jacobian_of_unit(dir, valid_pivot(pivot))
}

/// [`pivot_jacobian`] of a unit `dir` and a valid pivot, without their checks: for a
/// caller that holds both (the clipped sphere light sampler, whose samples are unit and
/// whose prepared pivot is valid): the same bits.
#[inline(always)]
pub(crate) fn jacobian_of_unit(dir: Vec3, pivot: Vec3) -> f32 {
    jacobian_of_numerator(dir, pivot, jacobian_numerator(pivot))
}

/// `1 − |r_p|²`, the numerator of [`jacobian_of_unit`]'s ratio, as it computes it (the
/// same value as [`pivot_upper_hemisphere`]'s `k`, which the compiler shares).
#[inline(always)]
pub(crate) fn jacobian_numerator(pivot: Vec3) -> f32 {
    1.0 - pivot.length_squared()
}

/// [`jacobian_of_unit`] with its numerator `n = jacobian_numerator(pivot)` given (see
/// [`transform_of_numerator`]). The same bits.
#[inline(always)]
pub(crate) fn jacobian_of_numerator(dir: Vec3, pivot: Vec3, n: f32) -> f32 {
    let ratio = n / (dir - pivot).length_squared();
    ratio * ratio
}

/// `g` in the 2D plane of a cap's axis (x) and the pivot (y ≥ 0), for a unit `w`, in the
/// form of [`transform`].
#[inline(always)]
fn transform_2d(w: Vec2, pivot: Vec2) -> Vec2 {
    let e = w - pivot;
    let rho = crate::math::length(pivot);
    let scale = (1.0 - rho) * (1.0 + rho) / e.length_squared();
    crate::math::normalize_or(pivot - e * scale, -w)
}

/// The counterclockwise angle from `a` to `b` in `[0, 2π)`.
#[inline(always)]
fn ccw_angle(a: Vec2, b: Vec2) -> f32 {
    let angle = libm::atan2f(a.perp_dot(b), a.dot(b));
    if angle < 0.0 { angle + 2.0 * PI } else { angle }
}

/// The image `g(C)` of a cap under the pivot transformation: the true image, which can
/// be wider than a hemisphere (see the module documentation). The cap must be valid
/// (see [`Cap::sanitized`]).
pub fn pivot_cap(cap: &Cap, pivot: Vec3) -> Cap {
    if !(cap.one_minus_cos > 0.0) {
        return Cap::EMPTY;
    }
    let pivot = valid_pivot(pivot);
    // The whole sphere by its hole: a cap whose hole `1 + cos θ` is below `ulp(2)/2`
    // (7.5e-7 sr) has `one_minus_cos = 2` but keeps its hole (issue 20, 1: the SPTD
    // over the complement of such a cap is the integral over that hole).
    if !(cap.one_plus_cos > 0.0) {
        return Cap {
            axis: transform(cap.axis, pivot),
            ..Cap::WHOLE_SPHERE
        };
    }
    // The plane of the axis and the pivot: x along the axis, y along the pivot's
    // perpendicular component (any tangent when the pivot is on the axis line).
    let along = pivot.dot(cap.axis);
    let perpendicular = pivot - cap.axis * along;
    let across = crate::math::length(perpendicular);
    let tangent = if across > 1e-30 {
        perpendicular / across
    } else {
        orthonormal_basis(cap.axis).0
    };
    let p = Vec2::new(along, across.min(MAX_PIVOT_LENGTH));
    let sin = crate::math::sqrtf(cap.sin2.max(0.0).min(1.0));
    let cos = cap.cos();
    // ω₁ below, ω₂ above the axis: ω₁ → ω_c → ω₂ is counterclockwise.
    let g1 = transform_2d(Vec2::new(cos, -sin), p);
    let g2 = transform_2d(Vec2::new(cos, sin), p);
    let gc = transform_2d(Vec2::X, p);
    // The image arc g(ω₁) → g(ω_c) → g(ω₂), counterclockwise.
    let mut first = ccw_angle(g1, gc);
    let mut second = ccw_angle(gc, g2);
    // Geometrically first + second < 2π; rounding can turn a tiny half into ~2π.
    if first + second > 2.0 * PI {
        if first > second {
            first = 0.0;
        } else {
            second = 0.0;
        }
    }
    let half = 0.5 * (first + second).min(2.0 * PI);
    let (sin_half, cos_half) = libm::sincosf(half);
    let axis_2d = Vec2::new(
        g1.x * cos_half - g1.y * sin_half,
        g1.x * sin_half + g1.y * cos_half,
    );
    let axis = cap.axis * axis_2d.x + tangent * axis_2d.y;
    if half <= 0.5 * PI {
        let s = libm::sinf(0.5 * half);
        return Cap::from_axis_one_minus_cos(axis, 2.0 * s * s);
    }
    // Wider than a hemisphere: the hole from the complementary arc g(ω₂) → g(ω₁), which
    // is `2π − L` in exact arithmetic. Where the hole is below the rounding of the image
    // points, that arc can come out as a turn minus a tiny angle: no hole then.
    let mut rest = ccw_angle(g2, g1);
    if rest > PI {
        rest = if rest > 1.5 * PI { 0.0 } else { PI };
    }
    let s = libm::sinf(0.25 * rest);
    Cap::from_axis_one_plus_cos(axis, 2.0 * s * s)
}

/// What [`pivot_cap_fast`] (or [`pivot_cap_by_points`]) did: its closed form, or the
/// careful [`pivot_cap`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PivotPath {
    /// The closed form (well-conditioned caps).
    Fast,
    /// [`pivot_cap`] ([`pivot_cap_fast`]: empty or whole-sphere caps, pivots not valid as
    /// they stand, `|n| < 1/16`; [`pivot_cap_by_points`]: also images near a hemisphere
    /// and images whose side is not decided by the rounded image points, tiny images or
    /// the pivot close to the cap's boundary).
    Careful,
}

/// `|r_p|²` up to which [`reduced_image`] takes the pivot as it is (`valid_pivot` would
/// return it unchanged: `√x ≤ 1 − 2⁻²⁰`).
const FAST_MAX_PIVOT_LENGTH2: f32 = 1.0 - 4.0 / 1_048_576.0;

/// `|n|²` of the image's plane normal from which [`reduced_image`] answers: `|n| ≥ 1/16`,
/// so that the rounding of `n` (below `8ε` absolute, see there) is below `1.5e-5` of it.
const FAST_MIN_NORMAL2: f32 = 1.0 / 256.0;

/// The image `g(C)` of a cap in closed form, reduced to at most a hemisphere (what Eq. 6–7
/// give): [`reduced_image`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct ReducedImage {
    /// `n = 2δ r_p + k a`, the normal of the image's plane `n·y = c'` (not unit).
    pub normal: Vec3,
    /// `1/|n|`.
    pub inverse_length: f32,
    /// `1 − |cos ψ'|` in `[0, 1]`: `1 − cos ψ'` of the image, or its hole `1 + cos ψ'`
    /// where it is wider than a hemisphere.
    pub side: f32,
    /// `c' ≥ 0`: the image is wider than a hemisphere (its complement, of axis `+n/|n|`, has
    /// the side), else the image itself has axis `−n/|n|` and the side.
    pub wide: bool,
}

impl ReducedImage {
    /// The image as a [`Cap`]: axis `−n/|n|` (unit to a few ulps), `side` on the small
    /// side (`one_minus_cos`, or `one_plus_cos` for a wide image) and `2 − side` (exact,
    /// Sterbenz) on the other, `sin²ψ' = side (2 − side)` as `Cap::with_sides` stores it.
    #[inline(always)]
    pub(crate) fn cap(&self) -> Cap {
        let side = self.side;
        let other = 2.0 - side;
        let (one_minus_cos, one_plus_cos) = if self.wide {
            (other, side)
        } else {
            (side, other)
        };
        Cap {
            axis: self.normal * -self.inverse_length,
            one_minus_cos,
            one_plus_cos,
            sin2: (side * other).max(0.0).min(1.0),
        }
    }
}

/// The image `g(C)` of a valid cap (see [`Cap::sanitized`]) in closed form, from the plane
/// of its boundary circle (issue 18): one square root and one division, no plane of the
/// axis and the pivot, no image points. `None` where the careful [`pivot_cap`] must
/// decide: an empty or whole cap (stored by its hole), a pivot not valid as it stands
/// (`|r_p|² > 1 − 2⁻¹⁸` or not finite), or `|n|² < 1/256`.
///
/// `g(y) = r_p − k(y − r_p)/|y − r_p|²` with `k = 1 − |r_p|²` (Eq. 2, in the form of
/// [`transform`]) is the inversion about `r_p` of power `−k`: `y = g(x)` ⇔
/// `x − r_p = −k(y − r_p)/|y − r_p|²`. The cap is `C = {x : a·x ≥ cos θ}`; with
/// `δ = a·r_p − cos θ`, `a·x − cos θ = δ − k a·(y − r_p)/|y − r_p|²`, and on the sphere
/// `|y − r_p|² = 1 + |r_p|² − 2 r_p·y > 0`, so `x ∈ C` ⇔ `n·y ≤ c'` with
///
/// `n = 2δ r_p + k a`, `c' = δ(1 + |r_p|²) + k (a·r_p)`:
///
/// `g(C)` is the cap of axis `−n/|n|` and `cos ψ' = −c'/|n|`. With `|a| = 1` and `s = a·r_p`,
/// `|n|² = 4δ²|r_p|² + 4δks + k²` and `c'² = δ²(1 + |r_p|²)² + 2δks(1 + |r_p|²) + k²s²`;
/// as `(1 + |r_p|²)² − 4|r_p|² = k²` and `2 − (1 + |r_p|²) = k`,
/// `|n|² − c'² = k²(1 − s² + 2δs − δ²) = k²(1 − (s − δ)²) = k² sin²θ`, so the smaller side
/// `1 − |cos ψ'| = (|n|² − c'²)/(|n|(|n| + |c'|)) = k² sin²θ / (|n|(|n| + |c'|))` has no
/// cancellation (the stored `sin²θ`: a tiny cap keeps the relative precision of its
/// image). It is `1 − cos ψ'` of the image where `c' < 0` and its hole `1 + cos ψ'`
/// otherwise (the image wider than a hemisphere); at `c' = 0` both are the same
/// hemisphere, so the switch is continuous. (`|n| = |ω₁ − r_p||ω₂ − r_p|` for the boundary
/// points `ω₁, ω₂` in the plane of `a` and `r_p`: `sin ψ' = k sin θ / |n|`, the form of
/// [`pivot_cap_by_points`].) `1/(|n|(|n| + |c'|))` once gives both the side and, times
/// `|n| + |c'|`, `1/|n|`.
///
/// Error bound (f32, an axis unit to rounding): the terms of `n` and `c'` are at most a few
/// units and `δ` is exact where it cancels (Sterbenz), so `n` and `c'` are within `8ε`
/// absolute of their values for the stored cap, and with `|n| ≥ 1/16` the axis is within
/// `128ε = 1.5e-5` rad and the side within `3e-5` relative from them, plus the rounding of
/// `k` (`ε|r_p|²/k` relative, doubled by `k²`: below `3ε (1 + ρ)/(1 − ρ)`, `ρ = |r_p|`,
/// shared with every form of `g`). In particular a tiny cap (1e-12 sr, which the points'
/// form sends to [`pivot_cap`], where `1 − ω'_c·g(ω₁)` keeps only a few digits) keeps its
/// side to these bounds, and an image wider than a hemisphere its hole. Tested against the
/// `f64` images of the boundary points (`the_reduced_image_against_f64`: caps from 1e-12 sr
/// to nearly the sphere, pivots to `|r_p| = 0.999`, on the axis line and at the origin),
/// which asserts these bounds and, for `|r_p| ≤ 0.95`, the points' form's 2e-5 relative in
/// the side; measured: the side to 6e-5 relative at `|r_p|` near 0.999 (8e-7 of the
/// magnification: the rounding of `k`), the axis to 3e-6 rad.
///
/// `OFF_AXIS` adds a gate that the closed form itself does not need (it has no plane of
/// the axis and the pivot): `None` also for the pivot (nearly) on the cap's axis line, for
/// the real-time shading (`shading_fast`), whose careful path is better there. Tested as
/// `|r_p⊥|² = |r_p|² − (a·r_p)² > 4e-6 |r_p|²` (the pivot more than 2e-3 rad off the line),
/// which needs only `a·r_p`: on the line `(a·r_p)² = |r_p|²|a|²`, and `|a|²` is 1 to
/// `UNIT_TOLERANCE = 1e-6` (a valid cap), the three roundings a few 1e-7 of `|r_p|²`, so
/// the difference is below `2e-6 |r_p|²` there. A pivot at the origin fails too
/// (`0 > 0`); the cone of pivots that the gate adds is a few 1e-6 of the directions.
#[inline(always)]
pub(crate) fn reduced_image<const OFF_AXIS: bool>(cap: &Cap, pivot: Vec3) -> Option<ReducedImage> {
    if !(cap.one_minus_cos > 0.0) || !(cap.one_plus_cos > 0.0) {
        return None;
    }
    let rho2 = pivot.length_squared();
    if !(rho2 <= FAST_MAX_PIVOT_LENGTH2) {
        return None;
    }
    let axis = cap.axis;
    let along = pivot.dot(axis);
    if OFF_AXIS && !(rho2 - along * along > 4e-6 * rho2) {
        return None;
    }
    // `k = 1 − |r_p|²` (exact for `|r_p|² ≥ 1/2`, Sterbenz), `δ = a·r_p − cos θ` (exact
    // subtraction where it cancels, Sterbenz), the image's plane `n·y = c'`.
    let k = 1.0 - rho2;
    let delta = along - cap.cos();
    let normal = pivot * (2.0 * delta) + axis * k;
    let offset = delta * (1.0 + rho2) + k * along;
    let n2 = normal.length_squared();
    // Ill-conditioned (the pivot near the sphere and the cap near `r_p/|r_p|`, whose image
    // is then nearly the whole sphere). NaN cannot occur here (finite valid inputs), but
    // fails the test as well.
    if !(n2 >= FAST_MIN_NORMAL2) {
        return None;
    }
    let n = crate::math::sqrtf(n2);
    let sum = n + offset.abs();
    let reciprocal = 1.0 / (n * sum);
    // `≤ 1` in exact arithmetic. (`min(1)` as a compare and select: the same value for
    // every input, NaN included.)
    let side = (k * k) * cap.sin2 * reciprocal;
    let side = if side < 1.0 { side } else { 1.0 };
    Some(ReducedImage {
        normal,
        inverse_length: reciprocal * sum,
        side,
        wide: offset >= 0.0,
    })
}

/// [`pivot_cap`] by the closed form [`reduced_image`] where it is well conditioned,
/// [`pivot_cap`] itself elsewhere (empty or whole caps, pivots not valid as they stand,
/// `|n| < 1/16`): the sphere light sampler's image (issue 18). Same contract; the pivot
/// need not be valid (the closed form takes only pivots that `valid_pivot` returns as they
/// are, and `pivot_cap` makes the others valid).
#[inline(always)]
pub(crate) fn pivot_cap_fast(cap: &Cap, pivot: Vec3) -> (Cap, PivotPath) {
    match reduced_image::<false>(cap, pivot) {
        Some(image) => (image.cap(), PivotPath::Fast),
        None => pivot_cap_careful(cap, &pivot),
    }
}

/// `|g(ω₁) − g(ω₂)|² / 4` below which the side test of [`pivot_cap_by_points`] is not
/// trusted (see there): `1 − 1/256`, i.e. `|cos ψ'| ≥ 1/16`.
const FAST_MAX_SIN2: f32 = 1.0 - 1.0 / 256.0;

/// [`pivot_cap`] by the images of the boundary points where it is well conditioned,
/// [`pivot_cap`] itself elsewhere: the real-time shading's images of the horizon and of
/// bent cones, and its careful path (`light.rs`), whose bits the closed form
/// [`pivot_cap_fast`] would move (the determinism table's `sphere_shade` rows; issue 18,
/// 1). Same contract.
///
/// In the plane of the cap's axis (x) and the pivot `p` (y ≥ 0), the boundary points
/// are `ωᵢ = (cos θ, ∓ sin θ)` and `g(ω) = p − k (ω − p)/|ω − p|²`, `k = 1 − |p|²`
/// (Eq. 2, the form of [`transform`]). The map `u ↦ u/|u|²` (inversion in the unit
/// circle) satisfies `|u/|u|² − v/|v|²| = |u − v| / (|u| |v|)`, so with `eᵢ = ωᵢ − p`
/// and `|ω₁ − ω₂| = 2 sin θ`:
///
/// `sin ψ' = |g(ω₁) − g(ω₂)| / 2 = k sin θ / (|e₁| |e₂|)`,
///
/// the half-chord of the image circle: the plane is a plane of symmetry, so
/// `g(ω₁), g(ω₂)` are the ends of a diameter of the image's boundary circle (the two
/// points of Eq. 6–7). It has no cancellation (`k = (1 − ρ)(1 + ρ)`, the `|eᵢ|` are
/// lengths of differences), so a tiny image keeps its relative precision, where
/// `1 − ω'_c·g(ω₁)` of Eq. 7 loses it. Then `|cos ψ'| = √(1 − sin²ψ')` and the stored side
/// `1 ∓ cos ψ' = sin²ψ' / (1 + |cos ψ'|)`, which is `1 − cos ψ'` for an image up to a
/// hemisphere (axis `ω'_c`, Eq. 6: the normalised `g(ω₁) + g(ω₂)`) and its hole
/// `1 + cos ψ'` for a wider one (axis `−ω'_c`; the module documentation explains why
/// Eq. 6–7 return the complement there).
///
/// The side: the image contains `g(ω_c)` (module documentation), which lies on the arc
/// `g(ω₁) → g(ω₂)` that is the image of the cap's arc. On a circle, a point lies on the
/// minor arc between two others exactly when the inscribed angle there is obtuse, so the
/// image is at most a hemisphere when `q = (g(ω₁) − g(ω_c))·(g(ω₂) − g(ω_c)) < 0` and
/// wider when `q > 0`. Each rounded image point is within `δ = 6e-7` of the exact one
/// (a few ulps of a normalised vector), so `q` is within `δ(|a| + |b|) + δ²` of the exact
/// value (`a, b` the two differences): the points are used only where
/// `|q| > 4e-6 (|a| + |b|) + 1e-12`, and where `|cos ψ'| ≥ 1/16` (the axis, the
/// direction of `g(ω₁) + g(ω₂)`, keeps its precision; near a hemisphere the careful
/// path's arc lengths are better conditioned). Everything else takes [`pivot_cap`].
///
/// The pivot by reference, and its careful path out of line: the occluded shading's bent
/// cone (`SphereLightShading::eval_occluded`) passed the prepared pivot by value, which
/// the compiler copied to the stack as 8 + 4 bytes for the careful call and read back as
/// 4 + 8 on the fast path (a load across two stores, which the store buffer cannot
/// forward; see `pivoted_intersection` in `light.rs`).
#[inline(always)]
pub(crate) fn pivot_cap_by_points(cap: &Cap, pivot: &Vec3) -> (Cap, PivotPath) {
    // Empty caps and whole spheres (stored by their hole) go the careful way.
    if !(cap.one_minus_cos > 0.0) || !(cap.one_plus_cos > 0.0) {
        return pivot_cap_careful(cap, pivot);
    }
    let p3 = valid_pivot(*pivot);
    let along = p3.dot(cap.axis);
    let perpendicular = p3 - cap.axis * along;
    let across2 = perpendicular.length_squared();
    // The pivot (nearly) on the axis line: the plane is not defined by it (the rounding
    // of `perpendicular`, about 6e-8, would tilt the tangent out of the tangent plane).
    if !(across2 > 1e-12) {
        return pivot_cap_careful(cap, pivot);
    }
    let across = crate::math::sqrtf(across2);
    let tangent = perpendicular * (1.0 / across);
    let p = Vec2::new(along, across.min(MAX_PIVOT_LENGTH));
    let ([g1, g2, gc], sin2) = images_in_plane(cap, p, p.length_squared());
    let a = g1 - gc;
    let b = g2 - gc;
    let q = a.dot(b);
    let margin = 4e-6 * (crate::math::length(a) + crate::math::length(b)) + 1e-12;
    let mid = g1 + g2;
    if !(sin2 <= FAST_MAX_SIN2) || !(q.abs() > margin) {
        return pivot_cap_careful(cap, pivot);
    }
    // |cos ψ'| ≥ 1/16 here, so |g(ω₁) + g(ω₂)| = 2|cos ψ'| ≥ 1/8 up to rounding: the
    // normalisation is safe (in 3D: the tangent is orthogonal to the axis only to
    // 6e-8 / |perpendicular|, and `Cap` wants a unit axis to 1e-6).
    let mid_axis = cap.axis * mid.x + tangent * mid.y;
    let mid_axis = mid_axis * (1.0 / crate::math::length(mid_axis));
    let abs_cos = crate::math::sqrtf(1.0 - sin2);
    // 1 ∓ cos ψ' ≤ 1; the other side 2 − it is exact (Sterbenz), and sin²ψ' = t h as
    // `Cap::with_sides` stores it.
    let side = (sin2 / (1.0 + abs_cos)).min(1.0);
    let other = 2.0 - side;
    let image = if q < 0.0 {
        Cap {
            axis: mid_axis,
            one_minus_cos: side,
            one_plus_cos: other,
            sin2: (side * other).max(0.0).min(1.0),
        }
    } else {
        Cap {
            axis: -mid_axis,
            one_minus_cos: other,
            one_plus_cos: side,
            sin2: (side * other).max(0.0).min(1.0),
        }
    };
    (image, PivotPath::Fast)
}

/// The image `g(H)` of the upper hemisphere `H = {ω : ω_z ≥ 0}` under a valid pivot `p`,
/// in closed form (the sphere light sampler's clipped preparation, issue 18: one square
/// root and a division where [`pivot_cap_fast`] of `H` took six of each).
///
/// `g` is the inversion `x ↦ p − k (x − p)/|x − p|²` (`k = 1 − |p|²`, Eq. 2 in the form of
/// [`transform`]), an involution, restricted to the unit sphere. A point `x'` of the sphere
/// is `g(x)` with `x − p = −k (x' − p)/|x' − p|²`, so for a plane `n·x = c`
///
/// `n·x − c = −[(c − n·p) |x' − p|² + k n·(x' − p)] / |x' − p|²`,
///
/// and with `|x' − p|² = 1 − 2 p·x' + |p|²` on the sphere the bracket is `m·x' − e` with
/// `m = k n − 2 (c − n·p) p`, `e = k n·p − (c − n·p)(1 + |p|²)`. For `H` (`n = z`,
/// `c = 0`): `m = k z + 2 p_z p`, `e = p_z (k + 1 + |p|²) = 2 p_z`. So `x ∈ H` exactly when
/// `m·x' ≤ e`: `g(H)` is the cap of axis `−m/|m|` with `cos ψ' = −2 p_z/|m|` (for `p = 0`
/// the antipodal map's lower hemisphere). Its smaller side `1 − |cos ψ'|` has no
/// cancellation: `|m|² = k² + 4 p_z² (k + |p|²) = k² + 4 p_z²`, so
/// `1 − 2|p_z|/|m| = (|m|² − 4 p_z²)/(|m| (|m| + 2|p_z|)) = k² / (|m| (|m| + 2|p_z|))`; it
/// is the hole `1 + cos ψ'` for `p_z ≥ 0` (the image contains `g(z)` near `−z`), else
/// `1 − cos ψ'`, and the other side is `2 −` it, as [`pivot_cap_fast`] stores them.
/// Tested against `f64` images of the boundary (`the_upper_hemisphere_s_image_in_closed_form`).
#[inline(always)]
pub(crate) fn pivot_upper_hemisphere(pivot: Vec3) -> Cap {
    let rho2 = pivot.length_squared();
    let k = 1.0 - rho2;
    let m = Vec3::new(0.0, 0.0, k) + pivot * (2.0 * pivot.z);
    let length = crate::math::length(m);
    let abs_z = pivot.z.abs();
    // (`|m| ≥ k > 0` for a valid pivot; `min` keeps a cap, and the axis unit, if not.)
    let side = ((k * k) / (length * (length + 2.0 * abs_z))).min(1.0);
    let other = 2.0 - side;
    let sin2 = (side * other).max(0.0).min(1.0);
    let axis = m * (-1.0 / length);
    if pivot.z >= 0.0 {
        Cap {
            axis,
            one_minus_cos: other,
            one_plus_cos: side,
            sin2,
        }
    } else {
        Cap {
            axis,
            one_minus_cos: side,
            one_plus_cos: other,
            sin2,
        }
    }
}

/// The careful path of [`pivot_cap_fast`] and [`pivot_cap_by_points`] (out of line: it is
/// rare).
#[cold]
#[inline(never)]
fn pivot_cap_careful(cap: &Cap, pivot: &Vec3) -> (Cap, PivotPath) {
    (pivot_cap(cap, *pivot), PivotPath::Careful)
}

/// In the plane of a cap's axis (x) and the pivot `p` (y ≥ 0; `rho2 = |r_p|²`), the
/// images under `g` (Eq. 2, as in `transform_2d`) of the cap's boundary points
/// `ωᵢ = (cos θ, ∓ sin θ)` and of its center `(1, 0)`, and `sin²ψ'` of the image: with
/// `eᵢ = ωᵢ − p` and `k = 1 − |r_p|²`, `g(ω) = p − k e / |e|²`, unit in exact arithmetic
/// and not renormalised (the callers' side tests allow for the rounding), and
/// `sin ψ' = k sin θ / (|e₁||e₂|)` squared (see [`pivot_cap_by_points`]). ([`reduced_image`]
/// is the closed form without the points.)
#[inline(always)]
pub(crate) fn images_in_plane(cap: &Cap, p: Vec2, rho2: f32) -> ([Vec2; 3], f32) {
    let sin = crate::math::sqrtf(cap.sin2.max(0.0).min(1.0));
    let cos = cap.cos();
    let e1 = Vec2::new(cos, -sin) - p;
    let e2 = Vec2::new(cos, sin) - p;
    let ec = Vec2::X - p;
    let (l1, l2, lc) = (
        e1.length_squared(),
        e2.length_squared(),
        ec.length_squared(),
    );
    let rho = crate::math::sqrtf(rho2);
    let k = (1.0 - rho) * (1.0 + rho);
    let g = |e: Vec2, l: f32| p - e * (k / l);
    let sin2 = (k * k * cap.sin2) / (l1 * l2);
    ([g(e1, l1), g(e2, l2), g(ec, lc)], sin2)
}

#[cfg(test)]
#[path = "pivot_tests.rs"]
mod tests;
