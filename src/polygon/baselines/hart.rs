//! Bilinear and biquadratic warps of solid angle sampling towards the cosine (Hart,
//! Pharr, Müller, Lopes, McGuire and Shirley 2020, "Practical Product Sampling by
//! Fitting and Composing Warps", EGSR), composed with the solid angle sampler of Peters
//! 2021 (supplement C, Algorithm 5). Two baselines of Peters 2021.
//!
//! Solid angle sampling maps the primary square `[0, 1)²` to the polygon with constant
//! density `1 / Ω`. The warps first draw a point `u'` of the square from a simple
//! density `p(u')` fitted to the cosine, then map it: `dir = solid_angle.sample(u')`,
//! so that the density per steradian is `p(u') / Ω`. The fit takes the cosine
//! `max(dir.z, 0)` at the directions that solid angle sampling gives for a grid of
//! primary points:
//!
//! - **bilinear**: the 2×2 corners `u' ∈ {0, 1 - ulp}²`; `p` is their bilinear
//!   interpolation, normalised. Drawn by its marginal in `u'_0` (linear) and the
//!   conditional in `u'_1` (linear), each inverted in closed form.
//! - **biquadratic**: the 3×3 points `u' ∈ {0, 1/2, 1 - ulp}²`. The biquadratic that
//!   interpolates them is written in the tensor-product Bernstein basis
//!   `B_0 = (1 - t)², B_1 = 2 t (1 - t), B_2 = t²` (per axis the control points are
//!   `f(0)`, `2 f(1/2) - (f(0) + f(1)) / 2`, `f(1)`). An interpolant of non-negative
//!   values can still dip below zero; the construction here clamps negative control
//!   points to zero, which makes the density non-negative everywhere (a Bernstein
//!   polynomial lies in the convex hull of its control points) at the price of no
//!   longer interpolating the values near a clamped control point. The density is drawn
//!   by its marginal in `u'_0` and the conditional in `u'_1`, both quadratics in
//!   Bernstein form whose cumulative distributions are cubics in Bernstein form with
//!   control points `(0, d_0, d_0 + d_1, d_0 + d_1 + d_2) / Σd`. Each cubic is inverted
//!   by Newton's method safeguarded by bisection (at most 24 steps, down to `f32`
//!   resolution); the inverse of the warp only evaluates the cubics.
//!
//! The grid follows solid angle sampling's parameterisation: `u'_1 = 0` is the fan
//! apex (vertex 0) for every `u'_0`, `u'_1 = 1 - ulp` the polygon's boundary opposite
//! the apex. For polygons of more than 3 vertices the corners see only the first and
//! last fan vertex; the 1/2 column of the biquadratic sees the fan's middle.
//!
//! These are *approximations* of cosine-weighted sampling, i.e. baselines: the density
//! is a low-order polynomial in the primary square, not proportional to the cosine.
//! Estimators stay unbiased because `sample` reports the density it used and `pdf`
//! computes the same density (through the inverse of solid angle sampling).
//!
//! Below the horizon. Polygons are not clipped: solid angle sampling covers the whole
//! polygon, and the warp's density in the part below the horizon is whatever the
//! polynomial is there (corner values are clamped to 0, the interpolant is not). Such
//! samples are never returned: `sample` reports "no sample" (`pdf == 0`) for a
//! direction with `z <= 0`, and `pdf(dir)` is 0 for `dir.z <= 0`, consistently. The
//! density is thus a sub-probability on the upper hemisphere whose missing mass is the
//! warp's mass below the horizon; estimators of integrands that vanish for `z <= 0`
//! (anything with a clamped cosine) remain unbiased.
//!
//! Degenerate fits. When all fitted values are 0 (every grid direction at or below the
//! horizon) the warp falls back to the uniform density, i.e. plain solid angle sampling
//! (restricted to `z > 0` as above), which is still unbiased when part of the polygon
//! between the grid directions lies above the horizon. A polygon entirely below the
//! horizon is therefore prepared, and all its samples have `pdf == 0`.

