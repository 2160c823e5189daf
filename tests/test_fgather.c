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
 * most half the interpolation's (the goal), over the vertices farther than one
 * fine element from every other polygon (nearer, the reference mixes in fine elements
 * under a box or behind a corner, which no view shows); both sets are printed. The
 * reference's patches are 4x finer too (--max-element L/4's default): with the
 * default's patches both solutions share the shooters' near-field error. A view
 * likewise against the fine render, away from outlines; 3 threads give 1's bits.
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
#include "host/polys.h"
#include "host/parallel.h"
#include "host/scene.h"
#include "host/tex_render.h"
#include "rad/rad.h"

#define CORNELL     "examples/cornell_box.obj"
#define RES         128   /* rad_cli's hemi-cube */
#define TOL         0.001 /* rad_cli's --tol */
/* The gather cube: at 32 the lamp aliases and the gather is worse than interpolation
 * (rms 0.076 against 0.067); 128 gives 0.020 at twice the time. */
#define GATHER_RES  64
#define THREADS     2   /* the test machine's cores */
#define IMAGE_BOUND 0.5 /* the vertices' goal, for a view */

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
    s->p = polys_from_obj(&s->sc, &s->n, NULL, NULL);
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
static void barycentric(const double *a, const double *b, const double *c, const double *p,
                        double *w)
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
static void fine_at(sc_solver *f, const int *first, const int *count, int surf, const double *vrgb,
                    const double *p, double *out)
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
                out[k] = w[0] * vrgb[3 * v[0] + k] + w[1] * vrgb[3 * v[t] + k] +
                         w[2] * vrgb[3 * v[t + 1] + k];
        }
    }
    /* Both meshes' vertices are rounded to the core's 2^-16 of 1/64 of the extent: over a
     * fine element (1/96 of it) a weight may be off by 2^-22 * 96 = 2.3e-5. */
    CHECK_GE(best, -1e-4, "coarse vertex (%g, %g, %g) inside a fine element of surface %d", p[0],
             p[1], p[2], surf);
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

/* The scene and its two solutions, shared by the tests. */
typedef struct {
    scene_t s;
    sc_solver *c, *f; /* rad_cli's defaults; elements (and patches) 4x finer */
} fixture_t;

static int setup(void **state)
{
    fixture_t *x = calloc(1, sizeof *x);
    if (!x) return -1;
    scene_load(&x->s, CORNELL);
    x->c = solved(&x->s, 24.0);
    x->f = solved(&x->s, 96.0);
    *state = x;
    return 0;
}

static int teardown(void **state)
{
    fixture_t *x = *state;
    sc_destroy(x->c);
    sc_destroy(x->f);
    scene_free(&x->s);
    free(x);
    return 0;
}

static void print_errors(const char *what, const err_t *interp, const err_t *gath)
{
    print_message("  %s (%d values): element interpolation rms %.4f max %.3f, gather (res %d) rms "
                  "%.4f max %.3f\n",
                  what, interp->n, sqrt(interp->sum2 / interp->n), interp->max, GATHER_RES,
                  sqrt(gath->sum2 / gath->n), gath->max);
}

static int emits(const rad_surface_t *sf)
{
    return sf->emission.r || sf->emission.g || sf->emission.b;
}

