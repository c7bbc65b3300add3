/* One-bounce indirect light from a spot: VSGLs (FIS or k-means) against path tracing.
 * See indirect.h. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "common.h"
#include "indirect.h"


/* ---- small helpers --------------------------------------------------------------- */

static float uniform(uint64_t *state) { return (float)(splitmix64(state) >> 40) * 0x1p-24f; }

static SpheraVec3 sv(float3 v) {
    SpheraVec3 r = {v.x, v.y, v.z};
    return r;
}

static float3 fv(SpheraVec3 v) { return f3(v.x, v.y, v.z); }

static float lum(float3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/* The nearest hit along a ray: false on a miss or a light's triangle. */
static bool intersect(const Scene *scene, struct RTCIntersectContext *context, float3 origin,
                      float3 dir, float *t, uint32_t *triangle) {
    struct RTCRayHit rh = make_ray_hit(origin, dir);
    rtcIntersect1(scene->rtc, context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    if (scene->triangle_light[rh.hit.primID] >= 0) return false;
    *t = rh.ray.tfar;
    *triangle = rh.hit.primID;
    return true;
}

/* Whether the segment from `origin` to `target` is free (ending `epsilon` short). */
static bool segment_free(const Scene *scene, struct RTCIntersectContext *context, float3 origin,
                         float3 target) {
    float3 d = f3_sub(target, origin);
    float length = f3_length(d);
    if (!(length > 2.0f * scene->ray_epsilon)) return true;
    struct RTCRay ray = make_ray(origin, f3(d.x / length, d.y / length, d.z / length),
                                 length - scene->ray_epsilon);
    rtcOccluded1(scene->rtc, context, &ray);
    return ray.tfar >= 0.0f;
}

/* The full BRDF f(wo, wi) of a material (no cosine), local frame. */
static float3 material_eval(const Material *m, SpheraVec3 wo, SpheraVec3 wi) {
    if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return f3(0, 0, 0);
    float3 f = f3_scale(m->diffuse, 1.0f / PI_F);
    if (m->roughness > 0.0f) f = f3_add(f, fv(sphera_ggx_brdf_eval(&m->ggx, wo, wi)));
    return f;
}

/* The GGX layer's directional albedo at `wo` (Schlick-weighted, from libsphera's
 * fitted LTC table): the specular reflectance R_s of a VPL. */
static float3 specular_albedo(const Material *m, SpheraVec3 wo) {
    SpheraLtc ltc;
    if (!(m->roughness > 0.0f) || !sphera_ltc_prepare(&ltc, wo, m->roughness)) return f3(0, 0, 0);
    return fv(sphera_ltc_specular_albedo(&ltc, sv(m->specular)));
}

/* ---- the spot -------------------------------------------------------------------- */

SpotLight indirect_scene_spot(void) {
    SpotLight spot;
    spot.position = f3(1.8f, 2.7f, 1.6f);
    spot.direction = f3_normalize(f3_sub(f3(-1.2f, 0.0f, -0.8f), spot.position));
    spot.cos_inner = cosf(20.0f * PI_F / 180.0f);
    spot.cos_outer = cosf(35.0f * PI_F / 180.0f);
    spot.intensity = f3(60.0f, 55.0f, 48.0f);
    return spot;
}

float3 spot_intensity(const SpotLight *spot, float3 dir) {
    float c = f3_dot(spot->direction, dir);
    if (!(c > spot->cos_outer)) return f3(0, 0, 0);
    float t = (c - spot->cos_outer) / (spot->cos_inner - spot->cos_outer);
    t = t > 1.0f ? 1.0f : t;
    return f3_scale(spot->intensity, t * t * (3.0f - 2.0f * t));
}

/* ---- camera hits ----------------------------------------------------------------- */

typedef struct CameraHit {
    float3 position, origin; /* origin: pushed off the surface along the normal */
    SpheraFrame frame;       /* z = the normal turned towards the camera */
    SpheraVec3 wo;           /* towards the camera, local */
    uint32_t material;
    bool valid;
} CameraHit;

static void trace_camera(const Scene *scene, uint32_t width, uint32_t height, CameraHit *hits) {
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    const Camera *camera = &scene->camera;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            CameraHit *hit = &hits[y * width + x];
            memset(hit, 0, sizeof *hit);
            float sx = 2.0f * ((float)x + 0.5f) / (float)width - 1.0f;
            float sy = 1.0f - 2.0f * ((float)y + 0.5f) / (float)height;
            float3 dir = f3_normalize(f3_add(
                camera->forward, f3_add(f3_scale(camera->right, sx), f3_scale(camera->up, sy))));
            float t;
            uint32_t triangle;
            if (!intersect(scene, &context, camera->position, dir, &t, &triangle)) continue;
            float3 normal = scene->triangle_normal[triangle];
            if (f3_dot(normal, dir) > 0.0f) normal = f3_scale(normal, -1.0f);
            if (!sphera_frame_from_normal(&hit->frame, sv(normal))) continue;
            hit->position = f3_add(camera->position, f3_scale(dir, t));
            hit->origin = f3_add(hit->position, f3_scale(normal, scene->ray_epsilon));
            hit->wo = frame_to_local(&hit->frame, f3_scale(dir, -1.0f));
            hit->material = scene->triangle_material[triangle];
            hit->valid = true;
        }
}

/* ---- parallel loop over image rows ----------------------------------------------- */

typedef struct RowJob {
    void (*row)(void *context, struct RTCIntersectContext *rtc, uint32_t y);
    void *context;
    uint32_t height, next;
} RowJob;

static void *row_worker(void *argument) {
    RowJob *job = argument;
    enable_flush_to_zero();
    struct RTCIntersectContext rtc;
    rtcInitIntersectContext(&rtc);
    for (;;) {
        uint32_t y = __atomic_fetch_add(&job->next, 1, __ATOMIC_RELAXED);
        if (y >= job->height) break;
        job->row(job->context, &rtc, y);
    }
    return NULL;
}

static void for_each_row(uint32_t threads, uint32_t height,
                         void (*row)(void *, struct RTCIntersectContext *, uint32_t),
                         void *context) {
    RowJob job = {row, context, height, 0};
    pthread_t ids[64];
    if (threads > 64) threads = 64;
    uint32_t started = 1;
    for (; started < threads; ++started)
        if (pthread_create(&ids[started], NULL, row_worker, &job) != 0) break;
    row_worker(&job);
    for (uint32_t t = 1; t < started; ++t) pthread_join(ids[t], NULL);
}

/* ---- the reference --------------------------------------------------------------- */

typedef struct ReferenceJob {
    const Scene *scene;
    const SpotLight *spot;
    const CameraHit *hits;
    uint32_t width, spp;
    uint64_t seed;
    float *image;
} ReferenceJob;

/* The spot's direct light reflected at the surface point reached along `dir` from
 * `from`, towards `from` (0 when nothing is hit, the spot is behind the surface or
 * occluded). */
static float3 bounce_radiance(const Scene *scene, const SpotLight *spot,
                              struct RTCIntersectContext *rtc, float3 from, float3 dir) {
    float t;
    uint32_t triangle;
    if (!intersect(scene, rtc, from, dir, &t, &triangle)) return f3(0, 0, 0);
    float3 y = f3_add(from, f3_scale(dir, t));
    float3 normal = scene->triangle_normal[triangle];
    if (f3_dot(normal, dir) > 0.0f) normal = f3_scale(normal, -1.0f);
    float3 to_light = f3_sub(spot->position, y);
    float distance2 = f3_dot(to_light, to_light);
    float3 l = f3_scale(to_light, 1.0f / sqrtf(distance2));
    float cosine = f3_dot(normal, l);
    if (!(cosine > 0.0f)) return f3(0, 0, 0);
    float3 intensity = spot_intensity(spot, f3_scale(l, -1.0f));
    if (intensity.x == 0.0f && intensity.y == 0.0f && intensity.z == 0.0f) return f3(0, 0, 0);
    float3 origin = f3_add(y, f3_scale(normal, scene->ray_epsilon));
    if (!segment_free(scene, rtc, origin, spot->position)) return f3(0, 0, 0);
    SpheraFrame frame;
    if (!sphera_frame_from_normal(&frame, sv(normal))) return f3(0, 0, 0);
    const Material *m = &scene->materials[scene->triangle_material[triangle]];
    float3 f = material_eval(m, frame_to_local(&frame, f3_scale(dir, -1.0f)), frame_to_local(&frame, l));
    return f3_scale(f3_mul(f, intensity), cosine / distance2);
}

static void reference_row(void *context, struct RTCIntersectContext *rtc, uint32_t y) {
    ReferenceJob *job = context;
    for (uint32_t x = 0; x < job->width; ++x) {
        uint32_t pixel = y * job->width + x;
        const CameraHit *hit = &job->hits[pixel];
        double sum[3] = {0, 0, 0};
        if (hit->valid) {
            const Material *m = &job->scene->materials[hit->material];
            /* The BRDF sampler: GGX by visible normals with the probability of the GGX
             * layer's share of the albedo (luminance), else cosine-weighted. */
            float q = 0.0f;
            float3 spec = specular_albedo(m, hit->wo);
            if (lum(spec) + lum(m->diffuse) > 0.0f) q = lum(spec) / (lum(spec) + lum(m->diffuse));
            uint64_t state = job->seed * 0xD1342543DE82EF95ull + pixel;
            splitmix64(&state);
            for (uint32_t s = 0; s < job->spp; ++s) {
                float u0 = uniform(&state), u1 = uniform(&state);
                SpheraSample sample = u0 < q ? sphera_ggx_brdf_sample(&m->ggx, hit->wo, u0 / q, u1)
                                             : sphera_lambert_sample((u0 - q) / (1.0f - q), u1);
                if (!(sample.pdf > 0.0f) || !(sample.dir.z > 0.0f)) continue;
                float pdf = (1.0f - q) * sphera_lambert_pdf(sample.dir);
                if (q > 0.0f) pdf += q * sphera_ggx_brdf_pdf(&m->ggx, hit->wo, sample.dir);
                if (!(pdf > 0.0f)) continue;
                float3 f = material_eval(m, hit->wo, sample.dir);
                float3 dir = frame_to_world(&hit->frame, sample.dir);
                float3 radiance = bounce_radiance(job->scene, job->spot, rtc, hit->origin, dir);
                float w = sample.dir.z / pdf;
                sum[0] += (double)(f.x * radiance.x * w);
                sum[1] += (double)(f.y * radiance.y * w);
                sum[2] += (double)(f.z * radiance.z * w);
            }
        }
        for (int c = 0; c < 3; ++c) job->image[3 * pixel + c] = (float)(sum[c] / job->spp);
    }
}

bool indirect_render_reference(const Scene *scene, const SpotLight *spot, uint32_t width,
                               uint32_t height, uint32_t spp, uint32_t threads, uint64_t seed,
                               float **image, double *ms) {
    size_t pixels = (size_t)width * height;
    CameraHit *hits = malloc(sizeof(CameraHit) * pixels);
    *image = malloc(sizeof(float) * 3 * pixels);
    if (!hits || !*image) {
        free(hits);
        free(*image);
        *image = NULL;
        return false;
    }
    enable_flush_to_zero();
    trace_camera(scene, width, height, hits);
    double start = now_ms();
    ReferenceJob job = {scene, spot, hits, width, spp ? spp : 1, seed, *image};
    for_each_row(threads ? threads : core_count(), height, reference_row, &job);
    *ms = now_ms() - start;
    free(hits);
    return true;
}

/* ---- the RSM and its pyramid ----------------------------------------------------- */

/* The VPLs of an `size²` grid of rays over the square that holds the spot's outer cone
 * (texel centres on the plane at distance 1 along the axis). A texel's ray carries the
 * flux `I(ω) dω` with `dω = (2 tan θ_outer / size)² cos³ψ` (ψ from the axis); a miss,
 * a light or a zero intensity leaves a VPL without power (`valid` false). */
typedef struct Rsm {
    uint32_t size;
    SpheraVpl *vpls;
    bool *valid;
    uint32_t *material; /* of the surface each VPL lies on */
    SpheraVsglTexel *texels; /* the pyramid, sphera_vsgl_pyramid_texel_count(size) */
    size_t texel_count;
    SpheraVec3 origin;
} Rsm;

static void rsm_free(Rsm *rsm) {
    free(rsm->vpls);
    free(rsm->valid);
    free(rsm->material);
    free(rsm->texels);
    memset(rsm, 0, sizeof *rsm);
}

static bool rsm_alloc(Rsm *rsm, uint32_t size, float3 origin) {
    memset(rsm, 0, sizeof *rsm);
    rsm->size = size;
    rsm->texel_count = sphera_vsgl_pyramid_texel_count(size);
    if (rsm->texel_count == 0) return false;
    rsm->vpls = calloc((size_t)size * size, sizeof(SpheraVpl));
    rsm->valid = calloc((size_t)size * size, sizeof(bool));
    rsm->material = calloc((size_t)size * size, sizeof(uint32_t));
    rsm->texels = calloc(rsm->texel_count, sizeof(SpheraVsglTexel));
    rsm->origin = sv(origin);
    if (!rsm->vpls || !rsm->valid || !rsm->material || !rsm->texels) {
        rsm_free(rsm);
        return false;
    }
    return true;
}

static void rsm_trace(const Scene *scene, const SpotLight *spot, Rsm *rsm) {
    struct RTCIntersectContext rtc;
    rtcInitIntersectContext(&rtc);
    SpheraFrame frame;
    sphera_frame_from_normal(&frame, sv(spot->direction));
    float3 tangent = fv(frame.tangent), bitangent = fv(frame.bitangent);
    const uint32_t size = rsm->size;
    float half = tanf(acosf(spot->cos_outer));
    float texel = 2.0f * half / (float)size;
    for (uint32_t j = 0; j < size; ++j)
        for (uint32_t i = 0; i < size; ++i) {
            uint32_t k = j * size + i;
            SpheraVpl *vpl = &rsm->vpls[k];
            memset(vpl, 0, sizeof *vpl);
            rsm->valid[k] = false;
            float sx = half * (2.0f * ((float)i + 0.5f) / (float)size - 1.0f);
            float sy = half * (2.0f * ((float)j + 0.5f) / (float)size - 1.0f);
            float3 v = f3_add(spot->direction,
                              f3_add(f3_scale(tangent, sx), f3_scale(bitangent, sy)));
            float length = f3_length(v);
            float3 dir = f3_scale(v, 1.0f / length);
            float3 intensity = spot_intensity(spot, dir);
            float t;
            uint32_t triangle;
            if (lum(intensity) > 0.0f &&
                intersect(scene, &rtc, spot->position, dir, &t, &triangle)) {
                float cos_psi = 1.0f / length;
                float solid_angle = texel * texel * cos_psi * cos_psi * cos_psi;
                float3 normal = scene->triangle_normal[triangle];
                if (f3_dot(normal, dir) > 0.0f) normal = f3_scale(normal, -1.0f);
                const Material *m = &scene->materials[scene->triangle_material[triangle]];
                SpheraFrame local;
                float3 toward = f3_scale(dir, -1.0f);
                vpl->position = sv(f3_add(spot->position, f3_scale(dir, t)));
                vpl->normal = sv(normal);
                vpl->power = sv(f3_scale(intensity, solid_angle));
                vpl->diffuse_reflectance = sv(m->diffuse);
                if (sphera_frame_from_normal(&local, sv(normal)))
                    vpl->specular_reflectance = sv(specular_albedo(m, frame_to_local(&local, toward)));
                vpl->toward_incoming = sv(toward);
                vpl->roughness = m->roughness * m->roughness; /* GGX alpha */
                rsm->material[k] = scene->triangle_material[triangle];
                rsm->valid[k] = true;
            }
        }
}

/* Level 0 from the VPLs, then every coarser texel the field-wise sum of its four
 * children (the layout of sphera_vsgl_fis_select). Returns the VPLs with weight. */
static uint32_t rsm_build_pyramid(Rsm *rsm) {
    const uint32_t size = rsm->size;
    uint32_t count = 0;
    for (uint32_t k = 0; k < size * size; ++k) {
        SpheraVsglTexel *t = &rsm->texels[k];
        if (!rsm->valid[k] || !sphera_vsgl_texel_from_vpl(&rsm->vpls[k], rsm->origin, t))
            memset(t, 0, sizeof *t);
        if (t->weight > 0.0f) ++count;
    }
    size_t below = 0, offset = (size_t)size * size;
    for (uint32_t side = size / 2; side >= 1; side /= 2) {
        uint32_t child = 2 * side;
        for (uint32_t y = 0; y < side; ++y)
            for (uint32_t x = 0; x < side; ++x) {
                const SpheraVsglTexel *c[4] = {
                    &rsm->texels[below + (2 * y) * child + 2 * x],
                    &rsm->texels[below + (2 * y) * child + 2 * x + 1],
                    &rsm->texels[below + (2 * y + 1) * child + 2 * x],
                    &rsm->texels[below + (2 * y + 1) * child + 2 * x + 1]};
                SpheraVsglTexel *t = &rsm->texels[offset + y * side + x];
                memset(t, 0, sizeof *t);
                for (int q = 0; q < 4; ++q) {
#define ADD3(field)                                                                           \
    t->field.x += c[q]->field.x;                                                              \
    t->field.y += c[q]->field.y;                                                              \
    t->field.z += c[q]->field.z
                    ADD3(diffuse_power);
                    ADD3(specular_power);
                    ADD3(diffuse_direction);
                    ADD3(specular_direction);
                    ADD3(position);
#undef ADD3
                    t->squared_distance += c[q]->squared_distance;
                    t->weight += c[q]->weight;
                }
            }
        below = offset;
        offset += (size_t)side * side;
    }
    return count;
}

/* ---- clustering ------------------------------------------------------------------ */

static float radical_inverse2(uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
    i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
    i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
    return (float)(i >> 8) * 0x1p-24f;
}

/* FIS: cluster i from the shifted Hammersley point ((i + ξ0)/N, frac(φ2(i) + ξ1)). */
static void cluster_fis(const Rsm *rsm, const IndirectSettings *s, uint64_t *state,
                        SpheraVsgl *vsgls, float *points) {
    float xi0 = uniform(state), xi1 = uniform(state);
    uint32_t n = s->cluster_count;
    for (uint32_t i = 0; i < n; ++i) {
        float u0 = ((float)i + xi0) / (float)n;
        float u1 = radical_inverse2(i) + xi1;
        if (u1 >= 1.0f) u1 -= 1.0f;
        if (points) {
            points[2 * i] = u0;
            points[2 * i + 1] = u1;
        }
        vsgls[i] = sphera_vsgl_fis_select(rsm->texels, rsm->texel_count, rsm->size, rsm->origin,
                                          n, s->kernel_scale, s->iterations, u0, u1);
    }
}

/* k-means of Section 5 (one assignment pass, as tools/src/measurements/vsgl_kmeans.rs): N centres
 * drawn among the texels in proportion to their weight (with replacement), every texel
 * with weight assigned to the nearest centre in
 * d² = |x_a − x_b|²/h_image² + |y_a − y_b|²/h_world², h_image = 1/√N,
 * h_world = world_extent/√N (brute force), each cluster summed about its centre. */
static bool cluster_kmeans(const Rsm *rsm, const IndirectSettings *s, uint64_t *state,
                           SpheraVsgl *vsgls, uint32_t *assignment) {
    const uint32_t size = rsm->size, m = size * size, n = s->cluster_count;
    double *cumulative = malloc(sizeof(double) * m);
    uint32_t *centres = malloc(sizeof(uint32_t) * n);
    SpheraVsglAccumulator *acc = malloc(sizeof(SpheraVsglAccumulator) * n);
    float *cx = malloc(sizeof(float) * 5 * n);
    if (!cumulative || !centres || !acc || !cx) {
        free(cumulative);
        free(centres);
        free(acc);
        free(cx);
        return false;
    }
    double running = 0.0;
    for (uint32_t k = 0; k < m; ++k) {
        float w = rsm->texels[k].weight;
        running += w > 0.0f ? (double)w : 0.0;
        cumulative[k] = running;
    }
    const float inv_image2 = (float)n, inv_world2 = (float)n / (s->world_extent * s->world_extent);
    for (uint32_t i = 0; i < n; ++i) {
        double target = (double)uniform(state) * running;
        uint32_t lo = 0, hi = m; /* the first k with cumulative[k] > target */
        while (lo < hi) {
            uint32_t mid = (lo + hi) / 2;
            if (cumulative[mid] <= target) lo = mid + 1;
            else hi = mid;
        }
        uint32_t c = lo < m ? lo : m - 1;
        while (c > 0 && !(rsm->texels[c].weight > 0.0f)) --c;
        centres[i] = c;
        const SpheraVpl *v = &rsm->vpls[c];
        cx[5 * i + 0] = ((float)(c % size) + 0.5f) / (float)size;
        cx[5 * i + 1] = ((float)(c / size) + 0.5f) / (float)size;
        cx[5 * i + 2] = v->position.x;
        cx[5 * i + 3] = v->position.y;
        cx[5 * i + 4] = v->position.z;
        sphera_vsgl_accumulator_new(&acc[i], v->position);
    }
    if (running > 0.0)
        for (uint32_t k = 0; k < m; ++k) {
            if (!(rsm->texels[k].weight > 0.0f)) continue;
            const SpheraVpl *v = &rsm->vpls[k];
            float ix = ((float)(k % size) + 0.5f) / (float)size;
            float iy = ((float)(k / size) + 0.5f) / (float)size;
            float best = INFINITY;
            uint32_t best_i = 0;
            for (uint32_t i = 0; i < n; ++i) {
                const float *c = &cx[5 * i];
                float dx = ix - c[0], dy = iy - c[1];
                float wx = v->position.x - c[2], wy = v->position.y - c[3],
                      wz = v->position.z - c[4];
                float d = (dx * dx + dy * dy) * inv_image2 +
                          (wx * wx + wy * wy + wz * wz) * inv_world2;
                if (d < best) {
                    best = d;
                    best_i = i;
                }
            }
            sphera_vsgl_accumulator_add_vpl(&acc[best_i], v);
            if (assignment) assignment[k] = best_i;
        }
    for (uint32_t i = 0; i < n; ++i) vsgls[i] = sphera_vsgl_accumulator_finish(&acc[i]);
    free(cumulative);
    free(centres);
    free(acc);
    free(cx);
    return true;
}

/* ---- shading --------------------------------------------------------------------- */

typedef struct ShadeJob {
    const Scene *scene;
    const CameraHit *hits;
    const SpheraVsgl *vsgls;
    uint32_t count, width;
    float *image;
    /* Diagnosis (VARIANT_*): */
    uint32_t variant;
    const Rsm *rsm;
    const IndirectSettings *settings;
    const float *fis_points;      /* FIS: the 2D point of each cluster */
    const uint32_t *assignment;   /* k-means: the cluster of each texel */
} ShadeJob;

/* A camera hit's SG shading points (sphera_sg_shading_point_prepare): what the diffuse and
 * specular terms need that does not depend on the lobe, prepared once per hit and shared by
 * every VSGL. Schlick's f0 is per point: one point per distinct RGB channel of F0 (`of[c]` is
 * the point of channel c). */
typedef struct {
    SpheraSgShadingPoint points[3];
    uint32_t count; /* points prepared, 1 to 3 */
    uint32_t of[3];
} HitShading;

static void hit_shading_prepare(HitShading *h, SpheraVec3 n, SpheraVec3 view, const Material *m) {
    const float f0[3] = {m->specular.x, m->specular.y, m->specular.z};
    float value[3] = {0.0f, 0.0f, 0.0f};
    h->count = 0;
    for (uint32_t c = 0; c < 3; ++c) {
        uint32_t k = 0;
        while (k < h->count && value[k] != f0[c]) ++k;
        h->of[c] = k;
        if (k == h->count) {
            /* A point that cannot be prepared is the empty one, which shades to zeros, as
             * the free functions do for such a normal or view. */
            (void)sphera_sg_shading_point_prepare(&h->points[k], n, view, m->roughness, f0[c]);
            value[k] = f0[c];
            ++h->count;
        }
    }
}

/* The diffuse term (R_d = 1, V = 1; the same at every point) and the GGX layer's specular
 * term per RGB channel of one incoming-radiance SG: bit for bit
 * sphera_sg_diffuse_shading_constant_cosine and sphera_sg_specular_shading at the hit. */
static float shade_rgb(const HitShading *h, SpheraSg incoming, float3 *specular) {
    SpheraSgShading s[3];
    for (uint32_t k = 0; k < h->count; ++k)
        s[k] = sphera_sg_shading_point_shade(&h->points[k], incoming, 1.0f, 1.0f);
    *specular = f3(s[h->of[0]].specular, s[h->of[1]].specular, s[h->of[2]].specular);
    return s[0].diffuse;
}

/* VARIANT_RECEIVER_QUADRATURE: ∫ L_in(ω) f(wo, ω) max(ω·n, 0) dω for the incoming SG
 * `L_in = a G(ω, ξ, λ)` as a A(λ) E[f cos] over 8 × 8 stratified vMF samples. */
static float3 receiver_quadrature(SpheraSg incoming, const CameraHit *hit, const Material *m) {
    if (!(incoming.log_amplitude > -1e29f)) return f3(0, 0, 0);
    float3 sum = f3(0, 0, 0);
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
            SpheraSample s = sphera_vmf_sample(incoming, (i + 0.5f) / 8.0f, (j + 0.5f) / 8.0f);
            if (!(s.pdf > 0.0f)) continue;
            SpheraVec3 wi = frame_to_local(&hit->frame, fv(s.dir));
            if (!(wi.z > 0.0f)) continue;
            sum = f3_add(sum, f3_scale(material_eval(m, hit->wo, wi), wi.z));
        }
    float scale = expf(incoming.log_amplitude) * sphera_sg_integral(incoming.sharpness) / 64.0f;
    return f3_scale(sum, scale);
}

