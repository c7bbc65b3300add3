//! Tests of the GGX BRDF: the distribution of sampled directions (chi-square against
//! cell probabilities integrated from an independent f64 implementation of the
//! textbook formulas), pdf consistency, the normalisation identities of `D`, the white
//! furnace, reciprocity, the `α` clamp and bad input.
//!
//! Cells live in a parametrisation `(q, b) ∈ [0, 1)²` of the half vector adapted to
//! the lobe: `b = φh / 2π` and `tan θh = α tan(πq/2)`, under which `D cos θh dω_h =
//! (π/2) sin(πq) dq db` for every `α` (so a narrow lobe is spread over the whole
//! square). Every term of the integrands is smooth in `(q, b)`, also at the pole and
//! at the horizon, so Gauss–Legendre quadrature converges on every cell. Cells that the
//! horizon of the reflected direction (or `ωo·h = 0`) crosses are subdivided
//! adaptively.
use super::*;
use crate::testing::*;
use core::f64::consts::PI;

const ALPHAS: [f32; 5] = [0.01, 0.1, 0.3, 0.6, 1.0];
const VIEW_DEGREES: [f64; 4] = [0.0, 45.0, 80.0, 89.0];

/// The view direction at `degrees` from the normal, at an azimuth off the axes.
fn view(degrees: f64) -> Vec3 {
    let (theta, phi) = (degrees.to_radians(), 0.7f64);
    Vec3::new(
        (theta.sin() * phi.cos()) as f32,
        (theta.sin() * phi.sin()) as f32,
        theta.cos() as f32,
    )
}

// ---- the f64 reference, from the textbook formulas -------------------------------

fn d64(alpha: f64, h: D3) -> f64 {
    let c = h[2] / norm(h);
    if c <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    a2 / (PI * (c * c * (a2 - 1.0) + 1.0).powi(2))
}

fn lambda64(alpha: f64, w: D3) -> f64 {
    let c = w[2] / norm(w);
    let tan2 = (1.0 - c * c) / (c * c);
    (-1.0 + (1.0 + alpha * alpha * tan2).sqrt()) / 2.0
}

fn g1_64(alpha: f64, w: D3) -> f64 {
    if w[2] <= 0.0 {
        0.0
    } else {
        1.0 / (1.0 + lambda64(alpha, w))
    }
}

fn g2_64(alpha: f64, wo: D3, wi: D3) -> f64 {
    if wo[2] <= 0.0 || wi[2] <= 0.0 {
        0.0
    } else {
        1.0 / (1.0 + lambda64(alpha, wo) + lambda64(alpha, wi))
    }
}

/// The density of visible normals `D_ωo(h) = G1(ωo) max(0, ωo·h) D(h) / ωo,z`.
fn vndf64(alpha: f64, wo: D3, h: D3) -> f64 {
    g1_64(alpha, wo) * dot(wo, h).max(0.0) * d64(alpha, h) / wo[2]
}

/// The density of reflected directions `D_ωo(h) / (4 ωo·h)`, 0 below the horizon.
fn pdf64(alpha: f64, wo: D3, wi: D3) -> f64 {
    if wi[2] <= 0.0 || wo[2] <= 0.0 {
        return 0.0;
    }
    let h = normalize(add(wo, wi));
    let cos = dot(wo, h);
    if cos <= 0.0 {
        0.0
    } else {
        vndf64(alpha, wo, h) / (4.0 * cos)
    }
}

/// `F D G2 / (4 ωo,z ωi,z)` with Schlick's `F` for a scalar `F0`.
fn brdf64(alpha: f64, f0: f64, wo: D3, wi: D3) -> f64 {
    if wo[2] <= 0.0 || wi[2] <= 0.0 {
        return 0.0;
    }
    let h = normalize(add(wo, wi));
    let fresnel = f0 + (1.0 - f0) * (1.0 - dot(wo, h)).powi(5);
    fresnel * d64(alpha, h) * g2_64(alpha, wo, wi) / (4.0 * wo[2] * wi[2])
}

fn reflect64(wo: D3, h: D3) -> D3 {
    sub(scale(h, 2.0 * dot(wo, h)), wo)
}

// ---- the half-vector parametrisation and the adaptive quadrature ----------------

/// The half vector at `(q, b)` and the Jacobian `dω_h / (dq db)`: `φ = 2π b` and
/// `tan θ = α tan(πq/2)`. With `s, c = sin, cos(πq/2)` and `N = c² + α² s²`,
/// `sin θ = α s / √N`, `cos θ = c / √N`, `dθ/dq = (π/2) α / N`, so
/// `dω_h = sin θ dθ dφ = π² α² s / N^(3/2) dq db`.
fn half_vector(alpha: f64, q: f64, b: f64) -> (D3, f64) {
    let (s, c) = (0.5 * PI * q).sin_cos();
    let n = c * c + alpha * alpha * s * s;
    let root = n.sqrt();
    let (sin_theta, cos_theta) = (alpha * s / root, c / root);
    let (sin_phi, cos_phi) = (2.0 * PI * b).sin_cos();
    let jacobian = PI * PI * alpha * alpha * s / (n * root);
    (
        [sin_theta * cos_phi, sin_theta * sin_phi, cos_theta],
        jacobian,
    )
}

/// `(q, b)` of a half vector above the horizon.
fn parameters(alpha: f64, h: D3) -> (f64, f64) {
    let h = normalize(h);
    let sin_theta = (h[0] * h[0] + h[1] * h[1]).sqrt();
    let q = sin_theta.atan2(alpha * h[2]) / (0.5 * PI);
    let b = (h[1].atan2(h[0]) / (2.0 * PI)).rem_euclid(1.0);
    (q, b)
}

