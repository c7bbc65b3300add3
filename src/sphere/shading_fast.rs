//! The per-light work of the real-time shading (issue 18, 1) in one pass: the image of
//! the light's cap under the pivot transformation and its intersection with the image of
//! the upper hemisphere (or of a bent cone), without building the image as a [`Cap`].
//!
//! The image in closed form, from the plane of the light's circle:
//! [`reduced_image`](super::pivot::reduced_image) (its documentation derives it and
//! bounds its error), the image reduced to at most a hemisphere (what Eq. 6–7 give) as
//! `(−n/|n|, side)` where the image is at most a hemisphere and `(n/|n|, side)` otherwise
//! (`side` is then the image's hole), with `n = 2δ r_p + k a`, `δ = a·r_p − cos θ`,
//! `k = 1 − |r_p|²`. No plane, no image points, no arc tangent: one square root and one
//! division instead of the points' three divisions, their plane's square root and the
//! midpoint's normalisation. Then `t_d = |A₁ − A₂|²/2` of the two reduced axes,
//! [`at_most_hemispheres_fast`] decides the case and measures the lens, and the
//! complements are undone as in `cap_intersection_solid_angle`.
//!
//! `None` sends the caller to the careful path (`pivot_cap_by_points` and
//! `cap_intersection_solid_angle`): an empty or whole light or clip, a pivot not valid as
//! it is (`|r_p|² > 1 − 2⁻¹⁸` or not finite), the pivot on the light's axis line (see
//! `reduced_image`), `|n| < 1/16` (the pivot near the sphere and a light near `r_p/|r_p|`, whose
//! image is then nearly the whole sphere), and the two caps' case too close to a
//! boundary.

use super::cap::Cap;
use super::cap_intersection::{at_most_hemispheres_fast, min_ordered, one_minus_dot};
use super::pivot::reduced_image;
use core::f32::consts::PI;
use glam::Vec3;

/// `Ω(g(light) ∩ clip)` for a valid light cap (see [`Cap::sanitized`]), a pivot and the
/// already pivoted `clip` (`g(H)` or `g(V)`); `None` where the careful path must decide
/// (see the module documentation).
#[inline(always)]
pub(crate) fn pivoted_intersection_fast(light: &Cap, pivot: &Vec3, clip: &Cap) -> Option<f32> {
    let pivot = *pivot;
    let (t2, h2) = (clip.one_minus_cos, clip.one_plus_cos);
    if !(t2 > 0.0) || !(h2 > 0.0) {
        return None;
    }
    // The light's image reduced to at most a hemisphere; careful for an empty or whole
    // light, a pivot not valid as it is, `|n| < 1/16`, and the pivot (nearly) on the
    // light's axis line (`OFF_AXIS`, see `reduced_image`): that path measures the lens with
    // `libm`'s arc tangents, which matters where a nearly whole image leaves a sliver of
    // the clip (`Ω₂ − inner` cancels; the test
    // `occlusion_of_a_light_whose_image_is_nearly_the_whole_sphere` aims the light at the
    // pivot).
    let image = reduced_image::<true>(light, pivot)?;
    let (normal, side, wide1) = (image.normal, image.side, image.wide);
    // Its axis `∓n/|n|`: `−n/|n|` (the image) for `c' < 0`, `+n/|n|` (the complement of
    // the image) otherwise.
    let inverse_n = image.inverse_length;
    // The clip up to a hemisphere: itself or its complement `(−axis, h₂)`.
    let wide2 = t2 > 1.0;
    let s2 = if wide2 { h2 } else { t2 };
    // `t_d = |A₁ − A₂|²/2` with `A₂ = ±clip.axis`: `|A₁ − A₂| = |±A₁ − clip.axis|` (a
    // negation is exact, so the same bits), i.e. the clip's own axis against `n/|n|` times
    // the product of the two signs: `+` exactly when one of the caps is complemented. One
    // scalar select instead of two vector ones.
    let scale = if wide1 != wide2 {
        inverse_n
    } else {
        -inverse_n
    };
    let td = one_minus_dot(normal * scale, clip.axis);
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
    // `ω(t₂) > 0` and `ω(t₁) ≥ 0` are not NaN: `min_ordered` is `f32::min` here.
    Some(result.max(low).min(min_ordered(omega(t1), omega(t2))))
}

#[cfg(test)]
#[path = "shading_fast_tests.rs"]
mod tests;
