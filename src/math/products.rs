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

/// `a * b - c * d` to within ε relative (ε = 2⁻²³), computing the error-free form of
/// [`difference_of_products`] only when the products may cancel.
///
/// The plain `fl(fl(ab) - fl(cd))` has relative error at most
/// `ε/2 · (1 + (|ab| + |cd|) / |ab - cd|)` (each product rounded by ε/2 of its size, the
/// difference by ε/2 of its own). When the products have opposite signs (or one is 0),
/// `|ab| + |cd| = |ab - cd|` and that is at most ε: no cancellation is possible. Otherwise,
/// and when the difference is below 2⁻¹⁰⁰ (where the products' rounding may be
/// subnormal), the careful form runs. The wider switch of
/// [`difference_of_products_unless_half_cancels`] (1.5ε) raised the largest error of Ω at
/// 1e-9 sr in the accuracy table of docs/polygon-lights.md from 4.7e-7 to 5.3e-7; the
/// solid angle fan determinants take it since stop 44, for their time.
#[inline(always)]
pub fn difference_of_products_unless_cancelling(a: f32, b: f32, c: f32, d: f32) -> f32 {
    plain_difference_where(a, b, c, d, |p1, p2, plain| {
        p1.abs() + p2.abs() <= plain.abs() && plain.abs() >= MIN_PLAIN_DIFFERENCE
    })
}

/// `a * b - c * d` to within 1.5ε relative (to first order in ε = 2⁻²³): the plain
/// `fl(fl(ab) - fl(cd))` unless at least half of the products' magnitude cancels, the
/// error-free form of [`difference_of_products`] otherwise (and below 2⁻¹⁰⁰, as
/// [`difference_of_products_unless_cancelling`]).
///
/// With `u = ε/2`, the rounded products `p1`, `p2` and `plain = fl(p1 - p2)`, the plain
/// form's error is at most `u (|ab| + |cd|) + u |plain|` (each product and the difference
/// rounded once). The test `fl(|p1| + |p2|) <= 2 |plain|` (`2 |plain|` exact) gives
/// `|p1| + |p2| <= 2 |plain| / (1 - u)` and `|ab| + |cd| <= (|p1| + |p2|) / (1 - u)`, so the
/// error is at most `u |plain| (1 + 2 / (1 - u)²) = 3u |plain| (1 + O(ε))`, that is 1.5ε of
/// the exact difference to first order. Products of opposite signs always pass
/// (`|p1| + |p2| = |plain|` up to rounding, as in
/// [`difference_of_products_unless_cancelling`], whose bound is ε); products of the same
/// sign pass when the smaller is at most a third of the larger. For the fan determinants
/// of solid angle sampling, `det = |x| |y| sin(ψ - φ)` of two edge vectors at angles φ and
/// ψ, and for products of the same sign `(|p1| + |p2|) / |det| = |sin(φ + ψ)| / |sin(ψ - φ)|`,
/// at most `1 / sin θ` for the angle θ between the edges: every fan triangle whose angle at
/// the apex lies between 30° and 150° takes the plain form, where the opposite-sign test
/// sent about a third of the benchmark's triangles to the careful one.
///
/// Not bit for bit [`difference_of_products_unless_cancelling`]: where the products have
/// the same sign, the careful form `fl(fl(p1 - p2) + fl(e1 - e2))` differs from the plain
/// one whenever the products' rounding errors `e1 - e2` reach half an ulp of the
/// difference, which no test of `p1` and `p2` alone can exclude (`ulp(plain) <=
/// ulp(max(|p1|, |p2|))` when the products have the same sign).
#[inline(always)]
pub fn difference_of_products_unless_half_cancels(a: f32, b: f32, c: f32, d: f32) -> f32 {
    plain_difference_where(a, b, c, d, plain_difference_is_within_half)
}

/// The test of [`difference_of_products_unless_half_cancels`]: `|p1| + |p2| <= 2 |plain|`
/// (at most half of the products' magnitude cancels) and `|plain| >= 2⁻¹⁰⁰`. False for NaN.
#[inline(always)]
pub(crate) fn plain_difference_is_within_half(p1: f32, p2: f32, plain: f32) -> bool {
    p1.abs() + p2.abs() <= 2.0 * plain.abs() && plain.abs() >= MIN_PLAIN_DIFFERENCE
}

