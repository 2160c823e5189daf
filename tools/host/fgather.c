/* SPDX-License-Identifier: MIT */
/* rad host glue: the final gather (see fgather.h). */
#if defined(RAD_FLOAT) && RAD_FLOAT
#include "host/float_names.h"
#endif
#include "host/fgather.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/geom.h"
#include "host/tex_render.h"
#include "rad/rad.h"

#define COS_PLANE 0.9999995 /* cos(10^-3 rad): normals of one plane (as lightmap.c) */
#define PLANE_TOL 1e-6      /* of the extent: offsets of one plane */

/* ---- gathers on threads ---- */

typedef struct {
    sc_split_fn fn;
    void *ctx;
    sc_gatherer *g;
    int first, step, rc;
} split_t;

static void *split_run(void *arg)
{
    split_t *t = arg;
    t->rc = t->fn(t->ctx, t->g, t->first, t->step);
    return NULL;
}

int sc_gather_split(sc_solver *s, int res, int threads, sc_split_fn fn, void *ctx)
{
    int n = threads > 1 ? threads : 1, i, started = 0, rc;
    split_t *t = calloc((size_t)n, sizeof *t);
    pthread_t *th = calloc((size_t)n, sizeof *th);
    rc = t && th ? 0 : -1;
    for (i = 0; rc == 0 && i < n; i++) {
        t[i].fn = fn;
        t[i].ctx = ctx;
        t[i].first = i;
        t[i].step = n;
        if (!(t[i].g = sc_gatherer_new(s, res, 0))) rc = -1;
    }
    for (i = 1; rc == 0 && i < n; i++, started++)
        if (pthread_create(&th[i], NULL, split_run, &t[i]) != 0) rc = -1;
    if (rc == 0) split_run(&t[0]);
    for (i = 1; i <= started; i++) pthread_join(th[i], NULL);
    for (i = 0; t && i < n; i++) {
        if (t[i].rc) rc = -1;
        sc_gatherer_free(t[i].g);
    }
    free(t);
    free(th);
    return rc;
}

/* ---- surfaces: frames and boundary edges ---- */

typedef struct {
    double o[3], u[3], v[3], n[3]; /* a vertex, the plane's axes, the unit normal */
    double rho[3];
    int emits;
    int first, count; /* boundary edges: edge[first .. first + count) */
    double elen;      /* longest element edge */
} fg_surface;

struct sc_fgather {
    sc_solver *s;
    const sc_poly *polys;
    void *grid;
    int res, threads, ambient, nsurf, nvert;
    fg_surface *sf;
    double (*edge)[3][2]; /* a boundary edge and its element's next vertex, in the plane */
    unsigned char (*flag)[3];
    double extent, lo[3], lift, margin;
    double *ve; /* per vertex: E, once gathered */
    unsigned char *vok;
    sc_fraction_fn progress; /* and its context: sc_fgather_progress */
    void *pctx;
};

typedef struct {
    uint32_t a, b;  /* vertex ids, a < b */
    uint32_t other; /* the element's vertex after b (inner side) */
    uint32_t elem;
} fg_edge;

static int edge_cmp(const void *x, const void *y)
{
    const fg_edge *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return p->elem < q->elem ? -1 : p->elem > q->elem;
}

static void to_plane(const fg_surface *sf, const double *p, double *q)
{
    double r[3];
    geom_sub(p, sf->o, r);
    q[0] = geom_dot(r, sf->u);
    q[1] = geom_dot(r, sf->v);
}

static void set_frame(sc_fgather *f, const rad_scene_t *core, int i)
{
    const rad_surface_t *c = &core->pools.surfaces[i];
    fg_surface *sf = &f->sf[i];
    sf->n[0] = RAD_TO_DOUBLE(c->normal.x);
    sf->n[1] = RAD_TO_DOUBLE(c->normal.y);
    sf->n[2] = RAD_TO_DOUBLE(c->normal.z);
    geom_normalize(sf->n);
    geom_any_perp(sf->n, sf->u);
    geom_cross(sf->n, sf->u, sf->v);
    sc_vertex_pos(f->s, (int)c->first_vertex, sf->o);
    sf->rho[0] = RAD_TO_DOUBLE(c->reflectance.r);
    sf->rho[1] = RAD_TO_DOUBLE(c->reflectance.g);
    sf->rho[2] = RAD_TO_DOUBLE(c->reflectance.b);
    sf->emits = c->emission.r > 0 || c->emission.g > 0 || c->emission.b > 0;
}

