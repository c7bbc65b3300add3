//! Uniform sampling of the solid angle of a convex polygon by Arvo's 1995 algorithm
//! ("Stratified Sampling of Spherical Triangles", SIGGRAPH '95), applied to a fan of
//! spherical triangles.
//!
//! Per fan triangle `A, B, C` (vertices projected to the unit sphere) the area is found
//! by Girard's theorem from the interior angles, which come from `acos` of dot products
//! of the edge planes' normals. Sampling first finds the point `Ĉ` on the arc `AC` such
//! that the sub-triangle `A B Ĉ` has the area `Â = u0 · area` (solving the spherical
//! law of cosines for the unknown side), then a point on the arc `B Ĉ` with `cos` of its
//! distance from `B` uniform.
//!
//! This is a baseline of Peters 2021 and is kept faithful: `α + β + γ - π` cancels
//! catastrophically for small triangles, and `A · B` rounds to 1 for short edges, so
//! that tiny triangles are sampled poorly (directions outside the triangle, or none).
//! The only changes to the algorithm are clamps of `sqrt` and `acos` arguments so that
//! nothing returns NaN; a sample that still goes non-finite is [`Sample::NONE`].
use crate::{MAX_POLYGON_VERTICES, Sample};
use core::f32::consts::PI;
use glam::Vec3;

const MAX_FAN_TRIANGLES: usize = MAX_POLYGON_VERTICES - 2;

/// A convex polygon prepared for Arvo's sampling of its spherical fan triangles.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct ArvoPolygon {
    /// The vertices projected onto the unit sphere.
    vertices: [Vec3; MAX_POLYGON_VERTICES],
    /// `v̂_i × v̂_{i+1}`, oriented so that the polygon lies on their positive side.
    edge_normals: [Vec3; MAX_POLYGON_VERTICES],
    /// Per fan triangle `A = v̂_0, B = v̂_{i+1}, C = v̂_{i+2}`: the unit tangent at `A`
    /// towards `C`, `normalize(C - (C·A) A)`.
    towards_c: [Vec3; MAX_FAN_TRIANGLES],
    /// Per fan triangle: its area by Girard's theorem (0 when degenerate).
    areas: [f32; MAX_FAN_TRIANGLES],
    /// Per fan triangle: the interior angle `α` at `A`, `cos α`, `sin α`, and
    /// `sin α · cos c` with `c` the side `AB`.
    alpha: [f32; MAX_FAN_TRIANGLES],
    cos_alpha: [f32; MAX_FAN_TRIANGLES],
    sin_alpha: [f32; MAX_FAN_TRIANGLES],
    sin_alpha_cos_c: [f32; MAX_FAN_TRIANGLES],
    /// Cumulative probabilities of the fan triangles; the last used entry is exactly 1.
    cdf: [f32; MAX_FAN_TRIANGLES],
    solid_angle: f32,
    inv_solid_angle: f32,
    count: u32,
}

/// `acos` with its argument clamped into [-1, 1].
#[inline]
fn acos_clamped(x: f32) -> f32 {
    libm::acosf(x.clamp(-1.0, 1.0))
}

/// `√max(0, x)`.
#[inline]
fn sqrt_clamped(x: f32) -> f32 {
    crate::math::sqrtf(x.max(0.0))
}

/// What Arvo's algorithm needs of one spherical triangle.
struct Triangle {
    area: f32,
    alpha: f32,
    cos_alpha: f32,
}

/// Girard's theorem: the area is `α + β + γ - π`, with each interior angle the angle
/// between the normals of the two edge planes through the vertex.
fn girard(a: Vec3, b: Vec3, c: Vec3) -> Triangle {
    let ab = crate::math::normalize_or_zero(a.cross(b));
    let bc = crate::math::normalize_or_zero(b.cross(c));
    let ca = crate::math::normalize_or_zero(c.cross(a));
    if ab == Vec3::ZERO || bc == Vec3::ZERO || ca == Vec3::ZERO {
        return Triangle {
            area: 0.0,
            alpha: 0.0,
            cos_alpha: 1.0,
        };
    }
    // At A between the planes (A, B) and (A, C): normals A×B and A×C = -(C×A).
    let cos_alpha = (-ab.dot(ca)).clamp(-1.0, 1.0);
    let alpha = libm::acosf(cos_alpha);
    // At B: B×C and B×A = -(A×B). At C: C×A and C×B = -(B×C).
    let beta = acos_clamped(-bc.dot(ab));
    let gamma = acos_clamped(-ca.dot(bc));
    Triangle {
        area: alpha + beta + gamma - PI,
        alpha,
        cos_alpha,
    }
}

