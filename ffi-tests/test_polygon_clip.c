/* C ABI tests of sphera_polygon_clip. */
#include <string.h>

#include "check.h"

/* The array handed to the clip, followed by a guard that must never be written. */
typedef struct Buffer {
  SpheraVec3 v[SPHERA_MAX_POLYGON_VERTICES];
  SpheraVec3 guard;
} Buffer;

static void load(Buffer *b, const SpheraVec3 *v, int n) {
  int i;
  for (i = 0; i < SPHERA_MAX_POLYGON_VERTICES; i++) b->v[i] = vec3(-7.0f, -7.0f, -7.0f);
  for (i = 0; i < n; i++) b->v[i] = v[i];
  b->guard = vec3(42.0f, 42.0f, 42.0f);
}

static int guard_intact(const Buffer *b) { return vec3_equal(b->guard, vec3(42.0f, 42.0f, 42.0f)); }

/* Clips v and compares the result with the expected polygon: the same vertices in the
 * same cyclic order (any starting vertex, same orientation) within `tolerance`; vertices
 * with expected z == 0 must have z == 0 exactly. */
static void check_clip(const char *name, const SpheraVec3 *v, int n, const SpheraVec3 *expected,
                       int expected_count, double tolerance) {
  Buffer b;
  uint32_t count;
  int i, shift, matched_shift = -1, exact_zeros = 1, nonnegative = 1;
  printf("clip %s: %d -> %d vertices expected\n", name, n, expected_count);
  load(&b, v, n);
  count = sphera_polygon_clip(b.v, (uint32_t)n);
  CHECK(count == (uint32_t)expected_count);
  CHECK(guard_intact(&b));
  if (count != (uint32_t)expected_count) {
    printf("    got %u vertices\n", (unsigned)count);
    return;
  }
  if (expected_count == 0) return;
  for (shift = 0; shift < expected_count && matched_shift < 0; shift++) {
    int all = 1;
    for (i = 0; i < expected_count; i++) {
      SpheraVec3 got = b.v[(i + shift) % expected_count];
      DVec3 d = dsub(dvec(got), dvec(expected[i]));
      if (!(dlength(d) <= tolerance)) all = 0;
    }
    if (all) matched_shift = shift;
  }
  CHECK(matched_shift >= 0);
  if (matched_shift < 0) {
    for (i = 0; i < expected_count; i++) {
      printf("    vertex %d: got (%.9g, %.9g, %.9g), expected (%.9g, %.9g, %.9g) (up to rotation)\n", i,
             b.v[i].x, b.v[i].y, b.v[i].z, expected[i].x, expected[i].y, expected[i].z);
    }
    return;
  }
  for (i = 0; i < expected_count; i++) {
    SpheraVec3 got = b.v[(i + matched_shift) % expected_count];
    if (expected[i].z == 0.0f && got.z != 0.0f) exact_zeros = 0;
    if (!(got.z >= 0.0f)) nonnegative = 0;
  }
  CHECK(exact_zeros);  /* vertices made by the clip lie exactly on z = 0 */
  CHECK(nonnegative);
}

