use super::sg::{MAX_SHARPNESS, Sg, sg_integral};
use super::shading::*;
use crate::Vec3;
use crate::brdf::ggx::GgxBrdf;
use crate::testing::{Rng, d3, dot, normalize, sub};
use core::f64::consts::PI as PI64;

/// `e^{λ(ω·ξ − 1)}` in f64 with `1 − ω·ξ = |ω − ξ|²/2`.
fn sg64(axis: [f64; 3], l: f64, w: [f64; 3]) -> f64 {
    let e = sub(normalize(w), normalize(axis));
    (-0.5 * l * dot(e, e)).exp()
}

#[test]
fn incoming_radiance_is_the_product_of_eq_7() {
    let mut rng = Rng::new(41);
    for _ in 0..5000 {
        let cv = rng.log_uniform(-2.0, 2.0);
        let lobe = Sg::new(
            rng.unit_vector_f32(),
            rng.log_uniform(-2.0, 3.0) as f32,
            cv as f32,
        );
        let mean = rng.unit_vector_f32() * rng.log_uniform(-2.0, 2.0) as f32;
        let variance = rng.log_uniform(-3.0, 1.0) as f32;
        let l_in = incoming_radiance(&lobe, mean, variance);
        let mu = d3(mean);
        let d2 = dot(mu, mu);
        // The planar Gaussian's per-axis variance s² = σ²/2 (module documentation).
        let s2 = 0.5 * variance as f64;
        let l_sigma = d2 / s2;
        if l_sigma > 1e5 {
            continue;
        }
        for _ in 0..4 {
            // Directions near the product's axis, where it is not negligible.
            let w = (l_in.axis + rng.unit_vector_f32() * (1.0 / (1.0 + l_in.sharpness).sqrt()))
                .normalize();
            let reference = cv / (2.0 * PI64 * s2)
                * sg64(d3(-lobe.axis), lobe.sharpness as f64, d3(w))
                * sg64(mu, l_sigma, d3(w));
            let value = l_in.eval(w) as f64;
            if reference > 1e-20 {
                let slack = 1e-5 * (1.0 + l_sigma + lobe.sharpness as f64);
                assert!(
                    ((value - reference) / reference).abs() < slack,
                    "{value} vs {reference}"
                );
            }
        }
    }
}

#[test]
fn point_light_limit_keeps_the_inverse_square_law() {
    // σ² → 0: ∫ L_in dω → c_v G(−ξ_μ... ) / |μ|² (the lobe at the direction toward the
    // shading point, −ξ_μ, i.e. G(ξ_μ, −ξ_v, λ_v)).
    let lobe = Sg::new(Vec3::new(0.0, 0.0, -1.0), 3.0, 2.0);
    let mean = Vec3::new(0.3, 0.0, 2.0);
    let d2 = mean.length_squared() as f64;
    let expected = 2.0 * sg64([0.0, 0.0, 1.0], 3.0, d3(mean)) / d2;
    for variance in [0.0f32, 1e-30, 1e-12, -1.0, f32::NAN] {
        let l_in = incoming_radiance(&lobe, mean, variance);
        assert!(l_in.sharpness <= MAX_SHARPNESS && l_in.sharpness > 1e6);
        let total = l_in.integral() as f64;
        assert!(
            ((total - expected) / expected).abs() < 1e-3,
            "σ² {variance}: {total} vs {expected}"
        );
    }
    // Just above the clamp the two branches agree.
    let v = (mean.length_squared() / MAX_SHARPNESS) * 1.0001;
    let a = incoming_radiance(&lobe, mean, v).integral();
    let b = incoming_radiance(&lobe, mean, v * 0.9998).integral();
    assert!(((a - b) / a).abs() < 1e-3);
}

