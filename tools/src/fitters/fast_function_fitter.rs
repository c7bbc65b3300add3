//! Fitter of the polynomial coefficients in `src/math/fast_functions_generated.rs`: the
//! `f32` polynomials of `atan` on `[0, 1]` and of `sin` and `cos` on `[0, π/4]` that the
//! core's fast functions (`src/math/atan.rs`, `src/math/sin_cos.rs`) evaluate.
//!
//! # The fit
//!
//! Each function `f` is approximated as `fixed(x) + Σ_j c_j x^(p_j)`, where `fixed` holds
//! the leading Taylor terms that stay exact (`x` for `atan` and `sin`, `1 - x²/2` for
//! `cos`: small arguments then get their correctly rounded value, and `atan(0) = 0`
//! exactly) and the powers `p_j` have the function's parity. The coefficients minimise
//! the largest relative error `|approximation / f - 1|` over a dense grid of the
//! interval (discrete minimax): the Remez exchange algorithm, all in `f64`.
//!
//! Remez: the error of the best approximation with `n` free coefficients equioscillates
//! at `n + 1` points (Chebyshev's alternation theorem, which holds for the weighted
//! error since `x^(p_j)` times the weight `1/f` is a Haar system on the interval). Given
//! `n + 1` reference points, the linear system `e(x_i) = (-1)^i E` gives the coefficients
//! and the level `E`; the next reference is the extremum of each sign-constant run of the
//! error on the grid (multiple exchange), trimmed at the end with the smaller error to
//! `n + 1` points. The level `|E|` rises to the largest error; the iteration stops when
//! they agree to 1e-9.
//!
//! # Rounding to `f32`
//!
//! Rounding all minimax coefficients to `f32` at once can add an error as large as the
//! approximation error. Instead they are rounded one at a time, lowest power first (the
//! largest, whose rounding matters most): each candidate (the nearest `f32` and its two
//! neighbours) is fixed, the remaining coefficients refitted, and the candidate whose
//! refit has the smallest error kept. The last coefficient is chosen among its nearest
//! `f32` and four neighbours by the error of the whole `f32` polynomial (still evaluated
//! in `f64`: the rounding of the `f32` evaluation is measured by the core's exhaustive
//! tests, not here).
//!
//! Everything uses the `libm` crate's `f64` functions, so the output does not depend on
//! the platform's C library.
use std::fmt::Write as _;

/// Points of the grid on which the error is minimised.
const GRID_POINTS: usize = 20_000;
/// The Remez iteration stops when the largest error on the grid exceeds the level `|E|`
/// by at most this fraction.
const CONVERGENCE: f64 = 1e-9;
const MAX_ITERATIONS: usize = 60;

/// One function to fit.
#[derive(Clone, Copy)]
pub struct Problem {
    /// The constant's name in the generated file.
    pub name: &'static str,
    /// What the constant approximates (the doc comment's first sentence).
    pub description: &'static str,
    /// The interval `(lo, hi]` (the grid leaves out `lo`, where the error of each
    /// function is zero by its fixed part).
    pub lo: f64,
    pub hi: f64,
    pub f: fn(f64) -> f64,
    pub fixed: fn(f64) -> f64,
    /// The power of the first fitted coefficient; later powers step by two.
    pub first_power: i32,
    /// The number of fitted coefficients.
    pub count: usize,
}

fn atan_fixed(x: f64) -> f64 {
    x
}

fn cos_fixed(x: f64) -> f64 {
    1.0 - 0.5 * x * x
}

/// The three polynomials, with the coefficient counts the core uses: `sin` and `cos` the
/// smallest whose `f32` coefficients stay far below an `f32` ulp of relative error (see
/// the table that `fit_fast_functions` prints), `atan` one more (8 coefficients give
/// 1.7e-8, a seventh of `f32::EPSILON`, and 1.24 instead of 1.12 ulps in the core's
/// exhaustive test), so that the `f32` evaluation's own rounding dominates.
pub fn problems() -> [Problem; 3] {
    [
        Problem {
            name: "ATAN_UNIT",
            description: "`atan(t) ≈ t + t³ (c[0] + t² (c[1] + t² (…)))` for `t` in `[0, 1]`",
            lo: 0.0,
            hi: 1.0,
            f: libm::atan,
            fixed: atan_fixed,
            first_power: 3,
            count: 9,
        },
        Problem {
            name: "SIN_QUARTER",
            description: "`sin(x) ≈ x + x³ (c[0] + x² (c[1] + x² (…)))` for `x` in `[0, π/4]`",
            lo: 0.0,
            hi: std::f64::consts::FRAC_PI_4,
            f: libm::sin,
            fixed: atan_fixed,
            first_power: 3,
            count: 3,
        },
        Problem {
            name: "COS_QUARTER",
            description: "`cos(x) ≈ 1 - x²/2 + x⁴ (c[0] + x² (c[1] + x² (…)))` for `x` in \
                          `[0, π/4]`",
            lo: 0.0,
            hi: std::f64::consts::FRAC_PI_4,
            f: libm::cos,
            fixed: cos_fixed,
            first_power: 4,
            count: 3,
        },
    ]
}

