//! SPTD integrals over unions and complements of caps (Eq. 11, issue 20, 1), against
//! references that do not call the functions under test: the f64 probability that a
//! pivoted base sample lands in the set (binomial), the f64 two-cap geometry of the
//! images (`pivot_image_f64`, `cap_intersection_f64`: Eq. 2 and Eq. 36 literally) for
//! the uniform base, and f64 quadrature of Eq. 8 over the caps for the clamped cosine.

use super::*;
use crate::testing::{
    D3, Rng, cap_intersection_f64, d3, dot, integrate_over_cap_axis_f64, normalize,
    pivot_image_f64, pivot_transform_f64, uniform_direction_f64,
};
use core::f64::consts::{PI as PI64, TAU as TAU64};

/// The SPTD density of Eq. 8 in f64: the base at `g(ω)` times
/// `((1 − |r_p|²)/|ω − r_p|²)²`; `cosine_axis = None` is the uniform base.
fn density_f64(w: D3, pivot: D3, cosine_axis: Option<D3>) -> f64 {
    let wi = pivot_transform_f64(w, pivot);
    let base = match cosine_axis {
        None => 0.25 / PI64,
        Some(a) => dot(wi, a).max(0.0) / PI64,
    };
    let e: D3 = core::array::from_fn(|i| w[i] - pivot[i]);
    let j = ((1.0 - dot(pivot, pivot)) / dot(e, e)).powi(2);
    base * j
}

/// A cap in f64: unit axis and `1 − cos θ`, `1 + cos θ`, from the f32 cap's
/// authoritative side (the axis normalised in f64).
#[derive(Clone, Copy, Debug)]
struct Cap64 {
    axis: D3,
    t: f64,
    h: f64,
}

fn cap64(cap: &Cap) -> Cap64 {
    let (t, h) = if cap.one_minus_cos <= 1.0 {
        (cap.one_minus_cos as f64, 2.0 - cap.one_minus_cos as f64)
    } else {
        (2.0 - cap.one_plus_cos as f64, cap.one_plus_cos as f64)
    };
    Cap64 {
        axis: normalize(d3(cap.axis)),
        t,
        h,
    }
}

impl Cap64 {
    fn contains(&self, w: D3) -> bool {
        if self.t <= 1.0 {
            let e: D3 = core::array::from_fn(|i| w[i] - self.axis[i]);
            0.5 * dot(e, e) <= self.t
        } else {
            let e: D3 = core::array::from_fn(|i| w[i] + self.axis[i]);
            0.5 * dot(e, e) >= self.h
        }
    }
    /// The complement: the cap about `−axis` with `t` and `h` exchanged.
    fn complement(&self) -> Cap64 {
        Cap64 {
            axis: core::array::from_fn(|i| -self.axis[i]),
            t: self.h,
            h: self.t,
        }
    }
    /// `∫ f` over the cap by the midpoint rule in `(s, φ)` with `1 − cos = t s²` (the
    /// grid refines towards the axis); for a cap wider than a hemisphere, the ring
    /// `t ∈ [1, 2 − h]` is integrated from the hole's side in `1 + cos`, so that a tiny
    /// hole keeps its resolution.
    fn integrate(&self, n: usize, f: &dyn Fn(D3) -> f64) -> f64 {
        let ring = |axis: D3, t_max: f64| integrate_over_cap_axis_f64(axis, t_max, n, f);
        if self.t <= 1.0 {
            ring(self.axis, self.t)
        } else {
            // Whole sphere minus the hole about −axis.
            let minus: D3 = core::array::from_fn(|i| -self.axis[i]);
            let hole = Cap64 {
                axis: minus,
                t: self.h,
                h: self.t,
            };
            ring(minus, 2.0) - ring(minus, hole.t)
        }
    }
}

fn sptd_of(pivot: Vec3, axis: Option<Vec3>) -> Sptd {
    match axis {
        None => Sptd::uniform(pivot),
        Some(a) => Sptd::clamped_cosine(pivot, a),
    }
}

fn cap(axis: Vec3, cos: f32) -> Cap {
    Cap::from_axis_cos(axis, cos)
}

