/* Small 3-vector helpers for the tracer (header-only, C99). */
#ifndef SPHERA_TRACER_VEC3_H
#define SPHERA_TRACER_VEC3_H

#include <math.h>

/* π in single precision, for the whole tracer. */
#define PI_F 3.14159265358979f

typedef struct float3 {
    float x, y, z;
} float3;

static inline float3 f3(float x, float y, float z) {
    float3 r = {x, y, z};
    return r;
}
static inline float3 f3_add(float3 a, float3 b) { return f3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline float3 f3_sub(float3 a, float3 b) { return f3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline float3 f3_mul(float3 a, float3 b) { return f3(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline float3 f3_scale(float3 a, float s) { return f3(a.x * s, a.y * s, a.z * s); }
static inline float f3_dot(float3 a, float3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline float3 f3_cross(float3 a, float3 b) {
    return f3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline float f3_length(float3 a) { return sqrtf(f3_dot(a, a)); }
static inline float3 f3_normalize(float3 a) { return f3_scale(a, 1.0f / f3_length(a)); }
static inline float f3_max_component(float3 a) {
    float m = a.x > a.y ? a.x : a.y;
    return m > a.z ? m : a.z;
}

#endif
