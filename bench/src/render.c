/* Rendering: camera rays once into a G-buffer, then passes of light sampling with
 * shadow rays, in parallel over tiles with pthreads. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "common.h"
#include "techniques.h"
#include "tracer.h"

#define TILE 16

/* What a camera ray found, computed once per pixel. */
typedef struct Hit {
    float3 position;     /* on the surface */
    float3 origin;       /* shadow ray origin: the position pushed off the surface */
    SpheraFrame frame;   /* z = geometric normal, turned towards the camera */
    float3 wo;           /* direction to the camera, local frame */
    float3 emission;     /* radiance emitted towards the camera (lights only) */
    uint32_t material;
    bool reflects;       /* false: nothing or a light was hit */
    /* The camera ray's part inside the scene's medium (if `in_medium`): from
     * camera + t0 dir to camera + t1 dir; `transmittance` (1 without a medium) scales
     * what lies behind it (emission and reflection). */
    bool in_medium;
    float3 camera_dir; /* world, unit */
    float t0, t1, transmittance;
} Hit;

/* ---- random numbers ---------------------------------------------------------------- */

typedef struct Rng {
    uint64_t state;
} Rng;

/* A float in [0, 1): the top 24 bits of a 64-bit draw times 2^-24, exact in f32. */
static float rng_float(Rng *rng) {
    return (float)(splitmix64(&rng->state) >> 40) * 0x1p-24f;
}

/* ---- BRDF ------------------------------------------------------------------------- */

/* The GGX layer's f(wo, wi) (local frame), evaluated by libsphera (isotropic GGX,
 * height-correlated Smith masking-shadowing, Schlick's Fresnel); 0 for Lambert-only
 * materials. */
static float3 brdf_specular(const Material *m, float3 wo, float3 wi) {
    if (!(m->roughness > 0.0f)) return f3(0, 0, 0);
    SpheraVec3 o = {wo.x, wo.y, wo.z}, i = {wi.x, wi.y, wi.z};
    SpheraVec3 f = sphera_ggx_brdf_eval(&m->ggx, o, i);
    return f3(f.x, f.y, f.z);
}

/* The Lambert part, albedo / pi. */
static float3 brdf_diffuse(const Material *m) { return f3_scale(m->diffuse, 1.0f / PI_F); }

/* ---- BRDF sampling ---------------------------------------------------------------- */

/* Sampling of a material's whole BRDF: the GGX lobe by its visible normals (libsphera)
 * with probability `specular_probability`, else the Lambert lobe cosine-weighted; the pdf
 * is the mixture's. The probability is the lobes' share of the directional albedo
 * (GGX's from the fitted LTC table), by luminance. */
typedef struct BrdfSampler {
    const Material *material;
    SpheraVec3 wo;
    float specular_probability;
} BrdfSampler;

static float luminance(float3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

static void brdf_sampler_init(BrdfSampler *b, const Material *m, float3 wo) {
    b->material = m;
    b->wo.x = wo.x;
    b->wo.y = wo.y;
    b->wo.z = wo.z;
    b->specular_probability = 0.0f;
    SpheraLtc ltc;
    if (m->roughness > 0.0f && sphera_ltc_prepare(&ltc, b->wo, m->roughness)) {
        SpheraVec3 f0 = {m->specular.x, m->specular.y, m->specular.z};
        SpheraVec3 a = sphera_ltc_specular_albedo(&ltc, f0);
        float specular = luminance(f3(a.x, a.y, a.z)), diffuse = luminance(m->diffuse);
        if (specular + diffuse > 0.0f) b->specular_probability = specular / (specular + diffuse);
    }
}

static float brdf_sampler_pdf(const BrdfSampler *b, SpheraVec3 wi) {
    float q = b->specular_probability;
    float p = (1.0f - q) * sphera_lambert_pdf(wi);
    if (q > 0.0f) p += q * sphera_ggx_brdf_pdf(&b->material->ggx, b->wo, wi);
    return p;
}

static SpheraSample brdf_sampler_sample(const BrdfSampler *b, float u0, float u1) {
    float q = b->specular_probability;
    SpheraSample s;
    if (u0 < q)
        s = sphera_ggx_brdf_sample(&b->material->ggx, b->wo, u0 / q, u1);
    else
        s = sphera_lambert_sample((u0 - q) / (1.0f - q), u1);
    if (s.pdf > 0.0f) s.pdf = brdf_sampler_pdf(b, s.dir);
    return s;
}

/* f (no cosine) of the whole material. */
static float3 brdf_sampler_eval(const BrdfSampler *b, SpheraVec3 wi) {
    if (!(wi.z > 0.0f)) return f3(0, 0, 0);
    float3 wo = f3(b->wo.x, b->wo.y, b->wo.z);
    return f3_add(brdf_diffuse(b->material), brdf_specular(b->material, wo, f3(wi.x, wi.y, wi.z)));
}

/* ---- light sampling ----------------------------------------------------------------- */

/* The part [t0, t1] of the ray origin + t dir, t in [0, tmax], inside the medium's box
 * (slab method); false when the ray misses it or there is no medium. */
static bool medium_segment(const Medium *m, float3 origin, float3 dir, float tmax, float *t0,
                           float *t1) {
    if (!m->present) return false;
    float lo = 0.0f, hi = tmax;
    const float o[3] = {origin.x, origin.y, origin.z}, d[3] = {dir.x, dir.y, dir.z};
    const float a[3] = {m->lo.x, m->lo.y, m->lo.z}, b[3] = {m->hi.x, m->hi.y, m->hi.z};
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0.0f) {
            if (o[i] < a[i] || o[i] > b[i]) return false;
            continue;
        }
        float ta = (a[i] - o[i]) / d[i], tb = (b[i] - o[i]) / d[i];
        if (ta > tb) {
            float t = ta;
            ta = tb;
            tb = t;
        }
        if (ta > lo) lo = ta;
        if (tb < hi) hi = tb;
    }
    if (!(lo < hi)) return false;
    *t0 = lo;
    *t1 = hi;
    return true;
}

/* exp(-sigma_t * length inside the medium) along origin + t dir, t in [0, tmax]. */
static float medium_transmittance(const Scene *scene, float3 origin, float3 dir, float tmax) {
    float t0, t1;
    if (!medium_segment(&scene->medium, origin, dir, tmax, &t0, &t1)) return 1.0f;
    return expf(-scene->medium.sigma_t * (t1 - t0));
}

/* The fraction of light that reaches `origin` from `light` along the world direction
 * `dir`: 0 when something blocks the way, else the medium's transmittance (1 without
 * a medium). The ray ends just before the light's plane or sphere, so that the light's
 * own triangles do not count. */
