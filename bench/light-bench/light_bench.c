/* Benchmark of the non-polygon families of the C ABI (include/sphera.h) and of the LTC
 * polygon light, as a renderer calls them: "prepare + 1 sample" (one prepare per
 * sample) and "per sample" (many samples from structs prepared beforehand), in ns per
 * call, each row against a minimal C baseline written here (or, for the LTC polygon
 * light, against the library's projected polygon sampler alone).
 *
 * Three pools of 1024 inputs, generated deterministically (SplitMix64):
 *   spheres:  sphere lights (distance log-uniform in [1, 4], sin²θmax uniform in
 *             [0.06, 0.44], centre direction uniform over the upper hemisphere), each
 *             with a view and a GGX roughness; the C baselines are cone sampling
 *             (uniform in the cone with a frame built from the axis, pdf
 *             1/(2π(1 − cos θmax))) and cone + GGX visible-normal sampling;
 *   brdf:     views (cos θo uniform in [0.1, 1]), roughness uniform in [0.1, 0.9]
 *             (α = roughness²) and a direction above the horizon for the pdf rows; the
 *             C baselines are Heitz 2018's visible-normal sampling of GGX with its pdf,
 *             and cosine-weighted hemisphere sampling (the floor);
 *   polygons: quads above the horizon (half with the zenith inside), each with a view
 *             and a roughness; the baseline is sphera's projected solid angle sampler;
 *   vsgls:    one lobe of a VSGL (Tokuyoshi 2016) each: emission axis facing the shading
 *             point within 60°, sharpness log-uniform in [1, 100], amplitude 1/A(λ), its
 *             mean at a distance log-uniform in [1, 4] in the upper hemisphere, its
 *             positional standard deviation 0.05–0.5 times that distance; a view and a
 *             roughness; the normal is z. The C baselines are the paper's shading of one
 *             lobe written in linear space (Eq. 6–7, the constant-cosine diffuse term,
 *             the ASG specular term) and von Mises–Fisher sampling as Jakob 2012 writes
 *             it.
 *
 * Timing: thread CPU time, best of R repetitions of N calls, the techniques interleaved
 * within each repetition. Every pdf and dir.x goes into a checksum printed at the end.
 * Every C baseline is checked before timing (its pdf against the library's, its samples
 * inside their support, its sample means against the expected ones), and the bench
 * exits 1 when a check fails or when a technique yields no valid sample.
 *
 *   light_bench [--quick] [--reps R] [--calls N] [--only NAME[,NAME...]] [--pool ID]
 *
 * --quick is 1 repetition of 2000 calls (it checks that everything runs; no timing is
 * asserted). --only runs only the named techniques (a ratio column needs the row's
 * baseline among them); --pool only the pool with that id (spheres, brdf, polygons,
 * vsgls).
 * Both serve profiling, e.g. under callgrind with --toggle-collect=loop_prepare_cap. */
#define _POSIX_C_SOURCE 199309L

#include "../bench-common.h"

enum { MAX_V = SPHERA_MAX_POLYGON_VERTICES, QUAD = 4 };

static const float PI_F = 3.14159265358979323846f;

enum Family { SPHERES, BRDF, POLYGONS, VSGLS, FAMILY_COUNT };

/* One input: what every family reads (each pool fills what its family needs). */
typedef struct {
  float center[3]; /* sphere centre relative to the shading point */
  float radius;
  float wo[3]; /* unit view direction above the horizon */
  float roughness;
  SpheraGgxPivot fit; /* the view's SPTD fit, once per shading point (sptd_fit) */
  float dir[3]; /* unit direction above the horizon, for the pdf rows */
  int n;
  float v[QUAD][3]; /* polygon vertices */
  /* a VSGL lobe (vsgls): `center` is its positional mean */
  float lobe_axis[3]; /* unit emission axis ξ_v */
  float sharpness;    /* λ_v */
  float amplitude;    /* c_v */
  float variance;     /* positional variance σ_v² = E‖y − μ‖² */
} Input;

typedef struct {
  const char *id;
  const char *title;
  enum Family family;
  Input inputs[POOL_SIZE];
} Pool;

/* ---- the C baselines: what a renderer author would write --------------------------- */

/* max(x, lo) as a comparison, as renderers write it (fmaxf is a call at -O2: its NaN
 * rules keep the compiler from using the max instruction). */
static float at_least(float x, float lo) { return x > lo ? x : lo; }

/* Cone sampling: directions uniform in solid angle within θmax of the axis. With
 * cos θ uniform in [cos θmax, 1] (the solid angle of the band above cos θ is linear in
 * cos θ), cos θ = (1 − u0) + u0 cos θmax, φ = 2π u1, mapped by an orthonormal frame
 * whose third vector is the axis; pdf = 1 / (2π (1 − cos θmax)). The frame is the
 * branchless one of Duff et al. 2017 ("Building an orthonormal basis, revisited"). No
 * checks, no care for tiny cones (1 − cos θmax computed as it stands). */
struct ConeC {
  float x[3], y[3], z[3];
  float cos_max;
  float pdf;
};

NOINLINE static void cone_prepare(struct ConeC *out, const float *center, float radius) {
  float d2 = center[0] * center[0] + center[1] * center[1] + center[2] * center[2];
  float sin2 = radius * radius / d2;
  float cos_max = sqrtf(at_least(1.0f - sin2, 0.0f));
  float inv = 1.0f / sqrtf(d2);
  float nx = center[0] * inv, ny = center[1] * inv, nz = center[2] * inv;
  float sign = copysignf(1.0f, nz);
  float a = -1.0f / (sign + nz);
  float b = nx * ny * a;
  out->x[0] = 1.0f + sign * nx * nx * a;
  out->x[1] = sign * b;
  out->x[2] = -sign * nx;
  out->y[0] = b;
  out->y[1] = sign + ny * ny * a;
  out->y[2] = -ny;
  out->z[0] = nx;
  out->z[1] = ny;
  out->z[2] = nz;
  out->cos_max = cos_max;
  out->pdf = 1.0f / (2.0f * PI_F * (1.0f - cos_max));
}

NOINLINE static SpheraSample cone_sample(const struct ConeC *c, float u0, float u1) {
  SpheraSample s;
  float cos_t = (1.0f - u0) + u0 * c->cos_max;
  float sin_t = sqrtf(at_least(1.0f - cos_t * cos_t, 0.0f));
  float phi = 2.0f * PI_F * u1;
  float a = sin_t * cosf(phi), b = sin_t * sinf(phi);
  s.dir.x = a * c->x[0] + b * c->y[0] + cos_t * c->z[0];
  s.dir.y = a * c->x[1] + b * c->y[1] + cos_t * c->z[1];
  s.dir.z = a * c->x[2] + b * c->y[2] + cos_t * c->z[2];
  s.pdf = c->pdf;
  return s;
}

/* GGX (isotropic, α = roughness²) visible-normal sampling, Heitz 2018: stretch the view
 * to the configuration α = 1, where the visible normals project to a disk that the
 * view's tilt squashes on one side; draw a point on the unit disk (polar, r = √u0,
 * φ = 2π u1), move its second coordinate to the visible half-disk, lift it onto the
 * hemisphere around the stretched view, and unstretch the normal. The direction is the
 * view reflected on it; its density is G1(wo) D(h) / (4 cos θo) with
 * D(h) = α² / (π (1 + (α² − 1) h_z²)²) and G1(wo) = 2 z / (z + √(z² + α² (1 − z²))),
 * z = cos θo, so pdf = D(h) / (2 (z + √(z² + α² (1 − z²)))). A reflection below the
 * horizon has pdf 0 (no sample). */
struct VndfC {
  float alpha;
  float wo[3];
};

NOINLINE static void vndf_prepare(struct VndfC *out, const float *wo, float roughness) {
  out->alpha = roughness * roughness;
  out->wo[0] = wo[0];
  out->wo[1] = wo[1];
  out->wo[2] = wo[2];
}

static float ggx_d(float alpha, float hz) {
  float a2 = alpha * alpha;
  float t = 1.0f + (a2 - 1.0f) * hz * hz;
  return a2 / (PI_F * t * t);
}

/* G1(wo) / (4 cos θo). */
static float ggx_g1_over_4z(float alpha, float z) {
  return 1.0f / (2.0f * (z + sqrtf(z * z + alpha * alpha * (1.0f - z * z))));
}

