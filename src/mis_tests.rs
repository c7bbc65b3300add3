//! Tests of the MIS heuristics: weights summing to one, the limits of clamped optimal
//! MIS, unbiased estimators on `[0, 1]` and on the hemisphere (with an occluder, and
//! with integrands of the form `V Σ c_k p_k` and not), zero variance where the paper
//! promises it, and bad input.
use super::*;
use crate::testing::*;
use core::f64::consts::PI;

// ---- techniques and integrands on [0, 1] ------------------------------------------

/// A sampling technique on `[0, 1)`: its warp of `u` and its density.
struct Technique {
    sample: fn(f32) -> f32,
    pdf: fn(f32) -> f32,
}

/// Uniform, `p = 1`.
const UNIFORM: Technique = Technique {
    sample: |u| u,
    pdf: |x| if (0.0..1.0).contains(&x) { 1.0 } else { 0.0 },
};
/// Linear, `p = 2x` (0 at `x = 0`).
const LINEAR: Technique = Technique {
    sample: |u| u.sqrt(),
    pdf: |x| {
        if (0.0..1.0).contains(&x) {
            2.0 * x
        } else {
            0.0
        }
    },
};
/// Uniform on the right half only, `p = 2` on `[1/2, 1)`, 0 elsewhere.
const RIGHT_HALF: Technique = Technique {
    sample: |u| 0.5 + 0.5 * u,
    pdf: |x| if (0.5..1.0).contains(&x) { 2.0 } else { 0.0 },
};

/// The occluder: `V = 0` on `[0.3, 0.55)`.
fn visible(x: f32) -> bool {
    !(0.3..0.55).contains(&x)
}

/// `∫ V p` of the three techniques.
const VISIBLE_MASS: [f64; 3] = [0.75, 1.0 - (0.55 * 0.55 - 0.3 * 0.3), 2.0 * 0.45];

/// An integrand not of the form `V Σ c p`: `V (1 + sin 5x)`, and its integral.
fn other(x: f32) -> f32 {
    if visible(x) {
        1.0 + (5.0 * x).sin()
    } else {
        0.0
    }
}

fn other_integral() -> f64 {
    let antiderivative = |x: f64| x - (5.0 * x).cos() / 5.0;
    antiderivative(1.0) - antiderivative(0.0) - (antiderivative(0.55) - antiderivative(0.3))
}

/// How a sample of technique `j` contributes, given `f` at the sample and the pdfs of
/// all techniques there.
type Contribution<'a> = &'a dyn Fn(f32, &[f32], usize) -> f32;

/// The one-sample-per-technique MIS estimator over `samples` trials: the mean and
/// standard error of `Σ_j contribution(f(x_j), p(x_j), j)`, and whether any single
/// contribution was negative.
fn run(
    techniques: &[&Technique],
    f: &dyn Fn(f32) -> f32,
    contribution: Contribution,
    samples: u64,
    seed: u64,
) -> (Estimate, bool) {
    let mut rng = Rng::new(seed);
    let mut estimate = Estimate::default();
    let mut negative = false;
    let mut pdfs = [0.0f32; 3];
    for _ in 0..samples {
        let mut total = 0.0f64;
        for (j, technique) in techniques.iter().enumerate() {
            let x = (technique.sample)(rng.uniform_f32());
            for (p, t) in pdfs.iter_mut().zip(techniques) {
                *p = (t.pdf)(x);
            }
            let c = contribution(f(x), &pdfs[..techniques.len()], j);
            assert!(c.is_finite());
            negative |= c < 0.0;
            total += c as f64;
        }
        estimate.add(total);
    }
    (estimate, negative)
}

/// A named contribution function.
type Named<'a> = (String, Box<dyn Fn(f32, &[f32], usize) -> f32 + 'a>);

