/*
 * The sphera example tracer: direct illumination from polygonal area lights, with
 * shadow rays through Intel Embree 3 and the light sampled by one of the techniques
 * that libsphera exports. The program (main.c) and the end-to-end test
 * (bench/tests/test_tracer_end_to_end.c) both drive it through this interface.
 *
 * What is rendered: camera rays through pixel centres (one per pixel, traced once and
 * cached, so the image has no antialiasing noise), emission of the lights they hit,
 * and at every other hit the reflected radiance of each light, estimated with `light
 * samples` samples per light per pass from the chosen technique. All noise in an image
 * therefore comes from light sampling, which is what the report compares.
 */
#ifndef SPHERA_TRACER_H
#define SPHERA_TRACER_H

#include <stdbool.h>
#include <stdint.h>

#include <embree3/rtcore.h>

#include "sphera.h"
#include "vec3.h"

#define TRACER_VERSION "0.1.0"
#define TRACER_MAX_LIGHTS 16

/* ---- techniques ------------------------------------------------------------------ */

typedef enum Technique {
    TECHNIQUE_TURK,                /* Turk's uniform area sampling (pdf -> solid angle) */
    TECHNIQUE_ARVO,                /* Arvo 1995 solid angle sampling */
    TECHNIQUE_SOLID_ANGLE,         /* Peters 2021 solid angle sampling of triangle fans */
    TECHNIQUE_CLIPPED_SOLID_ANGLE, /* the same after clipping to the horizon */
    TECHNIQUE_HART_BILINEAR,       /* Hart et al. 2020 bilinear cosine warp */
    TECHNIQUE_HART_BIQUADRATIC,    /* Hart et al. 2020 biquadratic cosine warp */
    TECHNIQUE_ARVO_PROJECTED,      /* Arvo 2001-style projected solid angle sampling */
    TECHNIQUE_PROJECTED,           /* Peters 2021 projected solid angle sampling */
    TECHNIQUE_PROJECTED_FAST,      /* its biased fast variant */
    /* Two samples per light sample, one from each technique, combined by MIS: */
    TECHNIQUE_BRDF_BALANCE,        /* BRDF (VNDF / cosine) + projected, balance heuristic */
    TECHNIQUE_BRDF_POWER,          /* BRDF + projected, power heuristic */
    TECHNIQUE_LTC_WEIGHTED,        /* LTC + projected, weighted balance heuristic */
    TECHNIQUE_LTC_CLAMPED,         /* LTC + projected, clamped optimal MIS, v = 1/2 */
    TECHNIQUE_LTC_OPTIMAL,         /* LTC + projected, optimal MIS, v = 1/2 */
    /* Sphere lights (polygon lights are then sampled by projected solid angle sampling): */
    TECHNIQUE_SPHERE_CAP,          /* uniform in the sphere's cap of directions */
    TECHNIQUE_SPHERE_CAP_BRDF,     /* one cap and one BRDF sample, balance heuristic */
    TECHNIQUE_SPHERE_SPTD,         /* GGX layer: one SPTD light and one VNDF sample, balance */
    TECHNIQUE_SPHERE_PROJECTED,    /* Lambert layer: cosine-weighted in the cap; GGX as sptd */
    TECHNIQUE_SPHERE_REALTIME,     /* biased: Eq. 19 SPTD shading x one-ray visibility */
    TECHNIQUE_SPHERE_OCCLUSION,    /* biased: Eq. 23 SPTD shading in a traced bent cone */
    TECHNIQUE_SPHERE_OCCLUSION_SEPARABLE, /* biased: its separable baseline, Eq. 21-22 */
    /* In-scattering in a medium (sphere lights; elsewhere as sphere_cap_brdf): */
    TECHNIQUE_MEDIUM_PIVOT,        /* the pivot phase function sampled in the light's cap */
    TECHNIQUE_MEDIUM_HG_CAP,       /* one HG and one uniform cap sample, balance heuristic */
    /* Two sphere lights of equal radiance (consecutive in the scene) as one light; other
     * sphere lights as sphere_cap: */
    TECHNIQUE_SPHERE_UNION,        /* uniform in the union of the two caps (SpheraCapUnion) */
    TECHNIQUE_SPHERE_MIXTURE,      /* one light with probability 1/2, uniform in its cap;
                                      pdf the mixture (baseline of sphere_union) */
    TECHNIQUE_REFERENCE,           /* solid angle + projected, multi-sample MIS */
    TECHNIQUE_COUNT
} Technique;

typedef struct TechniqueInfo {
    const char *name;
    bool biased;
    const char *description;
} TechniqueInfo;

extern const TechniqueInfo technique_info[TECHNIQUE_COUNT];

/* The technique called `name`, or -1. */
int technique_from_name(const char *name);

/* ---- scenes ---------------------------------------------------------------------- */

/* A surface's BRDF: Lambert with albedo `diffuse`, plus (when `roughness > 0`) a GGX
 * microfacet layer with alpha = roughness^2, Schlick's Fresnel from `specular` (F0) and
 * the height-correlated Smith masking-shadowing term. */
typedef struct Material {
    float3 diffuse;
    float3 specular;
    float roughness;
    SpheraGgxBrdf ggx; /* prepared from roughness and specular */
} Material;

