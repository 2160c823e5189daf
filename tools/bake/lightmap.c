/* SPDX-License-Identifier: MIT */
/* lightmap — charts, atlas packing, texel samples, gathering, dilation. See lightmap.h. */
#include "bake/lightmap.h"

#include "bake/tset.h"
#include "host/geom.h"
#include "formats/hdr.h"
#include "formats/image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define COS_PLANE 0.9999995 /* cos(10^-3 rad): normals of one plane */
#define PLANE_TOL 1e-6      /* of the extent: a neighbour's centroid off the plane */
#define RING      1         /* texels of dilation around a chart's texels */

/* ---- charts: polygons joined across shared edges in one plane ---- */

typedef struct {
    double a[3], b[3]; /* endpoints, a before b (lexicographic) */
    int poly, k;       /* polygon and its edge k (from vertex k to k + 1) */
} edge_t;

static int cmp3(const double *x, const double *y)
{
    int i;
    for (i = 0; i < 3; i++)
        if (x[i] != y[i]) return x[i] < y[i] ? -1 : 1;
    return 0;
}

static int edge_cmp(const void *x, const void *y)
{
    const edge_t *p = x, *q = y;
    int c = cmp3(p->a, q->a);
    if (!c) c = cmp3(p->b, q->b);
    return c ? c : p->poly - q->poly;
}

