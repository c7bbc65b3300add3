//! Polygonal lights (Peters 2021, "BRDF Importance Sampling for Polygonal Lights", and
//! its supplemental document).
//!
//! Polygons are convex, given by their vertices relative to the shading point in the
//! local frame (z = normal), in either winding, with 3 to [`MAX_POLYGON_VERTICES`]
//! vertices.
//!
//! [`MAX_POLYGON_VERTICES`]: crate::MAX_POLYGON_VERTICES

use crate::Vec3;
use glam::{BVec4A, Vec4};

pub mod baselines;
mod central_sectors;
pub mod clip;
mod edge_normal_rows;
mod ellipse;
mod ellipse_sector;
#[rustfmt::skip]
mod clip_generated;
pub mod clipped_solid_angle;
pub mod light;
pub mod ltc;
pub mod projected;
pub mod small_projected;
pub mod solid_angle;
mod sorting_networks;
#[rustfmt::skip]
mod sorting_networks_generated;

pub use clip::clip_to_upper_hemisphere;
pub use clipped_solid_angle::ClippedSolidAnglePolygon;
pub use ltc::LtcPolygon;
pub use projected::ProjectedPolygon;
pub use solid_angle::{SolidAngleFan, SolidAnglePolygon, SolidAngleQuad, SolidAngleTriangle};

/// The end of every in-place `prepare`: keeps the value that preparation completed, or
/// writes `empty` over what a failed preparation left half-written. Returns `prepared`.
#[inline(always)]
pub(crate) fn keep_or_empty<T>(value: &mut T, prepared: bool, empty: T) -> bool {
    if !prepared {
        *value = empty;
    }
    prepared
}

/// A count read from a prepared value, clamped to `max`: a value corrupted by a caller's
/// bug (outside the contract) must not index out of bounds (an abort across the C ABI)
/// or loop without bound; it may give a wrong result (issue 16, 6).
#[inline(always)]
pub(crate) fn stored_count(count: u32, max: usize) -> usize {
    (count as usize).min(max)
}

/// A bound on the rounding noise of a fan determinant computed in `f32` from edge
/// vectors, relative to `|e_b|∞ |e_c|∞` (times `|p_0|∞` for the triple product): 64ε.
/// Each edge vector `p_i - p_0` is rounded by ε/2 per component, and a cross product,
/// dot product or Householder reflection of them adds a few ε of `|e|∞` per component
/// (with `|e| <= √3 |e|∞`); the sum of these terms stays below 62ε. A determinant below
/// this bound cannot be told from zero by the plain computation, so
/// [`determinant_is_exactly_zero`](crate::math::determinant_is_exactly_zero) decides.
pub(crate) const FAN_DETERMINANT_NOISE: f32 = 64.0 * f32::EPSILON;

/// Whether the polygon lies exactly in a plane through the shading point (its solid
/// angle and projected solid angle are then 0; rounding would make them noise). Cheap
/// for the common polygon: the first fan triangle whose plain determinant exceeds
/// [`FAN_DETERMINANT_NOISE`] answers `false`; only polygons within the noise of such a
/// plane run the exact test on every fan triangle. `positions` as rescaled (a power of
/// two times the input: exact), 3 or more of them.
///
/// The plain determinants in the lanes `(x, y, z, 0)`, each rounded as `Vec3`'s
/// differences, `cross` ([`cross3_lanes`](crate::math::cross3_lanes)) and `dot` round
/// it; the largest magnitudes as `max_element` of the magnitudes (the fourth lane's 0
/// changes no maximum, and no lane is NaN: the positions are finite, their differences
/// finite or infinite). Issue 15: the scalar form was about 100 instructions of every
/// projected preparation.
pub(crate) fn lies_in_a_plane_through_the_shading_point(positions: &[Vec3]) -> bool {
    let apex = positions[0];
    let lanes = |p: Vec3| Vec4::from((p, 0.0));
    let apex_lanes = lanes(apex);
    let mut b = lanes(positions[1]) - apex_lanes;
    for &next in &positions[2..] {
        let c = lanes(next) - apex_lanes;
        if fan_triangle_leaves_the_plane(apex_lanes, b, c, crate::math::cross3_lanes(b, c)) {
            return false;
        }
        b = c;
    }
    positions[1..]
        .windows(2)
        .all(|pair| crate::math::determinant_is_exactly_zero(apex, pair[0], pair[1]))
}

