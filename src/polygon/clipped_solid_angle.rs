//! Clipped solid angle sampling: the polygon is clipped to the upper hemisphere
//! (supplement A.1) and the part above the horizon is sampled uniformly in solid angle
//! (supplement C, Algorithm 5). This is the "Solid angle, clipped" row of Table A.2 of
//! Peters 2021's supplement: a baseline that wastes no samples below the horizon but,
//! unlike projected solid angle sampling, ignores the cosine.
//!
//! The input is first rescaled by a power of two (exact, as in
//! [`SolidAnglePolygon::new`]) so that clipping neither overflows for coordinates near
//! `f32::MAX` nor loses subnormal ones. Clipped vertices lie exactly on `z = 0`, so
//! sampled directions have `z >= 0` up to rounding; `sample` maps the rounding that
//! would leave a direction a few ulps below the horizon to `z = 0`, so that no sample
//! ever has `z < 0`.

use crate::polygon::clip_to_upper_hemisphere;
use crate::polygon::rescale;
use crate::polygon::solid_angle::SolidAnglePolygon;
use crate::{MAX_POLYGON_VERTICES, Sample, Vec3};

/// A convex polygon clipped to the upper hemisphere and prepared for solid angle
/// sampling.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClippedSolidAnglePolygon {
    /// The solid angle sampler of the clipped polygon.
    clipped: SolidAnglePolygon,
}

impl Default for ClippedSolidAnglePolygon {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl ClippedSolidAnglePolygon {
    /// The state of a polygon that could not be prepared: samples have `pdf == 0`,
    /// `pdf()` is 0 and the solid angle is 0.
    ///
    /// (Rust-only, like the other samplers' `EMPTY`: cbindgen could express this one,
    /// in terms of the solid angle sampler's `EMPTY` that the header lacks.)
    ///
    /// cbindgen:ignore
    pub const EMPTY: Self = Self {
        clipped: SolidAnglePolygon::EMPTY,
    };

    /// Clips the convex polygon with the given vertices (positions relative to the
    /// shading point, not normalised, either winding, 3 to 8 of them) to the upper
    /// hemisphere `z >= 0` and prepares the rest for solid angle sampling.
    ///
    /// Returns `None` for fewer than 3 or more than 8 vertices, non-finite coordinates,
    /// all vertices at the shading point, a polygon with nothing above the horizon, an
    /// 8-vertex polygon that needs clipping (the result could have 9 vertices), and
    /// whatever [`SolidAnglePolygon::new`] rejects about the clipped polygon (no solid
    /// angle, for example a polygon that only touches the horizon, or a shading point in
    /// the polygon's plane).
    ///
    /// [`prepare`](Self::prepare) does the same in place.
    #[must_use]
    pub fn new(vertices: &[Vec3]) -> Option<Self> {
        let mut polygon = Self::EMPTY;
        polygon.prepare(vertices).then_some(polygon)
    }

    /// [`new`](Self::new) in place: writes the prepared polygon into `self` and returns
    /// `true`, or writes [`EMPTY`](Self::EMPTY) and returns `false` where `new` returns
    /// `None`.
    pub fn prepare(&mut self, vertices: &[Vec3]) -> bool {
        let count = vertices.len();
        let mut local = [Vec3::ZERO; MAX_POLYGON_VERTICES];
        let clipped_count = if (3..=MAX_POLYGON_VERTICES).contains(&count)
            && rescale(vertices, &mut local).is_some()
            // Before clipping, whose rounded horizon vertices would leave the plane.
            && !super::lies_in_a_plane_through_the_shading_point(&local[..count])
        {
            clip_to_upper_hemisphere(&mut local, count)
        } else {
            0
        };
        // An empty slice (nothing left above the horizon) is rejected there and writes
        // the empty value.
        let clipped = if clipped_count < 3 { 0 } else { clipped_count };
        self.clipped.prepare(&local[..clipped])
    }

    /// Solid angle Ω of the part of the polygon above the horizon, in steradians (0 when
    /// empty).
    #[inline]
    pub fn solid_angle(&self) -> f32 {
        self.clipped.solid_angle()
    }

