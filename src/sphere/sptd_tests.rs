use super::*;
use crate::testing::{
    CHI_SQUARE_ALPHA, D3, Estimate, Rng, cap_point, chi_square, cross, d3, dot, frame_f64,
    inside_f64, integrate_over_cap_f64, norm, normalize, pivot_image_f64, pivot_transform_f64,
    uniform_direction_f64,
};

/// The SPTD density of Eq. 8 in f64, literally: the base density at the preimage times
/// `((1 − |r_p|²)/|ω − r_p|²)²`. `cosine_axis = None` is the uniform base.
fn density_f64(w: D3, pivot: D3, cosine_axis: Option<D3>) -> f64 {
    let wi = pivot_transform_f64(w, pivot);
    let base = match cosine_axis {
        None => 0.25 / core::f64::consts::PI,
        Some(a) => dot(wi, a).max(0.0) / core::f64::consts::PI,
    };
    let e: D3 = core::array::from_fn(|i| w[i] - pivot[i]);
    let j = ((1.0 - dot(pivot, pivot)) / dot(e, e)).powi(2);
    base * j
}

fn cosine_direction_f64(rng: &mut Rng, a: D3) -> D3 {
    let r2 = rng.uniform();
    let phi = core::f64::consts::TAU * rng.uniform();
    let (u, v) = frame_f64(a);
    let r = r2.sqrt();
    let z = (1.0 - r2).sqrt();
    core::array::from_fn(|i| r * (phi.cos() * u[i] + phi.sin() * v[i]) + z * a[i])
}

/// Pivots and caps of the hard-case list: pivot at the origin, strong pivots, caps that
/// contain the pivot's direction, tiny caps, wide caps, hemispheres.
fn hard_cases() -> Vec<(Vec3, Cap)> {
    let tilt = Vec3::new(0.6, 0.0, 0.8);
    vec![
        (Vec3::ZERO, Cap::from_axis_cos(Vec3::Z, 0.8)),
        (Vec3::new(0.0, 0.0, 0.5), Cap::from_axis_cos(Vec3::Z, 0.9)),
        (
            tilt * 0.9,
            Cap::from_axis_cos(Vec3::new(0.5, 0.5, 0.7), 0.95),
        ),
        (
            tilt * 0.9,
            Cap::from_axis_cos(Vec3::new(-0.3, 0.2, 0.9), 0.7),
        ),
        (
            tilt * 0.99,
            Cap::from_axis_cos(Vec3::new(0.0, 0.7, 0.7), 0.99),
        ),
        (
            Vec3::new(0.3, -0.4, 0.2),
            Cap::from_axis_cos(Vec3::new(1.0, 0.0, -0.2), -0.3),
        ),
        (
            Vec3::new(0.0, 0.2, -0.7),
            Cap::from_axis_cos(Vec3::new(0.0, 0.1, 1.0), 0.0),
        ),
        (tilt * 0.6, Cap::from_axis_one_minus_cos(tilt, 1e-3)),
    ]
}

#[test]
fn density_matches_eq_8_in_f64_and_integrates_to_one() {
    let mut rng = Rng::new(5);
    for (pivot, _) in hard_cases() {
        for axis in [
            None,
            Some(Vec3::new(0.0, 0.6, 0.8)),
            Some(Vec3::new(0.0, 0.0, -1.0)),
        ] {
            let sptd = match axis {
                None => Sptd::uniform(pivot),
                Some(a) => Sptd::clamped_cosine(pivot, a),
            };
            let axis64 = axis.map(d3);
            // Importance sampling by the uniform SPTD of the same pivot in f64: u uniform,
            // ω = g(u), density J/4π; E[D/(J/4π)] = ∫ D = 1.
            let mut estimate = Estimate::default();
            for _ in 0..20000 {
                let u = uniform_direction_f64(&mut rng);
                let w = pivot_transform_f64(u, d3(pivot));
                let reference = density_f64(w, d3(pivot), axis64);
                let value = sptd.eval(Vec3::new(w[0] as f32, w[1] as f32, w[2] as f32)) as f64;
                // The cosine base at a preimage near its horizon is ill-conditioned: the
                // bound is relative to the uniform SPTD's density J/4π there.
                // g's condition number (1 + ρ)/(1 − ρ) amplifies the rounding of the
                // preimage.
                let scale = density_f64(w, d3(pivot), None);
                let rho = pivot.length() as f64;
                let condition = (1.0 + rho) / (1.0 - rho);
                assert!(
                    (value - reference).abs() <= (2e-4 + 1e-5 * condition) * (reference + scale),
                    "{pivot:?} {axis:?}: {value} vs {reference}"
                );
                estimate.add(reference / density_f64(w, d3(pivot), None));
            }
            estimate.assert_mean_is(1.0, 5.0, 1e-9, "∫ D over the sphere");
        }
    }
}

#[test]
fn integral_over_caps_is_the_probability_of_landing_in_them() {
    // Independent of the pivoted cap: the fraction of g(ω_i), ω_i from the base, that
    // lands in C (binomial noise ≤ 1/(2√n) = 5e-4 at n = 1e6).
    let mut rng = Rng::new(7);
    let n = 1_000_000;
    for (pivot, cap) in hard_cases() {
        for axis in [None, Some(Vec3::new(0.0, 0.6, 0.8))] {
            let sptd = match axis {
                None => Sptd::uniform(pivot),
                Some(a) => Sptd::clamped_cosine(pivot, a),
            };
            let second = Cap::from_axis_cos(Vec3::new(0.2, 0.0, 1.0), 0.3);
            let (mut hits, mut both) = (0u64, 0u64);
            for _ in 0..n {
                let wi = match axis {
                    None => uniform_direction_f64(&mut rng),
                    Some(a) => cosine_direction_f64(&mut rng, d3(a)),
                };
                let w = pivot_transform_f64(wi, d3(pivot));
                let in_cap = inside_f64(w, &cap);
                hits += in_cap as u64;
                both += (in_cap && inside_f64(w, &second)) as u64;
            }
            let p = hits as f64 / n as f64;
            let p_both = both as f64 / n as f64;
            let sigma = |p: f64| (p * (1.0 - p) / n as f64).sqrt();
            let single = sptd.integral_over_cap(&cap) as f64;
            assert!(
                (single - p).abs() <= 5.0 * sigma(p) + 2e-5,
                "{pivot:?} {axis:?} {cap:?}: {single} vs {p}"
            );
            let pair = sptd.integral_over_cap_intersection(&cap, &second) as f64;
            assert!(
                (pair - p_both).abs() <= 5.0 * sigma(p_both) + 2e-5,
                "{pivot:?} {axis:?} {cap:?} ∩ {second:?}: {pair} vs {p_both}"
            );
        }
    }
}

