/* SPDX-License-Identifier: MIT */
/* What a user adopting the library meets first (fixed build): rad_init's ABI check
 * against a unit compiled with the other RAD_INDEX_BITS, sizing pools with
 * rad_plan_polygon against what rad_add_polygon really takes, pool alignment, the
 * band fallback reported or refused, error texts and the problem a refused polygon
 * names, shooting with nothing emitting, the version macros and RAD_REAL_RATIO. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "adopt_other_abi.h"
#include "rad/rad.h"

#define Q(x) RAD_REAL(x)

/* Pools from malloc (aligned for any type), sized by the caller. */
typedef struct {
    rad_pools_t p;
} pools_t;

static void pools_make(pools_t *g, uint32_t ns, uint32_t np, uint32_t ne, uint32_t nv, size_t work)
{
    g->p.surfaces = calloc(ns ? ns : 1, sizeof(rad_surface_t));
    g->p.patches = calloc(np ? np : 1, sizeof(rad_patch_t));
    g->p.elements = calloc(ne ? ne : 1, sizeof(rad_element_t));
    g->p.vertices = calloc(nv ? nv : 1, sizeof(rad_vec3_t));
    g->p.work = calloc(work + 8, 1);
    assert_non_null(g->p.surfaces);
    assert_non_null(g->p.patches);
    assert_non_null(g->p.elements);
    assert_non_null(g->p.vertices);
    assert_non_null(g->p.work);
    g->p.max_surfaces = ns;
    g->p.max_patches = np;
    g->p.max_elements = ne;
    g->p.max_vertices = nv;
    g->p.work_bytes = work;
}

static void pools_free(pools_t *g)
{
    free(g->p.surfaces);
    free(g->p.patches);
    free(g->p.elements);
    free(g->p.vertices);
    free(g->p.work);
}

static rad_vec3_t V(double x, double y, double z)
{
    rad_vec3_t v = {Q(x), Q(y), Q(z)};
    return v;
}

static const rad_rgb_t grey = {Q(0.5), Q(0.5), Q(0.5)};
static const rad_rgb_t glow = {Q(4), Q(4), Q(4)};
static const rad_config_t res8 = {.res = 8};

/* ---- the ABI check ---------------------------------------------------------------- */

/* A unit compiled with the other index width calls rad_init of this library: refused
 * with RAD_ERR_ABI, its scene and work buffer not written (rad_init returns before it
 * touches either, so a wrong stride can never be used). */
static void test_abi_other_index_bits(void **st)
{
    adopt_other_t o;
    int rc;
    (void)st;
    rc = adopt_other_init(&o);
    print_message("other unit: sizeof(rad_index_t) %u against the library's %u: rad_init %d\n",
                  o.index_bytes, (unsigned)sizeof(rad_index_t), rc);
    assert_int_not_equal(o.index_bytes, sizeof(rad_index_t));
    assert_int_equal(rc, RAD_ERR_ABI);
    assert_int_equal(o.scene_untouched, 1);
    assert_int_equal(o.work_untouched, 1);
}

/* rad_init_abi itself: another scene size or build kind is refused, the right ones pass. */
static void test_abi_words(void **st)
{
    pools_t g;
    rad_scene_t s;
    (void)st;
    pools_make(&g, 4, 16, 64, 64, RAD_WORK_BYTES(8, RAD_PIXELS_ALL(8), 64));
    assert_int_equal(rad_init_abi(&s, &g.p, &res8, sizeof s - 8, sizeof(rad_index_t), RAD_FLOAT),
                     RAD_ERR_ABI);
    assert_int_equal(rad_init_abi(&s, &g.p, &res8, sizeof s, sizeof(rad_index_t), !RAD_FLOAT),
                     RAD_ERR_ABI);
    assert_int_equal(rad_init_abi(&s, &g.p, &res8, sizeof s, 2 * sizeof(rad_index_t), RAD_FLOAT),
                     RAD_ERR_ABI);
    assert_int_equal(rad_init_abi(NULL, &g.p, &res8, sizeof s, sizeof(rad_index_t), RAD_FLOAT),
                     RAD_ERR_ARG);
    assert_int_equal(rad_init(&s, &g.p, &res8), RAD_OK);
    pools_free(&g);
}

/* ---- planning ----------------------------------------------------------------------- */

typedef struct {
    rad_vec3_t v[4];
    unsigned n;
    int emits;
} poly_t;

