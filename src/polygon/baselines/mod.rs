//! The baselines that Peters 2021 measures against (supplement Table A.2): Turk's
//! area sampling with its density converted to solid angle, and Arvo's 1995 sampling
//! of spherical triangles.

pub mod arvo;
pub mod turk;

pub use arvo::ArvoPolygon;
pub use turk::TurkPolygon;
