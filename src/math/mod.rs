//! Numerics shared by every technique: error-free products, a stable cross product,
//! `atan` forms for arguments of known sign, orthonormal frames, `f32` bit helpers and the
//! normalisation of direction arguments.

mod atan;
mod atan_lanes;
mod bits;
mod fast_functions_generated;
mod frame;
mod lanes;
mod length;
mod products;
mod roots;
mod sin_cos;
mod sqrt;
mod unit;

pub(crate) use atan::atan_fast_nonneg4;
pub use atan::{
    atan_fast_nonneg, atan_unit, atan_unit_estrin, atan_unit_estrin4, atan2_upper_half_plane,
};
pub(crate) use atan_lanes::{atanf4, atanf4_below_7_16};
pub use bits::{
    copy_sign, is_sign_negative, opaque, select_bits, select_bits4, sign_mask, with_sign_of_product,
};
pub use frame::{Frame, orthonormal_basis};
pub(crate) use lanes::{
    LANES, atan2_upper_half_plane4, atan2_upper_half_plane4_small_first, cross_precise4,
    cross3_lanes, difference_of_products_unless_half_cancels4, difference_of_products4,
    finite_or_zero4, lane_starts, load4, max4, min4, sqrt4, store_record_words4, store4,
};
pub(crate) use length::is_positive_finite;
pub(crate) use length::{
    length, normalize_or, normalize_or_predicted, normalize_or_zero, try_normalize,
};
pub(crate) use products::plain_difference_is_certain;
pub use products::{
    HAS_HARDWARE_FMA, cross_precise, cross_with_residual, determinant_is_exactly_zero,
    difference_of_products, difference_of_products_sign, difference_of_products_unless_cancelling,
    difference_of_products_unless_half_cancels, dot_precise, fma, two_product, two_sum,
};
pub(crate) use roots::safeguarded_newton_step;
pub use sin_cos::sin_cos_0_to_pi;
pub(crate) use sin_cos::{sin_cos_of_half, sin_cos_of_quarter_turns, sin_cos_of_turn};
pub use sqrt::sqrtf;
pub(crate) use unit::{
    UNIT_TOLERANCE, is_unit, is_unit_output, normalize_scaled, unit, unit_if_needed,
    unit_if_needed_or_none,
};

/// `c[0] + s (c[1] + s (c[2] + …))` by Horner's rule, one multiplication and one
/// addition per coefficient after the last, each rounded (never fused: the bits do not
/// depend on the target's FMA).
#[inline(always)]
fn horner<const N: usize>(s: f32, c: &[f32; N]) -> f32 {
    // Starting from the last coefficient rather than from 0 saves the `0 * s`, which
    // the compiler may not fold (it is NaN for infinite `s`).
    let mut acc = c[N - 1];
    let mut i = N - 1;
    while i > 0 {
        i -= 1;
        acc = acc * s + c[i];
    }
    acc
}

/// Sweeps over `f32` bit patterns for the fast functions' exhaustive tests.
#[cfg(test)]
mod test_sweep {
    use std::vec::Vec;

    /// The largest errors of a function against its `f64` values.
    #[derive(Clone, Copy, Debug, Default)]
    pub struct Errors {
        /// In ulps of the correctly rounded `f32` value (the `f32` spacing at the exact
        /// value's binade, 2^-149 below the normal range).
        pub ulps: f64,
        pub ulps_at: f32,
        pub absolute: f64,
        pub absolute_at: f32,
        pub relative: f64,
    }

    impl Errors {
        pub fn add(&mut self, x: f32, got: f32, exact: f64) {
            let error = (got as f64 - exact).abs();
            // The unbiased exponent of the f64 `exact` (bits 52..=62 hold it with bias
            // 1023); an f32 ulp is 2^(exponent - 23), at least 2^-149.
            let exponent = ((exact.abs().to_bits() >> 52) as i32) - 1023;
            let ulp = libm::ldexp(1.0, exponent.max(-126) - 23);
            let ulps = error / ulp;
            if !(ulps <= self.ulps) {
                (self.ulps, self.ulps_at) = (ulps, x);
            }
            if !(error <= self.absolute) {
                (self.absolute, self.absolute_at) = (error, x);
            }
            if exact != 0.0 {
                self.relative = self.relative.max(error / exact.abs());
            }
        }

        pub fn merge(self, other: Errors) -> Errors {
            let mut out = self;
            if other.ulps > out.ulps {
                (out.ulps, out.ulps_at) = (other.ulps, other.ulps_at);
            }
            if other.absolute > out.absolute {
                (out.absolute, out.absolute_at) = (other.absolute, other.absolute_at);
            }
            out.relative = out.relative.max(other.relative);
            out
        }
    }

    /// The `f32` with bit patterns `first, first + stride, …` up to `last`, and `last`.
    pub fn points(first: u32, last: u32, stride: u32) -> impl Iterator<Item = f32> {
        let steps = (last - first) / stride;
        let aligned = first + steps * stride == last;
        (0..=steps)
            .map(move |k| first + k * stride)
            .chain((!aligned).then_some(last))
            .map(f32::from_bits)
    }

    /// Splits the bit patterns `lo, lo + stride, …` up to `hi` (and `hi` itself) into
    /// chunks, runs `work(first, last, stride)` on each on all available threads, and
    /// returns the results in the chunks' order.
    pub fn sweep<R: Send>(
        lo: u32,
        hi: u32,
        stride: u32,
        work: impl Fn(u32, u32, u32) -> R + Sync,
    ) -> Vec<R> {
        const CHUNKS: u32 = 256;
        let steps = (hi - lo) / stride;
        let per_chunk = steps.div_ceil(CHUNKS).max(1);
        let mut bounds = Vec::new();
        let mut first = lo;
        loop {
            let last_step = (first - lo) / stride + per_chunk - 1;
            let last = if last_step >= steps {
                hi
            } else {
                lo + last_step * stride
            };
            bounds.push((first, last));
            if last == hi {
                break;
            }
            first = last + stride;
        }
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        let next = core::sync::atomic::AtomicUsize::new(0);
        let mut results: Vec<(usize, R)> = std::thread::scope(|scope| {
            let handles: Vec<_> = (0..threads)
                .map(|_| {
                    scope.spawn(|| {
                        let mut mine = Vec::new();
                        loop {
                            let i = next.fetch_add(1, core::sync::atomic::Ordering::Relaxed);
                            let Some(&(first, last)) = bounds.get(i) else {
                                break;
                            };
                            mine.push((i, work(first, last, stride)));
                        }
                        mine
                    })
                })
                .collect();
            handles
                .into_iter()
                .flat_map(|h| h.join().expect("sweep thread"))
                .collect()
        });
        results.sort_by_key(|(i, _)| *i);
        results.into_iter().map(|(_, r)| r).collect()
    }
}
