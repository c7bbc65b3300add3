//! ns per sample of the samplers beyond the polygon light samplers of `report.rs`: BRDF
//! sampling (GGX visible normals, Lambert), the LTC inside a prepared polygon, sphere
//! caps (construction from a sphere and uniform sampling), the pivot transformation, and
//! the phase functions (pivot and Henyey–Greenstein), each with its pdf where the
//! sampler returns one, and the SG operations (evaluation, vMF sampling, product, inner
//! product, ASG convolution, VSGL incoming radiance, diffuse and specular shading). Median of repeated runs over 4096 random inputs; ratios to
//! uniform cap sampling measured in the same run (`cargo bench -p sphera-tools --bench
//! samplers`, a few seconds). A second table times the VSGL accumulator and FIS cluster
//! selection, and one frame of FIS against the k-means comparison.
use sphera::brdf::Ltc;
use sphera::brdf::ggx::GgxBrdf;
use sphera::brdf::lambert::Lambert;
use sphera::polygon::LtcPolygon;
use sphera::sg::asg::Asg;
use sphera::sg::shading::{
    beckmann_specular_shading, beckmann_specular_shading_sg, diffuse_shading_constant_cosine,
    diffuse_shading_product, incoming_radiance, specular_shading, specular_shading_sg,
};
use sphera::sg::{Sg, vmf_sample};
use sphera::sphere::phase;
use sphera::sphere::{Cap, CapIntersection, CapUnion, Sptd, SptdInCap, pivot_cap, pivot_transform};
use sphera::vsgl::{Vpl, Vsgl, VsglAccumulator, fis_select, luminance};
use sphera::{Sample, Vec3};
use sphera_test_support::Rng;
use sphera_tools::measurements::vsgl_kmeans::{KMeansMetric, kmeans_vsgls};
use sphera_tools::measurements::vsgl_pyramid::VsglPyramidBuffer;
use std::hint::black_box;
use std::time::Instant;

const INPUTS: usize = 4096;
const REPEATS: usize = 31;

fn time_ns(run: impl Fn(usize) -> f32) -> f64 {
    sphera_tools::measurements::bench::time_ns(INPUTS, REPEATS, run)
}

fn value(s: Sample) -> f32 {
    s.dir.x + s.pdf
}

