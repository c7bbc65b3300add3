/*
 * End to end through the example tracer (bench/src), linked with libsphera.a and
 * Embree 3 the way an engine links them:
 *
 * 1. The Cornell box at low resolution, rendered with every unbiased technique: the
 *    image means agree with one another within 5 standard errors (the standard errors
 *    come from the per-pixel variance across passes).
 * 2. The sphere lights of `spheres` at low resolution: joint SPTD light sampling
 *    (sphere_sptd) agrees with one cap and one BRDF sample (sphere_cap_brdf) within 5
 *    standard errors, and the biased real-time SPTD shading (sphere_realtime) stays
 *    within 2% of them.
 * 3. The `slab` medium: in-scattering by the pivot phase function restricted to the
 *    light's cap (medium_pivot) agrees with HG + uniform cap sampling (medium_hg_cap)
 *    within 5 standard errors, with a lower variance.
 * 4. The `occlusion` well: specular occlusion by SPTDs in a traced bent cone (Eq. 23)
 *    keeps out the light that the wall hides from the floor in front of the well, where
 *    the separable approximation (Eq. 21-22) lets it through.
 * 5. Two intersecting sphere lights of equal radiance (`overlap`) sampled as one light:
 *    uniformly in the union of their caps (sphere_union) and by the mixture of either
 *    light's cap (sphere_mixture) agree with a cap sample per light (sphere_cap), and
 *    the union has the lower variance at equal samples.
 * 6. One unoccluded quad light over a white Lambert floor: projected solid angle
 *    sampling gives every pixel the same value in every pass, so the per-pixel
 *    variance is zero up to float rounding (the central claim of Peters 2021), while
 *    solid angle sampling of the same scene is visibly noisy (so the test can fail).
 *
 * The renderer turns on flush-to-zero and denormals-are-zero, as Embree asks, so this
 * also runs the library in that floating-point environment.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "tracer.h"

static bool render_scene(const char *name, Technique technique, uint32_t width, uint32_t height,
                         uint32_t passes, RenderResult *result) {
    Scene scene;
    if (!scene_create(&scene, name, (float)width / (float)height)) return false;
    RenderSettings settings = {0};
    settings.width = width;
    settings.height = height;
    settings.technique = technique;
    settings.light_samples = 1;
    settings.passes = passes;
    settings.threads = 2;
    settings.seed = 7 + (uint64_t)technique;
    bool ok = render(&scene, &settings, result);
    scene_destroy(&scene);
    return ok;
}

static void unbiased_techniques_agree_in_the_cornell_box(void) {
    const uint32_t width = 40, height = 30, passes = 24;
    RenderResult results[TECHNIQUE_COUNT];
    bool rendered[TECHNIQUE_COUNT] = {false};
    for (int t = 0; t < TECHNIQUE_COUNT; ++t) {
        if (technique_info[t].biased) continue;
        rendered[t] = render_scene("cornell", (Technique)t, width, height, passes, &results[t]);
        CHECK(rendered[t]);
        if (!rendered[t]) continue;
        printf("cornell %-20s mean %.6f %.6f %.6f  stderr %.2e %.2e %.2e\n", technique_info[t].name,
               results[t].mean[0], results[t].mean[1], results[t].mean[2],
               results[t].mean_stderr[0], results[t].mean_stderr[1], results[t].mean_stderr[2]);
        /* every technique sees light: the image is not black and has noise estimates */
        CHECK(results[t].mean[0] > 0.1 && results[t].mean_stderr[0] > 0.0);
    }
    int compared = 0;
    for (int a = 0; a < TECHNIQUE_COUNT; ++a) {
        for (int b = a + 1; b < TECHNIQUE_COUNT; ++b) {
            if (!rendered[a] || !rendered[b]) continue;
            for (int c = 0; c < 3; ++c) {
                double sa = results[a].mean_stderr[c], sb = results[b].mean_stderr[c];
                double tolerance = 5.0 * sqrt(sa * sa + sb * sb) + 1e-5 * results[a].mean[c];
                if (!CHECK(fabs(results[a].mean[c] - results[b].mean[c]) <= tolerance))
                    printf("    %s vs %s, channel %d: %.7f vs %.7f, tolerance %.2e\n",
                           technique_info[a].name, technique_info[b].name, c, results[a].mean[c],
                           results[b].mean[c], tolerance);
                ++compared;
            }
        }
    }
    CHECK(compared >= 3 * 28); /* at least the 8 unbiased techniques and the reference */
    for (int t = 0; t < TECHNIQUE_COUNT; ++t)
        if (rendered[t]) render_result_free(&results[t]);
}

