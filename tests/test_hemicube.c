/* SPDX-License-Identifier: MIT */
/* The hemi-cube: its delta form factor table, form factors against analytic values
 * (Lambert's contour formula, catalog values), closed-scene row sums, banding, and
 * watertight occlusion. Both builds (fixed sc_*, float scf_*) are checked. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "check.h"
#include "host/parallel.h"
#include "rad/rad.h"
#include "reference/reference.h"
#include "scenes.h"

/* ---- the table ----------------------------------------------------------------- */

static void test_table_sums_to_one(void **st)
{
    static const uint16_t res[] = {8, 16, 32, 64, 100, 256, 1024};
    size_t i;
    (void)st;
    for (i = 0; i < sizeof res / sizeof res[0]; i++) {
        static rad_surface_t sf[1];
        static rad_patch_t pt[1];
        static rad_element_t el[1];
        static rad_vec3_t vx[1];
        size_t bytes = RAD_WORK_BYTES(res[i], RAD_PIXELS_ALL(res[i]), 1);
        void *work = malloc(bytes);
        rad_pools_t p = {.surfaces = sf,
                         .max_surfaces = 1,
                         .patches = pt,
                         .max_patches = 1,
                         .elements = el,
                         .max_elements = 1,
                         .vertices = vx,
                         .max_vertices = 1,
                         .work = work,
                         .work_bytes = bytes};
        rad_config_t c = {.res = res[i]};
        rad_scene_t s;
        uint64_t sum = 0;
        uint32_t q = res[i] / 2u, k;
        double maxrel = 0;
        assert_non_null(work);
        assert_int_equal(rad_init(&s, &p, &c), RAD_OK);
        assert_int_equal(s.band_rows, 0);
        for (k = 0; k < q * q; k++)
            sum += 4u * (uint64_t)s.dff_top[k] + 8u * (uint64_t)s.dff_side[k];
        /* Exactly one in Q2.30. */
        assert_int_equal(sum, (uint64_t)1 << 30);
        /* Each entry follows the paper's formula, normalised over the discrete cube. */
        {
            double tot = 0, x, y, z;
            uint32_t a, b;
            for (b = 0; b < q; b++)
                for (a = 0; a < q; a++) {
                    x = (2.0 * a + 1) / res[i];
                    y = (2.0 * b + 1) / res[i];
                    z = (res[i] - 2.0 * b - 1) / res[i];
                    tot += 4 / pow(x * x + y * y + 1, 2) + 8 * z / pow(x * x + z * z + 1, 2);
                }
            for (b = 0; b < q; b++)
                for (a = 0; a < q; a++) {
                    double t, sd;
                    x = (2.0 * a + 1) / res[i];
                    y = (2.0 * b + 1) / res[i];
                    z = (res[i] - 2.0 * b - 1) / res[i];
                    t = ldexp(1, 30) / pow(x * x + y * y + 1, 2) / tot;
                    sd = ldexp(1, 30) * z / pow(x * x + z * z + 1, 2) / tot;
                    /* Within 2 units: the floor, one unit of deficit, and the 32-bit
                     * pre-scaling of the raw values. */
                    CHECK_NEAR(s.dff_top[b * q + a], t, 2.0,
                               "res %u: top face entry %u, %u (Q2.30)", res[i], (unsigned)a,
                               (unsigned)b);
                    CHECK_NEAR(s.dff_side[b * q + a], sd, 2.0,
                               "res %u: side face entry %u, %u (Q2.30)", res[i], (unsigned)a,
                               (unsigned)b);
                    if (fabs(s.dff_top[b * q + a] - t) / t > maxrel)
                        maxrel = fabs(s.dff_top[b * q + a] - t) / t;
                }
        }
        print_message("res %4u: table sums to 2^30 exactly; max relative entry error %.2e\n",
                      res[i], maxrel);
        free(work);
    }
}

/* ---- analytic point-to-polygon form factors ------------------------------------- */

