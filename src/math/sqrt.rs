//! The square root of an `f32`: IEEE 754's correctly rounded operation, as the
//! processor's square root instruction, encoded for the build's target.
//!
//! `libm::sqrtf` on x86 is inline assembly of `sqrtss`, which the compiler emits as
//! written: in the legacy SSE encoding even in a build with AVX, where the code around it
//! uses VEX-encoded and 256-bit instructions. Executed while a 256-bit register's upper
//! half holds data, each such instruction waited on a state transition: the
//! `target-cpu=native` build's projected preparation of a decentral hexagon (two dozen
//! square roots next to the four-sector lanes) took 2040 ns where the default build takes
//! 750 (docs/speed.md, stop 37). The intrinsic is the same correctly rounded operation,
//! which the compiler encodes for the target (`vsqrtss` with AVX) and may schedule and
//! fold like any other arithmetic. Elsewhere (the `thumbv7em` build) this is
//! `libm::sqrtf`.

/// `√x`, correctly rounded (the same bits as `libm::sqrtf` for every input but the
/// payload of a NaN).
#[inline(always)]
#[must_use]
pub fn sqrtf(x: f32) -> f32 {
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{_mm_cvtss_f32, _mm_set_ss, _mm_sqrt_ss};
        // SAFETY: the three intrinsics need SSE, which every x86_64 target has; they
        // touch no memory.
        unsafe { _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x))) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        libm::sqrtf(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same bits as `libm::sqrtf` (the instruction `sqrtss`) over every exponent, both
    /// signs, zeros, subnormals, infinities and NaN (any NaN for a NaN), and 2^24
    /// consecutive patterns from 1 (two binades of significands).
    #[test]
    fn sqrtf_is_libm_sqrtf() {
        let check = |bits: u32| {
            let x = f32::from_bits(bits);
            let (ours, theirs) = (sqrtf(x), libm::sqrtf(x));
            assert!(
                ours.to_bits() == theirs.to_bits() || (ours.is_nan() && theirs.is_nan()),
                "{x:e} ({bits:#x}): {ours:e} against {theirs:e}"
            );
        };
        for exponent in 0..256u32 {
            for low in [0u32, 1, 2, 0x3f_ffff, 0x40_0000, 0x7f_fffe, 0x7f_ffff] {
                for sign in [0u32, 0x8000_0000] {
                    check(sign | exponent << 23 | low);
                }
            }
        }
        for bits in 0x3f80_0000u32..0x3f80_0000 + (1 << 24) {
            check(bits);
        }
    }
}
