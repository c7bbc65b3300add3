use super::accumulator::*;
use super::fis::*;
use crate::testing::{CHI_SQUARE_ALPHA, Estimate, Rng, chi_square};
use glam::Vec3;

/// The mip pyramid of a `size × size` level 0 (row-major): each texel of level `l + 1`
/// the sum of its four children.
fn build_pyramid(level0: &[VsglTexel], size: u32) -> Vec<VsglTexel> {
    let mut texels = level0.to_vec();
    texels.resize(VsglPyramid::texel_count(size), VsglTexel::ZERO);
    assert!(VsglPyramid::fill_levels(&mut texels, size));
    texels
}

/// A `size²` RSM of random VPLs around `origin`, with some black texels (about
/// `holes` of them) and an optional single hue.
fn random_rsm(rng: &mut Rng, size: u32, origin: Vec3, holes: f64, grey: bool) -> Vec<VsglTexel> {
    (0..size * size)
        .map(|k| {
            if rng.uniform() < holes {
                return VsglTexel::ZERO;
            }
            let (x, y) = ((k % size) as f32, (k / size) as f32);
            let brightness = 0.1 + 10.0 * rng.uniform_f32() * rng.uniform_f32();
            let colour = if grey {
                Vec3::ONE
            } else {
                Vec3::new(rng.uniform_f32(), rng.uniform_f32(), rng.uniform_f32()) + 0.05
            };
            let normal = (rng.unit_vector_f32() + Vec3::new(0.0, 0.0, 2.0)).normalize();
            let vpl = Vpl {
                position: origin + Vec3::new(x, y, rng.uniform_f32()),
                normal,
                power: colour * brightness,
                diffuse_reflectance: Vec3::splat(0.7),
                specular_reflectance: Vec3::splat(0.04),
                toward_incoming: Vec3::Z,
                roughness: 0.3,
            };
            VsglTexel::from_vpl(&vpl, origin).unwrap()
        })
        .collect()
}

#[test]
fn pyramid_layout_and_validation() {
    for log2 in 0..=6u32 {
        let size = 1 << log2;
        let texels = vec![VsglTexel::ZERO; VsglPyramid::texel_count(size)];
        let pyramid = VsglPyramid::new(&texels, size, Vec3::ZERO).unwrap();
        assert_eq!(pyramid.top_level(), log2);
        let mut offset = 0;
        for level in 0..=log2 {
            assert_eq!(pyramid.level_offset(level), offset);
            offset += (pyramid.level_size(level) * pyramid.level_size(level)) as usize;
        }
        assert_eq!(offset, texels.len());
        assert!(VsglPyramid::new(&texels[..texels.len() - 1], size, Vec3::ZERO).is_none());
        assert!(VsglPyramid::new(&texels, size, Vec3::splat(f32::NAN)).is_none());
        // An all-black map has no cluster.
        assert!(fis_cluster(&pyramid, 4, 1.0, 8, [0.5, 0.5]).is_none());
        assert!(fis_select(&pyramid, 4, 1.0, 8, [0.5, 0.5]).is_empty());
    }
    for size in [0, 3, 6, 12, 1 << 15, u32::MAX] {
        assert_eq!(VsglPyramid::texel_count(size), 0);
    }
    assert_eq!(VsglPyramid::texel_count(1 << 14), (4usize << 28) / 3);
    // Out-of-range levels and indices are clamped, never a panic.
    let mut texels = vec![VsglTexel::ZERO; VsglPyramid::texel_count(4)];
    texels[2].weight = 1.0;
    texels[20].weight = 5.0;
    let pyramid = VsglPyramid::new(&texels, 4, Vec3::ZERO).unwrap();
    assert_eq!(pyramid.texel(0, 7, 0).weight, 0.0);
    assert_eq!(pyramid.texel(0, 2, 0).weight, 1.0);
    assert_eq!(pyramid.texel(0, 2, u32::MAX).weight, 0.0);
    assert_eq!(pyramid.texel(99, 5, 5).weight, 5.0);
    assert_eq!(pyramid.level_size(40), 1);
    let texels = vec![VsglTexel::ZERO; 100];
    for size in [0, 3, 6, 12] {
        assert!(VsglPyramid::new(&texels, size, Vec3::ZERO).is_none());
    }
    assert!(VsglPyramid::new(&[], 1, Vec3::ZERO).is_none());
}