static float transmitted(const Scene *scene, struct RTCIntersectContext *context, float3 origin,
                         const Light *light, float3 dir) {
    float t;
    if (light->radius > 0.0f) {
        /* The nearer intersection with the sphere: t = -b - sqrt(b^2 - c), written as
         * c / (-b + sqrt(b^2 - c)) where -b > 0, which keeps precision for small
         * spheres far away. */
        float3 oc = f3_sub(origin, light->center);
        float b = f3_dot(oc, dir), c = f3_dot(oc, oc) - light->radius * light->radius;
        float discriminant = b * b - c;
        if (!(discriminant >= 0.0f) || !(b < 0.0f)) return 0.0f; /* misses or behind */
        t = c / (-b + sqrtf(discriminant));
    } else {
        float along = f3_dot(light->normal, dir);
        t = f3_dot(light->normal, f3_sub(light->vertices[0], origin)) / along;
    }
    if (!(t > 0.0f) || !(t < INFINITY)) return 0.0f; /* parallel or behind: no hit */
    float tfar = t * (1.0f - 1e-5f) - scene->ray_epsilon;
    if (tfar <= 0.0f) return medium_transmittance(scene, origin, dir, t);
    struct RTCRay ray = make_ray(origin, dir, tfar);
    rtcOccluded1(scene->rtc, context, &ray);
    if (!(ray.tfar >= 0.0f)) return 0.0f; /* Embree sets tfar to -inf on a hit */
    return medium_transmittance(scene, origin, dir, t);
}

/* transmitted() from a surface hit (its shadow ray origin). */
static float unoccluded(const Scene *scene, struct RTCIntersectContext *context, const Hit *hit,
                        const Light *light, float3 dir) {
    return transmitted(scene, context, hit->origin, light, dir);
}

/* L * cos * visibility for the local direction `wi` towards `light` (0 below the
 * horizon or when occluded); the caller multiplies by the BRDF. */
static float3 light_cosine(const Scene *scene, struct RTCIntersectContext *context,
                           const Hit *hit, const Light *light, SpheraVec3 wi) {
    if (!(wi.z > 0.0f)) return f3(0, 0, 0);
    float3 dir = frame_to_world(&hit->frame, wi);
    float visible = unoccluded(scene, context, hit, light, dir);
    if (!(visible > 0.0f)) return f3(0, 0, 0);
    return f3_scale(light->radiance, wi.z * visible);
}

static float3 to_float3(SpheraVec3 v) { return f3(v.x, v.y, v.z); }

static bool is_zero(float3 v) { return v.x == 0.0f && v.y == 0.0f && v.z == 0.0f; }

static SpheraVec3 to_sphera(float3 v) {
    SpheraVec3 r = {v.x, v.y, v.z};
    return r;
}

/* One light sample of a pair technique: one sample of each of its two techniques,
 * weighted by MIS, times the light's radiance and visibility. */
static float3 pair_estimate(const Scene *scene, struct RTCIntersectContext *context,
                            const Hit *hit, const Light *light, Technique technique,
                            const PreparedLight *prepared, const BrdfSampler *brdf, float u0,
                            float u1, float v0, float v1) {
    float3 sum = f3(0, 0, 0);
    if (technique == TECHNIQUE_BRDF_BALANCE || technique == TECHNIQUE_BRDF_POWER) {
        bool power = technique == TECHNIQUE_BRDF_POWER;
        const SpheraProjectedPolygon *polygon = &prepared->u.projected;
        /* light sampling */
        SpheraSample a = sphera_projected_polygon_sample(polygon, u0, u1);
        if (a.pdf > 0.0f) {
            float other = brdf_sampler_pdf(brdf, a.dir);
            float w = power ? sphera_mis_power(a.pdf, other) : sphera_mis_balance(a.pdf, other);
            float3 f = brdf_sampler_eval(brdf, a.dir);
            if (w > 0.0f && !is_zero(f)) {
                float3 radiance = light_cosine(scene, context, hit, light, a.dir);
                sum = f3_add(sum, f3_scale(f3_mul(radiance, f), w / a.pdf));
            }
        }
        /* BRDF sampling: counts where the direction passes through the light */
        SpheraSample b = brdf_sampler_sample(brdf, v0, v1);
        float light_pdf = b.pdf > 0.0f ? sphera_projected_polygon_pdf(polygon, b.dir) : 0.0f;
        if (light_pdf > 0.0f) {
            float w = power ? sphera_mis_power(b.pdf, light_pdf) : sphera_mis_balance(b.pdf, light_pdf);
            float3 f = brdf_sampler_eval(brdf, b.dir);
            if (w > 0.0f && !is_zero(f)) {
                float3 radiance = light_cosine(scene, context, hit, light, b.dir);
                sum = f3_add(sum, f3_scale(f3_mul(radiance, f), w / b.pdf));
            }
        }
        return sum;
    }
    /* LTC + projected through sphera_polygon_light_sample: L (V visible + unoccluded). */
    for (uint32_t t = 0; t < 2; ++t) {
        SpheraLightSample s = sphera_polygon_light_sample(&prepared->u.polygon_light, t,
                                                          t ? v0 : u0, t ? v1 : u1);
        if (!(s.pdf > 0.0f)) continue;
        float3 visible = to_float3(s.visible), offset = to_float3(s.unoccluded);
        sum = f3_add(sum, f3_mul(light->radiance, offset));
        if (!is_zero(visible) && s.dir.z > 0.0f) {
            /* light_cosine gives L cos V; the sample's factor already holds the cosine */
            float3 radiance = light_cosine(scene, context, hit, light, s.dir);
            sum = f3_add(sum, f3_scale(f3_mul(radiance, visible), 1.0f / s.dir.z));
        }
    }
    return sum;
}

/* Which part of the BRDF an estimate integrates: f = f_diffuse + f_specular. */
typedef enum BrdfPart { BRDF_WHOLE, BRDF_DIFFUSE, BRDF_SPECULAR } BrdfPart;

static float3 brdf_part(const Material *m, float3 wo, SpheraVec3 wi, BrdfPart part) {
    if (!(wi.z > 0.0f)) return f3(0, 0, 0);
    float3 f = f3(0, 0, 0);
    if (part != BRDF_SPECULAR) f = brdf_diffuse(m);
    if (part != BRDF_DIFFUSE) f = f3_add(f, brdf_specular(m, wo, to_float3(wi)));
    return f;
}

/* One term of a two-sample balance-heuristic estimate: the sample `s` (pdf > 0, above
 * the horizon, checked by the caller) weighted against the other technique's pdf at
 * its direction, times `part` of the BRDF and the light's cosine-weighted radiance. */
static float3 balance_term(const Scene *scene, struct RTCIntersectContext *context,
                           const Hit *hit, const Light *light, SpheraSample s, float other_pdf,
                           BrdfPart part) {
    float w = sphera_mis_balance(s.pdf, other_pdf);
    float3 f = brdf_part(&scene->materials[hit->material], hit->wo, s.dir, part);
    if (!(w > 0.0f) || is_zero(f)) return f3(0, 0, 0);
    float3 radiance = light_cosine(scene, context, hit, light, s.dir);
    return f3_scale(f3_mul(radiance, f), w / s.pdf);
}

/* One light sample of sphere_cap_brdf for `part` of the BRDF: one uniform cap sample
 * and one sample of the material's BRDF sampler, balance heuristic. */
