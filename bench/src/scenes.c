/* The built-in scenes and their Embree geometry. Every surface is a triangle of one
 * Embree mesh; lights are convex polygons that also enter the mesh (as fans) so that
 * camera rays see them and they occlude one another. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tracer.h"

const SceneInfo scene_info[] = {
    {"cornell", "the Cornell box (mm), its quad light under the ceiling"},
    {"polygons", "a room lit by a triangle, quad, pentagon, hexagon and heptagon, some tilted, "
                 "some crossing the horizon of the walls or the floor; GGX floor (roughness 0.55)"},
    {"hard", "a tiny distant light, a huge light just above the floor, a light edge-on to a wall"},
    {"floor", "one unoccluded quad light over a white Lambert floor (the zero-variance test)"},
    {"spheres", "sphere lights (small, large, near the floor, far and grazing, half sunk into "
                "the GGX floor) over a Lambert "
                "and a GGX floor"},
    {"indirect", "a room lit by a spot light (indirect.c) on a GGX floor, for one-bounce "
                 "indirect light (VSGLs against path tracing; render it with --scene indirect)"},
    {"glossy", "three GGX floor strips of roughness 0.1, 0.3 and 0.6 under a quad, a pentagon "
               "and a triangle light, with a wall casting shadows across them"},
    {"slab", "a thin slab of single-scattering medium (HG, g = 0.85) over part of a Lambert "
             "floor, lit by one sphere light behind it"},
    {"occlusion", "a GGX floor at the bottom of a round well, reflecting a sphere light that "
                  "the well's wall partly hides (specular occlusion, Dupuy et al. 2017 "
                  "Sec. 5.4)"},
    {"overlap", "two intersecting sphere lights of equal radiance over a Lambert and a GGX "
                "floor, whose caps overlap from every point (sphere_union against "
                "sphere_mixture)"},
};
const uint32_t scene_count = sizeof scene_info / sizeof scene_info[0];

/* ---- a growable triangle list ----------------------------------------------------- */

typedef struct Builder {
    float3 *positions; /* 3 per triangle */
    uint32_t *material;
    int32_t *light;
    uint32_t count, capacity;
    Scene *scene;
} Builder;

static bool builder_add_triangle(Builder *b, float3 p0, float3 p1, float3 p2, uint32_t material,
                                 int32_t light) {
    if (b->count == b->capacity) {
        uint32_t capacity = b->capacity ? 2 * b->capacity : 64;
        float3 *positions = realloc(b->positions, sizeof(float3) * 3 * capacity);
        if (positions) b->positions = positions;
        uint32_t *materials = realloc(b->material, sizeof(uint32_t) * capacity);
        if (materials) b->material = materials;
        int32_t *lights = realloc(b->light, sizeof(int32_t) * capacity);
        if (lights) b->light = lights;
        if (!positions || !materials || !lights) return false;
        b->capacity = capacity;
    }
    b->positions[3 * b->count + 0] = p0;
    b->positions[3 * b->count + 1] = p1;
    b->positions[3 * b->count + 2] = p2;
    b->material[b->count] = material;
    b->light[b->count] = light;
    b->count++;
    return true;
}

/* A planar convex polygon as a triangle fan. */
static bool add_polygon(Builder *b, const float3 *v, uint32_t n, uint32_t material,
                        int32_t light) {
    for (uint32_t i = 1; i + 1 < n; ++i)
        if (!builder_add_triangle(b, v[0], v[i], v[i + 1], material, light)) return false;
    return true;
}

static bool add_quad(Builder *b, float3 p0, float3 p1, float3 p2, float3 p3, uint32_t material) {
    float3 v[4] = {p0, p1, p2, p3};
    return add_polygon(b, v, 4, material, -1);
}

/* A box (without its bottom) standing on y = y0: base corners c0..c3, height h. */
static bool add_block(Builder *b, const float3 base[4], float height, uint32_t material) {
    float3 top[4];
    for (int i = 0; i < 4; ++i) top[i] = f3_add(base[i], f3(0, height, 0));
    bool ok = add_quad(b, top[0], top[1], top[2], top[3], material);
    for (int i = 0; i < 4; ++i) {
        int j = (i + 1) % 4;
        ok = ok && add_quad(b, base[i], base[j], top[j], top[i], material);
    }
    return ok;
}

/* An axis-aligned box with corners lo and hi, all six faces. */
static bool add_box(Builder *b, float3 lo, float3 hi, uint32_t material) {
    float3 base[4] = {f3(lo.x, lo.y, lo.z), f3(hi.x, lo.y, lo.z), f3(hi.x, lo.y, hi.z),
                      f3(lo.x, lo.y, hi.z)};
    return add_block(b, base, hi.y - lo.y, material) &&
           add_quad(b, base[0], base[1], base[2], base[3], material);
}

