//! Sphere lights over GGX surfaces with the fitted uniform SPTD (Dupuy et al. 2017,
//! Sections 5 and 6.1).
//!
//! [`GgxPivot::from_view`] reads the pivot table (`brdf/pivot_table.rs`, fitted by
//! `tools/src/fitters/pivot_fitter.rs`, in its Cartesian form `brdf/pivot_cartesian_table.rs`):
//! for a view `ω_o` and roughness `r = √α`, the pivot `r_p` of the uniform SPTD
//! `D ≈ f cos θ / albedo` and the albedo `∫ f cos θ dω` (Fresnel = 1), its components
//! interpolated bilinearly like the LTC table and rotated to the view's azimuth.
//!
//! **Real-time shading** (Section 5.2, Eq. 17–19; biased: the SPTD only approximates
//! GGX): a sphere of radiance `L` subtending the cap `C` gives
//!
//! `L_o ≈ L · albedo · ∫_{C ∩ H} D = L · albedo · Ω(g(C) ∩ g(H)) / 4π`,
//!
//! with `H` the upper hemisphere's cap and the exact two-cap solid angle (the paper uses
//! Oat and Sander's approximation, which fails for the image of `H`, often wider than a
//! hemisphere). **Specular occlusion** (Section 5.4, Eq. 23) replaces `H` by a bent cone
//! `V` (the visibility cap): `L · albedo · Ω(g(C) ∩ g(V)) / 4π`, the triple product of
//! BRDF, light and visibility; for an unoccluded point `V = H` and both agree. Its
//! baseline, the separable approximation of Eq. 21–22
//! ([`SphereLightShading::eval_occluded_separable`]), multiplies the unoccluded shading
//! by the fraction of the BRDF lobe inside the cone. The
//! Fresnel factor is the LTC table's Schlick-weighted albedo ([`Ltc::specular_albedo`]),
//! so the result is RGB.
//!
//! **Joint BRDF–light sampling** (Section 6.1, unbiased): [`SphereLightSampler`] draws
//! directions from the SPTD restricted to the light's cap (its density `J(ω)/Ω(g(C))`
//! follows the BRDF inside the cap) and is meant to be combined with GGX VNDF sampling
//! by MIS. When `Ω(g(C)) < 10⁻³` the SPTD density `∝ 1/Ω(g(C))` becomes unstable and
//! the sampler falls back to uniform cap sampling (the paper's "classic MIS"); those
//! are the configurations far from the highlight.
//!
//! Hard cases (tested): views from normal incidence to grazing (`cos θo = 10⁻⁴`),
//! roughness 0 to 1, tiny caps (1e-6 sr), caps straddling the horizon or below it, a
//! shading point inside the sphere (the whole sphere), bent cones narrower than and
//! disjoint from the light.

use super::cap::Cap;
use super::cap_intersection::cap_intersection_solid_angle;
use super::cap_intersection_sampling::{CapIntersection, MIN_NORMALISER};
use super::pivot::{
    jacobian_numerator, jacobian_of_numerator, pivot_cap, pivot_cap_by_points, pivot_cap_fast,
    transform_numerator, transform_of_numerator,
};
use super::shading_fast::pivoted_intersection_fast;
use super::sptd::{Sptd, SptdBase, SptdInCap};
use crate::Sample;
use crate::brdf::Ltc;
use crate::brdf::pivot_cartesian_table::{PIVOT_CARTESIAN_TABLE, PIVOT_CARTESIAN_TABLE_SIZE};
use crate::brdf::{ALONG_Y_LAST, table_bilinear_of_guess, table_coordinates, table_row_guess};
use core::f32::consts::PI;
use glam::Vec3;

/// The solid angle of `g(C)` below which [`SphereLightSampler`] samples the cap
/// uniformly instead of by the SPTD (Section 6.1: "smaller than 10⁻³").
pub const MIN_PIVOTED_SOLID_ANGLE: f32 = 1e-3;

/// The upper hemisphere's cap `H`, as `Cap::from_axis_one_minus_cos(Vec3::Z, 1.0)` builds
/// it (`light_tests::the_upper_hemisphere_constant_is_the_built_cap`), as a constant: the
/// clipped sampler's `pivot_cap_fast(H, r_p)` is then folded for its axis `z` and its
/// `cos θ = 0` (the same bits).
const UPPER_HEMISPHERE: Cap = Cap {
    axis: Vec3::Z,
    one_minus_cos: 1.0,
    one_plus_cos: 1.0,
    sin2: 1.0,
};

