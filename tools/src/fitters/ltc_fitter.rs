//! Fitter of the LTC table `src/brdf/ltc_table.rs`: linearly transformed cosines (Heitz,
//! Dupuy, Hill and Neubelt 2016, "Real-time Polygonal-light Shading with Linearly
//! Transformed Cosines") that approximate the isotropic GGX BRDF, all in f64.
//!
//! # The BRDF
//!
//! GGX with α = r², D(h) = α² / (π (cos²θh (α² − 1) + 1)²), Smith's
//! Λ(ω) = (√(1 + α² tan²θ) − 1) / 2 in the height-correlated
//! G2 = 1 / (1 + Λ(ωo) + Λ(ωi)), and f = F D G2 / (4 cos θo cos θi), in the frame with the
//! normal along z and the view ωo = (sin θo, 0, cos θo). With s(ω) = √(cos²θ + α² sin²θ)
//! = cos θ √(1 + α² tan²θ), G2 = 2 / (s(ωo)/cos θo + s(ωi)/cos θi), and the fitted
//! shape is
//!
//! f cos θi (F = 1) = D(h) cos θi / (2 (s(ωo) cos θi + s(ωi) cos θo)),
//!
//! which this file evaluates in that form: no tangent, no 1/cos θ, stable at the horizon.
//! D is evaluated from the unnormalised half vector H = ωo + ωi as
//! α² |H|⁴ / (π (α² H_z² + H_x² + H_y²)²), which keeps its relative precision for tiny α.
//!
//! # The table
//!
//! 64 × 64 cells: row i has r = √α = i/63 (row 0 uses [`MIN_ALPHA`]), column j has
//! t = √(1 − cos θo) = j/63 (column 63 uses [`MIN_COS_THETA`]). A cell stores the
//! normalised inverse matrix M⁻¹ = [[a, 0, b], [0, c, 0], [d, 0, 1]], the albedo
//! ∫ f cos θ dω (F = 1) and ∫ f (1 − ωo·h)⁵ cos θ dω. The LTC density is
//! D(ω) = D_o(M⁻¹ω / ‖M⁻¹ω‖) |det M⁻¹| / ‖M⁻¹ω‖³ with D_o(ω) = max(0, ω_z)/π.
//!
//! # The fit
//!
//! Per cell, the L1 distance ∫ |D − f̂| dω between the LTC density and the normalised
//! target f̂ = f cos θ / albedo is minimised by Nelder–Mead over all four degrees of
//! freedom of M (see [`coefficients_from_params`]). The L1 distance is twice the total
//! variation distance, so half of it bounds the error of the LTC's integral over any
//! polygon (any set of directions), which is exactly how the table is used; it is also
//! the error measure the table reports. The integral is estimated with the balance
//! heuristic over two fixed sets of samples (one from the LTC, one from the BRDF's
//! visible normals); the integrand |D − f̂| / (p_LTC + p_BRDF) is bounded, so the
//! estimate is accurate with a few thousand samples. See [`fit_cell`] for the warm starts.
//!
//! Everything is deterministic: fixed Fibonacci lattices, sums in a fixed order,
//! transcendental functions from the pure-Rust `libm` crate (not the platform's), and
//! a parallel schedule (anti-diagonals) whose cells never depend on one another.
use std::f64::consts::PI;
use std::fmt::Write as _;

/// Cells per axis of the table.
pub const TABLE_SIZE: usize = 64;
const LAST: usize = TABLE_SIZE - 1;

/// The α of row 0. r = 0 is a mirror, whose distribution is a Dirac delta that no LTC
/// fits. 10⁻⁴ (r = 0.01, the floor of Heitz et al.'s own fit) is below row 1's
/// α = 1/63² ≈ 2.5·10⁻⁴, so row 0 stays the narrowest lobe; the fit is still well
/// conditioned there (its L1 error at (0, 0) is below 10⁻⁴, the scaled cosine matching
/// GGX's small-angle shape), and the matrices stay far inside f32's range: their entries
/// grow like 1/α at the normal and faster towards grazing views, and the table's extremes
/// (stated in its documentation, about 7·10⁵ for an entry and 2·10¹¹ for det M⁻¹) leave
/// ‖M⁻¹ω‖⁴ and the densities many orders of magnitude below f32's limit.
pub const MIN_ALPHA: f32 = 1e-4;

/// The view cosine of column 63. At cos θo = 0 the BRDF is undefined (D G2 / (4 cos θo
/// cos θi) is 0/0 since G2 → 0), although f cos θi has a finite limit. Column 63 is
/// fitted at cos θo = 10⁻⁴ (θo ≈ 89.994°, t = √(1 − 10⁻⁴) ≈ 0.99995, 0.003 cells short
/// of t = 1), where the stable form of f cos θi above evaluates without cancellation.
pub const MIN_COS_THETA: f32 = 1e-4;

/// The Fibonacci lattice (F(k), F(k − 1)) of the fit's samples, per strategy.
pub const FIT_LATTICE: (usize, usize) = (2584, 1597);

/// The Fibonacci lattice (F(k), F(k − 1)) of the error measurement, per strategy.
pub const EVALUATION_LATTICE: (usize, usize) = (10946, 6765);

/// A direction or any 3-vector.
pub type V3 = [f64; 3];

pub(crate) use sphera_test_support::{add, dot, normalize, scale};
pub use sphera_test_support::{gauss_legendre, graded_panels};

/// The α of table row `i`: r² with r = i / 63, floored at [`MIN_ALPHA`].
pub fn cell_alpha(i: usize) -> f64 {
    let r = i as f64 / LAST as f64;
    (r * r).max(f64::from(MIN_ALPHA))
}