/// Gauss–Legendre nodes and weights of order 4 on `[0, 1]`.
fn gauss_legendre_4() -> [(f64, f64); 4] {
    let (x0, x1) = (0.339_981_043_584_856_3, 0.861_136_311_594_052_6);
    let (w0, w1) = (0.652_145_154_862_546_1, 0.347_854_845_137_453_9);
    [
        ((1.0 - x1) / 2.0, w1 / 2.0),
        ((1.0 - x0) / 2.0, w0 / 2.0),
        ((1.0 + x0) / 2.0, w0 / 2.0),
        ((1.0 + x1) / 2.0, w1 / 2.0),
    ]
}

/// Where a half vector `h` takes the view `ωo`: not visible (`ωo·h <= 0`), reflected
/// above the horizon, or reflected at or below it.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Region {
    Hidden,
    Above,
    Below,
}

fn region(wo: D3, h: D3) -> Region {
    if dot(wo, h) <= 0.0 {
        Region::Hidden
    } else if reflect64(wo, h)[2] > 0.0 {
        Region::Above
    } else {
        Region::Below
    }
}

/// `∫∫ f` over the part of `[x0, x1] × [y0, y1]` in region `wanted`, where `f` returns
/// the region of a point and the integrand there: 4×4 Gauss–Legendre over the nodes in
/// the region, subdivided (up to `depth` times) where the nodes, or the points of a
/// 5×5 grid through the corners, do not all lie in one region. (Labelling every
/// region, not just "inside" and "outside", finds the cells where a thin sliver of the
/// wanted region runs between two others.)
fn integrate(
    f: &impl Fn(f64, f64) -> (Region, f64),
    wanted: Region,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    depth: u32,
) -> f64 {
    let rule = gauss_legendre_4();
    let first = f(x0, y0).0;
    let mut mixed = false;
    if depth > 0 {
        for i in 0..5 {
            for j in 0..5 {
                let (x, y) = (
                    x0 + (x1 - x0) * i as f64 / 4.0,
                    y0 + (y1 - y0) * j as f64 / 4.0,
                );
                mixed |= f(x, y).0 != first;
            }
        }
    }
    let mut sum = 0.0;
    for &(x, wx) in &rule {
        for &(y, wy) in &rule {
            let (label, value) = f(x0 + (x1 - x0) * x, y0 + (y1 - y0) * y);
            mixed |= label != first;
            if label == wanted {
                sum += wx * wy * value;
            }
        }
    }
    if mixed && depth > 0 {
        let (xm, ym) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        integrate(f, wanted, (x0, xm), (y0, ym), depth - 1)
            + integrate(f, wanted, (xm, x1), (y0, ym), depth - 1)
            + integrate(f, wanted, (x0, xm), (ym, y1), depth - 1)
            + integrate(f, wanted, (xm, x1), (ym, y1), depth - 1)
    } else {
        sum * (x1 - x0) * (y1 - y0)
    }
}

/// `∫ f(h) dω_h` over the half vectors in region `wanted` for the view `wo`, on a
/// `cells × cells` grid of `(q, b)`.
fn integrate_over_half_vectors(
    alpha: f64,
    wo: D3,
    wanted: Region,
    cells: usize,
    f: impl Fn(D3) -> f64,
) -> f64 {
    let integrand = |q: f64, b: f64| {
        let (h, jacobian) = half_vector(alpha, q, b);
        let label = region(wo, h);
        (
            label,
            if label == wanted {
                f(h) * jacobian
            } else {
                0.0
            },
        )
    };
    let mut total = 0.0;
    let step = 1.0 / cells as f64;
    for i in 0..cells {
        for j in 0..cells {
            let (x, y) = (i as f64 * step, j as f64 * step);
            total += integrate(&integrand, wanted, (x, x + step), (y, y + step), 8);
        }
    }
    total
}

// ---- the distribution of samples ----------------------------------------------------

const CELLS: usize = 24;

/// The cell of a half vector on the `CELLS × CELLS` grid of `(q, b)`.
fn cell_of(alpha: f64, h: D3) -> usize {
    let (q, b) = parameters(alpha, h);
    let i = ((q * CELLS as f64) as usize).min(CELLS - 1);
    let j = ((b * CELLS as f64) as usize).min(CELLS - 1);
    i * CELLS + j
}

/// The probabilities of the cells for the half vectors of reflected directions above
/// the horizon, then of the reflection falling at or below the horizon (the last
/// entry): `∫ pdf64(ωo, ωi(h)) 4 (ωo·h) dω_h` over each cell.
fn reflected_cell_probabilities(alpha: f64, wo: D3) -> Vec<f64> {
    let step = 1.0 / CELLS as f64;
    let integrand = |q: f64, b: f64| {
        let (h, jacobian) = half_vector(alpha, q, b);
        let label = region(wo, h);
        let value = match label {
            Region::Hidden => 0.0,
            Region::Above => pdf64(alpha, wo, reflect64(wo, h)) * 4.0 * dot(wo, h) * jacobian,
            Region::Below => vndf64(alpha, wo, h) * jacobian,
        };
        (label, value)
    };
    let mut probabilities = Vec::with_capacity(CELLS * CELLS + 1);
    let mut lost = 0.0;
    for i in 0..CELLS {
        for j in 0..CELLS {
            let (x, y) = (
                (i as f64 * step, (i + 1) as f64 * step),
                (j as f64 * step, (j + 1) as f64 * step),
            );
            probabilities.push(integrate(&integrand, Region::Above, x, y, 8));
            lost += integrate(&integrand, Region::Below, x, y, 8);
        }
    }
    probabilities.push(lost);
    probabilities
}