#[test]
fn clamped_cosine_over_a_cap_matches_quadrature_in_every_configuration() {
    // Above, below, straddling the horizon, wider than a hemisphere, tiny, the whole
    // sphere; the closed form and the boundary integral against a midpoint rule.
    let mut rng = Rng::new(11);
    let a = Vec3::new(0.0, 0.0, 1.0);
    for case in 0..400 {
        let axis = rng.unit_vector_f32();
        let t = match case % 4 {
            0 => rng.uniform() as f32 * 2.0,
            1 => rng.log_uniform(-4.0, 0.0) as f32,
            2 => 1.0,
            _ => 1.0 + rng.uniform() as f32,
        };
        let cap = Cap::from_axis_one_minus_cos(axis, t);
        let reference = integrate_over_cap_f64(&cap, 200, |w| w[2].max(0.0));
        let closed = clamped_cosine_over_cap(&cap, a) as f64;
        let boundary = clamped_cosine_over_caps(&cap, &Cap::WHOLE_SPHERE, a) as f64;
        let bound = 2e-3 * reference + 2e-4 * cap.solid_angle() as f64 + 1e-6;
        assert!(
            (closed - reference).abs() <= bound,
            "{cap:?}: {closed} vs {reference}"
        );
        assert!(
            (boundary - reference).abs() <= bound,
            "{cap:?}: {boundary} vs {reference}"
        );
    }
    // The whole sphere and the empty cap.
    assert!((clamped_cosine_over_cap(&Cap::WHOLE_SPHERE, a) - PI).abs() < 1e-5);
    assert_eq!(clamped_cosine_over_cap(&Cap::EMPTY, a), 0.0);
}

#[test]
fn clamped_cosine_over_cap_intersections_matches_quadrature() {
    let mut rng = Rng::new(13);
    let a = Vec3::new(0.3, -0.2, 0.9).normalize();
    for case in 0..300 {
        let first = Cap::from_axis_one_minus_cos(rng.unit_vector_f32(), rng.uniform() as f32 * 2.0);
        let second = match case % 5 {
            // Coincident and complementary caps.
            0 => first,
            1 => Cap::from_axis_one_minus_cos(-first.axis, 2.0 - first.one_minus_cos),
            _ => Cap::from_axis_one_minus_cos(rng.unit_vector_f32(), rng.uniform() as f32 * 2.0),
        };
        let a64 = d3(a);
        let reference = integrate_over_cap_f64(&first, 300, |w| {
            if inside_f64(w, &second) {
                dot(w, a64).max(0.0)
            } else {
                0.0
            }
        });
        let value = clamped_cosine_over_caps(&first, &second, a) as f64;
        // The midpoint rule on a discontinuous integrand: error ~ perimeter × cell size.
        let bound = 2e-2 * reference + 1e-2 * first.solid_angle() as f64 / 30.0 + 1e-5;
        assert!(
            (value - reference).abs() <= bound,
            "case {case}: {first:?} ∩ {second:?}: {value} vs {reference}"
        );
    }
}

/// Samples of a prepared SPTD in a cap against cells of the cap (10 rings equal in
/// `1 − cos`, 12 sectors), with cell probabilities from the f64 density.
fn chi_square_in_cap(sptd: &Sptd, cap: &Cap, axis: Option<D3>, seed: u64) {
    let prepared = SptdInCap::new(sptd, cap).expect("prepares");
    let (rings, sectors, sub) = (10usize, 12usize, 24usize);
    let a = d3(cap.axis);
    let t_max = cap.one_minus_cos as f64;
    let pivot = d3(sptd.pivot);
    let mut probabilities = vec![0.0; rings * sectors];
    for (cell, p) in probabilities.iter_mut().enumerate() {
        let (ring, sector) = (cell / sectors, cell % sectors);
        let mut sum = 0.0;
        for i in 0..sub {
            for k in 0..sub {
                let t = (ring as f64 + (i as f64 + 0.5) / sub as f64) * t_max / rings as f64;
                let phi = (sector as f64 + (k as f64 + 0.5) / sub as f64) * core::f64::consts::TAU
                    / sectors as f64;
                sum += density_f64(cap_point(a, t, phi), pivot, axis);
            }
        }
        *p = sum;
    }
    let total: f64 = probabilities.iter().sum();
    probabilities.iter_mut().for_each(|p| *p /= total);
    let (u_frame, v_frame) = frame_f64(a);
    let mut observed = vec![0u64; rings * sectors];
    let mut rng = Rng::new(seed);
    let mut inverse_estimate = Estimate::default();
    let mut dropped = 0;
    for _ in 0..200_000 {
        let u = [rng.uniform_f32(), rng.uniform_f32()];
        let s = prepared.sample(u);
        if s.pdf == 0.0 {
            // Rounding moved it out of the cap (see `SptdInCap::sample`).
            dropped += 1;
            inverse_estimate.add(0.0);
            continue;
        }
        let w = d3(s.dir);
        let e: D3 = core::array::from_fn(|i| w[i] - a[i]);
        let t = (0.5 * dot(e, e) / t_max).min(1.0 - 1e-12);
        let mut phi = dot(w, v_frame).atan2(dot(w, u_frame));
        if phi < 0.0 {
            phi += core::f64::consts::TAU;
        }
        let ring = ((t * rings as f64) as usize).min(rings - 1);
        let sector = ((phi / core::f64::consts::TAU * sectors as f64) as usize).min(sectors - 1);
        observed[ring * sectors + sector] += 1;
        // pdf(dir) agrees with the sample's pdf, and E[1/pdf] = Ω(C).
        let pdf = prepared.pdf(s.dir);
        assert!((pdf - s.pdf).abs() <= 1e-3 * s.pdf, "{pdf} vs {}", s.pdf);
        inverse_estimate.add(1.0 / s.pdf as f64);
    }
    assert!(dropped <= 20, "{dropped} of 200000 samples dropped");
    let (statistic, dof, p) = chi_square(&observed, &probabilities);
    assert!(
        p > CHI_SQUARE_ALPHA,
        "{sptd:?} in {cap:?}: chi² {statistic} dof {dof} p {p}"
    );
    inverse_estimate.assert_mean_is(cap.solid_angle() as f64, 5.0, 2e-3, "E[1/pdf] = Ω(C)");
}

#[test]
fn uniform_sptd_samples_in_a_cap_follow_the_f64_density() {
    for (seed, (pivot, cap)) in hard_cases().into_iter().enumerate() {
        chi_square_in_cap(&Sptd::uniform(pivot), &cap, None, 100 + seed as u64);
    }
}

