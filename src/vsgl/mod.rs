//! Virtual spherical Gaussian lights (VSGLs, Tokuyoshi 2015; supplement Tokuyoshi 2016,
//! Sections 3 and 5): a cluster of virtual point lights (VPLs) summarised by plain sums
//! (the [`accumulator`]), and the selection of clusters from a mip pyramid of those sums
//! by filtered importance sampling ([`fis`]).
//!
//! The shading of a VSGL (incoming radiance SG, Eq. 6–7, and the diffuse and specular
//! product integrals of Section 4.2) lives with the SG algebra in [`crate::sg`].

pub mod accumulator;
pub mod fis;

pub use accumulator::{Vpl, Vsgl, VsglAccumulator, VsglTexel, luminance};
pub use fis::{FisCluster, VsglPyramid, fis_cluster, fis_select};

#[cfg(test)]
mod accumulator_tests;
#[cfg(test)]
mod fis_tests;

#[cfg(test)]
#[path = "shading_tests.rs"]
mod shading_tests;
