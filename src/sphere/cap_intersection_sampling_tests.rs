use super::*;
use crate::sample::ONE_MINUS_ULP;
use crate::testing::*;

fn cap(axis: Vec3, one_minus_cos: f32) -> Cap {
    Cap::from_axis_one_minus_cos(axis, one_minus_cos)
}

fn f64_cap(c: &Cap) -> (D3, f64, f64) {
    (d3(c.axis), c.one_minus_cos as f64, c.one_plus_cos as f64)
}

/// Pairs of caps: a lens, a cap wider than a hemisphere, both wider, nested, a small cap
/// across a larger one's rim, coaxial caps, and the upper hemisphere with a cap across
/// its horizon.
fn pairs() -> Vec<(&'static str, Cap, Cap)> {
    vec![
        ("lens", cap(Vec3::Z, 0.3), cap(tilted(40.0, 20.0), 0.2)),
        (
            "wide other",
            cap(Vec3::Z, 0.5),
            cap(tilted(100.0, -30.0), 1.6),
        ),
        ("both wide", cap(Vec3::Z, 1.5), cap(tilted(60.0, 70.0), 1.7)),
        ("nested", cap(Vec3::Z, 0.1), cap(tilted(5.0, 0.0), 0.8)),
        (
            "small across a rim",
            cap(tilted(10.0, 45.0), 1e-3),
            cap(Vec3::Z, (1.0 - 10f64.to_radians().cos()) as f32),
        ),
        ("coaxial", cap(Vec3::Z, 0.4), cap(Vec3::Z, 1.0)),
        ("horizon", cap(tilted(80.0, 0.0), 0.1), cap(Vec3::Z, 1.0)),
    ]
}

/// Cells of `a ∩ b` (`a` the narrower cap) whose probabilities under the uniform
/// distribution are known exactly in f64: `rows` bands of `s = 1 − a·ω` (uniform steps
/// over the part of `[0, t_a]` that meets `b`), each cut into `columns` equal parts of the
/// arc of the band's circle inside `b` (the normalised azimuth `v = (ψ/φ(s) + 1)/2` about
/// the direction of `b`). A band's probability is a difference of two-cap solid angles
/// (`cap_intersection_f64`, the acos form, independent of the sampler's), and the
/// arc's parts are equally likely.
struct Cells {
    a: D3,
    b: (D3, f64, f64),
    e1: D3,
    e2: D3,
    t_d: f64,
    s_edges: Vec<f64>,
    columns: usize,
    probabilities: Vec<f64>,
}

impl Cells {
    fn new(a: &Cap, b: &Cap, rows: usize, columns: usize) -> Cells {
        let (a, b) = if a.one_minus_cos <= b.one_minus_cos {
            (a, b)
        } else {
            (b, a)
        };
        let (fa, fb) = (f64_cap(a), f64_cap(b));
        let omega = cap_intersection_f64(fa, fb);
        let axis = fa.0;
        let t_d = 0.5 * norm(sub(fb.0, axis)).powi(2);
        let along = sub(fb.0, scale(axis, dot(fb.0, axis)));
        let e1 = if norm(along) > 1e-12 {
            normalize(along)
        } else {
            frame_f64(axis).0
        };
        let e2 = cross(axis, e1);
        let cumulative = |s: f64| {
            if s <= 0.0 {
                0.0
            } else {
                cap_intersection_f64((axis, s, 2.0 - s), fb)
            }
        };
        // The band of s that meets b, found on a fine grid.
        let t_a = fa.1;
        let (mut s_low, mut s_high) = (0.0, t_a);
        let steps = 100_000;
        for k in 0..=steps {
            let s = t_a * k as f64 / steps as f64;
            if cumulative(s) <= 1e-14 * omega {
                s_low = s;
            }
        }
        for k in (0..=steps).rev() {
            let s = t_a * k as f64 / steps as f64;
            if cumulative(s) >= omega * (1.0 - 1e-14) {
                s_high = s;
            }
        }
        let s_edges: Vec<f64> = (0..=rows)
            .map(|i| s_low + (s_high - s_low) * i as f64 / rows as f64)
            .collect();
        let mut probabilities = Vec::new();
        for i in 0..rows {
            let band = if i + 1 == rows {
                omega - cumulative(s_edges[i])
            } else {
                cumulative(s_edges[i + 1]) - cumulative(s_edges[i])
            };
            for _ in 0..columns {
                probabilities.push(band / omega / columns as f64);
            }
        }
        Cells {
            a: axis,
            b: fb,
            e1,
            e2,
            t_d,
            s_edges,
            columns,
            probabilities,
        }
    }