#define MAX_MATERIALS 16

/* Adds a material; past MAX_MATERIALS, surfaces get material 0 (black). */
static uint32_t add_material(Scene *s, float3 diffuse, float3 specular, float roughness) {
    Material m;
    if (s->material_count == MAX_MATERIALS) return 0;
    memset(&m, 0, sizeof m);
    m.diffuse = diffuse;
    m.specular = specular;
    m.roughness = roughness;
    SpheraVec3 f0 = {specular.x, specular.y, specular.z};
    sphera_ggx_brdf_prepare(&m.ggx, roughness, f0);
    s->materials[s->material_count] = m;
    return s->material_count++;
}

/* A light with the given vertices; its normal follows their winding
 * (counter-clockwise seen from the lit side). */
static bool add_light(Builder *b, const float3 *v, uint32_t n, float3 radiance) {
    Scene *s = b->scene;
    if (s->light_count == TRACER_MAX_LIGHTS || n < 3 || n > SPHERA_MAX_POLYGON_VERTICES)
        return false;
    Light *light = &s->lights[s->light_count];
    float3 normal = f3(0, 0, 0);
    for (uint32_t i = 1; i + 1 < n; ++i)
        normal = f3_add(normal, f3_cross(f3_sub(v[i], v[0]), f3_sub(v[i + 1], v[0])));
    light->normal = f3_normalize(normal);
    light->count = n;
    memcpy(light->vertices, v, sizeof(float3) * n);
    light->radiance = radiance;
    /* Lights are black where they do not emit (material 0 is black in every scene). */
    return add_polygon(b, v, n, 0, (int32_t)s->light_count++);
}

/* A sphere light; its surface enters the mesh as a UV sphere inscribed in it (so that
 * shadow rays that stop at the analytic sphere never reach the triangles). */
static bool add_sphere_light(Builder *b, float3 center, float radius, float3 radiance) {
    Scene *s = b->scene;
    if (s->light_count == TRACER_MAX_LIGHTS || !(radius > 0.0f)) return false;
    Light *light = &s->lights[s->light_count];
    memset(light, 0, sizeof *light);
    light->radius = radius;
    light->center = center;
    light->radiance = radiance;
    int32_t index = (int32_t)s->light_count++;
    enum { RINGS = 12, SEGMENTS = 24 };
    bool ok = true;
    for (int i = 0; i < RINGS && ok; ++i) {
        float t0 = 3.14159265f * (float)i / RINGS, t1 = 3.14159265f * (float)(i + 1) / RINGS;
        for (int j = 0; j < SEGMENTS && ok; ++j) {
            float p0 = 6.28318531f * (float)j / SEGMENTS, p1 = 6.28318531f * (float)(j + 1) / SEGMENTS;
            float3 v[4] = {f3(sinf(t0) * cosf(p0), cosf(t0), sinf(t0) * sinf(p0)),
                           f3(sinf(t0) * cosf(p1), cosf(t0), sinf(t0) * sinf(p1)),
                           f3(sinf(t1) * cosf(p1), cosf(t1), sinf(t1) * sinf(p1)),
                           f3(sinf(t1) * cosf(p0), cosf(t1), sinf(t1) * sinf(p0))};
            for (int k = 0; k < 4; ++k) v[k] = f3_add(center, f3_scale(v[k], radius));
            ok = builder_add_triangle(b, v[0], v[2], v[1], 0, index) &&
                 builder_add_triangle(b, v[0], v[3], v[2], 0, index);
        }
    }
    return ok;
}

/* A regular n-gon of circumradius r around `center`, facing `normal` (unit), rotated
 * by `phase` radians in its plane. */
static bool add_regular_light(Builder *b, uint32_t n, float3 center, float3 normal, float r,
                              float phase, float3 radiance) {
    float3 hint = fabsf(normal.y) < 0.9f ? f3(0, 1, 0) : f3(1, 0, 0);
    float3 a = f3_normalize(f3_cross(hint, normal));
    float3 c = f3_cross(normal, a); /* a x c = normal: counter-clockwise seen from the front */
    float3 v[SPHERA_MAX_POLYGON_VERTICES];
    for (uint32_t i = 0; i < n; ++i) {
        float t = phase + 6.28318531f * (float)i / (float)n;
        v[i] = f3_add(center, f3_add(f3_scale(a, r * cosf(t)), f3_scale(c, r * sinf(t))));
    }
    return add_light(b, v, n, radiance);
}

static void set_camera(Scene *s, float3 position, float3 target, float fov_y_degrees,
                       float aspect) {
    float3 forward = f3_normalize(f3_sub(target, position));
    float3 right = f3_normalize(f3_cross(forward, f3(0, 1, 0)));
    float3 up = f3_cross(right, forward);
    float h = tanf(0.5f * fov_y_degrees * 3.14159265f / 180.0f);
    s->camera.position = position;
    s->camera.forward = forward;
    s->camera.right = f3_scale(right, h * aspect);
    s->camera.up = f3_scale(up, h);
}