static int find(int *parent, int i)
{
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

/* The polygons' edges sorted so that shared ones are consecutive; *NE of them. */
static edge_t *sorted_edges(const sc_poly *p, int n, const geom_poly *g, int *ne)
{
    edge_t *e = malloc((size_t)(4 * n + 1) * sizeof *e);
    int i, k, m = 0;
    if (!e) return NULL;
    for (i = 0; i < n; i++) {
        if (g[i].area <= 0.0) continue;
        for (k = 0; k < p[i].n; k++) {
            const double *x = p[i].v[k], *y = p[i].v[(k + 1) % p[i].n];
            int sw = cmp3(x, y) > 0;
            memcpy(e[m].a, sw ? y : x, sizeof e[m].a);
            memcpy(e[m].b, sw ? x : y, sizeof e[m].b);
            e[m].poly = i;
            e[m++].k = k;
        }
    }
    qsort(e, (size_t)m, sizeof *e, edge_cmp);
    *ne = m;
    return e;
}

static int same_plane(const geom_poly *g, int p, int q, double tol)
{
    return geom_dot(g[p].n, g[q].n) >= COS_PLANE && fabs(geom_dot(g[p].n, g[q].c) - g[p].d) <= tol;
}

/* For each run of equal edges, J in [I, END): calls pairs by mode (0: union the
 * coplanar, 1: mark edges shared within a chart interior). */
static void shared_pairs(const edge_t *e, int ne, const geom_poly *g, double tol, int *parent,
                         unsigned char *interior, int mode)
{
    int i = 0;
    while (i < ne) {
        int end = i + 1, j, k;
        while (end < ne && !cmp3(e[end].a, e[i].a) && !cmp3(e[end].b, e[i].b)) end++;
        for (j = i; j < end; j++)
            for (k = j + 1; k < end; k++) {
                int p = e[j].poly, q = e[k].poly;
                if (mode == 0 && same_plane(g, p, q, tol))
                    parent[find(parent, p)] = find(parent, q);
                if (mode == 1 && find(parent, p) == find(parent, q)) {
                    interior[4 * p + e[j].k] = 1;
                    interior[4 * q + e[k].k] = 1;
                }
            }
        i = end;
    }
}

/* Polygons' corners sorted by position, with the unit directions of the corner's two
 * edges: two coplanar polygons with a corner at one point and an edge of each leaving
 * it the same way (within 10^-3 rad) touch along a segment of both edges, whole or
 * not, as at a T-junction (a vertex of one inside an edge of the other). */
typedef struct {
    double p[3], dir[2][3];
    int poly;
} corner_t;

static int corner_cmp(const void *x, const void *y)
{
    const corner_t *p = x, *q = y;
    int c = cmp3(p->p, q->p);
    return c ? c : p->poly - q->poly;
}

static int same_way(const corner_t *x, const corner_t *y)
{
    int i, j;
    for (i = 0; i < 2; i++)
        for (j = 0; j < 2; j++)
            if (geom_dot(x->dir[i], y->dir[j]) >= COS_PLANE) return 1;
    return 0;
}

/* Unions coplanar polygons that touch along part of an edge (see corner_t). 0, or -1
 * out of memory. */
static int join_partial_edges(const sc_poly *p, int n, const geom_poly *g, double tol, int *parent)
{
    corner_t *c = malloc((size_t)(4 * n + 1) * sizeof *c);
    int i, k, m = 0, j, end;
    if (!c) return -1;
    for (i = 0; i < n; i++)
        for (k = 0; g[i].area > 0.0 && k < p[i].n; k++) {
            memcpy(c[m].p, p[i].v[k], sizeof c[m].p);
            geom_sub(p[i].v[(k + 1) % p[i].n], p[i].v[k], c[m].dir[0]);
            geom_sub(p[i].v[(k + p[i].n - 1) % p[i].n], p[i].v[k], c[m].dir[1]);
            if (!geom_normalize(c[m].dir[0])) memset(c[m].dir[0], 0, sizeof c[m].dir[0]);
            if (!geom_normalize(c[m].dir[1])) memset(c[m].dir[1], 0, sizeof c[m].dir[1]);
            c[m++].poly = i;
        }
    qsort(c, (size_t)m, sizeof *c, corner_cmp);
    for (i = 0; i < m; i = end) {
        for (end = i + 1; end < m && !cmp3(c[end].p, c[i].p); end++) {}
        for (j = i; j < end; j++)
            for (k = j + 1; k < end; k++) {
                int a = c[j].poly, b = c[k].poly;
                if (find(parent, a) != find(parent, b) && same_plane(g, a, b, tol) &&
                    same_way(&c[j], &c[k]))
                    parent[find(parent, a)] = find(parent, b);
            }
    }
    free(c);
    return 0;
}

/* ---- smooth charts: coplanar charts joined across gentle folds ---- */

/* Coplanar charts (union-find roots) as groups: their polygons, areas and the groups
 * each shares an edge with across a fold of at most the crease (CSR lists). */
typedef struct {
    int *first, *polys; /* group R's polygons: polys[first[R] .. first[R + 1]) */
    int *nfirst, *next; /* group R's neighbours: next[nfirst[R] .. nfirst[R + 1]) */
    double *area;
    int *order; /* the roots, largest area first */
    int nroots;
} groups_t;

static void groups_free(groups_t *gr)
{
    free(gr->first);
    free(gr->polys);
    free(gr->nfirst);
    free(gr->next);
    free(gr->area);
    free(gr->order);
}

typedef struct {
    double area;
    int root;
} seed_t;

static int seed_cmp(const void *x, const void *y)
{
    const seed_t *p = x, *q = y;
    if (p->area != q->area) return p->area > q->area ? -1 : 1;
    return p->root - q->root;
}

/* GR's roots in order, largest area first (then lowest index). 0 or -1. */
static int order_seeds(groups_t *gr)
{
    seed_t *sd = malloc(((size_t)gr->nroots + 1) * sizeof *sd);
    int i;
    if (!sd) return -1;
    for (i = 0; i < gr->nroots; i++) {
        sd[i].root = gr->order[i];
        sd[i].area = gr->area[gr->order[i]];
    }
    qsort(sd, (size_t)gr->nroots, sizeof *sd, seed_cmp);
    for (i = 0; i < gr->nroots; i++) gr->order[i] = sd[i].root;
    free(sd);
    return 0;
}

/* Counting sort of N items by KEY[i] in 0..M-1 (-1: left out) into FIRST (M + 1) and
 * OUT (the items, or VAL[i] when VAL). 0 or -1. */
static int bucket(const int *key, const int *val, int n, int m, int **first, int **out)
{
    int i, *fill = calloc((size_t)m + 1, sizeof *fill);
    *first = calloc((size_t)m + 2, sizeof **first);
    *out = malloc(((size_t)n + 1) * sizeof **out);
    if (!fill || !*first || !*out) {
        free(fill);
        return -1;
    }
    for (i = 0; i < n; i++)
        if (key[i] >= 0) (*first)[key[i] + 1]++;
    for (i = 0; i < m; i++) (*first)[i + 1] += (*first)[i];
    for (i = 0; i < n; i++)
        if (key[i] >= 0) (*out)[(*first)[key[i]] + fill[key[i]]++] = val ? val[i] : i;
    free(fill);
    return 0;
}

static int make_groups(const lm_atlas *a, const geom_poly *g, const edge_t *e, int ne,
                       double cos_crease, int *parent, groups_t *gr)
{
    int n = a->npolys, i = 0, j, k, m = 0, rc = -1;
    int *root = malloc((size_t)(n + 1) * sizeof *root),
        *from = malloc((size_t)(2 * ne + 1) * sizeof *from);
    int *to = malloc((size_t)(2 * ne + 1) * sizeof *to);
    memset(gr, 0, sizeof *gr);
    gr->area = calloc((size_t)n + 1, sizeof *gr->area);
    gr->order = malloc((size_t)(n + 1) * sizeof *gr->order);
    if (root && from && to && gr->area && gr->order) {
        for (j = 0; j < n; j++) {
            root[j] = g[j].area > 0.0 ? find(parent, j) : -1;
            if (root[j] >= 0) gr->area[root[j]] += g[j].area;
            if (root[j] == j) gr->order[gr->nroots++] = j;
        }
        while (i < ne) { /* each run of equal edges: its pairs across a gentle fold */
            int end = i + 1;
            while (end < ne && !cmp3(e[end].a, e[i].a) && !cmp3(e[end].b, e[i].b)) end++;
            for (j = i; j < end; j++)
                for (k = j + 1; k < end; k++) {
                    int p = e[j].poly, q = e[k].poly;
                    if (root[p] == root[q] || geom_dot(g[p].n, g[q].n) < cos_crease) continue;
                    from[m] = root[p], to[m++] = root[q];
                    from[m] = root[q], to[m++] = root[p];
                }
            i = end;
        }
        if (order_seeds(gr) == 0 && bucket(root, NULL, n, n, &gr->first, &gr->polys) == 0 &&
            bucket(from, to, m, n, &gr->nfirst, &gr->next) == 0)
            rc = 0;
    }
    free(root);
    free(from);
    free(to);
    return rc;
}

/* Polygon P's fan triangles projected on the plane of axes U, V into T (n - 2 of them). */
static int project_fan(const sc_poly *p, const double *u, const double *v, double t[2][3][2])
{
    int k, j;
    for (k = 1; k + 1 < p->n; k++)
        for (j = 0; j < 3; j++) {
            const double *x = p->v[j == 0 ? 0 : k + j - 1];
            t[k - 1][j][0] = geom_dot(x, u);
            t[k - 1][j][1] = geom_dot(x, v);
        }
    return p->n - 2;
}

/* Group R's triangles on the plane: added to S (ADD), or 1 when one overlaps S's (0). */
static int group_on_plane(const lm_atlas *a, const groups_t *gr, int r, const double *u,
                          const double *v, tset *s, int add)
{
    double t[2][3][2];
    int i, k, m;
    for (i = gr->first[r]; i < gr->first[r + 1]; i++) {
        m = project_fan(&a->polys[gr->polys[i]], u, v, t);
        for (k = 0; k < m; k++)
            if (add ? tset_add(s, (const double(*)[2])t[k]) != 0
                    : tset_hits(s, (const double(*)[2])t[k]))
                return 1;
    }
    return 0;
}

/* Grows the chart of seed group SEED: breadth first across gentle folds, a neighbour
 * group joining when every polygon of it lies within the crease of the seed's normal
 * and its projection on the seed's plane overlaps none of the chart's. Each member's
 * CN (by polygon) is the seed's normal, the chart's plane. 0 or -1 out of memory. */
static int grow_chart(const lm_atlas *a, const geom_poly *g, const groups_t *gr, int seed,
                      double cos_crease, int *parent, int *queue, int *seen, unsigned char *joined,
                      tset *s, double (*cn)[3])
{
    double u[3], v[3];
    const double *n = g[seed].n;
    int head = 0, tail = 0, i, j;
    geom_any_perp(n, u);
    geom_cross(n, u, v);
    tset_clear(s);
    queue[tail++] = seed;
    seen[seed] = seed;
    joined[seed] = 1;
    if (group_on_plane(a, gr, seed, u, v, s, 1)) return -1;
    while (head < tail) {
        int r = queue[head++];
        for (i = gr->first[r]; i < gr->first[r + 1]; i++) memcpy(cn[gr->polys[i]], n, sizeof cn[0]);
        for (j = gr->nfirst[r]; j < gr->nfirst[r + 1]; j++) {
            int q = gr->next[j];
            if (seen[q] == seed || joined[q] || geom_dot(g[q].n, n) < cos_crease) continue;
            seen[q] = seed; /* tried for this chart once */
            if (group_on_plane(a, gr, q, u, v, s, 0)) continue;
            if (group_on_plane(a, gr, q, u, v, s, 1)) return -1;
            parent[q] = seed;
            joined[q] = 1;
            queue[tail++] = q;
        }
    }
    return 0;
}

/* Joins coplanar charts (the roots of PARENT) into smooth ones, seeds largest first;
 * every polygon's chart normal into CN. 0 or -1 out of memory. */
static int merge_smooth(const lm_atlas *a, const geom_poly *g, const edge_t *e, int ne,
                        double cos_crease, int *parent, double (*cn)[3])
{
    groups_t gr;
    int n = a->npolys, i, rc = make_groups(a, g, e, ne, cos_crease, parent, &gr);
    int *queue = malloc((size_t)(n + 1) * sizeof *queue),
        *seen = malloc((size_t)(n + 1) * sizeof *seen);
    unsigned char *joined = calloc((size_t)n + 1, 1);
    double cell = 0.0;
    tset *s;
    for (i = 0; i < n; i++) cell += sqrt(g[i].area);
    s = tset_new(fmax(2.0 * cell / n, a->extent * 1e-6), PLANE_TOL * a->extent);
    if (!queue || !seen || !joined || !s) rc = -1;
    for (i = 0; rc == 0 && i < n; i++) seen[i] = -1;
    for (i = 0; rc == 0 && i < gr.nroots; i++) {
        int r = gr.order[i];
        if (!joined[r])
            rc = grow_chart(a, g, &gr, r, cos_crease, parent, queue, seen, joined, s, cn);
    }
    groups_free(&gr);
    free(queue);
    free(seen);
    free(joined);
    tset_free(s);
    return rc;
}

/* Chart ids in order of each chart's first polygon, and the polygons by chart. */
static int number_charts(lm_atlas *a, int *parent)
{
    int i, n = a->npolys, nc = 0, *count, *id = malloc((size_t)(n + 1) * sizeof *id);
    if (!id) return -1;
    for (i = 0; i < n; i++) id[i] = -1;
    for (i = 0; i < n; i++) {
        int r;
        if (a->poly_chart[i] < 0) continue;
        r = find(parent, i);
        if (id[r] < 0) id[r] = nc++;
        a->poly_chart[i] = id[r];
    }
    free(id);
    a->ncharts = nc;
    a->charts = calloc((size_t)(nc + 1), sizeof *a->charts);
    count = calloc((size_t)(nc + 1), sizeof *count);
    if (!a->charts || !count) {
        free(count);
        return -1;
    }
    for (i = 0; i < n; i++)
        if (a->poly_chart[i] >= 0) a->charts[a->poly_chart[i]].count++;
    for (i = 1; i < nc; i++) a->charts[i].first = a->charts[i - 1].first + a->charts[i - 1].count;
    for (i = 0; i < n; i++)
        if (a->poly_chart[i] >= 0) {
            int c = a->poly_chart[i];
            a->chart_polys[a->charts[c].first + count[c]++] = i;
        }
    free(count);
    return 0;
}

/* ---- chart frames: the chart's plane's axes, u along the longest boundary edge ---- */

typedef struct {
    double smin, tmin, w, h, d; /* extent on the axes (world units) and plane offset */
} extent_t;

static void chart_axes(const lm_atlas *a, const unsigned char *interior, lm_chart *c)
{
    double best = -1.0, e[3];
    int i, k;
    for (i = 0; i < c->count; i++) {
        const sc_poly *q = &a->polys[a->chart_polys[c->first + i]];
        int p = a->chart_polys[c->first + i];
        for (k = 0; k < q->n; k++) {
            double len;
            geom_sub(q->v[(k + 1) % q->n], q->v[k], e);
            len = geom_dot(e, e) * (interior[4 * p + k] ? 0.25 : 1.0); /* boundary edges first */
            if (len > best) {
                best = len;
                geom_reject(e, c->n, c->u);
            }
        }
    }
    if (!geom_normalize(c->u)) geom_any_perp(c->n, c->u);
    geom_cross(c->n, c->u, c->v);
}

static void chart_extent(const lm_atlas *a, const lm_chart *c, extent_t *x)
{
    double smax = -HUGE_VAL, tmax = -HUGE_VAL, dsum = 0.0;
    int i, k, nv = 0;
    x->smin = x->tmin = HUGE_VAL;
    for (i = 0; i < c->count; i++) {
        const sc_poly *q = &a->polys[a->chart_polys[c->first + i]];
        for (k = 0; k < q->n; k++, nv++) {
            double s = geom_dot(q->v[k], c->u), t = geom_dot(q->v[k], c->v);
            x->smin = fmin(x->smin, s);
            x->tmin = fmin(x->tmin, t);
            smax = fmax(smax, s);
            tmax = fmax(tmax, t);
            dsum += geom_dot(q->v[k], c->n);
        }
    }
    x->w = smax - x->smin;
    x->h = tmax - x->tmin;
    x->d = dsum / nv;
}

/* ---- packing: shelves of rectangles sorted by height ---- */

typedef struct {
    int w, h, id;
} rect_t;

static int rect_cmp(const void *x, const void *y)
{
    const rect_t *p = x, *q = y;
    if (p->h != q->h) return q->h - p->h;
    if (p->w != q->w) return q->w - p->w;
    return p->id - q->id;
}

/* Texels of a rectangle along an extent of X world units at texel T: the chart's
 * texels start at EDGE = PAD + RING, so its far end lies in texel EDGE + floor(X / T),
 * and a ring and the gutter follow. 0 when it cannot fit an atlas of N. */
static int rect_len(double x, double t, int pad, int n)
{
    double k = floor(x / t) + 2 * (pad + RING) + 1;
    return k <= n ? (int)k : 0;
}

/* Lays the rectangles at texel T into the atlas; 0, or -1 when they do not fit. */
static int pack(lm_atlas *a, const extent_t *x, rect_t *r, double t)
{
    int i, n = a->size, cx = 0, cy = 0, shelf = 0;
    for (i = 0; i < a->ncharts; i++) {
        r[i].w = rect_len(x[i].w, t, a->padding, n);
        r[i].h = rect_len(x[i].h, t, a->padding, n);
        r[i].id = i;
        if (!r[i].w || !r[i].h) return -1;
    }
    qsort(r, (size_t)a->ncharts, sizeof *r, rect_cmp);
    for (i = 0; i < a->ncharts; i++) {
        lm_chart *c = &a->charts[r[i].id];
        if (cx + r[i].w > n) {
            cx = 0;
            cy += shelf;
            shelf = 0;
        }
        if (cy + r[i].h > n) return -1;
        if (!shelf) shelf = r[i].h;
        c->x = cx;
        c->y = cy;
        c->w = r[i].w;
        c->h = r[i].h;
        cx += r[i].w;
    }
    return 0;
}

/* The texel size: given, or the smallest that packs (doubling from the area's bound,
 * then halving the interval 20 times). 0, or -1 with err. */
static int choose_texel(lm_atlas *a, const extent_t *x, rect_t *r, double given, char *err,
                        size_t errlen)
{
    double area = 0.0, lo, hi;
    int i;
    if (given > 0.0) {
        a->texel = given;
        if (pack(a, x, r, given) == 0) return 0;
        snprintf(err, errlen,
                 "an atlas of %dx%d texels cannot fit %d charts at a texel of %g (use a larger "
                 "size or texel)",
                 a->size, a->size, a->ncharts, given);
        return -1;
    }
    for (i = 0; i < a->ncharts; i++) area += x[i].w * x[i].h;
    lo = sqrt(area) / a->size;
    if (!(lo > 0.0)) lo = a->extent / a->size;
    for (hi = lo, i = 0; pack(a, x, r, hi) != 0; i++, hi *= 2.0) {
        lo = hi;
        if (i == 64) {
            snprintf(err, errlen,
                     "an atlas of %dx%d texels cannot fit %d charts (each needs at least %dx%d "
                     "texels with "
                     "--lightmap-pad %d)",
                     a->size, a->size, a->ncharts, 2 * (a->padding + RING) + 1,
                     2 * (a->padding + RING) + 1, a->padding);
            return -1;
        }
    }
    for (i = 0; i < 20; i++) {
        double mid = 0.5 * (lo + hi);
        if (pack(a, x, r, mid) == 0)
            hi = mid;
        else
            lo = mid;
    }
    a->texel = hi;
    return pack(a, x, r, hi);
}

/* ---- texel samples ---- */

typedef struct {
    double p[3][2];     /* a triangle in the rectangle's texel coordinates */
    unsigned char b[3]; /* edge k (p[k] to p[k + 1]) is on the chart's boundary */
} tri_t;

/* The point of T nearest C, moved M texels in from its boundary edges; its distance
 * from C before the move into *DIST. */
static void tri_sample(const tri_t *t, const double c[2], double m, double q[2], double *dist)
{
    geom_tri2_closest(t->p, c, q);
    *dist = hypot(q[0] - c[0], q[1] - c[1]);
    geom_tri2_inset(&t->p, &t->b, 1, m, q);
}

/* Samples the texels of chart C within a texel of triangle T (those it touches, and
 * their ring), keeping each texel's nearest sample; BEST (the rectangle's texels)
 * holds the distances so far. */
static void raster_tri(lm_atlas *a, const lm_chart *c, const tri_t *tri, int poly, double m,
                       float *best)
{
    /* A copy: GCC 12's -Wstringop-overflow under -fsanitize=undefined (make check's soak
     * build) took T's corners for a region of 16 bytes when read through the pointer. */
    const tri_t copy = *tri, *t = &copy;
    double lo[2], hi[2];
    int i, j, k;
    for (k = 0; k < 2; k++) { /* clamped to the rectangle (a file's UVs may lie far off) */
        double len = k ? c->h : c->w;
        lo[k] = floor(fmin(t->p[0][k], fmin(t->p[1][k], t->p[2][k]))) - RING;
        hi[k] = floor(fmax(t->p[0][k], fmax(t->p[1][k], t->p[2][k]))) + RING;
        lo[k] = fmin(fmax(lo[k], 0.0), len);
        hi[k] = fmin(fmax(hi[k], -1.0), len - 1.0);
    }
    for (j = (int)lo[1]; j <= (int)hi[1]; j++)
        for (i = (int)lo[0]; i <= (int)hi[0]; i++) {
            double ctr[2] = {i + 0.5, j + 0.5}, q[2], d;
            size_t at;
            if (i < 0 || j < 0 || i >= c->w || j >= c->h ||
                !geom_tri2_touches_box(t->p, i - RING, j - RING, 1 + 2 * RING))
                continue;
            tri_sample(t, ctr, m, q, &d);
            if (d >= best[j * c->w + i]) continue;
            best[j * c->w + i] = (float)d;
            at = (size_t)(c->y + j) * a->size + (size_t)(c->x + i);
            a->sample[2 * at] = (float)q[0];
            a->sample[2 * at + 1] = (float)q[1];
            a->poly[at] = poly;
        }
}

static void to_rect(const lm_chart *c, double t, const double *p, double *st)
{
    double r[3];
    geom_sub(p, c->o, r);
    st[0] = geom_dot(r, c->u) / t;
    st[1] = geom_dot(r, c->v) / t;
}

/* Every polygon of chart C as triangles (a fan) rasterised into its rectangle. */
static int raster_chart(lm_atlas *a, const lm_chart *c, const unsigned char *interior, double m)
{
    float *best = malloc((size_t)c->w * c->h * sizeof *best);
    int i, k;
    if (!best) return -1;
    for (k = 0; k < c->w * c->h; k++) best[k] = HUGE_VALF;
    for (i = 0; i < c->count; i++) {
        int p = a->chart_polys[c->first + i];
        const sc_poly *q = &a->polys[p];
        for (k = 1; k + 1 < q->n; k++) {
            tri_t t;
            to_rect(c, a->texel, q->v[0], t.p[0]);
            to_rect(c, a->texel, q->v[k], t.p[1]);
            to_rect(c, a->texel, q->v[k + 1], t.p[2]);
            t.b[0] = k == 1 && !interior[4 * p];
            t.b[1] = !interior[4 * p + k];
            t.b[2] = k + 2 == q->n && !interior[4 * p + q->n - 1];
            raster_tri(a, c, &t, p, m, best);
        }
    }
    free(best);
    return 0;
}

/* World point of rectangle position ST of chart C on polygon POLY: the chart's plane's
 * point moved along the chart's normal onto the polygon's plane (a chart joined across
 * folds is a height field over its plane: n_poly . n_chart >= the crease's cosine > 0),
 * lifted off it by LIFT along the polygon's normal. */
static void surface_point(const lm_atlas *a, const lm_chart *c, int poly, const double *st,
                          double lift, double *p)
{
    const double *pl = &a->planes[4 * (size_t)poly];
    double h;
    int k;
    for (k = 0; k < 3; k++) p[k] = c->o[k] + a->texel * (st[0] * c->u[k] + st[1] * c->v[k]);
    h = (pl[3] - geom_dot(pl, p)) / geom_dot(pl, c->n);
    for (k = 0; k < 3; k++) p[k] += h * c->n[k] + lift * pl[k];
}

/* World point of position ST on frame C's plane (a file UV triangle's frame), lifted off
 * it by LIFT along its normal. */
static void rect_point(const lm_atlas *a, const lm_chart *c, const double *st, double lift,
                       double *p)
{
    int k;
    for (k = 0; k < 3; k++)
        p[k] = c->o[k] + a->texel * (st[0] * c->u[k] + st[1] * c->v[k]) + lift * c->n[k];
}

static double lift_of(const lm_atlas *a)
{
    return ldexp(a->extent, -12);
}
static double margin_of(const lm_atlas *a)
{
    return fmax(a->texel / 8.0, ldexp(a->extent, -12));
}

/* A sample whose rays along the plane meet a back face first is inside geometry: it
 * moves past the nearest such face by the margin. 1 when the rays met no face at all. */
static int push_out(lm_atlas *a, const lm_chart *c, int poly, float *st)
{
    double s[2] = {st[0], st[1]}, p[3], best, dir[3], met, u[3], v[3];
    surface_point(a, c, poly, s, lift_of(a), p);
    geom_reject(c->u, &a->planes[4 * (size_t)poly], u); /* the rays along the polygon's plane */
    if (!geom_normalize(u)) geom_any_perp(&a->planes[4 * (size_t)poly], u);
    geom_cross(&a->planes[4 * (size_t)poly], u, v);
    best = geom_back_ray(a->grid, a->polys, p, u, v, 0.75 * a->texel, dir, &met);
    if (!(best < HUGE_VAL)) return !(met < HUGE_VAL);
    best += margin_of(a);
    st[0] = (float)(s[0] + best / a->texel * geom_dot(dir, c->u));
    st[1] = (float)(s[1] + best / a->texel * geom_dot(dir, c->v));
    return 0;
}

static int place_samples(lm_atlas *a, const unsigned char *interior)
{
    int i, x, y;
    double m = margin_of(a) / a->texel;
    for (i = 0; i < a->ncharts; i++) {
        lm_chart *c = &a->charts[i];
        for (y = 0; y < c->h; y++)
            for (x = 0; x < c->w; x++)
                a->owner[(size_t)(c->y + y) * a->size + (size_t)(c->x + x)] = i;
        if (raster_chart(a, c, interior, m) != 0) return -1;
        for (y = 0; y < c->h; y++)
            for (x = 0; x < c->w; x++) {
                size_t at = (size_t)(c->y + y) * a->size + (size_t)(c->x + x);
                float *st = &a->sample[2 * at];
                /* free: no face within the rays' reach, and the sample at the centre (the
                 * float of x + 0.5 is exact) */
                if (!isnan(st[0]) && push_out(a, c, a->poly[at], st) && st[0] == x + 0.5f &&
                    st[1] == y + 0.5f)
                    a->state[at] = LM_FREE;
            }
    }
    return 0;
}

/* ---- building ---- */

static int alloc_atlas(lm_atlas *a, const geom_poly *g, int n)
{
    size_t t = (size_t)a->size * a->size, i;
    int k;
    a->poly_chart = calloc((size_t)n + 1, sizeof *a->poly_chart);
    a->chart_polys = calloc((size_t)n + 1, sizeof *a->chart_polys);
    a->owner = malloc(t * sizeof *a->owner);
    a->sample = malloc(2 * t * sizeof *a->sample);
    a->rgb = calloc(3 * t, sizeof *a->rgb);
    a->poly = malloc(t * sizeof *a->poly);
    a->state = calloc(t, 1);
    a->block = calloc(t, 1);
    a->planes = malloc(4 * ((size_t)n + 1) * sizeof *a->planes);
    if (!a->planes || !a->poly_chart || !a->chart_polys || !a->owner || !a->sample || !a->rgb ||
        !a->poly || !a->state || !a->block)
        return -1;
    for (k = 0; k < n; k++) {
        memcpy(&a->planes[4 * (size_t)k], g[k].n, sizeof g[k].n);
        a->planes[4 * (size_t)k + 3] = g[k].d;
    }
    for (i = 0; i < t; i++) {
        a->owner[i] = a->poly[i] = -1;
        a->sample[2 * i] = a->sample[2 * i + 1] = NAN;
    }
    return 0;
}

/* Charts of the polygons: union-find over coplanar shared edges, whole or in part, then
 * coplanar charts joined across gentle folds (COS_CREASE); each chart's normal set. */
static int make_charts(lm_atlas *a, const geom_poly *g, double cos_crease, unsigned char *interior)
{
    int ne = 0, i, rc = -1, *parent = malloc((size_t)(a->npolys + 1) * sizeof *parent);
    double(*cn)[3] = malloc((size_t)(a->npolys + 1) * sizeof *cn);
    edge_t *e = parent && cn ? sorted_edges(a->polys, a->npolys, g, &ne) : NULL;
    if (e) {
        for (i = 0; i < a->npolys; i++) {
            parent[i] = i;
            a->poly_chart[i] = g[i].area > 0.0 ? 0 : -1;
        }
        shared_pairs(e, ne, g, PLANE_TOL * a->extent, parent, interior, 0);
        rc = join_partial_edges(a->polys, a->npolys, g, PLANE_TOL * a->extent, parent);
        if (rc == 0) rc = merge_smooth(a, g, e, ne, cos_crease, parent, cn);
        shared_pairs(e, ne, g, PLANE_TOL * a->extent, parent, interior, 1);
        if (rc == 0) rc = number_charts(a, parent);
        for (i = 0; rc == 0 && i < a->ncharts; i++)
            memcpy(a->charts[i].n, cn[a->chart_polys[a->charts[i].first]], sizeof a->charts[i].n);
    }
    free(e);
    free(parent);
    free(cn);
    return rc;
}

static int layout(lm_atlas *a, const unsigned char *interior, double texel, char *err,
                  size_t errlen)
{
    extent_t *x = malloc((size_t)(a->ncharts + 1) * sizeof *x);
    rect_t *r = malloc((size_t)(a->ncharts + 1) * sizeof *r);
    int i, k, rc = -1;
    if (!x || !r) {
        snprintf(err, errlen, "out of memory for %d charts", a->ncharts);
    } else {
        for (i = 0; i < a->ncharts; i++) {
            chart_axes(a, interior, &a->charts[i]);
            chart_extent(a, &a->charts[i], &x[i]);
        }
        rc = choose_texel(a, x, r, texel, err, errlen);
        for (i = 0; rc == 0 && i < a->ncharts; i++)
            for (k = 0; k < 3; k++)
                a->charts[i].o[k] =
                    (x[i].smin - (a->padding + RING) * a->texel) * a->charts[i].u[k] +
                    (x[i].tmin - (a->padding + RING) * a->texel) * a->charts[i].v[k] +
                    x[i].d * a->charts[i].n[k];
    }
    free(x);
    free(r);
    return rc;
}

/* The cosine of the crease (lm_opts.crease); above 1 (no fold joins) when negative. */
static double cos_crease(const lm_opts *o)
{
    double deg = o->crease > 0.0 ? o->crease : o->crease < 0.0 ? -1.0 : LM_CREASE;
    return deg < 0.0 ? 2.0 : cos(deg * (3.14159265358979323846 / 180.0));
}

/* The atlas emptied and O's size, tolerance, crease and padding checked and kept, for
 * N POLYS. 0, or -1 with err. */
static int setup(lm_atlas *a, const sc_poly *polys, int n, const lm_opts *o, char *err,
                 size_t errlen)
{
    memset(a, 0, sizeof *a);
    if (o->size < 1 || o->size > LM_MAX_SIZE) {
        snprintf(err, errlen, "a lightmap size of %d is outside 1..%d", o->size, LM_MAX_SIZE);
        return -1;
    }
    if (!(o->tol >= 0.0 && o->tol <= 1.0)) {
        snprintf(err, errlen, "a lightmap tolerance of %g is outside 0..1", o->tol);
        return -1;
    }
    if (!(o->crease <= LM_MAX_CREASE)) {
        snprintf(err, errlen,
                 "a chart crease of %g degrees is outside 0..%d (negative: coplanar charts only)",
                 o->crease, LM_MAX_CREASE);
        return -1;
    }
    if (n < 1 || !(o->texel >= 0.0) || !isfinite(o->texel)) {
        snprintf(err, errlen,
                 n < 1 ? "no polygons to bake" : "a texel size must be a positive number");
        return -1;
    }
    a->size = o->size;
    a->tol = o->tol;
    a->padding = o->padding < 0      ? 0
                 : o->padding        ? o->padding
                 : o->size / 128 < 1 ? 1
                                     : o->size / 128;
    if (!o->padding && a->padding > LM_PADDING) a->padding = LM_PADDING;
    if (a->padding > LM_MAX_PADDING) {
        snprintf(err, errlen, "a lightmap padding of %d is outside 0..%d", o->padding,
                 LM_MAX_PADDING);
        return -1;
    }
    a->npolys = n;
    a->polys = polys;
    return 0;
}

int lm_build(lm_atlas *a, const sc_poly *polys, int n, const lm_opts *o, char *err, size_t errlen)
{
    geom_poly *g = NULL;
    unsigned char *interior = NULL;
    int rc = -1;
    if (setup(a, polys, n, o, err, errlen) != 0) return -1;
    g = geom_polys(polys, n, &a->extent);
    interior = calloc(4 * (size_t)n, 1);
    if (g && !(a->extent > 0.0 && isfinite(a->extent))) {
        snprintf(err, errlen, "the polygons have no extent (or one that is not finite)");
        rc = -2;
    } else if (g && interior && alloc_atlas(a, g, n) == 0 &&
               make_charts(a, g, cos_crease(o), interior) == 0 &&
               (a->grid = geom_grid_new(polys, g, n)) != NULL) {
        rc = 0;
    }
    if (rc == -1)
        snprintf(err, errlen, "out of memory for a %dx%d lightmap of %d polygons", o->size, o->size,
                 n);
    if (rc == 0) rc = layout(a, interior, o->texel, err, errlen);
    if (rc == 0 && place_samples(a, interior) != 0) {
        snprintf(err, errlen, "out of memory for a %dx%d lightmap", o->size, o->size);
        rc = -1;
    }
    free(g);
    free(interior);
    if (rc != 0) lm_free(a);
    return rc < 0 ? -1 : 0;
}

/* ---- the file's UVs (lm_build_file) ---- */

#define UV_FLAT \
    1e-12 /* a UV triangle whose doubled area is below this of its sides'
                       * squares has none: its affine map would divide by about 0 */

static double cross2d(const double *o, const double *x, const double *y)
{
    return (x[0] - o[0]) * (y[1] - o[1]) - (x[1] - o[1]) * (y[0] - o[0]);
}

/* Twice the area (signed) of polygon I's fan triangle K in texels, 0 when it has none
 * (UV_FLAT) or a UV is not finite. */
static double uv_det(const lm_atlas *a, int i, int k)
{
    const double *uv = &a->file_uv[8 * (size_t)i];
    const double *x = uv + 2 * (k + 1), *y = uv + 2 * (k + 2);
    double det, scale;
    if (k + 2 >= a->polys[i].n) return 0.0;
    det = cross2d(uv, x, y);
    scale = (x[0] - uv[0]) * (x[0] - uv[0]) + (x[1] - uv[1]) * (x[1] - uv[1]) +
            (y[0] - uv[0]) * (y[0] - uv[0]) + (y[1] - uv[1]) * (y[1] - uv[1]);
    return isfinite(det) && fabs(det) > UV_FLAT * scale ? det : 0.0;
}

/* Polygon I's fan triangle K (corners 0, K + 1, K + 2) as a frame (lm_atlas.frames) on
 * its plane of unit normal N: world = o + x Wx + y Wy solves the map from its UV
 * corners to its world corners; u, v = Wx, Wy over the texel size T. None (count 0)
 * for a triangle of no UV area or of no world area (a quad with three corners on a
 * line): its map could not be inverted. */
static void file_frame(lm_atlas *a, int i, int k, const double *n)
{
    const double *uv = &a->file_uv[8 * (size_t)i], *x = uv + 2 * (k + 1), *y = uv + 2 * (k + 2);
    const sc_poly *q = &a->polys[i];
    lm_chart *f = &a->frames[2 * (size_t)i + k];
    double det = uv_det(a, i, k), e1[3], e2[3], c[3];
    int j;
    memset(f, 0, sizeof *f);
    if (det == 0.0) return;
    geom_sub(q->v[k + 1], q->v[0], e1);
    geom_sub(q->v[k + 2], q->v[0], e2);
    geom_cross(e1, e2, c);
    if (!(geom_dot(c, c) > 0.0)) return;
    for (j = 0; j < 3; j++) {
        double wx = ((y[1] - uv[1]) * e1[j] - (x[1] - uv[1]) * e2[j]) / det;
        double wy = ((x[0] - uv[0]) * e2[j] - (y[0] - uv[0]) * e1[j]) / det;
        f->u[j] = wx / a->texel;
        f->v[j] = wy / a->texel;
        f->o[j] = q->v[0][j] - uv[0] * wx - uv[1] * wy;
        f->n[j] = n[j];
    }
    f->count = 1;
}

/* The frame of polygon P's fan triangle that holds atlas position ST: of a quad, by the
 * side of its diagonal (corner 0 to 2) ST lies on; the other when that one has none. */
static const lm_chart *file_tri(const lm_atlas *a, int p, const double *st)
{
    const double *uv = &a->file_uv[8 * (size_t)p];
    const lm_chart *f = &a->frames[2 * (size_t)p];
    int k = a->polys[p].n == 4 && cross2d(uv, uv + 4, uv + 2) * cross2d(uv, uv + 4, st) < 0.0;
    return f[k].count ? &f[k] : &f[!k];
}

/* World point P on frame F (on its plane) as an atlas position: the normal equations
 * of o + T (x u + y v) = P. */
static void frame_inverse(const lm_atlas *a, const lm_chart *f, const double *p, double *xy)
{
    double r[3], uu = geom_dot(f->u, f->u), uv = geom_dot(f->u, f->v), vv = geom_dot(f->v, f->v),
                 bu, bv;
    double det = uu * vv - uv * uv;
    geom_sub(p, f->o, r);
    bu = geom_dot(r, f->u) / a->texel;
    bv = geom_dot(r, f->v) / a->texel;
    xy[0] = (vv * bu - uv * bv) / det;
    xy[1] = (uu * bv - uv * bu) / det;
}

static int file_uv_of(const lm_atlas *a, int poly, const double p[3], double xy[2])
{
    const lm_chart *f = &a->frames[2 * (size_t)poly], *g;
    if (!f->count) f++;
    frame_inverse(a, f, p, xy);
    g = file_tri(a, poly, xy);
    if (g != f) frame_inverse(a, g, p, xy);
    return 0;
}

static void file_corner_uvs(const obj_scene *sc, double *uv)
{
    int c;
    for (c = 0; c < sc->nindices; c++) {
        const obj_vec2 *w = sc->uv2 ? &sc->uv2[c] : NULL;
        int ok = w && isfinite(w->u) && isfinite(w->v);
        uv[2 * (size_t)c] = ok ? w->u : 0.0;
        uv[2 * (size_t)c + 1] = ok ? 1.0 - w->v : 0.0;
    }
}

/* Edges X and Y (the same world endpoints) have the same UVs at each end. */
static int same_uv_edge(const lm_atlas *a, const edge_t *x, const edge_t *y)
{
    const sc_poly *p = &a->polys[x->poly], *q = &a->polys[y->poly];
    const double *u = &a->file_uv[8 * (size_t)x->poly], *w = &a->file_uv[8 * (size_t)y->poly];
    int x0 = x->k, x1 = (x->k + 1) % p->n, y0 = y->k, y1 = (y->k + 1) % q->n;
    if (cmp3(p->v[x0], q->v[y0])) {
        int t = y0;
        y0 = y1;
        y1 = t;
    }
    return u[2 * x0] == w[2 * y0] && u[2 * x0 + 1] == w[2 * y0 + 1] && u[2 * x1] == w[2 * y1] &&
           u[2 * x1 + 1] == w[2 * y1 + 1];
}

/* The file's charts: polygons unioned across edges whose world and UV endpoints are
 * the same, those edges flagged in INTERIOR. 0, or -1 out of memory. */
static int file_joins(lm_atlas *a, const geom_poly *g, int *parent, unsigned char *interior)
{
    int ne = 0, i, end, j, k;
    edge_t *e = sorted_edges(a->polys, a->npolys, g, &ne);
    if (!e) return -1;
    for (i = 0; i < a->npolys; i++) parent[i] = i;
    for (i = 0; i < ne; i = end) {
        for (end = i + 1; end < ne && !cmp3(e[end].a, e[i].a) && !cmp3(e[end].b, e[i].b); end++) {}
        for (j = i; j < end; j++)
            for (k = j + 1; k < end; k++)
                if (same_uv_edge(a, &e[j], &e[k])) {
                    parent[find(parent, e[j].poly)] = find(parent, e[k].poly);
                    interior[4 * e[j].poly + e[j].k] = interior[4 * e[k].poly + e[k].k] = 1;
                }
    }
    free(e);
    return 0;
}

/* A ray move of the sample ST on frame F out of geometry, as push_out's: the rays
 * along two unit axes of the plane, 3/4 of the triangle's own texel long, the move
 * solved back to atlas texels. 1 when the rays met no face at all. */
static int file_push_out(lm_atlas *a, const lm_chart *f, float *st)
{
    double s[2] = {st[0], st[1]}, p[3], e1[3], e2[3], dir[3], met, best, uxv[3];
    double uu = geom_dot(f->u, f->u), uv = geom_dot(f->u, f->v), vv = geom_dot(f->v, f->v), du, dv;
    geom_cross(f->u, f->v, uxv);
    rect_point(a, f, s, lift_of(a), p);
    geom_any_perp(f->n, e1);
    geom_cross(f->n, e1, e2);
    best = geom_back_ray(a->grid, a->polys, p, e1, e2,
                         0.75 * a->texel * sqrt(sqrt(geom_dot(uxv, uxv))), dir, &met);
    if (!(best < HUGE_VAL)) return !(met < HUGE_VAL);
    best = (best + margin_of(a)) / a->texel; /* the move T (ds u + dt v) = best dir */
    du = best * geom_dot(dir, f->u);
    dv = best * geom_dot(dir, f->v);
    st[0] = (float)(s[0] + (vv * du - uv * dv) / (uu * vv - uv * uv));
    st[1] = (float)(s[1] + (uu * dv - uv * du) / (uu * vv - uv * uv));
    return 0;
}

/* Every mapped polygon's fan triangles rasterised on the whole atlas (charts[0]), then
 * each covered texel owned by its polygon's chart COMP and tested free. 0, or -1. */
static int file_samples(lm_atlas *a, const unsigned char *interior, const int *comp)
{
    size_t t = (size_t)a->size * a->size, at;
    float *best = malloc(t * sizeof *best);
    double m = margin_of(a) / a->texel;
    int i, k;
    if (!best) return -1;
    for (at = 0; at < t; at++) best[at] = HUGE_VALF;
    for (i = 0; i < a->npolys; i++) {
        const sc_poly *q = &a->polys[i];
        const double *uv = &a->file_uv[8 * (size_t)i];
        for (k = 1; a->poly_chart[i] >= 0 && k + 1 < q->n; k++) {
            tri_t tr;
            if (!a->frames[2 * (size_t)i + k - 1].count) continue;
            memcpy(tr.p[0], uv, sizeof tr.p[0]);
            memcpy(tr.p[1], uv + 2 * k, sizeof tr.p[1]);
            memcpy(tr.p[2], uv + 2 * k + 2, sizeof tr.p[2]);
            tr.b[0] = k == 1 && !interior[4 * i];
            tr.b[1] = !interior[4 * i + k];
            tr.b[2] = k + 2 == q->n && !interior[4 * i + q->n - 1];
            raster_tri(a, &a->charts[0], &tr, i, m, best);
        }
    }
    free(best);
    for (at = 0; at < t; at++) {
        float *st = &a->sample[2 * at];
        double s[2];
        if (isnan(st[0])) continue;
        s[0] = st[0];
        s[1] = st[1];
        a->owner[at] = comp[a->poly[at]];
        if (file_push_out(a, file_tri(a, a->poly[at], s), st) &&
            st[0] == (float)(at % (size_t)a->size) + 0.5f &&
            st[1] == (float)(at / (size_t)a->size) + 0.5f)
            a->state[at] = LM_FREE;
    }
    return 0;
}

/* The gutter: PADDING rings around the charts' texels, each texel of no chart taken by
 * the lowest chart among its 8-neighbours of the rings before (a ring's own texels
 * marked -2 - chart until it is done, so that they are not read). */
static void file_gutter(lm_atlas *a)
{
    size_t t = (size_t)a->size * a->size, i;
    int r, dx, dy;
    for (r = 0; r < a->padding; r++) {
        for (i = 0; i < t; i++) {
            int x = (int)(i % (size_t)a->size), y = (int)(i / (size_t)a->size), best = -1;
            if (a->owner[i] != -1) continue;
            for (dy = -1; dy <= 1; dy++)
                for (dx = -1; dx <= 1; dx++) {
                    int o;
                    if (x + dx < 0 || y + dy < 0 || x + dx >= a->size || y + dy >= a->size)
                        continue;
                    o = a->owner[(size_t)(y + dy) * a->size + (size_t)(x + dx)];
                    if (o >= 0 && (best < 0 || o < best)) best = o;
                }
            if (best >= 0) a->owner[i] = -2 - best;
        }
        for (i = 0; i < t; i++)
            if (a->owner[i] <= -2) a->owner[i] = -2 - a->owner[i];
    }
}

/* Texels whose centre lies strictly inside the UV triangles of two polygons. -1 out
 * of memory. */
static long file_overlaps(const lm_atlas *a)
{
    size_t t = (size_t)a->size * a->size;
    int *first = malloc((t + 1) * sizeof *first), i, k, x, y;
    unsigned char *twice = calloc(t + 1, 1);
    long n = 0;
    if (!first || !twice) {
        free(first);
        free(twice);
        return -1;
    }
    memset(first, 0xff, t * sizeof *first);
    for (i = 0; i < a->npolys; i++)
        for (k = 0; a->poly_chart[i] >= 0 && k < 2; k++) {
            const double *uv = &a->file_uv[8 * (size_t)i], *p = uv + 2 * (k + 1),
                         *q = uv + 2 * (k + 2);
            double lo[2], hi[2], sign = uv_det(a, i, k) < 0.0 ? -1.0 : 1.0;
            int j;
            if (!a->frames[2 * (size_t)i + k].count) continue;
            for (j = 0; j < 2; j++) {
                lo[j] = fmin(fmax(floor(fmin(uv[j], fmin(p[j], q[j]))), 0.0), a->size);
                hi[j] = fmin(fmax(floor(fmax(uv[j], fmax(p[j], q[j]))), -1.0), a->size - 1.0);
            }
            for (y = (int)lo[1]; y <= (int)hi[1]; y++)
                for (x = (int)lo[0]; x <= (int)hi[0]; x++) {
                    double c[2] = {x + 0.5, y + 0.5};
                    size_t at = (size_t)y * a->size + (size_t)x;
                    if (!(sign * cross2d(uv, p, c) > 0 && sign * cross2d(p, q, c) > 0 &&
                          sign * cross2d(q, uv, c) > 0))
                        continue;
                    if (first[at] < 0)
                        first[at] = i;
                    else if (first[at] != i && !twice[at]++)
                        n++;
                }
        }
    free(first);
    free(twice);
    return n;
}

/* The file's UVs in texels, their faults counted, each polygon's frames; the texel size
 * T the root of the mapped triangles' world area over their texel area. Polygons with a
 * UV not finite are left out (missing). */
static void file_frames(lm_atlas *a, const double *uv, const geom_poly *g, lm_file_report *rep)
{
    double world = 0.0, texels = 0.0;
    int i, k;
    for (i = 0; i < a->npolys; i++) {
        int bad = 0;
        for (k = 0; k < 2 * a->polys[i].n; k++) {
            a->file_uv[8 * (size_t)i + k] = uv[8 * (size_t)i + k] * a->size;
            bad |= !isfinite(uv[8 * (size_t)i + k]);
        }
        for (k = 0; !bad && k < a->polys[i].n; k++) {
            const double *c = &uv[8 * (size_t)i + 2 * k];
            rep->outside += c[0] < 0.0 || c[0] > 1.0 || c[1] < 0.0 || c[1] > 1.0;
        }
        for (k = 0; k < 8; k++)
            if (bad || k >= 2 * a->polys[i].n) a->file_uv[8 * (size_t)i + k] = NAN;
        rep->missing += bad;
        for (k = 0; !bad && g[i].area > 0.0 && k + 2 < a->polys[i].n; k++) {
            double e1[3], e2[3], c[3];
            if (uv_det(a, i, k) == 0.0) {
                rep->zero_area++;
                continue;
            }
            geom_sub(a->polys[i].v[k + 1], a->polys[i].v[0], e1);
            geom_sub(a->polys[i].v[k + 2], a->polys[i].v[0], e2);
            geom_cross(e1, e2, c);
            world += sqrt(geom_dot(c, c));
            texels += fabs(uv_det(a, i, k));
        }
    }
    a->texel = texels > 0.0 ? sqrt(world / texels) : 0.0;
    for (i = 0; a->texel > 0.0 && i < a->npolys; i++) {
        file_frame(a, i, 0, g[i].n);
        file_frame(a, i, 1, g[i].n);
        a->poly_chart[i] = g[i].area > 0.0 && (a->frames[2 * (size_t)i].count ||
                                               a->frames[2 * (size_t)i + 1].count)
                               ? 0
                               : -1;
    }
}

/* The one rectangle of the adaptive blocks (the whole atlas) holding the mapped
 * polygons, and each one's chart into COMP (numbered in order of first polygon). */
static int file_charts(lm_atlas *a, int *parent, int *comp)
{
    int i, m = 0, *id = malloc((size_t)(a->npolys + 1) * sizeof *id);
    a->charts = calloc(2, sizeof *a->charts);
    if (!id || !a->charts) {
        free(id);
        return -1;
    }
    for (i = 0; i < a->npolys; i++) id[i] = -1;
    for (i = 0; i < a->npolys; i++) {
        int r;
        if (a->poly_chart[i] < 0) continue;
        r = find(parent, i);
        if (id[r] < 0) id[r] = a->file_charts++;
        comp[i] = id[r];
        a->chart_polys[m++] = i;
    }
    free(id);
    a->ncharts = 1;
    a->charts[0].w = a->charts[0].h = a->size;
    a->charts[0].count = m;
    a->charts[0].n[2] = 1.0;
    return 0;
}

int lm_build_file(lm_atlas *a, const sc_poly *polys, int n, const double *uv, const lm_opts *o,
                  lm_file_report *rep, char *err, size_t errlen)
{
    geom_poly *g;
    unsigned char *interior;
    int *parent, *comp, rc = -1;
    memset(rep, 0, sizeof *rep);
    if (setup(a, polys, n, o, err, errlen) != 0) return -1;
    g = geom_polys(polys, n, &a->extent);
    interior = calloc(4 * (size_t)n, 1);
    parent = malloc(((size_t)n + 1) * sizeof *parent);
    comp = malloc(((size_t)n + 1) * sizeof *comp);
    a->file_uv = malloc((8 * (size_t)n + 1) * sizeof *a->file_uv);
    a->frames = calloc(2 * (size_t)n + 1, sizeof *a->frames);
    if (g && !(a->extent > 0.0 && isfinite(a->extent))) {
        snprintf(err, errlen, "the polygons have no extent (or one that is not finite)");
        rc = -2;
    } else if (g && interior && parent && comp && a->file_uv && a->frames &&
               alloc_atlas(a, g, n) == 0 && (a->grid = geom_grid_new(polys, g, n)) != NULL) {
        file_frames(a, uv, g, rep);
        rc = a->texel > 0.0 ? 0 : -3;
        if (rc == -3)
            snprintf(err, errlen,
                     "no polygon has a second UV set with area (the file's lightmap UVs)");
    }
    if (rc == 0 && (file_joins(a, g, parent, interior) != 0 || file_charts(a, parent, comp) != 0 ||
                    file_samples(a, interior, comp) != 0 || (rep->overlap = file_overlaps(a)) < 0))
        rc = -1;
    if (rc == 0) file_gutter(a);
    if (rc == -1)
        snprintf(err, errlen, "out of memory for a %dx%d lightmap of %d polygons", o->size, o->size,
                 n);
    free(g);
    free(interior);
    free(parent);
    free(comp);
    if (rc != 0) lm_free(a);
    return rc < 0 ? -1 : 0;
}

double *lm_poly_file_uvs(const obj_scene *sc, const sc_poly *polys, int n)
{
    double *uv = sc->uv2 ? malloc((8 * (size_t)n + 1) * sizeof *uv) : NULL;
    int i, k, c;
    for (i = 0; uv && i < n; i++) {
        const obj_face *f =
            polys[i].tag >= 0 && polys[i].tag < sc->nfaces ? &sc->faces[polys[i].tag] : NULL;
        for (k = 0; k < 4; k++) {
            double *w = &uv[8 * (size_t)i + 2 * k];
            w[0] = w[1] = NAN;
            for (c = 0; f && k < polys[i].n && c < f->count; c++) {
                const obj_vec3 *v = &sc->verts[sc->indices[f->first + c]];
                const double p[3] = {v->x, v->y, v->z};
                if (cmp3(p, polys[i].v[k])) continue;
                w[0] = sc->uv2[f->first + c].u;
                w[1] = 1.0 - sc->uv2[f->first + c].v; /* v up, as vt: the atlas's rows go down */
                break;
            }
        }
    }
    return uv;
}

/* ---- baking and dilation ---- */

int lm_texel_point(const lm_atlas *a, int x, int y, double p[3])
{
    size_t at = (size_t)y * a->size + (size_t)x;
    double st[2];
    if (x < 0 || y < 0 || x >= a->size || y >= a->size || isnan(a->sample[2 * at])) return 0;
    st[0] = a->sample[2 * at];
    st[1] = a->sample[2 * at + 1];
    if (a->file_uv) /* on its triangle's frame (file_tri) */
        rect_point(a, file_tri(a, a->poly[at], st), st, lift_of(a), p);
    else
        surface_point(a, &a->charts[a->owner[at]], a->poly[at], st, lift_of(a), p);
    return 1;
}

/* The mean of texel AT's filled 8-neighbours of its chart into the texel; 1 if there
 * was one. */
static int fill_from(lm_atlas *a, const unsigned char *filled, size_t at)
{
    int x = (int)(at % (size_t)a->size), y = (int)(at / (size_t)a->size), dx, dy, n = 0, k;
    double sum[3] = {0, 0, 0};
    for (dy = -1; dy <= 1; dy++)
        for (dx = -1; dx <= 1; dx++) {
            size_t b = (size_t)(y + dy) * a->size + (size_t)(x + dx);
            if (x + dx < 0 || y + dy < 0 || x + dx >= a->size || y + dy >= a->size || !filled[b])
                continue;
            if (a->owner[b] != a->owner[at]) continue;
            for (k = 0; k < 3; k++) sum[k] += a->rgb[3 * b + k];
            n++;
        }
    for (k = 0; n && k < 3; k++) a->rgb[3 * at + k] = (float)(sum[k] / n);
    return n > 0;
}

/* Rings of dilation of the texels of charts' rectangles (the gutter, a concave chart's
 * rest) from their own chart until none is left; texels of no rectangle stay 0. Each
 * ring reads only the texels filled before it. */
static int dilate(lm_atlas *a, unsigned char *filled)
{
    size_t t = (size_t)a->size * a->size, i, n;
    size_t *ring = malloc(t * sizeof *ring);
    if (!ring) return -1;
    do {
        n = 0;
        for (i = 0; i < t; i++)
            if (!filled[i] && a->owner[i] >= 0 && fill_from(a, filled, i)) ring[n++] = i;
        for (i = 0; i < n; i++) filled[ring[i]] = 1;
    } while (n);
    free(ring);
    return 0;
}

/* FN at the covered texels of the rows Y % STEP == FIRST: the marked ones, their light
 * set (gathered), or (ADD) every one, its light added. */
static int texel_rows(lm_atlas *a, int first, int step, lm_gather_fn fn, void *ctx, int add)
{
    int x, y, k;
    for (y = first; y < a->size; y += step)
        for (x = 0; x < a->size; x++) {
            size_t i = (size_t)y * a->size + (size_t)x;
            double p[3], rgb[3];
            if ((!add && !(a->state[i] & LM_WANT)) || !lm_texel_point(a, x, y, p)) continue;
            if (fn(ctx, p, &a->planes[4 * (size_t)a->poly[i]], rgb) != 0) return -1;
            for (k = 0; k < 3; k++)
                a->rgb[3 * i + k] = (float)rgb[k] + (add ? a->rgb[3 * i + k] : 0);
            if (!add) a->state[i] = (unsigned char)((a->state[i] & LM_FREE) | LM_GATHERED);
        }
    return 0;
}

int lm_gather_rows(lm_atlas *a, int first, int step, lm_gather_fn fn, void *ctx)
{
    return texel_rows(a, first, step, fn, ctx, 0);
}

int lm_direct_rows(lm_atlas *a, int first, int step, lm_gather_fn fn, void *ctx)
{
    return texel_rows(a, first, step, fn, ctx, 1);
}

/* ---- adaptive gathering: blocks ---- */

/* Texel (X, Y) of chart C's rectangle, covered and not yet gathered, marked for the next
 * pass; 1 if it was marked. */
static long want(lm_atlas *a, const lm_chart *c, int x, int y)
{
    size_t at = (size_t)(c->y + y) * a->size + (size_t)(c->x + x);
    if (x >= c->w || y >= c->h || isnan(a->sample[2 * at]) ||
        (a->state[at] & (LM_WANT | LM_GATHERED)))
        return 0;
    a->state[at] = (unsigned char)((a->state[at] & LM_FREE) | LM_WANT);
    return 1;
}

/* Whether polygons P and Q lie in one plane (as coplanar charts join them). */
static int one_plane(const lm_atlas *a, int p, int q)
{
    const double *u = &a->planes[4 * (size_t)p], *v = &a->planes[4 * (size_t)q];
    return p == q || (geom_dot(u, v) >= COS_PLANE && fabs(u[3] - v[3]) <= PLANE_TOL * a->extent);
}

/* The block of B texels at (X, Y) of chart C: every one of its (B + 1)^2 texels inside
 * the rectangle, free and on polygons of one plane (an occluder standing on an edge
 * between them leaves the texels there not free), its corners gathered and their
 * channel sums within the tolerance of the largest. */
static int smooth(const lm_atlas *a, const lm_chart *c, int x, int y, int b)
{
    double lo = HUGE_VAL, hi = 0.0;
    int i, j, k, poly = a->poly[(size_t)(c->y + y) * a->size + (size_t)(c->x + x)];
    if (x + b >= c->w || y + b >= c->h) return 0;
    for (j = y; j <= y + b; j++)
        for (i = x; i <= x + b; i++) {
            size_t at = (size_t)(c->y + j) * a->size + (size_t)(c->x + i);
            if (!(a->state[at] & LM_FREE) || !one_plane(a, poly, a->poly[at])) return 0;
        }
    for (j = y; j <= y + b; j += b)
        for (i = x; i <= x + b; i += b) {
            size_t at = (size_t)(c->y + j) * a->size + (size_t)(c->x + i);
            double sum = 0.0;
            if (!(a->state[at] & LM_GATHERED)) return 0;
            for (k = 0; k < 3; k++) sum += a->rgb[3 * at + k];
            lo = fmin(lo, sum);
            hi = fmax(hi, sum);
        }
    return hi - lo <= a->tol * hi;
}

/* The block's texels not gathered (nor to be) take the bilinear mix of its corners. */
static void interpolate(lm_atlas *a, const lm_chart *c, int x, int y, int b)
{
    const float *e00 = &a->rgb[3 * ((size_t)(c->y + y) * a->size + (size_t)(c->x + x))];
    const float *e10 = e00 + 3 * (size_t)b, *e01 = e00 + 3 * (size_t)b * a->size,
                *e11 = e01 + 3 * (size_t)b;
    int i, j, k;
    for (j = 0; j <= b; j++)
        for (i = 0; i <= b; i++) {
            size_t at = (size_t)(c->y + y + j) * a->size + (size_t)(c->x + x + i);
            double u = (double)i / b, v = (double)j / b;
            if (a->state[at] & (LM_WANT | LM_GATHERED)) continue;
            for (k = 0; k < 3; k++)
                a->rgb[3 * at + k] = (float)((1 - v) * ((1 - u) * e00[k] + u * e10[k]) +
                                             v * ((1 - u) * e01[k] + u * e11[k]));
            a->state[at] |= LM_LERPED;
        }
}

/* Each waiting block of B texels: interpolated, or split in four (blocks of one texel:
 * every texel marked). The texels marked. */
static long split_blocks(lm_atlas *a, int b)
{
    long n = 0;
    int ci, x, y, i, j, h = b / 2;
    for (ci = 0; ci < a->ncharts; ci++) {
        const lm_chart *c = &a->charts[ci];
        for (y = 0; y < c->h; y += b)
            for (x = 0; x < c->w; x += b) {
                unsigned char *blk = &a->block[(size_t)(c->y + y) * a->size + (size_t)(c->x + x)];
                if (*blk != b) continue;
                *blk = 0;
                if (smooth(a, c, x, y, b)) {
                    interpolate(a, c, x, y, b);
                    continue;
                }
                for (j = 0; j <= b; j += h > 1 ? h : 1)
                    for (i = 0; i <= b; i += h > 1 ? h : 1) n += want(a, c, x + i, y + j);
                for (j = 0; h > 1 && j < b; j += h)
                    for (i = 0; i < b; i += h)
                        if (x + i < c->w && y + j < c->h)
                            a->block[(size_t)(c->y + y + j) * a->size + (size_t)(c->x + x + i)] =
                                (unsigned char)h;
            }
    }
    return n;
}

long lm_undecided(const lm_atlas *a)
{
    size_t i, t = (size_t)a->size * a->size;
    long n = 0;
    for (i = 0; i < t; i++)
        n += !isnan(a->sample[2 * i]) && !(a->state[i] & (LM_GATHERED | LM_LERPED));
    return n;
}

long lm_plan(lm_atlas *a)
{
    long n = 0;
    int ci, x, y;
    if (a->pass++ == 0 && a->painted) {
        size_t t = (size_t)a->size * a->size, i;
        for (i = 0; i < t; i++) n += (a->state[i] & LM_WANT) != 0;
        a->waiting = 0;
        return n;
    }
    if (a->pass == 1) {
        for (ci = 0; ci < a->ncharts; ci++) {
            const lm_chart *c = &a->charts[ci];
            int step = a->tol > 0.0 ? LM_STEP : 1;
            for (y = 0; y < c->h; y += step)
                for (x = 0; x < c->w; x += step) {
                    n += want(a, c, x, y);
                    if (step > 1)
                        a->block[(size_t)(c->y + y) * a->size + (size_t)(c->x + x)] = LM_STEP;
                }
        }
        a->waiting = a->tol > 0.0 ? LM_STEP : 0;
        return n;
    }
    for (; n == 0 && a->waiting > 1; a->waiting /= 2) n = split_blocks(a, a->waiting);
    return n;
}

int lm_dilate(lm_atlas *a)
{
    size_t t = (size_t)a->size * a->size, i;
    unsigned char *filled = malloc(t);
    int rc = filled ? 0 : -1;
    for (i = 0; filled && i < t; i++) filled[i] = !isnan(a->sample[2 * i]);
    if (rc == 0) rc = dilate(a, filled);
    free(filled);
    return rc;
}

int lm_visible(void *atlas, const double p[3], const double dir[3], double len)
{
    const lm_atlas *a = atlas;
    return !(geom_grid_march(a->grid, a->polys, p, dir, len, 1) < HUGE_VAL);
}

/* ---- painting from a solve's elements ---- */

/* An element corner (lm_paint): its key (place_key) and which corner it is. */
typedef struct {
    long long k[4];
    long e;
    int j;
} place_t;

/* Corners by key (qsort): equal keys, one place. */
static int place_cmp(const void *x, const void *y)
{
    const place_t *p = x, *q = y;
    int i;
    for (i = 0; i < 4; i++)
        if (p->k[i] != q->k[i]) return p->k[i] < q->k[i] ? -1 : 1;
    return 0;
}

/* The key of corner P of an element on polygon POLY: its chart (a file's UVs make one
 * rectangle of every polygon: there its polygon's normal, in bins of 2^-10 a
 * component, so that a floor's corners do not mix with a wall's) and its place. */
static void place_key(const lm_atlas *a, int poly, const double p[3], long long k[4])
{
    const double *n = &a->planes[4 * (size_t)poly];
    double q = a->extent * 0x1p-20;
    int j;
    k[0] = a->file_uv ? (llround(n[0] * 1024.0) + 1024) << 22 |
                            (llround(n[1] * 1024.0) + 1024) << 11 | (llround(n[2] * 1024.0) + 1024)
                      : a->poly_chart[poly];
    for (j = 0; j < 3; j++) k[1 + j] = llround(p[j] / q);
}

/* Weights of triangle T's corners (2D) at point Q on it; 0 for a triangle of no area. */
static int tri2_weights(const double t[3][2], const double q[2], double w[3])
{
    double d = cross2d(t[0], t[1], t[2]);
    if (!(fabs(d) > 1e-12)) return 0;
    w[1] = cross2d(t[0], q, t[2]) / d;
    w[2] = cross2d(t[0], t[1], q) / d;
    w[0] = 1.0 - w[1] - w[2];
    return 1;
}

/* Texel AT's sample's place in the atlas (texels). */
static void sample_xy(const lm_atlas *a, size_t at, double xy[2])
{
    xy[0] = a->sample[2 * at];
    xy[1] = a->sample[2 * at + 1];
    if (!a->file_uv) {
        xy[0] += a->charts[a->owner[at]].x;
        xy[1] += a->charts[a->owner[at]].y;
    }
}

/* Quad Q's (corners in order) bilinear coordinates (u along 0-1, v along 0-3) of point
 * C on it, from the quadratic of the inverse map (exact for any convex quad); 0 when
 * it has no root in [0, 1] (a quad folded in the projection). */
static int quad_uv(const double q[4][2], const double c[2], double *u, double *v)
{
    static const double o[2] = {0.0, 0.0};
    double e[2], f[2], g[2], h[2], k0, k1, k2, d, r, x;
    int i;
    for (i = 0; i < 2; i++) {
        e[i] = q[1][i] - q[0][i];
        f[i] = q[3][i] - q[0][i];
        g[i] = q[0][i] - q[1][i] + q[2][i] - q[3][i];
        h[i] = c[i] - q[0][i];
    }
    k2 = cross2d(o, g, f);
    k1 = cross2d(o, e, f) + cross2d(o, h, g);
    k0 = cross2d(o, h, e);
    if (fabs(k2) <= 1e-9 * fabs(k1)) {
        r = -k0 / k1;
    } else {
        d = k1 * k1 - 4.0 * k0 * k2;
        if (d < 0.0) return 0;
        d = sqrt(d);
        r = (-k1 - d) / (2.0 * k2);
        if (r < -1e-6 || r > 1.0 + 1e-6) r = (-k1 + d) / (2.0 * k2);
    }
    if (!(r >= -1e-6 && r <= 1.0 + 1e-6)) return 0;
    x = fabs(e[0] + g[0] * r) >= fabs(e[1] + g[1] * r) ? (h[0] - f[0] * r) / (e[0] + g[0] * r)
                                                       : (h[1] - f[1] * r) / (e[1] + g[1] * r);
    if (!(x >= -1e-6 && x <= 1.0 + 1e-6)) return 0;
    *u = fmin(fmax(x, 0.0), 1.0);
    *v = fmin(fmax(r, 0.0), 1.0);
    return 1;
}

/* Fan triangle J of corners XY (corners 0, J + 1, J + 2) into T. */
static void fan_tri(const double xy[4][2], int j, double t[3][2])
{
    int i;
    for (i = 0; i < 2; i++) {
        t[0][i] = xy[0][i];
        t[1][i] = xy[j + 1][i];
        t[2][i] = xy[j + 2][i];
    }
}

/* The light at point C of element corners XY (N = 3 or 4, atlas places) whose corners
 * hold V: linear over a triangle, bilinear over a quad (so a quad's light has no crease
 * along a diagonal), into RGB; T is the triangle of the element holding C (corners 0,
 * J + 1, J + 2), its fallback for a quad that has no inverse. */
static void element_light(int n, const double xy[4][2], const double v[4][3], const double c[2],
                          int j, double rgb[3])
{
    double t[3][2], w[3], u, s;
    int k;
    if (n == 4 && quad_uv(xy, c, &u, &s)) {
        for (k = 0; k < 3; k++)
            rgb[k] = (1 - u) * (1 - s) * v[0][k] + u * (1 - s) * v[1][k] + u * s * v[2][k] +
                     (1 - u) * s * v[3][k];
        return;
    }
    fan_tri(xy, j, t);
    if (!tri2_weights((const double(*)[2])t, c, w)) w[0] = 1, w[1] = w[2] = 0;
    for (k = 0; k < 3; k++) rgb[k] = w[0] * v[0][k] + w[1] * v[j + 1][k] + w[2] * v[j + 2][k];
}

/* Element M (its corners' atlas places XY, their light V when known) offered to the
 * texels of its polygon near it: each keeps the nearest element in BEST (squared
 * texels), its light or, when not known, a mark to gather. */
static void paint_element(lm_atlas *a, const sc_soft_element *m, const double xy[4][2],
                          const double v[4][3], float *best)
{
    const double r = LM_PAINT_REACH;
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    int x, y, j, k;
    for (j = 0; j < m->n; j++)
        for (k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], xy[j][k]);
            hi[k] = fmax(hi[k], xy[j][k]);
        }
    for (y = (int)fmax(floor(lo[1] - r), 0.0); y <= hi[1] + r && y < a->size; y++)
        for (x = (int)fmax(floor(lo[0] - r), 0.0); x <= hi[0] + r && x < a->size; x++) {
            size_t at = (size_t)y * a->size + (size_t)x;
            double q[2], c[2], near[2], d2 = HUGE_VAL, rgb[3];
            int tri = 0;
            if (isnan(a->sample[2 * at]) || a->poly[at] != m->poly) continue;
            sample_xy(a, at, q);
            for (j = 0; j + 2 < m->n; j++) { /* the nearest point of its triangles */
                double t[3][2], e;
                fan_tri(xy, j, t);
                geom_tri2_closest((const double(*)[2])t, q, c);
                e = (c[0] - q[0]) * (c[0] - q[0]) + (c[1] - q[1]) * (c[1] - q[1]);
                if (e < d2) {
                    d2 = e;
                    near[0] = c[0], near[1] = c[1];
                    tri = j;
                }
            }
            if (!(d2 < best[at])) continue;
            best[at] = (float)d2;
            a->state[at] =
                (unsigned char)((a->state[at] & LM_FREE) | (m->known ? LM_LERPED : LM_WANT));
            if (!m->known) continue;
            element_light(m->n, xy, v, near, tri, rgb);
            for (k = 0; k < 3; k++) a->rgb[3 * at + k] = (float)rgb[k];
        }
}

