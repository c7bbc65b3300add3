/* C ABI tests of the two-technique MIS heuristics (sphera_mis_*): their formulas,
 * weights summing to one, unbiased estimators on [0, 1] with an occluder, and bad
 * input (NaN, infinities, zeros, overflow). */
#include "check.h"

/* ---- a deterministic generator (xorshift64*) -------------------------------------- */

static unsigned long long rng_state = 0x9E3779B97F4A7C15ULL;

static float uniform(void) {
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return (float)((rng_state * 0x2545F4914F6CDD1DULL) >> 40) * (1.0f / 16777216.0f);
}

/* ---- formulas ----------------------------------------------------------------------- */

static void check_formulas(void) {
  const double p0 = 0.5, p1 = 2.0, c0 = 3.0, c1 = 1.0, f = 2.5, v = 0.3;
  double cp = c0 * p0 + c1 * p1, sum = p0 + p1;
  printf("formulas\n");
  CHECK_REL(sphera_mis_balance(0.5f, 2.0f), p0 / sum, 1e-6);
  CHECK_REL(sphera_mis_power(0.5f, 2.0f), p0 * p0 / (p0 * p0 + p1 * p1), 1e-6);
  CHECK_REL(sphera_mis_weighted_balance(0.5f, 3.0f, 2.0f, 1.0f), c0 * p0 / cp, 1e-6);
  CHECK_REL(sphera_mis_clamped_optimal_weight(0.5f, 3.0f, 2.0f, 1.0f, 0.3f),
            p0 * (v * c0 / cp + (1.0 - v) / sum), 1e-6);
  CHECK_REL(sphera_mis_clamped_optimal_contribution(2.5f, 0.5f, 3.0f, 2.0f, 1.0f, 0.3f),
            f * (v * c0 / cp + (1.0 - v) / sum), 1e-6);
  CHECK_REL(sphera_mis_optimal_contribution(2.5f, 0.5f, 3.0f, 2.0f, 1.0f, 0.3f),
            v * c0 + (f - v * cp) / sum, 1e-6);
  CHECK(SPHERA_MIS_DEFAULT_VISIBILITY == 0.5);
}

/* Weights sum to one; clamped optimal MIS blends balance (v = 0) and weighted balance
 * (v = 1); its contribution is f times its weight over the pdf. */
static void check_weights(void) {
  int k;
  printf("weights\n");
  for (k = 0; k < 10000; k++) {
    float p0 = (float)pow(10.0, 6.0 * uniform() - 3.0), p1 = (float)pow(10.0, 6.0 * uniform() - 3.0);
    float c0 = uniform(), c1 = uniform(), v = uniform(), f = 4.0f * uniform();
    float w0, w1, expected;
    if (k % 7 == 0) p1 = 0.0f;
    if (k % 11 == 0) c0 = 0.0f;
    if (!CHECK_ABS(sphera_mis_balance(p0, p1) + sphera_mis_balance(p1, p0), 1.0, 1e-6)) return;
    if (!CHECK_ABS(sphera_mis_power(p0, p1) + sphera_mis_power(p1, p0), 1.0, 1e-6)) return;
    w0 = sphera_mis_weighted_balance(p0, c0, p1, c1);
    w1 = sphera_mis_weighted_balance(p1, c1, p0, c0);
    if (!CHECK_ABS(w0 + w1, 1.0, 1e-6)) return;
    w0 = sphera_mis_clamped_optimal_weight(p0, c0, p1, c1, v);
    w1 = sphera_mis_clamped_optimal_weight(p1, c1, p0, c0, v);
    if (!CHECK_ABS(w0 + w1, 1.0, 1e-6)) return;
    if (!CHECK(sphera_mis_clamped_optimal_weight(p0, c0, p1, c1, 0.0f) == sphera_mis_balance(p0, p1)))
      return;
    if (!CHECK(sphera_mis_clamped_optimal_weight(p0, c0, p1, c1, 1.0f) ==
               sphera_mis_weighted_balance(p0, c0, p1, c1)))
      return;
    expected = f * w0 / p0;
    if (!CHECK_REL(sphera_mis_clamped_optimal_contribution(f, p0, c0, p1, c1, v), expected, 1e-5))
      return;
  }
  /* A technique with pdf 0 gets weight 0, the other one weight 1. */
  CHECK(sphera_mis_balance(0.0f, 3.0f) == 0.0f);
  CHECK(sphera_mis_balance(3.0f, 0.0f) == 1.0f);
  CHECK(sphera_mis_power(0.0f, 3.0f) == 0.0f);
  CHECK(sphera_mis_weighted_balance(0.0f, 1.0f, 3.0f, 1.0f) == 0.0f);
  CHECK(sphera_mis_weighted_balance(3.0f, 1.0f, 0.0f, 1.0f) == 1.0f);
  /* c p = 0 for both: the balance heuristic. */
  CHECK(sphera_mis_weighted_balance(1.0f, 0.0f, 3.0f, 0.0f) == 0.25f);
}