static float3 sphere_cap_brdf_estimate(const Scene *scene, struct RTCIntersectContext *context,
                                       const Hit *hit, const Light *light, SpheraCap cap,
                                       const BrdfSampler *brdf, BrdfPart part, Rng *rng) {
    float3 sum = f3(0, 0, 0);
    float u0 = rng_float(rng), u1 = rng_float(rng);
    SpheraSample a = sphera_cap_sample_uniform(cap, u0, u1);
    if (a.pdf > 0.0f && a.dir.z > 0.0f)
        sum = balance_term(scene, context, hit, light, a, brdf_sampler_pdf(brdf, a.dir), part);
    SpheraSample b = brdf_sampler_sample(brdf, rng_float(rng), rng_float(rng));
    float cap_pdf = b.pdf > 0.0f ? sphera_cap_pdf(cap, b.dir) : 0.0f;
    if (cap_pdf > 0.0f && b.dir.z > 0.0f)
        sum = f3_add(sum, balance_term(scene, context, hit, light, b, cap_pdf, part));
    return sum;
}

/* One light sample of sphere_sptd for the GGX layer alone: one sample of the joint
 * SPTD light sampler (the fitted SPTD restricted to the cap, Dupuy et al. 2017,
 * Section 6.1, or its own uniform-cap fallback) and one GGX visible-normal sample,
 * balance heuristic. The SPTD has support in the whole cap, so the weights sum to 1
 * wherever f_specular cos > 0 inside the cap. */
static float3 sphere_sptd_specular_estimate(const Scene *scene, struct RTCIntersectContext *context,
                                            const Hit *hit, const Light *light,
                                            const SpheraSphereLightSampler *sampler, Rng *rng) {
    const Material *m = &scene->materials[hit->material];
    const SpheraVec3 wo = to_sphera(hit->wo);
    float3 sum = f3(0, 0, 0);
    float u0 = rng_float(rng), u1 = rng_float(rng);
    SpheraSample a = sphera_sphere_light_sampler_sample(sampler, u0, u1);
    if (a.pdf > 0.0f && a.dir.z > 0.0f)
        sum = balance_term(scene, context, hit, light, a, sphera_ggx_brdf_pdf(&m->ggx, wo, a.dir),
                           BRDF_SPECULAR);
    float v0 = rng_float(rng), v1 = rng_float(rng);
    SpheraSample b = sphera_ggx_brdf_sample(&m->ggx, wo, v0, v1);
    float light_pdf = b.pdf > 0.0f ? sphera_sphere_light_sampler_pdf(sampler, b.dir) : 0.0f;
    if (light_pdf > 0.0f && b.dir.z > 0.0f)
        sum = f3_add(sum, balance_term(scene, context, hit, light, b, light_pdf, BRDF_SPECULAR));
    return sum;
}

/* One light sample of sphere_projected: the Lambert layer by one sample of the clamped
 * cosine inside the cap (the SPTD whose pivot is the origin, where the pivot
 * transformation is the antipodal map, so its base axis is -z), whose density cos θ /
 * ∫_C max(0, cos) covers every direction where f_diffuse cos > 0 in the cap: zero variance
 * for an unoccluded Lambertian receiver, also for a light across the horizon (the clipped
 * sampler of issue 20, 2); the GGX layer as sphere_sptd (where the SPTD sampler cannot
 * be prepared, one cap and one BRDF sample on it, balance heuristic). */
static float3 sphere_projected_estimate(const Scene *scene, struct RTCIntersectContext *context,
                                        const Hit *hit, const Light *light, SpheraCap cap,
                                        const SpheraSptdInCap *cosine,
                                        const SpheraSphereLightSampler *sampler,
                                        const BrdfSampler *brdf, Rng *rng, uint64_t *samples) {
    const Material *m = &scene->materials[hit->material];
    float3 sum = f3(0, 0, 0);
    float u0 = rng_float(rng), u1 = rng_float(rng);
    *samples += 3;
    if (cosine) {
        SpheraSample a = sphera_sptd_in_cap_sample(cosine, u0, u1);
        if (a.pdf > 0.0f && a.dir.z > 0.0f) {
            float3 f = brdf_part(m, hit->wo, a.dir, BRDF_DIFFUSE);
            float3 radiance = light_cosine(scene, context, hit, light, a.dir);
            sum = f3_scale(f3_mul(radiance, f), 1.0f / a.pdf);
        }
    }
    if (sampler)
        return f3_add(sum, sphere_sptd_specular_estimate(scene, context, hit, light, sampler, rng));
    return f3_add(sum, sphere_cap_brdf_estimate(scene, context, hit, light, cap, brdf,
                                                BRDF_SPECULAR, rng));
}

/* Draws at most this many uniform cap directions for sphere_realtime's visibility ray
 * before giving up (the cap is then almost all below the horizon). */
#define REALTIME_VISIBILITY_TRIES 8

/* One light sample of sphere_realtime (BIASED): the Lambert layer as in sphere_cap
 * (one uniform cap sample, unbiased), plus the GGX layer as
 *   L * S(C) * V,
 * where S(C) = sphera_sphere_light_shading_eval, the fitted SPTD's integral over the cap
 * clipped to the horizon (Dupuy et al. 2017, Eq. 19; includes cos and Fresnel), and V
 * is the visibility of one direction uniform in the cap above the horizon: the cap
 * sample when it lies above the horizon (its shadow ray is shared), else the first of
 * further uniform cap samples that does (rejection). V is an unbiased estimate of the
 * visible fraction of C ∩ H, so the GGX layer is exact up to the SPTD fit where the
 * light is wholly visible or wholly hidden; in penumbrae the product of the fraction
 * and S(C) is a further bias. */
static float3 sphere_realtime_estimate(const Scene *scene, struct RTCIntersectContext *context,
                                       const Hit *hit, const Light *light, SpheraCap cap,
                                       const SpheraSphereLightShading *shading, Rng *rng,
                                       uint64_t *samples) {
    const Material *m = &scene->materials[hit->material];
    float3 sum = f3(0, 0, 0);
    float u0 = rng_float(rng), u1 = rng_float(rng);
    SpheraSample a = sphera_cap_sample_uniform(cap, u0, u1);
    *samples += 1;
    bool drawn = false;
    float visible = 0.0f;
    if (a.pdf > 0.0f && a.dir.z > 0.0f) {
        drawn = true;
        visible = unoccluded(scene, context, hit, light, frame_to_world(&hit->frame, a.dir));
        sum = f3_scale(f3_mul(light->radiance, brdf_diffuse(m)), visible * a.dir.z / a.pdf);
    }
    if (!shading) return sum;
    for (uint32_t t = 0; !drawn && t < REALTIME_VISIBILITY_TRIES; ++t) {
        float v0 = rng_float(rng), v1 = rng_float(rng);
        SpheraSample b = sphera_cap_sample_uniform(cap, v0, v1);
        if (!(b.pdf > 0.0f)) break;
        if (!(b.dir.z > 0.0f)) continue;
        drawn = true;
        *samples += 1;
        visible = unoccluded(scene, context, hit, light, frame_to_world(&hit->frame, b.dir));
    }
    if (visible > 0.0f) {
        float3 specular = to_float3(sphera_sphere_light_shading_eval(shading, cap));
        sum = f3_add(sum, f3_scale(f3_mul(light->radiance, specular), visible));
    }
    return sum;
}