    fn of(&self, dir: Vec3) -> usize {
        let w = normalize(d3(dir));
        let s = 0.5 * norm(sub(w, self.a)).powi(2);
        let rows = self.s_edges.len() - 1;
        let row = self.s_edges[1..rows]
            .iter()
            .filter(|&&edge| edge <= s)
            .count();
        let (t_b, t_d) = (self.b.1, self.t_d);
        let c = (s + t_d - t_b - s * t_d) / ((s * (2.0 - s)) * (t_d * (2.0 - t_d))).sqrt();
        let phi = if c.is_finite() {
            c.clamp(-1.0, 1.0).acos()
        } else {
            core::f64::consts::PI
        };
        let psi = dot(w, self.e2).atan2(dot(w, self.e1));
        let v = if phi > 0.0 {
            0.5 * (psi / phi + 1.0)
        } else {
            0.5
        };
        let column = ((v * self.columns as f64).max(0.0) as usize).min(self.columns - 1);
        row * self.columns + column
    }
}

#[test]
fn samples_are_uniform_in_the_intersection() {
    let mut rng = Rng::new(5);
    for (name, a, b) in pairs() {
        let lens = CapIntersection::new(&a, &b).expect(name);
        let reference = cap_intersection_f64(f64_cap(&a), f64_cap(&b));
        assert!(
            (lens.solid_angle() as f64 - reference).abs() <= 1e-5 * reference + 1e-9,
            "{name}: {} vs {reference}",
            lens.solid_angle()
        );
        let cells = Cells::new(&a, &b, 24, 8);
        let mut counts = vec![0u64; cells.probabilities.len()];
        let n = 400_000;
        for _ in 0..n {
            let s = lens.sample_uniform([rng.uniform_f32(), rng.uniform_f32()]);
            assert!(s.pdf > 0.0, "{name}: no sample");
            assert_eq!(lens.pdf(s.dir).to_bits(), s.pdf.to_bits(), "{name}");
            assert!((s.dir.length() - 1.0).abs() < 1e-6, "{name}: {:?}", s.dir);
            counts[cells.of(s.dir)] += 1;
        }
        let (statistic, dof, p) = chi_square(&counts, &cells.probabilities);
        println!("{name}: chi-square {statistic:.1} with {dof} dof, p = {p:.3}");
        assert!(p > CHI_SQUARE_ALPHA, "{name}: p = {p}");
    }
}

/// The chi-square test can fail: it rejects a radial coordinate drawn uniformly in
/// `[s_low, s_high]` instead of by the intersection's marginal.
#[test]
fn the_chi_square_test_rejects_a_wrong_radial_marginal() {
    let (a, b) = (cap(Vec3::Z, 0.3), cap(tilted(40.0, 20.0), 0.2));
    let lens = CapIntersection::new(&a, &b).unwrap();
    let cells = Cells::new(&a, &b, 24, 8);
    let mut counts = vec![0u64; cells.probabilities.len()];
    let mut rng = Rng::new(6);
    for _ in 0..100_000 {
        let s = lens.s_low + (lens.s_high - lens.s_low) * rng.uniform_f32();
        let phi = lens.half_arc(s);
        counts[cells.of(lens.direction(s, (2.0 * rng.uniform_f32() - 1.0) * phi))] += 1;
    }
    let (_, _, p) = chi_square(&counts, &cells.probabilities);
    assert!(p < 1e-10, "p = {p}");
}

#[test]
fn invert_undoes_sample() {
    let mut rng = Rng::new(7);
    for (name, a, b) in pairs() {
        let lens = CapIntersection::new(&a, &b).unwrap();
        let mut worst = 0.0f32;
        for _ in 0..2000 {
            let u = [rng.uniform_f32(), rng.uniform_f32()];
            let s = lens.sample_uniform(u);
            let back = lens.invert(s.dir).expect(name);
            let again = lens.sample_uniform(back);
            // Directions, not u: u1 is ill-conditioned where the arc is short.
            worst = worst.max((again.dir - s.dir).length());
        }
        // Angular radius of the intersection as the scale.
        let scale = crate::math::sqrtf(lens.solid_angle() / PI).min(1.0);
        assert!(worst <= 2e-4 * scale.max(1e-3) + 1e-6, "{name}: {worst}");
    }
}

