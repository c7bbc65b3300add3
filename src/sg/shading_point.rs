//! A shading point prepared once for VSGL shading (Tokuyoshi 2016, supplement
//! Section 4.2), then shaded by any number of incoming-radiance SGs (issue 18, item 1).
//!
//! The free functions of [`crate::sg::shading`] take the normal and the view with every
//! lobe, so a renderer that shades many VSGLs at one point normalises both, fits the ASG
//! of the GGX lobe ([`Asg::from_ggx`]) and evaluates Smith's `Λ(ω_o)` once per lobe,
//! although none of them depends on the lobe. [`SgShadingPoint::prepare`] does that work
//! once; [`SgShadingPoint::shade`] then gives, per incoming SG, the constant-cosine
//! diffuse term ([`diffuse_shading_constant_cosine`](crate::sg::shading::diffuse_shading_constant_cosine))
//! and the ASG specular term ([`specular_shading`](crate::sg::shading::specular_shading))
//! **bit for bit** as the free functions give them for the same normal, view, roughness
//! and `f0` (test `shading_point_matches_the_free_functions_bit_for_bit`): every
//! operation below is the free function's, in the same order, only split at the point
//! where the lobe enters.
//!
//! What is kept (all depends on the shading point only):
//!
//! - the unit normal `n` and view `ω_o` (the library's one normalisation,
//!   [`crate::math::unit`], which returns a unit vector unchanged, so that the free
//!   functions' own normalisation of them is the identity on these values);
//! - the ASG fit `Ĝ` of GGX's lobe for `ω_o` (`z = ξ_s`, `η_x = λ_h/8`,
//!   `η_y = λ_h/(8 cos²θ_o)`, module documentation of [`crate::sg::asg`]);
//! - `α` (roughness², clamped as [`roughness_to_alpha`] does), `f0` clamped to `[0, 1]`;
//! - `cos θ_o = ω_o·n`, `1 + Λ(ω_o)` of the height-correlated `G2 = 1/(1 + Λ(ω_o) +
//!   Λ(ω))`, and the denominator `4πα² max(cos θ_o, MIN_SPECULAR_COSINE)` of
//!   `C(ω) = F G2/(4πα² cos θ_o)`.
//!
//! Per lobe there remain the incoming SG's sanitisation (once for both terms, where the
//! two free functions do it once each), `ξ_in·n`, the half vector, Schlick's Fresnel,
//! `Λ(ξ_in)`, the ASG × SG convolution and the diffuse term's `A(λ_in)`.
//!
//! Bad input: [`SgShadingPoint::prepare`] returns `false` and leaves
//! [`SgShadingPoint::EMPTY`] for a zero or non-finite normal or view; the empty point
//! shades every lobe to `(0, 0)`. (The free diffuse function does not read the view, so
//! with an invalid view it still gives a diffuse term; a prepared point without a valid
//! view is empty as a whole, the one difference.) A view at or below the horizon is
//! valid: the diffuse term as usual, the specular term 0 (as the free function gives).
//! NaN or out-of-range roughness, `f0`, `r_d` and visibility are clamped as the free
//! functions clamp them. Every output is finite and non-negative.

use super::asg::Asg;
use super::lobes::{MIN_SPECULAR_COSINE, clamp_lobe_alpha};
use super::sg::{Sg, exp_finite, log_of_amplitude, log_sg_integral, unit_or_none};
use super::shading::{clamp_nonnegative, clamp_unit, roughness_to_alpha};
use crate::Vec3;
use crate::brdf::ggx::GgxBrdf;
use core::f32::consts::PI;

/// The two shading terms of one incoming-radiance SG at a prepared point.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SgShading {
    /// `V (c_in R_d/π) A(λ_in) max(ξ_in·n, 0)`: constant-cosine diffuse shading.
    pub diffuse: f32,
    /// `V c_in C(ξ_in) ∫ G_in Ĝ dω`: GGX specular shading through the ASG fit.
    pub specular: f32,
}

