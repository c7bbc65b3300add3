//! Spherical pivot-transformed distributions (SPTDs; Dupuy, Heitz and Belcour 2017,
//! Section 4).
//!
//! An SPTD is the distribution of `ω = g(ω_i)` for `ω_i` drawn from a base distribution
//! `D_std` and `g` the pivot transformation of a pivot `r_p` (`|r_p| < 1`). Its density
//! (Eq. 8) is the base density at the preimage times the Jacobian of Eq. 4:
//!
//! `D(ω) = D_std(g(ω)) J(ω)`, `J(ω) = ((1 − |r_p|²) / |ω − r_p|²)²`,
//!
//! with `|ω − ρ n|² = ρ |ω − n|² + (1 − ρ)²` for `r_p = ρ n` (expand `ω − n + (1 − ρ) n`
//! and use `2 (ω − n)·n = −|ω − n|²`), a sum of non-negative terms that keeps `J`
//! accurate as `ρ → 1`.
//!
//! Because `g` is an involution that maps caps to caps ([`pivot_cap`]), the integral of
//! `D` over a cap `C` is the integral of the base over the image cap (Eq. 10), and over
//! an intersection of caps, the integral of the base over the intersection of the
//! images (Eq. 11, `g(A ∩ B) = g(A) ∩ g(B)` for a bijection); over a union, the
//! paper's algebra `∫_A + ∫_B − ∫_{A ∩ B}`, and over a complement, the integral over
//! the complement of the image (`g(Ā)` is the complement of `g(A)`, a cap; both bases
//! integrate to 1 over the sphere, so it is `1 − ∫_A D`). Sampling `D` inside `C`
//! draws `ω_i` from the base restricted to `g(C)` and returns `g(ω_i)`, with density
//! `D(ω) / ∫_C D` ([`SptdInCap`]).
//!
//! Two bases:
//!
//! - **uniform**, `D_std = 1/4π` (Eq. 16, the paper's choice for GGX): `∫_C D =
//!   Ω(g(C))/4π`, exact through the cap's stored `1 − cos`; sampling is uniform cap
//!   sampling of `g(C)`;
//! - **clamped cosine** about a unit axis `a`, `D_std = max(0, ω·a)/π`: its integral
//!   over a cap is the irradiance of a cap clipped to the hemisphere of `a`, in closed
//!   form ([`clamped_cosine_over_cap`]), and over an intersection of caps, the
//!   boundary integral `∫_R ω dω = ½ ∮_∂R ω × dω` over the arcs of the caps' circles
//!   that bound `R = A ∩ B ∩ H_a` ([`clamped_cosine_over_caps`]). Sampling inside a cap
//!   is exact for every cap with a positive integral, by Nusselt's analogue: the
//!   orthographic projection `P` onto the plane `⊥ a` maps `H_a` onto the unit disk
//!   with `dA = (ω·a) dω`, so a point uniform in `P(g(C) ∩ H_a)` (of area `A`) lifts to
//!   a direction of density `ω·a / A` there, the normalised clamped cosine
//!   (`A = ∫_{g(C)} max(0, ω·a) dω = π ∫_C D`). When `g(C)` lies in the hemisphere of `a`
//!   its projection is an ellipse (density `ω·a / (π sin²θ cos β)`). When `g(C)`
//!   crosses the horizon of `a` (or is wider than a hemisphere), `P(g(C) ∩ H_a)` is
//!   bounded by an arc of that ellipse and an arc of the unit circle, which it touches
//!   where the cap's circle meets the horizon: the disk up to the chord through those
//!   points and the ellipse beyond it when the cap's axis is above the horizon, the
//!   disk without the ellipse up to the chord when it is below ([`SptdInCap::new`]).
//!   Its area, a sum of circular and elliptic segments, is the closed form's `E`
//!   term by term; sampling inverts it along the ellipse's axis by a safeguarded
//!   Newton iteration (at most 40 steps) and draws the offset across uniformly.
//!
//! Hard cases (tested): pivots from the origin (where `g` is the antipodal map) to
//! `|r_p| = 0.9999` (the fitted GGX table reaches `1 − 3.3e-5`), caps containing the
//! pivot's direction (images wider than a hemisphere), tiny caps (1e-6 sr), caps
//! straddling the base's horizon (images just crossing it, mostly above or below it,
//! with the axis on it, tiny ones, wider than a hemisphere with or without a hole),
//! the whole sphere, the empty cap, caps that coincide or are complementary.

use super::cap::{Cap, sample_uniform_in_frame};
use super::cap_intersection::cap_intersection_solid_angle;
use super::cap_intersection_sampling::{MAX_ITERATIONS, MIN_NORMALISER};
use super::pivot::{pivot_cap, pivot_cap_fast, transform, valid_pivot};
use crate::Sample;
use crate::math::orthonormal_basis;
use crate::sample::{ONE_MINUS_ULP, clamp_inverted, clamp_random};
use core::f32::consts::{FRAC_1_PI, PI, TAU};
use glam::Vec3;

const INV_4PI: f32 = 0.25 * FRAC_1_PI;

/// The smallest side `1 − cos θ` of a cap whose zero-pivot image is taken in closed form
/// ([`SptdInCap::prepare_uniform_of_zero_pivot`]): far (a factor 1e8) above the sides
/// whose `∫ = Ω/4π` has no finite inverse.
const ANTIPODAL_MIN_SIDE: f32 = 1e-30;

/// The base distribution that the pivot transforms.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SptdBase {
    /// `D_std = 1/4π` over the sphere (Eq. 16).
    Uniform = 0,
    /// `D_std = max(0, ω·a)/π` about the SPTD's `cosine_axis`.
    ClampedCosine = 1,
}

impl SptdBase {
    /// The base with number `n` (0 uniform, 1 clamped cosine), `None` otherwise.
    pub fn from_u32(n: u32) -> Option<SptdBase> {
        match n {
            0 => Some(SptdBase::Uniform),
            1 => Some(SptdBase::ClampedCosine),
            _ => None,
        }
    }
}

/// A spherical pivot-transformed distribution (Eq. 8): a base distribution and a
/// pivot. Build it with [`Sptd::uniform`] or [`Sptd::clamped_cosine`], which make the
/// pivot valid (non-finite → origin, `|r_p|` clamped below 1).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sptd {
    /// The pivot `r_p`, `|r_p| ≤ 1 − 2⁻²⁰`.
    pub pivot: Vec3,
    /// The unit axis `a` of the clamped-cosine base (`z` for the uniform base).
    pub cosine_axis: Vec3,
    /// Which base distribution.
    pub base: SptdBase,
}

/// `J(ω) = ((1 − ρ²) / |ω − r_p|²)²` with `|ω − r_p|² = ρ |ω − n|² + (1 − ρ)²` (see
/// the module documentation), for a unit `dir` and a valid pivot.
#[inline(always)]
fn jacobian(dir: Vec3, pivot: Vec3) -> f32 {
    let rho = crate::math::length(pivot);
    let distance2 = if rho > 0.0 {
        let one_minus_rho = 1.0 - rho;
        rho * (dir - pivot / rho).length_squared() + one_minus_rho * one_minus_rho
    } else {
        1.0
    };
    let ratio = (1.0 - rho) * (1.0 + rho) / distance2;
    ratio * ratio
}

