//! Sampling a linearly transformed cosine ([`Ltc`]) inside a polygonal light (Peters
//! 2021, Section 5), beside the other polygon samplers: the polygon module depends on
//! the BRDF module's `Ltc`, never the reverse.
//!
//! Restricted to a polygon `P`, `∫_P D dω = Φ(M⁻¹P) / π`: linear maps keep polygons
//! polygons, and the cosine integral over the transformed polygon is its projected solid
//! angle (Heitz 2016, Eq. 11, "the polygon integral"). Sampling the LTC inside `P`
//! therefore is projected solid angle sampling of `M⁻¹P` followed by the map `M`
//! ([`LtcPolygon`], Peters 2021 Sec. 5): a sample `ω'` of `M⁻¹P` with density
//! `ω'_z / Φ'` maps to `ω = Mω' / ‖Mω'‖` with density
//! `(ω'_z / Φ') |det M⁻¹| ‖Mω'‖³` (since `‖M⁻¹ω‖ = 1 / ‖Mω'‖`), which equals
//! `D(ω) / ∫_P D`. As in Heitz 2016, the polygon is clipped to the horizon of the
//! transformed space (`(M⁻¹ω)_z > 0`, where `D` lives), not of the shading frame: the
//! LTC may place a little mass below the surface, and such samples carry a zero BRDF.
use super::ProjectedPolygon;
use crate::brdf::Ltc;
use crate::{MAX_POLYGON_VERTICES, Sample, Vec3};

const INV_PI: f32 = core::f32::consts::FRAC_1_PI;

/// How far (in radians, in the cosine's space) a direction may lie outside the
/// transformed polygon and still get the density: a few hundred f32 ulps of a unit
/// vector, above the rounding of the round trip `ω' → M ω' → M⁻¹(…)` for the
/// well-conditioned cells of the table and for polygons down to 1e-7 rad, and far
/// below the jumps of an ill-conditioned `M` (entries up to 7e5 in the smoothest,
/// most grazing cells).
const ROUND_TRIP_TOLERANCE: f32 = 1e-5;

/// The largest slack of `pdf`, as a fraction of the transformed polygon's width
/// `Φ' / P'` (its projected solid angle over its perimeter, both in the cosine's space):
/// the band of that width around the boundary holds at most this fraction of the
/// density's mass, so `∫ pdf dω` stays within it of 1 (issue 16, 1: the fixed 1e-5 rad
/// alone gave `∫ pdf = 1.044` at 1e-6 sr and 1.010 for a quad seen at 85° with
/// roughness 0.05). The same fraction as the projected small-polygon path's.
const TOLERANCE_PER_WIDTH: f32 = 2e-5;

/// Whether the polygon's plane passes the shading point at a distance larger than
/// rounding (relative to the polygon's size), so that it has a non-zero projected solid
/// angle in exact arithmetic. `M⁻¹` would turn an exact zero (the shading point in the
/// plane) into rounding noise that the projected sampler could not tell from a tiny
/// polygon, so the test is made here, on the input. False for non-finite or collinear
/// vertices.
fn plane_misses_origin(vertices: &[Vec3]) -> bool {
    let largest = largest_magnitude(vertices);
    // `0 < largest < ∞` in one comparison of the bits (two float comparisons took 14
    // instructions).
    if !crate::math::is_positive_finite(largest) {
        return false;
    }
    // Scaled into [-1, 1]: no overflow or underflow in the cross products.
    let scale = 1.0 / largest;
    let first = vertices[0] * scale;
    // The fan's edges from the first vertex, each scaled and subtracted once and kept
    // for the next triangle (the same values as computing it for both of its
    // triangles, which the compiler did, issue 18, stop 45).
    let edge = |v: Vec3| v * scale - first;
    let mut previous = edge(vertices[1]);
    let mut normal = Vec3::ZERO;
    for &v in &vertices[2..] {
        let next = edge(v);
        normal += previous.cross(next);
        previous = next;
    }
    let offset = normal.dot(first).abs();
    offset > 8.0 * f32::EPSILON * crate::math::length(normal) * crate::math::length(first)
}

/// The largest `|coordinate|` of the vertices' [`max_element`](Vec3::max_element)s, as
/// `fold(0.0, |m, v| m.max(v.abs().max_element()))`, with `m.max(x)` as a comparison
/// (one `maxss`, where `f32::max`'s NaN handling cost five instructions a vertex): the
/// same value, as `m` starts at 0 and only ever takes an `x > m`, so it is never NaN,
/// and a NaN `x` leaves it as `f32::max` does (`largest_magnitude_is_the_max_fold`).
#[inline(always)]
fn largest_magnitude(vertices: &[Vec3]) -> f32 {
    vertices.iter().fold(0.0f32, |m, v| {
        let x = v.abs().max_element();
        if x > m { x } else { m }
    })
}

