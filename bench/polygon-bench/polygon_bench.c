/* Benchmark of the polygon techniques of the C ABI (include/sphera.h), as a renderer
 * calls them: "prepare + 1 sample" (one prepare per sample, the one-sample-per-light
 * mode) and "per sample" (many samples from structs prepared beforehand), in ns per
 * call, against a minimal Turk sampler written here in C (the floor of the ratios).
 *
 * Pools of 1024 convex polygons, relative to the shading point in the local frame
 * (z = normal), generated deterministically (SplitMix64) for 3, 4, 6 and 7 vertices:
 * "central" (the zenith inside the polygon), "decentral" (outside), both entirely above
 * the horizon, and "straddling" (crossing the horizon; only for the techniques that clip
 * internally, and the C Turk floor on the unclipped polygon).
 *
 * Timing: thread CPU time, best of R repetitions of N calls, the techniques interleaved
 * within each repetition. Every pdf and dir.x goes into a checksum printed at the end.
 * Exits 1 when a technique yields no sample with pdf > 0 in a pool it runs on.
 *
 *   polygon_bench [--quick] [--reps R] [--calls N] [--only NAME[,NAME...]] [--pool ID]
 *
 * --quick is 1 repetition of 2000 calls (it checks that everything runs; no timing is
 * asserted). --only runs only the named techniques (the ratio columns then need c_turk
 * among them); --pool only the pool with that id (e.g. hexagons-central). Both serve
 * profiling, e.g. under callgrind with --toggle-collect=loop_prepare_solid_angle. */
#define _POSIX_C_SOURCE 199309L

#include "../bench-common.h"

enum { MAX_V = SPHERA_MAX_POLYGON_VERTICES };

typedef struct {
  float v[MAX_V][3];
  int n;
} Polygon;

enum Kind { CENTRAL, DECENTRAL, STRADDLING };

typedef struct {
  char id[32];
  char title[48];
  int n;
  enum Kind kind;
  Polygon polygons[POOL_SIZE];
} Pool;

/* ---- the C Turk baseline: what a renderer author would write ---------------------- */

struct TurkC {
  float v[MAX_V][3];
  float cumulative[MAX_V - 2]; /* areas of the fan triangles up to and including k */
  float normal[3];
  float area;
  int triangles;
};

NOINLINE static void turk_prepare(struct TurkC *out, const float (*v)[3], int n) {
  float nx = 0.0f, ny = 0.0f, nz = 0.0f, total = 0.0f, inv;
  int i, k;
  for (i = 0; i < n; i++) {
    out->v[i][0] = v[i][0];
    out->v[i][1] = v[i][1];
    out->v[i][2] = v[i][2];
  }
  for (k = 0; k < n - 2; k++) {
    float ax = v[k + 1][0] - v[0][0], ay = v[k + 1][1] - v[0][1], az = v[k + 1][2] - v[0][2];
    float bx = v[k + 2][0] - v[0][0], by = v[k + 2][1] - v[0][1], bz = v[k + 2][2] - v[0][2];
    float cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    nx += cx;
    ny += cy;
    nz += cz;
    total += 0.5f * sqrtf(cx * cx + cy * cy + cz * cz);
    out->cumulative[k] = total;
  }
  inv = 1.0f / sqrtf(nx * nx + ny * ny + nz * nz);
  out->normal[0] = nx * inv;
  out->normal[1] = ny * inv;
  out->normal[2] = nz * inv;
  out->area = total;
  out->triangles = n - 2;
}