/* Every element edge, sorted so that an edge two elements share comes twice. */
static fg_edge *element_edges(sc_fgather *f, const rad_scene_t *core, size_t *ne)
{
    fg_edge *e = malloc((4 * (size_t)core->n_elements + 1) * sizeof *e);
    uint32_t i;
    size_t m = 0;
    if (!e) return NULL;
    for (i = 0; i < core->n_elements; i++) {
        int v[4], n = sc_element_vertices(f->s, (int)i, v), k;
        fg_surface *sf = &f->sf[core->pools.elements[i].surface];
        for (k = 0; k < n; k++) {
            uint32_t a = (uint32_t)v[k], b = (uint32_t)v[(k + 1) % n];
            double pa[3], pb[3], d[3];
            e[m].a = a < b ? a : b;
            e[m].b = a < b ? b : a;
            e[m].other = (uint32_t)v[(k + 2) % n];
            e[m++].elem = i;
            sc_vertex_pos(f->s, (int)a, pa);
            sc_vertex_pos(f->s, (int)b, pb);
            geom_sub(pa, pb, d);
            sf->elen = fmax(sf->elen, sqrt(geom_dot(d, d)));
        }
    }
    qsort(e, m, sizeof *e, edge_cmp);
    *ne = m;
    return e;
}

/* The edges met once, by surface (their elements are sorted by surface: each surface's
 * elements are a run). */
static int boundary(sc_fgather *f, const rad_scene_t *core)
{
    size_t ne = 0, i, *at;
    fg_edge *e = element_edges(f, core, &ne);
    int rc = -1, s;
    at = calloc((size_t)f->nsurf + 1, sizeof *at);
    f->edge = malloc((ne + 1) * sizeof *f->edge);
    f->flag = calloc(ne + 1, sizeof *f->flag);
    if (e && at && f->edge && f->flag) {
        for (i = 0; i < ne; i++)
            if ((i == 0 || e[i - 1].a != e[i].a || e[i - 1].b != e[i].b) &&
                (i + 1 == ne || e[i + 1].a != e[i].a || e[i + 1].b != e[i].b))
                at[core->pools.elements[e[i].elem].surface + 1]++;
        for (s = 0; s < f->nsurf; s++) {
            f->sf[s].first = (int)at[s] + (s ? f->sf[s - 1].first : 0);
            at[s] = (size_t)f->sf[s].first;
        }
        for (i = 0; i < ne; i++)
            if ((i == 0 || e[i - 1].a != e[i].a || e[i - 1].b != e[i].b) &&
                (i + 1 == ne || e[i + 1].a != e[i].a || e[i + 1].b != e[i].b)) {
                uint32_t si = core->pools.elements[e[i].elem].surface;
                const uint32_t id[3] = {e[i].a, e[i].b, e[i].other};
                int k;
                for (k = 0; k < 3; k++) {
                    double p[3];
                    sc_vertex_pos(f->s, (int)id[k], p);
                    to_plane(&f->sf[si], p, f->edge[at[si]][k]);
                }
                f->flag[at[si]][0] = 1;
                f->sf[si].count++;
                at[si]++;
            }
        rc = 0;
    }
    free(e);
    free(at);
    return rc;
}

static void scene_extent(sc_fgather *f)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, p[3];
    int v, a;
    for (v = 0; v < f->nvert; v++) {
        sc_vertex_pos(f->s, v, p);
        for (a = 0; a < 3; a++) {
            lo[a] = fmin(lo[a], p[a]);
            hi[a] = fmax(hi[a], p[a]);
        }
    }
    f->extent = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    memcpy(f->lo, lo, sizeof lo);
    f->lift = f->margin = ldexp(f->extent, -12);
}

