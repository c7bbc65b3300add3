//! `sin` and `cos` together for angles in `[0, π]`, the half angles of the samplers
//! (solid angle: half a fan triangle's solid angle; projected: an ellipse sector's angle
//! in the coordinates where the ellipse is the unit circle).

use super::fast_functions_generated::{COS_QUARTER, SIN_QUARTER};
use super::horner;
use core::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// `π/2 - FRAC_PI_2` (about -4.37e-8): with `FRAC_PI_2` a two-float π/2 good to 2^-50
/// relative, so that `x - π/2 = (x - FRAC_PI_2) - HALF_PI_LO` keeps the relative
/// precision of the tiny `cos x` near π/2.
const HALF_PI_LO: f32 = (core::f64::consts::FRAC_PI_2 - FRAC_PI_2 as f64) as f32;
/// `π - PI` (about -8.74e-8, exactly `2 HALF_PI_LO` as `PI = 2 FRAC_PI_2`).
const PI_LO: f32 = (core::f64::consts::PI - PI as f64) as f32;
/// 3π/4 to within an ulp: above it the angle is reduced to `π - x`, below it to
/// `x - π/2`, both then within π/4 (plus an ulp, which the polynomials cover).
const THREE_PI_4: f32 = 3.0 * FRAC_PI_4;

/// `(sin x, cos x)` for `x` in `[0, π]` (clamped into `[0, PI]`; NaN gives NaN).
///
/// Reduced to `r` in `[-π/4, π/4]` by the symmetries about π/2 and π:
/// `x < π/4`: `r = x`, `(sin r, cos r)`; `x <= 3π/4`: `r = x - π/2`, `(cos r, -sin r)`;
/// above: `r = π - x`, `(sin r, -cos r)`. Both differences are exact before the low
/// part of the two-float constant is subtracted (Sterbenz: `x` is within a factor two
/// of `FRAC_PI_2`, resp. `PI`), so `r` is the correctly rounded reduced angle, and its
/// rounding error is kept as `r_lo` for a first-order correction; every output that tends to zero (`sin` at 0 and π, `cos` at π/2) comes from
/// `sin r ≈ r` and keeps its relative precision. `sin r = r + r³ P(r²)` and
/// `cos r = 1 - r²/2 + r⁴ Q(r²)` (degrees 7 and 8) are fitted by
/// `tools/src/fitters/fast_function_fitter.rs` (relative errors of the `f32` coefficients 4e-9
/// and 1.2e-10) and evaluated by Horner's rule without fused multiply-add, so `+fma`
/// builds give the same bits; `1 - r²/2` is compensated (its rounding error added back).
///
/// Measured over every `f32` in `[0, PI]` (the exhaustive test below) against `f64`
/// `sin` and `cos` of the same `f32` (note that `sin(PI) = -8.74e-8`): absolute error at
/// most 4.7e-8 for `sin` and 4.8e-8 for `cos` (0.39 and 0.40 `f32::EPSILON`), at most
/// 0.78 ulp of the correctly rounded `sin` and 0.80 ulp of `cos` everywhere, tiny
/// values included (`sin x = x` below 2^-12, `cos x` near π/2 is `-sin(x - π/2)`).
#[inline(always)]
pub fn sin_cos_0_to_pi(x: f32) -> (f32, f32) {
    // `x` in [0, π/4) (NaN fails both comparisons), which the clamp leaves as it is:
    // tested before the clamp, so that the common case's chain of dependent operations
    // starts at `x` itself, not after a `max` and a `min` (issue 15: a fan triangle's
    // sample and a central projected sample wait for this value). `-0.0` passes, as it
    // passes the clamp unchanged, and takes the same shortcut.
    if (0.0..FRAC_PI_4).contains(&x) {
        return sin_cos_below_quarter_pi(x);
    }
    let x = x.clamp(0.0, PI);
    if x < FRAC_PI_4 {
        // Only 0, from a negative `x`.
        return sin_cos_below_quarter_pi(x);
    }
    let high = x > THREE_PI_4;
    // The reduced angle r + r_lo: `a` is exact (Sterbenz), `r` the rounded sum with the
    // low part of the constant, and `r_lo` its rounding error, exact by Fast2Sum (`a` is 0
    // or a multiple of an ulp of `x`, at least 6e-8, so |a| >= |low part|).
    let (r, r_lo) = if high {
        let a = PI - x;
        let r = a + PI_LO;
        (r, PI_LO - (r - a))
    } else {
        let a = x - FRAC_PI_2;
        let r = a - HALF_PI_LO;
        (r, (a - r) - HALF_PI_LO)
    };
    let s = r * r;
    // 1 - s/2 + s² Q(s): `half = s/2` is exact and `w = 1 - half` is rounded; as
    // `half <= 0.31`, `1 - w` is exact (Sterbenz) and `(1 - w) - half` is the rounding
    // error of `w` exactly (Fast2Sum), which is added back with the small s² Q(s), so that
    // only the last addition rounds at the order of one.
    let half = 0.5 * s;
    let w = 1.0 - half;
    // sin(r + r_lo) = sin r + r_lo cos r and cos(r + r_lo) = cos r - r_lo sin r to
    // within r_lo² (below 2^-48): `w` and `r` stand in for cos r and sin r in the small
    // terms (errors below 0.05 ulp).
    let sin_r = r + ((r * s) * horner(s, &SIN_QUARTER) + r_lo * w);
    let cos_r = w + ((((1.0 - w) - half) + (s * s) * horner(s, &COS_QUARTER)) - r_lo * r);
    if high {
        (sin_r, -cos_r)
    } else {
        (cos_r, -sin_r)
    }
}

