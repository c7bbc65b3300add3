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

use super::central_sectors::{
    CENTRAL_WORDS, CentralLanes, CentralSectors, both_groups_kept, lanes_kept,
};
use super::clip::{clip_to_upper_hemisphere, clipped_edge_planes, reverse_clipped_edge_planes};
use super::edge_normal_rows::EdgeNormalRows;
use super::ellipse::{
    DEGENERATE, dot2, ellipse_area, ellipse_from_normal, ellipse_from_normal4, is_degenerate,
    is_inner, unit_direction, unit_direction4,
};
use super::ellipse_sector::{AreaPrecision, EllipseSector, atan2_positive_fast4};
use super::small_projected::{SLIVER_EXTENT2, SMALL_EXTENT, SmallPolygonCosineSampler};
use super::sorting_networks::sort_bitonic;
use crate::math::{
    LANES, copy_sign, cross_precise4, difference_of_products4, lane_starts, load4, store4,
};
use crate::sample::{clamp_random, pad_unselectable, select_piece};
use crate::{MAX_POLYGON_VERTICES, Sample, Vec3};
use glam::Vec4;

/// Refinement iterations of the unbiased sampler. Algorithm 3 takes two from an initial
/// guess by two quads; here the initial guess comes from four quads (about four times
/// as accurate), and one iteration gives the same accuracy at the 99th percentile (see
/// the report's error table: forward error 2.4e-6 rad after one, 1.5e-6 after two) for
/// 60% of the cost. Sectors whose outer ellipse's area exceeds 200 times the sector's
/// area (ill-conditioned, near the polygon's azimuthal ends or the horizon) get a second
/// iteration, and so do sectors whose ellipses touch or nearly touch at an end (a vertex
/// on or just above the horizon at the polygon's azimuthal end; issue 17, 2). [`sample_with_iterations`](ProjectedPolygon::sample_with_iterations)
/// takes any count.
pub const REFINEMENT_ITERATIONS: u32 = 1;

/// Iterations are skipped for `ξ0` this close to 0 or 1, where the two tangent lines of
/// the iteration may meet near the solution (supplement A.3).
const ITERATION_MARGIN: f32 = 1e-5;

/// The most refinement iterations a decentral sample runs (the default runs 1 or 2):
/// larger requests are clamped. The iteration converges cubically (supplement A.5,
/// Proposition 6; a test beside the iteration measures the order in f64), so from the initial guess's error of a few
/// hundredths of a radian two or three iterations reach f32 precision, and 8 leave ample
/// room for slow starts (Proposition 6 is local).
pub const MAX_REFINEMENT_ITERATIONS: u32 = 8;

/// A convex polygon prepared for projected solid angle sampling: the first part of
/// Algorithm 4 (ellipses paired with sectors, sector areas).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectedPolygon {
    /// The sectors of Algorithm 4 in counter-clockwise order or, for small polygons, the
    /// warped solid angle sampler: one storage for either.
    pieces: ProjectedPieces,
    /// Projected solid angle (area in the disk) of each sector.
    pub(crate) sector_area: [f32; MAX_POLYGON_VERTICES],
    /// Projected solid angle of the sectors before each sector.
    pub(crate) sector_start: [f32; MAX_POLYGON_VERTICES],
    /// Inward edge plane normals of the clipped polygon, for the inside test of
    /// [`pdf`](Self::pdf) (zero in unused slots).
    edge_normals: EdgeNormalRows,
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
    /// The slack of `pdf` in the small case (radians; 0 otherwise): see
    /// `SmallPolygonCosineSampler::tolerance`.
    small_tolerance: f32,
}

/// What a prepared polygon samples from: the sectors of Algorithm 4 or, below
/// [`SMALL_EXTENT`], the small-polygon sampler (issue 15, 3: one storage for the two, which
/// are never used together, saves the small sampler's 548 bytes of every prepared value
/// and of every preparation's writes). Both are plain `f32` and `u32` words, so every bit
/// pattern of the storage is a value of either view: reading the view that preparation
/// did not write (possible only for a caller's corrupted struct) gives wrong numbers,
/// never undefined behaviour. Preparation writes every byte of the union (the small case
/// writes the empty sectors first), so no stale word is left in it.
///
/// The central case has a third view, [`CentralPieces`]: its sectors as rows of lanes
/// and zeros for the rest of the storage.
#[repr(C)]
#[derive(Clone, Copy)]
pub union ProjectedPieces {
    sectors: [EllipseSector; MAX_POLYGON_VERTICES],
    small: SmallPolygonCosineSampler,
    central: CentralPieces,
}

/// The words of the sectors' view after the central sectors' rows.
const CENTRAL_REST: usize =
    core::mem::size_of::<[EllipseSector; MAX_POLYGON_VERTICES]>() / 4 - CENTRAL_WORDS;

/// The central case's view of the storage: the sectors' rows, then words that the
/// central preparation writes as 0 (so that the whole storage is written, as in the other
/// cases). Exactly as large as the sectors' view (asserted below).
#[repr(C)]
#[derive(Clone, Copy)]
struct CentralPieces {
    sectors: CentralSectors,
    rest: [u32; CENTRAL_REST],
}

const _: () = assert!(
    core::mem::size_of::<CentralPieces>()
        == core::mem::size_of::<[EllipseSector; MAX_POLYGON_VERTICES]>()
);

// The sectors are the larger view, so that writing them writes the whole storage.
const _: () = assert!(
    core::mem::size_of::<[EllipseSector; MAX_POLYGON_VERTICES]>()
        >= core::mem::size_of::<SmallPolygonCosineSampler>()
);

impl ProjectedPieces {
    const EMPTY: Self = Self {
        sectors: [EllipseSector::EMPTY; MAX_POLYGON_VERTICES],
    };
}

impl ProjectedPieces {
    /// The sectors' view, for preparation to write (a method of the storage, not of the
    /// polygon, so that the polygon's other fields stay borrowable meanwhile).
    #[inline(always)]
    fn sectors_mut(&mut self) -> &mut [EllipseSector; MAX_POLYGON_VERTICES] {
        // SAFETY: every bit pattern is a valid value of this view (see above).
        unsafe { &mut self.sectors }
    }
}

impl ProjectedPieces {
    /// The central view's rows, for preparation to write; the rest of the storage is
    /// written as 0 first.
    #[inline(always)]
    fn central_mut(&mut self) -> &mut CentralSectors {
        // SAFETY: every bit pattern is a valid value of this view (plain f32/u32 words).
        let central = unsafe { &mut self.central };
        central.rest = [0; CENTRAL_REST];
        &mut central.sectors
    }
}

impl PartialEq for ProjectedPieces {
    /// Field by field over the sectors' view, which covers the whole storage.
    fn eq(&self, other: &Self) -> bool {
        // SAFETY: every bit pattern is a valid `[EllipseSector; 8]` (plain f32/u32).
        unsafe { self.sectors == other.sectors }
    }
}

impl core::fmt::Debug for ProjectedPieces {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        // SAFETY: as in `eq`.
        unsafe { self.sectors.fmt(f) }
    }
}

