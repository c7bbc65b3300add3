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
//! images (Eq. 11, `g(A ∩ B) = g(A) ∩ g(B)` for a bijection). Sampling `D` inside `C`
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
//!   is exact when `g(C)` lies in the hemisphere of `a`: the orthographic projection of
//!   such a cap onto the plane `⊥ a` is an ellipse, and a point uniform in it lifts to a
//!   direction with density `ω·a / (π sin²θ cos β)` (Nusselt's analogue). When `g(C)`
//!   crosses the horizon of `a`, [`SptdInCap`] draws no sample (pdf 0) and its `pdf` is
//!   0 too, so the two stay consistent; its integral remains exact.
//!
//! Hard cases (tested): pivots from the origin (where `g` is the antipodal map) to
//! `|r_p| = 0.9999` (the fitted GGX table reaches `1 − 3.3e-5`), caps containing the
//! pivot's direction (images wider than a hemisphere), tiny caps (1e-6 sr), caps
//! straddling the base's horizon, the whole sphere, the empty cap, caps that coincide
//! or are complementary.

use super::cap::Cap;
use super::cap_intersection::cap_intersection_solid_angle;
use super::pivot::{pivot_cap, transform, valid_pivot};
use crate::Sample;
use crate::math::orthonormal_basis;
use crate::sample::{ONE_MINUS_ULP, clamp_random};
use core::f32::consts::{FRAC_1_PI, PI, TAU};
use glam::Vec3;

