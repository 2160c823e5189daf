/* SPDX-License-Identifier: MIT */
/* A program from outside the tree, as a user writes one: built by tests/pkgconfig_check.sh
 * with `pkg-config --cflags --libs rad` against a staged install, never with -Iinclude.
 * It sizes its pools with rad_plan_polygon, solves a closed box lit by its ceiling, and
 * prints what the script checks. Exit status: 0 solved, 3 rad_init refused (the message
 * on stdout), 1 anything else. */
#include <rad/rad.h>
#include <stdio.h>

#define L 8 /* half the box's edge, in units */

/* Six walls facing into the box (counter-clockwise seen from inside); the ceiling glows. */
static const int walls[6][4][3] = {
    {{-L, -L, -L}, {-L, -L, L}, {L, -L, L}, {L, -L, -L}}, /* floor */
    {{-L, L, -L}, {L, L, -L}, {L, L, L}, {-L, L, L}},     /* ceiling */
    {{-L, -L, -L}, {L, -L, -L}, {L, L, -L}, {-L, L, -L}}, /* back */
    {{-L, -L, L}, {-L, L, L}, {L, L, L}, {L, -L, L}},     /* front */
    {{-L, -L, -L}, {-L, L, -L}, {-L, L, L}, {-L, -L, L}}, /* left */
    {{L, -L, -L}, {L, -L, L}, {L, L, L}, {L, L, -L}},     /* right */
};

static rad_surface_t surfaces[8];
static rad_patch_t patches[256];
static rad_element_t elements[1024];
static rad_vec3_t vertices[1024];
static unsigned char work[RAD_WORK_BYTES(32, RAD_PIXELS_ALL(32), 1024)];

static void quad(int w, rad_vec3_t *v)
{
    int k;
    for (k = 0; k < 4; k++) {
        v[k].x = RAD_REAL_RATIO(walls[w][k][0], 1);
        v[k].y = RAD_REAL_RATIO(walls[w][k][1], 1);
        v[k].z = RAD_REAL_RATIO(walls[w][k][2], 1);
    }
}

int main(void)
{
    const rad_config_t cfg = {
        .max_patch = RAD_REAL_RATIO(8, 1), .max_element = RAD_REAL_RATIO(4, 1), .res = 32};
    const rad_rgb_t grey = {RAD_REAL_RATIO(1, 2), RAD_REAL_RATIO(1, 2), RAD_REAL_RATIO(1, 2)};
    const rad_rgb_t glow = {RAD_REAL_RATIO(1, 1), RAD_REAL_RATIO(1, 1), RAD_REAL_RATIO(1, 1)};
    rad_pools_t pools = {.surfaces = surfaces,
                         .max_surfaces = 8,
                         .patches = patches,
                         .max_patches = 256,
                         .elements = elements,
                         .max_elements = 1024,
                         .vertices = vertices,
                         .max_vertices = 1024,
                         .work = work,
                         .work_bytes = sizeof work};
    rad_plan_t plan = {0};
    rad_scene_t s;
    rad_vec3_t v[4];
    int w, rc, shots;

    printf("version %s\n", RAD_VERSION);
    printf("index_bits %d\n", RAD_INDEX_BITS);
#ifdef RAD_BUILD_TARGET
    printf("build_target %s\n", RAD_BUILD_TARGET);
#endif
    for (w = 0; w < 6; w++) {
        quad(w, v);
        rc = rad_plan_polygon(&cfg, v, 4, &grey, w == 1 ? &glow : NULL, &plan);
        if (rc < 0) {
            printf("rad_plan_polygon: %s\n", plan.problem);
            return 1;
        }
    }
    printf("planned %lu %lu %lu %lu\n", (unsigned long)plan.surfaces, (unsigned long)plan.patches,
           (unsigned long)plan.elements, (unsigned long)plan.vertices);
    rc = rad_init(&s, &pools, &cfg);
    if (rc < 0) {
        printf("rad_init: %s\n", rad_strerror(rc));
        return 3;
    }
    for (w = 0; w < 6; w++) {
        quad(w, v);
        rc = rad_add_polygon(&s, v, 4, &grey, w == 1 ? &glow : NULL);
        if (rc < 0) {
            printf("rad_add_polygon: %s\n", rad_strerror(rc));
            return 1;
        }
    }
    printf("used %lu %lu %lu %lu\n", (unsigned long)s.n_surfaces, (unsigned long)s.n_patches,
           (unsigned long)s.n_elements, (unsigned long)s.n_vertices);
    shots = rad_shoot(&s, 1000, RAD_REAL_RATIO(1, 100));
    printf("shots %d\n", shots);
    return shots > 0 && rad_unshot_fraction(&s) <= RAD_REAL_RATIO(1, 100) ? 0 : 1;
}
