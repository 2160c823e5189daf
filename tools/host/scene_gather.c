/* SPDX-License-Identifier: MIT */
/* rad host glue (see scene.h): gathering (rad_gather, rad_gather_sh) for lightmap texels and probes. Compiled once per build of the core. */
#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#endif
#include "host/scene_impl.h"
#include "host/geom.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>

struct sc_gatherer {
    struct sc_solver *h;
    rad_gather_t g;
    void *work;
    void *cull_work; /* rad_gather_cull's, or NULL */
};

/* Surfaces from which a new gatherer draws through the hierarchy: in rad_bench's cull
 * report (gathers at res 32 in grids of rooms; two runs) the culled gather took 1.49
 * to 1.56 times as long as drawing all at 27 surfaces, 1.04 to 1.09 at 116, 0.51 to
 * 0.52 at 480 and 0.19 to 0.20 at 1,952. */
#define CULL_SURFACES 200

/* Gatherers may be made in threads of their own: the hierarchy is built once, under
 * this lock, and only read after. */
static pthread_mutex_t cull_lock = PTHREAD_MUTEX_INITIALIZER;

/* H's hierarchy for the scene as it stands, built on first use; NULL when it cannot be
 * (geometry not frozen, out of memory) or when the scene changed since (its surfaces
 * or scale; gatherers may still read the old one). */
static const void *solver_cull(struct sc_solver *h)
{
    const void *c;
    pthread_mutex_lock(&cull_lock);
    if (!h->cull) {
        size_t bytes = RAD_CULL_BYTES(h->s.n_surfaces);
        void *b = malloc(bytes);
        if (b && rad_cull_build(&h->s, b, bytes) >= 0) {
            h->cull = b;
            h->cull_surfaces = h->s.n_surfaces;
            h->cull_shift = h->s.length_shift;
        } else {
            free(b);
        }
    }
    c = h->cull && h->cull_surfaces == h->s.n_surfaces && h->cull_shift == h->s.length_shift
            ? h->cull
            : NULL;
    pthread_mutex_unlock(&cull_lock);
    return c;
}

int sc_gatherer_cull(sc_gatherer *q, int on)
{
    const void *c = on ? solver_cull(q->h) : NULL;
    size_t bytes;
    if (!c) {
        rad_gather_cull(&q->g, NULL, NULL, 0);
        return on ? -1 : 0;
    }
    bytes = RAD_GATHER_CULL_BYTES(q->g.res, q->h->s.n_surfaces);
    free(q->cull_work);
    if (!(q->cull_work = malloc(bytes)) || rad_gather_cull(&q->g, c, q->cull_work, bytes) < 0) {
        rad_gather_cull(&q->g, NULL, NULL, 0);
        return -1;
    }
    return 0;
}

int sc_solve_cull(struct sc_solver *h)
{
    if (h->shots_drawn_all || h->s.n_surfaces < CULL_SURFACES) return 1;
    if (!h->s.solving) return 0;
    if (!h->s.cull) {
        const void *c = solver_cull(h);
        if (!c) h->shots_drawn_all = 1; /* no hierarchy to be had: not asked again */
        rad_shoot_cull(&h->s, c);
    }
    return 1;
}

void sc_shoot_cull(sc_solver *h, int on)
{
    h->shots_drawn_all = !on;
    rad_shoot_cull(&h->s, NULL); /* ON: again at the next solve's first shot */
}

sc_gatherer *sc_gatherer_new(sc_solver *h, int res, int sphere)
{
    struct sc_gatherer *q = calloc(1, sizeof *q);
    size_t bytes;
    if (!q || res < 8 || res > RAD_MAX_RES || (res & 1)) {
        free(q);
        return NULL;
    }
    bytes = sphere ? RAD_GATHER_SH_BYTES(res) : RAD_GATHER_BYTES(res);
    q->h = h;
    q->work = malloc(bytes);
    if (!q->work ||
        rad_gather_init(&q->g, (unsigned)res, sphere ? RAD_GATHER_SH : 0u, q->work, bytes) < 0) {
        sc_gatherer_free(q);
        return NULL;
    }
    /* without its hierarchy a gather draws every surface: the same values */
    if (h->s.n_surfaces >= CULL_SURFACES) sc_gatherer_cull(q, 1);
    return q;
}

