use super::sg::*;
use crate::Vec3;
use crate::testing::{D3, Rng, d3, dot, normalize, sub};
use core::f64::consts::PI as PI64;

/// `1 − ω·ξ` in f64 from the f32 vectors, by `|ω − ξ|²/2`.
fn one_minus_dot(w: D3, a: D3) -> f64 {
    let e = sub(normalize(w), normalize(a));
    0.5 * dot(e, e)
}

/// `A(λ)` in f64 by the composite Simpson rule over `t = 1 − cos θ ∈ [0, 2]`, split at
/// multiples of `1/λ` so that sharp lobes are resolved: `2π ∫ e^{−λt} dt`.
fn integral_by_quadrature(l: f64) -> f64 {
    let mut total = 0.0;
    let mut a = 0.0;
    let width = (1.0 / l.max(1e-12)).min(2.0) / 4.0;
    while a < 2.0 {
        let b = (a + width).min(2.0);
        let n = 16;
        let h = (b - a) / n as f64;
        let f = |t: f64| (-l * t).exp();
        let mut s = f(a) + f(b);
        for i in 1..n {
            s += if i % 2 == 1 { 4.0 } else { 2.0 } * f(a + i as f64 * h);
        }
        total += s * h / 3.0;
        if (-l * b).exp() < 1e-30 {
            break;
        }
        a = b;
    }
    2.0 * PI64 * total
}

#[test]
fn integral_matches_quadrature_and_limits() {
    for e in -8..=8 {
        let l = 10f64.powi(e);
        let value = sg_integral(l as f32) as f64;
        let reference = integral_by_quadrature(l as f32 as f64);
        assert!(
            ((value - reference) / reference).abs() < 2e-6,
            "λ = {l}: {value} vs {reference}"
        );
    }
    assert_eq!(sg_integral(0.0), 4.0 * core::f32::consts::PI);
    assert_eq!(sg_integral(-1.0), 4.0 * core::f32::consts::PI);
    assert_eq!(sg_integral(f32::NAN), 4.0 * core::f32::consts::PI);
    assert!(sg_integral(f32::INFINITY).is_finite() && sg_integral(f32::INFINITY) > 0.0);
    assert!((sg_integral(1e-30) - 4.0 * core::f32::consts::PI).abs() < 1e-6);
}

#[test]
fn eval_keeps_relative_precision_near_the_axis_for_sharp_lobes() {
    let mut rng = Rng::new(3);
    for _ in 0..20000 {
        let axis = rng.unit_vector_f32();
        let l = rng.log_uniform(-4.0, 6.0) as f32;
        // Angles from 1e-5 to π, log-uniform.
        let angle = rng.log_uniform(-5.0, 0.5);
        let (t, _) = crate::math::orthonormal_basis(axis);
        let dir = (axis * angle.cos() as f32 + t * angle.sin() as f32).normalize();
        let amplitude = rng.log_uniform(-3.0, 3.0) as f32;
        let sg = Sg::new(axis, l, amplitude);
        let reference = amplitude as f64 * (-(l as f64) * one_minus_dot(d3(dir), d3(axis))).exp();
        let value = sg.eval(dir) as f64;
        if reference > 1e-30 {
            let exponent = (l as f64) * one_minus_dot(d3(dir), d3(axis));
            // Relative error ~ f32 rounding of the exponent, which grows with it.
            let tolerance = 4e-6 * (1.0 + exponent);
            assert!(
                ((value - reference) / reference).abs() < tolerance,
                "λ {l} angle {angle}: {value} vs {reference}"
            );
        }
    }
}

#[test]
fn product_evaluates_to_the_product_and_its_integral_is_the_inner_product() {
    let mut rng = Rng::new(4);
    for _ in 0..5000 {
        let a = Sg::new(
            rng.unit_vector_f32(),
            rng.log_uniform(-4.0, 6.0) as f32,
            rng.log_uniform(-2.0, 2.0) as f32,
        );
        let b = Sg::new(
            rng.unit_vector_f32(),
            rng.log_uniform(-4.0, 6.0) as f32,
            rng.log_uniform(-2.0, 2.0) as f32,
        );
        let p = a.product(&b);
        assert!(p.axis.is_finite() && p.sharpness.is_finite() && p.log_amplitude.is_finite());
        // f64 reference of λm and the exponent, straight from the definition.
        let (x1, x2) = (d3(a.axis), d3(b.axis));
        let (l1, l2) = (a.sharpness as f64, b.sharpness as f64);
        let v = [
            l1 * x1[0] + l2 * x2[0],
            l1 * x1[1] + l2 * x2[1],
            l1 * x1[2] + l2 * x2[2],
        ];
        let lm = dot(v, v).sqrt();
        let log_amp = a.log_amplitude as f64 + b.log_amplitude as f64 + (lm - l1 - l2);
        // f32 rounding of the sharpness and the axes, relative to the larger sharpness.
        let tolerance = 2e-6 * l1.max(l2);
        assert!(
            (p.sharpness as f64 - lm).abs() <= 1e-5 * lm + tolerance,
            "{} vs {lm}",
            p.sharpness
        );
        assert!(
            (p.log_amplitude as f64 - log_amp).abs() <= 1e-5 * (1.0 + log_amp.abs()) + tolerance
        );
        // Inner product: a1 a2 e^{λm − λ1 − λ2} A(λm).
        let inner = a.inner_product(&b) as f64;
        let reference = log_amp.exp() * integral_by_quadrature(lm);
        if reference > 1e-30 {
            let slack = 1e-5 * (1.0 + log_amp.abs()) + tolerance;
            assert!(
                ((inner - reference) / reference).abs() < slack.max(1e-5) * 2.0,
                "{inner} vs {reference}"
            );
        }
        // Pointwise at directions near the product's axis.
        let w = (p.axis + rng.unit_vector_f32() * (0.3 / (1.0 + p.sharpness).sqrt())).normalize();
        let lhs = p.eval(w) as f64;
        let rhs = a.eval(w) as f64 * b.eval(w) as f64;
        if rhs > 1e-30 && lm < 1e4 {
            assert!(((lhs - rhs) / rhs).abs() < 1e-3, "{lhs} vs {rhs}");
        }
    }
}