/// The view cosine of table column `j`: 1 − t² with t = j / 63, floored at
/// [`MIN_COS_THETA`].
pub fn cell_cos_theta(j: usize) -> f64 {
    let t = j as f64 / LAST as f64;
    (1.0 - t * t).max(f64::from(MIN_COS_THETA))
}

/// The GGX BRDF (F = 1) for one roughness and view.
#[derive(Clone, Copy, Debug)]
pub struct Ggx {
    alpha: f64,
    alpha2: f64,
    view: V3,
    /// s(ωo).
    s_view: f64,
}

impl Ggx {
    /// The BRDF of roughness `alpha` seen from ωo = (sin θo, 0, cos θo).
    pub fn new(alpha: f64, cos_theta: f64) -> Ggx {
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let alpha2 = alpha * alpha;
        Ggx {
            alpha,
            alpha2,
            view: [sin_theta, 0.0, cos_theta],
            s_view: (cos_theta * cos_theta + alpha2 * sin_theta * sin_theta).sqrt(),
        }
    }

    /// The BRDF of table cell (i, j).
    pub fn of_cell(i: usize, j: usize) -> Ggx {
        Ggx::new(cell_alpha(i), cell_cos_theta(j))
    }

    /// The view direction ωo.
    pub fn view(&self) -> V3 {
        self.view
    }

    /// s(ω) = √(cos²θ + α² sin²θ) = cos θ (1 + 2Λ(ω)).
    fn smith_s(&self, w: V3) -> f64 {
        (w[2] * w[2] + self.alpha2 * (w[0] * w[0] + w[1] * w[1])).sqrt()
    }

    /// D(h) of the half vector along `hh` = ωo + ωi (any length, hh_z > 0).
    fn ndf_along(&self, hh: V3) -> f64 {
        let tangential = hh[0] * hh[0] + hh[1] * hh[1];
        let len2 = tangential + hh[2] * hh[2];
        let den = self.alpha2 * hh[2] * hh[2] + tangential;
        self.alpha2 * len2 * len2 / (PI * den * den)
    }

    /// f(ωo, ωi) cos θi with F = 1 for a unit ωi; zero below the horizon.
    pub fn cosine_weighted(&self, wi: V3) -> f64 {
        if wi[2] <= 0.0 {
            return 0.0;
        }
        let d = self.ndf_along(add(self.view, wi));
        d * wi[2] / (2.0 * (self.s_view * wi[2] + self.smith_s(wi) * self.view[2]))
    }

    /// The density of [`Ggx::sample`] at a unit ωi: G1(ωo) D(h) / (4 cos θo) =
    /// D(h) / (2 (cos θo + s(ωo))), zero where no visible normal reflects ωo into ωi.
    pub fn sample_pdf(&self, wi: V3) -> f64 {
        let hh = add(self.view, wi);
        if hh[2] <= 0.0 {
            return 0.0;
        }
        self.ndf_along(hh) / (2.0 * (self.view[2] + self.s_view))
    }

    /// The view reflected about a visible normal sampled with the spherical caps of Dupuy
    /// and Benyoub (2023, "Sampling Visible GGX Normals with Spherical Caps"): in the
    /// configuration stretched to α = 1, the normal is the half vector between the
    /// stretched view and a uniform direction of the cap z ≥ −(stretched view)_z.
    /// `u1` in [0, 1] picks the cap's z, (`cos_phi`, `sin_phi`) its azimuth.
    pub fn sample(&self, u1: f64, cos_phi: f64, sin_phi: f64) -> V3 {
        let stretched = normalize([self.alpha * self.view[0], 0.0, self.view[2]]);
        let z = (1.0 - u1) * (1.0 + stretched[2]) - stretched[2];
        let sin_theta = (1.0 - z * z).max(0.0).sqrt();
        let hs = add([sin_theta * cos_phi, sin_theta * sin_phi, z], stretched);
        let h = normalize([self.alpha * hs[0], self.alpha * hs[1], hs[2]]);
        add(scale(h, 2.0 * dot(self.view, h)), scale(self.view, -1.0))
    }
}

/// Gauss–Legendre order per panel of [`hemisphere_rule`].
pub const QUADRATURE_ORDER: usize = 8;
/// Geometric refinements towards each graded end in [`hemisphere_rule`].
pub const QUADRATURE_LEVELS: usize = 32;

/// A product Gauss–Legendre rule over the half of the upper hemisphere with y ≥ 0, in
/// ωi = (sin θ cos φ, sin θ sin φ, cos θ), θ in [0, π/2], φ in [0, π], as (direction,
/// weight) with the weights including sin θ and the factor 2 for the mirror half (so it
/// integrates functions even in y over the whole hemisphere). The θ panels are refined
/// geometrically (down to 2⁻³² of their length) towards the mirror direction θ = θo,
/// where f cos θ peaks with a width ~α, and towards the horizon, where it falls to zero
/// within ~cos θo; the φ panels towards the mirror azimuth φ = π.
pub fn hemisphere_rule(ggx: &Ggx) -> Vec<(V3, f64)> {
    hemisphere_rule_with(ggx, QUADRATURE_ORDER, QUADRATURE_LEVELS)
}

