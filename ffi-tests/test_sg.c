/* C ABI tests of spherical Gaussians, vMF sampling, lobes, ASGs and VSGL shading
 * (sphera_sg_*, sphera_asg_*). */
#include <float.h>
#include <stddef.h>
#include <string.h>

#include "check.h"

static const double PI_D = 3.14159265358979323846;

static int sg_is_finite(SpheraSg s) {
  return vec3_is_finite(s.axis) && isfinite(s.sharpness) && isfinite(s.log_amplitude) &&
         s.sharpness >= 0.0f && s.sharpness <= SPHERA_SG_MAX_SHARPNESS;
}

static int asg_is_finite(SpheraAsg a) {
  return vec3_is_finite(a.x) && vec3_is_finite(a.y) && vec3_is_finite(a.z) && isfinite(a.eta_x) &&
         isfinite(a.eta_y) && isfinite(a.amplitude);
}

/* A(lambda) in double. */
static double a_d(double l) { return l < 1e-12 ? 4.0 * PI_D : 2.0 * PI_D / l * (1.0 - exp(-2.0 * l)); }

static void check_algebra(void) {
  SpheraVec3 z = vec3(0.0f, 0.0f, 1.0f);
  SpheraSg a = sphera_sg_new(vec3(0.0f, 0.0f, 2.0f), 10.0f, 3.0f);
  SpheraSg b = sphera_sg_new(vec3(0.0f, 0.6f, 0.8f), 5.0f, 0.5f);
  SpheraSg p = sphera_sg_product(a, b);
  SpheraVec3 w = vec3(0.0f, 0.2f, 0.979795897f);
  double l_m;
  CHECK(sg_is_finite(a));
  CHECK_ABS(a.axis.z, 1.0, 1e-7);
  CHECK_REL(sphera_sg_eval(a, z), 3.0, 1e-6);
  CHECK_REL(sphera_sg_eval(a, w), 3.0 * exp(10.0 * (0.979795897 - 1.0)), 1e-5);
  CHECK_REL(sphera_sg_integral(0.0f), 4.0 * PI_D, 1e-7);
  CHECK_REL(sphera_sg_integral(1e-4f), a_d(1e-4), 1e-6);
  CHECK_REL(sphera_sg_integral(3.0f), a_d(3.0), 1e-6);
  CHECK_REL(sphera_sg_integral(1e6f), a_d(1e6), 1e-6);
  /* The product evaluates to the product, and integrates to the inner product. */
  CHECK_REL(sphera_sg_eval(p, w), (double)sphera_sg_eval(a, w) * sphera_sg_eval(b, w), 1e-4);
  l_m = sqrt(100.0 + 25.0 + 2.0 * 50.0 * 0.8);
  CHECK_REL(p.sharpness, l_m, 1e-5);
  CHECK_REL(sphera_sg_inner_product(a, b), 1.5 * exp(l_m - 15.0) * a_d(l_m), 1e-4);
  /* Opposite sharp lobes: a constant e^{-2 lambda}, no NaN. */
  {
    SpheraSg s = sphera_sg_new(z, 1e6f, 1.0f);
    SpheraSg t = sphera_sg_new(vec3(0.0f, 0.0f, -1.0f), 1e6f, 1.0f);
    SpheraSg q = sphera_sg_product(s, t);
    CHECK(sg_is_finite(q) && q.sharpness == 0.0f);
    CHECK(sphera_sg_inner_product(s, t) == 0.0f);
    CHECK_REL(q.log_amplitude, -2e6, 1e-6);
  }
}