use crate::polygon::SolidAnglePolygon;
use crate::sample::{ONE_MINUS_ULP, clamp_inverted, clamp_random};
use crate::{Sample, Vec3};

/// The most Newton (or bisection) steps that invert one cubic distribution function.
/// Bisection alone halves the bracket per step, so 24 steps reach the `f32` resolution
/// of `[0, 1]` even if Newton never helps; on the tests' polygons 3.7 to 4.4 steps are
/// taken on average.
const NEWTON_STEPS: u32 = 24;

/// The cosine `max(dir.z, 0)` of the direction that solid angle sampling produces for
/// the primary point `u`.
fn cosine_at(polygon: &SolidAnglePolygon, u: [f32; 2]) -> f32 {
    // The direction of the primary point itself, not pulled inside (as `finish` draws).
    let sample = polygon.sample_unchecked(u);
    if sample.pdf > 0.0 {
        // `max` maps NaN to 0 (the direction is finite anyway).
        sample.dir.z.max(0.0)
    } else {
        0.0
    }
}

/// Scales non-negative values so that they sum to `N` (mean 1), or sets them all to 1
/// when none is positive. Dividing by the largest value first keeps the sum in `[1, N]`.
fn normalise_to_mean_one<const N: usize>(values: [f32; N]) -> [f32; N] {
    let largest = values.iter().fold(0.0f32, |a, &b| a.max(b));
    if !(largest > 0.0) || !largest.is_finite() {
        return [1.0; N];
    }
    let scaled = values.map(|v| v.max(0.0) / largest);
    let sum: f32 = scaled.iter().sum();
    let factor = N as f32 / sum;
    scaled.map(|v| v * factor)
}

/// The sample's density per steradian `density / Ω` at the warped point, or "no sample"
/// when solid angle sampling gives no direction, the direction has `z <= 0` (see the
/// module documentation), or the density vanishes.
#[inline(always)]
fn finish(polygon: &SolidAnglePolygon, warped: [f32; 2], density: f32, inv_omega: f32) -> Sample {
    // As drawn (no pull inside for narrow polygons): `pdf` inverts the direction to the
    // primary sample, which a pulled direction would not give back.
    let sample = polygon.sample_unchecked(warped);
    let pdf = density * inv_omega;
    if sample.pdf > 0.0 && sample.dir.z > 0.0 && pdf > 0.0 && pdf.is_finite() {
        Sample {
            dir: sample.dir,
            pdf,
        }
    } else {
        Sample::NONE
    }
}

/// `dir` scaled by a power of two (exactly, so that the inside test sees the same
/// signs) to a largest coordinate in `[1, 2)` (or below, for subnormal input), so that
/// neither tiny nor huge directions underflow or overflow; `None` unless `dir` is finite, non-zero and has `z > 0`: the
/// directions at which the warps have a density. (The bit trick is the one of the solid
/// angle sampler's rescaling: `2^(127 - E)` for the biased exponent `E`.)
#[inline(always)]
fn upper_direction(dir: Vec3) -> Option<Vec3> {
    let largest = dir.abs().max_element();
    if !(dir.z > 0.0 && largest.is_finite()) {
        return None;
    }
    let biased_exponent = (largest.to_bits() >> 23) & 0xFF;
    Some(dir * f32::from_bits(254u32.saturating_sub(biased_exponent).max(1) << 23))
}

/// Draws `x ∈ [0, 1]` with density proportional to `(1 - x) a + x b` (`a, b >= 0`):
/// the root of the quadratic distribution function in the form
/// `x = ξ (a + b) / (a + sqrt((1 - ξ) a² + ξ b²))`, which has no cancellation for any
/// `a, b` (the textbook root `(sqrt(..) - a) / (b - a)` cancels when `a ≈ b`). Uniform
/// when `a = b = 0`.
#[inline(always)]
pub(crate) fn sample_linear(xi: f32, a: f32, b: f32) -> f32 {
    let denominator = a + crate::math::sqrtf((1.0 - xi) * a * a + xi * b * b);
    if denominator > 0.0 {
        (xi * (a + b) / denominator).min(1.0)
    } else {
        xi
    }
}

