/* SPDX-License-Identifier: MIT */
/* rad host glue: the final gather. Outputs shaded by gathering the light arriving
 * (sc_gather) at each vertex or pixel instead of interpolating elements, so shadows
 * come out sharper than the element mesh. Built once per build of the core, like
 * host/scene.c (float twin: scf_*).
 *
 * Where a gather sits: at the point on its surface (a core surface: one convex
 * polygon), moved 2^-12 of the scene's extent in from the surface's boundary edges and
 * lifted as far off its plane (tools/bake/lightmap.c's margin and lift: four times the
 * core's near plane, so a wall meeting the surface is never clipped into a leak, and
 * the surface's own plane is never seen edge-on). A vertex, which may lie under
 * geometry (a floor under a box), is pushed out past the nearest back face that one of
 * four rays along its plane meets within its surface's longest element edge, as the
 * lightmap's texels are (geom_back_ray). A pixel's point is where its ray meets its
 * surface's plane, so it is never hidden. Emitting surfaces keep their interpolated
 * values (a lamp's own light is its emission).
 *
 * Threads: every gather is a function of its point alone, and each thread has a
 * gatherer of its own and writes only its own vertices or pixels, so N threads give
 * the bits of one. */
#ifndef RAD_TOOLS_FGATHER_H
#define RAD_TOOLS_FGATHER_H

#include "host/scene.h"

#define FG_GRID  4 /* an image's first gathers: every FG_GRID-th pixel in x and y */
/* A grid cell is interpolated when its corners agree this well: a gather's own aliasing
 * under a small lamp is about 10% at res 64 (the Cornell box's lamp covers some 45 of
 * the top face's pixels, a row of them more or less), so a tighter bound gathers
 * nearly every pixel for that noise (2%: 85% of them), while a shadow's edge differs
 * by more. */
#define FG_AGREE 0.2

/* Runs FN(CTX, G, I, THREADS) for I in 0..THREADS-1 at once, each with a gatherer G of
 * resolution RES (even, 8..1024) of its own, I = 0 on the calling thread: FN does the
 * items with index % THREADS == I. Returns 0, or -1 (no memory, a bad RES, a thread
 * that cannot start, or FN returned nonzero). */
typedef int (*sc_split_fn)(void *ctx, sc_gatherer *g, int first, int step);
int sc_gather_split(sc_solver *s, int res, int threads, sc_split_fn fn, void *ctx);

typedef struct sc_fgather sc_fgather;
/* A final gather over the solved S at cube resolution RES on THREADS threads, with
 * the ambient term if AMBIENT; POLYS (N, kept by pointer), what S was made from, give
 * the rays that push vertices out of geometry (NULL: none). NULL when out of memory or
 * RES is not even in 8..1024. */
sc_fgather *sc_fgather_new(sc_solver *s, const sc_poly *polys, int n, int res, int threads,
                           int ambient);
void sc_fgather_free(sc_fgather *f);

/* Progress of the gathers that follow: FN(CTX, fraction done, 0..1) from the calling
 * thread now and then (its own share of the work standing for the whole); NULL: none. */
typedef int (*sc_fraction_fn)(void *ctx, double frac);
void sc_fgather_progress(sc_fgather *f, sc_fraction_fn fn, void *ctx);

/* The light arriving at every core vertex (E, radiosity units: a surface of reflectance
 * rho shows rho E), gathered once and kept: into E (3 a vertex, stats.vertices) and
 * OK[v] 1 where it was gathered (0: an emitter's vertex, or a gather that failed: the
 * point left the core's frame). Either may be NULL. Returns 0, or -1 (out of memory). */
int sc_fgather_vertices(sc_fgather *f, const double **e, const unsigned char **ok);

/* The colours of the core's vertices (3 each, caller units): the PLY's and any vertex
 * export's one source. F NULL: sc_shade's element interpolation (with AMBIENT); else
 * rho E at every gathered vertex, the interpolated value elsewhere. 0 or -1. */
int sc_vertex_colours(sc_solver *s, sc_fgather *f, int ambient, double *rgb);

/* Renders CAM as sc_render does (w x h linear RGB, row 0 at the top), each pixel of a
 * surface that does not emit shown as rho E gathered at the point its centre sees:
 * first on a grid of every FG_GRID-th pixel, then in each grid cell either every
 * pixel, or, where the cell shows one plane and its four corners agree within FG_AGREE
 * of their brightest channel, bilinear from the corners. Adds the gathers done to
 * *GATHERS (NULL: not counted). 0 or -1 with err. */
int sc_fgather_render(sc_fgather *f, const sc_camera *cam, int w, int h, float *rgb, long *gathers,
                      char *err, size_t errlen);

#define RAD_TWIN_FGATHER /* the float twin's names of the above (generated): */
#include "host/scene_float.h"

#endif
