//! Anisotropic spherical Gaussians (ASGs, Xu et al. 2013) as Tokuyoshi 2016 uses them
//! for the specular lobe at a shading point (supplement Section 4.2): evaluation, the
//! approximate integral, the ASG × SG product integral, and the ASG fit of the GGX lobe
//! (and of the Beckmann lobe, the same function).
//!
//! # Definition
//!
//! ```text
//! Ĝ(ω) = a · max(ω·z, 0) · e^{−η_x (ω·x)² − η_y (ω·y)²}
//! ```
//!
//! for an orthonormal frame `(x, y, z)` and bandwidths `η_x, η_y ≥ 0`.
//!
//! # Approximate integral
//!
//! In the coordinates `(p, q) = (ω·x, ω·y)` of the unit disk, `max(ω·z, 0) dω = dp dq`
//! on the upper hemisphere, so the integral is exactly
//! `a ∫_{p²+q² ≤ 1} e^{−η_x p² − η_y q²} dp dq`. Extending the domain to the plane gives
//! the approximation `∫ Ĝ ≈ a π/√(η_x η_y)`: it adds the Gaussian's tail outside the
//! unit disk, a relative error of `e^{−η}/(1 − e^{−η})` for `η_x = η_y = η` (below 1 %
//! for `η ≳ 4.6`, below 1e-6 for `η ≳ 14`), governed by the smaller bandwidth. It breaks
//! for small bandwidths: the true integral is at most `a π` (the exponential is ≤ 1),
//! while the approximation diverges as `η → 0` (at `η = 1` it is 58 % high).
//! [`Asg::integral`] returns the approximation clamped to that bound `a π`, so it stays
//! finite.
//!
//! # ASG × SG (Section 4.2, boxed formula, from Xu et al.)
//!
//! With the SG `c e^{λ(ω·ξ − 1)}` and `ν = λ/2`,
//!
//! ```text
//! ∫ G Ĝ dω ≈ c π Ĝ(ξ; η_x ν/(η_x + ν), η_y ν/(η_y + ν)) / √((η_x + ν)(η_y + ν)).
//! ```
//!
//! Both limits hold: `ν → ∞` gives `Ĝ(ξ) · 2π/λ` (the SG acts as a delta of mass
//! `A(λ) ≈ 2π/λ`) and `ν → 0` gives `c · π/√(η_x η_y)` (the approximate integral
//! above, weighted by `max(ξ·z, 0)`). As for the integral, the factor
//! `1/√((η_x + ν)(η_y + ν))` is clamped to at most 1, the bound `∫ G Ĝ ≤ c a π`.
//!
//! # The ASG fit of the GGX specular lobe
//!
//! Derived here (Section 4.2 asks for an ASG but gives no fit). Take the SG
//! approximation of GGX's unnormalised NDF `D̂(h) ≈ e^{−λ_h/2 |h − n|²}`,
//! `λ_h = 2/α²` ([`crate::sg::lobes`]), and map half vectors to directions:
//! `h = (ω_o + ω)/|ω_o + ω|` with `ω_o` the view. At `ω = ξ_s` (the reflection of
//! `ω_o` about `n`) `h = n` and `|ω_o + ξ_s| = 2 cos θ_o`. A small step `δ` from `ξ_s`
//! moves `h` by `(I − n nᵀ) δ / (2 cos θ_o)`. Let `z = ξ_s`, `y` the unit normal of
//! the plane of incidence (`∝ n × ξ_s`, orthogonal to `n`) and `x = y × z` (in the plane,
//! orthogonal to `ξ_s`, with `|x·n| = sin θ_o`):
//!
//! - a step `a x` moves `h` by `a |x − (x·n) n| / (2 cos θ_o) = a cos θ_o/(2 cos θ_o) = a/2`;
//! - a step `b y` (`y ⟂ n`) moves `h` by `b / (2 cos θ_o)`.
//!
//! So `|h − n|² ≈ a²/4 + b²/(4 cos²θ_o)` and
//!
//! ```text
//! D̂(h(ω)) ≈ e^{−(λ_h/8) (ω·x)² − (λ_h/(8 cos²θ_o)) (ω·y)²}:
//! η_x = λ_h/8 = 1/(4α²),   η_y = λ_h/(8 cos²θ_o) = 1/(4α² cos²θ_o).
//! ```
//!
//! The lobe is narrower across the plane of incidence (`η_y`) than along it, by
//! `1/cos θ_o` in width, as grazing views show. The geometric mean
//! `√(η_x η_y) = λ_h/(8 cos θ_o)` is the `λ_s/2` of the isotropic warp
//! `λ_s = λ_h/(4 cos θ_o)` (an SG `e^{λ(ω·ξ−1)} ≈ e^{−(λ/2)θ²}`), so both fits carry the
//! same energy: `π/√(η_x η_y) = 2π/λ_s = 4πα² cos θ_o`. The `max(ω·z, 0)` factor of the
//! ASG is ≈ 1 on the lobe and cuts off the back hemisphere. `cos θ_o` is clamped to at
//! least `MIN_SPECULAR_COSINE` and the bandwidths to `MAX_SHARPNESS`.

