//! Spherical Gaussians, vMF sampling, lobe fits, ASGs and VSGL shading (Tokuyoshi
//! 2016): `sphera_sg_*`.
//!
//! SGs and ASGs are passed by value. One built by hand in C may hold anything: every
//! function first makes it valid (`Sg::sanitized`, `Asg::sanitized`): a zero or
//! non-finite SG axis gives the zero SG (amplitude 0), a NaN or negative sharpness
//! counts as 0 and a larger one than `SPHERA_SG_MAX_SHARPNESS` as that bound, a NaN
//! log amplitude as amplitude 0; an ASG's frame is rebuilt from `x` and `z` (a zero or
//! non-finite `z` gives the zero ASG). Outputs are always finite and non-negative
//! (values are at most `FLT_MAX`).
use super::types::SpheraVec3;
use crate::sg::lobes::{
    DIFFUSE_LOBE_SHARPNESS, beckmann_lobe, beckmann_lobe_normalized, diffuse_lobe_normalized,
    specular_lobe, specular_lobe_normalized,
};
use crate::sg::sg::{MAX_SHARPNESS, Sg, sg_integral};
use crate::sg::shading::{
    beckmann_specular_shading, beckmann_specular_shading_sg, diffuse_shading_constant_cosine,
    diffuse_shading_product, diffuse_shading_sharp_lobe, incoming_radiance, specular_shading,
    specular_shading_sg,
};

/// The largest sharpness of an SG (and bandwidth of an ASG): a lobe 1e-4 rad wide.
pub const SPHERA_SG_MAX_SHARPNESS: f32 = 1e8;

/// The least-squares sharpness `λ_d` of the SG fit of the clamped cosine (Eq. 1).
pub const SPHERA_SG_DIFFUSE_LOBE_SHARPNESS: f32 = 2.292_504;

const _: () = assert!(SPHERA_SG_MAX_SHARPNESS == MAX_SHARPNESS);

const _: () = assert!(SPHERA_SG_DIFFUSE_LOBE_SHARPNESS == DIFFUSE_LOBE_SHARPNESS);

/// The SG `amplitude · exp(sharpness (ω·axis − 1))` (axis normalised, sharpness clamped
/// to [0, SPHERA_SG_MAX_SHARPNESS], amplitude stored as its logarithm; an amplitude
/// `<= 0` or NaN gives amplitude 0). A zero or non-finite axis gives the zero SG.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_new(axis: SpheraVec3, sharpness: f32, amplitude: f32) -> Sg {
    Sg::new(axis.into(), sharpness, amplitude)
}

/// The SG's value at `dir` (normalised; 0 for a zero or non-finite `dir`).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_eval(sg: Sg, dir: SpheraVec3) -> f32 {
    sg.sanitized().eval(dir.into())
}

/// `A(λ) = 2π/λ (1 − e^{−2λ})`, the integral of an SG of amplitude 1 (`4π` at
/// `λ = 0`; NaN or negative `λ` counts as 0).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_integral(sharpness: f32) -> f32 {
    sg_integral(sharpness)
}

/// The product of two SGs, an SG (sharpness 0 when the axes cancel).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_product(a: Sg, b: Sg) -> Sg {
    a.sanitized().product(&b.sanitized())
}

/// `∫ a(ω) b(ω) dω`, the integral of the product of two SGs.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_inner_product(a: Sg, b: Sg) -> f32 {
    a.sanitized().inner_product(&b.sanitized())
}

/// The diffuse lobe `G(ω, n, λ_d)/A(λ_d)` (Eq. 1 without `R_d`); the zero SG for a zero
/// or non-finite normal.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_from_lambert(normal: SpheraVec3) -> Sg {
    diffuse_lobe_normalized(normal.into())
}

/// The GGX specular lobe of Eq. 2 without `R_s`: axis `ξ_s = 2(ω'·n)n − ω'`, sharpness
/// `(2/α²)/(4|ξ_s·n|)` (`|ξ_s·n|` at least 1e-4, `α` clamped to [1e-3, 1]), amplitude
/// `1/A(λ_s)`. `toward_incoming` is `ω'`. The zero SG for invalid vectors.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_from_ggx(
    normal: SpheraVec3,
    toward_incoming: SpheraVec3,
    alpha: f32,
) -> Sg {
    specular_lobe_normalized(normal.into(), toward_incoming.into(), alpha)
}

/// As `sphera_sg_from_ggx` with amplitude 1 (the warped unnormalised NDF).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_from_ggx_unnormalized(
    normal: SpheraVec3,
    toward_incoming: SpheraVec3,
    alpha: f32,
) -> Sg {
    specular_lobe(normal.into(), toward_incoming.into(), alpha)
}

/// The Beckmann specular lobe of Eq. 2 without `R_s`: the paper's `λ_h = 2/α²` holds
/// for Beckmann as for GGX, so this is `sphera_sg_from_ggx` with the same `α`
/// (Beckmann's roughness); the lobes differ in their error (docs/sg-error.md).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_from_beckmann(
    normal: SpheraVec3,
    toward_incoming: SpheraVec3,
    alpha: f32,
) -> Sg {
    beckmann_lobe_normalized(normal.into(), toward_incoming.into(), alpha)
}

