use super::*;
use crate::testing::{
    CHI_SQUARE_ALPHA, D3, Rng, chi_square, d3, dot, frame_f64, normalize,
    sphere_cap_one_minus_cos_f64, sub,
};

/// `1 − ω·a` in f64 for unit vectors, by `|ω − a|²/2`.
fn one_minus_dot_f64(w: D3, a: D3) -> f64 {
    let w = normalize(w);
    let a = normalize(a);
    let e = sub(w, a);
    0.5 * dot(e, e)
}

#[test]
fn solid_angle_matches_f64_for_tiny_to_huge_caps_and_scaled_coordinates() {
    let mut rng = Rng::new(1);
    let mut worst = 0.0f64;
    let (mut worst_below, mut worst_above) = (0.0f64, 0.0f64);
    for i in 0..20000 {
        let dir = rng.unit_vector_f32();
        // sin²θ log-uniform in [1e-12, 1), then an f32 radius and distance.
        let sin2 = rng.log_uniform(-12.0, 0.0);
        let distance = rng.log_uniform(-3.0, 3.0) as f32;
        let radius = (distance as f64 * sin2.sqrt()) as f32;
        let scale = match i % 5 {
            0 => 1.0,
            1 => 1.267_650_6e30,
            2 => 7.888_609e-31,
            3 => 1e30,
            _ => 1e-30,
        };
        let center = dir * distance * scale;
        let radius = radius * scale;
        if !(radius > 0.0) || !center.is_finite() || !radius.is_finite() {
            continue;
        }
        let cap = Cap::from_sphere(center, radius);
        let reference = sphere_cap_one_minus_cos_f64(d3(center), radius as f64);
        let error = (cap.one_minus_cos as f64 - reference).abs() / reference;
        worst = worst.max(error);
        if sin2 < 0.75 {
            worst_below = worst_below.max(error);
        } else {
            worst_above = worst_above.max(error);
        }
        assert!(
            error < 2e-6,
            "center {center:?} radius {radius}: 1 − cos {} vs {reference}",
            cap.one_minus_cos
        );
        let omega = cap.solid_angle() as f64;
        let omega_ref = 2.0 * core::f64::consts::PI * reference;
        assert!((omega - omega_ref).abs() <= 3e-6 * omega_ref);
        assert!((cap.axis.length() - 1.0).abs() < 1e-6);
        assert!((cap.cos() as f64 - (1.0 - reference)).abs() < 1e-6);
        assert!((cap.one_plus_cos as f64 - (2.0 - reference)).abs() < 1e-6);
    }
    assert!(worst > 0.0, "the test compared nothing");
    // In units of 2⁻²⁴ (half an ulp of 1): 4.12 below sin²θ = 0.75 (the form
    // sin²θ / (1 + √(1 − sin²θ)); 5.13 with the form of the wide caps), 9.76 above.
    let (below, above) = (worst_below * 16_777_216.0, worst_above * 16_777_216.0);
    std::println!(
        "worst relative error of 1 − cos θ in units of 2⁻²⁴: sin²θ < 0.75 {below:.2}, above {above:.2}"
    );
    assert!(below <= 4.5 && above <= 10.0, "{below} {above}");
}

#[test]
fn distant_spheres_keep_relative_precision() {
    for &(d, r) in &[(1e6f32, 1.0f32), (1.0, 1e-6), (3.0e7, 0.5), (1e20, 1e14)] {
        let cap = Cap::from_sphere(Vec3::new(0.3 * d, -0.4 * d, 0.866_025_4 * d), r);
        let reference = sphere_cap_one_minus_cos_f64(
            d3(Vec3::new(0.3 * d, -0.4 * d, 0.866_025_4 * d)),
            r as f64,
        );
        assert!(
            ((cap.one_minus_cos as f64 - reference) / reference).abs() < 2e-6,
            "{d} {r}: {} vs {reference}",
            cap.one_minus_cos
        );
        // A direct `1 − cos` in f32 would give 0 (or a few bits) here.
        assert!(cap.solid_angle() > 0.0);
    }
}

