//! Ellipses in the unit disk: the orthographic projections of great circles onto the
//! tangent plane of the shading point (Peters 2021, Sec. 3, supplement A.2, A.7,
//! Algorithms 1 and 2).
//!
//! A direction `ω` of the upper hemisphere projects to `p = ω_xy` in the unit disk, and
//! a uniform density over the projected area is the cosine-weighted density `ω_z / Φ`
//! over solid angle (Nusselt's analogy). The great circle `n · ω = 0` with `n_z ≠ 0`
//! projects to the ellipse `pᵀ C p = 1` with `C = I + u uᵀ` and `u = n_xy / n_z`: on
//! the circle `ω_z = -u · p`, so `|p|² + (u · p)² = 1`. Its determinant is
//! `|C| = 1 + |u|²`; its minor axis runs along `u` and it touches the unit circle along
//! `R u`, where `R` is the rotation by +90°.
//!
//! `C` does not change when `u` is negated, so the sign of `u` is free to carry one bit:
//! the sign bit of `u_x` is set for an *inner* ellipse (an edge that runs clockwise around
//! the zenith) and clear for an *outer* one. A great circle through the zenith (`n_z =
//! 0`, a *degenerate* ellipse) is marked by `u_x = +∞` (supplement A.2, rule 1): it counts
//! as outer, and every area within it is zero (rule 2).

use crate::Vec3;
use crate::math::is_sign_negative;
use crate::math::{atan2_upper_half_plane, difference_of_products};
use glam::Vec4;

/// A vector in the plane of the unit disk.
pub(crate) type Vec2 = [f32; 2];

/// The largest magnitude kept for a component of `u`. Beyond it the ellipse is thinner
/// than `2^-40` and the areas it bounds are below every rounding error of the areas that
/// matter, while `1 + |u|²` and the products of the sampling step stay far from overflow.
pub(crate) const ELLIPSE_LIMIT: f32 = (1u64 << 40) as f32;

/// The marker of a degenerate ellipse (a great circle through the zenith).
pub(crate) const DEGENERATE: Vec2 = [f32::INFINITY, 0.0];

#[inline(always)]
pub(crate) fn dot2(a: Vec2, b: Vec2) -> f32 {
    a[0] * b[0] + a[1] * b[1]
}

/// `det(a, b) = a_x b_y - a_y b_x` by Kahan's algorithm (within 2 ulp).
#[inline(always)]
pub(crate) fn det2(a: Vec2, b: Vec2) -> f32 {
    difference_of_products(a[0], b[1], a[1], b[0])
}

/// `R a`, the rotation of `a` by +90°. Then `det(a, b) = (R a) · b = -aᵀ R b`.
#[inline(always)]
pub(crate) fn rotate(a: Vec2) -> Vec2 {
    [-a[1], a[0]]
}

#[inline(always)]
pub(crate) fn add2(a: Vec2, b: Vec2) -> Vec2 {
    [a[0] + b[0], a[1] + b[1]]
}

#[inline(always)]
pub(crate) fn scale2(a: Vec2, s: f32) -> Vec2 {
    [a[0] * s, a[1] * s]
}

/// The unit vector along the projection `v_xy` (zero for a vertex at the zenith). The
/// vector is first scaled by its largest component so that squaring cannot underflow.
#[inline(always)]
pub(crate) fn unit_direction(v: Vec3) -> Vec2 {
    let largest = v.x.abs().max(v.y.abs());
    if !(largest > 0.0) {
        return [0.0, 0.0];
    }
    let (x, y) = (v.x / largest, v.y / largest);
    let inverse_length = 1.0 / crate::math::sqrtf(x * x + y * y);
    [x * inverse_length, y * inverse_length]
}

/// [`unit_direction`] of four vertices (their x and y as lanes), each lane rounded as
/// there (the divisions by the largest component, `1 / sqrt` then the products), zero
/// where the largest component is not positive (the lanes compute 0 / 0 there and
/// select 0).
#[inline(always)]
pub(crate) fn unit_direction4(x: Vec4, y: Vec4) -> (Vec4, Vec4) {
    let largest = x.abs().max(y.abs());
    let (x, y) = (x / largest, y / largest);
    let inverse_length = Vec4::ONE / crate::math::sqrt4(x * x + y * y);
    let on_axis = !largest.cmpgt(Vec4::ZERO);
    (
        Vec4::select(on_axis, Vec4::ZERO, x * inverse_length),
        Vec4::select(on_axis, Vec4::ZERO, y * inverse_length),
    )
}