void sc_gatherer_free(sc_gatherer *q)
{
    if (q) {
        free(q->work);
        free(q->cull_work);
    }
    free(q);
}

/* P into the core's frame, C; -1 outside it. */
static int core_point(const struct sc_solver *h, const double p[3], rad_vec3_t *c)
{
    int a;
    for (a = 0; a < 3; a++)
        if (!sc__fits_core((p[a] - h->off[a]) * h->scale)) return -1;
    sc__to_core(h, p, c);
    return 0;
}

/* P in the core's frame; -1 outside it, else the core's flags for FLAGS (SC_*): the
 * ambient term unless mixed (then it is baked in), the soft light alone. */
static int gather_frame(sc_gatherer *q, const double p[3], int flags, rad_vec3_t *c)
{
    if (core_point(q->h, p, c) < 0) return -1;
    return ((flags & SC_AMBIENT) && !q->h->mixed ? RAD_SHADE_AMBIENT : 0) |
           ((flags & SC_SOFT) ? RAD_SHADE_SOFT : 0) | ((flags & SC_SKIES) ? RAD_SHADE_SKIES : 0);
}

int sc_gather(sc_gatherer *q, const double p[3], const double n[3], int flags, double rgb[3])
{
    return sc_gather_on(q, p, n, -1, flags, rgb);
}

/* N scaled to unit length into NC; -1 when it has none (zero, not finite). */
static int core_normal(const double n[3], rad_vec3_t *nc)
{
    double len = sqrt(geom_dot(n, n));
    if (!(len > 0.0) || !isfinite(len)) return -1;
    nc->x = RAD_REAL(n[0] / len);
    nc->y = RAD_REAL(n[1] / len);
    nc->z = RAD_REAL(n[2] / len);
    return 0;
}

int sc_gather_on(sc_gatherer *q, const double p[3], const double n[3], int surface, int flags,
                 double rgb[3])
{
    rad_vec3_t c, nc;
    rad_rgb_t out;
    int f = gather_frame(q, p, flags, &c);
    if (f < 0 || core_normal(n, &nc) < 0) return -1;
    if (rad_gather(&q->h->s, &q->g, &c, &nc, surface < 0 ? RAD_INDEX_NONE : (uint32_t)surface, f,
                   &out) < 0)
        return -1;
    sc__rgb_out(q->h, &out, rgb);
    return 0;
}

int sc_gather_sh(sc_gatherer *q, const double p[3], int ambient, double sh[9][3])
{
    rad_vec3_t c;
    rad_rgb_t out[9];
    int k, flags = gather_frame(q, p, ambient, &c);
    if (flags < 0 || rad_gather_sh(&q->h->s, &q->g, &c, RAD_INDEX_NONE, flags, out) < 0) return -1;
    for (k = 0; k < 9; k++) sc__rgb_out(q->h, &out[k], sh[k]);
    return 0;
}

typedef struct {
    const struct sc_solver *h;
    const double *p;
    sc_visible_fn *vis;
    void *ctx;
} direct_ctx;

/* Light K's direction DIR from the point: the ray up to a point light's position. */
static int direct_vis(void *ctx, uint32_t k, const rad_vec3_t *dir)
{
    const direct_ctx *d = ctx;
    const sc_light *l = &d->h->src[k];
    double u[3] = {RAD_TO_DOUBLE(dir->x), RAD_TO_DOUBLE(dir->y), RAD_TO_DOUBLE(dir->z)}, len;
    if (!geom_normalize(u)) return 0;
    if (l->type == RAD_LIGHT_POINT || l->type == RAD_LIGHT_SPOT) {
        double w[3];
        geom_sub(l->pos, d->p, w);
        len = sqrt(geom_dot(w, w));
    } else {
        len = HUGE_VAL;
    }
    return d->vis(d->ctx, d->p, u, len);
}