/// The slack of [`LtcPolygon::pdf`] in the cosine's space for the transformed polygon
/// `M⁻¹P` (unclipped vertices) of projected solid angle `Φ'` (after clipping): 0 for
/// the empty polygon (`count` 0, which contains nothing), else the
/// smaller of `ROUND_TRIP_TOLERANCE` and `TOLERANCE_PER_WIDTH · Φ' / P'`, with `P'` the
/// perimeter of the unclipped transformed polygon in radians (chords of its unit
/// vertices; clipping a convex polygon does not lengthen its boundary, so `P'` bounds
/// the clipped one's). A band of width `τ` along the clipped boundary has a mass of at
/// most `τ · P' · max ω'_z / Φ' <= TOLERANCE_PER_WIDTH` under the density `ω'_z / Φ'`,
/// and `∫ pdf dω` over the sphere equals that over the cosine's space (the pdf carries
/// the exact Jacobian of `M`).
fn round_trip_tolerance(
    transformed: &[Vec3; MAX_POLYGON_VERTICES],
    count: usize,
    projected_solid_angle: f32,
) -> f32 {
    if count == 0 {
        return 0.0;
    }
    let width = projected_solid_angle / unit_chord_perimeter(transformed, count);
    if width.is_finite() {
        ROUND_TRIP_TOLERANCE.min(TOLERANCE_PER_WIDTH * width)
    } else {
        ROUND_TRIP_TOLERANCE
    }
}

/// The lanes' indices `0, 1, 2, 3`, against the count of a polygon's vertices in a
/// group.
const LANE_INDICES: glam::Vec4 = glam::Vec4::new(0.0, 1.0, 2.0, 3.0);

/// The perimeter `P'` of [`round_trip_tolerance`] for the non-empty polygon of the first
/// `count` of `vertices` (the rest of the array is read, and ignored): the chords
/// between consecutive unit vertices `t / |t|`, the closing one last, summed in that
/// order. Four vertices at a time in lanes where every `|t|²` lies in `(1e-30, 1e30)`
/// (see [`perimeter_unit`]; the case of every polygon the sampler can resolve): each
/// lane rounds as the scalar `t · (1 / √|t|²)` and `√|u_k − u_(k−1)|²` do (the same
/// operations in the same order, glam's `dot` as `(x·x + y·y) + z·z`), and the chords are
/// added one by one in the scalar order, so the sum is [`unit_chord_perimeter_scalar`]'s
/// bit for bit (`unit_chord_perimeter_is_the_scalar_one` in the tests). Elsewhere the
/// scalar form, whose careful normalisation the lanes do not have. About 55
/// instructions less per quad than the scalar form (issue 18, stop 44). A polygon of at
/// most four vertices stays in registers, each vertex's successor a rotation of the
/// lanes and the chords summed in a row (30 instructions less per quad than through the
/// slots, stop 45).
fn unit_chord_perimeter(vertices: &[Vec3; MAX_POLYGON_VERTICES], count: usize) -> f32 {
    use crate::math::{LANES, lane_starts, load4, sqrt4, store4};
    use glam::{Vec4, Vec4Swizzles};
    let transformed = &vertices[..count];
    if count <= LANES {
        // One group, in registers: vertex `k`'s successor is lane `k + 1` (a rotation),
        // the first vertex for the last.
        let Some([x, y, z]) = unit_lanes(vertices, 0, count) else {
            return unit_chord_perimeter_scalar(transformed);
        };
        let last = LANE_INDICES.cmpeq(Vec4::splat((count - 1) as f32));
        let next = |u: Vec4| Vec4::select(last, Vec4::splat(u.x), u.yzwx());
        let (dx, dy, dz) = (next(x) - x, next(y) - y, next(z) - z);
        let chords = sqrt4((dx * dx + dy * dy) + dz * dz);
        // The lanes past the polygon as +0: the chords are finite and at least +0 (of
        // units in range), and so is their running sum, to which adding +0 changes no
        // bit; nor does starting the sum with the first chord instead of `0 + chord`.
        let inside = LANE_INDICES.cmplt(Vec4::splat(count as f32));
        let [a, b, c, d] = Vec4::select(inside, chords, Vec4::ZERO).to_array();
        return ((a + b) + c) + d;
    }
    // Slots `0..count`: the unit vertices in order; slot `count`: the first again (the
    // closing chord's end), so that chord `k` is slot `k + 1` minus slot `k`. One slot
    // more than the lane groups cover, for the last group's shifted load.
    let mut units = [[0.0f32; MAX_POLYGON_VERTICES + 1]; 3];
    for start in lane_starts(count) {
        let Some([x, y, z]) = unit_lanes(vertices, start, count) else {
            return unit_chord_perimeter_scalar(transformed);
        };
        store4(x, &mut units[0], start);
        store4(y, &mut units[1], start);
        store4(z, &mut units[2], start);
    }
    for axis in &mut units {
        axis[count] = axis[0];
    }
    let mut perimeter = 0.0f32;
    for start in lane_starts(count) {
        let difference = |axis: &[f32]| load4(axis, start + 1) - load4(axis, start);
        let (x, y, z) = (
            difference(&units[0]),
            difference(&units[1]),
            difference(&units[2]),
        );
        let chords = sqrt4((x * x + y * y) + z * z).to_array();
        for chord in &chords[..(count - start).min(LANES)] {
            perimeter += chord;
        }
    }
    perimeter
}

