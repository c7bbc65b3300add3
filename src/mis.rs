//! Multiple importance sampling (MIS) heuristics: the balance and power heuristics
//! (Veach and Guibas 1995), the weighted balance heuristic and (clamped) optimal MIS
//! of Peters 2021 (supplement B).
//!
//! # The estimator
//!
//! Techniques `k = 0..N` with densities `p_k` (per steradian) each draw one sample
//! `ω_k`. The MIS estimate of `∫ f` is
//!
//! ```text
//! F = Σ_j w_j(ω_j) f(ω_j) / p_j(ω_j),
//! ```
//!
//! unbiased whenever the weights sum to one, `Σ_j w_j(ω) = 1`, at every `ω` where
//! `f(ω) != 0`, and `w_j = 0` where `p_j = 0`. (For `n_k` samples of technique `k`,
//! pass `n_k p_k` as the pdfs and divide each sample's contribution by `n_j`.) A draw
//! that failed (`Sample::NONE`, such as a GGX reflection below the horizon) adds 0:
//! that keeps the estimate unbiased as long as `p_j` is the true density of the draws
//! that did not fail; do not renormalise it.
//!
//! Peters 2021 (supplement B) looks at integrands of the form
//! `f(ω) = V(ω) Σ_k c_k p_k(ω)`, exact when the densities are perfect fits of the
//! unoccluded integrand (linearly transformed cosines of the BRDF times cosine, and a
//! Lambertian light): `c_k >= 0` is the unoccluded contribution of technique `k` (its
//! share of the integral without occlusion), `V` the visibility. The functions here
//! take the `c_k` in the same units as `f` (for RGB, use per-channel values or a
//! luminance). Optimal MIS (Kondapaneni et al. 2019) under the supplement's assumption
//! that visibility scales every technique alike (`b = v A c`, a scalar `v ∈ [0, 1]`)
//! has the coefficients `α = v c`, which gives [`optimal_mis_contribution`];
//! dropping its zero-mean term for occluded samples gives
//! [`clamped_optimal_mis_contribution`].
//!
//! # Conventions for bad, zero and infinite input
//!
//! All functions take the densities of all techniques at the sample, `pdfs`, and the
//! index `j` of the technique that drew it (`pdfs[j]` is its own density).
//!
//! - A NaN or negative pdf counts as 0. A technique whose pdf is 0 at the sample gets
//!   weight 0 (and contribution 0); if all pdfs are 0, every weight is 0.
//! - An infinite pdf is treated as the limit of a density that grows without bound, all
//!   infinite ones at the same rate: the techniques with infinite pdf share the weight
//!   (equally for the balance and power heuristics, in proportion to `c_k` for the
//!   weighted forms) and the others get 0. The weights still sum to one. (A
//!   contribution `f / p_j` with infinite `p_j` is 0.)
//! - Unoccluded contributions `c_k` that are NaN, negative or infinite count as 0.
//!   Where `Σ c_k p_k = 0` the weighted balance heuristic is undefined (0/0); it falls
//!   back to the balance heuristic there, which keeps the weights summing to one.
//!   (Any choice of weights summing to one at each point, made from the values at that
//!   point alone, keeps the estimator unbiased.)
//! - `v` outside `[0, 1]` is clamped, NaN counts as 0 (the balance heuristic).
//! - A contribution (`f` times a weight over a pdf) that is not finite, because `f` is
//!   not finite or the result overflows `f32`, is returned as 0: the sample is
//!   discarded. No function returns NaN or an infinity.
//! - Slices of different lengths: only the first `min(pdfs.len(), contributions.len())`
//!   techniques take part; `j` beyond them gives 0.
//!
//! Weights are computed from the pdfs divided by their largest value, so that neither
//! `Σ p_k` nor `Σ p_k²` overflows or underflows for pdfs anywhere in the `f32` range.
//!
//! Hard cases, each tested below: pdfs of 0, NaN, negative, infinite, subnormal and
//! near `f32::MAX`; all pdfs 0; `Σ c_k p_k = 0`; `c` NaN and infinite; `v` outside
//! `[0, 1]` and NaN; unbiasedness with an occluder and with an integrand not of the form
//! `V Σ c_k p_k`, with techniques that vanish on parts of the domain.

