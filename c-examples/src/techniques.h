/* Dispatch over libsphera's polygon light samplers. */
#ifndef SPHERA_TRACER_TECHNIQUES_H
#define SPHERA_TRACER_TECHNIQUES_H

#include "tracer.h"

/* One prepared polygon for any technique (the reference technique uses two). */
typedef struct PreparedLight {
    union {
        SpheraTurkPolygon area;
        SpheraArvoPolygon arvo;
        SpheraSolidAnglePolygon solid_angle;
        SpheraClippedSolidAnglePolygon clipped;
        SpheraHartBilinearPolygon bilinear;
        SpheraHartBiquadraticPolygon biquadratic;
        SpheraArvoProjectedPolygon arvo_projected;
        SpheraProjectedSolidAnglePolygon projected;
    } u;
    SpheraSolidAnglePolygon reference_solid_angle;
} PreparedLight;

/* Prepares the polygon (local frame, relative to the shading point); false if the
 * technique has nothing to sample (then no sample may be drawn). */
bool technique_prepare(Technique technique, PreparedLight *out, const SpheraVec3 *vertices,
                       uint32_t count);

/* One sample (for the reference technique: its projected solid angle sample). */
SpheraSample technique_sample(Technique technique, const PreparedLight *prepared, float u0,
                              float u1);

#endif
