//! Arc tangents of arguments whose sign is known.
//!
//! `atan2` spends most of its time on quadrant logic. Where the caller knows that the
//! sine-like argument is non-negative (solid angles by van Oosterom and Strackee, sector
//! areas in Peters 2021, supplement A.7), one `atan` of a non-negative ratio suffices.

use super::fast_functions_generated::ATAN_UNIT;
use super::horner;
use core::f32::consts::FRAC_PI_2;

/// `atan2(y, x)` for `y >= 0`, in `[0, π]`, built from one `atan` of a non-negative
/// ratio no larger than one in magnitude where it matters:
/// `x > 0`: `atan(y / x)`; otherwise `π/2 + atan(-x / y)`.
///
/// Both ratios are computed with one rounding, and `atan` has condition number at most
/// one, so the result is as accurate as the library `atan` (below 0.85 ulp over `[0, 1]`,
/// measured). Returns 0 for `y == x == 0` and for NaN input, so that degenerate geometry
/// never yields NaN.
///
/// This stays on `libm::atanf` (issue 15, 4): with the fitted [`atan_unit`] in its place
/// (1.12 ulps; 0.9 with an argument reduction to `|r| <= 0.44` and two-float constants),
/// the largest relative error of Φ per decade in the side-by-side accuracy table of docs/polygon-lights.md
/// grew from 2.3e-7 to 2.9e-7 at 1 sr and from 8.8e-7 to 9.8e-7 at 0.1 sr (sums and
/// differences of sector areas, whose arc tangents' errors then add), and the
/// solid-angle maximum near the hemisphere from 1.4e-7 to 1.5e-7. The issue asks for no
/// accuracy figure to get worse; `atanf` costs about 30 instructions a call.
#[inline(always)]
pub fn atan2_upper_half_plane(y: f32, x: f32) -> f32 {
    let angle = if x > 0.0 {
        atanf(y / x)
    } else {
        FRAC_PI_2 + atanf(-x / y)
    };
    // 0/0 and NaN inputs give NaN, mapped to 0, as are -0 (from `y = -0`) and negative
    // angles (from a negative `y`). An explicit comparison rather than `angle.max(0.0)`,
    // whose result for `-0` IEEE maxNum leaves open (x86-64 compiled that `max` into
    // this very comparison, `maxss`; the lanes of `atan2_upper_half_plane4` use it too).
    if angle > 0.0 { angle } else { 0.0 }
}

/// `libm::atanf(x)`, the same bits for every `f32`, inline over its whole range (Sun's
/// fdlibm `s_atanf.c`, the form and the constants of [`atanf4`](super::atanf4), whose
/// module states the algorithm). fdlibm's range `2^-12 <= |x| < 7/16` comes first: there
/// `atanf` computes `x - x·S(x²)` (no reduction), and that range is tested the way
/// fdlibm tests it, one unsigned comparison of the bits of `|x|`, so the small ratios of
/// small solid angles (a fan triangle below 0.82 sr) take one branch; the others
/// ([`atanf_outside_small`]) follow fdlibm's branches. Inline throughout (issue 15): the
/// call of `libm::atanf` for the other ranges, its return and its tests for the huge and
/// tiny ranges before the small one cost those arguments about 37 instructions. Tested
/// against `libm::atanf` over every `f32` (`exhaustive_inline_atanf_is_libm_atanf`) and,
/// by `cargo test`, its ranges' ends and every 61st `f32` of the small range
/// (`inline_atanf_is_libm_atanf`).
#[inline(always)]
pub fn atanf(x: f32) -> f32 {
    let magnitude = x.to_bits() & 0x7fff_ffff;
    // 2^-12 (0x3980_0000) <= |x| < 7/16 (0x3ee0_0000), as fdlibm decides its ranges.
    if magnitude.wrapping_sub(0x3980_0000) < 0x3ee0_0000 - 0x3980_0000 {
        x - t_times_s(x)
    } else {
        atanf_outside_small(x, magnitude)
    }
}

/// fdlibm's `t·S(t²)` with `S = s1 + s2` (its polynomial `aT` as written there: the odd
/// and even terms apart, the same operations in the same order; the scalar form of
/// `atan_lanes`' `t_times_s`).
#[inline(always)]
fn t_times_s(t: f32) -> f32 {
    let c = &super::atan_lanes::T;
    let z = t * t;
    let w = z * z;
    let s1 = z * (c[0] + w * (c[2] + w * c[4]));
    let s2 = w * (c[1] + w * c[3]);
    t * (s1 + s2)
}

