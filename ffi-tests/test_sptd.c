/* C ABI tests of SPTDs and sphere lights over GGX (sphera_sptd_*, sphera_ggx_pivot_from_view,
 * sphera_sphere_light_*, sphera_sptd_in_cap_prepare_pivot_phase). */
#include <string.h>

#include "check.h"

static const double PI_D = 3.14159265358979323846;

static void check_sptd_in_cap(void) {
  SpheraVec3 pivot = vec3(0.3f, 0.0f, 0.6f);
  SpheraVec3 z = vec3(0.0f, 0.0f, 1.0f);
  SpheraCap cap = sphera_cap_from_sphere(vec3(1.0f, 0.5f, 3.0f), 1.0f);
  SpheraSptdInCap prepared;
  float u[U_COUNT];
  double inverse_sum = 0.0;
  int i, j, n = 0;
  CHECK(sphera_sptd_in_cap_prepare(&prepared, pivot, SPHERA_SPTD_UNIFORM, z, cap));
  /* The prepared integral takes the closed-form pivot of the cap, the general one the
   * careful form: each is within 6.2e-7 of an f64 reference here (measured), so they
   * agree to the sum of the two. */
  CHECK_REL(sphera_sptd_in_cap_integral(&prepared),
            sphera_sptd_integral_over_cap(pivot, SPHERA_SPTD_UNIFORM, z, cap), 1.5e-6);
  /* The uniform SPTD is the Jacobian over 4 pi (Eq. 8). */
  CHECK_REL(sphera_sptd_eval(pivot, SPHERA_SPTD_UNIFORM, z, vec3(0.0f, 0.6f, 0.8f)),
            sphera_pivot_jacobian(vec3(0.0f, 0.6f, 0.8f), pivot) / (4.0 * PI_D), 1e-5);
  fill_u_values(u);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = sphera_sptd_in_cap_sample(&prepared, u[i], u[j]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf));
      if (s.pdf > 0.0f) {
        CHECK(sphera_cap_contains(cap, s.dir));
        CHECK(sphera_sptd_in_cap_pdf(&prepared, s.dir) == s.pdf);
      }
    }
  }
  /* E[1/pdf] = solid angle of the cap. */
  for (i = 0; i < 100; i++) {
    for (j = 0; j < 100; j++) {
      SpheraSample s = sphera_sptd_in_cap_sample(&prepared, (i + 0.5f) / 100.0f, (j + 0.5f) / 100.0f);
      if (s.pdf > 0.0f) {
        inverse_sum += 1.0 / s.pdf;
        n++;
      }
    }
  }
  CHECK(n >= 9990);
  CHECK_REL(inverse_sum / 10000.0, sphera_cap_solid_angle(cap), 2e-2);
  /* The clamped cosine: the integral over the whole sphere is one; over the
   * intersection of a cap with itself, the integral over the cap. */
  CHECK_REL(sphera_sptd_integral_over_cap(pivot, SPHERA_SPTD_CLAMPED_COSINE, z,
                                          sphera_cap_from_axis_cos(z, -1.0f)),
            1.0, 1e-5);
  CHECK_REL(sphera_sptd_integral_over_cap_intersection(pivot, SPHERA_SPTD_CLAMPED_COSINE, z, cap, cap),
            sphera_sptd_integral_over_cap(pivot, SPHERA_SPTD_CLAMPED_COSINE, z, cap), 1e-4);
}

/* Unions and complements of caps (Eq. 11, issue 20, 1): the values against closed
 * forms in double (pivot at the origin: g is the antipodal map, so the uniform base
 * integrates to the solid angle over 4 pi; coaxial caps), the set identities, and
 * malformed caps, an unknown base and non-finite input giving 0. */
