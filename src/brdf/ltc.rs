//! Linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt 2016) fitted to GGX. Their
//! sampling inside polygonal lights is `LtcPolygon`, in the polygon module (which depends
//! on this one, never the reverse).
//!
//! An LTC is the distribution of `ω = M ω_c / ‖M ω_c‖` for `ω_c` cosine-distributed,
//! `D_c(ω_c) = max(0, ω_c,z) / π`. By the change of variables `ω_c = M⁻¹ω / ‖M⁻¹ω‖`,
//! whose Jacobian is `|det M⁻¹| / ‖M⁻¹ω‖³`, its density over solid angle is
//!
//! `D(ω) = max(0, (M⁻¹ω)_z) |det M⁻¹| / (π ‖M⁻¹ω‖⁴)`.
//!
//! The table (`ltc_table.rs`, fitted by `tools/src/fitters/ltc_fitter.rs`) gives, per roughness
//! `r = √α` and view `t = √(1 − cos θ_o)`, the inverse matrix in the frame where the
//! view lies in the xz-plane, `M⁻¹ = [[a, 0, b], [0, c, 0], [d, 0, 1]]`, such that
//! `D ≈ f(ω_o, ω) cos θ / albedo` for GGX with `F = 1`, and the integrals `albedo` and
//! `fresnel` that turn it into shading with Schlick's Fresnel. [`Ltc::from_ggx`] interpolates
//! it bilinearly (as Heitz et al. interpolate their inverse matrices) and rotates it
//! about the normal to the view's azimuth.
use crate::Vec3;

use super::ltc_table::{LTC_TABLE, LTC_TABLE_SIZE};

const INV_PI: f32 = core::f32::consts::FRAC_1_PI;

/// A linearly transformed cosine in the local shading frame (z = normal).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ltc {
    /// Rows of `M⁻¹`: `(M⁻¹ω)_k = inverse_rows[k] · ω`. The transformed space keeps the
    /// normal as its z axis.
    pub(crate) inverse_rows: [Vec3; 3],
    /// Columns of `M`: `Mω' = Σ_k matrix_columns[k] ω'_k`.
    matrix_columns: [Vec3; 3],
    /// `det M⁻¹ > 0`.
    pub(crate) inverse_determinant: f32,
    /// `∫ f cos θ dω` of the fitted BRDF with `F = 1`.
    albedo: f32,
    /// `∫ f (1 − ω_o·h)⁵ cos θ dω` of the fitted BRDF with `F = 1`.
    fresnel: f32,
}

/// The number of `f32` words of an [`Ltc`]: the six `Vec3`s and three scalars.
const LTC_WORDS: usize = 21;

const _: () =
    assert!(core::mem::size_of::<Ltc>() == 4 * LTC_WORDS && core::mem::align_of::<Ltc>() == 4);

/// The word at which [`Ltc`]'s `matrix_columns` start (after the nine of `inverse_rows`).
const MATRIX_COLUMNS_WORD: usize = 9;

impl Ltc {
    /// The cosine itself (`M = I`); written by a failed C `prepare`.
    ///
    /// cbindgen:ignore
    pub const IDENTITY: Ltc = Ltc {
        inverse_rows: [Vec3::X, Vec3::Y, Vec3::Z],
        matrix_columns: [Vec3::X, Vec3::Y, Vec3::Z],
        inverse_determinant: 1.0,
        albedo: 1.0,
        fresnel: 0.0,
    };

    /// The LTC fitted to GGX `f(ω_o, ·) cos θ` for the view direction `wo` (local frame,
    /// need not be normalised) and roughness `r = √α`, clamped to `[0, 1]` (NaN counts as
    /// 0; below the table's smallest α the first row is used). Returns `None` when `wo` is
    /// not finite, zero, or at or below the horizon.
    // Inlined: the table's coordinates and fetch then run in the caller's frame, and a C
    // caller's value is written once, not returned through a copy (issue 18, stop 45).
    #[inline(always)]
    pub fn from_ggx(wo: Vec3, roughness: f32) -> Option<Ltc> {
        let (x, y, cos_phi, sin_phi) = super::table_coordinates(wo, roughness)?;
        // The table's loads start from the guessed row (`table_row_guess`) without
        // waiting on `table_coordinates`' square root and two divisions: the bits of
        // `table_bilinear` (see `table_bilinear_of_guess`; issue 18, stop 46).
        let guess = super::table_row_guess(wo);
        let entry = super::table_bilinear_of_guess::<6, { super::ALONG_Y_FIRST }>(
            &LTC_TABLE,
            LTC_TABLE_SIZE,
            x,
            y,
            guess,
        );
        Self::from_view_frame(entry, cos_phi, sin_phi)
    }