/// A cosine-distributed direction about the unit `axis` (density `ω·a/π`), from a
/// uniform point of the unit disk (polar map).
#[inline(always)]
fn sample_cosine(axis: Vec3, u: [f32; 2]) -> Vec3 {
    let r2 = clamp_random(u[0]);
    let r = crate::math::sqrtf(r2);
    let (sin_phi, cos_phi) = crate::math::sin_cos_of_turn(clamp_random(u[1]));
    let (t, b) = orthonormal_basis(axis);
    crate::math::normalize_or(
        t * (r * cos_phi) + b * (r * sin_phi) + axis * crate::math::sqrtf((1.0 - r2).max(0.0)),
        axis,
    )
}

impl Sptd {
    /// The SPTD of the uniform base with pivot `pivot`.
    pub fn uniform(pivot: Vec3) -> Sptd {
        Sptd {
            pivot: valid_pivot(pivot),
            cosine_axis: Vec3::Z,
            base: SptdBase::Uniform,
        }
    }

    /// [`Sptd::uniform`] of a pivot that is valid already (`valid_pivot` returns it as
    /// it is: the fitted GGX pivots of `GgxPivot::from_view`,
    /// `light_tests::fitted_pivots_are_valid_as_they_stand`): the same value without
    /// making it valid again.
    #[inline(always)]
    pub(crate) fn uniform_of_valid(pivot: Vec3) -> Sptd {
        Sptd {
            pivot,
            cosine_axis: Vec3::Z,
            base: SptdBase::Uniform,
        }
    }

    /// The SPTD of the clamped-cosine base about `axis` (normalised here; a zero or
    /// non-finite axis becomes `z`) with pivot `pivot`.
    pub fn clamped_cosine(pivot: Vec3, axis: Vec3) -> Sptd {
        // Scaled by the largest component before normalising: an axis of 2e-21 has a
        // denormal |a|², whose rounding left |a| = 1.00006 and integrals above 1
        // (found by fuzzing). `normalize_scaled` gives 0 for zero or non-finite axes.
        let axis = crate::math::normalize_scaled(axis);
        let axis = if axis == Vec3::ZERO { Vec3::Z } else { axis };
        Sptd {
            pivot: valid_pivot(pivot),
            cosine_axis: axis,
            base: SptdBase::ClampedCosine,
        }
    }

    /// The base density `D_std(ω_i)` at a unit direction.
    #[inline]
    pub fn base_density(&self, dir: Vec3) -> f32 {
        match self.base {
            SptdBase::Uniform => INV_4PI,
            SptdBase::ClampedCosine => dir.dot(self.cosine_axis).max(0.0) * FRAC_1_PI,
        }
    }

    /// The density `D(ω) = D_std(g(ω)) J(ω)` (Eq. 8) at `dir` (normalised here); 0 for a
    /// zero or non-finite `dir`.
    pub fn eval(&self, dir: Vec3) -> f32 {
        // The shared helper: `dir / |dir|` overflowed or underflowed for lengths of 2¹⁰⁰
        // and 2⁻¹⁰⁰ (issue 17, 5).
        let Some(dir) = crate::math::unit(dir) else {
            return 0.0;
        };
        self.base_density(transform(dir, self.pivot)) * jacobian(dir, self.pivot)
    }

    /// Draws `ω = g(ω_i)` with `ω_i` from the base over the whole sphere; the pdf is
    /// [`Sptd::eval`] at the returned direction, bit for bit (Section 4.2, importance
    /// sampling). Computed from `ω_i` instead, `D_std(ω_i)` differs from `D_std(g(ω))`
    /// by the rounding of the round trip `g(g(ω_i))`, which the Jacobian amplifies for
    /// pivots near the unit sphere (found by fuzzing: 0.1–13% for the clamped cosine).
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        let base = match self.base {
            SptdBase::Uniform => Cap::WHOLE_SPHERE.sample_uniform(u).dir,
            SptdBase::ClampedCosine => sample_cosine(self.cosine_axis, u),
        };
        let dir = transform(base, self.pivot);
        let pdf = self.eval(dir);
        if pdf > 0.0 && pdf.is_finite() {
            Sample { dir, pdf }
        } else {
            Sample::NONE
        }
    }

    /// The integral of the base density over a cap (of base directions).
    fn base_integral_over_cap(&self, image: &Cap) -> f32 {
        match self.base {
            SptdBase::Uniform => image.solid_angle() * INV_4PI,
            SptdBase::ClampedCosine => clamped_cosine_over_cap(image, self.cosine_axis) * FRAC_1_PI,
        }
    }

    /// `∫_C D(ω) dω = ∫_{g(C)} D_std` (Eq. 10), in `[0, 1]`. The cap is sanitized first.
    pub fn integral_over_cap(&self, cap: &Cap) -> f32 {
        let image = pivot_cap(&cap.sanitized(), self.pivot);
        self.base_integral_over_cap(&image).max(0.0).min(1.0)
    }

    /// `∫_{A ∩ B} D(ω) dω = ∫_{g(A) ∩ g(B)} D_std` (Eq. 11), in `[0, 1]`: the exact
    /// two-cap solid angle for the uniform base, the boundary integral over
    /// `g(A) ∩ g(B) ∩ H_a` for the clamped cosine. The caps are sanitized first.
    pub fn integral_over_cap_intersection(&self, a: &Cap, b: &Cap) -> f32 {
        let image_a = pivot_cap(&a.sanitized(), self.pivot);
        let image_b = pivot_cap(&b.sanitized(), self.pivot);
        let integral = match self.base {
            SptdBase::Uniform => cap_intersection_solid_angle(&image_a, &image_b) * INV_4PI,
            SptdBase::ClampedCosine => {
                clamped_cosine_over_caps(&image_a, &image_b, self.cosine_axis) * FRAC_1_PI
            }
        };
        integral.max(0.0).min(1.0)
    }

    /// `∫_{A ∪ B} D(ω) dω = ∫_{g(A) ∪ g(B)} D_std` (Eq. 11; `g` is a bijection, so
    /// `g(A ∪ B) = g(A) ∪ g(B)`), in `[0, 1]`, by the paper's algebra
    /// `∫_A + ∫_B − ∫_{A ∩ B}` with the exact integrals over the images. The difference
    /// does not lose relative precision: the union is at least the larger of `∫_A` and
    /// `∫_B`, so the rounding of the three terms is a few ulps of the result (the form
    /// `∫_A + ∫_{B ∩ Ā}` that [`CapUnion`](super::CapUnion) samples would take the
    /// complement of a small `g(A)` as a cap wider than a hemisphere, whose boundary
    /// arcs against a small `g(B)` keep only `ulp(2)`). Disjoint, nested, identical and
    /// complementary caps and caps wider than a hemisphere need no special case. The
    /// caps are sanitized first; an empty cap is the empty set (the union is the other
    /// cap), but a malformed one (non-finite or zero axis, NaN `one_minus_cos`:
    /// [`Cap::is_malformed`]) is an error, reported as 0.
    pub fn integral_over_cap_union(&self, a: &Cap, b: &Cap) -> f32 {
        if a.is_malformed() || b.is_malformed() {
            return 0.0;
        }
        let image_a = pivot_cap(&a.sanitized(), self.pivot);
        let image_b = pivot_cap(&b.sanitized(), self.pivot);
        let (in_a, in_b, in_both) = match self.base {
            SptdBase::Uniform => (
                image_a.solid_angle() * INV_4PI,
                image_b.solid_angle() * INV_4PI,
                cap_intersection_solid_angle(&image_a, &image_b) * INV_4PI,
            ),
            SptdBase::ClampedCosine => (
                clamped_cosine_over_cap(&image_a, self.cosine_axis) * FRAC_1_PI,
                clamped_cosine_over_cap(&image_b, self.cosine_axis) * FRAC_1_PI,
                clamped_cosine_over_caps(&image_a, &image_b, self.cosine_axis) * FRAC_1_PI,
            ),
        };
        let (in_a, in_b) = (in_a.max(0.0), in_b.max(0.0));
        // Rounding keeps the union between the larger piece and the sum.
        (in_a + in_b - in_both.max(0.0).min(in_a.min(in_b)))
            .max(in_a.max(in_b))
            .min(1.0)
    }

    /// `∫_{Ā} D(ω) dω = ∫_{comp g(A)} D_std` (Eq. 11 with `g(Ā) = comp g(A)`), in
    /// `[0, 1]`. Both bases are normalised over the sphere (Eq. 9: the uniform
    /// `1/4π` over `S²`, the clamped cosine `max(0, ω·a)/π` over its hemisphere, which
    /// is all of its support), so this is `1 − ∫_A D`; it is computed directly over the
    /// complement cap (which keeps `1 ∓ cos` exact), so a cap that leaves only a tiny
    /// hole keeps the hole's integral to full relative precision, where `1 − ∫_A D`
    /// would keep only `ulp(1)`. The cap is sanitized first: the complement of the
    /// empty cap is the whole sphere (1); a malformed cap ([`Cap::is_malformed`]) is an
    /// error, reported as 0.
    pub fn integral_over_cap_complement(&self, cap: &Cap) -> f32 {
        if cap.is_malformed() {
            return 0.0;
        }
        let image = pivot_cap(&cap.sanitized(), self.pivot).complement();
        self.base_integral_over_cap(&image).max(0.0).min(1.0)
    }
}