/// `fl(fl(ab) - fl(cd))` where `plain_is_enough(fl(ab), fl(cd), fl(fl(ab) - fl(cd)))`,
/// otherwise the error-free form of [`difference_of_products`]: the one body of the three
/// plain-or-careful differences of products ([`difference_of_products_unless_cancelling`],
/// [`difference_of_products_unless_half_cancels`], [`difference_of_products_sign`]), each
/// with its own test.
#[inline(always)]
fn plain_difference_where(
    a: f32,
    b: f32,
    c: f32,
    d: f32,
    plain_is_enough: impl Fn(f32, f32, f32) -> bool,
) -> f32 {
    let (p1, p2) = (a * b, c * d);
    let plain = p1 - p2;
    if plain_is_enough(p1, p2, plain) {
        plain
    } else {
        difference_of_products(a, b, c, d)
    }
}

/// A number with the sign of the exact `a * b - c * d` (and 0 exactly when it is 0): the
/// plain difference where its sign is certain, otherwise
/// [`difference_of_products`] (for comparisons, which need only the sign).
///
/// `fl(fl(ab) - fl(cd))` has the sign of `fl(ab) - fl(cd)`, which differs from the exact
/// difference by at most `u (|ab| + |cd|)` (`u = ε/2`, each product rounded once). So
/// where `|plain| > ε (|fl(ab)| + |fl(cd)|)` (twice that bound, which covers the
/// rounding of the test's own terms) the sign is the exact one, and the careful form,
/// within 2 ulps of the exact value, has it too: both give the same comparisons. Below
/// 2⁻¹⁰⁰, where the products' rounding may be subnormal, the careful form runs.
#[inline(always)]
pub fn difference_of_products_sign(a: f32, b: f32, c: f32, d: f32) -> f32 {
    plain_difference_where(a, b, c, d, plain_difference_is_certain)
}

/// Whether the plain difference `plain = fl(p1 - p2)` of the rounded products `p1`, `p2`
/// has the exact sign of the unrounded difference (the test of
/// [`difference_of_products_sign`]): `|plain|` exceeds the products' rounding bound
/// `ε (|p1| + |p2|)` and is at least 2⁻¹⁰⁰ (no underflow). Never true for `plain == 0`.
/// `&`, not `&&`: no branch, for callers that evaluate it in sorting networks.
#[inline(always)]
pub(crate) fn plain_difference_is_certain(p1: f32, p2: f32, plain: f32) -> bool {
    (plain.abs() > f32::EPSILON * (p1.abs() + p2.abs())) & (plain.abs() >= MIN_PLAIN_DIFFERENCE)
}

/// 2⁻¹⁰⁰: below it [`difference_of_products_unless_cancelling`] takes the careful form.
pub(crate) const MIN_PLAIN_DIFFERENCE: f32 = 7.888_609_e-31;

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

