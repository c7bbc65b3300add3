//! The error table of the SG closed forms and approximations (`docs/sg-error.md`):
//! every quantity of `sphera::sg` measured against f64 numerical integration over the
//! sphere, written independently here (a product grid in the frame of a lobe, refined
//! near its axis), over a grid of sharpness (per decade 1e-4..1e4), angle between lobes
//! and GGX or Beckmann roughness (0.05..1); the Beckmann BRDF is written here in f64.
//!
//! `measure(false)` is the full table (`cargo run --release -p sphera-tools --bin
//! sg_error_table`); `measure(true)` a reduced grid that `tools/tests/sg_error.rs` runs.
use sphera::Vec3;
use sphera::brdf::ggx::GgxBrdf;
use sphera::sg::asg::Asg;
use sphera::sg::shading::{
    beckmann_specular_shading, beckmann_specular_shading_sg, diffuse_shading_constant_cosine,
    diffuse_shading_product, diffuse_shading_sharp_lobe, specular_shading, specular_shading_sg,
};
use sphera::sg::{
    Sg, beckmann_lobe_normalized, diffuse_lobe_normalized, sg_integral, specular_lobe_normalized,
    vmf_pdf,
};
use std::f64::consts::PI;

use sphera_test_support::{D3, dot, frame_f64 as frame, normalize, to_f32};

/// `∫_{S²} f(ω) dω` by a product grid in `(t = 1 − ω·c, φ)` around `c`: in `t`, the
/// panel `[0, t0]` and `n` geometrically growing panels from `t0` to 2
/// (`t0 = min(2, 50/λ)/1000` for a lobe of sharpness `λ` around `c`), 3-point
/// Gauss–Legendre in each; in `φ`, the midpoint rule with `2n` points.
pub fn integrate(c: D3, lambda: f64, n: usize, f: &dyn Fn(D3) -> f64) -> f64 {
    let c = normalize(c);
    let (t1, t2) = frame(c);
    let top = (50.0 / lambda.max(1e-9)).min(2.0);
    let t0 = top * 1e-3;
    let nphi = 2 * n;
    let mut total = 0.0;
    let mut ring = |t: f64, dt: f64| {
        let s = (t * (2.0 - t)).max(0.0).sqrt();
        let mut sum = 0.0;
        for j in 0..nphi {
            let phi = (j as f64 + 0.5) / nphi as f64 * 2.0 * PI;
            let (sp, cp) = phi.sin_cos();
            let w = [
                (1.0 - t) * c[0] + s * (cp * t1[0] + sp * t2[0]),
                (1.0 - t) * c[1] + s * (cp * t1[1] + sp * t2[1]),
                (1.0 - t) * c[2] + s * (cp * t1[2] + sp * t2[2]),
            ];
            sum += f(w);
        }
        total += sum * dt * 2.0 * PI / nphi as f64;
    };
    let nodes = [-(0.6f64).sqrt(), 0.0, (0.6f64).sqrt()];
    let weights = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
    let mut panel = |a: f64, b: f64| {
        for k in 0..3 {
            ring(
                0.5 * (a + b) + 0.5 * (b - a) * nodes[k],
                0.5 * (b - a) * weights[k],
            );
        }
    };
    panel(0.0, t0);
    let ratio = (2.0 / t0).powf(1.0 / n as f64);
    let mut a = t0;
    for i in 0..n {
        let b = if i + 1 == n { 2.0 } else { a * ratio };
        panel(a, b);
        a = b;
    }
    total
}

/// `e^{λ(ω·ξ − 1)}` in f64 by `|ω − ξ|²/2`.
fn sg64(axis: D3, l: f64, w: D3) -> f64 {
    let e = [w[0] - axis[0], w[1] - axis[1], w[2] - axis[2]];
    (-0.5 * l * (e[0] * e[0] + e[1] * e[1] + e[2] * e[2])).exp()
}

