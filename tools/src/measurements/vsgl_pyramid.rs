//! The mip pyramid of VPL sums that `sphera::vsgl::fis` samples, built from an RSM-like
//! grid of VPLs (std helper; a renderer builds it on the GPU with mipmapping).
//!
//! Level 0 holds [`VsglTexel::from_vpl`] of each VPL of a `size × size` row-major grid
//! (a VPL that the core rejects, such as one with a NaN position, becomes a zero
//! texel: no light); each coarser level holds the field-wise *sums* of 2×2 texels.

use sphera::Vec3;
use sphera::vsgl::{Vpl, VsglPyramid, VsglTexel};

/// An owned pyramid: the texels of every level, finest first, and their shared origin.
#[derive(Clone, Debug)]
pub struct VsglPyramidBuffer {
    /// All levels, finest first, each row-major.
    pub texels: Vec<VsglTexel>,
    /// The side of level 0 (a power of two).
    pub size: u32,
    /// The reference point of the sums.
    pub origin: Vec3,
    /// How many VPLs of the grid the core rejected (zero texels).
    pub rejected: usize,
}

impl VsglPyramidBuffer {
    /// The pyramid of a `size × size` grid of VPLs (row-major, `x` fastest), sums
    /// relative to `origin`. `None` when `size` is not a power of two in `1..=2^14`,
    /// `vpls.len() != size²` or `origin` is not finite.
    pub fn from_vpls(vpls: &[Vpl], size: u32, origin: Vec3) -> Option<VsglPyramidBuffer> {
        if VsglPyramid::texel_count(size) == 0
            || vpls.len() != (size as usize).pow(2)
            || !origin.is_finite()
        {
            return None;
        }
        let mut rejected = 0;
        let level0: Vec<VsglTexel> = vpls
            .iter()
            .map(|vpl| {
                VsglTexel::from_vpl(vpl, origin).unwrap_or_else(|| {
                    rejected += 1;
                    VsglTexel::ZERO
                })
            })
            .collect();
        Some(VsglPyramidBuffer {
            texels: mip_levels(level0, size),
            size,
            origin,
            rejected,
        })
    }

    /// The borrowed view that the core samples.
    pub fn pyramid(&self) -> VsglPyramid<'_> {
        VsglPyramid::new(&self.texels, self.size, self.origin)
            .expect("a buffer built by from_vpls is a valid pyramid")
    }
}

/// Appends to the `size × size` level 0 every coarser level, each texel the sum of its
/// four children.
pub fn mip_levels(level0: Vec<VsglTexel>, size: u32) -> Vec<VsglTexel> {
    let mut texels = level0;
    texels.resize(VsglPyramid::texel_count(size), VsglTexel::ZERO);
    assert!(
        VsglPyramid::fill_levels(&mut texels, size),
        "a supported size"
    );
    texels
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(size: u32) -> Vec<Vpl> {
        (0..size * size)
            .map(|k| {
                let (x, y) = ((k % size) as f32, (k / size) as f32);
                Vpl {
                    position: Vec3::new(x, y, 0.1 * (x * y).sin()),
                    normal: Vec3::new(0.1 * x.cos(), 0.1, 1.0),
                    power: Vec3::new(1.0 + (k % 3) as f32, 2.0, 0.5 + (k % 7) as f32),
                    diffuse_reflectance: Vec3::splat(0.6),
                    specular_reflectance: Vec3::splat(0.05 * (k % 4) as f32),
                    toward_incoming: Vec3::new(0.3, 0.0, 1.0),
                    roughness: 0.2 + 0.1 * (k % 5) as f32,
                }
            })
            .collect()
    }

    #[test]
    fn every_mip_texel_is_the_sum_of_its_children() {
        let size = 16;
        let buffer =
            VsglPyramidBuffer::from_vpls(&grid(size), size, Vec3::new(8.0, 8.0, 0.0)).unwrap();
        let pyramid = buffer.pyramid();
        assert_eq!(buffer.texels.len(), VsglPyramid::texel_count(size));
        assert_eq!(buffer.rejected, 0);
        for level in 1..=pyramid.top_level() {
            let side = pyramid.level_size(level);
            for y in 0..side {
                for x in 0..side {
                    let child = |i, j| *pyramid.texel(level - 1, 2 * x + i, 2 * y + j);
                    // (a + b) + (c + d), the order of `mip_levels`, so equal bits.
                    let sum = child(0, 0)
                        .add(&child(1, 0))
                        .add(&child(0, 1).add(&child(1, 1)));
                    assert_eq!(*pyramid.texel(level, x, y), sum);
                }
            }
        }
        // The top texel holds the total weight, in f64 from level 0.
        let total: f64 = buffer.texels[..(size * size) as usize]
            .iter()
            .map(|t| t.weight as f64)
            .sum();
        assert!((pyramid.total_importance() as f64 / total - 1.0).abs() < 1e-5);
    }

    #[test]
    fn rejected_vpls_become_black_texels_and_bad_sizes_no_pyramid() {
        let mut vpls = grid(4);
        vpls[5].position.x = f32::NAN;
        vpls[6].normal = Vec3::ZERO;
        let buffer = VsglPyramidBuffer::from_vpls(&vpls, 4, Vec3::ZERO).unwrap();
        assert_eq!(buffer.rejected, 2);
        assert_eq!(buffer.texels[5], VsglTexel::ZERO);
        assert!(buffer.texels.iter().all(VsglTexel::is_finite));
        assert!(VsglPyramidBuffer::from_vpls(&vpls, 2, Vec3::ZERO).is_none());
        assert!(VsglPyramidBuffer::from_vpls(&grid(3), 3, Vec3::ZERO).is_none());
        assert!(VsglPyramidBuffer::from_vpls(&vpls, 4, Vec3::splat(f32::NAN)).is_none());
    }
}