/// The uniform SPTD fitted to GGX `f cos θ` at one view and roughness.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GgxPivot {
    /// The pivot `r_p` in the local frame (`|r_p| < 1`).
    pub pivot: Vec3,
    /// `∫ f cos θ dω` with Fresnel = 1.
    pub albedo: f32,
}

impl GgxPivot {
    /// The fit for the view `wo` (local frame, need not be normalised) and roughness
    /// `r = √α` (clamped to `[0, 1]`, NaN as 0). `None` when `wo` is not finite, zero,
    /// or at or below the horizon. Always inlined: out of line, the sampler's `prepare`
    /// received the fit through memory (an `Option` of four floats), 45 instructions more
    /// per preparation (callgrind, light bench `sptd`).
    #[inline(always)]
    pub fn from_view(wo: Vec3, roughness: f32) -> Option<GgxPivot> {
        let (x, y, cos_phi, sin_phi) = table_coordinates(wo, roughness)?;
        // The table's loads start from the guessed row (`table_row_guess`) without
        // waiting on `table_coordinates`' square root and two divisions (the bits of
        // `table_bilinear`, see `table_bilinear_of_guess`; issue 18, stop 46: light bench
        // `sptd` about −6 to −11 ns per prepare + 1, `rt_shade` about −10 ns).
        let guess = table_row_guess(wo);
        // The pivot's components in the view frame, interpolated bilinearly (the Cartesian
        // form of the fitted (norm, elevation) table, `pivot_cartesian_table.rs`): no sine
        // and cosine of an interpolated elevation on the preparation's critical path
        // (issue 18, stop 47). The view frame's x axis has the view's azimuth, so the
        // pivot is `(x cos φ, x sin φ, z)`.
        let [x_view, z_view, albedo] = table_bilinear_of_guess::<3, ALONG_Y_LAST>(
            &PIVOT_CARTESIAN_TABLE,
            PIVOT_CARTESIAN_TABLE_SIZE,
            x,
            y,
            guess,
        );
        let pivot = Vec3::new(x_view * cos_phi, x_view * sin_phi, z_view);
        Some(GgxPivot {
            pivot: super::pivot::valid_pivot(pivot),
            albedo,
        })
    }

    /// The SPTD `D ≈ f cos θ / albedo`.
    #[inline]
    pub fn sptd(&self) -> Sptd {
        Sptd::uniform(self.pivot)
    }
}

/// Real-time GGX shading of sphere lights by the fitted SPTD (biased; see the module
/// documentation): prepared once per shading point and material, then evaluated for
/// any number of lights.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereLightShading {
    /// The fitted pivot.
    pub fit: GgxPivot,
    /// The image of the cap that clips the light: `g(H)`, the upper hemisphere's
    /// ([`new`](Self::new)), or `g(V)`, a bent cone's ([`new_occluded`](Self::new_occluded)).
    pub clip_image: Cap,
    /// The Schlick-weighted albedo per channel.
    pub specular_albedo: Vec3,
}

impl SphereLightShading {
    /// Prepares the shading of a GGX surface with roughness `r = √α` and Fresnel
    /// reflectance at normal incidence `f0` for the view `wo`. `None` when `wo` is not
    /// finite, zero, or at or below the horizon.
    pub fn new(wo: Vec3, roughness: f32, f0: Vec3) -> Option<SphereLightShading> {
        let fit = GgxPivot::from_view(wo, roughness)?;
        let ltc = Ltc::from_ggx(wo, roughness)?;
        Some(SphereLightShading {
            fit,
            clip_image: horizon_image(&fit.pivot),
            specular_albedo: ltc.specular_albedo(clamped_f0(f0)),
        })
    }

    /// [`new`](Self::new) with specular occlusion by the bent cone `visibility` (Eq. 23)
    /// prepared in: the bent cone's image `g(V)` takes the place of the upper
    /// hemisphere's, so that [`eval`](Self::eval) of every light gives
    /// [`eval_occluded`](Self::eval_occluded) with this bent cone, bit for bit, at the
    /// cost of `eval`. A renderer's bent cone belongs to the shading point, not to a
    /// light: it is pivoted once here instead of once per light (issue 18, 1). An empty
    /// `visibility` (after [`Cap::sanitized`]) shades every light to zero. `None` as
    /// [`new`](Self::new).
    pub fn new_occluded(
        wo: Vec3,
        roughness: f32,
        f0: Vec3,
        visibility: &Cap,
    ) -> Option<SphereLightShading> {
        let fit = GgxPivot::from_view(wo, roughness)?;
        let ltc = Ltc::from_ggx(wo, roughness)?;
        Some(SphereLightShading {
            fit,
            clip_image: visible_image(visibility, &fit.pivot),
            specular_albedo: ltc.specular_albedo(clamped_f0(f0)),
        })
    }

