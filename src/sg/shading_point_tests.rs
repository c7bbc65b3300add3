use super::sg::{MAX_SHARPNESS, MIN_LOG_AMPLITUDE, Sg};
use super::shading::{diffuse_shading_constant_cosine, incoming_radiance, specular_shading};
use super::shading_point::{SgShading, SgShadingPoint};
use crate::Vec3;
use crate::testing::Rng;

/// Hard scalars: NaN, infinities, zeros, denormals, the ends of the clamps.
const HARD: [f32; 14] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    0.0,
    -0.0,
    1e-45,
    1e-30,
    1e-4,
    0.5,
    1.0,
    1.5,
    -1.0,
    1e30,
    f32::MAX,
];

/// A random or hard vector: unit, scaled (lengths 1e-30 to 1e30), along an axis, zero or
/// non-finite.
fn vector(rng: &mut Rng) -> Vec3 {
    match rng.below(10) {
        0 => Vec3::ZERO,
        1 => Vec3::new(f32::NAN, 0.0, 1.0),
        2 => Vec3::new(0.0, f32::INFINITY, 0.0),
        3 => Vec3::Z,
        4 => -Vec3::Z,
        5 => Vec3::new(1.0, 0.0, 1e-7),
        6 => rng.unit_vector_f32() * rng.log_uniform(-30.0, 30.0) as f32,
        _ => rng.unit_vector_f32(),
    }
}

fn scalar(rng: &mut Rng, lo: f64, hi: f64) -> f32 {
    if rng.below(6) == 0 {
        HARD[rng.below(HARD.len() as u64) as usize]
    } else {
        rng.log_uniform(lo, hi) as f32
    }
}

/// An incoming SG: from `incoming_radiance` of a random VSGL (as the tracer shades), or
/// raw fields (any axis, sharpness and log amplitude, as C may pass).
fn incoming(rng: &mut Rng) -> Sg {
    if rng.below(2) == 0 {
        let lobe = Sg::new(
            rng.unit_vector_f32(),
            rng.log_uniform(-2.0, 4.0) as f32,
            rng.log_uniform(-3.0, 3.0) as f32,
        );
        let mean = rng.unit_vector_f32() * rng.log_uniform(-2.0, 2.0) as f32;
        incoming_radiance(&lobe, mean, rng.log_uniform(-4.0, 1.0) as f32)
    } else {
        Sg {
            axis: vector(rng),
            sharpness: scalar(rng, -3.0, 8.5),
            log_amplitude: if rng.below(8) == 0 {
                MIN_LOG_AMPLITUDE
            } else {
                scalar(rng, -2.0, 1.9) * if rng.below(2) == 0 { -1.0 } else { 1.0 }
            },
        }
    }
}

