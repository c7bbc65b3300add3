//! Tests of sphere-light shading and sampling with the fitted SPTD: the table lookup
//! against the table's cells and under rotation of the view, the real-time shading
//! against the f64 probability that the pivoted uniform distribution lands in the
//! light's cap above the horizon, the MIS estimate of joint SPTD–BRDF sampling against
//! an f64 quadrature of GGX over the cap, its variance against uniform cap sampling, and
//! the pivot phase function restricted to a cap.
//!
//! Hard cases: views at 0°, 45°, 80° and 89.9°, roughness 0.05 to 1, lights in the
//! mirror direction, overhead, straddling the horizon, tiny (1e-6 sr, the uniform
//! fallback) and huge (the shading point inside the sphere).
use super::*;
use crate::brdf::GgxBrdf;
use crate::brdf::pivot_table::PIVOT_TABLE;
use crate::sphere::pivot::transform;
use crate::testing::*;
use glam::Quat;

fn view(degrees: f32) -> Vec3 {
    let (s, c) = degrees.to_radians().sin_cos();
    Vec3::new(s, 0.0, c)
}

/// The mirror direction of `wo` about the normal.
fn mirror(wo: Vec3) -> Vec3 {
    Vec3::new(-wo.x, -wo.y, wo.z)
}

/// Light caps of the hard-case list for a view.
fn lights(wo: Vec3) -> Vec<(&'static str, Vec3, f32)> {
    vec![
        ("mirror, small", mirror(wo) * 4.0, 0.3),
        ("mirror, large", mirror(wo) * 2.0, 1.0),
        ("overhead", Vec3::new(0.1, 0.2, 3.0), 0.5),
        ("straddling the horizon", Vec3::new(-2.0, 1.0, 0.1), 0.6),
        ("tiny", mirror(wo) * 1000.0, 1.0),
        ("inside", Vec3::new(0.0, 0.0, 0.5), 1.0),
    ]
}

#[test]
fn lookup_matches_the_table_at_cells_and_turns_with_the_view() {
    for (i, j) in [(0, 0), (10, 20), (31, 40), (63, 5), (45, 62), (20, 61)] {
        let r = i as f32 / 63.0;
        let t = j as f32 / 63.0;
        let cos = if j == 63 { 1e-4 } else { 1.0 - t * t };
        let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
        let fit = GgxPivot::from_view(wo, r).unwrap();
        let [norm, elevation, albedo] = PIVOT_TABLE[i * 64 + j];
        assert!((fit.pivot.length() - norm).abs() < 2e-4, "({i}, {j})");
        let expected = Vec3::new(elevation.sin(), 0.0, elevation.cos()) * norm;
        assert!(
            (fit.pivot - expected).length() < 2e-3,
            "({i}, {j}): {fit:?}"
        );
        assert!((fit.albedo - albedo).abs() < 1e-4);
        // Rotating the view about the normal rotates the pivot.
        let phi = 1.1f32;
        let rotate = |v: Vec3| {
            Vec3::new(
                v.x * phi.cos() - v.y * phi.sin(),
                v.x * phi.sin() + v.y * phi.cos(),
                v.z,
            )
        };
        let turned = GgxPivot::from_view(rotate(wo), r).unwrap();
        assert!(
            (turned.pivot - rotate(fit.pivot)).length() < 1e-4,
            "({i}, {j})"
        );
    }
    assert!(GgxPivot::from_view(Vec3::new(1.0, 0.0, 0.0), 0.5).is_none());
    assert!(GgxPivot::from_view(Vec3::new(f32::NAN, 0.0, 1.0), 0.5).is_none());
    assert!(GgxPivot::from_view(Vec3::Z, f32::NAN).is_some());
}

#[test]
fn real_time_shading_is_the_pivoted_probability_of_the_clipped_cap() {
    // With F0 = 1 the specular albedo is the fit's albedo, and the shading must equal
    // albedo × P(g(u) ∈ C, g(u)_z > 0) for u uniform on the sphere (Eq. 17–19),
    // estimated here in f64 with Eq. 2 literally.
    let mut rng = Rng::new(3);
    let n = 400_000;
    for degrees in [0.0, 45.0, 80.0] {
        for roughness in [0.1, 0.5, 1.0] {
            let wo = view(degrees);
            let shading = SphereLightShading::new(wo, roughness, Vec3::ONE).unwrap();
            let pivot = d3(shading.fit.pivot);
            for (name, center, radius) in lights(wo) {
                let cap = Cap::from_sphere(center, radius);
                let mut hits = 0u64;
                for _ in 0..n {
                    let w = pivot_transform_f64(uniform_direction_f64(&mut rng), pivot);
                    hits += (w[2] > 0.0 && inside_f64(w, &cap)) as u64;
                }
                let p = hits as f64 / n as f64;
                let expected = shading.fit.albedo as f64 * p;
                let value = shading.eval(&cap);
                let sigma = shading.fit.albedo as f64 * (p * (1.0 - p) / n as f64).sqrt();
                assert!(
                    (value.x as f64 - expected).abs()
                        <= 5.0 * sigma + 1e-5 * shading.fit.albedo as f64,
                    "{degrees}° r {roughness} {name}: {value} vs {expected}"
                );
                assert_eq!(value.x, value.y);
                // The bent cone of an unoccluded point is the upper hemisphere.
                let horizon = Cap::from_axis_cos(Vec3::Z, 0.0);
                assert_eq!(shading.eval_occluded(&cap, &horizon), value);
                // A bent cone away from the light blocks it.
                let away = Cap::from_axis_cos(-cap.axis, 0.999);
                if cap.one_minus_cos < 1.0 {
                    assert_eq!(shading.eval_occluded(&cap, &away), Vec3::ZERO, "{name}");
                }
                // A narrower bent cone never lets more light through.
                let narrow = Cap::from_axis_cos(Vec3::new(0.2, 0.0, 1.0), 0.5);
                assert!(shading.eval_occluded(&cap, &narrow).x <= value.x + 1e-6);
                // The separable baseline (Eq. 21–22): the unoccluded shading for V = H,
                // a fraction of it for a narrower cone, nothing for a cone below the
                // horizon.
                let separable = shading.eval_occluded_separable(&cap, &horizon);
                assert!((separable.x - value.x).abs() <= 1e-6 * value.x, "{name}");
                let fraction = shading.eval_occluded_separable(&cap, &narrow).x;
                assert!((0.0..=value.x * (1.0 + 1e-6)).contains(&fraction), "{name}");
                let below = Cap::from_axis_cos(-Vec3::Z, 0.9);
                assert_eq!(shading.eval_occluded_separable(&cap, &below), Vec3::ZERO);
            }
        }
    }
}

/// A shading prepared with a bent cone (`new_occluded`) evaluates every light as
/// `eval_occluded` with that cone does, bit for bit, over random views, roughnesses, F0,
/// lights (small and large, crossing the horizon, the shading point inside, invalid caps)
/// and bent cones (the hemisphere, narrow, wide, below the horizon, empty, whole sphere,
/// not finite); the separable baseline of an occluded shading still uses `g(H)`, and the
/// bent cone `H` prepares the unoccluded shading itself.
#[test]
fn prepared_bent_cones_shade_as_eval_occluded() {
    let mut rng = Rng::new(38);
    let mut zero = 0;
    let mut lit = 0;
    for i in 0..3000 {
        let wo = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(0.01, 1.0),
        );
        let roughness = rng.range(0.0, 1.0);
        let f0 = Vec3::new(rng.uniform_f32(), rng.uniform_f32(), rng.uniform_f32());
        let cones = [
            Cap::from_axis_cos(Vec3::Z, 0.0),
            Cap::from_axis_cos(
                Vec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(0.0, 1.0),
                ),
                rng.range(-0.5, 0.999),
            ),
            Cap::from_axis_cos(Vec3::new(0.1, 0.0, 1.0), 0.99),
            Cap::from_axis_cos(-Vec3::Z, 0.5),
            Cap::EMPTY,
            Cap::WHOLE_SPHERE,
            Cap {
                axis: Vec3::new(f32::NAN, 0.0, 1.0),
                one_minus_cos: 0.5,
                one_plus_cos: 1.5,
                sin2: 0.75,
            },
        ];
        let visibility = cones[i % cones.len()];
        let (Some(shading), Some(occluded)) = (
            SphereLightShading::new(wo, roughness, f0),
            SphereLightShading::new_occluded(wo, roughness, f0, &visibility),
        ) else {
            panic!("{wo} is above the horizon");
        };
        let distance = 10f32.powf(rng.range(-0.5, 2.0));
        let center = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-0.3, 1.0),
        ) * distance;
        let radius = distance * 10f32.powf(rng.range(-4.0, 0.2));
        let lights = [
            Cap::from_sphere(center, radius),
            Cap::from_axis_cos(Vec3::new(0.0, 0.3, 1.0), rng.range(-0.9, 0.9999)),
            Cap {
                axis: Vec3::new(0.0, 0.0, 2.0),
                one_minus_cos: -1.0,
                one_plus_cos: 3.0,
                sin2: 7.0,
            },
        ];
        for light in lights {
            let expected = shading.eval_occluded(&light, &visibility);
            let got = occluded.eval(&light);
            assert_eq!(
                got.to_array().map(f32::to_bits),
                expected.to_array().map(f32::to_bits),
                "{i}: {wo} {roughness} {visibility:?} {light:?}"
            );
            assert_eq!(
                occluded.eval_occluded_separable(&light, &visibility),
                shading.eval_occluded_separable(&light, &visibility)
            );
            zero += (got == Vec3::ZERO) as u32;
            lit += (got.x > 0.0) as u32;
        }
    }
    // Both outcomes occur (the draws are not all blocked or all lit).
    assert!(zero > 1000 && lit > 1000, "{zero} {lit}");
    let wo = Vec3::new(0.3, 0.1, 0.8);
    let horizon = Cap::from_axis_cos(Vec3::Z, 0.0);
    assert_eq!(
        SphereLightShading::new_occluded(wo, 0.4, Vec3::ONE, &horizon),
        SphereLightShading::new(wo, 0.4, Vec3::ONE)
    );
    assert!(SphereLightShading::new_occluded(-wo, 0.4, Vec3::ONE, &horizon).is_none());
}

