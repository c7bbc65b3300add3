//! Issue 17, 5: direction arguments need not be normalised, but `sphera_ltc_eval` and
//! `sphera_sptd_eval` returned 0 for directions of length 2⁻¹⁰⁰, 2¹⁰⁰, 2¹²⁶ and 2⁻¹⁴⁰
//! (denormal components), and `sphera_ltc_prepare`, `sphera_ggx_pivot_from_view`,
//! `sphera_sphere_light_shading_prepare` and `sphera_sphere_light_sampler_prepare`
//! returned `false` for views of length 1e20 and more: `|v|²` overflowed or underflowed.
//! Every direction argument now goes through one helper that divides by the largest
//! component first, so a direction and its multiples by powers of two give the same
//! result bit for bit, and the same as the unit direction to a few ulps.

use crate::Vec3;
use crate::brdf::Ltc;
use crate::ffi::*;
use crate::polygon::LtcPolygon;
use crate::sphere::{Cap, GgxPivot, SphereLightSampler, SphereLightShading, SptdInCap};
use core::mem::MaybeUninit;

/// The lengths of the issue, as powers of two (with 1 for comparison).
const EXPONENTS: [i32; 5] = [0, -100, 100, 126, -140];

/// `v · 2^k` in two exact steps (neither factor over- or underflows); exact for the
/// vectors below, whose components have a few significant bits, even where they become
/// denormal.
fn times_power_of_two(v: Vec3, k: i32) -> SpheraVec3 {
    (v * 2f32.powi(k / 2) * 2f32.powi(k - k / 2)).into()
}

/// `v / |v|` in f64, rounded to f32: the unit direction as a caller would pass it.
fn unit_f64(v: Vec3) -> SpheraVec3 {
    let (x, y, z) = (v.x as f64, v.y as f64, v.z as f64);
    let length = (x * x + y * y + z * z).sqrt();
    Vec3::new(
        (x / length) as f32,
        (y / length) as f32,
        (z / length) as f32,
    )
    .into()
}

/// What a `prepare` writes, and whether it succeeded.
fn prepared<T>(prepare: impl FnOnce(*mut T) -> bool) -> (bool, T) {
    let mut out = MaybeUninit::<T>::uninit();
    let ok = prepare(out.as_mut_ptr());
    // SAFETY: every `prepare` of the C ABI writes `*out` when it is not null.
    (ok, unsafe { out.assume_init() })
}

fn ltc(view: SpheraVec3) -> (bool, Ltc) {
    // SAFETY: `out` points to writable memory for one `Ltc`.
    prepared(|out| unsafe { sphera_ltc_prepare(out, view, 0.5) })
}
fn pivot(view: SpheraVec3) -> (bool, GgxPivot) {
    // SAFETY: as above.
    prepared(|out| unsafe { sphera_ggx_pivot_from_view(out, view, 0.5) })
}
fn shading(view: SpheraVec3) -> (bool, SphereLightShading) {
    let f0 = Vec3::new(0.04, 0.5, 0.9).into();
    // SAFETY: as above.
    prepared(|out| unsafe { sphera_sphere_light_shading_prepare(out, view, 0.5, f0) })
}
fn sampler(view: SpheraVec3) -> (bool, SphereLightSampler) {
    let center = Vec3::new(-1.0, 0.5, 3.0).into();
    // SAFETY: as above.
    prepared(|out| unsafe { sphera_sphere_light_sampler_prepare(out, center, 1.0, view, 0.5) })
}

/// Relative difference, 0 for two zeros.
fn relative(a: f32, b: f32) -> f64 {
    let (a, b) = (a as f64, b as f64);
    if a == b {
        0.0
    } else {
        (a - b).abs() / b.abs().max(a.abs())
    }
}