/* Quads and triangles of several sizes and shapes, a skewed quad, an emitter (meshed
 * with a patch per element) and one below an element's size. */
static const poly_t *polys(unsigned *count)
{
    static poly_t p[8];
    p[0] = (poly_t){{V(-20, 0, -20), V(-20, 0, 20), V(20, 0, 20), V(20, 0, -20)}, 4, 0};
    p[1] = (poly_t){{V(0, 0, 0), V(7, 0, 0), V(0, 13, 0), V(0, 0, 0)}, 3, 0};
    p[2] = (poly_t){{V(-30, 5, 1), V(31, 5, 3), V(29, 19, 2), V(-28, 17, 0)}, 4, 0};
    p[3] = (poly_t){{V(-4, 30, -3), V(4, 30, -3), V(4, 30, 3), V(-4, 30, 3)}, 4, 1};
    p[4] = (poly_t){{V(1, 1, 1), V(1.5, 1, 1), V(1, 1.25, 1), V(0, 0, 0)}, 3, 0};
    p[5] = (poly_t){{V(-60, -60, 10), V(60, -60, 10), V(0, 60, 10), V(0, 0, 0)}, 3, 1};
    p[6] = (poly_t){{V(10, 0, 0), V(10, 0, 50), V(10, 9, 50), V(10, 9, 0)}, 4, 0};
    *count = 7;
    return p;
}

static const rad_config_t plan_cfgs[] = {
    {.max_element = Q(2.0)},
    {.max_element = Q(3.5), .max_patch = Q(9.0), .res = 16},
    {.max_element = Q(1.25), .max_patch = Q(1.25), .res = 8},
};

/* For every polygon and configuration, the plan equals what rad_add_polygon takes; the
 * summed plan then sizes pools exactly: everything fits, and one element fewer fails
 * with RAD_ERR_FULL on the last polygon. */
static void test_plan_matches_mesh(void **st)
{
    unsigned c, i, np;
    const poly_t *p = polys(&np);
    (void)st;
    for (c = 0; c < sizeof plan_cfgs / sizeof plan_cfgs[0]; c++) {
        const rad_config_t *cfg = &plan_cfgs[c];
        rad_plan_t total = {0};
        pools_t g;
        rad_scene_t s;
        int shrink;
        for (i = 0; i < np; i++)
            assert_int_equal(
                rad_plan_polygon(cfg, p[i].v, p[i].n, &grey, p[i].emits ? &glow : NULL, &total),
                RAD_OK);
        print_message("config %u: planned %u surfaces, %u patches, %u elements, %u vertices\n", c,
                      total.surfaces, total.patches, total.elements, total.vertices);
        for (shrink = 0; shrink < 2; shrink++) {
            uint32_t n_acc = total.elements > total.vertices ? total.elements : total.vertices;
            pools_make(&g, total.surfaces, total.patches, total.elements - (uint32_t)shrink,
                       total.vertices, RAD_WORK_BYTES(cfg->res ? cfg->res : 64, 64, n_acc));
            assert_int_equal(rad_init(&s, &g.p, cfg), RAD_OK);
            for (i = 0; i < np; i++) {
                rad_plan_t one = {0};
                uint32_t ns = s.n_surfaces, npt = s.n_patches, ne = s.n_elements;
                uint32_t nv = s.n_vertices;
                int rc;
                assert_int_equal(
                    rad_plan_polygon(cfg, p[i].v, p[i].n, &grey, p[i].emits ? &glow : NULL, &one),
                    RAD_OK);
                rc = rad_add_polygon(&s, p[i].v, p[i].n, &grey, p[i].emits ? &glow : NULL);
                if (shrink && i == np - 1) {
                    assert_int_equal(rc, RAD_ERR_FULL);
                    break;
                }
                assert_int_equal(rc, (int)i);
                assert_int_equal(s.n_surfaces - ns, one.surfaces);
                assert_int_equal(s.n_patches - npt, one.patches);
                assert_int_equal(s.n_elements - ne, one.elements);
                assert_int_equal(s.n_vertices - nv, one.vertices);
            }
            if (!shrink) {
                assert_int_equal(s.n_elements, total.elements);
                assert_int_equal(s.n_vertices, total.vertices);
            }
            pools_free(&g);
        }
    }
}

/* A refused polygon: the same error as rad_add_polygon, the counts unchanged, and the
 * problem naming which value (the detail rad_strerror's RAD_ERR_RANGE text points to). */
