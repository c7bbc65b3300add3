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
    let x = x.clamp(0.0, PI);
    let low = x < FRAC_PI_4;
    let high = x > THREE_PI_4;
    // The reduced angle r + r_lo: `a` is exact (Sterbenz), `r` the rounded sum with the
    // low part of the constant, and `r_lo` its rounding error, exact by Fast2Sum (`a` is 0
    // or a multiple of an ulp of `x`, at least 6e-8, so |a| >= |low part|).
    let (r, r_lo) = if low {
        (x, 0.0)
    } else if high {
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
    if low {
        (sin_r, cos_r)
    } else if high {
        (sin_r, -cos_r)
    } else {
        (cos_r, -sin_r)
    }
}

/// `(sin 2πu, cos 2πu)` for `u` in `[0, 1)` (an azimuth drawn from a random number),
/// from [`sin_cos_0_to_pi`]: `v = 2u` and, past a half turn, `v − 1` are exact, and
/// `sin(π + x) = −sin x`, `cos(π + x) = −cos x`; so the error is that of
/// [`sin_cos_0_to_pi`] (0.8 ulp) at the rounded angle `π v`, as `libm::sincosf` at the
/// rounded `2π u`. `u` outside `[0, 1)` is clamped into it by the caller.
#[inline(always)]
pub(crate) fn sin_cos_of_turn(u: f32) -> (f32, f32) {
    let v = 2.0 * u;
    let past_half = v >= 1.0;
    let (sin, cos) = sin_cos_0_to_pi(PI * if past_half { v - 1.0 } else { v });
    if past_half { (-sin, -cos) } else { (sin, cos) }
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

    /// `sin_cos_of_turn` against f64 `sin`, `cos` of `2πu` over 2²⁰ + 1 evenly spaced
    /// `u` and the quarter turns: the error is that of the angle `π v` (the rounding of
    /// the product, up to `ulp(2)/2` = 1.2e-7, and `f32` π's own error times `v`, up to
    /// 8.7e-8) plus that of `sin_cos_0_to_pi` (4.8e-8), so at most 2.6e-7 (measured
    /// 2.1e-7). `libm::sincosf(TAU * u)` erred by up to 2.4e-7 + 1.7e-7 from its angle
    /// alone.
    #[test]
    fn sin_cos_of_turn_matches_f64() {
        let mut worst = 0.0f64;
        let grid = (0..=1u32 << 20)
            .map(|k| (k as f32 * (1.0 / (1u32 << 20) as f32)).min(1.0 - f32::EPSILON / 2.0));
        for u in grid.chain([
            0.0,
            0.25,
            0.5,
            0.75,
            1.0 - f32::EPSILON / 2.0,
            1e-30,
            0.5 + f32::EPSILON,
        ]) {
            let (s, c) = sin_cos_of_turn(u);
            let angle = 2.0 * core::f64::consts::PI * u as f64;
            worst = worst
                .max((s as f64 - libm::sin(angle)).abs())
                .max((c as f64 - libm::cos(angle)).abs());
        }
        std::println!("sin_cos_of_turn: worst absolute error {worst:e}");
        assert!(worst <= 2.6e-7, "{worst:e}");
    }

    #[test]
    fn sin_cos_edges() {
        assert_eq!(HALF_PI_LO, -4.371139e-8);
        assert_eq!(PI_LO, 2.0 * HALF_PI_LO);
        assert_eq!(sin_cos_0_to_pi(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_0_to_pi(-1.0), (0.0, 1.0));
        assert_eq!(sin_cos_0_to_pi(1e-30), (1e-30, 1.0));
        assert_eq!(sin_cos_0_to_pi(4.0), sin_cos_0_to_pi(PI));
        assert_eq!(sin_cos_0_to_pi(PI), (PI_LO, -1.0));
        assert_eq!(sin_cos_0_to_pi(FRAC_PI_2), (1.0, HALF_PI_LO));
        let (s, c) = sin_cos_0_to_pi(f32::NAN);
        assert!(s.is_nan() && c.is_nan());
    }
}
