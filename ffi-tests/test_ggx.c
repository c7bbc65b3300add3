/* C ABI tests of the BRDFs: GGX with visible-normal sampling (sphera_ggx_*) and Lambert
 * (sphera_lambert_*). References are the textbook formulas in double. */
#include <string.h>

#include "check.h"

#define PI 3.14159265358979323846

/* ---- the textbook GGX in double --------------------------------------------------- */

static DVec3 dnormalize(DVec3 a) { return dscale(a, 1.0 / dlength(a)); }

/* Directions as the library reads them: vectors within 1e-6 of unit length are taken
 * as they are (a float direction is unit only up to rounding), others are normalised.
 * At grazing views and small α the densities are so ill-conditioned that normalising
 * a float "unit" vector once more moves them by up to ~1e-3. */
static DVec3 as_direction(DVec3 a) {
  double length2 = ddot(a, a);
  return fabs(length2 - 1.0) <= 1e-6 ? a : dnormalize(a);
}

static double ggx_d(double alpha, DVec3 h) {
  double c = h.z / dlength(h), a2 = alpha * alpha;
  double t = c * c * (a2 - 1.0) + 1.0;
  return c <= 0.0 ? 0.0 : a2 / (PI * t * t);
}

static double ggx_lambda(double alpha, DVec3 w) {
  double c = w.z / dlength(w);
  double tan2 = (1.0 - c * c) / (c * c);
  return (-1.0 + sqrt(1.0 + alpha * alpha * tan2)) / 2.0;
}

/* G1(wo) D(h) / (4 cos θo), h = normalize(wo + wi); 0 below the horizon. */
static double ggx_pdf(double alpha, DVec3 wo, DVec3 wi) {
  DVec3 h;
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  wo = as_direction(wo);
  wi = as_direction(wi);
  h.x = wo.x + wi.x;
  h.y = wo.y + wi.y;
  h.z = wo.z + wi.z;
  h = dnormalize(h);
  return ggx_d(alpha, h) / (1.0 + ggx_lambda(alpha, wo)) / (4.0 * wo.z);
}

/* F D G2 / (4 cos θo cos θi) with Schlick's F for one channel. */
static double ggx_brdf(double alpha, double f0, DVec3 wo, DVec3 wi) {
  DVec3 h;
  double g2, fresnel;
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  wo = as_direction(wo);
  wi = as_direction(wi);
  h.x = wo.x + wi.x;
  h.y = wo.y + wi.y;
  h.z = wo.z + wi.z;
  h = dnormalize(h);
  g2 = 1.0 / (1.0 + ggx_lambda(alpha, wo) + ggx_lambda(alpha, wi));
  fresnel = f0 + (1.0 - f0) * pow(1.0 - ddot(wo, h), 5.0);
  return fresnel * ggx_d(alpha, h) * g2 / (4.0 * wo.z * wi.z);
}

/* x rounded to float through memory. (With GCC 12.2 at -O2, the SLP vectorizer was
 * seen to hand the double references the unrounded values of a direction built from
 * (float) casts, while the library got the rounded ones; -fno-tree-vectorize made it
 * go away. At grazing views a 1e-8 difference in a direction moves the densities by
 * 1e-4, so the reference must see exactly the floats the library sees.) */
static float to_float(double x) {
  volatile float rounded = (float)x;
  return rounded;
}

static SpheraVec3 direction(double theta, double phi) {
  return vec3(to_float(sin(theta) * cos(phi)), to_float(sin(theta) * sin(phi)), to_float(cos(theta)));
}

static SpheraVec3 view(double degrees) { return direction(degrees * PI / 180.0, 0.7); }

static int vec3_is_zero(SpheraVec3 v) { return v.x == 0.0f && v.y == 0.0f && v.z == 0.0f; }

/* The α and F0 of a prepared BRDF, from its behaviour rather than its private fields:
 * at wo = wi = z, D = 1 / (π α²), G2 = 1 and F = F0, so f = F0 / (4π α²). */
