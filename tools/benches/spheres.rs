//! Sphere lights with SPTDs (Dupuy et al. 2017): variance of joint SPTD–light sampling
//! against uniform cap sampling (both combined with GGX visible-normal sampling by the
//! balance heuristic, Section 6.1), variance of joint pivot-phase–light sampling against
//! Henyey–Greenstein sampling + uniform cap sampling by MIS (Section 6.2), and ns per
//! operation of every sphere-light technique, as ratios measured in the same run
//! (`cargo bench -p sphera-tools --bench spheres`, about 20 s).
use sphera::brdf::GgxBrdf;
use sphera::sphere::light::{SphereLightSampler, SphereLightShading};
use sphera::sphere::phase::{
    henyey_greenstein, pivot_from_henyey_greenstein, pivot_phase, pivot_phase_in_cap,
    sample_henyey_greenstein,
};
use sphera::sphere::{Cap, pivot_cap};
use sphera::{Sample, Vec3};
use sphera_test_support::Rng;

/// A light configuration: view, sphere center and radius.
struct Config {
    wo: Vec3,
    center: Vec3,
    radius: f32,
}

/// Random views (cos θo in [0.1, 1]) and spheres above or across the horizon
/// (sin of the half-angle log-uniform in [0.01, 0.5]); `highlight` puts the light within
/// 15° of the mirror direction.
fn configs(rng: &mut Rng, count: usize, highlight: bool) -> Vec<Config> {
    (0..count)
        .map(|_| {
            let cos_o = 0.1 + 0.9 * rng.uniform_f32();
            let phi = 2.0 * std::f32::consts::PI * rng.uniform_f32();
            let sin_o = (1.0 - cos_o * cos_o).sqrt();
            let wo = Vec3::new(sin_o * phi.cos(), sin_o * phi.sin(), cos_o);
            let dir = if highlight {
                let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
                let jitter = Vec3::new(
                    rng.uniform_f32() - 0.5,
                    rng.uniform_f32() - 0.5,
                    rng.uniform_f32() - 0.5,
                );
                (mirror + jitter * 0.5).normalize()
            } else {
                let z = rng.uniform_f32() * 1.1 - 0.1;
                let a = 2.0 * std::f32::consts::PI * rng.uniform_f32();
                let s = (1.0 - z * z).max(0.0).sqrt();
                Vec3::new(s * a.cos(), s * a.sin(), z)
            };
            let sin = 10f32.powf(-2.0 + 1.7 * rng.uniform_f32());
            Config {
                wo,
                center: dir * 4.0,
                radius: 4.0 * sin,
            }
        })
        .collect()
}

/// Relative variance of a 16-sample estimate, or None when the mean is 0.
fn relative_variance(values: impl Iterator<Item = f64>) -> Option<f64> {
    let v: Vec<f64> = values.collect();
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    if mean.is_nan() || mean <= 0.0 {
        return None;
    }
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    Some(var / (mean * mean) / 16.0)
}

fn mean_and_median(mut v: Vec<f64>) -> (f64, f64) {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    (v.iter().sum::<f64>() / v.len() as f64, v[v.len() / 2])
}

/// One sample of each technique, balance heuristic, of `∫_C f cos`.
fn estimate(
    brdf: &GgxBrdf,
    wo: Vec3,
    cap: &Cap,
    light: (Sample, &dyn Fn(Vec3) -> f32),
    u: [f32; 2],
) -> f64 {
    let f = |d: Vec3| brdf.eval_without_fresnel(wo, d) as f64 * d.z.max(0.0) as f64;
    let (s, light_pdf) = light;
    let mut sum = 0.0;
    if s.pdf > 0.0 {
        sum += f(s.dir) / (s.pdf as f64 + brdf.pdf(wo, s.dir) as f64);
    }
    let b = brdf.sample(wo, u);
    if b.pdf > 0.0 && cap.contains(b.dir) {
        sum += f(b.dir) / (b.pdf as f64 + light_pdf(b.dir) as f64);
    }
    sum
}