/// The distribution function of [`sample_linear`]:
/// `F(x) = x (a (2 - x) + b x) / (a + b)`, a sum of non-negative terms.
#[inline(always)]
pub(crate) fn linear_cdf(x: f32, a: f32, b: f32) -> f32 {
    let sum = a + b;
    if sum > 0.0 {
        x * (a * (2.0 - x) + b * x) / sum
    } else {
        x
    }
}

/// `Σ d_i B_i(t)` in the quadratic Bernstein basis.
#[inline(always)]
pub(crate) fn quadratic_bernstein(t: f32, d: [f32; 3]) -> f32 {
    let s = 1.0 - t;
    d[0] * (s * s) + d[1] * (2.0 * s * t) + d[2] * (t * t)
}

/// The distribution function of the density `3 Σ d_i B_i(t) / Σ d` on `[0, 1]`
/// (`d_i >= 0`): the cubic Bernstein polynomial with control points
/// `(0, d_0, d_0 + d_1, Σ d) / Σ d`, all terms non-negative. The identity when
/// `Σ d = 0`.
#[inline(always)]
pub(crate) fn quadratic_cdf(t: f32, d: [f32; 3]) -> f32 {
    let sum = d[0] + d[1] + d[2];
    if !(sum > 0.0) {
        return t;
    }
    let s = 1.0 - t;
    let first = d[0];
    let second = d[0] + d[1];
    (3.0 * s * t * (s * first + t * second) + t * t * t * sum) / sum
}

/// Draws `t ∈ [0, 1]` with density proportional to `Σ d_i B_i(t)` (`d_i >= 0`) by
/// inverting [`quadratic_cdf`]: Newton's method from a first guess, with a bracket
/// that every step shrinks and bisection whenever a Newton step would leave it (the
/// density may vanish at an end). Uniform when `Σ d = 0`.
pub(crate) fn sample_quadratic(xi: f32, d: [f32; 3]) -> f32 {
    let sum = d[0] + d[1] + d[2];
    if !(sum > 0.0) {
        return xi;
    }
    let scale = 3.0 / sum;
    // First guess: the root of the linear density through the end values, which is
    // exact when the quadratic is linear (d_1 = (d_0 + d_2) / 2).
    let mut t = sample_linear(xi, d[0], d[2]);
    let (mut low, mut high) = (0.0f32, 1.0f32);
    for _ in 0..NEWTON_STEPS {
        let residual = quadratic_cdf(t, d) - xi;
        if residual == 0.0 {
            break;
        }
        let density = quadratic_bernstein(t, d) * scale;
        let next = crate::math::safeguarded_newton_step(t, residual, density, &mut low, &mut high);
        let step = (next - t).abs();
        t = next;
        if step <= 0.5 * f32::EPSILON * t.max(f32::EPSILON) || high - low <= f32::EPSILON {
            break;
        }
    }
    t
}

/// Solid angle sampling warped by a bilinear density fitted to the cosine at the four
/// corners of the primary square (Hart et al. 2020), an approximation of cosine-weighted
/// sampling whose pdf is exact for the samples it draws. Directions at or below the
/// horizon get "no sample" and pdf 0.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HartBilinearPolygon {
    /// The solid angle sampler that the warp composes with.
    solid_angle: SolidAnglePolygon,
    /// The warp density at the corners `(0, 0), (1, 0), (0, 1), (1, 1)` of the primary
    /// square `(u'_0, u'_1)`, normalised to mean 1 so that their bilinear interpolation
    /// is the density on the square.
    corners: [f32; 4],
    /// `1 / Ω` (0 when empty).
    inv_solid_angle: f32,
}

impl Default for HartBilinearPolygon {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl HartBilinearPolygon {
    /// The state of a polygon that could not be prepared: samples have `pdf == 0` and
    /// `pdf()` is 0.
    pub const EMPTY: Self = Self {
        solid_angle: SolidAnglePolygon::EMPTY,
        corners: [0.0; 4],
        inv_solid_angle: 0.0,
    };

