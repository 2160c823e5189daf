/* SPDX-License-Identifier: MIT */
/* rad host glue: scenes of double-precision polygons solved through the core.
 *
 * tools/host/scene*.c are compiled twice, once against the fixed library (names sc_*)
 * and once against the float twin (names scf_*), so a tool or test can run the same
 * scene through both. It owns the pools (malloc'd, grown until the scene fits),
 * scales the scene into the core's coordinate range (the radiosity solution does not
 * depend on scale) and emissions to a fixed peak (it is linear in emission), and maps
 * every result back to the caller's units.
 */
#ifndef RAD_TOOLS_SCENE_H
#define RAD_TOOLS_SCENE_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    double v[4][3];
    int n;          /* 3 or 4 */
    double rho[3];  /* reflectance, [0, 1) (values >= 1 are clamped and counted) */
    double emit[3]; /* emission, >= 0 */
    int tag;        /* caller's id (material, source line): passed back in warnings */
} sc_poly;

/* A light that is not a surface (rad_add_light), in the caller's units: TYPE 1 sun, 2
 * point, 3 spot, 4 sky (RAD_LIGHT_*); DIR the way its light travels (a sky's up, zero:
 * +Y); RGB a point's or spot's intensity (per steradian), a sun's irradiance on a plane
 * facing it or a sky's zenith radiance; a spot's cone by the cosines of its outer and
 * inner half angles; a sun's disc by RADIUS; a sky's HORIZON radiance and DIRS (0: the
 * core's default); DOME: for a sun of a sky's dome (rad_cli --sky-hdr), the count of
 * the dome's suns (rad_light_t.dirs: each raster coarser, as the core's sky draws its
 * own), else 0. */
typedef struct {
    int type;
    double pos[3], dir[3], rgb[3];
    double cos_outer, cos_inner;
    double radius; /* a sun's angular radius as its tangent, 0..1/4 */
    double horizon[3];
    int dirs;
    int dome;
} sc_light;

typedef struct {
    double max_patch, max_element; /* in the caller's units; 0: 1/8 and 1/32 of the extent */
    int res;                       /* hemi-cube resolution; 0: 64 */
    int band_rows;                 /* 0: all faces at once */
    long max_elements;             /* refuse scenes needing more; 0: 4,000,000 */
    int no_overshoot;              /* 1: shoot plainly (RAD_NO_OVERSHOOT) */
    double coarse;                 /* rad_config_t.coarse: unshot fraction below which
                                       shots coarsen; 0: never */
    int coarse_res;                /* rad_config_t.coarse_res: their floor; 0: res / 4 */
    const sc_light *lights;        /* lights shot first (sc_set_light changes them) */
    int nlights;
} sc_opts;

typedef struct {
    int surfaces, patches, elements, vertices, skipped, split, clamped;
    int shots;
    double unshot; /* unshot fraction */
    unsigned long saturations;
    unsigned long raster_calls;
    unsigned long long raster_pixels;
    size_t pool_bytes, work_bytes; /* memory handed to the core */
    /* How the last solve ended, for "not converged" and "saturated" reports: */
    int solved;                  /* 1 after a solve (shooting or Gauss-Seidel) */
    int converged;               /* it reached its tolerance (unshot <= tol; Gauss-Seidel:
                                       stopped before its sweep limit) */
    double tol;                  /* that tolerance */
    unsigned long backoffs;      /* overshoot halvings (rad_stats_t.backoffs) */
    unsigned long coarse_shots;  /* shots below res (rad_stats_t.coarse_shots) */
    int skipped_emitters;        /* emitting polygons skipped (each warned) */
    int tiny;                    /* surfaces below the core's 1/4096 (RAD_SMALL_FACES),
                                       shown from the light around them */
    unsigned long ambient_terms; /* shading calls (sc_element_rgb, sc_shade,
                                       sc_shade_elements, sc_render, sc_keep) that had the
                                       core compute the ambient term, a pass over the
                                       patches each: an export makes one */
} sc_stats;

typedef struct {
    double eye[3], target[3], up[3];
    double fov_deg; /* vertical field of view */
} sc_camera;

typedef void (*sc_warn_fn)(void *ctx, int tag, const char *msg);
typedef int (*sc_progress_fn)(void *ctx, int shots, double unshot); /* nonzero: stop */
typedef int (*sc_rows_progress_fn)(void *ctx, int rows, int total); /* nonzero: stop */
typedef int (*sc_tag_match_fn)(void *ctx, int tag);                 /* nonzero: this tag */