static double alpha_of(const SpheraGgxBrdf *brdf) {
  SpheraVec3 z = vec3(0.0f, 0.0f, 1.0f);
  return 1.0 / sqrt(4.0 * PI * sphera_ggx_brdf_eval_without_fresnel(brdf, z, z));
}

static SpheraVec3 f0_of(const SpheraGgxBrdf *brdf) {
  SpheraVec3 z = vec3(0.0f, 0.0f, 1.0f);
  SpheraVec3 f = sphera_ggx_brdf_eval(brdf, z, z);
  float scalar = sphera_ggx_brdf_eval_without_fresnel(brdf, z, z);
  return vec3(f.x / scalar, f.y / scalar, f.z / scalar);
}

static void check_f0(const SpheraGgxBrdf *brdf, double r, double g, double b) {
  SpheraVec3 f0 = f0_of(brdf);
  CHECK_ABS(f0.x, r, 1e-6);
  CHECK_ABS(f0.y, g, 1e-6);
  CHECK_ABS(f0.z, b, 1e-6);
}

static int is_no_sample(SpheraSample s) {
  return s.pdf == 0.0f && s.dir.x == 0.0f && s.dir.y == 0.0f && s.dir.z == 1.0f;
}

/* ---- good input ------------------------------------------------------------------- */

/* Samples on a grid of u: unit directions above the horizon whose pdf is
 * sphera_ggx_brdf_pdf of the direction and the double density; the estimator of the
 * albedo (F = 1) stays at most 1. Returns the estimate. */
static double check_sampling(const SpheraGgxBrdf *brdf, double alpha, SpheraVec3 wo, int n) {
  double sum = 0.0, worst = 0.0;
  int i, j, kept = 0;
  for (i = 0; i < n; i++) {
    for (j = 0; j < n; j++) {
      float u0 = ((float)i + 0.5f) / (float)n, u1 = ((float)j + 0.5f) / (float)n;
      SpheraSample s = sphera_ggx_brdf_sample(brdf, wo, u0, u1);
      double reference, f;
      if (s.pdf == 0.0f) {
        if (!CHECK(is_no_sample(s))) return -1.0;
        continue;
      }
      kept++;
      if (!CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf) && s.pdf > 0.0f && s.dir.z > 0.0f))
        return -1.0;
      if (!CHECK(fabs(dlength(dvec(s.dir)) - 1.0) < 1e-6)) return -1.0;
      if (!CHECK(sphera_ggx_brdf_pdf(brdf, wo, s.dir) == s.pdf)) return -1.0;
      reference = ggx_pdf(alpha, dvec(wo), dvec(s.dir));
      if (fabs(s.pdf - reference) / reference > worst) worst = fabs(s.pdf - reference) / reference;
      f = sphera_ggx_brdf_eval_without_fresnel(brdf, wo, s.dir);
      sum += f * s.dir.z / s.pdf;
    }
  }
  printf("  view (%.3f, %.3f, %.3f): %d of %d kept, worst pdf vs double %.2e, albedo %.6f\n",
         wo.x, wo.y, wo.z, kept, n * n, worst, sum / (n * n));
  CHECK(worst < 1e-5);
  CHECK(kept > 0);
  CHECK(sum / (n * n) <= 1.0 + 1e-3);
  return sum / (n * n);
}