static void check_vmf(void) {
  float u[U_COUNT];
  float lambdas[4] = {0.0f, 1e-4f, 2.0f, 1e5f};
  int i, j, k;
  fill_u_values(u);
  for (k = 0; k < 4; k++) {
    SpheraSg s = sphera_sg_new(vec3(0.3f, -0.4f, 0.5f), lambdas[k], 7.0f);
    for (i = 0; i < U_COUNT; i++) {
      for (j = 0; j < U_COUNT; j++) {
        SpheraSample x = sphera_vmf_sample(s, u[i], u[j]);
        float inverse[2] = {-1.0f, -1.0f};
        double t = 1.0 - ddot(dvec(x.dir), dvec(s.axis));
        double l = s.sharpness;
        double pdf = l < 1e-12 ? 1.0 / (4.0 * PI_D) : l * exp(-l * t) / (2.0 * PI_D * (1.0 - exp(-2.0 * l)));
        CHECK(vec3_is_finite(x.dir) && x.pdf > 0.0f && isfinite(x.pdf));
        CHECK_ABS(dlength(dvec(x.dir)), 1.0, 1e-6);
        if (l < 1e3) {
          CHECK_REL(x.pdf, pdf, 1e-4);
        }
        CHECK(sphera_vmf_pdf(s, x.dir) == x.pdf);
        CHECK(sphera_vmf_invert(s, x.dir, inverse));
        CHECK(inverse[0] >= 0.0f && inverse[0] <= 1.0f && inverse[1] >= 0.0f && inverse[1] < 1.0f);
        if (u_is_interior(i) && l < 1e3) {
          CHECK_ABS(inverse[0], u[i], 1e-3);
        }
      }
    }
  }
}

static void check_lobes_and_shading(void) {
  SpheraVec3 n = vec3(0.0f, 0.0f, 1.0f);
  SpheraVec3 view = vec3(0.5f, 0.0f, 0.8660254f);
  SpheraSg d = sphera_sg_from_lambert(n);
  SpheraSg s = sphera_sg_from_ggx(n, view, 0.09f);
  SpheraSg lobe = sphera_sg_new(vec3(0.0f, 0.0f, -1.0f), 4.0f, 10.0f);
  SpheraSg l_in = sphera_sg_incoming_radiance(lobe, vec3(0.0f, 1.0f, 3.0f), 0.04f);
  SpheraAsg g = sphera_asg_from_ggx(n, view, 0.09f);
  double exact;
  CHECK(d.sharpness == (float)SPHERA_SG_DIFFUSE_LOBE_SHARPNESS);
  CHECK_REL(exp(d.log_amplitude) * a_d(d.sharpness), 1.0, 1e-5);
  CHECK_ABS(s.axis.x, -0.5, 1e-6);
  CHECK_REL(s.sharpness, (2.0 / (0.09 * 0.09)) / (4.0 * 0.8660254), 1e-5);
  CHECK_REL(exp(s.log_amplitude) * a_d(s.sharpness), 1.0, 1e-4);
  CHECK_REL(sphera_sg_from_ggx_unnormalized(n, view, 0.09f).sharpness, s.sharpness, 1e-7);
  /* Eq. 7 with the planar Gaussian's s^2 = sigma^2/2 = 0.02 (README, issue 20):
   * lambda_sigma = 10 / 0.02 = 500 toward (0, 1, 3)/sqrt(10). */
  CHECK(sg_is_finite(l_in));
  CHECK(l_in.sharpness > 500.0f && l_in.sharpness < 504.0f);
  exact = 10.0 / (2.0 * PI_D * 0.02) * exp(4.0 * (3.0 / sqrt(10.0) - 1.0));
  CHECK_REL(sphera_sg_eval(l_in, vec3(0.0f, 1.0f, 3.0f)), exact, 1e-3);
  /* Diffuse: three forms agree to a few percent for this narrow lobe. */
  {
    float product = sphera_sg_diffuse_shading_product(l_in, n, 0.5f, 1.0f);
    float constant = sphera_sg_diffuse_shading_constant_cosine(l_in, n, 0.5f, 1.0f);
    float sharp = sphera_sg_diffuse_shading_sharp_lobe(l_in, n, 0.5f, 1.0f);
    CHECK(product > 0.0f && constant > 0.0f && sharp > 0.0f);
    CHECK_REL(sharp, constant, 0.01);
    CHECK_REL(product, constant, 0.1);
    CHECK_REL(sphera_sg_diffuse_shading_constant_cosine(l_in, n, 0.5f, 0.25f), 0.25 * constant, 1e-5);
  }
  /* Specular: the ASG's axis is the reflection, narrower across the plane. */
  CHECK(asg_is_finite(g));
  CHECK_ABS(g.z.x, -0.5, 1e-6);
  CHECK(g.eta_y > g.eta_x);
  CHECK_REL(g.eta_x, 1.0 / (4.0 * 0.09 * 0.09), 1e-5);
  {
    SpheraSg toward = sphera_sg_new(vec3(-0.5f, 0.0f, 0.8660254f), 1e4f, 1.0f);
    float asg = sphera_sg_specular_shading(toward, n, view, 0.3f, 0.04f, 1.0f);
    float sg = sphera_sg_specular_shading_sg(toward, n, view, 0.3f, 0.04f, 1.0f);
    CHECK(asg > 0.0f && sg > 0.0f);
    CHECK_REL(asg, sg, 0.01);
    CHECK(sphera_sg_specular_shading(toward, n, vec3(0.0f, 0.6f, -0.8f), 0.3f, 0.04f, 1.0f) == 0.0f);
  }
  /* ASG algebra. */
  {
    SpheraAsg h = sphera_asg_new(vec3(1.0f, 0.0f, 0.0f), n, 100.0f, 400.0f, 2.0f);
    SpheraSg narrow = sphera_sg_new(n, 1e6f, 1.0f);
    CHECK_REL(sphera_asg_eval(h, n), 2.0, 1e-6);
    CHECK_REL(sphera_asg_integral(h), 2.0 * PI_D / 200.0, 1e-6);
    CHECK_ABS(h.y.y, 1.0, 1e-6);
    CHECK_REL(sphera_asg_convolve_sg(h, narrow), 2.0 * a_d(1e6), 1e-3);
  }
}