static void test_point_to_polygon(void **st)
{
    int k, twin;
    (void)st;
    for (twin = 0; twin < 2; twin++)
        for (k = 0; k < REF_RECEIVERS; k++) {
            double want, f64 = ref_hemicube_ff(k, 64, twin, &want),
                         f256 = ref_hemicube_ff(k, 256, twin, &want);
            print_message(
                "%s receiver %d: analytic %.5f  res64 %.5f (%+.3f%%)  res256 %.5f (%+.3f%%)\n",
                twin ? "float" : "fixed", k, want, f64, 100 * (f64 / want - 1), f256,
                100 * (f256 / want - 1));
            /* 2% at 64, 0.5% at 256: pixel aliasing along the edges shrinks as 1/res. */
            if (getenv("RAD_TEST_NOASSERT")) continue;
            CHECK_LE(fabs(f64 / want - 1), 0.02,
                     "%s receiver %d at res 64: relative error against Lambert's contour formula",
                     twin ? "float" : "fixed", k);
            CHECK_LE(fabs(f256 / want - 1), 0.005,
                     "%s receiver %d at res 256: relative error against Lambert's contour formula",
                     twin ? "float" : "fixed", k);
        }
}

/* ---- area to area: catalog values ------------------------------------------------ */

/* Source polygon 0 subdivided into 16 x 16 patches, each shooting; the area form
 * factor is the area-weighted mean of each patch's sum over the receiver's elements. */
static double area_ff(const sc_poly *p, int res)
{
    sc_opts o = {.max_patch = 1.0 / 16, .max_element = 1.0 / 16, .res = res};
    char err[256];
    sc_solver *s = sc_create(p, 2, &o, NULL, NULL, err, sizeof err);
    sc_stats stt;
    double *ff, tot = 0, area = 0;
    int pt, e;
    assert_non_null(s);
    sc_get_stats(s, &stt);
    ff = calloc((size_t)stt.elements, sizeof *ff);
    /* Polygon 0's patches come first, each one element of equal area. */
    for (pt = 0; pt < stt.patches && sc_element_tag(s, pt) == 0; pt++) {
        double f = 0, a = sc_element_area(s, pt);
        assert_int_equal(sc_form_factors(s, pt, ff), 0);
        for (e = 0; e < stt.elements; e++)
            if (sc_element_tag(s, e) == 1) f += ff[e];
        tot += f * a;
        area += a;
    }
    assert_int_equal(pt, 256);
    free(ff);
    sc_destroy(s);
    return tot / area;
}

static void test_catalog(void **st)
{
    sc_poly p[2];
    double f;
    (void)st;
    memset(p, 0, sizeof p);
    /* Directly opposed unit squares at distance 1: 0.19982. */
    p[0] = quad(0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0);
    p[1] = quad(0, 0, 1, 0, 1, 1, 1, 1, 1, 1, 0, 1);
    p[1].tag = 1;
    f = area_ff(p, 128);
    print_message("opposed squares: %.5f (catalog 0.19982, %+.2f%%)\n", f, 100 * (f / 0.19982 - 1));
    CHECK_LE(fabs(f / 0.19982 - 1), 0.02,
             "opposed unit squares: relative error against the catalog");
    /* Perpendicular unit squares sharing an edge: 0.20004. */
    p[0] = quad(0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0);
    p[1] = quad(0, 0, 0, 0, 0, 1, 1, 0, 1, 1, 0, 0);
    p[1].tag = 1;
    f = area_ff(p, 128);
    print_message("perpendicular squares: %.5f (catalog 0.20004, %+.2f%%)\n", f,
                  100 * (f / 0.20004 - 1));
    CHECK_LE(fabs(f / 0.20004 - 1), 0.02,
             "perpendicular unit squares: relative error against the catalog");
}

/* ---- closed scenes, banding, occlusion -------------------------------------------- */

