//! The SG error table on a reduced grid (`tools/src/measurements/sg_error.rs`, full table in
//! `docs/sg-error.md`): the exact closed forms must match the f64 quadrature to 1e-4,
//! and the approximations must stay within the bounds measured by the full table, in
//! the regimes where they are meant to be used.
use sphera_tools::measurements::sg_error::{Sample, is_exact, measure};

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

/// Issue 20 (6): the Beckmann lobe (the paper's `λ_h = 2/α²`, the GGX lobe's functions)
/// against the f64 Beckmann BRDF of `tools/src/measurements/sg_error.rs`. On the reflection direction
/// both fits are within 10 % for roughness up to 0.5 at every sharpness up to 1e2
/// (measured 7.2 %; GGX's reach 18 %), and at roughness 0.1 the ASG is within 1e-3 at
/// every sharpness (measured 1.4e-4). Along the normal the SG has Beckmann's shape (L1
/// distance 1.1e-4 at roughness 0.1) where GGX's tail puts it at 0.41.
#[test]
fn beckmann_lobe_fits_the_beckmann_brdf() {
    let samples = measure(true);
    let on_peak = |s: &Sample| s.case.ends_with("off 0");
    let moderate = |s: &Sample| !s.case.contains("r=1 ");
    for q in [
        "Beckmann specular shading, ASG",
        "Beckmann specular shading, SG",
    ] {
        let w = worst(&samples, q, |s| on_peak(s) && moderate(s) && s.decade <= 2);
        assert!(w < 0.1, "{q}: {w}");
    }
    let w = worst(&samples, "Beckmann specular shading, ASG", |s| {
        on_peak(s) && s.case.contains("r=0.1 ")
    });
    assert!(w < 1e-3, "Beckmann ASG at r = 0.1: {w}");
    let along_normal = |s: &Sample| s.case == "r=0.1 view 0°";
    let beckmann = worst(
        &samples,
        "Beckmann SG lobe shape (L1 vs Beckmann·cos)",
        along_normal,
    );
    let ggx = worst(
        &samples,
        "specular SG lobe shape (L1 vs GGX·cos)",
        along_normal,
    );
    assert!(
        beckmann < 1e-3 && ggx > 0.3,
        "Beckmann {beckmann}, GGX {ggx}"
    );
}

const BOUND_CONSTANT_COSINE: f64 = 0.05;
const BOUND_SPECULAR: f64 = 0.5;