NOINLINE static SpheraSample turk_sample(const struct TurkC *t, float u0, float u1) {
  SpheraSample s;
  float target = u0 * t->area, lo, r, root, b0, b1, b2, px, py, pz, d2, inv, cosine;
  const float *a, *b, *c;
  int k = 0;
  while (k < t->triangles - 1 && target >= t->cumulative[k]) k++;
  lo = k > 0 ? t->cumulative[k - 1] : 0.0f;
  r = (target - lo) / (t->cumulative[k] - lo); /* the remainder of u0, in [0, 1) */
  root = sqrtf(r);
  b0 = 1.0f - root;
  b1 = root * (1.0f - u1);
  b2 = root * u1;
  a = t->v[0];
  b = t->v[k + 1];
  c = t->v[k + 2];
  px = b0 * a[0] + b1 * b[0] + b2 * c[0];
  py = b0 * a[1] + b1 * b[1] + b2 * c[1];
  pz = b0 * a[2] + b1 * b[2] + b2 * c[2];
  d2 = px * px + py * py + pz * pz;
  inv = 1.0f / sqrtf(d2);
  s.dir.x = px * inv;
  s.dir.y = py * inv;
  s.dir.z = pz * inv;
  cosine = fabsf(t->normal[0] * s.dir.x + t->normal[1] * s.dir.y + t->normal[2] * s.dir.z);
  s.pdf = d2 / (t->area * cosine);
  return s;
}

/* ---- the techniques ---------------------------------------------------------------- */

typedef struct {
  double sum;
  long valid; /* samples with pdf > 0 */
} Tally;

#define LIB_VERTS(p) ((const SpheraVec3 *)(const void *)(p)->v)
#define C_VERTS(p) ((const float(*)[3])(p)->v)

/* Per technique: the prepare + 1 sample loop, the preparation of a pool into an array,
 * and the per-sample loop over that array. */
#define DEFINE_TECHNIQUE(ID, TYPE, PREPARE, SAMPLE, VERTS, STRADDLING_TOO, VERTICES)         \
  NOINLINE static void loop_prepare_##ID(const Pool *pool, long calls, Tally *tally) {      \
    TYPE prepared;                                                                          \
    double sum = 0.0;                                                                       \
    long i, valid = 0;                                                                      \
    for (i = 0; i < calls; i++) {                                                           \
      const Polygon *p = &pool->polygons[i & (POOL_SIZE - 1)];                              \
      const float *u = g_u[i & (U_COUNT - 1)];                                              \
      SpheraSample s;                                                                       \
      PREPARE(&prepared, VERTS(p), p->n);                                                   \
      s = SAMPLE(&prepared, u[0], u[1]);                                                    \
      sum += (double)s.pdf + (double)s.dir.x;                                               \
      valid += s.pdf > 0.0f;                                                                \
    }                                                                                       \
    tally->sum += sum;                                                                      \
    tally->valid += valid;                                                                  \
  }                                                                                         \
  static void prepare_all_##ID(const Pool *pool, void *array) {                             \
    TYPE *prepared = (TYPE *)array;                                                         \
    int i;                                                                                  \
    for (i = 0; i < POOL_SIZE; i++)                                                         \
      PREPARE(&prepared[i], VERTS(&pool->polygons[i]), pool->polygons[i].n);                \
  }                                                                                         \
  NOINLINE static void loop_sample_##ID(const void *array, long calls, Tally *tally) {      \
    const TYPE *prepared = (const TYPE *)array;                                             \
    double sum = 0.0;                                                                       \
    long i, valid = 0;                                                                      \
    for (i = 0; i < calls; i++) {                                                           \
      const float *u = g_u[i & (U_COUNT - 1)];                                              \
      SpheraSample s = SAMPLE(&prepared[i & (POOL_SIZE - 1)], u[0], u[1]);                  \
      sum += (double)s.pdf + (double)s.dir.x;                                               \
      valid += s.pdf > 0.0f;                                                                \
    }                                                                                       \
    tally->sum += sum;                                                                      \
    tally->valid += valid;                                                                  \
  }

/* The fixed-size solid angle samplers take no count. */
#define TRIANGLE_PREPARE(out, vertices, n) sphera_solid_angle_triangle_prepare(out, vertices)
#define QUAD_PREPARE(out, vertices, n) sphera_solid_angle_quad_prepare(out, vertices)

/* id, prepared type, prepare, sample, vertex argument, runs on straddling pools, runs only on
 * pools of this many vertices (0: every pool) */