int main(void) {
  /* A vertical quad in the plane x = 1, half below the horizon. */
  const SpheraVec3 quad[4] = {{1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}};
  const SpheraVec3 quad_clipped[4] = {{1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}};
  /* The same quad tilted: the horizon crosses its edges at 1/4 and 3/4. */
  const SpheraVec3 tilted[4] = {{1.0f, -1.0f, -0.5f}, {1.0f, 1.0f, -1.5f}, {1.0f, 1.0f, 0.5f}, {1.0f, -1.0f, 1.5f}};
  const SpheraVec3 tilted_clipped[4] = {{1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 0.5f}, {1.0f, -1.0f, 1.5f}};
  /* Triangles with one and two vertices below the horizon. */
  const SpheraVec3 one_below[3] = {{-1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {0.0f, 1.0f, -1.0f}};
  const SpheraVec3 one_below_clipped[4] = {{-1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {0.5f, 1.0f, 0.0f}, {-0.5f, 1.0f, 0.0f}};
  const SpheraVec3 two_below[3] = {{0.0f, 1.0f, 1.0f}, {1.0f, 1.0f, -1.0f}, {-1.0f, 1.0f, -1.0f}};
  const SpheraVec3 two_below_clipped[3] = {{0.0f, 1.0f, 1.0f}, {0.5f, 1.0f, 0.0f}, {-0.5f, 1.0f, 0.0f}};
  /* Entirely above, entirely below, touching the horizon. */
  const SpheraVec3 above[4] = {{-1.0f, -1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 2.0f}, {-1.0f, 1.0f, 2.0f}};
  const SpheraVec3 below[4] = {{-1.0f, -1.0f, -1.0f}, {1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, -2.0f}, {-1.0f, 1.0f, -2.0f}};
  const SpheraVec3 touching[4] = {{1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}};
  const SpheraVec3 nine[9] = {{1.0f, 0.0f, 1.0f}, {0.77f, 0.64f, 1.0f}, {0.17f, 0.98f, 1.0f}, {-0.5f, 0.87f, 1.0f}, {-0.94f, 0.34f, 1.0f}, {-0.94f, -0.34f, 1.0f}, {-0.5f, -0.87f, 1.0f}, {0.17f, -0.98f, 1.0f}, {0.77f, -0.64f, -1.0f}};
  /* A heptagon in the plane y = 1 around (0, 1, 0.2) with radius 1; the horizon cuts off
   * the three vertices with z < 0, leaving 4 + 2 = 6 vertices. */
  SpheraVec3 heptagon[7];
  Buffer b, copy;
  int k;

  for (k = 0; k < 7; k++) {
    double angle = 3.14159265358979323846 * 2.0 * k / 7.0;
    heptagon[k] = vec3((float)cos(angle), 1.0f, (float)(0.2 + sin(angle)));
  }

  /* ---- good input (fails until the core clipping is implemented) ---- */
  check_clip("half-below quad", quad, 4, quad_clipped, 4, 1e-6);
  check_clip("tilted quad", tilted, 4, tilted_clipped, 4, 1e-6);
  check_clip("triangle, one vertex below", one_below, 3, one_below_clipped, 4, 1e-6);
  check_clip("triangle, two vertices below", two_below, 3, two_below_clipped, 3, 1e-6);
  check_clip("quad above", above, 4, above, 4, 0.0);
  check_clip("quad touching the horizon", touching, 4, touching, 4, 0.0);
  check_clip("quad below", below, 4, NULL, 0, 0.0);
  {
    uint32_t count;
    int i, on_horizon = 0, nonnegative = 1;
    load(&b, heptagon, 7);
    count = sphera_polygon_clip(b.v, 7);
    printf("clip heptagon: 7 -> %u vertices\n", (unsigned)count);
    CHECK(count == 6);
    CHECK(guard_intact(&b));
    for (i = 0; i < (int)count && i < 8; i++) {
      if (b.v[i].z == 0.0f) on_horizon++;
      if (!(b.v[i].z >= 0.0f)) nonnegative = 0;
    }
    CHECK(on_horizon == 2);
    CHECK(nonnegative);
  }
  {
    SpheraVec3 octagon[8];
    for (k = 0; k < 8; k++) {
      double angle = 3.14159265358979323846 * 2.0 * k / 8.0;
      octagon[k] = vec3((float)cos(angle), (float)sin(angle), 0.5f);
    }
    check_clip("octagon above", octagon, 8, octagon, 8, 0.0);
  }
  {
    /* An octagon with exactly one vertex below the horizon would need 9 vertices after
     * clipping; whatever the clip returns (the core returns 0 for any octagon that is not
     * entirely above), it must be a valid count within the array. */
    uint32_t count;
    SpheraVec3 one_low[8];
    for (k = 0; k < 8; k++) {
      double angle = 3.14159265358979323846 * 2.0 * k / 8.0;
      one_low[k] = vec3((float)cos(angle), 1.0f, (float)(0.8 + sin(angle)));
    }
    load(&b, one_low, 8);
    count = sphera_polygon_clip(b.v, 8);
    printf("clip octagon with one vertex below: %u vertices\n", (unsigned)count);
    CHECK(count == 0 || (count >= 3 && count <= SPHERA_MAX_POLYGON_VERTICES));
    CHECK(guard_intact(&b));
  }

  /* ---- bad input (holds for the stubs already) ---- */
  printf("bad input\n");
  CHECK(sphera_polygon_clip(NULL, 4) == 0);
  CHECK(sphera_polygon_clip(NULL, 0) == 0);
  for (k = 0; k <= 9; k += (k == 2 ? 7 : 1)) { /* counts 0, 1, 2, 9: array untouched */
    load(&b, quad, 4);
    copy = b;
    CHECK(sphera_polygon_clip(b.v, (uint32_t)k) == 0);
    CHECK(memcmp(&b, &copy, sizeof b) == 0);
  }
  load(&b, nine, 8);
  copy = b;
  CHECK(sphera_polygon_clip(b.v, 0xffffffffu) == 0);
  CHECK(memcmp(&b, &copy, sizeof b) == 0);
  {
    /* NaN and infinite coordinates: any valid count, no crash, no overflow. */
    const float values[3] = {NAN, INFINITY, -INFINITY};
    int coordinate, bad = 0;
    for (k = 0; k < 3; k++) {
      for (coordinate = 0; coordinate < 3; coordinate++) {
        uint32_t count;
        load(&b, quad, 4);
        if (coordinate == 0) b.v[1].x = values[k];
        if (coordinate == 1) b.v[2].y = values[k];
        if (coordinate == 2) b.v[0].z = values[k];
        count = sphera_polygon_clip(b.v, 4);
        if (!(count == 0 || (count >= 3 && count <= SPHERA_MAX_POLYGON_VERTICES)) || !guard_intact(&b)) bad++;
      }
    }
    CHECK(bad == 0);
  }

  return check_summary();
}