    /// Prepares the convex polygon with the given vertices (positions relative to the
    /// shading point, not normalised, either winding, 3 to 8 of them): the solid angle
    /// sampler and the cosine at the corners of its primary square.
    ///
    /// Returns `None` when [`SolidAnglePolygon::new`] does, and when the largest
    /// density (four times the mean) would overflow. A polygon at or below the horizon
    /// is prepared (see the module documentation).
    #[must_use]
    pub fn new(vertices: &[Vec3]) -> Option<Self> {
        let mut polygon = Self::EMPTY;
        polygon.prepare(vertices).then_some(polygon)
    }

    /// [`new`](Self::new) in place: writes the prepared warp into `self` and returns
    /// `true`, or writes [`EMPTY`](Self::EMPTY) and returns `false`.
    pub fn prepare(&mut self, vertices: &[Vec3]) -> bool {
        let prepared = self.solid_angle.prepare(vertices) && {
            let inv_solid_angle = 1.0 / self.solid_angle.solid_angle();
            let mut corners = [0.0f32; 4];
            for (k, corner) in corners.iter_mut().enumerate() {
                let u = [(k & 1) as f32, (k >> 1) as f32].map(|x| x.min(ONE_MINUS_ULP));
                *corner = cosine_at(&self.solid_angle, u);
            }
            self.corners = normalise_to_mean_one(corners);
            self.inv_solid_angle = inv_solid_angle;
            (4.0 * inv_solid_angle).is_finite()
        };
        crate::polygon::keep_or_empty(self, prepared, Self::EMPTY)
    }

    /// The end values of the marginal density of `u'_0`, `(1 - x) a + x b`.
    #[inline(always)]
    fn marginal(&self) -> (f32, f32) {
        let [w00, w10, w01, w11] = self.corners;
        (0.5 * (w00 + w01), 0.5 * (w10 + w11))
    }

    /// The end values of the density along `u'_1` at `u'_0 = x` (unnormalised
    /// conditional; the joint density at `(x, y)` is `(1 - y) c + y d`).
    #[inline(always)]
    fn conditional(&self, x: f32) -> (f32, f32) {
        let [w00, w10, w01, w11] = self.corners;
        ((1.0 - x) * w00 + x * w10, (1.0 - x) * w01 + x * w11)
    }

    /// The warp's density on the primary square at `u'` (mean 1 over the square).
    #[inline]
    pub fn warp_density(&self, warped: [f32; 2]) -> f32 {
        let (c, d) = self.conditional(warped[0]);
        let y = warped[1];
        (1.0 - y) * c + y * d
    }

    /// Solid angle Ω of the (unclipped) polygon in steradians (0 when empty).
    #[inline]
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle.solid_angle()
    }

    /// Draws a direction: `u'` from the bilinear density, then solid angle sampling at
    /// `u'`. `u` is clamped to `[0, 1 - ulp]`; NaN counts as 0. The pdf is the warp
    /// density at `u'` over Ω; "no sample" (`pdf == 0`, finite direction) for an empty
    /// polygon and for directions with `z <= 0`.
    #[inline]
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        if !(self.inv_solid_angle > 0.0) {
            return Sample::NONE;
        }
        let (u0, u1) = (clamp_random(u[0]), clamp_random(u[1]));
        let (a, b) = self.marginal();
        let x = sample_linear(u0, a, b);
        let (c, d) = self.conditional(x);
        let y = sample_linear(u1, c, d);
        let density = (1.0 - y) * c + y * d;
        finish(&self.solid_angle, [x, y], density, self.inv_solid_angle)
    }

    /// The density per steradian of [`sample`](Self::sample) in direction `dir` (need
    /// not be normalised): 0 for `dir.z <= 0`, outside the polygon, for zero or
    /// non-finite directions, and when the polygon is empty.
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        match upper_direction(dir).and_then(|dir| self.solid_angle.invert_strictly_inside(dir)) {
            Some(warped) => self.warp_density(warped) * self.inv_solid_angle,
            None => 0.0,
        }
    }

    /// The random numbers `u` for which [`sample`](Self::sample) returns `dir` (up to
    /// rounding), or `None` when `dir.z <= 0`, `dir` is outside the polygon, or the
    /// polygon is empty.
    pub fn invert(&self, dir: Vec3) -> Option<[f32; 2]> {
        let [x, y] = self
            .solid_angle
            .invert_strictly_inside(upper_direction(dir)?)?;
        let (a, b) = self.marginal();
        let (c, d) = self.conditional(x);
        Some([
            clamp_inverted(linear_cdf(x, a, b)),
            clamp_inverted(linear_cdf(y, c, d)),
        ])
    }
}