/// `∫_C f cos θ dω` (F = 1) by the midpoint rule over the cap in f64.
fn reference_integral(wo: Vec3, roughness: f32, cap: &Cap) -> f64 {
    let wo64 = d3(wo);
    integrate_over_cap_f64(cap, 400, |w| {
        ggx_f64(wo64, w, roughness as f64, 1.0) * w[2].max(0.0)
    })
}

/// One MIS estimate of `∫_C f cos` with the balance heuristic between a light sampler
/// (given as sample and pdf functions) and GGX VNDF sampling.
fn mis_estimate(
    brdf: &GgxBrdf,
    wo: Vec3,
    cap: &Cap,
    light_sample: impl Fn([f32; 2]) -> Sample,
    light_pdf: impl Fn(Vec3) -> f32,
    u: [f32; 4],
) -> f64 {
    let mut sum = 0.0;
    let s = light_sample([u[0], u[1]]);
    if s.pdf > 0.0 {
        let f = brdf.eval_without_fresnel(wo, s.dir) as f64 * s.dir.z.max(0.0) as f64;
        sum += f / (s.pdf as f64 + brdf.pdf(wo, s.dir) as f64);
    }
    let b = brdf.sample(wo, [u[2], u[3]]);
    if b.pdf > 0.0 && cap.contains(b.dir) {
        let f = brdf.eval_without_fresnel(wo, b.dir) as f64 * b.dir.z.max(0.0) as f64;
        sum += f / (b.pdf as f64 + light_pdf(b.dir) as f64);
    }
    sum
}

#[test]
fn joint_sptd_and_brdf_sampling_is_unbiased_and_beats_uniform_cap_sampling_in_the_highlight() {
    let mut rng = Rng::new(9);
    for degrees in [0.0, 45.0, 80.0] {
        for roughness in [0.2, 0.5, 1.0] {
            let wo = view(degrees);
            let brdf = GgxBrdf::new(roughness, Vec3::ONE);
            for (name, center, radius) in lights(wo) {
                let cap = Cap::from_sphere(center, radius);
                let sampler = SphereLightSampler::new(center, radius, wo, roughness).unwrap();
                let pivoted = pivot_cap(&cap, GgxPivot::from_view(wo, roughness).unwrap().pivot);
                assert_eq!(
                    sampler.uses_sptd(),
                    pivoted.solid_angle() >= MIN_PIVOTED_SOLID_ANGLE
                );
                let reference = reference_integral(wo, roughness, &cap);
                let (mut joint, mut classic) = (Estimate::default(), Estimate::default());
                for _ in 0..40_000 {
                    let u = [
                        rng.uniform_f32(),
                        rng.uniform_f32(),
                        rng.uniform_f32(),
                        rng.uniform_f32(),
                    ];
                    joint.add(mis_estimate(
                        &brdf,
                        wo,
                        &cap,
                        |u| sampler.sample(u),
                        |d| sampler.pdf(d),
                        u,
                    ));
                    classic.add(mis_estimate(
                        &brdf,
                        wo,
                        &cap,
                        |u| cap.sample_uniform(u),
                        |d| cap.pdf(d),
                        u,
                    ));
                }
                let what = format!("{degrees}° r {roughness} {name}");
                // The quadrature's own error: 0.5% of the value.
                joint.assert_mean_is(reference, 5.0, 5e-3, &what);
                classic.assert_mean_is(reference, 5.0, 5e-3, &what);
                if name == "mirror, large" && roughness <= 0.5 && degrees < 60.0 {
                    // Measured: 0.2-0.35× at r = 0.2, 0.65× at r = 0.5. At 80° the
                    // fitted SPTD misses GGX's elongated grazing lobe (the paper's Fig.
                    // 7 and Section 5.3) and the variance is 1.24× that of uniform cap
                    // sampling at r = 0.2: not asserted there.
                    let bound = if roughness < 0.3 { 0.5 } else { 0.8 };
                    assert!(
                        joint.variance() < bound * classic.variance(),
                        "{what}: variance {} vs {}",
                        joint.variance(),
                        classic.variance()
                    );
                }
            }
        }
    }
}

#[test]
fn small_pivoted_caps_fall_back_to_uniform_cap_sampling() {
    // A tiny light away from the highlight: its pivoted cap is smaller still.
    let wo = view(60.0);
    let center = Vec3::new(0.5, 0.2, 0.3) * 1000.0;
    let sampler = SphereLightSampler::new(center, 1.0, wo, 0.2).unwrap();
    assert!(!sampler.uses_sptd());
    let cap = Cap::from_sphere(center, 1.0);
    let s = sampler.sample([0.3, 0.7]);
    assert!(cap.contains(s.dir));
    assert_eq!(s.pdf, cap.pdf(s.dir));
    assert_eq!(sampler.pdf(s.dir), s.pdf);
    // The same light in the mirror direction is pivoted.
    let sampler = SphereLightSampler::new(mirror(wo) * 1000.0, 1.0, wo, 0.2).unwrap();
    assert!(sampler.uses_sptd());
}

#[test]
fn pivot_phase_in_a_cap_has_zero_variance_for_an_unoccluded_light() {
    let mut rng = Rng::new(21);
    let wo = Vec3::new(0.3, -0.2, 0.9).normalize();
    for g in [-0.7, 0.0, 0.5, 0.9, 0.99] {
        for (center, radius) in [
            (Vec3::new(1.0, 2.0, 3.0), 0.5),
            (wo * 10.0, 1.0),
            (Vec3::new(0.0, 0.0, -3.0), 2.9),
        ] {
            let cap = Cap::from_sphere(center, radius);
            let prepared = super::super::phase::pivot_phase_in_cap(wo, g, &cap).unwrap();
            // ∫_C f_pivot against the f64 probability that the pivoted uniform lands in C.
            let n = 400_000;
            let pivot = d3(wo * g);
            let hits = (0..n)
                .filter(|_| {
                    inside_f64(
                        pivot_transform_f64(uniform_direction_f64(&mut rng), pivot),
                        &cap,
                    )
                })
                .count();
            let p = hits as f64 / n as f64;
            let sigma = (p * (1.0 - p) / n as f64).sqrt();
            assert!(
                (prepared.integral as f64 - p).abs() <= 5.0 * sigma + 1e-5,
                "g {g}: {} vs {p}",
                prepared.integral
            );
            for _ in 0..2000 {
                let s = prepared.sample([rng.uniform_f32(), rng.uniform_f32()]);
                if s.pdf == 0.0 {
                    continue;
                }
                // Eq. 25 in f64 with 1 + g² − 2gμ = (1 − g)² + g|ω − ω_o|² (μ from the f32
                // dot product would cancel near the forward peak).
                let (w, o, g64) = (d3(s.dir), d3(wo), g as f64);
                let e = sub(w, o);
                let den = (1.0 - g64) * (1.0 - g64) + g64 * dot(e, e);
                let f = ((1.0 - g64 * g64) / den).powi(2) / (4.0 * core::f64::consts::PI);
                let ratio = (f / s.pdf as f64) as f32;
                assert!(
                    (ratio - prepared.integral).abs() <= 2e-3 * prepared.integral,
                    "g {g}: f/pdf {ratio} vs ∫ {}",
                    prepared.integral
                );
            }
        }
    }
    assert!(super::super::phase::pivot_phase_in_cap(Vec3::ZERO, 0.5, &Cap::WHOLE_SPHERE).is_none());
}

