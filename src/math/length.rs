//! Lengths and normalisations of glam vectors with glam's own bits, on
//! [`sqrtf`](crate::math::sqrtf): the core's one definition of `|v|`, `1/|v|` and
//! `v/|v|`, in place of glam's `length`, `length_recip`, `normalize_or`,
//! `normalize_or_zero` and `try_normalize` (the ones the core uses; glam's `normalize`,
//! `distance` and the rest of the family would be written the same way when needed).
//!
//! Why not glam's: the crate builds glam with `default-features = false, features =
//! ["libm"]`, so glam's `Vec3::length` (and `Vec2`'s, and everything built on them) is
//! `libm::sqrtf`, which on x86 is inline assembly of `sqrtss` in the legacy SSE
//! encoding, also in an AVX build (`-C target-cpu=native`); executed while the upper half
//! of a 256-bit register holds data, each such instruction waits on a state transition
//! (docs/speed.md, stop 37, and [`sqrtf`](crate::math::sqrtf)). 231 of them were left in
//! the native static library, all from glam's length family. [`sqrtf`] is the same
//! correctly rounded operation, encoded for the target.
//!
//! Each function is glam 0.34's operation, in glam's order of roundings (`dot` as
//! `(x·x + y·y) + z·z`, `1/|v|` as a division, the normalisation as a multiplication by
//! it), so the results are glam's bit for bit (`*_is_glams` in the tests, with glam's
//! own methods as the reference). The core calls these free functions only: the
//! workspace's `clippy.toml` disallows glam's methods (`disallowed-methods`), and
//! `lib.rs` allows them in the test build, where glam's are the references.

use core::ops::Mul;

use glam::{Vec2, Vec3, Vec3A};

use crate::math::sqrtf;

/// A glam vector whose length the functions of this module take: `length_squared` as
/// glam's `dot(self, self)`.
pub(crate) trait Length: Copy {
    /// `v·v` in glam's order of additions (glam's `length_squared`).
    fn squared(self) -> f32;
}

/// A [`Length`] vector that the normalisations scale: `Mul<f32>` lane by lane, and the
/// zero vector of [`normalize_or_zero`]. Not `Vec3A`: glam's SSE2 `Vec3A::normalize`
/// divides by the length where the scalar one multiplies by its reciprocal, so no one
/// definition has glam's bits on every target (the core normalises no `Vec3A`).
pub(crate) trait Normalize: Length + Mul<f32, Output = Self> {
    const ZERO: Self;
}

impl Length for Vec2 {
    #[inline(always)]
    fn squared(self) -> f32 {
        self.length_squared()
    }
}

impl Length for Vec3 {
    #[inline(always)]
    fn squared(self) -> f32 {
        self.length_squared()
    }
}

/// glam's SSE2 `Vec3A::length` is `_mm_sqrt_ps` of `dot3_in_x`, whose first lane is the
/// `dot` that `length_squared` returns; the scalar one is `sqrt(dot)`: either way
/// `sqrtf(length_squared)`.
impl Length for Vec3A {
    #[inline(always)]
    fn squared(self) -> f32 {
        self.length_squared()
    }
}

impl Normalize for Vec2 {
    const ZERO: Self = Vec2::ZERO;
}

impl Normalize for Vec3 {
    const ZERO: Self = Vec3::ZERO;
}

/// `|v|`, glam's `length`: `√(v·v)`, correctly rounded from the rounded `v·v` (so it
/// overflows for components from about 1.8e19 on and loses precision below about 1e-19,
/// like glam's; [`normalize_scaled`](crate::math::normalize_scaled) is the careful form).
#[inline(always)]
#[must_use]
pub(crate) fn length<V: Length>(v: V) -> f32 {
    sqrtf(v.squared())
}

/// `1/|v|`, glam's `length_recip`: a division (infinite for a zero `v`).
#[inline(always)]
#[must_use]
pub(crate) fn length_recip<V: Length>(v: V) -> f32 {
    1.0 / length(v)
}

/// `v · (1/|v|)` when `1/|v|` is finite and positive, else `None`: glam's
/// `try_normalize`.
#[inline(always)]
#[must_use]
pub(crate) fn try_normalize<V: Normalize>(v: V) -> Option<V> {
    let rcp = length_recip(v);
    if rcp.is_finite() && rcp > 0.0 {
        Some(v * rcp)
    } else {
        None
    }
}