/// [`hemisphere_rule`] of another Gauss–Legendre order and refinement depth.
pub fn hemisphere_rule_with(ggx: &Ggx, order: usize, levels: usize) -> Vec<(V3, f64)> {
    let rule = gauss_legendre(order);
    let nodes = |panels: Vec<(f64, f64)>| -> Vec<(f64, f64)> {
        panels
            .iter()
            .flat_map(|&(a, b)| {
                rule.iter()
                    .map(move |&(x, w)| (a + (b - a) * x, (b - a) * w))
            })
            .collect()
    };
    let theta_peak = libm::acos(ggx.view[2]);
    let mut theta_panels = Vec::new();
    if theta_peak > 0.0 {
        theta_panels.extend(graded_panels(0.0, theta_peak, false, true, levels));
    }
    theta_panels.extend(graded_panels(theta_peak, 0.5 * PI, true, true, levels));
    let azimuths: Vec<(f64, f64, f64)> = nodes(graded_panels(0.0, PI, false, true, levels))
        .into_iter()
        .map(|(phi, w)| (libm::cos(phi), libm::sin(phi), w))
        .collect();
    let mut out = Vec::new();
    for (theta, wt) in nodes(theta_panels) {
        let (sin_t, cos_t) = (libm::sin(theta), libm::cos(theta));
        for &(cos_p, sin_p, wp) in &azimuths {
            out.push(([sin_t * cos_p, sin_t * sin_p, cos_t], 2.0 * wt * sin_t * wp));
        }
    }
    out
}

/// Integrals of f cos θi (F = 1) over the hemisphere.
#[derive(Clone, Copy, Debug)]
pub struct Moments {
    /// ∫ f cos θ dω.
    pub albedo: f64,
    /// ∫ f (1 − ωo·h)⁵ cos θ dω.
    pub fresnel: f64,
}

/// [`Moments`] with [`hemisphere_rule`]; ωo·h = |ωo + ωi| / 2.
pub fn moments(ggx: &Ggx) -> Moments {
    moments_with(ggx, &hemisphere_rule(ggx))
}

/// [`Moments`] with the quadrature `rule`.
pub fn moments_with(ggx: &Ggx, rule: &[(V3, f64)]) -> Moments {
    let (mut albedo, mut fresnel) = (0.0, 0.0);
    for &(wi, w) in rule {
        let v = ggx.cosine_weighted(wi) * w;
        let hh = add(ggx.view, wi);
        let x = (1.0 - 0.5 * dot(hh, hh).sqrt()).max(0.0);
        albedo += v;
        fresnel += v * (x * x) * (x * x) * x;
    }
    Moments { albedo, fresnel }
}

/// A linearly transformed cosine given by its normalised inverse matrix
/// M⁻¹ = [[a, 0, b], [0, c, 0], [d, 0, 1]].
#[derive(Clone, Copy, Debug)]
pub struct Ltc {
    inv: [f64; 4],
    /// M = (M⁻¹)⁻¹ as [m00, m02, m11, m20, m22].
    m: [f64; 5],
    det_inv: f64,
}

impl Ltc {
    /// The LTC of `[a, b, c, d]`; `None` unless finite and invertible.
    pub fn new(coefficients: [f64; 4]) -> Option<Ltc> {
        let [a, b, c, d] = coefficients;
        let det_xz = a - b * d;
        let det_inv = c * det_xz;
        let m = [1.0 / det_xz, -b / det_xz, 1.0 / c, -d / det_xz, a / det_xz];
        if !(det_inv.is_finite() && det_inv != 0.0 && m.iter().all(|x| x.is_finite())) {
            return None;
        }
        Some(Ltc {
            inv: coefficients,
            m,
            det_inv: det_inv.abs(),
        })
    }

    /// The LTC of a stored cell.
    pub fn of_cell(values: &[f32; 6]) -> Option<Ltc> {
        Ltc::new([values[0], values[1], values[2], values[3]].map(f64::from))
    }

    /// D(ω) for a unit ω: max(0, ω'_z) |det M⁻¹| / (π ‖ω'‖⁴) with ω' = M⁻¹ω.
    pub fn density(&self, w: V3) -> f64 {
        let [a, b, c, d] = self.inv;
        let o = [a * w[0] + b * w[2], c * w[1], d * w[0] + w[2]];
        if o[2] <= 0.0 {
            return 0.0;
        }
        let n2 = dot(o, o);
        o[2] * self.det_inv / (PI * n2 * n2)
    }

    /// The image of a direction `wo` of the cosine distribution (unit, z > 0) and its
    /// density D_o(wo) |det M⁻¹| ‖M wo‖³.
    pub fn transform(&self, wo: V3) -> (V3, f64) {
        let [m00, m02, m11, m20, m22] = self.m;
        let v = [
            m00 * wo[0] + m02 * wo[2],
            m11 * wo[1],
            m20 * wo[0] + m22 * wo[2],
        ];
        let len = dot(v, v).sqrt();
        (
            scale(v, 1.0 / len),
            wo[2] / PI * self.det_inv * len * len * len,
        )
    }
}

/// Fit parameters p = [ln sx, ln sy, κ, d] ↦ `[a, b, c, d]`:
/// M = R · [[sx, 0, sx κ], [0, sy, 0], [0, 0, 1]] with R the rotation about y that takes
/// z to (d, 0, 1)/√(1 + d²), i.e. M⁻¹ = [[1/sx, 0, −κ], [0, 1/sy, 0], [0, 0, 1]] Rᵀ,
/// normalised. sx and sy are the lobe's widths, κ its skew (a shear in units of sx),
/// and (d, 0, 1) the normal of the great circle where the LTC drops to zero (its
/// "horizon"). This covers every M⁻¹ of the table's form with positive determinant (the
/// QR decomposition of M's xz block), and the logarithms keep M invertible.
pub fn coefficients_from_params(p: [f64; 4]) -> [f64; 4] {
    let q = libm::exp(-p[0]);
    let [_, _, kappa, d] = p;
    [
        q - kappa * d,
        -d * q - kappa,
        (1.0 + d * d).sqrt() * libm::exp(-p[1]),
        d,
    ]
}