/// The probabilities of the cells for visible normals: `∫ D_ωo(h) dω_h`.
fn visible_normal_cell_probabilities(alpha: f64, wo: D3) -> Vec<f64> {
    let step = 1.0 / CELLS as f64;
    let integrand = |q: f64, b: f64| {
        let (h, jacobian) = half_vector(alpha, q, b);
        // Above and below the horizon after reflection are one region here.
        let label = if dot(wo, h) > 0.0 {
            Region::Above
        } else {
            Region::Hidden
        };
        (label, vndf64(alpha, wo, h) * jacobian)
    };
    let mut probabilities = Vec::with_capacity(CELLS * CELLS);
    for i in 0..CELLS {
        for j in 0..CELLS {
            let (x, y) = (
                (i as f64 * step, (i + 1) as f64 * step),
                (j as f64 * step, (j + 1) as f64 * step),
            );
            probabilities.push(integrate(&integrand, Region::Above, x, y, 8));
        }
    }
    probabilities
}

#[test]
fn reference_probabilities_sum_to_one() {
    for alpha in [0.01, 0.3, 1.0] {
        for degrees in [0.0, 89.0] {
            let wo = d3(view(degrees));
            let reflected: f64 = reflected_cell_probabilities(alpha, wo).iter().sum();
            let visible: f64 = visible_normal_cell_probabilities(alpha, wo).iter().sum();
            assert!(
                (reflected - 1.0).abs() < 1e-6,
                "α {alpha}, {degrees}°: {reflected}"
            );
            assert!(
                (visible - 1.0).abs() < 1e-6,
                "α {alpha}, {degrees}°: {visible}"
            );
        }
    }
}

#[test]
fn visible_normals_follow_the_vndf() {
    for (k, &alpha) in ALPHAS.iter().enumerate() {
        let brdf = GgxBrdf::from_alpha(alpha, Vec3::ONE);
        for (l, &degrees) in VIEW_DEGREES.iter().enumerate() {
            let wo = view(degrees);
            let probabilities = visible_normal_cell_probabilities(alpha as f64, d3(wo));
            let mut counts = vec![0u64; CELLS * CELLS];
            let mut rng = Rng::new(1000 + 10 * k as u64 + l as u64);
            for _ in 0..500_000 {
                let h = brdf.sample_visible_normal(wo, [rng.uniform_f32(), rng.uniform_f32()]);
                assert!(h.is_finite() && h.z >= 0.0 && (h.length() - 1.0).abs() < 1e-6);
                counts[cell_of(alpha as f64, d3(h))] += 1;
            }
            let (statistic, dof, p) = chi_square(&counts, &probabilities);
            assert!(
                p > CHI_SQUARE_ALPHA,
                "α {alpha}, view {degrees}°: chi-square {statistic} (dof {dof}), p = {p}"
            );
        }
    }
}

/// The sampled directions follow the f64 reference density (chi-square over the cells
/// of their half vectors, plus one bin for the draws reflected below the horizon);
/// every sample's pdf is `pdf(wo, dir)`, and agrees with the f64 density.
#[test]
fn samples_follow_the_reflected_vndf_and_their_pdf_is_pdf_of_their_direction() {
    for (k, &alpha) in ALPHAS.iter().enumerate() {
        let brdf = GgxBrdf::from_alpha(alpha, Vec3::ONE);
        for (l, &degrees) in VIEW_DEGREES.iter().enumerate() {
            let wo = view(degrees);
            let probabilities = reflected_cell_probabilities(alpha as f64, d3(wo));
            let mut counts = vec![0u64; CELLS * CELLS + 1];
            let mut rng = Rng::new(2000 + 10 * k as u64 + l as u64);
            let (mut worst_consistency, mut worst_reference) = (0.0f64, 0.0f64);
            for _ in 0..1_000_000 {
                let s = brdf.sample(wo, [rng.uniform_f32(), rng.uniform_f32()]);
                if s.pdf == 0.0 {
                    assert_eq!(s, Sample::NONE);
                    counts[CELLS * CELLS] += 1;
                    continue;
                }
                assert!(s.pdf.is_finite() && s.pdf > 0.0 && s.dir.z > 0.0, "{s:?}");
                assert!((s.dir.length() - 1.0).abs() < 1e-6, "{s:?}");
                let wi = d3(s.dir);
                counts[cell_of(alpha as f64, add(d3(wo), wi))] += 1;
                let again = brdf.pdf(wo, s.dir) as f64;
                worst_consistency =
                    worst_consistency.max((again - s.pdf as f64).abs() / s.pdf as f64);
                let reference = pdf64(alpha as f64, d3(wo), wi);
                worst_reference = worst_reference.max((s.pdf as f64 - reference).abs() / reference);
            }
            let (statistic, dof, p) = chi_square(&counts, &probabilities);
            let what = format!("α {alpha}, view {degrees}°");
            assert!(
                p > CHI_SQUARE_ALPHA,
                "{what}: chi-square {statistic} (dof {dof}), p = {p}"
            );
            assert!(worst_consistency <= 1e-4, "{what}: {worst_consistency}");
            assert!(worst_reference <= 1e-5, "{what}: vs f64 {worst_reference}");
        }
    }
}

