//! Issue 16 (6): a prepared value corrupted by a renderer bug (outside the contract, but
//! it happens) must not hang or abort the renderer. Every 32-bit word of every prepared
//! value of the polygon and sphere families is overwritten in turn with each of a set of
//! hostile words (NaN, ±∞, huge and negative counts, the largest finite floats), and
//! every reader of the value (samples at several `u`, pdfs of several directions, the
//! getters) runs on it. A panic is what `abort()` is across the C ABI; a reader that
//! does not return within the watchdog's limit loops without bound. Wrong results are
//! allowed: only panics and hangs fail.
//!
//! Readers run on the Rust API (what the `sphera_*` functions call), in debug builds,
//! where integer overflow panics: a wrapped count that release builds would turn into a
//! 4-billion-iteration loop or an out-of-bounds index shows here as a panic.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use sphera::Vec3;
use sphera::brdf::Ltc;
use sphera::polygon::LtcPolygon;
use sphera::polygon::baselines::{
    ArvoPolygon, ArvoProjectedPolygon, HartBilinearPolygon, HartBiquadraticPolygon, TurkPolygon,
};
use sphera::polygon::light::{Material, MisHeuristic, PolygonLight};
use sphera::polygon::{ClippedSolidAnglePolygon, ProjectedPolygon, SolidAnglePolygon};
use sphera::sphere::{
    Cap, CapUnion, SolidAngleSphere, SphereLightSampler, SphereLightShading, Sptd, SptdInCap,
};

/// The words written over each word of a prepared value in turn.
const HOSTILE_WORDS: [u32; 12] = [
    0x7fc0_0000, // NaN
    0xffc0_0001, // a negative NaN with payload
    0x7f80_0000, // +∞
    0xff80_0000, // -∞
    0x7f7f_ffff, // f32::MAX
    0xff7f_ffff, // -f32::MAX
    0xffff_ffff, // u32::MAX (a NaN as f32)
    0x8000_0000, // -0.0, or 2³¹ as a count
    0x7fff_ffff, // i32::MAX (a NaN as f32)
    9,           // one past the largest vertex count
    1000,        // a large count (a denormal as f32)
    0x3f80_0000, // 1.0, or a count of over a billion
];

/// How long one reader call may take before it counts as a hang.
const WATCHDOG: Duration = Duration::from_secs(10);

fn polygon() -> [Vec3; 5] {
    [
        Vec3::new(-0.6, -0.4, 1.0),
        Vec3::new(0.5, -0.5, 1.2),
        Vec3::new(0.7, 0.3, 0.9),
        Vec3::new(0.0, 0.8, 1.1),
        Vec3::new(-0.7, 0.4, 0.95),
    ]
}

/// A polygon beside the zenith (the decentral case of projected sampling).
fn decentral() -> [Vec3; 4] {
    [
        Vec3::new(0.8, -0.3, 0.6),
        Vec3::new(1.4, -0.2, 0.5),
        Vec3::new(1.5, 0.4, 0.7),
        Vec3::new(0.9, 0.5, 0.8),
    ]
}

/// A polygon crossing the horizon.
fn straddling() -> [Vec3; 4] {
    [
        Vec3::new(-0.5, 1.0, -0.3),
        Vec3::new(0.5, 1.0, -0.3),
        Vec3::new(0.5, 1.2, 0.6),
        Vec3::new(-0.5, 1.2, 0.6),
    ]
}

const US: [[f32; 2]; 5] = [
    [0.0, 0.0],
    [0.5, 0.5],
    [0.999_999_9, 0.3],
    [0.25, 0.999_999_9],
    [0.7, 0.1],
];

fn directions() -> [Vec3; 5] {
    [
        Vec3::Z,
        Vec3::new(0.1, 0.05, 1.0).normalize(),
        Vec3::new(0.8, 0.0, 0.6),
        -Vec3::Z,
        Vec3::new(0.6, 0.1, 0.2).normalize(),
    ]
}

/// The name of the threads that run readers on corrupted values, whose panics are
/// expected and counted rather than printed.
const READER: &str = "corrupted-value-reader";

