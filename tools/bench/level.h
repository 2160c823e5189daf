/* SPDX-License-Identifier: MIT */
/* level — a generated level of Sponza's class for the benchmark (rad_bench --level):
 * a two-storey atrium, deterministic, every polygon a quad, metres with +Y up.
 *
 * A courtyard of 24 x 24 m open to the sky, ringed on two storeys (5 m each) by a
 * gallery 6 m deep behind an arcade: 32 columns a storey (32 facets in 22 rings, a
 * plinth and a capital), round arches between them (their soffits 32 segments of half
 * a cylinder, their spandrels faced on both sides), a moulded cornice of 8 facets along
 * the courtyard at each storey's top, the galleries' floor slab and roof (both sides),
 * and the outer walls, floors and walls tiled in 1 m quads like a modelled floor. Lit
 * by a sun from 50 degrees up and a sky; nothing emits. */
#ifndef RAD_TOOLS_LEVEL_H
#define RAD_TOOLS_LEVEL_H

#include "host/scene.h"

#define LEVEL_LIGHTS 2 /* the sun and the sky */

/* The atrium's polygons (malloc'd; *N of them, about 61,000) and its lights into
 * LIGHTS. NULL out of memory. */
sc_poly *level_atrium(int *n, sc_light lights[LEVEL_LIGHTS]);

/* The atrium as files for rad_cli (make readme-image): DIR/level.obj and level.mtl (a
 * material per reflectance) and DIR/level.json (its lights, for --lights). DIR must
 * exist. 0, or -1 with the reason in ERR. */
int level_write(const char *dir, char *err, size_t errlen);

#endif