/* ---- the scenes ------------------------------------------------------------------ */

static bool build_cornell(Builder *b, float aspect) {
    Scene *s = b->scene;
    add_material(s, f3(0, 0, 0), f3(0, 0, 0), 0); /* 0: black, the lights' material */
    uint32_t white = add_material(s, f3(0.73f, 0.73f, 0.73f), f3(0, 0, 0), 0);
    uint32_t red = add_material(s, f3(0.65f, 0.05f, 0.05f), f3(0, 0, 0), 0);
    uint32_t green = add_material(s, f3(0.12f, 0.45f, 0.15f), f3(0, 0, 0), 0);
    /* The measured geometry of the Cornell box (millimetres). */
    bool ok = add_quad(b, f3(552.8f, 0, 0), f3(0, 0, 0), f3(0, 0, 559.2f), f3(549.6f, 0, 559.2f),
                       white) &&
              add_quad(b, f3(556, 548.8f, 0), f3(556, 548.8f, 559.2f), f3(0, 548.8f, 559.2f),
                       f3(0, 548.8f, 0), white) &&
              add_quad(b, f3(549.6f, 0, 559.2f), f3(0, 0, 559.2f), f3(0, 548.8f, 559.2f),
                       f3(556, 548.8f, 559.2f), white) &&
              add_quad(b, f3(0, 0, 559.2f), f3(0, 0, 0), f3(0, 548.8f, 0), f3(0, 548.8f, 559.2f),
                       green) &&
              add_quad(b, f3(552.8f, 0, 0), f3(549.6f, 0, 559.2f), f3(556, 548.8f, 559.2f),
                       f3(556, 548.8f, 0), red);
    float3 short_block[4] = {f3(130, 0, 65), f3(82, 0, 225), f3(240, 0, 272), f3(290, 0, 114)};
    float3 tall_block[4] = {f3(423, 0, 247), f3(265, 0, 296), f3(314, 0, 456), f3(472, 0, 406)};
    ok = ok && add_block(b, short_block, 165, white) && add_block(b, tall_block, 330, white);
    /* The light, 0.1 mm under the ceiling, facing down. */
    float3 light[4] = {f3(343, 548.7f, 227), f3(343, 548.7f, 332), f3(213, 548.7f, 332),
                       f3(213, 548.7f, 227)};
    ok = ok && add_light(b, light, 4, f3(60, 43, 14));
    set_camera(s, f3(278, 273, -800), f3(278, 273, 0), 39.3f, aspect);
    s->ray_epsilon = 0.05f;
    return ok;
}

static bool build_polygons(Builder *b, float aspect) {
    Scene *s = b->scene;
    add_material(s, f3(0, 0, 0), f3(0, 0, 0), 0);
    uint32_t floor = add_material(s, f3(0.40f, 0.40f, 0.42f), f3(0.2f, 0.2f, 0.2f), 0.55f);
    uint32_t wall = add_material(s, f3(0.70f, 0.68f, 0.62f), f3(0, 0, 0), 0);
    uint32_t blue = add_material(s, f3(0.20f, 0.30f, 0.60f), f3(0, 0, 0), 0);
    uint32_t orange = add_material(s, f3(0.70f, 0.40f, 0.15f), f3(0, 0, 0), 0);
    /* A 8 m x 8 m room, open towards the camera and at the top (metres). */
    bool ok = add_quad(b, f3(-4, 0, -4), f3(-4, 0, 4), f3(4, 0, 4), f3(4, 0, -4), floor) &&
              add_quad(b, f3(-4, 0, -4), f3(4, 0, -4), f3(4, 3.5f, -4), f3(-4, 3.5f, -4), wall) &&
              add_quad(b, f3(-4, 0, -4), f3(-4, 3.5f, -4), f3(-4, 3.5f, 4), f3(-4, 0, 4), wall) &&
              add_quad(b, f3(4, 0, -4), f3(4, 0, 4), f3(4, 3.5f, 4), f3(4, 3.5f, -4), wall);
    /* Occluders: a table top on a pillar, and a low block. */
    ok = ok && add_box(b, f3(-1.2f, 0.9f, -0.8f), f3(0.4f, 1.0f, 0.4f), blue) &&
         add_box(b, f3(-0.5f, 0, -0.3f), f3(-0.3f, 0.9f, -0.1f), blue) &&
         add_box(b, f3(1.6f, 0, -2.6f), f3(2.6f, 0.6f, -1.8f), orange);
    /* Triangle on the left wall, facing the room and a little down: decentral for the
     * floor. */
    ok = ok && add_regular_light(b, 3, f3(-3.7f, 2.0f, 0.5f), f3_normalize(f3(0.94f, -0.35f, 0)),
                                 0.7f, 0.3f, f3(27, 10, 4.5f));
    /* Quad hanging overhead, tilted by 30 degrees: central for the floor below it. */
    ok = ok && add_regular_light(b, 4, f3(1.2f, 2.6f, 0.8f), f3(0, -0.866f, -0.5f), 0.6f, 0.785f,
                                 f3(12, 12, 13));
    /* Pentagon leaning against the back wall, its lower part sunk below the floor: it
     * crosses the horizon of every floor point. Facing the room and upwards. */
    ok = ok && add_regular_light(b, 5, f3(-1.8f, 0.25f, -3.6f), f3_normalize(f3(0, 0.34f, 0.94f)),
                                 0.8f, 0.2f, f3(4.5f, 15, 7.5f));
    /* Hexagon piercing the right wall, facing the camera: it crosses the horizon of the
     * wall points in front of it. */
    ok = ok && add_regular_light(b, 6, f3(4.0f, 1.6f, -1.0f), f3(0, 0, 1), 0.7f, 0.0f,
                                 f3(6, 9, 27));
    /* Heptagon high in the back left corner, tilted down into the room. */
    ok = ok && add_regular_light(b, 7, f3(-3.2f, 2.8f, -3.2f), f3_normalize(f3(0.6f, -0.5f, 0.6f)),
                                 0.5f, 0.1f, f3(18, 18, 15));
    set_camera(s, f3(0.5f, 3.0f, 7.5f), f3(-0.2f, 0.9f, -1.0f), 55.0f, aspect);
    s->ray_epsilon = 2e-4f;
    return ok;
}