/// The unit vertices `t / |t|` of the lane group from slot `start` of
/// [`unit_chord_perimeter`]'s polygon of `count` vertices, by coordinate (the slots past
/// the polygon hold anything), or `None` where some `|t|²` of the polygon lies outside
/// `(1e-30, 1e30)`, the direct range of [`perimeter_unit`]. Whole groups of the array
/// (no test per lane); lanes past the polygon are left out of the range test.
#[inline(always)]
fn unit_lanes(
    vertices: &[Vec3; MAX_POLYGON_VERTICES],
    start: usize,
    count: usize,
) -> Option<[glam::Vec4; 3]> {
    use glam::Vec4;
    let vertex = |k: usize| vertices[start + k];
    let [a, b, c, d] = [vertex(0), vertex(1), vertex(2), vertex(3)];
    let (x, y, z) = (
        Vec4::new(a.x, b.x, c.x, d.x),
        Vec4::new(a.y, b.y, c.y, d.y),
        Vec4::new(a.z, b.z, c.z, d.z),
    );
    let length2 = (x * x + y * y) + z * z;
    let outside = LANE_INDICES.cmpge(Vec4::splat((count - start) as f32));
    // False for NaN, as `perimeter_unit`'s comparisons are.
    let direct = length2.cmpgt(Vec4::splat(1e-30)) & length2.cmplt(Vec4::splat(1e30));
    if !(direct | outside).all() {
        return None;
    }
    let reciprocal = Vec4::ONE / crate::math::sqrt4(length2);
    Some([x * reciprocal, y * reciprocal, z * reciprocal])
}

/// [`unit_chord_perimeter`] one vertex at a time, with [`perimeter_unit`]'s careful
/// normalisation where `|t|²` is out of its direct range: its fallback, and the
/// reference of its test. The perimeter only sets the slack `τ`, bounded below by
/// `pdf_slack()` in the caller, and the few ulps by which the direct normalisation may
/// differ from the careful one move `τ` by a few ulps, well inside the 2e-5 budget.
///
/// Each unit vertex is kept only until both of its edges are summed.
fn unit_chord_perimeter_scalar(transformed: &[Vec3]) -> f32 {
    let Some((first, rest)) = transformed.split_first() else {
        return 0.0;
    };
    let first = perimeter_unit(*first);
    let mut previous = first;
    let mut perimeter = 0.0f32;
    for t in rest {
        let unit = perimeter_unit(*t);
        perimeter += crate::math::length(unit - previous);
        previous = unit;
    }
    perimeter + crate::math::length(first - previous)
}

/// `t / |t|` for the perimeter of [`round_trip_tolerance`] (zero for a zero or
/// non-finite `t`): directly, by one square root and one division, where `|t|²` lies in
/// `(1e-30, 1e30)` (then no square overflows and the denormal ones lose at most 1e-15
/// of `|t|²`, so the result is within a few ulps of the careful one), and by
/// [`normalize_scaled`](crate::math::normalize_scaled) (a division by the largest
/// component first) elsewhere. The comparisons fail for NaN, so non-finite `t` takes
/// the careful path.
#[inline(always)]
fn perimeter_unit(t: Vec3) -> Vec3 {
    let length2 = t.length_squared();
    if strictly_between(length2, 1e-30, 1e30) {
        t * (1.0 / crate::math::sqrtf(length2))
    } else {
        crate::math::normalize_scaled(t)
    }
}