#[test]
fn degenerate_vsgls_give_finite_radiance() {
    let lobe = Sg::new(Vec3::Z, 2.0, 1.0);
    // Shading point at the mean: λ_σ = 0, amplitude c_v/(2πs²) with s² = σ²/2 = 0.25.
    let at_mean = incoming_radiance(&lobe, Vec3::ZERO, 0.5);
    assert!((at_mean.amplitude() - 1.0 / (2.0 * core::f32::consts::PI * 0.25)).abs() < 1e-5);
    assert_eq!(at_mean.sharpness, 2.0);
    assert_eq!(incoming_radiance(&lobe, Vec3::ZERO, 0.0), Sg::ZERO);
    let vectors = [
        Vec3::ZERO,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::splat(f32::INFINITY),
        Vec3::splat(1e-38),
        Vec3::splat(3e38),
        Vec3::Z,
    ];
    let scalars = [f32::NAN, -1.0, 0.0, 1e-38, 1e38, f32::INFINITY];
    for &axis in &vectors {
        for &s in &scalars {
            let hand = Sg {
                axis,
                sharpness: s,
                log_amplitude: s,
            };
            for &mean in &vectors {
                for &variance in &scalars {
                    let l_in = incoming_radiance(&hand, mean, variance);
                    assert!(
                        l_in.axis.is_finite()
                            && l_in.sharpness.is_finite()
                            && l_in.log_amplitude.is_finite()
                    );
                    for &n in &vectors {
                        for value in [
                            diffuse_shading_product(&l_in, n, s, s),
                            diffuse_shading_constant_cosine(&l_in, n, s, 1.0),
                            diffuse_shading_sharp_lobe(&l_in, n, 1.0, s),
                            specular_shading(&l_in, n, mean, s, s, 1.0),
                            specular_shading_sg(&l_in, n, mean, s, 0.5, s),
                        ] {
                            assert!(value.is_finite() && value >= 0.0);
                        }
                    }
                }
            }
        }
    }
}

/// `∫ L(ω) max(ω·n, 0)/π dω` for an SG `L` by quadrature in the SG's frame (f64).
fn exact_diffuse(l_in: &Sg, n: Vec3) -> f64 {
    let (t, b) = crate::math::orthonormal_basis(l_in.axis);
    let l = l_in.sharpness as f64;
    let top = (60.0 / l.max(1e-9)).min(2.0);
    let (nt, np) = (4000, 512);
    let mut total = 0.0;
    for i in 0..nt {
        let s = (i as f64 + 0.5) / nt as f64;
        let tt = top * s * s;
        let dt = top * 2.0 * s / nt as f64;
        let sin = (tt * (2.0 - tt)).max(0.0).sqrt();
        for j in 0..np {
            let phi = (j as f64 + 0.5) / np as f64 * 2.0 * PI64;
            let w = [
                (1.0 - tt) * l_in.axis.x as f64
                    + sin * (phi.cos() * t.x as f64 + phi.sin() * b.x as f64),
                (1.0 - tt) * l_in.axis.y as f64
                    + sin * (phi.cos() * t.y as f64 + phi.sin() * b.y as f64),
                (1.0 - tt) * l_in.axis.z as f64
                    + sin * (phi.cos() * t.z as f64 + phi.sin() * b.z as f64),
            ];
            total += (-l * tt).exp() * dot(w, d3(n)).max(0.0) / PI64 * dt;
        }
    }
    total * 2.0 * PI64 / np as f64 * (l_in.log_amplitude as f64).exp()
}