/// The inverse of [`coefficients_from_params`] (for a − b d > 0 and c > 0).
pub fn params_from_coefficients(coefficients: [f64; 4]) -> [f64; 4] {
    let [a, b, c, d] = coefficients;
    let e = 1.0 + d * d;
    let q = (a - d * b) / e;
    let kappa = -(b + d * a) / e;
    [-libm::log(q), libm::log(e.sqrt() / c), kappa, d]
}

/// Fixed samples for the balance-heuristic estimates: cosine-distributed directions (for
/// the LTC) and (u1, cos φ, sin φ) for [`Ggx::sample`], from the points
/// ((k + ½)/n, {k g / n + shift}) of a Fibonacci lattice. Both sets only cover y ≥ 0
/// (φ in [0, π]): the LTC and the target are even in y, so the half is as good as the
/// whole with twice the density.
pub struct SampleSet {
    cosine: Vec<V3>,
    /// The lattice points as (u1, cos φ, sin φ) (also read by the pivot fitter).
    pub(crate) brdf: Vec<[f64; 3]>,
}

impl SampleSet {
    /// The lattice of `n` points with generator `g`, second coordinate shifted by `shift`.
    pub fn new((n, g): (usize, usize), shift: f64) -> SampleSet {
        let mut cosine = Vec::with_capacity(n);
        let mut brdf = Vec::with_capacity(n);
        for k in 0..n {
            let u1 = (k as f64 + 0.5) / n as f64;
            let u2 = ((k * g) % n) as f64 / n as f64 + shift;
            let phi = PI * (u2 - u2.floor());
            let (cos_phi, sin_phi) = (libm::cos(phi), libm::sin(phi));
            let r = u1.sqrt();
            cosine.push([r * cos_phi, r * sin_phi, (1.0 - u1).sqrt()]);
            brdf.push([u1, cos_phi, sin_phi]);
        }
        SampleSet { cosine, brdf }
    }

    /// The samples of the fit.
    pub fn fit() -> SampleSet {
        SampleSet::new(FIT_LATTICE, 0.0)
    }

    /// A larger, different set for measuring the table's error.
    pub fn evaluation() -> SampleSet {
        SampleSet::new(EVALUATION_LATTICE, 0.5 * (5f64.sqrt() - 1.0))
    }
}

/// The normalised target f̂ of one cell, with the BRDF's samples precomputed.
pub struct Target<'a> {
    ggx: Ggx,
    inv_albedo: f64,
    cosine: &'a [V3],
    /// Direction, f̂ and the BRDF sampling density.
    brdf: Vec<(V3, f64, f64)>,
}

