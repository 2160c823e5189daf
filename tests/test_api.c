/* SPDX-License-Identifier: MIT */
/* Every public function's error paths, the state after errors, guard bytes after every
 * caller buffer, relighting by restart, and saturation counting (fixed build). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "check.h"
#include "rad/rad.h"

#define GUARD 64
#define NS    16
#define NP    256
#define NE    1024
#define NV    2048
#define WORK  RAD_WORK_BYTES(32, RAD_PIXELS_ALL(32), NV)

/* Pools with GUARD bytes of 0xA5 after each, checked after every call. */
typedef struct {
    unsigned char *surf, *patch, *elem, *vert, *work;
    rad_pools_t p;
} guarded_t;

static unsigned char *galloc(size_t n)
{
    unsigned char *b = malloc(n + GUARD);
    assert_non_null(b);
    memset(b, 0, n);
    memset(b + n, 0xA5, GUARD);
    return b;
}

static void gcheck(const unsigned char *b, size_t n)
{
    size_t i;
    for (i = 0; i < GUARD; i++) assert_int_equal(b[n + i], 0xA5);
}

static void pools_make(guarded_t *g, uint32_t ns, uint32_t np, uint32_t ne, uint32_t nv,
                       size_t work)
{
    g->surf = galloc(ns * sizeof(rad_surface_t));
    g->patch = galloc(np * sizeof(rad_patch_t));
    g->elem = galloc(ne * sizeof(rad_element_t));
    g->vert = galloc(nv * sizeof(rad_vec3_t));
    g->work = galloc(work);
    g->p.surfaces = (rad_surface_t *)g->surf;
    g->p.max_surfaces = ns;
    g->p.patches = (rad_patch_t *)g->patch;
    g->p.max_patches = np;
    g->p.elements = (rad_element_t *)g->elem;
    g->p.max_elements = ne;
    g->p.vertices = (rad_vec3_t *)g->vert;
    g->p.max_vertices = nv;
    g->p.work = g->work;
    g->p.work_bytes = work;
}

static void pools_check(const guarded_t *g)
{
    gcheck(g->surf, g->p.max_surfaces * sizeof(rad_surface_t));
    gcheck(g->patch, g->p.max_patches * sizeof(rad_patch_t));
    gcheck(g->elem, g->p.max_elements * sizeof(rad_element_t));
    gcheck(g->vert, g->p.max_vertices * sizeof(rad_vec3_t));
    gcheck(g->work, g->p.work_bytes);
}

static void pools_free(guarded_t *g)
{
    free(g->surf);
    free(g->patch);
    free(g->elem);
    free(g->vert);
    free(g->work);
}

#define Q(x) RAD_REAL(x)
static rad_vec3_t V(double x, double y, double z)
{
    rad_vec3_t v;
    v.x = Q(x);
    v.y = Q(y);
    v.z = Q(z);
    return v;
}

static const rad_rgb_t grey = {Q(0.5), Q(0.5), Q(0.5)};
static const rad_rgb_t light = {Q(10), Q(10), Q(10)};

/* A closed cube of side 8 (inward faces) of reflectance RHO, the top emitting EM. */
static void add_cube_with(rad_scene_t *s, const rad_rgb_t *rho, const rad_rgb_t *em)
{
    rad_vec3_t f[6][4] = {
        {V(-4, -4, -4), V(-4, -4, 4), V(4, -4, 4), V(4, -4, -4)},
        {V(-4, 4, -4), V(4, 4, -4), V(4, 4, 4), V(-4, 4, 4)},
        {V(-4, -4, -4), V(-4, 4, -4), V(-4, 4, 4), V(-4, -4, 4)},
        {V(4, -4, -4), V(4, -4, 4), V(4, 4, 4), V(4, 4, -4)},
        {V(-4, -4, -4), V(4, -4, -4), V(4, 4, -4), V(-4, 4, -4)},
        {V(-4, -4, 4), V(-4, 4, 4), V(4, 4, 4), V(4, -4, 4)},
    };
    int i;
    for (i = 0; i < 6; i++)
        assert_int_equal(rad_add_polygon(s, f[i], 4, rho, i == 1 ? em : NULL), i);
}

static void add_cube(rad_scene_t *s)
{
    add_cube_with(s, &grey, &light);
}

static const rad_config_t cfg = {
    .max_patch = RAD_REAL(4.0), .max_element = RAD_REAL(2.0), .res = 32};