#[test]
fn diffuse_forms_approach_the_exact_integral_for_sharp_lobes() {
    let n = Vec3::Z;
    let axis = Vec3::new(0.6, 0.0, 0.8);
    for (l, bound_constant, bound_sharp) in
        [(1000.0f32, 2e-3, 2e-3), (30.0, 0.06, 0.06), (3.0, 0.6, 0.6)]
    {
        let l_in = Sg::new(axis, l, 1.5);
        let exact = exact_diffuse(&l_in, n);
        let constant = diffuse_shading_constant_cosine(&l_in, n, 1.0, 1.0) as f64;
        let sharp = diffuse_shading_sharp_lobe(&l_in, n, 1.0, 1.0) as f64;
        assert!(
            ((constant - exact) / exact).abs() < bound_constant,
            "λ {l}: {constant} vs {exact}"
        );
        assert!(
            ((sharp - exact) / exact).abs() < bound_sharp,
            "λ {l}: {sharp} vs {exact}"
        );
        // The product form is the inner product with the normalised diffuse SG.
        let product = diffuse_shading_product(&l_in, n, 0.5, 0.5) as f64;
        let reference = 0.25 * l_in.inner_product(&super::lobes::diffuse_lobe_normalized(n)) as f64;
        assert!(((product - reference) / reference).abs() < 1e-5);
    }
    // The constant-cosine form at λ_in = 0: c_in R_d 4 max(ξ·n, 0).
    let flat = Sg::new(Vec3::Z, 0.0, 1.0);
    assert!((diffuse_shading_constant_cosine(&flat, n, 1.0, 1.0) - 4.0).abs() < 1e-5);
    assert!((sg_integral(0.0) - 4.0 * core::f32::consts::PI).abs() < 1e-6);
}

#[test]
fn specular_shading_of_a_delta_like_light_is_the_brdf_at_its_direction() {
    // A very sharp incoming lobe (λ = 1e8, so that the fits' own width, ~η/ν, stays
    // below 1e-4) at direction ω: the exact result is
    // c A(λ) ρ_s(ω_o, ω) cos θ = c A(λ) F D G2 / (4 cos θ_o), and at the reflection
    // direction the fits' D̂ = 1, so both forms must give it.
    let n = Vec3::Z;
    for deg in [0.0f32, 30.0, 60.0, 75.0] {
        for roughness in [0.2f32, 0.5, 0.9] {
            let t = deg.to_radians();
            let view = Vec3::new(t.sin(), 0.0, t.cos());
            let reflected = Vec3::new(-t.sin(), 0.0, t.cos());
            let l_in = Sg::new(reflected, MAX_SHARPNESS, 1.0);
            let ggx = GgxBrdf::new(roughness, Vec3::splat(0.04));
            let exact =
                l_in.integral() as f64 * ggx.eval(view, reflected).x as f64 * reflected.z as f64;
            let asg = specular_shading(&l_in, n, view, roughness, 0.04, 1.0) as f64;
            let sg = specular_shading_sg(&l_in, n, view, roughness, 0.04, 1.0) as f64;
            assert!(
                ((asg - exact) / exact).abs() < 2e-3,
                "{deg}° r {roughness}: ASG {asg} vs {exact}"
            );
            assert!(
                ((sg - exact) / exact).abs() < 2e-3,
                "{deg}° r {roughness}: SG {sg} vs {exact}"
            );
            // Visibility multiplies.
            let half = specular_shading(&l_in, n, view, roughness, 0.04, 0.5) as f64;
            assert!((half - 0.5 * asg).abs() <= 1e-6 * asg);
        }
    }
    // Light from below the horizon, or a view below it: nothing.
    let below = Sg::new(Vec3::new(0.0, 0.6, -0.8), 100.0, 1.0);
    assert_eq!(specular_shading(&below, n, Vec3::Z, 0.5, 0.04, 1.0), 0.0);
    let l_in = Sg::new(Vec3::Z, 100.0, 1.0);
    assert_eq!(
        specular_shading(&l_in, n, Vec3::new(0.0, 0.6, -0.8), 0.5, 0.04, 1.0),
        0.0
    );
}

#[test]
fn ggx_lobe_factor_is_the_brdf_over_the_unnormalised_ndf() {
    let mut rng = Rng::new(43);
    for _ in 0..2000 {
        let mut wo = rng.unit_vector_f32();
        wo.z = wo.z.abs().max(0.05);
        let wo = wo.normalize();
        let mut wi = rng.unit_vector_f32();
        wi.z = wi.z.abs().max(0.05);
        let wi = wi.normalize();
        let roughness = 0.1 + 0.9 * rng.uniform_f32();
        let alpha = roughness * roughness;
        let ggx = GgxBrdf::new(roughness, Vec3::splat(0.04));
        let h = (wo + wi).normalize();
        let d_hat = ggx.d(h) as f64 * PI64 * (alpha as f64).powi(2);
        let expected = ggx.eval(wo, wi).x as f64 * wi.z as f64 / d_hat;
        let c = ggx_lobe_factor(Vec3::Z, wo, wi, alpha, 0.04) as f64;
        assert!(
            ((c - expected) / expected).abs() < 1e-4,
            "{c} vs {expected}"
        );
    }
}