NOINLINE static SpheraSample vndf_sample(const struct VndfC *g, float u0, float u1) {
  SpheraSample s;
  const float a = g->alpha, *wo = g->wo;
  float vx = a * wo[0], vy = a * wo[1], vz = wo[2];
  float inv = 1.0f / sqrtf(vx * vx + vy * vy + vz * vz);
  float len2, t1x, t1y, t2x, t2y, t2z, r, phi, p1, p2, blend, lift, nx, ny, nz, hx, hy, hz, dot;
  vx *= inv;
  vy *= inv;
  vz *= inv;
  /* T1 orthogonal to the stretched view and to the normal, T2 = V × T1. */
  len2 = vx * vx + vy * vy;
  if (len2 > 0.0f) {
    float il = 1.0f / sqrtf(len2);
    t1x = -vy * il;
    t1y = vx * il;
  } else {
    t1x = 1.0f;
    t1y = 0.0f;
  }
  t2x = -vz * t1y;
  t2y = vz * t1x;
  t2z = vx * t1y - vy * t1x;
  r = sqrtf(u0);
  phi = 2.0f * PI_F * u1;
  p1 = r * cosf(phi);
  p2 = r * sinf(phi);
  blend = 0.5f * (1.0f + vz);
  p2 = (1.0f - blend) * sqrtf(1.0f - p1 * p1) + blend * p2;
  lift = sqrtf(at_least(1.0f - p1 * p1 - p2 * p2, 0.0f));
  nx = p1 * t1x + p2 * t2x + lift * vx;
  ny = p1 * t1y + p2 * t2y + lift * vy;
  nz = p2 * t2z + lift * vz;
  hx = a * nx;
  hy = a * ny;
  hz = at_least(nz, 1e-6f);
  inv = 1.0f / sqrtf(hx * hx + hy * hy + hz * hz);
  hx *= inv;
  hy *= inv;
  hz *= inv;
  dot = wo[0] * hx + wo[1] * hy + wo[2] * hz;
  s.dir.x = 2.0f * dot * hx - wo[0];
  s.dir.y = 2.0f * dot * hy - wo[1];
  s.dir.z = 2.0f * dot * hz - wo[2];
  s.pdf = s.dir.z > 0.0f ? ggx_d(a, hz) * ggx_g1_over_4z(a, wo[2]) : 0.0f;
  return s;
}

/* The density of vndf_sample at wi (unit, above the horizon): h = (wo + wi) / |wo + wi|. */
NOINLINE static float vndf_pdf(const struct VndfC *g, const float *wi) {
  float hx = g->wo[0] + wi[0], hy = g->wo[1] + wi[1], hz = g->wo[2] + wi[2];
  float inv = 1.0f / sqrtf(hx * hx + hy * hy + hz * hz);
  return wi[2] > 0.0f ? ggx_d(g->alpha, hz * inv) * ggx_g1_over_4z(g->alpha, g->wo[2]) : 0.0f;
}

/* Cosine-weighted hemisphere sampling (Malley's method, polar disk): r = √u0, φ = 2π u1,
 * z = √(1 − u0), pdf = z / π. */
NOINLINE static SpheraSample cosine_sample(float u0, float u1) {
  SpheraSample s;
  float r = sqrtf(u0), phi = 2.0f * PI_F * u1;
  s.dir.x = r * cosf(phi);
  s.dir.y = r * sinf(phi);
  s.dir.z = sqrtf(1.0f - u0);
  s.pdf = s.dir.z * (1.0f / PI_F);
  return s;
}

/* One lobe of a VSGL at a shading point, as Tokuyoshi 2016 writes it (Sec. 4, Eq. 6–7),
 * in linear space and without checks: the incoming radiance is the product of the
 * emission lobe G(ω, −ξ_v, λ_v) and the spatial lobe G(ω, μ/|μ|, |μ|²/s²), s² = σ_v²/2
 * (the library's convention, docs/sg-and-vsgl.md), amplitude c_v/(2πs²):
 *   λ_in = |λ_s μ/|μ| − λ_v ξ_v|,  ξ_in = (λ_s μ/|μ| − λ_v ξ_v)/λ_in,
 *   c_in = c_v/(2πs²) e^{λ_in − λ_v − λ_s};
 * diffuse shading with the cosine at the lobe's axis, (c_in/π) A(λ_in) max(ξ_in·n, 0)
 * with A(λ) = 2π/λ (1 − e^{−2λ}) (albedo 1); specular shading C(ξ_in) ∫ G_in Ĝ dω with
 * the ASG fit of GGX (z the view's reflection, η_x = λ_h/8, η_y = λ_h/(8 cos²θo),
 * λ_h = 2/α²), the ASG–SG convolution of Sec. 4.2 (ν = λ_in/2), and
 * C = F G2/(4π α² cos θo): Schlick's Fresnel (F0 = 0.04) at the half vector and the
 * height-correlated Smith G2. Returns the diffuse term as pdf and the specular as dir.x. */
struct VsglC {
  float axis[3], sharpness, amplitude;
  float mean[3], variance;
  float n[3], wo[3], roughness;
};

static void vsgl_c_prepare(struct VsglC *out, const Input *in) {
  memcpy(out->axis, in->lobe_axis, sizeof out->axis);
  out->sharpness = in->sharpness;
  out->amplitude = in->amplitude;
  memcpy(out->mean, in->center, sizeof out->mean);
  out->variance = in->variance;
  out->n[0] = 0.0f;
  out->n[1] = 0.0f;
  out->n[2] = 1.0f;
  memcpy(out->wo, in->wo, sizeof out->wo);
  out->roughness = in->roughness;
}