/// Solid angle sampling warped by a biquadratic density fitted to the cosine at 3×3
/// points of the primary square (Hart et al. 2020), made non-negative by clamping its
/// Bernstein control points: an approximation of cosine-weighted sampling whose pdf is
/// exact for the samples it draws. Directions at or below the horizon get "no sample"
/// and pdf 0.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HartBiquadraticPolygon {
    /// The solid angle sampler that the warp composes with.
    solid_angle: SolidAnglePolygon,
    /// Bernstein control points `c[i + 3 j]` (`i` along `u'_0`, `j` along `u'_1`), all
    /// non-negative, normalised to mean 1 so that `Σ c_ij B_i(x) B_j(y)` is the density
    /// on the square.
    controls: [f32; 9],
    /// Control points of the marginal density of `u'_0`: `Σ_j c[i + 3 j] / 3`.
    marginal: [f32; 3],
    /// `1 / Ω` (0 when empty).
    inv_solid_angle: f32,
}

impl Default for HartBiquadraticPolygon {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// The grid of the biquadratic fit along each axis of the primary square.
const BIQUADRATIC_GRID: [f32; 3] = [0.0, 0.5, ONE_MINUS_ULP];

/// Bernstein control points of the quadratic through `(0, f0), (1/2, f1), (1, f2)`.
#[inline(always)]
fn interpolating_controls(f: [f32; 3]) -> [f32; 3] {
    [f[0], 2.0 * f[1] - 0.5 * (f[0] + f[2]), f[2]]
}

impl HartBiquadraticPolygon {
    /// The state of a polygon that could not be prepared: samples have `pdf == 0` and
    /// `pdf()` is 0.
    pub const EMPTY: Self = Self {
        solid_angle: SolidAnglePolygon::EMPTY,
        controls: [0.0; 9],
        marginal: [0.0; 3],
        inv_solid_angle: 0.0,
    };

    /// Prepares the convex polygon with the given vertices (positions relative to the
    /// shading point, not normalised, either winding, 3 to 8 of them): the solid angle
    /// sampler, the cosine at the 3×3 grid points of its primary square and the
    /// Bernstein control points of the clamped interpolant.
    ///
    /// Returns `None` when [`SolidAnglePolygon::new`] does, and when the largest
    /// possible density (nine times the mean) would overflow. A polygon at or below the
    /// horizon is prepared (see the module documentation).
    #[must_use]
    pub fn new(vertices: &[Vec3]) -> Option<Self> {
        let mut polygon = Self::EMPTY;
        polygon.prepare(vertices).then_some(polygon)
    }

    /// [`new`](Self::new) in place: writes the prepared warp into `self` and returns
    /// `true`, or writes [`EMPTY`](Self::EMPTY) and returns `false`.
    pub fn prepare(&mut self, vertices: &[Vec3]) -> bool {
        let prepared = self.solid_angle.prepare(vertices) && {
            let inv_solid_angle = 1.0 / self.solid_angle.solid_angle();
            let mut values = [0.0f32; 9];
            for j in 0..3 {
                for i in 0..3 {
                    values[i + 3 * j] = cosine_at(
                        &self.solid_angle,
                        [BIQUADRATIC_GRID[i], BIQUADRATIC_GRID[j]],
                    );
                }
            }
            self.fit(inv_solid_angle, values);
            (9.0 * inv_solid_angle).is_finite()
        };
        crate::polygon::keep_or_empty(self, prepared, Self::EMPTY)
    }

