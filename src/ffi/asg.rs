//! C ABI, `sphera_asg_*`: anisotropic spherical Gaussians (Tokuyoshi 2016, supplement).
use super::types::SpheraVec3;
use crate::sg::asg::Asg;
use crate::sg::sg::Sg;

/// The ASG `amplitude · max(ω·z, 0) · exp(−η_x (ω·x)² − η_y (ω·y)²)` with `z`
/// normalised, `x` made orthogonal to it and `y = z × x`; bandwidths clamped to
/// [0, SPHERA_SG_MAX_SHARPNESS], amplitude to [0, FLT_MAX] (NaN to 0). The zero ASG for
/// a zero or non-finite `z`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_asg_new(
    x: SpheraVec3,
    z: SpheraVec3,
    eta_x: f32,
    eta_y: f32,
    amplitude: f32,
) -> Asg {
    Asg::new(x.into(), z.into(), eta_x, eta_y, amplitude)
}

/// The ASG's value at `dir` (normalised; 0 for a zero or non-finite `dir`).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_asg_eval(asg: Asg, dir: SpheraVec3) -> f32 {
    asg.sanitized().eval(dir.into())
}

/// The approximate integral `a π/√(η_x η_y)`, at most `a π` (accurate to 1 % for
/// bandwidths above ~4.6; too high for small ones).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_asg_integral(asg: Asg) -> f32 {
    asg.sanitized().integral()
}

/// `∫ G Ĝ dω` for an SG `c e^{λ(ω·ξ − 1)}` and an ASG by the boxed formula of Section
/// 4.2, `c π Ĝ(ξ; η_x ν/(η_x + ν), η_y ν/(η_y + ν)) / √((η_x + ν)(η_y + ν))` with
/// `ν = λ/2`, except that the factor `1/√((η_x + ν)(η_y + ν))` is capped at 1 (where
/// `(η_x + ν)(η_y + ν) < 1`), as `sphera_asg_integral` caps at `a π`: the result is at
/// most `c a π`. 0 when the SG's axis lies at or behind the ASG's horizon (`ξ·z ≤ 0`).
#[unsafe(no_mangle)]
pub extern "C" fn sphera_asg_convolve_sg(asg: Asg, sg: Sg) -> f32 {
    asg.sanitized().convolve_sg(&sg.sanitized())
}

/// The ASG fit (amplitude 1) of GGX's warped unnormalised NDF at a shading point:
/// `z` the reflection of `view` about `normal`, `η_x = 1/(4α²)` in the plane of
/// incidence and `η_y = 1/(4α² cos²θ_o)` across it. The zero ASG for invalid vectors.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_asg_from_ggx(normal: SpheraVec3, view: SpheraVec3, alpha: f32) -> Asg {
    Asg::from_ggx(normal.into(), view.into(), alpha)
}

/// The ASG fit (amplitude 1) of Beckmann's warped unnormalised NDF at a shading point:
/// built from the same `λ_h = 2/α²`, so the same ASG as `sphera_asg_from_ggx`.
#[unsafe(no_mangle)]
pub extern "C" fn sphera_asg_from_beckmann(
    normal: SpheraVec3,
    view: SpheraVec3,
    alpha: f32,
) -> Asg {
    Asg::from_beckmann(normal.into(), view.into(), alpha)
}
