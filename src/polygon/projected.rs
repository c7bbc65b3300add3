//! Projected solid angle sampling of convex polygons (Peters 2021, Sec. 3–4, supplement
//! A.2–A.7, Algorithms 3 and 4): directions distributed exactly in proportion to
//! `cos θ = ω_z` inside a polygonal light, so that a diffuse surface lit by an unoccluded
//! Lambertian polygon is estimated with zero variance.
//!
//! Projected to the unit disk (see [`ellipse`](super::ellipse)), the polygon becomes a
//! region bounded by ellipse arcs, and sampling it uniformly by area is sampling its
//! directions in proportion to the cosine. The region is cut into sectors at the
//! vertices' azimuths. If the zenith lies inside the polygon (the *central* case), every
//! sector reaches from the origin out to one ellipse and is sampled in closed form. If
//! not (the *decentral* case), the vertices are sorted by azimuth (a bitonic sequence,
//! sorted by an optimal network of supplement A.6) and every sector lies between an
//! inner and an outer ellipse; its area is inverted by an initial guess from two quads
//! (Proposition 3) followed by an iteration with cubic convergence (supplement A.3–A.5).
//!
//! Polygons are given relative to the shading point in the local frame (z = normal), in
//! either winding; the part below the horizon is clipped away first (supplement A.1).
//!
//! Hard cases, each covered by a named test: central and decentral polygons of 3 to 8
//! vertices, one and two edges whose great circles pass through the zenith (A.2, Fig.
//! A.1 a and b), a vertex at the zenith, the shading point in the polygon's plane,
//! polygons touching and crossing the horizon, tiny and near-hemisphere polygons,
//! `ξ0` at 0, 1e-5, 1 - 1e-5 and 1 - ulp.

use super::clip::clip_to_upper_hemisphere;
use super::ellipse::{
    DEGENERATE, Vec2, add2, det2, dot2, ellipse_area, ellipse_area_fast, ellipse_from_edge,
    is_degenerate, is_inner, rotate, scale2, solve_homogeneous_quadratic, unit_direction,
};
use super::small_projected::{SLIVER_EXTENT2, SMALL_EXTENT, SmallPolygonCosineSampler};
use super::solid_angle::rescale;
use crate::math::{copy_sign, cross_precise, difference_of_products, dot_precise};
use crate::sample::clamp_random;
use crate::{MAX_POLYGON_VERTICES, Sample, Vec3};

/// Refinement iterations of the unbiased sampler (Algorithm 3: two suffice for `f32`).
pub const REFINEMENT_ITERATIONS: u32 = 2;

/// Iterations are skipped for `ξ0` this close to 0 or 1, where the two tangent lines of
/// the iteration may meet near the solution (supplement A.3).
const ITERATION_MARGIN: f32 = 1e-5;

/// A convex polygon prepared for projected solid angle sampling: the first part of
/// Algorithm 4 (ellipses paired with sectors, sector areas).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectedSolidAnglePolygon {
    /// Unit direction of the clockwise boundary `s0` of each sector.
    pub(crate) sector_begin: [[f32; 2]; MAX_POLYGON_VERTICES],
    /// Unit direction of the counter-clockwise boundary `s1` of each sector.
    pub(crate) sector_end: [[f32; 2]; MAX_POLYGON_VERTICES],
    /// The inner ellipse of each sector (unused in the central case).
    pub(crate) inner: [[f32; 2]; MAX_POLYGON_VERTICES],
    /// The outer ellipse of each sector.
    pub(crate) outer: [[f32; 2]; MAX_POLYGON_VERTICES],
    /// `det(s0, s1)` of each sector, from the vertex positions (exact to a few ulp even
    /// for thin sectors, unlike the determinant of the rounded unit directions).
    pub(crate) sector_det: [f32; MAX_POLYGON_VERTICES],
    /// `(u_i · s0, u_i · s1)` of each sector, computed from the vertex positions.
    pub(crate) inner_dots: [[f32; 2]; MAX_POLYGON_VERTICES],
    /// `(u_o · s0, u_o · s1)` of each sector, computed from the vertex positions.
    pub(crate) outer_dots: [[f32; 2]; MAX_POLYGON_VERTICES],
    /// Projected solid angle (area in the disk) of each sector.
    pub(crate) sector_area: [f32; MAX_POLYGON_VERTICES],
    /// Projected solid angle of the sectors before each sector.
    pub(crate) sector_start: [f32; MAX_POLYGON_VERTICES],
    /// Inward edge plane normals of the clipped polygon, for the inside test of
    /// [`pdf`](Self::pdf) (zero in unused slots).
    edge_normals: [Vec3; MAX_POLYGON_VERTICES],
    /// Total projected solid angle `Φ = ∫ cos θ dω` (0 when empty).
    pub(crate) projected_solid_angle: f32,
    /// `1 / Φ` (0 when empty).
    pub(crate) density: f32,
    /// Sectors up to the last one with non-zero area (0 when empty).
    pub(crate) selectable_sectors: u32,
    /// 1 when the zenith lies inside the polygon (the central case), else 0.
    pub(crate) central: u32,
    /// 1 when the polygon is smaller than [`SMALL_EXTENT`] and `small` samples it.
    is_small: u32,
    /// The exact alternative for small polygons (empty otherwise).
    small: SmallPolygonCosineSampler,
}

