/* SPDX-License-Identifier: MIT */
/* geom — the bake's geometry in double. See geom.h. */
#include "host/geom.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define GRID_MAX 64 /* cells a side */

int geom_normalize(double *v)
{
    double l = sqrt(geom_dot(v, v));
    if (!(l > 0.0) || !isfinite(l)) return 0;
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
    return 1;
}

void geom_reject(const double *e, const double *n, double *o)
{
    double k = geom_dot(e, n);
    o[0] = e[0] - k * n[0];
    o[1] = e[1] - k * n[1];
    o[2] = e[2] - k * n[2];
}

void geom_any_perp(const double *n, double *o)
{
    double x[3] = {0, 0, 0};
    x[fabs(n[0]) < 0.5 ? 0 : fabs(n[1]) < 0.5 ? 1 : 2] = 1.0;
    geom_reject(x, n, o);
    geom_normalize(o);
}

geom_poly *geom_polys(const sc_poly *p, int n, double *extent)
{
    geom_poly *g = calloc((size_t)n + 1, sizeof *g);
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    int i, k, a;
    if (!g) return NULL;
    for (i = 0; i < n; i++) {
        double nn[3] = {0, 0, 0};
        for (k = 0; k < p[i].n; k++) {
            const double *v = p[i].v[k], *w = p[i].v[(k + 1) % p[i].n];
            nn[0] += (v[1] - w[1]) * (v[2] + w[2]);
            nn[1] += (v[2] - w[2]) * (v[0] + w[0]);
            nn[2] += (v[0] - w[0]) * (v[1] + w[1]);
            for (a = 0; a < 3; a++) {
                g[i].c[a] += v[a] / p[i].n;
                lo[a] = fmin(lo[a], v[a]);
                hi[a] = fmax(hi[a], v[a]);
            }
        }
        g[i].area = 0.5 * sqrt(geom_dot(nn, nn));
        if (!geom_normalize(nn)) g[i].area = 0.0;
        memcpy(g[i].n, nn, sizeof nn);
        g[i].d = geom_dot(nn, g[i].c);
    }
    *extent = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    return g;
}

/* ---- 2D triangles ---- */

static double cross2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static void seg_closest(const double *a, const double *b, const double *c, double *q)
{
    double dx = b[0] - a[0], dy = b[1] - a[1], l = dx * dx + dy * dy;
    double t = l > 0.0 ? ((c[0] - a[0]) * dx + (c[1] - a[1]) * dy) / l : 0.0;
    t = fmin(fmax(t, 0.0), 1.0);
    q[0] = a[0] + t * dx;
    q[1] = a[1] + t * dy;
}

void geom_tri2_closest(const double t[3][2], const double c[2], double q[2])
{
    double s0 = cross2(t[0], t[1], c), s1 = cross2(t[1], t[2], c), s2 = cross2(t[2], t[0], c),
           best = HUGE_VAL;
    int k;
    if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) {
        q[0] = c[0];
        q[1] = c[1];
        return;
    }
    for (k = 0; k < 3; k++) {
        double r[2], d;
        seg_closest(t[k], t[(k + 1) % 3], c, r);
        d = hypot(r[0] - c[0], r[1] - c[1]);
        if (d < best) {
            best = d;
            q[0] = r[0];
            q[1] = r[1];
        }
    }
}

int geom_tri2_touches_box(const double t[3][2], double x0, double y0, double side)
{
    const double eps = 1e-9, lo[2] = {x0, y0};
    int k, a;
    for (a = 0; a < 2; a++) {
        double mn = fmin(t[0][a], fmin(t[1][a], t[2][a])),
               mx = fmax(t[0][a], fmax(t[1][a], t[2][a]));
        if (mx <= lo[a] + eps || mn >= lo[a] + side - eps) return 0;
    }
    for (k = 0; k < 3; k++) {
        const double *p = t[k], *q = t[(k + 1) % 3];
        double nx = p[1] - q[1], ny = q[0] - p[0], mn = HUGE_VAL, mx = -HUGE_VAL, c, r,
               l = hypot(nx, ny);
        if (!(l > 0.0)) continue;
        nx /= l;
        ny /= l;
        for (a = 0; a < 3; a++) {
            double s = t[a][0] * nx + t[a][1] * ny;
            mn = fmin(mn, s);
            mx = fmax(mx, s);
        }
        c = (x0 + 0.5 * side) * nx + (y0 + 0.5 * side) * ny;
        r = 0.5 * side * (fabs(nx) + fabs(ny));
        if (mx <= c - r + eps || mn >= c + r - eps) return 0;
    }
    return 1;
}