/// [`sin_cos_0_to_pi`] for `x` in `[0, π/4)`: `r = x` and `r_lo = 0`, for which the
/// general form adds `r_lo w = +0` and subtracts `r_lo r = +0`, which change no bits: the
/// same values without those operations and without the selections between the
/// reductions (a fan triangle's sample, whose half angles mostly lie here: 213 -> 199
/// instructions, callgrind). The tests below compare the bits with the general form.
#[inline(always)]
fn sin_cos_below_quarter_pi(x: f32) -> (f32, f32) {
    let s = x * x;
    let half = 0.5 * s;
    let w = 1.0 - half;
    let sin_r = x + (x * s) * horner(s, &SIN_QUARTER);
    let cos_r = w + (((1.0 - w) - half) + (s * s) * horner(s, &COS_QUARTER));
    (sin_r, cos_r)
}

/// [`SIN_QUARTER`] in powers of `y² = 4 x²`: coefficient `i` times `4^-(i+1)` (exact, a
/// power of two), so that `(x x²) P(x²) = (x y²) P'(y²)` bit for bit (see
/// [`sin_cos_of_half`]).
const SIN_QUARTER_OF_DOUBLE: [f32; 3] = [
    SIN_QUARTER[0] * 0.25,
    SIN_QUARTER[1] * 0.0625,
    SIN_QUARTER[2] * 0.015625,
];
/// [`COS_QUARTER`] in powers of `y² = 4 x²`: coefficient `i` times `4^-(i+2)`, so that
/// `(x²)² Q(x²) = (y²)² Q'(y²)` bit for bit.
const COS_QUARTER_OF_DOUBLE: [f32; 3] = [
    COS_QUARTER[0] * 0.0625,
    COS_QUARTER[1] * 0.015625,
    COS_QUARTER[2] * 0.00390625,
];

