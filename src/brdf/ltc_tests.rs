//! Tests of the LTC itself: its density integrates to one, and the GGX table lookup
//! (views below the horizon, clamped roughness, grid nodes, rotation with the view).
//! Its sampling inside polygons is tested in `src/polygon/ltc_tests.rs`.
use super::*;
use crate::testing::*;

#[test]
fn density_integrates_to_one_over_the_sphere() {
    // Midpoint rule in (z, φ): dω = dz dφ. The sharp LTCs need a fine grid near their
    // peak; 3000 × 3000 points suffice for the first three, the last is tested through
    // the polygon integral instead.
    for ltc in &ltcs()[..3] {
        let integral = integrate_over_sphere(3000, |dir| ltc.density(dir) as f64);
        assert!((integral - 1.0).abs() < 2e-3, "{ltc:?}: ∫D = {integral}");
    }
}

#[test]
fn ggx_lookup_rejects_views_below_the_horizon_and_clamps_roughness() {
    for wo in [
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, -0.1),
        Vec3::ZERO,
        Vec3::NAN,
        Vec3::new(f32::INFINITY, 0.0, 1.0),
    ] {
        assert!(Ltc::from_ggx(wo, 0.5).is_none(), "{wo:?}");
    }
    let wo = Vec3::new(0.6, 0.0, 0.8);
    assert_eq!(Ltc::from_ggx(wo, f32::NAN), Ltc::from_ggx(wo, 0.0));
    assert_eq!(Ltc::from_ggx(wo, -1.0), Ltc::from_ggx(wo, 0.0));
    assert_eq!(Ltc::from_ggx(wo, 7.0), Ltc::from_ggx(wo, 1.0));
    assert!(Ltc::from_ggx(Vec3::new(1.0, 0.0, 1e-7), 0.5).is_some());
    assert!(Ltc::from_ggx(Vec3::Z, 0.5).is_some());
}

#[test]
fn ggx_lookup_hits_table_entries_at_grid_nodes_and_rotates_with_the_view() {
    let last = (LTC_TABLE_SIZE - 1) as f32;
    for (i, j) in [(0, 0), (5, 17), (32, 40), (63, 62), (40, 63)] {
        let r = i as f32 / last;
        // t = √(1 − cos θ) = j / 63.
        let t = j as f32 / last;
        let cos_theta = (1.0 - t * t).max(1e-6);
        let sin_theta = (1.0 - cos_theta * cos_theta).sqrt();
        let wo = Vec3::new(sin_theta, 0.0, cos_theta);
        let looked_up = Ltc::from_ggx(wo, r).expect("above the horizon");
        let entry = LTC_TABLE[i * LTC_TABLE_SIZE + j];
        let direct = Ltc::from_view_frame(entry, 1.0, 0.0).expect("valid entry");
        for (a, b) in looked_up.inverse_rows.iter().zip(&direct.inverse_rows) {
            assert!((*a - *b).abs().max_element() <= 2e-4 * b.abs().max_element().max(1.0));
        }
        // Rotating the view about the normal rotates the distribution with it.
        let phi = 2.1f32;
        let (c, s) = (phi.cos(), phi.sin());
        let rotate = |v: Vec3| Vec3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z);
        let rotated = Ltc::from_ggx(rotate(wo), r).expect("above the horizon");
        let mut rng = Rng::new(5);
        for _ in 0..100 {
            let d = rng.unit_vector_f32();
            let (p, q) = (looked_up.density(d), rotated.density(rotate(d)));
            assert!((p - q).abs() <= 1e-3 * p.max(q) + 1e-6, "{p} vs {q}");
        }
    }
}

/// `map_to_cosine_space` (the columns of `M⁻¹` in lanes) is `to_cosine_space` vertex by
/// vertex, bit for bit, for fitted LTCs, the identity and vertices at every scale,
/// zero, huge (overflowing products) and non-finite.
#[test]
fn map_to_cosine_space_is_to_cosine_space() {
    let mut rng = Rng::new(0x45);
    let mut ltcs = ltcs();
    ltcs.push(Ltc::IDENTITY);
    let specials = [
        Vec3::ZERO,
        Vec3::new(-0.0, 0.0, -0.0),
        Vec3::new(3e38, -3e38, 1.0),
        Vec3::new(f32::INFINITY, 1.0, 0.0),
        Vec3::new(0.0, f32::NAN, 2.0),
        Vec3::new(1e-40, -1e-45, 1e-39),
    ];
    for ltc in &ltcs {
        for trial in 0..500 {
            let count = 1 + trial % 8;
            let scale = [1e-30f32, 1e-3, 1.0, 1e4, 1e30][trial % 5];
            let mut vertices: Vec<Vec3> = (0..count).map(|_| rng.cube() * scale).collect();
            if trial % 3 == 0 {
                vertices[trial / 3 % count] = specials[trial / 3 % specials.len()];
            }
            let mut out = [Vec3::NAN; 8];
            ltc.map_to_cosine_space(&vertices, &mut out);
            for (v, t) in vertices.iter().zip(&out) {
                assert_eq!(
                    t.to_array().map(f32::to_bits),
                    ltc.to_cosine_space(*v).to_array().map(f32::to_bits),
                    "{ltc:?} {v:?}"
                );
            }
            // Nothing written past the vertices.
            assert!(out[count..].iter().all(|t| t.x.is_nan()));
        }
    }
}

