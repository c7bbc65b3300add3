//! Test-only helpers shared by every sampler's tests: a deterministic random number
//! generator, f64 reference geometry, and chi-square / estimator tests.
use glam::Vec3;

/// SplitMix64: small, fast, deterministic, good enough for tests.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1) with 53 bits.
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    /// Uniform in [0, 1) as f32 with 24 bits (never rounds up to 1).
    pub fn uniform_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 * (1.0 / (1u32 << 24) as f32)
    }
    /// 10^x with x uniform in [lo, hi).
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        10f64.powf(lo + (hi - lo) * self.uniform())
    }
    pub fn signed_log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let v = self.log_uniform(lo, hi);
        if self.next_u64() & 1 == 0 { v } else { -v }
    }
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
    pub fn unit_vector_f32(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(
                2.0 * self.uniform_f32() - 1.0,
                2.0 * self.uniform_f32() - 1.0,
                2.0 * self.uniform_f32() - 1.0,
            );
            let l = v.length_squared();
            if l > 1e-4 && l <= 1.0 {
                return v.normalize();
            }
        }
    }
}

/// f64 vectors for reference computations, written independently of the f32 core.
pub type D3 = [f64; 3];

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

/// f64 GGX (height-correlated Smith, Schlick), written independently of the core.
pub fn ggx_f64(wo: D3, wi: D3, roughness: f64, f0: f64) -> f64 {
    if wo[2] <= 0.0 || wi[2] <= 0.0 {
        return 0.0;
    }
    let alpha = (roughness * roughness).max(1e-4);
    let a2 = alpha * alpha;
    let h = normalize(add(wo, wi));
    let d = a2 / (core::f64::consts::PI * (h[2] * h[2] * (a2 - 1.0) + 1.0).powi(2));
    let lambda = |c: f64| {
        let t2 = (1.0 - c * c) / (c * c);
        0.5 * ((1.0 + a2 * t2).sqrt() - 1.0)
    };
    let g2 = 1.0 / (1.0 + lambda(wo[2]) + lambda(wi[2]));
    let f = f0 + (1.0 - f0) * (1.0 - dot(wo, h)).max(0.0).powi(5);
    f * d * g2 / (4.0 * wo[2] * wi[2])
}