void geom_tri2_inset(const double (*t)[3][2], const unsigned char (*b)[3], int n, double m,
                     double q[2])
{
    int k, i, pass;
    for (pass = 0; pass < 2; pass++)
        for (i = 0; i < n; i++)
            for (k = 0; k < 3; k++) {
                const double *p0 = t[i][k], *p1 = t[i][(k + 1) % 3], *p2 = t[i][(k + 2) % 3];
                double nx = p0[1] - p1[1], ny = p1[0] - p0[0], len = hypot(nx, ny), s;
                if (!b[i][k] || !(len > 0.0)) continue;
                nx /= len;
                ny /= len;
                if ((p2[0] - p0[0]) * nx + (p2[1] - p0[1]) * ny < 0.0) {
                    nx = -nx;
                    ny = -ny;
                }
                s = (q[0] - p0[0]) * nx + (q[1] - p0[1]) * ny;
                if (s < m) {
                    q[0] += (m - s) * nx;
                    q[1] += (m - s) * ny;
                }
            }
}

/* ---- rays through a grid ---- */

typedef struct {
    int g, n;
    double lo[3], cell[3], eps;
    int *start, *ids; /* cell k's polygons: ids[start[k] .. start[k + 1]) */
    geom_poly *planes;
} grid_t;

static int cell_of(const grid_t *gr, int a, double x)
{
    double c = floor((x - gr->lo[a]) / gr->cell[a]);
    return c < 0 ? 0 : c >= gr->g ? gr->g - 1 : (int)c;
}

/* The cell box [LO, HI] of polygon or segment bounds. */
static void cell_box(const grid_t *gr, const double *mn, const double *mx, int *lo, int *hi)
{
    int a;
    for (a = 0; a < 3; a++) {
        lo[a] = cell_of(gr, a, mn[a]);
        hi[a] = cell_of(gr, a, mx[a]);
    }
}

static void poly_box(const sc_poly *p, double *mn, double *mx)
{
    int k, a;
    for (a = 0; a < 3; a++) mn[a] = mx[a] = p->v[0][a];
    for (k = 1; k < p->n; k++)
        for (a = 0; a < 3; a++) {
            mn[a] = fmin(mn[a], p->v[k][a]);
            mx[a] = fmax(mx[a], p->v[k][a]);
        }
}

/* Counts (FILL 0) or files (1) each polygon into the cells of its box. */
static void grid_pass(grid_t *gr, const sc_poly *p, int fill, int *at)
{
    int i, x, y, z, lo[3], hi[3];
    for (i = 0; i < gr->n; i++) {
        double mn[3], mx[3];
        if (gr->planes[i].area <= 0.0) continue;
        poly_box(&p[i], mn, mx);
        cell_box(gr, mn, mx, lo, hi);
        for (z = lo[2]; z <= hi[2]; z++)
            for (y = lo[1]; y <= hi[1]; y++)
                for (x = lo[0]; x <= hi[0]; x++) {
                    int k = (z * gr->g + y) * gr->g + x;
                    if (fill)
                        gr->ids[at[k]++] = i;
                    else
                        gr->start[k + 1]++;
                }
    }
}

