//! Fitter of the pivot table `src/brdf/pivot_table.rs`: uniform spherical pivot-transformed
//! distributions (SPTD; Dupuy, Heitz and Belcour 2017, "A Spherical Cap Preserving
//! Parameterization for Spherical Distributions") that approximate the isotropic GGX BRDF,
//! all in f64. The BRDF, its albedo, the sample lattices, the cell axes, the warm-start
//! schedule and Nelder–Mead are those of the LTC fitter ([`crate::fitters::ltc_fitter`]).
//!
//! # The distribution
//!
//! The pivot transformation of a pivot r_p (|r_p| < 1) maps a unit vector u to the other
//! end of the chord of the unit sphere through u and r_p (Dupuy et al., Eq. 2 restricted
//! to the sphere): with e = u − r_p, the point u + s e on the sphere has
//! 1 + 2s u·e + s² |e|² = 1, so
//!
//! g(u) = u − 2 (u·e / |e|²) e.
//!
//! g is an involution. By the intersecting chords theorem |g(u) − r_p| |u − r_p| = 1 − |r_p|²
//! (the power of r_p), and a small disk of radius δ around u maps to one of radius
//! δ |g(u) − r_p| / |u − r_p| around g(u), so the solid-angle Jacobian of g at ω is
//!
//! J(ω) = ((1 − |r_p|²) / |ω − r_p|²)²    (Eq. 4 and Appendix A of the paper),
//!
//! with J(ω) J(g(ω)) = 1. The uniform SPTD is the distribution of ω = g(u) for u uniform on
//! the sphere: D(ω) = J(ω) / 4π (u = g(ω)), which integrates to one over the sphere (checked
//! by `tools/tests/pivot_table.rs`). It peaks in the direction n = r_p / |r_p| with
//! D = ((1 + ρ)/(1 − ρ))² / 4π, ρ = |r_p|, and is rotationally symmetric about n. With
//! |ω − ρ n|² = ρ |ω − n|² + (1 − ρ)² (expand ω − n + (1 − ρ) n and use
//! 2 (ω − n)·n = −|ω − n|²), D is evaluated without cancellation for ρ → 1.
//!
//! # The fit
//!
//! The pivot lies in the plane of the view: r_p = ρ (sin θp, 0, cos θp), θp measured from
//! the normal, negative towards −x where the specular lobe leans. Each cell minimises the
//! same L1 distance ∫ |D − f̂| dω over the whole sphere as the LTC fitter, estimated with
//! the balance heuristic over the same lattice: uniform directions u of the half sphere
//! y ≥ 0 mapped through g (they land on y ≤ 0, which changes nothing since D and f̂ are even
//! in y) and the BRDF's visible-normal samples. D is not restricted to the upper
//! hemisphere: as in the paper, the fit compares the unrestricted distribution with f̂, so
//! the mass D leaks below the horizon counts in the error (the paper removes it at render
//! time by intersecting with the hemisphere's cap). Nelder–Mead runs over
//! (2 artanh ρ, θp): the first keeps ρ in (−1, 1) and resolves 1 − ρ ~ α near 1.
pub use crate::fitters::ltc_fitter::TABLE_SIZE;
use crate::fitters::ltc_fitter::{
    self, FIT_MAX_EVALUATIONS, FIT_STEP, FIT_TOLERANCE, Ggx, SampleSet, V3, add, dot, scale,
};
use std::f64::consts::PI;
use std::fmt::Write as _;

const LAST: usize = TABLE_SIZE - 1;

/// The largest stored norm: the f32 just below 1 (no cell of the committed table reaches
/// it; the guard only keeps |r_p| < 1 after rounding).
pub const MAX_NORM: f32 = 1.0 - f32::EPSILON / 2.0;

/// A uniform SPTD given by its pivot r_p = ρ (sin θp, 0, cos θp).
#[derive(Clone, Copy, Debug)]
pub struct Sptd {
    rho: f64,
    /// 1 − ρ, kept separately for its relative precision.
    one_minus: f64,
    /// n = (sin θp, 0, cos θp).
    axis: V3,
    /// (1 − ρ²)².
    numerator: f64,
}