/* The radiance at a camera hit from all VSGLs: per VSGL and per lobe (diffuse, specular
 * emission), L_in of Eq. 6-7 for unit power, constant-cosine diffuse and ASG specular
 * shading, times the lobe's RGB power; V from one shadow ray to the VSGL's mean, traced
 * only when the unshadowed term is positive. */
static float3 shade_vsgls(const Scene *scene, struct RTCIntersectContext *rtc,
                          const CameraHit *hit, const SpheraVsgl *vsgls, uint32_t count,
                          uint32_t variant, const float *visibility) {
    const Material *m = &scene->materials[hit->material];
    SpheraVec3 n = hit->frame.normal;
    SpheraVec3 view = sv(frame_to_world(&hit->frame, hit->wo));
    bool glossy = m->roughness > 0.0f;
    HitShading shading;
    if (glossy) hit_shading_prepare(&shading, n, view, m);
    float3 sum = f3(0, 0, 0);
    for (uint32_t v = 0; v < count; ++v) {
        const SpheraVsgl *g = &vsgls[v];
        float3 mean = fv(g->mean);
        SpheraVec3 offset = sv(f3_sub(mean, hit->position));
        float variance = variant & VARIANT_POINT ? 0.0f : g->variance;
        float3 value = f3(0, 0, 0);
        for (int lobe = 0; lobe < 2; ++lobe) {
            float3 power = fv(lobe ? g->specular_power : g->diffuse_power);
            if (!(lum(power) > 0.0f)) continue;
            SpheraSg incoming =
                sphera_sg_incoming_radiance(lobe ? g->specular : g->diffuse, offset, variance);
            float3 r;
            if (variant & VARIANT_RECEIVER_QUADRATURE) {
                r = receiver_quadrature(incoming, hit, m);
            } else {
                if (glossy) {
                    float3 specular;
                    r = f3_scale(m->diffuse, shade_rgb(&shading, incoming, &specular));
                    r = f3_add(r, specular);
                } else {
                    /* No GGX layer: the diffuse term alone, which needs no prepared point. */
                    float d = sphera_sg_diffuse_shading_constant_cosine(incoming, n, 1.0f, 1.0f);
                    r = f3_scale(m->diffuse, d);
                }
            }
            value = f3_add(value, f3_mul(power, r));
        }
        if (!(lum(value) > 0.0f)) continue;
        if (visibility) value = f3_scale(value, visibility[v]);
        else if (!(variant & VARIANT_UNSHADOWED) && !segment_free(scene, rtc, hit->origin, mean))
            continue;
        sum = f3_add(sum, value);
    }
    return sum;
}