impl Default for ProjectedPolygon {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// `det(s_a, s_b)` of the unit directions of the vertex pairs `(a, b)` of the sectors,
/// from the positions, four at a time (bit for bit as
/// [`difference_of_products`](crate::math::difference_of_products) over the product of
/// the lengths `|p_xy|`); 0 where a vertex lies on the z axis (`xy_length` 0, whose 0 / 0
/// gave a NaN det; found by fuzzing).
#[inline(always)]
fn sector_determinants(
    positions: &[Vec3; MAX_POLYGON_VERTICES],
    xy_length: &[f32; MAX_POLYGON_VERTICES],
    pairs: &[(usize, usize)],
) -> [f32; 2 * LANES] {
    // Columns: x_a, y_b, y_a, x_b, |p_a,xy|, |p_b,xy|; lanes past the sectors stay 0.
    let mut columns = [[0.0f32; 2 * LANES]; 6];
    for (j, &(a, b)) in pairs.iter().enumerate() {
        let (pa, pb) = (positions[a], positions[b]);
        columns[0][j] = pa.x;
        columns[1][j] = pb.y;
        columns[2][j] = pa.y;
        columns[3][j] = pb.x;
        columns[4][j] = xy_length[a];
        columns[5][j] = xy_length[b];
    }
    let mut dets = [0.0f32; 2 * LANES];
    for first in lane_starts(pairs.len()) {
        let [xa, yb, ya, xb, la, lb] = columns.each_ref().map(|c| load4(c, first));
        let det = difference_of_products4(xa, yb, ya, xb) / (la * lb);
        store4(
            Vec4::select(det.is_finite_mask(), det, Vec4::ZERO),
            &mut dets,
            first,
        );
    }
    dets
}

/// The outer ellipse's area over a decentral sector, as the extra-iteration and sliver
/// tests define it: Equation (1) of Peters 2021 (supplement A.7),
/// `atan2(det, (s0 · s1 + t0 t1) / k) · (0.5 / k)` with `k = √|C| = sqrt(1 + |u|²)`.
/// Computed only where [`outer_area_bound`] does not settle a test.
#[inline(never)]
fn exact_outer_area(sector: &EllipseSector) -> f32 {
    ellipse_area(
        sector.outer,
        sector.det,
        dot2(sector.s0(), sector.s1()),
        sector.outer_dots()[0],
        sector.outer_dots()[1],
    )
}

/// The sum of [`exact_outer_area`] over the sectors in order (out of line, as it runs
/// only where [`outer_area_bound`] leaves the sliver test open).
#[inline(never)]
fn exact_outer_sum(sectors: &[EllipseSector]) -> f32 {
    let mut sum = 0.0f32;
    for sector in sectors {
        sum += exact_outer_area(sector);
    }
    sum
}

/// An upper bound on [`exact_outer_area`] without its arc tangent: `1.6 / k`. The angle
/// there is `atan2_upper_half_plane`, at most `fl(π/2 + fl(π/2)) = fl(π)` (`atanf` never
/// exceeds `fl(π/2)`, NaN gives 0), and `fl(π) · fl(0.5 / k) < 1.6 / k` with room for
/// the roundings, so the rounded product is at most `fl(1.6 / k)` (rounding is
/// monotone). A degenerate ellipse (`k = ∞`) gives 0, its area. The outer area of a
/// sector is rarely within a factor 200 of the area between the ellipses, and Φ rarely
/// below 3e-7 of the outer areas' sum over the sliver's extent², so the comparisons of
/// the decentral preparation against this bound settle almost every test without the
/// five or so `atanf` of the exact areas.
#[inline(always)]
fn outer_area_bound(sector: &EllipseSector) -> f32 {
    1.6 / sector.outer_root_det
}

/// A tighter upper bound on [`exact_outer_area`] where [`outer_area_bound`] leaves the
/// extra-iteration test open, without the arc tangent: `fl(fl(det / x) · fl(0.5 / k))`
/// from the same `x = fl((s0 · s1 + t0 t1) / k)` and `k` (the same operations as
/// `ellipse_area`, `det` clamped at 0 as there). Where `x > 0` the angle is
/// `atanf(fl(det / x))`, and `atanf(r) <= r` for every `r >= 0`: `atan r < r`, and
/// a faithful `atanf` rounds to a neighbour of `atan r`, which cannot pass the float `r`
/// (checked over every non-negative `f32` against `libm::atanf`, of which the inline
/// `atanf` gives the same bits). Rounding is monotone, so the exact area
/// `fl(angle · fl(0.5 / k))` is at most this product. Elsewhere (`x <= 0`, NaN: an angle
/// from `π/2` on) it gives ∞, which settles nothing. Narrow sectors (small `det`) are
/// where `1.6 / k` is loosest and this bound tightest: it settled (issue 15, stop 47)
/// most of the exact areas that the bench's decentral hexagons computed.
#[inline(always)]
fn outer_area_ratio_bound(sector: &EllipseSector) -> f32 {
    let k = sector.outer_root_det;
    let [t0, t1] = sector.outer_dots();
    let x = (dot2(sector.s0(), sector.s1()) + t0 * t1) / k;
    if x > 0.0 {
        (sector.det.max(0.0) / x) * (0.5 / k)
    } else {
        f32::INFINITY
    }
}

/// Lanes of the vertices: one per vertex, read four at a time from slot 0 and slot 1.
const VERTEX_SLOTS: usize = 2 * LANES + 1;

/// The counts that [`SLOT_VERTEX`] has rows for: a power of two above the largest, so that
/// `count & (SLOT_VERTEX_COUNTS - 1)` is in bounds without a check (rows of counts below 3
/// and above 8 are never read).
const SLOT_VERTEX_COUNTS: usize = 2 * MAX_POLYGON_VERTICES;

/// The vertex in each slot of [`vertex_rows`], by order (`[1]` clockwise) and count:
/// vertex j (`count - 1 - j` clockwise) in slot j < count, the first slot's vertex in the
/// others. A table, where the index computed per slot was a comparison and two selections.
const SLOT_VERTEX: [[[u8; VERTEX_SLOTS]; SLOT_VERTEX_COUNTS]; 2] = {
    let mut table = [[[0u8; VERTEX_SLOTS]; SLOT_VERTEX_COUNTS]; 2];
    let mut count = 1;
    while count <= MAX_POLYGON_VERTICES {
        let mut j = 0;
        while j < VERTEX_SLOTS {
            let k = if j < count { j } else { 0 };
            table[0][count][j] = k as u8;
            table[1][count][j] = (count - 1 - k) as u8;
            j += 1;
        }
        count += 1;
    }
    table
};

/// The vertex lanes of `prepare_or_fail`: in the first rows (x, y, z) slot j holds vertex j
/// (vertex `count - 1 - j` of a clockwise polygon, `counter_clockwise`'s order) and the
/// slots from `count` on the first slot's vertex again; the second rows hold slot j + 1's
/// vertex in slot j (the last slot, which has no successor, the first vertex too).
///
/// Each group of four slots is gathered in registers and written with one 16-byte store
/// per row, and the rows from slot 1 are their own rows: written slot by slot (4-byte
/// stores), the rows were read back at once by 16-byte loads, from slot 1 across two
/// groups, which the store buffer cannot forward from the narrower stores (each such
/// load waited for the stores to reach the cache, on the preparation's critical path).
/// Reads of whole groups of these rows match their stores.
#[inline(always)]
fn vertex_rows(
    positions: &[Vec3; MAX_POLYGON_VERTICES],
    count: usize,
    reversed: bool,
) -> [[[f32; VERTEX_SLOTS]; 3]; 2] {
    // Each row's lanes gathered straight from the positions (built in a temporary array,
    // the lanes were themselves read back by a 16-byte load from narrower stores), the
    // position of each slot from the table (`& 7` only shows the compiler the indices in
    // bounds: they are below `count`).
    // The table's row chosen by a branch on the order, not indexed by it: indexed, every
    // gather waited for the orientation (the rescaled vertices' fan sums and their dot
    // product) before its first load, which put that whole sum on the preparation's
    // critical path; a branch is predicted (a light's polygons come in one order, as
    // seen from the side it faces) and the gathers start with the positions (issue 15:
    // central hexagons 237 -> 224 ns in the default build, the instructions alike).
    let slots = if reversed {
        &SLOT_VERTEX[1][count & (SLOT_VERTEX_COUNTS - 1)]
    } else {
        &SLOT_VERTEX[0][count & (SLOT_VERTEX_COUNTS - 1)]
    };
    let index = |j: usize| usize::from(slots[j]) & (MAX_POLYGON_VERTICES - 1);
    let group = |first: usize| -> [Vec4; 3] {
        let [i0, i1, i2, i3] = [first, first + 1, first + 2, first + 3].map(index);
        let (p0, p1, p2, p3) = (positions[i0], positions[i1], positions[i2], positions[i3]);
        [
            Vec4::new(p0.x, p1.x, p2.x, p3.x),
            Vec4::new(p0.y, p1.y, p2.y, p3.y),
            Vec4::new(p0.z, p1.z, p2.z, p3.z),
        ]
    };
    let (low, high) = (group(0), group(LANES));
    let last = positions[index(2 * LANES)].to_array();
    let mut rows = [[[0.0f32; VERTEX_SLOTS]; 3]; 2];
    for c in 0..3 {
        let (low, high, last) = (low[c], high[c], last[c]);
        let [vertex, next] = &mut rows;
        store4(low, &mut vertex[c], 0);
        store4(high, &mut vertex[c], LANES);
        vertex[c][2 * LANES] = last;
        store4(Vec4::new(low.y, low.z, low.w, high.x), &mut next[c], 0);
        store4(Vec4::new(high.y, high.z, high.w, last), &mut next[c], LANES);
        next[c][2 * LANES] = last;
    }
    rows
}

/// The ends of a clipped polygon's edge planes as lanes, `[end][c][j]`: coordinate c of
/// end `end` of edge j's plane (`planes[j]`, zeros past the polygon as there, and in the
/// last slot), for the edge planes and the short-edge test of `prepare_or_fail`.
///
/// Each group of four slots is gathered in registers and written with one 16-byte store
/// per row, as in [`vertex_rows`]: written one float at a time, the rows were read back
/// at once by the 16-byte loads of the edge planes, which the store buffer cannot forward
/// from the narrower stores (issue 15: the clipped path's regression of stop 45). Every
/// slot is gathered, whatever the count: the planes past the polygon are zeros. Out of
/// line: only clipped polygons take it, and in line it moved the code of the unclipped
/// paths (central hexagons about 10 ns slower, straddling ones 23 instructions more).
#[inline(never)]
fn clipped_end_rows(planes: &[[Vec3; 2]; MAX_POLYGON_VERTICES]) -> [[[f32; VERTEX_SLOTS]; 3]; 2] {
    let mut rows = [[[0.0f32; VERTEX_SLOTS]; 3]; 2];
    for first in [0, LANES] {
        for (end, rows) in rows.iter_mut().enumerate() {
            let [p0, p1, p2, p3] = [0, 1, 2, 3].map(|i| planes[first + i][end]);
            store4(Vec4::new(p0.x, p1.x, p2.x, p3.x), &mut rows[0], first);
            store4(Vec4::new(p0.y, p1.y, p2.y, p3.y), &mut rows[1], first);
            store4(Vec4::new(p0.z, p1.z, p2.z, p3.z), &mut rows[2], first);
        }
    }
    rows
}

/// `Σ (p_k - p_0) × (p_k+1 - p_0)` over the fan triangles `k = from..count - 1` of the
/// vertices `lanes(k)` (in the lanes `(x, y, z, 0)`, `apex` = `lanes(0)`), added to
/// `sum` in order, each term rounded as `cross3_lanes` rounds it: the orientation's area
/// vector, from either vertex source of `prepare_or_fail`.
#[inline(always)]
fn fan_cross_sum(
    lanes: impl Fn(usize) -> Vec4,
    count: usize,
    from: usize,
    apex: Vec4,
    mut sum: Vec4,
) -> Vec4 {
    let mut previous = lanes(from) - apex;
    for k in from..count - 1 {
        let next = lanes(k + 1) - apex;
        sum += crate::math::cross3_lanes(previous, next);
        previous = next;
    }
    sum
}

/// `sort_bitonic` with the decentral preparation's careful comparator, out of line: it
/// runs only where [`sort_by_certain_azimuths`] cannot decide (and in the careful path).
#[inline(never)]
fn sort_carefully(
    order: &mut [u8; MAX_POLYGON_VERTICES],
    count: usize,
    less: impl Fn(&u8, &u8) -> bool,
) {
    sort_bitonic(order, count, less);
}

/// The azimuth order of the decentral case with a cheap comparator, where it gives the
/// same answers as the careful one (issue 15: the careful comparator, a branchy
/// determinant with a tie rule, was most of the sort's 460 instructions per hexagon).
///
/// The comparator of the decentral preparation is `less(a, b)`: the sign of
/// `difference_of_products_sign(a_x, b_y, a_y, b_x)` = det(p_a,xy, p_b,xy), with ties
/// broken by the degenerate ellipses. Where the plain difference `fl(fl(a_x b_y) -
/// fl(a_y b_x))` passes that function's test (its sign is certain), the function returns
/// it, and it is not 0 (the test asks for at least 2⁻¹⁰⁰), so there is no tie and
/// `less(a, b)` is `plain > 0`. This comparator computes only that plain difference and
/// its test, without branches, and records whether any comparison failed the test. When
/// none did, every comparison of the network (the same code, `sort_bitonic`) had the
/// careful comparator's answer, so it made the same swaps and the order is the same, bit
/// for bit, whether or not the sequence is bitonic. Otherwise (a pair nearly collinear
/// with the zenith, a vertex on the z axis) this returns `false`, and the caller sorts
/// the identity again with the careful comparator.
///
/// The test `certain_azimuth_order_matches_the_network` pins which polygons come here
/// and compares the orders.
///
/// Out of line: in a function this small the network and the comparator are inlined
/// (inside the preparation they were calls, one per comparison).
#[inline(never)]
fn sort_by_certain_azimuths(
    order: &mut [u8; MAX_POLYGON_VERTICES],
    vertex: &[[f32; VERTEX_SLOTS]; 3],
    count: usize,
) -> bool {
    let uncertain = core::cell::Cell::new(false);
    let [xs, ys, _] = vertex;
    #[inline(always)]
    fn less(
        xs: &[f32; VERTEX_SLOTS],
        ys: &[f32; VERTEX_SLOTS],
        uncertain: &mut bool,
        a: u8,
        b: u8,
    ) -> bool {
        // `& 7` only shows the compiler the index in bounds (entries are below 8).
        let (a, b) = (usize::from(a & 7), usize::from(b & 7));
        // `difference_of_products_sign(a_x, b_y, a_y, b_x)`'s plain branch and its test.
        let (p1, p2) = (xs[a] * ys[b], ys[a] * xs[b]);
        let plain = p1 - p2;
        *uncertain |= !crate::math::plain_difference_is_certain(p1, p2, plain);
        plain > 0.0
    }
    sort_bitonic(order, count, |a: &u8, b: &u8| {
        let mut flag = uncertain.get();
        let less = less(xs, ys, &mut flag, *a, *b);
        uncertain.set(flag);
        less
    });
    !uncertain.get()
}

/// The decentral preparation's `edge_dot(e, c)` (`u_e · s_c` from the positions) of
/// every edge at its own two vertices: `[0][e]` at `c = e`, `[1][e]` at `c = e + 1`
/// (vertex 0 after the last), four edges at a time and bit for bit as `edge_dot`
/// computes them one by one. For an edge's own vertex the triple product
/// `det(p_a, p_b, p_c)` vanishes and `edge_dot` takes it as 0, so
/// `t = σ (0 - n_z p_z) / (n_z |p_xy|)` with `σ` the sign of `n_x`, and 0 where the
/// ellipse is degenerate, where `|p_xy|` is not positive and where `t` is not finite,
/// as there. Most of a decentral polygon's dot products are of this kind (each sector
/// asks for four, and only a vertex of the other chain than the ellipse's, inside its
/// azimuths, is not one of its own): a table of them leaves `edge_dot` itself the few
/// others (issue 15: sixteen calls per hexagon, 625 instructions, were the largest part
/// of the sectors' setup). `decentral_lanes_match_the_scalar_sectors` compares the
/// prepared values with those of the scalar path, which calls `edge_dot` for all.
#[inline(always)]
fn own_edge_dots(
    [vertex, next]: [&[[f32; VERTEX_SLOTS]; 3]; 2],
    normals: &[[f32; 2 * LANES]; 3],
    ux: &[f32; MAX_POLYGON_VERTICES],
    xy_length: &[f32; MAX_POLYGON_VERTICES],
    count: usize,
) -> [[f32; 2 * LANES]; 2] {
    // `|p_xy|` of each edge's two ends by group, in registers: `[0]` slot j's, `[1]` slot
    // j + 1's (slot `count` the first vertex again). `xy_length` holds slot j's in slot j,
    // stored a group of four at a time from the vertex lanes, whose slots from `count` on
    // hold the first vertex: there it is the first vertex's, bit for bit (the same lane
    // operations on the same values), and so is every lane of a group past the polygon
    // (not computed: the first lane splatted) and the last slot. Copied into a row of
    // slots one float at a time and read back at once by 16-byte loads (from slot 1
    // across two groups), the lengths waited for the copy to reach the cache (the store
    // buffer cannot forward a wider load from narrower stores). The `z` of the other end
    // likewise from `next`, the vertex lanes from slot 1 stored as rows of their own.
    let low = load4(xy_length, 0);
    let high = if count > LANES {
        load4(xy_length, LANES)
    } else {
        Vec4::splat(low.x)
    };
    let next_low = Vec4::new(low.y, low.z, low.w, high.x);
    let next_high = Vec4::new(high.y, high.z, high.w, low.x);
    let mut dots = [[0.0f32; 2 * LANES]; 2];
    for first in lane_starts(count) {
        let (nx, nz) = (load4(&normals[0], first), load4(&normals[2], first));
        // σ: 1 with the sign bit of n_x (`copysign` moves the bit, as `copy_sign`).
        let sigma = Vec4::ONE.copysign(nx);
        // `is_degenerate`: not |u_x| <= the limit (NaN included).
        let proper = load4(ux, first)
            .abs()
            .cmple(Vec4::splat(super::ellipse::ELLIPSE_LIMIT));
        let dot = |z: Vec4, xy: Vec4| {
            let t = sigma * (Vec4::ZERO - nz * z) / (nz * xy);
            let keep = proper & xy.cmpgt(Vec4::ZERO) & t.is_finite_mask();
            Vec4::select(keep, t, Vec4::ZERO)
        };
        let [start, end] = if first == 0 {
            [low, next_low]
        } else {
            [high, next_high]
        };
        store4(dot(load4(&vertex[2], first), start), &mut dots[0], first);
        store4(dot(load4(&next[2], first), end), &mut dots[1], first);
    }
    dots
}

/// `edge_dot(e, c)` from the table of [`own_edge_dots`] where `c` is one of the edge's
/// own vertices `e` and `next_e` (`None` elsewhere, or without the table).
#[inline(always)]
fn own_edge_dot(
    own: &Option<[[f32; 2 * LANES]; 2]>,
    e: usize,
    next_e: usize,
    c: usize,
) -> Option<f32> {
    let own = own.as_ref()?;
    if c == e {
        Some(own[0][e])
    } else if c == next_e {
        Some(own[1][e])
    } else {
        None
    }
}

/// The first `count` positions in counter-clockwise order: reversed where `reversed`
/// (the polygon winds clockwise; slots from `count` on are left as they are). The
/// preparation reverses them only on the paths that read them (see `prepare_or_fail`).
#[inline(always)]
fn counter_clockwise(positions: &mut [Vec3; MAX_POLYGON_VERTICES], count: usize, reversed: bool) {
    if reversed {
        positions[..count].reverse();
    }
}

/// [`counter_clockwise`] out of line, for the rare paths (small polygons, short edges),
/// so that the general path keeps its own copy inline.
#[inline(never)]
#[cold]
fn counter_clockwise_cold(
    positions: &mut [Vec3; MAX_POLYGON_VERTICES],
    count: usize,
    reversed: bool,
) {
    counter_clockwise(positions, count, reversed);
}

/// The central case of Algorithm 4 for an unclipped polygon whose edges are all outer and
/// none degenerate (`n_z > 0` for every edge plane `n = p_j × p_j+1`, so no vertex lies
/// on the z axis): the common case, four edges and sectors at a time straight from the
/// vertex lanes, bit for bit as the general path computes them one by one
/// (`ellipse_from_normal`, `unit_direction`, `sector_determinants`, the `edge_dot` of an
/// edge's own vertices and the sector constants). The test
/// `central_fast_path_matches_the_general_path` pins which polygons come here and
/// compares the prepared values bit for bit.
///
/// Writes the edge normals, the sectors `0..count` and every slot's area (0 in the
/// second group of four when `count <= 4`) and marks the polygon central; returns whether an edge may be short (the
/// first test of `ignore_short_edges_in_containment`); `central_starts` takes the areas
/// from there.
#[inline(always)]
fn central_unclipped_sectors(
    polygon: &mut ProjectedPolygon,
    [vertex, next]: [&[[f32; VERTEX_SLOTS]; 3]; 2],
    normals: &[[f32; 2 * LANES]; 3],
    count: usize,
    precision: AreaPrecision,
) -> bool {
    polygon.central = 1;
    let central = polygon.pieces.central_mut();
    let mut maybe_short = false;
    let limit = Vec4::splat(super::ellipse::ELLIPSE_LIMIT);
    // Per vertex, four at a time: `unit_direction` (n_z > 0 leaves no vertex on the z
    // axis), `|p_xy|` as `dot2(s, p_xy)` and `|p|²` as `length_squared`. Vertex j is
    // the s0 of sector j and the s1 of sector j - 1: computed once per vertex (the
    // same operations on the same coordinates, so the same bits in either role) where
    // each sector computed both of its ends (issue 15: two divisions, a square root and
    // a division per four vertices fewer).
    let groups = count.div_ceil(LANES);
    let mut per_vertex = [[Vec4::ZERO; 4]; 2];
    for (g, lanes) in per_vertex.iter_mut().enumerate().take(groups) {
        let [x, y, z] = vertex.each_ref().map(|c| load4(c, g * LANES));
        let largest = x.abs().max(y.abs());
        let (sx, sy) = (x / largest, y / largest);
        let inverse_length = Vec4::ONE / crate::math::sqrt4(sx * sx + sy * sy);
        let (sx, sy) = (sx * inverse_length, sy * inverse_length);
        *lanes = [sx, sy, sx * x + sy * y, (x * x + y * y) + z * z];
    }
    for (g, this) in per_vertex.iter().enumerate().take(groups) {
        let first = g * LANES;
        // The other end of each sector, vertex j + 1: this group's lanes moved down by
        // one, and into the last lane the first lane of the next group or, after the
        // last group, of the first (vertex 0, which follows the polygon's last vertex;
        // the padding slots from `count` on hold vertex 0 too, so every lane of sector
        // j < count gets vertex j + 1 or 0, as the vertex lanes from slot first + 1).
        let following = &per_vertex[if g + 1 < groups { g + 1 } else { 0 }];
        let [s1x, s1y, lb, b2] = core::array::from_fn(|i| {
            let (v, w) = (this[i], following[i]);
            Vec4::new(v.y, v.z, v.w, w.x)
        });
        let [s0x, s0y, la, a2] = *this;
        let (az, bz) = (load4(&vertex[2], first), load4(&next[2], first));
        let [nx, ny, nz] = normals.each_ref().map(|c| load4(c, first));
        // `ellipse_from_normal` for n_z > 0: u_x = |n_x| / n_z (an outer ellipse, sign bit
        // clear), u_y = n_y / n_z with the sign of n_x multiplied in (copying a sign to 1
        // and multiplying by it flips only the sign bit), both clamped to ELLIPSE_LIMIT.
        let inverse = Vec4::ONE / nz;
        let ux = (nx.abs() * inverse).min(limit);
        let uy = ny * Vec4::ONE.copysign(nx) * inverse;
        let uy = uy.abs().min(limit).copysign(uy);
        // `sector_determinants`: det(p_a,xy, p_b,xy) is n_z (the same Kahan difference of
        // products), over the product of the lengths.
        let det = nz / (la * lb);
        let det = Vec4::select(det.is_finite_mask(), det, Vec4::ZERO);
        // `edge_dot` at the edge's own vertices, where the triple product is 0:
        // t = σ (0 - n_z p_z) / (n_z |p_xy|), 0 where not finite.
        let sigma = Vec4::ONE.copysign(nx);
        let edge_dot = |z: Vec4, length: Vec4| {
            let t = sigma * (Vec4::ZERO - nz * z) / (nz * length);
            Vec4::select(t.is_finite_mask(), t, Vec4::ZERO)
        };
        let (t0, t1) = (edge_dot(az, la), edge_dot(bz, lb));
        // The first test of `ignore_short_edges_in_containment`, as `length_squared`.
        let short = !((nx * nx + ny * ny) + nz * nz)
            .cmpgt(Vec4::splat(super::SHORT_EDGE_SINE * super::SHORT_EDGE_SINE) * (a2 * b2));
        let lanes = (count - first).min(LANES);
        maybe_short |= short.bitmask() & ((1u32 << lanes) - 1) != 0;
        // The sector constants, as in the general central path.
        let root_det = crate::math::sqrt4(Vec4::ONE + (ux * ux + uy * uy));
        let cosine = s0x * s1x + s0y * s1y;
        let x = (cosine + t0 * t1) / root_det;
        let y = det.max(Vec4::ZERO);
        let half_inverse_k = Vec4::splat(0.5) / root_det;
        let sectors = CentralLanes {
            s0: [s0x, s0y],
            s1: [s1x, s1y],
            det,
            outer: [ux, uy],
            outer_dots: [t0, t1],
            root_det,
        };
        // The rows and the edge normals (slots past the polygon 0, as in
        // `EdgeNormalRows::ZERO`) of this group, stored before the arc tangent of the
        // areas, which needs most of the registers: stored after it, the lanes that the
        // rows take from here were spilled to the stack across it and reloaded (issue
        // 15: 26 fewer stack stores and loads per hexagon, as many register copies
        // more; the time alike). A group of four sectors stores its lanes without masks
        // (a constant mask, folded away: thirteen fewer operations); the last group of
        // a polygon whose count is not a multiple of four masks the lanes past it
        // (the areas past the polygon are masked to 0 below).
        #[inline(always)]
        fn store_group(
            central: &mut CentralSectors,
            edge_normals: &mut EdgeNormalRows,
            first: usize,
            keep: glam::BVec4A,
            sectors: &CentralLanes,
            half_inverse_k: Vec4,
            normal: [Vec4; 3],
        ) {
            central.store_with_half_inverse(first, keep, sectors, half_inverse_k);
            edge_normals.store4(first, normal, keep);
        }
        let normal = [nx, ny, nz];
        // The same call in both branches on purpose: in the first, `keep` is a constant
        // (all true) and the masks fold away, for every group but a partial last one.
        if lanes == LANES {
            let keep = glam::BVec4A::splat(true);
            store_group(
                central,
                &mut polygon.edge_normals,
                first,
                keep,
                &sectors,
                half_inverse_k,
                normal,
            );
        } else {
            let keep = lanes_kept(first, count);
            store_group(
                central,
                &mut polygon.edge_normals,
                first,
                keep,
                &sectors,
                half_inverse_k,
                normal,
            );
        }
        let angle = match precision {
            AreaPrecision::Exact => crate::math::atan2_upper_half_plane4(y, x, count - first),
            AreaPrecision::Fast => atan2_positive_fast4(y, x),
        };
        let area = (angle * half_inverse_k).max(Vec4::ZERO);
        store4(area, &mut polygon.sector_area, first);
    }
    if count <= LANES {
        central.store_zeros(LANES);
        let zero = [Vec4::ZERO; 3];
        polygon
            .edge_normals
            .store4(LANES, zero, glam::BVec4A::splat(true));
        store4(Vec4::ZERO, &mut polygon.sector_area, LANES);
    }
    maybe_short
}

/// `finish`'s sectors' starts and Φ from the areas of the central fast path as lanes
/// (as `central_unclipped_sectors` stored them; the slots past the polygon are written
/// as 0 here), bit for bit as
/// `finish`'s loop over the stored areas: the starts `Σ_{i<j} area_i` and the total
/// summed in the same order from `0.0`, `selectable_sectors` the index after the last
/// positive area (from a mask of the lanes, where the loop read every area back from
/// memory with a branch) and the starts from there on `+∞` (`pad_unselectable`), written
/// with one 16-byte store per group. The lanes past the polygon add `+0`, which leaves
/// every sum unchanged (the sum is never `-0`: it starts from `+0` and adds areas that
/// are `+0` or positive, `max(0)` having removed `-0` and NaN), so a group is summed
/// whole; the second group only for more than four sectors (with four or fewer, its
/// starts are all past the selectable ones). Returns Φ.
#[inline(always)]
fn central_starts(polygon: &mut ProjectedPolygon, count: usize) -> f32 {
    // The lanes past the polygon as 0 (as `finish` writes them), masked here where the
    // areas' loop masked its last group (and moved the code of the loop: 25 instructions
    // more per group). 16-byte loads and stores of the 16-byte stores of
    // `central_unclipped_sectors` (forwarded).
    let kept = both_groups_kept(count);
    let areas: [Vec4; 2] = core::array::from_fn(|g| {
        let first = g * LANES;
        let area = load4(&polygon.sector_area, first);
        let area = Vec4::select(kept[g], area, Vec4::ZERO);
        store4(area, &mut polygon.sector_area, first);
        area
    });
    let positive =
        areas[0].cmpgt(Vec4::ZERO).bitmask() | areas[1].cmpgt(Vec4::ZERO).bitmask() << LANES;
    let selectable = u32::BITS - positive.leading_zeros();
    polygon.selectable_sectors = selectable;
    // Each lane's start and the running total, in slot order.
    let prefix = |lanes: Vec4, total: &mut f32| {
        let area = lanes.to_array();
        let mut start = [0.0f32; LANES];
        for (start, area) in start.iter_mut().zip(area) {
            *start = *total;
            *total += area;
        }
        Vec4::from_array(start)
    };
    let mut total = 0.0f32;
    let low = prefix(areas[0], &mut total);
    // (With four sectors or fewer, the second group's starts are all unselectable.)
    let high = if count > LANES {
        prefix(areas[1], &mut total)
    } else {
        Vec4::ZERO
    };
    let selectable_lanes = both_groups_kept(selectable as usize);
    for (g, starts) in [low, high].into_iter().enumerate() {
        let starts = Vec4::select(selectable_lanes[g], starts, Vec4::splat(f32::INFINITY));
        store4(starts, &mut polygon.sector_start, g * LANES);
    }
    // Φ as the start of slot `count` where the polygon leaves one in its last group: the
    // same sum (the lanes after it add `+0`, which changes no bit, as above), a branch on
    // the count (predicted: a light keeps its count) rather than the adds of the `+0`
    // lanes, which put two more additions (hexagons) on the preparation's critical path,
    // from the areas to Φ and on to the sample, which starts from Φ.
    match count {
        3 => low.w,
        5 => high.y,
        6 => high.z,
        7 => high.w,
        _ => total,
    }
}

/// What `finish` reads besides the positions: the vertex count, the extent of the
/// small-polygon test (the largest sin² of the angle between the first vertex and
/// another) and whether the small-polygon sampler may take over.
#[derive(Clone, Copy)]
struct FinishInputs {
    count: usize,
    extent2: f32,
    allow_small: bool,
}

impl ProjectedPolygon {
    /// The state of a polygon that could not be prepared: samples have `pdf == 0`, and the
    /// pdf of every direction is 0.
    pub const EMPTY: Self = Self {
        pieces: ProjectedPieces::EMPTY,
        sector_area: [0.0; MAX_POLYGON_VERTICES],
        sector_start: [0.0; MAX_POLYGON_VERTICES],
        edge_normals: EdgeNormalRows::ZERO,
        projected_solid_angle: 0.0,
        density: 0.0,
        selectable_sectors: 0,
        central: 0,
        is_small: 0,
        small_tolerance: 0.0,
    };