#[test]
fn bad_input_gives_none_or_finite_values() {
    assert!(SphereLightSampler::new(Vec3::splat(f32::NAN), 1.0, Vec3::Z, 0.5).is_none());
    assert!(SphereLightSampler::new(Vec3::Z * 3.0, -1.0, Vec3::Z, 0.5).is_none());
    assert!(SphereLightSampler::new(Vec3::Z * 3.0, 1.0, -Vec3::Z, 0.5).is_none());
    assert!(SphereLightShading::new(Vec3::new(0.0, 0.0, f32::INFINITY), 0.5, Vec3::ONE).is_none());
    let shading = SphereLightShading::new(Vec3::Z, f32::NAN, Vec3::splat(f32::NAN)).unwrap();
    let nan_cap = Cap {
        axis: Vec3::splat(f32::NAN),
        ..Cap::WHOLE_SPHERE
    };
    assert_eq!(shading.eval(&nan_cap), Vec3::ZERO);
    assert!(shading.eval(&Cap::WHOLE_SPHERE).is_finite());
    let sampler =
        SphereLightSampler::new(Vec3::new(0.0, 0.5, 2.0), 0.3, Vec3::new(0.5, 0.0, 0.5), 0.0)
            .unwrap();
    for u in [[f32::NAN, 0.2], [2.0, -1.0], [1.0, 1.0]] {
        let s = sampler.sample(u);
        assert!(s.dir.is_finite() && s.pdf.is_finite(), "{u:?}: {s:?}");
    }
    assert_eq!(sampler.pdf(Vec3::splat(f32::NAN)), 0.0);
}

/// Found by fuzzing: where the sampler falls back to uniform cap sampling, `u` next to
/// 1 put the direction on the cap's rim and `pdf(dir)` said 0. Now every sample's pdf is
/// `pdf(sample.dir)` bit for bit, for both paths, and few samples are dropped.
#[test]
fn sample_pdf_is_the_pdf_of_the_sampled_direction() {
    let mut rng = Rng::new(91);
    let (mut drawn, mut dropped, mut fallbacks) = (0u32, 0u32, 0u32);
    let extremes = [0.0, 0.5, 1.0 - f32::EPSILON / 2.0];
    for _ in 0..400 {
        let distance = 10f32.powf(3.0 * rng.uniform_f32());
        let center = rng.unit_vector_f32() * distance;
        let radius = distance * 10f32.powf(-3.0 * rng.uniform_f32()) * 0.99;
        let theta = 1.5 * rng.uniform_f32();
        let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
        let Some(sampler) = SphereLightSampler::new(center, radius, wo, rng.uniform_f32()) else {
            continue;
        };
        fallbacks += u32::from(!sampler.uses_sptd());
        let mut us: std::vec::Vec<[f32; 2]> = (0..20)
            .map(|_| [rng.uniform_f32(), rng.uniform_f32()])
            .collect();
        for a in extremes {
            for b in extremes {
                us.push([a, b]);
            }
        }
        for (k, u) in us.into_iter().enumerate() {
            let s = sampler.sample(u);
            if s.pdf == 0.0 {
                // Only rounding at the rim drops a sample: counted for random `u`
                // (the extremes put half of their samples on the rim).
                dropped += u32::from(k < 20);
                continue;
            }
            drawn += u32::from(k < 20);
            assert_eq!(
                sampler.pdf(s.dir).to_bits(),
                s.pdf.to_bits(),
                "{center:?} {radius} {u:?}"
            );
        }
    }
    // (Lights wholly below the horizon have no sampler since issue 20, 1: about half.)
    assert!(fallbacks > 20 && drawn > 4000, "{fallbacks} {drawn}");
    assert!(
        (dropped as f64) < 1e-3 * drawn as f64,
        "{dropped} of {drawn}"
    );
}

/// Issue 16 (7): no padding in the sampler (a `bool` field left three bytes that C
/// callers copying the struct read uninitialised): its size is the sum of its fields'.
#[test]
fn the_sphere_light_sampler_has_no_padding() {
    let sampler = SphereLightSampler::EMPTY;
    assert_eq!(
        core::mem::size_of::<SphereLightSampler>(),
        core::mem::size_of_val(&sampler.sptd)
            + core::mem::size_of_val(&sampler.clipped_region)
            + core::mem::size_of_val(&sampler.light)
            + core::mem::size_of_val(&sampler.pivot)
            + core::mem::size_of_val(&sampler.pivot_numerators)
            + core::mem::size_of_val(&sampler.uses_sptd)
            + core::mem::size_of_val(&sampler.clipped)
    );
}

/// Issue 17 (6): at a grazing view (cos θo = 0.025, r = 0.074, |r_p| = 0.996) a light
/// of 0.31 rad around the pivot's direction has an image of 3.116 rad whose hole is
/// `1 + cos ψ' = 3.3e-4`; stored as `1 − cos ψ'` near 2 it kept only `ulp(2)` of the
/// hole (up to 3.6e-4 of it). A bent cone that lets through a sliver of the light, 0.03
/// to 0.2 rad deep, has an image that covers the hole and a thin ring around it, so the
/// shading is `Ω(g(V)) − 2π h` and inherits that error, amplified by the ring's
/// thinness. Lights of 200 sizes (every rounding of the hole), bent cones around the
/// normal and tilted away from the light; the reference is the f64 image and
/// intersection of the same f32 inputs (`testing::pivot_image_f64`,
/// `testing::cap_intersection_f64`).
///
/// Worst relative errors by reach (0.03, 0.1, 0.2 rad), measured: cones around the
/// normal 2.7e-3, 5.4e-4, 1.1e-4 before the fix, 1.2e-5, 9.9e-6, 9.5e-6 after; tilted
/// cones 2.9e-3, 6.1e-4, 1.5e-4 before, 2.8e-4, 8.7e-5, 4.9e-5 after, where what is
/// left is the cone's own image in f32 (its `1 − cos` 2–4e-5 and its axis 3e-7 rad off,
/// from image points near the pivot's direction that `g` computes to an absolute
/// `1e-7`), which the ring's thinness amplifies as it does the hole's error.
#[test]
fn occlusion_of_a_light_whose_image_is_nearly_the_whole_sphere() {
    let cos_o = 0.025f32;
    let wo = Vec3::new((1.0 - cos_o * cos_o).sqrt(), 0.0, cos_o);
    let shading = SphereLightShading::new(wo, 0.074, Vec3::ONE).unwrap();
    let fit = shading.fit;
    assert!((fit.pivot.length() - 0.996).abs() < 1e-3);
    let pivot = d3(fit.pivot);
    let direction = fit.pivot.normalize();
    const REACHES: [f32; 3] = [0.03, 0.1, 0.2];
    // Bounds by reach: cones around the normal, tilted cones.
    const AROUND_THE_NORMAL: [f64; 3] = [2.5e-5, 2e-5, 2e-5];
    const TILTED: [f64; 3] = [4e-4, 1.3e-4, 7e-5];
    let mut worst = [[0.0f64; 3]; 2];
    for k in 0..200 {
        let light = Cap::from_sphere(direction * 10.0, 3.079 + 2e-5 * k as f32);
        let light_image = pivot_image_f64(d3(light.axis), light.one_minus_cos as f64, pivot);
        let width = 2.0
            * (0.5 * light_image.1)
                .sqrt()
                .atan2((0.5 * light_image.2).sqrt());
        assert!((width - 3.116).abs() < 1e-3, "{light_image:?}");
        assert!((light_image.2 - 3.3e-4).abs() < 1e-5, "{light_image:?}");
        for tilt in [0.0f32, 0.3, 0.6, 1.0] {
            let axis = Vec3::new(tilt.sin(), 0.0, tilt.cos());
            for (r, reach) in REACHES.into_iter().enumerate() {
                let half_angle = direction.dot(axis).acos() - light.half_angle() + reach;
                let cone = Cap::from_axis_cos(axis, half_angle.cos());
                let cone_image = pivot_image_f64(d3(cone.axis), cone.one_minus_cos as f64, pivot);
                let expected = fit.albedo as f64 * cap_intersection_f64(light_image, cone_image)
                    / (4.0 * core::f64::consts::PI);
                let value = shading.eval_occluded(&light, &cone).x as f64;
                let error = (value - expected).abs() / expected;
                let (kind, bound) = if tilt == 0.0 {
                    (0, AROUND_THE_NORMAL[r])
                } else {
                    (1, TILTED[r])
                };
                worst[kind][r] = worst[kind][r].max(error);
                assert!(
                    error < bound,
                    "light {light:?} cone {cone:?}: {value:e} vs {expected:e} ({error:e})"
                );
            }
        }
    }
    println!(
        "worst relative errors by reach {REACHES:?}: around the normal {:?}, tilted {:?}",
        worst[0], worst[1]
    );
}