/// `Ltc::is_finite` (a sum of `0·x` in lanes) is the field-by-field test, for finite
/// values of every size and with infinities and NaNs of both signs in every field, one
/// or two at a time.
#[test]
fn is_finite_is_by_field() {
    let mut rng = Rng::new(0x46);
    let specials = [
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -f32::NAN,
        f32::MAX,
        -f32::MAX,
        -0.0,
        1e-45,
    ];
    let mut non_finite = 0;
    for trial in 0..20_000 {
        let mut values = [0.0f32; 20];
        for v in &mut values {
            *v = rng.range(-1.0, 1.0) * [1e-30f32, 1.0, 1e30][trial % 3];
        }
        for k in 0..trial % 3 {
            let slot = (trial / 3 + 7 * k) % 20;
            values[slot] = specials[(trial / 60 + k) % specials.len()];
        }
        let vec3 = |k: usize| Vec3::new(values[k], values[k + 1], values[k + 2]);
        let ltc = Ltc {
            inverse_rows: [vec3(0), vec3(3), vec3(6)],
            matrix_columns: [vec3(9), vec3(12), vec3(15)],
            inverse_determinant: 1.0,
            albedo: values[18],
            fresnel: values[19],
        };
        assert_eq!(ltc.is_finite(), ltc.is_finite_by_field(), "{values:?}");
        non_finite += !ltc.is_finite() as u32;
    }
    assert!(non_finite > 5000, "only {non_finite} non-finite cases");
}

/// `Ltc::from_ggx` reads the table from the guessed row (`table_row_guess`): the bits of
/// the former lookup (`table_bilinear` at the exact coordinates) for unit views and for
/// views of other lengths (whose guesses are wrong and take the checked fallback), and
/// the guess is the exact coordinate's cell for at least 99.9% of unit views.
#[test]
fn the_ltc_s_guessed_row_gives_the_former_lookup_s_bits() {
    use crate::brdf::{ALONG_Y_FIRST, table_bilinear, table_coordinates, table_row_guess};
    let former = |wo: Vec3, roughness: f32| -> Option<Ltc> {
        let (x, y, cos_phi, sin_phi) = table_coordinates(wo, roughness)?;
        let entry = table_bilinear::<6, ALONG_Y_FIRST>(&LTC_TABLE, LTC_TABLE_SIZE, x, y);
        Ltc::from_view_frame(entry, cos_phi, sin_phi)
    };
    let bits = |l: Option<Ltc>| {
        l.map(|l| {
            let rows = l.inverse_rows.map(|r| r.to_array().map(f32::to_bits));
            let columns = l.matrix_columns.map(|c| c.to_array().map(f32::to_bits));
            let scalars = [l.inverse_determinant, l.albedo, l.fresnel].map(f32::to_bits);
            (rows, columns, scalars)
        })
    };
    check_guessed_row_views(
        4619,
        |scaled, roughness| {
            assert_eq!(
                bits(Ltc::from_ggx(scaled, roughness)),
                bits(former(scaled, roughness)),
                "{scaled:?} {roughness}"
            )
        },
        |wo, roughness| {
            let last_cell = LTC_TABLE_SIZE as u32 - 2;
            let guess = table_row_guess(wo) as u32;
            table_coordinates(wo, roughness)
                .map(|(_, y, _, _)| guess.min(last_cell) == (y as u32).min(last_cell))
        },
    );
}

/// `from_cosine_space` in lanes (the columns loaded with the next word of the value) is
/// the `Vec3` sum `(c_0 v_x + c_1 v_y) + c_2 v_z` bit for bit (NaN for NaN), for the
/// LTCs of the table, for random matrices of every scale and with infinite entries, and
/// for directions with zero, tiny, huge and infinite coordinates.
#[test]
fn from_cosine_space_is_the_column_sum() {
    let mut rng = Rng::new(0x47);
    let specials = [f32::INFINITY, -0.0, 1e-45, f32::MAX, 1e30, -1e-30];
    let check = |ltc: &Ltc, v: Vec3| {
        let [c0, c1, c2] = ltc.matrix_columns;
        let expected = c0 * v.x + c1 * v.y + c2 * v.z;
        let got = ltc.from_cosine_space(v);
        for k in 0..3 {
            assert!(
                got[k].to_bits() == expected[k].to_bits()
                    || (got[k].is_nan() && expected[k].is_nan()),
                "{ltc:?} {v:?}: {got:?} against {expected:?}"
            );
        }
    };
    let mut ltcs = crate::testing::ltcs();
    for trial in 0..20_000 {
        let scale = [1e-30f32, 1.0, 1e30][trial % 3];
        let mut values = [0.0f32; 21];
        for v in &mut values {
            *v = rng.range(-1.0, 1.0) * scale;
        }
        if trial % 5 == 0 {
            values[rng.below(21) as usize] = specials[rng.below(specials.len() as u64) as usize];
        }
        let vec3 = |k: usize| Vec3::new(values[k], values[k + 1], values[k + 2]);
        ltcs.push(Ltc {
            inverse_rows: [vec3(0), vec3(3), vec3(6)],
            matrix_columns: [vec3(9), vec3(12), vec3(15)],
            inverse_determinant: values[18],
            albedo: values[19],
            fresnel: values[20],
        });
    }
    for ltc in &ltcs {
        for k in 0..4 {
            let mut v = rng.unit_vector_f32();
            if k == 3 {
                v[rng.below(3) as usize] = specials[rng.below(specials.len() as u64) as usize];
            }
            check(ltc, v);
        }
    }
}
