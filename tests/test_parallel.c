/* SPDX-License-Identifier: MIT */
/* The parallel solve (threads in tools/, parts in the core) against the serial one. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "check.h"
#include "host/polys.h"
#include "host/parallel.h"
#include "rad/rad.h"
#include "scenes.h"

static sc_poly *cornell(int *n)
{
    obj_scene sc;
    char err[256];
    sc_poly *p;
    assert_int_equal(obj_load("examples/cornell_box.obj", &sc, NULL, NULL, err, sizeof err), 0);
    p = polys_from_obj(&sc, n, NULL, NULL);
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
             * polygon crossing a cut is set up once in each part it touches. */ \
            assert_int_equal(b.raster_pixels, a.raster_pixels);                           \
            CHECK_INT_GE(b.raster_calls, a.raster_calls,                                  \
                         "polygons set up on %d threads "                                 \
                         "against 1",                                                     \
                         threads);                                                        \
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
        for (k = 0; k < nparts; k++)
            CHECK_INT_GE(rad_shot_part(s, p, k, nparts, bufs[k], bytes), 0, "part %u", k);
        assert_int_equal(rad_shot_receive_part(s, p, bufs, nparts, 0),
                         RAD_ERR_STATE); /* not aimed */
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
        for (c = 0; c < 3; c++)
            assert_int_equal(a->pools.patches[p].unshot[c], b->pools.patches[p].unshot[c]);
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

/* ---- batch shooting ------------------------------------------------------------ */

/* Batches of K = 4 on 1, 2 and 3 threads: every element the same bits, in the build P
 * (sc: fixed, scf: the float twin): a cube depends on its patch alone and the shots
 * are applied in the order picked. K = 1 on 1 and 2 threads: the serial solve's bits. */
