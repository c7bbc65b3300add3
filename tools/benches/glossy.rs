//! BRDF importance sampling for polygonal lights (Peters 2021, Sec. 5 and supplement B):
//! the variance and the cost of every combination of techniques on glossy surfaces,
//! printed as markdown tables by one run (`cargo bench -p sphera-tools --bench glossy`).
//!
//! Configurations: random convex polygons (3 to 6 vertices, 0.2 to 1.5 across, 1 to 4
//! away, tilted at random, some crossing the horizon), random view directions (0° to
//! 80° from the normal), a material with diffuse albedo 0.2 and GGX with F0 = 0.5, and
//! roughness 0.1, 0.3 and 0.6. Nothing is occluded (V = 1). The estimators of
//! `∫_P f cos θ dω` (per unit radiance, luminance of the RGB estimate), 16 samples each:
//!
//! - `projected`: 16 projected solid angle samples (light sampling);
//! - `solid angle`: 16 solid angle samples;
//! - `BRDF`: 16 samples of the BRDF (a lobe chosen by its albedo: cosine-weighted
//!   hemisphere for Lambert, visible normals for GGX), counted where they hit the light;
//! - `BRDF + projected, balance` / `power`: 8 samples of each, MIS (Veach 1997);
//! - `LTC + projected, weighted balance` / `clamped optimal` / `optimal`: 8 samples of
//!   each technique of [`PolygonLight`], with `v = 1/2` for the last two.
//!
//! The variance of each estimator is measured from 64 independent repetitions per
//! configuration and divided by the square of the configuration's value (the mean of
//! all estimators' means, which are all unbiased): the relative variance. The table
//! gives its mean and median over configurations. The timing table
//! gives ns per prepared polygon and one sample of each technique it uses, including
//! the BRDF and pdf evaluations that the estimate needs (no rays), median of repeats.
// NaN-rejecting comparisons are written `!(x > 0.0)` on purpose, as in the core.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use sphera::brdf::Ltc;
use sphera::brdf::ggx::GgxBrdf;
use sphera::brdf::lambert::Lambert;
use sphera::mis;
use sphera::polygon::light::{Material, MisHeuristic, PolygonLight};
use sphera::polygon::{ProjectedPolygon, SolidAnglePolygon};
use sphera::{Sample, Vec3};
use sphera_test_support::Rng;
use std::f32::consts::PI;
use std::hint::black_box;
use std::time::Instant;

const ROUGHNESS: [f32; 3] = [0.1, 0.3, 0.6];
const CONFIGURATIONS: usize = 200;
const REPETITIONS: usize = 64;
const SAMPLES: usize = 16;

fn luminance(v: Vec3) -> f32 {
    0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z
}

/// One configuration: a polygon, a view direction and a material.
struct Configuration {
    polygon: Vec<Vec3>,
    wo: Vec3,
    material: Material,
}

fn random_configuration(rng: &mut Rng, roughness: f32) -> Configuration {
    loop {
        let n = 3 + (rng.next_u64() % 4) as usize;
        let elevation = (rng.uniform_f32() * 80.0 - 5.0).to_radians();
        let azimuth = rng.uniform_f32() * 2.0 * PI;
        let distance = 1.0 + 3.0 * rng.uniform_f32();
        let centre = distance
            * Vec3::new(
                elevation.cos() * azimuth.cos(),
                elevation.cos() * azimuth.sin(),
                elevation.sin(),
            );
        // A random plane orientation facing the shading point more or less.
        let facing = -centre.normalize();
        let normal = (facing
            + 0.8
                * Vec3::new(
                    rng.uniform_f32() - 0.5,
                    rng.uniform_f32() - 0.5,
                    rng.uniform_f32() - 0.5,
                ))
        .normalize();
        let a = normal.any_orthonormal_vector();
        let b = normal.cross(a);
        let radius = 0.1 + 0.65 * rng.uniform_f32();
        let phase = rng.uniform_f32() * 2.0 * PI;
        let polygon: Vec<Vec3> = (0..n)
            .map(|k| {
                let t = phase + 2.0 * PI * k as f32 / n as f32;
                centre + radius * (t.cos() * a + t.sin() * b)
            })
            .collect();
        let view_elevation = (90.0 - 80.0 * rng.uniform_f32()).to_radians();
        let view_azimuth = rng.uniform_f32() * 2.0 * PI;
        let wo = Vec3::new(
            view_elevation.cos() * view_azimuth.cos(),
            view_elevation.cos() * view_azimuth.sin(),
            view_elevation.sin(),
        );
        let material = Material {
            diffuse: Vec3::splat(0.2),
            f0: Vec3::splat(0.5),
            roughness,
        };
        let light = PolygonLight::new(&polygon, wo, &material, MisHeuristic::Balance, 0.5);
        let above_horizon =
            ProjectedPolygon::new(&polygon).is_some() && SolidAnglePolygon::new(&polygon).is_some();
        if above_horizon && light.is_some_and(|l| luminance(l.unshadowed()) > 1e-6) {
            return Configuration {
                polygon,
                wo,
                material,
            };
        }
    }
}

