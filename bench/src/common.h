/* Helpers shared by the renderer (render.c) and the indirect-light scene (indirect.c):
 * timing, thread set-up, random numbers, the shading frame and Embree rays
 * (header-only, C99). */
#ifndef SPHERA_TRACER_COMMON_H
#define SPHERA_TRACER_COMMON_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#if defined(__SSE__) || defined(__x86_64__)
#include <pmmintrin.h>
#include <xmmintrin.h>
#define TRACER_SSE_CONTROL 1
#endif

#include <embree3/rtcore.h>

#include "sphera.h"
#include "vec3.h"

/* A command-line number: the whole of `text` a finite decimal number in [lo, hi]
 * (strtod; "nan", "inf", "1e300" outside the range, "abc", "" and "1x" are rejected, so
 * that a bad value is an error, never a silent 0 or a run without end). */
static inline bool parse_number(const char *text, double lo, double hi, double *out) {
    char *end;
    double v;
    if (!text || *text == '\0') return false;
    v = strtod(text, &end);
    if (*end != '\0' || !isfinite(v) || v < lo || v > hi) return false;
    *out = v;
    return true;
}

/* `v` as a JSON number, or `null` where it is not finite (JSON has no NaN or ∞). */
static inline void print_json_number(FILE *out, double v) {
    if (isfinite(v))
        fprintf(out, "%.9g", v);
    else
        fputs("null", out);
}

/* Milliseconds on the monotonic clock. */
static inline double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1e3 * (double)t.tv_sec + 1e-6 * (double)t.tv_nsec;
}

/* Embree asks for flush-to-zero and denormals-are-zero in every rendering thread. */
static inline void enable_flush_to_zero(void) {
#ifdef TRACER_SSE_CONTROL
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
#endif
}

/* The number of processors in /proc/cpuinfo (1 when it cannot be read). */
static inline uint32_t core_count(void) {
    FILE *f = fopen("/proc/cpuinfo", "r");
    uint32_t n = 0;
    char line[256];
    if (f) {
        while (fgets(line, sizeof line, f))
            if (strncmp(line, "processor", 9) == 0) ++n;
        fclose(f);
    }
    return n ? n : 1;
}

/* SplitMix64 (Steele et al. 2014): a fresh, well-mixed stream per pixel and pass. */
static inline uint64_t splitmix64(uint64_t *state) {
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* A local direction (z = normal) in world space. */
static inline float3 frame_to_world(const SpheraFrame *f, SpheraVec3 v) {
    return f3(f->tangent.x * v.x + f->bitangent.x * v.y + f->normal.x * v.z,
              f->tangent.y * v.x + f->bitangent.y * v.y + f->normal.y * v.z,
              f->tangent.z * v.x + f->bitangent.z * v.y + f->normal.z * v.z);
}

/* A world vector in the local frame. */
static inline SpheraVec3 frame_to_local(const SpheraFrame *f, float3 v) {
    SpheraVec3 r = {f->tangent.x * v.x + f->tangent.y * v.y + f->tangent.z * v.z,
                    f->bitangent.x * v.x + f->bitangent.y * v.y + f->bitangent.z * v.z,
                    f->normal.x * v.x + f->normal.y * v.y + f->normal.z * v.z};
    return r;
}

/* An Embree ray from `origin` along `dir` over [0, tfar], every mask bit set. */
static inline struct RTCRay make_ray(float3 origin, float3 dir, float tfar) {
    struct RTCRay ray;
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = dir.x;
    ray.dir_y = dir.y;
    ray.dir_z = dir.z;
    ray.tnear = 0.0f;
    ray.tfar = tfar;
    ray.time = 0.0f;
    ray.mask = (unsigned)-1;
    ray.id = 0;
    ray.flags = 0;
    return ray;
}

/* An Embree ray-hit query over [0, ∞) with no hit yet. */
static inline struct RTCRayHit make_ray_hit(float3 origin, float3 dir) {
    struct RTCRayHit rh;
    rh.ray = make_ray(origin, dir, INFINITY);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

#endif