static void check_good_input(void) {
  SpheraGgxBrdf brdf;
  const float roughness[4] = {0.1f, 0.4f, 0.8f, 1.0f};
  const double degrees[4] = {0.0, 45.0, 80.0, 89.0};
  int r, v, k;
  for (r = 0; r < 4; r++) {
    double alpha = (double)roughness[r] * (double)roughness[r];
    printf("roughness %.2f\n", roughness[r]);
    CHECK(sphera_ggx_brdf_prepare(&brdf, roughness[r], vec3(1.0f, 1.0f, 1.0f)));
    for (v = 0; v < 4; v++) {
      double albedo = check_sampling(&brdf, alpha, view(degrees[v]), 128);
      if (r == 0 && v == 0) CHECK(albedo > 0.99); /* smooth, normal incidence */
    }
  }

  /* eval against the double reference, symmetric in (wo, wi); Fresnel per channel. */
  CHECK(sphera_ggx_brdf_prepare(&brdf, 0.6f, vec3(0.04f, 0.5f, 1.0f)));
  for (k = 0; k < 64; k++) {
    SpheraVec3 wo = view(3.0 + 1.3 * k), wi;
    SpheraVec3 f, g;
    wi = direction((double)(k % 17) * 5.0 * PI / 180.0, 0.37 * k);
    f = sphera_ggx_brdf_eval(&brdf, wo, wi);
    g = sphera_ggx_brdf_eval(&brdf, wi, wo);
    CHECK(vec3_equal(f, g));
    CHECK_REL(f.x, ggx_brdf(0.36, 0.04f, dvec(wo), dvec(wi)), 2e-5);
    CHECK_REL(f.y, ggx_brdf(0.36, 0.5f, dvec(wo), dvec(wi)), 2e-5);
    CHECK_REL(f.z, ggx_brdf(0.36, 1.0f, dvec(wo), dvec(wi)), 2e-5);
    CHECK_REL(sphera_ggx_brdf_pdf(&brdf, wo, wi), ggx_pdf(0.36, dvec(wo), dvec(wi)), 2e-5);
  }
  {
    /* Mirror configuration at normal incidence: F = F0. */
    SpheraVec3 z = vec3(0.0f, 0.0f, 1.0f);
    SpheraVec3 f = sphera_ggx_brdf_eval(&brdf, z, z);
    float scalar = sphera_ggx_brdf_eval_without_fresnel(&brdf, z, z);
    CHECK_REL(f.x, 0.04 * scalar, 1e-6);
    CHECK_REL(f.y, 0.5 * scalar, 1e-6);
    CHECK_REL(f.z, 1.0 * scalar, 1e-6);
    /* Unnormalised directions are normalised. */
    CHECK_REL(sphera_ggx_brdf_pdf(&brdf, vec3(0.0f, 0.0f, 3.0f), vec3(0.1f, 0.0f, 2.0f)),
              ggx_pdf(0.36, dvec(z), dvec(vec3(0.1f, 0.0f, 2.0f))), 2e-5);
  }

  /* Lambert: cosine-weighted, pdf of the direction, albedo / π. */
  {
    int i, j;
    SpheraVec3 albedo = vec3(0.2f, 0.5f, 0.9f);
    double mean_z = 0.0;
    printf("lambert\n");
    for (i = 0; i < 256; i++) {
      for (j = 0; j < 256; j++) {
        SpheraSample s = sphera_lambert_sample(((float)i + 0.5f) / 256.0f, ((float)j + 0.5f) / 256.0f);
        if (!CHECK(s.pdf > 0.0f && s.dir.z > 0.0f && vec3_is_finite(s.dir))) return;
        CHECK_REL(s.pdf, s.dir.z / PI, 1e-6);
        CHECK(sphera_lambert_pdf(s.dir) == s.pdf);
        CHECK_ABS(dlength(dvec(s.dir)), 1.0, 1e-6);
        mean_z += s.dir.z;
      }
    }
    /* E[cos θ] under cos θ / π is 2/3. */
    CHECK_ABS(mean_z / 65536.0, 2.0 / 3.0, 2e-4);
    {
      SpheraVec3 f = sphera_lambert_eval(albedo, view(30.0), view(60.0));
      CHECK_REL(f.x, 0.2 / PI, 1e-6);
      CHECK_REL(f.y, 0.5 / PI, 1e-6);
      CHECK_REL(f.z, 0.9 / PI, 1e-6);
    }
    for (i = 0; i < U_COUNT; i++) {
      float u[U_COUNT];
      SpheraSample s;
      fill_u_values(u);
      s = sphera_lambert_sample(u[i], u[U_COUNT - 1 - i]);
      CHECK(s.pdf > 0.0f && s.dir.z > 0.0f && isfinite(s.pdf));
    }
  }
}