/* The rays per shading point that estimate the bent cone of sphere_occlusion and
 * sphere_occlusion_separable: one per cell of a grid of BENT_CONE_ROWS x
 * BENT_CONE_COLUMNS cells of equal solid angle over the hemisphere, the grid shifted by
 * one random offset per shading point (stratified, so the visible fraction varies by
 * little; the shift turns the steps of a fixed grid, rings on the floor, into noise
 * that the passes average). */
#define BENT_CONE_ROWS 8
#define BENT_CONE_COLUMNS 16

/* The bent cone at `hit` (Landis 2002; the visibility of Dupuy et al. 2017, Sec. 5.4),
 * in the local frame: the cone about the mean unoccluded direction whose solid angle
 * is the unoccluded part of the hemisphere, 1 - cos = the fraction of rays (uniform in
 * solid angle) that nothing blocks (lights are not occluders; rays run to infinity).
 * False when every ray is blocked. Its rays are not counted as light samples. */
static bool bent_cone(const Scene *scene, struct RTCIntersectContext *context, const Hit *hit,
                      Rng *rng, SpheraCap *cone) {
    float sum[3] = {0.0f, 0.0f, 0.0f};
    int visible = 0;
    const float shift_z = rng_float(rng), shift_phi = rng_float(rng);
    for (int i = 0; i < BENT_CONE_ROWS; ++i) {
        for (int j = 0; j < BENT_CONE_COLUMNS; ++j) {
            /* z uniform in (0, 1] and the azimuth in [0, 2π): uniform in solid angle. */
            float z = 1.0f - ((float)i + shift_z) / (float)BENT_CONE_ROWS;
            float phi = 2.0f * PI_F * ((float)j + shift_phi) / (float)BENT_CONE_COLUMNS;
            float r = sqrtf(fmaxf(1.0f - z * z, 0.0f));
            SpheraVec3 d = {r * cosf(phi), r * sinf(phi), z};
            struct RTCRay ray = make_ray(hit->origin, frame_to_world(&hit->frame, d), INFINITY);
            rtcOccluded1(scene->rtc, context, &ray);
            if (ray.tfar >= 0.0f) { /* Embree sets tfar to -inf on a hit */
                sum[0] += d.x;
                sum[1] += d.y;
                sum[2] += d.z;
                ++visible;
            }
        }
    }
    if (visible == 0) return false;
    SpheraVec3 axis = {sum[0], sum[1], sum[2]};
    float fraction = (float)visible / (float)(BENT_CONE_ROWS * BENT_CONE_COLUMNS);
    *cone = sphera_cap_from_axis_cos(axis, 1.0f - fraction);
    return true;
}

/* One light sample of sphere_occlusion or sphere_occlusion_separable (BIASED): the
 * Lambert layer as in sphere_cap (one uniform cap sample and its shadow ray), plus the
 * GGX layer as L * S, where S is the SPTD's specular occlusion of the light's cap by
 * the bent cone `cone` (Eq. 23: sphera_sphere_light_shading_eval of the shading prepared
 * with it, the value of sphera_sphere_light_shading_eval_occluded) or its separable
 * baseline (Eq. 21-22, sphera_sphere_light_shading_eval_occluded_separable). No shadow ray for
 * the GGX layer: the bent cone stands for the visibility. */
static float3 sphere_occlusion_estimate(const Scene *scene, struct RTCIntersectContext *context,
                                        const Hit *hit, const Light *light, SpheraCap cap,
                                        const SpheraSphereLightShading *shading,
                                        const SpheraCap *cone, bool separable, Rng *rng,
                                        uint64_t *samples) {
    const Material *m = &scene->materials[hit->material];
    float3 sum = f3(0, 0, 0);
    float u0 = rng_float(rng), u1 = rng_float(rng);
    SpheraSample a = sphera_cap_sample_uniform(cap, u0, u1);
    *samples += 1;
    if (a.pdf > 0.0f && a.dir.z > 0.0f) {
        float visible = unoccluded(scene, context, hit, light, frame_to_world(&hit->frame, a.dir));
        sum = f3_scale(f3_mul(light->radiance, brdf_diffuse(m)), visible * a.dir.z / a.pdf);
    }
    if (!shading || !cone) return sum;
    /* `shading` has the bent cone prepared in for the Eq. 23 technique (shade). */
    SpheraVec3 specular = separable
                              ? sphera_sphere_light_shading_eval_occluded_separable(shading, cap, *cone)
                              : sphera_sphere_light_shading_eval(shading, cap);
    return f3_add(sum, f3_mul(light->radiance, to_float3(specular)));
}

/* The reflected radiance from a sphere light, k samples: uniform cap sampling, or (for
 * sphere_cap_brdf) one cap and one BRDF sample per light sample with the balance
 * heuristic. sphere_sptd (and the reference, whose variance is lowest with it) splits
 * the BRDF: its Lambert part exactly as
 * sphere_cap_brdf (the same estimator on f_diffuse), its GGX part by the SPTD light
 * sampler and VNDF sampling; on materials without GGX it is sphere_cap_brdf.
 * sphere_realtime: see sphere_realtime_estimate (`shading` is its prepared SPTD
 * shading, NULL without a GGX layer). Every polygon technique samples spheres
 * uniformly in the cap. */