    /// The warp through the values `values[i + 3 j]` at the grid points
    /// `(BIQUADRATIC_GRID[i], BIQUADRATIC_GRID[j])`: interpolating Bernstein control
    /// points, clamped to be non-negative, normalised to mean 1.
    fn fit(&mut self, inv_solid_angle: f32, values: [f32; 9]) {
        // Interpolate along u'_0 (rows), then along u'_1 (columns).
        let mut controls = [0.0f32; 9];
        for j in 0..3 {
            let row = interpolating_controls([values[3 * j], values[1 + 3 * j], values[2 + 3 * j]]);
            controls[3 * j..3 * j + 3].copy_from_slice(&row);
        }
        for i in 0..3 {
            let column = interpolating_controls([controls[i], controls[i + 3], controls[i + 6]]);
            for (j, c) in column.iter().enumerate() {
                // Clamping makes the density non-negative (convex hull property).
                controls[i + 3 * j] = c.max(0.0);
            }
        }
        let controls = normalise_to_mean_one(controls);
        let mut marginal = [0.0f32; 3];
        for (i, m) in marginal.iter_mut().enumerate() {
            *m = (controls[i] + controls[i + 3] + controls[i + 6]) * (1.0 / 3.0);
        }
        self.controls = controls;
        self.marginal = marginal;
        self.inv_solid_angle = inv_solid_angle;
    }

    /// Control points of the density along `u'_1` at `u'_0 = x` (unnormalised
    /// conditional; the joint density at `(x, y)` is `Σ d_j B_j(y)`).
    #[inline(always)]
    fn conditional(&self, x: f32) -> [f32; 3] {
        let c = &self.controls;
        let s = 1.0 - x;
        let (b0, b1, b2) = (s * s, 2.0 * s * x, x * x);
        [0, 1, 2].map(|j| b0 * c[3 * j] + b1 * c[1 + 3 * j] + b2 * c[2 + 3 * j])
    }

    /// The warp's density on the primary square at `u'` (mean 1 over the square).
    #[inline]
    pub fn warp_density(&self, warped: [f32; 2]) -> f32 {
        quadratic_bernstein(warped[1], self.conditional(warped[0]))
    }

    /// Solid angle Ω of the (unclipped) polygon in steradians (0 when empty).
    #[inline]
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle.solid_angle()
    }

    /// Draws a direction: `u'` from the biquadratic density, then solid angle sampling
    /// at `u'`. `u` is clamped to `[0, 1 - ulp]`; NaN counts as 0. The pdf is the warp
    /// density at `u'` over Ω; "no sample" (`pdf == 0`, finite direction) for an empty
    /// polygon and for directions with `z <= 0`.
    #[inline]
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        if !(self.inv_solid_angle > 0.0) {
            return Sample::NONE;
        }
        let (u0, u1) = (clamp_random(u[0]), clamp_random(u[1]));
        let x = sample_quadratic(u0, self.marginal);
        let d = self.conditional(x);
        let y = sample_quadratic(u1, d);
        let density = quadratic_bernstein(y, d);
        finish(&self.solid_angle, [x, y], density, self.inv_solid_angle)
    }

    /// The density per steradian of [`sample`](Self::sample) in direction `dir` (need
    /// not be normalised): 0 for `dir.z <= 0`, outside the polygon, for zero or
    /// non-finite directions, and when the polygon is empty.
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        match upper_direction(dir).and_then(|dir| self.solid_angle.invert_strictly_inside(dir)) {
            Some(warped) => self.warp_density(warped) * self.inv_solid_angle,
            None => 0.0,
        }
    }

    /// The random numbers `u` for which [`sample`](Self::sample) returns `dir` (up to
    /// rounding), or `None` when `dir.z <= 0`, `dir` is outside the polygon, or the
    /// polygon is empty.
    pub fn invert(&self, dir: Vec3) -> Option<[f32; 2]> {
        let [x, y] = self
            .solid_angle
            .invert_strictly_inside(upper_direction(dir)?)?;
        Some([
            clamp_inverted(quadratic_cdf(x, self.marginal)),
            clamp_inverted(quadratic_cdf(y, self.conditional(x))),
        ])
    }
}

#[cfg(test)]
#[path = "hart_tests.rs"]
mod tests;