/// Pairs of caps `(name, A, B)`: lens, disjoint, nested both ways, identical,
/// complementary, wide and small, two wide caps covering the sphere, caps on the
/// horizon of `z` (where the clamped cosine's image straddles it for small pivots), an
/// empty cap.
fn pairs() -> Vec<(&'static str, Cap, Cap)> {
    let z = Vec3::Z;
    let x = Vec3::X;
    let tilt = |deg: f32| Vec3::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
    let a = cap(z, 0.8);
    vec![
        ("lens", a, cap(tilt(40.0), 0.8)),
        ("disjoint", cap(z, 0.9), cap(-z, 0.9)),
        ("nested", cap(z, 0.5), cap(tilt(10.0), 0.95)),
        ("nested reversed", cap(tilt(10.0), 0.95), cap(z, 0.5)),
        ("identical", a, a),
        ("complementary", a, a.complement()),
        (
            "wide and small",
            cap(x, -0.6),
            cap(Vec3::new(0.0, 0.8, 0.6), 0.3),
        ),
        ("two wide", cap(x, -0.5), cap(-x, -0.5)),
        (
            "across the horizon",
            cap(x, 0.9),
            cap(Vec3::new(0.94, 0.34, 0.0), 0.85),
        ),
        ("empty and one", Cap::EMPTY, cap(tilt(70.0), 0.7)),
    ]
}

fn pivots() -> [Vec3; 5] {
    let tilt = Vec3::new(0.6, 0.0, 0.8);
    [
        Vec3::ZERO,
        Vec3::new(0.0, 0.0, 0.1),
        Vec3::new(0.0, 0.0, 0.5),
        tilt * 0.9,
        Vec3::new(0.3, -0.4, 0.2),
    ]
}

#[test]
fn unions_and_complements_are_the_probability_of_landing_in_them() {
    // The fraction of g(ω_i), ω_i drawn from the base in f64, that lands in A ∪ B and
    // outside A, counted with f64 containment of each cap: binomial noise
    // √(p(1 − p)/n) ≤ 8e-4 at n = 4e5, tested at 5σ plus f32 rounding.
    let n = 400_000usize;
    let cosine_axis = Vec3::new(0.0, 0.6, 0.8).normalize();
    let pairs = pairs();
    let mut rng = Rng::new(2020);
    let mut worst = 0.0f64;
    for pivot in pivots() {
        for axis in [None, Some(cosine_axis), Some(Vec3::Z)] {
            let sptd = sptd_of(pivot, axis);
            let caps: Vec<(Cap64, Cap64)> =
                pairs.iter().map(|(_, a, b)| (cap64(a), cap64(b))).collect();
            let (mut union, mut outside) = (vec![0u64; caps.len()], vec![0u64; caps.len()]);
            for _ in 0..n {
                let wi = match axis {
                    None => uniform_direction_f64(&mut rng),
                    Some(a) => {
                        // Cosine-distributed about `a` in f64 (Malley's method).
                        let (r2, phi) = (rng.uniform(), TAU64 * rng.uniform());
                        let (u, v) = crate::testing::frame_f64(d3(a));
                        let (r, zc) = (r2.sqrt(), (1.0 - r2).sqrt());
                        let a = d3(a);
                        core::array::from_fn(|i| {
                            r * (phi.cos() * u[i] + phi.sin() * v[i]) + zc * a[i]
                        })
                    }
                };
                let w = pivot_transform_f64(wi, d3(pivot));
                for (k, (a, b)) in caps.iter().enumerate() {
                    let in_a = a.contains(w);
                    union[k] += (in_a || b.contains(w)) as u64;
                    outside[k] += (!in_a) as u64;
                }
            }
            for (k, (name, a, b)) in pairs.iter().enumerate() {
                for (value, hits, what) in [
                    (sptd.integral_over_cap_union(a, b), union[k], "A ∪ B"),
                    (sptd.integral_over_cap_complement(a), outside[k], "Ā"),
                ] {
                    let p = hits as f64 / n as f64;
                    let sigma = (p * (1.0 - p) / n as f64).sqrt();
                    let error = (value as f64 - p).abs();
                    worst = worst.max(error / (sigma + 1e-6));
                    assert!(
                        error <= 5.0 * sigma + 2e-5,
                        "{name}, {what}, pivot {pivot:?}, axis {axis:?}: {value} vs {p} (σ {sigma:.1e})"
                    );
                }
            }
        }
    }
    std::println!("binomial test: worst error {worst:.2} σ");
}

