use super::*;
use crate::sphere::cap_intersection_solid_angle;
use crate::sphere::pivot::{PivotPath, pivot_cap_by_points};
use crate::testing::{Rng, cap_intersection_f64, d3, pivot_image_f64};

fn random_pivot(rng: &mut Rng, max: f64) -> Vec3 {
    rng.unit_vector_f32() * (max * rng.uniform().sqrt()) as f32
}

/// The careful path: the image as a cap, then the exact two-cap solid angle.
fn careful(light: &Cap, pivot: Vec3, clip: &Cap) -> f32 {
    cap_intersection_solid_angle(&pivot_cap_by_points(light, &pivot).0, clip)
}

/// The f64 reference of `Ω(g(light) ∩ clip)`.
fn reference(light: &Cap, pivot: Vec3, clip: &Cap) -> f64 {
    let image = pivot_image_f64(d3(light.axis), light.one_minus_cos as f64, d3(pivot));
    let clip = (
        d3(clip.axis),
        clip.one_minus_cos as f64,
        clip.one_plus_cos as f64,
    );
    cap_intersection_f64(image, clip)
}

/// Random lights (1e-6 sr to wider than a hemisphere), pivots up to `|r_p| = 0.95` and
/// clips (the image of the upper hemisphere or of a random bent cone): where the one-pass
/// closed form answers, it agrees with the f64 reference as closely as the careful path
/// does (relative 1e-4 of the smaller cap, which the careful path also meets), and most
/// inputs take it.
#[test]
fn fast_intersection_agrees_with_f64_and_the_careful_path() {
    let mut rng = Rng::new(1801);
    let (mut fast, mut slow) = (0, 0);
    let (mut worst_fast, mut worst_careful) = (0.0f64, 0.0f64);
    for i in 0..40_000 {
        let t = match i % 4 {
            0 => rng.log_uniform(-6.0, 0.0) as f32,
            1 => (2.0 * rng.uniform()) as f32,
            _ => rng.log_uniform(-2.5, -0.3) as f32,
        };
        let light = Cap::from_axis_one_minus_cos(rng.unit_vector_f32(), t);
        let pivot = random_pivot(&mut rng, 0.95);
        let cone = if i % 3 == 0 {
            Cap::from_axis_one_minus_cos(Vec3::Z, 1.0)
        } else {
            Cap::from_axis_one_minus_cos(rng.unit_vector_f32(), (2.0 * rng.uniform()) as f32)
        };
        let clip = pivot_cap_by_points(&cone, &pivot).0;
        let Some(value) = pivoted_intersection_fast(&light, &pivot, &clip) else {
            slow += 1;
            continue;
        };
        fast += 1;
        let exact = reference(&light, pivot, &clip);
        let image = pivot_cap_by_points(&light, &pivot).0;
        let scale = (image.solid_angle().min(clip.solid_angle()) as f64).max(1e-30);
        let error_fast = (value as f64 - exact).abs() / scale;
        let error_careful = (careful(&light, pivot, &clip) as f64 - exact).abs() / scale;
        worst_fast = worst_fast.max(error_fast);
        worst_careful = worst_careful.max(error_careful);
        assert!(
            error_fast <= 1e-4,
            "{light:?} {pivot:?} {clip:?}: {value} vs {exact} (careful {})",
            careful(&light, pivot, &clip)
        );
    }
    println!(
        "fast {fast} careful {slow}; worst error over the smaller cap: fast {worst_fast:.2e}, careful {worst_careful:.2e}"
    );
    assert!(worst_careful <= 1e-4);
    assert!(fast > 30_000, "{fast} {slow}");
    // The careful path still answers some (the lens case too close to a boundary, pivots on
    // the light's axis line, images of a pivot near the sphere).
    assert!(slow > 40, "{fast} {slow}");
}

