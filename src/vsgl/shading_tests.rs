//! VSGLs of VPL clusters against the VPLs themselves (issue 20): the shading of the SG
//! layer (`crate::sg::shading`) applied to what the accumulator builds, checked here so
//! that the SG layer's own tests do not depend on the VSGL layer above it.
use super::{Vpl, VsglAccumulator};
use crate::Vec3;
use crate::sg::Sg;
use crate::sg::sg_integral;
use crate::sg::shading::*;
use crate::testing::{D3, Rng, d3, dot, normalize, scale, sub};
use core::f64::consts::PI as PI64;

fn sg64(axis: [f64; 3], l: f64, w: [f64; 3]) -> f64 {
    let e = sub(normalize(w), normalize(axis));
    (-0.5 * l * dot(e, e)).exp()
}

/// VPLs in the plane z = 0 around the origin within `radius`, normal +z, all lit from
/// the same direction (so that their lobes are identical), random powers and
/// reflectances.
fn planar_vpls(rng: &mut Rng, count: usize, radius: f32) -> std::vec::Vec<Vpl> {
    (0..count)
        .map(|_| {
            let (r, phi) = (
                radius * rng.uniform_f32().sqrt(),
                core::f32::consts::TAU * rng.uniform_f32(),
            );
            Vpl {
                position: Vec3::new(r * phi.cos(), r * phi.sin(), 0.0),
                normal: Vec3::Z,
                power: Vec3::new(
                    0.2 + rng.uniform_f32(),
                    0.2 + rng.uniform_f32(),
                    0.2 + rng.uniform_f32(),
                ),
                diffuse_reflectance: Vec3::splat(0.1 + 0.8 * rng.uniform_f32()),
                specular_reflectance: Vec3::splat(0.5 * rng.uniform_f32()),
                toward_incoming: Vec3::new(0.5, 0.2, 0.7),
                roughness: 0.3,
            }
        })
        .collect()
}

#[test]
fn a_planar_cluster_seen_face_on_has_its_own_angular_spread() {
    // Seen from a distance D along the plane's normal, a planar cluster's VPLs lie at
    // directions ω_j around ξ_μ with the weighted spread m = E|ω − ξ_μ|²; an SG of
    // sharpness λ has E|ω − ξ|² = 2/λ for λ ≫ 1, so the spatial SG of Eq. 6 must have
    // λ_σ = 2/m. The paper's λ_σ = D²/σ_v² is half of that (the VSGL √2 too wide).
    let mut rng = Rng::new(2020);
    for (count, radius, distance) in [(400usize, 0.5f32, 20.0f32), (50, 1.0, 40.0)] {
        let vpls = planar_vpls(&mut rng, count, radius);
        let mut accumulator = VsglAccumulator::new(Vec3::ZERO);
        for vpl in &vpls {
            assert!(accumulator.add_vpl(vpl));
        }
        let vsgl = accumulator.finish();
        let x = [0.0, 0.0, distance as f64];
        // f64: the luminance-weighted mean position and angular spread.
        let weight = |v: &Vpl| {
            let p = v.power * (v.diffuse_reflectance + v.specular_reflectance);
            0.2126 * p.x as f64 + 0.7152 * p.y as f64 + 0.0722 * p.z as f64
        };
        let total: f64 = vpls.iter().map(weight).sum();
        let mut mean = [0.0; 3];
        for v in &vpls {
            mean = crate::testing::add(mean, scale(d3(v.position), weight(v) / total));
        }
        let axis = normalize(sub(mean, x));
        let spread: f64 = vpls
            .iter()
            .map(|v| {
                let e = sub(normalize(sub(d3(v.position), x)), axis);
                weight(v) * dot(e, e)
            })
            .sum::<f64>()
            / total;
        // A uniform emission lobe (λ_v = 0): the product is the spatial SG itself.
        let uniform = Sg::new(Vec3::Z, 0.0, 1.0);
        let offset = vsgl.mean - Vec3::new(0.0, 0.0, distance);
        let l_in = incoming_radiance(&uniform, offset, vsgl.variance);
        let expected = 2.0 / spread;
        assert!(
            (l_in.sharpness as f64 / expected - 1.0).abs() < 0.02,
            "{count} VPLs: λ_σ {} vs {expected}",
            l_in.sharpness
        );
        // Its energy is the inverse-square law's: ∫ G_σ/(2πs²) dω = 1/|μ − x|².
        let energy = (l_in.log_amplitude as f64).exp() * sg_integral(l_in.sharpness) as f64;
        let d2 = dot(sub(mean, x), sub(mean, x));
        assert!((energy * d2 - 1.0).abs() < 1e-3, "{energy} vs {}", 1.0 / d2);
    }
}