static float dot3(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* GGX's Smith Λ at cos θ = c. */
static float ggx_lambda(float alpha, float c) {
  float c2 = c * c;
  return 0.5f * (sqrtf(1.0f + alpha * alpha * (1.0f - c2) / c2) - 1.0f);
}

NOINLINE static SpheraSample vsgl_c_shade(const struct VsglC *g, float u0, float u1) {
  SpheraSample s;
  const float *n = g->n, *wo = g->wo;
  float s2 = 0.5f * g->variance, d2 = dot3(g->mean, g->mean), inv_d = 1.0f / sqrtf(d2);
  float ls = d2 / s2, lv = g->sharpness, v[3], lin, xi[3], cin, diffuse, specular = 0.0f;
  float alpha = g->roughness * g->roughness, co = dot3(wo, n), ci;
  int k;
  (void)u0;
  (void)u1;
  for (k = 0; k < 3; k++) v[k] = ls * inv_d * g->mean[k] - lv * g->axis[k];
  lin = sqrtf(dot3(v, v));
  for (k = 0; k < 3; k++) xi[k] = v[k] / lin;
  cin = g->amplitude / (2.0f * PI_F * s2) * expf(lin - lv - ls);
  ci = dot3(xi, n);
  diffuse = cin * (2.0f / lin) * (1.0f - expf(-2.0f * lin)) * at_least(ci, 0.0f);
  if (co > 0.0f && ci > 0.0f) {
    float h[3], z[3], x[3], y[3], inv, m, m2, f, g2, c, lh, cos_o, ex, ey, nu, px, py, pz;
    for (k = 0; k < 3; k++) h[k] = wo[k] + xi[k];
    inv = 1.0f / sqrtf(dot3(h, h));
    m = 1.0f - dot3(wo, h) * inv;
    m2 = m * m;
    f = 0.04f + 0.96f * (m2 * m2 * m);
    g2 = 1.0f / (1.0f + ggx_lambda(alpha, co) + ggx_lambda(alpha, ci));
    c = f * g2 / (4.0f * PI_F * alpha * alpha * co);
    /* the ASG: z = 2(wo·n)n − wo, y ∝ n × z, x = y × z */
    for (k = 0; k < 3; k++) z[k] = 2.0f * co * n[k] - wo[k];
    y[0] = n[1] * z[2] - n[2] * z[1];
    y[1] = n[2] * z[0] - n[0] * z[2];
    y[2] = n[0] * z[1] - n[1] * z[0];
    inv = dot3(y, y);
    if (inv > 0.0f) {
      inv = 1.0f / sqrtf(inv);
      for (k = 0; k < 3; k++) y[k] *= inv;
      x[0] = y[1] * z[2] - y[2] * z[1];
      x[1] = y[2] * z[0] - y[0] * z[2];
      x[2] = y[0] * z[1] - y[1] * z[0];
    } else {
      x[0] = 1.0f, x[1] = 0.0f, x[2] = 0.0f;
      y[0] = 0.0f, y[1] = 1.0f, y[2] = 0.0f;
    }
    lh = 2.0f / (alpha * alpha);
    cos_o = at_least(co, 1e-4f);
    nu = 0.5f * lin;
    ex = lh / 8.0f + nu;
    ey = lh / (8.0f * cos_o * cos_o) + nu;
    px = dot3(xi, x);
    py = dot3(xi, y);
    pz = dot3(xi, z);
    /* 1/√((η_x + ν)(η_y + ν)) capped at 1, as the library caps the ASG's integral */
    if (pz > 0.0f)
      specular = c * cin * PI_F * pz / (ex * ey > 1.0f ? sqrtf(ex * ey) : 1.0f) *
                 expf(-(lh / 8.0f) * (nu / ex) * px * px - (lh / (8.0f * cos_o * cos_o)) * (nu / ey) * py * py);
  }
  s.pdf = diffuse;
  s.dir.x = specular;
  s.dir.y = 0.0f;
  s.dir.z = 0.0f;
  return s;
}

/* c_vsgl with the work that does not depend on the lobe moved into its prepare, as a
 * renderer that shades many VSGLs at one point would write it: the view's cosine, α,
 * Smith's Λ(ω_o), the ASG frame and bandwidths, and C's denominator 4π α² cos θo. The
 * shading of each lobe is then vsgl_c_shade's, term for term. */
struct VsglPointC {
  float axis[3], sharpness, amplitude;
  float mean[3], variance;
  float wo[3], co, alpha2, one_plus_lambda_o, denominator;
  float x[3], y[3], z[3], eta_x, eta_y;
};

static void vsgl_c_point_prepare(struct VsglPointC *out, const Input *in) {
  static const float n[3] = {0.0f, 0.0f, 1.0f};
  float alpha = in->roughness * in->roughness, co, lh, cos_o, inv;
  int k;
  memcpy(out->axis, in->lobe_axis, sizeof out->axis);
  out->sharpness = in->sharpness;
  out->amplitude = in->amplitude;
  memcpy(out->mean, in->center, sizeof out->mean);
  out->variance = in->variance;
  memcpy(out->wo, in->wo, sizeof out->wo);
  co = dot3(in->wo, n);
  out->co = co;
  out->alpha2 = alpha * alpha;
  out->one_plus_lambda_o = co > 0.0f ? 1.0f + ggx_lambda(alpha, co) : 1.0f;
  out->denominator = 4.0f * PI_F * alpha * alpha * co;
  for (k = 0; k < 3; k++) out->z[k] = 2.0f * co * n[k] - in->wo[k];
  out->y[0] = n[1] * out->z[2] - n[2] * out->z[1];
  out->y[1] = n[2] * out->z[0] - n[0] * out->z[2];
  out->y[2] = n[0] * out->z[1] - n[1] * out->z[0];
  inv = dot3(out->y, out->y);
  if (inv > 0.0f) {
    inv = 1.0f / sqrtf(inv);
    for (k = 0; k < 3; k++) out->y[k] *= inv;
    out->x[0] = out->y[1] * out->z[2] - out->y[2] * out->z[1];
    out->x[1] = out->y[2] * out->z[0] - out->y[0] * out->z[2];
    out->x[2] = out->y[0] * out->z[1] - out->y[1] * out->z[0];
  } else {
    out->x[0] = 1.0f, out->x[1] = 0.0f, out->x[2] = 0.0f;
    out->y[0] = 0.0f, out->y[1] = 1.0f, out->y[2] = 0.0f;
  }
  lh = 2.0f / (alpha * alpha);
  cos_o = at_least(co, 1e-4f);
  out->eta_x = lh / 8.0f;
  out->eta_y = lh / (8.0f * cos_o * cos_o);
}

NOINLINE static SpheraSample vsgl_c_point_shade(const struct VsglPointC *g, float u0, float u1) {
  SpheraSample s;
  float s2 = 0.5f * g->variance, d2 = dot3(g->mean, g->mean), inv_d = 1.0f / sqrtf(d2);
  float ls = d2 / s2, lv = g->sharpness, v[3], lin, xi[3], cin, ci, specular = 0.0f;
  int k;
  (void)u0;
  (void)u1;
  for (k = 0; k < 3; k++) v[k] = ls * inv_d * g->mean[k] - lv * g->axis[k];
  lin = sqrtf(dot3(v, v));
  for (k = 0; k < 3; k++) xi[k] = v[k] / lin;
  cin = g->amplitude / (2.0f * PI_F * s2) * expf(lin - lv - ls);
  ci = xi[2]; /* ξ_in·n with n = z */
  s.pdf = cin * (2.0f / lin) * (1.0f - expf(-2.0f * lin)) * at_least(ci, 0.0f);
  if (g->co > 0.0f && ci > 0.0f) {
    float h[3], inv, m, m2, f, g2, c, ex, ey, nu, px, py, pz, ci2;
    for (k = 0; k < 3; k++) h[k] = g->wo[k] + xi[k];
    inv = 1.0f / sqrtf(dot3(h, h));
    m = 1.0f - dot3(g->wo, h) * inv;
    m2 = m * m;
    f = 0.04f + 0.96f * (m2 * m2 * m);
    ci2 = ci * ci;
    g2 = 1.0f / (g->one_plus_lambda_o + 0.5f * (sqrtf(1.0f + g->alpha2 * (1.0f - ci2) / ci2) - 1.0f));
    c = f * g2 / g->denominator;
    nu = 0.5f * lin;
    ex = g->eta_x + nu;
    ey = g->eta_y + nu;
    px = dot3(xi, g->x);
    py = dot3(xi, g->y);
    pz = dot3(xi, g->z);
    if (pz > 0.0f)
      specular = c * cin * PI_F * pz / (ex * ey > 1.0f ? sqrtf(ex * ey) : 1.0f) *
                 expf(-g->eta_x * (nu / ex) * px * px - g->eta_y * (nu / ey) * py * py);
  }
  s.dir.x = specular;
  s.dir.y = 0.0f;
  s.dir.z = 0.0f;
  return s;
}

/* von Mises–Fisher sampling as Jakob 2012 ("Numerically stable sampling of the von
 * Mises Fisher distribution on S² (and other tricks)") writes it: cos θ = 1 + ln(u +
 * (1 − u) e^{−2κ})/κ (u at least 1e-6, as Mitsuba does, so that the logarithm stays
 * finite where e^{−2κ} underflows), φ = 2π u1, the frame of the axis as in cone sampling,
 * pdf = κ e^{κ(cos θ − 1)} / (2π (1 − e^{−2κ})). No prepare: the lobe goes by value, as
 * into sphera_vmf_sample. */
struct VmfC {
  float axis[3], kappa;
};
static void vmf_c_prepare(struct VmfC *out, const Input *in) {
  memcpy(out->axis, in->lobe_axis, sizeof out->axis);
  out->kappa = in->sharpness;
}

NOINLINE static SpheraSample vmf_c_sample(const struct VmfC *g, float u0, float u1) {
  SpheraSample s;
  const float k = g->kappa, *a = g->axis;
  float u = u0 > 1e-6f ? u0 : 1e-6f;
  float cos_t = 1.0f + logf(u + (1.0f - u) * expf(-2.0f * k)) / k;
  float sin_t = sqrtf(at_least(1.0f - cos_t * cos_t, 0.0f)), phi = 2.0f * PI_F * u1;
  float p = sin_t * cosf(phi), q = sin_t * sinf(phi);
  float sign = copysignf(1.0f, a[2]), b = -1.0f / (sign + a[2]), c = a[0] * a[1] * b;
  s.dir.x = p * (1.0f + sign * a[0] * a[0] * b) + q * c + cos_t * a[0];
  s.dir.y = p * (sign * c) + q * (sign + a[1] * a[1] * b) + cos_t * a[1];
  s.dir.z = p * (-sign * a[0]) + q * (-a[1]) + cos_t * a[2];
  s.pdf = k * expf(k * (cos_t - 1.0f)) / (2.0f * PI_F * (1.0f - expf(-2.0f * k)));
  return s;
}

/* ---- the techniques: prepared types, prepare and sample ---------------------------- */

static SpheraVec3 vec3(const float *v) {
  SpheraVec3 r;
  r.x = v[0];
  r.y = v[1];
  r.z = v[2];
  return r;
}

static SpheraVec3 splat3(float a) {
  SpheraVec3 r;
  r.x = r.y = r.z = a;
  return r;
}

/* A result that is not a sample (shading values): its components as pdf and dir.x. */
static SpheraSample from_rgb(SpheraVec3 rgb) {
  SpheraSample s;
  s.dir = rgb;
  s.pdf = rgb.x;
  s.dir.x = rgb.y;
  return s;
}

/* Two samples in one call (the sum of their pdfs and of their dir.x). */
static SpheraSample both(SpheraSample a, SpheraSample b) {
  a.pdf += b.pdf;
  a.dir.x += b.dir.x;
  return a;
}

/* spheres */

#define C_CONE_PREPARE(out, in) cone_prepare(out, (in)->center, (in)->radius)
#define C_CONE_SAMPLE(p, u0, u1) cone_sample(p, u0, u1)

#define CAP_PREPARE(out, in) (*(out) = sphera_cap_from_sphere(vec3((in)->center), (in)->radius))
#define CAP_SAMPLE(p, u0, u1) sphera_cap_sample_uniform(*(p), u0, u1)

#define SOLID_ANGLE_SPHERE_PREPARE(out, in) sphera_solid_angle_sphere_prepare(out, vec3((in)->center), (in)->radius)
#define SOLID_ANGLE_SPHERE_SAMPLE(p, u0, u1) sphera_solid_angle_sphere_sample(p, u0, u1)

struct ConeVndfC {
  struct ConeC cone;
  struct VndfC vndf;
};
#define C_CONE_VNDF_PREPARE(out, in) \
  (cone_prepare(&(out)->cone, (in)->center, (in)->radius), vndf_prepare(&(out)->vndf, (in)->wo, (in)->roughness))
#define C_CONE_VNDF_SAMPLE(p, u0, u1) both(cone_sample(&(p)->cone, u0, u1), vndf_sample(&(p)->vndf, u1, u0))

#define SPTD_PREPARE(out, in) \
  sphera_sphere_light_sampler_prepare(out, vec3((in)->center), (in)->radius, vec3((in)->wo), (in)->roughness)
#define SPTD_SAMPLE(p, u0, u1) sphera_sphere_light_sampler_sample(p, u0, u1)
/* The fit of the view prepared per shading point (in the pool, untimed): per light, the
 * sampler from it, the same sampler as sptd's, byte for byte. */
#define SPTD_FIT_PREPARE(out, in) \
  sphera_sphere_light_sampler_prepare_with_fit(out, vec3((in)->center), (in)->radius, &(in)->fit)

struct Shading {
  SpheraSphereLightShading shading;
  SpheraCap light;
};
static SpheraCap g_bent_cone; /* the bent cone of the occluded shading rows */
#define RT_SHADE_PREPARE(out, in)                                                                              \
  (sphera_sphere_light_shading_prepare(&(out)->shading, vec3((in)->wo), (in)->roughness, splat3(0.04f)),      \
   (out)->light = sphera_cap_from_sphere(vec3((in)->center), (in)->radius))
#define RT_SHADE_SAMPLE(p, u0, u1) ((void)(u0), (void)(u1), from_rgb(sphera_sphere_light_shading_eval(&(p)->shading, (p)->light)))
#define RT_SHADE_BENT_SAMPLE(p, u0, u1) \
  ((void)(u0), (void)(u1), from_rgb(sphera_sphere_light_shading_eval_occluded(&(p)->shading, (p)->light, g_bent_cone)))
/* The bent cone prepared in (once per shading point), then _eval per light: the same
 * values as rt_shade_bent, bit for bit. */
#define RT_SHADE_OCCLUDED_PREPARE(out, in)                                                          \
  (sphera_sphere_light_shading_prepare_occluded(&(out)->shading, vec3((in)->wo), (in)->roughness,  \
                                                splat3(0.04f), g_bent_cone),                      \
   (out)->light = sphera_cap_from_sphere(vec3((in)->center), (in)->radius))

/* brdf */

#define C_VNDF_PREPARE(out, in) vndf_prepare(out, (in)->wo, (in)->roughness)
#define C_VNDF_SAMPLE(p, u0, u1) vndf_sample(p, u0, u1)

struct Ggx {
  SpheraGgxBrdf brdf;
  SpheraVec3 wo;
};
#define GGX_PREPARE(out, in) \
  (sphera_ggx_brdf_prepare(&(out)->brdf, (in)->roughness, splat3(0.04f)), (out)->wo = vec3((in)->wo))
#define GGX_SAMPLE(p, u0, u1) sphera_ggx_brdf_sample(&(p)->brdf, (p)->wo, u0, u1)

/* The pdf rows: the density of the input's direction, returned as a sample. */
struct VndfPdfC {
  struct VndfC vndf;
  float wi[3];
};
static SpheraSample pdf_as_sample(SpheraVec3 dir, float pdf) {
  SpheraSample s;
  s.dir = dir;
  s.pdf = pdf;
  return s;
}
#define C_VNDF_PDF_PREPARE(out, in) \
  (vndf_prepare(&(out)->vndf, (in)->wo, (in)->roughness), memcpy((out)->wi, (in)->dir, sizeof(float[3])))
#define C_VNDF_PDF_SAMPLE(p, u0, u1) ((void)(u0), (void)(u1), pdf_as_sample(vec3((p)->wi), vndf_pdf(&(p)->vndf, (p)->wi)))

struct GgxPdf {
  struct Ggx ggx;
  SpheraVec3 wi;
};
#define GGX_PDF_PREPARE(out, in) (GGX_PREPARE(&(out)->ggx, in), (out)->wi = vec3((in)->dir))
#define GGX_PDF_SAMPLE(p, u0, u1) \
  ((void)(u0), (void)(u1), pdf_as_sample((p)->wi, sphera_ggx_brdf_pdf(&(p)->ggx.brdf, (p)->ggx.wo, (p)->wi)))

struct Nothing {
  int unused;
};
#define NO_PREPARE(out, in) ((out)->unused = (in)->n)
#define C_COSINE_SAMPLE(p, u0, u1) ((void)(p), cosine_sample(u0, u1))
#define LAMBERT_SAMPLE(p, u0, u1) ((void)(p), sphera_lambert_sample(u0, u1))

/* polygons */

#define LIB_VERTS(in) ((const SpheraVec3 *)(const void *)(in)->v)

#define PROJECTED_PREPARE(out, in) sphera_projected_polygon_prepare(out, LIB_VERTS(in), (uint32_t)(in)->n)
#define PROJECTED_SAMPLE(p, u0, u1) sphera_projected_polygon_sample(p, u0, u1)

static void ltc_polygon_prepare(SpheraLtcPolygon *out, const Input *in) {
  SpheraLtc ltc;
  sphera_ltc_prepare(&ltc, vec3(in->wo), in->roughness);
  sphera_ltc_polygon_prepare(out, &ltc, LIB_VERTS(in), (uint32_t)in->n);
}
#define LTC_POLYGON_PREPARE(out, in) ltc_polygon_prepare(out, in)
#define LTC_POLYGON_SAMPLE(p, u0, u1) sphera_ltc_polygon_sample(p, u0, u1)

static void polygon_light_prepare(SpheraPolygonLight *out, const Input *in, uint32_t heuristic) {
  SpheraMaterial material;
  material.diffuse = splat3(0.5f);
  material.f0 = splat3(0.04f);
  material.roughness = in->roughness;
  sphera_polygon_light_prepare(out, LIB_VERTS(in), (uint32_t)in->n, vec3(in->wo), &material, heuristic,
                               SPHERA_MIS_DEFAULT_VISIBILITY);
}
/* One estimate of the light: a sample of each technique (projected, LTC). */
static SpheraSample polygon_light_sample(const SpheraPolygonLight *light, float u0, float u1) {
  SpheraLightSample a = sphera_polygon_light_sample(light, 0, u0, u1);
  SpheraLightSample b = sphera_polygon_light_sample(light, 1, u0, u1);
  SpheraSample s;
  s.dir = a.dir;
  s.dir.x += b.dir.x + a.visible.x + b.visible.x + a.unoccluded.x + b.unoccluded.x;
  s.pdf = a.pdf + b.pdf;
  return s;
}
#define LIGHT_BALANCE_PREPARE(out, in) polygon_light_prepare(out, in, SPHERA_MIS_BALANCE)
#define LIGHT_WEIGHTED_PREPARE(out, in) polygon_light_prepare(out, in, SPHERA_MIS_WEIGHTED_BALANCE)
#define LIGHT_CLAMPED_PREPARE(out, in) polygon_light_prepare(out, in, SPHERA_MIS_CLAMPED_OPTIMAL)
#define LIGHT_OPTIMAL_PREPARE(out, in) polygon_light_prepare(out, in, SPHERA_MIS_OPTIMAL)
#define LIGHT_SAMPLE(p, u0, u1) polygon_light_sample(p, u0, u1)

/* vsgls */

#define C_VSGL_PREPARE(out, in) vsgl_c_prepare(out, in)
#define C_VSGL_SAMPLE(p, u0, u1) vsgl_c_shade(p, u0, u1)

/* The tracer's shading of one VSGL lobe (bench/src/indirect.c): the incoming radiance
 * SG, constant-cosine diffuse shading and ASG specular shading of one channel. */
struct VsglLobe {
  SpheraSg lobe;
  SpheraVec3 mean;
  float variance;
  SpheraVec3 wo;
  float roughness;
};
static void vsgl_lobe_prepare(struct VsglLobe *out, const Input *in) {
  out->lobe.axis = vec3(in->lobe_axis);
  out->lobe.sharpness = in->sharpness;
  out->lobe.log_amplitude = logf(in->amplitude);
  out->mean = vec3(in->center);
  out->variance = in->variance;
  out->wo = vec3(in->wo);
  out->roughness = in->roughness;
}
static SpheraSample vsgl_lobe_shade(const struct VsglLobe *g) {
  static const SpheraVec3 normal = {0.0f, 0.0f, 1.0f};
  SpheraSample s;
  SpheraSg incoming = sphera_sg_incoming_radiance(g->lobe, g->mean, g->variance);
  s.pdf = sphera_sg_diffuse_shading_constant_cosine(incoming, normal, 1.0f, 1.0f);
  s.dir.x = sphera_sg_specular_shading(incoming, normal, g->wo, g->roughness, 0.04f, 1.0f);
  s.dir.y = 0.0f;
  s.dir.z = 0.0f;
  return s;
}
#define VSGL_SHADE_PREPARE(out, in) vsgl_lobe_prepare(out, in)
#define VSGL_SHADE_SAMPLE(p, u0, u1) ((void)(u0), (void)(u1), vsgl_lobe_shade(p))

#define C_VSGL_POINT_PREPARE(out, in) vsgl_c_point_prepare(out, in)
#define C_VSGL_POINT_SAMPLE(p, u0, u1) vsgl_c_point_shade(p, u0, u1)

/* The same lobe shaded at a prepared shading point: sphera_sg_shading_point_prepare (the
 * normal, view, roughness and F0 = 0.04) with the lobe's set-up, then per lobe the
 * incoming radiance SG and sphera_sg_shading_point_shade. */
struct VsglPoint {
  SpheraSgShadingPoint point;
  SpheraSg lobe;
  SpheraVec3 mean;
  float variance;
};
static void vsgl_point_prepare(struct VsglPoint *out, const Input *in) {
  static const SpheraVec3 normal = {0.0f, 0.0f, 1.0f};
  sphera_sg_shading_point_prepare(&out->point, normal, vec3(in->wo), in->roughness, 0.04f);
  out->lobe.axis = vec3(in->lobe_axis);
  out->lobe.sharpness = in->sharpness;
  out->lobe.log_amplitude = logf(in->amplitude);
  out->mean = vec3(in->center);
  out->variance = in->variance;
}
static SpheraSample vsgl_point_shade(const struct VsglPoint *g) {
  SpheraSample s;
  SpheraSg incoming = sphera_sg_incoming_radiance(g->lobe, g->mean, g->variance);
  SpheraSgShading shading = sphera_sg_shading_point_shade(&g->point, incoming, 1.0f, 1.0f);
  s.pdf = shading.diffuse;
  s.dir.x = shading.specular;
  s.dir.y = 0.0f;
  s.dir.z = 0.0f;
  return s;
}
#define VSGL_POINT_PREPARE(out, in) vsgl_point_prepare(out, in)
#define VSGL_POINT_SAMPLE(p, u0, u1) ((void)(u0), (void)(u1), vsgl_point_shade(p))

#define C_VMF_PREPARE(out, in) vmf_c_prepare(out, in)
#define C_VMF_SAMPLE(p, u0, u1) vmf_c_sample(p, u0, u1)

#define VMF_PREPARE(out, in) ((out)->axis = vec3((in)->lobe_axis), (out)->sharpness = (in)->sharpness, (out)->log_amplitude = 0.0f)
#define VMF_SAMPLE(p, u0, u1) sphera_vmf_sample(*(p), u0, u1)

/* ---- the loops ------------------------------------------------------------------- */

typedef struct {
  double sum;
  long valid; /* samples with pdf > 0 */
} Tally;

/* Per technique: the prepare + 1 sample loop, the preparation of a pool into an array,
 * and the per-sample loop over that array. */
#define DEFINE_TECHNIQUE(ID, FAMILY, BASELINE, TYPE, PREPARE, SAMPLE)                    \
  NOINLINE static void loop_prepare_##ID(const Pool *pool, long calls, Tally *tally) { \
    TYPE prepared;                                                                     \
    double sum = 0.0;                                                                  \
    long i, valid = 0;                                                                 \
    for (i = 0; i < calls; i++) {                                                      \
      const Input *in = &pool->inputs[i & (POOL_SIZE - 1)];                            \
      const float *u = g_u[i & (U_COUNT - 1)];                                         \
      SpheraSample s;                                                                  \
      PREPARE(&prepared, in);                                                          \
      s = SAMPLE(&prepared, u[0], u[1]);                                               \
      sum += (double)s.pdf + (double)s.dir.x;                                          \
      valid += s.pdf > 0.0f;                                                           \
    }                                                                                  \
    tally->sum += sum;                                                                 \
    tally->valid += valid;                                                             \
  }                                                                                    \
  static void prepare_all_##ID(const Pool *pool, void *array) {                        \
    TYPE *prepared = (TYPE *)array;                                                    \
    int i;                                                                             \
    for (i = 0; i < POOL_SIZE; i++) PREPARE(&prepared[i], &pool->inputs[i]);           \
  }                                                                                    \
  NOINLINE static void loop_sample_##ID(const void *array, long calls, Tally *tally) { \
    const TYPE *prepared = (const TYPE *)array;                                        \
    double sum = 0.0;                                                                  \
    long i, valid = 0;                                                                 \
    for (i = 0; i < calls; i++) {                                                      \
      const float *u = g_u[i & (U_COUNT - 1)];                                         \
      SpheraSample s = SAMPLE(&prepared[i & (POOL_SIZE - 1)], u[0], u[1]);             \
      sum += (double)s.pdf + (double)s.dir.x;                                          \
      valid += s.pdf > 0.0f;                                                           \
    }                                                                                  \
    tally->sum += sum;                                                                 \
    tally->valid += valid;                                                             \
  }