    /// The LTC with `M⁻¹ = [[a, 0, b], [0, c, 0], [d, 0, 1]]` in the frame whose x axis
    /// has azimuth `(cos φ, sin φ)`, from a table entry `[a, b, c, d, albedo, fresnel]`.
    /// `None` when the matrix is not invertible with a positive determinant.
    // Out of line: inlined into the sphere light's shading (with the smaller
    // `is_finite`), its prepare took 12 instructions more (issue 18, stop 45).
    #[inline(never)]
    pub(crate) fn from_view_frame(entry: [f32; 6], cos_phi: f32, sin_phi: f32) -> Option<Ltc> {
        let [a, b, c, d, albedo, fresnel] = entry;
        // M⁻¹ (view frame) times R, where R maps local to view-frame coordinates:
        // x' = cos φ x + sin φ y, y' = −sin φ x + cos φ y, z' = z.
        let inverse_rows = [
            Vec3::new(a * cos_phi, a * sin_phi, b),
            Vec3::new(-c * sin_phi, c * cos_phi, 0.0),
            Vec3::new(d * cos_phi, d * sin_phi, 1.0),
        ];
        // The xz block [[a, b], [d, 1]] has the inverse [[1, −b], [−d, a]] / k.
        let k = a - b * d;
        let inverse_determinant = c * k;
        // `0 < det < ∞` in one comparison of the bits.
        if !crate::math::is_positive_finite(inverse_determinant) {
            return None;
        }
        let (ik, ic) = (1.0 / k, 1.0 / c);
        // M = Rᵀ M_view: columns of M_view rotated back by Rᵀ(x', y', z) =
        // (cos φ x' − sin φ y', sin φ x' + cos φ y', z).
        let matrix_columns = [
            Vec3::new(cos_phi * ik, sin_phi * ik, -d * ik),
            Vec3::new(-sin_phi * ic, cos_phi * ic, 0.0),
            Vec3::new(-cos_phi * b * ik, -sin_phi * b * ik, a * ik),
        ];
        let ltc = Ltc {
            inverse_rows,
            matrix_columns,
            inverse_determinant,
            albedo,
            fresnel,
        };
        ltc.is_finite().then_some(ltc)
    }

    /// Whether the rows of `M⁻¹`, the columns of `M`, `albedo` and `fresnel` are all
    /// finite ([`is_finite_by_field`](Self::is_finite_by_field), the definition), as
    /// `Σ 0·x = 0` over the twenty values in five groups of lanes: `0·x` is ±0 for a
    /// finite `x` and NaN for an infinite or NaN one, a sum of ±0 is ±0 and one NaN
    /// makes it NaN. Six vector operations where the twenty tests of the bits took
    /// about 60 instructions (issue 18, stop 45; test `is_finite_is_by_field`).
    fn is_finite(&self) -> bool {
        use glam::Vec4;
        let ([r0, r1, r2], [c0, c1, c2]) = (self.inverse_rows, self.matrix_columns);
        let groups = [
            Vec4::new(r0.x, r0.y, r0.z, r1.x),
            Vec4::new(r1.y, r1.z, r2.x, r2.y),
            Vec4::new(r2.z, c0.x, c0.y, c0.z),
            Vec4::new(c1.x, c1.y, c1.z, c2.x),
            Vec4::new(c2.y, c2.z, self.albedo, self.fresnel),
        ];
        let zeros = groups.iter().fold(Vec4::ZERO, |sum, g| sum + *g * 0.0);
        zeros.cmpeq(Vec4::ZERO).all()
    }

    /// The definition of [`is_finite`](Self::is_finite), field by field (its test's
    /// reference).
    #[cfg(test)]
    fn is_finite_by_field(&self) -> bool {
        self.inverse_rows.iter().all(|r| r.is_finite())
            && self.matrix_columns.iter().all(|c| c.is_finite())
            && self.albedo.is_finite()
            && self.fresnel.is_finite()
    }

    /// `M⁻¹ v`: from the shading frame to the cosine's space.
    #[inline]
    pub fn to_cosine_space(&self, v: Vec3) -> Vec3 {
        Vec3::new(
            self.inverse_rows[0].dot(v),
            self.inverse_rows[1].dot(v),
            self.inverse_rows[2].dot(v),
        )
    }

