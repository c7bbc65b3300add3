//! sphera's speed-versus-error report for polygon sampling, printed as markdown tables by
//! one run (a few seconds after the build):
//!
//! 1. **Speed**: ns per (prepare + 1 sample) and per sample from a prepared polygon for
//!    every technique (Turk's area sampling, solid angle sampling, clipped solid angle
//!    sampling, Arvo 1995, the bilinear and biquadratic warps of Hart et al. 2020,
//!    projected solid angle sampling and its biased variant), median of repeated runs
//!    over many random polygons, as ratios to Turk's area sampling and to solid angle
//!    sampling measured in the same run. Polygon sets: central (the zenith inside) and
//!    decentral (beside the zenith), both fully above the horizon, with 4 and 7
//!    vertices, and the mixed triangles of earlier reports; a note gives the paper's
//!    ratios (Table A.2 and Peters' shader code on a CPU) for comparison.
//! 2. **Error per iteration count** of projected solid angle sampling (decentral
//!    polygons larger than its small-polygon switch, 0 to 3 refinement iterations, and
//!    the biased variant): forward error (azimuth in radians) against an f64 inversion
//!    of the same azimuthal CDF (bisection on the f64 projected solid angle, by Lambert's
//!    formula, of the polygon clipped to the wedge up to an azimuth), and backward error
//!    (that f64 projected solid angle at the sample's azimuth minus the target `u0 Φ`,
//!    absolute and relative to Φ); median, 99th percentile and maximum.
//! 3. **Accuracy per decade of solid angle** (1e-10 sr to 10 sr, and near-hemisphere
//!    polygons): solid angle sampling against Arvo 1995 (random triangles and quads, as
//!    in earlier reports), and projected against solid angle sampling on polygons
//!    around the zenith, anywhere, and near or across the horizon: relative error of Φ
//!    or Ω against f64, the fraction of samples outside the polygon by an f64 test of
//!    the f32 direction and how far outside, and the fraction of non-finite samples.
//! 4. **Variance of the unoccluded diffuse estimate** `(1/16) Σ ω_z / pdf` of Φ, over
//!    Φ², per technique on the same random configurations (some crossing the horizon),
//!    and the bias of its mean.
//!
//! The f64 references (Lambert's formula with angles from positions, clipping by
//! planes, bisection) are in `sphera_test_support`, independent of the core. Each
//! table lists its techniques one per line; a new sampler with `new`, `sample` (and
//! for the accuracy table `projected_solid_angle` or `solid_angle`) joins by one
//! `technique!` line and one line per table.
//!
//! Run with `cargo bench -p sphera-tools --bench report`; add
//! `RUSTFLAGS="-C target-cpu=native"` to measure with FMA and AVX2.
use sphera::polygon::baselines::{
    ArvoPolygon, ArvoProjectedPolygon, HartBilinearPolygon, HartBiquadraticPolygon, TurkPolygon,
};
use sphera::polygon::{ClippedSolidAnglePolygon, ProjectedPolygon, SolidAnglePolygon};
use sphera::{Sample, Vec3};
use sphera_test_support::Rng;
use sphera_test_support::{self as reference, D3};
use std::f32::consts::{PI, TAU};
use std::hint::black_box;
use std::time::Instant;

/// A random convex polygon with `n` vertices, irregularly spaced on an ellipse of the
/// given radius and a random aspect in `[min_aspect, 1]` around `center`, in the plane
/// with unit normal `normal`.
fn polygon_in_plane(
    rng: &mut Rng,
    n: usize,
    center: Vec3,
    normal: Vec3,
    radius: f32,
    min_aspect: f32,
) -> Vec<Vec3> {
    let (t, b) = sphera::math::orthonormal_basis(normal);
    let aspect = rng.range(min_aspect, 1.0);
    let offset = rng.uniform_f32() * TAU;
    (0..n)
        .map(|i| {
            let angle = offset + TAU * (i as f32 + 0.4 * rng.uniform_f32()) / n as f32;
            center + t * (radius * angle.cos()) + b * (radius * aspect * angle.sin())
        })
        .collect()
}

/// A random convex polygon with `n` vertices on an ellipse above the shading point, in
/// a plane tilted from the horizontal by up to about 30°.
fn random_polygon(rng: &mut Rng, n: usize, center: Vec3, radius: f32) -> Vec<Vec3> {
    let normal = Vec3::new(rng.uniform_f32() - 0.5, rng.uniform_f32() - 0.5, 1.0).normalize();
    polygon_in_plane(rng, n, center, normal, radius, 0.5)
}

/// The unit direction at elevation `elevation` above the horizon and azimuth `azimuth`.
fn direction(elevation: f32, azimuth: f32) -> Vec3 {
    Vec3::new(
        elevation.cos() * azimuth.cos(),
        elevation.cos() * azimuth.sin(),
        elevation.sin(),
    )
}