/// `∫_C max(0, ω·a) dω` for a cap `C` (axis `c`, half-angle `θ`) and a unit `a`: the
/// irradiance that a cap of unit radiance gives a surface of normal `a`.
///
/// From the boundary integral `∫_R ω dω = ½ ∮ ω × dω` over `R = C ∩ H_a`: with
/// `cos β = c·a` and `s = √max(0, sin²θ − cos²β)` (the two circles cross iff
/// `s > 0`), the arc of the cap's circle above the horizon spans `2(π − φ₀)` with
/// `φ₀ = atan2(s, cos θ cos β)` and contributes `sin²θ cos β (π − φ₀) − s cos θ`, and
/// the arc of the horizon inside the cap spans `2ψ₀` with `ψ₀ = atan2(s, cos θ)` and
/// contributes `ψ₀`:
///
/// `E = sin²θ cos β (π − φ₀) − s cos θ + ψ₀`.
///
/// The same expression covers the cases without crossing (`s = 0`): the cap above the
/// horizon (`π sin²θ cos β`), below it (0), a cap wider than a hemisphere that contains
/// the upper hemisphere (π) or the lower one (`π + π sin²θ cos β`). A cap straddling
/// the horizon loses relative precision when `E ≪ θ` (about `θ³`): terms of size `θ`
/// cancel.
pub fn clamped_cosine_over_cap(cap: &Cap, a: Vec3) -> f32 {
    if !(cap.one_minus_cos > 0.0) {
        return 0.0;
    }
    let cos_beta = cap.axis.dot(a).max(-1.0).min(1.0);
    let cos = cap.cos();
    let s = crate::math::sqrtf((cap.sin2 - cos_beta * cos_beta).max(0.0));
    let phi0 = libm::atan2f(s, cos * cos_beta);
    let psi0 = libm::atan2f(s, cos);
    let e = cap.sin2 * cos_beta * (PI - phi0) - s * cos + psi0;
    e.max(0.0).min(PI)
}

/// The area of the part of the unit disk within depth `w ∈ [0, 2]` of a point `e` of
/// its rim, `{p : p·e ≥ 1 − w}` (a circular segment; π/2 at `w = 1`, π at 2):
/// `α − sin α cos α` with `cos α = 1 − w`, i.e. `(γ − sin γ)/2` for `γ = 2α`, with
/// `tan(α/2) = √w / √(2 − w)`. Its derivative is the chord, `2 √(w (2 − w))`. The
/// smaller of the segment and its complement is evaluated (`2 − w` is exact for
/// `w ∈ [1, 2]`), by the Taylor series of `γ − sin γ` for `γ < 1.2`, where the
/// difference would cancel (small segments have area `(4√2/3) w^{3/2}`).
fn segment(w: f32) -> f32 {
    let w = w.max(0.0).min(2.0);
    let small = w.min(2.0 - w);
    let gamma = 4.0 * libm::atan2f(crate::math::sqrtf(small), crate::math::sqrtf(2.0 - small));
    let g2 = gamma * gamma;
    let half = if gamma < 1.2 {
        // γ − sin γ = γ³/3! − γ⁵/5! + … in Horner form; the first term left out is
        // below 1e-8 of the sum.
        let series = 1.0
            - g2 / 20.0
                * (1.0 - g2 / 42.0 * (1.0 - g2 / 72.0 * (1.0 - g2 / 110.0 * (1.0 - g2 / 156.0))));
        gamma * g2 * (1.0 / 12.0) * series
    } else {
        0.5 * (gamma - libm::sinf(gamma))
    };
    if w > 1.0 { PI - half } else { half }
}

/// A circular interval `[start, start + length]` of azimuths, `length ∈ [0, 2π]`.
#[derive(Clone, Copy)]
struct Arc {
    start: f32,
    length: f32,
}

impl Arc {
    const FULL: Arc = Arc {
        start: 0.0,
        length: TAU,
    };
}

/// Whether the circles of two caps coincide: `Some(true)` for the same cap (to `1e-6`
/// of the circle's size `min(1 − cos, 1 + cos)` in `1 − cos`), `Some(false)` for
/// complementary caps (the same circle bounding opposite sides, to `1e-6` in
/// `1 − cos`), `None` otherwise. The first tolerance is relative: an absolute `1e-6`
/// took two caps of 1e-8 sr whose centres are half a radius apart for the same cap
/// (their `1 − cos` are 1.6e-9), and their intersection for the whole of one (issue 20,
/// 1: the SPTD over a union of tiny caps). The second stays absolute: for nearly
/// antipodal axes `arc_inside` forms `K` with `t_d` near 2, which keeps only `ulp(2)`.
fn same_circle(p: &Cap, q: &Cap) -> Option<bool> {
    const TOLERANCE: f32 = 1e-6;
    let tolerance = TOLERANCE * p.one_minus_cos.min(p.one_plus_cos);
    let t_d = 0.5 * (p.axis - q.axis).length_squared();
    if t_d <= tolerance && (p.one_minus_cos - q.one_minus_cos).abs() <= tolerance {
        Some(true)
    } else if t_d >= 2.0 - TOLERANCE && (p.one_minus_cos - q.one_plus_cos).abs() <= TOLERANCE {
        Some(false)
    } else {
        None
    }
}

