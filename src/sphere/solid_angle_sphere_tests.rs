use super::*;
use crate::testing::{
    CHI_SQUARE_ALPHA, Rng, chi_square, d3, dot, frame_f64, normalize, sphere_cap_one_minus_cos_f64,
    sub,
};

/// Chi-square of the samples of a sphere prepared for solid angle sampling, over cells
/// of equal solid angle in `(1 − ω·a, φ)` of the f64 cap (the f64 axis and `1 − cos θ`
/// from the f64 center and radius, the azimuth in the f64 frame of the axis); every
/// sample has the density `1/Ω` of the f64 cap, its pdf by `pdf`, and lies inside.
fn check_sphere(center: Vec3, radius: f32, seed: u64) {
    const N: usize = 12;
    let mut sphere = SolidAngleSphere::EMPTY;
    assert!(sphere.prepare(center, radius), "{center} {radius}");
    let axis = normalize(d3(center));
    let (tangent, bitangent) = frame_f64(axis);
    let t_max = sphere_cap_one_minus_cos_f64(d3(center), radius as f64);
    let expected_pdf = 1.0 / (2.0 * core::f64::consts::PI * t_max);
    let mut counts = vec![0u64; N * N];
    let mut rng = Rng::new(seed);
    for _ in 0..100_000 {
        let u = [rng.uniform_f32(), rng.uniform_f32()];
        let s = sphere.sample(u);
        assert!(
            ((s.pdf as f64 - expected_pdf) / expected_pdf).abs() < 2e-6,
            "{s:?}"
        );
        assert_eq!(sphere.pdf(s.dir), s.pdf, "{u:?}");
        assert!((s.dir.length() - 1.0).abs() < 1e-6);
        let w = d3(s.dir);
        let e = sub(w, axis);
        let t = 0.5 * dot(e, e);
        assert!(t <= t_max * (1.0 + 1e-4) + 1e-7, "outside: {t} > {t_max}");
        let phi = dot(w, bitangent).atan2(dot(w, tangent));
        let phi01 = (phi / (2.0 * core::f64::consts::PI)).rem_euclid(1.0);
        let i = ((t / t_max * N as f64) as usize).min(N - 1);
        let j = ((phi01 * N as f64) as usize).min(N - 1);
        counts[i * N + j] += 1;
    }
    let (statistic, dof, p) = chi_square(&counts, &vec![1.0 / (N * N) as f64; N * N]);
    assert!(
        p > CHI_SQUARE_ALPHA,
        "sphere {center} {radius}: chi-square {statistic} with {dof} dof, p = {p}"
    );
}

#[test]
fn samples_pass_chi_square_against_the_f64_cap() {
    let mut rng = Rng::new(41);
    let axis = rng.unit_vector_f32();
    check_sphere(axis * 3.0, 1.0, 1);
    check_sphere(axis * 1.001, 1.0, 2);
    check_sphere(axis * 40.0, 0.5, 3);
    // Inside the sphere: the whole sphere of directions.
    check_sphere(axis * 0.5, 1.0, 4);
    // Tiny caps around an axis close to z, where f32 directions resolve them.
    check_sphere(Vec3::new(0.0, 0.0, 1e5), 1.0, 5);
    check_sphere(Vec3::new(1e-3, 0.0, 1e6), 1.0, 6);
}

/// The prepared sampler draws exactly what `Cap::sample_uniform` draws from the cap of
/// `Cap::from_sphere`, and its pdf and inverse are the cap's: one body, two entry points.
#[test]
fn samples_are_bit_for_bit_those_of_the_cap() {
    let mut rng = Rng::new(43);
    for _ in 0..2000 {
        let center = rng.unit_vector_f32() * rng.log_uniform(-3.0, 7.0) as f32;
        let radius = rng.log_uniform(-3.0, 3.0) as f32;
        let cap = Cap::from_sphere(center, radius);
        let mut sphere = SolidAngleSphere::EMPTY;
        assert!(sphere.prepare(center, radius), "{center} {radius} {cap:?}");
        assert_eq!(sphere.cap(), cap);
        assert_eq!(sphere.solid_angle(), cap.solid_angle());
        for _ in 0..8 {
            let u = [rng.uniform_f32(), rng.uniform_f32()];
            let s = sphere.sample(u);
            assert_eq!(s, cap.sample_uniform(u), "{center} {radius} {u:?}");
            assert_eq!(sphere.pdf(s.dir), cap.pdf(s.dir));
            assert_eq!(sphere.invert(s.dir), cap.invert(s.dir));
        }
    }
    // The edges of `u`, and wide caps by hand (the pivot images' kind).
    for cap in [
        Cap::from_axis_cos(Vec3::new(1.0, 2.0, -3.0), -0.999),
        Cap::from_axis_one_plus_cos(Vec3::Z, 1e-6),
        Cap::from_axis_one_minus_cos(Vec3::NEG_Z, 1e-9),
        Cap::WHOLE_SPHERE,
    ] {
        let mut sphere = SolidAngleSphere::EMPTY;
        assert!(sphere.prepare_cap(cap));
        for u in [
            [0.0, 0.0],
            [1.0, 1.0],
            [0.5, 0.999_999_94],
            [f32::NAN, -1.0],
        ] {
            assert_eq!(sphere.sample(u), cap.sample_uniform(u), "{cap:?} {u:?}");
        }
    }
}

