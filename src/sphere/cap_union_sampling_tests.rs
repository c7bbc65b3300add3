//! Tests of uniform sampling of a union of two caps, against cell probabilities that
//! an f64 quadrature of the union's indicator gives, independently of the sampler's
//! decomposition into `A` and `B ∩ Ā`.
use super::*;
use crate::sample::ONE_MINUS_ULP;
use crate::testing::*;

fn cap(axis: Vec3, one_minus_cos: f32) -> Cap {
    Cap::from_axis_one_minus_cos(axis, one_minus_cos)
}

/// Pairs: a lens, disjoint caps, `B` inside `A`, `A` inside `B`, a cap wider than a
/// hemisphere with a small one across its rim, two wide caps, equal caps.
fn pairs() -> Vec<(&'static str, Cap, Cap)> {
    vec![
        ("lens", cap(Vec3::Z, 0.3), cap(tilted(40.0, 20.0), 0.2)),
        ("disjoint", cap(Vec3::Z, 0.1), cap(tilted(120.0, 50.0), 0.3)),
        (
            "b inside a",
            cap(Vec3::Z, 0.8),
            cap(tilted(10.0, 0.0), 0.05),
        ),
        (
            "a inside b",
            cap(tilted(10.0, 0.0), 0.05),
            cap(Vec3::Z, 0.8),
        ),
        (
            "wide and small",
            cap(Vec3::Z, 1.6),
            cap(tilted(125.0, 30.0), 0.08),
        ),
        (
            "both wide",
            cap(Vec3::Z, 1.3),
            cap(tilted(140.0, -60.0), 1.2),
        ),
        (
            "equal",
            cap(tilted(30.0, 10.0), 0.4),
            cap(tilted(30.0, 10.0), 0.4),
        ),
    ]
}

/// The arcs of azimuth `φ` (as intervals within `[φ0, φ1]`) of the circle at height `z`
/// about +z that lie in the f32 cap `c` (in f64): `r (c_x cos φ + c_y sin φ) + z c_z ≥
/// cos θ` is `cos(φ − φ_c) ≥ k` with `k = (cos θ − z c_z) / (r ρ)`, `ρ = |c_xy|`.
fn arcs_in(c: &Cap, z: f64, phi0: f64, phi1: f64, out: &mut Vec<(f64, f64)>) {
    let tau = 2.0 * core::f64::consts::PI;
    let (axis, t) = (d3(c.axis), c.one_minus_cos as f64);
    if !(t > 0.0) {
        return;
    }
    let r = (1.0 - z * z).max(0.0).sqrt();
    let rho = (axis[0] * axis[0] + axis[1] * axis[1]).sqrt();
    let cos_theta = 1.0 - t;
    let (lo, hi) = if r * rho < 1e-300 {
        if z * axis[2] >= cos_theta {
            (0.0, tau)
        } else {
            return;
        }
    } else {
        let k = (cos_theta - z * axis[2]) / (r * rho);
        if k > 1.0 {
            return;
        }
        if k <= -1.0 {
            (0.0, tau)
        } else {
            let centre = axis[1].atan2(axis[0]);
            let half = k.acos();
            (centre - half, centre + half)
        }
    };
    // The arc and its copies a turn away, clipped to [φ0, φ1].
    for shift in [-tau, 0.0, tau] {
        let (a, b) = ((lo + shift).max(phi0), (hi + shift).min(phi1));
        if b > a {
            out.push((a, b));
        }
    }
}

