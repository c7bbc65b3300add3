/* C ABI tests of the solid angle sampler (sphera_solid_angle_polygon_*). */
#include <string.h>

#include "check.h"

static const double PI = 3.14159265358979323846;

/* Asserts that *polygon behaves as the empty polygon: no sample, pdf 0, no inverse. */
static void check_is_empty(const SpheraSolidAnglePolygon *polygon, const char *what) {
  float u[U_COUNT];
  int i, j, bad_samples = 0;
  float u0 = 0.5f, u1 = 0.5f;
  fill_u_values(u);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = sphera_solid_angle_polygon_sample(polygon, u[i], u[j]);
      if (s.pdf != 0.0f || !vec3_is_finite(s.dir)) bad_samples++;
    }
  }
  printf("  empty polygon after: %s\n", what);
  CHECK(bad_samples == 0);
  CHECK(sphera_solid_angle_polygon_pdf(polygon, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  CHECK(sphera_solid_angle_polygon_pdf(polygon, vec3(0.0f, 0.6f, 0.8f)) == 0.0f);
  CHECK(isfinite(sphera_solid_angle_polygon_solid_angle(polygon)));
  CHECK(sphera_solid_angle_polygon_solid_angle(polygon) == 0.0f);
  CHECK(!sphera_solid_angle_polygon_invert(polygon, vec3(0.0f, 0.0f, 1.0f), &u0, &u1));
  CHECK(u0 == 0.0f && u1 == 0.0f);
}

/* Good input: prepare succeeds, the solid angle is right, samples are uniform in the
 * polygon, pdf() agrees with them and invert() undoes them. */
static void check_polygon(const char *name, const SpheraVec3 *v, int n) {
  SpheraSolidAnglePolygon polygon;
  double exact = polygon_solid_angle(v, n);
  float u[U_COUNT];
  int i, j;
  int bad_pdf = 0, bad_dir = 0, bad_hit = 0, bad_pdf_of_dir = 0, bad_invert = 0;
  double worst_invert = 0.0;
  printf("polygon %s (%d vertices), exact solid angle %.9g\n", name, n, exact);
  fill_u_values(u);
  CHECK(sphera_solid_angle_polygon_prepare(&polygon, v, (uint32_t)n));
  CHECK_REL(sphera_solid_angle_polygon_solid_angle(&polygon), exact, 1e-4);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = sphera_solid_angle_polygon_sample(&polygon, u[i], u[j]);
      double length = dlength(dvec(s.dir));
      if (!(fabs(s.pdf - 1.0 / exact) <= 1e-4 / exact)) {
        if (bad_pdf++ == 0) printf("    u = (%.9g, %.9g): pdf %.9g, expected %.9g\n", u[i], u[j], s.pdf, 1.0 / exact);
      }
      if (!vec3_is_finite(s.dir) || !(fabs(length - 1.0) <= 1e-5)) {
        if (bad_dir++ == 0) printf("    u = (%.9g, %.9g): dir (%.9g, %.9g, %.9g)\n", u[i], u[j], s.dir.x, s.dir.y, s.dir.z);
      }
      if (!ray_hits_polygon(v, n, s.dir, 1e-4, NULL)) {
        if (bad_hit++ == 0) printf("    u = (%.9g, %.9g): dir (%.9g, %.9g, %.9g) misses the polygon\n", u[i], u[j], s.dir.x, s.dir.y, s.dir.z);
      }
      if (u_is_interior(i) && u_is_interior(j)) {
        float pdf = sphera_solid_angle_polygon_pdf(&polygon, s.dir);
        float v0 = -1.0f, v1 = -1.0f;
        int inverted = sphera_solid_angle_polygon_invert(&polygon, s.dir, &v0, &v1);
        double error = fmax(fabs(v0 - u[i]), fabs(v1 - u[j]));
        if (!(fabs(pdf - s.pdf) <= 1e-4 * s.pdf) || s.pdf == 0.0f) {
          if (bad_pdf_of_dir++ == 0) printf("    u = (%.9g, %.9g): pdf(dir) %.9g, sample pdf %.9g\n", u[i], u[j], pdf, s.pdf);
        }
        if (!inverted || !(error <= 1e-3)) {
          if (bad_invert++ == 0) printf("    u = (%.9g, %.9g): invert %d -> (%.9g, %.9g)\n", u[i], u[j], inverted, v0, v1);
        }
        if (inverted && error > worst_invert) worst_invert = error;
      }
    }
  }
  CHECK(bad_pdf == 0);         /* sample pdf == 1 / solid angle */
  CHECK(bad_dir == 0);         /* finite unit directions */
  CHECK(bad_hit == 0);         /* that point into the polygon */
  CHECK(bad_pdf_of_dir == 0);  /* pdf(sample.dir) == sample.pdf */
  CHECK(bad_invert == 0);      /* invert(sample.dir) == u */
  printf("    worst inversion error %.3g\n", worst_invert);

  /* Directions outside the polygon have pdf 0 and no inverse. */
  {
    float u0 = 0.5f, u1 = 0.5f;
    CHECK(sphera_solid_angle_polygon_pdf(&polygon, vec3(0.0f, 0.0f, -1.0f)) == 0.0f);
    CHECK(!sphera_solid_angle_polygon_invert(&polygon, vec3(0.0f, 0.0f, -1.0f), &u0, &u1));
    CHECK(u0 == 0.0f && u1 == 0.0f);
  }

  /* Random numbers outside [0, 1) are the caller's bug, but never give NaN. */
  {
    const float odd[] = {-1.0f, 1.0f, 2.0f, -0.0f, NAN, INFINITY, -INFINITY, 1e-45f};
    int k, l, bad = 0;
    for (k = 0; k < 8; k++) {
      for (l = 0; l < 8; l++) {
        SpheraSample s = sphera_solid_angle_polygon_sample(&polygon, odd[k], odd[l]);
        if (!vec3_is_finite(s.dir) || !isfinite(s.pdf) || s.pdf < 0.0f) {
          if (bad++ == 0) printf("    u = (%g, %g): dir (%g, %g, %g) pdf %g\n", odd[k], odd[l], s.dir.x, s.dir.y, s.dir.z, s.pdf);
        }
      }
    }
    CHECK(bad == 0);
  }

  /* Odd directions give a finite pdf and no crash. */
  {
    float u0 = 0.5f, u1 = 0.5f;
    float pdf_nan = sphera_solid_angle_polygon_pdf(&polygon, vec3(NAN, 0.0f, 1.0f));
    float pdf_zero = sphera_solid_angle_polygon_pdf(&polygon, vec3(0.0f, 0.0f, 0.0f));
    float pdf_inf = sphera_solid_angle_polygon_pdf(&polygon, vec3(INFINITY, 0.0f, 1.0f));
    CHECK(isfinite(pdf_nan) && pdf_nan >= 0.0f);
    CHECK(isfinite(pdf_zero) && pdf_zero >= 0.0f);
    CHECK(isfinite(pdf_inf) && pdf_inf >= 0.0f);
    CHECK(!sphera_solid_angle_polygon_invert(&polygon, vec3(NAN, NAN, NAN), &u0, &u1));
    CHECK(u0 == 0.0f && u1 == 0.0f);
  }
}