/// The BRDF of a configuration, with the lobe selection of BRDF sampling.
struct Brdf {
    lambert: Lambert,
    ggx: GgxBrdf,
    wo: Vec3,
    /// Probability of sampling the GGX lobe.
    specular_probability: f32,
}

impl Brdf {
    fn new(c: &Configuration) -> Brdf {
        let ltc = Ltc::from_ggx(c.wo, c.material.roughness).expect("view above the horizon");
        let specular = luminance(ltc.specular_albedo(c.material.f0));
        let diffuse = luminance(c.material.diffuse);
        Brdf {
            lambert: Lambert::new(c.material.diffuse),
            ggx: GgxBrdf::new(c.material.roughness, c.material.f0),
            wo: c.wo,
            specular_probability: specular / (specular + diffuse),
        }
    }
    /// f cos θ, luminance.
    fn eval_cos(&self, wi: Vec3) -> f32 {
        if !(wi.z > 0.0) {
            return 0.0;
        }
        luminance(self.lambert.eval(self.wo, wi) + self.ggx.eval(self.wo, wi)) * wi.z
    }
    fn pdf(&self, wi: Vec3) -> f32 {
        let q = self.specular_probability;
        (1.0 - q) * self.lambert.pdf(wi) + q * self.ggx.pdf(self.wo, wi)
    }
    fn sample(&self, u: [f32; 2]) -> Sample {
        let q = self.specular_probability;
        let s = if u[0] < q {
            self.ggx.sample(self.wo, [u[0] / q, u[1]])
        } else {
            self.lambert.sample([(u[0] - q) / (1.0 - q), u[1]])
        };
        if !(s.pdf > 0.0) {
            return Sample::NONE;
        }
        Sample {
            dir: s.dir,
            pdf: self.pdf(s.dir),
        }
    }
}

/// The estimators of the variance table, as (name, one 16-sample estimate).
#[derive(Clone, Copy)]
enum Estimator {
    Projected,
    SolidAngle,
    BrdfOnly,
    BrdfBalance,
    BrdfPower,
    Ltc(MisHeuristic),
}

const ESTIMATORS: [(&str, Estimator); 8] = [
    ("projected (light sampling)", Estimator::Projected),
    ("solid angle (light sampling)", Estimator::SolidAngle),
    ("BRDF sampling", Estimator::BrdfOnly),
    ("BRDF + projected, balance", Estimator::BrdfBalance),
    ("BRDF + projected, power", Estimator::BrdfPower),
    (
        "LTC + projected, weighted balance",
        Estimator::Ltc(MisHeuristic::WeightedBalance),
    ),
    (
        "LTC + projected, clamped optimal (v = 1/2)",
        Estimator::Ltc(MisHeuristic::ClampedOptimal),
    ),
    (
        "LTC + projected, optimal (v = 1/2)",
        Estimator::Ltc(MisHeuristic::Optimal),
    ),
];

/// Everything an estimator needs, prepared once per configuration.
struct Prepared {
    brdf: Brdf,
    projected: ProjectedPolygon,
    solid_angle: SolidAnglePolygon,
    lights: Vec<(MisHeuristic, PolygonLight)>,
}

fn prepare(c: &Configuration) -> Prepared {
    let lights = [
        MisHeuristic::WeightedBalance,
        MisHeuristic::ClampedOptimal,
        MisHeuristic::Optimal,
    ]
    .into_iter()
    .map(|h| {
        (
            h,
            PolygonLight::new(&c.polygon, c.wo, &c.material, h, 0.5).expect("valid"),
        )
    })
    .collect();
    Prepared {
        brdf: Brdf::new(c),
        projected: ProjectedPolygon::new(&c.polygon).expect("valid"),
        solid_angle: SolidAnglePolygon::new(&c.polygon).expect("valid"),
        lights,
    }
}