impl Sptd {
    /// The SPTD of norm ρ = 1 − `one_minus` (in (−1, 1)) and elevation θp.
    fn with_one_minus(one_minus: f64, elevation: f64) -> Sptd {
        let rho = 1.0 - one_minus;
        let k = one_minus * (1.0 + rho);
        Sptd {
            rho,
            one_minus,
            axis: [libm::sin(elevation), 0.0, libm::cos(elevation)],
            numerator: k * k,
        }
    }

    /// The SPTD of norm ρ in [0, 1) and elevation θp.
    pub fn new(norm: f64, elevation: f64) -> Sptd {
        Sptd::with_one_minus(1.0 - norm, elevation)
    }

    /// The SPTD of a stored cell `[norm, elevation, albedo]`.
    pub fn of_cell(values: &[f32; 3]) -> Sptd {
        Sptd::new(f64::from(values[0]), f64::from(values[1]))
    }

    /// The SPTD of the fit parameters (2 artanh ρ, θp): 1 − ρ = 2 / (e^p + 1).
    fn of_params(p: [f64; 2]) -> Sptd {
        Sptd::with_one_minus(2.0 / (libm::exp(p[0]) + 1.0), p[1])
    }

    /// The fit parameters of a stored cell.
    fn params_of_cell(values: &[f32; 3]) -> [f64; 2] {
        let rho = f64::from(values[0]);
        [libm::log((1.0 + rho) / (1.0 - rho)), f64::from(values[1])]
    }

    /// The pivot r_p.
    pub fn pivot(&self) -> V3 {
        scale(self.axis, self.rho)
    }

    /// |ω − r_p|² = ρ |ω − n|² + (1 − ρ)² for a unit ω.
    fn distance2(&self, w: V3) -> f64 {
        let e = [w[0] - self.axis[0], w[1], w[2] - self.axis[2]];
        self.rho * dot(e, e) + self.one_minus * self.one_minus
    }

    /// D(ω) = ((1 − ρ²) / |ω − r_p|²)² / 4π for a unit ω.
    pub fn density(&self, w: V3) -> f64 {
        let d2 = self.distance2(w);
        self.numerator / (4.0 * PI * d2 * d2)
    }

    /// The pivot transformation g(u) of a unit u and the density D(g(u)) = 1 / (4π J(u)).
    pub fn transform(&self, u: V3) -> (V3, f64) {
        let e = add(u, scale(self.pivot(), -1.0));
        let d2 = self.distance2(u);
        let w = add(u, scale(e, -2.0 * dot(u, e) / d2));
        (w, d2 * d2 / (4.0 * PI * self.numerator))
    }
}

/// The normalised target f̂ of one cell with the BRDF's samples precomputed, and the
/// uniform directions of the half sphere y ≥ 0 (z = 1 − 2 u1 on the lattice points).
pub struct Target {
    ggx: Ggx,
    inv_albedo: f64,
    uniform: Vec<V3>,
    /// Direction, f̂ and the BRDF sampling density.
    brdf: Vec<(V3, f64, f64)>,
}

impl Target {
    /// f̂ = f cos θ / `albedo`, sampled with `set`.
    pub fn new(ggx: Ggx, albedo: f64, set: &SampleSet) -> Target {
        let inv_albedo = 1.0 / albedo;
        let brdf = set
            .brdf
            .iter()
            .map(|&[u1, c, s]| {
                let wi = ggx.sample(u1, c, s);
                (wi, ggx.cosine_weighted(wi) * inv_albedo, ggx.sample_pdf(wi))
            })
            .collect();
        let uniform = set
            .brdf
            .iter()
            .map(|&[u1, c, s]| {
                let z = 1.0 - 2.0 * u1;
                let r = (4.0 * u1 * (1.0 - u1)).sqrt();
                [r * c, r * s, z]
            })
            .collect();
        Target {
            ggx,
            inv_albedo,
            uniform,
            brdf,
        }
    }

    /// ∫ |D − f̂| dω over the sphere: with n samples of each strategy, the balance
    /// heuristic gives (1/n) Σ |D − f̂| / (D + p_BRDF) over both.
    pub fn l1(&self, sptd: &Sptd) -> f64 {
        let mut sum = 0.0;
        for &u in &self.uniform {
            let (w, d) = sptd.transform(u);
            let ft = self.ggx.cosine_weighted(w) * self.inv_albedo;
            sum += (d - ft).abs() / (d + self.ggx.sample_pdf(w));
        }
        for &(w, ft, pv) in &self.brdf {
            let d = sptd.density(w);
            sum += (d - ft).abs() / (d + pv);
        }
        sum / self.uniform.len() as f64
    }

