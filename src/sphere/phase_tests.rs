//! Tests of the phase functions against f64 references written here: closed-form CDFs
//! in `μ` for the chi-square tests, quadratures for normalisation and mean cosines.
use super::*;
use crate::testing::*;

const GS: [f32; 8] = [-0.95, -0.5, 0.0, 1e-3, 0.3, 0.7, 0.95, 0.999];

/// `f_pivot(μ)` in f64.
fn pivot_f64(mu: f64, g: f64) -> f64 {
    let r = (1.0 - g * g) / (1.0 + g * g - 2.0 * g * mu);
    r * r / (4.0 * core::f64::consts::PI)
}

fn hg_f64(mu: f64, g: f64) -> f64 {
    (1.0 - g * g) / (1.0 + g * g - 2.0 * g * mu).powf(1.5) / (4.0 * core::f64::consts::PI)
}

/// `∫_{-1}^{1} 2π h(μ) dμ` by the composite Simpson rule, refined towards `μ = ±1` by
/// the substitution `μ = sin(πt/2)`.
fn integrate(h: impl Fn(f64) -> f64) -> f64 {
    let n = 200_000;
    let mut sum = 0.0;
    for i in 0..=n {
        let t = -1.0 + 2.0 * i as f64 / n as f64;
        let mu = (core::f64::consts::FRAC_PI_2 * t).sin();
        let jacobian = core::f64::consts::FRAC_PI_2 * (core::f64::consts::FRAC_PI_2 * t).cos();
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        sum += w * h(mu) * jacobian;
    }
    sum * (2.0 / n as f64) / 3.0 * 2.0 * core::f64::consts::PI
}

/// Chi-square of sampled `μ` in `bins` bins of equal width against the probabilities
/// `cdf(μ_{k+1}) − cdf(μ_k)`; also checks every sample's pdf against `density(μ)`.
fn check_sampler(
    what: &str,
    sample: impl Fn([f32; 2]) -> Sample,
    cdf: impl Fn(f64) -> f64,
    density: impl Fn(f64) -> f64,
) {
    let bins = 64;
    let mut counts = vec![0u64; bins];
    let mut rng = Rng::new(21);
    for _ in 0..400_000 {
        let s = sample([rng.uniform_f32(), rng.uniform_f32()]);
        assert!(
            s.dir.is_finite() && s.pdf > 0.0 && s.pdf.is_finite(),
            "{what}: {s:?}"
        );
        let mu = (s.dir.z as f64).clamp(-1.0, 1.0);
        let expected = density(mu);
        assert!(
            (s.pdf as f64 - expected).abs() <= 2e-3 * expected + 1e-6,
            "{what}: pdf {} vs {expected} at μ = {mu}",
            s.pdf
        );
        let bin = (((mu + 1.0) / 2.0 * bins as f64) as usize).min(bins - 1);
        counts[bin] += 1;
    }
    let probabilities: Vec<f64> = (0..bins)
        .map(|k| {
            let lo = -1.0 + 2.0 * k as f64 / bins as f64;
            cdf(lo + 2.0 / bins as f64) - cdf(lo)
        })
        .collect();
    let (_, _, p) = chi_square(&counts, &probabilities);
    assert!(p > CHI_SQUARE_ALPHA, "{what}: p = {p}");
}

#[test]
fn phase_functions_are_normalised() {
    for g in GS {
        let pivot = integrate(|mu| pivot_phase(mu as f32, g) as f64);
        let hg = integrate(|mu| henyey_greenstein(mu as f32, g) as f64);
        // The sharpest (g = 0.999) peaks over 1 − μ ≈ 5e-7, about 8 f32 steps of μ: the
        // quadrature of the f32 function is then within 5e-3.
        let tolerance = if g.abs() > 0.99 { 5e-3 } else { 1e-5 };
        assert!((pivot - 1.0).abs() < tolerance, "pivot g = {g}: {pivot}");
        assert!((hg - 1.0).abs() < tolerance, "HG g = {g}: {hg}");
    }
}

#[test]
fn pivot_phase_samples_follow_eq_25() {
    for g in GS {
        let gd = g as f64;
        // CDF: (1 − g²)²/(2b) (1/(a − bμ) − 1/(a + b)), a = 1 + g², b = 2g.
        let cdf = |mu: f64| {
            if gd == 0.0 {
                return (mu + 1.0) / 2.0;
            }
            let (a, b) = (1.0 + gd * gd, 2.0 * gd);
            (1.0 - gd * gd).powi(2) / (2.0 * b) * (1.0 / (a - b * mu) - 1.0 / (a + b))
        };
        // Around +z, so that μ is the sample's z without a rounding round trip (near the
        // peak of g = 0.999 one ulp of μ moves the density by 10%).
        check_sampler(
            &format!("pivot g = {g}"),
            |u| sample_pivot_phase(Vec3::Z, g, u),
            cdf,
            |mu| pivot_f64(mu, gd),
        );
        let wo = Vec3::new(0.3, -0.2, 0.9).normalize();
        let mut rng = Rng::new(4);
        for _ in 0..1000 {
            let s = sample_pivot_phase(wo, g, [rng.uniform_f32(), rng.uniform_f32()]);
            assert!((s.dir.length() - 1.0).abs() < 1e-5 && s.pdf > 0.0);
        }
    }
}

