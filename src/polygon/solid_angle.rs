//! Solid angle sampling of convex polygons (Peters 2021, supplement C, Algorithm 5).
//!
//! A polygon is split into a fan of triangles around its first vertex. A fan triangle
//! is chosen in proportion to its solid angle, and Algorithm 5 samples it: the first
//! random number picks a sub-triangle of the wanted solid angle by rotating a new edge
//! around the fan apex, the second one picks a point along that edge, uniformly in
//! solid angle. The density is `1 / Ω` everywhere inside the polygon.
//!
//! Precision. van Oosterom and Strackee's formula gives each fan triangle's solid angle
//! as `Ω = 2 atan2(G0, G1 + G2)`, and `G0 = |det(v0, v1, v2)|` of the unit vertex
//! directions loses all precision for tiny triangles when it is expanded naively. The
//! supplement reflects the vertices with one Householder reflection that maps the apex
//! onto the x axis, which leaves a 2×2 determinant. Here the reflection is applied to
//! the edge vectors `p_i - p_apex` of the *unnormalised* input positions, which are
//! exact up to one rounding even when the vertices are 1e5 units away and the polygon
//! is 1e-5 across (see [`SolidAnglePolygon::new`]). The per-sample step avoids the
//! cancellation in `1 - s'²` of Algorithm 5 by the identity
//! `(1 - s²) / (1 - s'²) = ξ1 (1 + s) / (1 + s')`.
//!
//! Hard cases, each a named test below: solid angles from 1e-10 sr to nearly 2π, slivers,
//! a shading point in the polygon's plane, vertices 1e5 away, `u = 0` and `u = 1 - ulp`,
//! both windings, duplicate vertices (as clipping can produce), 3 to 8 vertices.

use crate::Sample;
use crate::math::{
    LANES, atan2_upper_half_plane, determinant_is_exactly_zero,
    difference_of_products_unless_cancelling, difference_of_products_unless_half_cancels,
    dot_precise, store4,
};
use crate::sample::{clamp_inverted, clamp_random, select_piece};
use crate::{MAX_POLYGON_VERTICES, Vec3};
use glam::{BVec4A, Vec3A, Vec4};

/// The most fan triangles a polygon has.
pub(crate) const MAX_TRIANGLES: usize = MAX_POLYGON_VERTICES - 2;

/// A convex polygon of 3 to `N` vertices prepared for solid angle sampling: everything
/// Algorithm 5 computes once per polygon, for its `T = N - 2` fan triangles.
///
/// One algorithm in three sizes (issue 15, 3): [`SolidAnglePolygon`] (up to
/// [`MAX_POLYGON_VERTICES`], 532 bytes), [`SolidAngleQuad`] (triangles and quads, 244
/// bytes) and [`SolidAngleTriangle`] (triangles, 172 bytes). A scene of triangle or quad
/// lights does not pay for the storage of eight vertices: the unused slots that
/// preparation writes, the edges that `pdf` tests and the fan triangles that sampling
/// looks through. The three give the same samples and densities, bit for bit, for the
/// polygons they all accept (tested).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidAngleFan<const N: usize, const T: usize> {
    /// Unit directions towards the vertices. `vertices[0]` is the fan apex, which
    /// Algorithm 5 calls `v1`; fan triangle `k` is `(vertices[k + 1], apex,
    /// vertices[k + 2])`, Algorithm 5's `(v0, v1, v2)`.
    pub(crate) vertices: [Vec3; N],
    /// Edge plane normals `± p_i × p_(i+1)` (not normalised), oriented so that directions
    /// inside the polygon have non-negative dot products with all of them.
    edge_normals: [Vec3; N],
    /// For the narrowest polygons (`checks_samples == 2`), the rounding errors of `edge_normals`: the
    /// exact plane of edge `i` is `edge_normals[i] + edge_residuals[i]` to about ε², so
    /// that the inside test carries no rotation of ε per edge (which moved the boundary
    /// of polygons of 1e-9 sr by a few percent of an ulp, systematically: `∫ pdf dω`
    /// was 1.00043 at 8e-10 sr). Zero otherwise.
    edge_residuals: [Vec3; N],
    /// `G0 = |det(v0, v1, v2)|` per fan triangle.
    pub(crate) g0: [f32; T],
    /// `G1 + G2 = 1 + v0·v1 + v0·v2 + v1·v2` per fan triangle (see [`denominator`]).
    pub(crate) g1_plus_g2: [f32; T],
    /// `G2 = 1 + v0·v1 = |v0 + v1|² / 2` per fan triangle.
    g2: [f32; T],
    /// `v0 + v2` per fan triangle, accurate even when `v0 ≈ -v2`.
    outer_sum: [Vec3; T],
    /// `m = v0·(v0 + v2)` per fan triangle, of the stored `vertices[k + 1]` and
    /// `outer_sum[k]`, rounded as `Vec3::dot` rounds it, `(x x' + y y') + z z'`: what the
    /// sample's step depends on of the fan triangle alone (see
    /// [`direction_in_triangle`](Self::direction_in_triangle)), computed once here instead
    /// of in every sample.
    outer_along: [f32; T],
    /// `|v0 + v2|² - m²` per fan triangle, with `|v0 + v2|²` of the stored `outer_sum[k]`
    /// rounded as `Vec3::length_squared` rounds it.
    outer_across2: [f32; T],
    /// Solid angle of the fan triangles before triangle `k`; `+∞` from the first triangle
    /// that cannot be selected on, which
    /// [`select_piece`](crate::sample::select_piece) then skips.
    pub(crate) start: [f32; T],
    /// Total solid angle Ω in steradians (0 when empty).
    pub(crate) solid_angle: f32,
    /// `1 / Ω` (0 when empty).
    density: f32,
    /// +1 when the polygon winds counter-clockwise seen from the shading point, -1
    /// otherwise: the sign that orients the edge and diagonal normals inwards.
    orientation: f32,
    /// Number of vertices (0 when empty).
    pub(crate) vertex_count: u32,
    /// Fan triangles that can be selected: up to the last one with non-zero solid angle.
    pub(crate) selectable_triangles: u32,
    /// The careful fallbacks that preparation took, as bits: 1, the compensated pair sums
    /// of a fan triangle; 2, the short-edge rule of the containment test; 0 for the fast
    /// path throughout.
    careful_paths: u32,
    /// 1 when the polygon is so narrow that the slack of `pdf` may be below the rounding
    /// of a sampled direction (an edge longer than 5 Ω), so that `sample` tests its
    /// direction; 2 when it is narrower still (an edge longer than 50 Ω), so that the
    /// inside test also takes the exact edge planes and a compensated dot product; 0
    /// otherwise.
    checks_samples: u32,
}

/// A convex polygon of 3 to [`MAX_POLYGON_VERTICES`] vertices prepared for solid angle
/// sampling (Peters 2021, supplement C, Algorithm 5).
pub type SolidAnglePolygon = SolidAngleFan<MAX_POLYGON_VERTICES, MAX_TRIANGLES>;

/// A triangle or a quad prepared for solid angle sampling: [`SolidAnglePolygon`] in the
/// storage of four vertices.
pub type SolidAngleQuad = SolidAngleFan<4, 2>;

/// A triangle prepared for solid angle sampling: [`SolidAnglePolygon`] in the storage of
/// three vertices.
pub type SolidAngleTriangle = SolidAngleFan<3, 1>;

// The sizes that the documentation states.
const _: () = {
    assert!(core::mem::size_of::<SolidAnglePolygon>() == 532);
    assert!(core::mem::size_of::<SolidAngleQuad>() == 244);
    assert!(core::mem::size_of::<SolidAngleTriangle>() == 172);
};

/// How far outside an edge (radians, approximately) `pdf` still finds a direction inside,
/// at the most: 16 ulps of a unit vector, above the rounding of a sampled direction on an
/// edge (a few ulps; the statistical tests assert below 5e-7 rad).
const EDGE_ROUNDING: f32 = 16.0 * f32::EPSILON;

/// The slack of `pdf` as a fraction of the polygon's width `Ω / P` (solid angle over
/// perimeter), where that is below [`EDGE_ROUNDING`]: a band of that width around the
/// boundary holds at most this fraction of the polygon, so `∫ pdf dω` stays within it of
/// 1 (issue 16, 1), and `pdf` is 0 farther outside than 4e-5 of the angular radius.
const SLACK_PER_WIDTH: f32 = 2e-5;

/// `sample` tests its direction against `pdf` (and pulls a direction that rounding put
/// outside back in) when some edge is longer than `Ω / SAMPLE_CHECK_WIDTH`: the
/// polygon's width `Ω / P` may then be below `SAMPLE_CHECK_WIDTH / n` (as `P <= n ℓ_max`),
/// and the slack `2e-5 Ω / P` below 5e-7 rad (`n <= 8`). Wider polygons have a slack of
/// at least 5e-7 rad, above the rounding of their samples (a few ulps: the statistical
/// tests assert below 5e-7 rad, and `every_sample_has_its_pdf_at_any_size` checks the
/// edges of `u`), and skip the test.
const SAMPLE_CHECK_WIDTH: f32 = 0.2;

/// The inside test takes the exact edge planes and a compensated dot product
/// (`checks_samples == 2`) when some edge is longer than `Ω / PRECISE_PLANE_WIDTH`: the
/// width may then be below 2.5e-3 rad, where the plain test's systematic shift of up to
/// an ulp per edge (6e-8 rad) would be 2.4e-5 of the polygon and more (`∫ pdf dω`
/// 1.00043 at 8e-10 sr).
const PRECISE_PLANE_WIDTH: f32 = 0.02;

/// [`SolidAnglePolygon::careful_paths`]: a fan triangle had a pair of vertices more than
/// 90° apart, whose sum the compensated form computed.
///
/// cbindgen:ignore
pub const CAREFUL_PAIR_SUMS: u32 = 1;
/// [`SolidAnglePolygon::careful_paths`]: an edge was short enough for the short-edge rule
/// of the containment test to run.
///
/// cbindgen:ignore
pub const CAREFUL_SHORT_EDGES: u32 = 2;

impl<const N: usize, const T: usize> Default for SolidAngleFan<N, T> {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// The Householder reflection `H = I - 2 h hᵀ` that maps the unit vector `apex` onto
/// `σ e0` (supplement C): `σ = -1` if `apex.x > 0`, else `1`, and
/// `h = (apex - σ e0) / sqrt(2 (|apex.x| + 1))`. Choosing `σ` against the sign of
/// `apex.x` avoids cancellation in `apex.x - σ`.
#[derive(Clone, Copy)]
struct Householder {
    h: Vec3,
    sigma: f32,
}

impl Householder {
    fn new(apex: Vec3) -> Householder {
        let sigma = if apex.x > 0.0 { -1.0 } else { 1.0 };
        let scale = 1.0 / crate::math::sqrtf(2.0 * (apex.x.abs() + 1.0));
        let h = Vec3::new(apex.x - sigma, apex.y, apex.z) * scale;
        Householder { h, sigma }
    }

    /// The y and z components of `H d`; the x component is not needed.
    #[inline(always)]
    fn reflect_yz(&self, d: Vec3) -> [f32; 2] {
        let twice_projection = 2.0 * self.h.dot(d);
        [
            d.y - self.h.y * twice_projection,
            d.z - self.h.z * twice_projection,
        ]
    }

