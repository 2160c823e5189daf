/* SPDX-License-Identifier: MIT */
/* A caller compiled with the other index width than the library's (the Makefile builds
 * this unit with RAD_INDEX_BITS 16 against a 32-bit library, or 32 against 16), linked
 * into test_adopt: its rad_scene_t and pools have the strides of the other width. */
#include <stdint.h>
#include <string.h>

#include "adopt_other_abi.h"
#include "rad/rad.h"

static rad_surface_t surfaces[4];
static rad_patch_t patches[16];
static rad_element_t elements[64];
static rad_vec3_t vertices[64];
static unsigned char work[RAD_WORK_BYTES(8, RAD_PIXELS_ALL(8), 64)];

int adopt_other_init(adopt_other_t *out)
{
    rad_pools_t pools = {.surfaces = surfaces,
                         .max_surfaces = 4,
                         .patches = patches,
                         .max_patches = 16,
                         .elements = elements,
                         .max_elements = 64,
                         .vertices = vertices,
                         .max_vertices = 64,
                         .work = work,
                         .work_bytes = sizeof work};
    const rad_config_t cfg = {.res = 8};
    rad_scene_t s;
    const unsigned char *b = (const unsigned char *)&s;
    size_t i;
    int rc;
    memset(&s, 0xA5, sizeof s);
    memset(work, 0x5A, sizeof work);
    rc = rad_init(&s, &pools, &cfg);
    out->index_bytes = (unsigned)sizeof(rad_index_t);
    out->scene_untouched = 1;
    for (i = 0; i < sizeof s; i++)
        if (b[i] != 0xA5) out->scene_untouched = 0;
    out->work_untouched = 1;
    for (i = 0; i < sizeof work; i++)
        if (work[i] != 0x5A) out->work_untouched = 0;
    return rc;
}
