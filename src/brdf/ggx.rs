//! The GGX (Trowbridge–Reitz) microfacet BRDF with the height-correlated Smith
//! masking-shadowing term and Schlick's Fresnel approximation, and sampling of the
//! distribution of visible normals (Heitz 2018, "Sampling the GGX Distribution of
//! Visible Normals", in the spherical-cap form of Dupuy and Benyoub 2023, "Sampling
//! Visible GGX Normals with Spherical Caps").
//!
//! # The model
//!
//! Roughness `r ∈ [0, 1]` gives `α = r²` (clamped to [`MIN_ALPHA`]). For a unit
//! microfacet normal `h` with `h.z = cos θh > 0`,
//!
//! ```text
//! D(h) = α² / (π (cos²θh (α² - 1) + 1)²) = α² / (π (hx² + hy² + α² hz²)²),
//! ```
//!
//! the second form being the first with `1 - cos²θh = hx² + hy²`, which keeps full
//! relative precision at the peak `h ≈ z` where `1 - cos²θh` would cancel. Smith's
//! auxiliary function of a direction `ω` with `a = α² tan²θ` is
//!
//! ```text
//! Λ(ω) = (-1 + √(1 + a)) / 2 = a / (2 (1 + √(1 + a))),
//! ```
//!
//! the second form without the cancellation of the first for small `a` (note the
//! factor 2: `a / (1 + √(1 + a))` would be `2Λ`). [`GgxBrdf::lambda`] evaluates it as
//! `α² sin²θ / (2 cos θ (R + cos θ))`, which also avoids the overflow of `tan²θ`. With
//! `R(ω) = √(ωz² + α² (ωx² + ωy²)) = ωz √(1 + a)` (for unit `ω` above the horizon) the
//! masking and height-correlated masking-shadowing functions become
//!
//! ```text
//! G1(ω)      = 1 / (1 + Λ(ω))              = 2 ωz / (ωz + R(ω)),
//! G2(ωo, ωi) = 1 / (1 + Λ(ωo) + Λ(ωi))     = 2 ωo,z ωi,z / (ωi,z R(ωo) + ωo,z R(ωi)),
//! ```
//!
//! which need neither `tan θ` nor `a` and so stay finite and accurate at grazing angles,
//! where `tan²θ` overflows. The BRDF with the half vector `h = (ωo + ωi) / |ωo + ωi|`,
//! Schlick's `F = F0 + (1 - F0)(1 - ωo·h)⁵` and the terms above is
//!
//! ```text
//! f(ωo, ωi) = F D G2 / (4 ωo,z ωi,z) = F D / (2 (ωi,z R(ωo) + ωo,z R(ωi))),
//! ```
//!
//! and 0 when either cosine is `<= 0`. The last form cancels `ωo,z ωi,z` analytically,
//! so it stays finite when one direction grazes the horizon.
//!
//! # Sampling visible normals
//!
//! The density of normals visible from `ωo` is
//! `D_ωo(h) = G1(ωo) max(0, ωo·h) D(h) / ωo,z`. It integrates to 1 over the hemisphere
//! of `h`: the projected area of the visible microfacets is that of the macrosurface,
//! `∫ G1(ωo) max(0, ωo·h) D(h) dh = ωo,z`.
//! Heitz's observation: GGX with roughness `α` is the distribution of normals of the
//! ellipsoid with semi-axes `(1/α, 1/α, 1)`, the image of the unit hemisphere under
//! `M = diag(1/α, 1/α, 1)`. Normals transform with `M⁻ᵀ`: the hemisphere normal
//! `n` becomes `normalize(α nx, α ny, nz)`, and the view direction `ωo` seen from the
//! hemisphere's side is `M⁻¹ ωo = (α ωo,x, α ωo,y, ωo,z)`. A visible normal is the
//! normal at the point hit by a ray along `-ωo` through a uniform point of the
//! surface's orthographic projection, and a linear map keeps projections uniform. So:
//!
//! 1. stretch: `v = normalize(α ωo,x, α ωo,y, ωo,z)`;
//! 2. (Dupuy and Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps") the
//!    view `v` reflected on the visible normals of a unit sphere is uniform over the
//!    sphere (a mirror ball reflects uniformly), and on the normals of the upper
//!    hemisphere (`h_z >= 0`) it is uniform in the spherical cap `{c : c_z >= -v_z}`,
//!    with `h = normalize(v + c)`: draw `c` uniformly in that cap, `c_z = 1 - w` with
//!    `w = u1 (1 + v_z)` and the azimuth `2π u0`;
//! 3. `n = v + c` (its length does not matter: step 4 normalises). This replaces
//!    Heitz's construction (a basis `t1, t2` of the plane orthogonal to `v`, a
//!    concentric disk point moved onto the projected hemisphere, and a lift along `v`)
//!    by one square root and a sine and cosine, with the same distribution;
//! 4. unstretch: `h = normalize(α n.x, α n.y, max(0, n.z))`;
//! 5. reflect: `ωi = 2 (ωo·h) h - ωo`.
//!
//! The reflection has Jacobian `|dh / dωi| = 1 / (4 ωo·h)`, so the density of `ωi` is
//! `D_ωo(h) / (4 ωo·h) = G1(ωo) D(h) / (4 ωo,z) = D(h) / (2 (ωo,z + R(ωo)))`, finite
//! even at `ωo,z → 0`. Reflected directions at or below the horizon are returned as
//! [`Sample::NONE`]: **the density then integrates to less than 1 over the upper
//! hemisphere**; the lost mass is the probability of reflecting below the horizon. An
//! estimator counts such a draw as a sample of contribution 0; callers must not
//! renormalise the pdf (that would bias every estimate by the lost mass).
//!
//! # Precision
//!
//! `f` and the pdf are evaluated to a few 1e-6 relative of the f64 values at the
//! directions they are given, for every `α` down to [`MIN_ALPHA`] and every view (the
//! tests check this). They are, however, ill-conditioned in the directions for narrow lobes and
//! grazing views, where the half vector comes from the short sum `ωo + ωi` and the lobe
//! is steep: perturbing `ωo` by one `f32` rounding (~3e-8) moves them by ~1e-5 at
//! `α = 0.01` and 80°, and by ~2e-4 at 89°. References must therefore see exactly the
//! `f32` directions the library sees. A direction whose `|ω|²` lies within 1e-6 of 1
//! is taken as it is, without normalising it again.
//!
//! Hard cases, each tested below or in `ggx_tests.rs`: `α` from [`MIN_ALPHA`] to 1,
//! views at 0°, 45°, 80° and 89° and at `ωo,z = 1e-30`; reflected directions below the
//! horizon (about half of them at `α = 1`); `ωi = ωo`, `ωi = -ωo` and both directions
//! grazing; `u` at both ends of `[0, 1)`, outside it and NaN; zero, huge, tiny and
//! non-finite directions; roughness and `F0` outside their ranges and NaN.