/// The lost mass (draws reflected below the horizon) is as large as the reference
/// says; in particular it is about 1/2 at `α = 1` and normal incidence, where `h` is
/// cosine distributed and the reflection stays above the horizon only for
/// `θh < 45°` (probability `sin² 45° = 1/2`).
#[test]
fn draws_below_the_horizon_are_lost_as_the_reference_predicts() {
    let brdf = GgxBrdf::from_alpha(1.0, Vec3::ONE);
    let mut rng = Rng::new(5);
    let n = 400_000;
    let lost = (0..n)
        .filter(|_| {
            brdf.sample(Vec3::Z, [rng.uniform_f32(), rng.uniform_f32()])
                .pdf
                == 0.0
        })
        .count() as f64
        / n as f64;
    let reference = *reflected_cell_probabilities(1.0, [0.0, 0.0, 1.0])
        .last()
        .unwrap();
    assert!((reference - 0.5).abs() < 1e-6, "{reference}");
    let sigma = (0.25 / n as f64).sqrt();
    assert!((lost - 0.5).abs() < 5.0 * sigma, "lost {lost}");
}

// ---- normalisation identities and the white furnace -----------------------------

#[test]
fn d_is_normalised_and_visible_projected_area_is_the_view_cosine() {
    for alpha in [MIN_ALPHA, 0.01, 0.1, 0.3, 0.6, 1.0] {
        let brdf = GgxBrdf::from_alpha(alpha, Vec3::ONE);
        let a = alpha as f64;
        // The regions only steer the subdivision: the visible half vectors are those
        // reflected above the horizon and those reflected below it.
        let z = [0.0, 0.0, 1.0];
        let normalisation: f64 = [Region::Above, Region::Below]
            .into_iter()
            .map(|r| integrate_over_half_vectors(a, z, r, 8, |h| brdf.d(to_f32(h)) as f64 * h[2]))
            .sum();
        assert!(
            (normalisation - 1.0).abs() < 1e-3,
            "α {alpha}: ∫ D cos = {normalisation}"
        );
        for degrees in VIEW_DEGREES {
            let wo = view(degrees);
            let g1 = brdf.g1(wo) as f64;
            let projected: f64 = [Region::Above, Region::Below]
                .into_iter()
                .map(|r| {
                    integrate_over_half_vectors(a, d3(wo), r, 8, |h| {
                        g1 * dot(d3(wo), h) * brdf.d(to_f32(h)) as f64
                    })
                })
                .sum();
            let expected = wo.z as f64;
            assert!(
                (projected - expected).abs() < 1e-3 * expected,
                "α {alpha}, {degrees}°: ∫ G1 (ωo·h) D = {projected}, ωo,z = {expected}"
            );
        }
    }
}

/// `∫ f(ωo, ωi) cos θi dωi` with `F = 1` (f32 `eval`, f64 quadrature over the half
/// vectors, `dωi = 4 (ωo·h) dω_h`).
fn directional_albedo(brdf: &GgxBrdf, wo: Vec3) -> f64 {
    let wo64 = d3(wo);
    integrate_over_half_vectors(brdf.alpha() as f64, wo64, Region::Above, 16, |h| {
        let wi = reflect64(wo64, h);
        brdf.eval_without_fresnel(wo, to_f32(wi)) as f64 * wi[2] * 4.0 * dot(wo64, h)
    })
}

#[test]
fn white_furnace_albedo_is_at_most_one_and_close_to_one_when_smooth() {
    for alpha in [MIN_ALPHA, 0.01, 0.1, 0.3, 0.6, 1.0] {
        let brdf = GgxBrdf::from_alpha(alpha, Vec3::ONE);
        for degrees in VIEW_DEGREES {
            let albedo = directional_albedo(&brdf, view(degrees));
            // At MIN_ALPHA, rounding the quadrature's directions to f32 moves `f` by up
            // to ~1e-3 relative (see MIN_ALPHA), and the quadrature by ~2e-4.
            let tolerance = if alpha == MIN_ALPHA { 1e-3 } else { 1e-4 };
            assert!(albedo <= 1.0 + tolerance, "α {alpha}, {degrees}°: {albedo}");
            assert!(albedo > 0.0, "α {alpha}, {degrees}°: {albedo}");
            if alpha <= 0.01 && degrees == 0.0 {
                assert!(albedo > 0.999, "α {alpha}: {albedo}");
            }
        }
    }
}

/// The estimator `f cos θi / pdf` over `sample`'s draws (a lost draw contributing 0)
/// converges to the quadrature of the albedo: the pdf is the density of the draws,
/// lost mass included.
#[test]
fn sampling_estimates_the_albedo_without_bias() {
    let mut rng = Rng::new(7);
    for alpha in [MIN_ALPHA, 0.01, 0.3, 1.0] {
        let brdf = GgxBrdf::from_alpha(alpha, Vec3::ONE);
        for degrees in [0.0, 60.0, 89.0] {
            let wo = view(degrees);
            let reference = directional_albedo(&brdf, wo);
            let mut estimate = Estimate::default();
            for _ in 0..200_000 {
                let s = brdf.sample(wo, [rng.uniform_f32(), rng.uniform_f32()]);
                let value = if s.pdf > 0.0 {
                    brdf.eval_without_fresnel(wo, s.dir) as f64 * s.dir.z as f64 / s.pdf as f64
                } else {
                    0.0
                };
                estimate.add(value);
            }
            // The quadrature of the f32 `eval` carries ~2e-4 of direction rounding at
            // MIN_ALPHA (see the white furnace test).
            let relative = if alpha == MIN_ALPHA { 1e-3 } else { 1e-4 };
            estimate.assert_mean_is(reference, 5.0, relative, &format!("α {alpha}, {degrees}°"));
        }
    }
}

// ---- pointwise checks against the textbook formulas ------------------------------