#[test]
fn products_of_sharp_and_opposite_lobes_stay_finite() {
    for l in [1e-4f32, 1.0, 1e3, 1e6, 1e8] {
        let a = Sg::new(Vec3::Z, l, 1.0);
        let b = Sg::new(-Vec3::Z, l, 1.0);
        let p = a.product(&b);
        assert_eq!(p.sharpness, 0.0);
        assert!(p.axis.is_finite() && (p.axis.length() - 1.0).abs() < 1e-6);
        let expected = -2.0 * l as f64;
        assert!(
            (p.log_amplitude as f64 - expected).abs() <= 1e-6 * expected.abs(),
            "{l}: {}",
            p.log_amplitude
        );
        let inner = a.inner_product(&b) as f64;
        let reference = (-2.0 * l as f64).exp() * 4.0 * PI64;
        assert!(inner.is_finite() && (inner - reference).abs() <= 1e-5 * reference + 1e-38);
        // Equal axes: λm = 2λ and no loss of the amplitude.
        let q = a.product(&a);
        let doubled = (2.0 * l).min(MAX_SHARPNESS);
        assert!(((q.sharpness - doubled) / doubled).abs() < 1e-6 && q.log_amplitude == 0.0);
        // Nearly equal axes at λ = 1e6: the exponent −λ1λ2|ξ1−ξ2|²/(λm+λ1+λ2).
        let c = Sg::new(Vec3::new(1e-3, 0.0, 1.0), l, 1.0);
        let r = a.product(&c);
        let xi = normalize([1e-3, 0.0, 1.0]);
        let e = sub(xi, [0.0, 0.0, 1.0]);
        let l = l as f64;
        let lm = (2.0 * l * l * (1.0 + xi[2])).sqrt();
        let expected = -l * l * dot(e, e) / (lm + 2.0 * l);
        assert!(
            (r.log_amplitude as f64 - expected).abs() <= 1e-5 * expected.abs() + 1e-9,
            "{} vs {expected}",
            r.log_amplitude
        );
    }
    // Huge amplitudes: log space keeps their product's integral finite.
    let big = Sg::new(Vec3::Z, 1e6, f32::MAX);
    assert!(big.product(&big).amplitude() >= 3.4e38);
    assert!(big.inner_product(&big).is_finite());
}

#[test]
fn bad_input_gives_finite_values() {
    let bad = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        -1.0,
        0.0,
        1e-45,
        f32::MAX,
    ];
    let axes = [
        Vec3::ZERO,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(f32::INFINITY, 0.0, 0.0),
        Vec3::new(1e-40, 0.0, 0.0),
        Vec3::splat(f32::MAX),
        Vec3::Z,
    ];
    for &axis in &axes {
        for &l in &bad {
            for &amp in &bad {
                let sg = Sg::new(axis, l, amp);
                assert!(
                    sg.axis.is_finite() && sg.sharpness.is_finite() && sg.log_amplitude.is_finite()
                );
                assert!(sg.sharpness >= 0.0 && sg.sharpness <= MAX_SHARPNESS);
                for &dir in &axes {
                    let v = sg.eval(dir);
                    assert!(v.is_finite() && v >= 0.0);
                }
                let i = sg.integral();
                assert!(i.is_finite() && i >= 0.0);
                let p = sg.product(&Sg::new(Vec3::X, l, amp));
                assert!(p.axis.is_finite() && p.log_amplitude.is_finite());
                let hand = Sg {
                    axis,
                    sharpness: l,
                    log_amplitude: amp,
                };
                let s = hand.sanitized();
                assert!(
                    s.axis.is_finite() && s.sharpness.is_finite() && s.log_amplitude.is_finite()
                );
            }
        }
    }
    assert_eq!(Sg::new(Vec3::Z, 1.0, 0.0).eval(Vec3::Z), 0.0);
    assert_eq!(Sg::new(Vec3::ZERO, 1.0, 1.0), Sg::ZERO);
}