    /// `det(b - a, apex, c - a) / |apex|`-style determinant from reflected edge vectors:
    /// for `x = (H(b - a))_yz` and `y = (H(c - a))_yz` with `a` parallel to the apex,
    /// `det(b, a, c) = |a| σ (x_y y_z - x_z y_y)` (the reflection has determinant -1 and
    /// maps the apex onto `σ e0`, so one column of the reflected matrix is `σ e0` and
    /// expanding along it leaves the 2×2 determinant).
    #[inline(always)]
    fn determinant(&self, x: [f32; 2], y: [f32; 2]) -> f32 {
        self.sigma * difference_of_products_unless_cancelling(x[0], y[1], x[1], y[0])
    }
}

/// `p/|p| + q/|q|` to full relative precision, also when `p` and `q` point in nearly
/// opposite directions and the naive sum of two rounded unit vectors would carry an
/// absolute error of an ulp of 1:
/// `p/|p| + q/|q| = (p + q)/|q| + p (|q| - |p|) / (|p| |q|)`, with
/// `|q| - |p| = (q - p)·(q + p) / (|p| + |q|)`. `p + q` is exact when the vectors nearly
/// cancel (Sterbenz), and the dot product is compensated.
#[inline(always)]
fn unit_vector_sum(p: Vec3, q: Vec3, length_p: f32, length_q: f32) -> Vec3 {
    let sum = p + q;
    let length_difference = dot_precise(q - p, sum) / (length_p + length_q);
    sum / length_q + p * (length_difference / (length_p * length_q))
}

/// `G1 + G2 = 1 + v0·v1 + v0·v2 + v1·v2`, the denominator of van Oosterom and Strackee's
/// formula, from the pair sums `s_ij = v_i + v_j`. It equals `|s_ij|²/2 + v_k·s_ij` for
/// each pair; the pair with the shortest sum (the most nearly antipodal vertices) gives
/// a form without cancellation. Near-flat triangles of almost π steradians, where the
/// naive sum of dot products loses everything, have exactly one such pair.
#[inline(always)]
fn denominator(v0: Vec3, v1: Vec3, v2: Vec3, sums: [Vec3; 3], length_squares: [f32; 3]) -> f32 {
    let [s01, s02, s12] = sums;
    let [l01, l02, l12] = length_squares;
    if l02 <= l01 && l02 <= l12 {
        0.5 * l02 + v1.dot(s02)
    } else if l12 <= l01 {
        0.5 * l12 + v0.dot(s12)
    } else {
        0.5 * l01 + v2.dot(s01)
    }
}

/// Slots of the structure-of-arrays working set (`VertexGroups`, `VertexLanes`): up to 8
/// vertices, the copy of the first that closes the polygon, and what the last lanes of
/// the fan read (up to slot `LANES + 2 + 3 = 9`), in whole lanes.
const SLOTS: usize = 3 * LANES;

/// Bits `first..first + 4` of a lane mask, for the lanes below `end`: lane `j` stands
/// for slot `first + j`.
#[inline(always)]
fn lane_bits(mask: BVec4A, first: usize, end: usize) -> u32 {
    let in_range = if end > first {
        (1u32 << (end - first).min(LANES)) - 1
    } else {
        0
    };
    (mask.bitmask() & in_range) << first
}

/// The positions and lengths of [`VertexGroups`] in memory, slot by slot, for the
/// careful paths, which index slots at run time: slot `i` holds vertex `i`, and slot
/// `count` vertex 0 again.
struct VertexLanes {
    /// The rescaled positions `p_i`.
    position: [[f32; SLOTS]; 3],
    /// `|p_i|`.
    length: [f32; SLOTS],
}

/// The input positions of slots `first..first + 4` as x, y and z lanes; slots from
/// `count` on read vertex 0 again.
#[inline(always)]
fn gather(vertices: &[Vec3], count: usize, first: usize) -> [Vec4; 3] {
    let vertex = |j: usize| {
        let slot = first + j;
        vertices[if slot < count { slot } else { 0 }]
    };
    let [a, b, c, d] = [vertex(0), vertex(1), vertex(2), vertex(3)];
    [
        Vec4::new(a.x, b.x, c.x, d.x),
        Vec4::new(a.y, b.y, c.y, d.y),
        Vec4::new(a.z, b.z, c.z, d.z),
    ]
}

/// [`rescale_factor_of_lanes`](super::rescale_factor_of_lanes) in every lane, computed
/// in the lanes from `largest_magnitude4`'s values (combined over the groups): the same
/// power of two bit for bit, and `None` in the same cases (tested:
/// `rescale_factor_in_lanes_is_the_scalar_one`). The factor heads the preparation's
/// chain of dependent operations (it scales the positions whose lengths, units,
/// reflection and determinant follow), and the scalar form took it out of the lanes and
/// back (a reduction to one lane, two moves between the register files, five integer
/// operations and a broadcast, about 25 cycles); here the maximum reaches every lane by
/// two exchanges, and the factor's bits are integer operations in the lanes. For a
/// finite largest magnitude of biased exponent `e <= 254`, `rescale_factor`'s
/// `max(254 - e, 1) << 23` is `0x7F00_0000 - (bits & 0x7F80_0000)` (no borrow: the
/// exponent field is at most `254 << 23`) raised to `1 << 23` where it is 0; the raise
/// is a maximum of floats with `f32::MIN_POSITIVE` (bits `1 << 23`), as non-negative
/// floats order as their bits.
#[inline(always)]
fn rescale_factor_in_lanes(largest: Vec4, finite: BVec4A) -> Option<Vec4> {
    if !finite.all() {
        return None;
    }
    // The maximum of the four lanes in every lane (a maximum of finite values is exact,
    // in any order).
    let pairs = largest.max(Vec4::new(largest.z, largest.w, largest.x, largest.y));
    let all = pairs.max(Vec4::new(pairs.y, pairs.x, pairs.w, pairs.z));
    // All coordinates zero (the bits, not `== 0.0`, which counts a subnormal as zero
    // under denormals-are-zero).
    if all.x.to_bits() == 0 {
        return None;
    }
    let power = |m: f32| f32::from_bits(0x7F00_0000 - (m.to_bits() & 0x7F80_0000));
    Some(Vec4::from_array(all.to_array().map(power)).max(Vec4::splat(f32::MIN_POSITIVE)))
}

/// The input lanes of [`gather`] for the groups of slots `0..=count` (the last closes
/// the polygon; groups 1 and 2 are zero where not needed, and nothing reads them then),
/// and `rescale_factor` of the polygon computed from them, in every lane
/// (`None` for a non-finite coordinate or all coordinates zero): the same factor bit
/// for bit, in lanes (the repeated vertex 0 changes no maximum).
#[inline(always)]
fn gather_and_rescale(vertices: &[Vec3], count: usize) -> ([[Vec4; 3]; 3], Option<Vec4>) {
    // Slots `0..count` need the groups up to slot `count - 1`: `count >= 3`, so group 1
    // is needed from `count = 5` on and group 2 never (`count <= 8`). Slot `count`, which
    // closes the polygon, holds vertex 0 again, which `VertexGroups::new` takes from
    // slot 0 where it falls in a group of its own (quads: the second group's vertex
    // work, a square root and three divisions, for the one slot 4; 982 -> see the commit).
    let zero = [Vec4::ZERO; 3];
    let raw0 = gather(vertices, count, 0);
    let raw1 = if count > LANES {
        gather(vertices, count, LANES)
    } else {
        zero
    };
    let raw2 = if count > 2 * LANES {
        gather(vertices, count, 2 * LANES)
    } else {
        zero
    };
    // Over the groups that hold vertices (the zero groups would change nothing).
    let (mut largest, mut finite) = super::largest_magnitude4(raw0);
    if count > LANES {
        let (m1, f1) = super::largest_magnitude4(raw1);
        (largest, finite) = (largest.max(m1), finite & f1);
    }
    if count > 2 * LANES {
        let (m2, f2) = super::largest_magnitude4(raw2);
        (largest, finite) = (largest.max(m2), finite & f2);
    }
    let factor = rescale_factor_in_lanes(largest, finite);
    ([raw0, raw1, raw2], factor)
}

/// One group of four slots of a polygon's per-vertex values ([`VertexGroups`]), in
/// registers: slot `i` holds vertex `i`, and every slot from `count` on holds vertex 0
/// again, so that slot `count` closes the polygon for the edges, and lanes past the
/// polygon compute, from a valid vertex, finite values that the masks then leave out.
/// Each value is rounded as the scalar form named beside it rounds it: `length_squared`
/// as `Vec3::length_squared`, `unit` divided by the length (correctly rounded per
/// component, not multiplied by a reciprocal), `reflected` as `Householder::reflect_yz`
/// of `p_i - p_0`, and `extent` is `|p_i - p_0|∞`, the scale of the fan determinants'
/// rounding noise.
#[derive(Clone, Copy)]
struct SlotGroup {
    position: [Vec4; 3],
    length_squared: Vec4,
    length: Vec4,
    unit: [Vec4; 3],
    reflected: [Vec4; 2],
    extent: Vec4,
}

impl SlotGroup {
    /// The group of slots that no lane of the polygon reads (only lanes that the masks
    /// leave out do): all 0.
    const ZERO: SlotGroup = SlotGroup {
        position: [Vec4::ZERO; 3],
        length_squared: Vec4::ZERO,
        length: Vec4::ZERO,
        unit: [Vec4::ZERO; 3],
        reflected: [Vec4::ZERO; 2],
        extent: Vec4::ZERO,
    };

    /// Positions (the input `raw`, the x, y and z lanes of [`gather`], times the power of
    /// two `factor` of [`rescale`]), lengths and unit directions of four slots; the
    /// reflected edges are left 0 (see [`reflect`](Self::reflect)). The second value is
    /// `false` when one has length 0 (a vertex at the shading point, or one whose squared
    /// length underflows).
    #[inline(always)]
    fn vertices(raw: [Vec4; 3], factor: Vec4) -> (SlotGroup, bool) {
        let [x, y, z] = raw;
        let (x, y, z) = (x * factor, y * factor, z * factor);
        let length_squared = (x * x + y * y) + z * z;
        let length = crate::math::sqrt4(length_squared);
        let nonzero = length.cmpgt(Vec4::ZERO).all();
        let group = SlotGroup {
            position: [x, y, z],
            length_squared,
            length,
            unit: [x / length, y / length, z / length],
            reflected: [Vec4::ZERO; 2],
            extent: Vec4::ZERO,
        };
        (group, nonzero)
    }

    /// The group whose four slots all hold slot 0 of `self` (each lane of each value
    /// `self`'s lane 0): for a group that lies wholly past the polygon, whose slots hold
    /// vertex 0 again. Its values are those that [`vertices`](Self::vertices) and
    /// [`reflect`](Self::reflect) would compute from the copies of vertex 0, bit for bit
    /// (the same operations on the same inputs; the edge vector `p_0 - p_0` is `+0`, and
    /// so are its reflection `0 - h·0` and extent), without the square root and the
    /// divisions.
    #[inline(always)]
    fn first_in_every_slot(&self) -> SlotGroup {
        let splat = |v: Vec4| Vec4::splat(v.x);
        SlotGroup {
            position: self.position.map(splat),
            length_squared: splat(self.length_squared),
            length: splat(self.length),
            unit: self.unit.map(splat),
            reflected: self.reflected.map(splat),
            extent: splat(self.extent),
        }
    }

    /// `reflected` and `extent`: the edge vectors `p_i - p_0` (exact differences of the
    /// inputs up to one rounding each, so that tiny and distant polygons keep their
    /// relative precision) through the reflection, for the apex at `origin`.
    #[inline(always)]
    fn reflect(&mut self, reflection: &Householder, origin: [Vec4; 3]) {
        let [x0, y0, z0] = origin;
        let [hx, hy, hz] = splat3(reflection.h);
        let [x, y, z] = self.position;
        let (ex, ey, ez) = (x - x0, y - y0, z - z0);
        let twice_projection = Vec4::splat(2.0) * ((hx * ex + hy * ey) + hz * ez);
        self.reflected = [ey - hy * twice_projection, ez - hz * twice_projection];
        self.extent = ex.abs().max(ey.abs().max(ez.abs()));
    }
}

/// The slots of three groups, in order.
#[inline(always)]
fn join(groups: [Vec4; 3]) -> [f32; SLOTS] {
    // Every slot is written (the compiler drops the zeros).
    let mut slots = [0.0; SLOTS];
    store4(groups[0], &mut slots, 0);
    store4(groups[1], &mut slots, LANES);
    store4(groups[2], &mut slots, 2 * LANES);
    slots
}

/// The working set of the polygon in registers (or in the compiler's aligned spill
/// slots), four slots at a time: slot `i` in lane `i % 4` of group `i / 4`. The fan and
/// the edges read slots shifted by one and two (vertices `k + 1`, `k + 2`), which
/// [`slots`](Self::slots) takes from two neighbouring groups by shuffles: the working set
/// in memory, stored as whole groups and loaded back at those shifts, had every shifted
/// load span two stores, which store-to-load forwarding cannot serve (the load waits
/// until the stores reach the cache), and cost the stores of all 36 lanes (576 bytes).
/// The rare careful paths, which index slots at run time, take the memory form
/// [`VertexLanes`] built on the spot ([`lanes`](Self::lanes)).
#[derive(Clone, Copy)]
struct VertexGroups {
    groups: [SlotGroup; 3],
}

impl VertexGroups {
    /// The working set of the polygon: the groups of slots `0..=count` (the last closes
    /// the polygon) from the input lanes of [`gather`], the groups above 0 (only lanes
    /// that the masks leave out read them), scaled by `factor` (the rescale factor in
    /// every lane), with the apex's reflection; `None` when a vertex has length 0.
    #[inline(always)]
    fn new(raw: [[Vec4; 3]; 3], factor: Vec4, count: usize) -> Option<(VertexGroups, Householder)> {
        // Slots `0..count` need the groups up to slot `count - 1`: `count >= 3`, so group
        // 1 is computed from `count = 5` on and group 2 never (`count <= 8`); the group
        // of slot `count`, where that is a group of its own, gets slot 0's values (below).
        let (mut g0, ok0) = SlotGroup::vertices(raw[0], factor);
        let (mut g1, ok1) = if count > LANES {
            SlotGroup::vertices(raw[1], factor)
        } else {
            (SlotGroup::ZERO, true)
        };
        let (mut g2, ok2) = if count > 2 * LANES {
            SlotGroup::vertices(raw[2], factor)
        } else {
            (SlotGroup::ZERO, true)
        };
        if !(ok0 && ok1 && ok2) {
            return None;
        }
        let apex = Vec3::new(g0.unit[0].x, g0.unit[1].x, g0.unit[2].x);
        let reflection = Householder::new(apex);
        let origin = splat3(Vec3::new(
            g0.position[0].x,
            g0.position[1].x,
            g0.position[2].x,
        ));
        g0.reflect(&reflection, origin);
        // A group past the polygon that holds slot `count` (which closes the last edge):
        // vertex 0 in every slot, slot 0's values. Other groups past the polygon stay
        // zero (only lanes that the masks leave out read them; the copies cost shuffles:
        // hexagons 1279 -> 1289 instructions with group 2 copied, callgrind).
        if count > LANES {
            g1.reflect(&reflection, origin);
        } else if count == LANES {
            g1 = g0.first_in_every_slot();
        }
        if count > 2 * LANES {
            g2.reflect(&reflection, origin);
        } else if count == 2 * LANES {
            g2 = g0.first_in_every_slot();
        }
        Some((
            VertexGroups {
                groups: [g0, g1, g2],
            },
            reflection,
        ))
    }

