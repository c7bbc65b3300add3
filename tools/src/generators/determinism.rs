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
//! - `pivot_phase` and `hg_phase <wo xyz> <g> <u0> <u1> <dir xyz> <pdf>`;
//! - `sptd_in_cap <base> <pivot xyz> <axis xyz> <center xyz> <radius> <u0> <u1> <dir xyz>
//!   <pdf> <pdf(dir)> <integral>` (an SPTD restricted to a sphere light's cap);
//! - `phase_in_cap <wo xyz> <g> <center xyz> <radius> <u0> <u1> <dir xyz> <pdf>`;
//! - `light_sampler <center xyz> <radius> <wo xyz> <roughness> <u0> <u1> <dir xyz> <pdf>
//!   <pdf(dir)>` (the joint SPTD sampler of a sphere light);
//! - `sphere_shade <wo xyz> <roughness> <f0 xyz> <center xyz> <radius> <cone axis xyz>
//!   <cone cos> <shade xyz> <shade_occluded xyz>` (real-time shading);
//! - `vmf <axis xyz> <sharpness> <u0> <u1> <dir xyz> <pdf>`;
//! - `sg_pair <a: axis xyz sharpness amplitude> <b: …> <product: axis xyz sharpness
//!   log_amplitude> <inner product>`;
//! - `sg_shading <sg: axis xyz sharpness amplitude> <normal xyz> <view xyz> <roughness>
//!   <mean xyz> <variance> <incoming: axis xyz sharpness log_amplitude> <ASG × SG>
//!   <specular ASG> <specular SG> <diffuse product> <diffuse constant cosine>
//!   <diffuse sharp lobe>` (the GGX ASG of α = roughness², f0 0.04, r_d 0.5, visibility 1);
//! - `vpl <id> <position xyz> <normal xyz> <power xyz> <R_d xyz> <R_s xyz>
//!   <toward_incoming xyz> <roughness>`: a VPL;
//! - `vsgl_finish <first id> <count> <VSGL>`: the accumulator of VPLs first..first+count
//!   about the origin, finished (`<VSGL>`: diffuse SG axis xyz sharpness log_amplitude,
//!   specular SG likewise, diffuse power xyz, specular power xyz, mean xyz, variance);
//! - `fis <cluster_count> <kernel_scale> <iterations> <u0> <u1> <VSGL>`: FIS selection on
//!   the 2×2 pyramid of VPLs 0..4 about the origin (level 1 summed by an accumulator).
//!
//! To add a family: a record type here and its case in the C test.

use std::fmt::Write;

use sphera::brdf::{GgxBrdf, Ltc};
use sphera::ffi::*;
use sphera::polygon::LtcPolygon;
use sphera::polygon::baselines::{
    ArvoPolygon, ArvoProjectedPolygon, HartBilinearPolygon, HartBiquadraticPolygon, TurkPolygon,
};
use sphera::polygon::light::{Material, PolygonLight};
use sphera::polygon::{ClippedSolidAnglePolygon, ProjectedPolygon, SolidAnglePolygon};
use sphera::sg::Sg;
use sphera::sphere::{SphereLightSampler, SphereLightShading, SptdInCap};
use sphera::vsgl::{Vpl, Vsgl, VsglAccumulator, VsglTexel};

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
         # tools/src/generators/determinism.rs.\n",
    );
    let mut ltc = std::mem::MaybeUninit::<Ltc>::uninit();
    // SAFETY: `out` is writable; `sphera_ltc_prepare` writes it.
    let ltc = unsafe {
        sphera_ltc_prepare(ltc.as_mut_ptr(), v3(0.3, 0.1, 0.9), 0.4);
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
                    sample_record(&mut out, format!("{} {id}", $name), u0, u1, s);
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
            ProjectedPolygon,
            sphera_projected_polygon_prepare,
            sphera_projected_polygon_sample
        );
        family!(
            "projected_fast",
            ProjectedPolygon,
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
                let s = unsafe { sphera_ggx_brdf_sample(&brdf, wo, u0, u1) };
                let head = format!("ggx {} {}", hex(roughness), hex3(wo));
                sample_record(&mut out, head, u0, u1, s);
            }
        }
    }
    for (u0, u1) in PAIRS {
        let s = sphera_lambert_sample(u0, u1);
        sample_record(&mut out, "lambert".into(), u0, u1, s);
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
            let head = format!("cap {} {}", hex3(center), hex(radius));
            sample_record(&mut out, head, u0, u1, s);
        }
    }
    for g in [-0.7f32, 0.0, 0.3, 0.95] {
        for wo in [v3(0.0, 0.0, 1.0), v3(0.48, -0.6, 0.64)] {
            for (u0, u1) in PAIRS {
                let a = sphera_phase_pivot_sample(wo, g, u0, u1);
                let b = sphera_phase_henyey_greenstein_sample(wo, g, u0, u1);
                for (name, s) in [("pivot_phase", a), ("hg_phase", b)] {
                    let head = format!("{name} {} {}", hex3(wo), hex(g));
                    sample_record(&mut out, head, u0, u1, s);
                }
            }
        }
    }
    sphere_records(&mut out);
    sg_records(&mut out);
    vsgl_records(&mut out);
    out
}