use glam::Vec3A;

/// The default visibility estimate `v = 1/2` of clamped optimal MIS (Peters 2021).
pub const DEFAULT_VISIBILITY: f32 = 0.5;

/// A pdf as the heuristics read it: NaN and negative values are 0; `+inf` stays.
#[inline(always)]
fn pdf_value(p: f32) -> f32 {
    if p > 0.0 { p } else { 0.0 }
}

/// An unoccluded contribution as the heuristics read it: finite and non-negative, or 0.
#[inline(always)]
fn contribution_value(c: f32) -> f32 {
    if c > 0.0 && c.is_finite() { c } else { 0.0 }
}

/// The pdfs rescaled by their largest value: `r_k = p_k / max p` in `[0, 1]`, or, when
/// some pdf is infinite, `r_k = 1` for the infinite ones and 0 for the others (the
/// limit described in the module documentation).
#[derive(Clone, Copy)]
struct Scale {
    /// The largest pdf, finite and positive (unused when `infinite`).
    largest: f32,
    infinite: bool,
}

impl Scale {
    /// `None` when every pdf is 0 (or NaN, or negative).
    #[inline(always)]
    fn of(pdfs: &[f32]) -> Option<Scale> {
        let mut largest = 0.0f32;
        for &p in pdfs {
            largest = largest.max(pdf_value(p));
        }
        if !(largest > 0.0) {
            return None;
        }
        Some(Scale {
            largest,
            infinite: largest == f32::INFINITY,
        })
    }

    #[inline(always)]
    fn ratio(self, p: f32) -> f32 {
        let p = pdf_value(p);
        if self.infinite {
            if p == f32::INFINITY { 1.0 } else { 0.0 }
        } else {
            p / self.largest
        }
    }

    /// `Σ_k r_k`, at least 1.
    #[inline(always)]
    fn sum(self, pdfs: &[f32]) -> f32 {
        pdfs.iter().map(|&p| self.ratio(p)).sum()
    }
}

/// The largest unoccluded contribution, or 0.
#[inline(always)]
fn largest_contribution(contributions: &[f32]) -> f32 {
    contributions
        .iter()
        .fold(0.0f32, |m, &c| m.max(contribution_value(c)))
}

/// The balance heuristic `w_j = p_j / Σ_k p_k` (Veach and Guibas 1995) for the sample
/// of technique `j`. With it, the MIS estimator's contribution `w_j f / p_j` is
/// `f / Σ_k p_k`: every sample is weighted as if drawn from the mixture of the
/// techniques. Provably not far from optimal (Veach's theorem 9.2).
///
/// Conventions (module documentation): NaN and negative pdfs count as 0, `p_j = 0`
/// gives 0, all pdfs 0 gives 0; infinite pdfs share the weight equally. The weights of
/// all `j` sum to one wherever some pdf is positive.
#[inline]
pub fn balance_heuristic(pdfs: &[f32], j: usize) -> f32 {
    let (Some(&p), Some(scale)) = (pdfs.get(j), Scale::of(pdfs)) else {
        return 0.0;
    };
    scale.ratio(p) / scale.sum(pdfs)
}