    /// The unit direction towards the apex, vertex 0.
    #[inline(always)]
    fn apex(&self) -> Vec3 {
        let [x, y, z] = self.groups[0].unit;
        Vec3::new(x.x, y.x, z.x)
    }

    /// The lanes of slots `start..start + 4` of the value that `field` picks from a
    /// group (`start` is a constant where this is inlined: the group and the shuffle are
    /// chosen at compile time).
    #[inline(always)]
    fn slots(&self, field: impl Fn(&SlotGroup) -> Vec4, start: usize, count: usize) -> Vec4 {
        let group = start / LANES;
        let low = field(&self.groups[group]);
        if start % LANES == 0 {
            return low;
        }
        // For triangles and quads (`count <= 4`, group 0): every slot of group 1 that a
        // used lane reads holds vertex 0 again, slot 0's value (the others are left out
        // by the masks), so the shuffle takes it from `low` itself: a rotation of one
        // register, where the zero group 1 of a triangle took a zeroing and two shuffles
        // (its edges: 675 -> 667 instructions per prepare + 1, quads 866 -> 862,
        // callgrind; the same for group 1 of hexagons and heptagons, which took slot 0
        // from group 0, cost them 3). And where this group holds slot `count` (the last
        // one that a used lane reads: the edges read up to slot `count`, the fan up to
        // `count - 1`), no used lane reads the next group at all: the same rotation fills
        // the unused lanes with finite values of this group (the edges of group 1 of
        // pentagons to heptagons, whose next group is zero: hexagons 1120.7 -> 1112.7
        // instructions per prepare + 1, heptagons 1387.8 -> 1378.8, callgrind; tested:
        // `shifted_slots_are_the_working_set_in_memory`).
        if (group == 0 && count <= LANES) || count < (group + 1) * LANES {
            return match start % LANES {
                1 => Vec4::new(low.y, low.z, low.w, low.x),
                2 => Vec4::new(low.z, low.w, low.x, low.x),
                _ => Vec4::new(low.w, low.x, low.x, low.x),
            };
        }
        let high = if group + 1 < self.groups.len() {
            field(&self.groups[group + 1])
        } else {
            Vec4::ZERO
        };
        // Lanes `start % 4..4` of the lower group, then the first lanes of the next.
        match start % LANES {
            1 => Vec4::new(low.y, low.z, low.w, high.x),
            2 => Vec4::new(low.z, low.w, high.x, high.y),
            _ => Vec4::new(low.w, high.x, high.y, high.z),
        }
    }

    /// The value that `field` picks from a group, of slot `i` alone (`i` is a constant
    /// where this is inlined: one lane of a register).
    #[inline(always)]
    fn slot(&self, field: impl Fn(&SlotGroup) -> Vec4, i: usize) -> f32 {
        field(&self.groups[i / LANES]).to_array()[i % LANES]
    }

    /// [`slots`](Self::slots) of the three coordinates of a vector value.
    #[inline(always)]
    fn slots3(
        &self,
        field: impl Fn(&SlotGroup) -> [Vec4; 3],
        start: usize,
        count: usize,
    ) -> [Vec4; 3] {
        [
            self.slots(|g| field(g)[0], start, count),
            self.slots(|g| field(g)[1], start, count),
            self.slots(|g| field(g)[2], start, count),
        ]
    }

    /// Writes the unit directions of slots `0..count` into `vertices`, and nothing else:
    /// the caller writes the slots from `count` on once (writing the group's other slots
    /// too, which the caller then overwrote, cost a hexagon 25 instructions per prepare
    /// together with the one comparison of `total`, callgrind).
    #[inline(always)]
    fn write_units<const N: usize>(&self, vertices: &mut [Vec3; N], count: usize) {
        for (g, group) in self.groups.iter().enumerate() {
            let first = g * LANES;
            // (`first` and `N` are constants here: the tests fold.)
            if first >= N || first >= count {
                break;
            }
            let [x, y, z] = group.unit;
            let (x, y, z) = (x.to_array(), y.to_array(), z.to_array());
            for j in 0..LANES.min(N - first).min(count - first) {
                vertices[first + j] = Vec3::new(x[j], y[j], z[j]);
            }
        }
    }

    /// The working set in memory, for the careful paths that index it at run time
    /// (inline: a call with a pointer to the groups kept them in memory on every path).
    #[inline(always)]
    fn lanes(&self) -> VertexLanes {
        let [g0, g1, g2] = &self.groups;
        // Written out, not by `array::map` (which the generic body may leave out of line).
        VertexLanes {
            position: [
                join([g0.position[0], g1.position[0], g2.position[0]]),
                join([g0.position[1], g1.position[1], g2.position[1]]),
                join([g0.position[2], g1.position[2], g2.position[2]]),
            ],
            length: join([g0.length, g1.length, g2.length]),
        }
    }
}

impl VertexLanes {
    /// The (rescaled) position of vertex `i`; slot `count` is vertex 0 again.
    #[inline(always)]
    fn position(&self, i: usize) -> Vec3 {
        Vec3::new(
            self.position[0][i],
            self.position[1][i],
            self.position[2][i],
        )
    }
}

/// The three coordinates of `v`, each in all four lanes.
#[inline(always)]
fn splat3(v: Vec3) -> [Vec4; 3] {
    [Vec4::splat(v.x), Vec4::splat(v.y), Vec4::splat(v.z)]
}

/// van Oosterom and Strackee's terms of the fan triangles, four triangles at a time,
/// rounded as the scalar forms beside them; triangle `k` is `(v_(k+1), apex, v_(k+2))`.
/// `G1 + G2`, `G2` and `v0 + v2` go straight into the prepared polygon; the signed
/// determinants and the flags of the triangles that need a careful form stay here.
#[derive(Default)]
struct FanLanes {
    /// `σ det(v0, v1, v2)`: the determinant with its sign up to the reflection's `σ`
    /// (as `Householder::determinant` without its factor `σ`, but by
    /// [`difference_of_products_unless_half_cancels`], over the product of the two
    /// vertices' lengths). `σ = ±1` is the same for every fan triangle, so the sum of
    /// these values is `σ` times the sum of the determinants exactly (rounding is
    /// symmetric under negation, up to the sign of a zero sum), and the orientation
    /// applies `σ` once to the sum; `G0`, the magnitude, does not depend on it (`|σ x| =
    /// |x|`, and `(σ a) / b = σ (a / b)` exactly). The multiplication by `σ` stood on the
    /// chain of dependent operations from the vertices to the solid angle, on which the
    /// sample's chain waits in the prepare + 1 sample use (one multiplication, about 3
    /// cycles; see the commit).
    signed_g0: [f32; 2 * LANES],
    /// Bit `k`: triangle `k`'s determinant is within the rounding noise of zero, so the
    /// exact test decides whether it is zero.
    maybe_flat: u32,
    /// Bit `k`: triangle `k` has two vertices more than 90° apart (`|v_i + v_j|² < 2`),
    /// whose sum the compensated form must compute.
    wide_pairs: u32,
}

/// Algorithm 5's solid angle `2 atan2(G0, G1 + G2)` per fan triangle, where
/// [`FanLanes::compute`] stores those below [`angles_in_lanes`] four at a time (see
/// there) and `prepare_or_fail` the others. An array of its own, not a field of
/// [`FanLanes`], whose determinants the careful paths index at run time: a triangle's or
/// a quad's solid angles, read and written at constant indices only, then live in
/// registers, where as a field they were zeroed in memory with the rest (two 16-byte
/// stores per prepare: quads 2 instructions fewer per prepare + 1, callgrind).
type FanAngles = [f32; 2 * LANES];

/// The fan triangles `0..angles_in_lanes(triangles)` get their solid angles in lanes,
/// from `G0` and `G1 + G2` still in registers ([`FanLanes::compute`]): one
/// [`atan2_upper_half_plane4_small_first`](crate::math::atan2_upper_half_plane4_small_first)
/// (the scalar form's bits in each lane) per group of up to four in place of a scalar
/// `atanf` per triangle (hexagons 1217.3 -> 1159.0 instructions per prepare + 1 with
/// `atan2_upper_half_plane4`, 1120.0 with the branch for small ratios, callgrind). A
/// triangle's one fan triangle and a heptagon's fifth, which `compute_triangle` and
/// `compute_one` prepare in scalar arithmetic, keep the scalar call, and so do a quad's
/// two: since `atan2_upper_half_plane` inlines the small range of `atanf`, two scalar
/// calls take fewer instructions than the lanes (828.3 against 829.3 per prepare + 1,
/// before `atanf` was inline over its whole range: 821.3 since) and less time (the
/// lanes' division and branch lengthen the chain: 106 against 110 ns, C benchmark).
#[inline(always)]
const fn angles_in_lanes(triangles: usize) -> usize {
    if triangles <= 2 {
        0
    } else if triangles == LANES + 1 {
        LANES
    } else {
        triangles
    }
}

impl FanLanes {
    /// The signed determinants `det(v0, v1, v2)` of the four fan triangles from
    /// triangle `first` on (of `triangles`), stored into `signed_g0` and returned, with
    /// their flat flags.
    #[inline(always)]
    fn determinants(&mut self, lanes: &VertexGroups, first: usize, triangles: usize) -> Vec4 {
        let (b, c) = (first + 1, first + 2);
        let count = triangles + 2;
        let rb = [
            lanes.slots(|g| g.reflected[0], b, count),
            lanes.slots(|g| g.reflected[1], b, count),
        ];
        let rc = [
            lanes.slots(|g| g.reflected[0], c, count),
            lanes.slots(|g| g.reflected[1], c, count),
        ];
        // G0 = det(v0, v1, v2) = det(p_b, p_a, p_c) / (|p_a| |p_b| |p_c|), here times σ.
        // The lanes of triangles that exist: a constant where this is inlined (`first` and
        // `triangles` are), which the mask test of the products folds; built as a lane
        // comparison of `first + j` with `triangles`, the comparison and its negation
        // stayed at run time (4 instructions per group, callgrind).
        let needed = BVec4A::new(
            first < triangles,
            first + 1 < triangles,
            first + 2 < triangles,
            first + 3 < triangles,
        );
        let det = crate::math::difference_of_products_unless_half_cancels4(
            rb[0], rc[1], rb[1], rc[0], needed,
        );
        let noise = Vec4::splat(super::FAN_DETERMINANT_NOISE)
            * lanes.slots(|g| g.extent, b, count)
            * lanes.slots(|g| g.extent, c, count);
        self.maybe_flat |= lane_bits(det.abs().cmple(noise), first, triangles);
        let signed_g0 =
            det / (lanes.slots(|g| g.length, b, count) * lanes.slots(|g| g.length, c, count));
        store4(signed_g0, &mut self.signed_g0, first);
        signed_g0
    }