static void test_closed_box_rows(void **st)
{
    sc_poly p[12];
    sc_opts o = {.max_patch = 0.5, .max_element = 0.25, .res = 64};
    char err[256];
    int n = box(p, -1, -1, -1, 1, 1, 1, 1), pt, e, twin;
    (void)st;
    /* A block floating inside makes the rows uneven without hiding any patch. */
    n += box(p + n, -0.3, -0.8, -0.3, 0.3, 0.2, 0.3, 0);
    for (twin = 0; twin < 2; twin++) {
        sc_stats stt;
        double *ff;
        void *s = twin ? (void *)scf_create(p, n, &o, NULL, NULL, err, sizeof err)
                       : (void *)sc_create(p, n, &o, NULL, NULL, err, sizeof err);
        assert_non_null(s);
        if (twin)
            scf_get_stats(s, &stt);
        else
            sc_get_stats(s, &stt);
        ff = calloc((size_t)stt.elements, sizeof *ff);
        for (pt = 0; pt < stt.patches; pt += 7) {
            double sum = 0;
            if (twin)
                scf_form_factors(s, pt, ff);
            else
                sc_form_factors(s, pt, ff);
            for (e = 0; e < stt.elements; e++) sum += ff[e];
            /* Every pixel sees some element, so the row is the table's sum: 1 within
             * float rounding (exactly 1 in fixed point). */
            CHECK_NEAR(sum, 1, 1e-4, "%s: patch %d's row sum in a closed box",
                       twin ? "float" : "fixed", pt);
            if (!twin) CHECK_EQ(sum, 1.0, "fixed: patch %d's row sum in a closed box", pt);
        }
        free(ff);
        if (twin)
            scf_destroy(s);
        else
            sc_destroy(s);
    }
}

static void test_bands_bit_exact(void **st)
{
    sc_poly p[12];
    char err[256];
    int n = box(p, -1, -1, -1, 1, 1, 1, 1), i, b;
    static const int bands[] = {0, 1, 3, 16, 31, 48, 95}; /* past res 32: bands span faces */
    uint64_t ref = 0;
    (void)st;
    n += box(p + n, -0.3, -1, -0.3, 0.3, 0.2, 0.3, 0);
    for (i = 0; i < n; i++) set_mat(&p[i], 0.6, 0.5, 0.4, 0, 0, 0);
    set_mat(&p[1], 0.5, 0.5, 0.5, 1, 1, 1);
    for (b = 0; b < (int)(sizeof bands / sizeof bands[0]); b++) {
        sc_opts o = {.max_patch = 0.5, .max_element = 0.25, .res = 32, .band_rows = bands[b]};
        sc_solver *s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
        assert_non_null(s);
        CHECK_INT_EQ(sc_solve(s, 100, 0, NULL, NULL), 100, "shots with %d band rows", bands[b]);
        /* Rendering one band of rows at a time changes nothing: same bits. */
        if (b == 0)
            ref = sc_checksum(s);
        else
            assert_int_equal(sc_checksum(s), ref);
        sc_destroy(s);
    }
}