/* Beckmann's rho_s cos = F D G2 / (4 cos theta_o) in double for the normal z, written
 * here: D = exp(-tan^2/alpha^2) / (pi alpha^2 cos^4) at the half vector, Smith's
 * Lambda = (exp(-a^2)/(a sqrt(pi)) - erfc(a))/2 with a = cos/(alpha sin), G2 = 1/(1 +
 * Lambda_o + Lambda_i), Schlick's F. */
static double beckmann_lambda_d(double alpha, double c) {
  double a = c / (alpha * sqrt(1.0 - c * c));
  return 0.5 * (exp(-a * a) / (a * sqrt(PI_D)) - erfc(a));
}

static double beckmann_cos_d(const double wo[3], const double wi[3], double alpha, double f0) {
  double h[3], len, c2, d, g2, f, m;
  int i;
  for (i = 0; i < 3; i++) h[i] = wo[i] + wi[i];
  len = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  for (i = 0; i < 3; i++) h[i] /= len;
  c2 = h[2] * h[2];
  d = exp(-(1.0 - c2) / c2 / (alpha * alpha)) / (PI_D * alpha * alpha * c2 * c2);
  g2 = 1.0 / (1.0 + beckmann_lambda_d(alpha, wo[2]) + beckmann_lambda_d(alpha, wi[2]));
  m = 1.0 - (wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2]);
  f = f0 + (1.0 - f0) * m * m * m * m * m;
  return f * d * g2 / (4.0 * wo[2]);
}

/* The Beckmann lobe: the paper's lambda_h = 2/alpha^2, so the same SG and ASG as the GGX
 * ones; shading with a delta-like light at the reflection direction gives Beckmann's
 * BRDF there (written above), and differs from GGX's at a grazing, rough view. */