#[test]
fn clamped_cosine_sptd_samples_in_a_cap_follow_the_f64_density() {
    let a = Vec3::new(0.0, 0.0, 1.0);
    let mut tested = 0;
    // The clamped cosine about z peaks, once pivoted by r_p, towards r_p/|r_p| when r_p
    // points down (the preimage of r_p/|r_p| is −r_p/|r_p|): caps below the horizon
    // whose images lie above it.
    let mut cases = hard_cases();
    cases.extend([
        (
            Vec3::new(0.2, 0.0, -0.6),
            Cap::from_axis_cos(Vec3::new(-0.1, 0.2, -1.0), 0.9),
        ),
        (
            Vec3::new(0.0, 0.0, -0.9),
            Cap::from_axis_cos(Vec3::new(0.3, 0.0, -1.0), 0.99),
        ),
        (
            Vec3::ZERO,
            Cap::from_axis_cos(Vec3::new(0.2, 0.1, -1.0), 0.8),
        ),
        (
            Vec3::new(0.1, 0.1, -0.3),
            Cap::from_axis_cos(Vec3::new(0.1, 0.1, -1.0), 0.3),
        ),
    ]);
    let mut clipped = 0;
    for (seed, (pivot, cap)) in cases.into_iter().enumerate() {
        let sptd = Sptd::clamped_cosine(pivot, a);
        let image = pivot_cap(&cap, sptd.pivot);
        let above = image.one_minus_cos <= 1.0 && image.axis.dot(a) >= image.sin2.sqrt();
        // Issue 20, 2: a sampler whenever the integral is positive (this asserted
        // `is_some() == above` before: no sampler when g(C) crossed the horizon).
        let prepared = SptdInCap::new(&sptd, &cap);
        assert_eq!(
            prepared.is_some(),
            sptd.integral_over_cap(&cap) > 0.0,
            "{pivot:?} {cap:?}"
        );
        if above {
            chi_square_in_cap(&sptd, &cap, Some(d3(a)), 200 + seed as u64);
            tested += 1;
        } else if let Some(prepared) = prepared {
            let (statistic, dof, p, _) = chi_square_region(
                &region_cells(&sptd, &cap),
                sptd.pivot,
                |u| prepared.sample(u),
                200_000,
                300 + seed as u64,
            );
            eprintln!("{pivot:?} {cap:?}: chi² {statistic:.1} dof {dof} p {p:.3}");
            assert!(
                p > CHI_SQUARE_ALPHA,
                "{pivot:?} {cap:?}: chi² {statistic} dof {dof} p {p}"
            );
            clipped += 1;
        }
    }
    assert!(tested >= 3, "only {tested} cases were samplable");
    assert!(clipped >= 3, "only {clipped} cases crossed the horizon");
}

#[test]
fn samples_invert_to_their_random_numbers() {
    let mut rng = Rng::new(17);
    for (pivot, cap) in hard_cases() {
        for sptd in [Sptd::uniform(pivot), Sptd::clamped_cosine(pivot, Vec3::Z)] {
            let Some(prepared) = SptdInCap::new(&sptd, &cap) else {
                continue;
            };
            for _ in 0..2000 {
                let u = [
                    rng.uniform_f32() * 0.98 + 0.01,
                    rng.uniform_f32() * 0.98 + 0.01,
                ];
                let s = prepared.sample(u);
                let back = prepared.invert(s.dir).expect("inside");
                // The inversion goes through g twice; strong pivots amplify rounding.
                assert!(
                    (back[0] - u[0]).abs() < 2e-3 && (back[1] - u[1]).abs() < 2e-3,
                    "{sptd:?} {cap:?}: {u:?} -> {back:?}"
                );
            }
        }
    }
}

#[test]
fn degenerate_inputs_give_no_sample_and_finite_values() {
    let sptd = Sptd::uniform(Vec3::new(f32::NAN, 0.0, 0.0));
    assert_eq!(sptd.pivot, Vec3::ZERO);
    let strong = Sptd::uniform(Vec3::new(0.0, 0.0, 5.0));
    assert!(strong.pivot.length() < 1.0);
    assert!(SptdInCap::new(&sptd, &Cap::EMPTY).is_none());
    assert_eq!(sptd.integral_over_cap(&Cap::EMPTY), 0.0);
    assert!((sptd.integral_over_cap(&Cap::WHOLE_SPHERE) - 1.0).abs() < 1e-6);
    let nan_cap = Cap {
        axis: Vec3::new(f32::NAN, 0.0, 1.0),
        ..Cap::WHOLE_SPHERE
    };
    assert_eq!(sptd.integral_over_cap(&nan_cap), 0.0);
    for d in [
        Vec3::ZERO,
        Vec3::splat(f32::NAN),
        Vec3::splat(f32::INFINITY),
    ] {
        assert_eq!(strong.eval(d), 0.0);
    }
    let prepared = SptdInCap::new(&strong, &Cap::from_axis_cos(Vec3::Z, 0.5)).unwrap();
    for u in [
        [f32::NAN, 0.5],
        [-1.0, 2.0],
        [1.0, 1.0],
        [f32::INFINITY, 0.0],
    ] {
        let s = prepared.sample(u);
        assert!(
            s.dir.is_finite() && s.pdf.is_finite() && s.pdf > 0.0,
            "{u:?}: {s:?}"
        );
    }
    assert_eq!(prepared.pdf(Vec3::splat(f32::NAN)), 0.0);
    assert_eq!(prepared.pdf(-Vec3::Z), 0.0);
    // A strong pivot: whole-sphere sampling stays finite.
    for k in 0..100 {
        let s = strong.sample([k as f32 / 100.0, 0.3]);
        assert!(s.dir.is_finite() && s.pdf.is_finite());
    }
}

/// Found by fuzzing: `Sptd::sample` computed its pdf from the base direction, which
/// differed from `eval` at the returned direction by 0.1–13% for the clamped-cosine
/// base and pivots near the unit sphere (the Jacobian amplifies the round trip's
/// rounding). Now the pdf is `eval(dir)` bit for bit.
#[test]
fn whole_sphere_sample_pdf_is_eval_of_the_sampled_direction() {
    let mut rng = Rng::new(61);
    for trial in 0..2000 {
        let length = 1.0 - 10f32.powf(-6.0 * rng.uniform_f32());
        let pivot = rng.unit_vector_f32() * length;
        let sptd = if trial % 2 == 0 {
            Sptd::uniform(pivot)
        } else {
            Sptd::clamped_cosine(pivot, rng.unit_vector_f32())
        };
        for _ in 0..10 {
            let s = sptd.sample([rng.uniform_f32(), rng.uniform_f32()]);
            if s.pdf > 0.0 {
                assert_eq!(sptd.eval(s.dir).to_bits(), s.pdf.to_bits(), "{pivot:?}");
            }
        }
    }
}