/// The azimuths of the circle of cap `i` (in the frame `t, b` around its axis) that lie
/// in cap `j`: `None` when none do, an arc otherwise (the full circle included).
///
/// A point `ω(φ) = cos θᵢ cᵢ + sin θᵢ (cos φ t + sin φ b)` lies in `j` iff
/// `A cos(φ − ψ) ≥ K` with `A cos ψ = sin θᵢ (t·cⱼ)`, `A sin ψ = sin θᵢ (b·cⱼ)` and
/// `K = cos θⱼ − cos θᵢ (cᵢ·cⱼ) = tᵢ + t_d − tⱼ − tᵢ t_d` (the `t = 1 − cos` forms, as
/// in the two-cap intersection, so that tiny caps do not cancel; see [`crossing_k`]).
fn arc_inside(ci: &Cap, t: Vec3, b: Vec3, sin_i: f32, cj: &Cap) -> Option<Arc> {
    if cj.one_minus_cos >= 2.0 {
        return Some(Arc::FULL);
    }
    let t_d = (0.5 * (ci.axis - cj.axis).length_squared()).min(2.0);
    let k = crossing_k(ci, cj, t_d);
    let x = sin_i * t.dot(cj.axis);
    let y = sin_i * b.dot(cj.axis);
    let a = crate::math::sqrtf(x * x + y * y);
    if k <= -a {
        return Some(Arc::FULL);
    }
    if !(k < a) {
        return None;
    }
    // `√(A² − K²)` is the same for both circles (`|cᵢ·(cⱼ × P)|` at a crossing point
    // `P`); from the smaller cap's side it has no cancellation (for a small cap against
    // the horizon, `A² − K² = sin²θᵢ sin²d − K²` subtracts numbers near 1 while
    // `sin²θⱼ sin²d − Kⱼ² = sin²θⱼ − cos²d` does not).
    let sin2_d = t_d * (2.0 - t_d);
    let y2 = if cj.one_minus_cos < ci.one_minus_cos {
        let kj = crossing_k(cj, ci, t_d);
        cj.sin2 * sin2_d - kj * kj
    } else {
        (a - k) * (a + k)
    };
    let psi = libm::atan2f(y, x);
    let half = libm::atan2f(crate::math::sqrtf(y2.max(0.0)), k);
    let mut start = psi - half;
    if start < 0.0 {
        start += TAU;
    }
    Some(Arc {
        start,
        length: 2.0 * half,
    })
}

/// `K = cos θⱼ − cos θᵢ cos d` for `t_d = 1 − cos d`: `tᵢ + t_d − tⱼ − tᵢ t_d`, except
/// when both caps are wider than a hemisphere, where `tᵢ − tⱼ` would keep only `ulp(2)`
/// of two small holes and `cos θⱼ − cos θᵢ = hⱼ − hᵢ` with the stored `h = 1 + cos θ`
/// (issue 17, 6): `K = (hⱼ − hᵢ) + t_d cos θᵢ`.
#[inline(always)]
fn crossing_k(ci: &Cap, cj: &Cap, t_d: f32) -> f32 {
    if ci.one_minus_cos > 1.0 && cj.one_minus_cos > 1.0 {
        (cj.one_plus_cos - ci.one_plus_cos) + t_d * ci.cos()
    } else {
        ci.one_minus_cos + t_d - cj.one_minus_cos - ci.one_minus_cos * t_d
    }
}

/// The intersection of two circular arcs: up to two arcs.
fn intersect_arcs(p: Arc, q: Arc) -> [Option<Arc>; 2] {
    let mut d = q.start - p.start;
    if d < 0.0 {
        d += TAU;
    }
    let first = (d < p.length).then(|| Arc {
        start: p.start + d,
        length: (p.length.min(d + q.length) - d).max(0.0),
    });
    let wrap = d + q.length - TAU;
    let second = (wrap > 0.0).then(|| Arc {
        start: p.start,
        length: wrap.min(p.length),
    });
    [first, second]
}

/// `∫_{A ∩ B ∩ H_a} ω·a dω` for two valid caps and a unit `a`, as `a · ½ ∮ ω × dω` over
/// the boundary of the region, which consists of the arcs of the three circles (of
/// `A`, `B` and the hemisphere `H_a`) that lie inside the other two caps, each
/// traversed counterclockwise about its own axis (the region on its left). Over the
/// arc `φ ∈ [φ₁, φ₂]` of a circle with axis `c` and half-angle `θ`,
/// `∫ ω × dω = sin²θ c (φ₂ − φ₁) − sin θ cos θ (t (sin φ₂ − sin φ₁) − b (cos φ₂ − cos φ₁))`.
/// This identity (`∫_R n dA = ½ ∮ r × dr`) holds for any region, so caps wider than a
/// hemisphere and regions that are not simply connected need no special case. A cap
/// whose circle coincides with another's is handled apart (see `same_circle`).
///
/// The position `r = ω − p` is taken from a point `p` near the region, the axis of the
/// smallest of the three caps (`∮ p × dω = 0` on a closed boundary, so the value is
/// the same): with `p = 0` a crossing point that the two circles through it place
/// `δ` apart (each from its own arc angles) costs `|ω × δ| ≈ δ`, which for two
/// overlapping caps of 1e-8 sr (radius 5.6e-5, region ~1e-9 sr) was 35% of the
/// region (issue 20, 1); from `p` it costs `|ω − p| δ`, of the order of the region's
/// radius times `δ`. Over an arc, with `ω = cos θ c + sin θ e(φ)` and
/// `q = cos θ c − p`: `∫ (ω − p) × dω = sin²θ c Δφ + sin θ q × (e(φ₂) − e(φ₁))`, with
/// `e(φ₂) − e(φ₁) = 2 sin(Δφ/2) (−sin φ_m t + cos φ_m b)` at the arc's middle `φ_m`
/// (no cancellation for short arcs) and `q = (c − p) − (1 − cos θ) c` for caps up to
/// a hemisphere (small when `c` is near `p`).
pub fn clamped_cosine_over_caps(a_cap: &Cap, b_cap: &Cap, a: Vec3) -> f32 {
    if !(a_cap.one_minus_cos > 0.0) || !(b_cap.one_minus_cos > 0.0) {
        return 0.0;
    }
    let horizon = Cap::from_axis_one_minus_cos(a, 1.0);
    let caps = [*a_cap, *b_cap, horizon];
    // The horizon's `1 − cos` is 1, so the smallest cap is at most a hemisphere.
    let mut origin = horizon.axis;
    let mut smallest = horizon.one_minus_cos;
    for c in [a_cap, b_cap] {
        if c.one_minus_cos < smallest {
            smallest = c.one_minus_cos;
            origin = c.axis;
        }
    }
    let mut total = Vec3::ZERO;
    for (i, ci) in caps.iter().enumerate() {
        let ci = *ci;
        if ci.one_minus_cos >= 2.0 {
            continue; // the whole sphere has no boundary
        }
        let (t, b) = orthonormal_basis(ci.axis);
        let sin_i = crate::math::sqrtf(ci.sin2.max(0.0));
        let cos_i = ci.cos();
        // The arcs of circle i inside every other cap: at most two after the first
        // intersection of two arcs, and the intersection of two arcs has at most two
        // pieces; four slots leave room for rounding at the seams.
        let mut arcs: [Option<Arc>; 4] = [Some(Arc::FULL), None, None, None];
        for (j, cj) in caps.iter().enumerate() {
            if j == i {
                continue;
            }
            // A circle shared with another cap: the same cap bounds the region once
            // (by its first copy), complementary caps leave a region of measure zero.
            let inside = match same_circle(&ci, cj) {
                Some(true) if j > i => Some(Arc::FULL),
                Some(_) => None,
                None => arc_inside(&ci, t, b, sin_i, cj),
            };
            let Some(inside) = inside else {
                arcs = [None; 4];
                break;
            };
            let mut next = [None; 4];
            let mut n = 0;
            for arc in arcs.iter().flatten() {
                let pieces = if arc.length >= TAU {
                    [Some(inside), None]
                } else {
                    intersect_arcs(*arc, inside)
                };
                for piece in pieces.into_iter().flatten() {
                    if n < 4 && piece.length > 0.0 {
                        next[n] = Some(piece);
                        n += 1;
                    }
                }
            }
            arcs = next;
        }
        let q = if ci.one_minus_cos <= 1.0 {
            (ci.axis - origin) - ci.axis * ci.one_minus_cos
        } else {
            ci.axis * cos_i - origin
        };
        for arc in arcs.iter().flatten() {
            let half = 0.5 * arc.length;
            let (sin_m, cos_m) = libm::sincosf(arc.start + half);
            let chord = (b * cos_m - t * sin_m) * (2.0 * libm::sinf(half));
            total += ci.axis * (ci.sin2 * arc.length) + q.cross(chord) * sin_i;
        }
    }
    (0.5 * total.dot(a)).max(0.0).min(PI)
}