/// `(name, pivot, A, B)` for the uniform base, with the hard cases that the binomial
/// test cannot resolve: tiny caps of 1e-8 sr (overlapping, disjoint, nested,
/// identical), a cap leaving a hole of 1e-8 sr, strong pivots.
fn uniform_cases() -> Vec<(&'static str, Vec3, Cap, Cap)> {
    let tiny_t = 1e-8 / TAU64; // 1e-8 sr
    let axis = Vec3::new(0.3, 0.2, 0.9).normalize();
    let theta = (2.0 * tiny_t).sqrt(); // the tiny cap's radius, ≈ 5.6e-5 rad
    let (u, _) = crate::testing::frame_f64(d3(axis));
    let shifted = |fraction: f64| -> Vec3 {
        let a = d3(axis);
        let d = normalize(core::array::from_fn(|i| a[i] + fraction * theta * u[i]));
        Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32)
    };
    let tiny = Cap::from_axis_one_minus_cos(axis, tiny_t as f32);
    let tilt = Vec3::new(0.6, 0.0, 0.8);
    let mut cases = Vec::new();
    for (pname, pivot) in [
        ("origin", Vec3::ZERO),
        ("0.5", tilt * 0.5),
        ("0.99", tilt * 0.99),
    ] {
        let _ = pname;
        cases.extend([
            (
                "tiny lens",
                pivot,
                tiny,
                Cap::from_axis_one_minus_cos(shifted(1.0), tiny_t as f32),
            ),
            (
                "tiny disjoint",
                pivot,
                tiny,
                Cap::from_axis_one_minus_cos(shifted(3.0), tiny_t as f32),
            ),
            (
                "tiny nested",
                pivot,
                tiny,
                Cap::from_axis_one_minus_cos(shifted(0.2), 0.25 * tiny_t as f32),
            ),
            ("tiny identical", pivot, tiny, tiny),
            (
                "hole of 1e-8 sr",
                pivot,
                Cap::from_axis_one_plus_cos(-axis, tiny_t as f32),
                cap(tilt, 0.9),
            ),
            ("lens", pivot, cap(Vec3::Z, 0.7), cap(tilt, 0.6)),
            (
                "wide and wide",
                pivot,
                cap(Vec3::X, -0.7),
                cap(Vec3::Y, -0.2),
            ),
            (
                "nearly nested",
                pivot,
                cap(Vec3::Z, 0.3),
                cap(Vec3::new(0.01, 0.0, 1.0), 0.3),
            ),
        ]);
    }
    cases
}

#[test]
fn uniform_base_over_unions_and_complements_matches_the_f64_images() {
    // Reference: the images by Eq. 2 in f64 (`pivot_image_f64`), the union's solid angle
    // Ω(g A) + Ω(g B) − Ω(g A ∩ g B) with the acos form of Eq. 36 in f64, and the
    // complement's 2π (1 + cos ψ'_A); over 4π. Relative error, plus 1e-7 of the whole.
    let mut worst = [0.0f64; 2];
    for (name, pivot, a, b) in uniform_cases() {
        let sptd = Sptd::uniform(pivot);
        let p = d3(sptd.pivot);
        let (ia, ib) = (
            pivot_image_f64(d3(a.axis), cap64(&a).t, p),
            pivot_image_f64(d3(b.axis), cap64(&b).t, p),
        );
        // A cap wider than a hemisphere: its hole from `h` in f64.
        let image = |c: &Cap, i: (D3, f64, f64)| -> (D3, f64, f64) {
            if c.one_minus_cos > 1.0 {
                // g of the complement (a small cap) in f64, complemented.
                let comp = pivot_image_f64(scale_d3(d3(c.axis), -1.0), c.one_plus_cos as f64, p);
                (scale_d3(comp.0, -1.0), comp.2, comp.1)
            } else {
                i
            }
        };
        let (ia, ib) = (image(&a, ia), image(&b, ib));
        let both = if ia.1 < 1e-6 && ib.1 < 1e-6 {
            planar_lens_f64(ia, ib)
        } else {
            cap_intersection_f64(ia, ib)
        };
        let union = (TAU64 * ia.1 + TAU64 * ib.1 - both) / (4.0 * PI64);
        let outside = TAU64 * ia.2 / (4.0 * PI64);
        for (k, (value, reference, what)) in [
            (sptd.integral_over_cap_union(&a, &b), union, "A ∪ B"),
            (sptd.integral_over_cap_complement(&a), outside, "Ā"),
        ]
        .into_iter()
        .enumerate()
        {
            let error = (value as f64 - reference).abs() / reference.max(1e-300);
            if reference > 1e-12 {
                worst[k] = worst[k].max(error);
            }
            // Tiny caps and holes under a pivot: the images are down to 1e-5 rad wide,
            // and their axes and boundary points carry the f32 rounding of g (about
            // 1e-7 rad), 1% of the offset that decides the lens or of the hole's arc.
            let tiny = name.starts_with("tiny") || name.starts_with("hole");
            let relative = if tiny && pivot != Vec3::ZERO {
                1e-2
            } else {
                2e-3
            };
            let absolute = if reference >= 1e-6 { 1e-7 } else { 0.0 };
            assert!(
                (value as f64 - reference).abs() <= relative * reference + absolute,
                "{name}, {what}, pivot {pivot:?}: {value:e} vs {reference:e} (relative {error:.1e})"
            );
        }
    }
    std::println!(
        "worst relative error: union {:.1e}, complement {:.1e}",
        worst[0],
        worst[1]
    );
}