fn variance_table(rng: &mut Rng, highlight: bool) {
    let samples = 2000;
    println!(
        "\n### Relative variance of a 16-sample estimate of ∫_C f cos θ dω, {}\n",
        if highlight {
            "lights within 15° of the mirror direction"
        } else {
            "lights anywhere above or across the horizon"
        }
    );
    println!("200 configurations per roughness; mean (median).\n");
    println!("| technique | r = 0.1 | r = 0.3 | r = 0.6 | r = 1 |");
    println!("|---|---:|---:|---:|---:|");
    let names = [
        "uniform cap",
        "SPTD in the cap",
        "GGX visible normals",
        "uniform cap + GGX (balance)",
        "SPTD + GGX (balance), the joint sampling",
    ];
    let mut columns = Vec::new();
    let mut ratios = Vec::new();
    for roughness in [0.1f32, 0.3, 0.6, 1.0] {
        let brdf = GgxBrdf::new(roughness, Vec3::ONE);
        let mut per_technique: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
        let mut ratio = Vec::new();
        for c in configs(rng, 200, highlight) {
            let cap = Cap::from_sphere(c.center, c.radius);
            let Some(sampler) = SphereLightSampler::new(c.center, c.radius, c.wo, roughness) else {
                continue;
            };
            let f = |d: Vec3| brdf.eval_without_fresnel(c.wo, d) as f64 * d.z.max(0.0) as f64;
            let us: Vec<[f32; 4]> = (0..samples).map(|_| rng.u4()).collect();
            let single = |s: Sample| {
                if s.pdf > 0.0 {
                    f(s.dir) / s.pdf as f64
                } else {
                    0.0
                }
            };
            let cap_pdf = |d: Vec3| cap.pdf(d);
            let sptd_pdf = |d: Vec3| sampler.pdf(d);
            let values = [
                relative_variance(us.iter().map(|u| single(cap.sample_uniform([u[0], u[1]])))),
                relative_variance(us.iter().map(|u| single(sampler.sample([u[0], u[1]])))),
                relative_variance(us.iter().map(|u| {
                    let b = brdf.sample(c.wo, [u[2], u[3]]);
                    if b.pdf > 0.0 && cap.contains(b.dir) {
                        f(b.dir) / b.pdf as f64
                    } else {
                        0.0
                    }
                })),
                relative_variance(us.iter().map(|u| {
                    estimate(
                        &brdf,
                        c.wo,
                        &cap,
                        (cap.sample_uniform([u[0], u[1]]), &cap_pdf),
                        [u[2], u[3]],
                    )
                })),
                relative_variance(us.iter().map(|u| {
                    estimate(
                        &brdf,
                        c.wo,
                        &cap,
                        (sampler.sample([u[0], u[1]]), &sptd_pdf),
                        [u[2], u[3]],
                    )
                })),
            ];
            if values.iter().all(|v| v.is_some()) {
                for (k, v) in values.iter().enumerate() {
                    per_technique[k].push(v.unwrap());
                }
                ratio.push(values[4].unwrap() / values[3].unwrap());
            }
        }
        columns.push(per_technique);
        ratios.push(ratio);
    }
    for (k, name) in names.iter().enumerate() {
        let cells: Vec<String> = columns
            .iter()
            .map(|c| {
                let (mean, median) = mean_and_median(c[k].clone());
                format!("{mean:.2e} ({median:.1e})")
            })
            .collect();
        println!("| {name} | {} |", cells.join(" | "));
    }
    let cells: Vec<String> = ratios
        .iter()
        .map(|r| {
            let (mean, median) = mean_and_median(r.clone());
            let better = r.iter().filter(|&&x| x < 1.0).count() as f64 / r.len() as f64;
            format!("{mean:.2} ({median:.2}), {:.0}% < 1", 100.0 * better)
        })
        .collect();
    println!(
        "| ratio joint / classic per configuration: mean (median), share below 1 | {} |",
        cells.join(" | ")
    );
}

