//! The Lambertian BRDF `f = ρ / π` and cosine-weighted sampling of the hemisphere.
//!
//! Sampling: a point `(x, y)` uniform in the unit disk, lifted to the hemisphere,
//! `ω = (x, y, √(1 - x² - y²))`, has density `cos θ / π` per steradian (Malley's
//! method: the projection onto the disk has Jacobian `cos θ`, and the disk has area
//! `π`). The disk point comes from the concentric mapping of Shirley and Chiu 1997,
//! which maps concentric squares of `[0, 1)²` to concentric circles and so keeps the
//! stratification of the random numbers. `z` is computed as `√((1 - r)(1 + r))` from
//! the disk radius `r`, so that it keeps its relative precision near the horizon.
//!
//! Hard cases, each tested below: `u` at both ends of `[0, 1)`, outside it and NaN
//! (clamped); the centre of the disk (`u = (1/2, 1/2)`); directions at and below the
//! horizon; zero, huge and non-finite directions; albedos outside `[0, 1]` and NaN.

use super::unit;
use crate::sample::{ONE_MINUS_ULP, clamp_random};
use crate::{Sample, Vec3};
use core::f32::consts::FRAC_1_PI;

/// A point uniformly distributed in the unit disk from `u` in `[0, 1)²` by the
/// concentric mapping (Shirley and Chiu 1997): `a = 2u0 - 1`, `b = 2u1 - 1`; for
/// `|a| > |b|` the radius is `a` and the angle `π/4 · b/a`, otherwise the radius is `b`
/// and the angle `π/2 - π/4 · a/b`. The signed radius puts each wedge on its side.
/// Returns the point and its distance from the centre. `u` is clamped to
/// `[0, 1 - ulp]`; NaN counts as 0.
///
/// The square is `a = 2u0 - (1 - 2⁻²⁴)`, shifted by half an ulp of `u` so that the
/// grid of `u` maps symmetrically into the open square `(-1, 1)²`: `u = 0` would
/// otherwise land on the rim of the disk, whose lift to the hemisphere lies on the
/// horizon. The largest radius is `1 - 2⁻²⁴`.
#[inline(always)]
pub(crate) fn concentric_disk(u: [f32; 2]) -> (f32, f32, f32) {
    let a = 2.0 * clamp_random(u[0]) - ONE_MINUS_ULP;
    let b = 2.0 * clamp_random(u[1]) - ONE_MINUS_ULP;
    if a == 0.0 && b == 0.0 {
        return (0.0, 0.0, 0.0);
    }
    // The angle in quarter turns: `π/4 · b/a = π/2 · (b/(2a))`, and
    // `π/2 − π/4 · a/b = π/2 · (1 − a/(2b))`; both remainders lie in `[−1/2, 1/2]`
    // and are exact but for the division (no rounded multiple of π).
    let (radius, quarter_turns, remainder) = if a.abs() > b.abs() {
        (a, 0, 0.5 * (b / a))
    } else {
        (b, 1, -0.5 * (a / b))
    };
    let (sin, cos) = crate::math::sin_cos_of_quarter_turns(quarter_turns, remainder);
    (radius * cos, radius * sin, radius.abs())
}

/// The Lambertian (perfectly diffuse) BRDF `f = ρ / π` with albedo `ρ` per RGB
/// channel.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambert {
    /// The albedo `ρ`, each channel in `[0, 1]`.
    pub(crate) albedo: Vec3,
}

impl Default for Lambert {
    fn default() -> Self {
        Self::new(Vec3::ONE)
    }
}

impl Lambert {
    /// The BRDF with albedo `albedo`, each channel clamped to `[0, 1]` (NaN counts as
    /// 0), so that the BRDF conserves energy.
    pub fn new(albedo: Vec3) -> Lambert {
        let clamp = |x: f32| x.max(0.0).min(1.0);
        Lambert {
            albedo: Vec3::new(clamp(albedo.x), clamp(albedo.y), clamp(albedo.z)),
        }
    }

    /// The albedo `ρ`.
    #[inline]
    pub fn albedo(&self) -> Vec3 {
        self.albedo
    }

