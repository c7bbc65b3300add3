/*
 * A tiny test harness shared by the C ABI tests (the .c files of ffi-tests).
 *
 * CHECK(expr) counts a pass or prints "file:line: CHECK failed: expr" and counts a
 * failure; CHECK_REL / CHECK_ABS also print the values compared. A test's main ends
 * with `return check_summary();`, which prints "N passed, M failed" and returns
 * nonzero when any check failed. Geometry helpers compute in double.
 */
#ifndef SPHERA_FFI_TESTS_CHECK_H
#define SPHERA_FFI_TESTS_CHECK_H

#include <math.h>
#include <stdio.h>

#include "sphera.h"

static int check_passed = 0;
static int check_failed = 0;

static inline int check_record(int ok, const char *file, int line, const char *expr) {
  if (ok) {
    check_passed++;
  } else {
    check_failed++;
    printf("%s:%d: CHECK failed: %s\n", file, line, expr);
    fflush(stdout);
  }
  return ok;
}

/* |actual - expected| <= tolerance (absolute) or <= tolerance * |expected| (relative);
 * NaN never passes. */
static inline int check_close(double actual, double expected, double tolerance, int relative,
                              const char *file, int line, const char *expr) {
  double bound = relative ? tolerance * fabs(expected) : tolerance;
  int ok = fabs(actual - expected) <= bound;
  if (!check_record(ok, file, line, expr)) {
    printf("    got %.9g, expected %.9g (%s tolerance %g)\n", actual, expected,
           relative ? "relative" : "absolute", tolerance);
  }
  return ok;
}

#define CHECK(expr) check_record((expr) ? 1 : 0, __FILE__, __LINE__, #expr)
#define CHECK_REL(actual, expected, tolerance)                                   \
  check_close((actual), (expected), (tolerance), 1, __FILE__, __LINE__,          \
              #actual " ~= " #expected)
#define CHECK_ABS(actual, expected, tolerance)                                   \
  check_close((actual), (expected), (tolerance), 0, __FILE__, __LINE__,          \
              #actual " ~= " #expected)

static inline int check_summary(void) {
  printf("%d passed, %d failed\n", check_passed, check_failed);
  return check_failed == 0 ? 0 : 1;
}

/* ---- small helpers ---------------------------------------------------------------- */

typedef struct DVec3 {
  double x, y, z;
} DVec3;

static inline SpheraVec3 vec3(float x, float y, float z) {
  SpheraVec3 v;
  v.x = x;
  v.y = y;
  v.z = z;
  return v;
}

static inline DVec3 dvec(SpheraVec3 v) {
  DVec3 d;
  d.x = v.x;
  d.y = v.y;
  d.z = v.z;
  return d;
}

static inline DVec3 dsub(DVec3 a, DVec3 b) {
  DVec3 d;
  d.x = a.x - b.x;
  d.y = a.y - b.y;
  d.z = a.z - b.z;
  return d;
}

static inline DVec3 dscale(DVec3 a, double s) {
  DVec3 d;
  d.x = a.x * s;
  d.y = a.y * s;
  d.z = a.z * s;
  return d;
}

static inline double ddot(DVec3 a, DVec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

static inline DVec3 dcross(DVec3 a, DVec3 b) {
  DVec3 d;
  d.x = a.y * b.z - a.z * b.y;
  d.y = a.z * b.x - a.x * b.z;
  d.z = a.x * b.y - a.y * b.x;
  return d;
}

static inline double dlength(DVec3 a) { return sqrt(ddot(a, a)); }

static inline int vec3_is_finite(SpheraVec3 v) {
  return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static inline int vec3_equal(SpheraVec3 a, SpheraVec3 b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

/* Solid angle of the triangle (a, b, c) seen from the origin (van Oosterom and
 * Strackee 1983): tan(Ω/2) = |a·(b×c)| / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|). */
static inline double triangle_solid_angle(SpheraVec3 a32, SpheraVec3 b32, SpheraVec3 c32) {
  DVec3 a = dvec(a32), b = dvec(b32), c = dvec(c32);
  double la = dlength(a), lb = dlength(b), lc = dlength(c);
  double numerator = fabs(ddot(a, dcross(b, c)));
  double denominator =
      la * lb * lc + ddot(a, b) * lc + ddot(a, c) * lb + ddot(b, c) * la;
  return 2.0 * atan2(numerator, denominator);
}

/* Solid angle of a convex polygon not containing the origin: its fan of triangles. */
static inline double polygon_solid_angle(const SpheraVec3 *v, int n) {
  double sum = 0.0;
  int i;
  for (i = 1; i + 1 < n; i++) sum += triangle_solid_angle(v[0], v[i], v[i + 1]);
  return sum;
}

/* Newell's normal: twice the area times the unit normal around which the vertices
 * turn counterclockwise. */
static inline DVec3 polygon_normal(const SpheraVec3 *v, int n) {
  DVec3 sum = {0.0, 0.0, 0.0};
  int i;
  for (i = 0; i < n; i++) {
    DVec3 c = dcross(dvec(v[i]), dvec(v[(i + 1) % n]));
    sum.x += c.x;
    sum.y += c.y;
    sum.z += c.z;
  }
  return sum;
}

static inline double polygon_area(const SpheraVec3 *v, int n) {
  return 0.5 * dlength(polygon_normal(v, n));
}

/* Whether the ray from the origin along dir hits the polygon's plane in front of the
 * origin and inside the polygon, up to `tolerance` (relative to the edge lengths).
 * Writes the distance to the hit point (for a unit dir) into *distance. */
static inline int ray_hits_polygon(const SpheraVec3 *v, int n, SpheraVec3 dir32, double tolerance,
                                   double *distance) {
  DVec3 normal = polygon_normal(v, n);
  DVec3 dir = dvec(dir32);
  double denominator = ddot(normal, dir);
  double t;
  DVec3 p;
  int i;
  double normal_length = dlength(normal);
  if (denominator == 0.0) return 0;
  t = ddot(normal, dvec(v[0])) / denominator;
  if (!(t > 0.0)) return 0;
  p = dscale(dir, t);
  if (distance) *distance = t * dlength(dir);
  for (i = 0; i < n; i++) {
    DVec3 a = dvec(v[i]);
    DVec3 edge = dsub(dvec(v[(i + 1) % n]), a);
    double side = ddot(dcross(edge, dsub(p, a)), normal) / (dlength(edge) * normal_length);
    if (side < -tolerance * dlength(edge)) return 0;
  }
  return 1;
}

/* The random numbers the good-input tests feed the samplers: both ends of [0, 1). */
#define U_COUNT 8
static inline void fill_u_values(float u[U_COUNT]) {
  u[0] = 0.0f;
  u[1] = 0.0625f;
  u[2] = 0.25f;
  u[3] = 0.3333f;
  u[4] = 0.5f;
  u[5] = 0.71f;
  u[6] = 0.9375f;
  u[7] = nextafterf(1.0f, 0.0f);
}

/* Whether u[i] lies strictly inside (0, 1), away from both ends. */
static inline int u_is_interior(int i) { return i > 0 && i < U_COUNT - 1; }

#endif /* SPHERA_FFI_TESTS_CHECK_H */