/// An SPTD restricted to a cap `C` and normalised there: a prepared sampler
/// (Section 4.2, importance sampling over spherical caps). Samples are
/// `ω = g(ω_i)` with `ω_i` drawn from the base inside `g(C)`; the density is
/// `D(ω) / ∫_C D` inside `C` and 0 outside. For the uniform base it is
/// `J(ω) / Ω(g(C))`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SptdInCap {
    /// The distribution.
    pub sptd: Sptd,
    /// The cap `C` (sanitized).
    pub cap: Cap,
    /// Its image `g(C)`.
    pub image: Cap,
    /// `∫_C D = ∫_{g(C)} D_std`.
    pub integral: f32,
    /// For the clamped-cosine base: `(x, y, z)` = the projected ellipse's center offset
    /// `cos θ sin β`, its semi-axes `sin θ cos β` (along `e1`) and `sin θ`. For the
    /// uniform base: the bitangent of the image's frame (see `e1`).
    ellipse: Vec3,
    /// For the clamped-cosine base: unit tangent of the base axis pointing to the image
    /// cap's axis (any unit tangent when the two axes coincide to rounding: the ellipse is
    /// then a circle). For the uniform base: the tangent of the image's frame
    /// `orthonormal_basis(image.axis)`, with `ellipse` its bitangent, prepared once for
    /// the image's uniform samples (`Cap::sample_uniform` built it per sample).
    e1: Vec3,
    /// For the clamped-cosine base: 1 when `g(C)` does not lie in the hemisphere of `a`
    /// and is sampled over the projection of `g(C) ∩ H_a` (see [`SptdInCap::new`]),
    /// else 0.
    clipped: u32,
    /// For a clipped sampler, depths `h = 1 − x` measured along `e1` from the rim point
    /// `e1` of the unit disk: of the chord where the projected ellipse touches the unit
    /// circle (`1 − cos θ / sin β`; 2 when the circles do not cross), else 0.
    chord_depth: f32,
    /// For a clipped sampler, the depth of the ellipse's vertex nearest the rim,
    /// `1 − cos θ sin β − sin θ |cos β|`, else 0.
    tip_depth: f32,
}

impl SptdInCap {
    /// The SPTD in the empty cap: no samples, pdf 0 everywhere, integral 0.
    ///
    /// cbindgen:ignore
    pub const EMPTY: SptdInCap = SptdInCap {
        sptd: Sptd {
            pivot: Vec3::ZERO,
            cosine_axis: Vec3::Z,
            base: SptdBase::Uniform,
        },
        cap: Cap::EMPTY,
        image: Cap::EMPTY,
        integral: 0.0,
        ellipse: Vec3::ZERO,
        e1: Vec3::X,
        clipped: 0,
        chord_depth: 0.0,
        tip_depth: 0.0,
    };

    /// Prepares `sptd` restricted to `cap` (sanitized). `None` when `∫_C D` is 0 or its
    /// inverse is not finite.
    ///
    /// For the clamped-cosine base the base directions are drawn in `R = g(C) ∩ H_a`
    /// through its orthographic projection onto the plane `⊥ a` (the module
    /// documentation; Eq. 10 and the paper's "importance sampling over sets of
    /// spherical caps" with the set `g(C) ∩ H_a`). In the frame `e1` (towards the image
    /// axis `c`), `e2`, `a`, with `cos β = c·a`, `sin β ≥ 0`, the cap's circle
    /// `ω·c = cos θ` projects to the ellipse of centre `x₀ = cos θ sin β`, semi-axes
    /// `a_x = sin θ |cos β|` along `e1` and `a_y = sin θ`, inside the unit disk and
    /// touching the unit circle at `x_c = cos θ / sin β` (where the circle meets the
    /// horizon, `s² = sin²θ − cos²β > 0`). A vertical line through a point of the disk
    /// meets the sphere at `±z`, and the plane `ω·c = cos θ` separates the two iff the
    /// point is inside the ellipse; with `x sin β + z cos β ≥ cos θ`:
    ///
    /// - `cos β ≥ 0`: `P(R) = (E ∩ {x ≤ x_c}) ∪ (D ∩ {x ≥ x_c})`,
    /// - `cos β < 0`: `P(R) = (D ∖ E) ∩ {x ≥ x_c}`,
    ///
    /// (without crossing, a cap wider than a hemisphere gives `D` or `D ∖ E`: the chord
    /// at `x = −1`). In depths `h = 1 − x` from the rim point `e1` (small caps near the
    /// horizon keep their precision), with `S(w) = α − sin α cos α`, `cos α = 1 − w`,
    /// the unit disk's segment of depth `w` (`segment`), the area at depths `≤ h` is
    ///
    /// `A(h) = S(min(h, h_c)) + a_x a_y [S(η(max(h, h_c))) − S(η(h_c))]` (`cos β ≥ 0`),
    /// `A(h) = S(min(h, h_c)) − a_x a_y S(η(min(h, h_c)))` (`cos β < 0`),
    ///
    /// `η` the normalised depth in the ellipse. At the far end it equals the closed form
    /// of [`clamped_cosine_over_cap`] term by term (`x_c = cos ψ₀`, `(x_c − x₀)/a_x =
    /// cos φ₀`). Sampling solves `A(h) = u₀ A` (`dA/dh` is twice the strip's half-width,
    /// Newton's method in a bisection bracket), draws the offset `y` uniformly across
    /// the strip at `h` (one interval, or two symmetric ones around the ellipse), and
    /// lifts the point: `z = √(h (2 − h) − y²)`. The density of `ω = g(ω_i)` is then
    /// `(ω_i·a / A) J(ω)`, i.e. `D(ω) / ∫_C D` with `∫_C D = A/π` (stored in
    /// `integral`), 0 where `g(ω)` is below the horizon.
    pub fn new(sptd: &Sptd, cap: &Cap) -> Option<SptdInCap> {
        let mut prepared = SptdInCap::EMPTY;
        prepared.prepare(sptd, cap).then_some(prepared)
    }

    /// [`SptdInCap::new`] written in place into `self` (no copy of the prepared value);
    /// `false` and [`SptdInCap::EMPTY`] written where `new` gives `None`.
    pub fn prepare(&mut self, sptd: &Sptd, cap: &Cap) -> bool {
        let prepared = self.prepare_unchecked(sptd, cap);
        if !prepared {
            *self = SptdInCap::EMPTY;
        }
        prepared
    }

    /// The body of [`SptdInCap::prepare`], which leaves `self` partly written when it
    /// returns `false`.
    #[inline(always)]
    fn prepare_unchecked(&mut self, sptd: &Sptd, cap: &Cap) -> bool {
        self.prepare_sanitized_unchecked(sptd, &cap.sanitized())
    }