/// `(sin(y/2), cos(y/2))` for `y` in `[0, 2π]`: [`sin_cos_0_to_pi`]`(0.5 * y)` bit for
/// bit, for every `y` (tested), with one multiplication fewer on the chain of dependent
/// operations in the common case `y < π/2` (a fan triangle's solid angle sample, whose
/// angle is half the solid angle `y` it draws).
///
/// Below π/2 the half angle `x = y/2` takes [`sin_cos_0_to_pi`]'s shortcut, which
/// evaluates its polynomials in `x² = x·x`, two dependent products after `y`. Here they
/// are evaluated in `y² = y·y`, one product after `y`, with the coefficients scaled by
/// the powers of 4 that `x² = y²/4` brings (exact: powers of two), and `x²/2 = y²/8`:
/// every rounded intermediate is the shortcut's one times a power of two, so the results
/// are its bits. (Where `y²` is subnormal, below 1.2e-38, the polynomial terms lie far
/// below an ulp of `x` and of 1 and round away in both forms.)
#[inline(always)]
pub(crate) fn sin_cos_of_half(y: f32) -> (f32, f32) {
    // `y` in [0, π/2) exactly when `y/2` is in [0, π/4): `FRAC_PI_2` is `2 FRAC_PI_4`
    // (scaling by 2 is exact) and `0.5 y` is exact; NaN fails here as it fails there.
    // One unsigned comparison of the bits instead of two of floats (three instructions
    // fewer per solid angle sample, callgrind): non-negative floats are ordered as their
    // bits, so `+0 <= y < π/2` holds exactly for the bits below those of `FRAC_PI_2`;
    // negative `y` (the sign bit) and NaN (above +∞) lie above. `-0.0`, which the float
    // comparisons let through, takes the general form here, which gives the shortcut's
    // bits for it (`sin_cos_0_to_pi` takes its own shortcut at `-0.0`; tested below).
    if y.to_bits() >= FRAC_PI_2.to_bits() {
        return sin_cos_0_to_pi(0.5 * y);
    }
    let x = 0.5 * y;
    let s4 = y * y;
    let half = 0.125 * s4;
    let w = 1.0 - half;
    let sin_r = x + (x * s4) * horner(s4, &SIN_QUARTER_OF_DOUBLE);
    let cos_r = w + (((1.0 - w) - half) + (s4 * s4) * horner(s4, &COS_QUARTER_OF_DOUBLE));
    (sin_r, cos_r)
}

/// The Taylor coefficient `(−1)^(k/2) (π/2)^k / k!` of `sin(π r/2)` (odd `k`) or
/// `cos(π r/2)` (even `k`), evaluated in `f64` at compile time and rounded once.
const fn quarter_turn_taylor(k: u32) -> f32 {
    let mut term = 1.0f64;
    let mut i = 1;
    while i <= k {
        term *= core::f64::consts::FRAC_PI_2 / i as f64;
        i += 1;
    }
    (if (k / 2) % 2 == 1 { -term } else { term }) as f32
}

/// `sin(π r/2) = r (S₁ + S₃ r² + … + S₉ r⁸)` and `cos(π r/2) = 1 + r² (C₂ + C₄ r² + … +
/// C₁₀ r⁸)` for `|r| ≤ 1/2`, lowest first (for [`horner`]). The first terms left out are
/// below `(π/2)^11/11! 2^-11 = 1.8e-9` and `(π/2)^12/12! 2^-12 = 1.2e-10`, under the
/// `f32` rounding of the results.
const SIN_OF_QUARTER_TURNS: [f32; 5] = [
    quarter_turn_taylor(1),
    quarter_turn_taylor(3),
    quarter_turn_taylor(5),
    quarter_turn_taylor(7),
    quarter_turn_taylor(9),
];
const COS_OF_QUARTER_TURNS: [f32; 5] = [
    quarter_turn_taylor(2),
    quarter_turn_taylor(4),
    quarter_turn_taylor(6),
    quarter_turn_taylor(8),
    quarter_turn_taylor(10),
];