static void check_unions_and_complements(void) {
  SpheraVec3 origin = vec3(0.0f, 0.0f, 0.0f), pivot = vec3(0.3f, 0.0f, 0.6f);
  SpheraVec3 z = vec3(0.0f, 0.0f, 1.0f);
  SpheraCap a = sphera_cap_from_axis_cos(z, 0.5f);                      /* 1 - cos = 0.5 */
  SpheraCap inner = sphera_cap_from_axis_cos(z, 0.8f);                  /* inside a */
  SpheraCap below = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, -1.0f), 0.9f); /* disjoint */
  SpheraCap light = sphera_cap_from_sphere(vec3(1.0f, 0.5f, 3.0f), 1.0f);
  SpheraCap malformed = a;
  const uint32_t bases[2] = {SPHERA_SPTD_UNIFORM, SPHERA_SPTD_CLAMPED_COSINE};
  const float bad[] = {NAN, INFINITY, -INFINITY, 0.0f, -1.0f, 1e30f, 3e38f, 1e-45f};
  const int n = (int)(sizeof(bad) / sizeof(bad[0]));
  int b, i, k;
  /* Uniform base, pivot at the origin: solid angles over 4 pi. */
  CHECK_REL(sphera_sptd_integral_over_cap_union(origin, SPHERA_SPTD_UNIFORM, z, a, inner),
            0.5 / 2.0, 1e-6);
  CHECK_REL(sphera_sptd_integral_over_cap_union(origin, SPHERA_SPTD_UNIFORM, z, a, below),
            (0.5 + 0.1) / 2.0, 1e-5);
  CHECK_REL(sphera_sptd_integral_over_cap_complement(origin, SPHERA_SPTD_UNIFORM, z, a),
            1.5 / 2.0, 1e-6);
  /* Clamped cosine about z, pivot at the origin: the images lie about -z, a below the
   * horizon (0) and `below`'s image the cap of 1 - cos = 0.1 about z: 1 - cos^2 = 0.19. */
  CHECK_ABS(sphera_sptd_integral_over_cap_union(origin, SPHERA_SPTD_CLAMPED_COSINE, z, a, below),
            0.19, 1e-6);
  CHECK_ABS(sphera_sptd_integral_over_cap_complement(origin, SPHERA_SPTD_CLAMPED_COSINE, z, below),
            1.0 - 0.19, 1e-6);
  for (b = 0; b < 2; b++) {
    float in_a = sphera_sptd_integral_over_cap(pivot, bases[b], z, a);
    float in_light = sphera_sptd_integral_over_cap(pivot, bases[b], z, light);
    float both = sphera_sptd_integral_over_cap_intersection(pivot, bases[b], z, a, light);
    SpheraCap empty = sphera_cap_from_sphere(vec3(0.0f, 0.0f, 1.0f), -1.0f);
    CHECK_ABS(sphera_sptd_integral_over_cap_union(pivot, bases[b], z, a, light),
              in_a + in_light - both, 2e-6);
    CHECK_ABS(sphera_sptd_integral_over_cap_union(pivot, bases[b], z, light, a),
              in_a + in_light - both, 2e-6);
    CHECK_ABS(sphera_sptd_integral_over_cap_union(pivot, bases[b], z, a, a), in_a, 2e-6);
    CHECK_ABS(sphera_sptd_integral_over_cap_complement(pivot, bases[b], z, a), 1.0 - in_a, 2e-6);
    /* The empty cap is the empty set; its complement the whole sphere. */
    CHECK_ABS(sphera_sptd_integral_over_cap_union(pivot, bases[b], z, empty, a), in_a, 0.0);
    CHECK_ABS(sphera_sptd_integral_over_cap_complement(pivot, bases[b], z, empty), 1.0, 1e-6);
  }
  /* Malformed caps and an unknown base: 0. */
  malformed.one_minus_cos = NAN;
  CHECK(sphera_sptd_integral_over_cap_union(pivot, SPHERA_SPTD_UNIFORM, z, malformed, a) == 0.0f);
  CHECK(sphera_sptd_integral_over_cap_union(pivot, SPHERA_SPTD_UNIFORM, z, a, malformed) == 0.0f);
  CHECK(sphera_sptd_integral_over_cap_complement(pivot, SPHERA_SPTD_UNIFORM, z, malformed) == 0.0f);
  malformed = a;
  malformed.axis = vec3(INFINITY, 0.0f, 1.0f);
  CHECK(sphera_sptd_integral_over_cap_complement(pivot, SPHERA_SPTD_CLAMPED_COSINE, z, malformed) == 0.0f);
  malformed.axis = vec3(0.0f, 0.0f, 0.0f);
  CHECK(sphera_sptd_integral_over_cap_union(pivot, SPHERA_SPTD_CLAMPED_COSINE, z, a, malformed) == 0.0f);
  CHECK(sphera_sptd_integral_over_cap_union(pivot, 2u, z, a, light) == 0.0f);
  CHECK(sphera_sptd_integral_over_cap_complement(pivot, UINT32_MAX, z, a) == 0.0f);
  /* Non-finite and extreme input anywhere: finite, in [0, 1]. */
  for (i = 0; i < n; i++) {
    for (k = 0; k < n; k++) {
      SpheraVec3 v = vec3(bad[i], 0.5f, bad[k]);
      SpheraCap garbage;
      float u, c;
      garbage.axis = v;
      garbage.one_minus_cos = bad[k];
      garbage.one_plus_cos = bad[i];
      garbage.sin2 = bad[k];
      for (b = 0; b < 3; b++) {
        u = sphera_sptd_integral_over_cap_union(v, (uint32_t)b, v, garbage, light);
        c = sphera_sptd_integral_over_cap_complement(v, (uint32_t)b, v, garbage);
        CHECK(isfinite(u) && u >= 0.0f && u <= 1.0f);
        CHECK(isfinite(c) && c >= 0.0f && c <= 1.0f);
        if (b == 2) CHECK(u == 0.0f && c == 0.0f);
      }
    }
  }
}