#define TECHNIQUES(X)                                                                                          \
  X(c_turk, struct TurkC, turk_prepare, turk_sample, C_VERTS, 1, 0)                                            \
  X(turk, SpheraTurkPolygon, sphera_turk_polygon_prepare, sphera_turk_polygon_sample, LIB_VERTS, 0, 0)         \
  X(solid_angle, SpheraSolidAnglePolygon, sphera_solid_angle_polygon_prepare,                                  \
    sphera_solid_angle_polygon_sample, LIB_VERTS, 0, 0)                                                        \
  X(solid_angle_triangle, SpheraSolidAngleTriangle, TRIANGLE_PREPARE, sphera_solid_angle_triangle_sample,      \
    LIB_VERTS, 0, 3)                                                                                           \
  X(solid_angle_quad, SpheraSolidAngleQuad, QUAD_PREPARE, sphera_solid_angle_quad_sample, LIB_VERTS, 0, 4)     \
  X(clipped_solid_angle, SpheraClippedSolidAnglePolygon, sphera_clipped_solid_angle_polygon_prepare,           \
    sphera_clipped_solid_angle_polygon_sample, LIB_VERTS, 1, 0)                                                \
  X(projected, SpheraProjectedPolygon, sphera_projected_polygon_prepare,                                       \
    sphera_projected_polygon_sample, LIB_VERTS, 1, 0)                                                          \
  X(projected_fast, SpheraProjectedPolygon, sphera_projected_polygon_prepare_fast,                             \
    sphera_projected_polygon_sample_fast, LIB_VERTS, 1, 0)                                                     \
  X(arvo, SpheraArvoPolygon, sphera_arvo_polygon_prepare, sphera_arvo_polygon_sample, LIB_VERTS, 0, 0)         \
  X(hart_bilinear, SpheraHartBilinearPolygon, sphera_hart_bilinear_polygon_prepare,                            \
    sphera_hart_bilinear_polygon_sample, LIB_VERTS, 0, 0)                                                      \
  X(hart_biquadratic, SpheraHartBiquadraticPolygon, sphera_hart_biquadratic_polygon_prepare,                   \
    sphera_hart_biquadratic_polygon_sample, LIB_VERTS, 0, 0)                                                   \
  X(arvo_projected, SpheraArvoProjectedPolygon, sphera_arvo_projected_polygon_prepare,                         \
    sphera_arvo_projected_polygon_sample, LIB_VERTS, 1, 0)

TECHNIQUES(DEFINE_TECHNIQUE)

typedef struct {
  const char *id;
  const char *type;
  size_t size;
  int straddling_too;
  int vertices; /* 0: every pool */
  void (*loop_prepare)(const Pool *, long, Tally *);
  void (*prepare_all)(const Pool *, void *);
  void (*loop_sample)(const void *, long, Tally *);
} Technique;