impl Default for ProjectedSolidAnglePolygon {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// Which `atan` the sector areas use.
#[derive(Clone, Copy, PartialEq)]
enum AreaPrecision {
    Exact,
    Fast,
}

impl ProjectedSolidAnglePolygon {
    /// The state of a polygon that could not be prepared: samples have `pdf == 0`, and the
    /// pdf of every direction is 0.
    pub const EMPTY: Self = Self {
        sector_begin: [[0.0; 2]; MAX_POLYGON_VERTICES],
        sector_end: [[0.0; 2]; MAX_POLYGON_VERTICES],
        inner: [[0.0; 2]; MAX_POLYGON_VERTICES],
        outer: [[0.0; 2]; MAX_POLYGON_VERTICES],
        sector_det: [0.0; MAX_POLYGON_VERTICES],
        inner_dots: [[0.0; 2]; MAX_POLYGON_VERTICES],
        outer_dots: [[0.0; 2]; MAX_POLYGON_VERTICES],
        sector_area: [0.0; MAX_POLYGON_VERTICES],
        sector_start: [0.0; MAX_POLYGON_VERTICES],
        edge_normals: [Vec3::ZERO; MAX_POLYGON_VERTICES],
        projected_solid_angle: 0.0,
        density: 0.0,
        selectable_sectors: 0,
        central: 0,
        is_small: 0,
        small: SmallPolygonCosineSampler::EMPTY,
    };

    /// Prepares the convex polygon with the given vertices (positions relative to the
    /// shading point in the local frame, not normalised, either winding, 3 to 8 of them).
    /// The part below the horizon is clipped away.
    ///
    /// Returns `None` for fewer than 3 or more than 8 vertices, 8 vertices that need
    /// clipping (9 would result), non-finite coordinates, a polygon with nothing above the
    /// horizon, and a zero projected solid angle (for example when the shading point lies
    /// in the polygon's plane).
    pub fn new(vertices: &[Vec3]) -> Option<Self> {
        Self::prepare(vertices, AreaPrecision::Exact, true)
    }

    /// [`new`](Self::new) with a fast `atan` for the sector areas (relative error below
    /// 1.4e-4 per sector), for the biased variant [`sample_fast`](Self::sample_fast).
    /// **Biased**: the projected solid angle, and with it the pdf, is off by up to 1.4e-4
    /// relative.
    pub fn new_fast_biased(vertices: &[Vec3]) -> Option<Self> {
        Self::prepare(vertices, AreaPrecision::Fast, true)
    }

    /// The sectors of Algorithm 4 without the switch to the small-polygon sampler, for
    /// the baseline of Arvo that shares them.
    pub(crate) fn new_sectors_only(vertices: &[Vec3]) -> Option<Self> {
        Self::prepare(vertices, AreaPrecision::Exact, false)
    }

