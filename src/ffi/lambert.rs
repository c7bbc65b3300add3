//! C ABI, `sphera_lambert_*`: the Lambertian BRDF and cosine-weighted sampling.
use super::types::{SpheraSample, SpheraVec3};
use crate::brdf::Lambert;

// ---- Lambert -------------------------------------------------------------------------

/// The Lambertian BRDF `albedo / π` per RGB channel (each channel of `albedo` clamped
/// to [0, 1], NaN to 0), without the cosine `cos θi`.
///
/// Returns (0, 0, 0) when either direction lies at or below the horizon (z <= 0), is
/// zero or is not finite.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_lambert_eval(
    albedo: SpheraVec3,
    wo: SpheraVec3,
    wi: SpheraVec3,
) -> SpheraVec3 {
    Lambert::new(albedo.into())
        .eval(wo.into(), wi.into())
        .into()
}

/// Draws a direction with density `cos θ / π` (cosine-weighted, by the concentric disk
/// mapping) from the random numbers `u0`, `u1` in [0, 1). Every draw lies strictly above
/// the horizon and its pdf equals `sphera_lambert_pdf(dir)`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_lambert_sample(u0: f32, u1: f32) -> SpheraSample {
    Lambert::default().sample([u0, u1]).into()
}

/// The density `max(0, cos θ) / π` per steradian with which `sphera_lambert_sample`
/// draws `wi`. Returns 0 when `wi` is zero or not finite.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_lambert_pdf(wi: SpheraVec3) -> f32 {
    Lambert::default().pdf(wi.into())
}