/// A record `<head> <u0> <u1> <dir xyz> <pdf>`.
fn sample_record(out: &mut String, head: String, u0: f32, u1: f32, s: SpheraSample) {
    writeln!(
        out,
        "{head} {} {} {} {}",
        hex(u0),
        hex(u1),
        hex3(s.dir),
        hex(s.pdf)
    )
    .unwrap();
}

fn hex_sg(g: Sg) -> String {
    format!(
        "{} {} {}",
        hex3(g.axis.into()),
        hex(g.sharpness),
        hex(g.log_amplitude)
    )
}

fn hex_vsgl(v: &Vsgl) -> String {
    format!(
        "{} {} {} {} {} {}",
        hex_sg(v.diffuse),
        hex_sg(v.specular),
        hex3(v.diffuse_power.into()),
        hex3(v.specular_power.into()),
        hex3(v.mean.into()),
        hex(v.variance)
    )
}

/// Writes `prepare`'s struct (which every prepare of the C ABI writes, also on failure).
fn prepared<T>(prepare: impl FnOnce(*mut T) -> bool) -> T {
    let mut value = std::mem::MaybeUninit::<T>::uninit();
    prepare(value.as_mut_ptr());
    // SAFETY: the C ABI's prepare functions write `out` whenever it is non-null.
    unsafe { value.assume_init() }
}

/// Sphere lights: SPTDs in caps, the pivot phase function in a cap, the joint light
/// sampler and real-time shading.
fn sphere_records(out: &mut String) {
    let spheres = [
        (v3(0.0, 0.0, 3.0), 1.0f32),
        (v3(2.0, 0.5, 0.4), 0.5),
        (v3(0.2, 0.1, 0.3), 1.0),
    ];
    let pivots = [v3(0.0, 0.0, 0.0), v3(0.3, -0.2, 0.5), v3(-0.9, 0.1, 0.2)];
    let axis = v3(0.0, 0.6, 0.8);
    for base in [SPHERA_SPTD_UNIFORM, SPHERA_SPTD_CLAMPED_COSINE] {
        for pivot in pivots {
            for (center, radius) in spheres {
                let cap = sphera_cap_from_sphere(center, radius);
                // SAFETY: `out` is writable.
                let value: SptdInCap =
                    prepared(|o| unsafe { sphera_sptd_in_cap_prepare(o, pivot, base, axis, cap) });
                for (u0, u1) in PAIRS {
                    // SAFETY: prepared above.
                    let (s, p, integral) = unsafe {
                        let s = sphera_sptd_in_cap_sample(&value, u0, u1);
                        let p = sphera_sptd_in_cap_pdf(&value, s.dir);
                        (s, p, sphera_sptd_in_cap_integral(&value))
                    };
                    writeln!(
                        out,
                        "sptd_in_cap {base} {} {} {} {} {} {} {} {} {} {}",
                        hex3(pivot),
                        hex3(axis),
                        hex3(center),
                        hex(radius),
                        hex(u0),
                        hex(u1),
                        hex3(s.dir),
                        hex(s.pdf),
                        hex(p),
                        hex(integral)
                    )
                    .unwrap();
                }
            }
        }
    }
    let views = [v3(0.0, 0.0, 1.0), v3(0.6, 0.0, 0.8), v3(0.1, -0.99, 0.05)];
    for wo in views {
        for g in [-0.5f32, 0.3, 0.9] {
            let (center, radius) = spheres[(g > 0.0) as usize];
            let cap = sphera_cap_from_sphere(center, radius);
            // SAFETY: `out` is writable.
            let value: SptdInCap =
                prepared(|o| unsafe { sphera_sptd_in_cap_prepare_pivot_phase(o, wo, g, cap) });
            for (u0, u1) in PAIRS {
                // SAFETY: prepared above.
                let s = unsafe { sphera_sptd_in_cap_sample(&value, u0, u1) };
                let head = format!(
                    "phase_in_cap {} {} {} {}",
                    hex3(wo),
                    hex(g),
                    hex3(center),
                    hex(radius)
                );
                sample_record(out, head, u0, u1, s);
            }
        }
        for roughness in [0.05f32, 0.4, 1.0] {
            for (center, radius) in spheres {
                // SAFETY: `out` is writable.
                let sampler: SphereLightSampler = prepared(|o| unsafe {
                    sphera_sphere_light_sampler_prepare(o, center, radius, wo, roughness)
                });
                for (u0, u1) in PAIRS {
                    // SAFETY: prepared above.
                    let (s, p) = unsafe {
                        let s = sphera_sphere_light_sampler_sample(&sampler, u0, u1);
                        (s, sphera_sphere_light_sampler_pdf(&sampler, s.dir))
                    };
                    writeln!(
                        out,
                        "light_sampler {} {} {} {} {} {} {} {} {}",
                        hex3(center),
                        hex(radius),
                        hex3(wo),
                        hex(roughness),
                        hex(u0),
                        hex(u1),
                        hex3(s.dir),
                        hex(s.pdf),
                        hex(p)
                    )
                    .unwrap();
                }
                let f0 = v3(0.04, 0.5, 1.0);
                let cone_axis = v3(0.0, 0.6, 0.8);
                let cone_cos = 0.2f32;
                // SAFETY: `out` is writable; then valid pointers.
                let (shade, occluded) = unsafe {
                    let shading: SphereLightShading =
                        prepared(|o| sphera_sphere_light_shading_prepare(o, wo, roughness, f0));
                    let light = sphera_cap_from_sphere(center, radius);
                    let cone = sphera_cap_from_axis_cos(cone_axis, cone_cos);
                    (
                        sphera_sphere_light_shading_eval(&shading, light),
                        sphera_sphere_light_shading_eval_occluded(&shading, light, cone),
                    )
                };
                writeln!(
                    out,
                    "sphere_shade {} {} {} {} {} {} {} {} {}",
                    hex3(wo),
                    hex(roughness),
                    hex3(f0),
                    hex3(center),
                    hex(radius),
                    hex3(cone_axis),
                    hex(cone_cos),
                    hex3(shade),
                    hex3(occluded)
                )
                .unwrap();
            }
        }
    }
}

