//! VSGL clusters by filtered importance sampling (FIS) of a mip pyramid of VPL sums
//! (supplement Section 3.3, Section 5 and Algorithm 1).
//!
//! **Pyramid.** A reflective shadow map of `size × size` texels (`size` a power of
//! two), each a [`VsglTexel`] of the VPL it holds, and its mip levels: level `l` has
//! `(size >> l)²` texels, each the *sum* (not the average) of its four children, up to
//! the single texel of level `L = log2 size`. The levels lie one after the other in one
//! slice, finest first, each row-major (`x` fastest). The importance `p` of a texel is
//! its `weight` (`lum(Φ ∘ (R_d + R_s))`), so no separate channel is needed.
//!
//! **Cluster `i` of `N`** from a 2D random point `u`:
//!
//! 1. the image position `x_i ∈ [0,1)²` is drawn with density proportional to `p`,
//!    exactly, top-down through the pyramid: at each level one of the four children is
//!    chosen by its importance (the row by `u.y`, then the column by `u.x`, each random
//!    number rescaled and reused), and the last rescaled `u` places `x_i` uniformly
//!    inside the chosen level-0 texel;
//! 2. the mip level `l_i ∈ [0, L]` by the bisection of Algorithm 1: with the kernel's
//!    probability mass `P(x, l) / P` (the paper's `(4^l/M) p̄(x, l)`, with `p`
//!    normalised to a density and `p̄` its mip average; here the texels hold sums, so
//!    `P(x, l)` is the filtered sum and `P` the sum at the top level), `l_min ← l` while
//!    `P(x, l)/P < K/N`;
//! 3. the filtered sums at `(x_i, l_i)`, fetched *trilinearly*: bilinear at the levels
//!    `⌊l⌋` and `⌊l⌋ + 1` (texel centres at `(k + ½)/side`, clamped to the edge), mixed
//!    linearly by the fraction of `l` — the same kernel as for `P(x, l)`;
//! 4. the weight `1 / (N · P(x_i, l_i)/P)`, so that the cluster holds
//!    `P / N` of luminance power whatever `x_i` and `l_i`: the `N` clusters hold the
//!    RSM's total luminance exactly, and each RGB channel `c` in expectation up to the
//!    ratio of filtered sums, `E[Σ_i F_c(x_i)/(N P(x_i)/P)] = Σ_t p_t F_c(t)/P(t)`,
//!    which is `Σ_t f_c,t` exactly when the colour is constant within each kernel.
//!
//! Derivation of 4: `x` has density `p(x)/P` per texel, so
//! `E[w(x) F(x)] = Σ_x (p_x/P) w(x) F(x)`; `w = P/(N P(x))` makes
//! `w F_lum = P/N` for every `x`, since the luminance of the filtered power is the
//! filtered weight `P(x)`. This is the paper's FIS weight `1/(N (4^l/M) p̄)`.

use super::accumulator::{Vsgl, VsglAccumulator, VsglTexel};
use glam::Vec3;

/// The largest pyramid: `2^14 × 2^14` texels at level 0 (the texel count then fits a
/// 32-bit `usize`).
const MAX_LOG2_SIZE: u32 = 14;

/// Bisection steps are capped at this count (more cannot change an `f32` level).
const MAX_ITERATIONS: u32 = 32;

/// A borrowed mip pyramid of VPL sums (module documentation), all relative to `origin`.
#[derive(Clone, Copy, Debug)]
pub struct VsglPyramid<'a> {
    texels: &'a [VsglTexel],
    size: u32,
    top_level: u32,
    origin: Vec3,
}

impl<'a> VsglPyramid<'a> {
    /// The number of texels of the pyramid of a `size × size` map, `(4 size² − 1)/3`,
    /// or 0 when `size` is not a power of two in `1..=2^14`.
    pub const fn texel_count(size: u32) -> usize {
        if !size.is_power_of_two() || size > 1 << MAX_LOG2_SIZE {
            return 0;
        }
        let size = size as usize;
        (4 * size * size - 1) / 3
    }