static float3 shade_sphere(const Scene *scene, struct RTCIntersectContext *context,
                           const Hit *hit, const Light *light, Technique technique, uint32_t k,
                           const BrdfSampler *brdf, const SpheraSphereLightShading *shading,
                           const SpheraCap *cone, Rng *rng, uint64_t *samples) {
    float3 centre = f3_sub(light->center, hit->position);
    SpheraVec3 local = frame_to_local(&hit->frame, centre);
    SpheraCap cap = sphera_cap_from_sphere(local, light->radius);
    if (f3_dot(centre, centre) <= light->radius * light->radius) return f3(0, 0, 0);
    const Material *m = &scene->materials[hit->material];
    float3 sum = f3(0, 0, 0);
    if (technique == TECHNIQUE_SPHERE_REALTIME) {
        for (uint32_t s = 0; s < k; ++s)
            sum = f3_add(sum, sphere_realtime_estimate(scene, context, hit, light, cap, shading,
                                                       rng, samples));
        return f3_scale(sum, 1.0f / (float)k);
    }
    if (technique == TECHNIQUE_SPHERE_OCCLUSION || technique == TECHNIQUE_SPHERE_OCCLUSION_SEPARABLE) {
        bool separable = technique == TECHNIQUE_SPHERE_OCCLUSION_SEPARABLE;
        for (uint32_t s = 0; s < k; ++s)
            sum = f3_add(sum, sphere_occlusion_estimate(scene, context, hit, light, cap, shading,
                                                        cone, separable, rng, samples));
        return f3_scale(sum, 1.0f / (float)k);
    }
    if (technique == TECHNIQUE_SPHERE_PROJECTED) {
        /* Prepared once per light at this point, as a renderer does, for k samples. */
        SpheraSptdInCap cosine;
        const SpheraVec3 origin = {0.0f, 0.0f, 0.0f}, down = {0.0f, 0.0f, -1.0f};
        bool has_cosine =
            sphera_sptd_in_cap_prepare(&cosine, origin, SPHERA_SPTD_CLAMPED_COSINE, down, cap);
        SpheraSphereLightSampler specular;
        bool has_specular = m->roughness > 0.0f &&
                            sphera_sphere_light_sampler_prepare(&specular, local, light->radius,
                                                                to_sphera(hit->wo), m->roughness);
        for (uint32_t s = 0; s < k; ++s)
            sum = f3_add(sum, sphere_projected_estimate(
                                  scene, context, hit, light, cap, has_cosine ? &cosine : NULL,
                                  has_specular ? &specular : NULL, brdf, rng, samples));
        return f3_scale(sum, 1.0f / (float)k);
    }
    SpheraSphereLightSampler sampler;
    bool sptd = (technique == TECHNIQUE_SPHERE_SPTD || technique == TECHNIQUE_REFERENCE) &&
                m->roughness > 0.0f &&
                sphera_sphere_light_sampler_prepare(&sampler, local, light->radius,
                                                    to_sphera(hit->wo), m->roughness);
    if (sptd) {
        for (uint32_t s = 0; s < k; ++s) {
            *samples += 4;
            sum = f3_add(sum, sphere_cap_brdf_estimate(scene, context, hit, light, cap, brdf,
                                                       BRDF_DIFFUSE, rng));
            sum = f3_add(sum, sphere_sptd_specular_estimate(scene, context, hit, light, &sampler,
                                                            rng));
        }
        return f3_scale(sum, 1.0f / (float)k);
    }
    bool mis = technique == TECHNIQUE_SPHERE_CAP_BRDF || technique == TECHNIQUE_SPHERE_SPTD ||
               technique == TECHNIQUE_MEDIUM_PIVOT || technique == TECHNIQUE_MEDIUM_HG_CAP ||
               technique == TECHNIQUE_REFERENCE;
    for (uint32_t s = 0; s < k; ++s) {
        if (mis) {
            *samples += 2;
            sum = f3_add(sum, sphere_cap_brdf_estimate(scene, context, hit, light, cap, brdf,
                                                       BRDF_WHOLE, rng));
            continue;
        }
        float u0 = rng_float(rng), u1 = rng_float(rng);
        SpheraSample a = sphera_cap_sample_uniform(cap, u0, u1);
        *samples += 1;
        if (a.pdf > 0.0f && a.dir.z > 0.0f) {
            float3 f = brdf_part(m, hit->wo, a.dir, BRDF_WHOLE);
            float3 radiance = light_cosine(scene, context, hit, light, a.dir);
            sum = f3_add(sum, f3_scale(f3_mul(radiance, f), 1.0f / a.pdf));
        }
    }
    return f3_scale(sum, 1.0f / (float)k);
}

/* The distance along the world direction `dir` from `origin` to the nearer
 * intersection with the sphere of `light`, or INFINITY when the ray misses it. */
static float sphere_distance(float3 origin, float3 dir, const Light *light) {
    float3 oc = f3_sub(origin, light->center);
    float b = f3_dot(oc, dir), c = f3_dot(oc, oc) - light->radius * light->radius;
    float discriminant = b * b - c;
    if (!(discriminant >= 0.0f) || !(b < 0.0f)) return INFINITY;
    return c / (-b + sqrtf(discriminant));
}

/* Whether lights `a` and `b` are two sphere lights of equal radiance, which
 * sphere_union and sphere_mixture sample as one light. */
static bool is_sphere_pair(const Light *a, const Light *b) {
    return a->radius > 0.0f && b->radius > 0.0f && a->radiance.x == b->radiance.x &&
           a->radiance.y == b->radiance.y && a->radiance.z == b->radiance.z;
}

/* The reflected radiance from two sphere lights of equal radiance L, sampled as one
 * light whose directions are the union of their caps A and B, k samples:
 * - sphere_union: uniform in A u B (sphera_cap_union_*, Dupuy et al. 2017 Sec. 4: sets
 *   of caps), pdf 1 / Omega(A u B);
 * - sphere_mixture (its baseline): light A or B with probability 1/2 (u0 picks it and
 *   is rescaled), uniform in its cap, pdf the mixture (p_A + p_B) / 2, so that a
 *   direction in A n B counts once with the density of both draws.
 * Either way a direction of the union sees the light that its ray meets first (in
 * A n B the nearer sphere hides the other), with radiance L, so the estimate
 * f L cos V / pdf is unbiased for the two lights together. */
static float3 shade_sphere_pair(const Scene *scene, struct RTCIntersectContext *context,
                                const Hit *hit, const Light *a, const Light *b,
                                Technique technique, uint32_t k, Rng *rng, uint64_t *samples) {
    float3 ca = f3_sub(a->center, hit->position), cb = f3_sub(b->center, hit->position);
    if (f3_dot(ca, ca) <= a->radius * a->radius || f3_dot(cb, cb) <= b->radius * b->radius)
        return f3(0, 0, 0);
    SpheraCap cap_a = sphera_cap_from_sphere(frame_to_local(&hit->frame, ca), a->radius);
    SpheraCap cap_b = sphera_cap_from_sphere(frame_to_local(&hit->frame, cb), b->radius);
    const Material *m = &scene->materials[hit->material];
    bool use_union = technique == TECHNIQUE_SPHERE_UNION;
    /* Prepared once per pair at this point, for k samples. */
    SpheraCapUnion both;
    if (use_union && !sphera_cap_union_prepare(&both, cap_a, cap_b)) return f3(0, 0, 0);
    float3 sum = f3(0, 0, 0);
    for (uint32_t s = 0; s < k; ++s) {
        float u0 = rng_float(rng), u1 = rng_float(rng);
        SpheraSample x;
        *samples += 1;
        if (use_union) {
            x = sphera_cap_union_sample(&both, u0, u1);
        } else {
            bool first = u0 < 0.5f;
            x = sphera_cap_sample_uniform(first ? cap_a : cap_b, first ? 2.0f * u0 : 2.0f * u0 - 1.0f,
                                          u1);
            if (x.pdf > 0.0f)
                x.pdf = 0.5f * (sphera_cap_pdf(cap_a, x.dir) + sphera_cap_pdf(cap_b, x.dir));
        }
        if (!(x.pdf > 0.0f) || !(x.dir.z > 0.0f)) continue;
        bool in_a = sphera_cap_contains(cap_a, x.dir), in_b = sphera_cap_contains(cap_b, x.dir);
        const Light *seen = in_a ? a : b;
        if (in_a && in_b) {
            float3 dir = frame_to_world(&hit->frame, x.dir);
            seen = sphere_distance(hit->origin, dir, a) <= sphere_distance(hit->origin, dir, b) ? a
                                                                                                : b;
        } else if (!in_a && !in_b) {
            continue;
        }
        float3 f = brdf_part(m, hit->wo, x.dir, BRDF_WHOLE);
        float3 radiance = light_cosine(scene, context, hit, seen, x.dir);
        sum = f3_add(sum, f3_scale(f3_mul(radiance, f), 1.0f / x.pdf));
    }
    return f3_scale(sum, 1.0f / (float)k);
}

