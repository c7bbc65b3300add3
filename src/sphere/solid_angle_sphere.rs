//! A sphere light prepared for solid angle sampling: uniform sampling of the cap it
//! subtends, with the cap's frame and density computed once (issue 18, 2).
//!
//! [`Cap::sample_uniform`] takes a plain cap, a value that a caller may build by hand,
//! and so builds the cap's frame (Duff et al. 2017, one division) and its density
//! `1/Ω` (another division) at every sample, and the C ABI checks the cap's fields at
//! every call. A renderer draws one or more samples per prepared light: here the
//! prepare does both divisions once, as a cone sampler does, and a sample is the
//! warp alone: `1 − cos θ' = u₀ (1 − cos θ)`, `sin θ' = √(t' (2 − t'))`, `φ = 2π u₁`,
//! mapped by the stored frame. The cap and the sample are exactly those of
//! [`Cap::from_sphere`] and [`Cap::sample_uniform`], bit for bit (one body, shared):
//! `1 − cos θ = sin²θ / (1 + cos θ)` keeps tiny caps exact to 1e-12 sr and below, and
//! the rim test with its inward pull keeps `pdf(sample.dir) == sample.pdf`.

use super::Cap;
use super::cap::{sample_uniform_in_frame, sphere_cap_in_range};
use crate::Sample;
use crate::math::orthonormal_basis;
use glam::{Vec3, Vec3A, Vec4};

/// A sphere light (or any cap) prepared for uniform sampling in solid angle: the cap,
/// its frame and its density.
//
// Three groups of four numbers, each a vector and a scalar: the prepare writes each
// group with one 16-byte store and a sample reads it with one 16-byte load. A load that
// spans several smaller stores cannot take its value from them in flight: it waits
// until they have reached the cache, which orders the sample after everything before
// the prepare's stores (docs/speed.md, "Sixth round").
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidAngleSphere {
    /// The cap's unit axis and its `1 − cos θ` ([`Cap::from_sphere`]).
    axis_and_one_minus_cos: [f32; 4],
    /// The frame's first tangent, `orthonormal_basis(axis).0`, and the cap's
    /// `1 + cos θ`.
    tangent_and_one_plus_cos: [f32; 4],
    /// The frame's second tangent and `1 / Ω` (0: empty, no sample).
    bitangent_and_density: [f32; 4],
}

impl Default for SolidAngleSphere {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl SolidAngleSphere {
    /// The value of a light that could not be prepared: no sample, `pdf` 0, solid
    /// angle 0.
    ///
    /// cbindgen:ignore
    pub const EMPTY: SolidAngleSphere = SolidAngleSphere {
        axis_and_one_minus_cos: [0.0, 0.0, 1.0, 0.0],
        tangent_and_one_plus_cos: [1.0, 0.0, 0.0, 2.0],
        bitangent_and_density: [0.0, 1.0, 0.0, 0.0],
    };

    /// Prepares the sphere of radius `radius` centred at `center` (relative to the
    /// shading point), in place: the cap of [`Cap::from_sphere`] (the whole sphere when
    /// the shading point is inside or on it), its frame and `1/Ω`. Returns `false` and
    /// writes [`EMPTY`](Self::EMPTY) for a non-finite center or a radius that is not
    /// finite and positive.
    #[inline]
    pub fn prepare(&mut self, center: Vec3, radius: f32) -> bool {
        match sphere_cap_in_range(center, radius) {
            Some(cap) => {
                // An ordinary sphere seen from outside: `1/Ω` is normal and finite
                // there (`sphere_cap_in_range`), so no check; the cap stays in
                // registers on its way to the three stores.
                self.write(cap, cap.one_minus_cos_pdf());
                true
            }
            None => self.prepare_careful(center.x, center.y, center.z, radius),
        }
    }

    /// [`prepare`](Self::prepare) of any input, out of line: the cap of
    /// [`Cap::from_sphere_careful`] (a valid cap, the form `Cap::sanitized` keeps: no
    /// check). The center by its coordinates, which travel in registers (a `Vec3`
    /// argument was stored to the stack before the fast path's first test).
    #[inline(never)]
    fn prepare_careful(&mut self, x: f32, y: f32, z: f32, radius: f32) -> bool {
        self.prepare_valid_cap(Cap::from_sphere_careful(Vec3::new(x, y, z), radius))
    }

