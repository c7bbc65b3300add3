//! The per-light work of the real-time shading (issue 18, 1) in one pass: the image of
//! the light's cap under the pivot transformation and its intersection with the image of
//! the upper hemisphere (or of a bent cone), without building the image as a [`Cap`].
//!
//! The image in closed form, from the plane of the light's circle. `g(y) = r_p −
//! k(y − r_p)/|y − r_p|²` with `k = 1 − |r_p|²` (Eq. 2, in the form of
//! [`transform`](super::pivot)) is the inversion about `r_p` of power `−k`: `y = g(x)` ⇔
//! `x − r_p = −k(y − r_p)/|y − r_p|²`. The light is `C = {x : a·x ≥ cos θ}`; with
//! `δ = a·r_p − cos θ`, `a·x − cos θ = δ − k a·(y − r_p)/|y − r_p|²`, and on the sphere
//! `|y − r_p|² = 1 + |r_p|² − 2 r_p·y > 0`, so `x ∈ C` ⇔ `n·y ≤ c'` with
//!
//! `n = 2δ r_p + k a`, `c' = δ(1 + |r_p|²) + k (a·r_p)`:
//!
//! `g(C)` is the cap of axis `−n/|n|` and `cos ψ' = −c'/|n|`. Expanding,
//! `|n|² − c'² = k²(1 − (a·r_p − δ)²) = k² sin²θ` (`|a| = 1`), so `1 − |cos ψ'| =
//! k² sin²θ / (|n|(|n| + |c'|))` without cancellation (the stored `sin²θ`: a tiny light
//! keeps the relative precision of its image), and `|n| = |ω₁ − r_p||ω₂ − r_p|` for the
//! boundary points `ω₁, ω₂` in the plane of `a` and `r_p` (so `sin ψ' = k sin θ / |n|`,
//! as in [`pivot_cap_fast`](super::pivot)). The image reduced to at most a hemisphere
//! (what Eq. 6–7 give, from `g(ω₁), g(ω₂)`) is `(−n/|n|, side)` where `c' < 0` (the image
//! itself, `1 − cos ψ' = side`) and `(n/|n|, side)` otherwise (the image is wider than a
//! hemisphere and `side` is its hole); at `c' = 0` both are the same hemisphere up to the
//! orientation that the complement undoes, so the switch is continuous. No plane, no
//! image points, no arc tangent: one square root and one division (`1/(|n|(|n| + |c'|))`
//! gives both the side and `1/|n|`) instead of the points' three divisions, their plane's
//! square root and the midpoint's normalisation. Then `t_d = |A₁ − A₂|²/2` of the two
//! reduced axes, [`at_most_hemispheres_fast`] decides the case and measures the lens, and
//! the complements are undone as in `cap_intersection_solid_angle`.
//!
//! Conditioning: the rounding of `n` is below `8ε` absolute (its terms and `δ` are at
//! most a few units; `δ` is exact where it cancels, Sterbenz), so `|n| ≥ 1/16` keeps the
//! image's axis and side to `1e-5` of their rounding-free values; `|n|` is small only for
//! a pivot near the sphere and a light near `r_p/|r_p|`, whose image is then nearly the
//! whole sphere. The rounding of `k` itself (`ε/k` relative, through `k²` in the side) is
//! shared with the points' form of `pivot_cap_fast`.
//!
//! `None` sends the caller to the careful path (`pivot_cap_fast` and
//! `cap_intersection_solid_angle`): an empty or whole light or clip, a pivot not valid as
//! it is (`|r_p|² > 1 − 2⁻¹⁸` or not finite), the pivot on the light's axis line (see
//! below), `|n| < 1/16`, and the two caps' case too close to a boundary.

use super::cap::Cap;
use super::cap_intersection::{at_most_hemispheres_fast, min_ordered, one_minus_dot};
use core::f32::consts::PI;
use glam::Vec3;

/// `|r_p|²` up to which the pivot is taken as it is (`valid_pivot` would return it
/// unchanged: `√x ≤ 1 − 2⁻²⁰`).
const FAST_MAX_PIVOT_LENGTH2: f32 = 1.0 - 4.0 / 1_048_576.0;

/// `|n|²` of the image's plane normal (module documentation) from which the closed form
/// is used: `|n| ≥ 1/16`, so that the rounding of `n` (below `8ε` absolute, module
/// documentation) is below `1e-5` of it.
const FAST_MIN_NORMAL2: f32 = 1.0 / 256.0;

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
    // The pivot (nearly) on the light's axis line goes the careful way, as it did before
    // the closed form below (which does not need the plane of the axis and the pivot):
    // that path measures the lens with `libm`'s arc tangents, which matters where a
    // nearly whole image leaves a sliver of the clip (`Ω₂ − inner` cancels; the test
    // `occlusion_of_a_light_whose_image_is_nearly_the_whole_sphere` aims the light at the
    // pivot). Tested as `|r_p⊥|² = |r_p|² − (a·r_p)² > 4e-6 |r_p|²` (the pivot more than
    // 2e-3 rad off the line), which needs only `a·r_p`: on the line `(a·r_p)² = |r_p|²|a|²`,
    // and `|a|²` is 1 to `UNIT_TOLERANCE = 1e-6` (a valid cap), the three roundings a few
    // 1e-7 of `|r_p|²`, so the difference is below `2e-6 |r_p|²` there. A pivot at the
    // origin fails too (`0 > 0`). The careful path is exact there, and the cone of pivots
    // that it adds is a few 1e-6 of the directions.
    let along = pivot.dot(axis);
    if !(rho2 - along * along > 4e-6 * rho2) {
        return None;
    }
    // `k = 1 − |r_p|²` (exact for `|r_p|² ≥ 1/2`, Sterbenz), `δ = a·r_p − cos θ` (exact
    // subtraction where it cancels, Sterbenz), the image's plane `n·y = c'`.
    let k = 1.0 - rho2;
    let delta = along - light.cos();
    let normal = pivot * (2.0 * delta) + axis * k;
    let offset = delta * (1.0 + rho2) + k * along;
    let n2 = normal.length_squared();
    // Ill-conditioned (the pivot near the sphere and the light near `r_p/|r_p|`): careful.
    // NaN cannot occur here (finite valid inputs), but fails the test as well.
    if !(n2 >= FAST_MIN_NORMAL2) {
        return None;
    }
    let n = crate::math::sqrtf(n2);
    // `1/(|n|(|n| + |c'|))` once: the side and, times `|n| + |c'|`, `1/|n|`.
    let abs_offset = offset.abs();
    let sum = n + abs_offset;
    let reciprocal = 1.0 / (n * sum);
    // The image reduced to at most a hemisphere (module documentation): `1 − |cos ψ'|`
    // with `|n|² − c'² = k² sin²θ`; `≤ 1` in exact arithmetic.
    // (`min(1)` as a compare and select: the same value for every input, NaN included.)
    let side = (k * k) * light.sin2 * reciprocal;
    let side = if side < 1.0 { side } else { 1.0 };
    let wide1 = offset >= 0.0;
    // Its axis `∓n/|n|`: `−n/|n|` (the image) for `c' < 0`, `+n/|n|` (the complement of
    // the image) otherwise.
    let inverse_n = reciprocal * sum;
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
