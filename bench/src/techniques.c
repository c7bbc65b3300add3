/* The light-sampling techniques of libsphera behind one switch: prepare a polygon given
 * in the local shading frame, then draw samples from it. */
#include <string.h>

#include "techniques.h"

const TechniqueInfo technique_info[TECHNIQUE_COUNT] = {
    {"turk", false, "Turk 1990: uniform on the polygon's area, pdf converted to solid angle"},
    {"arvo", false, "Arvo 1995: solid angle sampling of triangles, polygon as a fan"},
    {"solid_angle", false, "Peters 2021 (Algorithm 5): solid angle sampling of triangle fans"},
    {"clipped_solid_angle", false, "solid angle sampling of the polygon clipped to the horizon"},
    {"hart_bilinear", false, "Hart et al. 2020: solid angle sampling warped by a bilinear cosine fit"},
    {"hart_biquadratic", false,
     "Hart et al. 2020: solid angle sampling warped by a biquadratic cosine fit"},
    {"arvo_projected", false,
     "projected solid angle sampling by Newton steps on Arvo's sector areas (baseline)"},
    {"projected", false, "Peters 2021 (Algorithm 4): projected solid angle sampling"},
    {"projected_fast", true,
     "projected solid angle sampling with approximate sector areas and no refinement (biased)"},
    {"brdf_balance", false,
     "one BRDF sample (GGX visible normals or cosine) and one projected sample, balance heuristic"},
    {"brdf_power", false,
     "one BRDF sample and one projected sample, power heuristic"},
    {"ltc_weighted", false,
     "Peters 2021: one LTC and one projected sample, weighted balance heuristic"},
    {"ltc_clamped", false,
     "Peters 2021: one LTC and one projected sample, clamped optimal MIS (v = 1/2)"},
    {"ltc_optimal", false,
     "Peters 2021: one LTC and one projected sample, optimal MIS (v = 1/2)"},
    {"sphere_cap", false,
     "sphere lights: uniform sampling of the cap of directions the sphere covers"},
    {"sphere_cap_brdf", false,
     "sphere lights: one cap and one BRDF sample, balance heuristic"},
    {"sphere_sptd", false,
     "sphere lights: GGX layer by one SPTD light sample (Dupuy et al. 2017, Section 6.1) and one "
     "VNDF sample, balance heuristic; Lambert layer as in sphere_cap_brdf"},
    {"sphere_projected", false,
     "sphere lights: Lambert layer by one sample of the clamped cosine in the cap (an SPTD with "
     "the pivot at the origin, exact also where the cap crosses the horizon: issue 20, 2), "
     "zero variance where unoccluded; GGX layer as in sphere_sptd"},
    {"sphere_realtime", true,
     "sphere lights: GGX layer by SPTD shading (Dupuy et al. 2017, Eq. 19, biased) times the "
     "visibility of one shadow ray uniform in the cap above the horizon; Lambert layer as in "
     "sphere_cap"},
    {"sphere_occlusion", true,
     "sphere lights: GGX layer by specular occlusion with SPTDs (Dupuy et al. 2017, Eq. 23, "
     "biased) in a bent cone traced at the shading point (128 rays); Lambert layer as in "
     "sphere_cap"},
    {"sphere_occlusion_separable", true,
     "sphere lights: GGX layer by the separable specular occlusion of Eq. 21-22 (unoccluded "
     "SPTD shading times the lobe's fraction in the bent cone; biased), same bent cone; "
     "Lambert layer as in sphere_cap"},
    {"medium_pivot", false,
     "medium in-scattering from sphere lights: one sample of the pivot phase function fitted to "
     "HG (Eq. 27-28), restricted to the light's cap (Section 6.2); surfaces as sphere_cap_brdf"},
    {"medium_hg_cap", false,
     "medium in-scattering from sphere lights: one HG and one uniform cap sample, balance "
     "heuristic; surfaces as sphere_cap_brdf"},
    {"sphere_union", false,
     "two overlapping sphere lights of equal radiance as one: one sample uniform in the union of "
     "their caps (SpheraCapUnion, Dupuy et al. 2017 Sec. 4: sets of caps), pdf 1/Omega(A u B); "
     "other sphere lights as sphere_cap"},
    {"sphere_mixture", false,
     "two overlapping sphere lights of equal radiance as one: one light with probability 1/2, "
     "one sample uniform in its cap, pdf the mixture (pdf_A + pdf_B)/2 (baseline of "
     "sphere_union); other sphere lights as sphere_cap"},
    {"reference", false,
     "reference images: projected sampling on Lambertian surfaces, one projected and one LTC sample with the weighted balance heuristic on GGX ones; sphere lights as sphere_sptd, medium in-scattering as medium_hg_cap"},
};