    fn prepare(vertices: &[Vec3], precision: AreaPrecision, allow_small: bool) -> Option<Self> {
        let count = vertices.len();
        if !(3..=MAX_POLYGON_VERTICES).contains(&count) {
            return None;
        }
        let mut positions = [Vec3::ZERO; MAX_POLYGON_VERTICES];
        rescale(vertices, &mut positions)?;
        let count = clip_to_upper_hemisphere(&mut positions, count);
        if count < 3 {
            return None;
        }
        // Orientation: the sign of Σ det(p0, pk, pk+1) = p0 · Σ (pk - p0) × (pk+1 - p0),
        // positive when the polygon winds counter-clockwise around the zenith seen from
        // above (and around its centre seen from the shading point). Zero means the
        // shading point lies in the polygon's plane: nothing to sample.
        let mut area_vector = Vec3::ZERO;
        for k in 1..count - 1 {
            area_vector += (positions[k] - positions[0]).cross(positions[k + 1] - positions[0]);
        }
        let orientation = area_vector.dot(positions[0]);
        if !(orientation != 0.0) {
            return None;
        }
        if orientation < 0.0 {
            positions[..count].reverse();
        }
        let mut polygon = Self::EMPTY;
        // Small polygons: the ellipses of nearby edges are nearly equal, and the areas
        // between them (differences of sector areas of order 1) lose about 6e-8 / s of
        // relative precision for an angular size s. Below SMALL_EXTENT the warped solid
        // angle sampler, whose only approximation is of relative order s², takes over.
        let first = positions[0] / positions[0].length();
        let mut extent2 = 0.0f32;
        for p in &positions[1..count] {
            extent2 = extent2.max((*p / p.length() - first).length_squared());
        }
        let switch_to_small = |mut polygon: Self| {
            let small = SmallPolygonCosineSampler::new(&positions[..count])?;
            polygon.projected_solid_angle = small.projected_solid_angle();
            polygon.density = 1.0 / polygon.projected_solid_angle;
            polygon.selectable_sectors = 1;
            polygon.is_small = 1;
            polygon.small = small;
            Some(polygon)
        };
        if allow_small && extent2 < SMALL_EXTENT * SMALL_EXTENT {
            return switch_to_small(Self::EMPTY);
        }
        // Algorithm 1 per edge; edge j runs from vertex j to vertex j + 1.
        let next = |j: usize| if j + 1 == count { 0 } else { j + 1 };
        let mut edge = [DEGENERATE; MAX_POLYGON_VERTICES];
        let mut direction = [[0.0f32; 2]; MAX_POLYGON_VERTICES];
        let mut xy_length = [0.0f32; MAX_POLYGON_VERTICES];
        for j in 0..count {
            let (u, normal) = ellipse_from_edge(positions[j], positions[next(j)]);
            edge[j] = u;
            polygon.edge_normals[j] = normal;
            direction[j] = unit_direction(positions[j]);
            xy_length[j] = dot2(direction[j], [positions[j].x, positions[j].y]);
        }
        // `u_e · s_c` for the ellipse of edge e and the direction of vertex c, from the
        // positions. With u = σ n_xy / n_z (n = p_a × p_b, σ the sign that marks inner
        // ellipses), u · s_c = σ (n_xy · p_c,xy) / (n_z |p_c,xy|) and
        // n_xy · p_c,xy = det(p_a, p_b, p_c) - n_z p_c,z. The determinant vanishes for the
        // edge's own vertices and is otherwise computed from edge vectors. Computed from
        // the rounded u instead, the dot product loses all precision when |u| is large
        // and s nearly orthogonal to it (a great circle passing near the zenith).
        let edge_dot = |e: usize, c: usize| -> f32 {
            let u = edge[e];
            if is_degenerate(u) || !(xy_length[c] > 0.0) {
                return 0.0;
            }
            let (a, b) = (e, next(e));
            let n = polygon.edge_normals[e];
            let p = positions[c];
            let triple = if c == a || c == b {
                0.0
            } else {
                let pa = positions[a];
                dot_precise(cross_precise(positions[b] - pa, p - pa), pa)
            };
            let normal_dot = difference_of_products(triple, 1.0, n.z, p.z);
            let sigma = copy_sign(1.0, n.x);
            let t = sigma * normal_dot / (n.z * xy_length[c]);
            if t.is_finite() { t } else { 0.0 }
        };
        // det(s_a, s_b) from the positions.
        let sector_det = |a: usize, b: usize| {
            let (pa, pb) = (positions[a], positions[b]);
            difference_of_products(pa.x, pb.y, pa.y, pb.x) / (xy_length[a] * xy_length[b])
        };
        let area = |u: Vec2, det: f32, dot: f32, t: [f32; 2]| match precision {
            AreaPrecision::Exact => ellipse_area(u, det, dot, t[0], t[1]),
            AreaPrecision::Fast => ellipse_area_fast(u, det, dot, t[0], t[1]),
        };
        // Algorithm 4, first part: each vertex is associated with the ellipse that leaves
        // it counter-clockwise: its own edge if that edge is outer, else the previous edge.
        // The inner ellipse of the first sector is the inner edge that ends at the
        // clockwise end of the polygon.
        let mut vertex_edge = [0usize; MAX_POLYGON_VERTICES];
        let mut first_inner = None;
        for j in 0..count {
            let previous = if j == 0 { count - 1 } else { j - 1 };
            vertex_edge[j] = if is_inner(edge[j]) { previous } else { j };
            if is_inner(edge[previous]) && !is_inner(edge[j]) {
                first_inner = Some(previous);
            }
        }
        let sectors;
        // Σ of the outer sector areas: Φ is their difference with the inner ones, and
        // their ratio is the factor by which rounding errors are amplified.
        let mut outer_sum = 0.0f32;
        if let Some(first_inner) = first_inner {
            // Decentral case: sort the vertices by azimuth. Vertex a comes before b when
            // det(p_a,xy, p_b,xy) > 0, computed from the clipped positions (not the rounded
            // unit directions) so that a degenerate edge's two vertices compare exactly
            // equal; then the one with the degenerate ellipse comes first (rule 3).
            let mut order = [0u8, 1, 2, 3, 4, 5, 6, 7];
            let xy = |k: u8| {
                let p = positions[k as usize];
                [p.x, p.y]
            };
            let degenerate = |k: u8| is_degenerate(edge[vertex_edge[k as usize]]);
            let less = |a: &u8, b: &u8| {
                let d = det2(xy(*a), xy(*b));
                d > 0.0 || (d == 0.0 && degenerate(*a) && !degenerate(*b))
            };
            sort_bitonic(&mut order, count, less);
            sectors = count - 1;
            let mut inner = first_inner;
            let mut outer = 0usize;
            for j in 0..sectors {
                let (a, b) = (order[j] as usize, order[j + 1] as usize);
                let e = vertex_edge[a];
                if j > 0 && is_inner(edge[e]) {
                    inner = e;
                }
                if j == 0 || !is_inner(edge[e]) {
                    outer = e;
                }
                let (det, dot) = (sector_det(a, b), dot2(direction[a], direction[b]));
                let inner_dots = [edge_dot(inner, a), edge_dot(inner, b)];
                let outer_dots = [edge_dot(outer, a), edge_dot(outer, b)];
                polygon.sector_begin[j] = direction[a];
                polygon.sector_end[j] = direction[b];
                polygon.sector_det[j] = det;
                polygon.inner[j] = edge[inner];
                polygon.outer[j] = edge[outer];
                polygon.inner_dots[j] = inner_dots;
                polygon.outer_dots[j] = outer_dots;
                let outer_area = area(edge[outer], det, dot, outer_dots);
                outer_sum += outer_area;
                polygon.sector_area[j] =
                    (outer_area - area(edge[inner], det, dot, inner_dots)).max(0.0);
            }
        } else {
            // Central case: sector j reaches from the origin to the ellipse of edge j,
            // which passes through both of the sector's vertices.
            polygon.central = 1;
            sectors = count;
            #[allow(clippy::needless_range_loop)] // j indexes several arrays and vertices
            for j in 0..count {
                let (a, b) = (j, next(j));
                let (det, dot) = (sector_det(a, b), dot2(direction[a], direction[b]));
                let outer_dots = [edge_dot(j, a), edge_dot(j, b)];
                polygon.sector_begin[j] = direction[a];
                polygon.sector_end[j] = direction[b];
                polygon.sector_det[j] = det;
                polygon.outer[j] = edge[j];
                polygon.outer_dots[j] = outer_dots;
                polygon.sector_area[j] = area(edge[j], det, dot, outer_dots);
            }
        }
        let mut total = 0.0f32;
        for j in 0..sectors {
            polygon.sector_start[j] = total;
            if polygon.sector_area[j] > 0.0 {
                polygon.selectable_sectors = j as u32 + 1;
            }
            total += polygon.sector_area[j];
        }
        let density = 1.0 / total;
        if !(total > 0.0) || !total.is_finite() || !density.is_finite() {
            return None;
        }
        // Slivers seen nearly edge-on: the inner and outer ellipses almost coincide and Φ
        // is a small difference of large areas, with a relative error of about
        // 3e-7 × outer_sum / Φ. The small-polygon sampler deviates from the cosine by
        // 0.2 extent² (and is exact for its own pdf); switch when that is smaller, as long
        // as it stays within the 1e-4 that the pdf contract allows.
        if allow_small && 3e-7 * outer_sum > 0.2 * extent2 * total && extent2 < SLIVER_EXTENT2 {
            return switch_to_small(polygon);
        }
        polygon.projected_solid_angle = total;
        polygon.density = density;
        Some(polygon)
    }