    /// `∫_{C ∩ H} f cos θ dω ≈ albedo_F · Ω(g(C) ∩ g(H)) / 4π` per unit radiance
    /// (Eq. 19), for the cap `C` of a light (sanitized here); for a shading prepared by
    /// [`new_occluded`](Self::new_occluded), `albedo_F · Ω(g(C) ∩ g(V)) / 4π` (Eq. 23).
    #[inline(always)]
    pub fn eval(&self, light: &Cap) -> Vec3 {
        self.eval_clipped(light, &self.clip_image)
    }

    /// `albedo_F · Ω(g(C) ∩ clip) / 4π` for the pivoted clip `g(H)` or `g(V)`.
    #[inline(always)]
    fn eval_clipped(&self, light: &Cap, clip: &Cap) -> Vec3 {
        // The image and its intersection in one pass where well conditioned, the image
        // as a cap and the exact two-cap solid angle elsewhere (issue 18, 1).
        let area = if light.is_valid() {
            pivoted_intersection(light, &self.fit.pivot, clip)
        } else {
            pivoted_intersection_of_invalid(light, &self.fit.pivot, clip)
        };
        self.specular_albedo * (area * (0.25 / PI))
    }

    /// Specular occlusion with a bent cone `visibility` (Eq. 23): `∫_{C ∩ V} f cos θ dω
    /// ≈ albedo_F · Ω(g(C) ∩ g(V)) / 4π`. The bent cone takes the place of the upper
    /// hemisphere (an unoccluded point's bent cone is `H`, and then this equals
    /// [`SphereLightShading::eval`]).
    ///
    /// The bent cone is pivoted at every call: where it belongs to the shading point,
    /// prepare it once with [`new_occluded`](Self::new_occluded) and call `eval`.
    #[inline(always)]
    pub fn eval_occluded(&self, light: &Cap, visibility: &Cap) -> Vec3 {
        self.eval_clipped(light, &visible_image(visibility, &self.fit.pivot))
    }

    /// Specular occlusion by the separable approximation that Eq. 23 improves on
    /// (Eq. 21–22; the baseline of [`eval_occluded`](Self::eval_occluded)):
    /// `L_o ≈ (V_f / f̄) · L_f`, the unoccluded shading `L_f` of
    /// [`eval`](Self::eval) times the fraction of the BRDF lobe inside the bent cone,
    /// `V_f / f̄ = ∫_{V ∩ H} D / ∫_H D = Ω(g(V) ∩ g(H)) / Ω(g(H))`, the same SPTD `D`
    /// standing for `f cos θ` in both factors, so that the two methods differ only in
    /// the separation. It neglects the correlation of visibility and light: a bent cone
    /// that holds most of the lobe but not the light lets the light through (shadow
    /// leaking, the paper's Fig. 11 d). Equals `shade` for `V = H`.
    ///
    /// `g(H)` is computed here (the prepared clip may be a bent cone's image, from
    /// [`new_occluded`](Self::new_occluded)), bit for bit as [`new`](Self::new) stores it.
    pub fn eval_occluded_separable(&self, light: &Cap, visibility: &Cap) -> Vec3 {
        let horizon = horizon_image(&self.fit.pivot);
        let visible = pivot_cap(&visibility.sanitized(), self.fit.pivot);
        let lobe = horizon.solid_angle();
        let inside = cap_intersection_solid_angle(&visible, &horizon);
        // `lobe > 0` for every prepared value (the image of H is at least a hemisphere's
        // worth of the pivoted sphere); the test keeps a hand-made one finite.
        let fraction = if lobe > 0.0 {
            (inside / lobe).min(1.0)
        } else {
            0.0
        };
        self.eval_clipped(light, &horizon) * fraction
    }
}

/// `f0` clamped to `[0, 1]` per channel; 0 unless every channel is finite.
#[inline(always)]
fn clamped_f0(f0: Vec3) -> Vec3 {
    if f0.is_finite() {
        f0.max(Vec3::ZERO).min(Vec3::ONE)
    } else {
        Vec3::ZERO
    }
}

/// The image `g(H)` of the upper hemisphere's cap by the pivot: the function that
/// [`visible_image`] applies to a bent cone, so that the bent cone `H` gives
/// [`SphereLightShading::eval`] bit for bit.
#[inline(always)]
fn horizon_image(pivot: &Vec3) -> Cap {
    visible_image(&Cap::from_axis_one_minus_cos(Vec3::Z, 1.0), pivot)
}