/// [`atanf`] for `|x|` (whose bits, sign cleared, are `magnitude`) outside
/// `2^-12 <= |x| < 7/16`: fdlibm's other ranges in its order, each step its operation.
/// - `|x| < 2^-12` (zeros, subnormals): `x` (the cubic term is below half an ulp);
/// - `|x| >= 2^26`: NaN as it came, else `±(atan(∞)_hi + 2^-120)`, the `f32` below π/2
///   (the addition is fdlibm's way of raising the inexact flag; its sum rounds to `hi`);
/// - otherwise `atan |x| = atan c + atan t`, `t` by the tangent's subtraction formula for
///   `c` = 1/2, 1, 3/2 below 11/16, 19/16, 39/16 (fdlibm's forms `(2a - 1)/(2 + a)`,
///   `(a - 1)/(a + 1)`, `(a - 1.5)/(1 + 1.5a)`), and `t = -1/a` above (`c = ∞`), summed as
///   `hi - ((t·S(t²) - lo) - t)` with `atan c = hi + lo`, then the sign of `x`.
#[inline]
fn atanf_outside_small(x: f32, magnitude: u32) -> f32 {
    use super::atan_lanes::{ATAN_HI, ATAN_LO};
    let negative = x.is_sign_negative();
    if magnitude < 0x3980_0000 {
        return x;
    }
    if magnitude >= 0x4c80_0000 {
        if x.is_nan() {
            return x;
        }
        let z = ATAN_HI[3] + f32::from_bits(0x0380_0000);
        return if negative { -z } else { z };
    }
    let a = f32::from_bits(magnitude);
    let (t, range) = if magnitude < 0x3f98_0000 {
        if magnitude < 0x3f30_0000 {
            ((2.0 * a - 1.0) / (2.0 + a), 0)
        } else {
            ((a - 1.0) / (a + 1.0), 1)
        }
    } else if magnitude < 0x401c_0000 {
        ((a - 1.5) / (1.0 + 1.5 * a), 2)
    } else {
        (-1.0 / a, 3)
    };
    let z = ATAN_HI[range] - ((t_times_s(t) - ATAN_LO[range]) - t);
    if negative { -z } else { z }
}

/// `atan(t)` for `t` in `[0, 1]`: `t + t³ P(t²)` with the degree-8 polynomial `P`
/// fitted for relative error by `tools/src/fitters/fast_function_fitter.rs` (relative minimax
/// error of the `f32` coefficients 2.7e-9, a fortieth of `f32::EPSILON`), evaluated by
/// Horner's rule in `f32`. Adding the correction `t³ P(t²)` (at most 22 % of the result)
/// to the exact `t` last keeps the final rounding the dominant one.
///
/// Measured over every `f32` in `[0, 1]` (the exhaustive test below): at most 1.12 ulps
/// of the correctly rounded value, relative error at most 8.8e-8; `atan_unit(0) = 0`,
/// `atan_unit(t) = t` for `t` below 2^-12; `atan_unit(1)` is the `f32` below `f32` π/4
/// (0.63 ulp below π/4). Monotone but
/// for 124 steps from one `f32` to the next, each down by one ulp (where a step of `t`
/// raises `atan` by less than an ulp, rounding noise of about an ulp can exceed it). No fused multiply-add is used (Rust never contracts
/// `a * b + c`), so `+fma` builds give the same bits. Outside `[0, 1]` the result is
/// unspecified (finite for finite input up to about 1e4).
///
/// The exact samplers keep `libm::atanf` (see [`atan2_upper_half_plane`] for the
/// measurement); this is for callers whose budget allows 1.12 ulps.
#[inline(always)]
pub fn atan_unit(t: f32) -> f32 {
    let s = t * t;
    t + (t * s) * horner(s, &ATAN_UNIT)
}

/// [`atan_unit`]'s polynomial by Estrin's scheme instead of Horner's rule, for callers
/// whose arc tangent is on the critical path (the real-time shading's lens, issue 18, 1):
/// with `s = t²`, `s₂ = s²`, `s₄ = s₂²`, the pairs `c₂ᵢ + c₂ᵢ₊₁ s` and their
/// combinations are independent, so the chain is 6 multiply–add levels instead of 9.
/// Different rounding from [`atan_unit`]: over every 61st `f32` of `[0, 1]` (the test
/// below) at most 1.05 ulps and a relative error of at most 8.3e-8 (asserted: 1.1 and
/// 8.5e-8); `t` for `t` below 2^-12 and 0 at 0 as there.
#[inline(always)]
pub fn atan_unit_estrin(t: f32) -> f32 {
    let c = &ATAN_UNIT;
    let s = t * t;
    let s2 = s * s;
    let s4 = s2 * s2;
    let low = (c[0] + c[1] * s) + (c[2] + c[3] * s) * s2;
    let high = (c[4] + c[5] * s) + (c[6] + c[7] * s) * s2;
    let p = low + (high + c[8] * s4) * s4;
    t + (t * s) * p
}

