/* SPDX-License-Identifier: MIT */
/* Scenes built in C for the tests (no files): boxes, blockers, a Cornell-like room. */
#ifndef RAD_TEST_SCENES_H
#define RAD_TEST_SCENES_H

#include <string.h>
#include "reference/reference.h"
#include "host/scene.h"

#define quad ref_quad

static inline void set_mat(sc_poly *p, double r, double g, double b, double er, double eg,
                           double eb)
{
    p->rho[0] = r;
    p->rho[1] = g;
    p->rho[2] = b;
    p->emit[0] = er;
    p->emit[1] = eg;
    p->emit[2] = eb;
}

/* Axis-aligned box [x0,x1]x[y0,y1]x[z0,z1]; inward: faces look into the box (a room),
 * else outward (a block). Writes 6 quads, returns 6. */
static inline int box(sc_poly *out, double x0, double y0, double z0, double x1, double y1,
                      double z1, int inward)
{
    sc_poly f[6];
    int i;
    f[0] = quad(x0, y0, z0, x1, y0, z0, x1, y0, z1, x0, y0, z1); /* floor, normal -y */
    f[1] = quad(x0, y1, z0, x0, y1, z1, x1, y1, z1, x1, y1, z0); /* top, +y */
    f[2] = quad(x0, y0, z0, x0, y0, z1, x0, y1, z1, x0, y1, z0); /* -x */
    f[3] = quad(x1, y0, z0, x1, y1, z0, x1, y1, z1, x1, y0, z1); /* +x */
    f[4] = quad(x0, y0, z0, x0, y1, z0, x1, y1, z0, x1, y0, z0); /* -z */
    f[5] = quad(x0, y0, z1, x1, y0, z1, x1, y1, z1, x0, y1, z1); /* +z */
    for (i = 0; i < 6; i++) {
        out[i] = f[i];
        if (inward) { /* reverse the winding */
            double t[3];
            memcpy(t, out[i].v[1], sizeof t);
            memcpy(out[i].v[1], out[i].v[3], sizeof t);
            memcpy(out[i].v[3], t, sizeof t);
        }
    }
    return 6;
}

#endif