static void test_init_errors(void **st)
{
    guarded_t g;
    rad_scene_t s;
    rad_pools_t p;
    rad_config_t c;
    (void)st;
    pools_make(&g, NS, NP, NE, NV, WORK);
    assert_int_equal(rad_init(NULL, &g.p, &cfg), RAD_ERR_ARG);
    assert_int_equal(rad_init(&s, NULL, &cfg), RAD_ERR_ARG);
    p = g.p;
    p.elements = NULL;
    assert_int_equal(rad_init(&s, &p, &cfg), RAD_ERR_ARG);
    p = g.p;
    p.work = NULL;
    assert_int_equal(rad_init(&s, &p, &cfg), RAD_ERR_ARG);
    p = g.p;
    p.max_elements = 0xFFFFFFFFu; /* beyond the index type */
    assert_int_equal(rad_init(&s, &p, &cfg), RAD_ERR_ARG);
    c = cfg;
    c.res = 31; /* odd */
    assert_int_equal(rad_init(&s, &g.p, &c), RAD_ERR_ARG);
    c = cfg;
    c.res = 6;
    assert_int_equal(rad_init(&s, &g.p, &c), RAD_ERR_ARG);
    c = cfg;
    c.res = RAD_MAX_RES + 2;
    assert_int_equal(rad_init(&s, &g.p, &c), RAD_ERR_ARG);
    c = cfg;
    c.max_element = -1; /* below one LSB */
    assert_int_equal(rad_init(&s, &g.p, &c), RAD_ERR_ARG);
    c = cfg;
    c.max_element = 1;
    c.max_patch = 0; /* one LSB: any unit is the caller's */
    assert_int_equal(rad_init(&s, &g.p, &c), RAD_OK);
    assert_int_equal(s.cfg.max_patch, 4);
    c = cfg;
    c.max_patch = Q(1.0); /* smaller than an element */
    assert_int_equal(rad_init(&s, &g.p, &c), RAD_ERR_ARG);
    c = cfg;
    c.flags = 2; /* no such flag */
    assert_int_equal(rad_init(&s, &g.p, &c), RAD_ERR_ARG);
    /* Out of range with the default patch size (0): refused before 4 * max_element is
     * formed (it overflowed in the fixed build: found by fuzz_core). */
    c = cfg;
    c.max_patch = 0;
    c.max_element = -Q(16384.0);
    assert_int_equal(rad_init(&s, &g.p, &c), RAD_ERR_ARG);
    c = cfg;
    c.max_patch = 0;
    c.max_element = Q(16384.0) + 1; /* 2 RAD_INPUT_LIMIT */
    assert_int_equal(rad_init(&s, &g.p, &c), RAD_ERR_ARG);
    c = cfg;
    c.max_patch = 0;
    c.max_element = Q(16384.0); /* the default patch: the most */
    assert_int_equal(rad_init(&s, &g.p, &c), RAD_OK);
    assert_int_equal(s.cfg.max_patch, Q(16384.0));
    /* Work: the table and accumulators fit, but not one row of a face. */
    p = g.p;
    p.work_bytes = RAD_WORK_BYTES(32, 0, NV);
    assert_int_equal(rad_init(&s, &p, &cfg), RAD_ERR_WORK);
    /* One row fits: banded to a single row. */
    p.work_bytes = RAD_WORK_BYTES(32, 32, NV);
    assert_int_equal(rad_init(&s, &p, &cfg), RAD_OK);
    assert_int_equal(s.band_rows, 1);
    /* Defaults: zero config. */
    assert_int_equal(rad_init(&s, &g.p, NULL), RAD_OK);
    assert_int_equal(s.cfg.res, 64);
    assert_int_equal(s.cfg.max_element, Q(4.0));
    assert_int_equal(s.cfg.max_patch, Q(16.0));
    /* the work buffer was sized for 32: it bands */
    CHECK_INT_GT(s.band_rows, 0,
                 "rows per band at the default res 64 in a work buffer sized for 32");
    pools_check(&g);
    pools_free(&g);
}

static void test_add_errors(void **st)
{
    guarded_t g;
    rad_scene_t s;
    rad_rgb_t bad;
    rad_vec3_t ok[4] = {V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)}, v[4];
    (void)st;
    pools_make(&g, NS, NP, NE, NV, WORK);
    assert_int_equal(rad_init(&s, &g.p, &cfg), RAD_OK);
    assert_int_equal(rad_add_polygon(NULL, ok, 4, NULL, NULL), RAD_ERR_ARG);
    assert_int_equal(rad_add_polygon(&s, NULL, 4, NULL, NULL), RAD_ERR_ARG);
    assert_int_equal(rad_add_polygon(&s, ok, 2, NULL, NULL), RAD_ERR_ARG);
    assert_int_equal(rad_add_polygon(&s, ok, 5, NULL, NULL), RAD_ERR_ARG);
    /* Coordinates: RAD_INPUT_LIMIT (8192.0) is the limit, one LSB more is out. */
    v[0] = V(8184, 0, 0);
    v[1] = V(8192, 0, 0);
    v[2] = V(8184, 8, 0);
    assert_int_equal(rad_add_polygon(&s, v, 3, NULL, NULL), 0);
    memcpy(v, ok, sizeof v);
    v[1].y = Q(8192.0) + 1;
    assert_int_equal(rad_add_polygon(&s, v, 3, NULL, NULL), RAD_ERR_RANGE);
    memcpy(v, ok, sizeof v);
    v[0].z = INT32_MIN;
    assert_int_equal(rad_add_polygon(&s, v, 3, NULL, NULL), RAD_ERR_RANGE);
    /* Reflectance in [0, 1), emission in [0, 4096]. */
    bad = grey;
    bad.g = Q(1.0);
    assert_int_equal(rad_add_polygon(&s, ok, 4, &bad, NULL), RAD_ERR_RANGE);
    bad = grey;
    bad.b = -1;
    assert_int_equal(rad_add_polygon(&s, ok, 4, &bad, NULL), RAD_ERR_RANGE);
    bad = light;
    bad.r = Q(4096.0) + 1;
    assert_int_equal(rad_add_polygon(&s, ok, 4, NULL, &bad), RAD_ERR_RANGE);
    bad = light;
    bad.g = -5;
    assert_int_equal(rad_add_polygon(&s, ok, 4, NULL, &bad), RAD_ERR_RANGE);
    /* Degenerate: a point, collinear, a repeated vertex, below the minimum area. */
    v[0] = v[1] = v[2] = V(1, 1, 1);
    assert_int_equal(rad_add_polygon(&s, v, 3, NULL, NULL), RAD_ERR_DEGENERATE);
    v[0] = V(0, 0, 0);
    v[1] = V(1, 1, 1);
    v[2] = V(2, 2, 2);
    assert_int_equal(rad_add_polygon(&s, v, 3, NULL, NULL), RAD_ERR_DEGENERATE);
    memcpy(v, ok, sizeof v);
    v[2] = v[1];
    assert_int_equal(rad_add_polygon(&s, v, 4, NULL, NULL), RAD_ERR_DEGENERATE);
    v[0] = V(0, 0, 0);
    v[1] = V(0.01, 0, 0);
    v[2] = V(0, 0.01, 0); /* area 5e-5 < 1/4096 */
    assert_int_equal(rad_add_polygon(&s, v, 3, NULL, NULL), RAD_ERR_DEGENERATE);
    /* Non-planar (a corner lifted by a quarter of the side), non-convex, bow-tie. */
    memcpy(v, ok, sizeof v);
    v[2].z = Q(0.25);
    assert_int_equal(rad_add_polygon(&s, v, 4, NULL, NULL), RAD_ERR_NONPLANAR);
    memcpy(v, ok, sizeof v);
    v[2] = V(0.3, 0.3, 0);
    assert_int_equal(rad_add_polygon(&s, v, 4, NULL, NULL), RAD_ERR_NONPLANAR);
    v[0] = V(0, 0, 0);
    v[1] = V(1, 1, 0);
    v[2] = V(1, 0, 0);
    v[3] = V(0, 1, 0);
    CHECK_INT_LT(rad_add_polygon(&s, v, 4, NULL, NULL), 0,
                 "rad_add_polygon of a bow-tie quad: an error");
    /* Far out, a polygon is measured at its own scale (2^-7 at 8192, rad.h): a
     * triangle of area 0.5 there is 2^-15 square units, below 1/4096. */
    v[0] = V(8000, 0, 0);
    v[1] = V(8001, 0, 0);
    v[2] = V(8000, 1, 0);
    assert_int_equal(rad_add_polygon(&s, v, 3, NULL, NULL), RAD_ERR_DEGENERATE);
    /* A lattice of more than 32768 elements a side: no pool holds it. */
    {
        rad_config_t fine = cfg;
        rad_plan_t plan = {0};
        fine.max_element = 1; /* 2^-16 units: 65536 elements along the unit quad's side */
        fine.max_patch = 0;
        CHECK_INT_EQ(rad_plan_polygon(&fine, ok, 4, NULL, NULL, &plan), RAD_ERR_FULL,
                     "rad_plan_polygon of a unit quad at 2^-16 a side");
        CHECK_CONTAINS(plan.problem, "32768", "rad_plan_polygon's problem");
    }
    /* Nothing was added by any of these, except the in-range triangle above. */
    assert_int_equal(s.n_surfaces, 1);
    /* A slightly bent quad (1/200 of its side) is accepted as planar. */
    memcpy(v, ok, sizeof v);
    v[2].z = Q(0.005);
    assert_int_equal(rad_add_polygon(&s, v, 4, NULL, NULL), 1);
    pools_check(&g);
    pools_free(&g);
}