#[test]
fn hard_cases() {
    // Disjoint caps: no sampler.
    assert!(CapIntersection::new(&cap(Vec3::Z, 0.1), &cap(-Vec3::Z, 0.1)).is_none());
    assert!(CapIntersection::new(&cap(Vec3::Z, 0.0), &cap(Vec3::Z, 1.0)).is_none());
    // Tangent caps (a vanishing lens) and a tiny cap: finite samples inside, or none.
    let mut rng = Rng::new(8);
    let edges = [0.0, 0.5, ONE_MINUS_ULP, 1.0, f32::NAN, -1.0];
    for (a, b) in [
        (cap(Vec3::Z, 1.0), cap(tilted(179.999, 0.0), 1.0)),
        (cap(tilted(30.0, 10.0), 1e-10), cap(Vec3::Z, 0.2)),
        (cap(Vec3::Z, 2.0), cap(tilted(90.0, 0.0), 1e-6)),
    ] {
        let Some(lens) = CapIntersection::new(&a, &b) else {
            continue;
        };
        for &u0 in &edges {
            for &u1 in &edges {
                let s = lens.sample_uniform([u0, u1]);
                assert!(s.dir.is_finite() && s.pdf.is_finite(), "{s:?}");
                if s.pdf > 0.0 {
                    assert_eq!(lens.pdf(s.dir), s.pdf);
                }
            }
        }
        for _ in 0..1000 {
            let s = lens.sample_uniform([rng.uniform_f32(), rng.uniform_f32()]);
            assert!(s.pdf == 0.0 || lens.pdf(s.dir) == s.pdf, "{s:?}");
        }
    }
    // The empty value.
    let empty = CapIntersection::EMPTY;
    assert_eq!(empty.sample_uniform([0.5, 0.5]), Sample::NONE);
    assert_eq!(empty.pdf(Vec3::Z), 0.0);
    assert!(empty.invert(Vec3::Z).is_none());
}

/// `∫ pdf dω = 1`: the pdf is `1/Ω` on the intersection, whose f64 area is Ω to 1e-5,
/// and 0 elsewhere (checked on a grid of directions over the whole sphere).
#[test]
fn the_pdf_integrates_to_one() {
    for (name, a, b) in pairs() {
        let lens = CapIntersection::new(&a, &b).unwrap();
        let n = 600;
        let (dt, dphi) = (2.0 / n as f64, core::f64::consts::TAU / n as f64);
        let mut integral = 0.0;
        for i in 0..n {
            let t = (i as f64 + 0.5) * dt;
            let sin = (t * (2.0 - t)).sqrt();
            for j in 0..n {
                let phi = (j as f64 + 0.5) * dphi;
                let w = Vec3::new(
                    (sin * phi.cos()) as f32,
                    (sin * phi.sin()) as f32,
                    (1.0 - t) as f32,
                );
                integral += lens.pdf(w) as f64 * dt * dphi;
            }
        }
        // The midpoint rule's error at the boundary: a band of one cell.
        let tolerance = if name == "small across a rim" {
            0.3
        } else {
            0.01
        };
        assert!((integral - 1.0).abs() < tolerance, "{name}: {integral}");
    }
}

/// The Newton slope that the lens formula returns beside the CDF (`2 φ(s)`, from its own
/// `atan2(Y, N₁)`, or `2(π − φ)` against a wide cap's complement) is the derivative of
/// the CDF: it agrees with `2 half_arc(s)` (an `acos` of the law of cosines) and with a
/// central difference of `cumulative`, on both fast-path branches and the general one.
#[test]
fn the_newton_slope_is_the_derivative_of_the_radial_cdf() {
    let mut fast_lens = 0;
    let mut fast_complement = 0;
    for (name, a, b) in pairs() {
        let lens = CapIntersection::new(&a, &b).unwrap();
        let (low, high) = (lens.s_low, lens.s_high);
        for i in 1..64 {
            let s = low + (high - low) * (i as f32 / 64.0);
            let [value, slope] = lens.cumulative_and_slope(s);
            assert_eq!(value.to_bits(), lens.cumulative(s).to_bits(), "{name}");
            let on_fast_path = s > 0.0 && s <= 1.0 && s < lens.other.one_minus_cos;
            if on_fast_path && lens.other.one_minus_cos <= 1.0 {
                fast_lens += 1;
            } else if on_fast_path {
                fast_complement += 1;
            }
            let expected = 2.0 * lens.half_arc(s);
            assert!(
                (slope - expected).abs() <= 2e-3 * expected.max(1e-2),
                "{name}: s {s}: slope {slope} against 2 φ {expected}"
            );
            // The derivative of F, by a central difference in f64 of f32 evaluations
            // (a step of 1e-3 of the range: F is smooth inside it).
            let h = 1e-3 * (high - low);
            if s - h > low && s + h < high {
                let difference = (lens.cumulative(s + h) as f64 - lens.cumulative(s - h) as f64)
                    / (2.0 * h as f64);
                assert!(
                    (slope as f64 - difference).abs() <= 2e-2 * difference.abs().max(0.05),
                    "{name}: s {s}: slope {slope} against the difference {difference}"
                );
            }
        }
    }
    // Both branches of the fast path were exercised.
    assert!(
        fast_lens > 0 && fast_complement > 0,
        "{fast_lens} {fast_complement}"
    );
}

