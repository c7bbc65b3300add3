use super::asg::Asg;
use super::sg::Sg;
use crate::Vec3;
use crate::testing::Rng;
use core::f64::consts::PI as PI64;

/// `∫ f(ω) Ĝ(ω)/a dω` over the ASG's upper hemisphere in the coordinates
/// `(p, q) = (ω·x, ω·y)` of the unit disk, where `max(ω·z, 0) dω = dp dq`: polar
/// midpoint rule, radially refined near the origin (f64).
fn disk_integral(eta_x: f64, eta_y: f64, f: impl Fn([f64; 3]) -> f64) -> f64 {
    let (nr, nphi) = (1500, 256);
    let scale = (1.0 / eta_x.min(eta_y).max(1e-3)).sqrt().min(1.0) * 12.0;
    let rmax = scale.min(1.0);
    let mut total = 0.0;
    for i in 0..nr {
        // r = rmax s², denser near 0.
        let s0 = i as f64 / nr as f64;
        let s1 = (i + 1) as f64 / nr as f64;
        let r = rmax * (0.5 * (s0 + s1)).powi(2);
        let dr = rmax * (s1 * s1 - s0 * s0);
        for j in 0..nphi {
            let phi = (j as f64 + 0.5) / nphi as f64 * 2.0 * PI64;
            let (p, q) = (r * phi.cos(), r * phi.sin());
            let z = (1.0 - p * p - q * q).max(0.0).sqrt();
            total += (-eta_x * p * p - eta_y * q * q).exp() * f([p, q, z]) * r * dr;
        }
    }
    total * 2.0 * PI64 / nphi as f64
}

#[test]
fn integral_approximation_is_the_gaussian_integral_without_its_tail() {
    for &(ex, ey) in &[
        (5.0f32, 5.0f32),
        (10.0, 50.0),
        (100.0, 100.0),
        (1e3, 1e4),
        (1e5, 3e5),
    ] {
        let asg = Asg::new(Vec3::X, Vec3::Z, ex, ey, 2.0);
        let exact = 2.0 * disk_integral(ex as f64, ey as f64, |_| 1.0);
        let approx = asg.integral() as f64;
        // The approximation adds the Gaussian's tail outside the unit disk, ~e^{−min η}.
        let bound = 2.0 * (-(ex.min(ey) as f64)).exp() + 2e-4;
        assert!(
            ((approx - exact) / exact).abs() < bound,
            "{ex} {ey}: {approx} vs {exact}"
        );
    }
    // Small bandwidths: clamped to the bound a π.
    assert!(
        (Asg::new(Vec3::X, Vec3::Z, 1e-3, 1e-3, 1.0).integral() - core::f32::consts::PI).abs()
            < 1e-6
    );
}

#[test]
fn convolution_with_an_sg_matches_quadrature_for_narrow_lobes() {
    let mut rng = Rng::new(31);
    let mut worst = 0.0f64;
    for _ in 0..40 {
        let ex = rng.log_uniform(2.0, 4.0) as f32;
        let ey = rng.log_uniform(2.0, 4.0) as f32;
        let l = rng.log_uniform(2.0, 4.0) as f32;
        let asg = Asg::new(Vec3::X, Vec3::Z, ex, ey, 1.5);
        // SG axis within a few lobe widths of z.
        let spread = 2.0 / (ex.min(ey).min(l)).sqrt();
        let axis = Vec3::new(
            spread * (rng.uniform_f32() - 0.5),
            spread * (rng.uniform_f32() - 0.5),
            1.0,
        )
        .normalize();
        let sg = Sg::new(axis, l, 0.7);
        let value = asg.convolve_sg(&sg) as f64;
        let xi = [axis.x as f64, axis.y as f64, axis.z as f64];
        let exact = 1.5
            * 0.7
            * disk_integral(ex as f64, ey as f64, |w| {
                let e = [w[0] - xi[0], w[1] - xi[1], w[2] - xi[2]];
                (-(l as f64) * 0.5 * (e[0] * e[0] + e[1] * e[1] + e[2] * e[2])).exp()
                    / w[2].max(1e-300)
                    * w[2]
            });
        if exact > 1e-20 {
            let error = ((value - exact) / exact).abs();
            worst = worst.max(error);
            assert!(error < 0.05, "η {ex} {ey} λ {l}: {value} vs {exact}");
        }
    }
    assert!(worst > 0.0);
}