    /// Prepares uniform sampling of any cap, in place (made valid first as
    /// [`Cap::sanitized`] does). Returns `false` and writes [`EMPTY`](Self::EMPTY) for an
    /// empty cap or one whose density `1/Ω` is not finite.
    pub fn prepare_cap(&mut self, cap: Cap) -> bool {
        self.prepare_valid_cap(cap.sanitized())
    }

    /// [`prepare_cap`](Self::prepare_cap) of a cap that is valid already.
    #[inline(always)]
    fn prepare_valid_cap(&mut self, cap: Cap) -> bool {
        let density = cap.uniform_pdf();
        if density == 0.0 {
            *self = Self::EMPTY;
            return false;
        }
        self.write(cap, density);
        true
    }

    /// Writes a non-empty cap, its frame and its density `1/Ω`: three 16-byte stores.
    #[inline(always)]
    fn write(&mut self, cap: Cap, density: f32) {
        let (tangent, bitangent) = orthonormal_basis(cap.axis);
        self.axis_and_one_minus_cos = cap.axis.extend(cap.one_minus_cos).to_array();
        self.tangent_and_one_plus_cos = tangent.extend(cap.one_plus_cos).to_array();
        self.bitangent_and_density = bitangent.extend(density).to_array();
    }

    /// `1 / Ω` (0: empty).
    #[inline(always)]
    fn density(&self) -> f32 {
        self.bitangent_and_density[3]
    }

    /// The prepared cap.
    #[inline]
    #[must_use]
    pub fn cap(&self) -> Cap {
        let [x, y, z, t] = self.axis_and_one_minus_cos;
        let h = self.tangent_and_one_plus_cos[3];
        // A valid cap's `sin2` is `(t h)` clamped (`Cap::sanitized`): not stored.
        Cap {
            axis: Vec3::new(x, y, z),
            one_minus_cos: t,
            one_plus_cos: h,
            sin2: (t * h).max(0.0).min(1.0),
        }
    }

    /// The solid angle `Ω` of the cap (0 when empty).
    #[inline]
    #[must_use]
    pub fn solid_angle(&self) -> f32 {
        if self.density() > 0.0 {
            self.cap().solid_angle()
        } else {
            0.0
        }
    }

    /// A direction uniform in solid angle inside the cap, pdf `1/Ω`: bit for bit
    /// [`Cap::sample_uniform`] of the prepared cap. `u` is clamped to `[0, 1 − ulp]`
    /// (NaN counts as 0); no sample (pdf 0) from the empty value.
    #[inline]
    #[must_use]
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        let bitangent_and_density = Vec4::from_array(self.bitangent_and_density);
        let density = bitangent_and_density.w;
        if !(density > 0.0) {
            return Sample::NONE;
        }
        let axis_and_t = Vec4::from_array(self.axis_and_one_minus_cos);
        let tangent_and_h = Vec4::from_array(self.tangent_and_one_plus_cos);
        sample_uniform_in_frame(
            [
                Vec3A::from_vec4(axis_and_t),
                Vec3A::from_vec4(tangent_and_h),
                Vec3A::from_vec4(bitangent_and_density),
            ],
            axis_and_t.w,
            tangent_and_h.w,
            density,
            u,
        )
    }

    /// The density of [`sample`](Self::sample): `1/Ω` inside the cap (boundary
    /// included), 0 outside it, for the empty value, and for a zero or non-finite `dir`
    /// (which need not be normalised).
    #[inline]
    #[must_use]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        if self.density() > 0.0 && self.cap().contains(dir) {
            self.density()
        } else {
            0.0
        }
    }

    /// The random numbers that [`sample`](Self::sample) maps to `dir` ([`Cap::invert`]);
    /// `None` outside the cap and for the empty value.
    #[must_use]
    pub fn invert(&self, dir: Vec3) -> Option<[f32; 2]> {
        if !(self.density() > 0.0) {
            return None;
        }
        self.cap().invert(dir)
    }
}

#[cfg(test)]
#[path = "solid_angle_sphere_tests.rs"]
mod tests;
