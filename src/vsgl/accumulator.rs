//! The VSGL of a cluster of VPLs from plain sums (supplement Sections 3.1–3.3).
//!
//! A VPL `j` with power `Φ_j` (RGB), diffuse and specular reflectances `R_d,j`, `R_s,j`
//! (RGB) and SG reflection lobes (axis `ξ_j`, sharpness `λ_j`, Eq. 1 and Eq. 2)
//! contributes to the sums of a [`VsglTexel`]:
//!
//! | field | sum |
//! |---|---|
//! | `diffuse_power`, `specular_power` | `Σ Φ_j ∘ R_j` (RGB, per component) |
//! | `diffuse_direction`, `specular_direction` | `Σ w_j ξ̄_j`, `ξ̄_j = λ_j/(λ_j+1) ξ_j` (Toksvig) |
//! | `position` | `Σ w_j (y_j − o)` |
//! | `squared_distance` | `Σ w_j ‖y_j − o‖²` |
//! | `weight` | `Σ w_j`, `w_j = lum(Φ_j ∘ (R_d,j + R_s,j))` |
//!
//! **Colour.** The powers are RGB; every direction and position average is weighted by
//! a scalar: the Rec. 709 [`luminance`] of the RGB power, `lum(Φ ∘ R_d)` for the diffuse
//! axis, `lum(Φ ∘ R_s)` for the specular axis and `lum(Φ ∘ (R_d + R_s))` for the
//! position (the paper's `Φ R` with a scalar `R`; luminance is linear, so the weight of
//! a sum is the luminance of the summed power and the sums stay plain sums).
//!
//! **Reference point.** Positions are summed relative to a reference point `o` (the
//! accumulator's `origin`, chosen by the caller; a mip pyramid has one for all its
//! texels). The variance `σ² = E‖y − o‖² − ‖μ − o‖²` (Section 3.2, which takes
//! `o = 0`) then loses only about `ε · E‖y − o‖²` to cancellation in `f32` instead of
//! `ε · E‖y‖²`: for VPLs at 10⁴ from the world origin with unit spread, `o = 0` leaves
//! no correct digit of `σ²` while an `o` among the VPLs keeps at least four (tested).
//! Pick `o` near the VPLs (the centre of the scene or of the light's view).
//! A cluster far from `o` still loses digits in the same way: with one `o` for a
//! whole RSM, a small cluster at distance `D` from `o` keeps about
//! `log10(σ²/(ε D²))` digits of its variance.
//!
//! **Compensation.** Each field's running sum in a [`VsglAccumulator`] is kept as the
//! triple (`sums`, `compensation`, `second_compensation`): the rounded sum, the sum of the
//! rounding errors of its additions (each exact by Knuth's TwoSum, and summed by TwoSum
//! too), and the sum of that sum's rounding errors. This is Ogita, Rump and Oishi's SumK
//! with K = 3, applied online: for the non-negative sums (powers, weights, squared
//! distances) the relative error after `n` additions is at most about `ε + (n ε)³` (ε =
//! 2⁻²³), where plain `f32` sums drift by up to `n ε`. Measured: a million identical VPLs
//! added one by one give the VSGL of one VPL, the mean within 1.1e-7 of its distance and
//! the powers within 2.1e-7 (plain sums: a mean 3e-2 off and a spread of 11% of the
//! distance; with one level of compensation, 3e-5 and 5e-5; tested).

use crate::sg::{Sg, diffuse_lobe_normalized, sg_integral, specular_lobe_normalized};
use glam::Vec3;

/// The Rec. 709 / sRGB luminance weights.
const LUMINANCE_WEIGHTS: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// The luminance `0.2126 r + 0.7152 g + 0.0722 b` (Rec. 709) of an RGB power.
#[inline]
pub fn luminance(rgb: Vec3) -> f32 {
    rgb.dot(LUMINANCE_WEIGHTS)
}

/// A virtual point light: a point `y` on a surface lit by a photon of power `Φ` that
/// arrived from `toward_incoming` (`ω'`, pointing away from the surface).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vpl {
    /// World position `y`.
    pub position: Vec3,
    /// Surface normal `n` (normalised on use).
    pub normal: Vec3,
    /// Photon power `Φ` (RGB, negative or NaN channels count as 0).
    pub power: Vec3,
    /// Diffuse reflectance `R_d` (RGB, negative or NaN channels count as 0).
    pub diffuse_reflectance: Vec3,
    /// Specular reflectance `R_s` (RGB, negative or NaN channels count as 0).
    pub specular_reflectance: Vec3,
    /// Unit direction toward the light the photon came from, `ω'` (normalised on use).
    pub toward_incoming: Vec3,
    /// GGX/Beckmann roughness `α` of the specular lobe (raised to `1e-4`).
    pub roughness: f32,
}