#define BATCH_BITS(P)                                                                             \
    static void batch_bits_##P(const sc_poly *p, int n)                                           \
    {                                                                                             \
        int threads;                                                                              \
        sc_opts o = {.max_element = 0.04, .res = 64};                                             \
        char err[256];                                                                            \
        P##_solver *ref = P##_create(p, n, &o, NULL, NULL, err, sizeof err), *s;                  \
        uint64_t serial, four = 0;                                                                \
        sc_stats a, b;                                                                            \
        assert_non_null(ref);                                                                     \
        assert_int_equal(P##_solve(ref, 300, 0, NULL, NULL), 300);                                \
        serial = P##_checksum(ref);                                                               \
        P##_get_stats(ref, &a);                                                                   \
        for (threads = 1; threads <= 2; threads++) {                                              \
            assert_non_null(s = P##_create(p, n, &o, NULL, NULL, err, sizeof err));               \
            assert_int_equal(P##_solve_batch(s, threads, 1, 300, 0, NULL, NULL), 300);            \
            P##_get_stats(s, &b);                                                                 \
            assert_int_equal(P##_checksum(s), serial);                                            \
            assert_int_equal(b.raster_pixels, a.raster_pixels);                                   \
            P##_destroy(s);                                                                       \
        }                                                                                         \
        for (threads = 1; threads <= 3; threads++) {                                              \
            assert_non_null(s = P##_create(p, n, &o, NULL, NULL, err, sizeof err));               \
            assert_int_equal(P##_solve_batch(s, threads, 4, 300, 0, NULL, NULL), 300);            \
            P##_get_stats(s, &b);                                                                 \
            assert_int_equal(b.shots, 300);                                                       \
            if (threads == 1) four = P##_checksum(s);                                             \
            CHECK_INT_EQ(P##_checksum(s) == four, 1,                                              \
                         "K = 4 on %d threads: checksum "                                         \
                         "%016llx, on 1: %016llx",                                                \
                         threads, (unsigned long long)P##_checksum(s), (unsigned long long)four); \
            P##_destroy(s);                                                                       \
        }                                                                                         \
        /* the batches shoot in another order than one patch at a time */                         \
        CHECK_INT_EQ(four != serial, 1, "K = 4's checksum differs from the serial one");          \
        P##_destroy(ref);                                                                         \
    }
BATCH_BITS(sc)
BATCH_BITS(scf)

static void test_batch_bits(void **st)
{
    int n;
    sc_poly *p = cornell(&n);
    (void)st;
    batch_bits_sc(p, n);
    batch_bits_scf(p, n);
    free(p);
}

/* The fixed build against its float twin, both in batches of 4 on 2 threads to 0.001,
 * each channel of each element above 1% of the brightest: the twins differ as much as
 * they do shooting one patch at a time (within 1.25 times that, + 0.01%), and within
 * 1.5% (measured on this box at res 64: 0.958% in batches, 0.956% one at a time; the
 * builds stop at 0.001 after other shots, and their pixels differ at res 64). */
static double twin_worst(const sc_poly *p, int n, int batch)
{
    sc_opts o = {.max_element = 0.04, .res = 64};
    char err[256];
    sc_solver *x = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    scf_solver *f = scf_create(p, n, &o, NULL, NULL, err, sizeof err);
    sc_stats st;
    double top = 0, worst = 0;
    int e, c;
    assert_non_null(x);
    assert_non_null(f);
    CHECK_INT_GT(sc_solve_batch(x, 2, batch, 100000, 0.001, NULL, NULL), 0, "fixed, K = %d", batch);
    CHECK_INT_GT(scf_solve_batch(f, 2, batch, 100000, 0.001, NULL, NULL), 0, "float, K = %d",
                 batch);
    sc_get_stats(x, &st);
    for (e = 0; e < st.elements; e++) {
        double a[3];
        sc_element_rgb(x, e, 1, a);
        for (c = 0; c < 3; c++) top = a[c] > top ? a[c] : top;
    }
    for (e = 0; e < st.elements; e++) {
        double a[3], b[3];
        sc_element_rgb(x, e, 1, a);
        scf_element_rgb(f, e, 1, b);
        for (c = 0; c < 3; c++)
            if (b[c] > 0.01 * top && fabs(a[c] / b[c] - 1) > worst) worst = fabs(a[c] / b[c] - 1);
    }
    sc_destroy(x);
    scf_destroy(f);
    return worst;
}

static void test_batch_twin(void **st)
{
    int n;
    sc_poly *p = cornell(&n);
    double batch, serial;
    (void)st;
    batch = twin_worst(p, n, 4);
    serial = twin_worst(p, n, 1);
    print_message(
        "fixed against float: worst channel %.4f%% in batches of 4, %.4f%% one at a time\n",
        100 * batch, 100 * serial);
    CHECK_LE(batch, 0.015, "fixed against float in batches of 4, worst channel");
    CHECK_LE(batch, 1.25 * serial + 1e-4,
             "batches of 4 against one at a time, twins' worst difference");
    free(p);
}

/* Shots to 0.001 in batches of K against one at a time: a batch's later shooters are
 * picked before the earlier ones shoot, so a batch may shoot a patch whose power the
 * earlier shots have changed; measured on this box (res 64): 0.995, 1.000, 1.021 and
 * 1.083 times K = 1's 384 shots for K = 2, 4, 8 and 16: bound 1.2. */
static void test_batch_converges(void **st)
{
    static const int ks[] = {1, 2, 4, 8, 16};
    int n, k, one = 0;
    sc_poly *p = cornell(&n);
    sc_opts o = {.max_element = 0.04, .res = 64};
    char err[256];
    (void)st;
    for (k = 0; k < 5; k++) {
        sc_solver *s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
        sc_stats b;
        int shots;
        assert_non_null(s);
        shots = sc_solve_batch(s, 2, ks[k], 100000, 0.001, NULL, NULL);
        sc_get_stats(s, &b);
        CHECK_LE(b.unshot, 0.001 + 1.0 / 65536, "K = %d: unshot fraction at the end", ks[k]);
        if (k == 0) one = shots;
        print_message("K = %2d: %d shots to 0.001 (%.3f of K = 1's)\n", ks[k], shots,
                      shots / (double)one);
        CHECK_LE(shots, 1.2 * one, "K = %d: shots to 0.001 against 1.2 x K = 1's %d", ks[k], one);
        sc_destroy(s);
    }
    free(p);
}

/* The batch calls out of order, or with buffers not the batch's, are refused with
 * RAD_ERR_STATE (bad arguments with RAD_ERR_ARG) and shoot nothing; in order, the
 * receipts in parts run last first give rad_batch_end's bits. */
static void test_batch_misuse(void **st)
{
    int n;
    sc_poly *p = cornell(&n);
    sc_opts o = {.max_element = 0.04, .res = 64};
    char err[256];
    sc_solver *h = sc_create(p, n, &o, NULL, NULL, err, sizeof err), *ref;
    rad_scene_t *s;
    size_t bytes;
    void *bufs[4], *swap[4];
    uint32_t pt[4], shots, k;
    (void)st;
    assert_non_null(h);
    s = sc_core(h);
    bytes = RAD_BATCH_BYTES(s->cfg.res, s->n_elements);
    for (k = 0; k < 4; k++) assert_non_null(bufs[k] = calloc(1, bytes));
    assert_int_equal(rad_batch_render(s, 0, 0, bufs[0], bytes), RAD_ERR_STATE); /* no batch */
    assert_int_equal(rad_batch_end(s, bufs, 1), RAD_ERR_STATE);
    assert_int_equal(rad_batch_begin(s, 0, 0, pt), RAD_ERR_ARG);
    assert_int_equal(rad_batch_begin(s, 0, RAD_BATCH_MAX + 1, pt), RAD_ERR_ARG);
    assert_int_equal(rad_batch_begin(s, 0, 4, pt), 4);
    shots = s->stats.shots;
    assert_int_equal(rad_batch_end(s, bufs, 4), RAD_ERR_STATE); /* nothing rendered */
    assert_int_equal(rad_batch_render(s, pt[0], 4, bufs[0], bytes), RAD_ERR_STATE); /* past K */
    assert_int_equal(rad_batch_render(s, pt[0], 0, bufs[0], bytes - 1), RAD_ERR_ARG);
    assert_int_equal(rad_shot_part(s, pt[0], 0, 1, bufs[0], bytes),
                     RAD_ERR_STATE); /* a batch, not a shot */
    for (k = 0; k < 4; k++)
        CHECK_INT_GE(rad_batch_render(s, pt[k], k, bufs[k], bytes), 0, "cube %u", k);
    for (k = 0; k < 4; k++) swap[k] = bufs[k ^ 1u];
    assert_int_equal(rad_batch_end(s, swap, 4), RAD_ERR_STATE); /* out of order */
    assert_int_equal(rad_batch_end(s, bufs, 3), RAD_ERR_STATE); /* not all */
    CHECK_INT_GE(rad_batch_render(s, pt[1], 0, bufs[0], bytes), 0, "cube 0 of patch %u", pt[1]);
    assert_int_equal(rad_batch_end(s, bufs, 4), RAD_ERR_STATE); /* cube 0 of the wrong patch */
    CHECK_INT_GE(rad_batch_render(s, pt[0], 0, bufs[0], bytes), 0, "cube 0 again");
    assert_int_equal(rad_batch_receive_part(s, bufs, 4, 0, 2), RAD_ERR_STATE); /* not aimed */
    assert_int_equal(s->stats.shots, shots);
    assert_int_equal(rad_batch_aim(s, bufs, 4), 4);
    assert_int_equal(rad_batch_aim(s, bufs, 4), RAD_ERR_STATE); /* aimed twice */
    assert_int_equal(rad_batch_receive_part(s, bufs, 4, 0, 5),
                     RAD_ERR_ARG); /* more parts than cubes */
    assert_int_equal(rad_batch_receive_part(s, bufs, 4, 2, 2), RAD_ERR_ARG);
    assert_int_equal(rad_batch_receive_part(s, bufs, 4, 1, 2), 4);
    assert_int_equal(rad_batch_receive_part(s, bufs, 4, 1, 2), RAD_ERR_STATE); /* twice */
    assert_int_equal(rad_batch_receive_part(s, bufs, 4, 0, 3), RAD_ERR_STATE); /* another count */
    assert_int_equal(rad_batch_receive_part(s, bufs, 4, 0, 2), 4);
    assert_int_equal(rad_batch_end(s, bufs, 4), 4);
    assert_int_equal(s->stats.shots, shots + 4u);
    assert_int_equal(rad_batch_end(s, bufs, 4), RAD_ERR_STATE); /* ended twice */
    assert_int_equal(s->stats.shots, shots + 4u);
    /* the same batch through rad_batch_end alone: the same bits */
    ref = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    assert_non_null(ref);
    {
        rad_scene_t *r = sc_core(ref);
        uint32_t q[4];
        assert_int_equal(rad_batch_begin(r, 0, 4, q), 4);
        for (k = 0; k < 4; k++) {
            assert_int_equal(q[k], pt[k]);
            CHECK_INT_GE(rad_batch_render(r, q[k], k, bufs[k], bytes), 0, "cube %u", k);
        }
        assert_int_equal(rad_batch_end(r, bufs, 4), 4);
        unshot_same(r, s);
        assert_int_equal(sc_checksum(ref), sc_checksum(h));
    }
    /* a shot voids a batch begun */
    assert_int_equal(rad_batch_begin(s, 0, 2, pt), 2);
    for (k = 0; k < 2; k++)
        CHECK_INT_GE(rad_batch_render(s, pt[k], k, bufs[k], bytes), 0, "cube %u", k);
    assert_int_equal(rad_shoot(s, 1, 0), 1);
    assert_int_equal(rad_batch_end(s, bufs, 2), RAD_ERR_STATE);
    sc_destroy(ref);
    sc_destroy(h);
    for (k = 0; k < 4; k++) free(bufs[k]);
    free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bit_exact),       cmocka_unit_test(test_split_receive),
        cmocka_unit_test(test_batch_bits),      cmocka_unit_test(test_batch_twin),
        cmocka_unit_test(test_batch_converges), cmocka_unit_test(test_batch_misuse),
    };
    return cmocka_run_group_tests_name("parallel", tests, NULL, NULL);
}