/// The radial inversion's accuracy: the f32 radial CDF at the `s` that the Newton
/// iteration returns for `u₀`, normalised, against `u₀` (how well the iteration inverts
/// the function it evaluates), and the f64 CDF (`cap_intersection_f64` of the f64 caps)
/// there (how well that function matches the geometry). For every pair and random
/// sphere lights across the horizon (the SPTD sampler's clipped case: the pivoted
/// light's image against the pivoted horizon's, wider than a hemisphere), 40,000 draws.
///
/// Measured with the stopping rule of `invert_radial` (which saves the evaluations that
/// confirm a converged step) and, in brackets, with the rule that waits for a step
/// below the tolerance: the named pairs' worst f32 residual 5.4e-7 (4.9e-7); over all
/// draws 5.1e-4 (5.1e-4), above 1e-5 in 407 draws (308), f64 error 6.3e-4 (6.0e-4).
/// The number of evaluations of `F` per inversion is bounded too (see the end).
/// The large residuals are the f32 lens formula's, not the iteration's: a small
/// radial cap (`1 − cos = 5e-4`) across the rim of a wide one, whose radial range is 3%
/// of its size, has its CDF to a few 1e-4, so that no `s` reaches the target closer.
#[test]
fn the_radial_inversion_inverts_the_cdf() {
    let mut rng = Rng::new(307);
    let mut cases = pairs();
    for _ in 0..200 {
        let light = Cap::from_sphere(
            rng.unit_vector_f32() * rng.log_uniform(0.0, 0.6) as f32,
            rng.log_uniform(-1.3, -0.2) as f32,
        );
        let pivot = rng.unit_vector_f32() * (0.9 * rng.uniform_f32());
        let horizon = cap(Vec3::Z, 1.0);
        let images = (
            crate::sphere::pivot_cap(&light, pivot),
            crate::sphere::pivot_cap(&horizon, pivot),
        );
        if CapIntersection::new(&images.0, &images.1).is_some() {
            cases.push(("pivoted light across the horizon", images.0, images.1));
        }
    }
    let (mut worst_f32, mut worst_f64, mut worst_pairs) = (0.0f64, 0.0f64, 0.0f64);
    let mut above = 0;
    // Evaluations of F per inversion: their sum and how many inversions took more than
    // 8 (bisection steps, which a Newton step landing exactly on the root once set off).
    let (mut evaluations, mut inversions, mut slow) = (0u32, 0u32, 0u32);
    for (name, a, b) in cases {
        let lens = CapIntersection::new(&a, &b).unwrap();
        let radial = |s: f64| (d3(lens.radial.axis), s, 2.0 - s);
        let other = f64_cap(&lens.other);
        let total = cap_intersection_f64(radial(lens.radial.one_minus_cos as f64), other);
        for i in 0..200 {
            let u0 = if i < 100 {
                (i as f32 + 0.5) / 100.0
            } else {
                rng.uniform_f32()
            };
            let (s, count) = lens.invert_radial_counting(u0 * lens.solid_angle);
            evaluations += count;
            inversions += 1;
            slow += (count > 8) as u32;
            let f32_error = (lens.cumulative(s) as f64 / lens.solid_angle as f64 - u0 as f64).abs();
            let f64_error =
                (cap_intersection_f64(radial(s as f64), other) / total - u0 as f64).abs();
            worst_f32 = worst_f32.max(f32_error);
            if !name.starts_with("pivoted") {
                worst_pairs = worst_pairs.max(f32_error);
            }
            worst_f64 = worst_f64.max(f64_error);
            if f32_error > 1e-5 {
                above += 1;
            }
        }
    }
    let mean = evaluations as f64 / inversions as f64;
    std::println!(
        "worst |F(s)/Ω − u0|: named pairs {worst_pairs:e}; all: f32 {worst_f32:e} \
         ({above} above 1e-5), f64 {worst_f64:e}; evaluations per inversion {mean:.2}, \
         {slow} of {inversions} took more than 8"
    );
    assert!(worst_pairs <= 1e-6, "{worst_pairs:e}");
    assert!(worst_f32 <= 6e-4 && above <= 600, "{worst_f32:e} {above}");
    assert!(worst_f64 <= 1e-3, "{worst_f64:e}");
    // Before the zero-residual rule of `safeguarded_newton_step`: 8.51 evaluations per
    // inversion, 6997 of 23200 inversions above 8; with it 1.65 and 130.
    assert!(mean <= 2.5 && slow <= inversions / 100, "{mean} {slow}");
}