#[test]
fn terms_match_the_textbook_formulas_in_f64() {
    let mut rng = Rng::new(11);
    let mut worst = [0.0f64; 5];
    for _ in 0..200_000 {
        let alpha = rng.log_uniform(-2.0, 0.0) as f32;
        let f0 = rng.uniform_f32();
        let brdf = GgxBrdf::from_alpha(alpha, Vec3::splat(f0));
        let a = alpha as f64;
        let (mut wo, mut wi) = (rng.unit_vector_f32(), rng.unit_vector_f32());
        wo.z = wo.z.abs().max(1e-3);
        wi.z = wi.z.abs().max(1e-3);
        let (wo, wi) = (wo.normalize(), wi.normalize());
        let h = (wo + wi).normalize();
        let checks = [
            (brdf.d(h) as f64, d64(a, d3(h))),
            (brdf.g1(wo) as f64, g1_64(a, d3(wo))),
            (brdf.g2(wo, wi) as f64, g2_64(a, d3(wo), d3(wi))),
            (
                brdf.eval(wo, wi).x as f64,
                brdf64(a, f0 as f64, d3(wo), d3(wi)),
            ),
            (brdf.pdf(wo, wi) as f64, pdf64(a, d3(wo), d3(wi))),
        ];
        for (w, (value, reference)) in worst.iter_mut().zip(checks) {
            *w = w.max((value - reference).abs() / reference);
        }
    }
    assert!(
        worst.iter().all(|&w| w < 2e-5),
        "D, G1, G2, f, pdf: {worst:?}"
    );
}

#[test]
fn lambda_keeps_its_relative_precision_near_the_normal_and_is_finite_at_the_horizon() {
    for alpha in [MIN_ALPHA, 0.01, 0.5, 1.0] {
        let brdf = GgxBrdf::from_alpha(alpha, Vec3::ONE);
        for cos in [1.0 - f32::EPSILON / 2.0, 0.999_999, 0.99, 0.5, 1e-3, 1e-20] {
            let c = cos as f64;
            let sin2 = (1.0 - c) * (1.0 + c);
            let a = (alpha as f64).powi(2) * sin2 / (c * c);
            let reference = ((1.0 + a).sqrt() - 1.0) / 2.0;
            let reference = if a < 1e-6 {
                a / 4.0 - a * a / 16.0
            } else {
                reference
            };
            let lambda = brdf.lambda(cos) as f64;
            assert!(
                (lambda - reference).abs() <= 2e-6 * reference,
                "α {alpha}, cos {cos}: Λ {lambda} vs {reference}"
            );
            // G1 from Λ agrees with g1 of a direction at that angle.
            let w = Vec3::new(((1.0 - c * c).sqrt()) as f32, 0.0, cos);
            let g1 = 1.0 / (1.0 + lambda);
            assert!(
                (brdf.g1(w) as f64 - g1).abs() <= 1e-6 * g1,
                "α {alpha}, cos {cos}"
            );
        }
        assert_eq!(brdf.lambda(1.0), 0.0);
        assert_eq!(brdf.lambda(2.0), 0.0);
        for bad in [0.0, -0.5, f32::NAN, f32::NEG_INFINITY] {
            assert_eq!(brdf.lambda(bad), f32::MAX, "{bad}");
        }
        assert_eq!(brdf.lambda(1e-45), f32::MAX);
    }
}

#[test]
fn eval_is_exactly_reciprocal() {
    let mut rng = Rng::new(13);
    for _ in 0..100_000 {
        let brdf = GgxBrdf::new(rng.uniform_f32(), Vec3::new(0.9, 0.5, 0.02));
        let (wo, wi) = (rng.unit_vector_f32(), rng.unit_vector_f32());
        assert_eq!(brdf.eval(wo, wi), brdf.eval(wi, wo), "{wo} {wi}");
        assert_eq!(brdf.g2(wo, wi), brdf.g2(wi, wo));
    }
}

#[test]
fn fresnel_is_schlick_per_channel() {
    let brdf = GgxBrdf::new(0.5, Vec3::new(0.0, 0.5, 1.0));
    let (wo, wi) = (Vec3::new(0.8, 0.0, 0.6), Vec3::new(-0.6, 0.0, 0.8));
    let h = (wo + wi).normalize();
    let m = 1.0 - wo.dot(h);
    let f = brdf.eval_without_fresnel(wo, wi);
    let rgb = brdf.eval(wo, wi);
    let expected = Vec3::new(m.powi(5), 0.5 + 0.5 * m.powi(5), 1.0) * f;
    assert!(
        (rgb - expected).abs().max_element() <= 1e-6 * f,
        "{rgb} vs {expected}"
    );
    // Normal incidence, mirror direction: F = F0.
    let mirror = brdf.eval(Vec3::Z, Vec3::Z);
    let f_mirror = brdf.eval_without_fresnel(Vec3::Z, Vec3::Z);
    assert_eq!(mirror, Vec3::new(0.0, 0.5, 1.0) * f_mirror);
}

// ---- clamping, extreme and bad input -------------------------------------------------