static void sphere_light_techniques_agree(void) {
    const uint32_t width = 48, height = 36, passes = 24;
    const Technique techniques[3] = {TECHNIQUE_SPHERE_CAP_BRDF, TECHNIQUE_SPHERE_SPTD,
                                     TECHNIQUE_SPHERE_REALTIME};
    RenderResult r[3];
    for (int t = 0; t < 3; ++t) {
        if (!CHECK(render_scene("spheres", techniques[t], width, height, passes, &r[t]))) {
            for (int i = 0; i < t; ++i) render_result_free(&r[i]);
            return;
        }
        printf("spheres %-20s mean %.6f %.6f %.6f  stderr %.2e %.2e %.2e\n",
               technique_info[techniques[t]].name, r[t].mean[0], r[t].mean[1], r[t].mean[2],
               r[t].mean_stderr[0], r[t].mean_stderr[1], r[t].mean_stderr[2]);
        CHECK(r[t].mean[0] > 0.05 && r[t].mean_stderr[0] > 0.0);
    }
    for (int c = 0; c < 3; ++c) {
        double sa = r[0].mean_stderr[c], sb = r[1].mean_stderr[c];
        double tolerance = 5.0 * sqrt(sa * sa + sb * sb) + 1e-5 * r[0].mean[c];
        if (!CHECK(fabs(r[0].mean[c] - r[1].mean[c]) <= tolerance))
            printf("    sphere_cap_brdf vs sphere_sptd, channel %d: %.7f vs %.7f, tolerance %.2e\n",
                   c, r[0].mean[c], r[1].mean[c], tolerance);
        /* biased: the SPTD fit and the one-ray visibility; measured 0.1% here */
        double bias = fabs(r[2].mean[c] - r[1].mean[c]) / r[1].mean[c];
        if (!CHECK(bias < 0.02))
            printf("    sphere_realtime vs sphere_sptd, channel %d: relative difference %.3g\n", c,
                   bias);
    }
    for (int t = 0; t < 3; ++t) render_result_free(&r[t]);
}

static void medium_techniques_agree(void) {
    const uint32_t width = 48, height = 36, passes = 24;
    RenderResult pivot, hg_cap;
    if (!CHECK(render_scene("slab", TECHNIQUE_MEDIUM_PIVOT, width, height, passes, &pivot))) return;
    if (!CHECK(render_scene("slab", TECHNIQUE_MEDIUM_HG_CAP, width, height, passes, &hg_cap))) {
        render_result_free(&pivot);
        return;
    }
    printf("slab: mean %.6f (medium_pivot) vs %.6f (medium_hg_cap), variance of the mean "
           "%.3e vs %.3e\n",
           pivot.mean[0], hg_cap.mean[0], pivot.variance_of_mean, hg_cap.variance_of_mean);
    for (int c = 0; c < 3; ++c) {
        double sa = pivot.mean_stderr[c], sb = hg_cap.mean_stderr[c];
        CHECK(pivot.mean[c] > 0.05 && sa > 0.0 && sb > 0.0);
        double tolerance = 5.0 * sqrt(sa * sa + sb * sb) + 1e-5 * pivot.mean[c];
        CHECK(fabs(pivot.mean[c] - hg_cap.mean[c]) <= tolerance);
    }
    /* measured 0.46 at 96 x 72 (the floor's and the distance's noise are shared) */
    CHECK(pivot.variance_of_mean < 0.8 * hg_cap.variance_of_mean);
    render_result_free(&pivot);
    render_result_free(&hg_cap);
}