/// Whether the ellipse is an inner one: the sign bit of `u_x`, so `-0` is inner and `+0`
/// is outer (supplement A.7, `is_inner`).
#[inline(always)]
pub(crate) fn is_inner(u: Vec2) -> bool {
    is_sign_negative(u[0])
}

/// Whether the ellipse is degenerate (its great circle passes through the zenith).
#[inline(always)]
pub(crate) fn is_degenerate(u: Vec2) -> bool {
    !(u[0].abs() <= ELLIPSE_LIMIT)
}

/// `aᵀ C b = a · b + (u · a)(u · b)`.
#[cfg(test)]
#[inline(always)]
pub(crate) fn quadratic_form(u: Vec2, a: Vec2, b: Vec2) -> f32 {
    dot2(a, b) + dot2(u, a) * dot2(u, b)
}

/// Algorithm 1 (`ellipse_from_edge`): the ellipse of the great circle through the edge
/// from `p` to `q` of a polygon that winds counter-clockwise around the zenith (seen from
/// above), given the edge's plane normal `n = p × q` computed by Kahan's algorithm per
/// component ([`cross_precise`]), which is exact to 2 ulp for the given positions however
/// close `p` and `q` are.
///
/// The edge runs counter-clockwise around the zenith where `n_z = det(p_xy, q_xy) > 0`
/// (an outer edge: the polygon lies inside its ellipse) and clockwise where `n_z < 0` (an
/// inner edge: the polygon lies outside). `u = ±n_xy / n_z` with the sign chosen so that
/// the sign bit of `u_x = |n_x| / n_z` is that of `n_z`: multiplying by the sign of `n_x`
/// makes `u_x`'s sign bit `sign(n_z)`, also when `n_x` is a zero of either sign. `n_z = ±0`
/// gives [`DEGENERATE`].
#[cfg(test)]
#[inline(always)]
pub(crate) fn ellipse_from_edge(p: Vec3, q: Vec3) -> (Vec2, Vec3) {
    let n = crate::math::cross_precise(p, q);
    (ellipse_from_normal(n), n)
}

/// [`ellipse_from_edge`] from the plane normal `n = p × q` computed by the caller (as
/// [`cross_precise`] computes it; the projected sampler computes four edges' normals at
/// a time).
#[inline(always)]
pub(crate) fn ellipse_from_normal(n: Vec3) -> Vec2 {
    if n.z == 0.0 {
        return DEGENERATE;
    }
    let inverse = 1.0 / n.z;
    let x = n.x.abs() * inverse;
    let y = crate::math::with_sign_of_product(n.y, n.x, 1.0) * inverse;
    // Clamp the magnitudes (NaN cannot occur: n is finite and n_z is not zero). `min`
    // keeps the sign bit of `x` by working on the magnitude and copying the sign back.
    let clamp = |c: f32| crate::math::copy_sign(c.abs().min(ELLIPSE_LIMIT), c);
    [clamp(x), clamp(y)]
}

/// [`ellipse_from_normal`] of four normals (their components as lanes), each lane the
/// same bits: `1 / n_z`, `|n_x|` times it, `n_y` with the sign of `n_x` multiplied in
/// (multiplying by `±1` flips the sign bit only, as `with_sign_of_product`; `n` is
/// finite), both magnitudes clamped to [`ELLIPSE_LIMIT`] (`minps` gives its second
/// operand, the limit, for a NaN magnitude, as `f32::min` does) with their sign copied
/// back, and [`DEGENERATE`] where `n_z = ±0`.
#[inline(always)]
pub(crate) fn ellipse_from_normal4(nx: Vec4, ny: Vec4, nz: Vec4) -> (Vec4, Vec4) {
    let inverse = Vec4::ONE / nz;
    let x = nx.abs() * inverse;
    let y = ny * Vec4::ONE.copysign(nx) * inverse;
    let limit = Vec4::splat(ELLIPSE_LIMIT);
    let clamp = |c: Vec4| c.abs().min(limit).copysign(c);
    let degenerate = nz.cmpeq(Vec4::ZERO);
    (
        Vec4::select(degenerate, Vec4::splat(DEGENERATE[0]), clamp(x)),
        Vec4::select(degenerate, Vec4::splat(DEGENERATE[1]), clamp(y)),
    )
}

