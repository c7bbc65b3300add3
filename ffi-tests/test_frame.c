/* C ABI tests of shading frames (sphera_frame_*) and sphera_has_hardware_fma. */
#include "check.h"

#include <string.h>

static int is_identity(const SpheraFrame *f) {
  return vec3_equal(f->tangent, vec3(1.0f, 0.0f, 0.0f)) &&
         vec3_equal(f->bitangent, vec3(0.0f, 1.0f, 0.0f)) &&
         vec3_equal(f->normal, vec3(0.0f, 0.0f, 1.0f));
}

static void check_good_normal(SpheraVec3 n) {
  SpheraFrame f;
  DVec3 t, b, nn;
  SpheraVec3 v = vec3(0.3f, -0.7f, 0.2f);
  SpheraVec3 local, back, z;
  printf("normal (%.9g, %.9g, %.9g)\n", n.x, n.y, n.z);
  CHECK(sphera_frame_from_normal(&f, n));
  t = dvec(f.tangent);
  b = dvec(f.bitangent);
  nn = dvec(f.normal);
  CHECK(vec3_equal(f.normal, n));
  CHECK_ABS(ddot(t, t), 1.0, 1e-6);
  CHECK_ABS(ddot(b, b), 1.0, 1e-6);
  CHECK_ABS(ddot(t, b), 0.0, 1e-6);
  CHECK_ABS(ddot(t, nn), 0.0, 1e-6);
  CHECK_ABS(ddot(b, nn), 0.0, 1e-6);
  CHECK_ABS(ddot(dcross(t, b), nn), 1.0, 1e-6); /* right-handed */

  local = sphera_frame_to_local(&f, n);
  CHECK_ABS(local.x, 0.0, 1e-6);
  CHECK_ABS(local.y, 0.0, 1e-6);
  CHECK_ABS(local.z, 1.0, 1e-6);
  z = sphera_frame_to_world(&f, vec3(0.0f, 0.0f, 1.0f));
  CHECK(vec3_equal(z, n));
  local = sphera_frame_to_local(&f, v);
  back = sphera_frame_to_world(&f, local);
  CHECK_ABS(back.x, v.x, 1e-6);
  CHECK_ABS(back.y, v.y, 1e-6);
  CHECK_ABS(back.z, v.z, 1e-6);
  CHECK_ABS(local.x, ddot(dvec(v), t), 1e-6);
  CHECK_ABS(local.y, ddot(dvec(v), b), 1e-6);
  CHECK_ABS(local.z, ddot(dvec(v), nn), 1e-6);
}

int main(void) {
  SpheraFrame f;
  SpheraVec3 v = vec3(0.25f, -2.0f, 8.0f);
  SpheraVec3 r;
  double s = 1.0 / sqrt(14.0);
  int k;
  const SpheraVec3 bad_normals[] = {
      {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 2.0f},      {0.0f, 0.0f, 0.5f},       {NAN, 0.0f, 1.0f},
      {0.0f, NAN, 1.0f},  {0.0f, 0.0f, INFINITY}, {-INFINITY, 0.0f, 0.0f}, {NAN, NAN, NAN},
  };

  /* ---- good input ---- */
  check_good_normal(vec3(0.0f, 0.0f, 1.0f));
  check_good_normal(vec3(0.0f, 0.0f, -1.0f));
  check_good_normal(vec3(1.0f, 0.0f, 0.0f));
  check_good_normal(vec3(0.0f, -1.0f, 0.0f));
  check_good_normal(vec3(0.0f, 0.6f, 0.8f));
  check_good_normal(vec3(0.6f, 0.0f, -0.8f));
  check_good_normal(vec3((float)(1.0 * s), (float)(2.0 * s), (float)(-3.0 * s)));
  check_good_normal(vec3(1e-7f, 0.0f, -1.0f));

  /* ---- bad input ---- */
  printf("bad input\n");
  CHECK(!sphera_frame_from_normal(NULL, vec3(0.0f, 0.0f, 1.0f)));
  CHECK(!sphera_frame_from_normal(NULL, vec3(NAN, 0.0f, 1.0f)));
  for (k = 0; k < (int)(sizeof bad_normals / sizeof bad_normals[0]); k++) {
    /* Start from a valid frame, which the failing call must overwrite. */
    CHECK(sphera_frame_from_normal(&f, vec3(0.0f, 0.6f, -0.8f)));
    CHECK(!sphera_frame_from_normal(&f, bad_normals[k]));
    CHECK(is_identity(&f));
  }
  r = sphera_frame_to_local(NULL, v);
  CHECK(vec3_equal(r, v));
  r = sphera_frame_to_world(NULL, v);
  CHECK(vec3_equal(r, v));
  /* Non-finite vectors through a valid frame do not crash. */
  CHECK(sphera_frame_from_normal(&f, vec3(0.0f, 0.6f, 0.8f)));
  r = sphera_frame_to_local(&f, vec3(NAN, INFINITY, 0.0f));
  (void)r;
  r = sphera_frame_to_world(&f, vec3(NAN, INFINITY, 0.0f));
  (void)r;

  /* ---- capabilities ---- */
  {
    bool fma = sphera_has_hardware_fma();
    printf("sphera_has_hardware_fma() = %d\n", (int)fma);
    CHECK(fma == true || fma == false);
#if defined(__aarch64__) || defined(__i386__) || defined(__arm__)
    CHECK(!fma); /* only x86_64 with the fma target feature reports hardware FMA */
#endif
  }

  /* ---- version: "MAJOR.MINOR.PATCH", then "+fma" exactly in the FMA build; static and
   * NUL-terminated ---- */
  {
    const char *version = sphera_version();
    unsigned major, minor, patch;
    int consumed = 0;
    CHECK(version != NULL);
    printf("sphera_version() = %s\n", version ? version : "(null)");
    CHECK(version && sscanf(version, "%u.%u.%u%n", &major, &minor, &patch, &consumed) == 3);
    if (sphera_has_hardware_fma()) {
      CHECK(version && strcmp(version + consumed, "+fma") == 0);
    } else {
      CHECK(version && version[consumed] == '\0');
    }
    CHECK(sphera_version() == version);
  }

  CHECK(SPHERA_MAX_POLYGON_VERTICES == 8);
  return check_summary();
}