static bool build_hard(Builder *b, float aspect) {
    Scene *s = b->scene;
    add_material(s, f3(0, 0, 0), f3(0, 0, 0), 0);
    uint32_t grey = add_material(s, f3(0.6f, 0.6f, 0.6f), f3(0, 0, 0), 0);
    uint32_t wall = add_material(s, f3(0.7f, 0.7f, 0.7f), f3(0, 0, 0), 0);
    bool ok = add_quad(b, f3(-6, 0, -3), f3(-6, 0, 6), f3(6, 0, 6), f3(6, 0, -3), grey) &&
              add_quad(b, f3(-6, 0, -3), f3(6, 0, -3), f3(6, 4, -3), f3(-6, 4, -3), wall);
    /* A tiny distant light: 2 cm wide, 60 m away (about 1e-7 sr). */
    float3 dir = f3_normalize(f3(-0.6f, 0.5f, 0.62f));
    ok = ok && add_regular_light(b, 4, f3_scale(dir, 60.0f), f3_scale(dir, -1), 0.014f, 0.785f,
                                 f3(2e7f, 1.8e7f, 1.6e7f));
    /* A huge light 2 cm above the floor, facing down: floor points around it see it at
     * grazing elevations, just above their horizon. */
    float3 huge[4] = {f3(-5, 0.02f, 0.5f), f3(1, 0.02f, 0.5f), f3(1, 0.02f, 3.5f),
                      f3(-5, 0.02f, 3.5f)};
    ok = ok && add_light(b, huge, 4, f3(2, 3.2f, 6));
    /* A light edge-on to the back wall: in the plane x = 2, touching the wall, facing -x.
     * Wall points near x = 2 see it exactly edge-on. */
    float3 edge[4] = {f3(2, 0.6f, -3), f3(2, 0.6f, -1.4f), f3(2, 2.6f, -1.4f), f3(2, 2.6f, -3)};
    ok = ok && add_light(b, edge, 4, f3(12, 5, 3));
    set_camera(s, f3(0, 3.2f, 8.5f), f3(0, 0.6f, -0.5f), 50.0f, aspect);
    s->ray_epsilon = 2e-4f;
    return ok;
}

static bool build_floor(Builder *b, float aspect) {
    Scene *s = b->scene;
    add_material(s, f3(0, 0, 0), f3(0, 0, 0), 0);
    uint32_t white = add_material(s, f3(1, 1, 1), f3(0, 0, 0), 0);
    bool ok = add_quad(b, f3(-5, 0, -5), f3(-5, 0, 5), f3(5, 0, 5), f3(5, 0, -5), white);
    float3 light[4] = {f3(-0.6f, 1.2f, -0.5f), f3(0.6f, 1.2f, -0.5f), f3(0.6f, 1.4f, 0.5f),
                       f3(-0.6f, 1.4f, 0.5f)};
    /* wound clockwise seen from above, so its normal points down */
    ok = ok && add_light(b, light, 4, f3(12, 12, 12));
    set_camera(s, f3(0, 3.5f, 5.0f), f3(0, 0, 0), 60.0f, aspect);
    s->ray_epsilon = 2e-4f;
    return ok;
}