int technique_from_name(const char *name) {
    for (int t = 0; t < TECHNIQUE_COUNT; ++t)
        if (strcmp(technique_info[t].name, name) == 0) return t;
    return -1;
}

bool technique_is_pair(Technique technique) {
    return technique >= TECHNIQUE_BRDF_BALANCE && technique <= TECHNIQUE_LTC_OPTIMAL;
}

uint32_t technique_heuristic(Technique technique) {
    switch (technique) {
    case TECHNIQUE_LTC_WEIGHTED: return SPHERA_MIS_WEIGHTED_BALANCE;
    case TECHNIQUE_LTC_OPTIMAL: return SPHERA_MIS_OPTIMAL;
    default: return SPHERA_MIS_CLAMPED_OPTIMAL;
    }
}

bool technique_prepare(Technique technique, PreparedLight *out, const SpheraVec3 *vertices,
                       uint32_t count, const ShadingPoint *point) {
    switch (technique) {
    case TECHNIQUE_BRDF_BALANCE:
    case TECHNIQUE_BRDF_POWER:
        return sphera_projected_polygon_prepare(&out->u.projected, vertices, count);
    case TECHNIQUE_LTC_WEIGHTED:
    case TECHNIQUE_LTC_CLAMPED:
    case TECHNIQUE_LTC_OPTIMAL:
        return sphera_polygon_light_prepare(&out->u.polygon_light, vertices, count, point->wo,
                                            &point->material, technique_heuristic(technique),
                                            0.5f);
    case TECHNIQUE_TURK: return sphera_turk_polygon_prepare(&out->u.turk, vertices, count);
    case TECHNIQUE_ARVO: return sphera_arvo_polygon_prepare(&out->u.arvo, vertices, count);
    case TECHNIQUE_SOLID_ANGLE:
        return sphera_solid_angle_polygon_prepare(&out->u.solid_angle, vertices, count);
    case TECHNIQUE_CLIPPED_SOLID_ANGLE:
        return sphera_clipped_solid_angle_polygon_prepare(&out->u.clipped, vertices, count);
    case TECHNIQUE_HART_BILINEAR:
        return sphera_hart_bilinear_polygon_prepare(&out->u.bilinear, vertices, count);
    case TECHNIQUE_HART_BIQUADRATIC:
        return sphera_hart_biquadratic_polygon_prepare(&out->u.biquadratic, vertices, count);
    case TECHNIQUE_ARVO_PROJECTED:
        return sphera_arvo_projected_polygon_prepare(&out->u.arvo_projected, vertices, count);
    case TECHNIQUE_PROJECTED:
    case TECHNIQUE_SPHERE_CAP:
    case TECHNIQUE_SPHERE_CAP_BRDF:
    case TECHNIQUE_SPHERE_SPTD:
    case TECHNIQUE_SPHERE_PROJECTED:
    case TECHNIQUE_SPHERE_REALTIME:
    case TECHNIQUE_SPHERE_OCCLUSION:
    case TECHNIQUE_SPHERE_OCCLUSION_SEPARABLE:
    case TECHNIQUE_MEDIUM_PIVOT:
    case TECHNIQUE_MEDIUM_HG_CAP:
    case TECHNIQUE_SPHERE_UNION:
    case TECHNIQUE_SPHERE_MIXTURE:
        return sphera_projected_polygon_prepare(&out->u.projected, vertices, count);
    case TECHNIQUE_PROJECTED_FAST:
        return sphera_projected_polygon_prepare_fast(&out->u.projected, vertices, count);
    case TECHNIQUE_REFERENCE: {
        /* Lambertian: projected sampling (zero variance where unoccluded). GGX: the
         * weighted balance heuristic over projected and LTC sampling, the estimator of
         * lowest variance here; its independence from the techniques under test is
         * not needed for an unbiased reference, and a bias of its own would show up in
         * the report's mean check against every other technique. */
        const SpheraVec3 f0 = point->material.f0;
        out->reference_glossy = f0.x > 0.0f || f0.y > 0.0f || f0.z > 0.0f;
        if (out->reference_glossy)
            return sphera_polygon_light_prepare(&out->u.polygon_light, vertices, count, point->wo,
                                                &point->material, SPHERA_MIS_WEIGHTED_BALANCE,
                                                0.5f);
        return sphera_projected_polygon_prepare(&out->u.projected, vertices, count);
    }
    case TECHNIQUE_COUNT: break;
    }
    return false;
}