/* Diagnosis (`--technique vpl`): every VPL as a point light with the exact BRDFs at
 * both ends, Φ f_y(ω', ω) cos_y f_x cos_x / d² V (instant radiosity, unclamped): the
 * RSM's own discretisation error, without the VSGL approximations. */
static float3 shade_vpls(const Scene *scene, struct RTCIntersectContext *rtc,
                         const CameraHit *hit, const Rsm *rsm, uint32_t variant) {
    const Material *m = &scene->materials[hit->material];
    float3 sum = f3(0, 0, 0);
    for (uint32_t k = 0; k < rsm->size * rsm->size; ++k) {
        if (!rsm->valid[k]) continue;
        const SpheraVpl *vpl = &rsm->vpls[k];
        float3 d = f3_sub(fv(vpl->position), hit->position);
        float d2 = f3_dot(d, d);
        if (!(d2 > 1e-8f)) continue;
        float3 l = f3_scale(d, 1.0f / sqrtf(d2));
        SpheraVec3 wi = frame_to_local(&hit->frame, l);
        float3 fx = material_eval(m, hit->wo, wi);
        if (!(lum(fx) > 0.0f)) continue;
        SpheraFrame frame;
        if (!sphera_frame_from_normal(&frame, vpl->normal)) continue;
        const Material *my = &scene->materials[rsm->material[k]];
        SpheraVec3 out = frame_to_local(&frame, f3_scale(l, -1.0f));
        float3 emitted; /* the VPL's radiant intensity towards the shading point */
        if (variant & VARIANT_SG_EMISSION) {
            /* Eq. 1 and 2: Φ∘R_d G_d/A_d + Φ∘R_s G_s/A_s. */
            SpheraVec3 toward = sv(f3_scale(l, -1.0f));
            float gd = sphera_sg_eval(sphera_sg_from_lambert(vpl->normal), toward);
            float gs = sphera_sg_eval(
                sphera_sg_from_ggx(vpl->normal, vpl->toward_incoming, vpl->roughness),
                toward);
            emitted = f3_mul(fv(vpl->power), f3_add(f3_scale(fv(vpl->diffuse_reflectance), gd),
                                                    f3_scale(fv(vpl->specular_reflectance), gs)));
        } else {
            float3 fy =
                material_eval(my, frame_to_local(&frame, fv(vpl->toward_incoming)), out);
            emitted = f3_scale(f3_mul(fy, fv(vpl->power)), out.z);
        }
        if (!(lum(emitted) > 0.0f)) continue;
        float3 value = f3_scale(f3_mul(fx, emitted), wi.z / d2);
        if (!(variant & VARIANT_UNSHADOWED) &&
            !segment_free(scene, rtc, hit->origin, fv(vpl->position)))
            continue;
        sum = f3_add(sum, value);
    }
    return sum;
}