#[test]
fn ggx_fit_matches_the_warped_ndf_sg_near_the_reflection() {
    let n = Vec3::Z;
    for deg in [0.0f32, 30.0, 60.0, 80.0, 87.0] {
        let t = deg.to_radians();
        let view = Vec3::new(t.sin(), 0.0, t.cos());
        let alpha = 0.1;
        let asg = Asg::from_ggx(n, view, alpha);
        let lh = 2.0 / (alpha as f64 * alpha as f64);
        assert!((asg.z - Vec3::new(-t.sin(), 0.0, t.cos())).length() < 1e-6);
        assert!(asg.eta_y >= asg.eta_x * 0.999);
        for (k, step_axis) in [asg.x, asg.y].iter().enumerate() {
            let eta = if k == 0 { asg.eta_x } else { asg.eta_y };
            let step = 0.3 / eta.sqrt();
            let w = (asg.z + *step_axis * step).normalize();
            let h = (w + view).normalize();
            let e = h - n;
            let exact_exponent = -0.5 * lh * (e.length_squared() as f64);
            let asg_exponent = (asg.eval(w) as f64 / w.dot(asg.z) as f64).ln();
            assert!(
                ((asg_exponent - exact_exponent) / exact_exponent).abs() < 0.02,
                "{deg}° axis {k}: {asg_exponent} vs {exact_exponent}"
            );
        }
    }
    assert_eq!(Asg::from_ggx(Vec3::ZERO, Vec3::Z, 0.5), Asg::ZERO);
}

#[test]
fn bad_input_gives_finite_values() {
    let vectors = [
        Vec3::ZERO,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::splat(f32::INFINITY),
        Vec3::Z,
        Vec3::X,
    ];
    let scalars = [f32::NAN, -1.0, 0.0, 1e-30, 1e30, f32::INFINITY];
    for &x in &vectors {
        for &z in &vectors {
            for &e in &scalars {
                let asg = Asg::new(x, z, e, 1.0, e);
                let hand = Asg {
                    x,
                    y: z,
                    z,
                    eta_x: e,
                    eta_y: e,
                    amplitude: e,
                }
                .sanitized();
                for a in [asg, hand] {
                    assert!(a.x.is_finite() && a.y.is_finite() && a.z.is_finite());
                    assert!(a.integral().is_finite() && a.integral() >= 0.0);
                    for &d in &vectors {
                        assert!(a.eval(d).is_finite());
                        let sg = Sg::new(d, e, e);
                        let c = a.convolve_sg(&sg);
                        assert!(c.is_finite() && c >= 0.0, "{a:?} {sg:?}: {c}");
                    }
                }
            }
        }
    }
}

/// Issue 17, 7: the convolution caps the factor `1/√((η_x + ν)(η_y + ν))` at 1 (the bound
/// `∫ G Ĝ ≤ c a π`), which the header did not say. The behaviour, and that the header's
/// documentation of `sphera_asg_convolve_sg` states it.
#[test]
fn convolution_caps_its_normalisation_factor_at_one_as_the_header_says() {
    let (c, a) = (0.7f32, 1.5f32);
    let axis = Vec3::new(0.3, -0.2, 1.0).normalize();
    let (ex, ey, lambda) = (0.1f32, 0.4, 0.2);
    let asg = Asg::new(Vec3::X, Vec3::Z, ex, ey, a);
    let sg = Sg::new(axis, lambda, c);
    let nu = 0.5 * lambda as f64;
    let (sx, sy) = (ex as f64 + nu, ey as f64 + nu);
    assert!(sx * sy < 1.0);
    let (px, py, pz) = (axis.x as f64, axis.y as f64, axis.z as f64);
    let capped = c as f64
        * a as f64
        * core::f64::consts::PI
        * pz
        * (-(ex as f64 * nu / sx) * px * px - (ey as f64 * nu / sy) * py * py).exp();
    let value = asg.convolve_sg(&sg) as f64;
    assert!(
        (value - capped).abs() <= 1e-5 * capped,
        "{value} vs {capped}"
    );
    assert!(value <= (c * a) as f64 * core::f64::consts::PI);
    // The boxed formula without the cap would be 1/√(sx sy) = 3.5 times larger.
    assert!(value * 3.0 < capped / (sx * sy).sqrt());
    let header = include_str!("../../include/sphera.h");
    let end = header.find("sphera_asg_convolve_sg(").expect("declared");
    let doc = &header[header[..end].rfind("/*").expect("documented")..end];
    assert!(
        doc.contains("capped at 1") && doc.contains("most `c a π`"),
        "the header does not say that the factor is capped: {doc}"
    );
}
