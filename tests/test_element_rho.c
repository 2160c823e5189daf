/* SPDX-License-Identifier: MIT */
/* Reflectance per element (rad_use_element_reflectance, fixed build): a shot against the
 * same shot at the surface's reflectance, closed boxes against their energy balance and
 * E / (1 - rho), the ambient term's part, Gauss-Seidel, the errors, and a scene without
 * differing elements against one without the array, bit for bit. */
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
#include "world.h"

/* The six inner faces of the cube [-32, 32]^3, each of reflectance RHO and emission EM. */
static void box(world_t *w, const rad_rgb_t *rho, const rad_rgb_t *em)
{
    const rad_vec3_t f[6][4] = {
        {V(-32, -32, -32), V(-32, -32, 32), V(32, -32, 32), V(32, -32, -32)},
        {V(-32, 32, -32), V(32, 32, -32), V(32, 32, 32), V(-32, 32, 32)},
        {V(-32, -32, -32), V(-32, 32, -32), V(-32, 32, 32), V(-32, -32, 32)},
        {V(32, -32, -32), V(32, -32, 32), V(32, 32, 32), V(32, 32, -32)},
        {V(-32, -32, -32), V(32, -32, -32), V(32, 32, -32), V(-32, 32, -32)},
        {V(-32, -32, 32), V(-32, 32, 32), V(32, 32, 32), V(32, -32, 32)},
    };
    int i;
    for (i = 0; i < 6; i++) assert_int_equal(rad_add_polygon(&w->s, f[i], 4, rho, em), i);
}

/* A pattern of four reflectances, element by element. */
static rad_rgb_t pattern(uint32_t e)
{
    static const double r[4][3] = {
        {0.2, 0.7, 0.4}, {0.9, 0.3, 0.6}, {0.5, 0.5, 0.1}, {0.05, 0.8, 0.95}};
    return C(r[e % 4][0], r[e % 4][1], r[e % 4][2]);
}

/* W's elements given reflectances of their own: UNIFORM for every one, or (NULL)
 * pattern's. */
static void own_reflectances(world_t *w, const rad_rgb_t *uniform)
{
    uint32_t e;
    assert_int_equal(rad_use_element_reflectance(&w->s, w->rho), RAD_OK);
    for (e = 0; e < w->s.n_elements; e++) {
        rad_rgb_t r = uniform ? *uniform : pattern(e);
        assert_int_equal(rad_set_element_reflectance(&w->s, e, &r), RAD_OK);
    }
}

static double ch(const rad_rgb_t *c, int k)
{
    return RAD_TO_DOUBLE(k == 0 ? c->r : k == 1 ? c->g : c->b);
}

/* One shot of a lamp onto a floor of 4 x 4 elements in one patch: B_j = rho_j F_j U / A_j,
 * so with rho_j of its own each element has the radiosity of the shot at the surface's
 * 0.5 times rho_j / 0.5. The shot is the lamp's (the only power) and does not overshoot
 * (the lamp reflects nothing). Rounding: the power F U is the same in both runs; each
 * multiplies it by its rho (0.5 LSB of power) and divides by the area (0.5 LSB of
 * radiosity): the scaled value of the first, times rho_j / 0.5 <= 1.9, is within 1.5
 * LSB, so 2 LSB. */