/// Which inputs take the closed form and which the careful path (`None`).
#[test]
fn fast_intersection_paths() {
    let pivot = Vec3::new(0.3, 0.1, 0.6);
    let horizon = Cap::from_axis_one_minus_cos(Vec3::Z, 1.0);
    let clip = pivot_cap_by_points(&horizon, &pivot).0;
    let axis = Vec3::new(0.2, 0.3, 0.9).normalize();
    // Ordinary lights (sin θ from 0.006 to 0.5), above the horizon or across it: fast,
    // and as the careful path to a few ulps of the light's image.
    for (axis, sins) in [
        (axis, [0.006f32, 0.05, 0.2, 0.5]),
        (Vec3::new(0.9, 0.0, 0.1).normalize(), [0.15, 0.2, 0.3, 0.5]),
    ] {
        for sin in sins {
            let light = Cap::from_axis_cos(axis, (1.0 - sin * sin).sqrt());
            let value = pivoted_intersection_fast(&light, &pivot, &clip).unwrap();
            let expected = careful(&light, pivot, &clip);
            let image = pivot_cap_by_points(&light, &pivot).0.solid_angle();
            assert!(
                (value - expected).abs() <= 1e-5 * image,
                "{sin}: {value} {expected}"
            );
        }
    }
    // Empty and whole lights; an empty or whole clip.
    assert_eq!(pivoted_intersection_fast(&Cap::EMPTY, &pivot, &clip), None);
    let light = Cap::from_axis_cos(axis, 0.9);
    assert_eq!(
        pivoted_intersection_fast(&Cap::WHOLE_SPHERE, &pivot, &clip),
        None
    );
    assert_eq!(pivoted_intersection_fast(&light, &pivot, &Cap::EMPTY), None);
    assert_eq!(
        pivoted_intersection_fast(&light, &pivot, &Cap::WHOLE_SPHERE),
        None
    );
    // Pivots that `valid_pivot` would change (at or past the unit sphere, not finite), and
    // the pivot on the light's axis line.
    for bad in [
        Vec3::new(0.0, 0.6, 0.8),
        Vec3::new(3.0, 0.0, 0.0),
        Vec3::new(f32::NAN, 0.0, 0.0),
        Vec3::new(f32::INFINITY, 0.0, 0.0),
        axis * 0.5,
        Vec3::ZERO,
    ] {
        assert_eq!(
            pivoted_intersection_fast(&light, &bad, &clip),
            None,
            "{bad}"
        );
    }
    // The pivot-on-the-axis-line test: 1e-3 rad off the line careful, 5e-3 rad off fast
    // (the bound is `|r_p⊥|² > 4e-6 |r_p|²`, 2e-3 rad), and there as the careful path.
    let perpendicular = axis.cross(Vec3::X).normalize();
    for (angle, fast) in [(1e-3f32, false), (5e-3, true)] {
        let off = (axis * angle.cos() + perpendicular * angle.sin()) * 0.5;
        let value = pivoted_intersection_fast(&light, &off, &clip);
        assert_eq!(value.is_some(), fast, "{angle}");
        if let Some(value) = value {
            let expected = careful(&light, off, &clip);
            let image = pivot_cap_by_points(&light, &off).0.solid_angle();
            assert!(
                (value - expected).abs() <= 1e-5 * image,
                "{value} {expected}"
            );
        }
    }
    // The closed form needs no well-conditioned image points: a 1e-12 sr light (whose
    // image's side is below the rounding of the image points, where `pivot_cap_by_points`
    // goes careful, and 9% off) and an image at a hemisphere (the upper hemisphere under
    // a pivot in its boundary's plane, `c' = 0`) are fast, and agree with the f64
    // reference (the first; the reference has no axis for the second: `g(ω₁) + g(ω₂) = 0`)
    // and the careful path (the second).
    let tiny = Cap::from_axis_one_minus_cos(axis, 1e-12 / (2.0 * PI));
    assert_eq!(pivot_cap_by_points(&tiny, &pivot).1, PivotPath::Careful);
    let flat = Vec3::new(0.5, 0.0, 0.0);
    for (light, pivot) in [(tiny, pivot), (horizon, flat)] {
        let value = pivoted_intersection_fast(&light, &pivot, &clip).unwrap();
        let expected = if light == tiny {
            reference(&light, pivot, &clip)
        } else {
            careful(&light, pivot, &clip) as f64
        };
        let image = pivot_cap_by_points(&light, &pivot).0.solid_angle() as f64;
        assert!(
            (value as f64 - expected).abs() <= 1e-5 * image,
            "{light:?}: {value} {expected}"
        );
    }
    // The pivot near the sphere and a light near `r_p/|r_p|`: the image's plane normal
    // `|n| = |ω₁ − r_p||ω₂ − r_p|` is about `(1 − |r_p|)² = 1e-4`, below `1/16`; careful.
    // A little farther from the pivot's direction (`|n|` above `1/16`), fast.
    let near = Vec3::new(0.0, 0.6, 0.8) * 0.99;
    for (tilt, fast) in [(0.02f32, false), (0.35, true)] {
        let light_axis = Vec3::new(tilt.sin(), 0.6 * tilt.cos(), 0.8 * tilt.cos());
        let light = Cap::from_axis_cos(light_axis, 0.9999);
        let clip = pivot_cap_by_points(&horizon, &near).0;
        let value = pivoted_intersection_fast(&light, &near, &clip);
        assert_eq!(value.is_some(), fast, "{tilt}");
        if let Some(value) = value {
            // (Against the f64 reference: the careful path is 1e-5 off here, the closed
            // form 1.3e-6.)
            let expected = reference(&light, near, &clip);
            let image = pivot_cap_by_points(&light, &near).0.solid_angle() as f64;
            assert!(
                (value as f64 - expected).abs() <= 3e-6 * image,
                "{value} {expected}"
            );
        }
    }
    // A light whose image touches the clip's boundary from inside: the case is not clear
    // without the angles. The light's image is the clip shrunk by a hair: a cap tangent
    // to the horizon from above, whose image is tangent to g(H) from inside.
    let touching = Cap::from_axis_cos(Vec3::new(0.6, 0.0, 0.8), 0.6);
    assert_eq!(pivoted_intersection_fast(&touching, &pivot, &clip), None);
    // Clearly disjoint and clearly nested: fast, exactly 0 and the image's solid angle.
    let below = Cap::from_axis_cos(Vec3::new(0.0, 0.3, -1.0).normalize(), 0.95);
    assert_eq!(pivoted_intersection_fast(&below, &pivot, &clip), Some(0.0));
    // (The image's side agrees with `pivot_cap_by_points`'s to rounding: the closed form's
    // `k² sin²θ / (|n|(|n| + |c'|))` against `pivot_cap_by_points`'s points in the plane.)
    let above = Cap::from_axis_cos(axis, 0.95);
    let nested = pivoted_intersection_fast(&above, &pivot, &clip).unwrap();
    let image = pivot_cap_by_points(&above, &pivot).0.solid_angle();
    assert!((nested - image).abs() <= 1e-6 * image, "{nested} {image}");
}
