use super::lobes::*;
use super::sg::sg_integral;
use crate::Vec3;
use crate::testing::Rng;
use core::f64::consts::PI as PI64;

/// `A(λ)` in f64 from its definition's closed form.
fn a64(l: f64) -> f64 {
    2.0 * PI64 / l * (1.0 - (-2.0 * l).exp())
}

/// Simpson's rule of `f` on `[a, b]` with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for i in 1..n {
        s += if i % 2 == 1 { 4.0 } else { 2.0 } * f(a + i as f64 * h);
    }
    s * h / 3.0
}

/// `E(λ)` of the module documentation (L2 error squared), and the L1 error.
fn errors(l: f64) -> (f64, f64) {
    let d = |c: f64| c.max(0.0) / PI64 - (l * (c - 1.0)).exp() / a64(l);
    let l2 = 2.0
        * PI64
        * (simpson(|c| d(c) * d(c), -1.0, 0.0, 2000) + simpson(|c| d(c) * d(c), 0.0, 1.0, 2000));
    let l1 = 2.0
        * PI64
        * (simpson(|c| d(c).abs(), -1.0, 0.0, 20000) + simpson(|c| d(c).abs(), 0.0, 1.0, 20000));
    (l2, l1)
}

#[test]
fn diffuse_sharpness_minimises_the_l2_error() {
    // Golden section search for the minimiser of E on [1, 4].
    let (mut a, mut b) = (1.0f64, 4.0f64);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..60 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if errors(c).0 < errors(d).0 {
            b = d
        } else {
            a = c
        }
    }
    let optimum = 0.5 * (a + b);
    assert!(
        (optimum - DIFFUSE_LOBE_SHARPNESS as f64).abs() < 1e-4,
        "{optimum}"
    );
    let (l2, l1) = errors(DIFFUSE_LOBE_SHARPNESS as f64);
    let norm = (2.0 * PI64 / 3.0).sqrt() / PI64;
    // The figures stated in the module documentation.
    assert!(
        (l2.sqrt() / norm - 0.187).abs() < 5e-4,
        "{}",
        l2.sqrt() / norm
    );
    assert!((l1 - 0.258).abs() < 5e-4, "{l1}");
    assert!(errors(2.0).0 > l2 && errors(2.6).0 > l2);
}

#[test]
fn normalised_lobes_integrate_to_one() {
    let mut rng = Rng::new(21);
    for _ in 0..1000 {
        let n = rng.unit_vector_f32();
        let d = diffuse_lobe_normalized(n);
        assert!((d.integral() - 1.0).abs() < 1e-5);
        assert_eq!(d.axis, n);
        let wo = rng.unit_vector_f32();
        let alpha = rng.log_uniform(-3.0, 0.0) as f32;
        let s = specular_lobe_normalized(n, wo, alpha);
        assert!((s.integral() - 1.0).abs() < 1e-5, "{s:?}");
    }
}

#[test]
fn specular_lobe_is_the_warped_ndf_sg() {
    let mut rng = Rng::new(22);
    for _ in 0..1000 {
        let n = rng.unit_vector_f32();
        let wo = rng.unit_vector_f32();
        let alpha = rng.log_uniform(-2.0, 0.0) as f32;
        let s = specular_lobe(n, wo, alpha);
        let c = wo.dot(n) as f64;
        let xi = n * (2.0 * wo.dot(n)) - wo;
        assert!((s.axis - xi).length() < 1e-5);
        assert!((s.axis.dot(n) as f64 - c).abs() < 1e-5);
        let expected =
            (2.0 / (alpha as f64 * alpha as f64)) / (4.0 * c.abs().max(MIN_SPECULAR_COSINE as f64));
        let expected = expected.min(super::sg::MAX_SHARPNESS as f64);
        assert!(
            ((s.sharpness as f64 - expected) / expected).abs() < 1e-4,
            "{} vs {expected}",
            s.sharpness
        );
        assert_eq!(s.log_amplitude, 0.0);
    }
    // Grazing view: the clamp keeps λ_s finite; at α = 0.05 that is 2/α²/(4·1e-4) = 2e6.
    let grazing = specular_lobe(Vec3::Z, Vec3::new(1.0, 0.0, 0.0), 0.05);
    assert!((grazing.sharpness - 2e6).abs() < 2.0);
    assert!(sg_integral(grazing.sharpness) > 0.0);
    // Bad input.
    for bad in [
        Vec3::ZERO,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::splat(f32::INFINITY),
    ] {
        assert_eq!(specular_lobe(bad, Vec3::Z, 0.5), super::sg::Sg::ZERO);
        assert_eq!(
            specular_lobe_normalized(Vec3::Z, bad, 0.5),
            super::sg::Sg::ZERO
        );
        assert_eq!(diffuse_lobe_normalized(bad), super::sg::Sg::ZERO);
    }
    for alpha in [f32::NAN, -1.0, 0.0, f32::INFINITY] {
        let s = specular_lobe_normalized(Vec3::Z, Vec3::new(0.0, 0.6, 0.8), alpha);
        assert!(s.sharpness.is_finite() && s.log_amplitude.is_finite() && s.sharpness > 0.0);
    }
}