/* Two intersecting sphere lights of equal radiance (`overlap`), sampled as one light:
 * uniformly in the union of their caps (sphere_union, SpheraCapUnion) and by the
 * mixture of one cap sample of either light (sphere_mixture) agree with a cap sample per
 * light (sphere_cap) within 5 standard errors, and the union has the lower variance at
 * equal samples. */
static void sphere_union_agrees_and_beats_the_mixture(void) {
    const uint32_t width = 48, height = 36, passes = 24;
    const Technique techniques[3] = {TECHNIQUE_SPHERE_CAP, TECHNIQUE_SPHERE_MIXTURE,
                                     TECHNIQUE_SPHERE_UNION};
    RenderResult r[3];
    for (int t = 0; t < 3; ++t) {
        if (!CHECK(render_scene("overlap", techniques[t], width, height, passes, &r[t]))) {
            for (int i = 0; i < t; ++i) render_result_free(&r[i]);
            return;
        }
        printf("overlap %-16s mean %.6f %.6f %.6f  stderr %.2e %.2e %.2e  variance of the "
               "mean %.3e\n",
               technique_info[techniques[t]].name, r[t].mean[0], r[t].mean[1], r[t].mean[2],
               r[t].mean_stderr[0], r[t].mean_stderr[1], r[t].mean_stderr[2],
               r[t].variance_of_mean);
        CHECK(r[t].mean[0] > 0.05 && r[t].mean_stderr[0] > 0.0);
    }
    for (int t = 1; t < 3; ++t) {
        for (int c = 0; c < 3; ++c) {
            double sa = r[0].mean_stderr[c], sb = r[t].mean_stderr[c];
            double tolerance = 5.0 * sqrt(sa * sa + sb * sb) + 1e-5 * r[0].mean[c];
            if (!CHECK(fabs(r[0].mean[c] - r[t].mean[c]) <= tolerance))
                printf("    sphere_cap vs %s, channel %d: %.7f vs %.7f, tolerance %.2e\n",
                       technique_info[techniques[t]].name, c, r[0].mean[c], r[t].mean[c],
                       tolerance);
        }
    }
    /* measured 0.68 at 48 x 36 (0.66 at 128 x 96) */
    CHECK(r[2].variance_of_mean < 0.95 * r[1].variance_of_mean);
    for (int t = 0; t < 3; ++t) render_result_free(&r[t]);
}

/* The mean over the channels of the image's rows [first, end). */
static double rows_mean(const RenderResult *r, uint32_t width, uint32_t first, uint32_t end) {
    double sum = 0.0;
    for (uint32_t i = 3 * width * first; i < 3 * width * end; ++i) sum += r->image[i];
    return sum / (3.0 * width * (end - first));
}

/* Specular occlusion in the `occlusion` well (Dupuy et al. 2017, Sec. 5.4): the
 * separable approximation (Eq. 21) lets the light through where the well's wall hides
 * it from the floor in front of the well (the image's bottom rows), as a bent cone that
 * holds most of the BRDF lobe does not tell it that the light is outside (shadow
 * leaking, the paper's Fig. 11 d); the triple product (Eq. 23) keeps the cone's
 * correlation with the light and lets none through. Over the whole image both stay
 * within 10% of the ray-traced mean (measured -4% and +1% at 128 x 96). */
