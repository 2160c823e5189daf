/* SPDX-License-Identifier: MIT */
/* level — the generated atrium. See level.h. */
#include "bench/level.h"
#include "formats/file_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TURN     6.283185307179586
#define COURT    12.0 /* half the courtyard's side: the arcades' centre lines */
#define OUTER    18.0 /* half the outer walls' side */
#define STOREY   5.0  /* floor to floor */
#define SLAB     0.3  /* the slab's and the roof's thickness */
#define TILE     1.0  /* floor and wall tiles */
#define COL_R    0.35 /* a column's radius: the arcade wall is 2 COL_R thick */
#define COL_STEP 3.0  /* columns' spacing along the arcade */
#define SPRING   3.5  /* the arches' spring above the storey's floor */
#define FACETS   32   /* around a column and along an arch */
#define RINGS    22   /* up a column's shaft */
#define BLOCK    0.3  /* plinth and capital height; their half side is 0.45 */

typedef struct {
    sc_poly *p;
    int n, cap, oom;
} lv_t;

static const double stone[3] = {0.55, 0.52, 0.47}, plaster[3] = {0.7, 0.68, 0.62},
                    marble[3] = {0.72, 0.72, 0.7}, roof[3] = {0.35, 0.25, 0.2};

/* Quad A B C D (a planar, convex one) turned so that its lit side faces along WANT. */
static void quad(lv_t *l, const double *a, const double *b, const double *c, const double *d,
                 const double *want, const double *rho)
{
    const double *v[4] = {a, b, c, d};
    double e[3], f[3], n[3];
    sc_poly *q;
    int k, flip;
    if (l->n == l->cap) {
        sc_poly *p = realloc(l->p, 2 * (size_t)l->cap * sizeof *p);
        if (!p) {
            l->oom = 1;
            return;
        }
        l->p = p;
        l->cap *= 2;
    }
    for (k = 0; k < 3; k++) {
        e[k] = c[k] - a[k];
        f[k] = d[k] - b[k];
    }
    n[0] = e[1] * f[2] - e[2] * f[1];
    n[1] = e[2] * f[0] - e[0] * f[2];
    n[2] = e[0] * f[1] - e[1] * f[0];
    flip = n[0] * want[0] + n[1] * want[1] + n[2] * want[2] < 0;
    q = &l->p[l->n];
    memset(q, 0, sizeof *q);
    q->n = 4;
    for (k = 0; k < 4; k++) memcpy(q->v[k], v[flip ? 3 - k : k], sizeof q->v[k]);
    memcpy(q->rho, rho, sizeof q->rho);
    q->tag = l->n++;
}

/* The parallelogram O + [0, 1] U + [0, 1] V in tiles of about SIDE, facing WANT. */
static void tiles(lv_t *l, const double *o, const double *u, const double *v, double side,
                  const double *want, const double *rho)
{
    int nu = (int)ceil(sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) / side - 1e-9);
    int nv = (int)ceil(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) / side - 1e-9), i, j, k;
    for (i = 0; i < nu; i++)
        for (j = 0; j < nv; j++) {
            double c[4][3], s[4] = {i, i + 1, i + 1, i}, t[4] = {j, j, j + 1, j + 1};
            int m;
            for (m = 0; m < 4; m++)
                for (k = 0; k < 3; k++) c[m][k] = o[k] + s[m] / nu * u[k] + t[m] / nv * v[k];
            quad(l, c[0], c[1], c[2], c[3], want, rho);
        }
}

/* The horizontal rectangle [X0, X1] x [Z0, Z1] at height Y, facing up (UP) or down. */
static void flat(lv_t *l, double x0, double x1, double z0, double z1, double y, int up, double side,
                 const double *rho)
{
    double o[3] = {x0, y, z0}, u[3] = {x1 - x0, 0, 0}, v[3] = {0, 0, z1 - z0},
           w[3] = {0, up ? 1 : -1, 0};
    tiles(l, o, u, v, side, w, rho);
}

