//! The one-call shading of a polygonal light for renderers (Peters 2021, Sec. 5 and
//! supplement B): a diffuse technique, projected solid angle sampling, and a specular
//! technique, the GGX-fitted LTC sampled inside the polygon, combined by multiple
//! importance sampling with one sample from each.
//!
//! For a light of constant radiance `L` and the BRDF `f = ρ/π + f_GGX`, the integrand is
//! `L V(ω) f(ω_o, ω) cos θ`. With perfect fits it equals `L V Σ_k c_k p_k(ω)`, where
//! `p_0 = cos θ / Φ` (projected solid angle sampling) and `p_1 = D / ∫_P D` (the LTC
//! inside the polygon), with the unoccluded contributions per unit radiance
//!
//! `c_0 = ρ Φ / π`,  `c_1 = (F0 (albedo − fresnel) + fresnel) ∫_P D`.
//!
//! Every heuristic of [`crate::mis`] is available; the default is clamped optimal MIS
//! with `v = 1/2` (supplement B.3), which Peters recommends. The weights of the
//! weighted balance heuristic and of (clamped) optimal MIS are applied per colour
//! channel, with `c_k` per channel: each channel is its own integral, so the estimate
//! stays unbiased and, unoccluded, has zero variance up to the fit error of the LTC.
use crate::brdf::Ltc;
use crate::brdf::ggx::GgxBrdf;
use crate::mis;
use crate::polygon::LtcPolygon;
use crate::polygon::ProjectedPolygon;
use crate::{MAX_POLYGON_VERTICES, Sample, Vec3};
use glam::Vec3A;

/// A surface's BRDF: Lambert with albedo `diffuse`, plus GGX with reflectance `f0` at
/// normal incidence (Schlick's Fresnel) and `roughness = √α` in `[0, 1]`. `f0 = (0, 0, 0)`
/// means no GGX layer at all (a Lambertian surface; Schlick's grazing reflection
/// `(1 − ω_o·h)⁵`, which `F0 = 0` would otherwise keep, is dropped too).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Lambertian albedo per channel, in `[0, 1]`.
    pub diffuse: Vec3,
    /// GGX reflectance at normal incidence per channel, in `[0, 1]`.
    pub f0: Vec3,
    /// `√α`, in `[0, 1]`.
    pub roughness: f32,
}

/// How the two techniques' samples are weighted.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MisHeuristic {
    /// `p_j / Σ p_k` (Veach 1997).
    Balance = 0,
    /// `p_j² / Σ p_k²` (Veach 1997).
    Power = 1,
    /// `c_j p_j / Σ c_k p_k` (Peters 2021): zero variance when nothing is occluded.
    WeightedBalance = 2,
    /// Clamped optimal MIS with visibility estimate `v` (supplement B.3): the weighted
    /// balance heuristic blended with the balance heuristic, `v c_j p_j / Σ c_k p_k +
    /// (1 − v) p_j / Σ p_k`.
    ClampedOptimal = 3,
    /// Optimal MIS with visibility estimate `v` (supplement B.1): contributions
    /// `v c_j + (f − v Σ c_k p_k) / Σ p_k`, part of which does not depend on visibility.
    Optimal = 4,
}

impl MisHeuristic {
    /// The heuristic with the given number, or `None`.
    pub fn from_u32(value: u32) -> Option<Self> {
        Some(match value {
            0 => Self::Balance,
            1 => Self::Power,
            2 => Self::WeightedBalance,
            3 => Self::ClampedOptimal,
            4 => Self::Optimal,
            _ => return None,
        })
    }
}

/// A sample of a [`PolygonLight`]: the direction, the density of the technique that
/// drew it, and its MIS-weighted contribution per unit radiance, in two parts. The
/// estimate of the reflected radiance from this sample is
/// `L × (V(dir) × visible + unoccluded)`, with `V` the visibility of the light along
/// `dir`. `unoccluded` is zero except for optimal MIS, whose zero-mean terms do not
/// depend on visibility (supplement B.1).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit direction in the local frame.
    pub dir: Vec3,
    /// The density of the technique that drew the sample; 0: no sample (and both
    /// contribution parts are 0).
    pub pdf: f32,
    /// `f cos θ × weight / pdf`, per channel: multiply by `L V`.
    pub visible: Vec3,
    /// The part of optimal MIS that does not depend on visibility: multiply by `L`.
    pub unoccluded: Vec3,
}

impl LightSample {
    /// No sample.
    ///
    /// cbindgen:ignore
    pub const NONE: LightSample = LightSample {
        dir: Vec3::Z,
        pdf: 0.0,
        visible: Vec3::ZERO,
        unoccluded: Vec3::ZERO,
    };
}