    /// The sectors (not meaningful for a polygon that uses the small-polygon sampler).
    #[inline(always)]
    pub(crate) fn sectors(&self) -> &[EllipseSector; MAX_POLYGON_VERTICES] {
        // SAFETY: every bit pattern of the storage is a valid value of this view (see
        // `ProjectedPieces`).
        unsafe { &self.pieces.sectors }
    }

    /// The central case's sectors (meaningful only when `central` is 1 and `is_small` 0).
    #[inline(always)]
    pub(crate) fn central_sectors(&self) -> &CentralSectors {
        // SAFETY: as in `sectors`.
        unsafe { &self.pieces.central.sectors }
    }

    /// Sector `j` (below 8) as an [`EllipseSector`], from either case's storage (not
    /// meaningful for a polygon that uses the small-polygon sampler): the central case
    /// rebuilds it from its rows.
    #[inline(always)]
    pub(crate) fn sector(&self, j: usize) -> EllipseSector {
        if self.central != 0 {
            self.central_sectors().sector(j)
        } else {
            self.sectors()[j]
        }
    }

    /// The small-polygon sampler (meaningful only when `is_small` is 1).
    #[inline(always)]
    fn small(&self) -> &SmallPolygonCosineSampler {
        // SAFETY: as in `sectors`.
        unsafe { &self.pieces.small }
    }

