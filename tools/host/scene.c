/* SPDX-License-Identifier: MIT */
/* rad host glue (see scene.h): the scene built from polygons and lights, solved by
 * shooting, and its results queried and rendered. Compiled once per build of the core;
 * stored rows, relighting and gathering are in scene_rows.c, scene_relight.c and
 * scene_gather.c. */
#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#endif
#include "host/scene_impl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rad/rad.h"

typedef struct {
    sc_warn_fn warn;
    void *ctx;
    int seen, emitted; /* warnings met in this attempt, already reported */
} warner_t;

static void warnf(warner_t *w, int tag, const char *msg, int code)
{
    char buf[256];
    if (w->seen++ < w->emitted || !w->warn) return;
    snprintf(buf, sizeof buf, "%s (%s)", msg, rad_strerror(code));
    w->warn(w->ctx, tag, buf);
    w->emitted++;
}

/* A skipped polygon, warned about; one that emits says that its light is lost. */
static void skip_poly(struct sc_solver *h, const sc_poly *q, warner_t *w, const char *what,
                      int code)
{
    char msg[192];
    h->skipped++;
    if (q->emit[0] > 0 || q->emit[1] > 0 || q->emit[2] > 0) {
        h->skipped_emitters++;
        snprintf(msg, sizeof msg, "skipped %s that emits light (%g %g %g): its light is lost", what,
                 q->emit[0], q->emit[1], q->emit[2]);
        warnf(w, q->tag, msg, code);
        return;
    }
    snprintf(msg, sizeof msg, "skipped %s", what);
    warnf(w, q->tag, msg, code);
}

static void free_pools(struct sc_solver *h)
{
    free(h->pools.surfaces);
    free(h->pools.patches);
    free(h->pools.elements);
    free(h->pools.vertices);
    free(h->pools.work);
    free(h->tags);
    free(h->poly_of);
    free(h->soft_base);
    h->poly_of = NULL;
    h->soft_base = NULL;
    free(h->emit);
    free(h->tiny);
    free(h->area);
    free(h->erho);
    h->erho = NULL;
    memset(&h->pools, 0, sizeof h->pools);
    h->tags = NULL;
    h->emit = NULL;
    h->tiny = NULL;
    h->area = NULL;
}

static int alloc_pools(struct sc_solver *h, long elements, int npolys, const rad_config_t *cfg)
{
    uint32_t nacc;
    rad_pools_t *p = &h->pools;
    size_t pixels;
    const long lim = (long)RAD_INDEX_NONE - 1; /* what the index type can count */
    p->max_surfaces = (uint32_t)(2L * npolys + 1 < lim ? 2L * npolys + 1 : lim);
    p->max_elements = (uint32_t)elements;
    p->max_patches = (uint32_t)elements;
    p->max_vertices = (uint32_t)(3 * elements < lim ? 3 * elements : lim);
    nacc = p->max_vertices;
    pixels = cfg->band_rows ? (size_t)cfg->res * cfg->band_rows : RAD_PIXELS_ALL(cfg->res);
    p->work_bytes = RAD_WORK_BYTES(cfg->res, pixels, nacc);
    p->surfaces = calloc(p->max_surfaces, sizeof *p->surfaces);
    p->patches = calloc(p->max_patches, sizeof *p->patches);
    p->elements = calloc(p->max_elements, sizeof *p->elements);
    p->vertices = calloc(p->max_vertices, sizeof *p->vertices);
    p->work = malloc(p->work_bytes);
    h->tags = calloc(p->max_surfaces, sizeof *h->tags);
    h->poly_of = calloc(p->max_surfaces, sizeof *h->poly_of);
    h->emit = calloc(3u * (size_t)p->max_surfaces, sizeof *h->emit);
    h->tiny = calloc(p->max_surfaces, sizeof *h->tiny);
    h->area = calloc(p->max_surfaces, sizeof *h->area);
    return p->surfaces && p->patches && p->elements && p->vertices && p->work && h->tags &&
           h->poly_of && h->emit && h->tiny && h->area;
}

rad_real_t sc__emit_ch(struct sc_solver *h, double e)
{
    /* Emissions so small that 256 / peak overflows still scale by their ratio to the
     * peak (results in caller units then underflow to 0). */
    double v = isfinite(h->escale) ? e * h->escale : e / h->epeak * CORE_EMIT_PEAK;
    return RAD_REAL(v > 4096.0 ? 4096.0 : v);
}

rad_real_t sc__rho_ch(struct sc_solver *h, double r)
{
    if (r >= 1.0) {
        h->clamped++;
        r = RHO_MAX;
    }
    return RAD_REAL(r);
}

void sc__to_core(const struct sc_solver *h, const double *p, rad_vec3_t *v)
{
    v->x = RAD_REAL((p[0] - h->off[0]) * h->scale);
    v->y = RAD_REAL((p[1] - h->off[1]) * h->scale);
    v->z = RAD_REAL((p[2] - h->off[2]) * h->scale);
}

/* A face below the core's own minimum area: the core meshes it only with
 * RAD_SMALL_FACES, in a group of its neighbours (join_poly). */
#define TINY_AREA (1.0 / 4096.0)

/* Area of polygon V (N corners, convex) in core units^2, from its rounded corners;
 * NRM (if not NULL) gets its normal, of twice that length. */