    /// The fraction of D's mass below the horizon, ∫_{z < 0} D dω, estimated from the
    /// mapped uniform samples.
    pub fn leak(&self, sptd: &Sptd) -> f64 {
        let below = self
            .uniform
            .iter()
            .filter(|&&u| sptd.transform(u).0[2] < 0.0)
            .count();
        below as f64 / self.uniform.len() as f64
    }
}

/// One fitted cell.
#[derive(Clone, Copy, Debug)]
pub struct CellFit {
    /// `[norm, elevation, albedo]` as stored.
    pub values: [f32; 3],
    /// The fit's L1 estimate at the optimum (in f64, before rounding to f32).
    pub l1: f64,
    /// Objective evaluations over all starts.
    pub evaluations: usize,
}

/// The start of the first cell fitted, (63, 0): ρ = ½ on the normal.
pub const FIRST_START: [f32; 3] = [0.5, 0.0, 0.0];

/// Fits cell (i, j) from each of `starts` (stored cells of
/// [`ltc_fitter::warm_start_sources`], or [`FIRST_START`] for none) and keeps the best
/// (the first on ties). In column 0 the view is the normal and θp = 0: one parameter.
/// Elsewhere both (2 artanh ρ, θp) are free. The result is folded to ρ ≥ 0 (a negative ρ
/// is the pivot −ρ in the opposite direction) with θp in (−π, π], and ρ is stored at most
/// [`MAX_NORM`].
pub fn fit_cell(i: usize, j: usize, starts: &[[f32; 3]], set: &SampleSet) -> CellFit {
    let ggx = Ggx::of_cell(i, j);
    let albedo = ltc_fitter::moments(&ggx).albedo;
    let target = Target::new(ggx, albedo, set);
    let l1_of = |p: [f64; 2]| {
        let value = target.l1(&Sptd::of_params(p));
        if value.is_finite() {
            value
        } else {
            f64::INFINITY
        }
    };
    let first = [FIRST_START];
    let starts = if starts.is_empty() {
        &first[..]
    } else {
        starts
    };
    let mut best: Option<([f64; 2], f64)> = None;
    let mut evaluations = 0;
    for start in starts {
        let p0 = Sptd::params_of_cell(start);
        let (p, l1, n) = if j == 0 {
            let mut f = |x: &[f64; 1]| l1_of([x[0], 0.0]);
            let (x, l1, n) = ltc_fitter::nelder_mead(
                &mut f,
                [p0[0]],
                [FIT_STEP],
                FIT_TOLERANCE,
                FIT_MAX_EVALUATIONS,
            );
            ([x[0], 0.0], l1, n)
        } else {
            let mut f = |x: &[f64; 2]| l1_of(*x);
            ltc_fitter::nelder_mead(
                &mut f,
                p0,
                [FIT_STEP; 2],
                FIT_TOLERANCE,
                FIT_MAX_EVALUATIONS,
            )
        };
        evaluations += n;
        if best.is_none_or(|(_, b)| l1 < b) {
            best = Some((p, l1));
        }
    }
    let ([p, mut elevation], l1) = best.expect("at least one start");
    // ρ = tanh(p / 2).
    let norm = -libm::expm1(-p.abs()) / (1.0 + libm::exp(-p.abs()));
    if p < 0.0 {
        elevation += PI;
    }
    elevation = libm::remainder(elevation, 2.0 * PI);
    if elevation <= -PI {
        elevation += 2.0 * PI;
    }
    CellFit {
        values: [
            (norm as f32).min(MAX_NORM),
            elevation as f32 + 0.0,
            albedo as f32,
        ],
        l1,
        evaluations,
    }
}

/// The starts of cell (i, j) read from a (partly) filled table.
pub fn starts_from(table: &[[f32; 3]], i: usize, j: usize) -> Vec<[f32; 3]> {
    ltc_fitter::warm_start_sources(i, j)
        .into_iter()
        .map(|(si, sj)| table[si * TABLE_SIZE + sj])
        .collect()
}

