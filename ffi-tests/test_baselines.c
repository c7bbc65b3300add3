/* C ABI tests of the baselines: Turk's area sampling (sphera_turk_polygon_*) and Arvo's
 * spherical triangle sampling (sphera_arvo_polygon_*). */
#include <string.h>

#include "check.h"

static const double PI = 3.14159265358979323846;

static const SpheraVec3 QUAD[4] = {{-1.0f, -1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {-1.0f, 1.0f, 1.0f}};
static const SpheraVec3 TRIANGLE[3] = {{0.2f, -0.3f, 1.0f}, {1.5f, 0.4f, 0.7f}, {-0.6f, 1.1f, 1.3f}};
static const SpheraVec3 NINE[9] = {{1.0f, 0.0f, 1.0f}, {0.77f, 0.64f, 1.0f}, {0.17f, 0.98f, 1.0f}, {-0.5f, 0.87f, 1.0f}, {-0.94f, 0.34f, 1.0f}, {-0.94f, -0.34f, 1.0f}, {-0.5f, -0.87f, 1.0f}, {0.17f, -0.98f, 1.0f}, {0.77f, -0.64f, 1.0f}};
static const SpheraVec3 DEGENERATE[3] = {{1.0f, 0.0f, 1.0f}, {2.0f, 0.0f, 2.0f}, {3.0f, 0.0f, 3.0f}};

/* ---- Turk ------------------------------------------------------------------------ */

static void check_turk_is_empty(const SpheraTurkPolygon *polygon, const char *what) {
  float u[U_COUNT];
  int i, j, bad_samples = 0;
  fill_u_values(u);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = sphera_turk_polygon_sample(polygon, u[i], u[j]);
      if (s.pdf != 0.0f || !vec3_is_finite(s.dir)) bad_samples++;
    }
  }
  printf("  empty Turk polygon after: %s\n", what);
  CHECK(bad_samples == 0);
  CHECK(sphera_turk_polygon_pdf(polygon, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  CHECK(sphera_turk_polygon_area(polygon) == 0.0f);
}

static void check_turk_polygon(const char *name, const SpheraVec3 *v, int n) {
  SpheraTurkPolygon polygon;
  double area = polygon_area(v, n);
  DVec3 normal = polygon_normal(v, n);
  float u[U_COUNT];
  int i, j, bad_pdf = 0, bad_dir = 0, bad_hit = 0, bad_pdf_of_dir = 0;
  printf("Turk: polygon %s (%d vertices), area %.9g\n", name, n, area);
  fill_u_values(u);
  normal = dscale(normal, 1.0 / dlength(normal));
  CHECK(sphera_turk_polygon_prepare(&polygon, v, (uint32_t)n));
  CHECK_REL(sphera_turk_polygon_area(&polygon), area, 1e-5);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = sphera_turk_polygon_sample(&polygon, u[i], u[j]);
      double distance = 0.0, expected;
      DVec3 dir = dvec(s.dir);
      double length = dlength(dir);
      if (!vec3_is_finite(s.dir) || !(fabs(length - 1.0) <= 1e-5)) {
        if (bad_dir++ == 0) printf("    u = (%.9g, %.9g): dir (%.9g, %.9g, %.9g)\n", u[i], u[j], s.dir.x, s.dir.y, s.dir.z);
        continue;
      }
      if (!ray_hits_polygon(v, n, s.dir, 1e-4, &distance)) {
        if (bad_hit++ == 0) printf("    u = (%.9g, %.9g): dir (%.9g, %.9g, %.9g) misses the polygon\n", u[i], u[j], s.dir.x, s.dir.y, s.dir.z);
        continue;
      }
      /* Area density converted to solid angle: distance² / (area · |cos θ|). */
      expected = distance * distance / (area * fabs(ddot(normal, dscale(dir, 1.0 / length))));
      if (!(fabs(s.pdf - expected) <= 1e-3 * expected)) {
        if (bad_pdf++ == 0) printf("    u = (%.9g, %.9g): pdf %.9g, expected %.9g\n", u[i], u[j], s.pdf, expected);
      }
      if (u_is_interior(i) && u_is_interior(j)) {
        float pdf = sphera_turk_polygon_pdf(&polygon, s.dir);
        if (!(fabs(pdf - s.pdf) <= 1e-3 * s.pdf) || s.pdf == 0.0f) {
          if (bad_pdf_of_dir++ == 0) printf("    u = (%.9g, %.9g): pdf(dir) %.9g, sample pdf %.9g\n", u[i], u[j], pdf, s.pdf);
        }
      }
    }
  }
  CHECK(bad_dir == 0);
  CHECK(bad_hit == 0);
  CHECK(bad_pdf == 0);
  CHECK(bad_pdf_of_dir == 0);
  CHECK(sphera_turk_polygon_pdf(&polygon, vec3(0.0f, 0.0f, -1.0f)) == 0.0f);
  {
    const float odd[] = {-1.0f, 1.0f, 2.0f, NAN, INFINITY, -INFINITY};
    int k, l, bad = 0;
    for (k = 0; k < 6; k++) {
      for (l = 0; l < 6; l++) {
        SpheraSample s = sphera_turk_polygon_sample(&polygon, odd[k], odd[l]);
        if (!vec3_is_finite(s.dir) || !isfinite(s.pdf) || s.pdf < 0.0f) bad++;
      }
    }
    CHECK(bad == 0);
    CHECK(isfinite(sphera_turk_polygon_pdf(&polygon, vec3(NAN, 0.0f, 1.0f))));
    CHECK(isfinite(sphera_turk_polygon_pdf(&polygon, vec3(0.0f, 0.0f, 0.0f))));
  }
}