static bool build_glossy(Builder *b, float aspect) {
    Scene *s = b->scene;
    add_material(s, f3(0, 0, 0), f3(0, 0, 0), 0);
    /* Three strips across the view: roughness 0.1 (front), 0.3, 0.6 (back). */
    uint32_t strip[3];
    const float roughness[3] = {0.1f, 0.3f, 0.6f};
    for (int k = 0; k < 3; ++k)
        strip[k] = add_material(s, f3(0.15f, 0.15f, 0.16f), f3(0.6f, 0.6f, 0.6f), roughness[k]);
    uint32_t wall = add_material(s, f3(0.6f, 0.6f, 0.6f), f3(0, 0, 0), 0);
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
        float z0 = 3.0f - 2.5f * (float)k, z1 = z0 - 2.5f;
        ok = ok && add_quad(b, f3(-5, 0, z1), f3(-5, 0, z0), f3(5, 0, z0), f3(5, 0, z1), strip[k]);
    }
    ok = ok && add_quad(b, f3(-5, 0, -4.5f), f3(5, 0, -4.5f), f3(5, 4, -4.5f), f3(-5, 4, -4.5f), wall);
    /* A low wall across the middle: shadows (occluded light samples) on every strip. */
    ok = ok && add_box(b, f3(-0.3f, 0, -1.2f), f3(0.3f, 1.0f, 1.8f), wall);
    /* A quad light overhead on the left, tilted towards the camera. */
    ok = ok && add_regular_light(b, 4, f3(-2.2f, 2.2f, -1.5f), f3_normalize(f3(0.1f, -0.9f, 0.45f)),
                                 1.0f, 0.785f, f3(9, 9, 8));
    /* A pentagon on the right, lower and facing the strips at a grazing angle. */
    ok = ok && add_regular_light(b, 5, f3(2.6f, 1.0f, -3.2f), f3_normalize(f3(-0.2f, -0.3f, 0.93f)),
                                 0.8f, 0.1f, f3(4, 6, 12));
    /* A small triangle high behind the wall. */
    ok = ok && add_regular_light(b, 3, f3(0.0f, 3.0f, -4.0f), f3_normalize(f3(0.0f, -0.6f, 0.8f)),
                                 0.5f, 0.0f, f3(20, 12, 6));
    set_camera(s, f3(0, 2.0f, 6.5f), f3(0, 0.3f, -1.5f), 50.0f, aspect);
    s->ray_epsilon = 2e-4f;
    return ok;
}

static bool build_spheres(Builder *b, float aspect) {
    Scene *s = b->scene;
    add_material(s, f3(0, 0, 0), f3(0, 0, 0), 0);
    uint32_t matte = add_material(s, f3(0.6f, 0.6f, 0.6f), f3(0, 0, 0), 0);
    uint32_t glossy = add_material(s, f3(0.15f, 0.15f, 0.16f), f3(0.6f, 0.6f, 0.6f), 0.25f);
    uint32_t wall = add_material(s, f3(0.5f, 0.5f, 0.5f), f3(0, 0, 0), 0);
    bool ok = add_quad(b, f3(-6, 0, -6), f3(-6, 0, 6), f3(0, 0, 6), f3(0, 0, -6), matte) &&
              add_quad(b, f3(0, 0, -6), f3(0, 0, 6), f3(6, 0, 6), f3(6, 0, -6), glossy) &&
              add_quad(b, f3(-6, 0, -6), f3(6, 0, -6), f3(6, 4, -6), f3(-6, 4, -6), wall);
    ok = ok && add_sphere_light(b, f3(-1.5f, 1.2f, -1.0f), 0.05f, f3(800, 700, 600)) /* small */
         && add_sphere_light(b, f3(1.8f, 2.6f, -3.0f), 1.0f, f3(2.0f, 2.4f, 3.0f))  /* large */
         && add_sphere_light(b, f3(0.8f, 0.32f, 0.8f), 0.3f, f3(6, 3, 1.5f))        /* near */
         && add_sphere_light(b, f3(-14.0f, 0.8f, -12.0f), 0.6f, f3(40, 30, 20))    /* grazing */
         /* half sunk into the GGX floor: its cap crosses the horizon of the floor around
          * it (issue 20, 1: sampled above the horizon only) */
         && add_sphere_light(b, f3(2.2f, 0.1f, 0.6f), 0.35f, f3(8, 6, 10));
    set_camera(s, f3(0, 2.2f, 6.5f), f3(0, 0.5f, -1.0f), 55.0f, aspect);
    s->ray_epsilon = 2e-4f;
    return ok;
}