/* ---- unbiased estimators on [0, 1] ------------------------------------------------- */

/* Technique 0 uniform (p = 1), technique 1 linear (p = 2x); occluded on [0.3, 0.55). */
static int visible(float x) { return !(x >= 0.3f && x < 0.55f); }

typedef float (*Contribution)(float f, float p_this, float c_this, float p_other, float c_other);

static float by_balance(float f, float p, float c, float q, float d) {
  (void)c;
  (void)d;
  return sphera_mis_balance(p, q) * f / p;
}
static float by_power(float f, float p, float c, float q, float d) {
  (void)c;
  (void)d;
  return sphera_mis_power(p, q) * f / p;
}
static float by_weighted(float f, float p, float c, float q, float d) {
  return sphera_mis_weighted_balance(p, c, q, d) * f / p;
}
static float by_clamped_weight(float f, float p, float c, float q, float d) {
  return sphera_mis_clamped_optimal_weight(p, c, q, d, 0.5f) * f / p;
}
static float by_clamped(float f, float p, float c, float q, float d) {
  return sphera_mis_clamped_optimal_contribution(f, p, c, q, d, (float)SPHERA_MIS_DEFAULT_VISIBILITY);
}
static float by_optimal(float f, float p, float c, float q, float d) {
  return sphera_mis_optimal_contribution(f, p, c, q, d, 0.5f);
}

static void check_estimator(const char *name, Contribution contribution, int occluded) {
  const float c[2] = {0.7f, 0.4f};
  /* ∫ V (c0 + 2 c1 x) dx with V = 0 on [0.3, 0.55) (or 1 everywhere). */
  double reference = occluded ? c[0] * 0.75 + c[1] * (1.0 - (0.55 * 0.55 - 0.3 * 0.3)) : c[0] + c[1];
  double sum = 0.0, sum2 = 0.0, mean, error;
  int n = 400000, i, j;
  for (i = 0; i < n; i++) {
    double total = 0.0;
    for (j = 0; j < 2; j++) {
      float u = uniform();
      float x = j == 0 ? u : sqrtf(u);
      float p[2], f;
      p[0] = 1.0f;
      p[1] = 2.0f * x;
      if (p[j] == 0.0f) continue;
      f = (!occluded || visible(x)) ? c[0] * p[0] + c[1] * p[1] : 0.0f;
      total += contribution(f, p[j], c[j], p[1 - j], c[1 - j]);
    }
    sum += total;
    sum2 += total * total;
  }
  mean = sum / n;
  error = sqrt((sum2 / n - mean * mean) / (n - 1));
  printf("  %s (%s): mean %.6f, reference %.6f, standard error %.2e\n", name,
         occluded ? "occluded" : "unoccluded", mean, reference, error);
  CHECK(fabs(mean - reference) <= 5.0 * error + 1e-6 * reference);
  /* Without occlusion the weighted balance heuristic has zero variance. */
  if (!occluded && contribution == by_weighted) CHECK(error < 1e-6);
}

static void check_estimators(void) {
  const Contribution all[6] = {by_balance, by_power, by_weighted, by_clamped_weight, by_clamped, by_optimal};
  const char *names[6] = {"balance", "power", "weighted balance", "clamped optimal weight",
                          "clamped optimal", "optimal"};
  int k;
  printf("estimators\n");
  for (k = 0; k < 6; k++) {
    check_estimator(names[k], all[k], 1);
    check_estimator(names[k], all[k], 0);
  }
}

/* ---- bad input ---------------------------------------------------------------------- */