    /// The four fan triangles from triangle `first` on (of `triangles`).
    #[inline(always)]
    fn compute<const N: usize, const T: usize>(
        &mut self,
        polygon: &mut SolidAngleFan<N, T>,
        angles: &mut FanAngles,
        lanes: &VertexGroups,
        apex: Vec3,
        first: usize,
        triangles: usize,
    ) {
        let (b, c) = (first + 1, first + 2);
        let count = triangles + 2;
        let signed_g0 = self.determinants(lanes, first, triangles);
        let [bx, by, bz] = lanes.slots3(|g| g.unit, b, count);
        let [cx, cy, cz] = lanes.slots3(|g| g.unit, c, count);
        let [ax, ay, az] = splat3(apex);
        let (s01x, s01y, s01z) = (bx + ax, by + ay, bz + az);
        let (s02x, s02y, s02z) = (bx + cx, by + cy, bz + cz);
        let (s12x, s12y, s12z) = (ax + cx, ay + cy, az + cz);
        let l01 = (s01x * s01x + s01y * s01y) + s01z * s01z;
        let l02 = (s02x * s02x + s02y * s02y) + s02z * s02z;
        let l12 = (s12x * s12x + s12y * s12y) + s12z * s12z;
        // `m = v0·(v0 + v2)` and `|v0 + v2|² - m²` (`l02` is `|v0 + v2|²`, rounded as
        // `length_squared`), for the sample. Where they are computed changes how the
        // compiler allocates registers: here, for a quad's two fan triangles, 11 register
        // copies more than below (hexagons 1240.3 instructions per prepare + 1 here,
        // 1246.3 below; quads 853.2 here, 842.2 below, callgrind). Quads now take
        // `compute_quad` (two fan triangles here are the tests' reference for it); the
        // closure stays: written inline here, without the branch below, it cost native
        // hexagons one instruction per prepare + 1 (856.4 -> 857.4, callgrind).
        let outer_terms = |polygon: &mut SolidAngleFan<N, T>| {
            let along = (bx * s02x + by * s02y) + bz * s02z;
            store_triangle_lanes(along, &mut polygon.outer_along, first);
            store_triangle_lanes(l02 - along * along, &mut polygon.outer_across2, first);
        };
        if triangles > 2 {
            outer_terms(polygon);
        }
        self.wide_pairs |= lane_bits(
            l01.min(l02).min(l12).cmplt(Vec4::splat(2.0)),
            first,
            triangles,
        );
        // `denominator`, its three candidates and the choice of the shortest pair sum.
        let half = Vec4::splat(0.5);
        let d02 = half * l02 + ((ax * s02x + ay * s02y) + az * s02z);
        let d12 = half * l12 + ((bx * s12x + by * s12y) + bz * s12z);
        let d01 = half * l01 + ((cx * s01x + cy * s01y) + cz * s01z);
        let g1_plus_g2 = Vec4::select(
            l02.cmple(l01) & l02.cmple(l12),
            d02,
            Vec4::select(l12.cmple(l01), d12, d01),
        );
        store_triangle_lanes(g1_plus_g2, &mut polygon.g1_plus_g2, first);
        store_triangle_lanes(half * l01, &mut polygon.g2, first);
        if first < angles_in_lanes(triangles) {
            // `2 atan2(G0, G1 + G2)` with `G0 = |det|` as the loop of `prepare_or_fail`
            // computes it for the others (lanes past `triangles` give 0).
            let g0 = signed_g0.abs();
            let lanes = Vec4::splat(2.0)
                * crate::math::atan2_upper_half_plane4_small_first(
                    g0,
                    g1_plus_g2,
                    triangles - first,
                );
            store4(lanes, angles, first);
        }
        if triangles <= 2 {
            outer_terms(polygon);
        }
        let (s02x, s02y, s02z) = (s02x.to_array(), s02y.to_array(), s02z.to_array());
        for j in 0..LANES.min(T - first) {
            polygon.outer_sum[first + j] = Vec3::new(s02x[j], s02y[j], s02z[j]);
        }
    }
}

impl FanLanes {
    /// [`compute`](Self::compute) of the one fan triangle `k` alone, in scalar
    /// arithmetic: the same operations on the same values in the same order (Rust never
    /// contracts `a * b + c`, and the lanes' `min` and selections are the comparisons
    /// written out; none of these values is NaN: the unit vectors and the reflected edges
    /// are finite), so the same bits (tested: `a_lone_fan_triangle_is_prepared_as_in_lanes`).
    /// For a group of lanes that would hold one triangle (a triangle's, a heptagon's
    /// fifth), where the four lanes' work, their shuffles and transposed stores cost more
    /// than the one triangle's scalar work.
    #[inline(always)]
    fn compute_one<const N: usize, const T: usize>(
        &mut self,
        polygon: &mut SolidAngleFan<N, T>,
        lanes: &VertexGroups,
        apex: Vec3,
        k: usize,
    ) {
        let (b, c) = (k + 1, k + 2);
        let slot = |field: fn(&SlotGroup) -> Vec4, i: usize| lanes.slot(field, i);
        let (rb0, rb1) = (slot(|g| g.reflected[0], b), slot(|g| g.reflected[1], b));
        let (rc0, rc1) = (slot(|g| g.reflected[0], c), slot(|g| g.reflected[1], c));
        // As the lanes: `difference_of_products_unless_half_cancels4` is this lane by lane.
        let det = difference_of_products_unless_half_cancels(rb0, rc1, rb1, rc0);
        let noise = super::FAN_DETERMINANT_NOISE * slot(|g| g.extent, b) * slot(|g| g.extent, c);
        if det.abs() <= noise {
            self.maybe_flat |= 1 << k;
        }
        self.signed_g0[k] = det / (slot(|g| g.length, b) * slot(|g| g.length, c));
        let (bx, by, bz) = (
            slot(|g| g.unit[0], b),
            slot(|g| g.unit[1], b),
            slot(|g| g.unit[2], b),
        );
        let (cx, cy, cz) = (
            slot(|g| g.unit[0], c),
            slot(|g| g.unit[1], c),
            slot(|g| g.unit[2], c),
        );
        let (ax, ay, az) = (apex.x, apex.y, apex.z);
        let (s01x, s01y, s01z) = (bx + ax, by + ay, bz + az);
        let (s02x, s02y, s02z) = (bx + cx, by + cy, bz + cz);
        let (s12x, s12y, s12z) = (ax + cx, ay + cy, az + cz);
        let l01 = (s01x * s01x + s01y * s01y) + s01z * s01z;
        let l02 = (s02x * s02x + s02y * s02y) + s02z * s02z;
        let l12 = (s12x * s12x + s12y * s12y) + s12z * s12z;
        if l01 < 2.0 || l02 < 2.0 || l12 < 2.0 {
            self.wide_pairs |= 1 << k;
        }
        let d02 = 0.5 * l02 + ((ax * s02x + ay * s02y) + az * s02z);
        let d12 = 0.5 * l12 + ((bx * s12x + by * s12y) + bz * s12z);
        let d01 = 0.5 * l01 + ((cx * s01x + cy * s01y) + cz * s01z);
        polygon.g1_plus_g2[k] = if l02 <= l01 && l02 <= l12 {
            d02
        } else if l12 <= l01 {
            d12
        } else {
            d01
        };
        polygon.g2[k] = 0.5 * l01;
        polygon.outer_sum[k] = Vec3::new(s02x, s02y, s02z);
        let along = (bx * s02x + by * s02y) + bz * s02z;
        polygon.outer_along[k] = along;
        polygon.outer_across2[k] = l02 - along * along;
    }
}

impl FanLanes {
    /// [`compute_one`](Self::compute_one) of a triangle's one fan triangle (`count == 3`),
    /// with the pair sums in the lanes of group 0 instead of scalars taken out of them.
    /// A triangle's three pair sums are its three "edges" `v_i + v_(i+1)` taken
    /// cyclically, and each sum's opposite vertex is `v_(i+2)`: with slot 3 holding vertex
    /// 0 again, the lanes `(v0, v1, v2)`, shifted by one slot `(v1, v2, v0)` and by two
    /// `(v2, v0, v1)`, give in lanes 0, 1, 2 the sums `s01 = v_b + v_a`, `s02 = v_b + v_c`,
    /// `s12 = v_a + v_c` of `compute_one` (fan triangle `(v_b, v_a, v_c) = (v1, v0, v2)`)
    /// and their opposite vertices `v_c`, `v_a`, `v_b`. Addition and multiplication are
    /// commutative in IEEE arithmetic and every other operation is `compute_one`'s in its
    /// order, so each lane holds `compute_one`'s value bit for bit (tested:
    /// `a_lone_fan_triangle_is_prepared_as_in_lanes`). The three lengths, the three
    /// candidates of `denominator` and the wide-pair test take one lane operation each
    /// instead of three scalar ones and the shuffles that fed them (triangles' prepare +
    /// 1 sample: see the commit).
    #[inline(always)]
    fn compute_triangle<const N: usize, const T: usize>(
        &mut self,
        polygon: &mut SolidAngleFan<N, T>,
        lanes: &VertexGroups,
    ) {
        // The determinant as `compute_one` (scalar: one product pair).
        let slot = |field: fn(&SlotGroup) -> Vec4, i: usize| lanes.slot(field, i);
        let (rb0, rb1) = (slot(|g| g.reflected[0], 1), slot(|g| g.reflected[1], 1));
        let (rc0, rc1) = (slot(|g| g.reflected[0], 2), slot(|g| g.reflected[1], 2));
        let det = difference_of_products_unless_half_cancels(rb0, rc1, rb1, rc0);
        let noise = super::FAN_DETERMINANT_NOISE * slot(|g| g.extent, 1) * slot(|g| g.extent, 2);
        if det.abs() <= noise {
            self.maybe_flat |= 1;
        }
        self.signed_g0[0] = det / (slot(|g| g.length, 1) * slot(|g| g.length, 2));
        // `G0 = |det|` stored here, beside `G1 + G2` below, not in the loop of
        // `prepare_or_fail` after the solid angle: the sample reads the two adjacent
        // words by one 8-byte load, which store-to-load forwarding cannot serve from two
        // 4-byte stores; stored this early, both have reached the cache when the sample
        // of prepare + 1 runs (triangles' prepare + 1 about −1 to −2 ns, issue 15, stop
        // 48). The exact test of a flagged determinant writes its zero again.
        polygon.g0[0] = self.signed_g0[0].abs();
        // Slots 0..4 of group 0 hold vertices 0, 1, 2, 0: `next` is (v1, v2, v0, ·) and
        // `opposite` (v2, v0, v1, ·) (lane 3 is finite and unused).
        let [x, y, z] = lanes.groups[0].unit;
        let next = |v: Vec4| Vec4::new(v.y, v.z, v.w, v.y);
        let opposite = |v: Vec4| Vec4::new(v.z, v.w, v.y, v.z);
        // Lanes 0, 1, 2: s01, s02, s12 (`v_a + v_b`, `v_b + v_c`, `v_c + v_a`).
        let (sx, sy, sz) = (x + next(x), y + next(y), z + next(z));
        let length2 = (sx * sx + sy * sy) + sz * sz;
        if length2.cmplt(Vec4::splat(2.0)).bitmask() & 0b111 != 0 {
            self.wide_pairs |= 1;
        }
        let half_length2 = Vec4::splat(0.5) * length2;
        // Lanes 0, 1, 2: d01 (with v_c), d02 (with v_a), d12 (with v_b).
        let (ox, oy, oz) = (opposite(x), opposite(y), opposite(z));
        let candidates = half_length2 + ((ox * sx + oy * sy) + oz * sz);
        // `compute_one`'s choice of a candidate from the comparisons `l02 <= l01`,
        // `l02 <= l12` and `l12 <= l01`, made in lanes 0, 1, 2 at once (no lane is NaN:
        // the unit vectors are finite), then read from the candidates' lane that
        // `SHORTEST_PAIR` names: the same value, where the scalar comparisons and their
        // selections took 25 instructions (callgrind, issue 15).
        let (l01, l02, l12) = (length2.x, length2.y, length2.z);
        let tests = Vec4::new(l02, l02, l12, l12)
            .cmple(Vec4::new(l01, l12, l01, l01))
            .bitmask();
        polygon.g1_plus_g2[0] = candidates.to_array()[SHORTEST_PAIR[tests as usize & 0b111]];
        polygon.g2[0] = half_length2.x;
        polygon.outer_sum[0] = Vec3::new(sx.y, sy.y, sz.y);
        // `m = v_b·(v_b + v_c)` and `|s02|² - m²` in lane 1 (vertex 1 and the sum s02),
        // as `compute_one` rounds them; the lanes' work costs less than taking the six
        // scalars out of them.
        let along = (x * sx + y * sy) + z * sz;
        let across2 = length2 - along * along;
        polygon.outer_along[0] = along.y;
        polygon.outer_across2[0] = across2.y;
    }
}

impl FanLanes {
    /// [`compute`](Self::compute) of a quad's two fan triangles (`count == 4`), with the
    /// pair sums in the lanes of group 0 instead of two triangles' three sums each in
    /// lanes of their own (of which two lanes were unused). The two triangles
    /// `(v1, v0, v2)` and `(v2, v0, v3)` have five distinct pair sums, not six: the
    /// quad's four edges `v_i + v_(i+1)` (lane `i` of the lanes `(v0, v1, v2, v3)` plus
    /// the same shifted by one slot), whose opposite vertices in their fan triangle are
    /// `(v2, v0, v0, v2)`, and the diagonal `v0 + v2`, which both triangles share (lanes
    /// 0 and 2 of the lanes plus the same shifted by two slots: `v0 + v2` and
    /// `v2 + v0`), whose opposite vertices are `v1` and `v3` (the lanes shifted by one).
    /// So triangle 0's `s01`, `s02`, `s12` (`v_b + v_a`, `v_b + v_c`, `v_a + v_c` in
    /// `compute`) are edge 0, edge 1 and the diagonal's lane 0, and triangle 1's are the
    /// diagonal's lane 2, edge 2 and edge 3. Addition and multiplication are commutative
    /// in IEEE arithmetic and every other operation is `compute`'s in its order, so each
    /// value is `compute`'s bit for bit (tested:
    /// `a_lone_fan_triangle_is_prepared_as_in_lanes`), from two lengths and two
    /// candidates of `denominator` in lanes where `compute` took three (quads' prepare +
    /// 1 sample 781 -> 764 instructions, the general polygon's at 4 vertices 858 -> 828,
    /// callgrind, 3 of them from the triangles' lanes 1 and 2, where their `s02` lies).
    #[inline(always)]
    fn compute_quad<const N: usize, const T: usize>(
        &mut self,
        polygon: &mut SolidAngleFan<N, T>,
        lanes: &VertexGroups,
    ) {
        self.determinants(lanes, 0, 2);
        // Slots 0..4 of group 0 hold vertices 0, 1, 2, 3.
        let [x, y, z] = lanes.groups[0].unit;
        let next = |v: Vec4| Vec4::new(v.y, v.z, v.w, v.x);
        let across = |v: Vec4| Vec4::new(v.z, v.w, v.x, v.y);
        let edge_opposite = |v: Vec4| Vec4::new(v.z, v.x, v.x, v.z);
        // The edges `v_i + v_(i+1)` and the diagonals `v_i + v_(i+2)`.
        let (ex, ey, ez) = (x + next(x), y + next(y), z + next(z));
        let (dx, dy, dz) = (x + across(x), y + across(y), z + across(z));
        let edge2 = (ex * ex + ey * ey) + ez * ez;
        let diagonal2 = (dx * dx + dy * dy) + dz * dz;
        let half = Vec4::splat(0.5);
        let (ox, oy, oz) = (edge_opposite(x), edge_opposite(y), edge_opposite(z));
        let edge_candidates = half * edge2 + ((ox * ex + oy * ey) + oz * ez);
        let (ox, oy, oz) = (next(x), next(y), next(z));
        let diagonal_candidates = half * diagonal2 + ((ox * dx + oy * dy) + oz * dz);
        // The two triangles' `s01`, `s02` and `s12` values in lanes 1 and 2, where their
        // `s02` (edges 1 and 2) lies (lanes 0 and 3 repeat them: finite, and left out
        // below).
        let per_triangle = |e: Vec4, d: Vec4| {
            [
                Vec4::new(e.x, e.x, d.z, d.z),
                e,
                Vec4::new(d.x, d.x, e.w, e.w),
            ]
        };
        let [l01, l02, l12] = per_triangle(edge2, diagonal2);
        let [d01, d02, d12] = per_triangle(edge_candidates, diagonal_candidates);
        // As `compute`, in lanes 1 and 2.
        let wide = l01.min(l02).min(l12).cmplt(Vec4::splat(2.0));
        self.wide_pairs |= (wide.bitmask() >> 1) & 0b11;
        let g1_plus_g2 = Vec4::select(
            l02.cmple(l01) & l02.cmple(l12),
            d02,
            Vec4::select(l12.cmple(l01), d12, d01),
        );
        let lanes_1_2 = |v: Vec4| Vec4::new(v.y, v.z, v.y, v.z);
        store_triangle_lanes(lanes_1_2(g1_plus_g2), &mut polygon.g1_plus_g2, 0);
        store_triangle_lanes(lanes_1_2(half * l01), &mut polygon.g2, 0);
        // `m = v_b·(v_b + v_c)` and `|s02|² - m²`: vertex 1 and edge 1, vertex 2 and
        // edge 2, in lanes 1 and 2.
        let along = (x * ex + y * ey) + z * ez;
        let across2 = edge2 - along * along;
        store_triangle_lanes(lanes_1_2(along), &mut polygon.outer_along, 0);
        store_triangle_lanes(lanes_1_2(across2), &mut polygon.outer_across2, 0);
        let (ex, ey, ez) = (ex.to_array(), ey.to_array(), ez.to_array());
        for k in 0..2.min(T) {
            polygon.outer_sum[k] = Vec3::new(ex[k + 1], ey[k + 1], ez[k + 1]);
        }
    }
}

/// The lane of `denominator`'s candidate (0: with `s01`, 1: `s02`, 2: `s12`) from the
/// bits of its comparisons, bit 0 `l02 <= l01`, bit 1 `l02 <= l12`, bit 2 `l12 <= l01`:
/// `s02` where bits 0 and 1 are set, else `s12` where bit 2 is, else `s01` (tested against
/// `denominator` for every combination: `shortest_pair_is_the_choice_of_denominator`).
const SHORTEST_PAIR: [usize; 8] = [0, 0, 0, 1, 2, 2, 2, 1];

/// Algorithm 5's solid angle of a fan triangle, `2 atan2(G0, G1 + G2)` for `G0 >= 0`
/// (van Oosterom and Strackee).
#[inline(always)]
fn triangle_angle(g0: f32, g1_plus_g2: f32) -> f32 {
    2.0 * atan2_upper_half_plane(g0, g1_plus_g2)
}

/// `0 < x < ∞` (false for NaN) as one unsigned comparison of the bits: positive floats
/// are ordered as their bits, `+0` wraps around to the top, and negative values (the sign
/// bit), `∞` and NaN lie at or above the bits of `∞` minus one. The float comparisons and
/// the test for NaN took 14 instructions (tested for every bit pattern's class:
/// `positive_and_finite_is_the_float_test`).
#[inline(always)]
fn positive_and_finite(x: f32) -> bool {
    x.to_bits().wrapping_sub(1) < f32::INFINITY.to_bits() - 1
}

/// Writes the lanes of triangles `first..first + 4` that exist into a per-triangle array
/// of the prepared polygon (`first` is a constant where this is inlined, so the test
/// is made at compile time).
#[inline(always)]
fn store_triangle_lanes<const T: usize>(lanes: Vec4, values: &mut [f32; T], first: usize) {
    if first + LANES <= T {
        store4(lanes, values, first);
    } else {
        let end = T - first;
        values[first..].copy_from_slice(&lanes.to_array()[..end]);
    }
}

/// The edge planes four edges at a time, with the tests on their lengths.
struct EdgeLanes {
    /// `sin²` of an edge `Ω / SAMPLE_CHECK_WIDTH` long (as `Ω²` over the square).
    long_edge_sine2: f32,
    /// `sin²` of an edge `Ω / PRECISE_PLANE_WIDTH` long.
    longest_edge_sine2: f32,
    /// The polygon's winding, which orients the normals inwards.
    orientation: f32,
    count: usize,
}

impl EdgeLanes {
    /// The oriented normals of edges `first..first + 4` into `normals` (lanes past the
    /// polygon get zero vectors from the repeated first vertex), and the tests on the
    /// lengths of those that exist, as lane masks (lanes past the polygon false): an edge
    /// short enough for the short-edge rule to look at it, an edge longer than
    /// `Ω / SAMPLE_CHECK_WIDTH`, and one longer than `Ω / PRECISE_PLANE_WIDTH`. The
    /// caller combines the groups' masks with `|` and reads each once: one mask
    /// extraction per test instead of one per test and group, with the bit arithmetic
    /// that joined them (hexagons 1299 -> 1275 instructions per prepare + 1, callgrind).
    #[inline(always)]
    fn compute<const N: usize>(
        &self,
        lanes: &VertexGroups,
        first: usize,
        normals: &mut [Vec3; N],
    ) -> [BVec4A; 3] {
        let [px, py, pz] = lanes.slots3(|g| g.position, first, self.count);
        let [qx, qy, qz] = lanes.slots3(|g| g.position, first + 1, self.count);
        // p_i × p_(i+1) = p_i × (p_(i+1) - p_i): the edge vector is exact up to one
        // rounding and nearly orthogonal to p_i, so no cancellation occurs (the
        // components in the order of `Vec3::cross`).
        let (dx, dy, dz) = (qx - px, qy - py, qz - pz);
        let nx = py * dz - dy * pz;
        let ny = pz * dx - dz * px;
        let nz = px * dy - dx * py;
        // sin²ℓ = |n|² / (|p_i|² |p_(i+1)|²), kept as products (no division).
        let normal2 = (nx * nx + ny * ny) + nz * nz;
        let scale2 = lanes.slots(|g| g.length_squared, first, self.count)
            * lanes.slots(|g| g.length_squared, first + 1, self.count);
        // The first test of `ignore_short_edges_in_containment` (sin² of the edge's
        // length against SHORT_EDGE_SINE²), on the same values: the common polygon has
        // no short edge and skips it.
        let short_sine2 = Vec4::splat(super::SHORT_EDGE_SINE * super::SHORT_EDGE_SINE);
        // The lanes of edges that exist (`first` and `count` are constants where this is
        // inlined: the mask is a constant).
        let count = self.count;
        let exists = BVec4A::new(
            first < count,
            first + 1 < count,
            first + 2 < count,
            first + 3 < count,
        );
        let masks = [
            normal2.cmple(short_sine2 * scale2) & exists,
            normal2.cmpgt(Vec4::splat(self.long_edge_sine2) * scale2) & exists,
            normal2.cmpgt(Vec4::splat(self.longest_edge_sine2) * scale2) & exists,
        ];
        let orientation = Vec4::splat(self.orientation);
        let (nx, ny, nz) = (
            (nx * orientation).to_array(),
            (ny * orientation).to_array(),
            (nz * orientation).to_array(),
        );
        // All four lanes where they fit (`N` and `first` are constants here).
        for j in 0..if first + LANES <= N { LANES } else { N - first } {
            normals[first + j] = Vec3::new(nx[j], ny[j], nz[j]);
        }
        masks
    }
}

impl<const N: usize, const T: usize> SolidAngleFan<N, T> {
    /// `3 <= N <= MAX_POLYGON_VERTICES` and `T = N - 2` (a compile-time error otherwise).
    const VALID_SIZE: () = assert!(3 <= N && N <= MAX_POLYGON_VERTICES && T + 2 == N);