/// The inner point towards which `sample_uniform` pulls a sample that rounding put just
/// outside (computed where that happens, not prepared) lies in both caps: for the named
/// pairs (among them a ring around a hole, both caps wider than a hemisphere) and random
/// pairs of every size, including caps across each other's rims and pivoted sphere
/// lights across the horizon (the SPTD sampler's clipped case).
#[test]
fn the_inner_point_lies_in_both_caps() {
    let mut rng = Rng::new(1811);
    let mut cases: Vec<(Cap, Cap)> = pairs().into_iter().map(|(_, a, b)| (a, b)).collect();
    for _ in 0..20_000 {
        let a = cap(rng.unit_vector_f32(), 2.0 * rng.uniform_f32());
        let b = cap(rng.unit_vector_f32(), 2.0 * rng.uniform_f32());
        cases.push((a, b));
        let light = Cap::from_sphere(
            rng.unit_vector_f32() * rng.log_uniform(0.0, 0.6) as f32,
            rng.log_uniform(-1.3, -0.2) as f32,
        );
        let pivot = rng.unit_vector_f32() * (0.9 * rng.uniform_f32());
        cases.push((
            crate::sphere::pivot_cap(&light, pivot),
            crate::sphere::pivot_cap(&cap(Vec3::Z, 1.0), pivot),
        ));
    }
    let mut tested = 0;
    for (a, b) in cases {
        let Some(lens) = CapIntersection::new(&a, &b) else {
            continue;
        };
        let inner = lens.inner_point();
        assert!(
            lens.radial.contains(inner) && lens.other.contains(inner),
            "{a:?} {b:?}: {inner}"
        );
        tested += 1;
    }
    assert!(tested > 20_000, "{tested}");
}

/// The radial range `[s_low, s_high]` (the Newton iteration's bracket and start), from
/// the half-angles' sines and cosines, against f64 (`1 − cos` of `max(0, d − θ_B)` and of
/// `min(d + θ_B, θ_A)`, all of `[0, t_A]` past `d + θ_B ≥ π`, from the same f32 caps) for
/// random pairs of every size and for small caps (`t_A` from 1e-6) across a large one's
/// rim, where `d − θ_B` cancels and an absolute error of a few 1e-8 in it is a large part
/// of a tiny cap. Measured: the largest error of an end 1.9e-3 of `t_A`, and 1.8e-2 of
/// itself where it is above 1e-3 `t_A`; the angles' form that this replaced (`asin` of the
/// sides, `sin` of the half differences) had 6.1e-3 and 1.9e-2 on the same draws.
#[test]
fn the_radial_range_matches_f64() {
    let mut rng = Rng::new(2203);
    let (mut worst_abs, mut worst_rel) = (0.0f64, 0.0f64);
    let mut tested = 0;
    for i in 0..100_000 {
        let (a, b) = if i % 2 == 0 {
            (
                cap(rng.unit_vector_f32(), 2.0 * rng.uniform_f32()),
                cap(rng.unit_vector_f32(), 2.0 * rng.uniform_f32()),
            )
        } else {
            // A small cap near the rim of a large one.
            let t_b = 2.0 * rng.uniform_f32();
            let theta_b = 2.0 * ((t_b as f64) / 2.0).sqrt().asin();
            let t_a = rng.log_uniform(-6.0, -1.0) as f32;
            let theta_a = 2.0 * ((t_a as f64) / 2.0).sqrt().asin();
            let offset = theta_a * (2.0 * rng.uniform() - 1.0);
            let d = (theta_b + offset).clamp(0.0, core::f64::consts::PI);
            let axis = tilted(d.to_degrees(), 360.0 * rng.uniform());
            (cap(axis, t_a), cap(Vec3::Z, t_b))
        };
        let Some(lens) = CapIntersection::new(&a, &b) else {
            continue;
        };
        let (ra, ob) = (&lens.radial, &lens.other);
        let angle = |t: f64| 2.0 * (t / 2.0).max(0.0).min(1.0).sqrt().asin();
        let (t_a, t_b) = (ra.one_minus_cos as f64, ob.one_minus_cos as f64);
        let (theta_a, theta_b) = (angle(t_a), angle(t_b));
        let diff = sub(d3(ob.axis), d3(ra.axis));
        let t_d = 0.5 * dot(diff, diff);
        let d = angle(t_d);
        let one_minus_cos = |x: f64| 2.0 * (0.5 * x).sin().powi(2);
        let low = one_minus_cos((d - theta_b).max(0.0)).min(t_a);
        let high = if d + theta_b >= core::f64::consts::PI {
            t_a
        } else {
            one_minus_cos((d + theta_b).min(theta_a)).min(t_a)
        };
        for (got, exact) in [
            (lens.s_low as f64, low),
            (lens.s_high as f64, high.max(low)),
        ] {
            let abs = (got - exact).abs() / t_a;
            worst_abs = worst_abs.max(abs);
            if exact > 1e-3 * t_a {
                worst_rel = worst_rel.max((got - exact).abs() / exact);
            }
        }
        tested += 1;
    }
    std::println!("radial range: worst error {worst_abs:e} of t_A, {worst_rel:e} relative");
    assert!(tested > 50_000, "{tested}");
    assert!(
        worst_abs <= 2.5e-3 && worst_rel <= 2.5e-2,
        "{worst_abs:e} {worst_rel:e}"
    );
}