static double poly_area(const rad_vec3_t *v, int n, double *nrm)
{
    double c[3] = {0, 0, 0};
    int k;
    for (k = 1; k + 1 < n; k++) {
        double a[3] = {RAD_TO_DOUBLE(v[k].x) - RAD_TO_DOUBLE(v[0].x),
                       RAD_TO_DOUBLE(v[k].y) - RAD_TO_DOUBLE(v[0].y),
                       RAD_TO_DOUBLE(v[k].z) - RAD_TO_DOUBLE(v[0].z)};
        double b[3] = {RAD_TO_DOUBLE(v[k + 1].x) - RAD_TO_DOUBLE(v[0].x),
                       RAD_TO_DOUBLE(v[k + 1].y) - RAD_TO_DOUBLE(v[0].y),
                       RAD_TO_DOUBLE(v[k + 1].z) - RAD_TO_DOUBLE(v[0].z)};
        c[0] += a[1] * b[2] - a[2] * b[1];
        c[1] += a[2] * b[0] - a[0] * b[2];
        c[2] += a[0] * b[1] - a[1] * b[0];
    }
    if (nrm) memcpy(nrm, c, sizeof c);
    return 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

/* The group of a tiny face of centre C (core units) and normal N (any length): the
 * cell of a grid CELL wide holding C, and the bin of N's direction, TINY_DIRS^2 on each
 * face of a cube map (about 30 degrees each). */
#define TINY_DIRS 3
static uint64_t group_key(const double *c, const double *n, double cell)
{
    uint64_t key = 0;
    int a, major = 0, face;
    for (a = 0; a < 3; a++) /* |c| <= 64 and cell >= 1/16: 2048 cells an axis at most */
        key = key << 16 | ((uint64_t)((long)floor(c[a] / cell) + 32768L) & 0xFFFFu);
    for (a = 1; a < 3; a++)
        if (fabs(n[a]) > fabs(n[major])) major = a;
    face = 2 * major + (n[major] < 0);
    if (!(fabs(n[major]) > 0))
        return key << 8; /* no normal (a zero-area face): any bin,
                                                   the core refuses it when it is joined */
    for (a = 0; a < 3; a++) {
        int bin;
        if (a == major) continue;
        bin = (int)floor((n[a] / fabs(n[major]) + 1.0) * 0.5 * TINY_DIRS);
        face = face * TINY_DIRS + (bin < 0 ? 0 : bin >= TINY_DIRS ? TINY_DIRS - 1 : bin);
    }
    return key << 8 | (uint64_t)face;
}

/* Surface SURF, made of polygon Q's corners V (N of them), is kept. */
static void keep_surface(struct sc_solver *h, int surf, const sc_poly *q, const rad_vec3_t *v,
                         int n)
{
    h->tags[surf] = q->tag;
    memcpy(&h->emit[3 * surf], q->emit, sizeof q->emit);
    h->area[surf] = poly_area(v, n, NULL);
    h->tiny[surf] = h->area[surf] < TINY_AREA;
    h->n_tiny += h->tiny[surf] & 1;
}

/* Polygon Q in the core's units into V; its area there. */
static double poly_core(const struct sc_solver *h, const sc_poly *q, rad_vec3_t *v)
{
    int i;
    for (i = 0; i < q->n; i++) sc__to_core(h, q->v[i], &v[i]);
    return poly_area(v, q->n, NULL);
}

/* Adds one polygon; a quad the core refuses as non-planar is split in two. Returns
 * RAD_OK, RAD_ERR_FULL (grow and retry) or another error (fatal). */
static int add_poly(struct sc_solver *h, const sc_poly *q, warner_t *w)
{
    rad_vec3_t v[4];
    rad_rgb_t rho, em;
    int rc;
    poly_core(h, q, v);
    rho.r = sc__rho_ch(h, q->rho[0]);
    rho.g = sc__rho_ch(h, q->rho[1]);
    rho.b = sc__rho_ch(h, q->rho[2]);
    em.r = sc__emit_ch(h, q->emit[0]);
    em.g = sc__emit_ch(h, q->emit[1]);
    em.b = sc__emit_ch(h, q->emit[2]);
    rc = rad_add_polygon(&h->s, v, (unsigned)q->n, &rho, &em);
    if (rc >= 0) {
        keep_surface(h, rc, q, v, q->n);
        return RAD_OK;
    }
    if (q->n == 4 && (rc == RAD_ERR_NONPLANAR || rc == RAD_ERR_DEGENERATE)) {
        rad_vec3_t t[3];
        int k;
        h->split++;
        for (k = 0; k < 2; k++) {
            t[0] = v[0];
            t[1] = v[1 + k];
            t[2] = v[2 + k];
            rc = rad_add_polygon(&h->s, t, 3, &rho, &em);
            if (rc >= 0)
                keep_surface(h, rc, q, t, 3);
            else if (rc == RAD_ERR_DEGENERATE)
                skip_poly(h, q, w, "a degenerate triangle of a split quad", rc);
            else
                return rc;
        }
        return RAD_OK;
    }
    if (rc == RAD_ERR_DEGENERATE) {
        skip_poly(h, q, w, "a degenerate polygon", rc);
        return RAD_OK;
    }
    return rc;
}

/* Most faces a group shoots together (each join is a pass over the group). */
#define GROUP_MAX 1024

/* Tiny polygon Q joins the group of the last patch (rad_join_polygon), so that the
 * group's power is shot at once rather than left in thousands of patches too small to
 * be chosen. Where the core cannot join it (a quad to split, a sliver longer than an
 * element, a full group) it is added as add_poly does, and starts a group. Returns as
 * add_poly. */
static int join_poly(struct sc_solver *h, const sc_poly *q, warner_t *w)
{
    uint32_t p = h->s.n_patches - 1u, first = h->s.pools.patches[p].surface;
    rad_vec3_t v[4];
    rad_rgb_t rho;
    int rc, c;
    poly_core(h, q, v);
    rho.r = RAD_REAL(q->rho[0] >= 1.0 ? RHO_MAX : q->rho[0]);
    rho.g = RAD_REAL(q->rho[1] >= 1.0 ? RHO_MAX : q->rho[1]);
    rho.b = RAD_REAL(q->rho[2] >= 1.0 ? RHO_MAX : q->rho[2]);
    rc = h->s.pools.patches[p].n_elements < GROUP_MAX
             ? rad_join_polygon(&h->s, v, (unsigned)q->n, &rho)
             : RAD_ERR_ARG;
    if (rc == RAD_ERR_FULL) return rc;
    if (rc < 0) return add_poly(h, q, w);
    for (c = 0; c < 3; c++) h->clamped += q->rho[c] >= 1.0;
    keep_surface(h, rc, q, v, q->n);
    h->tiny[rc] |= 2;
    h->tiny[first] |= 2;
    return RAD_OK;
}

typedef struct {
    int tiny, i, part;
    uint64_t key;
    const double *rho;
} order_item;

static int cmp_order(const void *a, const void *b)
{
    const order_item *x = a, *y = b;
    int c;
    if (x->tiny != y->tiny) return x->tiny - y->tiny;
    if (!x->tiny) return x->i - y->i; /* as given */
    if (x->key != y->key) return x->key < y->key ? -1 : 1;
    for (c = 0; c < 3; c++)
        if (x->rho[c] != y->rho[c]) return x->rho[c] < y->rho[c] ? -1 : 1;
    if (x->part != y->part) return x->part - y->part;
    return x->i - y->i;
}

/* A corner of a polygon, for finding polygons that touch. */
typedef struct {
    uint64_t key;
    double p[3];
    int poly;
} corner_item;

static int cmp_corner(const void *a, const void *b)
{
    const corner_item *x = a, *y = b;
    int k;
    if (x->key != y->key) return x->key < y->key ? -1 : 1;
    for (k = 0; k < 3; k++)
        if (x->p[k] != y->p[k]) return x->p[k] < y->p[k] ? -1 : 1;
    return x->poly - y->poly;
}

static int find_part(int *up, int k)
{
    while (up[k] != k) k = up[k] = up[up[k]];
    return k;
}

/* PART[k]: the least index of the polygons joined to polygon k through shared corners
 * (equal coordinates), among the tiny ones of its key and reflectance: a group is one
 * connected piece, not separate things that share a cell and a direction. Returns 0,
 * or -1 out of memory. */
static int touching_parts(const sc_poly *polys, int n, const order_item *it, int *part)
{
    size_t nc = 0, i;
    corner_item *c;
    int k, a;
    for (k = 0; k < n; k++) {
        part[k] = k;
        if (it[k].tiny) nc += (size_t)polys[k].n;
    }
    c = malloc((nc ? nc : 1) * sizeof *c);
    if (!c) return -1;
    for (k = 0, nc = 0; k < n; k++)
        for (a = 0; it[k].tiny && a < polys[k].n; a++) {
            memcpy(c[nc].p, polys[k].v[a], sizeof c[nc].p);
            c[nc].key = it[k].key;
            c[nc++].poly = k;
        }
    qsort(c, nc, sizeof *c, cmp_corner);
    for (i = 1; i < nc; i++)
        if (c[i].key == c[i - 1].key && !memcmp(c[i].p, c[i - 1].p, sizeof c[i].p) &&
            !memcmp(polys[c[i].poly].rho, polys[c[i - 1].poly].rho, sizeof polys[0].rho)) {
            int x = find_part(part, c[i].poly), y = find_part(part, c[i - 1].poly);
            if (x < y)
                part[y] = x;
            else
                part[x] = y;
        }
    free(c);
    for (k = 0; k < n; k++) part[k] = find_part(part, k);
    return 0;
}

/* The order polygons go to the core: every one that is not tiny as given, then the
 * tiny ones by group (group_key, of the element size CELL, reflectance and connected
 * piece), so that each group's faces follow one another. SAME[k]: polygon ORDER[k] may join the group
 * of the one before it. Returns ORDER (malloc'd; NULL: out of memory). */
static int *poly_order(const struct sc_solver *h, const sc_poly *polys, int n, double cell,
                       unsigned char *same)
{
    order_item *it = malloc((size_t)n * sizeof *it);
    int *order = malloc((size_t)n * sizeof *order), k, a;
    if (!it || !order) {
        free(it);
        free(order);
        return NULL;
    }
    /* ORDER's memory holds the pieces until the sort */
    for (k = 0; k < n; k++) {
        rad_vec3_t v[4];
        double nrm[3], c[3] = {0, 0, 0};
        it[k].i = k;
        it[k].key = 0;
        it[k].rho = polys[k].rho;
        poly_core(h, &polys[k], v);
        it[k].tiny = poly_area(v, polys[k].n, nrm) < TINY_AREA;
        for (a = 0; a < polys[k].n; a++) {
            c[0] += RAD_TO_DOUBLE(v[a].x) / polys[k].n;
            c[1] += RAD_TO_DOUBLE(v[a].y) / polys[k].n;
            c[2] += RAD_TO_DOUBLE(v[a].z) / polys[k].n;
        }
        if (it[k].tiny) it[k].key = group_key(c, nrm, cell);
    }
    if (touching_parts(polys, n, it, order) < 0) {
        free(it);
        free(order);
        return NULL;
    }
    for (k = 0; k < n; k++) it[k].part = order[k];
    qsort(it, (size_t)n, sizeof *it, cmp_order);
    for (k = 0; k < n; k++) {
        const sc_poly *q = &polys[it[k].i], *r = k ? &polys[it[k - 1].i] : NULL;
        order[k] = it[k].i;
        same[k] = r && it[k].tiny && it[k - 1].tiny && it[k].key == it[k - 1].key &&
                  it[k].part == it[k - 1].part && !memcmp(q->rho, r->rho, sizeof q->rho) &&
                  !(q->emit[0] > 0 || q->emit[1] > 0 || q->emit[2] > 0);
    }
    free(it);
    return order;
}

static int frame_scene(struct sc_solver *h, const sc_poly *polys, int n, char *err, size_t errlen)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double half = 0.0, emax = 0.0;
    int i, k, a;
    for (i = 0; i < n; i++) {
        if (polys[i].n != 3 && polys[i].n != 4) {
            snprintf(err, errlen, "polygon %d has %d vertices (the core takes 3 or 4)", i,
                     polys[i].n);
            return -1;
        }
        for (k = 0; k < polys[i].n; k++)
            for (a = 0; a < 3; a++) {
                double c = polys[i].v[k][a];
                if (!isfinite(c) || fabs(c) > 1e30) {
                    snprintf(err, errlen, "polygon %d has a coordinate that is not a finite number",
                             i);
                    return -1;
                }
                if (c < lo[a]) lo[a] = c;
                if (c > hi[a]) hi[a] = c;
            }
        for (a = 0; a < 3; a++) {
            double e = polys[i].emit[a], r = polys[i].rho[a];
            if (!isfinite(e) || e < 0 || !isfinite(r) || r < 0) {
                snprintf(err, errlen,
                         "polygon %d has a negative or non-finite reflectance or emission", i);
                return -1;
            }
            if (e > emax) emax = e;
        }
    }
    for (a = 0; a < 3; a++) {
        h->off[a] = 0.5 * (lo[a] + hi[a]);
        if (0.5 * (hi[a] - lo[a]) > half) half = 0.5 * (hi[a] - lo[a]);
    }
    if (!(half > 0.0) || !isfinite(half)) {
        snprintf(err, errlen, "the scene has no extent");
        return -1;
    }
    h->scale = CORE_HALF_EXTENT / half;
    if (!isfinite(h->scale)) { /* a denormal extent */
        snprintf(err, errlen, "the scene has no extent");
        return -1;
    }
    h->epeak = emax;
    h->escale = h->escale0 = emax > 0.0 ? CORE_EMIT_PEAK / emax : 1.0;
    return 0;
}