/* The estimate of the radiance reflected at `hit` from all lights, with `k` samples
 * per light. */
static float3 shade(const Scene *scene, struct RTCIntersectContext *context, const Hit *hit,
                    Technique technique, uint32_t k, Rng *rng, uint64_t *samples) {
    const Material *m = &scene->materials[hit->material];
    ShadingPoint point;
    point.wo = to_sphera(hit->wo);
    point.material.diffuse = to_sphera(m->diffuse);
    point.material.f0 = to_sphera(m->specular);
    point.material.roughness = m->roughness;
    BrdfSampler brdf;
    memset(&brdf, 0, sizeof brdf);
    if (technique == TECHNIQUE_BRDF_BALANCE || technique == TECHNIQUE_BRDF_POWER ||
        technique == TECHNIQUE_SPHERE_CAP_BRDF || technique == TECHNIQUE_SPHERE_SPTD ||
        technique == TECHNIQUE_SPHERE_PROJECTED || technique == TECHNIQUE_MEDIUM_PIVOT ||
        technique == TECHNIQUE_MEDIUM_HG_CAP ||
        technique == TECHNIQUE_REFERENCE)
        brdf_sampler_init(&brdf, m, hit->wo);
    /* sphere_realtime: the SPTD shading depends on the view and the material only */
    SpheraSphereLightShading shading;
    const SpheraSphereLightShading *sphere_shading = NULL;
    bool occlusion = technique == TECHNIQUE_SPHERE_OCCLUSION ||
                     technique == TECHNIQUE_SPHERE_OCCLUSION_SEPARABLE;
    if ((technique == TECHNIQUE_SPHERE_REALTIME || occlusion) && m->roughness > 0.0f &&
        sphera_sphere_light_shading_prepare(&shading, point.wo, m->roughness, point.material.f0))
        sphere_shading = &shading;
    /* sphere_occlusion*: the bent cone, once per shading point with a GGX layer */
    SpheraCap cone;
    const SpheraCap *bent = NULL;
    if (occlusion && sphere_shading && bent_cone(scene, context, hit, rng, &cone)) {
        bent = &cone;
        /* sphere_occlusion: the bent cone prepared into the shading, once per shading
         * point; _eval per light then gives _eval_occluded with it, bit for bit. */
        if (technique == TECHNIQUE_SPHERE_OCCLUSION &&
            !sphera_sphere_light_shading_prepare_occluded(&shading, point.wo, m->roughness,
                                                          point.material.f0, cone))
            sphere_shading = NULL;
    }
    float3 sum = f3(0, 0, 0);
    for (uint32_t l = 0; l < scene->light_count; ++l) {
        const Light *light = &scene->lights[l];
        if ((technique == TECHNIQUE_SPHERE_UNION || technique == TECHNIQUE_SPHERE_MIXTURE) &&
            l + 1 < scene->light_count && is_sphere_pair(light, &scene->lights[l + 1])) {
            sum = f3_add(sum, shade_sphere_pair(scene, context, hit, light, &scene->lights[l + 1],
                                                technique, k, rng, samples));
            ++l;
            continue;
        }
        if (light->radius > 0.0f) {
            sum = f3_add(sum, shade_sphere(scene, context, hit, light, technique, k, &brdf,
                                           sphere_shading, bent, rng, samples));
            continue;
        }
        /* One-sided lights: nothing reaches points behind the light's plane. */
        if (!(f3_dot(light->normal, f3_sub(hit->position, light->vertices[0])) > 0.0f)) continue;
        SpheraVec3 local[SPHERA_MAX_POLYGON_VERTICES];
        for (uint32_t i = 0; i < light->count; ++i)
            local[i] = frame_to_local(&hit->frame, f3_sub(light->vertices[i], hit->position));
        PreparedLight prepared;
        if (!technique_prepare(technique, &prepared, local, light->count, &point)) continue;
        float3 light_sum = f3(0, 0, 0);
        for (uint32_t s = 0; s < k; ++s) {
            float u0 = rng_float(rng), u1 = rng_float(rng);
            if (technique_is_pair(technique)) {
                float v0 = rng_float(rng), v1 = rng_float(rng);
                *samples += 2;
                light_sum = f3_add(light_sum, pair_estimate(scene, context, hit, light, technique,
                                                            &prepared, &brdf, u0, u1, v0, v1));
            } else if (technique == TECHNIQUE_REFERENCE) {
                float v0 = rng_float(rng), v1 = rng_float(rng);
                if (prepared.reference_glossy) {
                    *samples += 2;
                    light_sum = f3_add(light_sum,
                                       pair_estimate(scene, context, hit, light, TECHNIQUE_LTC_WEIGHTED,
                                                     &prepared, &brdf, u0, u1, v0, v1));
                } else {
                    SpheraSample a = sphera_projected_polygon_sample(&prepared.u.projected, u0, u1);
                    *samples += 1;
                    if (a.pdf > 0.0f) {
                        float3 radiance = light_cosine(scene, context, hit, light, a.dir);
                        light_sum = f3_add(light_sum,
                                           f3_scale(f3_mul(radiance, brdf_diffuse(m)), 1.0f / a.pdf));
                    }
                }
            } else {
                SpheraSample sample = technique_sample(technique, &prepared, u0, u1);
                *samples += 1;
                if (!(sample.pdf > 0.0f)) continue;
                float3 radiance = light_cosine(scene, context, hit, light, sample.dir);
                float3 f = f3_add(brdf_diffuse(m), brdf_specular(m, hit->wo, to_float3(sample.dir)));
                light_sum = f3_add(light_sum, f3_scale(f3_mul(radiance, f), 1.0f / sample.pdf));
            }
        }
        sum = f3_add(sum, f3_scale(light_sum, 1.0f / (float)k));
    }
    return sum;
}

/* ---- single scattering in the medium ------------------------------------------------ */

/* The radiance scattered once towards the camera along the camera ray's part inside
 * the medium, from all sphere lights, k samples per light (polygon lights do not light
 * the medium). The distance is drawn proportionally to the transmittance over
 * [t0, t1]: t = t0 - ln(1 - u (1 - e^(-sigma_t d))) / sigma_t, so that
 * transmittance * sigma_s / pdf(t) = (sigma_s / sigma_t) (1 - e^(-sigma_t d)), and at
 * that point the in-scattered radiance
 *   L_s = int_cap HG(w . camera_dir, g) L(w) T(w) dw
 * (w towards the light; forward scattering when w = camera_dir) is estimated by
 * - medium_pivot: one sample of the pivot phase function with pivot g_p
 *   = sphera_phase_pivot_from_henyey_greenstein(g) (Eq. 27-28) restricted to the cap
 *   (sphera_sptd_in_cap_prepare_pivot_phase, Section 6.2), estimate HG L T / pdf: unbiased,
 *   as the pdf is positive in the whole cap;
 * - medium_hg_cap and the reference: one HG sample and one uniform cap sample,
 *   balance heuristic;
 * - every other technique: one uniform cap sample. */