/// Algorithm 2 (`solve_homogeneous_quadratic`, Blinn 2006): a non-zero `w` with
/// `wᵀ Q w = 0`, given `Q_xx`, `Q_xy + Q_yx` and `Q_yy`. With `b = (Q_xy + Q_yx) / 2` and
/// `Δ = b² - Q_xx Q_yy` (Kahan's algorithm; clamped at 0 against rounding), it returns
/// `(|b| + √Δ, -Q_xx)` for `b >= 0` and `(Q_yy, |b| + √Δ)` otherwise. Both forms avoid
/// cancellation, and as a point of the projective line the result depends continuously
/// on `Q` (supplement A.3, Lemma 1), which is what selects the right root.
///
/// The sampler's iteration solves the same quadratic in the basis `(w, R w)` of the
/// current direction (`EllipseSector::tangent_step`), where the root continuous with `w`
/// needs no case distinction; this form is its reference in the tests
/// (`the_tangent_step_is_algorithm_2`).
#[cfg(test)]
#[inline(always)]
pub(crate) fn solve_homogeneous_quadratic(xx: f32, xy_plus_yx: f32, yy: f32) -> Vec2 {
    use crate::math::difference_of_products_unless_cancelling;
    let b = 0.5 * xy_plus_yx;
    // The plain difference where the products cannot cancel (`xx yy <= 0`, relative
    // error at most ε; the usual case for the iteration of supplement A.3 in about half
    // of its steps), the error-free form otherwise.
    let discriminant = difference_of_products_unless_cancelling(b, b, xx, yy).max(0.0);
    let root = b.abs() + crate::math::sqrtf(discriminant);
    if b >= 0.0 { [root, -xx] } else { [yy, root] }
}

/// The area of the ellipse `C = I + u uᵀ` within the sector from `s0` counter-clockwise
/// to `s1` (supplement A.7, Equation (1) of the paper):
///
/// `1 / (2 √|C|) · atan2(√|C| det(s0, s1), s0ᵀ C s1)`.
///
/// The linear map `Lᵀ` with `C = L Lᵀ` takes the ellipse to the unit circle and scales
/// areas by `|L| = √|C|`; there the sector is a circular one of angle
/// `atan2(det(Lᵀ s0, Lᵀ s1), (Lᵀ s0) · (Lᵀ s1))` and area half that angle. The sine-like
/// argument is non-negative for a counter-clockwise sector, so one `atan` of a
/// non-negative ratio suffices (clamped at 0 against rounding). The cosine-like argument
/// is divided by `√|C|` instead of multiplying the other. Degenerate ellipses give 0
/// (rule 2), as do zero vectors.
///
/// This form computes `det(s0, s1)`, `s0 · s1` and `u · s0`, `u · s1` from the rounded
/// inputs; [`ellipse_area`] takes them from the caller, who may know them to full
/// precision.
#[cfg(test)]
#[inline(always)]
pub(crate) fn ellipse_area_in_sector(u: Vec2, s0: Vec2, s1: Vec2) -> f32 {
    ellipse_area(u, det2(s0, s1), dot2(s0, s1), dot2(u, s0), dot2(u, s1))
}

