/* SPDX-License-Identifier: MIT */
/* Stored form factors (the 1985 paper's promises): the 16-bit code, rows against
 * the hemi-cube, relighting without rendering, Gauss-Seidel against progressive
 * refinement, and light groups (fixed build). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "check.h"
#include "core_values.h"
#include "rad/rad.h"

#define NS   32
#define NP   512
#define NE   2048
#define NV   4096
#define NENT (NP * NE / 2)

typedef struct {
    rad_surface_t sf[NS];
    rad_patch_t pt[NP];
    rad_element_t el[NE];
    rad_vec3_t vx[NV];
    unsigned char work[RAD_WORK_BYTES(64, RAD_PIXELS_ALL(64), NV)];
    rad_scene_t s;
} world_t;

/* A closed room 64 x 64 x 64 with a red and a green wall, a plate, and two lights
 * (surfaces 7 and 8) under the ceiling: the scale and brightness rad_cli gives every
 * scene (64 units across, emission around 256), where Q16.16 energies keep 20 bits. */
static world_t *room(const rad_rgb_t *l1, const rad_rgb_t *l2, const rad_rgb_t *left)
{
    world_t *w = calloc(1, sizeof *w);
    rad_pools_t p;
    rad_config_t c = {.max_patch = RAD_REAL(16), .max_element = RAD_REAL(8), .res = 64};
    const rad_rgb_t white = C(0.7, 0.7, 0.7), green = C(0.15, 0.5, 0.1);
    rad_vec3_t f[9][4] = {
        {V(-32, -32, -32), V(-32, -32, 32), V(32, -32, 32), V(32, -32, -32)}, /* floor */
        {V(-32, 32, -32), V(32, 32, -32), V(32, 32, 32), V(-32, 32, 32)},     /* ceiling */
        {V(-32, -32, -32), V(-32, 32, -32), V(-32, 32, 32), V(-32, -32, 32)}, /* left */
        {V(32, -32, -32), V(32, -32, 32), V(32, 32, 32), V(32, 32, -32)},     /* right */
        {V(-32, -32, -32), V(32, -32, -32), V(32, 32, -32), V(-32, 32, -32)}, /* back */
        {V(-32, -32, 32), V(-32, 32, 32), V(32, 32, 32), V(32, -32, 32)},     /* front */
        {V(-8, 0, -8), V(-8, 0, 8), V(8, 0, 8), V(8, 0, -8)}, /* a plate, facing up */
        {V(-20, 31.6, -20), V(-12, 31.6, -20), V(-12, 31.6, -12), V(-20, 31.6, -12)}, /* light 1 */
        {V(12, 31.6, 12), V(20, 31.6, 12), V(20, 31.6, 20), V(12, 31.6, 20)},         /* light 2 */
    };
    int i;
    assert_non_null(w);
    p.surfaces = w->sf;
    p.max_surfaces = NS;
    p.patches = w->pt;
    p.max_patches = NP;
    p.elements = w->el;
    p.max_elements = NE;
    p.vertices = w->vx;
    p.max_vertices = NV;
    p.work = w->work;
    p.work_bytes = sizeof w->work;
    assert_int_equal(rad_init(&w->s, &p, &c), RAD_OK);
    for (i = 0; i < 9; i++) {
        const rad_rgb_t *refl = i == 2 ? left : i == 3 ? &green : &white;
        const rad_rgb_t *em = i == 7 ? l1 : i == 8 ? l2 : NULL;
        assert_int_equal(rad_add_polygon(&w->s, f[i], 4, refl, em), i);
    }
    return w;
}

typedef struct {
    uint32_t start[NP + 1];
    rad_index_t ids[NENT];
    uint16_t ffs[NENT];
    rad_rows_t r;
} rows_t;

static rows_t *rows_for(world_t *w)
{
    rows_t *r = calloc(1, sizeof *r);
    assert_non_null(r);
    r->r.start = r->start;
    r->r.ids = r->ids;
    r->r.ffs = r->ffs;
    r->r.max_rows = NP;
    r->r.max_entries = NENT;
    assert_int_equal(rad_rows_compute(&w->s, &r->r, NP), (int)w->s.n_patches);
    assert_int_equal(rad_rows_compute(&w->s, &r->r, NP), 0); /* all there */
    return r;
}