    #[inline(always)]
    fn small_mut(&mut self) -> &mut SmallPolygonCosineSampler {
        // SAFETY: as in `sectors`.
        unsafe { &mut self.pieces.small }
    }

    /// Prepares the convex polygon with the given vertices (positions relative to the
    /// shading point in the local frame, not normalised, either winding, 3 to 8 of them).
    /// The part below the horizon is clipped away.
    ///
    /// Returns `None` for fewer than 3 or more than 8 vertices, 8 vertices that need
    /// clipping (9 would result), non-finite coordinates, a polygon with nothing above the
    /// horizon, and a zero projected solid angle (for example when the shading point lies
    /// in the polygon's plane, decided exactly for vertices exactly in such a plane).
    ///
    /// [`prepare`](Self::prepare) does the same in place.
    #[must_use]
    pub fn new(vertices: &[Vec3]) -> Option<Self> {
        let mut polygon = Self::EMPTY;
        polygon.prepare(vertices).then_some(polygon)
    }

    /// [`new`](Self::new) with a fast `atan` for the sector areas (relative error below
    /// 1.4e-4 per sector), for the biased variant [`sample_fast`](Self::sample_fast).
    /// **Biased**: the projected solid angle, and with it the pdf, is off by up to 1.4e-4
    /// relative. Prepared for `sample_fast` (and `pdf`): the unbiased sampler's extra
    /// iteration of ill-conditioned sectors is not decided (see `extra_iterations`).
    #[must_use]
    pub fn new_fast_biased(vertices: &[Vec3]) -> Option<Self> {
        let mut polygon = Self::EMPTY;
        polygon.prepare_fast_biased(vertices).then_some(polygon)
    }

    /// The sectors of Algorithm 4 without the switch to the small-polygon sampler, in
    /// place, for the baseline of Arvo that shares them.
    pub(crate) fn prepare_sectors_only(&mut self, vertices: &[Vec3]) -> bool {
        self.prepare_with(vertices, AreaPrecision::Exact, false)
    }

    /// [`new`](Self::new) in place: writes the prepared polygon into `self` and returns
    /// `true`, or writes [`EMPTY`](Self::EMPTY) and returns `false` where `new` returns
    /// `None`. Every field that sampling and `pdf` read is written, whatever `self` held
    /// before, and the prepared value (2288 bytes) is never copied.
    pub fn prepare(&mut self, vertices: &[Vec3]) -> bool {
        self.prepare_with(vertices, AreaPrecision::Exact, true)
    }

    /// [`new_fast_biased`](Self::new_fast_biased) in place, as [`prepare`](Self::prepare).
    /// **Biased.**
    pub fn prepare_fast_biased(&mut self, vertices: &[Vec3]) -> bool {
        self.prepare_with(vertices, AreaPrecision::Fast, true)
    }

    /// The in-place preparation: the empty value on failure.
    fn prepare_with(
        &mut self,
        vertices: &[Vec3],
        precision: AreaPrecision,
        allow_small: bool,
    ) -> bool {
        let prepared = self.prepare_or_fail(vertices, precision, allow_small, true, &mut false);
        super::keep_or_empty(self, prepared, Self::EMPTY)
    }

    /// [`prepare_with`](Self::prepare_with) with the central fast path allowed or not,
    /// for the test that compares the two paths; returns whether the fast path ran.
    #[cfg(test)]
    pub(crate) fn prepare_choosing_path(
        &mut self,
        vertices: &[Vec3],
        precision: AreaPrecision,
        allow_fast: bool,
    ) -> (bool, bool) {
        let mut took_fast = false;
        let prepared = self.prepare_or_fail(vertices, precision, true, allow_fast, &mut took_fast);
        (super::keep_or_empty(self, prepared, Self::EMPTY), took_fast)
    }