/* The gallery ring (between the arcade's courtyard face and the outer walls) at height Y. */
static void ring(lv_t *l, double y, int up, const double *rho)
{
    double c = COURT - COL_R;
    flat(l, -OUTER, OUTER, c, OUTER, y, up, TILE, rho);
    flat(l, -OUTER, OUTER, -OUTER, -c, y, up, TILE, rho);
    flat(l, c, OUTER, -c, c, y, up, TILE, rho);
    flat(l, -OUTER, -c, -c, c, y, up, TILE, rho);
}

/* A side of the arcade: world point of position S along it, height Y, depth W (towards
 * the gallery), for side K (0..3: +x, +z, -x, -z). */
static void side_point(int k, double s, double y, double w, double *p)
{
    static const double m[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    double mx = m[k][0], mz = m[k][1];
    p[0] = (COURT + w) * mx - s * mz;
    p[1] = y;
    p[2] = (COURT + w) * mz + s * mx;
}

/* An axis-aligned box's sides (and top or bottom: CAP +1 or -1) around (X, Z), half side H. */
static void block(lv_t *l, double x, double z, double h, double y0, double y1, int cap)
{
    int f;
    for (f = 0; f < 4; f++) {
        double dx = f == 0   ? 1
                    : f == 2 ? -1
                             : 0,
               dz = f == 1   ? 1
                    : f == 3 ? -1
                             : 0,
               want[3] = {dx, 0, dz};
        double a[3] = {x + h * dx - h * dz, y0, z + h * dz + h * dx},
               b[3] = {x + h * dx + h * dz, y0, z + h * dz - h * dx};
        double c[3] = {b[0], y1, b[2]}, d[3] = {a[0], y1, a[2]};
        quad(l, a, b, c, d, want, marble);
    }
    flat(l, x - h, x + h, z - h, z + h, cap > 0 ? y1 : y0, cap > 0, 2 * h, marble);
}

/* A column at (X, Z) from Y0 to the spring: plinth, shaft of FACETS x RINGS, capital. */
static void column(lv_t *l, double x, double z, double y0)
{
    double ys = y0 + SPRING, lo = y0 + BLOCK, hi = ys - BLOCK;
    int i, j;
    block(l, x, z, 0.45, y0, lo, 1);
    block(l, x, z, 0.45, hi, ys, -1);
    for (i = 0; i < FACETS; i++)
        for (j = 0; j < RINGS; j++) {
            double a0 = TURN * i / FACETS, a1 = TURN * (i + 1) / FACETS, m = 0.5 * (a0 + a1);
            double y1 = lo + (hi - lo) * j / RINGS, y2 = lo + (hi - lo) * (j + 1) / RINGS;
            double a[3] = {x + COL_R * cos(a0), y1, z + COL_R * sin(a0)},
                   b[3] = {x + COL_R * cos(a1), y1, z + COL_R * sin(a1)};
            double c[3] = {b[0], y2, b[2]}, d[3] = {a[0], y2, a[2]}, want[3] = {cos(m), 0, sin(m)};
            quad(l, a, b, c, d, want, marble);
        }
}

/* The arch of side K from column position S0 to S1 (centres), floor Y0, the wall above
 * it up to TOP: its soffit (half a cylinder, two quads deep) and its spandrels on both
 * faces. */
static void arch(lv_t *l, int k, double s0, double s1, double y0, double top)
{
    double sa = s0 + COL_R, sb = s1 - COL_R, sc = 0.5 * (sa + sb), r = 0.5 * (sb - sa),
           ys = y0 + SPRING;
    int i, j, f;
    for (i = 0; i < FACETS; i++) {
        double t0 = TURN / 2 * (1.0 - (double)i / FACETS),
               t1 = TURN / 2 * (1.0 - (double)(i + 1) / FACETS);
        double s[2] = {sc + r * cos(t0), sc + r * cos(t1)},
               y[2] = {ys + r * sin(t0), ys + r * sin(t1)};
        double tm = 0.5 * (t0 + t1), c0[3], c1[3], want[3], p[4][3];
        side_point(k, sc, ys, 0, c0);
        side_point(k, sc + cos(tm), ys + sin(tm), 0, c1);
        for (j = 0; j < 3; j++) want[j] = c0[j] - c1[j]; /* the soffit faces the arch's axis */
        for (j = 0; j < 2; j++) {
            double w0 = -COL_R + COL_R * j, w1 = w0 + COL_R;
            side_point(k, s[0], y[0], w0, p[0]);
            side_point(k, s[1], y[1], w0, p[1]);
            side_point(k, s[1], y[1], w1, p[2]);
            side_point(k, s[0], y[0], w1, p[3]);
            quad(l, p[0], p[1], p[2], p[3], want, plaster);
        }
        for (f = 0; f < 2; f++) { /* the spandrel above the segment, each face */
            double w = f ? COL_R : -COL_R, o[3], n[3];
            side_point(k, s[0], y[0], w, p[0]);
            side_point(k, s[1], y[1], w, p[1]);
            side_point(k, s[1], top, w, p[2]);
            side_point(k, s[0], top, w, p[3]);
            side_point(k, 0, 0, 0, o);
            side_point(k, 0, 0, f ? 1 : -1, n);
            for (j = 0; j < 3; j++) n[j] -= o[j];
            quad(l, p[0], p[1], p[2], p[3], n, plaster);
        }
    }
    for (f = 0; f < 4; f++) { /* over the columns' halves, each face */
        double w = f & 1 ? COL_R : -COL_R, e0 = f < 2 ? s0 : sb, e1 = f < 2 ? sa : s1, o[3], n[3],
               p[4][3];
        side_point(k, e0, ys, w, p[0]);
        side_point(k, e1, ys, w, p[1]);
        side_point(k, e1, top, w, p[2]);
        side_point(k, e0, top, w, p[3]);
        side_point(k, 0, 0, 0, o);
        side_point(k, 0, 0, f & 1 ? 1 : -1, n);
        for (j = 0; j < 3; j++) n[j] -= o[j];
        quad(l, p[0], p[1], p[2], p[3], n, plaster);
    }
}

/* The cornice of side K at the storey's TOP (the slab's underside): a quarter round of
 * 0.4 under an overhang, then its front and top up to the floor above, in TILE lengths. */
static void cornice(lv_t *l, int k, double top)
{
    enum { ARC = 6 };
    double pw[ARC + 3], py[ARC + 3], nw[ARC + 2], ny[ARC + 2], len = 2 * (COURT + COL_R);
    int i, j, seg = (int)ceil(len / TILE);
    for (i = 0; i <= ARC; i++) {
        double a = TURN / 4 * i / ARC;
        pw[i] = -COL_R - 0.4 * sin(a);
        py[i] = top - 0.4 * cos(a);
    }
    pw[ARC + 1] = pw[ARC];
    py[ARC + 1] = top + SLAB;
    pw[ARC + 2] = -COL_R;
    py[ARC + 2] = top + SLAB;
    for (i = 0; i < ARC; i++) {
        double a = TURN / 4 * (i + 0.5) / ARC;
        nw[i] = -sin(a);
        ny[i] = -cos(a);
    }
    nw[ARC] = -1, ny[ARC] = 0;
    nw[ARC + 1] = 0, ny[ARC + 1] = 1;
    for (j = 0; j < seg; j++) {
        double s0 = -len / 2 + len * j / seg, s1 = -len / 2 + len * (j + 1) / seg;
        for (i = 0; i < ARC + 2; i++) {
            double p[4][3], o[3], n[3];
            int c;
            side_point(k, s0, py[i], pw[i], p[0]);
            side_point(k, s1, py[i], pw[i], p[1]);
            side_point(k, s1, py[i + 1], pw[i + 1], p[2]);
            side_point(k, s0, py[i + 1], pw[i + 1], p[3]);
            side_point(k, 0, 0, 0, o);
            side_point(k, 0, ny[i], nw[i], n);
            for (c = 0; c < 3; c++) n[c] -= o[c];
            quad(l, p[0], p[1], p[2], p[3], n, plaster);
        }
    }
}

/* The parallelogram from side K's points A (its corner) to B along U and to C along V,
 * in tiles of SIDE facing WANT. */
static void side_tiles(lv_t *l, const double *a, const double *b, const double *c, double side,
                       const double *want, const double *rho)
{
    double u[3], v[3];
    int i;
    for (i = 0; i < 3; i++) {
        u[i] = b[i] - a[i];
        v[i] = c[i] - a[i];
    }
    tiles(l, a, u, v, side, want, rho);
}

/* The outer walls: inside faces in tiles, outside faces and tops in 2 m panels (they
 * keep the sun out of the galleries: a light passes through faces turned away). */
static void walls(lv_t *l)
{
    double h = 2 * STOREY, in = OUTER - COURT, out = in + 0.4, up[3] = {0, 1, 0};
    int k, c;
    for (k = 0; k < 4; k++) {
        double a[3], b[3], t[3], o[3], m[3];
        side_point(k, 0, 0, 0, o);
        side_point(k, 0, 0, 1, m);
        for (c = 0; c < 3; c++) m[c] -= o[c]; /* outwards */
        side_point(k, -OUTER, 0, in, a);
        side_point(k, OUTER, 0, in, b);
        side_point(k, -OUTER, h, in, t);
        for (c = 0; c < 3; c++) o[c] = -m[c];
        side_tiles(l, a, b, t, TILE, o, plaster);
        side_point(k, -OUTER - 0.4, 0, out, a);
        side_point(k, OUTER + 0.4, 0, out, b);
        side_point(k, -OUTER - 0.4, h, out, t);
        side_tiles(l, a, b, t, 2.0, m, stone);
        side_point(k, -OUTER - 0.4, h, in, a);
        side_point(k, OUTER + 0.4, h, in, b);
        side_point(k, -OUTER - 0.4, h, out, t);
        side_tiles(l, a, b, t, 2.0, up, stone);
    }
}

sc_poly *level_atrium(int *n, sc_light lights[LEVEL_LIGHTS])
{
    lv_t l = {NULL, 0, 4096, 0};
    int s, k, i;
    l.p = malloc((size_t)l.cap * sizeof *l.p);
    if (!l.p) return NULL;
    flat(&l, -OUTER, OUTER, -OUTER, OUTER, 0.0, 1, TILE, stone);
    for (s = 0; s < 2; s++) {
        double y0 = s * STOREY, top = y0 + STOREY - SLAB;
        ring(&l, top + SLAB, 1, s ? roof : stone);
        ring(&l, top, 0, plaster);
        for (k = 0; k < 4; k++) {
            for (i = 0; i < 8; i++) {
                double p[3], s0 = -COURT + COL_STEP * i;
                side_point(k, s0, y0, 0, p);
                column(&l, p[0], p[2], y0);
                arch(&l, k, s0, s0 + COL_STEP, y0, top);
            }
            cornice(&l, k, top);
        }
    }
    walls(&l);
    if (l.oom) {
        free(l.p);
        return NULL;
    }
    memset(lights, 0, LEVEL_LIGHTS * sizeof *lights);
    lights[0].type = 1; /* the sun, 50 degrees up, its light travelling down and to -x -z */
    lights[0].dir[0] = -0.45;
    lights[0].dir[1] = -0.766;
    lights[0].dir[2] = -0.46;
    lights[0].rgb[0] = 3.0;
    lights[0].rgb[1] = 2.8;
    lights[0].rgb[2] = 2.4;
    lights[1].type = 4; /* the sky over +Y, bluer at the zenith */
    lights[1].rgb[0] = 0.20;
    lights[1].rgb[1] = 0.26;
    lights[1].rgb[2] = 0.40;
    lights[1].horizon[0] = 0.30;
    lights[1].horizon[1] = 0.32;
    lights[1].horizon[2] = 0.36;
    lights[1].dirs = 48;
    *n = l.n;
    return l.p;
}

int level_write(const char *dir, char *err, size_t errlen)
{
    static const char *const names[3] = {"level.obj", "level.mtl", "level.json"};
    fio_out *out[3] = {NULL, NULL, NULL};
    FILE *obj, *mtl, *js;
    sc_light l[LEVEL_LIGHTS];
    int n, i, k, j, nm = 0, cur = -1, v = 1, rc = -1;
    sc_poly *p = level_atrium(&n, l);
    double(*mats)[3] = p ? malloc((size_t)n * sizeof *mats) : NULL;
    if (!mats) {
        snprintf(err, errlen, "out of memory");
        goto done;
    }
    for (k = 0; k < 3; k++) { /* each written in full or not at all (fio_out) */
        char path[4096];
        if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, names[k]) >= sizeof path) {
            snprintf(err, errlen, "%s: path too long", dir);
            goto done;
        }
        if (!(out[k] = fio_out_open(path, err, errlen))) goto done;
    }
    obj = fio_out_stream(out[0]);
    mtl = fio_out_stream(out[1]);
    js = fio_out_stream(out[2]);
    fprintf(obj, "# rad_bench --write-level: the benchmark's atrium "
                 "(tools/bench/level.c)\nmtllib level.mtl\n");
    for (i = 0; i < n; i++)
        for (k = 0; k < p[i].n; k++)
            fprintf(obj, "v %.6f %.6f %.6f\n", p[i].v[k][0], p[i].v[k][1], p[i].v[k][2]);
    for (i = 0; i < n; i++) { /* a material per reflectance, in order of first use */
        for (j = 0; j < nm && memcmp(mats[j], p[i].rho, sizeof mats[j]) != 0; j++) continue;
        if (j == nm) {
            memcpy(mats[nm++], p[i].rho, sizeof mats[j]);
            fprintf(mtl, "newmtl m%d\nKd %.6f %.6f %.6f\n", j, p[i].rho[0], p[i].rho[1],
                    p[i].rho[2]);
        }
        if (j != cur) fprintf(obj, "usemtl m%d\n", cur = j);
        fprintf(obj, "f");
        for (k = 0; k < p[i].n; k++) fprintf(obj, " %d", v++);
        fprintf(obj, "\n");
    }
    fprintf(js, "{\"lights\": [\n");
    for (i = 0; i < LEVEL_LIGHTS; i++) {
        const sc_light *a = &l[i];
        if (a->type == 1)
            fprintf(js,
                    "  {\"type\": \"sun\", \"direction\": [%.9g, %.9g, %.9g], \"irradiance\": "
                    "[%.9g, %.9g, %.9g]}",
                    a->dir[0], a->dir[1], a->dir[2], a->rgb[0], a->rgb[1], a->rgb[2]);
        else
            fprintf(js,
                    "  {\"type\": \"sky\", \"radiance\": [%.9g, %.9g, %.9g], \"horizon\": "
                    "[%.9g, %.9g, %.9g], "
                    "\"directions\": %d}",
                    a->rgb[0], a->rgb[1], a->rgb[2], a->horizon[0], a->horizon[1], a->horizon[2],
                    a->dirs);
        fprintf(js, i + 1 < LEVEL_LIGHTS ? ",\n" : "\n");
    }
    fprintf(js, "]}\n");
    for (rc = 0, k = 0; k < 3 && rc == 0; k++) {
        rc = fio_out_commit(out[k], err, errlen) < 0 ? -1 : 0;
        out[k] = NULL; /* freed either way */
    }
done:
    for (k = 0; k < 3; k++)
        if (out[k]) fio_out_abort(out[k]);
    free(mats);
    free(p);
    return rc;
}