int main(void) {
  const SpheraVec3 quad[4] = {{-1.0f, -1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {-1.0f, 1.0f, 1.0f}};
  const SpheraVec3 quad_clockwise[4] = {{-1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}, {-1.0f, -1.0f, 1.0f}};
  const SpheraVec3 triangle[3] = {{0.2f, -0.3f, 1.0f}, {1.5f, 0.4f, 0.7f}, {-0.6f, 1.1f, 1.3f}};
  const SpheraVec3 small_triangle[3] = {{2.0f, 3.0f, 1.0f}, {2.01f, 3.0f, 1.0f}, {2.0f, 3.01f, 1.02f}};
  const SpheraVec3 nine[9] = {{1.0f, 0.0f, 1.0f}, {0.77f, 0.64f, 1.0f}, {0.17f, 0.98f, 1.0f}, {-0.5f, 0.87f, 1.0f}, {-0.94f, 0.34f, 1.0f}, {-0.94f, -0.34f, 1.0f}, {-0.5f, -0.87f, 1.0f}, {0.17f, -0.98f, 1.0f}, {0.77f, -0.64f, 1.0f}};
  const SpheraVec3 degenerate[3] = {{1.0f, 0.0f, 1.0f}, {2.0f, 0.0f, 2.0f}, {3.0f, 0.0f, 3.0f}};
  const SpheraVec3 point[3] = {{1.0f, 0.5f, 1.0f}, {1.0f, 0.5f, 1.0f}, {1.0f, 0.5f, 1.0f}};
  SpheraVec3 octagon[8];
  SpheraVec3 bad[4];
  SpheraSolidAnglePolygon polygon;
  int k;

  CHECK(SPHERA_MAX_POLYGON_VERTICES == 8);
  for (k = 0; k < 8; k++) {
    double angle = 2.0 * PI * k / 8.0;
    octagon[k] = vec3((float)(0.3 + cos(angle)), (float)(-0.2 + sin(angle)), 0.8f);
  }

  /* ---- good input (fails until the core sampler is implemented) ---- */
  check_polygon("unit quad at z = 1", quad, 4);
  CHECK_REL(polygon_solid_angle(quad, 4), 2.0 * PI / 3.0, 1e-12); /* the test's own reference */
  check_polygon("unit quad at z = 1, clockwise", quad_clockwise, 4);
  check_polygon("triangle", triangle, 3);
  check_polygon("small triangle", small_triangle, 3);
  check_polygon("octagon", octagon, 8);

  /* ---- bad input (holds for the stubs already) ---- */
  printf("bad input\n");
  CHECK(!sphera_solid_angle_polygon_prepare(NULL, quad, 4));
  CHECK(!sphera_solid_angle_polygon_prepare(NULL, NULL, 0));

  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, NULL, 4));
  check_is_empty(&polygon, "null vertices");
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, quad, 0));
  check_is_empty(&polygon, "count 0");
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, quad, 1));
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, quad, 2));
  check_is_empty(&polygon, "count 2");
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, nine, 9));
  check_is_empty(&polygon, "count 9");
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, nine, 0xffffffffu));
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, degenerate, 3));
  check_is_empty(&polygon, "zero solid angle (collinear with the origin)");
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, point, 3));
  check_is_empty(&polygon, "zero solid angle (one point)");
  for (k = 0; k < 3; k++) {
    const float values[3] = {NAN, INFINITY, -INFINITY};
    int coordinate;
    for (coordinate = 0; coordinate < 3; coordinate++) {
      memcpy(bad, quad, sizeof bad);
      if (coordinate == 0) bad[2].x = values[k];
      if (coordinate == 1) bad[1].y = values[k];
      if (coordinate == 2) bad[3].z = values[k];
      CHECK(!sphera_solid_angle_polygon_prepare(&polygon, bad, 4));
    }
    check_is_empty(&polygon, "NaN or infinite coordinate");
  }

  /* A failing prepare overwrites a valid polygon. */
  CHECK(sphera_solid_angle_polygon_prepare(&polygon, quad, 4)); /* good input */
  memcpy(bad, quad, sizeof bad);
  bad[0].x = NAN;
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, bad, 4));
  check_is_empty(&polygon, "NaN coordinate over a valid polygon");
  CHECK(sphera_solid_angle_polygon_prepare(&polygon, quad, 4)); /* good input */
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, quad, 9));
  check_is_empty(&polygon, "count 9 over a valid polygon");
  CHECK(sphera_solid_angle_polygon_prepare(&polygon, quad, 4)); /* good input */
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, NULL, 4));
  check_is_empty(&polygon, "null vertices over a valid polygon");
  memset(&polygon, 0x5a, sizeof polygon);
  CHECK(!sphera_solid_angle_polygon_prepare(&polygon, degenerate, 3));
  check_is_empty(&polygon, "zero solid angle over garbage");

  /* Null polygon. */
  {
    SpheraSample s = sphera_solid_angle_polygon_sample(NULL, 0.5f, 0.5f);
    float u0 = 0.5f, u1 = 0.5f;
    CHECK(s.pdf == 0.0f && s.dir.x == 0.0f && s.dir.y == 0.0f && s.dir.z == 1.0f);
    CHECK(sphera_solid_angle_polygon_pdf(NULL, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
    CHECK(sphera_solid_angle_polygon_solid_angle(NULL) == 0.0f);
    CHECK(!sphera_solid_angle_polygon_invert(NULL, vec3(0.0f, 0.0f, 1.0f), &u0, &u1));
    CHECK(u0 == 0.0f && u1 == 0.0f);
    CHECK(!sphera_solid_angle_polygon_invert(NULL, vec3(0.0f, 0.0f, 1.0f), NULL, NULL));
  }

  /* Null outputs of invert, on a valid polygon. */
  {
    float u0 = 0.5f, u1 = 0.5f;
    sphera_solid_angle_polygon_prepare(&polygon, quad, 4);
    CHECK(!sphera_solid_angle_polygon_invert(&polygon, vec3(0.0f, 0.0f, 1.0f), NULL, &u1));
    CHECK(u1 == 0.0f);
    CHECK(!sphera_solid_angle_polygon_invert(&polygon, vec3(0.0f, 0.0f, 1.0f), &u0, NULL));
    CHECK(u0 == 0.0f);
    CHECK(!sphera_solid_angle_polygon_invert(&polygon, vec3(0.0f, 0.0f, 1.0f), NULL, NULL));
  }

  return check_summary();
}