#[test]
fn direction_arguments_of_any_length_give_the_results_of_the_unit_direction() {
    // |view| = |dir| = 13/16 (components 3, ±4, 12 sixteenths), so neither is taken as
    // a unit vector as it is; `dir` lies near the view's reflection.
    let view = Vec3::new(0.1875, -0.25, 0.75);
    let dir = Vec3::new(-0.25, 0.1875, 0.75);
    let (unit_view, unit_dir) = (unit_f64(view), unit_f64(dir));
    let probe = Vec3::new(-0.3, 0.1, 0.9);
    let light = Cap::from_sphere(Vec3::new(-1.0, 0.5, 3.0), 1.0);
    let sptd_pivot = Vec3::new(0.2, -0.1, 0.5).into();
    let (_, fixed_ltc) = ltc(unit_view);
    let polygon_vertices: [SpheraVec3; 4] = [
        Vec3::new(-2.0, -1.0, 3.0).into(),
        Vec3::new(1.0, -1.0, 3.0).into(),
        Vec3::new(1.0, 2.0, 3.0).into(),
        Vec3::new(-2.0, 2.0, 3.0).into(),
    ];
    // SAFETY: `out`, `ltc` and the four vertices are valid.
    let (ok, polygon) = prepared(|out: *mut LtcPolygon| unsafe {
        sphera_ltc_polygon_prepare(out, &fixed_ltc, polygon_vertices.as_ptr(), 4)
    });
    assert!(ok);
    let (ok, in_cap) = prepared(|out: *mut SptdInCap| unsafe {
        // SAFETY: `out` is writable.
        sphera_sptd_in_cap_prepare(out, sptd_pivot, SPHERA_SPTD_UNIFORM, Vec3::Z.into(), light)
    });
    assert!(ok);

    // Every scalar result for a direction (or view) `d`.
    let results = |v: SpheraVec3, d: SpheraVec3| -> Vec<(&'static str, f32)> {
        let (ok_ltc, l) = ltc(v);
        let (ok_pivot, p) = pivot(v);
        let (ok_shading, s) = shading(v);
        let (ok_sampler, m) = sampler(v);
        let shaded = s.eval(&light);
        let d3: Vec3 = d.into();
        vec![
            ("sphera_ltc_prepare ok", ok_ltc as u32 as f32),
            ("sphera_ltc_prepare density", l.density(probe)),
            ("sphera_ltc_prepare albedo", l.albedo()),
            ("sphera_ggx_pivot_from_view ok", ok_pivot as u32 as f32),
            ("sphera_ggx_pivot_from_view pivot.x", p.pivot.x),
            ("sphera_ggx_pivot_from_view pivot.y", p.pivot.y),
            ("sphera_ggx_pivot_from_view pivot.z", p.pivot.z),
            ("sphera_ggx_pivot_from_view albedo", p.albedo),
            (
                "sphera_sphere_light_shading_prepare ok",
                ok_shading as u32 as f32,
            ),
            ("sphera_sphere_light_shading_prepare shade.y", shaded.y),
            (
                "sphera_sphere_light_sampler_prepare ok",
                ok_sampler as u32 as f32,
            ),
            ("sphera_sphere_light_sampler_prepare pdf", m.pdf(light.axis)),
            // SAFETY: `fixed_ltc`, `polygon` and `in_cap` are valid prepared values.
            ("sphera_ltc_eval", unsafe { sphera_ltc_eval(&fixed_ltc, d) }),
            ("sphera_ltc_polygon_pdf", unsafe {
                sphera_ltc_polygon_pdf(&polygon, d)
            }),
            ("sphera_sptd_in_cap_pdf", unsafe {
                sphera_sptd_in_cap_pdf(&in_cap, d3.into())
            }),
            (
                "sphera_sptd_eval uniform",
                sphera_sptd_eval(sptd_pivot, SPHERA_SPTD_UNIFORM, Vec3::Z.into(), d),
            ),
            (
                "sphera_sptd_eval clamped cosine",
                sphera_sptd_eval(
                    sptd_pivot,
                    SPHERA_SPTD_CLAMPED_COSINE,
                    Vec3::NEG_Z.into(),
                    d,
                ),
            ),
            (
                "sphera_pivot_jacobian",
                sphera_pivot_jacobian(d, sptd_pivot),
            ),
            (
                "sphera_pivot_transform.z",
                sphera_pivot_transform(d, sptd_pivot).z,
            ),
            ("sphera_cap_pdf", sphera_cap_pdf(light, d)),
        ]
    };
    let reference = results(unit_view, unit_dir);
    let mut worst = 0.0f64;
    for (name, value) in &reference {
        assert!(
            *value != 0.0 && value.is_finite(),
            "{name}: {value} for the unit direction"
        );
    }
    // The cap's pdf and the SPTD in the cap need the direction inside the light.
    let inside = unit_f64(Vec3::new(-0.25, 0.125, 0.75));
    assert!(sphera_cap_contains(light, inside));
    for k in EXPONENTS {
        let scaled = results(times_power_of_two(view, k), times_power_of_two(dir, k));
        let unscaled = results(view.into(), dir.into());
        for ((name, value), ((_, same), (_, unit))) in
            scaled.iter().zip(unscaled.iter().zip(&reference))
        {
            assert_eq!(
                value.to_bits(),
                same.to_bits(),
                "{name} at length 2^{k}: {value} vs {same}"
            );
            let difference = relative(*value, *unit);
            worst = worst.max(difference);
            assert!(
                difference <= 1e-6,
                "{name} at length 2^{k}: {value} vs {unit} for the unit direction"
            );
        }
        let scaled_inside = times_power_of_two(inside.into(), k);
        assert!(
            sphera_cap_contains(light, scaled_inside),
            "cap_contains at 2^{k}"
        );
        assert_eq!(
            sphera_cap_pdf(light, scaled_inside),
            sphera_cap_pdf(light, inside)
        );
        // SAFETY: `in_cap` is valid.
        let (a, b) = unsafe {
            (
                sphera_sptd_in_cap_pdf(&in_cap, scaled_inside),
                sphera_sptd_in_cap_pdf(&in_cap, inside),
            )
        };
        assert!(
            a > 0.0 && relative(a, b) <= 1e-6,
            "sptd_in_cap_pdf at 2^{k}: {a} vs {b}"
        );
    }
    eprintln!("worst relative difference from the unit direction: {worst:e}");
}