impl ArvoPolygon {
    /// The polygon that samples nothing.
    pub const EMPTY: Self = Self {
        vertices: [Vec3::ZERO; MAX_POLYGON_VERTICES],
        edge_normals: [Vec3::ZERO; MAX_POLYGON_VERTICES],
        towards_c: [Vec3::ZERO; MAX_FAN_TRIANGLES],
        areas: [0.0; MAX_FAN_TRIANGLES],
        alpha: [0.0; MAX_FAN_TRIANGLES],
        cos_alpha: [1.0; MAX_FAN_TRIANGLES],
        sin_alpha: [0.0; MAX_FAN_TRIANGLES],
        sin_alpha_cos_c: [0.0; MAX_FAN_TRIANGLES],
        cdf: [1.0; MAX_FAN_TRIANGLES],
        solid_angle: 0.0,
        inv_solid_angle: 0.0,
        count: 0,
    };

    /// Prepares a convex planar polygon (3 to 8 vertices relative to the shading point,
    /// either winding). Returns None for a bad vertex count, a non-finite coordinate, a
    /// zero area, a plane through the shading point, or a zero (Girard) solid angle.
    ///
    /// [`prepare`](Self::prepare) does the same in place.
    #[must_use]
    pub fn new(vertices: &[Vec3]) -> Option<Self> {
        let mut polygon = Self::EMPTY;
        polygon.prepare(vertices).then_some(polygon)
    }

    /// [`new`](Self::new) in place: writes the prepared polygon into `self` and returns
    /// `true`, or writes [`EMPTY`](Self::EMPTY) and returns `false`.
    pub fn prepare(&mut self, vertices: &[Vec3]) -> bool {
        let prepared = self.prepare_or_fail(vertices);
        crate::polygon::keep_or_empty(self, prepared, Self::EMPTY)
    }