/* Whether element M can be painted on A: its polygon laid out. */
static int paintable(const lm_atlas *a, const sc_soft_element *m)
{
    return m->poly >= 0 && m->poly < a->npolys && a->poly_chart[m->poly] >= 0 && m->n >= 3;
}

long lm_paint(lm_atlas *a, const sc_soft_element *el, long n)
{
    size_t t = (size_t)a->size * a->size, i, np = 0, r, s;
    long e, left = 0;
    place_t *pl = malloc((size_t)(n ? n : 1) * 4 * sizeof *pl);
    double(*v)[4][3] = malloc((size_t)(n ? n : 1) * sizeof *v);
    float *best = malloc(t * sizeof *best);
    int j, k;
    if (!pl || !v || !best) {
        free(pl);
        free(v);
        free(best);
        return -1;
    }
    for (e = 0; e < n; e++)
        for (j = 0; el[e].known && paintable(a, &el[e]) && j < el[e].n; j++, np++) {
            place_key(a, el[e].poly, el[e].p[j], pl[np].k);
            pl[np].e = e;
            pl[np].j = j;
        }
    qsort(pl, np, sizeof *pl, place_cmp);
    for (r = 0; r < np; r = s) { /* each place: the area-weighted mean of its corners */
        double sum[3] = {0.0, 0.0, 0.0}, w = 0.0;
        for (s = r; s < np && !place_cmp(&pl[r], &pl[s]); s++) {
            const sc_soft_element *m = &el[pl[s].e];
            for (k = 0; k < 3; k++) sum[k] += m->area * m->rgb[k];
            w += m->area;
        }
        for (i = r; i < s; i++)
            for (k = 0; k < 3; k++)
                v[pl[i].e][pl[i].j][k] = w > 0.0 ? sum[k] / w : el[pl[i].e].rgb[k];
    }
    for (i = 0; i < t; i++) {
        best[i] = (float)(LM_PAINT_REACH * LM_PAINT_REACH);
        a->state[i] =
            (unsigned char)((a->state[i] & LM_FREE) | (isnan(a->sample[2 * i]) ? 0 : LM_WANT));
    }
    for (e = 0; e < n; e++) {
        double xy[4][2];
        if (!paintable(a, &el[e])) continue;
        for (j = 0; j < el[e].n; j++) lm_uv(a, el[e].poly, el[e].p[j], xy[j]);
        paint_element(a, &el[e], (const double(*)[2])xy, (const double(*)[3])v[e], best);
    }
    for (i = 0; i < t; i++) left += (a->state[i] & LM_WANT) != 0;
    free(pl);
    free(v);
    free(best);
    a->painted = 1;
    a->pass = 0;
    return left;
}