/// The pivot transformation, Eq. 2 of Dupuy et al. 2017 literally, in f64.
pub fn pivot_transform_f64(r: D3, p: D3) -> D3 {
    let c = |a: D3, b: D3| -> D3 {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let rp = dot(r, p) - 1.0;
    let e: D3 = core::array::from_fn(|i| r[i] - p[i]);
    let rxp = c(r, p);
    let num0 = c(e, rxp);
    let den = rp * rp + dot(rxp, rxp);
    core::array::from_fn(|i| (rp * e[i] - num0[i]) / den)
}

/// The image `g(C)` of a cap `(axis, 1 − cos θ)` under the pivot, in f64 and
/// independently of `pivot_cap`: Eq. 6–7 on the two boundary points in the plane of the
/// axis and the pivot (Eq. 2 literally), which give the cap `(m, χ)` through them with
/// `χ ≤ π/2`; the image is that cap when it contains `g(axis)`, else its complement
/// `(−m, π − χ)`. Returns `(axis, 1 − cos ψ', 1 + cos ψ')`, each to f64 relative
/// precision (`1 − cos χ = sin²χ / (1 + cos χ)` from the chord).
pub fn pivot_image_f64(axis: D3, t: f64, pivot: D3) -> (D3, f64, f64) {
    // Normalised in f64 first: an f32 unit axis is 6e-8 off unit length, which is as
    // large as the pivot's component across an axis that points at it.
    let axis = normalize(axis);
    let across: D3 = core::array::from_fn(|i| pivot[i] - axis[i] * dot(pivot, axis));
    let u = if norm(across) > 1e-12 {
        normalize(across)
    } else {
        frame_f64(axis).0
    };
    let (c, s) = (1.0 - t, (t * (2.0 - t)).sqrt());
    let w1: D3 = core::array::from_fn(|i| axis[i] * c - u[i] * s);
    let w2: D3 = core::array::from_fn(|i| axis[i] * c + u[i] * s);
    let (g1, g2) = (
        pivot_transform_f64(w1, pivot),
        pivot_transform_f64(w2, pivot),
    );
    let gc = pivot_transform_f64(axis, pivot);
    let m = normalize(add(g1, g2));
    let chord = sub(g1, g2);
    let small = 0.25 * dot(chord, chord) / (1.0 + 0.5 * norm(add(g1, g2)));
    let e = sub(gc, m);
    if 0.5 * dot(e, e) <= small {
        (m, small, 2.0 - small)
    } else {
        (scale(m, -1.0), 2.0 - small, small)
    }
}

/// The solid angle of the intersection of two caps `(axis, 1 − cos, 1 + cos)` in f64,
/// by the spherical-triangle form with `acos` (Eq. 36 of the paper, Tovchigrechko and
/// Vakser), not the Gauss–Bonnet form of `cap_intersection_solid_angle`.
pub fn cap_intersection_f64(a: (D3, f64, f64), b: (D3, f64, f64)) -> f64 {
    use core::f64::consts::PI;
    let angle = |t: f64, h: f64| 2.0 * (0.5 * t).sqrt().atan2((0.5 * h).sqrt());
    let (ta, tb) = (angle(a.1, a.2), angle(b.1, b.2));
    let d = 2.0 * (0.5 * norm(sub(a.0, b.0))).atan2(0.5 * norm(add(a.0, b.0)));
    if d >= ta + tb {
        return 0.0;
    }
    if d <= (ta - tb).abs() {
        return 2.0 * PI * a.1.min(b.1);
    }
    if d >= 2.0 * PI - ta - tb {
        return 2.0 * PI * (a.1 + b.1) - 4.0 * PI;
    }
    let (ca, cb, cd) = (ta.cos(), tb.cos(), d.cos());
    let (sa, sb, sd) = (ta.sin(), tb.sin(), d.sin());
    let gamma = ((cd - ca * cb) / (sa * sb)).clamp(-1.0, 1.0).acos();
    let phi_a = ((cb - cd * ca) / (sd * sa)).clamp(-1.0, 1.0).acos();
    let phi_b = ((ca - cd * cb) / (sd * sb)).clamp(-1.0, 1.0).acos();
    2.0 * (PI - gamma - ca * phi_a - cb * phi_b)
}

/// A direction of the cap (axis `a`) at `1 − cos = t` and azimuth `phi`, in f64.
pub fn cap_point(a: D3, t: f64, phi: f64) -> D3 {
    let (u, v) = frame_f64(a);
    let s = (t * (2.0 - t)).max(0.0).sqrt();
    normalize(core::array::from_fn(|i| {
        a[i] * (1.0 - t) + s * (phi.cos() * u[i] + phi.sin() * v[i])
    }))
}

pub fn inside_f64(w: D3, cap: &crate::sphere::Cap) -> bool {
    let a = d3(cap.axis);
    let e: D3 = core::array::from_fn(|i| w[i] - a[i]);
    0.5 * dot(e, e) <= cap.one_minus_cos as f64
}

/// `∫ f` over a cap by the midpoint rule in `(s, φ)` with `1 − cos θ = t_max s²`, where
/// `dω = dt dφ = 2 t_max s ds dφ`: the substitution refines the grid towards the cap's
/// axis, where peaked integrands (glossy lobes, pivoted densities) concentrate.
pub fn integrate_over_cap_f64(cap: &crate::sphere::Cap, n: usize, f: impl Fn(D3) -> f64) -> f64 {
    let a = d3(cap.axis);
    let t_max = cap.one_minus_cos as f64;
    let (ds, dphi) = (1.0 / n as f64, core::f64::consts::TAU / (2 * n) as f64);
    let mut sum = 0.0;
    for i in 0..n {
        let s = (i as f64 + 0.5) * ds;
        let t = t_max * s * s;
        let mut ring = 0.0;
        for k in 0..2 * n {
            ring += f(cap_point(a, t, (k as f64 + 0.5) * dphi));
        }
        sum += ring * 2.0 * t_max * s;
    }
    sum * ds * dphi
}

/// A uniformly distributed direction, in f64.
pub fn uniform_direction_f64(rng: &mut Rng) -> D3 {
    let z = 1.0 - 2.0 * rng.uniform();
    let phi = core::f64::consts::TAU * rng.uniform();
    let s = (1.0 - z * z).max(0.0).sqrt();
    [s * phi.cos(), s * phi.sin(), z]
}

/// An f64 orthonormal frame around `a` (independent of the core's basis).
pub fn frame_f64(a: D3) -> (D3, D3) {
    let helper = if a[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let t = normalize(crate::testing::cross(helper, a));
    let b = crate::testing::cross(a, t);
    (t, b)
}

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

/// `∫_P f(ω) dω` over a convex planar polygon by the midpoint rule on the `n²` cells per
/// fan triangle of [`PolygonCells`] (each cell's exact solid angle times `f` at the
/// direction of its centroid): relative error `O(1/n²)` for smooth `f`. f64 throughout,
/// independent of every sampler.
pub fn integrate_over_polygon_f64(vertices: &[Vec3], n: usize, f: impl Fn(D3) -> f64) -> f64 {
    let p: Vec<D3> = vertices.iter().map(|&x| d3(x)).collect();
    PolygonCells::new(&p, n)
        .cells
        .iter()
        .map(|c| {
            let centroid = scale(add(add(c[0], c[1]), c[2]), 1.0 / 3.0);
            solid_angle_triangle_f64(c[0], c[1], c[2]) * f(normalize(centroid))
        })
        .sum()
}

/// `count` random-number pairs for a sampler test: first the 16 pairs of the edges and
/// middle of `[0, 1)` (0, 1e-7, 0.5, 1 − ulp in each coordinate), then uniform ones.
pub fn random_numbers_with_edges(rng: &mut Rng, count: usize) -> Vec<[f32; 2]> {
    let edges = [0.0, 1e-7, 0.5, crate::sample::ONE_MINUS_ULP];
    (0..count)
        .map(|k| {
            if k < 16 {
                [edges[k % 4], edges[k / 4]]
            } else {
                [rng.uniform_f32(), rng.uniform_f32()]
            }
        })
        .collect()
}

/// `∫ pdf(ω) dω` over the directions near a convex polygon (all its vertices in front of
/// their mean direction `c`), by quadrature in the gnomonic plane tangent at `c`:
/// directions `c + x t + y b`, `dω = dx dy / |(x, y, 1)|³`. The `y` range (the polygon's
/// extent plus a margin of 20% on each side) is cut at the vertices' `y`, each piece
/// integrated by 16-point Gauss–Legendre; on each row the interval where `pdf > 0` is
/// found by bisection (60 steps) from the exact chord's midpoint outwards to the margin,
/// and `pdf · dω` integrated over it by 16-point Gauss–Legendre. For densities that vary
/// sharply across the polygon (a GGX lobe much narrower than the light), each piece and
/// each row's support are split into `subdivisions` equal parts (1: none), each
/// integrated so. So a `pdf` whose support
/// reaches outside the polygon, or has holes at its edges, shows as an integral off 1;
/// the quadrature itself is accurate to about 1e-9 for the smooth densities of the
/// polygon samplers. Returns the integral and the largest distance (in the plane, where
/// it is the angle to first order) by which the support reaches outside the exact
/// polygon.
pub fn integrate_pdf_near_polygon(
    vertices: &[Vec3],
    subdivisions: usize,
    pdf: impl Fn(Vec3) -> f32,
) -> (f64, f64) {
    let v: Vec<D3> = vertices.iter().map(|&p| d3(p)).collect();
    let mut c = [0.0; 3];
    for p in &v {
        c = add(c, normalize(*p));
    }
    let c = normalize(c);
    let (t, b) = frame_f64(c);
    let xy: Vec<(f64, f64)> = v
        .iter()
        .map(|p| (dot(*p, t) / dot(*p, c), dot(*p, b) / dot(*p, c)))
        .collect();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in &xy {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    let size = (x1 - x0).max(y1 - y0);
    let (left_limit, right_limit) = (x0 - 0.2 * size, x1 + 0.2 * size);
    let dir = |x: f64, y: f64| {
        let d: [f64; 3] = core::array::from_fn(|i| c[i] + x * t[i] + y * b[i]);
        Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32)
    };
    let jacobian = |x: f64, y: f64| (x * x + y * y + 1.0).powf(-1.5);
    // The exact polygon's chord at `y`: the intersections of the horizontal line with
    // the edges.
    let chord = |y: f64| {
        let (mut lo, mut hi) = (f64::MAX, f64::MIN);
        for i in 0..xy.len() {
            let (a, e) = (xy[i], xy[(i + 1) % xy.len()]);
            if (a.1 - y) * (e.1 - y) <= 0.0 && a.1 != e.1 {
                let x = a.0 + (y - a.1) / (e.1 - a.1) * (e.0 - a.0);
                (lo, hi) = (lo.min(x), hi.max(x));
            }
        }
        (lo, hi)
    };
    let (nodes, weights) = gauss_legendre_16();
    let mut cuts: Vec<f64> = xy.iter().map(|&(_, y)| y).collect();
    cuts.push(y0 - 0.2 * size);
    cuts.push(y1 + 0.2 * size);
    cuts.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let (mut integral, mut reach) = (0.0f64, 0.0f64);
    let pieces: Vec<(f64, f64)> = cuts
        .windows(2)
        .flat_map(|piece| {
            let (ya, yb) = (piece[0], piece[1]);
            (0..subdivisions).map(move |j| {
                let step = (yb - ya) / subdivisions as f64;
                (ya + step * j as f64, ya + step * (j + 1) as f64)
            })
        })
        .collect();
    for &(ya, yb) in &pieces {
        if yb <= ya {
            continue;
        }
        for k in 0..16 {
            let y = 0.5 * (ya + yb) + 0.5 * (yb - ya) * nodes[k];
            let (lo, hi) = chord(y);
            // The start: the chord's midpoint, or (outside the polygon's y range) a scan
            // for any direction with pdf > 0.
            let start = if lo <= hi {
                Some(0.5 * (lo + hi))
            } else {
                (0..=256)
                    .map(|j| left_limit + (right_limit - left_limit) * j as f64 / 256.0)
                    .find(|&x| pdf(dir(x, y)) > 0.0)
            };
            let Some(start) = start.filter(|&x| pdf(dir(x, y)) > 0.0) else {
                continue;
            };
            let edge = |outside: f64| {
                let (mut inside, mut outside) = (start, outside);
                for _ in 0..60 {
                    let mid = 0.5 * (inside + outside);
                    if pdf(dir(mid, y)) > 0.0 {
                        inside = mid;
                    } else {
                        outside = mid;
                    }
                }
                inside
            };
            let (xl, xr) = (edge(left_limit), edge(right_limit));
            if lo <= hi {
                reach = reach.max(lo - xl).max(xr - hi);
            } else {
                reach = reach.max((y0 - y).max(y - y1));
            }
            let mut row = 0.0;
            let step = (xr - xl) / subdivisions as f64;
            for j in 0..subdivisions {
                let (xa, xb) = (xl + step * j as f64, xl + step * (j + 1) as f64);
                for m in 0..16 {
                    let x = 0.5 * (xa + xb) + 0.5 * (xb - xa) * nodes[m];
                    row += weights[m] * pdf(dir(x, y)) as f64 * jacobian(x, y) * 0.5 * (xb - xa);
                }
            }
            integral += 0.5 * (yb - ya) * weights[k] * row;
        }
    }
    (integral, reach)
}

/// Issue 16 (1): `∫ pdf dω` over the sphere near the polygon (by
/// [`integrate_pdf_near_polygon`]) within `tolerance` of 1, and every sample (at random
/// `u` and at the edges of `u`) drawn with `pdf > 0` and `pdf(dir) == pdf` bit for bit.
pub fn assert_pdf_integrates_to_one_and_samples_have_their_pdf(
    name: &str,
    vertices: &[Vec3],
    tolerance: f64,
    rng: &mut Rng,
    sample: impl Fn([f32; 2]) -> crate::Sample,
    pdf: impl Fn(Vec3) -> f32,
) {
    assert_peaked_pdf_integrates_to_one_and_samples_have_their_pdf(
        name, vertices, 1, tolerance, rng, sample, pdf,
    );
}

/// [`assert_pdf_integrates_to_one_and_samples_have_their_pdf`] with the quadrature of
/// [`integrate_pdf_near_polygon`] split into `subdivisions` per dimension.
pub fn assert_peaked_pdf_integrates_to_one_and_samples_have_their_pdf(
    name: &str,
    vertices: &[Vec3],
    subdivisions: usize,
    tolerance: f64,
    rng: &mut Rng,
    sample: impl Fn([f32; 2]) -> crate::Sample,
    pdf: impl Fn(Vec3) -> f32,
) {
    let (integral, _) = integrate_pdf_near_polygon(vertices, subdivisions, &pdf);
    assert!(
        (integral - 1.0).abs() < tolerance,
        "{name}: ∫ pdf = {integral}"
    );
    for u in random_numbers_with_edges(rng, 20_000) {
        let s = sample(u);
        assert!(s.pdf > 0.0, "{name} at {u:?}: no sample");
        assert_eq!(s.pdf.to_bits(), pdf(s.dir).to_bits(), "{name} at {u:?}");
    }
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

/// Regularised upper incomplete gamma function Q(a, x), for chi-square p-values.
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let ln_gamma_a = ln_gamma(a);
    if x < a + 1.0 {
        // Series for P(a, x).
        let mut term = 1.0 / a;
        let mut sum = term;
        let mut ap = a;
        for _ in 0..10_000 {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * (-x + a * x.ln() - ln_gamma_a).exp()
    } else {
        // Continued fraction for Q(a, x) (modified Lentz).
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-15 {
                break;
            }
        }
        (-x + a * x.ln() - ln_gamma_a).exp() * h
    }
}

/// ln Γ(x) for x > 0 by the Lanczos approximation (g = 7, n = 9).
pub fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        let pi = core::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut sum = C[0];
    for (i, &c) in C.iter().enumerate().skip(1) {
        sum += c / (x + i as f64);
    }
    let t = x + 7.5;
    0.5 * (2.0 * core::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + sum.ln()
}

/// Pearson's chi-square test of observed counts against exact cell probabilities.
/// Cells whose expected count is below 5 are pooled. Returns (statistic, dof, p-value).
pub fn chi_square(observed: &[u64], probabilities: &[f64]) -> (f64, usize, f64) {
    let total: u64 = observed.iter().sum();
    let mut statistic = 0.0;
    let mut bins = 0usize;
    let (mut pooled_observed, mut pooled_expected) = (0.0, 0.0);
    for (&o, &p) in observed.iter().zip(probabilities) {
        let e = p * total as f64;
        if e < 5.0 {
            pooled_observed += o as f64;
            pooled_expected += e;
        } else {
            statistic += (o as f64 - e).powi(2) / e;
            bins += 1;
        }
    }
    if pooled_expected >= 5.0 {
        statistic += (pooled_observed - pooled_expected).powi(2) / pooled_expected;
        bins += 1;
    } else if pooled_observed > pooled_expected + 5.0 {
        // Many samples where almost none are expected: fail loudly.
        statistic += f64::INFINITY;
    }
    let dof = bins.saturating_sub(1).max(1);
    (statistic, dof, gamma_q(dof as f64 / 2.0, statistic / 2.0))
}

/// The significance level of every chi-square test in the crate. With a few dozen
/// tests, 1e-4 keeps the chance of any false alarm per run below a percent while a
/// wrong distribution at these sample counts gives p-values far below it.
pub const CHI_SQUARE_ALPHA: f64 = 1e-4;

/// Running mean and variance (Welford), for estimator tests.
#[derive(Default)]
pub struct Estimate {
    count: u64,
    mean: f64,
    m2: f64,
}

impl Estimate {
    pub fn add(&mut self, x: f64) {
        self.count += 1;
        let delta = x - self.mean;
        self.mean += delta / self.count as f64;
        self.m2 += delta * (x - self.mean);
    }
    pub fn variance(&self) -> f64 {
        self.m2 / (self.count.max(2) - 1) as f64
    }
    pub fn mean(&self) -> f64 {
        self.mean
    }
    pub fn standard_error(&self) -> f64 {
        (self.variance() / self.count as f64).sqrt()
    }
    /// Asserts that the mean agrees with `reference` within `sigmas` standard errors
    /// plus a relative tolerance for f32 rounding.
    pub fn assert_mean_is(&self, reference: f64, sigmas: f64, relative: f64, what: &str) {
        let allowed = sigmas * self.standard_error() + relative * reference.abs();
        assert!(
            (self.mean - reference).abs() <= allowed,
            "{what}: mean {} vs reference {} (standard error {}, allowed {})",
            self.mean,
            reference,
            self.standard_error(),
            allowed
        );
    }
}

/// A convex polygon with `n` vertices on a circle (irregularly spaced) around `center`
/// in the plane with normal `normal`, in f32, optionally reversed.
pub fn circle_polygon(n: usize, center: D3, normal: D3, radius: f64, reversed: bool) -> Vec<Vec3> {
    let normal = normalize(normal);
    let helper = if normal[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = normalize(cross(normal, helper));
    let e2 = cross(normal, e1);
    let mut vertices: Vec<Vec3> = (0..n)
        .map(|k| {
            let k = k as f64;
            let angle = 2.0 * core::f64::consts::PI * (k + 0.35 * (2.3 * k + 1.0).sin()) / n as f64;
            let p = add(
                center,
                add(
                    scale(e1, radius * angle.cos()),
                    scale(e2, radius * angle.sin()),
                ),
            );
            Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32)
        })
        .collect();
    if reversed {
        vertices.reverse();
    }
    vertices
}

/// Projected solid angle (the cosine integral) of a polygon by Lambert's formula, in
/// f64: σ/2 Σ angle(v_i, v_(i+1)) (n̂_i · z) with n̂_i = normalize(v_i × v_(i+1)) and σ
/// the orientation of the polygon seen from the origin.
pub fn projected_solid_angle_polygon_f64(vertices: &[Vec3]) -> f64 {
    let p: Vec<D3> = vertices.iter().map(|&p| d3(p)).collect();
    projected_solid_angle_d3(&p)
}

/// [`projected_solid_angle_polygon_f64`] of f64 positions.
pub fn projected_solid_angle_d3(p: &[D3]) -> f64 {
    let sigma = dot(p[0], cross(sub(p[1], p[0]), sub(p[2], p[0]))).signum();
    let mut sum = 0.0;
    for i in 0..p.len() {
        let j = (i + 1) % p.len();
        // The edge plane's normal from the exact positions (no cancellation).
        let c = cross(p[i], sub(p[j], p[i]));
        // The angle from the positions, so that tiny polygons (where Lambert's terms
        // cancel by a factor of up to 1e7) keep f64 precision: |p_i × p_j| = |c|.
        let angle = norm(c).atan2(dot(p[i], p[j]));
        sum += angle * normalize(c)[2];
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

/// The plane x + y + z = 0 through the shading point; moved by (0.1, 0.2, 0.3) it is a
/// valid polygon.
const TILTED_THROUGH_ORIGIN: [Vec3; 4] = [
    Vec3::new(1.0, -1.0, 0.0),
    Vec3::new(0.0, 1.0, -1.0),
    Vec3::new(-1.0, 0.0, 1.0),
    Vec3::new(-0.5, -0.5, 1.0),
];

/// Polygons every sampler's `new` must reject, built around a valid `triangle`: 0, 1,
/// 2 and 9 vertices, each coordinate in turn replaced by NaN or ±inf, all vertices
/// equal (also all at the origin), collinear vertices, and polygons whose plane passes
/// through the shading point (z = 0, and x + y + z = 0).
pub fn invalid_polygons(triangle: &[Vec3]) -> Vec<Vec<Vec3>> {
    let mut out = Vec::new();
    let nine = circle_polygon(9, [0.2, -0.1, 1.5], [0.1, 0.1, -1.0], 0.5, false);
    for count in [0, 1, 2, 9] {
        out.push(nine[..count].to_vec());
    }
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        for vertex in 0..3 {
            for axis in 0..3 {
                let mut t = triangle.to_vec();
                t[vertex][axis] = bad;
                out.push(t);
            }
        }
    }
    let p = Vec3::new(0.3, -0.2, 1.0);
    out.push(vec![p; 3]);
    out.push(vec![p; 4]);
    out.push(vec![Vec3::ZERO; 4]);
    out.push(vec![
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(2.0, 2.0, 1.0),
    ]);
    out.push(vec![
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(-1.0, -0.5, 0.0),
    ]);
    out.push(TILTED_THROUGH_ORIGIN.to_vec());
    out
}

/// Valid polygons next to the invalid ones: 8 vertices, and the plane through the
/// shading point of [`invalid_polygons`] moved off it.
pub fn valid_edge_case_polygons() -> Vec<Vec<Vec3>> {
    vec![
        circle_polygon(8, [0.2, -0.1, 1.5], [0.1, 0.1, -1.0], 0.5, false),
        TILTED_THROUGH_ORIGIN
            .iter()
            .map(|&v| v + Vec3::new(0.1, 0.2, 0.3))
            .collect(),
    ]
}

/// A convex polygon with `n` vertices on an ellipse (semi-axes `radius` and
/// `radius * aspect`) centred at `center`, in the plane with the given normal, at
/// random sorted angles (with a minimum gap so that no three vertices are collinear).
pub fn ellipse_polygon(
    rng: &mut Rng,
    n: usize,
    center: Vec3,
    normal: Vec3,
    radius: f32,
    aspect: f32,
) -> Vec<Vec3> {
    let (t, b) = crate::math::orthonormal_basis(normal.normalize());
    let mut angles: Vec<f64> = Vec::new();
    'retry: loop {
        angles.clear();
        for _ in 0..n {
            angles.push(rng.uniform() * core::f64::consts::TAU);
        }
        angles.sort_by(|a, b| a.partial_cmp(b).unwrap());
        for i in 0..n {
            let gap = if i + 1 < n {
                angles[i + 1] - angles[i]
            } else {
                angles[0] + core::f64::consts::TAU - angles[i]
            };
            if gap < 0.3 / n as f64 {
                continue 'retry;
            }
        }
        break;
    }
    angles
        .iter()
        .map(|&a| center + t * (radius * a.cos() as f32) + b * (radius * aspect * a.sin() as f32))
        .collect()
}

pub fn reversed(v: &[Vec3]) -> Vec<Vec3> {
    v.iter().rev().copied().collect()
}

/// What a statistical run of a polygon sampler found.
#[derive(Debug)]
pub struct SamplerReport {
    /// Chi-square p-value of the sample counts per cell against the cell weights.
    pub p_value: f64,
    /// Samples whose f64 ray misses the polygon.
    pub outside: u64,
    /// Largest angle (radians) by which a sample lies outside the polygon: rounding a
    /// direction to f32 moves it by up to ~6e-8, so samples right at an edge may end up
    /// outside by about that much, but never by more.
    pub worst_outside_angle: f64,
    /// Samples with a non-finite direction or pdf, or pdf <= 0.
    pub non_finite: u64,
    /// Largest relative difference between a sample's pdf and `pdf(sample.dir)`.
    pub worst_pdf_mismatch: f64,
    pub samples: u64,
}

/// Draws `samples` samples with `sample`, locates each in the cells of the polygon
/// (`subdivisions²` cells per fan triangle), and tests the counts against the cells'
/// exact probabilities `weight(cell) / Σ weight` with a chi-square test. Also counts
/// samples outside the polygon, non-finite samples, and compares the sample's pdf with
/// `pdf(dir)`.
pub fn run_polygon_sampler(
    vertices: &[Vec3],
    subdivisions: usize,
    samples: u64,
    seed: u64,
    weight: impl Fn(&[D3; 3]) -> f64,
    sample: impl Fn([f32; 2]) -> crate::Sample,
    pdf: impl Fn(Vec3) -> f32,
) -> SamplerReport {
    let polygon: Vec<D3> = vertices.iter().map(|&v| d3(v)).collect();
    let cells = PolygonCells::new(&polygon, subdivisions);
    let weights: Vec<f64> = cells.cells.iter().map(&weight).collect();
    let total: f64 = weights.iter().sum();
    let probabilities: Vec<f64> = weights.iter().map(|w| w / total).collect();
    let mut counts = vec![0u64; cells.cells.len()];
    let mut rng = Rng::new(seed);
    let n = polygon.len();
    let centroid = polygon.iter().fold([0.0; 3], |a, &b| add(a, b));
    let inward: Vec<D3> = (0..n)
        .map(|i| normalize(cross(polygon[i], sub(polygon[(i + 1) % n], polygon[i]))))
        .map(|e| {
            if dot(e, centroid) < 0.0 {
                scale(e, -1.0)
            } else {
                e
            }
        })
        .collect();
    let mut worst_outside_angle = 0.0f64;
    let (mut outside, mut non_finite, mut worst) = (0, 0, 0.0f64);
    for _ in 0..samples {
        let s = sample([rng.uniform_f32(), rng.uniform_f32()]);
        if !s.dir.is_finite() || !s.pdf.is_finite() || s.pdf <= 0.0 {
            non_finite += 1;
            continue;
        }
        match cells.locate(d3(s.dir)) {
            Some(cell) => counts[cell] += 1,
            None => {
                outside += 1;
                let d = normalize(d3(s.dir));
                for e in &inward {
                    worst_outside_angle = worst_outside_angle.max(-dot(*e, d));
                }
            }
        }
        let p = pdf(s.dir) as f64;
        worst = worst.max((p - s.pdf as f64).abs() / s.pdf as f64);
    }
    let (_, _, p_value) = chi_square(&counts, &probabilities);
    SamplerReport {
        p_value,
        outside,
        worst_outside_angle,
        non_finite,
        worst_pdf_mismatch: worst,
        samples,
    }
}

/// The quad of the pdf-support tests (issue 16, 1): centred on (0.2, -0.1, 1), of
/// half-size `size`, its plane tilted by `tilt` (0.1: nearly facing the shading point,
/// 0.9: a sliver seen at a grazing angle).
pub fn scaled_quad(size: f32, tilt: f32) -> [Vec3; 4] {
    let c = Vec3::new(0.2, -0.1, 1.0);
    let (t, b) = (Vec3::new(1.0, 0.0, -0.2), Vec3::new(0.0, 1.0, tilt));
    [
        c + size * (-1.0 * t - 0.8 * b),
        c + size * (0.9 * t - 1.0 * b),
        c + size * (1.0 * t + 0.7 * b),
        c + size * (-0.8 * t + 1.0 * b),
    ]
}

// ---- directions, caps and integrals over the sphere shared by several tests --------

/// The unit direction at `degrees` from +z towards +x, then turned by `azimuth` about z.
pub fn tilted(degrees: f64, azimuth: f64) -> Vec3 {
    let (t, p) = (degrees.to_radians(), azimuth.to_radians());
    Vec3::new(
        (t.sin() * p.cos()) as f32,
        (t.sin() * p.sin()) as f32,
        t.cos() as f32,
    )
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

// ---- LTCs shared by the LTC's tests and the LTC polygon sampler's ---------------------

/// A few LTCs in the view frame `[a, b, c, d, albedo, fresnel]`: the cosine, a mildly
/// anisotropic one, a sharp one leaning away from the view (as GGX at grazing angles),
/// and a very sharp one.
pub const LTC_ENTRIES: [[f32; 6]; 4] = [
    [1.0, 0.0, 1.0, 0.0, 1.0, 0.0],
    [1.6, 0.3, 1.4, -0.2, 0.9, 0.1],
    [8.0, 2.0, 5.0, 1.5, 0.7, 0.05],
    [300.0, -40.0, 250.0, 0.0, 0.95, 0.02],
];

pub fn ltcs() -> Vec<crate::brdf::Ltc> {
    let mut out = Vec::new();
    for (k, entry) in LTC_ENTRIES.iter().enumerate() {
        let phi = 0.7 * k as f32;
        out.push(crate::brdf::Ltc::from_view_frame(*entry, phi.cos(), phi.sin()).expect("valid"));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chi_square_p_values_match_known_quantiles() {
        // 95% quantiles of chi-square: dof 1 -> 3.841, dof 10 -> 18.307.
        assert!((gamma_q(0.5, 3.841_458_8 / 2.0) - 0.05).abs() < 1e-6);
        assert!((gamma_q(5.0, 18.307_038 / 2.0) - 0.05).abs() < 1e-6);
        assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-12);
    }

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
