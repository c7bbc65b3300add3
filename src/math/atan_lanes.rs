//! `libm::atanf` in four lanes, bit for bit and without branches (issues 15, 4 and 18).
//!
//! The exact samplers keep `libm::atanf` (0.85 ulp; fitted replacements made the
//! report's accuracy worse, see [`atan2_upper_half_plane`](super::atan2_upper_half_plane)).
//! Its algorithm (Sun's fdlibm `s_atanf.c`, as FreeBSD and the `libm` crate have it) is
//! a range reduction chosen by comparing `|x|` with 7/16, 11/16, 19/16 and 39/16, then
//! one polynomial for every range: branches that random geometry mispredicts, and one
//! lane at a time. Every step is a single correctly rounded `f32` operation (no fused
//! multiply-add: Rust never contracts `a * b + c`), so the same operations done in four
//! lanes give the same bits in each lane; what differs per range becomes a per-lane
//! constant chosen by the comparisons, in a form whose operations round exactly as the
//! scalar ones do (argued below step by step, and tested over every `f32`).
//!
//! The algorithm, with `a = |x|` and `atan(-x) = -atan(x)`:
//! - `a < 2^-12`: `atan x = x` (the cubic term is below half an ulp); ±0, subnormals.
//! - `a < 7/16`: `atan a = a - a·S(a²)` with `S(z) = z(T₀ + T₂w + T₄w²) + w(T₁ + T₃w)`,
//!   `w = z²` (odd and even terms apart, two short Horner chains).
//! - otherwise `atan a = atan c + atan t` with `t = (a - c)/(1 + c·a)` (the tangent's
//!   subtraction formula) for `c` = 1/2, 1 and 3/2 below 11/16, 19/16 and 39/16, and
//!   `atan a = π/2 + atan t` with `t = -1/a` above (`c = ∞`); `|t| <= 7/16` in every
//!   range. `atan c` is a two-float `hi + lo` (`hi` rounded, `lo` its remainder) and
//!   the sum is `hi - ((t·S(t²) - lo) - t)`, so that the small terms meet before `hi`.
//! - `a >= 2^26` (and ∞): the `f32` nearest π/2 from below, `hi` of `atan ∞`.

use glam::Vec4;

/// `atan(1/2)`, `atan(1)`, `atan(3/2)` and `atan(∞) = π/2`, rounded to `f32` (fdlibm's
/// `atanhi`; bit patterns `0x3eed6338`, `0x3f490fda`, `0x3f7b985e`, `0x3fc90fda`).
#[allow(clippy::excessive_precision)] // the f32 values as fdlibm prints them
pub(super) const ATAN_HI: [f32; 4] = [
    4.636_476_039_9e-1,
    7.853_981_256_5e-1,
    9.827_936_887_7e-1,
    1.570_796_251_3,
];

/// The remainders `atan c - ATAN_HI` (fdlibm's `atanlo`; `0x31ac3769`, `0x33222168`,
/// `0x33140fb4`, `0x33a22168`).
#[allow(clippy::excessive_precision)]
pub(super) const ATAN_LO: [f32; 4] = [
    5.012_158_244_0e-9,
    3.774_894_707_9e-8,
    3.447_321_717_0e-8,
    7.549_789_415_9e-8,
];

/// fdlibm's `aT` for `atanf`: `atan t = t - t·S(t²)` on `|t| <= 7/16` with
/// `S(z) = Σ T_i z^(i+1)` (its relative error is below 2^-23 there).
#[allow(clippy::excessive_precision)]
pub(super) const T: [f32; 5] = [
    3.333_332_836_6e-1,
    -1.999_915_838_2e-1,
    1.425_363_570_5e-1,
    -1.064_801_737_7e-1,
    6.168_760_731_8e-2,
];

