//! Every normalisation of the library, in one place (issue 19, 5): direction arguments
//! as unit vectors ([`unit`], the one normalisation that every function taking a
//! direction goes through, issue 17, 5), a sampler's computed directions
//! ([`unit_if_needed`], with its own tolerance), and the zero-or-unit form
//! ([`normalize_scaled`]); all three share [`normalize_by_largest`].
//!
//! `v / |v|` computed directly fails at both ends of the range: `|v|²` overflows to
//! infinity for components from about `1.8e19` on, and underflows to zero, or into
//! denormals with few significant bits, for components below about `1e-19` (found by
//! fuzzing and by an acceptance suite: views of length `1e20` and directions of length
//! `2⁻¹⁰⁰` and `2⁻¹⁴⁰` were rejected, and a `5e-22` view normalised to length 0.99986).
//! Dividing by the largest absolute component first is exact up to one rounding per
//! component and leaves a vector whose largest component is 1, so `|v|² ∈ [1, 3]`.

use glam::Vec3;

/// How far `|v|²` may lie from 1 for [`unit`] to take `v` as a unit vector unchanged. A
/// direction normalised in `f32` has `|v|²` within a few ulps (~4e-7) of 1; taking such
/// a vector as it is (instead of normalising it again) makes [`unit`] idempotent, so
/// that a sampler's returned direction evaluates to bit-identical densities when it is
/// passed back to `pdf`.
pub(crate) const UNIT_TOLERANCE: f32 = 1e-6;

/// `v / |v|` for a non-zero finite `v`, `None` otherwise: `v` is divided by its largest
/// absolute component first, so that neither `|v|²` overflows for huge vectors nor
/// underflows for tiny (even subnormal) ones, then multiplied by `1/|v|`. A vector and
/// its multiples by powers of two give the same result, bit for bit.
#[inline(always)]
pub(crate) fn normalize_by_largest(v: Vec3) -> Option<Vec3> {
    let largest = v.abs().max_element();
    if !v.is_finite() || !(largest > 0.0) {
        return None;
    }
    let scaled = v / largest;
    Some(scaled * (1.0 / crate::math::sqrtf(scaled.length_squared())))
}

/// A direction argument as a unit vector: `v` itself when `|v|²` lies within
/// [`UNIT_TOLERANCE`] of 1, [`normalize_by_largest`] otherwise; `None` for a zero or
/// non-finite `v`.
#[inline(always)]
pub(crate) fn unit(v: Vec3) -> Option<Vec3> {
    if is_unit(v) {
        return Some(v);
    }
    normalize_by_largest(v)
}

/// Whether [`unit`] takes `v` as it is: `| |v|² - 1 | <= UNIT_TOLERANCE`. False for
/// NaN components (the comparison fails) and infinite ones (`|v|² = inf`).
#[inline(always)]
pub(crate) fn is_unit(v: Vec3) -> bool {
    (v.length_squared() - 1.0).abs() <= UNIT_TOLERANCE
}

/// The tolerance of [`unit_if_needed`] for a sampler's own output: 2e-6, twice
/// [`UNIT_TOLERANCE`] (an argument's), as a computed direction carries a few more
/// roundings than one a caller normalised.
// The definition of the tolerance: the code tests the bits of its interval
// (`OUTPUT_UNIT_LOW`, `OUTPUT_UNIT_HIGH`), the tests compare the two.
#[cfg_attr(not(test), allow(dead_code))]
const OUTPUT_UNIT_TOLERANCE: f32 = 2e-6;

/// `dir` unchanged when `| |dir|² - 1 | <= 2e-6` (every direction a sampler computes
/// accurately, bit for bit), otherwise `dir / |dir|` by the shared helper
/// [`normalize_by_largest`] (scaled by its largest component first so that
/// the squares neither underflow into denormals nor overflow); a zero or non-finite
/// `dir` comes back non-finite, for the caller's "no sample" test. The samplers use it
/// where an ill-conditioned construction can lose the unit length (found by fuzzing;
/// see the callers).
#[inline(always)]
pub(crate) fn unit_if_needed(dir: Vec3) -> Vec3 {
    unit_if_needed_or_none(dir).unwrap_or(Vec3::NAN)
}

/// [`unit_if_needed`] with `None` for a zero or non-finite `dir`: a caller that returns
/// "no sample" then needs no finiteness test on the common path (a `dir` that passes the
/// length test is finite, as NaN and infinite lengths fail it).
#[inline(always)]
pub(crate) fn unit_if_needed_or_none(dir: Vec3) -> Option<Vec3> {
    if is_unit_output(dir) {
        return Some(dir);
    }
    normalize_by_largest(dir)
}

/// Whether [`unit_if_needed`] returns `dir` unchanged: `| |dir|² - 1 | <= 2e-6` (false
/// for non-finite `dir`). For the samplers' common paths, which leave the other
/// directions to their rare path.
#[inline(always)]
pub(crate) fn is_unit_output(dir: Vec3) -> bool {
    is_unit_output_length_squared(dir.length_squared())
}

