/* Adversarial C ABI test: every exported function driven with NaN, ±inf, ±0, denormals,
 * 1e±30, FLT_MAX, counts 0, 1, 2, 9 and UINT32_MAX, null pointers, duplicate and
 * collinear vertices, non-convex and non-planar polygons, lights behind the shading
 * point, random numbers outside [0, 1), and the near-degenerate hard cases (polygons of
 * 1e-10 sr, through the zenith, crossing the horizon, the shading point in the
 * polygon's plane, caps of 1e-7 sr, shading point on and inside a sphere, pivot norms
 * 0, 1 - ulp, 1, 2, NaN). A combinatorial generator replaces each coordinate of a table
 * of base polygons (and each argument of the scalar functions) by each special float.
 *
 * Asserted everywhere: no crash, every returned float and every field of every
 * returned struct finite, no NaN word in a prepared struct (±inf marks a degenerate
 * ellipse inside the projected samplers' private sectors), pdfs and measures
 * non-negative, sampled directions unit vectors, and "no sample" = {(0, 0, 1), 0};
 * where the input is invalid (see docs/contract.md), the documented failure value.
 *
 * The whole suite runs twice: in the default float environment and, on x86 with SSE,
 * with MXCSR's flush-to-zero and denormals-are-zero bits set (FTZ|DAZ). */
#include <float.h>
#include <stdint.h>
#include <string.h>

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#define HAVE_MXCSR 1
#else
#define HAVE_MXCSR 0
#endif

#include "check.h"

/* ---- counting expectations (check.h's CHECK prints every failure; here only the
 * first few of each kind, since a broken invariant would repeat millions of times) -- */

static long expectations = 0;
static int daz_mode = 0; /* denormal inputs read as 0 in C's comparisons */
static long calls = 0;
static int failures_printed = 0;

static void expect_at(int ok, const char *what, const char *file, int line) {
  expectations++;
  if (!ok) {
    check_failed++;
    if (failures_printed < 400) {
      failures_printed++;
      printf("%s:%d: EXPECT failed: %s\n", file, line, what);
      fflush(stdout);
    }
  } else {
    check_passed++;
  }
}
#define EXPECT(expr) expect_at((expr) ? 1 : 0, #expr, __FILE__, __LINE__)

/* ---- special values ----------------------------------------------------------------- */

static float specials[24];
static const int SPECIAL_COUNT = 24;
static float us[13];
static const int U_VALUES = 13;

static void fill_tables(void) {
  const float s[24] = {0.0f,     -0.0f,   1e-45f,   -1e-45f,  1e-40f, FLT_MIN, 1e-30f, -1e-30f,
                       1e-10f,   1.0f,    -1.0f,    0.5f,     2.0f,   3.0f,    1e10f,  1e30f,
                       -1e30f,   FLT_MAX, -FLT_MAX, FLT_EPSILON, 0.0f, 0.0f, 0.0f, 0.0f};
  const float u[13] = {0.0f, 0.5f, 0.25f, 1.0f, -1.0f, -0.0f, 2.0f, 1e-45f, 0.0f, 0.0f, 0.0f,
                       0.0f, 0.0f};
  memcpy(specials, s, sizeof s);
  specials[20] = NAN;
  specials[21] = INFINITY;
  specials[22] = -INFINITY;
  specials[23] = nextafterf(1.0f, 0.0f);
  memcpy(us, u, sizeof u);
  us[8] = nextafterf(1.0f, 0.0f);
  us[9] = nextafterf(1.0f, 2.0f);
  us[10] = NAN;
  us[11] = INFINITY;
  us[12] = -INFINITY;
}

/* ---- invariants --------------------------------------------------------------------- */

static int finite3(SpheraVec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

static int unit3(SpheraVec3 v) {
  double l = sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z);
  return fabs(l - 1.0) < 1e-5;
}

static int is_no_sample(SpheraSample s) {
  return s.pdf == 0.0f && s.dir.x == 0.0f && s.dir.y == 0.0f && s.dir.z == 1.0f;
}

/* A sample: finite, pdf >= 0, a unit dir, and pdf 0 only as {(0, 0, 1), 0}. */
static void expect_sample_at(SpheraSample s, const char *file, int line) {
  expect_at(finite3(s.dir) && isfinite(s.pdf) && s.pdf >= 0.0f, "finite sample", file, line);
  expect_at(unit3(s.dir), "unit direction", file, line);
  if (s.pdf == 0.0f) expect_at(is_no_sample(s), "pdf 0 is {(0, 0, 1), 0}", file, line);
}
#define expect_sample(s) expect_sample_at((s), __FILE__, __LINE__)

#define expect_density(x) expect_density_at((x), __FILE__, __LINE__)
static void expect_density_at(float x, const char *file, int line) {
  if (!(isfinite(x) && x >= 0.0f) && failures_printed < 400) printf("    density %g\n", x);
  expect_at(isfinite(x) && x >= 0.0f, "finite non-negative density", file, line);
}

/* No 32-bit word of a prepared struct is NaN (all are f32 or u32 fields). */
#define expect_words_not_nan(v, n) expect_words_not_nan_at((v), (n), __FILE__, __LINE__)
static void expect_words_not_nan_at(const void *value, size_t size, const char *file, int line) {
  const unsigned char *bytes = (const unsigned char *)value;
  size_t i;
  int ok = 1;
  for (i = 0; i + 4 <= size; i += 4) {
    uint32_t bits;
    memcpy(&bits, bytes + i, 4);
    if ((bits & 0x7f800000u) == 0x7f800000u && (bits & 0x007fffffu) != 0u) {
      if (ok && failures_printed < 400) printf("    NaN word at byte %lu of %lu\n", (unsigned long)i, (unsigned long)size);
      ok = 0;
    }
  }
  expect_at(ok && size % 4 == 0, "no NaN word in a prepared struct", file, line);
}

/* Every word finite (structs with public fields: caps, LTCs, frames, samples). */
static void expect_words_finite(const void *value, size_t size) {
  const unsigned char *bytes = (const unsigned char *)value;
  size_t i;
  int ok = 1;
  for (i = 0; i + 4 <= size; i += 4) {
    uint32_t bits;
    memcpy(&bits, bytes + i, 4);
    if ((bits & 0x7f800000u) == 0x7f800000u) ok = 0;
  }
  EXPECT(ok);
}

/* ---- polygons ----------------------------------------------------------------------- */

typedef struct Polygon {
  SpheraVec3 v[SPHERA_MAX_POLYGON_VERTICES];
  uint32_t count;
} Polygon;

/* The base polygons: good and hard cases. */
#define BASE_COUNT 17
static Polygon bases[BASE_COUNT];

static void set_polygon(Polygon *p, uint32_t count, const float *xyz) {
  uint32_t i;
  memset(p, 0, sizeof *p);
  p->count = count;
  for (i = 0; i < count && i < SPHERA_MAX_POLYGON_VERTICES; i++)
    p->v[i] = vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
}

static void regular(Polygon *p, uint32_t n, float cx, float cy, float cz, float radius, float tilt) {
  uint32_t i;
  memset(p, 0, sizeof *p);
  p->count = n;
  for (i = 0; i < n; i++) {
    double t = 6.283185307179586 * i / n;
    p->v[i] = vec3(cx + radius * (float)cos(t), cy + radius * (float)sin(t),
                   cz + tilt * radius * (float)cos(t));
  }
}

static void fill_bases(void) {
  const float quad[12] = {-1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1};
  const float horizon[12] = {-1, 0.5f, -0.5f, 1, 0.5f, -0.5f, 1, 1.5f, 0.8f, -1, 1.5f, 0.8f};
  const float behind[9] = {0.5f, 0, -1, -0.5f, 0.5f, -1, -0.5f, -0.5f, -1};
  const float in_plane[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};     /* z = 0 */
  const float through_point[12] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1}; /* plane y = 0 */
  const float collinear[9] = {0, 0, 1, 1, 1, 1, 2, 2, 1};
  const float duplicate[12] = {-1, -1, 1, -1, -1, 1, 1, 1, 1, -1, 1, 1};
  const float nonconvex[15] = {-1, -1, 1, 1, -1, 1, 0, -0.5f, 1, 1, 1, 1, -1, 1, 1};
  const float nonplanar[12] = {-1, -1, 1, 1, -1, 3, 1, 1, 1, -1, 1, 4};
  const float huge[12] = {-1e30f, -1e30f, 1e30f, 1e30f, -1e30f, 1e30f, 1e30f, 1e30f, 1e30f,
                          -1e30f, 1e30f, 1e30f};
  const float tiny_near[9] = {1e-30f, 0, 1e-30f, 0, 1e-30f, 1e-30f, -1e-30f, 0, 1e-30f};
  set_polygon(&bases[0], 4, quad);
  set_polygon(&bases[1], 4, horizon);
  set_polygon(&bases[2], 3, behind);
  set_polygon(&bases[3], 4, in_plane);
  set_polygon(&bases[4], 4, through_point);
  set_polygon(&bases[5], 3, collinear);
  set_polygon(&bases[6], 4, duplicate);
  set_polygon(&bases[7], 5, nonconvex);
  set_polygon(&bases[8], 4, nonplanar);
  set_polygon(&bases[9], 4, huge);
  set_polygon(&bases[10], 3, tiny_near);
  regular(&bases[11], 8, 0.0f, 0.0f, 1.0f, 0.5f, 0.0f);            /* zenith, 8 vertices */
  regular(&bases[12], 5, 0.3f, 0.0f, 1e5f, 0.56f, 0.0f);           /* about 1e-10 sr */
  regular(&bases[13], 7, 0.0f, 2.0f, 0.2f, 1.0f, 0.5f);            /* crosses the horizon */
  regular(&bases[14], 8, 2.0f, 0.0f, 0.1f, 1.0f, 0.3f);            /* 8 vertices, crossing */
  regular(&bases[15], 6, 0.0f, 0.0f, 1e-6f, 3.0f, 0.0f);           /* just above, large */
  regular(&bases[16], 3, 1e4f, 1e4f, 1e-3f, 1.0f, 0.0f);           /* far, grazing */
}

static int polygon_is_finite(const Polygon *p, uint32_t count) {
  uint32_t i;
  for (i = 0; i < count && i < SPHERA_MAX_POLYGON_VERTICES; i++)
    if (!finite3(p->v[i])) return 0;
  return 1;
}