/// Beckmann's Smith `Λ` in f64 (Walter et al. 2007): `a = cos θ/(α sin θ)`,
/// `Λ = (e^{−a²}/(a√π) − erfc(a))/2`.
fn beckmann_lambda64(alpha: f64, c: f64) -> f64 {
    let a = c / (alpha * (1.0 - c * c).max(0.0).sqrt());
    0.5 * ((-a * a).exp() / (a * PI.sqrt()) - libm::erfc(a))
}

/// Beckmann's `ρ_s cos θ_i = F D G2/(4 cos θ_o)` in f64 for the normal `z`, written here
/// independently of `sphera`: `D = e^{−tan²θ_h/α²}/(πα² cos⁴θ_h)`, the height-correlated
/// `G2 = 1/(1 + Λ(ω_o) + Λ(ω_i))`, Schlick's `F` at `ω_o·h`.
fn beckmann_cos64(wo: D3, wi: D3, alpha: f64, f0: f64) -> f64 {
    if wo[2] <= 0.0 || wi[2] <= 0.0 {
        return 0.0;
    }
    let h = normalize([wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]]);
    let c2 = h[2] * h[2];
    let d = (-(1.0 - c2) / c2 / (alpha * alpha)).exp() / (PI * alpha * alpha * c2 * c2);
    let g2 = 1.0 / (1.0 + beckmann_lambda64(alpha, wo[2]) + beckmann_lambda64(alpha, wi[2]));
    let f = f0 + (1.0 - f0) * (1.0 - dot(wo, h)).max(0.0).powi(5);
    f * d * g2 / (4.0 * wo[2])
}

/// One measured relative error.
pub struct Sample {
    pub quantity: &'static str,
    /// The decade of the sharpness (log10), or of the roughness for lobe fits.
    pub decade: i32,
    pub case: String,
    pub error: f64,
}

/// Whether a quantity is an exact closed form (asserted within 1e-4) or an approximation.
pub fn is_exact(quantity: &str) -> bool {
    matches!(quantity, "A(λ)" | "inner product" | "vMF pdf normalisation")
}

fn rel(value: f64, reference: f64) -> f64 {
    if reference == 0.0 {
        value.abs()
    } else {
        ((value - reference) / reference).abs()
    }
}