static void test_blocker_no_leak(void **st)
{
    sc_poly p[8];
    char err[256];
    int n = 0, e, twin;
    (void)st;
    memset(p, 0, sizeof p);
    /* Emitter at z = 0 facing +z; a black blocker at z = 1 facing it, made of four
     * quads meeting at shared edges; the receiver at z = 2 behind it. Every line from
     * emitter to receiver crosses the blocker, so no light may arrive. */
    p[n] = quad(-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0);
    set_mat(&p[n], 0.5, 0.5, 0.5, 5, 5, 5);
    p[n++].tag = 0;
    p[n] = quad(-3, -3, 1, -3, 0, 1, 0, 0, 1, 0, -3, 1);
    p[n++].tag = 1;
    p[n] = quad(0, -3, 1, 0, 0, 1, 3, 0, 1, 3, -3, 1);
    p[n++].tag = 1;
    p[n] = quad(-3, 0, 1, -3, 3, 1, 0, 3, 1, 0, 0, 1);
    p[n++].tag = 1;
    p[n] = quad(0, 0, 1, 0, 3, 1, 3, 3, 1, 3, 0, 1);
    p[n++].tag = 1;
    p[n] = quad(-1, -1, 2, -1, 1, 2, 1, 1, 2, 1, -1, 2);
    set_mat(&p[n], 0.8, 0.8, 0.8, 0, 0, 0);
    p[n++].tag = 2;
    for (twin = 0; twin < 2; twin++) {
        sc_opts o = {.max_patch = 0.25, .max_element = 0.125, .res = 128};
        sc_stats stt;
        double rgb[3], lit = 0;
        void *s = twin ? (void *)scf_create(p, n, &o, NULL, NULL, err, sizeof err)
                       : (void *)sc_create(p, n, &o, NULL, NULL, err, sizeof err);
        assert_non_null(s);
        if (twin) {
            scf_solve(s, 1000, 0, NULL, NULL);
            scf_get_stats(s, &stt);
        } else {
            sc_solve(s, 1000, 0, NULL, NULL);
            sc_get_stats(s, &stt);
        }
        for (e = 0; e < stt.elements; e++) {
            int tag = twin ? scf_element_tag(s, e) : sc_element_tag(s, e);
            if (twin)
                scf_element_rgb(s, e, 0, rgb);
            else
                sc_element_rgb(s, e, 0, rgb);
            if (tag == 2) {
                CHECK_EQ(rgb[0], 0, "%s: receiver element %d's red behind the blocker",
                         twin ? "float" : "fixed", e);
                CHECK_EQ(rgb[1], 0, "%s: receiver element %d's green behind the blocker",
                         twin ? "float" : "fixed", e);
                CHECK_EQ(rgb[2], 0, "%s: receiver element %d's blue behind the blocker",
                         twin ? "float" : "fixed", e);
            }
            if (tag == 1) lit += rgb[0];
        }
        /* The blocker is black: it reflects nothing although it is hit. */
        CHECK_EQ(lit, 0, "%s: red reflected by the black blocker", twin ? "float" : "fixed");
        CHECK_INT_GT(stt.raster_pixels, 0, "%s: hemi-cube pixels covered",
                     twin ? "float" : "fixed");
        if (twin)
            scf_destroy(s);
        else
            sc_destroy(s);
    }
}

/* ---- element by element: the surface lattice ------------------------------------- */

/* Every element's form factor from a point at the origin (normal +z) against Lambert's
 * formula for the element's own polygon: a quad that is not a parallelogram (its
 * lattice lines are not parallel), a triangle with up and down patches of 3 x 3
 * elements (its second half of patches is numbered reflected), and a wall standing
 * beside the shooter. A wrong lattice line or element number puts an element's pixels
 * in a neighbour, whose form factor differs by 10% to 40% here. */