    /// The body of [`prepare_with`](Self::prepare_with); on `false`, `self` holds partial
    /// values. `allow_fast` permits the central fast path (`central_unclipped_sectors`),
    /// and `took_fast` tells whether it ran (both for the test that compares the paths).
    #[inline(always)]
    fn prepare_or_fail(
        &mut self,
        vertices: &[Vec3],
        precision: AreaPrecision,
        allow_small: bool,
        allow_fast: bool,
        took_fast: &mut bool,
    ) -> bool {
        let count = vertices.len();
        if !(3..=MAX_POLYGON_VERTICES).contains(&count) {
            return false;
        }
        let mut positions = [Vec3::ZERO; MAX_POLYGON_VERTICES];
        // A polygon wholly above the horizon (the common case) is its own clipped polygon
        // (clipping would return it unchanged) and its edges are their own planes.
        let Some((above, factor)) = super::rescale_above_the_horizon(vertices, &mut positions)
        else {
            return false;
        };
        // Vertex k rescaled, as the lanes `(x, y, z, 0)`: `positions[k]` bit for bit (the
        // same product per coordinate), formed from the input. Read back from `positions`
        // right after their 8- and 4-byte stores, the vertices came with 16-byte loads
        // across those stores (the compiler's), which the store buffer cannot forward:
        // each waited for the stores to reach the cache.
        let rescaled = |k: usize| Vec4::from((vertices[k], 0.0)) * factor;
        // The first fan triangle, shared by the plane test and (nothing clipped) the
        // orientation below: where its determinant clears the noise (almost always), the
        // polygon is off the plane and the whole test is not called (issue 15: the call
        // formed this triangle again, about 90 instructions per preparation).
        let first_apex = rescaled(0);
        let first_fan = [1, 2].map(|k| rescaled(k) - first_apex);
        let first_cross = crate::math::cross3_lanes(first_fan[0], first_fan[1]);
        if !super::fan_triangle_leaves_the_plane(
            first_apex,
            first_fan[0],
            first_fan[1],
            first_cross,
        ) && super::lies_in_a_plane_through_the_shading_point(&positions[..count])
        {
            return false;
        }
        let was_clipped = !above;
        // (None where not clipped: not even zeros are written.)
        let mut planes = None;
        let mut count = count;
        if was_clipped {
            let input = positions;
            count = clip_to_upper_hemisphere(&mut positions, count);
            if count < 3 {
                return false;
            }
            // The plane of each clipped edge from the input edge it lies on (exact), not
            // from the rounded horizon points.
            planes = Some(clipped_edge_planes(
                &input[..vertices.len()],
                &positions[..count],
            ));
        }
        // Orientation: the sign of Σ det(p0, pk, pk+1) = p0 · Σ (pk - p0) × (pk+1 - p0),
        // positive when the polygon winds counter-clockwise around the zenith seen from
        // above (and around its centre seen from the shading point). Zero means the
        // shading point lies in the polygon's plane: nothing to sample.
        // In the lanes `(x, y, z, 0)`, each component rounded as `Vec3`'s differences,
        // `cross` and sums round it (`cross3_lanes`; issue 15: about 26 instructions a
        // fan triangle as scalars, 4 per hexagon).
        // Unclipped, from the input's lanes (`rescaled`), the sum starting from the first
        // fan triangle's cross product above (`0 + c`, as the sum adds it).
        let (apex, area_vector) = if was_clipped {
            let lanes = |k: usize| Vec4::from((positions[k], 0.0));
            let apex = lanes(0);
            (apex, fan_cross_sum(lanes, count, 1, apex, Vec4::ZERO))
        } else {
            let sum = Vec4::ZERO + first_cross;
            (
                first_apex,
                fan_cross_sum(rescaled, count, 2, first_apex, sum),
            )
        };
        let orientation = area_vector.truncate().dot(apex.truncate());
        if !(orientation != 0.0) {
            return false;
        }
        // A clockwise polygon is taken in reverse order. Unclipped, `positions` is
        // reversed only where it is read (`counter_clockwise`: the small polygons, the
        // short edges and the general path) and `reversed` tells that it still runs
        // clockwise; the vertex lanes below take the vertices in counter-clockwise order
        // straight from it, so that the central fast path, which reads only the lanes,
        // does not move the vertices (issue 15: 44 instructions per clockwise hexagon).
        // A clipped polygon, which never takes that path, is reversed here.
        let mut reversed = orientation < 0.0;
        if let (Some(planes), true) = (planes.as_mut(), reversed) {
            counter_clockwise(&mut positions, count, true);
            reversed = false;
            reverse_clipped_edge_planes(planes, count);
        }
        let polygon = self;
        polygon.selectable_sectors = 0;
        polygon.central = 0;
        polygon.is_small = 0;
        polygon.small_tolerance = 0.0;
        // Small polygons: the ellipses of nearby edges are nearly equal, and the areas
        // between them (differences of sector areas of order 1) lose about 6e-8 / s of
        // relative precision for an angular size s. Below SMALL_EXTENT the warped solid
        // angle sampler, whose only approximation is of relative order s², takes over.
        // The extent: the largest sin² of the angle between the first vertex and another
        // (no square roots; a vertex in the opposite half-space counts as far away).
        let first = positions[if reversed { count - 1 } else { 0 }];
        let first2 = first.length_squared();
        // Four vertices at a time, each lane rounded as the scalar
        // `p.cross(first).length_squared() / (p.length_squared() * first2)`; lanes past
        // the polygon hold the first vertex again (sin² 0), and a NaN (a vertex whose
        // squared length underflows) counts as 0, as `f32::max` leaves it out.
        // The vertices as lanes: slot j holds vertex j, and the slots from `count` on the
        // first vertex again, and `next` slot j + 1's vertex, each edge's other end (the
        // edge planes of an unclipped polygon take both below) and, past the polygon, the
        // first vertex (sin² 0 here).
        let [vertex, next] = vertex_rows(&positions, count, reversed);
        let [fx, fy, fz] = first.to_array().map(Vec4::splat);
        let mut largest = Vec4::ZERO;
        for start in lane_starts(count - 1) {
            let [x, y, z] = next.each_ref().map(|c| load4(c, start));
            let (cx, cy, cz) = (y * fz - fy * z, z * fx - fz * x, x * fy - fx * y);
            let sin2 = ((cx * cx + cy * cy) + cz * cz) / (((x * x + y * y) + z * z) * first2);
            let ahead = ((x * fx + y * fy) + z * fz).cmpgt(Vec4::ZERO);
            let sin2 = Vec4::select(ahead, sin2, Vec4::ONE);
            largest = largest.max(Vec4::select(sin2.is_nan_mask(), Vec4::ZERO, sin2));
        }
        let extent2 = largest.max_element();
        if allow_small && extent2 < SMALL_EXTENT * SMALL_EXTENT {
            // As from the empty value: `contains` of the small case passes every edge.
            polygon.edge_normals = EdgeNormalRows::ZERO;
            counter_clockwise_cold(&mut positions, count, reversed);
            return polygon.switch_to_small(&positions[..count]);
        }
        // The edge planes n = p_a × p_b, four edges at a time, bit for bit as
        // `cross_precise` (each component's two products split error-free: without
        // hardware FMA the bulk of this preparation's arithmetic). A clipped edge takes
        // the plane of the input edge it lies on (`planes`).
        // Each end's lanes (slot j: edge j's end).
        let clipped_ends;
        let ends = if let Some(planes) = &planes {
            clipped_ends = clipped_end_rows(planes);
            [&clipped_ends[0], &clipped_ends[1]]
        } else {
            [&vertex, &next]
        };
        let mut normals = [[0.0f32; 2 * LANES]; 3];
        // Bit j: n_z > 0 for edge j.
        let mut outer_edges = 0u32;
        for first in lane_starts(count) {
            let [a, b] = ends.map(|lanes| lanes.each_ref().map(|c| load4(c, first)));
            let n = cross_precise4(a, b);
            for (c, lanes) in n.iter().enumerate() {
                store4(*lanes, &mut normals[c], first);
            }
            outer_edges |= n[2].cmpgt(Vec4::ZERO).bitmask() << first;
        }
        let all_edges = (1u32 << count) - 1;
        let outer_edges = outer_edges & all_edges == all_edges;
        // The common case: the zenith inside, nothing clipped, every edge outer and none
        // degenerate (n_z > 0 for every edge, so no vertex lies on the z axis).
        let inputs = FinishInputs {
            count,
            extent2,
            allow_small,
        };
        if allow_fast && !was_clipped && outer_edges {
            *took_fast = true;
            let maybe_short =
                central_unclipped_sectors(polygon, [&vertex, &next], &normals, count, precision);
            let total = central_starts(polygon, count);
            if maybe_short {
                counter_clockwise_cold(&mut positions, count, reversed);
            }
            return polygon.finish_total(&positions, &inputs, count, total, 0.0, maybe_short);
        }
        counter_clockwise(&mut positions, count, reversed);
        // (The vertex lanes, before `next` names the following vertex's index.)
        let vertex_lanes = [&vertex, &next];
        // Algorithm 1 per edge; edge j runs from vertex j to vertex j + 1.
        let next = |j: usize| if j + 1 == count { 0 } else { j + 1 };
        // The edges' ellipses `u` and the vertices' unit directions `s`, as rows of x and
        // y (the lanes' path stores its lanes there; slots past the polygon are not read).
        let mut edge_rows = DEGENERATE.map(|c| [c; MAX_POLYGON_VERTICES]);
        let mut direction_rows = [[0.0f32; MAX_POLYGON_VERTICES]; 2];
        let mut xy_length = [0.0f32; MAX_POLYGON_VERTICES];
        let mut maybe_short = false;
        let edge_ends = |j: usize| match &planes {
            Some(planes) => planes[j],
            None => [positions[j], positions[next(j)]],
        };
        if allow_fast {
            // Four edges and vertices at a time, bit for bit as the loop below, stored
            // as rows: the edge normals (slots past the polygon 0, as in
            // `EdgeNormalRows::ZERO`), u_x, u_y of the edges' ellipses and s_x, s_y of the
            // vertices' directions (issue 15: copied slot by slot from columns, 150
            // instructions per hexagon).
            for first in lane_starts(count) {
                let [nx, ny, nz] = normals.each_ref().map(|c| load4(c, first));
                let (ux, uy) = ellipse_from_normal4(nx, ny, nz);
                let [x, y, _] = vertex.each_ref().map(|c| load4(c, first));
                let (sx, sy) = unit_direction4(x, y);
                // `dot2(direction, p_xy)`.
                store4(sx * x + sy * y, &mut xy_length, first);
                let rows = edge_rows.iter_mut().chain(direction_rows.iter_mut());
                for (row, lanes) in rows.zip([ux, uy, sx, sy]) {
                    store4(lanes, row, first);
                }
                polygon
                    .edge_normals
                    .store4(first, [nx, ny, nz], lanes_kept(first, count));
                // The first test of `ignore_short_edges_in_containment`, as below (lanes
                // past the edges masked: their zero normals would count as short).
                let [a, b] = ends.map(|lanes| lanes.each_ref().map(|c| load4(c, first)));
                let length2 = |[x, y, z]: [Vec4; 3]| (x * x + y * y) + z * z;
                let short = !(length2([nx, ny, nz])).cmpgt(
                    Vec4::splat(super::SHORT_EDGE_SINE * super::SHORT_EDGE_SINE)
                        * (length2(a) * length2(b)),
                );
                let lanes = (count - first).min(LANES);
                maybe_short |= short.bitmask() & ((1u32 << lanes) - 1) != 0;
            }
            if count <= LANES {
                let zero = [Vec4::ZERO; 3];
                polygon
                    .edge_normals
                    .store4(LANES, zero, glam::BVec4A::splat(true));
            }
        } else {
            polygon.edge_normals = EdgeNormalRows::ZERO;
            for j in 0..count {
                let [pa, pb] = edge_ends(j);
                let normal = Vec3::new(normals[0][j], normals[1][j], normals[2][j]);
                let u = ellipse_from_normal(normal);
                [edge_rows[0][j], edge_rows[1][j]] = u;
                polygon.edge_normals.set(j, normal);
                // The first test of `ignore_short_edges_in_containment` on the same
                // values: the common polygon has no short edge and skips it.
                maybe_short |= !(normal.length_squared()
                    > super::SHORT_EDGE_SINE
                        * super::SHORT_EDGE_SINE
                        * (pa.length_squared() * pb.length_squared()));
                let s = unit_direction(positions[j]);
                [direction_rows[0][j], direction_rows[1][j]] = s;
                xy_length[j] = dot2(s, [positions[j].x, positions[j].y]);
            }
        }
        let edge = |j: usize| [edge_rows[0][j], edge_rows[1][j]];
        let direction = |j: usize| [direction_rows[0][j], direction_rows[1][j]];
        // `u_e · s_c` for the ellipse of edge e and the direction of vertex c, from the
        // positions. With u = σ n_xy / n_z (n = p_a × p_b, σ the sign that marks inner
        // ellipses), u · s_c = σ (n_xy · p_c,xy) / (n_z |p_c,xy|) and
        // n_xy · p_c,xy = det(p_a, p_b, p_c) - n_z p_c,z. The determinant vanishes for the
        // edge's own vertices and is otherwise computed from edge vectors. Computed from
        // the rounded u instead, the dot product loses all precision when |u| is large
        // and s nearly orthogonal to it (a great circle passing near the zenith).
        let edge_dot = |e: usize, c: usize| -> f32 {
            let u = edge(e);
            if is_degenerate(u) || !(xy_length[c] > 0.0) {
                return 0.0;
            }
            let (a, b) = (e, next(e));
            let n = polygon.edge_normals.get(e);
            let p = positions[c];
            let triple = if c == a || c == b {
                0.0
            } else {
                // n · p_c = n · (p_c - p_a): the normal is accurate to 2 ulps per
                // component (for a clipped edge from the input edge's plane, see
                // `clipped_edge_planes`), and the edge vector from the clipped edge's
                // start is an exact difference up to one rounding, so the plain products
                // are accurate unless the polygon is degenerate.
                n.dot(p - positions[a])
            };
            // Plain: where the two terms cancel, t is small and only its absolute error
            // (an ulp of p_z / |p_xy|) matters.
            let normal_dot = triple - n.z * p.z;
            let sigma = copy_sign(1.0, n.x);
            let t = sigma * normal_dot / (n.z * xy_length[c]);
            if t.is_finite() { t } else { 0.0 }
        };
        // Algorithm 4, first part: each vertex is associated with the ellipse that leaves
        // it counter-clockwise: its own edge if that edge is outer, else the previous edge.
        // The inner ellipse of the first sector is the inner edge that ends at the
        // clockwise end of the polygon.
        let mut vertex_edge = [0usize; MAX_POLYGON_VERTICES];
        let mut first_inner = None;
        #[allow(clippy::needless_range_loop)] // j indexes the edge rows (`edge(j)`) too
        for j in 0..count {
            let previous = if j == 0 { count - 1 } else { j - 1 };
            vertex_edge[j] = if is_inner(edge(j)) { previous } else { j };
            if is_inner(edge(previous)) && !is_inner(edge(j)) {
                first_inner = Some(previous);
            }
        }
        let sectors;
        // Σ of the outer sector areas: Φ is their difference with the inner ones, and
        // their ratio is the factor by which rounding errors are amplified.
        // (Its upper bound from `outer_area_bound`, summed in the same order: 0 in the
        // central case, where the sliver test does not apply.)
        let mut outer_sum_bound = 0.0f32;
        if let Some(first_inner) = first_inner {
            // Decentral case: sort the vertices by azimuth. Vertex a comes before b when
            // det(p_a,xy, p_b,xy) > 0, computed from the clipped positions (not the rounded
            // unit directions) so that a degenerate edge's two vertices compare exactly
            // equal; then the one with the degenerate ellipse comes first (rule 3).
            let mut order = [0u8, 1, 2, 3, 4, 5, 6, 7];
            let xy = |k: u8| {
                // `& 7` only shows the compiler the index in bounds (entries are below 8).
                let p = positions[(k & 7) as usize];
                [p.x, p.y]
            };
            let degenerate = |k: u8| is_degenerate(edge(vertex_edge[k as usize]));
            let less = |a: &u8, b: &u8| {
                // Only the sign of det(p_a,xy, p_b,xy) matters: the careful form only
                // where the plain one may have it wrong.
                let ([ax, ay], [bx, by]) = (xy(*a), xy(*b));
                let d = crate::math::difference_of_products_sign(ax, by, ay, bx);
                d > 0.0 || (d == 0.0 && degenerate(*a) && !degenerate(*b))
            };
            if !(allow_fast && sort_by_certain_azimuths(&mut order, &vertex, count)) {
                order = [0, 1, 2, 3, 4, 5, 6, 7];
                sort_carefully(&mut order, count, less);
            }
            sectors = count - 1;
            // The vertices' x, y, |p_xy| and unit direction in azimuth order (slot j holds
            // vertex order[j]; zeros past the polygon), so that sector j's ends are slots j
            // and j + 1 of the same lanes: one copy per vertex where the sectors' pairs
            // took two.
            let mut sorted = [[0.0f32; VERTEX_SLOTS]; 5];
            for (j, &k) in order[..count].iter().enumerate() {
                // `& 7` only shows the compiler the index in bounds (entries are below 8).
                let k = (k & 7) as usize;
                let p = positions[k];
                let values = [p.x, p.y, xy_length[k], direction(k)[0], direction(k)[1]];
                for (column, value) in sorted.iter_mut().zip(values) {
                    column[j] = value;
                }
            }
            let sector_det = if allow_fast {
                // `sector_determinants` of the pairs (order[j], order[j + 1]), four at a
                // time straight from the sorted lanes, bit for bit (the same operations);
                // lanes past the sectors are not read.
                let mut dets = [0.0f32; 2 * LANES];
                let [xs, ys, lengths, _, _] = &sorted;
                for first in lane_starts(sectors) {
                    let (xa, ya, la) = (load4(xs, first), load4(ys, first), load4(lengths, first));
                    let (xb, yb, lb) = (
                        load4(xs, first + 1),
                        load4(ys, first + 1),
                        load4(lengths, first + 1),
                    );
                    let det = difference_of_products4(xa, yb, ya, xb) / (la * lb);
                    store4(crate::math::finite_or_zero4(det), &mut dets, first);
                }
                dets
            } else {
                let mut pairs = [(0usize, 0usize); MAX_POLYGON_VERTICES];
                for j in 0..sectors {
                    pairs[j] = (order[j] as usize, order[j + 1] as usize);
                }
                sector_determinants(&positions, &xy_length, &pairs[..sectors])
            };
            // Per sector: the inner ellipse and its dot products with s0 and s1, the outer
            // one and its (columns, one lane per sector; lanes past the sectors stay 0;
            // s0 and s1 are slots j and j + 1 of the sorted directions).
            let mut columns = [[0.0f32; 2 * LANES]; 8];
            let mut inner = first_inner;
            let mut outer = 0usize;
            // The previous sector's inner and outer ellipse and their dot products with
            // its s1, this sector's s0: the same `edge_dot` where the ellipse is the same.
            let mut previous = [(usize::MAX, 0.0f32); 2];
            // The table of `edge_dot` at each edge's own vertices (see `own_edge_dots`).
            let own = allow_fast
                .then(|| own_edge_dots(vertex_lanes, &normals, &edge_rows[0], &xy_length, count));
            for j in 0..sectors {
                let (a, b) = (order[j] as usize, order[j + 1] as usize);
                let e = vertex_edge[a];
                if j > 0 && is_inner(edge(e)) {
                    inner = e;
                }
                if j == 0 || !is_inner(edge(e)) {
                    outer = e;
                }
                let mut dots = [[0.0f32; 2]; 2];
                for (k, e) in [inner, outer].into_iter().enumerate() {
                    let at_a = if previous[k].0 == e {
                        previous[k].1
                    } else {
                        own_edge_dot(&own, e, next(e), a).unwrap_or_else(|| edge_dot(e, a))
                    };
                    let at_b = own_edge_dot(&own, e, next(e), b).unwrap_or_else(|| edge_dot(e, b));
                    previous[k] = (e, at_b);
                    dots[k] = [at_a, at_b];
                }
                let [ti, to] = dots;
                let values = [
                    edge(inner)[0],
                    edge(inner)[1],
                    ti[0],
                    ti[1],
                    edge(outer)[0],
                    edge(outer)[1],
                    to[0],
                    to[1],
                ];
                for (column, value) in columns.iter_mut().zip(values) {
                    column[j] = value;
                }
            }
            let sectors_mut = polygon.pieces.sectors_mut();
            // The sectors' areas, `area(false, precision)` (before `max(0)`).
            let mut areas = [0.0f32; 2 * LANES];
            // `EllipseSector::new` of sector j and its area, one at a time.
            let scalar_sector = |sector: &mut EllipseSector, j: usize| {
                let pair = |c: usize| [columns[c][j], columns[c + 1][j]];
                let direction = |slot: usize| [sorted[3][slot], sorted[4][slot]];
                *sector = EllipseSector::new(
                    direction(j),
                    direction(j + 1),
                    sector_det[j],
                    pair(0),
                    pair(2),
                    pair(4),
                    pair(6),
                );
                sector.area(false, precision)
            };
            if allow_fast {
                // Four sectors at a time, bit for bit as `EllipseSector::new`. The slots
                // of lanes past the sectors (at most 7 of 8 slots are sectors) are
                // written here and then again by `finish`, as empty sectors. A last
                // sector alone (a hexagon's fifth) takes `new`, cheaper than four lanes.
                for first in lane_starts(sectors) {
                    if sectors - first == 1 {
                        areas[first] = scalar_sector(&mut sectors_mut[first], first);
                        continue;
                    }
                    let [uix, uiy, ti0, ti1, uox, uoy, to0, to1] =
                        columns.each_ref().map(|c| load4(c, first));
                    let (s0x, s0y) = (load4(&sorted[3], first), load4(&sorted[4], first));
                    let (s1x, s1y) = (load4(&sorted[3], first + 1), load4(&sorted[4], first + 1));
                    let lanes = EllipseSector::new4(
                        [s0x, s0y],
                        [s1x, s1y],
                        load4(&sector_det, first),
                        [uix, uiy],
                        [ti0, ti1],
                        [uox, uoy],
                        [to0, to1],
                        precision,
                        (sectors - first).min(LANES),
                        (&mut sectors_mut[first..first + LANES]).try_into().unwrap(),
                    );
                    areas[first..first + LANES].copy_from_slice(&lanes);
                }
            } else {
                for (j, sector) in sectors_mut[..sectors].iter_mut().enumerate() {
                    areas[j] = scalar_sector(sector, j);
                }
            }
            // The polygon's azimuthal ends: the first and the last sector with det != 0
            // (past the empty sectors of a vertex that clipping repeated), tested together
            // (`ends_touch_pair`; both exist or neither).
            // (Bit j: sector j's det, as stored, is not 0; lanes past the sectors masked.)
            let live = (0..2).fold(0u32, |bits, group| {
                let det = load4(&sector_det, group * LANES);
                bits | det.cmpne(Vec4::ZERO).bitmask() << (group * LANES)
            }) & ((1u32 << sectors) - 1);
            let (first_live, last_live) = match live {
                0 => (None, None),
                _ => (
                    Some(live.trailing_zeros() as usize),
                    Some(31 - live.leading_zeros() as usize),
                ),
            };
            let [first_touches, last_touches] = match (first_live, last_live) {
                (Some(first), Some(last)) => {
                    let sectors = polygon.pieces.sectors_mut();
                    EllipseSector::ends_touch_pair(&sectors[first], &sectors[last])
                }
                _ => [false; 2],
            };
            #[allow(clippy::needless_range_loop)] // j indexes the sectors and their areas
            for j in 0..sectors {
                let sector = &mut polygon.pieces.sectors_mut()[j];
                // An upper bound on the outer ellipse's area instead of the area itself
                // (see `outer_area_bound`): it decides the extra iteration here and the
                // sliver test in `finish` but where the exact area could reach their
                // thresholds.
                let outer_bound = outer_area_bound(sector);
                outer_sum_bound += outer_bound;
                let area = areas[j].max(0.0);
                // Also where the ellipses touch or nearly touch at an end of the sector (a
                // vertex on or just above the horizon at the polygon's azimuthal end, issue
                // 17, 2): the shape of the region there is modelled in the initial guess,
                // but a steep edge beside it (|u| of 28) left up to 2.3e-4 rad after one
                // iteration 0.05 rad above the horizon, 3e-6 after two.
                // Only the polygon's azimuthal ends have a vertex on both ellipses: the
                // first sector's s0 and the last one's s1, past the empty sectors of a
                // vertex that clipping repeated (det 0). Elsewhere the region has a width
                // at the sector's ends, and the test (two divisions, an arc tangent at a
                // meeting point) is not made; the last end is tested after the loop.
                // (The sectors before the first live one, all empty, one by one.)
                let touching = match first_live {
                    Some(first) if j == first => first_touches,
                    Some(first) if j > first => false,
                    _ => sector.ends_touch(false),
                };
                // (This and `extra_iterations` below are written for every sector here:
                // `new4` leaves both words.)
                sector.touching_ends = touching as u32;
                let limit = 200.0 * area;
                // (A NaN bound, which no finite ellipse gives, falls back too.) Not for
                // the biased variant (fast areas): its sampler runs no iteration and
                // reads no `extra_iterations`, and the exact outer area (an `atanf` behind
                // a call) was where the bound left the test open, about a third of the
                // bench's decentral hexagons (issue 15, stop 47). The precision is tested
                // only there (`prepare_with` takes it as an argument, not a constant).
                // Where `1.6 / k` does not settle it, the tighter `outer_area_ratio_bound`
                // (a division more) mostly does, before the exact area's `atanf`.
                let ill_conditioned = !(outer_bound < limit)
                    && precision == AreaPrecision::Exact
                    && !(outer_area_ratio_bound(sector) < limit)
                    && exact_outer_area(sector) > limit;
                sector.extra_iterations = (ill_conditioned || touching) as u32;
                polygon.sector_area[j] = area;
            }
            if let (Some(last), true) = (last_live, last_touches) {
                let sector = &mut polygon.pieces.sectors_mut()[last];
                sector.touching_ends |= 2;
                sector.extra_iterations = 1;
            }
        } else {
            // Central case: sector j reaches from the origin to the ellipse of edge j,
            // which passes through both of the sector's vertices.
            polygon.central = 1;
            sectors = count;
            let mut pairs = [(0usize, 0usize); MAX_POLYGON_VERTICES];
            for (j, pair) in pairs[..count].iter_mut().enumerate() {
                *pair = (j, next(j));
            }
            let sector_det = sector_determinants(&positions, &xy_length, &pairs[..count]);
            // Per sector, four at a time and bit for bit as `EllipseSector::new_central`
            // and `area` compute them one by one: the outer ellipse's √|C|, s0 · s1,
            // 1 / det(s0, s1) and (exact areas) the area of Equation (1).
            // Columns: s0, s1, u, u · s0, u · s1, det; lanes past the sectors stay 0.
            let mut columns = [[0.0f32; 2 * LANES]; 9];
            #[allow(clippy::needless_range_loop)] // j indexes several arrays and vertices
            for j in 0..count {
                let (a, b) = (j, next(j));
                let values = [
                    direction(a)[0],
                    direction(a)[1],
                    direction(b)[0],
                    direction(b)[1],
                    edge(j)[0],
                    edge(j)[1],
                    edge_dot(j, a),
                    edge_dot(j, b),
                    sector_det[j],
                ];
                for (column, value) in columns.iter_mut().zip(values) {
                    column[j] = value;
                }
            }
            let mut area = [0.0f32; 2 * LANES];
            let central = polygon.pieces.central_mut();
            for first in lane_starts(count) {
                let [s0x, s0y, s1x, s1y, ux, uy, t0, t1, det] =
                    columns.each_ref().map(|c| load4(c, first));
                let root_det = crate::math::sqrt4(Vec4::ONE + (ux * ux + uy * uy));
                let cosine = s0x * s1x + s0y * s1y;
                let x = (cosine + t0 * t1) / root_det;
                let lanes_area =
                    crate::math::atan2_upper_half_plane4(det.max(Vec4::ZERO), x, count - first)
                        * (Vec4::splat(0.5) / root_det);
                // `is_degenerate`: not |u_x| <= the limit (NaN included).
                let proper = ux.abs().cmple(Vec4::splat(super::ellipse::ELLIPSE_LIMIT));
                let lanes_area = Vec4::select(proper, lanes_area, Vec4::ZERO).max(Vec4::ZERO);
                store4(lanes_area, &mut area, first);
                central.store(
                    first,
                    lanes_kept(first, count),
                    &CentralLanes {
                        s0: [s0x, s0y],
                        s1: [s1x, s1y],
                        det,
                        outer: [ux, uy],
                        outer_dots: [t0, t1],
                        root_det,
                    },
                );
            }
            if count <= LANES {
                central.store_zeros(LANES);
            }
            #[allow(clippy::needless_range_loop)] // j indexes two arrays and the sectors
            for j in 0..count {
                polygon.sector_area[j] = match precision {
                    AreaPrecision::Exact => area[j],
                    AreaPrecision::Fast => polygon
                        .central_sectors()
                        .sector(j)
                        .area(true, precision)
                        .max(0.0),
                };
            }
        }
        polygon.finish(&positions, &inputs, sectors, outer_sum_bound, maybe_short)
    }

