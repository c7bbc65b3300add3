//! f64 spherical geometry of planar polygons seen from the origin: solid angles,
//! projected solid angles, clipping, containment. Written independently of the f32 core.
use crate::vector::{D3, add, cross, d3, dot, norm, scale, sub};
use glam::Vec3;

/// Solid angle of the planar triangle `a, b, c` (positions relative to the viewpoint)
/// by van Oosterom and Strackee (1983), in f64, with the determinant taken over edge
/// vectors so that tiny triangles keep their relative precision.
pub fn solid_angle_triangle_f64(a: D3, b: D3, c: D3) -> f64 {
    let det = dot(a, cross(sub(b, a), sub(c, a))).abs();
    let (la, lb, lc) = (norm(a), norm(b), norm(c));
    let denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    2.0 * det.atan2(denominator)
}

/// Solid angle of a convex planar polygon (fan of triangles), f64.
pub fn solid_angle_polygon_f64(vertices: &[D3]) -> f64 {
    (1..vertices.len() - 1)
        .map(|i| solid_angle_triangle_f64(vertices[0], vertices[i], vertices[i + 1]))
        .sum()
}

/// Projected solid angle (the cosine integral) of a polygon by Lambert's formula, in
/// f64: σ/2 Σ angle(v_i, v_(i+1)) (n̂_i · z) with n̂_i = normalize(v_i × v_(i+1)) and σ
/// the orientation of the polygon seen from the origin (so `Φ ≥ 0` for a convex polygon
/// on or above the horizon, whichever its winding). 0 for fewer than 3 vertices.
pub fn projected_solid_angle_polygon_f64(vertices: &[Vec3]) -> f64 {
    let p: Vec<D3> = vertices.iter().map(|&p| d3(p)).collect();
    projected_solid_angle_d3(&p)
}

/// [`projected_solid_angle_polygon_f64`] of f64 positions.
pub fn projected_solid_angle_d3(p: &[D3]) -> f64 {
    if p.len() < 3 {
        return 0.0;
    }
    // The orientation from the whole fan, so that a repeated vertex (a clipped
    // polygon's vertex on the horizon) does not hide it.
    let sigma = (1..p.len() - 1)
        .map(|i| dot(p[0], cross(sub(p[i], p[0]), sub(p[i + 1], p[0]))))
        .sum::<f64>()
        .signum();
    let mut sum = 0.0;
    for i in 0..p.len() {
        let j = (i + 1) % p.len();
        // The edge plane's normal from the exact positions (no cancellation).
        let c = cross(p[i], sub(p[j], p[i]));
        // The angle from the positions, so that tiny polygons (where Lambert's terms
        // cancel by a factor of up to 1e7) keep f64 precision: |p_i × p_j| = |c|.
        // Repeated vertices contribute nothing. `angle · c_z / |c|` with one division (the
        // tools' form; the tests' `normalize(c)[2]` rounded twice, which the cancellation
        // amplifies into the report's printed digits).
        let length = norm(c);
        if length > 0.0 {
            sum += length.atan2(dot(p[i], p[j])) * c[2] / length;
        }
    }
    0.5 * sigma * sum
}

/// The polygon clipped to `z >= 0` by Sutherland–Hodgman, in f64 (new vertices lie
/// exactly on `z = 0`).
pub fn clip_to_upper_hemisphere_f64(p: &[D3]) -> Vec<D3> {
    let mut out = Vec::new();
    for i in 0..p.len() {
        let (a, b) = (p[i], p[(i + 1) % p.len()]);
        if a[2] >= 0.0 {
            out.push(a);
        }
        if (a[2] >= 0.0) != (b[2] >= 0.0) {
            let t = a[2] / (a[2] - b[2]);
            let mut q = add(a, scale(sub(b, a), t));
            q[2] = 0.0;
            out.push(q);
        }
    }
    out
}

/// The part of the convex polygon `p` on the non-negative side of the plane through the
/// origin with normal `n` (Sutherland–Hodgman, f64).
pub fn clip_by_plane(p: &[D3], n: D3) -> Vec<D3> {
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
    projected_solid_angle_d3(&clip_by_plane(p, [phi.sin(), -phi.cos(), 0.0]))
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

/// The part of the f32 polygon above the horizon, by Sutherland–Hodgman in f64 with the
/// strict rule `z > 0` (also for 8 vertices, where the result may have 9), the new
/// vertices rounded to f32 and exactly on z = 0: the polygon an f32 sampler sees.
pub fn clip_to_upper_hemisphere_f32(vertices: &[Vec3]) -> Vec<Vec3> {
    let n = vertices.len();
    let mut out = Vec::new();
    for i in 0..n {
        let (a, b) = (d3(vertices[i]), d3(vertices[(i + 1) % n]));
        if a[2] > 0.0 {
            out.push(vertices[i]);
        }
        if (a[2] > 0.0) != (b[2] > 0.0) {
            let t = a[2] / (a[2] - b[2]);
            let p = add(a, scale(sub(b, a), t));
            out.push(Vec3::new(p[0] as f32, p[1] as f32, 0.0));
        }
    }
    out
}

/// `1 − cos θ` of the cap that a sphere of `radius` centred at `center` subtends, in f64:
/// `sin²θ / (1 + cos θ)` with `sin θ = radius / |center|`; 2 (the whole sphere) from inside.
pub fn sphere_cap_one_minus_cos_f64(center: D3, radius: f64) -> f64 {
    let d = norm(center);
    if d <= radius {
        return 2.0;
    }
    let s2 = (radius / d) * (radius / d);
    s2 / (1.0 + (1.0 - s2).sqrt())
}