/// Measures every quantity; `reduced` takes a coarser grid (for the test).
pub fn measure(reduced: bool) -> Vec<Sample> {
    let n = if reduced { 120 } else { 300 };
    let decades: Vec<i32> = (-4..=4).collect();
    let per_decade: &[f64] = if reduced { &[1.0] } else { &[1.0, 3.0] };
    let lambdas: Vec<(i32, f64)> = decades
        .iter()
        .flat_map(|&d| per_decade.iter().map(move |&m| (d, m * 10f64.powi(d))))
        .collect();
    let angles: &[f64] = if reduced {
        &[0.0, 90.0, 180.0]
    } else {
        &[0.0, 10.0, 45.0, 90.0, 135.0, 180.0]
    };
    let roughnesses: &[f64] = if reduced {
        &[0.1, 0.5, 1.0]
    } else {
        &[0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0]
    };
    let mut out = Vec::new();
    let z = [0.0, 0.0, 1.0];
    for &(decade, l) in &lambdas {
        let lf = l as f32;
        let l32 = lf as f64;
        // A(λ).
        let reference = integrate(z, l32, n, &|w| sg64(z, l32, w));
        out.push(Sample {
            quantity: "A(λ)",
            decade,
            case: format!("λ={l:.0e}"),
            error: rel(sg_integral(lf) as f64, reference),
        });
        // vMF normalisation.
        let sg = Sg::new(Vec3::Z, lf, 1.0);
        let total = integrate(z, l32, n, &|w| vmf_pdf(&sg, to_f32(w)) as f64);
        out.push(Sample {
            quantity: "vMF pdf normalisation",
            decade,
            case: format!("λ={l:.0e}"),
            error: rel(total, 1.0),
        });
        for &angle in angles {
            let a = angle.to_radians();
            let x2 = [a.sin(), 0.0, a.cos()];
            let (s1, s2) = (Sg::new(Vec3::Z, lf, 1.0), Sg::new(to_f32(x2), lf, 2.0));
            let x2 = [s2.axis.x as f64, s2.axis.y as f64, s2.axis.z as f64];
            let p = s1.product(&s2);
            let centre = [p.axis.x as f64, p.axis.y as f64, p.axis.z as f64];
            let reference = integrate(centre, p.sharpness as f64, n, &|w| {
                2.0 * sg64(z, l32, w) * sg64(x2, l32, w)
            });
            if reference > 1e-35 {
                out.push(Sample {
                    quantity: "inner product",
                    decade,
                    case: format!("λ={l:.0e} {angle}°"),
                    error: rel(s1.inner_product(&s2) as f64, reference),
                });
            }
            // Diffuse shading: an incoming SG at `angle` from the normal z.
            if angle <= 90.0 {
                let xi = [a.sin(), 0.0, a.cos()];
                let l_in = Sg::new(to_f32(xi), lf, 1.0);
                let xi = [l_in.axis.x as f64, l_in.axis.y as f64, l_in.axis.z as f64];
                let exact = integrate(xi, l32, n, &|w| sg64(xi, l32, w) * w[2].max(0.0) / PI);
                if exact > 1e-30 {
                    let case = format!("λ={l:.0e} {angle}°");
                    out.push(Sample {
                        quantity: "diffuse shading, SG product",
                        decade,
                        case: case.clone(),
                        error: rel(
                            diffuse_shading_product(&l_in, Vec3::Z, 1.0, 1.0) as f64,
                            exact,
                        ),
                    });
                    out.push(Sample {
                        quantity: "diffuse shading, constant cosine",
                        decade,
                        case: case.clone(),
                        error: rel(
                            diffuse_shading_constant_cosine(&l_in, Vec3::Z, 1.0, 1.0) as f64,
                            exact,
                        ),
                    });
                    out.push(Sample {
                        quantity: "diffuse shading, 2/λ shortcut",
                        decade,
                        case,
                        error: rel(
                            diffuse_shading_sharp_lobe(&l_in, Vec3::Z, 1.0, 1.0) as f64,
                            exact,
                        ),
                    });
                }
            }
        }
        // ASG integral: isotropic η and anisotropy 10 (exact: the disk integral).
        for ratio in [1.0f64, 10.0] {
            let (ex, ey) = (l32, l32 * ratio);
            let asg = Asg::new(Vec3::X, Vec3::Z, ex as f32, ey as f32, 1.0);
            let exact = integrate(z, ex, n, &|w| {
                w[2].max(0.0) * (-ex * w[0] * w[0] - ey * w[1] * w[1]).exp()
            });
            out.push(Sample {
                quantity: "ASG integral π/√(η_x η_y)",
                decade,
                case: format!("η={l:.0e}×{ratio}"),
                error: rel(asg.integral() as f64, exact),
            });
        }
        // ASG × SG: the GGX ASG at 45° view, roughness 0.3, an SG of sharpness λ at the
        // reflection direction and 0.1 rad off it.
        let view = [0.5f64.sqrt(), 0.0, 0.5f64.sqrt()];
        let asg = Asg::from_ggx(Vec3::Z, to_f32(view), 0.09);
        for offset in [0.0f64, 0.1] {
            let xi = normalize([-(0.5f64.sqrt()) + offset, 0.0, 0.5f64.sqrt()]);
            let sg = Sg::new(to_f32(xi), lf, 1.0);
            let xi = [sg.axis.x as f64, sg.axis.y as f64, sg.axis.z as f64];
            let (ax, ay, az) = (asg.x, asg.y, asg.z);
            let d = |v: Vec3| [v.x as f64, v.y as f64, v.z as f64];
            let (ax, ay, az) = (d(ax), d(ay), d(az));
            let (ex, ey) = (asg.eta_x as f64, asg.eta_y as f64);
            let g = |w: D3| {
                dot(w, az).max(0.0)
                    * (-ex * dot(w, ax).powi(2) - ey * dot(w, ay).powi(2)).exp()
                    * sg64(xi, l32, w)
            };
            let exact =
                integrate(az, ex.min(ey).max(l32), n, &g).max(integrate(xi, l32.max(ex), n, &g));
            if exact > 1e-30 {
                out.push(Sample {
                    quantity: "ASG × SG convolution",
                    decade,
                    case: format!("λ={l:.0e} off {offset}"),
                    error: rel(asg.convolve_sg(&sg) as f64, exact),
                });
            }
        }
        // Specular shading: view 45°, incoming SG of sharpness λ at the reflection
        // direction and 0.2 rad off it, against ∫ L_in ρ_s cos.
        for &r in roughnesses {
            let ggx = GgxBrdf::new(r as f32, Vec3::splat(0.04));
            for offset in [0.0f64, 0.2] {
                let xi = normalize([-(0.5f64.sqrt()) + offset, 0.0, 0.5f64.sqrt()]);
                let l_in = Sg::new(to_f32(xi), lf, 1.0);
                let xi = [l_in.axis.x as f64, l_in.axis.y as f64, l_in.axis.z as f64];
                let wo = to_f32(view);
                let f = |w: D3| {
                    if w[2] <= 0.0 {
                        return 0.0;
                    }
                    sg64(xi, l32, w) * ggx.eval(wo, to_f32(w)).x as f64 * w[2]
                };
                let alpha = r * r;
                let lobe_l = 2.0 / (alpha * alpha);
                let exact = integrate(xi, l32, n, &f).max(integrate(
                    [-(0.5f64.sqrt()), 0.0, 0.5f64.sqrt()],
                    lobe_l,
                    n,
                    &f,
                ));
                let beckmann = |w: D3| {
                    if w[2] <= 0.0 {
                        return 0.0;
                    }
                    sg64(xi, l32, w) * beckmann_cos64(view, w, alpha, 0.04)
                };
                let exact_beckmann = integrate(xi, l32, n, &beckmann).max(integrate(
                    [-(0.5f64.sqrt()), 0.0, 0.5f64.sqrt()],
                    lobe_l,
                    n,
                    &beckmann,
                ));
                if exact_beckmann > 1e-30 {
                    let case = format!("λ={l:.0e} r={r} off {offset}");
                    out.push(Sample {
                        quantity: "Beckmann specular shading, ASG",
                        decade,
                        case: case.clone(),
                        error: rel(
                            beckmann_specular_shading(&l_in, Vec3::Z, wo, r as f32, 0.04, 1.0)
                                as f64,
                            exact_beckmann,
                        ),
                    });
                    out.push(Sample {
                        quantity: "Beckmann specular shading, SG",
                        decade,
                        case,
                        error: rel(
                            beckmann_specular_shading_sg(&l_in, Vec3::Z, wo, r as f32, 0.04, 1.0)
                                as f64,
                            exact_beckmann,
                        ),
                    });
                }
                if exact > 1e-30 {
                    let case = format!("λ={l:.0e} r={r} off {offset}");
                    out.push(Sample {
                        quantity: "specular shading, ASG",
                        decade,
                        case: case.clone(),
                        error: rel(
                            specular_shading(&l_in, Vec3::Z, wo, r as f32, 0.04, 1.0) as f64,
                            exact,
                        ),
                    });
                    out.push(Sample {
                        quantity: "specular shading, SG",
                        decade,
                        case,
                        error: rel(
                            specular_shading_sg(&l_in, Vec3::Z, wo, r as f32, 0.04, 1.0) as f64,
                            exact,
                        ),
                    });
                }
            }
        }
    }
    // Lobe fits (per roughness "decade" = index): normalised shape error
    // ∫ |f/∫f − g/∫g| (an L1 distance of densities, in [0, 2]).
    let d = diffuse_lobe_normalized(Vec3::Z);
    let shape = integrate(z, 2.0, n, &|w| {
        (w[2].max(0.0) / PI - d.eval(to_f32(w)) as f64).abs()
    });
    out.push(Sample {
        quantity: "diffuse lobe fit (L1 vs cos/π)",
        decade: 0,
        case: "λ_d".into(),
        error: shape,
    });
    for &r in roughnesses {
        for view_deg in [0.0f64, 45.0, 75.0] {
            let t = view_deg.to_radians();
            let wo = [t.sin(), 0.0, t.cos()];
            let ggx = GgxBrdf::new(r as f32, Vec3::ONE);
            let alpha = (r * r).max(1e-3);
            let s = specular_lobe_normalized(Vec3::Z, to_f32(wo), alpha as f32);
            let refl = [-t.sin(), 0.0, t.cos()];
            let f = |w: D3| {
                if w[2] > 0.0 {
                    ggx.eval(to_f32(wo), to_f32(w)).x as f64 * w[2]
                } else {
                    0.0
                }
            };
            let norm_f = integrate(refl, s.sharpness as f64, n, &f);
            let shape = integrate(refl, s.sharpness as f64, n, &|w| {
                (f(w) / norm_f - s.eval(to_f32(w)) as f64).abs()
            });
            out.push(Sample {
                quantity: "specular SG lobe shape (L1 vs GGX·cos)",
                decade: (r.log10().floor()) as i32,
                case: format!("r={r} view {view_deg}°"),
                error: shape,
            });
            // Beckmann: the same SG (λ_h = 2/α²) against the f64 Beckmann BRDF · cos.
            let b = beckmann_lobe_normalized(Vec3::Z, to_f32(wo), alpha as f32);
            let alpha32 = (alpha as f32) as f64;
            let f = |w: D3| beckmann_cos64(wo, w, alpha32, 1.0);
            let norm_f = integrate(refl, b.sharpness as f64, n, &f);
            let shape = integrate(refl, b.sharpness as f64, n, &|w| {
                (f(w) / norm_f - b.eval(to_f32(w)) as f64).abs()
            });
            out.push(Sample {
                quantity: "Beckmann SG lobe shape (L1 vs Beckmann·cos)",
                decade: (r.log10().floor()) as i32,
                case: format!("r={r} view {view_deg}°"),
                error: shape,
            });
        }
    }
    out
}