    /// `f(ωo, ωi) = ρ / π` when both directions lie above the horizon (z > 0), 0
    /// otherwise and for zero or non-finite directions.
    #[inline]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match (unit(wo), unit(wi)) {
            (Some(wo), Some(wi)) if wo.z > 0.0 && wi.z > 0.0 => self.albedo * FRAC_1_PI,
            _ => Vec3::ZERO,
        }
    }

    /// Draws `ωi` with density `cos θi / π` (see the module documentation). `u` is
    /// clamped to `[0, 1 - ulp]`; NaN counts as 0. Every `u` gives a sample strictly
    /// above the horizon: the largest disk radius, `1 - 2⁻²⁴`, leaves `z ≈ 3.5e-4`.
    #[inline]
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        let (x, y, r) = concentric_disk(u);
        let z = crate::math::sqrtf(((1.0 - r) * (1.0 + r)).max(0.0));
        if !(z > 0.0) {
            return Sample::NONE;
        }
        Sample {
            dir: Vec3::new(x, y, z),
            pdf: z * FRAC_1_PI,
        }
    }

    /// The density `max(0, cos θi) / π` with which [`sample`](Self::sample) draws `wi`
    /// (normalised first); 0 for zero or non-finite `wi`.
    #[inline]
    pub fn pdf(&self, wi: Vec3) -> f32 {
        match unit(wi) {
            Some(wi) if wi.z > 0.0 => wi.z * FRAC_1_PI,
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::*;
    use core::f64::consts::PI;

    #[test]
    fn concentric_disk_is_uniform_and_inside_the_disk() {
        // Chi-square over rings of equal area and angular sectors: each of the
        // RINGS × SECTORS cells has probability 1 / (RINGS SECTORS).
        const RINGS: usize = 16;
        const SECTORS: usize = 32;
        let mut counts = vec![0u64; RINGS * SECTORS];
        let mut rng = Rng::new(1);
        for _ in 0..1_000_000 {
            let (x, y, r) = concentric_disk([rng.uniform_f32(), rng.uniform_f32()]);
            assert!(r < 1.0 && ((x * x + y * y).sqrt() - r).abs() <= 1e-6);
            let ring = (((r as f64).powi(2) * RINGS as f64) as usize).min(RINGS - 1);
            let angle = (y as f64).atan2(x as f64).rem_euclid(2.0 * PI);
            let sector = ((angle / (2.0 * PI) * SECTORS as f64) as usize).min(SECTORS - 1);
            counts[ring * SECTORS + sector] += 1;
        }
        let probabilities = vec![1.0 / (RINGS * SECTORS) as f64; RINGS * SECTORS];
        let (_, _, p) = chi_square(&counts, &probabilities);
        assert!(p > CHI_SQUARE_ALPHA, "p = {p}");
        assert!(concentric_disk([0.5, 0.5]).2 < 1e-7);
        assert_eq!(concentric_disk([0.5 - 2f32.powi(-25); 2]), (0.0, 0.0, 0.0));
        // u = 0 and u = 1 - ulp map symmetrically inside the rim.
        let last = 1.0 - f32::EPSILON / 2.0;
        for u in [
            [0.0, 0.0],
            [last, last],
            [0.0, last],
            [last, 0.3],
            [0.3, 0.0],
        ] {
            let r = concentric_disk(u).2;
            assert!((1.0 - f32::EPSILON..1.0).contains(&r), "{u:?}: {r}");
        }
    }

    /// Chi-square of the samples against the exact probabilities of cells uniform in
    /// `(cos θ, φ)`: `∫ cos θ / π dω = (φ1 - φ0) (c1² - c0²) / (2π)` over a cell.
    #[test]
    fn samples_are_cosine_distributed_and_their_pdf_is_pdf_of_their_direction() {
        const BANDS: usize = 20;
        const SECTORS: usize = 24;
        let brdf = Lambert::new(Vec3::new(0.2, 0.5, 0.9));
        let mut counts = vec![0u64; BANDS * SECTORS];
        let mut rng = Rng::new(2);
        let mut worst = 0.0f64;
        for _ in 0..1_000_000 {
            let s = brdf.sample([rng.uniform_f32(), rng.uniform_f32()]);
            assert!(s.pdf > 0.0 && s.pdf.is_finite() && s.dir.z > 0.0);
            assert!((s.dir.length() - 1.0).abs() < 1e-6);
            assert_eq!(s.pdf, brdf.pdf(s.dir));
            let reference = s.dir.z as f64 / s.dir.length() as f64 / PI;
            worst = worst.max((s.pdf as f64 - reference).abs() / reference);
            let band = ((s.dir.z as f64 * BANDS as f64) as usize).min(BANDS - 1);
            let angle = (s.dir.y as f64).atan2(s.dir.x as f64).rem_euclid(2.0 * PI);
            let sector = ((angle / (2.0 * PI) * SECTORS as f64) as usize).min(SECTORS - 1);
            counts[band * SECTORS + sector] += 1;
        }
        let mut probabilities = Vec::new();
        for band in 0..BANDS {
            let (c0, c1) = (band as f64 / BANDS as f64, (band + 1) as f64 / BANDS as f64);
            for _ in 0..SECTORS {
                probabilities.push((2.0 * PI / SECTORS as f64) * (c1 * c1 - c0 * c0) / (2.0 * PI));
            }
        }
        let (_, _, p) = chi_square(&counts, &probabilities);
        assert!(p > CHI_SQUARE_ALPHA, "p = {p}");
        assert!(worst < 1e-5, "pdf vs f64 cos/π: {worst}");
    }

    #[test]
    fn extreme_random_numbers_give_valid_samples_near_the_horizon_and_the_pole() {
        let brdf = Lambert::default();
        let last = 1.0 - f32::EPSILON / 2.0;
        for u in [
            [0.0, 0.0],
            [last, last],
            [0.0, last],
            [last, 0.0],
            [0.5, 0.5],
            [f32::NAN, 2.0],
            [-1.0, f32::INFINITY],
            [f32::NEG_INFINITY, 0.25],
        ] {
            let s = brdf.sample(u);
            assert!(s.pdf > 0.0 && s.pdf.is_finite(), "{u:?}: {s:?}");
            assert!(s.dir.is_finite() && s.dir.z > 0.0, "{u:?}: {s:?}");
            assert!((s.dir.length() - 1.0).abs() < 1e-6, "{u:?}: {s:?}");
            assert_eq!(s.pdf, brdf.pdf(s.dir));
        }
        // The edges of the square are the rim of the disk: z ≈ sqrt(2 · 2⁻²⁴).
        for u in [[last, 0.5], [0.0, 0.5], [0.5, 0.0]] {
            let rim = brdf.sample(u);
            assert!(rim.dir.z > 3e-4 && rim.dir.z < 4e-4, "{rim:?}");
        }
        assert!(brdf.sample([0.5, 0.5]).dir.z > 1.0 - 1e-7);
    }

    #[test]
    fn eval_is_albedo_over_pi_above_the_horizon_and_zero_for_bad_input() {
        let brdf = Lambert::new(Vec3::new(0.25, 0.5, 1.0));
        let (wo, wi) = (Vec3::new(0.3, 0.1, 0.9), Vec3::new(-0.5, 0.2, 0.4));
        let f = brdf.eval(wo, wi);
        assert!((f - Vec3::new(0.25, 0.5, 1.0) / core::f32::consts::PI).length() < 1e-7);
        assert_eq!(brdf.eval(wo * 1e30, wi * 1e-30), f);
        assert_eq!(brdf.eval(wi, wo), f);
        let below = Vec3::new(0.3, 0.1, -0.9);
        let horizontal = Vec3::new(1.0, 0.0, 0.0);
        for bad in [
            below,
            horizontal,
            Vec3::ZERO,
            Vec3::new(f32::NAN, 0.0, 1.0),
            Vec3::new(0.0, 0.0, f32::INFINITY),
        ] {
            assert_eq!(brdf.eval(bad, wi), Vec3::ZERO, "{bad}");
            assert_eq!(brdf.eval(wo, bad), Vec3::ZERO, "{bad}");
            assert_eq!(brdf.pdf(bad), 0.0, "{bad}");
        }
        assert!((brdf.pdf(Vec3::new(0.0, 0.0, 7.0)) - core::f32::consts::FRAC_1_PI).abs() < 1e-7);
    }

    #[test]
    fn albedo_is_clamped_to_the_unit_interval() {
        let brdf = Lambert::new(Vec3::new(f32::NAN, -2.0, 3.0));
        assert_eq!(brdf.albedo(), Vec3::new(0.0, 0.0, 1.0));
        let brdf = Lambert::new(Vec3::new(f32::INFINITY, f32::NEG_INFINITY, 0.5));
        assert_eq!(brdf.albedo(), Vec3::new(1.0, 0.0, 0.5));
    }

    /// The estimator `f cos θi / pdf` of the albedo has zero variance: every sample
    /// contributes exactly `ρ`.
    #[test]
    fn cosine_sampling_estimates_the_albedo_without_variance() {
        let brdf = Lambert::new(Vec3::new(0.3, 0.6, 0.9));
        let wo = Vec3::new(0.5, -0.5, 0.7);
        let mut rng = Rng::new(3);
        for _ in 0..10_000 {
            let s = brdf.sample([rng.uniform_f32(), rng.uniform_f32()]);
            let weight = brdf.eval(wo, s.dir) * s.dir.z / s.pdf;
            assert!(
                (weight - brdf.albedo()).abs().max_element() < 1e-6,
                "{weight}"
            );
        }
    }
}