/// The closed-form part of the radial inversion: up to `s_nested`, `cap(a, s)` lies inside
/// `B` and `F(s) = 2πs`. Over sphere lights across the horizon as the light bench draws
/// them (distance log-uniform in [1, 4], `sin²θ` in [0.06, 0.44], centres uniform over the
/// upper hemisphere, views with `cos θo` in [0.1, 1] and roughness in [0.1, 0.9], the
/// fitted GGX pivot), pivoted as the SPTD sampler pivots them, and random pairs:
/// `s_nested` is below the f64 bound `1 − cos(θ_B − d)` (never claims a lens), its half
/// sine `√(s/2)` at most 4.5e-6 below the bound's (the margin of 4e-6 and the rounding);
/// the f32 CDF there is `2πs` bit for bit, and the closed form's `s` has a residual
/// `|F(s) − target|` below 1e-6 of `Ω`. Measured: 52% of the bench's clipped draws take
/// the closed form, and the others take 2.13 evaluations of `F` each.
#[test]
fn the_nested_part_inverts_in_closed_form() {
    let mut rng = Rng::new(1918);
    let mut cases = bench_like_pivoted_pairs(&mut rng, 3000);
    let bench_cases = cases.len();
    for _ in 0..3000 {
        cases.push((
            cap(rng.unit_vector_f32(), 2.0 * rng.uniform_f32()),
            cap(rng.unit_vector_f32(), 2.0 * rng.uniform_f32()),
        ));
    }
    let (mut closed, mut draws, mut worst_gap) = (0u32, 0u32, 0.0f64);
    let mut newton_evaluations = 0u32;
    // In the nested part the sampler takes the whole circle's half arc as a constant
    // (`sample_uniform`), mostly `half_arc`'s value bit for bit. `half_arc` falls short
    // of it where B is nearly the whole sphere and the axes nearly antipodal (a strong
    // pivot's image of the upper hemisphere against a light's image across from it; its
    // numerator `t_d − t_B` then keeps only `ulp(2)`): there the constant is the exact
    // value (`s ≤ s_nested` ≤ the f64 bound asserted below, so the circle lies in B)
    // and `half_arc` left a wedge of the circle unsampled. Counted per part: the bench's
    // lights, the random pairs.
    let mut half_arcs_off = [0u32; 2];
    let whole_circle = |index: usize, half_arc: f32, off: &mut [u32; 2]| {
        let same = half_arc.to_bits() == WHOLE_CIRCLE_HALF_ARC.to_bits();
        assert!(half_arc <= WHOLE_CIRCLE_HALF_ARC, "{index}: {half_arc}");
        off[(index >= bench_cases) as usize] += !same as u32;
    };
    for (index, (a, b)) in cases.into_iter().enumerate() {
        let Some(lens) = CapIntersection::new(&a, &b) else {
            continue;
        };
        let angle = |t: f64| 2.0 * (t / 2.0).max(0.0).min(1.0).sqrt().asin();
        let t_a = lens.radial.one_minus_cos as f64;
        // Angles past π/2 from the complement's side (`1 + cos`), where `asin` of
        // `√(t/2)` near 1 would lose them.
        let angle_of_sides = |t: f64, h: f64| {
            if t <= 1.0 {
                angle(t)
            } else {
                core::f64::consts::PI - angle(h)
            }
        };
        let (a64, b64) = (d3(lens.radial.axis), d3(lens.other.axis));
        let (diff, sum) = (sub(b64, a64), add(b64, a64));
        let theta_b = angle_of_sides(
            lens.other.one_minus_cos as f64,
            lens.other.one_plus_cos as f64,
        );
        let d = angle_of_sides(0.5 * dot(diff, diff), 0.5 * dot(sum, sum));
        let bound = if theta_b > d {
            (2.0 * (0.5 * (theta_b - d)).sin().powi(2)).min(t_a)
        } else {
            0.0
        };
        let nested = lens.nested as f64;
        assert!(nested <= bound, "{a:?} {b:?}: {nested:e} > {bound:e}");
        // The gap in the half sine `sin((θ_B − d)/2) = √(s/2)`: the margin of 4e-6
        // and the rounding.
        worst_gap = worst_gap.max((0.5 * bound).sqrt() - (0.5 * nested).sqrt());
        for i in 0..=16 {
            let s = lens.nested * i as f32 / 16.0;
            if s > 0.0 && s <= 1.0 && s < lens.other.one_minus_cos {
                assert_eq!(lens.cumulative(s), TAU * s, "{a:?} {b:?} at {s:e}");
            }
            // The sampler takes the half arc there as the constant (`sample_uniform`).
            if s > 0.0 {
                whole_circle(index, lens.half_arc(s), &mut half_arcs_off);
            }
        }
        for i in 0..100 {
            let u0 = (i as f32 + 0.5) / 100.0;
            let target = u0 * lens.solid_angle;
            let (s, evaluations) = lens.invert_radial_counting(target);
            if index < bench_cases {
                draws += 1;
                closed += (evaluations == 0) as u32;
                newton_evaluations += evaluations;
            }
            if evaluations == 0 {
                // The nested part's half arc is the whole circle's, bit for bit (also at
                // `s = 0`, where `half_arc` gives `PI`, the direction is the axis).
                if s > 0.0 {
                    whole_circle(index, lens.half_arc(s), &mut half_arcs_off);
                }
                let residual = (lens.cumulative(s) - target).abs() as f64 / lens.solid_angle as f64;
                assert!(residual <= 1e-6, "{a:?} {b:?} u0 {u0}: {residual:e}");
            }
        }
    }
    let fraction = closed as f64 / draws as f64;
    let per_newton = newton_evaluations as f64 / (draws - closed) as f64;
    std::println!(
        "closed-form inversions: {fraction:.3} of the bench's clipped draws, the others \
         {per_newton:.2} evaluations each; half sine of s_nested at most {worst_gap:e} \
         below the f64 bound's"
    );
    std::println!("nested half arcs short of the whole circle (bench, random): {half_arcs_off:?}");
    // Rare: a few cases of 3000 each.
    assert!(
        half_arcs_off[0] <= 200 && half_arcs_off[1] <= 200,
        "{half_arcs_off:?}"
    );
    assert!(worst_gap <= 4.5e-6, "{worst_gap:e}");
    assert!((0.3..=0.6).contains(&fraction), "{fraction}");
    // The others start from the chord beyond `s_nested` (2.42 evaluations each from the
    // chord over the whole radial range).
    assert!(per_newton <= 2.3, "{per_newton}");
}