/// The heuristics as contributions, for the given unoccluded contributions `c` and `v`.
fn heuristics(c: &[f32], v: f32) -> Vec<Named<'_>> {
    let by_weight = |w: f32, f: f32, p: f32| if w > 0.0 { w * f / p } else { 0.0 };
    vec![
        (
            "balance".into(),
            Box::new(move |f, p: &[f32], j| by_weight(balance_heuristic(p, j), f, p[j])),
        ),
        (
            "power".into(),
            Box::new(move |f, p: &[f32], j| by_weight(power_heuristic(p, j), f, p[j])),
        ),
        (
            "weighted balance".into(),
            Box::new(move |f, p: &[f32], j| {
                by_weight(weighted_balance_heuristic(p, c, j), f, p[j])
            }),
        ),
        (
            format!("clamped optimal weight, v = {v}"),
            Box::new(move |f, p: &[f32], j| {
                by_weight(clamped_optimal_mis_weight(p, c, v, j), f, p[j])
            }),
        ),
        (
            format!("clamped optimal contribution, v = {v}"),
            Box::new(move |f, p: &[f32], j| clamped_optimal_mis_contribution(f, p, c, v, j)),
        ),
        (
            format!("optimal contribution, v = {v}"),
            Box::new(move |f, p: &[f32], j| optimal_mis_contribution(f, p, c, v, j)),
        ),
    ]
}

#[test]
fn every_heuristic_is_unbiased_on_the_unit_interval_with_an_occluder() {
    let c = [0.7f32, 0.4, 1.3];
    let sets: [&[&Technique]; 2] = [&[&UNIFORM, &LINEAR], &[&UNIFORM, &LINEAR, &RIGHT_HALF]];
    let mut seed = 0;
    for techniques in sets {
        let n = techniques.len();
        let c = &c[..n];
        // f = V Σ c_k p_k, the form the weighted heuristics are made for.
        let form = |x: f32| {
            if visible(x) {
                techniques.iter().zip(c).map(|(t, c)| c * (t.pdf)(x)).sum()
            } else {
                0.0
            }
        };
        let form_integral: f64 = (0..n).map(|k| c[k] as f64 * VISIBLE_MASS[k]).sum();
        for v in [0.0, DEFAULT_VISIBILITY, 1.0] {
            for (name, contribution) in heuristics(c, v) {
                for (integrand, f, reference) in [
                    ("V Σ c p", &form as &dyn Fn(f32) -> f32, form_integral),
                    ("V (1 + sin 5x)", &other, other_integral()),
                ] {
                    seed += 1;
                    let (estimate, _) = run(techniques, f, &*contribution, 400_000, seed);
                    estimate.assert_mean_is(
                        reference,
                        5.0,
                        1e-6,
                        &format!("{name}, {n} techniques, {integrand}"),
                    );
                }
            }
        }
    }
}

#[test]
fn optimal_mis_is_unbiased_for_any_visibility_estimate_though_contributions_go_negative() {
    let c = [0.7f32, 0.4];
    let techniques: [&Technique; 2] = [&UNIFORM, &LINEAR];
    let form = |x: f32| {
        if visible(x) {
            c[0] * (UNIFORM.pdf)(x) + c[1] * (LINEAR.pdf)(x)
        } else {
            0.0
        }
    };
    let reference = c[0] as f64 * VISIBLE_MASS[0] + c[1] as f64 * VISIBLE_MASS[1];
    for (k, v) in [0.0f32, 0.1, 0.37, 0.5, 0.9, 1.0].into_iter().enumerate() {
        let contribution = |f: f32, p: &[f32], j: usize| optimal_mis_contribution(f, p, &c, v, j);
        let (estimate, negative) =
            run(&techniques, &form, &contribution, 1_000_000, 100 + k as u64);
        estimate.assert_mean_is(reference, 5.0, 1e-6, &format!("v = {v}"));
        // Occluded samples contribute v (c_j - Σ c p / Σ p), negative for one of them.
        assert_eq!(negative, v > 0.0, "v = {v}");
    }
}