static void test_element_lattice(void **st)
{
    enum { NE = 512, RES = 512 };
    static rad_surface_t sf[2];
    static rad_patch_t pt[NE];
    static rad_element_t el[NE];
    static rad_vec3_t vx[2 * NE];
    static const double shape[3][4][3] = {
        {{-0.6, -0.5, 0.45}, {-0.5, 0.6, 0.5}, {0.9, 0.4, 0.8}, {0.7, -0.5, 0.75}},
        {{-0.7, -0.6, 0.5}, {0.2, 0.8, 0.7}, {0.8, -0.4, 0.6}, {0, 0, 0}},
        {{0.3, -0.6, 0.05}, {0.3, -0.6, 0.9}, {0.3, 0.6, 0.9}, {0.3, 0.6, 0.05}}};
    size_t bytes = RAD_WORK_BYTES(RES, RAD_PIXELS_ALL(RES), 2 * NE);
    void *work = malloc(bytes);
    rad_ff_t *ff = malloc(NE * sizeof *ff);
    int k;
    (void)st;
    assert_non_null(work);
    assert_non_null(ff);
    for (k = 0; k < 3; k++) {
        rad_pools_t p = {.surfaces = sf,
                         .max_surfaces = 2,
                         .patches = pt,
                         .max_patches = NE,
                         .elements = el,
                         .max_elements = NE,
                         .vertices = vx,
                         .max_vertices = 2 * NE};
        rad_config_t cfg = {.res = RES};
        rad_scene_t s;
        rad_vec3_t v[4], shooter[4];
        rad_rgb_t one = {RAD_REAL(1), RAD_REAL(1), RAD_REAL(1)};
        double worst = 0, s2 = 0, sum = 0, want = 0;
        unsigned i, n = k == 1 ? 3 : 4;
        uint32_t e;
        p.work = work;
        p.work_bytes = bytes;
        cfg.max_element = RAD_REAL(0.125);
        cfg.max_patch = RAD_REAL(0.3);
        assert_int_equal(rad_init(&s, &p, &cfg), RAD_OK);
        for (i = 0; i < 4; i++) {
            shooter[i].x = RAD_REAL(i == 1 || i == 2 ? 0.01 : -0.01);
            shooter[i].y = RAD_REAL(i >= 2 ? 0.01 : -0.01);
            shooter[i].z = 0;
            v[i].x = RAD_REAL(shape[k][i][0]);
            v[i].y = RAD_REAL(shape[k][i][1]);
            v[i].z = RAD_REAL(shape[k][i][2]);
        }
        assert_int_equal(rad_add_polygon(&s, shooter, 4, NULL, &one), 0);
        assert_int_equal(rad_add_polygon(&s, v, n, NULL, NULL), 1);
        CHECK_INT_GT(sf[1].pu, 1, "receiver %d: patches along its first side", k);
        CHECK_INT_EQ(sf[1].ku, 3, "receiver %d: elements per patch along its first side", k);
        assert_int_equal(rad_form_factors(&s, 0, ff), (int)s.n_elements);
        for (e = sf[1].first_element; e < s.n_elements; e++) {
            sc_poly q;
            double f = RAD_FF_TO_DOUBLE(ff[e]), w, r;
            memset(&q, 0, sizeof q);
            q.n = (int)(el[e].v[3] == RAD_INDEX_NONE ? 3u : 4u);
            for (i = 0; i < (unsigned)q.n; i++) {
                q.v[i][0] = RAD_TO_DOUBLE(vx[el[e].v[i]].x);
                q.v[i][1] = RAD_TO_DOUBLE(vx[el[e].v[i]].y);
                q.v[i][2] = RAD_TO_DOUBLE(vx[el[e].v[i]].z);
            }
            w = ref_point_ff(&q);
            r = f / w - 1;
            if (fabs(r) > worst) worst = fabs(r);
            s2 += r * r;
            sum += f;
            want += w;
        }
        print_message("receiver %d: %u elements, sum %.5f (analytic %.5f), per element max %.2f%% "
                      "rms %.2f%%\n",
                      k, sf[1].n_elements, sum, want, 100 * worst,
                      100 * sqrt(s2 / sf[1].n_elements));
        /* The whole within 0.1% (as test_point_to_polygon at 256). Each element within
         * 6%, rms 2%: at 512 an element is 20 to 60 pixels across, and an edge
         * parallel to the pixel grid (the wall's vertical lines on the side faces,
         * which no turn of the cube about its normal tilts) is off by up to half a
         * pixel all along: up to 1/20 for two such edges. */
        CHECK_LE(fabs(sum / want - 1), 0.001,
                 "receiver %d: the whole's relative error against Lambert's contour formula", k);
        CHECK_LE(worst, 0.06,
                 "receiver %d: the worst element's relative error against Lambert's formula", k);
        CHECK_LE(sqrt(s2 / sf[1].n_elements), 0.02,
                 "receiver %d: rms relative error of the elements against Lambert's formula", k);
    }
    free(ff);
    free(work);
}

/* ---- coarse shots (rad_config_t.coarse) ----------------------------------------- */

/* A closed room 2 x 2 x 2 of reflectance RHO whose ceiling (face 1) emits 1: 6 quads. */
static int lit_room(sc_poly *p, double rho, double ceiling_rho)
{
    int n = box(p, -1, -1, -1, 1, 1, 1, 1), i;
    for (i = 0; i < n; i++) set_mat(&p[i], rho, rho, rho, 0, 0, 0);
    set_mat(&p[1], ceiling_rho, ceiling_rho, ceiling_rho, 1, 1, 1);
    return n;
}

/* The level the rule in rad.h gives at unshot fraction FRAC, worked out in double:
 * one per power of 8 that COARSE / 8^k stays at or above FRAC, then cut to the deepest
 * the resolution allows (res >> level >= FLOOR, and res / 2 a multiple of 2^level). */
