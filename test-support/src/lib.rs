//! What sphera's tests, its std tools and benchmarks, and (through the tools) its fuzz
//! targets share, each in one place: SplitMix64 ([`Rng`]), f64 vectors and reference
//! geometry of polygons (solid angle, projected solid angle, clipping), the chi-square
//! test, and quadrature over polygons and the sphere.
//!
//! It does not depend on `sphera`: its f64 references stay independent of the f32
//! core they check. The core takes it as a dev-dependency only, so the `no_std`
//! library and the static library never see it.
// `!(t > 0.0)` rejects NaN on purpose, as in the core.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
pub mod geometry;
pub mod quadrature;
pub mod rng;
pub mod stats;
pub mod vector;

pub use geometry::*;
pub use quadrature::*;
pub use rng::Rng;
pub use stats::*;
pub use vector::*;