impl SgShading {
    /// Both terms 0.
    ///
    /// cbindgen:ignore
    pub const ZERO: SgShading = SgShading {
        diffuse: 0.0,
        specular: 0.0,
    };
}

/// A shading point prepared for VSGL shading: what the diffuse and specular terms need
/// that does not depend on the lobe (see the module documentation). 23 `f32` words,
/// 92 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SgShadingPoint {
    /// The unit normal `n` (zero in [`SgShadingPoint::EMPTY`]).
    normal: Vec3,
    /// The unit view `ω_o`, toward the viewer.
    view: Vec3,
    /// The ASG fit of GGX's lobe for `ω_o` ([`Asg::from_ggx`]).
    lobe: Asg,
    /// `α = roughness²`, clamped to `[MIN_LOBE_ALPHA, 1]`.
    alpha: f32,
    /// Schlick's reflectance at normal incidence, clamped to `[0, 1]`.
    f0: f32,
    /// `cos θ_o = ω_o·n`; the specular term is 0 unless it is positive (0 in `EMPTY`).
    cos_view: f32,
    /// `1 + Λ(ω_o)`: the first two terms of `G2`'s denominator, in the free function's
    /// order of addition `(1 + Λ(ω_o)) + Λ(ω)`.
    one_plus_lambda_view: f32,
    /// `4πα² max(cos θ_o, MIN_SPECULAR_COSINE)`, multiplied in the free function's order
    /// `((4π α) α) cos`.
    denominator: f32,
}

impl SgShadingPoint {
    /// The empty point: every lobe shades to `(0, 0)` (a zero normal makes
    /// `max(ξ_in·n, 0) = 0`, `cos θ_o = 0` turns the specular term off).
    ///
    /// cbindgen:ignore
    pub const EMPTY: SgShadingPoint = SgShadingPoint {
        normal: Vec3::ZERO,
        view: Vec3::ZERO,
        lobe: Asg::ZERO,
        alpha: 1.0,
        f0: 0.0,
        cos_view: 0.0,
        one_plus_lambda_view: 1.0,
        denominator: 1.0,
    };

    /// Prepares the point with shading normal `normal`, view `view` (toward the viewer;
    /// both in any frame, the same as the incoming SGs', normalised here), GGX roughness
    /// `roughness` (`α = roughness²`, clamped as in [`roughness_to_alpha`]) and Schlick's
    /// `f0` of one channel (clamped to `[0, 1]`, NaN to 0). Writes
    /// [`SgShadingPoint::EMPTY`] and returns `false` for a zero or non-finite normal or
    /// view.
    pub fn prepare(&mut self, normal: Vec3, view: Vec3, roughness: f32, f0: f32) -> bool {
        let (Some(n), Some(wo)) = (unit_or_none(normal), unit_or_none(view)) else {
            *self = SgShadingPoint::EMPTY;
            return false;
        };
        // `specular_factor`: α from the roughness; `lobe_factor` clamps it again (a
        // no-op on a clamped value, kept for the same bits).
        let alpha = clamp_lobe_alpha(roughness_to_alpha(roughness));
        let cos_view = wo.dot(n);
        // Λ(ω_o) as `ggx_lobe_factor` evaluates it (f32::MAX at or below the horizon,
        // where the specular term is 0 anyway).
        let lambda_view = GgxBrdf::from_alpha(alpha, Vec3::ONE).lambda(cos_view);
        *self = SgShadingPoint {
            normal: n,
            view: wo,
            // `asg_shading` fits the lobe from the raw normal and view; `from_ggx`
            // normalises them by the same `unit`, which returns `n`, `wo` unchanged.
            lobe: Asg::from_ggx(n, wo, roughness_to_alpha(roughness)),
            alpha,
            f0: clamp_unit(f0),
            cos_view,
            one_plus_lambda_view: 1.0 + lambda_view,
            denominator: 4.0 * PI * alpha * alpha * cos_view.max(MIN_SPECULAR_COSINE),
        };
        true
    }