/// Fits the whole table on `threads` threads, anti-diagonal by anti-diagonal as the LTC
/// fitter does (cell (i, j) starts from (i, j − 1) and (i + 1, j)); the result does not
/// depend on `threads`. Returns the table and the total number of objective evaluations.
pub fn fit_table(threads: usize) -> (Vec<[f32; 3]>, usize) {
    let set = SampleSet::fit();
    ltc_fitter::sweep_anti_diagonals(threads, [0f32; 3], |i, j, table| {
        let fit = fit_cell(i, j, &starts_from(table, i, j), &set);
        (fit.values, fit.evaluations)
    })
}

/// L1 distance ∫ |D − f̂| dω and the mass below the horizon of stored cell (i, j),
/// estimated with `set`.
pub fn cell_errors(i: usize, j: usize, values: &[f32; 3], set: &SampleSet) -> (f64, f64) {
    let ggx = Ggx::of_cell(i, j);
    let target = Target::new(ggx, ltc_fitter::moments(&ggx).albedo, set);
    let sptd = Sptd::of_cell(values);
    (target.l1(&sptd), target.leak(&sptd))
}

/// The L1 errors and leaks of all cells of `table` with [`SampleSet::evaluation`],
/// row-major (rows computed on `threads` threads; the result does not depend on it).
pub fn table_errors(table: &[[f32; 3]], threads: usize) -> (Vec<f64>, Vec<f64>) {
    let set = SampleSet::evaluation();
    let cells = ltc_fitter::map_cells(threads, |i, j| {
        cell_errors(i, j, &table[i * TABLE_SIZE + j], &set)
    });
    cells.into_iter().unzip()
}