/* A one-sided convex polygonal light: it emits `radiance` from the side its `normal`
 * points to (the vertices wind counter-clockwise seen from that side). */
typedef struct Light {
    float3 vertices[SPHERA_MAX_POLYGON_VERTICES];
    uint32_t count;
    float3 normal;
    float3 radiance;
    /* radius > 0: a sphere light of this radius around `center`, emitting from its
     * whole surface (vertices, count and normal unused). */
    float radius;
    float3 center;
} Light;

/* A box of homogeneous, grey, single-scattering medium (no geometry: camera rays and
 * shadow rays pass through it and are attenuated by exp(-sigma_t * length)). Light
 * scattered once towards the camera from sphere lights is added; light scattered onto
 * surfaces is not (single scattering along camera rays only). Phase function:
 * Henyey-Greenstein with mean cosine `g`. */
typedef struct Medium {
    bool present;
    float3 lo, hi; /* the box's corners */
    float sigma_s, sigma_t;
    float g;
} Medium;

typedef struct Camera {
    float3 position, forward, right, up; /* right and up are scaled to the image plane */
} Camera;

typedef struct Scene {
    const char *name;
    RTCDevice device;
    RTCScene rtc;
    /* Per triangle of the one Embree mesh: its material, its light (or -1) and its
     * unit geometric normal. */
    uint32_t triangle_count;
    uint32_t *triangle_material;
    int32_t *triangle_light;
    float3 *triangle_normal;
    Material *materials;
    uint32_t material_count;
    Light lights[TRACER_MAX_LIGHTS];
    uint32_t light_count;
    Camera camera;
    float ray_epsilon; /* offset of shadow ray origins, in scene units */
    Medium medium;
} Scene;

typedef struct SceneInfo {
    const char *name;
    const char *description;
} SceneInfo;

extern const SceneInfo scene_info[];
extern const uint32_t scene_count;

/* Builds the built-in scene `name` for an image of the given aspect ratio (width /
 * height). Returns false (with a message on stderr) when the name is unknown or Embree
 * fails. */
bool scene_create(Scene *scene, const char *name, float aspect);
/* The same, with the triangles of a simple OBJ file added (see --obj). */
bool scene_create_with_obj(Scene *scene, const char *name, float aspect, const char *obj_path,
                           float obj_scale, float3 obj_offset);
void scene_destroy(Scene *scene);

/* ---- rendering ------------------------------------------------------------------- */

typedef struct RenderSettings {
    uint32_t width, height;
    Technique technique;
    uint32_t light_samples; /* samples per light per pixel per pass */
    uint32_t passes;        /* passes to render; with time_budget_ms > 0, the most */
    double time_budget_ms;  /* > 0: render passes until this much time has passed */
    uint32_t threads;       /* 0: all cores */
    uint64_t seed;
    bool progress;          /* progress line on stderr */
    /* Optional reference image (width * height * 3 floats, rows top to bottom) and a
     * callback after passes 1, 2, 4, 8, ... and the last, for error-versus-time curves. */
    const float *reference;
    void (*on_checkpoint)(void *context, uint32_t passes, double time_ms, double rmse,
                          double relmse);
    void *checkpoint_context;
} RenderSettings;

typedef struct RenderResult {
    uint32_t passes;
    double time_ms;       /* sampling passes only (camera rays are traced once, before) */
    uint64_t samples;     /* light samples drawn (each with its shadow ray, if needed) */
    float *image;         /* mean, width * height * 3, rows top to bottom (malloc'ed) */
    float *variance;      /* per-pixel variance of the mean (0 when passes < 2) */
    double mean[3];       /* image mean */
    double mean_stderr[3];/* standard error of the image mean */
    double variance_of_mean; /* average over pixels and channels of `variance` */
    double rmse, relmse;  /* against the reference, when one was given */
} RenderResult;

/* Renders `scene`; returns false (message on stderr) if memory or threads fail. */
bool render(const Scene *scene, const RenderSettings *settings, RenderResult *result);
void render_result_free(RenderResult *result);

/* RMSE and relative MSE (mean of (x - r)^2 / (r^2 + 0.01)) over pixels and channels. */
void image_error(const float *image, const float *reference, uint32_t width,
                 uint32_t height, double *rmse, double *relmse);

/* ---- images ---------------------------------------------------------------------- */

/* PFM (colour, little-endian); `image` rows top to bottom. */
bool write_pfm(const char *path, const float *image, uint32_t width, uint32_t height);
/* Reads a colour PFM; returns a malloc'ed image, rows top to bottom, or NULL. */
float *read_pfm(const char *path, uint32_t *width, uint32_t *height);
/* 8-bit sRGB PNG of image * 2^exposure. */
bool write_png(const char *path, const float *image, uint32_t width, uint32_t height,
               float exposure);
/* 8-bit PNG of the error against `reference`, per pixel the mean over the channels of
 * (image - reference) * 2^exposure * ERROR_IMAGE_GAIN: red where the image is brighter,
 * blue where darker, black where they agree. */
#define ERROR_IMAGE_GAIN 4.0f
bool write_error_png(const char *path, const float *image, const float *reference,
                     uint32_t width, uint32_t height, float exposure);

#endif