/// The sums of a cluster of VPLs (tabled in the docs of `sphera::vsgl::accumulator`),
/// relative to a reference point `o` kept outside the texel. This is what a texel of
/// the mip pyramid stores: a texel of level `l + 1` is the field-wise sum of its four
/// children.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct VsglTexel {
    /// `Σ Φ ∘ R_d` (RGB).
    pub diffuse_power: Vec3,
    /// `Σ Φ ∘ R_s` (RGB).
    pub specular_power: Vec3,
    /// `Σ lum(Φ ∘ R_d) ξ̄_d` with `ξ̄ = λ/(λ+1) ξ`.
    pub diffuse_direction: Vec3,
    /// `Σ lum(Φ ∘ R_s) ξ̄_s` with `ξ̄ = λ/(λ+1) ξ`.
    pub specular_direction: Vec3,
    /// `Σ w (y − o)`, `w = lum(Φ ∘ (R_d + R_s))`.
    pub position: Vec3,
    /// `Σ w ‖y − o‖²`.
    pub squared_distance: f32,
    /// `Σ w`: also the importance `p` of filtered importance sampling.
    pub weight: f32,
}

impl VsglTexel {
    /// No VPL.
    /// cbindgen:ignore
    pub const ZERO: VsglTexel = VsglTexel {
        diffuse_power: Vec3::ZERO,
        specular_power: Vec3::ZERO,
        diffuse_direction: Vec3::ZERO,
        specular_direction: Vec3::ZERO,
        position: Vec3::ZERO,
        squared_distance: 0.0,
        weight: 0.0,
    };

    /// The sums of a single VPL relative to `origin`, or `None` when the VPL has a
    /// non-finite position, normal, direction or roughness, a zero normal or direction,
    /// or sums that overflow `f32`. A VPL without power gives the zero texel.
    pub fn from_vpl(vpl: &Vpl, origin: Vec3) -> Option<VsglTexel> {
        let normal = crate::math::unit(vpl.normal)?;
        let toward_incoming = crate::math::unit(vpl.toward_incoming)?;
        if !vpl.position.is_finite() || !vpl.roughness.is_finite() || !origin.is_finite() {
            return None;
        }
        // `Vec3::max` is `f32::max` per channel, which maps NaN to 0.
        let power = vpl.power.max(Vec3::ZERO);
        let diffuse_power = power * vpl.diffuse_reflectance.max(Vec3::ZERO);
        let specular_power = power * vpl.specular_reflectance.max(Vec3::ZERO);
        let diffuse_weight = luminance(diffuse_power);
        let specular_weight = luminance(specular_power);
        let weight = diffuse_weight + specular_weight;
        let diffuse = diffuse_lobe_normalized(normal);
        let specular =
            specular_lobe_normalized(normal, toward_incoming, vpl.roughness.max(MIN_ROUGHNESS));
        let offset = vpl.position - origin;
        let texel = VsglTexel {
            diffuse_power,
            specular_power,
            diffuse_direction: diffuse_weight * toksvig_mean_direction(&diffuse),
            specular_direction: specular_weight * toksvig_mean_direction(&specular),
            position: weight * offset,
            squared_distance: weight * offset.length_squared(),
            weight,
        };
        texel.is_finite().then_some(texel)
    }

    /// The field-wise sum (the mip texel of four children is `a + b + c + d`).
    pub fn add(&self, other: &VsglTexel) -> VsglTexel {
        VsglTexel {
            diffuse_power: self.diffuse_power + other.diffuse_power,
            specular_power: self.specular_power + other.specular_power,
            diffuse_direction: self.diffuse_direction + other.diffuse_direction,
            specular_direction: self.specular_direction + other.specular_direction,
            position: self.position + other.position,
            squared_distance: self.squared_distance + other.squared_distance,
            weight: self.weight + other.weight,
        }
    }