#[test]
fn henyey_greenstein_samples_follow_eq_26() {
    for g in GS {
        let gd = g as f64;
        // CDF: (1 − g²)/(2g) (1/√(a − bμ) − 1/(1 + g)).
        let cdf = |mu: f64| {
            if gd.abs() < 1e-4 {
                return (mu + 1.0) / 2.0;
            }
            (1.0 - gd * gd) / (2.0 * gd)
                * (1.0 / (1.0 + gd * gd - 2.0 * gd * mu).sqrt() - 1.0 / (1.0 + gd))
        };
        let wo = Vec3::Z;
        check_sampler(
            &format!("HG g = {g}"),
            |u| sample_henyey_greenstein(wo, g, u),
            cdf,
            |mu| hg_f64(mu, gd),
        );
    }
}

#[test]
fn pivot_mean_cosine_matches_a_quadrature_and_is_not_g() {
    for g in [
        -0.9f32, -0.49, -0.1, 1e-6, 1e-3, 0.2, 0.499, 0.501, 0.8, 0.99,
    ] {
        let gd = g as f64;
        let reference = integrate(|mu| mu * pivot_f64(mu, gd));
        let mean = pivot_mean_cosine(g) as f64;
        assert!(
            (mean - reference).abs() <= 1e-5 * reference.abs() + 1e-12,
            "g = {g}: {mean} vs quadrature {reference}"
        );
    }
    assert_eq!(pivot_mean_cosine(0.0), 0.0);
    assert!((pivot_mean_cosine(1e-3) / 1e-3 - 4.0 / 3.0).abs() < 1e-5);
    assert!((pivot_mean_cosine(MAX_ANISOTROPY) - 1.0).abs() < 1e-4);
}

#[test]
fn the_henyey_greenstein_fit_is_odd_monotone_and_below_one() {
    assert_eq!(pivot_from_henyey_greenstein(0.0), 0.0);
    let mut previous = -1.0;
    for k in -100..=100 {
        let g = k as f32 / 100.0;
        let p = pivot_from_henyey_greenstein(g);
        assert!(p.abs() < 1.0 && p > previous, "g = {g}: {p}");
        assert_eq!(p, -pivot_from_henyey_greenstein(-g));
        previous = p;
    }
    // The fit keeps the mean cosine for weak anisotropy and falls behind for strong.
    for (g, mean) in [
        (0.1f32, 0.1f32),
        (0.3, 0.2985),
        (0.5, 0.4898),
        (0.9, 0.8181),
        (0.99, 0.8739),
    ] {
        let fitted = pivot_mean_cosine(pivot_from_henyey_greenstein(g));
        assert!((fitted - mean).abs() < 5e-4, "g = {g}: {fitted}");
    }
    // Eq. 28 at g = 0.9: (0.7489·0.9 − 0.6121·0.81) / (1 − 0.8409·0.9 + 0.0223·0.81).
    let expected = (0.7489 * 0.9 - 0.6121 * 0.81) / (1.0 - 0.8409 * 0.9 + 0.0223 * 0.81);
    assert!((pivot_from_henyey_greenstein(0.9) - expected).abs() < 1e-6);
}

#[test]
fn bad_input_stays_finite() {
    for g in [f32::NAN, f32::INFINITY, -2.0, 1.0, -1.0] {
        for mu in [f32::NAN, -1.0, 1.0, 2.0] {
            assert!(pivot_phase(mu, g).is_finite(), "{mu} {g}");
            assert!(henyey_greenstein(mu, g).is_finite(), "{mu} {g}");
        }
        assert!(pivot_mean_cosine(g).is_finite());
        assert!(pivot_from_henyey_greenstein(g).is_finite());
        for u in [[f32::NAN, 0.5], [-1.0, 2.0], [1.0, 1.0]] {
            let s = sample_pivot_phase(Vec3::Z, g, u);
            assert!(s.dir.is_finite() && s.pdf.is_finite() && s.pdf > 0.0);
            let s = sample_henyey_greenstein(Vec3::Z, g, u);
            assert!(s.dir.is_finite() && s.pdf.is_finite() && s.pdf > 0.0);
        }
    }
    assert_eq!(
        sample_pivot_phase(Vec3::ZERO, 0.5, [0.5, 0.5]),
        Sample::NONE
    );
    assert_eq!(
        sample_henyey_greenstein(Vec3::NAN, 0.5, [0.5, 0.5]),
        Sample::NONE
    );
}

