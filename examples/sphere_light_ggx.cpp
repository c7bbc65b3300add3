// The radiance that a glossy GGX surface reflects from a sphere light, by multiple
// importance sampling of two techniques: joint sampling (a spherical pivot-transformed
// distribution fitted to GGX × cos, restricted to the light's cap; Dupuy et al. 2017)
// and GGX visible-normal sampling, one sample each per round, balance heuristic. A
// brute-force estimate by uniform cap sampling and the biased real-time shading of the
// same light are printed for comparison. Nothing occludes the light here; a renderer
// traces a shadow ray for the light sample and a ray for the BRDF sample.
//
// Build: c++ -std=c++11 sphere_light_ggx.cpp -I<prefix>/include <prefix>/lib/libsphera.a -lm
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "sphera.h"

namespace {

// Random numbers in [0, 1): a small LCG; use your renderer's sampler instead.
struct Rng {
  std::uint32_t state = 7u;
  float next() {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) * (1.0f / 16777216.0f);
  }
};

// The mean and standard error of an RGB estimate.
struct Estimate {
  double sum[3] = {0.0, 0.0, 0.0}, squares[3] = {0.0, 0.0, 0.0};
  int count = 0;
  void add(const double x[3]) {
    for (int c = 0; c < 3; c++) sum[c] += x[c], squares[c] += x[c] * x[c];
    count++;
  }
  void print(const char *name) const {
    std::printf("%s", name);
    for (int c = 0; c < 3; c++) std::printf(" %.6f", sum[c] / count);
    std::printf(" standard error");
    for (int c = 0; c < 3; c++) {
      double mean = sum[c] / count;
      std::printf(" %.6f", std::sqrt((squares[c] / count - mean * mean) / count));
    }
    std::printf("\n");
  }
};

// Adds radiance × f × cos θ / pdf × weight to x.
void accumulate(double x[3], SpheraVec3 f, float radiance, float cos_theta, float pdf,
                float weight) {
  const double scale = static_cast<double>(radiance) * cos_theta / pdf * weight;
  x[0] += f.x * scale, x[1] += f.y * scale, x[2] += f.z * scale;
}

}  // namespace

int main() {
  if (!sphera_check_version(SPHERA_VERSION_MAJOR, SPHERA_VERSION_MINOR)) return 1;
  // In the local frame of the shading point (z = normal): the view, a sphere light of
  // radius 1 near the mirror direction, and a gold-like GGX surface.
  const SpheraVec3 wo = {0.5f, 0.0f, 0.8660254f};
  const SpheraVec3 center = {-1.5f, 0.3f, 2.6f};
  const float radius = 1.0f, radiance = 4.0f, roughness = 0.3f;
  const SpheraVec3 f0 = {1.0f, 0.78f, 0.34f};
  const int rounds = 200000;

  SpheraGgxBrdf brdf;
  SpheraSphereLightSampler light;
  sphera_ggx_brdf_prepare(&brdf, roughness, f0);
  if (!sphera_sphere_light_sampler_prepare(&light, center, radius, wo, roughness)) return 1;
  const SpheraCap cap = sphera_cap_from_sphere(center, radius);  // the light's directions

  Rng rng;
  Estimate mis, uniform;
  for (int i = 0; i < rounds; i++) {
    double x[3] = {0.0, 0.0, 0.0};
    // Light sample, drawn jointly for the light and the BRDF.
    SpheraSample s = sphera_sphere_light_sampler_sample(&light, rng.next(), rng.next());
    if (s.pdf > 0.0f)
      accumulate(x, sphera_ggx_brdf_eval(&brdf, wo, s.dir), radiance, s.dir.z, s.pdf,
                 sphera_mis_balance(s.pdf, sphera_ggx_brdf_pdf(&brdf, wo, s.dir)));
    // BRDF sample; it counts where it hits the light.
    SpheraSample b = sphera_ggx_brdf_sample(&brdf, wo, rng.next(), rng.next());
    if (b.pdf > 0.0f && sphera_cap_contains(cap, b.dir))
      accumulate(x, sphera_ggx_brdf_eval(&brdf, wo, b.dir), radiance, b.dir.z, b.pdf,
                 sphera_mis_balance(b.pdf, sphera_sphere_light_sampler_pdf(&light, b.dir)));
    mis.add(x);
  }
  // Brute force: uniform directions in the cap, four per round.
  for (int i = 0; i < 4 * rounds; i++) {
    double x[3] = {0.0, 0.0, 0.0};
    SpheraSample u = sphera_cap_sample_uniform(cap, rng.next(), rng.next());
    if (u.pdf > 0.0f && u.dir.z > 0.0f)
      accumulate(x, sphera_ggx_brdf_eval(&brdf, wo, u.dir), radiance, u.dir.z, u.pdf, 1.0f);
    uniform.add(x);
  }
  mis.print("mis");
  uniform.print("uniform");
  // The real-time approximation (biased): one call per light, no samples.
  SpheraSphereLightShading shading;
  sphera_sphere_light_shading_prepare(&shading, wo, roughness, f0);
  const SpheraVec3 shaded = sphera_sphere_light_shading_eval(&shading, cap);
  std::printf("real-time %.6f %.6f %.6f\n", radiance * shaded.x, radiance * shaded.y,
              radiance * shaded.z);
  return 0;
}