/// `(sin 2πu, cos 2πu)` for `u` in `[0, 1)` (an azimuth drawn from a random number;
/// the caller clamps `u` into `[0, 1)`), in quarter turns: `v = 4u` (exact), `q` the
/// nearest integer to `v` and `r = v − q` in `[−1/2, 1/2]` (exact: Sterbenz for `q ≥ 1`),
/// so that no rounded multiple of π enters; `(sin, cos)(π r/2)` from the Taylor
/// polynomials above, rotated by `q` quarter turns: `(S, C)`, `(C, −S)`, `(−S, −C)`,
/// `(−C, S)`, by exchanging the two values' bits and flipping sign bits.
///
/// No branch: the azimuth is random, and a branch on its quadrant is mispredicted about
/// every other call (15–20 cycles each). The integer conversion, the exchange and the
/// sign flips are integer operations, which the compiler keeps without a branch (a
/// choice between two floats became one).
///
/// Absolute error at most 1.0e-7 against `f64` `sin` and `cos` of `2πu` over every `f32`
/// `u` in `[0, 1)` (the exhaustive test below; measured 9.3e-8), and relative precision
/// kept where a result tends to zero (`r ≈ 0`). `libm::sincosf(TAU * u)` erred by up to
/// 2.4e-7 + 1.7e-7 from its rounded angle alone.
#[inline(always)]
pub(crate) fn sin_cos_of_turn(u: f32) -> (f32, f32) {
    let v = 4.0 * u;
    // The nearest quarter turn, by the rounding of an addition: `v + 1.5·2²³` lies in
    // [2²³, 2²⁴), where the spacing of `f32` is 1, so the sum is `v` rounded to an integer
    // (ties to even), which the low bits of its significand hold, and subtracting the
    // constant again is exact. No conversion between floats and integers (a conversion
    // made the cap's and GGX's samples slower than the branches it replaced); `q` is 4
    // for the last eighth of a turn, 0 quarter turns modulo 4.
    const ROUNDER: f32 = 12_582_912.0;
    let rounded = v + ROUNDER;
    let q = rounded.to_bits();
    let r = v - (rounded - ROUNDER);
    sin_cos_of_quarter_turns(q, r)
}

/// `(sin, cos)(π/2 (q + r))` for an integer `q` (its two low bits count) and
/// `|r| ≤ 1/2`: the Taylor polynomials of [`sin_cos_of_turn`] in `r`, rotated by `q`
/// quarter turns without a branch. For callers whose angle is a known number of
/// quarter turns plus an exact remainder (the concentric disk map: `π/4 · b/a` is
/// `r = b/(2a)` quarter turns), so that no rounded multiple of π enters. Same error
/// bound as [`sin_cos_of_turn`] (its polynomials' error over `|r| ≤ 1/2`).
#[inline(always)]
pub(crate) fn sin_cos_of_quarter_turns(q: u32, r: f32) -> (f32, f32) {
    let s = r * r;
    // The small terms by Estrin's scheme (pairs `c + c' s` independent of each other and
    // of `s² = s2`), the large ones added last as Horner's rule adds them, so that the
    // roundings at the results' magnitude are the same as Horner's: `sin = S₁r + rs (S₃
    // + s T)` and `cos = 1 + (C₂s + s² R)`. The chain after `s` is seven and six
    // operations deep instead of nine and ten (a sample's latency runs through it).
    let s2 = s * s;
    let [s1, s3, s5, s7, s9] = SIN_OF_QUARTER_TURNS;
    let [c2, c4, c6, c8, c10] = COS_OF_QUARTER_TURNS;
    let sin_tail = (s5 + s7 * s) + s9 * s2;
    let sin_r = s1 * r + (r * s) * (s3 + s * sin_tail);
    let cos_tail = (c4 + c6 * s) + s2 * (c8 + c10 * s);
    let cos_r = 1.0 + (c2 * s + s2 * cos_tail);
    // Bit 0 of q exchanges the two, bit 1 negates the sine, bit 0 xor bit 1 the cosine.
    let (sin_bits, cos_bits) = (sin_r.to_bits(), cos_r.to_bits());
    let swapped = (sin_bits ^ cos_bits) & 0u32.wrapping_sub(q & 1);
    let negate_sin = (q & 2) << 30;
    let negate_cos = ((q ^ (q >> 1)) & 1) << 31;
    (
        f32::from_bits(sin_bits ^ swapped ^ negate_sin),
        f32::from_bits(cos_bits ^ swapped ^ negate_cos),
    )
}

