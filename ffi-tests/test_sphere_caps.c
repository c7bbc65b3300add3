/* C ABI tests of sphere caps and the pivot transformation (sphera_cap_*, sphera_pivot_*),
 * of spheres prepared for solid angle sampling (sphera_solid_angle_sphere_*) and of unions
 * of caps (sphera_cap_union_*). */
#include <string.h>

#include "check.h"

static const double PI_D = 3.14159265358979323846;

static int cap_is_finite(SpheraCap c) {
  return vec3_is_finite(c.axis) && isfinite(c.one_minus_cos) && isfinite(c.one_plus_cos) &&
         isfinite(c.sin2) && c.one_minus_cos >= 0.0f && c.one_minus_cos <= 2.0f;
}

/* 1 - cos of the cap of a sphere, in double. */
static double one_minus_cos_d(SpheraVec3 center, double radius) {
  double d = dlength(dvec(center));
  double s2 = (radius / d) * (radius / d);
  return s2 / (1.0 + sqrt(1.0 - s2));
}

static void check_good_caps(void) {
  SpheraVec3 center = vec3(1.0f, 2.0f, 2.0f); /* distance 3 */
  SpheraCap cap = sphera_cap_from_sphere(center, 1.0f);
  SpheraCap tiny = sphera_cap_from_sphere(vec3(0.0f, 0.0f, 1e6f), 1.0f);
  SpheraCap whole = sphera_cap_from_sphere(center, 5.0f);
  SpheraCap on = sphera_cap_from_sphere(center, 3.0f);
  float u[U_COUNT];
  int i, j;
  CHECK(cap_is_finite(cap));
  CHECK_REL(cap.one_minus_cos, one_minus_cos_d(center, 1.0), 1e-6);
  CHECK_REL(sphera_cap_solid_angle(cap), 2.0 * PI_D * one_minus_cos_d(center, 1.0), 1e-6);
  CHECK_ABS(cap.axis.x, 1.0 / 3.0, 1e-6);
  /* sin^2 = 1e-12: a plain 1 - cos in float would be 0. */
  CHECK_REL(sphera_cap_solid_angle(tiny), 2.0 * PI_D * 0.5e-12, 1e-5);
  CHECK_REL(sphera_cap_solid_angle(whole), 4.0 * PI_D, 1e-6);
  CHECK_REL(sphera_cap_solid_angle(on), 4.0 * PI_D, 1e-6);
  CHECK(sphera_cap_contains(cap, center));
  CHECK(!sphera_cap_contains(cap, vec3(-1.0f, 0.0f, 0.0f)));

  fill_u_values(u);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = sphera_cap_sample_uniform(cap, u[i], u[j]);
      SpheraSample t = sphera_cap_sample_uniform(tiny, u[i], u[j]);
      CHECK(vec3_is_finite(s.dir) && s.pdf > 0.0f);
      CHECK_REL(s.pdf, 1.0 / (2.0 * PI_D * one_minus_cos_d(center, 1.0)), 1e-5);
      CHECK(1.0 - ddot(dvec(s.dir), dscale(dvec(center), 1.0 / 3.0)) <=
            one_minus_cos_d(center, 1.0) * (1.0 + 1e-4) + 1e-7);
      CHECK(vec3_is_finite(t.dir) && t.pdf > 0.0f && isfinite(t.pdf));
      CHECK(sqrt((double)t.dir.x * t.dir.x + (double)t.dir.y * t.dir.y) <= 1e-6 * (1.0 + 1e-5));
      if (u_is_interior(i) && u_is_interior(j)) {
        CHECK(sphera_cap_pdf(cap, s.dir) == s.pdf);
      }
    }
  }
}