    /// The state of a polygon that could not be prepared: samples have `pdf == 0`,
    /// `pdf()` is 0 and the solid angle is 0.
    pub const EMPTY: Self = Self {
        vertices: [Vec3::Z; N],
        edge_normals: [Vec3::ZERO; N],
        edge_residuals: [Vec3::ZERO; N],
        g0: [0.0; T],
        g1_plus_g2: [0.0; T],
        g2: [0.0; T],
        outer_sum: [Vec3::ZERO; T],
        outer_along: [0.0; T],
        outer_across2: [0.0; T],
        start: [0.0; T],
        solid_angle: 0.0,
        density: 0.0,
        orientation: 1.0,
        vertex_count: 0,
        selectable_triangles: 0,
        careful_paths: 0,
        checks_samples: 0,
    };

    /// Prepares the convex polygon with the given vertices (positions relative to the
    /// shading point, not normalised, either winding, 3 to 8 of them).
    ///
    /// Returns `None` for fewer than 3 or more than 8 vertices, non-finite coordinates,
    /// a vertex at the shading point, and a zero (or non-representable) solid angle, for
    /// example when the shading point lies in the polygon's plane. A non-convex polygon
    /// gives a finite but meaningless result.
    ///
    /// [`prepare`](Self::prepare) does the same in place, without the copies of the
    /// prepared value that returning it costs.
    #[must_use]
    pub fn new(vertices: &[Vec3]) -> Option<Self> {
        let mut polygon = Self::EMPTY;
        polygon.prepare(vertices).then_some(polygon)
    }

    /// [`new`](Self::new) in place: writes the prepared polygon into `self` and returns
    /// `true`, or writes [`EMPTY`](Self::EMPTY) and returns `false` where `new` returns
    /// `None`. Every field that sampling, `pdf` and `invert` read is written, whatever
    /// `self` held before, and nothing is copied.
    pub fn prepare(&mut self, vertices: &[Vec3]) -> bool {
        // Every count gets its copy of the body with the count a constant: the loops
        // unroll and the lanes' masks fold, so that each pays only for its own vertices
        // (issue 15, 3): 1361 -> 1106 and 1539 -> 1338 instructions per prepare + 1 sample
        // for triangles and quads (callgrind, C benchmark). Since the working set stays in
        // registers (`VertexGroups`), the copies pay for 5 to 8 vertices too (one shared
        // body with a run-time count: hexagons 1504, heptagons 1792; one per count: 1326
        // and 1622; a body for 5 to 7 and one for 8: 1453 and 1730). Those four copies
        // are kept out of line (inlined beside the small copies, the shared body grew
        // from 1667 to 1903 instructions per hexagon).
        // The sizes' parameters, checked where a size is first used.
        let () = Self::VALID_SIZE;
        let count = vertices.len();
        // 5 to 8 vertices first, by a tail call into their own function, which writes the
        // empty value itself: this function's frame (the registers that the inlined
        // triangle and quad bodies save) is then set up on their paths only, where the
        // call through it saved and restored six registers twice (hexagons: see the
        // commit, callgrind).
        if (5..=MAX_POLYGON_VERTICES).contains(&count) && count <= N {
            return self.prepare_five_to_eight(vertices);
        }
        let prepared = match count {
            3 => self.prepare_or_fail(vertices, 3),
            4 if N >= 4 => self.prepare_or_fail(vertices, 4),
            _ => false,
        };
        super::keep_or_empty(self, prepared, Self::EMPTY)
    }

    /// [`prepare`](Self::prepare) for 5 to 8 vertices, a copy of
    /// [`prepare_or_fail`](Self::prepare_or_fail) per count (kept apart so that the
    /// triangles' and quads' copies do not change how the compiler inlines them).
    #[inline(never)]
    fn prepare_five_to_eight(&mut self, vertices: &[Vec3]) -> bool {
        let count = vertices.len();
        // One copy per count (for `N < 8`, `prepare_or_fail`'s range test folds the
        // copies above `N` to `false`; guards `if N >= 5` here instead cost the triangle
        // size 10 instructions per prepare + 1, callgrind).
        let prepared = match count {
            5 => self.prepare_or_fail(vertices, 5),
            6 => self.prepare_or_fail(vertices, 6),
            7 => self.prepare_or_fail(vertices, 7),
            8 => self.prepare_or_fail(vertices, 8),
            _ => false,
        };
        super::keep_or_empty(self, prepared, Self::EMPTY)
    }

