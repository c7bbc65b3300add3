//! The sectors of the central case of Algorithm 4 (Peters 2021, supplement A.7) as rows
//! of lanes (structure of arrays): one row per quantity, one slot per sector (issue 15).
//!
//! A central sector needs a handful of the 46 words of an
//! [`EllipseSector`](super::ellipse_sector::EllipseSector); written as such records from
//! four sectors' lanes, each sector was a transposition and a record of mostly constant
//! words (about 35 instructions per sector). Here preparation writes each quantity of
//! four sectors with one 16-byte store, and the per-sample constants that do not depend
//! on the sample are computed once per sector instead of once per sample: the two
//! directions that span the sector's arc and their dot products with `u`, already divided
//! by the ellipse norm `√(wᵀ C w)`, which is the same at every point of the arc (see
//! [`CentralSectors::sample`]).

use super::ellipse::{add2, det2, dot2, scale2};
use super::ellipse_sector::EllipseSector;
use crate::MAX_POLYGON_VERTICES;
use crate::math::{LANES, difference_of_products4, store4};
use glam::{BVec4A, Vec4};

type Vec2 = [f32; 2];

/// One quantity of each sector (slots past the sectors 0).
type Row = [f32; MAX_POLYGON_VERTICES];

/// The central sectors: sector `j` reaches from the origin along `s0` to `s1` out to the
/// outer ellipse `u` (the ellipse of its edge). The first rows are what
/// [`sample`](Self::sample) reads, the others what the sector's `EllipseSector` held
/// (for [`sector`](Self::sector), which the baseline of Arvo and the tests read).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CentralSectors {
    /// `â = s0 / √(1 + t0²)`: `√|C| s0` over the ellipse norm `√(wᵀ C w) = √|C| √(1 + t0²)`
    /// of the arc's points (see [`sample`](Self::sample)): x and y rows (finite, as `t0`
    /// is).
    a_hat: [Row; 2],
    /// `b̂ = R C s0 / (√|C| √(1 + t0²))` for `C = I + u uᵀ` (the ellipse's matrix; `R` the
    /// rotation by +90°): the direction at the right angle to `s0` in the circle's
    /// coordinates, mapped back and divided by the same norm. 0 where not finite (a
    /// degenerate ellipse, whose sector has zero area and is never sampled).
    b_hat: [Row; 2],
    /// `2k = 2 √|C| = 2 √(1 + |u|²)`, the factor from the area to the angle in the
    /// circle's coordinates (doubling is exact, so `k` is `0.5` times it bit for bit).
    two_k: Row,
    /// `u · â = t0 / √(1 + t0²)` (finite, in [-1, 1]).
    at_hat: Row,
    /// `u · b̂ = det(s0, u) / (√|C| √(1 + t0²))` (`det(s0, u)` by Kahan's difference of
    /// products, as `det2`); 0 where not finite.
    bt_hat: Row,
    /// `s0`, the clockwise boundary (unit direction): x and y rows.
    s0: [Row; 2],
    /// `t0 = u · s0`, from the vertex positions.
    t0: Row,
    /// `s1`, the counter-clockwise boundary: x and y rows.
    s1: [Row; 2],
    /// `det(s0, s1)` from the vertex positions.
    det: Row,
    /// The outer ellipse `u`: x and y rows.
    outer: [Row; 2],
    /// `t1 = u · s1`, from the vertex positions.
    t1: Row,
    // `s0 · s1` and `1 / det(s0, s1)`, which the sector's `EllipseSector` also holds,
    // are not rows: [`sector`](Self::sector) computes them from the rows `s0` and `s1`
    // (the sampler never reads them; as rows they cost the preparation a difference of
    // products with its error-free products and a division per four sectors, issue 15).
}

/// The 4-byte words of [`CentralSectors`] (16 rows of 8 slots).
pub(crate) const CENTRAL_WORDS: usize = 16 * MAX_POLYGON_VERTICES;
const _: () = assert!(core::mem::size_of::<CentralSectors>() == 4 * CENTRAL_WORDS);