/// The sampler's constant half arc of a circle wholly inside `B` is `half_arc`'s value
/// there, `acos` of the clamped cosine −1, bit for bit (one ulp below `f32` π).
#[test]
fn the_whole_circle_half_arc_is_acos_of_minus_one() {
    assert_eq!(libm::acosf(-1.0).to_bits(), WHOLE_CIRCLE_HALF_ARC.to_bits());
    assert_eq!(
        WHOLE_CIRCLE_HALF_ARC.to_bits() + 1,
        core::f32::consts::PI.to_bits()
    );
    // A circle inside B: the clamped cosine −1.
    let lens = CapIntersection::new(&cap(Vec3::Z, 0.1), &cap(tilted(5.0, 0.0), 0.8)).unwrap();
    assert!(lens.nested > 0.0);
    assert_eq!(
        lens.half_arc(0.5 * lens.nested).to_bits(),
        WHOLE_CIRCLE_HALF_ARC.to_bits()
    );
}

/// Sphere lights across the horizon as the light bench draws them (distance log-uniform
/// in [1, 4], `sin²θ` in [0.06, 0.44], centres over the upper hemisphere, views with
/// `cos θo` in [0.1, 1], roughness in [0.1, 0.9], the fitted GGX pivot), pivoted as the
/// SPTD sphere light sampler pivots them: `(g(C), g(H))`.
fn bench_like_pivoted_pairs(rng: &mut Rng, count: usize) -> Vec<(Cap, Cap)> {
    let mut cases = Vec::new();
    while cases.len() < count {
        let distance = rng.log_uniform(0.0, 4f64.log10()) as f32;
        let sin2 = 0.06 + 0.38 * rng.uniform_f32();
        let center = loop {
            let v = rng.unit_vector_f32();
            if v.z >= 0.0 {
                break v;
            }
        };
        let light = Cap::from_sphere(center * distance, distance * sin2.sqrt());
        if light.axis.z * light.axis.z >= light.sin2 {
            continue;
        }
        let cos_o = 0.1 + 0.9 * rng.uniform_f32();
        let phi = core::f32::consts::TAU * rng.uniform_f32();
        let sin_o = (1.0 - cos_o * cos_o).sqrt();
        let wo = Vec3::new(sin_o * phi.cos(), sin_o * phi.sin(), cos_o);
        let roughness = 0.1 + 0.8 * rng.uniform_f32();
        let pivot = crate::sphere::GgxPivot::from_view(wo, roughness)
            .unwrap()
            .pivot;
        let (image, _) = crate::sphere::pivot::pivot_cap_fast(&light, pivot);
        cases.push((image, crate::sphere::pivot::pivot_upper_hemisphere(pivot)));
    }
    cases
}