/// `lo < x < hi` for bounds `0 < lo < hi < ∞` (false for NaN), as one comparison of the
/// bits, as [`is_positive_finite`](crate::math::is_positive_finite) does for `(0, ∞)`:
/// the non-negative `f32` are ordered as their bits, and `bits − (lo_bits + 1)`
/// (wrapping) maps `(lo, hi)` onto `0..hi_bits − lo_bits − 1` and everything else above
/// it: `x <= lo` wraps to at least `2³² − lo_bits − 1`, `x >= hi` (with +∞ and the
/// positive NaNs) stays at least `hi_bits − lo_bits − 1`, and the negative patterns
/// (from `0x8000_0000`, −0 and the negative NaNs too) at least `0x8000_0000 − lo_bits − 1`,
/// above the range as `hi_bits < 0x7f80_0000`. With constant bounds the compiler folds
/// both; the two float comparisons took a comparison with a constant from memory more
/// and a second branch (issue 18, stop 47). Test `strictly_between_is_the_comparisons`.
#[inline(always)]
fn strictly_between(x: f32, lo: f32, hi: f32) -> bool {
    let (lo, hi) = (lo.to_bits(), hi.to_bits());
    x.to_bits().wrapping_sub(lo + 1) < hi - lo - 1
}

/// `w / |w|` (as `w / length(w)`) and its [`unit`](crate::math::unit). Where `|w|²` (as
/// computed, `d`) lies in `(1e-30, 1e30)` the quotient is its own `unit`, given without
/// `unit`'s test (about 10 instructions per LTC sample, issue 18, stop 47): with
/// `u = 2⁻²⁴`, `d` is `|w|² (1 + θ)` with `|θ| <= 3u` (three products and two sums of
/// non-negative terms; a square below the normal range errs by at most 2⁻¹⁵⁰, nothing
/// against `d > 1e-30`), its square root `|w| (1 + ε)` with `|ε| <= 2.5u`, and each
/// quotient `w_k / √d` rounds by `u` relatively (or by 2⁻¹⁵⁰ absolutely), so the exact
/// `|w / √d|²` is `1 ± 7u`, and `unit`'s computed `|·|²` rounds by `3u` more: within
/// `10u = 6e-7` of 1, inside `UNIT_TOLERANCE` (1e-6), where `unit` returns its
/// argument as it is. Elsewhere (tiny, huge or non-finite `w`) `unit` itself. Test
/// `unit_quotient_is_unit`.
#[inline(always)]
fn unit_quotient(w: Vec3) -> (Vec3, Option<Vec3>) {
    let length2 = w.length_squared();
    let dir = w / crate::math::sqrtf(length2);
    if strictly_between(length2, 1e-30, 1e30) {
        (dir, Some(dir))
    } else {
        (dir, crate::math::unit(dir))
    }
}

/// Where a transformed direction lies for [`LtcPolygon::pdf`]: the three outcomes of
/// its containment test in steps ([`LtcPolygon::containment`]).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Containment {
    /// Strictly inside every edge's plane of the transformed polygon and above its
    /// horizon (the test's first step, without the slack).
    Inner,
    /// Outside some edge's plane, but within the slack of `pdf`.
    WithinSlack,
    /// Beyond the slack: `pdf` is 0.
    Outside,
}

/// A sample of [`LtcPolygon`] with what the polygon light reuses of its evaluation
/// ([`LtcPolygon::sample_and_unit`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct LtcSample {
    /// The sample, as [`LtcPolygon::sample`] draws it.
    pub sample: Sample,
    /// `unit` of the sample's direction (`None` only with `Sample::NONE`).
    pub unit: Option<Vec3>,
    /// Whether the sample's transformed direction passed `pdf`'s containment test
    /// without the slack ([`Containment::Inner`]): then the direction lies inside the
    /// polygon up to the rounding of `M ω'`.
    pub inner: bool,
}

impl LtcSample {
    /// No sample.
    const NONE: Self = Self {
        sample: Sample::NONE,
        unit: None,
        inner: false,
    };
}

/// An LTC restricted to a convex polygon: projected solid angle sampling of the polygon
/// transformed by `M⁻¹`, mapped back by `M` (Peters 2021, Sec. 5).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct LtcPolygon {
    ltc: Ltc,
    /// The transformed polygon `M⁻¹P`, clipped to its horizon.
    transformed: ProjectedPolygon,
    /// The vertices of `M⁻¹P` before clipping (zero past `vertex_count`), from which
    /// [`tolerance`](Self::tolerance) computes `pdf`'s slack only where `pdf` needs it
    /// (next to the boundary): computed in every prepare, the slack's perimeter and
    /// quotient were about 115 instructions of a quad's (issue 18, stop 46).
    unclipped: [Vec3; MAX_POLYGON_VERTICES],
    /// The number of `unclipped` vertices, 3 to 8 (0 when empty).
    vertex_count: u32,
}

impl LtcPolygon {
    /// An empty polygon: no samples, pdf 0, integral 0.
    ///
    /// cbindgen:ignore
    pub const EMPTY: LtcPolygon = LtcPolygon {
        ltc: Ltc::IDENTITY,
        transformed: ProjectedPolygon::EMPTY,
        unclipped: [Vec3::ZERO; MAX_POLYGON_VERTICES],
        vertex_count: 0,
    };