int lm_bake(lm_atlas *a, lm_gather_fn fn, lm_gather_fn direct, void *ctx)
{
    while (lm_plan(a) > 0)
        if (lm_gather_rows(a, 0, 1, fn, ctx) != 0) return -1;
    if (direct && lm_direct_rows(a, 0, 1, direct, ctx) != 0) return -1;
    return lm_dilate(a);
}

/* ---- lookups and output ---- */

int lm_uv(const lm_atlas *a, int poly, const double p[3], double xy[2])
{
    const lm_chart *c;
    if (poly < 0 || poly >= a->npolys || a->poly_chart[poly] < 0) return -1;
    if (a->file_uv) return file_uv_of(a, poly, p, xy);
    c = &a->charts[a->poly_chart[poly]];
    to_rect(c, a->texel, p, xy);
    xy[0] += c->x;
    xy[1] += c->y;
    return 0;
}

void lm_lookup(const lm_atlas *a, const double xy[2], double rgb[3])
{
    double fx = xy[0] - 0.5, fy = xy[1] - 0.5, x0 = floor(fx), y0 = floor(fy), wx = fx - x0,
           wy = fy - y0;
    int k, dx, dy;
    memset(rgb, 0, 3 * sizeof *rgb);
    for (dy = 0; dy < 2; dy++)
        for (dx = 0; dx < 2; dx++) {
            double w = (dx ? wx : 1.0 - wx) * (dy ? wy : 1.0 - wy);
            int x = (int)fmin(fmax(x0 + dx, 0.0), a->size - 1),
                y = (int)fmin(fmax(y0 + dy, 0.0), a->size - 1);
            for (k = 0; k < 3; k++) rgb[k] += w * a->rgb[3 * ((size_t)y * a->size + (size_t)x) + k];
        }
}

