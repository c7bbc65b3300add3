/* C ABI tests of the GGX-fitted LTCs and their sampling inside polygons (sphera_ltc_*). */
#include <string.h>

#include "check.h"

static const SpheraVec3 QUAD[4] = {{-1.0f, -1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {-1.0f, 1.0f, 1.0f}};
/* Around the mirror direction (-0.5, 0, 0.866) of the view (0.5, 0, 0.866), and the same
 * quad mirrored to the side of the view. */
static const SpheraVec3 MIRROR_QUAD[4] = {{-1.2f, -0.3f, 1.5f}, {-0.6f, -0.3f, 1.5f}, {-0.6f, 0.3f, 1.5f}, {-1.2f, 0.3f, 1.5f}};
static const SpheraVec3 AWAY_QUAD[4] = {{1.2f, -0.3f, 1.5f}, {0.6f, -0.3f, 1.5f}, {0.6f, 0.3f, 1.5f}, {1.2f, 0.3f, 1.5f}};
static const SpheraVec3 BELOW[3] = {{0.5f, 0.0f, -1.0f}, {-0.5f, 0.5f, -1.0f}, {-0.5f, -0.5f, -1.0f}};
static const SpheraVec3 IN_PLANE[4] = {{1.0f, 0.0f, 0.1f}, {2.0f, 0.0f, 0.1f}, {2.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 1.0f}};
static const SpheraVec3 NINE[9] = {{1.0f, 0.0f, 1.0f}, {0.77f, 0.64f, 1.0f}, {0.17f, 0.98f, 1.0f}, {-0.5f, 0.87f, 1.0f}, {-0.94f, 0.34f, 1.0f}, {-0.94f, -0.34f, 1.0f}, {-0.5f, -0.87f, 1.0f}, {0.17f, -0.98f, 1.0f}, {0.77f, -0.64f, 1.0f}};

static unsigned rng_state = 12345u;
static float uniform(void) {
  rng_state = rng_state * 1664525u + 1013904223u;
  return (float)(rng_state >> 8) * (1.0f / 16777216.0f);
}

static void check_polygon(const SpheraLtc *ltc, const SpheraVec3 *v, int n) {
  SpheraLtcPolygon polygon;
  double integral, sum = 0.0;
  int i, positive = 0;
  CHECK(sphera_ltc_polygon_prepare(&polygon, ltc, v, (uint32_t)n));
  integral = sphera_ltc_polygon_integral(&polygon);
  CHECK(integral > 0.0 && integral <= 1.0 + 1e-6);
  for (i = 0; i < 4000; i++) {
    SpheraSample s = sphera_ltc_polygon_sample(&polygon, uniform(), uniform());
    float p = sphera_ltc_polygon_pdf(&polygon, s.dir);
    CHECK(vec3_is_finite(s.dir) && s.pdf > 0.0f && isfinite(s.pdf));
    if (p > 0.0f) {
      ++positive;
      CHECK_REL(p, s.pdf, 1e-3);
    }
    /* D / pdf = ∫_P D exactly for every sample */
    sum += sphera_ltc_eval(ltc, s.dir) / s.pdf;
  }
  CHECK(positive >= 3990);
  CHECK_REL(sum / 4000.0, integral, 2e-3);
}

int main(void) {
  SpheraLtc ltc, smooth;
  SpheraVec3 wo = vec3(0.5f, 0.0f, 0.8660254f);
  SpheraLtcPolygon polygon;
  SpheraVec3 albedo;
  int i;

  /* ---- good input ---- */
  CHECK(sphera_ltc_prepare(&ltc, wo, 0.5f));
  albedo = sphera_ltc_specular_albedo(&ltc, vec3(0.04f, 0.5f, 1.0f));
  CHECK(albedo.x > 0.0f && albedo.x < albedo.y && albedo.y < albedo.z && albedo.z <= 1.0f);
  check_polygon(&ltc, QUAD, 4);
  check_polygon(&ltc, MIRROR_QUAD, 4);
  /* A smooth GGX concentrates its mass around the mirror direction. */
  CHECK(sphera_ltc_prepare(&smooth, wo, 0.1f));
  CHECK(sphera_ltc_polygon_prepare(&polygon, &smooth, MIRROR_QUAD, 4));
  {
    float mirror_mass = sphera_ltc_polygon_integral(&polygon);
    CHECK(sphera_ltc_polygon_prepare(&polygon, &smooth, AWAY_QUAD, 4));
    printf("smooth GGX: mass %.4f in the mirror quad, %.4f in the quad on the view's side\n", mirror_mass,
           sphera_ltc_polygon_integral(&polygon));
    CHECK(mirror_mass > 10.0f * sphera_ltc_polygon_integral(&polygon));
  }
  /* roughness is clamped; NaN counts as 0 */
  {
    SpheraLtc a, b;
    CHECK(sphera_ltc_prepare(&a, wo, NAN) && sphera_ltc_prepare(&b, wo, 0.0f));
    CHECK(memcmp(&a, &b, sizeof a) == 0);
    CHECK(sphera_ltc_prepare(&a, wo, 5.0f) && sphera_ltc_prepare(&b, wo, 1.0f));
    CHECK(memcmp(&a, &b, sizeof a) == 0);
  }

  /* ---- bad input ---- */
  CHECK(!sphera_ltc_prepare(NULL, wo, 0.5f));
  {
    const SpheraVec3 bad_views[5] = {{1.0f, 0.0f, 0.0f}, {0.3f, 0.0f, -1.0f}, {0.0f, 0.0f, 0.0f},
                                      {NAN, 0.0f, 1.0f}, {INFINITY, 0.0f, 1.0f}};
    for (i = 0; i < 5; i++) {
      SpheraLtc bad;
      CHECK(!sphera_ltc_prepare(&bad, bad_views[i], 0.5f));
      /* the plain cosine is written: D(z) = 1/π */
      CHECK_REL(sphera_ltc_eval(&bad, vec3(0.0f, 0.0f, 1.0f)), 1.0 / 3.14159265358979, 1e-6);
    }
  }
  CHECK(sphera_ltc_eval(NULL, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  CHECK(sphera_ltc_eval(&ltc, vec3(0.0f, 0.0f, 0.0f)) == 0.0f);
  CHECK(sphera_ltc_eval(&ltc, vec3(NAN, 0.0f, 1.0f)) == 0.0f);
  albedo = sphera_ltc_specular_albedo(NULL, vec3(1.0f, 1.0f, 1.0f));
  CHECK(albedo.x == 0.0f && albedo.y == 0.0f && albedo.z == 0.0f);

  CHECK(!sphera_ltc_polygon_prepare(NULL, &ltc, QUAD, 4));
  CHECK(!sphera_ltc_polygon_prepare(&polygon, NULL, QUAD, 4));
  CHECK(sphera_ltc_polygon_integral(&polygon) == 0.0f);
  CHECK(!sphera_ltc_polygon_prepare(&polygon, &ltc, NULL, 4));
  CHECK(!sphera_ltc_polygon_prepare(&polygon, &ltc, QUAD, 2));
  CHECK(!sphera_ltc_polygon_prepare(&polygon, &ltc, NINE, 9));
  CHECK(!sphera_ltc_polygon_prepare(&polygon, &ltc, BELOW, 3));
  CHECK(!sphera_ltc_polygon_prepare(&polygon, &ltc, IN_PLANE, 4));
  {
    SpheraVec3 nan_quad[4];
    memcpy(nan_quad, QUAD, sizeof QUAD);
    nan_quad[2].y = NAN;
    CHECK(!sphera_ltc_polygon_prepare(&polygon, &ltc, nan_quad, 4));
  }
  {
    SpheraSample s = sphera_ltc_polygon_sample(&polygon, 0.5f, 0.5f);
    CHECK(s.pdf == 0.0f && vec3_is_finite(s.dir));
    s = sphera_ltc_polygon_sample(NULL, 0.5f, 0.5f);
    CHECK(s.pdf == 0.0f && vec3_is_finite(s.dir));
    CHECK(sphera_ltc_polygon_pdf(NULL, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
    CHECK(sphera_ltc_polygon_integral(NULL) == 0.0f);
  }
  /* u outside [0, 1) and NaN are clamped */
  CHECK(sphera_ltc_polygon_prepare(&polygon, &ltc, QUAD, 4));
  {
    const float us[5] = {-1.0f, 1.0f, 2.0f, NAN, INFINITY};
    for (i = 0; i < 5; i++) {
      SpheraSample s = sphera_ltc_polygon_sample(&polygon, us[i], us[(i + 2) % 5]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf) && s.pdf > 0.0f);
    }
    CHECK(sphera_ltc_polygon_pdf(&polygon, vec3(0.0f, 0.0f, 0.0f)) == 0.0f);
    CHECK(sphera_ltc_polygon_pdf(&polygon, vec3(NAN, 0.0f, 1.0f)) == 0.0f);
    CHECK(sphera_ltc_polygon_pdf(&polygon, vec3(0.0f, 0.0f, -1.0f)) == 0.0f);
  }
  return check_summary();
}
