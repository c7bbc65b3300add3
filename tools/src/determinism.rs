//! The determinism table: every sampler of the C ABI over a fixed set of inputs, with
//! inputs and outputs as the bit patterns of their `f32`s in hex, so that a change in
//! numerics shows in review as a changed line of `ffi-tests/determinism_table.txt`.
//!
//! Written by `cargo run -p sphera-tools --bin generate_determinism_table` through the
//! Rust entry points (`sphera::ffi::*`); `tools/tests/determinism.rs` checks that
//! regenerating gives the committed file, and `ffi-tests/test_determinism.c` recomputes
//! every line through the C entry points of `libsphera.a` and requires the same bits.
//!
//! Format (one record per line, fields separated by one space, `#` starts a comment):
//! - `polygon <id> <count> <x y z>×count`: a polygon (vertex coordinates);
//! - `<sampler> <id> <u0> <u1> <dir.x> <dir.y> <dir.z> <pdf>` for the polygon samplers
//!   `solid_angle`, `turk`, `arvo`, `hart_bilinear`, `hart_biquadratic`,
//!   `clipped_solid_angle`, `projected`, `projected_fast`, `arvo_projected`, `ltc`
//!   (the GGX LTC for `wo = (0.3, 0.1, 0.9)`, roughness 0.4, inside the polygon);
//! - `light <id> <technique> <u0> <u1> <dir xyz> <pdf> <visible xyz> <unoccluded xyz>`
//!   (clamped optimal MIS, the material of the C tests);
//! - `ggx <roughness> <wo xyz> <u0> <u1> <dir xyz> <pdf>`, `lambert <u0> <u1> <dir xyz> <pdf>`;
//! - `cap <center xyz> <radius> <u0> <u1> <dir xyz> <pdf>` (uniform cap sampling);
//! - `pivot_phase` and `hg_phase <wo xyz> <g> <u0> <u1> <dir xyz> <pdf>`.
//!
//! To add a family (e.g. `sphera_sg_*`): a record type here and its case in the C test.

use std::fmt::Write;

use sphera::brdf::{GgxBrdf, Ltc, LtcPolygon};
use sphera::ffi::*;
use sphera::polygon::baselines::{
    ArvoPolygon, ArvoProjectedPolygon, HartBilinearPolygon, HartBiquadraticPolygon, TurkPolygon,
};
use sphera::polygon::light::{Material, PolygonLight};
use sphera::polygon::{ClippedSolidAnglePolygon, ProjectedSolidAnglePolygon, SolidAnglePolygon};

fn hex(x: f32) -> String {
    format!("{:08x}", x.to_bits())
}

fn hex3(v: SpheraVec3) -> String {
    format!("{} {} {}", hex(v.x), hex(v.y), hex(v.z))
}

fn v3(x: f32, y: f32, z: f32) -> SpheraVec3 {
    SpheraVec3 { x, y, z }
}

/// The polygons: a quad around the zenith, a decentral pentagon, a polygon crossing the
/// horizon, a tiny far triangle, a large hexagon just above the shading point.
fn polygons() -> Vec<Vec<SpheraVec3>> {
    let regular = |n: usize, c: [f32; 3], r: f32, tilt: f32| -> Vec<SpheraVec3> {
        (0..n)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / n as f64;
                let (s, co) = (t.sin() as f32, t.cos() as f32);
                v3(c[0] + r * co, c[1] + r * s, c[2] + tilt * r * co)
            })
            .collect()
    };
    vec![
        vec![
            v3(-1.0, -1.0, 1.0),
            v3(1.0, -1.0, 1.0),
            v3(1.0, 1.0, 1.0),
            v3(-1.0, 1.0, 1.0),
        ],
        regular(5, [1.5, 0.3, 1.0], 0.6, 0.2),
        regular(6, [0.0, 2.0, 0.2], 1.0, 0.5),
        regular(3, [0.3, 0.0, 1e4], 0.5, 0.0),
        regular(6, [0.0, 0.0, 1e-3], 5.0, 0.0),
    ]
}