    /// Fills the coarser levels of the pyramid in place: `texels[..size²]` holds level 0
    /// (row-major); every texel of level `l + 1` becomes the sum of its four children,
    /// `(a + b) + (c + d)` in the order top-left, top-right, bottom-left, bottom-right.
    /// Returns `false` (touching nothing) when `size` is not a power of two in
    /// `1..=2^14` or `texels` holds fewer than [`Self::texel_count`] texels.
    pub fn fill_levels(texels: &mut [VsglTexel], size: u32) -> bool {
        let count = Self::texel_count(size);
        if count == 0 || texels.len() < count {
            return false;
        }
        let (mut start, mut side) = (0usize, size as usize);
        while side > 1 {
            let half = side / 2;
            let next = start + side * side;
            for y in 0..half {
                for x in 0..half {
                    let at = |i: usize, j: usize| texels[start + (2 * y + j) * side + 2 * x + i];
                    texels[next + y * half + x] =
                        at(0, 0).add(&at(1, 0)).add(&at(0, 1).add(&at(1, 1)));
                }
            }
            start = next;
            side = half;
        }
        true
    }

    /// The pyramid over `texels`, or `None` when `size` is not a power of two in
    /// `1..=2^14`, `texels` holds fewer than [`Self::texel_count`] texels (extra ones
    /// are ignored) or `origin` is not finite.
    pub fn new(texels: &'a [VsglTexel], size: u32, origin: Vec3) -> Option<VsglPyramid<'a>> {
        if !size.is_power_of_two()
            || size > 1 << MAX_LOG2_SIZE
            || texels.len() < Self::texel_count(size)
            || !origin.is_finite()
        {
            return None;
        }
        Some(VsglPyramid {
            texels,
            size,
            top_level: size.trailing_zeros(),
            origin,
        })
    }

    /// The side of level 0.
    pub fn size(&self) -> u32 {
        self.size
    }

    /// The coarsest level `L = log2 size` (a single texel).
    pub fn top_level(&self) -> u32 {
        self.top_level
    }

    /// The reference point of the sums.
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// The side of `level` (levels above `L` count as `L`).
    pub fn level_size(&self, level: u32) -> u32 {
        self.size >> level.min(self.top_level)
    }

    /// The index of the first texel of `level` in the slice (levels above `L` count as
    /// `L`).
    pub fn level_offset(&self, level: u32) -> usize {
        // Σ_{k<l} 4^{L−k} = (4^{L+1} − 4^{L+1−l}) / 3.
        let level = level.min(self.top_level);
        let total = 1usize << (2 * (self.top_level + 1));
        let rest = 1usize << (2 * (self.top_level + 1 - level));
        (total - rest) / 3
    }

    /// The texel `(x, y)` of `level`; a level above `L` counts as `L`, and indices
    /// outside the level are clamped to its edge (so this never panics).
    pub fn texel(&self, level: u32, x: u32, y: u32) -> &VsglTexel {
        let side = self.level_size(level);
        let (x, y) = (x.min(side - 1) as usize, y.min(side - 1) as usize);
        &self.texels[self.level_offset(level) + y * side as usize + x]
    }

    /// The importance `p` of a texel: its weight, with negative, NaN or infinite
    /// weights counted as 0.
    pub fn importance(&self, level: u32, x: u32, y: u32) -> f32 {
        let weight = self.texel(level, x, y).weight;
        if weight.is_finite() {
            weight.max(0.0)
        } else {
            0.0
        }
    }

    /// The total importance `P`: the weight of the top texel.
    pub fn total_importance(&self) -> f32 {
        self.importance(self.top_level, 0, 0)
    }

    /// Calls `visit(level, x, y, filter weight)` for the (up to 8) texels of the
    /// trilinear kernel at image position `position` (in `[0, 1]²`, clamped) and
    /// fractional `level` (clamped to `[0, L]`).
    pub fn for_each_filtered(
        &self,
        position: [f32; 2],
        level: f32,
        mut visit: impl FnMut(u32, u32, u32, f32),
    ) {
        let level = level.max(0.0).min(self.top_level as f32);
        let lower = (libm::floorf(level) as u32).min(self.top_level);
        let fraction = level - lower as f32;
        let upper = (lower + 1).min(self.top_level);
        self.for_each_bilinear(position, lower, 1.0 - fraction, &mut visit);
        if fraction > 0.0 {
            self.for_each_bilinear(position, upper, fraction, &mut visit);
        }
    }

    fn for_each_bilinear(
        &self,
        position: [f32; 2],
        level: u32,
        scale: f32,
        visit: &mut impl FnMut(u32, u32, u32, f32),
    ) {
        let side = self.level_size(level);
        let axis = |coordinate: f32| -> ([u32; 2], [f32; 2]) {
            let t = coordinate.max(0.0).min(1.0) * side as f32 - 0.5;
            let first = libm::floorf(t);
            let fraction = t - first;
            let clamp = |i: f32| (i.max(0.0) as u32).min(side - 1);
            (
                [clamp(first), clamp(first + 1.0)],
                [1.0 - fraction, fraction],
            )
        };
        let (xs, wx) = axis(position[0]);
        let (ys, wy) = axis(position[1]);
        for j in 0..2 {
            for i in 0..2 {
                let weight = scale * wx[i] * wy[j];
                if weight > 0.0 {
                    visit(level, xs[i], ys[j], weight);
                }
            }
        }
    }

    /// The filtered importance `P(x, l)`: the trilinear kernel applied to `p`.
    pub fn filtered_importance(&self, position: [f32; 2], level: f32) -> f32 {
        let mut sum = 0.0;
        self.for_each_filtered(position, level, |l, x, y, weight| {
            sum += weight * self.importance(l, x, y);
        });
        sum
    }

    /// Draws an image position with density proportional to the importance (step 1
    /// of the module documentation); also returns the level-0 texel it lies in. `None`
    /// when no texel has positive importance.
    pub fn sample_position(&self, u: [f32; 2]) -> Option<([f32; 2], [u32; 2])> {
        let mut u = [clamp_unit(u[0]), clamp_unit(u[1])];
        let (mut x, mut y) = (0u32, 0u32);
        if !(self.total_importance() > 0.0) {
            return None;
        }
        for level in (0..self.top_level).rev() {
            let (cx, cy) = (2 * x, 2 * y);
            let p = |i: u32, j: u32| self.importance(level, cx + i, cy + j);
            let (p00, p10, p01, p11) = (p(0, 0), p(1, 0), p(0, 1), p(1, 1));
            let row = choose(&mut u[1], p00 + p10, p01 + p11)?;
            let column = if row == 0 {
                choose(&mut u[0], p00, p10)?
            } else {
                choose(&mut u[0], p01, p11)?
            };
            x = cx + column;
            y = cy + row;
        }
        let side = self.size as f32;
        let position = [
            ((x as f32 + u[0]) / side).min(ONE_BELOW),
            ((y as f32 + u[1]) / side).min(ONE_BELOW),
        ];
        Some((position, [x, y]))
    }

    /// The mip level of Algorithm 1: `iterations` bisection steps on `[0, L]` keeping
    /// `l_min` where `P(x, l) < mass · P` (`mass = K/N`), then the midpoint.
    pub fn bisect_level(&self, position: [f32; 2], mass: f32, iterations: u32) -> f32 {
        let threshold = mass * self.total_importance();
        let (mut low, mut high) = (0.0f32, self.top_level as f32);
        for _ in 0..iterations.min(MAX_ITERATIONS) {
            let middle = 0.5 * (low + high);
            if self.filtered_importance(position, middle) < threshold {
                low = middle;
            } else {
                high = middle;
            }
        }
        0.5 * (low + high)
    }
}

/// The largest `f32` below 1.
const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;

fn clamp_unit(u: f32) -> f32 {
    u.max(0.0).min(ONE_BELOW)
}

/// Chooses 0 with probability `a/(a+b)`, else 1, and rescales `u` to `[0, 1)` inside
/// the chosen part. `None` when `a + b` is not positive.
fn choose(u: &mut f32, a: f32, b: f32) -> Option<u32> {
    let total = a + b;
    if !(total > 0.0) {
        return None;
    }
    let t = *u * total;
    if t < a || !(b > 0.0) {
        *u = clamp_unit(t / a);
        Some(0)
    } else {
        *u = clamp_unit((t - a) / b);
        Some(1)
    }
}

/// One FIS cluster: where it was taken, its weight and its VSGL.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FisCluster {
    /// The image position `x_i ∈ [0, 1)²`.
    pub position: [f32; 2],
    /// The level-0 texel that `x_i` lies in.
    pub texel: [u32; 2],
    /// The mip level `l_i ∈ [0, L]`.
    pub level: f32,
    /// The weight `P / (N P(x_i, l_i))` applied to the filtered sums.
    pub weight: f32,
    /// The VSGL of the weighted, filtered sums.
    pub vsgl: Vsgl,
}