typedef struct VplJob {
    const Scene *scene;
    const CameraHit *hits;
    const Rsm *rsm;
    uint32_t width;
    float *image;
    uint32_t variant;
    const SpheraVsgl *vsgls; /* VARIANT_VSGL_PER_VPL: one VSGL per VPL */
    uint32_t vsgl_count;
} VplJob;

static void vpl_row(void *context, struct RTCIntersectContext *rtc, uint32_t y) {
    VplJob *job = context;
    for (uint32_t x = 0; x < job->width; ++x) {
        uint32_t pixel = y * job->width + x;
        const CameraHit *hit = &job->hits[pixel];
        float3 value = f3(0, 0, 0);
        if (hit->valid && job->vsgls)
            value = shade_vsgls(job->scene, rtc, hit, job->vsgls, job->vsgl_count, job->variant,
                                NULL);
        else if (hit->valid)
            value = shade_vpls(job->scene, rtc, hit, job->rsm, job->variant);
        job->image[3 * pixel + 0] = value.x;
        job->image[3 * pixel + 1] = value.y;
        job->image[3 * pixel + 2] = value.z;
    }
}

/* VARIANT_CLUSTER_VISIBILITY: the visible share of each cluster's luminance from `hit`,
 * `Σ_t m_it w_t V(hit, y_t) / Σ_t m_it w_t` with the membership m_it of texel t in
 * cluster i. k-means: m = 1 for the assigned cluster. FIS: the same draw on a pyramid
 * whose texels keep their weight (so the same position, level and weight) and carry
 * (w V, w, 0) as diffuse power; `scratch` holds that pyramid. */
