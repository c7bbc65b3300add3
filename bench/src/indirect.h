/*
 * One-bounce indirect illumination from a spot light (the `indirect` scene): virtual
 * spherical Gaussian lights (Tokuyoshi 2016) against a path-traced reference.
 *
 * VSGL frame: (1) an RSM-like `rsm_size²` grid of rays from the spot, traced with
 * Embree, each hit a VPL (`sphera_vsgl_texel_from_vpl`), misses black texels; (2) the
 * mip pyramid of sums (`sphera_vsgl_fis_select`'s layout); (3) N clusters by FIS
 * (`sphera_vsgl_fis_select`, Hammersley points) or by one k-means pass (Section 5:
 * centres drawn in proportion to importance, every texel to its nearest centre in the
 * metric |Δx|²/h_image² + |Δy|²/h_world², no iteration; as tools/src/measurements/vsgl_kmeans.rs);
 * (4) at every camera hit, per VSGL, the incoming-radiance SG (Eq. 6-7), constant-
 * cosine diffuse and ASG specular shading (`sphera_sg_*`), times the visibility of the
 * VSGL's mean (one shadow ray). Biased by design (lobe fits, visibility of the mean).
 *
 * Reference: camera hit -> one BRDF sample (GGX VNDF / cosine mixture) -> hit -> the
 * spot's direct light there with a shadow ray. Both images hold indirect light only.
 */
#ifndef SPHERA_TRACER_INDIRECT_H
#define SPHERA_TRACER_INDIRECT_H

#include "tracer.h"

/* A spot light: radiant intensity `intensity · smoothstep(cos_outer, cos_inner, cos θ)`
 * around the unit `direction` (W/sr per RGB channel). */
typedef struct SpotLight {
    float3 position, direction;
    float cos_inner, cos_outer;
    float3 intensity;
} SpotLight;

/* The spot of the `indirect` scene. */
SpotLight indirect_scene_spot(void);

/* Its intensity toward the unit direction `dir` (from the light). */
float3 spot_intensity(const SpotLight *spot, float3 dir);

typedef enum Clustering {
    CLUSTERING_FIS,
    CLUSTERING_KMEANS,
    CLUSTERING_VPLS /* diagnosis: no clusters, every VPL shaded exactly (N ignored) */
} Clustering;

/* Diagnosis switches (`--variant a,b,...`), each removing one approximation or adding
 * one, to decompose the VSGLs' loss of energy (README, issue 20): */
enum {
    VARIANT_UNSHADOWED = 1u << 0,  /* no shadow rays (V = 1), VPLs and VSGLs */
    VARIANT_SG_EMISSION = 1u << 1, /* vpl: each VPL emits by its SG lobes (Eq. 1, 2) */
    VARIANT_VSGL_PER_VPL = 1u << 2, /* vpl: each VPL a VSGL of its own, SG shading */
    VARIANT_POINT = 1u << 3,       /* fis/kmeans: variance 0 (a point at the mean) */
    VARIANT_CLUSTER_VISIBILITY = 1u << 4, /* fis/kmeans: V = the visible share of the
                                             cluster's VPLs (per pixel, exact) */
    VARIANT_RECEIVER_QUADRATURE = 1u << 5, /* the receiver's ∫ L_in f cos dω by 64
                                              stratified vMF samples of L_in, exact BRDF,
                                              instead of the closed forms of Sec. 4.2 */
    VARIANT_EXACT_LOBES = 1u << 6 /* k-means: each cluster a point light at its mean
                                     emitting the sum of its VPLs' SG lobes (Eq. 1, 2)
                                     instead of one Toksvig lobe per component, exact
                                     receiver BRDF, unshadowed */
};

typedef struct IndirectSettings {
    uint32_t width, height;
    uint32_t rsm_size;      /* a power of two */
    uint32_t cluster_count; /* N */
    Clustering clustering;
    uint32_t frames;        /* frames rendered (each with fresh random numbers) */
    uint32_t threads;       /* 0: all cores */
    uint64_t seed;
    float kernel_scale;     /* FIS's K (1) */
    uint32_t iterations;    /* FIS's bisection steps (8) */
    float world_extent;     /* k-means: h_world = world_extent / sqrt(N) */
    uint32_t variant;       /* VARIANT_* bits (0: the method as specified) */
} IndirectSettings;

typedef struct IndirectResult {
    float *image;              /* the last frame, width * height * 3 (malloc'ed) */
    uint32_t frames;
    double ms_per_frame;       /* RSM + pyramid + clustering + shading, mean over frames */
    double ms_rsm, ms_clustering, ms_shading; /* its parts (clustering: pyramid included) */
    double rsm_luminance;      /* Σ lum(Φ ∘ (R_d + R_s)) over the VPLs (the top texel) */
    double cluster_luminance;  /* the same summed over the N VSGLs (last frame) */
    double rsm_flux[3];        /* Σ Φ over the VPLs: the spot's flux onto the scene */
    uint32_t vpl_count;        /* texels with a VPL of positive weight */
    uint32_t empty_clusters;   /* VSGLs without power (last frame) */
    double mean[3];            /* image mean (last frame) */
    /* Against the reference, when one is given: mean over frames of the RMSE and the
     * relative MSE, and the ratio of the image means (bias). */
    double rmse, relmse, mean_ratio;
} IndirectResult;

/* Renders `settings->frames` VSGL frames of `scene` lit by `spot`. */
bool indirect_render_vsgl(const Scene *scene, const SpotLight *spot,
                          const IndirectSettings *settings, const float *reference,
                          IndirectResult *result);

/* The path-traced reference: `spp` one-bounce paths per pixel (mean image, malloc'ed
 * into *image); *ms the time taken. */
bool indirect_render_reference(const Scene *scene, const SpotLight *spot, uint32_t width,
                               uint32_t height, uint32_t spp, uint32_t threads, uint64_t seed,
                               float **image, double *ms);

/* The `--scene indirect` command line (called by main.c). */
int indirect_main(int argc, char **argv);

#endif
