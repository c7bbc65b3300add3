//! Numerics shared by every technique: error-free products, a stable cross product,
//! `atan` forms for arguments of known sign, orthonormal frames, `f32` bit helpers and the
//! normalisation of direction arguments.

mod atan;
mod bits;
mod frame;
mod lanes;
mod products;
mod unit;

pub use atan::{atan_fast_nonneg, atan2_upper_half_plane};
pub use bits::{copy_sign, is_sign_negative, sign_mask, with_sign_of_product};
pub use frame::{Frame, orthonormal_basis};
pub(crate) use lanes::{
    LANES, cross_precise4, difference_of_products_unless_cancelling4, difference_of_products4,
    lane_starts, sqrt4,
};
pub use products::{
    HAS_HARDWARE_FMA, cross_precise, cross_with_residual, determinant_is_exactly_zero,
    difference_of_products, difference_of_products_unless_cancelling, dot_precise, fma,
    two_product, two_sum,
};
pub(crate) use unit::{normalize_by_largest, unit};
