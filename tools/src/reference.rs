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

/// `∫_P f(ω) dω` over a convex planar polygon: each fan triangle cut into `n²` triangles
/// on a barycentric grid, each weighted by its exact solid angle and `f` at the
/// direction of its centroid (the midpoint rule; relative error `O(1/n²)` for smooth
/// `f`).
pub fn integrate_over_polygon(v: &[D3], n: usize, f: impl Fn(D3) -> f64) -> f64 {
    let mut total = 0.0;
    for k in 1..v.len() - 1 {
        let (a, b, c) = (v[0], v[k], v[k + 1]);
        let at = |i: usize, j: usize| {
            let (s, t) = (i as f64 / n as f64, j as f64 / n as f64);
            add(a, add(scale(sub(b, a), s), scale(sub(c, a), t)))
        };
        for i in 0..n {
            for j in 0..n - i {
                let mut cells = vec![[at(i, j), at(i + 1, j), at(i, j + 1)]];
                if i + j + 1 < n {
                    cells.push([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
                for [p, q, r] in cells {
                    let centroid = scale(add(add(p, q), r), 1.0 / 3.0);
                    let direction = scale(centroid, 1.0 / norm(centroid));
                    total += triangle_solid_angle(p, q, r) * f(direction);
                }
            }
        }
    }
    total
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

pub fn add(a: D3, b: D3) -> D3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub fn scale(a: D3, s: f64) -> D3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// The part of the convex polygon `p` on the non-negative side of the plane through the
/// origin with normal `n` (Sutherland–Hodgman, f64).
pub fn clip(p: &[D3], n: D3) -> Vec<D3> {
    let mut out = Vec::with_capacity(p.len() + 1);
    for i in 0..p.len() {
        let (a, b) = (p[i], p[(i + 1) % p.len()]);
        let (da, db) = (dot(a, n), dot(b, n));
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            out.push(add(a, scale(sub(b, a), t)));
        }
    }
    out
}

/// The part of the polygon above the horizon `z >= 0`.
pub fn clip_to_upper_hemisphere(p: &[D3]) -> Vec<D3> {
    clip(p, [0.0, 0.0, 1.0])
}

/// Projected solid angle `Φ = ∫ cos θ dω` of a convex polygon lying on or above the
/// horizon, by Lambert's formula `½ |Σ angle(p_i, p_j) n̂_ij · z|` with the edge plane's
/// normal `n̂_ij ∝ p_i × (p_j - p_i)` and the angle between the vertices taken from their
/// positions, `atan2(|p_i × p_j|, p_i · p_j)`, so that tiny polygons (whose terms cancel
/// by a factor of about their angular size) keep f64 precision. 0 for fewer than 3
/// vertices; degenerate (repeated) vertices contribute nothing.
pub fn projected_solid_angle(p: &[D3]) -> f64 {
    if p.len() < 3 {
        return 0.0;
    }
    let mut sum = 0.0;
    for i in 0..p.len() {
        let j = (i + 1) % p.len();
        let c = cross(p[i], sub(p[j], p[i]));
        let length = norm(c);
        if length > 0.0 {
            sum += length.atan2(dot(p[i], p[j])) * c[2] / length;
        }
    }
    (0.5 * sum).abs()
}

/// The azimuths `(clockwise-most, counter-clockwise-most)` of the vertices of a polygon
/// whose directions do not contain the zenith (its azimuths then span less than π),
/// with the second within π of the first. Vertices on the z axis are skipped.
pub fn azimuth_range(p: &[D3]) -> (f64, f64) {
    use std::f64::consts::{PI, TAU};
    let azimuths: Vec<f64> = p
        .iter()
        .filter(|q| q[0] != 0.0 || q[1] != 0.0)
        .map(|q| q[1].atan2(q[0]))
        .collect();
    let base = azimuths[0];
    let relative = |a: &f64| (a - base + PI).rem_euclid(TAU) - PI;
    let lo = azimuths.iter().map(relative).fold(f64::MAX, f64::min);
    let hi = azimuths.iter().map(relative).fold(f64::MIN, f64::max);
    (base + lo, base + hi)
}

/// Projected solid angle of the part of the polygon (on or above the horizon, not
/// containing the zenith) clockwise of azimuth `phi`: the polygon clipped by the plane
/// through the z axis at azimuth `phi`, keeping `det(e_phi, ω_xy) <= 0`.
pub fn projected_solid_angle_clockwise_of(p: &[D3], phi: f64) -> f64 {
    projected_solid_angle(&clip(p, [phi.sin(), -phi.cos(), 0.0]))
}

/// The azimuth in `[lo, hi]` at which the projected solid angle of the polygon clockwise
/// of it reaches `target`, by bisection (to f64 resolution) on
/// [`projected_solid_angle_clockwise_of`]; `(lo, hi)` is the polygon's
/// [`azimuth_range`].
pub fn azimuth_of_projected_solid_angle(p: &[D3], lo: f64, hi: f64, target: f64) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..64 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if projected_solid_angle_clockwise_of(p, mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// How far the ray along `dir` lies outside the convex polygon `v`: the largest sine of
/// the angle by which it violates an edge plane through the origin (0 when inside or on
/// the boundary; 1 for a ray pointing away from the polygon's plane).
pub fn angle_outside(v: &[D3], dir: D3) -> f64 {
    let n = v.len();
    let d = scale(dir, 1.0 / norm(dir));
    let centroid = v.iter().fold([0.0; 3], |s, p| add(s, *p));
    let mut worst = 0.0f64;
    for i in 0..n {
        let c = cross(v[i], sub(v[(i + 1) % n], v[i]));
        let length = norm(c);
        if length > 0.0 {
            let inward = if dot(c, centroid) >= 0.0 { 1.0 } else { -1.0 };
            worst = worst.max(-inward * dot(c, d) / length);
        }
    }
    let normal = cross(sub(v[1], v[0]), sub(v[2], v[0]));
    if dot(normal, v[0]) * dot(normal, d) <= 0.0 {
        return 1.0;
    }
    worst
}