/// Found by fuzzing: a cosine axis of 2e-21 (denormal |a|²) normalised to a length of
/// 1.00006, and the integral over a hemisphere came out as 1.00006.
#[test]
fn tiny_cosine_axes_are_normalised_exactly() {
    for axis in [
        Vec3::new(1e-30, 2.304376e-21, 1e-30),
        Vec3::new(1e-40, 0.0, 3e-41),
        Vec3::new(3e38, -3e38, 1.0),
    ] {
        let sptd = Sptd::clamped_cosine(Vec3::ZERO, axis);
        assert!((sptd.cosine_axis.length() - 1.0).abs() < 1e-6, "{axis:?}");
        // With the pivot at the origin g(ω) = −ω: the cap around −a maps onto the one around a.
        let hemisphere = Cap::from_axis_one_minus_cos(-sptd.cosine_axis, 1.0);
        let prepared = SptdInCap::new(&sptd, &hemisphere)
            .unwrap_or_else(|| panic!("{axis:?} {sptd:?} {hemisphere:?}"));
        assert!(prepared.integral <= 1.0, "{}", prepared.integral);
    }
}

/// `∫_C f` by the estimator `E[f/pdf]` of a prepared sampler, which includes its dropped
/// draws (as zeros), against the f64 midpoint rule.
fn assert_estimates_integral(prepared: &SptdInCap, f: impl Fn(D3) -> f64, seed: u64, what: &str) {
    let reference = integrate_over_cap_f64(&prepared.cap, 400, &f);
    let mut rng = Rng::new(seed);
    let mut estimate = Estimate::default();
    for _ in 0..200_000 {
        let s = prepared.sample([rng.uniform_f32(), rng.uniform_f32()]);
        estimate.add(if s.pdf > 0.0 {
            f(d3(s.dir)) / s.pdf as f64
        } else {
            0.0
        });
    }
    estimate.assert_mean_is(reference, 5.0, 1e-3, what);
}

/// Issue 17, 3: a clamped-cosine SPTD whose cosine axis lies on the image cap's axis (or
/// within 1e-7 to 1e-5 rad of it), e.g. the cosine axis on the cap's direction with the
/// pivot at the origin. The prepared unit tangent towards the image's axis was the
/// normalised rounding noise of `c − a (c·a)`, not perpendicular to `a`: samples
/// concentrated near the middle (chi-square p = 0, E[1/pdf] 1–25% off) and were dropped
/// outside the cap (424 of 1.3 M).
#[test]
fn clamped_cosine_sptd_with_the_cosine_axis_on_the_image_axis_samples_its_density() {
    let tilt = Vec3::new(0.3, -0.5, 0.8).normalize();
    let cases = [
        // Pivot at the origin: g(ω) = −ω, the image of the cap around −c is around c.
        (Vec3::ZERO, Cap::from_axis_cos(-tilt, 0.9)),
        (Vec3::ZERO, Cap::from_axis_one_minus_cos(-tilt, 1e-3)),
        // Pivots on the cap's axis line and off it.
        (tilt * 0.5, Cap::from_axis_cos(tilt, 0.95)),
        (
            Vec3::new(0.2, 0.4, -0.3),
            Cap::from_axis_cos(Vec3::new(-0.4, 0.1, 0.9), 0.8),
        ),
        (
            Vec3::new(0.0, 0.0, -0.9),
            Cap::from_axis_cos(Vec3::new(0.3, 0.0, -1.0), 0.99),
        ),
    ];
    let mut rng = Rng::new(1717);
    let mut seed = 1700;
    for (pivot, cap) in cases {
        let image = pivot_cap(&cap, valid_pivot(pivot));
        let c = d3(image.axis);
        let (u, v) = frame_f64(c);
        for offset in [0.0, 1e-7, 1e-6, 1e-5] {
            // The cosine axis `offset` rad from the image's axis, in a random direction;
            // at 0 the image's axis itself, bit for bit.
            let sptd = if offset == 0.0 {
                Sptd {
                    cosine_axis: image.axis,
                    ..Sptd::clamped_cosine(pivot, image.axis)
                }
            } else {
                let phi = core::f64::consts::TAU * rng.uniform();
                let a: D3 = core::array::from_fn(|i| {
                    c[i] * f64::cos(offset)
                        + f64::sin(offset) * (phi.cos() * u[i] + phi.sin() * v[i])
                });
                Sptd::clamped_cosine(pivot, Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32))
            };
            let what = format!("{pivot:?} {cap:?}, axis {offset} rad off");
            seed += 1;
            chi_square_in_cap(&sptd, &cap, Some(d3(sptd.cosine_axis)), seed);
            let prepared = SptdInCap::new(&sptd, &cap).expect("prepares");
            let (p64, a64) = (d3(sptd.pivot), d3(sptd.cosine_axis));
            assert_estimates_integral(
                &prepared,
                |w| density_f64(w, p64, Some(a64)) * (1.0 + w[0] * w[0]),
                seed,
                &what,
            );
            // Dropped draws over a million: at most 1e-4.
            let dropped = (0..1_000_000)
                .filter(|_| prepared.sample([rng.uniform_f32(), rng.uniform_f32()]).pdf == 0.0)
                .count();
            assert!(dropped <= 100, "{what}: {dropped} of 1000000 dropped");
        }
    }
}

// ---------------------------------------------------------------------------------------
// Issue 20, 2: the clamped-cosine SPTD in caps whose image is not inside the base's
// hemisphere (crossing its horizon, or wider than a hemisphere), sampled over the
// projection of `g(C) ∩ H_a`.

/// A direction at angle `beta` (rad) from +z, turned by `phi` about z.
fn from_polar(beta: f64, phi: f64) -> Vec3 {
    Vec3::new(
        (beta.sin() * phi.cos()) as f32,
        (beta.sin() * phi.sin()) as f32,
        beta.cos() as f32,
    )
}

/// Configurations given by their image `g(C)` about the cosine axis z: the image's
/// `1 − cos θ` and `cos β = c·z` as a multiple of `sin θ` (|k| < 1 crosses the horizon),
/// and the pivot; the cap is `C = g(image)`.
fn clipped_cases() -> Vec<(&'static str, Vec3, Cap)> {
    let case = |name, pivot: Vec3, t: f64, k: f64, phi: f64| {
        let sin_theta = (t * (2.0 - t)).sqrt();
        let beta = (k * sin_theta).clamp(-1.0, 1.0).acos();
        let image = Cap::from_axis_one_minus_cos(from_polar(beta, phi), t as f32);
        let pivot = valid_pivot(pivot);
        (name, pivot, pivot_cap(&image, pivot))
    };
    let p = Vec3::new(0.3, -0.2, 0.4);
    vec![
        case("just crossing", p, 0.3, 0.9, 0.7),
        case("mostly above", p, 0.3, 0.4, 0.7),
        case("axis on the horizon", p, 0.3, 0.0, 2.0),
        case("mostly below", p, 0.3, -0.6, -1.0),
        case("just crossing from below", p, 0.5, -0.95, 0.3),
        case("wider than a hemisphere, crossing", p, 1.4, 0.3, 0.7),
        case("wider, crossing, axis below", p, 1.6, -0.4, 2.5),
        case("wider, holding the hemisphere", p, 1.8, 1.6, 0.7),
        case("wider, the hemisphere but a hole", p, 1.7, -1.1, 0.7),
        case("tiny near the horizon", p, 1e-5, 0.3, 0.7),
        case("tiny mostly below", Vec3::ZERO, 1e-5, -0.5, 1.1),
        // Strong pivots, with C small: a cap C nearly the whole sphere (the image's
        // complement near the pivot) keeps its hole to f32 precision only, and its
        // image moves by the condition number (1 + ρ)/(1 − ρ) = 2e4 times that.
        case(
            "pivot 0.9999",
            Vec3::new(-0.6, 0.0, -0.8) * 0.9999,
            0.5,
            0.2,
            0.7,
        ),
        case(
            "pivot 0.9999, axis below",
            Vec3::new(0.0, 0.6, -0.8) * 0.9999,
            0.8,
            -0.5,
            -2.0,
        ),
    ]
}