    /// Prepares `ltc` restricted to the convex polygon with the given vertices (relative
    /// to the shading point, local frame, either winding, 3 to 8 of them). Returns `None`
    /// where [`ProjectedPolygon::new`] does for the transformed polygon: bad
    /// counts or coordinates, nothing of it where the LTC lives (`(M⁻¹ω)_z > 0`), or the
    /// shading point in its plane.
    ///
    /// [`prepare`](Self::prepare) does the same in place.
    #[must_use]
    pub fn new(ltc: &Ltc, vertices: &[Vec3]) -> Option<Self> {
        let mut polygon = Self::EMPTY;
        polygon.prepare(ltc, vertices).then_some(polygon)
    }

    /// [`new`](Self::new) in place: writes the prepared polygon into `self` once and
    /// returns `true`, or writes [`EMPTY`](Self::EMPTY) and returns `false`.
    pub fn prepare(&mut self, ltc: &Ltc, vertices: &[Vec3]) -> bool {
        let count = vertices.len();
        self.unclipped = [Vec3::ZERO; MAX_POLYGON_VERTICES];
        // Mapped before the plane's test, whatever its outcome (the first eight vertices
        // at most; cleared again where rejected; the test reads only `vertices`): the
        // test's chain of about 50 cycles lets the vertices' 8- and 4-byte stores reach
        // the cache before the projected prepare loads them as 4- and 8-byte pieces at
        // other offsets, which the store buffer cannot forward (with the test first,
        // the loads came a few instructions after the stores). The same instructions;
        // its time was within the noise of the timings (stop 46).
        ltc.map_to_cosine_space(vertices, &mut self.unclipped);
        let accepted = (3..=MAX_POLYGON_VERTICES).contains(&count) && plane_misses_origin(vertices);
        // An empty slice (rejected input) makes the projected prepare write its empty
        // value.
        let count = if accepted { count } else { 0 };
        if self.transformed.prepare(&self.unclipped[..count]) {
            self.ltc = *ltc;
            self.vertex_count = count as u32;
            true
        } else {
            self.ltc = Ltc::IDENTITY;
            self.unclipped = [Vec3::ZERO; MAX_POLYGON_VERTICES];
            self.vertex_count = 0;
            false
        }
    }

    /// How far (radians, in the cosine's space) outside the transformed polygon `pdf`
    /// continues the density: the smaller of `ROUND_TRIP_TOLERANCE` and
    /// `TOLERANCE_PER_WIDTH` of the polygon's width ([`round_trip_tolerance`] of the
    /// unclipped vertices), never tighter than the transformed polygon's own `pdf`,
    /// which accepts its samples within its slack (the small-polygon path's, bounded
    /// the same way); 0 when empty. Positive for every prepared polygon (`Φ' > 0`).
    /// Out of line: only directions outside some edge's plane of the transformed
    /// polygon (within rounding of its boundary) and the careful path need it.
    #[cold]
    #[inline(never)]
    fn tolerance(&self) -> f32 {
        let count = super::stored_count(self.vertex_count, MAX_POLYGON_VERTICES);
        round_trip_tolerance(
            &self.unclipped,
            count,
            self.transformed.projected_solid_angle(),
        )
        .max(self.transformed.pdf_slack())
    }

    /// `contains_within(w, tolerance())` of the transformed polygon (not
    /// [`Containment::Outside`]), in three steps so
    /// that the slack is computed only for directions within 1e-5 rad of the boundary:
    /// `contains(w)` (the test without the slack, its fast accept) implies it for every
    /// `τ >= 0`, and `contains_within(w, ROUND_TRIP_TOLERANCE)` false excludes it, as
    /// that constant bounds the slack (`min(1e-5, …)` or 0, raised at most to the
    /// small-polygon path's 16 ulps) and the test passes for a larger slack wherever it
    /// passes for a smaller one (each edge's bound `(-τ |n|) |w|` only falls as `τ`
    /// grows; without the small-polygon sampler `contains` is the fast accept of
    /// `contains_within`, with it each edge's `side >= -0 · |n| |w|` implies
    /// `side >= -τ |n| |w|`). The first step inlined, the others out of line.
    ///
    /// `w` is finite (the caller has tested `|w|²` to lie in a finite range), so the
    /// first step is [`contains_finite`](ProjectedPolygon::contains_finite), `contains`
    /// without its test of finiteness (about 12 instructions per sample, stop 47).
    ///
    /// Returns where `w` lies: [`Containment::Inner`] for the first step's accept,
    /// which the polygon light's sample uses (see
    /// [`pdf_of_unit_and_inner`](Self::pdf_of_unit_and_inner)).
    #[inline(always)]
    fn containment(&self, w: Vec3) -> Containment {
        if self.transformed.contains_finite(w) {
            Containment::Inner
        } else if self.within_tolerance(w.x, w.y, w.z) {
            Containment::WithinSlack
        } else {
            Containment::Outside
        }
    }

