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

/// Its operand (an `f32` or an SSE vector), unchanged, through an empty `asm!` that
/// hides the value from the optimiser: the one mechanism behind [`select_bits`] and
/// [`select_bits4`] (whose mask, 0 or all ones, would otherwise be recognised as a
/// `select` and turned back into a branch) and [`opaque`].
#[cfg(target_arch = "x86_64")]
macro_rules! hidden_from_optimiser {
    ($value:expr) => {{
        let mut value = $value;
        // SAFETY: an empty template (a comment naming the register) that reads and
        // writes nothing but its one operand, which it leaves as it is. (Allowed to be
        // nested: the selects expand it inside their own `unsafe` blocks.)
        #[allow(unused_unsafe)]
        unsafe {
            core::arch::asm!(
                "/* {0} */",
                inout(xmm_reg) value,
                options(pure, nomem, nostack, preserves_flags)
            );
        }
        value
    }};
}

/// `if_true` where `condition` holds, `if_false` otherwise, bit for bit, by a mask
/// instead of a branch: for a condition that the data decide at random (a sample's
/// coordinates), a branch is mispredicted about every other call, and each
/// misprediction discards the work issued after it (15–20 cycles and the overlap with
/// the next call). The compiler turned `if` between two floats into a branch where
/// the condition came from an integer comparison or where one arm was an addition.
///
/// Bit trick: `0 - (condition as u32)` is `0xFFFF_FFFF` (every bit set) for `true` and
/// `0` for `false`, so `(t & m) | (f & !m)` takes all 32 bits of one operand: exact for
/// every value, zeros of either sign, infinities and NaN payloads included.
///
/// On x86-64 the mask is an SSE register that passes through an empty `asm!`, which
/// hides from the optimiser that it is 0 or all ones: otherwise it recognises the blend
/// as a `select` again and, for a float chosen by an integer comparison or by `>=`,
/// emits a branch (measured: the same mispredictions as the `if`). The blend is
/// `andps`/`andnps`/`orps` on that register, without moving the operands to integer
/// registers. Elsewhere (Arm, where the selects become `vsel`/`fcsel` or short branches
/// of a pipeline that mispredicts cheaply) it is the plain blend of the bits.
#[inline(always)]
pub fn select_bits(condition: bool, if_true: f32, if_false: f32) -> f32 {
    let mask = 0u32.wrapping_sub(condition as u32);
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{
            _mm_and_ps, _mm_andnot_ps, _mm_castsi128_ps, _mm_cvtsi32_si128, _mm_cvtss_f32,
            _mm_or_ps, _mm_set_ss,
        };
        // SAFETY: the intrinsics need SSE2, which every x86_64 target has, and touch no
        // memory.
        unsafe {
            let m = hidden_from_optimiser!(_mm_castsi128_ps(_mm_cvtsi32_si128(mask as i32)));
            _mm_cvtss_f32(_mm_or_ps(
                _mm_and_ps(m, _mm_set_ss(if_true)),
                _mm_andnot_ps(m, _mm_set_ss(if_false)),
            ))
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        f32::from_bits((if_true.to_bits() & mask) | (if_false.to_bits() & !mask))
    }
}

/// [`select_bits`] of four lanes by one condition: every lane of `if_true` where
/// `condition` holds, of `if_false` otherwise, bit for bit, by a mask instead of a
/// branch (the same bit trick and the same `asm!` as there: a `select` of two vectors
/// by a scalar condition becomes a branch on x86-64, whose conditional moves of vector
/// registers are branches).
#[inline(always)]
pub fn select_bits4(condition: bool, if_true: glam::Vec4, if_false: glam::Vec4) -> glam::Vec4 {
    let mask = 0u32.wrapping_sub(condition as u32);
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{
            _mm_and_ps, _mm_andnot_ps, _mm_castsi128_ps, _mm_or_ps, _mm_set1_epi32,
        };
        // SAFETY: the intrinsics need SSE2, which every x86_64 target has, and touch no
        // memory.
        unsafe {
            let m = hidden_from_optimiser!(_mm_castsi128_ps(_mm_set1_epi32(mask as i32)));
            glam::Vec4::from(_mm_or_ps(
                _mm_and_ps(m, if_true.into()),
                _mm_andnot_ps(m, if_false.into()),
            ))
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        let pick = |t: f32, f: f32| f32::from_bits((t.to_bits() & mask) | (f.to_bits() & !mask));
        glam::Vec4::new(
            pick(if_true.x, if_false.x),
            pick(if_true.y, if_false.y),
            pick(if_true.z, if_false.z),
            pick(if_true.w, if_false.w),
        )
    }
}

/// `x` itself, bit for bit, as a value the optimiser cannot see through (an empty
/// `asm!` on x86-64 that takes and returns the register; `x` elsewhere). For a value
/// that one branch keeps across calls (which clobber every vector register, so the
/// value goes to a stack slot) and another branch uses at once: the copy's own live
/// range takes the spill, and the other branch keeps the register (without it the
/// register allocator spilled the value where it was computed, and the other branch
/// reloaded it from the stack: about 8 cycles on its chain).
#[inline(always)]
pub fn opaque(x: f32) -> f32 {
    #[cfg(target_arch = "x86_64")]
    {
        hidden_from_optimiser!(x)
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values whose bits a selection must keep: both zeros, a subnormal, the largest
    /// finite value, both infinities, a quiet NaN with a payload and a negative
    /// signalling NaN.
    const SELECTED_VALUES: [f32; 10] = [
        0.0,
        -0.0,
        1.0,
        -1.5,
        1e-45,
        f32::MAX,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::from_bits(0x7FC0_1234),
        f32::from_bits(0xFFA0_0001),
    ];

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

    #[test]
    fn opaque_keeps_every_bit() {
        for bits in [
            0u32,
            0x8000_0000,
            1,
            0x3F80_0000,
            0x7F80_0000,
            0x7FC0_1234,
            0xFFA0_0001,
        ] {
            assert_eq!(opaque(f32::from_bits(bits)).to_bits(), bits);
        }
    }

    #[test]
    fn select_bits4_takes_every_bit_of_one_operand() {
        let values = SELECTED_VALUES;
        for (i, &a) in values.iter().enumerate() {
            for &b in &values {
                let t = glam::Vec4::new(a, b, values[(i + 3) % values.len()], -a);
                let f = glam::Vec4::new(b, a, -b, values[(i + 5) % values.len()]);
                let bits = |v: glam::Vec4| v.to_array().map(f32::to_bits);
                assert_eq!(bits(select_bits4(true, t, f)), bits(t));
                assert_eq!(bits(select_bits4(false, t, f)), bits(f));
            }
        }
    }

    #[test]
    fn select_bits_takes_every_bit_of_one_operand() {
        let values = SELECTED_VALUES;
        for &a in &values {
            for &b in &values {
                assert_eq!(select_bits(true, a, b).to_bits(), a.to_bits());
                assert_eq!(select_bits(false, a, b).to_bits(), b.to_bits());
            }
        }
    }
}