static void specular_occlusion_keeps_the_light_out_where_the_separable_form_leaks(void) {
    const uint32_t width = 48, height = 36, passes = 16;
    const Technique techniques[3] = {TECHNIQUE_SPHERE_CAP_BRDF, TECHNIQUE_SPHERE_OCCLUSION,
                                     TECHNIQUE_SPHERE_OCCLUSION_SEPARABLE};
    RenderResult r[3];
    for (int t = 0; t < 3; ++t) {
        if (!CHECK(render_scene("occlusion", techniques[t], width, height, passes, &r[t]))) {
            for (int i = 0; i < t; ++i) render_result_free(&r[i]);
            return;
        }
    }
    const uint32_t front = height - height / 6;
    double traced = rows_mean(&r[0], width, front, height);
    double triple = rows_mean(&r[1], width, front, height);
    double separable = rows_mean(&r[2], width, front, height);
    printf("occlusion: in front of the well %.3e (ray traced), %.3e (Eq. 23), %.3e (Eq. 21); "
           "image means %.4f, %.4f, %.4f\n",
           traced, triple, separable, r[0].mean[0], r[1].mean[0], r[2].mean[0]);
    CHECK(separable > 2.0 * traced + 1e-4);
    CHECK(triple < 0.5 * separable);
    for (int t = 1; t < 3; ++t)
        CHECK(fabs(r[t].mean[0] - r[0].mean[0]) < 0.1 * r[0].mean[0]);
    for (int t = 0; t < 3; ++t) render_result_free(&r[t]);
}

/* The largest per-pixel standard deviation of one pass's value, relative to the pixel's
 * mean, over pixels that receive light. */
static double worst_relative_deviation(const RenderResult *r, uint32_t pixels, uint32_t *lit) {
    double worst = 0.0;
    *lit = 0;
    for (uint32_t i = 0; i < 3 * pixels; ++i) {
        if (!(r->image[i] > 1e-4f)) continue;
        ++*lit;
        /* variance holds the variance of the mean: times passes is that of one pass */
        double deviation = sqrt((double)r->variance[i] * r->passes) / r->image[i];
        if (deviation > worst) worst = deviation;
    }
    return worst;
}

static void projected_sampling_has_zero_variance_on_an_unoccluded_lambert_floor(void) {
    const uint32_t width = 48, height = 36, passes = 8;
    RenderResult projected, solid_angle;
    CHECK(render_scene("floor", TECHNIQUE_PROJECTED, width, height, passes, &projected));
    CHECK(render_scene("floor", TECHNIQUE_SOLID_ANGLE, width, height, passes, &solid_angle));
    uint32_t lit_projected, lit_solid_angle;
    double projected_deviation = worst_relative_deviation(&projected, width * height, &lit_projected);
    double solid_angle_deviation =
        worst_relative_deviation(&solid_angle, width * height, &lit_solid_angle);
    printf("floor: worst relative deviation per pixel: projected %.3e, solid angle %.3e "
           "(%u lit pixel channels)\n",
           projected_deviation, solid_angle_deviation, lit_projected);
    CHECK(lit_projected > width * height * 3 / 2);
    CHECK(lit_projected == lit_solid_angle);
    /* f32 rounding of cos / pdf and of the frame: a few ulps */
    CHECK(projected_deviation < 1e-5);
    CHECK(solid_angle_deviation > 1e-2);
    /* and both estimate the same image */
    for (int c = 0; c < 3; ++c)
        CHECK(fabs(projected.mean[c] - solid_angle.mean[c]) <=
              5.0 * solid_angle.mean_stderr[c] + 1e-5 * projected.mean[c]);
    render_result_free(&projected);
    render_result_free(&solid_angle);
}

int main(void) {
    unbiased_techniques_agree_in_the_cornell_box();
    sphere_light_techniques_agree();
    medium_techniques_agree();
    sphere_union_agrees_and_beats_the_mixture();
    specular_occlusion_keeps_the_light_out_where_the_separable_form_leaks();
    projected_sampling_has_zero_variance_on_an_unoccluded_lambert_floor();
    return check_summary();
}
