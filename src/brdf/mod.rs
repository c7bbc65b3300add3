//! BRDFs of the shading point: the GGX microfacet BRDF with visible-normal sampling
//! (Heitz 2018, in Dupuy and Benyoub's spherical-cap form), the Lambertian BRDF with cosine-weighted sampling, and linearly
//! transformed cosines fitted to GGX (Heitz et al. 2016), the distributions that Peters
//! 2021 samples inside polygonal lights.
//!
//! Conventions, shared with the light samplers: directions live in the local shading
//! frame whose z axis is the surface normal; `wo` points away from the surface towards
//! the viewer, `wi` towards the light; both need not be normalised (they are, up to a
//! tolerance, by convention, and are normalised otherwise); densities are per steradian
//! of `wi`; random numbers lie in `[0, 1)` and are clamped into it; `Sample::NONE`
//! (pdf 0) means "no sample". A zero or non-finite direction evaluates to 0, has pdf 0
//! and gives no sample: no function returns NaN or an infinity.
//!
//! BRDF values `f` are per steradian and do not include the cosine `cos θi`.

pub mod ggx;
pub mod lambert;
pub mod ltc;
#[rustfmt::skip]
pub mod ltc_table;
#[rustfmt::skip]
pub mod pivot_cartesian_table;
#[rustfmt::skip]
pub mod pivot_table;

pub use ggx::GgxBrdf;
pub use lambert::Lambert;
pub use ltc::Ltc;

use crate::Vec3;

/// A direction argument as a unit vector (the shared helper, see [`crate::math::unit`]).
pub(crate) use crate::math::{is_unit, unit};

/// The coordinates of the fitted tables (LTC, pivot) for a view `wo` (local frame, need
/// not be normalised) and roughness `r = √α`: `(x, y, cos φ, sin φ)` with
/// `x = r·63` (`r` clamped to `[0, 1]`, NaN as 0), `y = √(1 − cos θo)·63` and the view's
/// azimuth `φ` (any azimuth at normal incidence, where the fits are symmetric about the
/// normal). `None` when `wo` is not finite, zero, or at or below the horizon.
#[inline]
pub(crate) fn table_coordinates(wo: Vec3, roughness: f32) -> Option<(f32, f32, f32, f32)> {
    // Normalised by the shared helper first: `wo.length()` overflowed for views of
    // length 1e20 and underflowed for 2⁻¹⁰⁰ (issue 17, 5); a unit `wo` stays as it is.
    let wo = unit(wo)?;
    let length = crate::math::length(wo);
    let cos_theta = wo.z / length;
    if !(cos_theta > 0.0) || !(length < f32::INFINITY) {
        return None;
    }
    let last = 63.0;
    let x = roughness.max(0.0).min(1.0) * last;
    // t = √(1 − cos θ) from 1 − cos θ = sin²θ / (1 + cos θ), which keeps precision near
    // normal incidence.
    let sin2 = (wo.x * wo.x + wo.y * wo.y) / (length * length);
    let y = crate::math::sqrtf(sin2 / (1.0 + cos_theta)).min(1.0) * last;
    let rho = crate::math::sqrtf(wo.x * wo.x + wo.y * wo.y);
    let (cos_phi, sin_phi) = if rho > 0.0 {
        (wo.x / rho, wo.y / rho)
    } else {
        (1.0, 0.0)
    };
    Some((x, y, cos_phi, sin_phi))
}

/// A guess of the fitted tables' row coordinate `y = √(1 − cos θo)·63` of
/// [`table_coordinates`] from the view as given: `√(1 − wo_z)·63`, a square root away
/// from the view where `y` is a square root, two divisions and another square root away
/// (`cos θo = wo_z/|wo|`, `y = √(sin²θo/(1 + cos θo))·63`). For a unit view (the
/// convention; `|wo|² = 1` to 1e-6) both are `√(1 − cos θo)·63` up to rounding, so the
/// guess nearly always lies in `y`'s cell (the pivot fit's
/// `the_fit_s_guessed_row_is_the_exact_cell_for_unit_views`, the LTC's
/// `the_ltc_s_guessed_row_gives_the_former_lookup_s_bits`); a view of another length may
/// guess wrong, and [`table_bilinear_of_guess`] then reads `y`'s own cell (the same bits
/// either way).
#[inline(always)]
pub(crate) fn table_row_guess(wo: Vec3) -> f32 {
    crate::math::sqrtf((1.0 - wo.z).max(0.0)) * 63.0
}

/// Interpolate a table along its row coordinate `y` first, then along `x`: the LTC
/// table's order (a `Y_LAST` argument of [`table_bilinear`] and [`table_bilinear_of_guess`]).
pub(crate) const ALONG_Y_FIRST: bool = false;

/// Interpolate a table along `x` first and along its row coordinate `y` last (see
/// [`table_interpolated`]): the pivot fit's order, in which `y`, the last to arrive, enters
/// only the final interpolation.
pub(crate) const ALONG_Y_LAST: bool = true;