/// The power heuristic with exponent 2, `w_j = p_j² / Σ_k p_k²` (Veach and Guibas
/// 1995), for the sample of technique `j`: closer to 1 for the technique with the
/// largest density than the balance heuristic, which lowers variance where one
/// technique fits the integrand much better. Computed from `p_k / max p`, so that the
/// squares neither overflow nor underflow.
///
/// Conventions as for [`balance_heuristic`]; the weights sum to one wherever some pdf
/// is positive.
#[inline]
pub fn power_heuristic(pdfs: &[f32], j: usize) -> f32 {
    let (Some(&p), Some(scale)) = (pdfs.get(j), Scale::of(pdfs)) else {
        return 0.0;
    };
    let r = scale.ratio(p);
    let sum: f32 = pdfs
        .iter()
        .map(|&p| {
            let r = scale.ratio(p);
            r * r
        })
        .sum();
    r * r / sum
}

/// `c'_j r_j / Σ_k c'_k r_k` with `c' = c / max c` and `r = p / max p`, or `None`
/// where `Σ_k c_k p_k = 0` (including when every `c` is 0).
#[inline(always)]
fn weighted_share(
    pdfs: &[f32],
    contributions: &[f32],
    scale: Scale,
    largest_c: f32,
    j: usize,
) -> Option<f32> {
    if !(largest_c > 0.0) {
        return None;
    }
    let term = |k: usize| contribution_value(contributions[k]) / largest_c * scale.ratio(pdfs[k]);
    let sum: f32 = (0..pdfs.len()).map(term).sum();
    (sum > 0.0).then(|| term(j) / sum)
}

/// The weighted balance heuristic of Peters 2021, `w_j = c_j p_j / Σ_k c_k p_k`, for the
/// sample of technique `j`, with `c_k >= 0` the unoccluded contribution of technique
/// `k`. For an integrand `f = V Σ_k c_k p_k` the contribution `w_j f / p_j` is
/// `V c_j`: without occlusion (`V = 1`) the MIS estimator `Σ_j c_j` has zero variance
/// (when the densities integrate to one; a failed draw contributes 0 instead of `c_j`).
///
/// Only the first `min(pdfs.len(), contributions.len())` techniques take part.
/// Conventions (module documentation): NaN and negative pdfs count as 0, and `p_j = 0`
/// gives 0; NaN, negative and infinite `c` count as 0; where `Σ_k c_k p_k = 0` this is
/// the balance heuristic; infinite pdfs share the weight in proportion to `c`. The
/// weights of all `j` sum to one wherever some pdf is positive.
#[inline]
pub fn weighted_balance_heuristic(pdfs: &[f32], contributions: &[f32], j: usize) -> f32 {
    let n = pdfs.len().min(contributions.len());
    let (pdfs, contributions) = (&pdfs[..n], &contributions[..n]);
    let (Some(&p), Some(scale)) = (pdfs.get(j), Scale::of(pdfs)) else {
        return 0.0;
    };
    if scale.ratio(p) == 0.0 {
        return 0.0;
    }
    let largest_c = largest_contribution(contributions);
    weighted_share(pdfs, contributions, scale, largest_c, j)
        .unwrap_or_else(|| scale.ratio(p) / scale.sum(pdfs))
}

/// The weight of clamped optimal MIS (Peters 2021, supplement B.3) for the sample of
/// technique `j`:
///
/// ```text
/// w_j = p_j (v c_j / Σ_k c_k p_k + (1 - v) / Σ_k p_k)
///     = v (weighted balance)_j + (1 - v) (balance)_j,
/// ```
///
/// with `v ∈ [0, 1]` an estimate of the visibility ([`DEFAULT_VISIBILITY`] = 1/2 in
/// the paper). `v = 0` is the balance heuristic, `v = 1` the weighted balance
/// heuristic. The weights of all `j` sum to one wherever some pdf is positive; the
/// contribution is `w_j f / p_j` (see [`clamped_optimal_mis_contribution`]).
///
/// Conventions as for [`weighted_balance_heuristic`]; `v` is clamped to `[0, 1]`, NaN
/// counts as 0.
#[inline]
pub fn clamped_optimal_mis_weight(
    pdfs: &[f32],
    contributions: &[f32],
    visibility: f32,
    j: usize,
) -> f32 {
    let v = visibility.max(0.0).min(1.0);
    let n = pdfs.len().min(contributions.len());
    let balance = balance_heuristic(&pdfs[..n], j);
    if balance == 0.0 {
        return 0.0;
    }
    let weighted = weighted_balance_heuristic(pdfs, contributions, j);
    v * weighted + (1.0 - v) * balance
}

