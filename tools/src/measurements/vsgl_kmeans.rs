//! VSGLs by k-means-style VPL clustering, the comparison of Tokuyoshi 2016, Section 5
//! (std only).
//!
//! As in the paper: `N` cluster centres are sampled among the texels of the RSM with
//! probability proportional to the importance (the texel weight
//! `lum(Φ ∘ (R_d + R_s))`, with replacement), every texel with positive importance is
//! assigned to its closest centre, and each cluster is summed with the accumulator;
//! centres are not updated iteratively. The search is brute force (`O(M N)`; the paper
//! uses a kd-tree, which changes the speed only).
//!
//! **Metric.** Between texels `a` and `b` with image positions `x ∈ [0,1]²` (texel
//! centres) and world positions `y`:
//!
//! `d²(a, b) = ‖x_a − x_b‖² / h_image² + ‖y_a − y_b‖² / h_world²`,
//!
//! with bandwidths `h_image` and `h_world` ([`KMeansMetric`]; by default the spacing of
//! `N` evenly spread centres, `1/√N` in the image and `extent/√N` in the world, since
//! the VPLs lie on surfaces). Ties go to the centre drawn first.

use sphera::Vec3;
use sphera::vsgl::{Vpl, Vsgl, VsglAccumulator, VsglTexel};

/// The bandwidths of the combined image + world distance (module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KMeansMetric {
    /// `h_image`, in units of the image side.
    pub image_bandwidth: f64,
    /// `h_world`, in world units.
    pub world_bandwidth: f64,
}

impl KMeansMetric {
    /// `h_image = 1/√N`, `h_world = world_extent/√N`.
    pub fn for_clusters(cluster_count: usize, world_extent: f64) -> KMeansMetric {
        let spacing = 1.0 / (cluster_count.max(1) as f64).sqrt();
        KMeansMetric {
            image_bandwidth: spacing,
            world_bandwidth: world_extent * spacing,
        }
    }

    /// `d²` between two texels given by image and world positions.
    pub fn distance2(
        &self,
        image: [f64; 2],
        world: Vec3,
        other_image: [f64; 2],
        other_world: Vec3,
    ) -> f64 {
        let di = [image[0] - other_image[0], image[1] - other_image[1]];
        let dw = [
            world.x as f64 - other_world.x as f64,
            world.y as f64 - other_world.y as f64,
            world.z as f64 - other_world.z as f64,
        ];
        (di[0] * di[0] + di[1] * di[1]) / (self.image_bandwidth * self.image_bandwidth)
            + (dw[0] * dw[0] + dw[1] * dw[1] + dw[2] * dw[2])
                / (self.world_bandwidth * self.world_bandwidth)
    }
}

/// The clusters of one k-means pass.
#[derive(Clone, Debug)]
pub struct KMeansClusters {
    /// The texel index of each centre (in drawing order).
    pub centres: Vec<usize>,
    /// The cluster of each texel (`u32::MAX` for texels without importance).
    pub assignment: Vec<u32>,
    /// One VSGL per centre (empty when a repeated centre got no texel).
    pub vsgls: Vec<Vsgl>,
}

/// Clusters a `size × size` row-major grid of VPLs into `cluster_count` VSGLs
/// (module documentation), drawing centres with `uniform()` (numbers in `[0, 1)`).
/// Each cluster is summed relative to its centre's position. Empty when no VPL has
/// importance or `cluster_count` is 0.
pub fn kmeans_vsgls(
    vpls: &[Vpl],
    size: usize,
    cluster_count: usize,
    metric: KMeansMetric,
    uniform: &mut dyn FnMut() -> f64,
) -> KMeansClusters {
    assert_eq!(vpls.len(), size * size, "a size × size grid");
    let weights: Vec<f64> = vpls
        .iter()
        .map(|vpl| VsglTexel::from_vpl(vpl, vpl.position).map_or(0.0, |t| t.weight.max(0.0) as f64))
        .collect();
    let total: f64 = weights.iter().sum();
    let mut clusters = KMeansClusters {
        centres: Vec::new(),
        assignment: vec![u32::MAX; vpls.len()],
        vsgls: Vec::new(),
    };
    if total <= 0.0 || total.is_nan() || cluster_count == 0 {
        return clusters;
    }
    // Centres ∝ importance, by the inverse of the cumulative sum.
    let mut cumulative = Vec::with_capacity(weights.len());
    let mut running = 0.0;
    for w in &weights {
        running += w;
        cumulative.push(running);
    }
    for _ in 0..cluster_count {
        let target = uniform() * running;
        let mut index = cumulative
            .partition_point(|&c| c <= target)
            .min(weights.len() - 1);
        while weights[index] == 0.0 && index > 0 {
            index -= 1;
        }
        clusters.centres.push(index);
    }
    let image = |k: usize| {
        [
            ((k % size) as f64 + 0.5) / size as f64,
            ((k / size) as f64 + 0.5) / size as f64,
        ]
    };
    let mut accumulators: Vec<VsglAccumulator> = clusters
        .centres
        .iter()
        .map(|&c| VsglAccumulator::new(vpls[c].position))
        .collect();
    for (k, vpl) in vpls.iter().enumerate() {
        if weights[k] == 0.0 {
            continue;
        }
        let mut best = (f64::INFINITY, 0usize);
        for (i, &c) in clusters.centres.iter().enumerate() {
            let d = metric.distance2(image(k), vpl.position, image(c), vpls[c].position);
            if d < best.0 {
                best = (d, i);
            }
        }
        clusters.assignment[k] = best.1 as u32;
        accumulators[best.1].add_vpl(vpl);
    }
    clusters.vsgls = accumulators.iter().map(VsglAccumulator::finish).collect();
    clusters
}