/* The u pairs a prepared sampler is driven with: all 13 × 13 for the base polygons,
 * a diagonal subset for the perturbed ones. */
static int pair_count(int full) { return full ? U_VALUES * U_VALUES : U_VALUES + 4; }
static void pair(int k, int full, float *u0, float *u1) {
  if (full) {
    *u0 = us[k / U_VALUES];
    *u1 = us[k % U_VALUES];
  } else if (k < U_VALUES) {
    *u0 = us[k];
    *u1 = us[(k * 5 + 3) % U_VALUES];
  } else {
    *u0 = 0.5f * (float)(k - U_VALUES) / 4.0f + 0.1f;
    *u1 = 0.7f;
  }
}

static SpheraVec3 probes[6];
static void fill_probes(void) {
  probes[0] = vec3(0.0f, 0.0f, 1.0f);
  probes[1] = vec3(0.0f, 0.0f, 0.0f);
  probes[2] = vec3(NAN, 0.0f, 1.0f);
  probes[3] = vec3(0.0f, 0.0f, INFINITY);
  probes[4] = vec3(1e-45f, 1e-45f, 1e-45f);
  probes[5] = vec3(FLT_MAX, FLT_MAX, FLT_MAX);
}

/* One family through its prepare, sample, pdf and measure: the shared body. */
#define CHECK_FAMILY(TYPE, PREPARE, SAMPLE, PDF, MEASURE)                               \
  do {                                                                                 \
    TYPE value;                                                                        \
    int ok, k;                                                                         \
    float m;                                                                           \
    memset(&value, 0xff, sizeof value); /* NaN garbage that prepare must overwrite */  \
    ok = PREPARE(&value, p->v, count);                                                 \
    calls++;                                                                           \
    expect_words_not_nan(&value, sizeof value);                                        \
    if (invalid) EXPECT(!ok);                                                          \
    EXPECT(!PREPARE(NULL, p->v, count));                                               \
    m = MEASURE(&value);                                                               \
    expect_density(m);                                                                 \
    if (!ok) EXPECT(m == 0.0f);                                                        \
    EXPECT(MEASURE(NULL) == 0.0f);                                                     \
    EXPECT(is_no_sample(SAMPLE(NULL, 0.5f, 0.5f)));                                    \
    EXPECT(PDF(NULL, probes[0]) == 0.0f);                                              \
    for (k = 0; k < 6; k++) {                                                          \
      float d = PDF(&value, probes[k]);                                                \
      expect_density(d);                                                               \
      if (!ok || !finite3(probes[k])) EXPECT(d == 0.0f);                               \
    }                                                                                  \
    for (k = 0; k < pair_count(full); k++) {                                           \
      float u0, u1;                                                                    \
      SpheraSample s;                                                                  \
      pair(k, full, &u0, &u1);                                                         \
      s = SAMPLE(&value, u0, u1);                                                      \
      calls++;                                                                         \
      expect_sample(s);                                                                \
      if (!ok) EXPECT(is_no_sample(s));                                                \
      if (s.pdf > 0.0f) expect_density(PDF(&value, s.dir));                            \
    }                                                                                  \
    calls += 8;                                                                        \
  } while (0)

/* Measures for the families without one. */
static float hart_bilinear_measure(const SpheraHartBilinearPolygon *p) {
  return sphera_hart_bilinear_polygon_pdf(p, vec3(0.0f, 0.0f, 0.0f));
}
static float hart_biquadratic_measure(const SpheraHartBiquadraticPolygon *p) {
  return sphera_hart_biquadratic_polygon_pdf(p, vec3(0.0f, 0.0f, 0.0f));
}

static SpheraLtc ltc_for_polygons;
static SpheraMaterial material_for_polygons;

static float ltc_measure(const SpheraLtcPolygon *p) {
  float x = sphera_ltc_polygon_integral(p);
  EXPECT(x <= 1.0f + 1e-5f);
  return x;
}

/* The fixed-size solid angle samplers take exactly 3 or 4 vertices: other counts prepare
 * from null vertices, which must fail and write the empty value. */
static bool triangle_prepare(SpheraSolidAngleTriangle *out, const SpheraVec3 *v, uint32_t count) {
  return sphera_solid_angle_triangle_prepare(out, count == 3 ? v : NULL);
}
static bool quad_prepare(SpheraSolidAngleQuad *out, const SpheraVec3 *v, uint32_t count) {
  return sphera_solid_angle_quad_prepare(out, count == 4 ? v : NULL);
}

static void check_polygon(const Polygon *p, uint32_t count, int full) {
  int invalid = !(count >= 3 && count <= SPHERA_MAX_POLYGON_VERTICES) ||
                !polygon_is_finite(p, count);
  /* Clip. */
  {
    SpheraVec3 copy[SPHERA_MAX_POLYGON_VERTICES];
    uint32_t n, i;
    memcpy(copy, p->v, sizeof copy);
    n = sphera_polygon_clip(copy, count);
    calls++;
    EXPECT(n == 0 || (n >= 3 && n <= SPHERA_MAX_POLYGON_VERTICES));
    if (!(count >= 3 && count <= SPHERA_MAX_POLYGON_VERTICES)) {
      EXPECT(n == 0);
      EXPECT(memcmp(copy, p->v, sizeof copy) == 0);
    }
    if (!invalid)
      for (i = 0; i < n; i++) EXPECT(finite3(copy[i]) && copy[i].z >= 0.0f);
    EXPECT(sphera_polygon_clip(NULL, count) == 0);
  }
  CHECK_FAMILY(SpheraSolidAnglePolygon, sphera_solid_angle_polygon_prepare,
               sphera_solid_angle_polygon_sample, sphera_solid_angle_polygon_pdf,
               sphera_solid_angle_polygon_solid_angle);
  /* The inverse of solid angle sampling. */
  {
    SpheraSolidAnglePolygon value;
    int ok = sphera_solid_angle_polygon_prepare(&value, p->v, count), k;
    for (k = 0; k < pair_count(0); k++) {
      float u0, u1, v0 = NAN, v1 = NAN;
      int inverted;
      SpheraSample s;
      pair(k, 0, &u0, &u1);
      s = sphera_solid_angle_polygon_sample(&value, u0, u1);
      inverted = sphera_solid_angle_polygon_invert(&value, s.dir, &v0, &v1);
      calls += 2;
      EXPECT(isfinite(v0) && isfinite(v1) && v0 >= 0.0f && v0 <= 1.0f && v1 >= 0.0f &&
             v1 <= 1.0f);
      if (!inverted) EXPECT(v0 == 0.0f && v1 == 0.0f);
      if (!ok) EXPECT(!inverted);
      EXPECT(!sphera_solid_angle_polygon_invert(&value, s.dir, NULL, &v1));
      EXPECT(!sphera_solid_angle_polygon_invert(NULL, s.dir, &v0, &v1));
    }
  }
  CHECK_FAMILY(SpheraSolidAngleTriangle, triangle_prepare, sphera_solid_angle_triangle_sample,
               sphera_solid_angle_triangle_pdf, sphera_solid_angle_triangle_solid_angle);
  CHECK_FAMILY(SpheraSolidAngleQuad, quad_prepare, sphera_solid_angle_quad_sample,
               sphera_solid_angle_quad_pdf, sphera_solid_angle_quad_solid_angle);
  /* Their inverses: the polygon's, bit for bit (where the sizes prepare). */
  {
    SpheraSolidAnglePolygon polygon;
    SpheraSolidAngleTriangle triangle;
    SpheraSolidAngleQuad quad;
    int ok = sphera_solid_angle_polygon_prepare(&polygon, p->v, count), k;
    int ok3 = triangle_prepare(&triangle, p->v, count), ok4 = quad_prepare(&quad, p->v, count);
    EXPECT(ok3 == (ok && count == 3) && ok4 == (ok && count == 4));
    for (k = 0; k < pair_count(0); k++) {
      float u0, u1, v0 = NAN, v1 = NAN, w0 = NAN, w1 = NAN, x0 = NAN, x1 = NAN;
      int inverted, inverted3, inverted4;
      SpheraSample s;
      pair(k, 0, &u0, &u1);
      s = sphera_solid_angle_polygon_sample(&polygon, u0, u1);
      inverted = sphera_solid_angle_polygon_invert(&polygon, s.dir, &v0, &v1);
      inverted3 = sphera_solid_angle_triangle_invert(&triangle, s.dir, &w0, &w1);
      inverted4 = sphera_solid_angle_quad_invert(&quad, s.dir, &x0, &x1);
      calls += 3;
      EXPECT(isfinite(w0) && isfinite(w1) && isfinite(x0) && isfinite(x1));
      if (ok3) EXPECT(inverted3 == inverted && w0 == v0 && w1 == v1);
      if (ok4) EXPECT(inverted4 == inverted && x0 == v0 && x1 == v1);
      if (!ok3) EXPECT(!inverted3 && w0 == 0.0f && w1 == 0.0f);
      if (!ok4) EXPECT(!inverted4 && x0 == 0.0f && x1 == 0.0f);
      EXPECT(!sphera_solid_angle_triangle_invert(NULL, s.dir, &w0, &w1));
      EXPECT(!sphera_solid_angle_quad_invert(&quad, s.dir, &x0, NULL));
    }
  }
  CHECK_FAMILY(SpheraTurkPolygon, sphera_turk_polygon_prepare, sphera_turk_polygon_sample,
               sphera_turk_polygon_pdf, sphera_turk_polygon_area);
  CHECK_FAMILY(SpheraArvoPolygon, sphera_arvo_polygon_prepare, sphera_arvo_polygon_sample,
               sphera_arvo_polygon_pdf, sphera_arvo_polygon_solid_angle);
  CHECK_FAMILY(SpheraHartBilinearPolygon, sphera_hart_bilinear_polygon_prepare,
               sphera_hart_bilinear_polygon_sample, sphera_hart_bilinear_polygon_pdf,
               hart_bilinear_measure);
  CHECK_FAMILY(SpheraHartBiquadraticPolygon, sphera_hart_biquadratic_polygon_prepare,
               sphera_hart_biquadratic_polygon_sample, sphera_hart_biquadratic_polygon_pdf,
               hart_biquadratic_measure);
  CHECK_FAMILY(SpheraClippedSolidAnglePolygon, sphera_clipped_solid_angle_polygon_prepare,
               sphera_clipped_solid_angle_polygon_sample,
               sphera_clipped_solid_angle_polygon_pdf,
               sphera_clipped_solid_angle_polygon_solid_angle);
  CHECK_FAMILY(SpheraProjectedPolygon, sphera_projected_polygon_prepare,
               sphera_projected_polygon_sample, sphera_projected_polygon_pdf,
               sphera_projected_polygon_projected_solid_angle);
  CHECK_FAMILY(SpheraProjectedPolygon, sphera_projected_polygon_prepare_fast,
               sphera_projected_polygon_sample_fast, sphera_projected_polygon_pdf,
               sphera_projected_polygon_projected_solid_angle);
  CHECK_FAMILY(SpheraArvoProjectedPolygon, sphera_arvo_projected_polygon_prepare,
               sphera_arvo_projected_polygon_sample, sphera_arvo_projected_polygon_pdf,
               sphera_arvo_projected_polygon_projected_solid_angle);
  /* The LTC restricted to the polygon. */
  {
    SpheraLtcPolygon value;
    int ok, k;
    memset(&value, 0xff, sizeof value);
    ok = sphera_ltc_polygon_prepare(&value, &ltc_for_polygons, p->v, count);
    calls++;
    expect_words_not_nan(&value, sizeof value);
    if (invalid) EXPECT(!ok);
    EXPECT(!sphera_ltc_polygon_prepare(&value, NULL, p->v, count));
    EXPECT(sphera_ltc_polygon_integral(&value) == 0.0f);
    EXPECT(!sphera_ltc_polygon_prepare(NULL, &ltc_for_polygons, p->v, count));
    ok = sphera_ltc_polygon_prepare(&value, &ltc_for_polygons, p->v, count);
    expect_density(ltc_measure(&value));
    if (!ok) EXPECT(sphera_ltc_polygon_integral(&value) == 0.0f);
    EXPECT(is_no_sample(sphera_ltc_polygon_sample(NULL, 0.5f, 0.5f)));
    EXPECT(sphera_ltc_polygon_pdf(NULL, probes[0]) == 0.0f);
    for (k = 0; k < 6; k++) {
      float d = sphera_ltc_polygon_pdf(&value, probes[k]);
      expect_density(d);
      if (!ok || !finite3(probes[k])) EXPECT(d == 0.0f);
    }
    for (k = 0; k < pair_count(full); k++) {
      float u0, u1;
      SpheraSample s;
      pair(k, full, &u0, &u1);
      s = sphera_ltc_polygon_sample(&value, u0, u1);
      calls++;
      expect_sample(s);
      if (!ok) EXPECT(is_no_sample(s));
      if (s.pdf > 0.0f) expect_density(sphera_ltc_polygon_pdf(&value, s.dir));
    }
  }
  /* The polygon light, every heuristic (one with a NaN visibility, and two unknown
   * ones, which fail). */
  {
    const uint32_t heuristics[8] = {0, 1, 2, 3, 4, SPHERA_MIS_CLAMPED_OPTIMAL, 5, UINT32_MAX};
    int h;
    for (h = 0; h < 8; h++) {
      uint32_t heuristic = heuristics[h];
      SpheraPolygonLight light;
      SpheraVec3 unshadowed;
      int ok, k;
      uint32_t technique;
      float visibility = h == 5 ? NAN : 0.5f;
      memset(&light, 0xff, sizeof light);
      ok = sphera_polygon_light_prepare(&light, p->v, count, vec3(0.3f, 0.1f, 0.9f),
                                        &material_for_polygons, heuristic, visibility);
      calls++;
      expect_words_not_nan(&light, sizeof light);
      if (invalid || heuristic > SPHERA_MIS_OPTIMAL) EXPECT(!ok);
      unshadowed = sphera_polygon_light_unshadowed(&light);
      EXPECT(finite3(unshadowed) && unshadowed.x >= 0.0f && unshadowed.y >= 0.0f &&
             unshadowed.z >= 0.0f);
      for (technique = 0; technique <= 2; technique++) {
        for (k = 0; k < pair_count(0); k++) {
          float u0, u1;
          SpheraLightSample s;
          SpheraSample plain;
          pair(k, 0, &u0, &u1);
          s = sphera_polygon_light_sample(&light, technique, u0, u1);
          calls++;
          expect_words_finite(&s, sizeof s);
          plain.dir = s.dir;
          plain.pdf = s.pdf;
          expect_sample(plain);
          if (s.pdf == 0.0f || !ok || technique == 2)
            EXPECT(s.pdf == 0.0f && s.visible.x == 0.0f && s.visible.y == 0.0f &&
                   s.visible.z == 0.0f && s.unoccluded.x == 0.0f &&
                   s.unoccluded.y == 0.0f && s.unoccluded.z == 0.0f);
        }
      }
    }
    EXPECT(!sphera_polygon_light_prepare(NULL, p->v, count, vec3(0, 0, 1),
                                         &material_for_polygons, 0, 0.5f));
  }
}

