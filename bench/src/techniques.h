/* Dispatch over libsphera's polygon light samplers. */
#ifndef SPHERA_TRACER_TECHNIQUES_H
#define SPHERA_TRACER_TECHNIQUES_H

#include "tracer.h"

/* One prepared polygon for any technique (the reference technique uses two). */
typedef struct PreparedLight {
    union {
        SpheraTurkPolygon turk;
        SpheraArvoPolygon arvo;
        SpheraSolidAnglePolygon solid_angle;
        SpheraClippedSolidAnglePolygon clipped;
        SpheraHartBilinearPolygon bilinear;
        SpheraHartBiquadraticPolygon biquadratic;
        SpheraArvoProjectedPolygon arvo_projected;
        SpheraProjectedPolygon projected;
        SpheraPolygonLight polygon_light;
    } u;
    /* The reference technique on a GGX material: u.polygon_light (weighted balance);
     * on a Lambertian one: u.projected. */
    bool reference_glossy;
} PreparedLight;

/* The view direction (local frame) and the material at a shading point, for the
 * techniques that sample the BRDF. */
typedef struct ShadingPoint {
    SpheraVec3 wo;
    SpheraMaterial material;
} ShadingPoint;

/* Whether the technique draws two samples per light sample (one per technique, MIS). */
bool technique_is_pair(Technique technique);

/* The SPHERA_MIS_* heuristic of an LTC technique. */
uint32_t technique_heuristic(Technique technique);

/* Prepares the polygon (local frame, relative to the shading point); false if the
 * technique has nothing to sample (then no sample may be drawn). */
bool technique_prepare(Technique technique, PreparedLight *out, const SpheraVec3 *vertices,
                       uint32_t count, const ShadingPoint *point);

/* One sample (for the reference technique: its projected solid angle sample). */
SpheraSample technique_sample(Technique technique, const PreparedLight *prepared, float u0,
                              float u1);

#endif