    /// Writes the small-polygon sampler of the polygon `positions` in place; the
    /// sectors are then not read.
    #[inline(always)]
    fn switch_to_small(&mut self, positions: &[Vec3]) -> bool {
        let polygon = self;
        // The whole storage first (the sectors' view is the larger), then the small
        // sampler over its start: no stale word is left.
        polygon.pieces = ProjectedPieces::EMPTY;
        if !polygon.small_mut().prepare(positions) {
            return false;
        }
        polygon.sector_area = [0.0; MAX_POLYGON_VERTICES];
        polygon.sector_start = [0.0; MAX_POLYGON_VERTICES];
        polygon.projected_solid_angle = polygon.small().projected_solid_angle();
        polygon.density = 1.0 / polygon.projected_solid_angle;
        polygon.selectable_sectors = 1;
        polygon.is_small = 1;
        polygon.small_tolerance = polygon.small().tolerance(SMALL_ROUNDING);
        true
    }

    /// The end of the general path of [`prepare_or_fail`](Self::prepare_or_fail): the
    /// unused slots, the sectors' starts, Φ and the checks (`positions` in
    /// counter-clockwise order). The central fast path writes its areas and starts from
    /// lanes (`central_starts`) and joins at [`finish_total`](Self::finish_total).
    #[inline(always)]
    fn finish(
        &mut self,
        positions: &[Vec3; MAX_POLYGON_VERTICES],
        inputs: &FinishInputs,
        sectors: usize,
        outer_sum: f32,
        maybe_short: bool,
    ) -> bool {
        let polygon = self;
        // The unused slots too (no stale or NaN word is left in a prepared value, which
        // the adversarial C test checks by filling the struct with NaN first).
        // `EllipseSector::EMPTY` from registers (see `empty_from`): copied from the
        // constant, each slot was a call of `memcpy`. (The central sectors' rows have
        // their unused slots written already, as 0.)
        let one = core::hint::black_box(1.0f32);
        for j in sectors..MAX_POLYGON_VERTICES {
            if polygon.central == 0 {
                polygon.pieces.sectors_mut()[j] = EllipseSector::empty_from(one);
            }
            polygon.sector_area[j] = 0.0;
        }
        let mut total = 0.0f32;
        for j in 0..sectors {
            polygon.sector_start[j] = total;
            if polygon.sector_area[j] > 0.0 {
                polygon.selectable_sectors = j as u32 + 1;
            }
            total += polygon.sector_area[j];
        }
        pad_unselectable(&mut polygon.sector_start, polygon.selectable_sectors);
        polygon.finish_total(positions, inputs, sectors, total, outer_sum, maybe_short)
    }

