/* SPDX-License-Identifier: MIT */
/* Progressive refinement against closed-form solutions, and the fixed build against
 * its float twin on a Cornell-like room. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "check.h"
#include "scenes.h"

/* A closed box of uniform reflectance RHO (per channel) and emission 1 has
 * B = 1 / (1 - rho) everywhere. */
static int closed_box(sc_poly *p, const double *rho)
{
    int n = box(p, -1, -1, -1, 1, 1, 1, 1), i;
    for (i = 0; i < n; i++) set_mat(&p[i], rho[0], rho[1], rho[2], 1, 1, 1);
    return n;
}

static void check_closed_box(int twin, double max_patch, double max_elem, double per_elem_bound)
{
    static const double rho[3] = {0.3, 0.5, 0.8};
    sc_poly p[6];
    sc_opts o = {.max_patch = max_patch, .max_element = max_elem, .res = 128};
    char err[256];
    int n = closed_box(p, rho), e, c;
    double mean[3] = {0, 0, 0}, area = 0, worst = 0, worst_mean = 0;
    sc_stats stt;
    void *s = twin ? (void *)scf_create(p, n, &o, NULL, NULL, err, sizeof err)
                   : (void *)sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    assert_non_null(s);
    if (twin) {
        scf_solve(s, 100000, 1e-4, NULL, NULL);
        scf_get_stats(s, &stt);
    } else {
        sc_solve(s, 100000, 1e-4, NULL, NULL);
        sc_get_stats(s, &stt);
    }
    CHECK_LE(stt.unshot, 1e-4 + 1.0 / 65536, "%s: unshot fraction after solving to 1e-4 (Q16.16)",
             twin ? "float" : "fixed");
    for (e = 0; e < stt.elements; e++) {
        double rgb[3], a = twin ? scf_element_area(s, e) : sc_element_area(s, e);
        /* The ambient term stands in for the last 0.01% of unshot power. */
        if (twin)
            scf_element_rgb(s, e, 1, rgb);
        else
            sc_element_rgb(s, e, 1, rgb);
        for (c = 0; c < 3; c++) {
            double want = 1 / (1 - rho[c]), dev = fabs(rgb[c] / want - 1);
            mean[c] += rgb[c] * a;
            if (dev > worst) worst = dev;
        }
        area += a;
    }
    for (c = 0; c < 3; c++) {
        double want = 1 / (1 - rho[c]);
        if (fabs(mean[c] / area / want - 1) > worst_mean)
            worst_mean = fabs(mean[c] / area / want - 1);
    }
    print_message(
        "%s, patch %.3g element %.3g: mean within %.4f%% (bound 0.5%%), worst element %.2f%% "
        "(bound %.0f%%)\n",
        twin ? "float" : "fixed", max_patch, max_elem, 100 * worst_mean, 100 * worst,
        100 * per_elem_bound);
    for (c = 0; c < 3; c++) {
        double want = 1 / (1 - rho[c]);
        /* Energy balance: power is only moved, never made or lost, so the area-weighted
         * mean is exact up to the rounding of a few thousand additions. */
        CHECK_LE(fabs(mean[c] / area / want - 1), 0.005,
                 "%s, channel %d: the area-weighted mean's relative error against E / (1 - rho)",
                 twin ? "float" : "fixed", c);
    }
    CHECK_LE(worst, per_elem_bound, "%s: the worst element's relative error against E / (1 - rho)",
             twin ? "float" : "fixed");
    if (twin)
        scf_destroy(s);
    else
        sc_destroy(s);
}

static void test_closed_box(void **st)
{
    (void)st;
    /* Per element, the hemi-cube at a patch's centre stands for the whole patch: an
     * element at a corner next to the shooter receives by the centre's view, not by the
     * patch's. That error does not shrink with resolution, only with the patch size
     * relative to the distance. The bound is what one element per patch measures at
     * res 128 (the test prints it) with room for rounding (emitters always shoot from
     * every element; elsewhere 2x2 elements a patch err several times more at corners). */
    check_closed_box(0, 0.25, 0.25, 0.05);
    check_closed_box(1, 0.25, 0.25, 0.05);
}

static void test_ambient_partial(void **st)
{
    static const double rho[3] = {0.5, 0.5, 0.5};
    sc_poly p[6];
    sc_opts o = {.max_patch = 0.5, .max_element = 0.25, .res = 64};
    char err[256];
    int n = closed_box(p, rho), e, shots;
    sc_solver *s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    sc_stats stt;
    (void)st;
    assert_non_null(s);
    sc_get_stats(s, &stt);
    /* Before any shot, with all power unshot, ambient = E / (1 - rho) and the display
     * E + rho * ambient = E / (1 - rho) = 2: the closed form. */
    for (shots = 0; shots <= 40; shots += 20) {
        double mean = 0, area = 0, prev = 2;
        if (shots) sc_solve(s, 20, 0, NULL, NULL);
        for (e = 0; e < stt.elements; e++) {
            double rgb[3], a = sc_element_area(s, e);
            sc_element_rgb(s, e, 1, rgb);
            mean += rgb[0] * a;
            area += a;
        }
        print_message("after %2d shots: mean displayed radiosity %.5f (closed form 2)\n", shots,
                      mean / area);
        /* The ambient estimate is exact for uniform reflectance: any partial solution
         * displays the right mean brightness (the 1988 paper's point). */
        CHECK_NEAR(mean / area, prev, 0.005 * 2, "after %d shots: mean displayed radiosity", shots);
    }
    sc_destroy(s);
}

