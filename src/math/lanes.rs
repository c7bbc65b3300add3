//! Four `f32` lanes at a time, for the per-vertex and per-fan-triangle work of polygon
//! preparation: glam's [`Vec4`] (SSE2 registers on x86-64, plain arrays elsewhere).
//!
//! Every function here rounds each lane exactly as its scalar counterpart in
//! [`products`](super::products) does (the same operations in the same order, each
//! correctly rounded in IEEE arithmetic whether one lane or four compute it), so a
//! prepared value is the same bit for bit on every target and whether a lane or the
//! scalar fallback computed it.

use glam::{BVec4A, Mat4, Vec4};

/// The number of lanes: four `f32` in one SSE register.
pub(crate) const LANES: usize = 4;

/// The first slot of each lane group covering slots `0..end`: `0, 4, 8, …` (as
/// `(0..end).step_by(LANES)`, whose general stride costs a division and more per loop).
#[inline(always)]
pub(crate) fn lane_starts(end: usize) -> impl Iterator<Item = usize> {
    (0..end.div_ceil(LANES)).map(|group| group * LANES)
}

/// The four slots of `values` from `first` as lanes (one home for the lanes' loads).
#[inline(always)]
#[must_use]
pub(crate) fn load4(values: &[f32], first: usize) -> Vec4 {
    Vec4::from_slice(&values[first..first + LANES])
}

/// Writes four lanes into the slots of `values` from `first`.
#[inline(always)]
pub(crate) fn store4(lanes: Vec4, values: &mut [f32], first: usize) {
    lanes.write_to_slice(&mut values[first..first + LANES]);
}

/// `sqrt` of each lane, correctly rounded (one `sqrtps` on x86-64, where glam computes
/// the lanes one by one).
#[inline(always)]
#[must_use]
pub fn sqrt4(v: Vec4) -> Vec4 {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        use core::arch::x86_64::_mm_sqrt_ps;
        // SAFETY: SSE2 is enabled for this compilation (a baseline of x86-64).
        Vec4::from(unsafe { _mm_sqrt_ps(v.into()) })
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
    {
        Vec4::new(
            crate::math::sqrtf(v.x),
            crate::math::sqrtf(v.y),
            crate::math::sqrtf(v.z),
            crate::math::sqrtf(v.w),
        )
    }
}

/// Each lane as it is where finite, else 0 (the scalar
/// `if x.is_finite() { x } else { 0.0 }`: `is_finite_mask` is `|x| < ∞`, false for NaN).
#[inline(always)]
#[must_use]
pub fn finite_or_zero4(v: Vec4) -> Vec4 {
    Vec4::select(v.is_finite_mask(), v, Vec4::ZERO)
}

/// `f32::max` lane by lane, a NaN operand ignored as there: `maxps` (glam's `max` on
/// SSE) gives its second operand where either is NaN, right for a NaN `a` and, with
/// the select, for a NaN `b` (elsewhere glam's `max` is `f32::max` and the select
/// changes nothing).
#[inline(always)]
#[must_use]
pub fn max4(a: Vec4, b: Vec4) -> Vec4 {
    Vec4::select(b.is_nan_mask(), a, a.max(b))
}

/// `f32::min` lane by lane, a NaN operand ignored as there (see [`max4`]).
#[inline(always)]
#[must_use]
pub fn min4(a: Vec4, b: Vec4) -> Vec4 {
    Vec4::select(b.is_nan_mask(), a, a.min(b))
}

/// Writes the words `start..start + 4` of four records of `N` words, one record per
/// lane: record `lane` gets `words[w][lane]` as its word `start + w`. A 4×4 transpose
/// (glam's `Mat4::transpose`, shuffles on SSE) turns the four words' lanes into each
/// record's four consecutive words, stored at once. A caller that writes whole records
/// this way (`EllipseSector::new4`) stores each group of four words as soon as it has
/// computed them, so that fewer values are live at once (all 46 words of a sector held
/// to the end spilled to the stack). Moves bits only (no arithmetic), so every word is
/// stored as computed, NaN payloads included.
#[inline(always)]
pub(crate) fn store_record_words4<const N: usize>(
    words: [Vec4; LANES],
    records: &mut [[f32; N]; LANES],
    start: usize,
) {
    let rows = Mat4::from_cols(words[0], words[1], words[2], words[3]).transpose();
    for (record, row) in
        records
            .iter_mut()
            .zip([rows.x_axis, rows.y_axis, rows.z_axis, rows.w_axis])
    {
        row.write_to_slice(&mut record[start..start + LANES]);
    }
}