static void test_sharper_than_mesh(void **state)
{
    fixture_t *x = *state;
    sc_solver *c = x->c, *f = x->f;
    sc_fgather *fg;
    sc_stats cs, fs;
    const rad_scene_t *cc = sc_core(c), *fc = sc_core(f);
    double *ref, *interp, *gath, *fine, top = 0;
    int *first, *count, si, k;
    uint32_t v;
    err_t e[2][2]; /* [interpolation, gather][every vertex, apart from other polygons] */
    memset(e, 0, sizeof e);
    sc_get_stats(c, &cs);
    sc_get_stats(f, &fs);
    assert_int_equal(cc->n_surfaces, fc->n_surfaces);
    ref = calloc(3 * (size_t)cs.vertices, sizeof *ref);
    interp = calloc(3 * (size_t)cs.vertices, sizeof *interp);
    gath = calloc(3 * (size_t)cs.vertices, sizeof *gath);
    fine = calloc(3 * (size_t)fs.vertices, sizeof *fine);
    first = calloc(fc->n_surfaces, sizeof *first);
    count = calloc(fc->n_surfaces, sizeof *count);
    assert_true(ref && interp && gath && fine && first && count);
    fg = sc_fgather_new(c, x->s.p, x->s.n, GATHER_RES, THREADS, 1);
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
            for (k = 0; k < 3 && !emits(sf); k++) top = fmax(top, ref[3 * v + k]);
        }
    }
    for (si = 0; si < (int)cc->n_surfaces; si++) {
        const rad_surface_t *sf = &cc->pools.surfaces[si];
        int tag = sc_element_tag(c, (int)sf->first_element);
        if (emits(sf)) continue;
        for (v = sf->first_vertex; v < sf->first_vertex + sf->n_vertices; v++) {
            double p[3];
            int far;
            sc_vertex_pos(c, (int)v, p);
            far = apart(&x->s, p, tag, x->s.extent / 96.0);
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
    print_message("Cornell box, %d vertices (%d elements) against %d elements 4x finer; relative "
                  "error per vertex "
                  "and channel above 1%% of the brightest:\n",
                  cs.vertices, cs.elements, fs.elements);
    print_errors("every vertex", &e[0][0], &e[1][0]);
    print_errors("apart from other polygons", &e[0][1], &e[1][1]);
    CHECK_INT_GT(e[0][1].n, cs.vertices, "values compared apart from other polygons");
    CHECK_LE(sqrt(e[1][1].sum2 / e[1][1].n), 0.5 * sqrt(e[0][1].sum2 / e[0][1].n),
             "rms error of the vertex gather against half element interpolation's, apart from "
             "other polygons");
    sc_fgather_free(fg);
    free(ref);
    free(interp);
    free(gath);
    free(fine);
    free(first);
    free(count);
}

#define W 128
#define H 128

/* The view rad_cli takes by default, near enough: along -Z at the box's middle. */
static const sc_camera view = {{-0.278, 0.274, 0.75}, {-0.278, 0.274, -0.28}, {0, 1, 0}, 45.0};

/* Pixel I of a W x H view of surfaces SURF, and its 8 neighbours, show one surface that
 * does not emit: away from the outlines, where two meshes' renders part by a pixel. */
static int inner_pixel(const rad_scene_t *core, const int *surf, int i)
{
    int x = i % W, y = i / W, dx, dy;
    if (x == 0 || y == 0 || x == W - 1 || y == H - 1 || surf[i] < 0 ||
        emits(&core->pools.surfaces[surf[i]]))
        return 0;
    for (dy = -1; dy <= 1; dy++)
        for (dx = -1; dx <= 1; dx++)
            if (surf[i + dy * W + dx] != surf[i]) return 0;
    return 1;
}

/* A view through the gather against the fine solution's render, per pixel and channel
 * above 1% of the brightest, away from outlines and lamps: closer than the coarse
 * solution's render. */
static void test_image_sharper(void **state)
{
    fixture_t *x = *state;
    float *interp = malloc(3 * W * H * sizeof *interp), *gath = malloc(3 * W * H * sizeof *gath);
    float *ref = malloc(3 * W * H * sizeof *ref);
    int *surf = malloc(W * H * sizeof *surf), i, k;
    const rad_scene_t *cc = sc_core(x->c);
    char err[512];
    long gathers = 0;
    double top = 0;
    err_t e[2];
    sc_fgather *fg = sc_fgather_new(x->c, x->s.p, x->s.n, GATHER_RES, THREADS, 1);
    memset(e, 0, sizeof e);
    assert_true(interp && gath && ref && surf && fg);
    assert_int_equal(sc_render(x->c, &view, 1, W, H, interp, err, sizeof err), 0);
    assert_int_equal(sc_render(x->f, &view, 1, W, H, ref, err, sizeof err), 0);
    assert_int_equal(sc_fgather_render(fg, &view, W, H, gath, &gathers, err, sizeof err), 0);
    assert_int_equal(sc_render_surfaces(x->c, &view, W, H, surf, err, sizeof err), 0);
    for (i = 0; i < W * H; i++)
        for (k = 0; k < 3 && inner_pixel(cc, surf, i); k++) top = fmax(top, ref[3 * i + k]);
    for (i = 0; i < W * H; i++)
        for (k = 0; k < 3 && inner_pixel(cc, surf, i); k++)
            if (ref[3 * i + k] > 0.01 * top) {
                add_err(&e[0], interp[3 * i + k], ref[3 * i + k]);
                add_err(&e[1], gath[3 * i + k], ref[3 * i + k]);
            }
    print_message(
        "a %dx%d view, %ld gathers (%.0f%% of the pixels), against the fine solution's render:\n",
        W, H, gathers, 100.0 * gathers / (W * H));
    print_errors("pixels", &e[0], &e[1]);
    CHECK_INT_GT(e[0].n, W * H, "values compared");
    CHECK_LE(sqrt(e[1].sum2 / e[1].n), IMAGE_BOUND * sqrt(e[0].sum2 / e[0].n),
             "rms error of the gathered view against %g times the interpolated view's",
             IMAGE_BOUND);
    sc_fgather_free(fg);
    free(interp);
    free(gath);
    free(ref);
    free(surf);
}

/* Gathers on 3 threads give the bits of 1: vertices and a view (its grid, its cells). */
static void test_threads_same_bits(void **state)
{
    fixture_t *x = *state;
    sc_stats st;
    sc_fgather *one = sc_fgather_new(x->c, x->s.p, x->s.n, 16, 1, 1),
               *three = sc_fgather_new(x->c, x->s.p, x->s.n, 16, 3, 1);
    double *a, *b;
    float *ia = malloc(3 * 61 * 37 * sizeof *ia), *ib = malloc(3 * 61 * 37 * sizeof *ib);
    char err[512];
    long ga = 0, gb = 0;
    sc_get_stats(x->c, &st);
    a = malloc(3 * (size_t)st.vertices * sizeof *a);
    b = malloc(3 * (size_t)st.vertices * sizeof *b);
    assert_true(one && three && a && b && ia && ib);
    assert_int_equal(sc_vertex_colours(x->c, one, 1, a), 0);
    assert_int_equal(sc_vertex_colours(x->c, three, 1, b), 0);
    assert_memory_equal(a, b, 3 * (size_t)st.vertices * sizeof *a);
    assert_int_equal(sc_fgather_render(one, &view, 61, 37, ia, &ga, err, sizeof err), 0);
    assert_int_equal(sc_fgather_render(three, &view, 61, 37, ib, &gb, err, sizeof err), 0);
    assert_int_equal(ga, gb);
    assert_memory_equal(ia, ib, 3 * 61 * 37 * sizeof *ia);
    sc_fgather_free(one);
    sc_fgather_free(three);
    free(a);
    free(b);
    free(ia);
    free(ib);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sharper_than_mesh),
        cmocka_unit_test(test_image_sharper),
        cmocka_unit_test(test_threads_same_bits),
    };
    return cmocka_run_group_tests_name("fgather", tests, setup, teardown);
}