/// The grid: `GRID_POINTS` points evenly spaced in `(lo, hi]`.
fn grid(problem: &Problem) -> Vec<f64> {
    (1..=GRID_POINTS)
        .map(|i| problem.lo + (problem.hi - problem.lo) * i as f64 / GRID_POINTS as f64)
        .collect()
}

/// The fit of a problem's free coefficients with some leading ones fixed.
struct Fit {
    coefficients: Vec<f64>,
    max_error: f64,
}

/// The largest relative error of `fixed + Σ c_j x^(p_j)` on the grid.
fn max_error(problem: &Problem, coefficients: &[f64], xs: &[f64]) -> f64 {
    xs.iter()
        .map(|&x| relative_error(problem, coefficients, x).abs())
        .fold(0.0, f64::max)
}

fn relative_error(problem: &Problem, coefficients: &[f64], x: f64) -> f64 {
    let exact = (problem.f)(x);
    let mut value = (problem.fixed)(x);
    for (j, c) in coefficients.iter().enumerate() {
        value += c * x.powi(problem.first_power + 2 * j as i32);
    }
    (value - exact) / exact
}

/// Solves `a x = b` (`a` square, row-major) by Gaussian elimination with partial
/// pivoting.
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .expect("non-empty");
        a.swap(col, pivot);
        b.swap(col, pivot);
        let (upper, lower) = a.split_at_mut(col + 1);
        let pivot_row = &upper[col];
        for (offset, row) in lower.iter_mut().enumerate() {
            let factor = row[col] / pivot_row[col];
            for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= factor * p;
            }
            b[col + 1 + offset] -= factor * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        let mut sum = b[row];
        for (ak, xk) in a[row][row + 1..].iter().zip(&x[row + 1..]) {
            sum -= ak * xk;
        }
        x[row] = sum / a[row][row];
    }
    x
}

/// The discrete minimax fit of the coefficients after the `fixed` leading ones.
fn remez(problem: &Problem, fixed: &[f64], xs: &[f64]) -> Fit {
    let free = problem.count - fixed.len();
    let first = fixed.len();
    if free == 0 {
        return Fit {
            coefficients: fixed.to_vec(),
            max_error: max_error(problem, fixed, xs),
        };
    }
    // The grid's targets: what the free terms must supply, and the weight 1/f.
    let residual: Vec<f64> = xs
        .iter()
        .map(|&x| {
            let mut r = (problem.f)(x) - (problem.fixed)(x);
            for (j, c) in fixed.iter().enumerate() {
                r -= c * x.powi(problem.first_power + 2 * j as i32);
            }
            r
        })
        .collect();
    let weight: Vec<f64> = xs.iter().map(|&x| 1.0 / (problem.f)(x)).collect();
    let power = |j: usize| problem.first_power + 2 * (first + j) as i32;
    // Start from the Chebyshev points of the interval.
    let mut reference: Vec<usize> = (0..=free)
        .map(|i| {
            let c =
                0.5 * (1.0 - (std::f64::consts::PI * (i as f64 + 0.5) / (free + 1) as f64).cos());
            ((c * xs.len() as f64) as usize).min(xs.len() - 1)
        })
        .collect();
    reference.dedup();
    let mut coefficients = vec![0.0; free];
    for _ in 0..MAX_ITERATIONS {
        // w_i (Σ c_j x_i^p_j - r_i) = (-1)^i E.
        let a: Vec<Vec<f64>> = reference
            .iter()
            .enumerate()
            .map(|(i, &g)| {
                let mut row: Vec<f64> = (0..free)
                    .map(|j| weight[g] * xs[g].powi(power(j)))
                    .collect();
                row.push(if i % 2 == 0 { -1.0 } else { 1.0 });
                row
            })
            .collect();
        let b: Vec<f64> = reference.iter().map(|&g| weight[g] * residual[g]).collect();
        let solution = solve(a, b);
        coefficients.copy_from_slice(&solution[..free]);
        let level = solution[free].abs();
        let error: Vec<f64> = (0..xs.len())
            .map(|g| {
                let value: f64 = (0..free)
                    .map(|j| coefficients[j] * xs[g].powi(power(j)))
                    .sum();
                weight[g] * (value - residual[g])
            })
            .collect();
        let largest = error.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        if largest <= level * (1.0 + CONVERGENCE) {
            break;
        }
        // The extremum of each run of one sign.
        let mut extrema: Vec<usize> = Vec::new();
        for g in 0..xs.len() {
            if error[g] == 0.0 {
                continue;
            }
            match extrema.last() {
                Some(&last) if (error[last] > 0.0) == (error[g] > 0.0) => {
                    if error[g].abs() > error[last].abs() {
                        *extrema.last_mut().expect("non-empty") = g;
                    }
                }
                _ => extrema.push(g),
            }
        }
        if extrema.len() < free + 1 {
            break;
        }
        while extrema.len() > free + 1 {
            if error[extrema[0]].abs() < error[*extrema.last().expect("non-empty")].abs() {
                extrema.remove(0);
            } else {
                extrema.pop();
            }
        }
        if extrema == reference {
            break;
        }
        reference = extrema;
    }
    let mut all = fixed.to_vec();
    all.extend_from_slice(&coefficients);
    let max_error = max_error(problem, &all, xs);
    Fit {
        coefficients: all,
        max_error,
    }
}