#[cfg(test)]
mod tests {
    use super::super::test_sweep::{Errors, points, sweep};
    use super::*;

    /// The errors of `sin` and `cos` over every `stride`-th `f32` bit pattern in
    /// `[0, PI]` (and `PI` itself).
    fn measure(stride: u32) -> (Errors, Errors) {
        sweep(0, PI.to_bits(), stride, |first, last, step| {
            let (mut sin_errors, mut cos_errors) = (Errors::default(), Errors::default());
            for x in points(first, last, step) {
                let (s, c) = sin_cos_0_to_pi(x);
                sin_errors.add(x, s, libm::sin(x as f64));
                cos_errors.add(x, c, libm::cos(x as f64));
            }
            (sin_errors, cos_errors)
        })
        .into_iter()
        .fold((Errors::default(), Errors::default()), |(a, b), (c, d)| {
            (a.merge(c), b.merge(d))
        })
    }

    fn assert_bounds(sin_errors: Errors, cos_errors: Errors) {
        // The documented bounds.
        assert!(sin_errors.absolute <= 4.7e-8, "sin {sin_errors:?}");
        assert!(cos_errors.absolute <= 4.8e-8, "cos {cos_errors:?}");
        assert!(sin_errors.ulps <= 0.78, "sin {sin_errors:?}");
        assert!(cos_errors.ulps <= 0.80, "cos {cos_errors:?}");
    }

    #[test]
    fn sin_cos_dense_error_bounds() {
        let (s, c) = measure(61);
        std::println!("sin {s:?}\ncos {c:?}");
        assert_bounds(s, c);
    }

    /// Every `f32` in `[0, π]`: about a billion evaluations (about a minute and a half
    /// with optimisation on 2 cores), so ignored by default; `.ci/run` runs it in release mode.
    #[test]
    #[ignore]
    fn exhaustive_sin_cos_error_bounds() {
        let (s, c) = measure(1);
        std::println!("sin {s:?}\ncos {c:?}");
        assert_bounds(s, c);
    }

    /// The largest absolute error of `sin_cos_of_turn` against f64 `sin`, `cos` of `2πu`
    /// over every `stride`-th `f32` bit pattern of `[0, 1)`.
    fn measure_turns(stride: u32) -> f64 {
        let last = (1.0f32 - f32::EPSILON / 2.0).to_bits();
        sweep(0, last, stride, |first, last, step| {
            let mut worst = 0.0f64;
            for u in points(first, last, step) {
                let (s, c) = sin_cos_of_turn(u);
                let angle = 2.0 * core::f64::consts::PI * u as f64;
                worst = worst
                    .max((s as f64 - libm::sin(angle)).abs())
                    .max((c as f64 - libm::cos(angle)).abs());
            }
            worst
        })
        .into_iter()
        .fold(0.0, f64::max)
    }