/// Beckmann's Smith `Λ` in f64 from the slope distribution (Walter et al. 2007):
/// `a = cos θ/(α sin θ)`, `Λ = (e^{−a²}/(a√π) − erfc(a))/2`.
fn beckmann_lambda64(alpha: f64, c: f64) -> f64 {
    let a = c / (alpha * (1.0 - c * c).sqrt());
    0.5 * ((-a * a).exp() / (a * PI64.sqrt()) - libm::erfc(a))
}

/// Beckmann's `ρ_s cos θ_i = F D G2/(4 cos θ_o)` in f64 (normal `z`):
/// `D = e^{−tan²θ_h/α²}/(πα² cos⁴θ_h)`, `G2 = 1/(1 + Λ(ω_o) + Λ(ω_i))`, Schlick's `F`.
fn beckmann_cos64(wo: [f64; 3], wi: [f64; 3], alpha: f64, f0: f64) -> f64 {
    if wo[2] <= 0.0 || wi[2] <= 0.0 {
        return 0.0;
    }
    let h = normalize([wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]]);
    let c2 = h[2] * h[2];
    let d = (-(1.0 - c2) / c2 / (alpha * alpha)).exp() / (PI64 * alpha * alpha * c2 * c2);
    let g2 = 1.0 / (1.0 + beckmann_lambda64(alpha, wo[2]) + beckmann_lambda64(alpha, wi[2]));
    let f = f0 + (1.0 - f0) * (1.0 - dot(wo, h)).powi(5);
    f * d * g2 / (4.0 * wo[2])
}

/// Issue 20 (6): `C(ω)` of the Beckmann lobe is Beckmann's `ρ_s cos` over its
/// unnormalised NDF `D̂ = πα² D`, against the f64 BRDF above, and its `Λ` is the f64 one.
#[test]
fn beckmann_lobe_factor_is_the_brdf_over_the_unnormalised_ndf() {
    let mut rng = Rng::new(44);
    for _ in 0..2000 {
        let mut wo = rng.unit_vector_f32();
        wo.z = wo.z.abs().max(0.05);
        let wo = wo.normalize();
        let mut wi = rng.unit_vector_f32();
        wi.z = wi.z.abs().max(0.05);
        let wi = wi.normalize();
        let alpha = (0.1 + 0.9 * rng.uniform()).powi(2);
        let alpha32 = alpha as f32;
        let alpha = alpha32 as f64;
        let (o, i) = (d3(wo), d3(wi));
        let h = normalize([o[0] + i[0], o[1] + i[1], o[2] + i[2]]);
        let c2 = h[2] * h[2];
        let d_hat = (-(1.0 - c2) / c2 / (alpha * alpha)).exp() / (c2 * c2);
        if d_hat < 1e-30 {
            continue; // the ratio of two underflowed values
        }
        let expected = beckmann_cos64(o, i, alpha, 0.04) / d_hat;
        let c = beckmann_lobe_factor(Vec3::Z, wo, wi, alpha32, 0.04) as f64;
        assert!(
            ((c - expected) / expected).abs() < 2e-4,
            "{c} vs {expected}"
        );
    }
    for alpha in [1e-3f32, 0.05, 0.3, 1.0] {
        for c in [1e-4f32, 0.01, 0.1, 0.5, 0.9, 0.999] {
            let exact = beckmann_lambda64(alpha as f64, c as f64);
            let got = beckmann_lambda(alpha, c) as f64;
            assert!(
                (got - exact).abs() <= 1e-4 * exact + 1e-7,
                "α {alpha} cos {c}: {got} vs {exact}"
            );
        }
        assert_eq!(beckmann_lambda(alpha, 1.0), 0.0);
    }
}