/// A polygonal light prepared at one shading point for both techniques.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct PolygonLight {
    /// Technique 0: projected solid angle sampling.
    diffuse: ProjectedPolygon,
    /// Technique 1: the GGX LTC inside the polygon.
    specular: LtcPolygon,
    brdf: GgxBrdf,
    /// 1 when the material has a GGX layer (`f0` not zero), else 0.
    has_specular: u32,
    /// `ρ / π`.
    lambert: Vec3,
    /// The view direction, unit, above the horizon.
    wo: Vec3,
    /// `c_0, c_1` per channel (unoccluded contribution per unit radiance).
    contributions: [Vec3; 2],
    /// A [`MisHeuristic`] as a number.
    heuristic: u32,
    /// `v` of (clamped) optimal MIS, in `[0, 1]`.
    visibility: f32,
}

impl PolygonLight {
    /// A light with nothing to sample: every sample is [`LightSample::NONE`].
    ///
    /// cbindgen:ignore
    pub const EMPTY: PolygonLight = PolygonLight {
        diffuse: ProjectedPolygon::EMPTY,
        specular: LtcPolygon::EMPTY,
        brdf: GgxBrdf {
            alpha: 1.0,
            f0: Vec3::ZERO,
        },
        has_specular: 0,
        lambert: Vec3::ZERO,
        wo: Vec3::Z,
        contributions: [Vec3::ZERO; 2],
        heuristic: MisHeuristic::ClampedOptimal as u32,
        visibility: 0.5,
    };

    /// Prepares both techniques for the convex polygon with the given vertices (relative
    /// to the shading point, local frame, either winding, 3 to 8), seen from the unit
    /// view direction `wo` (towards the viewer, `wo.z > 0`), for `material`.
    /// `visibility` is `v` of (clamped) optimal MIS, clamped to `[0, 1]` (NaN: 1/2).
    ///
    /// Returns `None` when `wo` is not above the horizon or not finite, or when neither
    /// technique can sample the polygon (bad vertices, nothing above the horizon). A
    /// technique that cannot sample it (for example when the LTC has no mass in the
    /// polygon) gets `c = 0` and draws no samples.
    ///
    /// [`prepare`](Self::prepare) does the same in place.
    #[must_use]
    pub fn new(
        vertices: &[Vec3],
        wo: Vec3,
        material: &Material,
        heuristic: MisHeuristic,
        visibility: f32,
    ) -> Option<Self> {
        let mut light = Self::EMPTY;
        light
            .prepare(vertices, wo, material, heuristic, visibility)
            .then_some(light)
    }

    /// [`new`](Self::new) in place: writes the prepared light into `self` and returns
    /// `true`, or writes [`EMPTY`](Self::EMPTY) and returns `false` where `new` returns
    /// `None`. Both techniques are prepared in their own fields (3572 bytes that are
    /// never copied), and the LTC polygon only for a material with a GGX layer: a
    /// Lambertian surface gives the LTC no weight (`c_1 = 0`) and no samples, so its
    /// transformed polygon is not built at all.
    pub fn prepare(
        &mut self,
        vertices: &[Vec3],
        wo: Vec3,
        material: &Material,
        heuristic: MisHeuristic,
        visibility: f32,
    ) -> bool {
        let prepared = self.prepare_or_fail(vertices, wo, material, heuristic, visibility);
        super::keep_or_empty(self, prepared, Self::EMPTY)
    }

    /// The body of [`prepare`](Self::prepare); on `false`, `self` holds partial values.
    #[inline(always)]
    fn prepare_or_fail(
        &mut self,
        vertices: &[Vec3],
        wo: Vec3,
        material: &Material,
        heuristic: MisHeuristic,
        visibility: f32,
    ) -> bool {
        if !(3..=MAX_POLYGON_VERTICES).contains(&vertices.len()) {
            return false;
        }
        let wo = crate::math::normalize_scaled(wo);
        // `normalize_scaled` leaves `|wo|²` within about 7 ulps (4e-7) of 1: its
        // largest component is 1 after the division, `|v|²` in [1, 3] is rounded by
        // 2 ulps, the square root, the reciprocal and the products by half an ulp each,
        // and the test's own `|wo|²` by 2 more. So `unit` takes it as it is, which the
        // BRDF's evaluation in `sample` relies on (`eval_from_unit_view`); checked here
        // all the same (`prepared_views_are_unit`).
        if !(wo.z > 0.0 && crate::math::is_unit(wo)) {
            return false;
        }
        let diffuse_albedo = material.diffuse.max(Vec3::ZERO).min(Vec3::ONE);
        let f0 = material.f0.max(Vec3::ZERO).min(Vec3::ONE);
        let Some(ltc) = Ltc::from_ggx(wo, material.roughness) else {
            return false;
        };
        let has_specular = f0.max_element() > 0.0;
        // Each technique in place, its empty value when it cannot sample the polygon.
        let diffuse_ok = self.diffuse.prepare(vertices);
        // A Lambertian surface has nothing for the LTC to sample.
        let specular_ok = if has_specular {
            self.specular.prepare(&ltc, vertices)
        } else {
            self.specular = LtcPolygon::EMPTY;
            false
        };
        if !diffuse_ok && !specular_ok {
            return false;
        }
        self.brdf = GgxBrdf::new(material.roughness, f0);
        self.lambert = diffuse_albedo * core::f32::consts::FRAC_1_PI;
        // Without a GGX layer the specular technique gets c_1 = 0 (no weight under the
        // weighted heuristics) and the BRDF no GGX term.
        let specular_albedo = if has_specular {
            ltc.specular_albedo(f0)
        } else {
            Vec3::ZERO
        };
        self.contributions = [
            self.lambert * self.diffuse.projected_solid_angle(),
            specular_albedo * self.specular.integral(),
        ];
        self.has_specular = has_specular as u32;
        self.wo = wo;
        self.heuristic = heuristic as u32;
        self.visibility = if visibility.is_nan() {
            0.5
        } else {
            visibility.max(0.0).min(1.0)
        };
        true
    }

