/* sphera-trace: the command line of the example tracer. See bench/README.md. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common.h"
#include "indirect.h"
#include "tracer.h"

static void usage(FILE *out) {
    fprintf(out,
            "usage: sphera-trace [options]\n"
            "  --scene NAME            built-in scene (--list-scenes); default cornell\n"
            "                          (--scene indirect: VSGLs, its own options: --scene indirect --help)\n"
            "  --technique NAME        light sampling technique (--list-techniques); default projected\n"
            "  --width W --height H    image size; default 256 x 192\n"
            "  --spp N                 passes (a pass: one camera ray per pixel, K light samples\n"
            "                          per light); default 16\n"
            "  --time-ms T             instead: render passes until T ms have passed (at least 1)\n"
            "  --light-samples K       light samples per light per pixel per pass; default 1\n"
            "  --threads N             default: all cores\n"
            "  --seed S                default 1\n"
            "  --reference FILE.pfm    report RMSE and relative MSE against this image\n"
            "  --curve FILE.csv        with --reference: passes,time_ms,rmse,relmse after passes\n"
            "                          1, 2, 4, 8, ... and the last\n"
            "  --out-pfm FILE          the mean image (PFM)\n"
            "  --out-variance-pfm FILE per-pixel variance of the mean (PFM)\n"
            "  --out-png FILE          the mean image as 8-bit sRGB PNG, scaled by 2^exposure\n"
            "  --out-error-png FILE    with --reference: the error image (image - reference,\n"
            "                          mean of the channels, x 2^exposure x 4; red brighter, blue darker)\n"
            "  --exposure E            in stops; default 0\n"
            "  --obj FILE              add the triangles of a simple OBJ file (white Lambert)\n"
            "  --obj-scale S --obj-offset X,Y,Z   its placement; default 1 and 0,0,0\n"
            "  --quiet                 no progress line on stderr\n"
            "  --list-scenes | --list-techniques | --version | --help\n"
            "Prints one JSON line of measurements on stdout.\n");
}

typedef struct Curve {
    FILE *file;
} Curve;

static void write_checkpoint(void *context, uint32_t passes, double time_ms, double rmse,
                             double relmse) {
    Curve *curve = context;
    if (curve->file) fprintf(curve->file, "%u,%.6g,%.9g,%.9g\n", passes, time_ms, rmse, relmse);
}

static bool parse_uint(const char *text, uint32_t *out) {
    char *end;
    unsigned long v = strtoul(text, &end, 10);
    if (*text == '\0' || *end != '\0' || v > 100000000ul) return false;
    *out = (uint32_t)v;
    return true;
}

int main(int argc, char **argv) {
    const char *scene_name = "cornell", *technique_name = "projected";
    const char *reference_path = NULL, *curve_path = NULL, *pfm_path = NULL, *png_path = NULL;
    const char *error_png_path = NULL;
    const char *variance_path = NULL;
    RenderSettings settings = {0};
    settings.width = 256;
    settings.height = 192;
    settings.passes = 16;
    settings.light_samples = 1;
    settings.seed = 1;
    settings.progress = true;
    float exposure = 0.0f;
    const char *obj_path = NULL;
    float obj_scale = 1.0f;
    float3 obj_offset = f3(0, 0, 0);

    /* The one-bounce indirect scene has its own renderer and options (indirect.c). */
    for (int i = 1; i + 1 < argc; ++i)
        if (strcmp(argv[i], "--scene") == 0 && strcmp(argv[i + 1], "indirect") == 0)
            return indirect_main(argc, argv);

    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        bool ok = true, takes_value = true;
        if (strcmp(arg, "--list-scenes") == 0) {
            for (uint32_t s = 0; s < scene_count; ++s)
                printf("%s\t%s\n", scene_info[s].name, scene_info[s].description);
            return 0;
        } else if (strcmp(arg, "--list-techniques") == 0) {
            for (int t = 0; t < TECHNIQUE_COUNT; ++t)
                printf("%s\t%s\t%s\n", technique_info[t].name,
                       technique_info[t].biased ? "biased" : "unbiased",
                       technique_info[t].description);
            return 0;
        } else if (strcmp(arg, "--version") == 0) {
            printf("sphera-trace %s libsphera %s\n", TRACER_VERSION, sphera_version());
            return 0;
        } else if (strcmp(arg, "--help") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(arg, "--quiet") == 0) {
            settings.progress = false;
            takes_value = false;
        } else if (!value) {
            ok = false;
        } else if (strcmp(arg, "--scene") == 0) {
            scene_name = value;
        } else if (strcmp(arg, "--technique") == 0) {
            technique_name = value;
        } else if (strcmp(arg, "--width") == 0) {
            ok = parse_uint(value, &settings.width) && settings.width > 0;
        } else if (strcmp(arg, "--height") == 0) {
            ok = parse_uint(value, &settings.height) && settings.height > 0;
        } else if (strcmp(arg, "--spp") == 0) {
            ok = parse_uint(value, &settings.passes) && settings.passes > 0;
        } else if (strcmp(arg, "--time-ms") == 0) {
            /* At most a day: a larger budget (or inf) would never finish. */
            ok = parse_number(value, 1e-3, 86400e3, &settings.time_budget_ms);
        } else if (strcmp(arg, "--light-samples") == 0) {
            ok = parse_uint(value, &settings.light_samples) && settings.light_samples > 0;
        } else if (strcmp(arg, "--threads") == 0) {
            ok = parse_uint(value, &settings.threads);
        } else if (strcmp(arg, "--seed") == 0) {
            uint32_t seed;
            ok = parse_uint(value, &seed);
            settings.seed = seed;
        } else if (strcmp(arg, "--reference") == 0) {
            reference_path = value;
        } else if (strcmp(arg, "--curve") == 0) {
            curve_path = value;
        } else if (strcmp(arg, "--out-pfm") == 0) {
            pfm_path = value;
        } else if (strcmp(arg, "--out-variance-pfm") == 0) {
            variance_path = value;
        } else if (strcmp(arg, "--out-png") == 0) {
            png_path = value;
        } else if (strcmp(arg, "--out-error-png") == 0) {
            error_png_path = value;
        } else if (strcmp(arg, "--obj") == 0) {
            obj_path = value;
        } else if (strcmp(arg, "--obj-scale") == 0) {
            double scale = 1.0;
            ok = parse_number(value, 1e-20, 1e20, &scale) && scale > 0.0;
            obj_scale = (float)scale;
        } else if (strcmp(arg, "--obj-offset") == 0) {
            int consumed = 0;
            ok = sscanf(value, "%f,%f,%f%n", &obj_offset.x, &obj_offset.y, &obj_offset.z,
                        &consumed) == 3 &&
                 value[consumed] == '\0' && isfinite(obj_offset.x) && isfinite(obj_offset.y) &&
                 isfinite(obj_offset.z);
        } else if (strcmp(arg, "--exposure") == 0) {
            double stops = 0.0;
            ok = parse_number(value, -64.0, 64.0, &stops);
            exposure = (float)stops;
        } else {
            ok = false;
        }
        if (!ok) {
            fprintf(stderr, "sphera-trace: bad option or value: %s%s%s\n", arg, value ? " " : "",
                    value && takes_value ? value : "");
            usage(stderr);
            return 2;
        }
        if (takes_value) ++i;
    }

    if (curve_path && !reference_path) {
        fprintf(stderr, "sphera-trace: --curve needs --reference (its errors are against it)\n");
        return 2;
    }
    if (error_png_path && !reference_path) {
        fprintf(stderr, "sphera-trace: --out-error-png needs --reference\n");
        return 2;
    }
    int technique = technique_from_name(technique_name);
    if (technique < 0) {
        fprintf(stderr, "sphera-trace: unknown technique '%s' (see --list-techniques)\n",
                technique_name);
        return 2;
    }
    settings.technique = (Technique)technique;

    float *reference = NULL;
    if (reference_path) {
        uint32_t w, h;
        reference = read_pfm(reference_path, &w, &h);
        if (!reference || w != settings.width || h != settings.height) {
            fprintf(stderr, "sphera-trace: cannot use %s as a %u x %u reference\n",
                    reference_path, settings.width, settings.height);
            free(reference);
            return 1;
        }
        settings.reference = reference;
    }
    Curve curve = {NULL};
    if (curve_path) {
        curve.file = fopen(curve_path, "w");
        if (!curve.file) {
            fprintf(stderr, "sphera-trace: cannot write %s\n", curve_path);
            return 1;
        }
        fprintf(curve.file, "passes,time_ms,rmse,relmse\n");
        settings.on_checkpoint = write_checkpoint;
        settings.checkpoint_context = &curve;
    }

    Scene scene;
    if (!scene_create_with_obj(&scene, scene_name, (float)settings.width / (float)settings.height,
                               obj_path, obj_scale, obj_offset))
        return 1;
    RenderResult result;
    bool ok = render(&scene, &settings, &result);
    if (curve.file) fclose(curve.file);
    if (!ok) return 1;
    if (pfm_path && !write_pfm(pfm_path, result.image, settings.width, settings.height)) {
        fprintf(stderr, "sphera-trace: cannot write %s\n", pfm_path);
        ok = false;
    }
    if (variance_path &&
        !write_pfm(variance_path, result.variance, settings.width, settings.height)) {
        fprintf(stderr, "sphera-trace: cannot write %s\n", variance_path);
        ok = false;
    }
    if (png_path && !write_png(png_path, result.image, settings.width, settings.height, exposure)) {
        fprintf(stderr, "sphera-trace: cannot write %s\n", png_path);
        ok = false;
    }
    if (error_png_path && !write_error_png(error_png_path, result.image, reference, settings.width,
                                           settings.height, exposure)) {
        fprintf(stderr, "sphera-trace: cannot write %s\n", error_png_path);
        ok = false;
    }
    double samples = result.samples ? (double)result.samples : 1.0;
    printf("{\"scene\": \"%s\", \"technique\": \"%s\", \"biased\": %s, \"width\": %u, "
           "\"height\": %u, \"passes\": %u, \"light_samples\": %u, \"lights\": %u, "
           "\"time_ms\": %.6g, \"ms_per_frame\": %.6g, \"ns_per_sample\": %.6g, "
           "\"samples\": %llu, \"mean\": [%.9g, %.9g, %.9g], "
           "\"mean_stderr\": [%.9g, %.9g, %.9g], \"variance_of_mean\": %.9g",
           scene_name, technique_name, technique_info[technique].biased ? "true" : "false",
           settings.width, settings.height, result.passes, settings.light_samples,
           scene.light_count, result.time_ms, result.time_ms / result.passes,
           1e6 * result.time_ms / samples, (unsigned long long)result.samples, result.mean[0],
           result.mean[1], result.mean[2], result.mean_stderr[0], result.mean_stderr[1],
           result.mean_stderr[2], result.variance_of_mean);
    if (reference) {
        /* null where the reference holds NaN or ∞ pixels: JSON has no NaN. */
        printf(", \"rmse\": ");
        print_json_number(stdout, result.rmse);
        printf(", \"relmse\": ");
        print_json_number(stdout, result.relmse);
    }
    printf("}\n");
    render_result_free(&result);
    scene_destroy(&scene);
    free(reference);
    return ok ? 0 : 1;
}
