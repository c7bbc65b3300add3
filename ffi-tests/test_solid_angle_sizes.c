/* C ABI tests of the fixed-size solid angle samplers (sphera_solid_angle_triangle_*,
 * sphera_solid_angle_quad_*): the same bits as sphera_solid_angle_polygon_* for the same
 * triangle or quad, and the contract for bad input and null pointers. */
#include <string.h>

#include "check.h"

/* Two samples, or two floats, are the same bits. */
static int same_sample(SpheraSample a, SpheraSample b) { return memcmp(&a, &b, sizeof a) == 0; }
static int same_float(float a, float b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Everything a triangle (quad) computes through its own storage equals the polygon
 * sampler's values for the same vertices, bit for bit. One body for both sizes: SIZE is
 * `triangle` or `quad`, TYPE its prepared struct, N its vertex count. */
#define DEFINE_CHECK_SAME_BITS(SIZE, TYPE, N)                                                \
  static void check_##SIZE(const char *name, const SpheraVec3 v[N]) {                       \
    SpheraSolidAnglePolygon polygon;                                                         \
    TYPE sized;                                                                              \
    float u[U_COUNT];                                                                        \
    int i, j, prepared = sphera_solid_angle_polygon_prepare(&polygon, v, N);                \
    int different = 0;                                                                       \
    printf(#SIZE " %s\n", name);                                                             \
    fill_u_values(u);                                                                        \
    CHECK(sphera_solid_angle_##SIZE##_prepare(&sized, v) == prepared);                      \
    CHECK(same_float(sphera_solid_angle_##SIZE##_solid_angle(&sized),                       \
                     sphera_solid_angle_polygon_solid_angle(&polygon)));                     \
    for (i = 0; i < U_COUNT; i++) {                                                          \
      for (j = 0; j < U_COUNT; j++) {                                                        \
        SpheraSample a = sphera_solid_angle_polygon_sample(&polygon, u[i], u[j]);           \
        SpheraSample b = sphera_solid_angle_##SIZE##_sample(&sized, u[i], u[j]);            \
        SpheraVec3 outside = vec3(-a.dir.x, -a.dir.y, a.dir.z + 0.5f);                      \
        float a0 = -1.0f, a1 = -1.0f, b0 = -2.0f, b1 = -2.0f;                               \
        int ia = sphera_solid_angle_polygon_invert(&polygon, a.dir, &a0, &a1);              \
        int ib = sphera_solid_angle_##SIZE##_invert(&sized, a.dir, &b0, &b1);               \
        different += !same_sample(a, b);                                                     \
        different += !same_float(sphera_solid_angle_polygon_pdf(&polygon, a.dir),          \
                                 sphera_solid_angle_##SIZE##_pdf(&sized, a.dir));           \
        different += !same_float(sphera_solid_angle_polygon_pdf(&polygon, outside),        \
                                 sphera_solid_angle_##SIZE##_pdf(&sized, outside));         \
        different += ia != ib || !same_float(a0, b0) || !same_float(a1, b1);                \
      }                                                                                      \
    }                                                                                        \
    CHECK(different == 0);                                                                   \
    if (prepared) CHECK(sphera_solid_angle_##SIZE##_solid_angle(&sized) > 0.0f);            \
  }

DEFINE_CHECK_SAME_BITS(triangle, SpheraSolidAngleTriangle, 3)
DEFINE_CHECK_SAME_BITS(quad, SpheraSolidAngleQuad, 4)

/* The empty value: no sample, pdf 0, solid angle 0, no inverse. */
static void check_triangle_is_empty(const SpheraSolidAngleTriangle *t, const char *what) {
  float u0 = 0.5f, u1 = 0.5f;
  printf("  empty triangle after: %s\n", what);
  CHECK(sphera_solid_angle_triangle_sample(t, 0.5f, 0.5f).pdf == 0.0f);
  CHECK(sphera_solid_angle_triangle_sample(t, 0.5f, 0.5f).dir.z == 1.0f);
  CHECK(sphera_solid_angle_triangle_pdf(t, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  CHECK(sphera_solid_angle_triangle_solid_angle(t) == 0.0f);
  CHECK(!sphera_solid_angle_triangle_invert(t, vec3(0.0f, 0.0f, 1.0f), &u0, &u1));
  CHECK(u0 == 0.0f && u1 == 0.0f);
}

static void check_quad_is_empty(const SpheraSolidAngleQuad *q, const char *what) {
  float u0 = 0.5f, u1 = 0.5f;
  printf("  empty quad after: %s\n", what);
  CHECK(sphera_solid_angle_quad_sample(q, 0.5f, 0.5f).pdf == 0.0f);
  CHECK(sphera_solid_angle_quad_sample(q, 0.5f, 0.5f).dir.z == 1.0f);
  CHECK(sphera_solid_angle_quad_pdf(q, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  CHECK(sphera_solid_angle_quad_solid_angle(q) == 0.0f);
  CHECK(!sphera_solid_angle_quad_invert(q, vec3(0.0f, 0.0f, 1.0f), &u0, &u1));
  CHECK(u0 == 0.0f && u1 == 0.0f);
}

int main(void) {
  const SpheraVec3 triangle[3] = {{0.2f, -0.3f, 1.0f}, {1.5f, 0.4f, 0.7f}, {-0.6f, 1.1f, 1.3f}};
  const SpheraVec3 small_triangle[3] = {{2.0f, 3.0f, 1.0f}, {2.01f, 3.0f, 1.0f}, {2.0f, 3.01f, 1.02f}};
  const SpheraVec3 tiny_triangle[3] = {{1.0f, 1.0f, 1.0f}, {1.0f + 1e-5f, 1.0f, 1.0f}, {1.0f, 1.0f + 1e-5f, 1.0f}};
  const SpheraVec3 distant_triangle[3] = {{3e4f, -2e4f, 1e5f}, {3e4f + 300.0f, -2e4f, 1e5f}, {3e4f, -2e4f + 200.0f, 1e5f + 50.0f}};
  const SpheraVec3 low_triangle[3] = {{-50.0f, -50.0f, 1e-6f}, {50.0f, -50.0f, 1e-6f}, {0.0f, 60.0f, 1e-6f}};
  const SpheraVec3 quad[4] = {{-1.0f, -1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {-1.0f, 1.0f, 1.0f}};
  const SpheraVec3 quad_clockwise[4] = {{-1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}, {-1.0f, -1.0f, 1.0f}};
  const SpheraVec3 low_quad[4] = {{-50.0f, -50.0f, 1e-6f}, {50.0f, -50.0f, 1e-6f}, {50.0f, 50.0f, 1e-6f}, {-50.0f, 50.0f, 1e-6f}};
  const SpheraVec3 degenerate[4] = {{1.0f, 0.0f, 1.0f}, {2.0f, 0.0f, 2.0f}, {3.0f, 0.0f, 3.0f}, {4.0f, 0.0f, 4.0f}};
  SpheraVec3 bad[4];
  SpheraSolidAngleTriangle t;
  SpheraSolidAngleQuad q;
  int k;

  /* The storage is smaller than the polygon's (the point of the sizes). */
  CHECK(sizeof(SpheraSolidAngleTriangle) < sizeof(SpheraSolidAngleQuad));
  CHECK(sizeof(SpheraSolidAngleQuad) < sizeof(SpheraSolidAnglePolygon));

  check_triangle("ordinary", triangle);
  check_triangle("small", small_triangle);
  check_triangle("1e-10 sr", tiny_triangle);
  check_triangle("1e5 away", distant_triangle);
  check_triangle("huge, 1e-6 above the shading point", low_triangle);
  check_triangle("degenerate", degenerate);
  check_quad("unit quad at z = 1", quad);
  check_quad("clockwise", quad_clockwise);
  check_quad("huge, 1e-6 above the shading point", low_quad);
  check_quad("degenerate", degenerate);
  {
    /* The triangles of a quad's storage: a quad with its last vertex repeated. */
    SpheraVec3 repeated[4] = {triangle[0], triangle[1], triangle[2], triangle[2]};
    check_quad("triangle with a repeated vertex", repeated);
  }

  printf("bad input\n");
  CHECK(!sphera_solid_angle_triangle_prepare(NULL, triangle));
  CHECK(!sphera_solid_angle_quad_prepare(NULL, quad));
  CHECK(!sphera_solid_angle_triangle_prepare(&t, NULL));
  check_triangle_is_empty(&t, "null vertices");
  CHECK(!sphera_solid_angle_quad_prepare(&q, NULL));
  check_quad_is_empty(&q, "null vertices");
  CHECK(!sphera_solid_angle_triangle_prepare(&t, degenerate));
  check_triangle_is_empty(&t, "zero solid angle");
  CHECK(!sphera_solid_angle_quad_prepare(&q, degenerate));
  check_quad_is_empty(&q, "zero solid angle");
  for (k = 0; k < 3; k++) {
    const float values[3] = {NAN, INFINITY, -INFINITY};
    CHECK(sphera_solid_angle_triangle_prepare(&t, triangle));
    CHECK(sphera_solid_angle_quad_prepare(&q, quad));
    memcpy(bad, quad, sizeof bad);
    bad[k].y = values[k];
    CHECK(!sphera_solid_angle_triangle_prepare(&t, bad));
    check_triangle_is_empty(&t, "a non-finite coordinate over a valid triangle");
    CHECK(!sphera_solid_angle_quad_prepare(&q, bad));
    check_quad_is_empty(&q, "a non-finite coordinate over a valid quad");
  }
  memset(&t, 0x5a, sizeof t);
  memset(&q, 0x5a, sizeof q);
  CHECK(!sphera_solid_angle_triangle_prepare(&t, degenerate));
  check_triangle_is_empty(&t, "zero solid angle over garbage");
  CHECK(!sphera_solid_angle_quad_prepare(&q, degenerate));
  check_quad_is_empty(&q, "zero solid angle over garbage");

  printf("null pointers\n");
  check_triangle_is_empty(NULL, "(a null triangle)");
  check_quad_is_empty(NULL, "(a null quad)");
  CHECK(sphera_solid_angle_triangle_prepare(&t, triangle));
  CHECK(sphera_solid_angle_quad_prepare(&q, quad));
  CHECK(!sphera_solid_angle_triangle_invert(&t, vec3(0.0f, 0.0f, 1.0f), NULL, NULL));
  CHECK(!sphera_solid_angle_quad_invert(&q, vec3(0.0f, 0.0f, 1.0f), NULL, NULL));
  return check_summary();
}