/// The FIS cluster of `u` among `cluster_count` clusters (module documentation), with
/// the kernel mass `kernel_scale / cluster_count` (the paper's `K/N`) and `iterations`
/// bisection steps (capped at 32). `None` when `cluster_count` is 0, `kernel_scale` is
/// not finite and positive, or the pyramid has no importance.
pub fn fis_cluster(
    pyramid: &VsglPyramid,
    cluster_count: u32,
    kernel_scale: f32,
    iterations: u32,
    u: [f32; 2],
) -> Option<FisCluster> {
    if cluster_count == 0 || !(kernel_scale > 0.0) || !kernel_scale.is_finite() {
        return None;
    }
    let (position, texel) = pyramid.sample_position(u)?;
    let mass = kernel_scale / cluster_count as f32;
    let level = pyramid.bisect_level(position, mass, iterations);
    let filtered = pyramid.filtered_importance(position, level);
    let weight = pyramid.total_importance() / (cluster_count as f32 * filtered);
    if !(weight > 0.0) || !weight.is_finite() {
        return None;
    }
    let mut accumulator = VsglAccumulator::new(pyramid.origin());
    pyramid.for_each_filtered(position, level, |l, x, y, kernel| {
        accumulator.add_texel_scaled(pyramid.texel(l, x, y), kernel * weight);
    });
    Some(FisCluster {
        position,
        texel,
        level,
        weight,
        vsgl: accumulator.finish(),
    })
}

/// The VSGL of [`fis_cluster`], or [`Vsgl::EMPTY`] (mean at the pyramid's origin) when
/// there is none. Give each cluster `i` of the `N` its own random point, stratified
/// over `[0, 1)²` (for example the Hammersley point `((i + ξ)/N, radical_inverse(i))`):
/// the kernel masses are then close to `K/N` and the kernels tile the map with few
/// overlaps and gaps (Tokuyoshi 2016); the `N` VSGLs together carry the total power of
/// the map (module documentation, step 4).
pub fn fis_select(
    pyramid: &VsglPyramid,
    cluster_count: u32,
    kernel_scale: f32,
    iterations: u32,
    u: [f32; 2],
) -> Vsgl {
    match fis_cluster(pyramid, cluster_count, kernel_scale, iterations, u) {
        Some(cluster) => cluster.vsgl,
        None => Vsgl {
            mean: pyramid.origin(),
            ..Vsgl::EMPTY
        },
    }
}
