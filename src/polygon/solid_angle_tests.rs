//! Tests of solid angle sampling: distribution (chi-square against exact cell solid
//! angles in f64), estimators, containment, the inverse, and the hard cases.
use super::*;
use crate::sample::ONE_MINUS_ULP;
use crate::testing::*;

fn cell_solid_angle(c: &[D3; 3]) -> f64 {
    solid_angle_triangle_f64(c[0], c[1], c[2])
}

fn reference_solid_angle(v: &[Vec3]) -> f64 {
    solid_angle_polygon_f64(&v.iter().map(|&x| d3(x)).collect::<Vec<_>>())
}

/// Runs the chi-square test and the pdf consistency check on one polygon.
fn assert_uniform_in_solid_angle(
    vertices: &[Vec3],
    samples: u64,
    seed: u64,
    what: &str,
) -> SamplerReport {
    assert_uniform_in_solid_angle_of::<8, 6>(vertices, samples, seed, what)
}

/// [`assert_uniform_in_solid_angle`] with the sampler of a given size.
fn assert_uniform_in_solid_angle_of<const N: usize, const T: usize>(
    vertices: &[Vec3],
    samples: u64,
    seed: u64,
    what: &str,
) -> SamplerReport {
    let polygon =
        SolidAngleFan::<N, T>::new(vertices).unwrap_or_else(|| panic!("{what}: prepare failed"));
    let reference = reference_solid_angle(vertices);
    let relative = (polygon.solid_angle() as f64 - reference).abs() / reference;
    assert!(
        relative < 1e-5,
        "{what}: solid angle {} vs f64 {reference}",
        polygon.solid_angle()
    );
    let report = run_polygon_sampler(
        vertices,
        8,
        samples,
        seed,
        cell_solid_angle,
        |u| polygon.sample(u),
        |d| polygon.pdf(d),
    );
    assert!(
        report.p_value > CHI_SQUARE_ALPHA,
        "{what}: chi-square rejects, {report:?}"
    );
    assert_eq!(report.non_finite, 0, "{what}: {report:?}");
    assert!(report.worst_outside_angle < 5e-7, "{what}: {report:?}");
    assert!(
        report.outside as f64 <= 1e-3 * samples as f64,
        "{what}: {report:?}"
    );
    assert!(
        report.worst_pdf_mismatch == 0.0
            || (report.outside > 0 && report.worst_pdf_mismatch == 1.0),
        "{what}: {report:?}"
    );
    report
}

/// A random convex polygon of `n` vertices on an ellipse of radius `radius_min` plus up to
/// `radius_span`, centred 1 to 2 above the shading point within ±0.5 sideways, its plane
/// tilted at random.
fn random_polygon_above(rng: &mut Rng, n: usize, radius_min: f32, radius_span: f32) -> Vec<Vec3> {
    let center = Vec3::new(
        rng.uniform_f32() - 0.5,
        rng.uniform_f32() - 0.5,
        1.0 + rng.uniform_f32(),
    );
    let normal = Vec3::new(rng.uniform_f32() - 0.5, rng.uniform_f32() - 0.5, 1.0);
    let (radius, aspect) = (
        radius_min + radius_span * rng.uniform_f32(),
        0.3 + 0.7 * rng.uniform_f32(),
    );
    ellipse_polygon(rng, n, center, normal, radius, aspect)
}

#[test]
fn samples_follow_the_uniform_density_on_polygons_of_3_to_8_vertices_in_both_windings() {
    let mut rng = Rng::new(100);
    for n in 3..=8 {
        for trial in 0..3 {
            let v = random_polygon_above(&mut rng, n, 0.3, 1.0);
            assert_uniform_in_solid_angle(
                &v,
                400_000,
                n as u64 * 10 + trial,
                &format!("{n} vertices, trial {trial}"),
            );
            assert_uniform_in_solid_angle(
                &reversed(&v),
                400_000,
                n as u64 * 10 + trial + 5,
                &format!("{n} vertices reversed"),
            );
        }
    }
}

#[test]
fn near_hemisphere_quads_just_above_the_shading_point() {
    // Quads centred over the shading point, and offset so that a fan diagonal passes
    // right over it (its end points are nearly antipodal), at heights down to 1e-6 of
    // their size: nearly 2π steradians.
    for (size, height) in [
        (1.0f32, 1e-2f32),
        (1.0, 1e-3),
        (1.0, 1e-4),
        (100.0, 1e-4),
        (1.0, 1e-6),
    ] {
        for skew in [0.0f32, 0.3] {
            let v = [
                Vec3::new(-size, -size * (1.0 - skew), height),
                Vec3::new(size * (1.0 + skew), -size, height),
                Vec3::new(size, size, height),
                Vec3::new(-size, size * (1.0 - skew), height),
            ];
            let what = format!("size {size}, height {height}, skew {skew}");
            let polygon = SolidAnglePolygon::new(&v).unwrap();
            let reference = reference_solid_angle(&v);
            let error = (polygon.solid_angle() as f64 - reference).abs() / reference;
            assert!(
                error < 1e-6,
                "{what}: Ω = {} vs {reference}",
                polygon.solid_angle()
            );
            // Directions this close to the horizon cannot be located in planar cells from
            // f32 directions when the quad is very flat, so the distribution is tested by
            // chi-square only down to 1e-3 and by the cosine estimator everywhere.
            if height / size >= 1e-3 {
                assert_uniform_in_solid_angle(&v, 300_000, 7, &what);
            }
            let mut rng = Rng::new(8);
            let mut estimate = Estimate::default();
            for _ in 0..200_000 {
                let s = polygon.sample([rng.uniform_f32(), rng.uniform_f32()]);
                assert!(
                    s.dir.is_finite() && s.pdf > 0.0 && s.dir.z > -1e-6,
                    "{what}: {s:?}"
                );
                estimate.add(s.dir.z as f64 / s.pdf as f64);
            }
            estimate.assert_mean_is(projected_solid_angle_polygon_f64(&v), 5.0, 1e-5, &what);
        }
    }
}

