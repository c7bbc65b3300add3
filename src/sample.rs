//! The result of drawing one sample.

use glam::Vec3;

/// A sampled direction and its density with respect to solid angle (per steradian).
///
/// `pdf == 0` means that no sample could be drawn; `dir` is then still finite (it is
/// `(0, 0, 1)`), so that a caller that forgets to check never sees NaN.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Unit direction in the local frame.
    pub dir: Vec3,
    /// Density per steradian; 0 when there is no sample.
    pub pdf: f32,
}

impl Sample {
    /// The "no sample" value: a finite direction and `pdf == 0`.
    pub const NONE: Sample = Sample {
        dir: Vec3::Z,
        pdf: 0.0,
    };

    /// The sample `dir` with density `pdf`, or [`Sample::NONE`] where `pdf` is not
    /// positive (for example a cosine-weighted sampler's direction exactly on the
    /// horizon, where `cos θ = 0`), so that `pdf == 0` always comes with
    /// `dir = (0, 0, 1)` as documented above.
    #[inline(always)]
    pub fn new_or_none(dir: Vec3, pdf: f32) -> Sample {
        if pdf > 0.0 {
            Sample { dir, pdf }
        } else {
            Sample::NONE
        }
    }
}

/// The largest `f32` below one.
pub(crate) const ONE_MINUS_ULP: f32 = 1.0 - f32::EPSILON / 2.0;

/// A random number clamped into `[0, 1 - ulp]`, the domain of every sampler; NaN
/// becomes 0.
#[inline(always)]
pub(crate) fn clamp_random(u: f32) -> f32 {
    if u >= 0.0 { u.min(ONE_MINUS_ULP) } else { 0.0 }
}

/// The piece that a target value falls into, for pieces laid end to end with start
/// values `starts` (non-decreasing): the number of pieces among `1..selectable` that
/// start at or before `target`. Branch-free; `<=` skips pieces of zero size, and the
/// result is at most `selectable - 1` (0 when `selectable` is 0).
#[inline(always)]
pub(crate) fn select_piece<const N: usize>(
    starts: &[f32; N],
    selectable: u32,
    target: f32,
) -> usize {
    let mut k = 0usize;
    #[allow(clippy::needless_range_loop)] // an index loop that the compiler unrolls
    for j in 1..N {
        k += (j < selectable as usize && starts[j] <= target) as usize;
    }
    k
}