/// A plane normal around `dir`, tilted randomly by up to about `tilt` radians.
fn tilted(rng: &mut Rng, dir: Vec3, tilt: f32) -> Vec3 {
    (dir + rng.cube() * tilt).normalize()
}

fn to_d3(v: &[Vec3]) -> Vec<D3> {
    v.iter()
        .map(|p| [p.x as f64, p.y as f64, p.z as f64])
        .collect()
}

fn dir_d3(s: &Sample) -> D3 {
    [s.dir.x as f64, s.dir.y as f64, s.dir.z as f64]
}

const ZENITH: D3 = [0.0, 0.0, 1.0];

/// Whether the f32 polygon is still strictly convex in f64 (tiny polygons are a few
/// hundred ulps of their distance wide, and rounding their vertices can bend them).
fn is_convex(d: &[D3]) -> bool {
    let n = d.len();
    let mut sign = 0.0f64;
    for i in 0..n {
        let c = reference::cross(d[i], reference::sub(d[(i + 1) % n], d[i]));
        for (k, v) in d.iter().enumerate() {
            if k != i && k != (i + 1) % n {
                let s = reference::dot(c, *v).signum();
                if s == 0.0 || (sign != 0.0 && s != sign) {
                    return false;
                }
                sign = s;
            }
        }
    }
    true
}

/// Median, 99th percentile and maximum.
fn percentiles(v: &mut [f64]) -> (f64, f64, f64) {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let at = |q: f64| v[(q * (v.len() - 1) as f64).round() as usize];
    (at(0.5), at(0.99), at(1.0))
}

// ---------------------------------------------------------------------------------------
// Techniques

/// What a technique's `integral` returns, and so which f64 reference it is compared
/// with and where its samples must land.
#[derive(Clone, Copy, PartialEq)]
enum Integral {
    /// Solid angle Ω of the whole polygon (samples anywhere in it).
    SolidAngle,
    /// Projected solid angle Φ of the part above the horizon (samples there).
    Projected,
}

trait Technique: Copy {
    const NAME: &'static str;
    /// `Some` for the techniques of the accuracy tables.
    const INTEGRAL: Option<Integral> = None;
    fn prepare(vertices: &[Vec3]) -> Option<Self>;
    fn sample(&self, u: [f32; 2]) -> Sample;
    fn integral(&self) -> f32 {
        f32::NAN
    }
}

/// `technique!(Type, "name")`, or `technique!(Type, "name", method: Kind)` for a
/// technique whose `method()` returns the [`Integral`] `Kind`.
macro_rules! technique {
    ($t:ty, $name:expr $(, $method:ident: $kind:ident)?) => {
        impl Technique for $t {
            const NAME: &'static str = $name;
            $(
                const INTEGRAL: Option<Integral> = Some(Integral::$kind);
                #[inline(always)]
                fn integral(&self) -> f32 {
                    <$t>::$method(self)
                }
            )?
            #[inline(always)]
            fn prepare(vertices: &[Vec3]) -> Option<Self> {
                <$t>::new(vertices)
            }
            #[inline(always)]
            fn sample(&self, u: [f32; 2]) -> Sample {
                <$t>::sample(self, u)
            }
        }
    };
}
technique!(TurkPolygon, "Turk area sampling");
technique!(ArvoPolygon, "Arvo 1995 (solid angle)", solid_angle: SolidAngle);
technique!(SolidAnglePolygon, "solid angle (Alg. 5)", solid_angle: SolidAngle);
technique!(ClippedSolidAnglePolygon, "clipped solid angle");
technique!(HartBilinearPolygon, "Hart bilinear");
technique!(HartBiquadraticPolygon, "Hart biquadratic");
technique!(
    ProjectedPolygon,
    "projected (ours)",
    projected_solid_angle: Projected
);
technique!(
    ArvoProjectedPolygon,
    "Arvo projected",
    projected_solid_angle: Projected
);

/// The biased variant of projected solid angle sampling: fast `atan` in `prepare`, no
/// refinement iterations per sample.
#[derive(Clone, Copy)]
struct BiasedProjected(ProjectedPolygon);
impl Technique for BiasedProjected {
    const NAME: &'static str = "projected, biased";
    #[inline(always)]
    fn prepare(vertices: &[Vec3]) -> Option<Self> {
        ProjectedPolygon::new_fast_biased(vertices).map(Self)
    }
    #[inline(always)]
    fn sample(&self, u: [f32; 2]) -> Sample {
        self.0.sample_fast(u)
    }
}

// ---------------------------------------------------------------------------------------
// 1. Speed

const POLYGONS: usize = 1024;
const SAMPLES_PER_POLYGON: usize = 16;
const REPEATS: usize = 21;

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

type Measure = fn(&[Vec<Vec3>], &[[f32; 2]]) -> (f64, f64);
fn speed_of<T: Technique>() -> (&'static str, Measure) {
    (T::NAME, measure::<T>)
}