    /// The unshadowed shading per unit radiance in closed form, `c_0 + c_1`: exact for
    /// the diffuse part, the LTC approximation (Heitz 2016) for the specular part.
    pub fn unshadowed(&self) -> Vec3 {
        self.contributions[0] + self.contributions[1]
    }

    /// `c_0` (diffuse) and `c_1` (specular), per channel.
    pub fn contributions(&self) -> [Vec3; 2] {
        self.contributions
    }

    /// The densities of both techniques at `dir`.
    pub fn pdfs(&self, dir: Vec3) -> [f32; 2] {
        [self.diffuse.pdf(dir), self.specular.pdf(dir)]
    }

    /// Draws a sample from technique `technique` (0: projected solid angle sampling, 1:
    /// the LTC; anything else: no sample) and weights it for the multi-sample MIS
    /// estimator that takes one sample from each technique: the sum of the two samples'
    /// estimates is unbiased. Samples at or below the horizon, and samples of a
    /// technique that could not be prepared, have zero contribution (`pdf` says which).
    /// A light whose stored heuristic is not a [`MisHeuristic`] (only a corrupted value
    /// can hold one: [`PolygonLight::new`] takes the enum) gives no sample.
    pub fn sample(&self, technique: u32, u: [f32; 2]) -> LightSample {
        let Some(heuristic) = MisHeuristic::from_u32(self.heuristic) else {
            return LightSample::NONE;
        };
        // The LTC's sample comes with its direction's `unit` (from its own `pdf`) and
        // whether that `pdf` found it strictly inside.
        let (sample, sample_unit, ltc_inner) = match technique {
            0 => (self.diffuse.sample(u), None, false),
            1 => {
                let ltc = self.specular.sample_and_unit(u);
                (ltc.sample, Some(ltc.unit), ltc.inner)
            }
            _ => (Sample::NONE, None, false),
        };
        if !(sample.pdf > 0.0) {
            return LightSample::NONE;
        }
        let mut out = LightSample {
            dir: sample.dir,
            pdf: sample.pdf,
            visible: Vec3::ZERO,
            unoccluded: Vec3::ZERO,
        };
        let wi = sample.dir;
        if !(wi.z > 0.0) {
            // Below the horizon: f = 0, and the zero-mean terms of optimal MIS are
            // dropped there too (supplement B.2 allows any admissible set).
            return out;
        }
        let j = technique as usize;
        // The sample's own technique has the density it was drawn with (its own `pdf`
        // at `wi`, which the LTC polygon's sample has just evaluated, and which the
        // projected sampler's `pdf` may round to 0 on the polygon's edge): only the
        // other technique's density is evaluated, and from the sample's own state
        // (issue 18, 3): both techniques sample the same polygon `P`, so a sample
        // lies inside `P` and the other density needs no test of `P`'s edges.
        // - A projected sample lies in `P` above the horizon: the LTC's density is 0
        //   there only below the transformed horizon, `(M⁻¹ω)_z <= 0`
        //   (`pdf_of_unit_inside`).
        // - An LTC sample above the horizon whose transformed direction passed the LTC's
        //   test without its slack (`inner`) lies in `P` up to the rounding of `M ω'`:
        //   its projected density is `ω_z / Φ` (`pdf_inside`). Other LTC samples (within
        //   the slack of the boundary, or pulled inward) take the projected `pdf`
        //   (`pdf_inline`, the bits of `pdf`).
        // Wherever the skipped test accepts the sample, the densities are `pdfs`' bit
        // for bit; a sample that rounding put outside the other technique's polygon gets
        // the other density continued past the boundary, where `pdfs` gives 0: a
        // difference confined to a band of rounding width along the boundary
        // (`a_sample_carries_its_own_techniques_pdf` checks it there, and
        // finds none at random `u`).
        // `wi` through `unit` once (the LTC's sample has done it), for the BRDF and the
        // LTC's density, which both start with it (the same bits as their public forms
        // `eval` and `pdf`).
        let wi_unit = sample_unit.unwrap_or_else(|| crate::math::unit(wi));
        let other = if j == 0 {
            match wi_unit {
                Some(dir) => self.specular.pdf_of_unit_inside(dir),
                None => 0.0,
            }
        } else if ltc_inner {
            self.diffuse.pdf_inside(wi)
        } else {
            self.diffuse.pdf_inline(wi)
        };
        let p = if j == 0 {
            [sample.pdf, other]
        } else {
            [other, sample.pdf]
        };
        // The stored view is unit and above the horizon (`prepare`), which the BRDF's
        // evaluation then does not test again: `eval(self.wo, wi)` bit for bit.
        let specular = if self.has_specular != 0 {
            self.brdf.eval_from_unit_view(self.wo, wi_unit)
        } else {
            Vec3::ZERO
        };
        let f = (self.lambert + specular) * wi.z;
        let c = self.contributions;
        let v = self.visibility;
        // Both pdfs finite (always, for the samplers' own pdfs): the ratios to the
        // larger one with one division (`TwoPdfs`), for the balance heuristic and the
        // three channels of the weighted ones at once, bit for bit the scalar functions.
        let two_pdfs = mis::TwoPdfs::new(sample.pdf, other, j);
        // The sample's share of the balance heuristic, f / Σ p as a factor of f.
        let balance = match two_pdfs {
            Some(two) => two.balance_over_pdf(sample.pdf),
            None => mis::balance_heuristic(&p, j) / p[j],
        };
        match heuristic {
            MisHeuristic::Balance => out.visible = f * balance,
            MisHeuristic::Power => out.visible = f * (mis::power_heuristic(&p, j) / p[j]),
            heuristic => {
                // Otherwise the per-channel loop below.
                if let Some(two) =
                    two_pdfs.map(|two| mis::TwoTechniques::new(two, [c[0].into(), c[1].into()]))
                {
                    let f = Vec3A::from(f);
                    match heuristic {
                        MisHeuristic::WeightedBalance => {
                            out.visible = two.weighted_balance(f, sample.pdf).into();
                        }
                        MisHeuristic::ClampedOptimal => {
                            out.visible = two.clamped_optimal(f, v).into();
                        }
                        _ => {
                            out.visible = (f * balance).into();
                            out.unoccluded = two.optimal_unoccluded(v).into();
                        }
                    }
                } else {
                    Self::weigh_per_channel(&mut out, heuristic, f, &p, &c, v, j, balance);
                }
            }
        }
        // The six channels' test in two vector comparisons (`Vec3A`'s `is_finite` is
        // one mask per vector; the same answer as `Vec3`'s three scalar tests).
        if !(Vec3A::from(out.visible).is_finite_mask()
            & Vec3A::from(out.unoccluded).is_finite_mask())
        .all()
        {
            out.visible = Vec3::ZERO;
            out.unoccluded = Vec3::ZERO;
        }
        out
    }