/// The f64 reference of the clamped cosine restricted to an image cap `(c, cos θ)`:
/// in the frame of `a` (height `z = ω·a`, azimuth `φ` from the image axis's
/// tangential direction `e`), `ω·a dω = z dz dφ`, and the directions of height `z` in
/// the cap form one arc `|φ| ≤ ψ(z)`, `cos ψ = (cos θ − z cos β)/(√(1 − z²) sin β)`.
/// Cells: `bands` equal bands of `z` over the cap's part above the horizon, each cut
/// into `columns` equal parts of its arc (`v = (φ/ψ + 1)/2`), where the density is
/// uniform in `φ`: a band's probability is `∫ z 2ψ(z) dz` (midpoint rule in f64) over
/// the total, shared equally by its columns. Independent of the sampler's projection
/// onto the plane ⊥ a and its strips along `e1`.
struct RegionCells {
    a: D3,
    e: D3,
    f: D3,
    cos_beta: f64,
    sin_beta: f64,
    cos_theta: f64,
    z_low: f64,
    z_high: f64,
    bands: usize,
    columns: usize,
    probabilities: Vec<f64>,
    /// `∫_{g(C) ∩ H} ω·a dω`.
    total: f64,
}

impl RegionCells {
    fn new(image: (D3, f64, f64), a: D3, bands: usize, columns: usize) -> RegionCells {
        use core::f64::consts::PI;
        let (c, t, h) = image;
        let cos_theta = if t <= 1.0 { 1.0 - t } else { h - 1.0 };
        let theta = 2.0 * (0.5 * t).sqrt().atan2((0.5 * h).sqrt());
        let cos_beta = dot(c, a).clamp(-1.0, 1.0);
        let along: D3 = core::array::from_fn(|i| c[i] - a[i] * cos_beta);
        let sin_beta = norm(along);
        let e = normalize(along);
        let f = cross(a, e);
        let beta = sin_beta.atan2(cos_beta);
        let z_high = (beta - theta).max(0.0).cos();
        let z_low = (beta + theta).min(PI).cos().max(0.0);
        let mut cells = RegionCells {
            a,
            e,
            f,
            cos_beta,
            sin_beta,
            cos_theta,
            z_low,
            z_high,
            bands,
            columns,
            probabilities: Vec::new(),
            total: 0.0,
        };
        let steps = 4000;
        let width = (z_high - z_low) / bands as f64;
        let masses: Vec<f64> = (0..bands)
            .map(|band| {
                (0..steps)
                    .map(|k| {
                        let z = z_low + width * (band as f64 + (k as f64 + 0.5) / steps as f64);
                        z * 2.0 * cells.half_arc(z)
                    })
                    .sum::<f64>()
                    * width
                    / steps as f64
            })
            .collect();
        cells.total = masses.iter().sum();
        cells.probabilities = masses
            .iter()
            .flat_map(|m| core::iter::repeat_n(m / cells.total / columns as f64, columns))
            .collect();
        cells
    }

    fn half_arc(&self, z: f64) -> f64 {
        let k =
            (self.cos_theta - z * self.cos_beta) / ((1.0 - z * z).max(0.0).sqrt() * self.sin_beta);
        k.clamp(-1.0, 1.0).acos()
    }

    /// The cell of a base direction, `None` outside the region's range of heights (by
    /// more than 1e-3 of it, which f32 rounding of the direction stays below).
    fn cell(&self, w: D3) -> Option<usize> {
        let z = dot(w, self.a);
        let x = (z - self.z_low) / (self.z_high - self.z_low);
        if !(-1e-3..=1.0 + 1e-3).contains(&x) {
            return None;
        }
        let band = ((x * self.bands as f64).max(0.0) as usize).min(self.bands - 1);
        let phi = dot(w, self.f).atan2(dot(w, self.e));
        let psi = self.half_arc(z.clamp(self.z_low, self.z_high));
        let v = if psi > 0.0 {
            (0.5 * (phi / psi + 1.0)).clamp(0.0, 1.0 - 1e-12)
        } else {
            0.5
        };
        Some(band * self.columns + (v * self.columns as f64) as usize)
    }
}

/// The reference cells of a clamped-cosine SPTD (axis z) in a cap: the image of the
/// f32 cap by the f64 pivot (`pivot_image_f64`, independent of `pivot_cap`).
fn region_cells(sptd: &Sptd, cap: &Cap) -> RegionCells {
    let image = pivot_image_f64(d3(cap.axis), cap.one_minus_cos as f64, d3(sptd.pivot));
    RegionCells::new(image, d3(sptd.cosine_axis), 12, 10)
}

/// Chi-square of `n` draws of `sampler` (directions in `C`) against the region's cells,
/// the draws' preimages by the f64 pivot. Returns (statistic, dof, p, dropped).
fn chi_square_region(
    cells: &RegionCells,
    pivot: Vec3,
    sampler: impl Fn([f32; 2]) -> Sample,
    n: usize,
    seed: u64,
) -> (f64, usize, f64, usize) {
    let mut rng = Rng::new(seed);
    let mut observed = vec![0u64; cells.probabilities.len()];
    let (mut dropped, mut outside) = (0, 0u64);
    for _ in 0..n {
        let s = sampler([rng.uniform_f32(), rng.uniform_f32()]);
        if s.pdf == 0.0 {
            dropped += 1;
            continue;
        }
        let w = pivot_transform_f64(d3(s.dir), d3(pivot));
        match cells.cell(w) {
            Some(k) => observed[k] += 1,
            None => outside += 1,
        }
    }
    // Draws outside the region (by more than f32 rounding) fail the test: one more cell
    // of probability ~0.
    let mut probabilities = cells.probabilities.clone();
    observed.push(outside);
    probabilities.push(0.0);
    let (statistic, dof, p) = chi_square(&observed, &probabilities);
    (statistic, dof, p, dropped)
}