use super::{is_unit, unit};
use crate::math::sin_cos_of_turn;
use crate::sample::clamp_random;
use crate::{Sample, Vec3};
use core::f32::consts::FRAC_1_PI;

/// The smallest `α` (roughness `10⁻²`). As `α → 0`, `D` tends to a Dirac delta:
/// its peak `D(z) = 1 / (π α²)` and the pdf near the mirror direction grow like `α⁻²`
/// (and `α⁻³` for grazing views), and `α²` squared underflows `f32` below
/// `α ≈ 3e-10`. Well before that, the lobe becomes too narrow for `f32` directions: at
/// `α = 1e-4` it is only ~2000 direction ulps (`6e-8` rad) wide, so moving a direction
/// by one ulp changes `f` and the pdf by up to ~1e-3 relative. Both are still
/// evaluated to ~1e-6 at the direction they are given (the tests check this), but
/// anything that rounds directions (a quadrature, a renderer's frame transforms) sees
/// that much noise, and for smaller `α` the lobe is a matter of rounding. Renderers
/// treat smoother surfaces as perfect mirrors (a delta BRDF), which this module does
/// not model.
pub const MIN_ALPHA: f32 = 1e-4;

/// The GGX microfacet BRDF: the Trowbridge–Reitz normal distribution with
/// `α = roughness²`, height-correlated Smith masking-shadowing, and Schlick's Fresnel
/// with the reflectance `F0` at normal incidence per RGB channel.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GgxBrdf {
    /// `α = roughness²`, from the smallest `α` (`MIN_ALPHA`, `SPHERA_GGX_MIN_ALPHA` in
    /// C) to 1.
    pub(crate) alpha: f32,
    /// Schlick's `F0` per channel, in `[0, 1]`.
    pub(crate) f0: Vec3,
}