#[test]
fn roughness_and_f0_are_clamped() {
    let f0 = Vec3::splat(0.04);
    assert_eq!(GgxBrdf::new(0.0, f0).alpha(), MIN_ALPHA);
    assert_eq!(GgxBrdf::new(0.005, f0).alpha(), MIN_ALPHA);
    assert_eq!(GgxBrdf::new(0.5, f0).alpha(), 0.25);
    assert_eq!(GgxBrdf::new(1.0, f0).alpha(), 1.0);
    assert_eq!(GgxBrdf::new(7.0, f0).alpha(), 1.0);
    assert_eq!(GgxBrdf::new(f32::INFINITY, f0).alpha(), 1.0);
    assert_eq!(GgxBrdf::new(-3.0, f0).alpha(), MIN_ALPHA);
    assert_eq!(GgxBrdf::new(f32::NAN, f0).alpha(), MIN_ALPHA);
    assert_eq!(GgxBrdf::new(f32::NEG_INFINITY, f0).alpha(), MIN_ALPHA);
    assert_eq!(GgxBrdf::from_alpha(f32::NAN, f0).alpha(), MIN_ALPHA);
    assert_eq!(GgxBrdf::from_alpha(1e-30, f0).alpha(), MIN_ALPHA);
    assert_eq!(GgxBrdf::from_alpha(0.3, f0).alpha(), 0.3);
    let clamped = GgxBrdf::new(0.5, Vec3::new(f32::NAN, -1.0, 2.0)).f0();
    assert_eq!(clamped, Vec3::new(0.0, 0.0, 1.0));
    let clamped = GgxBrdf::new(0.5, Vec3::new(f32::INFINITY, f32::NEG_INFINITY, 0.3)).f0();
    assert_eq!(clamped, Vec3::new(1.0, 0.0, 0.3));
}

/// At the smallest `α` the peak of `D` and the pdf stay finite, sampling and the pdf
/// agree exactly, and the pdf of each sampled direction matches the f64 density at
/// that direction to 1e-5.
#[test]
fn the_smoothest_brdf_stays_finite_and_consistent() {
    let brdf = GgxBrdf::new(0.0, Vec3::ONE);
    let peak = brdf.d(Vec3::Z);
    assert!(
        (peak as f64 - 1.0 / (PI * 1e-8)).abs() < 1e-6 * peak as f64,
        "{peak}"
    );
    let mut rng = Rng::new(17);
    for degrees in VIEW_DEGREES {
        let wo = view(degrees);
        let mut worst = 0.0f64;
        for _ in 0..100_000 {
            let s = brdf.sample(wo, [rng.uniform_f32(), rng.uniform_f32()]);
            if s.pdf == 0.0 {
                continue;
            }
            assert!(s.pdf.is_finite() && s.dir.is_finite());
            assert_eq!(brdf.pdf(wo, s.dir), s.pdf);
            let f = brdf.eval(wo, s.dir);
            assert!(f.is_finite() && f.min_element() > 0.0, "{f}");
            let reference = pdf64(MIN_ALPHA as f64, d3(wo), d3(s.dir));
            worst = worst.max((s.pdf as f64 - reference).abs() / reference);
        }
        assert!(worst < 1e-5, "{degrees}°: pdf vs f64 {worst}");
    }
}

#[test]
fn grazing_and_degenerate_directions_give_finite_values() {
    let graze = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let directions = [
        graze(1.0, 0.0, 1e-30),
        graze(-1.0, 0.0, 1e-30),
        graze(0.0, 1.0, 1e-7),
        graze(1.0, 0.0, f32::MIN_POSITIVE),
        graze(1.0, 0.0, 1e-45),
        graze(1.0, 0.0, 0.0),
        graze(0.6, 0.0, 0.8),
        graze(-0.6, 0.0, 0.8),
        Vec3::Z,
        graze(0.0, 0.0, 1e-30),
        graze(0.0, 0.0, 1e30),
        graze(3e38, 3e38, 3e38),
    ];
    let mut rng = Rng::new(19);
    for alpha in [MIN_ALPHA, 0.01, 0.5, 1.0] {
        let brdf = GgxBrdf::from_alpha(alpha, Vec3::splat(0.5));
        for &wo in &directions {
            for &wi in &directions {
                let f = brdf.eval(wo, wi);
                assert!(
                    f.is_finite() && f.min_element() >= 0.0,
                    "α {alpha}: {wo} {wi}: {f}"
                );
                let p = brdf.pdf(wo, wi);
                assert!(p.is_finite() && p >= 0.0, "α {alpha}: {wo} {wi}: {p}");
                let g2 = brdf.g2(wo, wi);
                assert!((0.0..=1.0).contains(&g2), "{g2}");
            }
            for _ in 0..1000 {
                let s = brdf.sample(wo, [rng.uniform_f32(), rng.uniform_f32()]);
                assert!(
                    s.dir.is_finite() && s.pdf.is_finite() && s.pdf >= 0.0,
                    "{s:?}"
                );
                if s.pdf > 0.0 {
                    assert!(s.dir.z > 0.0 && (s.dir.length() - 1.0).abs() < 1e-6);
                    assert_eq!(brdf.pdf(wo, s.dir), s.pdf);
                } else {
                    assert_eq!(s, Sample::NONE);
                }
            }
        }
        // A view at 1e-30 above the horizon still samples, with finite pdfs.
        let wo = Vec3::new(1.0, 0.0, 1e-30);
        let kept = (0..1000)
            .filter(|_| brdf.sample(wo, [rng.uniform_f32(), rng.uniform_f32()]).pdf > 0.0)
            .count();
        assert!(kept > 0, "α {alpha}");
        // ωi = ωo (h = ωo) and ωi = -ωo (one below the horizon).
        let wo = Vec3::new(0.6, 0.0, 0.8);
        assert!(brdf.eval(wo, wo).min_element() > 0.0);
        assert!(brdf.pdf(wo, wo) > 0.0);
        assert_eq!(brdf.eval(wo, -wo), Vec3::ZERO);
        assert_eq!(brdf.pdf(wo, -wo), 0.0);
    }
}

