//! Test-only helpers shared by every sampler's tests: polygons, caps and LTCs to test
//! with, the f64 references that need the core's types, and the statistical run of a
//! polygon sampler. The random number generator, f64 vectors and polygon geometry, the
//! chi-square test and quadrature live in the `sphera-test-support` crate (shared with
//! the tools), re-exported here.
use glam::Vec3;
pub use sphera_test_support::*;

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
    // Made orthogonal to the axis a second time: for a pivot within 1e-8 rad of the axis
    // line (an `f32` pivot "on" it), one pass leaves the tangent 1e-8 off orthogonal (the
    // rounding of `r_p − a (a·r_p)` over its length), the boundary points 1e-8 off the
    // sphere, and the axis of an image near a hemisphere (`|g(ω₁) + g(ω₂)| = 2|cos ψ'|`
    // small) 5e-6 rad off for `|cos ψ'| = 5e-4`.
    let u = normalize(sub(u, scale(axis, dot(u, axis))));
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
    integrate_over_cap_axis_f64(d3(cap.axis), cap.one_minus_cos as f64, n, f)
}

/// [`integrate_over_cap_f64`] over the cap about the unit `a` with `1 − cos θ = t_max`
/// (an f64 cap, which an f32 `Cap` may not represent).
pub fn integrate_over_cap_axis_f64(a: D3, t_max: f64, n: usize, f: impl Fn(D3) -> f64) -> f64 {
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

/// The significance level of every chi-square test in the crate. With a few dozen
/// tests, 1e-4 keeps the chance of any false alarm per run below a percent while a
/// wrong distribution at these sample counts gives p-values far below it.
pub const CHI_SQUARE_ALPHA: f64 = 1e-4;

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

/// The `f32` values from `ulps` below `x` to `ulps` above it, one ulp apart (positive
/// finite `x` away from the ends of the range): the lengths around a bound that a test
/// pins on both sides.
pub fn ulps_around(x: f32, ulps: u32) -> impl Iterator<Item = f32> {
    (x.to_bits() - ulps..=x.to_bits() + ulps).map(f32::from_bits)
}

/// A prepared value's words. For the `repr(C)` prepared values, whose fields are all
/// `f32` and `u32` (no padding).
pub fn words<T: Copy>(value: &T) -> &[u32] {
    assert_eq!(core::mem::size_of::<T>() % 4, 0);
    assert_eq!(core::mem::align_of::<T>(), 4);
    // SAFETY: `T` is one of the `repr(C)` prepared values, of `f32` and `u32` fields
    // only (no padding: every field is 4-byte aligned and a multiple of 4 bytes), so
    // its bytes are initialised `u32` words.
    unsafe {
        core::slice::from_raw_parts(
            (value as *const T).cast::<u32>(),
            core::mem::size_of::<T>() / 4,
        )
    }
}

/// `value` with every word a NaN: what a C caller's uninitialised or reused struct may
/// hold, for the tests of prepares that write in place.
pub fn nan_filled<T: Copy>(mut value: T) -> T {
    assert_eq!(core::mem::size_of::<T>() % 4, 0);
    assert_eq!(core::mem::align_of::<T>(), 4);
    // SAFETY: as in `words`: any `u32` words are a value of such a struct.
    unsafe {
        core::slice::from_raw_parts_mut(
            (&mut value as *mut T).cast::<u32>(),
            core::mem::size_of::<T>() / 4,
        )
        .fill(f32::NAN.to_bits());
    }
    value
}

/// The views of the tests of the tables' guessed row (`brdf::table_row_guess`): 200 000
/// unit directions `ω_o`, each with a roughness in [0, 1), every fourth scaled by 3.5 (not
/// unit). `check(view, roughness)` asserts a lookup's bits against the former lookup's,
/// for every view; `guess_is_right(ω_o, roughness)`, for each unit view, says whether the
/// guessed row is the exact cell (`None` where the view has no table coordinates), and
/// at least 99.9 % of those that have must be: a wrong guess needs the row coordinate
/// within the guess's rounding, a few 1e-5, of a cell's boundary.
pub fn check_guessed_row_views(
    seed: u64,
    mut check: impl FnMut(Vec3, f32),
    mut guess_is_right: impl FnMut(Vec3, f32) -> Option<bool>,
) {
    let mut rng = Rng::new(seed);
    let (mut unit_views, mut right) = (0u32, 0u32);
    for i in 0..200_000 {
        let wo = rng.unit_vector_f32();
        let roughness = rng.uniform_f32();
        let scaled = if i % 4 == 3 { wo * 3.5 } else { wo };
        check(scaled, roughness);
        if scaled == wo
            && let Some(is_right) = guess_is_right(wo, roughness)
        {
            unit_views += 1;
            right += is_right as u32;
        }
    }
    assert!(
        right as f64 >= 0.999 * unit_views as f64,
        "{right} of {unit_views}"
    );
}
