/* C ABI tests of the one-call polygonal light shading (sphera_polygon_light_*): every
 * heuristic's two-sample estimate agrees with an independent estimate of the same
 * integral by solid angle sampling and sphera_ggx_brdf_eval; bad input gives no sample. */
#include <string.h>

#include "check.h"

static const SpheraVec3 QUAD[4] = {{-1.6f, -0.4f, 1.0f}, {-0.8f, -0.4f, 1.2f}, {-0.8f, 0.4f, 1.2f}, {-1.6f, 0.4f, 1.0f}};
static const SpheraVec3 BELOW[3] = {{0.5f, 0.0f, -1.0f}, {-0.5f, 0.5f, -1.0f}, {-0.5f, -0.5f, -1.0f}};

static unsigned rng_state = 4321u;
static float uniform(void) {
  rng_state = rng_state * 1664525u + 1013904223u;
  return (float)(rng_state >> 8) * (1.0f / 16777216.0f);
}

int main(void) {
  SpheraMaterial material;
  SpheraPolygonLight light;
  SpheraVec3 wo = vec3(0.6f, 0.0f, 0.8f);
  SpheraGgxBrdf ggx;
  SpheraSolidAnglePolygon solid_angle;
  double reference = 0.0, reference_square = 0.0;
  const int n = 400000;
  uint32_t heuristic;
  int i;

  material.diffuse = vec3(0.3f, 0.3f, 0.3f);
  material.f0 = vec3(0.5f, 0.5f, 0.5f);
  material.roughness = 0.3f;

  /* The independent estimate: solid angle sampling of (ρ/π + GGX) cos. */
  CHECK(sphera_ggx_brdf_prepare(&ggx, material.roughness, material.f0));
  CHECK(sphera_solid_angle_polygon_prepare(&solid_angle, QUAD, 4));
  for (i = 0; i < n; i++) {
    SpheraSample s = sphera_solid_angle_polygon_sample(&solid_angle, uniform(), uniform());
    double x = 0.0;
    if (s.pdf > 0.0f && s.dir.z > 0.0f) {
      SpheraVec3 f = sphera_ggx_brdf_eval(&ggx, wo, s.dir);
      x = (0.3 / 3.14159265358979 + f.x) * s.dir.z / s.pdf;
    }
    reference += x;
    reference_square += x * x;
  }
  reference /= n;
  {
    double reference_error = sqrt((reference_square / n - reference * reference) / n);
    for (heuristic = SPHERA_MIS_BALANCE; heuristic <= SPHERA_MIS_OPTIMAL; heuristic++) {
      double sum = 0.0, sum_square = 0.0, error;
      CHECK(sphera_polygon_light_prepare(&light, QUAD, 4, wo, &material, heuristic, 0.5f));
      for (i = 0; i < n; i++) {
        double x = 0.0;
        uint32_t technique;
        for (technique = 0; technique < 2; technique++) {
          SpheraLightSample s = sphera_polygon_light_sample(&light, technique, uniform(), uniform());
          CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf) && vec3_is_finite(s.visible) &&
                vec3_is_finite(s.unoccluded));
          x += s.visible.x + s.unoccluded.x; /* unoccluded: V = 1 */
        }
        sum += x;
        sum_square += x * x;
      }
      sum /= n;
      error = sqrt((sum_square / n - sum * sum) / n);
      printf("heuristic %u: %.6f ± %.1e, solid angle sampling %.6f ± %.1e, closed form %.6f\n",
             heuristic, sum, error, reference, reference_error,
             sphera_polygon_light_unshadowed(&light).x);
      CHECK(fabs(sum - reference) <= 5.0 * sqrt(error * error + reference_error * reference_error) +
                                         1e-5 * reference);
      /* the closed form: exact diffuse plus the LTC's specular, within its fit error */
      CHECK_REL(sphera_polygon_light_unshadowed(&light).x, reference, 0.05);
    }
  }

  /* ---- bad input ---- */
  CHECK(!sphera_polygon_light_prepare(NULL, QUAD, 4, wo, &material, 0, 0.5f));
  CHECK(!sphera_polygon_light_prepare(&light, NULL, 4, wo, &material, 0, 0.5f));
  CHECK(!sphera_polygon_light_prepare(&light, QUAD, 4, wo, NULL, 0, 0.5f));
  CHECK(!sphera_polygon_light_prepare(&light, QUAD, 2, wo, &material, 0, 0.5f));
  CHECK(!sphera_polygon_light_prepare(&light, QUAD, 9, wo, &material, 0, 0.5f));
  CHECK(!sphera_polygon_light_prepare(&light, BELOW, 3, wo, &material, 0, 0.5f));
  CHECK(!sphera_polygon_light_prepare(&light, QUAD, 4, vec3(1.0f, 0.0f, -0.1f), &material, 0, 0.5f));
  CHECK(!sphera_polygon_light_prepare(&light, QUAD, 4, vec3(NAN, 0.0f, 1.0f), &material, 0, 0.5f));
  {
    SpheraLightSample s = sphera_polygon_light_sample(&light, 0, 0.5f, 0.5f);
    SpheraVec3 u = sphera_polygon_light_unshadowed(&light);
    CHECK(s.pdf == 0.0f && s.visible.x == 0.0f && s.unoccluded.x == 0.0f && vec3_is_finite(s.dir));
    CHECK(u.x == 0.0f && u.y == 0.0f && u.z == 0.0f);
    s = sphera_polygon_light_sample(NULL, 0, 0.5f, 0.5f);
    CHECK(s.pdf == 0.0f && vec3_is_finite(s.dir));
    u = sphera_polygon_light_unshadowed(NULL);
    CHECK(u.x == 0.0f);
  }
  {
    SpheraMaterial odd = material;
    SpheraVec3 nan_quad[4];
    odd.roughness = NAN;
    odd.diffuse = vec3(NAN, -1.0f, 5.0f);
    odd.f0 = vec3(INFINITY, NAN, 0.5f);
    /* bad material values are clamped and a NaN v defaults to 1/2 */
    CHECK(sphera_polygon_light_prepare(&light, QUAD, 4, wo, &odd, SPHERA_MIS_CLAMPED_OPTIMAL, NAN));
    for (i = 0; i < 100; i++) {
      SpheraLightSample s = sphera_polygon_light_sample(&light, (uint32_t)(i % 3), uniform(), NAN);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf) && vec3_is_finite(s.visible) &&
            vec3_is_finite(s.unoccluded));
      if (i % 3 == 2) CHECK(s.pdf == 0.0f);
    }
    /* An unknown heuristic is an error, not a silent default: prepare fails, and the
     * light it writes (over whatever was there) gives no samples. */
    {
      const uint32_t unknown[3] = {SPHERA_MIS_OPTIMAL + 1u, 99u, UINT32_MAX};
      int k;
      for (k = 0; k < 3; k++) {
        SpheraVec3 u;
        memset(&light, 0xff, sizeof light);
        CHECK(!sphera_polygon_light_prepare(&light, QUAD, 4, wo, &material, unknown[k], 0.5f));
        u = sphera_polygon_light_unshadowed(&light);
        CHECK(u.x == 0.0f && u.y == 0.0f && u.z == 0.0f);
        for (i = 0; i < 100; i++) {
          SpheraLightSample s = sphera_polygon_light_sample(&light, (uint32_t)(i % 2), uniform(), uniform());
          CHECK(s.pdf == 0.0f && s.visible.x == 0.0f && s.unoccluded.x == 0.0f &&
                vec3_is_finite(s.dir));
        }
      }
      /* The same call with a known heuristic succeeds (the failure above is the
       * heuristic's). */
      CHECK(sphera_polygon_light_prepare(&light, QUAD, 4, wo, &material, SPHERA_MIS_OPTIMAL, 0.5f));
    }
    memcpy(nan_quad, QUAD, sizeof QUAD);
    nan_quad[1].z = NAN;
    CHECK(!sphera_polygon_light_prepare(&light, nan_quad, 4, wo, &material, 0, 0.5f));
  }
  return check_summary();
}