use super::lobes::{MIN_SPECULAR_COSINE, ndf_sharpness, reflection};
use super::sg::{MAX_SHARPNESS, Sg, exp_finite, log_of_amplitude, unit_or_none};
use crate::Vec3;
use crate::math::orthonormal_basis;
use core::f32::consts::PI;

/// An anisotropic spherical Gaussian
/// `a · max(ω·z, 0) · exp(−η_x (ω·x)² − η_y (ω·y)²)`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Asg {
    /// Tangent axis of bandwidth `eta_x`.
    pub x: Vec3,
    /// Tangent axis of bandwidth `eta_y`.
    pub y: Vec3,
    /// Lobe axis.
    pub z: Vec3,
    /// Bandwidth along `x`, in `[0, MAX_SHARPNESS]`.
    pub eta_x: f32,
    /// Bandwidth along `y`, in `[0, MAX_SHARPNESS]`.
    pub eta_y: f32,
    /// Amplitude `a ≥ 0` (finite).
    pub amplitude: f32,
}

#[inline(always)]
fn clamp_bandwidth(x: f32) -> f32 {
    x.max(0.0).min(MAX_SHARPNESS)
}

impl Asg {
    /// The zero function (frame `x, y, z`, bandwidths 0, amplitude 0).
    ///
    /// cbindgen:ignore
    pub const ZERO: Asg = Asg {
        x: Vec3::X,
        y: Vec3::Y,
        z: Vec3::Z,
        eta_x: 0.0,
        eta_y: 0.0,
        amplitude: 0.0,
    };

    /// The ASG around `z` with `x` projected orthogonal to `z` and `y = z × x`
    /// (right-handed), bandwidths clamped to `[0, MAX_SHARPNESS]` (NaN to 0), amplitude
    /// clamped to `[0, f32::MAX]` (NaN to 0). When `z` is zero or not finite this is
    /// [`Asg::ZERO`]; when `x` is (or is parallel to `z`), `x` is any tangent.
    pub fn new(x: Vec3, z: Vec3, eta_x: f32, eta_y: f32, amplitude: f32) -> Asg {
        let Some(z) = unit_or_none(z) else {
            return Asg::ZERO;
        };
        let x = match unit_or_none(x).and_then(|x| unit_or_none(x - z * x.dot(z))) {
            Some(x) if x.dot(z).abs() < 1e-3 => x,
            _ => orthonormal_basis(z).0,
        };
        let y = z.cross(x);
        Asg {
            x,
            y,
            z,
            eta_x: clamp_bandwidth(eta_x),
            eta_y: clamp_bandwidth(eta_y),
            amplitude: amplitude.max(0.0).min(f32::MAX),
        }
    }

    /// The same ASG with every field made valid (the frame rebuilt from `x` and `z` as
    /// in [`Asg::new`]); the C ABI sanitises every ASG it receives.
    pub fn sanitized(&self) -> Asg {
        Asg::new(self.x, self.z, self.eta_x, self.eta_y, self.amplitude)
    }