/// `v · (1/|v|)` when `1/|v|` is finite and positive (`v` non-zero, finite and `v·v`
/// finite), else `fallback`: glam's `normalize_or`.
#[inline(always)]
#[must_use]
pub(crate) fn normalize_or<V: Normalize>(v: V, fallback: V) -> V {
    let rcp = length_recip(v);
    if rcp.is_finite() && rcp > 0.0 {
        v * rcp
    } else {
        fallback
    }
}

/// [`normalize_or`], bit for bit, decided by a branch instead of a selection: for a
/// caller whose `v` is almost never degenerate (the pivot transformation of unit
/// directions), so that the processor predicts the branch and goes on with `v · (1/|v|)`
/// at once. `normalize_or`'s selection waits for its test, which x86-64 computes on the
/// reciprocal's bits in the integer unit and moves back as a mask (about 12 cycles on
/// the critical path of the SPTD sphere light sample, llvm-mca). The same test, written
/// as `0 < 1/|v| < ∞` (false for NaN, as `is_finite() && > 0`, [`is_positive_finite`]);
/// the fallback is a call to a cold function that returns it, which the compiler cannot
/// hoist into a selection.
#[inline(always)]
#[must_use]
pub(crate) fn normalize_or_predicted<V: Normalize>(v: V, fallback: V) -> V {
    let rcp = length_recip(v);
    if is_positive_finite(rcp) {
        v * rcp
    } else {
        cold_fallback(fallback)
    }
}

/// `0 < x < ∞` (false for NaN) as one comparison of the bits: the positive finite
/// non-zero `f32` are the patterns `0x0000_0001` (the smallest subnormal) to
/// `0x7f7f_ffff` (`f32::MAX`), in order, and `bits − 1` (wrapping) maps them onto
/// `0..0x7f7f_ffff` and everything else (+0 onto `u32::MAX`, +∞ and NaN above `f32::MAX`,
/// the negative ones from `0x7fff_ffff` on) above it (`is_positive_finite_is_the_comparisons`).
/// Written as two float comparisons, the compiler tested the class of the bits instead,
/// positive normal or positive subnormal, in 14 integer instructions per call (twice per
/// clipped sample of the SPTD sphere light sampler, callgrind, light bench `sptd`).
#[inline(always)]
pub(crate) fn is_positive_finite(x: f32) -> bool {
    x.to_bits().wrapping_sub(1) < 0x7f7f_ffff
}

/// `fallback` itself, out of line and cold (see [`normalize_or_predicted`]).
#[cold]
#[inline(never)]
fn cold_fallback<V>(fallback: V) -> V {
    fallback
}

/// [`normalize_or`] with the zero vector as the fallback: glam's `normalize_or_zero`.
#[inline(always)]
#[must_use]
pub(crate) fn normalize_or_zero<V: Normalize>(v: V) -> V {
    normalize_or(v, V::ZERO)
}

#[cfg(test)]
mod tests {
    //! glam's own methods are the reference: each helper must give their bits (any NaN
    //! for a NaN, as `sqrtf` may differ from `libm::sqrtf` only in a NaN's payload).

    use super::*;
    use crate::testing::Rng;

