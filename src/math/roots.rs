//! Inversion of increasing functions (CDFs of the samplers that have no closed-form
//! inverse): one step of Newton's method safeguarded by bisection, shared by the
//! biquadratic warp of Hart et al., the two-cap intersection and the clipped
//! clamped-cosine SPTD, each of which keeps its own start and stopping rule.

/// One step for a root of an increasing `F` inside the bracket `[low, high]`, at `x`
/// with `residual = F(x) − target` and `slope = F′(x)`: the bracket shrinks to the side
/// of `x` that holds the root, and the Newton step `x − residual / slope` is returned
/// where it lands strictly inside the bracket, the bracket's midpoint otherwise (also
/// for a zero, negative or non-finite slope, and a NaN step). The bracket halves at
/// least every other step, so a loop of these steps cannot wander. A zero residual
/// (`x` is the root, as the first Newton step often lands exactly when `F` is nearly
/// linear) returns `x` and closes the bracket on it: the Newton step is then `x`
/// itself, which is not strictly inside the bracket `[x, high]`, and bisecting from it
/// took the two-cap inversion some twenty evaluations back to the root it had.
#[inline(always)]
pub(crate) fn safeguarded_newton_step(
    x: f32,
    residual: f32,
    slope: f32,
    low: &mut f32,
    high: &mut f32,
) -> f32 {
    if residual == 0.0 {
        (*low, *high) = (x, x);
        return x;
    }
    if residual > 0.0 {
        *high = x;
    } else {
        *low = x;
    }
    let newton = x - residual / slope;
    if slope > 0.0 && newton > *low && newton < *high {
        newton
    } else {
        0.5 * (*low + *high)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The steps find the cube root of 2 (F(x) = x³ on [0, 2]) to f32 precision in a
    /// few steps (stopping, as the callers do, when a step no longer moves `x`), and a
    /// negative, zero or NaN slope bisects instead of leaving the bracket.
    #[test]
    fn newton_steps_converge_and_bad_slopes_bisect() {
        let (mut low, mut high, mut x) = (0.0f32, 2.0f32, 1.9f32);
        let mut steps = 0;
        loop {
            let next =
                safeguarded_newton_step(x, x * x * x - 2.0, 3.0 * x * x, &mut low, &mut high);
            steps += 1;
            let converged = (next - x).abs() <= 2.0 * f32::EPSILON * x;
            x = next;
            if converged || steps == 40 {
                break;
            }
        }
        assert!(steps < 10, "{steps} steps");
        assert!((x - 2f32.cbrt()).abs() <= 4.0 * f32::EPSILON, "{x}");
        for slope in [-1.0, 0.0, f32::NAN] {
            let (mut low, mut high) = (0.0f32, 1.0f32);
            let next = safeguarded_newton_step(0.25, -0.1, slope, &mut low, &mut high);
            assert_eq!((low, high, next), (0.25, 1.0, 0.625));
        }
    }
}