    /// [`SptdInCap::prepare`] of a cap that is valid already (`cap.sanitized()` returns it
    /// as it is: every constructor's cap), without sanitizing it again: the same bits,
    /// for a caller that sanitized it (the sphere light sampler).
    pub(crate) fn prepare_sanitized(&mut self, sptd: &Sptd, cap: &Cap) -> bool {
        self.prepare_sanitized_in_line(sptd, cap)
    }

    /// [`SptdInCap::prepare_sanitized`] always inlined: the sphere light sampler's call
    /// for its fitted pivots, the common case (the other pivots call `prepare_sanitized`
    /// out of line). The same bits.
    #[inline(always)]
    pub(crate) fn prepare_sanitized_in_line(&mut self, sptd: &Sptd, cap: &Cap) -> bool {
        let prepared = self.prepare_sanitized_unchecked(sptd, cap);
        if !prepared {
            *self = SptdInCap::EMPTY;
        }
        prepared
    }

    /// [`SptdInCap::prepare_sanitized`] of the zero pivot, `Sptd::uniform_of_valid(Vec3::ZERO)`
    /// (the sphere light sampler's fallback: `g(ω) = −ω` and `J = 1`, the uniform
    /// distribution in the cap), with the image in closed form: the antipodal cap (axis
    /// `−c`, the same sides), which `g` maps the cap onto exactly. `pivot_cap_fast` found
    /// the zero pivot on the axis line and took the careful `pivot_cap` (three `atan2f`, a
    /// `sincosf` and a `sinf`: about 550 instructions per fallback, issue 18, stop 45),
    /// whose image is that cap to a few ulps; its closed form (`reduced_image`, stop 48)
    /// takes the zero pivot (`n = a`), with a side within a few ulps of the cap's, but this
    /// copy is cheaper still and exact. The sampler's fallback reads only `cap` and
    /// the result (`SphereLightSampler::sample` and `pdf` sample and evaluate the cap
    /// itself), and the result is the same: with `1 − cos θ ≥ ANTIPODAL_MIN_SIDE`
    /// (1e-30) both images have a side within a few ulps of the cap's (or past a
    /// hemisphere, a side ≥ 1), so `∫_C D = Ω/4π` is in `[2e-31, 1]` for both, positive
    /// with a finite inverse, and both return `true`; below it (where `1/∫` overflows, near
    /// `1 − cos θ = 6e-39`, the ulps of the careful image could decide) the careful path
    /// itself (`the_zero_pivot_s_antipodal_image_prepares_as_the_careful_one`).
    pub(crate) fn prepare_uniform_of_zero_pivot(&mut self, cap: &Cap) -> bool {
        let sptd = Sptd::uniform_of_valid(Vec3::ZERO);
        if !(cap.one_minus_cos >= ANTIPODAL_MIN_SIDE) {
            return self.prepare_sanitized(&sptd, cap);
        }
        let image = Cap {
            axis: -cap.axis,
            ..*cap
        };
        let prepared = self.prepare_of_image(&sptd, *cap, image);
        if !prepared {
            *self = SptdInCap::EMPTY;
        }
        prepared
    }

    /// The body of [`SptdInCap::prepare_sanitized`], which leaves `self` partly written
    /// when it returns `false`.
    #[inline(always)]
    fn prepare_sanitized_unchecked(&mut self, sptd: &Sptd, cap: &Cap) -> bool {
        let cap = *cap;
        // (The closed form of the image, `reduced_image`, where it is well conditioned.)
        let image = pivot_cap_fast(&cap, sptd.pivot).0;
        self.prepare_of_image(sptd, cap, image)
    }

    /// The body of [`SptdInCap::prepare_sanitized_unchecked`] from the image `g(C)`, which
    /// leaves `self` partly written when it returns `false`.
    #[inline(always)]
    fn prepare_of_image(&mut self, sptd: &Sptd, cap: Cap, image: Cap) -> bool {
        // (The uniform base's integral inline: the call was out of line.)
        let integral = match sptd.base {
            SptdBase::Uniform => image.solid_angle() * INV_4PI,
            SptdBase::ClampedCosine => sptd.base_integral_over_cap(&image),
        };
        let integral = integral.max(0.0).min(1.0);
        if !(integral > 0.0) || !(1.0 / integral).is_finite() {
            return false;
        }
        *self = SptdInCap {
            sptd: *sptd,
            cap,
            image,
            integral,
            ellipse: Vec3::ZERO,
            e1: Vec3::X,
            clipped: 0,
            chord_depth: 0.0,
            tip_depth: 0.0,
        };
        let prepared = self;
        if sptd.base == SptdBase::Uniform {
            (prepared.e1, prepared.ellipse) = orthonormal_basis(image.axis);
        }
        if sptd.base == SptdBase::ClampedCosine {
            let a = sptd.cosine_axis;
            let cos_beta = image.axis.dot(a);
            let sin_theta = crate::math::sqrtf(image.sin2.max(0.0));
            // The tangential part of the image's axis in a basis (t, b) of the plane ⊥ a:
            // `c − a (c·a)` is rounding noise, not perpendicular to `a`, when `c` is
            // within ~1e-5 rad of `a` (issue 17, 3: normalised into `e1`, it tilted the
            // ellipse out of the plane; samples bunched and were dropped), while
            // `(c·t, c·b)` has an absolute error of a few ulps and any combination of `t`
            // and `b` is perpendicular to `a`. Where `sin β` is that noise, the ellipse
            // is a circle (semi-axes `sin θ` and `sin θ cos β`, `1 − cos β ≈ sin²β/2`)
            // centred within ulps of `a`, so its orientation does not matter.
            let (t, b) = orthonormal_basis(a);
            let (x, y) = (image.axis.dot(t), image.axis.dot(b));
            let sin_beta = crate::math::sqrtf(x * x + y * y);
            // (Below 1e-18 the squares can be denormal and `sin β` inaccurate.)
            prepared.e1 = if sin_beta > 1e-18 {
                t * (x / sin_beta) + b * (y / sin_beta)
            } else {
                t
            };
            prepared.ellipse = Vec3::new(
                (1.0 - image.one_minus_cos) * sin_beta,
                sin_theta * cos_beta,
                sin_theta,
            );
            // Inside the hemisphere of a: β + θ ≤ π/2, i.e. cos β ≥ sin θ with θ ≤ π/2.
            if image.one_minus_cos <= 1.0 && cos_beta >= sin_theta && cos_beta > 0.0 {
                // The sampling density is ω·a / (π sin²θ cos β): use that normalisation,
                // the closed form's value in this case.
                prepared.integral = image.sin2 * cos_beta;
            } else {
                prepared.prepare_clipped(cos_beta.max(-1.0).min(1.0), sin_beta.min(1.0));
            }
            if !(prepared.integral > 0.0) || !(1.0 / prepared.integral).is_finite() {
                return false;
            }
        }
        true
    }