#[test]
fn slivers_are_sampled_correctly() {
    // Long thin triangles and quads, in both windings.
    for aspect in [1e-2f32, 1e-3, 1e-4] {
        let v = [
            Vec3::new(-1.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(0.0, aspect, 1.0),
        ];
        assert_uniform_in_solid_angle(&v, 200_000, 11, &format!("sliver {aspect}"));
        assert_uniform_in_solid_angle(
            &reversed(&v),
            200_000,
            12,
            &format!("sliver {aspect} reversed"),
        );
    }
}

#[test]
fn shading_point_in_the_polygon_plane_gives_no_polygon() {
    let v = [
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(2.0, 1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
    ];
    assert!(SolidAnglePolygon::new(&v).is_none());
    let tilted = [
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(2.0, 2.0, 2.0),
        Vec3::new(2.0, 0.0, 0.0),
    ];
    // The exact f32 inputs are coplanar with the origin (p1 = 2 p0), so Ω = 0.
    assert!(SolidAnglePolygon::new(&tilted).is_none());
}

#[test]
fn distant_vertices_at_1e5_keep_their_accuracy() {
    let mut rng = Rng::new(5);
    for n in [3, 4, 7] {
        let v = ellipse_polygon(
            &mut rng,
            n,
            Vec3::new(3e4, -2e4, 1e5),
            Vec3::new(0.2, 0.1, 1.0),
            300.0,
            0.6,
        );
        assert_uniform_in_solid_angle(&v, 200_000, 13, &format!("distant {n}"));
    }
}

#[test]
fn extreme_random_numbers_give_valid_samples() {
    let v = [
        Vec3::new(-1.0, -1.0, 1.0),
        Vec3::new(1.0, -1.0, 1.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
    ];
    let polygon = SolidAnglePolygon::new(&v).unwrap();
    let below_one = 1.0 - f32::EPSILON / 2.0;
    for u0 in [0.0, 1e-7, 0.5, below_one, 1.0, 2.0, -1.0, f32::NAN] {
        for u1 in [0.0, 1e-7, 0.5, below_one, 1.0, f32::INFINITY, f32::NAN] {
            let s = polygon.sample([u0, u1]);
            assert!(s.dir.is_finite() && s.pdf > 0.0, "u = {u0}, {u1}: {s:?}");
            assert!((s.dir.length() - 1.0).abs() < 1e-6);
            assert!(polygon.pdf(s.dir) > 0.0, "u = {u0}, {u1}: {s:?} outside");
        }
    }
}

#[test]
fn duplicate_vertices_from_clipping_are_tolerated() {
    let v = [
        Vec3::new(-1.0, -1.0, 1.0),
        Vec3::new(1.0, -1.0, 1.0),
        Vec3::new(1.0, -1.0, 1.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
    ];
    let distinct = [v[0], v[1], v[3], v[4]];
    let polygon = SolidAnglePolygon::new(&v).unwrap();
    assert!((polygon.solid_angle() as f64 - reference_solid_angle(&distinct)).abs() < 1e-6);
    let report = run_polygon_sampler(
        &distinct,
        8,
        200_000,
        17,
        cell_solid_angle,
        |u| polygon.sample(u),
        |d| polygon.pdf(d),
    );
    assert!(
        report.p_value > CHI_SQUARE_ALPHA && report.outside == 0 && report.non_finite == 0,
        "{report:?}"
    );
    // A duplicate first vertex (the fan apex's first triangle is empty).
    let w = [v[0], v[0], v[1], v[3], v[4]];
    let polygon = SolidAnglePolygon::new(&w).unwrap();
    for u0 in [0.0, 0.3, 1.0] {
        assert!(polygon.sample([u0, 0.5]).pdf > 0.0);
    }
}

#[test]
fn bad_input_is_rejected() {
    let ok = [
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(0.0, 1.0, 1.0),
    ];
    assert!(SolidAnglePolygon::new(&ok).is_some());
    for bad in invalid_polygons(&ok) {
        assert!(SolidAnglePolygon::new(&bad).is_none(), "{bad:?}");
    }
    for good in valid_edge_case_polygons() {
        assert!(SolidAnglePolygon::new(&good).is_some(), "{good:?}");
    }
    assert!(SolidAnglePolygon::new(&ok[..2]).is_none());
    assert!(SolidAnglePolygon::new(&[]).is_none());
    assert!(SolidAnglePolygon::new(&[ok[0]; 9]).is_none());
    for bad in [f32::NAN, f32::INFINITY, -f32::INFINITY] {
        let mut v = ok;
        v[1].y = bad;
        assert!(SolidAnglePolygon::new(&v).is_none());
    }
    assert!(
        SolidAnglePolygon::new(&[ok[0]; 3]).is_none(),
        "all vertices equal"
    );
    let collinear = [
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(2.0, 0.0, 1.0),
    ];
    assert!(SolidAnglePolygon::new(&collinear).is_none());
    let at_origin = [
        Vec3::ZERO,
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(0.0, 1.0, 1.0),
    ];
    assert!(SolidAnglePolygon::new(&at_origin).is_none());
    let huge = [
        Vec3::new(0.0, 0.0, 1e38),
        Vec3::new(3e38, 0.0, 1e38),
        Vec3::new(0.0, 3e38, 1e38),
    ];
    let p = SolidAnglePolygon::new(&huge).expect("huge coordinates are rescaled");
    assert!((p.solid_angle() as f64 - reference_solid_angle(&huge)).abs() < 1e-5);
    let tiny = [
        Vec3::new(0.0, 0.0, 1e-40),
        Vec3::new(3e-40, 0.0, 1e-40),
        Vec3::new(0.0, 3e-40, 1e-40),
    ];
    let p = SolidAnglePolygon::new(&tiny).expect("subnormal coordinates are rescaled");
    assert!(p.solid_angle().is_finite() && p.solid_angle() > 0.0);
    let empty = SolidAnglePolygon::EMPTY;
    assert_eq!(empty.sample([0.5, 0.5]).pdf, 0.0);
    assert!(empty.sample([0.5, 0.5]).dir.is_finite());
    assert_eq!(empty.pdf(Vec3::Z), 0.0);
    assert!(empty.invert(Vec3::Z).is_none());
    let polygon = SolidAnglePolygon::new(&ok).unwrap();
    assert_eq!(polygon.pdf(Vec3::ZERO), 0.0);
    assert_eq!(polygon.pdf(Vec3::new(f32::NAN, 0.0, 1.0)), 0.0);
    assert_eq!(
        polygon.pdf(Vec3::new(0.1, 0.1, 1.0) * 1e30),
        polygon.pdf(Vec3::new(0.1, 0.1, 1.0))
    );
    assert_eq!(polygon.pdf(-Vec3::new(0.1, 0.1, 1.0)), 0.0);
}

#[test]
fn projected_solid_angle_estimator_matches_lamberts_formula() {
    // E[cos θ / pdf] = projected solid angle, by Lambert's formula in f64.
    let mut rng = Rng::new(31);
    for n in [3, 5, 8] {
        let v = ellipse_polygon(
            &mut rng,
            n,
            Vec3::new(0.3, -0.2, 0.8),
            Vec3::new(0.3, 0.4, 1.0),
            0.7,
            0.5,
        );
        let reference = projected_solid_angle_polygon_f64(&v).abs();
        let polygon = SolidAnglePolygon::new(&v).unwrap();
        let mut estimate = Estimate::default();
        for _ in 0..200_000 {
            let s = polygon.sample([rng.uniform_f32(), rng.uniform_f32()]);
            estimate.add(s.dir.z as f64 / s.pdf as f64);
        }
        estimate.assert_mean_is(reference, 5.0, 1e-5, &format!("{n} vertices"));
    }
}

#[test]
fn invert_round_trips_samples() {
    let mut rng = Rng::new(41);
    let mut worst = [0.0f64; 2];
    for n in 3..=8 {
        for _ in 0..20 {
            let v = ellipse_polygon(
                &mut rng,
                n,
                Vec3::new(0.2, 0.1, 1.0),
                Vec3::new(0.1, -0.3, 1.0),
                0.8,
                0.5,
            );
            let polygon = SolidAnglePolygon::new(&v).unwrap();
            for _ in 0..2_000 {
                let u = [rng.uniform_f32(), rng.uniform_f32()];
                let s = polygon.sample(u);
                let back = polygon.invert(s.dir).expect("a sample is inside");
                for i in 0..2 {
                    worst[i] = worst[i].max((back[i] - u[i]).abs() as f64);
                }
            }
            assert!(polygon.invert(-Vec3::Z).is_none());
        }
    }
    assert!(
        worst[0] < 1e-4 && worst[1] < 1e-3,
        "worst round-trip error {worst:?}"
    );
}

/// Solid angle accuracy and containment per decade of Ω, from 1e-10 sr to 1 sr:
/// triangles shrunk towards a point 1 unit away. Prints the table (run with
/// `--nocapture`) and asserts bounds that pbrt-v4's method fails (4e-3 at 1e-5 sr).
#[test]
fn accuracy_per_decade_of_solid_angle() {
    let mut rng = Rng::new(51);
    std::println!("decade  median_rel_err  max_rel_err  outside_fraction");
    for decade in (-10..=0).rev() {
        let mut errors = Vec::new();
        let (mut outside, mut total) = (0u64, 0u64);
        for trial in 0..200 {
            let target = 10f64.powf(decade as f64 + rng.uniform());
            // An equilateral-ish random triangle of solid angle ~target at distance ~1.
            let size = (target * 2.0).sqrt() as f32;
            let center = rng.unit_vector_f32() * (0.5 + rng.uniform_f32());
            let normal = center + rng.unit_vector_f32() * 0.5;
            let aspect = 0.5 + 0.5 * rng.uniform_f32();
            let v = ellipse_polygon(&mut rng, 3 + (trial % 2), center, normal, size, aspect);
            let Some(polygon) = SolidAnglePolygon::new(&v) else {
                continue;
            };
            let reference = reference_solid_angle(&v);
            errors.push((polygon.solid_angle() as f64 - reference).abs() / reference);
            let p: Vec<D3> = v.iter().map(|&x| d3(x)).collect();
            let cells = PolygonCells::new(&p, 1);
            for _ in 0..200 {
                let s = polygon.sample([rng.uniform_f32(), rng.uniform_f32()]);
                total += 1;
                outside += cells.locate(d3(s.dir)).is_none() as u64;
            }
        }
        errors.sort_by(|a, b| a.partial_cmp(b).unwrap());
        let median = errors[errors.len() / 2];
        let max = *errors.last().unwrap();
        let fraction = outside as f64 / total as f64;
        std::println!("1e{decade:<4} {median:14.2e} {max:12.2e} {fraction:16.2e}");
        // What docs/polygon-lights.md states for this test (issue 16, 9: it asserted 1e-5 and 1e-4
        // while the README claimed 1e-7): medians 7e-8 to 1.1e-7, maxima 6e-7 to 4e-6. The
        // maxima exceed the report table's 7e-7 because these triangles are seen from as
        // close as 0.5 units with random normals, some nearly edge-on, where Ω is
        // ill-conditioned in the rounding of the unit vertex directions.
        assert!(
            median < 1.5e-7 && max < 5e-6,
            "decade {decade}: median {median}, max {max}"
        );
        // f32 unit vectors are spaced ~6e-8 apart, so samples within that distance of
        // an edge can land on either side: the fraction outside grows like 1/size.
        let allowed = (4e-7 / (10f64.powi(decade)).sqrt()).max(1e-4);
        assert!(
            fraction <= allowed,
            "decade {decade}: {fraction} outside (allowed {allowed})"
        );
    }
}

/// Regression (found by the fuzz target `polygon` through the Hart warps): a pentagon of
/// radius 1e5 just above the shading point, whose fan triangles have nearly antipodal
/// corners, gave directions of length 0.99957.
#[test]
fn directions_are_unit_for_a_huge_polygon_just_above_the_shading_point() {
    let v = [
        Vec3::new(-0.5, -99_998.5, 3.75),
        Vec3::new(-95_107.195, -30_902.277, 0.373_970_5),
        Vec3::new(-58_781.734, 80_901.914, -0.927_687_05),
        Vec3::new(58_775.34, 80_904.47, 1.643_874_5),
        Vec3::new(95_104.11, -30_898.133, 4.534_843_4),
    ];
    let polygon = SolidAnglePolygon::new(&v).expect("valid");
    let mut worst = 0.0f32;
    for i in 0..64 {
        for j in 0..64 {
            let u = [(i as f32 + 0.5) / 64.0, (j as f32 + 0.5) / 64.0];
            let s = polygon.sample(u);
            assert!(s.pdf > 0.0, "{u:?}");
            worst = worst.max((s.dir.length() - 1.0).abs());
        }
    }
    // Directions with | |dir|² - 1 | <= 2e-6 are kept as they are: |dir| within 1e-6.
    assert!(worst < 1.5e-6, "|dir| off by {worst}");
}

/// Regression (found by the fuzz target `polygon`): `(0, 0, ∞)` passed every edge test
/// of a polygon around the zenith and got the density `1 / Ω`.
#[test]
fn non_finite_directions_are_outside() {
    let v = [
        Vec3::new(-1.0, -1.0, 1.0),
        Vec3::new(1.0, -1.0, 1.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
    ];
    let polygon = SolidAnglePolygon::new(&v).expect("valid");
    assert!(polygon.pdf(Vec3::Z) > 0.0);
    for dir in [
        Vec3::new(0.0, 0.0, f32::INFINITY),
        Vec3::new(f32::INFINITY, f32::INFINITY, f32::INFINITY),
        Vec3::new(0.0, 0.0, f32::NAN),
    ] {
        assert_eq!(polygon.pdf(dir), 0.0, "{dir:?}");
        assert!(polygon.invert(dir).is_none(), "{dir:?}");
    }
}

/// Regression (found by the fuzz target `polygon`): vertices of z up to 3e38 and x, y
/// of a few units rescale to directions of denormal x, y, and a sample on the horizon
/// came out of length 0.973 (its renormalisation squared denormals).
#[test]
fn directions_are_unit_for_vertices_at_the_poles() {
    let v = [
        Vec3::new(-2.809_545, -4.147_937, -3.330_761e38),
        Vec3::new(3.515_491_2, 0.272_501_3, 1.378_964_7e38),
        Vec3::new(1.001_577_3, 1.107_870_3, 3.110_894_3e38),
        Vec3::new(-4.648_689_3, -3.269_245_4, -1.691_758_4e38),
    ];
    let Some(polygon) = SolidAnglePolygon::new(&v) else {
        return;
    };
    for u in [
        [ONE_MINUS_ULP, ONE_MINUS_ULP],
        [0.5, 0.5],
        [0.0, 0.0],
        [0.9, 0.1],
    ] {
        let s = polygon.sample(u);
        assert!(
            s.pdf == 0.0 || (s.dir.length() - 1.0).abs() < 1e-6,
            "{u:?}: {s:?}"
        );
    }
}

/// Which inputs take the fast path and which the careful fallbacks (and that the
/// fallbacks are what keeps the hard cases accurate: their accuracy is asserted by the
/// hard-case tests above, which all run through them).
#[test]
fn ordinary_polygons_take_the_fast_path_and_hard_ones_the_careful_fallbacks() {
    use super::{CAREFUL_PAIR_SUMS, CAREFUL_SHORT_EDGES};
    let mut rng = Rng::new(501);
    let mut fast = 0;
    for n in 3..=8 {
        for _ in 0..50 {
            let v = random_polygon_above(&mut rng, n, 0.2, 0.7);
            let polygon = SolidAnglePolygon::new(&v).expect("valid polygon");
            fast += (polygon.careful_paths() == 0) as u32;
        }
    }
    // Polygons of radius 0.2-0.9 at distance 1-2 from the shading point: vertices at
    // most about 84° apart, so every one takes the fast path.
    assert_eq!(
        fast, 300,
        "fast path taken by {fast} of 300 ordinary polygons"
    );
    // A quad 2 × 2 at 1e-6 above the shading point: its fan diagonal passes over the
    // shading point, whose opposite vertices are nearly antipodal.
    let near = [
        Vec3::new(-1.0, -1.0, 1e-6),
        Vec3::new(1.0, -1.0, 1e-6),
        Vec3::new(1.0, 1.0, 1e-6),
        Vec3::new(-1.0, 1.0, 1e-6),
    ];
    let polygon = SolidAnglePolygon::new(&near).expect("valid polygon");
    assert_eq!(
        polygon.careful_paths() & CAREFUL_PAIR_SUMS,
        CAREFUL_PAIR_SUMS
    );
    let exact = reference_solid_angle(&near);
    assert!(
        ((polygon.solid_angle() as f64 - exact) / exact).abs() < 1e-6,
        "{} vs {exact}",
        polygon.solid_angle()
    );
    // Two vertices 1e-7 apart (as clipping can leave them): the short-edge rule runs.
    let short = [
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.5, 0.0, 1.0),
        Vec3::new(0.5, 1e-7, 1.0),
        Vec3::new(0.0, 0.5, 1.0),
    ];
    let polygon = SolidAnglePolygon::new(&short).expect("valid polygon");
    assert_eq!(polygon.careful_paths(), CAREFUL_SHORT_EDGES);
    // A failed prepare reports no path.
    assert_eq!(SolidAnglePolygon::EMPTY.careful_paths(), 0);
}

/// Issue 16 (2): a polygon exactly in a plane through the shading point has solid angle
/// and projected solid angle 0. Every family rejects it (or samples nothing): planes
/// through the point at any tilt, the horizon plane around and beside it, vertical planes.
/// The coordinates are dyadic, so the inputs lie in the plane exactly. The same polygons
/// moved off the plane by 5% of their distance are accepted by every family, so the
/// test fails if a family rejects everything.
#[test]
fn polygons_in_planes_through_the_shading_point_get_no_samples_in_any_family() {
    use crate::polygon::baselines::*;
    use crate::polygon::*;
    let mut rng = Rng::new(5);
    let u = [[0.3, 0.6], [0.9, 0.1], [0.05, 0.95]];
    for i in 0..3000 {
        let kind = i % 6;
        let count = 3 + rng.below(6) as usize;
        let (cx, cy) = (
            1.0 + 3.0 * rng.uniform_f32(),
            -1.0 + 2.0 * rng.uniform_f32(),
        );
        let r = 0.5 + rng.uniform_f32();
        let dyadic = |x: f32| (x * 1024.0).round() / 1024.0;
        let in_plane = |offset: f32| -> Vec<Vec3> {
            (0..count)
                .map(|j| {
                    let a = j as f32 / count as f32 * core::f32::consts::TAU;
                    let (s, t) = (dyadic(cx + r * a.cos()), dyadic(cy + r * a.sin()));
                    let (s0, t0) = (dyadic(r * a.cos()), dyadic(r * a.sin()));
                    match kind {
                        0 => Vec3::new(s, t, -s - t + offset),  // x + y + z = 0
                        1 => Vec3::new(offset, s, t),           // x = 0
                        2 => Vec3::new(s, 2.0 * s + offset, t), // y = 2x
                        3 => Vec3::new(s, t, 0.5 * s - 0.25 * t + offset), // z = x/2 - y/4
                        4 => Vec3::new(s0, t0, offset),         // horizon, around
                        _ => Vec3::new(s, t, offset),           // horizon, beside
                    }
                })
                .collect()
        };
        for (offset, expect_light) in [(0.0, false), (0.05 * (cx + r), true)] {
            let v = in_plane(offset);
            let check = |name: &str, prepared: bool, sample: &dyn Fn([f32; 2]) -> Sample| {
                let got_light = prepared && u.iter().any(|&u| sample(u).pdf > 0.0);
                // Off the plane, the horizon-plane polygons lie above it: all
                // families see them; the others straddle or lie above the horizon, which
                // the unclipped families (and Turk, for a polygon facing away) may reject.
                if expect_light {
                    if kind >= 4 {
                        assert!(
                            got_light,
                            "{name}, kind {kind}, off the plane: no light {v:?}"
                        );
                    }
                } else {
                    assert!(!got_light, "{name}, kind {kind}: samples of {v:?}");
                }
            };
            let p = SolidAnglePolygon::new(&v);
            check("solid angle", p.is_some(), &|u| {
                p.as_ref().unwrap().sample(u)
            });
            let p = ClippedSolidAnglePolygon::new(&v);
            check("clipped", p.is_some(), &|u| p.as_ref().unwrap().sample(u));
            let p = TurkPolygon::new(&v);
            check("Turk", p.is_some(), &|u| p.as_ref().unwrap().sample(u));
            let p = ArvoPolygon::new(&v);
            check("Arvo", p.is_some(), &|u| p.as_ref().unwrap().sample(u));
            let p = HartBilinearPolygon::new(&v);
            check("Hart bilinear", p.is_some(), &|u| {
                p.as_ref().unwrap().sample(u)
            });
            let p = HartBiquadraticPolygon::new(&v);
            check("Hart biquadratic", p.is_some(), &|u| {
                p.as_ref().unwrap().sample(u)
            });
            let p = ProjectedPolygon::new(&v);
            check("projected", p.is_some(), &|u| p.as_ref().unwrap().sample(u));
            let mut p = ProjectedPolygon::EMPTY;
            let ok = p.prepare_fast_biased(&v);
            check("projected fast", ok, &|u| p.sample(u));
            let p = ArvoProjectedPolygon::new(&v);
            check("Arvo projected", p.is_some(), &|u| {
                p.as_ref().unwrap().sample(u)
            });
            let ltc = crate::brdf::ltc::Ltc::IDENTITY;
            let p = crate::polygon::LtcPolygon::new(&ltc, &v);
            check("LTC polygon", p.is_some(), &|u| {
                p.as_ref().unwrap().sample(u)
            });
        }
    }
}

/// Issue 16 (7): samples at `u` on the edges of `[0, 1)²` (0 and 1 - ulp), for quads at
/// scales from 1e-30 to 1e38. They miss the polygon by at most 8e-7 rad (measured: 5.6e-7
/// at scale 1, 7.8e-7 at 1e20, 6.3e-7 at 1e38), more than the 1.3e-7 of random `u` that
/// docs/contract.md used to state for every sample: asserted below 1e-6, as the contract
/// now says.
#[test]
fn samples_at_the_edges_of_u_stay_within_1e_6_rad_at_every_scale() {
    let mut rng = Rng::new(9);
    let ulp_below_one = crate::sample::ONE_MINUS_ULP;
    let mut worst = [0.0f64; 4];
    for _ in 0..2000 {
        let center = rng.unit_vector_f32();
        let center = Vec3::new(center.x, center.y, center.z.abs() + 0.1) * 2.0;
        let normal = center + rng.unit_vector_f32();
        let radius = 0.5 + rng.uniform_f32();
        let v = ellipse_polygon(&mut rng, 4, center, normal, radius, 0.7);
        for (si, scale) in [1.0f32, 1e20, 1e38, 1e-30].iter().enumerate() {
            let w: Vec<Vec3> = v.iter().map(|&p| p * *scale).collect();
            let Some(p) = SolidAnglePolygon::new(&w) else {
                continue;
            };
            let d: Vec<D3> = w.iter().map(|&x| d3(x)).collect();
            let sign = if dot(d[0], cross(d[1], d[2])) > 0.0 {
                1.0
            } else {
                -1.0
            };
            for u in [
                [0.0, 0.0],
                [0.0, ulp_below_one],
                [ulp_below_one, 0.0],
                [ulp_below_one, ulp_below_one],
                [0.5, ulp_below_one],
                [ulp_below_one, 0.5],
                [0.0, 0.5],
            ] {
                let s = p.sample(u);
                if s.pdf == 0.0 {
                    continue;
                }
                let dir = normalize(d3(s.dir));
                let mut out = 0.0f64;
                for i in 0..d.len() {
                    let n = normalize(cross(d[i], d[(i + 1) % d.len()]));
                    let side = sign * dot(dir, n);
                    out = out.max(-side);
                }
                if out > worst[si] {
                    worst[si] = out;
                }
            }
        }
    }
    assert!(
        worst.iter().all(|&w| w < 1e-6),
        "worst outside by scale 1, 1e20, 1e38, 1e-30: {worst:?}"
    );
    // The edges of u reach the polygon's boundary: the misses are rounding, not zero.
    assert!(worst.iter().all(|&w| w > 0.0));
}

/// Issue 16 (1): on polygons of about 1e-9 sr (angular radius 3e-6 to 4e-5 rad, 3 to 8
/// vertices, so that every edge is shorter than the short-edge rule's 1.5e-5 rad), `pdf`
/// is 0 for directions farther outside an edge than the rounding of an `f32` direction
/// (5e-7 rad) plus 1e-4 of the angular radius: checked at 21 points beyond every edge, at
/// 1.5 times that distance. With the rule's fixed reach of 2.4e-4 rad, `pdf` reached up
/// to 2.4e-5 rad outside such polygons and `∫ pdf dω` was up to 3.1; the quadrature's
/// `∫ pdf dω` must now stay within the mass of the allowed band (`P · bound / Ω`; these
/// polygons are only 10 to 300 `f32` ulps of a direction across).
#[test]
fn tiny_polygons_keep_their_pdf_inside() {
    let mut rng = Rng::new(164);
    let mut short = 0;
    for trial in 0..120 {
        let n = 3 + trial % 6;
        let v = random_polygon_above(&mut rng, n, 1.5e-5, 3e-5);
        let polygon = SolidAnglePolygon::new(&v).expect("prepared");
        short += (polygon.careful_paths() & CAREFUL_SHORT_EDGES != 0) as usize;
        let vd: Vec<D3> = v.iter().map(|&p| normalize(d3(p))).collect();
        let mut c = [0.0; 3];
        for p in &vd {
            c = add(c, *p);
        }
        let c = normalize(c);
        let radius = vd.iter().map(|p| norm(sub(*p, c))).fold(0.0, f64::max);
        let bound = 5e-7 + 1e-4 * radius;
        let sigma = (1..n - 1)
            .map(|k| dot(vd[0], cross(sub(vd[k], vd[0]), sub(vd[k + 1], vd[0]))))
            .sum::<f64>()
            .signum();
        let mut perimeter = 0.0;
        for i in 0..n {
            let (a, b) = (vd[i], vd[(i + 1) % n]);
            perimeter += norm(sub(b, a));
            let outward = scale(normalize(cross(a, sub(b, a))), -sigma);
            for s in 0..=20 {
                let t = s as f64 / 20.0;
                let on_edge = normalize(add(scale(a, 1.0 - t), scale(b, t)));
                let d = normalize(add(on_edge, scale(outward, 1.5 * bound)));
                let dir = Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32);
                assert_eq!(
                    polygon.pdf(dir),
                    0.0,
                    "trial {trial}: {t} along edge {i}: {v:?}"
                );
            }
        }
        let (integral, _) = integrate_pdf_near_polygon(&v, 1, |d| polygon.pdf(d));
        let band = perimeter * bound / polygon.solid_angle() as f64;
        assert!(
            (integral - 1.0).abs() <= band,
            "trial {trial}: ∫ pdf = {integral}, band {band}: {v:?}"
        );
    }
    assert!(short > 60, "{short} polygons took the short-edge rule");
}

/// Issue 16 (1): every sample, at random `u` and at the edges of `u`, has
/// `pdf(sample.dir) == sample.pdf` bit for bit (with no slack, 8 to 14 of these 20,000
/// draws per polygon fell outside by rounding and got `pdf = 0`, at every size), and
/// `∫ pdf dω` by quadrature stays within 1e-4 of 1 (measured 2.6e-5 at most; at 8e-10
/// sr 3.4e-5, where the rounded edge planes with plain dot products gave 4.3e-4 too much
/// and exact planes with plain dot products 3.4e-4 too little: `checks_samples == 2`).
/// The polygons below 1e-2 sr and the sliver take the sample test (`checks_samples`), the
/// others do not; those of 1e-4 sr and below also the exact planes.
#[test]
fn every_sample_has_its_pdf_at_any_size() {
    let mut rng = Rng::new(61);
    for (name, v, tolerance, checks) in [
        ("1.4 sr", scaled_quad(3.0, 0.1), 1e-4, false),
        ("0.3 sr", scaled_quad(0.3, 0.1), 1e-4, false),
        ("sliver", scaled_quad(0.1, 0.9), 1e-4, true),
        ("1e-2 sr", scaled_quad(5e-2, 0.1), 1e-4, true),
        ("1e-4 sr", scaled_quad(5e-3, 0.1), 1e-4, true),
        ("1e-6 sr", scaled_quad(5e-4, 0.1), 1e-4, true),
        ("8e-10 sr", scaled_quad(1.6e-5, 0.1), 1e-4, true),
    ] {
        let p = SolidAnglePolygon::new(&v).unwrap();
        assert_eq!(p.checks_samples != 0, checks, "{name}");
        let exact_planes =
            name.starts_with("1e-4") || name.starts_with("1e-6") || name.starts_with("8e-10");
        assert_eq!(p.checks_samples == 2, exact_planes, "{name}");
        assert_pdf_integrates_to_one_and_samples_have_their_pdf(
            name,
            &v,
            tolerance,
            &mut rng,
            |u| p.sample(u),
            |d| p.pdf(d),
        );
    }
}

/// The C entry point's split (issue 15): `sample_common` gives `sample`'s sample bit for
/// bit wherever it gives one, takes every draw of ordinary polygons (random ones of 3 to
/// 8 vertices, and `u` at the edges of `[0, 1)`), and leaves to the rare path `u` outside
/// `[0, 1)²` (NaN and -0 included), the empty value, the narrow polygons whose samples are tested (`checks_samples`) and the
/// directions renormalised in the huge pentagon just above the shading point.
#[test]
fn sample_common_takes_ordinary_draws_and_leaves_the_rare_ones() {
    let mut rng = Rng::new(15);
    let edges = [0.0, 1e-30, 0.5, ONE_MINUS_ULP, 1.0, -1.0, -0.0, f32::NAN];
    let mut narrow = 0;
    for n in 3..=MAX_POLYGON_VERTICES {
        for _ in 0..20 {
            let v = random_polygon_above(&mut rng, n, 0.6, 1.0);
            let p = SolidAnglePolygon::new(&v).expect("valid");
            if p.checks_samples != 0 {
                // A narrow one (an edge longer than 5 Ω): its samples are tested.
                assert_eq!(p.sample_common([0.5, 0.5]), None);
                narrow += 1;
                continue;
            }
            for _ in 0..50 {
                let u = [rng.uniform_f32(), rng.uniform_f32()];
                assert_eq!(p.sample_common(u), Some(p.sample(u)), "{v:?} {u:?}");
            }
            for u0 in edges {
                for u1 in edges {
                    // `u` outside [0, 1)² (clamped by `sample`) takes the rare path.
                    let inside = [u0, u1].iter().all(|u| (0.0..1.0).contains(u))
                        && u0.is_sign_positive()
                        && u1.is_sign_positive();
                    let expected = inside.then(|| p.sample([u0, u1]));
                    assert_eq!(p.sample_common([u0, u1]), expected, "{u0} {u1}");
                }
            }
        }
    }
    std::println!("{narrow} of 120 polygons narrow");
    assert!(narrow <= 40, "{narrow} of 120 polygons narrow");
    assert_eq!(SolidAnglePolygon::EMPTY.sample_common([0.5, 0.5]), None);
    let sliver = SolidAnglePolygon::new(&scaled_quad(0.1, 0.9)).unwrap();
    assert_ne!(sliver.checks_samples, 0);
    assert_eq!(sliver.sample_common([0.5, 0.5]), None);
    let huge = SolidAnglePolygon::new(&[
        Vec3::new(-0.5, -99_998.5, 3.75),
        Vec3::new(-95_107.195, -30_902.277, 0.373_970_5),
        Vec3::new(-58_781.734, 80_901.914, -0.927_687_05),
        Vec3::new(58_775.34, 80_904.47, 1.643_874_5),
        Vec3::new(95_104.11, -30_898.133, 4.534_843_4),
    ])
    .unwrap();
    assert_eq!(huge.checks_samples, 0);
    let (mut common, mut rare) = (0, 0);
    for i in 0..64 {
        for j in 0..64 {
            let u = [(i as f32 + 0.5) / 64.0, (j as f32 + 0.5) / 64.0];
            match huge.sample_common(u) {
                Some(s) => {
                    assert_eq!(s, huge.sample(u), "{u:?}");
                    common += 1;
                }
                None => rare += 1,
            }
        }
    }
    std::println!("huge pentagon: {common} common, {rare} rare");
    assert!(common > 0 && rare > 0, "{common} common, {rare} rare");
}

/// The triangle and quad sizes (issue 15, 3): the chi-square test of each against the
/// cells' exact f64 solid angles, on triangles and quads in both windings.
#[test]
fn the_triangle_and_quad_sizes_sample_uniformly_in_solid_angle() {
    let mut rng = Rng::new(300);
    for trial in 0..3 {
        let triangle = random_polygon_above(&mut rng, 3, 0.3, 1.0);
        let quad = random_polygon_above(&mut rng, 4, 0.3, 1.0);
        for (v, what) in [
            (triangle.clone(), "triangle"),
            (reversed(&triangle), "reversed"),
        ] {
            assert_uniform_in_solid_angle_of::<3, 1>(&v, 300_000, 60 + trial, what);
            assert_uniform_in_solid_angle_of::<4, 2>(&v, 300_000, 70 + trial, what);
        }
        for (v, what) in [(quad.clone(), "quad"), (reversed(&quad), "reversed quad")] {
            assert_uniform_in_solid_angle_of::<4, 2>(&v, 300_000, 80 + trial, what);
        }
    }
}

/// Everything the three sizes compute for the same triangle or quad is the same, bit for
/// bit: the solid angle, every sample, `pdf` (inside, outside, on the boundary's slack)
/// and the inverse, over ordinary polygons and the hard cases (1e-10 sr, vertices 1e5
/// away, near hemispheres just above the shading point, the shading point 1e-6 off the
/// plane, duplicate vertices, both windings), and the failures are the same failures.
#[test]
fn the_three_sizes_give_the_same_bits() {
    let mut rng = Rng::new(301);
    let mut polygons: Vec<Vec<Vec3>> = Vec::new();
    for n in [3, 4] {
        for _ in 0..200 {
            polygons.push(random_polygon_above(&mut rng, n, 0.01, 2.0));
        }
        for scale in [1e-5f32, 1e-3, 1e5] {
            let center = rng.unit_vector_f32() * (0.5 + rng.uniform_f32());
            let normal = center + rng.unit_vector_f32() * 0.5;
            polygons.push(ellipse_polygon(
                &mut rng,
                n,
                center * scale.max(1.0),
                normal,
                scale.min(1.0) * 0.3,
                0.7,
            ));
        }
        for height in [1e-6f32, 1e-3, 0.0, -1e-6] {
            polygons.push(ellipse_polygon(
                &mut rng,
                n,
                Vec3::new(0.1, 0.0, height),
                Vec3::Z,
                50.0,
                0.8,
            ));
        }
    }
    polygons.push(vec![
        Vec3::new(-1.0, -1.0, 1.0),
        Vec3::new(1.0, -1.0, 1.0),
        Vec3::new(1.0, -1.0, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
    ]);
    polygons.push(vec![
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(0.0, 1.0, 1.0),
    ]);
    let reversed_ones: Vec<Vec<Vec3>> = polygons.iter().map(|v| reversed(v)).collect();
    polygons.extend(reversed_ones);
    let mut compared = [0usize; 2];
    for v in &polygons {
        let big = SolidAnglePolygon::new(v);
        let quad = SolidAngleQuad::new(v);
        let triangle = SolidAngleTriangle::new(v);
        assert_eq!(big.is_some(), quad.is_some(), "{v:?}");
        if v.len() == 3 {
            assert_eq!(big.is_some(), triangle.is_some(), "{v:?}");
        } else {
            assert!(
                triangle.is_none(),
                "a triangle's storage took {} vertices",
                v.len()
            );
        }
        let Some(big) = big else {
            continue;
        };
        compared[v.len() - 3] += 1;
        let quad = quad.unwrap();
        let same = |a: Sample, b: Sample, what: &str| {
            assert_eq!(
                (a.dir.to_array().map(f32::to_bits), a.pdf.to_bits()),
                (b.dir.to_array().map(f32::to_bits), b.pdf.to_bits()),
                "{what}: {a:?} vs {b:?} for {v:?}"
            );
        };
        assert_eq!(big.solid_angle().to_bits(), quad.solid_angle().to_bits());
        assert_eq!(big.careful_paths(), quad.careful_paths());
        for k in 0..64 {
            let u = if k < 4 {
                [
                    [0.0, 0.0],
                    [ONE_MINUS_ULP, ONE_MINUS_ULP],
                    [0.5, 1.0],
                    [f32::NAN, -1.0],
                ][k]
            } else {
                [rng.uniform_f32(), rng.uniform_f32()]
            };
            let s = big.sample(u);
            same(s, quad.sample(u), "quad sample");
            // Directions inside, at the sample, and nearby (some outside).
            let nearby = (s.dir + rng.unit_vector_f32() * 1e-3).normalize();
            for dir in [s.dir, nearby, rng.unit_vector_f32()] {
                assert_eq!(
                    big.pdf(dir).to_bits(),
                    quad.pdf(dir).to_bits(),
                    "pdf {dir:?}"
                );
                assert_eq!(big.invert(dir), quad.invert(dir), "invert {dir:?}");
            }
            if let Some(triangle) = &triangle {
                same(s, triangle.sample(u), "triangle sample");
                for dir in [s.dir, nearby] {
                    assert_eq!(big.pdf(dir).to_bits(), triangle.pdf(dir).to_bits());
                    assert_eq!(big.invert(dir), triangle.invert(dir));
                }
            }
        }
    }
    // Most of the polygons above prepare (a few lie in the shading point's plane).
    assert!(compared[0] > 200 && compared[1] > 200, "{compared:?}");
}

/// A size takes no more vertices than it stores, and writes its empty value then.
#[test]
fn the_triangle_and_quad_sizes_reject_more_vertices_than_they_store() {
    let mut rng = Rng::new(302);
    for n in [4, 5, 8] {
        let v = random_polygon_above(&mut rng, n, 0.3, 1.0);
        let mut triangle = SolidAngleTriangle::new(&v[..3]).unwrap();
        assert!(!triangle.prepare(&v));
        assert_eq!(triangle, SolidAngleTriangle::EMPTY);
        if n > 4 {
            let mut quad = SolidAngleQuad::new(&v[..4]).unwrap();
            assert!(!quad.prepare(&v));
            assert_eq!(quad, SolidAngleQuad::EMPTY);
        }
    }
}

/// `VertexGroups::slots` (the shifted lanes of the fan and the edges, taken from two
/// groups by shuffles) gives the lanes that the working set in memory holds at every
/// shift the preparation reads (slots `start..start + 4` for `start` 0 to 8), for 3 to 8
/// vertices, and the unit directions that `write_units` stores are the positions over
/// the lengths of the memory form (`VertexLanes`, built from the same groups).
#[test]
fn shifted_slots_are_the_working_set_in_memory() {
    let mut rng = Rng::new(3535);
    for case in 0..2_000 {
        let count = 3 + case % 6;
        let vertices: Vec<Vec3> = (0..count)
            .map(|_| {
                Vec3::new(
                    rng.range(-2.0, 2.0),
                    rng.range(-2.0, 2.0),
                    rng.range(0.5, 3.0),
                )
            })
            .collect();
        let (raw, factor) = gather_and_rescale(&vertices, count);
        let (groups, _) = VertexGroups::new(raw, factor.unwrap(), count).unwrap();
        let memory = groups.lanes();
        for start in 0..=2 * LANES {
            let lanes = |slots: &[f32; SLOTS]| Vec4::from_slice(&slots[start..start + LANES]);
            // The lanes of slots up to `count` (slot `count` closes the polygon); the
            // preparation's masks leave out the lanes of slots past it, which `slots`
            // may fill with any finite value (triangles and quads: vertex 0 again).
            let read = |lane: Vec4, memory: Vec4| {
                for j in 0..LANES {
                    if start + j <= count {
                        assert_eq!(lane.to_array()[j], memory.to_array()[j], "{start} {j}");
                    } else {
                        assert!(lane.to_array()[j].is_finite());
                    }
                }
            };
            let [x, y, z] = groups.slots3(|g| g.position, start, count);
            for (c, lane) in [x, y, z].into_iter().enumerate() {
                read(lane, lanes(&memory.position[c]));
            }
            let length = groups.slots(|g| g.length, start, count);
            read(length, lanes(&memory.length));
        }
        // Slot `count` closes the polygon: vertex 0 again.
        assert_eq!(memory.position(count), memory.position(0));
        let mut units = [Vec3::ZERO; MAX_POLYGON_VERTICES];
        groups.write_units(&mut units, count);
        for (i, unit) in units.iter().enumerate().take(count) {
            let (p, l) = (memory.position(i), memory.length[i]);
            assert_eq!(unit.to_array(), [p.x / l, p.y / l, p.z / l], "{i}");
        }
    }
}

/// Algorithm 5 in `f64` (Peters' closed form, with `G1 = v0·v2 + v1·v2`), on the
/// prepared unit vertices of fan triangle `k` taken as exact: the direction at solid
/// angle `local` from the first edge and at `u1` along the new edge.
fn algorithm_5_f64(polygon: &SolidAnglePolygon, k: usize, local: f64, u1: f64) -> D3 {
    let (v0, v1, v2) = (
        d3(polygon.vertices[k + 1]),
        d3(polygon.vertices[0]),
        d3(polygon.vertices[k + 2]),
    );
    let g0 = dot(v0, cross(v1, v2)).abs();
    let (g1, g2) = (dot(v0, v2) + dot(v1, v2), 1.0 + dot(v0, v1));
    let (sin_half, cos_half) = (0.5 * local).sin_cos();
    let r = add(
        scale(v0, g0 * cos_half - g1 * sin_half),
        scale(v2, g2 * sin_half),
    );
    let new_vertex = sub(scale(r, 2.0 * dot(v0, r) / dot(r, r)), v0);
    let new_vertex = normalize(new_vertex);
    let s_new = dot(v1, new_vertex);
    let s = (1.0 - u1) + u1 * s_new;
    let t = ((1.0 - s * s) / (1.0 - s_new * s_new)).max(0.0).sqrt();
    normalize(add(scale(v1, s - t * s_new), scale(new_vertex, t)))
}

/// The direction of fan triangle `k` as sampling computed it before issue 15's stop 38
/// (the reflection's dot products of r and `a = |v1 - v2'|²/2` in vectors, then
/// `t' = sqrt(ξ1 (b + (1 - ξ1) a) / b)` and `v1 (s - t' s') + t' v2'`), for the
/// comparison of the errors.
fn direction_before_stop_38(polygon: &SolidAnglePolygon, k: usize, local: f32, u1: f32) -> Vec3 {
    let (v0, v1) = (
        Vec3A::from(polygon.vertices[k + 1]),
        Vec3A::from(polygon.vertices[0]),
    );
    let outer_sum = Vec3A::from(polygon.outer_sum[k]);
    let (g0, g1_plus_g2, g2) = (polygon.g0[k], polygon.g1_plus_g2[k], polygon.g2[k]);
    let (sin_half, cos_half) = crate::math::sin_cos_0_to_pi(0.5 * local);
    let r = v0 * (g0 * cos_half - g1_plus_g2 * sin_half) + outer_sum * (g2 * sin_half);
    let new_vertex = r * (2.0 * v0.dot(r) / r.length_squared()) - v0;
    let a = 0.5 * (v1 - new_vertex).length_squared();
    let b = 0.5 * (v1 + new_vertex).length_squared();
    let one_plus_s = b + (1.0 - u1) * a;
    let s = 1.0 - u1 * a;
    let s_new = b - 1.0;
    let t = crate::math::sqrtf(u1 * one_plus_s / b.max(f32::MIN_POSITIVE));
    Vec3::from(v1 * (s - t * s_new) + new_vertex * t)
}

/// The sampled direction of a fan triangle against [`algorithm_5_f64`] on the same
/// (rounded) unit vertices, for triangles from 1e-3 sr to nearly 2π (a third of them
/// seen from just above their plane), and against the form that sampling had before
/// issue 15's stop 38 ([`direction_before_stop_38`]): at the median, the 99th and
/// 99.99th percentiles and the maximum, the angle to the `f64` direction is at most
/// that of the earlier form (plus 2e-8 rad, a third of an `f32` direction's rounding),
/// and so is `| |dir| - 1 |`, which stays below 2e-6 (measured: angles 8.6e-8 / 3.3e-6 /
/// 6.5e-5 / 6.8e-5 rad against 1.4e-7 / 3.4e-6 / 6.6e-5 / 6.8e-5 before, the large
/// ones in the triangles seen from just above their plane, where the `f64` reference
/// on rounded unit vertices is itself that far from the sampler's exact fan terms;
/// lengths 4.5e-8 / 3.7e-7 / 9.6e-7 / 9.9e-7 against 5.8e-8 / 6.5e-7 / 5.5e-6 /
/// 8.2e-6 before). Where `sample_common` returns a sample, it is this direction.
#[test]
fn sampled_directions_match_algorithm_5_in_f64() {
    let mut rng = Rng::new(0x05a3_8f64);
    let mut errors = Vec::new();
    let (mut errors_before, mut length_errors, mut length_errors_before) =
        (Vec::new(), Vec::new(), Vec::new());
    let mut worst = (0.0f64, Vec3::ZERO, 0.0f32, 0.0f32);
    for i in 0..4_000 {
        // A third small and far, a third around 1 sr, a third seen from just above.
        let height = match i % 3 {
            0 => 10f32.powf(rng.range(0.5, 1.5)),
            1 => rng.range(0.5, 2.0),
            _ => 10f32.powf(rng.range(-3.0, -1.0)),
        };
        let vertices = random_polygon_above(&mut rng, 3, 0.3, 1.0);
        let vertices: Vec<Vec3> = vertices
            .iter()
            .map(|v| Vec3::new(v.x, v.y, (v.z - 1.0) * 0.2 + height))
            .collect();
        let Some(polygon) = SolidAnglePolygon::new(&vertices) else {
            continue;
        };
        if polygon.solid_angle() < 1e-3 || polygon.checks_samples != 0 {
            continue;
        }
        let omega = polygon.triangle_solid_angle(0);
        for _ in 0..50 {
            let (u0, u1) = (rng.uniform_f32(), rng.uniform_f32());
            let local = u0 * omega;
            let sample = polygon.sample_in_triangle(0, local, u1);
            let reference = algorithm_5_f64(&polygon, 0, local as f64, u1 as f64);
            let dir = d3(sample.dir);
            let error = norm(cross(normalize(dir), reference)).asin();
            if error > worst.0 {
                worst = (error, polygon.vertices[2], local, u1);
            }
            errors.push(error);
            let before = d3(direction_before_stop_38(&polygon, 0, local, u1));
            errors_before.push(norm(cross(normalize(before), reference)).asin());
            length_errors.push((dot(dir, dir).sqrt() - 1.0).abs());
            length_errors_before.push((dot(before, before).sqrt() - 1.0).abs());
            // One fan triangle: the common path draws the same direction from `u`.
            if let Some(common) = polygon.sample_common([u0, u1]) {
                assert_eq!(common.dir, sample.dir);
                assert!((dot(dir, dir) - 1.0).abs() <= 2.1e-6);
            }
        }
    }
    let quantiles = |mut e: Vec<f64>| {
        e.sort_by(f64::total_cmp);
        let n = e.len();
        [e[n / 2], e[n * 99 / 100], e[n * 9999 / 10000], e[n - 1]]
    };
    let show = |q: [f64; 4]| q.map(|x| std::format!("{x:.2e}")).join(" / ");
    let count = errors.len();
    let (angle, angle_before) = (quantiles(errors), quantiles(errors_before));
    let (length, length_before) = (quantiles(length_errors), quantiles(length_errors_before));
    std::println!(
        "{count} samples; angle to f64 (median / 99% / 99.99% / max): {}, before stop 38 {}; \
         | |dir| - 1 |: {}, before {}; worst {worst:?}",
        show(angle),
        show(angle_before),
        show(length),
        show(length_before),
    );
    assert!(count > 40_000, "{count}");
    for (now, before) in angle
        .iter()
        .zip(angle_before)
        .chain(length.iter().zip(length_before))
    {
        assert!(
            *now <= before + 2e-8,
            "{angle:?} {angle_before:?} {length:?} {length_before:?}"
        );
    }
    assert!(length[3] < 2e-6, "{length:?}");
}

/// `FanLanes::compute_one` (a triangle's fan triangle and a heptagon's fifth in scalar
/// arithmetic), and `FanLanes::compute_quad` (a quad's two), give
/// the bits of the lanes' `FanLanes::compute` for the same triangle: `G0` with its sign,
/// `G1 + G2`, `G2`, `v0 + v2` and the flags of the careful forms, for every fan triangle
/// of triangles, quads, heptagons and octagons (not only a heptagon's fifth) of every kind: ordinary ones in both
/// windings, tiny ones far away (products that cancel: the error-free determinant), ones
/// close over the shading point (pairs more than 90° apart: the wide-pair flag) and ones
/// within rounding of a plane through the shading point (the flat flag). And that a
/// heptagon's prepare stores these bits for its fifth triangle (where no careful form
/// replaces them).
#[test]
fn a_lone_fan_triangle_is_prepared_as_in_lanes() {
    let mut rng = Rng::new(3901);
    let mut cases: Vec<Vec<Vec3>> = Vec::new();
    for n in [3, 4, 7, 8] {
        for _ in 0..200 {
            let v = random_polygon_above(&mut rng, n, 0.2, 0.7);
            cases.push(reversed(&v));
            cases.push(v);
            // Tiny and far: 1e-5 across at 1e4.
            let far = random_polygon_above(&mut rng, n, 1e-5, 1e-5);
            cases.push(far.iter().map(|&p| p * 1e4).collect());
            // Close over the shading point: vertices up to nearly antipodal.
            let near = random_polygon_above(&mut rng, n, 2.0, 3.0);
            cases.push(
                near.iter()
                    .map(|&p| Vec3::new(p.x, p.y, 1e-3 * p.z))
                    .collect(),
            );
        }
        // In a plane through the shading point up to rounding (the plane z = 0.3 x + 0.7 y
        // evaluated in f32).
        for _ in 0..50 {
            let v: Vec<Vec3> = (0..n)
                .map(|i| {
                    let t = i as f32 / n as f32 * core::f32::consts::TAU;
                    let (x, y) = (2.0 + t.cos(), 1.0 + t.sin() * (0.5 + rng.uniform_f32()));
                    Vec3::new(x, y, 0.3 * x + 0.7 * y)
                })
                .collect();
            cases.push(v);
        }
    }
    let (mut flat, mut wide) = (0, 0);
    let (mut triangle_flat, mut triangle_wide) = (0, 0);
    let (mut quad_flat, mut quad_wide) = (0, 0);
    for v in &cases {
        let count = v.len();
        let triangles = count - 2;
        let (raw, factor) = gather_and_rescale(v, count);
        let (groups, reflection) =
            VertexGroups::new(raw, factor.expect("finite"), count).expect("no zero vertex");
        let apex = groups.apex();
        let mut lanes_polygon = SolidAnglePolygon::EMPTY;
        let mut lanes = FanLanes::default();
        let mut angles: FanAngles = [0.0; 2 * LANES];
        lanes.compute(&mut lanes_polygon, &mut angles, &groups, apex, 0, triangles);
        if triangles > LANES {
            lanes.compute(
                &mut lanes_polygon,
                &mut angles,
                &groups,
                apex,
                LANES,
                triangles,
            );
        }
        for k in 0..triangles {
            let mut one_polygon = SolidAnglePolygon::EMPTY;
            let mut one = FanLanes::default();
            one.compute_one(&mut one_polygon, &groups, apex, k);
            let what = format!("{v:?}, triangle {k}");
            assert_eq!(
                one.signed_g0[k].to_bits(),
                lanes.signed_g0[k].to_bits(),
                "{what}"
            );
            // `signed_g0` is σ times the determinant that the reflection gives, divided
            // by the lengths as before σ left the division: `(σ a) / b = σ (a / b)`.
            let slot = |field: fn(&SlotGroup) -> Vec4, i: usize| groups.slot(field, i);
            let (b, c) = (k + 1, k + 2);
            let signed = difference_of_products_unless_half_cancels(
                slot(|g| g.reflected[0], b),
                slot(|g| g.reflected[1], c),
                slot(|g| g.reflected[1], b),
                slot(|g| g.reflected[0], c),
            ) * reflection.sigma
                / (slot(|g| g.length, b) * slot(|g| g.length, c));
            assert_eq!(
                (one.signed_g0[k] * reflection.sigma).to_bits(),
                signed.to_bits(),
                "{what}"
            );
            assert_eq!(
                one_polygon.g1_plus_g2[k].to_bits(),
                lanes_polygon.g1_plus_g2[k].to_bits(),
                "{what}"
            );
            assert_eq!(
                one_polygon.g2[k].to_bits(),
                lanes_polygon.g2[k].to_bits(),
                "{what}"
            );
            let bits = |s: Vec3| s.to_array().map(f32::to_bits);
            assert_eq!(
                bits(one_polygon.outer_sum[k]),
                bits(lanes_polygon.outer_sum[k]),
                "{what}"
            );
            // The sample's terms of the fan triangle, `m` and `|v0 + v2|² - m²`.
            let outer = |p: &SolidAnglePolygon, k: usize| {
                [p.outer_along[k], p.outer_across2[k]].map(f32::to_bits)
            };
            assert_eq!(outer(&one_polygon, k), outer(&lanes_polygon, k), "{what}");
            assert_eq!(one.maybe_flat, lanes.maybe_flat & (1 << k), "{what}");
            assert_eq!(one.wide_pairs, lanes.wide_pairs & (1 << k), "{what}");
            flat += (one.maybe_flat != 0) as u32;
            wide += (one.wide_pairs != 0) as u32;
            // A triangle's prepare takes `compute_triangle`, the pair sums in lanes: the
            // same values and flags bit for bit.
            if count == 3 {
                let mut triangle_polygon = SolidAnglePolygon::EMPTY;
                let mut triangle = FanLanes::default();
                triangle.compute_triangle(&mut triangle_polygon, &groups);
                assert_eq!(
                    triangle.signed_g0[0].to_bits(),
                    one.signed_g0[0].to_bits(),
                    "{what}"
                );
                // `compute_triangle` stores `G0 = |det|` itself (the loop of
                // `prepare_or_fail` leaves a triangle's alone).
                assert_eq!(
                    triangle_polygon.g0[0].to_bits(),
                    one.signed_g0[0].abs().to_bits(),
                    "{what}"
                );
                assert_eq!(
                    triangle_polygon.g1_plus_g2[0].to_bits(),
                    one_polygon.g1_plus_g2[0].to_bits(),
                    "{what}"
                );
                assert_eq!(
                    triangle_polygon.g2[0].to_bits(),
                    one_polygon.g2[0].to_bits(),
                    "{what}"
                );
                assert_eq!(
                    bits(triangle_polygon.outer_sum[0]),
                    bits(one_polygon.outer_sum[0]),
                    "{what}"
                );
                assert_eq!(
                    outer(&triangle_polygon, 0),
                    outer(&one_polygon, 0),
                    "{what}"
                );
                assert_eq!(triangle.maybe_flat, one.maybe_flat, "{what}");
                assert_eq!(triangle.wide_pairs, one.wide_pairs, "{what}");
                triangle_flat += (triangle.maybe_flat != 0) as u32;
                triangle_wide += (triangle.wide_pairs != 0) as u32;
            }
        }
        // A quad's prepare takes `compute_quad`, the pair sums of both triangles in one
        // group of lanes: the lanes' values and flags bit for bit.
        if count == 4 {
            let mut quad_polygon = SolidAnglePolygon::EMPTY;
            let mut quad = FanLanes::default();
            quad.compute_quad(&mut quad_polygon, &groups);
            let what = format!("{v:?}");
            let words = |p: &SolidAnglePolygon, f: &FanLanes| {
                let mut words = std::vec![f.maybe_flat, f.wide_pairs];
                for k in 0..2 {
                    words.extend(
                        [
                            f.signed_g0[k],
                            p.g1_plus_g2[k],
                            p.g2[k],
                            p.outer_along[k],
                            p.outer_across2[k],
                        ]
                        .map(f32::to_bits),
                    );
                    words.extend(p.outer_sum[k].to_array().map(f32::to_bits));
                }
                words
            };
            assert_eq!(
                words(&quad_polygon, &quad),
                words(&lanes_polygon, &lanes),
                "{what}"
            );
            quad_flat += (quad.maybe_flat != 0) as u32;
            quad_wide += (quad.wide_pairs != 0) as u32;
        }
        // A heptagon's prepare takes `compute_one` for its fifth triangle, a triangle's
        // for its one: the prepared values are the lanes'.
        if count == 7 || count == 3 {
            let mut prepared = SolidAnglePolygon::EMPTY;
            let k = if count == 7 { LANES } else { 0 };
            if prepared.prepare(v) && lanes.wide_pairs & (1 << k) == 0 {
                assert_eq!(
                    prepared.g1_plus_g2[k].to_bits(),
                    lanes_polygon.g1_plus_g2[k].to_bits()
                );
                assert_eq!(prepared.g2[k].to_bits(), lanes_polygon.g2[k].to_bits());
            }
        }
    }
    // Each kind was met (the careful flags many times).
    assert!(flat > 50 && wide > 50, "flat {flat}, wide {wide}");
    assert!(
        triangle_flat > 10 && triangle_wide > 10,
        "triangles: flat {triangle_flat}, wide {triangle_wide}"
    );
    assert!(
        quad_flat > 10 && quad_wide > 10,
        "quads: flat {quad_flat}, wide {quad_wide}"
    );
}

/// `rescale_factor_in_lanes` gives `rescale_factor_of_lanes`'s factor in every lane, bit
/// for bit, and `None` in the same cases: every biased exponent from subnormal (0) to the
/// largest finite (254) in each lane, with random mantissas and the other lanes random
/// magnitudes below it, zeros (all lanes, or some), infinities and NaNs.
#[test]
fn rescale_factor_in_lanes_is_the_scalar_one() {
    let mut rng = Rng::new(4501);
    let bits4 = |v: Vec4| v.to_array().map(f32::to_bits);
    let magnitude = |rng: &mut Rng, exponent: u32| {
        let mantissa = rng.next_u64() as u32 & 0x007F_FFFF;
        f32::from_bits((exponent << 23) | mantissa)
    };
    let mut cases: Vec<Vec4> = vec![
        Vec4::ZERO,
        Vec4::new(0.0, 0.0, f32::from_bits(1), 0.0),
        Vec4::splat(f32::MAX),
        Vec4::new(1.0, f32::INFINITY, 2.0, 3.0),
        Vec4::new(f32::NAN, 1.0, 2.0, 3.0),
        Vec4::new(0.0, 0.0, 0.0, f32::MIN_POSITIVE),
        Vec4::new(0.0, 0.0, 0.0, f32::MIN_POSITIVE * 2.0),
    ];
    for exponent in 0..=254u32 {
        for lane in 0..4 {
            for _ in 0..8 {
                let mut v = [0.0f32; 4];
                for (j, x) in v.iter_mut().enumerate() {
                    *x = if j == lane {
                        magnitude(&mut rng, exponent)
                    } else {
                        match rng.below(3) {
                            0 => 0.0,
                            1 => {
                                let below = rng.below(u64::from(exponent) + 1) as u32;
                                magnitude(&mut rng, below)
                            }
                            _ => magnitude(&mut rng, exponent),
                        }
                    };
                }
                cases.push(Vec4::from_array(v));
            }
        }
    }
    for largest in cases {
        let finite = largest.cmplt(Vec4::splat(f32::INFINITY));
        let got = rescale_factor_in_lanes(largest, finite).map(bits4);
        let expected =
            crate::polygon::rescale_factor_of_lanes(largest, finite).map(|f| bits4(Vec4::splat(f)));
        assert_eq!(got, expected, "{largest:?}");
    }
}

/// The group of slot `count` where it is a group of its own (quads: slots 4..8;
/// octagons: 8..12) is taken from slot 0 (`first_in_every_slot`) in place of the vertex
/// work on the copies of vertex 0 that fill it: every value the same bits as that work
/// gives, for polygons at every scale and near the shading point.
#[test]
fn the_group_that_closes_the_polygon_is_slot_zero_again() {
    let mut rng = Rng::new(4001);
    let bits4 = |v: Vec4| v.to_array().map(f32::to_bits);
    let mut checked = 0;
    for n in [4usize, 8] {
        for i in 0..400 {
            let v = match i % 4 {
                0 => random_polygon_above(&mut rng, n, 0.2, 0.7),
                1 => random_polygon_above(&mut rng, n, 1e-5, 1e-5)
                    .iter()
                    .map(|&p| p * 1e4)
                    .collect(),
                2 => random_polygon_above(&mut rng, n, 2.0, 3.0)
                    .iter()
                    .map(|&p| Vec3::new(p.x, p.y, 1e-3 * p.z))
                    .collect(),
                _ => reversed(&random_polygon_above(&mut rng, n, 0.5, 1.5)),
            };
            let (raw, factor) = gather_and_rescale(&v, n);
            let factor = factor.expect("finite");
            let (groups, reflection) = VertexGroups::new(raw, factor, n).expect("no zero vertex");
            // The group of slot `n`, computed as every other group is.
            let first = n;
            let (mut expected, ok) = SlotGroup::vertices(gather(&v, n, first), factor);
            assert!(ok);
            let p0 = groups.groups[0].position;
            let origin = [
                Vec4::splat(p0[0].x),
                Vec4::splat(p0[1].x),
                Vec4::splat(p0[2].x),
            ];
            expected.reflect(&reflection, origin);
            let got = groups.groups[first / LANES];
            let what = format!("{v:?}");
            for c in 0..3 {
                assert_eq!(
                    bits4(got.position[c]),
                    bits4(expected.position[c]),
                    "{what}"
                );
                assert_eq!(bits4(got.unit[c]), bits4(expected.unit[c]), "{what}");
            }
            for c in 0..2 {
                assert_eq!(
                    bits4(got.reflected[c]),
                    bits4(expected.reflected[c]),
                    "{what}"
                );
            }
            assert_eq!(bits4(got.length_squared), bits4(expected.length_squared));
            assert_eq!(bits4(got.length), bits4(expected.length), "{what}");
            assert_eq!(bits4(got.extent), bits4(expected.extent), "{what}");
            checked += 1;
        }
    }
    assert_eq!(checked, 800);
}

/// `padded` (the sample's 16-byte loads of a vertex and a pair sum) gives each element's
/// three components bit for bit, for every slot of both fields (the last ones, whose
/// fourth lane is the next field's first word, included), in all three sizes, for
/// prepared polygons of every count and for the empty value.
#[test]
fn padded_loads_read_the_elements() {
    fn check<const N: usize, const T: usize>(polygon: &SolidAngleFan<N, T>) -> usize {
        let bits = |v: Vec3A| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
        let bits3 = |v: Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
        let vertices = core::mem::offset_of!(SolidAngleFan<N, T>, vertices);
        let outer_sum = core::mem::offset_of!(SolidAngleFan<N, T>, outer_sum);
        for i in 0..N {
            assert_eq!(
                bits(polygon.padded(vertices, i, N)),
                bits3(polygon.vertices[i])
            );
        }
        for k in 0..T {
            assert_eq!(
                bits(polygon.padded(outer_sum, k, T)),
                bits3(polygon.outer_sum[k])
            );
        }
        N + T
    }
    let mut rng = Rng::new(41);
    let mut checked = 0;
    for _ in 0..50 {
        for n in 3..=MAX_POLYGON_VERTICES {
            let v = random_polygon_above(&mut rng, n, 0.2, 1.0);
            let polygon = SolidAnglePolygon::new(&v).expect("a polygon above");
            checked += check(&polygon);
            if n <= 4 {
                checked += check(&SolidAngleQuad::new(&v).expect("a quad above"));
            }
            if n == 3 {
                checked += check(&SolidAngleTriangle::new(&v).expect("a triangle above"));
            }
        }
    }
    checked += check(&SolidAnglePolygon::EMPTY);
    assert_eq!(checked, 50 * (6 * 14 + 2 * 6 + 4) + 14);
}

/// `positive_and_finite` is `0 < x < ∞` for every 4093rd bit pattern and those around
/// 0, the smallest subnormal, 1, the largest finite value, ∞ and NaN, of either sign.
#[test]
fn positive_and_finite_is_the_float_test() {
    let check = |bits: u32| {
        let x = f32::from_bits(bits);
        assert_eq!(
            positive_and_finite(x),
            x > 0.0 && x < f32::INFINITY,
            "{bits:#x}"
        );
    };
    let edges = [
        0u32,
        1,
        1.0f32.to_bits(),
        f32::MAX.to_bits(),
        f32::INFINITY.to_bits(),
    ];
    for edge in edges {
        for sign in [0, 0x8000_0000u32] {
            for d in 0..=16u32 {
                check((edge | sign).wrapping_add(d));
                check((edge | sign).wrapping_sub(d));
            }
        }
    }
    for bits in (0..=u32::MAX).step_by(4093) {
        check(bits);
    }
}

/// The prepared `outer_along` and `outer_across2` are, bit for bit, what the sample
/// computed from the stored vertex and pair sum before they were prepared: `m =
/// vertices[k + 1]·outer_sum[k]` and `|outer_sum[k]|² - m²`, rounded as `Vec3::dot` and
/// `length_squared` round them; 0 past the fan triangles. For every count in all three
/// sizes, on the lanes' path (`compute`, `compute_one` for a heptagon's fifth,
/// `compute_triangle`) and on the careful pair sums (large polygons just above the
/// shading point, which some of them take: counted).
#[test]
fn the_outer_terms_are_the_samples_dot_products() {
    fn check<const N: usize, const T: usize>(polygon: &SolidAngleFan<N, T>) -> bool {
        let triangles = polygon.vertex_count as usize - 2;
        for k in 0..T {
            let (m, across2) = if k < triangles {
                let (v0, s) = (polygon.vertices[k + 1], polygon.outer_sum[k]);
                let m = v0.dot(s);
                (m, s.length_squared() - m * m)
            } else {
                (0.0, 0.0)
            };
            assert_eq!(
                polygon.outer_along[k].to_bits(),
                m.to_bits(),
                "{k} {polygon:?}"
            );
            assert_eq!(polygon.outer_across2[k].to_bits(), across2.to_bits(), "{k}");
        }
        polygon.careful_paths() & CAREFUL_PAIR_SUMS != 0
    }
    let mut rng = Rng::new(4141);
    let (mut checked, mut careful) = (0, 0);
    for n in 3..=MAX_POLYGON_VERTICES {
        for i in 0..200 {
            let mut v = if i % 2 == 0 {
                random_polygon_above(&mut rng, n, 0.2, 0.7)
            } else {
                // Large and close: vertices far more than 90° apart from the apex.
                let mut v = random_polygon_above(&mut rng, n, 3.0, 3.0);
                for p in &mut v {
                    p.z = 1e-3 + 1e-2 * (p.z - 1.0).abs();
                }
                v
            };
            if i % 4 < 2 {
                v.reverse();
            }
            let Some(polygon) = SolidAnglePolygon::new(&v) else {
                continue;
            };
            careful += check(&polygon) as u32;
            checked += 1;
            if n <= 4 {
                check(&SolidAngleQuad::new(&v).expect("as the polygon"));
            }
            if n == 3 {
                check(&SolidAngleTriangle::new(&v).expect("as the polygon"));
            }
        }
    }
    assert!(checked >= 1100, "{checked}");
    assert!(
        careful >= 100,
        "{careful} of {checked} took the careful pair sums"
    );
}

/// The fan triangles' solid angles that `FanLanes::compute` takes in lanes
/// (`angles_in_lanes`: all of 3, 4 and 6 fan triangles, the first four of 5) are the
/// scalar `triangle_angle` of the prepared `G0` and `G1 + G2`, bit for bit, as are the
/// running sums `start` and the total built from them: for 3 to 8 vertices, on small fan
/// triangles (every ratio `G0 / (G1 + G2)` below 7/16: the branch of
/// `atan2_upper_half_plane4_small_first` without the reduction) and large ones (the
/// general branch), both windings, and polygons close over the shading point (the
/// careful pair sums, after which the angle of the replaced values is computed again),
/// with triangles of zero solid angle (a duplicated vertex: `start` is `+∞` past the
/// last selectable one).
#[test]
fn the_fan_angles_in_lanes_are_the_scalar_ones() {
    let mut rng = Rng::new(4201);
    let (mut small, mut general, mut careful, mut unselectable) = (0, 0, 0, 0);
    for n in 3..=8 {
        for trial in 0..600 {
            let mut v = match trial % 4 {
                0 => random_polygon_above(&mut rng, n, 0.05, 0.3),
                1 => random_polygon_above(&mut rng, n, 1.0, 3.0),
                2 => reversed(&random_polygon_above(&mut rng, n, 0.05, 3.0)),
                _ => random_polygon_above(&mut rng, n, 2.0, 3.0)
                    .iter()
                    .map(|&p| Vec3::new(p.x, p.y, 1e-2 * p.z))
                    .collect(),
            };
            if trial % 7 == 0 {
                // The last vertex again: the last fan triangle has no solid angle.
                let last = v[n - 1];
                v.push(last);
                if v.len() > MAX_POLYGON_VERTICES {
                    v.remove(1);
                }
            }
            let Some(polygon) = SolidAnglePolygon::new(&v) else {
                continue;
            };
            let triangles = v.len() - 2;
            let in_lanes = angles_in_lanes(triangles);
            let mut total = 0.0f32;
            for k in 0..triangles {
                let angle = triangle_angle(polygon.g0[k], polygon.g1_plus_g2[k]);
                if k < polygon.selectable_triangles as usize {
                    assert_eq!(polygon.start[k].to_bits(), total.to_bits(), "{v:?} {k}");
                } else {
                    assert_eq!(polygon.start[k], f32::INFINITY, "{v:?} {k}");
                    unselectable += 1;
                }
                total += angle;
            }
            assert_eq!(polygon.solid_angle.to_bits(), total.to_bits(), "{v:?}");
            if in_lanes > 0 {
                let ratios_small = (0..in_lanes.min(LANES))
                    .all(|k| polygon.g0[k] / polygon.g1_plus_g2[k] < 0.4375);
                small += ratios_small as u32;
                general += !ratios_small as u32;
                careful += (polygon.careful_paths() & CAREFUL_PAIR_SUMS != 0) as u32;
            }
        }
    }
    std::println!(
        "small {small}, general {general}, careful {careful}, unselectable {unselectable}"
    );
    assert!(small > 300 && general > 300, "{small} {general}");
    assert!(
        careful > 100 && unselectable > 50,
        "{careful} {unselectable}"
    );
}

/// `SHORTEST_PAIR`, the lane that `compute_triangle` reads its `G1 + G2` from, names
/// `denominator`'s choice for every order of the three squared pair sums, ties included:
/// each candidate made distinct by its own dot product.
#[test]
fn shortest_pair_is_the_choice_of_denominator() {
    let v = Vec3::X;
    let sums = [Vec3::X * 1000.0, Vec3::X * 2000.0, Vec3::X * 3000.0];
    for l01 in [1.0f32, 2.0, 3.0] {
        for l02 in [1.0f32, 2.0, 3.0] {
            for l12 in [1.0f32, 2.0, 3.0] {
                let lengths = [l01, l02, l12];
                // Lanes 0, 1, 2 as `compute_triangle` orders them: with s01, s02, s12.
                let candidates = [0, 1, 2].map(|i| 0.5 * lengths[i] + v.dot(sums[i]));
                let tests = usize::from(l02 <= l01)
                    | usize::from(l02 <= l12) << 1
                    | usize::from(l12 <= l01) << 2;
                assert_eq!(
                    candidates[SHORTEST_PAIR[tests]],
                    denominator(v, v, v, sums, lengths),
                    "{lengths:?}"
                );
            }
        }
    }
}

/// `piece` is the piece `k` that `select_piece` picks and `start[k]` bit for bit,
/// for prepared triangles and quads (the sizes that do not load it) and the general size:
/// at targets drawn across `[0, Ω)`, at the starts themselves and an ulp either side of
/// them, and for quads whose first fan triangle has zero solid angle (a repeated vertex,
/// `start[1] = 0`).
#[test]
fn piece_is_select_piece_and_its_start() {
    fn check<const N: usize, const T: usize>(p: &SolidAngleFan<N, T>, rng: &mut Rng) -> usize {
        let mut targets: Vec<f32> = (0..64).map(|_| rng.uniform_f32() * p.solid_angle).collect();
        for &start in &p.start {
            if start.is_finite() {
                targets.extend([start, start.next_down(), start.next_up()]);
            }
        }
        targets.extend([0.0, p.solid_angle.next_down()]);
        for &target in targets.iter().filter(|t| **t >= 0.0) {
            let k = select_piece(&p.start, target);
            let (piece, start) = p.piece(target);
            assert_eq!(piece, k, "{target:e} in {:?}", p.start);
            assert_eq!(
                start.to_bits(),
                p.start[k].to_bits(),
                "{target:e} in {:?}",
                p.start
            );
        }
        targets.len()
    }
    let mut rng = Rng::new(46);
    let mut checked = 0;
    for n in 3..=MAX_POLYGON_VERTICES {
        for _ in 0..50 {
            let v = random_polygon_above(&mut rng, n, 0.6, 1.0);
            checked += check(&SolidAnglePolygon::new(&v).expect("valid"), &mut rng);
            if n <= 4 {
                checked += check(&SolidAngleQuad::new(&v).expect("valid"), &mut rng);
            }
            if n == 3 {
                checked += check(&SolidAngleTriangle::new(&v).expect("valid"), &mut rng);
            }
        }
    }
    // A quad with vertex 1 repeated: its first fan triangle is empty.
    let v = random_polygon_above(&mut rng, 3, 0.6, 1.0);
    let repeated = [v[0], v[1], v[1], v[2]];
    let quad = SolidAngleQuad::new(&repeated).expect("valid");
    assert_eq!(quad.start[1], 0.0);
    checked += check(&quad, &mut rng);
    assert!(checked > 10_000, "{checked}");
}