/* Replaces each element's radiosity by its display value with the ambient term, which
 * stands in for the power still unshot (linear in emission like the rest). */
static void bake_ambient(world_t *w)
{
    rad_rgb_t *o = calloc(NE, sizeof *o);
    uint32_t e;
    assert_non_null(o);
    for (e = 0; e < w->s.n_elements; e++) rad_element_radiosity(&w->s, e, RAD_SHADE_AMBIENT, &o[e]);
    for (e = 0; e < w->s.n_elements; e++) w->el[e].radiosity = o[e];
    free(o);
}

/* Max relative difference over channels above 1% of the brightest. */
static double max_rel(const world_t *a, const world_t *b)
{
    double top = 0, worst = 0;
    uint32_t e;
    for (e = 0; e < a->s.n_elements; e++) {
        const rad_rgb_t *x = &a->el[e].radiosity;
        if (RAD_TO_DOUBLE(x->r) > top) top = RAD_TO_DOUBLE(x->r);
        if (RAD_TO_DOUBLE(x->g) > top) top = RAD_TO_DOUBLE(x->g);
        if (RAD_TO_DOUBLE(x->b) > top) top = RAD_TO_DOUBLE(x->b);
    }
    for (e = 0; e < a->s.n_elements; e++) {
        const rad_real_t *x = &a->el[e].radiosity.r, *y = &b->el[e].radiosity.r;
        int c;
        for (c = 0; c < 3; c++) {
            double u = RAD_TO_DOUBLE(x[c]), v = RAD_TO_DOUBLE(y[c]);
            if (v < 0.01 * top) continue;
            if (fabs(u / v - 1) > worst) worst = fabs(u / v - 1);
        }
    }
    return worst;
}

static void test_code(void **st)
{
    uint32_t q;
    (void)st;
    /* Exact below 2^11; within 2^-11 relative (half an 11-bit step) above. */
    for (q = 0; q < 4096; q++)
        if (q < 2048)
            CHECK_INT_EQ(rad_ff_from_code((uint16_t)q), q, "code %u (exact below 2^11)",
                         (unsigned)q);
    for (q = 1; q < (1u << 30); q = q * 3 / 2 + 7) {
        uint16_t c = 0;
        uint32_t e = 0, m;
        while ((q >> e) >= 2048u) e++;
        m = e ? (q + (1u << (e - 1))) >> e : q;
        if (m == 2048u) {
            m = 1024u;
            e++;
        }
        c = (uint16_t)(e << 11 | m);
        CHECK_NEAR((double)rad_ff_from_code(c), q, q / 2048.0 + 0.5,
                   "form factor %u (Q2.30) through its code: within 2^-11 relative", (unsigned)q);
    }
}

static void test_rows_match_hemicube(void **st)
{
    rad_rgb_t l = C(160, 160, 160), red = C(0.6, 0.1, 0.1);
    world_t *w = room(&l, &l, &red);
    rows_t *r = rows_for(w);
    rad_ff_t *ff = calloc(NE, sizeof *ff);
    uint32_t p, i;
    (void)st;
    for (p = 0; p < w->s.n_patches; p += 5) {
        assert_int_equal(rad_form_factors(&w->s, p, ff), (int)w->s.n_elements);
        for (i = r->start[p]; i < r->start[p + 1]; i++) {
            double want = ff[r->ids[i]], got = rad_ff_from_code(r->ffs[i]);
            CHECK_NEAR(got, want, want / 2048.0 + 0.5,
                       "patch %u, element %u: stored form factor (Q2.30) within the code's 2^-11",
                       (unsigned)p, (unsigned)r->ids[i]);
            ff[r->ids[i]] = 0;
        }
        for (i = 0; i < w->s.n_elements; i++) assert_int_equal(ff[i], 0); /* nothing left out */
    }
    free(ff);
    free(r);
    free(w);
}