    /// [`to_cosine_space`](Self::to_cosine_space) of each of `vertices`, written to the
    /// start of `out`, bit for bit: coordinate `k` of `M⁻¹v` is
    /// `(m_k0 v_x + m_k1 v_y) + m_k2 v_z` either way (glam's `dot` sums in that order),
    /// here the three coordinates at once in the lanes of one register per column of
    /// `M⁻¹` (three broadcasts, three products and two sums a vertex, where the three
    /// dot products took 22 instructions; issue 18, stop 45). The fourth lane is 0 and
    /// dropped. Test `map_to_cosine_space_is_to_cosine_space`.
    #[inline(always)]
    pub(crate) fn map_to_cosine_space(&self, vertices: &[Vec3], out: &mut [Vec3]) {
        use glam::Vec4;
        let [r0, r1, r2] = self.inverse_rows;
        let (c0, c1, c2) = (
            Vec4::new(r0.x, r1.x, r2.x, 0.0),
            Vec4::new(r0.y, r1.y, r2.y, 0.0),
            Vec4::new(r0.z, r1.z, r2.z, 0.0),
        );
        for (t, v) in out.iter_mut().zip(vertices) {
            *t = ((c0 * v.x + c1 * v.y) + c2 * v.z).truncate();
        }
    }

    /// `M v`: from the cosine's space to the shading frame, as
    /// `(c_0 v_x + c_1 v_y) + c_2 v_z` with `c_k` the columns of `M`, each coordinate
    /// in a lane: a column's lanes are the four words from its first (its coordinates
    /// and the next word of the value, whose lane is dropped), loaded as they are, where
    /// the `Vec3` columns took shuffles to clear a fourth lane (17 instructions less per
    /// LTC polygon sample, issue 18, stop 47). The same operations on the same values in
    /// each of the three lanes, so the same bits as the `Vec3` sum
    /// (`from_cosine_space_is_the_column_sum`).
    #[inline]
    pub fn from_cosine_space(&self, v: Vec3) -> Vec3 {
        let column = |k: usize| crate::math::load4(self.words(), MATRIX_COLUMNS_WORD + 3 * k);
        ((column(0) * v.x + column(1) * v.y) + column(2) * v.z).truncate()
    }

    /// The value's words in memory order: `inverse_rows`, `matrix_columns` (from
    /// [`MATRIX_COLUMNS_WORD`]), `inverse_determinant`, `albedo`, `fresnel`.
    #[inline(always)]
    fn words(&self) -> &[f32; LTC_WORDS] {
        // SAFETY: `Ltc` is `repr(C)` of `f32` fields and `repr(C)` `Vec3`s of three
        // `f32` each, `LTC_WORDS` words without padding (asserted at `LTC_WORDS`), of
        // alignment 4, and every bit pattern is an `f32`.
        unsafe { &*(self as *const Self).cast::<[f32; LTC_WORDS]>() }
    }

    /// `det M⁻¹`.
    #[inline]
    pub fn inverse_determinant(&self) -> f32 {
        self.inverse_determinant
    }

    /// The density `D(ω) = max(0, (M⁻¹ω)_z) |det M⁻¹| / (π ‖M⁻¹ω‖⁴)` over the whole
    /// sphere, for a unit `dir` (a non-unit `dir` is normalised; zero or non-finite
    /// gives 0).
    pub fn density(&self, dir: Vec3) -> f32 {
        let Some(dir) = super::unit(dir) else {
            return 0.0;
        };
        let w = self.to_cosine_space(dir);
        let length2 = w.length_squared();
        if !(w.z > 0.0) || !(length2 < f32::INFINITY) {
            return 0.0;
        }
        w.z * self.inverse_determinant * INV_PI / (length2 * length2)
    }

    /// `∫ f cos θ dω` of the fitted GGX with `F = 1`.
    #[inline]
    pub fn albedo(&self) -> f32 {
        self.albedo
    }

    /// `∫ f (1 − ω_o·h)⁵ cos θ dω` of the fitted GGX with `F = 1`.
    #[inline]
    pub fn fresnel(&self) -> f32 {
        self.fresnel
    }

    /// The directional albedo with Schlick's Fresnel `F0 + (1 − F0)(1 − ω_o·h)⁵`:
    /// `F0 (albedo − fresnel) + fresnel`, per channel. Unshadowed GGX shading of a
    /// polygon with radiance `L` is `L × specular_albedo(F0) × ∫_P D dω`.
    #[inline]
    pub fn specular_albedo(&self, f0: Vec3) -> Vec3 {
        f0 * (self.albedo - self.fresnel) + Vec3::splat(self.fresnel)
    }
}

#[cfg(test)]
#[path = "ltc_tests.rs"]
mod tests;
