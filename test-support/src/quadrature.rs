//! Quadrature over polygons seen from the origin and over the sphere, in f64.
use crate::geometry::solid_angle_triangle_f64;
use crate::vector::{D3, add, cross, dot, normalize, scale, sub};
use glam::Vec3;

/// `∫_P f(ω) dω` over a convex planar polygon by the midpoint rule on the `n²` cells per
/// fan triangle of [`PolygonCells`] (each cell's exact solid angle times `f` at the
/// direction of its centroid): relative error `O(1/n²)` for smooth `f`. f64 throughout,
/// independent of every sampler.
pub fn integrate_over_polygon_f64(vertices: &[D3], n: usize, f: impl Fn(D3) -> f64) -> f64 {
    PolygonCells::new(vertices, n)
        .cells
        .iter()
        .map(|c| {
            let centroid = scale(add(add(c[0], c[1]), c[2]), 1.0 / 3.0);
            solid_angle_triangle_f64(c[0], c[1], c[2]) * f(normalize(centroid))
        })
        .sum()
}

/// The nodes and weights of the 16-point Gauss–Legendre rule on [-1, 1].
pub fn gauss_legendre_16() -> ([f64; 16], [f64; 16]) {
    const X: [f64; 8] = [
        0.095_012_509_837_637_44,
        0.281_603_550_779_258_9,
        0.458_016_777_657_227_4,
        0.617_876_244_402_643_8,
        0.755_404_408_355_003,
        0.865_631_202_387_831_8,
        0.944_575_023_073_232_6,
        0.989_400_934_991_649_9,
    ];
    const W: [f64; 8] = [
        0.189_450_610_455_068_5,
        0.182_603_415_044_923_6,
        0.169_156_519_395_002_5,
        0.149_595_988_816_576_7,
        0.124_628_971_255_533_9,
        0.095_158_511_682_492_8,
        0.062_253_523_938_647_9,
        0.027_152_459_411_754_1,
    ];
    let mut nodes = [0.0; 16];
    let mut weights = [0.0; 16];
    for i in 0..8 {
        (nodes[7 - i], weights[7 - i]) = (-X[i], W[i]);
        (nodes[8 + i], weights[8 + i]) = (X[i], W[i]);
    }
    (nodes, weights)
}

/// A convex planar polygon split into small planar triangles: each fan triangle of the
/// polygon is cut into `n²` triangles on a barycentric grid. Directions are located in
/// a cell by intersecting their ray with the polygon's plane (f64).
pub struct PolygonCells {
    pub cells: Vec<[D3; 3]>,
    vertices: Vec<D3>,
    n: usize,
    plane_normal: D3,
    plane_offset: f64,
}

impl PolygonCells {
    pub fn new(vertices: &[D3], n: usize) -> PolygonCells {
        let mut plane_normal = [0.0; 3];
        for i in 1..vertices.len() - 1 {
            plane_normal = add(
                plane_normal,
                cross(
                    sub(vertices[i], vertices[0]),
                    sub(vertices[i + 1], vertices[0]),
                ),
            );
        }
        let plane_normal = normalize(plane_normal);
        let plane_offset = dot(plane_normal, vertices[0]);
        let mut cells = Vec::new();
        for t in 0..vertices.len() - 2 {
            let (a, b, c) = (vertices[0], vertices[t + 1], vertices[t + 2]);
            let point = |i: usize, j: usize| {
                add(
                    a,
                    add(
                        scale(sub(b, a), i as f64 / n as f64),
                        scale(sub(c, a), j as f64 / n as f64),
                    ),
                )
            };
            for i in 0..n {
                for j in 0..n - i {
                    cells.push([point(i, j), point(i + 1, j), point(i, j + 1)]);
                    if i + j + 2 <= n {
                        cells.push([point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)]);
                    }
                }
            }
        }
        PolygonCells {
            cells,
            vertices: vertices.to_vec(),
            n,
            plane_normal,
            plane_offset,
        }
    }

    /// The cell hit by the ray along `dir`, or None when the ray misses the polygon.
    pub fn locate(&self, dir: D3) -> Option<usize> {
        let denominator = dot(self.plane_normal, dir);
        let t = self.plane_offset / denominator;
        if !(t > 0.0) || !t.is_finite() {
            return None;
        }
        let q = scale(dir, t);
        let mut base = 0;
        let per_triangle = self.n * self.n;
        for tri in 0..self.vertices.len() - 2 {
            let (a, b, c) = (
                self.vertices[0],
                self.vertices[tri + 1],
                self.vertices[tri + 2],
            );
            let total = dot(cross(sub(b, a), sub(c, a)), self.plane_normal);
            let beta = dot(cross(sub(q, a), sub(c, a)), self.plane_normal) / total;
            let gamma = dot(cross(sub(b, a), sub(q, a)), self.plane_normal) / total;
            if beta >= 0.0 && gamma >= 0.0 && beta + gamma <= 1.0 {
                let n = self.n as f64;
                let i = ((beta * n).floor() as usize).min(self.n - 1);
                let j = ((gamma * n).floor() as usize).min(self.n - 1 - i);
                let upper =
                    (beta * n - i as f64) + (gamma * n - j as f64) > 1.0 && i + j + 2 <= self.n;
                // Index of cell (i, j): cells of rows before i, then 2 per j.
                let mut index = 0;
                for row in 0..i {
                    index += 2 * (self.n - row) - 1;
                }
                index += 2 * j + upper as usize;
                return Some(base + index);
            }
            base += per_triangle;
        }
        None
    }
}