/* ---- Arvo ------------------------------------------------------------------------ */

static void check_arvo_is_empty(const SpheraArvoPolygon *polygon, const char *what) {
  float u[U_COUNT];
  int i, j, bad_samples = 0;
  fill_u_values(u);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = sphera_arvo_polygon_sample(polygon, u[i], u[j]);
      if (s.pdf != 0.0f || !vec3_is_finite(s.dir)) bad_samples++;
    }
  }
  printf("  empty Arvo polygon after: %s\n", what);
  CHECK(bad_samples == 0);
  CHECK(sphera_arvo_polygon_pdf(polygon, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  CHECK(isfinite(sphera_arvo_polygon_solid_angle(polygon)));
  CHECK(sphera_arvo_polygon_solid_angle(polygon) == 0.0f);
}

static void check_arvo_polygon(const char *name, const SpheraVec3 *v, int n) {
  SpheraArvoPolygon polygon;
  double exact = polygon_solid_angle(v, n);
  float u[U_COUNT];
  int i, j, bad_pdf = 0, bad_dir = 0, bad_hit = 0, bad_pdf_of_dir = 0;
  printf("Arvo: polygon %s (%d vertices), exact solid angle %.9g\n", name, n, exact);
  fill_u_values(u);
  CHECK(sphera_arvo_polygon_prepare(&polygon, v, (uint32_t)n));
  CHECK_REL(sphera_arvo_polygon_solid_angle(&polygon), exact, 1e-3);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = sphera_arvo_polygon_sample(&polygon, u[i], u[j]);
      double length = dlength(dvec(s.dir));
      if (!(fabs(s.pdf - 1.0 / exact) <= 1e-3 / exact)) {
        if (bad_pdf++ == 0) printf("    u = (%.9g, %.9g): pdf %.9g, expected %.9g\n", u[i], u[j], s.pdf, 1.0 / exact);
      }
      if (!vec3_is_finite(s.dir) || !(fabs(length - 1.0) <= 1e-5)) {
        if (bad_dir++ == 0) printf("    u = (%.9g, %.9g): dir (%.9g, %.9g, %.9g)\n", u[i], u[j], s.dir.x, s.dir.y, s.dir.z);
      }
      if (!ray_hits_polygon(v, n, s.dir, 1e-4, NULL)) {
        if (bad_hit++ == 0) printf("    u = (%.9g, %.9g): dir (%.9g, %.9g, %.9g) misses the polygon\n", u[i], u[j], s.dir.x, s.dir.y, s.dir.z);
      }
      if (u_is_interior(i) && u_is_interior(j)) {
        float pdf = sphera_arvo_polygon_pdf(&polygon, s.dir);
        if (!(fabs(pdf - s.pdf) <= 1e-4 * s.pdf) || s.pdf == 0.0f) {
          if (bad_pdf_of_dir++ == 0) printf("    u = (%.9g, %.9g): pdf(dir) %.9g, sample pdf %.9g\n", u[i], u[j], pdf, s.pdf);
        }
      }
    }
  }
  CHECK(bad_pdf == 0);
  CHECK(bad_dir == 0);
  CHECK(bad_hit == 0);
  CHECK(bad_pdf_of_dir == 0);
  CHECK(sphera_arvo_polygon_pdf(&polygon, vec3(0.0f, 0.0f, -1.0f)) == 0.0f);
  {
    const float odd[] = {-1.0f, 1.0f, 2.0f, NAN, INFINITY, -INFINITY};
    int k, l, bad = 0;
    for (k = 0; k < 6; k++) {
      for (l = 0; l < 6; l++) {
        SpheraSample s = sphera_arvo_polygon_sample(&polygon, odd[k], odd[l]);
        if (!vec3_is_finite(s.dir) || !isfinite(s.pdf) || s.pdf < 0.0f) bad++;
      }
    }
    CHECK(bad == 0);
    CHECK(isfinite(sphera_arvo_polygon_pdf(&polygon, vec3(NAN, 0.0f, 1.0f))));
    CHECK(isfinite(sphera_arvo_polygon_pdf(&polygon, vec3(0.0f, 0.0f, 0.0f))));
  }
}