/// The image `g(V)` of a bent cone by the pivot (made valid first).
#[inline(always)]
fn visible_image(visibility: &Cap, pivot: &Vec3) -> Cap {
    pivot_cap_by_points(&visibility.sanitized(), pivot).0
}

/// `Ω(g(light) ∩ clip)` for a valid light cap and the pivoted clip (`g(H)` or `g(V)`): the
/// one-pass closed form where it is well conditioned (`shading_fast`), else the image by
/// `pivot_cap_by_points` and the exact two-cap solid angle.
///
/// The pivot by reference: by value, the compiler copied it from the prepared struct to
/// the stack as 8 + 4 bytes and read it back as 4 + 8 (a load across two stores, which
/// the store buffer cannot forward: 72 instead of 55 ns a light in one build).
#[inline(always)]
fn pivoted_intersection(light: &Cap, pivot: &Vec3, clip: &Cap) -> f32 {
    match pivoted_intersection_fast(light, pivot, clip) {
        Some(area) => area,
        None => pivoted_intersection_careful(light, pivot, clip),
    }
}

/// [`pivoted_intersection`] of a light cap that is not valid as it is (built by hand), made
/// valid first: out of line and cold, so that the common path reads a valid light where
/// it is (`light.sanitized()` in line returned a copy, which the compiler stored to the
/// stack and loaded back: six instructions a light). `Cap::sanitized` returns a valid cap
/// unchanged, so both paths give what `pivoted_intersection(&light.sanitized(), ..)` gave.
#[inline(never)]
#[cold]
fn pivoted_intersection_of_invalid(light: &Cap, pivot: &Vec3, clip: &Cap) -> f32 {
    pivoted_intersection(&light.sanitized(), pivot, clip)
}

/// The careful path of [`pivoted_intersection`] (out of line: it is rare).
#[inline(never)]
#[cold]
fn pivoted_intersection_careful(light: &Cap, pivot: &Vec3, clip: &Cap) -> f32 {
    let (image, _) = pivot_cap_by_points(light, pivot);
    cap_intersection_solid_angle(&image, clip)
}

/// `[transform_numerator(pivot), jacobian_numerator(pivot)]`, the numerators of
/// [`transform`](super::pivot::transform) and of
/// [`jacobian_of_unit`](super::pivot::jacobian_of_unit) that [`SphereLightSampler`]
/// prepares for its pivot (`[1, 1]` for the zero pivot, exactly).
#[inline(always)]
fn pivot_numerators(pivot: Vec3) -> [f32; 2] {
    [transform_numerator(pivot), jacobian_numerator(pivot)]
}

/// Light sampling of a sphere light by the fitted SPTD restricted to its cap (Section 6.1),
/// with the paper's fallback to uniform cap sampling when `Ω(g(C)) < 10⁻³`; combine it with
/// [`crate::brdf::GgxBrdf::sample`] by MIS. Its pdf is per steradian and 0 outside the cap.
/// A cap that crosses the horizon is sampled in `C ∩ H` only, uniformly in `g(C) ∩ g(H)`
/// mapped back by `g` (density `J(ω) / Ω(g(C) ∩ g(H))`; the fallback uniformly in `C ∩ H`),
/// so that no sample is wasted below the horizon.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereLightSampler {
    /// The SPTD in the light's cap (its `cap` is the light's cap), for a cap above the
    /// horizon.
    pub sptd: SptdInCap,
    /// For a cap that crosses the horizon: the region sampled uniformly, `g(C) ∩ g(H)`
    /// (`C ∩ H` for the fallback); empty otherwise.
    clipped_region: CapIntersection,
    /// For a cap that crosses the horizon: the light's cap `C`.
    light: Cap,
    /// For a cap that crosses the horizon and the SPTD: the pivot, made valid
    /// (`valid_pivot`, as `pivot_transform` and `pivot_jacobian` make it; zero otherwise).
    pivot: Vec3,
    /// The numerators of the transformation and of the Jacobian for `pivot`,
    /// `(1 − ρ)(1 + ρ)` and `1 − |r_p|²` ([`pivot_numerators`]): computed once in `prepare`
    /// rather than per sample (the same bits; a length and its square root per clipped
    /// sample).
    pivot_numerators: [f32; 2],
    /// 1 when the SPTD is used, 0 for uniform sampling (any other value, from a
    /// corrupted struct, counts as 1). A `u32`, not a `bool`: a `bool` left three
    /// padding bytes that a C caller copying the struct reads uninitialised (issue 16, 7;
    /// valgrind flagged the adversarial C test).
    uses_sptd: u32,
    /// 1 when the cap crosses the horizon and `clipped_region` is sampled.
    clipped: u32,
}