/// Without occlusion and for `f = Σ c_k p_k`, the weighted balance heuristic and
/// (clamped) optimal MIS with `v = 1` give every estimate `Σ c_k`; the balance
/// heuristic does not (so the check can fail).
#[test]
fn weighted_balance_and_optimal_mis_have_zero_variance_for_unoccluded_perfect_fits() {
    let c = [0.7f32, 0.4, 1.3];
    let techniques: [&Technique; 3] = [&UNIFORM, &LINEAR, &RIGHT_HALF];
    let f = |x: f32| {
        techniques
            .iter()
            .zip(&c)
            .map(|(t, c)| c * (t.pdf)(x))
            .sum::<f32>()
    };
    let total: f64 = c.iter().map(|&c| c as f64).sum();
    let zero_variance: [(&str, Contribution); 4] = [
        ("weighted balance", &|f, p, j| {
            weighted_balance_heuristic(p, &c, j) * f / p[j]
        }),
        ("clamped optimal weight, v = 1", &|f, p, j| {
            clamped_optimal_mis_weight(p, &c, 1.0, j) * f / p[j]
        }),
        ("clamped optimal, v = 1", &|f, p, j| {
            clamped_optimal_mis_contribution(f, p, &c, 1.0, j)
        }),
        ("optimal, v = 1", &|f, p, j| {
            optimal_mis_contribution(f, p, &c, 1.0, j)
        }),
    ];
    for (name, contribution) in zero_variance {
        let (estimate, _) = run(&techniques, &f, contribution, 100_000, 7);
        estimate.assert_mean_is(total, 0.0, 1e-6, name);
        assert!(
            estimate.variance() < 1e-11 * total * total,
            "{name}: {}",
            estimate.variance()
        );
    }
    let balance = |f: f32, p: &[f32], j: usize| balance_heuristic(p, j) * f / p[j];
    let (estimate, _) = run(&techniques, &f, &balance, 100_000, 7);
    assert!(
        estimate.variance() > 1e-3,
        "balance: {}",
        estimate.variance()
    );
}

// ---- the hemisphere: cosine-weighted and uniform sampling ----------------------------

/// MIS of cosine-weighted (Malley's method, written here so that these tests need no
/// BRDF module) and uniform hemisphere sampling, for
/// `f = V (c0 cos θ / π + c1 / 2π)` and for `V (z³ + x²/2)`, with `V = 0` where
/// `φ ∈ [0.5, 2)` and `θ < 60°`. References in closed form:
/// `∫ V cos θ / π = 1 - Δφ/2π · sin²60°`, `∫ V / 2π = 1 - Δφ/2π · (1 - cos 60°)`,
/// `∫ z³ = π/2`, `∫ x² = 2π/3` over the hemisphere, and over the occluded patch
/// `∫ z³ = Δφ (1 - 0.5⁴)/4`, `∫ x² = (Δφ/2 + (sin 2φ1 - sin 2φ0)/4) ∫_{1/2}^1 (1 - z²) dz`.
#[test]
fn every_heuristic_is_unbiased_on_the_hemisphere_with_an_occluder() {
    use crate::Vec3;
    let (phi0, phi1) = (0.5f64, 2.0f64);
    let occluded = |w: Vec3| {
        let phi = (w.y as f64).atan2(w.x as f64).rem_euclid(2.0 * PI);
        phi >= phi0 && phi < phi1 && w.z > 0.5
    };
    let uniform_pdf = 1.0 / (2.0 * core::f32::consts::PI);
    let cosine_pdf = |w: Vec3| w.z.max(0.0) * core::f32::consts::FRAC_1_PI;
    let pdfs = |w: Vec3| [cosine_pdf(w), if w.z > 0.0 { uniform_pdf } else { 0.0 }];
    // Malley's method: uniform in the unit disk, lifted to the hemisphere.
    let cosine_sample = |u0: f32, u1: f32| {
        let (r, phi) = (u0.sqrt(), 2.0 * core::f32::consts::PI * u1);
        Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u0).max(0.0).sqrt())
    };
    let c = [0.8f32, 0.3];
    let form = |w: Vec3| {
        let p = pdfs(w);
        if occluded(w) {
            0.0
        } else {
            c[0] * p[0] + c[1] * p[1]
        }
    };
    let other = |w: Vec3| {
        if occluded(w) {
            0.0
        } else {
            w.z.powi(3) + 0.5 * w.x * w.x
        }
    };
    let share = (phi1 - phi0) / (2.0 * PI);
    let form_reference = c[0] as f64 * (1.0 - share * 0.75) + c[1] as f64 * (1.0 - share * 0.5);
    let patch_x2 = ((phi1 - phi0) / 2.0 + ((2.0 * phi1).sin() - (2.0 * phi0).sin()) / 4.0)
        * (0.5 - (1.0 - 0.125) / 3.0);
    let other_reference =
        PI / 2.0 - (phi1 - phi0) * (1.0 - 0.0625) / 4.0 + 0.5 * (2.0 * PI / 3.0 - patch_x2);
    let mut seed = 500;
    for v in [0.0, DEFAULT_VISIBILITY, 1.0] {
        for (name, contribution) in heuristics(&c, v) {
            for (integrand, f, reference) in [
                ("V Σ c p", &form as &dyn Fn(Vec3) -> f32, form_reference),
                ("V (z³ + x²/2)", &other, other_reference),
            ] {
                seed += 1;
                let mut rng = Rng::new(seed);
                let mut estimate = Estimate::default();
                for _ in 0..300_000 {
                    let cosine = cosine_sample(rng.uniform_f32(), rng.uniform_f32());
                    let (z, phi) = (
                        rng.uniform_f32(),
                        2.0 * core::f32::consts::PI * rng.uniform_f32(),
                    );
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    let uniform = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                    let mut total = 0.0;
                    for (j, w) in [cosine, uniform].into_iter().enumerate() {
                        total += contribution(f(w), &pdfs(w), j) as f64;
                    }
                    estimate.add(total);
                }
                estimate.assert_mean_is(reference, 5.0, 1e-5, &format!("{name}, {integrand}"));
            }
        }
    }
}