/* id, family, baseline id, prepared type, prepare, sample */
#define TECHNIQUES(X)                                                                                 \
  X(c_cone, SPHERES, c_cone, struct ConeC, C_CONE_PREPARE, C_CONE_SAMPLE)                             \
  X(cap, SPHERES, c_cone, SpheraCap, CAP_PREPARE, CAP_SAMPLE)                                         \
  X(solid_angle_sphere, SPHERES, c_cone, SpheraSolidAngleSphere, SOLID_ANGLE_SPHERE_PREPARE, SOLID_ANGLE_SPHERE_SAMPLE) \
  X(c_cone_vndf, SPHERES, c_cone_vndf, struct ConeVndfC, C_CONE_VNDF_PREPARE, C_CONE_VNDF_SAMPLE)     \
  X(sptd, SPHERES, c_cone_vndf, SpheraSphereLightSampler, SPTD_PREPARE, SPTD_SAMPLE)                  \
  X(sptd_fit, SPHERES, c_cone_vndf, SpheraSphereLightSampler, SPTD_FIT_PREPARE, SPTD_SAMPLE)         \
  X(rt_shade, SPHERES, c_cone, struct Shading, RT_SHADE_PREPARE, RT_SHADE_SAMPLE)                     \
  X(rt_shade_bent, SPHERES, c_cone, struct Shading, RT_SHADE_PREPARE, RT_SHADE_BENT_SAMPLE)           \
  X(rt_shade_occluded, SPHERES, c_cone, struct Shading, RT_SHADE_OCCLUDED_PREPARE, RT_SHADE_SAMPLE)    \
  X(c_vndf, BRDF, c_vndf, struct VndfC, C_VNDF_PREPARE, C_VNDF_SAMPLE)                                \
  X(ggx, BRDF, c_vndf, struct Ggx, GGX_PREPARE, GGX_SAMPLE)                                           \
  X(c_vndf_pdf, BRDF, c_vndf_pdf, struct VndfPdfC, C_VNDF_PDF_PREPARE, C_VNDF_PDF_SAMPLE)             \
  X(ggx_pdf, BRDF, c_vndf_pdf, struct GgxPdf, GGX_PDF_PREPARE, GGX_PDF_SAMPLE)                        \
  X(c_cosine, BRDF, c_cosine, struct Nothing, NO_PREPARE, C_COSINE_SAMPLE)                            \
  X(lambert, BRDF, c_cosine, struct Nothing, NO_PREPARE, LAMBERT_SAMPLE)                              \
  X(projected, POLYGONS, projected, SpheraProjectedPolygon, PROJECTED_PREPARE, PROJECTED_SAMPLE) \
  X(ltc_polygon, POLYGONS, projected, SpheraLtcPolygon, LTC_POLYGON_PREPARE, LTC_POLYGON_SAMPLE)      \
  X(light_balance, POLYGONS, projected, SpheraPolygonLight, LIGHT_BALANCE_PREPARE, LIGHT_SAMPLE)      \
  X(light_weighted_balance, POLYGONS, projected, SpheraPolygonLight, LIGHT_WEIGHTED_PREPARE, LIGHT_SAMPLE) \
  X(light_clamped_optimal, POLYGONS, projected, SpheraPolygonLight, LIGHT_CLAMPED_PREPARE, LIGHT_SAMPLE)   \
  X(light_optimal, POLYGONS, projected, SpheraPolygonLight, LIGHT_OPTIMAL_PREPARE, LIGHT_SAMPLE)             \
  X(c_vsgl, VSGLS, c_vsgl, struct VsglC, C_VSGL_PREPARE, C_VSGL_SAMPLE)                                 \
  X(vsgl_shade, VSGLS, c_vsgl, struct VsglLobe, VSGL_SHADE_PREPARE, VSGL_SHADE_SAMPLE)                  \
  X(c_vsgl_point, VSGLS, c_vsgl_point, struct VsglPointC, C_VSGL_POINT_PREPARE, C_VSGL_POINT_SAMPLE)     \
  X(vsgl_point, VSGLS, c_vsgl_point, struct VsglPoint, VSGL_POINT_PREPARE, VSGL_POINT_SAMPLE)            \
  X(c_vmf, VSGLS, c_vmf, struct VmfC, C_VMF_PREPARE, C_VMF_SAMPLE)                                      \
  X(vmf, VSGLS, c_vmf, SpheraSg, VMF_PREPARE, VMF_SAMPLE)