#[test]
fn clipped_clamped_cosine_sptd_samples_follow_the_f64_region_density() {
    let n = 200_000;
    for (seed, (name, pivot, cap)) in clipped_cases().into_iter().enumerate() {
        let sptd = Sptd::clamped_cosine(pivot, Vec3::Z);
        let prepared = SptdInCap::new(&sptd, &cap).unwrap_or_else(|| panic!("{name}: no sampler"));
        assert!(prepared.is_clipped(), "{name}");
        let cells = region_cells(&sptd, &cap);
        let (statistic, dof, p, dropped) = chi_square_region(
            &cells,
            sptd.pivot,
            |u| prepared.sample(u),
            n,
            900 + seed as u64,
        );
        eprintln!("{name}: chi² {statistic:.1} dof {dof} p {p:.3} dropped {dropped}");
        assert!(
            p > CHI_SQUARE_ALPHA,
            "{name}: chi² {statistic} dof {dof} p {p}"
        );
        // Draws that rounding moves out of C are dropped; g's condition number
        // (1 + ρ)/(1 − ρ), 2e4 at ρ = 0.9999, moves more of them.
        let allowed = if sptd.pivot.length() > 0.999 {
            n / 1000
        } else {
            n / 10_000
        };
        assert!(dropped <= allowed, "{name}: {dropped} of {n} dropped");
        // The normalisation: the f64 region integral, and the closed form of the module.
        let integral = prepared.integral as f64;
        let reference = cells.total / core::f64::consts::PI;
        assert!(
            (integral - reference).abs() <= 1e-3 * reference + 1e-7,
            "{name}: integral {integral} vs f64 {reference}"
        );
        let closed = sptd.integral_over_cap(&cap) as f64;
        assert!(
            (integral - closed).abs() <= 1e-3 * reference + 1e-7,
            "{name}: integral {integral} vs closed form {closed}"
        );
        // pdf(dir) is the sample's pdf bit for bit, and E[1/pdf] = Ω(C ∩ g(H_a)), the
        // support's solid angle, by the f64 midpoint rule over C (the indicator of the
        // preimage above the horizon).
        let pivot64 = d3(sptd.pivot);
        let support = integrate_over_cap_f64(&cap, 600, |w| {
            (pivot_transform_f64(w, pivot64)[2] > 0.0) as u8 as f64
        });
        let mut rng = Rng::new(77 + seed as u64);
        let mut inverse = Estimate::default();
        for _ in 0..100_000 {
            let s = prepared.sample([rng.uniform_f32(), rng.uniform_f32()]);
            if s.pdf > 0.0 {
                assert_eq!(prepared.pdf(s.dir).to_bits(), s.pdf.to_bits(), "{name}");
                assert!(cap.contains(s.dir), "{name}");
                inverse.add(1.0 / s.pdf as f64);
            } else {
                inverse.add(0.0);
            }
        }
        inverse.assert_mean_is(
            support,
            5.0,
            5e-3,
            &format!("{name}: E[1/pdf] = Ω(C ∩ g(H))"),
        );
    }
}

/// Wrong samplers that the region test must reject (p far below α): uniform in
/// `g(C) ∩ H_a` (the cosine weight forgotten, through `CapIntersection`), and the right
/// sampler with its offset across the strip distorted (`u₁ → u₁^1.3`).
#[test]
fn the_region_chi_square_rejects_wrong_clipped_samplers() {
    use super::super::cap_intersection_sampling::CapIntersection;
    let n = 200_000;
    for (seed, (name, pivot, cap)) in clipped_cases().into_iter().enumerate() {
        let sptd = Sptd::clamped_cosine(pivot, Vec3::Z);
        let prepared = SptdInCap::new(&sptd, &cap).unwrap();
        let cells = region_cells(&sptd, &cap);
        let hemisphere = Cap::from_axis_one_minus_cos(Vec3::Z, 1.0);
        let uniform = CapIntersection::new(&prepared.image, &hemisphere).unwrap();
        let forgets_cosine = |u: [f32; 2]| {
            let s = uniform.sample_uniform(u);
            let dir = transform(s.dir, sptd.pivot);
            if cap.contains(dir) {
                Sample { dir, pdf: 1.0 }
            } else {
                Sample::NONE
            }
        };
        let (_, _, p_uniform, _) =
            chi_square_region(&cells, sptd.pivot, forgets_cosine, n, 950 + seed as u64);
        let distorted = |u: [f32; 2]| prepared.sample([u[0], u[1].powf(1.3)]);
        let (_, _, p_distorted, _) =
            chi_square_region(&cells, sptd.pivot, distorted, n, 970 + seed as u64);
        eprintln!(
            "{name}: wrong samplers p {p_uniform:.3e} (uniform), {p_distorted:.3e} (distorted offset)"
        );
        assert!(
            p_distorted < CHI_SQUARE_ALPHA,
            "{name}: distorted offset p {p_distorted}"
        );
        assert!(
            p_uniform < CHI_SQUARE_ALPHA,
            "{name}: uniform p {p_uniform}"
        );
    }
}

#[test]
fn clipped_pdf_integrates_to_one() {
    for (name, pivot, cap) in clipped_cases() {
        let sptd = Sptd::clamped_cosine(pivot, Vec3::Z);
        let prepared = SptdInCap::new(&sptd, &cap).unwrap();
        let f32_dir = |w: D3| Vec3::new(w[0] as f32, w[1] as f32, w[2] as f32);
        // Over C (midpoint rule refined towards its axis); a pivot of 0.9999 concentrates
        // the density by (1 + ρ)²/(1 − ρ)² = 4e8 where no grid over C finds it.
        let over_cap = integrate_over_cap_f64(&cap, 600, |w| prepared.pdf(f32_dir(w)) as f64);
        // Over the image, with ω = g(ω_i) and dω = dω_i / J(ω) (Eq. 4, 8): the same
        // integral, well conditioned for every pivot.
        let pivot64 = d3(sptd.pivot);
        let image64 = pivot_image_f64(d3(cap.axis), cap.one_minus_cos as f64, pivot64);
        let image = Cap::from_axis_one_minus_cos(f32_dir(image64.0), image64.1 as f32);
        let over_image = integrate_over_cap_f64(&image, 600, |wi| {
            let w = pivot_transform_f64(wi, pivot64);
            let e: D3 = core::array::from_fn(|i| w[i] - pivot64[i]);
            let jacobian = ((1.0 - dot(pivot64, pivot64)) / dot(e, e)).powi(2);
            prepared.pdf(f32_dir(w)) as f64 / jacobian
        });
        eprintln!("{name}: ∫ pdf = {over_cap} over C, {over_image} over g(C)");
        assert!(
            (over_image - 1.0).abs() <= 5e-3,
            "{name}: ∫ pdf = {over_image}"
        );
        if sptd.pivot.length() < 0.99 {
            assert!((over_cap - 1.0).abs() <= 5e-3, "{name}: ∫ pdf = {over_cap}");
        }
    }
}