/// The random-number pairs: both ends of [0, 1), the middle, and a few inside.
const PAIRS: [(f32, f32); 6] = [
    (0.0, 0.0),
    (0.5, 0.5),
    (0.999_999_94, 0.999_999_94),
    (0.125, 0.875),
    (0.7, 0.3),
    (0.333_333_34, 0.1),
];

/// The text of the table (deterministic: the same bits on every run of the same build).
pub fn table() -> String {
    let mut out = String::from(
        "# sphera determinism table: f32 bit patterns in hex. Regenerate with\n\
         # `cargo run -p sphera-tools --bin generate_determinism_table`; format in\n\
         # tools/src/determinism.rs.\n",
    );
    let mut ltc = std::mem::MaybeUninit::<Ltc>::uninit();
    // SAFETY: `out` is writable; `sphera_ltc_ggx` writes it.
    let ltc = unsafe {
        sphera_ltc_ggx(ltc.as_mut_ptr(), v3(0.3, 0.1, 0.9), 0.4);
        ltc.assume_init()
    };
    let material = Material {
        diffuse: sphera::Vec3::splat(0.5),
        f0: sphera::Vec3::splat(0.04),
        roughness: 0.4,
    };
    for (id, polygon) in polygons().iter().enumerate() {
        write!(out, "polygon {id} {}", polygon.len()).unwrap();
        for v in polygon {
            write!(out, " {}", hex3(*v)).unwrap();
        }
        out.push('\n');
        let (ptr, n) = (polygon.as_ptr(), polygon.len() as u32);
        macro_rules! family {
            ($name:expr, $t:ty, $prepare:expr, $sample:expr) => {{
                let mut value = std::mem::MaybeUninit::<$t>::uninit();
                // SAFETY: valid pointers; prepare always writes `out`.
                let value = unsafe {
                    $prepare(value.as_mut_ptr(), ptr, n);
                    value.assume_init()
                };
                for (u0, u1) in PAIRS {
                    // SAFETY: `value` was prepared above.
                    let s = unsafe { $sample(&value, u0, u1) };
                    writeln!(
                        out,
                        "{} {id} {} {} {} {}",
                        $name,
                        hex(u0),
                        hex(u1),
                        hex3(s.dir),
                        hex(s.pdf)
                    )
                    .unwrap();
                }
            }};
        }
        family!(
            "solid_angle",
            SolidAnglePolygon,
            sphera_solid_angle_polygon_prepare,
            sphera_solid_angle_polygon_sample
        );
        family!(
            "turk",
            TurkPolygon,
            sphera_turk_polygon_prepare,
            sphera_turk_polygon_sample
        );
        family!(
            "arvo",
            ArvoPolygon,
            sphera_arvo_polygon_prepare,
            sphera_arvo_polygon_sample
        );
        family!(
            "hart_bilinear",
            HartBilinearPolygon,
            sphera_hart_bilinear_polygon_prepare,
            sphera_hart_bilinear_polygon_sample
        );
        family!(
            "hart_biquadratic",
            HartBiquadraticPolygon,
            sphera_hart_biquadratic_polygon_prepare,
            sphera_hart_biquadratic_polygon_sample
        );
        family!(
            "clipped_solid_angle",
            ClippedSolidAnglePolygon,
            sphera_clipped_solid_angle_polygon_prepare,
            sphera_clipped_solid_angle_polygon_sample
        );
        family!(
            "projected",
            ProjectedSolidAnglePolygon,
            sphera_projected_polygon_prepare,
            sphera_projected_polygon_sample
        );
        family!(
            "projected_fast",
            ProjectedSolidAnglePolygon,
            sphera_projected_polygon_prepare_fast,
            sphera_projected_polygon_sample_fast
        );
        family!(
            "arvo_projected",
            ArvoProjectedPolygon,
            sphera_arvo_projected_polygon_prepare,
            sphera_arvo_projected_polygon_sample
        );
        let ltc_prepare = |out: *mut LtcPolygon, v: *const SpheraVec3, n: u32| {
            // SAFETY: forwarded.
            unsafe { sphera_ltc_polygon_prepare(out, &ltc, v, n) }
        };
        family!("ltc", LtcPolygon, ltc_prepare, sphera_ltc_polygon_sample);
        let mut light = std::mem::MaybeUninit::<PolygonLight>::uninit();
        // SAFETY: valid pointers.
        let light = unsafe {
            sphera_polygon_light_prepare(
                light.as_mut_ptr(),
                ptr,
                n,
                v3(0.3, 0.1, 0.9),
                &material,
                SPHERA_MIS_CLAMPED_OPTIMAL,
                0.5,
            );
            light.assume_init()
        };
        for technique in 0..2u32 {
            for (u0, u1) in PAIRS {
                // SAFETY: prepared above.
                let s = unsafe { sphera_polygon_light_sample(&light, technique, u0, u1) };
                writeln!(
                    out,
                    "light {id} {technique} {} {} {} {} {} {}",
                    hex(u0),
                    hex(u1),
                    hex3(s.dir.into()),
                    hex(s.pdf),
                    hex3(s.visible.into()),
                    hex3(s.unoccluded.into())
                )
                .unwrap();
            }
        }
    }
    let views = [v3(0.0, 0.0, 1.0), v3(0.6, 0.0, 0.8), v3(0.1, -0.99, 0.05)];
    for roughness in [0.05f32, 0.4, 1.0] {
        let mut brdf = std::mem::MaybeUninit::<GgxBrdf>::uninit();
        // SAFETY: writable.
        let brdf = unsafe {
            sphera_ggx_brdf_prepare(brdf.as_mut_ptr(), roughness, v3(1.0, 1.0, 1.0));
            brdf.assume_init()
        };
        for wo in views {
            for (u0, u1) in PAIRS {
                // SAFETY: prepared above.
                let s = unsafe { sphera_ggx_sample(&brdf, wo, u0, u1) };
                writeln!(
                    out,
                    "ggx {} {} {} {} {} {}",
                    hex(roughness),
                    hex3(wo),
                    hex(u0),
                    hex(u1),
                    hex3(s.dir),
                    hex(s.pdf)
                )
                .unwrap();
            }
        }
    }
    for (u0, u1) in PAIRS {
        let s = sphera_lambert_sample(u0, u1);
        writeln!(
            out,
            "lambert {} {} {} {}",
            hex(u0),
            hex(u1),
            hex3(s.dir),
            hex(s.pdf)
        )
        .unwrap();
    }
    let spheres = [
        (v3(0.0, 0.0, 3.0), 1.0f32),
        (v3(1e3, 20.0, 5.0), 0.178),
        (v3(0.2, 0.1, 0.3), 1.0),
    ];
    for (center, radius) in spheres {
        let cap = sphera_cap_from_sphere(center, radius);
        for (u0, u1) in PAIRS {
            let s = sphera_cap_sample_uniform(cap, u0, u1);
            writeln!(
                out,
                "cap {} {} {} {} {} {}",
                hex3(center),
                hex(radius),
                hex(u0),
                hex(u1),
                hex3(s.dir),
                hex(s.pdf)
            )
            .unwrap();
        }
    }
    for g in [-0.7f32, 0.0, 0.3, 0.95] {
        for wo in [v3(0.0, 0.0, 1.0), v3(0.48, -0.6, 0.64)] {
            for (u0, u1) in PAIRS {
                let a = sphera_phase_pivot_sample(wo, g, u0, u1);
                let b = sphera_phase_henyey_greenstein_sample(wo, g, u0, u1);
                for (name, s) in [("pivot_phase", a), ("hg_phase", b)] {
                    writeln!(
                        out,
                        "{name} {} {} {} {} {} {}",
                        hex3(wo),
                        hex(g),
                        hex(u0),
                        hex(u1),
                        hex3(s.dir),
                        hex(s.pdf)
                    )
                    .unwrap();
                }
            }
        }
    }
    out
}