TECHNIQUES(DEFINE_TECHNIQUE)

typedef struct {
  const char *id;
  enum Family family;
  const char *baseline;
  const char *type;
  size_t size;
  void (*loop_prepare)(const Pool *, long, Tally *);
  void (*prepare_all)(const Pool *, void *);
  void (*loop_sample)(const void *, long, Tally *);
} Technique;

#define TECHNIQUE_ENTRY(ID, FAMILY, BASELINE, TYPE, PREPARE, SAMPLE) \
  {#ID, FAMILY, #BASELINE, #TYPE, sizeof(TYPE), loop_prepare_##ID, prepare_all_##ID, loop_sample_##ID},

static const Technique TECHNIQUE_LIST[] = {TECHNIQUES(TECHNIQUE_ENTRY)};
enum { TECHNIQUE_COUNT = sizeof(TECHNIQUE_LIST) / sizeof(TECHNIQUE_LIST[0]) };

/* ---- pools --------------------------------------------------------------------- */

/* A unit vector with z uniform in [z_lo, z_hi] and a uniform azimuth. */
static D3 direction(uint64_t *rng, double z_lo, double z_hi) {
  double z = uniform_in(rng, z_lo, z_hi), s = sqrt(fmax(0.0, 1.0 - z * z)), a = uniform_in(rng, 0.0, 2.0 * PI);
  return d3(s * cos(a), s * sin(a), z);
}

static void store(float *out, D3 v) {
  out[0] = (float)v.x;
  out[1] = (float)v.y;
  out[2] = (float)v.z;
}

/* Whether the zenith lies inside the polygon (all vertices above the horizon): the
 * signs of (v_i × v_{i+1}).z all agree. */
static int zenith_inside(const Input *p) {
  int i, positive = 0, negative = 0;
  for (i = 0; i < p->n; i++) {
    const float *a = p->v[i], *b = p->v[(i + 1) % p->n];
    double s = (double)a[0] * b[1] - (double)a[1] * b[0];
    positive += s > 0.0;
    negative += s < 0.0;
  }
  return positive == p->n || negative == p->n;
}

/* A quad as in bench/polygon-bench: vertices irregularly spaced on an ellipse
 * (aspect in [0.5, 1], random rotation) in a plane tilted up to 50° from facing the
 * shading point, centre at a log-uniform distance in [1, 4], radius 0.3–1 times the
 * distance, entirely above the horizon, the zenith inside (central) or outside. */
static void generate_quad(uint64_t *rng, int central, Input *out) {
  for (;;) {
    double distance = exp(uniform_in(rng, 0.0, log(4.0)));
    double cos_polar = central ? uniform_in(rng, cos(40.0 * PI / 180.0), 1.0)
                               : uniform_in(rng, cos(75.0 * PI / 180.0), cos(15.0 * PI / 180.0));
    double sin_polar = sqrt(1.0 - cos_polar * cos_polar), azimuth = uniform_in(rng, 0.0, 2.0 * PI);
    double spin, tilt, radius, aspect, min_z = 1e30;
    D3 c = d3(sin_polar * cos(azimuth), sin_polar * sin(azimuth), cos_polar), w, m, t1, t2, t1r, t2r, centre;
    int k;
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
    out->n = QUAD;
    for (k = 0; k < QUAD; k++) {
      double angle = 2.0 * PI * (k + 0.4 * uniform(rng)) / QUAD;
      store(out->v[k], add(centre, add(scale(t1r, radius * cos(angle)), scale(t2r, radius * aspect * sin(angle)))));
      if (out->v[k][2] < min_z) min_z = out->v[k][2];
    }
    if (min_z > 0.0 && central == zenith_inside(out)) return;
  }
}

static void make_pool(Pool *pool, enum Family family) {
  uint64_t rng = 0x11647000ull + (uint64_t)family;
  int i;
  static const char *IDS[FAMILY_COUNT] = {"spheres", "brdf", "polygons", "vsgls"};
  static const char *TITLES[FAMILY_COUNT] = {
      "spheres (distance log-uniform in [1, 4], sin²θmax in [0.06, 0.44], upper hemisphere)",
      "brdf (cos θo in [0.1, 1], roughness in [0.1, 0.9])",
      "polygons (quads above the horizon, half central; roughness in [0.1, 0.9])",
      "vsgls (one lobe each: λ_v log-uniform in [1, 100], mean at a distance log-uniform in [1, 4], σ_v / distance in "
      "[0.05, 0.5]; roughness in [0.1, 0.9])"};
  pool->id = IDS[family];
  pool->title = TITLES[family];
  pool->family = family;
  memset(pool->inputs, 0, sizeof pool->inputs);
  for (i = 0; i < POOL_SIZE; i++) {
    Input *in = &pool->inputs[i];
    double distance = exp(uniform_in(&rng, 0.0, log(4.0)));
    double sin2 = uniform_in(&rng, 0.06, 0.44);
    store(in->center, scale(direction(&rng, 0.0, 1.0), distance));
    in->radius = (float)(distance * sqrt(sin2));
    store(in->wo, direction(&rng, 0.1, 1.0));
    in->roughness = (float)uniform_in(&rng, 0.1, 0.9);
    if (!sphera_ggx_pivot_from_view(&in->fit, vec3(in->wo), in->roughness)) abort();
    store(in->dir, direction(&rng, 0.02, 1.0));
    in->n = 0;
    if (family == POLYGONS) generate_quad(&rng, i & 1, in);
    if (family == VSGLS) {
      /* the emission axis within 60° of the direction from the mean to the shading point */
      D3 toward = scale(normalize(d3(in->center[0], in->center[1], in->center[2])), -1.0), t1 = orthogonal(toward);
      D3 t2 = cross(toward, t1);
      double z = uniform_in(&rng, 0.5, 1.0), r = sqrt(1.0 - z * z), a = uniform_in(&rng, 0.0, 2.0 * PI);
      double l = exp(uniform_in(&rng, 0.0, log(100.0))), spread = uniform_in(&rng, 0.05, 0.5) * distance;
      store(in->lobe_axis, add(scale(toward, z), add(scale(t1, r * cos(a)), scale(t2, r * sin(a)))));
      in->sharpness = (float)l;
      in->amplitude = (float)(l / (2.0 * PI * (1.0 - exp(-2.0 * l)))); /* 1 / A(λ) */
      in->variance = (float)(spread * spread);
    }
  }
}

/* ---- checks of the C baselines (not timed) ------------------------------------------ */

static int relative_ok(float value, float expected, float tolerance) {
  return fabsf(value - expected) <= tolerance * fabsf(expected);
}

static int unit(SpheraVec3 d) { return fabsf(d.x * d.x + d.y * d.y + d.z * d.z - 1.0f) <= 1e-5f; }

/* Whether the mean of n values with the given standard deviation each is within five
 * standard errors of the expected mean; reports it otherwise. */
static int mean_ok(const char *what, double sum, long n, double expected, double deviation) {
  double mean = sum / (double)n, error = 5.0 * deviation / sqrt((double)n);
  if (fabs(mean - expected) <= error) return 1;
  fprintf(stderr, "FAILED: %s: mean %.6f, expected %.6f within %.6f\n", what, mean, expected, error);
  return 0;
}

/* Cone sampling: every sample a unit vector inside the cone, its pdf 1 / Ω of the cap
 * the library computes for the same sphere; and for the first 16 spheres, over all
 * 4096 (u0, u1), the mean of cos θ is (1 + cos θmax) / 2 (cos θ uniform, variance
 * (1 − cos θmax)² / 12) and the means of the two tangent coordinates are 0 (variance
 * E[sin²θ] / 2 ≤ (1 − cos²θmax) / 2). */
static int check_c_cone(const Pool *pool) {
  int i, j, bad = 0;
  for (i = 0; i < POOL_SIZE; i++) {
    const Input *in = &pool->inputs[i];
    struct ConeC c;
    SpheraSample s;
    float cos_t;
    cone_prepare(&c, in->center, in->radius);
    s = cone_sample(&c, g_u[i][0], g_u[i][1]);
    cos_t = s.dir.x * c.z[0] + s.dir.y * c.z[1] + s.dir.z * c.z[2];
    if (!unit(s.dir) || !(cos_t >= c.cos_max - 1e-5f) ||
        !relative_ok(s.pdf, 1.0f / sphera_cap_solid_angle(sphera_cap_from_sphere(vec3(in->center), in->radius)), 1e-3f))
      bad++;
  }
  if (bad) fprintf(stderr, "FAILED: cone sampling: %d spheres with a sample outside the cone or a wrong pdf\n", bad);
  for (i = 0; i < 16; i++) {
    struct ConeC c;
    double sum_cos = 0.0, sum_x = 0.0, sum_y = 0.0, width, sin2;
    cone_prepare(&c, pool->inputs[i].center, pool->inputs[i].radius);
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = cone_sample(&c, g_u[j][0], g_u[j][1]);
      sum_cos += s.dir.x * c.z[0] + s.dir.y * c.z[1] + s.dir.z * c.z[2];
      sum_x += s.dir.x * c.x[0] + s.dir.y * c.x[1] + s.dir.z * c.x[2];
      sum_y += s.dir.x * c.y[0] + s.dir.y * c.y[1] + s.dir.z * c.y[2];
    }
    width = 1.0 - c.cos_max;
    sin2 = 1.0 - (double)c.cos_max * c.cos_max;
    if (!mean_ok("cone sampling, cos θ", sum_cos, U_COUNT, 0.5 * (1.0 + c.cos_max), width / sqrt(12.0)) ||
        !mean_ok("cone sampling, first tangent", sum_x, U_COUNT, 0.0, sqrt(0.5 * sin2)) ||
        !mean_ok("cone sampling, second tangent", sum_y, U_COUNT, 0.0, sqrt(0.5 * sin2)))
      bad++;
  }
  return bad;
}

