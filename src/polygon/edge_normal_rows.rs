//! The inward edge plane normals of a prepared projected polygon, stored as three rows of
//! coordinates (issue 18, item 3: `pdf` of the LTC polygon light runs the containment
//! test twice per light sample).
//!
//! Stored as `[Vec3; 8]`, the eight dot products `n · d` of the containment test were
//! about 78 instructions, most of them shuffles that gathered the normals' x, y and z
//! into lanes. As rows, two groups of four lanes load directly; each lane computes
//! `(n_x d_x + n_y d_y) + n_z d_z`, the order of `Vec3::dot`, and `sqrt` of `n · n` as
//! `Vec3::length`, with the same correctly rounded `f32` operations, so every lane has
//! the bits of the scalar form.

use crate::math::{LANES, load4, sqrt4, store4};
use crate::{MAX_POLYGON_VERTICES, Vec3};
use glam::{BVec4A, Vec4};

/// Edge plane normals `n_j`, `j < 8`, as coordinate rows (zero in unused slots, whose
/// dot product 0 passes every test below).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct EdgeNormalRows {
    x: [f32; MAX_POLYGON_VERTICES],
    y: [f32; MAX_POLYGON_VERTICES],
    z: [f32; MAX_POLYGON_VERTICES],
}

// Two groups of four lanes cover the slots.
const _: () = assert!(MAX_POLYGON_VERTICES == 2 * LANES);

impl EdgeNormalRows {
    /// Every normal zero: every direction passes.
    pub(crate) const ZERO: Self = Self {
        x: [0.0; MAX_POLYGON_VERTICES],
        y: [0.0; MAX_POLYGON_VERTICES],
        z: [0.0; MAX_POLYGON_VERTICES],
    };

    /// Sets normal `j`.
    #[inline(always)]
    pub(crate) fn set(&mut self, j: usize, n: Vec3) {
        self.x[j] = n.x;
        self.y[j] = n.y;
        self.z[j] = n.z;
    }

    /// Sets the normals `first..first + 4` from their coordinates' lanes, each lane not
    /// in `keep` as 0 (a slot past the polygon, as in [`ZERO`](Self::ZERO)): one
    /// 16-byte store per row where `set` of each normal gathered single words.
    #[inline(always)]
    pub(crate) fn store4(&mut self, first: usize, [x, y, z]: [Vec4; 3], keep: BVec4A) {
        let put = |row: &mut [f32; MAX_POLYGON_VERTICES], v: Vec4| {
            store4(Vec4::select(keep, v, Vec4::ZERO), row, first);
        };
        put(&mut self.x, x);
        put(&mut self.y, y);
        put(&mut self.z, z);
    }

    /// Normal `j`.
    #[inline(always)]
    #[must_use]
    pub(crate) fn get(&self, j: usize) -> Vec3 {
        Vec3::new(self.x[j], self.y[j], self.z[j])
    }

    /// The normals as `Vec3`s (the careful paths, which work on them).
    #[must_use]
    pub(crate) fn vectors(&self) -> [Vec3; MAX_POLYGON_VERTICES] {
        core::array::from_fn(|j| self.get(j))
    }

    /// Sets every normal from an array.
    pub(crate) fn set_all(&mut self, normals: &[Vec3; MAX_POLYGON_VERTICES]) {
        for (j, n) in normals.iter().enumerate() {
            self.set(j, *n);
        }
    }

    /// `n · d` of the four normals from slot `first`, rounded as `Vec3::dot`.
    #[inline(always)]
    fn dots4(&self, first: usize, d: Vec3) -> Vec4 {
        let (x, y, z) = (
            load4(&self.x, first),
            load4(&self.y, first),
            load4(&self.z, first),
        );
        (x * d.x + y * d.y) + z * d.z
    }

    /// `|n|` of the four normals from slot `first`, rounded as `Vec3::length`.
    #[inline(always)]
    fn lengths4(&self, first: usize) -> Vec4 {
        let (x, y, z) = (
            load4(&self.x, first),
            load4(&self.y, first),
            load4(&self.z, first),
        );
        sqrt4((x * x + y * y) + z * z)
    }

    /// Whether `n_j · d >= 0` for every `j` (false where a dot product is NaN, as the
    /// scalar comparison is).
    #[inline(always)]
    #[must_use]
    pub(crate) fn all_on_inner_side(&self, d: Vec3) -> bool {
        let passes = |first| self.dots4(first, d).cmpge(Vec4::ZERO);
        (passes(0) & passes(LANES)).all()
    }

    /// Whether `n_j · d >= -tolerance |n_j| length` for every `j`, each side rounded as
    /// the scalar `n.dot(d) >= -tolerance * n.length() * length`.
    #[inline(always)]
    #[must_use]
    pub(crate) fn all_within(&self, d: Vec3, tolerance: f32, length: f32) -> bool {
        let passes = |first| -> BVec4A {
            self.dots4(first, d)
                .cmpge((Vec4::splat(-tolerance) * self.lengths4(first)) * length)
        };
        (passes(0) & passes(LANES)).all()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::Rng;

    /// The lanes decide as the scalar tests of `Vec3` normals do, on random normals and
    /// directions (some of them on a normal's plane, where `n · d` rounds near 0), zero
    /// slots, tiny and huge magnitudes, and NaN.
    #[test]
    fn rows_decide_as_the_scalar_tests() {
        let mut rng = Rng::new(36);
        let (mut inside, mut outside, mut within) = (0, 0, 0);
        for trial in 0..200_000 {
            let mut draw = || rng.signed_log_uniform(-20.0, 20.0) as f32;
            let mut normals = [Vec3::ZERO; MAX_POLYGON_VERTICES];
            let used = 3 + trial % 6;
            for n in normals.iter_mut().take(used) {
                *n = Vec3::new(draw(), draw(), draw());
            }
            let mut d = Vec3::new(draw(), draw(), draw());
            if trial % 3 == 0 {
                // On the plane of normal 0, up to rounding.
                let n = normals[0];
                d -= n * (n.dot(d) / n.length_squared());
            }
            if trial % 1000 == 1 {
                d.y = f32::NAN;
            }
            if trial % 2 == 0 {
                // Most normals facing d, so that the tests pass often.
                for n in normals.iter_mut().take(used) {
                    if n.dot(d) < 0.0 && trial % 4 == 0 {
                        *n = -*n;
                    }
                }
            }
            let mut rows = EdgeNormalRows::ZERO;
            rows.set_all(&normals);
            assert_eq!(rows.vectors(), normals);
            let scalar = normals.iter().all(|n| n.dot(d) >= 0.0);
            assert_eq!(rows.all_on_inner_side(d), scalar, "{normals:?} {d:?}");
            let (tolerance, length) = (1e-6 * (1 + trial % 7) as f32, d.length());
            let scalar_within = normals
                .iter()
                .all(|n| n.dot(d) >= -tolerance * n.length() * length);
            assert_eq!(
                rows.all_within(d, tolerance, length),
                scalar_within,
                "{normals:?} {d:?}"
            );
            inside += scalar as u32;
            outside += !scalar_within as u32;
            within += (scalar_within && !scalar) as u32;
        }
        // Each outcome is exercised.
        assert!(
            inside > 10_000 && outside > 10_000 && within > 100,
            "{inside} {outside} {within}"
        );
    }
}
