//! Arvo's projected solid angle sampling of polygons, the baseline of Peters 2021 (Table
//! A.2, "Proj., Arvo"): the same sectors and areas as
//! [`ProjectedPolygon`](crate::polygon::ProjectedPolygon), but the
//! azimuth within a sector comes from inverting its area function `F(φ)` numerically, as
//! Arvo (2001) does, instead of Peters' homogeneous quadratics.
//!
//! Within a sector of angle `h` starting at `s0`, the area up to azimuth `φ` is
//! `F(φ) = A_o(φ) - A_i(φ)` (the ellipse sector areas of Equation (1); `A_i = 0` in the
//! central case) with derivative `F'(φ) = (r_o(φ)² - r_i(φ)²) / 2`, where
//! `r_l(φ)² = 1 / (eᵀ C_l e)` for the unit direction `e` at `φ`. The initial guess is the
//! cubic Hermite interpolant of the inverse function `φ(A)` through its end points with
//! slopes `1 / F'` (clamped to keep it monotonic); Newton steps on `F(φ) = A`, clamped to
//! the sector `[0, h]`, refine it until the step is below `1e-7 h` (at most
//! [`NEWTON_STEPS`]). Each step costs a `sin`/`cos` pair and two `atan`s, which is what
//! makes this baseline slower than Peters' method. The radial step and the pdf
//! (`ω_z / Φ` inside the polygon) are the same as in the unbiased sampler.

use super::super::ellipse::{add2, det2, dot2, rotate, scale2};
use super::super::ellipse_sector::{AreaPrecision, point_between_ellipses};
use super::super::projected::ProjectedPolygon;
use crate::sample::{clamp_random, select_piece};
use crate::{MAX_POLYGON_VERTICES, Sample, Vec3};

/// The most Newton steps per sample.
pub const NEWTON_STEPS: u32 = 8;

/// A convex polygon prepared for Arvo's projected solid angle sampling.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArvoProjectedPolygon {
    sectors: ProjectedPolygon,
    /// The angle of each sector in radians.
    sector_angle: [f32; MAX_POLYGON_VERTICES],
}

impl Default for ArvoProjectedPolygon {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl ArvoProjectedPolygon {
    /// The state of a polygon that could not be prepared: samples have `pdf == 0`.
    pub const EMPTY: Self = Self {
        sectors: ProjectedPolygon::EMPTY,
        sector_angle: [0.0; MAX_POLYGON_VERTICES],
    };

    /// Prepares the polygon (same input and rejections as
    /// [`ProjectedPolygon::new`], but without the small-polygon alternative).
    #[must_use]
    pub fn new(vertices: &[Vec3]) -> Option<Self> {
        let mut polygon = Self::EMPTY;
        polygon.prepare(vertices).then_some(polygon)
    }

    /// [`new`](Self::new) in place: writes the prepared polygon into `self` and returns
    /// `true`, or writes [`EMPTY`](Self::EMPTY) and returns `false` (2320 bytes, written
    /// once).
    pub fn prepare(&mut self, vertices: &[Vec3]) -> bool {
        if !self.sectors.prepare_sectors_only(vertices) {
            self.sector_angle = [0.0; MAX_POLYGON_VERTICES];
            return false;
        }
        let selectable = self.sectors.selectable_sectors as usize;
        for j in 0..MAX_POLYGON_VERTICES {
            let sector = self.sectors.sector(j);
            let (s0, s1) = (sector.s0(), sector.s1());
            // Unused slots 0, as in the empty value.
            self.sector_angle[j] = if j < selectable {
                crate::math::atan2_upper_half_plane(det2(s0, s1).max(0.0), dot2(s0, s1))
            } else {
                0.0
            };
        }
        true
    }

    /// The projected solid angle `Φ` in steradians (0 when empty).
    #[inline]
    pub fn projected_solid_angle(&self) -> f32 {
        self.sectors.projected_solid_angle
    }