    /// `sin_cos_of_turn` on a dense sample of `[0, 1)`, the quarter turns and the edges:
    /// within the documented 1.0e-7; exact at the quarter turns (`r = 0`).
    #[test]
    fn sin_cos_of_turn_matches_f64() {
        let worst = measure_turns(97);
        std::println!("sin_cos_of_turn: worst absolute error {worst:e}");
        assert!(worst <= 1.0e-7, "{worst:e}");
        assert_eq!(sin_cos_of_turn(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_of_turn(0.25), (1.0, -0.0));
        assert_eq!(sin_cos_of_turn(0.5), (-0.0, -1.0));
        assert_eq!(sin_cos_of_turn(0.75), (-1.0, 0.0));
        // Relative precision near the zeros of sin and cos.
        let (s, _) = sin_cos_of_turn(1e-30);
        assert!((s as f64 / (2.0 * core::f64::consts::PI * 1e-30) - 1.0).abs() < 1e-7);
        let u = 0.25 + f32::EPSILON / 4.0; // the next f32 above a quarter turn
        let (_, c) = sin_cos_of_turn(u);
        let exact = (2.0 * core::f64::consts::PI * u as f64).cos();
        assert!((c as f64 / exact - 1.0).abs() < 1e-6, "{c:e} {exact:e}");
        let (s, c) = sin_cos_of_turn(1.0 - f32::EPSILON / 2.0);
        assert!(s < 0.0 && s > -4e-7 && c == 1.0);
    }

    /// Every `f32` in `[0, 1)`: about a billion evaluations, so ignored by default;
    /// `.ci/run` runs it in release mode.
    #[test]
    #[ignore]
    fn exhaustive_sin_cos_of_turn_error_bound() {
        let worst = measure_turns(1);
        std::println!("sin_cos_of_turn: worst absolute error {worst:e}");
        assert!(worst <= 1.0e-7, "{worst:e}");
    }

    /// `sin_cos_of_quarter_turns` over a dense sweep of `r ∈ [−1/2, 1/2]` (every 64th
    /// `f32` of each sign, 2⁻¹⁰⁰ and below included) and every `q`: within the bound
    /// of `sin_cos_of_turn`, whose exhaustive test only reaches the remainders `4u − q`.
    #[test]
    fn sin_cos_of_quarter_turns_error_bound() {
        let mut worst = 0.0f64;
        for bits in (0..=0.5f32.to_bits()).step_by(64) {
            for r in [f32::from_bits(bits), -f32::from_bits(bits)] {
                for q in 0..4u32 {
                    let angle = core::f64::consts::FRAC_PI_2 * (q as f64 + r as f64);
                    let (s, c) = sin_cos_of_quarter_turns(q, r);
                    worst = worst
                        .max((s as f64 - angle.sin()).abs())
                        .max((c as f64 - angle.cos()).abs());
                }
            }
        }
        assert!(worst <= 1.0e-7, "{worst:e}");
    }

    /// The form that `sin_cos_0_to_pi` evaluates below π/4 before its shortcut: the
    /// general one with `r = x` and `r_lo = 0`.
    fn sin_cos_below_quarter_pi_in_general_form(x: f32) -> (f32, f32) {
        let (r, r_lo) = (x, 0.0f32);
        let s = r * r;
        let half = 0.5 * s;
        let w = 1.0 - half;
        let sin_r = r + ((r * s) * horner(s, &SIN_QUARTER) + r_lo * w);
        let cos_r = w + ((((1.0 - w) - half) + (s * s) * horner(s, &COS_QUARTER)) - r_lo * r);
        (sin_r, cos_r)
    }

    /// `sin_cos_0_to_pi(x)` has the bits of `expected`.
    fn assert_same_bits(x: f32, (s0, c0): (f32, f32)) {
        let (s, c) = sin_cos_0_to_pi(x);
        assert_eq!(
            (s.to_bits(), c.to_bits()),
            (s0.to_bits(), c0.to_bits()),
            "{x:e}"
        );
    }

    /// Every `stride`-th `f32` of `[0, π/4)`: the shortcut gives the general form's bits.
    fn assert_shortcut_matches_general_form(stride: u32) {
        let last = FRAC_PI_4.to_bits() - 1;
        sweep(0, last, stride, |first, last, step| {
            for x in points(first, last, step) {
                assert_same_bits(x, sin_cos_below_quarter_pi_in_general_form(x));
            }
        });
    }

    #[test]
    fn shortcut_below_quarter_pi_keeps_the_bits() {
        assert_shortcut_matches_general_form(61);
    }

    /// Every `f32` of `[0, π/4)` (about a billion), so ignored by default.
    #[test]
    #[ignore]
    fn exhaustive_shortcut_below_quarter_pi_keeps_the_bits() {
        assert_shortcut_matches_general_form(1);
    }

    /// The range test before the clamp (issue 15) gives the bits of the clamp followed by
    /// the shortcut below π/4 or the general form: at both ends of the shortcut's range,
    /// on either side of them, for `-0.0`, negative, huge and non-finite angles, and
    /// over `[0, π]` in steps of 1e-4.
    #[test]
    fn shortcut_before_the_clamp_keeps_the_bits() {
        let reference = |x: f32| {
            let x = x.clamp(0.0, PI);
            if x < FRAC_PI_4 {
                sin_cos_below_quarter_pi_in_general_form(x)
            } else {
                sin_cos_0_to_pi(x)
            }
        };
        let below = f32::from_bits(FRAC_PI_4.to_bits() - 1);
        let mut angles = vec![
            0.0,
            -0.0,
            f32::from_bits(1),
            -f32::from_bits(1),
            -1.0,
            below,
            FRAC_PI_4,
            f32::from_bits(FRAC_PI_4.to_bits() + 1),
            PI,
            4.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        angles.extend((0..=31416).map(|i| i as f32 * 1e-4));
        for x in angles {
            assert_same_bits(x, reference(x));
        }
        let (s, c) = sin_cos_0_to_pi(f32::NAN);
        assert!(s.is_nan() && c.is_nan());
    }

    /// `sin_cos_of_half(y)` is `sin_cos_0_to_pi(0.5 * y)` bit for bit: every 61st `f32`
    /// of `[0, 2π]` (subnormals, the shortcut's end at π/2 and the general range), and
    /// `-0.0`, negative, huge and non-finite angles and NaN.
    #[test]
    fn sin_cos_of_half_keeps_the_bits() {
        let check = |y: f32| {
            let (s, c) = sin_cos_of_half(y);
            let (s0, c0) = sin_cos_0_to_pi(0.5 * y);
            assert_eq!(
                (s.to_bits(), c.to_bits()),
                (s0.to_bits(), c0.to_bits()),
                "{y:e}"
            );
        };
        sweep(0, (2.0 * PI).to_bits(), 61, |first, last, step| {
            for y in points(first, last, step) {
                check(y);
            }
        });
        let edge = FRAC_PI_2.to_bits();
        for bits in (edge - 64..edge + 64).chain(0..4096) {
            check(f32::from_bits(bits));
        }
        for y in [
            -0.0,
            -1e-45,
            -1.0,
            7.0,
            1e30,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ] {
            check(y);
        }
        let (s, c) = sin_cos_of_half(f32::NAN);
        assert!(s.is_nan() && c.is_nan());
    }

    #[test]
    fn sin_cos_edges() {
        assert_eq!(HALF_PI_LO, -4.371139e-8);
        assert_eq!(PI_LO, 2.0 * HALF_PI_LO);
        assert_eq!(sin_cos_0_to_pi(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_0_to_pi(-1.0), (0.0, 1.0));
        assert_eq!(sin_cos_0_to_pi(f32::NEG_INFINITY), (0.0, 1.0));
        assert_eq!(sin_cos_0_to_pi(-1e-45), (0.0, 1.0));
        assert_eq!(sin_cos_0_to_pi(1e-30), (1e-30, 1.0));
        assert_eq!(sin_cos_0_to_pi(4.0), sin_cos_0_to_pi(PI));
        assert_eq!(sin_cos_0_to_pi(PI), (PI_LO, -1.0));
        assert_eq!(sin_cos_0_to_pi(FRAC_PI_2), (1.0, HALF_PI_LO));
        let (s, c) = sin_cos_0_to_pi(f32::NAN);
        assert!(s.is_nan() && c.is_nan());
    }
}