static void test_one_shot(void **st)
{
    const rad_vec3_t floor4[4] = {V(-16, 0, -16), V(-16, 0, 16), V(16, 0, 16), V(16, 0, -16)};
    const rad_vec3_t lamp[4] = {V(-4, 8, -4), V(4, 8, -4), V(4, 8, 4), V(-4, 8, 4)};
    const rad_rgb_t half = C(0.5, 0.5, 0.5), em = C(10, 10, 10);
    world_t *a = world(32, 8), *b = world(32, 8);
    double worst = 0, spread = 0;
    uint32_t e;
    int k;
    (void)st;
    assert_int_equal(rad_add_polygon(&a->s, floor4, 4, &half, NULL), 0);
    assert_int_equal(rad_add_polygon(&a->s, lamp, 4, NULL, &em), 1);
    assert_int_equal(rad_use_element_reflectance(&b->s, b->rho), RAD_OK);
    assert_int_equal(rad_add_polygon(&b->s, floor4, 4, &half, NULL), 0);
    assert_int_equal(rad_add_polygon(&b->s, lamp, 4, NULL, &em), 1);
    CHECK_INT_EQ(b->s.pools.surfaces[0].n_elements, 16, "floor elements");
    for (e = 0; e < 16; e++) {
        rad_rgb_t r = pattern(e);
        assert_int_equal(rad_set_element_reflectance(&b->s, e, &r), RAD_OK);
    }
    assert_int_equal(rad_shoot(&a->s, 1, 0), 1);
    assert_int_equal(rad_shoot(&b->s, 1, 0), 1);
    for (e = 0; e < 16; e++) {
        rad_rgb_t ra, rb, r = pattern(e);
        assert_int_equal(rad_element_radiosity(&a->s, e, RAD_SHADE_SCALED, &ra), RAD_OK);
        assert_int_equal(rad_element_radiosity(&b->s, e, RAD_SHADE_SCALED, &rb), RAD_OK);
        for (k = 0; k < 3; k++) {
            double want = ch(&ra, k) * ch(&r, k) / 0.5, d = fabs(ch(&rb, k) - want) * 65536;
            if (d > worst) worst = d;
            if (fabs(ch(&rb, k) - ch(&ra, k)) > spread) spread = fabs(ch(&rb, k) - ch(&ra, k));
        }
    }
    print_message(
        "one shot: element radiosity against the surface's times rho_j / 0.5: worst %.2f LSB "
        "(bound 2); largest change %.3f\n",
        worst, spread);
    CHECK_LE(worst, 2.0,
             "one shot: element radiosity, in LSB, against the shot at 0.5 times rho_j / 0.5");
    CHECK_GE(spread, 1.0,
             "one shot: the elements' own reflectance changed their radiosity (core scale)");
    free(a);
    free(b);
}

/* A closed box, emission 1, surfaces of reflectance 0.2 but every element 0.5 of its own:
 * B = 1 / (1 - 0.5) = 2 everywhere, only if every step reflects with the element's
 * (receiving, the patch's reflectance for overshooting, the ambient term and its part).
 * Bounds: test_solver's closed box (the mean within 0.5%: energy moved, never made; an
 * element within 5%: the hemi-cube at the patch's centre stands for the whole patch). */
static void test_closed_box_uniform(void **st)
{
    const rad_rgb_t r02 = C(0.2, 0.2, 0.2), r05 = C(0.5, 0.5, 0.5), one = C(1, 1, 1);
    world_t *w = world(32, 16);
    double mean = 0, area = 0, worst = 0;
    uint32_t e;
    int k;
    (void)st;
    box(w, &r02, &one);
    own_reflectances(w, &r05);
    assert_true(rad_shoot(&w->s, 100000, RAD_REAL(1e-4)) > 0);
    for (e = 0; e < w->s.n_elements; e++) {
        rad_rgb_t b;
        double a = RAD_TO_DOUBLE(w->s.pools.elements[e].area);
        assert_int_equal(rad_element_radiosity(&w->s, e, RAD_SHADE_AMBIENT, &b), RAD_OK);
        for (k = 0; k < 3; k++) {
            double dev = fabs(ch(&b, k) / 2 - 1);
            if (dev > worst) worst = dev;
            mean += a * ch(&b, k) / 3;
        }
        area += a;
    }
    print_message(
        "closed box, elements 0.5 on surfaces 0.2: mean %.5f (want 2, bound 0.5%%), worst element "
        "%.2f%% (bound 5%%)\n",
        mean / area, 100 * worst);
    CHECK_LE(fabs(mean / area / 2 - 1), 0.005,
             "closed box: the area-weighted mean against 1 / (1 - 0.5)");
    CHECK_LE(worst, 0.05, "closed box: the worst element against 1 / (1 - 0.5)");
    free(w);
}

/* A closed box, emission 1, elements of four different reflectances (pattern): no closed
 * form, but energy balance holds for any reflectances: every emitted unit is absorbed
 * somewhere, sum_j A_j E = sum_j A_j (1 - rho_j) H_j, with H_j = (B_j - E) / rho_j the
 * light arriving at element j. Solved to an unshot fraction of 1e-4, with the ambient
 * term standing in for the rest: bound 0.5%, as the uniform box's mean. Against the
 * same box at the surfaces' mean reflectance the solution does differ. */
