//! Cosine-weighted sampling of *small* polygons: solid angle sampling (Algorithm 5) with
//! an exact warp per fan triangle towards a density that is linear in the position on the
//! triangle. This is the alternative that [`ProjectedPolygon`](super::ProjectedPolygon) switches to when
//! a polygon spans less than [`SMALL_EXTENT`] radians, where the ellipse construction in
//! `f32` loses precision (see its documentation).
//!
//! Solid angle sampling maps `(a, u1) ∈ [0, 1]²` onto fan triangle `k` with apex `A` and
//! far edge `B C`: `a` is the fraction of the triangle's solid angle swept from `A B`, and
//! the direction lies at `t = √u1` of the way from `A` to the point `(1 - a) B + a C` of
//! the far edge (exactly so for a planar triangle; up to relative `O(s²)` for a spherical
//! one of angular size `s`). The area element in `(a, t)` is proportional to `t`, and the
//! cosine, a linear function of the direction, becomes
//! `ℓ(a, t) = z_A + t ((1 - a) z_B + a z_C - z_A)`.
//!
//! The sampler draws `(a, t)` with density `∝ t ℓ(a, t)`, exactly:
//! - `a` from the linear marginal `m(a) ∝ (1 - a) m0 + a m1`, `m0 = z_A/6 + z_B/3`,
//!   `m1 = z_A/6 + z_C/3`, inverted in closed form;
//! - `t` from the conditional `∝ t ((1 - t) z_A + t z_f)` with `z_f = (1 - a) z_B + a z_C`,
//!   whose CDF is a cubic, inverted by safeguarded Newton steps;
//!
//! and picks triangle `k` in proportion to `Ω_k z̄_k` with `z̄_k = (z_A + z_B + z_C) / 3`,
//! the mean of `ℓ` over the triangle. The density over solid angle is then exactly
//! `ℓ / Φ̃` with `Φ̃ = Σ Ω_k z̄_k` (this sampler's [`pdf`](SmallPolygonCosineSampler::pdf),
//! through the inverse of solid angle sampling), and `ℓ / Φ̃` differs from the ideal
//! `ω_z / Φ` by relative `O(s²)` (below 0.2 s², 2e-5 at the switch-over size).
//! [`ProjectedPolygon`](super::ProjectedPolygon) reports `ω_z / Φ` itself, from the direction's own `z`
//! (see its `pdf`): the warp's density evaluated at an `f32` direction loses the relative
//! precision of `ω_z` next to the horizon. The projected solid angle `Φ` is computed in
//! closed form per triangle (see `mean_cosine`), to relative `O(s⁴)`.

use super::solid_angle::{MAX_TRIANGLES, SolidAnglePolygon};
use crate::sample::{pad_unselectable, select_piece};
use crate::{Sample, Vec3};

/// The angular extent (sine of the largest angle between the first vertex and another)
/// below which
/// [`ProjectedPolygon`] uses this sampler: 1e-2 rad, polygons up to about 1e-4
/// sr. There the ellipse construction's areas lose about `3e-7 × condition` of relative
/// precision (the condition, outer area over Φ, grows like `1/s`: 100 to 500 at this
/// size), while this sampler's pdf deviates from `ω_z / Φ` by at most `0.2 s²` = 2e-5 and
/// its `Φ` is accurate to `O(s⁴)`.
///
/// [`ProjectedPolygon`]: super::ProjectedPolygon
pub const SMALL_EXTENT: f32 = 1e-2;

/// The largest squared extent for which a sliver (a polygon seen nearly edge-on, whose
/// ellipse areas cancel badly) is handed to this sampler: `0.2 s²` stays below 1e-4.
pub const SLIVER_EXTENT2: f32 = 5e-4;

/// A small convex polygon prepared for cosine-weighted sampling by warped solid angle
/// sampling.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmallPolygonCosineSampler {
    fan: SolidAnglePolygon,
    /// `Ω_k z̄_k` per fan triangle.
    weight: [f32; MAX_TRIANGLES],
    /// Sum of the weights of the triangles before each triangle.
    weight_start: [f32; MAX_TRIANGLES],
    /// `Φ = ∫ ω_z dω` by Gauss quadrature (relative error `O(s⁴)`; 0 when empty).
    projected_solid_angle: f32,
    /// `Φ̃ = Σ Ω_k z̄_k`, the normalisation of `ℓ` (0 when empty).
    linear_integral: f32,
    /// `1 / Φ̃` (0 when empty).
    density: f32,
    /// Triangles up to the last one with non-zero weight (0 when empty).
    selectable_triangles: u32,
}

