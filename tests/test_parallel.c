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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bit_exact),
    };
    return cmocka_run_group_tests_name("parallel", tests, NULL, NULL);
}
