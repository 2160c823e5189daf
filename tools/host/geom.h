/* SPDX-License-Identifier: MIT */
/* geom — the bake's geometry in double: vectors, polygons' planes, 2D triangles
 * against texel squares, and short rays through a uniform grid of polygons. */
#ifndef RAD_TOOLS_GEOM_H
#define RAD_TOOLS_GEOM_H

#include "host/scene.h"

typedef struct {
    double n[3]; /* unit normal (Newell), the lit side */
    double c[3]; /* centroid of the vertices */
    double d;    /* plane offset: n . x = d */
    double area; /* 0 for a degenerate polygon */
} geom_poly;

static inline double geom_dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void geom_sub(const double *a, const double *b, double *o)
{
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}

static inline void geom_cross(const double *a, const double *b, double *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Scales V to unit length; 0 (V unchanged) when it has none. */
int geom_normalize(double *v);
/* E without its part along unit N. */
void geom_reject(const double *e, const double *n, double *o);
/* A unit vector perpendicular to unit N. */
void geom_any_perp(const double *n, double *o);

/* Planes of N polygons (malloc'd), and the scene's extent (largest side of the box
 * around them) into *EXTENT. NULL when out of memory. */
geom_poly *geom_polys(const sc_poly *p, int n, double *extent);

/* The point of triangle T (2D) nearest C. */
void geom_tri2_closest(const double t[3][2], const double c[2], double q[2]);
/* 1 when triangle T and the square [X0, X0 + SIDE] x [Y0, Y0 + SIDE] overlap by more
 * than a touch. */
int geom_tri2_touches_box(const double t[3][2], double x0, double y0, double side);
/* Moves Q M in from the lines of the edges of the N triangles T flagged in B (edge k
 * from vertex k to k + 1; the third vertex lies on the inner side), in two passes so
 * that both edges of a corner are met: a sample kept off a boundary. */
void geom_tri2_inset(const double (*t)[3][2], const unsigned char (*b)[3], int n, double m,
                     double q[2]);

/* A uniform grid of the polygons' boxes; NULL when out of memory. */
void *geom_grid_new(const sc_poly *p, const geom_poly *g, int n);
void geom_grid_free(void *grid);
/* The nearest polygon that the ray from P along unit DIR meets within LEN (HUGE_VAL: any
 * distance): its distance, HUGE_VAL if none; *BACK 1 when it is met from behind. */
double geom_grid_ray(const void *grid, const sc_poly *p, const double *o, const double *dir,
                     double len, int *back);
/* The nearest polygon that the ray from O along unit DIR meets within LEN (HUGE_VAL:
 * any distance), cell by cell through the grid (Amanatides & Woo): its distance,
 * HUGE_VAL if none; with ANY, the first met, not the nearest (an occlusion test). For
 * long rays, where geom_grid_ray's box of cells would hold the whole grid. */
double geom_grid_march(const void *grid, const sc_poly *p, const double *o, const double *dir,
                       double len, int any);
/* Of the four rays from P along +-U and +-V (unit, in a plane P lies just above) within
 * LEN, the one that meets a back face nearest: its distance, its direction into DIR;
 * HUGE_VAL if none does. A sample whose ray meets a back face first lies inside
 * geometry (a box on the floor, a thick wall through it): move it out past that face.
 * MET (unless NULL): the nearest face of any side the four meet, HUGE_VAL if none. */
double geom_back_ray(const void *grid, const sc_poly *p, const double *o, const double *u,
                     const double *v, double len, double dir[3], double *met);

#endif