/// The quick answer of [`lies_in_a_plane_through_the_shading_point`] for one fan
/// triangle `(p0, p0 + b, p0 + c)` (`apex` = `p0`, `b`, `c` and `cross` = `b × c` as
/// [`cross3_lanes`](crate::math::cross3_lanes) rounds it, all in the lanes
/// `(x, y, z, 0)`): whether its plain determinant `det(p0, pb, pc) = (pb - p0) × (pc - p0)
/// · p0` exceeds [`FAN_DETERMINANT_NOISE`] times the magnitudes, so that the polygon
/// does not lie in a plane through the shading point. Inlined, so that a preparation
/// that forms the first fan triangle's cross product anyway (the projected polygon's
/// orientation) shares it and calls the whole test only where this does not answer.
#[inline(always)]
pub(crate) fn fan_triangle_leaves_the_plane(apex: Vec4, b: Vec4, c: Vec4, cross: Vec4) -> bool {
    let det = cross.truncate().dot(apex.truncate());
    let bound = FAN_DETERMINANT_NOISE
        * b.abs().max_element()
        * c.abs().max_element()
        * apex.abs().max_element();
    !(det.abs() <= bound)
}

/// Edges shorter than this (the sine of the angle between their endpoints) may be left
/// out of the containment test: 2⁻¹⁶ ≈ 1.5e-5 rad.
const SHORT_EDGE_SINE: f32 = 1.0 / 65_536.0;

/// The farthest (in radians) that leaving a short edge out of the containment test may
/// extend the polygon: 16 × [`SHORT_EDGE_SINE`] ≈ 2.4e-4 rad (by a triangle whose base
/// is the edge, at most 3.7e-9 sr).
const SHORT_EDGE_REACH: f32 = 16.0 * SHORT_EDGE_SINE;

/// How far (radians) leaving a short edge out may extend any polygon, however small:
/// 4e-7, below the rounding of an `f32` unit direction (about 5e-7 rad at the worst).
/// Beyond it the reach is limited to [`SHORT_EDGE_REACH_PER_LENGTH`] of the polygon's
/// longest edge (issue 16, 1: with the fixed [`SHORT_EDGE_REACH`], `pdf` of a solid
/// angle sampler was non-zero 6e-6 rad outside a polygon 2e-5 rad across).
const SHORT_EDGE_ROUNDING_REACH: f32 = 4e-7;

/// The reach allowed beyond [`SHORT_EDGE_ROUNDING_REACH`], per unit of the polygon's
/// longest edge: 5e-5, so 1e-4 of the polygon's angular radius at the most (the radius
/// is at least half the longest edge).
const SHORT_EDGE_REACH_PER_LENGTH: f32 = 5e-5;