/// The entry of a `size × size` table (row-major, rows along `x`) at fractional cell
/// coordinates `(x, y)` in `[0, size − 1]²`, interpolated bilinearly in the order
/// `Y_LAST` ([`ALONG_Y_FIRST`] or [`ALONG_Y_LAST`]). (The lookups read the tables from a
/// guessed cell, [`table_bilinear_of_guess`]: this is their tests' reference, and the
/// cold path of a wrong guess.)
#[inline]
pub(crate) fn table_bilinear<const K: usize, const Y_LAST: bool>(
    table: &[[f32; K]],
    size: usize,
    x: f32,
    y: f32,
) -> [f32; K] {
    let (i0, j0) = (table_cell(x, size), table_cell(y, size));
    table_interpolated::<K, Y_LAST>(table, size, [i0, j0], x - i0 as f32, y - j0 as f32)
}

/// The cell of a fractional coordinate of [`table_bilinear`]: its integer part, at most
/// `size − 2` (the last cell holds `size − 1`).
#[inline(always)]
fn table_cell(v: f32, size: usize) -> usize {
    // `as u32` truncates towards zero and maps NaN and negative numbers to 0, as
    // `as usize` does, with x86's one signed conversion and a clamp where `as usize`
    // needed a second conversion for the upper half of its range; the inputs are in
    // [0, size − 1].
    (v as u32 as usize).min(size - 2)
}

/// The bilinear interpolation of [`table_bilinear`] in the cell `[i0, j0]` at the offsets
/// `fx = x − i0`, `fy = y − j0`: along `y` first, then along `x` (`Y_LAST = false`), or
/// along `x` first, then along `y` (`Y_LAST = true`). Both are the same bilinear function
/// in exact arithmetic, rounded differently; with `y` last, a `y` that arrives after `x`
/// and the entries waits for one multiplication and two additions instead of four
/// operations and a multiplication.
#[inline(always)]
fn table_interpolated<const K: usize, const Y_LAST: bool>(
    table: &[[f32; K]],
    size: usize,
    [i0, j0]: [usize; 2],
    fx: f32,
    fy: f32,
) -> [f32; K] {
    let at = |i: usize, j: usize| &table[i * size + j];
    let (e00, e01, e10, e11) = (
        at(i0, j0),
        at(i0, j0 + 1),
        at(i0 + 1, j0),
        at(i0 + 1, j0 + 1),
    );
    let lerp = |a: f32, b: f32, t: f32| a + t * (b - a);
    let mut out = [0.0; K];
    for k in 0..K {
        out[k] = if Y_LAST {
            lerp(lerp(e00[k], e10[k], fx), lerp(e01[k], e11[k], fx), fy)
        } else {
            lerp(lerp(e00[k], e01[k], fy), lerp(e10[k], e11[k], fy), fx)
        };
    }
    out
}

/// [`table_bilinear`] in the same order `Y_LAST`, bit for bit, with the cell along `y` read from a guess `y_guess`
/// of `y` that is known earlier (fewer operations away from the inputs): the entries are
/// loaded from the guessed cell while `y` is still being computed, and the guess is
/// checked against `y` afterwards, by a predicted branch. The guessed cell `j` is
/// `y`'s exactly when `j ≤ y < j + 1` (`y ≥ j` for the last cell, `size − 2`), i.e.
/// `0 ≤ fy < 1` for `fy = y − j`, which is exact there (`j = 0`: `fy = y`; `j ≥ 1` and
/// `j ≤ y < j + 1 ≤ 2j`: Sterbenz), and fails for every other `y` in `[0, size − 1]`
/// (`y < j` gives `fy < 0`, `y ≥ j + 1` gives `fy ≥ 1`: rounding keeps the order with 0
/// and 1) and for NaN; `fy` is then `table_bilinear`'s own offset. A wrong guess takes
/// `table_bilinear` (out of line and cold). (Issue 18: the sphere light sampler's fit,
/// whose row coordinate waited on a square root and two divisions before the table's
/// loads could start, on the preparation's critical path.)
#[inline(always)]
pub(crate) fn table_bilinear_of_guess<const K: usize, const Y_LAST: bool>(
    table: &[[f32; K]],
    size: usize,
    x: f32,
    y: f32,
    y_guess: f32,
) -> [f32; K] {
    let (i0, j) = (table_cell(x, size), table_cell(y_guess, size));
    let fy = y - j as f32;
    if fy >= 0.0 && (fy < 1.0 || j == size - 2) {
        table_interpolated::<K, Y_LAST>(table, size, [i0, j], x - i0 as f32, fy)
    } else {
        table_bilinear_cold::<K, Y_LAST>(table, size, x, y)
    }
}

/// [`table_bilinear`] out of line and cold: [`table_bilinear_of_guess`] of a wrong guess.
#[cold]
#[inline(never)]
fn table_bilinear_cold<const K: usize, const Y_LAST: bool>(
    table: &[[f32; K]],
    size: usize,
    x: f32,
    y: f32,
) -> [f32; K] {
    table_bilinear::<K, Y_LAST>(table, size, x, y)
}