/// `x` and its `f32` neighbours `steps` ulps to either side, nearest first.
fn f32_candidates(x: f64, steps: u32) -> Vec<f32> {
    let nearest = x as f32;
    let mut out = vec![nearest];
    let (mut up, mut down) = (nearest, nearest);
    for _ in 0..steps {
        up = up.next_up();
        down = down.next_down();
        out.push(up);
        out.push(down);
    }
    out
}

/// The result of one problem: the real minimax fit and the `f32` coefficients.
pub struct Fitted {
    pub problem: Problem,
    /// The largest relative error of the real (unrounded) minimax polynomial.
    pub minimax_error: f64,
    pub coefficients: Vec<f32>,
    /// The largest relative error of the `f32` coefficients, evaluated in `f64`.
    pub error: f64,
}

/// Fits `problem` and rounds its coefficients to `f32` (see the module documentation).
pub fn fit(problem: &Problem) -> Fitted {
    let xs = grid(problem);
    let minimax = remez(problem, &[], &xs);
    let mut chosen: Vec<f64> = Vec::new();
    let mut current = minimax.coefficients.clone();
    for j in 0..problem.count {
        let last = j + 1 == problem.count;
        let mut best: Option<(f64, f32, Vec<f64>)> = None;
        for candidate in f32_candidates(current[j], if last { 2 } else { 1 }) {
            let mut fixed = chosen.clone();
            fixed.push(candidate as f64);
            let refit = remez(problem, &fixed, &xs);
            if best.as_ref().is_none_or(|(e, _, _)| refit.max_error < *e) {
                best = Some((refit.max_error, candidate, refit.coefficients));
            }
        }
        let (_, candidate, refit) = best.expect("candidates");
        chosen.push(candidate as f64);
        current = refit;
    }
    let error = max_error(problem, &chosen, &xs);
    Fitted {
        problem: *problem,
        minimax_error: minimax.max_error,
        coefficients: chosen.iter().map(|&c| c as f32).collect(),
        error,
    }
}

/// The largest relative errors of the real minimax fits with `count` coefficients (the
/// table printed by the binary, to justify the chosen counts).
pub fn minimax_error_with(problem: &Problem, count: usize) -> f64 {
    let p = Problem { count, ..*problem };
    remez(&p, &[], &grid(&p)).max_error
}

/// The complete text of `src/math/fast_functions_generated.rs` (deterministic).
pub fn generate() -> String {
    render(&problems().map(|p| fit(&p)))
}

/// Renders the generated file.
pub fn render(fits: &[Fitted]) -> String {
    let mut out = String::new();
    out.push_str(
        "// Generated by `cargo run --release -p sphera-tools --bin fit_fast_functions`\n\
         // from tools/src/fitters/fast_function_fitter.rs. Do not edit: edit the fitter and rerun it.\n\
         //! Coefficients of the fast functions' polynomials: relative minimax fits (Remez)\n\
         //! rounded to `f32` one coefficient at a time, each rounding followed by a refit of\n\
         //! the rest. The errors quoted are those of the `f32` coefficients evaluated\n\
         //! exactly; the `f32` evaluation's own rounding is measured by the exhaustive\n\
         //! tests in `atan.rs` and `sin_cos.rs`.\n",
    );
    for fitted in fits {
        let p = &fitted.problem;
        writeln!(
            out,
            "\n/// {}.\n///\n/// Largest relative error {:.2e} (the real minimax polynomial: {:.2e}).",
            p.description, fitted.error, fitted.minimax_error
        )
        .expect("write to String");
        // The layout rustfmt gives: one line if it fits in 100 columns, else one
        // coefficient per line (`cargo fmt --check` must accept the file).
        let head = format!(
            "pub(super) const {}: [f32; {}] = [",
            p.name,
            fitted.coefficients.len()
        );
        let items: Vec<String> = fitted
            .coefficients
            .iter()
            .map(|c| format!("{c:?}"))
            .collect();
        let one_line = format!("{head}{}];", items.join(", "));
        if one_line.len() <= 100 {
            writeln!(out, "{one_line}").expect("write to String");
        } else {
            writeln!(out, "{head}").expect("write to String");
            for item in &items {
                writeln!(out, "    {item},").expect("write to String");
            }
            out.push_str("];\n");
        }
    }
    out
}