static void cluster_visibility(const ShadeJob *job, struct RTCIntersectContext *rtc,
                               const CameraHit *hit, SpheraVsglTexel *scratch, double *num,
                               double *den, float *visibility) {
    const Rsm *rsm = job->rsm;
    const uint32_t size = rsm->size, m = size * size, n = job->count;
    bool fis = job->fis_points != NULL;
    if (!fis)
        for (uint32_t i = 0; i < n; ++i) num[i] = den[i] = 0.0;
    for (uint32_t k = 0; k < m; ++k) {
        float w = rsm->texels[k].weight;
        float v = 0.0f;
        if (w > 0.0f) v = segment_free(job->scene, rtc, hit->origin, fv(rsm->vpls[k].position));
        if (fis) {
            memset(&scratch[k], 0, sizeof scratch[k]);
            scratch[k].weight = w > 0.0f ? w : 0.0f;
            scratch[k].diffuse_power.x = scratch[k].weight * v;
            scratch[k].diffuse_power.y = scratch[k].weight;
        } else if (w > 0.0f) {
            num[job->assignment[k]] += (double)w * v;
            den[job->assignment[k]] += (double)w;
        }
    }
    if (fis) {
        size_t below = 0, offset = m;
        for (uint32_t side = size / 2; side >= 1; side /= 2) {
            uint32_t child = 2 * side;
            for (uint32_t y = 0; y < side; ++y)
                for (uint32_t x = 0; x < side; ++x) {
                    SpheraVsglTexel *t = &scratch[offset + y * side + x];
                    memset(t, 0, sizeof *t);
                    for (uint32_t q = 0; q < 4; ++q) {
                        const SpheraVsglTexel *c =
                            &scratch[below + (2 * y + q / 2) * child + 2 * x + q % 2];
                        t->weight += c->weight;
                        t->diffuse_power.x += c->diffuse_power.x;
                        t->diffuse_power.y += c->diffuse_power.y;
                    }
                }
            below = offset;
            offset += (size_t)side * side;
        }
        for (uint32_t i = 0; i < n; ++i) {
            SpheraVsgl g = sphera_vsgl_fis_select(
                scratch, rsm->texel_count, size, rsm->origin, n, job->settings->kernel_scale,
                job->settings->iterations, job->fis_points[2 * i], job->fis_points[2 * i + 1]);
            num[i] = g.diffuse_power.x;
            den[i] = g.diffuse_power.y;
        }
    }
    for (uint32_t i = 0; i < n; ++i) visibility[i] = den[i] > 0.0 ? (float)(num[i] / den[i]) : 0.0f;
}