/// Where the last reader panic happened, for the failure message.
static LAST_PANIC: std::sync::Mutex<String> = std::sync::Mutex::new(String::new());

/// Installs (once) a panic hook that stays silent for the reader threads and prints as
/// usual for every other thread (the tests' own assertions).
fn silence_reader_panics() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if std::thread::current().name() != Some(READER) {
                default(info);
            } else if let Some(location) = info.location() {
                *LAST_PANIC.lock().unwrap() = location.to_string();
            }
        }));
    });
}

/// Overwrites every word of `valid` with every hostile word in turn and runs `read` on
/// the result; fails on a panic or on a call that outlives the watchdog.
fn corrupt_every_word<T: Copy + Send + 'static>(
    name: &'static str,
    valid: T,
    read: impl Fn(&T) -> f32 + Send + 'static,
) {
    assert_eq!(size_of::<T>() % 4, 0, "{name}: not a whole number of words");
    let words = size_of::<T>() / 4;
    // The position being read: word << 8 | hostile index, and a count of finished calls.
    let position = Arc::new(AtomicU64::new(0));
    let finished = Arc::new(AtomicU64::new(0));
    let (p, f) = (position.clone(), finished.clone());
    let worker = std::thread::Builder::new()
        .name(READER.into())
        .spawn(move || {
            let mut failures = Vec::new();
            for word in 0..words {
                for (h, &hostile) in HOSTILE_WORDS.iter().enumerate() {
                    p.store(((word as u64) << 8) | h as u64, Ordering::SeqCst);
                    let mut value = valid;
                    // SAFETY: `T` is a `repr(C)` struct of `f32` and `u32` fields (checked by
                    // the header's size assertions), so every 4-byte word is a field and any
                    // bit pattern is a valid value of it.
                    unsafe {
                        let base = (&mut value as *mut T).cast::<u32>();
                        base.add(word).write_unaligned(hostile);
                    }
                    let result = catch_unwind(AssertUnwindSafe(|| read(&value)));
                    if result.is_err() {
                        let at = LAST_PANIC.lock().unwrap().clone();
                        failures.push(format!("word {word} = {hostile:#010x} at {at}"));
                    }
                    f.fetch_add(1, Ordering::SeqCst);
                }
            }
            failures
        })
        .unwrap();
    let total = (words * HOSTILE_WORDS.len()) as u64;
    let mut last = (0, Instant::now());
    while !worker.is_finished() {
        std::thread::sleep(Duration::from_millis(20));
        let done = finished.load(Ordering::SeqCst);
        if done != last.0 {
            last = (done, Instant::now());
        } else if last.1.elapsed() > WATCHDOG {
            let at = position.load(Ordering::SeqCst);
            panic!(
                "{name}: a reader has not returned for {WATCHDOG:?} with word {} = {:#010x} \
                 (a loop without bound); {done} of {total} calls finished",
                at >> 8,
                HOSTILE_WORDS[(at & 0xff) as usize]
            );
        }
    }
    let failures = worker.join().unwrap();
    if !failures.is_empty() {
        FAILURES.with_borrow_mut(|f| {
            f.push(format!(
                "{name}: {} of {total} corrupted values panicked (abort across the C ABI): {}",
                failures.len(),
                failures.join(", ")
            ))
        });
    }
}

thread_local! {
    /// The failures of every type of this test's thread, reported together at its end.
    static FAILURES: std::cell::RefCell<Vec<String>> = const { std::cell::RefCell::new(Vec::new()) };
}