    /// A prepared point (see [`SgShadingPoint::prepare`]).
    pub fn new(normal: Vec3, view: Vec3, roughness: f32, f0: f32) -> SgShadingPoint {
        let mut point = SgShadingPoint::EMPTY;
        point.prepare(normal, view, roughness, f0);
        point
    }

    /// The diffuse and specular shading of the incoming-radiance SG `incoming`
    /// ([`crate::sg::shading::incoming_radiance`]) with diffuse albedo `r_d` (clamped to
    /// `[0, f32::MAX]`, NaN to 0) and visibility `visibility` (clamped to `[0, 1]`, NaN
    /// to 0): bit for bit `diffuse_shading_constant_cosine(incoming, n, r_d, V)` and
    /// `specular_shading(incoming, n, ω_o, roughness, f0, V)` of the prepared values.
    pub fn shade(&self, incoming: &Sg, r_d: f32, visibility: f32) -> SgShading {
        let incoming = incoming.sanitized();
        let visibility = clamp_unit(visibility);
        SgShading {
            diffuse: self.diffuse(&incoming, r_d, visibility),
            specular: self.specular(&incoming, visibility),
        }
    }

    /// `diffuse_shading_constant_cosine` for a sanitised SG and a clamped visibility.
    #[inline(always)]
    fn diffuse(&self, incoming: &Sg, r_d: f32, visibility: f32) -> f32 {
        // `axis_cosine`: max(ξ_in·n, 0); 0 for the empty point's zero normal.
        let cosine = incoming.axis.dot(self.normal).max(0.0);
        let factor = clamp_nonnegative(r_d) * visibility * cosine;
        exp_finite(
            incoming.log_amplitude + log_sg_integral(incoming.sharpness) - libm::logf(PI)
                + log_of_amplitude(factor),
        )
    }

    /// `specular_shading` for a sanitised SG and a clamped visibility: `V C(ξ_in)` as
    /// `ggx_lobe_factor` forms it, times the ASG × SG convolution as `asg_shading`.
    #[inline(always)]
    fn specular(&self, incoming: &Sg, visibility: f32) -> f32 {
        let factor = self.lobe_factor(incoming.axis) * visibility;
        if !(factor > 0.0) {
            return 0.0;
        }
        let value = factor * self.lobe.convolve_sg(incoming);
        if value.is_finite() {
            value.min(f32::MAX)
        } else {
            f32::MAX
        }
    }

    /// `C(ξ_in) = F(ω_o·h) G2/(4πα² cos θ_o)` (`lobe_factor` of
    /// [`crate::sg::shading`] with the view's part prepared); 0 at or below either
    /// horizon.
    #[inline(always)]
    fn lobe_factor(&self, dir: Vec3) -> f32 {
        // The sanitised axis is a unit vector: `unit` returns it unchanged (one `|v|²`
        // test), as in the free function.
        let Some(wi) = unit_or_none(dir) else {
            return 0.0;
        };
        let (co, ci) = (self.cos_view, wi.dot(self.normal));
        if !(co > 0.0) || !(ci > 0.0) {
            return 0.0;
        }
        let wo = self.view;
        let Some(h) = unit_or_none(wo + wi) else {
            return 0.0;
        };
        let m = (1.0 - wo.dot(h)).max(0.0).min(1.0);
        let m2 = m * m;
        let fresnel = self.f0 + (1.0 - self.f0) * (m2 * m2 * m);
        let lambda = GgxBrdf::from_alpha(self.alpha, Vec3::ONE).lambda(ci);
        let g2 = 1.0 / (self.one_plus_lambda_view + lambda);
        let value = fresnel * g2 / self.denominator;
        if value.is_finite() { value } else { 0.0 }
    }
}