impl<'a> Target<'a> {
    /// f̂ = f cos θ / `albedo`, sampled with `set`.
    pub fn new(ggx: Ggx, albedo: f64, set: &'a SampleSet) -> Target<'a> {
        let inv_albedo = 1.0 / albedo;
        let brdf = set
            .brdf
            .iter()
            .map(|&[u1, c, s]| {
                let wi = ggx.sample(u1, c, s);
                (wi, ggx.cosine_weighted(wi) * inv_albedo, ggx.sample_pdf(wi))
            })
            .collect();
        Target {
            ggx,
            inv_albedo,
            cosine: &set.cosine,
            brdf,
        }
    }

    /// ∫ |D − f̂| dω over the sphere: with n samples of each strategy, the balance
    /// heuristic gives (1/n) Σ |D − f̂| / (D + p_BRDF) over both.
    pub fn l1(&self, ltc: &Ltc) -> f64 {
        let mut sum = 0.0;
        for &wo in self.cosine {
            let (w, dl) = ltc.transform(wo);
            let ft = self.ggx.cosine_weighted(w) * self.inv_albedo;
            sum += (dl - ft).abs() / (dl + self.ggx.sample_pdf(w));
        }
        for &(w, ft, pv) in &self.brdf {
            let dl = ltc.density(w);
            sum += (dl - ft).abs() / (dl + pv);
        }
        sum / self.cosine.len() as f64
    }
}

/// Nelder–Mead minimisation of `f` from `x0` with the initial simplex x0 + step_k e_k
/// (reflection 1, expansion 2, contractions ½, shrink ½). A run stops when the values
/// on the simplex agree to `ftol` (relative) or after `max_evals`; it is restarted from
/// the best point while a restart still gains more than `ftol`. Returns the best point,
/// its value and the number of evaluations.
pub fn nelder_mead<const N: usize>(
    f: &mut dyn FnMut(&[f64; N]) -> f64,
    x0: [f64; N],
    step: [f64; N],
    ftol: f64,
    max_evals: usize,
) -> ([f64; N], f64, usize) {
    let mut best = (x0, f(&x0));
    let mut evals = 1;
    loop {
        let before = best.1;
        let mut simplex = vec![best];
        for k in 0..N {
            let mut x = best.0;
            x[k] += step[k];
            simplex.push((x, f(&x)));
            evals += 1;
        }
        while evals < max_evals {
            simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
            if simplex[N].1 - simplex[0].1 <= ftol * simplex[0].1.abs() {
                break;
            }
            let mut centroid = [0.0; N];
            for (x, _) in &simplex[..N] {
                for k in 0..N {
                    centroid[k] += x[k] / N as f64;
                }
            }
            let worst = simplex[N];
            let along = |t: f64| -> [f64; N] {
                std::array::from_fn(|k| centroid[k] + t * (worst.0[k] - centroid[k]))
            };
            let reflected = along(-1.0);
            let fr = f(&reflected);
            evals += 1;
            if fr < simplex[0].1 {
                let expanded = along(-2.0);
                let fe = f(&expanded);
                evals += 1;
                simplex[N] = if fe < fr {
                    (expanded, fe)
                } else {
                    (reflected, fr)
                };
            } else if fr < simplex[N - 1].1 {
                simplex[N] = (reflected, fr);
            } else {
                let contracted = along(if fr < worst.1 { -0.5 } else { 0.5 });
                let fc = f(&contracted);
                evals += 1;
                if fc < fr.min(worst.1) {
                    simplex[N] = (contracted, fc);
                } else {
                    let x0 = simplex[0].0;
                    for (x, fx) in simplex[1..].iter_mut() {
                        for k in 0..N {
                            x[k] = x0[k] + 0.5 * (x[k] - x0[k]);
                        }
                        *fx = f(x);
                        evals += 1;
                    }
                }
            }
        }
        for &candidate in &simplex {
            if candidate.1 < best.1 {
                best = candidate;
            }
        }
        if evals >= max_evals || best.1 >= before * (1.0 - ftol) {
            return (best.0, best.1, evals);
        }
    }
}

/// The relative tolerance of the fit's Nelder–Mead runs.
pub const FIT_TOLERANCE: f64 = 1e-7;
/// The evaluation budget of one Nelder–Mead run (a safety limit).
pub const FIT_MAX_EVALUATIONS: usize = 20_000;
/// The Nelder–Mead initial step of every parameter.
pub const FIT_STEP: f64 = 0.05;

/// The cells whose stored values start the fit of cell (i, j), in order of preference
/// on ties: the previous column (i, j − 1) and the next rougher row (i + 1, j), where they
/// exist. The roughest normal-view cell (63, 0) starts from the cosine itself (M = I).
pub fn warm_start_sources(i: usize, j: usize) -> Vec<(usize, usize)> {
    let mut sources = Vec::new();
    if j > 0 {
        sources.push((i, j - 1));
    }
    if i < LAST {
        sources.push((i + 1, j));
    }
    sources
}

/// The coefficients of the stored cell values.
fn coefficients_of(values: &[f32; 6]) -> [f32; 4] {
    [values[0], values[1], values[2], values[3]]
}

/// One fitted cell.
#[derive(Clone, Copy, Debug)]
pub struct CellFit {
    /// `[a, b, c, d, albedo, fresnel]` as stored.
    pub values: [f32; 6],
    /// The fit's L1 estimate at the optimum (in f64, before rounding to f32).
    pub l1: f64,
    /// Objective evaluations over all starts.
    pub evaluations: usize,
}

/// Fits cell (i, j) from each of `starts` (the stored coefficients of
/// [`warm_start_sources`], or `[1, 0, 1, 0]` for none) and keeps the best (the first on
/// ties).
///
/// In column 0 the view is the normal, the target is rotationally symmetric, and the
/// fit has one parameter: M = diag(s, s, 1). Elsewhere all four parameters of
/// [`coefficients_from_params`] are free. Heitz et al. instead fix d to the slope of the
/// BRDF's mean direction (the third column of their M) and fit three. In our
/// experiments (one start per cell, 1597 samples) freeing d lowered the table's mean L1
/// error from 0.114 to 0.072, and that of the LTCs interpolated bilinearly at the cell
/// centres' midpoints from 0.151 to 0.109; the gain is largest at grazing views, where
/// the best LTC lines its own horizon up with the surface's (d → 0) instead of tilting
/// it with the lobe. (Heitz's objective, ∫ |D − f̂|³, with d fixed, gave 0.121.) With
/// narrow lobes (small α) d and κ are weakly determined, so these parameters wander a
/// little from cell to cell where it does not change the fit. The second start (the
/// rougher row) matters mostly in column 63, where the lobe changes shape abruptly from
/// column 62: it lowered the column's largest L1 error from 0.85 to 0.69.
pub fn fit_cell(i: usize, j: usize, starts: &[[f32; 4]], set: &SampleSet) -> CellFit {
    let ggx = Ggx::of_cell(i, j);
    let moments = moments(&ggx);
    let target = Target::new(ggx, moments.albedo, set);
    let l1_of = |p: [f64; 4]| match Ltc::new(coefficients_from_params(p)) {
        Some(ltc) => target.l1(&ltc),
        None => f64::INFINITY,
    };
    let identity = [[1.0, 0.0, 1.0, 0.0]];
    let starts = if starts.is_empty() {
        &identity[..]
    } else {
        starts
    };
    let mut best: Option<([f64; 4], f64)> = None;
    let mut evaluations = 0;
    for start in starts {
        let p0 = params_from_coefficients(start.map(f64::from));
        let (p, l1, n) = if j == 0 {
            let mut f = |x: &[f64; 1]| l1_of([x[0], x[0], 0.0, 0.0]);
            let (x, l1, n) = nelder_mead(
                &mut f,
                [p0[0]],
                [FIT_STEP],
                FIT_TOLERANCE,
                FIT_MAX_EVALUATIONS,
            );
            ([x[0], x[0], 0.0, 0.0], l1, n)
        } else {
            let mut f = |x: &[f64; 4]| l1_of(*x);
            nelder_mead(
                &mut f,
                p0,
                [FIT_STEP; 4],
                FIT_TOLERANCE,
                FIT_MAX_EVALUATIONS,
            )
        };
        evaluations += n;
        if best.is_none_or(|(_, b)| l1 < b) {
            best = Some((p, l1));
        }
    }
    let (p, l1) = best.expect("at least one start");
    let [a, b, c, d] = coefficients_from_params(p);
    // `+ 0.0` turns the −0 of b in column 0 into +0.
    CellFit {
        values: [
            a as f32,
            b as f32 + 0.0,
            c as f32,
            d as f32 + 0.0,
            moments.albedo as f32,
            moments.fresnel as f32,
        ],
        l1,
        evaluations,
    }
}

/// The starts of cell (i, j) read from a (partly) filled table.
pub fn starts_from(table: &[[f32; 6]], i: usize, j: usize) -> Vec<[f32; 4]> {
    warm_start_sources(i, j)
        .into_iter()
        .map(|(si, sj)| coefficients_of(&table[si * TABLE_SIZE + sj]))
        .collect()
}

/// Fits the whole table on `threads` threads (see [`sweep_anti_diagonals`]). Returns the
/// table and the total number of objective evaluations.
pub fn fit_table(threads: usize) -> (Vec<[f32; 6]>, usize) {
    let set = SampleSet::fit();
    sweep_anti_diagonals(threads, [0f32; 6], |i, j, table| {
        let fit = fit_cell(i, j, &starts_from(table, i, j), &set);
        (fit.values, fit.evaluations)
    })
}

/// Fills a `TABLE_SIZE`² table whose cell (i, j) is fitted from its stored neighbours
/// (i, j − 1) and (i + 1, j): the anti-diagonals (63 − i) + j = 0, 1, …, 126 are fitted in
/// turn, the cells of one in parallel on `threads` threads, so the result does not depend
/// on `threads`. `fit(i, j, table)` returns the cell's values and its objective
/// evaluations; returns the table and their total. Shared by the LTC and the pivot
/// fitter.
pub(crate) fn sweep_anti_diagonals<T: Copy + Send + Sync>(
    threads: usize,
    empty: T,
    fit: impl Fn(usize, usize, &[T]) -> (T, usize) + Sync,
) -> (Vec<T>, usize) {
    let mut table = vec![empty; TABLE_SIZE * TABLE_SIZE];
    let mut evaluations = 0;
    for diagonal in 0..2 * TABLE_SIZE - 1 {
        let cells: Vec<(usize, usize)> = (diagonal.saturating_sub(LAST)..=diagonal.min(LAST))
            .map(|j| (LAST + j - diagonal, j))
            .collect();
        let next = std::sync::atomic::AtomicUsize::new(0);
        let results: Vec<(usize, (T, usize))> = std::thread::scope(|scope| {
            let workers: Vec<_> = (0..threads.clamp(1, cells.len()))
                .map(|_| {
                    let (fit, next, table, cells) = (&fit, &next, &table, &cells);
                    scope.spawn(move || {
                        let mut done = Vec::new();
                        loop {
                            let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                            let Some(&(i, j)) = cells.get(k) else {
                                return done;
                            };
                            done.push((i * TABLE_SIZE + j, fit(i, j, table)));
                        }
                    })
                })
                .collect();
            workers
                .into_iter()
                .flat_map(|w| w.join().expect("a fit thread panicked"))
                .collect()
        });
        for (index, (values, count)) in results {
            table[index] = values;
            evaluations += count;
        }
    }
    (table, evaluations)
}

/// L1 distance ∫ |D − f̂| dω of stored cell (i, j), estimated with `set`.
pub fn cell_l1(i: usize, j: usize, values: &[f32; 6], set: &SampleSet) -> f64 {
    let ggx = Ggx::of_cell(i, j);
    let target = Target::new(ggx, moments(&ggx).albedo, set);
    target.l1(&Ltc::of_cell(values).expect("an invertible matrix"))
}

/// The L1 errors of all cells of `table` with [`SampleSet::evaluation`], row-major
/// (rows computed on `threads` threads; the result does not depend on it).
pub fn table_l1(table: &[[f32; 6]], threads: usize) -> Vec<f64> {
    let set = SampleSet::evaluation();
    map_cells(threads, |i, j| {
        cell_l1(i, j, &table[i * TABLE_SIZE + j], &set)
    })
}

/// `f(i, j)` for every cell of a `TABLE_SIZE`² table, row-major, rows computed on
/// `threads` threads (the result does not depend on `threads`). Shared by the LTC and
/// the pivot fitter's error measurements.
pub(crate) fn map_cells<R: Send>(threads: usize, f: impl Fn(usize, usize) -> R + Sync) -> Vec<R> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut rows: Vec<(usize, Vec<R>)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads.max(1))
            .map(|_| {
                let (f, next) = (&f, &next);
                scope.spawn(move || {
                    let mut done = Vec::new();
                    loop {
                        let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        if i >= TABLE_SIZE {
                            return done;
                        }
                        done.push((i, (0..TABLE_SIZE).map(|j| f(i, j)).collect()));
                    }
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().expect("an error thread panicked"))
            .collect()
    });
    rows.sort_by_key(|(i, _)| *i);
    rows.into_iter().flat_map(|(_, row)| row).collect()
}