/// The cap of a sphere 1e6 radii away is 1e-12 sr, exact to a few ulps (`1 − cos θ` by
/// `sin²θ / (1 + cos θ)`, not by subtraction), and its samples reach its rim.
#[test]
fn tiny_caps_keep_their_solid_angle_and_samples() {
    for distance in [1e3f32, 1e5, 1e6, 1e7] {
        let mut sphere = SolidAngleSphere::EMPTY;
        assert!(sphere.prepare(Vec3::new(0.0, 0.0, distance), 1.0));
        let exact = 2.0
            * core::f64::consts::PI
            * sphere_cap_one_minus_cos_f64([0.0, 0.0, distance as f64], 1.0);
        let relative = (sphere.solid_angle() as f64 - exact).abs() / exact;
        assert!(
            relative < 1e-6,
            "{distance}: {} vs {exact}",
            sphere.solid_angle()
        );
        let mut rng = Rng::new(distance as u64);
        let mut largest = 0.0f64;
        for _ in 0..4000 {
            let s = sphere.sample([rng.uniform_f32(), rng.uniform_f32()]);
            assert!(s.pdf > 0.0 && sphere.pdf(s.dir) == s.pdf);
            largest = largest.max(((s.dir.x as f64).powi(2) + (s.dir.y as f64).powi(2)).sqrt());
        }
        let radius = 1.0 / distance as f64;
        assert!(
            largest <= radius * (1.0 + 1e-4) + 1e-7,
            "{distance}: {largest}"
        );
        if distance <= 1e5 {
            assert!(
                largest > 0.98 * radius,
                "{distance}: samples miss the rim: {largest}"
            );
        }
    }
}

/// Bad input: `false`, the empty value written over whatever the struct held, no
/// sample, pdf 0, no inverse, no NaN.
#[test]
fn bad_input_writes_the_empty_value() {
    let garbage = SolidAngleSphere {
        axis_and_one_minus_cos: [f32::NAN, f32::NAN, f32::NAN, f32::NAN],
        tangent_and_one_plus_cos: [f32::INFINITY, f32::INFINITY, f32::INFINITY, 7.0],
        bitangent_and_density: [f32::NAN, f32::NAN, f32::NAN, f32::NAN],
    };
    let garbage_cap = Cap {
        axis: Vec3::NAN,
        one_minus_cos: f32::NAN,
        one_plus_cos: 7.0,
        sin2: -1.0,
    };
    for (center, radius) in [
        (Vec3::new(0.0, 0.0, 2.0), 0.0),
        (Vec3::new(0.0, 0.0, 2.0), -1.0),
        (Vec3::new(0.0, 0.0, 2.0), f32::NAN),
        (Vec3::new(0.0, 0.0, 2.0), f32::INFINITY),
        (Vec3::new(f32::NAN, 0.0, 2.0), 1.0),
        (Vec3::new(0.0, f32::INFINITY, 2.0), 1.0),
    ] {
        let mut sphere = garbage;
        assert!(!sphere.prepare(center, radius), "{center} {radius}");
        assert_eq!(sphere, SolidAngleSphere::EMPTY);
        assert_eq!(sphere.sample([0.3, 0.7]), Sample::NONE);
        assert_eq!(sphere.pdf(Vec3::Z), 0.0);
        assert_eq!(sphere.invert(Vec3::Z), None);
        assert_eq!(sphere.solid_angle(), 0.0);
    }
    let mut sphere = garbage;
    assert!(!sphere.prepare_cap(Cap::EMPTY));
    assert_eq!(sphere, SolidAngleSphere::EMPTY);
    // A cap built by hand with garbage is made valid first (here: empty).
    let mut sphere = garbage;
    assert!(!sphere.prepare_cap(garbage_cap));
    assert_eq!(sphere, SolidAngleSphere::EMPTY);
    // Huge and tiny coordinates are rescaled, not overflowed.
    for scale in [1e-30f32, 1e30] {
        let mut sphere = garbage;
        assert!(sphere.prepare(Vec3::new(0.0, 0.0, 3.0) * scale, scale));
        let expected =
            2.0 * core::f64::consts::PI * sphere_cap_one_minus_cos_f64([0.0, 0.0, 3.0], 1.0);
        assert!((sphere.solid_angle() as f64 - expected).abs() < 1e-6 * expected);
        assert!(sphere.sample([0.5, 0.5]).pdf > 0.0);
    }
}

/// `pdf` integrates to 1 over the sphere of directions, and is 0 outside the cap.
#[test]
fn pdf_integrates_to_one() {
    let mut sphere = SolidAngleSphere::EMPTY;
    assert!(sphere.prepare(Vec3::new(0.3, -0.4, 2.0), 0.8));
    let mut rng = Rng::new(47);
    let n = 400_000;
    let mut sum = 0.0f64;
    for _ in 0..n {
        let w = crate::testing::uniform_direction_f64(&mut rng);
        sum += sphere.pdf(Vec3::new(w[0] as f32, w[1] as f32, w[2] as f32)) as f64;
    }
    let integral = sum * 4.0 * core::f64::consts::PI / n as f64;
    // The estimator's standard deviation is sqrt(4π/Ω - 1)/sqrt(n) ≈ 0.004 here.
    assert!((integral - 1.0).abs() < 0.02, "∫ pdf = {integral}");
    assert_eq!(sphere.pdf(Vec3::new(0.0, 0.0, -1.0)), 0.0);
}