/* A light's intensities' factor from the caller's units to the core's (before escale):
 * a sun's irradiance and a sky's radiance keep with lengths, a point's I / r^2 scales by
 * scale^2. */
static double light_k(const struct sc_solver *h, const sc_light *l)
{
    return l->type == RAD_LIGHT_SUN || l->type == RAD_LIGHT_SKY ? 1.0 : h->scale * h->scale;
}

double sc__light_peak(const struct sc_solver *h, const sc_light *l)
{
    double k = light_k(h, l) * (l->type == RAD_LIGHT_SKY ? 3.14159265358979323846 : 1.0), peak = 0;
    int a;
    for (a = 0; a < 3; a++) peak = fmax(peak, fmax(l->rgb[a], l->horizon[a]) * k);
    return peak;
}

void sc__light_to_core(const struct sc_solver *h, const sc_light *l, int res, rad_light_t *c)
{
    double k = light_k(h, l) * h->escale;
    double d = sqrt(l->dir[0] * l->dir[0] + l->dir[1] * l->dir[1] + l->dir[2] * l->dir[2]);
    memset(c, 0, sizeof *c);
    c->type = (uint16_t)l->type;
    /* A light shoots once, so its aliasing is not averaged over many shots as a
     * patch's is: a point light over a floor of 2,592 elements at res 192 gave
     * the direct light 11% rms (79% max) off I cos t / r^2 per element, at 4 res
     * 1.2% (10%). The core's default is the scene's res (the same bits
     * in any work buffer); the glue's buffer holds the 2 x 4 res pixels a pass
     * that a point light's finer cube needs. Suns and skies take the core's
     * default (lib/light.c: fine enough for the smallest elements). */
    if (l->type == RAD_LIGHT_POINT || l->type == RAD_LIGHT_SPOT) {
        int r = 4 * res;
        c->res = (uint16_t)(r < RAD_MAX_RES ? r : RAD_MAX_RES);
    }
    c->dirs = (uint32_t)l->dome; /* a sky's: below */
    sc__to_core(h, l->pos, &c->position);
    if (d > 0) {
        c->direction.x = RAD_REAL(l->dir[0] / d);
        c->direction.y = RAD_REAL(l->dir[1] / d);
        c->direction.z = RAD_REAL(l->dir[2] / d);
    }
    c->intensity.r = RAD_REAL(fmin(l->rgb[0] * k, 4096.0));
    c->intensity.g = RAD_REAL(fmin(l->rgb[1] * k, 4096.0));
    c->intensity.b = RAD_REAL(fmin(l->rgb[2] * k, 4096.0));
    c->cos_outer = RAD_REAL(l->cos_outer);
    c->cos_inner = RAD_REAL(l->cos_inner);
    c->radius = RAD_REAL(l->radius);
    if (l->type == RAD_LIGHT_SKY) {
        memset(&c->position, 0, sizeof c->position);
        c->horizon.r = RAD_REAL(fmin(l->horizon[0] * k, 4096.0));
        c->horizon.g = RAD_REAL(fmin(l->horizon[1] * k, 4096.0));
        c->horizon.b = RAD_REAL(fmin(l->horizon[2] * k, 4096.0));
        c->dirs = (uint32_t)l->dirs;
    }
}