#define TECHNIQUE_ENTRY(ID, TYPE, PREPARE, SAMPLE, VERTS, STRADDLING_TOO, VERTICES) \
  {#ID, #TYPE, sizeof(TYPE), STRADDLING_TOO, VERTICES, loop_prepare_##ID, prepare_all_##ID, loop_sample_##ID},

static const Technique TECHNIQUE_LIST[] = {TECHNIQUES(TECHNIQUE_ENTRY)};
enum { TECHNIQUE_COUNT = sizeof(TECHNIQUE_LIST) / sizeof(TECHNIQUE_LIST[0]) };

/* ---- polygon pools --------------------------------------------------------------- */

/* Whether the zenith lies inside the polygon: the signs of (v_i × v_{i+1}).z all agree
 * (all vertices are above the horizon, so the zenith, not its opposite, is inside). */
static int zenith_inside(const Polygon *p) {
  int i, positive = 0, negative = 0;
  for (i = 0; i < p->n; i++) {
    const float *a = p->v[i], *b = p->v[(i + 1) % p->n];
    double s = (double)a[0] * b[1] - (double)a[1] * b[0];
    positive += s > 0.0;
    negative += s < 0.0;
  }
  return positive == p->n || negative == p->n;
}

/* One polygon of the pool's kind: vertices irregularly spaced on an ellipse (aspect in
 * [0.5, 1], random rotation) in a plane facing the shading point (tilted up to 50° from
 * the direction to its centre), centre at a log-uniform distance in [1, 4], radius 0.3–1
 * times the distance; rejected and redrawn until it belongs to its kind. */
static void generate_polygon(uint64_t *rng, int n, enum Kind kind, Polygon *out) {
  for (;;) {
    double distance = exp(uniform_in(rng, 0.0, log(4.0)));
    double cos_polar, sin_polar, azimuth, tilt, spin, radius, aspect, min_z = 1e30, max_z = -1e30;
    D3 c, w, m, t1, t2, t1r, t2r, centre;
    int k, ok = 1;
    if (kind == CENTRAL) {
      cos_polar = uniform_in(rng, cos(40.0 * PI / 180.0), 1.0);
    } else if (kind == DECENTRAL) {
      cos_polar = uniform_in(rng, cos(75.0 * PI / 180.0), cos(15.0 * PI / 180.0));
    } else {
      cos_polar = sin(uniform_in(rng, -25.0, 30.0) * PI / 180.0); /* elevation */
    }
    sin_polar = sqrt(1.0 - cos_polar * cos_polar);
    azimuth = uniform_in(rng, 0.0, 2.0 * PI);
    c = d3(sin_polar * cos(azimuth), sin_polar * sin(azimuth), cos_polar);
    /* The plane's normal m: -c tilted by up to 50° about an axis orthogonal to c, so
     * that the polygon faces the shading point (m · c < 0). */
    w = orthogonal(c);
    spin = uniform_in(rng, 0.0, 2.0 * PI);
    w = add(scale(w, cos(spin)), scale(cross(c, w), sin(spin)));
    tilt = uniform_in(rng, 0.0, 50.0 * PI / 180.0);
    m = scale(add(scale(c, cos(tilt)), scale(w, sin(tilt))), -1.0);
    t1 = orthogonal(m);
    t2 = cross(m, t1);
    spin = uniform_in(rng, 0.0, 2.0 * PI);
    t1r = add(scale(t1, cos(spin)), scale(t2, sin(spin)));
    t2r = add(scale(t2, cos(spin)), scale(t1, -sin(spin)));
    radius = distance * uniform_in(rng, 0.3, 1.0);
    aspect = uniform_in(rng, 0.5, 1.0);
    centre = scale(c, distance);
    out->n = n;
    for (k = 0; k < n; k++) {
      double angle = 2.0 * PI * (k + 0.4 * uniform(rng)) / n;
      D3 v = add(centre, add(scale(t1r, radius * cos(angle)), scale(t2r, radius * aspect * sin(angle))));
      out->v[k][0] = (float)v.x;
      out->v[k][1] = (float)v.y;
      out->v[k][2] = (float)v.z;
      if (out->v[k][2] < min_z) min_z = out->v[k][2];
      if (out->v[k][2] > max_z) max_z = out->v[k][2];
    }
    for (k = n; k < MAX_V; k++) out->v[k][0] = out->v[k][1] = out->v[k][2] = 0.0f;
    if (kind == STRADDLING) {
      /* Some vertices clearly below and some clearly above the horizon; the plane at
       * least 1/50 of the polygon's size (its diameter) from the shading point. */
      ok = n < MAX_V && min_z < -0.05 * radius && max_z > 0.1 * radius &&
           fabs(dot(m, centre)) >= 2.0 * radius / 50.0;
    } else {
      ok = min_z > 0.0 && (kind == CENTRAL) == zenith_inside(out);
    }
    if (ok) return;
  }
}

static const char *shape_name(int n) {
  switch (n) {
    case 3: return "triangles";
    case 4: return "quads";
    case 6: return "hexagons";
    case 7: return "heptagons";
    default: return "polygons";
  }
}

static const char *kind_name(enum Kind kind) {
  return kind == CENTRAL ? "central" : kind == DECENTRAL ? "decentral" : "straddling";
}

static void make_pool(Pool *pool, int n, enum Kind kind) {
  uint64_t rng = 0x5EED0000ull + 0x100ull * (uint64_t)n + (uint64_t)kind;
  int i;
  pool->n = n;
  pool->kind = kind;
  snprintf(pool->id, sizeof pool->id, "%s-%s", shape_name(n), kind_name(kind));
  snprintf(pool->title, sizeof pool->title, "%s, %s", shape_name(n), kind_name(kind));
  for (i = 0; i < POOL_SIZE; i++) generate_polygon(&rng, n, kind, &pool->polygons[i]);
}

/* The C Turk baseline checked against the library's Turk pdf (not timed): one sample
 * per polygon, whose pdf must agree with sphera_turk_polygon_pdf to 1e-3 relative, so
 * that the floor of the ratios computes what it claims to. */
static int check_c_turk(const Pool *pool) {
  int i, bad = 0;
  for (i = 0; i < POOL_SIZE; i++) {
    const Polygon *p = &pool->polygons[i];
    struct TurkC mine;
    SpheraTurkPolygon library;
    SpheraSample s;
    float expected;
    turk_prepare(&mine, C_VERTS(p), p->n);
    s = turk_sample(&mine, g_u[i][0], g_u[i][1]);
    sphera_turk_polygon_prepare(&library, LIB_VERTS(p), (uint32_t)p->n);
    expected = sphera_turk_polygon_pdf(&library, s.dir);
    if (!(fabsf(s.pdf - expected) <= 1e-3f * expected)) bad++;
  }
  if (bad) fprintf(stderr, "FAILED: the C Turk pdf differs from sphera_turk_polygon_pdf for %d polygons of %s\n", bad, pool->title);
  return bad;
}

/* ---- main ----------------------------------------------------------------------- */

int main(int argc, char **argv) {
  static const int SHAPES[4] = {3, 4, 6, 7};
  long reps = 5, calls = 200000;
  const char *only = NULL, *pool_filter = NULL;
  double checksum = 0.0;
  int failures = 0, pools_run = 0, t, s, k;
  uint64_t rng = 0xC0FFEEull;
  Pool *pool = (Pool *)malloc(sizeof(Pool));
  void *arrays[TECHNIQUE_COUNT];

  BenchOptions options;
  if (!parse_bench_options(argc, argv, &options) || !pool) return 2;
  reps = options.reps;
  calls = options.calls;
  only = options.only;
  pool_filter = options.pool;
  draw_random_numbers(&rng);

  printf("sphera %s, hardware FMA: %s; best of %ld x %ld calls, thread CPU time\n\n", sphera_version(),
         sphera_has_hardware_fma() ? "yes" : "no", reps, calls);
  printf("| technique | prepared struct | sizeof (bytes) |\n|---|---|---:|\n");
  for (t = 0; t < TECHNIQUE_COUNT; t++) {
    printf("| %s | %s | %zu |\n", TECHNIQUE_LIST[t].id, TECHNIQUE_LIST[t].type, TECHNIQUE_LIST[t].size);
    arrays[t] = malloc(TECHNIQUE_LIST[t].size * POOL_SIZE);
    if (!arrays[t]) return 2;
  }

  for (k = 0; k < 3; k++) {
    for (s = 0; s < 4; s++) {
      double best_prepare[TECHNIQUE_COUNT], best_sample[TECHNIQUE_COUNT];
      Tally prepare_tally[TECHNIQUE_COUNT], sample_tally[TECHNIQUE_COUNT];
      int runs[TECHNIQUE_COUNT], floor_index = -1;
      long rep;
      make_pool(pool, SHAPES[s], (enum Kind)k);
      if (pool_filter && strcmp(pool_filter, pool->id) != 0) continue;
      pools_run++;
      if (check_c_turk(pool)) failures++;
      for (t = 0; t < TECHNIQUE_COUNT; t++) {
        runs[t] = selected(only, TECHNIQUE_LIST[t].id) && (pool->kind != STRADDLING || TECHNIQUE_LIST[t].straddling_too) &&
                  (TECHNIQUE_LIST[t].vertices == 0 || TECHNIQUE_LIST[t].vertices == pool->n);
        best_prepare[t] = best_sample[t] = 1e300;
        prepare_tally[t].sum = sample_tally[t].sum = 0.0;
        prepare_tally[t].valid = sample_tally[t].valid = 0;
        if (runs[t]) TECHNIQUE_LIST[t].prepare_all(pool, arrays[t]); /* outside the timing */
        if (runs[t] && strcmp(TECHNIQUE_LIST[t].id, "c_turk") == 0) floor_index = t;
      }
      /* Interleaved: every repetition times every technique once. */
      for (rep = 0; rep < reps; rep++) {
        for (t = 0; t < TECHNIQUE_COUNT; t++) {
          double t0, t1, t2;
          if (!runs[t]) continue;
          t0 = thread_seconds();
          TECHNIQUE_LIST[t].loop_prepare(pool, calls, &prepare_tally[t]);
          t1 = thread_seconds();
          TECHNIQUE_LIST[t].loop_sample(arrays[t], calls, &sample_tally[t]);
          t2 = thread_seconds();
          if (t1 - t0 < best_prepare[t]) best_prepare[t] = t1 - t0;
          if (t2 - t1 < best_sample[t]) best_sample[t] = t2 - t1;
        }
      }
      printf("\n### %s (%d vertices, %d polygons%s)\n\n", pool->title, pool->n, POOL_SIZE,
             pool->kind == STRADDLING ? "; c_turk samples the unclipped polygon" : "");
      printf("| technique | ns prepare+1 sample | ns per sample | prepare+1 / C Turk | per sample / C Turk | valid |\n");
      printf("|---|---:|---:|---:|---:|---:|\n");
      for (t = 0; t < TECHNIQUE_COUNT; t++) {
        double ns_prepare = 1e9 * best_prepare[t] / (double)calls, ns_sample = 1e9 * best_sample[t] / (double)calls;
        double valid = 100.0 * (double)(prepare_tally[t].valid + sample_tally[t].valid) / (2.0 * (double)reps * (double)calls);
        if (!runs[t]) continue;
        checksum += prepare_tally[t].sum + sample_tally[t].sum;
        printf("| %s | %.1f | %.1f | ", TECHNIQUE_LIST[t].id, ns_prepare, ns_sample);
        if (floor_index >= 0) {
          double floor_prepare = 1e9 * best_prepare[floor_index] / (double)calls;
          double floor_sample = 1e9 * best_sample[floor_index] / (double)calls;
          printf("%.2f | %.2f | ", ns_prepare / floor_prepare, ns_sample / floor_sample);
        } else {
          printf("- | - | ");
        }
        printf("%.1f %% |\n", valid);
        if (prepare_tally[t].valid == 0 || sample_tally[t].valid == 0) {
          fprintf(stderr, "FAILED: %s yields no sample with pdf > 0 on %s (%s)\n", TECHNIQUE_LIST[t].id, pool->title,
                  prepare_tally[t].valid == 0 ? "prepare + 1 sample" : "per sample");
          failures++;
        }
      }
    }
  }
  for (t = 0; t < TECHNIQUE_COUNT; t++) free(arrays[t]);
  free(pool);
  printf("\nchecksum (sum of pdf + dir.x over all samples): %.9e\n", checksum);
  if (pools_run == 0) {
    fprintf(stderr, "FAILED: no pool matches --pool %s\n", pool_filter);
    return 1;
  }
  if (failures) {
    fprintf(stderr, "FAILED: %d technique/pool pairs without valid samples\n", failures);
    return 1;
  }
  return 0;
}