sc_fgather *sc_fgather_new(sc_solver *s, const sc_poly *polys, int n, int res, int threads,
                           int ambient)
{
    const rad_scene_t *core = sc_core(s);
    sc_fgather *f = calloc(1, sizeof *f);
    geom_poly *g = NULL;
    double ext;
    int i, ok;
    if (!f || res < 8 || res > 1024 || (res & 1)) {
        free(f);
        return NULL;
    }
    f->s = s;
    f->res = res;
    f->threads = threads > 1 ? threads : 1;
    f->ambient = ambient;
    f->nsurf = (int)core->n_surfaces;
    f->nvert = (int)core->n_vertices;
    f->sf = calloc((size_t)f->nsurf + 1, sizeof *f->sf);
    ok = f->sf != NULL;
    for (i = 0; ok && i < f->nsurf; i++) set_frame(f, core, i);
    ok = ok && boundary(f, core) == 0;
    scene_extent(f);
    if (ok && polys && n > 0) {
        f->polys = polys;
        ok = (g = geom_polys(polys, n, &ext)) != NULL &&
             (f->grid = geom_grid_new(polys, g, n)) != NULL;
    }
    free(g);
    if (!ok) {
        sc_fgather_free(f);
        return NULL;
    }
    return f;
}

void sc_fgather_progress(sc_fgather *f, sc_fraction_fn fn, void *ctx)
{
    f->progress = fn;
    f->pctx = ctx;
}

/* Thread FIRST's progress, DONE of TOTAL of its own items: the calling thread's (0)
 * stands for all. */
static void report(const sc_fgather *f, int first, double done, double total)
{
    if (first == 0 && f->progress && total > 0) f->progress(f->pctx, done / total);
}

void sc_fgather_free(sc_fgather *f)
{
    if (!f) return;
    geom_grid_free(f->grid);
    free(f->sf);
    free(f->edge);
    free(f->flag);
    free(f->ve);
    free(f->vok);
    free(f);
}

/* ---- sample points ---- */

/* X on surface SI moved the margin in from its boundary (along its mean plane: a quad
 * may be planar only within the core's tolerance, so X keeps its own height) and
 * lifted: the point a gather for X sits at. */
static void surface_point(const sc_fgather *f, int si, const double *x, double *p)
{
    const fg_surface *sf = &f->sf[si];
    double q[2], m[2];
    int k;
    to_plane(sf, x, q);
    m[0] = q[0];
    m[1] = q[1];
    geom_tri2_inset((const double(*)[3][2])f->edge + sf->first,
                    (const unsigned char(*)[3])f->flag + sf->first, sf->count, f->margin, m);
    for (k = 0; k < 3; k++)
        p[k] = x[k] + (m[0] - q[0]) * sf->u[k] + (m[1] - q[1]) * sf->v[k] + f->lift * sf->n[k];
}

/* Vertex V of surface SI: its point, out of geometry, gathered into E. 0 or -1. */
static int vertex_gather(const sc_fgather *f, sc_gatherer *g, int si, int v, double *e)
{
    const fg_surface *sf = &f->sf[si];
    double x[3], p[3], dir[3], t;
    int k;
    sc_vertex_pos(f->s, v, x);
    surface_point(f, si, x, p);
    if (f->grid) {
        t = geom_back_ray(f->grid, f->polys, p, sf->u, sf->v, sf->elen, dir, NULL);
        if (t < HUGE_VAL)
            for (k = 0; k < 3; k++) p[k] += (t + f->margin) * dir[k];
    }
    return sc_gather_on(g, p, sf->n, si, f->ambient, e);
}

typedef struct {
    sc_fgather *f;
    const rad_scene_t *core;
} vjob_t;

static int vertex_rows(void *ctx, sc_gatherer *g, int first, int step)
{
    vjob_t *j = ctx;
    sc_fgather *f = j->f;
    int si;
    uint32_t v;
    long k = 0;
    for (si = 0; si < f->nsurf; si++) {
        const rad_surface_t *c = &j->core->pools.surfaces[si];
        for (v = c->first_vertex; v < c->first_vertex + c->n_vertices; v++, k++)
            if (k % step == first && !f->sf[si].emits)
                f->vok[v] = vertex_gather(f, g, si, (int)v, &f->ve[3 * v]) == 0;
        report(f, first, (double)k, (double)f->nvert);
    }
    return 0;
}