static void polygon_suite(void) {
  int b;
  uint32_t counts[7] = {0, 1, 2, 9, 4294967295u, 3, 8};
  for (b = 0; b < BASE_COUNT; b++) {
    const Polygon *base = &bases[b];
    uint32_t i, c;
    int s, k;
    check_polygon(base, base->count, 1);
    /* Null vertices and counts out of range (and in range with the same array). */
    {
      SpheraSolidAnglePolygon value;
      EXPECT(!sphera_solid_angle_polygon_prepare(&value, NULL, base->count));
      EXPECT(sphera_solid_angle_polygon_solid_angle(&value) == 0.0f);
      EXPECT(!sphera_projected_polygon_prepare(NULL, NULL, 4));
    }
    for (k = 0; k < 7; k++) {
      Polygon padded = *base;
      check_polygon(&padded, counts[k], 0);
    }
    /* Each coordinate of each vertex replaced by each special float. */
    for (i = 0; i < base->count; i++) {
      for (c = 0; c < 3; c++) {
        for (s = 0; s < SPECIAL_COUNT; s++) {
          Polygon perturbed = *base;
          float *coordinate = c == 0 ? &perturbed.v[i].x : c == 1 ? &perturbed.v[i].y
                                                                  : &perturbed.v[i].z;
          *coordinate = specials[s];
          check_polygon(&perturbed, perturbed.count, 0);
        }
      }
    }
    /* Whole polygons scaled by specials (tiny, huge, denormal, mirrored). */
    for (s = 0; s < SPECIAL_COUNT; s++) {
      Polygon scaled = *base;
      for (i = 0; i < base->count; i++) {
        scaled.v[i].x *= specials[s];
        scaled.v[i].y *= specials[s];
        scaled.v[i].z *= specials[s];
      }
      check_polygon(&scaled, scaled.count, 0);
    }
  }
}

/* ---- BRDFs, MIS, frame, LTC --------------------------------------------------------- */

static SpheraVec3 special_vec(int k) {
  /* Vectors with special coordinates: k indexes (x, y, z) combinations. */
  return vec3(specials[k % SPECIAL_COUNT], specials[(k / 3 + 7) % SPECIAL_COUNT],
              specials[(k / 5 + 11) % SPECIAL_COUNT]);
}

#define DIRECTION_COUNT 12
static SpheraVec3 directions[DIRECTION_COUNT];
static void fill_directions(void) {
  directions[0] = vec3(0.0f, 0.0f, 1.0f);
  directions[1] = vec3(0.6f, 0.0f, 0.8f);
  directions[2] = vec3(1.0f, 0.0f, 1e-7f);     /* grazing */
  directions[3] = vec3(1.0f, 0.0f, 0.0f);      /* horizon */
  directions[4] = vec3(0.0f, 0.6f, -0.8f);     /* below */
  directions[5] = vec3(0.0f, 0.0f, 0.0f);
  directions[6] = vec3(NAN, 0.0f, 1.0f);
  directions[7] = vec3(0.0f, 0.0f, INFINITY);
  directions[8] = vec3(1e-30f, 1e-30f, 1e-30f);
  directions[9] = vec3(1e-45f, 0.0f, 1e-45f);
  directions[10] = vec3(1e30f, -1e30f, 1e30f);
  directions[11] = vec3(0.0f, 0.0f, -1.0f);
}

static void brdf_suite(void) {
  int r, d, e, k;
  for (r = 0; r < SPECIAL_COUNT; r++) {
    SpheraGgxBrdf ggx;
    int ok;
    memset(&ggx, 0xff, sizeof ggx);
    ok = sphera_ggx_brdf_prepare(&ggx, specials[r], special_vec(r));
    calls++;
    expect_words_finite(&ggx, sizeof ggx);
    if (!isfinite(specials[r])) EXPECT(!ok);
    EXPECT(!sphera_ggx_brdf_prepare(NULL, 0.5f, vec3(1, 1, 1)));
    for (d = 0; d < DIRECTION_COUNT; d++) {
      for (e = 0; e < DIRECTION_COUNT; e++) {
        SpheraVec3 f = sphera_ggx_brdf_eval(&ggx, directions[d], directions[e]);
        float g = sphera_ggx_brdf_eval_without_fresnel(&ggx, directions[d], directions[e]);
        float p = sphera_ggx_brdf_pdf(&ggx, directions[d], directions[e]);
        SpheraVec3 l = sphera_lambert_eval(special_vec(r + e), directions[d], directions[e]);
        calls += 4;
        EXPECT(finite3(f) && f.x >= 0.0f && f.y >= 0.0f && f.z >= 0.0f);
        expect_density(g);
        expect_density(p);
        EXPECT(finite3(l) && l.x >= 0.0f && l.y >= 0.0f && l.z >= 0.0f);
        if (!(directions[d].z > 0.0f) || !(directions[e].z > 0.0f)) {
          EXPECT(f.x == 0.0f && g == 0.0f && p == 0.0f && l.x == 0.0f);
        }
      }
      for (k = 0; k < U_VALUES * U_VALUES; k += 7) {
        SpheraSample s = sphera_ggx_brdf_sample(&ggx, directions[d], us[k / U_VALUES], us[k % U_VALUES]);
        calls++;
        expect_sample(s);
        if (!(directions[d].z > 0.0f) || !finite3(directions[d])) EXPECT(is_no_sample(s));
        if (s.pdf > 0.0f) EXPECT(s.dir.z > 0.0f);
      }
      EXPECT(is_no_sample(sphera_ggx_brdf_sample(NULL, directions[d], 0.5f, 0.5f)));
      EXPECT(sphera_ggx_brdf_pdf(NULL, directions[d], directions[0]) == 0.0f);
      EXPECT(sphera_ggx_brdf_eval_without_fresnel(NULL, directions[d], directions[0]) == 0.0f);
      expect_density(sphera_lambert_pdf(directions[d]));
    }
  }
  for (k = 0; k < U_VALUES * U_VALUES; k++) {
    SpheraSample s = sphera_lambert_sample(us[k / U_VALUES], us[k % U_VALUES]);
    calls++;
    expect_sample(s);
    EXPECT(s.pdf > 0.0f && s.dir.z > 0.0f);
  }
}