#[cfg(test)]
mod tests {
    use super::*;

    use sphera_test_support::Rng;

    /// Two flat patches far apart in the world but adjacent in the image.
    fn two_patches(size: usize) -> Vec<Vpl> {
        (0..size * size)
            .map(|k| {
                let (x, y) = ((k % size) as f32, (k / size) as f32);
                let far = if x < size as f32 / 2.0 { 0.0 } else { 1000.0 };
                Vpl {
                    position: Vec3::new(x + far, y, 0.0),
                    normal: Vec3::Z,
                    power: Vec3::new(1.0, 0.5 + (k % 3) as f32, 2.0),
                    diffuse_reflectance: Vec3::splat(0.5),
                    specular_reflectance: Vec3::splat(0.1),
                    toward_incoming: Vec3::new(0.0, 0.3, 1.0),
                    roughness: 0.4,
                }
            })
            .collect()
    }

    #[test]
    fn clusters_partition_the_power_and_take_the_nearest_centre() {
        let size = 16;
        let vpls = two_patches(size);
        let mut rng = Rng(5);
        let metric = KMeansMetric::for_clusters(8, 16.0);
        let clusters = kmeans_vsgls(&vpls, size, 8, metric, &mut || rng.uniform());
        assert_eq!(clusters.vsgls.len(), 8);
        // The clusters hold the total power (they partition the texels).
        let mut total = [0.0f64; 3];
        for vpl in &vpls {
            let p = vpl.power * (vpl.diffuse_reflectance + vpl.specular_reflectance);
            total[0] += p.x as f64;
            total[1] += p.y as f64;
            total[2] += p.z as f64;
        }
        let mut sum = [0.0f64; 3];
        for v in &clusters.vsgls {
            let p = v.diffuse_power + v.specular_power;
            sum[0] += p.x as f64;
            sum[1] += p.y as f64;
            sum[2] += p.z as f64;
        }
        for c in 0..3 {
            assert!((sum[c] / total[c] - 1.0).abs() < 1e-5);
        }
        // Each texel sits in the cluster of its closest centre.
        let image = |k: usize| {
            [
                ((k % size) as f64 + 0.5) / size as f64,
                ((k / size) as f64 + 0.5) / size as f64,
            ]
        };
        for (k, vpl) in vpls.iter().enumerate() {
            let d = |i: usize| {
                let c = clusters.centres[i];
                metric.distance2(image(k), vpl.position, image(c), vpls[c].position)
            };
            let own = d(clusters.assignment[k] as usize);
            assert!((0..8).all(|i| own <= d(i)), "texel {k}");
        }
        // No cluster straddles the two patches (1000 apart in the world).
        for (i, v) in clusters.vsgls.iter().enumerate() {
            if v.is_empty() {
                continue;
            }
            let members: Vec<usize> = (0..vpls.len())
                .filter(|&k| clusters.assignment[k] == i as u32)
                .collect();
            let left = members.iter().filter(|&&k| k % size < size / 2).count();
            assert!(left == 0 || left == members.len(), "cluster {i} straddles");
            assert!(v.variance < 200.0);
        }
    }

    #[test]
    fn one_cluster_is_the_whole_map_and_no_importance_no_cluster() {
        let size = 4;
        let vpls = two_patches(size);
        let mut rng = Rng(6);
        let one = kmeans_vsgls(
            &vpls,
            size,
            1,
            KMeansMetric::for_clusters(1, 4.0),
            &mut || rng.uniform(),
        );
        let mut all = VsglAccumulator::new(Vec3::ZERO);
        for vpl in &vpls {
            all.add_vpl(vpl);
        }
        let (a, b) = (all.finish(), one.vsgls[0]);
        assert!((a.mean - b.mean).length() < 1e-2);
        assert!((a.variance / b.variance - 1.0).abs() < 1e-4);
        let dark: Vec<Vpl> = vpls
            .iter()
            .map(|v| Vpl {
                power: Vec3::ZERO,
                ..*v
            })
            .collect();
        let none = kmeans_vsgls(
            &dark,
            size,
            4,
            KMeansMetric::for_clusters(4, 4.0),
            &mut || rng.uniform(),
        );
        assert!(none.vsgls.is_empty() && none.centres.is_empty());
    }
}
