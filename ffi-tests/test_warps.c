/* C ABI tests of the baselines built on solid angle sampling: the bilinear and
 * biquadratic warps of Hart et al. 2020 (sphera_hart_bilinear_polygon_*,
 * sphera_hart_biquadratic_polygon_*) and clipped solid angle sampling
 * (sphera_clipped_solid_angle_polygon_*). */
#include <string.h>

#include "check.h"

static const SpheraVec3 QUAD[4] = {{-1.0f, -1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {-1.0f, 1.0f, 1.0f}};
static const SpheraVec3 TRIANGLE[3] = {{0.2f, -0.3f, 1.0f}, {1.5f, 0.4f, 0.7f}, {-0.6f, 1.1f, 1.3f}};
/* A wall in front of the shading point, its lower part below the horizon. */
static const SpheraVec3 CROSSING[4] = {{2.0f, 1.0f, -0.5f}, {2.0f, 1.0f, 1.5f}, {-2.0f, 1.0f, 1.5f}, {-2.0f, 1.0f, -0.5f}};
/* Entirely below the horizon. */
static const SpheraVec3 BELOW[3] = {{0.5f, 0.0f, -1.0f}, {-0.5f, 0.5f, -1.0f}, {-0.5f, -0.5f, -1.0f}};
static const SpheraVec3 NINE[9] = {{1.0f, 0.0f, 1.0f}, {0.77f, 0.64f, 1.0f}, {0.17f, 0.98f, 1.0f}, {-0.5f, 0.87f, 1.0f}, {-0.94f, 0.34f, 1.0f}, {-0.94f, -0.34f, 1.0f}, {-0.5f, -0.87f, 1.0f}, {0.17f, -0.98f, 1.0f}, {0.77f, -0.64f, 1.0f}};
/* Eight vertices around a centre on the horizon: clipping is needed. */
static const SpheraVec3 EIGHT_CROSSING[8] = {{1.0f, 1.0f, 0.0f}, {0.7f, 1.0f, 0.7f}, {0.0f, 1.0f, 1.0f}, {-0.7f, 1.0f, 0.7f}, {-1.0f, 1.0f, 0.0f}, {-0.7f, 1.0f, -0.7f}, {0.0f, 1.0f, -1.0f}, {0.7f, 1.0f, -0.7f}};
static const SpheraVec3 DEGENERATE[3] = {{1.0f, 0.0f, 1.0f}, {2.0f, 0.0f, 2.0f}, {3.0f, 0.0f, 3.0f}};

/* ---- the three samplers behind one interface ------------------------------------- */

typedef union AnyPolygon {
  SpheraHartBilinearPolygon bilinear;
  SpheraHartBiquadraticPolygon biquadratic;
  SpheraClippedSolidAnglePolygon clipped;
} AnyPolygon;

typedef struct Technique {
  const char *name;
  size_t size;
  bool (*prepare)(AnyPolygon *out, const SpheraVec3 *v, uint32_t n);
  SpheraSample (*sample)(const AnyPolygon *p, float u0, float u1);
  float (*pdf)(const AnyPolygon *p, SpheraVec3 dir);
  /* Whether the technique clips (prepare fails below the horizon). */
  int clips;
} Technique;

static bool bilinear_prepare(AnyPolygon *out, const SpheraVec3 *v, uint32_t n) {
  return sphera_hart_bilinear_polygon_prepare(out ? &out->bilinear : NULL, v, n);
}
static SpheraSample bilinear_sample(const AnyPolygon *p, float u0, float u1) {
  return sphera_hart_bilinear_polygon_sample(p ? &p->bilinear : NULL, u0, u1);
}
static float bilinear_pdf(const AnyPolygon *p, SpheraVec3 dir) {
  return sphera_hart_bilinear_polygon_pdf(p ? &p->bilinear : NULL, dir);
}
static bool biquadratic_prepare(AnyPolygon *out, const SpheraVec3 *v, uint32_t n) {
  return sphera_hart_biquadratic_polygon_prepare(out ? &out->biquadratic : NULL, v, n);
}
static SpheraSample biquadratic_sample(const AnyPolygon *p, float u0, float u1) {
  return sphera_hart_biquadratic_polygon_sample(p ? &p->biquadratic : NULL, u0, u1);
}
static float biquadratic_pdf(const AnyPolygon *p, SpheraVec3 dir) {
  return sphera_hart_biquadratic_polygon_pdf(p ? &p->biquadratic : NULL, dir);
}
static bool clipped_prepare(AnyPolygon *out, const SpheraVec3 *v, uint32_t n) {
  return sphera_clipped_solid_angle_polygon_prepare(out ? &out->clipped : NULL, v, n);
}
static SpheraSample clipped_sample(const AnyPolygon *p, float u0, float u1) {
  return sphera_clipped_solid_angle_polygon_sample(p ? &p->clipped : NULL, u0, u1);
}
static float clipped_pdf(const AnyPolygon *p, SpheraVec3 dir) {
  return sphera_clipped_solid_angle_polygon_pdf(p ? &p->clipped : NULL, dir);
}

static const Technique TECHNIQUES[3] = {
    {"bilinear", sizeof(SpheraHartBilinearPolygon), bilinear_prepare, bilinear_sample, bilinear_pdf, 0},
    {"biquadratic", sizeof(SpheraHartBiquadraticPolygon), biquadratic_prepare, biquadratic_sample, biquadratic_pdf, 0},
    {"clipped solid angle", sizeof(SpheraClippedSolidAnglePolygon), clipped_prepare, clipped_sample, clipped_pdf, 1},
};

/* ---- references ------------------------------------------------------------------- */

/* The cosine integral of a convex polygon above the horizon (Lambert): half the sum
 * over edges of the edge's angle times the z component of its plane's unit normal,
 * oriented by the polygon's winding as seen from the origin. */
static double projected_solid_angle(const SpheraVec3 *v, int n) {
  DVec3 p0 = dvec(v[0]);
  double orientation = ddot(p0, dcross(dsub(dvec(v[1]), p0), dsub(dvec(v[2]), p0))) > 0.0 ? 1.0 : -1.0;
  double sum = 0.0;
  int i;
  for (i = 0; i < n; i++) {
    DVec3 a = dvec(v[i]), b = dvec(v[(i + 1) % n]);
    DVec3 c = dcross(a, dsub(b, a));
    double angle = atan2(dlength(dcross(a, b)), ddot(a, b));
    sum += angle * c.z / dlength(c);
  }
  return 0.5 * orientation * sum;
}

/* The part of the polygon above the horizon, through the library's clipping. */
static int clip(const SpheraVec3 *v, int n, SpheraVec3 out[SPHERA_MAX_POLYGON_VERTICES]) {
  memcpy(out, v, (size_t)n * sizeof *v);
  return (int)sphera_polygon_clip(out, (uint32_t)n);
}

/* ---- checks ----------------------------------------------------------------------- */

/* Asserts that *polygon behaves as the empty polygon: no sample, pdf 0. */
static void check_is_empty(const Technique *t, const AnyPolygon *polygon, const char *what) {
  float u[U_COUNT];
  int i, j, bad_samples = 0;
  fill_u_values(u);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = t->sample(polygon, u[i], u[j]);
      if (s.pdf != 0.0f || !vec3_is_finite(s.dir)) bad_samples++;
    }
  }
  printf("  empty %s polygon after: %s\n", t->name, what);
  CHECK(bad_samples == 0);
  CHECK(t->pdf(polygon, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  CHECK(t->pdf(polygon, vec3(0.0f, 0.6f, 0.8f)) == 0.0f);
  if (t->clips) CHECK(sphera_clipped_solid_angle_polygon_solid_angle(&polygon->clipped) == 0.0f);
}

/* Good input: samples are finite unit directions into the polygon and above the horizon
 * (or "no sample" below it), pdf() agrees with them, and the cosine estimator over a
 * 64 × 64 grid of random numbers is close to the cosine integral of the part above the
 * horizon. */
static void check_polygon(const Technique *t, const char *name, const SpheraVec3 *v, int n) {
  AnyPolygon polygon;
  SpheraVec3 above[SPHERA_MAX_POLYGON_VERTICES];
  int above_count = clip(v, n, above);
  int all_above = above_count == n && memcmp(above, v, (size_t)n * sizeof *v) == 0;
  double reference = projected_solid_angle(above, above_count);
  float u[U_COUNT];
  int i, j, bad_dir = 0, bad_hit = 0, bad_pdf = 0, bad_pdf_of_dir = 0, no_sample = 0;
  double estimate = 0.0;
  const int grid = 64;
  printf("%s: polygon %s (%d vertices, %d above the horizon), cosine integral %.9g\n", t->name, name, n,
         above_count, reference);
  fill_u_values(u);
  CHECK(t->prepare(&polygon, v, (uint32_t)n));
  if (t->clips) {
    CHECK_REL(sphera_clipped_solid_angle_polygon_solid_angle(&polygon.clipped),
              polygon_solid_angle(above, above_count), 1e-4);
  }
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = t->sample(&polygon, u[i], u[j]);
      double length = dlength(dvec(s.dir));
      if (!vec3_is_finite(s.dir) || !(fabs(length - 1.0) <= 1e-5) || !isfinite(s.pdf)) {
        if (bad_dir++ == 0) printf("    u = (%.9g, %.9g): dir (%.9g, %.9g, %.9g)\n", u[i], u[j], s.dir.x, s.dir.y, s.dir.z);
        continue;
      }
      if (s.pdf == 0.0f) {
        /* Only the warps, only below the horizon. */
        if (all_above || t->clips) {
          if (bad_pdf++ == 0) printf("    u = (%.9g, %.9g): no sample\n", u[i], u[j]);
        }
        continue;
      }
      if (!(s.dir.z >= 0.0f) || !ray_hits_polygon(above, above_count, s.dir, 1e-4, NULL)) {
        if (bad_hit++ == 0) printf("    u = (%.9g, %.9g): dir (%.9g, %.9g, %.9g) misses the polygon above the horizon\n", u[i], u[j], s.dir.x, s.dir.y, s.dir.z);
      }
      if (u_is_interior(i) && u_is_interior(j)) {
        float pdf = t->pdf(&polygon, s.dir);
        if (!(fabs(pdf - s.pdf) <= 1e-3 * s.pdf)) {
          if (bad_pdf_of_dir++ == 0) printf("    u = (%.9g, %.9g): pdf(dir) %.9g, sample pdf %.9g\n", u[i], u[j], pdf, s.pdf);
        }
      }
    }
  }
  CHECK(bad_dir == 0);        /* finite unit directions, finite pdfs */
  CHECK(bad_pdf == 0);        /* a sample wherever the polygon is above the horizon */
  CHECK(bad_hit == 0);        /* into the polygon, above the horizon */
  CHECK(bad_pdf_of_dir == 0); /* pdf(sample.dir) == sample.pdf */
  for (i = 0; i < grid; i++) {
    for (j = 0; j < grid; j++) {
      SpheraSample s = t->sample(&polygon, ((float)i + 0.5f) / (float)grid, ((float)j + 0.5f) / (float)grid);
      if (s.pdf > 0.0f) {
        estimate += s.dir.z / s.pdf;
      } else {
        no_sample++;
      }
    }
  }
  estimate /= (double)(grid * grid);
  printf("    cosine estimate %.9g, %d of %d without a sample\n", estimate, no_sample, grid * grid);
  CHECK_REL(estimate, reference, 1e-2);
  CHECK(all_above || t->clips ? no_sample == 0 : no_sample > 0);
  /* Below the horizon and outside the polygon: pdf 0. */
  CHECK(t->pdf(&polygon, vec3(0.0f, 0.0f, -1.0f)) == 0.0f);
  CHECK(t->pdf(&polygon, vec3(0.0f, 0.0f, 0.0f)) == 0.0f);
  CHECK(t->pdf(&polygon, vec3(NAN, 0.0f, 1.0f)) == 0.0f);
  CHECK(t->pdf(&polygon, vec3(INFINITY, 0.0f, 1.0f)) == 0.0f);
  {
    const float odd[] = {-1.0f, 0.0f, nextafterf(1.0f, 0.0f), 1.0f, 2.0f, NAN, INFINITY, -INFINITY};
    int k, l, bad = 0;
    for (k = 0; k < 8; k++) {
      for (l = 0; l < 8; l++) {
        SpheraSample s = t->sample(&polygon, odd[k], odd[l]);
        if (!vec3_is_finite(s.dir) || !isfinite(s.pdf) || s.pdf < 0.0f || (s.pdf > 0.0f && s.dir.z < 0.0f)) bad++;
      }
    }
    CHECK(bad == 0); /* extreme and out-of-range random numbers */
  }
}