impl SphereLightSampler {
    /// The sampler of an empty cap: no samples, pdf 0.
    ///
    /// cbindgen:ignore
    pub const EMPTY: SphereLightSampler = SphereLightSampler {
        sptd: SptdInCap::EMPTY,
        clipped_region: CapIntersection::EMPTY,
        light: Cap::EMPTY,
        pivot: Vec3::ZERO,
        pivot_numerators: [1.0; 2],
        uses_sptd: 0,
        clipped: 0,
    };

    /// Whether the SPTD is used (else uniform sampling of the light's cap, for caps
    /// whose pivoted image is below 1e-3 sr).
    #[inline]
    #[must_use]
    pub fn uses_sptd(&self) -> bool {
        self.uses_sptd != 0
    }

    /// Whether the light's cap crosses the horizon, so that only `C ∩ H` is sampled.
    #[inline]
    #[must_use]
    pub fn is_clipped(&self) -> bool {
        self.clipped != 0
    }

    /// Prepares sampling of the sphere (center relative to the shading point, radius)
    /// for a GGX surface with roughness `r = √α` seen from `wo`. `None` when the cap is
    /// empty (bad center or radius), lies wholly below the horizon, or `wo` is at or
    /// below the horizon, not finite or zero.
    pub fn new(center: Vec3, radius: f32, wo: Vec3, roughness: f32) -> Option<SphereLightSampler> {
        let mut sampler = Self::EMPTY;
        sampler
            .prepare(center, radius, wo, roughness)
            .then_some(sampler)
    }

    /// [`SphereLightSampler::new`] written in place into `self` (no copy of the
    /// prepared value); `false` and [`SphereLightSampler::EMPTY`] written where `new`
    /// gives `None`. Always inlined (into the C entry point; 7 instructions per
    /// preparation, measured).
    #[inline(always)]
    pub fn prepare(&mut self, center: Vec3, radius: f32, wo: Vec3, roughness: f32) -> bool {
        let cap = Cap::from_sphere(center, radius);
        // The fitted pivot is valid as it stands (`fitted_pivots_are_valid_as_they_stand`):
        // not made valid again.
        let prepared = cap.one_minus_cos > 0.0
            && GgxPivot::from_view(wo, roughness)
                .is_some_and(|fit| self.prepare_sanitized::<true>(&cap, fit.pivot));
        if !prepared {
            *self = Self::EMPTY;
        }
        prepared
    }

    /// [`prepare`](Self::prepare) with the view's fit computed by the caller
    /// ([`GgxPivot::from_view`] of the shading point's view and roughness): the fit
    /// depends on the shading point and the material, not on the light, so that a
    /// renderer fits once per shading point and prepares each sphere light from it. The
    /// same bits as `prepare` for the fit that `from_view` returns; any other pivot is
    /// made valid first (as [`prepare_with_pivot`](Self::prepare_with_pivot) does).
    /// `false` and [`SphereLightSampler::EMPTY`] written where `prepare` fails (an
    /// empty cap, one wholly below the horizon).
    #[inline(always)]
    pub fn prepare_with_fit(&mut self, center: Vec3, radius: f32, fit: &GgxPivot) -> bool {
        let cap = Cap::from_sphere(center, radius);
        // A C caller's fit may hold anything: a pivot that `valid_pivot` returns as it is
        // (finite, `|r_p| ≤ 1 − 2⁻²⁰`: every fit of `from_view`,
        // `fitted_pivots_are_valid_as_they_stand`) takes the `VALID_PIVOT` path, which
        // skips making it valid again (the same bits: `valid_pivot` is the identity there,
        // and the clipped path's own test, finite and `|r_p|² < 1`, holds), any other the
        // careful one, out of line (`a_fit_s_pivot_takes_the_valid_path_where_it_is_valid`;
        // issue 18, stop 40: the image's and the clipped path's three `valid_pivot` were
        // about 50 instructions per preparation, measured).
        let prepared = cap.one_minus_cos > 0.0
            && if super::pivot::is_valid_as_it_stands(fit.pivot) {
                self.prepare_sanitized::<true>(&cap, fit.pivot)
            } else {
                self.prepare_sanitized_of_any_pivot(&cap, fit.pivot)
            };
        if !prepared {
            *self = Self::EMPTY;
        }
        prepared
    }