/// The intersection of two tiny caps `(axis, 1 − cos, 1 + cos)` as that of two plane
/// disks of the same areas (`r² = 2 (1 − cos)`) at the chord between the axes: the
/// lens of two circles, relative error of order `θ²` (below 1e-8 for caps of 1e-8 sr),
/// where the acos form of Eq. 36 cancels in f64 (`acos` near 1 keeps only √ε).
fn planar_lens_f64(a: (D3, f64, f64), b: (D3, f64, f64)) -> f64 {
    let (r1, r2) = ((2.0 * a.1).sqrt(), (2.0 * b.1).sqrt());
    let e: D3 = core::array::from_fn(|i| a.0[i] - b.0[i]);
    let d = dot(e, e).sqrt();
    if d >= r1 + r2 {
        return 0.0;
    }
    if d <= (r1 - r2).abs() {
        return PI64 * r1.min(r2).powi(2);
    }
    let alpha = ((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1))
        .clamp(-1.0, 1.0)
        .acos();
    let beta = ((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2))
        .clamp(-1.0, 1.0)
        .acos();
    let k = ((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2)).max(0.0);
    r1 * r1 * alpha + r2 * r2 * beta - 0.5 * k.sqrt()
}

fn scale_d3(a: D3, s: f64) -> D3 {
    core::array::from_fn(|i| a[i] * s)
}

/// `(name, pivot, A, B)` for the clamped cosine about `z`: caps whose images straddle
/// its horizon, a cap wider than a hemisphere, a tiny cap on the horizon and one above
/// it, a hole of 1e-8 sr.
fn clamped_cases() -> Vec<(&'static str, Vec3, Cap, Cap)> {
    let tiny_t = (1e-8 / TAU64) as f32;
    let on_horizon = Vec3::new(0.8, 0.6, 0.0);
    vec![
        (
            "across the horizon",
            Vec3::new(0.0, 0.0, 0.1),
            cap(Vec3::X, 0.9),
            cap(Vec3::new(0.94, 0.34, 0.0), 0.85),
        ),
        (
            "across, axes below",
            Vec3::new(0.1, 0.0, 0.2),
            cap(Vec3::new(0.9, 0.0, 0.3), 0.8),
            cap(Vec3::new(0.7, 0.5, 0.2), 0.9),
        ),
        (
            "wide across",
            Vec3::new(0.2, 0.1, 0.0),
            cap(Vec3::new(1.0, 0.0, 0.2), -0.4),
            cap(Vec3::new(-0.6, 0.0, 0.8), 0.6),
        ),
        (
            "disjoint across",
            Vec3::new(0.0, 0.0, 0.3),
            cap(Vec3::X, 0.95),
            cap(-Vec3::X, 0.95),
        ),
        (
            "nested across",
            Vec3::new(0.0, 0.2, 0.0),
            cap(Vec3::X, 0.6),
            cap(Vec3::new(0.95, 0.2, 0.1), 0.97),
        ),
        (
            "tiny on the horizon",
            Vec3::ZERO,
            Cap::from_axis_one_minus_cos(on_horizon, tiny_t),
            Cap::from_axis_one_minus_cos(Vec3::new(0.8, 0.6, 4e-5), tiny_t),
        ),
        (
            "tiny above",
            Vec3::new(0.0, 0.0, -0.4),
            Cap::from_axis_one_minus_cos(Vec3::new(0.3, 0.2, -0.9), tiny_t),
            Cap::from_axis_one_minus_cos(Vec3::new(0.30004, 0.2, -0.9), tiny_t),
        ),
        (
            "hole of 1e-8 sr",
            Vec3::new(0.0, 0.0, 0.3),
            Cap::from_axis_one_plus_cos(Vec3::new(0.2, 0.1, 0.97), tiny_t),
            cap(Vec3::X, 0.5),
        ),
    ]
}

