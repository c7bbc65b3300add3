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
//! normal range. It also stores the complement `h = 1 + cos θ = 2 − t`, the size of
//! the cap's hole, to full relative precision: a cap wider than a hemisphere has `t`
//! near 2, where `f32` keeps only `ulp(2) = 2.4e-7` of `h` (issue 17, 6: the pivot
//! image of a light, 3.116 rad wide with a hole `h = 3.3e-4`, lost 4e-4 of its hole
//! and shading with a bent cone 3.7e-4 of its value). Of the two, the smaller one
//! (at most 1) is the authoritative value and the other is `2 −` it, rounded once;
//! both are then accurate to a few ulps. Every other quantity (solid angle, sampling,
//! containment, inversion) is derived from `t` and `h` without forming `1 ± cos`
//! again:
//!
//! - sampling: `t' = u₀ t` is uniform in `[0, t]` (uniform in solid angle, since
//!   `dΩ = d(1 − cos) dφ`), and the direction is built from `sin θ' = √(t' h')`,
//!   `cos θ' = 1 − t'`, `φ = 2π u₁`, where `h' = 1 + cos θ' = 2 − t'` is formed as
//!   `h + (1 − u₀) t` when `t' > 1` (`1 − u₀` is exact there), so that samples near
//!   a small hole are placed relative to the hole's size, not to `ulp(2)`;
//! - containment and inversion: for unit vectors `|ω − a|² = 2 (1 − ω·a)` and
//!   `|ω + a|² = 2 (1 + ω·a)`, which give `1 ∓ cos` of a direction without
//!   cancellation; wide caps compare the direction's `1 + ω·a` with `h`.
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
use glam::{Vec3, Vec3A};

/// A spherical cap `{ω : ω·axis ≥ cos θ}` with `1 ∓ cos θ` both to full relative
/// precision: the smaller is authoritative, the other `2 −` it. Every function makes a cap
/// built by hand valid, from `one_minus_cos` (a wide cap keeps an `one_plus_cos` within
/// `2⁻²²` of `2 − one_minus_cos`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cap {
    /// Unit axis (direction of the cap's center).
    pub axis: Vec3,
    /// `1 − cos θ` in `[0, 2]`: 0 for an empty cap, 1 for a hemisphere, 2 for the whole
    /// sphere. Authoritative for caps up to a hemisphere (`one_minus_cos ≤ 1`).
    pub one_minus_cos: f32,
    /// `1 + cos θ` in `[0, 2]`, the cap's hole: 2 for an empty cap, 0 for the whole
    /// sphere. Authoritative for caps wider than a hemisphere (`one_minus_cos > 1`).
    pub one_plus_cos: f32,
    /// `sin²θ = (1 − cos θ)(1 + cos θ)` in `[0, 1]`.
    pub sin2: f32,
}

/// The unit axis of [`Cap::outside_sphere`]: `c` divided by its largest component, then
/// by its length. In `Vec3A`, whose four lanes are computed as they stand: built from
/// three scalars, the prepared sphere's first 16-byte group (axis and `1 − cos θ`) was
/// vectorised as `(c, t) / (m, m, m, 1)`, which made the axis's chain (a division, a
/// square root, a division, then the frame's division) wait for `t`'s (a division, a
/// square root and a division): the two chains in series instead of side by side. The
/// same operations lane for lane, so the same bits.
#[inline(always)]
fn outside_sphere_axis(c: Vec3) -> Vec3A {
    let c = Vec3A::from(c);
    let scaled = c / c.abs().max_element();
    scaled * (1.0 / crate::math::sqrtf(scaled.length_squared()))
}

/// `2^k` for `k` in `[−126, 127]`.
#[inline(always)]
fn power_of_two(k: i32) -> f32 {
    f32::from_bits(((127 + k) as u32) << 23)
}

/// The smallest radius and center distance that [`Cap::from_sphere`] takes without
/// rescaling, `2⁻²⁹`.
const SPHERE_RANGE_MIN: f32 = 1.0 / (1u32 << 29) as f32;
/// The largest, `2²⁹`.
const SPHERE_RANGE_MAX: f32 = (1u32 << 29) as f32;