    /// The body of [`prepare`](Self::prepare); on `false`, `self` holds partial values.
    #[inline(always)]
    fn prepare_or_fail(&mut self, vertices: &[Vec3]) -> bool {
        let count = vertices.len();
        if !(3..=MAX_POLYGON_VERTICES).contains(&count) || !vertices.iter().all(|v| v.is_finite()) {
            return false;
        }
        // Scale into [-1, 1] so that neither the plane test nor the normalisation below
        // overflows or underflows (the directions do not depend on the scale).
        let largest = vertices
            .iter()
            .fold(0.0f32, |m, v| m.max(v.abs().max_element()));
        if largest <= 0.0 || !largest.is_finite() {
            return false;
        }
        let mut scaled = [Vec3::ZERO; MAX_POLYGON_VERTICES];
        for (s, v) in scaled.iter_mut().zip(vertices) {
            *s = *v / largest;
        }
        let scaled = &scaled[..count];
        // The plane: reject zero area and planes through the shading point.
        let mut normal_sum = Vec3::ZERO;
        for i in 1..count - 1 {
            normal_sum += (scaled[i] - scaled[0]).cross(scaled[i + 1] - scaled[0]);
        }
        let Some(normal) = crate::math::try_normalize(normal_sum) else {
            return false;
        };
        let mut offset_sum = 0.0;
        let mut extent = 0.0f32;
        for v in scaled {
            offset_sum += normal.dot(*v);
            extent = extent.max(crate::math::length(*v));
        }
        let plane_offset = offset_sum / count as f32;
        if plane_offset.abs() <= 8.0 * f32::EPSILON * extent || !plane_offset.is_finite() {
            return false;
        }
        let polygon = self;
        for (unit, v) in polygon.vertices.iter_mut().zip(scaled) {
            let Some(direction) = crate::math::try_normalize(*v) else {
                return false;
            };
            *unit = direction;
        }
        let unit = polygon.vertices;
        // Edge planes, oriented by the side of the plane the shading point is on.
        let orientation = if plane_offset > 0.0 { 1.0 } else { -1.0 };
        for i in 0..count {
            polygon.edge_normals[i] = orientation * unit[i].cross(unit[(i + 1) % count]);
        }
        // Per fan triangle: Girard's area and the quantities of Arvo's algorithm.
        let a = unit[0];
        let mut total = 0.0;
        for i in 0..count - 2 {
            let (b, c) = (unit[i + 1], unit[i + 2]);
            let triangle = girard(a, b, c);
            let area = if triangle.area > 0.0 {
                triangle.area
            } else {
                0.0
            };
            polygon.areas[i] = area;
            polygon.alpha[i] = triangle.alpha;
            polygon.cos_alpha[i] = triangle.cos_alpha;
            let sin_alpha = libm::sinf(triangle.alpha);
            polygon.sin_alpha[i] = sin_alpha;
            polygon.sin_alpha_cos_c[i] = sin_alpha * a.dot(b);
            polygon.towards_c[i] = crate::math::normalize_or_zero(c - c.dot(a) * a);
            total += area;
        }
        if !(total > 0.0 && total.is_finite()) {
            return false;
        }
        let mut running = 0.0;
        for i in 0..count - 2 {
            running += polygon.areas[i];
            polygon.cdf[i] = (running / total).min(1.0);
        }
        polygon.cdf[count - 3] = 1.0;
        // The unused slots as in the empty value: no stale or NaN word is left.
        for i in count..MAX_POLYGON_VERTICES {
            polygon.vertices[i] = Vec3::ZERO;
            polygon.edge_normals[i] = Vec3::ZERO;
        }
        for i in count - 2..MAX_FAN_TRIANGLES {
            polygon.towards_c[i] = Vec3::ZERO;
            polygon.areas[i] = 0.0;
            polygon.alpha[i] = 0.0;
            polygon.cos_alpha[i] = 1.0;
            polygon.sin_alpha[i] = 0.0;
            polygon.sin_alpha_cos_c[i] = 0.0;
            polygon.cdf[i] = 1.0;
        }
        polygon.solid_angle = total;
        polygon.inv_solid_angle = 1.0 / total;
        polygon.count = count as u32;
        true
    }