static void expect_problem(const rad_vec3_t *v, unsigned n, const rad_rgb_t *rho,
                           const rad_rgb_t *em, int err, const char *word)
{
    rad_plan_t pl = {1, 2, 3, 4, NULL};
    int rc = rad_plan_polygon(NULL, v, n, rho, em, &pl);
    print_message("plan: %d \"%s\" (expected %d naming \"%s\")\n", rc,
                  pl.problem ? pl.problem : "(null)", err, word);
    assert_int_equal(rc, err);
    assert_non_null(pl.problem);
    assert_non_null(strstr(pl.problem, word));
    assert_int_equal(pl.surfaces, 1);
    assert_int_equal(pl.patches, 2);
    assert_int_equal(pl.elements, 3);
    assert_int_equal(pl.vertices, 4);
}

static void test_plan_problems(void **st)
{
    const rad_vec3_t ok[4] = {V(0, 0, 0), V(4, 0, 0), V(4, 4, 0), V(0, 4, 0)};
    const rad_vec3_t far[3] = {V(0, 0, 0), V(8193, 0, 0), V(0, 4, 0)}; /* RAD_INPUT_LIMIT */
    const rad_vec3_t same[3] = {V(0, 0, 0), V(0, 0, 0), V(0, 4, 0)};
    const rad_vec3_t line[3] = {V(0, 0, 0), V(1, 0, 0), V(2, 0, 0)};
    const rad_vec3_t bent[4] = {V(0, 0, 0), V(4, 0, 0), V(4, 4, 1), V(0, 4, 0)};
    const rad_vec3_t dart[4] = {V(0, 0, 0), V(4, 0, 0), V(1, 1, 0), V(0, 4, 0)};
    const rad_rgb_t rho_one = {Q(1.0), 0, 0}, em_big = {0, 0, Q(4097.0)}, neg = {0, -1, 0};
    rad_config_t bad = {.res = 9};
    rad_plan_t pl = {0};
    pools_t g;
    rad_scene_t s;
    (void)st;
    expect_problem(far, 3, &grey, NULL, RAD_ERR_RANGE, "coordinate");
    expect_problem(ok, 4, &rho_one, NULL, RAD_ERR_RANGE, "reflectance");
    expect_problem(ok, 4, &grey, &em_big, RAD_ERR_RANGE, "emission");
    expect_problem(ok, 4, &grey, &neg, RAD_ERR_RANGE, "emission");
    expect_problem(same, 3, &grey, NULL, RAD_ERR_DEGENERATE, "vertices equal");
    expect_problem(line, 3, &grey, NULL, RAD_ERR_DEGENERATE, "area");
    expect_problem(bent, 4, &grey, NULL, RAD_ERR_NONPLANAR, "plane");
    expect_problem(dart, 4, &grey, NULL, RAD_ERR_NONPLANAR, "convex");
    expect_problem(ok, 5, &grey, NULL, RAD_ERR_ARG, "3 or 4");
    assert_int_equal(rad_plan_polygon(&bad, ok, 4, &grey, NULL, &pl), RAD_ERR_ARG);
    print_message("res 9: \"%s\"\n", pl.problem);
    assert_non_null(strstr(pl.problem, "res"));
    assert_int_equal(rad_plan_polygon(NULL, ok, 4, &grey, NULL, NULL), RAD_ERR_ARG);
    /* rad_add_polygon refuses the same polygons with the same codes. */
    pools_make(&g, 4, 16, 64, 64, RAD_WORK_BYTES(8, RAD_PIXELS_ALL(8), 64));
    assert_int_equal(rad_init(&s, &g.p, &res8), RAD_OK);
    assert_int_equal(rad_add_polygon(&s, far, 3, &grey, NULL), RAD_ERR_RANGE);
    assert_int_equal(rad_add_polygon(&s, ok, 4, &rho_one, NULL), RAD_ERR_RANGE);
    assert_int_equal(rad_add_polygon(&s, ok, 4, &grey, &em_big), RAD_ERR_RANGE);
    assert_int_equal(rad_add_polygon(&s, dart, 4, &grey, NULL), RAD_ERR_NONPLANAR);
    assert_int_equal(s.n_surfaces, 0);
    pools_free(&g);
    /* Counts saturate instead of wrapping. */
    pl.surfaces = pl.patches = pl.elements = pl.vertices = UINT32_MAX - 1u;
    assert_int_equal(rad_plan_polygon(NULL, ok, 4, &grey, NULL, &pl), RAD_OK);
    assert_int_equal(pl.surfaces, UINT32_MAX);
    assert_int_equal(pl.elements, UINT32_MAX);
}