static void test_unshot_decreases(void **st)
{
    sc_poly p[6];
    static const double rho[3] = {0.7, 0.6, 0.5};
    /* plain shooting: overshooting owes power */
    sc_opts o = {.max_patch = 0.5, .max_element = 0.25, .res = 32, .no_overshoot = 1};
    char err[256];
    int n = closed_box(p, rho), i;
    sc_solver *s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    double last = 1.0;
    (void)st;
    assert_non_null(s);
    for (i = 0; i < 600; i++) {
        sc_stats stt;
        assert_int_equal(sc_solve(s, 1, 0, NULL, NULL), 1);
        sc_get_stats(s, &stt);
        /* Shooting moves power rho F U <= U elsewhere: the unshot total never grows. */
        CHECK_LE(stt.unshot, last, "unshot fraction after shot %d against before", i + 1);
        last = stt.unshot;
    }
    CHECK_LT(last, 0.5, "unshot fraction after 600 plain shots");
    sc_destroy(s);
}

/* A Cornell-like room in C: inward walls, two blocks, a ceiling light. */
static int cornell(sc_poly *p)
{
    int n = box(p, -1, 0, -1, 1, 2, 1, 1), i;
    for (i = 0; i < n; i++) set_mat(&p[i], 0.73, 0.71, 0.68, 0, 0, 0);
    set_mat(&p[2], 0.63, 0.065, 0.05, 0, 0, 0); /* -x: red */
    set_mat(&p[3], 0.14, 0.45, 0.091, 0, 0, 0); /* +x: green */
    n = 5;                                      /* open at +z, as the original */
    n += box(p + n, -0.6, 0, -0.6, -0.05, 1.2, -0.05, 0);
    n += box(p + n, 0.1, 0, 0.05, 0.65, 0.6, 0.6, 0);
    for (i = 5; i < n; i++) set_mat(&p[i], 0.73, 0.71, 0.68, 0, 0, 0);
    p[n] = quad(-0.25, 1.99, -0.25, 0.25, 1.99, -0.25, 0.25, 1.99, 0.25, -0.25, 1.99, 0.25);
    set_mat(&p[n], 0.78, 0.78, 0.78, 17, 12, 4);
    return n + 1;
}

static void test_twin_cornell(void **st)
{
    sc_poly p[24];
    /* At resolution 64 a floor element 2 units from the light covers a few pixels of a
     * light patch's hemi-cube, and a last-bit difference in a vertex can move a pixel
     * centre across its edge. At 128 (rad_cli's default) each covers four times the
     * pixels, and the difference is several times smaller. */
    sc_opts o = {.res = 128};
    char err[256];
    int n = cornell(p), compared;
    sc_solver *fx = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    scf_solver *fl = scf_create(p, n, &o, NULL, NULL, err, sizeof err);
    sc_stats a, b;
    double worst, rms;
    (void)st;
    assert_non_null(fx);
    assert_non_null(fl);
    /* Converged far enough that the order of shots (which may differ once two patches'
     * unshot powers tie within rounding) no longer matters. */
    sc_solve(fx, 100000, 1e-4, NULL, NULL);
    scf_solve(fl, 100000, 1e-4, NULL, NULL);
    sc_get_stats(fx, &a);
    scf_get_stats(fl, &b);
    assert_int_equal(a.elements, b.elements);
    compared = ref_twin_diff(fx, fl, &worst, &rms);
    print_message("fixed vs float: %d elements, %d channels above 1%% of max compared: max %.4f%%, "
                  "rms %.4f%%\n",
                  a.elements, compared, 100 * worst, 100 * rms);
    /* The twins run one algorithm: what differs is rounding, and a last-bit vertex
     * moving a pixel centre across an edge. Bound: 1% per element above 1% of the
     * maximum. */
    CHECK_LE(worst, 0.01,
             "fixed against float: max relative difference per element above 1%% "
             "of the maximum");
    CHECK_INT_GT(compared, a.elements / 4, "channels compared (most of the lit room)");
    sc_destroy(fx);
    scf_destroy(fl);
}

