// STUB: replaced by the sg branch at merge
//! A spherical Gaussian `G(ω) = a · exp(λ(ω·ξ − 1))` (supplement Section 2).

use glam::Vec3;

/// `G(ω) = exp(log_amplitude) · exp(λ(ω·ξ − 1))`, axis `ξ` a unit vector, sharpness
/// `λ ≥ 0`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sg {
    /// The lobe axis `ξ` (unit vector).
    pub axis: Vec3,
    /// The sharpness `λ ≥ 0`.
    pub sharpness: f32,
    /// The natural logarithm of the amplitude.
    pub log_amplitude: f32,
}

impl Sg {
    /// The SG with the given axis, sharpness and amplitude (amplitudes ≤ 0 are raised
    /// to the smallest positive normal `f32`, so that the logarithm stays finite).
    pub fn new(axis: Vec3, sharpness: f32, amplitude: f32) -> Sg {
        Sg {
            axis,
            sharpness,
            log_amplitude: libm::logf(amplitude.max(f32::MIN_POSITIVE)),
        }
    }

    /// `G(dir)` for a unit direction.
    pub fn eval(&self, dir: Vec3) -> f32 {
        libm::expf(self.log_amplitude + self.sharpness * (dir.dot(self.axis) - 1.0))
    }
}

/// `A(λ) = ∫ G dω = 2π/λ (1 − e^{−2λ})` for a unit amplitude (supplement Section 2);
/// `4π` at `λ = 0`, NaN and negative sharpness count as 0.
pub fn sg_integral(sharpness: f32) -> f32 {
    let lambda = sharpness.max(0.0);
    if lambda < 1e-6 {
        return 4.0 * core::f32::consts::PI * (1.0 - lambda);
    }
    -2.0 * core::f32::consts::PI * libm::expm1f(-2.0 * lambda) / lambda
}