    /// Components that stress the formulas: zeros of both signs, subnormals, the ends
    /// of the range where `v·v` underflows or overflows, infinities and NaN.
    const HARD: [f32; 22] = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        3.0,
        -4.0,
        1e-45,
        -1e-45,
        1e-40,
        1.2e-38,
        1e-20,
        -1e-19,
        1.8e19,
        2e19,
        -1e30,
        f32::MAX,
        f32::MIN,
        f32::EPSILON,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ];

    fn same(a: f32, b: f32) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    fn same3(a: Vec3, b: Vec3) -> bool {
        same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z)
    }

    fn same2(a: Vec2, b: Vec2) -> bool {
        same(a.x, b.x) && same(a.y, b.y)
    }

    /// A random component: a random sign and significand at an exponent anywhere in the
    /// `f32` range (subnormals, infinities and NaN included) half of the time, a value
    /// in `[-2, 2]` otherwise.
    fn component(rng: &mut Rng) -> f32 {
        let bits = rng.next_u64();
        if bits & 1 == 0 {
            f32::from_bits((bits >> 32) as u32)
        } else {
            4.0 * rng.uniform_f32() - 2.0
        }
    }

    /// The `Vec3` cases: every triple of [`HARD`] components, and random vectors.
    fn vec3_cases() -> impl Iterator<Item = Vec3> {
        let hard = HARD.iter().flat_map(|&x| {
            HARD.iter()
                .flat_map(move |&y| HARD.iter().map(move |&z| Vec3::new(x, y, z)))
        });
        let mut rng = Rng::new(38);
        let random = (0..200_000).map(move |_| {
            Vec3::new(
                component(&mut rng),
                component(&mut rng),
                component(&mut rng),
            )
        });
        hard.chain(random)
    }

    fn vec2_cases() -> impl Iterator<Item = Vec2> {
        let hard = HARD
            .iter()
            .flat_map(|&x| HARD.iter().map(move |&y| Vec2::new(x, y)));
        let mut rng = Rng::new(39);
        let random = (0..200_000).map(move |_| Vec2::new(component(&mut rng), component(&mut rng)));
        hard.chain(random)
    }

    /// `is_positive_finite` is `0 < x < ∞` for every class of `f32`: around each end of
    /// the positive finite range (0, the subnormals, `f32::MAX`, +∞), the negative
    /// patterns, NaNs of both signs, and random patterns.
    #[test]
    fn is_positive_finite_is_the_comparisons() {
        let check = |bits: u32| {
            let x = f32::from_bits(bits);
            assert_eq!(
                is_positive_finite(x),
                x > 0.0 && x < f32::INFINITY,
                "{bits:#x}"
            );
        };
        for base in [
            0u32,
            0x0080_0000,
            0x7f7f_ffff,
            0x7f80_0000,
            0x7fc0_0000,
            0x8000_0000,
        ] {
            for offset in 0..64u32 {
                check(base.wrapping_add(offset));
                check(base.wrapping_sub(offset));
            }
        }
        for bits in [u32::MAX, 0xff80_0000, 0xffc0_0000, 0x3f80_0000, 0xbf80_0000] {
            check(bits);
        }
        let mut rng = Rng::new(4419);
        for _ in 0..1_000_000 {
            check(rng.next_u64() as u32);
        }
    }

    #[test]
    fn vec3_length_and_normalisations_are_glams() {
        let fallback = Vec3::new(0.25, -0.5, 2.0);
        for v in vec3_cases() {
            assert!(same(length(v), v.length()), "length {v:?}");
            assert!(
                same(length_recip(v), v.length_recip()),
                "length_recip {v:?}"
            );
            assert!(
                same3(normalize_or(v, fallback), v.normalize_or(fallback)),
                "normalize_or {v:?}"
            );
            assert!(
                same3(normalize_or_zero(v), v.normalize_or_zero()),
                "normalize_or_zero {v:?}"
            );
            // The predicted branch's form: `normalize_or`'s bits, the fallback included
            // (zero, subnormal, huge, infinite and NaN vectors among the cases).
            assert!(
                same3(
                    normalize_or_predicted(v, fallback),
                    v.normalize_or(fallback)
                ),
                "normalize_or_predicted {v:?}"
            );
            match (try_normalize(v), v.try_normalize()) {
                (None, None) => {}
                (Some(a), Some(b)) => assert!(same3(a, b), "try_normalize {v:?}"),
                (a, b) => panic!("try_normalize {v:?}: {a:?} against {b:?}"),
            }
        }
    }

    #[test]
    fn vec2_length_and_normalisations_are_glams() {
        let fallback = Vec2::new(0.25, -0.5);
        for v in vec2_cases() {
            assert!(same(length(v), v.length()), "length {v:?}");
            assert!(
                same(length_recip(v), v.length_recip()),
                "length_recip {v:?}"
            );
            assert!(
                same2(normalize_or(v, fallback), v.normalize_or(fallback)),
                "normalize_or {v:?}"
            );
            assert!(
                same2(normalize_or_zero(v), v.normalize_or_zero()),
                "normalize_or_zero {v:?}"
            );
            match (try_normalize(v), v.try_normalize()) {
                (None, None) => {}
                (Some(a), Some(b)) => assert!(same2(a, b), "try_normalize {v:?}"),
                (a, b) => panic!("try_normalize {v:?}: {a:?} against {b:?}"),
            }
        }
    }

    #[test]
    fn vec3a_length_is_glams() {
        for v in vec3_cases() {
            let v = Vec3A::from(v);
            assert!(same(length(v), v.length()), "length {v:?}");
            assert!(
                same(length_recip(v), v.length_recip()),
                "length_recip {v:?}"
            );
        }
    }
}