static void test_closed_box_balance(void **st)
{
    const rad_rgb_t grey = C(0.4, 0.4, 0.4), one = C(1, 1, 1);
    world_t *w = world(32, 16);
    double emitted = 0, absorbed[3] = {0, 0, 0}, worst = 0, lo = 1e9, hi = 0;
    uint32_t e;
    int k;
    (void)st;
    box(w, &grey, &one);
    own_reflectances(w, NULL);
    assert_true(rad_shoot(&w->s, 100000, RAD_REAL(1e-4)) > 0);
    for (e = 0; e < w->s.n_elements; e++) {
        rad_rgb_t b, r = pattern(e);
        double a = RAD_TO_DOUBLE(w->s.pools.elements[e].area);
        assert_int_equal(rad_element_radiosity(&w->s, e, RAD_SHADE_AMBIENT, &b), RAD_OK);
        emitted += a;
        for (k = 0; k < 3; k++) {
            double h = (ch(&b, k) - 1) / ch(&r, k);
            absorbed[k] += a * (1 - ch(&r, k)) * h;
        }
        if (ch(&b, 0) < lo) lo = ch(&b, 0);
        if (ch(&b, 0) > hi) hi = ch(&b, 0);
    }
    for (k = 0; k < 3; k++)
        if (fabs(absorbed[k] / emitted - 1) > worst) worst = fabs(absorbed[k] / emitted - 1);
    print_message(
        "closed box, four reflectances: absorbed / emitted within %.3f%% (bound 0.5%%); red "
        "radiosity %.3f..%.3f\n",
        100 * worst, lo, hi);
    CHECK_LE(worst, 0.005,
             "closed box of differing elements: absorbed over emitted power, minus 1");
    CHECK_GE(hi - lo, 0.5,
             "closed box of differing elements: red radiosity spread (0.05 to 0.9 reflect)");
    free(w);
}

/* The ambient part shown (RAD_SHADE_AMBIENT) is the element's reflectance times the
 * ambient term: within 2 LSB (the part rounds once, the sum once, the scale back once). */
static void test_ambient_part(void **st)
{
    const rad_rgb_t grey = C(0.4, 0.4, 0.4), one = C(1, 1, 1);
    world_t *w = world(32, 16);
    rad_rgb_t amb;
    double worst = 0;
    uint32_t e;
    int k;
    (void)st;
    box(w, &grey, &one);
    own_reflectances(w, NULL);
    assert_int_equal(rad_shoot(&w->s, 3, 0), 3);
    assert_int_equal(rad_ambient(&w->s, &amb), RAD_OK);
    CHECK_GT(ch(&amb, 0), 0.1, "ambient term after 3 shots of 96 lit patches");
    for (e = 0; e < w->s.n_elements; e++) {
        rad_rgb_t b0, b1, r = pattern(e);
        assert_int_equal(rad_element_radiosity(&w->s, e, 0, &b0), RAD_OK);
        assert_int_equal(rad_element_radiosity(&w->s, e, RAD_SHADE_AMBIENT, &b1), RAD_OK);
        for (k = 0; k < 3; k++) {
            double d = fabs(ch(&b1, k) - ch(&b0, k) - ch(&r, k) * ch(&amb, k)) * 65536;
            if (d > worst) worst = d;
        }
    }
    print_message("ambient part: within %.2f LSB of rho_e times the ambient term (bound 2)\n",
                  worst);
    CHECK_LE(worst, 2.0, "shown ambient part against the element's rho times rad_ambient, in LSB");
    free(w);
}

/* Gauss-Seidel reads the patch's reflectance from its elements: the closed box of
 * test_closed_box_uniform solved from stored rows gives 2 (bounds as there; no
 * ambient term: Gauss-Seidel converges). */
static void test_gauss_seidel(void **st)
{
    const rad_rgb_t r02 = C(0.2, 0.2, 0.2), r05 = C(0.5, 0.5, 0.5), one = C(1, 1, 1);
    world_t *w = world(32, 16);
    static uint32_t start[NP + 1];
    static rad_index_t ids[NP * 96];
    static uint16_t ffs[NP * 96];
    rad_rows_t rows = {start, ids, ffs, NP, NP * 96, 0};
    rad_ff_t *m;
    double mean = 0, area = 0;
    uint32_t e;
    (void)st;
    box(w, &r02, &one);
    own_reflectances(w, &r05);
    CHECK_INT_EQ(rad_rows_compute(&w->s, &rows, NP), (int)w->s.n_patches, "rows stored");
    m = malloc(RAD_GS_ENTRIES(w->s.n_patches) * sizeof *m);
    assert_non_null(m);
    assert_true(rad_rows_gauss_seidel(&w->s, &rows, m, RAD_GS_ENTRIES(w->s.n_patches), 200,
                                      RAD_REAL(1e-4)) > 0);
    for (e = 0; e < w->s.n_elements; e++) {
        rad_rgb_t b;
        double a = RAD_TO_DOUBLE(w->s.pools.elements[e].area);
        assert_int_equal(rad_element_radiosity(&w->s, e, 0, &b), RAD_OK);
        mean += a * ch(&b, 1);
        area += a;
    }
    print_message("Gauss-Seidel, elements 0.5 on surfaces 0.2: mean %.5f (want 2, bound 0.5%%)\n",
                  mean / area);
    CHECK_LE(fabs(mean / area / 2 - 1), 0.005,
             "Gauss-Seidel closed box: the mean against 1 / (1 - 0.5)");
    free(m);
    free(w);
}

