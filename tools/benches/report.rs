//! sphera's speed-versus-error report for polygon sampling: ns per (prepare + 1 sample)
//! and per sample for every technique, as ratios to Turk's area sampling measured in
//! the same run, and the accuracy of each technique per decade of solid angle against
//! an f64 reference.
//!
//! Run with `cargo bench -p sphera-tools --bench report`; add
//! `RUSTFLAGS="-C target-cpu=native"` to measure with FMA and AVX2.
use sphera::Vec3;
use sphera::polygon::SolidAnglePolygon;
use sphera::polygon::baselines::{ArvoPolygon, TurkPolygon};
use sphera_tools::reference::{self, D3};
use std::hint::black_box;
use std::time::Instant;

/// SplitMix64 for inputs.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn uniform(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u32 << 24) as f32
    }
}

/// A random convex polygon with `n` vertices on an ellipse above the shading point.
fn random_polygon(rng: &mut Rng, n: usize, center: Vec3, radius: f32) -> Vec<Vec3> {
    let normal = Vec3::new(rng.uniform() - 0.5, rng.uniform() - 0.5, 1.0).normalize();
    let (t, b) = sphera::math::orthonormal_basis(normal);
    let aspect = 0.5 + 0.5 * rng.uniform();
    let offset = rng.uniform() * std::f32::consts::TAU;
    (0..n)
        .map(|i| {
            let angle =
                offset + std::f32::consts::TAU * (i as f32 + 0.4 * rng.uniform()) / n as f32;
            center + t * (radius * angle.cos()) + b * (radius * aspect * angle.sin())
        })
        .collect()
}

const POLYGONS: usize = 1024;
const SAMPLES_PER_POLYGON: usize = 16;
const REPEATS: usize = 9;

/// Median over repeats of the time per operation in ns.
fn time_ns(operations: usize, mut run: impl FnMut() -> f32) -> f64 {
    let mut times: Vec<f64> = (0..REPEATS)
        .map(|_| {
            let start = Instant::now();
            black_box(run());
            start.elapsed().as_secs_f64() * 1e9 / operations as f64
        })
        .collect();
    times.sort_by(|a, b| a.partial_cmp(b).unwrap());
    times[REPEATS / 2]
}

trait Technique: Copy {
    const NAME: &'static str;
    fn prepare(vertices: &[Vec3]) -> Option<Self>;
    fn sample(&self, u: [f32; 2]) -> sphera::Sample;
}

macro_rules! technique {
    ($t:ty, $name:expr) => {
        impl Technique for $t {
            const NAME: &'static str = $name;
            #[inline(always)]
            fn prepare(vertices: &[Vec3]) -> Option<Self> {
                <$t>::new(vertices)
            }
            #[inline(always)]
            fn sample(&self, u: [f32; 2]) -> sphera::Sample {
                <$t>::sample(self, u)
            }
        }
    };
}
technique!(TurkPolygon, "Turk area sampling");
technique!(ArvoPolygon, "Arvo 1995");
technique!(SolidAnglePolygon, "solid angle (Alg. 5)");

/// (ns per prepare + 1 sample, ns per sample).
fn measure<T: Technique>(polygons: &[Vec<Vec3>], us: &[[f32; 2]]) -> (f64, f64) {
    let prepare_and_sample = time_ns(polygons.len() * 4, || {
        let mut sum = 0.0f32;
        for round in 0..4 {
            for (i, p) in polygons.iter().enumerate() {
                let prepared = T::prepare(black_box(p)).unwrap();
                let s = prepared.sample(us[(i + round * POLYGONS) % us.len()]);
                sum += s.dir.x + s.pdf;
            }
        }
        sum
    });
    let prepared: Vec<T> = polygons.iter().map(|p| T::prepare(p).unwrap()).collect();
    let per_sample = time_ns(prepared.len() * SAMPLES_PER_POLYGON, || {
        let mut sum = 0.0f32;
        for (i, p) in prepared.iter().enumerate() {
            for j in 0..SAMPLES_PER_POLYGON {
                let s = black_box(p).sample(us[(i * SAMPLES_PER_POLYGON + j) % us.len()]);
                sum += s.dir.x + s.pdf;
            }
        }
        sum
    });
    (prepare_and_sample, per_sample)
}