#[test]
fn mip_texels_are_the_sums_of_their_children() {
    let mut rng = Rng::new(21);
    let size = 8;
    let texels = build_pyramid(&random_rsm(&mut rng, size, Vec3::ZERO, 0.2, false), size);
    let pyramid = VsglPyramid::new(&texels, size, Vec3::ZERO).unwrap();
    // The top texel's VSGL equals the VSGL of all level-0 texels summed one by one.
    let mut all = VsglAccumulator::new(Vec3::ZERO);
    for y in 0..size {
        for x in 0..size {
            all.add_texel(pyramid.texel(0, x, y));
        }
    }
    let mut top = VsglAccumulator::new(Vec3::ZERO);
    top.add_texel(pyramid.texel(pyramid.top_level(), 0, 0));
    let (a, b) = (all.finish(), top.finish());
    assert!((a.mean - b.mean).length() < 1e-4);
    assert!((a.variance - b.variance).abs() < 1e-4 * a.variance);
    assert!((a.diffuse_power - b.diffuse_power).length() < 1e-5 * a.diffuse_power.length());
}

#[test]
fn cluster_positions_follow_the_importance() {
    let mut rng = Rng::new(22);
    let size = 16;
    let mut level0 = random_rsm(&mut rng, size, Vec3::ZERO, 0.3, false);
    // One very dim texel next to bright ones.
    level0[5].weight *= 1e-3;
    let texels = build_pyramid(&level0, size);
    let pyramid = VsglPyramid::new(&texels, size, Vec3::ZERO).unwrap();
    let total: f64 = level0.iter().map(|t| t.weight as f64).sum();
    let probabilities: Vec<f64> = level0.iter().map(|t| t.weight as f64 / total).collect();
    let mut counts = vec![0u64; level0.len()];
    for _ in 0..400_000 {
        let (position, texel) = pyramid
            .sample_position([rng.uniform_f32(), rng.uniform_f32()])
            .unwrap();
        // The position lies inside the texel it reports.
        for axis in 0..2 {
            let t = position[axis] * size as f32;
            assert!(t >= texel[axis] as f32 && t <= (texel[axis] + 1) as f32);
        }
        counts[(texel[1] * size + texel[0]) as usize] += 1;
    }
    for (count, texel) in counts.iter().zip(&level0) {
        if texel.weight == 0.0 {
            assert_eq!(*count, 0, "a black texel was chosen");
        }
    }
    let (statistic, dof, p) = chi_square(&counts, &probabilities);
    assert!(
        p > CHI_SQUARE_ALPHA,
        "chi-square {statistic} dof {dof} p {p}"
    );
    // Within a texel the position is uniform: the fractional parts over all draws.
    let mut fractions = vec![0u64; 8];
    for _ in 0..80_000 {
        let (position, texel) = pyramid
            .sample_position([rng.uniform_f32(), rng.uniform_f32()])
            .unwrap();
        let f = position[0] * size as f32 - texel[0] as f32;
        fractions[((f * 8.0) as usize).min(7)] += 1;
    }
    let (statistic, dof, p) = chi_square(&fractions, &[0.125; 8]);
    assert!(
        p > CHI_SQUARE_ALPHA,
        "within texel: {statistic} dof {dof} p {p}"
    );
}

/// The filtered importance in f64, written as a tent filter over the clamped texel
/// coordinate (equivalent to clamp-to-edge bilinear filtering), linear between levels.
fn filtered_importance_f64(pyramid: &VsglPyramid, position: [f32; 2], level: f64) -> f64 {
    let top = pyramid.top_level() as f64;
    let level = level.clamp(0.0, top);
    let lower = level.floor();
    let fraction = level - lower;
    let bilinear = |l: u32| {
        let side = pyramid.level_size(l);
        let coordinate = |x: f32| (x as f64 * side as f64 - 0.5).clamp(0.0, side as f64 - 1.0);
        let (tx, ty) = (coordinate(position[0]), coordinate(position[1]));
        let mut sum = 0.0;
        for y in 0..side {
            for x in 0..side {
                let w =
                    (1.0 - (tx - x as f64).abs()).max(0.0) * (1.0 - (ty - y as f64).abs()).max(0.0);
                sum += w * pyramid.texel(l, x, y).weight as f64;
            }
        }
        sum
    };
    let lower_value = bilinear(lower as u32);
    if fraction > 0.0 {
        (1.0 - fraction) * lower_value + fraction * bilinear((lower as u32 + 1).min(top as u32))
    } else {
        lower_value
    }
}