/// Four sectors' values as lanes, as the two central paths of the preparation compute
/// them (the arguments of [`EllipseSector::new_central`], lane by lane).
pub(crate) struct CentralLanes {
    pub(crate) s0: [Vec4; 2],
    pub(crate) s1: [Vec4; 2],
    pub(crate) det: Vec4,
    pub(crate) outer: [Vec4; 2],
    pub(crate) outer_dots: [Vec4; 2],
    pub(crate) root_det: Vec4,
}

/// The lanes of the four slots from `first` that hold one of `count` sectors (all four
/// where `count - first >= 4`).
#[inline(always)]
pub(crate) fn lanes_kept(first: usize, count: usize) -> BVec4A {
    // Compares the lane indices with count - first (both small integers, exact in f32;
    // converted through `i32`, one signed conversion, where a `usize` takes a branch for
    // the sign bit). Saturating: a group past the polygon keeps no lane (and a debug
    // build does not panic on the subtraction).
    let remaining = count.saturating_sub(first) as i32 as f32;
    Vec4::new(0.0, 1.0, 2.0, 3.0).cmplt(Vec4::splat(remaining))
}

/// [`lanes_kept`] of both groups of four slots, `[lanes_kept(0, count),
/// lanes_kept(4, count)]` (`count` at most 8): the slot indices of each group compared
/// with `count` itself (small integers, exact in f32), one conversion for the two groups
/// and no subtraction.
#[inline(always)]
pub(crate) fn both_groups_kept(count: usize) -> [BVec4A; 2] {
    let count = Vec4::splat(count as i32 as f32);
    [
        Vec4::new(0.0, 1.0, 2.0, 3.0).cmplt(count),
        Vec4::new(4.0, 5.0, 6.0, 7.0).cmplt(count),
    ]
}

impl CentralSectors {
    /// Writes the sectors `first..first + 4` from their lanes; lanes not in `keep`
    /// (past the polygon, whose values the caller may have computed from padding) are
    /// written as 0. A caller that passes a constant all-true `keep` for a group of four
    /// sectors has the masks folded away.
    #[inline(always)]
    pub(crate) fn store(&mut self, first: usize, keep: BVec4A, lanes: &CentralLanes) {
        self.store_with_half_inverse(first, keep, lanes, Vec4::splat(0.5) / lanes.root_det);
    }

    /// [`store`](Self::store) with `0.5 / k` given (`half_inverse_k`, which the caller
    /// computed as `0.5 / root_det` for the sector areas: the same operation, so the same
    /// bits). The central fast path stores the rows before the arc tangent of the areas
    /// (a branch apart), where the compiler no longer shared the one division.
    #[inline(always)]
    pub(crate) fn store_with_half_inverse(
        &mut self,
        first: usize,
        keep: BVec4A,
        lanes: &CentralLanes,
        half_inverse_k: Vec4,
    ) {
        let put = |row: &mut Row, v: Vec4| store4(Vec4::select(keep, v, Vec4::ZERO), row, first);
        let [s0x, s0y] = lanes.s0;
        let [ux, uy] = lanes.outer;
        let [t0, t1] = lanes.outer_dots;
        let k = lanes.root_det;
        // `C s0 = s0 + (u · s0) u` lane by lane.
        let (cx, cy) = (s0x + ux * t0, s0y + uy * t0);
        // The ellipse norm of the arc's points over √|C|: √(wᵀ C w) / k = √(1 + t0²)
        // (see `sample`). `1 / √(wᵀ C w)` is taken as the product of `g = 1 / √(1 + t0²)`
        // and `1 / k`, not as the root of k² (1 + t0²): with |u| and |t0| up to 2^40.5
        // (ELLIPSE_LIMIT) the product of the squares overflows f32, each root stays below
        // 2^41. `t0` is finite (both central paths store 0 where it is not), so `g` lies
        // in (0, 1] and `â`, `u · â` are finite (|s0| = 1), without a select.
        let root = crate::math::sqrt4(Vec4::ONE + t0 * t0);
        let g = Vec4::ONE / root;
        // 1 / k as `0.5 / k` (which both central paths compute for the sector areas)
        // doubled, exactly.
        let h = g * (half_inverse_k + half_inverse_k);
        let finite = |v: Vec4| Vec4::select(v.is_finite_mask(), v, Vec4::ZERO);
        put(&mut self.a_hat[0], s0x * g);
        put(&mut self.a_hat[1], s0y * g);
        // R (x, y) = (-y, x), the negation exact. Not finite for a degenerate ellipse
        // (k = ∞, `C s0` ∞ or NaN).
        put(&mut self.b_hat[0], finite(-cy * h));
        put(&mut self.b_hat[1], finite(cx * h));
        put(&mut self.at_hat, t0 * g);
        // `det2(s0, u)`: `difference_of_products4` is `difference_of_products` lane by
        // lane.
        put(
            &mut self.bt_hat,
            finite(difference_of_products4(s0x, uy, s0y, ux) * h),
        );
        put(&mut self.s0[0], s0x);
        put(&mut self.s0[1], s0y);
        put(&mut self.two_k, k + k);
        put(&mut self.t0, t0);
        put(&mut self.s1[0], lanes.s1[0]);
        put(&mut self.s1[1], lanes.s1[1]);
        put(&mut self.det, lanes.det);
        put(&mut self.outer[0], ux);
        put(&mut self.outer[1], uy);
        put(&mut self.t1, t1);
    }

