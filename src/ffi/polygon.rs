//! Polygonal lights: clipping to the upper hemisphere, the solid angle sampler
//! (Peters 2021) and the baselines of Turk and Arvo.
//!
//! Vertices are given relative to the shading point in the local frame (z = normal),
//! convex, in either winding, 3 to `SPHERA_MAX_POLYGON_VERTICES` of them.
//!
//! Every polygon `prepare` writes its result once, in place, into the caller's struct
//! (the empty value only on failure): nothing prepared is copied.
use super::types::{SpheraVec3, read_polygon};
use crate::{MAX_POLYGON_VERTICES, Vec3};

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

/// Clips the convex polygon `vertices[0..count]` to z >= 0 in place and returns the new count:
/// 0 when nothing lies above the horizon (or for a null `vertices` or a `count` out of range),
/// else 3 to `SPHERA_MAX_POLYGON_VERTICES`. New vertices lie exactly on z = 0, winding kept. A
/// polygon of the maximum count gives 0 unless wholly above the horizon (no room for a vertex).
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