#[test]
fn whole_sphere_on_and_inside_and_invalid_spheres() {
    let c = Vec3::new(0.0, 0.0, 2.0);
    assert_eq!(Cap::from_sphere(c, 2.0).one_minus_cos, 2.0);
    assert_eq!(Cap::from_sphere(c, 3.0).one_minus_cos, 2.0);
    assert_eq!(Cap::from_sphere(Vec3::ZERO, 1.0).one_minus_cos, 2.0);
    let whole = Cap::from_sphere(c, 3.0);
    assert!((whole.solid_angle() - 4.0 * PI).abs() < 1e-6);
    assert!(whole.contains(Vec3::new(0.0, 0.0, -1.0)));
    // Just outside the sphere: nearly a hemisphere.
    let near = Cap::from_sphere(c, 2.0 * (1.0 - 1e-6));
    assert!(near.one_minus_cos > 0.99 && near.one_minus_cos <= 1.0);
    for (center, radius) in [
        (c, 0.0),
        (c, -1.0),
        (c, f32::NAN),
        (c, f32::INFINITY),
        (Vec3::new(f32::NAN, 0.0, 1.0), 1.0),
        (Vec3::new(f32::INFINITY, 0.0, 1.0), 1.0),
    ] {
        let cap = Cap::from_sphere(center, radius);
        assert_eq!(cap, Cap::EMPTY);
        assert_eq!(cap.solid_angle(), 0.0);
        assert_eq!(cap.sample_uniform([0.5, 0.5]).pdf, 0.0);
        assert!(!cap.contains(Vec3::Z));
    }
    // Huge coordinates do not overflow.
    let cap = Cap::from_sphere(Vec3::new(3e38, 3e38, 3e38), 1e38);
    assert!(cap.one_minus_cos > 0.0 && cap.one_minus_cos.is_finite());
    assert!((cap.axis.length() - 1.0).abs() < 1e-6);
}

#[test]
fn from_axis_cos_and_sanitized_handle_garbage() {
    let cap = Cap::from_axis_cos(Vec3::new(0.0, 0.0, 5.0), -0.5);
    assert_eq!(cap.axis, Vec3::Z);
    assert!((cap.one_minus_cos - 1.5).abs() < 1e-7);
    assert!((cap.sin2 - 0.75).abs() < 1e-6);
    let garbage = Cap {
        axis: Vec3::new(f32::NAN, 1.0, 0.0),
        one_minus_cos: 7.0,
        one_plus_cos: f32::INFINITY,
        sin2: -3.0,
    };
    assert_eq!(garbage.sanitized(), Cap::EMPTY);
    let big = Cap {
        axis: Vec3::new(3e38, 3e38, 0.0),
        one_minus_cos: 7.0,
        one_plus_cos: 0.0,
        sin2: 0.0,
    }
    .sanitized();
    assert_eq!(big.one_minus_cos, 2.0);
    assert!((big.axis.length() - 1.0).abs() < 1e-6);
}

/// Samples a cap, checks every sample against the pdf, containment and inversion, and
/// runs a chi-square test on cells uniform in `(1 − cos)/(1 − cos θ)` and `φ` (in an
/// independent f64 frame).
fn check_sampler(cap: Cap, seed: u64, samples: usize) {
    const N: usize = 12;
    let mut rng = Rng::new(seed);
    let a = d3(cap.axis);
    let (t64, b64) = frame_f64(a);
    let t_max = cap.one_minus_cos as f64;
    let mut counts = vec![0u64; N * N];
    let mut worst_round_trip = 0.0f32;
    for _ in 0..samples {
        let u = [rng.uniform_f32(), rng.uniform_f32()];
        let s = cap.sample_uniform(u);
        assert!(s.pdf > 0.0 && s.dir.is_finite());
        assert!((s.dir.length() - 1.0).abs() < 1e-6);
        let expected_pdf = 1.0 / (2.0 * core::f64::consts::PI * t_max);
        assert!(((s.pdf as f64 - expected_pdf) / expected_pdf).abs() < 1e-6);
        let w = d3(s.dir);
        let t = one_minus_dot_f64(w, a);
        assert!(
            t <= t_max * (1.0 + 1e-4) + 1e-7,
            "sample outside the cap: {t} > {t_max}"
        );
        let pdf = cap.pdf(s.dir);
        // Every sample inside by the cap's own test (issue 16, 4: rim samples rounded
        // outside, where `pdf` is 0).
        assert_eq!(pdf, s.pdf, "{u:?}: pdf(dir) differs from the sample's");
        {
            // The round trip in direction space: f32 directions do not resolve `u`
            // near the axis of a small cap, but the direction comes back to rounding.
            let v = cap.invert(s.dir).expect("inside");
            let back = cap.sample_uniform(v).dir;
            worst_round_trip = worst_round_trip.max((back - s.dir).length());
            if cap.one_minus_cos > 0.1 {
                let du1 = (v[1] - u[1]).abs().min(1.0 - (v[1] - u[1]).abs());
                assert!((v[0] - u[0]).abs() < 1e-4 && du1 < 1e-4, "{u:?} -> {v:?}");
            }
        }
        let phi = dot(w, b64).atan2(dot(w, t64));
        let phi01 = (phi / (2.0 * core::f64::consts::PI)).rem_euclid(1.0);
        let i = ((t / t_max * N as f64) as usize).min(N - 1);
        let j = ((phi01 * N as f64) as usize).min(N - 1);
        counts[i * N + j] += 1;
    }
    let probabilities = vec![1.0 / (N * N) as f64; N * N];
    let (statistic, dof, p) = chi_square(&counts, &probabilities);
    assert!(
        p > CHI_SQUARE_ALPHA,
        "cap {cap:?}: chi-square {statistic} with {dof} dof, p = {p}"
    );
    // Near the antipode of a wide cap, `sin θ = √(t(2 − t))` rounds `2 − t`.
    let allowed = if cap.one_minus_cos <= 1.0 { 1e-6 } else { 3e-4 };
    assert!(
        worst_round_trip < allowed,
        "cap {cap:?}: inverse round trip {worst_round_trip}"
    );
}