SpheraSample technique_sample(Technique technique, const PreparedLight *p, float u0, float u1) {
    switch (technique) {
    case TECHNIQUE_TURK: return sphera_turk_polygon_sample(&p->u.turk, u0, u1);
    case TECHNIQUE_ARVO: return sphera_arvo_polygon_sample(&p->u.arvo, u0, u1);
    case TECHNIQUE_SOLID_ANGLE: return sphera_solid_angle_polygon_sample(&p->u.solid_angle, u0, u1);
    case TECHNIQUE_CLIPPED_SOLID_ANGLE:
        return sphera_clipped_solid_angle_polygon_sample(&p->u.clipped, u0, u1);
    case TECHNIQUE_HART_BILINEAR:
        return sphera_hart_bilinear_polygon_sample(&p->u.bilinear, u0, u1);
    case TECHNIQUE_HART_BIQUADRATIC:
        return sphera_hart_biquadratic_polygon_sample(&p->u.biquadratic, u0, u1);
    case TECHNIQUE_ARVO_PROJECTED:
        return sphera_arvo_projected_polygon_sample(&p->u.arvo_projected, u0, u1);
    case TECHNIQUE_PROJECTED:
    case TECHNIQUE_SPHERE_CAP:
    case TECHNIQUE_SPHERE_CAP_BRDF:
    case TECHNIQUE_SPHERE_SPTD:
    case TECHNIQUE_SPHERE_PROJECTED:
    case TECHNIQUE_SPHERE_REALTIME:
    case TECHNIQUE_SPHERE_OCCLUSION:
    case TECHNIQUE_SPHERE_OCCLUSION_SEPARABLE:
    case TECHNIQUE_MEDIUM_PIVOT:
    case TECHNIQUE_MEDIUM_HG_CAP:
    case TECHNIQUE_SPHERE_UNION:
    case TECHNIQUE_SPHERE_MIXTURE: return sphera_projected_polygon_sample(&p->u.projected, u0, u1);
    case TECHNIQUE_PROJECTED_FAST:
        return sphera_projected_polygon_sample_fast(&p->u.projected, u0, u1);
    case TECHNIQUE_BRDF_BALANCE:
    case TECHNIQUE_BRDF_POWER:
    case TECHNIQUE_LTC_WEIGHTED:
    case TECHNIQUE_LTC_CLAMPED:
    case TECHNIQUE_LTC_OPTIMAL:
    case TECHNIQUE_REFERENCE:
    case TECHNIQUE_COUNT: break;
    }
    SpheraSample none = {{0, 0, 0}, 0};
    return none;
}