    /// The clipped sampler's geometry from `cos β = c·a` and `sin β ≥ 0` (`ellipse` and
    /// `e1` already set): the chord and tip depths, and `integral` = the projected area
    /// `A(2)` over π (see [`SptdInCap::new`]).
    fn prepare_clipped(&mut self, cos_beta: f32, sin_beta: f32) {
        let sin_theta = self.ellipse.z;
        let cos_theta = self.image.cos();
        let abs_cos_beta = cos_beta.abs();
        // `s² = sin²θ − cos²β` (> 0 iff the circles cross, as in
        // `clamped_cosine_over_cap`) as a product: for a small cap near the horizon both
        // squares are ~θ².
        let s2 = (sin_theta - abs_cos_beta) * (sin_theta + abs_cos_beta);
        // The crossing points lie on the horizon (`z = 0`) and on the plane
        // `ω·c = cos θ`, so at `x = cos θ / sin β`; for `cos θ ≥ 0` the depth
        // `1 − cos θ / sin β = (sin²β − cos²θ) / (sin β (sin β + cos θ))` with
        // `sin²β − cos²θ = sin²θ − cos²β = s²` keeps small depths to full precision.
        // Without a crossing, the region is the whole disk or the disk without the
        // ellipse (θ > π/2, chord at the far end, depth 2) or empty (θ ≤ π/2, depth 0).
        let chord = if s2 > 0.0 {
            if cos_theta >= 0.0 {
                s2 / (sin_beta * (sin_beta + cos_theta))
            } else {
                1.0 - cos_theta / sin_beta
            }
        } else if cos_theta < 0.0 {
            2.0
        } else {
            0.0
        };
        // The ellipse's centre at depth `1 − cos θ sin β = (1 − cos θ) + cos θ (1 − sin β)`
        // with `1 − sin β = cos²β / (1 + sin β)`; its vertex nearest the rim `sin θ |cos β|`
        // closer (≥ 0: the ellipse lies in the disk).
        let center =
            self.image.one_minus_cos + cos_theta * (cos_beta * cos_beta / (1.0 + sin_beta));
        let tip = center - sin_theta * abs_cos_beta;
        self.clipped = 1;
        // (`max` first: a NaN becomes 0.)
        self.chord_depth = chord.max(0.0).min(2.0);
        self.tip_depth = tip.max(0.0).min(2.0);
        self.integral = self.clipped_cumulative(2.0) * FRAC_1_PI;
    }

    /// The normalised depth `η ∈ [0, 2]` of depth `h` in the projected ellipse (0 at the
    /// vertex nearest the rim, 2 at the far one); 0 or 2 for a degenerate ellipse.
    #[inline(always)]
    fn ellipse_depth(&self, h: f32) -> f32 {
        ((h - self.tip_depth) / self.ellipse.y.abs())
            .max(0.0)
            .min(2.0)
    }

    /// `A(h)`: the area of the clipped region's projection at depths `≤ h` (see
    /// [`SptdInCap::new`]), non-decreasing from 0 to the whole area at `h = 2`.
    fn clipped_cumulative(&self, h: f32) -> f32 {
        // The ellipse is the unit disk scaled by |a_x| along e1 and a_y across, so its
        // part at normalised depth ≤ η has area |a_x| a_y S(η).
        let area = self.ellipse.y.abs() * self.ellipse.z;
        let chord = self.chord_depth;
        let near = h.min(chord);
        let value = if self.ellipse.y >= 0.0 {
            // cos β ≥ 0: the disk up to the chord, then the ellipse beyond it.
            segment(near)
                + area
                    * (segment(self.ellipse_depth(h.max(chord)))
                        - segment(self.ellipse_depth(chord)))
        } else {
            // cos β < 0: the disk without the ellipse, up to the chord.
            segment(near) - area * segment(self.ellipse_depth(near))
        };
        value.max(0.0)
    }

    /// The half-widths `(inner, outer)` across `e1` of the clipped region's projection at
    /// depth `h`: the points `x = 1 − h` with `inner ≤ |y| ≤ outer`. `dA/dh = 2 (outer −
    /// inner)`.
    #[inline]
    fn clipped_strip(&self, h: f32) -> (f32, f32) {
        let circle = crate::math::sqrtf((h * (2.0 - h)).max(0.0));
        let eta = self.ellipse_depth(h);
        let ellipse =
            (self.ellipse.z * crate::math::sqrtf((eta * (2.0 - eta)).max(0.0))).min(circle);
        if self.ellipse.y >= 0.0 {
            (
                0.0,
                if h <= self.chord_depth {
                    circle
                } else {
                    ellipse
                },
            )
        } else if h <= self.chord_depth {
            (ellipse, circle)
        } else {
            (0.0, 0.0)
        }
    }

    /// The depth range of the clipped region: `[0, end]`.
    #[inline]
    fn clipped_end(&self) -> f32 {
        if self.ellipse.y >= 0.0 {
            let far = self.tip_depth + 2.0 * self.ellipse.y;
            far.max(self.chord_depth).max(0.0).min(2.0)
        } else {
            self.chord_depth.max(0.0).min(2.0)
        }
    }

    /// The depth `h` with `A(h) = target`, by Newton's method on `A` (slope `2 (outer −
    /// inner)`) in a bracket, bisecting where a step leaves it: at most
    /// [`MAX_ITERATIONS`] steps.
    fn clipped_depth(&self, target: f32, total: f32) -> f32 {
        let end = self.clipped_end();
        let (mut low, mut high) = (0.0f32, end);
        // Near either end of the range the area grows like a circular segment's,
        // `∝ h^{3/2}` (and so does the rest towards the far end): a start from the
        // approximate inverse of a disk's normalised segment, `q ↦ (2q)^{2/3}` on the
        // near half and its mirror image on the far half (13% off at worst).
        let fraction = (target / total).max(0.0).min(1.0);
        let near = fraction.min(1.0 - fraction);
        let twice = 2.0 * near;
        let w = libm::cbrtf(twice * twice);
        let mut h = 0.5 * end * if fraction <= 0.5 { w } else { 2.0 - w };
        for _ in 0..MAX_ITERATIONS {
            let f = self.clipped_cumulative(h) - target;
            // Within a few ulps of the target, the rounding of `A` (absolute near the
            // far end, where the slope vanishes) would only steer Newton's steps at
            // random.
            if f.abs() <= 5e-7 * target {
                return h.max(0.0).min(end);
            }
            let (inner, outer) = self.clipped_strip(h);
            let slope = 2.0 * (outer - inner);
            let next = crate::math::safeguarded_newton_step(h, f, slope, &mut low, &mut high);
            if (next - h).abs() <= 3e-7 * h.max(1e-30) || !(high > low) {
                return next.max(0.0).min(end);
            }
            h = next;
        }
        h.max(0.0).min(end)
    }

    /// A base direction of the clipped sampler: the depth from `u₀`, the offset across
    /// `e1` uniform in the strip from `u₁` (its two halves for `u₁ < ½` and `u₁ ≥ ½`),
    /// lifted to the hemisphere of `a`.
    fn sample_clipped(&self, u: [f32; 2]) -> Vec3 {
        let a = self.sptd.cosine_axis;
        let e2 = a.cross(self.e1);
        let total = PI * self.integral;
        let h = self.clipped_depth(clamp_random(u[0]) * total, total);
        let (inner, outer) = self.clipped_strip(h);
        let v = 2.0 * clamp_random(u[1]) - 1.0;
        let y = libm::copysignf(inner + (outer - inner) * v.abs(), v);
        // `1 − x² − y² = h (2 − h) − y²`: no cancellation of `x² ≈ 1` near the rim.
        let z = crate::math::sqrtf((h * (2.0 - h) - y * y).max(0.0));
        crate::math::normalize_or(self.e1 * (1.0 - h) + e2 * y + a * z, a)
    }