#[test]
fn bad_input_gives_zero_and_no_sample() {
    let brdf = GgxBrdf::new(0.4, Vec3::splat(0.04));
    let good = Vec3::new(0.3, -0.2, 0.9).normalize();
    let bad = [
        Vec3::ZERO,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(0.0, f32::NAN, 1.0),
        Vec3::new(0.0, 0.0, f32::NAN),
        Vec3::new(f32::INFINITY, 0.0, 1.0),
        Vec3::new(0.0, 0.0, f32::INFINITY),
        Vec3::new(0.0, f32::NEG_INFINITY, 1.0),
        Vec3::new(0.3, 0.2, -0.9),
        Vec3::new(0.0, 0.0, -1.0),
    ];
    for &b in &bad {
        assert_eq!(brdf.eval(b, good), Vec3::ZERO, "{b}");
        assert_eq!(brdf.eval(good, b), Vec3::ZERO, "{b}");
        assert_eq!(brdf.eval_without_fresnel(b, good), 0.0, "{b}");
        assert_eq!(brdf.pdf(b, good), 0.0, "{b}");
        assert_eq!(brdf.pdf(good, b), 0.0, "{b}");
        assert_eq!(brdf.g1(b), 0.0, "{b}");
        assert_eq!(brdf.g2(b, good), 0.0, "{b}");
        assert_eq!(brdf.d(b), 0.0, "{b}");
        for u in [[0.5, 0.5], [0.0, 0.0], [f32::NAN, f32::NAN]] {
            assert_eq!(brdf.sample(b, u), Sample::NONE, "{b}");
        }
    }
    // Random numbers outside [0, 1) are clamped, NaN counts as 0.
    let last = 1.0 - f32::EPSILON / 2.0;
    for (u, clamped) in [
        ([f32::NAN, 0.3], [0.0, 0.3]),
        ([-1.0, 0.3], [0.0, 0.3]),
        ([f32::NEG_INFINITY, 0.3], [0.0, 0.3]),
        ([0.3, 1.0], [0.3, last]),
        ([0.3, 7.0], [0.3, last]),
        ([0.3, f32::INFINITY], [0.3, last]),
    ] {
        assert_eq!(brdf.sample(good, u), brdf.sample(good, clamped), "{u:?}");
    }
    for u in [
        [0.0, 0.0],
        [last, last],
        [0.0, last],
        [last, 0.0],
        [0.5, 0.5],
    ] {
        let s = brdf.sample(good, u);
        assert!(s.dir.is_finite() && s.pdf.is_finite(), "{u:?}: {s:?}");
    }
    // Unnormalised input is normalised.
    let wi = Vec3::new(-0.2, 0.1, 0.95).normalize();
    let (f, f_scaled) = (brdf.eval(good, wi), brdf.eval(good * 1e20, wi * 1e-20));
    assert!(
        (f - f_scaled).abs().max_element() <= 1e-5 * f.max_element(),
        "{f} {f_scaled}"
    );
    let (p, p_scaled) = (brdf.pdf(good, wi), brdf.pdf(good * 3.0, wi * 0.5));
    assert!((p - p_scaled).abs() <= 1e-5 * p, "{p} {p_scaled}");
    assert_eq!(brdf.d(Vec3::new(0.0, 0.0, 5.0)), brdf.d(Vec3::Z));
}

/// MIS of visible-normal sampling and cosine-weighted sampling estimates the GGX albedo
/// (f64 quadrature) without bias under every heuristic of `crate::mis`: this holds only
/// if both pdfs are the true densities of their draws, lost GGX draws included.
#[test]
fn mis_of_vndf_and_cosine_sampling_estimates_the_albedo_without_bias() {
    use crate::brdf::Lambert;
    use crate::mis::*;
    let lambert = Lambert::default();
    let mut seed = 40;
    for (alpha, degrees) in [(0.3f32, 60.0), (1.0, 30.0), (0.05, 85.0)] {
        let brdf = GgxBrdf::from_alpha(alpha, Vec3::ONE);
        let wo = view(degrees);
        let reference = directional_albedo(&brdf, wo);
        // Rough guesses of the unoccluded contributions of the two techniques.
        let c = [0.8f32 * reference as f32, 0.2 * reference as f32];
        let contribution = |name: &str, f: f32, p: &[f32], j: usize| -> f32 {
            let by_weight = |w: f32| if w > 0.0 { w * f / p[j] } else { 0.0 };
            match name {
                "balance" => by_weight(balance_heuristic(p, j)),
                "power" => by_weight(power_heuristic(p, j)),
                "weighted balance" => by_weight(weighted_balance_heuristic(p, &c, j)),
                "clamped optimal" => {
                    clamped_optimal_mis_contribution(f, p, &c, DEFAULT_VISIBILITY, j)
                }
                _ => optimal_mis_contribution(f, p, &c, DEFAULT_VISIBILITY, j),
            }
        };
        for name in [
            "balance",
            "power",
            "weighted balance",
            "clamped optimal",
            "optimal",
        ] {
            seed += 1;
            let mut rng = Rng::new(seed);
            let mut estimate = Estimate::default();
            for _ in 0..200_000 {
                let draws = [
                    brdf.sample(wo, [rng.uniform_f32(), rng.uniform_f32()]),
                    lambert.sample([rng.uniform_f32(), rng.uniform_f32()]),
                ];
                let mut total = 0.0;
                for (j, s) in draws.into_iter().enumerate() {
                    if s.pdf == 0.0 {
                        continue; // a lost draw contributes 0
                    }
                    let f = brdf.eval_without_fresnel(wo, s.dir) * s.dir.z;
                    let p = [brdf.pdf(wo, s.dir), lambert.pdf(s.dir)];
                    total += contribution(name, f, &p, j) as f64;
                }
                estimate.add(total);
            }
            estimate.assert_mean_is(
                reference,
                5.0,
                1e-4,
                &format!("{name}, α {alpha}, {degrees}°"),
            );
        }
    }
}

