/* The parallel solve (threads in tools/, parts in the core) against the serial one. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "check.h"
#include "host/obj_polys.h"
#include "host/parallel.h"
#include "rad/rad.h"
#include "scenes.h"

static sc_poly *cornell(int *n)
{
    obj_scene sc;
    char err[256];
    sc_poly *p;
    assert_int_equal(obj_load("examples/cornell_box.obj", &sc, NULL, NULL, err, sizeof err), 0);
    p = obj_to_polys(&sc, n, NULL, NULL);
    obj_free(&sc);
    assert_non_null(p);
    return p;
}

/* 1, 2, 3 and 7 parts: every element's radiosity the same bits as serially, in the
 * build P (sc: fixed, scf: the float twin; both add the parts in the serial order). */
#define BIT_EXACT(P)                                                                      \
    static void bit_exact_##P(const sc_poly *p, int n)                                    \
    {                                                                                     \
        int threads;                                                                      \
        sc_opts o = {.max_element = 0.04, .res = 64};                                     \
        char err[256];                                                                    \
        P##_solver *ref = P##_create(p, n, &o, NULL, NULL, err, sizeof err);              \
        uint64_t want;                                                                    \
        sc_stats a;                                                                       \
        assert_non_null(ref);                                                             \
        assert_int_equal(P##_solve(ref, 300, 0, NULL, NULL), 300);                        \
        want = P##_checksum(ref);                                                         \
        P##_get_stats(ref, &a);                                                           \
        for (threads = 1; threads <= 7; threads += threads < 3 ? 1 : 4) {                 \
            P##_solver *s = P##_create(p, n, &o, NULL, NULL, err, sizeof err);            \
            sc_stats b;                                                                   \
            assert_non_null(s);                                                           \
            assert_int_equal(P##_solve_parallel(s, threads, 300, 0, NULL, NULL), 300);    \
            P##_get_stats(s, &b);                                                         \
            assert_int_equal(P##_checksum(s), want);                                      \
            /* Parts split the cube's rows: each pixel is drawn by one part, but a      \
             * polygon crossing a cut is set up once in each part it touches. */         \
            assert_int_equal(b.raster_pixels, a.raster_pixels);                           \
            CHECK_INT_GE(b.raster_calls, a.raster_calls, "polygons set up on %d threads "    \
                         "against 1", threads);                                           \
            if (threads == 1) assert_int_equal(b.raster_calls, a.raster_calls);           \
            P##_destroy(s);                                                               \
        }                                                                                 \
        P##_destroy(ref);                                                                 \
    }
BIT_EXACT(sc)
BIT_EXACT(scf)

static void test_bit_exact(void **st)
{
    int n;
    sc_poly *p = cornell(&n);
    char err[256];
    (void)st;
    bit_exact_sc(p, n);
    bit_exact_scf(p, n);
    /* A banded core cannot split a shot: a clear refusal, not a wrong answer. */
    {
        sc_opts ob = {.max_element = 0.04, .res = 64, .band_rows = 8};
        sc_solver *s = sc_create(p, n, &ob, NULL, NULL, err, sizeof err);
        assert_non_null(s);
        assert_int_equal(sc_solve_parallel(s, 2, 10, 0, NULL, NULL), -1);
        sc_destroy(s);
    }
    free(p);
}

/* Shots through the core's split calls, NPARTS parts, the receiving parts run last
 * first: each part writes only its own elements and patches, so any order gives the
 * serial bits. Out-of-order calls are refused and change nothing. */
static void split_shots(sc_solver *h, unsigned nparts, int shots)
{
    rad_scene_t *s = sc_core(h);
    size_t bytes = RAD_PART_BYTES(s->cfg.res);
    void *bufs[4];
    unsigned k;
    int shot;
    assert_true(nparts <= 4);
    for (k = 0; k < nparts; k++) assert_non_null(bufs[k] = malloc(bytes));
    for (shot = 0; shot < shots; shot++) {
        uint32_t p, st0 = s->stats.shots;
        int got = 0;
        assert_int_equal(rad_shot_begin(s, 0, &p), 1);
        for (k = 0; k < nparts; k++) CHECK_INT_GE(rad_shot_part(s, p, k, nparts, bufs[k], bytes), 0, "part %u", k);
        assert_int_equal(rad_shot_receive_part(s, p, bufs, nparts, 0), RAD_ERR_STATE); /* not aimed */
        assert_int_equal(rad_shot_aim(s, p, bufs, nparts), 1);
        assert_int_equal(rad_shot_aim(s, p, bufs, nparts), RAD_ERR_STATE); /* aimed twice */
        assert_int_equal(rad_shot_receive_part(s, p, bufs, nparts, nparts), RAD_ERR_ARG);
        for (k = nparts; k-- > 0;) {
            int r = rad_shot_receive_part(s, p, bufs, nparts, k);
            CHECK_INT_GE(r, 0, "receiving part %u of %u", k, nparts);
            got += r;
        }
        assert_int_equal(rad_shot_receive_part(s, p, bufs, nparts, 0), RAD_ERR_STATE); /* twice */
        /* A closed box: every element but the shooter's surface's sees the shooter. */
        CHECK_INT_GT(got, 0, "elements that received in shot %d", shot);
        assert_int_equal(rad_shot_end(s, p, bufs, nparts), 1);
        assert_int_equal(s->stats.shots, st0 + 1u);
        assert_int_equal(rad_shot_end(s, p, bufs, nparts), RAD_ERR_STATE); /* shot twice */
        assert_int_equal(s->stats.shots, st0 + 1u);
    }
    for (k = 0; k < nparts; k++) free(bufs[k]);
}

/* Every patch's unshot power the same bits in A and B. */
static void unshot_same(const rad_scene_t *a, const rad_scene_t *b)
{
    uint32_t p, c;
    assert_int_equal(a->n_patches, b->n_patches);
    for (p = 0; p < a->n_patches; p++)
        for (c = 0; c < 3; c++) assert_int_equal(a->pools.patches[p].unshot[c], b->pools.patches[p].unshot[c]);
}

static void test_split_receive(void **st)
{
    int n;
    unsigned nparts;
    sc_poly *p = cornell(&n);
    sc_opts o = {.max_element = 0.04, .res = 64};
    char err[256];
    sc_solver *ref = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    sc_stats a;
    (void)st;
    assert_non_null(ref);
    assert_int_equal(sc_solve(ref, 60, 0, NULL, NULL), 60);
    sc_get_stats(ref, &a);
    for (nparts = 1; nparts <= 4; nparts++) {
        sc_solver *s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
        sc_stats b;
        assert_non_null(s);
        split_shots(s, nparts, 60);
        sc_get_stats(s, &b);
        assert_int_equal(sc_checksum(s), sc_checksum(ref));
        unshot_same(sc_core(ref), sc_core(s));
        assert_int_equal(b.shots, a.shots);
        assert_int_equal(b.raster_pixels, a.raster_pixels);
        sc_destroy(s);
    }
    sc_destroy(ref);
    free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bit_exact),
        cmocka_unit_test(test_split_receive),
    };
    return cmocka_run_group_tests_name("parallel", tests, NULL, NULL);
}