/* ---- bad input -------------------------------------------------------------------- */

static void check_outputs_finite(const SpheraGgxBrdf *brdf, SpheraVec3 wo, SpheraVec3 wi, float u0,
                                 float u1) {
  SpheraVec3 f = sphera_ggx_brdf_eval(brdf, wo, wi);
  SpheraSample s = sphera_ggx_brdf_sample(brdf, wo, u0, u1);
  float p = sphera_ggx_brdf_pdf(brdf, wo, wi);
  SpheraSample l = sphera_lambert_sample(u0, u1);
  SpheraVec3 lf = sphera_lambert_eval(wo, wo, wi);
  CHECK(vec3_is_finite(f) && f.x >= 0.0f && f.y >= 0.0f && f.z >= 0.0f);
  CHECK(vec3_is_finite(s.dir) && isfinite(s.pdf) && s.pdf >= 0.0f);
  CHECK(isfinite(p) && p >= 0.0f);
  CHECK(isfinite(sphera_ggx_brdf_eval_without_fresnel(brdf, wo, wi)));
  CHECK(vec3_is_finite(l.dir) && isfinite(l.pdf) && l.pdf > 0.0f);
  CHECK(vec3_is_finite(lf));
  CHECK(isfinite(sphera_lambert_pdf(wi)));
}