int sc_fgather_vertices(sc_fgather *f, const double **e, const unsigned char **ok)
{
    if (!f->ve) {
        vjob_t j;
        f->ve = calloc(3 * (size_t)f->nvert + 3, sizeof *f->ve);
        f->vok = calloc((size_t)f->nvert + 1, 1);
        j.f = f;
        j.core = sc_core(f->s);
        if (!f->ve || !f->vok || sc_gather_split(f->s, f->res, f->threads, vertex_rows, &j) < 0) {
            free(f->ve);
            free(f->vok);
            f->ve = NULL;
            f->vok = NULL;
            return -1;
        }
    }
    if (e) *e = f->ve;
    if (ok) *ok = f->vok;
    return 0;
}

int sc_vertex_colours(sc_solver *s, sc_fgather *f, int ambient, double *rgb)
{
    const rad_scene_t *core = sc_core(s);
    const double *e;
    const unsigned char *ok;
    int si, k;
    uint32_t v;
    if (sc_shade(s, ambient, rgb) < 0) return -1;
    if (!f) return 0;
    if (sc_fgather_vertices(f, &e, &ok) < 0) return -1;
    for (si = 0; si < f->nsurf; si++) {
        const rad_surface_t *c = &core->pools.surfaces[si];
        for (v = c->first_vertex; v < c->first_vertex + c->n_vertices; v++)
            for (k = 0; k < 3 && ok[v]; k++) rgb[3 * v + k] = f->sf[si].rho[k] * e[3 * v + k];
    }
    return 0;
}

/* ---- images ---- */

enum { PX_NONE, PX_GATHERED, PX_KEPT, PX_BILINEAR };

typedef struct {
    sc_fgather *f;
    int w, h, nx, ny; /* image, grid points across and down */
    const int *surf;
    double *e;
    unsigned char *state;
    double *pos; /* per pixel: the point it shows */
    long gathers[64];
    int phase;
} rjob_t;

#define POS_SCALE 32000.0 /* positions rendered as values within the renderer's 0..32767 */

/* Every pixel's point on the surface it shows: each core vertex's position rendered as
 * its value, so that a pixel gets a point of the very triangle drawn there (screen-space
 * interpolation: at most a fraction of a pixel's footprint off its centre's ray). */
static int pixel_points(rjob_t *j, const sc_camera *cam, char *err, size_t errlen)
{
    size_t n = (size_t)j->w * j->h, i;
    double *val = malloc((3 * (size_t)j->f->nvert + 3) * sizeof *val), k = POS_SCALE / j->f->extent;
    unsigned char *solid = malloc(n + 1);
    int v, a, rc = -1;
    if (!val || !solid) {
        snprintf(err, errlen, "out of memory for a %dx%d image", j->w, j->h);
    } else {
        for (v = 0; v < j->f->nvert; v++) {
            sc_vertex_pos(j->f->s, v, &val[3 * v]);
            for (a = 0; a < 3; a++) val[3 * v + a] = (val[3 * v + a] - j->f->lo[a]) * k;
        }
        rc = sc_render_values(j->f->s, cam, val, j->w, j->h, j->pos, solid, err, errlen);
        for (i = 0; rc == 0 && i < 3 * n; i++) j->pos[i] = j->f->lo[i % 3] + j->pos[i] / k;
    }
    free(val);
    free(solid);
    return rc;
}

/* Pixel I's gather, if its surface takes one: its state. */
static int pixel_gather(rjob_t *j, sc_gatherer *g, int x, int y, long *count)
{
    size_t i = (size_t)y * j->w + x;
    int si = j->surf[i];
    double p[3];
    if (j->state[i] != PX_NONE) return j->state[i];
    j->state[i] = PX_KEPT;
    if (si < 0 || j->f->sf[si].emits) return PX_KEPT;
    surface_point(j->f, si, &j->pos[3 * i], p);
    (*count)++;
    if (sc_gather_on(g, p, j->f->sf[si].n, si, j->f->ambient, &j->e[3 * i]) < 0) return PX_KEPT;
    return j->state[i] = PX_GATHERED;
}