    /// The weighted heuristics one channel at a time by the scalar functions of
    /// [`mis`], for pdfs that [`mis::TwoTechniques`] does not take (not finite).
    #[cold]
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn weigh_per_channel(
        out: &mut LightSample,
        heuristic: MisHeuristic,
        f: Vec3,
        p: &[f32; 2],
        c: &[Vec3; 2],
        v: f32,
        j: usize,
        balance: f32,
    ) {
        for k in 0..3 {
            let ck = [c[0][k], c[1][k]];
            match heuristic {
                MisHeuristic::WeightedBalance => {
                    out.visible[k] = f[k] * (mis::weighted_balance_heuristic(p, &ck, j) / p[j]);
                }
                MisHeuristic::ClampedOptimal => {
                    out.visible[k] = mis::clamped_optimal_mis_contribution(f[k], p, &ck, v, j);
                }
                _ => {
                    // Optimal MIS: v c_j + (f − v Σ c p) / Σ p = f / Σ p (the
                    // balance heuristic, times V) + the rest (independent of V).
                    out.visible[k] = f[k] * balance;
                    out.unoccluded[k] = mis::optimal_mis_contribution(0.0, p, &ck, v, j);
                }
            }
        }
    }
}

#[cfg(test)]
#[path = "light_tests.rs"]
mod tests;
