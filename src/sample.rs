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

/// The fractions of the way towards a point inside a light by which a sample that
/// rounding put just outside (where the light's `pdf` is 0) is pulled in, one after the
/// other until inside: 2⁻²⁰, 2⁻¹⁴, 2⁻⁸ and 2⁻⁴ of the way, then the inner point itself,
/// for lights too small for `f32` directions to resolve. Only such samples move, and they
/// keep `pdf(sample.dir) == sample.pdf` (issue 16: small caps, Turk's and projected
/// sampling's small polygons).
pub(crate) const INWARD_PULLS: [f32; 5] = [
    1.0 / 1_048_576.0,
    1.0 / 16_384.0,
    1.0 / 256.0,
    1.0 / 16.0,
    1.0,
];

/// The largest `f32` below one.
pub(crate) const ONE_MINUS_ULP: f32 = 1.0 - f32::EPSILON / 2.0;

/// A random number clamped into `[0, 1 - ulp]`, the domain of every sampler; NaN
/// becomes 0.
#[inline(always)]
pub(crate) fn clamp_random(u: f32) -> f32 {
    if u >= 0.0 { u.min(ONE_MINUS_ULP) } else { 0.0 }
}

/// A random number recovered by an inverse, clamped into `[0, 1 − ulp]`, the domain of
/// every sampler; NaN and ±∞ become 0.
#[inline(always)]
pub(crate) fn clamp_inverted(x: f32) -> f32 {
    if x.is_finite() {
        x.max(0.0).min(ONE_MINUS_ULP)
    } else {
        0.0
    }
}

/// The piece that a target value falls into, for pieces laid end to end with start
/// values `starts`: the number of pieces among `1..N` that start at or before `target`.
/// The starts are non-decreasing up to the last selectable piece and `+∞` from there on
/// ([`pad_unselectable`]), so that no count is compared: branch-free, 5 comparisons for
/// a hexagon's fan. `<=` skips pieces of zero size; the result is at most `N - 1`
/// whatever the array holds (a corrupted prepared value gives a wrong piece, never an
/// index out of bounds), and NaN starts are never selected.
#[inline(always)]
pub(crate) fn select_piece<const N: usize>(starts: &[f32; N], target: f32) -> usize {
    let mut k = 0usize;
    #[allow(clippy::needless_range_loop)] // an index loop that the compiler unrolls
    for j in 1..N {
        k += (starts[j] <= target) as usize;
    }
    k
}

/// Writes `+∞` into the starts of the pieces from `selectable` on, which
/// [`select_piece`] then never selects (a finite target is below them).
#[inline(always)]
pub(crate) fn pad_unselectable<const N: usize>(starts: &mut [f32; N], selectable: u32) {
    for start in starts.iter_mut().skip(selectable as usize) {
        *start = f32::INFINITY;
    }
}
