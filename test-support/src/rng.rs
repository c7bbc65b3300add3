//! SplitMix64, the one deterministic random number generator of the tests, the tools
//! and the benchmarks.
use glam::Vec3;

/// SplitMix64: small, fast, deterministic, good enough for tests. [`Rng::new`] mixes
/// the seed first (the core's tests); `Rng(state)` starts from the raw state (the
/// benchmarks' inputs). Both give the same sequence as the copies they replace.
pub struct Rng(pub u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1) with 53 bits.
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    /// Uniform in [0, 1) as f32 with 24 bits (never rounds up to 1).
    pub fn uniform_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 * (1.0 / (1u32 << 24) as f32)
    }
    /// 10^x with x uniform in [lo, hi).
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        10f64.powf(lo + (hi - lo) * self.uniform())
    }
    pub fn signed_log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let v = self.log_uniform(lo, hi);
        if self.next_u64() & 1 == 0 { v } else { -v }
    }
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
    pub fn unit_vector_f32(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(
                2.0 * self.uniform_f32() - 1.0,
                2.0 * self.uniform_f32() - 1.0,
                2.0 * self.uniform_f32() - 1.0,
            );
            let l = v.length_squared();
            if l > 1e-4 && l <= 1.0 {
                return v.normalize();
            }
        }
    }

    /// Two uniform numbers.
    pub fn u2(&mut self) -> [f32; 2] {
        [self.uniform_f32(), self.uniform_f32()]
    }

    /// Four uniform numbers.
    pub fn u4(&mut self) -> [f32; 4] {
        [
            self.uniform_f32(),
            self.uniform_f32(),
            self.uniform_f32(),
            self.uniform_f32(),
        ]
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.uniform_f32()
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
        let z = 1.0 - 2.0 * self.uniform_f32();
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = 2.0 * std::f32::consts::PI * self.uniform_f32();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}