/* A scene scaled down to fit (rad.h: any units) keeps every vertex within
 * +-RAD_COORD_LIMIT: a coordinate one LSB beyond -256 rounds down (away from 0) at the
 * quarter scale, so that scale is too large for it; it takes an eighth. The fuzzer found
 * -64 - 2^-16 in the pool when the choice rounded the magnitude to nearest. */
static void test_scaled_down_fits(void **st)
{
    guarded_t g;
    rad_scene_t s;
    rad_vec3_t v[3] = {V(-64, 64, 0), V(64, 64, 0), V(0, 64, 0)};
    uint32_t i;
    int outside = 0;
    (void)st;
    v[2].z = -Q(256.0) - 1;
    pools_make(&g, NS, NP, NE, NV, WORK);
    assert_int_equal(rad_init(&s, &g.p, &cfg), RAD_OK);
    assert_int_equal(rad_add_polygon(&s, v, 3, &grey, NULL), 0);
    for (i = 0; i < s.n_vertices; i++) {
        const rad_vec3_t *p = &g.p.vertices[i];
        outside += p->x < -Q(64.0) || p->x > Q(64.0) || p->y < -Q(64.0) || p->y > Q(64.0) ||
                   p->z < -Q(64.0) || p->z > Q(64.0);
    }
    print_message("length shift %d; vertices beyond +-64: %d of %u\n", s.length_shift, outside,
                  (unsigned)s.n_vertices);
    CHECK_INT_EQ(outside, 0, "vertices beyond +-RAD_COORD_LIMIT in the pool");
    CHECK_INT_EQ(s.length_shift, -3, "the scale of a coordinate just beyond -256");
    pools_check(&g);
    pools_free(&g);
}

static void test_full_pools(void **st)
{
    /* Each pool in turn too small for the cube: RAD_ERR_FULL, counts untouched, and
     * a smaller polygon still goes in afterwards. */
    static const uint32_t sizes[4][4] = {
        {2, NP, NE, NV}, {NS, 22, NE, NV}, {NS, NP, 90, NV}, {NS, NP, NE, 140}};
    int k;
    (void)st;
    for (k = 0; k < 4; k++) {
        guarded_t g;
        rad_scene_t s;
        rad_vec3_t big[4] = {V(-4, -4, -4), V(-4, -4, 4), V(4, -4, 4), V(4, -4, -4)};
        rad_vec3_t small[3] = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
        uint32_t ns, np, ne, nv;
        int i, rc = 0;
        pools_make(&g, sizes[k][0], sizes[k][1], sizes[k][2], sizes[k][3],
                   RAD_WORK_BYTES(32, RAD_PIXELS_ALL(32), NV));
        assert_int_equal(rad_init(&s, &g.p, &cfg), RAD_OK);
        for (i = 0; i < 6 && rc >= 0; i++) {
            ns = s.n_surfaces;
            np = s.n_patches;
            ne = s.n_elements;
            nv = s.n_vertices;
            rc = rad_add_polygon(&s, big, 4, &grey, &light);
        }
        assert_int_equal(rc, RAD_ERR_FULL);
        assert_int_equal(s.n_surfaces, ns);
        assert_int_equal(s.n_patches, np);
        assert_int_equal(s.n_elements, ne);
        assert_int_equal(s.n_vertices, nv);
        if (k != 0)
            CHECK_INT_GE(rad_add_polygon(&s, small, 3, &grey, NULL), 0,
                         "pool %d full: a smaller polygon still goes in", k);
        /* The scene still solves. */
        CHECK_INT_GE(rad_shoot(&s, 5, 0), 0, "pool %d full: the scene still solves", k);
        pools_check(&g);
        pools_free(&g);
    }
}

