//! Polygonal lights (Peters 2021, "BRDF Importance Sampling for Polygonal Lights", and
//! its supplemental document).
//!
//! Polygons are convex, given by their vertices relative to the shading point in the
//! local frame (z = normal), in either winding, with 3 to [`MAX_POLYGON_VERTICES`]
//! vertices.
//!
//! [`MAX_POLYGON_VERTICES`]: crate::MAX_POLYGON_VERTICES

pub mod baselines;
pub mod clip;
mod ellipse;
mod ellipse_sector;
#[rustfmt::skip]
mod clip_generated;
pub mod clipped_solid_angle;
pub mod light;
pub mod projected;
pub mod small_projected;
pub mod solid_angle;
mod sorting_networks;
#[rustfmt::skip]
mod sorting_networks_generated;

pub use clip::clip_to_upper_hemisphere;
pub use clipped_solid_angle::ClippedSolidAnglePolygon;
pub use projected::ProjectedSolidAnglePolygon;
pub use solid_angle::SolidAnglePolygon;