int main(void) {
  SpheraTurkPolygon turk;
  SpheraArvoPolygon arvo;
  SpheraVec3 bad[4];
  int k;

  /* ---- good input (fails until the core samplers are implemented) ---- */
  check_turk_polygon("unit quad at z = 1", QUAD, 4);
  CHECK_REL(polygon_area(QUAD, 4), 4.0, 1e-12); /* the test's own reference */
  check_turk_polygon("triangle", TRIANGLE, 3);
  check_arvo_polygon("triangle", TRIANGLE, 3);
  check_arvo_polygon("unit quad at z = 1", QUAD, 4);
  CHECK_REL(polygon_solid_angle(QUAD, 4), 2.0 * PI / 3.0, 1e-12);

  /* ---- bad input (holds for the stubs already) ---- */
  printf("bad input\n");
  CHECK(!sphera_turk_polygon_prepare(NULL, QUAD, 4));
  CHECK(!sphera_arvo_polygon_prepare(NULL, QUAD, 4));
  CHECK(!sphera_turk_polygon_prepare(&turk, NULL, 4));
  check_turk_is_empty(&turk, "null vertices");
  CHECK(!sphera_arvo_polygon_prepare(&arvo, NULL, 4));
  check_arvo_is_empty(&arvo, "null vertices");
  for (k = 0; k <= 9; k += (k == 2 ? 7 : 1)) { /* counts 0, 1, 2, 9 */
    CHECK(!sphera_turk_polygon_prepare(&turk, NINE, (uint32_t)k));
    CHECK(!sphera_arvo_polygon_prepare(&arvo, NINE, (uint32_t)k));
  }
  check_turk_is_empty(&turk, "count 9");
  check_arvo_is_empty(&arvo, "count 9");
  CHECK(!sphera_turk_polygon_prepare(&turk, DEGENERATE, 3));
  check_turk_is_empty(&turk, "a degenerate triangle");
  CHECK(!sphera_arvo_polygon_prepare(&arvo, DEGENERATE, 3));
  check_arvo_is_empty(&arvo, "a triangle of zero solid angle");
  for (k = 0; k < 3; k++) {
    const float values[3] = {NAN, INFINITY, -INFINITY};
    memcpy(bad, QUAD, sizeof bad);
    bad[k + 1].y = values[k];
    CHECK(!sphera_turk_polygon_prepare(&turk, bad, 4));
    CHECK(!sphera_arvo_polygon_prepare(&arvo, bad, 4));
  }
  check_turk_is_empty(&turk, "NaN or infinite coordinate");
  check_arvo_is_empty(&arvo, "NaN or infinite coordinate");

  /* A failing prepare overwrites a valid polygon. */
  memcpy(bad, QUAD, sizeof bad);
  bad[0].z = NAN;
  CHECK(sphera_turk_polygon_prepare(&turk, QUAD, 4)); /* good input */
  CHECK(!sphera_turk_polygon_prepare(&turk, bad, 4));
  check_turk_is_empty(&turk, "NaN coordinate over a valid polygon");
  CHECK(sphera_turk_polygon_prepare(&turk, QUAD, 4)); /* good input */
  CHECK(!sphera_turk_polygon_prepare(&turk, NULL, 4));
  check_turk_is_empty(&turk, "null vertices over a valid polygon");
  CHECK(sphera_arvo_polygon_prepare(&arvo, TRIANGLE, 3)); /* good input */
  CHECK(!sphera_arvo_polygon_prepare(&arvo, bad, 4));
  check_arvo_is_empty(&arvo, "NaN coordinate over a valid polygon");
  CHECK(sphera_arvo_polygon_prepare(&arvo, TRIANGLE, 3)); /* good input */
  CHECK(!sphera_arvo_polygon_prepare(&arvo, TRIANGLE, 2));
  check_arvo_is_empty(&arvo, "count 2 over a valid polygon");
  memset(&turk, 0x5a, sizeof turk);
  memset(&arvo, 0x5a, sizeof arvo);
  CHECK(!sphera_turk_polygon_prepare(&turk, QUAD, 9));
  CHECK(!sphera_arvo_polygon_prepare(&arvo, QUAD, 9));
  check_turk_is_empty(&turk, "count 9 over garbage");
  check_arvo_is_empty(&arvo, "count 9 over garbage");

  /* Null polygons. */
  {
    SpheraSample s = sphera_turk_polygon_sample(NULL, 0.5f, 0.5f);
    CHECK(s.pdf == 0.0f && s.dir.x == 0.0f && s.dir.y == 0.0f && s.dir.z == 1.0f);
    s = sphera_arvo_polygon_sample(NULL, 0.5f, 0.5f);
    CHECK(s.pdf == 0.0f && s.dir.x == 0.0f && s.dir.y == 0.0f && s.dir.z == 1.0f);
    CHECK(sphera_turk_polygon_pdf(NULL, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
    CHECK(sphera_arvo_polygon_pdf(NULL, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
    CHECK(sphera_turk_polygon_area(NULL) == 0.0f);
    CHECK(sphera_arvo_polygon_solid_angle(NULL) == 0.0f);
  }

  return check_summary();
}