impl Default for GgxBrdf {
    fn default() -> Self {
        Self::new(0.5, Vec3::splat(0.04))
    }
}

/// `x` clamped to `[0, 1]`, NaN to 0.
#[inline(always)]
fn clamp_unit(x: f32) -> f32 {
    x.max(0.0).min(1.0)
}

impl GgxBrdf {
    /// The BRDF with perceptual roughness `roughness` (`α = roughness²`) and Fresnel
    /// reflectance `f0` at normal incidence. `roughness` is clamped to `[0, 1]` and
    /// `α` to `[MIN_ALPHA, 1]`; a NaN roughness counts as the smoothest one
    /// (`α = MIN_ALPHA`). Each channel of `f0` is clamped to `[0, 1]` (NaN to 0).
    pub fn new(roughness: f32, f0: Vec3) -> GgxBrdf {
        let r = clamp_unit(roughness);
        Self::from_alpha(r * r, f0)
    }

    /// The BRDF with `α` given directly (clamped to `[MIN_ALPHA, 1]`, NaN to
    /// `MIN_ALPHA`) and `f0` as in [`new`](Self::new).
    pub fn from_alpha(alpha: f32, f0: Vec3) -> GgxBrdf {
        GgxBrdf {
            alpha: alpha.max(MIN_ALPHA).min(1.0),
            f0: Vec3::new(clamp_unit(f0.x), clamp_unit(f0.y), clamp_unit(f0.z)),
        }
    }

    /// `α`, in `[MIN_ALPHA, 1]`.
    #[inline]
    pub fn alpha(&self) -> f32 {
        self.alpha
    }

    /// Schlick's `F0` per channel.
    #[inline]
    pub fn f0(&self) -> Vec3 {
        self.f0
    }

    /// `R(ω) = √(ωz² + α² (ωx² + ωy²))` of a unit direction: `ωz √(1 + α² tan²θ)`.
    #[inline(always)]
    fn r(&self, w: Vec3) -> f32 {
        let a2 = self.alpha * self.alpha;
        crate::math::sqrtf(w.z * w.z + a2 * (w.x * w.x + w.y * w.y))
    }

    /// `D(h)` of a unit `h` with `h.z > 0`.
    #[inline(always)]
    fn d_unit(&self, h: Vec3) -> f32 {
        let a2 = self.alpha * self.alpha;
        let s = h.x * h.x + h.y * h.y + a2 * (h.z * h.z);
        a2 * FRAC_1_PI / (s * s)
    }

    /// The normal distribution `D(h) = α² / (π (cos²θh (α² - 1) + 1)²)` per steradian
    /// (normalised by `∫ D(h) cos θh dh = 1`), 0 for `h` at or below the horizon. `h`
    /// is normalised first; zero or non-finite `h` gives 0.
    #[inline]
    pub fn d(&self, h: Vec3) -> f32 {
        match unit(h) {
            Some(h) if h.z > 0.0 => self.d_unit(h),
            _ => 0.0,
        }
    }