/// The summary of the L1 errors that the table's documentation states.
pub fn error_summary(errors: &[f64]) -> String {
    let cell = |k: usize| (k / TABLE_SIZE, k % TABLE_SIZE);
    let stats = |keep: &dyn Fn(usize, usize) -> bool| {
        let (mut sum, mut n, mut max, mut at) = (0.0, 0, f64::NEG_INFINITY, (0, 0));
        for (k, &e) in errors.iter().enumerate() {
            let (i, j) = cell(k);
            if keep(i, j) {
                sum += e;
                n += 1;
                if e > max {
                    max = e;
                    at = (i, j);
                }
            }
        }
        (sum / n as f64, max, at)
    };
    let mut out = String::new();
    let mut line = |name: &str, keep: &dyn Fn(usize, usize) -> bool| {
        let (mean, max, (i, j)) = stats(keep);
        writeln!(out, "//! | {name} | {mean:.4} | {max:.4} | ({i}, {j}) |").unwrap();
    };
    line("all cells", &|_, _| true);
    line("cos θo ≥ 0.5 (j ≤ 44)", &|_, j| j <= 44);
    line("j ≤ 62", &|_, j| j <= 62);
    line("column 63 (grazing floor)", &|_, j| j == LAST);
    line("r ≤ 0.25 (i ≤ 15), j ≤ 62", &|i, j| {
        i <= 15 && j <= 62
    });
    line("r ≥ 0.5 (i ≥ 32)", &|i, _| i >= 32);
    out
}