/// [`atan_unit_estrin`] in each of four lanes: the same operations in the same order, so
/// every lane gives [`atan_unit_estrin`]'s bits (tested); for the real-time shading's
/// lens, whose three arc tangents (two azimuths and the triangle's excess) then take one
/// packed evaluation instead of three scalar ones (on SSE2 `Vec4` is one register; on a
/// target without SIMD, glam evaluates the lanes one by one, the same bits).
#[inline(always)]
pub fn atan_unit_estrin4(t: glam::Vec4) -> glam::Vec4 {
    use glam::Vec4;
    let c = &ATAN_UNIT;
    let k = |i: usize| Vec4::splat(c[i]);
    let s = t * t;
    let s2 = s * s;
    let s4 = s2 * s2;
    let low = (k(0) + k(1) * s) + (k(2) + k(3) * s) * s2;
    let high = (k(4) + k(5) * s) + (k(6) + k(7) * s) * s2;
    let p = low + (high + k(8) * s4) * s4;
    t + (t * s) * p
}

/// A fast approximation of `atan(x)` for `x >= 0` with absolute error below 1.2e-5 rad
/// (measured by the test below over the whole range), for the biased samplers.
///
/// Range reduction `atan(x) = π/2 - atan(1/x)` for `x > 1`, then an odd minimax-style
/// polynomial in `t = min(x, 1/x)` on `[0, 1]`.
#[inline(always)]
pub fn atan_fast_nonneg(x: f32) -> f32 {
    let invert = x > 1.0;
    let t = if invert { 1.0 / x } else { x };
    let t2 = t * t;
    let c = &ATAN_FAST;
    let p = t * (c[0] + t2 * (c[1] + t2 * (c[2] + t2 * (c[3] + t2 * c[4]))));
    if invert { FRAC_PI_2 - p } else { p }
}

/// Coefficients of an odd polynomial fitted to atan on [0, 1] (Abramowitz and Stegun
/// 4.4.49 style, degree 9), for [`atan_fast_nonneg`] and [`atan_fast_nonneg4`].
#[allow(clippy::excessive_precision)] // the coefficients as fitted
const ATAN_FAST: [f32; 5] = [
    0.999_866_0,
    -0.330_299_5,
    0.180_141_0,
    -0.085_133_0,
    0.020_835_1,
];

/// [`atan_fast_nonneg`] of four lanes, each rounded as the scalar form (the same
/// operations in the same order; both branches computed and one selected).
#[inline(always)]
#[must_use]
pub(crate) fn atan_fast_nonneg4(x: glam::Vec4) -> glam::Vec4 {
    use glam::Vec4;
    let invert = x.cmpgt(Vec4::ONE);
    let t = Vec4::select(invert, Vec4::ONE / x, x);
    let t2 = t * t;
    let c = ATAN_FAST.map(Vec4::splat);
    let p = t * (c[0] + t2 * (c[1] + t2 * (c[2] + t2 * (c[3] + t2 * c[4]))));
    Vec4::select(invert, Vec4::splat(FRAC_PI_2) - p, p)
}

#[cfg(test)]
mod tests {
    use super::super::test_sweep::{Errors, points, sweep};
    use super::*;
    use crate::testing::Rng;

    #[test]
    fn atan2_upper_half_plane_matches_f64_atan2() {
        let mut rng = Rng::new(11);
        let mut worst = 0.0f64;
        for _ in 0..200_000 {
            let y = rng.log_uniform(-30.0, 30.0) as f32;
            let x = rng.signed_log_uniform(-30.0, 30.0) as f32;
            let exact = (y as f64).atan2(x as f64);
            let got = atan2_upper_half_plane(y, x) as f64;
            worst = worst.max((got - exact).abs() / exact.abs().max(1e-30));
        }
        std::println!("worst relative error {worst:e}");
        assert!(
            worst < 4.0 * f32::EPSILON as f64,
            "worst relative error {worst}"
        );
    }