static float3 in_scattering(const Scene *scene, struct RTCIntersectContext *context,
                            const Hit *hit, Technique technique, uint32_t k, Rng *rng,
                            uint64_t *samples) {
    const Medium *medium = &scene->medium;
    const float3 d = hit->camera_dir;
    const float length = hit->t1 - hit->t0;
    const float sigma_t = medium->sigma_t, g = medium->g;
    const float absorbed = -expm1f(-sigma_t * length); /* 1 - e^(-sigma_t d) */
    const float scale = medium->sigma_s / sigma_t * absorbed;
    float3 sum = f3(0, 0, 0);
    for (uint32_t l = 0; l < scene->light_count; ++l) {
        const Light *light = &scene->lights[l];
        if (!(light->radius > 0.0f)) continue;
        for (uint32_t s = 0; s < k; ++s) {
            float u = rng_float(rng);
            float t = hit->t0 - log1pf(-u * absorbed) / sigma_t;
            if (!(t < hit->t1)) t = hit->t1;
            float3 x = f3_add(scene->camera.position, f3_scale(d, t));
            float3 centre = f3_sub(light->center, x);
            if (f3_dot(centre, centre) <= light->radius * light->radius) continue;
            SpheraVec3 c = to_sphera(centre);
            SpheraCap cap = sphera_cap_from_sphere(c, light->radius);
            float u0 = rng_float(rng), u1 = rng_float(rng);
            float v0 = rng_float(rng), v1 = rng_float(rng);
            float estimate = 0.0f; /* of L_s per unit radiance */
            if (technique == TECHNIQUE_MEDIUM_PIVOT) {
                SpheraSptdInCap pivot;
                *samples += 1;
                if (!sphera_sptd_in_cap_prepare_pivot_phase(
                        &pivot, to_sphera(d), sphera_phase_pivot_from_henyey_greenstein(g), cap))
                    continue;
                SpheraSample a = sphera_sptd_in_cap_sample(&pivot, u0, u1);
                if (!(a.pdf > 0.0f)) continue;
                float3 w = to_float3(a.dir);
                float f = sphera_phase_henyey_greenstein(f3_dot(w, d), g);
                estimate = f * transmitted(scene, context, x, light, w) / a.pdf;
            } else if (technique == TECHNIQUE_MEDIUM_HG_CAP || technique == TECHNIQUE_REFERENCE) {
                *samples += 2;
                SpheraSample a = sphera_cap_sample_uniform(cap, u0, u1);
                if (a.pdf > 0.0f) {
                    float3 w = to_float3(a.dir);
                    float f = sphera_phase_henyey_greenstein(f3_dot(w, d), g);
                    float weight = sphera_mis_balance(a.pdf, f);
                    if (weight > 0.0f)
                        estimate += f * weight * transmitted(scene, context, x, light, w) / a.pdf;
                }
                SpheraSample b = sphera_phase_henyey_greenstein_sample(to_sphera(d), g, v0, v1);
                float cap_pdf = b.pdf > 0.0f ? sphera_cap_pdf(cap, b.dir) : 0.0f;
                if (cap_pdf > 0.0f) {
                    float3 w = to_float3(b.dir);
                    float f = sphera_phase_henyey_greenstein(f3_dot(w, d), g);
                    float weight = sphera_mis_balance(b.pdf, cap_pdf);
                    if (weight > 0.0f)
                        estimate += f * weight * transmitted(scene, context, x, light, w) / b.pdf;
                }
            } else {
                *samples += 1;
                SpheraSample a = sphera_cap_sample_uniform(cap, u0, u1);
                if (!(a.pdf > 0.0f)) continue;
                float3 w = to_float3(a.dir);
                float f = sphera_phase_henyey_greenstein(f3_dot(w, d), g);
                estimate = f * transmitted(scene, context, x, light, w) / a.pdf;
            }
            sum = f3_add(sum, f3_scale(light->radiance, scale * estimate / (float)k));
        }
    }
    return sum;
}

/* ---- camera rays ------------------------------------------------------------------ */

static void trace_camera_rays(const Scene *scene, uint32_t width, uint32_t height, Hit *hits) {
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    const Camera *camera = &scene->camera;
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            Hit *hit = &hits[y * width + x];
            memset(hit, 0, sizeof *hit);
            float sx = 2.0f * ((float)x + 0.5f) / (float)width - 1.0f;
            float sy = 1.0f - 2.0f * ((float)y + 0.5f) / (float)height;
            float3 dir = f3_normalize(f3_add(
                camera->forward, f3_add(f3_scale(camera->right, sx), f3_scale(camera->up, sy))));
            struct RTCRayHit rh = make_ray_hit(camera->position, dir);
            rtcIntersect1(scene->rtc, &context, &rh);
            hit->camera_dir = dir;
            hit->transmittance = 1.0f;
            if (medium_segment(&scene->medium, camera->position, dir, rh.ray.tfar, &hit->t0,
                               &hit->t1)) {
                hit->in_medium = true;
                hit->transmittance = expf(-scene->medium.sigma_t * (hit->t1 - hit->t0));
            }
            if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
            uint32_t triangle = rh.hit.primID;
            float3 normal = scene->triangle_normal[triangle];
            int32_t light = scene->triangle_light[triangle];
            if (light >= 0) {
                const Light *l = &scene->lights[light];
                if (l->radius > 0.0f || f3_dot(l->normal, dir) < 0.0f) hit->emission = l->radiance;
                continue;
            }
            if (f3_dot(normal, dir) > 0.0f) normal = f3_scale(normal, -1.0f);
            SpheraVec3 n = {normal.x, normal.y, normal.z};
            if (!sphera_frame_from_normal(&hit->frame, n)) continue;
            hit->position = f3_add(camera->position, f3_scale(dir, rh.ray.tfar));
            hit->origin = f3_add(hit->position, f3_scale(normal, scene->ray_epsilon));
            SpheraVec3 wo = frame_to_local(&hit->frame, f3_scale(dir, -1.0f));
            hit->wo = f3(wo.x, wo.y, wo.z);
            hit->material = scene->triangle_material[triangle];
            hit->reflects = true;
        }
    }
}

/* ---- passes over tiles ------------------------------------------------------------- */

typedef struct PassShared {
    const Scene *scene;
    const RenderSettings *settings;
    const Hit *hits;
    double *sum, *sum_squares; /* per pixel and channel */
    uint32_t pass;
    uint32_t tiles_x, tile_count;
    uint32_t next_tile; /* taken with an atomic add */
} PassShared;

typedef struct Worker {
    PassShared *shared;
    uint64_t samples;
} Worker;