/* VARIANT_EXACT_LOBES (k-means): Σ_i I_i(ω_i) f(wo, ω_i) cos / d_i², each cluster i a
 * point light at its mean whose intensity toward the shading point is the sum of its
 * VPLs' SG lobes, Φ∘(R_d G_d/A_d + R_s G_s/A_s) (Eq. 1, 2), unshadowed. `emitted` holds
 * one RGB value per cluster. */
static float3 shade_exact_lobes(const ShadeJob *job, const CameraHit *hit, float3 *emitted) {
    const Rsm *rsm = job->rsm;
    const uint32_t m = rsm->size * rsm->size, n = job->count;
    const Material *mat = &job->scene->materials[hit->material];
    for (uint32_t i = 0; i < n; ++i) emitted[i] = f3(0, 0, 0);
    for (uint32_t k = 0; k < m; ++k) {
        if (!(rsm->texels[k].weight > 0.0f)) continue;
        uint32_t i = job->assignment[k];
        const SpheraVpl *vpl = &rsm->vpls[k];
        float3 out = f3_sub(hit->position, fv(job->vsgls[i].mean));
        float length = f3_length(out);
        if (!(length > 0.0f)) continue;
        SpheraVec3 toward = sv(f3_scale(out, 1.0f / length));
        float gd = sphera_sg_eval(sphera_sg_from_lambert(vpl->normal), toward);
        float gs = sphera_sg_eval(
            sphera_sg_from_ggx(vpl->normal, vpl->toward_incoming, vpl->roughness), toward);
        emitted[i] = f3_add(emitted[i],
                            f3_mul(fv(vpl->power), f3_add(f3_scale(fv(vpl->diffuse_reflectance), gd),
                                                          f3_scale(fv(vpl->specular_reflectance), gs))));
    }
    float3 sum = f3(0, 0, 0);
    for (uint32_t i = 0; i < n; ++i) {
        float3 d = f3_sub(fv(job->vsgls[i].mean), hit->position);
        float d2 = f3_dot(d, d);
        if (!(d2 > 1e-8f) || !(lum(emitted[i]) > 0.0f)) continue;
        SpheraVec3 wi = frame_to_local(&hit->frame, f3_scale(d, 1.0f / sqrtf(d2)));
        float3 f = material_eval(mat, hit->wo, wi);
        sum = f3_add(sum, f3_scale(f3_mul(f, emitted[i]), wi.z / d2));
    }
    return sum;
}

static void shade_row(void *context, struct RTCIntersectContext *rtc, uint32_t y) {
    ShadeJob *job = context;
    SpheraVsglTexel *scratch = NULL;
    double *num = NULL, *den = NULL;
    float *visibility = NULL;
    if (job->variant & VARIANT_CLUSTER_VISIBILITY) {
        scratch = malloc(sizeof(SpheraVsglTexel) * job->rsm->texel_count);
        num = malloc(sizeof(double) * job->count);
        den = malloc(sizeof(double) * job->count);
        visibility = malloc(sizeof(float) * job->count);
        if (!scratch || !num || !den || !visibility) abort();
    }
    for (uint32_t x = 0; x < job->width; ++x) {
        uint32_t pixel = y * job->width + x;
        const CameraHit *hit = &job->hits[pixel];
        if (visibility && hit->valid) cluster_visibility(job, rtc, hit, scratch, num, den, visibility);
        float3 value = f3(0, 0, 0);
        if (hit->valid && (job->variant & VARIANT_EXACT_LOBES) && job->assignment) {
            float3 *emitted = malloc(sizeof(float3) * job->count);
            if (!emitted) abort();
            value = shade_exact_lobes(job, hit, emitted);
            free(emitted);
        } else if (hit->valid)
            value = shade_vsgls(job->scene, rtc, hit, job->vsgls, job->count, job->variant,
                                visibility);
        job->image[3 * pixel + 0] = value.x;
        job->image[3 * pixel + 1] = value.y;
        job->image[3 * pixel + 2] = value.z;
    }
    free(scratch);
    free(num);
    free(den);
    free(visibility);
}

/* ---- frames ---------------------------------------------------------------------- */