    /// The body of [`prepare`](Self::prepare) for `count == vertices.len()` (3 to 8); on
    /// `false`, `self` holds partial values.
    #[inline(always)]
    fn prepare_or_fail(&mut self, vertices: &[Vec3], count: usize) -> bool {
        // The range of `count` where the compiler sees it (the callers test it too): the
        // indices below `count` then need no bounds checks.
        if !(3..=N).contains(&count) {
            return false;
        }
        let vertices = &vertices[..count];
        // The input in lanes, and the power of two that rescales it (as `rescale`).
        let (raw, factor) = gather_and_rescale(vertices, count);
        let Some(factor) = factor else {
            return false;
        };
        // The per-vertex work four vertices at a time (see `VertexGroups`), rounded as the
        // scalar forms round it: divided, not multiplied by a reciprocal, so that unit
        // vectors are correctly rounded (half an ulp). With the reciprocal (one ulp) the
        // chi-square test found a sample at u0 = 1 - 5e-7 whose direction rounded 1.5e-8
        // to the outer side of its edge, where `pdf` was 0; and the reciprocal of a length
        // below 2^-128 overflows.
        let Some((groups, reflection)) = VertexGroups::new(raw, factor, count) else {
            return false;
        };
        groups.write_units(&mut self.vertices, count);
        let apex = groups.apex();
        let triangles = count - 2;
        let mut fan = FanLanes::default();
        let mut angles: FanAngles = [0.0; 2 * LANES];
        // A triangle's one fan triangle on its own, the same bits: the determinant in
        // scalar arithmetic, the pair sums in the lanes of its three vertices
        // (`compute_triangle`; triangles 763 -> 734 instructions per prepare + 1 with
        // `compute_one`, 734 -> 675 with the pair sums in lanes, callgrind). A quad's two
        // fan triangles share one group of lanes for their five pair sums
        // (`compute_quad`; quads 781 -> 764 instructions per prepare + 1, callgrind).
        if triangles == 1 {
            fan.compute_triangle(self, &groups);
        } else if triangles == 2 {
            fan.compute_quad(self, &groups);
        } else {
            fan.compute(self, &mut angles, &groups, apex, 0, triangles);
        }
        // A last group of one triangle (heptagons) in scalar arithmetic, the same bits
        // (heptagons 1588 -> 1546 instructions per prepare + 1, callgrind).
        if triangles == LANES + 1 {
            fan.compute_one(self, &groups, apex, LANES);
        } else if triangles > LANES {
            fan.compute(self, &mut angles, &groups, apex, LANES, triangles);
        }
        // The rare triangles that the lanes flagged, in the scalar careful forms.
        let mut careful_paths = 0;
        // One pass per set bit (the lanes' flags have no bits past `triangles`): the
        // common polygon, with no flag, skips the loop at once.
        let mut flagged = fan.maybe_flat | fan.wide_pairs;
        // The working set in memory, for the run-time indices below (rare), built only
        // when a triangle is flagged: an `if` that chose between it and a zero value
        // stored the 576 zero bytes on the common path too (14 instructions per
        // hexagon, callgrind).
        if flagged != 0 {
            let memory = groups.lanes();
            let lanes = &memory;
            while flagged != 0 {
                let k = flagged.trailing_zeros() as usize;
                // Clears the lowest set bit.
                flagged &= flagged - 1;
                let (b, c) = (k + 1, k + 2);
                // A triangle exactly in a plane through the shading point has G0 = 0, which
                // the reflection's rounding would turn into noise (and a polygon in such a
                // plane into a tiny light with a huge pdf): below the noise bound, the exact
                // test decides.
                if fan.maybe_flat & (1 << k) != 0
                    && determinant_is_exactly_zero(
                        lanes.position(0),
                        lanes.position(b),
                        lanes.position(c),
                    )
                {
                    fan.signed_g0[k] = 0.0;
                    self.g0[k] = 0.0;
                }
                // The pair sums `v_i + v_j`. Fast path (the lanes): the plain sums of the
                // rounded unit vectors. Each unit vector is off by at most half an ulp of 1 per
                // component (correctly rounded division), so a sum of length `|s|` carries a
                // relative error of at most about `ε / |s| + ε/2`: for `|s|² >= 2` (the
                // vertices at most 90° apart) at most 1.2ε, against the compensated sums' ε/2.
                // The bound was chosen by measurement: with `|s|² >= 1` (120°) the largest
                // error of Ω at 1 sr in the report's accuracy table grew from 6.4e-7 to
                // 7.8e-7; with 90° every row stays as docs/polygon-lights.md states it but for 1e-8 sr
                // (max 5.2e-7 against 4.9e-7). Only for pairs farther apart (up to nearly
                // antipodal, where the plain sum loses its relative precision: a shading
                // point close to a large polygon) do the compensated sums run.
                if fan.wide_pairs & (1 << k) != 0 {
                    let unit_sum = |i: usize, j: usize| {
                        let (p, q) = (lanes.position(i), lanes.position(j));
                        unit_vector_sum(p, q, lanes.length[i], lanes.length[j])
                    };
                    let (s01, s02, s12) = (unit_sum(b, 0), unit_sum(b, c), unit_sum(0, c));
                    let (l01, l02, l12) = (
                        s01.length_squared(),
                        s02.length_squared(),
                        s12.length_squared(),
                    );
                    let (v0, v1, v2) = (self.vertices[b], apex, self.vertices[c]);
                    self.g1_plus_g2[k] = denominator(v0, v1, v2, [s01, s02, s12], [l01, l02, l12]);
                    self.g2[k] = 0.5 * l01;
                    self.outer_sum[k] = s02;
                    let along = self.vertices[b].dot(s02);
                    self.outer_along[k] = along;
                    self.outer_across2[k] = l02 - along * along;
                    careful_paths |= CAREFUL_PAIR_SUMS;
                }
                // The lanes' solid angle of the values just replaced, again (scalar).
                if k < angles_in_lanes(triangles) {
                    angles[k] = triangle_angle(fan.signed_g0[k].abs(), self.g1_plus_g2[k]);
                }
            }
        }
        // Algorithm 5: A = 2 atan2(G0, G2 + G1), with G0 >= 0 (bit for bit as
        // `triangle_solid_angle` computes it again when sampling): in lanes where
        // `FanLanes::compute` computed them from its registers (`angles_in_lanes`; a lanes'
        // round trip, scalar `G0` and `G1 + G2` stored and loaded back as lanes, stalled
        // on store-to-load forwarding), else here. One loop over the triangles: the
        // running sums and the tests on the solid angles.
        // `G0 = |det|` four triangles at a time, and whether every determinant is zero
        // (below), from the lanes: one store and one comparison per four triangles in
        // place of a store and a comparison per triangle in the loop (lanes past
        // `triangles` store values that the unused slots' zeros overwrite at the end, and
        // their comparisons are masked off; `-0 == 0` and a NaN compares unequal, as in
        // the scalar `g0 == 0.0`).
        // Triangles and quads (one or two fan triangles) keep the scalar form in the loop,
        // which costs them less (a triangle's prepare + 1 sample: 762 -> 773 instructions
        // with the lanes, callgrind).
        let in_lanes = triangles > 2;
        let mut edge_on = true;
        if in_lanes {
            let signed_lanes =
                |first: usize| Vec4::from_slice(&fan.signed_g0[first..first + LANES]);
            let signed0 = signed_lanes(0);
            store_triangle_lanes(signed0.abs(), &mut self.g0, 0);
            let mut zero_determinants = lane_bits(signed0.cmpeq(Vec4::ZERO), 0, triangles);
            if triangles > LANES {
                let signed1 = signed_lanes(LANES);
                store_triangle_lanes(signed1.abs(), &mut self.g0, LANES);
                zero_determinants |= lane_bits(signed1.cmpeq(Vec4::ZERO), LANES, triangles);
            }
            edge_on = zero_determinants == (1 << triangles) - 1;
        }
        // Fan triangles up to the last one with a positive solid angle are selectable.
        let mut selectable = 0usize;
        // From -0, the identity of addition (`-0 + x` is `x`, also for `x = +0`), which the
        // compiler then leaves out; only the sign of a zero sum can differ from a sum
        // from +0, and the orientation's test `> 0` does not see it.
        let mut signed_sum = -0.0f32;
        let mut total = 0.0f32;
        // The solid angles of the triangles that the lanes left out, before the loop: a
        // loop of its own for them and the running sums, each with a scalar `atanf`
        // inline over its whole range, stayed a loop of two passes for a quad (828 -> 861
        // instructions per prepare + 1, callgrind).
        #[allow(clippy::needless_range_loop)] // k indexes the fan's and the polygon's arrays
        for k in angles_in_lanes(triangles)..triangles {
            angles[k] = triangle_angle(fan.signed_g0[k].abs(), self.g1_plus_g2[k]);
        }
        #[allow(clippy::needless_range_loop)] // k indexes the fan's and the polygon's arrays
        for k in 0..triangles {
            let g0 = fan.signed_g0[k].abs();
            if !in_lanes {
                // (A triangle's `G0` is stored by `compute_triangle`.)
                if triangles > 1 {
                    self.g0[k] = g0;
                }
                edge_on &= g0 == 0.0;
            }
            let angle = angles[k];
            if angle > 0.0 {
                selectable = k + 1;
            }
            signed_sum += fan.signed_g0[k];
            self.start[k] = total;
            total += angle;
        }
        self.selectable_triangles = selectable as u32;
        // `+∞` past the selectable triangles, which `select_piece` then skips (rare: the
        // last triangles have zero solid angle).
        for start in &mut self.start[selectable..triangles] {
            *start = f32::INFINITY;
        }
        let density = 1.0 / total;
        // All determinants zero: the shading point lies in the polygon's plane. If it
        // also lies inside the polygon, van Oosterom and Strackee's formula gives 2π
        // (atan2(0, negative)) for a polygon that is seen edge-on: reject it.
        // (`total` positive and finite, and `density` finite: for a positive `total`,
        // `density` is positive and not NaN, so comparisons with ∞ are the whole test;
        // `is_finite` compiled to a classification of the bits, 20 instructions.)
        // `density < ∞` stays a comparison of floats: under denormals-are-zero a
        // subnormal `total` gives an infinite `density`.
        let accepted = positive_and_finite(total) && density < f32::INFINITY;
        if edge_on || !accepted {
            return false;
        }
        // det(p_b, p_a, p_c) = -det(p_a, p_b, p_c): a positive sum means the polygon
        // winds clockwise as seen from the shading point (`signed_sum` is σ times it: see
        // `FanLanes::signed_g0`).
        let orientation = if reflection.sigma * signed_sum > 0.0 {
            -1.0
        } else {
            1.0
        };
        // Stored here, where they are known (the edges below read `orientation` and
        // `total` from registers): stored at the end, they were kept across the call of
        // the short-edge rule in stack slots, a store and a load each on the common path
        // (with `signed_sum` from -0 above: quads 5 and hexagons 14 instructions fewer
        // per prepare + 1, callgrind).
        self.solid_angle = total;
        self.density = density;
        self.orientation = orientation;
        // Ω² · SAMPLE_CHECK_WIDTH⁻²: an edge with sin²ℓ above it is longer than
        // Ω / SAMPLE_CHECK_WIDTH.
        let edges = EdgeLanes {
            long_edge_sine2: total * total * (1.0 / (SAMPLE_CHECK_WIDTH * SAMPLE_CHECK_WIDTH)),
            longest_edge_sine2: total * total * (1.0 / (PRECISE_PLANE_WIDTH * PRECISE_PLANE_WIDTH)),
            orientation,
            count,
        };
        // Edge i runs from vertex i to vertex i + 1 (slot `count` holds the first vertex
        // again, so the lanes need no wrap-around).
        let mut flags = edges.compute(&groups, 0, &mut self.edge_normals);
        if count > LANES {
            let [short, narrow, narrowest] = edges.compute(&groups, LANES, &mut self.edge_normals);
            flags = [flags[0] | short, flags[1] | narrow, flags[2] | narrowest];
        }
        let [maybe_short, narrow, narrowest] = flags.map(|mask| mask.any());
        self.checks_samples = narrow as u32 + narrowest as u32;
        // The narrowest polygons: the edge planes to about ε² (see `edge_residuals`), in
        // place of the rounded ones; the others keep zero residuals.
        self.edge_residuals = [Vec3::ZERO; N];
        if narrowest {
            let lanes = groups.lanes();
            for i in 0..count {
                let (normal, residual) = crate::math::cross_with_residual(
                    lanes.position(i),
                    lanes.position(i + 1) - lanes.position(i),
                );
                self.edge_normals[i] = normal * orientation;
                self.edge_residuals[i] = residual * orientation;
            }
        }
        // Unused slots get zero normals, which every direction passes.
        for normal in &mut self.edge_normals[count..] {
            *normal = Vec3::ZERO;
        }
        // An edge a few ulps long (a vertex that clipping put a few ulps from its
        // neighbour) has a plane of rounding noise, which cut away up to 0.03 rad of the
        // polygon from `contains` (found by fuzzing); it is left out of the test.
        if maybe_short {
            let lanes = groups.lanes();
            let positions: [Vec3; MAX_POLYGON_VERTICES + 1] =
                core::array::from_fn(|i| lanes.position(i));
            super::ignore_short_edges_in_containment(&mut self.edge_normals, &positions, count);
            // A dropped edge passes every direction: its residual goes too.
            for (residual, normal) in self.edge_residuals.iter_mut().zip(&self.edge_normals) {
                if *normal == Vec3::ZERO {
                    *residual = Vec3::ZERO;
                }
            }
            careful_paths |= CAREFUL_SHORT_EDGES;
        }
        self.careful_paths = careful_paths;
        // The unused slots as in the empty value: no stale or NaN word is left in a
        // prepared value (the adversarial C test fills it with NaN first).
        for i in count..N {
            self.vertices[i] = Vec3::Z;
        }
        for k in triangles..T {
            self.g0[k] = 0.0;
            self.g1_plus_g2[k] = 0.0;
            self.g2[k] = 0.0;
            self.outer_sum[k] = Vec3::ZERO;
            self.outer_along[k] = 0.0;
            self.outer_across2[k] = 0.0;
            self.start[k] = f32::INFINITY;
        }
        self.vertex_count = count as u32;
        true
    }

    /// Which careful fallbacks preparation took, as a set of bits: [`CAREFUL_PAIR_SUMS`]
    /// and [`CAREFUL_SHORT_EDGES`]; 0 for the common, well-conditioned polygon, which
    /// takes the fast path throughout (and for the empty polygon).
    ///
    /// The fast path sums unit vertex directions plainly; it is taken for every fan
    /// triangle whose three pairwise sums have `|v_i + v_j|² >= 2` (vertices at most 90°
    /// apart), where the plain sum's relative error is at most about 1.2ε against the
    /// compensated sum's ε/2. The containment test's short-edge rule runs only when an edge
    /// is shorter than about 1.5e-5 rad.
    #[inline]
    #[must_use]
    pub fn careful_paths(&self) -> u32 {
        self.careful_paths
    }