/// Drops from the containment test (sets the normal to 0, which passes) every edge
/// whose endpoints are closer than [`SHORT_EDGE_SINE`] where that extends the region by
/// at most the reach allowed (below).
///
/// Why: a vertex carries a rounding error of about `ε |p|`, which tilts the plane of an
/// edge of angular length `ℓ` by about `ε / ℓ`. Where clipping puts a horizon point next
/// to a vertex a few ulps above the horizon, `ℓ` is of the order of `ε` and the edge's
/// plane is noise: found by fuzzing, the rounded clip point had the x and y of its
/// neighbour, so the edge's plane passed through the zenith and cut the polygon in two,
/// and `pdf` denied samples 0.2 rad inside (projected solid angle sampling; solid angle
/// sampling of a clipped polygon likewise, 6e-3 rad inside for an edge of 1.3e-6 rad).
/// The samplers never see such an edge: projected solid angle sampling works with the
/// sectors between vertex azimuths, solid angle sampling with fan triangles.
///
/// Without the edge, the region grows by the triangle between its endpoints and the
/// meeting point of its neighbours' planes. With the exterior angles `δa`, `δb` at its
/// endpoints, that triangle's height is `ℓ sin δa sin δb / sin(δa + δb)`: at most `ℓ`
/// when `δa + δb < 90°`, and at most `ℓ / sin(δa + δb)` otherwise, where `δa + δb` is
/// the angle between the neighbours' normals. The edge is kept where that bound exceeds
/// the reach allowed: the smaller of [`SHORT_EDGE_REACH`] and
/// [`SHORT_EDGE_ROUNDING_REACH`] plus [`SHORT_EDGE_REACH_PER_LENGTH`] times the longest
/// edge (neighbours nearly
/// antiparallel, the sharp end of a sliver, and every edge of a polygon so small that
/// the fixed reach would be a large part of it, keep their planes).
pub(crate) fn ignore_short_edges_in_containment<const N: usize>(
    normals: &mut [Vec3; N],
    positions: &[Vec3],
    count: usize,
) {
    let original = *normals;
    // sin² of the longest edge (the careful path only: divisions are affordable here).
    let mut longest2 = 0.0f32;
    for j in 0..count {
        let (a, b) = (
            positions[j],
            positions[if j + 1 == count { 0 } else { j + 1 }],
        );
        let sine2 = original[j].length_squared() / (a.length_squared() * b.length_squared());
        if sine2 > longest2 {
            longest2 = sine2;
        }
    }
    let reach = SHORT_EDGE_REACH.min(
        SHORT_EDGE_ROUNDING_REACH + SHORT_EDGE_REACH_PER_LENGTH * crate::math::sqrtf(longest2),
    );
    for j in 0..count {
        let (a, b) = (
            positions[j],
            positions[if j + 1 == count { 0 } else { j + 1 }],
        );
        // sin²ℓ = |n|² / (|a|² |b|²), kept as products (no division by a tiny length).
        let length2 = original[j].length_squared();
        let scale2 = a.length_squared() * b.length_squared();
        if !(length2 <= SHORT_EDGE_SINE * SHORT_EDGE_SINE * scale2) {
            continue; // not short: the common case, decided before the rest
        }
        let previous = original[if j == 0 { count - 1 } else { j - 1 }];
        let next = original[if j + 1 == count { 0 } else { j + 1 }];
        // sin²(δa + δb) = |p × q|² / (|p|² |q|²); reach² = sin²ℓ / sin²(δa + δb).
        let bounded = if previous.dot(next) > 0.0 {
            length2 <= reach * reach * scale2
        } else {
            length2 * previous.length_squared() * next.length_squared()
                <= reach * reach * previous.cross(next).length_squared() * scale2
        };
        if bounded {
            normals[j] = Vec3::ZERO;
        }
    }
}

/// Rescales positions by a power of two so that the largest coordinate lies in
/// `[1, 2)`. Returns `None` when all coordinates are zero or any is not finite.
///
/// Bit trick: for a normal `f32` `m` with biased exponent `E` (bits 23..=30), `2^(127-E)`
/// has biased exponent `254 - E`, so `f32::from_bits((254 - E) << 23)` is exactly
/// `2^-(E-127)` and `m` times it lies in `[1, 2)`. Multiplying by a power of two is exact
/// while the result stays normal, so the polygon's shape is unchanged. For subnormal `m`
/// (`E = 0`) the factor is `2^127`, still exact; `E` is at most 254 for finite values
/// and the factor's exponent is kept at least 1 (a normal number).
///
/// The factor comes from each vertex as the lanes `(x, y, z, 0)`: their running maximum
/// and finiteness mask ([`largest_magnitude4`]'s operations on one vertex's coordinates
/// instead of one coordinate of four vertices) give `rescale_factor`'s factor, bit for
/// bit, through [`rescale_factor_of_lanes`] (the maximum is over the same coordinates and
/// a 0 that does not change it; issue 15: the scalar pass, 18 dependent integer maxima,
/// was about 90 instructions of a hexagon's preparation). Tested by
/// `lanes_rescale_as_the_scalar_pass`.
pub(crate) fn rescale(vertices: &[Vec3], out: &mut [Vec3]) -> Option<()> {
    rescale_above_the_horizon(vertices, out).map(|_| ())
}