static unsigned expected_level(double frac, double coarse, unsigned res, unsigned floor)
{
    unsigned level = 0, deepest = 0;
    while (coarse > 0 && frac <= coarse && level < 8) {
        level++;
        coarse /= 8;
    }
    while ((res >> (deepest + 1)) >= floor && (res / 2) % (2u << deepest) == 0) deepest++;
    return level < deepest ? level : deepest;
}

/* The first non-emitting shooter's cube: its resolution is the rule's, and its tables
 * are the block sums of the res table, entry by entry, summing to exactly 2^30. */
static void test_coarse_tables(void **st)
{
    static const struct {
        unsigned res, floor;
        double coarse;
    } c[] = {{64, 8, 64}, {64, 16, 64}, {64, 0, 64}, {192, 8, 64},
             {192, 8, 1}, {100, 8, 64}, {256, 32, 8}};
    size_t i;
    (void)st;
    for (i = 0; i < sizeof c / sizeof c[0]; i++) {
        sc_poly p[6];
        int n = lit_room(p, 0.5, 0);
        sc_opts o = {.max_patch = 1,
                     .max_element = 0.5,
                     .res = (int)c[i].res,
                     .coarse = c[i].coarse,
                     .coarse_res = (int)c[i].floor};
        char err[256];
        sc_solver *h = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
        rad_scene_t *s;
        uint32_t patch = 0, q = c[i].res / 2u, m, qc, a, b, x, y, shots = 0;
        uint64_t sum = 0;
        unsigned want, floor = c[i].floor ? c[i].floor : c[i].res / 4u;
        assert_non_null(h);
        s = sc_core(h);
        /* The ceiling's patches shoot first (at res: emitters' shots stay there). */
        for (;;) {
            const rad_rgb_t *e;
            assert_int_equal(rad_shot_begin(s, 0, &patch), 1);
            e = &s->pools.surfaces[s->pools.patches[patch].surface].emission;
            if (e->r == 0) break;
            CHECK_INT_EQ(s->cube_res, c[i].res, "res %u: an emitter's cube", c[i].res);
            assert_int_equal(sc_solve(h, 1, 0, NULL, NULL), 1);
            shots++;
        }
        want = expected_level(RAD_TO_DOUBLE(rad_unshot_fraction(s)), c[i].coarse, c[i].res,
                              floor < 8 ? 8 : floor);
        CHECK_INT_EQ(s->cube_res, c[i].res >> want,
                     "res %u, floor %u, coarse %g after %u emitter shots (unshot %.4f)", c[i].res,
                     floor, c[i].coarse, shots, RAD_TO_DOUBLE(rad_unshot_fraction(s)));
        m = 1u << want;
        qc = q / m;
        for (y = 0; y < qc; y++)
            for (x = 0; x < qc; x++) {
                uint64_t t = 0, d = 0;
                for (b = 0; b < m; b++)
                    for (a = 0; a < m; a++) {
                        t += s->dff_top[(y * m + b) * q + x * m + a];
                        d += s->dff_side[(y * m + b) * q + x * m + a];
                    }
                CHECK_INT_EQ(s->cube_top[y * qc + x], t, "res %u level %u: top entry %u, %u",
                             c[i].res, want, x, y);
                CHECK_INT_EQ(s->cube_side[y * qc + x], d, "res %u level %u: side entry %u, %u",
                             c[i].res, want, x, y);
                sum += 4u * (uint64_t)s->cube_top[y * qc + x] +
                       8u * (uint64_t)s->cube_side[y * qc + x];
            }
        CHECK_INT_EQ(sum, (uint64_t)1 << 30, "res %u level %u: the coarse table's sum (Q2.30)",
                     c[i].res, want);
        print_message("res %3u floor %2u coarse %4g: first non-emitter at unshot %.4f renders at "
                      "%u, table sums to 2^30\n",
                      c[i].res, floor, c[i].coarse, RAD_TO_DOUBLE(rad_unshot_fraction(s)),
                      (unsigned)s->cube_res);
        sc_destroy(h);
    }
}