/* Triangles are cut by their longest side unless they are slivers: then by 2 sqrt(area)
 * (lib/mesh.c, plan_mesh), so their element count follows their area as a quad's does.
 * A 60 x 0.25 sliver at max_element 1 was 60^2 = 3,600 elements (a 65 KB wall of 2,000
 * such meshed into 1.15 million); by its area 7.5, s = 2 sqrt(7.5) = 5.48: 2 patch
 * levels (max_patch 4) of 3 element levels, 6^2 = 36. A triangle whose height is over
 * half its longest side is cut as it always was: side 10, 3 patch levels of 4, 144. */
static void test_plan_slivers(void **st)
{
    const rad_vec3_t sliver[3] = {V(0, 0, 0), V(60, 0, 0), V(60, 0.25, 0)};
    const rad_vec3_t fat[3] = {V(0, 0, 0), V(10, 0, 0), V(5, 8.66, 0)};
    const rad_config_t cfg = {.max_element = Q(1.0), .max_patch = Q(4.0)};
    rad_plan_t a = {0}, b = {0};
    (void)st;
    assert_int_equal(rad_plan_polygon(&cfg, sliver, 3, &grey, NULL, &a), RAD_OK);
    assert_int_equal(rad_plan_polygon(&cfg, fat, 3, &grey, NULL, &b), RAD_OK);
    print_message("sliver 60 x 0.25: %u elements, %u patches (bound 36, 4; by its long side "
                  "3600); triangle of side 10: %u elements (expected 144)\n",
                  a.elements, a.patches, b.elements);
    assert_true(a.elements <= 36u);
    assert_true(a.patches <= 4u);
    assert_int_equal(b.elements, 144u);
}

/* ---- alignment and the work buffer -------------------------------------------------- */

/* Each pool one byte off its type's alignment: RAD_ERR_ALIGN, the scene not written. */
static void test_alignment_refused(void **st)
{
    pools_t g;
    rad_scene_t s, before;
    unsigned k;
    (void)st;
    pools_make(&g, 5, 16, 64, 64, RAD_WORK_BYTES(8, RAD_PIXELS_ALL(8), 64));
    for (k = 0; k < 4; k++) {
        rad_pools_t p = g.p;
        unsigned char *b;
        switch (k) {
        case 0:
            b = (unsigned char *)p.surfaces;
            p.surfaces = (rad_surface_t *)(void *)(b + 1);
            break;
        case 1:
            b = (unsigned char *)p.patches;
            p.patches = (rad_patch_t *)(void *)(b + 1);
            break;
        case 2:
            b = (unsigned char *)p.elements;
            p.elements = (rad_element_t *)(void *)(b + 1);
            break;
        default:
            b = (unsigned char *)p.vertices;
            p.vertices = (rad_vec3_t *)(void *)(b + 1);
            break;
        }
        p.max_surfaces = p.max_patches = p.max_elements = p.max_vertices = 4;
        memset(&s, 0x5A, sizeof s);
        before = s;
        before.self = NULL; /* a failed rad_init clears the marker alone (rad.h) */
        assert_int_equal(rad_init(&s, &p, NULL), RAD_ERR_ALIGN);
        assert_memory_equal(&s, &before, sizeof s);
    }
    pools_free(&g);
}

/* A closed box lit from its top, solved for 20 shots with the work buffer at offset OFF. */
static void solve_box(size_t off, rad_rgb_t *out, uint32_t n)
{
    const double h = 8;
    const rad_vec3_t f[6][4] = {
        {V(-h, -h, -h), V(-h, -h, h), V(h, -h, h), V(h, -h, -h)},
        {V(-h, h, -h), V(h, h, -h), V(h, h, h), V(-h, h, h)},
        {V(-h, -h, -h), V(-h, h, -h), V(-h, h, h), V(-h, -h, h)},
        {V(h, -h, -h), V(h, -h, h), V(h, h, h), V(h, h, -h)},
        {V(-h, -h, -h), V(h, -h, -h), V(h, h, -h), V(-h, h, -h)},
        {V(-h, -h, h), V(-h, h, h), V(h, h, h), V(h, -h, h)},
    };
    const rad_config_t cfg = {.max_element = Q(4.0), .max_patch = Q(8.0), .res = 16};
    size_t bytes = RAD_WORK_BYTES(16, RAD_PIXELS_ALL(16), 256);
    pools_t g;
    rad_scene_t s;
    uint32_t e;
    int i;
    pools_make(&g, 8, 64, 256, 256, bytes + off);
    g.p.work = (unsigned char *)g.p.work + off;
    g.p.work_bytes = bytes;
    assert_int_equal(rad_init(&s, &g.p, &cfg), RAD_OK);
    assert_int_equal(s.band_rows, 0);
    for (i = 0; i < 6; i++)
        assert_int_equal(rad_add_polygon(&s, f[i], 4, &grey, i == 1 ? &glow : NULL), i);
    assert_int_equal(rad_shoot(&s, 20, 0), 20);
    assert_int_equal(s.n_elements, n);
    for (e = 0; e < n; e++) assert_int_equal(rad_element_radiosity(&s, e, 0, &out[e]), RAD_OK);
    g.p.work = (unsigned char *)g.p.work - off;
    pools_free(&g);
}