/// Shadow leaking of the separable approximation (Eq. 21, the paper's Fig. 11 d) against
/// the triple product of Eq. 23, with the f64 reference `∫_{C ∩ V} f cos θ dω` by the
/// midpoint rule: a bent cone around the mirror direction that holds most of the lobe,
/// and a light just outside it, so that the exact value is 0. Eq. 23 gives 0; the
/// separable form gives most of the unoccluded shading. With the light inside the cone
/// both agree with the reference to the fit's error.
#[test]
fn separable_occlusion_leaks_light_that_the_triple_product_blocks() {
    let wo = view(30.0);
    let roughness = 0.5;
    let shading = SphereLightShading::new(wo, roughness, Vec3::ONE).unwrap();
    let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
    // A cone of half-angle 50° about the mirror direction; a light of half-angle 5.7°
    // whose centre is 62° from the mirror direction (6° outside the cone's edge).
    let cone = Cap::from_axis_cos(mirror, 50f32.to_radians().cos());
    let outside = Quat::from_rotation_y(62f32.to_radians()) * mirror;
    let light = Cap::from_sphere(outside * 5.0, 0.5);
    let exact = integrate_over_cap_f64(&light, 200, |w| {
        if inside_f64(w, &cone) {
            ggx_f64(d3(wo), w, roughness as f64, 1.0) * w[2].max(0.0)
        } else {
            0.0
        }
    });
    assert_eq!(exact, 0.0);
    assert_eq!(shading.eval_occluded(&light, &cone), Vec3::ZERO);
    let leaked = shading.eval_occluded_separable(&light, &cone).x;
    let open = shading.eval(&light).x;
    assert!(open > 0.0 && leaked > 0.5 * open, "{leaked} of {open}");
    // The light inside the cone: both near the reference (the SPTD fit's error, a few
    // percent at this view and roughness), the triple product closer.
    let light = Cap::from_sphere(mirror * 5.0, 0.5);
    let reference = integrate_over_cap_f64(&light, 200, |w| {
        if inside_f64(w, &cone) {
            ggx_f64(d3(wo), w, roughness as f64, 1.0) * w[2].max(0.0)
        } else {
            0.0
        }
    });
    let triple = shading.eval_occluded(&light, &cone).x as f64;
    let separable = shading.eval_occluded_separable(&light, &cone).x as f64;
    let (e_triple, e_separable) = (
        (triple - reference).abs() / reference,
        (separable - reference).abs() / reference,
    );
    // Measured: 0.19% for Eq. 23 (the fit's error), 13% for Eq. 21 (the lobe's part
    // outside the cone is taken off a light that lies wholly inside it); leaked 87%.
    assert!(e_triple < 0.01, "{triple} vs {reference}");
    assert!(e_separable > 0.05, "{separable} vs {reference}");
}

/// Issue 20 (1): a light whose cap crosses the horizon is sampled in `C ∩ H` only (the
/// SPTD over the intersection of the images `g(C) ∩ g(H)`), so that no sample is wasted
/// below the horizon: every sample lies above it, `pdf(sample.dir) == sample.pdf`, the
/// MIS estimate with GGX sampling matches the f64 reference of `∫_{C ∩ H} f cos`, and
/// its variance is below that of the SPTD over the whole cap, whose samples below the
/// horizon count for nothing.
#[test]
fn a_light_across_the_horizon_is_sampled_above_it_only() {
    let mut rng = Rng::new(31);
    for (degrees, roughness) in [(30.0, 0.5), (60.0, 0.3), (0.0, 0.8)] {
        let wo = view(degrees);
        let brdf = GgxBrdf::new(roughness, Vec3::ONE);
        let pivot = GgxPivot::from_view(wo, roughness).unwrap().pivot;
        let m = mirror(wo);
        let low = Vec3::new(m.x, m.y, 0.0).normalize_or(Vec3::X);
        for (name, center, radius) in [
            ("just above", low * 2.0 + Vec3::Z * 0.3, 1.0f32),
            ("centre below", low * 2.0 - Vec3::Z * 0.3, 1.0),
            ("huge", low * 1.5 + Vec3::Z * 0.2, 1.4),
        ] {
            let what = format!("{degrees}° r {roughness} {name}");
            let cap = Cap::from_sphere(center, radius);
            let sampler = SphereLightSampler::new(center, radius, wo, roughness).unwrap();
            assert!(sampler.is_clipped(), "{what}");
            let whole = SptdInCap::new(&Sptd::uniform(pivot), &cap).unwrap();
            let reference = reference_integral(wo, roughness, &cap);
            let (mut clipped, mut unclipped) = (Estimate::default(), Estimate::default());
            let mut below = 0u32;
            for _ in 0..40_000 {
                let u: [f32; 4] = core::array::from_fn(|_| rng.uniform_f32());
                let s = sampler.sample([u[0], u[1]]);
                if s.pdf > 0.0 {
                    assert!(s.dir.z >= 0.0 && cap.contains(s.dir), "{what}: {s:?}");
                    assert_eq!(sampler.pdf(s.dir).to_bits(), s.pdf.to_bits(), "{what}");
                }
                below += u32::from(whole.sample([u[0], u[1]]).dir.z < 0.0);
                clipped.add(mis_estimate(
                    &brdf,
                    wo,
                    &cap,
                    |u| sampler.sample(u),
                    |d| sampler.pdf(d),
                    u,
                ));
                unclipped.add(mis_estimate(
                    &brdf,
                    wo,
                    &cap,
                    |u| whole.sample(u),
                    |d| whole.pdf(d),
                    u,
                ));
            }
            clipped.assert_mean_is(reference, 5.0, 5e-3, &what);
            unclipped.assert_mean_is(reference, 5.0, 5e-3, &what);
            println!(
                "{what}: {below} of 40000 whole-cap samples below the horizon; variance {:.3e} (C ∩ H) vs {:.3e} (C)",
                clipped.variance(),
                unclipped.variance()
            );
            assert!(below > 0, "{what}: the whole cap's SPTD wastes no sample");
            assert!(
                clipped.variance() <= 1.02 * unclipped.variance(),
                "{what}: {} vs {}",
                clipped.variance(),
                unclipped.variance()
            );
        }
    }
}

