//! Profiling harness: prepares central polygons in a loop (`perf record`).
use sphera::Vec3;
use sphera::polygon::ProjectedPolygon;
use sphera_test_support::Rng;
use std::hint::black_box;

fn main() {
    let mut rng = Rng(1);
    let mut next = || rng.uniform_f32();
    let polygons: Vec<Vec<Vec3>> = (0..256)
        .map(|_| {
            let c = Vec3::new(0.2 * next() - 0.1, 0.2 * next() - 0.1, 1.0);
            (0..4)
                .map(|i| {
                    let a = i as f32 * 1.57 + 0.3 * next();
                    c + Vec3::new(0.5 * a.cos(), 0.5 * a.sin(), 0.1 * a.sin())
                })
                .collect()
        })
        .collect();
    let mut sum = 0.0f32;
    for _ in 0..4000 {
        for v in &polygons {
            if let Some(p) = ProjectedPolygon::new(black_box(v)) {
                sum += p.projected_solid_angle();
            }
        }
    }
    println!("{}", black_box(sum));
}