/// The largest |a|, |b|, |c|, |d| and det M⁻¹ of the table, and their cells, as a list.
fn extremes(table: &[[f32; 6]]) -> String {
    let det = |v: &[f32; 6]| {
        let [a, b, c, d] = coefficients_of(v).map(f64::from);
        c * (a - b * d)
    };
    let largest = |key: &dyn Fn(&[f32; 6]) -> f64| {
        let (k, v) = table
            .iter()
            .enumerate()
            .max_by(|x, y| key(x.1).total_cmp(&key(y.1)))
            .expect("a non-empty table");
        format!("{:.2e} at ({}, {})", key(v), k / TABLE_SIZE, k % TABLE_SIZE)
    };
    let mut out = String::new();
    for (n, name) in ["a", "b", "c", "d"].iter().enumerate() {
        let line = largest(&|v| f64::from(v[n].abs()));
        writeln!(out, "//! - |{name}| ≤ {line}").unwrap();
    }
    writeln!(out, "//! - det M⁻¹ ≤ {}", largest(&det)).unwrap();
    out
}

/// Where the error grows, from the means of the rows and columns.
fn error_trend(errors: &[f64]) -> String {
    let mean = |index: &dyn Fn(usize) -> usize, at: usize| {
        (0..errors.len())
            .filter(|&k| index(k) == at)
            .map(|k| errors[k])
            .sum::<f64>()
            / TABLE_SIZE as f64
    };
    let column = |j: usize| mean(&|k| k % TABLE_SIZE, j);
    let row = |i: usize| mean(&|k| k / TABLE_SIZE, i);
    let (worst_row, worst) = (0..TABLE_SIZE)
        .map(|i| (i, row(i)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("rows");
    format!(
        "\
//! The error grows towards grazing views (the mean over a column is {:.3} at the normal,
//! {:.3} in column 62 and {:.3} in column 63) and peaks at middle roughness (the mean over
//! a row is {:.3} in row 0 and {:.3} in row 63, at most {worst:.3} in row {worst_row},
//! r = {:.2}): there the horizon cuts the lobe, which lies stretched along it, a shape no
//! LTC fits well; in column 63 with small α the lobe is a sliver along the horizon.
",
        column(0),
        column(LAST - 1),
        column(LAST),
        row(0),
        row(LAST),
        worst_row as f64 / LAST as f64,
    )
}

/// The generated line of cell (i, j).
pub fn cell_line(i: usize, j: usize, values: &[f32; 6]) -> String {
    let [a, b, c, d, albedo, fresnel] = values;
    format!("    [{a:?}, {b:?}, {c:?}, {d:?}, {albedo:?}, {fresnel:?}], // ({i}, {j})")
}

/// The text of `src/brdf/ltc_table.rs` for `table` with its L1 errors `errors`.
pub fn render(table: &[[f32; 6]], errors: &[f64]) -> String {
    let mut out = String::new();
    out.push_str(&format!(
        "\
//! Linearly transformed cosines (LTC; Heitz, Dupuy, Hill and Neubelt 2016, \"Real-time
//! Polygonal-light Shading with Linearly Transformed Cosines\") fitted to the GGX BRDF.
//!
//! Generated by `cargo run --release -p sphera-tools --bin fit_ltc`
//! (`tools/src/fitters/ltc_fitter.rs`); do not edit. `tools/tests/ltc_table.rs` re-fits cells
//! and compares them with this file.
//!
//! # BRDF
//!
//! Isotropic GGX with roughness r and α = r²: D(h) = α² / (π (cos²θh (α² − 1) + 1)²),
//! Λ(ω) = (√(1 + α² tan²θ) − 1) / 2, the height-correlated Smith term
//! G2 = 1 / (1 + Λ(ωo) + Λ(ωi)) and f = F D G2 / (4 cos θo cos θi), h = (ωo + ωi) / |ωo + ωi|,
//! in the frame with the normal along z and the view ωo = (sin θo, 0, cos θo) (the
//! specular lobe leans towards −x). The fitted shape is f cos θ with F = 1, normalised by
//! its integral, the albedo.
//!
//! # Parameterisation
//!
//! Row i has r = √α = i/63 (row 0 uses α = {MIN_ALPHA:?}, r = 0.01, instead of the mirror
//! α = 0, whose distribution is a Dirac delta that no LTC fits; it is below row 1's
//! α ≈ 2.5·10⁻⁴ and keeps the matrices far inside f32's range, see the extremes below).
//! Column j has t = √(1 − cos θo) = j/63 (column 63 uses cos θo = {MIN_COS_THETA:?},
//! t ≈ 0.99995, instead of 0, where f = D G2 / (4 cos θo cos θi) is 0/0 although f cos θ
//! has a finite limit). A cell holds the inverse LTC matrix
//! M⁻¹ = [[a, 0, b], [0, c, 0], [d, 0, 1]], normalised so that its (2, 2) entry is 1; the
//! LTC density is D(ω) = D_o(M⁻¹ω / ‖M⁻¹ω‖) |det M⁻¹| / ‖M⁻¹ω‖³ with
//! D_o(ω) = max(0, ω_z)/π and |det M⁻¹| = c (a − b d). The extremes of the table:
//!
{extremes}//!
//! # Fit
//!
//! Each cell minimises the L1 distance ∫ |D − f̂| dω between the LTC density D and the
//! normalised target f̂ = f cos θ / albedo (half of it bounds the error of the LTC's
//! integral over any polygon), estimated with the balance heuristic over {fit} samples of
//! the LTC and {fit} of the BRDF's visible normals (spherical caps, Dupuy and Benyoub 2023),
//! from a fixed Fibonacci lattice. Nelder–Mead (restarted until it stops gaining) runs
//! over M = R [[sx, 0, sx κ], [0, sy, 0], [0, 0, 1]] with parameters (ln sx, ln sy, κ, d),
//! R the rotation taking z to (d, 0, 1)/√(1 + d²): all four degrees of freedom (column 0,
//! the normal view, is rotationally symmetric and fits M = diag(s, s, 1)). Each cell
//! starts from the stored values of the previous column (i, j − 1) and of the next
//! rougher row (i + 1, j), where they exist, and keeps the better fit; the roughest
//! normal-view cell starts from M = I.
//!
//! The albedo ∫ f cos θ dω (F = 1) and the Fresnel integral ∫ f (1 − ωo·h)⁵ cos θ dω come
//! from a product Gauss–Legendre rule over (θ, φ) with panels refined geometrically
//! towards the mirror direction and the horizon (relative error below 10⁻⁹ against
//! finer rules).
//!
//! # Error
//!
//! L1 distance ∫ |D − f̂| dω (between 0 and 2) of the stored f32 values, measured with
//! {eval} + {eval} samples of a different lattice:
//!
//! | cells | mean | max | at (i, j) |
//! |---|---|---|---|
{summary}//!
{trend}
/// Cells per axis.
pub const LTC_TABLE_SIZE: usize = {size};
/// The smallest α the table was fitted for (row 0 uses it instead of α = 0).
pub const LTC_MIN_ALPHA: f32 = {MIN_ALPHA:?};
/// The largest view angle's cosine floor (column 63 uses it instead of cos θ = 0).
pub const LTC_MIN_COS_THETA: f32 = {MIN_COS_THETA:?};
/// `LTC_TABLE[i * LTC_TABLE_SIZE + j]` for roughness r = √α = i / 63 and view
/// t = √(1 − cos θo) = j / 63: `[a, b, c, d, albedo, fresnel]` where the inverse LTC matrix is
/// M⁻¹ = [[a, 0, b], [0, c, 0], [d, 0, 1]] (normalised so that its (2,2) entry is 1),
/// albedo = ∫ f₁(ωo, ω) cos θ dω with F = 1, and fresnel = ∫ f₁(ωo, ω) (1 − ωo·h)⁵ cos θ dω,
/// so that with Schlick's Fresnel F = F0 + (1 − F0)(1 − ωo·h)⁵ the directional albedo is F0·(albedo − fresnel) + fresnel.
pub static LTC_TABLE: [[f32; 6]; LTC_TABLE_SIZE * LTC_TABLE_SIZE] = [
",
        fit = FIT_LATTICE.0,
        eval = EVALUATION_LATTICE.0,
        summary = error_summary(errors),
        trend = error_trend(errors),
        extremes = extremes(table),
        size = TABLE_SIZE,
    ));
    push_cell_lines(&mut out, table, cell_line);
    out
}

/// The cell lines `[..], // (i, j)` of a rendered table, row by row, and its end.
pub fn push_cell_lines<T>(
    out: &mut String,
    table: &[T],
    cell_line: impl Fn(usize, usize, &T) -> String,
) {
    for i in 0..TABLE_SIZE {
        for j in 0..TABLE_SIZE {
            out.push_str(&cell_line(i, j, &table[i * TABLE_SIZE + j]));
            out.push('\n');
        }
    }
    out.push_str("];\n");
}

/// The command line of `fit_ltc` and `fit_pivot`: `--threads N` (default: all cores; the
/// output does not depend on it) and `--render-only`. Returns `(threads, render_only)`.
pub fn fitter_arguments() -> (usize, bool) {
    let mut threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut render_only = false;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--render-only" => render_only = true,
            "--threads" => {
                threads = args
                    .next()
                    .and_then(|n| n.parse().ok())
                    .expect("--threads takes a positive integer")
            }
            other => panic!("unknown argument {other:?} (--threads N, --render-only)"),
        }
    }
    (threads, render_only)
}

/// The cells of a rendered table (`N` values a cell: 6 for the LTC table, 3 for the
/// pivot table), read back from its lines `[..], // (i, j)`.
pub fn parse_table<const N: usize>(text: &str) -> Vec<[f32; N]> {
    let mut table = Vec::with_capacity(TABLE_SIZE * TABLE_SIZE);
    for line in text.lines() {
        let Some(rest) = line.strip_prefix("    [") else {
            continue;
        };
        let (numbers, label) = rest.split_once("], // ").expect("a cell line");
        let values: Vec<f32> = numbers
            .split(", ")
            .map(|x| x.parse().expect("an f32 literal"))
            .collect();
        let k = table.len();
        assert_eq!(
            label,
            format!("({}, {})", k / TABLE_SIZE, k % TABLE_SIZE),
            "cells out of order"
        );
        let cell: [f32; N] = values
            .try_into()
            .unwrap_or_else(|_| panic!("{N} values per cell"));
        table.push(cell);
    }
    assert_eq!(table.len(), TABLE_SIZE * TABLE_SIZE, "cell count");
    table
}