fn assert_no_failures() {
    let failures = FAILURES.take();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Sums what the readers return, so that nothing is optimised away.
fn polygon_readers<T>(
    sample: impl Fn(&T, [f32; 2]) -> (Vec3, f32),
    pdf: impl Fn(&T, Vec3) -> f32,
) -> impl Fn(&T) -> f32 {
    move |p: &T| {
        let mut sum = 0.0f32;
        for u in US {
            let (dir, density) = sample(p, u);
            sum += density + dir.x + pdf(p, dir);
        }
        for d in directions() {
            sum += pdf(p, d);
        }
        std::hint::black_box(sum)
    }
}

macro_rules! polygon_case {
    ($name:literal, $ty:ty, $value:expr, $extra:expr) => {{
        let value: $ty = $value;
        let read = polygon_readers(
            |p: &$ty, u| {
                let s = p.sample(u);
                (s.dir, s.pdf)
            },
            |p: &$ty, d| p.pdf(d),
        );
        let extra: fn(&$ty) -> f32 = $extra;
        corrupt_every_word($name, value, move |p| read(p) + extra(p));
    }};
}

#[test]
fn corrupted_polygon_values_neither_hang_nor_panic() {
    silence_reader_panics();
    for (shape, v) in [
        ("central", &polygon()[..]),
        ("decentral", &decentral()[..]),
        ("straddling", &straddling()[..]),
    ] {
        let _ = shape;
        polygon_case!(
            "SolidAnglePolygon",
            SolidAnglePolygon,
            SolidAnglePolygon::new(v).unwrap(),
            |p| {
                let inverse = p
                    .invert(Vec3::new(0.1, 0.05, 1.0))
                    .map_or(0.0, |u| u[0] + u[1]);
                p.solid_angle() + inverse
            }
        );
        polygon_case!(
            "ClippedSolidAnglePolygon",
            ClippedSolidAnglePolygon,
            ClippedSolidAnglePolygon::new(v).unwrap(),
            |p| p.solid_angle()
        );
        if let Some(turk) = TurkPolygon::new(v) {
            polygon_case!("TurkPolygon", TurkPolygon, turk, |_| 0.0);
        }
        if let Some(arvo) = ArvoPolygon::new(v) {
            polygon_case!("ArvoPolygon", ArvoPolygon, arvo, |_| 0.0);
        }
        if let Some(hart) = HartBilinearPolygon::new(v) {
            polygon_case!("HartBilinearPolygon", HartBilinearPolygon, hart, |_| 0.0);
        }
        if let Some(hart) = HartBiquadraticPolygon::new(v) {
            polygon_case!(
                "HartBiquadraticPolygon",
                HartBiquadraticPolygon,
                hart,
                |_| 0.0
            );
        }
        polygon_case!(
            "ProjectedPolygon",
            ProjectedPolygon,
            ProjectedPolygon::new(v).unwrap(),
            |p| p.projected_solid_angle()
                + p.sample_fast([0.3, 0.6]).pdf
                + p.sample_with_iterations([0.9, 0.2], 3).pdf
        );
        let tiny: Vec<Vec3> = v
            .iter()
            .map(|&x| Vec3::new(0.1, 0.2, 1.0) + 1e-4 * x)
            .collect();
        polygon_case!(
            "ProjectedPolygon (small)",
            ProjectedPolygon,
            ProjectedPolygon::new(&tiny).unwrap(),
            |p| p.projected_solid_angle()
        );
        if let Some(arvo) = ArvoProjectedPolygon::new(v) {
            polygon_case!("ArvoProjectedPolygon", ArvoProjectedPolygon, arvo, |_| 0.0);
        }
        let ltc = Ltc::from_ggx(Vec3::new(0.3, 0.0, 0.95).normalize(), 0.4).unwrap();
        polygon_case!(
            "LtcPolygon",
            LtcPolygon,
            LtcPolygon::new(&ltc, v).unwrap(),
            |p| p.integral()
        );
        let material = Material {
            diffuse: Vec3::splat(0.5),
            f0: Vec3::splat(0.04),
            roughness: 0.4,
        };
        let light = PolygonLight::new(
            v,
            Vec3::new(0.3, 0.0, 0.95),
            &material,
            MisHeuristic::WeightedBalance,
            1.0,
        )
        .unwrap();
        corrupt_every_word("PolygonLight", light, |p: &PolygonLight| {
            let mut sum = 0.0;
            for technique in [0, 1, 2, u32::MAX] {
                for u in US {
                    let s = p.sample(technique, u);
                    sum += s.pdf + s.dir.x + s.visible.x + p.pdfs(s.dir)[0];
                }
            }
            std::hint::black_box(sum)
        });
    }
    assert_no_failures();
}

#[test]
fn corrupted_sphere_values_neither_hang_nor_panic() {
    silence_reader_panics();
    let cap = Cap::from_sphere(Vec3::new(0.3, 0.2, 2.0), 0.5);
    let cap_readers = |c: &Cap| {
        let mut sum = c.solid_angle() + c.half_angle();
        for u in US {
            let s = c.sample_uniform(u);
            sum += s.pdf + s.dir.x + c.pdf(s.dir) + c.invert(s.dir).map_or(0.0, |u| u[0]);
        }
        std::hint::black_box(sum)
    };
    corrupt_every_word("Cap", cap, cap_readers);
    let sptd_readers = |s: &Sptd| {
        let mut sum = s.integral_over_cap(&Cap::from_sphere(Vec3::new(0.3, 0.2, 2.0), 0.5));
        for u in US {
            let x = s.sample(u);
            sum += x.pdf + x.dir.x + s.eval(x.dir);
        }
        std::hint::black_box(sum)
    };
    corrupt_every_word(
        "Sptd (uniform)",
        Sptd::uniform(Vec3::new(0.2, 0.1, 0.3)),
        sptd_readers,
    );
    let cosine = Sptd::clamped_cosine(
        Vec3::new(0.2, 0.1, 0.3),
        Vec3::new(0.1, 0.0, 1.0).normalize(),
    );
    corrupt_every_word("Sptd (clamped cosine)", cosine, sptd_readers);
    let mut in_caps = 0;
    // The last one's image crosses the cosine base's horizon: the clipped sampler
    // (issue 20, 2), whose inversion is a bounded Newton iteration.
    let mut clipped = 0;
    for sptd in [
        Sptd::uniform(Vec3::new(0.2, 0.1, 0.3)),
        Sptd::uniform(Vec3::new(-0.5, 0.3, 0.1)),
        cosine,
        Sptd::clamped_cosine(Vec3::new(0.2, 0.1, 0.3), Vec3::X),
    ] {
        let Some(in_cap) = SptdInCap::new(&sptd, &cap) else {
            continue;
        };
        in_caps += 1;
        clipped += in_cap.is_clipped() as usize;
        corrupt_every_word("SptdInCap", in_cap, |s: &SptdInCap| {
            let mut sum = 0.0;
            for u in US {
                let x = s.sample(u);
                sum += x.pdf + x.dir.x + s.pdf(x.dir) + s.invert(x.dir).map_or(0.0, |u| u[0]);
            }
            std::hint::black_box(sum)
        });
    }
    assert!(in_caps >= 2, "only {in_caps} SPTDs in a cap prepared");
    assert_eq!(clipped, 1, "the clipped sampler was not corrupted");
    let mut sphere = SolidAngleSphere::EMPTY;
    assert!(sphere.prepare(Vec3::new(0.3, 0.2, 2.0), 0.5));
    corrupt_every_word("SolidAngleSphere", sphere, |s: &SolidAngleSphere| {
        let mut sum = 0.0;
        for u in US {
            let x = s.sample(u);
            sum += x.pdf + x.dir.x + s.pdf(x.dir) + s.invert(x.dir).map_or(0.0, |u| u[0]);
        }
        std::hint::black_box(sum + s.solid_angle())
    });
    // The union of two lights' caps (issue 20, 1): its `B ∩ Ā` piece is a bounded
    // Newton iteration.
    let other = Cap::from_sphere(Vec3::new(0.8, 0.1, 2.0), 0.6);
    let union = CapUnion::new(&cap, &other).expect("the union prepares");
    corrupt_every_word("CapUnion", union, |s: &CapUnion| {
        let mut sum = s.solid_angle();
        for u in US {
            let x = s.sample_uniform(u);
            sum += x.pdf + x.dir.x + s.pdf(x.dir) + s.invert(x.dir).map_or(0.0, |u| u[0]);
        }
        std::hint::black_box(sum)
    });
    let wo = Vec3::new(0.4, 0.0, 0.9).normalize();
    let sampler = SphereLightSampler::new(Vec3::new(0.3, 0.2, 2.0), 0.5, wo, 0.4).unwrap();
    corrupt_every_word("SphereLightSampler", sampler, |s: &SphereLightSampler| {
        let mut sum = 0.0;
        for u in US {
            let x = s.sample(u);
            sum += x.pdf + x.dir.x + s.pdf(x.dir);
        }
        std::hint::black_box(sum)
    });
    let shading = SphereLightShading::new(wo, 0.4, Vec3::splat(0.04)).unwrap();
    corrupt_every_word(
        "SphereLightShading",
        shading,
        move |s: &SphereLightShading| {
            let light = Cap::from_sphere(Vec3::new(0.3, 0.2, 2.0), 0.5);
            let visibility = Cap::from_axis_cos(Vec3::new(0.0, 0.3, 1.0).normalize(), 0.8);
            std::hint::black_box(s.eval(&light).x + s.eval_occluded(&light, &visibility).x)
        },
    );
    assert_no_failures();
}

#[test]
fn corrupted_brdf_and_vsgl_values_neither_hang_nor_panic() {
    use sphera::brdf::GgxBrdf;
    use sphera::vsgl::accumulator::{Vpl, VsglAccumulator, VsglTexel};
    use sphera::vsgl::fis::{VsglPyramid, fis_select};
    silence_reader_panics();
    let wo = Vec3::new(0.4, 0.0, 0.9).normalize();
    let ltc = Ltc::from_ggx(wo, 0.4).unwrap();
    corrupt_every_word("Ltc", ltc, |l: &Ltc| {
        let mut sum = l.albedo() + l.fresnel() + l.inverse_determinant();
        for d in directions() {
            sum += l.density(d) + l.to_cosine_space(d).x + l.from_cosine_space(d).x;
        }
        std::hint::black_box(sum)
    });
    let ggx = GgxBrdf::new(0.4, Vec3::splat(0.04));
    corrupt_every_word("GgxBrdf", ggx, move |b: &GgxBrdf| {
        let mut sum = 0.0;
        for u in US {
            let s = b.sample(wo, u);
            sum += s.pdf + s.dir.x + b.pdf(wo, s.dir) + b.eval(wo, s.dir).x;
        }
        std::hint::black_box(sum)
    });
    let vpl = |k: u32| Vpl {
        position: Vec3::new(k as f32 * 0.3, 1.0 + (k % 3) as f32, 2.0),
        normal: Vec3::new(0.0, -1.0, 0.2),
        power: Vec3::splat(1.0 + k as f32),
        diffuse_reflectance: Vec3::splat(0.5),
        specular_reflectance: Vec3::splat(0.2),
        toward_incoming: Vec3::new(0.3, 0.5, 0.8).normalize(),
        roughness: 0.3,
    };
    let origin = Vec3::ZERO;
    let mut accumulator = VsglAccumulator::new(origin);
    for k in 0..5 {
        assert!(accumulator.add_vpl(&vpl(k)));
    }
    corrupt_every_word(
        "VsglAccumulator",
        accumulator,
        move |a: &VsglAccumulator| {
            let mut copy = *a;
            copy.add_vpl(&vpl(7));
            copy.merge(a);
            let v = copy.finish();
            std::hint::black_box(v.intensity(Vec3::Z).x + v.mean.x)
        },
    );
    // A 4 × 4 pyramid (21 texels), every word of every texel corrupted in turn.
    let mut texels = [VsglTexel::default(); 21];
    for (k, t) in texels.iter_mut().take(16).enumerate() {
        *t = VsglTexel::from_vpl(&vpl(k as u32), origin).unwrap();
    }
    assert!(VsglPyramid::fill_levels(&mut texels, 4));
    corrupt_every_word("VsglPyramid texels", texels, move |t: &[VsglTexel; 21]| {
        let Some(pyramid) = VsglPyramid::new(t, 4, origin) else {
            return 0.0;
        };
        let mut sum = pyramid.total_importance();
        for u in US {
            let v = fis_select(&pyramid, 4, 1.0, 8, u);
            sum += v.mean.x + v.intensity(Vec3::Z).x;
            sum += pyramid.sample_position(u).map_or(0.0, |(p, _)| p[0]);
        }
        std::hint::black_box(sum)
    });
    assert_no_failures();
}