static void check_beckmann(void) {
  SpheraVec3 n = vec3(0.0f, 0.0f, 1.0f);
  SpheraVec3 view = vec3(0.5f, 0.0f, 0.8660254f);
  SpheraSg b = sphera_sg_from_beckmann(n, view, 0.09f);
  SpheraSg s = sphera_sg_from_ggx(n, view, 0.09f);
  SpheraSg bu = sphera_sg_from_beckmann_unnormalized(n, view, 0.09f);
  SpheraAsg ab = sphera_asg_from_beckmann(n, view, 0.09f);
  SpheraAsg ag = sphera_asg_from_ggx(n, view, 0.09f);
  int i, j;
  CHECK(sg_is_finite(b) && sg_is_finite(bu) && asg_is_finite(ab));
  CHECK_ABS(b.axis.x, -0.5, 1e-6);
  CHECK_REL(b.sharpness, (2.0 / (0.09 * 0.09)) / (4.0 * 0.8660254), 1e-5);
  CHECK(b.sharpness == s.sharpness && b.log_amplitude == s.log_amplitude);
  CHECK_REL(exp(b.log_amplitude) * a_d(b.sharpness), 1.0, 1e-4);
  CHECK(bu.sharpness == b.sharpness && bu.log_amplitude == 0.0f);
  CHECK(ab.eta_x == ag.eta_x && ab.eta_y == ag.eta_y && ab.z.x == ag.z.x);
  for (i = 0; i < 3; i++) {
    double deg[3] = {0.0, 45.0, 75.0};
    double t = deg[i] * PI_D / 180.0;
    SpheraVec3 v = vec3((float)sin(t), 0.0f, (float)cos(t));
    SpheraVec3 r = vec3(-(float)sin(t), 0.0f, (float)cos(t));
    SpheraSg toward = sphera_sg_new(r, SPHERA_SG_MAX_SHARPNESS, 1.0f);
    for (j = 0; j < 3; j++) {
      float roughness[3] = {0.2f, 0.5f, 0.9f};
      double alpha = (double)roughness[j] * roughness[j];
      double wo[3], wi[3], exact;
      float asg, sg, ggx;
      wo[0] = v.x;
      wo[1] = v.y;
      wo[2] = v.z;
      wi[0] = r.x;
      wi[1] = r.y;
      wi[2] = r.z;
      exact = sphera_sg_integral(toward.sharpness) * beckmann_cos_d(wo, wi, alpha, 0.04);
      asg = sphera_sg_beckmann_specular_shading(toward, n, v, roughness[j], 0.04f, 1.0f);
      sg = sphera_sg_beckmann_specular_shading_sg(toward, n, v, roughness[j], 0.04f, 1.0f);
      ggx = sphera_sg_specular_shading(toward, n, v, roughness[j], 0.04f, 1.0f);
      CHECK_REL(asg, exact, 2e-3);
      CHECK_REL(sg, exact, 2e-3);
      if (i == 2 && j == 2) CHECK(fabs(ggx - asg) > 1e-2 * asg);
    }
  }
  CHECK(sphera_sg_beckmann_specular_shading(sphera_sg_new(n, 100.0f, 1.0f), n,
                                            vec3(0.0f, 0.6f, -0.8f), 0.3f, 0.04f, 1.0f) == 0.0f);
}

static void check_bad_input(void) {
  float bad[7] = {NAN, INFINITY, -INFINITY, -1.0f, 0.0f, 1e-45f, FLT_MAX};
  SpheraVec3 vectors[5];
  float u[2];
  int i, j, k;
  vectors[0] = vec3(0.0f, 0.0f, 0.0f);
  vectors[1] = vec3(NAN, 0.0f, 1.0f);
  vectors[2] = vec3(INFINITY, 0.0f, 0.0f);
  vectors[3] = vec3(FLT_MAX, FLT_MAX, FLT_MAX);
  vectors[4] = vec3(0.0f, 0.0f, 1.0f);
  for (i = 0; i < 5; i++) {
    for (j = 0; j < 7; j++) {
      SpheraSg hand;
      SpheraAsg ahand;
      SpheraSg s = sphera_sg_new(vectors[i], bad[j], bad[j]);
      hand.axis = vectors[i];
      hand.sharpness = bad[j];
      hand.log_amplitude = bad[j];
      ahand.x = vectors[i];
      ahand.y = vectors[i];
      ahand.z = vectors[i];
      ahand.eta_x = bad[j];
      ahand.eta_y = bad[j];
      ahand.amplitude = bad[j];
      CHECK(sg_is_finite(s));
      CHECK(asg_is_finite(sphera_asg_new(vectors[i], vectors[i], bad[j], bad[j], bad[j])));
      CHECK(asg_is_finite(sphera_asg_from_ggx(vectors[i], vectors[4], bad[j])));
      CHECK(sg_is_finite(sphera_sg_from_ggx(vectors[i], vectors[4], bad[j])));
      CHECK(asg_is_finite(sphera_asg_from_beckmann(vectors[i], vectors[4], bad[j])));
      CHECK(sg_is_finite(sphera_sg_from_beckmann(vectors[i], vectors[4], bad[j])));
      CHECK(sg_is_finite(sphera_sg_from_beckmann_unnormalized(vectors[4], vectors[i], bad[j])));
      CHECK(isfinite(sphera_sg_integral(bad[j])) && sphera_sg_integral(bad[j]) > 0.0f);
      for (k = 0; k < 5; k++) {
        SpheraSg l_in = sphera_sg_incoming_radiance(hand, vectors[k], bad[j]);
        SpheraSample x = sphera_vmf_sample(hand, bad[j], bad[j]);
        float values[13];
        int m;
        values[0] = sphera_sg_eval(hand, vectors[k]);
        values[1] = sphera_sg_inner_product(hand, s);
        values[2] = sphera_vmf_pdf(hand, vectors[k]);
        values[3] = sphera_sg_diffuse_shading_product(l_in, vectors[k], bad[j], bad[j]);
        values[4] = sphera_sg_diffuse_shading_constant_cosine(l_in, vectors[k], bad[j], 1.0f);
        values[5] = sphera_sg_diffuse_shading_sharp_lobe(l_in, vectors[k], 1.0f, bad[j]);
        values[6] = sphera_sg_specular_shading(l_in, vectors[i], vectors[k], bad[j], bad[j], 1.0f);
        values[7] = sphera_sg_specular_shading_sg(l_in, vectors[k], vectors[4], bad[j], 0.5f, 1.0f);
        values[8] = sphera_asg_eval(ahand, vectors[k]);
        values[9] = sphera_asg_integral(ahand);
        values[10] = sphera_asg_convolve_sg(ahand, hand);
        values[11] = sphera_sg_beckmann_specular_shading(l_in, vectors[i], vectors[k], bad[j], bad[j], 1.0f);
        values[12] = sphera_sg_beckmann_specular_shading_sg(l_in, vectors[k], vectors[4], bad[j], 0.5f, bad[j]);
        for (m = 0; m < 13; m++) {
          CHECK(isfinite(values[m]) && values[m] >= 0.0f);
        }
        CHECK(sg_is_finite(l_in));
        CHECK(sg_is_finite(sphera_sg_product(hand, l_in)));
        CHECK(vec3_is_finite(x.dir) && isfinite(x.pdf) && x.pdf >= 0.0f);
        (void)sphera_vmf_invert(hand, vectors[k], u);
      }
    }
  }
  /* Zero axis: no sample; null output: false. */
  {
    SpheraSg zero;
    zero.axis = vec3(0.0f, 0.0f, 0.0f);
    zero.sharpness = 1.0f;
    zero.log_amplitude = 0.0f;
    CHECK(sphera_vmf_sample(zero, 0.5f, 0.5f).pdf == 0.0f);
    CHECK(!sphera_vmf_invert(sphera_sg_new(vec3(0.0f, 0.0f, 1.0f), 1.0f, 1.0f),
                                vec3(0.0f, 0.0f, 1.0f), NULL));
    CHECK(!sphera_vmf_invert(zero, vec3(0.0f, 0.0f, 1.0f), u));
  }
}