/// The contribution `f(ω_j) w_j / p_j(ω_j)` of a sample of technique `j` under clamped
/// optimal MIS (Peters 2021, supplement B.3), computed without dividing by `p_j`:
///
/// ```text
/// f (v c_j / Σ_k c_k p_k + (1 - v) / Σ_k p_k).
/// ```
///
/// It is the contribution of optimal MIS ([`optimal_mis_contribution`]) rewritten for
/// `f = V Σ c_k p_k` as the part for visible samples,
/// `f (v c_j / Σ c p + (1 - v) / Σ p)`, plus the zero-mean part for occluded ones,
/// `(1 - V) v (c_j - Σ c p / Σ p)`, which is dropped because it is what puts noise
/// into umbras. The remaining weights still sum
/// to one (see [`clamped_optimal_mis_weight`]), so the estimate is unbiased for every
/// integrand `f` and every `v`. Add the contributions of the samples of all techniques
/// (one sample each).
///
/// Conventions as for [`clamped_optimal_mis_weight`]; `p_j = 0` or an infinite pdf
/// gives 0, where `Σ_k c_k p_k = 0` the balance heuristic's `f / Σ_k p_k` is used, and a
/// non-finite `f` or result gives 0.
#[inline]
pub fn clamped_optimal_mis_contribution(
    f: f32,
    pdfs: &[f32],
    contributions: &[f32],
    visibility: f32,
    j: usize,
) -> f32 {
    let v = visibility.max(0.0).min(1.0);
    let n = pdfs.len().min(contributions.len());
    let (pdfs, contributions) = (&pdfs[..n], &contributions[..n]);
    let (Some(&p), Some(scale)) = (pdfs.get(j), Scale::of(pdfs)) else {
        return 0.0;
    };
    // An infinite Σ p makes every term 0 (and f / p_j is 0 for an infinite p_j).
    if pdf_value(p) == 0.0 || scale.infinite || !f.is_finite() {
        return 0.0;
    }
    // Σ p = m Σ r and Σ c p = m c_max Σ c' r, so both terms share the factor f / m.
    let largest_c = largest_contribution(contributions);
    let inverse_sum = 1.0 / scale.sum(pdfs);
    let factor = if largest_c > 0.0 {
        let term =
            |k: usize| contribution_value(contributions[k]) / largest_c * scale.ratio(pdfs[k]);
        let sum: f32 = (0..n).map(term).sum();
        if sum > 0.0 {
            v * (contribution_value(contributions[j]) / largest_c) / sum + (1.0 - v) * inverse_sum
        } else {
            inverse_sum
        }
    } else {
        inverse_sum
    };
    finite_or_zero(f / scale.largest * factor)
}