static void check_bad_input(void) {
  const float odd[] = {0.0f, -0.0f, 1e-45f, 1e-30f, 0.5f, 1.0f, 1e30f, 3e38f, -1.0f, NAN, INFINITY, -INFINITY};
  const int n = (int)(sizeof odd / sizeof odd[0]);
  int a, b, c, finite = 1;
  printf("bad input\n");
  /* NaN and negative pdfs count as 0; both 0: weight 0. */
  CHECK(sphera_mis_balance(NAN, 1.0f) == 0.0f);
  CHECK(sphera_mis_balance(1.0f, NAN) == 1.0f);
  CHECK(sphera_mis_balance(-2.0f, 1.0f) == 0.0f);
  CHECK(sphera_mis_balance(0.0f, 0.0f) == 0.0f);
  CHECK(sphera_mis_power(NAN, NAN) == 0.0f);
  CHECK(sphera_mis_clamped_optimal_weight(0.0f, 1.0f, 0.0f, 1.0f, 0.5f) == 0.0f);
  CHECK(sphera_mis_optimal_contribution(1.0f, 0.0f, 1.0f, 2.0f, 1.0f, 0.5f) == 0.0f);
  CHECK(sphera_mis_clamped_optimal_contribution(1.0f, 0.0f, 1.0f, 2.0f, 1.0f, 0.5f) == 0.0f);
  /* Infinite pdfs take the weight, shared when both are infinite. */
  CHECK(sphera_mis_balance(INFINITY, 1.0f) == 1.0f);
  CHECK(sphera_mis_balance(1.0f, INFINITY) == 0.0f);
  CHECK(sphera_mis_balance(INFINITY, INFINITY) == 0.5f);
  CHECK(sphera_mis_power(INFINITY, INFINITY) == 0.5f);
  CHECK(sphera_mis_clamped_optimal_contribution(1.0f, INFINITY, 1.0f, 1.0f, 1.0f, 0.5f) == 0.0f);
  /* Huge and tiny pdfs: no overflow of p² or of the sums. */
  CHECK(sphera_mis_power(3e38f, 3e38f) == 0.5f);
  CHECK(sphera_mis_power(1e-30f, 1e-30f) == 0.5f);
  CHECK(sphera_mis_balance(3e38f, 3e38f) == 0.5f);
  /* NaN v counts as 0 (balance), v outside [0, 1] is clamped. */
  CHECK(sphera_mis_clamped_optimal_weight(1.0f, 3.0f, 1.0f, 1.0f, NAN) == 0.5f);
  CHECK(sphera_mis_clamped_optimal_weight(1.0f, 3.0f, 1.0f, 1.0f, 5.0f) == 0.75f);
  /* NaN or infinite f: the sample is discarded. */
  CHECK(sphera_mis_optimal_contribution(NAN, 1.0f, 1.0f, 1.0f, 1.0f, 0.5f) == 0.0f);
  CHECK(sphera_mis_clamped_optimal_contribution(INFINITY, 1.0f, 1.0f, 1.0f, 1.0f, 0.5f) == 0.0f);
  /* An overflowing contribution is 0. */
  CHECK(sphera_mis_clamped_optimal_contribution(1e30f, 1e-30f, 1.0f, 1e-30f, 1.0f, 0.5f) == 0.0f);
  /* NaN and infinite contributions count as 0. */
  CHECK(sphera_mis_weighted_balance(1.0f, NAN, 1.0f, 2.0f) == 0.0f);
  CHECK(sphera_mis_weighted_balance(1.0f, INFINITY, 1.0f, 2.0f) == 0.0f);
  /* Every combination of odd values gives finite results in [0, 1] for the weights. */
  for (a = 0; a < n; a++) {
    for (b = 0; b < n; b++) {
      for (c = 0; c < n; c++) {
        float w[4], k[2];
        int i;
        w[0] = sphera_mis_balance(odd[a], odd[b]);
        w[1] = sphera_mis_power(odd[a], odd[b]);
        w[2] = sphera_mis_weighted_balance(odd[a], odd[c], odd[b], odd[(c + 5) % n]);
        w[3] = sphera_mis_clamped_optimal_weight(odd[a], odd[c], odd[b], odd[(c + 3) % n], odd[(a + c) % n]);
        k[0] = sphera_mis_optimal_contribution(odd[c], odd[a], odd[b], odd[(a + 1) % n], odd[c], odd[b]);
        k[1] = sphera_mis_clamped_optimal_contribution(odd[c], odd[a], odd[b], odd[(a + 1) % n], odd[c],
                                                       odd[b]);
        for (i = 0; i < 4; i++) finite &= isfinite(w[i]) && w[i] >= 0.0f && w[i] <= 1.0f;
        finite &= isfinite(k[0]) && isfinite(k[1]);
      }
    }
  }
  CHECK(finite);
}

int main(void) {
  check_formulas();
  check_weights();
  check_estimators();
  check_bad_input();
  return check_summary();
}
