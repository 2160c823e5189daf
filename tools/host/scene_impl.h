/* SPDX-License-Identifier: MIT */
/* rad host glue, private: the solver's state and the helpers its files share
 * (scene.c builds, solves and answers queries; scene_rows.c stores form factors;
 * scene_relight.c relights; scene_gather.c gathers). Built once per build of the core,
 * as they are; only those four files include it. */
#ifndef RAD_TOOLS_SCENE_IMPL_H
#define RAD_TOOLS_SCENE_IMPL_H

#include "host/scene.h"
#include "rad/rad.h"

#define CORE_HALF_EXTENT 32.0  /* scene scaled into +-32: half the core's range */
#define CORE_EMIT_PEAK   256.0 /* brightest emission channel, well inside 4096 */
#define RHO_MAX          (65535.0 / 65536.0)

struct sc_solver {
    rad_scene_t s;
    rad_pools_t pools;
    int *tags;         /* per surface */
    int *poly_of;      /* per surface: its polygon's index in sc_create's array */
    double *soft_base; /* per element (3 each): its radiosity but the part of the lights
                        * sc_solve_lights split off, or NULL */
    double *emit;      /* per surface: emission in caller units (3 each) */
    double scale, off[3], escale;
    double escale0; /* escale of the scene as built */
    double epeak;   /* the brightest emission escale maps to the core's peak */
    int skipped, split, clamped;
    /* stored form factors */
    rad_rows_t rows; /* n_rows == n_patches once computed or loaded */
    int has_rows;
    unsigned long rows_raster; /* hemi-cube polygons rendered for the rows */
    rad_ff_t *gs;              /* Gauss-Seidel matrix, RAD_GS_ENTRIES(patches) */
    size_t gs_entries;
    int mixed;            /* elements hold a mix with the ambient term baked in */
    int skipped_emitters; /* emitting polygons the core could not mesh */
    int solve_kind;       /* 0: none yet, 1: shooting to tol, 2 / 3: Gauss-Seidel
                                   converged / stopped at its sweep limit */
    double tol;           /* the last solve's tolerance */
    double mem_limit;     /* rows + matrix bytes; 0: half the physical memory */
    /* faces below the core's own minimum area (RAD_SMALL_FACES; see join_poly) */
    unsigned char *tiny; /* per surface: 1 below TINY_AREA, | 2 in a group */
    double *area;        /* per surface: its area from its vertices, in core units^2 */
    int n_tiny;
    rad_rgb_t *erho; /* per element reflectance (rad_use_element_reflectance), or NULL */
    unsigned long ambient_terms; /* sc_stats.ambient_terms */
    rad_light_t *lights;         /* the lights in the core's units (sc_opts.lights), or NULL */
    sc_light *src;               /* and in the caller's, as now set (sc_set_light) */
    int nlights, light_res;      /* light_res: the scene's res, for sc__light_to_core */
    void *cull;                  /* the surfaces' hierarchy (rad_cull_build), or NULL */
    uint32_t cull_surfaces;      /* the scene it was built for: its surfaces and scale */
    int cull_shift;
    int shots_drawn_all; /* sc_shoot_cull(h, 0): shots draw every surface */
};

/* Emission E (caller units) as a core channel at the current escale, at most 4096. */
rad_real_t sc__emit_ch(struct sc_solver *h, double e);
/* Reflectance R as a core channel; 1 and above clamped below 1 (counted). */
rad_real_t sc__rho_ch(struct sc_solver *h, double r);
/* Point P (caller units) into the core's frame. */
void sc__to_core(const struct sc_solver *h, const double *p, rad_vec3_t *v);
/* A double that RAD_REAL converts without overflow (and not NaN). */
int sc__fits_core(double x);
/* The brightest of light L as an emission in the core's units before escale (a sky's
 * irradiance: at most pi times its brightest radiance). */
double sc__light_peak(const struct sc_solver *h, const sc_light *l);
/* Light L (one of h->src, or a mix of them) into the core's units at the current
 * escale, into C. */
void sc__light_to_core(const struct sc_solver *h, const sc_light *l, int res, rad_light_t *c);
/* A mixed scene (sc_mix) restarted before it is solved again. */
void sc__unmix(struct sc_solver *h);
/* Core radiosity C in caller units, into O[3]. */
void sc__rgb_out(const struct sc_solver *h, const rad_rgb_t *c, double *o);
/* The core's flags for AMBIENT; each call with the term is a computation of it. */
int sc__shade_flags(struct sc_solver *h, int ambient);

#endif