/* A room (lamp, coloured walls) solved with overshooting, once without the array and once
 * with it but no element set apart (and one surface changed through rad_set_surface, which
 * sets its elements): the same shots, radiosities and ambient term, bit for bit. */
static void test_uniform_same_bits(void **st)
{
    const rad_vec3_t lamp[4] = {V(-8, 31, -8), V(8, 31, -8), V(8, 31, 8), V(-8, 31, 8)};
    const rad_rgb_t r = C(0.6, 0.3, 0.2), g = C(0.2, 0.7, 0.3), em = C(50, 40, 30);
    world_t *w[2];
    rad_rgb_t amb[2];
    int i, shots[2];
    uint32_t e;
    (void)st;
    for (i = 0; i < 2; i++) {
        w[i] = world(16, 8);
        if (i) assert_int_equal(rad_use_element_reflectance(&w[i]->s, w[i]->rho), RAD_OK);
        box(w[i], &r, NULL);
        assert_int_equal(rad_add_polygon(&w[i]->s, lamp, 4, NULL, &em), 6);
        assert_int_equal(rad_set_surface(&w[i]->s, 2, &g, NULL), RAD_OK);
        shots[i] = rad_shoot(&w[i]->s, 400, RAD_REAL(1e-3));
        assert_int_equal(rad_ambient(&w[i]->s, &amb[i]), RAD_OK);
    }
    CHECK_INT_EQ(shots[1], shots[0], "shots with a uniform element array against none");
    assert_true(shots[0] > 10);
    assert_int_equal(w[1]->rho[w[1]->s.pools.surfaces[2].first_element].g, g.g);
    for (e = 0; e < w[0]->s.n_elements; e++)
        assert_memory_equal(&w[0]->el[e].radiosity, &w[1]->el[e].radiosity, sizeof(rad_rgb_t));
    assert_memory_equal(&amb[0], &amb[1], sizeof amb[0]);
    { /* a gather with the ambient term: the array's uncached path, the same bits */
        static unsigned char gw[RAD_GATHER_BYTES(32)];
        const rad_vec3_t at = V(3, -20, 5), up = V(0, 1, 0);
        rad_rgb_t ga[2];
        for (i = 0; i < 2; i++) {
            rad_gather_t gt;
            assert_int_equal(rad_gather_init(&gt, 32, 0, gw, sizeof gw), RAD_OK);
            assert_int_equal(
                rad_gather(&w[i]->s, &gt, &at, &up, RAD_INDEX_NONE, RAD_SHADE_AMBIENT, &ga[i]),
                RAD_OK);
        }
        assert_true(ga[0].r > 0);
        assert_memory_equal(&ga[0], &ga[1], sizeof ga[0]);
    }
    print_message(
        "uniform element array: %d shots, %u elements, the same bits as without (and a gather)\n",
        shots[0], (unsigned)w[0]->s.n_elements);
    free(w[0]);
    free(w[1]);
}

/* The ambient term mid-solve, after a wall's reflectance changes (rad_set_surface, then
 * through the element array): the solver keeps its sums of area and of reflectance times
 * area between shots, so a change must reach them. At one unshot state the term is
 * U_c / (A - R_c), A the total area and R_c the sum of reflectance times area, so the
 * change scales it by (A - R_c) / (A - R'_c), from the geometry (six walls of 64 x 64, a
 * black lamp of 16 x 16); a stale sum leaves it unchanged. Bound 0.5%: the term is three
 * roundings of 2^-16 relative (R / A, 1 / (1 - R / A), the product) away from exact, on a
 * change of 2-14% per channel. */