/// [`rescale`], returning also whether every rescaled vertex lies above the horizon
/// (`z > 0`): the test of the projected preparation for a polygon that needs no clipping,
/// made as the vertices are written (issue 15: a pass of its own over them, with its
/// loop, was about 55 instructions per hexagon), and the factor (so that the caller can
/// form a rescaled vertex from the input, bit for bit, instead of reading back `out`
/// while its stores are in flight).
#[inline(always)]
pub(crate) fn rescale_above_the_horizon(
    vertices: &[Vec3],
    out: &mut [Vec3],
) -> Option<(bool, f32)> {
    let (mut largest, mut finite) = (Vec4::ZERO, BVec4A::splat(true));
    for v in vertices {
        let (magnitude, finite_lanes) = magnitudes4(Vec4::from((*v, 0.0)));
        finite &= finite_lanes;
        largest = largest.max(magnitude);
    }
    let factor = rescale_factor_of_lanes(largest, finite)?;
    let mut above = true;
    for (o, v) in out.iter_mut().zip(vertices) {
        *o = *v * factor;
        above &= o.z > 0.0;
    }
    Some((above, factor))
}

/// The power of two by which [`rescale`] multiplies, or `None` when all coordinates are
/// zero or any is not finite: the scalar pass that [`rescale`] and the lanes of
/// [`largest_magnitude4`] are tested against.
#[cfg(test)]
pub(crate) fn rescale_factor(vertices: &[Vec3]) -> Option<f32> {
    // Bit trick: with the sign bit cleared, IEEE-754 bit patterns order as unsigned
    // integers in the order of the magnitudes they encode, and +inf (0x7f80_0000) and
    // every NaN (above it) have the largest patterns. One integer maximum over the
    // cleared patterns therefore gives the largest magnitude and, in the same pass,
    // whether any coordinate is not finite (no early exit, no separate finiteness test).
    let mut largest_bits = 0u32;
    for v in vertices {
        for c in v.to_array() {
            largest_bits = largest_bits.max(c.to_bits() & 0x7fff_ffff);
        }
    }
    if largest_bits >= 0x7f80_0000 {
        return None;
    }
    factor_for_largest_bits(largest_bits)
}

/// `rescale_factor` from the largest magnitude's bits (finite, sign bit clear): `None`
/// when it is 0 (all coordinates zero), else the power of two of the bit trick described
/// at [`rescale`].
#[inline(always)]
fn factor_for_largest_bits(largest_bits: u32) -> Option<f32> {
    if largest_bits == 0 {
        return None;
    }
    let biased_exponent = largest_bits >> 23;
    Some(f32::from_bits(
        254u32.saturating_sub(biased_exponent).max(1) << 23,
    ))
}

/// The coordinates' largest magnitude lane by lane, and the lanes whose coordinates are
/// all finite: the lane form of `rescale_factor`'s pass over the coordinates, for
/// vertices already gathered into x, y and z lanes (the preparations that work in lanes
/// load them so anyway: the scalar pass cost about 90 instructions per hexagon, 18
/// dependent integer maxima).
///
/// The maximum of floats is the maximum of their magnitudes' bit patterns (the order of
/// `rescale_factor`'s bit trick) for every value but NaN, and the lanes with a NaN or
/// an infinity are rejected by the finiteness mask (`|c| < ∞` is false for both), so
/// whatever the maximum makes of a NaN is never used.
#[inline(always)]
pub(crate) fn largest_magnitude4(coordinates: [Vec4; 3]) -> (Vec4, BVec4A) {
    let [(x, fx), (y, fy), (z, fz)] = coordinates.map(magnitudes4);
    (x.max(y).max(z), fx & fy & fz)
}

/// The magnitudes of four coordinates and the lanes where they are finite (`|c| < ∞`,
/// false for an infinity and a NaN): the terms of [`largest_magnitude4`] and of
/// [`rescale_above_the_horizon`]'s factor.
#[inline(always)]
fn magnitudes4(c: Vec4) -> (Vec4, BVec4A) {
    let magnitude = c.abs();
    (magnitude, magnitude.cmplt(Vec4::splat(f32::INFINITY)))
}