/* The work buffer at any address: the core aligns it itself, with the same bits. */
static void test_work_any_alignment(void **st)
{
    rad_rgb_t a[96], b[96];
    size_t off;
    (void)st;
    solve_box(0, a, 96);
    for (off = 1; off < 8; off++) {
        solve_box(off, b, 96);
        assert_memory_equal(a, b, sizeof a);
    }
}

/* A work buffer sized for fewer accumulators than the pools need has room for no more
 * than bands: reported in band_rows, or refused with RAD_NO_BANDS. */
static void test_band_fallback(void **st)
{
    const rad_config_t all = {.res = 32}, strict = {.res = 32, .flags = RAD_NO_BANDS};
    const rad_config_t both = {.res = 32, .band_rows = 4, .flags = RAD_NO_BANDS};
    pools_t small, full;
    rad_scene_t s;
    (void)st;
    pools_make(&small, 4, 64, 1000, 1000, RAD_WORK_BYTES(32, RAD_PIXELS_ALL(32), 100));
    pools_make(&full, 4, 64, 1000, 1000, RAD_WORK_BYTES(32, RAD_PIXELS_ALL(32), 1000));
    assert_int_equal(rad_init(&s, &small.p, &all), RAD_OK);
    print_message("work for 100 accumulators, pools of 1000: band_rows %u\n", s.band_rows);
    assert_int_not_equal(s.band_rows, 0);
    assert_int_equal(rad_init(&s, &small.p, &strict), RAD_ERR_WORK);
    assert_int_equal(rad_init(&s, &full.p, &strict), RAD_OK);
    assert_int_equal(s.band_rows, 0);
    assert_int_equal(rad_init(&s, &full.p, &both), RAD_ERR_ARG);
    pools_free(&small);
    pools_free(&full);
}

/* ---- errors, shooting with nothing emitting, constants ----------------------------- */

static void test_strerror_texts(void **st)
{
    int k, j;
    (void)st;
    for (k = RAD_OK; k >= RAD_ERR_ABI; k--) {
        assert_non_null(rad_strerror(k));
        print_message("%d: %s\n", k, rad_strerror(k));
        assert_in_range(strlen(rad_strerror(k)), 7, 100);
        for (j = RAD_OK; j > k; j--) assert_string_not_equal(rad_strerror(k), rad_strerror(j));
    }
    assert_non_null(strstr(rad_strerror(RAD_ERR_RANGE), "rad_plan_polygon"));
    assert_non_null(strstr(rad_strerror(RAD_ERR_ABI), "RAD_INDEX_BITS"));
    assert_non_null(strstr(rad_strerror(RAD_ERR_ALIGN), "aligned"));
    assert_string_equal(rad_strerror(RAD_ERR_ARG), "invalid argument");
    assert_string_equal(rad_strerror(-99), "unknown error");
}

/* Shooting a scene where nothing emits shoots nothing and leaves it open: more polygons
 * go in, and the first shot once something emits freezes it as before. */