    /// Total projected solid angle `Φ = ∫ cos θ dω` of the part above the horizon, in
    /// steradians (0 when empty).
    #[inline]
    pub fn projected_solid_angle(&self) -> f32 {
        self.projected_solid_angle
    }

    /// Draws a direction with density `ω_z / Φ` inside the polygon (Algorithm 4, second
    /// part). `u` is clamped to `[0, 1 - ulp]`; NaN counts as 0. The pdf is `ω_z / Φ`, or 0
    /// (with a finite direction) for an empty polygon.
    #[inline]
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        self.sample_with_iterations(u, REFINEMENT_ITERATIONS)
    }

    /// The biased variant: no refinement iterations in the decentral case, so the azimuth
    /// is the initial guess of Proposition 3 (its error is in the report). **Biased**: the
    /// returned pdf is that of the exact distribution, `ω_z / Φ`, which differs from the
    /// density with which this function actually places its samples.
    #[inline]
    pub fn sample_fast(&self, u: [f32; 2]) -> Sample {
        self.sample_with_iterations(u, 0)
    }

    /// [`sample`](Self::sample) with the given number of refinement iterations in the
    /// decentral case (0 is [`sample_fast`](Self::sample_fast)).
    pub fn sample_with_iterations(&self, u: [f32; 2], iterations: u32) -> Sample {
        if self.selectable_sectors == 0 {
            return Sample::NONE;
        }
        let (u0, u1) = (clamp_random(u[0]), clamp_random(u[1]));
        if self.is_small != 0 {
            return self.small.sample(u0, u1);
        }
        let target = u0 * self.projected_solid_angle;
        // The sector: the number of sectors (among all but the last selectable) that start
        // at or before the target. `<=` skips sectors of zero area.
        let mut k = 0usize;
        for j in 1..MAX_POLYGON_VERTICES {
            k += (j < self.selectable_sectors as usize && self.sector_start[j] <= target) as usize;
        }
        let sector_area = self.sector_area[k];
        let local = (target - self.sector_start[k]).max(0.0).min(sector_area);
        let (point, z2) = if self.central != 0 {
            sample_sector_of_ellipse(
                local,
                u1,
                self.outer[k],
                self.sector_begin[k],
                self.outer_dots[k][0],
            )
        } else {
            let fraction = local / sector_area;
            let iterations = if (ITERATION_MARGIN..=1.0 - ITERATION_MARGIN).contains(&fraction) {
                iterations
            } else {
                0
            };
            sample_sector_between_ellipses(local, fraction, u1, &self.sector(k), iterations)
        };
        let dir = Vec3::new(point[0], point[1], libm::sqrtf(z2.max(0.0)));
        if !dir.is_finite() {
            return Sample::NONE;
        }
        Sample {
            dir,
            pdf: dir.z * self.density,
        }
    }

