//! C ABI, `sphera_vmf_*`: sampling of a normalised SG, the von Mises–Fisher distribution
//! (Tokuyoshi 2016, supplement Sec. 4). SGs are passed by value (see `sphera_sg_*`).
use super::types::{SpheraSample, SpheraVec3};
use crate::sg::sg::Sg;
use crate::sg::vmf::{vmf_invert, vmf_pdf, vmf_sample};

/// Draws a direction from the normalised SG (von Mises–Fisher distribution; the
/// amplitude is ignored). `u0`, `u1` in [0, 1) (clamped). pdf 0 (and `dir = (0, 0, 1)`)
/// for the zero SG built from an invalid axis.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_vmf_sample(sg: Sg, u0: f32, u1: f32) -> SpheraSample {
    // Not sanitised: an invalid axis must give "no sample" rather than the zero SG's
    // axis (`vmf_sample` checks the axis and clamps the sharpness itself).
    vmf_sample(&sg, [u0, u1]).into()
}

/// The density per steradian of `sphera_vmf_sample` at `dir` (normalised; 0 for a
/// zero or non-finite `dir`).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_vmf_pdf(sg: Sg, dir: SpheraVec3) -> f32 {
    vmf_pdf(&sg, dir.into())
}

/// Writes to `u[0]`, `u[1]` the random numbers that `sphera_vmf_sample` maps to
/// `dir` and returns true; returns false (writing nothing) for a null `u`, a zero or
/// non-finite `dir`, or an SG with an invalid axis.
///
/// # Safety
///
/// `u` must be null or point to two writable `float`s.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_vmf_invert(sg: Sg, dir: SpheraVec3, u: *mut f32) -> bool {
    if u.is_null() {
        return false;
    }
    match vmf_invert(&sg, dir.into()) {
        Some(values) => {
            // SAFETY: the caller guarantees two writable floats at `u`.
            unsafe {
                u.write(values[0]);
                u.add(1).write(values[1]);
            }
            true
        }
        None => false,
    }
}
