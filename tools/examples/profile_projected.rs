//! Profiling harness: samples decentral polygons in a loop (`perf record`).
use sphera::Vec3;
use sphera::polygon::ProjectedPolygon;
use sphera_test_support::Rng;
use std::hint::black_box;

fn main() {
    let mut polygons = Vec::new();
    let mut rng = Rng(1);
    let mut next = || rng.uniform_f32();
    while polygons.len() < 256 {
        let c = Vec3::new(1.5 + next(), next() - 0.5, 0.8 + next());
        let v: Vec<Vec3> = (0..4)
            .map(|i| {
                let a = i as f32 * 1.57 + 0.3 * next();
                c + Vec3::new(0.4 * a.cos(), 0.4 * a.sin(), 0.2 * a.sin())
            })
            .collect();
        if let Some(p) = ProjectedPolygon::new(&v) {
            polygons.push(p);
        }
    }
    let mode = std::env::args().nth(1).unwrap_or_default();
    let mut sum = 0.0f32;
    for round in 0..4000 {
        for p in &polygons {
            let u = [next(), next()];
            let s = if mode == "fast" {
                p.sample_fast(u)
            } else {
                p.sample(u)
            };
            sum += s.pdf + round as f32 * 0.0;
        }
    }
    println!("{}", black_box(sum));
}
