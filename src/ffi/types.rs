//! Plain data shared by every family of the C ABI.

use crate::{Sample, Vec3};

/// The most vertices a polygon may have, in the C ABI: the length of the array that
/// `sphera_polygon_clip` works on and the largest `count` that a `prepare` accepts.
pub const SPHERA_MAX_POLYGON_VERTICES: u32 = 8;

const _: () = assert!(SPHERA_MAX_POLYGON_VERTICES as usize == crate::MAX_POLYGON_VERTICES);

/// A 3D vector of `float`s (a point or a direction in the local shading frame, whose z
/// axis is the surface normal).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpheraVec3 {
    /// First tangent coordinate.
    pub x: f32,
    /// Second tangent coordinate.
    pub y: f32,
    /// Coordinate along the normal.
    pub z: f32,
}

// The header shows the core's `Vec3` (inside the prepared structs and `SpheraSample`)
// under the name `SpheraVec3`, so both must have the same layout.
const _: () = {
    assert!(core::mem::size_of::<SpheraVec3>() == core::mem::size_of::<Vec3>());
    assert!(core::mem::align_of::<SpheraVec3>() == core::mem::align_of::<Vec3>());
    assert!(core::mem::offset_of!(SpheraVec3, x) == core::mem::offset_of!(Vec3, x));
    assert!(core::mem::offset_of!(SpheraVec3, y) == core::mem::offset_of!(Vec3, y));
    assert!(core::mem::offset_of!(SpheraVec3, z) == core::mem::offset_of!(Vec3, z));
};

impl From<SpheraVec3> for Vec3 {
    #[inline(always)]
    fn from(v: SpheraVec3) -> Vec3 {
        Vec3::new(v.x, v.y, v.z)
    }
}

impl From<Vec3> for SpheraVec3 {
    #[inline(always)]
    fn from(v: Vec3) -> SpheraVec3 {
        SpheraVec3 {
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }
}

/// A sampled direction and its density per steradian, as the C ABI returns it.
///
/// `pdf == 0` means that no sample could be drawn; `dir` is then still finite (it is
/// `(0, 0, 1)`), so that a caller that forgets to check never sees NaN.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpheraSample {
    /// Unit direction in the local frame.
    pub dir: SpheraVec3,
    /// Density per steradian; 0 when there is no sample.
    pub pdf: f32,
}

impl From<Sample> for SpheraSample {
    #[inline(always)]
    fn from(sample: Sample) -> SpheraSample {
        SpheraSample {
            dir: sample.dir.into(),
            pdf: sample.pdf,
        }
    }
}

/// `f` applied to the value behind `pointer`, or `default` when `pointer` is null: the
/// null-pointer contract of every getter and sampler of the C ABI.
///
/// # Safety
///
/// `pointer` must be null or point to a valid, initialised `T`.
#[inline(always)]
pub(crate) unsafe fn with_ref<T, R>(pointer: *const T, default: R, f: impl FnOnce(&T) -> R) -> R {
    // SAFETY: forwarded from the caller.
    match unsafe { pointer.as_ref() } {
        Some(value) => f(value),
        None => default,
    }
}

/// A sampler whose common sample the C entry point runs inline, with the rest (empty
/// values, rare inputs, careful paths) behind one call: see [`sample_common_or_rare`].
pub(crate) trait CommonAndRareSamples {
    /// The sample of an ordinary draw, or `None` where [`sample_rare`](Self::sample_rare)
    /// must decide; where it gives a sample, the same bits as the sampler's `sample`.
    fn sample_common(&self, u: [f32; 2]) -> Option<Sample>;
    /// The sampler's `sample` for every draw (called where `sample_common` gives `None`).
    fn sample_rare(&self, u: [f32; 2]) -> Sample;
}

/// The body of a sample entry point of the C ABI for a sampler with a common path: the
/// common case inline, the rare one by a call out of line with the entry point's
/// signature (so that the arguments and the result stay in their registers, and only
/// the rare path sets up a stack frame; returning the sample through the stack had
/// failed store-to-load forwarding), and the empty sample for a null pointer.
///
/// # Safety
///
/// `pointer` must be null or point to a valid, initialised `T`.
#[inline(always)]
pub(crate) unsafe fn sample_common_or_rare<T: CommonAndRareSamples>(
    pointer: *const T,
    u0: f32,
    u1: f32,
) -> SpheraSample {
    // SAFETY: forwarded from the caller.
    let Some(sampler) = (unsafe { pointer.as_ref() }) else {
        return Sample::NONE.into();
    };
    match sampler.sample_common([u0, u1]) {
        Some(sample) => sample.into(),
        None => sample_rare(sampler, u0, u1),
    }
}

/// The rare path of [`sample_common_or_rare`], out of line with the entry points'
/// signature.
#[inline(never)]
extern "C" fn sample_rare<T: CommonAndRareSamples>(sampler: &T, u0: f32, u1: f32) -> SpheraSample {
    sampler.sample_rare([u0, u1]).into()
}

/// Copies `count` vertices from C memory into a fixed array, or `None` when `vertices`
/// is null or `count` lies outside `3..=SPHERA_MAX_POLYGON_VERTICES`.
///
/// # Safety
///
/// When non-null and `count` is in range, `vertices` must point to `count` readable,
/// initialised `SpheraVec3`s.
#[inline(always)]
pub(crate) unsafe fn read_polygon(
    vertices: *const SpheraVec3,
    count: u32,
) -> Option<([Vec3; crate::MAX_POLYGON_VERTICES], usize)> {
    let count = count as usize;
    if vertices.is_null() || !(3..=crate::MAX_POLYGON_VERTICES).contains(&count) {
        return None;
    }
    let mut local = [Vec3::ZERO; crate::MAX_POLYGON_VERTICES];
    for (i, slot) in local.iter_mut().enumerate().take(count) {
        // SAFETY: the caller guarantees `count` readable elements and `i < count`.
        *slot = unsafe { vertices.add(i).read() }.into();
    }
    Some((local, count))
}