    /// The end of [`finish`](Self::finish) from Φ (`total`), with the sectors, their
    /// areas and starts and `selectable_sectors` written: the checks, Φ, the density and
    /// the short edges. The central fast path comes here from `central_starts`.
    #[inline(always)]
    fn finish_total(
        &mut self,
        positions: &[Vec3; MAX_POLYGON_VERTICES],
        inputs: &FinishInputs,
        sectors: usize,
        total: f32,
        outer_sum: f32,
        maybe_short: bool,
    ) -> bool {
        let polygon = self;
        let FinishInputs {
            count,
            extent2,
            allow_small,
        } = *inputs;
        let density = 1.0 / total;
        // Positive and finite, as plain comparisons (`is_finite` compiled to a
        // classification of the bits here).
        if !(total > 0.0 && total < f32::INFINITY && density < f32::INFINITY) {
            return false;
        }
        // Slivers seen nearly edge-on: the inner and outer ellipses almost coincide and Φ
        // is a small difference of large areas, with a relative error of about
        // 3e-7 × outer_sum / Φ. The small-polygon sampler deviates from the cosine by
        // 0.2 extent² (and is exact for its own pdf); switch when that is smaller, as long
        // as it stays within the 1e-4 that the pdf contract allows.
        // `outer_sum` is an upper bound on that sum (the sum of `outer_area_bound`;
        // rounding is monotone, so sums in the same order keep the order of their
        // terms): the exact sum is formed only where the bound does not settle
        // the test (NaN included). 0 (the central case, or only degenerate outer
        // ellipses, whose areas are 0) never passes it.
        if allow_small
            && outer_sum != 0.0
            && !(3e-7 * outer_sum <= 0.2 * extent2 * total)
            && extent2 < SLIVER_EXTENT2
        {
            let exact_sum = exact_outer_sum(&polygon.sectors()[..sectors]);
            if 3e-7 * exact_sum > 0.2 * extent2 * total {
                return polygon.switch_to_small(&positions[..count]);
            }
        }
        polygon.projected_solid_angle = total;
        polygon.density = density;
        if maybe_short {
            let mut normals = polygon.edge_normals.vectors();
            super::ignore_short_edges_in_containment(&mut normals, positions, count);
            polygon.edge_normals.set_all(&normals);
        }
        true
    }

    /// Whether [`prepare`](Self::prepare) of `vertices` succeeds through the central fast
    /// path (`central_unclipped_sectors`: the zenith inside, nothing clipped, every edge
    /// outer and none degenerate), for the report's share of polygons per path. Prepares
    /// a scratch value; `#[inline]` keeps it out of the static library.
    #[doc(hidden)]
    #[inline]
    #[must_use]
    pub fn takes_central_fast_path(vertices: &[Vec3]) -> bool {
        let mut scratch = Self::EMPTY;
        let mut took_fast = false;
        let prepared =
            scratch.prepare_or_fail(vertices, AreaPrecision::Exact, true, true, &mut took_fast);
        prepared && took_fast
    }

    /// Whether preparation handed the polygon to the small-polygon sampler (warped solid
    /// angle sampling, for polygons below [`SMALL_EXTENT`] across and for slivers whose
    /// sector areas cancel) instead of the sectors of Algorithm 4.
    #[inline]
    #[must_use]
    pub fn uses_small_polygon_sampler(&self) -> bool {
        self.is_small != 0
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
        self.sample_impl(u, REFINEMENT_ITERATIONS, true)
    }

    /// The biased variant: no refinement iterations in the decentral case, so the azimuth
    /// is the initial guess of Proposition 3 (its error is in the report). **Biased**: the
    /// returned pdf is that of the exact distribution, `ω_z / Φ`, which differs from the
    /// density with which this function actually places its samples.
    #[inline]
    pub fn sample_fast(&self, u: [f32; 2]) -> Sample {
        self.sample_impl(u, 0, false)
    }

    /// [`sample`](Self::sample) with the given number of refinement iterations in the
    /// decentral case (0 is [`sample_fast`](Self::sample_fast)), at most
    /// [`MAX_REFINEMENT_ITERATIONS`] (larger counts are clamped).
    pub fn sample_with_iterations(&self, u: [f32; 2], iterations: u32) -> Sample {
        self.sample_impl(u, iterations, false)
    }

