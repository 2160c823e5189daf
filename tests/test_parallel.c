/* The parallel solve (threads in tools/, parts in the core) against the serial one. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "objpoly.h"
#include "parallel.h"
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

static void test_bit_exact(void **st)
{
    int n, threads;
    sc_poly *p = cornell(&n);
    sc_opts o = {0, 0.04, 64, 0, 0};
    char err[256];
    sc_solver *ref = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    uint64_t want;
    sc_stats a;
    (void)st;
    assert_non_null(ref);
    assert_int_equal(sc_solve(ref, 300, 0, NULL, NULL), 300);
    want = sc_checksum(ref);
    sc_get_stats(ref, &a);
    /* 1, 2, 3 and 7 parts: every element's radiosity the same bits as serially. */
    for (threads = 1; threads <= 7; threads += threads < 3 ? 1 : 4) {
        sc_solver *s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
        sc_stats b;
        assert_non_null(s);
        assert_int_equal(sc_solve_parallel(s, threads, 300, 0, NULL, NULL), 300);
        sc_get_stats(s, &b);
        assert_true(sc_checksum(s) == want);
        assert_int_equal(b.raster_calls, a.raster_calls);
        assert_true(b.raster_pixels == a.raster_pixels);
        sc_destroy(s);
    }
    /* A banded core cannot split a shot: a clear refusal, not a wrong answer. */
    {
        sc_opts ob = o;
        sc_solver *s;
        ob.band_rows = 8;
        s = sc_create(p, n, &ob, NULL, NULL, err, sizeof err);
        assert_non_null(s);
        assert_int_equal(sc_solve_parallel(s, 2, 10, 0, NULL, NULL), -1);
        sc_destroy(s);
    }
    sc_destroy(ref);
    free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bit_exact),
    };
    return cmocka_run_group_tests_name("parallel", tests, NULL, NULL);
}