    /// Draws a direction uniform in the polygon's solid angle (up to Arvo's rounding).
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        let count = crate::polygon::stored_count(self.count, MAX_POLYGON_VERTICES);
        if count < 3 {
            return Sample::NONE;
        }
        let (u0, u1) = (
            crate::sample::clamp_random(u[0]),
            crate::sample::clamp_random(u[1]),
        );
        // Choose a fan triangle by solid angle, then reuse u0 within it.
        let triangles = count - 2;
        let mut i = 0;
        while i + 1 < triangles && u0 >= self.cdf[i] {
            i += 1;
        }
        let low = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        let u0 = ((u0 - low) / (self.cdf[i] - low)).min(1.0);
        let (a, b) = (self.vertices[0], self.vertices[i + 1]);
        let (cos_alpha, sin_alpha) = (self.cos_alpha[i], self.sin_alpha[i]);
        // The sub-triangle A B Ĉ of area Â: its angle at Ĉ is γ̂ = π + (Â - α) - β̂, and
        // the law of cosines for angles, cos γ̂ = -cos β̂ cos α + sin β̂ sin α cos c,
        // gives tan β̂ = -u / v; the same law at B then gives q = cos |AĈ|.
        let area_hat = u0 * self.areas[i];
        let phi = area_hat - self.alpha[i];
        let (s, t) = (libm::sinf(phi), libm::cosf(phi));
        let u = t - cos_alpha;
        let v = s + self.sin_alpha_cos_c[i];
        let q = ((v * t - u * s) * cos_alpha - v) / ((v * s + u * t) * sin_alpha);
        // Guard: rounding takes q out of [-1, 1] (NaN stays NaN and is caught below).
        let q = q.clamp(-1.0, 1.0);
        let c_hat = q * a + sqrt_clamped(1.0 - q * q) * self.towards_c[i];
        // A point on the arc B Ĉ with the cosine of its distance from B uniform.
        let z = 1.0 - u1 * (1.0 - c_hat.dot(b));
        let dir = z * b
            + sqrt_clamped(1.0 - z * z) * crate::math::normalize_or_zero(c_hat - c_hat.dot(b) * b);
        // Far, tiny triangles lose the unit length to about 1e-5 (found by fuzzing).
        let dir = crate::math::unit_if_needed(dir);
        // No sample where Arvo's f32 construction put the direction outside the polygon
        // by more than the rounding of a unit vector (issue 16, 5: 29% of the samples of
        // a 1e-6 sr polygon, far outside). A baseline keeps its algorithm's weaknesses
        // but must not lie about its density: the sample's pdf is `pdf(dir)`, whose
        // edge tests allow the rounding of an edge (see `within_edge_slack`). Arvo's
        // construction misses by more even on ordinary polygons at the edges of `u`
        // (2.1e-6 rad at u0 = 1 - ulp on an octagon): such draws are no sample.
        if !dir.is_finite() {
            return Sample::NONE;
        }
        Sample::new_or_none(dir, self.pdf(dir))
    }

    /// Whether the unit `dir` lies inside every edge plane or outside by at most the
    /// rounding: 4 ulps of a unit vector (2.4e-7 rad) plus the rounding of the edge
    /// normal `v_i × v_{i+1}` itself (2ε absolute in `dir · n`, which is `2ε / |n|` in
    /// angle for an edge of length `|n|`). False for NaN.
    fn within_edge_slack(&self, dir: Vec3) -> bool {
        const ANGLE: f32 = 2.0 * f32::EPSILON;
        const ABSOLUTE: f32 = 2.0 * f32::EPSILON;
        let count = crate::polygon::stored_count(self.count, MAX_POLYGON_VERTICES);
        self.edge_normals[..count]
            .iter()
            .all(|normal| dir.dot(*normal) >= -(ANGLE * crate::math::length(*normal) + ABSOLUTE))
            && dir.is_finite()
    }

    /// `1 / solid_angle` for directions inside the polygon (edge-plane sign tests with
    /// the normalised vertices), 0 outside and for NaN or zero directions. `dir` need
    /// not be normalised.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        let count = crate::polygon::stored_count(self.count, MAX_POLYGON_VERTICES);
        if count < 3 || !dir.is_finite() || dir == Vec3::ZERO {
            return 0.0;
        }
        if self.within_edge_slack(crate::math::normalize_scaled(dir)) {
            self.inv_solid_angle
        } else {
            0.0
        }
    }

    /// The polygon's solid angle, the sum of its fan triangles' Girard areas.
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::*;

    /// Facing the shading point, tilted.
    fn moderate(n: usize, reversed: bool) -> Vec<Vec3> {
        circle_polygon(n, [0.4, -0.3, 1.5], [-0.1, 0.2, -1.5], 0.8, reversed)
    }

    /// The plane nearly contains the direction to the polygon's centre: the cosine
    /// between them is about `tilt` (0.03: grazing; 0.3: oblique).
    fn grazing(n: usize, reversed: bool, tilt: f64) -> Vec<Vec3> {
        let center = [0.8, 0.3, 1.0];
        let c = normalize(center);
        let perpendicular = normalize(cross(c, [0.0, 0.0, 1.0]));
        circle_polygon(n, center, add(perpendicular, scale(c, tilt)), 0.5, reversed)
    }

    const GRAZING: f64 = 0.03;
    const OBLIQUE: f64 = 0.3;

    /// Every test polygon: moderate and grazing, both windings, 3, 4, 5 and 8 vertices.
    fn all_polygons() -> Vec<(String, Vec<Vec3>)> {
        let mut list = Vec::new();
        for n in [3, 4, 5, 8] {
            for reversed in [false, true] {
                list.push((
                    format!("{n}-gon moderate reversed={reversed}"),
                    moderate(n, reversed),
                ));
                list.push((
                    format!("{n}-gon grazing reversed={reversed}"),
                    grazing(n, reversed, GRAZING),
                ));
            }
        }
        list
    }

    fn solid_angle_f64(vertices: &[Vec3]) -> f64 {
        solid_angle_polygon_f64(&vertices.iter().map(|&v| d3(v)).collect::<Vec<_>>())
    }

    fn run(vertices: &[Vec3], subdivisions: usize, samples: u64, seed: u64) -> SamplerReport {
        let arvo = ArvoPolygon::new(vertices).expect("valid polygon");
        run_polygon_sampler(
            vertices,
            subdivisions,
            samples,
            seed,
            |c| solid_angle_triangle_f64(c[0], c[1], c[2]),
            |u| arvo.sample(u),
            |d| arvo.pdf(d),
        )
    }

    /// Moderate and oblique polygons must pass the chi-square test. At grazing angles
    /// (cos ≈ 0.03) the faithful f32 Arvo does not (see
    /// `arvo_grazing_slivers_show_the_known_bias`): there only robustness is asserted
    /// and the p-values are printed.
    fn check_distribution(n: usize, subdivisions: usize) {
        let mut seed = 1000 * n as u64;
        for reversed in [false, true] {
            // (name, polygon, chi-square must pass, most samples outside, largest angle outside)
            for (name, vertices, must_pass, outside_fraction, outside_angle) in [
                ("moderate", moderate(n, reversed), true, 1e-3, 1e-6),
                ("oblique", grazing(n, reversed, OBLIQUE), true, 1e-3, 1e-4),
                ("grazing", grazing(n, reversed, GRAZING), false, 1e-2, 1e-2),
            ] {
                seed += 1;
                let report = run(&vertices, subdivisions, 1_000_000, seed);
                let what = format!("{n}-gon {name} reversed={reversed}: {report:?}");
                println!("arvo {what}");
                if must_pass {
                    assert!(report.p_value > CHI_SQUARE_ALPHA, "{what}");
                }
                // Draws that Arvo's f32 construction puts outside by more than the
                // rounding are no sample (issue 16, 5): none on moderate polygons, and
                // no more than the share allowed outside on oblique and grazing ones.
                if name == "moderate" {
                    assert_eq!(report.non_finite, 0, "{what}");
                } else {
                    assert!(
                        (report.non_finite as f64) < outside_fraction * report.samples as f64,
                        "{what}"
                    );
                }
                assert!(
                    (report.outside as f64) < outside_fraction * report.samples as f64,
                    "{what}"
                );
                assert!(report.worst_outside_angle < outside_angle, "{what}");
            }
        }
    }

    #[test]
    fn arvo_chi_square_triangle() {
        check_distribution(3, 10);
    }

    #[test]
    fn arvo_chi_square_quad() {
        check_distribution(4, 10);
    }

    #[test]
    fn arvo_chi_square_pentagon() {
        check_distribution(5, 8);
    }

    #[test]
    fn arvo_chi_square_octagon() {
        check_distribution(8, 6);
    }

    /// Girard's formula cancels for sliver fan triangles: at grazing angles the 8-gon's
    /// last fan triangle (interior angle at the apex ≈ 0.004 rad) gets a solid angle
    /// several percent off, which the chi-square test sees. This documents the baseline's
    /// known weakness and fails should Arvo be made more precise than the original.
    #[test]
    fn arvo_grazing_slivers_show_the_known_bias() {
        let vertices = grazing(8, false, GRAZING);
        let arvo = ArvoPolygon::new(&vertices).unwrap();
        let v: Vec<D3> = vertices.iter().map(|&p| d3(p)).collect();
        let mut worst = 0.0f64;
        for i in 0..6 {
            let reference = solid_angle_triangle_f64(v[0], v[i + 1], v[i + 2]);
            let relative = (arvo.areas[i] as f64 - reference) / reference;
            println!(
                "arvo grazing 8-gon fan triangle {i}: Girard {:.6e} sr, f64 {reference:.6e} sr, relative error {relative:.2e}",
                arvo.areas[i]
            );
            worst = worst.max(relative.abs());
        }
        assert!(
            worst > 1e-2,
            "Girard's area should cancel for slivers (worst {worst:e})"
        );
        let report = run(&vertices, 6, 1_000_000, 77);
        println!("arvo grazing 8-gon: {report:?}");
        assert!(report.p_value < CHI_SQUARE_ALPHA, "{report:?}");
    }

    #[test]
    fn arvo_solid_angle_matches_f64() {
        for (name, vertices) in all_polygons() {
            let arvo = ArvoPolygon::new(&vertices).unwrap();
            let reference = solid_angle_f64(&vertices);
            let relative = (arvo.solid_angle() as f64 - reference).abs() / reference;
            // Girard's formula in f32: ~1e-6 for moderate sizes, up to ~2e-3 at grazing.
            let allowed = if name.contains("moderate") {
                1e-5
            } else {
                5e-3
            };
            assert!(
                relative < allowed,
                "{name}: {} vs {reference}",
                arvo.solid_angle()
            );
        }
    }

    #[test]
    fn arvo_pdf_is_one_over_the_solid_angle_inside() {
        let mut seed = 3;
        for (name, vertices) in all_polygons() {
            seed += 1;
            let arvo = ArvoPolygon::new(&vertices).unwrap();
            let expected = 1.0 / arvo.solid_angle();
            let mut rng = Rng::new(seed);
            let mut rejected = 0;
            let samples = 200_000;
            for _ in 0..samples {
                let s = arvo.sample([rng.uniform_f32(), rng.uniform_f32()]);
                // Exactly 1/Ω, or no sample where Arvo's construction put the direction
                // outside by more than the rounding (issue 16, 5); the sample's pdf is
                // `pdf(dir)` either way.
                assert!(s.pdf == expected || s.pdf == 0.0, "{name}: {s:?}");
                assert!((s.dir.length() - 1.0).abs() < 1e-5, "{name}: {s:?}");
                let p = if s.pdf > 0.0 { arvo.pdf(s.dir) } else { 0.0 };
                assert_eq!(p, s.pdf, "{name}");
                rejected += (p == 0.0) as u64;
                // Scaling by powers of two is exact: the pdf must not change.
                assert_eq!(arvo.pdf(s.dir * 4.0), p, "{name}");
                assert_eq!(arvo.pdf(s.dir * 0.0009765625), p, "{name}");
            }
            let allowed = if name.contains("moderate") {
                samples / 10_000
            } else {
                samples / 100
            };
            println!("arvo {name}: {rejected} of {samples} draws are no sample");
            assert!(
                rejected <= allowed,
                "{name}: {rejected} draws without a sample"
            );
        }
    }

    /// ∫ cos θ dω over the polygon by Lambert's formula, f64:

    #[test]
    fn arvo_lambert_reference_matches_cell_integration() {
        for vertices in [moderate(8, true), grazing(3, false, GRAZING)] {
            let cells =
                PolygonCells::new(&vertices.iter().map(|&v| d3(v)).collect::<Vec<_>>(), 200);
            let midpoint: f64 = cells
                .cells
                .iter()
                .map(|c| {
                    let centroid = normalize(scale(add(c[0], add(c[1], c[2])), 1.0 / 3.0));
                    solid_angle_triangle_f64(c[0], c[1], c[2]) * centroid[2]
                })
                .sum();
            let lambert = projected_solid_angle_polygon_f64(&vertices);
            assert!(
                (midpoint - lambert).abs() < 1e-5 * lambert.abs(),
                "{midpoint} vs {lambert}"
            );
        }
    }

    #[test]
    fn arvo_estimates_the_cosine_integral() {
        let mut seed = 70;
        for (name, vertices) in all_polygons() {
            seed += 1;
            let arvo = ArvoPolygon::new(&vertices).unwrap();
            let mut rng = Rng::new(seed);
            let mut estimate = Estimate::default();
            let mut dropped = 0u32;
            for _ in 0..200_000 {
                let s = arvo.sample([rng.uniform_f32(), rng.uniform_f32()]);
                // A draw that Arvo's construction put outside is no sample (issue 16,
                // 5) and contributes 0: never on moderate polygons.
                if s.pdf > 0.0 {
                    estimate.add(s.dir.z as f64 / s.pdf as f64);
                } else {
                    assert!(!name.contains("moderate"), "{name}: no sample");
                    dropped += 1;
                    estimate.add(0.0);
                }
            }
            let reference = projected_solid_angle_polygon_f64(&vertices);
            // The relative term covers the error of Girard's solid angle (1/pdf) and the
            // energy of the dropped draws.
            let relative = if name.contains("moderate") {
                2e-5
            } else {
                3e-3 + dropped as f64 / 200_000.0
            };
            estimate.assert_mean_is(reference, 5.0, relative, &format!("arvo {name}"));
        }
    }

    #[test]
    fn arvo_rejects_bad_input() {
        let triangle = moderate(3, false);
        for bad in invalid_polygons(&triangle) {
            assert!(ArvoPolygon::new(&bad).is_none(), "{bad:?}");
        }
        for good in valid_edge_case_polygons() {
            assert!(ArvoPolygon::new(&good).is_some(), "{good:?}");
        }
        // Scale does not matter: huge and tiny coordinates give the same solid angle.
        let reference = ArvoPolygon::new(&triangle).unwrap().solid_angle();
        for factor in [1e30f32, 1e-30] {
            let scaled: Vec<Vec3> = triangle.iter().map(|&v| v * factor).collect();
            let arvo = ArvoPolygon::new(&scaled).expect("scaled triangle");
            assert!((arvo.solid_angle() - reference).abs() <= 1e-5 * reference);
        }
    }

    #[test]
    fn arvo_empty_and_degenerate_queries() {
        let e = ArvoPolygon::EMPTY;
        assert_eq!(e.sample([0.5, 0.5]), Sample::NONE);
        assert_eq!(e.pdf(Vec3::Z), 0.0);
        assert_eq!(e.solid_angle(), 0.0);
        let arvo = ArvoPolygon::new(&moderate(5, true)).unwrap();
        for dir in [
            Vec3::ZERO,
            Vec3::NAN,
            Vec3::INFINITY,
            Vec3::new(f32::NAN, 0.0, 1.0),
        ] {
            assert_eq!(arvo.pdf(dir), 0.0, "{dir:?}");
        }
        let center = Vec3::new(0.4, -0.3, 1.5);
        assert_eq!(arvo.pdf(center), 1.0 / arvo.solid_angle());
        assert_eq!(arvo.pdf(center * 1e-30), 1.0 / arvo.solid_angle());
        assert_eq!(arvo.pdf(-center), 0.0);
        assert_eq!(arvo.pdf(Vec3::new(0.0, 0.0, -1.0)), 0.0);
        assert_eq!(arvo.pdf(Vec3::new(1.0, 0.0, 0.0)), 0.0);
    }

    #[test]
    fn arvo_extreme_random_numbers_give_finite_samples() {
        let edge = [
            0.0,
            0.5,
            crate::sample::ONE_MINUS_ULP,
            1.0,
            -0.0,
            f32::NAN,
            2.0,
            -1.0,
        ];
        for (name, vertices) in all_polygons() {
            let arvo = ArvoPolygon::new(&vertices).unwrap();
            for &u0 in &edge {
                for &u1 in &edge {
                    let s = arvo.sample([u0, u1]);
                    // A draw at the edges of u may be no sample (issue 16, 5: Arvo's
                    // construction misses by 2e-6 rad there); its pdf is `pdf(dir)`.
                    assert!(s.dir.is_finite(), "{name} {u0} {u1}: {s:?}");
                    assert_eq!(s.pdf, if s.pdf > 0.0 { arvo.pdf(s.dir) } else { 0.0 });
                    assert!(
                        (s.dir.length() - 1.0).abs() < 1e-5,
                        "{name} {u0} {u1}: {s:?}"
                    );
                    if s.pdf > 0.0 {
                        assert_eq!(s.pdf, 1.0 / arvo.solid_angle());
                    }
                }
            }
        }
    }

    /// A nearly equilateral triangle of about `target` sr at distance `distance` along a
    /// generic direction, tilted against the viewing direction; `apex` rotates which
    /// vertex is Arvo's `A`.
    fn small_triangle(target: f64, distance: f64, apex: usize) -> Vec<Vec3> {
        let center = scale(normalize([0.3, 0.2, 1.0]), distance);
        let normal = normalize(add(scale(normalize(center), -1.0), [0.2, -0.1, 0.1]));
        let e1 = normalize(cross(normal, [1.0, 0.0, 0.0]));
        let e2 = cross(normal, e1);
        let make = |r: f64| -> Vec<D3> {
            [0.3f64, 2.4, 4.2]
                .iter()
                .map(|&angle| {
                    add(
                        center,
                        add(scale(e1, r * angle.cos()), scale(e2, r * angle.sin())),
                    )
                })
                .collect()
        };
        let mut r = 1e-3 * distance;
        for _ in 0..4 {
            r *= (target / solid_angle_polygon_f64(&make(r))).sqrt();
        }
        let v = make(r);
        (0..3)
            .map(|k| v[(k + apex) % 3])
            .map(|p| Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32))
            .collect()
    }

    /// Fractions of samples outside the triangle (f64 edge-plane tests with the f32
    /// vertices): at all, by more than 1e-6 rad (beyond the rounding of a direction), by
    /// more than 10% of the triangle's angular size; and of samples that are NONE.
    fn outside_fractions(vertices: &[Vec3], samples: u64, seed: u64) -> [f64; 4] {
        let arvo = ArvoPolygon::new(vertices).unwrap();
        let p: Vec<D3> = vertices.iter().map(|&v| d3(v)).collect();
        let centroid = add(p[0], add(p[1], p[2]));
        let inward: Vec<D3> = (0..3)
            .map(|i| normalize(cross(p[i], sub(p[(i + 1) % 3], p[i]))))
            .map(|e| {
                if dot(e, centroid) < 0.0 {
                    scale(e, -1.0)
                } else {
                    e
                }
            })
            .collect();
        let size = solid_angle_polygon_f64(&p).sqrt();
        let mut rng = Rng::new(seed);
        let mut counts = [0u64; 4];
        for _ in 0..samples {
            let s = arvo.sample([rng.uniform_f32(), rng.uniform_f32()]);
            if s.pdf == 0.0 {
                counts[3] += 1;
                continue;
            }
            let d = normalize(d3(s.dir));
            let outside = inward.iter().map(|e| -dot(*e, d)).fold(f64::MIN, f64::max);
            counts[0] += (outside > 0.0) as u64;
            counts[1] += (outside > 1e-6) as u64;
            counts[2] += (outside > 0.1 * size) as u64;
        }
        counts.map(|c| c as f64 / samples as f64)
    }

    #[test]
    fn arvo_outside_fraction_grows_for_tiny_triangles() {
        let samples = 1_000_000;
        println!(
            "arvo: fractions of samples outside a nearly equilateral triangle, {samples} samples each"
        );
        println!(
            "  apex = which vertex is Arvo's A; > 1e-6: outside by more than 1e-6 rad; > 10%: by more than 10% of √Ω"
        );
        println!(
            "  target sr | distance | apex | f64 sr     | Girard sr  | outside  | > 1e-6   | > 10%    | NONE"
        );
        for (k, target) in [1e-2, 1e-4, 1e-5, 1e-6, 1e-8].into_iter().enumerate() {
            let mut mean_outside = 0.0;
            for (distance, apex) in [(1.0, 0), (1.0, 1), (1.0, 2), (1e3, 0)] {
                let vertices = small_triangle(target, distance, apex);
                let reference =
                    solid_angle_polygon_f64(&vertices.iter().map(|&v| d3(v)).collect::<Vec<_>>());
                let Some(arvo) = ArvoPolygon::new(&vertices) else {
                    println!(
                        "  {target:9.0e} | {distance:8.0e} | {apex:4} | {reference:.4e} | new() returned None (Girard area <= 0)"
                    );
                    assert!(target < 1e-2, "Arvo rejected a {target} sr triangle");
                    continue;
                };
                let f = outside_fractions(&vertices, samples, 500 + 10 * k as u64 + apex as u64);
                println!(
                    "  {target:9.0e} | {distance:8.0e} | {apex:4} | {reference:.4e} | {:.4e} | {:.2e} | {:.2e} | {:.2e} | {:.2e}",
                    arvo.solid_angle(),
                    f[0],
                    f[1],
                    f[2],
                    f[3]
                );
                if target == 1e-2 {
                    if distance == 1.0 {
                        mean_outside += f[0] / 3.0;
                    }
                    // At 1e-2 sr the samples outside are on an edge, outside by rounding.
                    assert!(f[1] < 1e-5 && f[2] == 0.0 && f[3] == 0.0, "{f:?}");
                }
            }
            if target == 1e-2 {
                println!(
                    "  1e-2 sr: outside fraction averaged over the three apices: {mean_outside:.3e}"
                );
                assert!(mean_outside < 1e-3, "{mean_outside}");
            }
        }
    }
}
