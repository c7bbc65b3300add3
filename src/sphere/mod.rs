//! Sphere lights (Dupuy, Heitz and Belcour 2017, "A Spherical Cap Preserving
//! Parameterization for Spherical Distributions"): the cap that a sphere subtends,
//! uniform sampling inside it, the solid angle of the intersection of two caps and uniform
//! sampling of that intersection, the pivot
//! transformation that maps caps to caps, and the pivot phase function.

pub mod cap;
pub mod cap_intersection;
pub mod cap_intersection_sampling;
pub mod cap_union_sampling;
pub mod light;
pub mod phase;
pub mod pivot;
mod shading_fast;
pub mod solid_angle_sphere;
pub mod sptd;

pub use cap::Cap;
pub use cap_intersection::{cap_intersection_solid_angle, cap_intersection_solid_angle_oat_sander};
pub use cap_intersection_sampling::CapIntersection;
pub use cap_union_sampling::CapUnion;
pub use light::{GgxPivot, SphereLightSampler, SphereLightShading};
pub use pivot::{pivot_cap, pivot_jacobian, pivot_transform};
pub use solid_angle_sphere::SolidAngleSphere;
pub use sptd::{Sptd, SptdBase, SptdInCap};