/* An unknown base number is an error, not a silent uniform base: density 0, no sample,
 * integrals 0 and a failed prepare, where the uniform base (checked alongside with the
 * same arguments) gives positive values. */
static void check_unknown_base(void) {
  const uint32_t unknown[3] = {SPHERA_SPTD_CLAMPED_COSINE + 1u, 7u, UINT32_MAX};
  SpheraVec3 pivot = vec3(0.3f, 0.0f, 0.6f);
  SpheraVec3 z = vec3(0.0f, 0.0f, 1.0f);
  SpheraVec3 dir = vec3(0.0f, 0.6f, 0.8f);
  SpheraCap cap = sphera_cap_from_sphere(vec3(1.0f, 0.5f, 3.0f), 1.0f);
  SpheraCap other = sphera_cap_from_axis_cos(z, 0.0f);
  SpheraSptdInCap prepared;
  SpheraSample s;
  int k;
  CHECK(sphera_sptd_eval(pivot, SPHERA_SPTD_UNIFORM, z, dir) > 0.0f);
  CHECK(sphera_sptd_sample(pivot, SPHERA_SPTD_UNIFORM, z, 0.3f, 0.7f).pdf > 0.0f);
  CHECK(sphera_sptd_integral_over_cap(pivot, SPHERA_SPTD_UNIFORM, z, cap) > 0.0f);
  CHECK(sphera_sptd_integral_over_cap_intersection(pivot, SPHERA_SPTD_UNIFORM, z, cap, other) > 0.0f);
  for (k = 0; k < 3; k++) {
    CHECK(sphera_sptd_eval(pivot, unknown[k], z, dir) == 0.0f);
    s = sphera_sptd_sample(pivot, unknown[k], z, 0.3f, 0.7f);
    CHECK(s.pdf == 0.0f && s.dir.x == 0.0f && s.dir.y == 0.0f && s.dir.z == 1.0f);
    CHECK(sphera_sptd_integral_over_cap(pivot, unknown[k], z, cap) == 0.0f);
    CHECK(sphera_sptd_integral_over_cap_intersection(pivot, unknown[k], z, cap, other) == 0.0f);
    memset(&prepared, 0xff, sizeof prepared);
    CHECK(!sphera_sptd_in_cap_prepare(&prepared, pivot, unknown[k], z, cap));
    CHECK(sphera_sptd_in_cap_integral(&prepared) == 0.0f);
    CHECK(sphera_sptd_in_cap_sample(&prepared, 0.3f, 0.7f).pdf == 0.0f);
    CHECK(sphera_sptd_in_cap_pdf(&prepared, dir) == 0.0f);
  }
  CHECK(sphera_sptd_in_cap_prepare(&prepared, pivot, SPHERA_SPTD_UNIFORM, z, cap));
}