// ---- pointwise properties ------------------------------------------------------------

/// Random pdfs with zeros, over the whole f32 range when `wide`.
fn random_pdfs(rng: &mut Rng, n: usize, wide: bool) -> Vec<f32> {
    (0..n)
        .map(|_| match rng.below(5) {
            0 => 0.0,
            1 if wide => rng.log_uniform(-44.0, 38.0) as f32,
            _ => rng.log_uniform(-3.0, 3.0) as f32,
        })
        .collect()
}

#[test]
fn weights_sum_to_one_wherever_some_pdf_is_positive() {
    let mut rng = Rng::new(31);
    for _ in 0..200_000 {
        let n = 1 + rng.below(4) as usize;
        let pdfs = random_pdfs(&mut rng, n, true);
        let c: Vec<f32> = (0..n)
            .map(|_| {
                if rng.below(3) == 0 {
                    0.0
                } else {
                    rng.log_uniform(-3.0, 3.0) as f32
                }
            })
            .collect();
        let v = rng.uniform_f32();
        let any = pdfs.iter().any(|&p| p > 0.0);
        let sums = [
            (0..n).map(|j| balance_heuristic(&pdfs, j)).sum::<f32>(),
            (0..n).map(|j| power_heuristic(&pdfs, j)).sum::<f32>(),
            (0..n)
                .map(|j| weighted_balance_heuristic(&pdfs, &c, j))
                .sum::<f32>(),
            (0..n)
                .map(|j| clamped_optimal_mis_weight(&pdfs, &c, v, j))
                .sum::<f32>(),
        ];
        for (k, sum) in sums.into_iter().enumerate() {
            if any {
                assert!(
                    (sum - 1.0).abs() < 1e-5,
                    "heuristic {k}: {pdfs:?} {c:?}: {sum}"
                );
            } else {
                assert_eq!(sum, 0.0, "heuristic {k}: {pdfs:?}");
            }
        }
        for j in 0..n {
            let w = [
                balance_heuristic(&pdfs, j),
                power_heuristic(&pdfs, j),
                weighted_balance_heuristic(&pdfs, &c, j),
                clamped_optimal_mis_weight(&pdfs, &c, v, j),
            ];
            for w in w {
                assert!((0.0..=1.0).contains(&w), "{pdfs:?} {c:?} {j}: {w}");
                if pdfs[j] == 0.0 {
                    assert_eq!(w, 0.0);
                }
            }
        }
    }
}