static int has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext), i;
    if (n < e) return 0;
    for (i = 0; i < e; i++)
        if ((path[n - e + i] | 0x20) != ext[i]) return 0;
    return 1;
}

int lm_write(const lm_atlas *a, const char *path, double exposure, char *err, size_t errlen)
{
    size_t t = (size_t)a->size * a->size;
    unsigned char *px;
    int rc;
    if (has_ext(path, ".hdr")) return hdr_write(path, a->rgb, a->size, a->size, err, errlen);
    if (!has_ext(path, ".png") && !has_ext(path, ".ppm")) {
        snprintf(err, errlen, "%s: unknown lightmap extension (use .png, .ppm or .hdr)", path);
        return -1;
    }
    if (!(px = malloc(3 * t))) {
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    tonemap(a->rgb, t, exposure > 0.0 ? exposure : tonemap_auto_exposure(a->rgb, t), px);
    rc = img_write(path, px, a->size, a->size, err, errlen);
    free(px);
    return rc;
}

/* Polygon Q has vertex P (exactly: the polygons carry the OBJ's coordinates). */
static int poly_has(const sc_poly *q, const double p[3])
{
    int k;
    for (k = 0; k < q->n; k++)
        if (!cmp3(q->v[k], p)) return 1;
    return 0;
}

static void corner_uv(const lm_atlas *a, const int *byface, int lo, int hi, const double p[3],
                      double uv[2])
{
    int i, poly = lo < hi ? byface[lo] : -1;
    double xy[2];
    for (i = lo; i < hi; i++)
        if (poly_has(&a->polys[byface[i]], p)) {
            poly = byface[i];
            break;
        }
    uv[0] = uv[1] = 0.0;
    if (poly >= 0 && lm_uv(a, poly, p, xy) == 0) {
        uv[0] = xy[0] / a->size;
        uv[1] = xy[1] / a->size;
    }
}

int lm_corner_uvs(const lm_atlas *a, const obj_scene *sc, double *uv)
{
    int *first = calloc((size_t)sc->nfaces + 2, sizeof *first),
        *byface = malloc(((size_t)a->npolys + 1) * sizeof *byface);
    int *fill = calloc((size_t)sc->nfaces + 1, sizeof *fill), i, f, k;
    if (!first || !byface || !fill || a->file_uv) {
        free(first);
        free(byface);
        free(fill);
        if (!a->file_uv) return -1;
        file_corner_uvs(sc, uv);
        return 0;
    }
    for (i = 0; i < a->npolys; i++)
        if (a->polys[i].tag >= 0 && a->polys[i].tag < sc->nfaces) first[a->polys[i].tag + 1]++;
    for (f = 0; f < sc->nfaces; f++) first[f + 1] += first[f];
    for (i = 0; i < a->npolys; i++) {
        int t = a->polys[i].tag;
        if (t >= 0 && t < sc->nfaces) byface[first[t] + fill[t]++] = i;
    }
    for (f = 0; f < sc->nfaces; f++)
        for (k = 0; k < sc->faces[f].count; k++) {
            int c = sc->faces[f].first + k;
            const obj_vec3 *v = &sc->verts[sc->indices[c]];
            const double p[3] = {v->x, v->y, v->z};
            corner_uv(a, byface, first[f], first[f + 1], p, uv + 2 * (size_t)c);
        }
    free(first);
    free(byface);
    free(fill);
    return 0;
}

int lm_png(const lm_atlas *a, unsigned char **png, size_t *n, double *scale, char *err,
           size_t errlen)
{
    size_t t = (size_t)a->size * a->size, i;
    unsigned char *px = malloc(3 * t);
    float top = 0.0f;
    int rc;
    for (i = 0; i < 3 * t; i++)
        if (a->rgb[i] > top) top = a->rgb[i]; /* NaN compares false: left out */
    *scale = top > 0.0f ? top : 1.0;
    if (!px) {
        snprintf(err, errlen, "out of memory for a %dx%d lightmap image", a->size, a->size);
        return -1;
    }
    tonemap(a->rgb, t, 1.0 / *scale, px);
    rc = img_encode_png(px, a->size, a->size, png, n, err, errlen);
    free(px);
    return rc;
}

void lm_free(lm_atlas *a)
{
    free(a->charts);
    free(a->poly_chart);
    free(a->chart_polys);
    free(a->owner);
    free(a->sample);
    free(a->rgb);
    free(a->poly);
    free(a->state);
    free(a->block);
    free(a->planes);
    geom_grid_free(a->grid);
    free(a->file_uv);
    free(a->frames);
    memset(a, 0, sizeof *a);
}
