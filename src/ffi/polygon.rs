//! Polygonal lights: clipping to the upper hemisphere, the solid angle sampler
//! (Peters 2021) and the baselines of Turk and Arvo.
//!
//! Vertices are given relative to the shading point in the local frame (z = normal),
//! convex, in either winding, 3 to `SPHERA_MAX_POLYGON_VERTICES` of them.
//!
//! Every polygon `prepare` writes its result once, in place, into the caller's struct
//! (the empty value only on failure): nothing prepared is copied.

use super::types::{SpheraSample, SpheraVec3, read_polygon, with_ref};
use crate::polygon::SolidAnglePolygon;
use crate::polygon::baselines::{ArvoPolygon, TurkPolygon};
use crate::{MAX_POLYGON_VERTICES, Sample, Vec3};

/// The shared body of every `prepare`: `prepare(*out, vertices)` in place, which writes
/// the prepared value or the empty one; bad pointers or counts hand it no vertices, which
/// every in-place `prepare` rejects (writing the empty value). Nothing is copied but the
/// vertices (96 bytes at most).
///
/// # Safety
///
/// As for the `prepare` functions: `out` null or writable, `vertices` null or pointing
/// to `count` readable vertices. `T` holds only `f32` and `u32` fields (the prepared
/// structs of the header), for which any bytes that C left in `*out` are a valid value,
/// and every in-place `prepare` writes all that it reads back.
#[inline(always)]
pub(super) unsafe fn prepare<T>(
    out: *mut T,
    vertices: *const SpheraVec3,
    count: u32,
    prepare: impl FnOnce(&mut T, &[Vec3]) -> bool,
) -> bool {
    // SAFETY: `out` is null or writable memory for a `T` (the caller's contract), and
    // every bit pattern is a valid `T` (above).
    let Some(out) = (unsafe { out.as_mut() }) else {
        return false;
    };
    // SAFETY: forwarded from the caller.
    prepare(out, unsafe { polygon_slice(vertices, count) })
}

/// The `count` vertices at `vertices` as a slice, read in place (the 96 bytes of a copy
/// are a tenth of a lean prepare), or an empty slice when `vertices` is null or `count`
/// lies outside `3..=SPHERA_MAX_POLYGON_VERTICES`.
///
/// # Safety
///
/// When non-null and `count` is in range, `vertices` must point to `count` readable,
/// initialised `SpheraVec3`s that nothing writes while the slice lives (the header: they
/// must not overlap `*out`).
#[inline(always)]
unsafe fn polygon_slice<'a>(vertices: *const SpheraVec3, count: u32) -> &'a [Vec3] {
    let count = count as usize;
    if vertices.is_null() || !(3..=MAX_POLYGON_VERTICES).contains(&count) {
        return &[];
    }
    // SAFETY: `SpheraVec3` and `Vec3` have the same layout (asserted in `types.rs`), and
    // the caller guarantees `count` readable elements that nothing writes meanwhile.
    unsafe { core::slice::from_raw_parts(vertices.cast::<Vec3>(), count) }
}

/// Clips the convex polygon `vertices[0..count]` to the upper hemisphere (z >= 0) in
/// place and returns the new vertex count: 0 when nothing of the polygon lies above the
/// horizon, otherwise 3 to `SPHERA_MAX_POLYGON_VERTICES`. Vertices created by the clip
/// lie exactly on z = 0; the winding is kept. A polygon with
/// `SPHERA_MAX_POLYGON_VERTICES` vertices is kept only when it lies entirely above the
/// horizon (z > 0), otherwise the result is 0, since clipping could need one vertex
/// more than the array holds.
///
/// Returns 0 and leaves the array untouched when `vertices` is null or `count` lies
/// outside 3..=`SPHERA_MAX_POLYGON_VERTICES`.
///
/// # Safety
///
/// `vertices` must be null or point to an array of `SPHERA_MAX_POLYGON_VERTICES`
/// writable `SpheraVec3`s whose first `count` are initialised (the clipped polygon may
/// have more vertices than the input).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_polygon_clip(vertices: *mut SpheraVec3, count: u32) -> u32 {
    // SAFETY: forwarded from the caller.
    let Some((mut local, count)) = (unsafe { read_polygon(vertices, count) }) else {
        return 0;
    };
    let clipped =
        crate::polygon::clip_to_upper_hemisphere(&mut local, count).min(MAX_POLYGON_VERTICES);
    for (i, vertex) in local.iter().enumerate().take(clipped) {
        // SAFETY: `vertices` is non-null and the caller guarantees room for
        // `SPHERA_MAX_POLYGON_VERTICES` elements; `i < clipped <= MAX_POLYGON_VERTICES`.
        unsafe { vertices.add(i).write((*vertex).into()) };
    }
    clipped as u32
}