static void test_calls_and_guards(void **st)
{
    guarded_t g;
    rad_scene_t s;
    rad_rgb_t amb, out, *vrgb, *fb;
    rad_ff_t *ff;
    uint32_t *zb, e;
    rad_camera_t cam = {
        .eye = {0, 0, Q(3.9)}, .target = {0, 0, 0}, .up = {0, Q(1), 0}, .tan_half_fov = Q(1.0)};
    rad_vec3_t tri[3] = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
    unsigned char *vb, *fbb, *zbb, *ffb;
    (void)st;
    pools_make(&g, NS, NP, NE, NV, WORK);
    assert_int_equal(rad_init(&s, &g.p, &cfg), RAD_OK);
    add_cube(&s);
    assert_int_equal(rad_shoot(NULL, 1, 0), RAD_ERR_ARG);
    assert_int_equal(rad_shoot(&s, 0, 0), 0);
    assert_int_equal(rad_shoot(&s, 30, 0), 30);
    assert_int_equal(rad_add_polygon(&s, tri, 3, NULL, NULL), RAD_ERR_STATE);
    CHECK_INT_GT(rad_unshot_fraction(&s), 0, "unshot fraction (Q16.16) after 30 shots");
    CHECK_INT_LT(rad_unshot_fraction(&s), Q(1.0), "unshot fraction (Q16.16) after 30 shots");
    assert_int_equal(rad_unshot_fraction(NULL), 0);
    assert_int_equal(rad_ambient(NULL, &amb), RAD_ERR_ARG);
    assert_int_equal(rad_ambient(&s, NULL), RAD_ERR_ARG);
    assert_int_equal(rad_ambient(&s, &amb), RAD_OK);
    CHECK_INT_GT(amb.r, 0, "ambient term (red, Q16.16) of a lit grey cube");
    assert_int_equal(rad_element_radiosity(&s, s.n_elements, 0, &out), RAD_ERR_ARG);
    assert_int_equal(rad_element_radiosity(&s, 0, 0, NULL), RAD_ERR_ARG);
    for (e = 0; e < s.n_elements; e++) {
        rad_rgb_t a;
        assert_int_equal(rad_element_radiosity(&s, e, 0, &out), RAD_OK);
        assert_int_equal(rad_element_radiosity(&s, e, RAD_SHADE_AMBIENT, &a), RAD_OK);
        CHECK_INT_GE(a.r, out.r,
                     "element %u: red with the ambient term against without (it only adds)",
                     (unsigned)e);
    }
    vb = galloc(s.n_vertices * sizeof *vrgb);
    vrgb = (rad_rgb_t *)vb;
    assert_int_equal(rad_shade_vertices(&s, 0, vrgb, s.n_vertices - 1), RAD_ERR_ARG);
    assert_int_equal(rad_shade_vertices(&s, RAD_SHADE_AMBIENT, vrgb, s.n_vertices),
                     (int)s.n_vertices);
    gcheck(vb, s.n_vertices * sizeof *vrgb);
    fbb = galloc(40 * 30 * sizeof *fb);
    zbb = galloc(40 * 30 * sizeof *zb);
    fb = (rad_rgb_t *)fbb;
    zb = (uint32_t *)zbb;
    assert_int_equal(rad_render(&s, vrgb, &cam, fb, zb, 0, 30), RAD_ERR_ARG);
    assert_int_equal(rad_render(&s, vrgb, &cam, fb, zb, RAD_MAX_RASTER + 1, 30), RAD_ERR_ARG);
    assert_int_equal(rad_render(&s, NULL, &cam, fb, zb, 40, 30), RAD_ERR_ARG);
    {
        rad_camera_t c2 = cam;
        c2.target = c2.eye; /* no direction */
        assert_int_equal(rad_render(&s, vrgb, &c2, fb, zb, 40, 30), RAD_ERR_ARG);
        c2 = cam;
        c2.up = V(0, 0, 1); /* up along the view */
        assert_int_equal(rad_render(&s, vrgb, &c2, fb, zb, 40, 30), RAD_ERR_ARG);
        c2 = cam;
        c2.eye.x = Q(300); /* beyond 4 * 64 */
        assert_int_equal(rad_render(&s, vrgb, &c2, fb, zb, 40, 30), RAD_ERR_ARG);
        c2 = cam;
        c2.tan_half_fov = 0;
        assert_int_equal(rad_render(&s, vrgb, &c2, fb, zb, 40, 30), RAD_ERR_ARG);
    }
    CHECK_INT_GT(rad_render(&s, vrgb, &cam, fb, zb, 40, 30), 0,
                 "triangles drawn from inside the cube");
    gcheck(fbb, 40 * 30 * sizeof *fb);
    gcheck(zbb, 40 * 30 * sizeof *zb);
    ffb = galloc(s.n_elements * sizeof *ff);
    ff = (rad_ff_t *)ffb;
    assert_int_equal(rad_form_factors(&s, s.n_patches, ff), RAD_ERR_ARG);
    assert_int_equal(rad_form_factors(&s, 0, NULL), RAD_ERR_ARG);
    assert_int_equal(rad_form_factors(&s, 3, ff), (int)s.n_elements);
    gcheck(ffb, s.n_elements * sizeof *ff);
    assert_int_equal(rad_set_surface(&s, 6, &grey, NULL), RAD_ERR_ARG);
    assert_int_equal(rad_restart(NULL), RAD_ERR_ARG);
    pools_check(&g);
    free(vb);
    free(fbb);
    free(zbb);
    free(ffb);
    pools_free(&g);
}

static uint64_t checksum(const rad_scene_t *s)
{
    uint64_t x = 1469598103934665603ull;
    uint32_t e;
    for (e = 0; e < s->n_elements; e++) {
        const rad_rgb_t *c = &s->pools.elements[e].radiosity;
        x = (x ^ (uint32_t)c->r) * 1099511628211ull;
        x = (x ^ (uint32_t)c->g) * 1099511628211ull;
        x = (x ^ (uint32_t)c->b) * 1099511628211ull;
    }
    return x;
}