    /// Draws a direction with density `ω_z / Φ`; `u` is clamped to `[0, 1 - ulp]`.
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        let sectors = &self.sectors;
        if sectors.selectable_sectors == 0 {
            return Sample::NONE;
        }
        let (u0, u1) = (clamp_random(u[0]), clamp_random(u[1]));
        let target = u0 * sectors.projected_solid_angle;
        let k = select_piece(&sectors.sector_start, target);
        let area = sectors.sector_area[k];
        // `max(0).min(b)` rather than `clamp(0, b)`, here and below: `clamp` panics (an
        // abort across the C ABI) when a bound read from a corrupted value is NaN or
        // negative (issue 16, 6); `min` and `max` return a number.
        let local = (target - sectors.sector_start[k]).max(0.0).min(area);
        let central = sectors.central != 0;
        let sector = &sectors.sector(k);
        let s0 = sector.s0();
        let h = self.sector_angle[k];
        let direction = |phi: f32| {
            let (sin, cos) = libm::sincosf(phi);
            add2(scale2(s0, cos), scale2(rotate(s0), sin))
        };
        // F'(φ) = (r_o² - r_i²) / 2 at the unit direction e, with r_l² = 1 / (1 + (u_l·e)²).
        let slope = |e: [f32; 2]| {
            let (i, o) = sector.dots(e);
            let inner = if central { 0.0 } else { 1.0 / (1.0 + i * i) };
            0.5 * (1.0 / (1.0 + o * o) - inner)
        };
        let area_to = |e: [f32; 2]| {
            let (det, dot) = (det2(s0, e), dot2(s0, e));
            if central {
                sector.outer_area(det, dot, sector.dots(e).1, AreaPrecision::Exact)
            } else {
                // The coordinates of e, with its det and dot from e itself as before.
                let mut c = sector.coordinates(e);
                (c.det, c.dot) = (det, dot);
                sector.area_between(&c, AreaPrecision::Exact)
            }
        };
        // Cubic Hermite guess for the inverse function, slopes in units of the fraction t.
        let t = local / area;
        let limit = 3.0 * h;
        let m0 = (area / slope(s0)).max(0.0).min(limit);
        let m1 = (area / slope(sector.s1())).max(0.0).min(limit);
        let (t2, t3) = (t * t, t * t * t);
        let guess = (t3 - 2.0 * t2 + t) * m0 + (3.0 * t2 - 2.0 * t3) * h + (t3 - t2) * m1;
        let mut phi = if guess.is_finite() {
            guess.max(0.0).min(h)
        } else {
            t * h
        };
        for _ in 0..NEWTON_STEPS {
            let e = direction(phi);
            let step = (area_to(e) - local) / slope(e);
            if !step.is_finite() {
                break;
            }
            phi = (phi - step).max(0.0).min(h);
            if step.abs() <= 1e-7 * h {
                break;
            }
        }
        let e = direction(phi);
        let (i, o) = sector.dots(e);
        let (point, z2) = if central {
            let q = 1.0 + o * o;
            let z2 = ((1.0 - u1) + o * o) / q;
            (scale2(e, crate::math::sqrtf(u1 / q)), z2)
        } else {
            let Some(point_and_z2) = point_between_ellipses(e, u1, dot2(e, e), i, o) else {
                return Sample::NONE;
            };
            point_and_z2
        };
        let dir = Vec3::new(point[0], point[1], crate::math::sqrtf(z2.max(0.0)));
        if !dir.is_finite() {
            return Sample::NONE;
        }
        // The density that `pdf` gives the direction: 0 where the f32 construction put
        // it outside the polygon (issue 16, 5: 40% of the samples of polygons 1e-4 rad
        // across, up to 565 radii away). A baseline keeps its algorithm's weaknesses
        // but must not lie about its density: such samples are no sample.
        Sample::new_or_none(dir, self.pdf(dir))
    }

