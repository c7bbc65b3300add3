/* C ABI tests of the VSGL accumulator and FIS cluster selection (sphera_vsgl_*): the
 * mean, variance and lobes of small clusters against closed forms in double, texels
 * and merges, the total power of FIS clusters, and bad input (NaN power, null
 * pointers, empty pyramids, n = 0). */
#include <stdlib.h>

#include "check.h"

static unsigned rng_state = 7u;
static float uniform(void) {
  rng_state = rng_state * 1664525u + 1013904223u;
  return (float)(rng_state >> 8) * (1.0f / 16777216.0f);
}

static double luminance(SpheraVec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

static SpheraVpl make_vpl(SpheraVec3 position, SpheraVec3 normal, float power) {
  SpheraVpl vpl;
  vpl.position = position;
  vpl.normal = normal;
  vpl.power = vec3(power, power, power);
  vpl.diffuse_reflectance = vec3(0.5f, 0.5f, 0.5f);
  vpl.specular_reflectance = vec3(0.0f, 0.0f, 0.0f);
  vpl.toward_incoming = normal;
  vpl.roughness = 0.5f;
  return vpl;
}

static int vsgl_is_finite(SpheraVsgl v) {
  return vec3_is_finite(v.diffuse.axis) && isfinite(v.diffuse.sharpness) &&
         isfinite(v.diffuse.log_amplitude) && vec3_is_finite(v.specular.axis) &&
         isfinite(v.specular.sharpness) && isfinite(v.specular.log_amplitude) &&
         vec3_is_finite(v.diffuse_power) && vec3_is_finite(v.specular_power) &&
         vec3_is_finite(v.mean) && isfinite(v.variance) && v.variance >= 0.0f;
}

static int vsgl_is_empty(SpheraVsgl v) {
  return vsgl_is_finite(v) && luminance(v.diffuse_power) == 0.0 &&
         luminance(v.specular_power) == 0.0;
}

static SpheraVsglTexel texel_sum(SpheraVsglTexel a, SpheraVsglTexel b) {
  SpheraVsglTexel t;
  t.diffuse_power = vec3(a.diffuse_power.x + b.diffuse_power.x, a.diffuse_power.y + b.diffuse_power.y,
                         a.diffuse_power.z + b.diffuse_power.z);
  t.specular_power = vec3(a.specular_power.x + b.specular_power.x,
                          a.specular_power.y + b.specular_power.y,
                          a.specular_power.z + b.specular_power.z);
  t.diffuse_direction = vec3(a.diffuse_direction.x + b.diffuse_direction.x,
                             a.diffuse_direction.y + b.diffuse_direction.y,
                             a.diffuse_direction.z + b.diffuse_direction.z);
  t.specular_direction = vec3(a.specular_direction.x + b.specular_direction.x,
                              a.specular_direction.y + b.specular_direction.y,
                              a.specular_direction.z + b.specular_direction.z);
  t.position = vec3(a.position.x + b.position.x, a.position.y + b.position.y,
                    a.position.z + b.position.z);
  t.squared_distance = a.squared_distance + b.squared_distance;
  t.weight = a.weight + b.weight;
  return t;
}

#define SIZE 8

int main(void) {
  SpheraVsglAccumulator acc, other;
  SpheraVsgl v;
  SpheraVec3 origin = vec3(100.0f, 0.0f, -50.0f);
  const float nan = nanf("");

  /* Two VPLs of equal power 2 apart: mean halfway, variance 1 (|y − μ|² = 1 each). */
  CHECK(sphera_vsgl_accumulator_new(&acc, origin));
  {
    SpheraVpl a = make_vpl(vec3(101.0f, 0.0f, -50.0f), vec3(0.0f, 0.0f, 1.0f), 2.0f);
    SpheraVpl b = make_vpl(vec3(99.0f, 0.0f, -50.0f), vec3(0.0f, 0.0f, 1.0f), 2.0f);
    CHECK(sphera_vsgl_accumulator_add_vpl(&acc, &a));
    CHECK(sphera_vsgl_accumulator_add_vpl(&acc, &b));
  }
  v = sphera_vsgl_accumulator_finish(&acc);
  CHECK(vsgl_is_finite(v));
  CHECK_ABS(v.mean.x, 100.0, 1e-4);
  CHECK_ABS(v.variance, 1.0, 1e-5);
  CHECK_REL(v.diffuse_power.y, 2.0, 1e-6); /* 2 VPLs × power 2 × R_d 0.5 */
  CHECK_ABS(v.diffuse.axis.z, 1.0, 1e-6);
  CHECK_REL(v.diffuse.sharpness, SPHERA_SG_DIFFUSE_LOBE_SHARPNESS, 1e-5); /* λ_d of a single normal */
  /* amplitude 1/A(λ_d) = λ_d / (2π (1 − e^(−2λ_d))) */
  CHECK_REL(exp(v.diffuse.log_amplitude),
            SPHERA_SG_DIFFUSE_LOBE_SHARPNESS /
                (2.0 * 3.14159265358979 * (1.0 - exp(-2.0 * SPHERA_SG_DIFFUSE_LOBE_SHARPNESS))),
            1e-5);

  /* Merging the accumulator with itself doubles the power, keeps mean and variance. */
  other = acc;
  CHECK(sphera_vsgl_accumulator_merge(&acc, &other));
  v = sphera_vsgl_accumulator_finish(&acc);
  CHECK_REL(v.diffuse_power.x, 4.0, 1e-6);
  CHECK_ABS(v.variance, 1.0, 1e-5);
  CHECK(sphera_vsgl_accumulator_merge(&acc, &acc));
  CHECK_REL(sphera_vsgl_accumulator_finish(&acc).diffuse_power.x, 8.0, 1e-6);

  /* A texel from a VPL adds like the VPL; a single VPL has variance 0. */
  {
    SpheraVsglTexel t;
    SpheraVpl a = make_vpl(vec3(103.0f, 4.0f, -50.0f), vec3(0.0f, 1.0f, 0.0f), 1.0f);
    SpheraVsgl from_vpl, from_texel;
    CHECK(sphera_vsgl_texel_from_vpl(&a, origin, &t));
    CHECK(sphera_vsgl_accumulator_new(&acc, origin));
    CHECK(sphera_vsgl_accumulator_add_texel(&acc, &t));
    from_texel = sphera_vsgl_accumulator_finish(&acc);
    CHECK(sphera_vsgl_accumulator_new(&acc, origin));
    CHECK(sphera_vsgl_accumulator_add_vpl(&acc, &a));
    from_vpl = sphera_vsgl_accumulator_finish(&acc);
    CHECK(from_vpl.variance == 0.0f && from_texel.variance == 0.0f);
    CHECK(vec3_equal(from_vpl.mean, from_texel.mean));
    CHECK_ABS(from_vpl.mean.y, 4.0, 1e-5);
    CHECK_ABS(from_vpl.diffuse.axis.y, 1.0, 1e-6);
  }

  /* Bad VPLs: NaN position rejected; NaN power channels count as 0. */
  CHECK(sphera_vsgl_accumulator_new(&acc, origin));
  {
    SpheraVpl bad = make_vpl(vec3(nan, 0.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f), 1.0f);
    SpheraVpl nan_power = make_vpl(vec3(100.0f, 0.0f, -50.0f), vec3(0.0f, 0.0f, 1.0f), 1.0f);
    SpheraVsglTexel t;
    CHECK(!sphera_vsgl_accumulator_add_vpl(&acc, &bad));
    CHECK(vsgl_is_empty(sphera_vsgl_accumulator_finish(&acc)));
    CHECK(!sphera_vsgl_texel_from_vpl(&bad, origin, &t));
    CHECK(t.weight == 0.0f);
    nan_power.power = vec3(nan, nan, nan);
    CHECK(sphera_vsgl_accumulator_add_vpl(&acc, &nan_power));
    CHECK(vsgl_is_empty(sphera_vsgl_accumulator_finish(&acc)));
    nan_power.power = vec3(nan, 1.0f, 1.0f);
    CHECK(sphera_vsgl_accumulator_add_vpl(&acc, &nan_power));
    v = sphera_vsgl_accumulator_finish(&acc);
    CHECK(vsgl_is_finite(v) && v.diffuse_power.x == 0.0f && v.diffuse_power.y > 0.0f);
    /* A texel with infinite sums is refused. */
    t.weight = INFINITY;
    CHECK(!sphera_vsgl_accumulator_add_texel(&acc, &t));
  }

  /* Null pointers. */
  {
    SpheraVpl a = make_vpl(vec3(0.0f, 0.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f), 1.0f);
    SpheraVsglTexel t;
    CHECK(!sphera_vsgl_accumulator_new(NULL, origin));
    CHECK(!sphera_vsgl_accumulator_add_vpl(NULL, &a));
    CHECK(!sphera_vsgl_accumulator_add_vpl(&acc, NULL));
    CHECK(!sphera_vsgl_accumulator_add_texel(NULL, &t));
    CHECK(!sphera_vsgl_accumulator_add_texel(&acc, NULL));
    CHECK(!sphera_vsgl_accumulator_merge(NULL, &acc));
    CHECK(!sphera_vsgl_accumulator_merge(&acc, NULL));
    CHECK(vsgl_is_empty(sphera_vsgl_accumulator_finish(NULL)));
    CHECK(!sphera_vsgl_texel_from_vpl(NULL, origin, &t));
    CHECK(!sphera_vsgl_texel_from_vpl(&a, origin, NULL));
  }

  /* FIS over an 8×8 map and its mip pyramid built here. */
  CHECK(sphera_vsgl_pyramid_texel_count(1) == 1);
  CHECK(sphera_vsgl_pyramid_texel_count(8) == 85);
  CHECK(sphera_vsgl_pyramid_texel_count(0) == 0);
  CHECK(sphera_vsgl_pyramid_texel_count(12) == 0);
  CHECK(sphera_vsgl_pyramid_texel_count(1u << 15) == 0);
  {
    SpheraVsglTexel texels[85];
    size_t start = 0, next = SIZE * SIZE;
    int side = SIZE, x, y, i, trial;
    double total = 0.0;
    for (i = 0; i < SIZE * SIZE; i++) {
      SpheraVpl vpl = make_vpl(vec3(100.0f + (float)(i % SIZE), (float)(i / SIZE), -50.0f),
                               vec3(0.0f, 0.0f, 1.0f), (i % 5 == 0) ? 0.0f : 1.0f + 9.0f * uniform());
      vpl.power.x *= 0.5f;
      CHECK(sphera_vsgl_texel_from_vpl(&vpl, origin, &texels[i]));
      total += texels[i].weight;
    }
    while (side > 1) {
      for (y = 0; y < side / 2; y++) {
        for (x = 0; x < side / 2; x++) {
          SpheraVsglTexel a = texels[start + (size_t)(2 * y * side + 2 * x)];
          SpheraVsglTexel b = texels[start + (size_t)(2 * y * side + 2 * x + 1)];
          SpheraVsglTexel c = texels[start + (size_t)((2 * y + 1) * side + 2 * x)];
          SpheraVsglTexel d = texels[start + (size_t)((2 * y + 1) * side + 2 * x + 1)];
          texels[next++] = texel_sum(texel_sum(a, b), texel_sum(c, d));
        }
      }
      start += (size_t)(side * side);
      side /= 2;
    }
    CHECK(next == 85);
    CHECK_REL(texels[84].weight, total, 1e-5);
    for (trial = 0; trial < 100; trial++) {
      const unsigned n = 16;
      double sum = 0.0;
      unsigned k;
      for (k = 0; k < n; k++) {
        v = sphera_vsgl_fis_select(texels, 85, SIZE, origin, n, 1.0f, 8, uniform(), uniform());
        CHECK(vsgl_is_finite(v) && !vsgl_is_empty(v));
        CHECK(v.mean.x >= 100.0f && v.mean.x <= 107.0f && v.mean.y >= 0.0f && v.mean.y <= 7.0f);
        sum += luminance(v.diffuse_power) + luminance(v.specular_power);
      }
      /* the 16 clusters carry the total luminance of the map */
      CHECK_REL(sum, total, 1e-4);
    }
    /* Bad input: no cluster (an empty VSGL), never NaN. */
    CHECK(vsgl_is_empty(sphera_vsgl_fis_select(NULL, 85, SIZE, origin, 16, 1.0f, 8, 0.5f, 0.5f)));
    CHECK(vsgl_is_empty(sphera_vsgl_fis_select(texels, 84, SIZE, origin, 16, 1.0f, 8, 0.5f, 0.5f)));
    CHECK(vsgl_is_empty(sphera_vsgl_fis_select(texels, 85, 6, origin, 16, 1.0f, 8, 0.5f, 0.5f)));
    CHECK(vsgl_is_empty(sphera_vsgl_fis_select(texels, 85, 0, origin, 16, 1.0f, 8, 0.5f, 0.5f)));
    CHECK(vsgl_is_empty(sphera_vsgl_fis_select(texels, 85, SIZE, origin, 0, 1.0f, 8, 0.5f, 0.5f)));
    CHECK(vsgl_is_empty(sphera_vsgl_fis_select(texels, 85, SIZE, origin, 16, nan, 8, 0.5f, 0.5f)));
    CHECK(vsgl_is_empty(sphera_vsgl_fis_select(texels, 85, SIZE, origin, 16, -1.0f, 8, 0.5f, 0.5f)));
    CHECK(vsgl_is_empty(
        sphera_vsgl_fis_select(texels, 85, SIZE, vec3(nan, 0.0f, 0.0f), 16, 1.0f, 8, 0.5f, 0.5f)));
    v = sphera_vsgl_fis_select(texels, 85, SIZE, origin, 16, 1.0f, 8, nan, 2.0f);
    CHECK(vsgl_is_finite(v) && !vsgl_is_empty(v));
    /* An all-black map. */
    for (i = 0; i < 85; i++) texels[i].weight = 0.0f;
    CHECK(vsgl_is_empty(sphera_vsgl_fis_select(texels, 85, SIZE, origin, 16, 1.0f, 8, 0.5f, 0.5f)));
  }
  return check_summary();
}