static void test_rows_full_and_chunks(void **st)
{
    rad_rgb_t l = C(160, 160, 160), red = C(0.6, 0.1, 0.1);
    world_t *w = room(&l, &l, &red);
    rows_t *a = rows_for(w), *b = calloc(1, sizeof *b);
    int n;
    (void)st;
    b->r.start = b->start;
    b->r.ids = b->ids;
    b->r.ffs = b->ffs;
    b->r.max_rows = NP;
    b->r.max_entries = a->start[3] + 1; /* room for three rows and a bit */
    assert_int_equal(rad_rows_compute(&w->s, &b->r, 2), 2);
    assert_int_equal(rad_rows_compute(&w->s, &b->r, 5), 1); /* the fourth does not fit */
    assert_int_equal(rad_rows_compute(&w->s, &b->r, 5), RAD_ERR_FULL);
    assert_int_equal(b->r.n_rows, 3);
    /* In chunks, the same rows as all at once. */
    assert_memory_equal(b->start, a->start, 4 * sizeof(uint32_t));
    assert_memory_equal(b->ids, a->ids, a->start[3] * sizeof(rad_index_t));
    assert_memory_equal(b->ffs, a->ffs, a->start[3] * sizeof(uint16_t));
    assert_int_equal(rad_rows_shoot(&w->s, &b->r, 10, 0), RAD_ERR_STATE);
    b->r.max_rows = 3;
    n = rad_rows_compute(&w->s, &b->r, 1);
    assert_int_equal(n, RAD_ERR_ARG);
    free(a);
    free(b);
    free(w);
}

static void test_relight_without_rendering(void **st)
{
    rad_rgb_t l = C(160, 160, 160), blue = C(32, 64, 192), red = C(0.6, 0.1, 0.1),
              yellow = C(0.7, 0.6, 0.1);
    world_t *w = room(&l, &l, &red), *fresh = room(&blue, &l, &yellow);
    rows_t *r = rows_for(w);
    uint32_t calls;
    double d;
    (void)st;
    CHECK_INT_GT(rad_rows_shoot(&w->s, &r->r, 100000, RAD_REAL(0.0002)), 0, "shots from the rows");
    /* A new colour for light 1 and for the left wall: restart and shoot from the rows. */
    assert_int_equal(rad_set_surface(&w->s, 7, NULL, &blue), RAD_OK);
    assert_int_equal(rad_set_surface(&w->s, 2, &yellow, NULL), RAD_OK);
    assert_int_equal(rad_restart(&w->s), RAD_OK);
    calls = w->s.stats.raster_calls;
    CHECK_INT_GT(rad_rows_shoot(&w->s, &r->r, 100000, RAD_REAL(0.0002)), 0,
                 "shots from the rows, relit");
    assert_int_equal(w->s.stats.raster_calls, calls); /* no hemi-cube was rendered */
    CHECK_INT_GT(rad_shoot(&fresh->s, 100000, RAD_REAL(0.0002)), 0, "shots of the fresh solve");
    d = max_rel(w, fresh);
    print_message("relit from rows vs fresh hemi-cube solve: max %.4f%% per element\n", 100 * d);
    /* The code's 2^-11 per form factor, plus the last 0.02% unshot in each. */
    CHECK_LE(d, 0.002,
             "relit from rows against a fresh hemi-cube solve: max relative difference "
             "per element above 1%% of the brightest");
    free(r);
    free(w);
    free(fresh);
}

static void test_gauss_seidel_vs_shooting(void **st)
{
    rad_rgb_t l = C(160, 144, 112), red = C(0.6, 0.1, 0.1);
    world_t *a = room(&l, &l, &red), *b = room(&l, &l, &red);
    rows_t *ra = rows_for(a), *rb = rows_for(b);
    size_t n = RAD_GS_ENTRIES(a->s.n_patches);
    rad_ff_t *m = malloc(n * sizeof *m);
    uint32_t calls = b->s.stats.raster_calls;
    int it;
    double d;
    (void)st;
    CHECK_INT_GT(rad_rows_shoot(&a->s, &ra->r, 100000, RAD_REAL(0.0001)), 0, "shots from the rows");
    bake_ambient(a);
    assert_int_equal(rad_rows_gauss_seidel(&b->s, &rb->r, m, n - 1, 100, RAD_REAL(0.0001)),
                     RAD_ERR_ARG);
    it = rad_rows_gauss_seidel(&b->s, &rb->r, m, n, 100, RAD_REAL(0.0001));
    CHECK_INT_GT(it, 1, "Gauss-Seidel sweeps to a change of 0.01%%");
    CHECK_INT_LT(it, 100, "Gauss-Seidel sweeps to a change of 0.01%%");
    assert_int_equal(b->s.stats.raster_calls, calls);
    d = max_rel(b, a);
    print_message("Gauss-Seidel (%d sweeps) vs progressive refinement: max %.4f%% per element\n",
                  it, 100 * d);
    /* The same equations solved two ways, each to 0.0001: docs/cli.md's bound for
     * Gauss-Seidel against shooting, 0.5% per element. */
    CHECK_LE(d, 0.005,
             "Gauss-Seidel against progressive refinement: max relative difference "
             "per element above 1%% of the brightest");
    CHECK_INT_EQ(rad_unshot_fraction(&b->s), 0, "unshot fraction after Gauss-Seidel");
    /* The largest tolerance: value * tol saturates, and the test against it must not
     * overflow (found by fuzz_core under UBSan); nothing moves by more, so one sweep. */
    assert_int_equal(rad_rows_gauss_seidel(&b->s, &rb->r, m, n, 100, INT32_MAX), 1);
    free(m);
    free(ra);
    free(rb);
    free(a);
    free(b);
}