static void test_overshoot(void **st)
{
    sc_poly p[24];
    sc_opts plain_o = {.max_patch = 0.5, .max_element = 0.125, .res = 32, .no_overshoot = 1};
    sc_opts over_o = {.max_patch = 0.5, .max_element = 0.125, .res = 32};
    char err[256];
    int n = cornell(p), k;
    sc_solver *ref = sc_create(p, n, &plain_o, NULL, NULL, err, sizeof err);
    sc_solver *plain = sc_create(p, n, &plain_o, NULL, NULL, err, sizeof err);
    sc_solver *over = sc_create(p, n, &over_o, NULL, NULL, err, sizeof err);
    double worst[2], rms[2];
    int shots[2];
    (void)st;
    assert_non_null(ref);
    assert_non_null(plain);
    assert_non_null(over);
    sc_solve(ref, 100000, 1e-4, NULL, NULL);
    shots[0] = sc_solve(plain, 100000, 0.01, NULL, NULL);
    shots[1] = sc_solve(over, 100000, 0.01, NULL, NULL);
    ref_solution_diff(plain, ref, &worst[0], &rms[0]);
    ref_solution_diff(over, ref, &worst[1], &rms[1]);
    print_message(
        "to an unshot fraction of 0.01: plain %d shots (max %.3f%%, rms %.3f%% from converged), "
        "overshooting %d shots (max %.3f%%, rms %.3f%%)\n",
        shots[0], 100 * worst[0], 100 * rms[0], shots[1], 100 * worst[1], 100 * rms[1]);
    /* Overshooting needs fewer shots for partial solutions about as far from the
     * converged one: the power it shoots early is power plain shooting shoots later.
     * Bounds, with room over what the test prints: 0.8 of the shots, 1.25 times plain's
     * rms. */
    CHECK_INT_LE(shots[1] * 5, shots[0] * 4, "5 x overshooting's shots against 4 x plain's");
    CHECK_LE(rms[1], 1.25 * rms[0],
             "overshooting's rms distance from converged against 1.25 x plain's");
    /* Converged, both are the one solution of the same equations: what remains is the
     * last 1e-4 of unshot power, which the ambient term covers on average. */
    sc_solve(over, 100000, 1e-4, NULL, NULL);
    ref_solution_diff(over, ref, &worst[1], &rms[1]);
    print_message("converged to 1e-4: overshooting against plain max %.4f%%, rms %.4f%%\n",
                  100 * worst[1], 100 * rms[1]);
    CHECK_LE(worst[1], 0.001,
             "converged: overshooting against plain, max relative difference per "
             "element");
    for (k = 0; k < 2; k++) {
        sc_stats stt;
        sc_get_stats(k ? over : plain, &stt);
        CHECK_GE(stt.unshot, 0, "%s: unshot fraction (debts count by magnitude)",
                 k ? "overshooting" : "plain");
    }
    sc_destroy(ref);
    sc_destroy(plain);
    sc_destroy(over);
}

/* A closed box of reflectance 0.9 lit by one face: plain shooting needs about as many
 * rounds of shots as the light takes bounces to fade (0.9^k), overshooting shoots most
 * of them at once. Both display the mean the energy balance gives, (1/6) / (1 - 0.9). */
static void test_overshoot_bright_box(void **st)
{
    int k, shots[2];
    double mean[2];
    (void)st;
    for (k = 0; k < 2; k++) {
        sc_poly p[6];
        sc_opts o = {.max_patch = 0.5, .max_element = 0.25, .res = 32};
        char err[256];
        int n = box(p, -1, -1, -1, 1, 1, 1, 1), i, e;
        sc_solver *s;
        sc_stats stt;
        double area = 0, sum = 0;
        o.no_overshoot = k == 0;
        for (i = 0; i < n; i++) set_mat(&p[i], 0.9, 0.9, 0.9, i == 0, i == 0, i == 0);
        s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
        assert_non_null(s);
        shots[k] = sc_solve(s, 100000, 0.01, NULL, NULL);
        sc_get_stats(s, &stt);
        CHECK_LE(stt.unshot, 0.01 + 1.0 / 65536, "%s: unshot fraction after solving to 0.01",
                 k ? "overshooting" : "plain");
        assert_int_equal(stt.saturations, 0);
        for (e = 0; e < stt.elements; e++) {
            double rgb[3], a = sc_element_area(s, e);
            sc_element_rgb(s, e, 1, rgb);
            sum += rgb[0] * a;
            area += a;
        }
        mean[k] = sum / area;
        sc_destroy(s);
    }
    print_message("closed box, rho 0.9, to 0.01: plain %d shots, overshooting %d; mean displayed "
                  "%.4f and %.4f "
                  "(energy balance %.4f)\n",
                  shots[0], shots[1], mean[0], mean[1], 1.0 / 6 / (1 - 0.9));
    /* Bound: a quarter of plain's shots. */
    CHECK_INT_LE(4 * shots[1], shots[0], "4 x overshooting's shots against plain's");
    /* The ambient term covers the 1% left unshot exactly for uniform reflectance: the
     * means agree with the balance within rounding. */
    for (k = 0; k < 2; k++)
        CHECK_LE(fabs(mean[k] * 6 * (1 - 0.9) - 1), 0.002,
                 "%s: mean displayed radiosity's relative error against the energy balance",
                 k ? "overshooting" : "plain");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_box),       cmocka_unit_test(test_ambient_partial),
        cmocka_unit_test(test_unshot_decreases), cmocka_unit_test(test_twin_cornell),
        cmocka_unit_test(test_overshoot),        cmocka_unit_test(test_overshoot_bright_box),
    };
    return cmocka_run_group_tests_name("solver", tests, NULL, NULL);
}
