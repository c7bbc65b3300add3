//! What the benchmarks share: a deterministic input generator and a timer.

use sphera::Vec3;
use std::hint::black_box;
use std::time::Instant;

/// SplitMix64, for reproducible benchmark inputs.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` with 24 bits.
    pub fn uniform(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 * (1.0 / 16_777_216.0)
    }

    /// Two uniform numbers.
    pub fn u2(&mut self) -> [f32; 2] {
        [self.uniform(), self.uniform()]
    }

    /// Four uniform numbers.
    pub fn u4(&mut self) -> [f32; 4] {
        [
            self.uniform(),
            self.uniform(),
            self.uniform(),
            self.uniform(),
        ]
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.uniform()
    }

    /// A random vector in the cube `[-1, 1)³`.
    pub fn cube(&mut self) -> Vec3 {
        Vec3::new(
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
        )
    }

    /// A uniformly distributed unit vector.
    pub fn direction(&mut self) -> Vec3 {
        let z = 1.0 - 2.0 * self.uniform();
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = 2.0 * std::f32::consts::PI * self.uniform();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}

/// Median over `repeats` runs of ns per call of `run(i)` for `i` in `0..inputs` (the sum
/// of the results is kept alive so that nothing is optimised away).
pub fn time_ns(inputs: usize, repeats: usize, run: impl Fn(usize) -> f32) -> f64 {
    let mut times: Vec<f64> = (0..repeats)
        .map(|_| {
            let start = Instant::now();
            let mut sum = 0.0f32;
            for i in 0..inputs {
                sum += run(black_box(i));
            }
            black_box(sum);
            start.elapsed().as_secs_f64() * 1e9 / inputs as f64
        })
        .collect();
    times.sort_by(|a, b| a.partial_cmp(b).unwrap());
    times[repeats / 2]
}