fn main() {
    let mut rng = Rng(7);
    let us: Vec<[f32; 2]> = (0..INPUTS)
        .map(|_| [rng.uniform_f32(), rng.uniform_f32()])
        .collect();
    let views: Vec<Vec3> = (0..INPUTS)
        .map(|_| {
            let d = rng.direction();
            Vec3::new(d.x, d.y, d.z.abs().max(0.05)).normalize()
        })
        .collect();
    let spheres: Vec<(Vec3, f32)> = (0..INPUTS)
        .map(|_| {
            (
                rng.direction() * (1.0 + 9.0 * rng.uniform_f32()),
                0.05 + 0.9 * rng.uniform_f32(),
            )
        })
        .collect();
    let caps: Vec<Cap> = spheres
        .iter()
        .map(|&(c, r)| Cap::from_sphere(c, r))
        .collect();
    let pivots: Vec<Vec3> = (0..INPUTS)
        .map(|_| rng.direction() * (0.95 * rng.uniform_f32()))
        .collect();
    let ggx = GgxBrdf::new(0.3, Vec3::splat(0.04));
    let lambert = Lambert::new(Vec3::splat(0.5));
    let quad = [
        Vec3::new(-0.8, -0.4, 1.0),
        Vec3::new(0.2, -0.4, 1.2),
        Vec3::new(0.2, 0.5, 1.2),
        Vec3::new(-0.8, 0.5, 1.0),
    ];
    let ltc_polygons: Vec<LtcPolygon> = views
        .iter()
        .map(|&wo| {
            LtcPolygon::new(&Ltc::from_ggx(wo, 0.3).unwrap(), &quad).unwrap_or(LtcPolygon::EMPTY)
        })
        .collect();

    let sgs: Vec<Sg> = (0..INPUTS)
        .map(|_| {
            Sg::new(
                rng.direction(),
                10f32.powf(4.0 * rng.uniform_f32() - 1.0),
                1.0 + rng.uniform_f32(),
            )
        })
        .collect();
    let asgs: Vec<Asg> = views
        .iter()
        .map(|&wo| Asg::from_ggx(Vec3::Z, wo, 0.09))
        .collect();
    let vsgl_means: Vec<Vec3> = (0..INPUTS)
        .map(|_| rng.direction() * (1.0 + 9.0 * rng.uniform_f32()))
        .collect();
    let incoming: Vec<Sg> = (0..INPUTS)
        .map(|i| incoming_radiance(&sgs[i], vsgl_means[i], 0.1))
        .collect();
    // Lights across the horizon of the upper hemisphere: the intersection C ∩ H that
    // the sphere-light sampler samples for them (issue 20, 1).
    let horizon = Cap::from_axis_one_minus_cos(Vec3::Z, 1.0);
    let lenses: Vec<CapIntersection> = caps
        .iter()
        .map(|cap| {
            let across = Cap::from_axis_one_minus_cos(
                Vec3::new(cap.axis.x, cap.axis.y, 0.2 * cap.axis.z).normalize(),
                cap.one_minus_cos,
            );
            CapIntersection::new(&across, &horizon).unwrap_or(CapIntersection::EMPTY)
        })
        .collect();
    // Two lights' caps: their union (issue 20, 1: sets of caps).
    let unions: Vec<(Cap, Cap, Option<CapUnion>)> = (0..INPUTS)
        .map(|i| {
            let (a, b) = (caps[i], caps[(i + 1) % INPUTS]);
            (a, b, CapUnion::new(&a, &b))
        })
        .collect();
    // Clamped-cosine SPTDs (axis z) in caps whose image crosses the base's horizon
    // (issue 20, 2: the clipped sampler), and for comparison in caps whose image lies
    // above it (the ellipse); the cap is the image's preimage under the pivot.
    let cosine_sptds: Vec<Sptd> = pivots
        .iter()
        .map(|&p| Sptd::clamped_cosine(p, Vec3::Z))
        .collect();
    let sptd_caps = |z_scale: f32, one_minus_cos: f32| -> Vec<Cap> {
        caps.iter()
            .zip(&cosine_sptds)
            .map(|(cap, sptd)| {
                let axis = Vec3::new(cap.axis.x, cap.axis.y, z_scale * cap.axis.z.abs() + 0.1);
                let t = one_minus_cos.min(cap.one_minus_cos * 10.0).max(1e-3);
                pivot_cap(
                    &Cap::from_axis_one_minus_cos(axis.normalize(), t),
                    sptd.pivot,
                )
            })
            .collect()
    };
    // Images across the horizon: `1 − cos θ` in [0.01, 1.5], `cos β = k sin θ` with
    // `k` in (−0.9, 0.9) (axis above or below the horizon, wider than a hemisphere too).
    // (A generator of their own: the inputs of the other rows stay as they were.)
    let mut cap_rng = Rng(20);
    let across_caps: Vec<Cap> = cosine_sptds
        .iter()
        .map(|sptd| {
            let t = 0.01 + 1.49 * cap_rng.uniform_f32();
            let k = 1.8 * cap_rng.uniform_f32() - 0.9;
            let cos_beta = k * (t * (2.0 - t)).sqrt();
            let sin_beta = (1.0 - cos_beta * cos_beta).sqrt();
            let phi = std::f32::consts::TAU * cap_rng.uniform_f32();
            let axis = Vec3::new(sin_beta * phi.cos(), sin_beta * phi.sin(), cos_beta);
            pivot_cap(&Cap::from_axis_one_minus_cos(axis, t), sptd.pivot)
        })
        .collect();
    let above_caps = sptd_caps(20.0, 0.05);
    let prepare = |caps: &[Cap]| -> Vec<SptdInCap> {
        caps.iter()
            .zip(&cosine_sptds)
            .map(|(cap, sptd)| SptdInCap::new(sptd, cap).unwrap_or(SptdInCap::EMPTY))
            .collect()
    };
    let across_sptds = prepare(&across_caps);
    let above_sptds = prepare(&above_caps);
    let cap_sample = time_ns(|i| value(caps[i].sample_uniform(us[i])));
    let rows = [
        ("sphere cap: uniform sample", cap_sample),
        (
            "sphere cap: from_sphere + uniform sample",
            time_ns(|i| {
                let (c, r) = spheres[i];
                value(Cap::from_sphere(c, r).sample_uniform(us[i]))
            }),
        ),
        ("sphere cap: pdf", time_ns(|i| caps[i].pdf(views[i]))),
        (
            "two-cap intersection (a cap across the horizon ∩ H): new + uniform sample",
            time_ns(|i| {
                let lens = &lenses[i];
                CapIntersection::new(&lens.radial, &lens.other)
                    .map_or(0.0, |lens| value(lens.sample_uniform(us[i])))
            }),
        ),
        (
            "two-cap intersection: uniform sample",
            time_ns(|i| value(lenses[i].sample_uniform(us[i]))),
        ),
        (
            "two-cap intersection: pdf",
            time_ns(|i| lenses[i].pdf(views[i])),
        ),
        (
            "two-cap union (two lights' caps): new + uniform sample",
            time_ns(|i| {
                let (a, b, _) = &unions[i];
                CapUnion::new(a, b).map_or(0.0, |union| value(union.sample_uniform(us[i])))
            }),
        ),
        (
            "two-cap union: uniform sample",
            time_ns(|i| {
                unions[i]
                    .2
                    .map_or(0.0, |union| value(union.sample_uniform(us[i])))
            }),
        ),
        (
            "two-cap union: pdf",
            time_ns(|i| unions[i].2.map_or(0.0, |union| union.pdf(views[i]))),
        ),
        // SPTD integrals over sets of caps (Eq. 10-11; issue 20, 1), two lights' caps
        // under random pivots; the single cap and the intersection for comparison.
        (
            "uniform SPTD integral over a cap",
            time_ns(|i| Sptd::uniform(pivots[i]).integral_over_cap(&unions[i].0)),
        ),
        (
            "uniform SPTD integral over a cap intersection",
            time_ns(|i| {
                let (a, b, _) = &unions[i];
                Sptd::uniform(pivots[i]).integral_over_cap_intersection(a, b)
            }),
        ),
        (
            "uniform SPTD integral over a cap union",
            time_ns(|i| {
                let (a, b, _) = &unions[i];
                Sptd::uniform(pivots[i]).integral_over_cap_union(a, b)
            }),
        ),
        (
            "uniform SPTD integral over a cap complement",
            time_ns(|i| Sptd::uniform(pivots[i]).integral_over_cap_complement(&unions[i].0)),
        ),
        (
            "clamped-cosine SPTD integral over a cap",
            time_ns(|i| cosine_sptds[i].integral_over_cap(&unions[i].0)),
        ),
        (
            "clamped-cosine SPTD integral over a cap intersection",
            time_ns(|i| {
                let (a, b, _) = &unions[i];
                cosine_sptds[i].integral_over_cap_intersection(a, b)
            }),
        ),
        (
            "clamped-cosine SPTD integral over a cap union",
            time_ns(|i| {
                let (a, b, _) = &unions[i];
                cosine_sptds[i].integral_over_cap_union(a, b)
            }),
        ),
        (
            "clamped-cosine SPTD integral over a cap complement",
            time_ns(|i| cosine_sptds[i].integral_over_cap_complement(&unions[i].0)),
        ),
        (
            "clamped-cosine SPTD in a cap, image across the horizon: new + sample",
            time_ns(|i| {
                SptdInCap::new(&cosine_sptds[i], &across_caps[i])
                    .map_or(0.0, |s| value(s.sample(us[i])))
            }),
        ),
        (
            "clamped-cosine SPTD in a cap, image across the horizon: sample",
            time_ns(|i| value(across_sptds[i].sample(us[i]))),
        ),
        (
            "clamped-cosine SPTD in a cap, image across the horizon: pdf",
            time_ns(|i| across_sptds[i].pdf(views[i])),
        ),
        (
            "clamped-cosine SPTD in a cap, image above the horizon: sample",
            time_ns(|i| value(above_sptds[i].sample(us[i]))),
        ),
        (
            "pivot transformation of a direction",
            time_ns(|i| pivot_transform(views[i], pivots[i]).x),
        ),
        (
            "pivot phase function: sample",
            time_ns(|i| value(phase::sample_pivot_phase(views[i], 0.7, us[i]))),
        ),
        (
            "Henyey–Greenstein: sample",
            time_ns(|i| value(phase::sample_henyey_greenstein(views[i], 0.7, us[i]))),
        ),
        (
            "GGX: visible-normal sample (α = 0.09)",
            time_ns(|i| value(ggx.sample(views[i], us[i]))),
        ),
        (
            "GGX: pdf",
            time_ns(|i| ggx.pdf(views[i], views[(i + 1) % INPUTS])),
        ),
        (
            "Lambert: cosine sample",
            time_ns(|i| value(lambert.sample(us[i]))),
        ),
        (
            "LTC in a prepared quad: sample",
            time_ns(|i| value(ltc_polygons[i].sample(us[i]))),
        ),
        (
            "LTC: lookup (Ltc::from_ggx)",
            time_ns(|i| Ltc::from_ggx(views[i], 0.3).map_or(0.0, |l| l.albedo())),
        ),
        ("SG: eval", time_ns(|i| sgs[i].eval(views[i]))),
        (
            "SG: vMF sample",
            time_ns(|i| value(vmf_sample(&sgs[i], us[i]))),
        ),
        (
            "SG: product",
            time_ns(|i| sgs[i].product(&sgs[(i + 1) % INPUTS]).log_amplitude),
        ),
        (
            "SG: inner product",
            time_ns(|i| sgs[i].inner_product(&sgs[(i + 1) % INPUTS])),
        ),
        (
            "ASG: convolution with an SG",
            time_ns(|i| asgs[i].convolve_sg(&sgs[i])),
        ),
        (
            "VSGL: incoming radiance SG (Eq. 7)",
            time_ns(|i| incoming_radiance(&sgs[i], vsgl_means[i], 0.1).log_amplitude),
        ),
        (
            "VSGL: diffuse shading, SG product",
            time_ns(|i| diffuse_shading_product(&incoming[i], Vec3::Z, 0.5, 1.0)),
        ),
        (
            "VSGL: diffuse shading, constant cosine",
            time_ns(|i| diffuse_shading_constant_cosine(&incoming[i], Vec3::Z, 0.5, 1.0)),
        ),
        (
            "VSGL: specular shading, ASG (incl. the fit)",
            time_ns(|i| specular_shading(&incoming[i], Vec3::Z, views[i], 0.3, 0.04, 1.0)),
        ),
        (
            "VSGL: specular shading, SG (incl. the fit)",
            time_ns(|i| specular_shading_sg(&incoming[i], Vec3::Z, views[i], 0.3, 0.04, 1.0)),
        ),
        (
            "VSGL: Beckmann specular shading, ASG (incl. the fit)",
            time_ns(|i| beckmann_specular_shading(&incoming[i], Vec3::Z, views[i], 0.3, 0.04, 1.0)),
        ),
        (
            "VSGL: Beckmann specular shading, SG (incl. the fit)",
            time_ns(|i| {
                beckmann_specular_shading_sg(&incoming[i], Vec3::Z, views[i], 0.3, 0.04, 1.0)
            }),
        ),
    ];
    let clipped = across_sptds.iter().filter(|s| s.is_clipped()).count();
    let ellipses = above_sptds
        .iter()
        .filter(|s| s.integral > 0.0 && !s.is_clipped())
        .count();
    println!("## ns per call of the BRDF, LTC, sphere-cap, phase-function and SG operations\n");
    println!("{INPUTS} random inputs, median of {REPEATS} runs; ratio to uniform cap sampling.");
    println!(
        "Clamped-cosine SPTDs: {clipped} of {INPUTS} images across the horizon are clipped, \
         {ellipses} of {INPUTS} above it are ellipses.\n"
    );
    println!("| operation | ns | ratio |");
    println!("|---|---:|---:|");
    for (name, ns) in rows {
        println!("| {name} | {ns:.1} | {:.2}× |", ns / cap_sample);
    }
    vsgl_table(&mut rng, &us);
}