    /// Sector `k` with its accurate products.
    #[inline(always)]
    pub(crate) fn sector(&self, k: usize) -> Sector {
        Sector {
            s0: self.sector_begin[k],
            s1: self.sector_end[k],
            det: self.sector_det[k],
            ui: self.inner[k],
            uo: self.outer[k],
            inner_dots: self.inner_dots[k],
            outer_dots: self.outer_dots[k],
        }
    }

    /// `ω_z / Φ` for a direction inside the polygon (or on its boundary) and above the
    /// horizon, 0 otherwise. `dir` need not be normalised; a zero or non-finite `dir`
    /// gives 0.
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        if self.is_small != 0 {
            return self.small.pdf(dir);
        }
        if self.contains(dir) {
            dir.z / dir.length() * self.density
        } else {
            0.0
        }
    }

    /// Whether the ray along `dir` passes through the clipped polygon (boundary
    /// included) and lies strictly above the horizon.
    #[inline]
    pub fn contains(&self, dir: Vec3) -> bool {
        let mut inside = self.selectable_sectors > 0 && dir.z > 0.0 && dir.is_finite();
        for n in &self.edge_normals {
            // Unused slots hold zero normals, whose dot product 0 passes.
            inside &= n.dot(dir) >= 0.0;
        }
        inside
    }
}