#[test]
fn weights_match_their_formulas() {
    let p = [0.5f32, 2.0, 1.5];
    let c = [3.0f32, 1.0, 0.0];
    let close = |a: f32, b: f64| (a as f64 - b).abs() <= 1e-6 * b.abs().max(1e-30);
    assert!(close(balance_heuristic(&p, 1), 2.0 / 4.0));
    assert!(close(power_heuristic(&p, 1), 4.0 / (0.25 + 4.0 + 2.25)));
    let cp = 3.0 * 0.5 + 2.0;
    assert!(close(weighted_balance_heuristic(&p, &c, 0), 1.5 / cp));
    assert_eq!(weighted_balance_heuristic(&p, &c, 2), 0.0);
    let v = 0.3;
    for j in 0..3 {
        let expected = p[j] as f64 * (v * c[j] as f64 / cp + (1.0 - v) / 4.0);
        assert!(
            close(clamped_optimal_mis_weight(&p, &c, v as f32, j), expected),
            "{j}"
        );
        let f = 2.5f32;
        let expected = f as f64 * (v * c[j] as f64 / cp + (1.0 - v) / 4.0);
        assert!(close(
            clamped_optimal_mis_contribution(f, &p, &c, v as f32, j),
            expected
        ));
        let expected = v * c[j] as f64 + (f as f64 - v * cp) / 4.0;
        assert!(
            close(optimal_mis_contribution(f, &p, &c, v as f32, j), expected),
            "{j}"
        );
    }
}

#[test]
fn clamped_optimal_mis_blends_balance_and_weighted_balance() {
    let mut rng = Rng::new(37);
    for _ in 0..100_000 {
        let n = 1 + rng.below(4) as usize;
        // Within 1e6 of each other: subnormal ratios would cost the weights (not the
        // direct contribution) their precision.
        let pdfs = random_pdfs(&mut rng, n, false);
        let c: Vec<f32> = (0..n).map(|_| rng.uniform_f32()).collect();
        let f = rng.log_uniform(-3.0, 3.0) as f32;
        let v = rng.uniform_f32();
        for j in 0..n {
            let balance = balance_heuristic(&pdfs, j);
            let weighted = weighted_balance_heuristic(&pdfs, &c, j);
            assert_eq!(clamped_optimal_mis_weight(&pdfs, &c, 0.0, j), balance);
            assert_eq!(clamped_optimal_mis_weight(&pdfs, &c, 1.0, j), weighted);
            let w = clamped_optimal_mis_weight(&pdfs, &c, v, j);
            assert!((w - (v * weighted + (1.0 - v) * balance)).abs() <= 1e-6);
            // The contribution is the weight times f / p_j, where that is representable.
            let contribution = clamped_optimal_mis_contribution(f, &pdfs, &c, v, j);
            let expected = w as f64 * f as f64 / pdfs[j] as f64;
            if pdfs[j] > 0.0 && expected.abs() < 1e30 && expected.abs() > 1e-30 {
                assert!(
                    (contribution as f64 - expected).abs() <= 1e-5 * expected.abs(),
                    "{pdfs:?} {c:?} v {v} j {j}: {contribution} vs {expected}"
                );
            }
        }
    }
}

// ---- zero, infinite and bad input -----------------------------------------------------

#[test]
fn zero_nan_and_negative_pdfs_get_weight_zero() {
    let c = [1.0f32, 2.0];
    for bad in [0.0, -0.0, -1.0, f32::NAN, f32::NEG_INFINITY] {
        for (j, other) in [(0usize, 1usize), (1, 0)] {
            let mut p = [0.0f32; 2];
            p[j] = bad;
            p[other] = 0.7;
            assert_eq!(balance_heuristic(&p, j), 0.0);
            assert_eq!(balance_heuristic(&p, other), 1.0);
            assert_eq!(power_heuristic(&p, j), 0.0);
            assert_eq!(power_heuristic(&p, other), 1.0);
            assert_eq!(weighted_balance_heuristic(&p, &c, j), 0.0);
            assert_eq!(weighted_balance_heuristic(&p, &c, other), 1.0);
            assert_eq!(clamped_optimal_mis_weight(&p, &c, 0.5, j), 0.0);
            assert_eq!(clamped_optimal_mis_weight(&p, &c, 0.5, other), 1.0);
            assert_eq!(clamped_optimal_mis_contribution(1.0, &p, &c, 0.5, j), 0.0);
            assert_eq!(optimal_mis_contribution(1.0, &p, &c, 0.5, j), 0.0);
            // The other technique alone: f / p.
            let alone = clamped_optimal_mis_contribution(1.4, &p, &c, 0.5, other);
            assert!((alone - 2.0).abs() < 1e-6, "{alone}");
            let alone = optimal_mis_contribution(1.4, &p, &c, 0.5, other);
            assert!((alone - 2.0).abs() < 1e-6, "{alone}");
        }
        // All pdfs bad: every weight 0.
        let p = [bad, 0.0];
        for j in 0..2 {
            assert_eq!(balance_heuristic(&p, j), 0.0);
            assert_eq!(power_heuristic(&p, j), 0.0);
            assert_eq!(weighted_balance_heuristic(&p, &c, j), 0.0);
            assert_eq!(clamped_optimal_mis_weight(&p, &c, 0.5, j), 0.0);
            assert_eq!(clamped_optimal_mis_contribution(1.0, &p, &c, 0.5, j), 0.0);
            assert_eq!(optimal_mis_contribution(1.0, &p, &c, 0.5, j), 0.0);
        }
    }
    assert_eq!(balance_heuristic(&[], 0), 0.0);
    assert_eq!(optimal_mis_contribution(1.0, &[], &[], 0.5, 0), 0.0);
}