static void test_ambient_follows_reflectance(void **st)
{
    const rad_vec3_t lamp[4] = {V(-8, 31, -8), V(8, 31, -8), V(8, 31, 8), V(-8, 31, 8)};
    const double rr[3] = {0.6, 0.3, 0.2}, gg[3] = {0.2, 0.7, 0.3}, wall = 4096,
                 total = 6 * wall + 256;
    const rad_rgb_t r = C(rr[0], rr[1], rr[2]), g = C(gg[0], gg[1], gg[2]), em = C(50, 40, 30);
    int arr, k;
    (void)st;
    for (arr = 0; arr < 2; arr++) {
        world_t *w = world(16, 8);
        rad_rgb_t before, after;
        double worst = 0;
        uint32_t e;
        const rad_surface_t *sf;
        if (arr) assert_int_equal(rad_use_element_reflectance(&w->s, w->rho), RAD_OK);
        box(w, &r, NULL);
        assert_int_equal(rad_add_polygon(&w->s, lamp, 4, NULL, &em), 6);
        assert_int_equal(rad_shoot(&w->s, 20, 0), 20);
        assert_int_equal(rad_ambient(&w->s, &before), RAD_OK);
        sf = &w->s.pools.surfaces[2];
        if (arr) {
            for (e = sf->first_element; e < sf->first_element + sf->n_elements; e++)
                assert_int_equal(rad_set_element_reflectance(&w->s, e, &g), RAD_OK);
        } else {
            assert_int_equal(rad_set_surface(&w->s, 2, &g, NULL), RAD_OK);
        }
        assert_int_equal(rad_ambient(&w->s, &after), RAD_OK);
        for (k = 0; k < 3; k++) {
            double want = (total - 6 * wall * rr[k]) / (total - 5 * wall * rr[k] - wall * gg[k]);
            double got = ch(&after, k) / ch(&before, k);
            assert_true(ch(&before, k) > 0);
            print_message("%s: channel %d ambient scaled by %.5f (want %.5f)\n",
                          arr ? "rad_set_element_reflectance" : "rad_set_surface", k, got, want);
            worst = fmax(worst, fabs(got / want - 1));
        }
        CHECK_LE(worst, 0.005,
                 "ambient term after a reflectance change mid-solve against (A - R) / (A - R')");
        free(w);
    }
}

static void test_errors(void **st)
{
    const rad_rgb_t ok = C(0.5, 0.5, 0.5), em = C(1, 1, 1);
    rad_rgb_t bad = C(0.5, 1.0, 0.5), neg = C(-0.01, 0.5, 0.5);
    world_t *w = world(32, 16);
    (void)st;
    box(w, &ok, &em);
    CHECK_INT_EQ(rad_set_element_reflectance(&w->s, 0, &ok), RAD_ERR_STATE, "set without an array");
    CHECK_INT_EQ(rad_use_element_reflectance(NULL, w->rho), RAD_ERR_ARG, "use on NULL");
    CHECK_INT_EQ(rad_use_element_reflectance(&w->s, NULL), RAD_ERR_ARG, "use of NULL");
    CHECK_INT_EQ(rad_use_element_reflectance(&w->s, (rad_rgb_t *)(void *)((char *)w->rho + 1)),
                 RAD_ERR_ALIGN, "use of a misaligned array");
    CHECK_INT_EQ(rad_use_element_reflectance(&w->s, w->rho), RAD_OK, "use after adding");
    assert_int_equal(w->rho[w->s.n_elements - 1].r,
                     ok.r); /* elements added before: their surface's */
    CHECK_INT_EQ(rad_use_element_reflectance(&w->s, w->rho), RAD_ERR_STATE, "use twice");
    CHECK_INT_EQ(rad_set_element_reflectance(&w->s, w->s.n_elements, &ok), RAD_ERR_ARG,
                 "element past the last");
    CHECK_INT_EQ(rad_set_element_reflectance(&w->s, 0, NULL), RAD_ERR_ARG, "NULL reflectance");
    CHECK_INT_EQ(rad_set_element_reflectance(NULL, 0, &ok), RAD_ERR_ARG, "NULL scene");
    CHECK_INT_EQ(rad_set_element_reflectance(&w->s, 0, &bad), RAD_ERR_RANGE, "reflectance 1");
    CHECK_INT_EQ(rad_set_element_reflectance(&w->s, 0, &neg), RAD_ERR_RANGE,
                 "negative reflectance");
    assert_int_equal(w->rho[0].g, ok.g); /* refused: unchanged */
    assert_true(rad_shoot(&w->s, 1, 0) == 1);
    CHECK_INT_EQ(rad_set_element_reflectance(&w->s, 0, &ok), RAD_OK,
                 "set while solving (for the next restart)");
    {
        world_t *v = world(32, 16);
        box(v, &ok, &em);
        assert_true(rad_shoot(&v->s, 1, 0) == 1);
        CHECK_INT_EQ(rad_use_element_reflectance(&v->s, v->rho), RAD_ERR_STATE,
                     "use after the geometry froze");
        free(v);
    }
    free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_shot),
        cmocka_unit_test(test_closed_box_uniform),
        cmocka_unit_test(test_closed_box_balance),
        cmocka_unit_test(test_ambient_part),
        cmocka_unit_test(test_gauss_seidel),
        cmocka_unit_test(test_uniform_same_bits),
        cmocka_unit_test(test_ambient_follows_reflectance),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