/// `libm::atanf` of each lane, the same bits in every lane for every `f32` (±0,
/// subnormals, ±∞; NaN in gives a NaN out, not necessarily the same one): tested over
/// all 2^32 inputs by `exhaustive_atanf4_is_libm_atanf`, ignored by `cargo test` and run
/// by `.ci/run`.
///
/// No branch and no final choice between fdlibm's cases: the reductions are one
/// `t = (a·k - c)/(k + c·a)` with per-lane constants `k` (0 or 1) and `c`; one division
/// for the four lanes; the tiny and huge arguments go through the same operations, which
/// give fdlibm's results there exactly (argued below). About 80 SSE2 instructions for
/// four lanes, where the scalar form costs about 35 a lane and mispredicts its range
/// branches for random arguments.
///
/// Under flush-to-zero and denormals-are-zero (which a renderer may set) a subnormal
/// argument reads as 0 and gives ±0 where fdlibm returns it unchanged.
#[inline(always)]
#[must_use]
pub fn atanf4(x: Vec4) -> Vec4 {
    let a = x.abs();
    // fdlibm's ranges, where it compares the bit pattern of `|x|`: as comparisons of
    // `f32` the same for every non-NaN lane (for NaN all are false).
    let at_least = |bound: f32| a.cmpge(Vec4::splat(bound));
    let (from_7_16, from_11_16) = (at_least(0.4375), at_least(0.6875));
    let (from_19_16, from_39_16) = (at_least(1.1875), at_least(2.4375));
    let huge = at_least(67_108_864.0); // 2^26
    // One mask per reduced range, disjoint.
    let around_half = from_7_16 & !from_11_16;
    let around_one = from_11_16 & !from_19_16;
    let around_three_halves = from_19_16 & !from_39_16;
    let large = from_39_16 & !huge;
    // The range's value `v` in its lanes and 0 elsewhere; the sums below have exactly
    // one non-zero term in each lane (`v + 0 = v`, `0 + 0 = +0`), so they are exact.
    let pick = |range, v: f32| Vec4::select(range, Vec4::splat(v), Vec4::ZERO);
    let one_of = |values: [f32; 4], last_range| {
        (pick(around_half, values[0]) + pick(around_one, values[1]))
            + (pick(around_three_halves, values[2]) + pick(last_range, values[3]))
    };
    // `c` = 0 below 7/16, then 1/2, 1, 3/2, and 1 from 39/16 (see `t`).
    let c = one_of([0.5, 1.0, 1.5, 1.0], from_39_16);
    // `k = 0` from 39/16 (the mask clears `a` and 1 there), else 1.
    let k_a = Vec4::select(from_39_16, Vec4::ZERO, a);
    let k = Vec4::select(from_39_16, Vec4::ZERO, Vec4::ONE);
    // `t = (k·a - c)/(k + c·a)`, rounding as fdlibm's form of each range:
    // - below 7/16, `c = 0`: `a - 0 = a` and `1 + 0·a = 1`, so `t = a/1 = a` exactly;
    // - 7/16 to 11/16: fdlibm's `(2a - 1)/(2 + a)`; here numerator and denominator are
    //   both halved before rounding (`a - 1/2` exact by Sterbenz as `2a - 1` is, and
    //   `round(1 + a/2) = round(2 + a)/2`, halving an `f32` at least 1 being exact), so
    //   the quotient is the same real number, rounded once the same way;
    // - 11/16 to 19/16: fdlibm's `(a - 1)/(a + 1)`, `1·a` exact and the sum commutative;
    // - 19/16 to 39/16: fdlibm's `(a - 1.5)/(1 + 1.5a)` as written;
    // - from 39/16, fdlibm's `-1/a`: `0 - 1 = -1` over `0 + 1·a = a`, exact (also for
    //   `a = ∞`: `t = -0`).
    let t = (k_a - c) / (k + c * a);
    let t_s = t_times_s(t);
    // `atan c` as `hi + lo` per range, both 0 below 7/16. From 2^26 on, `lo = 0` (below).
    // (Chosen after the polynomial, in the order of fdlibm's source: chosen before it, the
    // projected prepare took 10 to 12 instructions more per hexagon, callgrind.)
    let hi = one_of(ATAN_HI, from_39_16);
    let lo = one_of(ATAN_LO, large);
    reduced_atan(t, t_s, hi, lo, x)
}

/// [`atanf4`] for arguments below 7/16 in magnitude (the others give unspecified values):
/// there `atanf4` reduces to `t = a` and `hi = lo = 0` exactly (see there), and this is
/// its tail on those very values, so the same bits, without the comparisons, selections
/// and the division of the reduction (tested against `libm::atanf` below 7/16). For
/// callers whose arguments are mostly that small and that test for it (a branch: the
/// reduction's division is on the critical path).
#[inline(always)]
#[must_use]
pub fn atanf4_below_7_16(x: Vec4) -> Vec4 {
    let a = x.abs();
    reduced_atan(a, t_times_s(a), Vec4::ZERO, Vec4::ZERO, x)
}

/// fdlibm's `t·S(t²)` with `S = s1 + s2`, its polynomial as it is written there (the
/// same operations, the same order).
#[inline(always)]
fn t_times_s(t: Vec4) -> Vec4 {
    let z = t * t;
    let w = z * z;
    let s1 = z * (Vec4::splat(T[0]) + w * (Vec4::splat(T[2]) + w * Vec4::splat(T[4])));
    let s2 = w * (Vec4::splat(T[1]) + w * Vec4::splat(T[3]));
    t * (s1 + s2)
}