    /// The field-wise sum and its rounding error per component (Knuth's TwoSum):
    /// `self + other == sum + error` exactly, barring overflow.
    pub(crate) fn two_sum(&self, other: &VsglTexel) -> (VsglTexel, VsglTexel) {
        let pair = |a: f32, b: f32| crate::math::two_sum(a, b);
        let vec = |a: Vec3, b: Vec3| {
            let (x, y, z) = (pair(a.x, b.x), pair(a.y, b.y), pair(a.z, b.z));
            (Vec3::new(x.0, y.0, z.0), Vec3::new(x.1, y.1, z.1))
        };
        let (diffuse_power, e0) = vec(self.diffuse_power, other.diffuse_power);
        let (specular_power, e1) = vec(self.specular_power, other.specular_power);
        let (diffuse_direction, e2) = vec(self.diffuse_direction, other.diffuse_direction);
        let (specular_direction, e3) = vec(self.specular_direction, other.specular_direction);
        let (position, e4) = vec(self.position, other.position);
        let (squared_distance, e5) = pair(self.squared_distance, other.squared_distance);
        let (weight, e6) = pair(self.weight, other.weight);
        (
            VsglTexel {
                diffuse_power,
                specular_power,
                diffuse_direction,
                specular_direction,
                position,
                squared_distance,
                weight,
            },
            VsglTexel {
                diffuse_power: e0,
                specular_power: e1,
                diffuse_direction: e2,
                specular_direction: e3,
                position: e4,
                squared_distance: e5,
                weight: e6,
            },
        )
    }

    /// Every sum multiplied by `factor` (a filter weight).
    pub fn scaled(&self, factor: f32) -> VsglTexel {
        VsglTexel {
            diffuse_power: self.diffuse_power * factor,
            specular_power: self.specular_power * factor,
            diffuse_direction: self.diffuse_direction * factor,
            specular_direction: self.specular_direction * factor,
            position: self.position * factor,
            squared_distance: self.squared_distance * factor,
            weight: self.weight * factor,
        }
    }

    /// Whether the sums can be those of VPLs: every sum finite, and the powers, the
    /// weight and the squared distances non-negative (per channel; NaN fails).
    pub fn is_valid_sum(&self) -> bool {
        self.is_finite()
            && self.diffuse_power.min_element() >= 0.0
            && self.specular_power.min_element() >= 0.0
            && self.weight >= 0.0
            && self.squared_distance >= 0.0
    }

    /// Whether every sum is finite.
    pub fn is_finite(&self) -> bool {
        self.diffuse_power.is_finite()
            && self.specular_power.is_finite()
            && self.diffuse_direction.is_finite()
            && self.specular_direction.is_finite()
            && self.position.is_finite()
            && self.squared_distance.is_finite()
            && self.weight.is_finite()
    }

    /// The same sums relative to `new_origin` instead of `origin`: with `d = o − o'`,
    /// `Σ w (y − o') = Σ w (y − o) + W d` and
    /// `Σ w ‖y − o'‖² = Σ w ‖y − o‖² + 2 d · Σ w (y − o) + W ‖d‖²`.
    pub fn moved(&self, origin: Vec3, new_origin: Vec3) -> VsglTexel {
        let d = origin - new_origin;
        VsglTexel {
            position: self.position + self.weight * d,
            squared_distance: self.squared_distance
                + 2.0 * d.dot(self.position)
                + self.weight * d.length_squared(),
            ..*self
        }
    }
}

/// Roughness below this is raised to it (the lobe sharpness is clamped anyway).
const MIN_ROUGHNESS: f32 = 1e-4;

/// Toksvig's mean direction of a normalised SG, `ξ̄ = λ/(λ+1) ξ` (supplement Section
/// 3.1), with the axis normalised (a zero axis gives a zero mean direction).
fn toksvig_mean_direction(lobe: &Sg) -> Vec3 {
    let lambda = lobe.sharpness.max(0.0);
    let length = if lambda > 1e30 {
        1.0
    } else {
        lambda / (lambda + 1.0)
    };
    crate::math::normalize_or_zero(lobe.axis) * length
}

/// A virtual spherical Gaussian light (supplement Sections 3.1–3.2): the radiant intensity
/// `I_v(ω) = diffuse_power ∘ diffuse(ω) + specular_power ∘ specular(ω)` of a cluster with
/// normalised SGs (amplitude `1/A(λ_v)`, so the paper's `c_v` is `power / A(λ_v)` per RGB
/// channel) and its positions as an isotropic Gaussian. An empty cluster (no power, or sums
/// that are not finite) has both powers zero, like [`Vsgl::EMPTY`].
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vsgl {
    /// Normalised SG of the diffuse radiant intensity: axis `ξ_v`, sharpness `λ_v`.
    pub diffuse: Sg,
    /// Normalised SG of the specular radiant intensity.
    pub specular: Sg,
    /// `Σ Φ ∘ R_d` (RGB).
    pub diffuse_power: Vec3,
    /// `Σ Φ ∘ R_s` (RGB).
    pub specular_power: Vec3,
    /// The weighted mean position `μ_v`.
    pub mean: Vec3,
    /// The positional variance `σ_v²` (Section 3.2). 0 for a single VPL or a cluster
    /// whose spread is below the `f32` rounding of the sums: the shading must treat
    /// `σ² = 0` as a point light (the limit `λ_σ → ∞` of Eq. 6).
    pub variance: f32,
}