    /// Writes the sectors `first..first + 4` as 0 (slots past the polygon).
    #[inline(always)]
    pub(crate) fn store_zeros(&mut self, first: usize) {
        let rows: [&mut Row; 16] = {
            let Self {
                a_hat: [a0, a1],
                b_hat: [b0, b1],
                two_k,
                at_hat,
                bt_hat,
                s0: [a, b],
                t0,
                s1: [e, f],
                det,
                outer: [g, h],
                t1,
            } = self;
            [
                a0, a1, b0, b1, two_k, at_hat, bt_hat, a, b, t0, e, f, det, g, h, t1,
            ]
        };
        for row in rows {
            store4(Vec4::ZERO, row, first);
        }
    }

    /// Sector `j` as the [`EllipseSector::new_central`] that preparation built before
    /// these rows (bit for bit: the same values), for the readers of a sector's other
    /// fields.
    ///
    /// Inlined, so that a reader of a few fields (the baseline of Arvo) computes only
    /// those (`1 / det(s0, s1)` is not a row).
    #[inline(always)]
    pub(crate) fn sector(&self, j: usize) -> EllipseSector {
        let pair = |row: &[Row; 2]| [row[0][j], row[1][j]];
        let (s0, s1) = (pair(&self.s0), pair(&self.s1));
        // `s0 · s1` and `1 / det(s0, s1)` (0 where not finite) of the rounded `s0` and
        // `s1`, as the preparations computed them lane by lane before (`dot2` and
        // `det2` round as the lanes' `s0x s1x + s0y s1y` and `difference_of_products4`
        // do). A slot past the sectors (s0 = s1 = 0) gives 0 and 1 / 0 = ∞, so 0: the
        // zeros that those slots' rows held.
        let inverse_basis = 1.0 / det2(s0, s1);
        let inverse_basis = if inverse_basis.is_finite() {
            inverse_basis
        } else {
            0.0
        };
        EllipseSector::new_central(
            [s0, s1],
            self.det[j],
            pair(&self.outer),
            [self.t0[j], self.t1[j]],
            0.5 * self.two_k[j],
            dot2(s0, s1),
            inverse_basis,
        )
    }