#[test]
fn infinite_pdfs_share_the_weight_as_in_the_limit() {
    let inf = f32::INFINITY;
    let c = [1.0f32, 3.0, 2.0];
    let p = [inf, 5.0, inf];
    assert_eq!(balance_heuristic(&p, 0), 0.5);
    assert_eq!(balance_heuristic(&p, 1), 0.0);
    assert_eq!(balance_heuristic(&p, 2), 0.5);
    assert_eq!(power_heuristic(&p, 0), 0.5);
    assert_eq!(power_heuristic(&p, 1), 0.0);
    // In proportion to c among the infinite ones: 1 : 2.
    assert!((weighted_balance_heuristic(&p, &c, 0) - 1.0 / 3.0).abs() < 1e-7);
    assert_eq!(weighted_balance_heuristic(&p, &c, 1), 0.0);
    assert!((weighted_balance_heuristic(&p, &c, 2) - 2.0 / 3.0).abs() < 1e-7);
    // If the infinite techniques all have c = 0, the balance heuristic decides.
    let c0 = [0.0f32, 3.0, 0.0];
    assert_eq!(weighted_balance_heuristic(&p, &c0, 0), 0.5);
    assert_eq!(weighted_balance_heuristic(&p, &c0, 1), 0.0);
    // Contributions: f / inf = 0; optimal MIS keeps v (c_j - mean of c over infinite).
    assert_eq!(clamped_optimal_mis_contribution(2.0, &p, &c, 0.5, 0), 0.0);
    assert_eq!(clamped_optimal_mis_contribution(2.0, &p, &c, 0.5, 1), 0.0);
    let optimal = optimal_mis_contribution(2.0, &p, &c, 0.5, 1);
    assert!((optimal - 0.5 * (3.0 - 1.5)).abs() < 1e-6, "{optimal}");
}

#[test]
fn extreme_pdfs_neither_overflow_nor_underflow() {
    for p in [f32::MAX, 3e38, 1e30, 1e-30, f32::MIN_POSITIVE, 1e-45] {
        let pdfs = [p, p];
        assert_eq!(balance_heuristic(&pdfs, 0), 0.5, "{p}");
        assert_eq!(power_heuristic(&pdfs, 0), 0.5, "{p}");
        assert_eq!(
            weighted_balance_heuristic(&pdfs, &[1.0, 1.0], 0),
            0.5,
            "{p}"
        );
        assert_eq!(
            clamped_optimal_mis_weight(&pdfs, &[1.0, 3.0], 0.5, 0),
            0.375,
            "{p}"
        );
        for f in [0.0, 1.0, -2.0, 1e-20, 1e20] {
            let c = clamped_optimal_mis_contribution(f, &pdfs, &[1.0, 3.0], 0.5, 0);
            let o = optimal_mis_contribution(f, &pdfs, &[1.0, 3.0], 0.5, 0);
            assert!(c.is_finite() && o.is_finite(), "{p} {f}: {c} {o}");
            let expected = 0.375 * f as f64 / p as f64;
            // (Results below the f32 normal range may round to 0.)
            if expected == 0.0 || (1e-30..f32::MAX as f64 / 4.0).contains(&expected.abs()) {
                assert!(
                    (c as f64 - expected).abs() <= 1e-5 * expected.abs(),
                    "{p} {f}: {c}"
                );
            } else if expected.abs() > f32::MAX as f64 * 4.0 {
                assert_eq!(c, 0.0, "{p} {f}: an overflowing contribution is 0");
            }
        }
    }
    // 1e30 and 1e-30: the small one's weight is 1e-60 (balance) and 1e-120 (power):
    // 0 in f32, but no NaN.
    let pdfs = [1e30f32, 1e-30];
    assert_eq!(balance_heuristic(&pdfs, 0), 1.0);
    assert_eq!(power_heuristic(&pdfs, 0), 1.0);
    assert_eq!(power_heuristic(&pdfs, 1), 0.0);
}