/// Whether the radius and `d = |center|` lie in `[2⁻²⁹, 2²⁹]` (NaN and infinities fail
/// the comparisons). There, every square and product of [`Cap::outside_sphere`] is a
/// normal finite number (`r²`, `|c|² ∈ [2⁻⁵⁸, 2⁵⁸]`, `sin²θ = r²/|c|² ≥ 2⁻¹¹⁶`,
/// `d (d + q) ≤ 2⁵⁹`), `1 − cos θ ≥ 2⁻¹¹⁷` and `1/Ω ≤ 2¹¹⁵` are normal and finite, and so
/// the power-of-two rescaling of [`Cap::from_sphere_careful`] changes no bit: rounding
/// commutes with it in the normal range, and a square below `2⁻¹²⁶` is absorbed by a sum
/// of at least `2⁻⁵⁸` either way (a center component below `2⁻¹²⁶` of the largest may
/// round differently when rescaled; this path keeps it exact).
#[inline(always)]
fn sphere_in_range(center: Vec3, radius: f32) -> bool {
    let d2 = center.length_squared();
    (SPHERE_RANGE_MIN..=SPHERE_RANGE_MAX).contains(&radius)
        && (SPHERE_RANGE_MIN * SPHERE_RANGE_MIN..=SPHERE_RANGE_MAX * SPHERE_RANGE_MAX).contains(&d2)
}

/// `d = |center|` when the sphere is seen from outside (`d > r`) and in range
/// ([`sphere_in_range`]): exactly the spheres whose cap [`sphere_cap_in_range`] gives
/// (`the_spheres_that_skip_the_rescaling`), written out for the tests.
#[cfg(test)]
pub(crate) fn sphere_distance_in_range(center: Vec3, radius: f32) -> Option<f32> {
    if !sphere_in_range(center, radius) {
        return None;
    }
    let d = crate::math::sqrtf(center.length_squared());
    if d > radius { Some(d) } else { None }
}

