//! The size of every prepared polygon struct of the C ABI and the bytes that one
//! `prepare` writes into it (issue 15, items 2 and 3), for triangles, quads, hexagons and
//! heptagons whose zenith lies inside (central) and outside (decentral).
//!
//! Bytes written are measured, not counted from the code: the struct is filled once with
//! `0x55` and once with `0xAA`, the same polygon is prepared into both, and a byte that
//! holds the same value in both afterwards was written by `prepare`.
//!
//! `cargo run --release -p sphera-tools --example prepared_sizes`
use core::mem::{MaybeUninit, size_of};
use sphera::ffi::*;
use sphera::polygon::baselines::{
    ArvoPolygon, ArvoProjectedPolygon, HartBilinearPolygon, TurkPolygon,
};
use sphera::polygon::{
    ClippedSolidAnglePolygon, ProjectedPolygon, SolidAnglePolygon, SolidAngleQuad,
    SolidAngleTriangle,
};

/// Bytes of `T` that `prepare` writes for these vertices (see the module docs).
fn bytes_written<T>(
    prepare: unsafe extern "C" fn(*mut T, *const SpheraVec3, u32) -> bool,
    v: &[SpheraVec3],
) -> usize {
    let mut filled = [MaybeUninit::<T>::uninit(), MaybeUninit::<T>::uninit()];
    for (value, byte) in filled.iter_mut().zip([0x55u8, 0xAA]) {
        // SAFETY: every prepared struct is plain f32 / u32 words; any bit pattern is a
        // value, and prepare overwrites what it uses.
        unsafe {
            value
                .as_mut_ptr()
                .cast::<u8>()
                .write_bytes(byte, size_of::<T>());
            assert!(prepare(value.as_mut_ptr(), v.as_ptr(), v.len() as u32));
        }
    }
    let bytes = |value: &MaybeUninit<T>| {
        // SAFETY: the storage is initialised bytes (filled above).
        unsafe { core::slice::from_raw_parts(value.as_ptr().cast::<u8>(), size_of::<T>()) }
    };
    bytes(&filled[0])
        .iter()
        .zip(bytes(&filled[1]))
        .filter(|(a, b)| a == b)
        .count()
}

/// `count` vertices on an ellipse at height 1, its centre offset by `offset` in x.
fn polygon(count: usize, offset: f32) -> Vec<SpheraVec3> {
    (0..count)
        .map(|k| {
            let a = core::f32::consts::TAU * k as f32 / count as f32 + 0.1;
            SpheraVec3 {
                x: offset + 0.6 * a.cos(),
                y: 0.4 * a.sin(),
                z: 1.0,
            }
        })
        .collect()
}

fn main() {
    type Prepare<T> = unsafe extern "C" fn(*mut T, *const SpheraVec3, u32) -> bool;
    fn row<T>(name: &str, prepare: Prepare<T>) {
        row_of_counts(name, prepare, 8);
    }
    /// A row for a struct that stores at most `most` vertices ("—" for larger polygons).
    fn row_of_counts<T>(name: &str, prepare: Prepare<T>, most: usize) {
        let mut cells = vec![];
        for (count, offset) in [(3, 0.0), (4, 0.0), (6, 0.0), (7, 0.0), (6, 1.5)] {
            cells.push(if count <= most {
                format!("{:>5}", bytes_written(prepare, &polygon(count, offset)))
            } else {
                format!("{:>5}", "—")
            });
        }
        println!(
            "| {name:<30} | {:>5} | {} |",
            size_of::<T>(),
            cells.join(" | ")
        );
    }
    println!(
        "| prepared struct | size (B) | bytes written: tri | quad | hex | hept | hex decentral |"
    );
    println!("|---|---|---|---|---|---|---|");
    row::<SolidAnglePolygon>(
        "SpheraSolidAnglePolygon",
        sphera_solid_angle_polygon_prepare,
    );
    // The fixed sizes take no count: their own vertex count only.
    unsafe extern "C" fn triangle(
        out: *mut SolidAngleTriangle,
        vertices: *const SpheraVec3,
        count: u32,
    ) -> bool {
        assert_eq!(count, 3);
        // SAFETY: forwarded from the caller.
        unsafe { sphera_solid_angle_triangle_prepare(out, vertices) }
    }
    unsafe extern "C" fn quad(
        out: *mut SolidAngleQuad,
        vertices: *const SpheraVec3,
        count: u32,
    ) -> bool {
        // A triangle as a quad with its last vertex repeated.
        let v: Vec<SpheraVec3> = (0..4)
            // SAFETY: `count` readable vertices (3 or 4).
            .map(|k| unsafe { *vertices.add(k.min(count as usize - 1)) })
            .collect();
        // SAFETY: four readable vertices.
        unsafe { sphera_solid_angle_quad_prepare(out, v.as_ptr()) }
    }
    row_of_counts::<SolidAngleTriangle>("SpheraSolidAngleTriangle", triangle, 3);
    row_of_counts::<SolidAngleQuad>("SpheraSolidAngleQuad", quad, 4);
    row::<TurkPolygon>("SpheraTurkPolygon", sphera_turk_polygon_prepare);
    row::<ArvoPolygon>("SpheraArvoPolygon", sphera_arvo_polygon_prepare);
    row::<ClippedSolidAnglePolygon>(
        "SpheraClippedSolidAnglePolygon",
        sphera_clipped_solid_angle_polygon_prepare,
    );
    row::<HartBilinearPolygon>(
        "SpheraHartBilinearPolygon",
        sphera_hart_bilinear_polygon_prepare,
    );
    row::<ProjectedPolygon>("SpheraProjectedPolygon", sphera_projected_polygon_prepare);
    row::<ArvoProjectedPolygon>(
        "SpheraArvoProjectedPolygon",
        sphera_arvo_projected_polygon_prepare,
    );
}