/* The lights of O checked and taken to the core (h->lights): positions as the
 * polygons', directions unit, intensities by escale (a point's also by scale^2, as its
 * irradiance I / r^2 keeps with lengths), escale lowered first so that the brightest
 * light, as an emission, reaches at most CORE_EMIT_PEAK. 0 or -1 with err. */
static int frame_lights(struct sc_solver *h, const sc_opts *o, char *err, size_t errlen)
{
    double peak = h->epeak;
    int i, a;
    if (o->nlights <= 0) return 0;
    for (i = 0; i < o->nlights; i++) {
        const sc_light *l = &o->lights[i];
        double d = 0;
        for (a = 0; a < 3; a++) {
            if (!isfinite(l->rgb[a]) || l->rgb[a] < 0 || !isfinite(l->pos[a]) ||
                !isfinite(l->dir[a]) || !(l->horizon[a] >= 0) || !isfinite(l->horizon[a])) {
                snprintf(err, errlen, "light %d: a negative or non-finite value", i + 1);
                return -1;
            }
            d += l->dir[a] * l->dir[a];
            if ((l->type == RAD_LIGHT_POINT || l->type == RAD_LIGHT_SPOT) &&
                fabs((l->pos[a] - h->off[a]) * h->scale) > RAD_COORD_LIMIT) {
                snprintf(err, errlen,
                         "light %d: its position lies beyond the core's range, twice the scene's "
                         "extent from its centre: move it nearer",
                         i + 1);
                return -1;
            }
        }
        if (l->type != RAD_LIGHT_POINT && l->type != RAD_LIGHT_SKY && !(d > 0)) {
            snprintf(err, errlen, "light %d: a zero direction", i + 1);
            return -1;
        }
        peak = fmax(peak, sc__light_peak(h, l));
    }
    if (peak > h->epeak) {
        h->epeak = peak;
        h->escale = h->escale0 = CORE_EMIT_PEAK / peak;
    }
    h->lights = calloc((size_t)o->nlights, sizeof *h->lights);
    h->src = malloc((size_t)o->nlights * sizeof *h->src);
    if (!h->lights || !h->src) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    memcpy(h->src, o->lights, (size_t)o->nlights * sizeof *h->src);
    h->nlights = o->nlights;
    h->light_res = o->res ? o->res : RAD_DEFAULT_RES;
    for (i = 0; i < o->nlights; i++) sc__light_to_core(h, &h->src[i], h->light_res, &h->lights[i]);
    return 0;
}