/* GGX visible-normal sampling: every sample a unit vector; above the horizon, the C pdf
 * function agrees with sphera_ggx_brdf_pdf at the sample (2e-3) and so does the pdf that the
 * sample carries (1e-2: its half vector is the sampled normal, not (wo + wi) normalised,
 * whose rounding the narrowest lobes amplify to about 1e-3); the C pdf function agrees
 * with sphera_ggx_brdf_pdf at the input's direction (2e-3); and for the first 16 views, over all 4096 (u0, u1), the
 * means of the direction's x and z (0 for no sample) agree with those of
 * sphera_ggx_brdf_sample within five standard errors of their difference (from the two
 * samples' variances, as if independent). */
static int check_c_vndf(const Pool *pool) {
  int i, j, bad = 0;
  for (i = 0; i < POOL_SIZE; i++) {
    const Input *in = &pool->inputs[i];
    struct VndfC g;
    SpheraGgxBrdf brdf;
    SpheraSample s;
    vndf_prepare(&g, in->wo, in->roughness);
    sphera_ggx_brdf_prepare(&brdf, in->roughness, splat3(0.04f));
    s = vndf_sample(&g, g_u[i][0], g_u[i][1]);
    if (!unit(s.dir)) bad++;
    if (s.dir.z > 1e-3f) {
      float wi[3];
      wi[0] = s.dir.x;
      wi[1] = s.dir.y;
      wi[2] = s.dir.z;
      float expected = sphera_ggx_brdf_pdf(&brdf, vec3(in->wo), s.dir);
      if (!relative_ok(vndf_pdf(&g, wi), expected, 2e-3f) || !relative_ok(s.pdf, expected, 1e-2f)) bad++;
    }
    if (!relative_ok(vndf_pdf(&g, in->dir), sphera_ggx_brdf_pdf(&brdf, vec3(in->wo), vec3(in->dir)), 2e-3f)) bad++;
  }
  if (bad) fprintf(stderr, "FAILED: GGX visible-normal sampling: %d views with a wrong pdf or direction\n", bad);
  for (i = 0; i < 16; i++) {
    const Input *in = &pool->inputs[i];
    struct VndfC g;
    SpheraGgxBrdf brdf;
    /* sums of x, z, x², z² of the C samples [0] and of the library's [1] */
    double sums[2][4] = {{0.0, 0.0, 0.0, 0.0}, {0.0, 0.0, 0.0, 0.0}}, deviation[2];
    int c, k;
    vndf_prepare(&g, in->wo, in->roughness);
    sphera_ggx_brdf_prepare(&brdf, in->roughness, splat3(0.04f));
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s[2];
      s[0] = vndf_sample(&g, g_u[j][0], g_u[j][1]);
      s[1] = sphera_ggx_brdf_sample(&brdf, vec3(in->wo), g_u[j][0], g_u[j][1]);
      for (c = 0; c < 2; c++) {
        double x = s[c].pdf > 0.0f ? s[c].dir.x : 0.0, z = s[c].pdf > 0.0f ? s[c].dir.z : 0.0;
        sums[c][0] += x;
        sums[c][1] += z;
        sums[c][2] += x * x;
        sums[c][3] += z * z;
      }
    }
    /* The standard deviation of (one C sample − one library sample), as if independent. */
    for (k = 0; k < 2; k++) {
      double variance = 0.0;
      for (c = 0; c < 2; c++) {
        double mean = sums[c][k] / U_COUNT;
        variance += sums[c][k + 2] / U_COUNT - mean * mean;
      }
      deviation[k] = sqrt(fmax(variance, 1e-8));
    }
    if (!mean_ok("GGX visible normals, x minus the library's", sums[0][0] - sums[1][0], U_COUNT, 0.0, deviation[0]) ||
        !mean_ok("GGX visible normals, z minus the library's", sums[0][1] - sums[1][1], U_COUNT, 0.0, deviation[1]))
      bad++;
  }
  return bad;
}

