/* SPDX-License-Identifier: MIT */
/* The final gather (tools/host/fgather.c): vertices and pixels shaded by gathering the
 * light arriving instead of interpolating elements.
 *
 * Sharper than the mesh: the bundled Cornell box at rad_cli's defaults (elements of
 * 1/24 of the extent, hemi-cube 128, tolerance 0.001, the ambient term) against a
 * reference solved with elements 4 times finer (patches as the default's), taken at
 * each coarse vertex by interpolating its fine elements as the renderer does (the fine
 * vertices' values, barycentric in the fine triangle holding the point). Element
 * interpolation averages the elements around a vertex, so at a shadow's edge it is off
 * by up to half the step between them; a gather at the vertex sees the edge where it
 * is. Per vertex and channel, over values above 1% of the brightest (emitters left
 * out: a lamp keeps its interpolated value), the gather's rms relative error must be at
 * most half the interpolation's (the goal); both are printed.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "formats/obj.h"
#include "host/fgather.h"
#include "host/obj_polys.h"
#include "host/parallel.h"
#include "host/scene.h"
#include "rad/rad.h"

#define CORNELL "examples/cornell_box.obj"
#define RES 128       /* rad_cli's hemi-cube */
#define TOL 0.001     /* rad_cli's --tol */
#define GATHER_RES 64 /* rad_cli's gather cube without --gather */
#define THREADS 2     /* the test machine's cores */

typedef struct {
    obj_scene sc;
    sc_poly *p;
    int n;
    double extent;
} scene_t;

static void scene_load(scene_t *s, const char *path)
{
    char err[512];
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    int i, k, a;
    if (obj_load(path, &s->sc, NULL, NULL, err, sizeof err) < 0) fail_msg("%s", err);
    s->p = obj_to_polys(&s->sc, &s->n, NULL, NULL);
    assert_non_null(s->p);
    for (i = 0; i < s->n; i++)
        for (k = 0; k < s->p[i].n; k++)
            for (a = 0; a < 3; a++) {
                lo[a] = fmin(lo[a], s->p[i].v[k][a]);
                hi[a] = fmax(hi[a], s->p[i].v[k][a]);
            }
    s->extent = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
}

static void scene_free(scene_t *s)
{
    free(s->p);
    obj_free(&s->sc);
}

/* Solved at rad_cli's defaults with elements of EXTENT / DIV (patches 4 elements), on
 * THREADS threads (the same bits as one). */
static sc_solver *solved(const scene_t *s, double div)
{
    sc_opts o;
    char err[512];
    sc_solver *h;
    memset(&o, 0, sizeof o);
    o.res = RES;
    o.max_element = s->extent / div;
    h = sc_create(s->p, s->n, &o, NULL, NULL, err, sizeof err);
    if (!h) fail_msg("sc_create: %s", err);
    CHECK_INT_GT(sc_solve_parallel(h, THREADS, 1000000, TOL, NULL, NULL), 0,
                 "shots of the solve at elements of extent / %g", div);
    return h;
}

static double seg_distance(const double *p, const double *a, const double *b)
{
    double ab[3], ap[3], t, d = 0, l = 0, q;
    int k;
    for (k = 0; k < 3; k++) {
        ab[k] = b[k] - a[k];
        ap[k] = p[k] - a[k];
        l += ab[k] * ab[k];
        d += ap[k] * ab[k];
    }
    t = l > 0 ? fmin(fmax(d / l, 0.0), 1.0) : 0.0;
    for (d = 0, k = 0; k < 3; k++) {
        q = ap[k] - t * ab[k];
        d += q * q;
    }
    return sqrt(d);
}