    /// Smith's `Λ = (-1 + √(1 + α² tan²θ)) / 2` at `cos θ = c = cos_theta`. With
    /// `s² = (1 - c)(1 + c)` (exact where `1 - c²` would cancel) and
    /// `R = √(c² + α² s²) = c √(1 + α² tan²θ)`,
    /// `Λ = (R - c) / (2c) = α² s² / (2c (R + c))`: no cancellation near the normal
    /// (where `Λ ≈ α² tan²θ / 4` is tiny) and no overflow of `tan²θ` near the horizon
    /// (where `Λ ≈ α tan θ / 2`). `cos_theta` above 1 counts as 1. At and below the
    /// horizon (`cos_theta <= 0`, or NaN), and where `Λ` exceeds `f32::MAX` (`c` below
    /// ~1e-39 α), `Λ` is infinite; this returns `f32::MAX` instead, so that
    /// `1 / (1 + Λ)` is 0 to within 3e-39 and no infinity leaves the library.
    #[inline]
    pub fn lambda(&self, cos_theta: f32) -> f32 {
        if !(cos_theta > 0.0) {
            return f32::MAX;
        }
        let c = cos_theta.min(1.0);
        let a2 = self.alpha * self.alpha;
        let s2 = (1.0 - c) * (1.0 + c);
        let r = crate::math::sqrtf(c * c + a2 * s2);
        let lambda = a2 * s2 / (2.0 * c * (r + c));
        if lambda.is_finite() { lambda } else { f32::MAX }
    }

    /// Smith's masking function `G1(ω) = 1 / (1 + Λ(ω)) = 2 ωz / (ωz + R(ω))` of the
    /// direction `w` (normalised first); 0 at or below the horizon and for zero or
    /// non-finite `w`.
    #[inline]
    pub fn g1(&self, w: Vec3) -> f32 {
        match unit(w) {
            Some(w) if w.z > 0.0 => 2.0 * w.z / (w.z + self.r(w)),
            _ => 0.0,
        }
    }

    /// The height-correlated masking-shadowing function
    /// `G2 = 1 / (1 + Λ(ωo) + Λ(ωi)) = 2 ωo,z ωi,z / (ωi,z R(ωo) + ωo,z R(ωi))`
    /// (directions normalised first); 0 when either lies at or below the horizon or is
    /// zero or non-finite.
    #[inline]
    pub fn g2(&self, wo: Vec3, wi: Vec3) -> f32 {
        match (unit(wo), unit(wi)) {
            (Some(wo), Some(wi)) if wo.z > 0.0 && wi.z > 0.0 => {
                let g2 = 2.0 * wo.z * wi.z / (wi.z * self.r(wo) + wo.z * self.r(wi));
                if g2.is_finite() { g2.min(1.0) } else { 0.0 }
            }
            _ => 0.0,
        }
    }

    /// `D(h) / (2 (ωi,z R(ωo) + ωo,z R(ωi)))` and `ωo·h` for unit directions above the
    /// horizon: the BRDF without Fresnel, and the cosine Fresnel needs. `None` where
    /// the value is not finite (both directions grazing within ~1e-38).
    #[inline(always)]
    fn eval_unit(&self, wo: Vec3, wi: Vec3) -> Option<(f32, f32)> {
        let s = wo + wi;
        let (d, length2) = self.d_of_sum(s)?;
        let f = d / (2.0 * (wi.z * self.r(wo) + wo.z * self.r(wi)));
        // ωo·h = ωi·h = (1 + ωo·ωi) / |s| = |s| / 2 for unit directions, as
        // |s|² = 2 (1 + ωo·ωi): no normalisation of s, and exactly symmetric.
        let cos_d = 0.5 * crate::math::sqrtf(length2);
        f.is_finite().then_some((f, cos_d))
    }

    /// `D(h)` for the half vector `h = s / |s|` of `s = ωo + ωi` (unit directions above
    /// the horizon), and `|s|²`. `D` depends on `h` only through
    /// `h_x² + h_y² + α² h_z² = (s_x² + s_y² + α² s_z²) / |s|²`, so
    /// `D(h) = α² |s|⁴ / (π (s_x² + s_y² + α² s_z²)²)` needs neither the square root nor
    /// the division of normalising `s` (issue 18, 4). Only where `|s|²` is below 1e-20
    /// (both directions grazing and nearly opposite), whose squares could underflow, is
    /// `s` normalised first; `None` where it cannot be.
    #[inline(always)]
    fn d_of_sum(&self, s: Vec3) -> Option<(f32, f32)> {
        let (xy2, z2) = (s.x * s.x + s.y * s.y, s.z * s.z);
        let length2 = xy2 + z2;
        let d = if length2 > 1e-20 {
            let a2 = self.alpha * self.alpha;
            // 1 / (h_x² + h_y² + α² h_z²) for the unit h along s.
            let inverse = length2 / (xy2 + a2 * z2);
            a2 * FRAC_1_PI * (inverse * inverse)
        } else {
            self.d_unit(unit(s)?)
        };
        Some((d, length2))
    }