impl SmallPolygonCosineSampler {
    pub const EMPTY: Self = Self {
        fan: SolidAnglePolygon::EMPTY,
        weight: [0.0; MAX_TRIANGLES],
        weight_start: [0.0; MAX_TRIANGLES],
        projected_solid_angle: 0.0,
        linear_integral: 0.0,
        density: 0.0,
        selectable_triangles: 0,
    };

    /// Prepares a polygon that lies entirely on or above the horizon (already clipped).
    #[must_use]
    pub fn new(vertices: &[Vec3]) -> Option<Self> {
        let mut sampler = Self::EMPTY;
        sampler.prepare(vertices).then_some(sampler)
    }

    /// [`new`](Self::new) in place: writes the prepared sampler into `self` and returns
    /// `true`, or writes [`EMPTY`](Self::EMPTY) and returns `false`.
    pub fn prepare(&mut self, vertices: &[Vec3]) -> bool {
        let prepared = self.fan.prepare(vertices) && self.prepare_weights();
        super::keep_or_empty(self, prepared, Self::EMPTY)
    }

    /// The weights of the prepared fan; `false` when no triangle can be selected.
    #[inline(always)]
    fn prepare_weights(&mut self) -> bool {
        let fan = &self.fan;
        let triangles = fan.vertex_count as usize - 2;
        let z_apex = fan.vertices[0].z.max(0.0);
        let mut total = 0.0f32;
        let mut projected = 0.0f32;
        self.selectable_triangles = 0;
        for k in 0..triangles {
            // Each triangle's own solid angle, not a difference of the running sums, which
            // would lose the precision of small triangles next to large ones.
            let solid_angle = fan.triangle_solid_angle(k);
            let (zb, zc) = (
                fan.vertices[k + 1].z.max(0.0),
                fan.vertices[k + 2].z.max(0.0),
            );
            let weight = solid_angle * (z_apex + zb + zc) * (1.0 / 3.0);
            projected += solid_angle * mean_cosine(fan, k, (z_apex, zb, zc));
            self.weight[k] = weight;
            self.weight_start[k] = total;
            if weight > 0.0 && (k as u32) < fan.selectable_triangles {
                self.selectable_triangles = k as u32 + 1;
            }
            total += weight;
        }
        let density = 1.0 / total;
        if !(total > 0.0) || !density.is_finite() || self.selectable_triangles == 0 {
            return false;
        }
        for k in triangles..MAX_TRIANGLES {
            // The unused slots as in the empty value: no stale or NaN word is left.
            self.weight[k] = 0.0;
        }
        pad_unselectable(&mut self.weight_start, self.selectable_triangles);
        self.projected_solid_angle = projected.max(0.0);
        self.linear_integral = total;
        self.density = density;
        true
    }

    /// The slack of [`pdf_within`](Self::pdf_within) that keeps `∫ pdf dω` within about
    /// 2e-5 of 1: the smaller of `rounding` and 2e-5 of the polygon's width `Ω / P` (its
    /// solid angle over its perimeter in radians), so that the band of that width around
    /// the boundary holds at most 2e-5 of the polygon (issue 16, 1: 16 ulps alone gave
    /// `∫ pdf = 1.0086` at 1e-6 sr and 1.285 at 8e-10 sr).
    pub(crate) fn tolerance(&self, rounding: f32) -> f32 {
        let fan = &self.fan;
        let count = super::stored_count(fan.vertex_count, crate::MAX_POLYGON_VERTICES);
        let mut perimeter = 0.0f32;
        for i in 0..count {
            let next = if i + 1 == count { 0 } else { i + 1 };
            perimeter += crate::math::length(fan.vertices[next] - fan.vertices[i]);
        }
        let width = fan.solid_angle() / perimeter;
        if width.is_finite() {
            rounding.min(2e-5 * width)
        } else {
            rounding
        }
    }

    /// Whether `dir` lies in the polygon or outside by at most `tolerance` radians (see
    /// [`SolidAnglePolygon::contains_within`]).
    #[inline(always)]
    pub(crate) fn contains_within(&self, dir: Vec3, tolerance: f32) -> bool {
        self.fan.contains_within(dir, tolerance)
    }