    /// The random numbers of the clipped sampler for a base direction.
    fn invert_clipped(&self, base: Vec3) -> Option<[f32; 2]> {
        let a = self.sptd.cosine_axis;
        let e2 = a.cross(self.e1);
        let (x, y, z) = (base.dot(self.e1), base.dot(e2), base.dot(a));
        // `1 − x = (y² + z²)/(1 + x)` for a unit direction, accurate near the rim.
        let h = if x > 0.0 {
            (y * y + z * z) / (1.0 + x)
        } else {
            1.0 - x
        };
        let total = PI * self.integral;
        let u0 = self.clipped_cumulative(h) / total;
        let (inner, outer) = self.clipped_strip(h);
        let width = outer - inner;
        let v = if width > 0.0 {
            ((y.abs() - inner) / width).max(0.0).min(1.0)
        } else {
            0.0
        };
        let u1 = 0.5 * (1.0 + libm::copysignf(v, y));
        let u = [clamp_inverted(u0), clamp_inverted(u1)];
        (u[0].is_finite() && u[1].is_finite()).then_some(u)
    }

    /// Whether this clamped-cosine sampler draws over the projection of `g(C) ∩ H_a`
    /// (`g(C)` crosses the base's horizon or is wider than a hemisphere) rather than
    /// over the ellipse of an image inside the hemisphere; `false` for the uniform base.
    #[inline]
    #[must_use]
    pub fn is_clipped(&self) -> bool {
        self.sptd.base == SptdBase::ClampedCosine && self.clipped != 0
    }

    /// Draws a direction inside `C` with density [`SptdInCap::pdf`].
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        let base = match self.sptd.base {
            SptdBase::Uniform => return self.sample_uniform_base(u),
            SptdBase::ClampedCosine if self.clipped != 0 => self.sample_clipped(u),
            SptdBase::ClampedCosine => {
                let a = self.sptd.cosine_axis;
                let e2 = a.cross(self.e1);
                let r = crate::math::sqrtf(clamp_random(u[0]));
                let (sin_phi, cos_phi) = crate::math::sin_cos_of_turn(clamp_random(u[1]));
                let p = self.e1 * (self.ellipse.x + self.ellipse.y * r * cos_phi)
                    + e2 * (self.ellipse.z * r * sin_phi);
                crate::math::normalize_or(
                    p + a * crate::math::sqrtf((1.0 - p.length_squared()).max(0.0)),
                    a,
                )
            }
        };
        let dir = transform(base, self.sptd.pivot);
        // A sample that rounding moved out of C (by ulps, at the boundary) is dropped, so
        // that `pdf` of every sample equals its density.
        if !self.cap.contains_inlined(dir) {
            return Sample::NONE;
        }
        // The density from `dir` alone, exactly as `pdf` computes it (the cosine base
        // re-derives the preimage), so that `pdf(sample.dir) == sample.pdf` bit for bit.
        let pdf = self.density_of(dir, transform(dir, self.sptd.pivot));
        if pdf > 0.0 && pdf.is_finite() {
            Sample { dir, pdf }
        } else {
            Sample::NONE
        }
    }

    /// [`SptdInCap::sample`] of the uniform base (`sptd.base` must be
    /// [`SptdBase::Uniform`]), always inlined: the body of `sample`'s uniform case, which
    /// the sphere light sampler calls directly for a cap above the horizon (without
    /// `sample`'s call, its dispatch on the base and the clamped cosine's code around it:
    /// the same bits).
    #[inline(always)]
    pub(crate) fn sample_uniform_base(&self, u: [f32; 2]) -> Sample {
        // `Cap::sample_uniform` of the image with its frame prepared (the same bits:
        // `orthonormal_basis(image.axis)`, see `e1`).
        let image = &self.image;
        // `image.uniform_pdf() == 0` without its division: the uniform pdf `1/Ω` only fed
        // that test and `sample_uniform_in_frame`'s pdf, which the test below reads only
        // for 0 (the density is `J(ω)/Ω`, below). `uniform_pdf` is 0 for `t ≤ 0` or NaN
        // and where `1/(2π t)` is infinite or 0, i.e. for `Ω = 2π t` (the same product)
        // below `MIN_NORMALISER` or infinite (only a struct corrupted through C): the
        // range test below, which NaN fails (`the_uniform_base_sample_skips_the_uniform_pdf`).
        let normaliser = TAU * image.one_minus_cos;
        if !(MIN_NORMALISER..f32::INFINITY).contains(&normaliser) {
            return Sample::NONE;
        }
        let frame = [image.axis.into(), self.e1.into(), self.ellipse.into()];
        // (Any non-zero pdf: `sample_uniform_in_frame` returns it or 0 for no sample.)
        let s = sample_uniform_in_frame(frame, image.one_minus_cos, image.one_plus_cos, 1.0, u);
        if s.pdf == 0.0 {
            return Sample::NONE;
        }
        let base = s.dir;
        let dir = transform(base, self.sptd.pivot);
        // As in `sample`: a sample that rounding moved out of C is dropped.
        if !self.cap.contains_inlined(dir) {
            return Sample::NONE;
        }
        // `density_of` of the uniform base: `J(ω) / Ω(g(C))` (the numerator 1).
        let pdf = jacobian(dir, self.sptd.pivot) / image.solid_angle();
        if pdf > 0.0 && pdf.is_finite() {
            Sample { dir, pdf }
        } else {
            Sample::NONE
        }
    }

    /// `D(ω)/∫_C D` for a direction and its preimage.
    #[inline(always)]
    fn density_of(&self, dir: Vec3, base: Vec3) -> f32 {
        let numerator = match self.sptd.base {
            SptdBase::Uniform => 1.0,
            SptdBase::ClampedCosine => base.dot(self.sptd.cosine_axis).max(0.0),
        };
        // For the uniform base `integral` holds Ω(g(C))/4π and D_std = 1/4π; for the
        // clamped cosine it holds π·∫ and D_std = ω·a/π: both reduce to
        // `numerator J / (normalisation)` below.
        let normalisation = match self.sptd.base {
            SptdBase::Uniform => self.image.solid_angle(),
            SptdBase::ClampedCosine => PI * self.integral,
        };
        numerator * jacobian(dir, self.sptd.pivot) / normalisation
    }

    /// The density of [`SptdInCap::sample`] at `dir` (normalised here): `D(ω)/∫_C D`
    /// inside `C`, 0 outside or for an invalid `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        if !self.cap.contains(dir) {
            return 0.0;
        }
        // `unit` leaves the samplers' (unit) directions unchanged, bit for bit.
        let Some(dir) = crate::math::unit(dir) else {
            return 0.0;
        };
        let base = transform(dir, self.sptd.pivot);
        let pdf = self.density_of(dir, base);
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// The random numbers that [`SptdInCap::sample`] maps to `dir`, or `None` outside
    /// `C`.
    pub fn invert(&self, dir: Vec3) -> Option<[f32; 2]> {
        if !self.cap.contains(dir) {
            return None;
        }
        let base = transform(crate::math::normalize_scaled(dir), self.sptd.pivot);
        match self.sptd.base {
            SptdBase::Uniform => self.image.invert(base),
            SptdBase::ClampedCosine if self.clipped != 0 => self.invert_clipped(base),
            SptdBase::ClampedCosine => {
                let a = self.sptd.cosine_axis;
                let e2 = a.cross(self.e1);
                let x = (base.dot(self.e1) - self.ellipse.x) / self.ellipse.y;
                let y = base.dot(e2) / self.ellipse.z;
                let mut phi = libm::atan2f(y, x);
                if phi < 0.0 {
                    phi += TAU;
                }
                let u0 = (x * x + y * y).max(0.0).min(ONE_MINUS_ULP);
                let u1 = (phi * (0.5 / PI)).max(0.0).min(ONE_MINUS_ULP);
                (u0.is_finite() && u1.is_finite()).then_some([u0, u1])
            }
        }
    }
}

#[cfg(test)]
#[path = "sptd_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "sptd_set_tests.rs"]
mod set_tests;