fn speed_table() {
    println!("## Speed (ns, median of {REPEATS} runs; ratios to Turk in the same run)\n");
    println!(
        "hardware FMA in this build: {}\n",
        sphera::math::HAS_HARDWARE_FMA
    );
    println!("| vertices | technique | prepare + 1 sample | ratio | per sample | ratio |");
    println!("|---:|---|---:|---:|---:|---:|");
    let mut rng = Rng(42);
    let us: Vec<[f32; 2]> = (0..POLYGONS * SAMPLES_PER_POLYGON)
        .map(|_| [rng.uniform(), rng.uniform()])
        .collect();
    for n in [3usize, 4, 7] {
        let polygons: Vec<Vec<Vec3>> = (0..POLYGONS)
            .map(|_| {
                let c = Vec3::new(
                    rng.uniform() - 0.5,
                    rng.uniform() - 0.5,
                    0.5 + rng.uniform(),
                );
                let radius = 0.3 + 0.5 * rng.uniform();
                random_polygon(&mut rng, n, c, radius)
            })
            .collect();
        let turk = measure::<TurkPolygon>(&polygons, &us);
        let rows = [
            (TurkPolygon::NAME, turk),
            (ArvoPolygon::NAME, measure::<ArvoPolygon>(&polygons, &us)),
            (
                SolidAnglePolygon::NAME,
                measure::<SolidAnglePolygon>(&polygons, &us),
            ),
        ];
        for (name, (both, sample)) in rows {
            println!(
                "| {n} | {name} | {both:.1} | {:.2}× | {sample:.1} | {:.2}× |",
                both / turk.0,
                sample / turk.1
            );
        }
    }
    println!();
}

fn accuracy_table() {
    println!("## Accuracy per decade of solid angle (random triangles and quads)\n");
    println!(
        "Relative error of Ω against f64 (median / max over 200 polygons) and the fraction of 400 samples per polygon whose f64 ray misses the polygon.\n"
    );
    println!(
        "| Ω | ours: median err | ours: max err | Arvo: median err | Arvo: max err | ours: outside | Arvo: outside |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let mut rng = Rng(7);
    for decade in (-10..=0).rev() {
        let (mut ours, mut arvo) = (Vec::new(), Vec::new());
        let (mut ours_out, mut arvo_out, mut total) = (0u64, 0u64, 0u64);
        while ours.len() < 200 {
            // A polygon of about the target solid angle, at least three times its own
            // size away; kept only when its exact Ω falls into the decade.
            let target = 10f64.powf(decade as f64 + rng.uniform() as f64);
            let size = (2.0 * target).sqrt().min(0.4) as f32;
            let distance = (size as f64 / (2.0 * target).sqrt()) as f32;
            let dir = Vec3::new(
                rng.uniform() - 0.5,
                rng.uniform() - 0.5,
                0.2 + rng.uniform(),
            )
            .normalize();
            let v = random_polygon(&mut rng, 3 + ours.len() % 2, dir * distance, size);
            let d: Vec<D3> = v
                .iter()
                .map(|p| [p.x as f64, p.y as f64, p.z as f64])
                .collect();
            let exact = reference::polygon_solid_angle(&d);
            if exact.log10().floor() as i32 != decade {
                continue;
            }
            let (Some(a), Some(b)) = (SolidAnglePolygon::new(&v), ArvoPolygon::new(&v)) else {
                continue;
            };
            ours.push((a.solid_angle() as f64 - exact).abs() / exact);
            arvo.push((b.solid_angle() as f64 - exact).abs() / exact);
            for _ in 0..400 {
                let u = [rng.uniform(), rng.uniform()];
                let to_d3 = |s: sphera::Sample| [s.dir.x as f64, s.dir.y as f64, s.dir.z as f64];
                total += 1;
                ours_out += !reference::polygon_contains(&d, to_d3(a.sample(u))) as u64;
                arvo_out += !reference::polygon_contains(&d, to_d3(b.sample(u))) as u64;
            }
        }
        let stats = |v: &mut Vec<f64>| {
            v.sort_by(|a, b| a.partial_cmp(b).unwrap());
            (v[v.len() / 2], v[v.len() - 1])
        };
        let (om, ox) = stats(&mut ours);
        let (am, ax) = stats(&mut arvo);
        println!(
            "| 1e{decade} | {om:.1e} | {ox:.1e} | {am:.1e} | {ax:.1e} | {:.1e} | {:.1e} |",
            ours_out as f64 / total as f64,
            arvo_out as f64 / total as f64
        );
    }
    println!();
}

fn main() {
    // `cargo bench` passes `--bench`; `cargo test --benches` passes nothing else: both
    // run the full report, which takes a few seconds.
    println!("# sphera polygon sampling report\n");
    speed_table();
    accuracy_table();
}