static void test_restart_relight(void **st)
{
    guarded_t a, b;
    rad_scene_t s, t;
    const rad_rgb_t red = {Q(0.7), Q(0.1), Q(0.1)}, blue = {Q(0), Q(0), Q(8)};
    (void)st;
    pools_make(&a, NS, NP, NE, NV, WORK);
    pools_make(&b, NS, NP, NE, NV, WORK);
    assert_int_equal(rad_init(&s, &a.p, &cfg), RAD_OK);
    assert_int_equal(rad_init(&t, &b.p, &cfg), RAD_OK);
    add_cube(&s);
    add_cube(&t);
    rad_shoot(&s, 50, 0);
    /* Change a wall's colour and the light's colour, then restart: the new solution is
     * bit for bit a fresh solve of the changed scene. */
    assert_int_equal(rad_set_surface(&s, 2, &red, NULL), RAD_OK);
    assert_int_equal(rad_set_surface(&s, 1, NULL, &blue), RAD_OK);
    assert_int_equal(rad_set_surface(&s, 1, &red, &(rad_rgb_t){0, 0, Q(5000)}), RAD_ERR_RANGE);
    assert_int_equal(rad_restart(&s), RAD_OK);
    assert_int_equal(s.stats.shots, 0);
    rad_set_surface(&t, 2, &red, NULL);
    rad_set_surface(&t, 1, NULL, &blue);
    rad_restart(&t);
    assert_int_equal(rad_shoot(&s, 60, 0), 60);
    assert_int_equal(rad_shoot(&t, 60, 0), 60);
    assert_int_equal(checksum(&s), checksum(&t));
    /* Blue light only: no red or green anywhere. */
    assert_int_equal(s.pools.elements[0].radiosity.r, 0);
    CHECK_INT_GT(s.pools.elements[0].radiosity.b, 0, "element 0's blue under the blue light");
    pools_check(&a);
    pools_free(&a);
    pools_free(&b);
}

static void test_saturation_counted(void **st)
{
    guarded_t g;
    rad_scene_t s;
    const rad_rgb_t white = {65535, 65535, 65535}, hot = {Q(4096), Q(4096), Q(4096)};
    (void)st;
    pools_make(&g, NS, NP, NE, NV, WORK);
    assert_int_equal(rad_init(&s, &g.p, &cfg), RAD_OK);
    /* A closed white cube with a face at the emission limit converges towards
     * 4096 / (1 - 65535/65536), far past the Q16.16 limit of 32768: clamped, counted. */
    add_cube_with(&s, &white, &hot);
    rad_shoot(&s, 2000, 0);
    CHECK_INT_GT(s.stats.saturations, 0, "saturations counted past the Q16.16 limit");
    assert_int_equal(s.pools.elements[0].radiosity.r, INT32_MAX);
    pools_check(&g);
    pools_free(&g);
}

/* After one shot the shooter holds nothing (plain) or owes what it expects back
 * (overshooting), and the unshot fraction counts debts by their magnitude. */
static void test_overshoot_debt(void **st)
{
    int k;
    (void)st;
    for (k = 0; k < 2; k++) {
        guarded_t g;
        rad_scene_t s;
        rad_config_t c = cfg;
        uint32_t shooter, p, e;
        double sum = 0;
        int ch;
        c.flags = k ? RAD_NO_OVERSHOOT : 0;
        pools_make(&g, NS, NP, NE, NV, WORK);
        assert_int_equal(rad_init(&s, &g.p, &c), RAD_OK);
        add_cube(&s);
        assert_int_equal(rad_shot_begin(&s, 0, &shooter), 1);
        assert_int_equal(rad_shoot(&s, 1, 0), 1);
        for (ch = 0; ch < 3; ch++) {
            rad_energy_t u = s.pools.patches[shooter].unshot[ch];
            if (k)
                CHECK_INT_EQ(u, 0, "the plain shooter's unshot power, channel %d", ch);
            else /* a closed grey cube: the ambient term is > 0 */
                CHECK_INT_LT(u, 0, "the overshooting shooter's unshot power (owed), channel %d",
                             ch);
        }
        for (p = 0; p < s.n_patches; p++)
            for (ch = 0; ch < 3; ch++) sum += fabs((double)s.pools.patches[p].unshot[ch]);
        CHECK_NEAR(sum / (double)s.emitted * 65536.0, rad_unshot_fraction(&s), 1.0,
                   "unshot fraction (Q16.16) against the sum of |unshot| over the emitted power");
        /* Whatever is owed, nothing is displayed below black. */
        for (e = 0; e < s.n_elements; e++) {
            rad_rgb_t b;
            assert_int_equal(rad_element_radiosity(&s, e, RAD_SHADE_AMBIENT, &b), RAD_OK);
            CHECK_INT_GE(b.r, 0, "element %u: displayed red", (unsigned)e);
            CHECK_INT_GE(b.g, 0, "element %u: displayed green", (unsigned)e);
            CHECK_INT_GE(b.b, 0, "element %u: displayed blue", (unsigned)e);
        }
        pools_check(&g);
        pools_free(&g);
    }
}

/* The core assumes nothing of the caller's buffers' contents: a work buffer and parts'
 * buffers full of 0xA5 (the lattice's row of id steps, depth and ids among them) give
 * the bits of zeroed ones, serially and in parts. */
