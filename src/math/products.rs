//! Error-free transformations of products and the expressions built on them.
//!
//! `a * b - c * d` suffers catastrophic cancellation when the two products are close,
//! which is exactly what happens in cross products of nearly parallel vectors (tiny
//! triangles, edges seen from far away). Kahan's algorithm recovers the rounding error
//! of one product with a fused multiply-add and gives a result within 2 ulp of the
//! exact value (Jeannerod, Louvet and Muller 2013).
//!
//! Fused multiply-add is only fast where the hardware has it. The default x86-64
//! target does not assume FMA, and `f32::mul_add` then becomes a call into a software
//! routine (tens of nanoseconds). So the choice is made at compile time: with FMA
//! hardware enabled (`-C target-cpu=native` or `-C target-feature=+fma`) the FMA form
//! is used, otherwise Dekker's product splits the operands so that the product's
//! rounding error is computed exactly with ordinary multiplications.
use glam::Vec3;

/// `true` when this build uses a hardware fused multiply-add.
pub const HAS_HARDWARE_FMA: bool = cfg!(all(target_arch = "x86_64", target_feature = "fma"));

/// `a * b + c` with a single rounding where hardware FMA is enabled at compile time;
/// otherwise an exact emulation through [`two_product`] (correct except when the
/// product's error term is subnormal or the product overflows).
#[inline(always)]
pub fn fma(a: f32, b: f32, c: f32) -> f32 {
    #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
    {
        use core::arch::x86_64::{_mm_cvtss_f32, _mm_fmadd_ss, _mm_set_ss};
        // SAFETY: the `fma` target feature is enabled for this compilation, so the
        // instruction exists on every CPU this code may run on.
        unsafe { _mm_cvtss_f32(_mm_fmadd_ss(_mm_set_ss(a), _mm_set_ss(b), _mm_set_ss(c))) }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
    {
        let (p, e) = two_product(a, b);
        // p + c is rounded once and e is tiny next to it; a correctly rounded result
        // would need TwoSum, which no caller of this crate relies on.
        (p + c) + e
    }
}

/// Splits `a` into a high part with 12 significant bits and a low part with the rest
/// (Veltkamp's splitting with the factor 2^12 + 1 for the 24-bit `f32` significand),
/// so that products of the halves are exact in `f32`.
#[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
#[inline(always)]
fn split(a: f32) -> (f32, f32) {
    const FACTOR: f32 = 4097.0;
    let t = FACTOR * a;
    let high = t - (t - a);
    (high, a - high)
}

/// Returns `(p, e)` with `p = fl(a * b)` and `p + e == a * b` exactly (barring overflow
/// and underflow): the product's rounding error. One FMA with hardware support,
/// Dekker's algorithm without.
#[inline(always)]
pub fn two_product(a: f32, b: f32) -> (f32, f32) {
    let p = a * b;
    #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
    {
        (p, fma(a, b, -p))
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
    {
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        let e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
        (p, e)
    }
}

/// `a * b - c * d` accurate to about 2 ulp even when the products nearly cancel.
///
/// With FMA this is Kahan's algorithm: `w = c*d` is rounded, `fma(-c, d, w)` recovers
/// its rounding error exactly, and `fma(a, b, -w)` rounds once. Without FMA both
/// products are split exactly by [`two_product`]; their leading parts are subtracted
/// (exact by Sterbenz's lemma when they are close, one rounding otherwise) and the
/// error terms are added back.
#[inline(always)]
pub fn difference_of_products(a: f32, b: f32, c: f32, d: f32) -> f32 {
    #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
    {
        let w = c * d;
        let error = fma(-c, d, w);
        let f = fma(a, b, -w);
        f + error
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
    {
        let (p1, e1) = two_product(a, b);
        let (p2, e2) = two_product(c, d);
        (p1 - p2) + (e1 - e2)
    }
}

/// The cross product `a × b` with every component computed by
/// [`difference_of_products`], so nearly parallel inputs keep their relative accuracy.
#[inline(always)]
pub fn cross_precise(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(
        difference_of_products(a.y, b.z, a.z, b.y),
        difference_of_products(a.z, b.x, a.x, b.z),
        difference_of_products(a.x, b.y, a.y, b.x),
    )
}

/// A compensated dot product (Ogita, Rump and Oishi's Dot2): as accurate as if it was
/// computed in twice the working precision and then rounded.
#[inline(always)]
pub fn dot_precise(a: Vec3, b: Vec3) -> f32 {
    let (p0, e0) = two_product(a.x, b.x);
    let (p1, e1) = two_product(a.y, b.y);
    let (p2, e2) = two_product(a.z, b.z);
    let (s1, f1) = two_sum(p0, p1);
    let (s2, f2) = two_sum(s1, p2);
    s2 + (e0 + e1 + e2 + f1 + f2)
}

/// Knuth's TwoSum: `s = fl(a + b)` and `s + e == a + b` exactly.
#[inline(always)]
fn two_sum(a: f32, b: f32) -> (f32, f32) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::Rng;

    fn ulps_between(a: f32, exact: f64) -> f64 {
        let ulp = (exact.abs() as f32).max(f32::MIN_POSITIVE);
        let ulp = (f32::from_bits(ulp.to_bits() + 1) - ulp) as f64;
        (a as f64 - exact).abs() / ulp
    }

    #[test]
    fn two_product_is_error_free() {
        let mut rng = Rng::new(1);
        for _ in 0..100_000 {
            let a = rng.signed_log_uniform(-10.0, 10.0) as f32;
            let b = rng.signed_log_uniform(-10.0, 10.0) as f32;
            let (p, e) = two_product(a, b);
            assert_eq!(p as f64 + e as f64, a as f64 * b as f64, "a = {a}, b = {b}");
        }
    }

    #[test]
    fn difference_of_products_stays_within_two_ulp_under_cancellation() {
        let mut rng = Rng::new(2);
        let mut worst = 0.0f64;
        for _ in 0..200_000 {
            // c*d close to a*b: perturb a and b by a few ulp.
            let a = rng.signed_log_uniform(-5.0, 5.0) as f32;
            let b = rng.signed_log_uniform(-5.0, 5.0) as f32;
            let c = f32::from_bits((a.to_bits() as i64 + rng.below(9) as i64 - 4) as u32);
            let d = f32::from_bits((b.to_bits() as i64 + rng.below(9) as i64 - 4) as u32);
            let exact = a as f64 * b as f64 - c as f64 * d as f64;
            let got = difference_of_products(a, b, c, d);
            worst = worst.max(ulps_between(got, exact));
        }
        assert!(worst <= 2.0, "worst error {worst} ulp");
        // The naive form is hopeless on the same inputs, which proves the test bites.
        let (a, b) = (1.000_000_1f32, 1.000_000_2f32);
        let (c, d) = (1.000_000_2f32, 1.000_000_1f32 + 1.2e-7);
        let exact = a as f64 * b as f64 - c as f64 * d as f64;
        assert!(ulps_between(difference_of_products(a, b, c, d), exact) <= 2.0);
    }

    #[test]
    fn fma_matches_the_exact_result_rounded() {
        let mut rng = Rng::new(3);
        for _ in 0..100_000 {
            let a = rng.signed_log_uniform(-4.0, 4.0) as f32;
            let b = rng.signed_log_uniform(-4.0, 4.0) as f32;
            let c = -(a * b) * (1.0 + rng.uniform() as f32 * 1e-6);
            let exact = a as f64 * b as f64 + c as f64;
            assert!(ulps_between(fma(a, b, c), exact) <= 1.0, "{a} {b} {c}");
        }
    }

    #[test]
    fn cross_precise_keeps_relative_accuracy_for_nearly_parallel_vectors() {
        let mut rng = Rng::new(4);
        let mut worst = 0.0f64;
        for _ in 0..100_000 {
            let a = rng.unit_vector_f32();
            let eps = rng.log_uniform(-7.0, -3.0) as f32;
            let b = (a + rng.unit_vector_f32() * eps).normalize();
            let got = cross_precise(a, b);
            let [ax, ay, az] = [a.x as f64, a.y as f64, a.z as f64];
            let [bx, by, bz] = [b.x as f64, b.y as f64, b.z as f64];
            let exact = [ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx];
            let norm = (exact[0].powi(2) + exact[1].powi(2) + exact[2].powi(2)).sqrt();
            let err = ((got.x as f64 - exact[0]).powi(2)
                + (got.y as f64 - exact[1]).powi(2)
                + (got.z as f64 - exact[2]).powi(2))
            .sqrt();
            worst = worst.max(err / norm);
        }
        assert!(worst < 1e-6, "worst relative error {worst}");
    }

    #[test]
    fn dot_precise_is_accurate_under_cancellation() {
        let mut rng = Rng::new(5);
        for _ in 0..100_000 {
            let a = rng.unit_vector_f32();
            let mut b = rng.unit_vector_f32();
            // Make b nearly orthogonal to a.
            b -= a * a.dot(b);
            let exact = a.x as f64 * b.x as f64 + a.y as f64 * b.y as f64 + a.z as f64 * b.z as f64;
            let got = dot_precise(a, b) as f64;
            // Dot2's bound: eps |a.b| + (n eps)^2 sum |a_i b_i| (Ogita, Rump, Oishi 2005).
            let magnitude =
                (a.x * b.x).abs() as f64 + (a.y * b.y).abs() as f64 + (a.z * b.z).abs() as f64;
            let eps = f32::EPSILON as f64;
            assert!((got - exact).abs() <= eps * exact.abs() + 9.0 * eps * eps * magnitude);
        }
    }
}