/// `∫_C V f dω` estimates for a phase function: joint pivot-phase sampling in the cap
/// against HG sampling + uniform cap sampling by the balance heuristic. V blocks the
/// half of the cap on the negative side of the plane through the cap's axis and `y`
/// when `occluded`.
fn phase_table(rng: &mut Rng) {
    println!("\n### Phase functions: relative variance of a 16-sample estimate of ∫_C V f_p dω\n");
    println!(
        "200 random spheres (sin of half-angle log-uniform in [0.01, 0.5]) around random \
         directions; HG with g, the pivot phase function with g_p = Q(g) (Eq. 27–28). Joint: \
         one sample of the pivot phase function in the light's cap (Section 6.2). MIS: one HG \
         sample + one uniform cap sample, balance heuristic. V = 1 (unoccluded) or half of the \
         cap blocked. Mean (median).\n"
    );
    println!("| g | V | pivot, joint in cap | HG + cap, MIS |");
    println!("|---|---|---:|---:|");
    let wo = Vec3::Z;
    for g in [0.3f32, 0.7, 0.9] {
        let gp = pivot_from_henyey_greenstein(g);
        for occluded in [false, true] {
            let (mut joint, mut mis) = (Vec::new(), Vec::new());
            for c in configs(rng, 200, false) {
                let cap = Cap::from_sphere(c.center, c.radius);
                let Some(prepared) = pivot_phase_in_cap(wo, gp, &cap) else {
                    continue;
                };
                let side = cap.axis.cross(Vec3::Y).normalize_or(Vec3::X);
                let v = |d: Vec3| {
                    if occluded && d.dot(side) < 0.0 {
                        0.0
                    } else {
                        1.0
                    }
                };
                let us: Vec<[f32; 4]> = (0..2000).map(|_| rng.u4()).collect();
                let a = relative_variance(us.iter().map(|u| {
                    let s = prepared.sample([u[0], u[1]]);
                    if s.pdf > 0.0 {
                        v(s.dir) * pivot_phase(wo.dot(s.dir), gp) as f64 / s.pdf as f64
                    } else {
                        0.0
                    }
                }));
                let b = relative_variance(us.iter().map(|u| {
                    let mut sum = 0.0;
                    let s = cap.sample_uniform([u[0], u[1]]);
                    if s.pdf > 0.0 {
                        let f = henyey_greenstein(wo.dot(s.dir), g) as f64;
                        sum += v(s.dir) * f / (s.pdf as f64 + f);
                    }
                    let h = sample_henyey_greenstein(wo, g, [u[2], u[3]]);
                    if h.pdf > 0.0 && cap.contains(h.dir) {
                        sum += v(h.dir) * h.pdf as f64 / (h.pdf as f64 + cap.pdf(h.dir) as f64);
                    }
                    sum
                }));
                if let (Some(a), Some(b)) = (a, b) {
                    joint.push(a);
                    mis.push(b);
                }
            }
            let (ja, jm) = mean_and_median(joint);
            let (ma, mm) = mean_and_median(mis);
            println!(
                "| {g} | {} | {ja:.2e} ({jm:.1e}) | {ma:.2e} ({mm:.1e}) |",
                if occluded { "half" } else { "1" }
            );
        }
    }
}

const INPUTS: usize = 4096;
const REPEATS: usize = 31;

fn time_ns(run: impl Fn(usize) -> f32) -> f64 {
    sphera_tools::measurements::bench::time_ns(INPUTS, REPEATS, run)
}