static void check_sphere_light(void) {
  SpheraVec3 wo = vec3(0.5f, 0.0f, 0.8660254f);
  SpheraVec3 mirror = vec3(-1.5f, 0.0f, 2.598076f);
  SpheraCap light = sphera_cap_from_sphere(mirror, 0.5f);
  SpheraCap horizon = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, 1.0f), 0.0f);
  SpheraCap away = sphera_cap_from_axis_cos(vec3(1.0f, 0.0f, 0.2f), 0.9f);
  SpheraSphereLightShading shading;
  SpheraSphereLightSampler sampler;
  SpheraGgxPivot fit;
  SpheraVec3 value;
  float u[U_COUNT];
  int i, j;
  CHECK(sphera_ggx_pivot_from_view(&fit, wo, 0.3f));
  CHECK(dlength(dvec(fit.pivot)) < 1.0 && fit.albedo > 0.5f && fit.albedo <= 1.0f);
  CHECK(fit.pivot.x < 0.0f); /* it leans towards the mirror direction */
  CHECK(sphera_sphere_light_shading_prepare(&shading, wo, 0.3f, vec3(1.0f, 1.0f, 1.0f)));
  value = sphera_sphere_light_shading_eval(&shading, light);
  CHECK(value.x > 0.0f && value.x <= fit.albedo && value.x == value.z);
  CHECK(vec3_equal(sphera_sphere_light_shading_eval_occluded(&shading, light, horizon), value));
  CHECK(sphera_sphere_light_shading_eval_occluded(&shading, light, away).x == 0.0f);
  /* The separable baseline (Eq. 21-22): the unoccluded value for the hemisphere, none
   * for a cone away from the light and the lobe. */
  CHECK(fabsf(sphera_sphere_light_shading_eval_occluded_separable(&shading, light, horizon).x - value.x) <=
        1e-6f * value.x);
  CHECK(sphera_sphere_light_shading_eval_occluded_separable(&shading, light, away).x >= 0.0f);
  CHECK(sphera_sphere_light_shading_eval_occluded_separable(&shading, light, away).x <= value.x);
  /* The bent cone prepared in: _eval gives _eval_occluded with that cone, bit for bit. */
  {
    SpheraSphereLightShading occluded;
    SpheraCap cones[3];
    int c;
    cones[0] = horizon;
    cones[1] = away;
    cones[2] = sphera_cap_from_axis_cos(vec3(-0.3f, 0.1f, 1.0f), 0.6f);
    for (c = 0; c < 3; c++) {
      CHECK(sphera_sphere_light_shading_prepare_occluded(&occluded, wo, 0.3f, vec3(1.0f, 1.0f, 1.0f), cones[c]));
      CHECK(vec3_equal(sphera_sphere_light_shading_eval(&occluded, light),
                       sphera_sphere_light_shading_eval_occluded(&shading, light, cones[c])));
    }
    CHECK(sphera_sphere_light_shading_eval(&occluded, light).x > 0.0f);
    CHECK(sphera_sphere_light_shading_eval(&occluded, light).x <= value.x);
  }

  CHECK(sphera_sphere_light_sampler_prepare(&sampler, mirror, 0.5f, wo, 0.3f));
  CHECK(sphera_sphere_light_sampler_uses_sptd(&sampler));
  /* The fit of the shading point prepared once: the same sampler, byte for byte. */
  {
    SpheraSphereLightSampler from_fit;
    memset(&from_fit, 0xff, sizeof from_fit);
    CHECK(sphera_sphere_light_sampler_prepare_with_fit(&from_fit, mirror, 0.5f, &fit));
    CHECK(memcmp(&from_fit, &sampler, sizeof sampler) == 0);
    CHECK(!sphera_sphere_light_sampler_prepare_with_fit(&from_fit, mirror, 0.5f, NULL));
    CHECK(sphera_sphere_light_sampler_sample(&from_fit, 0.5f, 0.5f).pdf == 0.0f);
    CHECK(!sphera_sphere_light_sampler_prepare_with_fit(&from_fit, mirror, -1.0f, &fit));
    CHECK(sphera_sphere_light_sampler_sample(&from_fit, 0.5f, 0.5f).pdf == 0.0f);
  }
  fill_u_values(u);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = sphera_sphere_light_sampler_sample(&sampler, u[i], u[j]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf));
      if (s.pdf > 0.0f) {
        CHECK(sphera_cap_contains(light, s.dir));
        CHECK(sphera_sphere_light_sampler_pdf(&sampler, s.dir) == s.pdf);
      }
    }
  }
  /* A tiny light away from the highlight falls back to uniform cap sampling. */
  CHECK(sphera_sphere_light_sampler_prepare(&sampler, vec3(500.0f, 200.0f, 300.0f), 1.0f, wo, 0.2f));
  CHECK(!sphera_sphere_light_sampler_uses_sptd(&sampler));
}