void *geom_grid_new(const sc_poly *p, const geom_poly *g, int n)
{
    grid_t *gr = calloc(1, sizeof *gr);
    int i, a, cells, *at = NULL;
    double hi[3];
    if (!gr) return NULL;
    gr->n = n;
    gr->g = (int)fmin(fmax(floor(cbrt((double)n)), 1.0), GRID_MAX);
    cells = gr->g * gr->g * gr->g;
    for (a = 0; a < 3; a++) gr->lo[a] = hi[a] = p[0].v[0][a];
    for (i = 0; i < n; i++) {
        double mn[3], mx[3];
        poly_box(&p[i], mn, mx);
        for (a = 0; a < 3; a++) {
            gr->lo[a] = fmin(gr->lo[a], mn[a]);
            hi[a] = fmax(hi[a], mx[a]);
        }
    }
    for (a = 0; a < 3; a++) gr->eps = fmax(gr->eps, hi[a] - gr->lo[a]);
    if (!(gr->eps > 0.0) || !isfinite(gr->eps)) gr->eps = 1.0; /* no extent: one cell holds all */
    for (a = 0; a < 3; a++)
        gr->cell[a] = fmax(hi[a] - gr->lo[a], gr->eps * 1e-6) / gr->g * (1.0 + 1e-9);
    gr->eps *= 1e-12;
    gr->planes = malloc(((size_t)n + 1) * sizeof *gr->planes);
    gr->start = calloc((size_t)cells + 1, sizeof *gr->start);
    at = malloc(((size_t)cells + 1) * sizeof *at);
    if (gr->planes && gr->start && at) {
        memcpy(gr->planes, g, (size_t)n * sizeof *g);
        grid_pass(gr, p, 0, NULL);
        for (i = 0; i < cells; i++) gr->start[i + 1] += gr->start[i];
        memcpy(at, gr->start, (size_t)cells * sizeof *at);
        gr->ids = malloc(((size_t)gr->start[cells] + 1) * sizeof *gr->ids);
        if (gr->ids) grid_pass(gr, p, 1, at);
    }
    free(at);
    if (!gr->ids) {
        geom_grid_free(gr);
        return NULL;
    }
    return gr;
}

void geom_grid_free(void *grid)
{
    grid_t *gr = grid;
    if (!gr) return;
    free(gr->planes);
    free(gr->start);
    free(gr->ids);
    free(gr);
}

/* Distance along the ray to polygon I within LEN, HUGE_VAL if it is not met. */
static double ray_poly(const grid_t *gr, const sc_poly *p, int i, const double *o,
                       const double *dir, double len)
{
    const geom_poly *g = &gr->planes[i];
    double den = geom_dot(g->n, dir), t, h[3];
    int k;
    if (g->area <= 0.0 || fabs(den) < 1e-12) return HUGE_VAL;
    t = (g->d - geom_dot(g->n, o)) / den;
    if (!(t > gr->eps) || t > len) return HUGE_VAL;
    for (k = 0; k < 3; k++) h[k] = o[k] + t * dir[k];
    for (k = 0; k < p[i].n; k++) {
        double e[3], r[3], c[3];
        geom_sub(p[i].v[(k + 1) % p[i].n], p[i].v[k], e);
        geom_sub(h, p[i].v[k], r);
        geom_cross(e, r, c);
        if (geom_dot(c, g->n) < -gr->eps * sqrt(geom_dot(e, e))) return HUGE_VAL;
    }
    return t;
}

static void nearest(const grid_t *gr, const sc_poly *p, int i, const double *o, const double *dir,
                    double len, double *best, int *back)
{
    double t = ray_poly(gr, p, i, o, dir, len);
    if (t < *best) {
        *best = t;
        *back = geom_dot(gr->planes[i].n, dir) > 0.0;
    }
}