static void check_intersections(void) {
  SpheraCap a = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, 1.0f), 0.0f);
  SpheraCap b = sphera_cap_from_axis_cos(vec3(1.0f, 0.0f, 0.0f), 0.0f);
  SpheraCap c = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, 1.0f), 0.5f);
  SpheraCap d = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, -1.0f), 0.5f);
  SpheraCap w1 = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, 1.0f), -0.5f);
  SpheraCap w2 = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, -1.0f), -0.5f);
  /* Two orthogonal hemispheres: a lune of angle pi/2, area pi. */
  CHECK_REL(sphera_cap_intersection_solid_angle(a, b), PI_D, 1e-5);
  CHECK_REL(sphera_cap_intersection_solid_angle(a, c), 2.0 * PI_D * 0.5, 1e-6); /* nested */
  CHECK_ABS(sphera_cap_intersection_solid_angle(c, d), 0.0, 0.0);               /* disjoint */
  /* Antipodal caps wider than a hemisphere: the union is the sphere. */
  CHECK_REL(sphera_cap_intersection_solid_angle(w1, w2), 2.0 * 2.0 * PI_D * 1.5 - 4.0 * PI_D,
            1e-5);
  CHECK_REL(sphera_cap_intersection_solid_angle_oat_sander(a, c), 2.0 * PI_D * 0.5, 1e-6);
  CHECK(sphera_cap_intersection_solid_angle_oat_sander(a, b) > 0.0f);
  {
    /* Issue 17 (6): a cap wider than a hemisphere keeps its hole 1 + cos (exact here)
     * in one_plus_cos, through the ABI's sanitisation. A cap around the hole, twice its
     * size, meets the wide cap in a ring of 2 pi ((1 - cos_small) - (1 + cos_wide));
     * from one_minus_cos near 2 the hole was only known to ulp(2), 3.6e-4 of it. */
    const float cos_wide = -0.99967f, cos_small = 0.99934f;
    SpheraCap wide = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, 1.0f), cos_wide);
    SpheraCap small = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, -1.0f), cos_small);
    double hole = 1.0 + (double)cos_wide;
    CHECK(wide.one_plus_cos == 1.0f + cos_wide);
    CHECK(wide.one_minus_cos == 2.0f - wide.one_plus_cos);
    CHECK_REL(sphera_cap_intersection_solid_angle(wide, small),
              2.0 * PI_D * ((1.0 - (double)cos_small) - hole), 1e-5);
    CHECK_REL(sphera_cap_intersection_solid_angle(small, wide),
              2.0 * PI_D * ((1.0 - (double)cos_small) - hole), 1e-5);
  }
}

/* Uniform sampling of the union of two caps: pdf 1/Omega(A u B) inside either cap,
 * Omega(A u B) = Omega(A) + Omega(B) - Omega(A n B), the samples inside the union with
 * pdf(dir) == pdf, the share of samples in A against Omega(A)/Omega(A u B), null
 * pointers and bad input. */
