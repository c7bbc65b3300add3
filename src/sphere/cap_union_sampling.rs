//! Uniform sampling of the union of two spherical caps (Dupuy et al. 2017, Sec. 4: SPTDs
//! over sets of caps; with [`Cap::complement`] and [`CapIntersection`], the sets that
//! the paper's algebra of caps gives).
//!
//! `A ∪ B` is the disjoint union of `A` and `B ∖ A = B ∩ Ā`, and the complement of a cap
//! is a cap, so `Ω(A ∪ B) = Ω(A) + Ω(B ∩ Ā)`: a sum of two non-negative exact terms,
//! without the cancellation of `Ω(A) + Ω(B) − Ω(A ∩ B)` when one cap nearly contains the
//! other. A uniform sample of `A ∪ B` is a uniform sample of `A` with probability
//! `Ω(A) / Ω(A ∪ B)` and otherwise a uniform sample of `B ∩ Ā` ([`CapIntersection`]); the
//! first random number selects the piece and is rescaled into it, so the map stays
//! invertible. The pdf is `1 / Ω(A ∪ B)` inside either cap and 0 outside.
//!
//! Hard cases (tested): disjoint caps, nested caps (either way round), equal caps, caps
//! wider than a hemisphere whose union is the whole sphere, a tiny cap on a large one's
//! rim, empty caps.

use super::cap::Cap;
use super::cap_intersection_sampling::CapIntersection;
use crate::Sample;
use crate::sample::{clamp_inverted, clamp_random};
use glam::Vec3;

/// Two caps prepared for uniform sampling of their union.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CapUnion {
    /// `A`, sampled with probability `first_share`.
    first: Cap,
    /// `B ∩ Ā`, sampled otherwise (empty when `B ⊂ A`).
    rest: CapIntersection,
    /// `Ω(A) / Ω(A ∪ B)`, in `[0, 1]`.
    first_share: f32,
    /// `Ω(A ∪ B)`.
    solid_angle: f32,
    /// `1 / Ω(A ∪ B)`.
    density: f32,
    /// `B` itself, for `contains`.
    second: Cap,
}

impl CapUnion {
    /// The empty union: no samples, pdf 0, solid angle 0 (what a failed prepare writes).
    ///
    /// cbindgen:ignore
    pub const EMPTY: CapUnion = CapUnion {
        first: Cap::EMPTY,
        rest: CapIntersection::EMPTY,
        first_share: 0.0,
        solid_angle: 0.0,
        density: 0.0,
        second: Cap::EMPTY,
    };

    /// Prepares uniform sampling of `a ∪ b` (both sanitized here). `None` when the union
    /// is empty or its density `1 / Ω` is not finite.
    #[must_use]
    pub fn new(a: &Cap, b: &Cap) -> Option<CapUnion> {
        let (first, second) = (a.sanitized(), b.sanitized());
        let rest = CapIntersection::new(&second, &first.complement());
        let rest_solid_angle = rest.map_or(0.0, |r| r.solid_angle());
        let first_solid_angle = if first.one_minus_cos > 0.0 {
            first.solid_angle()
        } else {
            0.0
        };
        let solid_angle = first_solid_angle + rest_solid_angle;
        let density = 1.0 / solid_angle;
        if !(solid_angle > 0.0) || !density.is_finite() {
            return None;
        }
        Some(CapUnion {
            first,
            rest: rest.unwrap_or(CapIntersection::EMPTY),
            first_share: (first_solid_angle / solid_angle).min(1.0),
            solid_angle,
            density,
            second,
        })
    }

    /// `Ω(A ∪ B)` in steradians.
    #[inline]
    #[must_use]
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle
    }

    /// Whether `dir` (any non-zero finite vector) lies in either cap.
    #[inline]
    #[must_use]
    pub fn contains(&self, dir: Vec3) -> bool {
        self.first.contains(dir) || self.second.contains(dir)
    }

    /// A direction uniform in `A ∪ B`, pdf `1 / Ω(A ∪ B)`; `u` is clamped to
    /// `[0, 1 − ulp]` (NaN counts as 0). The piece is chosen by `u₀ < Ω(A) / Ω(A ∪ B)`,
    /// and `u₀` rescaled into it.
    #[must_use]
    pub fn sample_uniform(&self, u: [f32; 2]) -> Sample {
        let u0 = clamp_random(u[0]);
        let share = self.first_share;
        let piece = if u0 < share {
            self.first.sample_uniform([u0 / share, u[1]])
        } else {
            self.rest
                .sample_uniform([(u0 - share) / (1.0 - share), u[1]])
        };
        if piece.pdf > 0.0 {
            Sample {
                dir: piece.dir,
                pdf: self.density,
            }
        } else {
            Sample::NONE
        }
    }

    /// The density of [`sample_uniform`](Self::sample_uniform): `1 / Ω(A ∪ B)` inside
    /// either cap, 0 outside (and for a zero or non-finite `dir`).
    #[inline]
    #[must_use]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        if self.contains(dir) {
            self.density
        } else {
            0.0
        }
    }

    /// The random numbers that [`sample_uniform`](Self::sample_uniform) maps to `dir`
    /// (up to rounding); `None` outside the union.
    #[must_use]
    pub fn invert(&self, dir: Vec3) -> Option<[f32; 2]> {
        let share = self.first_share;
        if self.first.contains(dir) {
            let [u0, u1] = self.first.invert(dir)?;
            return Some([clamp_inverted(u0 * share), u1]);
        }
        let [u0, u1] = self.rest.invert(dir)?;
        Some([clamp_inverted(share + u0 * (1.0 - share)), u1])
    }
}

#[cfg(test)]
#[path = "cap_union_sampling_tests.rs"]
mod tests;