#[test]
fn uniform_sampling_passes_chi_square_with_consistent_pdf_and_inverse() {
    let mut rng = Rng::new(7);
    let axis = rng.unit_vector_f32();
    check_sampler(Cap::from_sphere(axis * 3.0, 1.0), 11, 200_000);
    check_sampler(Cap::from_sphere(axis * 1e3, 1.0), 12, 200_000);
    check_sampler(Cap::from_axis_cos(axis, 0.0), 13, 200_000);
    check_sampler(Cap::from_axis_cos(axis, -0.7), 14, 200_000);
    check_sampler(Cap::from_axis_one_minus_cos(axis, 2.0), 15, 200_000);
    // Tiny caps around an axis close to z, where f32 directions resolve them.
    check_sampler(Cap::from_sphere(Vec3::new(0.0, 0.0, 1e5), 1.0), 16, 200_000);
    check_sampler(Cap::from_sphere(Vec3::new(0.0, 0.0, 1e6), 1.0), 17, 200_000);
}

#[test]
fn tiny_cap_samples_stay_inside_and_spread_over_the_cap() {
    // sin²θ = 1e-12: a direct `1 − cos` in f32 would be 0 and every sample the axis.
    let cap = Cap::from_sphere(Vec3::new(0.0, 0.0, 1e6), 1.0);
    let mut rng = Rng::new(3);
    let mut largest = 0.0f64;
    for _ in 0..10000 {
        let s = cap.sample_uniform([rng.uniform_f32(), rng.uniform_f32()]);
        let sin = ((s.dir.x as f64).powi(2) + (s.dir.y as f64).powi(2)).sqrt();
        assert!(sin <= 1e-6 * (1.0 + 1e-5));
        largest = largest.max(sin);
    }
    assert!(
        largest > 0.99e-6,
        "samples do not reach the boundary: {largest}"
    );
}

#[test]
fn containment_boundary_matches_f64() {
    let mut rng = Rng::new(5);
    let mut disagreements = 0;
    for _ in 0..20000 {
        let axis = rng.unit_vector_f32();
        let cos = (2.0 * rng.uniform() - 1.0) as f32;
        let cap = Cap::from_axis_cos(axis, cos);
        let w = rng.unit_vector_f32();
        let t = one_minus_dot_f64(d3(w), d3(cap.axis));
        let inside = t <= cap.one_minus_cos as f64;
        if (t - cap.one_minus_cos as f64).abs() > 1e-5 {
            assert_eq!(cap.contains(w), inside);
            assert_eq!(cap.pdf(w) > 0.0, inside);
            assert_eq!(cap.invert(w).is_some(), inside);
        } else {
            disagreements += (cap.contains(w) != inside) as usize;
        }
    }
    assert!(disagreements < 10);
}