#[test]
fn the_bisection_finds_the_level_where_the_kernel_mass_crosses_k_over_n() {
    let mut rng = Rng::new(23);
    let size = 32;
    let texels = build_pyramid(&random_rsm(&mut rng, size, Vec3::ZERO, 0.1, false), size);
    let pyramid = VsglPyramid::new(&texels, size, Vec3::ZERO).unwrap();
    let total = pyramid.total_importance() as f64;
    let top = pyramid.top_level() as f64;
    let mut interior = 0;
    for trial in 0..400 {
        let cluster_count = [1u32, 4, 16, 64, 256, 1024, 4096][trial % 7];
        let kernel_scale = [0.5f32, 1.0, 2.0][trial % 3];
        let iterations = [4u32, 8, 12][trial % 3];
        let u = [rng.uniform_f32(), rng.uniform_f32()];
        let cluster = fis_cluster(&pyramid, cluster_count, kernel_scale, iterations, u).unwrap();
        let mass = kernel_scale as f64 / cluster_count as f64;
        // An f64 bisection, independent of the core's.
        let (mut low, mut high) = (0.0f64, top);
        for _ in 0..iterations {
            let middle = 0.5 * (low + high);
            if filtered_importance_f64(&pyramid, cluster.position, middle) < mass * total {
                low = middle;
            } else {
                high = middle;
            }
        }
        let reference = 0.5 * (low + high);
        let step = top / (1u64 << iterations) as f64;
        // Both searches may only part where P(x, l) lies within rounding of K/N.
        if (cluster.level as f64 - reference).abs() > 1e-4 {
            let between = reference.min(cluster.level as f64);
            let p = filtered_importance_f64(&pyramid, cluster.position, between + 0.5 * step);
            assert!(
                (p / (mass * total) - 1.0).abs() < 1e-4,
                "level {} vs f64 {reference} (N {cluster_count})",
                cluster.level
            );
        }
        // The bracket around the level holds the crossing (unless it is at an end).
        let below = filtered_importance_f64(&pyramid, cluster.position, reference - 0.5 * step);
        let above = filtered_importance_f64(&pyramid, cluster.position, reference + 0.5 * step);
        if reference - 0.5 * step > 0.0 {
            assert!(below < mass * total);
        }
        if reference + 0.5 * step < top {
            assert!(above >= mass * total);
            interior += 1;
        }
        // The weight makes the cluster's luminance P/N.
        let expected_weight = total
            / (cluster_count as f64
                * filtered_importance_f64(&pyramid, cluster.position, cluster.level as f64));
        assert!((cluster.weight as f64 / expected_weight - 1.0).abs() < 1e-4);
    }
    assert!(interior > 100, "only {interior} interior levels");
}

#[test]
fn the_clusters_carry_the_total_power() {
    let mut rng = Rng::new(24);
    let size = 16;
    let cluster_count = 8;
    for grey in [true, false] {
        let level0 = random_rsm(&mut rng, size, Vec3::splat(100.0), 0.2, grey);
        let texels = build_pyramid(&level0, size);
        let pyramid = VsglPyramid::new(&texels, size, Vec3::splat(100.0)).unwrap();
        let mut total = [0.0f64; 3];
        let mut total_weight = 0.0;
        for t in &level0 {
            let p = t.diffuse_power + t.specular_power;
            for c in 0..3 {
                total[c] += p[c] as f64;
            }
            total_weight += t.weight as f64;
        }
        let mut estimates = [
            Estimate::default(),
            Estimate::default(),
            Estimate::default(),
        ];
        for _ in 0..20_000 {
            let mut sum = Vec3::ZERO;
            for _ in 0..cluster_count {
                let u = [rng.uniform_f32(), rng.uniform_f32()];
                let vsgl = fis_select(&pyramid, cluster_count, 1.0, 8, u);
                sum += vsgl.diffuse_power + vsgl.specular_power;
            }
            // The luminance of the N clusters is the total every time.
            assert!((luminance(sum) as f64 / total_weight - 1.0).abs() < 1e-4);
            for c in 0..3 {
                estimates[c].add(sum[c] as f64);
            }
        }
        for c in 0..3 {
            let bias = estimates[c].mean() / total[c] - 1.0;
            println!(
                "grey {grey}: channel {c} relative bias {bias:.2e} ± {:.1e}",
                estimates[c].standard_error() / total[c]
            );
            if grey {
                estimates[c].assert_mean_is(total[c], 5.0, 1e-4, "grey RSM power");
            } else {
                // Hues vary per texel: the ratio estimator is biased, by a few percent
                // at most on this map.
                assert!(bias.abs() < 0.05, "channel {c}: bias {bias}");
            }
        }
    }
}