    /// [`prepare_sanitized`](Self::prepare_sanitized) of a pivot that may not be valid
    /// (`VALID_PIVOT = false`), out of line and cold: [`prepare_with_fit`](Self::prepare_with_fit)
    /// of a pivot that no fit gives.
    #[inline(never)]
    #[cold]
    fn prepare_sanitized_of_any_pivot(&mut self, cap: &Cap, pivot: Vec3) -> bool {
        self.prepare_sanitized::<false>(cap, pivot)
    }

    /// Prepares sampling of a cap with an explicit pivot (any uniform SPTD). `None` for
    /// an empty cap or one wholly below the horizon.
    pub fn with_pivot(cap: &Cap, pivot: Vec3) -> Option<SphereLightSampler> {
        let mut sampler = Self::EMPTY;
        sampler.prepare_with_pivot(cap, pivot).then_some(sampler)
    }

    /// [`SphereLightSampler::with_pivot`] written in place into `self`; `false` and
    /// [`SphereLightSampler::EMPTY`] written where `with_pivot` gives `None`.
    pub fn prepare_with_pivot(&mut self, cap: &Cap, pivot: Vec3) -> bool {
        let prepared = self.prepare_unchecked(cap, pivot);
        if !prepared {
            *self = Self::EMPTY;
        }
        prepared
    }

    /// The body of [`SphereLightSampler::prepare_with_pivot`], which leaves `self` partly
    /// written when it returns `false`.
    fn prepare_unchecked(&mut self, cap: &Cap, pivot: Vec3) -> bool {
        self.prepare_sanitized::<false>(&cap.sanitized(), pivot)
    }

    /// [`prepare_unchecked`](Self::prepare_unchecked) of a cap that `sanitized` returns as
    /// it is: the caps of spheres (`Cap::from_sphere`; tested by
    /// `cap_tests::sanitized_keeps_valid_caps_and_is_idempotent`), which `prepare` does not
    /// sanitize again (the same bits). `VALID_PIVOT`: the pivot is valid as it stands
    /// (`valid_pivot` returns it bit for bit: `prepare`'s fitted pivots), so that it is
    /// not made valid again (a length, a square root and six finiteness tests).
    #[inline(always)]
    fn prepare_sanitized<const VALID_PIVOT: bool>(&mut self, cap: &Cap, pivot: Vec3) -> bool {
        // (`cap` read where it lies, not copied: with the clipped region's preparation in
        // line, the copy became a 16-byte and an 8-byte load of a cap stored field by
        // field, which the store buffer cannot forward; issue 18, stop 45: `sptd_fit`
        // 247 -> 227 ns per prepare + 1, and 6 instructions fewer.)
        if !(cap.one_minus_cos > 0.0) {
            return false;
        }
        // Wholly above the horizon: the angle of the axis from the zenith plus the
        // half-angle at most π/2, i.e. cos ≥ sin for a cap up to a hemisphere.
        let above =
            cap.one_minus_cos <= 1.0 && cap.axis.z >= 0.0 && cap.axis.z * cap.axis.z >= cap.sin2;
        if !above {
            return self.prepare_clipped_to_the_horizon::<VALID_PIVOT>(cap, pivot);
        }
        let sptd = if VALID_PIVOT {
            Sptd::uniform_of_valid(pivot)
        } else {
            Sptd::uniform(pivot)
        };
        // (`cap` is sanitized: not again.)
        let prepared = if VALID_PIVOT {
            self.sptd.prepare_sanitized_in_line(&sptd, cap)
        } else {
            self.sptd.prepare_sanitized(&sptd, cap)
        };
        let uses_sptd = prepared && self.sptd.image.solid_angle() >= MIN_PIVOTED_SOLID_ANGLE;
        // The pivot at the origin gives J = 1: the uniform distribution in the cap,
        // sampled directly below (its image, the antipodal cap, in closed form).
        if !uses_sptd && !self.sptd.prepare_uniform_of_zero_pivot(cap) {
            return false;
        }
        self.clipped_region = CapIntersection::EMPTY;
        self.light = Cap::EMPTY;
        self.pivot = Vec3::ZERO;
        self.pivot_numerators = [1.0; 2];
        self.uses_sptd = uses_sptd as u32;
        self.clipped = 0;
        true
    }

