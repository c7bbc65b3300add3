/* Determinism through the C ABI: recomputes every record of
 * ffi-tests/determinism_table.txt (written through the Rust entry points by
 * `cargo run -p sphera-tools --bin generate_determinism_table`) with the functions of
 * libsphera.a and requires bit-identical outputs. The record format is documented in
 * tools/src/generators/determinism.rs. */
#include <stdlib.h>
#include <string.h>

#include "check.h"

#define MAX_TOKENS 48

static float bits_to_float(const char *token) {
  uint32_t bits = (uint32_t)strtoul(token, NULL, 16);
  float x;
  memcpy(&x, &bits, sizeof x);
  return x;
}

static uint32_t float_to_bits(float x) {
  uint32_t bits;
  memcpy(&bits, &x, sizeof bits);
  return bits;
}

static int mismatches_printed = 0;

/* Compares n outputs with the tokens from `first` on; reports the line on a mismatch. */
static void expect_bits(const float *outputs, int n, char **tokens, int first, int line) {
  int i, ok = 1;
  for (i = 0; i < n; i++)
    if (float_to_bits(outputs[i]) != (uint32_t)strtoul(tokens[first + i], NULL, 16)) ok = 0;
  if (!ok && mismatches_printed++ < 20) {
    printf("line %d differs:", line);
    for (i = 0; i < n; i++) printf(" %08lx/%s", (unsigned long)float_to_bits(outputs[i]), tokens[first + i]);
    printf("\n");
  }
  CHECK(ok);
}

static SpheraVec3 polygons[16][SPHERA_MAX_POLYGON_VERTICES];
static uint32_t counts[16];

static SpheraVpl vpls[16];

/* Reads a vector from tokens[i..i + 3]. */
static SpheraVec3 read3(char **tokens, int i) {
  return vec3(bits_to_float(tokens[i]), bits_to_float(tokens[i + 1]), bits_to_float(tokens[i + 2]));
}

static void sg_outputs(SpheraSg g, float *o) {
  o[0] = g.axis.x, o[1] = g.axis.y, o[2] = g.axis.z, o[3] = g.sharpness, o[4] = g.log_amplitude;
}

static void vec3_outputs(SpheraVec3 v, float *o) { o[0] = v.x, o[1] = v.y, o[2] = v.z; }

static void vsgl_outputs(SpheraVsgl v, float *o) {
  sg_outputs(v.diffuse, o);
  sg_outputs(v.specular, o + 5);
  vec3_outputs(v.diffuse_power, o + 10);
  vec3_outputs(v.specular_power, o + 13);
  vec3_outputs(v.mean, o + 16);
  o[19] = v.variance;
}

static void sample_outputs(SpheraSample s, float *o) {
  o[0] = s.dir.x;
  o[1] = s.dir.y;
  o[2] = s.dir.z;
  o[3] = s.pdf;
}