    /// The last two steps of
    /// [`containment`](Self::containment), out of line: only
    /// directions outside some edge's plane of the transformed polygon (within rounding
    /// of its boundary, for the samples) take them. The direction by its coordinates,
    /// which the caller passes in registers: as a `Vec3` it went through the stack, and
    /// the sample stored it there (and copied it) before every containment test.
    #[cold]
    #[inline(never)]
    fn within_tolerance(&self, x: f32, y: f32, z: f32) -> bool {
        let w = Vec3::new(x, y, z);
        self.transformed.contains_within(w, ROUND_TRIP_TOLERANCE)
            && self.transformed.contains_within(w, self.tolerance())
    }

    /// `∫_P D dω = Φ(M⁻¹P) / π`: the LTC's mass inside the polygon (Heitz 2016, the
    /// polygon integral), in `[0, 1]`; 0 when empty. Clamped to 1: `M⁻¹P` is convex and
    /// clipped to the upper hemisphere, so `Φ ≤ π`, but a polygon 1e5 across seen within
    /// 1e-5 of its plane, stretched by a sharp `M⁻¹`, loses its convexity to rounding
    /// (found by fuzzing: integrals up to 1.5).
    #[inline]
    pub fn integral(&self) -> f32 {
        (self.transformed.projected_solid_angle() * INV_PI).min(1.0)
    }

    /// The LTC this polygon was prepared with.
    #[inline]
    pub fn ltc(&self) -> &Ltc {
        &self.ltc
    }