/// The central case of Algorithm 4: a point uniformly distributed in the part of the
/// ellipse `u` within the sector that starts at `s0` (with `t0 = u · s0`), at area
/// `area` from `s0` counter-clockwise, and at relative radius² `xi1` (supplement A.7).
///
/// In the coordinates `Lᵀ p` (with `C = L Lᵀ`) the ellipse is the unit circle, the area
/// `A` is the angle `2 √|C| A`, and rotating `Lᵀ s0` by it and mapping back gives
/// `w = cos(2 √|C| A) √|C| s0 + sin(2 √|C| A) R C s0` up to a positive factor (using
/// `L⁻ᵀ R Lᵀ = |L| C⁻¹ R` and `C⁻¹ R = R C / |C|` for symmetric 2×2 `C`). The point on
/// the ellipse is `w / √(wᵀ C w)`; uniform area along the ray puts it at `√ξ1` of that.
///
/// Returns the point and `ω_z² = 1 - |p|²`, computed as `((1 - ξ1)|w|² + (u·w)²) / wᵀCw`
/// without the cancellation of `1 - |p|²` near the rim of the disk (the horizon). Here
/// `u · w = cos · √|C| t0 + sin · det(s0, u)` (as `u · R u = 0`), from the accurate `t0`.
#[inline(always)]
fn sample_sector_of_ellipse(area: f32, xi1: f32, u: Vec2, s0: Vec2, t0: f32) -> (Vec2, f32) {
    let root_determinant = libm::sqrtf(1.0 + dot2(u, u));
    let (sin, cos) = libm::sincosf(2.0 * root_determinant * area);
    let c_s0 = add2(s0, scale2(u, t0));
    let w = add2(
        scale2(s0, cos * root_determinant),
        scale2(rotate(c_s0), sin),
    );
    let uw = cos * root_determinant * t0 + sin * det2(s0, u);
    let length2 = dot2(w, w);
    let norm = (length2 + uw * uw).max(f32::MIN_POSITIVE);
    let z2 = ((1.0 - xi1) * length2 + uw * uw) / norm;
    (scale2(w, libm::sqrtf(xi1 / norm)), z2)
}

/// `w / (|w_x| + |w_y|)` up to a factor in `[2, 8)`, without a division (supplement A.7):
/// the iteration only needs the direction of `w`, but its magnitude must stay away from
/// overflow and underflow.
///
/// Bit trick: `x ^ 0x7F80_0000` flips the 8 exponent bits of `x`. For a normal `f32`
/// with biased exponent `E ∈ [1, 254]`, `x = 2^(E-127) (1 + f)`, the result has biased
/// exponent `255 - E ∈ [1, 254]`, also normal and finite, with the same significand, so
/// the product is `2^(E-127) 2^(128-E) (1 + f)² = 2 (1 + f)² ∈ [2, 8)`. It is applied only
/// when `|w_x| + |w_y|` is normal (not zero, subnormal, infinite or NaN), where that
/// argument holds; otherwise `w` is left as it is.
#[inline(always)]
fn normalize_magnitude(w: Vec2) -> Vec2 {
    let sum = w[0].abs() + w[1].abs();
    if sum.is_normal() {
        scale2(w, f32::from_bits(sum.to_bits() ^ 0x7F80_0000))
    } else {
        w
    }
}

/// `w` or `-w`, whichever points into the half-plane of the sector's bisector `h`.
#[inline(always)]
fn towards(w: Vec2, h: Vec2) -> Vec2 {
    let sign = copy_sign(1.0, dot2(w, h));
    scale2(w, sign)
}

/// A sector between two ellipses with the quantities that [`ProjectedSolidAnglePolygon`]
/// computes from the vertex positions: `det(s0, s1)` and the dot products of each
/// ellipse's `u` with the boundaries. Dot products with any `w = α s0 + β s1` follow by
/// linearity, `u · w = α (u · s0) + β (u · s1)`, without the cancellation of `u · w` for
/// large `u`.
#[derive(Clone, Copy)]
pub(crate) struct Sector {
    pub s0: Vec2,
    pub s1: Vec2,
    pub det: f32,
    pub ui: Vec2,
    pub uo: Vec2,
    pub inner_dots: [f32; 2],
    pub outer_dots: [f32; 2],
}