static void check_union(void) {
  SpheraCap a = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, 1.0f), 0.8f);
  SpheraCap b = sphera_cap_from_axis_cos(vec3(0.6f, 0.0f, 0.8f), 0.7f);
  SpheraCap far = sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, -1.0f), 0.9f);
  SpheraCapUnion u;
  double expected = (double)sphera_cap_solid_angle(a) + sphera_cap_solid_angle(b) -
                    sphera_cap_intersection_solid_angle(a, b);
  const float bad[] = {NAN, INFINITY, -INFINITY, 0.0f, -1.0f, 1e30f, 3e38f, 1e-45f};
  const int nbad = (int)(sizeof(bad) / sizeof(bad[0]));
  int i, j, in_a = 0, n = 0;
  CHECK(sphera_cap_union_prepare(&u, a, b));
  CHECK_REL(sphera_cap_union_solid_angle(&u), expected, 1e-5);
  for (i = 0; i < 100; i++) {
    for (j = 0; j < 100; j++) {
      SpheraSample s = sphera_cap_union_sample(&u, (i + 0.5f) / 100.0f, (j + 0.5f) / 100.0f);
      CHECK(s.pdf > 0.0f);
      CHECK(sphera_cap_contains(a, s.dir) || sphera_cap_contains(b, s.dir));
      CHECK(sphera_cap_union_pdf(&u, s.dir) == s.pdf);
      in_a += sphera_cap_contains(a, s.dir);
      n++;
    }
  }
  CHECK_REL(1.0f / sphera_cap_union_pdf(&u, a.axis), expected, 1e-5);
  CHECK_ABS((double)in_a / n, sphera_cap_solid_angle(a) / expected, 0.02);
  CHECK(sphera_cap_union_pdf(&u, vec3(0.0f, 0.0f, -1.0f)) == 0.0f);
  /* Disjoint caps: the sum; a cap and its complement: the sphere. */
  CHECK(sphera_cap_union_prepare(&u, a, far));
  CHECK_REL(sphera_cap_union_solid_angle(&u), 2.0 * PI_D * (0.2 + 0.1), 1e-5);
  CHECK(sphera_cap_union_prepare(&u, a, sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, -1.0f), -0.8f)));
  CHECK_REL(sphera_cap_union_solid_angle(&u), 4.0 * PI_D, 1e-5);
  /* Null pointers and empty unions. */
  CHECK(!sphera_cap_union_prepare(NULL, a, b));
  CHECK(sphera_cap_union_sample(NULL, 0.5f, 0.5f).pdf == 0.0f);
  CHECK(sphera_cap_union_pdf(NULL, a.axis) == 0.0f);
  CHECK(sphera_cap_union_solid_angle(NULL) == 0.0f);
  memset(&u, 0xff, sizeof u);
  CHECK(!sphera_cap_union_prepare(&u, sphera_cap_from_sphere(a.axis, -1.0f),
                                  sphera_cap_from_sphere(a.axis, NAN)));
  CHECK(sphera_cap_union_sample(&u, 0.5f, 0.5f).pdf == 0.0f);
  CHECK(sphera_cap_union_pdf(&u, a.axis) == 0.0f);
  CHECK(sphera_cap_union_solid_angle(&u) == 0.0f);
  /* Bad input anywhere: finite. */
  for (i = 0; i < nbad; i++) {
    for (j = 0; j < nbad; j++) {
      SpheraVec3 v = vec3(bad[i], 0.5f, bad[j]);
      SpheraCap garbage;
      SpheraSample s;
      garbage.axis = v;
      garbage.one_minus_cos = bad[j];
      garbage.one_plus_cos = bad[i];
      garbage.sin2 = bad[j];
      sphera_cap_union_prepare(&u, garbage, b);
      s = sphera_cap_union_sample(&u, bad[i], bad[j]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf) && s.pdf >= 0.0f);
      CHECK(isfinite(sphera_cap_union_pdf(&u, v)));
      CHECK(isfinite(sphera_cap_union_solid_angle(&u)));
    }
  }
}

static void check_pivot(void) {
  SpheraVec3 pivot = vec3(0.2f, -0.3f, 0.4f);
  SpheraVec3 w = vec3(0.6f, 0.0f, 0.8f);
  SpheraVec3 g = sphera_pivot_transform(w, pivot);
  SpheraVec3 back = sphera_pivot_transform(g, pivot);
  SpheraCap cap = sphera_cap_from_axis_cos(vec3(0.0f, 0.6f, 0.8f), 0.7f);
  SpheraCap image = sphera_pivot_transform_cap(cap, pivot);
  DVec3 e, p = dvec(pivot), wd = dvec(w);
  double pp = ddot(p, p), j;
  CHECK_ABS(dlength(dvec(g)), 1.0, 1e-6);
  CHECK_ABS(back.x, w.x, 1e-5);
  CHECK_ABS(back.y, w.y, 1e-5);
  CHECK_ABS(back.z, w.z, 1e-5);
  /* g(w) lies on the line from w through the pivot. */
  CHECK_ABS(dlength(dcross(dsub(dvec(g), p), dsub(wd, p))), 0.0, 1e-5);
  e = dsub(wd, p);
  j = (1.0 - pp) / ddot(e, e);
  CHECK_REL(sphera_pivot_jacobian(w, pivot), j * j, 1e-5);
  CHECK(cap_is_finite(image) && image.one_minus_cos > 0.0f);
  /* Pivot at the origin: the antipodal cap. */
  image = sphera_pivot_transform_cap(cap, vec3(0.0f, 0.0f, 0.0f));
  CHECK_ABS(image.axis.y, -0.6, 1e-6);
  CHECK_ABS(image.one_minus_cos, cap.one_minus_cos, 1e-6);
}