static void check_bad_input(const Technique *t) {
  AnyPolygon polygon;
  SpheraVec3 bad[4];
  int k;
  printf("%s: bad input\n", t->name);
  CHECK(!t->prepare(NULL, QUAD, 4));
  CHECK(!t->prepare(&polygon, NULL, 4));
  check_is_empty(t, &polygon, "null vertices");
  for (k = 0; k <= 9; k += (k == 2 ? 7 : 1)) { /* counts 0, 1, 2, 9 */
    CHECK(t->prepare(&polygon, QUAD, 4));     /* good input */
    CHECK(!t->prepare(&polygon, NINE, (uint32_t)k));
  }
  check_is_empty(t, &polygon, "counts 0, 1, 2, 9 over a valid polygon");
  CHECK(!t->prepare(&polygon, DEGENERATE, 3));
  check_is_empty(t, &polygon, "a triangle of zero solid angle");
  for (k = 0; k < 36; k++) { /* every vertex, every axis, NaN, inf and -inf */
    const float values[3] = {NAN, INFINITY, -INFINITY};
    float value = values[k % 3];
    int vertex = k / 9, axis = (k / 3) % 3;
    memcpy(bad, CROSSING, sizeof bad);
    if (axis == 0) bad[vertex].x = value;
    if (axis == 1) bad[vertex].y = value;
    if (axis == 2) bad[vertex].z = value;
    CHECK(t->prepare(&polygon, TRIANGLE, 3)); /* good input */
    CHECK(!t->prepare(&polygon, bad, 4));
  }
  check_is_empty(t, &polygon, "NaN or infinite coordinates over a valid polygon");
  memset(&polygon, 0x5a, sizeof polygon);
  CHECK(!t->prepare(&polygon, QUAD, 9));
  check_is_empty(t, &polygon, "count 9 over garbage");
  {
    SpheraSample s = t->sample(NULL, 0.5f, 0.5f);
    CHECK(s.pdf == 0.0f && s.dir.x == 0.0f && s.dir.y == 0.0f && s.dir.z == 1.0f);
    CHECK(t->pdf(NULL, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  }
  /* Below the horizon: the clipped sampler has nothing to sample; the warps prepare
   * the polygon and return no samples. */
  if (t->clips) {
    CHECK(!t->prepare(&polygon, BELOW, 3));
    check_is_empty(t, &polygon, "a polygon below the horizon");
    CHECK(!t->prepare(&polygon, EIGHT_CROSSING, 8));
    check_is_empty(t, &polygon, "8 vertices that need clipping");
  } else {
    CHECK(t->prepare(&polygon, BELOW, 3));
    check_is_empty(t, &polygon, "a polygon below the horizon (prepared)");
    CHECK(t->prepare(&polygon, EIGHT_CROSSING, 8));
  }
}

int main(void) {
  int k;
  for (k = 0; k < 3; k++) {
    const Technique *t = &TECHNIQUES[k];
    SpheraVec3 reversed[4];
    int i;
    for (i = 0; i < 4; i++) reversed[i] = CROSSING[3 - i];
    check_polygon(t, "unit quad at z = 1", QUAD, 4);
    check_polygon(t, "triangle", TRIANGLE, 3);
    check_polygon(t, "wall crossing the horizon", CROSSING, 4);
    check_polygon(t, "wall crossing the horizon, reversed", reversed, 4);
    check_bad_input(t);
    CHECK(t->size >= sizeof(SpheraSolidAnglePolygon));
  }
  CHECK(sphera_clipped_solid_angle_polygon_solid_angle(NULL) == 0.0f);
  /* The test's own reference: each edge of the quad subtends acos(1/3), and its plane's
   * normal has z = 1/sqrt(2). */
  CHECK_REL(projected_solid_angle(QUAD, 4), sqrt(2.0) * acos(1.0 / 3.0), 1e-12);
  return check_summary();
}