/* Cosine-weighted sampling: unit samples above the horizon whose pdf agrees with
 * sphera_lambert_pdf; the mean of z over all (u0, u1) is 2/3 (variance 1/2 − 4/9). */
static int check_c_cosine(void) {
  int j, bad = 0;
  double sum_z = 0.0;
  for (j = 0; j < U_COUNT; j++) {
    SpheraSample s = cosine_sample(g_u[j][0], g_u[j][1]);
    if (!unit(s.dir) || !(s.dir.z > 0.0f) || !relative_ok(s.pdf, sphera_lambert_pdf(s.dir), 1e-4f)) bad++;
    sum_z += s.dir.z;
  }
  if (bad) fprintf(stderr, "FAILED: cosine-weighted sampling: %d samples with a wrong pdf or direction\n", bad);
  if (!mean_ok("cosine-weighted sampling, z", sum_z, U_COUNT, 2.0 / 3.0, sqrt(1.0 / 18.0))) bad++;
  return bad;
}

/* Whether the C terms `a` (diffuse as pdf, specular as dir.x) differ from the library's
 * `b` by more than 1e-3 relative (or 1e-30 absolute); the first four are reported. */
static int vsgl_terms_differ(const char *what, int i, SpheraSample a, SpheraSample b, int reported) {
  if (fabsf(a.pdf - b.pdf) <= 1e-3f * b.pdf + 1e-30f && fabsf(a.dir.x - b.dir.x) <= 1e-3f * b.dir.x + 1e-30f)
    return 0;
  if (reported < 4)
    fprintf(stderr, "%s %d: C diffuse %.9g specular %.9g, library %.9g %.9g\n", what, i, a.pdf, a.dir.x, b.pdf,
            b.dir.x);
  return 1;
}

/* VSGL shading: the C terms agree with the library's (sphera_sg_incoming_radiance,
 * sphera_sg_diffuse_shading_constant_cosine, sphera_sg_specular_shading) to 1e-3
 * relative, or 1e-30 absolute for values the library gives as (almost) 0; and most
 * lobes give positive diffuse and specular terms (the pool is not degenerate). */