    /// [`EllipseSector::sample_central`] of sector `j` with the ellipse norm taken from
    /// the rows: a point uniformly distributed in the sector's part of the outer
    /// ellipse, at area `area` from `s0` counter-clockwise and relative radius² `xi1`,
    /// and `ω_z²`.
    ///
    /// As there (supplement A.7), the point is `√ξ1 w / √(wᵀ C w)` for
    /// `w = cos(2kA) k s0 + sin(2kA) R C s0`. The norm is the same along the whole arc:
    /// with `a = k s0` and `b = R C s0`, `bᵀ C b = s0ᵀ C Rᵀ C R C s0 = |C| s0ᵀ C s0 = aᵀ C a`
    /// (`Rᵀ C R = adj C = |C| C⁻¹` for a symmetric 2×2 `C`) and `aᵀ C b = k (C s0)ᵀ R (C s0)
    /// = 0` (`R` is antisymmetric), so `wᵀ C w = (cos² + sin²) aᵀ C a = k² (1 + t0²)`
    /// (`|s0| = 1`). Preparation stores `a` and `b` and their dot products with `u`
    /// divided by it (`â`, `b̂`, `u · â`, `u · b̂`), and the sample needs no division and
    /// no square root of `w`: `p = √ξ1 ŵ` with `ŵ = cos â + sin b̂`, and with
    /// `|ŵ|² + (u · ŵ)² = 1`, `ω_z² = 1 - |p|² = 1 - ξ1 + ξ1 (u · ŵ)²`, a sum of two
    /// non-negative terms (no cancellation next to the horizon, where both are small),
    /// from `u · ŵ = cos (u · â) + sin (u · b̂)` (as `u · R u = 0`, `u · b = det(s0, u)`).
    ///
    /// The chain of dependent operations after `sin_cos` (issue 15: the central sample
    /// waited on it) is a multiplication and an addition to `√ξ1 u · ŵ`, two operations
    /// to `ω_z²` and its square root in the caller; the point is a multiplication and an
    /// addition. Before, it was `|w|²`, the norm, a division and a square root for the
    /// point and a division for `ω_z²` (llvm-mca, znver3, the whole central sample: 161
    /// -> 130 cycles). `|p|² + ω_z²` is 1 to within the rows' and `sin_cos`'
    /// roundings (a few ulps; the test `central_rows_sample_as_the_sectors` bounds it,
    /// and the distance to an `f64` evaluation of Algorithm 4).
    #[inline(always)]
    pub(crate) fn sample(&self, j: usize, area: f32, xi1: f32) -> (Vec2, f32) {
        // `& 7` only shows the compiler the slot in bounds (sector indices are below 8).
        let j = j & (MAX_POLYGON_VERTICES - 1);
        // `√ξ1 â`, `√ξ1 b̂` and their dot products with `u`: the point's factor applied
        // while `sin_cos` runs (it depends on the random number and the rows only), so
        // that the point is `cos √ξ1 â + sin √ξ1 b̂` and `ω_z² = 1 - ξ1 + (√ξ1 u · ŵ)²`
        // are an operation shorter after `sin_cos` than with `√ξ1` multiplied last.
        let r = crate::math::sqrtf(xi1);
        let a = scale2([self.a_hat[0][j], self.a_hat[1][j]], r);
        let b = scale2([self.b_hat[0][j], self.b_hat[1][j]], r);
        let (at, bt) = (r * self.at_hat[j], r * self.bt_hat[j]);
        // 2 k area is the sector's angle in the circle's coordinates up to `area`: in
        // [0, π] (the sector's area is atan2_upper_half_plane / (2 k)).
        let (sin, cos) = crate::math::sin_cos_0_to_pi(self.two_k[j] * area);
        let point = add2(scale2(a, cos), scale2(b, sin));
        let uw = cos * at + sin * bt;
        (point, (1.0 - xi1) + uw * uw)
    }
}