/// Random pivots (up to |r_p| = 0.9999), caps (1e-6 sr to nearly the whole sphere) and
/// cosine axes: a sampler whenever the integral is positive; samples finite, in `C`,
/// with `pdf(dir)` their pdf bit for bit; pdf 0 outside `C` and where the preimage is
/// below the horizon; the prepared integral the closed form's; inversion.
#[test]
fn clipped_hard_cases_are_finite_and_consistent() {
    let mut rng = Rng::new(2020);
    let mut clipped = 0;
    for trial in 0..4000 {
        let length = match trial % 4 {
            0 => 0.0,
            1 => rng.uniform_f32() * 0.9,
            2 => 1.0 - 10f32.powf(-4.0 * rng.uniform_f32()),
            _ => 0.9999,
        };
        let pivot = rng.unit_vector_f32() * length;
        let t = match trial % 5 {
            0 => rng.log_uniform(-6.5, -2.0) as f32,
            1 => rng.uniform_f32(),
            2 => 1.0 + rng.uniform_f32(),
            3 => 2.0 - rng.log_uniform(-6.0, -1.0) as f32,
            _ => 1.0,
        };
        let cap = Cap::from_axis_one_minus_cos(rng.unit_vector_f32(), t);
        let sptd = Sptd::clamped_cosine(pivot, rng.unit_vector_f32());
        let closed = sptd.integral_over_cap(&cap);
        let Some(prepared) = SptdInCap::new(&sptd, &cap) else {
            // No sampler only where the integral vanishes (or its inverse overflows).
            assert!(
                !(closed > 1e-30),
                "{sptd:?} {cap:?}: no sampler but ∫ = {closed}"
            );
            continue;
        };
        if !prepared.is_clipped() {
            continue;
        }
        clipped += 1;
        let what = format!("{sptd:?} {cap:?}");
        // The projected area against the closed form (which cancels for slivers).
        assert!(
            (prepared.integral - closed).abs() <= 2e-3 * closed + 2e-6,
            "{what}: {} vs {closed}",
            prepared.integral
        );
        for k in 0..64 {
            let u = match k {
                0 => [0.0, 0.0],
                1 => [ONE_MINUS_ULP, ONE_MINUS_ULP],
                2 => [0.0, ONE_MINUS_ULP],
                3 => [ONE_MINUS_ULP, 0.5],
                4 => [f32::NAN, f32::INFINITY],
                _ => [rng.uniform_f32(), rng.uniform_f32()],
            };
            let s = prepared.sample(u);
            assert!(
                s.dir.is_finite() && s.pdf.is_finite() && s.pdf >= 0.0,
                "{what} {u:?}: {s:?}"
            );
            if s.pdf > 0.0 {
                assert!(cap.contains(s.dir), "{what} {u:?}");
                assert_eq!(
                    prepared.pdf(s.dir).to_bits(),
                    s.pdf.to_bits(),
                    "{what} {u:?}"
                );
                let back = prepared.invert(s.dir).expect("inside");
                assert!(back[0].is_finite() && back[1].is_finite());
            }
        }
        // pdf 0 outside C, and inside C where the preimage is below the horizon.
        if !cap.contains(-cap.axis) {
            assert_eq!(prepared.pdf(-cap.axis), 0.0, "{what}");
        }
        for _ in 0..16 {
            let w = rng.unit_vector_f32();
            let p = prepared.pdf(w);
            assert!(p.is_finite() && p >= 0.0, "{what}");
            if !cap.contains(w) || transform(w, sptd.pivot).dot(sptd.cosine_axis) < 0.0 {
                assert_eq!(p, 0.0, "{what}: pdf({w:?})");
            }
        }
    }
    assert!(clipped >= 1000, "only {clipped} clipped samplers");
}

/// Inversion of the clipped sampler in the configurations of the region test.
#[test]
fn clipped_samples_invert_to_their_random_numbers() {
    let mut rng = Rng::new(2021);
    for (name, pivot, cap) in clipped_cases() {
        let sptd = Sptd::clamped_cosine(pivot, Vec3::Z);
        let prepared = SptdInCap::new(&sptd, &cap).unwrap();
        let strong = sptd.pivot.length() > 0.99;
        let mut worst = 0.0f32;
        for _ in 0..2000 {
            let u = [
                rng.uniform_f32() * 0.98 + 0.01,
                rng.uniform_f32() * 0.98 + 0.01,
            ];
            let s = prepared.sample(u);
            if s.pdf == 0.0 {
                continue;
            }
            let back = prepared.invert(s.dir).expect("inside");
            worst = worst
                .max((back[0] - u[0]).abs())
                .max((back[1] - u[1]).abs());
        }
        eprintln!("{name}: worst inversion error {worst:e}");
        // g's condition number (1 + ρ)/(1 − ρ) = 2e4 at 0.9999 amplifies the round trip.
        assert!(worst < if strong { 3e-2 } else { 2e-3 }, "{name}: {worst}");
    }
}

/// The uniform base draws in its image with the frame prepared in `e1` and `ellipse`:
/// every sample is `g` of `Cap::sample_uniform` of the image (which builds the frame per
/// sample), bit for bit, over random caps (tiny to wider than a hemisphere) and pivots
/// (up to the table's `1 − 3.3e-5`).
#[test]
fn the_uniform_base_s_prepared_frame_gives_cap_sampling_s_bits() {
    let mut rng = Rng::new(1809);
    let mut compared = 0;
    for _ in 0..2000 {
        let cap =
            Cap::from_axis_one_minus_cos(rng.unit_vector_f32(), rng.log_uniform(-6.0, 0.3) as f32);
        let pivot = rng.unit_vector_f32() * (0.99997 * rng.uniform_f32());
        let sptd = Sptd::uniform(pivot);
        let Some(sampler) = SptdInCap::new(&sptd, &cap) else {
            continue;
        };
        for _ in 0..20 {
            let u = [rng.uniform_f32(), rng.uniform_f32()];
            let s = sampler.sample(u);
            let base = sampler.image.sample_uniform(u);
            let dir = crate::sphere::pivot::transform(base.dir, sptd.pivot);
            if s.pdf > 0.0 {
                assert_eq!(
                    s.dir.to_array().map(f32::to_bits),
                    dir.to_array().map(f32::to_bits),
                    "{cap:?} {pivot:?} {u:?}"
                );
                compared += 1;
            } else {
                assert!(
                    base.pdf == 0.0 || !sampler.cap.contains(dir),
                    "{cap:?} {u:?}"
                );
            }
        }
    }
    assert!(compared > 20_000, "{compared}");
}