/// `e^{λ(ω·ξ − 1)}/A(λ)` in f64, `A(λ) = 2π(1 − e^{−2λ})/λ`.
fn normalised_sg64(axis: D3, l: f64, w: D3) -> f64 {
    sg64(axis, l, w) * l / (2.0 * PI64 * (1.0 - (-2.0 * l).exp()))
}

#[test]
fn far_from_a_cluster_vsgl_shading_converges_to_the_vpls_sum() {
    // The diffuse shading (constant cosine, unit albedo) of a point at distance D from
    // a cluster of VPLs with identical lobes, from the VSGL (Eq. 6-7) against the sum
    // over the VPLs of Φ R G(−ω_j)/A · max(n·ω_j, 0)/π / r_j² in f64 (Eq. 1, 2 with
    // λ_d = 2.2925, λ_s = (2/α²)/(4 cos θ'), written out here): the error falls with
    // the cluster's angular size.
    let mut rng = Rng::new(77);
    let vpls = planar_vpls(&mut rng, 300, 0.1);
    let mut accumulator = VsglAccumulator::new(Vec3::ZERO);
    for vpl in &vpls {
        assert!(accumulator.add_vpl(vpl));
    }
    let vsgl = accumulator.finish();
    let w_in = normalize(d3(vpls[0].toward_incoming));
    let reflected = sub(scale([0.0, 0.0, 1.0], 2.0 * w_in[2]), w_in);
    let alpha = 0.3f64;
    let l_s = 2.0 / (alpha * alpha) / (4.0 * w_in[2]);
    let mut worst = [0.0f64; 2];
    for (k, distance) in [10.0f64, 1000.0].into_iter().enumerate() {
        for _ in 0..40 {
            let dir = loop {
                let d = crate::testing::uniform_direction_f64(&mut rng);
                if d[2] > 0.2 {
                    break d;
                }
            };
            let x = scale(dir, distance);
            let n = scale(dir, -1.0); // the receiver faces the cluster
            let mut reference = 0.0;
            for v in &vpls {
                let to_vpl = sub(d3(v.position), x);
                let r2 = dot(to_vpl, to_vpl);
                let w = normalize(to_vpl);
                let out = scale(w, -1.0); // from the VPL towards the receiver
                let emitted = (v.power.x * v.diffuse_reflectance.x) as f64
                    * normalised_sg64([0.0, 0.0, 1.0], 2.2925, out)
                    + (v.power.x * v.specular_reflectance.x) as f64
                        * normalised_sg64(reflected, l_s, out);
                reference += emitted * dot(n, w).max(0.0) / PI64 / r2;
            }
            let offset = vsgl.mean - Vec3::new(x[0] as f32, x[1] as f32, x[2] as f32);
            let normal = Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32);
            let mut value = 0.0f64;
            for (lobe, power) in [
                (vsgl.diffuse, vsgl.diffuse_power.x),
                (vsgl.specular, vsgl.specular_power.x),
            ] {
                let l_in = incoming_radiance(&lobe, offset, vsgl.variance);
                value +=
                    power as f64 * diffuse_shading_constant_cosine(&l_in, normal, 1.0, 1.0) as f64;
            }
            let error = (value / reference - 1.0).abs();
            worst[k] = worst[k].max(error);
        }
    }
    assert!(worst[0] < 0.02, "D = 10: worst relative error {}", worst[0]);
    assert!(
        worst[1] < 2e-4,
        "D = 1000: worst relative error {}",
        worst[1]
    );
}