/// The tail of [`atanf4`] from the reduced argument `t`, `t_s = t·S(t²)`
/// ([`t_times_s`]) and `atan c = hi + lo`: fdlibm's `hi - ((t·S - lo) - t)` with the sign
/// of `x`.
#[inline(always)]
fn reduced_atan(t: Vec4, t_s: Vec4, hi: Vec4, lo: Vec4, x: Vec4) -> Vec4 {
    // fdlibm's `hi - ((t·S - lo) - t)` with `S = s1 + s2`. Where fdlibm does otherwise:
    // - 2^-12 to 7/16 fdlibm computes `a - a·S`; with `hi = lo = 0` this is
    //   `0 - ((a·S - 0) - a)`: `a·S - 0 = a·S` (positive, at least about 2^-38, no zero
    //   whose sign could change), and `0 - (p - a)` is `-(p - a)`, the same rounding as
    //   `a - p` (round to nearest is symmetric), not zero as `p < a`;
    // - below 2^-12 fdlibm returns `a`; here `p = a·S`, at most `a·a²/3`, a relative
    //   2^-25.6 of `a`, less than half an ulp of `a` (a relative 2^-25 at least, and
    //   `p` is under a quarter ulp where `a` is a power of two and `a - p` falls into the
    //   binade below), so `p - a` rounds to `-a` and the result is `a` exactly; for
    //   subnormal `a`, `p` is 0, and for `a = 0` every term is +0, so the result is +0;
    // - from 2^26 on (and ∞) fdlibm returns `hi` of `atan ∞`: here `t = -1/a` is at most
    //   2^-26 in magnitude and `lo = 0`, so `(t·S - 0) - t` is positive and below 2^-26
    //   (0 for `a = ∞`), less than half an ulp of `hi` (2^-24), and `hi` minus it rounds
    //   to `hi`.
    let positive = hi - ((t_s - lo) - t);
    // Odd: `positive` has a clear sign bit in every lane (+0 at most), so taking `x`'s
    // sign is fdlibm's negation for negative `x` (and returns -0 for -0); its odd form
    // below 7/16, `x - x·S(x²)` with `x` negative, is the negation of the one for `|x|`
    // (symmetric rounding).
    positive.copysign(x)
}

#[cfg(test)]
mod tests {
    use super::super::test_sweep::{points, sweep};
    use super::*;
    use crate::testing::Rng;
    use std::vec::Vec;

    /// `atanf4` of the four `f32` with these bit patterns against `libm::atanf`, bit for
    /// bit (a NaN lane only needs a NaN).
    fn assert_lanes_are_libm(bits: [u32; 4]) {
        let x = bits.map(f32::from_bits);
        let got = atanf4(Vec4::from_array(x)).to_array();
        for lane in 0..4 {
            let expected = libm::atanf(x[lane]);
            assert!(
                got[lane].to_bits() == expected.to_bits()
                    || (expected.is_nan() && got[lane].is_nan()),
                "atanf4({:e} = {:#010x}) = {:#010x}, libm::atanf gives {:#010x}",
                x[lane],
                bits[lane],
                got[lane].to_bits(),
                expected.to_bits()
            );
        }
    }

    /// The inputs where fdlibm's form changes and their neighbours: the range
    /// thresholds 2^-12, 7/16, 11/16, 19/16, 39/16, 2^26 and ∞ ±4 ulps, both signs;
    /// signed zeros, the smallest and largest subnormals, the smallest normal; and the
    /// points where the reduced argument is 0 (1/2, 1, 3/2).
    fn special_bits() -> Vec<u32> {
        let mut bits = Vec::new();
        for threshold in [
            1.0f32 / 4096.0,
            0.4375,
            0.6875,
            1.1875,
            2.4375,
            67_108_864.0,
            f32::INFINITY,
            0.5,
            1.0,
            1.5,
            f32::MIN_POSITIVE,
        ] {
            for offset in -4i32..=4 {
                let b = threshold.to_bits() as i32 + offset;
                bits.push(b as u32);
                bits.push(b as u32 | 0x8000_0000);
            }
        }
        for b in [0, 1, 2, 0x007f_ffff, 0x7fc0_0000, 0x7fff_ffff, 0x7f80_0001] {
            bits.push(b);
            bits.push(b | 0x8000_0000);
        }
        bits
    }

