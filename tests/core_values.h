/* SPDX-License-Identifier: MIT */
/* Core values from doubles, for the tests that build scenes through rad.h: a point or
 * direction V and a colour C, each component RAD_REAL's (the build's own format). */
#ifndef RAD_TESTS_CORE_VALUES_H
#define RAD_TESTS_CORE_VALUES_H

#include "rad/rad.h"

static inline rad_vec3_t V(double x, double y, double z)
{
    rad_vec3_t v;
    v.x = RAD_REAL(x);
    v.y = RAD_REAL(y);
    v.z = RAD_REAL(z);
    return v;
}

static inline rad_rgb_t C(double r, double g, double b)
{
    rad_rgb_t c;
    c.r = RAD_REAL(r);
    c.g = RAD_REAL(g);
    c.b = RAD_REAL(b);
    return c;
}

#endif