/// Cells `Z × Φ` over the whole sphere (bands of `z` about +z, equal azimuths), with the
/// probability of each under the uniform distribution on `a ∪ b`: for `n` heights per
/// band (midpoint rule in `z`, `dω = dz dφ`) the exact length of the union of the two
/// caps' arcs inside the cell, normalised by the exact f64 `Ω(a ∪ b) = Ω(a) + Ω(b) −
/// Ω(a ∩ b)` (`cap_intersection_f64`). Also returns the quadrature's total, which the
/// test compares with the closed form.
fn cells(a: &Cap, b: &Cap, bands: usize, sectors: usize, n: usize) -> (Vec<f64>, f64, f64) {
    let f64_cap = |c: &Cap| (d3(c.axis), c.one_minus_cos as f64, c.one_plus_cos as f64);
    let exact = 2.0 * core::f64::consts::PI * (a.one_minus_cos as f64 + b.one_minus_cos as f64)
        - cap_intersection_f64(f64_cap(a), f64_cap(b));
    let mut areas = vec![0.0f64; bands * sectors];
    let (dz, dphi) = (
        2.0 / bands as f64,
        2.0 * core::f64::consts::PI / sectors as f64,
    );
    let mut arcs = Vec::new();
    for i in 0..bands {
        for k in 0..n {
            let z = -1.0 + dz * (i as f64 + (k as f64 + 0.5) / n as f64);
            for j in 0..sectors {
                let (phi0, phi1) = (dphi * j as f64, dphi * (j + 1) as f64);
                arcs.clear();
                arcs_in(a, z, phi0, phi1, &mut arcs);
                arcs_in(b, z, phi0, phi1, &mut arcs);
                arcs.sort_by(|x, y| x.0.total_cmp(&y.0));
                // The length of the union of the intervals.
                let (mut length, mut end) = (0.0, f64::NEG_INFINITY);
                for &(lo, hi) in &arcs {
                    if hi > end {
                        length += hi - lo.max(end);
                        end = hi;
                    }
                }
                areas[i * sectors + j] += length * dz / n as f64;
            }
        }
    }
    let total: f64 = areas.iter().sum();
    (areas.iter().map(|x| x / exact).collect(), total, exact)
}

fn cell_of(dir: Vec3, bands: usize, sectors: usize) -> usize {
    let w = normalize(d3(dir));
    let band = (((w[2] + 1.0) / 2.0 * bands as f64) as usize).min(bands - 1);
    let phi = w[1].atan2(w[0]).rem_euclid(2.0 * core::f64::consts::PI);
    let sector = ((phi / (2.0 * core::f64::consts::PI) * sectors as f64) as usize).min(sectors - 1);
    band * sectors + sector
}

fn chi_square_of(union: &CapUnion, a: &Cap, b: &Cap, seed: u64, share: Option<f32>) -> f64 {
    let (bands, sectors) = (16, 16);
    let (probabilities, total, exact) = cells(a, b, bands, sectors, 2000);
    assert!(
        (total - exact).abs() <= 1e-4 * exact,
        "quadrature {total} vs {exact}"
    );
    let mut union = *union;
    if let Some(share) = share {
        union.first_share = share;
    }
    let mut rng = Rng::new(seed);
    let mut counts = vec![0u64; bands * sectors];
    for _ in 0..200_000 {
        let s = union.sample_uniform([rng.uniform_f32(), rng.uniform_f32()]);
        assert!(s.pdf > 0.0 && union.contains(s.dir) && union.pdf(s.dir) == s.pdf);
        counts[cell_of(s.dir, bands, sectors)] += 1;
    }
    chi_square(&counts, &probabilities).2
}

#[test]
fn samples_are_uniform_in_the_union() {
    for (k, (name, a, b)) in pairs().into_iter().enumerate() {
        let union = CapUnion::new(&a, &b).expect(name);
        let f64_cap = |c: &Cap| (d3(c.axis), c.one_minus_cos as f64, c.one_plus_cos as f64);
        let exact = 2.0 * core::f64::consts::PI * (a.one_minus_cos as f64 + b.one_minus_cos as f64)
            - cap_intersection_f64(f64_cap(&a), f64_cap(&b));
        let omega = union.solid_angle() as f64;
        assert!(
            (omega - exact).abs() <= 1e-5 * exact,
            "{name}: Ω {omega} vs {exact}"
        );
        let p = chi_square_of(&union, &a, &b, 40 + k as u64, None);
        println!("{name}: Ω = {omega:.6}, p = {p:.3}");
        assert!(p > CHI_SQUARE_ALPHA, "{name}: p = {p}");
    }
}