static void test_dirty_buffers(void **st)
{
    enum { SHOTS = 20, PARTS = 3 };
    static rad_rgb_t want[NE];
    guarded_t g;
    rad_scene_t s;
    uint32_t e, n;
    int k, shot;
    (void)st;
    for (k = 0; k < 3; k++) {
        pools_make(&g, NS, NP, NE, NV, WORK);
        if (k == 1) memset(g.work, 0xA5, WORK);
        assert_int_equal(rad_init(&s, &g.p, &cfg), RAD_OK);
        add_cube(&s);
        if (k < 2) {
            assert_int_equal(rad_shoot(&s, SHOTS, 0), SHOTS);
        } else {
            size_t bytes = RAD_PART_BYTES(cfg.res);
            void *bufs[PARTS];
            unsigned part;
            for (part = 0; part < PARTS; part++) assert_non_null(bufs[part] = malloc(bytes));
            for (shot = 0; shot < SHOTS; shot++) {
                uint32_t p;
                assert_int_equal(rad_shot_begin(&s, 0, &p), 1);
                for (part = 0; part < PARTS; part++) {
                    memset(bufs[part], 0xA5, bytes);
                    CHECK_INT_GE(rad_shot_part(&s, p, part, PARTS, bufs[part], bytes), 0,
                                 "rad_shot_part %u of %d", part, PARTS);
                }
                assert_int_equal(rad_shot_end(&s, p, bufs, PARTS), 1);
            }
            for (part = 0; part < PARTS; part++) free(bufs[part]);
        }
        n = s.n_elements;
        /* a lattice on every face, not one element each */
        CHECK_INT_GT(n, 6, "elements of the cube");
        CHECK_INT_LE(n, NE, "elements of the cube");
        for (e = 0; e < n; e++) {
            const rad_rgb_t *b = &s.pools.elements[e].radiosity;
            if (k == 0)
                want[e] = *b;
            else {
                assert_int_equal(b->r, want[e].r);
                assert_int_equal(b->g, want[e].g);
                assert_int_equal(b->b, want[e].b);
            }
        }
        pools_check(&g);
        pools_free(&g);
    }
}

/* The public calls refused_calls makes, each on a scene that must be refused. */
#define CALLS 34

/* Every call taking a scene, on scene S: how many of them refused it with RAD_ERR_STATE
 * (printed one by one; rad_unshot_fraction, which returns a value, counts when 0). The
 * arguments are otherwise valid for a scene with at least one patch and element. */

static int refused_calls(rad_scene_t *s, const char *what)
{
    static rad_rgb_t rho[NE + NP], vrgb[NV], fb[4 * 4], groups0[NE], out[NE];
    static rad_ff_t ff[NE], matrix[RAD_GS_ENTRIES(4)];
    static uint32_t zb[4 * 4], start[NP + 1];
    static rad_index_t ids[4];
    static uint16_t ffs[4];
    static unsigned char gwork[RAD_GATHER_SH_BYTES(8)];
    static uint64_t part_mem[RAD_BATCH_BYTES(32, NE) / 8 + 1];
    rad_vec3_t tri[3] = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}, pt = V(0, 0, 0), up = V(0, 1, 0);
    rad_camera_t cam = {
        .eye = {0, 0, Q(3)}, .target = {0, 0, 0}, .up = {0, Q(1), 0}, .tan_half_fov = Q(1.0)};
    rad_rows_t rows = {start, ids, ffs, NP, 4, 0};
    const rad_rgb_t *gr[1] = {groups0};
    void *bufs[1] = {part_mem};
    rad_gather_t g, gs;
    rad_rgb_t c;
    static rad_light_t lights[1];
    const rad_light_t sun = {RAD_LIGHT_SUN,
                             0,
                             {0, 0, 0},
                             {0, -RAD_REAL(1), 0},
                             {RAD_REAL(1), RAD_REAL(1), RAD_REAL(1)},
                             0,
                             0,
                             0,
                             {0, 0, 0},
                             0};
    uint32_t patch = 0;
    int rc[CALLS], n = 0, k, refused = 0;
    assert_int_equal(rad_gather_init(&g, 8, 0, gwork, sizeof gwork), RAD_OK);
    rc[n++] = rad_add_polygon(s, tri, 3, &grey, NULL);
    rc[n++] = rad_join_polygon(s, tri, 3, &grey);
    rc[n++] = rad_set_surface(s, 0, &grey, NULL);
    rc[n++] = rad_use_element_reflectance(s, rho);
    rc[n++] = rad_set_element_reflectance(s, 0, &grey);
    rc[n++] = rad_restart(s);
    rc[n++] = rad_shoot(s, 1, 0);
    rc[n++] = rad_shot_begin(s, 0, &patch);
    rc[n++] = rad_shot_part(s, 0, 0, 1, part_mem, sizeof part_mem);
    rc[n++] = rad_shot_aim(s, 0, bufs, 1);
    rc[n++] = rad_shot_receive_part(s, 0, bufs, 1, 0);
    rc[n++] = rad_shot_end(s, 0, bufs, 1);
    rc[n++] = rad_batch_begin(s, 0, 1, &patch);
    rc[n++] = rad_batch_render(s, 0, 0, part_mem, sizeof part_mem);
    rc[n++] = rad_batch_aim(s, bufs, 1);
    rc[n++] = rad_batch_receive_part(s, bufs, 1, 0, 1);
    rc[n++] = rad_batch_end(s, bufs, 1);
    rc[n++] = rad_ambient(s, &c);
    rc[n++] = rad_element_radiosity(s, 0, 0, &c);
    rc[n++] = rad_shade_vertices(s, 0, vrgb, NV);
    rc[n++] = rad_shade_elements(s, 0, vrgb, NV);
    rc[n++] = rad_element_geometry(s, 0, NULL, NULL);
    rc[n++] = rad_use_lights(s, lights, 1);
    rc[n++] = rad_add_light(s, &sun);
    rc[n++] = rad_set_light(s, 0, &sun);
    rc[n++] = rad_render(s, vrgb, &cam, fb, zb, 4, 4);
    rc[n++] = rad_form_factors(s, 0, ff);
    rc[n++] = rad_rows_compute(s, &rows, 1);
    rc[n++] = rad_rows_shoot(s, &rows, 1, 0);
    rc[n++] = rad_rows_gauss_seidel(s, &rows, matrix, RAD_GS_ENTRIES(4), 1, 0);
    rc[n++] = rad_mix(s, gr, &grey, 1, out);
    rc[n++] = rad_gather(s, &g, &pt, &up, RAD_INDEX_NONE, 0, &c);
    assert_int_equal(rad_gather_init(&gs, 8, RAD_GATHER_SH, gwork, sizeof gwork), RAD_OK);
    rc[n++] = rad_gather_sh(s, &gs, &pt, RAD_INDEX_NONE, 0, vrgb);
    rc[n++] = rad_unshot_fraction(s) == 0 ? RAD_ERR_STATE : 1;
    for (k = 0; k < n; k++) {
        if (rc[k] != RAD_ERR_STATE) printf("%s: call %d returned %d\n", what, k, rc[k]);
        refused += rc[k] == RAD_ERR_STATE;
    }
    printf("%s: %d of %d calls refused with RAD_ERR_STATE\n", what, refused, n);
    return refused;
}

