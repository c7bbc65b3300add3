//! f64 vectors for reference computations, written independently of the f32 core.
use crate::Rng;
use glam::Vec3;

/// A 3-vector in f64.
pub type D3 = [f64; 3];

/// An f32 vector in f64.
pub fn d3(v: Vec3) -> D3 {
    [v.x as f64, v.y as f64, v.z as f64]
}
pub fn sub(a: D3, b: D3) -> D3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn add(a: D3, b: D3) -> D3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub fn scale(a: D3, s: f64) -> D3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub fn dot(a: D3, b: D3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: D3, b: D3) -> D3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm(a: D3) -> f64 {
    dot(a, a).sqrt()
}
pub fn normalize(a: D3) -> D3 {
    scale(a, 1.0 / norm(a))
}

/// An f64 orthonormal frame around `a` (independent of the core's basis).
pub fn frame_f64(a: D3) -> (D3, D3) {
    let helper = if a[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let t = normalize(cross(helper, a));
    let b = cross(a, t);
    (t, b)
}

/// A uniformly distributed direction, in f64.
pub fn uniform_direction_f64(rng: &mut Rng) -> D3 {
    let z = 1.0 - 2.0 * rng.uniform();
    let phi = core::f64::consts::TAU * rng.uniform();
    let s = (1.0 - z * z).max(0.0).sqrt();
    [s * phi.cos(), s * phi.sin(), z]
}

/// An f64 direction as an f32 vector.
pub fn to_f32(v: D3) -> Vec3 {
    Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)
}