    /// `Ĝ(dir)`; `dir` normalised first, 0 for a zero or non-finite `dir`.
    pub fn eval(&self, dir: Vec3) -> f32 {
        let Some(w) = unit_or_none(dir) else {
            return 0.0;
        };
        let (px, py) = (w.dot(self.x), w.dot(self.y));
        let value = self.amplitude
            * w.dot(self.z).max(0.0)
            * libm::expf(-self.eta_x * px * px - self.eta_y * py * py);
        if value.is_finite() { value } else { 0.0 }
    }

    /// The approximate integral `a π/√(η_x η_y)`, clamped to the bound `a π` (see the
    /// module documentation: within 1 % for `η ≳ 4.6`, wrong for small `η`).
    pub fn integral(&self) -> f32 {
        let product = self.eta_x * self.eta_y;
        let factor = if product > 1.0 {
            1.0 / crate::math::sqrtf(product)
        } else {
            1.0
        };
        (self.amplitude * PI * factor).min(f32::MAX)
    }

    /// `∫ G Ĝ dω` by the boxed formula of Section 4.2 (`ν = λ/2`, see the module
    /// documentation), the SG amplitude applied in log space, with the factor
    /// `1/√((η_x + ν)(η_y + ν))` capped at 1 (as [`Asg::integral`] caps at `a π`), so
    /// the result is at most `c a π`. 0 when the SG's axis lies at or behind the ASG's
    /// horizon (`ξ·z ≤ 0`).
    pub fn convolve_sg(&self, sg: &Sg) -> f32 {
        let nu = 0.5 * sg.sharpness;
        let (ex, ey) = (self.eta_x + nu, self.eta_y + nu);
        // η ν/(η + ν), 0 when both are 0.
        let narrowed = |eta: f32, sum: f32| if sum > 0.0 { eta * (nu / sum) } else { 0.0 };
        let (nx, ny) = (narrowed(self.eta_x, ex), narrowed(self.eta_y, ey));
        let (px, py, pz) = (
            sg.axis.dot(self.x),
            sg.axis.dot(self.y),
            sg.axis.dot(self.z),
        );
        if !(pz > 0.0) || !(self.amplitude > 0.0) {
            return 0.0;
        }
        let product = ex * ey;
        let factor = if product > 1.0 {
            1.0 / crate::math::sqrtf(product)
        } else {
            1.0
        };
        let log_value = sg.log_amplitude - nx * px * px - ny * py * py
            + log_of_amplitude(self.amplitude * PI * pz * factor);
        exp_finite(log_value)
    }

    /// The ASG fit of GGX's unnormalised NDF warped to directions (amplitude 1, see the
    /// module documentation): `z = ξ_s = 2(ω_o·n)n − ω_o`, `y ∝ n × ξ_s`, `x = y × z`,
    /// `η_x = λ_h/8`, `η_y = λ_h/(8 cos²θ_o)`, `λ_h = 2/α²` (`α` clamped as in
    /// [`crate::sg::lobes`]). [`Asg::ZERO`] for a zero or non-finite normal or view.
    pub fn from_ggx(normal: Vec3, view: Vec3, alpha: f32) -> Asg {
        let Some((n, z, cos)) = reflection(normal, view) else {
            return Asg::ZERO;
        };
        let cos = cos.max(MIN_SPECULAR_COSINE);
        let lh = ndf_sharpness(alpha);
        let eta_x = lh / 8.0;
        let eta_y = lh / (8.0 * cos * cos);
        // y ⟂ plane of incidence; for a view along the normal any tangent will do.
        let x = match unit_or_none(n.cross(z)) {
            Some(y) => y.cross(z),
            None => orthonormal_basis(z).0,
        };
        Asg::new(x, z, eta_x, eta_y, 1.0)
    }

    /// The ASG fit of Beckmann's unnormalised NDF warped to directions: the derivation
    /// above starts from the SG `e^{−λ_h/2 |h − n|²}` with the paper's `λ_h = 2/α²`,
    /// which is Beckmann's as well as GGX's ([`crate::sg::lobes`]), so this is
    /// [`Asg::from_ggx`] with the same `α`.
    pub fn from_beckmann(normal: Vec3, view: Vec3, alpha: f32) -> Asg {
        Asg::from_ggx(normal, view, alpha)
    }
}