static bool build_slab(Builder *b, float aspect) {
    Scene *s = b->scene;
    add_material(s, f3(0, 0, 0), f3(0, 0, 0), 0);
    uint32_t matte = add_material(s, f3(0.3f, 0.3f, 0.3f), f3(0, 0, 0), 0);
    uint32_t wall = add_material(s, f3(0.3f, 0.3f, 0.3f), f3(0, 0, 0), 0);
    bool ok = add_quad(b, f3(-6, 0, -6), f3(-6, 0, 6), f3(6, 0, 6), f3(6, 0, -6), matte) &&
              add_quad(b, f3(-6, 0, -6), f3(6, 0, -6), f3(6, 4, -6), f3(-6, 4, -6), wall);
    /* A box on the floor inside the slab: shadows and occluded in-scattering. */
    ok = ok && add_box(b, f3(-1.6f, 0, -0.6f), f3(-1.0f, 0.8f, 0.0f), wall);
    ok = ok && add_sphere_light(b, f3(0.3f, 1.0f, -2.5f), 0.4f, f3(30, 25, 20));
    s->medium.present = true;
    s->medium.lo = f3(-3.0f, 0.0f, -4.5f);
    s->medium.hi = f3(2.5f, 0.5f, 3.0f);
    s->medium.sigma_s = 1.5f;
    s->medium.sigma_t = 1.6f;
    s->medium.g = 0.85f;
    set_camera(s, f3(0, 1.6f, 5.5f), f3(0, 0.3f, -1.5f), 50.0f, aspect);
    s->ray_epsilon = 2e-4f;
    return ok;
}

/* Two intersecting sphere lights of equal radiance (a double bulb): from every point
 * their caps overlap, in a part that grows towards the direction of the line through
 * their centres. sphere_union samples the union of the caps uniformly; sphere_mixture
 * picks one light with probability 1/2 and doubles the density in the overlap. A box
 * on the floor casts a partial shadow; the GGX half shows the highlights. */
static bool build_overlap(Builder *b, float aspect) {
    Scene *s = b->scene;
    add_material(s, f3(0, 0, 0), f3(0, 0, 0), 0);
    uint32_t matte = add_material(s, f3(0.6f, 0.6f, 0.6f), f3(0, 0, 0), 0);
    uint32_t glossy = add_material(s, f3(0.2f, 0.2f, 0.2f), f3(0.5f, 0.5f, 0.5f), 0.5f);
    uint32_t wall = add_material(s, f3(0.5f, 0.5f, 0.5f), f3(0, 0, 0), 0);
    bool ok = add_quad(b, f3(-6, 0, -6), f3(-6, 0, 6), f3(0, 0, 6), f3(0, 0, -6), matte) &&
              add_quad(b, f3(0, 0, -6), f3(0, 0, 6), f3(6, 0, 6), f3(6, 0, -6), glossy) &&
              add_quad(b, f3(-6, 0, -6), f3(6, 0, -6), f3(6, 4, -6), f3(-6, 4, -6), wall);
    ok = ok && add_box(b, f3(-1.9f, 0, 0.4f), f3(-1.3f, 0.6f, 1.0f), wall);
    ok = ok && add_sphere_light(b, f3(-0.35f, 1.3f, -0.8f), 0.5f, f3(6, 5.5f, 5)) &&
         add_sphere_light(b, f3(0.35f, 1.45f, -0.6f), 0.5f, f3(6, 5.5f, 5));
    set_camera(s, f3(0, 2.2f, 6.0f), f3(0, 0.6f, -1.0f), 55.0f, aspect);
    s->ray_epsilon = 2e-4f;
    return ok;
}

/* Specular occlusion (Dupuy et al. 2017, Sec. 5.4, Fig. 11): a GGX floor (roughness
 * 0.35, nearly no Lambert layer) at the bottom of a round well (radius 2 m, walls
 * 1.6 m high, 32 facets), whose visibility from the floor is the well's opening: a cone
 * about the normal at the centre, much as a bent cone has it, and less so towards the
 * wall. A sphere light above and behind the well is reflected in its floor and hidden
 * by the wall from the floor's back part: the highlight is partly occluded. */
