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

/// Beckmann's unnormalised NDF `D̂ = πα² D = e^{−tan²θ/α²}/cos⁴θ` at `c = cos θ` (f64).
fn beckmann_hat(alpha: f64, c: f64) -> f64 {
    if c <= 0.0 {
        return 0.0;
    }
    let c2 = c * c;
    (-(1.0 - c2) / c2 / (alpha * alpha)).exp() / (c2 * c2)
}

/// GGX's unnormalised NDF `D̂ = πα² D = α⁴/(cos²θ (α² − 1) + 1)²` at `c = cos θ` (f64).
fn ggx_hat(alpha: f64, c: f64) -> f64 {
    let a2 = alpha * alpha;
    a2 * a2 / (c * c * (a2 - 1.0) + 1.0).powi(2)
}

/// `2π ∫₀¹ f(c) dc` (an integral over the upper hemisphere of a function of `cos θ`),
/// Simpson's rule on `t = 1 − c` with a fine panel over the lobe of width `~α²`.
fn hemisphere(alpha: f64, f: impl Fn(f64) -> f64) -> f64 {
    let m = (50.0 * alpha * alpha).min(1.0);
    let g = |t: f64| f(1.0 - t);
    let tail = if m < 1.0 {
        simpson(g, m, 1.0, 4000)
    } else {
        0.0
    };
    2.0 * PI64 * (simpson(g, 0.0, m, 4000) + tail)
}

/// Issue 20 (6): the paper's `λ_h = 2/α²` for Beckmann's NDF (Tokuyoshi 2016, Section
/// 2.1). Against Beckmann written here in f64: its projected integral is `πα²` (checking
/// the reference), the SG keeps it up to the closed-form factor
/// `1 − (α²/2)(1 − e^{−2/α²})`, and the L1 distance of the normalised projected lobes
/// (in half-vector space) is at most `0.7 α²` (0.0017 at α = 0.05, 0.14 at 0.5), where
/// GGX's is 0.28–0.41 at every `α`: the Gaussian fits Beckmann, not GGX's tail. The
/// Beckmann lobe functions are the GGX ones (no fitted constant).
#[test]
fn beckmann_lobe_keeps_beckmanns_energy_and_shape() {
    for alpha in [0.05f64, 0.1, 0.2, 0.3, 0.5, 0.7] {
        let lambda = 2.0 / (alpha * alpha);
        let sg = |c: f64| (lambda * (c - 1.0)).exp();
        let beckmann = hemisphere(alpha, |c| beckmann_hat(alpha, c) * c);
        let ggx = hemisphere(alpha, |c| ggx_hat(alpha, c) * c);
        let energy = hemisphere(alpha, |c| sg(c) * c);
        let area = PI64 * alpha * alpha;
        assert!(
            (beckmann / area - 1.0).abs() < 1e-6,
            "α {alpha}: {beckmann}"
        );
        assert!((ggx / area - 1.0).abs() < 1e-6, "α {alpha}: {ggx}");
        let kept = 1.0 - 0.5 * alpha * alpha * (1.0 - (-lambda).exp());
        assert!((energy / area - kept).abs() < 1e-6, "α {alpha}: {energy}");
        let l1 = |reference: f64, d: &dyn Fn(f64) -> f64| {
            hemisphere(alpha, |c| (d(c) / reference - sg(c) / energy).abs() * c)
        };
        let l1_beckmann = l1(beckmann, &|c| beckmann_hat(alpha, c));
        let l1_ggx = l1(ggx, &|c| ggx_hat(alpha, c));
        assert!(
            l1_beckmann <= 0.7 * alpha * alpha,
            "α {alpha}: {l1_beckmann}"
        );
        assert!(
            l1_ggx >= 0.28 && l1_beckmann < l1_ggx,
            "α {alpha}: {l1_ggx}"
        );
    }
    let mut rng = Rng::new(23);
    for _ in 0..1000 {
        let (n, wo) = (rng.unit_vector_f32(), rng.unit_vector_f32());
        let alpha = rng.log_uniform(-3.0, 0.0) as f32;
        let s = beckmann_lobe(n, wo, alpha);
        assert_eq!(s, specular_lobe(n, wo, alpha));
        assert_eq!(
            beckmann_lobe_normalized(n, wo, alpha),
            specular_lobe_normalized(n, wo, alpha)
        );
        let expected = (2.0 / (alpha as f64).powi(2))
            / (4.0 * (wo.dot(n) as f64).abs().max(MIN_SPECULAR_COSINE as f64));
        let expected = expected.min(super::sg::MAX_SHARPNESS as f64);
        assert!(((s.sharpness as f64 - expected) / expected).abs() < 1e-4);
    }
}
