//! The result of drawing one sample.

use glam::{Vec3, Vec4};

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
/// ([`pad_unselectable`]), so that no count is compared: branch-free. `<=` skips pieces
/// of zero size; the result is at most `N - 1` whatever the array holds (a corrupted
/// prepared value gives a wrong piece, never an index out of bounds), and NaN starts
/// are never selected.
///
/// Where the target has `popcnt` (x86-64 built for a CPU that has it) and the starts
/// fill groups of four (a projected polygon's 8 sectors), the comparisons run four
/// lanes at a time ([`select_piece_by_lanes`]): the serial chain of 7 `sbb` that adds
/// the scalar comparisons becomes two lane comparisons, their masks and one `popcnt`
/// (projected hexagons, native: 27.5 -> 25.1 ns per sample). Elsewhere the scalar
/// comparisons stay: without `popcnt` the count of set bits is a dozen operations (or
/// a table look-up, longer on the chain than the `sbb`s: 26.3 -> 26.9 ns), and 6
/// starts (a solid angle polygon's fan), which the compiler already compares four at a
/// time and one alone, took 0.5 ns longer by lanes.
#[inline(always)]
pub(crate) fn select_piece<const N: usize>(starts: &[f32; N], target: f32) -> usize {
    if selects_by_lanes(N) {
        select_piece_by_lanes(starts, target)
    } else {
        select_piece_by_comparisons(starts, target)
    }
}

/// Whether [`select_piece`] compares `n` starts by lanes: with `popcnt`, for whole
/// groups of four.
const fn selects_by_lanes(n: usize) -> bool {
    cfg!(all(target_arch = "x86_64", target_feature = "popcnt")) && n % 4 == 0
}

/// [`select_piece`] by scalar comparisons, one per start among `1..N`.
#[inline(always)]
fn select_piece_by_comparisons<const N: usize>(starts: &[f32; N], target: f32) -> usize {
    let mut k = 0usize;
    #[allow(clippy::needless_range_loop)] // an index loop that the compiler unrolls
    for j in 1..N {
        k += (starts[j] <= target) as usize;
    }
    k
}

/// [`select_piece`] by lanes, for `N` a multiple of 4 (at most 32): each group of four
/// starts against the target (`cmpleps`, the scalar `<=` lane by lane, false for a NaN
/// start or target as there), each comparison's bit at its start's index `j` in one
/// integer mask, `start[0]`'s bit cleared (piece 0 is not counted), and `k` the number
/// of set bits: the same `k` as [`select_piece_by_comparisons`] for every input (tested
/// exhaustively over adversarial starts: `select_piece_counts_as_the_scalar_comparisons`).
/// The mask has `N - 1` bits that may be set, so the compiler knows `k < N` (no bounds
/// check on the loads that `k` indexes, for `N = 8`).
#[inline(always)]
fn select_piece_by_lanes<const N: usize>(starts: &[f32; N], target: f32) -> usize {
    debug_assert!(N % 4 == 0 && N <= 32);
    let target = Vec4::splat(target);
    let mut mask = 0u32;
    for (g, group) in starts.chunks_exact(4).enumerate() {
        mask |= Vec4::from_slice(group).cmple(target).bitmask() << (4 * g);
    }
    (mask & !1).count_ones() as usize
}

/// Writes `+∞` into the starts of the pieces from `selectable` on, which
/// [`select_piece`] then never selects (a finite target is below them).
#[inline(always)]
pub(crate) fn pad_unselectable<const N: usize>(starts: &mut [f32; N], selectable: u32) {
    for start in starts.iter_mut().skip(selectable as usize) {
        *start = f32::INFINITY;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition of [`select_piece`]: the number of starts among `1..N` at or
    /// below the target.
    fn scalar_count<const N: usize>(starts: &[f32; N], target: f32) -> usize {
        (1..N).filter(|&j| starts[j] <= target).count()
    }

    /// Every start from an adversarial set in every slot (NaN, ±∞, ±0, ties,
    /// decreasing runs), against targets from the same set and between: the same `k`.
    fn check_every_combination<const N: usize>() {
        const VALUES: [f32; 6] = [f32::NAN, f32::NEG_INFINITY, -0.0, 0.0, 1.0, f32::INFINITY];
        const TARGETS: [f32; 8] = [
            f32::NAN,
            f32::NEG_INFINITY,
            -0.0,
            0.0,
            0.5,
            1.0,
            2.0,
            f32::INFINITY,
        ];
        let mut starts = [0.0f32; N];
        for code in 0..VALUES.len().pow(N as u32) {
            let mut c = code;
            for start in starts.iter_mut() {
                *start = VALUES[c % VALUES.len()];
                c /= VALUES.len();
            }
            for target in TARGETS {
                let expected = scalar_count(&starts, target);
                if N % 4 == 0 {
                    let by_lanes = select_piece_by_lanes(&starts, target);
                    assert_eq!(by_lanes, expected, "{starts:?} {target}");
                }
                let by_comparisons = select_piece_by_comparisons(&starts, target);
                assert_eq!(by_comparisons, expected, "{starts:?} {target}");
                assert_eq!(
                    select_piece(&starts, target),
                    expected,
                    "{starts:?} {target}"
                );
            }
        }
    }

    #[test]
    fn select_piece_counts_as_the_scalar_comparisons() {
        check_every_combination::<1>();
        check_every_combination::<2>();
        check_every_combination::<3>();
        check_every_combination::<4>();
        check_every_combination::<6>();
        check_every_combination::<8>();
    }

    /// A projected polygon's 8 starts go by lanes where `popcnt` exists; a solid angle
    /// polygon's 6 and the small projected sampler's 6 never do.
    #[test]
    fn which_starts_select_by_lanes() {
        let popcnt = cfg!(all(target_arch = "x86_64", target_feature = "popcnt"));
        assert_eq!(selects_by_lanes(crate::MAX_POLYGON_VERTICES), popcnt);
        assert!(!selects_by_lanes(
            crate::polygon::solid_angle::MAX_TRIANGLES
        ));
        assert!(!selects_by_lanes(2) && !selects_by_lanes(1));
    }
}