impl Vsgl {
    /// The largest sharpness `λ_v` (`2²⁰`): Toksvig's `|ξ̄| = λ/(λ+1)` cannot resolve
    /// sharper lobes in `f32`.
    /// cbindgen:ignore
    pub const MAX_SHARPNESS: f32 = 1_048_576.0;

    /// No light: zero powers, uniform lobes around +z, mean at the origin.
    /// cbindgen:ignore
    pub const EMPTY: Vsgl = Vsgl {
        diffuse: UNIFORM_SG,
        specular: UNIFORM_SG,
        diffuse_power: Vec3::ZERO,
        specular_power: Vec3::ZERO,
        mean: Vec3::ZERO,
        variance: 0.0,
    };

    /// Whether the VSGL carries no power.
    pub fn is_empty(&self) -> bool {
        !(luminance(self.diffuse_power + self.specular_power) > 0.0)
    }

    /// The radiant intensity `I_v(dir)` (RGB) for a unit direction (Section 3.1).
    pub fn intensity(&self, dir: Vec3) -> Vec3 {
        self.diffuse_power * self.diffuse.eval(dir) + self.specular_power * self.specular.eval(dir)
    }
}

/// `1/(4π)` on the whole sphere: the normalised SG of sharpness 0.
const UNIFORM_SG: Sg = Sg {
    axis: Vec3::Z,
    sharpness: 0.0,
    // ln(1/(4π))
    log_amplitude: -2.531_024_2,
};

/// Sums VPLs, mip texels or other accumulators into one VSGL. Allocation-free and `Copy`;
/// the sums are relative to `origin`, a point the caller picks near the VPLs, and carry two
/// levels of compensation (relative error about `ε + (n ε)³` after `n` additions, where
/// plain `f32` sums drift by `n ε`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VsglAccumulator {
    /// The sums so far, rounded.
    pub sums: VsglTexel,
    /// The reference point `o` of the sums.
    pub origin: Vec3,
    /// The rounding errors of the additions into `sums`: the sums to full precision are
    /// `sums + compensation`.
    pub compensation: VsglTexel,
    /// The rounding errors of the additions into `compensation`.
    pub second_compensation: VsglTexel,
}

impl VsglAccumulator {
    /// An empty accumulator whose sums are taken relative to `origin` (a non-finite
    /// origin counts as the world origin).
    pub fn new(origin: Vec3) -> VsglAccumulator {
        VsglAccumulator {
            sums: VsglTexel::ZERO,
            origin: if origin.is_finite() {
                origin
            } else {
                Vec3::ZERO
            },
            compensation: VsglTexel::ZERO,
            second_compensation: VsglTexel::ZERO,
        }
    }

    /// Adds one VPL; returns `false` (and adds nothing) when [`VsglTexel::from_vpl`]
    /// rejects it.
    pub fn add_vpl(&mut self, vpl: &Vpl) -> bool {
        match VsglTexel::from_vpl(vpl, self.origin) {
            Some(texel) => self.add_sums(&texel),
            None => false,
        }
    }

    /// Adds pre-summed sums (a mip texel) taken relative to this accumulator's origin;
    /// returns `false` (and adds nothing) when they are not valid sums of VPLs
    /// ([`VsglTexel::is_valid_sum`]: a non-finite sum, a negative power, weight or
    /// squared distance) or when the total would overflow.
    pub fn add_texel(&mut self, texel: &VsglTexel) -> bool {
        self.add_texel_scaled(texel, 1.0)
    }

    /// Adds `factor` times a texel (a filter weight); `false` (adding nothing) when the
    /// product is not a valid sum or the total would overflow.
    pub fn add_texel_scaled(&mut self, texel: &VsglTexel, factor: f32) -> bool {
        let scaled = texel.scaled(factor);
        scaled.is_valid_sum() && self.add_sums(&scaled)
    }