static void *render_tiles(void *argument) {
    Worker *worker = argument;
    PassShared *shared = worker->shared;
    const RenderSettings *settings = shared->settings;
    const uint32_t width = settings->width, height = settings->height;
    enable_flush_to_zero();
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    uint64_t samples = 0; /* counted locally: no false sharing between workers */
    for (;;) {
        uint32_t tile = __atomic_fetch_add(&shared->next_tile, 1, __ATOMIC_RELAXED);
        if (tile >= shared->tile_count) break;
        uint32_t x0 = (tile % shared->tiles_x) * TILE, y0 = (tile / shared->tiles_x) * TILE;
        for (uint32_t y = y0; y < y0 + TILE && y < height; ++y) {
            for (uint32_t x = x0; x < x0 + TILE && x < width; ++x) {
                uint32_t pixel = y * width + x;
                const Hit *hit = &shared->hits[pixel];
                float3 value = hit->emission;
                Rng rng = {settings->seed * 0x632BE59BD9B4E019ull +
                           ((uint64_t)shared->pass << 32) + pixel};
                splitmix64(&rng.state);
                if (hit->reflects)
                    value = f3_add(value, shade(shared->scene, &context, hit, settings->technique,
                                                settings->light_samples, &rng, &samples));
                /* what lies behind the medium is seen through it */
                value = f3_scale(value, hit->transmittance);
                if (hit->in_medium)
                    value = f3_add(value, in_scattering(shared->scene, &context, hit,
                                                        settings->technique,
                                                        settings->light_samples, &rng, &samples));
                double v[3] = {value.x, value.y, value.z};
                for (int c = 0; c < 3; ++c) {
                    shared->sum[3 * pixel + c] += v[c];
                    shared->sum_squares[3 * pixel + c] += v[c] * v[c];
                }
            }
        }
    }
    worker->samples += samples;
    return NULL;
}

void image_error(const float *image, const float *reference, uint32_t width, uint32_t height,
                 double *rmse, double *relmse) {
    double squared = 0.0, relative = 0.0;
    size_t n = (size_t)width * height * 3;
    for (size_t i = 0; i < n; ++i) {
        double d = (double)image[i] - (double)reference[i];
        squared += d * d;
        relative += d * d / ((double)reference[i] * reference[i] + 0.01);
    }
    *rmse = sqrt(squared / (double)n);
    *relmse = relative / (double)n;
}

static void mean_image(const double *sum, uint32_t passes, size_t n, float *out) {
    for (size_t i = 0; i < n; ++i) out[i] = (float)(sum[i] / passes);
}

bool render(const Scene *scene, const RenderSettings *settings, RenderResult *result) {
    memset(result, 0, sizeof *result);
    const uint32_t width = settings->width, height = settings->height;
    const size_t pixels = (size_t)width * height;
    Hit *hits = malloc(sizeof(Hit) * pixels);
    double *sum = calloc(pixels * 3, sizeof(double));
    double *sum_squares = calloc(pixels * 3, sizeof(double));
    float *image = malloc(sizeof(float) * pixels * 3);
    float *variance = calloc(pixels * 3, sizeof(float));
    uint32_t threads = settings->threads ? settings->threads : core_count();
    pthread_t *ids = malloc(sizeof(pthread_t) * threads);
    Worker *workers = calloc(threads, sizeof(Worker));
    if (!hits || !sum || !sum_squares || !image || !variance || !ids || !workers) {
        fprintf(stderr, "sphera-trace: out of memory\n");
        goto fail;
    }
    enable_flush_to_zero();
    trace_camera_rays(scene, width, height, hits);

    PassShared shared = {0};
    shared.scene = scene;
    shared.settings = settings;
    shared.hits = hits;
    shared.sum = sum;
    shared.sum_squares = sum_squares;
    shared.tiles_x = (width + TILE - 1) / TILE;
    shared.tile_count = shared.tiles_x * ((height + TILE - 1) / TILE);
    for (uint32_t t = 0; t < threads; ++t) workers[t].shared = &shared;

    const uint32_t max_passes =
        settings->time_budget_ms > 0.0 ? UINT32_MAX : (settings->passes ? settings->passes : 1);
    double elapsed = 0.0, last_progress = now_ms();
    uint32_t pass = 0, next_checkpoint = 1;
    while (pass < max_passes) {
        double start = now_ms();
        shared.pass = pass;
        shared.next_tile = 0;
        uint32_t started = 1;
        for (; started < threads; ++started)
            if (pthread_create(&ids[started], NULL, render_tiles, &workers[started]) != 0) break;
        render_tiles(&workers[0]);
        for (uint32_t t = 1; t < started; ++t) pthread_join(ids[t], NULL);
        double end = now_ms();
        elapsed += end - start;
        ++pass;
        bool done = pass == max_passes ||
                    (settings->time_budget_ms > 0.0 && elapsed >= settings->time_budget_ms);
        if (settings->reference && settings->on_checkpoint && (pass == next_checkpoint || done)) {
            double rmse, relmse;
            mean_image(sum, pass, pixels * 3, image);
            image_error(image, settings->reference, width, height, &rmse, &relmse);
            settings->on_checkpoint(settings->checkpoint_context, pass, elapsed, rmse, relmse);
            while (next_checkpoint <= pass) next_checkpoint *= 2;
        }
        if (settings->progress && (end - last_progress > 500.0 || done)) {
            if (settings->time_budget_ms > 0.0)
                fprintf(stderr, "\r%s/%s: pass %u, %.0f of %.0f ms   ", scene->name,
                        technique_info[settings->technique].name, pass, elapsed,
                        settings->time_budget_ms);
            else
                fprintf(stderr, "\r%s/%s: pass %u of %u, %.0f ms   ", scene->name,
                        technique_info[settings->technique].name, pass, max_passes, elapsed);
            if (done) fputc('\n', stderr);
            last_progress = end;
        }
        if (done) break;
    }

    mean_image(sum, pass, pixels * 3, image);
    double channel_variance[3] = {0, 0, 0}, total_variance = 0.0;
    for (size_t i = 0; i < pixels * 3; ++i) {
        double mean = sum[i] / pass;
        double v = 0.0;
        if (pass > 1) {
            /* unbiased sample variance of the pass values, divided by the pass count */
            v = (sum_squares[i] - pass * mean * mean) / ((double)pass * (pass - 1));
            if (v < 0.0) v = 0.0;
        }
        variance[i] = (float)v;
        channel_variance[i % 3] += v;
        total_variance += v;
        result->mean[i % 3] += mean;
    }
    for (int c = 0; c < 3; ++c) {
        result->mean[c] /= (double)pixels;
        result->mean_stderr[c] = sqrt(channel_variance[c]) / (double)pixels;
    }
    result->variance_of_mean = total_variance / (double)(pixels * 3);
    if (settings->reference)
        image_error(image, settings->reference, width, height, &result->rmse, &result->relmse);
    result->passes = pass;
    result->time_ms = elapsed;
    for (uint32_t t = 0; t < threads; ++t) result->samples += workers[t].samples;
    result->image = image;
    result->variance = variance;
    free(hits);
    free(sum);
    free(sum_squares);
    free(ids);
    free(workers);
    return true;

fail:
    free(hits);
    free(sum);
    free(sum_squares);
    free(image);
    free(variance);
    free(ids);
    free(workers);
    return false;
}

void render_result_free(RenderResult *result) {
    free(result->image);
    free(result->variance);
    result->image = result->variance = NULL;
}
