//! The SG error table on a reduced grid (`tools/src/sg_error.rs`, full table in
//! `docs/sg-error.md`): the exact closed forms must match the f64 quadrature to 1e-4,
//! and the approximations must stay within the bounds measured by the full table, in
//! the regimes where they are meant to be used.
use sphera_tools::sg_error::{Sample, is_exact, measure};

/// Which measurements of a quantity a bound applies to.
type Filter<'a> = &'a dyn Fn(&Sample) -> bool;

fn worst(samples: &[Sample], quantity: &str, keep: impl Fn(&Sample) -> bool) -> f64 {
    let errors: Vec<f64> = samples
        .iter()
        .filter(|s| s.quantity == quantity && keep(s))
        .map(|s| s.error)
        .collect();
    assert!(!errors.is_empty(), "no measurement of {quantity}");
    errors.into_iter().fold(0.0, f64::max)
}

#[test]
fn reduced_error_table_stays_within_the_measured_bounds() {
    let samples = measure(true);
    for s in &samples {
        eprintln!(
            "{} | {} | {} | {:.3e}",
            s.quantity, s.decade, s.case, s.error
        );
    }
    for q in ["A(λ)", "inner product", "vMF pdf normalisation"] {
        assert!(is_exact(q));
        let w = worst(&samples, q, |_| true);
        assert!(w < 1e-4, "{q}: {w}");
    }
    let checks: [(&str, Filter, f64); 7] = [
        ("ASG × SG convolution", &|_| true, 5e-3),
        ("ASG integral π/√(η_x η_y)", &|s| s.decade >= 1, 2e-4),
        ("diffuse shading, SG product", &|s| s.decade <= 0, 0.1),
        (
            "diffuse shading, constant cosine",
            &|s| s.decade >= 2 && !s.case.ends_with("90°"),
            BOUND_CONSTANT_COSINE,
        ),
        (
            "diffuse shading, 2/λ shortcut",
            &|s| s.decade >= 2 && !s.case.ends_with("90°"),
            BOUND_CONSTANT_COSINE,
        ),
        (
            "specular shading, ASG",
            &|s| s.decade <= 2 && s.case.ends_with("off 0"),
            BOUND_SPECULAR,
        ),
        (
            "specular shading, SG",
            &|s| s.decade <= 2 && s.case.ends_with("off 0"),
            BOUND_SPECULAR,
        ),
    ];
    for (q, keep, bound) in checks {
        let w = worst(&samples, q, keep);
        assert!(w < bound, "{q}: {w} (bound {bound})");
    }
}

const BOUND_CONSTANT_COSINE: f64 = 0.05;
const BOUND_SPECULAR: f64 = 0.5;