/// The contribution of a sample `ω_j` of technique `j` under optimal MIS as specialised
/// by Peters 2021 (supplement B.1, the contribution derived from the optimal weights):
///
/// ```text
/// f(ω_j) w_j / p_j = v c_j + (f(ω_j) - v Σ_k c_k p_k(ω_j)) / Σ_k p_k(ω_j),
/// ```
///
/// i.e. the optimal weights of Kondapaneni et al. 2019 with coefficients `α = v c`.
/// This is a **contribution**, already divided by the pdf, not a weight; it can be
/// negative, and it is non-zero even where `f = 0` (occluded samples): the supplement
/// defines `f / f = 1` there. The estimate (the sum over the techniques' samples, one
/// each) is unbiased for every integrand `f` and every `v` independent of the samples:
/// `f / Σ p` is the balance heuristic's contribution, and the rest,
/// `v (c_j - Σ c p / Σ p)`, has zero mean (supplement B.2) over any set of sample
/// points, so also when draws that failed (below the horizon) add 0 — which they must:
/// a failed draw contributes 0, not `v c_j`.
///
/// Conventions (module documentation): `p_j = 0` gives 0; infinite pdfs make
/// `f / Σ p` 0 and `Σ c p / Σ p` the mean of `c` over the infinite techniques (the
/// limit, which leaves `v (c_j - mean)` also for a finite `p_j`); a non-finite `f` or
/// result gives 0; `v` is clamped to `[0, 1]`, NaN counts as 0.
#[inline]
pub fn optimal_mis_contribution(
    f: f32,
    pdfs: &[f32],
    contributions: &[f32],
    visibility: f32,
    j: usize,
) -> f32 {
    let v = visibility.max(0.0).min(1.0);
    let n = pdfs.len().min(contributions.len());
    let (pdfs, contributions) = (&pdfs[..n], &contributions[..n]);
    let (Some(&p), Some(scale)) = (pdfs.get(j), Scale::of(pdfs)) else {
        return 0.0;
    };
    if pdf_value(p) == 0.0 || !f.is_finite() {
        return 0.0;
    }
    let sum = scale.sum(pdfs);
    // Σ c p / Σ p = c_max Σ (c / c_max) r / Σ r: a convex combination of the c_k.
    let largest_c = largest_contribution(contributions);
    let mean_c = if largest_c > 0.0 {
        let weighted: f32 = (0..n)
            .map(|k| contribution_value(contributions[k]) / largest_c * scale.ratio(pdfs[k]))
            .sum();
        largest_c * (weighted / sum)
    } else {
        0.0
    };
    let balance = if scale.infinite {
        0.0
    } else {
        f / scale.largest / sum
    };
    finite_or_zero(v * (contribution_value(contributions[j]) - mean_c) + balance)
}

/// The pdfs of two techniques as [`Scale`] reads them, for the sample of technique `j`
/// with its own pdf `p_j` positive and finite and the other's, `p_{1-j}`, `+0` or
/// positive and finite (every sampler's pdf; [`TwoPdfs::new`] returns `None`
/// otherwise): the ratios `r_k = p_k / max p` and their sum, with the same bits as
/// `Scale::ratio` and `Scale::sum` but one division instead of two. The largest pdf's
/// own ratio `max p / max p` is exactly 1 (IEEE division is correctly rounded, and
/// `x / x = 1` for every finite positive `x`, subnormal too), so only the other ratio
/// is divided; `Σ r` is added as `Scale::sum` does, `(0 + r_0) + r_1`, which is
/// `r_0 + r_1` (adding a ratio `>= 0` to 0 is exact), in either order (IEEE addition is
/// commutative). For the polygon light's heuristics (issue 18, 3).
#[derive(Clone, Copy)]
pub(crate) struct TwoPdfs {
    /// `r_j`.
    own_ratio: f32,
    /// Whether `p_j >= p_{1-j}` (then `r_j = 1`), and the smaller pdf over the larger.
    own_largest: bool,
    ratio: f32,
    /// `r_0 + r_1`, at least 1.
    sum: f32,
    /// `max p`.
    largest: f32,
    /// The sample's technique, 0 or 1.
    j: usize,
}