/// One sample of light sampling with `projected`, weighted against BRDF sampling.
fn light_sample_weighted(p: &Prepared, u: [f32; 2], power: bool) -> f32 {
    let s = p.projected.sample(u);
    if !(s.pdf > 0.0) {
        return 0.0;
    }
    let other = p.brdf.pdf(s.dir);
    let w = if power {
        mis::power_heuristic(&[s.pdf, other], 0)
    } else {
        mis::balance_heuristic(&[s.pdf, other], 0)
    };
    p.brdf.eval_cos(s.dir) * w / s.pdf
}

/// One sample of BRDF sampling, counted where it hits the polygon, weighted against
/// light sampling (or not, for BRDF sampling alone).
fn brdf_sample_weighted(p: &Prepared, u: [f32; 2], weighting: Option<bool>) -> f32 {
    let s = p.brdf.sample(u);
    if !(s.pdf > 0.0) {
        return 0.0;
    }
    let light_pdf = p.projected.pdf(s.dir);
    if !(light_pdf > 0.0) {
        return 0.0; // misses the light
    }
    let w = match weighting {
        None => 1.0,
        Some(true) => mis::power_heuristic(&[s.pdf, light_pdf], 0),
        Some(false) => mis::balance_heuristic(&[s.pdf, light_pdf], 0),
    };
    p.brdf.eval_cos(s.dir) * w / s.pdf
}

fn estimate(p: &Prepared, estimator: Estimator, rng: &mut Rng) -> f32 {
    let mut sum = 0.0;
    match estimator {
        Estimator::Projected => {
            for _ in 0..SAMPLES {
                let s = p.projected.sample(rng.u2());
                if s.pdf > 0.0 {
                    sum += p.brdf.eval_cos(s.dir) / s.pdf;
                }
            }
            sum / SAMPLES as f32
        }
        Estimator::SolidAngle => {
            for _ in 0..SAMPLES {
                let s = p.solid_angle.sample(rng.u2());
                if s.pdf > 0.0 {
                    sum += p.brdf.eval_cos(s.dir) / s.pdf;
                }
            }
            sum / SAMPLES as f32
        }
        Estimator::BrdfOnly => {
            for _ in 0..SAMPLES {
                sum += brdf_sample_weighted(p, rng.u2(), None);
            }
            sum / SAMPLES as f32
        }
        Estimator::BrdfBalance | Estimator::BrdfPower => {
            let power = matches!(estimator, Estimator::BrdfPower);
            for _ in 0..SAMPLES / 2 {
                sum += light_sample_weighted(p, rng.u2(), power);
                sum += brdf_sample_weighted(p, rng.u2(), Some(power));
            }
            sum / (SAMPLES / 2) as f32
        }
        Estimator::Ltc(heuristic) => {
            let light = &p
                .lights
                .iter()
                .find(|(h, _)| *h == heuristic)
                .expect("prepared")
                .1;
            for _ in 0..SAMPLES / 2 {
                for technique in 0..2 {
                    let s = light.sample(technique, rng.u2());
                    sum += luminance(s.visible + s.unoccluded);
                }
            }
            sum / (SAMPLES / 2) as f32
        }
    }
}

fn variance_table() {
    println!("## Relative variance of 16-sample estimates, unoccluded\n");
    println!(
        "{CONFIGURATIONS} random configurations per roughness, {REPETITIONS} repetitions each; \
         relative variance = variance / value², mean (median) over configurations; diffuse 0.2, F0 0.5.\n"
    );
    print!("| technique |");
    for r in ROUGHNESS {
        print!(" roughness {r} |");
    }
    println!();
    print!("|---|");
    for _ in ROUGHNESS {
        print!("---:|");
    }
    println!();
    let mut table = vec![vec![(0.0f64, 0.0f64); ROUGHNESS.len()]; ESTIMATORS.len()];
    for (ri, &roughness) in ROUGHNESS.iter().enumerate() {
        let mut rng = Rng(1000 + ri as u64);
        let configurations: Vec<Configuration> = (0..CONFIGURATIONS)
            .map(|_| random_configuration(&mut rng, roughness))
            .collect();
        // Per configuration: every estimator's variance, and the mean of all
        // estimators' means (all unbiased) as the common scale.
        let mut relative = vec![Vec::with_capacity(CONFIGURATIONS); ESTIMATORS.len()];
        let mut estimates_rng = Rng(77 + ri as u64);
        for c in &configurations {
            let p = prepare(c);
            let mut variances = [0.0f64; ESTIMATORS.len()];
            let mut mean_of_means = 0.0;
            for (ei, &(_, estimator)) in ESTIMATORS.iter().enumerate() {
                let values: Vec<f64> = (0..REPETITIONS)
                    .map(|_| estimate(&p, estimator, &mut estimates_rng) as f64)
                    .collect();
                let mean = values.iter().sum::<f64>() / REPETITIONS as f64;
                variances[ei] = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>()
                    / (REPETITIONS - 1) as f64;
                mean_of_means += mean / ESTIMATORS.len() as f64;
            }
            for (ei, variance) in variances.iter().enumerate() {
                relative[ei].push(variance / (mean_of_means * mean_of_means));
            }
        }
        for (ei, values) in relative.iter_mut().enumerate() {
            values.sort_by(|a, b| a.partial_cmp(b).unwrap());
            let mean = values.iter().sum::<f64>() / values.len() as f64;
            table[ei][ri] = (mean, values[values.len() / 2]);
        }
    }
    for (ei, (name, _)) in ESTIMATORS.iter().enumerate() {
        print!("| {name} |");
        for &(mean, median) in &table[ei] {
            print!(" {mean:.2e} ({median:.2e}) |");
        }
        println!();
    }
    println!();
}