/// ns per VSGL operation on a 64×64 RSM of random VPLs, and one frame of 256 clusters
/// by FIS and by the k-means comparison.
fn vsgl_table(rng: &mut Rng, us: &[[f32; 2]]) {
    const SIZE: usize = 64;
    const CLUSTERS: u32 = 256;
    let vpls: Vec<Vpl> = (0..SIZE * SIZE)
        .map(|k| {
            let (x, y) = ((k % SIZE) as f32, (k / SIZE) as f32);
            let normal = (rng.direction() + Vec3::new(0.0, 0.0, 1.5)).normalize();
            Vpl {
                position: Vec3::new(x * 0.1, y * 0.1, rng.uniform_f32()),
                normal,
                power: Vec3::new(rng.uniform_f32(), rng.uniform_f32(), rng.uniform_f32()) * 4.0,
                diffuse_reflectance: Vec3::splat(0.6),
                specular_reflectance: Vec3::splat(0.04),
                toward_incoming: (normal + rng.direction() * 0.5).normalize(),
                roughness: 0.1 + 0.8 * rng.uniform_f32(),
            }
        })
        .collect();
    let origin = Vec3::new(3.2, 3.2, 0.5);
    let base = {
        let mut a = VsglAccumulator::new(origin);
        a.add_vpl(&vpls[0]);
        a
    };
    let clusters: Vec<VsglAccumulator> = (0..INPUTS)
        .map(|i| {
            let mut a = VsglAccumulator::new(origin);
            for k in 0..16 {
                a.add_vpl(&vpls[(i * 16 + k) % vpls.len()]);
            }
            a
        })
        .collect();
    let buffer = VsglPyramidBuffer::from_vpls(&vpls, SIZE as u32, origin).unwrap();
    let pyramid = buffer.pyramid();
    let add_vpl = time_ns(|i| {
        let mut a = base;
        a.add_vpl(&vpls[i % vpls.len()]);
        a.sums.weight
    });
    let rows = [
        ("accumulator: add_vpl", add_vpl),
        (
            "accumulator: finish",
            time_ns(|i| clusters[i].finish().variance),
        ),
        (
            "fis_select (64² RSM, N = 256, K = 1, 8 bisection steps)",
            time_ns(|i| fis_select(&pyramid, CLUSTERS, 1.0, 8, us[i]).variance),
        ),
    ];
    println!("\n## ns per call of the VSGL accumulator and FIS\n");
    println!("{INPUTS} random inputs, median of {REPEATS} runs; ratio to add_vpl.\n");
    println!("| operation | ns | ratio |");
    println!("|---|---:|---:|");
    for (name, ns) in rows {
        println!("| {name} | {ns:.1} | {:.2}× |", ns / add_vpl);
    }
    // One frame: building the pyramid + 256 FIS clusters, against k-means.
    let frame = |run: &dyn Fn() -> f32| {
        let mut times: Vec<f64> = (0..9)
            .map(|_| {
                let start = Instant::now();
                black_box(run());
                start.elapsed().as_secs_f64() * 1e3
            })
            .collect();
        times.sort_by(|a, b| a.partial_cmp(b).unwrap());
        times[4]
    };
    let fis_ms = frame(&|| {
        let buffer = VsglPyramidBuffer::from_vpls(&vpls, SIZE as u32, origin).unwrap();
        let pyramid = buffer.pyramid();
        (0..CLUSTERS as usize)
            .map(|i| fis_select(&pyramid, CLUSTERS, 1.0, 8, us[i]).variance)
            .sum()
    });
    let kmeans_ms = frame(&|| {
        let mut rng = Rng(1);
        let mut uniform = || rng.uniform();
        let metric = KMeansMetric::for_clusters(CLUSTERS as usize, 6.4);
        kmeans_vsgls(&vpls, SIZE, CLUSTERS as usize, metric, &mut uniform)
            .vsgls
            .iter()
            .map(|v| v.variance)
            .sum()
    });
    println!("\n## One frame of {CLUSTERS} VSGLs from a {SIZE}² RSM (one core, ms, median of 9)\n");
    println!("| method | ms |");
    println!("|---|---:|");
    println!("| pyramid build + FIS | {fis_ms:.3} |");
    println!("| k-means (brute-force nearest centre, no iteration) | {kmeans_ms:.3} |");

    // Compactness of the clusters: luminance-weighted mean σ_v and mean diffuse and
    // specular λ_v (smaller σ, sharper lobes: tighter clusters).
    let fis: Vec<Vsgl> = (0..CLUSTERS as usize)
        .map(|i| fis_select(&pyramid, CLUSTERS, 1.0, 8, us[i]))
        .collect();
    let mut rng = Rng(1);
    let mut uniform = || rng.uniform();
    let metric = KMeansMetric::for_clusters(CLUSTERS as usize, 6.4);
    let kmeans = kmeans_vsgls(&vpls, SIZE, CLUSTERS as usize, metric, &mut uniform).vsgls;
    let stats = |vsgls: &[Vsgl]| {
        let (mut w, mut sigma, mut diffuse, mut specular, mut empty) = (0.0, 0.0, 0.0, 0.0, 0);
        for v in vsgls {
            let weight = luminance(v.diffuse_power + v.specular_power) as f64;
            if weight <= 0.0 || weight.is_nan() {
                empty += 1;
                continue;
            }
            w += weight;
            sigma += weight * (v.variance as f64).sqrt();
            diffuse += weight * v.diffuse.sharpness as f64;
            specular += weight * v.specular.sharpness as f64;
        }
        (sigma / w, diffuse / w, specular / w, empty, w)
    };
    println!("\n## Cluster compactness, {CLUSTERS} VSGLs from the same {SIZE}² RSM (one draw)\n");
    println!("Luminance-weighted means; the RSM spans 6.4 × 6.4 world units.\n");
    println!("| method | σ_v | diffuse λ_v | specular λ_v | empty clusters | Σ luminance |");
    println!("|---|---:|---:|---:|---:|---:|");
    for (name, vsgls) in [("FIS (K = 1)", &fis), ("k-means", &kmeans)] {
        let (sigma, diffuse, specular, empty, w) = stats(vsgls);
        println!("| {name} | {sigma:.3} | {diffuse:.3} | {specular:.3} | {empty} | {w:.1} |");
    }
}