/* The distance from P to convex polygon Q. */
static double poly_distance(const double *p, const sc_poly *q)
{
    double n[3] = {0, 0, 0}, l, h = 0, best = HUGE_VAL;
    int k, a, inside = 1;
    for (k = 0; k < q->n; k++) {
        const double *u = q->v[k], *w = q->v[(k + 1) % q->n];
        n[0] += (u[1] - w[1]) * (u[2] + w[2]);
        n[1] += (u[2] - w[2]) * (u[0] + w[0]);
        n[2] += (u[0] - w[0]) * (u[1] + w[1]);
    }
    l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (a = 0; a < 3; a++) h += (p[a] - q->v[0][a]) * n[a] / l;
    for (k = 0; k < q->n; k++) {
        const double *u = q->v[k], *w = q->v[(k + 1) % q->n];
        double e[3], r[3], c[3];
        for (a = 0; a < 3; a++) {
            e[a] = w[a] - u[a];
            r[a] = p[a] - u[a];
        }
        c[0] = e[1] * r[2] - e[2] * r[1];
        c[1] = e[2] * r[0] - e[0] * r[2];
        c[2] = e[0] * r[1] - e[1] * r[0];
        if (c[0] * n[0] + c[1] * n[1] + c[2] * n[2] < 0) inside = 0;
        best = fmin(best, seg_distance(p, u, w));
    }
    return inside ? fabs(h) : best;
}

/* Whether P (on a polygon of tag TAG) lies farther than D from every other polygon. */
static int apart(const scene_t *s, const double *p, int tag, double d)
{
    int i;
    for (i = 0; i < s->n; i++)
        if (s->p[i].tag != tag && poly_distance(p, &s->p[i]) <= d) return 0;
    return 1;
}

/* The barycentric weights of P in triangle A, B, C (projected on its plane). */
static void barycentric(const double *a, const double *b, const double *c, const double *p, double *w)
{
    double e1[3], e2[3], d[3], d11 = 0, d12 = 0, d22 = 0, d1 = 0, d2 = 0, det;
    int k;
    for (k = 0; k < 3; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
        d[k] = p[k] - a[k];
        d11 += e1[k] * e1[k];
        d12 += e1[k] * e2[k];
        d22 += e2[k] * e2[k];
        d1 += d[k] * e1[k];
        d2 += d[k] * e2[k];
    }
    det = d11 * d22 - d12 * d12;
    w[1] = (d1 * d22 - d2 * d12) / det;
    w[2] = (d2 * d11 - d1 * d12) / det;
    w[0] = 1 - w[1] - w[2];
}

/* The fine solution's rendered value at P on surface SURF: its elements' triangles
 * (a quad as the renderer's fan from its first vertex), the one holding P best. */
static void fine_at(sc_solver *f, const int *first, const int *count, int surf, const double *vrgb, const double *p,
                    double *out)
{
    double best = -HUGE_VAL;
    int i, t, k;
    for (i = first[surf]; i < first[surf] + count[surf]; i++) {
        int v[4], n = sc_element_vertices(f, i, v);
        for (t = 1; t + 1 < n; t++) {
            double a[3], b[3], c[3], w[3], lo;
            sc_vertex_pos(f, v[0], a);
            sc_vertex_pos(f, v[t], b);
            sc_vertex_pos(f, v[t + 1], c);
            barycentric(a, b, c, p, w);
            lo = fmin(w[0], fmin(w[1], w[2]));
            if (lo <= best) continue;
            best = lo;
            for (k = 0; k < 3; k++)
                out[k] = w[0] * vrgb[3 * v[0] + k] + w[1] * vrgb[3 * v[t] + k] + w[2] * vrgb[3 * v[t + 1] + k];
        }
    }
    /* Both meshes' vertices are rounded to the core's 2^-16 of 1/64 of the extent: over a
     * fine element (1/96 of it) a weight may be off by 2^-22 * 96 = 2.3e-5. */
    CHECK_GE(best, -1e-4, "coarse vertex (%g, %g, %g) inside a fine element of surface %d", p[0], p[1], p[2], surf);
}

typedef struct {
    double sum2, max;
    int n;
} err_t;

static void add_err(err_t *e, double got, double ref)
{
    double r = fabs(got - ref) / ref;
    e->sum2 += r * r;
    e->max = fmax(e->max, r);
    e->n++;
}