/// The cap of a sphere seen from outside and in range ([`sphere_in_range`]), the fast
/// path of [`Cap::from_sphere`] and of the prepared sphere light; `None` for the rest
/// (bad input, the shading point inside or on the sphere, huge or tiny coordinates),
/// which the careful path takes. Bit for bit [`Cap::from_sphere_careful`] where it gives
/// a cap (`the_fast_sphere_cap_is_the_careful_one_bit_for_bit`).
#[inline(always)]
pub(crate) fn sphere_cap_in_range(center: Vec3, radius: f32) -> Option<Cap> {
    if !sphere_in_range(center, radius) {
        return None;
    }
    Cap::outside_sphere(center, radius)
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
        one_plus_cos: 2.0,
        sin2: 0.0,
    };

    /// The whole sphere around the axis `z`.
    ///
    /// cbindgen:ignore
    pub const WHOLE_SPHERE: Cap = Cap {
        axis: Vec3::Z,
        one_minus_cos: 2.0,
        one_plus_cos: 0.0,
        sin2: 0.0,
    };

    /// The cap that a sphere of radius `radius` centered at `center` (relative to the
    /// shading point) subtends: `sin θ = r / d`, `cos θ = √((d − r)(d + r)) / d`,
    /// `1 − cos θ = sin²θ / (1 + cos θ)`. The whole sphere when `d ≤ r` (axis `z` when
    /// the center is the shading point); [`Cap::EMPTY`] for a non-finite center or a
    /// radius that is not finite and positive.
    #[inline]
    pub fn from_sphere(center: Vec3, radius: f32) -> Cap {
        // Ordinary spheres take the formula as they come; the rest (bad input, the
        // shading point inside, huge or tiny coordinates) the careful path.
        match sphere_cap_in_range(center, radius) {
            Some(cap) => cap,
            None => Cap::from_sphere_careful_of(center.x, center.y, center.z, radius),
        }
    }

    /// [`Cap::from_sphere_careful`] of the center's coordinates: the fast paths' call,
    /// whose four floats travel in registers (a `Vec3` argument went through the stack,
    /// stored before the fast path's first test).
    #[inline(never)]
    pub(crate) fn from_sphere_careful_of(x: f32, y: f32, z: f32, radius: f32) -> Cap {
        Cap::from_sphere_careful(Vec3::new(x, y, z), radius)
    }

    /// [`Cap::from_sphere`] of any input: checked, and rescaled by a power of two
    /// before squaring.
    #[inline(always)]
    pub(crate) fn from_sphere_careful(center: Vec3, radius: f32) -> Cap {
        // `x − x` is 0 for a finite `x` and NaN for an infinite or NaN one: one test of
        // the four numbers (in place of a classification of each).
        #[allow(clippy::eq_op)] // `x − x` on purpose
        let finite = (center.x - center.x)
            + (center.y - center.y)
            + (center.z - center.z)
            + (radius - radius);
        if !(finite == 0.0 && radius > 0.0) {
            return Cap::EMPTY;
        }
        // Rescale by a power of two (exact) so that squaring neither overflows nor
        // underflows.
        let m = center.abs().max_element().max(radius);
        let (s1, s2) = rescaling(m);
        let c = center * s1 * s2;
        let r = radius * s1 * s2;
        if let Some(cap) = Cap::outside_sphere(c, r) {
            return cap;
        }
        // `d ≤ r`: the shading point is inside or on the sphere.
        let axis = if crate::math::length(c) > 0.0 {
            crate::math::normalize_scaled(c)
        } else {
            Vec3::Z
        };
        Cap {
            axis,
            ..Cap::WHOLE_SPHERE
        }
    }

    /// The cap of a sphere of radius `r > 0` centered at `c`, with `r²`, `|c|²` and the
    /// products below normal and finite; `None` when it is not seen from outside
    /// (`d = |c| ≤ r`).
    #[inline(always)]
    pub(crate) fn outside_sphere(c: Vec3, r: f32) -> Option<Cap> {
        // `1 − cos θ = sin²θ / (1 + cos θ)`: exact to a few ulps for tiny caps (no
        // subtraction), and `1 + cos θ` has no cancellation (the cap is at most a
        // hemisphere). `cos θ` from `sin²θ = r²/d²` where `cos²θ >= 1/4`; for wider caps
        // as `q / d` with `q = d cos θ = √((d − r)(d + r))`, without the cancellation of
        // `1 − sin²θ`: `1 − cos θ = r² / (d (d + q))`. Measured against f64 (the cap
        // tests): at most 4.1 and 9.8 units of 2⁻²⁴ relative. The cap is written in the
        // form that `Cap::sanitized` keeps unchanged (`1 + cos θ = 2 − t`,
        // `sin²θ = t (2 − t)`).
        let d2 = c.length_squared();
        let sin2 = r * r / d2;
        let t = if sin2 <= 0.75 {
            // sin²θ = r²/d² and `cos θ = √(1 − sin²θ)`, which has no cancellation to
            // speak of where `cos²θ >= 1/4`: one square root and two divisions on the
            // way from `|c|²` (none of them on `d`), where the form below has two
            // square roots in a row. Here the sphere is seen from outside without `d`:
            // the rounded `r²/d²` is at most 0.75, so `d² ≥ 0.75⁻¹ r² (1 − 2⁻²²) > 1.3 r²`
            // and `d = √(d²)` rounds above `r` (the test `d > r` below, and its square
            // root, are needed only for wider caps).
            sin2 / (1.0 + crate::math::sqrtf(1.0 - sin2))
        } else {
            let d = crate::math::sqrtf(d2);
            if !(d > r) {
                return None;
            }
            let q = crate::math::sqrtf((d - r) * (d + r));
            r * r / (d * (d + q))
        }
        .min(1.0);
        let h = 2.0 - t;
        Some(Cap {
            // Normalised as `Cap::sanitized` normalises an invalid axis (by the largest
            // component first): unit to a few ulps, which the pivot transformation needs
            // (see `Cap::sanitized`; `c / d` failed a test of the pivot). Written out
            // without `normalize_by_largest`'s checks, which `c` passes (finite, and its
            // largest component at least `d / √3 > r / √3 > 0`): the same bits.
            axis: outside_sphere_axis(c).into(),
            one_minus_cos: t,
            one_plus_cos: h,
            sin2: (t * h).max(0.0).min(1.0),
        })
    }

    /// The cap around `axis` (normalised here) with `cos θ = cos` (clamped to
    /// `[−1, 1]`). [`Cap::EMPTY`] for a non-finite or zero axis or a NaN `cos`. The
    /// smaller of `1 ∓ cos` is exact (Sterbenz), so a wide cap keeps its hole `1 + cos`
    /// exactly; tiny caps and tiny holes below `ulp(1)` are not representable through
    /// `cos`: prefer [`Cap::from_axis_one_minus_cos`] and
    /// [`Cap::from_axis_one_plus_cos`] for them.
    pub fn from_axis_cos(axis: Vec3, cos: f32) -> Cap {
        if cos.is_nan() {
            return Cap::EMPTY;
        }
        let cos = cos.max(-1.0).min(1.0);
        if cos >= 0.0 {
            Cap::from_axis_one_minus_cos(axis, 1.0 - cos)
        } else {
            Cap::from_axis_one_plus_cos(axis, 1.0 + cos)
        }
    }

    /// The cap around `axis` (normalised here) with `1 − cos θ = one_minus_cos`
    /// (clamped to `[0, 2]`). [`Cap::EMPTY`] for a non-finite or zero axis or a NaN
    /// `one_minus_cos`. Caps wider than a hemisphere get their hole `2 − one_minus_cos`
    /// only to `ulp(2)`; prefer [`Cap::from_axis_one_plus_cos`] for them.
    pub fn from_axis_one_minus_cos(axis: Vec3, one_minus_cos: f32) -> Cap {
        if one_minus_cos.is_nan() {
            return Cap::EMPTY;
        }
        let t = one_minus_cos.max(0.0).min(2.0);
        Cap::with_sides(axis, t, 2.0 - t)
    }

    /// The cap around `axis` (normalised here) with `1 + cos θ = one_plus_cos` (clamped to
    /// `[0, 2]`): the complement form, which keeps the hole of a cap wider than a
    /// hemisphere to full relative precision. [`Cap::EMPTY`] for a non-finite or zero
    /// axis or a NaN `one_plus_cos`.
    pub fn from_axis_one_plus_cos(axis: Vec3, one_plus_cos: f32) -> Cap {
        if one_plus_cos.is_nan() {
            return Cap::EMPTY;
        }
        let h = one_plus_cos.max(0.0).min(2.0);
        Cap::with_sides(axis, 2.0 - h, h)
    }

    /// The cap with `1 − cos θ = t`, `1 + cos θ = h` (`t + h = 2` to rounding, both in
    /// `[0, 2]`): the smaller one is kept and the other recomputed from it (one
    /// rounding), and `sin²θ = t h` is the product of two accurate factors.
    #[inline(always)]
    fn with_sides(axis: Vec3, t: f32, h: f32) -> Cap {
        // Normalised by the largest component first: a huge axis overflowed `length`,
        // and a tiny one (components of 1e-23) normalised through denormal squares to
        // length 1.006 (found by fuzzing).
        let unit = crate::math::normalize_scaled(axis);
        if unit == Vec3::ZERO {
            return Cap::EMPTY;
        }
        let (t, h) = if t <= 1.0 { (t, 2.0 - t) } else { (2.0 - h, h) };
        Cap {
            axis: unit,
            one_minus_cos: t,
            one_plus_cos: h,
            sin2: (t * h).max(0.0).min(1.0),
        }
    }

    /// Whether the cap is in the form that `Cap::with_sides` writes (with any axis of
    /// unit length to `UNIT_TOLERANCE`): then [`Cap::sanitized`] has nothing to do.
    #[inline(always)]
    pub(crate) fn is_valid(&self) -> bool {
        let (t, h) = (self.one_minus_cos, self.one_plus_cos);
        // NaN fails every comparison; `2 − t` and `2 − h` are exact (Sterbenz).
        let sides = if t <= 1.0 {
            t >= 0.0 && h == 2.0 - t
        } else {
            h >= 0.0 && t == 2.0 - h
        };
        let a = self.axis;
        // An infinite or NaN axis gives an infinite or NaN `|axis|²`, which fails.
        sides
            && self.sin2 == (t * h).max(0.0).min(1.0)
            && (a.length_squared() - 1.0).abs() <= crate::math::UNIT_TOLERANCE
    }

    /// This cap with every field made valid: a non-finite or zero axis or a NaN
    /// `one_minus_cos` gives [`Cap::EMPTY`]; otherwise the axis is normalised,
    /// `one_minus_cos` clamped to `[0, 2]`, and `one_plus_cos` and `sin2` recomputed
    /// from it, except that a cap wider than a hemisphere (`one_minus_cos > 1`) keeps
    /// its `one_plus_cos` (clamped to `[0, 1]`) when that agrees with
    /// `2 − one_minus_cos` to `2⁻²²` (the rounding of `one_minus_cos` near 2), and
    /// `one_minus_cos` is recomputed from it: the hole's precision survives the trip
    /// through C, and a cap built by hand with a stale `one_plus_cos` still gets the
    /// cap that its `one_minus_cos` says. Idempotent. Used by the C ABI, where a caller
    /// may build a cap by hand.
    ///
    /// A cap that is valid already (finite axis with `|axis|²` within
    /// `UNIT_TOLERANCE` of 1, the authoritative side in range, the other side `2 −` it
    /// and `sin2` their clamped product, bit for bit: what every constructor writes) is
    /// returned as it is, without normalising its axis again: that made this function
    /// idempotent bit for bit (a normalised axis normalised again could change in its
    /// last bit), and saves 80 of the 390 instructions of a sample through the C ABI.
    /// The constructors normalise their axes with the same function as the slow path
    /// (dividing by the largest component first), whose results are unit to a few ulps:
    /// the pivot transformation of a cap whose axis points at a pivot near the unit
    /// sphere amplifies an axis's deviation from unit length a thousandfold (an axis
    /// `c / |c|` instead failed `occlusion_of_a_light_whose_image_is_nearly_the_whole_sphere`).
    #[inline]
    pub fn sanitized(self) -> Cap {
        if self.is_valid() {
            return self;
        }
        self.sanitized_slow()
    }

    #[inline(never)]
    fn sanitized_slow(self) -> Cap {
        let (t, h) = (self.one_minus_cos, self.one_plus_cos);
        // `2 − t` is exact for `t ∈ [1, 2]` (Sterbenz); NaN or infinite `h` fail the test.
        if t > 1.0 && t <= 2.0 && ((2.0 - t) - h).abs() <= 1.0 / 4_194_304.0 {
            return Cap::from_axis_one_plus_cos(self.axis, h.max(0.0).min(1.0));
        }
        Cap::from_axis_one_minus_cos(self.axis, t)
    }

    /// Whether this is not a cap at all: a non-finite or zero axis or a NaN
    /// `one_minus_cos`, exactly the input that [`Cap::sanitized`] turns into
    /// [`Cap::EMPTY`] for being invalid (a valid empty cap, `one_minus_cos = 0` about a
    /// finite axis, is a cap). Functions whose result for the empty set is not 0 (the
    /// integral over a complement or a union) report such input as 0 instead.
    #[inline]
    pub fn is_malformed(&self) -> bool {
        self.one_minus_cos.is_nan() || !self.axis.is_finite() || self.axis == Vec3::ZERO
    }

    /// `cos θ`, from the authoritative one of `1 ∓ cos θ` (exact for both).
    #[inline]
    pub fn cos(&self) -> f32 {
        if self.one_minus_cos <= 1.0 {
            1.0 - self.one_minus_cos
        } else {
            self.one_plus_cos - 1.0
        }
    }

    /// The half-angle `θ = 2 asin(√(t/2))` (accurate for tiny caps, unlike `acos`), and
    /// `π − 2 asin(√(h/2))` for caps wider than a hemisphere.
    #[inline]
    pub fn half_angle(&self) -> f32 {
        let half_chord =
            |x: f32| 2.0 * libm::asinf(crate::math::sqrtf((0.5 * x).max(0.0).min(1.0)));
        if self.one_minus_cos <= 1.0 {
            half_chord(self.one_minus_cos)
        } else {
            PI - half_chord(self.one_plus_cos)
        }
    }

    /// The complement `{ω : ω·axis < cos θ}`, up to its boundary circle (a set of
    /// measure zero): the cap around `−axis` with `1 ∓ cos` exchanged, so that both stay
    /// exact (Dupuy et al. 2017, Sec. 4: sets of caps). The empty cap and the whole
    /// sphere are each other's complement.
    #[inline]
    #[must_use]
    pub fn complement(&self) -> Cap {
        Cap {
            axis: -self.axis,
            one_minus_cos: self.one_plus_cos,
            one_plus_cos: self.one_minus_cos,
            sin2: self.sin2,
        }
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
        self.contains_inlined(dir)
    }

    /// [`Cap::contains`], always inlined: for the samplers' per-sample tests, where the
    /// call (its argument spilled to the stack, the cap's fields reloaded) cost as much
    /// as the test.
    #[inline(always)]
    pub(crate) fn contains_inlined(&self, dir: Vec3) -> bool {
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
        self.contains_unit(unit)
    }

    /// [`Cap::contains`] of a direction that `math::unit` returns as it is (`is_unit`):
    /// the same answer without the length test, for a caller that made it (several caps
    /// tested with one direction). Always inlined: it is a few operations, and the
    /// samplers call it per sample (out of line in `SptdInCap::sample`, measured).
    #[inline(always)]
    pub(crate) fn contains_unit(&self, unit: Vec3) -> bool {
        if !(self.one_minus_cos > 0.0) {
            return false;
        }
        if self.one_minus_cos >= 2.0 {
            return unit.is_finite() && unit != Vec3::ZERO;
        }
        if self.one_minus_cos > 1.0 {
            // Wider than a hemisphere: the boundary is near the antipode, where
            // `|ω − a|²/2` is close to 2 and has lost the absolute precision that the
            // excluded disk needs (found by fuzzing: a sample 2e-4 rad inside a cap with
            // `1 − cos θ = 2 − ulp` was outside). Compared in the complement instead:
            // `1 + ω·a = |ω + a|²/2 >= 1 + cos θ`, the stored hole.
            0.5 * (unit + self.axis).length_squared() >= self.one_plus_cos
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
        let (tangent, bitangent) = orthonormal_basis(self.axis);
        sample_uniform_in_frame(
            [self.axis.into(), tangent.into(), bitangent.into()],
            self.one_minus_cos,
            self.one_plus_cos,
            pdf,
            u,
        )
    }

    /// `1 / Ω`, or 0 when the cap is empty or `1/Ω` is not finite.
    #[inline]
    pub(crate) fn uniform_pdf(&self) -> f32 {
        if !(self.one_minus_cos > 0.0) {
            return 0.0;
        }
        let pdf = self.one_minus_cos_pdf();
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// `1 / Ω = 1 / (2π (1 − cos θ))` as it stands, unchecked: for a cap whose
    /// `1 − cos θ` is known to be normal.
    #[inline(always)]
    pub(crate) fn one_minus_cos_pdf(&self) -> f32 {
        1.0 / (TAU * self.one_minus_cos)
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
    /// `u₀ = (1 − dir·axis) / (1 − cos θ)`, `u₁ = φ / 2π`; `None` outside the cap. Past
    /// the hemisphere, `1 − u₀ = ((1 + dir·axis) − (1 + cos θ)) / (1 − cos θ)` from the
    /// complement (the inverse of the sampling's `h + (1 − u₀) t`).
    pub fn invert(&self, dir: Vec3) -> Option<[f32; 2]> {
        if !self.contains(dir) || self.uniform_pdf() == 0.0 {
            return None;
        }
        let t = self.one_minus_cos_of(dir)?;
        let u0 = if t > 1.0 {
            let unit = crate::math::unit(dir)?;
            let h = 0.5 * (unit + self.axis).length_squared();
            1.0 - (h - self.one_plus_cos).max(0.0) / self.one_minus_cos
        } else {
            t / self.one_minus_cos
        };
        let u0 = u0.max(0.0).min(ONE_MINUS_ULP);
        let (tangent, bitangent) = orthonormal_basis(self.axis);
        let mut phi = libm::atan2f(dir.dot(bitangent), dir.dot(tangent));
        if phi < 0.0 {
            phi += TAU;
        }
        let u1 = (phi * (0.5 / PI)).max(0.0).min(ONE_MINUS_ULP);
        Some([u0, u1])
    }
}

/// How far `|axis|²` may lie from 1 for [`sample_uniform_in_frame`] to take its
/// direction as unit without a Newton step: 3 ulps of 1 (3.6e-7). The caps of spheres
/// are within 2.5 (measured); with the sample's own rounding, `|dir|² − 1` stays below
/// 8e-7 for such axes, under the `UNIT_TOLERANCE` (1e-6) of `pdf`.
const UNIT_AXIS: f32 = 3.0 * f32::EPSILON;

/// [`Cap::sample_uniform`] of a non-empty cap `(axis, 1 − cos θ = t, 1 + cos θ = h)`
/// with its frame `[axis, tangent, bitangent]` (from [`orthonormal_basis`]) and its
/// density `pdf = 1/Ω` given: the body that [`SolidAngleSphere`](super::SolidAngleSphere)
/// runs with the frame and the density it prepared once. In `Vec3A` (four lanes, the
/// fourth ignored), which holds a vector that the prepared sampler loads 16 bytes at a
/// time without moving it.
#[inline(always)]
pub(crate) fn sample_uniform_in_frame(
    [axis, tangent, bitangent]: [Vec3A; 3],
    one_minus_cos: f32,
    one_plus_cos: f32,
    pdf: f32,
    u: [f32; 2],
) -> Sample {
    let u0 = clamp_random(u[0]);
    let t = u0 * one_minus_cos;
    // `1 + cos θ' = 2 − t'`; past the hemisphere (`t' > 1`, so `u₀ > 1/2` and
    // `1 − u₀` is exact) as `h + (1 − u₀) t`, which resolves a small hole.
    let (one_plus, cos) = if t > 1.0 {
        let h = one_plus_cos + (1.0 - u0) * one_minus_cos;
        (h, h - 1.0)
    } else {
        (2.0 - t, 1.0 - t)
    };
    let sin = crate::math::sqrtf((t * one_plus).max(0.0));
    let (sin_phi, cos_phi) = crate::math::sin_cos_of_turn(clamp_random(u[1]));
    let dir = tangent * (sin * cos_phi) + bitangent * (sin * sin_phi) + axis * cos;
    // `dir` is a unit vector to a few ulps when the axis is (the frame is orthonormal
    // around a unit axis, `sin² + cos² = 1`): every cap of a sphere, whose axis is
    // normalised here, and `dir` is then taken as it is (`|dir|² − 1` at most 4.8e-7
    // for spheres, 8e-7 for any axis within `UNIT_AXIS`, measured by
    // `samples_of_unit_axes_are_unit_without_the_newton_step`: within the
    // `UNIT_TOLERANCE` of 1e-6 by which `pdf` takes it as it is). A cap built by hand
    // may have `|axis|²` anywhere within `UNIT_TOLERANCE` of 1: there, one Newton step
    // for `1/√(|dir|²)` at 1, `(3 − |dir|²)/2`, leaves an error of `(3/8) ε²` for
    // `|dir|² = 1 + ε` (below 1e-12), without a square root or a division. The test
    // is on the axis, known before the sample, so it is predicted and not waited for.
    let dir = if (axis.length_squared() - 1.0).abs() <= UNIT_AXIS {
        dir
    } else {
        dir * (1.5 - 0.5 * dir.length_squared())
    };
    // `contains` for a unit `dir` (which it takes as it is) in a non-empty cap
    // (`pdf > 0`), without its checks.
    let inside = if one_minus_cos > 1.0 {
        0.5 * (dir + axis).length_squared() >= one_plus_cos
    } else {
        0.5 * (dir - axis).length_squared() <= one_minus_cos
    };
    if inside {
        return Sample {
            dir: dir.into(),
            pdf,
        };
    }
    let cap = Cap {
        axis: axis.into(),
        one_minus_cos,
        one_plus_cos,
        sin2: (one_minus_cos * one_plus_cos).max(0.0).min(1.0),
    };
    pulled_inside(&cap, dir.into(), pdf)
}

/// Rounding put a sample from the rim just outside (for small caps the rounding of a
/// unit vector, 6e-8, is a large part of the radius: 10 of 16 draws at u0 = 1 - 1e-5
/// for a 1e-7 sr cap), where `pdf` is 0 (issue 16, 4): pulled towards the axis until
/// inside (`INWARD_PULLS`; a cap below about 1e-6 rad, which `f32` directions do not
/// resolve, gets its axis). Rare: out of line.
#[cold]
#[inline(never)]
fn pulled_inside(cap: &Cap, dir: Vec3, pdf: f32) -> Sample {
    INWARD_PULLS
        .iter()
        .map(|&pull| crate::math::normalize_or(dir * (1.0 - pull) + cap.axis * pull, cap.axis))
        .find(|&pulled| cap.contains(pulled))
        .map_or(Sample::NONE, |dir| Sample { dir, pdf })
}

#[cfg(test)]
#[path = "cap_tests.rs"]
mod tests;