/* Energy in a closed room of reflectance 1/2, shot plainly: a shot of power u hands
 * rho F u to each element it sees, and their patches hold it as unshot power, so the
 * room's unshot total goes from T0 to T0 - u + rho u S, S the row's sum: 1 when the
 * cube's table sums to one (a closed room: every pixel sees an element). A coarse
 * table that lost or doubled a block would move S by that block's share. */
static void test_coarse_closed_room(void **st)
{
    sc_poly p[6];
    int n = lit_room(p, 0.5, 0.5), shot, coarse = 0;
    sc_opts o = {.max_patch = 0.5,
                 .max_element = 0.25,
                 .res = 64,
                 .no_overshoot = 1,
                 .coarse = 1,
                 .coarse_res = 8};
    char err[256];
    sc_solver *h = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
    rad_scene_t *s;
    double worst = 0, least = 1e300;
    (void)st;
    assert_non_null(h);
    s = sc_core(h);
    for (shot = 0; shot < 200; shot++) {
        uint32_t q, best = 0;
        double t0 = 0, t1 = 0, u, sum;
        for (q = 0; q < s->n_patches; q++) {
            t0 += (double)s->pools.patches[q].unshot[0];
            if (s->pools.patches[q].unshot[0] > s->pools.patches[best].unshot[0]) best = q;
        }
        u = (double)s->pools.patches[best].unshot[0];
        assert_int_equal(sc_solve(h, 1, 0, NULL, NULL), 1);
        for (q = 0; q < s->n_patches; q++) t1 += (double)s->pools.patches[q].unshot[0];
        sum = (t1 - t0 + u) / (0.5 * u);
        if (s->cube_res == s->cfg.res) continue;
        coarse++;
        /* Each receiving element rounds its share to the nearest unit of power: at
         * most 1/2 unit each, over the room's 384 elements, against rho u >= 5.4e7
         * units here (the least coarse shot's, measured): below 3.6e-6. */
        CHECK_LE(fabs(sum - 1), 3.6e-6,
                 "shot %d at res %u: the row's sum (unshot %.0f -> %.0f, shooter %.0f)", shot,
                 (unsigned)s->cube_res, t0, t1, u);
        if (fabs(sum - 1) > worst) worst = fabs(sum - 1);
        if (0.5 * u < least) least = 0.5 * u;
    }
    CHECK_INT_GE(coarse, 100,
                 "coarse shots of 200 (every non-emitter's once the unshot fraction is below 1)");
    print_message(
        "closed room: %d coarse shots of 200, row sums within %.2e of 1 (least rho u %.3g units)\n",
        coarse, worst, least);
    sc_destroy(h);
}

/* Coarse shots through the core's parts (sc_solve_parallel) give the serial bits, in
 * both builds: the parts lay their buffers out at the shot's resolution and merge
 * through its tables; and with bands (no room for the tables) every shot stays at
 * res, the same bits as without coarse shots. */
