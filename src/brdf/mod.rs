//! BRDFs of the shading point: the GGX microfacet BRDF with visible-normal sampling
//! (Heitz 2018), the Lambertian BRDF with cosine-weighted sampling, and linearly
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
pub mod pivot_table;

pub use ggx::GgxBrdf;
pub use lambert::Lambert;
pub use ltc::{Ltc, LtcPolygon};

use crate::Vec3;

/// How far `|v|²` may lie from 1 for `v` to be taken as a unit vector unchanged. A
/// direction normalised in `f32` has `|v|²` within a few ulp (~4e-7) of 1; taking
/// such a vector as it is (instead of normalising it again) makes [`unit`] idempotent,
/// so that a sampler's returned direction evaluates to bit-identical densities when it
/// is passed back to `pdf`.
const UNIT_TOLERANCE: f32 = 1e-6;

/// `v / |v|`, or `None` when `v` is zero or not finite. A vector whose squared length
/// lies within [`UNIT_TOLERANCE`] of 1 is returned unchanged. Others are first divided
/// by their largest absolute coordinate, so that neither `|v|²` overflows for huge
/// vectors nor underflows for tiny (even subnormal) ones.
#[inline(always)]
pub(crate) fn unit(v: Vec3) -> Option<Vec3> {
    if (v.length_squared() - 1.0).abs() <= UNIT_TOLERANCE {
        // NaN fails the comparison above; an infinity gives |v|² = inf.
        return Some(v);
    }
    if !v.is_finite() {
        return None;
    }
    let largest = v.x.abs().max(v.y.abs()).max(v.z.abs());
    if !(largest > 0.0) {
        return None;
    }
    let scaled = v / largest;
    Some(scaled / scaled.length())
}

/// The coordinates of the fitted tables (LTC, pivot) for a view `wo` (local frame, need
/// not be normalised) and roughness `r = √α`: `(x, y, cos φ, sin φ)` with
/// `x = r·63` (`r` clamped to `[0, 1]`, NaN as 0), `y = √(1 − cos θo)·63` and the view's
/// azimuth `φ` (any azimuth at normal incidence, where the fits are symmetric about the
/// normal). `None` when `wo` is not finite, zero, or at or below the horizon.
#[inline]
pub(crate) fn table_coordinates(wo: Vec3, roughness: f32) -> Option<(f32, f32, f32, f32)> {
    let length = wo.length();
    let cos_theta = wo.z / length;
    if !(cos_theta > 0.0) || !(length < f32::INFINITY) {
        return None;
    }
    let last = 63.0;
    let x = roughness.max(0.0).min(1.0) * last;
    // t = √(1 − cos θ) from 1 − cos θ = sin²θ / (1 + cos θ), which keeps precision near
    // normal incidence.
    let sin2 = (wo.x * wo.x + wo.y * wo.y) / (length * length);
    let y = libm::sqrtf(sin2 / (1.0 + cos_theta)).min(1.0) * last;
    let rho = libm::sqrtf(wo.x * wo.x + wo.y * wo.y);
    let (cos_phi, sin_phi) = if rho > 0.0 {
        (wo.x / rho, wo.y / rho)
    } else {
        (1.0, 0.0)
    };
    Some((x, y, cos_phi, sin_phi))
}

/// The entry of a `size × size` table (row-major, rows along `x`) at fractional cell
/// coordinates `(x, y)` in `[0, size − 1]²`, interpolated bilinearly.
#[inline]
pub(crate) fn table_bilinear<const K: usize>(
    table: &[[f32; K]],
    size: usize,
    x: f32,
    y: f32,
) -> [f32; K] {
    let last = size - 1;
    // `as usize` truncates towards zero and maps NaN to 0; the inputs are in [0, last].
    let (i0, j0) = ((x as usize).min(last - 1), (y as usize).min(last - 1));
    let (fx, fy) = (x - i0 as f32, y - j0 as f32);
    let at = |i: usize, j: usize| &table[i * size + j];
    let (e00, e01, e10, e11) = (
        at(i0, j0),
        at(i0, j0 + 1),
        at(i0 + 1, j0),
        at(i0 + 1, j0 + 1),
    );
    let mut out = [0.0; K];
    for k in 0..K {
        let low = e00[k] + fy * (e01[k] - e00[k]);
        let high = e10[k] + fy * (e11[k] - e10[k]);
        out[k] = low + fx * (high - low);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_normalises_rejects_and_is_idempotent() {
        assert_eq!(unit(Vec3::ZERO), None);
        assert_eq!(unit(Vec3::new(f32::NAN, 0.0, 1.0)), None);
        assert_eq!(unit(Vec3::new(0.0, f32::INFINITY, 1.0)), None);
        assert_eq!(unit(Vec3::new(0.0, 0.0, f32::NEG_INFINITY)), None);
        for v in [
            Vec3::new(3.0, -4.0, 12.0),
            Vec3::new(1e30, 2e30, -2e30),
            Vec3::new(1e-40, 0.0, 1e-40),
            Vec3::new(f32::MAX, f32::MAX, f32::MAX),
        ] {
            let u = unit(v).unwrap();
            assert!((u.length() - 1.0).abs() < 1e-6, "{v} -> {u}");
            assert!(u.dot(v) > 0.0);
            assert_eq!(unit(u), Some(u), "not idempotent for {v}");
        }
    }
}