#[test]
fn kernel_mass_extremes_pick_the_end_levels() {
    let mut rng = Rng::new(25);
    let size = 16;
    let texels = build_pyramid(&random_rsm(&mut rng, size, Vec3::ZERO, 0.0, true), size);
    let pyramid = VsglPyramid::new(&texels, size, Vec3::ZERO).unwrap();
    let top = pyramid.top_level() as f32;
    // K/N ≥ 1: the whole map, one cluster holds everything.
    let whole = fis_cluster(&pyramid, 1, 1.0, 16, [0.3, 0.7]).unwrap();
    assert!(whole.level > top - 1e-3);
    assert!((whole.weight - 1.0).abs() < 1e-4);
    // Tiny K/N: level 0.
    let tiny = fis_cluster(&pyramid, 1 << 20, 1.0, 16, [0.3, 0.7]).unwrap();
    assert!(tiny.level < 1e-3);
    // A 1×1 map: the single texel, weight 1/N.
    let single = build_pyramid(&random_rsm(&mut rng, 1, Vec3::ZERO, 0.0, true), 1);
    let pyramid = VsglPyramid::new(&single, 1, Vec3::ZERO).unwrap();
    let cluster = fis_cluster(&pyramid, 4, 1.0, 8, [0.5, 0.5]).unwrap();
    assert_eq!(cluster.level, 0.0);
    assert!((cluster.weight - 0.25).abs() < 1e-6);
}

#[test]
fn bad_parameters_give_no_cluster() {
    let mut rng = Rng::new(26);
    let size = 4;
    let texels = build_pyramid(&random_rsm(&mut rng, size, Vec3::ZERO, 0.0, false), size);
    let pyramid = VsglPyramid::new(&texels, size, Vec3::ZERO).unwrap();
    assert!(fis_cluster(&pyramid, 0, 1.0, 8, [0.5, 0.5]).is_none());
    for k in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert!(fis_cluster(&pyramid, 4, k, 8, [0.5, 0.5]).is_none());
        assert!(fis_select(&pyramid, 4, k, 8, [0.5, 0.5]).is_empty());
    }
    // Random numbers outside [0, 1) or NaN are clamped; 0 iterations are allowed.
    for u in [
        [f32::NAN, 0.5],
        [-1.0, 2.0],
        [1.0, 1.0],
        [f32::INFINITY, f32::NEG_INFINITY],
    ] {
        for iterations in [0, 8, 1000] {
            let cluster = fis_cluster(&pyramid, 4, 1.0, iterations, u).unwrap();
            assert!(cluster.position[0] < 1.0 && cluster.position[1] < 1.0);
            assert!(!cluster.vsgl.is_empty() && cluster.vsgl.mean.is_finite());
        }
    }
    // A texel with a NaN weight is never chosen and does not poison the rest.
    let mut level0 = random_rsm(&mut rng, size, Vec3::ZERO, 0.0, false);
    level0[3].weight = f32::NAN;
    let mut texels = build_pyramid(&level0, size);
    let top = texels.len() - 1;
    texels[top] = level0
        .iter()
        .enumerate()
        .filter(|(k, _)| *k != 3)
        .fold(VsglTexel::ZERO, |a, (_, t)| a.add(t));
    let pyramid = VsglPyramid::new(&texels, size, Vec3::ZERO).unwrap();
    for _ in 0..1000 {
        let u = [rng.uniform_f32(), rng.uniform_f32()];
        let vsgl = fis_select(&pyramid, 4, 1.0, 8, u);
        assert!(vsgl.mean.is_finite() && vsgl.variance.is_finite());
        assert!(vsgl.diffuse_power.is_finite());
    }
}