typedef struct {
    int rows;                   /* patches with a stored row (0: none) */
    unsigned long entries;      /* non-zero form factors stored */
    size_t bytes;               /* memory of the rows in use: starts, ids, codes */
    size_t matrix_bytes;        /* Gauss-Seidel matrix, once allocated */
    unsigned long raster_calls; /* hemi-cube polygons rendered to compute them */
} sc_rows_stats;

typedef struct sc_solver sc_solver;
typedef struct sc_solution sc_solution;
/* The most elements sc_create makes under O: o->max_elements, or 4,000,000, at most
 * what the core's indices count (65534 with RAD_INDEX_BITS 16). */
long sc_element_limit(const sc_opts *o);
/* Builds the scene; NULL with a message in err on failure. */
sc_solver *sc_create(const sc_poly *polys, int n, const sc_opts *o, sc_warn_fn warn, void *ctx,
                     char *err, size_t errlen);
void sc_destroy(sc_solver *s);
/* Shoots until the unshot fraction <= tol or max_shots; returns shots done. */
int sc_solve(sc_solver *s, int max_shots, double tol, sc_progress_fn progress, void *ctx);
/* Records that a shooting solve to TOL starts (sc_solve and sc_rows_solve do it; other
 * solvers over sc_core, such as sc_solve_parallel, call it), for sc_stats.converged. */
void sc_solve_started(sc_solver *s, double tol);
/* For the same solvers, once the geometry is frozen (the first shot or batch begun):
 * makes S's shots draw through the surfaces' hierarchy from CULL_SURFACES surfaces
 * (rad_shoot_cull; unless sc_shoot_cull turned it off). 1 once that is settled, 0
 * while the geometry is not frozen (shoot once, then call again). */
int sc_solve_cull(sc_solver *s);
void sc_get_stats(sc_solver *s, sc_stats *st);
/* Element radiosity in caller units (with the ambient term if ambient != 0). */
void sc_element_rgb(sc_solver *s, int e, int ambient, double rgb[3]);
double sc_element_area(sc_solver *s, int e);
void sc_element_centroid(sc_solver *s, int e, double c[3]);
int sc_element_tag(sc_solver *s, int e);
/* Element E's reflectance of its own (rad_use_element_reflectance; the array is made
 * by the first call, which must come before the first solve), each channel >= 0,
 * clamped below 1 as at create (counted), for the next solve. sc_set_surfaces sets a
 * surface's elements back to the surface's. 0, or -1 with err (a negative or
 * non-finite value, out of memory, the first call after solving). */
int sc_set_element_rho(sc_solver *s, int e, const double rho[3], char *err, size_t errlen);
/* Element E's reflectance: its own if set, else its surface's. */
void sc_element_rho(sc_solver *s, int e, double rho[3]);
/* Vertex ids of element e (3 or 4, returned). */
int sc_element_vertices(sc_solver *s, int e, int v[4]);
void sc_vertex_pos(sc_solver *s, int v, double p[3]);
/* Every element's sc_element_rgb (the same values) into RGB (3 an element), the
 * ambient term computed once (rad_shade_elements). 0, or -1 when out of memory. */
int sc_shade_elements(sc_solver *s, int ambient, double *rgb);
/* Gouraud vertex colours (caller units), n >= stats.vertices entries of 3. */
int sc_shade(sc_solver *s, int ambient, double *rgb);
/* Renders w x h linear RGB (caller units, row 0 at top); 0 or -1 with err. */
int sc_render(sc_solver *s, const sc_camera *cam, int ambient, int w, int h, float *rgb, char *err,
              size_t errlen);
/* Renders per-vertex VALUES (3 a core vertex, 0..65535, taken as they are: not in
 * caller units) through CAM as sc_render does, into OUT (w x h x 3); SOLID[pixel] is 1
 * where a surface was drawn (not a crack filled from its neighbours). For attributes
 * other than light (texture coordinates, ids). 0 or -1 with err. */
int sc_render_values(sc_solver *s, const sc_camera *cam, const double *values, int w, int h,
                     double *out, unsigned char *solid, char *err, size_t errlen);
/* Form factors from patch p to every element (n >= stats.elements). */
int sc_form_factors(sc_solver *s, int p, double *ff);
/* The raw bits of every element's radiosity, hashed (FNV-1a 64). */
uint64_t sc_checksum(sc_solver *s);
/* The core's rad_scene_t (of this build) inside, for glue of the same build. */
void *sc_core(sc_solver *s);
/* Patches: how many, and patch P's first element and its area in core units (the core
 * scales every area alike, so ratios of them hold in caller units). sc_patch returns 0,
 * or -1 for P out of range. */
int sc_patch_count(sc_solver *s);
int sc_patch(sc_solver *s, int p, int *first_element, double *area);