/// The Markdown report of `measure`.
pub fn render(samples: &[Sample]) -> String {
    let mut quantities: Vec<&str> = Vec::new();
    for s in samples {
        if !quantities.contains(&s.quantity) {
            quantities.push(s.quantity);
        }
    }
    let mut md = String::from("# SG closed forms and approximations: measured error\n\n");
    md +=
        "Generated by `cargo run --release -p sphera-tools --bin sg_error_table` (do not edit).\n";
    md += "Each value of `sphera::sg` (f32) against f64 numerical integration over the sphere\n";
    md += "(a product grid in (1 − cos θ, φ) around the lobe, refined near its axis; see\n";
    md += "`tools/src/measurements/sg_error.rs`). Relative errors `|value − reference| / reference`, except\n";
    md += "the lobe-shape rows, which are L1 distances between normalised lobes (0..2).\n";
    md += "Decade = ⌊log10 λ⌋ of the sharpness (of the SG, the incoming lobe, or η for the ASG\n";
    md += "integral); for the specular lobe shape it is ⌊log10 roughness⌋.\n\n";
    md += "## Findings\n\n";
    md += "- Exact closed forms (A(λ), the inner product through the product SG, the vMF\n";
    md +=
        "  density's normalisation) agree with the quadrature to ~1e-7..4e-6 over λ = 1e-4..3e4\n";
    md += "  (f32 rounding); the opposite-axis products at large λ underflow to 0 in both.\n";
    md += "- ASG integral π/√(η_x η_y): ~1e-4 for η ≥ 10 (f32), wrong for η ≲ 1 (the unit-disk\n";
    md += "  tail; clamped to a π, 58 % high at η = 1, 86 % at η_x = 0.3, η_y = 3).\n";
    md += "- ASG × SG (boxed formula of Section 4.2): within 0.3 % for the GGX ASG at 45°,\n";
    md += "  roughness 0.3, at every λ measured.\n";
    md += "- Diffuse, constant-cosine form: error ~1/λ for lobes well above the horizon (1 % at\n";
    md += "  λ = 100), 300 % as λ → 0 (it gives 4 c R_d instead of c R_d), and 100 % at the horizon\n";
    md += "  (90°), where half the lobe is above it but max(ξ·n, 0) = 0. The 2/λ shortcut matches it\n";
    md += "  for λ ≳ 10 and diverges as 1/λ below 1. The SG-product form is good for wide lobes\n";
    md +=
        "  (≤ 7 % for λ ≤ 3) and leaks for sharp ones: 15 % at 0° and far more at grazing axes.\n";
    md += "- Specular (ASG or SG fit) against ∫ SG · GGX · cos: the λ_h = 2/α² fit keeps energy,\n";
    md +=
        "  but the Gaussian misses GGX's long tail: an incoming lobe 0.2 rad off the reflection\n";
    md += "  direction on a smooth surface (r = 0.05, 0.1) gets ~0 instead of the tail's value\n";
    md += "  (100 % error), and at roughness 1 the fit is 30–47 % off for wide lobes. The ASG is\n";
    md += "  better than the SG fit at r = 1 (34 % vs 42 %), about equal elsewhere.\n";
    md += "- Lobe shapes (L1 distance of normalised lobes, 0..2): diffuse fit 0.258; the\n";
    md += "  specular SG fit 0.5–1.15 (GGX's peak is narrower and its tail heavier than the\n";
    md +=
        "  Gaussian's; worst at grazing views, where the isotropic warp is also wrong in shape).\n";
    md += "- Beckmann (the same λ_h = 2/α² fit, against an f64 Beckmann BRDF with its own Smith\n";
    md += "  term): along the normal the SG has Beckmann's shape (L1 1.1e-4 at r = 0.1, 0.068 at\n";
    md +=
        "  r = 0.5, against GGX's 0.41 and 0.23); at 45° and 75° the isotropic warp's own error\n";
    md += "  dominates (0.22 and 0.80 at r = 0.1). Shading on the reflection direction is within\n";
    md += "  7.2 % for r ≤ 0.5 at λ ≤ 1e2 (1.4e-4 for the ASG at r = 0.1); at r = 1 (Beckmann\n";
    md +=
        "  peaks off the normal there) the ASG is 49 % off for wide lobes, the SG 10 %. Beckmann\n";
    md += "  has no tail, so 0.2 rad off the reflection both the reference and the fits are\n";
    md +=
        "  tiny on smooth surfaces and the relative error reaches 100 % of a negligible value.\n\n";
    md += "| quantity | decade | cases | mean error | max error | worst case |\n|---|---|---|---|---|---|\n";
    for q in &quantities {
        let mut decades: Vec<i32> = samples
            .iter()
            .filter(|s| s.quantity == *q)
            .map(|s| s.decade)
            .collect();
        decades.sort();
        decades.dedup();
        for d in decades {
            let rows: Vec<&Sample> = samples
                .iter()
                .filter(|s| s.quantity == *q && s.decade == d)
                .collect();
            let mean = rows.iter().map(|s| s.error).sum::<f64>() / rows.len() as f64;
            let worst = rows
                .iter()
                .max_by(|a, b| a.error.partial_cmp(&b.error).unwrap())
                .unwrap();
            md += &format!(
                "| {q} | {d} | {} | {mean:.2e} | {:.2e} | {} |\n",
                rows.len(),
                worst.error,
                worst.case
            );
        }
    }
    md += "\n## Where the approximations break (cases with error above 10 %)\n\n";
    for q in &quantities {
        let bad: Vec<&Sample> = samples
            .iter()
            .filter(|s| s.quantity == *q && s.error > 0.1)
            .collect();
        if !bad.is_empty() && !q.contains("shape") && !q.contains("diffuse lobe") {
            let list: Vec<String> = bad
                .iter()
                .take(12)
                .map(|s| format!("{} ({:.0}%)", s.case, 100.0 * s.error))
                .collect();
            md += &format!(
                "- **{q}**: {} of {} cases: {}{}\n",
                bad.len(),
                samples.iter().filter(|s| s.quantity == *q).count(),
                list.join(", "),
                if bad.len() > 12 { ", …" } else { "" }
            );
        }
    }
    md
}