// `MAX_POLYGON_VERTICES` is a power of two (the mask in `sample`) and a multiple of the
// lanes (`store` writes whole groups).
const _: () = assert!(MAX_POLYGON_VERTICES.is_power_of_two());
const _: () = assert!(MAX_POLYGON_VERTICES % LANES == 0);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{lane_starts, load4};
    use crate::testing::Rng;

    /// `both_groups_kept` is `lanes_kept` of the two groups, for every count 0..=8.
    #[test]
    fn both_groups_kept_matches_lanes_kept() {
        for count in 0..=MAX_POLYGON_VERTICES {
            let [low, high] = both_groups_kept(count);
            assert_eq!(low.bitmask(), lanes_kept(0, count).bitmask(), "{count}");
            assert_eq!(
                high.bitmask(),
                lanes_kept(LANES, count).bitmask(),
                "{count}"
            );
        }
    }

    /// `sector` computes `s0 · s1` and `1 / det(s0, s1)` (0 where not finite) from the
    /// rows `s0` and `s1`, scalar, where they were rows that the preparations computed
    /// four at a time (`s0x s1x + s0y s1y` and `1 / difference_of_products4`): the same
    /// bits, over random unit directions of all angles, equal and opposite pairs (det 0
    /// or rounding to 0), nearly opposite ones (det near the underflow), tiny and huge
    /// components, and the slots past the sectors (zero rows, whose sector has 0 and 0).
    #[test]
    fn sector_constants_match_the_lanes() {
        let mut rng = Rng::new(37);
        let (mut zero_inverse, mut finite_inverse) = (0, 0);
        for trial in 0..20_000 {
            let count = 3 + trial % 6;
            let mut s = [[[0.0f32; MAX_POLYGON_VERTICES]; 2]; 2];
            #[allow(clippy::needless_range_loop)] // j indexes the innermost arrays
            for j in 0..count {
                let angle = (rng.uniform() * core::f64::consts::TAU) as f32;
                let s0 = [angle.cos(), angle.sin()];
                let s1 = match trial % 5 {
                    0 => s0,
                    1 => [-s0[0], -s0[1]],
                    2 => [-s0[0], -s0[1] + f32::EPSILON * s0[0].signum()],
                    3 => {
                        let scale = rng.signed_log_uniform(-30.0, 30.0) as f32;
                        [s0[1] * scale, -s0[0]]
                    }
                    _ => {
                        let other = (rng.uniform() * core::f64::consts::TAU) as f32;
                        [other.cos(), other.sin()]
                    }
                };
                for c in 0..2 {
                    s[0][c][j] = s0[c];
                    s[1][c][j] = s1[c];
                }
            }
            let mut rows = CentralSectors {
                a_hat: [[f32::NAN; MAX_POLYGON_VERTICES]; 2],
                b_hat: [[f32::NAN; MAX_POLYGON_VERTICES]; 2],
                two_k: [f32::NAN; MAX_POLYGON_VERTICES],
                at_hat: [f32::NAN; MAX_POLYGON_VERTICES],
                bt_hat: [f32::NAN; MAX_POLYGON_VERTICES],
                s0: [[f32::NAN; MAX_POLYGON_VERTICES]; 2],
                t0: [f32::NAN; MAX_POLYGON_VERTICES],
                s1: [[f32::NAN; MAX_POLYGON_VERTICES]; 2],
                det: [f32::NAN; MAX_POLYGON_VERTICES],
                outer: [[f32::NAN; MAX_POLYGON_VERTICES]; 2],
                t1: [f32::NAN; MAX_POLYGON_VERTICES],
            };
            let mut cosine = [0.0f32; MAX_POLYGON_VERTICES];
            let mut inverse = [0.0f32; MAX_POLYGON_VERTICES];
            for first in lane_starts(MAX_POLYGON_VERTICES) {
                let [[s0x, s0y], [s1x, s1y]] = s.map(|d| d.map(|row| load4(&row, first)));
                let lanes = CentralLanes {
                    s0: [s0x, s0y],
                    s1: [s1x, s1y],
                    det: Vec4::ONE,
                    outer: [Vec4::ONE; 2],
                    outer_dots: [Vec4::ONE; 2],
                    root_det: Vec4::ONE,
                };
                rows.store(first, lanes_kept(first, count), &lanes);
                // The lanes' forms that the preparations stored before.
                store4(s0x * s1x + s0y * s1y, &mut cosine, first);
                let lanes_inverse = Vec4::ONE / difference_of_products4(s0x, s1y, s0y, s1x);
                let lanes_inverse =
                    Vec4::select(lanes_inverse.is_finite_mask(), lanes_inverse, Vec4::ZERO);
                store4(lanes_inverse, &mut inverse, first);
            }
            for j in 0..MAX_POLYGON_VERTICES {
                let sector = rows.sector(j);
                let (expected_cosine, expected_inverse) = if j < count {
                    (cosine[j], inverse[j])
                } else {
                    (0.0, 0.0)
                };
                assert_eq!(
                    (sector.cosine.to_bits(), sector.inverse_basis.to_bits()),
                    (expected_cosine.to_bits(), expected_inverse.to_bits()),
                    "trial {trial}, sector {j}: {s:?}"
                );
                if j < count {
                    zero_inverse += (expected_inverse == 0.0) as u32;
                    finite_inverse += (expected_inverse != 0.0) as u32;
                }
            }
        }
        // Both outcomes of the finiteness test are exercised.
        assert!(
            zero_inverse > 10_000 && finite_inverse > 10_000,
            "{zero_inverse} {finite_inverse}"
        );
    }
}
