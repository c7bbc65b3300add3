//! Spherical Gaussians for virtual spherical Gaussian lights (Tokuyoshi 2016,
//! "Modified Filtered Importance Sampling for Virtual Spherical Gaussian Lights",
//! supplement Sections 2, 2.1 and 4): SG algebra, von Mises–Fisher sampling, SG fits
//! of reflection lobes, anisotropic SGs, and shading with the incoming radiance of a
//! VSGL.

pub mod asg;
pub mod lobes;
#[allow(clippy::module_inception)] // the interface fixes `sg::sg::Sg`
pub mod sg;
pub mod shading;
pub mod shading_point;
pub mod vmf;

pub use asg::Asg;
pub use lobes::{
    DIFFUSE_LOBE_SHARPNESS, beckmann_lobe, beckmann_lobe_normalized, diffuse_lobe_normalized,
    specular_lobe, specular_lobe_normalized,
};
pub use sg::{MAX_SHARPNESS, Sg, sg_inner_product, sg_integral, sg_product};
pub use shading_point::{SgShading, SgShadingPoint};
pub use vmf::{vmf_invert, vmf_pdf, vmf_sample};

#[cfg(test)]
mod asg_tests;
#[cfg(test)]
mod lobes_tests;
#[cfg(test)]
mod sg_tests;
#[cfg(test)]
mod shading_point_tests;
#[cfg(test)]
mod shading_tests;
#[cfg(test)]
mod vmf_tests;