impl Sector {
    /// `(u_i · w, u_o · w)` for `w` in (or near) the sector.
    #[inline(always)]
    pub fn dots(&self, w: Vec2) -> (f32, f32) {
        // w = α s0 + β s1 with α = det(w, s1) / det(s0, s1), β = det(s0, w) / det(s0, s1);
        // the basis determinant is that of the rounded boundary vectors themselves.
        let basis = det2(self.s0, self.s1);
        let (alpha, beta) = (det2(w, self.s1) / basis, det2(self.s0, w) / basis);
        let i = alpha * self.inner_dots[0] + beta * self.inner_dots[1];
        let o = alpha * self.outer_dots[0] + beta * self.outer_dots[1];
        if i.is_finite() && o.is_finite() {
            (i, o)
        } else {
            (dot2(self.ui, w), dot2(self.uo, w))
        }
    }

    /// The area between the two ellipses from `s0` to `w`.
    #[inline(always)]
    pub fn area_to(&self, w: Vec2) -> f32 {
        let (det, dot) = (det2(self.s0, w), dot2(self.s0, w));
        let (i, o) = self.dots(w);
        ellipse_area(self.uo, det, dot, self.outer_dots[0], o)
            - ellipse_area(self.ui, det, dot, self.inner_dots[0], i)
    }
}

/// `1 / √(|s|² + t²)` with `t = u · s`: the factor `λ` that puts `λ s` on the ellipse.
#[inline(always)]
fn ellipse_radius(length2: f32, t: f32) -> f32 {
    1.0 / libm::sqrtf(length2 + t * t)
}

/// Algorithm 3 (`sample_sector_between_ellipses`): a point uniformly distributed in the
/// region between the inner ellipse and the outer ellipse of `sector`, at area `area`
/// from `s0` (a fraction `fraction` of the sector's area), at relative radius² `xi1`
/// between the two ellipses.
///
/// Initialisation (supplement A.4): the sector is halved by `s_h = s0 + s1`, and each half
/// is approximated by the quad whose corners lie on the two ellipses at the sector's
/// boundaries. A quad is chosen by `fraction`, and the direction `w` where the area
/// between the quad's two edges (lines `r_l · q = D_l`) reaches the wanted share is the
/// root of the homogeneous quadratic `wᵀ Q w = 0`, which Algorithm 2 picks correctly
/// (Proposition 3). Then `iterations` steps of the iteration of supplement A.3 replace
/// the quad's edges by the tangents of the ellipses at the current direction; the error
/// shrinks cubically (Proposition 6). All products `u · v` come from [`Sector::dots`].
///
/// Returns the point and `ω_z²` (see [`point_between_ellipses`]).
#[inline(always)]
fn sample_sector_between_ellipses(
    area: f32,
    fraction: f32,
    xi1: f32,
    sector: &Sector,
    iterations: u32,
) -> (Vec2, f32) {
    let Sector {
        s0,
        s1,
        ui,
        uo,
        inner_dots: ti,
        outer_dots: to,
        ..
    } = *sector;
    let sh = add2(s0, s1);
    let sh2 = dot2(sh, sh);
    let (ti_h, to_h) = (ti[0] + ti[1], to[0] + to[1]);
    let (li0, lih, li1) = (
        ellipse_radius(1.0, ti[0]),
        ellipse_radius(sh2, ti_h),
        ellipse_radius(1.0, ti[1]),
    );
    let (lo0, loh, lo1) = (
        ellipse_radius(1.0, to[0]),
        ellipse_radius(sh2, to_h),
        ellipse_radius(1.0, to[1]),
    );
    // Twice the quad areas over |det(s0, s1)| (= |det(s_h, s_k)| for both halves).
    let quad0 = lo0 * loh - li0 * lih;
    let quad1 = loh * lo1 - lih * li1;
    // Measured from s0 for the first quad (counter-clockwise, positive) and from s1 for
    // the second (clockwise, negative); the quad's own boundary s_k is the reference.
    // (The supplement's listing scales by "|(s_h, s_1)|", which is garbled in the text:
    // it must be the absolute value, as the signs of the two cases show.)
    let split = fraction * (quad0 + quad1) - quad0;
    let first = split <= 0.0;
    let (sk, lik, lok, tik, tok, quad_area) = if first {
        (s0, li0, lo0, ti[0], to[0], split + quad0)
    } else {
        (s1, li1, lo1, ti[1], to[1], split - quad1)
    };
    let quad_area = 0.5 * quad_area * sector.det.abs();
    // Quad edges: normals r_l = C_l a_l with a_l = λ_l,h s_h + λ_l,k s_k, and offsets
    // D_l = λ_l,h r_l·s_h = λ_l,h (a_l·s_h + (u_l·a_l)(u_l·s_h)).
    let (ai, ao) = (
        add2(scale2(sh, lih), scale2(sk, lik)),
        add2(scale2(sh, loh), scale2(sk, lok)),
    );
    let (uai, uao) = (lih * ti_h + lik * tik, loh * to_h + lok * tok);
    let ri = add2(ai, scale2(ui, uai));
    let ro = add2(ao, scale2(uo, uao));
    let di = lih * (dot2(ai, sh) + uai * ti_h);
    let d_o = loh * (dot2(ao, sh) + uao * to_h);
    // The area between the two edges from s_k to w is
    // ½ (λ_o,k D_o / (r_o·w) - λ_i,k D_i / (r_i·w)) det(s_k, w); setting it to the wanted
    // area and multiplying by (r_o·w)(r_i·w) gives wᵀ Q w = 0 with
    // Q = (R s_k) cᵀ - 2 A_q r_o r_iᵀ, c = λ_o,k D_o r_i - λ_i,k D_i r_o.
    let a = rotate(sk);
    let c = add2(scale2(ri, lok * d_o), scale2(ro, -lik * di));
    let twice = 2.0 * quad_area;
    let qxx = a[0] * c[0] - twice * ro[0] * ri[0];
    let qxy_plus_qyx = a[0] * c[1] + a[1] * c[0] - twice * (ro[0] * ri[1] + ro[1] * ri[0]);
    let qyy = a[1] * c[1] - twice * ro[1] * ri[1];
    let mut w = towards(solve_homogeneous_quadratic(qxx, qxy_plus_qyx, qyy), sh);
    for _ in 0..iterations {
        w = normalize_magnitude(w);
        // Residual A_δ = A - (area between the ellipses from s0 to w).
        let residual = area - sector.area_to(w);
        // T = R w (C_i w - C_o w)ᵀ - 2 A_δ (C_i w)(C_o w)ᵀ (supplement A.3).
        let (uiw, uow) = sector.dots(w);
        let (wi, wo) = (add2(w, scale2(ui, uiw)), add2(w, scale2(uo, uow)));
        let rw = rotate(w);
        let d = [wi[0] - wo[0], wi[1] - wo[1]];
        let twice = 2.0 * residual;
        let txx = rw[0] * d[0] - twice * wi[0] * wo[0];
        let txy_plus_tyx = rw[0] * d[1] + rw[1] * d[0] - twice * (wi[0] * wo[1] + wi[1] * wo[0]);
        let tyy = rw[1] * d[1] - twice * wi[1] * wo[1];
        w = towards(solve_homogeneous_quadratic(txx, txy_plus_tyx, tyy), sh);
    }
    let (uiw, uow) = sector.dots(w);
    point_between_ellipses(w, xi1, uiw, uow)
}