/// As `sphera_sg_from_beckmann` with amplitude 1 (the warped unnormalised NDF).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_from_beckmann_unnormalized(
    normal: SpheraVec3,
    toward_incoming: SpheraVec3,
    alpha: f32,
) -> Sg {
    beckmann_lobe(normal.into(), toward_incoming.into(), alpha)
}

/// The incoming radiance SG of a VSGL (Eq. 6–7): `lobe` holds `c_v` (amplitude), `ξ_v` and
/// `λ_v`; `mean` is the positional mean relative to the shading point, `variance` the
/// positional variance `σ_v² = E‖y − μ‖²` (the planar Gaussian of Eq. 3 gets `σ_v²/2`, its
/// per-axis variance). A variance of 0 (or NaN, or negative) is a point light (sharpness
/// clamped, inverse-square energy kept); a mean at the shading point with variance 0, a
/// non-finite mean or an infinite variance give the zero SG.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_incoming_radiance(lobe: Sg, mean: SpheraVec3, variance: f32) -> Sg {
    incoming_radiance(&lobe, mean.into(), variance)
}

/// Diffuse shading `V R_d ∫ L_in G(ω, n, λ_d)/A(λ_d) dω` (product integral with the
/// diffuse SG). `visibility` is clamped to [0, 1] (NaN to 0), `r_d` to [0, FLT_MAX].
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_diffuse_shading_product(
    incoming: Sg,
    normal: SpheraVec3,
    r_d: f32,
    visibility: f32,
) -> f32 {
    diffuse_shading_product(&incoming, normal.into(), r_d, visibility)
}

/// Diffuse shading `V (c_in R_d/π) A(λ_in) max(ξ_in·n, 0)` (the cosine taken at the
/// lobe's axis).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_diffuse_shading_constant_cosine(
    incoming: Sg,
    normal: SpheraVec3,
    r_d: f32,
    visibility: f32,
) -> f32 {
    diffuse_shading_constant_cosine(&incoming, normal.into(), r_d, visibility)
}

/// Diffuse shading `V (2 c_in R_d/λ_in) max(ξ_in·n, 0)`: the constant-cosine form with
/// `A(λ) ≈ 2π/λ`, for `λ_in ≳ 2` only (it diverges as `λ_in → 0`; finite, at most
/// FLT_MAX).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_diffuse_shading_sharp_lobe(
    incoming: Sg,
    normal: SpheraVec3,
    r_d: f32,
    visibility: f32,
) -> f32 {
    diffuse_shading_sharp_lobe(&incoming, normal.into(), r_d, visibility)
}

/// GGX specular shading `V c_in C(ξ_in) ∫ G_in Ĝ dω` through the ASG fit of the lobe
/// (Section 4.2). `view` points toward the viewer; `α = roughness²` (clamped to
/// [1e-3, 1]); `f0` is Schlick's reflectance of one channel (clamped to [0, 1]). 0
/// when the view or `ξ_in` lies at or below the horizon.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_specular_shading(
    incoming: Sg,
    normal: SpheraVec3,
    view: SpheraVec3,
    roughness: f32,
    f0: f32,
    visibility: f32,
) -> f32 {
    specular_shading(
        &incoming,
        normal.into(),
        view.into(),
        roughness,
        f0,
        visibility,
    )
}

/// As `sphera_sg_specular_shading` with the isotropic SG fit of Eq. 2 instead of the
/// ASG.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_specular_shading_sg(
    incoming: Sg,
    normal: SpheraVec3,
    view: SpheraVec3,
    roughness: f32,
    f0: f32,
    visibility: f32,
) -> f32 {
    specular_shading_sg(
        &incoming,
        normal.into(),
        view.into(),
        roughness,
        f0,
        visibility,
    )
}

/// Beckmann specular shading: as `sphera_sg_specular_shading` with Beckmann's NDF and
/// Smith term (`α = roughness²` is Beckmann's `α`); the ASG fit is
/// `sphera_asg_from_beckmann`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_beckmann_specular_shading(
    incoming: Sg,
    normal: SpheraVec3,
    view: SpheraVec3,
    roughness: f32,
    f0: f32,
    visibility: f32,
) -> f32 {
    beckmann_specular_shading(
        &incoming,
        normal.into(),
        view.into(),
        roughness,
        f0,
        visibility,
    )
}

/// As `sphera_sg_beckmann_specular_shading` with the isotropic SG fit of Eq. 2
/// (`sphera_sg_from_beckmann_unnormalized`) instead of the ASG.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_sg_beckmann_specular_shading_sg(
    incoming: Sg,
    normal: SpheraVec3,
    view: SpheraVec3,
    roughness: f32,
    f0: f32,
    visibility: f32,
) -> f32 {
    beckmann_specular_shading_sg(
        &incoming,
        normal.into(),
        view.into(),
        roughness,
        f0,
        visibility,
    )
}