#[test]
fn bad_contributions_visibility_and_integrands_are_handled() {
    let p = [0.5f32, 1.5];
    // c NaN, negative, infinite count as 0: technique 1 alone has c > 0.
    for bad in [f32::NAN, -1.0, f32::INFINITY, f32::NEG_INFINITY] {
        let c = [bad, 2.0];
        assert_eq!(weighted_balance_heuristic(&p, &c, 0), 0.0);
        assert_eq!(weighted_balance_heuristic(&p, &c, 1), 1.0);
        let o = optimal_mis_contribution(1.0, &p, &c, 1.0, 0);
        assert!(o.is_finite());
        assert_eq!(o, optimal_mis_contribution(1.0, &p, &[0.0, 2.0], 1.0, 0));
    }
    // Σ c p = 0: the weighted forms fall back to the balance heuristic.
    for c in [[0.0f32, 0.0], [f32::NAN, -1.0]] {
        for j in 0..2 {
            assert_eq!(
                weighted_balance_heuristic(&p, &c, j),
                balance_heuristic(&p, j)
            );
            assert_eq!(
                clamped_optimal_mis_weight(&p, &c, 0.7, j),
                balance_heuristic(&p, j)
            );
            let contribution = clamped_optimal_mis_contribution(2.0, &p, &c, 0.7, j);
            assert!((contribution - 2.0 / 2.0).abs() < 1e-6);
        }
    }
    // v is clamped, NaN is 0.
    let c = [1.0f32, 2.0];
    for (v, clamped) in [
        (f32::NAN, 0.0),
        (-3.0, 0.0),
        (7.0, 1.0),
        (f32::INFINITY, 1.0),
    ] {
        for j in 0..2 {
            assert_eq!(
                clamped_optimal_mis_weight(&p, &c, v, j),
                clamped_optimal_mis_weight(&p, &c, clamped, j)
            );
            assert_eq!(
                clamped_optimal_mis_contribution(1.5, &p, &c, v, j),
                clamped_optimal_mis_contribution(1.5, &p, &c, clamped, j)
            );
            assert_eq!(
                optimal_mis_contribution(1.5, &p, &c, v, j),
                optimal_mis_contribution(1.5, &p, &c, clamped, j)
            );
        }
    }
    // Non-finite f: the sample is discarded.
    for f in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert_eq!(clamped_optimal_mis_contribution(f, &p, &c, 0.5, 0), 0.0);
        assert_eq!(optimal_mis_contribution(f, &p, &c, 0.5, 0), 0.0);
    }
    // Lengths: only the common prefix takes part; j beyond it gives 0.
    assert_eq!(
        weighted_balance_heuristic(&[1.0, 1.0, 1.0], &[1.0, 1.0], 2),
        0.0
    );
    assert_eq!(
        weighted_balance_heuristic(&[1.0, 1.0, 1.0], &[1.0, 1.0], 0),
        0.5
    );
    assert_eq!(clamped_optimal_mis_weight(&[1.0, 1.0], &[1.0], 0.5, 0), 1.0);
    assert_eq!(balance_heuristic(&[1.0], 3), 0.0);
    assert_eq!(power_heuristic(&[1.0], 1), 0.0);
}

/// A contribution or integrand value for the per-channel test: mostly ordinary, with
/// zeros, negatives, NaN, infinities and the extremes of the range.
fn random_channel_value(rng: &mut Rng) -> f32 {
    match rng.below(12) {
        0 => 0.0,
        1 => -(rng.log_uniform(-3.0, 3.0) as f32),
        2 => f32::NAN,
        3 => f32::INFINITY,
        4 => rng.log_uniform(-44.0, 38.0) as f32,
        _ => rng.log_uniform(-3.0, 3.0) as f32,
    }
}