/// `∫ f(ω) dω` over the sphere by the midpoint rule on `n × n` cells of `(z, φ)`, in
/// which `dω = dz dφ` (exact for functions of `z` alone; `f` sees `f32` directions).
pub fn integrate_over_sphere(n: usize, f: impl Fn(Vec3) -> f64) -> f64 {
    let mut sum = 0.0f64;
    for i in 0..n {
        let z = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
        let r = (1.0 - z * z).sqrt();
        for j in 0..n {
            let phi = (j as f64 + 0.5) * 2.0 * core::f64::consts::PI / n as f64;
            sum += f(Vec3::new(
                (r * phi.cos()) as f32,
                (r * phi.sin()) as f32,
                z as f32,
            ));
        }
    }
    sum * (2.0 / n as f64) * (2.0 * core::f64::consts::PI / n as f64)
}

/// Gauss–Legendre nodes and weights of order `m` on [0, 1] (Newton's iteration on the
/// three-term recurrence of the Legendre polynomials).
pub fn gauss_legendre(m: usize) -> Vec<(f64, f64)> {
    (0..m)
        .map(|i| {
            let mut x = libm::cos(core::f64::consts::PI * (i as f64 + 0.75) / (m as f64 + 0.5));
            let mut derivative = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=m {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                derivative = m as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / derivative;
                x -= dx;
                if dx.abs() < 1e-15 {
                    break;
                }
            }
            (
                0.5 * (1.0 + x),
                1.0 / ((1.0 - x * x) * derivative * derivative),
            )
        })
        .collect()
}

/// The bounds of the panels covering [l, r]: halves, each refined geometrically (`levels` halvings)
/// towards its end if that end is flagged.
pub fn graded_bounds(
    l: f64,
    r: f64,
    grade_left: bool,
    grade_right: bool,
    levels: usize,
) -> Vec<f64> {
    let mid = 0.5 * (l + r);
    let mut bounds = vec![l];
    if grade_left {
        bounds.extend(
            (1..=levels)
                .rev()
                .map(|k| l + (mid - l) * libm::ldexp(1.0, -(k as i32))),
        );
    }
    bounds.push(mid);
    if grade_right {
        bounds.extend((1..=levels).map(|k| r - (r - mid) * libm::ldexp(1.0, -(k as i32))));
    }
    bounds.push(r);
    bounds
}

/// [`graded_bounds`] as `(left, right)` panels.
pub fn graded_panels(
    l: f64,
    r: f64,
    grade_left: bool,
    grade_right: bool,
    levels: usize,
) -> Vec<(f64, f64)> {
    graded_bounds(l, r, grade_left, grade_right, levels)
        .windows(2)
        .map(|w| (w[0], w[1]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Rng;

    #[test]
    fn polygon_cells_cover_the_polygon_and_their_solid_angles_sum_up() {
        let quad = [
            [-1.0, -1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
        ];
        let cells = PolygonCells::new(&quad, 7);
        let total: f64 = cells
            .cells
            .iter()
            .map(|c| solid_angle_triangle_f64(c[0], c[1], c[2]))
            .sum();
        assert!((total - 2.0 * core::f64::consts::PI / 3.0).abs() < 1e-12);
        let mut rng = Rng::new(9);
        for _ in 0..10_000 {
            let (x, y) = (2.0 * rng.uniform() - 1.0, 2.0 * rng.uniform() - 1.0);
            let cell = cells.locate([x, y, 1.0]).expect("inside");
            let c = cells.cells[cell];
            // The point must be inside the located cell.
            let p = [x, y, 1.0];
            let n = [0.0, 0.0, 1.0];
            for k in 0..3 {
                let e = sub(c[(k + 1) % 3], c[k]);
                let s = dot(cross(e, sub(p, c[k])), n)
                    * dot(cross(sub(c[1], c[0]), sub(c[2], c[0])), n);
                assert!(s >= -1e-12, "point {p:?} not in cell {c:?}");
            }
        }
        assert!(cells.locate([3.0, 0.0, 1.0]).is_none());
        assert!(cells.locate([0.0, 0.0, -1.0]).is_none());
    }
}