#define WELL_FACETS 32
static bool build_occlusion(Builder *b, float aspect) {
    Scene *s = b->scene;
    add_material(s, f3(0, 0, 0), f3(0, 0, 0), 0);
    uint32_t glossy = add_material(s, f3(0.03f, 0.03f, 0.03f), f3(0.6f, 0.6f, 0.6f), 0.35f);
    uint32_t matte = add_material(s, f3(0.4f, 0.4f, 0.4f), f3(0, 0, 0), 0);
    bool ok = add_quad(b, f3(-8, 0, -8), f3(-8, 0, 8), f3(8, 0, 8), f3(8, 0, -8), glossy);
    const float radius = 2.0f, height = 1.6f;
    for (int i = 0; ok && i < WELL_FACETS; ++i) {
        float a0 = 2.0f * PI_F * (float)i / WELL_FACETS;
        float a1 = 2.0f * PI_F * (float)(i + 1) / WELL_FACETS;
        float3 p0 = f3(radius * cosf(a0), 0, radius * sinf(a0));
        float3 p1 = f3(radius * cosf(a1), 0, radius * sinf(a1));
        ok = add_quad(b, p0, p1, f3_add(p1, f3(0, height, 0)), f3_add(p0, f3(0, height, 0)),
                      matte);
    }
    ok = ok && add_sphere_light(b, f3(0.0f, 3.5f, -4.0f), 0.6f, f3(16, 14, 12));
    /* Seen about 45° from the floor's normal, where the SPTD fit is good (its error
     * table: a few percent up to 60°), so that the images compare the occlusion. */
    set_camera(s, f3(0, 4.5f, 4.5f), f3(0, 0.0f, -0.5f), 45.0f, aspect);
    s->ray_epsilon = 2e-4f;
    return ok;
}

/* A 6 m room (open towards the camera) lit only by the spot light of indirect.c,
 * which shines down onto a GGX floor and the red left wall: their first bounce lights
 * the rest of the room, glossily off the floor. No polygon light: render it with
 * `--scene indirect` (indirect.c). */
static bool build_indirect(Builder *b, float aspect) {
    Scene *s = b->scene;
    add_material(s, f3(0, 0, 0), f3(0, 0, 0), 0);
    uint32_t floor = add_material(s, f3(0.30f, 0.30f, 0.32f), f3(0.5f, 0.5f, 0.5f), 0.45f);
    uint32_t white = add_material(s, f3(0.75f, 0.75f, 0.72f), f3(0, 0, 0), 0);
    uint32_t red = add_material(s, f3(0.70f, 0.15f, 0.12f), f3(0.2f, 0.2f, 0.2f), 0.6f);
    uint32_t green = add_material(s, f3(0.15f, 0.55f, 0.20f), f3(0, 0, 0), 0);
    uint32_t box = add_material(s, f3(0.60f, 0.55f, 0.45f), f3(0.3f, 0.3f, 0.3f), 0.35f);
    bool ok = add_quad(b, f3(-3, 0, -3), f3(-3, 0, 3), f3(3, 0, 3), f3(3, 0, -3), floor) &&
              add_quad(b, f3(-3, 3, -3), f3(3, 3, -3), f3(3, 3, 3), f3(-3, 3, 3), white) &&
              add_quad(b, f3(-3, 0, -3), f3(3, 0, -3), f3(3, 3, -3), f3(-3, 3, -3), white) &&
              add_quad(b, f3(-3, 0, -3), f3(-3, 3, -3), f3(-3, 3, 3), f3(-3, 0, 3), red) &&
              add_quad(b, f3(3, 0, -3), f3(3, 0, 3), f3(3, 3, 3), f3(3, 3, -3), green);
    /* A glossy block on the floor: a receiver of glossy indirect light that also casts
     * indirect shadows. */
    ok = ok && add_box(b, f3(0.6f, 0, -2.0f), f3(1.6f, 1.0f, -1.0f), box);
    set_camera(s, f3(0, 1.5f, 2.9f), f3(0, 1.1f, -3.0f), 70.0f, aspect);
    s->ray_epsilon = 2e-4f;
    return ok;
}

/* ---- OBJ ------------------------------------------------------------------------- */

/* Adds the faces of a simple Wavefront OBJ file (`v x y z` and `f a b c ...` lines,
 * 1-based or negative indices, `a/b/c` forms; convex faces are fanned) with a white
 * Lambert material, scaled by `scale` and moved by `offset`. */
static bool add_obj(Builder *b, const char *path, float scale, float3 offset) {
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "sphera-trace: cannot open %s\n", path);
        return false;
    }
    uint32_t material = add_material(b->scene, f3(0.7f, 0.7f, 0.7f), f3(0, 0, 0), 0);
    float3 *positions = NULL;
    size_t count = 0, capacity = 0;
    char line[1024];
    bool ok = true;
    while (ok && fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') {
            float3 p;
            if (sscanf(line + 2, "%f %f %f", &p.x, &p.y, &p.z) != 3) continue;
            if (count == capacity) {
                capacity = capacity ? 2 * capacity : 256;
                float3 *grown = realloc(positions, sizeof(float3) * capacity);
                if (!grown) {
                    ok = false;
                    break;
                }
                positions = grown;
            }
            positions[count++] = f3_add(f3_scale(p, scale), offset);
        } else if (line[0] == 'f' && line[1] == ' ') {
            float3 face[3];
            uint32_t n = 0;
            char *cursor = line + 2, *end;
            for (;;) {
                long index = strtol(cursor, &end, 10);
                if (end == cursor) break;
                cursor = end;
                while (*cursor && *cursor != ' ' && *cursor != '\t' && *cursor != '\n') ++cursor;
                long resolved = index < 0 ? (long)count + index : index - 1;
                if (resolved < 0 || resolved >= (long)count) {
                    fprintf(stderr, "sphera-trace: %s: bad face index %ld\n", path, index);
                    ok = false;
                    break;
                }
                float3 p = positions[resolved];
                if (n < 2) face[n] = p;
                else {
                    face[2] = p;
                    ok = ok && builder_add_triangle(b, face[0], face[1], face[2], material, -1);
                    face[1] = p;
                }
                ++n;
            }
        }
    }
    free(positions);
    fclose(f);
    return ok;
}