/// SGs: vMF sampling, products and inner products, the ASG convolution, incoming
/// radiance and the shading forms.
fn sg_records(out: &mut String) {
    let lobes = [
        (v3(0.0, 0.0, 1.0), 0.5f32, 1.0f32),
        (v3(0.6, 0.0, 0.8), 20.0, 3.0),
        (v3(-0.48, 0.6, 0.64), 2000.0, 0.25),
        (v3(0.0, 1.0, 0.0), 1e-3, 7.0),
    ];
    for (axis, sharpness, amplitude) in lobes {
        let sg = sphera_sg_new(axis, sharpness, amplitude);
        for (u0, u1) in PAIRS {
            let s = sphera_vmf_sample(sg, u0, u1);
            let head = format!("vmf {} {}", hex3(axis), hex(sharpness));
            sample_record(out, head, u0, u1, s);
        }
        for (axis_b, sharpness_b, amplitude_b) in lobes {
            let other = sphera_sg_new(axis_b, sharpness_b, amplitude_b);
            writeln!(
                out,
                "sg_pair {} {} {} {} {} {} {} {}",
                hex3(axis),
                hex(sharpness),
                hex(amplitude),
                hex3(axis_b),
                hex(sharpness_b),
                hex(amplitude_b),
                hex_sg(sphera_sg_product(sg, other)),
                hex(sphera_sg_inner_product(sg, other))
            )
            .unwrap();
        }
        let normals = [v3(0.0, 0.0, 1.0), v3(0.0, 0.8, 0.6)];
        let views = [v3(0.6, 0.0, 0.8), v3(-0.1, 0.2, 0.97)];
        for (normal, view) in normals.into_iter().zip(views) {
            for roughness in [0.1f32, 0.5] {
                let mean = v3(0.5, -1.0, 2.0);
                let variance = 0.3f32;
                let incoming = sphera_sg_incoming_radiance(sg, mean, variance);
                let asg = sphera_asg_from_ggx(normal, view, roughness * roughness);
                writeln!(
                    out,
                    "sg_shading {} {} {} {} {} {} {} {} {} {} {} {} {} {} {}",
                    hex3(axis),
                    hex(sharpness),
                    hex(amplitude),
                    hex3(normal),
                    hex3(view),
                    hex(roughness),
                    hex3(mean),
                    hex(variance),
                    hex_sg(incoming),
                    hex(sphera_asg_convolve_sg(asg, incoming)),
                    hex(sphera_sg_specular_shading(
                        incoming, normal, view, roughness, 0.04, 1.0
                    )),
                    hex(sphera_sg_specular_shading_sg(
                        incoming, normal, view, roughness, 0.04, 1.0
                    )),
                    hex(sphera_sg_diffuse_shading_product(
                        incoming, normal, 0.5, 1.0
                    )),
                    hex(sphera_sg_diffuse_shading_constant_cosine(
                        incoming, normal, 0.5, 1.0
                    )),
                    hex(sphera_sg_diffuse_shading_sharp_lobe(
                        incoming, normal, 0.5, 1.0
                    ))
                )
                .unwrap();
            }
        }
    }
}

