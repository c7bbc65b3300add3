//! The error of real-time sphere-light shading with the fitted SPTD (Dupuy et al. 2017,
//! Section 5, Eq. 19; `SphereLightShading`) against a converged Monte Carlo reference of
//! `∫_{C ∩ H} f cos θ dω` (GGX with F = 1, f64, one uniform cap sample and one
//! visible-normal sample per stratum, balance heuristic, 512² strata), over a grid of
//! roughness, view angle, light size and distance, and light direction. Also the two
//! variants the paper discusses: the unclipped integral `Ω(g(C))/4π` (light leaking below
//! the horizon) and the horizon clipping with Oat and Sander's approximation of the
//! two-cap solid angle (Eq. 37–38), and specular occlusion with a bent cone (Eq. 23, and
//! its separable baseline, Eq. 21–22)
//! against the reference with the cone as the exact visibility.
//!
//! The table: `cargo run --release -p sphera-tools --bin sphere_shading_error >
//! docs/sphere-shading-error.md` (about 20 s); `tools/tests/sphere_shading.rs` bounds the
//! errors on part of the grid.
use crate::fitters::ltc_fitter::{Ggx, V3};
use std::f64::consts::PI;

/// One configuration of the grid.
pub struct Config {
    pub roughness: f32,
    pub view_degrees: f64,
    pub radius: f64,
    pub distance: f64,
    pub direction: &'static str,
    pub center: V3,
}

pub use sphera_test_support::normalize;
use sphera_test_support::{dot, frame_f64};

/// The light directions of the grid for a view elevation θo (view in the xz plane).
pub fn directions(theta_o: f64) -> [(&'static str, V3); 4] {
    let mirror = [-theta_o.sin(), 0.0, theta_o.cos()];
    let lowered = (theta_o + 20f64.to_radians()).min(85f64.to_radians());
    let side = 45f64.to_radians();
    [
        ("mirror", mirror),
        ("overhead", [0.0, 0.0, 1.0]),
        ("mirror, 20° lower", [-lowered.sin(), 0.0, lowered.cos()]),
        (
            "45° in azimuth",
            [
                -theta_o.sin() * side.cos(),
                theta_o.sin() * side.sin(),
                theta_o.cos(),
            ],
        ),
    ]
}

pub fn configs() -> Vec<Config> {
    let mut out = Vec::new();
    for roughness in [0.1f32, 0.25, 0.5, 0.75, 1.0] {
        for view_degrees in [0.0, 30.0, 60.0, 80.0] {
            for (name, dir) in directions(f64::to_radians(view_degrees)) {
                for radius in [0.05, 0.25, 1.0] {
                    for distance in [2.0, 8.0] {
                        let d = normalize(dir);
                        out.push(Config {
                            roughness,
                            view_degrees,
                            radius,
                            distance,
                            direction: name,
                            center: [d[0] * distance, d[1] * distance, d[2] * distance],
                        });
                    }
                }
            }
        }
    }
    out
}

/// A uniform direction of the cap (axis `a`, `1 − cos = t_max`) in f64.
fn cap_direction(a: V3, t_max: f64, u0: f64, u1: f64) -> V3 {
    let (t, b) = frame_f64(a);
    let tt = u0 * t_max;
    let s = (tt * (2.0 - tt)).max(0.0).sqrt();
    let phi = 2.0 * PI * u1;
    normalize(std::array::from_fn(|i| {
        a[i] * (1.0 - tt) + s * (phi.cos() * t[i] + phi.sin() * b[i])
    }))
}

/// `∫_{C ∩ V} f cos θ dω` (F = 1) by MIS of uniform cap and visible-normal sampling over
/// `n²` jittered strata; `visibility` is a cap given by (axis, 1 − cos) or none.
pub fn reference(
    ggx: &Ggx,
    center: V3,
    radius: f64,
    visibility: Option<(V3, f64)>,
    n: usize,
) -> f64 {
    let d = dot(center, center).sqrt();
    let axis = normalize(center);
    let s2 = (radius / d).powi(2);
    let t_max = s2 / (1.0 + (1.0 - s2).sqrt());
    let pdf_cap = 1.0 / (2.0 * PI * t_max);
    let inside = |w: V3, a: V3, t: f64| {
        let e = [w[0] - a[0], w[1] - a[1], w[2] - a[2]];
        0.5 * dot(e, e) <= t
    };
    let visible = |w: V3| visibility.is_none_or(|(a, t)| inside(w, a, t));
    let mut sum = 0.0;
    let mut state = 0x1234_5678_9abc_def0u64;
    let mut jitter = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for i in 0..n {
        for j in 0..n {
            let u0 = (i as f64 + jitter()) / n as f64;
            let u1 = (j as f64 + jitter()) / n as f64;
            let w = cap_direction(axis, t_max, u0, u1);
            if visible(w) {
                sum += ggx.cosine_weighted(w) / (pdf_cap + ggx.sample_pdf(w));
            }
            let phi = 2.0 * PI * u1;
            let w = normalize(ggx.sample(u0, phi.cos(), phi.sin()));
            if inside(w, axis, t_max) && visible(w) {
                sum += ggx.cosine_weighted(w) / (pdf_cap + ggx.sample_pdf(w));
            }
        }
    }
    sum / (n * n) as f64
}