/// Prepares the solid angle sampler (Peters 2021) for the convex polygon
/// `vertices[0..count]`: positions relative to the shading point, not normalised, in
/// either winding. The polygon need not be clipped; clip it first with
/// `sphera_polygon_clip` to sample only the part above the horizon.
///
/// Returns `false` when `out` is null, when `vertices` is null, when `count` lies
/// outside 3..=`SPHERA_MAX_POLYGON_VERTICES`, when a coordinate is NaN or infinite, or
/// when the polygon subtends no solid angle, in particular when its vertices lie exactly
/// in a plane through the shading point (decided exactly, at any tilt). Unless `out` is
/// null, a `false` return writes the empty polygon into `*out`: its samples have pdf 0,
/// its `pdf` is 0 and its solid angle is 0, whatever `*out` held before.
///
/// # Safety
///
/// `out` must be null or point to writable memory for one `SpheraSolidAnglePolygon`;
/// `vertices` must be null or point to `count` readable `SpheraVec3`s that do not overlap `*out`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_polygon_prepare(
    out: *mut SolidAnglePolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, SolidAnglePolygon::prepare) }
}

/// Draws a direction uniformly distributed in the solid angle of `polygon` from the
/// random numbers `u0`, `u1` in [0, 1) (values outside are clamped by the library).
/// The pdf of the sample is 1 / solid angle per steradian.
///
/// Returns `{dir = (0, 0, 1), pdf = 0}` (no sample) when `polygon` is null or empty.
/// `dir` is always a finite unit vector.
///
/// # Safety
///
/// `polygon` must be null or point to a `SpheraSolidAnglePolygon` written by
/// `sphera_solid_angle_polygon_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_polygon_sample(
    polygon: *const SolidAnglePolygon,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe {
        with_ref(polygon, Sample::NONE.into(), |polygon| {
            polygon.sample([u0, u1]).into()
        })
    }
}

/// The density per steradian with which `sphera_solid_angle_polygon_sample` produces
/// the direction `dir` (need not be normalised): 1 / solid angle inside the polygon
/// (boundary included, and up to a slack outside it where rounding puts samples drawn
/// next to an edge: the smaller of 16 ulps, 1.9e-6 rad, and 2e-5 of the polygon's width,
/// solid angle over perimeter), 0 outside it. Every sample's pdf is this function's
/// value at its direction, bit for bit.
///
/// Returns 0 when `polygon` is null or empty, and for a zero or non-finite `dir`.
///
/// # Safety
///
/// `polygon` must be null or point to a `SpheraSolidAnglePolygon` written by
/// `sphera_solid_angle_polygon_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_polygon_pdf(
    polygon: *const SolidAnglePolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// The solid angle (in steradians) that the polygon subtends.
///
/// Returns 0 when `polygon` is null or empty.
///
/// # Safety
///
/// `polygon` must be null or point to a `SpheraSolidAnglePolygon` written by
/// `sphera_solid_angle_polygon_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_polygon_solid_angle(
    polygon: *const SolidAnglePolygon,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.solid_angle()) }
}

/// Inverts `sphera_solid_angle_polygon_sample`: finds the random numbers `*u0`, `*u1`
/// in [0, 1] for which the sampler produces the unit direction `dir`.
///
/// Returns `false` when `polygon`, `u0` or `u1` is null, when the polygon is empty, or
/// when `dir` does not point into the polygon; `*u0` and `*u1` are then set to 0 where
/// they are non-null.
///
/// # Safety
///
/// `polygon` must be null or point to a `SpheraSolidAnglePolygon` written by
/// `sphera_solid_angle_polygon_prepare`; `u0` and `u1` must each be null or point to a
/// writable `float`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_solid_angle_polygon_invert(
    polygon: *const SolidAnglePolygon,
    dir: SpheraVec3,
    u0: *mut f32,
    u1: *mut f32,
) -> bool {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    let inverted = match unsafe { polygon.as_ref() } {
        Some(polygon) if !u0.is_null() && !u1.is_null() => polygon.invert(dir.into()),
        _ => None,
    };
    let [v0, v1] = inverted.unwrap_or([0.0, 0.0]);
    if !u0.is_null() {
        // SAFETY: non-null, and the caller guarantees it is writable.
        unsafe { u0.write(v0) };
    }
    if !u1.is_null() {
        // SAFETY: non-null, and the caller guarantees it is writable.
        unsafe { u1.write(v1) };
    }
    inverted.is_some()
}

/// Prepares Turk's baseline for the convex polygon `vertices[0..count]`: points
/// uniformly distributed over the polygon's area, with the density converted to solid
/// angle.
///
/// Returns `false` when `out` is null, when `vertices` is null, when `count` lies
/// outside 3..=`SPHERA_MAX_POLYGON_VERTICES`, when a coordinate is NaN or infinite,
/// when a coordinate exceeds about 1e18 (2^60) (so that the edge
/// planes that `sphera_turk_polygon_pdf` computes stay finite), or when the polygon is
/// degenerate. Unless `out` is null, a `false` return writes the empty polygon into
/// `*out`: its samples have pdf 0, its `pdf` is 0 and its area is 0, whatever `*out`
/// held before.
///
/// # Safety
///
/// `out` must be null or point to writable memory for one `SpheraTurkPolygon`;
/// `vertices` must be null or point to `count` readable `SpheraVec3`s that do not overlap `*out`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_turk_polygon_prepare(
    out: *mut TurkPolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, TurkPolygon::prepare) }
}