/* ---- Embree ---------------------------------------------------------------------- */

static void embree_error(void *user, enum RTCError code, const char *message) {
    (void)user;
    fprintf(stderr, "sphera-trace: Embree error %d: %s\n", (int)code, message);
}

bool scene_create(Scene *s, const char *name, float aspect) {
    return scene_create_with_obj(s, name, aspect, NULL, 1.0f, f3(0, 0, 0));
}

bool scene_create_with_obj(Scene *s, const char *name, float aspect, const char *obj_path,
                           float obj_scale, float3 obj_offset) {
    memset(s, 0, sizeof *s);
    s->materials = calloc(MAX_MATERIALS, sizeof(Material));
    Builder b = {0};
    b.scene = s;
    bool ok;
    if (!s->materials) return false;
    if (strcmp(name, "cornell") == 0) ok = build_cornell(&b, aspect);
    else if (strcmp(name, "polygons") == 0) ok = build_polygons(&b, aspect);
    else if (strcmp(name, "hard") == 0) ok = build_hard(&b, aspect);
    else if (strcmp(name, "floor") == 0) ok = build_floor(&b, aspect);
    else if (strcmp(name, "glossy") == 0) ok = build_glossy(&b, aspect);
    else if (strcmp(name, "spheres") == 0) ok = build_spheres(&b, aspect);
    else if (strcmp(name, "slab") == 0) ok = build_slab(&b, aspect);
    else if (strcmp(name, "occlusion") == 0) ok = build_occlusion(&b, aspect);
    else if (strcmp(name, "overlap") == 0) ok = build_overlap(&b, aspect);
    else if (strcmp(name, "indirect") == 0) ok = build_indirect(&b, aspect);
    else {
        fprintf(stderr, "sphera-trace: unknown scene '%s' (see --list-scenes)\n", name);
        free(s->materials);
        return false;
    }
    if (ok && obj_path) ok = add_obj(&b, obj_path, obj_scale, obj_offset);
    if (!ok) {
        fprintf(stderr, "sphera-trace: building scene '%s' failed\n", name);
        goto fail;
    }
    s->name = name;
    s->triangle_count = b.count;
    s->triangle_material = b.material;
    s->triangle_light = b.light;
    s->triangle_normal = malloc(sizeof(float3) * b.count);
    if (!s->triangle_normal) goto fail;
    for (uint32_t i = 0; i < b.count; ++i) {
        float3 *p = &b.positions[3 * i];
        s->triangle_normal[i] = f3_normalize(f3_cross(f3_sub(p[1], p[0]), f3_sub(p[2], p[0])));
    }

    s->device = rtcNewDevice(NULL);
    if (!s->device) {
        fprintf(stderr, "sphera-trace: rtcNewDevice failed\n");
        goto fail;
    }
    rtcSetDeviceErrorFunction(s->device, embree_error, NULL);
    s->rtc = rtcNewScene(s->device);
    RTCGeometry geometry = rtcNewGeometry(s->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vertices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                              RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * b.count);
    unsigned *indices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                RTC_FORMAT_UINT3, 3 * sizeof(unsigned), b.count);
    if (!vertices || !indices) goto fail;
    for (uint32_t i = 0; i < 3 * b.count; ++i) {
        vertices[3 * i + 0] = b.positions[i].x;
        vertices[3 * i + 1] = b.positions[i].y;
        vertices[3 * i + 2] = b.positions[i].z;
        indices[i] = i;
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(s->rtc, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(s->rtc);
    free(b.positions);
    return true;

fail:
    free(b.positions);
    s->triangle_material = b.material;
    s->triangle_light = b.light;
    scene_destroy(s);
    return false;
}

void scene_destroy(Scene *s) {
    if (s->rtc) rtcReleaseScene(s->rtc);
    if (s->device) rtcReleaseDevice(s->device);
    free(s->triangle_material);
    free(s->triangle_light);
    free(s->triangle_normal);
    free(s->materials);
    memset(s, 0, sizeof *s);
}