/// The bit patterns of the smallest and the largest `f32` `x` with
/// `|x - 1| <= OUTPUT_UNIT_TOLERANCE`: 1 - 1.967e-6 and 1 + 1.907e-6 (one ulp of 1 below
/// is 2^-24, above 2^-23; `output_unit_interval_is_the_tolerance` finds them again).
const OUTPUT_UNIT_LOW: u32 = 0x3F7F_FFDF;
const OUTPUT_UNIT_HIGH: u32 = 0x3F80_0010;

/// `| x - 1 | <= OUTPUT_UNIT_TOLERANCE` for `x = |dir|²`, as a range test on the bits:
/// for `x` in `[0.5, 2]` the difference `x - 1` is exact (Sterbenz), so the test holds
/// exactly for the `f32` from [`OUTPUT_UNIT_LOW`] to [`OUTPUT_UNIT_HIGH`], and it fails
/// everywhere else (`|x - 1| >= 0.5`, NaN). Non-negative floats are ordered as their
/// bits are, so one wrapping subtraction and one unsigned comparison decide it: bits
/// below the low end wrap around to huge values, and negative `x` (the sign bit) and
/// NaN (above +∞) lie above the high end. The same predicate as the subtraction, the
/// absolute value and the comparison (tested for every `f32`), with two operations fewer
/// after `|dir|²`: the test ends a sampler's chain of dependent operations, and the
/// sample's instructions cannot retire before it.
#[inline(always)]
pub(crate) fn is_unit_output_length_squared(x: f32) -> bool {
    x.to_bits().wrapping_sub(OUTPUT_UNIT_LOW) <= OUTPUT_UNIT_HIGH - OUTPUT_UNIT_LOW
}

/// `v / |v|` by the shared helper [`normalize_by_largest`] (tiny vectors,
/// whose squares are denormal, e.g. 5e-22, and huge ones normalise to full precision);
/// zero for a zero or non-finite `v` (found by fuzzing: a view or phase direction of
/// length 5e-22 normalised to length 0.99986).
#[inline(always)]
pub(crate) fn normalize_scaled(v: Vec3) -> Vec3 {
    normalize_by_largest(v).unwrap_or(Vec3::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `is_unit_output_length_squared` is `(x - 1).abs() <= OUTPUT_UNIT_TOLERANCE` for
    /// every `f32` bit pattern (NaN, infinities, negative values and subnormals
    /// included).
    #[test]
    fn output_unit_interval_is_the_tolerance() {
        let reference = |x: f32| (x - 1.0).abs() <= OUTPUT_UNIT_TOLERANCE;
        // Every pattern from 0.25 to 4 (where the test can hold, and around), then a
        // stride through all of them.
        let (low, high) = (0.25f32.to_bits(), 4.0f32.to_bits());
        let mut inside = 0u32;
        for bits in low..=high {
            let x = f32::from_bits(bits);
            assert_eq!(is_unit_output_length_squared(x), reference(x), "{x:e}");
            inside += reference(x) as u32;
        }
        // The interval's ends: 33 patterns below 1 and 17 from 1 up.
        assert_eq!(inside, OUTPUT_UNIT_HIGH - OUTPUT_UNIT_LOW + 1);
        assert!(reference(f32::from_bits(OUTPUT_UNIT_LOW)));
        assert!(!reference(f32::from_bits(OUTPUT_UNIT_LOW - 1)));
        assert!(reference(f32::from_bits(OUTPUT_UNIT_HIGH)));
        assert!(!reference(f32::from_bits(OUTPUT_UNIT_HIGH + 1)));
        for bits in (0..=u32::MAX).step_by(4099).chain([u32::MAX, 0x8000_0000]) {
            let x = f32::from_bits(bits);
            assert_eq!(is_unit_output_length_squared(x), reference(x), "{bits:#x}");
        }
        for x in [
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            -f32::INFINITY,
            -1.0,
            -0.0,
            0.0,
        ] {
            assert_eq!(is_unit_output_length_squared(x), reference(x), "{x}");
        }
    }

    #[test]
    fn unit_normalises_rejects_and_is_idempotent() {
        assert_eq!(unit(Vec3::ZERO), None);
        assert_eq!(unit(Vec3::new(f32::NAN, 0.0, 1.0)), None);
        assert_eq!(unit(Vec3::new(0.0, f32::INFINITY, 1.0)), None);
        assert_eq!(unit(Vec3::new(0.0, 0.0, f32::NEG_INFINITY)), None);
        assert_eq!(normalize_by_largest(Vec3::new(f32::NAN, 0.0, 1.0)), None);
        for v in [
            Vec3::new(3.0, -4.0, 12.0),
            Vec3::new(1e30, 2e30, -2e30),
            Vec3::new(1e-40, 0.0, 1e-40),
            Vec3::new(f32::MAX, f32::MAX, f32::MAX),
        ] {
            let u = unit(v).unwrap();
            assert!((u.length() - 1.0).abs() < 1e-6, "{v} -> {u}");
            assert!(u.dot(v) > 0.0);
            assert_eq!(unit(u), Some(u), "not idempotent for {v}");
        }
    }
}
