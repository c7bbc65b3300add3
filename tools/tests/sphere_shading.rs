//! Bounds on the error of real-time sphere-light shading with the fitted SPTD
//! (`SphereLightShading`, Dupuy et al. 2017 Eq. 19) against the f64 Monte Carlo reference
//! of `sphera_tools::measurements::sphere_shading_error`, on the part of the grid where the paper's
//! approximation is good (lights in the mirror direction, views up to 30°, r ≤ 0.5) and
//! everywhere against the measured maxima, so that a regression of the fit or of the pivoted-cap pipeline
//! shows. The full table is `docs/sphere-shading-error.md`.
use sphera::Vec3;
use sphera::sphere::Cap;
use sphera::sphere::light::SphereLightShading;
use sphera_tools::fitters::ltc_fitter::Ggx;
use sphera_tools::measurements::sphere_shading_error::{configs, reference};

#[test]
fn shading_error_stays_within_the_measured_bounds() {
    let mut checked = 0;
    for c in configs()
        .iter()
        .filter(|c| c.radius == 0.25 && c.distance == 2.0)
    {
        let theta = c.view_degrees.to_radians();
        let ggx = Ggx::new(
            (c.roughness as f64).powi(2).max(1e-4),
            theta.cos().max(1e-4),
        );
        let view = ggx.view();
        let wo = Vec3::new(view[0] as f32, view[1] as f32, view[2] as f32);
        let center = Vec3::new(c.center[0] as f32, c.center[1] as f32, c.center[2] as f32);
        let expected = reference(&ggx, c.center, c.radius, None, 96);
        let shading = SphereLightShading::new(wo, c.roughness, Vec3::ONE).unwrap();
        let value = shading.eval(&Cap::from_sphere(center, c.radius as f32)).x as f64;
        let relative = (value - expected).abs() / expected;
        let what = format!(
            "r {} θo {} {}: {value} vs {expected}",
            c.roughness, c.view_degrees, c.direction
        );
        if c.direction == "mirror" && c.view_degrees <= 30.0 && c.roughness <= 0.5 {
            // Measured: at most 4.7e-2 over all sizes (the table's 0°/30° columns).
            assert!(relative < 0.06, "{what}");
        }
        // Every cell against the largest relative error measured over the roughnesses
        // for its light direction and view angle, plus 15% (issue 16, 9: one bound of
        // 0.95 for all mirror cells let most of them regress unseen).
        let bound = 1.15 * measured_maximum(c.direction, c.view_degrees);
        assert!(
            relative <= bound,
            "{what}: relative error {relative} above {bound}"
        );
        checked += 1;
    }
    assert_eq!(checked, 80);
}

/// The largest relative error over roughness 0.1 to 1 measured for a light direction and
/// view angle (radius 0.25 at distance 2; `docs/sphere-shading-error.md` has every cell).
fn measured_maximum(direction: &str, view_degrees: f64) -> f64 {
    let by_view = match direction {
        "mirror" => [0.3512, 0.0360, 0.4388, 0.7747],
        "mirror, 20° lower" => [0.1496, 0.3307, 0.6661, 0.7620],
        "45° in azimuth" => [0.3512, 0.2141, 0.9586, 1.9592],
        "overhead" => [0.3512, 0.3656, 0.7453, 0.9691],
        other => panic!("no measured bound for the light direction {other:?}"),
    };
    let column = [0.0, 30.0, 60.0, 80.0]
        .iter()
        .position(|&v| v == view_degrees)
        .unwrap_or_else(|| panic!("no measured bound for the view angle {view_degrees}"));
    by_view[column]
}