/* ---- stored form factors (rad_rows_t): visibility once, then relighting ---- */
/* The memory the rows (and the Gauss-Seidel matrix) may take, in bytes; 0: the
 * default, half of the physical memory. */
void sc_set_memory_limit(sc_solver *s, double bytes);
/* Renders every patch's hemi-cube once and keeps its row (malloc'd, grown until
 * it fits). Refused before anything is allocated when the rows' bound, patches x
 * min(elements, 3 res^2) entries of 6 bytes (a hemi-cube has 3 res^2 pixels, each
 * seeing one element), exceeds the memory limit. Progress may stop it (-1). Returns
 * 0 or -1 with err. */
int sc_rows_compute(sc_solver *s, sc_rows_progress_fn progress, void *ctx, char *err,
                    size_t errlen);
/* Writes the rows to PATH (tools/formats/ff_file.h, atomic) / reads them from PATH, checking
 * that the file was made by this build for this very mesh (fingerprint) at this
 * resolution. No hemi-cube is rendered. 0 or -1 with "PATH: what" in err. */
int sc_rows_save(sc_solver *s, const char *path, char *err, size_t errlen);
int sc_rows_load(sc_solver *s, const char *path, char *err, size_t errlen);
/* Rows memory and counters (all zero without rows). */
void sc_get_rows_stats(sc_solver *s, sc_rows_stats *st);
/* Progressive refinement through the rows (no hemi-cube), as sc_solve. Returns
 * the shots, or -1 without rows. */
int sc_rows_solve(sc_solver *s, int max_shots, double tol, sc_progress_fn progress, void *ctx);
/* The full-matrix Gauss-Seidel solve on the rows (rad_rows_gauss_seidel; matrix of
 * RAD_GS_ENTRIES(patches) malloc'd once and kept). Returns the sweeps, or -1 with
 * err (no rows, more than 16384 patches, out of memory). */
int sc_rows_gauss_seidel(sc_solver *s, int max_iter, double tol, char *err, size_t errlen);
/* Whether Gauss-Seidel can take this scene (patches, matrix memory), to ask before
 * the rows are computed: 0 or -1 with err. */
int sc_gauss_seidel_check(sc_solver *s, char *err, size_t errlen);
/* New reflectance RHO and/or emission EMIT (caller units; NULL keeps it) for every
 * surface whose polygon tag MATCH accepts, then sc_restart. Reflectance >= 1 is
 * clamped as at create. Returns the surfaces changed, or -1 with err (negative or
 * non-finite values). */
int sc_set_surfaces(sc_solver *s, sc_tag_match_fn match, void *ctx, const double *rho,
                    const double *emit, char *err, size_t errlen);
/* Resets the solution to the emission alone (the rows stay). As at create, the
 * brightest emission or light now set goes to the core at 256, so a dim relit scene
 * (one light group alone) keeps the core's precision; results map back to caller units. */
void sc_restart(sc_solver *s);
/* Light I's (0-based, as sc_opts.lights) intensity RGB and a sky's horizon HORIZON
 * (caller units; NULL keeps it; all 0: dark, not rendered), then sc_restart. 0, or -1
 * with err (no such light, a negative or non-finite value). */
int sc_set_light(sc_solver *s, int i, const double *rgb, const double *horizon, char *err,
                 size_t errlen);
/* A solution kept aside: every element's radiosity, with the ambient term baked in
 * if AMBIENT (radiosity is linear in emission, so is the ambient term). */
sc_solution *sc_keep(sc_solver *s, int ambient);
void sc_solution_free(sc_solution *k);
/* Light groups: sets every element's radiosity to sum_g INTENSITY[g] * GROUPS[g]
 * per channel (rad_mix's sum, in double over caller units, since every solution
 * has its own scale). Until the next solve or restart, element_rgb, shade and
 * render show this mix and ignore their ambient flag (the kept solutions carry
 * their own); solving again starts from the emission. 0 or -1 with err. */
int sc_mix(sc_solver *s, sc_solution *const *groups, const double (*intensity)[3], int n, char *err,
           size_t errlen);

/* ---- gathering: the light arriving at any point (rad_gather, rad_gather_sh) ---- */
typedef struct sc_gatherer sc_gatherer;
/* A gatherer of cube resolution RES (even, 8..RAD_MAX_RES) over S's solution, for
 * hemispheres (SPHERE 0: sc_gather) or spheres (1: sc_gather_sh); one per thread (they
 * only read S). NULL on a bad RES or out of memory. S must have been solved. */