/// Issue 16 (4): samples from the rim of small caps (u0 next to 1) rounded outside the
/// cap, where `pdf` is 0: the 1e-7 sr cap and random small caps, every sample at
/// u0 = 1 - ulp and near it now inside with `pdf(dir) == pdf`.
#[test]
fn rim_samples_of_small_caps_are_inside() {
    let from_bits = |x: u32| f32::from_bits(x);
    let cap = Cap::from_sphere(
        Vec3::new(
            from_bits(0xc120e6d0),
            from_bits(0x40f8aaa1),
            from_bits(0x4106ee51),
        ),
        from_bits(0x3ad2a42c),
    );
    let u = [from_bits(0x3f7ff8d7), from_bits(0x3f3ef3c4)];
    let s = cap.sample_uniform(u);
    assert!(s.pdf > 0.0 && cap.pdf(s.dir) == s.pdf, "{s:?}");
    let mut rng = Rng::new(19);
    for _ in 0..2000 {
        let distance = 10f32.powf(1.0 + 5.0 * rng.uniform_f32());
        let cap = Cap::from_sphere(rng.unit_vector_f32() * distance, 1.0);
        for u0 in [crate::sample::ONE_MINUS_ULP, 0.999_99, 0.9999] {
            let s = cap.sample_uniform([u0, rng.uniform_f32()]);
            assert!(s.pdf > 0.0, "{cap:?} at u0 = {u0}: no sample");
            assert_eq!(cap.pdf(s.dir), s.pdf, "{cap:?} at u0 = {u0}");
        }
    }
}

/// Issue 16 (4): a cap with `1 − cos θ = 2 − ulp` (all but a disk of 7e-4 rad around the
/// antipode): directions 2e-4 rad inside its boundary were outside by the plain test,
/// whose `|ω − a|²/2` near 2 has no absolute precision left. The complement form
/// decides them right (against f64), and every sample is inside.
#[test]
fn a_nearly_whole_sphere_cap_contains_what_is_inside() {
    let cap = Cap::from_axis_one_minus_cos(
        Vec3::new(1.0, 0.25, 0.25).normalize(),
        2.0 - 2.0 * f32::EPSILON / 2.0,
    );
    let axis = normalize(d3(cap.axis));
    let antipode = [-axis[0], -axis[1], -axis[2]];
    // 1 + cos ρ = 2 − (1 − cos θ) for the excluded disk's radius ρ around the antipode.
    let one_plus_cos_boundary = 2.0 - cap.one_minus_cos as f64;
    let excluded = (2.0 * one_plus_cos_boundary).sqrt();
    let (t, b) = frame_f64(antipode);
    let mut rng = Rng::new(23);
    let mut decided = 0;
    for _ in 0..20_000 {
        // Directions at 0.5 to 1.5 times the excluded radius from the antipode.
        let angle = excluded * (0.5 + rng.uniform());
        let phi = 2.0 * core::f64::consts::PI * rng.uniform();
        let w: [f64; 3] = core::array::from_fn(|i| {
            antipode[i] * angle.cos() + (t[i] * phi.cos() + b[i] * phi.sin()) * angle.sin()
        });
        let dir = Vec3::new(w[0] as f32, w[1] as f32, w[2] as f32);
        // In f64 from the f32 direction: 1 + ω·a, exact enough near the antipode.
        let one_plus = 1.0 + dot(normalize(d3(dir)), axis);
        // Only directions clearly on one side (by 2% in 1 + cos).
        if (one_plus / one_plus_cos_boundary - 1.0).abs() > 2e-2 {
            let inside = one_plus >= one_plus_cos_boundary;
            assert_eq!(
                cap.contains(dir),
                inside,
                "{dir} at {angle} rad from the antipode"
            );
            decided += 1;
        }
    }
    assert!(decided > 15_000);
    for _ in 0..20_000 {
        let s = cap.sample_uniform([rng.uniform_f32(), rng.uniform_f32()]);
        assert!(s.pdf > 0.0 && cap.pdf(s.dir) == s.pdf);
    }
    let s = cap.sample_uniform([crate::sample::ONE_MINUS_ULP, crate::sample::ONE_MINUS_ULP]);
    assert!(s.pdf > 0.0 && cap.pdf(s.dir) == s.pdf);
}