/// The sphere light sampler, its SPTD in a cap and its cap intersection are prepared in
/// place: whatever the struct held before (NaN words, another prepared light, the empty
/// value), the words written are the same, and a failed prepare leaves the empty value.
/// Lights above, across and below the horizon, views below it, bad radii.
#[test]
fn prepares_in_place_write_every_word() {
    let mut rng = Rng::new(211);
    let mut previous = SphereLightSampler::EMPTY;
    let (mut above, mut clipped, mut failed) = (0, 0, 0);
    for i in 0..4000 {
        let center = rng.unit_vector_f32() * rng.log_uniform(0.0, 1.0) as f32;
        let radius = if i % 101 == 0 {
            -1.0
        } else {
            rng.log_uniform(-2.0, 0.0) as f32
        };
        let mut wo = rng.unit_vector_f32();
        wo.z = if i % 37 == 0 { -wo.z.abs() } else { wo.z.abs() };
        let roughness = rng.uniform_f32();
        let mut written = Vec::new();
        for start in [
            nan_filled(SphereLightSampler::EMPTY),
            previous,
            SphereLightSampler::EMPTY,
        ] {
            let mut sampler = start;
            let ok = sampler.prepare(center, radius, wo, roughness);
            if !ok {
                assert_eq!(words(&sampler), words(&SphereLightSampler::EMPTY), "{i}");
            }
            written.push((ok, words(&sampler).to_vec()));
            previous = sampler;
        }
        assert!(written.windows(2).all(|w| w[0] == w[1]), "{i}");
        // `prepare_with_fit` of the view's fit writes `prepare`'s words, from any start;
        // where the view has no fit, its zero pivot prepares a sampler (or fails as the
        // cap does), and `prepare` fails.
        let fit = GgxPivot::from_view(wo, roughness);
        for start in [nan_filled(SphereLightSampler::EMPTY), previous] {
            let mut sampler = start;
            let zero = GgxPivot {
                pivot: Vec3::ZERO,
                albedo: 0.0,
            };
            let ok = sampler.prepare_with_fit(center, radius, fit.as_ref().unwrap_or(&zero));
            if fit.is_some() {
                assert_eq!((ok, words(&sampler).to_vec()), written[0], "{i}");
            } else if !ok {
                assert_eq!(words(&sampler), words(&SphereLightSampler::EMPTY), "{i}");
            }
        }
        match (written[0].0, previous.is_clipped()) {
            (false, _) => failed += 1,
            (true, false) => above += 1,
            (true, true) => clipped += 1,
        }
        // The SPTD in the light's cap and the cap's intersection with the horizon.
        let cap = Cap::from_sphere(center, radius);
        let sptd = Sptd::uniform(rng.unit_vector_f32() * rng.uniform_f32() * 0.9);
        let horizon = Cap::from_axis_one_minus_cos(Vec3::Z, 1.0);
        let mut in_cap = [nan_filled(SptdInCap::EMPTY), SptdInCap::EMPTY];
        let mut region = [nan_filled(CapIntersection::EMPTY), CapIntersection::EMPTY];
        for k in 0..2 {
            if !in_cap[k].prepare(&sptd, &cap) {
                assert_eq!(words(&in_cap[k]), words(&SptdInCap::EMPTY), "{i}");
            }
            if !region[k].prepare(&cap, &horizon) {
                assert_eq!(words(&region[k]), words(&CapIntersection::EMPTY), "{i}");
            }
        }
        assert_eq!(words(&in_cap[0]), words(&in_cap[1]), "{i}");
        assert_eq!(words(&region[0]), words(&region[1]), "{i}");
    }
    assert!(
        above > 500 && clipped > 200 && failed > 50,
        "{above} {clipped} {failed}"
    );
}

/// The clipped sampler's constant `H` is the cap that `Cap::from_axis_one_minus_cos`
/// builds for the upper hemisphere, bit for bit, and valid as it stands (`sanitized`
/// returns it unchanged), so that its image is the one the built cap had.
#[test]
fn the_upper_hemisphere_constant_is_the_built_cap() {
    let built = Cap::from_axis_one_minus_cos(Vec3::Z, 1.0);
    let constant = super::UPPER_HEMISPHERE;
    let bits = |c: &Cap| {
        (
            c.axis.to_array().map(f32::to_bits),
            c.one_minus_cos.to_bits(),
            c.one_plus_cos.to_bits(),
            c.sin2.to_bits(),
        )
    };
    assert_eq!(bits(&constant), bits(&built));
    assert_eq!(bits(&constant.sanitized()), bits(&constant));
}

/// The sampler prepares the SPTD and the clipped region from caps it does not sanitize
/// again (`SptdInCap::prepare_sanitized`, `CapIntersection::prepare_sanitized`): the
/// light's sanitized cap, the constant `H` and the images of both by `pivot_cap_fast`.
/// Those images are valid caps as they stand (`sanitized` returns them bit for bit), so
/// the preparations are those of `prepare`, which sanitizes: over sphere lights as the
/// light bench draws them (above and across the horizon) with the fitted pivots, and
/// random caps of every size with random pivots up to the table's largest.
#[test]
fn the_sampler_s_pivoted_images_are_valid_caps() {
    let mut rng = Rng::new(1807);
    let horizon = super::UPPER_HEMISPHERE;
    let (mut images, mut clipped) = (0, 0);
    for i in 0..20_000 {
        let (light, pivot) = if i % 2 == 0 {
            let distance = rng.log_uniform(0.0, 4f64.log10()) as f32;
            let sin2 = 0.06 + 0.38 * rng.uniform_f32();
            let center = rng.unit_vector_f32();
            let center = Vec3::new(center.x, center.y, center.z.abs());
            let cos_o = 0.1 + 0.9 * rng.uniform_f32();
            let phi = core::f32::consts::TAU * rng.uniform_f32();
            let sin_o = (1.0 - cos_o * cos_o).sqrt();
            let wo = Vec3::new(sin_o * phi.cos(), sin_o * phi.sin(), cos_o);
            let roughness = 0.1 + 0.8 * rng.uniform_f32();
            (
                Cap::from_sphere(center * distance, distance * sin2.sqrt()),
                GgxPivot::from_view(wo, roughness).unwrap().pivot,
            )
        } else {
            (
                Cap::from_axis_one_minus_cos(rng.unit_vector_f32(), 2.0 * rng.uniform_f32()),
                rng.unit_vector_f32() * (0.99997 * rng.uniform_f32()),
            )
        };
        let light = light.sanitized();
        for cap in [light, horizon] {
            let (image, _) = pivot_cap_fast(&cap, pivot);
            images += 1;
            assert_eq!(image.sanitized(), image, "{cap:?} {pivot:?}");
            assert_eq!(
                image.sanitized().axis.to_array().map(f32::to_bits),
                image.axis.to_array().map(f32::to_bits)
            );
        }
        let (a, b) = (
            pivot_cap_fast(&light, pivot).0,
            pivot_cap_fast(&horizon, pivot).0,
        );
        let mut direct = CapIntersection::EMPTY;
        let prepared = direct.prepare_sanitized(&a, &b);
        assert_eq!(CapIntersection::new(&a, &b), prepared.then_some(direct));
        clipped += prepared as u32;
        let mut sptd = SptdInCap::EMPTY;
        let prepared = sptd.prepare_sanitized(&Sptd::uniform(pivot), &light);
        assert_eq!(
            SptdInCap::new(&Sptd::uniform(pivot), &light),
            prepared.then_some(sptd)
        );
    }
    assert!(images == 40_000 && clipped > 5_000, "{images} {clipped}");
}

/// `eval` and `eval_occluded` read a valid light where it is and send a light that is not
/// valid as it stands to the cold path, which sanitizes it first: pinned here which caps
/// take which path (every constructor's cap is valid; a hand-made cap with a scaled axis,
/// a stale `one_plus_cos` or `sin2`, a side out of range or a NaN is not), and that both
/// give `eval(&light.sanitized())` bit for bit, over random views, roughnesses and lights.
#[test]
fn shading_of_a_hand_made_light_is_that_of_its_sanitized_cap() {
    let mut rng = Rng::new(1805);
    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
    let bent = Cap::from_axis_one_minus_cos(Vec3::new(0.3, -0.2, 0.9), 0.6);
    for _ in 0..2_000 {
        let wo = Vec3::new(
            rng.uniform_f32() - 0.5,
            rng.uniform_f32() - 0.5,
            0.05 + rng.uniform_f32(),
        );
        let shading = SphereLightShading::new(wo, rng.uniform_f32(), Vec3::splat(0.04)).unwrap();
        let direction = Vec3::new(
            rng.uniform_f32() - 0.5,
            rng.uniform_f32() - 0.5,
            rng.uniform_f32() - 0.3,
        );
        let distance = 1.0 + 4.0 * rng.uniform_f32();
        let light = Cap::from_sphere(direction * distance, rng.uniform_f32() * distance);
        assert!(light.is_valid(), "{light:?}");
        let hand_made = [
            Cap {
                axis: light.axis * 2.0,
                ..light
            },
            Cap {
                one_plus_cos: light.one_plus_cos * 0.5,
                ..light
            },
            Cap {
                sin2: light.sin2 * 0.5 + 0.1,
                ..light
            },
            Cap {
                one_minus_cos: 2.5,
                ..light
            },
            Cap {
                one_minus_cos: f32::NAN,
                ..light
            },
            Cap {
                axis: Vec3::new(f32::NAN, 0.0, 1.0),
                ..light
            },
        ];
        for cap in core::iter::once(light).chain(hand_made) {
            let clean = cap.sanitized();
            assert_eq!(cap.is_valid(), cap == light, "{cap:?}");
            assert_eq!(
                bits(shading.eval(&cap)),
                bits(shading.eval(&clean)),
                "{cap:?}"
            );
            assert_eq!(
                bits(shading.eval_occluded(&cap, &bent)),
                bits(shading.eval_occluded(&clean, &bent)),
                "{cap:?}"
            );
            assert!(shading.eval(&cap).is_finite());
        }
    }
}