static unsigned lcg = 12345u;
static int pick(void) {
  lcg = lcg * 1664525u + 1013904223u;
  return (int)((lcg >> 8) % (unsigned)SPECIAL_COUNT);
}

static void mis_suite(void) {
  int a, b, k;
  /* All pairs for the two-argument heuristics. */
  for (a = 0; a < SPECIAL_COUNT; a++) {
    for (b = 0; b < SPECIAL_COUNT; b++) {
      float x = sphera_mis_balance(specials[a], specials[b]);
      float y = sphera_mis_power(specials[a], specials[b]);
      calls += 2;
      EXPECT(isfinite(x) && x >= 0.0f && x <= 1.0f);
      EXPECT(isfinite(y) && y >= 0.0f && y <= 1.0f);
    }
  }
  /* Random combinations of specials for the four- to six-argument ones. */
  for (k = 0; k < 60000; k++) {
    float f = specials[pick()], p0 = specials[pick()], c0 = specials[pick()];
    float p1 = specials[pick()], c1 = specials[pick()], v = specials[pick()];
    float w = sphera_mis_weighted_balance(p0, c0, p1, c1);
    float o = sphera_mis_optimal_contribution(f, p0, c0, p1, c1, v);
    float q = sphera_mis_clamped_optimal_contribution(f, p0, c0, p1, c1, v);
    float cw = sphera_mis_clamped_optimal_weight(p0, c0, p1, c1, v);
    calls += 4;
    EXPECT(isfinite(w) && w >= 0.0f && w <= 1.0f);
    EXPECT(isfinite(o));
    EXPECT(isfinite(q));
    EXPECT(isfinite(cw) && cw >= 0.0f && cw <= 1.0f + 1e-6f);
  }
}

static void frame_and_ltc_suite(void) {
  int k, d, r;
  for (k = 0; k < SPECIAL_COUNT * 15; k++) {
    SpheraFrame frame;
    SpheraVec3 n = k < DIRECTION_COUNT ? directions[k] : special_vec(k);
    int ok;
    memset(&frame, 0xff, sizeof frame);
    ok = sphera_frame_from_normal(&frame, n);
    calls++;
    expect_words_finite(&frame, sizeof frame);
    if (!finite3(n)) EXPECT(!ok);
    if (!ok) EXPECT(frame.normal.z == 1.0f && frame.tangent.x == 1.0f);
    for (d = 0; d < DIRECTION_COUNT; d++) {
      SpheraVec3 a = sphera_frame_to_local(&frame, directions[d]);
      SpheraVec3 b = sphera_frame_to_world(&frame, directions[d]);
      calls += 2;
      if (finite3(directions[d]) && fabsf(directions[d].x) < 1e20f)
        EXPECT(finite3(a) && finite3(b));
    }
  }
  EXPECT(!sphera_frame_from_normal(NULL, vec3(0, 0, 1)));
  {
    SpheraVec3 v = vec3(1.0f, 2.0f, 3.0f);
    EXPECT(vec3_equal(sphera_frame_to_local(NULL, v), v));
    EXPECT(vec3_equal(sphera_frame_to_world(NULL, v), v));
  }
  /* LTCs for special views and roughnesses. */
  for (d = 0; d < DIRECTION_COUNT + SPECIAL_COUNT; d++) {
    SpheraVec3 wo = d < DIRECTION_COUNT ? directions[d] : special_vec(d * 3);
    for (r = 0; r < SPECIAL_COUNT; r++) {
      SpheraLtc ltc;
      SpheraVec3 albedo;
      int ok, e;
      memset(&ltc, 0xff, sizeof ltc);
      ok = sphera_ltc_prepare(&ltc, wo, specials[r]);
      calls++;
      expect_words_finite(&ltc, sizeof ltc);
      if (!finite3(wo) || !(wo.z > 0.0f)) EXPECT(!ok);
      albedo = sphera_ltc_specular_albedo(&ltc, special_vec(r));
      EXPECT(finite3(albedo));
      for (e = 0; e < DIRECTION_COUNT; e++) expect_density(sphera_ltc_eval(&ltc, directions[e]));
      calls += DIRECTION_COUNT + 1;
    }
  }
  EXPECT(!sphera_ltc_prepare(NULL, vec3(0, 0, 1), 0.5f));
  EXPECT(sphera_ltc_eval(NULL, vec3(0, 0, 1)) == 0.0f);
  {
    SpheraVec3 zero = sphera_ltc_specular_albedo(NULL, vec3(1, 1, 1));
    EXPECT(zero.x == 0.0f && zero.y == 0.0f && zero.z == 0.0f);
  }
}

/* ---- sphere lights: caps, pivot, phase ---------------------------------------------- */

static int cap_is_valid(SpheraCap c) {
  return finite3(c.axis) && unit3(c.axis) && c.one_minus_cos >= 0.0f && c.one_minus_cos <= 2.0f &&
         c.one_plus_cos >= 0.0f && c.one_plus_cos <= 2.0f && c.sin2 >= 0.0f && c.sin2 <= 1.0f;
}

/* A sphere prepared for solid angle sampling: a prepared value that held garbage, the
 * empty value on failure, samples with their pdf bit for bit. */
static void check_solid_angle_sphere(const SpheraSolidAngleSphere *sphere, int ok, int full) {
  float omega = sphera_solid_angle_sphere_solid_angle(sphere);
  int k, d;
  calls++;
  expect_words_not_nan(sphere, sizeof *sphere);
  EXPECT(isfinite(omega) && omega >= 0.0f && omega <= 12.566371f * 1.000001f);
  if (!ok) EXPECT(omega == 0.0f);
  for (d = 0; d < DIRECTION_COUNT; d++) {
    float p = sphera_solid_angle_sphere_pdf(sphere, directions[d]);
    calls++;
    expect_density(p);
    if (!ok || !finite3(directions[d])) EXPECT(p == 0.0f);
  }
  for (k = 0; k < pair_count(full); k++) {
    float u0, u1;
    SpheraSample s;
    pair(k, full, &u0, &u1);
    s = sphera_solid_angle_sphere_sample(sphere, u0, u1);
    calls++;
    expect_sample(s);
    if (!ok) EXPECT(is_no_sample(s));
    if (s.pdf > 0.0f) EXPECT(sphera_solid_angle_sphere_pdf(sphere, s.dir) == s.pdf);
  }
}

static void check_solid_angle_sphere_of_cap(SpheraCap cap, int full) {
  SpheraSolidAngleSphere sphere;
  int ok;
  memset(&sphere, 0xff, sizeof sphere);
  ok = sphera_solid_angle_sphere_prepare_cap(&sphere, cap);
  calls++;
  check_solid_angle_sphere(&sphere, ok, full);
}

static void check_cap(SpheraCap cap, int full) {
  float omega = sphera_cap_solid_angle(cap);
  int k, d;
  calls++;
  EXPECT(isfinite(omega) && omega >= 0.0f && omega <= 12.566371f * 1.000001f);
  for (d = 0; d < DIRECTION_COUNT; d++) {
    float p = sphera_cap_pdf(cap, directions[d]);
    (void)sphera_cap_contains(cap, directions[d]);
    calls += 2;
    expect_density(p);
    if (!finite3(directions[d])) EXPECT(p == 0.0f);
  }
  for (k = 0; k < pair_count(full); k++) {
    float u0, u1;
    SpheraSample s;
    pair(k, full, &u0, &u1);
    s = sphera_cap_sample_uniform(cap, u0, u1);
    calls++;
    expect_sample(s);
    if (omega == 0.0f) EXPECT(is_no_sample(s));
  }
  check_solid_angle_sphere_of_cap(cap, full);
}