    /// Draws a direction uniformly in solid angle inside the clipped polygon, with
    /// `dir.z >= 0`. `u` is clamped to `[0, 1 - ulp]`; NaN counts as 0. The pdf is
    /// `1 / Ω`, or 0 (with a finite direction) for an empty polygon.
    #[inline]
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        let mut sample = self.clipped.sample(u);
        // Only rounding puts a direction below the clipped horizon edge; for a
        // degenerate clipped polygon (coordinates near f32::MAX) that can be far below,
        // so the direction is renormalised where clamping cost its unit length (found by
        // fuzzing: |dir| = 0.875).
        if sample.dir.z < 0.0 {
            sample.dir.z = 0.0;
            sample.dir = crate::math::unit_if_needed(sample.dir);
            if !(sample.dir.is_finite() && sample.dir != Vec3::ZERO) {
                return Sample::NONE;
            }
        }
        sample
    }

    /// [`sample`](Self::sample) in the common case, `None` in the rare one: that of
    /// [`SolidAnglePolygon::sample_common`], and a direction below the horizon. Equal to
    /// `sample` bit for bit where it gives a sample.
    #[inline(always)]
    pub(crate) fn sample_common(&self, u: [f32; 2]) -> Option<Sample> {
        self.clipped
            .sample_common(u)
            .filter(|sample| sample.dir.z >= 0.0)
    }

    /// [`sample`](Self::sample) out of line, for the rare path of the C entry point.
    #[inline(never)]
    pub(crate) fn sample_rare(&self, u: [f32; 2]) -> Sample {
        self.sample(u)
    }