    /// The mean of the polygon's unit vertex directions: a direction inside it (convex,
    /// smaller than a hemisphere), towards which `sample`'s callers pull a direction
    /// that rounding put outside.
    pub(crate) fn inner_direction(&self) -> Vec3 {
        let fan = &self.fan;
        let count = super::stored_count(fan.vertex_count, crate::MAX_POLYGON_VERTICES);
        let mut sum = Vec3::ZERO;
        for v in &fan.vertices[..count] {
            sum += *v;
        }
        crate::math::normalize_or(sum, Vec3::Z)
    }

    /// The projected solid angle `Φ` (within relative `O(s⁴)`).
    #[inline]
    pub fn projected_solid_angle(&self) -> f32 {
        self.projected_solid_angle
    }

    /// The cosines at the apex and at the two ends of the far edge of triangle `k`.
    #[inline(always)]
    fn cosines(&self, k: usize) -> (f32, f32, f32) {
        (
            self.fan.vertices[0].z.max(0.0),
            self.fan.vertices[k + 1].z.max(0.0),
            self.fan.vertices[k + 2].z.max(0.0),
        )
    }

    /// Draws a direction with density `ℓ / Φ̃` (see the module documentation); `u` in
    /// `[0, 1)²`, already clamped by the caller.
    #[inline]
    pub fn sample(&self, u0: f32, u1: f32) -> Sample {
        if self.selectable_triangles == 0 {
            return Sample::NONE;
        }
        let target = u0 * self.linear_integral;
        let k = select_piece(&self.weight_start, target);
        let xi = ((target - self.weight_start[k]) / self.weight[k]).clamp(0.0, 1.0);
        let (za, zb, zc) = self.cosines(k);
        // The linear marginal in a (pbrt's stable form of the quadratic's root).
        let (m0, m1) = (
            za * (1.0 / 6.0) + zb * (1.0 / 3.0),
            za * (1.0 / 6.0) + zc * (1.0 / 3.0),
        );
        let a = if m0 == m1 {
            xi
        } else {
            let root = crate::math::sqrtf((1.0 - xi) * m0 * m0 + xi * m1 * m1);
            (xi * (m0 + m1) / (m0 + root)).clamp(0.0, 1.0)
        };
        let zf = (1.0 - a) * zb + a * zc;
        let t = invert_cubic_cdf(u1, za, zf);
        let triangle_solid_angle = self.fan.triangle_solid_angle(k);
        let sample = self
            .fan
            .sample_in_triangle(k, a * triangle_solid_angle, t * t);
        let cosine = (1.0 - t) * za + t * zf;
        // Only rounding puts a direction of the clipped fan below the horizon (found by
        // fuzzing: z = -3e-10 with pdf > 0 for a polygon 4e-8 rad across the horizon):
        // clamp as clipped solid angle sampling does, keeping the unit length.
        let mut dir = sample.dir;
        if dir.z < 0.0 {
            dir.z = 0.0;
            dir = crate::math::unit_if_needed(dir);
        }
        if !dir.is_finite() {
            return Sample::NONE;
        }
        Sample::new_or_none(dir, cosine * self.density)
    }

    /// `ℓ / Φ̃` at the direction (through the inverse of solid angle sampling), 0 outside
    /// the polygon or at or below the horizon.
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        self.pdf_within(dir, 0.0)
    }

    /// [`pdf`](Self::pdf) extended to directions outside the polygon by at most
    /// `tolerance` radians (the density formula continued there), for samplers that map
    /// this sampler's directions through a transformation whose rounding may move them
    /// slightly out (the LTC polygon). With `tolerance = 0` this is `pdf`.
    pub(crate) fn pdf_within(&self, dir: Vec3, tolerance: f32) -> f32 {
        if !(dir.z > 0.0) {
            return 0.0;
        }
        let Some((k, local, u1)) = self.fan.invert_in_triangle_within(dir, tolerance) else {
            return 0.0;
        };
        let triangle_solid_angle = self.fan.triangle_solid_angle(k);
        let a = if triangle_solid_angle > 0.0 {
            (local / triangle_solid_angle).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (za, zb, zc) = self.cosines(k);
        let t = crate::math::sqrtf(u1);
        let cosine = (1.0 - t) * za + t * ((1.0 - a) * zb + a * zc);
        cosine * self.density
    }
}