/// The test can fail: a union that picks `A` 10% too often (a wrong share of the pieces)
/// is rejected for every pair whose pieces both carry at least a tenth of the mass.
#[test]
fn the_chi_square_test_rejects_a_wrong_share() {
    let mut tested = 0;
    for (k, (name, a, b)) in pairs().into_iter().enumerate() {
        let union = CapUnion::new(&a, &b).expect(name);
        if !(union.first_share > 0.1 && union.first_share < 0.9) {
            continue;
        }
        let p = chi_square_of(&union, &a, &b, 70 + k as u64, Some(union.first_share * 1.1));
        assert!(p < 1e-6, "{name}: a wrong share passed, p = {p}");
        tested += 1;
    }
    assert!(tested >= 3, "only {tested} pairs tested");
}

#[test]
fn invert_undoes_sample() {
    let mut rng = Rng::new(9);
    for (name, a, b) in pairs() {
        let union = CapUnion::new(&a, &b).expect(name);
        for _ in 0..2000 {
            let u = [rng.uniform_f32(), rng.uniform_f32()];
            let s = union.sample_uniform(u);
            let back = union.invert(s.dir).expect("inside");
            assert!((back[0] - u[0]).abs() < 2e-3, "{name}: {u:?} -> {back:?}");
            // u₁ is an azimuth: compare on the circle.
            let d = (back[1] - u[1]).abs();
            assert!(d.min(1.0 - d) < 2e-3, "{name}: {u:?} -> {back:?}");
        }
    }
}

#[test]
fn the_pdf_integrates_to_one() {
    for (name, a, b) in pairs() {
        let union = CapUnion::new(&a, &b).expect(name);
        let integral = integrate_over_sphere(1000, |dir| union.pdf(dir) as f64);
        assert!((integral - 1.0).abs() < 5e-3, "{name}: ∫ pdf = {integral}");
    }
}

#[test]
fn hard_cases() {
    // Both empty: no sampler; one empty: the other cap.
    assert!(CapUnion::new(&Cap::EMPTY, &Cap::EMPTY).is_none());
    let c = cap(tilted(20.0, 0.0), 0.3);
    for (a, b) in [(Cap::EMPTY, c), (c, Cap::EMPTY)] {
        let union = CapUnion::new(&a, &b).expect("one cap");
        assert!((union.solid_angle() - c.solid_angle()).abs() <= 1e-6 * c.solid_angle());
    }
    // Two caps wider than a hemisphere covering the sphere: the whole sphere.
    let whole = CapUnion::new(&cap(Vec3::Z, 1.5), &cap(-Vec3::Z, 1.5)).expect("sphere");
    let sphere = 4.0 * core::f32::consts::PI;
    assert!((whole.solid_angle() - sphere).abs() <= 1e-5 * sphere);
    // A cap and its complement: the whole sphere, each part sampled in proportion.
    let complement = CapUnion::new(&c, &c.complement()).expect("sphere");
    assert!((complement.solid_angle() - sphere).abs() <= 1e-5 * sphere);
    // A tiny cap on a large one's rim, `u` at the ends of [0, 1), out of range, NaN.
    let rim = cap(tilted(60.0, 0.0), 1e-6);
    let union = CapUnion::new(&cap(Vec3::Z, 0.5), &rim).expect("rim");
    for u in [
        [0.0, 0.0],
        [ONE_MINUS_ULP, ONE_MINUS_ULP],
        [1.0, 1.0],
        [-1.0, 2.0],
        [f32::NAN, f32::NAN],
        [union.first_share, 0.5],
    ] {
        let s = union.sample_uniform(u);
        assert!(s.dir.is_finite() && s.pdf.is_finite(), "{u:?}");
        assert!(s.pdf == 0.0 || union.pdf(s.dir) == s.pdf, "{u:?}");
    }
    for dir in [Vec3::ZERO, Vec3::NAN, Vec3::new(f32::INFINITY, 0.0, 1.0)] {
        assert_eq!(union.pdf(dir), 0.0);
        assert!(union.invert(dir).is_none());
    }
    // The complement of a cap holds what the cap does not.
    let mut rng = Rng::new(3);
    for _ in 0..1000 {
        let d = rng.unit_vector_f32();
        let boundary = (0.5 * (d - c.axis).length_squared() - c.one_minus_cos).abs() < 1e-5;
        if !boundary {
            assert_ne!(c.contains(d), c.complement().contains(d), "{d:?}");
        }
    }
}