static int grid_x(const rjob_t *j, int gx)
{
    return gx * FG_GRID < j->w - 1 ? gx * FG_GRID : j->w - 1;
}
static int grid_y(const rjob_t *j, int gy)
{
    return gy * FG_GRID < j->h - 1 ? gy * FG_GRID : j->h - 1;
}

static int same_plane(const sc_fgather *f, int a, int b)
{
    const fg_surface *p = &f->sf[a], *q = &f->sf[b];
    double r[3];
    if (a == b) return 1;
    geom_sub(q->o, p->o, r);
    return geom_dot(p->n, q->n) >= COS_PLANE && fabs(geom_dot(r, p->n)) <= PLANE_TOL * f->extent;
}

/* Cell [X0, X1] x [Y0, Y1]: one plane, its corners gathered and agreeing. */
static int smooth(const rjob_t *j, int x0, int y0, int x1, int y1)
{
    const size_t c[4] = {(size_t)y0 * j->w + x0, (size_t)y0 * j->w + x1, (size_t)y1 * j->w + x0,
                         (size_t)y1 * j->w + x1};
    double lo[3], hi[3], top = 0.0;
    int x, y, k, m, s0 = j->surf[c[0]];
    for (m = 0; m < 4; m++)
        if (j->state[c[m]] != PX_GATHERED) return 0;
    for (y = y0; y <= y1; y++)
        for (x = x0; x <= x1; x++) {
            int s = j->surf[(size_t)y * j->w + x];
            if (s < 0 || j->f->sf[s].emits || !same_plane(j->f, s0, s)) return 0;
        }
    for (k = 0; k < 3; k++) {
        lo[k] = hi[k] = j->e[3 * c[0] + k];
        for (m = 1; m < 4; m++) {
            lo[k] = fmin(lo[k], j->e[3 * c[m] + k]);
            hi[k] = fmax(hi[k], j->e[3 * c[m] + k]);
        }
        top = fmax(top, hi[k]);
    }
    for (k = 0; k < 3; k++)
        if (hi[k] - lo[k] > FG_AGREE * top) return 0;
    return 1;
}

static void bilinear(rjob_t *j, int x0, int y0, int x1, int y1, int x, int y)
{
    size_t i = (size_t)y * j->w + x;
    double a = x1 > x0 ? (double)(x - x0) / (x1 - x0) : 0.0,
           b = y1 > y0 ? (double)(y - y0) / (y1 - y0) : 0.0;
    const double *e00 = &j->e[3 * ((size_t)y0 * j->w + x0)],
                 *e10 = &j->e[3 * ((size_t)y0 * j->w + x1)];
    const double *e01 = &j->e[3 * ((size_t)y1 * j->w + x0)],
                 *e11 = &j->e[3 * ((size_t)y1 * j->w + x1)];
    int k;
    for (k = 0; k < 3; k++)
        j->e[3 * i + k] =
            (1 - b) * ((1 - a) * e00[k] + a * e10[k]) + b * ((1 - a) * e01[k] + a * e11[k]);
    j->state[i] = PX_BILINEAR;
}

/* Grid cell (GX, GY): owns its pixels but the last column and row, which are the next
 * cell's (or its own at the image's edge), so each pixel has one writer. */
static void cell(rjob_t *j, sc_gatherer *g, int gx, int gy, long *count)
{
    int x0 = grid_x(j, gx), x1 = grid_x(j, gx + 1), y0 = grid_y(j, gy), y1 = grid_y(j, gy + 1), x,
        y;
    int xe = gx + 2 >= j->nx ? x1 + 1 : x1, ye = gy + 2 >= j->ny ? y1 + 1 : y1, flat;
    if (j->nx == 1) xe = x0 + 1;
    if (j->ny == 1) ye = y0 + 1;
    flat = smooth(j, x0, y0, x1, y1);
    for (y = y0; y < ye; y++)
        for (x = x0; x < xe; x++) {
            if (j->state[(size_t)y * j->w + x] != PX_NONE) continue;
            if (flat)
                bilinear(j, x0, y0, x1, y1, x, y);
            else
                pixel_gather(j, g, x, y, count);
        }
}