double geom_grid_ray(const void *grid, const sc_poly *p, const double *o, const double *dir,
                     double len, int *back)
{
    const grid_t *gr = grid;
    double best = HUGE_VAL, mn[3], mx[3];
    int lo[3], hi[3], x, y, z, a, i;
    long cells = 1;
    *back = 0;
    for (a = 0; a < 3; a++) {
        double e = o[a] + (isfinite(len) ? len * dir[a]
                                         : (dir[a] > 0   ? HUGE_VAL
                                            : dir[a] < 0 ? -HUGE_VAL
                                                         : 0.0));
        mn[a] = fmin(o[a], e);
        mx[a] = fmax(o[a], e);
    }
    cell_box(gr, mn, mx, lo, hi);
    for (a = 0; a < 3; a++) cells *= hi[a] - lo[a] + 1;
    if (cells * 4 > gr->n) { /* a long ray: every polygon once beats the cells' repeats */
        for (i = 0; i < gr->n; i++) nearest(gr, p, i, o, dir, len, &best, back);
        return best;
    }
    for (z = lo[2]; z <= hi[2]; z++)
        for (y = lo[1]; y <= hi[1]; y++)
            for (x = lo[0]; x <= hi[0]; x++) {
                int k = (z * gr->g + y) * gr->g + x, j;
                for (j = gr->start[k]; j < gr->start[k + 1]; j++)
                    nearest(gr, p, gr->ids[j], o, dir, len, &best, back);
            }
    return best;
}

double geom_grid_march(const void *grid, const sc_poly *p, const double *o, const double *dir,
                       double len, int any)
{
    const grid_t *gr = grid;
    double t0 = 0.0, t1 = len, best = HUGE_VAL, next[3], delta[3];
    int a, c[3], step[3], back;
    for (a = 0; a < 3; a++) { /* the part of the ray inside the grid's box */
        double lo = gr->lo[a], hi = gr->lo[a] + gr->cell[a] * gr->g;
        if (!isfinite(o[a]) || !isfinite(dir[a])) return HUGE_VAL; /* no cell to start in */
        if (fabs(dir[a]) < 1e-300) {
            if (o[a] < lo || o[a] > hi) return HUGE_VAL;
            continue;
        }
        {
            double ta = (lo - o[a]) / dir[a], tb = (hi - o[a]) / dir[a];
            t0 = fmax(t0, fmin(ta, tb));
            t1 = fmin(t1, fmax(ta, tb));
        }
    }
    if (!(t0 <= t1)) return HUGE_VAL;
    for (a = 0; a < 3; a++) {
        double x = o[a] + t0 * dir[a], edge;
        c[a] = cell_of(gr, a, x);
        step[a] = dir[a] > 0.0 ? 1 : -1;
        if (fabs(dir[a]) < 1e-300) {
            next[a] = delta[a] = HUGE_VAL;
            continue;
        }
        edge = gr->lo[a] + (c[a] + (dir[a] > 0.0)) * gr->cell[a];
        next[a] = (edge - o[a]) / dir[a];
        delta[a] = gr->cell[a] / fabs(dir[a]);
    }
    for (;;) {
        int k = (c[2] * gr->g + c[1]) * gr->g + c[0], j;
        double exit = fmin(next[0], fmin(next[1], next[2]));
        for (j = gr->start[k]; j < gr->start[k + 1]; j++) {
            nearest(gr, p, gr->ids[j], o, dir, len, &best, &back);
            if (any && best < HUGE_VAL) return best;
        }
        if (best <= exit || exit > t1) return best; /* later cells lie farther */
        a = next[0] == exit ? 0 : next[1] == exit ? 1 : 2;
        c[a] += step[a];
        if (c[a] < 0 || c[a] >= gr->g) return best;
        next[a] += delta[a];
    }
}

double geom_back_ray(const void *grid, const sc_poly *p, const double *o, const double *u,
                     const double *v, double len, double dir[3], double *met)
{
    double best = HUGE_VAL, dirs[4][3];
    int k, j, found = -1;
    if (met) *met = HUGE_VAL;
    for (k = 0; k < 3; k++) {
        dirs[0][k] = u[k];
        dirs[1][k] = -u[k];
        dirs[2][k] = v[k];
        dirs[3][k] = -v[k];
    }
    for (j = 0; j < 4; j++) {
        int back = 0;
        double t = geom_grid_ray(grid, p, o, dirs[j], len, &back);
        if (met && t < *met) *met = t;
        if (back && t < best) {
            best = t;
            found = j;
        }
    }
    if (found >= 0) memcpy(dir, dirs[found], 3 * sizeof *dir);
    return best;
}
