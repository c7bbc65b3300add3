/* C ABI tests of the phase functions (sphera_phase_*): normalisation, sampling
 * consistency, the mean cosine, the Henyey–Greenstein fit, bad input. */
#include "check.h"

static unsigned rng_state = 99u;
static float uniform(void) {
  rng_state = rng_state * 1664525u + 1013904223u;
  return (float)(rng_state >> 8) * (1.0f / 16777216.0f);
}

int main(void) {
  const float gs[6] = {-0.8f, -0.2f, 0.0f, 0.4f, 0.9f, 0.99f};
  int i, k;
  for (k = 0; k < 6; k++) {
    float g = gs[k];
    double pivot = 0.0, hg = 0.0, mean = 0.0;
    const int n = 200000;
    /* 2π ∫ f dμ by the midpoint rule */
    for (i = 0; i < n; i++) {
      float mu = -1.0f + 2.0f * ((float)i + 0.5f) / (float)n;
      pivot += sphera_phase_pivot(mu, g);
      hg += sphera_phase_henyey_greenstein(mu, g);
    }
    pivot *= 2.0 * 3.14159265358979 * 2.0 / n;
    hg *= 2.0 * 3.14159265358979 * 2.0 / n;
    CHECK_REL(pivot, 1.0, g > 0.95 ? 2e-2 : 1e-3);
    CHECK_REL(hg, 1.0, g > 0.95 ? 2e-2 : 1e-3);
    /* samples: unit, pdf = f(μ), and their mean μ is the mean cosine */
    for (i = 0; i < n; i++) {
      SpheraSample s = sphera_phase_pivot_sample(vec3(0.0f, 0.0f, 1.0f), g, uniform(), uniform());
      CHECK(vec3_is_finite(s.dir) && s.pdf > 0.0f);
      if (i < 1000) CHECK_REL(s.pdf, sphera_phase_pivot(s.dir.z, g), 1e-3);
      mean += s.dir.z;
    }
    mean /= n;
    printf("g = %+.2f: pivot mean cosine %.4f (sampled %.4f), HG fit g_p = %.4f\n", g,
           sphera_phase_pivot_mean_cosine(g), mean, sphera_phase_pivot_from_henyey_greenstein(g));
    CHECK_ABS(mean, sphera_phase_pivot_mean_cosine(g), 5e-3);
    {
      SpheraSample s = sphera_phase_henyey_greenstein_sample(vec3(1.0f, 0.0f, 0.0f), g, uniform(), uniform());
      CHECK(vec3_is_finite(s.dir) && s.pdf > 0.0f);
      CHECK_REL(s.pdf, sphera_phase_henyey_greenstein(s.dir.x, g), 1e-3);
    }
  }
  CHECK_ABS(sphera_phase_pivot_mean_cosine(0.001f) / 0.001f, 4.0 / 3.0, 1e-4);
  /* bad input */
  CHECK(isfinite(sphera_phase_pivot(NAN, NAN)) && isfinite(sphera_phase_pivot(2.0f, 1.0f)));
  CHECK(isfinite(sphera_phase_henyey_greenstein(-1.0f, -1.0f)));
  CHECK(isfinite(sphera_phase_pivot_mean_cosine(INFINITY)));
  CHECK(fabsf(sphera_phase_pivot_from_henyey_greenstein(NAN)) < 1.0f);
  {
    SpheraSample s = sphera_phase_pivot_sample(vec3(0.0f, 0.0f, 0.0f), 0.5f, 0.5f, 0.5f);
    CHECK(s.pdf == 0.0f && vec3_is_finite(s.dir));
    s = sphera_phase_henyey_greenstein_sample(vec3(NAN, 0.0f, 1.0f), 0.5f, 0.5f, 0.5f);
    CHECK(s.pdf == 0.0f && vec3_is_finite(s.dir));
    s = sphera_phase_pivot_sample(vec3(0.0f, 1.0f, 0.0f), 0.9f, NAN, 7.0f);
    CHECK(s.pdf > 0.0f && vec3_is_finite(s.dir));
  }
  return check_summary();
}