static int render_rows(void *ctx, sc_gatherer *g, int first, int step)
{
    rjob_t *j = ctx;
    long *count = &j->gathers[first];
    int gx, gy, ncx = j->nx > 1 ? j->nx - 1 : 1, ncy = j->ny > 1 ? j->ny - 1 : 1;
    /* the grid's gathers, every FG_GRID^2-th pixel, as the first tenth */
    if (j->phase == 0) {
        for (gy = first; gy < j->ny; gy += step) {
            for (gx = 0; gx < j->nx; gx++) pixel_gather(j, g, grid_x(j, gx), grid_y(j, gy), count);
            report(j->f, first, 0.1 * gy, j->ny);
        }
    } else {
        for (gy = first; gy < ncy; gy += step) {
            for (gx = 0; gx < ncx; gx++) cell(j, g, gx, gy, count);
            report(j->f, first, 0.1 * ncy + 0.9 * gy, ncy);
        }
    }
    return 0;
}

/* Pixels gathered or interpolated become rho E; a crack the render filled from two
 * neighbours (left and right, else above and below) takes their mean again. */
static void compose(const rjob_t *j, float *rgb)
{
    size_t i, n = (size_t)j->w * j->h;
    int k;
    for (i = 0; i < n; i++)
        if (j->state[i] == PX_GATHERED || j->state[i] == PX_BILINEAR)
            for (k = 0; k < 3; k++)
                rgb[3 * i + k] = (float)(j->f->sf[j->surf[i]].rho[k] * j->e[3 * i + k]);
    for (i = 0; i < n; i++) {
        int x = (int)(i % (size_t)j->w), y = (int)(i / (size_t)j->w);
        size_t a, b;
        if (j->surf[i] >= 0 || (rgb[3 * i] == 0 && rgb[3 * i + 1] == 0 && rgb[3 * i + 2] == 0))
            continue;
        if (x > 0 && x + 1 < j->w && j->surf[i - 1] >= 0 && j->surf[i + 1] >= 0) {
            a = i - 1;
            b = i + 1;
        } else if (y > 0 && y + 1 < j->h && j->surf[i - j->w] >= 0 && j->surf[i + j->w] >= 0) {
            a = i - j->w;
            b = i + j->w;
        } else
            continue;
        for (k = 0; k < 3; k++) rgb[3 * i + k] = 0.5f * rgb[3 * a + k] + 0.5f * rgb[3 * b + k];
    }
}

int sc_fgather_render(sc_fgather *f, const sc_camera *cam, int w, int h, float *rgb, long *gathers,
                      char *err, size_t errlen)
{
    size_t n = (size_t)w * h;
    rjob_t j;
    int *surf = malloc((n + 1) * sizeof *surf), rc = -1, t;
    memset(&j, 0, sizeof j);
    j.f = f;
    j.w = w;
    j.h = h;
    j.nx = (w - 1 + FG_GRID - 1) / FG_GRID + 1;
    j.ny = (h - 1 + FG_GRID - 1) / FG_GRID + 1;
    j.surf = surf;
    j.e = malloc((3 * n + 3) * sizeof *j.e);
    j.state = calloc(n + 1, 1);
    j.pos = malloc((3 * n + 3) * sizeof *j.pos);
    if (!surf || !j.e || !j.state || !j.pos) {
        snprintf(err, errlen, "out of memory for a %dx%d image", w, h);
    } else if (sc_render(f->s, cam, f->ambient, w, h, rgb, err, errlen) == 0 &&
               sc_render_surfaces(f->s, cam, w, h, surf, err, errlen) == 0 &&
               pixel_points(&j, cam, err, errlen) == 0) {
        rc = sc_gather_split(f->s, f->res, f->threads > 64 ? 64 : f->threads, render_rows, &j);
        j.phase = 1;
        if (rc == 0)
            rc = sc_gather_split(f->s, f->res, f->threads > 64 ? 64 : f->threads, render_rows, &j);
        if (rc < 0)
            snprintf(err, errlen, "out of memory for gathers of resolution %d", f->res);
        else
            compose(&j, rgb);
        for (t = 0; gathers && t < 64; t++) *gathers += j.gathers[t];
    }
    free(surf);
    free(j.e);
    free(j.state);
    free(j.pos);
    return rc;
}