impl TwoPdfs {
    /// The pdfs `own = p_j` and `other = p_{1-j}` of the sample of technique `j` (0 or
    /// 1; larger counts as 1); `None` unless `0 < own < ∞` and `0 <= other < ∞` with
    /// `other` not `-0`. Both tests on the bits, two integer comparisons (as float
    /// comparisons, the compiler classified the bits in a dozen instructions): the
    /// patterns of `+0` to `f32::MAX` are `0` to `0x7f7f_ffff`, and every negative
    /// value, `-0`, the infinities and the NaNs lie above (`-0` is left to the scalar
    /// functions, which read it as `+0`, only so that no ratio is `-0` here).
    #[inline(always)]
    pub(crate) fn new(own: f32, other: f32, j: usize) -> Option<Self> {
        if !(crate::math::is_positive_finite(own) && other.to_bits() < 0x7f80_0000) {
            return None;
        }
        // `max(p_0, p_1)` as `Scale::of` finds it (no NaN here), and the other pdf's
        // ratio to it. Which pdf is larger is up to the sample: no branch (one around
        // the division was mispredicted about every other sample). The larger and the
        // smaller pdf in the forms of `maxss` and `minss` (`a > b ? a : b`,
        // `a < b ? a : b`; for equal pdfs, both of the same bits, either is right), the
        // ratio `r_j` by a mask (`select_bits`).
        let own_largest = own >= other;
        let largest = if own > other { own } else { other };
        let smaller = if own < other { own } else { other };
        let ratio = smaller / largest;
        Some(TwoPdfs {
            own_ratio: crate::math::select_bits(own_largest, 1.0, ratio),
            own_largest,
            ratio,
            // `r_j + r_{1-j}` is `1 + ratio` in one order or the other: no selection.
            sum: 1.0 + ratio,
            largest,
            j: j.min(1),
        })
    }

    /// `[r_0, r_1]`.
    #[inline(always)]
    fn ratios(&self) -> [f32; 2] {
        let other_ratio = crate::math::select_bits(self.own_largest, self.ratio, 1.0);
        if self.j == 0 {
            [self.own_ratio, other_ratio]
        } else {
            [other_ratio, self.own_ratio]
        }
    }

    /// [`balance_heuristic`] divided by the sample's own pdf, `(r_j / Σ r) / p_j` (the
    /// bits of `balance_heuristic(&pdfs, j) / pdfs[j]`): `f / Σ p` as a factor of `f`.
    #[inline(always)]
    pub(crate) fn balance_over_pdf(&self, p_j: f32) -> f32 {
        self.own_ratio / self.sum / p_j
    }
}

/// The weighted heuristics of two techniques for all three colour channels at once:
/// [`weighted_balance_heuristic`], [`clamped_optimal_mis_contribution`] and
/// [`optimal_mis_contribution`] evaluated per channel with per-channel contributions
/// `c_0`, `c_1`, four lanes wide, with the same operations in the same order as the
/// scalar functions, so that each channel is bit for bit their result (tested). For the
/// polygon light (issue 18, 3), whose three scalar evaluations with slices repeated
/// the pdfs' scaling per channel.
///
/// Valid for pdfs `p_j > 0` and `p_{1-j} >= 0`, both finite (every sampler's pdf):
/// made from a [`TwoPdfs`], whose `new` returns `None` otherwise, and the caller takes
/// the scalar functions.
#[derive(Clone, Copy)]
pub(crate) struct TwoTechniques {
    /// `r_k = p_k / max p`.
    ratios: [f32; 2],
    /// `r_0 + r_1` (at least 1) and its reciprocal.
    sum: f32,
    inverse_sum: f32,
    /// `max p`.
    largest: f32,
    /// The sample's technique.
    j: usize,
    /// `c_k` with NaN, negative and infinite entries as 0 (`contribution_value`).
    c: [Vec3A; 2],
    /// `max(c_0, c_1)` per channel.
    largest_c: Vec3A,
    /// `Σ_k (c_k / max c) r_k` per channel (NaN where `max c = 0`).
    weighted_sum: Vec3A,
}

/// `contribution_value` per lane: `c` where `0 < c < ∞`, else 0.
#[inline(always)]
fn contribution_values(c: Vec3A) -> Vec3A {
    Vec3A::select(
        c.cmpgt(Vec3A::ZERO) & c.cmplt(Vec3A::INFINITY),
        c,
        Vec3A::ZERO,
    )
}