    /// The normal suite's check: the special inputs in every lane position, a few
    /// million random bit patterns, and dense runs around every threshold.
    #[test]
    fn atanf4_is_libm_atanf_on_special_and_random_inputs() {
        let special = special_bits();
        for (i, &b) in special.iter().enumerate() {
            let other = special[(i * 7 + 3) % special.len()];
            assert_lanes_are_libm([b, other, b ^ 0x8000_0000, 0x3f00_0000]);
            assert_lanes_are_libm([other, b, 0, b]);
        }
        let mut rng = Rng::new(18);
        for _ in 0..1_000_000 {
            let r = rng.next_u64();
            assert_lanes_are_libm([
                r as u32,
                (r >> 32) as u32,
                // Mostly in the reduction's ranges: exponents of 2^-13 to 2^27.
                0x3900_0000 + (r as u32 % 0x1400_0000),
                (0x3900_0000 + ((r >> 32) as u32 % 0x1400_0000)) | 0x8000_0000,
            ]);
        }
        // 2^16 consecutive patterns on either side of each threshold.
        for threshold in [0.4375f32, 0.6875, 1.1875, 2.4375] {
            let b = threshold.to_bits();
            for first in (b - (1 << 16)..b + (1 << 16)).step_by(4) {
                assert_lanes_are_libm([first, first + 1, first + 2, first + 3]);
            }
        }
    }

    /// `atanf4_below_7_16` is `libm::atanf` below 7/16 in magnitude (its domain): every
    /// 61st bit pattern from 0 up to the last `f32` below 7/16, in both signs and in
    /// every lane position.
    #[test]
    fn atanf4_below_7_16_is_libm_atanf_below_7_16() {
        let last = 0.4375f32.next_down();
        let check = |x: [f32; 4]| {
            let got = atanf4_below_7_16(Vec4::from_array(x)).to_array();
            for lane in 0..4 {
                assert_eq!(
                    got[lane].to_bits(),
                    libm::atanf(x[lane]).to_bits(),
                    "{:e} ({:#x})",
                    x[lane],
                    x[lane].to_bits()
                );
            }
        };
        sweep(0, last.to_bits(), 61, |first, end, step| {
            for (i, t) in points(first, end, step).enumerate() {
                let other = [last, -0.0, f32::from_bits(1), -1e-3][i % 4];
                check([t, -t, other, t]);
                check([other, t, -t, -t]);
            }
        });
    }

    /// `atanf4_below_7_16` is `libm::atanf` for every `f32` below 7/16 in magnitude (its
    /// domain), both signs, four at a time (each lane position takes every fourth
    /// pattern): 2.1e9 evaluations of both, ignored by `cargo test`; `.ci/run` runs it
    /// with the other exhaustive tests.
    #[test]
    #[ignore]
    fn exhaustive_atanf4_below_7_16_is_libm_atanf() {
        let end = 0.4375f32.to_bits(); // exclusive; a multiple of 4
        sweep(0, end - 1, 1 << 16, |first, last, step| {
            for start in (first..=last).step_by(step as usize) {
                for b in (start..start + step).step_by(4) {
                    for sign in [0, 0x8000_0000u32] {
                        let lanes = [b, b + 1, b + 2, b + 3].map(|b| b | sign);
                        let got = atanf4_below_7_16(Vec4::from_array(lanes.map(f32::from_bits)));
                        let expected = lanes.map(|b| libm::atanf(f32::from_bits(b)).to_bits());
                        assert_eq!(got.to_array().map(f32::to_bits), expected, "{lanes:#x?}");
                    }
                }
            }
        });
    }

    /// Every `f32` bit pattern, four at a time: 2^32 evaluations of both forms, about
    /// 40 s of one core (measured; `sweep` uses every core) after the release build, so
    /// ignored by `cargo test`; `.ci/run` runs it with the other exhaustive tests (its
    /// name starts with `exhaustive`).
    #[test]
    #[ignore]
    fn exhaustive_atanf4_is_libm_atanf() {
        sweep(0, u32::MAX, 1 << 20, |first, last, step| {
            for start in (first..=last).step_by(step as usize) {
                // A block of `step` patterns (a multiple of 4) from `start`.
                for b in (start..=start + (step - 1)).step_by(4) {
                    let lanes = [b, b + 1, b + 2, b + 3];
                    let got = atanf4(Vec4::from_array(lanes.map(f32::from_bits)));
                    let expected = lanes.map(|b| libm::atanf(f32::from_bits(b)).to_bits());
                    // Equal bits in all four lanes, the common case, checked at once;
                    // the careful check (NaN lanes, the message) otherwise.
                    if got.to_array().map(f32::to_bits) != expected {
                        assert_lanes_are_libm(lanes);
                    }
                }
            }
        });
    }
}