/// The prepared `Ω(A ∩ B)` (`whole_solid_angle`: on its fast path `F(t_A)` from the
/// prepared lens partner) is `cap_intersection_solid_angle` of the two caps bit for bit,
/// and the preparation fails exactly where that is not a usable normaliser, for the named
/// pairs, random pairs of every size (the radial cap up to and past a hemisphere, the other
/// up to, past and at a hemisphere, equal sides, caps whose hole is 0) and pivoted sphere
/// lights across the horizon as the light bench draws them; both branches of the fast path
/// (the other cap at most and wider than a hemisphere) are taken many times, and so is the
/// general call.
#[test]
fn the_prepared_solid_angle_is_the_general_one() {
    let mut rng = Rng::new(3718);
    let mut cases: Vec<(Cap, Cap)> = pairs().into_iter().map(|(_, a, b)| (a, b)).collect();
    cases.extend(bench_like_pivoted_pairs(&mut rng, 5000));
    for i in 0..40_000 {
        let side = |rng: &mut Rng| match i % 5 {
            0 => 2.0 * rng.uniform_f32(),
            1 => rng.log_uniform(-6.0, 0.3) as f32,
            2 => 1.0,
            3 => 2.0,
            _ => 0.5 + rng.uniform_f32(),
        };
        let a = cap(rng.unit_vector_f32(), side(&mut rng));
        let b = if i % 7 == 0 {
            Cap {
                axis: rng.unit_vector_f32(),
                ..a
            }
        } else {
            cap(rng.unit_vector_f32(), side(&mut rng))
        };
        cases.push((a, b));
    }
    // [fast, other at most a hemisphere], [fast, wider], [general]
    let mut paths = [0u32; 3];
    for (a, b) in cases {
        let (radial, other) = if a.one_minus_cos <= b.one_minus_cos {
            (a, b)
        } else {
            (b, a)
        };
        let general = cap_intersection_solid_angle(&radial, &other);
        let (t_a, t_b) = (radial.one_minus_cos, other.one_minus_cos);
        let fast = t_a > 0.0 && t_a <= 1.0 && t_a < t_b && (t_b <= 1.0 || other.one_plus_cos > 0.0);
        paths[if !fast {
            2
        } else if t_b <= 1.0 {
            0
        } else {
            1
        }] += 1;
        match CapIntersection::new(&a, &b) {
            Some(lens) => assert_eq!(
                lens.solid_angle.to_bits(),
                general.to_bits(),
                "{a:?} {b:?}: {} {general}",
                lens.solid_angle
            ),
            None => assert!(
                !(general > 0.0) || !(1.0 / general).is_finite(),
                "{a:?} {b:?}: {general}"
            ),
        }
    }
    std::println!("prepared solid angle paths [fast ≤ hemisphere, fast wider, general]: {paths:?}");
    assert!(paths.iter().all(|&n| n > 3000), "{paths:?}");
}

/// `Ω ≥ MIN_NORMALISER` is `Ω > 0 && (1/Ω).is_finite()`: for every `f32` from 0 up to 2⁻¹²⁰
/// (the threshold among them) and for negative, zero, large, infinite and NaN values.
#[test]
fn min_normaliser_is_where_the_reciprocal_is_finite() {
    let same = |x: f32| (x >= MIN_NORMALISER) == (x > 0.0 && (1.0 / x).is_finite());
    for bits in 0..=0x0380_0000u32 {
        let x = f32::from_bits(bits);
        assert!(same(x) && same(-x), "{bits:#x}");
    }
    for x in [
        1e-30,
        1.0,
        4.0 * PI,
        f32::MAX,
        f32::INFINITY,
        f32::NAN,
        -0.0,
    ] {
        assert!(same(x) && same(-x), "{x}");
    }
    assert!(!(1.0 / f32::from_bits(0x0020_0000)).is_finite());
    assert!((1.0 / MIN_NORMALISER).is_finite());
}