static void check_bad_input(void) {
  SpheraGgxBrdf brdf;
  SpheraVec3 good = view(30.0), other = view(50.0);
  const SpheraVec3 bad[] = {
      {0.0f, 0.0f, 0.0f},       {NAN, 0.0f, 1.0f},       {0.0f, NAN, 1.0f},
      {0.0f, 0.0f, NAN},        {INFINITY, 0.0f, 1.0f},  {0.0f, 0.0f, INFINITY},
      {0.0f, -INFINITY, 1.0f},  {0.3f, 0.2f, -0.9f},     {1.0f, 0.0f, 0.0f},
  };
  const float odd[] = {0.0f, 1e-45f, 1e-30f, 1.0f, 1e30f, 3e38f, -1.0f, NAN, INFINITY, -INFINITY};
  const int nbad = (int)(sizeof bad / sizeof bad[0]), nodd = (int)(sizeof odd / sizeof odd[0]);
  int i, j, k;
  printf("bad input\n");

  /* prepare: null out, non-finite parameters (still written), clamping. */
  CHECK(!sphera_ggx_brdf_prepare(NULL, 0.5f, vec3(0.04f, 0.04f, 0.04f)));
  CHECK(!sphera_ggx_brdf_prepare(&brdf, NAN, vec3(0.04f, 0.04f, 0.04f)));
  CHECK_REL(alpha_of(&brdf), SPHERA_GGX_MIN_ALPHA, 1e-5);
  CHECK(sphera_ggx_brdf_sample(&brdf, good, 0.3f, 0.6f).pdf > 0.0f);
  CHECK(!sphera_ggx_brdf_prepare(&brdf, INFINITY, vec3(0.04f, 0.04f, 0.04f)));
  CHECK_REL(alpha_of(&brdf), 1.0, 1e-6);
  CHECK(!sphera_ggx_brdf_prepare(&brdf, 0.5f, vec3(NAN, 0.5f, INFINITY)));
  CHECK_REL(alpha_of(&brdf), 0.25, 1e-6);
  check_f0(&brdf, 0.0, 0.5, 1.0);
  CHECK(sphera_ggx_brdf_prepare(&brdf, 0.0f, vec3(-1.0f, 2.0f, 0.5f)));
  CHECK_REL(alpha_of(&brdf), SPHERA_GGX_MIN_ALPHA, 1e-5);
  check_f0(&brdf, 0.0, 1.0, 0.5);
  CHECK(sphera_ggx_brdf_prepare(&brdf, 7.0f, vec3(0.04f, 0.04f, 0.04f)));
  CHECK_REL(alpha_of(&brdf), 1.0, 1e-6);
  CHECK(sphera_ggx_brdf_prepare(&brdf, 0.5f, vec3(0.04f, 0.04f, 0.04f)));
  CHECK_REL(alpha_of(&brdf), 0.25, 1e-6);

  /* Null BRDF. */
  CHECK(vec3_is_zero(sphera_ggx_brdf_eval(NULL, good, other)));
  CHECK(sphera_ggx_brdf_eval_without_fresnel(NULL, good, other) == 0.0f);
  CHECK(is_no_sample(sphera_ggx_brdf_sample(NULL, good, 0.5f, 0.5f)));
  CHECK(sphera_ggx_brdf_pdf(NULL, good, other) == 0.0f);

  /* Bad directions: 0 and no sample. */
  CHECK(sphera_ggx_brdf_prepare(&brdf, 0.4f, vec3(0.04f, 0.04f, 0.04f)));
  for (i = 0; i < nbad; i++) {
    CHECK(vec3_is_zero(sphera_ggx_brdf_eval(&brdf, bad[i], good)));
    CHECK(vec3_is_zero(sphera_ggx_brdf_eval(&brdf, good, bad[i])));
    CHECK(sphera_ggx_brdf_eval_without_fresnel(&brdf, bad[i], good) == 0.0f);
    CHECK(sphera_ggx_brdf_pdf(&brdf, bad[i], good) == 0.0f);
    CHECK(sphera_ggx_brdf_pdf(&brdf, good, bad[i]) == 0.0f);
    CHECK(is_no_sample(sphera_ggx_brdf_sample(&brdf, bad[i], 0.5f, 0.5f)));
    CHECK(vec3_is_zero(sphera_lambert_eval(vec3(1.0f, 1.0f, 1.0f), bad[i], good)));
    CHECK(vec3_is_zero(sphera_lambert_eval(vec3(1.0f, 1.0f, 1.0f), good, bad[i])));
    CHECK(sphera_lambert_pdf(bad[i]) == 0.0f);
  }

  /* Random numbers outside [0, 1) are clamped, NaN counts as 0. */
  {
    float last = nextafterf(1.0f, 0.0f);
    SpheraSample a = sphera_ggx_brdf_sample(&brdf, good, NAN, 0.3f);
    SpheraSample b = sphera_ggx_brdf_sample(&brdf, good, 0.0f, 0.3f);
    CHECK(memcmp(&a, &b, sizeof a) == 0);
    a = sphera_ggx_brdf_sample(&brdf, good, -5.0f, 0.3f);
    CHECK(memcmp(&a, &b, sizeof a) == 0);
    a = sphera_ggx_brdf_sample(&brdf, good, 0.3f, 2.0f);
    b = sphera_ggx_brdf_sample(&brdf, good, 0.3f, last);
    CHECK(memcmp(&a, &b, sizeof a) == 0);
    a = sphera_ggx_brdf_sample(&brdf, good, 0.3f, INFINITY);
    CHECK(memcmp(&a, &b, sizeof a) == 0);
    a = sphera_lambert_sample(INFINITY, -INFINITY);
    b = sphera_lambert_sample(last, 0.0f);
    CHECK(memcmp(&a, &b, sizeof a) == 0);
  }

  /* Every combination of odd coordinates and random numbers: finite outputs. */
  for (k = 0; k < 2; k++) {
    if (k == 1) CHECK(sphera_ggx_brdf_prepare(&brdf, 0.0f, vec3(1.0f, 1.0f, 1.0f)));
    for (i = 0; i < nodd; i++) {
      for (j = 0; j < nodd; j++) {
        SpheraVec3 wo = vec3(odd[i], 0.3f, odd[j]), wi = vec3(-0.2f, odd[j], odd[i]);
        check_outputs_finite(&brdf, wo, wi, odd[i], odd[j]);
        check_outputs_finite(&brdf, vec3(1.0f, 0.0f, odd[i]), vec3(-1.0f, 0.0f, odd[j]), odd[j], odd[i]);
      }
    }
  }
}

int main(void) {
  check_good_input();
  check_bad_input();
  return check_summary();
}