/// The point along the direction `w` at relative radius² `xi1` between the inner and
/// the outer ellipse (uniform in area along the ray), given `u_i · w` and `u_o · w`, and
/// its `ω_z² = 1 - |p|²`, computed as `(1 - ξ1) (u_i·w)² / wᵀC_iw + ξ1 (u_o·w)² / wᵀC_ow`
/// without the cancellation of `1 - |p|²` near the rim of the disk.
#[inline(always)]
pub(crate) fn point_between_ellipses(w: Vec2, xi1: f32, uiw: f32, uow: f32) -> (Vec2, f32) {
    let length2 = dot2(w, w);
    let (qi, qo) = (length2 + uiw * uiw, length2 + uow * uow);
    let radius2 = (1.0 - xi1) / qi + xi1 / qo;
    let z2 = (1.0 - xi1) * (uiw * uiw / qi) + xi1 * (uow * uow / qo);
    let scale = libm::sqrtf(radius2);
    if scale.is_finite() && z2.is_finite() {
        (scale2(w, scale), z2)
    } else {
        ([0.0, 0.0], 1.0)
    }
}

/// Sorts the first `count` entries of the bitonic sequence `items` (temporary: a
/// general odd-even transposition network until the optimal bitonic networks land).
fn sort_bitonic(items: &mut [u8; 8], count: usize, less: impl Fn(&u8, &u8) -> bool) {
    for round in 0..count {
        let mut i = round % 2;
        while i + 1 < count {
            let (a, b) = (items[i], items[i + 1]);
            let swap = less(&b, &a);
            items[i] = if swap { b } else { a };
            items[i + 1] = if swap { a } else { b };
            i += 2;
        }
    }
}

#[cfg(test)]
#[path = "projected_tests.rs"]
mod tests;