/// `prepare` does not make the fitted pivot valid again (`prepare_sanitized::<true>`,
/// `Sptd::uniform_of_valid`): `valid_pivot` returns every pivot of
/// `GgxPivot::from_view` as it is. The table's norms are at most `1 − 3.3e-5`, and the
/// pivot's length is the interpolated norm (a convex combination of entries) times a
/// unit vector's rounding, far below `valid_pivot`'s clamp at `1 − 2⁻²⁰`; checked bit
/// for bit over views from normal incidence to `cos θo = 1e-4`, every azimuth octant and
/// roughness 0 to 1 (and NaN), and random views.
#[test]
fn fitted_pivots_are_valid_as_they_stand() {
    let largest = PIVOT_TABLE.iter().map(|e| e[0]).fold(0.0f32, f32::max);
    assert!(largest <= 1.0 - 1e-5, "{largest}");
    let bits = |p: Vec3| p.to_array().map(f32::to_bits);
    let check = |wo: Vec3, roughness: f32| {
        let Some(fit) = GgxPivot::from_view(wo, roughness) else {
            return false;
        };
        let again = crate::sphere::pivot::valid_pivot(fit.pivot);
        assert_eq!(bits(again), bits(fit.pivot), "{wo:?} {roughness}");
        assert_eq!(
            bits(Sptd::uniform_of_valid(fit.pivot).pivot),
            bits(Sptd::uniform(fit.pivot).pivot)
        );
        assert!(fit.pivot.length() < 1.0 - 1e-5);
        true
    };
    let mut checked = 0;
    for i in 0..=200 {
        let cos_o = if i == 0 { 1e-4 } else { i as f32 / 200.0 };
        let sin_o = (1.0 - cos_o * cos_o).max(0.0).sqrt();
        for k in 0..8 {
            let phi = core::f32::consts::TAU * k as f32 / 8.0 + 0.1;
            let wo = Vec3::new(sin_o * phi.cos(), sin_o * phi.sin(), cos_o);
            for j in 0..=64 {
                checked += check(wo, j as f32 / 64.0) as u32;
            }
            checked += check(wo, f32::NAN) as u32;
        }
    }
    let mut rng = Rng::new(2218);
    // `prepare` (the fitted pivot taken as valid: `prepare_sanitized::<true>`,
    // `SptdInCap::prepare_sanitized_in_line`) against `prepare_with_pivot` (made valid),
    // bit for bit, over sphere lights as the light bench draws them (above and across the
    // horizon).
    let (mut compared, mut clipped) = (0, 0);
    for _ in 0..20_000 {
        let v = rng.unit_vector_f32();
        let wo = Vec3::new(v.x, v.y, v.z.abs()) * (0.5 + 4.0 * rng.uniform_f32());
        let roughness = rng.uniform_f32();
        checked += check(wo, roughness) as u32;
        let distance = rng.log_uniform(0.0, 4f64.log10()) as f32;
        let sin2 = 0.06 + 0.38 * rng.uniform_f32();
        let c = rng.unit_vector_f32();
        let center = Vec3::new(c.x, c.y, c.z.abs()) * distance;
        let radius = distance * sin2.sqrt();
        let (Some(fit), Some(fast)) = (
            GgxPivot::from_view(wo, roughness),
            SphereLightSampler::new(center, radius, wo, roughness),
        ) else {
            continue;
        };
        let careful =
            SphereLightSampler::with_pivot(&Cap::from_sphere(center, radius), fit.pivot).unwrap();
        assert_eq!(format!("{fast:?}"), format!("{careful:?}"));
        assert_eq!(fast, careful);
        compared += 1;
        clipped += fast.is_clipped() as u32;
    }
    assert!(checked > 120_000, "{checked}");
    assert!(compared > 15_000 && clipped > 3_000, "{compared} {clipped}");
}

/// `prepare_with_fit` takes the valid-pivot path (`prepare_sanitized::<true>`) exactly
/// for the pivots that `valid_pivot` returns as they are (`is_valid_as_it_stands`), and
/// gives `prepare_with_pivot`'s bits for every pivot: random ones inside the ball, lengths
/// within ulps of the bound `1 − 2⁻²⁰` on either side, at and beyond 1, zero, huge,
/// infinite and NaN, for lights above and across the horizon.
#[test]
fn a_fit_s_pivot_takes_the_valid_path_where_it_is_valid() {
    use crate::sphere::pivot::{is_valid_as_it_stands, valid_pivot};
    let bits = |p: Vec3| p.to_array().map(f32::to_bits);
    let mut rng = Rng::new(4018);
    let bound = 1.0f32 - 1.0 / 1_048_576.0;
    let mut pivots = vec![
        Vec3::ZERO,
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1e30, 0.0, 0.0),
        Vec3::new(3e19, 3e19, 3e19),
        Vec3::new(f32::INFINITY, 0.0, 0.0),
        Vec3::new(0.1, f32::NAN, 0.2),
        Vec3::new(f32::MIN_POSITIVE, 0.0, -f32::MIN_POSITIVE),
    ];
    for _ in 0..400 {
        let dir = rng.unit_vector_f32();
        pivots.push(dir * rng.uniform_f32());
        // Lengths from 8 ulps below the bound to 8 above.
        pivots.extend(crate::testing::ulps_around(bound, 8).map(|length| dir * length));
        pivots.push(dir * (1.0 + rng.uniform_f32()));
    }
    let (mut valid, mut invalid, mut compared, mut clipped) = (0, 0, 0, 0);
    for (k, &pivot) in pivots.iter().enumerate() {
        let as_it_stands = bits(valid_pivot(pivot)) == bits(pivot);
        assert_eq!(is_valid_as_it_stands(pivot), as_it_stands, "{pivot:?}");
        if as_it_stands {
            valid += 1;
        } else {
            invalid += 1;
        }
        // Two lights a pivot: one above the horizon, one across it (every 4th also a
        // small one near the horizon).
        let lights = [
            (Vec3::new(0.3, -0.2, 2.0), 0.7),
            (
                Vec3::new(2.0, 0.5, 0.3),
                0.8 - 0.6 * (k % 4 == 0) as u32 as f32,
            ),
        ];
        for (center, radius) in lights {
            let fit = GgxPivot { pivot, albedo: 0.5 };
            let mut fast = SphereLightSampler::EMPTY;
            let ok = fast.prepare_with_fit(center, radius, &fit);
            let mut careful = SphereLightSampler::EMPTY;
            let careful_ok = careful.prepare_with_pivot(&Cap::from_sphere(center, radius), pivot);
            assert_eq!(ok, careful_ok, "{pivot:?}");
            assert_eq!(format!("{fast:?}"), format!("{careful:?}"), "{pivot:?}");
            compared += 1;
            clipped += (ok && fast.is_clipped()) as u32;
        }
    }
    assert!(valid > 4000 && invalid > 3000, "{valid} {invalid}");
    assert!(compared > 14_000 && clipped > 3_000, "{compared} {clipped}");
}

/// The sampler's direct uniform-base path (`SptdInCap::sample_uniform_base`, taken for
/// lights above the horizon that use the SPTD) gives `SptdInCap::sample`'s bits (its
/// dispatch on the base), for random lights, views and roughnesses and random and extreme
/// `u`; lights across the horizon and the uniform fallback do not take it.
#[test]
fn the_direct_uniform_path_gives_the_sptd_sample_s_bits() {
    let mut rng = Rng::new(1807);
    let (mut direct, mut other) = (0u32, 0u32);
    let extremes = [0.0, 0.5, 1.0 - f32::EPSILON / 2.0];
    for _ in 0..2000 {
        let distance = 10f32.powf(2.0 * rng.uniform_f32());
        let center = rng.unit_vector_f32() * distance;
        let radius = distance * 10f32.powf(-2.0 * rng.uniform_f32()) * 0.99;
        let theta = 1.5 * rng.uniform_f32();
        let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
        let Some(sampler) = SphereLightSampler::new(center, radius, wo, rng.uniform_f32()) else {
            continue;
        };
        if sampler.is_clipped() || !sampler.uses_sptd() {
            other += 1;
            continue;
        }
        assert_eq!(sampler.sptd.sptd.base, SptdBase::Uniform);
        direct += 1;
        let mut us: std::vec::Vec<[f32; 2]> = (0..50)
            .map(|_| [rng.uniform_f32(), rng.uniform_f32()])
            .collect();
        for a in extremes {
            for b in extremes {
                us.push([a, b]);
            }
        }
        for u in us {
            let (got, expected) = (sampler.sample(u), sampler.sptd.sample(u));
            assert_eq!(
                (got.dir.to_array().map(f32::to_bits), got.pdf.to_bits()),
                (
                    expected.dir.to_array().map(f32::to_bits),
                    expected.pdf.to_bits()
                ),
                "{center:?} {radius} {wo:?} {u:?}"
            );
        }
    }
    assert!(direct > 300 && other > 300, "{direct} {other}");
}