/// The visible-normal map of Dupuy and Benyoub 2023 in f64, written here from the paper:
/// `v = normalize(α ωo,x, α ωo,y, ωo,z)`, `c` in the cap `c_z >= -v_z` at
/// `c_z = 1 - u1 (1 + v_z)` and azimuth `2π u0`, `h = normalize(α n_x, α n_y, n_z)` with
/// `n = v + c`.
fn visible_normal64(alpha: f64, wo: D3, u: [f64; 2]) -> D3 {
    let stretched = [alpha * wo[0], alpha * wo[1], wo[2]];
    let v = normalize(stretched);
    let cz = 1.0 - u[1] * (1.0 + v[2]);
    let sin_theta = (1.0 - cz * cz).max(0.0).sqrt();
    let phi = 2.0 * PI * u[0];
    let n = [
        v[0] + sin_theta * phi.cos(),
        v[1] + sin_theta * phi.sin(),
        v[2] + cz,
    ];
    normalize([alpha * n[0], alpha * n[1], n[2].max(0.0)])
}

/// The error of the f32 visible-normal map against the same map in f64, as the angle
/// between the two normals, over a 256 × 256 grid of `u` per roughness and view (the
/// grid's last row and column at `1 - 2⁻⁹`). Measured: 2e-8 to 7e-6 rad at the 99.9th
/// percentile, 5e-8 to 3.5e-5 rad at worst, over α from 0.01 to 1 and views to 89°. The
/// worst cases lie next to the cap's rim opposite the view, where `n = v + c` is short
/// and the map itself is ill-conditioned (`u` moved by one ulp moves `h` about as far).
/// Heitz 2018's construction, measured the same way against its own f64 map, which this
/// replaced: 4e-7 to 6e-6 rad at the 99.9th percentile and 1e-6 to 1.5e-5 rad at worst
/// (its maxima are lower at grazing views, its percentiles higher at normal incidence).
#[test]
fn visible_normals_match_the_f64_map() {
    let mut worst = 0.0f64;
    for &alpha in &ALPHAS {
        let brdf = GgxBrdf::from_alpha(alpha, Vec3::ONE);
        let alpha64 = brdf.alpha() as f64;
        for &degrees in &VIEW_DEGREES {
            let wo = view(degrees);
            let mut errors = Vec::new();
            for i in 0..256 {
                for j in 0..256 {
                    let u = [(i as f32 + 0.5) / 256.0, (j as f32 + 0.5) / 256.0];
                    let h = d3(brdf.sample_visible_normal(wo, u));
                    let reference = visible_normal64(alpha64, d3(wo), [u[0] as f64, u[1] as f64]);
                    let cross = cross(h, reference);
                    errors.push(dot(cross, cross).sqrt().atan2(dot(h, reference)));
                }
            }
            errors.sort_by(f64::total_cmp);
            let (p999, max) = (errors[errors.len() * 999 / 1000], errors[errors.len() - 1]);
            worst = worst.max(max);
            println!("α {alpha}, view {degrees}°: 99.9th percentile {p999:.2e} rad, max {max:.2e}");
            assert!(p999 < 1e-5, "α {alpha}, view {degrees}°: {p999:e}");
            assert!(max < 5e-5, "α {alpha}, view {degrees}°: {max:e}");
        }
    }
    println!("worst {worst:.2e} rad");
}

/// `pdf` runs unit directions above the horizon inline and everything else through
/// `pdf_careful`: over random directions (unit, and scaled by factors at and beyond
/// the unit tolerance, the grazing and the opposite ones among them) both give the
/// same bits, and the careful path is what normalises (a scaled direction's pdf is
/// that of its normalised form).
#[test]
fn the_pdf_common_path_gives_the_careful_paths_bits() {
    let mut rng = Rng::new(77);
    let (mut common, mut careful) = (0, 0);
    for k in 0..20_000 {
        let brdf = GgxBrdf::new(rng.range(0.0, 1.0), Vec3::splat(0.04));
        let mut wo = rng.unit_vector_f32();
        let mut wi = rng.unit_vector_f32();
        if k % 7 == 0 {
            wi = -wo + Vec3::new(0.0, 0.0, 1e-6); // nearly opposite: |wo + wi| tiny
        }
        if k % 11 == 0 {
            wo.z = 1e-7 * wo.z.signum(); // grazing
        }
        let scale = [1.0, 1.0 + 4e-7, 1.0 + 2e-6, 0.5, 3.0][k % 5];
        let (wo, wi) = (wo * scale, wi * [1.0, 1.0 - 3e-7, 1.0][k % 3]);
        let expected = GgxBrdf::pdf_careful(&brdf, wo, wi);
        assert_eq!(brdf.pdf(wo, wi).to_bits(), expected.to_bits(), "{wo} {wi}");
        if is_unit(wo) && is_unit(wi) && wo.z > 0.0 && wi.z > 0.0 {
            common += 1;
        } else if wo.z > 0.0 && wi.z > 0.0 {
            careful += 1;
        }
        if k % 5 >= 3 && wo.z > 0.0 && wi.z > 0.0 {
            // Scaled by 0.5 or 3: the unit path on the raw vectors would be off by
            // factors, the normalised directions differ from glam's by an ulp or so
            // (to which a narrow lobe's D is sensitive).
            let normalised = brdf.pdf(wo.normalize(), wi.normalize());
            assert!(
                (expected - normalised).abs() <= 1e-3 * normalised,
                "{wo} {wi}: {expected} vs {normalised}"
            );
        }
    }
    assert!(
        common > 1000 && careful > 2000,
        "{common} common, {careful} careful"
    );
}