/// `rescale_factor` from [`largest_magnitude4`]'s lanes (combined over the groups of
/// vertices by `max` and `&`): the same factor, bit for bit, and `None` in the same
/// cases (tested: `lanes_rescale_as_the_scalar_pass`).
#[inline(always)]
pub(crate) fn rescale_factor_of_lanes(largest: Vec4, finite: BVec4A) -> Option<f32> {
    if !finite.all() {
        return None;
    }
    factor_for_largest_bits(largest.max_element().to_bits())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::Rng;

    /// The lane forms of the rescale factor (`largest_magnitude4` over groups of four
    /// vertices, as the solid angle preparation takes them, then
    /// `rescale_factor_of_lanes`; and `rescale`'s, from each vertex's lanes) give the
    /// scalar pass's factor bit for bit, and `None` in the same cases, and `rescale`
    /// writes each vertex times that factor: coordinates from subnormal to near
    /// `f32::MAX`, zeros of both signs, all-zero polygons, infinities and NaNs of either
    /// sign, 3 to 8 vertices with the groups' unused slots filled as the preparations
    /// fill them (vertex 0 again).
    #[test]
    fn lanes_rescale_as_the_scalar_pass() {
        let mut rng = Rng::new(35);
        let special = [
            0.0,
            -0.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
            f32::MIN_POSITIVE,
            1e-45,
            -1e-45,
            f32::MAX,
            -f32::MAX,
        ];
        let (mut nones, mut subnormal_largest, mut above_count) = (0, 0, 0);
        for case in 0..200_000 {
            let count = 3 + (case % 6);
            // One polygon in 20 of subnormal (and tiny normal) coordinates only.
            let top = if rng.below(20) == 0 { -37.5 } else { 38.5 };
            let coordinate = |rng: &mut Rng| match rng.below(12) {
                0 => special[rng.below(special.len() as u64) as usize],
                1 => 0.0,
                _ => rng.signed_log_uniform(-45.0, top) as f32,
            };
            let all_zero = rng.below(50) == 0;
            let vertices: Vec<Vec3> = (0..count)
                .map(|_| {
                    if all_zero {
                        Vec3::ZERO
                    } else {
                        Vec3::new(
                            coordinate(&mut rng),
                            coordinate(&mut rng),
                            coordinate(&mut rng),
                        )
                    }
                })
                .collect();
            let scalar = rescale_factor(&vertices);
            let (mut largest, mut finite) = (Vec4::ZERO, BVec4A::splat(true));
            for first in (0..count).step_by(4) {
                let vertex = |j: usize| vertices[if first + j < count { first + j } else { 0 }];
                let lane =
                    |c: usize| Vec4::new(vertex(0)[c], vertex(1)[c], vertex(2)[c], vertex(3)[c]);
                let (m, f) = largest_magnitude4([lane(0), lane(1), lane(2)]);
                if first == 0 {
                    (largest, finite) = (m, f);
                } else {
                    (largest, finite) = (largest.max(m), finite & f);
                }
            }
            let lanes = rescale_factor_of_lanes(largest, finite);
            assert_eq!(
                scalar.map(f32::to_bits),
                lanes.map(f32::to_bits),
                "{vertices:?}"
            );
            let mut out = [Vec3::splat(7.0); 8];
            let above = rescale_above_the_horizon(&vertices, &mut out);
            assert_eq!(above.is_some(), scalar.is_some(), "{vertices:?}");
            if let (Some(factor), Some((above, lanes_factor))) = (scalar, above) {
                assert_eq!(lanes_factor.to_bits(), factor.to_bits(), "{vertices:?}");
                for (o, v) in out.iter().zip(&vertices) {
                    let expected = (*v * factor).to_array().map(f32::to_bits);
                    assert_eq!(o.to_array().map(f32::to_bits), expected, "{vertices:?}");
                }
                assert_eq!(above, out[..count].iter().all(|o| o.z > 0.0));
                above_count += above as u32;
            }
            nones += scalar.is_none() as u32;
            subnormal_largest +=
                (scalar.is_some() && largest.max_element() < f32::MIN_POSITIVE) as u32;
        }
        // Both outcomes and the subnormal case were exercised.
        assert!(nones > 10_000 && nones < 190_000, "{nones}");
        assert!(subnormal_largest > 0);
        assert!(above_count > 100, "{above_count}");
    }
}