/// As for GGX: a very sharp incoming lobe at the reflection direction gives
/// `c A(λ) ρ_s cos θ` of Beckmann's f64 BRDF with both fits (their `D̂ = 1` there).
#[test]
fn beckmann_shading_of_a_delta_like_light_is_the_brdf_at_its_direction() {
    let n = Vec3::Z;
    for deg in [0.0f32, 30.0, 60.0, 75.0] {
        for roughness in [0.2f32, 0.5, 0.9] {
            let t = deg.to_radians();
            let view = Vec3::new(t.sin(), 0.0, t.cos());
            let reflected = Vec3::new(-t.sin(), 0.0, t.cos());
            let l_in = Sg::new(reflected, MAX_SHARPNESS, 1.0);
            let alpha = (roughness * roughness) as f64;
            let exact =
                l_in.integral() as f64 * beckmann_cos64(d3(view), d3(reflected), alpha, 0.04);
            let asg = beckmann_specular_shading(&l_in, n, view, roughness, 0.04, 1.0) as f64;
            let sg = beckmann_specular_shading_sg(&l_in, n, view, roughness, 0.04, 1.0) as f64;
            for (form, value) in [("ASG", asg), ("SG", sg)] {
                assert!(
                    ((value - exact) / exact).abs() < 2e-3,
                    "{deg}° r {roughness}: {form} {value} vs {exact}"
                );
            }
            // The Smith terms differ: Beckmann's G2 is not GGX's.
            let ggx = specular_shading(&l_in, n, view, roughness, 0.04, 1.0) as f64;
            if deg >= 60.0 && roughness >= 0.5 {
                assert!(((ggx - asg) / asg).abs() > 1e-3, "{deg}° r {roughness}");
            }
        }
    }
    let below = Sg::new(Vec3::new(0.0, 0.6, -0.8), 100.0, 1.0);
    assert_eq!(
        beckmann_specular_shading(&below, n, Vec3::Z, 0.5, 0.04, 1.0),
        0.0
    );
    assert_eq!(
        beckmann_specular_shading_sg(&below, n, Vec3::Z, 0.5, 0.04, 1.0),
        0.0
    );
}