    /// Total solid angle Ω of the polygon in steradians (0 when empty).
    #[inline]
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle
    }

    /// Draws a direction uniformly in solid angle inside the polygon (Algorithm 5 with
    /// fan selection). `u` is clamped to `[0, 1 - ulp]`; NaN counts as 0. The returned
    /// pdf is `1 / Ω`, or 0 (with a finite direction) for an empty polygon.
    #[inline]
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        let sample = self.sample_unchecked(u);
        // `pdf` finds directions inside up to a slack that, for narrow polygons, may be
        // below the rounding of a direction sampled next to an edge (issue 16, 1): there
        // the direction is tested, and one that rounding put outside is pulled towards
        // the polygon's centroid until inside (`INWARD_PULLS`), so that
        // `pdf(sample.dir) == sample.pdf` for every sample.
        if self.checks_samples != 0 && sample.pdf > 0.0 && !self.contains(sample.dir) {
            return self.pulled_inside(sample.dir);
        }
        sample
    }

    /// `dir` (a sample just outside) pulled towards the centroid of the unit vertex
    /// directions (inside: the polygon is convex) by the fractions of `INWARD_PULLS` until
    /// [`contains`](Self::contains) accepts it, with the density `1 / Ω`; no sample where
    /// even the centroid is rejected.
    #[cold]
    fn pulled_inside(&self, dir: Vec3) -> Sample {
        let count = super::stored_count(self.vertex_count, N);
        let mut sum = Vec3::ZERO;
        for v in &self.vertices[..count] {
            sum += *v;
        }
        let centroid = crate::math::normalize_or(sum, self.vertices[0]);
        crate::sample::INWARD_PULLS
            .iter()
            .map(|&pull| crate::math::normalize_or(dir * (1.0 - pull) + centroid * pull, centroid))
            .find(|&pulled| self.contains(pulled))
            .map_or(Sample::NONE, |dir| Sample {
                dir,
                pdf: self.density,
            })
    }

    /// The sample of the common case, `None` for the rare one (then
    /// [`sample`](Self::sample) gives it): `u` outside `[0, 1)²` (which `sample` clamps),
    /// the empty value, the narrow polygons whose
    /// samples `sample` tests (`checks_samples`), and directions that the construction
    /// left more than 2e-6 off unit length squared (which `sample` renormalises). Equal
    /// to `sample` bit for bit where it gives a sample (the same computation without
    /// those branches). Without calls and with one return value, so that the C entry
    /// point keeps everything in registers and reaches the rare path by one call on that
    /// path only: the call of `sample` out of line returned the sample through the stack,
    /// and the caller's 8-byte load of `dir.z` and `pdf` from two 4-byte stores stalled
    /// on the failed store-to-load forwarding.
    #[inline(always)]
    pub(crate) fn sample_common(&self, u: [f32; 2]) -> Option<Sample> {
        // `u` in [0, 1)², where `clamp_random` changes nothing: as unsigned integers, the
        // bits of the floats in [0, 1) are those below the bits of 1.0 (`0x3F80_0000`);
        // 1 and above, NaN (above +∞) and negative values (the sign bit) are not.
        let outside = u[0].to_bits().max(u[1].to_bits()) >= 0x3F80_0000;
        if self.selectable_triangles == 0 || self.checks_samples != 0 || outside {
            return None;
        }
        let target = u[0] * self.solid_angle;
        let (k, start) = self.piece(target);
        // `start[k] <= target` (`select_piece` counts the starts at or below it, and
        // `start[0] = 0`), so the difference is not negative: no clamp to 0 (a NaN start,
        // a corrupted value, gives a NaN direction, which the unit test sends to the rare
        // path).
        let local = target - start;
        let dir = self.direction_in_triangle(k, local, u[1]);
        crate::math::is_unit_output(dir).then_some(Sample {
            dir,
            pdf: self.density,
        })
    }

    /// [`sample`](Self::sample) out of line, for the rare path of the C entry points
    /// (see [`sample_common`](Self::sample_common)).
    #[inline(never)]
    pub(crate) fn sample_rare(&self, u: [f32; 2]) -> Sample {
        self.sample(u)
    }

    /// [`sample`](Self::sample) without the test of narrow polygons' samples: the
    /// direction of Algorithm 5 as computed, which rounding may put just outside `pdf`'s
    /// support. For the warps that map their own density through it (Hart et al.), whose
    /// `pdf` inverts the direction and must see it where it was drawn.
    #[inline(always)]
    pub(crate) fn sample_unchecked(&self, u: [f32; 2]) -> Sample {
        if self.selectable_triangles == 0 {
            return Sample::NONE;
        }
        let (k, local, u1) = self.fan_coordinates(u);
        self.sample_in_triangle(k, local, u1)
    }

    /// The fan triangle `k`, the solid angle `local` from its first edge and the clamped
    /// `u1` of the random numbers `u`, for a polygon with a selectable triangle.
    #[inline(always)]
    fn fan_coordinates(&self, u: [f32; 2]) -> (usize, f32, f32) {
        let (u0, u1) = (clamp_random(u[0]), clamp_random(u[1]));
        let target = u0 * self.solid_angle;
        // Fan triangle k: the number of triangles (among all but the last selectable)
        // that end at or before the target. `<=` skips triangles of zero solid angle.
        let (k, start) = self.piece(target);
        let local = (target - start).max(0.0);
        (k, local, u1)
    }

    /// The piece `k = select_piece(&self.start, target)` and its start `start[k]`, for a
    /// prepared polygon (`start[0] = 0`, as preparation writes it), without a load from
    /// the index that the comparisons compute: such a load waits for the comparison and
    /// then for the cache (about 10 cycles at the head of the sample's chain of dependent
    /// operations, which runs from `target` through the sine and cosine, two divisions
    /// and a square root to the direction). A triangle's one fan triangle starts at 0,
    /// and `target - 0 = target` exactly (also for `-0`), so the subtraction goes too;
    /// a quad's second starts at `start[1]` when `start[1] <= target` (the comparison of
    /// `select_piece`), else the first at 0: one lane comparison gives both the mask of
    /// the one value and `k` (its sign bit), so that `k` is an integer that the loads
    /// index, where the comparison's flag made the compiler select each field's address
    /// by a `cmov` (quads: 179 -> 177 instructions per sample, callgrind). Larger fans
    /// keep the load. The same values bit for bit (tested:
    /// `piece_is_select_piece_and_its_start`); a corrupted `start[0]` (outside the
    /// contract) is read as 0.
    #[inline(always)]
    fn piece(&self, target: f32) -> (usize, f32) {
        if T == 1 {
            (0, 0.0)
        } else if T == 2 {
            // `start[1] <= target` in lane 0 (false for a NaN, as the scalar `<=`); the
            // other lanes are not read (`start[1]` in lane 0 alone is one 4-byte load).
            let start1 = Vec4::new(self.start[1], 0.0, 0.0, 0.0);
            let second = start1.cmple(Vec4::splat(target));
            let start = Vec4::select(second, start1, Vec4::ZERO);
            ((second.bitmask() & 1) as usize, start.x)
        } else {
            let k = select_piece(&self.start, target);
            (k, self.start[k])
        }
    }

    /// The solid angle of fan triangle `k`, `2 atan2(G0, G1 + G2)`, computed anew (the
    /// difference of the running sums `start` loses the precision of a small triangle
    /// next to large ones).
    #[inline(always)]
    pub(crate) fn triangle_solid_angle(&self, k: usize) -> f32 {
        triangle_angle(self.g0[k], self.g1_plus_g2[k])
    }

    /// Algorithm 5 in fan triangle `k`: the direction at solid angle `local` from the
    /// triangle's first edge and at `u1` along the new edge, with pdf `1 / Ω`.
    #[inline(always)]
    pub(crate) fn sample_in_triangle(&self, k: usize, local: f32, u1: f32) -> Sample {
        let dir = self.direction_in_triangle(k, local, u1);
        // Where the apex and v2' are nearly antipodal (a shading point just above a
        // large polygon, close to its plane), b is tiny and known only to an absolute
        // ulp, so t and with it |dir| can be off by up to about 1e-3 (found by fuzzing:
        // |dir| = 0.99957); renormalise then. The test leaves every other direction
        // (|dir|² within 2e-6 of 1) bit for bit as it was.
        let Some(dir) = crate::math::unit_if_needed_or_none(dir) else {
            return Sample::NONE;
        };
        Sample {
            dir,
            pdf: self.density,
        }
    }

    /// Element `i < len` of the `[Vec3; len]` field at byte offset `field` of `self` as a
    /// `Vec3A`, by one 16-byte load whose fourth lane is the float that follows the element
    /// in `self` (`Vec3A::from(Vec3)` took four instructions per vector: a 4-byte and an
    /// 8-byte load and two shuffles). The fourth lane is garbage that nothing reads: every
    /// use of these vectors in [`direction_in_triangle`](Self::direction_in_triangle) takes
    /// `x`, `y` and `z` lane by lane (products, sums and `length_squared`, whose sums leave `w` out), and the direction returned is the
    /// `Vec3` of the first three lanes, so the bits are those of the 12-byte loads
    /// (`padded_loads_read_the_elements` pins it). The load stays inside `self`: the
    /// struct is `repr(C)` of `f32`, `u32` and `Vec3` fields without padding (its size is
    /// the sum of theirs, asserted below), and both fields read this way are followed by
    /// another field (`PADDED_FIELDS_ARE_FOLLOWED`), so the float after the last element
    /// is an initialised word of `self`. The load is of a `Vec4`, not of `[f32; 4]`: the
    /// array's four floats were split into four loads, and a triangle's apex (slot 0,
    /// whose fourth lane is the first float of `v0`, slot 1) was rebuilt from a 4-byte and
    /// an 8-byte load, `v0`'s register and three shuffles (triangles' sample 166.4 ->
    /// 164.4 instructions, 24.1 -> 23.3 ns, callgrind and interleaved timing).
    #[inline(always)]
    fn padded(&self, field: usize, i: usize, len: usize) -> Vec3A {
        let () = Self::PADDED_FIELDS_ARE_FOLLOWED;
        assert!(i < len);
        let offset = field + 12 * i;
        // SAFETY: `offset + 16 <= size_of::<Self>()` for `i < len` (see
        // `PADDED_FIELDS_ARE_FOLLOWED`), the pointer derives from `self`, which covers
        // the whole struct, the read is unaligned, and every bit pattern is an `f32`.
        let lanes = unsafe {
            core::ptr::from_ref(self)
                .cast::<u8>()
                .add(offset)
                .cast::<Vec4>()
                .read_unaligned()
        };
        Vec3A::from_vec4(lanes)
    }

    /// [`padded`](Self::padded)'s fields, `vertices` and `outer_sum`, are each followed by
    /// at least one 4-byte word of `self` (`edge_normals`, `start`), and the struct has no
    /// padding (a byte of padding would be uninitialised).
    const PADDED_FIELDS_ARE_FOLLOWED: () = {
        use core::mem::{offset_of, size_of};
        assert!(offset_of!(Self, vertices) + 12 * N + 4 <= size_of::<Self>());
        assert!(offset_of!(Self, outer_sum) + 12 * T + 4 <= size_of::<Self>());
        // Three `[Vec3; N]`, six `[f32; T]`, one `[Vec3; T]` and seven 4-byte words.
        assert!(size_of::<Self>() == 4 * (9 * N + 9 * T + 7));
    };

    /// The direction of [`sample_in_triangle`](Self::sample_in_triangle) before its
    /// length is checked.
    #[inline(always)]
    fn direction_in_triangle(&self, k: usize, local: f32, u1: f32) -> Vec3 {
        // In `Vec3A` (a whole SSE register, the fourth lane unused): each lane rounds as
        // `Vec3`'s component does, and the dot products add `(x x' + y y') + z z'` in
        // both, so the bits are the same, with fewer shuffles between the three
        // components (callgrind: 230 -> 213 instructions per sample).
        let v0 = self.padded(core::mem::offset_of!(Self, vertices), k + 1, N);
        let outer_sum = self.padded(core::mem::offset_of!(Self, outer_sum), k, T);
        // sin and cos of A/2 from A itself (`sin_cos_of_half`: the bits of
        // `sin_cos_0_to_pi(0.5 * local)`, one multiplication fewer on the chain).
        let (sin_half, cos_half) = crate::math::sin_cos_of_half(local);
        // Algorithm 5's r = (G0 cos(A/2) - G1 sin(A/2)) v0 + G2 sin(A/2) v2 bisects the
        // arc from v0 to the new vertex v2', the reflection of -v0 about r. Rewritten as
        // r = (G0 cos(A/2) - (G1 + G2) sin(A/2)) v0 + G2 sin(A/2) (v0 + v2), all of whose
        // factors are known to full relative precision, it stays accurate when v0 and v2
        // are nearly antipodal (a shading point just above a large polygon), where
        // G0 and G1 + G2 are both tiny and G1 alone would be off by an ulp of 1.
        // The prepared scalars are loaded after the sine and cosine, where they are
        // first used (and the apex below, after v2'): loaded at the top, they were live
        // across both branches of `sin_cos_of_half`, and the compiler kept some of them in
        // stack slots (triangles 170.4 -> 166.4, quads 176 -> 166 instructions per
        // sample, callgrind; 24.6 -> 24.3 and 23.8 -> 23.0 ns). The same loads, the same
        // bits.
        let (g0, g1_plus_g2, g2) = (self.g0[k], self.g1_plus_g2[k], self.g2[k]);
        // What depends on the fan triangle alone, off the chain of dependent operations
        // (which runs from `local` through the sine and cosine, a division and a square
        // root to the direction): m = v0·(v0 + v2) = 1 + v0·v2 and |s|² - m² for
        // s = v0 + v2, the squared length of the part of s orthogonal to v0 (sin²Θ for
        // the arc Θ from v0 to v2), both rounded to within a few ulps of |s|², which is
        // small exactly when they are (v0 and v2 nearly antipodal). Both come from the
        // prepared value (`outer_along`, `outer_across2`), computed there as the dot
        // products of the stored `v0` and `s` were computed here (per sample: 196 -> see
        // the commit, callgrind).
        let (m, orthogonal2) = (self.outer_along[k], self.outer_across2[k]);
        let (alpha, beta) = (g0 * cos_half - g1_plus_g2 * sin_half, g2 * sin_half);
        let r = v0 * alpha + outer_sum * beta;
        // The reflection of -v0 about r, 2 (v0·r) / (r·r) r - v0, with v0·r and r·r from
        // the scalars instead of two dot products of r (which waited for r and for a
        // horizontal sum): v0·r = α + β m and, as r = (α + β m) v0 + β (s - m v0) splits
        // into two orthogonal parts, r·r = (v0·r)² + β² (|s|² - m²), a sum of two squares
        // without cancellation. The error of |s|² - m² (a few ulps of |s|²) enters r·r
        // with the weight β² ≤ |r|² / |s|² (the orthogonal part of r, β |s - m v0|, is
        // |r| sin(θ/2), at most |r| sin(Θ/2) = |r| |s - m v0| / |s|), so at most a few
        // ulps of r·r: as accurate as the dot product.
        let v0_r = alpha + beta * m;
        let r_r = v0_r * v0_r + (beta * beta) * orthogonal2;
        // (The factor 2 on r, off the chain, is exact. v2' is formed before v1 ± v2':
        // forming v1 + v2' as 2 (v0·r) / (r·r) r + (v1 - v0) and v2' - s' v1 as
        // 2 (v0·r) / (r·r) r - (v0 + s' v1) would save 3 cycles on the chain, but adds a
        // rounding at the magnitude of 2 v0 to the tangent of a tiny triangle, the part
        // of the direction that decides whether it lies inside; the report's accuracy
        // tables could not tell the two forms apart, and the shorter error was kept.)
        let new_vertex = (r + r) * (v0_r / r_r) - v0;
        // Uniform in solid angle along the arc from the apex v1 to v2': the cosine to
        // the apex is s = (1 - ξ1) + ξ1 s'. With a = 1 - s' and b = 1 + s' =
        // |v1 + v2'|²/2 (accurate where v2' is nearly opposite the apex, and b is
        // small), the tangent coefficient t' = sqrt((1 - s²) / (1 - s'²)) is
        // sqrt(ξ1 (1 + s) / b) because 1 - s = ξ1 a, and 1 + s = b + (1 - ξ1) a with
        // a = 2 - b (v1 and v2' are unit vectors) is ξ1 b + 2 (1 - ξ1), so that
        // t'² = ξ1² + 2 ξ1 (1 - ξ1) / b = ξ1² + 4 ξ1 (1 - ξ1) / |v1 + v2'|²: one division
        // and a sum of two positive terms, no cancellation. a enters only through
        // 1 + s and s, where its rounding (an ulp of 2, where a itself may be tiny: a
        // tiny triangle) moves the direction along v1 alone, i.e. changes its length by
        // an ulp, not where it points.
        // The apex v1 is loaded here, where it is first used: loaded beside v0 at the
        // top, its 16 bytes overlapped v0's, and the compiler built v0 from the apex's
        // load and two narrower ones and kept the apex in a stack slot across the sine
        // and cosine (triangles: 172.3 -> 170.4 instructions and 25.0 -> 24.4 ns per
        // sample, callgrind and interleaved timing). The same loads, so the same bits.
        let v1 = self.padded(core::mem::offset_of!(Self, vertices), 0, N);
        let sum2 = (v1 + new_vertex).length_squared();
        let b = 0.5 * sum2;
        let s_new = b - 1.0;
        let s = 1.0 - u1 * (2.0 - b);
        let t = crate::math::sqrtf(
            u1 * u1 + (4.0 * u1 * (1.0 - u1)) / sum2.max(2.0 * f32::MIN_POSITIVE),
        );
        // s v1 + t' (v2' - s' v1): the part along v1 and t' times the part of v2'
        // orthogonal to it (of length sqrt(1 - s'²)), which is formed while the division
        // and the square root run.
        let tangent = new_vertex - v1 * s_new;
        Vec3::from(v1 * s + tangent * t)
    }

    /// `1 / Ω` for a direction inside the polygon (or on its boundary, or outside it by at
    /// most the smaller of 16 ulps (1.9e-6 rad) and 2e-5 of the polygon's width `Ω / P`,
    /// where rounding puts samples drawn next to an edge), 0 outside. `dir` need not be
    /// normalised; a zero or non-finite `dir` gives 0.
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        if self.contains(dir) {
            self.density
        } else {
            0.0
        }
    }

    /// Whether the ray along `dir` passes through the polygon (boundary included), or
    /// outside it by at most the slack of [`pdf`](Self::pdf).
    #[inline]
    pub fn contains(&self, dir: Vec3) -> bool {
        // A non-finite `dir` is outside (found by fuzzing: (0, 0, ∞) passed every edge
        // test with an infinite dot product and got the density 1 / Ω).
        let valid = self.vertex_count > 0 && dir.is_finite() && dir.length_squared() > 0.0;
        let mut inside = true;
        if self.checks_samples >= 2 {
            for i in 0..N {
                // Unused slots hold zero normals, whose dot product 0 passes.
                inside &= self.edge_side(i, dir) >= 0.0;
            }
        } else {
            for i in 0..N {
                inside &= self.edge_normals[i].dot(dir) >= 0.0;
            }
        }
        // Directions inside (every MIS query of a direction in the light) pass the plain
        // test; only those outside or within rounding of the boundary pay for the slack.
        valid && (inside || self.contains_with_slack(dir))
    }

    /// [`contains_within`](Self::contains_within) with the slack of [`pdf`](Self::pdf):
    /// the smaller of [`EDGE_ROUNDING`] and [`SLACK_PER_WIDTH`] of the width `Ω / P`,
    /// with the perimeter `P` from the chords of the unit vertex directions.
    #[cold]
    fn contains_with_slack(&self, dir: Vec3) -> bool {
        let count = super::stored_count(self.vertex_count, N);
        let mut perimeter = 0.0f32;
        for i in 0..count {
            let next = if i + 1 == count { 0 } else { i + 1 };
            perimeter += crate::math::length(self.vertices[next] - self.vertices[i]);
        }
        // `min` returns the number where the width is NaN (a corrupted value).
        let slack = EDGE_ROUNDING.min(SLACK_PER_WIDTH * (self.solid_angle / perimeter));
        self.contains_within(dir, slack)
    }

    /// Whether `dir` lies inside the polygon or outside by at most `tolerance` radians
    /// (approximately: the sine of the angle to each edge's great circle). With
    /// `tolerance = 0` this is [`contains`](Self::contains).
    #[inline]
    pub fn contains_within(&self, dir: Vec3, tolerance: f32) -> bool {
        let length = crate::math::length(dir);
        let mut inside = self.vertex_count > 0 && dir.is_finite() && length > 0.0;
        for i in 0..N {
            // Unused slots hold zero normals, whose dot product 0 passes.
            let n = self.edge_normals[i];
            inside &= self.edge_side(i, dir) >= -tolerance * crate::math::length(n) * length;
        }
        inside
    }

    /// `dir` against the plane of edge `i`: `(n_i + r_i) · dir`, positive inside. For the
    /// narrowest polygons (`checks_samples == 2`) with the residual `r_i` and a compensated dot
    /// product: near the boundary the three terms of `n_i · dir` nearly cancel, and their
    /// rounding, correlated along an edge, moved the boundary of a polygon of 8e-10 sr
    /// systematically (`∫ pdf dω` 0.99966 with exact planes and a plain dot product).
    #[inline(always)]
    fn edge_side(&self, i: usize, dir: Vec3) -> f32 {
        if self.checks_samples >= 2 {
            crate::math::dot_precise(self.edge_normals[i], dir) + self.edge_residuals[i].dot(dir)
        } else {
            self.edge_normals[i].dot(dir)
        }
    }

    /// The random numbers `u` for which [`sample`](Self::sample) returns `dir` (up to
    /// rounding), or `None` when `dir` is outside the polygon or the polygon is empty.
    pub fn invert(&self, dir: Vec3) -> Option<[f32; 2]> {
        self.invert_from(self.invert_in_triangle(dir)?)
    }

    /// [`invert`](Self::invert) for directions strictly inside (the plain edge test,
    /// without `pdf`'s slack), as [`sample_unchecked`](Self::sample_unchecked) draws
    /// them: for the warps whose `pdf` evaluates their density at the inverted primary
    /// sample (Hart et al.), which a direction outside would only reach clamped.
    pub(crate) fn invert_strictly_inside(&self, dir: Vec3) -> Option<[f32; 2]> {
        self.invert_from(self.invert_in_triangle_within(dir, 0.0)?)
    }

    /// The random numbers from a fan triangle, the solid angle from its first edge and
    /// `u1`, clamped into `[0, 1 - ulp]`.
    fn invert_from(&self, (k, local, u1): (usize, f32, f32)) -> Option<[f32; 2]> {
        let u0 = (self.start[k] + local) / self.solid_angle;
        Some([clamp_inverted(u0), clamp_inverted(u1)])
    }

    /// The fan triangle `k`, the solid angle `local` from its first edge and the `u1` at
    /// which [`sample_in_triangle`](Self::sample_in_triangle) returns `dir` (up to
    /// rounding), or `None` when `dir` is outside the polygon or the polygon is empty.
    pub(crate) fn invert_in_triangle(&self, dir: Vec3) -> Option<(usize, f32, f32)> {
        if !self.contains(dir) {
            return None;
        }
        self.invert_in_triangle_unchecked(dir)
    }

    /// [`invert_in_triangle`](Self::invert_in_triangle) for a `dir` inside or outside by
    /// at most `tolerance` radians (see [`contains_within`](Self::contains_within)); a
    /// direction outside maps to the nearest triangle and clamped coordinates.
    pub(crate) fn invert_in_triangle_within(
        &self,
        dir: Vec3,
        tolerance: f32,
    ) -> Option<(usize, f32, f32)> {
        if !self.contains_within(dir, tolerance) {
            return None;
        }
        self.invert_in_triangle_unchecked(dir)
    }

    /// The inversion for a finite, non-zero `dir` already tested to lie in the polygon.
    fn invert_in_triangle_unchecked(&self, dir: Vec3) -> Option<(usize, f32, f32)> {
        if self.selectable_triangles == 0 {
            return None;
        }
        let w = crate::math::normalize_scaled(dir);
        let apex = self.vertices[0];
        let count = super::stored_count(self.vertex_count, N);
        let selectable = super::stored_count(self.selectable_triangles, T);
        // Diagonal j runs from the apex to vertex j; w is on the inner side of diagonal
        // k + 1 and the outer side of diagonal k + 2 when it lies in fan triangle k.
        let orientation = self.orientation;
        let mut k = 0usize;
        for j in 2..count.saturating_sub(1) {
            k += (orientation * w.dot(apex.cross(self.vertices[j])) > 0.0) as usize;
        }
        let mut k = k.min(selectable.saturating_sub(1));
        // A fan triangle of zero solid angle (a vertex that clipping repeated) has no
        // inside: a direction assigned to it lies on a diagonal it shares with a
        // neighbour, which sampling would have used (`select_piece` skips empty pieces).
        // Inverting in the empty triangle gave ξ1 = 0 there, and the small-polygon
        // sampler's pdf of such a direction twice its value (issue 16, 9).
        if self.g0[k] == 0.0 {
            if k + 1 < selectable && self.g0[k + 1] > 0.0 {
                k += 1;
            } else if k > 0 && self.g0[k - 1] > 0.0 {
                k -= 1;
            }
        }
        let (v0, v1, v2) = (self.vertices[k + 1], apex, self.vertices[k + 2]);
        // v2' is where the great circle through the apex and w meets the edge v0 v2.
        let mut new_vertex = crate::math::normalize_or_zero(
            crate::math::cross_precise(v1, w).cross(crate::math::cross_precise(v0, v2)),
        );
        if new_vertex.dot(v0 + v2) < 0.0 {
            new_vertex = -new_vertex;
        }
        if new_vertex == Vec3::ZERO {
            // w is the apex itself (or the great circles coincide): ξ1 = 0.
            return Some((k, 0.0, 0.0));
        }
        // Solid angle of the sub-triangle (v0, v1, v2') by the same Householder form.
        let reflection = Householder::new(v1);
        let x = reflection.reflect_yz(v0 - v1);
        let y = reflection.reflect_yz(new_vertex - v1);
        let g0 = reflection.determinant(x, y).abs();
        let g1 = v0.dot(new_vertex) + v1.dot(new_vertex);
        let g2 = self.g2[k];
        let local = triangle_angle(g0, g2 + g1);
        // 1 - s = ξ1 (1 - s'), with 1 - a·b = |a - b|² / 2 for unit vectors.
        let u1 = (v1 - w).length_squared() / (v1 - new_vertex).length_squared();
        let u1 = clamp_inverted(u1);
        Some((k, local, u1))
    }
}

#[cfg(test)]
#[path = "solid_angle_tests.rs"]
mod tests;
