//! `f32` bit helpers.
//!
//! IEEE 754 binary32 stores the sign in bit 31, the biased exponent in bits 23..=30 and
//! the significand in bits 0..=22. Flipping or copying bit 31 changes only the sign,
//! exactly, for every value including zeros, infinities and NaN; these helpers rely on
//! nothing else.

/// The sign bit of `x` alone: `0x8000_0000` for negative values (and -0, and NaN with
/// the sign set), `0` otherwise.
#[inline(always)]
pub fn sign_mask(x: f32) -> u32 {
    x.to_bits() & 0x8000_0000
}

/// `true` when the sign bit of `x` is set. Unlike `x < 0.0`, this tells `-0.0` from
/// `+0.0`, which Peters 2021 (supplement A.2) uses to classify ellipses.
#[inline(always)]
pub fn is_sign_negative(x: f32) -> bool {
    sign_mask(x) != 0
}

/// `|magnitude|` with the sign bit of `sign`: clears bit 31 of `magnitude` and ors in
/// bit 31 of `sign`. Exact for all inputs.
#[inline(always)]
pub fn copy_sign(magnitude: f32, sign: f32) -> f32 {
    f32::from_bits((magnitude.to_bits() & 0x7FFF_FFFF) | sign_mask(sign))
}

/// `x` multiplied by the sign of `a * b` without multiplying: xoring bit 31 of `x` with
/// the xor of the sign bits of `a` and `b` negates `x` exactly when `a * b` is negative
/// (or when exactly one of them is a negative zero).
#[inline(always)]
pub fn with_sign_of_product(x: f32, a: f32, b: f32) -> f32 {
    f32::from_bits(x.to_bits() ^ sign_mask(a) ^ sign_mask(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sign_helpers_agree_with_arithmetic() {
        let values = [
            0.0f32,
            -0.0,
            1.0,
            -1.0,
            1e-40,
            -1e-40,
            3.0e38,
            -3.0e38,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        for &a in &values {
            assert_eq!(is_sign_negative(a), a.is_sign_negative());
            for &b in &values {
                assert_eq!(copy_sign(a, b).to_bits(), a.copysign(b).to_bits());
                for &x in &values[..4] {
                    let expected = if a.is_sign_negative() != b.is_sign_negative() {
                        -x
                    } else {
                        x
                    };
                    assert_eq!(with_sign_of_product(x, a, b).to_bits(), expected.to_bits());
                }
            }
        }
    }
}