/// `sanitized` takes the caps that the constructors write as they are (the caps of
/// spheres included), makes any other cap valid, and is idempotent bit for bit.
#[test]
fn sanitized_keeps_valid_caps_and_is_idempotent() {
    let mut rng = Rng::new(7);
    for _ in 0..2000 {
        let dir = rng.unit_vector_f32();
        let sin2 = rng.log_uniform(-12.0, 0.0);
        let distance = rng.log_uniform(-3.0, 3.0) as f32;
        let radius = (distance as f64 * sin2.sqrt()) as f32;
        for cap in [
            Cap::from_sphere(dir * distance, radius),
            Cap::from_sphere(dir * distance, distance * 2.0),
            Cap::from_axis_cos(dir, (1.0 - 2.0 * sin2) as f32),
            Cap::from_axis_one_plus_cos(dir * 3.0, sin2 as f32),
            Cap::from_axis_one_minus_cos(dir, sin2 as f32).sanitized(),
        ] {
            assert_eq!(cap.sanitized(), cap, "{cap:?}");
        }
    }
    let hand_built = [
        Cap {
            axis: Vec3::new(0.0, 0.0, 2.0),
            one_minus_cos: 0.5,
            one_plus_cos: 1.5,
            sin2: 0.75,
        },
        Cap {
            axis: Vec3::Z,
            one_minus_cos: 0.5,
            one_plus_cos: 1.0,
            sin2: 0.75,
        },
        Cap {
            axis: Vec3::Z,
            one_minus_cos: 1.999,
            one_plus_cos: 0.001,
            sin2: 0.5,
        },
        Cap {
            axis: Vec3::new(f32::NAN, 1.0, 0.0),
            one_minus_cos: 7.0,
            one_plus_cos: f32::INFINITY,
            sin2: -3.0,
        },
        Cap {
            axis: Vec3::X,
            one_minus_cos: -1.0,
            one_plus_cos: 3.0,
            sin2: 0.0,
        },
    ];
    for cap in hand_built {
        let valid = cap.sanitized();
        assert_ne!(valid, cap, "{cap:?}");
        assert_eq!(valid.sanitized(), valid, "{cap:?}");
        assert!((valid.axis.length() - 1.0).abs() < 1e-6, "{cap:?}");
    }
}

/// Which spheres `Cap::from_sphere` takes without rescaling: seen from outside, radius
/// and distance in `[2⁻²⁹, 2²⁹]`; bad input, the shading point inside or on the sphere,
/// and huge or tiny coordinates take the careful path.
#[test]
fn the_spheres_that_skip_the_rescaling() {
    let fast = |c: Vec3, r: f32| super::sphere_distance_in_range(c, r).is_some();
    assert!(fast(Vec3::new(1.0, 2.0, 3.0), 0.5));
    assert!(fast(Vec3::new(0.0, 0.0, 1e-8), 2e-9));
    assert!(fast(Vec3::new(0.0, 5e8, 0.0), 1.0));
    // Just outside the sphere (the nearly hemispherical cap).
    assert!(fast(Vec3::new(0.0, 0.0, 1.000_001), 1.0));
    for (c, r) in [
        (Vec3::new(0.0, 0.0, 1.0), 1.0),    // on the sphere
        (Vec3::new(0.0, 0.0, 0.5), 1.0),    // inside
        (Vec3::ZERO, 1.0),                  // at the center
        (Vec3::new(0.0, 0.0, 3.0), 1e-9),   // radius below 2⁻²⁹
        (Vec3::new(0.0, 0.0, 1e9), 1.0),    // distance above 2²⁹
        (Vec3::new(0.0, 0.0, 1e-9), 1e-10), // distance below 2⁻²⁹
        (Vec3::new(0.0, 0.0, 3e30), 1e30),  // huge
        (Vec3::new(0.0, 0.0, 3.0), 0.0),    // no radius
        (Vec3::new(0.0, 0.0, 3.0), -1.0),   // negative radius
        (Vec3::new(0.0, 0.0, 3.0), f32::NAN),
        (Vec3::new(f32::NAN, 0.0, 3.0), 1.0),
        (Vec3::new(0.0, f32::INFINITY, 3.0), 1.0),
    ] {
        assert!(!fast(c, r), "{c} {r}");
    }
    // The fast path decides "seen from outside" without `d` where `sin²θ ≤ 0.75` (see
    // `Cap::outside_sphere`): it takes exactly these spheres, also at `d` within ulps of
    // `r` and around `sin²θ = 0.75`.
    let mut rng = Rng::new(61);
    let mut near_rim = 0;
    for i in 0..200_000 {
        let dir = rng.unit_vector_f32();
        let radius = rng.log_uniform(-8.0, 8.0) as f32;
        let ratio = match i % 3 {
            // d/r within ±1e-6 of 1: either side of the surface.
            0 => 1.0 + (rng.uniform() as f32 - 0.5) * 2e-6,
            // sin²θ near 0.75: d/r near 2/√3.
            1 => 1.154_700_5 * (1.0 + (rng.uniform() as f32 - 0.5) * 1e-6),
            _ => rng.log_uniform(-1.0, 3.0) as f32,
        };
        let center = dir * (radius * ratio);
        let fast_cap = super::sphere_cap_in_range(center, radius);
        assert_eq!(
            fast_cap.is_some(),
            fast(center, radius),
            "{center} {radius}"
        );
        if let Some(cap) = fast_cap {
            assert_eq!(
                cap,
                Cap::from_sphere_careful(center, radius),
                "{center} {radius}"
            );
            near_rim += (i % 3 == 0) as u32;
        }
    }
    assert!(near_rim > 10_000, "{near_rim}");
}

