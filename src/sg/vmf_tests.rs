use super::sg::Sg;
use super::vmf::*;
use crate::Vec3;
use crate::testing::{CHI_SQUARE_ALPHA, Rng, chi_square, d3, dot, sub};
use core::f64::consts::PI as PI64;

/// The f64 CDF of `t = 1 − ω·ξ` under the vMF of sharpness `l`, written from
/// `∫_0^t λ e^{−λs} ds / ∫_0^2 λ e^{−λs} ds` (independent of the core's forms).
fn cdf(l: f64, t: f64) -> f64 {
    if l < 1e-12 {
        return t / 2.0;
    }
    (1.0 - (-l * t).exp()) / (1.0 - (-2.0 * l).exp())
}

/// Inverse of `cdf` by bisection (independent of the core's closed form).
fn quantile(l: f64, p: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 2.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if cdf(l, mid) < p { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

#[test]
fn samples_follow_the_vmf_chi_square() {
    const T_BINS: usize = 24;
    const PHI_BINS: usize = 8;
    const N: usize = 240_000;
    for (k, &l) in [1e-4f32, 0.1, 1.0, 10.0, 1e3, 1e5].iter().enumerate() {
        let mut rng = Rng::new(10 + k as u64);
        let axis = rng.unit_vector_f32();
        let sg = Sg::new(axis, l, 1.0);
        let edges: Vec<f64> = (1..T_BINS)
            .map(|i| quantile(l as f64, i as f64 / T_BINS as f64))
            .collect();
        let (tangent, bitangent) = crate::math::orthonormal_basis(sg.axis);
        let mut counts = vec![0u64; T_BINS * PHI_BINS];
        for _ in 0..N {
            let s = vmf_sample(&sg, [rng.uniform_f32(), rng.uniform_f32()]);
            assert!(s.pdf > 0.0 && s.pdf.is_finite() && s.dir.is_finite());
            let e = sub(d3(s.dir), d3(sg.axis));
            let t = 0.5 * dot(e, e);
            let tb = edges.iter().take_while(|&&edge| edge < t).count();
            let phi = (dot(d3(s.dir), d3(bitangent))).atan2(dot(d3(s.dir), d3(tangent)));
            let pb = (((phi / (2.0 * PI64)).rem_euclid(1.0)) * PHI_BINS as f64) as usize % PHI_BINS;
            counts[tb * PHI_BINS + pb] += 1;
            // The sample's pdf is the pdf of its direction.
            assert_eq!(s.pdf, vmf_pdf(&sg, s.dir));
        }
        let probabilities = vec![1.0 / (T_BINS * PHI_BINS) as f64; T_BINS * PHI_BINS];
        let (_, _, p) = chi_square(&counts, &probabilities);
        assert!(p > CHI_SQUARE_ALPHA, "λ = {l}: p = {p}");
    }
}

#[test]
fn pdf_matches_the_normalised_sg_and_the_inverse_round_trips() {
    let mut rng = Rng::new(5);
    for _ in 0..20000 {
        let l = rng.log_uniform(-4.0, 6.0) as f32;
        let sg = Sg::new(rng.unit_vector_f32(), l, 3.0);
        let u = [rng.uniform_f32(), rng.uniform_f32()];
        let s = vmf_sample(&sg, u);
        let e = sub(d3(s.dir), d3(sg.axis));
        let t = 0.5 * dot(e, e);
        let l64 = l as f64;
        let reference = if l64 < 1e-12 {
            1.0 / (4.0 * PI64)
        } else {
            l64 * (-l64 * t).exp() / (2.0 * PI64 * (1.0 - (-2.0 * l64).exp()))
        };
        assert!(
            ((s.pdf as f64 - reference) / reference).abs() < 2e-5 * (1.0 + l64 * t),
            "λ {l}: {} vs {reference}",
            s.pdf
        );
        // Inverse: u0 through the CDF (f32 directions limit it), u1 exactly up to rounding.
        let inverse = vmf_invert(&sg, s.dir).unwrap();
        assert!(
            (inverse[0] as f64 - cdf(l64, t)).abs() < 1e-5,
            "{inverse:?} vs {}",
            cdf(l64, t)
        );
        assert!(
            (inverse[0] - u[0]).abs() < 1e-3 + 2e-3 * (l64 * t) as f32,
            "λ {l}: {inverse:?} vs {u:?}"
        );
        let d = (inverse[1] - u[1]).abs();
        if t > 1e-6 / l64.max(1.0) && t < 1.99 {
            assert!(d.min(1.0 - d) < 1e-3, "λ {l}, t {t}: {inverse:?} vs {u:?}");
        }
    }
}

#[test]
fn pdf_integrates_to_one() {
    // Midpoint rule over t (refined near the axis) and φ-independence: 2π ∫ p dt.
    for l in [0.0f32, 1e-4, 0.3, 7.0, 300.0, 1e5] {
        let sg = Sg::new(Vec3::Z, l, 1.0);
        let n = 200_000;
        let top = (40.0 / l.max(1e-6) as f64).min(2.0);
        let mut total = 0.0;
        for i in 0..n {
            let t = (i as f64 + 0.5) / n as f64 * top;
            let z = 1.0 - t;
            let s = (t * (2.0 - t)).sqrt();
            total += vmf_pdf(&sg, Vec3::new(s as f32, 0.0, z as f32)) as f64;
        }
        total *= 2.0 * PI64 * top / n as f64;
        assert!((total - 1.0).abs() < 2e-3, "λ {l}: {total}");
    }
}

#[test]
fn bad_input_draws_no_sample_or_a_finite_one() {
    let hand = Sg {
        axis: Vec3::ZERO,
        sharpness: 1.0,
        log_amplitude: 0.0,
    };
    assert_eq!(vmf_sample(&hand, [0.5, 0.5]).pdf, 0.0);
    assert_eq!(vmf_pdf(&hand, Vec3::Z), 0.0);
    assert!(vmf_invert(&hand, Vec3::Z).is_none());
    for l in [f32::NAN, -1.0, 0.0, f32::INFINITY, 1e30] {
        let sg = Sg {
            axis: Vec3::new(0.0, 3.0, 4.0),
            sharpness: l,
            log_amplitude: 0.0,
        };
        for u in [
            [f32::NAN, 0.5],
            [-1.0, 2.0],
            [1.0, 1.0],
            [0.0, 0.0],
            [0.999_999_94, 0.999_999_94],
        ] {
            let s = vmf_sample(&sg, u);
            assert!(
                s.dir.is_finite() && s.pdf.is_finite() && s.pdf > 0.0,
                "{l} {u:?}: {s:?}"
            );
            assert!((s.dir.length() - 1.0).abs() < 1e-5);
        }
        assert_eq!(vmf_pdf(&sg, Vec3::ZERO), 0.0);
        assert_eq!(vmf_pdf(&sg, Vec3::new(f32::NAN, 0.0, 0.0)), 0.0);
    }
}

/// Found by fuzzing: the antipode of the axis inverted to `u0 = 1`, outside `[0, 1)`.
#[test]
fn the_antipode_inverts_inside_the_unit_square() {
    for sharpness in [0.0, 1e-3, 1.0, 30.0] {
        let sg = Sg::new(Vec3::new(0.0, 0.6, 0.8), sharpness, 1.0);
        let u = vmf_invert(&sg, -sg.axis).expect("valid");
        assert!(
            u.iter().all(|x| (0.0..1.0).contains(x)),
            "λ {sharpness}: {u:?}"
        );
    }
}