    /// Draws a direction with density `D(ω) / ∫_P D` inside the polygon. Its `z` may be
    /// at or below 0 (the LTC's mass below the surface), where the BRDF is zero. `u` is
    /// clamped to `[0, 1 − ulp]`. `Sample::NONE` when empty.
    ///
    /// The returned pdf is [`pdf`](Self::pdf) of the returned direction, so
    /// `pdf(sample.dir) == sample.pdf` bit for bit, which MIS weights rely on. The
    /// sampler's own density at the transformed direction, `ω'_z / Φ'` times the
    /// Jacobian `|det M⁻¹| ‖M ω'‖³`, agrees with it up to the rounding of the round
    /// trip `ω' → M ω' → M⁻¹(…)`, which loses up to `ε · cond(M)` in `ω'` and is far
    /// larger than f32 rounding where `ω'` is near the transformed horizon or where
    /// `M` is ill-conditioned (found by fuzzing: 0.1–35%). A direction that the round
    /// trip throws out of the transformed polygon by more than the slack of `pdf` (see
    /// there) is pulled towards an inner direction of the transformed polygon, in the
    /// cosine's space, by the fractions of `INWARD_PULLS` until `pdf` accepts it (a
    /// bias confined to a band of the round trip's rounding along the boundary); where
    /// even the inner direction fails (polygons that the round trip cannot resolve) the
    /// sample is dropped (`Sample::NONE`).
    ///
    /// Always inlined (into the C ABI's `sphera_ltc_polygon_sample`, its one caller in
    /// the crate): out of line it returned the `Sample` through memory, stored as an
    /// 8-byte and two 4-byte pieces, and the C ABI's function loaded its last 8 bytes
    /// (`z` and `pdf`) in one piece, which the store buffer cannot forward (issue 18,
    /// stop 48).
    #[inline(always)]
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        let Some(w_cosine) = self.transformed_sample(u) else {
            return Sample::NONE;
        };
        let sample = self.finish_sample(self.through_m(w_cosine));
        if sample.pdf > 0.0 {
            return sample;
        }
        self.pulled_inward(w_cosine)
    }

    /// The result of [`sample`](Self::sample) for a direction mapped by `M` and its
    /// `unit` ([`through_m`](Self::through_m)): the direction and `pdf`'s own body after
    /// `unit` (the same operations on the same direction, so the same bits). Called
    /// directly on the common path, where it is inlined, and by the rare one.
    #[inline(always)]
    fn finish_sample(&self, (dir, unit): (Vec3, Option<Vec3>)) -> Sample {
        Sample {
            dir,
            pdf: self.pdf_of_unit_or_zero(unit),
        }
    }

    /// [`sample`](Self::sample) (the same bits), the sample's direction as
    /// [`unit`](crate::math::unit) gives it, which `pdf` computes on the way (`None`
    /// only with `Sample::NONE`), for a caller that passes the direction on to functions
    /// that start with `unit` (the polygon light's BRDF), and whether the direction passed
    /// `pdf`'s containment test without its slack ([`LtcSample::inner`]).
    ///
    /// The rare path (the inward pulls) returns only its `Sample`, whose direction's
    /// `unit` is computed again here: the pulls' direction and its `unit` both come from
    /// [`unit_quotient`], whose `unit` is `unit` of its direction bit for bit
    /// (`unit_quotient_is_unit`), so it is the same value. Returned with its `unit`
    /// through memory (the pulls' function is out of line), the pair made the common
    /// path store its own pair to the stack and load it back where the paths merge
    /// (8 stores and 2 loads per polygon light sample, issue 18, stop 47). A pulled
    /// sample counts as not inner: it lies within the slack of the boundary.
    #[inline(always)]
    pub(crate) fn sample_and_unit(&self, u: [f32; 2]) -> LtcSample {
        let Some(w_cosine) = self.transformed_sample(u) else {
            return LtcSample::NONE;
        };
        let (dir, unit) = self.through_m(w_cosine);
        let (pdf, inner) = match unit {
            Some(unit) => self.pdf_of_unit_and_inner(unit),
            None => (0.0, false),
        };
        if pdf > 0.0 {
            return LtcSample {
                sample: Sample { dir, pdf },
                unit,
                inner,
            };
        }
        let pulled = self.pulled_inward(w_cosine);
        LtcSample {
            sample: pulled,
            unit: if pulled.pdf > 0.0 {
                crate::math::unit(pulled.dir)
            } else {
                None
            },
            inner: false,
        }
    }

    /// The transformed polygon's sample `ω'` (in the cosine's space), `None` where it
    /// has none; [`through_m`](Self::through_m) maps it to the sample's direction.
    #[inline(always)]
    fn transformed_sample(&self, u: [f32; 2]) -> Option<Vec3> {
        let s = self.transformed.sample(u);
        (s.pdf > 0.0).then_some(s.dir)
    }

    /// `M ω' / ‖M ω'‖` and its [`unit`](crate::math::unit), with which `pdf` starts
    /// ([`unit_quotient`]). `|M ω'|` is finite and positive for a finite unit direction
    /// and invertible `M`, unless `M` is so large that it overflows; `pdf` then sees a
    /// non-finite or zero direction and returns 0.
    #[inline(always)]
    fn through_m(&self, w_cosine: Vec3) -> (Vec3, Option<Vec3>) {
        unit_quotient(self.ltc.from_cosine_space(w_cosine))
    }

    /// The rare end of [`sample`](Self::sample) and [`sample_and_unit`](Self::sample_and_unit), out of line: the
    /// transformed polygon's sample `w_cosine` went through `M` to a direction that the
    /// pdf does not accept, which only samples within the round trip's rounding of the
    /// boundary do, so the inner direction (the transformed polygon's sample at the
    /// middle of the unit square) is drawn only here.
    #[cold]
    #[inline(never)]
    fn pulled_inward(&self, w_cosine: Vec3) -> Sample {
        let inner = self.transformed.sample([0.5, 0.5]);
        if !(inner.pdf > 0.0) {
            return Sample::NONE;
        }
        crate::sample::INWARD_PULLS
            .iter()
            .map(|&pull| {
                let pulled = crate::math::normalize_or(
                    w_cosine * (1.0 - pull) + inner.dir * pull,
                    inner.dir,
                );
                self.finish_sample(self.through_m(pulled))
            })
            .find(|pulled| pulled.pdf > 0.0)
            .unwrap_or(Sample::NONE)
    }

    /// The density of [`sample`](Self::sample) at `dir`: `D(ω) / ∫_P D` inside the
    /// polygon (computed as the transformed polygon's `ω'_z / Φ'` times the Jacobian
    /// `|det M⁻¹| / ‖M⁻¹ω‖³`), 0 outside. The transformed polygon counts as reaching a
    /// slack `τ` beyond its edges (in the cosine's space), where the round trip's
    /// rounding may put samples: there the formula is continued. `τ` is the smaller of
    /// 1e-5 rad and 2e-5 of the transformed polygon's width `Φ' / P'`, so that
    /// `∫ pdf dω` stays within 2e-5 of 1 (measured by quadrature in the tests). `dir`
    /// is normalised first; zero or non-finite gives 0.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        self.pdf_of_unit_or_zero(crate::math::unit(dir))
    }

    /// [`pdf`](Self::pdf) of a direction already passed through
    /// [`unit`](crate::math::unit) (the rest of its body), for a caller that has that
    /// direction's `unit` for other uses too (the polygon light's BRDF).
    #[inline(always)]
    pub(crate) fn pdf_of_unit(&self, dir: Vec3) -> f32 {
        self.pdf_of_unit_and_inner(dir).0
    }

    /// [`pdf_of_unit`](Self::pdf_of_unit) and whether the transformed direction passed
    /// the containment test's first step, strictly inside every edge's plane of the
    /// transformed polygon and above its horizon (`contains_finite`, without the
    /// slack). Such a direction `ω = M ω'` lies inside the polygon's own edge planes
    /// (`M` maps the planes through the origin and the edges of `M⁻¹P` to those of
    /// `P`), up to the rounding of `M ω'`: the polygon light's sample then takes the
    /// projected sampler's density without its containment test (issue 18, 3).
    #[inline(always)]
    fn pdf_of_unit_and_inner(&self, dir: Vec3) -> (f32, bool) {
        let w = self.ltc.to_cosine_space(dir);
        let length2 = w.length_squared();
        if !strictly_between(length2, 1e-18, 1e18) {
            return (self.pdf_careful(w.x, w.y, w.z), false);
        }
        let containment = self.containment(w);
        if containment == Containment::Outside {
            return (0.0, false);
        }
        (
            self.density_of_transformed(w, length2),
            containment == Containment::Inner,
        )
    }

    /// The density at a direction `ω` inside the polygon (a sample of the polygon's
    /// projected solid angle sampler, the other technique of the polygon light),
    /// without the containment test: `D` is 0 there only below the transformed
    /// horizon, so only `ω'_z > 0` is tested, where [`pdf_of_unit`](Self::pdf_of_unit)
    /// tests every edge plane of the transformed polygon. The same bits wherever that
    /// test accepts `ω'`; for a sample that rounding put outside the polygon by more
    /// than the slack (in the cosine's space) the density formula is continued there.
    /// `dir` is a [`unit`](crate::math::unit) result, as for `pdf_of_unit`.
    #[inline(always)]
    pub(crate) fn pdf_of_unit_inside(&self, dir: Vec3) -> f32 {
        let w = self.ltc.to_cosine_space(dir);
        let length2 = w.length_squared();
        if !strictly_between(length2, 1e-18, 1e18) {
            return self.pdf_careful(w.x, w.y, w.z);
        }
        if !(w.z > 0.0) {
            return 0.0;
        }
        self.density_of_transformed(w, length2)
    }

    /// `(ω'_z / |ω'|) / Φ' · |det M⁻¹| / |ω'|³` with `ω' = M⁻¹ω` as it is, not
    /// normalised: `ω'_z / |ω'|⁴` needs neither a square root nor a normalisation.
    /// `|ω'|⁴` lies in (1e-36, 1e36) for `length2 = |ω'|²` in (1e-18, 1e18) (normal
    /// and finite); a pdf that still overflows (a huge density) or underflows gives 0.
    /// 0 also for an empty polygon (`Φ'⁻¹ = 0`).
    #[inline(always)]
    fn density_of_transformed(&self, w: Vec3, length2: f32) -> f32 {
        let pdf =
            w.z * (self.transformed.density * self.ltc.inverse_determinant) / (length2 * length2);
        // `0 < pdf < ∞` in one comparison of the bits.
        if crate::math::is_positive_finite(pdf) {
            pdf
        } else {
            0.0
        }
    }

    /// [`pdf_of_unit`](Self::pdf_of_unit) of a [`unit`](crate::math::unit) result, 0
    /// for `None` (a zero or non-finite direction), as `pdf` gives. A `match`, always
    /// inlined: through `Option::map_or` the body was called out of line once the slack
    /// moved out of the prepared value (26 instructions per call, stop 46).
    #[inline(always)]
    fn pdf_of_unit_or_zero(&self, unit: Option<Vec3>) -> f32 {
        match unit {
            Some(dir) => self.pdf_of_unit(dir),
            None => 0.0,
        }
    }

    /// [`pdf`](Self::pdf) for a transformed direction whose squared length lies outside
    /// `(1e-18, 1e18)` (only an `M` or `M⁻¹` with entries beyond 1e9 gives one): the density of
    /// the transformed polygon at the direction normalised by its largest component,
    /// divided by `|ω'|³`. The direction by its coordinates, in registers (see
    /// [`within_tolerance`](Self::within_tolerance)).
    #[inline(never)]
    #[cold]
    fn pdf_careful(&self, x: f32, y: f32, z: f32) -> f32 {
        let w = Vec3::new(x, y, z);
        let length = crate::math::length(w);
        let p = self.transformed.pdf_within(w, self.tolerance());
        if !(p > 0.0) || !(length > 0.0) {
            return 0.0;
        }
        let pdf = p * self.ltc.inverse_determinant / (length * length * length);
        if pdf < f32::INFINITY { pdf } else { 0.0 }
    }
}

#[cfg(test)]
#[path = "ltc_tests.rs"]
mod tests;