const INV_4PI: f32 = 0.25 * FRAC_1_PI;

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
    let rho = pivot.length();
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
    let r = libm::sqrtf(r2);
    let (sin_phi, cos_phi) = libm::sincosf(TAU * clamp_random(u[1]));
    let (t, b) = orthonormal_basis(axis);
    (t * (r * cos_phi) + b * (r * sin_phi) + axis * libm::sqrtf((1.0 - r2).max(0.0)))
        .normalize_or(axis)
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

    /// The SPTD of the clamped-cosine base about `axis` (normalised here; a zero or
    /// non-finite axis becomes `z`) with pivot `pivot`.
    pub fn clamped_cosine(pivot: Vec3, axis: Vec3) -> Sptd {
        // Scaled by the largest component before normalising: an axis of 2e-21 has a
        // denormal |a|², whose rounding left |a| = 1.00006 and integrals above 1
        // (found by fuzzing). `normalize_scaled` gives 0 for zero or non-finite axes.
        let axis = crate::sample::normalize_scaled(axis);
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
    let s = libm::sqrtf((cap.sin2 - cos_beta * cos_beta).max(0.0));
    let phi0 = libm::atan2f(s, cos * cos_beta);
    let psi0 = libm::atan2f(s, cos);
    let e = cap.sin2 * cos_beta * (PI - phi0) - s * cos + psi0;
    e.max(0.0).min(PI)
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

/// Whether the circles of two caps coincide (to `1e-6` in `1 − cos`): `Some(true)`
/// for the same cap, `Some(false)` for complementary caps (the same circle bounding
/// opposite sides), `None` otherwise.
fn same_circle(p: &Cap, q: &Cap) -> Option<bool> {
    const TOLERANCE: f32 = 1e-6;
    let t_d = 0.5 * (p.axis - q.axis).length_squared();
    if t_d <= TOLERANCE && (p.one_minus_cos - q.one_minus_cos).abs() <= TOLERANCE {
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
    let a = libm::sqrtf(x * x + y * y);
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
    let half = libm::atan2f(libm::sqrtf(y2.max(0.0)), k);
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
pub fn clamped_cosine_over_caps(a_cap: &Cap, b_cap: &Cap, a: Vec3) -> f32 {
    if !(a_cap.one_minus_cos > 0.0) || !(b_cap.one_minus_cos > 0.0) {
        return 0.0;
    }
    let horizon = Cap::from_axis_one_minus_cos(a, 1.0);
    let caps = [*a_cap, *b_cap, horizon];
    let mut total = Vec3::ZERO;
    for (i, ci) in caps.iter().enumerate() {
        let ci = *ci;
        if ci.one_minus_cos >= 2.0 {
            continue; // the whole sphere has no boundary
        }
        let (t, b) = orthonormal_basis(ci.axis);
        let sin_i = libm::sqrtf(ci.sin2.max(0.0));
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
        for arc in arcs.iter().flatten() {
            let (s1, c1) = libm::sincosf(arc.start);
            let (s2, c2) = libm::sincosf(arc.start + arc.length);
            total += ci.axis * (ci.sin2 * arc.length)
                - (t * (s2 - s1) - b * (c2 - c1)) * (sin_i * cos_i);
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
    /// `cos θ sin β`, its semi-axes `sin θ cos β` (along `e1`) and `sin θ`.
    ellipse: Vec3,
    /// Unit tangent of the base axis pointing to the image cap's axis (any unit
    /// tangent when the two axes coincide to rounding: the ellipse is then a circle).
    e1: Vec3,
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
    };

    /// Prepares `sptd` restricted to `cap` (sanitized). `None` when `∫_C D` is 0 or its
    /// inverse is not finite, or, for the clamped-cosine base, when `g(C)` crosses the
    /// base's horizon (see the module documentation; use
    /// [`Sptd::integral_over_cap`] for the integral there).
    pub fn new(sptd: &Sptd, cap: &Cap) -> Option<SptdInCap> {
        let cap = cap.sanitized();
        let image = pivot_cap(&cap, sptd.pivot);
        let integral = sptd.base_integral_over_cap(&image).max(0.0).min(1.0);
        if !(integral > 0.0) || !(1.0 / integral).is_finite() {
            return None;
        }
        let mut prepared = SptdInCap {
            sptd: *sptd,
            cap,
            image,
            integral,
            ellipse: Vec3::ZERO,
            e1: Vec3::X,
        };
        if sptd.base == SptdBase::ClampedCosine {
            let a = sptd.cosine_axis;
            let cos_beta = image.axis.dot(a);
            let sin_theta = libm::sqrtf(image.sin2.max(0.0));
            // Inside the hemisphere of a: β + θ ≤ π/2, i.e. cos β ≥ sin θ with θ ≤ π/2.
            if !(image.one_minus_cos <= 1.0) || !(cos_beta >= sin_theta) || !(cos_beta > 0.0) {
                return None;
            }
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
            let sin_beta = libm::sqrtf(x * x + y * y);
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
            // The sampling density is ω·a / (π sin²θ cos β): use that normalisation, the
            // closed form's value in this case.
            prepared.integral = image.sin2 * cos_beta;
            if !(prepared.integral > 0.0) || !(1.0 / prepared.integral).is_finite() {
                return None;
            }
        }
        Some(prepared)
    }

    /// Draws a direction inside `C` with density [`SptdInCap::pdf`].
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        let base = match self.sptd.base {
            SptdBase::Uniform => {
                let s = self.image.sample_uniform(u);
                if s.pdf == 0.0 {
                    return Sample::NONE;
                }
                s.dir
            }
            SptdBase::ClampedCosine => {
                let a = self.sptd.cosine_axis;
                let e2 = a.cross(self.e1);
                let r = libm::sqrtf(clamp_random(u[0]));
                let (sin_phi, cos_phi) = libm::sincosf(TAU * clamp_random(u[1]));
                let p = self.e1 * (self.ellipse.x + self.ellipse.y * r * cos_phi)
                    + e2 * (self.ellipse.z * r * sin_phi);
                (p + a * libm::sqrtf((1.0 - p.length_squared()).max(0.0))).normalize_or(a)
            }
        };
        let dir = transform(base, self.sptd.pivot);
        // A sample that rounding moved out of C (by ulps, at the boundary) is dropped, so
        // that `pdf` of every sample equals its density.
        if !self.cap.contains(dir) {
            return Sample::NONE;
        }
        // The density from `dir` alone, exactly as `pdf` computes it (the cosine base
        // re-derives the preimage), so that `pdf(sample.dir) == sample.pdf` bit for bit.
        let base = match self.sptd.base {
            SptdBase::Uniform => base,
            SptdBase::ClampedCosine => transform(dir, self.sptd.pivot),
        };
        let pdf = self.density_of(dir, base);
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
        let base = transform(crate::sample::normalize_scaled(dir), self.sptd.pivot);
        match self.sptd.base {
            SptdBase::Uniform => self.image.invert(base),
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