#[test]
fn clamped_cosine_over_unions_and_complements_matches_quadrature() {
    // Reference: f64 midpoint quadrature of Eq. 8 over A, over B outside A, and over the
    // complement of A (its own f64 cap), 400 × 800 cells each. The indicator of A inside
    // B's cells makes the union's quadrature error about perimeter × cell size: the
    // bound is 2e-3 relative; tiny caps on the horizon (a value of about θ³ from terms
    // of size θ, see `clamped_cosine_over_cap`) are held to an absolute bound.
    let z = d3(Vec3::Z);
    let n = 400;
    let mut worst = 0.0f64;
    for (name, pivot, a, b) in clamped_cases() {
        let sptd = Sptd::clamped_cosine(pivot, Vec3::Z);
        let p = d3(sptd.pivot);
        let (a64, b64) = (cap64(&a), cap64(&b));
        let d = |w: D3| density_f64(w, p, Some(z));
        let in_a = a64.integrate(n, &d);
        let b_outside_a = b64.integrate(n, &|w| if a64.contains(w) { 0.0 } else { d(w) });
        let union = in_a + b_outside_a;
        let outside = a64.complement().integrate(n, &d);
        for (value, reference, what) in [
            (sptd.integral_over_cap_union(&a, &b), union, "A ∪ B"),
            (sptd.integral_over_cap_complement(&a), outside, "Ā"),
        ] {
            let tiny = a.solid_angle() < 1e-6 || (what == "Ā" && a.one_plus_cos < 1e-6);
            let bound = if tiny {
                2e-3 * reference + 1e-12
            } else {
                2e-3 * reference + 2e-6
            };
            if !tiny || name.starts_with("tiny above") {
                worst = worst.max((value as f64 - reference).abs() / reference);
            }
            assert!(
                (value as f64 - reference).abs() <= bound,
                "{name}, {what}: {value:e} vs {reference:e}"
            );
        }
    }
    std::println!("quadrature test: worst relative error {worst:.1e}");
}