/// Regression (found by the fuzz target `sphere`): a direction `wo` of length 5e-22
/// normalised (through denormal squares) to length 0.99986, and so did the samples.
#[test]
fn tiny_directions_give_unit_samples() {
    for wo in [
        Vec3::new(5.449_677e-22, -0.0, -0.0),
        Vec3::new(1e-30, 2e-30, -1e-30),
        Vec3::new(1e-45, 0.0, 0.0),
    ] {
        for g in [0.0, 0.5, -0.9] {
            for s in [
                sample_pivot_phase(wo, g, [0.0, 0.0]),
                sample_henyey_greenstein(wo, g, [0.3, 0.7]),
            ] {
                assert!(
                    s.pdf > 0.0 && (s.dir.length() - 1.0).abs() < 1e-6,
                    "{wo:?} {s:?}"
                );
            }
        }
    }
}

/// Issue 17, 4: near `|g| = 1`, `1 − g²` from the rounded `g²` cancelled, so the pivot
/// phase function (squared) and Henyey–Greenstein were off by `ε/(1 − |g|)` everywhere:
/// 1.7e-4 at `g = ±0.99983`, and `∫f − 1 = −1.3e-5` at `g = ±0.999`.
#[test]
fn phase_functions_near_unit_anisotropy_match_eq_25_and_26_and_integrate_to_one() {
    let (nodes, weights) = gauss_legendre_16();
    let limit = 1.0 - 1.0 / 1_048_576.0;
    for g in [0.999f32, -0.999, 0.99983, -0.99983, limit, -limit] {
        // Eq. 25 and 26 in f64 as functions of the distance x = 1 − sign(g) μ from the
        // peak, with 1 + g² − 2gμ = (1 − |g|)² + 2|g| x (no cancellation) and 1 − g²
        // exact in f64 for an f32 g.
        let (gd, a) = (g as f64, g.abs() as f64);
        let one_minus_g2 = 1.0 - gd * gd;
        let den = |x: f64| (1.0 - a) * (1.0 - a) + 2.0 * a * x;
        let pivot_ref = |x: f64| (one_minus_g2 / den(x)).powi(2) / (4.0 * core::f64::consts::PI);
        let hg_ref = |x: f64| one_minus_g2 / den(x).powf(1.5) / (4.0 * core::f64::consts::PI);
        // Nodes graded towards the peak: x = w (e^t − 1) with w = (1 − |g|)²/(2|g|) the
        // peak's width, so that f dx ∝ e^{−t} dt is smooth; 16-point Gauss–Legendre on
        // panels of 1/2 in t.
        let w = (1.0 - a) * (1.0 - a) / (2.0 * a);
        let t_max = (2.0 / w + 1.0).ln();
        let panels = (2.0 * t_max).ceil() as usize;
        let (mut integral, mut reference_integral, mut worst_pivot, mut worst_hg) =
            (0.0, 0.0, 0.0f64, 0.0f64);
        for panel in 0..panels {
            let (t0, t1) = (
                t_max * panel as f64 / panels as f64,
                t_max * (panel + 1) as f64 / panels as f64,
            );
            for (node, weight) in nodes.iter().zip(weights) {
                let t = 0.5 * (t0 + t1) + 0.5 * (t1 - t0) * node;
                let x = w * t.exp_m1();
                let dx = w * t.exp() * 0.5 * (t1 - t0) * weight;
                // f32's μ steps by 6e-8 near ±1, coarser than the peaks of g = 0.99983 and
                // 1 − 2⁻²⁰: each node takes f32's value at the nearest f32 μ relative to
                // the reference there, so that the sum is ∫ f_ref · (f/f_ref) and measures
                // the normalisation of the f32 function however fine its peak.
                let mu = (gd.signum() * (1.0 - x)) as f32;
                let x32 = 1.0 - gd.signum() * mu as f64;
                let ratio = pivot_phase(mu, g) as f64 / pivot_ref(x32);
                worst_pivot = worst_pivot.max((ratio - 1.0).abs());
                worst_hg =
                    worst_hg.max((henyey_greenstein(mu, g) as f64 / hg_ref(x32) - 1.0).abs());
                integral += 2.0 * core::f64::consts::PI * pivot_ref(x) * ratio * dx;
                reference_integral += 2.0 * core::f64::consts::PI * pivot_ref(x) * dx;
            }
        }
        for mu in [-1.0f32, 0.0, 1.0] {
            let x = 1.0 - gd.signum() * mu as f64;
            worst_pivot = worst_pivot.max((pivot_phase(mu, g) as f64 / pivot_ref(x) - 1.0).abs());
        }
        assert!(
            (reference_integral - 1.0).abs() < 1e-9,
            "g = {g}: the quadrature gives {reference_integral}"
        );
        assert!(
            worst_pivot <= 2e-6,
            "g = {g}: pivot relative error {worst_pivot:e}"
        );
        assert!(worst_hg <= 2e-6, "g = {g}: HG relative error {worst_hg:e}");
        assert!(
            (integral - 1.0).abs() <= 1e-5,
            "g = {g}: ∫f − 1 = {:e}",
            integral - 1.0
        );
        eprintln!(
            "g = {g}: pivot {worst_pivot:e}, HG {worst_hg:e}, ∫f − 1 = {:e}",
            integral - 1.0
        );
    }
}