static void check_bad_input(void) {
  const float bad[] = {NAN, INFINITY, -INFINITY, 0.0f, -1.0f, 1e30f, -1e30f, 3e38f};
  const int n = (int)(sizeof(bad) / sizeof(bad[0]));
  int i, k;
  for (i = 0; i < n; i++) {
    for (k = 0; k < n; k++) {
      SpheraVec3 v = vec3(bad[i], 0.5f, bad[k]);
      SpheraCap cap = sphera_cap_from_sphere(v, bad[k]);
      SpheraCap garbage;
      SpheraSample s;
      SpheraVec3 g;
      CHECK(cap_is_finite(cap));
      CHECK(isfinite(sphera_cap_solid_angle(cap)));
      s = sphera_cap_sample_uniform(cap, bad[i], bad[k]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf) && s.pdf >= 0.0f);
      garbage.axis = v;
      garbage.one_minus_cos = bad[k];
      garbage.one_plus_cos = bad[i];
      garbage.sin2 = bad[k];
      CHECK(isfinite(sphera_cap_solid_angle(garbage)));
      CHECK(sphera_cap_solid_angle(garbage) >= 0.0f);
      s = sphera_cap_sample_uniform(garbage, bad[i], bad[k]);
      CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf) && s.pdf >= 0.0f);
      CHECK(isfinite(sphera_cap_pdf(garbage, v)));
      CHECK(isfinite(sphera_cap_intersection_solid_angle(garbage, cap)));
      CHECK(isfinite(sphera_cap_intersection_solid_angle_oat_sander(garbage, cap)));
      CHECK(cap_is_finite(sphera_cap_from_axis_cos(v, bad[i])));
      /* |pivot| >= 1, NaN, inf. */
      g = sphera_pivot_transform(vec3(0.0f, 0.6f, 0.8f), v);
      CHECK(vec3_is_finite(g));
      g = sphera_pivot_transform(v, vec3(0.1f, 0.2f, 0.3f));
      CHECK(vec3_is_finite(g));
      CHECK(isfinite(sphera_pivot_jacobian(vec3(0.0f, 0.6f, 0.8f), v)));
      CHECK(cap_is_finite(sphera_pivot_transform_cap(garbage, v)));
      CHECK(cap_is_finite(sphera_pivot_transform_cap(sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, 1.0f), 0.3f), v)));
    }
  }
  /* Invalid spheres give the empty cap: no samples. */
  CHECK(sphera_cap_solid_angle(sphera_cap_from_sphere(vec3(0.0f, 0.0f, 3.0f), 0.0f)) == 0.0f);
  CHECK(sphera_cap_solid_angle(sphera_cap_from_sphere(vec3(0.0f, 0.0f, 3.0f), -1.0f)) == 0.0f);
  CHECK(sphera_cap_sample_uniform(sphera_cap_from_sphere(vec3(0.0f, 0.0f, 3.0f), NAN), 0.5f, 0.5f)
            .pdf == 0.0f);
  /* Point inside the sphere: the whole sphere. */
  CHECK_REL(sphera_cap_solid_angle(sphera_cap_from_sphere(vec3(0.0f, 0.0f, 0.5f), 1.0f)),
            4.0 * PI_D, 1e-6);
}

/* A sphere prepared for solid angle sampling draws what sphera_cap_sample_uniform draws
 * from the same cap, bit for bit, with its pdf; bad input writes the empty value. */