int sc_direct(sc_solver *h, const double p[3], const double n[3], int flags, sc_visible_fn *vis,
              void *ctx, double rgb[3])
{
    direct_ctx d = {h, p, vis, ctx};
    rad_vec3_t c, nc;
    rad_rgb_t out;
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (!h->nlights) return 0;
    if (core_point(h, p, &c) < 0 || core_normal(n, &nc) < 0) return -1;
    if (rad_direct(&h->s, &c, &nc, (flags & SC_SKIES) ? RAD_SHADE_SKIES : 0, direct_vis, &d, &out) <
        0)
        return -1;
    sc__rgb_out(h, &out, rgb);
    return 0;
}

unsigned long sc_gatherer_saturations(sc_gatherer *q)
{
    return q->g.stats.saturations;
}

/* ---- the soft light the solve's elements received ---- */

int sc_solve_lights(sc_solver *h, int flags)
{
    size_t n = 3u * (size_t)h->s.n_elements, i;
    double *base, *before = malloc(n * sizeof *before), *after = malloc(n * sizeof *after);
    int rc = 0;
    sc__unmix(h);
    free(h->soft_base);
    h->soft_base = NULL;
    base = calloc(n, sizeof *base); /* first the gains of the lights not split off */
    if (!base || !before || !after || h->s.stats.shots > 0 || h->s.lights_shot > 0) rc = -1;
    /* no shot: the scene frozen, its power at the core's scale, so that radiosities
     * read in the caller's units compare from here on */
    sc_solve_cull(h);
    if (rc == 0 && rad_shoot(&h->s, 0, 0) != 0) rc = -1;
    while (rc == 0 && h->s.lights_shot < h->s.n_lights) {
        int kept = !(flags & SC_SKIES) && h->s.lights[h->s.lights_shot].type == RAD_LIGHT_SKY;
        sc_solve_cull(h);
        if (kept && sc_shade_elements(h, 0, before) < 0) rc = -1;
        if (rc == 0 && rad_shoot(&h->s, 1, 0) != 1) rc = -1; /* this light alone */
        if (rc == 0 && kept && sc_shade_elements(h, 0, after) < 0) rc = -1;
        for (i = 0; rc == 0 && kept && i < n; i++) base[i] += after[i] - before[i];
    }
    /* every light shot: the radiosity but the gains split off */
    if (rc == 0 && sc_shade_elements(h, 0, after) < 0) rc = -1;
    for (i = 0; rc == 0 && i < n; i++) base[i] = after[i] - base[i];
    free(before);
    free(after);
    if (rc == 0)
        h->soft_base = base;
    else
        free(base);
    return rc;
}

/* Element E's soft light into RGB from its radiosity B (caller units): 1, or 0 when
 * not known (sc_soft_elements; a face of a group of tiny faces shows the group's). */
static int element_soft(sc_solver *h, int e, const double *b, double rgb[3])
{
    double rho[3];
    int c;
    if (h->tiny[h->pools.elements[e].surface] & 2) return 0;
    sc_element_rho(h, e, rho);
    for (c = 0; c < 3; c++) {
        if (!(rho[c] >= SOFT_RHO_MIN)) return 0;
        rgb[c] = fmax(0.0, (b[c] - h->soft_base[3 * (size_t)e + c]) / rho[c]);
    }
    return 1;
}

sc_soft_element *sc_soft_elements(sc_solver *h, int ambient, long *n)
{
    long ne = (long)h->s.n_elements, e;
    sc_soft_element *el = malloc((size_t)(ne ? ne : 1) * sizeof *el);
    double *b = malloc((size_t)(ne ? ne : 1) * 3 * sizeof *b);
    int v[4], j, known = h->soft_base && !h->mixed;
    if (!el || !b || sc_shade_elements(h, ambient, b) < 0) {
        free(el);
        free(b);
        return NULL;
    }
    *n = ne;
    for (e = 0; e < ne; e++) {
        sc_soft_element *m = &el[e];
        m->poly = h->poly_of[h->pools.elements[e].surface];
        m->n = sc_element_vertices(h, (int)e, v);
        for (j = 0; j < m->n; j++) sc_vertex_pos(h, v[j], m->p[j]);
        m->area = sc_element_area(h, (int)e);
        m->known = known && element_soft(h, (int)e, &b[3 * e], m->rgb);
    }
    free(b);
    return el;
}