static int check_c_vsgl(const Pool *pool) {
  int i, bad = 0, diffuse_positive = 0, specular_positive = 0;
  for (i = 0; i < POOL_SIZE; i++) {
    struct VsglC c;
    struct VsglLobe lib;
    SpheraSample a, b;
    vsgl_c_prepare(&c, &pool->inputs[i]);
    vsgl_lobe_prepare(&lib, &pool->inputs[i]);
    a = vsgl_c_shade(&c, 0.0f, 0.0f);
    b = vsgl_lobe_shade(&lib);
    bad += vsgl_terms_differ("vsgl", i, a, b, bad);
    diffuse_positive += b.pdf > 0.0f;
    specular_positive += b.dir.x > 0.0f;
  }
  if (bad) fprintf(stderr, "FAILED: VSGL shading: %d lobes where the C terms differ from the library's\n", bad);
  if (diffuse_positive < POOL_SIZE / 2 || specular_positive < POOL_SIZE / 4) {
    fprintf(stderr, "FAILED: VSGL shading: only %d diffuse and %d specular terms positive\n", diffuse_positive,
            specular_positive);
    bad++;
  }
  return bad;
}

/* VSGL shading at a prepared point: c_vsgl_point agrees with the library's prepared
 * point (sphera_sg_shading_point_prepare, sphera_sg_incoming_radiance,
 * sphera_sg_shading_point_shade) to 1e-3 relative, or 1e-30 absolute, as check_c_vsgl. */
static int check_c_vsgl_point(const Pool *pool) {
  int i, bad = 0;
  for (i = 0; i < POOL_SIZE; i++) {
    struct VsglPointC c;
    struct VsglPoint lib;
    SpheraSample a, b;
    vsgl_c_point_prepare(&c, &pool->inputs[i]);
    vsgl_point_prepare(&lib, &pool->inputs[i]);
    a = vsgl_c_point_shade(&c, 0.0f, 0.0f);
    b = vsgl_point_shade(&lib);
    bad += vsgl_terms_differ("vsgl point", i, a, b, bad);
  }
  if (bad) fprintf(stderr, "FAILED: VSGL shading at a prepared point: %d lobes where the C terms differ\n", bad);
  return bad;
}

/* vMF sampling: every sample a unit vector whose pdf agrees with sphera_vmf_pdf (1e-3,
 * or 1e-30 absolute far in the tail); and for the first 16 lobes, over all 4096
 * (u0, u1), the mean of cos θ is coth κ − 1/κ (variance at most 1/κ²... bounded by 1). */
static int check_c_vmf(const Pool *pool) {
  int i, j, bad = 0;
  for (i = 0; i < POOL_SIZE; i++) {
    struct VmfC g;
    SpheraSg sg;
    SpheraSample s;
    float expected;
    vmf_c_prepare(&g, &pool->inputs[i]);
    VMF_PREPARE(&sg, &pool->inputs[i]);
    s = vmf_c_sample(&g, g_u[i][0], g_u[i][1]);
    expected = sphera_vmf_pdf(sg, s.dir);
    if (!unit(s.dir) || !(fabsf(s.pdf - expected) <= 1e-3f * expected + 1e-30f)) bad++;
  }
  if (bad) fprintf(stderr, "FAILED: vMF sampling: %d lobes with a wrong pdf or direction\n", bad);
  for (i = 0; i < 16; i++) {
    struct VmfC g;
    double sum = 0.0, k;
    vmf_c_prepare(&g, &pool->inputs[i]);
    k = g.kappa;
    for (j = 0; j < U_COUNT; j++) {
      SpheraSample s = vmf_c_sample(&g, g_u[j][0], g_u[j][1]);
      sum += s.dir.x * g.axis[0] + s.dir.y * g.axis[1] + s.dir.z * g.axis[2];
    }
    /* E[cos θ] = coth κ − 1/κ; the standard deviation of cos θ is at most 1/κ (and 1). */
    if (!mean_ok("vMF sampling, cos θ", sum, U_COUNT, 1.0 / tanh(k) - 1.0 / k, fmin(1.0, 1.0 / k))) bad++;
  }
  return bad;
}

/* ---- main ----------------------------------------------------------------------- */

static int technique_index(const char *id) {
  int t;
  for (t = 0; t < TECHNIQUE_COUNT; t++)
    if (strcmp(TECHNIQUE_LIST[t].id, id) == 0) return t;
  return -1;
}

int main(int argc, char **argv) {
  long reps = 5, calls = 200000;
  const char *only = NULL, *pool_filter = NULL;
  double checksum = 0.0;
  int failures = 0, pools_run = 0, i, t, f;
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
  {
    SpheraVec3 axis;
    axis.x = 0.2f;
    axis.y = 0.0f;
    axis.z = 1.0f;
    g_bent_cone = sphera_cap_from_axis_cos(axis, 0.3f);
  }

  printf("sphera %s, hardware FMA: %s; best of %ld x %ld calls, thread CPU time\n\n", sphera_version(),
         sphera_has_hardware_fma() ? "yes" : "no", reps, calls);
  printf("| technique | prepared struct | sizeof (bytes) |\n|---|---|---:|\n");
  for (t = 0; t < TECHNIQUE_COUNT; t++) {
    printf("| %s | %s | %zu |\n", TECHNIQUE_LIST[t].id, TECHNIQUE_LIST[t].type, TECHNIQUE_LIST[t].size);
    arrays[t] = malloc(TECHNIQUE_LIST[t].size * POOL_SIZE);
    if (!arrays[t]) return 2;
  }

  for (f = 0; f < FAMILY_COUNT; f++) {
    double best_prepare[TECHNIQUE_COUNT], best_sample[TECHNIQUE_COUNT];
    Tally prepare_tally[TECHNIQUE_COUNT], sample_tally[TECHNIQUE_COUNT];
    int runs[TECHNIQUE_COUNT];
    long rep;
    make_pool(pool, (enum Family)f);
    if (pool_filter && strcmp(pool_filter, pool->id) != 0) continue;
    pools_run++;
    if (f == SPHERES) failures += check_c_cone(pool) != 0;
    if (f == BRDF) failures += (check_c_vndf(pool) != 0) + (check_c_cosine() != 0);
    if (f == VSGLS) failures += (check_c_vsgl(pool) != 0) + (check_c_vsgl_point(pool) != 0) + (check_c_vmf(pool) != 0);
    for (t = 0; t < TECHNIQUE_COUNT; t++) {
      runs[t] = TECHNIQUE_LIST[t].family == pool->family && selected(only, TECHNIQUE_LIST[t].id);
      best_prepare[t] = best_sample[t] = 1e300;
      prepare_tally[t].sum = sample_tally[t].sum = 0.0;
      prepare_tally[t].valid = sample_tally[t].valid = 0;
      if (runs[t]) TECHNIQUE_LIST[t].prepare_all(pool, arrays[t]); /* outside the timing */
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
    printf("\n### %s\n\n", pool->title);
    printf("| technique | baseline | ns prepare+1 sample | ns per sample | prepare+1 / baseline | per sample / baseline | valid |\n");
    printf("|---|---|---:|---:|---:|---:|---:|\n");
    for (t = 0; t < TECHNIQUE_COUNT; t++) {
      double ns_prepare = 1e9 * best_prepare[t] / (double)calls, ns_sample = 1e9 * best_sample[t] / (double)calls;
      double valid = 100.0 * (double)(prepare_tally[t].valid + sample_tally[t].valid) / (2.0 * (double)reps * (double)calls);
      int b = technique_index(TECHNIQUE_LIST[t].baseline);
      if (!runs[t]) continue;
      checksum += prepare_tally[t].sum + sample_tally[t].sum;
      printf("| %s | %s | %.1f | %.1f | ", TECHNIQUE_LIST[t].id, TECHNIQUE_LIST[t].baseline, ns_prepare, ns_sample);
      if (b >= 0 && runs[b]) {
        double floor_prepare = 1e9 * best_prepare[b] / (double)calls;
        double floor_sample = 1e9 * best_sample[b] / (double)calls;
        printf("%.2f | %.2f | ", ns_prepare / floor_prepare, ns_sample / floor_sample);
      } else {
        printf("- | - | ");
      }
      printf("%.1f %% |\n", valid);
      if (prepare_tally[t].valid == 0 || sample_tally[t].valid == 0) {
        fprintf(stderr, "FAILED: %s yields no sample with pdf > 0 on %s (%s)\n", TECHNIQUE_LIST[t].id, pool->id,
                prepare_tally[t].valid == 0 ? "prepare + 1 sample" : "per sample");
        failures++;
      }
    }
    if (f == SPHERES && runs[technique_index("sptd")]) {
      const SpheraSphereLightSampler *samplers = (const SpheraSphereLightSampler *)arrays[technique_index("sptd")];
      int sptd = 0;
      for (i = 0; i < POOL_SIZE; i++) sptd += sphera_sphere_light_sampler_uses_sptd(&samplers[i]);
      printf("\nsptd: %d of %d lights sample the SPTD (the others uniformly in the cap).\n", sptd, POOL_SIZE);
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
    fprintf(stderr, "FAILED: %d failed checks or techniques without valid samples\n", failures);
    return 1;
  }
  return 0;
}