/// The clipped sampler takes its region's direction without the region's uniform pdf
/// (`CapIntersection::sample_direction`): over sphere lights across the horizon as the
/// light bench draws them (SPTD and uniform fallback) and random and extreme `u`, its
/// samples are bit for bit the old path's (`sample_uniform` of the region, no sample where
/// its pdf is 0, else the pivoted direction and `clipped_pdf`); a struct whose region's
/// `Ω` is denormal (`1/Ω` overflows: only through C) or 0 gives no sample.
#[test]
fn the_clipped_sample_skips_the_uniform_pdf() {
    let mut rng = Rng::new(3719);
    let old_path = |sampler: &SphereLightSampler, u: [f32; 2]| {
        let s = sampler.clipped_region.sample_uniform(u);
        if s.pdf == 0.0 {
            return Sample::NONE;
        }
        let dir = if sampler.uses_sptd() {
            transform(s.dir, sampler.pivot)
        } else {
            s.dir
        };
        Sample::new_or_none(dir, sampler.clipped_pdf(dir))
    };
    let bits = |s: Sample| (s.dir.to_array().map(f32::to_bits), s.pdf.to_bits());
    let (mut compared, mut fallbacks) = (0, 0);
    while compared < 3000 {
        let v = rng.unit_vector_f32();
        let wo = Vec3::new(v.x, v.y, v.z.abs().max(0.05));
        let roughness = rng.uniform_f32();
        let distance = rng.log_uniform(0.0, 4f64.log10()) as f32;
        let sin2 = 0.06 + 0.38 * rng.uniform_f32();
        let c = rng.unit_vector_f32();
        let center = Vec3::new(c.x, c.y, c.z.abs()) * distance;
        let Some(mut sampler) =
            SphereLightSampler::new(center, distance * sin2.sqrt(), wo, roughness)
        else {
            continue;
        };
        if !sampler.is_clipped() {
            continue;
        }
        compared += 1;
        fallbacks += !sampler.uses_sptd() as u32;
        for k in 0..20 {
            let u = match k {
                0 => [0.0, 0.0],
                1 => [crate::sample::ONE_MINUS_ULP, crate::sample::ONE_MINUS_ULP],
                2 => [0.5, crate::sample::ONE_MINUS_ULP],
                _ => [rng.uniform_f32(), rng.uniform_f32()],
            };
            // (A draw whose region direction rounding put outside the region is sampled
            // by its image where that has a density: `the_clipped_sample_tests_its_image_only`.)
            let base = sampler.clipped_region.sample_direction_unchecked(u);
            if !sampler.clipped_region.contains(base) {
                continue;
            }
            assert_eq!(
                bits(sampler.sample(u)),
                bits(old_path(&sampler, u)),
                "{u:?}"
            );
        }
        if compared % 100 == 0 {
            let edge = f32::from_bits(0x0020_0000);
            for omega in [1e-40, edge, 0.0, -0.0, -1.0, f32::NAN, f32::NEG_INFINITY] {
                sampler.clipped_region.solid_angle = omega;
                for u in [[0.3, 0.7], [0.99, 0.01]] {
                    assert_eq!(sampler.sample(u), Sample::NONE, "{omega:e}");
                }
            }
        }
    }
    assert!(fallbacks > 0, "{fallbacks}");
}

/// The clipped sampler's density takes a direction that `is_unit` accepts as it is and
/// normalises any other (`clipped_pdf` in line, `clipped_pdf_of_non_unit` out of line):
/// the samples of lights across the horizon are unit, their density is the sample's pdf
/// bit for bit, and the same direction scaled by 2, 2⁻⁷⁰ and 2⁷⁰ (normalised by the
/// out-of-line path) has the density of its normalised form, bit for bit; zero and
/// non-finite directions have density 0.
#[test]
fn the_clipped_pdf_takes_unit_directions_in_line_and_normalises_the_others() {
    let mut rng = Rng::new(4242);
    let mut checked = 0;
    for (degrees, roughness) in [(30.0, 0.5), (60.0, 0.3), (0.0, 0.8)] {
        let wo = view(degrees);
        let m = mirror(wo);
        let low = Vec3::new(m.x, m.y, 0.0).normalize_or(Vec3::X);
        for (center, radius) in [
            (low * 2.0 + Vec3::Z * 0.3, 1.0f32),
            (low * 2.0 - Vec3::Z * 0.3, 1.0),
        ] {
            let sampler = SphereLightSampler::new(center, radius, wo, roughness).unwrap();
            assert!(sampler.is_clipped());
            for _ in 0..2000 {
                let s = sampler.sample([rng.uniform_f32(), rng.uniform_f32()]);
                if !(s.pdf > 0.0) {
                    continue;
                }
                assert!(crate::math::is_unit(s.dir), "{s:?}");
                assert_eq!(sampler.clipped_pdf(s.dir).to_bits(), s.pdf.to_bits());
                // `normalize_scaled` is what `unit` does to a direction it does not take
                // as it is, and gives the same bits for every power-of-two multiple.
                let unit = crate::math::normalize_scaled(s.dir);
                assert!(crate::math::is_unit(unit));
                for scale in [2.0f32, 2f32.powi(-70), 2f32.powi(70)] {
                    let scaled = s.dir * scale;
                    assert!(!crate::math::is_unit(scaled));
                    assert_eq!(
                        sampler.pdf(scaled).to_bits(),
                        sampler.pdf(unit).to_bits(),
                        "{s:?} {scale}"
                    );
                }
                checked += 1;
            }
            for bad in [Vec3::ZERO, Vec3::NAN, Vec3::new(f32::INFINITY, 0.0, 1.0)] {
                assert_eq!(sampler.pdf(bad), 0.0);
            }
        }
    }
    assert!(checked > 5000, "{checked}");
}

/// The clipped sample tests its direction in `C ∩ H` only (`clipped_pdf`), not its
/// preimage in the region `g(C) ∩ g(H)`: where the region's direction lies in the region
/// (every draw but those that rounding puts across its boundary) the sample is the
/// region's sample mapped by `g`, its test and pulls included (`sample_clipped_pulled`),
/// bit for bit; where it does not, the sample is its image if that has a density, else
/// the pulled one. Either way `pdf(sample.dir) == sample.pdf`. Lights as the light
/// bench draws them (none of whose preimages left the region) and tiny ones across the
/// horizon (2% of whose preimages rounding put outside it, a ninth of those kept), with
/// `u` at the ends of `[0, 1)`.
#[test]
fn the_clipped_sample_tests_its_image_only() {
    let mut rng = Rng::new(1842);
    let bits = |s: Sample| (s.dir.to_array().map(f32::to_bits), s.pdf.to_bits());
    let (mut samplers, mut draws, mut outside, mut kept) = (0, 0, 0, 0);
    while samplers < 2000 {
        let v = rng.unit_vector_f32();
        let wo = Vec3::new(v.x, v.y, v.z.abs().max(0.05));
        let roughness = rng.uniform_f32();
        let distance = rng.log_uniform(0.0, 4f64.log10()) as f32;
        let sin2 = if samplers % 4 == 0 {
            rng.log_uniform(-7.0, -2.0) as f32
        } else {
            0.06 + 0.38 * rng.uniform_f32()
        };
        let c = rng.unit_vector_f32();
        let center = Vec3::new(c.x, c.y, c.z.abs() * sin2.sqrt()) * distance;
        let Some(sampler) = SphereLightSampler::new(center, distance * sin2.sqrt(), wo, roughness)
        else {
            continue;
        };
        if !sampler.is_clipped() {
            continue;
        }
        samplers += 1;
        for k in 0..50 {
            let u = match k {
                0 => [0.0, 0.0],
                1 => [crate::sample::ONE_MINUS_ULP, crate::sample::ONE_MINUS_ULP],
                2 => [crate::sample::ONE_MINUS_ULP, 0.0],
                _ => [rng.uniform_f32(), rng.uniform_f32()],
            };
            draws += 1;
            let s = sampler.sample(u);
            if s.pdf > 0.0 {
                assert_eq!(sampler.pdf(s.dir).to_bits(), s.pdf.to_bits(), "{u:?}");
            }
            let base = sampler.clipped_region.sample_direction_unchecked(u);
            if sampler.clipped_region.contains(base) {
                assert_eq!(bits(s), bits(sampler.sample_clipped_pulled(u)), "{u:?}");
                continue;
            }
            outside += 1;
            let image = sampler.clipped_image(base);
            if sampler.clipped_pdf(image) > 0.0 {
                kept += 1;
                assert_eq!(s.dir.to_array(), image.to_array(), "{u:?}");
            } else {
                assert_eq!(bits(s), bits(sampler.sample_clipped_pulled(u)), "{u:?}");
            }
        }
    }
    println!("{draws} draws: {outside} preimages outside the region, {kept} of them kept");
    // Both ways are taken (the tiny lights' preimages cross the region's boundary).
    assert!(kept > 0 && kept < outside, "{kept} of {outside} of {draws}");
}