#[test]
fn the_two_technique_channels_are_the_scalar_heuristics_bit_for_bit() {
    let mut rng = Rng::new(47);
    let mut compared = 0;
    for _ in 0..200_000 {
        let pdfs = random_pdfs(&mut rng, 2, true);
        let pdfs = [pdfs[0], pdfs[1]];
        let j = rng.below(2) as usize;
        let c = [0, 1].map(|_| {
            Vec3A::new(
                random_channel_value(&mut rng),
                random_channel_value(&mut rng),
                random_channel_value(&mut rng),
            )
        });
        let f = Vec3A::new(
            random_channel_value(&mut rng),
            random_channel_value(&mut rng),
            random_channel_value(&mut rng),
        );
        let v = match rng.below(6) {
            0 => f32::NAN,
            1 => -0.5,
            2 => 1.5,
            _ => rng.uniform() as f32,
        };
        let Some(two) = TwoPdfs::new(pdfs[j], pdfs[1 - j], j) else {
            // Only a zero pdf of the sample's own technique is refused here.
            assert!(!(pdfs[j] > 0.0), "{pdfs:?} {j}");
            continue;
        };
        let two = TwoTechniques::new(two, c);
        compared += 1;
        let (weighted, clamped, unoccluded) = (
            two.weighted_balance(f, pdfs[j]),
            two.clamped_optimal(f, v),
            two.optimal_unoccluded(v),
        );
        for k in 0..3 {
            let ck = [c[0][k], c[1][k]];
            let expected = [
                f[k] * (weighted_balance_heuristic(&pdfs, &ck, j) / pdfs[j]),
                clamped_optimal_mis_contribution(f[k], &pdfs, &ck, v, j),
                optimal_mis_contribution(0.0, &pdfs, &ck, v, j),
            ];
            let got = [weighted[k], clamped[k], unoccluded[k]];
            for (g, e) in got.iter().zip(expected) {
                assert!(
                    g.to_bits() == e.to_bits() || (g.is_nan() && e.is_nan()),
                    "{got:?} != {expected:?}: pdfs {pdfs:?}, j {j}, c {ck:?}, f {}, v {v}",
                    f[k]
                );
            }
        }
    }
    assert!(compared > 100_000, "{compared}");
}

#[test]
fn the_two_pdfs_balance_is_the_scalar_balance_bit_for_bit() {
    // `TwoPdfs` divides only the smaller pdf by the larger: the same bits as
    // `balance_heuristic(&p, j) / p[j]` for every pair it takes, equal pdfs, zeros
    // (of both signs), subnormals and the extremes of the range included.
    let mut rng = Rng::new(48);
    let specials = [
        0.0,
        -0.0,
        f32::MIN_POSITIVE,
        1e-45,
        3e-39,
        1.0,
        f32::MAX,
        f32::INFINITY,
        f32::NAN,
        -1.0,
    ];
    let mut pairs: Vec<[f32; 2]> = specials
        .iter()
        .flat_map(|&a| specials.iter().map(move |&b| [a, b]))
        .collect();
    for _ in 0..200_000 {
        let p = random_pdfs(&mut rng, 2, true);
        pairs.push([p[0], p[1]]);
        pairs.push([p[0], p[0]]);
    }
    let mut compared = 0;
    for pdfs in pairs {
        for j in 0..2 {
            let (p, q) = (pdfs[j], pdfs[1 - j]);
            let Some(two) = TwoPdfs::new(p, q, j) else {
                // Refused: what is not finite, a pdf of the sample below or at 0, and
                // a negative other one (`-0` too).
                assert!(
                    !(p > 0.0 && p.is_finite() && q >= 0.0 && q.is_finite())
                        || q.to_bits() == (-0.0f32).to_bits(),
                    "{pdfs:?} {j}"
                );
                continue;
            };
            compared += 1;
            let expected = balance_heuristic(&pdfs, j) / pdfs[j];
            assert_eq!(
                two.balance_over_pdf(pdfs[j]).to_bits(),
                expected.to_bits(),
                "{pdfs:?} {j}"
            );
        }
    }
    assert!(compared > 200_000, "{compared}");
}