/* The lights into the core's scene, after rad_init: RAD_OK or the core's error. */
static int add_lights(struct sc_solver *h)
{
    int i, rc;
    if (!h->nlights) return RAD_OK;
    rc = rad_use_lights(&h->s, h->lights, (uint32_t)h->nlights);
    for (i = 0; i < h->nlights && rc >= 0; i++) rc = rad_add_light(&h->s, &h->lights[i]);
    return rc < 0 ? rc : RAD_OK;
}

/* A generous estimate of the elements the core will make (it grows if short). */
static long estimate_elements(const struct sc_solver *h, const sc_poly *polys, int n, double me)
{
    double sum = 0.0;
    int i;
    for (i = 0; i < n; i++) {
        double l = 0.0;
        int k, a;
        for (k = 0; k < polys[i].n; k++) {
            double d = 0.0;
            for (a = 0; a < 3; a++) {
                double x = (polys[i].v[(k + 1) % polys[i].n][a] - polys[i].v[k][a]) * h->scale;
                d += x * x;
            }
            if (sqrt(d) > l) l = sqrt(d);
        }
        sum += 2.0 * (ceil(l / me) + 1.0) * (ceil(l / me) + 1.0);
    }
    return (long)(sum > 1024.0 ? sum : 1024.0);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Coordinates scaled by 32 / (half the span) keep 1/65536 of a unit: a vertex far
 * from the rest shrinks every other polygon below that. When the farthest vertex from
 * the median point is over 2^16 times as far as 90% of the vertices (all but one, when
 * there are fewer than 20), writes which it is to err and returns 1 (else 0, and
 * nothing is written). */
static int outlier(const sc_poly *polys, int n, char *err, size_t errlen)
{
    size_t nv = 0, i, far = 0;
    double *c, mid[3], d90, dmax = -1.0;
    int k, a, ok = 1;
    for (i = 0; i < (size_t)n; i++) nv += (size_t)polys[i].n;
    c = malloc(nv * sizeof *c);
    if (!c) return 0;
    for (a = 0; a < 3; a++) {
        for (i = 0, nv = 0; i < (size_t)n; i++)
            for (k = 0; k < polys[i].n; k++) c[nv++] = polys[i].v[k][a];
        qsort(c, nv, sizeof *c, cmp_double);
        mid[a] = c[nv / 2];
    }
    for (i = 0, nv = 0; i < (size_t)n; i++)
        for (k = 0; k < polys[i].n; k++) {
            const double *v = polys[i].v[k];
            double d = fmax(fabs(v[0] - mid[0]), fmax(fabs(v[1] - mid[1]), fabs(v[2] - mid[2])));
            if (d > dmax) {
                dmax = d;
                far = i;
            }
            c[nv++] = d;
        }
    qsort(c, nv, sizeof *c, cmp_double);
    d90 = c[nv - 1 - (nv / 10 > 0 ? nv / 10 : 1)]; /* the farthest tenth left out, at least one */
    free(c);
    ok = dmax > 65536.0 * d90;
    if (ok) {
        const sc_poly *q = &polys[far];
        int v = 0;
        for (k = 1; k < q->n; k++)
            if (fmax(fabs(q->v[k][0] - mid[0]),
                     fmax(fabs(q->v[k][1] - mid[1]), fabs(q->v[k][2] - mid[2]))) >
                fmax(fabs(q->v[v][0] - mid[0]),
                     fmax(fabs(q->v[v][1] - mid[1]), fabs(q->v[v][2] - mid[2]))))
                v = k;
        snprintf(err, errlen,
                 "the scene spans %.3g units: polygon %d (tag %d) has a vertex at (%.3g, %.3g, "
                 "%.3g), %.2g times "
                 "farther from the middle than the rest (90%% of the vertices lie within %.3g of "
                 "it), so every "
                 "other polygon falls below the core's precision (1/65536 of the span)",
                 2.0 * dmax, (int)far, q->tag, q->v[v][0], q->v[v][1], q->v[v][2],
                 d90 > 0 ? dmax / d90 : HUGE_VAL, d90);
    }
    return ok;
}

sc_solver *sc_create(const sc_poly *polys, int n, const sc_opts *o, sc_warn_fn warn, void *ctx,
                     char *err, size_t errlen)
{
    static const sc_opts defaults = {0};
    struct sc_solver *h = calloc(1, sizeof *h);
    rad_config_t cfg;
    long cap, limit;
    warner_t w;
    int *order = NULL;
    unsigned char *same = NULL;
    if (!o) o = &defaults;
    if (!h) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    if (n <= 0) {
        snprintf(err, errlen, "the scene has no polygons");
        free(h);
        return NULL;
    }
    if (frame_scene(h, polys, n, err, errlen) < 0 || frame_lights(h, o, err, errlen) < 0) {
        free(h->lights);
        free(h->src);
        free(h);
        return NULL;
    }
    memset(&cfg, 0, sizeof cfg);
    {
        double me = o->max_element > 0 ? o->max_element * h->scale : 2.0 * CORE_HALF_EXTENT / 24.0;
        double mp = o->max_patch > 0 ? o->max_patch * h->scale : 4.0 * me;
        if (me < 1.0 / 16.0 || me > 128.0 || mp < me || mp > 256.0) {
            snprintf(err, errlen,
                     "element size %g / patch size %g out of range for this scene (element >= %g, "
                     "patch >= element)",
                     me / h->scale, mp / h->scale, 1.0 / 16.0 / h->scale);
            free(h->lights);
            free(h->src);
            free(h);
            return NULL;
        }
        cfg.max_element = RAD_REAL(me);
        cfg.max_patch = RAD_REAL(mp);
        cfg.res = (uint16_t)(o->res ? o->res : RAD_DEFAULT_RES);
        cfg.band_rows = (uint16_t)o->band_rows;
        cfg.flags = (o->no_overshoot ? RAD_NO_OVERSHOOT : 0u) | RAD_SMALL_FACES;
        cfg.coarse = RAD_REAL(o->coarse);
        cfg.coarse_res = (uint16_t)o->coarse_res;
        cap = estimate_elements(h, polys, n, me);
        same = malloc((size_t)n);
        order = same ? poly_order(h, polys, n, me, same) : NULL;
        if (!order) {
            snprintf(err, errlen, "out of memory");
            free(same);
            free(h->lights);
            free(h->src);
            free(h);
            return NULL;
        }
    }
    limit = sc_element_limit(o);
    w.warn = warn;
    w.ctx = ctx;
    w.emitted = 0;
    for (;;) {
        int i, added, rc = RAD_OK;
        if (cap > limit) cap = limit;
        if (!alloc_pools(h, cap, n, &cfg)) {
            snprintf(err, errlen, "out of memory for %ld elements", cap);
            break;
        }
        rc = rad_init(&h->s, &h->pools, &cfg);
        if (rc == RAD_OK) rc = add_lights(h);
        if (rc < 0) {
            snprintf(err, errlen, "cannot set up the solver: %s", rad_strerror(rc));
            break;
        }
        h->skipped = h->split = h->clamped = h->skipped_emitters = h->n_tiny = 0;
        w.seen = 0;
        for (i = 0, added = 0; i < n && rc == RAD_OK; i++) {
            uint32_t before = h->s.n_surfaces, k;
            rc = same[i] && added ? join_poly(h, &polys[order[i]], &w)
                                  : add_poly(h, &polys[order[i]], &w);
            added = h->s.n_surfaces > before;
            for (k = before; k < h->s.n_surfaces; k++) h->poly_of[k] = order[i];
        }
        if (rc == RAD_OK) {
            if (h->s.n_elements == 0) {
                if (!outlier(polys, n, err, errlen))
                    snprintf(err, errlen, "no polygon could be meshed");
                break;
            }
            free(order);
            free(same);
            return h;
        }
        if (rc != RAD_ERR_FULL) {
            snprintf(err, errlen, "polygon %d (tag %d): %s", order[i - 1], polys[order[i - 1]].tag,
                     rad_strerror(rc));
            break;
        }
        free_pools(h);
        if (cap >= limit) {
            snprintf(err, errlen, "the scene needs more than %ld elements: raise the element size",
                     limit);
            break;
        }
        cap *= 2;
    }
    free(order);
    free(same);
    sc_destroy(h);
    return NULL;
}

long sc_element_limit(const sc_opts *o)
{
    long limit = o->max_elements > 0 ? o->max_elements : 4000000L;
    return limit > (long)RAD_INDEX_NONE - 1 ? (long)RAD_INDEX_NONE - 1
                                            : limit; /* 65534 with 16-bit indices */
}

void sc_destroy(sc_solver *h)
{
    if (!h) return;
    free_pools(h);
    free(h->rows.start);
    free(h->rows.ids);
    free(h->rows.ffs);
    free(h->gs);
    free(h->lights);
    free(h->cull);
    free(h->src);
    free(h);
}

void sc__unmix(struct sc_solver *h)
{
    if (h->mixed) sc_restart(h); /* also puts the emissions back at their scale */
}

void sc_solve_started(sc_solver *h, double tol)
{
    h->solve_kind = 1;
    h->tol = tol;
}

int sc_solve(sc_solver *h, int max_shots, double tol, sc_progress_fn progress, void *ctx)
{
    int done = 0;
    rad_real_t t = RAD_REAL(tol);
    sc__unmix(h);
    sc_solve_started(h, tol);
    while (done < max_shots) {
        int settled = sc_solve_cull(h); /* else one shot freezes the geometry first */
        int k = rad_shoot(&h->s, progress || !settled ? 1u : (uint32_t)(max_shots - done), t);
        if (k <= 0) break;
        done += k;
        if (progress && progress(ctx, done, RAD_TO_DOUBLE(rad_unshot_fraction(&h->s)))) break;
    }
    return done;
}

void sc_get_stats(sc_solver *h, sc_stats *st)
{
    const rad_pools_t *p = &h->pools;
    memset(st, 0, sizeof *st);
    st->surfaces = (int)h->s.n_surfaces;
    st->ambient_terms = h->ambient_terms;
    st->patches = (int)h->s.n_patches;
    st->elements = (int)h->s.n_elements;
    st->vertices = (int)h->s.n_vertices;
    st->skipped = h->skipped;
    st->split = h->split;
    st->clamped = h->clamped;
    st->shots = (int)h->s.stats.shots;
    st->unshot = RAD_TO_DOUBLE(rad_unshot_fraction(&h->s));
    st->saturations = h->s.stats.saturations;
    st->raster_calls = h->s.stats.raster_calls;
    st->raster_pixels = h->s.stats.raster_pixels;
    st->solved = h->solve_kind != 0;
    st->tol = h->tol;
    st->converged = h->solve_kind == 2 ||
                    (h->solve_kind == 1 && rad_unshot_fraction(&h->s) <= RAD_REAL(h->tol));
    st->backoffs = h->s.stats.backoffs;
    st->coarse_shots = h->s.stats.coarse_shots;
    st->skipped_emitters = h->skipped_emitters;
    st->tiny = h->n_tiny;
    st->pool_bytes = h->s.n_surfaces * sizeof *p->surfaces + h->s.n_patches * sizeof *p->patches +
                     h->s.n_elements * sizeof *p->elements + h->s.n_vertices * sizeof *p->vertices;
    st->work_bytes =
        RAD_WORK_BYTES(h->s.cfg.res, h->s.pass_pixels,
                       h->s.n_elements > h->s.n_vertices ? h->s.n_elements : h->s.n_vertices);
}

void sc__rgb_out(const struct sc_solver *h, const rad_rgb_t *c, double *o)
{
    o[0] = RAD_TO_DOUBLE(c->r) / h->escale;
    o[1] = RAD_TO_DOUBLE(c->g) / h->escale;
    o[2] = RAD_TO_DOUBLE(c->b) / h->escale;
}

int sc__shade_flags(struct sc_solver *h, int ambient)
{
    int f = ambient && !h->mixed ? RAD_SHADE_AMBIENT : 0;
    h->ambient_terms += f != 0;
    return f;
}

void sc_element_rgb(sc_solver *h, int e, int ambient, double rgb[3])
{
    rad_rgb_t c = {0, 0, 0};
    rad_element_radiosity(&h->s, (uint32_t)e, sc__shade_flags(h, ambient),
                          &c); /* a group's face: the group's */
    sc__rgb_out(h, &c, rgb);
}

double sc_element_area(sc_solver *h, int e)
{
    uint32_t surf = h->pools.elements[e].surface;
    if (h->tiny[surf] &&
        h->pools.surfaces[surf].n_elements == 1) /* a group's receiver holds the group's */
        return h->area[surf] / (h->scale * h->scale);
    return RAD_TO_DOUBLE(h->pools.elements[e].area) / (h->scale * h->scale);
}

void sc_vertex_pos(sc_solver *h, int v, double p[3])
{
    const rad_vec3_t *c = &h->pools.vertices[v];
    p[0] = RAD_TO_DOUBLE(c->x) / h->scale + h->off[0];
    p[1] = RAD_TO_DOUBLE(c->y) / h->scale + h->off[1];
    p[2] = RAD_TO_DOUBLE(c->z) / h->scale + h->off[2];
}

int sc_element_vertices(sc_solver *h, int e, int v[4])
{
    const rad_element_t *el = &h->pools.elements[e];
    int k, n = el->v[3] == RAD_INDEX_NONE ? 3 : 4;
    for (k = 0; k < n; k++) v[k] = (int)el->v[k];
    return n;
}

void sc_element_centroid(sc_solver *h, int e, double c[3])
{
    int v[4], n = sc_element_vertices(h, e, v), k, a;
    c[0] = c[1] = c[2] = 0.0;
    for (k = 0; k < n; k++) {
        double p[3];
        sc_vertex_pos(h, v[k], p);
        for (a = 0; a < 3; a++) c[a] += p[a] / n;
    }
}

int sc_element_tag(sc_solver *h, int e)
{
    return h->tags[h->pools.elements[e].surface];
}

int sc_set_element_rho(sc_solver *h, int e, const double rho[3], char *err, size_t errlen)
{
    rad_rgb_t r;
    int k, rc;
    for (k = 0; k < 3; k++)
        if (!(rho[k] >= 0 && rho[k] <= 1e30)) {
            snprintf(err, errlen, "element %d: reflectance must be finite and >= 0", e);
            return -1;
        }
    if (!h->erho) {
        h->erho = malloc(RAD_ELEMENT_RHO_ENTRIES(h->pools.max_elements, h->pools.max_patches) *
                         sizeof *h->erho);
        if (!h->erho) {
            snprintf(err, errlen, "out of memory for %u element reflectances",
                     (unsigned)h->pools.max_elements);
            return -1;
        }
        if ((rc = rad_use_element_reflectance(&h->s, h->erho)) < 0) {
            free(h->erho);
            h->erho = NULL;
            snprintf(err, errlen, "per-element reflectance: %s", rad_strerror(rc));
            return -1;
        }
    }
    r.r = sc__rho_ch(h, rho[0]);
    r.g = sc__rho_ch(h, rho[1]);
    r.b = sc__rho_ch(h, rho[2]);
    if ((rc = rad_set_element_reflectance(&h->s, (uint32_t)e, &r)) < 0) {
        snprintf(err, errlen, "element %d: %s", e, rad_strerror(rc));
        return -1;
    }
    return 0;
}

void sc_element_rho(sc_solver *h, int e, double rho[3])
{
    const rad_element_t *el = &h->pools.elements[e];
    const rad_rgb_t *r = h->erho ? &h->erho[e] : &h->pools.surfaces[el->surface].reflectance;
    rho[0] = RAD_TO_DOUBLE(r->r);
    rho[1] = RAD_TO_DOUBLE(r->g);
    rho[2] = RAD_TO_DOUBLE(r->b);
}

int sc__fits_core(double x)
{
    return x > -32767.0 && x < 32767.0;
}

static rad_rgb_t *shade_core(struct sc_solver *h, int ambient)
{
    rad_rgb_t *v = malloc((h->s.n_vertices ? h->s.n_vertices : 1) * sizeof *v);
    if (v) rad_shade_vertices(&h->s, sc__shade_flags(h, ambient), v, h->s.n_vertices);
    return v;
}

int sc_shade_elements(sc_solver *h, int ambient, double *rgb)
{
    rad_rgb_t *c = malloc((h->s.n_elements ? h->s.n_elements : 1) * sizeof *c);
    uint32_t e;
    if (!c) return -1;
    rad_shade_elements(&h->s, sc__shade_flags(h, ambient), c, h->s.n_elements);
    for (e = 0; e < h->s.n_elements; e++) sc__rgb_out(h, &c[e], &rgb[3 * e]);
    free(c);
    return 0;
}

int sc_shade(sc_solver *h, int ambient, double *rgb)
{
    rad_rgb_t *v = shade_core(h, ambient);
    uint32_t i;
    if (!v) return -1;
    for (i = 0; i < h->s.n_vertices; i++) sc__rgb_out(h, &v[i], &rgb[3 * i]);
    free(v);
    return 0;
}

/* Draws vertex values V through CAM into FB and Z (w * hgt each). RAD_OK or an error,
 * with err. */
static int render_core(struct sc_solver *h, const sc_camera *cam, const rad_rgb_t *v, int w,
                       int hgt, rad_rgb_t *fb, uint32_t *z, char *err, size_t errlen)
{
    rad_camera_t c;
    double t = tan(cam->fov_deg * 0.5 * 3.14159265358979323846 / 180.0);
    int a, rc = RAD_ERR_ARG,
           ok = sc__fits_core(t) && sc__fits_core(cam->up[0]) && sc__fits_core(cam->up[1]) &&
                sc__fits_core(cam->up[2]);
    /* Values past Q16.16 cannot even be converted: the core's refusal, without it. */
    for (a = 0; a < 3; a++)
        ok = ok && sc__fits_core((cam->eye[a] - h->off[a]) * h->scale) &&
             sc__fits_core((cam->target[a] - h->off[a]) * h->scale);
    if (ok) {
        sc__to_core(h, cam->eye, &c.eye);
        sc__to_core(h, cam->target, &c.target);
        c.up.x = RAD_REAL(cam->up[0]);
        c.up.y = RAD_REAL(cam->up[1]);
        c.up.z = RAD_REAL(cam->up[2]);
        c.tan_half_fov = RAD_REAL(t);
        rc = rad_render(&h->s, v, &c, fb, z, (unsigned)w, (unsigned)hgt);
    }
    if (rc < 0)
        snprintf(err, errlen,
                 "cannot render this view: %s (camera too far, degenerate, or image too large)",
                 rad_strerror(rc));
    return rc;
}

int sc_render(sc_solver *h, const sc_camera *cam, int ambient, int w, int hgt, float *rgb,
              char *err, size_t errlen)
{
    rad_rgb_t *v = shade_core(h, ambient), *fb = malloc((size_t)w * hgt * sizeof *fb);
    uint32_t *z = malloc((size_t)w * hgt * sizeof *z);
    int rc = -1;
    if (v && fb && z) {
        size_t i;
        rc = render_core(h, cam, v, w, hgt, fb, z, err, errlen);
        for (i = 0; rc >= 0 && i < (size_t)w * hgt; i++) {
            double o[3];
            sc__rgb_out(h, &fb[i], o);
            rgb[3 * i] = (float)o[0];
            rgb[3 * i + 1] = (float)o[1];
            rgb[3 * i + 2] = (float)o[2];
        }
    } else {
        snprintf(err, errlen, "out of memory for a %dx%d image", w, hgt);
    }
    free(v);
    free(fb);
    free(z);
    return rc < 0 ? -1 : 0;
}

int sc_render_values(sc_solver *h, const sc_camera *cam, const double *values, int w, int hgt,
                     double *out, unsigned char *solid, char *err, size_t errlen)
{
    rad_rgb_t *v = malloc((h->s.n_vertices ? h->s.n_vertices : 1) * sizeof *v),
              *fb = malloc((size_t)w * hgt * sizeof *fb);
    uint32_t *z = malloc((size_t)w * hgt * sizeof *z), i;
    int rc = -1;
    if (v && fb && z) {
        size_t p;
        for (i = 0; i < h->s.n_vertices; i++) {
            v[i].r = RAD_REAL(values[3 * i]);
            v[i].g = RAD_REAL(values[3 * i + 1]);
            v[i].b = RAD_REAL(values[3 * i + 2]);
        }
        rc = render_core(h, cam, v, w, hgt, fb, z, err, errlen);
        for (p = 0; rc >= 0 && p < (size_t)w * hgt; p++) {
            out[3 * p] = RAD_TO_DOUBLE(fb[p].r);
            out[3 * p + 1] = RAD_TO_DOUBLE(fb[p].g);
            out[3 * p + 2] = RAD_TO_DOUBLE(fb[p].b);
            solid[p] = z[p] > 1; /* 0: nothing drawn; 1: a crack filled from its neighbours */
        }
    } else {
        snprintf(err, errlen, "out of memory for a %dx%d image", w, hgt);
    }
    free(v);
    free(fb);
    free(z);
    return rc < 0 ? -1 : 0;
}

int sc_form_factors(sc_solver *h, int p, double *ff)
{
    rad_ff_t *f = malloc((h->s.n_elements ? h->s.n_elements : 1) * sizeof *f);
    int rc, e;
    if (!f) return -1;
    rc = rad_form_factors(&h->s, (uint32_t)p, f);
    for (e = 0; rc >= 0 && e < rc; e++) ff[e] = RAD_FF_TO_DOUBLE(f[e]);
    free(f);
    return rc < 0 ? -1 : 0;
}

uint64_t sc_checksum(sc_solver *h)
{
    uint64_t x = 1469598103934665603ull;
    uint32_t e;
    for (e = 0; e < h->s.n_elements; e++) {
        const rad_rgb_t *c = &h->pools.elements[e].radiosity;
        unsigned char b[sizeof *c];
        size_t k;
        memcpy(b, c, sizeof b);
        for (k = 0; k < sizeof b; k++) {
            x ^= b[k];
            x *= 1099511628211ull;
        }
    }
    return x;
}

void *sc_core(sc_solver *h)
{
    return &h->s;
}

int sc_patch_count(sc_solver *h)
{
    return (int)h->s.n_patches;
}

int sc_patch(sc_solver *h, int p, int *first_element, double *area)
{
    const rad_patch_t *q;
    if (p < 0 || (uint32_t)p >= h->s.n_patches) return -1;
    q = &h->pools.patches[p];
    *first_element = (int)q->first_element;
    *area = RAD_TO_DOUBLE(q->area);
    return 0;
}