#define COARSE_PARTS(P)                                                                      \
    static void coarse_parts_##P(const sc_poly *p, int n)                                    \
    {                                                                                        \
        sc_opts o = {                                                                        \
            .max_patch = 0.5, .max_element = 0.25, .res = 64, .coarse = 1, .coarse_res = 8}; \
        char err[256];                                                                       \
        P##_solver *ref = P##_create(p, n, &o, NULL, NULL, err, sizeof err);                 \
        sc_stats a, b;                                                                       \
        int threads;                                                                         \
        assert_non_null(ref);                                                                \
        assert_int_equal(P##_solve(ref, 200, 0, NULL, NULL), 200);                           \
        P##_get_stats(ref, &a);                                                              \
        CHECK_INT_GE(a.coarse_shots, 100, #P ": coarse shots of 200");                       \
        for (threads = 2; threads <= 3; threads++) {                                         \
            P##_solver *s = P##_create(p, n, &o, NULL, NULL, err, sizeof err);               \
            assert_non_null(s);                                                              \
            assert_int_equal(P##_solve_parallel(s, threads, 200, 0, NULL, NULL), 200);       \
            P##_get_stats(s, &b);                                                            \
            assert_int_equal(P##_checksum(s), P##_checksum(ref));                            \
            assert_int_equal(b.raster_pixels, a.raster_pixels);                              \
            assert_int_equal(b.coarse_shots, a.coarse_shots);                                \
            P##_destroy(s);                                                                  \
        }                                                                                    \
        P##_destroy(ref);                                                                    \
    }
COARSE_PARTS(sc)
COARSE_PARTS(scf)

static void test_coarse_parts_and_bands(void **st)
{
    sc_poly p[12];
    int n = lit_room(p, 0.6, 0.5), k;
    char err[256];
    uint64_t sum[2];
    (void)st;
    n += box(p + n, -0.3, -1, -0.3, 0.3, 0.2, 0.3, 0);
    for (k = 6; k < n; k++) set_mat(&p[k], 0.4, 0.5, 0.6, 0, 0, 0);
    coarse_parts_sc(p, n);
    coarse_parts_scf(p, n);
    for (k = 0; k < 2; k++) {
        sc_opts o = {.max_patch = 0.5,
                     .max_element = 0.25,
                     .res = 32,
                     .band_rows = 5,
                     .coarse = k,
                     .coarse_res = 8};
        sc_solver *s = sc_create(p, n, &o, NULL, NULL, err, sizeof err);
        sc_stats stt;
        assert_non_null(s);
        assert_int_equal(sc_solve(s, 100, 0, NULL, NULL), 100);
        sc_get_stats(s, &stt);
        CHECK_INT_EQ(stt.coarse_shots, 0, "coarse shots with bands (coarse %d)", k);
        sum[k] = sc_checksum(s);
        sc_destroy(s);
    }
    assert_int_equal(sum[1], sum[0]);
}

/* rad_init refuses a floor that is odd, below 8 or above res, and a negative fraction. */
static void test_coarse_config(void **st)
{
    static rad_surface_t sf[1];
    static rad_patch_t pt[1];
    static rad_element_t el[1];
    static rad_vec3_t vx[1];
    static const struct {
        uint16_t floor;
        double coarse;
        int rc;
    } c[] = {{0, 0, RAD_OK},         {8, 0.5, RAD_OK},      {32, 1, RAD_OK},
             {7, 0.5, RAD_ERR_ARG},  {6, 0.5, RAD_ERR_ARG}, {34, 0.5, RAD_ERR_ARG},
             {0, -0.25, RAD_ERR_ARG}};
    size_t bytes = RAD_WORK_BYTES(32, RAD_PIXELS_ALL(32), 1), i;
    void *work = malloc(bytes);
    (void)st;
    assert_non_null(work);
    for (i = 0; i < sizeof c / sizeof c[0]; i++) {
        rad_pools_t p = {.surfaces = sf,
                         .max_surfaces = 1,
                         .patches = pt,
                         .max_patches = 1,
                         .elements = el,
                         .max_elements = 1,
                         .vertices = vx,
                         .max_vertices = 1,
                         .work = work,
                         .work_bytes = bytes};
        rad_config_t cfg = {.res = 32, .coarse_res = c[i].floor, .coarse = RAD_REAL(c[i].coarse)};
        rad_scene_t s;
        CHECK_INT_EQ(rad_init(&s, &p, &cfg), c[i].rc, "coarse_res %u, coarse %g", c[i].floor,
                     c[i].coarse);
    }
    free(work);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_sums_to_one),
        cmocka_unit_test(test_point_to_polygon),
        cmocka_unit_test(test_catalog),
        cmocka_unit_test(test_closed_box_rows),
        cmocka_unit_test(test_bands_bit_exact),
        cmocka_unit_test(test_blocker_no_leak),
        cmocka_unit_test(test_element_lattice),
        cmocka_unit_test(test_coarse_tables),
        cmocka_unit_test(test_coarse_closed_room),
        cmocka_unit_test(test_coarse_parts_and_bands),
        cmocka_unit_test(test_coarse_config),
    };
    return cmocka_run_group_tests_name("hemicube", tests, NULL, NULL);
}