#[test]
fn the_set_algebra_holds_for_random_caps() {
    // ∫_{A ∪ A} = ∫_A, ∫_{A ∪ Ā} = 1, ∫_Ā + ∫_A = 1 (both bases are normalised over the
    // sphere, Eq. 9), the union is symmetric, at least the larger cap and at most the
    // sum, and ∫_{A ∪ B} = ∫_A + ∫_B − ∫_{A ∩ B} (the paper's algebra, which the
    // implementation does not use).
    let mut rng = Rng::new(99);
    for case in 0..3000 {
        let pivot = rng.unit_vector_f32() * (rng.uniform() as f32 * 0.95);
        let axis = (case % 2 == 1).then(|| rng.unit_vector_f32());
        let sptd = sptd_of(pivot, axis);
        let random_cap = |rng: &mut Rng| {
            let t = match rng.below(3) {
                0 => rng.uniform() as f32 * 2.0,
                1 => rng.log_uniform(-6.0, 0.0) as f32,
                _ => 2.0 - rng.log_uniform(-6.0, 0.0) as f32,
            };
            Cap::from_axis_one_minus_cos(rng.unit_vector_f32(), t)
        };
        let a = random_cap(&mut rng);
        let b = random_cap(&mut rng);
        let (ia, ib) = (sptd.integral_over_cap(&a), sptd.integral_over_cap(&b));
        let both = sptd.integral_over_cap_intersection(&a, &b);
        let union = sptd.integral_over_cap_union(&a, &b);
        let what = format!("case {case}: {sptd:?} {a:?} {b:?}");
        let tolerance = 2e-5;
        assert!(
            (sptd.integral_over_cap_union(&a, &a) - ia).abs() <= tolerance,
            "{what}"
        );
        assert!(
            (sptd.integral_over_cap_union(&a, &a.complement()) - 1.0).abs() <= tolerance,
            "{what}: {}",
            sptd.integral_over_cap_union(&a, &a.complement())
        );
        assert!(
            (sptd.integral_over_cap_complement(&a) + ia - 1.0).abs() <= tolerance,
            "{what}"
        );
        assert!(
            (sptd.integral_over_cap_union(&b, &a) - union).abs() <= tolerance,
            "{what}"
        );
        assert!(
            union >= ia.max(ib) - tolerance && union <= ia + ib + tolerance,
            "{what}"
        );
        assert!(
            (union - (ia + ib - both)).abs() <= 5e-5,
            "{what}: {union} vs {}",
            ia + ib - both
        );
    }
    // The whole sphere and the empty set, for both bases.
    for sptd in [
        Sptd::uniform(Vec3::new(0.2, 0.3, 0.4)),
        Sptd::clamped_cosine(Vec3::ZERO, Vec3::Y),
    ] {
        assert_eq!(sptd.integral_over_cap_complement(&Cap::EMPTY), 1.0);
        assert_eq!(sptd.integral_over_cap_complement(&Cap::WHOLE_SPHERE), 0.0);
        assert_eq!(sptd.integral_over_cap_union(&Cap::EMPTY, &Cap::EMPTY), 0.0);
        assert!((sptd.integral_over_cap_union(&Cap::EMPTY, &Cap::WHOLE_SPHERE) - 1.0).abs() < 1e-6);
    }
}

#[test]
fn malformed_caps_give_zero_and_every_value_is_finite() {
    let good = cap(Vec3::new(0.0, 0.6, 0.8), 0.5);
    let bad = [
        Cap {
            one_minus_cos: f32::NAN,
            ..good
        },
        Cap {
            axis: Vec3::new(f32::NAN, 0.0, 1.0),
            ..good
        },
        Cap {
            axis: Vec3::new(f32::INFINITY, 0.0, 1.0),
            ..good
        },
        Cap {
            axis: Vec3::ZERO,
            ..good
        },
    ];
    for sptd in [
        Sptd::uniform(Vec3::new(0.0, 0.0, 0.5)),
        Sptd::clamped_cosine(Vec3::ZERO, Vec3::Z),
    ] {
        for b in bad {
            assert_eq!(sptd.integral_over_cap_union(&b, &good), 0.0);
            assert_eq!(sptd.integral_over_cap_union(&good, &b), 0.0);
            assert_eq!(sptd.integral_over_cap_complement(&b), 0.0);
        }
    }
    // Hand-built caps of special values (not malformed: clamped, sanitized) and
    // special pivots: finite, in [0, 1].
    let specials = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        2.0,
        3.0,
        f32::INFINITY,
        f32::NEG_INFINITY,
        1e-45,
        f32::MAX,
        0.5,
    ];
    let mut rng = Rng::new(3);
    for &t in &specials {
        for &h in &specials {
            let c = Cap {
                axis: rng.unit_vector_f32(),
                one_minus_cos: t,
                one_plus_cos: h,
                sin2: 0.3,
            };
            for pivot in [
                Vec3::ZERO,
                Vec3::splat(f32::NAN),
                Vec3::new(0.0, 0.0, 1.0),
                Vec3::new(2.0, 0.0, 0.0),
            ] {
                for sptd in [Sptd::uniform(pivot), Sptd::clamped_cosine(pivot, Vec3::X)] {
                    for v in [
                        sptd.integral_over_cap_union(&c, &good),
                        sptd.integral_over_cap_union(&good, &c),
                        sptd.integral_over_cap_complement(&c),
                    ] {
                        assert!(
                            v.is_finite() && (0.0..=1.0).contains(&v),
                            "{c:?} {pivot:?}: {v}"
                        );
                    }
                }
            }
        }
    }
}