    /// The sampler of a cap that crosses the horizon: the SPTD over `C ∩ H` through the
    /// images' intersection, or uniform in `C ∩ H` where that image is below 1e-3 sr.
    /// Always inlined (5 instructions per preparation, measured).
    #[inline(always)]
    fn prepare_clipped_to_the_horizon<const VALID_PIVOT: bool>(
        &mut self,
        cap: &Cap,
        pivot: Vec3,
    ) -> bool {
        let horizon = UPPER_HEMISPHERE;
        // (A valid pivot is finite and shorter than 1.)
        let valid_pivot = VALID_PIVOT || (pivot.is_finite() && pivot.length_squared() < 1.0);
        // (The closed form `reduced_image` takes the pivot as it is, or leaves it to the
        // careful `pivot_cap`, which makes it valid.)
        let pivoted = |c: &Cap| pivot_cap_fast(c, pivot);
        // The image of the upper hemisphere in closed form (`pivot_upper_hemisphere`: one
        // square root and a division for the points' form's six of each, and more
        // accurate), of the pivot made valid (as `pivot_cap_fast` makes it).
        let horizon_image = || {
            super::pivot::pivot_upper_hemisphere(if VALID_PIVOT {
                pivot
            } else {
                super::pivot::valid_pivot(pivot)
            })
        };
        let uses_sptd = valid_pivot
            // The images are valid caps as `pivot_cap_fast` and `pivot_upper_hemisphere`
            // build them (tested by `the_sampler_s_pivoted_images_are_valid_caps` and
            // `the_upper_hemisphere_s_image_in_closed_form`): not sanitized again.
            && self.clipped_region.prepare_sanitized_inlined(pivoted(cap).0, horizon_image())
            && self.clipped_region.solid_angle() >= MIN_PIVOTED_SOLID_ANGLE;
        if !uses_sptd && !self.clipped_region.prepare_sanitized(cap, &horizon) {
            return false;
        }
        self.sptd = SptdInCap::EMPTY;
        self.light = *cap;
        // Made valid once here rather than per sample (the same bits: the transformation
        // and the Jacobian made the same pivot valid at every call).
        let pivot = if uses_sptd && VALID_PIVOT {
            pivot
        } else if uses_sptd {
            super::pivot::valid_pivot(pivot)
        } else {
            Vec3::ZERO
        };
        self.pivot = pivot;
        self.pivot_numerators = if uses_sptd {
            pivot_numerators(pivot)
        } else {
            [1.0; 2]
        };
        self.uses_sptd = uses_sptd as u32;
        self.clipped = 1;
        true
    }

    /// The density of the clipped sampler at `dir`: `J(ω)/Ω(g(C) ∩ g(H))` (or
    /// `1/Ω(C ∩ H)`) in `C ∩ H`, 0 elsewhere.
    ///
    /// Always inlined, with `unit`'s normalisation out of line: `unit` returns a `dir`
    /// that passes `is_unit` as it is (every sample of the sampler, whose directions are
    /// normalised), so that the test alone stays on the sample's path, where the compiler
    /// also drops the tests that `sample` made already (`Ω ≥ MIN_NORMALISER` implies
    /// `Ω > 0`; `uses_sptd` is decided once). Out of line, the call and its spills were
    /// 10 instructions per clipped sample (callgrind, light bench `sptd`: 815.5 -> 805.4
    /// per clipped sample).
    #[inline(always)]
    fn clipped_pdf(&self, dir: Vec3) -> f32 {
        if crate::math::is_unit(dir) {
            self.clipped_pdf_of_unit(dir)
        } else {
            self.clipped_pdf_of_non_unit(dir)
        }
    }

    /// [`clipped_pdf`](Self::clipped_pdf) of a `dir` that `is_unit` rejects: normalised by
    /// `unit` first (which changes neither the sign of `z` nor the containment test, which
    /// normalises `dir` the same way); 0 for a zero or non-finite `dir`. Out of line and
    /// cold: no sample takes it.
    #[inline(never)]
    #[cold]
    fn clipped_pdf_of_non_unit(&self, dir: Vec3) -> f32 {
        match crate::math::unit(dir) {
            Some(dir) => self.clipped_pdf_of_unit(dir),
            None => 0.0,
        }
    }