    /// The sampler, with the ill-conditioned sectors' extra iteration when
    /// `extra_iterations` is set.
    #[inline(always)]
    fn sample_impl(&self, u: [f32; 2], iterations: u32, extra_iterations: bool) -> Sample {
        // The biased variant (a constant there) and `sample_with_iterations(u, 0)`: the
        // initial guess is the sample, evaluated directly (see `sample_between`).
        let guess_only = !extra_iterations && iterations == 0;
        if self.selectable_sectors == 0 {
            return Sample::NONE;
        }
        let (u0, u1) = (clamp_random(u[0]), clamp_random(u[1]));
        if self.is_small != 0 {
            // The pdf through the inverse of the warp, exactly as `pdf` computes it: the
            // warp's own value at the drawn coordinates differs from it by the rounding
            // of the direction relative to the polygon's size, which is large for
            // polygons of 1e-5 rad and below and unbounded relative to ℓ near a vertex on
            // the horizon (found by fuzzing: up to 2e3 times; 2 times for u0 = 0 where a
            // clipped vertex repeats). MIS needs `pdf(sample.dir) == sample.pdf`.
            let s = self.small().sample(u0, u1);
            let tolerance = self.small_tolerance.min(SMALL_ROUNDING);
            let pdf = self.small_pdf_within(s.dir, tolerance);
            if pdf > 0.0 || s.pdf == 0.0 {
                return Sample::new_or_none(s.dir, pdf);
            }
            // Rounding put the direction outside by more than the slack, which is a
            // small fraction of the polygon's width (issue 16, 1): pulled towards the
            // polygon's inner direction until inside (`INWARD_PULLS`), or (where even that
            // fails the tight test, for polygons that f32 directions barely resolve) the
            // direction with the 16-ulp slack of before, which the LTC polygon's own
            // `pdf` (slack 1e-5 rad) accepts.
            let inner = self.small().inner_direction();
            let pulled = crate::sample::INWARD_PULLS.iter().find_map(|&pull| {
                let dir = crate::math::normalize_or(s.dir * (1.0 - pull) + inner * pull, inner);
                let pdf = self.small_pdf_within(dir, tolerance);
                (pdf > 0.0).then_some(Sample { dir, pdf })
            });
            if let Some(sample) = pulled {
                return sample;
            }
            return Sample::new_or_none(s.dir, self.small_pdf_within(s.dir, SMALL_ROUNDING));
        }
        let target = u0 * self.projected_solid_angle;
        // The sector: the number of sectors (among all but the last selectable) that start
        // at or before the target. `<=` skips sectors of zero area.
        let k = select_piece(&self.sector_start, target);
        let sector_area = self.sector_area[k];
        let local = (target - self.sector_start[k]).max(0.0).min(sector_area);
        let point_and_z2 = if self.central != 0 {
            Some(self.central_sectors().sample(k, local, u1))
        } else {
            let sector = &self.sectors()[k];
            let fraction = local / sector_area;
            // Both counts clamped: `extra_iterations` is a 0/1 flag, and a corrupted
            // prepared value (or a huge argument) must not loop without bound (issue 16,
            // 6). Convergence is cubic (supplement A.5, Proposition 6): more than
            // MAX_REFINEMENT_ITERATIONS changes no bit.
            let iterations = if (ITERATION_MARGIN..=1.0 - ITERATION_MARGIN).contains(&fraction) {
                iterations.min(MAX_REFINEMENT_ITERATIONS)
                    + extra_iterations as u32 * sector.extra_iterations.min(1)
            } else {
                0
            };
            // `local` through `opaque`: the iterations keep the area across the arc
            // tangents' calls, in a stack slot, and without the copy the central path
            // above reloaded `local` from that slot (9 cycles on its chain, llvm-mca).
            let area = crate::math::opaque(local);
            sector.sample_between(area, fraction, u1, iterations, guess_only)
        };
        let Some((point, z2)) = point_and_z2 else {
            return Sample::NONE;
        };
        let dir = Vec3::new(point[0], point[1], crate::math::sqrtf(z2.max(0.0)));
        // In a sector of nearly π (a large polygon seen nearly edge-on, crossing the
        // horizon), |w|² from the sector's coordinates cancels, and the point and its z
        // disagree: found by fuzzing, |dir| = 1.117. Renormalise such a direction (the
        // test leaves every direction with | |dir|² - 1 | <= 2e-6 bit for bit as it was);
        // its pdf is then `dir.z / Φ` of the direction returned, as `pdf` gives.
        let Some(dir) = crate::math::unit_if_needed_or_none(dir) else {
            return Sample::NONE;
        };
        // `dir.z / Φ` as `pdf` computes it (`unit_if_needed` leaves this `dir` as it is),
        // so that `pdf(sample.dir) == sample.pdf` bit for bit wherever `pdf` finds the
        // direction inside.
        Sample::new_or_none(dir, dir.z * self.density)
    }

    /// `ω_z / Φ` for a direction inside the polygon (or on its boundary) and above the
    /// horizon, 0 otherwise. `dir` need not be normalised; a zero or non-finite `dir`
    /// gives 0. For polygons below [`SMALL_EXTENT`](super::small_projected::SMALL_EXTENT)
    /// (handled by the small-polygon sampler, whose draws follow `ω_z / Φ` within
    /// `0.2 s²`) directions outside by at most the smaller of 16 ulps (1.9e-6 rad) and
    /// 2e-5 of the polygon's width count as inside (samples that rounding puts farther
    /// out are pulled inside by `sample`).
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        self.pdf_inline(dir)
    }

    /// The body of [`pdf`](Self::pdf), always inlined: for the polygon light's sample,
    /// which evaluates it at every LTC sample and where `pdf` itself was called out of
    /// line (68 instructions per call with the call's own). The same operations, so the
    /// same bits.
    #[inline(always)]
    pub(crate) fn pdf_inline(&self, dir: Vec3) -> f32 {
        if self.is_small != 0 {
            return self.small_pdf_within(dir, self.pdf_slack());
        }
        if self.contains(dir) {
            self.pdf_inside(dir)
        } else {
            0.0
        }
    }

    /// `ω_z / Φ`, the density of [`pdf`](Self::pdf) at a direction inside the polygon
    /// and above the horizon, without the containment test: for `pdf` and its forms
    /// with a slack, and for the polygon light's sample at an LTC sample that lies
    /// inside the polygon by the LTC's own test (`LtcSample::inner`; issue 18, 3).
    /// Unit directions (every sample) as they are, so that a sample's pdf is this bit
    /// for bit; others normalised by the largest component first: a tiny `dir` (1e-45)
    /// had a length of 0 and an infinite pdf (found by the adversarial C test).
    #[inline(always)]
    pub(crate) fn pdf_inside(&self, dir: Vec3) -> f32 {
        crate::math::unit_if_needed(dir).z * self.density
    }

    /// Whether `dir` lies inside the clipped polygon or outside by at most `tolerance`
    /// radians (approximately: the sine of the angle to each edge's great circle), and
    /// strictly above the horizon. With `tolerance = 0` this is [`contains`](Self::contains).
    #[inline]
    pub fn contains_within(&self, dir: Vec3, tolerance: f32) -> bool {
        if self.is_small != 0 {
            return dir.z > 0.0 && self.small().contains_within(dir, tolerance);
        }
        let inside = self.selectable_sectors > 0 && dir.z > 0.0 && dir.is_finite();
        // Fast accept: a direction on the inner side of every edge's plane (every
        // sample but those within rounding of the boundary) is inside for any slack,
        // without the lengths of the slack's test (nine square roots).
        // Unused slots hold zero normals, whose dot product 0 passes.
        let strictly = self.edge_normals.all_on_inner_side(dir);
        if strictly || !inside {
            return inside && strictly;
        }
        self.contains_within_slack(dir, tolerance)
    }

    /// The slack's test of [`contains_within`](Self::contains_within), for a direction
    /// outside some edge's plane: the sine of its angle to each such great circle
    /// against `tolerance`. Out of line: it runs only next to the boundary.
    #[inline(never)]
    #[cold]
    fn contains_within_slack(&self, dir: Vec3, tolerance: f32) -> bool {
        self.edge_normals
            .all_within(dir, tolerance, crate::math::length(dir))
    }

    /// The slack of [`pdf`](Self::pdf) in radians: how far outside the polygon a
    /// direction still gets the density (0 but for the small-polygon path).
    #[inline]
    pub(crate) fn pdf_slack(&self) -> f32 {
        if self.is_small != 0 {
            self.small_tolerance.min(SMALL_ROUNDING)
        } else {
            0.0
        }
    }

    /// [`pdf`](Self::pdf) extended to directions outside the polygon by at most
    /// `tolerance` radians (approximately; see [`contains_within`](Self::contains_within)):
    /// the density formula continued there. For samplers that map this sampler's
    /// directions through a transformation whose rounding may move them slightly out
    /// (the LTC polygon). With `tolerance = 0` this is `pdf`.
    pub(crate) fn pdf_within(&self, dir: Vec3, tolerance: f32) -> f32 {
        if self.is_small != 0 {
            return self.small_pdf_within(dir, tolerance);
        }
        if self.contains_within(dir, tolerance) {
            self.pdf_inside(dir)
        } else {
            0.0
        }
    }

    /// The density of the small-polygon case, `ω_z / Φ` for `dir` inside the fan or
    /// outside by at most `tolerance` radians, 0 otherwise: the same formula as the
    /// sectors' case, evaluated from the direction's own `z` (to its full relative
    /// precision, also next to the horizon). The warp's exact density `ℓ / Φ̃` differs
    /// from it by at most `0.2 s²` (2e-5 at the switch-over size); evaluated through
    /// the inverse of the warp at an `f32` direction it was off by up to 6e-2 for a
    /// polygon 1e-4 rad across just above the horizon, where `ω_z` is 1e-5 and the
    /// inversion's absolute error an ulp of 1 (issue 16, 3).
    #[inline(always)]
    fn small_pdf_within(&self, dir: Vec3, tolerance: f32) -> f32 {
        if dir.z > 0.0 && self.small().contains_within(dir, tolerance) {
            self.pdf_inside(dir)
        } else {
            0.0
        }
    }

    /// Whether the ray along `dir` passes through the clipped polygon (boundary
    /// included) and lies strictly above the horizon.
    #[inline]
    pub fn contains(&self, dir: Vec3) -> bool {
        if self.is_small != 0 {
            return dir.z > 0.0 && self.small().contains_within(dir, 0.0);
        }
        // Unused slots hold zero normals, whose dot product 0 passes.
        self.selectable_sectors > 0
            && dir.z > 0.0
            && dir.is_finite()
            && self.edge_normals.all_on_inner_side(dir)
    }

    /// [`contains`](Self::contains) for a direction the caller knows to be finite
    /// (the LTC polygon's, whose `|w|²` it has range-tested: a non-finite coordinate
    /// makes `|w|²` infinite or NaN): the same answer without `contains`' test of
    /// finiteness, about 12 instructions per call. The small-polygon path is `contains`'
    /// own (it has no such test). Tested in the LTC polygon's
    /// `containment_in_steps_is_contains_within_the_slack`.
    #[inline(always)]
    pub(crate) fn contains_finite(&self, dir: Vec3) -> bool {
        debug_assert!(dir.is_finite());
        if self.is_small != 0 {
            return self.contains(dir);
        }
        // Unused slots hold zero normals, whose dot product 0 passes.
        self.selectable_sectors > 0 && dir.z > 0.0 && self.edge_normals.all_on_inner_side(dir)
    }
}

/// How far outside a polygon handled by the small-polygon sampler (in radians) a
/// direction may lie and still get the density `ω_z / Φ`: 16 ulps
/// of a unit vector, the rounding of a sampled direction, which for polygons of 1e-6 rad
/// and below is a good part of their size.
const SMALL_ROUNDING: f32 = 16.0 * f32::EPSILON;

#[cfg(test)]
#[path = "projected_tests.rs"]
mod tests;