static void test_sharper_than_mesh(void **state)
{
    scene_t s;
    sc_solver *c, *f;
    sc_fgather *fg;
    sc_stats cs, fs;
    const rad_scene_t *cc, *fc;
    double *ref, *interp, *gath, *fine, top = 0;
    int *first, *count, si, k;
    uint32_t v;
    err_t e[2][2]; /* [interpolation, gather][every vertex, apart from other polygons] */
    (void)state;
    memset(e, 0, sizeof e);
    scene_load(&s, CORNELL);
    c = solved(&s, 24.0);
    f = solved(&s, 96.0);
    sc_get_stats(c, &cs);
    sc_get_stats(f, &fs);
    cc = sc_core(c);
    fc = sc_core(f);
    assert_int_equal(cc->n_surfaces, fc->n_surfaces);
    ref = calloc(3 * (size_t)cs.vertices, sizeof *ref);
    interp = calloc(3 * (size_t)cs.vertices, sizeof *interp);
    gath = calloc(3 * (size_t)cs.vertices, sizeof *gath);
    fine = calloc(3 * (size_t)fs.vertices, sizeof *fine);
    first = calloc(fc->n_surfaces, sizeof *first);
    count = calloc(fc->n_surfaces, sizeof *count);
    assert_true(ref && interp && gath && fine && first && count);
    fg = sc_fgather_new(c, s.p, s.n, GATHER_RES, THREADS, 1);
    assert_non_null(fg);
    assert_int_equal(sc_vertex_colours(c, NULL, 1, interp), 0);
    assert_int_equal(sc_vertex_colours(c, fg, 1, gath), 0);
    assert_int_equal(sc_shade(f, 1, fine), 0);
    for (si = 0; si < (int)fc->n_surfaces; si++) {
        first[si] = (int)fc->pools.surfaces[si].first_element;
        count[si] = (int)fc->pools.surfaces[si].n_elements;
    }
    for (si = 0; si < (int)cc->n_surfaces; si++) {
        const rad_surface_t *sf = &cc->pools.surfaces[si];
        for (v = sf->first_vertex; v < sf->first_vertex + sf->n_vertices; v++) {
            double p[3];
            sc_vertex_pos(c, (int)v, p);
            fine_at(f, first, count, si, fine, p, &ref[3 * v]);
            for (k = 0; k < 3 && !sf->emission.r && !sf->emission.g && !sf->emission.b; k++)
                top = fmax(top, ref[3 * v + k]);
        }
    }
    for (si = 0; si < (int)cc->n_surfaces; si++) {
        const rad_surface_t *sf = &cc->pools.surfaces[si];
        int tag = sc_element_tag(c, (int)sf->first_element);
        if (sf->emission.r || sf->emission.g || sf->emission.b) continue;
        for (v = sf->first_vertex; v < sf->first_vertex + sf->n_vertices; v++) {
            double p[3];
            int far;
            sc_vertex_pos(c, (int)v, p);
            far = apart(&s, p, tag, s.extent / 96.0);
            for (k = 0; k < 3; k++)
                if (ref[3 * v + k] > 0.01 * top) {
                    add_err(&e[0][0], interp[3 * v + k], ref[3 * v + k]);
                    add_err(&e[1][0], gath[3 * v + k], ref[3 * v + k]);
                    if (!far) continue;
                    add_err(&e[0][1], interp[3 * v + k], ref[3 * v + k]);
                    add_err(&e[1][1], gath[3 * v + k], ref[3 * v + k]);
                }
        }
    }
    print_message("Cornell box, %d vertices (%d elements) against %d elements 4x finer; relative error per vertex "
                  "and channel above 1%% of the brightest:\n",
                  cs.vertices, cs.elements, fs.elements);
    for (k = 0; k < 2; k++)
        print_message("  %s (%d values): element interpolation rms %.4f max %.3f, gather (res %d) rms %.4f max %.3f\n",
                      k ? "apart from other polygons" : "every vertex", e[0][k].n, sqrt(e[0][k].sum2 / e[0][k].n),
                      e[0][k].max, GATHER_RES, sqrt(e[1][k].sum2 / e[1][k].n), e[1][k].max);
    CHECK_INT_GT(e[0][1].n, cs.vertices, "values compared apart from other polygons");
    CHECK_LE(sqrt(e[1][1].sum2 / e[1][1].n), 0.5 * sqrt(e[0][1].sum2 / e[0][1].n),
             "rms error of the vertex gather against half element interpolation's, apart from other polygons");
    sc_fgather_free(fg);
    free(ref);
    free(interp);
    free(gath);
    free(fine);
    free(first);
    free(count);
    sc_destroy(c);
    sc_destroy(f);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sharper_than_mesh),
    };
    return cmocka_run_group_tests_name("fgather", tests, NULL, NULL);
}