int main(void) {
  const char *paths[3] = {"../ffi-tests/determinism_table.txt", "ffi-tests/determinism_table.txt",
                          "determinism_table.txt"};
  FILE *file = NULL;
  char buffer[2048];
  char *tokens[MAX_TOKENS];
  int i, line = 0, records = 0;
  SpheraLtc ltc;
  SpheraMaterial material;

  for (i = 0; i < 3 && file == NULL; i++) file = fopen(paths[i], "r");
  CHECK(file != NULL);
  if (file == NULL) return check_summary();
  CHECK(sphera_ltc_prepare(&ltc, vec3(0.3f, 0.1f, 0.9f), 0.4f));
  material.diffuse = vec3(0.5f, 0.5f, 0.5f);
  material.f0 = vec3(0.04f, 0.04f, 0.04f);
  material.roughness = 0.4f;

  while (fgets(buffer, sizeof buffer, file) != NULL) {
    int n = 0;
    char *token;
    const char *kind;
    float o[32];
    line++;
    if (buffer[0] == '#' || buffer[0] == '\n') continue;
    for (token = strtok(buffer, " \n"); token != NULL && n < MAX_TOKENS; token = strtok(NULL, " \n"))
      tokens[n++] = token;
    kind = tokens[0];
    records++;
    if (strcmp(kind, "polygon") == 0) {
      int id = atoi(tokens[1]), k;
      counts[id] = (uint32_t)atoi(tokens[2]);
      for (k = 0; k < (int)counts[id]; k++)
        polygons[id][k] = vec3(bits_to_float(tokens[3 + 3 * k]), bits_to_float(tokens[4 + 3 * k]),
                               bits_to_float(tokens[5 + 3 * k]));
      continue;
    }
    if (strcmp(kind, "light") == 0) {
      int id = atoi(tokens[1]);
      uint32_t technique = (uint32_t)atoi(tokens[2]);
      SpheraPolygonLight light;
      SpheraLightSample s;
      sphera_polygon_light_prepare(&light, polygons[id], counts[id], vec3(0.3f, 0.1f, 0.9f),
                                   &material, SPHERA_MIS_CLAMPED_OPTIMAL, 0.5f);
      s = sphera_polygon_light_sample(&light, technique, bits_to_float(tokens[3]),
                                      bits_to_float(tokens[4]));
      o[0] = s.dir.x, o[1] = s.dir.y, o[2] = s.dir.z, o[3] = s.pdf;
      o[4] = s.visible.x, o[5] = s.visible.y, o[6] = s.visible.z;
      o[7] = s.unoccluded.x, o[8] = s.unoccluded.y, o[9] = s.unoccluded.z;
      expect_bits(o, 10, tokens, 5, line);
      continue;
    }
    if (strcmp(kind, "ggx") == 0) {
      SpheraGgxBrdf brdf;
      sphera_ggx_brdf_prepare(&brdf, bits_to_float(tokens[1]), vec3(1.0f, 1.0f, 1.0f));
      sample_outputs(sphera_ggx_brdf_sample(&brdf,
                                       vec3(bits_to_float(tokens[2]), bits_to_float(tokens[3]),
                                            bits_to_float(tokens[4])),
                                       bits_to_float(tokens[5]), bits_to_float(tokens[6])),
                     o);
      expect_bits(o, 4, tokens, 7, line);
      continue;
    }
    if (strcmp(kind, "lambert") == 0) {
      sample_outputs(sphera_lambert_sample(bits_to_float(tokens[1]), bits_to_float(tokens[2])), o);
      expect_bits(o, 4, tokens, 3, line);
      continue;
    }
    if (strcmp(kind, "cap") == 0) {
      SpheraCap cap = sphera_cap_from_sphere(
          vec3(bits_to_float(tokens[1]), bits_to_float(tokens[2]), bits_to_float(tokens[3])),
          bits_to_float(tokens[4]));
      sample_outputs(sphera_cap_sample_uniform(cap, bits_to_float(tokens[5]), bits_to_float(tokens[6])), o);
      expect_bits(o, 4, tokens, 7, line);
      continue;
    }
    if (strcmp(kind, "pivot_phase") == 0 || strcmp(kind, "hg_phase") == 0) {
      SpheraVec3 wo = vec3(bits_to_float(tokens[1]), bits_to_float(tokens[2]), bits_to_float(tokens[3]));
      float g = bits_to_float(tokens[4]), u0 = bits_to_float(tokens[5]), u1 = bits_to_float(tokens[6]);
      sample_outputs(kind[0] == 'p' ? sphera_phase_pivot_sample(wo, g, u0, u1)
                                    : sphera_phase_henyey_greenstein_sample(wo, g, u0, u1),
                     o);
      expect_bits(o, 4, tokens, 7, line);
      continue;
    }
    if (strcmp(kind, "sptd_in_cap") == 0) {
      SpheraSptdInCap p;
      SpheraSample s;
      SpheraCap cap = sphera_cap_from_sphere(read3(tokens, 8), bits_to_float(tokens[11]));
      sphera_sptd_in_cap_prepare(&p, read3(tokens, 2), (uint32_t)atoi(tokens[1]), read3(tokens, 5), cap);
      s = sphera_sptd_in_cap_sample(&p, bits_to_float(tokens[12]), bits_to_float(tokens[13]));
      sample_outputs(s, o);
      o[4] = sphera_sptd_in_cap_pdf(&p, s.dir);
      o[5] = sphera_sptd_in_cap_integral(&p);
      expect_bits(o, 6, tokens, 14, line);
      continue;
    }
    if (strcmp(kind, "phase_in_cap") == 0) {
      SpheraSptdInCap p;
      SpheraCap cap = sphera_cap_from_sphere(read3(tokens, 5), bits_to_float(tokens[8]));
      sphera_sptd_in_cap_prepare_pivot_phase(&p, read3(tokens, 1), bits_to_float(tokens[4]), cap);
      sample_outputs(sphera_sptd_in_cap_sample(&p, bits_to_float(tokens[9]), bits_to_float(tokens[10])), o);
      expect_bits(o, 4, tokens, 11, line);
      continue;
    }
    if (strcmp(kind, "light_sampler") == 0) {
      SpheraSphereLightSampler p;
      SpheraSample s;
      sphera_sphere_light_sampler_prepare(&p, read3(tokens, 1), bits_to_float(tokens[4]),
                                          read3(tokens, 5), bits_to_float(tokens[8]));
      s = sphera_sphere_light_sampler_sample(&p, bits_to_float(tokens[9]), bits_to_float(tokens[10]));
      sample_outputs(s, o);
      o[4] = sphera_sphere_light_sampler_pdf(&p, s.dir);
      expect_bits(o, 5, tokens, 11, line);
      continue;
    }
    if (strcmp(kind, "sphere_shade") == 0) {
      SpheraSphereLightShading shading;
      SpheraCap light = sphera_cap_from_sphere(read3(tokens, 8), bits_to_float(tokens[11]));
      SpheraCap cone = sphera_cap_from_axis_cos(read3(tokens, 12), bits_to_float(tokens[15]));
      sphera_sphere_light_shading_prepare(&shading, read3(tokens, 1), bits_to_float(tokens[4]),
                                          read3(tokens, 5));
      vec3_outputs(sphera_sphere_light_shading_eval(&shading, light), o);
      vec3_outputs(sphera_sphere_light_shading_eval_occluded(&shading, light, cone), o + 3);
      expect_bits(o, 6, tokens, 16, line);
      continue;
    }
    if (strcmp(kind, "vmf") == 0) {
      SpheraSg g = sphera_sg_new(read3(tokens, 1), bits_to_float(tokens[4]), 1.0f);
      sample_outputs(sphera_vmf_sample(g, bits_to_float(tokens[5]), bits_to_float(tokens[6])), o);
      expect_bits(o, 4, tokens, 7, line);
      continue;
    }
    if (strcmp(kind, "sg_pair") == 0) {
      SpheraSg a = sphera_sg_new(read3(tokens, 1), bits_to_float(tokens[4]), bits_to_float(tokens[5]));
      SpheraSg b = sphera_sg_new(read3(tokens, 6), bits_to_float(tokens[9]), bits_to_float(tokens[10]));
      sg_outputs(sphera_sg_product(a, b), o);
      o[5] = sphera_sg_inner_product(a, b);
      expect_bits(o, 6, tokens, 11, line);
      continue;
    }
    if (strcmp(kind, "sg_shading") == 0) {
      SpheraSg sg = sphera_sg_new(read3(tokens, 1), bits_to_float(tokens[4]), bits_to_float(tokens[5]));
      SpheraVec3 normal = read3(tokens, 6), view = read3(tokens, 9);
      float roughness = bits_to_float(tokens[12]);
      SpheraSg incoming = sphera_sg_incoming_radiance(sg, read3(tokens, 13), bits_to_float(tokens[16]));
      SpheraAsg asg = sphera_asg_from_ggx(normal, view, roughness * roughness);
      sg_outputs(incoming, o);
      o[5] = sphera_asg_convolve_sg(asg, incoming);
      o[6] = sphera_sg_specular_shading(incoming, normal, view, roughness, 0.04f, 1.0f);
      o[7] = sphera_sg_specular_shading_sg(incoming, normal, view, roughness, 0.04f, 1.0f);
      o[8] = sphera_sg_diffuse_shading_product(incoming, normal, 0.5f, 1.0f);
      o[9] = sphera_sg_diffuse_shading_constant_cosine(incoming, normal, 0.5f, 1.0f);
      o[10] = sphera_sg_diffuse_shading_sharp_lobe(incoming, normal, 0.5f, 1.0f);
      expect_bits(o, 11, tokens, 17, line);
      continue;
    }
    if (strcmp(kind, "vpl") == 0) {
      SpheraVpl *v = &vpls[atoi(tokens[1])];
      v->position = read3(tokens, 2);
      v->normal = read3(tokens, 5);
      v->power = read3(tokens, 8);
      v->diffuse_reflectance = read3(tokens, 11);
      v->specular_reflectance = read3(tokens, 14);
      v->toward_incoming = read3(tokens, 17);
      v->roughness = bits_to_float(tokens[20]);
      continue;
    }
    if (strcmp(kind, "vsgl_finish") == 0) {
      SpheraVsglAccumulator acc;
      int first = atoi(tokens[1]), count = atoi(tokens[2]), k;
      sphera_vsgl_accumulator_new(&acc, vec3(0.0f, 0.0f, 0.0f));
      for (k = first; k < first + count; k++) sphera_vsgl_accumulator_add_vpl(&acc, &vpls[k]);
      vsgl_outputs(sphera_vsgl_accumulator_finish(&acc), o);
      expect_bits(o, 20, tokens, 3, line);
      continue;
    }
    if (strcmp(kind, "fis") == 0) {
      SpheraVsglTexel pyramid[5];
      SpheraVsglAccumulator acc;
      SpheraVec3 origin = vec3(0.0f, 0.0f, 0.0f);
      int k;
      sphera_vsgl_accumulator_new(&acc, origin);
      for (k = 0; k < 4; k++) {
        sphera_vsgl_texel_from_vpl(&vpls[k], origin, &pyramid[k]);
        sphera_vsgl_accumulator_add_texel(&acc, &pyramid[k]);
      }
      pyramid[4] = acc.sums;
      vsgl_outputs(sphera_vsgl_fis_select(pyramid, 5, 2, origin, (uint32_t)atoi(tokens[1]),
                                          bits_to_float(tokens[2]), (uint32_t)atoi(tokens[3]),
                                          bits_to_float(tokens[4]), bits_to_float(tokens[5])),
                   o);
      expect_bits(o, 20, tokens, 6, line);
      continue;
    }
    /* The polygon samplers: <sampler> <id> <u0> <u1> -> dir, pdf. */
    {
      int id = atoi(tokens[1]);
      float u0 = bits_to_float(tokens[2]), u1 = bits_to_float(tokens[3]);
      const SpheraVec3 *v = polygons[id];
      uint32_t count = counts[id];
      SpheraSample s;
      s.pdf = -1.0f;
      s.dir = vec3(0.0f, 0.0f, 0.0f);
      if (strcmp(kind, "solid_angle") == 0) {
        SpheraSolidAnglePolygon p;
        sphera_solid_angle_polygon_prepare(&p, v, count);
        s = sphera_solid_angle_polygon_sample(&p, u0, u1);
      } else if (strcmp(kind, "turk") == 0) {
        SpheraTurkPolygon p;
        sphera_turk_polygon_prepare(&p, v, count);
        s = sphera_turk_polygon_sample(&p, u0, u1);
      } else if (strcmp(kind, "arvo") == 0) {
        SpheraArvoPolygon p;
        sphera_arvo_polygon_prepare(&p, v, count);
        s = sphera_arvo_polygon_sample(&p, u0, u1);
      } else if (strcmp(kind, "hart_bilinear") == 0) {
        SpheraHartBilinearPolygon p;
        sphera_hart_bilinear_polygon_prepare(&p, v, count);
        s = sphera_hart_bilinear_polygon_sample(&p, u0, u1);
      } else if (strcmp(kind, "hart_biquadratic") == 0) {
        SpheraHartBiquadraticPolygon p;
        sphera_hart_biquadratic_polygon_prepare(&p, v, count);
        s = sphera_hart_biquadratic_polygon_sample(&p, u0, u1);
      } else if (strcmp(kind, "clipped_solid_angle") == 0) {
        SpheraClippedSolidAnglePolygon p;
        sphera_clipped_solid_angle_polygon_prepare(&p, v, count);
        s = sphera_clipped_solid_angle_polygon_sample(&p, u0, u1);
      } else if (strcmp(kind, "projected") == 0) {
        SpheraProjectedPolygon p;
        sphera_projected_polygon_prepare(&p, v, count);
        s = sphera_projected_polygon_sample(&p, u0, u1);
      } else if (strcmp(kind, "projected_fast") == 0) {
        SpheraProjectedPolygon p;
        sphera_projected_polygon_prepare_fast(&p, v, count);
        s = sphera_projected_polygon_sample_fast(&p, u0, u1);
      } else if (strcmp(kind, "arvo_projected") == 0) {
        SpheraArvoProjectedPolygon p;
        sphera_arvo_projected_polygon_prepare(&p, v, count);
        s = sphera_arvo_projected_polygon_sample(&p, u0, u1);
      } else if (strcmp(kind, "ltc") == 0) {
        SpheraLtcPolygon p;
        sphera_ltc_polygon_prepare(&p, &ltc, v, count);
        s = sphera_ltc_polygon_sample(&p, u0, u1);
      } else {
        printf("line %d: unknown record %s\n", line, kind);
        CHECK(0);
        continue;
      }
      sample_outputs(s, o);
      expect_bits(o, 4, tokens, 4, line);
    }
  }
  fclose(file);
  printf("%d records\n", records);
  CHECK(records > 900);
  return check_summary();
}