/// The polygon sets of the speed table.
#[derive(Clone, Copy, PartialEq)]
enum Placement {
    /// Around a random point of `[-0.5, 0.5]² × [0.5, 1.5]` (earlier reports).
    Mixed,
    /// The zenith inside, fully above the horizon.
    Central,
    /// Beside the zenith, fully above the horizon.
    Decentral,
}

fn speed_polygons(rng: &mut Rng, placement: Placement, n: usize) -> Vec<Vec<Vec3>> {
    let mut polygons = Vec::new();
    while polygons.len() < POLYGONS {
        let v = match placement {
            Placement::Mixed => {
                let c = Vec3::new(
                    rng.uniform_f32() - 0.5,
                    rng.uniform_f32() - 0.5,
                    0.5 + rng.uniform_f32(),
                );
                let radius = 0.3 + 0.5 * rng.uniform_f32();
                random_polygon(rng, n, c, radius)
            }
            Placement::Central => {
                let height = rng.range(0.5, 1.5);
                let c = Vec3::new(
                    rng.range(-0.2, 0.2) * height,
                    rng.range(-0.2, 0.2) * height,
                    height,
                );
                let radius = rng.range(0.5, 1.0) * height;
                random_polygon(rng, n, c, radius)
            }
            Placement::Decentral => {
                let dir = direction(rng.range(0.35, 1.25), rng.uniform_f32() * TAU);
                let distance = rng.range(0.5, 1.5);
                let normal = tilted(rng, dir, 0.5);
                let radius = rng.range(0.1, 0.5) * distance;
                polygon_in_plane(rng, n, dir * distance, normal, radius, 0.5)
            }
        };
        let d = to_d3(&v);
        let central = reference::polygon_contains(&d, ZENITH);
        let keep = v.iter().all(|p| p.z > 0.0)
            && match placement {
                Placement::Mixed => true,
                Placement::Central => central,
                Placement::Decentral => !central,
            };
        if keep {
            polygons.push(v);
        }
    }
    polygons
}