    /// [`clipped_pdf`](Self::clipped_pdf) of a unit `dir`, with the pivot made valid in
    /// `prepare` (it was made valid at every call) and the Jacobian's numerator prepared.
    #[inline(always)]
    fn clipped_pdf_of_unit(&self, dir: Vec3) -> f32 {
        if !(self.light.contains_unit(dir) && dir.z >= 0.0) {
            return 0.0;
        }
        let area = self.clipped_region.solid_angle();
        if !(area > 0.0) {
            return 0.0;
        }
        // A struct corrupted through C may hold any pivot and numerator: the Jacobian is
        // then finite, infinite or NaN, and the last two give 0 below.
        let jacobian = if self.uses_sptd() {
            jacobian_of_numerator(dir, self.pivot, self.pivot_numerators[1])
        } else {
            1.0
        };
        let pdf = jacobian / area;
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// Draws a direction in the light's cap (above the horizon); `pdf(sample.dir) ==
    /// sample.pdf` bit for bit (MIS relies on it). Samples that rounding puts just
    /// outside the cap are dropped (`Sample::NONE`), as [`SptdInCap::sample`] drops
    /// them; for uniform sampling (found by fuzzing: `u` next to 1 put the direction on
    /// the rim, where the cap's containment test said outside).
    #[inline]
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        if self.is_clipped() {
            // The region's direction without its uniform pdf `1/Ω` (a division per sample
            // that only the test for no sample used): `Ω ≥ MIN_NORMALISER` is that test
            // (`Ω > 0` with `1/Ω` finite) without the division, also for a struct
            // corrupted through C (`the_clipped_sample_skips_the_uniform_pdf`).
            if !(self.clipped_region.solid_angle() >= MIN_NORMALISER) {
                return Sample::NONE;
            }
            // The region's direction without its test of containment in `g(C) ∩ g(H)`:
            // `g` maps that region onto `C ∩ H`, which `clipped_pdf` tests (a direction
            // with a density is a sample whatever side of the images' boundaries rounding
            // put its preimage). Only a direction that fails it goes the region's way, its
            // test and its pulls towards the inside (`sample_clipped_pulled`). (Issue 18:
            // the region's test was 35 instructions per clipped sample, light bench `sptd`,
            // where no draw failed it.)
            let base = self.clipped_region.sample_direction_unchecked(u);
            let dir = self.clipped_image(base);
            let pdf = self.clipped_pdf(dir);
            if pdf > 0.0 {
                return Sample { dir, pdf };
            }
            return self.sample_clipped_pulled(u);
        }
        if self.uses_sptd() {
            // The sampler's SPTD is always uniform (`prepare_sanitized`); a struct corrupted
            // through C may say otherwise, and takes `sample` then.
            if self.sptd.sptd.base == SptdBase::Uniform {
                self.sptd.sample_uniform_base(u)
            } else {
                self.sptd.sample(u)
            }
        } else {
            let s = self.sptd.cap.sample_uniform(u);
            Sample::new_or_none(s.dir, self.sptd.cap.pdf(s.dir))
        }
    }

    /// The direction of the clipped sampler for a direction `base` of its region: `g(ω)`
    /// for the SPTD, `ω` for the uniform fallback. `base` is unit (normalised by the
    /// region's sampler) and the pivot valid (prepared): `transform` is `pivot_transform`
    /// without their checks (here with its numerator prepared, `transform_of_numerator`),
    /// and its result is unit again.
    #[inline(always)]
    fn clipped_image(&self, base: Vec3) -> Vec3 {
        if self.uses_sptd() {
            transform_of_numerator(base, self.pivot, self.pivot_numerators[0])
        } else {
            base
        }
    }

    /// The clipped sample of a draw whose first direction has no density (rounding put it
    /// outside `C ∩ H`): the region's own sample, its direction tested in `g(C) ∩ g(H)`
    /// and pulled inside where it is not (`CapIntersection::sample_direction`), then its
    /// image and density (`clipped_pdf`, which `pdf` calls: the same bits by
    /// construction, also for a struct corrupted through C whose sample is not unit).
    /// Out of line and cold: no draw of the light bench takes it.
    #[cold]
    #[inline(never)]
    fn sample_clipped_pulled(&self, u: [f32; 2]) -> Sample {
        let Some(base) = self.clipped_region.sample_direction(u) else {
            return Sample::NONE;
        };
        let dir = self.clipped_image(base);
        Sample::new_or_none(dir, self.clipped_pdf(dir))
    }

    /// The density of [`SphereLightSampler::sample`] at `dir`: 0 outside the cap (and,
    /// for a cap that crosses the horizon, below the horizon).
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        if self.is_clipped() {
            return self.clipped_pdf(dir);
        }
        if self.uses_sptd() {
            self.sptd.pdf(dir)
        } else {
            self.sptd.cap.pdf(dir)
        }
    }
}

#[cfg(test)]
#[path = "light_tests.rs"]
mod tests;