bool indirect_render_vsgl(const Scene *scene, const SpotLight *spot,
                          const IndirectSettings *s, const float *reference,
                          IndirectResult *result) {
    memset(result, 0, sizeof *result);
    const size_t pixels = (size_t)s->width * s->height;
    const uint32_t frames = s->frames ? s->frames : 1;
    const uint32_t threads = s->threads ? s->threads : core_count();
    CameraHit *hits = malloc(sizeof(CameraHit) * pixels);
    SpheraVsgl *vsgls = malloc(sizeof(SpheraVsgl) * (s->cluster_count ? s->cluster_count : 1));
    /* Diagnosis only: the FIS points, the k-means assignment, the per-VPL VSGLs. */
    float *fis_points = malloc(sizeof(float) * 2 * (s->cluster_count ? s->cluster_count : 1));
    uint32_t *assignment = calloc((size_t)s->rsm_size * s->rsm_size, sizeof(uint32_t));
    SpheraVsgl *per_vpl = NULL;
    float *image = malloc(sizeof(float) * 3 * pixels);
    Rsm rsm;
    /* The pyramid's reference point: the room's centre. */
    bool ok = hits && vsgls && image && fis_points && assignment && s->cluster_count > 0 &&
              rsm_alloc(&rsm, s->rsm_size, f3(0.0f, 1.5f, 0.0f));
    if (!ok) {
        fprintf(stderr, "sphera-trace: indirect: bad settings or out of memory\n");
        free(hits);
        free(vsgls);
        free(image);
        free(fis_points);
        free(assignment);
        return false;
    }
    enable_flush_to_zero();
    trace_camera(scene, s->width, s->height, hits);
    uint64_t state = s->seed * 0x9E3779B97F4A7C15ull + 0x1234567ull;
    double rmse_sum = 0.0, relmse_sum = 0.0, ratio_sum = 0.0;
    for (uint32_t frame = 0; frame < frames; ++frame) {
        double t0 = now_ms();
        rsm_trace(scene, spot, &rsm);
        double t1 = now_ms();
        result->vpl_count = rsm_build_pyramid(&rsm);
        memset(result->rsm_flux, 0, sizeof result->rsm_flux);
        for (uint32_t k = 0; k < s->rsm_size * s->rsm_size; ++k)
            if (rsm.valid[k]) {
                result->rsm_flux[0] += rsm.vpls[k].power.x;
                result->rsm_flux[1] += rsm.vpls[k].power.y;
                result->rsm_flux[2] += rsm.vpls[k].power.z;
            }
        if (s->clustering == CLUSTERING_FIS) cluster_fis(&rsm, s, &state, vsgls, fis_points);
        else if (s->clustering == CLUSTERING_KMEANS) {
            if (!cluster_kmeans(&rsm, s, &state, vsgls, assignment)) ok = false;
        } else
            memset(vsgls, 0, sizeof(SpheraVsgl) * s->cluster_count);
        double t2 = now_ms();
        if (s->clustering == CLUSTERING_VPLS) {
            VplJob job = {scene, hits, &rsm, s->width, image, s->variant, NULL, 0};
            if (s->variant & VARIANT_VSGL_PER_VPL) {
                /* Each VPL its own VSGL (σ² = 0), about its own position. */
                free(per_vpl);
                per_vpl = malloc(sizeof(SpheraVsgl) * s->rsm_size * s->rsm_size);
                if (!per_vpl) abort();
                uint32_t count = 0;
                for (uint32_t k = 0; k < s->rsm_size * s->rsm_size; ++k) {
                    if (!rsm.valid[k]) continue;
                    SpheraVsglAccumulator a;
                    sphera_vsgl_accumulator_new(&a, rsm.vpls[k].position);
                    if (sphera_vsgl_accumulator_add_vpl(&a, &rsm.vpls[k]))
                        per_vpl[count++] = sphera_vsgl_accumulator_finish(&a);
                }
                job.vsgls = per_vpl;
                job.vsgl_count = count;
            }
            for_each_row(threads, s->height, vpl_row, &job);
        } else {
            ShadeJob job = {scene, hits, vsgls, s->cluster_count, s->width, image,
                            s->variant, &rsm, s,
                            s->clustering == CLUSTERING_FIS ? fis_points : NULL,
                            s->clustering == CLUSTERING_KMEANS ? assignment : NULL};
            for_each_row(threads, s->height, shade_row, &job);
        }
        double t3 = now_ms();
        result->ms_rsm += t1 - t0;
        result->ms_clustering += t2 - t1;
        result->ms_shading += t3 - t2;
        if (reference) {
            double rmse, relmse, a = 0.0, b = 0.0;
            image_error(image, reference, s->width, s->height, &rmse, &relmse);
            for (size_t i = 0; i < 3 * pixels; ++i) {
                a += image[i];
                b += reference[i];
            }
            rmse_sum += rmse;
            relmse_sum += relmse;
            ratio_sum += b > 0.0 ? a / b : 0.0;
        }
    }
    result->frames = frames;
    result->ms_rsm /= frames;
    result->ms_clustering /= frames;
    result->ms_shading /= frames;
    result->ms_per_frame = result->ms_rsm + result->ms_clustering + result->ms_shading;
    result->rmse = rmse_sum / frames;
    result->relmse = relmse_sum / frames;
    result->mean_ratio = ratio_sum / frames;
    result->rsm_luminance = rsm.texels[rsm.texel_count - 1].weight;
    for (uint32_t i = 0; i < s->cluster_count; ++i) {
        double l = lum(f3_add(fv(vsgls[i].diffuse_power), fv(vsgls[i].specular_power)));
        result->cluster_luminance += l;
        if (!(l > 0.0)) ++result->empty_clusters;
    }
    for (size_t i = 0; i < 3 * pixels; ++i) result->mean[i % 3] += image[i];
    for (int c = 0; c < 3; ++c) result->mean[c] /= (double)pixels;
    result->image = image;
    rsm_free(&rsm);
    free(hits);
    free(vsgls);
    free(fis_points);
    free(assignment);
    free(per_vpl);
    return ok;
}

/* ---- the command line ------------------------------------------------------------ */

static bool parse_u32(const char *text, uint32_t *out) {
    char *end;
    unsigned long v = strtoul(text, &end, 10);
    if (*text == '\0' || *end != '\0' || v > 100000000ul) return false;
    *out = (uint32_t)v;
    return true;
}

/* `--variant a,b,...` (diagnosis): unshadowed, sg-emission, vsgl-per-vpl, point,
 * cluster-visibility, receiver-quadrature, exact-lobes, or none. */
static bool parse_variant(const char *text, uint32_t *out) {
    static const struct {
        const char *name;
        uint32_t bit;
    } names[] = {{"none", 0},
                 {"unshadowed", VARIANT_UNSHADOWED},
                 {"sg-emission", VARIANT_SG_EMISSION},
                 {"vsgl-per-vpl", VARIANT_VSGL_PER_VPL},
                 {"point", VARIANT_POINT},
                 {"cluster-visibility", VARIANT_CLUSTER_VISIBILITY},
                 {"receiver-quadrature", VARIANT_RECEIVER_QUADRATURE},
                 {"exact-lobes", VARIANT_EXACT_LOBES}};
    *out = 0;
    while (*text) {
        size_t length = strcspn(text, ",");
        bool found = false;
        for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
            if (strlen(names[i].name) == length && strncmp(text, names[i].name, length) == 0) {
                *out |= names[i].bit;
                found = true;
            }
        if (!found) return false;
        text += length;
        if (*text == ',') ++text;
    }
    return true;
}