/// VSGLs: accumulators of VPLs, finished, and FIS cluster selection on a 2×2 pyramid.
fn vsgl_records(out: &mut String) {
    let vpls: Vec<Vpl> = (0..6)
        .map(|k| {
            let t = k as f32;
            Vpl {
                position: sphera::Vec3::new(0.3 * t - 0.5, 1.0 + 0.1 * t, -0.2 * t),
                normal: sphera::Vec3::new(0.1 * t, 1.0, -0.05 * t),
                power: sphera::Vec3::new(1.0 + t, 0.5, 0.25 * t),
                diffuse_reflectance: sphera::Vec3::new(0.5, 0.4, 0.3),
                specular_reflectance: sphera::Vec3::splat(0.04 + 0.1 * t),
                toward_incoming: sphera::Vec3::new(0.2 * t - 0.5, 0.8, 0.3),
                roughness: 0.05 + 0.15 * t,
            }
        })
        .collect();
    for (id, vpl) in vpls.iter().enumerate() {
        writeln!(
            out,
            "vpl {id} {} {} {} {} {} {} {}",
            hex3(vpl.position.into()),
            hex3(vpl.normal.into()),
            hex3(vpl.power.into()),
            hex3(vpl.diffuse_reflectance.into()),
            hex3(vpl.specular_reflectance.into()),
            hex3(vpl.toward_incoming.into()),
            hex(vpl.roughness)
        )
        .unwrap();
    }
    let origin = v3(0.0, 0.0, 0.0);
    for (first, count) in [(0usize, 1usize), (0, 2), (1, 5), (0, 6)] {
        // SAFETY: valid pointers throughout.
        let vsgl = unsafe {
            let mut acc: VsglAccumulator = prepared(|o| sphera_vsgl_accumulator_new(o, origin));
            for vpl in &vpls[first..first + count] {
                sphera_vsgl_accumulator_add_vpl(&mut acc, vpl);
            }
            sphera_vsgl_accumulator_finish(&acc)
        };
        writeln!(out, "vsgl_finish {first} {count} {}", hex_vsgl(&vsgl)).unwrap();
    }
    // The 2×2 pyramid: level 0 from VPLs 0..4, level 1 their sum.
    // SAFETY: valid pointers throughout.
    let pyramid: Vec<VsglTexel> = unsafe {
        let mut level0: Vec<VsglTexel> = vpls[..4]
            .iter()
            .map(|vpl| prepared(|o| sphera_vsgl_texel_from_vpl(vpl, origin, o)))
            .collect();
        let mut acc: VsglAccumulator = prepared(|o| sphera_vsgl_accumulator_new(o, origin));
        for texel in &level0 {
            sphera_vsgl_accumulator_add_texel(&mut acc, texel);
        }
        level0.push(acc.sums);
        level0
    };
    for (clusters, kernel_scale, iterations) in [(1u32, 1.0f32, 8u32), (4, 1.0, 8), (16, 0.5, 0)] {
        for (u0, u1) in PAIRS {
            // SAFETY: `pyramid` holds the 5 texels of a 2×2 map.
            let vsgl = unsafe {
                sphera_vsgl_fis_select(
                    pyramid.as_ptr(),
                    pyramid.len(),
                    2,
                    origin,
                    clusters,
                    kernel_scale,
                    iterations,
                    u0,
                    u1,
                )
            };
            writeln!(
                out,
                "fis {clusters} {} {iterations} {} {} {}",
                hex(kernel_scale),
                hex(u0),
                hex(u1),
                hex_vsgl(&vsgl)
            )
            .unwrap();
        }
    }
}