/// Where `Cap::from_sphere` skips the rescaling, it gives the careful path's cap bit
/// for bit (rounding commutes with a power of two in the normal range), including
/// centers with components far below the largest, and spheres at both ends of the
/// range.
#[test]
fn the_fast_sphere_cap_is_the_careful_one_bit_for_bit() {
    let mut rng = Rng::new(59);
    let mut fast_cases = 0;
    for i in 0..200_000 {
        let mut dir = rng.unit_vector_f32();
        if i % 4 == 1 {
            // A component far below the others (down to 2⁻⁶⁰ of them).
            dir.x *= rng.log_uniform(-18.0, 0.0) as f32;
        }
        let distance = rng.log_uniform(-8.7, 8.7) as f32;
        let radius = distance * rng.log_uniform(-8.0, 0.0) as f32;
        let center = dir * distance;
        if super::sphere_distance_in_range(center, radius).is_none() {
            continue;
        }
        fast_cases += 1;
        let careful = Cap::from_sphere_careful(center, radius);
        assert_eq!(
            Cap::from_sphere(center, radius),
            careful,
            "{center} {radius}"
        );
        assert!(careful.uniform_pdf() > 0.0 && careful.uniform_pdf().is_finite());
    }
    assert!(fast_cases > 150_000, "{fast_cases}");
    // The ends of the range: the smallest and largest sphere, and the smallest cap.
    for (c, r) in [
        (
            Vec3::new(0.0, 0.0, 3.0 / (1u32 << 29) as f32),
            1.0 / (1u32 << 29) as f32,
        ),
        (
            Vec3::new(0.0, 0.0, (1u32 << 29) as f32),
            (1u32 << 28) as f32,
        ),
        (
            Vec3::new(0.0, 0.0, (1u32 << 29) as f32),
            1.0 / (1u32 << 29) as f32,
        ),
    ] {
        assert!(super::sphere_distance_in_range(c, r).is_some(), "{c} {r}");
        let careful = Cap::from_sphere_careful(c, r);
        assert_eq!(Cap::from_sphere(c, r), careful, "{c} {r}");
        assert!(careful.uniform_pdf() > 0.0 && careful.uniform_pdf().is_finite());
    }
}

