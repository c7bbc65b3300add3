/* What the two C benchmarks (polygon-bench, light-bench) share: the pre-drawn random
 * numbers, a deterministic generator, f64 vector helpers for building pools, thread CPU
 * time, and the command line (--quick, --reps, --calls, --only, --pool). Header-only;
 * each benchmark is one translation unit that defines _POSIX_C_SOURCE before including
 * it. */
#ifndef SPHERA_BENCH_COMMON_H
#define SPHERA_BENCH_COMMON_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sphera.h"

#define NOINLINE __attribute__((noinline))

/* Inputs per pool, and pre-drawn (u0, u1) pairs. */
enum { POOL_SIZE = 1024, U_COUNT = 4096 };

/* The pools store plain floats; the library reads them as SpheraVec3 (three floats). */
typedef char vec3_is_three_floats[sizeof(SpheraVec3) == 3 * sizeof(float) ? 1 : -1];

static const double PI = 3.14159265358979323846;

/* The pre-drawn random numbers, in [0, 1) with 24 bits (exact in f32). */
static float g_u[U_COUNT][2];

/* ---- deterministic random numbers ------------------------------------------------ */

static inline uint64_t splitmix64(uint64_t *state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/* In [0, 1). */
static inline double uniform(uint64_t *state) { return (double)(splitmix64(state) >> 11) * 0x1.0p-53; }

static inline double uniform_in(uint64_t *state, double lo, double hi) { return lo + (hi - lo) * uniform(state); }

/* Fills g_u from the generator. */
static inline void draw_random_numbers(uint64_t *rng) {
  int i;
  for (i = 0; i < U_COUNT; i++) {
    g_u[i][0] = (float)((splitmix64(rng) >> 40) * 0x1.0p-24);
    g_u[i][1] = (float)((splitmix64(rng) >> 40) * 0x1.0p-24);
  }
}

/* ---- f64 vectors, for building pools ------------------------------------------------ */

typedef struct {
  double x, y, z;
} D3;

static inline D3 d3(double x, double y, double z) {
  D3 r;
  r.x = x;
  r.y = y;
  r.z = z;
  return r;
}
static inline D3 add(D3 a, D3 b) { return d3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline D3 scale(D3 a, double s) { return d3(a.x * s, a.y * s, a.z * s); }
static inline double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline D3 cross(D3 a, D3 b) { return d3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x); }
static inline D3 normalize(D3 a) { return scale(a, 1.0 / sqrt(dot(a, a))); }

/* A unit vector orthogonal to the unit vector a. */
static inline D3 orthogonal(D3 a) { return normalize(fabs(a.x) < 0.6 ? cross(a, d3(1, 0, 0)) : cross(a, d3(0, 1, 0))); }

/* ---- timing and the command line ---------------------------------------------------- */

static inline double thread_seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Whether `id` is one of the comma-separated names of `only` (every id when NULL). */
static inline int selected(const char *only, const char *id) {
  size_t length = strlen(id);
  const char *p = only;
  if (!only) return 1;
  while ((p = strstr(p, id)) != NULL) {
    if ((p == only || p[-1] == ',') && (p[length] == '\0' || p[length] == ',')) return 1;
    p += length;
  }
  return 0;
}

typedef struct {
  long reps, calls;
  const char *only, *pool;
} BenchOptions;

/* Parses the command line into `options` (defaults: best of 5 x 200,000 calls, every
 * technique and pool); on a bad argument prints the usage and returns 0. */
static inline int parse_bench_options(int argc, char **argv, BenchOptions *options) {
  int i;
  options->reps = 5;
  options->calls = 200000;
  options->only = NULL;
  options->pool = NULL;
  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--quick") == 0) {
      options->reps = 1;
      options->calls = 2000;
    } else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) {
      options->reps = atol(argv[++i]);
    } else if (strcmp(argv[i], "--calls") == 0 && i + 1 < argc) {
      options->calls = atol(argv[++i]);
    } else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
      options->only = argv[++i];
    } else if (strcmp(argv[i], "--pool") == 0 && i + 1 < argc) {
      options->pool = argv[++i];
    } else {
      break;
    }
  }
  if (i < argc || options->reps < 1 || options->calls < 1) {
    fprintf(stderr, "usage: %s [--quick] [--reps R] [--calls N] [--only NAME[,NAME...]] [--pool ID]\n", argv[0]);
    return 0;
  }
  return 1;
}

#endif