/// The regions of the error summary.
type Region = (&'static str, fn(usize, usize) -> bool);
const REGIONS: [Region; 6] = [
    ("all cells", |_, _| true),
    ("cos θo ≥ 0.5 (j ≤ 44)", |_, j| j <= 44),
    ("j ≤ 62", |_, j| j <= 62),
    ("column 63 (grazing floor)", |_, j| j == LAST),
    ("r ≤ 0.25 (i ≤ 15), j ≤ 62", |i, j| i <= 15 && j <= 62),
    ("r ≥ 0.5 (i ≥ 32)", |i, _| i >= 32),
];

/// Mean, max and the cell of the max of `values` over the cells kept by `keep`.
fn stats(values: &[f64], keep: fn(usize, usize) -> bool) -> (f64, f64, (usize, usize)) {
    let (mut sum, mut n, mut max, mut at) = (0.0, 0, f64::NEG_INFINITY, (0, 0));
    for (k, &e) in values.iter().enumerate() {
        let (i, j) = (k / TABLE_SIZE, k % TABLE_SIZE);
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
}

/// The error table of the documentation: the SPTD's L1 (mean, max, where), the LTC
/// table's L1 on the same cells (mean, max) and the SPTD's mean mass below the horizon.
pub fn error_summary(l1: &[f64], leak: &[f64], ltc_l1: &[f64]) -> String {
    let mut out = String::new();
    for (name, keep) in REGIONS {
        let (mean, max, (i, j)) = stats(l1, keep);
        let (ltc_mean, ltc_max, _) = stats(ltc_l1, keep);
        let (leak_mean, _, _) = stats(leak, keep);
        writeln!(
            out,
            "//! | {name} | {mean:.4} | {max:.4} | ({i}, {j}) | {ltc_mean:.4} | {ltc_max:.4} \
             | {leak_mean:.4} |"
        )
        .unwrap();
    }
    out
}

/// Where the error grows, and how often the SPTD beats the LTC.
fn error_trend(l1: &[f64], ltc_l1: &[f64]) -> String {
    let mean = |index: &dyn Fn(usize) -> usize, at: usize| {
        (0..l1.len())
            .filter(|&k| index(k) == at)
            .map(|k| l1[k])
            .sum::<f64>()
            / TABLE_SIZE as f64
    };
    let column = |j: usize| mean(&|k| k % TABLE_SIZE, j);
    let row = |i: usize| mean(&|k| k / TABLE_SIZE, i);
    let better = l1.iter().zip(ltc_l1).filter(|(s, l)| s < l).count();
    format!(
        "\
//! The mean over a column is {:.3} at the normal, {:.3} in column 44, {:.3} in column 62
//! and {:.3} in column 63; the mean over a row is {:.3} in row 0, {:.3} in row 31 and
//! {:.3} in row 63. The SPTD has the smaller L1 error in {better} of the {} cells. Narrow
//! lobes seen from the normal have the SPTD's own shape: near the mirror direction GGX's
//! D(h) ∝ 1/(α² + θh²)² is, with θ = 2θh, ∝ 1/(4α² + θ²)², and the SPTD is
//! ∝ 1/((1 − ρ)²/ρ + θ²)² about its axis, so 1 − ρ ≈ 2α fits it almost exactly (cell
//! (0, 0)). Away from the normal the reflected lobe is anisotropic: a tilt δ of h across
//! the plane of incidence turns ω by 2δ cos θo, one within it by 2δ, so the lobe is
//! narrower across the plane by the factor cos θo, which the rotationally symmetric SPTD
//! cannot follow; rough lobes are wide and the SPTD's mass below the horizon counts in
//! full; at grazing views the horizon cuts the lobe, whose bulk the SPTD then misses.
//! These are the shapes where the four-parameter LTC does better (a cosine restricted to
//! its own hemisphere, any linear stretch); the SPTD's advantages are elsewhere
//! (closed-form integrals over spherical caps, which the paper renders with the
//! hemisphere's cap removing the leak).
",
        column(0),
        column(44),
        column(LAST - 1),
        column(LAST),
        row(0),
        row(31),
        row(LAST),
        l1.len(),
    )
}

/// The extremes of the norm and the elevation.
fn extremes(table: &[[f32; 3]]) -> String {
    let (mut max_norm, mut at_norm) = (f32::NEG_INFINITY, 0);
    let (mut min_norm, mut at_min) = (f32::INFINITY, 0);
    let (mut min_elevation, mut at_elevation) = (f32::INFINITY, 0);
    let (mut max_elevation, mut at_max_elevation) = (f32::NEG_INFINITY, 0);
    for (k, v) in table.iter().enumerate() {
        if v[0] > max_norm {
            (max_norm, at_norm) = (v[0], k);
        }
        if v[0] < min_norm {
            (min_norm, at_min) = (v[0], k);
        }
        if v[1] < min_elevation {
            (min_elevation, at_elevation) = (v[1], k);
        }
        if v[1] > max_elevation {
            (max_elevation, at_max_elevation) = (v[1], k);
        }
    }
    let at = |k: usize| format!("({}, {})", k / TABLE_SIZE, k % TABLE_SIZE);
    format!(
        "\
//! The norm lies in [{min_norm:?}, {max_norm:?}] (min at {}, max at {}: 1 − ρ = {:.2e}), the
//! elevation in [{min_elevation:?}, {max_elevation:?}] rad (min at {}, max at {}: in the
//! roughest rows the pivot stays near the normal, where the leak below the horizon is
//! smallest, and in a few cells it is tilted slightly towards +x).
",
        at(at_min),
        at(at_norm),
        1.0 - f64::from(max_norm),
        at(at_elevation),
        at(at_max_elevation),
    )
}

/// The generated line of cell (i, j).
pub fn cell_line(i: usize, j: usize, values: &[f32; 3]) -> String {
    let [norm, elevation, albedo] = values;
    format!("    [{norm:?}, {elevation:?}, {albedo:?}], // ({i}, {j})")
}

/// The prefix of the documentation line that states the fit's runtime (kept by
/// `--render-only`).
pub const RUNTIME_PREFIX: &str = "//! Fitting took ";

/// The text of `src/brdf/pivot_table.rs` for `table`, its L1 errors and leaks, the LTC
/// table's L1 errors `ltc_l1`, and the runtime line `runtime` (starting with
/// [`RUNTIME_PREFIX`]).
pub fn render(
    table: &[[f32; 3]],
    l1: &[f64],
    leak: &[f64],
    ltc_l1: &[f64],
    runtime: &str,
) -> String {
    let mut out = String::new();
    out.push_str(&format!(
        "\
//! Uniform spherical pivot-transformed distributions (SPTD; Dupuy, Heitz and Belcour 2017,
//! \"A Spherical Cap Preserving Parameterization for Spherical Distributions\") fitted to
//! the GGX BRDF.
//!
//! Generated by `cargo run --release -p sphera-tools --bin fit_pivot`
//! (`tools/src/fitters/pivot_fitter.rs`); do not edit. `tools/tests/pivot_table.rs` re-fits cells
//! and compares them with this file.
//!
//! # BRDF
//!
//! The BRDF of the LTC table (`ltc_table.rs`): isotropic GGX with roughness r and α = r²,
//! D(h) = α² / (π (cos²θh (α² − 1) + 1)²), the height-correlated Smith term
//! G2 = 1 / (1 + Λ(ωo) + Λ(ωi)), Λ(ω) = (√(1 + α² tan²θ) − 1) / 2, and
//! f = F D G2 / (4 cos θo cos θi), in the frame with the normal along z and the view
//! ωo = (sin θo, 0, cos θo) (the specular lobe leans towards −x). The fitted shape is
//! f cos θ with F = 1, normalised by its integral, the albedo.
//!
//! # Parameterisation
//!
//! The axes of the LTC table: row i has r = √α = i/63 (row 0 uses α = 10⁻⁴), column j has
//! t = √(1 − cos θo) = j/63 (column 63 uses cos θo = 10⁻⁴). A cell holds the pivot's norm
//! ρ = |r_p| in [0, 1), its elevation θp in radians, and the albedo ∫ f cos θ dω (F = 1,
//! the LTC table's albedo column): the pivot is r_p = ρ (sin θp, 0, cos θp), θp measured
//! from the normal and negative towards −x. The pivot transformation g maps a unit u to
//! the other end of the chord of the unit sphere through u and r_p; the uniform SPTD is
//! the distribution of g(u) for u uniform on the sphere, with density
//!
//! D(ω) = (1/4π) ((1 − ρ²) / |ω − r_p|²)²,
//!
//! the Jacobian of g (Eq. 4 of the paper) over 4π. It is rotationally symmetric about
//! r_p / ρ, where it peaks, and is defined over the whole sphere: it leaks below the
//! horizon (the last column of the error table is its mass there), which the paper
//! removes when rendering by intersecting with the cap of the upper hemisphere.
//!
{extremes}//!
//! # Fit
//!
//! Each cell minimises the L1 distance ∫ |D − f̂| dω over the whole sphere between the
//! unrestricted SPTD and the normalised target f̂ = f cos θ / albedo (zero below the
//! horizon, so the leaked mass counts as error, as in the paper's fit), estimated with the
//! balance heuristic over {fit} uniform directions mapped through g and {fit} samples of the
//! BRDF's visible normals, from the LTC fitter's Fibonacci lattice. Nelder–Mead (restarted
//! until it stops gaining) runs over (2 artanh ρ, θp); column 0, the normal view, fixes
//! θp = 0. Each cell starts from the stored values of the previous column (i, j − 1) and
//! of the next rougher row (i + 1, j), where they exist, and keeps the better fit; cell
//! (63, 0) starts from ρ = ½. The albedo comes from the LTC fitter's quadrature.
{runtime}
//!
//! # Error
//!
//! L1 distance ∫ |D − f̂| dω (between 0 and 2; half of it bounds the error of the integral
//! over any set of directions) of the stored f32 values, measured with {eval} + {eval}
//! samples of a different lattice, next to the same measure of the LTC table
//! (`ltc_table.rs`) on the same cells, and the SPTD's mean mass below the horizon:
//!
//! | cells | SPTD mean | SPTD max | at (i, j) | LTC mean | LTC max | SPTD leak |
//! |---|---|---|---|---|---|---|
{summary}//!
{trend}
/// Cells per axis.
pub const PIVOT_TABLE_SIZE: usize = {size};
/// `PIVOT_TABLE[i * PIVOT_TABLE_SIZE + j]` for roughness r = √α = i / 63 (α ≥ 10⁻⁴) and view
/// t = √(1 − cos θo) = j / 63 (cos θo ≥ 10⁻⁴): `[norm, elevation, albedo]`, the pivot
/// r_p = norm · (sin(elevation), 0, cos(elevation)) with 0 ≤ norm < 1 and the elevation in
/// radians from the normal (negative: towards −x, the side the lobe leans to for the view
/// (sin θo, 0, cos θo); slightly positive in a few of the roughest cells), and albedo = ∫ f₁(ωo, ω) cos θ dω with F = 1.
pub static PIVOT_TABLE: [[f32; 3]; PIVOT_TABLE_SIZE * PIVOT_TABLE_SIZE] = [
",
        fit = ltc_fitter::FIT_LATTICE.0,
        eval = ltc_fitter::EVALUATION_LATTICE.0,
        summary = error_summary(l1, leak, ltc_l1),
        trend = error_trend(l1, ltc_l1),
        extremes = extremes(table),
        size = TABLE_SIZE,
    ));
    ltc_fitter::push_cell_lines(&mut out, table, cell_line);
    out
}

/// The runtime line of a rendered table.
pub fn runtime_line(text: &str) -> String {
    text.lines()
        .find(|l| l.starts_with(RUNTIME_PREFIX))
        .expect("a runtime line")
        .to_string()
}

/// The cells of a rendered table, read back from its lines `[..], // (i, j)`.
pub fn parse_table(text: &str) -> Vec<[f32; 3]> {
    ltc_fitter::parse_table(text)
}

/// The Cartesian cell of a stored cell `[norm, elevation, albedo]`: the pivot's
/// components in the view frame, `[ρ sin θp, ρ cos θp, albedo]` (its `x` towards the
/// view's azimuth and `z` along the normal; `y` is 0), computed in `f64` from the stored
/// `f32` values and rounded once.
pub fn cartesian_cell(values: &[f32; 3]) -> [f32; 3] {
    let [norm, elevation, albedo] = values.map(f64::from);
    [
        (norm * libm::sin(elevation)) as f32,
        (norm * libm::cos(elevation)) as f32,
        albedo as f32,
    ]
}

/// The text of `src/brdf/pivot_cartesian_table.rs` for the polar `table` of
/// `src/brdf/pivot_table.rs`: its cells by [`cartesian_cell`], one line per cell as there.
pub fn render_cartesian(table: &[[f32; 3]]) -> String {
    let mut out = format!(
        "\
//! The pivot table `pivot_table.rs` in Cartesian form: per cell, the pivot's components in
//! the view frame, `ρ sin θp` (along `x`, the view's azimuth) and `ρ cos θp` (along the
//! normal `z`), and the albedo, so that the fit interpolates the pivot's components
//! bilinearly and needs no sine and cosine of an interpolated elevation at run time.
//!
//! Generated from `pivot_table.rs` by `cargo run --release -p sphera-tools --bin
//! generate_pivot_cartesian_table` (`pivot_fitter::render_cartesian`; the components in
//! `f64` from the stored `f32` norm and elevation, rounded once); do not edit.
//! `tools/tests/pivot_table.rs` regenerates it and compares.
//!
//! A bilinear interpolation is a convex combination of the four corners, so an
//! interpolated pivot is no longer than the longest corner's (norm at most 0.9999671,
//! `pivot_table.rs`), up to rounding: within `|r_p| < 1`.

/// Cells per axis, as in `pivot_table.rs`.
pub const PIVOT_CARTESIAN_TABLE_SIZE: usize = {size};
/// `PIVOT_CARTESIAN_TABLE[i * PIVOT_CARTESIAN_TABLE_SIZE + j]` for roughness r = √α = i / 63
/// and view t = √(1 − cos θo) = j / 63 (the cells of `PIVOT_TABLE`): `[x, z, albedo]`, the
/// pivot r_p = (x, 0, z) = norm · (sin(elevation), 0, cos(elevation)) for the view
/// (sin θo, 0, cos θo), and `PIVOT_TABLE`'s albedo.
pub static PIVOT_CARTESIAN_TABLE: [[f32; 3]; PIVOT_CARTESIAN_TABLE_SIZE * PIVOT_CARTESIAN_TABLE_SIZE] = [
",
        size = TABLE_SIZE,
    );
    let cells: Vec<[f32; 3]> = table.iter().map(cartesian_cell).collect();
    ltc_fitter::push_cell_lines(&mut out, &cells, |i, j, values: &[f32; 3]| {
        let [x, z, albedo] = values;
        format!("    [{x:?}, {z:?}, {albedo:?}], // ({i}, {j})")
    });
    out
}
