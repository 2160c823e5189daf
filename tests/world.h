/* SPDX-License-Identifier: MIT */
/* A small scene on the heap for the tests that build one through rad.h: pools for a
 * few boxes, the per-element reflectance array, and a work buffer for every face at
 * once at res 64. */
#ifndef RAD_TESTS_WORLD_H
#define RAD_TESTS_WORLD_H

#include <stdlib.h>

#include "rad/rad.h"

#define NS 16
#define NP 512
#define NE 2048
#define NV 4096

typedef struct {
    rad_surface_t sf[NS];
    rad_patch_t pt[NP];
    rad_element_t el[NE];
    rad_vec3_t vx[NV];
    rad_rgb_t rho[RAD_ELEMENT_RHO_ENTRIES(NE, NP)];
    unsigned char work[RAD_WORK_BYTES(64, RAD_PIXELS_ALL(64), NV)];
    rad_scene_t s;
} world_t;

/* A world meshed at MAX_PATCH and MAX_ELEMENT, res 64 (free it). */
static world_t *world(double max_patch, double max_element)
{
    world_t *w = calloc(1, sizeof *w);
    rad_pools_t p;
    rad_config_t c = {
        .max_patch = RAD_REAL(max_patch), .max_element = RAD_REAL(max_element), .res = 64};
    assert_non_null(w);
    p.surfaces = w->sf;
    p.max_surfaces = NS;
    p.patches = w->pt;
    p.max_patches = NP;
    p.elements = w->el;
    p.max_elements = NE;
    p.vertices = w->vx;
    p.max_vertices = NV;
    p.work = w->work;
    p.work_bytes = sizeof w->work;
    assert_int_equal(rad_init(&w->s, &p, &c), RAD_OK);
    return w;
}

#endif