static void check_phase_in_cap(void) {
  SpheraVec3 wo = vec3(0.0f, 0.6f, 0.8f);
  SpheraCap light = sphera_cap_from_sphere(vec3(0.0f, 3.0f, 4.0f), 1.0f);
  SpheraSptdInCap prepared;
  int i;
  CHECK(sphera_sptd_in_cap_prepare_pivot_phase(&prepared, wo, 0.7f, light));
  for (i = 0; i < 64; i++) {
    SpheraSample s = sphera_sptd_in_cap_sample(&prepared, (i + 0.5f) / 64.0f, 0.37f);
    float f;
    if (s.pdf == 0.0f) continue;
    f = sphera_phase_pivot(s.dir.x * wo.x + s.dir.y * wo.y + s.dir.z * wo.z, 0.7f);
    /* Zero variance: f / pdf is the integral for every sample. */
    CHECK_REL(f / s.pdf, sphera_sptd_in_cap_integral(&prepared), 2e-3);
  }
}

static void check_bad_input(void) {
  const float bad[] = {NAN, INFINITY, -INFINITY, 0.0f, -0.0f, 1e-40f, 1e30f, -1e30f};
  const int n = (int)(sizeof bad / sizeof bad[0]);
  SpheraCap cap = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, 1.0f), 0.5f);
  SpheraSptdInCap prepared;
  SpheraSphereLightShading shading;
  SpheraSphereLightSampler sampler;
  SpheraGgxPivot fit;
  int i, k;
  CHECK(!sphera_sptd_in_cap_prepare(NULL, vec3(0, 0, 0), 0, vec3(0, 0, 1), cap));
  CHECK(sphera_sptd_in_cap_sample(NULL, 0.5f, 0.5f).pdf == 0.0f);
  CHECK(sphera_sptd_in_cap_pdf(NULL, vec3(0, 0, 1)) == 0.0f);
  CHECK(sphera_sptd_in_cap_integral(NULL) == 0.0f);
  CHECK(!sphera_ggx_pivot_from_view(NULL, vec3(0, 0, 1), 0.5f));
  CHECK(!sphera_sphere_light_shading_prepare(NULL, vec3(0, 0, 1), 0.5f, vec3(1, 1, 1)));
  CHECK(!sphera_sphere_light_shading_prepare_occluded(NULL, vec3(0, 0, 1), 0.5f, vec3(1, 1, 1), cap));
  CHECK(vec3_equal(sphera_sphere_light_shading_eval(NULL, cap), vec3(0, 0, 0)));
  CHECK(vec3_equal(sphera_sphere_light_shading_eval_occluded(NULL, cap, cap), vec3(0, 0, 0)));
  CHECK(vec3_equal(sphera_sphere_light_shading_eval_occluded_separable(NULL, cap, cap), vec3(0, 0, 0)));
  CHECK(!sphera_sphere_light_sampler_prepare(NULL, vec3(0, 0, 3), 1.0f, vec3(0, 0, 1), 0.5f));
  CHECK(!sphera_sphere_light_sampler_prepare_with_fit(NULL, vec3(0, 0, 3), 1.0f, &fit));
  CHECK(!sphera_sphere_light_sampler_prepare_with_fit(NULL, vec3(0, 0, 3), 1.0f, NULL));
  CHECK(sphera_sphere_light_sampler_sample(NULL, 0.5f, 0.5f).pdf == 0.0f);
  CHECK(sphera_sphere_light_sampler_pdf(NULL, vec3(0, 0, 1)) == 0.0f);
  CHECK(!sphera_sphere_light_sampler_uses_sptd(NULL));
  CHECK(!sphera_sptd_in_cap_prepare_pivot_phase(NULL, vec3(0, 0, 1), 0.5f, cap));
  /* Failed prepares write samplers without samples. */
  CHECK(!sphera_sptd_in_cap_prepare(&prepared, vec3(0, 0, 0), 0, vec3(0, 0, 1),
                                    sphera_cap_from_sphere(vec3(0, 0, 3), -1.0f)));
  CHECK(sphera_sptd_in_cap_sample(&prepared, 0.5f, 0.5f).pdf == 0.0f);
  CHECK(!sphera_sphere_light_sampler_prepare(&sampler, vec3(0, 0, 3), 1.0f, vec3(0, 0, -1), 0.5f));
  CHECK(sphera_sphere_light_sampler_sample(&sampler, 0.5f, 0.5f).pdf == 0.0f);
  CHECK(!sphera_sphere_light_shading_prepare(&shading, vec3(1, 0, 0), 0.5f, vec3(1, 1, 1)));
  CHECK(vec3_equal(sphera_sphere_light_shading_eval(&shading, cap), vec3(0, 0, 0)));
  CHECK(sphera_sphere_light_shading_prepare(&shading, vec3(0, 0, 1), 0.5f, vec3(1, 1, 1)));
  CHECK(!sphera_sphere_light_shading_prepare_occluded(&shading, vec3(1, 0, 0), 0.5f, vec3(1, 1, 1), cap));
  CHECK(vec3_equal(sphera_sphere_light_shading_eval(&shading, cap), vec3(0, 0, 0)));
  CHECK(!sphera_ggx_pivot_from_view(&fit, vec3(0, 0, -1), 0.5f));
  for (i = 0; i < n; i++) {
    for (k = 0; k < n; k++) {
      SpheraVec3 v = vec3(bad[i], bad[k], 1.0f);
      SpheraCap garbage;
      SpheraSample s;
      unsigned base = (unsigned)(i % 3); /* 2 is not a base: uniform */
      garbage.axis = v;
      garbage.one_minus_cos = bad[k];
      garbage.one_plus_cos = bad[i];
      garbage.sin2 = bad[k];
      CHECK(isfinite(sphera_sptd_eval(v, base, v, v)));
      s = sphera_sptd_sample(v, base, v, bad[i], bad[k]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf));
      CHECK(isfinite(sphera_sptd_integral_over_cap(v, base, v, garbage)));
      CHECK(isfinite(sphera_sptd_integral_over_cap_intersection(v, base, v, garbage, cap)));
      sphera_sptd_in_cap_prepare(&prepared, v, base, v, garbage);
      s = sphera_sptd_in_cap_sample(&prepared, bad[i], bad[k]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf));
      CHECK(isfinite(sphera_sptd_in_cap_pdf(&prepared, v)));
      sphera_sptd_in_cap_prepare(&prepared, v, base, v, cap);
      s = sphera_sptd_in_cap_sample(&prepared, bad[i], bad[k]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf));
      sphera_sphere_light_shading_prepare(&shading, v, bad[k], v);
      CHECK(vec3_is_finite(sphera_sphere_light_shading_eval(&shading, garbage)));
      CHECK(vec3_is_finite(sphera_sphere_light_shading_eval_occluded(&shading, cap, garbage)));
      CHECK(vec3_is_finite(sphera_sphere_light_shading_eval_occluded_separable(&shading, garbage, garbage)));
      sphera_sphere_light_shading_prepare_occluded(&shading, v, bad[k], v, garbage);
      CHECK(vec3_is_finite(sphera_sphere_light_shading_eval(&shading, garbage)));
      CHECK(vec3_is_finite(sphera_sphere_light_shading_eval(&shading, cap)));
      sphera_sphere_light_sampler_prepare(&sampler, v, bad[k], v, bad[i]);
      s = sphera_sphere_light_sampler_sample(&sampler, bad[i], bad[k]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf));
      fit.pivot = v;
      fit.albedo = bad[i];
      sphera_sphere_light_sampler_prepare_with_fit(&sampler, v, bad[k], &fit);
      s = sphera_sphere_light_sampler_sample(&sampler, bad[i], bad[k]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf));
      CHECK(isfinite(sphera_sphere_light_sampler_pdf(&sampler, v)));
      CHECK(isfinite(sphera_sphere_light_sampler_pdf(&sampler, v)));
      sphera_sptd_in_cap_prepare_pivot_phase(&prepared, v, bad[k], garbage);
      s = sphera_sptd_in_cap_sample(&prepared, bad[i], bad[k]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf));
      sphera_ggx_pivot_from_view(&fit, v, bad[k]);
      CHECK(vec3_is_finite(fit.pivot) && isfinite(fit.albedo));
    }
  }
}

int main(void) {
  check_sptd_in_cap();
  check_unknown_base();
  check_unions_and_complements();
  check_sphere_light();
  check_phase_in_cap();
  check_bad_input();
  return check_summary();
}
