//! The per-light work of the real-time shading (issue 18, 1) in one pass: the image of
//! the light's cap under the pivot transformation and its intersection with the image of
//! the upper hemisphere (or of a bent cone), without building the image as a [`Cap`].
//!
//! [`pivot_cap_fast`](super::pivot::pivot_cap_fast) followed by
//! [`cap_intersection_solid_angle`](super::cap_intersection_solid_angle) is a chain of
//! dependent square roots and divisions (about 250 cycles a light, most of the time of a
//! call): the plane's tangent, the image points, the image's axis normalised in 3D, the
//! axes' `t_d`, the lens's `Y` and its three arc tangents. Here the same closed form of the
//! image (see `pivot_cap_fast` for its derivation and its conditions) stays in the plane
//! of the light's axis and the pivot: the other cap's axis `A` is written once in that
//! plane's frame, `A = α a + β t̂ + γ n̂` (`a` the light's axis, `t̂` the tangent towards
//! the pivot, `n̂ = (r_p × a)/|r_p × a|` the plane's normal; `α, β, γ` do not wait for
//! the image), and with `m = g(ω₁) + g(ω₂)` (the image's axis direction, unnormalised)
//!
//! `t_d = |m/|m| − A|²/2 = (|m − |m|(α, β)|² + |m|²γ²) / (2|m|²)`,
//!
//! a sum of squares as `|a₁ − a₂|²/2` is (no cancellation), without the axis in 3D. The
//! image reduced to at most a hemisphere is always `(m/|m|, side)`: an image up to a
//! hemisphere has axis `m/|m|` and `1 − cos ψ' = side`, a wider one axis `−m/|m|` and the
//! hole `side`, whose complement is `(m/|m|, side)`. `|r_p × a|` gives `|r_p⊥|` without
//! waiting for `r_p·a`. Then [`at_most_hemispheres_fast`] decides the case and measures the
//! lens, and the complements are undone as in `cap_intersection_solid_angle`.
//!
//! `None` sends the caller to the careful path (`pivot_cap_fast` and
//! `cap_intersection_solid_angle`, as before this pass): an empty or whole light or clip,
//! a pivot not valid as it is (`|r_p|² > 1 − 2⁻¹⁸` or not finite), the pivot on the light's
//! axis line, an image whose side or axis is not well conditioned (`pivot_cap_fast`'s
//! conditions), and the two caps' case too close to a boundary.

use super::cap::Cap;
use super::cap_intersection::at_most_hemispheres_fast;
use super::pivot::images_in_plane;
use core::f32::consts::PI;
use glam::{Vec2, Vec3};

/// `|r_p|²` up to which the pivot is taken as it is (`valid_pivot` would return it
/// unchanged: `√x ≤ 1 − 2⁻²⁰`).
const FAST_MAX_PIVOT_LENGTH2: f32 = 1.0 - 4.0 / 1_048_576.0;

/// `sin²ψ'` of the image up to which the closed form is used (`|cos ψ'| ≥ 1/16`), as in
/// `pivot_cap_fast`.
const FAST_MAX_SIN2: f32 = 1.0 - 1.0 / 256.0;

/// `Ω(g(light) ∩ clip)` for a valid light cap (see [`Cap::sanitized`]), a pivot and the
/// already pivoted `clip` (`g(H)` or `g(V)`); `None` where the careful path must decide
/// (see the module documentation).
#[inline(always)]
pub(crate) fn pivoted_intersection_fast(light: &Cap, pivot: &Vec3, clip: &Cap) -> Option<f32> {
    let pivot = *pivot;
    let (t2, h2) = (clip.one_minus_cos, clip.one_plus_cos);
    if !(light.one_minus_cos > 0.0) || !(light.one_plus_cos > 0.0) || !(t2 > 0.0) || !(h2 > 0.0) {
        return None;
    }
    let rho2 = pivot.length_squared();
    if !(rho2 <= FAST_MAX_PIVOT_LENGTH2) {
        return None;
    }
    let axis = light.axis;
    let along = pivot.dot(axis);
    let normal = pivot.cross(axis);
    let across2 = normal.length_squared();
    // The pivot (nearly) on the axis line: no plane (as in `pivot_cap_fast`).
    if !(across2 > 1e-12) {
        return None;
    }
    let across = libm::sqrtf(across2);
    let p = Vec2::new(along, across);
    let ([g1, g2, gc], sin2) = images_in_plane(light, p, rho2);
    let a = g1 - gc;
    let b = g2 - gc;
    let q = a.dot(b);
    // `pivot_cap_fast`'s bound with the 1-norms, which bound the lengths from above.
    let margin = 4e-6 * (a.abs().element_sum() + b.abs().element_sum()) + 1e-12;
    if !(sin2 <= FAST_MAX_SIN2) || !(q.abs() > margin) {
        return None;
    }
    let wide1 = q >= 0.0;
    let side = (sin2 / (1.0 + libm::sqrtf(1.0 - sin2))).min(1.0);
    // The clip up to a hemisphere: itself or its complement.
    let wide2 = t2 > 1.0;
    let (axis2, s2) = if wide2 {
        (-clip.axis, h2)
    } else {
        (clip.axis, t2)
    };
    // Its axis in the plane's frame. The tangent is `a × n̂` (`= r_p⊥/|r_p⊥|` in exact
    // arithmetic), not `(r_p − a(r_p·a))/|r_p × a|`: both differences cancel where the
    // pivot is near the axis line, to different roundings, so that quotient is not unit
    // (by 1e-6 at `|r_p⊥| = 0.08`, which moved `t_d` by as much); `a × n̂` is unit to
    // 1e-13 and orthogonal to `n̂`, and `(r_p·a, |r_p × a|)` is the pivot in this frame
    // up to a perturbation of the pivot by its rounding.
    let tangent = axis.cross(normal);
    let inverse_across = 1.0 / across;
    let alpha = axis2.dot(axis);
    let beta = axis2.dot(tangent) * inverse_across;
    let gamma = axis2.dot(normal) * inverse_across;
    // |m| = 2|cos ψ'| ≥ 1/8 up to rounding (FAST_MAX_SIN2).
    let mid = g1 + g2;
    let m2 = mid.length_squared();
    let m = libm::sqrtf(m2);
    let d = mid - Vec2::new(alpha, beta) * m;
    let td = ((d.length_squared() + m2 * (gamma * gamma)) * (0.5 / m2)).min(2.0);
    let inner = at_most_hemispheres_fast(side, s2, td)?;
    let (t1, h1) = if wide1 {
        (2.0 - side, side)
    } else {
        (side, 2.0 - side)
    };
    let omega = |t: f32| 2.0 * PI * t;
    let result = match (wide1, wide2) {
        (false, false) => inner,
        (true, false) => omega(t2) - inner,
        (false, true) => omega(t1) - inner,
        (true, true) => 4.0 * PI - omega(h1) - omega(h2) + inner,
    };
    let low = (omega(t1) + omega(t2) - 4.0 * PI).max(0.0);
    Some(result.max(low).min(omega(t1).min(omega(t2))))
}

#[cfg(test)]
#[path = "shading_fast_tests.rs"]
mod tests;
