//! f64 reference geometry for the reports, written independently of the f32 core.

/// A 3-vector in f64.
pub type D3 = [f64; 3];

pub fn sub(a: D3, b: D3) -> D3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
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

/// Solid angle of a planar triangle seen from the origin (van Oosterom and Strackee),
/// with the determinant over edge vectors.
pub fn triangle_solid_angle(a: D3, b: D3, c: D3) -> f64 {
    let det = dot(a, cross(sub(b, a), sub(c, a))).abs();
    let (la, lb, lc) = (norm(a), norm(b), norm(c));
    2.0 * det.atan2(la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la)
}

/// Solid angle of a convex planar polygon (fan).
pub fn polygon_solid_angle(v: &[D3]) -> f64 {
    (1..v.len() - 1)
        .map(|i| triangle_solid_angle(v[0], v[i], v[i + 1]))
        .sum()
}

/// Whether the ray along `dir` passes through the convex polygon `v` (exact sign tests
/// in f64 on the f32 inputs, so only rounding of the f32 direction itself matters).
pub fn polygon_contains(v: &[D3], dir: D3) -> bool {
    let n = v.len();
    let mut sign = 0.0f64;
    for i in 0..n {
        let s = dot(cross(v[i], sub(v[(i + 1) % n], v[i])), dir);
        if s != 0.0 {
            if sign == 0.0 {
                sign = s.signum();
            } else if s.signum() != sign {
                return false;
            }
        }
    }
    // A ray pointing away from the polygon also passes every sign test: it must meet
    // the polygon's plane in front of the origin.
    let normal = cross(sub(v[1], v[0]), sub(v[2], v[0]));
    dot(normal, v[0]) / dot(normal, dir) > 0.0
}