const TIMING_CONFIGURATIONS: usize = 1024;
const TIMING_REPEATS: usize = 15;

/// One timed operation: a configuration and two pairs of random numbers in, a value out.
type TimedRun = dyn Fn(&Configuration, [f32; 2], [f32; 2]) -> f32;

/// ns per (prepare + one sample of each technique the estimator uses + evaluations).
fn timing_table() {
    println!("## ns per prepared polygon and one sample of each technique (no rays)\n");
    println!(
        "{TIMING_CONFIGURATIONS} random configurations, roughness 0.3, median of {TIMING_REPEATS} runs.\n"
    );
    let mut rng = Rng(4242);
    let configurations: Vec<Configuration> = (0..TIMING_CONFIGURATIONS)
        .map(|_| random_configuration(&mut rng, 0.3))
        .collect();
    let us: Vec<[f32; 2]> = (0..4 * TIMING_CONFIGURATIONS).map(|_| rng.u2()).collect();
    let time = |run: &TimedRun| -> f64 {
        let mut times: Vec<f64> = (0..TIMING_REPEATS)
            .map(|_| {
                let start = Instant::now();
                let mut sum = 0.0f32;
                for (i, c) in configurations.iter().enumerate() {
                    sum += run(black_box(c), us[2 * i], us[2 * i + 1]);
                }
                black_box(sum);
                start.elapsed().as_secs_f64() * 1e9 / configurations.len() as f64
            })
            .collect();
        times.sort_by(|a, b| a.partial_cmp(b).unwrap());
        times[TIMING_REPEATS / 2]
    };
    let projected_only = time(&|c, u, _| {
        let brdf = Brdf::new(c);
        let p = ProjectedPolygon::new(&c.polygon).unwrap();
        let s = p.sample(u);
        brdf.eval_cos(s.dir) / s.pdf
    });
    let brdf_and_projected = time(&|c, u, v| {
        let brdf = Brdf::new(c);
        let p = ProjectedPolygon::new(&c.polygon).unwrap();
        let s = p.sample(u);
        let b = brdf.sample(v);
        let mut sum =
            brdf.eval_cos(s.dir) * mis::balance_heuristic(&[s.pdf, brdf.pdf(s.dir)], 0) / s.pdf;
        let lp = p.pdf(b.dir);
        if lp > 0.0 {
            sum += brdf.eval_cos(b.dir) * mis::balance_heuristic(&[b.pdf, lp], 0) / b.pdf;
        }
        sum
    });
    let ltc = |heuristic: MisHeuristic| {
        time(&move |c, u, v| {
            let light = PolygonLight::new(&c.polygon, c.wo, &c.material, heuristic, 0.5).unwrap();
            let a = light.sample(0, u);
            let b = light.sample(1, v);
            luminance(a.visible + a.unoccluded + b.visible + b.unoccluded)
        })
    };
    let rows = [
        ("projected only (1 sample)", projected_only),
        ("BRDF + projected, balance (2 samples)", brdf_and_projected),
        (
            "LTC + projected, weighted balance (2 samples)",
            ltc(MisHeuristic::WeightedBalance),
        ),
        (
            "LTC + projected, clamped optimal (2 samples)",
            ltc(MisHeuristic::ClampedOptimal),
        ),
        (
            "LTC + projected, optimal (2 samples)",
            ltc(MisHeuristic::Optimal),
        ),
    ];
    println!("| technique | ns | ratio to projected only |");
    println!("|---|---:|---:|");
    for (name, ns) in rows {
        println!("| {name} | {ns:.1} | {:.2}× |", ns / projected_only);
    }
    println!();
}

fn main() {
    timing_table();
    variance_table();
}