    /// `atan_unit` over every `stride`-th `f32` bit pattern in `[0, 1]` (and 1): the
    /// errors, and the number of steps where the value decreases (within each chunk
    /// and across chunk boundaries), none by more than one ulp.
    fn measure_atan_unit(stride: u32) -> (Errors, usize) {
        let chunks = sweep(0, 1.0f32.to_bits(), stride, |first, last, step| {
            let mut errors = Errors::default();
            let mut decreases = 0;
            let mut previous = atan_unit(f32::from_bits(first));
            for t in points(first, last, step) {
                let got = atan_unit(t);
                if got < previous {
                    assert_eq!(
                        got.next_up(),
                        previous,
                        "decrease of more than an ulp at {t:e}"
                    );
                    decreases += 1;
                }
                previous = got;
                errors.add(t, got, libm::atan(t as f64));
            }
            (
                errors,
                decreases,
                atan_unit(f32::from_bits(first)),
                previous,
            )
        });
        let mut decreases = 0;
        for pair in chunks.windows(2) {
            decreases += usize::from(pair[1].2 < pair[0].3);
        }
        chunks
            .into_iter()
            .fold((Errors::default(), decreases), |(a, n), (b, m, _, _)| {
                (a.merge(b), n + m)
            })
    }

    fn assert_atan_unit_bounds((errors, decreases): (Errors, usize), stride: u32) {
        std::println!("{errors:?}, {decreases} one-ulp decreases");
        // The documented bounds.
        assert!(errors.ulps <= 1.12, "{errors:?}");
        assert!(errors.relative <= 8.8e-8, "{errors:?}");
        assert!(decreases <= DECREASES / stride as usize, "{decreases}");
    }

    /// The one-ulp decreases of `atan_unit` over all of `[0, 1]` (measured).
    const DECREASES: usize = 124;

    #[test]
    fn atan_unit_dense_error_bounds() {
        assert_atan_unit_bounds(measure_atan_unit(61), 61);
    }

    /// Every `f32` in `[0, 1]`: about a billion evaluations (about a minute with
    /// optimisation on 2 cores), so ignored by default; `.ci/run` runs it in release
    /// mode.
    #[test]
    #[ignore]
    fn exhaustive_atan_unit_error_bounds() {
        assert_atan_unit_bounds(measure_atan_unit(1), 1);
    }

    #[test]
    fn atan_unit_edges() {
        assert_eq!(atan_unit(0.0).to_bits(), 0);
        // One ulp below f32 π/4, which is 0.37 ulp above π/4.
        assert_eq!(atan_unit(1.0), core::f32::consts::FRAC_PI_4.next_down());
        // Below 2^-12, t³/3 is less than half an ulp of t.
        for t in [f32::from_bits(1), f32::MIN_POSITIVE, 1e-20, 2e-4] {
            assert_eq!(atan_unit(t), t);
        }
    }

    /// [`atan_unit_estrin`] over every 61st `f32` of `[0, 1]` against f64: its
    /// documented bounds, and its edges.
    #[test]
    fn atan_unit_estrin_error_bounds() {
        let chunks = sweep(0, 1.0f32.to_bits(), 61, |first, last, step| {
            let mut errors = Errors::default();
            for t in points(first, last, step) {
                errors.add(t, atan_unit_estrin(t), libm::atan(t as f64));
            }
            errors
        });
        let errors = chunks.into_iter().fold(Errors::default(), Errors::merge);
        std::println!("{errors:?}");
        assert!(errors.ulps <= 1.1, "{errors:?}");
        assert!(errors.relative <= 8.5e-8, "{errors:?}");
        assert_eq!(atan_unit_estrin(0.0).to_bits(), 0);
        for t in [f32::from_bits(1), f32::MIN_POSITIVE, 1e-20, 2e-4] {
            assert_eq!(atan_unit_estrin(t), t);
        }
    }

    /// The relative error of the upper half plane's `atan2` along rays of every
    /// direction, from 0 to π in steps of about 1e-6 rad (including the octant ends,
    /// where the reduction's cases meet).
    #[test]
    fn atan2_upper_half_plane_dense_directions() {
        let mut worst = (0.0f64, 0.0f64);
        for i in 0..=3_000_000u32 {
            let angle = core::f64::consts::PI * i as f64 / 3_000_000.0;
            let (y, x) = (
                (angle.sin().max(0.0) * 3.0) as f32,
                (angle.cos() * 3.0) as f32,
            );
            let exact = (y as f64).atan2(x as f64);
            let got = atan2_upper_half_plane(y, x) as f64;
            if exact > 0.0 {
                let relative = (got - exact).abs() / exact;
                if relative > worst.0 {
                    worst = (relative, exact);
                }
            }
        }
        std::println!("worst relative error {:e} at {}", worst.0, worst.1);
        assert!(worst.0 < 1.3 * f32::EPSILON as f64, "{worst:?}");
    }