    /// `1 / Ω` for a direction inside the clipped polygon (boundary included), 0
    /// outside, in particular below the horizon. `dir` need not be normalised; a zero or
    /// non-finite `dir` gives 0.
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        self.clipped.pdf(dir)
    }

    /// Whether the ray along `dir` passes through the clipped polygon.
    #[inline]
    pub fn contains(&self, dir: Vec3) -> bool {
        self.clipped.contains(dir)
    }

    /// The random numbers `u` for which [`sample`](Self::sample) returns `dir` (up to
    /// rounding), or `None` when `dir` is outside the clipped polygon or it is empty.
    #[inline]
    pub fn invert(&self, dir: Vec3) -> Option<[f32; 2]> {
        self.clipped.invert(dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Sample;
    use crate::sample::ONE_MINUS_ULP;
    use crate::testing::*;

    /// Crossing the horizon: part of the polygon below.
    fn crossing(n: usize, reversed: bool) -> Vec<Vec3> {
        let v = circle_polygon(n, [0.2, 1.0, 0.35], [0.1, -1.0, 0.3], 0.8, reversed);
        let below = v.iter().filter(|p| p.z <= 0.0).count();
        assert!(below > 0 && below < n, "{v:?}");
        v
    }

    /// Entirely above the horizon.
    fn above(n: usize, reversed: bool) -> Vec<Vec3> {
        circle_polygon(n, [0.3, -0.2, 1.0], [0.3, -0.2, -1.0], 0.9, reversed)
    }

    fn cell_solid_angle(c: &[D3; 3]) -> f64 {
        solid_angle_triangle_f64(c[0], c[1], c[2])
    }

    #[test]
    fn samples_are_uniform_over_the_part_above_the_horizon() {
        for n in 3..=7 {
            for reversed in [false, true] {
                for (name, vertices) in [
                    ("crossing", crossing(n, reversed)),
                    ("above", above(n, reversed)),
                ] {
                    let polygon = ClippedSolidAnglePolygon::new(&vertices).expect("valid");
                    let part = clip_to_upper_hemisphere_f32(&vertices);
                    let what = format!("{name} {n}-gon reversed={reversed}");
                    let report = run_polygon_sampler(
                        &part,
                        8,
                        200_000,
                        n as u64 * 2 + reversed as u64,
                        cell_solid_angle,
                        |u| {
                            let s = polygon.sample(u);
                            assert!(s.dir.z >= 0.0, "{what}: {s:?}");
                            s
                        },
                        |d| polygon.pdf(d),
                    );
                    println!(
                        "clipped {what}: p = {:.4}, outside {}",
                        report.p_value, report.outside
                    );
                    assert!(report.p_value > CHI_SQUARE_ALPHA, "{what}: {report:?}");
                    assert_eq!(report.non_finite, 0, "{what}: {report:?}");
                    assert!(report.worst_outside_angle < 5e-7, "{what}: {report:?}");
                    assert!(report.outside <= 200, "{what}: {report:?}");
                    assert!(
                        report.worst_pdf_mismatch == 0.0
                            || (report.outside > 0 && report.worst_pdf_mismatch == 1.0),
                        "{what}: {report:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn solid_angle_is_that_of_the_part_above_the_horizon() {
        for n in 3..=7 {
            for reversed in [false, true] {
                let vertices = crossing(n, reversed);
                let polygon = ClippedSolidAnglePolygon::new(&vertices).unwrap();
                let part: Vec<D3> = clip_to_upper_hemisphere_f32(&vertices)
                    .iter()
                    .map(|&v| d3(v))
                    .collect();
                let reference = solid_angle_polygon_f64(&part);
                let full =
                    solid_angle_polygon_f64(&vertices.iter().map(|&v| d3(v)).collect::<Vec<_>>());
                assert!(reference < 0.95 * full);
                let relative = (polygon.solid_angle() as f64 - reference).abs() / reference;
                assert!(
                    relative < 1e-5,
                    "{n}: {} vs {reference}",
                    polygon.solid_angle()
                );
            }
        }
    }

    /// The diffuse estimator `mean(dir.z / pdf)` converges to the cosine integral of the
    /// part above the horizon (Lambert's formula in f64).
    #[test]
    fn cosine_estimator_matches_the_projected_solid_angle_of_the_clipped_polygon() {
        let mut seed = 40;
        for n in 3..=7 {
            for reversed in [false, true] {
                seed += 1;
                let vertices = crossing(n, reversed);
                let polygon = ClippedSolidAnglePolygon::new(&vertices).unwrap();
                let mut rng = Rng::new(seed);
                let mut estimate = Estimate::default();
                for _ in 0..200_000 {
                    let s = polygon.sample([rng.uniform_f32(), rng.uniform_f32()]);
                    assert!(s.pdf > 0.0);
                    estimate.add(s.dir.z as f64 / s.pdf as f64);
                }
                let reference =
                    projected_solid_angle_polygon_f64(&clip_to_upper_hemisphere_f32(&vertices));
                estimate.assert_mean_is(reference, 5.0, 1e-5, &format!("{n}-gon {reversed}"));
            }
        }
    }

    /// Above the horizon the clipped sampler is the plain one, bit for bit.
    #[test]
    fn polygons_above_the_horizon_are_sampled_as_without_clipping() {
        for n in 3..=8 {
            for reversed in [false, true] {
                let vertices = above(n, reversed);
                let clipped = ClippedSolidAnglePolygon::new(&vertices).unwrap();
                let plain = SolidAnglePolygon::new(&vertices).unwrap();
                assert_eq!(clipped.clipped, plain);
                let mut rng = Rng::new(n as u64);
                for _ in 0..100 {
                    let u = [rng.uniform_f32(), rng.uniform_f32()];
                    assert_eq!(clipped.sample(u), plain.sample(u));
                }
            }
        }
    }

    #[test]
    fn invalid_polygons_and_polygons_without_a_part_above_the_horizon_are_rejected() {
        for bad in invalid_polygons(&above(3, false)) {
            assert!(ClippedSolidAnglePolygon::new(&bad).is_none(), "{bad:?}");
        }
        for good in valid_edge_case_polygons() {
            let polygon =
                ClippedSolidAnglePolygon::new(&good).unwrap_or_else(|| panic!("{good:?}"));
            assert!(polygon.solid_angle() > 0.0);
        }
        // Entirely below, touching the horizon from below at a vertex or along an edge.
        for below in [
            circle_polygon(5, [0.2, 0.3, -1.0], [0.1, 0.0, 1.0], 0.5, false),
            vec![
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(-1.0, 1.0, -1.0),
                Vec3::new(-1.0, -1.0, -1.0),
            ],
            vec![
                Vec3::new(1.0, -1.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(-1.0, 0.0, -1.0),
            ],
        ] {
            assert!(ClippedSolidAnglePolygon::new(&below).is_none(), "{below:?}");
        }
        // 8 vertices: accepted entirely above the horizon, rejected when clipping is
        // needed (the result could have 9 vertices).
        assert!(ClippedSolidAnglePolygon::new(&above(8, false)).is_some());
        let crossing8 = crossing(8, false);
        assert!(ClippedSolidAnglePolygon::new(&crossing8).is_none());
        assert!(SolidAnglePolygon::new(&crossing8).is_some());
    }

    /// Coordinates near `f32::MAX` and subnormal ones: the power-of-two rescaling before
    /// clipping keeps the clipped polygon and its solid angle.
    #[test]
    fn huge_and_subnormal_coordinates_are_clipped_exactly() {
        // The triangle spans 3 in z: at 2^127 its differences of coordinates overflow.
        let tall = vec![
            Vec3::new(1.5, 1.0, -1.5),
            Vec3::new(-1.5, 1.0, -1.5),
            Vec3::new(0.0, 1.0, 1.5),
        ];
        for vertices in [crossing(5, false), tall] {
            let reference = ClippedSolidAnglePolygon::new(&vertices)
                .unwrap()
                .solid_angle();
            // Powers of two in the normal range scale the input exactly; 1e30 rounds each
            // coordinate; 2^-140 makes them subnormal, with about 14 significant bits.
            for (factor, tolerance) in [
                (2f32.powi(127), 1e-6),
                (2f32.powi(-120), 1e-6),
                (1e30, 1e-5),
                (2f32.powi(-140), 2e-3),
            ] {
                let scaled: Vec<Vec3> = vertices.iter().map(|&v| v * factor).collect();
                let polygon = ClippedSolidAnglePolygon::new(&scaled)
                    .unwrap_or_else(|| panic!("factor {factor}"));
                let relative = (polygon.solid_angle() - reference).abs() / reference;
                assert!(
                    relative < tolerance,
                    "factor {factor}: {} vs {reference}",
                    polygon.solid_angle()
                );
                let s = polygon.sample([0.3, 0.6]);
                assert!(s.pdf > 0.0 && s.dir.z >= 0.0 && s.dir.is_finite());
            }
        }
    }

    /// `u = 0`, `u = 1 - ulp` and out-of-range values give finite samples above the
    /// horizon with the uniform pdf, which `pdf(dir)` reproduces (or, for a direction
    /// that rounding put just outside the polygon, gives 0), and `invert` round-trips
    /// interior samples.
    #[test]
    fn extreme_random_numbers_and_the_inverse() {
        let edge = [
            0.0,
            1e-30,
            0.5,
            ONE_MINUS_ULP,
            1.0,
            -1.0,
            2.0,
            f32::NAN,
            f32::INFINITY,
        ];
        for n in 3..=7 {
            for reversed in [false, true] {
                let vertices = crossing(n, reversed);
                let polygon = ClippedSolidAnglePolygon::new(&vertices).unwrap();
                let density = 1.0 / polygon.solid_angle();
                for &u0 in &edge {
                    for &u1 in &edge {
                        let s = polygon.sample([u0, u1]);
                        let what = format!("{n} {reversed} {u0} {u1}: {s:?}");
                        assert!(s.dir.is_finite() && s.dir.z >= 0.0, "{what}");
                        assert!((s.dir.length() - 1.0).abs() < 2e-6, "{what}");
                        assert_eq!(s.pdf, density, "{what}");
                        let p = polygon.pdf(s.dir);
                        assert!(
                            p == density || (p == 0.0 && !polygon.contains(s.dir)),
                            "{what}"
                        );
                    }
                }
                let mut rng = Rng::new(n as u64);
                for _ in 0..1000 {
                    let u = [rng.uniform_f32(), rng.uniform_f32()];
                    let s = polygon.sample(u);
                    if let Some(back) = polygon.invert(s.dir) {
                        assert!((back[0] - u[0]).abs() < 1e-4, "{u:?} -> {back:?}");
                        assert!((back[1] - u[1]).abs() < 1e-3, "{u:?} -> {back:?}");
                    }
                }
                // Below the horizon: no density, no inverse.
                let plain = SolidAnglePolygon::new(&vertices).unwrap();
                let mut below = 0;
                for _ in 0..1000 {
                    let d = plain.sample([rng.uniform_f32(), rng.uniform_f32()]).dir;
                    if d.z < 0.0 {
                        below += 1;
                        assert_eq!(polygon.pdf(d), 0.0, "{d:?}");
                        assert!(polygon.invert(d).is_none(), "{d:?}");
                    }
                }
                assert!(below > 0);
            }
        }
    }

    #[test]
    fn empty_polygon_gives_nothing() {
        let empty = ClippedSolidAnglePolygon::default();
        assert_eq!(empty, ClippedSolidAnglePolygon::EMPTY);
        assert_eq!(empty.sample([0.5, 0.5]), Sample::NONE);
        assert_eq!(empty.pdf(Vec3::Z), 0.0);
        assert_eq!(empty.solid_angle(), 0.0);
        assert!(empty.invert(Vec3::Z).is_none());
        let polygon = ClippedSolidAnglePolygon::new(&crossing(4, false)).unwrap();
        for dir in [Vec3::ZERO, Vec3::NAN, Vec3::INFINITY, -Vec3::Z] {
            assert_eq!(polygon.pdf(dir), 0.0, "{dir:?}");
        }
    }
}
