//! What the benchmarks share: a timer (their inputs come from
//! `sphera_test_support::Rng`).

use std::hint::black_box;
use std::time::Instant;

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