fn speed_table() {
    println!(
        "## Speed (ns, median of {REPEATS} runs over {POLYGONS} polygons; ratios to Turk and to solid angle sampling in the same run)\n"
    );
    println!(
        "Hardware FMA in this build: {}. Per sample: {SAMPLES_PER_POLYGON} samples per prepared polygon.\n",
        sphera::math::HAS_HARDWARE_FMA
    );
    // One line per technique.
    let techniques = [
        speed_of::<TurkPolygon>(),
        speed_of::<SolidAnglePolygon>(),
        speed_of::<ClippedSolidAnglePolygon>(),
        speed_of::<ArvoPolygon>(),
        speed_of::<HartBilinearPolygon>(),
        speed_of::<HartBiquadraticPolygon>(),
        speed_of::<ProjectedPolygon>(),
        speed_of::<BiasedProjected>(),
        speed_of::<ArvoProjectedPolygon>(),
    ];
    println!(
        "| polygons | technique | prepare + 1 sample | ×Turk | ×solid angle | per sample | ×Turk | ×solid angle |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    let mut rng = Rng(42);
    let us: Vec<[f32; 2]> = (0..POLYGONS * SAMPLES_PER_POLYGON)
        .map(|_| [rng.uniform_f32(), rng.uniform_f32()])
        .collect();
    let sets = [
        (Placement::Mixed, 3, "mixed"),
        (Placement::Central, 4, "central"),
        (Placement::Central, 7, "central"),
        (Placement::Decentral, 4, "decentral"),
        (Placement::Decentral, 7, "decentral"),
    ];
    for (placement, n, label) in sets {
        let polygons = speed_polygons(&mut rng, placement, n);
        let rows: Vec<(&str, (f64, f64))> = techniques
            .iter()
            .map(|(name, measure)| (*name, measure(&polygons, &us)))
            .collect();
        let find = |name: &str| rows.iter().find(|r| r.0 == name).unwrap().1;
        let turk = find(TurkPolygon::NAME);
        let solid = find(SolidAnglePolygon::NAME);
        for (name, (both, sample)) in &rows {
            println!(
                "| {label}, {n} | {name} | {both:.1} | {:.2}× | {:.2}× | {sample:.1} | {:.2}× | {:.2}× |",
                both / turk.0,
                both / solid.0,
                sample / turk.1,
                sample / solid.1
            );
        }
    }
    println!();
    println!(
        "For comparison (projected solid angle sampling as a multiple of solid angle sampling, central / decentral): Peters 2021, Table A.2 (GPU, 6 vertices, 128 lights): projected 1.8× / 4.8×, Arvo's projected 6.9× / 10.6×. Peters' shader code compiled as C++ for this CPU (-O3 -march=native, 4 vertices): 1.65× / 3.75× per (prepare + 1 sample), 1.1× / 7.8× per sample.\n"
    );
}

// ---------------------------------------------------------------------------------------
// 2. Error of projected solid angle sampling per iteration count

const ITERATION_POLYGONS: usize = 1000;
const ITERATION_SAMPLES: usize = 25;

fn iteration_error_table() {
    println!(
        "## Projected solid angle sampling: error per refinement iteration count (decentral polygons)\n"
    );
    println!(
        "{ITERATION_POLYGONS} random decentral polygons (3 to 7 vertices, some crossing the horizon, angular extent > 0.02 rad so that the ellipse path is used) × {ITERATION_SAMPLES} samples. Forward error: |azimuth of the sample − azimuth of the f64 solution| in rad, the f64 solution found by bisection on the f64 projected solid angle (Lambert's formula) of the clipped polygon cut at the azimuth, for the target u0 × Φ_f64. Backward error: |Φ_f64 up to the sample's azimuth − target| in sr, and over Φ_f64. Rows 0 to 3 use `sample_with_iterations` (initial guess from four quads, then that many iterations); `sample` uses one iteration, two in ill-conditioned sectors (outer ellipse area over 200 times the sector's area), shown in the row `sample`; the last row is the biased variant (`new_fast_biased` + `sample_fast`: no iterations and sector areas by a fast `atan`).\n"
    );
    let mut rng = Rng(2021);
    let mut polygons = Vec::new();
    while polygons.len() < ITERATION_POLYGONS {
        let n = 3 + polygons.len() % 5;
        let dir = direction(rng.range(-0.2, 1.3), rng.uniform_f32() * TAU);
        let normal = tilted(&mut rng, dir, 0.7);
        let radius = rng.range(0.03, 0.7);
        let v = polygon_in_plane(&mut rng, n, dir, normal, radius, 0.3);
        let d = to_d3(&v);
        if reference::polygon_contains(&d, ZENITH) {
            continue;
        }
        let clipped = reference::clip_to_upper_hemisphere_f64(&d);
        if clipped.len() < 3 {
            continue;
        }
        let unit: Vec<D3> = clipped
            .iter()
            .map(|p| reference::scale(*p, 1.0 / reference::norm(*p)))
            .collect();
        let extent = unit
            .iter()
            .flat_map(|a| unit.iter().map(|b| reference::norm(reference::sub(*a, *b))))
            .fold(0.0, f64::max);
        let Some(polygon) = ProjectedPolygon::new(&v) else {
            continue;
        };
        // The small-polygon path (also taken by slivers) ignores the iteration count.
        let probes = [[0.3, 0.5], [0.5, 0.5], [0.7, 0.5]];
        let iterated = probes
            .iter()
            .any(|&u| polygon.sample_with_iterations(u, 0) != polygon.sample_with_iterations(u, 2));
        let Some(fast) = ProjectedPolygon::new_fast_biased(&v) else {
            continue;
        };
        if extent > 0.02 && iterated {
            polygons.push((clipped, polygon, fast));
        }
    }
    // Per iteration count 0 to 3, for `sample` and for the biased variant: forward, backward
    // absolute, backward relative.
    let mut errors: [[Vec<f64>; 3]; 6] = Default::default();
    for (clipped, polygon, fast) in &polygons {
        let total = reference::projected_solid_angle_d3(clipped);
        let (lo, hi) = reference::azimuth_range(clipped);
        for _ in 0..ITERATION_SAMPLES {
            let u = [rng.uniform_f32(), rng.uniform_f32()];
            let target = u[0] as f64 * total;
            let expected = reference::azimuth_of_projected_solid_angle(clipped, lo, hi, target);
            for (iterations, e) in errors.iter_mut().enumerate() {
                let s = match iterations {
                    0..=3 => polygon.sample_with_iterations(u, iterations as u32),
                    4 => polygon.sample(u),
                    _ => fast.sample_fast(u),
                };
                let got = (s.dir.y as f64).atan2(s.dir.x as f64);
                let mut forward = (got - expected).rem_euclid(std::f64::consts::TAU);
                forward = forward.min(std::f64::consts::TAU - forward);
                // The azimuth of the sample, unwrapped next to the bracket.
                let unwrapped = expected
                    + (got - expected + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                    - std::f64::consts::PI;
                let backward = (reference::projected_solid_angle_clockwise_of(clipped, unwrapped)
                    - target)
                    .abs();
                e[0].push(forward);
                e[1].push(backward);
                e[2].push(backward / total);
            }
        }
    }
    println!(
        "| iterations | forward (rad): median | p99 | max | backward (sr): median | p99 | max | backward / Φ: median | p99 | max |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (iterations, e) in errors.iter_mut().enumerate() {
        let mut row = match iterations {
            0..=3 => format!("| {iterations} "),
            4 => "| `sample` (1, or 2 where ill-conditioned) ".to_string(),
            _ => "| 0, fast `atan` (the biased variant) ".to_string(),
        };
        for column in e.iter_mut() {
            let (median, p99, max) = percentiles(column);
            row += &format!("| {median:.1e} | {p99:.1e} | {max:.1e} ");
        }
        println!("{row}|");
    }
    println!();
}

// ---------------------------------------------------------------------------------------
// 3. Accuracy per decade

fn arvo_accuracy_table() {
    println!(
        "## Accuracy per decade of solid angle: solid angle sampling and Arvo 1995 (random triangles and quads)\n"
    );
    println!(
        "Relative error of Ω against f64 (median / max over 200 polygons), the fraction of 400 draws per polygon whose f64 ray misses the polygon (for Arvo, with the draws that give no sample: since issue 16 its samples outside are dropped), and the fraction of polygons whose preparation took the fast path throughout (`careful_paths() == 0`).\n"
    );
    println!(
        "| Ω | ours: median err | ours: max err | Arvo: median err | Arvo: max err | ours: outside | Arvo: outside | ours: fast path |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    let mut rng = Rng(7);
    for decade in (-10..=0).rev() {
        let (mut ours, mut arvo) = (Vec::new(), Vec::new());
        let (mut ours_out, mut arvo_out, mut total) = (0u64, 0u64, 0u64);
        let mut fast_path = 0usize;
        while ours.len() < 200 {
            // A polygon of about the target solid angle, at least three times its own
            // size away; kept only when its exact Ω falls into the decade.
            let target = 10f64.powf(decade as f64 + rng.uniform_f32() as f64);
            let size = (2.0 * target).sqrt().min(0.4) as f32;
            let distance = (size as f64 / (2.0 * target).sqrt()) as f32;
            let dir = Vec3::new(
                rng.uniform_f32() - 0.5,
                rng.uniform_f32() - 0.5,
                0.2 + rng.uniform_f32(),
            )
            .normalize();
            let v = random_polygon(&mut rng, 3 + ours.len() % 2, dir * distance, size);
            let d = to_d3(&v);
            let exact = reference::solid_angle_polygon_f64(&d);
            if exact.log10().floor() as i32 != decade {
                continue;
            }
            let (Some(a), Some(b)) = (SolidAnglePolygon::new(&v), ArvoPolygon::new(&v)) else {
                continue;
            };
            ours.push((a.solid_angle() as f64 - exact).abs() / exact);
            fast_path += (a.careful_paths() == 0) as usize;
            arvo.push((b.solid_angle() as f64 - exact).abs() / exact);
            for _ in 0..400 {
                let u = [rng.uniform_f32(), rng.uniform_f32()];
                total += 1;
                ours_out += !reference::polygon_contains(&d, dir_d3(&a.sample(u))) as u64;
                arvo_out += !reference::polygon_contains(&d, dir_d3(&b.sample(u))) as u64;
            }
        }
        let (om, _, ox) = percentiles(&mut ours);
        let (am, _, ax) = percentiles(&mut arvo);
        println!(
            "| 1e{decade} | {om:.1e} | {ox:.1e} | {am:.1e} | {ax:.1e} | {:.1e} | {:.1e} | {:.1}% |",
            ours_out as f64 / total as f64,
            arvo_out as f64 / total as f64,
            100.0 * fast_path as f64 / ours.len() as f64
        );
    }
    println!();
}

const DECADE_POLYGONS: usize = 400;
const DECADE_SAMPLES: usize = 400;

/// A polygon of the accuracy table with its f64 references.
struct Case {
    vertices: Vec<Vec3>,
    /// f64 vertices.
    d: Vec<D3>,
    /// Ω of the whole polygon.
    solid_angle: f64,
    /// Φ of the part above the horizon.
    projected: f64,
}

/// Per technique and row: relative errors of the integral, samples outside (and by how
/// much), samples with a non-finite direction or pdf (or pdf 0 above the horizon),
/// samples in all.
#[derive(Default)]
struct Accuracy {
    errors: Vec<f64>,
    outside: u64,
    /// The largest sine of the angle by which a sample misses the polygon.
    worst_outside: f64,
    non_finite: u64,
    samples: u64,
}

type AccuracyOf = fn(&[Case], &mut Rng) -> Option<Accuracy>;
fn accuracy_of<T: Technique>() -> (&'static str, AccuracyOf) {
    (T::NAME, measure_accuracy::<T>)
}

/// `None` when some polygon could not be prepared (reported as such in the table).
fn measure_accuracy<T: Technique>(cases: &[Case], rng: &mut Rng) -> Option<Accuracy> {
    let kind = T::INTEGRAL.expect("a technique of the accuracy table");
    let mut accuracy = Accuracy::default();
    for case in cases {
        let prepared = T::prepare(&case.vertices)?;
        let exact = match kind {
            Integral::SolidAngle => case.solid_angle,
            Integral::Projected => case.projected,
        };
        accuracy
            .errors
            .push((prepared.integral() as f64 - exact).abs() / exact);
        for _ in 0..DECADE_SAMPLES {
            let s = prepared.sample([rng.uniform_f32(), rng.uniform_f32()]);
            accuracy.samples += 1;
            if !s.dir.is_finite() || !s.pdf.is_finite() || (s.pdf <= 0.0 && s.dir.z > 0.0) {
                accuracy.non_finite += 1;
                continue;
            }
            let above = kind == Integral::SolidAngle || s.dir.z >= 0.0;
            if !(reference::polygon_contains(&case.d, dir_d3(&s)) && above) {
                accuracy.outside += 1;
                let below = if above { 0.0 } else { -s.dir.z as f64 };
                let angle = reference::angle_outside(&case.d, dir_d3(&s)).max(below);
                accuracy.worst_outside = accuracy.worst_outside.max(angle);
            }
        }
    }
    Some(accuracy)
}

/// `DECADE_POLYGONS` random polygons whose solid angle above the horizon lies in
/// `[10^decade, 10^(decade + 1))`: 3 to 7 vertices, random aspect and orientation, a
/// third each around the zenith (mostly central), anywhere above the horizon, and near
/// the horizon (crossing it for decades from 1e-3 up).
fn decade_cases(rng: &mut Rng, decade: i32) -> Vec<Case> {
    let mut cases = Vec::new();
    while cases.len() < DECADE_POLYGONS {
        let target = 10f32.powf(decade as f32 + rng.uniform_f32());
        // The angular radius of a cap of that solid angle.
        let angle = (2.0 * (target / (4.0 * PI)).sqrt().asin()).min(1.4);
        let dir = match cases.len() % 3 {
            0 => Vec3::new(
                rng.range(-0.5, 0.5) * angle,
                rng.range(-0.5, 0.5) * angle,
                1.0,
            )
            .normalize(),
            1 => direction(rng.range(0.1, 1.5), rng.uniform_f32() * TAU),
            _ if decade >= -3 => direction(rng.range(-1.0, 1.0) * angle, rng.uniform_f32() * TAU),
            _ => direction(rng.range(1.5, 4.0) * angle, rng.uniform_f32() * TAU),
        };
        let normal = tilted(rng, dir, 0.6);
        let v = polygon_in_plane(rng, 3 + cases.len() % 5, dir, normal, angle.tan(), 0.3);
        let d = to_d3(&v);
        if !is_convex(&d) {
            continue;
        }
        let clipped = reference::clip_to_upper_hemisphere_f64(&d);
        if clipped.len() < 3 {
            continue;
        }
        let solid_angle_above = reference::solid_angle_polygon_f64(&clipped);
        if solid_angle_above.log10().floor() as i32 != decade {
            continue;
        }
        cases.push(Case {
            vertices: v,
            solid_angle: reference::solid_angle_polygon_f64(&d),
            projected: reference::projected_solid_angle_d3(&clipped),
            d,
        });
    }
    cases
}

/// Central polygons at height 1 of radius 10 to 1000, tilted slightly (some crossing the
/// horizon), with Φ > 3.
fn near_hemisphere_cases(rng: &mut Rng) -> Vec<Case> {
    let mut cases = Vec::new();
    while cases.len() < DECADE_POLYGONS {
        let radius = 10f32.powf(rng.range(1.0, 3.0));
        let center = Vec3::new(rng.range(-0.5, 0.5), rng.range(-0.5, 0.5), 1.0);
        let normal = tilted(rng, Vec3::Z, 0.02);
        let v = polygon_in_plane(rng, 3 + cases.len() % 5, center, normal, radius, 0.7);
        let d = to_d3(&v);
        let clipped = reference::clip_to_upper_hemisphere_f64(&d);
        let projected = reference::projected_solid_angle_d3(&clipped);
        if projected > 3.0 {
            cases.push(Case {
                vertices: v,
                solid_angle: reference::solid_angle_polygon_f64(&d),
                projected,
                d,
            });
        }
    }
    cases
}

fn projected_accuracy_table() {
    // One line per technique.
    let techniques = [
        accuracy_of::<ProjectedPolygon>(),
        accuracy_of::<SolidAnglePolygon>(),
    ];
    println!("## Accuracy per decade of solid angle: projected and solid angle sampling\n");
    println!(
        "Per row {DECADE_POLYGONS} random polygons (3 to 7 vertices, random aspect and orientation; a third around the zenith, a third anywhere above the horizon, a third near the horizon, crossing it from 1e-3 sr up), classified by the f64 solid angle of their part above the horizon; {DECADE_SAMPLES} samples each. Error: relative error of Φ (projected, of the part above the horizon) or Ω (solid angle, whole polygon) against f64 (Lambert's formula, van Oosterom–Strackee), median and max. Outside: the f64 ray of the f32 direction misses the polygon (or, for projected, lies below the horizon); worst outside: the largest sine of the angle by which such a ray misses (for comparison, an f32 direction is rounded by about 6e-8). Non-finite: non-finite direction or pdf, or pdf ≤ 0 above the horizon. Small-polygon path: the share of polygons that projected preparation hands to the small-polygon sampler (`uses_small_polygon_sampler()`); central fast path: the share that it prepares through the central fast path (the zenith inside, nothing clipped, every edge outer; `takes_central_fast_path`); the rest take the general path of Algorithm 4.\n"
    );
    let mut header = String::from(
        "| Ω | central | crossing | projected: small-polygon path | projected: central fast path ",
    );
    let mut rule = String::from("|---|---:|---:|---:|---:");
    for (name, _) in &techniques {
        header +=
            &format!("| {name}: median err | max err | outside | worst outside | non-finite ");
        rule += "|---:|---:|---:|---:|---:";
    }
    println!("{header}|\n{rule}|");
    let mut rng = Rng(11);
    let mut rows: Vec<(String, Vec<Case>)> = (-10..=0)
        .rev()
        .map(|decade| (format!("1e{decade}"), decade_cases(&mut rng, decade)))
        .collect();
    rows.push((
        "Φ > 3 (near hemisphere)".to_string(),
        near_hemisphere_cases(&mut rng),
    ));
    for (label, cases) in rows {
        let central = cases
            .iter()
            .filter(|c| reference::polygon_contains(&c.d, ZENITH))
            .count();
        let crossing = cases
            .iter()
            .filter(|c| c.vertices.iter().any(|p| p.z < 0.0))
            .count();
        // The path that projected preparation takes (the rest use the sectors).
        let small = cases
            .iter()
            .filter(|c| {
                ProjectedPolygon::new(&c.vertices).is_some_and(|p| p.uses_small_polygon_sampler())
            })
            .count();
        let central_fast = cases
            .iter()
            .filter(|c| ProjectedPolygon::takes_central_fast_path(&c.vertices))
            .count();
        let share = |n: usize| format!("{:.1}%", 100.0 * n as f64 / cases.len().max(1) as f64);
        let (small, central_fast) = (share(small), share(central_fast));
        let mut row = format!("| {label} | {central} | {crossing} | {small} | {central_fast} ");
        for (_, accuracy) in &techniques {
            match accuracy(&cases, &mut rng) {
                Some(mut a) => {
                    let (median, _, max) = percentiles(&mut a.errors);
                    row += &format!(
                        "| {median:.1e} | {max:.1e} | {:.1e} | {:.1e} | {:.1e} ",
                        a.outside as f64 / a.samples as f64,
                        a.worst_outside,
                        a.non_finite as f64 / a.samples as f64
                    );
                }
                None => row += "| not prepared | | | | ",
            }
        }
        println!("{row}|");
    }
    println!();
}

// ---------------------------------------------------------------------------------------
// 4. Variance of the unoccluded diffuse estimate of a varying emission

const VARIANCE_CONFIGURATIONS: usize = 1000;
const VARIANCE_SAMPLES: usize = 1024;
const ESTIMATE_SAMPLES: usize = 16;

/// Per configuration: the variance of the mean of `ESTIMATE_SAMPLES` samples of
/// `f(ω) ω_z / pdf` over I² (from the variance of `VARIANCE_SAMPLES` single samples), and the
/// relative error of the mean of all samples; `None` where the polygon is not prepared.
type Variances = Vec<Option<(f64, f64)>>;
type VarianceOf = fn(&[(Vec<Vec3>, f64)], &[[f32; 2]]) -> Variances;
fn variance_of<T: Technique>() -> (&'static str, VarianceOf) {
    (T::NAME, measure_variance::<T>)
}

fn measure_variance<T: Technique>(
    configurations: &[(Vec<Vec3>, f64)],
    us: &[[f32; 2]],
) -> Variances {
    configurations
        .iter()
        .map(|(v, integral)| {
            let prepared = T::prepare(v)?;
            let (mut sum, mut sum2) = (0.0f64, 0.0f64);
            for &u in us {
                let s = prepared.sample(u);
                let x = if s.pdf > 0.0 {
                    let dir = [s.dir.x as f64, s.dir.y as f64, s.dir.z as f64];
                    emission(dir) * s.dir.z.max(0.0) as f64 / s.pdf as f64
                } else {
                    0.0
                };
                sum += x;
                sum2 += x * x;
            }
            let n = us.len() as f64;
            let mean = sum / n;
            let variance = (sum2 - sum * mean).max(0.0) / (n - 1.0);
            Some((
                variance / ESTIMATE_SAMPLES as f64 / (integral * integral),
                (mean - integral).abs() / integral,
            ))
        })
        .collect()
}

/// The emission of the variance table's light, `f(ω) = 1/4 + ω_x²`: not constant, so
/// that no technique's estimate is constant by the formula of its own pdf (with a
/// constant emission, `ω_z / pdf` is identically Φ for projected sampling: a zero
/// variance that measures nothing; issue 16, 9).
fn emission(w: D3) -> f64 {
    0.25 + w[0] * w[0]
}

fn variance_table() {
    // One line per technique.
    let techniques = [
        variance_of::<SolidAnglePolygon>(),
        variance_of::<ClippedSolidAnglePolygon>(),
        variance_of::<HartBilinearPolygon>(),
        variance_of::<HartBiquadraticPolygon>(),
        variance_of::<ProjectedPolygon>(),
        variance_of::<BiasedProjected>(),
        variance_of::<ArvoProjectedPolygon>(),
    ];
    let mut rng = Rng(16);
    let configurations: Vec<(Vec<Vec3>, f64)> = (0..VARIANCE_CONFIGURATIONS)
        .map(|i| {
            loop {
                let dir = direction(rng.range(-0.15, 1.5), rng.uniform_f32() * TAU);
                let normal = tilted(&mut rng, dir, 0.8);
                let radius = rng.range(0.1, 1.5);
                let v = polygon_in_plane(&mut rng, 3 + i % 5, dir, normal, radius, 0.3);
                let clipped = reference::clip_to_upper_hemisphere_f64(&to_d3(&v));
                let projected = reference::projected_solid_angle_d3(&clipped);
                if projected > 1e-6 {
                    let integral = reference::integrate_over_polygon_f64(&clipped, 32, |w| {
                        emission(w) * w[2].max(0.0)
                    });
                    break (v, integral);
                }
            }
        })
        .collect();
    let crossing = configurations
        .iter()
        .filter(|(v, _)| v.iter().any(|p| p.z < 0.0))
        .count();
    let us: Vec<[f32; 2]> = (0..VARIANCE_SAMPLES)
        .map(|_| [rng.uniform_f32(), rng.uniform_f32()])
        .collect();
    let results: Vec<(&str, Variances)> = techniques
        .iter()
        .map(|(name, variance)| (*name, variance(&configurations, &us)))
        .collect();
    // Only the configurations that every technique prepared.
    let used: Vec<usize> = (0..configurations.len())
        .filter(|&i| results.iter().all(|(_, r)| r[i].is_some()))
        .collect();
    println!(
        "## Variance of the unoccluded diffuse estimate of a varying emission ({ESTIMATE_SAMPLES} samples)\n"
    );
    println!(
        "Estimator of I = ∫ f(ω) cos θ dω with the emission f(ω) = 1/4 + ω_x²: (1/{ESTIMATE_SAMPLES}) Σ f(ω) max(ω_z, 0) / pdf. Relative variance Var / I² (I in f64 by the midpoint rule on 32² cells per fan triangle of the clipped polygon; mean over all configurations, over those fully above the horizon and those crossing it, median, max) per configuration from {VARIANCE_SAMPLES} samples, over {} random configurations (3 to 7 vertices, angular radius about 0.1 to 1 rad, random orientation and aspect, {crossing} crossing the horizon) that every technique prepared. Bias: |mean of all {VARIANCE_SAMPLES} samples − I| / I, a sampling error of about √(16 Var / I² / {VARIANCE_SAMPLES}) for every technique (the biased variant adds its own). The emission is not constant, so the estimate is not constant for any technique: with f = 1, projected sampling's f cos θ / pdf would be Φ by the formula of its pdf.\n",
        used.len()
    );
    println!(
        "| technique | mean Var / I² | above the horizon | crossing it | median | max | mean / solid angle's | mean bias | max bias |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    let is_crossing = |i: usize| configurations[i].0.iter().any(|p| p.z < 0.0);
    let mean_where = |r: &[Option<(f64, f64)>], crossing: Option<bool>| {
        let selected: Vec<f64> = used
            .iter()
            .filter(|&&i| crossing.is_none_or(|c| c == is_crossing(i)))
            .map(|&i| r[i].unwrap().0)
            .collect();
        selected.iter().sum::<f64>() / selected.len() as f64
    };
    let mean_of = |r: &[Option<(f64, f64)>]| mean_where(r, None);
    let reference_mean = mean_of(
        &results
            .iter()
            .find(|(name, _)| *name == SolidAnglePolygon::NAME)
            .unwrap()
            .1,
    );
    for (name, r) in &results {
        let mut variances: Vec<f64> = used.iter().map(|&i| r[i].unwrap().0).collect();
        let mut biases: Vec<f64> = used.iter().map(|&i| r[i].unwrap().1).collect();
        let mean = mean_of(r);
        let mean_bias = biases.iter().sum::<f64>() / biases.len() as f64;
        let (median, _, max) = percentiles(&mut variances);
        let (_, _, max_bias) = percentiles(&mut biases);
        println!(
            "| {name} | {mean:.2e} | {:.2e} | {:.2e} | {median:.2e} | {max:.2e} | {:.2e} | {mean_bias:.1e} | {max_bias:.1e} |",
            mean_where(r, Some(false)),
            mean_where(r, Some(true)),
            mean / reference_mean
        );
    }
    println!();
}

fn main() {
    // `cargo bench` passes `--bench`; `cargo test --benches` passes nothing else: both
    // run the full report.
    println!("# sphera polygon sampling report\n");
    let start = Instant::now();
    speed_table();
    iteration_error_table();
    arvo_accuracy_table();
    projected_accuracy_table();
    variance_table();
    println!("(report run time: {:.1} s)", start.elapsed().as_secs_f64());
}