    /// Adds valid sums unless the total overflows (found by fuzzing: texels near
    /// `f32::MAX` made the totals infinite, and negative powers made negative VSGLs).
    fn add_sums(&mut self, sums: &VsglTexel) -> bool {
        let (total, error) = self.sums.two_sum(sums);
        if !total.is_valid_sum() {
            return false;
        }
        self.sums = total;
        // Finite: TwoSum is error-free where the total is finite. The errors are summed
        // with TwoSum too, and that sum's own errors plainly (Sum3).
        let (compensation, second) = self.compensation.two_sum(&error);
        self.compensation = compensation;
        self.second_compensation = self.second_compensation.add(&second);
        true
    }

    /// `sums + compensation`, rounded once: the sums to full precision.
    fn corrected_sums(&self) -> VsglTexel {
        let corrected = self
            .sums
            .add(&self.compensation.add(&self.second_compensation));
        // A compensation from a corrupted or overflowing value must not turn valid sums
        // invalid: then the rounded sums are used.
        if corrected.is_valid_sum() {
            corrected
        } else {
            self.sums
        }
    }

    /// Adds the sums of `other`, moved from its origin to this one
    /// ([`VsglTexel::moved`]); `false` when they are not finite.
    pub fn merge(&mut self, other: &VsglAccumulator) -> bool {
        let mut moved = other.corrected_sums().moved(other.origin, self.origin);
        // Non-negative in exact arithmetic; rounding may leave a tiny negative value.
        moved.squared_distance = moved.squared_distance.max(0.0);
        moved.is_finite() && self.add_sums(&moved)
    }

    /// The VSGL of the sums (supplement Sections 3.1–3.2):
    ///
    /// - per component, `ξ̄_v = Σ w ξ̄ / Σ w`, `ξ_v = ξ̄_v/‖ξ̄_v‖`,
    ///   `λ_v = ‖ξ̄_v‖/(1 − ‖ξ̄_v‖)` clamped to `[0, MAX_SHARPNESS]` (`λ_v = 0` and
    ///   `ξ_v = +z` when `ξ̄_v = 0`, e.g. opposing lobes), amplitude `1/A(λ_v)`;
    /// - `μ_v = o + Σ w (y − o) / W`,
    ///   `σ_v² = Σ w ‖y − o‖² / W − ‖μ_v − o‖²`, set to 0 when below `16 ε` times
    ///   `Σ w ‖y − o‖² / W` (rounding noise of the difference).
    ///
    /// [`Vsgl::EMPTY`] (with `mean = origin`) when the total weight `W` is not positive
    /// or a sum is not finite.
    pub fn finish(&self) -> Vsgl {
        let sums = &self.corrected_sums();
        let weight = sums.weight;
        if !(weight > 0.0) || !sums.is_finite() {
            return Vsgl {
                mean: self.origin,
                ..Vsgl::EMPTY
            };
        }
        let offset = sums.position / weight;
        let mean_square = sums.squared_distance / weight;
        let variance = mean_square - offset.length_squared();
        let noise = 16.0 * f32::EPSILON * mean_square;
        let vsgl = Vsgl {
            diffuse: filtered_lobe(sums.diffuse_power, sums.diffuse_direction),
            specular: filtered_lobe(sums.specular_power, sums.specular_direction),
            diffuse_power: sums.diffuse_power,
            specular_power: sums.specular_power,
            mean: self.origin + offset,
            variance: if variance > noise { variance } else { 0.0 },
        };
        // A tiny weight under large position sums overflows the mean or the variance.
        if vsgl.mean.is_finite()
            && vsgl.variance.is_finite()
            && vsgl.diffuse.log_amplitude.is_finite()
            && vsgl.specular.log_amplitude.is_finite()
        {
            vsgl
        } else {
            Vsgl {
                mean: self.origin,
                ..Vsgl::EMPTY
            }
        }
    }
}

/// The normalised SG of Toksvig's filtering from `Σ Φ R` and `Σ w ξ̄` (Section 3.1).
fn filtered_lobe(power: Vec3, direction_sum: Vec3) -> Sg {
    let weight = luminance(power);
    if !(weight > 0.0) {
        return UNIFORM_SG;
    }
    let mean_direction = direction_sum / weight;
    let length = crate::math::length(mean_direction);
    let max_length = Vsgl::MAX_SHARPNESS / (Vsgl::MAX_SHARPNESS + 1.0);
    let sharpness = if !(length > 0.0) {
        0.0
    } else if length >= max_length {
        Vsgl::MAX_SHARPNESS
    } else {
        length / (1.0 - length)
    };
    let axis = if length > 0.0 {
        crate::math::normalize_or(mean_direction / length, Vec3::Z)
    } else {
        Vec3::Z
    };
    Sg::new(axis, sharpness, 1.0 / sg_integral(sharpness))
}