/// Draws a direction towards a point uniformly distributed over the polygon's area from
/// the random numbers `u0`, `u1` in [0, 1) (values outside are clamped by the library).
/// The pdf is distance² / (area · |cos θ|) per steradian, with θ the angle between the
/// direction and the polygon's normal, computed as `sphera_turk_polygon_pdf` computes it:
/// equal to it bit for bit wherever that finds the direction inside the polygon.
///
/// Returns `{dir = (0, 0, 1), pdf = 0}` (no sample) when `polygon` is null or empty.
/// `dir` is always a finite unit vector.
///
/// # Safety
///
/// `polygon` must be null or point to a `SpheraTurkPolygon` written by
/// `sphera_turk_polygon_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_turk_polygon_sample(
    polygon: *const TurkPolygon,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe {
        with_ref(polygon, Sample::NONE.into(), |polygon| {
            polygon.sample([u0, u1]).into()
        })
    }
}

/// The density per steradian with which `sphera_turk_polygon_sample` produces the unit
/// direction `dir`; 0 when `dir` misses the polygon.
///
/// Returns 0 when `polygon` is null or empty.
///
/// # Safety
///
/// `polygon` must be null or point to a `SpheraTurkPolygon` written by
/// `sphera_turk_polygon_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_turk_polygon_pdf(
    polygon: *const TurkPolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// The area of the polygon (in squared units of the vertex coordinates).
///
/// Returns 0 when `polygon` is null or empty.
///
/// # Safety
///
/// `polygon` must be null or point to a `SpheraTurkPolygon` written by
/// `sphera_turk_polygon_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_turk_polygon_area(polygon: *const TurkPolygon) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.area()) }
}

/// Prepares Arvo's 1995 baseline for the convex polygon `vertices[0..count]`: uniform
/// sampling of the solid angle, triangle by triangle.
///
/// Returns `false` when `out` is null, when `vertices` is null, when `count` lies
/// outside 3..=`SPHERA_MAX_POLYGON_VERTICES`, when a coordinate is NaN or infinite, or
/// when the polygon subtends no solid angle, in particular when its vertices lie exactly
/// in a plane through the shading point (decided exactly, at any tilt). Unless `out` is
/// null, a `false` return writes the empty polygon into `*out`: its samples have pdf 0,
/// its `pdf` is 0 and its solid angle is 0, whatever `*out` held before.
///
/// # Safety
///
/// `out` must be null or point to writable memory for one `SpheraArvoPolygon`;
/// `vertices` must be null or point to `count` readable `SpheraVec3`s that do not overlap `*out`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_polygon_prepare(
    out: *mut ArvoPolygon,
    vertices: *const SpheraVec3,
    count: u32,
) -> bool {
    // SAFETY: forwarded from the caller.
    unsafe { prepare(out, vertices, count, ArvoPolygon::prepare) }
}

/// Draws a direction uniformly distributed in the solid angle of `polygon` with Arvo's
/// method from the random numbers `u0`, `u1` in [0, 1) (values outside are clamped by
/// the library). The pdf of the sample is 1 / solid angle per steradian, as
/// `sphera_arvo_polygon_pdf` gives it for the direction.
///
/// Returns `{dir = (0, 0, 1), pdf = 0}` (no sample) when `polygon` is null or empty, and
/// when Arvo's construction in f32 puts the direction outside the polygon. A baseline:
/// **unreliable for polygons below about 1e-2 rad across**, where such draws are many
/// (measured on quads at distance 1: 0.25% of the draws at 2e-2 rad across, 7.6% at
/// 2e-3, 20% at 2e-4) and its f32 solid angle is inaccurate (docs/polygon-lights.md). `dir` is always a
/// finite unit vector.
///
/// # Safety
///
/// `polygon` must be null or point to a `SpheraArvoPolygon` written by
/// `sphera_arvo_polygon_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_polygon_sample(
    polygon: *const ArvoPolygon,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe {
        with_ref(polygon, Sample::NONE.into(), |polygon| {
            polygon.sample([u0, u1]).into()
        })
    }
}

/// The density per steradian with which `sphera_arvo_polygon_sample` produces the unit
/// direction `dir`: 1 / solid angle inside the polygon, 0 outside it.
///
/// Returns 0 when `polygon` is null or empty.
///
/// # Safety
///
/// `polygon` must be null or point to a `SpheraArvoPolygon` written by
/// `sphera_arvo_polygon_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_polygon_pdf(
    polygon: *const ArvoPolygon,
    dir: SpheraVec3,
) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.pdf(dir.into())) }
}

/// The solid angle (in steradians) that the polygon subtends, as Arvo's method computes
/// it.
///
/// Returns 0 when `polygon` is null or empty.
///
/// # Safety
///
/// `polygon` must be null or point to a `SpheraArvoPolygon` written by
/// `sphera_arvo_polygon_prepare`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sphera_arvo_polygon_solid_angle(polygon: *const ArvoPolygon) -> f32 {
    // SAFETY: the caller guarantees that a non-null `polygon` points to a prepared value.
    unsafe { with_ref(polygon, 0.0, |polygon| polygon.solid_angle()) }
}
