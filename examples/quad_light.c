/* The irradiance at a point under a quad light, by multiple importance sampling: each
 * round draws one light sample (projected solid angle sampling of the quad) and one
 * BRDF sample (cosine sampling of a Lambertian surface) and weights both with the
 * balance heuristic. Nothing occludes the light here; a renderer traces a shadow ray
 * for the light sample and a ray for the BRDF sample instead of asking the pdf.
 *
 * Build: cc -std=c99 quad_light.c -I<prefix>/include <prefix>/lib/libsphera.a -lm
 * (or with pkg-config / CMake: see README.md). */
#include <math.h>
#include <stdio.h>

#include "sphera.h"

/* Random numbers in [0, 1): a small LCG; use your renderer's sampler instead. */
static float next_uniform(uint32_t *state) {
  *state = *state * 1664525u + 1013904223u;
  return (float)(*state >> 8) * (1.0f / 16777216.0f);
}

int main(void) {
  const SpheraVec3 point = {0.1f, 0.2f, 0.0f}, normal = {0.0f, 0.6f, 0.8f};
  const SpheraVec3 quad[4] = {{-1.0f, -0.5f, 2.0f}, {1.0f, -0.5f, 2.0f},
                              {1.0f, 0.5f, 2.5f}, {-1.0f, 0.5f, 2.5f}}; /* world space */
  const float radiance = 3.0f;
  const int rounds = 200000;
  SpheraFrame frame;
  SpheraVec3 local[4];
  SpheraProjectedPolygon light;
  double sum = 0.0, sum_squares = 0.0;
  uint32_t rng = 1u;
  int i;

  if (!sphera_check_version(SPHERA_VERSION_MAJOR, SPHERA_VERSION_MINOR)) return 1;
  /* The light relative to the shading point, in the local frame (z = normal). */
  sphera_frame_from_normal(&frame, normal);
  for (i = 0; i < 4; i++) {
    SpheraVec3 d = {quad[i].x - point.x, quad[i].y - point.y, quad[i].z - point.z};
    local[i] = sphera_frame_to_local(&frame, d);
  }
  if (!sphera_projected_polygon_prepare(&light, local, 4)) return 1; /* nothing visible */
  for (i = 0; i < rounds; i++) {
    double x = 0.0;
    /* Light sample: density cos θ / Φ inside the quad. */
    SpheraSample s = sphera_projected_polygon_sample(&light, next_uniform(&rng), next_uniform(&rng));
    if (s.pdf > 0.0f)
      x += radiance * s.dir.z / s.pdf * sphera_mis_balance(s.pdf, sphera_lambert_pdf(s.dir));
    /* BRDF sample: density cos θ / π; it sees the light where the light's pdf is > 0. */
    SpheraSample b = sphera_lambert_sample(next_uniform(&rng), next_uniform(&rng));
    float light_pdf = sphera_projected_polygon_pdf(&light, b.dir);
    if (light_pdf > 0.0f)
      x += radiance * b.dir.z / b.pdf * sphera_mis_balance(b.pdf, light_pdf);
    sum += x;
    sum_squares += x * x;
  }
  sum /= rounds;
  printf("irradiance %.6f standard error %.6f\n", sum,
         sqrt((sum_squares / rounds - sum * sum) / rounds));
  /* For a light of constant radiance the exact value is radiance × Φ. */
  printf("exact %.6f\n", radiance * sphera_projected_polygon_projected_solid_angle(&light));
  return 0;
}