/* A scene rad_init never set up (memory of 0x00, 0xA5, 0xFF), one whose rad_init
 * failed (fresh, and a working scene initialised again with a bad setting), and a copy
 * of a working scene at another address: every call refuses each with RAD_ERR_STATE
 * and leaves the pools untouched (rad_add_polygon divided by zero on such a scene). */
static void test_scene_not_set_up(void **st)
{
    static const unsigned char fill[3] = {0x00, 0xA5, 0xFF};
    guarded_t g;
    rad_scene_t *s = malloc(sizeof *s), *copy = malloc(sizeof *copy);
    rad_config_t bad = cfg;
    int k;
    (void)st;
    assert_non_null(s);
    assert_non_null(copy);
    bad.res = 31;
    pools_make(&g, NS, NP, NE, NV, WORK);
    for (k = 0; k < 3; k++) {
        memset(s, fill[k], sizeof *s);
        s->pools = g.p; /* pools as a caller might have left them: never written */
        CHECK_INT_EQ(refused_calls(s, "never initialised"), CALLS,
                     "calls refusing a scene of bytes 0x%02X never initialised", fill[k]);
    }
    memset(s, 0xA5, sizeof *s);
    assert_int_equal(rad_init(s, &g.p, &bad), RAD_ERR_ARG);
    CHECK_INT_EQ(refused_calls(s, "init failed"), CALLS,
                 "calls refusing a scene whose rad_init failed");
    assert_int_equal(rad_init(s, &g.p, &cfg), RAD_OK);
    add_cube(s);
    assert_int_equal(rad_shoot(s, 5, 0), 5);
    memcpy(copy, s, sizeof *s);
    CHECK_INT_EQ(refused_calls(copy, "a copy"), CALLS, "calls refusing a copy of a working scene");
    assert_int_equal(rad_init(s, &g.p, &bad), RAD_ERR_ARG);
    CHECK_INT_EQ(refused_calls(s, "re-init failed"), CALLS,
                 "calls refusing a working scene after a failed rad_init");
    pools_check(&g);
    pools_free(&g);
    free(s);
    free(copy);
}

/* Stored rows that are not the scene's: an element id beyond its elements, offsets
 * falling or beyond max_entries. rad_rows_shoot and Gauss-Seidel refuse them
 * (RAD_ERR_ARG) before changing anything, rad_rows_compute refuses to go on from them;
 * today they read and wrote past the element pool. */
static void test_rows_refused(void **st)
{
    static rad_ff_t matrix[RAD_GS_ENTRIES(NP)];
    guarded_t g;
    rad_scene_t s;
    rad_rows_t rows;
    uint64_t before;
    uint32_t n, i, max = 16384;
    (void)st;
    pools_make(&g, NS, NP, NE, NV, WORK);
    assert_int_equal(rad_init(&s, &g.p, &cfg), RAD_OK);
    add_cube(&s);
    rows.start = malloc((NP + 1) * sizeof *rows.start);
    rows.ids = malloc(max * sizeof *rows.ids);
    rows.ffs = malloc(max * sizeof *rows.ffs);
    rows.max_rows = NP;
    rows.max_entries = max;
    rows.n_rows = 0;
    assert_non_null(rows.start);
    assert_non_null(rows.ids);
    assert_non_null(rows.ffs);
    assert_int_equal(rad_rows_compute(&s, &rows, 2), 2);
    /* resuming from a stored offset beyond max_entries: would write past ids */
    i = rows.start[2];
    rows.start[2] = max + 1;
    assert_int_equal(rad_rows_compute(&s, &rows, 1), RAD_ERR_ARG);
    rows.start[2] = i;
    assert_int_equal(rad_rows_compute(&s, &rows, NP), (int)s.n_patches - 2);
    n = rows.start[s.n_patches];
    printf("rows: %u patches, %u entries, %u elements\n", (unsigned)s.n_patches, (unsigned)n,
           (unsigned)s.n_elements);
    before = checksum(&s);
    for (i = 0; i < 4; i++) {
        uint32_t at = i == 0 ? 0 : i == 1 ? n - 1 : n / 2, keep = rows.ids[at];
        rows.ids[at] = (rad_index_t)(i == 3 ? RAD_INDEX_NONE : s.n_elements + i);
        CHECK_INT_EQ(rad_rows_shoot(&s, &rows, 10, 0), RAD_ERR_ARG,
                     "rad_rows_shoot with entry %u's id %u of %u elements", (unsigned)at,
                     (unsigned)rows.ids[at], (unsigned)s.n_elements);
        CHECK_INT_EQ(rad_rows_gauss_seidel(&s, &rows, matrix, RAD_GS_ENTRIES(NP), 10, 0),
                     RAD_ERR_ARG, "Gauss-Seidel with entry %u's id %u", (unsigned)at,
                     (unsigned)rows.ids[at]);
        rows.ids[at] = (rad_index_t)keep;
    }
    i = rows.start[3];
    rows.start[3] = rows.start[4] + 1; /* falling */
    CHECK_INT_EQ(rad_rows_shoot(&s, &rows, 10, 0), RAD_ERR_ARG, "rad_rows_shoot, offsets falling");
    rows.start[3] = i;
    rows.start[s.n_patches] = max + 1; /* beyond the entries */
    CHECK_INT_EQ(rad_rows_shoot(&s, &rows, 10, 0), RAD_ERR_ARG,
                 "rad_rows_shoot, last offset beyond max_entries");
    rows.start[s.n_patches] = n;
    assert_int_equal(checksum(&s), before); /* nothing shot */
    assert_int_equal(s.stats.shots, 0);
    assert_int_equal(rad_rows_shoot(&s, &rows, 10, 0), 10);
    pools_check(&g);
    pools_free(&g);
    free(rows.start);
    free(rows.ids);
    free(rows.ffs);
}