/// The mean of `ω_z` over fan triangle `k` under uniform solid angle sampling, to
/// relative `O(s⁴)` in closed form.
///
/// The spherical triangle is the central projection of the planar one with the unit
/// vertex directions `v_i`; a point `P = Σ b_i v_i` (barycentric `b`) projects to
/// `ω = P / |P|`, with `ω_z = ℓ / |P|`, `ℓ = Σ b_i z_i`, and the solid angle element is
/// `h |P|⁻³ dA` (`h` the plane's distance from the origin). With
/// `|P|² = 1 - q`, `q = Σ_(i<j) b_i b_j d_ij²`, `d_ij = |v_i - v_j|`, the mean is
/// `∫ ℓ |P|⁻⁴ dA / ∫ |P|⁻³ dA = z̄ + 2 E[ℓ q] - (3/2) z̄ E[q] + O(s⁴)`, and the moments
/// of the uniform distribution on the triangle (`E[b_i b_j] = 1/12`,
/// `E[b_i² b_j] = 1/30`, `E[b_i b_j b_k] = 1/60`) give
///
/// `z̄ + Σ_(i<j) d_ij² (3 (z_i + z_j) - z_k) / 120`, `z̄ = (z_0 + z_1 + z_2) / 3`.
///
/// Every term comes from the vertices' own cosines (accurate next to the horizon too,
/// and exactly 0 for clipped vertices) and squared distances; a quadrature of the cosines
/// of `f32` directions inside the triangle was off by an ulp of 1 per node, up to 13 %
/// for a polygon 3e-5 rad across standing on the horizon (issue 16, 3). Checked against
/// f64 quadrature: relative error 2e-10 at `s = 5e-3`, 7e-5 at `s = 0.1`.
fn mean_cosine(fan: &SolidAnglePolygon, k: usize, cosines: (f32, f32, f32)) -> f32 {
    let v = [fan.vertices[0], fan.vertices[k + 1], fan.vertices[k + 2]];
    let z = [cosines.0, cosines.1, cosines.2];
    let mut correction = 0.0f32;
    for (i, j, other) in [(0, 1, 2), (0, 2, 1), (1, 2, 0)] {
        correction += (v[i] - v[j]).length_squared() * (3.0 * (z[i] + z[j]) - z[other]);
    }
    (z[0] + z[1] + z[2]) * (1.0 / 3.0) + correction * (1.0 / 120.0)
}

/// The `t ∈ [0, 1]` with `G(t) = ξ`, where `G` is the CDF of the density
/// `∝ t ((1 - t) e + t f)` (`e, f >= 0`, not both 0):
/// `G(t) = (e t²/2 + (f - e) t³/3) / (e/2 + (f - e)/3)`.
///
/// Newton's method from the root of the nearer pure case (`√ξ` for `f ≈ e`, `∛ξ` when
/// `e` is small), safeguarded by bisection on a bracket that every step shrinks; 8 steps
/// reach `f32` precision for every ratio `e / f` (asserted by a test), and 2 or 3 suffice
/// for the near-constant cosines of small polygons away from the horizon.
#[inline(always)]
fn invert_cubic_cdf(xi: f32, e: f32, f: f32) -> f32 {
    let d = f - e;
    let total = e * 0.5 + d * (1.0 / 3.0);
    if !(total > 0.0) {
        return crate::math::sqrtf(xi);
    }
    let target = xi * total;
    let mut t = if e >= f * 0.25 {
        crate::math::sqrtf(xi)
    } else {
        libm::cbrtf(xi)
    };
    let (mut lo, mut hi) = (0.0f32, 1.0f32);
    for _ in 0..8 {
        let value = t * t * (e * 0.5 + d * (1.0 / 3.0) * t) - target;
        if value > 0.0 {
            hi = t;
        } else {
            lo = t;
        }
        let slope = t * (e + d * t);
        let newton = t - value / slope;
        t = if newton >= lo && newton <= hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::Rng;

    #[test]
    fn cubic_cdf_inversion_is_exact_for_all_cosine_ratios() {
        let mut rng = Rng::new(1);
        for _ in 0..100_000 {
            let (e, f) = (rng.uniform(), rng.uniform());
            let (e, f) = match rng.below(4) {
                0 => (0.0, f),
                1 => (e, e * (1.0 + 1e-3 * (rng.uniform() - 0.5))),
                _ => (e, f),
            };
            let xi = rng.uniform();
            let t = invert_cubic_cdf(xi as f32, e as f32, f as f32) as f64;
            let cdf =
                |t: f64| (e * t * t / 2.0 + (f - e) * t * t * t / 3.0) / (e / 2.0 + (f - e) / 3.0);
            assert!((cdf(t) - xi).abs() < 2e-6, "e {e} f {f} xi {xi}: t {t}");
        }
    }
}
