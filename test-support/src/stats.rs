//! Pearson's chi-square test with its p-value by the regularised incomplete gamma
//! function, and running estimates of a mean.

/// Regularised upper incomplete gamma function Q(a, x), for chi-square p-values.
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let ln_gamma_a = ln_gamma(a);
    if x < a + 1.0 {
        // Series for P(a, x).
        let mut term = 1.0 / a;
        let mut sum = term;
        let mut ap = a;
        for _ in 0..10_000 {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * (-x + a * x.ln() - ln_gamma_a).exp()
    } else {
        // Continued fraction for Q(a, x) (modified Lentz).
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-15 {
                break;
            }
        }
        (-x + a * x.ln() - ln_gamma_a).exp() * h
    }
}

/// ln Γ(x) for x > 0 by the Lanczos approximation (g = 7, n = 9).
pub fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        let pi = core::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut sum = C[0];
    for (i, &c) in C.iter().enumerate().skip(1) {
        sum += c / (x + i as f64);
    }
    let t = x + 7.5;
    0.5 * (2.0 * core::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + sum.ln()
}

/// Pearson's chi-square test of observed counts against exact cell probabilities.
/// Cells whose expected count is below 5 are pooled. Returns (statistic, dof, p-value).
pub fn chi_square(observed: &[u64], probabilities: &[f64]) -> (f64, usize, f64) {
    let total: u64 = observed.iter().sum();
    let mut statistic = 0.0;
    let mut bins = 0usize;
    let (mut pooled_observed, mut pooled_expected) = (0.0, 0.0);
    for (&o, &p) in observed.iter().zip(probabilities) {
        let e = p * total as f64;
        if e < 5.0 {
            pooled_observed += o as f64;
            pooled_expected += e;
        } else {
            statistic += (o as f64 - e).powi(2) / e;
            bins += 1;
        }
    }
    if pooled_expected >= 5.0 {
        statistic += (pooled_observed - pooled_expected).powi(2) / pooled_expected;
        bins += 1;
    } else if pooled_observed > pooled_expected + 5.0 {
        // Many samples where almost none are expected: fail loudly.
        statistic += f64::INFINITY;
    }
    let dof = bins.saturating_sub(1).max(1);
    (statistic, dof, gamma_q(dof as f64 / 2.0, statistic / 2.0))
}

/// Running mean and variance (Welford), for estimator tests.
#[derive(Default)]
pub struct Estimate {
    count: u64,
    mean: f64,
    m2: f64,
}

impl Estimate {
    pub fn add(&mut self, x: f64) {
        self.count += 1;
        let delta = x - self.mean;
        self.mean += delta / self.count as f64;
        self.m2 += delta * (x - self.mean);
    }
    pub fn variance(&self) -> f64 {
        self.m2 / (self.count.max(2) - 1) as f64
    }
    pub fn mean(&self) -> f64 {
        self.mean
    }
    pub fn standard_error(&self) -> f64 {
        (self.variance() / self.count as f64).sqrt()
    }
    /// Asserts that the mean agrees with `reference` within `sigmas` standard errors
    /// plus a relative tolerance for f32 rounding.
    pub fn assert_mean_is(&self, reference: f64, sigmas: f64, relative: f64, what: &str) {
        let allowed = sigmas * self.standard_error() + relative * reference.abs();
        assert!(
            (self.mean - reference).abs() <= allowed,
            "{what}: mean {} vs reference {} (standard error {}, allowed {})",
            self.mean,
            reference,
            self.standard_error(),
            allowed
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chi_square_p_values_match_known_quantiles() {
        // 95% quantiles of chi-square: dof 1 -> 3.841, dof 10 -> 18.307.
        assert!((gamma_q(0.5, 3.841_458_8 / 2.0) - 0.05).abs() < 1e-6);
        assert!((gamma_q(5.0, 18.307_038 / 2.0) - 0.05).abs() < 1e-6);
        assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-12);
    }
}