static void check_solid_angle_sphere(void) {
  SpheraVec3 center = vec3(1.0f, 2.0f, 2.0f);
  SpheraCap cap = sphera_cap_from_sphere(center, 1.0f);
  SpheraSolidAngleSphere sphere, garbage;
  float u[U_COUNT];
  int i, j;
  CHECK(sphera_solid_angle_sphere_prepare(&sphere, center, 1.0f));
  CHECK(sphera_solid_angle_sphere_solid_angle(&sphere) == sphera_cap_solid_angle(cap));
  CHECK_REL(sphera_solid_angle_sphere_solid_angle(&sphere), 2.0 * PI_D * one_minus_cos_d(center, 1.0), 1e-6);
  fill_u_values(u);
  for (i = 0; i < U_COUNT; i++) {
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = sphera_solid_angle_sphere_sample(&sphere, u[i], u[j]);
      SpheraSample t = sphera_cap_sample_uniform(cap, u[i], u[j]);
      CHECK(s.pdf > 0.0f && s.pdf == t.pdf);
      CHECK(s.dir.x == t.dir.x && s.dir.y == t.dir.y && s.dir.z == t.dir.z);
      CHECK(sphera_solid_angle_sphere_pdf(&sphere, s.dir) == s.pdf);
    }
  }
  CHECK(sphera_solid_angle_sphere_pdf(&sphere, vec3(-1.0f, 0.0f, 0.0f)) == 0.0f);
  /* A cap by hand, and the whole sphere from inside. */
  CHECK(sphera_solid_angle_sphere_prepare_cap(&sphere, sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, 2.0f), -0.5f)));
  CHECK_REL(sphera_solid_angle_sphere_solid_angle(&sphere), 3.0 * PI_D, 1e-6);
  CHECK(sphera_solid_angle_sphere_prepare(&sphere, center, 4.0f));
  CHECK_REL(sphera_solid_angle_sphere_solid_angle(&sphere), 4.0 * PI_D, 1e-6);
  /* Bad input: false, the empty value over whatever the struct held. */
  memset(&garbage, 0xff, sizeof garbage);
  CHECK(!sphera_solid_angle_sphere_prepare(&garbage, vec3(NAN, 0.0f, 1.0f), 1.0f));
  CHECK(sphera_solid_angle_sphere_sample(&garbage, 0.5f, 0.5f).pdf == 0.0f);
  CHECK(vec3_is_finite(sphera_solid_angle_sphere_sample(&garbage, 0.5f, 0.5f).dir));
  CHECK(sphera_solid_angle_sphere_pdf(&garbage, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  CHECK(sphera_solid_angle_sphere_solid_angle(&garbage) == 0.0f);
  memset(&garbage, 0xff, sizeof garbage);
  CHECK(!sphera_solid_angle_sphere_prepare(&garbage, center, -1.0f));
  CHECK(sphera_solid_angle_sphere_solid_angle(&garbage) == 0.0f);
  memset(&garbage, 0xff, sizeof garbage);
  CHECK(!sphera_solid_angle_sphere_prepare(&garbage, center, INFINITY));
  CHECK(!sphera_solid_angle_sphere_prepare_cap(&garbage, sphera_cap_from_axis_cos(vec3(0.0f, 0.0f, 0.0f), 0.5f)));
  CHECK(sphera_solid_angle_sphere_sample(&garbage, 0.5f, 0.5f).pdf == 0.0f);
  /* Null pointers. */
  CHECK(!sphera_solid_angle_sphere_prepare(NULL, center, 1.0f));
  CHECK(!sphera_solid_angle_sphere_prepare_cap(NULL, cap));
  CHECK(sphera_solid_angle_sphere_sample(NULL, 0.5f, 0.5f).pdf == 0.0f);
  CHECK(sphera_solid_angle_sphere_pdf(NULL, vec3(0.0f, 0.0f, 1.0f)) == 0.0f);
  CHECK(sphera_solid_angle_sphere_solid_angle(NULL) == 0.0f);
}

int main(void) {
  check_good_caps();
  check_solid_angle_sphere();
  check_intersections();
  check_union();
  check_pivot();
  check_bad_input();
  return check_summary();
}