/// Veltkamp's split of each lane, as [`products::split`](super::products).
#[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
#[inline(always)]
fn split4(a: Vec4) -> (Vec4, Vec4) {
    let t = Vec4::splat(4097.0) * a;
    let high = t - (t - a);
    (high, a - high)
}

/// [`difference_of_products`](super::difference_of_products) lane by lane.
#[inline(always)]
#[must_use]
pub fn difference_of_products4(a: Vec4, b: Vec4, c: Vec4, d: Vec4) -> Vec4 {
    #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
    {
        // Kahan's algorithm, as the scalar form (glam's `mul_add` is `vfmadd` here).
        let w = c * d;
        let error = (-c).mul_add(d, w);
        let f = a.mul_add(b, -w);
        f + error
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
    {
        let two_product = |x: Vec4, y: Vec4| {
            let p = x * y;
            let (xh, xl) = split4(x);
            let (yh, yl) = split4(y);
            (p, ((xh * yh - p) + xh * yl + xl * yh) + xl * yl)
        };
        let (p1, e1) = two_product(a, b);
        let (p2, e2) = two_product(c, d);
        (p1 - p2) + (e1 - e2)
    }
}

/// [`cross_precise`](super::cross_precise) of four pairs of vectors, given as their x,
/// y and z lanes.
#[inline(always)]
#[must_use]
pub fn cross_precise4(a: [Vec4; 3], b: [Vec4; 3]) -> [Vec4; 3] {
    [
        difference_of_products4(a[1], b[2], a[2], b[1]),
        difference_of_products4(a[2], b[0], a[0], b[2]),
        difference_of_products4(a[0], b[1], a[1], b[0]),
    ]
}

/// [`difference_of_products_unless_half_cancels`](super::difference_of_products_unless_half_cancels)
/// lane by lane: the plain difference in the lanes where at most half of the products'
/// magnitude cancels, the error-free form in the others (computed for all four lanes only
/// when one of the lanes in `needed` needs it; the other lanes may hold anything, NaN
/// included).
#[inline(always)]
#[must_use]
pub fn difference_of_products_unless_half_cancels4(
    a: Vec4,
    b: Vec4,
    c: Vec4,
    d: Vec4,
    needed: BVec4A,
) -> Vec4 {
    let (p1, p2) = (a * b, c * d);
    let plain = p1 - p2;
    // `plain_difference_is_within_half` in lanes (`2 |plain|` exact in each).
    let plain_is_accurate: BVec4A = (p1.abs() + p2.abs()).cmple(Vec4::splat(2.0) * plain.abs())
        & plain
            .abs()
            .cmpge(Vec4::splat(super::products::MIN_PLAIN_DIFFERENCE));
    if (plain_is_accurate | !needed).all() {
        plain
    } else {
        Vec4::select(
            plain_is_accurate,
            plain,
            difference_of_products4(a, b, c, d),
        )
    }
}

/// [`atan2_upper_half_plane`](super::atan2_upper_half_plane) of the first `lanes` lanes
/// (the others 0), every lane the same bits as the scalar call (tested), without a
/// branch: the scalar form's choice between `atan(y/x)` and `π/2 + atan(-x/y)` becomes
/// a choice of numerator and denominator (one division for four lanes) and of the
/// offset, and `libm::atanf` is [`atanf4`](super::atanf4), its bits in four lanes.
#[inline(always)]
#[must_use]
pub fn atan2_upper_half_plane4(y: Vec4, x: Vec4, lanes: usize) -> Vec4 {
    atan2_upper_half_plane4_with(y, x, lanes, false)
}

/// [`atan2_upper_half_plane4`], the same bits, for callers whose ratios are mostly below
/// 7/16 (angles below 0.41 rad, or within 0.41 rad of π/2): when every used lane's ratio
/// is, one branch takes [`atanf4_below_7_16`](super::atanf4_below_7_16), which
/// leaves out the reduction's comparisons, selections and its second division (on the
/// critical path of the solid angle prepare); otherwise the general form.
#[inline(always)]
#[must_use]
pub fn atan2_upper_half_plane4_small_first(y: Vec4, x: Vec4, lanes: usize) -> Vec4 {
    atan2_upper_half_plane4_with(y, x, lanes, true)
}

/// The body of the two: `small_first` (a constant where this is inlined) tests for the
/// small ratios.
#[inline(always)]
fn atan2_upper_half_plane4_with(y: Vec4, x: Vec4, lanes: usize, small_first: bool) -> Vec4 {
    // `x > 0`, false for a NaN `x`, which takes the second form as in the scalar.
    let right = x.cmpgt(Vec4::ZERO);
    let ratio = Vec4::select(right, y, -x) / Vec4::select(right, x, y);
    // Below 7/16 in every used lane (false for NaN, which takes the general form); the
    // unused lanes' values are discarded below.
    let small = || (ratio.abs().cmplt(Vec4::splat(0.4375)) | !used_lanes(lanes)).all();
    let atan = if small_first && small() {
        super::atanf4_below_7_16(ratio)
    } else {
        super::atanf4(ratio)
    };
    // The offset 0 or π/2 added in every lane: `0 + a` is `a` but for `a = -0`, where it
    // is +0, which the clamp below turns into +0 in either case.
    let offset = Vec4::select(right, Vec4::ZERO, Vec4::splat(core::f32::consts::FRAC_PI_2));
    let angle = offset + atan;
    // The scalar's clamp `if angle > 0 { angle } else { 0 }` (NaN and ±0 give +0), and 0
    // in the unused lanes.
    Vec4::select(
        angle.cmpgt(Vec4::ZERO) & used_lanes(lanes),
        angle,
        Vec4::ZERO,
    )
}

/// The lanes below `lanes` (their index compared as an `f32`: exact, at most 4 — larger
/// counts only mean "all").
#[inline(always)]
fn used_lanes(lanes: usize) -> BVec4A {
    Vec4::new(0.0, 1.0, 2.0, 3.0).cmplt(Vec4::splat(lanes.min(LANES) as f32))
}

/// glam's `Vec3::cross` of vectors held as the lanes `(x, y, z, _)`, each component
/// rounded as there: `a_y b_z - b_y a_z`, `a_z b_x - b_z a_x`, `a_x b_y - b_x a_y`, as
/// `a.yzx · b.zxy - b.yzx · a.zxy` (two products and a difference per lane; the fourth
/// lane is `a_w b_w - b_w a_w`). Explicit products and a difference, where glam's own
/// lanes (`Vec3A::cross`) fuse them with hardware FMA and would round differently.
#[inline(always)]
#[must_use]
pub(crate) fn cross3_lanes(a: Vec4, b: Vec4) -> Vec4 {
    use glam::Vec4Swizzles;
    a.yzxw() * b.zxyw() - b.yzxw() * a.zxyw()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{difference_of_products, difference_of_products_unless_half_cancels};
    use crate::testing::Rng;

    /// `cross3_lanes` is `Vec3::cross` bit for bit, on cancelling and non-cancelling
    /// products over many magnitudes.
    #[test]
    fn cross3_lanes_is_the_scalar_cross() {
        let mut rng = Rng::new(37);
        for case in 0..100_000 {
            let mut v = || {
                crate::Vec3::from_array(core::array::from_fn(|_| {
                    rng.signed_log_uniform(-20.0, 20.0) as f32
                }))
            };
            let a = v();
            // Every other pair nearly parallel (the products nearly cancel).
            let b = if case % 2 == 0 {
                v()
            } else {
                a * 1.000_001 + v() * 1e-6
            };
            let lanes = cross3_lanes(Vec4::from((a, 0.0)), Vec4::from((b, 0.0)));
            let expected = a.cross(b).to_array().map(f32::to_bits);
            assert_eq!(
                lanes.truncate().to_array().map(f32::to_bits),
                expected,
                "{a} {b}"
            );
        }
    }

    /// The lanes round as the scalar forms, bit for bit, on cancelling and
    /// non-cancelling products, tiny and huge magnitudes.
    /// `store_record_words4` puts lane `l` of word `w` at word `start + w` of record `l`
    /// and leaves every other word as it was.
    #[test]
    fn store_record_words4_writes_one_group_of_each_record() {
        let mut records = [[f32::NAN; 7]; LANES];
        let words = core::array::from_fn(|w| {
            Vec4::from_array(core::array::from_fn(|lane| (10 * w + lane) as f32))
        });
        store_record_words4(words, &mut records, 2);
        for (lane, record) in records.iter().enumerate() {
            for (i, word) in record.iter().enumerate() {
                if (2..6).contains(&i) {
                    assert_eq!(
                        *word,
                        (10 * (i - 2) + lane) as f32,
                        "record {lane} word {i}"
                    );
                } else {
                    assert!(word.is_nan(), "record {lane} word {i}");
                }
            }
        }
    }

    #[test]
    fn lanes_round_as_the_scalar_forms() {
        let mut rng = Rng::new(5);
        let mut careful_lanes = 0;
        for _ in 0..50_000 {
            let mut draw = || rng.signed_log_uniform(-40.0, 30.0) as f32;
            let (a, b, c) = (
                Vec4::new(draw(), draw(), draw(), draw()),
                Vec4::new(draw(), draw(), draw(), draw()),
                Vec4::new(draw(), draw(), draw(), draw()),
            );
            // d close to a b / c in two lanes, so that the products nearly cancel there.
            let mut d = Vec4::new(draw(), draw(), draw(), draw());
            d.x = a.x * b.x / c.x * (1.0 + 1e-6);
            d.z = a.z * b.z / c.z;
            let (plain, careful) = (
                difference_of_products_unless_half_cancels4(a, b, c, d, BVec4A::splat(true)),
                difference_of_products4(a, b, c, d),
            );
            for lane in 0..4 {
                let (a, b, c, d) = (a[lane], b[lane], c[lane], d[lane]);
                let scalar = difference_of_products_unless_half_cancels(a, b, c, d);
                assert_eq!(plain[lane].to_bits(), scalar.to_bits(), "{a} {b} {c} {d}");
                let scalar = difference_of_products(a, b, c, d);
                assert_eq!(careful[lane].to_bits(), scalar.to_bits(), "{a} {b} {c} {d}");
                careful_lanes += (plain[lane] != a * b - c * d) as u32;
            }
            let crosses = cross_precise4([a, b, c], [d, b, a]);
            for lane in 0..4 {
                let scalar = crate::math::cross_precise(
                    glam::Vec3::new(a[lane], b[lane], c[lane]),
                    glam::Vec3::new(d[lane], b[lane], a[lane]),
                );
                for (component, lanes) in crosses.iter().enumerate() {
                    assert_eq!(lanes[lane].to_bits(), scalar[component].to_bits());
                }
            }
            let nan_in = |v: Vec4| Vec4::select(v.cmpgt(Vec4::splat(1e20)), Vec4::NAN, v);
            let (x, y) = (nan_in(a), nan_in(b));
            let (largest, smallest) = (max4(x, y), min4(x, y));
            for lane in 0..4 {
                let (x, y) = (x[lane], y[lane]);
                assert_eq!(largest[lane].to_bits(), x.max(y).to_bits(), "{x} {y}");
                assert_eq!(smallest[lane].to_bits(), x.min(y).to_bits(), "{x} {y}");
            }
            let v = Vec4::new(draw().abs(), draw().abs(), 0.0, draw().abs());
            let roots = sqrt4(v);
            for lane in 0..4 {
                assert_eq!(roots[lane].to_bits(), crate::math::sqrtf(v[lane]).to_bits());
            }
        }
        for _ in 0..20_000 {
            let mut draw = || rng.signed_log_uniform(-30.0, 30.0) as f32;
            let x = Vec4::new(draw(), draw(), 0.0, draw());
            let y = Vec4::new(draw().abs(), 0.0, 0.0, f32::NAN);
            let used = rng.below(5) as usize;
            let angles = atan2_upper_half_plane4(y, x, used);
            for lane in 0..4 {
                let scalar = if lane < used {
                    crate::math::atan2_upper_half_plane(y[lane], x[lane])
                } else {
                    0.0
                };
                assert_eq!(
                    angles[lane].to_bits(),
                    scalar.to_bits(),
                    "{} {}",
                    y[lane],
                    x[lane]
                );
            }
        }
        // The careful form ran in some lanes (the test covers both).
        assert!(careful_lanes > 1000, "{careful_lanes}");
    }

    /// `atan2_upper_half_plane4` against the scalar form lane by lane, bit for bit: every
    /// pair of special values (signed zeros, whose `-0` angles the clamp makes +0, the
    /// smallest subnormal, ±1, ratios at fdlibm's thresholds, huge values, infinities,
    /// NaN, negative `y` outside the contract), every lane position and lane count
    /// (0 to 5: more than four means all), and random pairs of all magnitudes and of
    /// random bit patterns; and the same for `atan2_upper_half_plane4_small_first`, also
    /// on random pairs whose used lanes all have ratios below 7/16 (its branch without the
    /// reduction) and whose unused lanes do not.
    #[test]
    fn atan2_upper_half_plane4_is_the_scalar_form() {
        use crate::math::atan2_upper_half_plane;
        let check = |y: Vec4, x: Vec4, lanes: usize| {
            let general = atan2_upper_half_plane4(y, x, lanes);
            let small_first = atan2_upper_half_plane4_small_first(y, x, lanes);
            for (lane, angles) in (0..LANES).flat_map(|l| [(l, general), (l, small_first)]) {
                let scalar = if lane < lanes {
                    atan2_upper_half_plane(y[lane], x[lane])
                } else {
                    0.0
                };
                assert_eq!(
                    angles[lane].to_bits(),
                    scalar.to_bits(),
                    "lane {lane} of {lanes}: y {:e} ({:#x}), x {:e} ({:#x})",
                    y[lane],
                    y[lane].to_bits(),
                    x[lane],
                    x[lane].to_bits()
                );
            }
        };
        let special = [
            0.0f32,
            -0.0,
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::MIN_POSITIVE,
            1.0,
            -1.0,
            0.4375,
            -0.6875,
            1.1875,
            2.4375,
            -2.4375,
            3e-39,
            1e30,
            -1e30,
            f32::MAX,
            -f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        for (i, &y) in special.iter().enumerate() {
            for (j, &x) in special.iter().enumerate() {
                let (y2, x2) = (special[(i + j) % special.len()], special[(3 * j + 1) % 20]);
                for lanes in 0..=5 {
                    check(Vec4::new(y, y2, x, y), Vec4::new(x, x2, y, -x), lanes);
                    check(Vec4::new(y2, y, y, x), Vec4::new(x2, x, -x, y), lanes);
                }
            }
        }
        let mut rng = Rng::new(15);
        for _ in 0..200_000 {
            let mut draw = || rng.signed_log_uniform(-40.0, 40.0) as f32;
            let y = Vec4::new(draw().abs(), draw().abs(), draw(), draw().abs());
            let x = Vec4::new(draw(), draw(), draw(), draw());
            check(y, x, 4);
            let r = rng.next_u64();
            let bits = Vec4::new(
                f32::from_bits(r as u32),
                f32::from_bits((r >> 32) as u32),
                f32::from_bits((r >> 16) as u32),
                f32::from_bits((r >> 8) as u32),
            );
            check(bits, glam::Vec4Swizzles::zwxy(bits), 4);
        }
        // Ratios `y / x` or `-x / y` below 7/16 (up to 0.5, so that a few lanes are just
        // above), with a large ratio in the lanes past `lanes`.
        for _ in 0..200_000 {
            let lanes = 1 + (rng.next_u64() % 4) as usize;
            let mut lane = |i: usize| {
                let ratio = 0.5 * rng.uniform_f32() * [1.0, 1e-3, 1e-20][i % 3];
                let along = rng.log_uniform(-20.0, 20.0) as f32;
                match i {
                    _ if i >= lanes => (along, 0.1 * along),
                    0 | 2 => (ratio * along, along),
                    _ => (along, -ratio * along),
                }
            };
            let [a, b, c, d] = [lane(0), lane(1), lane(2), lane(3)];
            check(
                Vec4::new(a.0, b.0, c.0, d.0),
                Vec4::new(a.1, b.1, c.1, d.1),
                lanes,
            );
        }
    }
}
