//! Sphere lights as spherical caps (Dupuy et al. 2017): `sphera_cap_*` and
//! `sphera_pivot_*`.
//!
//! Caps are passed by value. A cap built by hand in C may hold anything: every
//! function first makes it valid (`Cap::sanitized`: a non-finite or zero axis or a NaN
//! `one_minus_cos` is the empty cap; otherwise the axis is normalised,
//! `one_minus_cos` clamped to [0, 2] and `one_plus_cos`, `sin2` recomputed from it,
//! except that a cap wider than a hemisphere keeps an `one_plus_cos` that agrees with
//! `2 − one_minus_cos` to 2⁻²², its hole to full precision, and takes `one_minus_cos`
//! from it), so outputs are always finite.
use super::types::{SpheraSample, SpheraVec3};
use crate::sphere::{Cap, cap_intersection_solid_angle, cap_intersection_solid_angle_oat_sander};

/// The cap of directions that a sphere of `radius` centered at `center` (relative to
/// the shading point) subtends: `sin θ = radius / |center|`, with `1 − cos θ` kept to
/// full relative precision for tiny or distant spheres. The whole sphere
/// (`one_minus_cos = 2`) when the shading point is inside or on the sphere; the empty
/// cap (solid angle 0, no samples) for a non-finite center or a radius that is not
/// finite and positive.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_cap_from_sphere(center: SpheraVec3, radius: f32) -> Cap {
    Cap::from_sphere(center.into(), radius)
}

/// The cap around `axis` (normalised) with `cos θ = cos_theta` (clamped to [-1, 1]); the
/// empty cap for a non-finite or zero axis or a NaN `cos_theta`. The smaller of
/// `1 ∓ cos θ` is exact: a cap wider than a hemisphere keeps its hole `1 + cos θ`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_cap_from_axis_cos(axis: SpheraVec3, cos_theta: f32) -> Cap {
    Cap::from_axis_cos(axis.into(), cos_theta)
}

/// The solid angle `2π (1 − cos θ)` of a cap, in [0, 4π].
#[unsafe(no_mangle)]
pub extern "C" fn sphera_cap_solid_angle(cap: Cap) -> f32 {
    cap.sanitized().solid_angle()
}

/// Whether `dir` (any non-zero finite vector) points into the cap, boundary included.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_cap_contains(cap: Cap, dir: SpheraVec3) -> bool {
    cap.sanitized().contains(dir.into())
}

/// Draws a direction uniformly in solid angle inside the cap (`u0`, `u1` in [0, 1),
/// clamped). pdf 0 (and `dir = (0, 0, 1)`) for an empty cap. Every call checks the cap
/// and builds its frame and `1 / Ω` (two divisions): for several samples of one cap, or
/// for a sphere light at the cost of a cone sampler, prepare a `SpheraSolidAngleSphere`
/// once (`sphera_solid_angle_sphere_prepare`, `_prepare_cap`), whose samples are these
/// bit for bit.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_cap_sample_uniform(cap: Cap, u0: f32, u1: f32) -> SpheraSample {
    cap.sanitized().sample_uniform([u0, u1]).into()
}

/// The density of `sphera_cap_sample_uniform`: `1 / Ω` inside the cap, 0 outside.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_cap_pdf(cap: Cap, dir: SpheraVec3) -> f32 {
    cap.sanitized().pdf(dir.into())
}

/// The exact solid angle of the intersection of two caps (disjoint, nested, lens, or
/// both wider than a hemisphere with a union covering the sphere).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_cap_intersection_solid_angle(a: Cap, b: Cap) -> f32 {
    cap_intersection_solid_angle(&a.sanitized(), &b.sanitized())
}

/// The Oat–Sander approximation of `sphera_cap_intersection_solid_angle` (Eq. 37–38
/// of Dupuy et al. 2017), for caps up to about a hemisphere; exact for disjoint and
/// nested caps.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_cap_intersection_solid_angle_oat_sander(a: Cap, b: Cap) -> f32 {
    cap_intersection_solid_angle_oat_sander(&a.sanitized(), &b.sanitized())
}