fn timing_table(rng: &mut Rng) {
    let cs = configs(rng, INPUTS, false);
    let us: Vec<[f32; 4]> = (0..INPUTS).map(|_| rng.u4()).collect();
    let caps: Vec<Cap> = cs
        .iter()
        .map(|c| Cap::from_sphere(c.center, c.radius))
        .collect();
    let samplers: Vec<SphereLightSampler> = cs
        .iter()
        .map(|c| {
            SphereLightSampler::new(c.center, c.radius, c.wo, 0.3)
                .unwrap_or(SphereLightSampler::EMPTY)
        })
        .collect();
    let shadings: Vec<SphereLightShading> = cs
        .iter()
        .map(|c| SphereLightShading::new(c.wo, 0.3, Vec3::splat(0.04)).unwrap())
        .collect();
    let brdf = GgxBrdf::new(0.3, Vec3::splat(0.04));
    let bent = Cap::from_axis_cos(Vec3::new(0.2, 0.0, 1.0), 0.3);
    let value = |s: Sample| s.dir.x + s.pdf;
    let cap_sample = time_ns(|i| value(caps[i].sample_uniform([us[i][0], us[i][1]])));
    let classic = time_ns(|i| {
        let c = &cs[i];
        let cap = Cap::from_sphere(c.center, c.radius);
        let s = cap.sample_uniform([us[i][0], us[i][1]]);
        let b = brdf.sample(c.wo, [us[i][2], us[i][3]]);
        value(s)
            + brdf.pdf(c.wo, s.dir)
            + cap.pdf(b.dir)
            + brdf.eval(c.wo, s.dir).x
            + brdf.eval(c.wo, b.dir).x
    });
    let rows = [
        ("uniform cap: sample", cap_sample),
        (
            "SPTD light sampler: prepare (table lookup, pivoted cap)",
            time_ns(|i| {
                let c = &cs[i];
                SphereLightSampler::new(c.center, c.radius, c.wo, 0.3)
                    .map_or(0.0, |s| s.sptd.integral)
            }),
        ),
        (
            "SPTD light sampler: sample",
            time_ns(|i| value(samplers[i].sample([us[i][0], us[i][1]]))),
        ),
        (
            "SPTD light sampler: pdf",
            time_ns(|i| samplers[i].pdf(caps[(i + 1) % INPUTS].axis)),
        ),
        (
            "GGX visible normals: sample",
            time_ns(|i| value(brdf.sample(cs[i].wo, [us[i][2], us[i][3]]))),
        ),
        (
            "classic: cap + GGX sample, pdfs and BRDF values (per light sample)",
            classic,
        ),
        (
            "joint: prepare + SPTD + GGX sample, pdfs and BRDF values (per light sample)",
            time_ns(|i| {
                let c = &cs[i];
                let Some(sampler) = SphereLightSampler::new(c.center, c.radius, c.wo, 0.3) else {
                    return 0.0;
                };
                let s = sampler.sample([us[i][0], us[i][1]]);
                let b = brdf.sample(c.wo, [us[i][2], us[i][3]]);
                value(s)
                    + brdf.pdf(c.wo, s.dir)
                    + sampler.pdf(b.dir)
                    + brdf.eval(c.wo, s.dir).x
                    + brdf.eval(c.wo, b.dir).x
            }),
        ),
        (
            "real-time shading: prepare (pivot + LTC Fresnel lookup, g(H))",
            time_ns(|i| {
                SphereLightShading::new(cs[i].wo, 0.3, Vec3::splat(0.04))
                    .map_or(0.0, |s| s.fit.albedo)
            }),
        ),
        (
            "real-time shading: shade one light",
            time_ns(|i| shadings[i].eval(&caps[i]).x),
        ),
        (
            "real-time shading: shade with a bent cone",
            time_ns(|i| shadings[i].eval_occluded(&caps[i], &bent).x),
        ),
        (
            "pivot cap (g(C))",
            time_ns(|i| pivot_cap(&caps[i], samplers[i].sptd.sptd.pivot).one_minus_cos),
        ),
        (
            "pivot phase in a cap: prepare + sample",
            time_ns(|i| {
                pivot_phase_in_cap(cs[i].wo, 0.7, &caps[i])
                    .map_or(0.0, |p| value(p.sample([us[i][0], us[i][1]])))
            }),
        ),
        (
            "Henyey–Greenstein: sample",
            time_ns(|i| {
                value(sample_henyey_greenstein(
                    cs[i].wo,
                    0.7,
                    [us[i][0], us[i][1]],
                ))
            }),
        ),
    ];
    println!("\n### ns per operation ({INPUTS} random inputs, median of {REPEATS} runs)\n");
    println!("| operation | ns | ratio to uniform cap sample |");
    println!("|---|---:|---:|");
    for (name, ns) in rows {
        println!("| {name} | {ns:.1} | {:.2}× |", ns / cap_sample);
    }
    println!(
        "\nJoint per light sample over classic per light sample: {:.2}×.",
        rows[6].1 / classic
    );
}

fn main() {
    let mut rng = Rng(11);
    println!("## Sphere lights with SPTDs (cargo bench -p sphera-tools --bench spheres)");
    variance_table(&mut rng, false);
    variance_table(&mut rng, true);
    phase_table(&mut rng);
    timing_table(&mut rng);
}
