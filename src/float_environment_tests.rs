//! Statistical checks under flush-to-zero and denormals-are-zero (MXCSR FTZ|DAZ, x86_64
//! only): renderers often run with both set, and then every denormal intermediate and
//! input reads as zero. A selection of the distribution and estimator checks of the
//! samplers must still pass, and outputs stay finite. (`ffi-tests/test_adversarial.c`
//! reruns its whole suite under FTZ|DAZ through the C ABI.)

use crate::Vec3;
use crate::polygon::{ProjectedPolygon, SolidAnglePolygon};
use crate::sphere::Cap;
use crate::testing::*;

/// Sets MXCSR's FTZ (bit 15) and DAZ (bit 6) bits for its lifetime on this thread.
struct FlushDenormals(u32);

impl FlushDenormals {
    fn new() -> FlushDenormals {
        let mut saved = 0u32;
        // SAFETY: `stmxcsr` stores the 32-bit control register to the given address and
        // `ldmxcsr` loads it; both only change the SSE rounding and exception controls of
        // this thread, which `Drop` restores.
        unsafe {
            core::arch::asm!("stmxcsr [{}]", in(reg) &mut saved);
            let flushed = saved | 0x8040;
            core::arch::asm!("ldmxcsr [{}]", in(reg) &flushed);
        }
        FlushDenormals(saved)
    }

    fn mxcsr() -> u32 {
        let mut value = 0u32;
        // SAFETY: as above.
        unsafe { core::arch::asm!("stmxcsr [{}]", in(reg) &mut value) };
        value
    }
}

impl Drop for FlushDenormals {
    fn drop(&mut self) {
        // SAFETY: restores the register saved in `new`.
        unsafe { core::arch::asm!("ldmxcsr [{}]", in(reg) &self.0) };
    }
}

#[test]
fn flushing_is_in_effect() {
    let _flush = FlushDenormals::new();
    assert_eq!(FlushDenormals::mxcsr() & 0x8040, 0x8040);
    // A denormal input reads as zero: 1e-40 * 1 is flushed.
    let tiny = core::hint::black_box(1e-40f32);
    assert_eq!(core::hint::black_box(tiny * 1.0), 0.0);
}

#[test]
fn solid_angle_and_projected_sampling_follow_their_densities_under_ftz_daz() {
    let _flush = FlushDenormals::new();
    let mut rng = Rng::new(77);
    for (k, vertices) in [
        circle_polygon(5, [0.2, 0.1, 1.0], [0.1, 0.2, 1.0], 0.7, false),
        circle_polygon(4, [1.2, -0.4, 0.6], [-0.5, 0.2, 1.0], 0.5, true),
        circle_polygon(6, [0.0, 1.5, 0.3], [0.0, -0.3, 1.0], 0.9, false),
    ]
    .iter()
    .enumerate()
    {
        let solid_angle = SolidAnglePolygon::new(vertices).expect("valid");
        let report = run_polygon_sampler(
            vertices,
            6,
            40_000,
            rng.next_u64(),
            |c| solid_angle_triangle_f64(c[0], c[1], c[2]),
            |u| solid_angle.sample(u),
            |d| solid_angle.pdf(d),
        );
        assert!(
            report.p_value > CHI_SQUARE_ALPHA,
            "solid angle #{k}: p = {}",
            report.p_value
        );
        assert_eq!(report.non_finite, 0);
        let clipped: Vec<Vec3> = {
            let mut v = [Vec3::ZERO; 8];
            v[..vertices.len()].copy_from_slice(vertices);
            let n = crate::polygon::clip_to_upper_hemisphere(&mut v, vertices.len());
            v[..n].to_vec()
        };
        let projected = ProjectedPolygon::new(vertices).expect("valid");
        let report = run_polygon_sampler(
            &clipped,
            6,
            40_000,
            rng.next_u64(),
            |c| projected_solid_angle_d3(c).abs(),
            |u| projected.sample(u),
            |d| projected.pdf(d),
        );
        assert!(
            report.p_value > CHI_SQUARE_ALPHA,
            "projected #{k}: p = {}",
            report.p_value
        );
        assert_eq!(report.non_finite, 0);
        let reference = projected_solid_angle_polygon_f64(&clipped);
        let relative = (projected.projected_solid_angle() as f64 - reference).abs() / reference;
        assert!(relative < 1e-4, "projected #{k}: Φ off by {relative}");
    }
}

#[test]
fn estimators_of_solid_angles_are_unbiased_under_ftz_daz() {
    let _flush = FlushDenormals::new();
    let mut rng = Rng::new(78);
    // A cap of 1e-7 sr and one of a sphere seen from just outside it: E[1/pdf] = Ω.
    for cap in [
        Cap::from_sphere(Vec3::new(0.0, 0.0, 1e3), 0.178),
        Cap::from_sphere(Vec3::new(0.3, 0.0, 1.0), 1.04),
    ] {
        let mut estimate = Estimate::default();
        for _ in 0..20_000 {
            let s = cap.sample_uniform([rng.uniform_f32(), rng.uniform_f32()]);
            assert!(
                s.pdf > 0.0 && s.dir.is_finite() && cap.pdf(s.dir) > 0.0,
                "{s:?}"
            );
            estimate.add(1.0 / s.pdf as f64);
        }
        estimate.assert_mean_is(cap.solid_angle() as f64, 4.0, 1e-5, "cap");
    }
    // Projected solid angle by solid angle sampling: E[cos θ / pdf] = Φ, for a polygon
    // and a tiny one (1e-10 sr, where intermediates come close to the denormal range).
    for vertices in [
        circle_polygon(5, [0.4, 0.3, 1.0], [0.2, 0.1, 1.0], 0.5, false),
        circle_polygon(4, [0.3, 0.0, 1e5], [0.0, 0.0, 1.0], 0.56, false),
    ] {
        let solid_angle = SolidAnglePolygon::new(&vertices).expect("valid");
        let projected = ProjectedPolygon::new(&vertices).expect("valid");
        let mut estimate = Estimate::default();
        for _ in 0..20_000 {
            let s = solid_angle.sample([rng.uniform_f32(), rng.uniform_f32()]);
            assert!(s.pdf > 0.0 && s.dir.is_finite());
            estimate.add(s.dir.z as f64 / s.pdf as f64);
        }
        estimate.assert_mean_is(projected.projected_solid_angle() as f64, 4.0, 1e-4, "Φ");
    }
}