/// The linear-space fast path of `incoming_radiance` (`spatial_lobe_linear`): which
/// inputs take it, and its agreement with an f64 evaluation of Eq. 6–7 next to the
/// log-space path's on the same inputs.
#[test]
fn linear_spatial_lobe_agrees_with_f64_and_the_log_space_path() {
    use super::shading::{LINEAR_MAX, LINEAR_MIN, incoming_radiance_paths, spatial_lobe_linear};
    assert_eq!(LINEAR_MIN, 2f32.powi(-60));
    assert_eq!(LINEAR_MAX, 2f32.powi(60));
    // The path: typical VSGLs take it; point lights, clamped sharpness, distances and
    // variances beyond 2^±60 (squared), NaN and infinity do not.
    let m = Vec3::new(0.3, -1.0, 2.0);
    assert!(spatial_lobe_linear(m, 0.02).is_some());
    assert!(spatial_lobe_linear(m * 1e-9, 1e-18).is_some());
    assert!(spatial_lobe_linear(m * 1e8, 1e17).is_some());
    assert!(spatial_lobe_linear(m, 0.0).is_none());
    assert!(spatial_lobe_linear(m, 1e-8).is_none()); // λ_σ = 5.1e8 > MAX_SHARPNESS
    assert!(spatial_lobe_linear(m, m.length_squared() / 1e8 * 1.001).is_some());
    assert!(spatial_lobe_linear(m * 1e10, 1e17).is_none()); // |μ|² > 2^60
    assert!(spatial_lobe_linear(m * 1e-10, 1e-20).is_none()); // |μ|² < 2^-60
    assert!(spatial_lobe_linear(m, 1e-19).is_none()); // s² < 2^-60
    assert!(spatial_lobe_linear(m, 2e18).is_none()); // s² > 2^60
    assert!(spatial_lobe_linear(Vec3::ZERO, 1.0).is_none());
    assert!(spatial_lobe_linear(Vec3::new(f32::NAN, 0.0, 1.0), 1.0).is_none());
    assert!(spatial_lobe_linear(m, f32::NAN).is_none());
    assert!(spatial_lobe_linear(m, f32::INFINITY).is_none());
    let mut rng = Rng::new(3838);
    let (mut worst_fast, mut worst_log) = ([0.0f64; 3], [0.0f64; 3]);
    let mut taken = 0;
    for i in 0..20000 {
        let lobe = Sg::new(
            rng.unit_vector_f32(),
            rng.log_uniform(-2.0, 3.0) as f32,
            rng.log_uniform(-2.0, 2.0) as f32,
        );
        // Most draws as the tracer's; every fourth over a wide range of scales.
        let (mean, variance) = if i % 4 == 0 {
            let scale = rng.log_uniform(-8.0, 8.0);
            (
                rng.unit_vector_f32() * scale as f32,
                (scale * scale * rng.log_uniform(-7.0, 1.0)) as f32,
            )
        } else {
            let d = rng.log_uniform(-1.0, 1.0);
            (
                rng.unit_vector_f32() * d as f32,
                (d * d * rng.log_uniform(-3.0, 0.0)) as f32,
            )
        };
        let fast = incoming_radiance_paths(&lobe, mean, variance, true);
        let log = incoming_radiance_paths(&lobe, mean, variance, false);
        assert_eq!(fast, incoming_radiance(&lobe, mean, variance));
        if spatial_lobe_linear(mean, 0.5 * variance).is_none() {
            assert_eq!(fast, log, "off the fast path: the log-space path's bits");
            continue;
        }
        taken += 1;
        // f64: G(ω, −ξ_v, λ_v) · G(ω, ξ_μ, λ_σ)/(2πs²), the product in the
        // cancellation-free form of `Sg::product`.
        let (mu, xv) = (d3(mean), d3(lobe.axis));
        let (d2, s2) = (dot(mu, mu), 0.5 * variance as f64);
        let (ls, lv) = (d2 / s2, lobe.sharpness as f64);
        let xm = normalize(mu);
        let v = [
            ls * xm[0] - lv * xv[0],
            ls * xm[1] - lv * xv[1],
            ls * xm[2] - lv * xv[2],
        ];
        let lin = dot(v, v).sqrt();
        let sum = [xm[0] + xv[0], xm[1] + xv[1], xm[2] + xv[2]]; // ξ_μ − (−ξ_v)
        let exponent = -ls * lv * dot(sum, sum) / (lin + ls + lv);
        let log_amplitude = lobe.log_amplitude as f64 - (2.0 * PI64).ln() - s2.ln() + exponent;
        if lin < 1e-3 || log_amplitude < -80.0 || lin > 1e7 {
            continue;
        }
        let axis = [v[0] / lin, v[1] / lin, v[2] / lin];
        for (value, worst) in [(fast, &mut worst_fast), (log, &mut worst_log)] {
            let errors = [
                (value.sharpness as f64 - lin).abs() / lin,
                // The log amplitude's error relative to its size, 1 + |ln c_in|.
                (value.log_amplitude as f64 - log_amplitude).abs() / (1.0 + log_amplitude.abs()),
                // The axis' angle, in units of the lobe's width 1/√λ_in.
                dot(sub(d3(value.axis), axis), sub(d3(value.axis), axis)).sqrt() * lin.sqrt(),
            ];
            for (w, e) in worst.iter_mut().zip(errors) {
                *w = w.max(e);
            }
        }
    }
    eprintln!("fast path taken {taken}: worst fast {worst_fast:?}, log space {worst_log:?}");
    assert!(taken > 15000, "{taken}");
    assert!(
        worst_fast.iter().zip(&worst_log).all(|(f, l)| f <= l),
        "{worst_fast:?} vs {worst_log:?}"
    );
}