/// Caps of spheres have axes unit to `2⁻²²` (so that their samples skip the Newton step
/// of `sample_uniform_in_frame`), and their samples are unit to within
/// `UNIT_TOLERANCE` without it (measured: at most 4.8e-7; the bound asserted is 6e-7),
/// with `pdf(dir) == sample.pdf`, from tiny caps to nearly hemispheres and across the
/// range of coordinates.
#[test]
fn samples_of_unit_axes_are_unit_without_the_newton_step() {
    let mut rng = Rng::new(83);
    let (mut worst_axis, mut worst_dir) = (0.0f32, 0.0f32);
    for i in 0..20000 {
        let sin2 = rng.log_uniform(-12.0, 0.0);
        let distance = rng.log_uniform(-3.0, 3.0) as f32;
        let scale = [1.0, 1e30, 1e-30][i % 3];
        let center = rng.unit_vector_f32() * distance * scale;
        let radius = (distance as f64 * sin2.sqrt()) as f32 * scale;
        let cap = Cap::from_sphere(center, radius);
        if cap.one_minus_cos >= 2.0 || !(cap.one_minus_cos > 0.0) {
            continue;
        }
        worst_axis = worst_axis.max((cap.axis.length_squared() - 1.0).abs());
        for _ in 0..4 {
            let s = cap.sample_uniform([rng.uniform_f32(), rng.uniform_f32()]);
            assert!(s.pdf > 0.0, "{cap:?}");
            assert_eq!(cap.pdf(s.dir), s.pdf, "{cap:?} {:?}", s.dir);
            worst_dir = worst_dir.max((s.dir.length_squared() - 1.0).abs());
        }
    }
    std::println!("worst | |axis|² − 1 | {worst_axis:e}, | |dir|² − 1 | {worst_dir:e}");
    assert!(worst_axis <= UNIT_AXIS, "{worst_axis:e}");
    assert!(worst_dir <= 6e-7, "{worst_dir:e}");
    // Caps by hand whose axes are off unit by up to `UNIT_AXIS` (no step) and beyond
    // it up to `UNIT_TOLERANCE` (the step; without it `pdf` rejects some of their
    // samples, checked): samples unit within `UNIT_TOLERANCE`, pdf as sampled.
    let mut worst_hand = 0.0f32;
    for i in 0..20000 {
        // |axis|² − 1 from −9.5e-7 to 9.5e-7, in steps of ε/2: `Cap::sanitized` keeps
        // every such axis as it is.
        let stretch = 1.0 + ((i % 17) as f32 - 8.0) * 0.5 * f32::EPSILON;
        let axis = rng.unit_vector_f32() * stretch;
        let t = rng.log_uniform(-12.0, 0.3) as f32;
        let cap = Cap {
            axis,
            one_minus_cos: t,
            one_plus_cos: 2.0 - t,
            sin2: (t * (2.0 - t)).min(1.0),
        };
        let s = cap.sample_uniform([rng.uniform_f32(), rng.uniform_f32()]);
        assert!(s.pdf > 0.0, "{cap:?}");
        assert_eq!(cap.pdf(s.dir), s.pdf, "{cap:?} {:?}", s.dir);
        worst_hand = worst_hand.max((s.dir.length_squared() - 1.0).abs());
    }
    std::println!("caps by hand: | |dir|² − 1 | {worst_hand:e}");
    assert!(
        worst_hand <= 0.9 * crate::math::UNIT_TOLERANCE,
        "{worst_hand:e}"
    );
}

/// `contains_unit` (the containment test without the length test, for a direction that
/// `math::unit` takes as it is) agrees with `contains` for unit directions and for the
/// normalised ones of any length, in caps of every size (empty, tiny, wide, whole), as
/// does the two-cap test that uses it for unit directions (`CapIntersection::contains`).
#[test]
fn contains_unit_agrees_with_contains() {
    let mut rng = Rng::new(1808);
    let (mut inside, mut unit_directions) = (0, 0);
    for i in 0..50_000 {
        let t = match i % 5 {
            0 => 0.0,
            1 => rng.log_uniform(-8.0, 0.0) as f32,
            2 => 2.0 * rng.uniform_f32(),
            3 => 2.0 - rng.log_uniform(-7.0, -1.0) as f32,
            _ => 2.0,
        };
        let cap = Cap::from_axis_one_minus_cos(rng.unit_vector_f32(), t);
        let other = Cap::from_axis_one_minus_cos(rng.unit_vector_f32(), 2.0 * rng.uniform_f32());
        // Near the axis (inside or just outside small caps) or anywhere.
        let dir = if i % 2 == 0 {
            (cap.axis + rng.unit_vector_f32() * (2.0 * t.max(1e-6)).sqrt()).normalize()
        } else {
            rng.unit_vector_f32()
        };
        let scaled = dir * rng.log_uniform(-20.0, 20.0) as f32;
        for v in [dir, scaled] {
            let Some(u) = crate::math::unit(v) else {
                continue;
            };
            assert_eq!(cap.contains(v), cap.contains_unit(u), "{cap:?} {v:?}");
            inside += cap.contains(v) as u32;
            if crate::math::is_unit(v) {
                unit_directions += 1;
            }
            if let Some(both) = crate::sphere::CapIntersection::new(&cap, &other) {
                assert_eq!(
                    both.contains(v),
                    both.radial.contains(v) && both.other.contains(v),
                    "{cap:?} {other:?} {v:?}"
                );
            }
        }
    }
    assert!(
        inside > 10_000 && unit_directions > 40_000,
        "{inside} {unit_directions}"
    );
}