/// `sample_uniform_base` tests the uniform pdf `1/Ω` for 0 without computing it (the
/// comparisons of `Ω = 2π t` with `MIN_NORMALISER` and infinity): its samples are bit for
/// bit the old path's (`uniform_pdf`, no sample where it is 0, `sample_uniform_in_frame`
/// with it, then the same steps) for the hard cases' and random uniform SPTDs in caps with
/// random and extreme `u`, and with the image's `t = 1 − cos` corrupted as only a struct
/// from C can hold it: 0, −0, negative, NaN, every 97th denormal, the `t` within 64 ulps
/// of where `1/(2π t)` overflows, huge ones within 64 ulps of where `2π t` overflows (its
/// reciprocal 0), `f32::MAX` and infinity. Both paths give no sample in the same cases.
#[test]
fn the_uniform_base_sample_skips_the_uniform_pdf() {
    let old_path = |p: &SptdInCap, u: [f32; 2]| -> Sample {
        let image = &p.image;
        let pdf = image.uniform_pdf();
        if pdf == 0.0 {
            return Sample::NONE;
        }
        let frame = [image.axis.into(), p.e1.into(), p.ellipse.into()];
        let s = sample_uniform_in_frame(frame, image.one_minus_cos, image.one_plus_cos, pdf, u);
        if s.pdf == 0.0 {
            return Sample::NONE;
        }
        let dir = transform(s.dir, p.sptd.pivot);
        if !p.cap.contains_inlined(dir) {
            return Sample::NONE;
        }
        let pdf = jacobian(dir, p.sptd.pivot) / image.solid_angle();
        if pdf > 0.0 && pdf.is_finite() {
            Sample { dir, pdf }
        } else {
            Sample::NONE
        }
    };
    let bits = |s: Sample| (s.dir.to_array().map(f32::to_bits), s.pdf.to_bits());
    let mut rng = Rng::new(3907);
    let mut prepared: Vec<SptdInCap> = hard_cases()
        .iter()
        .filter_map(|(pivot, cap)| SptdInCap::new(&Sptd::uniform(*pivot), cap))
        .collect();
    while prepared.len() < 300 {
        let pivot = rng.unit_vector_f32() * (0.99 * rng.uniform_f32());
        let cap = Cap::from_axis_cos(rng.unit_vector_f32(), 2.0 * rng.uniform_f32() - 1.0);
        if let Some(p) = SptdInCap::new(&Sptd::uniform(pivot), &cap) {
            prepared.push(p);
        }
    }
    let extremes = [0.0, 0.5, 1.0 - f32::EPSILON / 2.0];
    let mut us: Vec<[f32; 2]> = (0..40)
        .map(|_| [rng.uniform_f32(), rng.uniform_f32()])
        .collect();
    for a in extremes {
        for b in extremes {
            us.push([a, b]);
        }
    }
    let mut samples = 0;
    for p in &prepared {
        for &u in &us {
            let (got, expected) = (p.sample_uniform_base(u), old_path(p, u));
            assert_eq!(bits(got), bits(expected), "{p:?} {u:?}");
            samples += (got.pdf > 0.0) as u32;
        }
    }
    assert!(samples > 10_000, "{samples}");
    // Corrupted images' `t`.
    let overflow_of_reciprocal = (MIN_NORMALISER / TAU).to_bits();
    let overflow_of_product = (f32::MAX / TAU).to_bits();
    let mut corrupted: Vec<f32> = vec![0.0, -0.0, -1.0, f32::NAN, f32::MAX, f32::INFINITY];
    corrupted.extend((1..0x0080_0000u32).step_by(97).map(f32::from_bits));
    for centre in [overflow_of_reciprocal, overflow_of_product] {
        corrupted.extend((centre - 64..=centre + 64).map(f32::from_bits));
    }
    let mut none = 0;
    for &t in &corrupted {
        for p in prepared.iter().take(20) {
            let mut p = *p;
            p.image.one_minus_cos = t;
            for &u in us.iter().take(8) {
                let (got, expected) = (p.sample_uniform_base(u), old_path(&p, u));
                assert_eq!(bits(got), bits(expected), "t = {t:e} {u:?}");
                none += (got.pdf == 0.0) as u32;
            }
        }
    }
    assert!(none > 1000, "{none}");
}

/// The zero pivot's image in closed form (`prepare_uniform_of_zero_pivot`, the sphere
/// light sampler's fallback) prepares as the careful path (`prepare_sanitized` of
/// `Sptd::uniform_of_valid(Vec3::ZERO)`, through `pivot_cap`) does: the same result for
/// every cap, tiny ones around the overflow of `1/∫` and around `ANTIPODAL_MIN_SIDE`
/// included, the same distribution and cap, and an integral within a few ulps.
#[test]
fn the_zero_pivot_s_antipodal_image_prepares_as_the_careful_one() {
    let mut rng = Rng::new(45);
    let mut sides: Vec<f32> = vec![
        f32::from_bits(1),
        1e-45,
        1e-40,
        5.8e-39,
        5.9e-39,
        6e-39,
        1.2e-38,
        1e-35,
        ANTIPODAL_MIN_SIDE,
        f32::from_bits(ANTIPODAL_MIN_SIDE.to_bits() - 1),
        f32::from_bits(ANTIPODAL_MIN_SIDE.to_bits() + 1),
        1e-12,
        1e-6,
        0.5,
        1.0,
        1.5,
        2.0 - f32::EPSILON,
        2.0,
    ];
    for _ in 0..2000 {
        sides.push(rng.log_uniform(-45.0, 0.3) as f32);
    }
    let (mut closed, mut careful) = (0, 0);
    for (i, &side) in sides.iter().enumerate() {
        let axis = if i % 3 == 0 {
            Vec3::Z
        } else {
            rng.unit_vector_f32()
        };
        let cap = Cap::from_axis_one_minus_cos(axis, side.min(2.0)).sanitized();
        let zero = Sptd::uniform_of_valid(Vec3::ZERO);
        let mut old = SptdInCap::EMPTY;
        let old_ok = old.prepare_sanitized(&zero, &cap);
        let mut new = SptdInCap::EMPTY;
        let new_ok = new.prepare_uniform_of_zero_pivot(&cap);
        assert_eq!(new_ok, old_ok, "{cap:?}");
        if cap.one_minus_cos >= ANTIPODAL_MIN_SIDE {
            closed += 1;
            assert!(new_ok, "{cap:?}");
            assert_eq!(new.image.axis, -cap.axis);
            assert_eq!(new.image.one_minus_cos, cap.one_minus_cos);
        } else {
            careful += 1;
            assert_eq!(new, old);
        }
        if new_ok {
            assert_eq!((new.sptd, new.cap), (old.sptd, old.cap));
            let error = (new.integral - old.integral).abs() / old.integral;
            assert!(
                error <= 2e-6,
                "{cap:?}: {} vs {}",
                new.integral,
                old.integral
            );
        } else {
            assert_eq!(new, SptdInCap::EMPTY);
        }
    }
    assert!(closed > 500 && careful > 100, "{closed} {careful}");
}