static void test_light_groups(void **st)
{
    rad_rgb_t l1 = C(160, 128, 96), l2 = C(48, 80, 192), off = C(0, 0, 0), red = C(0.6, 0.1, 0.1);
    world_t *w = room(&l1, &off, &red), *sum = room(&l1, &l2, &red);
    rows_t *r = rows_for(w);
    rad_rgb_t *g1 = calloc(NE, sizeof *g1), *g2 = calloc(NE, sizeof *g2),
              *mix = calloc(NE, sizeof *mix);
    const rad_rgb_t *groups[2];
    rad_rgb_t k[2];
    uint32_t e;
    double d;
    (void)st;
    /* Group 1: light 1 alone; group 2: light 2 alone; each solved from the rows. */
    rad_rows_shoot(&w->s, &r->r, 100000, RAD_REAL(0.0001));
    bake_ambient(w);
    for (e = 0; e < w->s.n_elements; e++) g1[e] = w->el[e].radiosity;
    rad_set_surface(&w->s, 7, NULL, &off);
    rad_set_surface(&w->s, 8, NULL, &l2);
    rad_restart(&w->s);
    rad_rows_shoot(&w->s, &r->r, 100000, RAD_REAL(0.0001));
    bake_ambient(w);
    for (e = 0; e < w->s.n_elements; e++) g2[e] = w->el[e].radiosity;
    groups[0] = g1;
    groups[1] = g2;
    k[0] = C(1, 1, 1);
    k[1] = C(1, 1, 1);
    assert_int_equal(rad_mix(&w->s, groups, k, 2, mix), RAD_OK);
    for (e = 0; e < w->s.n_elements; e++) w->el[e].radiosity = mix[e];
    rad_shoot(&sum->s, 100000, RAD_REAL(0.0001));
    bake_ambient(sum);
    d = max_rel(w, sum);
    print_message("mix of two groups vs both lights solved at once: max %.4f%%\n", 100 * d);
    /* The code's 2^-11 per form factor, and rounding: each solve adds one rounding of
     * half an LSB per shot to every element it reaches. */
    CHECK_LE(d, 0.002,
             "a mix of two groups against both lights solved at once: max relative "
             "difference per element above 1%% of the brightest");
    /* Dimming: half of group 2 is half of its contribution, exactly up to rounding. */
    k[1] = C(0.5, 0.5, 0.5);
    rad_mix(&w->s, groups, k, 2, mix);
    for (e = 0; e < w->s.n_elements; e++) {
        double want = RAD_TO_DOUBLE(g1[e].b) + 0.5 * RAD_TO_DOUBLE(g2[e].b);
        CHECK_NEAR(RAD_TO_DOUBLE(mix[e].b), want, 2.0 / 65536,
                   "element %u: blue of group 1 + half group 2, within 2 LSB", (unsigned)e);
    }
    assert_int_equal(rad_mix(&w->s, NULL, k, 2, mix), RAD_ERR_ARG);
    free(g1);
    free(g2);
    free(mix);
    free(r);
    free(w);
    free(sum);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_code),
        cmocka_unit_test(test_rows_match_hemicube),
        cmocka_unit_test(test_rows_full_and_chunks),
        cmocka_unit_test(test_relight_without_rendering),
        cmocka_unit_test(test_gauss_seidel_vs_shooting),
        cmocka_unit_test(test_light_groups),
    };
    return cmocka_run_group_tests_name("rows", tests, NULL, NULL);
}