    /// The BRDF `f(ωo, ωi) = F D G2 / (4 ωo,z ωi,z)` per channel (without the cosine
    /// `ωi,z`). 0 when either direction lies at or below the horizon, is zero or is not
    /// finite, and on the measure-zero set where both graze the horizon so closely that
    /// `f` overflows `f32`. Directions are normalised first. Exactly symmetric in
    /// `(wo, wi)`.
    #[inline]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.with_fresnel(self.eval_checked(wo, wi))
    }

    /// [`eval`](Self::eval) for a view `wo` that [`unit`] takes as it is
    /// ([`is_unit`]`(wo)`) and that lies above the horizon, and an `wi` already passed
    /// through [`unit`] (`None`: zero or non-finite): the same value bit for bit
    /// (`eval`'s `unit(wo)` returns `wo` itself, and its `wo.z > 0` holds), without the
    /// view's normalisation test, for a caller that stores the view normalised once (a
    /// prepared polygon light) and has the direction's `unit` already.
    #[inline(always)]
    pub(crate) fn eval_from_unit_view(&self, wo: Vec3, wi: Option<Vec3>) -> Vec3 {
        self.with_fresnel(
            wi.filter(|wi| wi.z > 0.0)
                .and_then(|wi| self.eval_unit(wo, wi)),
        )
    }

    /// Schlick's Fresnel times the BRDF without it, from [`eval_unit`](Self::eval_unit)'s
    /// `(f, ωo·h)`; 0 for `None`.
    #[inline(always)]
    fn with_fresnel(&self, checked: Option<(f32, f32)>) -> Vec3 {
        match checked {
            Some((f, cos_d)) => {
                let m = clamp_unit(1.0 - cos_d);
                let m2 = m * m;
                let schlick = m2 * m2 * m;
                (self.f0 + (Vec3::ONE - self.f0) * schlick) * f
            }
            None => Vec3::ZERO,
        }
    }

    /// `D G2 / (4 ωo,z ωi,z)`: [`eval`](Self::eval) with `F = 1`.
    #[inline]
    pub fn eval_without_fresnel(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_checked(wo, wi).map_or(0.0, |(f, _)| f)
    }

    #[inline(always)]
    fn eval_checked(&self, wo: Vec3, wi: Vec3) -> Option<(f32, f32)> {
        let (wo, wi) = (unit(wo)?, unit(wi)?);
        if !(wo.z > 0.0 && wi.z > 0.0) {
            return None;
        }
        self.eval_unit(wo, wi)
    }

    /// A normal `h` distributed with the density of visible normals `D_ωo(h)` (steps
    /// 1–4 of the module documentation, Dupuy and Benyoub 2023) for a unit `wo` with
    /// `wo.z > 0`. `u` is clamped to `[0, 1 - ulp]` (NaN counts as 0).
    #[inline(always)]
    pub(crate) fn sample_visible_normal(&self, wo: Vec3, u: [f32; 2]) -> Vec3 {
        let alpha = self.alpha;
        let (u0, u1) = (clamp_random(u[0]), clamp_random(u[1]));
        // 1. The view seen from the hemisphere configuration. Its squared length lies in
        //    [α², 1] for a unit `wo` (α >= MIN_ALPHA): plain normalisation neither
        //    underflows nor overflows.
        let stretched = Vec3::new(alpha * wo.x, alpha * wo.y, wo.z);
        let v = stretched * (1.0 / crate::math::sqrtf(stretched.length_squared()));
        // 2. c uniform in the spherical cap {c : c_z >= -v_z}: c_z = 1 - w with
        //    w = u1 (1 + v_z) uniform in [0, 1 + v_z], and sin²θ = (1 - c_z)(1 + c_z)
        //    = w (2 - w) without the cancellation of 1 - c_z² near the pole.
        let w = u1 * (1.0 + v.z);
        let sin_theta = crate::math::sqrtf((w * (2.0 - w)).max(0.0));
        let (sin_phi, cos_phi) = sin_cos_of_turn(u0);
        // 3. The hemisphere's visible normal v + c (not normalised: step 4 normalises).
        let n = Vec3::new(
            v.x + sin_theta * cos_phi,
            v.y + sin_theta * sin_phi,
            v.z + (1.0 - w),
        );
        // 4. Unstretch: normals transform with the inverse transpose. `n` is short only
        //    next to the cap's rim opposite `v` (`unit` then rescales it first).
        unit(Vec3::new(alpha * n.x, alpha * n.y, n.z.max(0.0))).unwrap_or(Vec3::Z)
    }

    /// `D(h) / (2 (ωo,z + R(ωo)))` with `h = normalize(ωo + ωi)` for unit directions
    /// above the horizon: the density of [`sample`](Self::sample), with `D(h)` from
    /// the unnormalised sum ([`d_of_sum`](Self::d_of_sum)).
    #[inline(always)]
    fn pdf_unit(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some((d, _)) = self.d_of_sum(wo + wi) else {
            return 0.0;
        };
        let pdf = d / (2.0 * (wo.z + self.r(wo)));
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// Draws `ωi` by sampling a visible normal `h` (Heitz 2018; Dupuy and Benyoub 2023)
    /// and reflecting `wo` on it; the pdf is `D_ωo(h) / (4 ωo·h) = G1(ωo) D(h) / (4 ωo,z)` per steradian,
    /// identical to [`pdf`](Self::pdf) of the returned direction.
    ///
    /// Returns [`Sample::NONE`] when the reflected direction lies at or below the
    /// horizon (the density then integrates to less than one: count the draw as a
    /// zero contribution, do not renormalise), when `wo` lies at or below the horizon,
    /// and when `wo` is zero or not finite. `wo` is normalised first; `u` is clamped to
    /// `[0, 1 - ulp]` (NaN counts as 0).
    #[inline]
    pub fn sample(&self, wo: Vec3, u: [f32; 2]) -> Sample {
        let Some(wo) = unit(wo) else {
            return Sample::NONE;
        };
        if !(wo.z > 0.0) {
            return Sample::NONE;
        }
        let h = self.sample_visible_normal(wo, u);
        let reflected = h * (2.0 * wo.dot(h)) - wo;
        let Some(wi) = unit(reflected) else {
            return Sample::NONE;
        };
        if !(wi.z > 0.0) {
            return Sample::NONE;
        }
        let pdf = self.pdf_unit(wo, wi);
        if pdf > 0.0 {
            Sample { dir: wi, pdf }
        } else {
            Sample::NONE
        }
    }

    /// The density per steradian with which [`sample`](Self::sample) draws `wi` given
    /// `wo`: `G1(ωo) D(h) / (4 ωo,z)` with `h = normalize(ωo + ωi)`. 0 when either
    /// direction lies at or below the horizon, is zero or is not finite. Directions
    /// are normalised first.
    ///
    /// The common case, both directions unit ([`is_unit`]) and above the horizon, runs
    /// inline: [`unit`] returns such a direction unchanged, so this is the
    /// same value, bit for bit, without the normalisation's branches. Everything else
    /// (directions to normalise, zero, non-finite, at or below the horizon) goes to
    /// the out-of-line [`pdf_careful`](Self::pdf_careful).
    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if is_unit(wo) && is_unit(wi) && wo.z > 0.0 && wi.z > 0.0 {
            return self.pdf_unit(wo, wi);
        }
        Self::pdf_careful(self, wo, wi)
    }

    /// [`pdf`](Self::pdf) for every input: the directions normalised by [`unit`] first.
    /// The C calling convention keeps the directions in vector registers (the Rust one
    /// passes a `Vec3` in integer registers or through memory, which cost the inline
    /// common path its shuffles and stores).
    #[inline(never)]
    #[cold]
    extern "C" fn pdf_careful(&self, wo: Vec3, wi: Vec3) -> f32 {
        match (unit(wo), unit(wi)) {
            (Some(wo), Some(wi)) if wo.z > 0.0 && wi.z > 0.0 => self.pdf_unit(wo, wi),
            _ => 0.0,
        }
    }
}

#[cfg(test)]
#[path = "ggx_tests.rs"]
mod tests;
