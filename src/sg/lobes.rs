// STUB: replaced by the sg branch at merge
//! SG approximations of the diffuse and specular reflection lobes (supplement
//! Section 2.1, Eq. 1 and Eq. 2).

use super::sg::{Sg, sg_integral};
use glam::Vec3;

/// `λ_d ≈ 2`: the sharpness of the SG fitted to the clamped cosine lobe (Eq. 1).
pub const DIFFUSE_LOBE_SHARPNESS: f32 = 2.0;

/// `G(ω, n, λ_d) / A(λ_d)`: the normalised diffuse lobe of Eq. 1.
pub fn diffuse_lobe_normalized(normal: Vec3) -> Sg {
    Sg::new(
        normal,
        DIFFUSE_LOBE_SHARPNESS,
        1.0 / sg_integral(DIFFUSE_LOBE_SHARPNESS),
    )
}

/// The normalised specular lobe of Eq. 2: axis `ξ_s = 2(ω'·n)n − ω'`, sharpness
/// `λ_s = (2/α²) / (4|ξ_s·n|)`, amplitude `1/A(λ_s)`.
pub fn specular_lobe_normalized(normal: Vec3, toward_incoming: Vec3, alpha: f32) -> Sg {
    let axis = 2.0 * toward_incoming.dot(normal) * normal - toward_incoming;
    let alpha2 = (alpha * alpha).max(1e-8);
    let sharpness = (2.0 / alpha2) / (4.0 * axis.dot(normal).abs().max(1e-6));
    Sg::new(axis, sharpness, 1.0 / sg_integral(sharpness))
}
