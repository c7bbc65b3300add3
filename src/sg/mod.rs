// STUB: replaced by the sg branch at merge
//! Spherical Gaussians (SGs) and the SG approximations of reflection lobes
//! (Tokuyoshi 2016, supplement Section 2). Minimal stub: only what the VSGL accumulator
//! needs, with the signatures of the `sg` branch.

#[allow(clippy::module_inception)]
pub mod sg;

pub mod lobes;

pub use lobes::{DIFFUSE_LOBE_SHARPNESS, diffuse_lobe_normalized, specular_lobe_normalized};
pub use sg::{Sg, sg_integral};