sc_gatherer *sc_gatherer_new(sc_solver *s, int res, int sphere);
void sc_gatherer_free(sc_gatherer *g);
/* Whether G draws through the hierarchy of the surfaces (ON 1: rad_gather_cull) or
 * every surface (0): the same values either way, only the time differs. A new
 * gatherer does from CULL_SURFACES surfaces (host/scene.c). 0, or -1 (ON and the
 * hierarchy could not be had: G then draws every surface). */
int sc_gatherer_cull(sc_gatherer *g, int on);
/* Whether S's shots draw through the same hierarchy (ON 1, the default from
 * CULL_SURFACES surfaces: rad_shoot_cull, which draws every surface for a while after
 * a cube the hierarchy did not help) or every surface (0): the same bits either way
 * (rad_bench compares the times). */
void sc_shoot_cull(sc_solver *s, int on);
/* The radiosity arriving at P (caller units) on a surface of normal N (any length),
 * in caller units: what an element of reflectance rho there would show as rho RGB +
 * its emission. FLAGS: SC_AMBIENT adds the ambient term; SC_SOFT leaves out the
 * sharp lights' direct light (suns, points and spots: sc_direct's), and with SC_SKIES
 * the skies' too (every light's: sc_direct with SC_SKIES). Nothing is skipped: put P
 * off the surface. 0, or -1 (P outside the scene's frame, N zero, a sphere gatherer). */
#define SC_AMBIENT 1
#define SC_SOFT    2
#define SC_SKIES   4
int sc_gather(sc_gatherer *g, const double p[3], const double n[3], int flags, double rgb[3]);
/* sc_gather from a point on core surface SURFACE (-1: none), which is not drawn: a
 * quad planar only within the core's tolerance is not seen edge-on from just above. */
int sc_gather_on(sc_gatherer *g, const double p[3], const double n[3], int surface, int flags,
                 double rgb[3]);
/* The radiosity seen from P in every direction, projected on the nine real SH of bands
 * 0..2 (rad_gather_sh's order and scale), caller units. 0 or -1 as sc_gather. */
int sc_gather_sh(sc_gatherer *g, const double p[3], int ambient, double sh[9][3]);
/* Whether the ray from P along unit DIR reaches LEN (HUGE_VAL: a sun's, unbounded)
 * unoccluded: nonzero when it does. */
typedef int sc_visible_fn(void *ctx, const double p[3], const double dir[3], double len);
/* The sharp lights' direct light at P on a surface of normal N (rad_direct), each
 * light's visibility VIS's: with sc_gather's SC_SOFT value, the whole gather's but for
 * visibility. FLAGS: SC_SKIES adds the skies' (a ray a sky's direction: with
 * SC_SOFT | SC_SKIES's gather, the whole). 0 (RGB 0 without lights), or -1 (P outside
 * the frame, N zero). */
int sc_direct(sc_solver *s, const double p[3], const double n[3], int flags, sc_visible_fn *vis,
              void *ctx, double rgb[3]);
/* The soft light the solve's elements received, for a lightmap painted from them
 * (lm_paint) rather than gathered. sc_solve_lights shoots S's lights (a shooting
 * solve's first shots) one at a time and keeps each element's radiosity without the
 * suns', points' and spots' part (its emission and the skies' light; with FLAGS
 * SC_SKIES, the skies' part too, as sc_gather's); call it before
 * sc_solve, sc_solve_batch or sc_solve_parallel, before any shot. 0, or -1 (out of
 * memory, a shot already taken). */
int sc_solve_lights(sc_solver *s, int flags);
/* Every element of S as one of these (its polygon POLY, the index in sc_create's
 * array; N = 3 or 4 corners P in order round it; its AREA; and, when KNOWN, RGB: the
 * light it received but the direct light of the lights sc_solve_lights split off, as
 * sc_gather's SC_SOFT with its FLAGS, with the ambient term when AMBIENT), into a
 * malloc'd array of *N; NULL when out of memory. RGB is the radiosity's rise over the
 * reflectance; not known without sc_solve_lights since the solution started, after
 * sc_mix, on a face of a group of tiny faces (which shows the group's radiosity), or
 * where a channel's reflectance is below SOFT_RHO_MIN (the radiosity's rounding,
 * 2^-16 of the core's scale, over the reflectance would pass a gather's error). */
#define SOFT_RHO_MIN (1.0 / 64.0)
typedef struct {
    int poly, n, known;
    double p[4][3], rgb[3], area;
} sc_soft_element;
sc_soft_element *sc_soft_elements(sc_solver *s, int ambient, long *n);

/* Values past the core's range met by this gatherer (saturated, counted). */
unsigned long sc_gatherer_saturations(sc_gatherer *g);

#define RAD_TWIN_SCENE /* the float twin's names of the above (generated): */
#include "host/scene_float.h"

#endif