    /// `ω_z / Φ` inside the polygon and above the horizon, 0 otherwise.
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        self.sectors.pdf(dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::*;

    /// Regression (found by the fuzz target `polygon`): a polygon with a vertex a few
    /// ulps above the horizon drew, at `u = (0, 0)`, a direction exactly on the horizon
    /// with pdf 0 but not the canonical "no sample" direction `(0, 0, 1)`.
    #[test]
    fn a_sample_on_the_horizon_is_no_sample() {
        let v = [
            Vec3::new(-5.375, -5.75, -5.375),
            Vec3::new(-5.375, -0.375, -6.125),
            Vec3::new(2.349_487_1e-7, -0.375_000_24, 3.005_158e-7),
            Vec3::new(0.0, -5.75, 0.75),
        ];
        let polygon = ArvoProjectedPolygon::new(&v).expect("part of it lies above the horizon");
        for u in [
            [0.0, 0.0],
            [0.0, 0.5],
            [0.5, 0.0],
            [crate::sample::ONE_MINUS_ULP, 0.0],
        ] {
            let s = polygon.sample(u);
            assert!(s.pdf > 0.0 || s == Sample::NONE, "{u:?}: {s:?}");
        }
        assert_eq!(polygon.sample([0.0, 0.0]), Sample::NONE);
    }

    fn cell_weight(c: &[D3; 3]) -> f64 {
        projected_solid_angle_d3(c).abs()
    }

    #[test]
    fn samples_follow_the_cosine_on_central_and_decentral_polygons() {
        let mut rng = Rng::new(31);
        let mut cases = [0, 0];
        for n in 3..=8 {
            for central in [true, false] {
                let center = if central {
                    Vec3::new(0.1, -0.05, 1.0)
                } else {
                    Vec3::new(1.5, 0.3, 1.0)
                };
                let v = ellipse_polygon(&mut rng, n, center, Vec3::new(0.2, 0.1, 1.0), 0.7, 0.6);
                let polygon = ArvoProjectedPolygon::new(&v).expect("valid");
                cases[(polygon.sectors.central != 0) as usize] += 1;
                let reference = projected_solid_angle_polygon_f64(&v);
                let e = (polygon.projected_solid_angle() as f64 - reference).abs() / reference;
                assert!(e < 1e-4, "{e}");
                let report = run_polygon_sampler(
                    &v,
                    8,
                    60_000,
                    n as u64,
                    cell_weight,
                    |u| polygon.sample(u),
                    |d| polygon.pdf(d),
                );
                assert!(
                    report.p_value > CHI_SQUARE_ALPHA,
                    "{n} {central}: {report:?}"
                );
                assert_eq!(report.non_finite, 0);
                assert!(
                    report.outside <= 60 && report.worst_outside_angle < 1e-6,
                    "{report:?}"
                );
                assert!(
                    report.worst_pdf_mismatch < 1e-4 || report.outside > 0,
                    "{report:?}"
                );
            }
        }
    }

    #[test]
    fn bad_input_is_rejected_and_extreme_random_numbers_are_safe() {
        let triangle = [
            Vec3::new(0.1, 0.2, 1.0),
            Vec3::new(0.5, 0.1, 1.2),
            Vec3::new(0.2, 0.6, 0.9),
        ];
        for v in invalid_polygons(&triangle) {
            assert_eq!(ArvoProjectedPolygon::new(&v), None, "{v:?}");
        }
        assert_eq!(ArvoProjectedPolygon::EMPTY.sample([0.5, 0.5]).pdf, 0.0);
        let polygon = ArvoProjectedPolygon::new(&triangle).unwrap();
        for a in [0.0, 1e-5, 0.5, 1.0, f32::NAN, -1.0] {
            for b in [0.0, 1e-5, 0.5, 1.0, f32::NAN, 2.0] {
                let s = polygon.sample([a, b]);
                // At the edges of u the f32 construction may miss the polygon: no sample
                // then (issue 16, 5), never a non-finite one, and never a pdf that
                // `pdf` does not give the direction.
                assert!(s.dir.is_finite() && s.pdf.is_finite() && s.pdf >= 0.0);
                assert_eq!(s.pdf, if s.pdf > 0.0 { polygon.pdf(s.dir) } else { 0.0 });
                assert!(s.pdf > 0.0 || a.is_nan() || b.is_nan() || a != 0.5 || b != 0.5);
            }
        }
    }
}

/// Issue 16 (5): both Arvo baselines on small polygons. Every sample's pdf is what `pdf`
/// gives its direction (samples that the f32 construction puts outside have none), and
/// the share of draws without a sample per angular size, which the header states as the
/// size below which they are unreliable. The quad (1e-5 rad across) and `u`:
/// a sample far outside with pdf > 0 before.
#[cfg(test)]
mod small_polygon_tests {
    use super::*;
    use crate::polygon::baselines::ArvoPolygon;
    use crate::testing::Rng;

    #[test]
    fn arvo_baselines_do_not_lie_about_their_density_on_small_polygons() {
        let b = |x: u32, y: u32, z: u32| {
            Vec3::new(f32::from_bits(x), f32::from_bits(y), f32::from_bits(z))
        };
        let quad = [
            b(0x3f345e2a, 0x3e9882d4, 0x3f24ed54),
            b(0x3f3455f8, 0x3e988b7a, 0x3f24eadf),
            b(0x3f3451a5, 0x3e987b14, 0x3f24e992),
            b(0x3f3459d7, 0x3e98726e, 0x3f24ec08),
        ];
        let u = [f32::from_bits(0x3f125013), f32::from_bits(0x3d6ba5e0)];
        let p = ArvoProjectedPolygon::new(&quad).expect("prepared");
        let s = p.sample(u);
        assert_eq!(s.pdf, p.pdf(s.dir), "{s:?}");
        let mut rng = Rng::new(41);
        let mut dropped = [[0u32; 2]; 4];
        let sizes = [1e-2f32, 1e-3, 1e-4, 1e-5];
        for (k, &size) in sizes.iter().enumerate() {
            for _ in 0..200 {
                let centre = Vec3::new(0.3 * rng.uniform_f32(), 0.3 * rng.uniform_f32(), 1.0);
                let square = [
                    centre + Vec3::new(-size, -size, 0.0),
                    centre + Vec3::new(size, -size * 0.7, 0.0),
                    centre + Vec3::new(size * 0.8, size, 0.0),
                    centre + Vec3::new(-size, size * 0.9, 0.0),
                ];
                let projected = ArvoProjectedPolygon::new(&square);
                let solid = ArvoPolygon::new(&square);
                for _ in 0..50 {
                    let u = [rng.uniform_f32(), rng.uniform_f32()];
                    if let Some(p) = &projected {
                        let s = p.sample(u);
                        assert_eq!(s.pdf, p.pdf(s.dir));
                        dropped[k][0] += (s.pdf == 0.0) as u32;
                    }
                    if let Some(p) = &solid {
                        let s = p.sample(u);
                        assert_eq!(s.pdf, p.pdf(s.dir));
                        dropped[k][1] += (s.pdf == 0.0) as u32;
                    }
                }
            }
        }
        std::println!("dropped of 10,000 per size (projected, solid angle): {dropped:?}");
        // The header's statement: from 1e-2 rad across both keep (nearly) every draw.
        assert!(dropped[0][0] < 100 && dropped[0][1] < 100, "{dropped:?}");
    }
}