static void test_shoot_nothing_emitting(void **st)
{
    const rad_vec3_t floor[4] = {V(-8, 0, -8), V(-8, 0, 8), V(8, 0, 8), V(8, 0, -8)};
    const rad_vec3_t lamp[4] = {V(-2, 6, -2), V(2, 6, -2), V(2, 6, 2), V(-2, 6, 2)};
    const rad_config_t cfg = {.max_element = Q(4.0), .res = 16};
    pools_t g;
    rad_scene_t s;
    uint32_t p;
    (void)st;
    pools_make(&g, 4, 64, 64, 64, RAD_WORK_BYTES(16, RAD_PIXELS_ALL(16), 64));
    assert_int_equal(rad_init(&s, &g.p, &cfg), RAD_OK);
    assert_int_equal(rad_add_polygon(&s, floor, 4, &grey, NULL), 0);
    assert_int_equal(rad_shoot(&s, 10, 0), 0);
    assert_int_equal(rad_shot_begin(&s, 0, &p), 0);
    assert_int_equal(s.solving, 0);
    assert_int_equal(rad_add_polygon(&s, lamp, 4, &grey, &glow), 1);
    assert_int_equal(rad_shoot(&s, 3, 0), 3);
    assert_int_equal(s.solving, 1);
    assert_int_equal(rad_add_polygon(&s, floor, 4, &grey, NULL), RAD_ERR_STATE);
    pools_free(&g);
}

static void test_version(void **st)
{
    char want[32];
    (void)st;
    snprintf(want, sizeof want, "%d.%d.%d", RAD_VERSION_MAJOR, RAD_VERSION_MINOR,
             RAD_VERSION_PATCH);
    assert_string_equal(RAD_VERSION, want);
    assert_int_equal(RAD_VERSION_NUMBER,
                     RAD_VERSION_MAJOR * 10000 + RAD_VERSION_MINOR * 100 + RAD_VERSION_PATCH);
#if RAD_VERSION_NUMBER < 900
#error "RAD_VERSION_NUMBER must be usable in #if"
#endif
}

/* Folded at compile time: a static initialiser (no floating point on a target). */
static const rad_real_t seven_tenths = RAD_REAL_RATIO(7, 10);

/* RAD_REAL_RATIO equals RAD_REAL of the double quotient: exact ties (multiples of
 * 2^-17), both signs, the range's ends, and pseudo-random pairs with DEN < 2^20. */
static void test_real_ratio(void **st)
{
    static const int64_t pairs[][2] = {
        {7, 10},        {-7, 10},   {1, 131072}, {-1, 131072},       {3, 131072},
        {-5, 131072},   {1, 3},     {-2, 3},     {32767, 1},         {-32767, 1},
        {65535, 65536}, {1, 65536}, {0, 7},      {1048575, 1048575}, {-1, 1048575},
    };
    uint64_t x = 0x9E3779B97F4A7C15u;
    unsigned i, bad = 0;
    (void)st;
    assert_int_equal(seven_tenths, RAD_REAL(0.7));
    for (i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        int64_t n = pairs[i][0], d = pairs[i][1];
        rad_real_t a = RAD_REAL_RATIO(n, d), b = RAD_REAL((double)n / (double)d);
        if (a != b)
            print_message("RAD_REAL_RATIO(%lld, %lld) = %d, RAD_REAL %d\n", (long long)n,
                          (long long)d, (int)a, (int)b);
        assert_int_equal(a, b);
    }
    for (i = 0; i < 200000; i++) {
        int64_t d, n;
        x = x * 6364136223846793005u + 1442695040888963407u;
        d = (int64_t)(x >> 44) + 1; /* 1 .. 2^20 */
        if (d >= 1048576) d = 1048575;
        n = (int64_t)((x >> 8) % (uint64_t)(32767 * d)) * ((x >> 7) & 1 ? -1 : 1);
        if (RAD_REAL_RATIO(n, d) != RAD_REAL((double)n / (double)d)) {
            if (bad++ < 5)
                print_message("RAD_REAL_RATIO(%lld, %lld) = %d, RAD_REAL %d\n", (long long)n,
                              (long long)d, (int)RAD_REAL_RATIO(n, d),
                              (int)RAD_REAL((double)n / (double)d));
        }
    }
    assert_int_equal(bad, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_abi_other_index_bits),
        cmocka_unit_test(test_abi_words),
        cmocka_unit_test(test_plan_matches_mesh),
        cmocka_unit_test(test_plan_problems),
        cmocka_unit_test(test_plan_slivers),
        cmocka_unit_test(test_alignment_refused),
        cmocka_unit_test(test_work_any_alignment),
        cmocka_unit_test(test_band_fallback),
        cmocka_unit_test(test_strerror_texts),
        cmocka_unit_test(test_shoot_nothing_emitting),
        cmocka_unit_test(test_version),
        cmocka_unit_test(test_real_ratio),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