int indirect_main(int argc, char **argv) {
    IndirectSettings s;
    memset(&s, 0, sizeof s);
    s.width = 128;
    s.height = 96;
    s.rsm_size = 64;
    s.cluster_count = 256;
    s.clustering = CLUSTERING_FIS;
    s.frames = 1;
    s.seed = 1;
    s.kernel_scale = 1.0f;
    s.iterations = 8;
    s.world_extent = 6.0f;
    const char *technique = "fis", *reference_path = NULL, *pfm = NULL, *png = NULL;
    uint32_t spp = 256, seed = 1;
    float exposure = 0.0f;
    bool ok = true, help = false;
    for (int i = 1; i < argc && ok; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--quiet") == 0) continue;
        if (strcmp(a, "--help") == 0) {
            help = true;
            break;
        }
        if (!v) {
            ok = false;
            break;
        }
        if (strcmp(a, "--scene") == 0) ok = strcmp(v, "indirect") == 0;
        else if (strcmp(a, "--technique") == 0 || strcmp(a, "--clustering") == 0) technique = v;
        else if (strcmp(a, "--width") == 0) ok = parse_u32(v, &s.width) && s.width > 0;
        else if (strcmp(a, "--height") == 0) ok = parse_u32(v, &s.height) && s.height > 0;
        else if (strcmp(a, "--clusters") == 0)
            ok = parse_u32(v, &s.cluster_count) && s.cluster_count > 0;
        else if (strcmp(a, "--rsm-size") == 0)
            ok = parse_u32(v, &s.rsm_size) && sphera_vsgl_pyramid_texel_count(s.rsm_size) > 0;
        else if (strcmp(a, "--frames") == 0) ok = parse_u32(v, &s.frames) && s.frames > 0;
        else if (strcmp(a, "--spp") == 0) ok = parse_u32(v, &spp) && spp > 0;
        else if (strcmp(a, "--threads") == 0) ok = parse_u32(v, &s.threads);
        else if (strcmp(a, "--seed") == 0) ok = parse_u32(v, &seed);
        else if (strcmp(a, "--variant") == 0) ok = parse_variant(v, &s.variant);
        else if (strcmp(a, "--reference") == 0) reference_path = v;
        else if (strcmp(a, "--out-pfm") == 0) pfm = v;
        else if (strcmp(a, "--out-png") == 0) png = v;
        else if (strcmp(a, "--exposure") == 0) {
            double stops = 0.0;
            ok = parse_number(v, -64.0, 64.0, &stops);
            exposure = (float)stops;
        }
        else ok = false;
        if (!ok) fprintf(stderr, "sphera-trace: indirect: bad option or value: %s %s\n", a, v);
        ++i;
    }
    bool is_reference = strcmp(technique, "reference") == 0;
    if (strcmp(technique, "kmeans") == 0) s.clustering = CLUSTERING_KMEANS;
    else if (strcmp(technique, "vpl") == 0) s.clustering = CLUSTERING_VPLS;
    else if (!is_reference && strcmp(technique, "fis") != 0) {
        fprintf(stderr,
                "sphera-trace: indirect: technique must be fis, kmeans, vpl or reference\n");
        ok = false;
    }
    if (!ok || help) {
        fprintf(help ? stdout : stderr,
                "usage: sphera-trace --scene indirect [--technique fis|kmeans|vpl|reference]\n"
                "  [--clusters N] [--rsm-size S] [--frames F] [--spp P (reference)]\n"
                "  [--width W --height H] [--threads T] [--seed S] [--reference F.pfm]\n"
                "  [--out-pfm F] [--out-png F] [--exposure E] [--quiet]\n"
                "  [--variant V,...] diagnosis: unshadowed, sg-emission (vpl), vsgl-per-vpl\n"
                "    (vpl), point (fis/kmeans), cluster-visibility (fis/kmeans),\n"
                "    receiver-quadrature (VSGL shading by quadrature), exact-lobes (kmeans)\n");
        return help ? 0 : 2;
    }
    s.seed = seed;
    Scene scene;
    if (!scene_create(&scene, "indirect", (float)s.width / (float)s.height)) return 1;
    SpotLight spot = indirect_scene_spot();
    float *reference = NULL;
    if (reference_path) {
        uint32_t w, h;
        reference = read_pfm(reference_path, &w, &h);
        if (!reference || w != s.width || h != s.height) {
            fprintf(stderr, "sphera-trace: cannot use %s as a %u x %u reference\n",
                    reference_path, s.width, s.height);
            free(reference);
            scene_destroy(&scene);
            return 1;
        }
    }
    float *image = NULL;
    int status = 0;
    if (is_reference) {
        double ms;
        if (!indirect_render_reference(&scene, &spot, s.width, s.height, spp, s.threads, s.seed,
                                       &image, &ms))
            status = 1;
        else {
            double mean[3] = {0, 0, 0};
            for (size_t i = 0; i < 3 * (size_t)s.width * s.height; ++i) mean[i % 3] += image[i];
            double pixels = (double)s.width * s.height;
            printf("{\"scene\": \"indirect\", \"technique\": \"reference\", \"width\": %u, "
                   "\"height\": %u, \"spp\": %u, \"time_ms\": %.6g, "
                   "\"mean\": [%.9g, %.9g, %.9g]}\n",
                   s.width, s.height, spp, ms, mean[0] / pixels, mean[1] / pixels,
                   mean[2] / pixels);
        }
    } else {
        IndirectResult r;
        if (!indirect_render_vsgl(&scene, &spot, &s, reference, &r)) status = 1;
        image = r.image;
        if (status == 0) {
            printf("{\"scene\": \"indirect\", \"technique\": \"%s\", \"biased\": true, "
                   "\"width\": %u, \"height\": %u, \"clusters\": %u, \"rsm_size\": %u, "
                   "\"frames\": %u, \"ms_per_frame\": %.6g, \"ms_rsm\": %.6g, "
                   "\"ms_clustering\": %.6g, \"ms_shading\": %.6g, \"vpls\": %u, "
                   "\"rsm_luminance\": %.9g, \"cluster_luminance\": %.9g, "
                   "\"empty_clusters\": %u, \"mean\": [%.9g, %.9g, %.9g]",
                   technique, s.width, s.height, s.cluster_count, s.rsm_size, r.frames,
                   r.ms_per_frame, r.ms_rsm, r.ms_clustering, r.ms_shading, r.vpl_count,
                   r.rsm_luminance, r.cluster_luminance, r.empty_clusters, r.mean[0], r.mean[1],
                   r.mean[2]);
            if (reference) {
                printf(", \"rmse\": ");
                print_json_number(stdout, r.rmse);
                printf(", \"relmse\": ");
                print_json_number(stdout, r.relmse);
                printf(", \"mean_ratio\": ");
                print_json_number(stdout, r.mean_ratio);
            }
            printf("}\n");
        }
    }
    if (status == 0 && pfm && !write_pfm(pfm, image, s.width, s.height)) {
        fprintf(stderr, "sphera-trace: indirect: cannot write %s\n", pfm);
        status = 1;
    }
    if (status == 0 && png && !write_png(png, image, s.width, s.height, exposure)) {
        fprintf(stderr, "sphera-trace: indirect: cannot write %s\n", png);
        status = 1;
    }
    free(image);
    free(reference);
    scene_destroy(&scene);
    return status;
}