static void sphere_suite(void) {
  int k, j, d;
  SpheraCap caps[64];
  int cap_count = 0;
  /* Null pointers of the prepared sphere. */
  EXPECT(!sphera_solid_angle_sphere_prepare(NULL, vec3(0.0f, 0.0f, 3.0f), 1.0f));
  EXPECT(!sphera_solid_angle_sphere_prepare_cap(NULL, sphera_cap_from_axis_cos(vec3(0, 0, 1), 0.5f)));
  EXPECT(is_no_sample(sphera_solid_angle_sphere_sample(NULL, 0.5f, 0.5f)));
  EXPECT(sphera_solid_angle_sphere_pdf(NULL, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  EXPECT(sphera_solid_angle_sphere_solid_angle(NULL) == 0.0f);
  calls += 5;
  /* Hard cases: tiny (1e-7 sr), on and inside the sphere, distant, whole sphere. */
  caps[cap_count++] = sphera_cap_from_sphere(vec3(0.0f, 0.0f, 1e3f), 0.178f); /* ~1e-7 sr */
  caps[cap_count++] = sphera_cap_from_sphere(vec3(0.0f, 0.0f, 1.0f), 1.0f);   /* on it */
  caps[cap_count++] = sphera_cap_from_sphere(vec3(0.1f, 0.0f, 0.0f), 1.0f);   /* inside */
  caps[cap_count++] = sphera_cap_from_sphere(vec3(1e30f, 0.0f, 0.0f), 1.0f);  /* distant */
  caps[cap_count++] = sphera_cap_from_axis_cos(vec3(0, 0, 1), -1.0f);        /* whole */
  caps[cap_count++] = sphera_cap_from_axis_cos(vec3(0, 0, 1), 1.0f);         /* empty */
  caps[cap_count++] = sphera_cap_from_axis_cos(vec3(1, 1, 1), 0.0f);         /* hemisphere */
  caps[cap_count++] = sphera_cap_from_axis_cos(vec3(0, 1, 0), nextafterf(1.0f, 0.0f));
  for (k = 0; k < cap_count; k++) {
    EXPECT(cap_is_valid(caps[k]));
    check_cap(caps[k], 1);
  }
  /* Constructors with special arguments. */
  for (k = 0; k < SPECIAL_COUNT * 20; k++) {
    SpheraVec3 v = special_vec(k);
    float x = specials[(k * 7) % SPECIAL_COUNT];
    SpheraCap a = sphera_cap_from_sphere(v, x);
    SpheraCap b = sphera_cap_from_axis_cos(v, x);
    SpheraCap hand;
    SpheraSolidAngleSphere sphere;
    int ok;
    memset(&sphere, 0xff, sizeof sphere);
    ok = sphera_solid_angle_sphere_prepare(&sphere, v, x);
    calls += 3;
    check_solid_angle_sphere(&sphere, ok, 0);
    if (!daz_mode && (!finite3(v) || !(x > 0.0f) || !isfinite(x))) EXPECT(!ok);
    EXPECT(cap_is_valid(a));
    EXPECT(cap_is_valid(b));
    if (!daz_mode && (!finite3(v) || !(x > 0.0f) || !isfinite(x))) {
      if (sphera_cap_solid_angle(a) != 0.0f)
        printf("    center (%g, %g, %g) radius %g\n", v.x, v.y, v.z, x);
      EXPECT(sphera_cap_solid_angle(a) == 0.0f);
    }
    check_cap(a, 0);
    check_cap(b, 0);
    /* A cap built by hand, any fields. */
    hand.axis = v;
    hand.one_minus_cos = x;
    hand.one_plus_cos = specials[(k * 3) % SPECIAL_COUNT];
    hand.sin2 = specials[(k * 5) % SPECIAL_COUNT];
    check_cap(hand, 0);
    if (cap_count < 64) caps[cap_count++] = hand;
  }
  /* Intersections of all pairs. */
  for (k = 0; k < cap_count; k++) {
    for (j = 0; j < cap_count; j++) {
      float exact = sphera_cap_intersection_solid_angle(caps[k], caps[j]);
      float approximate = sphera_cap_intersection_solid_angle_oat_sander(caps[k], caps[j]);
      float smaller = fminf(sphera_cap_solid_angle(caps[k]), sphera_cap_solid_angle(caps[j]));
      calls += 2;
      expect_density(exact);
      expect_density(approximate);
      EXPECT(exact <= smaller * 1.0001f + 1e-6f);
    }
  }
  /* Unions of all pairs: a failed prepare writes a union without samples; every sample
   * is finite, inside the union and has pdf(dir) == pdf bit for bit. */
  for (k = 0; k < cap_count; k++) {
    for (j = 0; j < cap_count; j++) {
      SpheraCapUnion u;
      int ok;
      float omega;
      memset(&u, 0xff, sizeof u);
      ok = sphera_cap_union_prepare(&u, caps[k], caps[j]);
      omega = sphera_cap_union_solid_angle(&u);
      calls += 2;
      expect_words_not_nan(&u, sizeof u);
      EXPECT(isfinite(omega) && omega >= 0.0f && omega <= 12.566371f * 1.0001f);
      if (!ok) EXPECT(omega == 0.0f);
      for (d = 0; d < DIRECTION_COUNT; d++) {
        expect_density(sphera_cap_union_pdf(&u, directions[d]));
        calls++;
      }
      for (d = 0; d < pair_count(0); d++) {
        float u0, u1, p;
        SpheraSample s;
        pair(d, 0, &u0, &u1);
        s = sphera_cap_union_sample(&u, u0, u1);
        calls++;
        expect_sample(s);
        if (!ok) EXPECT(is_no_sample(s));
        if (s.pdf > 0.0f) {
          p = sphera_cap_union_pdf(&u, s.dir);
          calls++;
          EXPECT(memcmp(&p, &s.pdf, sizeof p) == 0);
        }
      }
    }
  }
  EXPECT(!sphera_cap_union_prepare(NULL, caps[0], caps[1]));
  EXPECT(is_no_sample(sphera_cap_union_sample(NULL, 0.5f, 0.5f)));
  EXPECT(sphera_cap_union_pdf(NULL, directions[0]) == 0.0f);
  EXPECT(sphera_cap_union_solid_angle(NULL) == 0.0f);
  calls += 4;
  /* Pivots of norm 0, 1 - ulp, 1, 2, NaN, inf, denormal, in every direction. */
  {
    float norms[8] = {0.0f, 0.0f, 1.0f, 2.0f, 0.0f, 0.0f, 1e-45f, 0.5f};
    norms[1] = nextafterf(1.0f, 0.0f);
    norms[4] = NAN;
    norms[5] = INFINITY;
    for (k = 0; k < 8; k++) {
      for (d = 0; d < DIRECTION_COUNT; d++) {
        SpheraVec3 axis = directions[(d + 1) % DIRECTION_COUNT];
        SpheraVec3 pivot = vec3(axis.x * norms[k], axis.y * norms[k], axis.z * norms[k]);
        for (j = 0; j < DIRECTION_COUNT; j++) {
          SpheraVec3 g = sphera_pivot_transform(directions[j], pivot);
          float jacobian = sphera_pivot_jacobian(directions[j], pivot);
          calls += 2;
          EXPECT(finite3(g) && fabs(sqrt((double)g.x * g.x + (double)g.y * g.y +
                                        (double)g.z * g.z) - 1.0) < 1e-4);
          expect_density(jacobian);
          if (!finite3(directions[j])) EXPECT(vec3_equal(g, vec3(0, 0, 1)) && jacobian == 0.0f);
        }
        for (j = 0; j < cap_count; j++) {
          SpheraCap image = sphera_pivot_transform_cap(caps[j], pivot);
          calls++;
          EXPECT(cap_is_valid(image));
        }
      }
    }
  }
  /* Phase functions. */
  for (k = 0; k < SPECIAL_COUNT; k++) {
    float g = specials[k];
    float fitted = sphera_phase_pivot_from_henyey_greenstein(g);
    float mean = sphera_phase_pivot_mean_cosine(g);
    calls += 2;
    EXPECT(isfinite(fitted) && fabsf(fitted) <= 1.0f);
    EXPECT(isfinite(mean) && fabsf(mean) <= 1.0f);
    for (j = 0; j < SPECIAL_COUNT; j++) {
      expect_density(sphera_phase_pivot(specials[j], g));
      expect_density(sphera_phase_henyey_greenstein(specials[j], g));
      calls += 2;
    }
    for (d = 0; d < DIRECTION_COUNT; d++) {
      for (j = 0; j < pair_count(0); j++) {
        float u0, u1;
        SpheraSample a, b;
        pair(j, 0, &u0, &u1);
        a = sphera_phase_pivot_sample(directions[d], g, u0, u1);
        b = sphera_phase_henyey_greenstein_sample(directions[d], g, u0, u1);
        calls += 2;
        expect_sample(a);
        expect_sample(b);
        if (!finite3(directions[d]) || (directions[d].x == 0.0f && directions[d].y == 0.0f &&
                                        directions[d].z == 0.0f))
          EXPECT(is_no_sample(a) && is_no_sample(b));
      }
    }
  }
}


/* ---- SPTDs, the GGX pivot table, real-time sphere shading, the light sampler -------- */

static SpheraCap hard_caps[10];
static int hard_cap_count = 0;
static void fill_hard_caps(void) {
  hard_cap_count = 0;
  hard_caps[hard_cap_count++] = sphera_cap_from_sphere(vec3(0.0f, 0.0f, 1e3f), 0.178f);
  hard_caps[hard_cap_count++] = sphera_cap_from_sphere(vec3(0.0f, 0.0f, 1.0f), 1.0f);
  hard_caps[hard_cap_count++] = sphera_cap_from_sphere(vec3(0.1f, 0.0f, 0.0f), 1.0f);
  hard_caps[hard_cap_count++] = sphera_cap_from_sphere(vec3(0.3f, -0.2f, 2.0f), 0.5f);
  hard_caps[hard_cap_count++] = sphera_cap_from_sphere(vec3(2.0f, 0.0f, -0.3f), 0.5f); /* behind */
  hard_caps[hard_cap_count++] = sphera_cap_from_axis_cos(vec3(0, 0, 1), -1.0f);       /* whole */
  hard_caps[hard_cap_count++] = sphera_cap_from_axis_cos(vec3(0, 0, 1), 1.0f);        /* empty */
  hard_caps[hard_cap_count++] = sphera_cap_from_axis_cos(vec3(1, 1, 1), 0.0f);        /* half */
  hard_caps[hard_cap_count++] = sphera_cap_from_axis_cos(vec3(0, 1, 0), nextafterf(1.0f, 0.0f));
  hard_caps[hard_cap_count].axis = vec3(NAN, 0.0f, 1.0f); /* by hand, broken */
  hard_caps[hard_cap_count].one_minus_cos = INFINITY;
  hard_caps[hard_cap_count].one_plus_cos = NAN;
  hard_caps[hard_cap_count].sin2 = -1.0f;
  hard_cap_count++;
}

/* A prepared sampler: pdf finite, non-negative and 0 after a failed prepare or for a
 * non-finite direction; samples valid, none after a failed prepare, and each with the
 * pdf that PDF gives its direction, bit for bit (the contract of the SPTD and light
 * samplers). */
#define CHECK_SAMPLES(VALUE, OK, SAMPLE, PDF)                                              \
  do {                                                                                     \
    int d_, k_;                                                                            \
    for (d_ = 0; d_ < DIRECTION_COUNT; d_++) {                                             \
      float p_ = PDF((VALUE), directions[d_]);                                             \
      calls++;                                                                             \
      expect_density(p_);                                                                  \
      if (!(OK) || !finite3(directions[d_])) EXPECT(p_ == 0.0f);                           \
    }                                                                                      \
    for (k_ = 0; k_ < pair_count(0); k_++) {                                               \
      float u0_, u1_;                                                                      \
      SpheraSample sample_;                                                                \
      pair(k_, 0, &u0_, &u1_);                                                             \
      sample_ = SAMPLE((VALUE), u0_, u1_);                                                 \
      calls++;                                                                             \
      expect_sample(sample_);                                                              \
      if (!(OK)) EXPECT(is_no_sample(sample_));                                            \
      if (sample_.pdf > 0.0f) {                                                            \
        float p_ = PDF((VALUE), sample_.dir);                                              \
        calls++;                                                                           \
        EXPECT(memcmp(&p_, &sample_.pdf, sizeof p_) == 0);                                 \
      }                                                                                    \
    }                                                                                      \
  } while (0)

/* A prepared SPTD in a cap: finite, the empty sampler after a failed prepare, integral
 * in [0, 1], and the samples' checks. */
static void check_sptd_in_cap(const SpheraSptdInCap *s, int ok) {
  float integral = sphera_sptd_in_cap_integral(s);
  calls++;
  expect_words_not_nan(s, sizeof *s);
  EXPECT(isfinite(integral) && integral >= 0.0f && integral <= 1.00001f);
  if (!ok) EXPECT(integral == 0.0f);
  CHECK_SAMPLES(s, ok, sphera_sptd_in_cap_sample, sphera_sptd_in_cap_pdf);
}

static void sptd_suite(void) {
  const uint32_t bases[4] = {SPHERA_SPTD_UNIFORM, SPHERA_SPTD_CLAMPED_COSINE, 2u, UINT32_MAX};
  float norms[8] = {0.0f, 0.0f, 1.0f, 2.0f, 0.0f, 0.0f, 1e-45f, 0.5f};
  SpheraVec3 pivots[8 * DIRECTION_COUNT + 24];
  int pivot_count = 0, k, j, b, c, d;
  norms[1] = nextafterf(1.0f, 0.0f);
  norms[4] = NAN;
  norms[5] = INFINITY;
  fill_hard_caps();
  for (k = 0; k < 8; k++)
    for (d = 0; d < DIRECTION_COUNT; d++) {
      SpheraVec3 a = directions[(d + 1) % DIRECTION_COUNT];
      pivots[pivot_count++] = vec3(a.x * norms[k], a.y * norms[k], a.z * norms[k]);
    }
  for (k = 0; k < 24; k++) pivots[pivot_count++] = special_vec(k * 5);

  /* Null pointers. */
  EXPECT(!sphera_sptd_in_cap_prepare(NULL, pivots[0], 0, directions[0], hard_caps[0]));
  EXPECT(!sphera_sptd_in_cap_prepare_pivot_phase(NULL, directions[0], 0.5f, hard_caps[0]));
  EXPECT(sphera_sptd_in_cap_integral(NULL) == 0.0f);
  EXPECT(sphera_sptd_in_cap_pdf(NULL, directions[0]) == 0.0f);
  EXPECT(is_no_sample(sphera_sptd_in_cap_sample(NULL, 0.5f, 0.5f)));
  EXPECT(!sphera_ggx_pivot_from_view(NULL, directions[1], 0.5f));
  EXPECT(!sphera_sphere_light_shading_prepare(NULL, directions[1], 0.5f, vec3(1, 1, 1)));
  EXPECT(!sphera_sphere_light_shading_prepare_occluded(NULL, directions[1], 0.5f, vec3(1, 1, 1), hard_caps[7]));
  EXPECT(vec3_equal(sphera_sphere_light_shading_eval(NULL, hard_caps[3]), vec3(0, 0, 0)));
  EXPECT(vec3_equal(sphera_sphere_light_shading_eval_occluded(NULL, hard_caps[3], hard_caps[7]),
                    vec3(0, 0, 0)));
  EXPECT(vec3_equal(sphera_sphere_light_shading_eval_occluded_separable(NULL, hard_caps[3], hard_caps[7]),
                    vec3(0, 0, 0)));
  EXPECT(!sphera_sphere_light_sampler_prepare(NULL, vec3(0, 0, 2), 0.5f, directions[1], 0.5f));
  EXPECT(!sphera_sphere_light_sampler_prepare_with_fit(NULL, vec3(0, 0, 2), 0.5f, NULL));
  EXPECT(is_no_sample(sphera_sphere_light_sampler_sample(NULL, 0.5f, 0.5f)));
  EXPECT(sphera_sphere_light_sampler_pdf(NULL, directions[0]) == 0.0f);
  EXPECT(!sphera_sphere_light_sampler_uses_sptd(NULL));
  calls += 13;

  /* SPTDs: every pivot, base and cosine axis. */
  for (k = 0; k < pivot_count; k++) {
    for (b = 0; b < 4; b++) {
      for (j = 0; j < 3; j++) {
        SpheraVec3 axis = directions[(k + 5 * j) % DIRECTION_COUNT];
        for (d = 0; d < DIRECTION_COUNT; d++) {
          float e = sphera_sptd_eval(pivots[k], bases[b], axis, directions[d]);
          calls++;
          expect_density(e);
          if (!finite3(directions[d]) || b >= 2) EXPECT(e == 0.0f);
        }
        for (d = 0; d < pair_count(0); d++) {
          float u0, u1;
          SpheraSample s;
          pair(d, 0, &u0, &u1);
          s = sphera_sptd_sample(pivots[k], bases[b], axis, u0, u1);
          calls++;
          expect_sample(s);
          if (b >= 2) EXPECT(is_no_sample(s)); /* an unknown base draws nothing */
          if (s.pdf > 0.0f) {
            float e = sphera_sptd_eval(pivots[k], bases[b], axis, s.dir);
            calls++;
            EXPECT(memcmp(&e, &s.pdf, sizeof e) == 0);
          }
        }
        for (c = 0; c < hard_cap_count; c++) {
          SpheraSptdInCap in_cap;
          int ok;
          float whole = sphera_sptd_integral_over_cap(pivots[k], bases[b], axis, hard_caps[c]);
          float both = sphera_sptd_integral_over_cap_intersection(
              pivots[k], bases[b], axis, hard_caps[c], hard_caps[(c + 3) % hard_cap_count]);
          float either = sphera_sptd_integral_over_cap_union(
              pivots[k], bases[b], axis, hard_caps[c], hard_caps[(c + 3) % hard_cap_count]);
          float outside = sphera_sptd_integral_over_cap_complement(pivots[k], bases[b], axis,
                                                                   hard_caps[c]);
          calls += 4;
          EXPECT(isfinite(whole) && whole >= 0.0f && whole <= 1.00001f);
          EXPECT(isfinite(both) && both >= 0.0f && both <= 1.00001f);
          EXPECT(isfinite(either) && either >= 0.0f && either <= 1.00001f);
          EXPECT(isfinite(outside) && outside >= 0.0f && outside <= 1.00001f);
          if (b >= 2) EXPECT(whole == 0.0f && both == 0.0f && either == 0.0f && outside == 0.0f);
          memset(&in_cap, 0xff, sizeof in_cap);
          ok = sphera_sptd_in_cap_prepare(&in_cap, pivots[k], bases[b], axis, hard_caps[c]);
          calls++;
          if (b >= 2) EXPECT(!ok);
          if (j == 0) check_sptd_in_cap(&in_cap, ok);
        }
      }
    }
  }

  /* The pivot phase function in a cap, the pivot table, real-time shading and the
   * light sampler, over special views, parameters and caps. */
  for (k = 0; k < SPECIAL_COUNT + DIRECTION_COUNT; k++) {
    SpheraVec3 wo = k < DIRECTION_COUNT ? directions[k] : special_vec(k * 3);
    for (j = 0; j < SPECIAL_COUNT; j++) {
      float x = specials[j];
      SpheraSptdInCap phase;
      SpheraGgxPivot fit;
      SpheraSphereLightShading shading;
      SpheraSphereLightSampler sampler;
      SpheraVec3 f0 = special_vec(j + k);
      int ok, c2;
      for (c = 0; c < hard_cap_count; c += 3) {
        memset(&phase, 0xff, sizeof phase);
        ok = sphera_sptd_in_cap_prepare_pivot_phase(&phase, wo, x, hard_caps[c]);
        calls++;
        check_sptd_in_cap(&phase, ok);
      }
      memset(&fit, 0xff, sizeof fit);
      ok = sphera_ggx_pivot_from_view(&fit, wo, x);
      calls++;
      expect_words_finite(&fit, sizeof fit);
      if (ok) EXPECT(fit.albedo >= 0.0f && fit.albedo <= 1.00001f &&
                     fit.pivot.x * fit.pivot.x + fit.pivot.y * fit.pivot.y +
                             fit.pivot.z * fit.pivot.z < 1.0f);
      if (!finite3(wo) || !(wo.z > 0.0f)) EXPECT(!ok);

      memset(&shading, 0xff, sizeof shading);
      ok = sphera_sphere_light_shading_prepare(&shading, wo, x, f0);
      calls++;
      expect_words_finite(&shading, sizeof shading);
      if (!finite3(wo) || !(wo.z > 0.0f)) EXPECT(!ok);
      for (c = 0; c < hard_cap_count; c++) {
        for (c2 = 0; c2 < hard_cap_count; c2 += 2) {
          SpheraVec3 v = c2 == 0 ? sphera_sphere_light_shading_eval(&shading, hard_caps[c])
                                 : sphera_sphere_light_shading_eval_occluded(&shading, hard_caps[c],
                                                                      hard_caps[c2]);
          SpheraVec3 w = sphera_sphere_light_shading_eval_occluded_separable(&shading, hard_caps[c],
                                                                      hard_caps[c2]);
          EXPECT(finite3(w) && w.x >= 0.0f && w.y >= 0.0f && w.z >= 0.0f && w.x <= 1.00001f &&
                 w.y <= 1.00001f && w.z <= 1.00001f);
          if (!ok) EXPECT(vec3_equal(w, vec3(0, 0, 0)));
          calls++;
          EXPECT(finite3(v) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f && v.x <= 1.00001f &&
                 v.y <= 1.00001f && v.z <= 1.00001f);
          if (!ok) EXPECT(vec3_equal(v, vec3(0, 0, 0)));
        }
      }
      for (c2 = 0; c2 < hard_cap_count; c2 += 2) {
        SpheraSphereLightShading occluded;
        bool ok_occluded;
        memset(&occluded, 0xff, sizeof occluded);
        ok_occluded = sphera_sphere_light_shading_prepare_occluded(&occluded, wo, x, f0, hard_caps[c2]);
        calls++;
        expect_words_finite(&occluded, sizeof occluded);
        EXPECT(ok_occluded == ok);
        for (c = 0; c < hard_cap_count; c++) {
          SpheraVec3 v = sphera_sphere_light_shading_eval(&occluded, hard_caps[c]);
          calls++;
          EXPECT(vec3_equal(v, sphera_sphere_light_shading_eval_occluded(&shading, hard_caps[c], hard_caps[c2])));
        }
      }

      for (c = 0; c < 4; c++) {
        SpheraVec3 center = c == 0 ? vec3(0.3f, -0.2f, 2.0f)
                            : c == 1 ? special_vec(j * 7 + k)
                            : c == 2 ? vec3(0.0f, 0.0f, 0.1f) /* inside the sphere */
                                     : vec3(3.0f, 0.0f, -1.0f); /* behind */
        float radius = c == 1 ? 0.5f : x;
        memset(&sampler, 0xff, sizeof sampler);
        ok = sphera_sphere_light_sampler_prepare(&sampler, center, radius, wo,
                                                 specials[(j + 5) % SPECIAL_COUNT]);
        calls += 2;
        expect_words_not_nan(&sampler, sizeof sampler);
        (void)sphera_sphere_light_sampler_uses_sptd(&sampler);
        if (!finite3(center) || !(radius > 0.0f) || !isfinite(radius)) EXPECT(!ok);
        CHECK_SAMPLES(&sampler, ok, sphera_sphere_light_sampler_sample,
                      sphera_sphere_light_sampler_pdf);
        {
          /* From a fit of this view (any pivot, even garbage): no NaN, the contract. */
          SpheraGgxPivot fit;
          SpheraSphereLightSampler from_fit;
          bool has_fit = sphera_ggx_pivot_from_view(&fit, wo, specials[(j + 5) % SPECIAL_COUNT]);
          if (!has_fit) fit.pivot = special_vec(j + 3 * k);
          memset(&from_fit, 0xff, sizeof from_fit);
          ok = sphera_sphere_light_sampler_prepare_with_fit(&from_fit, center, radius, &fit);
          calls += 2;
          expect_words_not_nan(&from_fit, sizeof from_fit);
          if (has_fit) EXPECT(memcmp(&from_fit, &sampler, sizeof sampler) == 0);
          if (!finite3(center) || !(radius > 0.0f) || !isfinite(radius)) EXPECT(!ok);
          CHECK_SAMPLES(&from_fit, ok, sphera_sphere_light_sampler_sample,
                        sphera_sphere_light_sampler_pdf);
        }
      }
    }
  }
}

/* ---- SGs, ASGs, VSGLs ---------------------------------------------------------------- */

static int sg_is_valid(SpheraSg g) {
  return finite3(g.axis) && isfinite(g.sharpness) && g.sharpness >= 0.0f &&
         g.sharpness <= (float)SPHERA_SG_MAX_SHARPNESS && isfinite(g.log_amplitude);
}

static int vsgl_is_finite(SpheraVsgl v) {
  return sg_is_valid(v.diffuse) && sg_is_valid(v.specular) && finite3(v.diffuse_power) &&
         finite3(v.specular_power) && finite3(v.mean) && isfinite(v.variance) &&
         v.variance >= 0.0f && v.diffuse_power.x >= 0.0f && v.diffuse_power.y >= 0.0f &&
         v.diffuse_power.z >= 0.0f && v.specular_power.x >= 0.0f &&
         v.specular_power.y >= 0.0f && v.specular_power.z >= 0.0f;
}

static int vsgl_is_empty(SpheraVsgl v) {
  return vec3_equal(v.diffuse_power, vec3(0, 0, 0)) && vec3_equal(v.specular_power, vec3(0, 0, 0));
}

#define SG_COUNT 96
static SpheraSg sgs[SG_COUNT];
static void fill_sgs(void) {
  int k;
  for (k = 0; k < SG_COUNT; k++) {
    SpheraVec3 axis = k % 2 ? directions[k % DIRECTION_COUNT] : special_vec(k);
    if (k < 64) {
      sgs[k] = sphera_sg_new(axis, specials[k % SPECIAL_COUNT], specials[(k * 7 + 3) % SPECIAL_COUNT]);
    } else {
      /* By hand: any fields. */
      sgs[k].axis = axis;
      sgs[k].sharpness = specials[k % SPECIAL_COUNT];
      sgs[k].log_amplitude = specials[(k * 5) % SPECIAL_COUNT];
    }
  }
}

static void sg_suite(void) {
  int k, j, d;
  fill_sgs();
  for (k = 0; k < SG_COUNT; k++) {
    SpheraSg g = sgs[k];
    if (k < 64) EXPECT(sg_is_valid(g));
    EXPECT(isfinite(sphera_sg_integral(specials[k % SPECIAL_COUNT])) &&
           sphera_sg_integral(specials[k % SPECIAL_COUNT]) >= 0.0f);
    calls += 2;
    for (d = 0; d < DIRECTION_COUNT; d++) {
      float e = sphera_sg_eval(g, directions[d]);
      float p = sphera_vmf_pdf(g, directions[d]);
      float u[2] = {-1.0f, -1.0f};
      int inverted = sphera_vmf_invert(g, directions[d], u);
      calls += 3;
      expect_density(e);
      expect_density(p);
      if (inverted)
        EXPECT(u[0] >= 0.0f && u[0] <= 1.0f && u[1] >= 0.0f && u[1] <= 1.0f);
      else
        EXPECT(u[0] == -1.0f && u[1] == -1.0f); /* writes nothing */
      if (!finite3(directions[d])) EXPECT(!inverted);
      EXPECT(!sphera_vmf_invert(g, directions[d], NULL));
      calls++;
    }
    for (d = 0; d < pair_count(0); d++) {
      float u0, u1;
      SpheraSample s;
      pair(d, 0, &u0, &u1);
      s = sphera_vmf_sample(g, u0, u1);
      calls++;
      expect_sample(s);
    }
    for (j = 0; j < SG_COUNT; j += 3) {
      SpheraSg product = sphera_sg_product(g, sgs[j]);
      float inner = sphera_sg_inner_product(g, sgs[j]);
      calls += 2;
      EXPECT(sg_is_valid(product));
      expect_density(inner);
    }
    for (j = 0; j < SPECIAL_COUNT; j++) {
      SpheraVec3 normal = j < DIRECTION_COUNT ? directions[j] : special_vec(j + k);
      SpheraVec3 view = directions[(j + k) % DIRECTION_COUNT];
      float x = specials[(j * 3 + k) % SPECIAL_COUNT];
      float vis = specials[(j + 2 * k) % SPECIAL_COUNT];
      SpheraSg incoming = sphera_sg_incoming_radiance(g, special_vec(j * 11 + k), x);
      SpheraSg lobe = sphera_sg_from_lambert(normal);
      SpheraSg specular = sphera_sg_from_ggx(normal, view, x);
      SpheraSg unnormalized = sphera_sg_from_ggx_unnormalized(normal, view, x);
      SpheraAsg asg = sphera_asg_from_ggx(normal, view, x);
      SpheraSg beckmann = sphera_sg_from_beckmann(normal, view, x);
      SpheraSg beckmann_unnormalized = sphera_sg_from_beckmann_unnormalized(normal, view, x);
      SpheraAsg beckmann_asg = sphera_asg_from_beckmann(normal, view, x);
      SpheraAsg hand = sphera_asg_new(view, normal, x, vis, specials[(j + 9) % SPECIAL_COUNT]);
      calls += 6;
      EXPECT(sg_is_valid(incoming) && sg_is_valid(lobe) && sg_is_valid(specular) &&
             sg_is_valid(unnormalized));
      expect_words_finite(&asg, sizeof asg);
      expect_words_finite(&hand, sizeof hand);
      expect_density(sphera_sg_diffuse_shading_product(g, normal, x, vis));
      expect_density(sphera_sg_diffuse_shading_constant_cosine(g, normal, x, vis));
      expect_density(sphera_sg_diffuse_shading_sharp_lobe(g, normal, x, vis));
      expect_density(sphera_sg_specular_shading(g, normal, view, x, vis, 1.0f));
      expect_density(sphera_sg_specular_shading_sg(g, normal, view, x, 0.04f, vis));
      {
        /* The prepared shading point: the free functions' bits where prepared, zeros
         * otherwise and for null. */
        SpheraSgShadingPoint point;
        SpheraSgShading shaded;
        bool prepared;
        memset(&point, 0xff, sizeof point);
        prepared = sphera_sg_shading_point_prepare(&point, normal, view, x, vis);
        expect_words_finite(&point, sizeof point);
        shaded = sphera_sg_shading_point_shade(&point, g, x, 1.0f);
        calls += 2;
        expect_density(shaded.diffuse);
        expect_density(shaded.specular);
        if (prepared) {
          float diffuse = sphera_sg_diffuse_shading_constant_cosine(g, normal, x, 1.0f);
          float specular = sphera_sg_specular_shading(g, normal, view, x, vis, 1.0f);
          EXPECT(memcmp(&shaded.diffuse, &diffuse, sizeof diffuse) == 0);
          EXPECT(memcmp(&shaded.specular, &specular, sizeof specular) == 0);
        } else {
          EXPECT(shaded.diffuse == 0.0f && shaded.specular == 0.0f);
        }
        if (!finite3(normal) || !finite3(view)) EXPECT(!prepared);
        EXPECT(!sphera_sg_shading_point_prepare(NULL, normal, view, x, vis));
        shaded = sphera_sg_shading_point_shade(NULL, g, x, vis);
        EXPECT(shaded.diffuse == 0.0f && shaded.specular == 0.0f);
      }
      EXPECT(sg_is_valid(beckmann) && sg_is_valid(beckmann_unnormalized));
      expect_words_finite(&beckmann_asg, sizeof beckmann_asg);
      expect_density(sphera_sg_beckmann_specular_shading(g, normal, view, x, vis, 1.0f));
      expect_density(sphera_sg_beckmann_specular_shading_sg(g, normal, view, x, 0.04f, vis));
      expect_density(sphera_asg_convolve_sg(beckmann_asg, g));
      calls += 6;
      expect_density(sphera_asg_eval(asg, directions[(j + 3) % DIRECTION_COUNT]));
      expect_density(sphera_asg_eval(hand, directions[(j + 5) % DIRECTION_COUNT]));
      expect_density(sphera_asg_integral(asg));
      expect_density(sphera_asg_integral(hand));
      expect_density(sphera_asg_convolve_sg(asg, g));
      expect_density(sphera_asg_convolve_sg(hand, incoming));
      calls += 11;
    }
  }
}

static SpheraVpl special_vpl(int k) {
  SpheraVpl v;
  v.position = k % 4 ? vec3(0.1f * (float)(k % 7), 1.0f, -0.2f * (float)(k % 3)) : special_vec(k);
  v.normal = k % 3 ? directions[k % DIRECTION_COUNT] : special_vec(k + 1);
  v.power = k % 5 ? vec3(1.0f, 0.5f, 0.25f) : special_vec(k + 2);
  v.diffuse_reflectance = k % 2 ? vec3(0.5f, 0.5f, 0.5f) : special_vec(k + 3);
  v.specular_reflectance = k % 6 ? vec3(0.04f, 0.04f, 0.04f) : special_vec(k + 4);
  v.toward_incoming = k % 7 ? directions[(k + 1) % DIRECTION_COUNT] : special_vec(k + 5);
  v.roughness = specials[k % SPECIAL_COUNT];
  return v;
}

#define PYRAMID_SIZE 4
#define PYRAMID_TEXELS 21 /* (4 · 16 − 1) / 3 */

static void vsgl_suite(void) {
  int k, j;
  SpheraVsglAccumulator acc, other;
  SpheraVsglTexel texel, pyramid[PYRAMID_TEXELS];
  SpheraVsgl v;
  SpheraVec3 origin = vec3(0.0f, 0.0f, 0.0f);
  const uint32_t sizes[6] = {0u, 1u, 3u, 4u, 16384u, UINT32_MAX};
  const uint32_t clusters[5] = {0u, 1u, 2u, 9u, UINT32_MAX};

  /* Null pointers. */
  EXPECT(!sphera_vsgl_accumulator_new(NULL, origin));
  EXPECT(!sphera_vsgl_accumulator_add_vpl(NULL, NULL));
  EXPECT(!sphera_vsgl_accumulator_add_texel(NULL, NULL));
  EXPECT(!sphera_vsgl_accumulator_merge(NULL, NULL));
  EXPECT(!sphera_vsgl_texel_from_vpl(NULL, origin, NULL));
  EXPECT(vsgl_is_empty(sphera_vsgl_accumulator_finish(NULL)));
  EXPECT(vsgl_is_empty(sphera_vsgl_fis_select(NULL, 21, 4, origin, 4, 1.0f, 8, 0.5f, 0.5f)));
  calls += 7;
  for (k = 0; k < 6; k++) {
    size_t n = sphera_vsgl_pyramid_texel_count(sizes[k]);
    calls++;
    EXPECT(n == (sizes[k] == 1 ? 1u : sizes[k] == 4 ? 21u : sizes[k] == 16384u ? 357913941u : 0u));
  }

  /* Accumulators fed special VPLs and texels, one by one and merged. */
  for (k = 0; k < 160; k++) {
    SpheraVpl vpl = special_vpl(k);
    SpheraVec3 o = k % 8 ? origin : special_vec(k);
    int ok = sphera_vsgl_accumulator_new(&acc, o);
    calls++;
    /* The contract: a non-finite origin counts as the world origin. */
    EXPECT(ok && finite3(acc.origin));
    if (!finite3(o)) EXPECT(vec3_equal(acc.origin, origin));
    for (j = 0; j < 9; j++) {
      SpheraVpl w = special_vpl(k + j * 13);
      (void)sphera_vsgl_accumulator_add_vpl(&acc, &w);
      calls++;
    }
    memset(&texel, 0xff, sizeof texel);
    ok = sphera_vsgl_texel_from_vpl(&vpl, o, &texel);
    calls++;
    expect_words_finite(&texel, sizeof texel);
    (void)sphera_vsgl_accumulator_add_texel(&acc, &texel);
    calls++;
    expect_words_finite(&acc, sizeof acc);
    v = sphera_vsgl_accumulator_finish(&acc);
    calls++;
    EXPECT(vsgl_is_finite(v));
    EXPECT(sphera_vsgl_accumulator_new(&other, origin));
    (void)sphera_vsgl_accumulator_add_vpl(&other, &vpl);
    (void)sphera_vsgl_accumulator_merge(&other, &acc);
    (void)sphera_vsgl_accumulator_merge(&other, &other);
    calls += 4;
    EXPECT(vsgl_is_finite(sphera_vsgl_accumulator_finish(&other)));
    calls++;
    /* A texel by hand: any fields. */
    texel.diffuse_power = special_vec(k);
    texel.specular_power = special_vec(k + 1);
    texel.diffuse_direction = special_vec(k + 2);
    texel.specular_direction = special_vec(k + 3);
    texel.position = special_vec(k + 4);
    texel.squared_distance = specials[k % SPECIAL_COUNT];
    texel.weight = specials[(k + 1) % SPECIAL_COUNT];
    EXPECT(sphera_vsgl_accumulator_new(&other, origin));
    (void)sphera_vsgl_accumulator_add_texel(&other, &texel);
    calls += 2;
    EXPECT(vsgl_is_finite(sphera_vsgl_accumulator_finish(&other)));
    calls++;
  }

  /* FIS on a 4×4 pyramid: a valid one, then texels with special fields; every size,
   * count, kernel scale and random number. */
  for (k = 0; k < 64; k++) {
    int t, s, c, q;
    for (t = 0; t < PYRAMID_TEXELS; t++) {
      SpheraVpl vpl = special_vpl(t * 5 + 1);
      vpl.position = vec3(0.1f * (float)(t % 4), 1.0f, 0.1f * (float)(t / 4));
      vpl.power = vec3(1.0f + (float)t, 1.0f, 1.0f);
      vpl.roughness = 0.3f;
      if (!sphera_vsgl_texel_from_vpl(&vpl, origin, &pyramid[t]))
        memset(&pyramid[t], 0, sizeof pyramid[t]);
      calls++;
    }
    if (k > 0) {
      /* Break one texel (the pyramid need not be consistent: no crash, finite). */
      SpheraVsglTexel *broken = &pyramid[k % PYRAMID_TEXELS];
      broken->weight = specials[k % SPECIAL_COUNT];
      broken->diffuse_power = special_vec(k);
      broken->position = special_vec(k + 1);
      broken->squared_distance = specials[(k + 3) % SPECIAL_COUNT];
    }
    for (s = 0; s < 6; s++) {
      for (c = 0; c < 5; c++) {
        for (q = 0; q < pair_count(0); q += 4) {
          float u0, u1;
          pair(q, 0, &u0, &u1);
          v = sphera_vsgl_fis_select(pyramid, PYRAMID_TEXELS, sizes[s], origin, clusters[c],
                                     specials[(k + q) % SPECIAL_COUNT], (uint32_t)(q * 7), u0, u1);
          calls++;
          EXPECT(vsgl_is_finite(v));
          if (sizes[s] != 4u && sizes[s] != 1u) EXPECT(vsgl_is_empty(v));
          if (clusters[c] == 0u) EXPECT(vsgl_is_empty(v));
        }
      }
    }
    /* Too few texels, a bad origin. */
    v = sphera_vsgl_fis_select(pyramid, PYRAMID_TEXELS - 1, 4, origin, 4, 1.0f, 8, 0.5f, 0.5f);
    EXPECT(vsgl_is_empty(v));
    v = sphera_vsgl_fis_select(pyramid, PYRAMID_TEXELS, 4, special_vec(k), 4, 1.0f, 8, 0.5f,
                               0.5f);
    EXPECT(vsgl_is_finite(v));
    calls += 2;
  }
}

static void run_all(void) {
  SpheraVec3 view = vec3(0.3f, 0.1f, 0.9f);
  EXPECT(sphera_ltc_prepare(&ltc_for_polygons, view, 0.4f));
  material_for_polygons.diffuse = vec3(0.5f, 0.5f, 0.5f);
  material_for_polygons.f0 = vec3(0.04f, 0.04f, 0.04f);
  material_for_polygons.roughness = 0.4f;
  polygon_suite();
  brdf_suite();
  mis_suite();
  frame_and_ltc_suite();
  sphere_suite();
  sptd_suite();
  sg_suite();
  vsgl_suite();
  EXPECT(sphera_version() != NULL && sphera_version()[0] != '\0');
  (void)sphera_has_hardware_fma();
  /* The version check over special numbers: the header's major version, and its minor
   * version (before 1.0) or one up to it (from 1.0 on), only. */
  {
    const uint32_t numbers[6] = {0u, 1u, 2u, 0x7fffffffu, 0x80000000u, UINT32_MAX};
    int a, b;
    for (a = 0; a < 6; a++)
      for (b = 0; b < 6; b++) {
        calls++;
        EXPECT(sphera_check_version(numbers[a], numbers[b]) ==
               (numbers[a] == SPHERA_VERSION_MAJOR &&
                (SPHERA_VERSION_MAJOR == 0 ? numbers[b] == SPHERA_VERSION_MINOR
                                           : numbers[b] <= SPHERA_VERSION_MINOR)));
      }
    EXPECT(sphera_check_version(SPHERA_VERSION_MAJOR, SPHERA_VERSION_MINOR));
  }
}

int main(void) {
  fill_tables();
  fill_bases();
  fill_probes();
  fill_directions();
  run_all();
  printf("default float environment: %ld calls, %ld expectations\n", calls, expectations);
#if HAVE_MXCSR
  {
    unsigned int saved = _mm_getcsr();
    long before = calls;
    _mm_setcsr(saved | 0x8040u); /* FTZ (bit 15) | DAZ (bit 6) */
    daz_mode = 1;
    run_all();
    _mm_setcsr(saved);
    printf("FTZ|DAZ: %ld calls\n", calls - before);
  }
#else
  printf("FTZ|DAZ: not available on this target\n");
#endif
  return check_summary();
}