/* The prepared shading point: the same bits as the free functions for valid points
 * (a grid of views, roughnesses, f0 and lobes, grazing and below-horizon views
 * included); a failed prepare (zero or non-finite normal or view) writes the empty
 * point, which shades to zeros; a null point shades to zeros, a null `out` is false. */
static void check_shading_point(void) {
  static const float VIEWS[][3] = {{0.5f, 0.0f, 0.8660254f}, {0.0f, 0.0f, 2.0f}, {0.3f, -0.2f, 0.01f},
                                   {0.6f, 0.0f, -0.8f}, {-1e20f, 3e19f, 1e20f}, {1e-30f, 0.0f, 2e-30f}};
  static const float ROUGHNESS[] = {0.0f, 0.09f, 0.3f, 0.8f, 1.0f, 2.0f, NAN};
  static const float F0[] = {0.04f, 1.0f, -1.0f, NAN};
  SpheraVec3 n = vec3(0.0f, 0.3f, 2.0f);
  SpheraSg lobes[4];
  SpheraSgShadingPoint point;
  SpheraSgShading s;
  int v, r, f, l, positive = 0;
  lobes[0] = sphera_sg_incoming_radiance(sphera_sg_new(vec3(0.0f, 0.0f, -1.0f), 4.0f, 10.0f), vec3(0.0f, 1.0f, 3.0f), 0.04f);
  lobes[1] = sphera_sg_incoming_radiance(sphera_sg_new(vec3(0.3f, 0.1f, -1.0f), 40.0f, 2.0f), vec3(-1.0f, 0.5f, 2.0f), 0.5f);
  lobes[2] = sphera_sg_new(vec3(-0.5f, 0.0f, 0.8660254f), 1e4f, 1.0f);
  lobes[3] = sphera_sg_new(vec3(0.0f, 0.0f, -1.0f), 1.0f, 1.0f);
  for (v = 0; v < 6; v++)
    for (r = 0; r < 7; r++)
      for (f = 0; f < 4; f++) {
        SpheraVec3 view = vec3(VIEWS[v][0], VIEWS[v][1], VIEWS[v][2]);
        CHECK(sphera_sg_shading_point_prepare(&point, n, view, ROUGHNESS[r], F0[f]));
        for (l = 0; l < 4; l++) {
          float d = sphera_sg_diffuse_shading_constant_cosine(lobes[l], n, 0.7f, 0.5f);
          float sp = sphera_sg_specular_shading(lobes[l], n, view, ROUGHNESS[r], F0[f], 0.5f);
          s = sphera_sg_shading_point_shade(&point, lobes[l], 0.7f, 0.5f);
          CHECK(memcmp(&s.diffuse, &d, sizeof d) == 0 && memcmp(&s.specular, &sp, sizeof sp) == 0);
          positive += d > 0.0f && sp > 0.0f;
        }
      }
  CHECK(positive > 100);
  /* Bad input. */
  CHECK(!sphera_sg_shading_point_prepare(NULL, n, vec3(0.0f, 0.0f, 1.0f), 0.5f, 0.04f));
  CHECK(sphera_sg_shading_point_prepare(&point, n, vec3(0.0f, 0.0f, 1.0f), 0.5f, 0.04f));
  CHECK(!sphera_sg_shading_point_prepare(&point, vec3(0.0f, 0.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f), 0.5f, 0.04f));
  s = sphera_sg_shading_point_shade(&point, lobes[0], 1.0f, 1.0f);
  CHECK(s.diffuse == 0.0f && s.specular == 0.0f);
  CHECK(!sphera_sg_shading_point_prepare(&point, n, vec3(NAN, 0.0f, 1.0f), 0.5f, 0.04f));
  CHECK(!sphera_sg_shading_point_prepare(&point, vec3(0.0f, INFINITY, 1.0f), n, 0.5f, 0.04f));
  s = sphera_sg_shading_point_shade(&point, lobes[0], 1.0f, 1.0f);
  CHECK(s.diffuse == 0.0f && s.specular == 0.0f);
  s = sphera_sg_shading_point_shade(NULL, lobes[0], 1.0f, 1.0f);
  CHECK(s.diffuse == 0.0f && s.specular == 0.0f);
  /* Non-finite albedo, visibility and lobe: finite, non-negative. */
  CHECK(sphera_sg_shading_point_prepare(&point, n, vec3(0.5f, 0.0f, 0.8660254f), 0.3f, 0.04f));
  {
    SpheraSg raw = lobes[2];
    raw.sharpness = NAN;
    raw.log_amplitude = INFINITY;
    s = sphera_sg_shading_point_shade(&point, raw, INFINITY, NAN);
    CHECK(isfinite(s.diffuse) && s.diffuse >= 0.0f && isfinite(s.specular) && s.specular >= 0.0f);
    s = sphera_sg_shading_point_shade(&point, raw, FLT_MAX, 1.0f);
    CHECK(isfinite(s.diffuse) && s.diffuse >= 0.0f && isfinite(s.specular) && s.specular >= 0.0f);
    raw.axis = vec3(NAN, 0.0f, 0.0f);
    s = sphera_sg_shading_point_shade(&point, raw, 1.0f, 1.0f);
    CHECK(s.diffuse == 0.0f && s.specular == 0.0f);
  }
}

static void check_layout(void) {
  CHECK(sizeof(SpheraSg) == 5 * sizeof(float));
  CHECK(offsetof(SpheraSg, sharpness) == 3 * sizeof(float));
  CHECK(offsetof(SpheraSg, log_amplitude) == 4 * sizeof(float));
  CHECK(sizeof(SpheraAsg) == 12 * sizeof(float));
  CHECK(offsetof(SpheraAsg, z) == 6 * sizeof(float));
  CHECK(offsetof(SpheraAsg, amplitude) == 11 * sizeof(float));
  CHECK(sizeof(SpheraSgShading) == 2 * sizeof(float));
  CHECK(offsetof(SpheraSgShading, specular) == sizeof(float));
  CHECK(sizeof(SpheraSgShadingPoint) == 23 * sizeof(float));
}

int main(void) {
  check_algebra();
  check_vmf();
  check_lobes_and_shading();
  check_beckmann();
  check_bad_input();
  check_shading_point();
  check_layout();
  return check_summary();
}
