//! The one-call shading of a polygonal light: projected solid angle sampling and the GGX
//! LTC inside the polygon, combined by multiple importance sampling
//! (`sphera_polygon_light_*`).
use super::polygon::prepare;
use super::types::SpheraVec3;
use crate::Vec3;
use crate::polygon::light::{LightSample, Material, MisHeuristic, PolygonLight};

/// The balance heuristic, `p_j / Σ p_k`.
pub const SPHERA_MIS_BALANCE: u32 = 0;

/// The power heuristic with exponent 2, `p_j² / Σ p_k²`.
pub const SPHERA_MIS_POWER: u32 = 1;

/// The weighted balance heuristic of Peters 2021, `c_j p_j / Σ c_k p_k`.
pub const SPHERA_MIS_WEIGHTED_BALANCE: u32 = 2;

/// Clamped optimal MIS (Peters 2021, supplement B.3), with visibility estimate `v`.
pub const SPHERA_MIS_CLAMPED_OPTIMAL: u32 = 3;

/// Optimal MIS (Peters 2021, supplement B.1), with visibility estimate `v`.
pub const SPHERA_MIS_OPTIMAL: u32 = 4;

// The numbers of the C constants are those of the Rust enum.
const _: () = {
    assert!(SPHERA_MIS_BALANCE == MisHeuristic::Balance as u32);
    assert!(SPHERA_MIS_POWER == MisHeuristic::Power as u32);
    assert!(SPHERA_MIS_WEIGHTED_BALANCE == MisHeuristic::WeightedBalance as u32);
    assert!(SPHERA_MIS_CLAMPED_OPTIMAL == MisHeuristic::ClampedOptimal as u32);
    assert!(SPHERA_MIS_OPTIMAL == MisHeuristic::Optimal as u32);
};

/// Prepares a polygonal light for Peters 2021's two techniques: 0, projected solid angle
/// sampling; 1, the LTC of GGX (`material->roughness`, view `wo`). `heuristic` is a
/// `SPHERA_MIS_*` value; `visibility` is `v` of (clamped) optimal MIS, clamped to [0, 1],
/// NaN meaning 1/2. Albedos and F0 are clamped to [0, 1]; `f0 = (0, 0, 0)` is Lambertian.
/// Returns `false` also for a null `material`, an unknown `heuristic`, a `wo` not above the
/// horizon, and a polygon neither technique can sample; a technique that cannot sample it
/// alone gets zero weight.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_polygon_light_prepare(
    out: *mut PolygonLight,
    vertices: *const SpheraVec3,
    count: u32,
    wo: SpheraVec3,
    material: *const Material,
    heuristic: u32,
    visibility: f32,
) -> bool {
    let heuristic = MisHeuristic::from_u32(heuristic);
    // SAFETY: the caller guarantees that a non-null `material` points to a valid value.
    let material = unsafe { material.as_ref() };
    // SAFETY: forwarded from the caller. In place (the value is 3572 bytes): the empty
    // value only on failure.
    unsafe {
        prepare(
            out,
            vertices,
            count,
            |out: &mut PolygonLight, local: &[Vec3]| {
                if let (Some(material), Some(heuristic)) = (material, heuristic) {
                    out.prepare(local, Vec3::from(wo), material, heuristic, visibility)
                } else {
                    *out = PolygonLight::EMPTY;
                    false
                }
            },
        )
    }
}

/// Draws a sample of technique `technique` (0: projected solid angle, 1: the GGX LTC), weighted
/// so that one sample of each gives `L × (V(dir) × visible + unoccluded)` (trace a shadow ray only
/// where `visible` is non-zero; `unoccluded` is non-zero only for `SPHERA_MIS_OPTIMAL`); `pdf` is
/// the drawing technique's. Directions at or below the horizon contribute 0.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_polygon_light_sample(
    light: *const PolygonLight,
    technique: u32,
    u0: f32,
    u1: f32,
) -> LightSample {
    if light.is_null() {
        return LightSample::NONE;
    }
    // SAFETY: `light` is non-null and the caller guarantees it is prepared.
    unsafe { &*light }.sample(technique, [u0, u1])
}

/// The unshadowed shading per unit radiance in closed form: `ρ Φ / π` (exact) plus
/// GGX's directional albedo times the LTC's mass in the polygon (Heitz et al. 2016),
/// per channel. (0, 0, 0) for a null or empty `light`.
///
/// # Safety
///
/// Pointers as in the conventions of the C ABI ([`crate::ffi`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_polygon_light_unshadowed(light: *const PolygonLight) -> SpheraVec3 {
    if light.is_null() {
        return Vec3::ZERO.into();
    }
    // SAFETY: `light` is non-null and the caller guarantees it is prepared.
    unsafe { &*light }.unshadowed().into()
}