/// The cross product `a × b` as an unevaluated sum `hi + lo` of two vectors, accurate to
/// about ε² relative to `|a| |b|` per component: each component's two products split
/// exactly by [`two_product`], their difference by [`two_sum`], and the rounding errors
/// gathered into `lo`. For planes that must not carry the ε rotation of a rounded normal
/// (the edges of polygons a few hundred ulps across).
#[inline(always)]
pub fn cross_with_residual(a: Vec3, b: Vec3) -> (Vec3, Vec3) {
    let component = |p: f32, q: f32, r: f32, s: f32| {
        let (p1, e1) = two_product(p, q);
        let (p2, e2) = two_product(r, s);
        let (difference, error) = two_sum(p1, -p2);
        two_sum(difference, error + (e1 - e2))
    };
    let (x, ex) = component(a.y, b.z, a.z, b.y);
    let (y, ey) = component(a.z, b.x, a.x, b.z);
    let (z, ez) = component(a.x, b.y, a.y, b.x);
    (Vec3::new(x, y, z), Vec3::new(ex, ey, ez))
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
pub fn two_sum(a: f32, b: f32) -> (f32, f32) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// Whether `det(a, b, c) = a · (b × c)` is exactly zero: the three points lie exactly in
/// one plane with the origin (for example a polygon's vertices in a plane through the
/// shading point), decided without rounding.
///
/// The determinant is the sum of six signed triple products. Each triple product
/// `x y z` is split exactly into four floats ([`two_product`] of `x y`, then of both
/// parts with `z`), and the 24 floats are summed into a nonoverlapping expansion by
/// Shewchuk's Grow-Expansion (each step a [`two_sum`], which is error-free): the exact
/// sum is zero if and only if every component is. Exact in round-to-nearest, barring
/// overflow and products below about 2⁻¹⁰⁰ (whose rounding errors may be subnormal);
/// there it may answer `false` for a zero determinant, never `true` for one of size
/// above 2⁻¹²⁰ of the coordinates cubed. About 350 operations: a fallback, for
/// determinants that a cheap test cannot tell from zero.
#[must_use]
pub fn determinant_is_exactly_zero(a: Vec3, b: Vec3, c: Vec3) -> bool {
    let triples = [
        (a.x, b.y, c.z),
        (a.y, b.z, c.x),
        (a.z, b.x, c.y),
        (-a.x, b.z, c.y),
        (-a.y, b.x, c.z),
        (-a.z, b.y, c.x),
    ];
    let mut expansion = [0.0f32; 24];
    let mut length = 0;
    for (x, y, z) in triples {
        let (p, e) = two_product(x, y);
        let (p1, e1) = two_product(p, z);
        let (p2, e2) = two_product(e, z);
        for term in [p1, e1, p2, e2] {
            // Grow-Expansion: adds `term` to the expansion exactly, component by component.
            let mut q = term;
            for component in &mut expansion[..length] {
                let (sum, error) = two_sum(q, *component);
                *component = error;
                q = sum;
            }
            expansion[length] = q;
            length += 1;
        }
    }
    expansion.iter().all(|&component| component == 0.0)
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

    /// A factor of the tests' products: random sign, log-uniform magnitude 1e-6 to 1e6.
    fn random_factor(rng: &mut Rng) -> f32 {
        rng.signed_log_uniform(-6.0, 6.0) as f32
    }

    /// `x` moved by up to 4 ulps either way (uniformly over the 9 patterns).
    fn within_4_ulps(x: f32, rng: &mut Rng) -> f32 {
        f32::from_bits((x.to_bits() as i64 + rng.below(9) as i64 - 4) as u32)
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
            let c = within_4_ulps(a, &mut rng);
            let d = within_4_ulps(b, &mut rng);
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

    /// The sign of the exact difference (f64 products of `f32` are exact), on both
    /// branches: independent products (plain), products a few ulps apart and exactly equal
    /// ones (careful), and products whose difference is just above the plain branch's
    /// threshold.
    #[test]
    fn difference_of_products_sign_is_the_exact_sign() {
        let mut rng = Rng::new(23);
        let (mut plain_taken, mut careful_taken) = (0u32, 0u32);
        for i in 0..300_000 {
            let a = random_factor(&mut rng);
            let b = random_factor(&mut rng);
            let (c, d) = match i % 4 {
                0 => (random_factor(&mut rng), random_factor(&mut rng)),
                1 => (within_4_ulps(a, &mut rng), within_4_ulps(b, &mut rng)),
                2 => (b, a),
                _ => {
                    // c d = a b (1 + k ε) for a few k: differences near the threshold.
                    let k = rng.below(7) as f32 - 3.0;
                    (a * (1.0 + k * f32::EPSILON), b)
                }
            };
            let exact = a as f64 * b as f64 - c as f64 * d as f64;
            let got = difference_of_products_sign(a, b, c, d);
            assert_eq!(
                got.partial_cmp(&0.0),
                exact.partial_cmp(&0.0),
                "{a} {b} {c} {d}: {got} against {exact}"
            );
            let (p1, p2) = (a * b, c * d);
            if got == p1 - p2 && got != difference_of_products(a, b, c, d) {
                plain_taken += 1;
            } else {
                careful_taken += 1;
            }
        }
        assert!(
            plain_taken > 1000 && careful_taken > 1000,
            "{plain_taken} {careful_taken}"
        );
    }

    /// The stated bound, ε relative, on both branches: independent products (the plain
    /// branch when their signs differ), products a few ulps apart (the careful one), and
    /// products of opposite signs and nearly equal size, where the plain branch is at its
    /// worst.
    #[test]
    fn difference_of_products_unless_cancelling_stays_within_its_bound() {
        let mut rng = Rng::new(21);
        let (mut worst, mut plain_taken) = (0.0f64, 0u32);
        for i in 0..300_000 {
            let a = random_factor(&mut rng);
            let b = random_factor(&mut rng);
            let (c, d) = match i % 3 {
                0 => (random_factor(&mut rng), random_factor(&mut rng)),
                1 => (within_4_ulps(a, &mut rng), within_4_ulps(b, &mut rng)),
                _ => (
                    a * (1.0 / 3.0) * (1.0 + 1e-6 * (rng.uniform() as f32 - 0.5)),
                    b,
                ),
            };
            let exact = a as f64 * b as f64 - c as f64 * d as f64;
            if exact == 0.0 {
                continue;
            }
            let got = difference_of_products_unless_cancelling(a, b, c, d);
            let (p1, p2) = (a * b, c * d);
            plain_taken +=
                (got == p1 - p2 && (p1.abs() + p2.abs()) <= 2.0 * (p1 - p2).abs()) as u32;
            worst = worst.max((got as f64 - exact).abs() / exact.abs());
        }
        let epsilon = f32::EPSILON as f64;
        assert!(
            worst <= 1.5 * epsilon,
            "worst relative error {} ε",
            worst / epsilon
        );
        // Both branches ran: the independent products of opposite signs and all of the
        // third group take the plain one (131,020 of 300,000 with this seed).
        assert!(
            (110_000..160_000).contains(&plain_taken),
            "plain branch taken {plain_taken} times"
        );
    }

    /// The stated bound of [`difference_of_products_unless_half_cancels`], 1.5ε relative
    /// (to first order), and which inputs take which branch: products of opposite signs,
    /// and products of the same sign whose ratio is below 1/3, take the plain one; products
    /// of the same sign whose ratio is above 1/3 the careful one (bit for bit
    /// `difference_of_products`). Ratios within a few ulps of 1/3 may take either.
    #[test]
    fn difference_of_products_unless_half_cancels_stays_within_its_bound() {
        let mut rng = Rng::new(24);
        let (mut worst, mut plain_taken, mut careful_taken) = (0.0f64, 0u32, 0u32);
        for i in 0..300_000 {
            let a = random_factor(&mut rng);
            let b = random_factor(&mut rng);
            let (c, d) = match i % 4 {
                0 => (random_factor(&mut rng), random_factor(&mut rng)),
                1 => (within_4_ulps(a, &mut rng), within_4_ulps(b, &mut rng)),
                // Same signs, the ratio of the products around the switch at 1/3.
                2 => (
                    a * (1.0 / 3.0) * (1.0 + 1e-3 * (rng.uniform() as f32 - 0.5)),
                    b,
                ),
                // Same signs, well apart (ratio 1/4 to 1/10): the plain branch's worst case.
                _ => (a * (0.1 + 0.15 * rng.uniform() as f32), b),
            };
            let exact = a as f64 * b as f64 - c as f64 * d as f64;
            if exact == 0.0 {
                continue;
            }
            let got = difference_of_products_unless_half_cancels(a, b, c, d);
            let (p1, p2) = (a * b, c * d);
            let plain = p1 - p2;
            if plain.abs() >= MIN_PLAIN_DIFFERENCE {
                // The branch taken follows the products' ratio.
                let (small, large) = (p1.abs().min(p2.abs()), p1.abs().max(p2.abs()));
                let opposite = (p1 < 0.0) != (p2 < 0.0);
                if opposite || small <= large * (1.0 / 3.0) * (1.0 - 4.0 * f32::EPSILON) {
                    assert_eq!(got.to_bits(), plain.to_bits(), "{a} {b} {c} {d}");
                    plain_taken += 1;
                } else if small >= large * (1.0 / 3.0) * (1.0 + 4.0 * f32::EPSILON) {
                    let careful = difference_of_products(a, b, c, d);
                    assert_eq!(got.to_bits(), careful.to_bits(), "{a} {b} {c} {d}");
                    careful_taken += 1;
                }
            }
            worst = worst.max((got as f64 - exact).abs() / exact.abs());
        }
        let epsilon = f32::EPSILON as f64;
        assert!(
            worst <= 1.5 * epsilon * (1.0 + 4.0 * epsilon),
            "worst relative error {} ε",
            worst / epsilon
        );
        // The plain branch's error came close to its bound (the test bites).
        assert!(
            worst > 1.0 * epsilon,
            "worst relative error {} ε",
            worst / epsilon
        );
        assert!(
            plain_taken > 100_000 && careful_taken > 50_000,
            "{plain_taken} {careful_taken}"
        );
    }

    /// Exactly coplanar triples (dyadic coordinates in planes through the origin) give
    /// `true`; the same triples with one coordinate moved by one ulp give `false`, and so
    /// do random triples (checked against the f64 determinant, exact for these inputs).
    #[test]
    fn determinant_is_exactly_zero_decides_exactly() {
        let mut rng = Rng::new(22);
        let dyadic = |rng: &mut Rng| ((rng.uniform() * 2.0 - 1.0) * 4096.0).round() as f32 / 1024.0;
        for i in 0..20_000 {
            // Two random in-plane directions of the plane n · x = 0 with n = (1, k, m), k and
            // m small integers: x = (-k s - m t, s, t) is exact.
            let (k, m) = ((i % 7) as f32 - 3.0, (i % 5) as f32 - 2.0);
            let point = |rng: &mut Rng| {
                let (s, t) = (dyadic(rng), dyadic(rng));
                Vec3::new(-k * s - m * t, s, t)
            };
            let (a, b, c) = (point(&mut rng), point(&mut rng), point(&mut rng));
            assert!(determinant_is_exactly_zero(a, b, c), "{a} {b} {c}");
            assert!(determinant_is_exactly_zero(c, a, b));
            // (Of a non-zero coordinate: an ulp of 0 is subnormal, below the exact range.)
            let nudge = |x: f32| {
                if x != 0.0 {
                    f32::from_bits(x.to_bits() ^ 1)
                } else {
                    x
                }
            };
            let nudged = Vec3::new(nudge(c.x), nudge(c.y), c.z);
            let exact = |a: Vec3, b: Vec3, c: Vec3| {
                use crate::testing::{cross, d3, dot};
                dot(d3(a), cross(d3(b), d3(c)))
            };
            // Moving one coordinate by an ulp leaves the plane unless the others make its
            // coefficient vanish (b × c with a zero x component).
            if exact(a, b, nudged) != 0.0 {
                assert!(
                    !determinant_is_exactly_zero(a, b, nudged),
                    "{a} {b} {nudged}"
                );
            }
        }
        for _ in 0..20_000 {
            let (a, b, c) = (
                rng.unit_vector_f32(),
                rng.unit_vector_f32(),
                rng.unit_vector_f32(),
            );
            assert!(!determinant_is_exactly_zero(a, b, c));
        }
        // Coplanar with the origin in large and small magnitudes (rescaled by powers of two).
        let (a, b, c) = (
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(0.5, 1.0, 1.5),
            Vec3::new(3.0, -1.0, 0.25),
        );
        assert!(determinant_is_exactly_zero(
            a * 2f32.powi(30),
            b,
            c * 2f32.powi(-30)
        ));
        assert!(!determinant_is_exactly_zero(
            a,
            b + Vec3::new(0.0, 0.0, 2f32.powi(-20)),
            c
        ));
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
