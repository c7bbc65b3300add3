//! The baselines that Peters 2021 measures against (supplement Table A.2): Turk's
//! area sampling with its density converted to solid angle, Arvo's 1995 sampling of
//! spherical triangles, Arvo's projected solid angle sampling by Newton's method on
//! the sectors' area functions, and the bilinear and biquadratic warps of Hart et al. 2020
//! composed with solid angle sampling. (Clipped solid angle sampling, another row of
//! the table, is [`crate::polygon::ClippedSolidAnglePolygon`].)

pub mod arvo;
pub mod arvo_projected;
pub mod hart;
pub mod turk;

pub use arvo::ArvoPolygon;
pub use arvo_projected::ArvoProjectedPolygon;
pub use hart::{HartBilinearPolygon, HartBiquadraticPolygon};
pub use turk::TurkPolygon;