/// The prepared numerators of the transformation and the Jacobian are those of the
/// prepared pivot, bit for bit (`pivot_numerators`; `[1, 1]`, written as a constant for
/// the uniform fallback and the caps above the horizon, is the zero pivot's), so that
/// the sample's `transform_of_numerator` and `jacobian_of_numerator`, which `transform`
/// and `jacobian_of_unit` call with the numerators of their pivot, give their bits; for
/// lights above, across and below the horizon, fitted and arbitrary pivots (tiny caps
/// take the fallback).
#[test]
fn the_prepared_pivot_numerators_are_the_pivot_s() {
    assert_eq!(
        pivot_numerators(Vec3::ZERO).map(f32::to_bits),
        [1.0f32; 2].map(f32::to_bits)
    );
    assert_eq!(
        SphereLightSampler::EMPTY.pivot_numerators,
        pivot_numerators(SphereLightSampler::EMPTY.pivot)
    );
    let mut rng = Rng::new(4318);
    let (mut clipped, mut fallback) = (0, 0);
    for i in 0..20_000 {
        let center = rng.unit_vector_f32() * (1.0 + 3.0 * rng.uniform_f32());
        let radius = if i % 4 == 3 {
            1e-3 * rng.uniform_f32()
        } else {
            center.length() * (0.06 + 0.38 * rng.uniform_f32()).sqrt()
        };
        let cap = Cap::from_sphere(center, radius);
        let pivot = if i % 2 == 0 {
            let wo = Vec3::new(
                rng.uniform_f32() - 0.5,
                rng.uniform_f32() - 0.5,
                0.1 + rng.uniform_f32(),
            );
            GgxPivot::from_view(wo, rng.uniform_f32()).unwrap().pivot
        } else {
            rng.unit_vector_f32() * (0.99997 * rng.uniform_f32())
        };
        let Some(sampler) = SphereLightSampler::with_pivot(&cap, pivot) else {
            continue;
        };
        assert_eq!(
            sampler.pivot_numerators.map(f32::to_bits),
            pivot_numerators(sampler.pivot).map(f32::to_bits),
            "{cap:?} {pivot:?}"
        );
        clipped += sampler.is_clipped() as u32;
        fallback += (sampler.is_clipped() && !sampler.uses_sptd()) as u32;
    }
    assert!(clipped > 1000 && fallback > 10, "{clipped} {fallback}");
}

/// `table_bilinear_of_guess` (a table read from a guessed cell) gives `table_bilinear`'s
/// bits in both orders of interpolation (`ALONG_Y_FIRST`, the LTC's; `ALONG_Y_LAST`, the
/// fit's Cartesian table's), for every guess: the right cell, a cell off by one or more on
/// either side (the checked path's fallback), the last cell, NaN, negative and
/// out-of-range guesses, at coordinates on and next to the cells' boundaries.
#[test]
fn the_table_s_guessed_cell_gives_table_bilinear_s_bits() {
    use crate::brdf::pivot_cartesian_table::PIVOT_CARTESIAN_TABLE;
    use crate::brdf::pivot_table::{PIVOT_TABLE, PIVOT_TABLE_SIZE};
    use crate::brdf::{ALONG_Y_FIRST, ALONG_Y_LAST, table_bilinear, table_bilinear_of_guess};
    let last = (PIVOT_TABLE_SIZE - 1) as f32;
    let mut ys = vec![0.0f32, 1e-30, 0.5, last, last - 1.0, 62.5];
    for j in 1..PIVOT_TABLE_SIZE {
        let j = j as f32;
        ys.extend([j, j.next_down(), j.next_up(), j - 0.5]);
    }
    let ys: Vec<f32> = ys
        .into_iter()
        .filter(|y| (0.0..=last).contains(y))
        .collect();
    /// The number of guesses in the right cell; asserts the bits of every guess.
    fn check<const Y_LAST: bool>(table: &[[f32; 3]], ys: &[f32]) -> u32 {
        let bits = |e: [f32; 3]| e.map(f32::to_bits);
        let last = (PIVOT_TABLE_SIZE - 1) as f32;
        let mut guessed_right = 0;
        for &y in ys {
            for x in [0.0, 0.25, 17.5, last] {
                let exact = table_bilinear::<3, Y_LAST>(table, PIVOT_TABLE_SIZE, x, y);
                let guesses = [
                    y,
                    y.next_down(),
                    y.next_up(),
                    y - 1.0,
                    y + 1.0,
                    y - 7.0,
                    y + 7.0,
                    -1.0,
                    100.0,
                    f32::NAN,
                    last,
                ];
                for guess in guesses {
                    let of_guess =
                        table_bilinear_of_guess::<3, Y_LAST>(table, PIVOT_TABLE_SIZE, x, y, guess);
                    assert_eq!(
                        bits(of_guess),
                        bits(exact),
                        "y last {Y_LAST} x {x} y {y:e} guess {guess:e}"
                    );
                    guessed_right += (guess as u32 == y as u32) as u32;
                }
            }
        }
        guessed_right
    }
    for table in [&PIVOT_TABLE[..], &PIVOT_CARTESIAN_TABLE[..]] {
        assert!(check::<ALONG_Y_FIRST>(table, &ys) > 0);
        assert!(check::<ALONG_Y_LAST>(table, &ys) > 0);
    }
}

/// The fit's guess of the table's row coordinate (`table_row_guess`) is the exact
/// coordinate's cell for unit views (at least 99.9% of them: the checked path's fallback
/// is rare),
/// and the fit is `table_bilinear`'s along y last (the lookup at the exact cell) bit for bit for
/// unit views and views of other lengths (whose guesses are wrong and take the fallback).
#[test]
fn the_fit_s_guessed_row_is_the_exact_cell_for_unit_views() {
    use crate::brdf::pivot_cartesian_table::{PIVOT_CARTESIAN_TABLE, PIVOT_CARTESIAN_TABLE_SIZE};
    use crate::brdf::{ALONG_Y_LAST, table_bilinear, table_coordinates};
    let former = |wo: Vec3, roughness: f32| -> Option<GgxPivot> {
        let (x, y, cos_phi, sin_phi) = table_coordinates(wo, roughness)?;
        let [x_view, z_view, albedo] = table_bilinear::<3, ALONG_Y_LAST>(
            &PIVOT_CARTESIAN_TABLE,
            PIVOT_CARTESIAN_TABLE_SIZE,
            x,
            y,
        );
        let pivot = Vec3::new(x_view * cos_phi, x_view * sin_phi, z_view);
        Some(GgxPivot {
            pivot: crate::sphere::pivot::valid_pivot(pivot),
            albedo,
        })
    };
    let bits =
        |f: Option<GgxPivot>| f.map(|f| (f.pivot.to_array().map(f32::to_bits), f.albedo.to_bits()));
    check_guessed_row_views(
        4618,
        |scaled, roughness| {
            assert_eq!(
                bits(GgxPivot::from_view(scaled, roughness)),
                bits(former(scaled, roughness)),
                "{scaled:?} {roughness}"
            )
        },
        |wo, roughness| {
            let guess = table_row_guess(wo) as u32;
            table_coordinates(wo, roughness).map(|(_, y, _, _)| guess.min(62) == (y as u32).min(62))
        },
    );
}