    /// [`atanf`] is `libm::atanf`, bit for bit: every 61st `f32` over the small range
    /// `2^-12 <= |x| < 7/16` and a margin on either side, every 997th over all finite
    /// `f32` (each of fdlibm's ranges), in both signs; the ends of every range (2^-12,
    /// 7/16, 11/16, 19/16, 39/16, 2^26, ∞) ±4 ulps, the points where the reduced
    /// argument is 0, and special values (zeros, subnormals, ∞, NaN).
    #[test]
    fn inline_atanf_is_libm_atanf() {
        let same = |x: f32| {
            let (got, expected) = (atanf(x), libm::atanf(x));
            assert!(
                got.to_bits() == expected.to_bits() || (got.is_nan() && expected.is_nan()),
                "{x:e} ({:#x}): {got:e}, libm {expected:e}",
                x.to_bits()
            );
        };
        sweep(0x3900_0000, 0x3f00_0000, 61, |first, last, step| {
            for x in points(first, last, step) {
                same(x);
                same(-x);
            }
        });
        sweep(0, f32::MAX.to_bits(), 997, |first, last, step| {
            for x in points(first, last, step) {
                same(x);
                same(-x);
            }
        });
        for end in [
            0x3980_0000u32,
            0x3ee0_0000,
            0x3f30_0000,
            0x3f98_0000,
            0x401c_0000,
            0x4c80_0000,
            0x7f80_0000,
        ] {
            for b in end - 4..=end + 4 {
                same(f32::from_bits(b));
                same(-f32::from_bits(b));
            }
        }
        for x in [
            0.0f32,
            -0.0,
            f32::from_bits(1),
            f32::MIN_POSITIVE,
            1e-30,
            0.5,
            1.0,
            1.5,
            2.0,
            1e30,
            f32::MAX,
        ] {
            same(x);
            same(-x);
        }
        same(f32::INFINITY);
        same(f32::NAN);
    }

    /// [`atanf`] is `libm::atanf` for every `f32` bit pattern (each of fdlibm's ranges,
    /// inline, so the range tests too): 2^32 evaluations of both, ignored by
    /// `cargo test`; `.ci/run` runs it with the other exhaustive tests (its name starts
    /// with `exhaustive`).
    #[test]
    #[ignore]
    fn exhaustive_inline_atanf_is_libm_atanf() {
        sweep(0, u32::MAX, 1 << 20, |first, last, step| {
            for start in (first..=last).step_by(step as usize) {
                for b in start..=start.saturating_add(step - 1) {
                    let x = f32::from_bits(b);
                    let (got, expected) = (atanf(x), libm::atanf(x));
                    assert!(
                        got.to_bits() == expected.to_bits() || (got.is_nan() && expected.is_nan()),
                        "{x:e} ({b:#x}): {got:e}, libm {expected:e}"
                    );
                }
            }
        });
    }

    #[test]
    fn atan2_upper_half_plane_edges() {
        assert_eq!(atan2_upper_half_plane(0.0, 1.0), 0.0);
        assert_eq!(atan2_upper_half_plane(0.0, 0.0), 0.0);
        assert_eq!(atan2_upper_half_plane(f32::NAN, 1.0), 0.0);
        assert!((atan2_upper_half_plane(1.0, 0.0) - FRAC_PI_2).abs() < 1e-7);
        assert!((atan2_upper_half_plane(0.0, -1.0) - core::f32::consts::PI).abs() < 1e-6);
        assert!((atan2_upper_half_plane(1e-30, -1.0) - core::f32::consts::PI).abs() < 1e-6);
    }

    #[test]
    fn atan_fast_error_bound_holds() {
        let mut worst = 0.0f64;
        for i in 0..=1_000_000 {
            let x = (i as f64 / 1_000_000.0) * 50.0;
            let got = atan_fast_nonneg(x as f32) as f64;
            worst = worst.max((got - x.atan()).abs());
        }
        for i in 0..1000 {
            let x = 10f64.powf(-10.0 + i as f64 * 0.02);
            worst = worst.max((atan_fast_nonneg(x as f32) as f64 - x.atan()).abs());
        }
        assert!(worst < 1.2e-5, "worst absolute error {worst}");
    }
}