/* rad_shot_end (and rad_shot_aim, _receive_part, _part) out of order: RAD_ERR_STATE
 * as rad.h says, the scene unchanged. Today rad_shot_end shot with any of these. */
static void test_shot_end_misuse(void **st)
{
    enum { PARTS = 2 };
    guarded_t g;
    rad_scene_t s;
    size_t bytes = RAD_PART_BYTES(32);
    void *bufs[PARTS], *mixed[PARTS], *zero;
    uint32_t p, other, shots;
    uint64_t before;
    unsigned k;
    (void)st;
    pools_make(&g, NS, NP, NE, NV, WORK);
    assert_int_equal(rad_init(&s, &g.p, &cfg), RAD_OK);
    add_cube(&s);
    for (k = 0; k < PARTS; k++) assert_non_null(bufs[k] = calloc(1, bytes));
    assert_non_null(zero = calloc(1, bytes));
    /* no shot begun: zeroed buffers */
    assert_int_equal(rad_shot_end(&s, 0, bufs, PARTS), RAD_ERR_STATE);
    assert_int_equal(rad_shot_part(&s, 0, 0, PARTS, bufs[0], bytes), RAD_ERR_STATE);
    assert_int_equal(rad_shot_begin(&s, 0, &p), 1);
    other = p == 0 ? 1u : 0u;
    before = checksum(&s);
    shots = s.stats.shots;
    /* parts never rendered */
    assert_int_equal(rad_shot_end(&s, p, bufs, PARTS), RAD_ERR_STATE);
    assert_int_equal(rad_shot_aim(&s, p, bufs, PARTS), RAD_ERR_STATE);
    /* only part 0 rendered */
    CHECK_INT_GE(rad_shot_part(&s, p, 0, PARTS, bufs[0], bytes), 0, "part 0");
    assert_int_equal(rad_shot_end(&s, p, bufs, PARTS), RAD_ERR_STATE);
    /* another patch than the one begun: refused at render and at the end */
    assert_int_equal(rad_shot_part(&s, other, 1, PARTS, bufs[1], bytes), RAD_ERR_STATE);
    CHECK_INT_GE(rad_shot_part(&s, p, 1, PARTS, bufs[1], bytes), 0, "part 1");
    assert_int_equal(rad_shot_end(&s, other, bufs, PARTS), RAD_ERR_STATE);
    assert_int_equal(rad_shot_aim(&s, other, bufs, PARTS), RAD_ERR_STATE);
    /* the same part twice, parts swapped, or fewer parts than rendered */
    mixed[0] = bufs[0];
    mixed[1] = bufs[0];
    assert_int_equal(rad_shot_end(&s, p, mixed, PARTS), RAD_ERR_STATE);
    mixed[0] = bufs[1];
    mixed[1] = bufs[0];
    assert_int_equal(rad_shot_end(&s, p, mixed, PARTS), RAD_ERR_STATE);
    assert_int_equal(rad_shot_end(&s, p, bufs, 1), RAD_ERR_STATE);
    mixed[0] = bufs[0];
    mixed[1] = zero;
    assert_int_equal(rad_shot_end(&s, p, mixed, PARTS), RAD_ERR_STATE);
    assert_int_equal(checksum(&s), before);
    assert_int_equal(s.stats.shots, shots);
    /* the right call shoots, once */
    assert_int_equal(rad_shot_end(&s, p, bufs, PARTS), 1);
    assert_int_equal(s.stats.shots, shots + 1);
    assert_int_equal(rad_shot_end(&s, p, bufs, PARTS), RAD_ERR_STATE);
    /* buffers of an earlier shot of the same patch, after a new begin */
    before = checksum(&s);
    assert_int_equal(rad_shot_begin(&s, 0, &p), 1);
    for (k = 0; k < PARTS; k++)
        CHECK_INT_GE(rad_shot_part(&s, p, k, PARTS, bufs[k], bytes), 0, "part");
    assert_int_equal(rad_shot_begin(&s, 0, &p), 1); /* begun again: those parts are stale */
    assert_int_equal(rad_shot_end(&s, p, bufs, PARTS), RAD_ERR_STATE);
    /* and a serial shot in between voids the shot begun */
    for (k = 0; k < PARTS; k++)
        CHECK_INT_GE(rad_shot_part(&s, p, k, PARTS, bufs[k], bytes), 0, "part");
    assert_int_equal(rad_shoot(&s, 1, 0), 1);
    assert_int_equal(rad_shot_end(&s, p, bufs, PARTS), RAD_ERR_STATE);
    CHECK_INT_EQ(s.stats.shots, shots + 2, "shots: one in parts, one serial");
    assert_int_not_equal(checksum(&s), before);
    for (k = 0; k < PARTS; k++) free(bufs[k]);
    free(zero);
    pools_check(&g);
    pools_free(&g);
}

static void test_strerror(void **st)
{
    int k;
    (void)st;
    for (k = 0; k >= -7; k--) {
        int j;
        assert_non_null(rad_strerror(k));
        for (j = 0; j > k; j--) assert_string_not_equal(rad_strerror(k), rad_strerror(j));
    }
    assert_string_equal(rad_strerror(-99), "unknown error");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_init_errors),        cmocka_unit_test(test_add_errors),
        cmocka_unit_test(test_scaled_down_fits),   cmocka_unit_test(test_full_pools),
        cmocka_unit_test(test_calls_and_guards),   cmocka_unit_test(test_restart_relight),
        cmocka_unit_test(test_saturation_counted), cmocka_unit_test(test_overshoot_debt),
        cmocka_unit_test(test_dirty_buffers),      cmocka_unit_test(test_scene_not_set_up),
        cmocka_unit_test(test_rows_refused),       cmocka_unit_test(test_shot_end_misuse),
        cmocka_unit_test(test_strerror),
    };
    return cmocka_run_group_tests_name("api", tests, NULL, NULL);
}