#[test]
fn shading_point_matches_the_free_functions_bit_for_bit() {
    let mut rng = Rng::new(38);
    let (mut diffuse_positive, mut specular_positive) = (0, 0);
    for _ in 0..4000 {
        let normal = vector(&mut rng);
        let view = if rng.below(3) == 0 {
            vector(&mut rng)
        } else {
            // Views near the normal's hemisphere, grazing ones included.
            let n = normal.normalize_or_zero();
            (rng.unit_vector_f32() + n * rng.range(0.0, 1.5)) * rng.log_uniform(-3.0, 3.0) as f32
        };
        let roughness = if rng.below(5) == 0 {
            HARD[rng.below(HARD.len() as u64) as usize]
        } else {
            rng.range(0.0, 1.0)
        };
        let f0 = if rng.below(5) == 0 {
            HARD[rng.below(HARD.len() as u64) as usize]
        } else {
            rng.range(0.0, 1.0)
        };
        let mut point = SgShadingPoint::EMPTY;
        let prepared = point.prepare(normal, view, roughness, f0);
        assert_eq!(
            prepared,
            normal.is_finite() && normal != Vec3::ZERO && view.is_finite() && view != Vec3::ZERO,
            "{normal:?} {view:?}"
        );
        for _ in 0..8 {
            let sg = incoming(&mut rng);
            let r_d = if rng.below(4) == 0 {
                HARD[rng.below(HARD.len() as u64) as usize]
            } else {
                rng.range(0.0, 1.0)
            };
            let visibility = if rng.below(4) == 0 {
                HARD[rng.below(HARD.len() as u64) as usize]
            } else {
                1.0
            };
            let shading = point.shade(&sg, r_d, visibility);
            assert!(
                shading.diffuse.is_finite()
                    && shading.diffuse >= 0.0
                    && shading.specular.is_finite()
                    && shading.specular >= 0.0,
                "{shading:?}"
            );
            if !prepared {
                assert_eq!(shading, SgShading::ZERO);
                continue;
            }
            let diffuse = diffuse_shading_constant_cosine(&sg, normal, r_d, visibility);
            let specular = specular_shading(&sg, normal, view, roughness, f0, visibility);
            let what = format!("{normal:?} {view:?} {roughness} {f0} {sg:?} {r_d} {visibility}");
            assert_eq!(
                shading.diffuse.to_bits(),
                diffuse.to_bits(),
                "diffuse {what}"
            );
            assert_eq!(
                shading.specular.to_bits(),
                specular.to_bits(),
                "specular {what}"
            );
            diffuse_positive += (diffuse > 0.0) as u32;
            specular_positive += (specular > 0.0) as u32;
        }
    }
    // The draws reach both terms (not a comparison of zeros).
    assert!(diffuse_positive > 5000, "{diffuse_positive}");
    assert!(specular_positive > 2000, "{specular_positive}");
}

#[test]
fn bad_normals_and_views_give_the_empty_point() {
    let lobe = Sg::new(Vec3::new(0.1, 0.2, 1.0), 10.0, 1.0);
    for (normal, view) in [
        (Vec3::ZERO, Vec3::Z),
        (Vec3::Z, Vec3::ZERO),
        (Vec3::new(f32::NAN, 0.0, 1.0), Vec3::Z),
        (Vec3::Z, Vec3::new(0.0, f32::INFINITY, 1.0)),
        (
            Vec3::new(f32::NEG_INFINITY, 0.0, 0.0),
            Vec3::new(f32::NAN, 0.0, 0.0),
        ),
    ] {
        // A prepared point first, so that the failed prepare must overwrite it.
        let mut point = SgShadingPoint::new(Vec3::Z, Vec3::Z, 0.5, 0.04);
        assert!(point.shade(&lobe, 1.0, 1.0).diffuse > 0.0);
        assert!(!point.prepare(normal, view, 0.5, 0.04));
        assert_eq!(point, SgShadingPoint::EMPTY);
        assert_eq!(point.shade(&lobe, 1.0, 1.0), SgShading::ZERO);
    }
    // A view below the horizon is valid: diffuse as usual, specular 0.
    let mut point = SgShadingPoint::EMPTY;
    assert!(point.prepare(Vec3::Z, Vec3::new(0.3, 0.0, -1.0), 0.5, 0.04));
    let shading = point.shade(&lobe, 1.0, 1.0);
    assert!(shading.diffuse > 0.0);
    assert_eq!(shading.specular, 0.0);
}

#[test]
fn sharp_and_extreme_lobes_stay_finite() {
    let point = SgShadingPoint::new(Vec3::Z, Vec3::new(0.0, 0.3, 1.0), 0.0, 1.0);
    for sharpness in [0.0, 1e-30, 1.0, 1e4, MAX_SHARPNESS, f32::INFINITY] {
        for log_amplitude in [MIN_LOG_AMPLITUDE, -100.0, 0.0, 88.72283, f32::INFINITY] {
            let sg = Sg {
                axis: Vec3::new(0.0, -0.3, 1.0).normalize(),
                sharpness,
                log_amplitude,
            };
            let s = point.shade(&sg, f32::MAX, 1.0);
            assert!(s.diffuse.is_finite() && s.diffuse >= 0.0, "{s:?}");
            assert!(s.specular.is_finite() && s.specular >= 0.0, "{s:?}");
        }
    }
}