/// [`ellipse_area_in_sector`] from `det = det(s0, s1)`, `dot = s0 · s1` and the dot
/// products `t0 = u · s0`, `t1 = u · s1`, so that `s0ᵀ C s1 = dot + t0 t1`. For an ellipse
/// with large `u` (a great circle passing near the zenith) `u · s` cancels badly when
/// computed from the rounded `u`; [`ProjectedPolygon`] computes it from the
/// vertex positions instead.
///
/// [`ProjectedPolygon`]: super::ProjectedPolygon
#[inline(always)]
pub(crate) fn ellipse_area(u: Vec2, det: f32, dot: f32, t0: f32, t1: f32) -> f32 {
    if is_degenerate(u) {
        return 0.0;
    }
    let root_determinant = crate::math::sqrtf(1.0 + dot2(u, u));
    let x = (dot + t0 * t1) / root_determinant;
    atan2_upper_half_plane(det.max(0.0), x) * (0.5 / root_determinant)
}

/// [`ellipse_area`] with the fast `atan` of the biased variant: absolute error below
/// `1.2e-5 / (2 √|C|)` and relative error below `1.4e-4` (the polynomial's leading
/// coefficient is 0.999866). (Tests only: the sampler's fast areas are in
/// `EllipseSector::area_between`.)
#[cfg(test)]
#[inline(always)]
pub(crate) fn ellipse_area_fast(u: Vec2, det: f32, dot: f32, t0: f32, t1: f32) -> f32 {
    if is_degenerate(u) {
        return 0.0;
    }
    use crate::math::atan_fast_nonneg;
    let root_determinant = crate::math::sqrtf(1.0 + dot2(u, u));
    let y = det.max(0.0);
    let x = (dot + t0 * t1) / root_determinant;
    let angle = if x > 0.0 {
        atan_fast_nonneg(y / x)
    } else {
        core::f32::consts::FRAC_PI_2 + atan_fast_nonneg(-x / y)
    };
    angle.max(0.0) * (0.5 / root_determinant)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::Rng;

    /// The area of `{p : pᵀ C p <= 1}` in a sector by numerical integration in f64:
    /// `½ ∫ r(φ)² dφ` with `r(φ)² = 1 / (eᵀ C e)`, `e = (cos φ, sin φ)`.
    fn area_by_quadrature(u: [f64; 2], from: f64, to: f64) -> f64 {
        let n = 20_000;
        let h = (to - from) / n as f64;
        let f = |phi: f64| {
            let (s, c) = phi.sin_cos();
            let t = u[0] * c + u[1] * s;
            0.5 / (1.0 + t * t)
        };
        // Simpson's rule.
        let mut sum = f(from) + f(to);
        for k in 1..n {
            sum += f(from + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        sum * h / 3.0
    }

    #[test]
    fn ellipse_area_in_sector_matches_quadrature() {
        let mut rng = Rng::new(3);
        for _ in 0..300 {
            let u = [
                rng.signed_log_uniform(-3.0, 1.5) as f32,
                rng.signed_log_uniform(-3.0, 1.5) as f32,
            ];
            let from = rng.uniform() * 6.0;
            let to = from + rng.log_uniform(-4.0, 0.49);
            let s0 = [from.cos() as f32, from.sin() as f32];
            let s1 = [to.cos() as f32, to.sin() as f32];
            // The sector between the rounded boundaries.
            let from = (s0[1] as f64).atan2(s0[0] as f64);
            let to = from + (det2(s0, s1) as f64).atan2(dot2(s0, s1) as f64);
            let got = ellipse_area_in_sector(u, s0, s1) as f64;
            let fast =
                ellipse_area_fast(u, det2(s0, s1), dot2(s0, s1), dot2(u, s0), dot2(u, s1)) as f64;
            let exact = area_by_quadrature([u[0] as f64, u[1] as f64], from, to);
            assert!(
                (got - exact).abs() <= 2e-6 * exact + 1e-9,
                "u {u:?} sector {from}..{to}: {got} vs {exact}"
            );
            assert!((fast - exact).abs() <= 1.5e-4 * exact + 1e-9);
        }
    }

    #[test]
    fn projected_great_circle_lies_on_its_ellipse() {
        let mut rng = Rng::new(5);
        for _ in 0..1000 {
            let p = rng.unit_vector_f32();
            let q = rng.unit_vector_f32();
            let (u, n) = ellipse_from_edge(p, q);
            if is_degenerate(u) {
                continue;
            }
            // A point on the great circle in the upper hemisphere.
            let mut w = n.cross(Vec3::new(n.y, -n.x, 0.0)).normalize();
            if w.z < 0.0 {
                w = -w;
            }
            let on = quadratic_form(u, [w.x, w.y], [w.x, w.y]);
            assert!((on - 1.0).abs() < 1e-4 * (1.0 + dot2(u, u)), "{on}");
            assert_eq!(is_inner(u), n.z < 0.0);
        }
    }

    #[test]
    fn inner_and_outer_are_told_apart_by_the_sign_bit_of_zero() {
        // Edges whose normal has n_x = ±0: u_x is a zero whose sign bit is that of n_z.
        let (p, q) = (Vec3::new(1.0, -1.0, 1.0), Vec3::new(2.0, -1.0, 1.0));
        let (outer, _) = ellipse_from_edge(p, q);
        let (inner, _) = ellipse_from_edge(q, p);
        assert_eq!(outer[0], 0.0);
        assert!(!is_inner(outer));
        assert!(is_inner(inner));
        assert_eq!(inner[0].to_bits(), (-0.0f32).to_bits());
        // n_z = 0: a great circle through the zenith.
        let (u, _) = ellipse_from_edge(Vec3::new(1.0, 0.0, 1.0), Vec3::new(2.0, 0.0, 1.0));
        assert!(is_degenerate(u) && !is_inner(u));
        assert_eq!(ellipse_area_in_sector(u, [1.0, 0.0], [0.0, 1.0]), 0.0);
    }

    #[test]
    fn homogeneous_quadratic_roots_are_roots() {
        let mut rng = Rng::new(8);
        for _ in 0..10_000 {
            let (xx, xy, yy) = (
                rng.signed_log_uniform(-3.0, 3.0) as f32,
                rng.signed_log_uniform(-3.0, 3.0) as f32,
                rng.signed_log_uniform(-3.0, 3.0) as f32,
            );
            if (xy as f64).powi(2) / 4.0 <= xx as f64 * yy as f64 {
                continue; // no real root
            }
            let w = solve_homogeneous_quadratic(xx, xy, yy);
            let (x, y) = (w[0] as f64, w[1] as f64);
            let value = xx as f64 * x * x + xy as f64 * x * y + yy as f64 * y * y;
            let scale = (xx.abs() as f64 + xy.abs() as f64 + yy.abs() as f64) * (x * x + y * y);
            assert!(scale > 0.0);
            assert!(value.abs() <= 1e-5 * scale, "{xx} {xy} {yy}: {value}");
        }
    }

    /// Issue 15: the discriminant takes the plain difference `b² - xx yy` exactly where
    /// no cancellation is possible, `xx yy <= 0` or `xx yy` so small against `b²` that
    /// the rounded sum and difference of the two products are equal (relative error at
    /// most ε either way), and the error-free form elsewhere: pinned on the root's bits,
    /// in builds with and without FMA (whose error-free form rounds differently from
    /// the plain one).
    #[test]
    fn the_discriminant_is_plain_only_where_the_products_cannot_cancel() {
        let root = |b: f32, discriminant: f32| b.abs() + crate::math::sqrtf(discriminant.max(0.0));
        let mut rng = Rng::new(15);
        let (mut plain, mut careful) = (0, 0);
        for _ in 0..100_000 {
            let (xx, xy, yy) = (
                rng.signed_log_uniform(-3.0, 3.0) as f32,
                rng.signed_log_uniform(-3.0, 3.0) as f32,
                rng.signed_log_uniform(-3.0, 3.0) as f32,
            );
            let b = 0.5 * xy;
            let w = solve_homogeneous_quadratic(xx, xy, yy);
            let got = if b >= 0.0 { w[0] } else { w[1] };
            let (p1, p2) = (b * b, xx * yy);
            let expected = if p2 <= 0.0 || p1 + p2 == p1 - p2 {
                plain += 1;
                root(b, b * b - xx * yy)
            } else {
                careful += 1;
                root(b, difference_of_products(b, b, xx, yy))
            };
            assert_eq!(got.to_bits(), expected.to_bits(), "{xx} {xy} {yy}");
        }
        assert!(plain > 40_000 && careful > 40_000, "{plain} {careful}");
    }
}