/// Lanes of `x` that are finite, 0 elsewhere (`finite_or_zero` per lane).
#[inline(always)]
fn finite_or_zero_lanes(x: Vec3A) -> Vec3A {
    Vec3A::select(x.is_finite_mask(), x, Vec3A::ZERO)
}

impl TwoTechniques {
    /// The shared terms for the sample whose two pdfs `pdfs` has read, with per-channel
    /// contributions `contributions`.
    #[inline(always)]
    pub(crate) fn new(pdfs: TwoPdfs, contributions: [Vec3A; 2]) -> Self {
        // As `Scale`: the largest pdf and the ratios to it; their sum is at least 1.
        let ratios = pdfs.ratios();
        let TwoPdfs {
            sum, largest, j, ..
        } = pdfs;
        let c = [
            contribution_values(contributions[0]),
            contribution_values(contributions[1]),
        ];
        let largest_c = Vec3A::ZERO.max(c[0]).max(c[1]);
        // As `weighted_share`'s sum, `0 + term_0 + term_1` (the iterator's sum starts at 0).
        let weighted_sum =
            Vec3A::ZERO + c[0] / largest_c * ratios[0] + c[1] / largest_c * ratios[1];
        TwoTechniques {
            ratios,
            sum,
            inverse_sum: 1.0 / sum,
            largest,
            j,
            c,
            largest_c,
            weighted_sum,
        }
    }

    /// Where the weighted share `c_j r_j / Σ c r` exists (`max c > 0` and `Σ > 0`).
    #[inline(always)]
    fn weighted(&self) -> glam::BVec3A {
        self.largest_c.cmpgt(Vec3A::ZERO) & self.weighted_sum.cmpgt(Vec3A::ZERO)
    }

    /// `f (w_j / p_j)` per channel with `w_j` [`weighted_balance_heuristic`].
    #[inline(always)]
    pub(crate) fn weighted_balance(&self, f: Vec3A, p_j: f32) -> Vec3A {
        let r = self.ratios[self.j];
        let share = self.c[self.j] / self.largest_c * r / self.weighted_sum;
        let balance = Vec3A::splat(r / self.sum);
        f * (Vec3A::select(self.weighted(), share, balance) / p_j)
    }

    /// [`clamped_optimal_mis_contribution`] per channel, for `f` and visibility `v`.
    #[inline(always)]
    pub(crate) fn clamped_optimal(&self, f: Vec3A, visibility: f32) -> Vec3A {
        let v = visibility.max(0.0).min(1.0);
        let blended = v * (self.c[self.j] / self.largest_c) / self.weighted_sum
            + (1.0 - v) * self.inverse_sum;
        let factor = Vec3A::select(self.weighted(), blended, Vec3A::splat(self.inverse_sum));
        let contribution = finite_or_zero_lanes(f / self.largest * factor);
        // A non-finite f gives 0 (checked before the product in the scalar form).
        Vec3A::select(f.is_finite_mask(), contribution, Vec3A::ZERO)
    }

    /// [`optimal_mis_contribution`] per channel with `f = 0`: the part of optimal MIS
    /// that does not depend on visibility, `v (c_j − Σ c p / Σ p)`.
    #[inline(always)]
    pub(crate) fn optimal_unoccluded(&self, visibility: f32) -> Vec3A {
        let v = visibility.max(0.0).min(1.0);
        let mean_c = Vec3A::select(
            self.largest_c.cmpgt(Vec3A::ZERO),
            self.largest_c * (self.weighted_sum / self.sum),
            Vec3A::ZERO,
        );
        // `+ 0`: the scalar form adds its balance term, `0 / max p / Σ r`.
        finite_or_zero_lanes(v * (self.c[self.j] - mean_c) + Vec3A::ZERO)
    }
}

#[inline(always)]
fn finite_or_zero(x: f32) -> f32 {
    if x.is_finite() { x } else { 0.0 }
}

#[cfg(test)]
#[path = "mis_tests.rs"]
mod tests;
