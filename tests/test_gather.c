/* SPDX-License-Identifier: MIT */
/* Gathering (lib/gather.c) in both builds: a closed box glowing uniformly gathers its
 * radiance exactly and its probe has band 0 alone; a point under a square emitter
 * against Lambert's point-to-polygon form factor; a gather at a patch's centre against
 * the patch's own hemi-cube row; the twin against the fixed build; threads; bad input.
 *
 * This file is compiled twice (Makefile: tests/float/test_gather.o): with RAD_FLOAT=1
 * it defines the *_float scene functions, without it the *_fixed ones and the tests.
 * The scene functions speak doubles only, so one test can drive both cores. */
#include <math.h>
#include <pthread.h>
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
#include "reference/reference.h"

#if RAD_FLOAT
#define TW(name) name##_float
#else
#define TW(name) name##_fixed
#endif

/* One gather's results: E per channel, the probe's nine coefficients per channel. */
typedef struct {
    double e[3], sh[9][3];
    double tilted[3];   /* scene_emitter: the gather on the normal TILT */
    double lo, hi;      /* the least and greatest shown element radiosity (red) */
    double row;         /* sum F B over a patch's hemi-cube row (patch_row) */
    unsigned long sats; /* saturations counted by the gatherer */
} gres;

#define DECLARE(B)                                                                           \
    int scene_box_##B(double emit, double rho, int res, const double *pt, const double *nrm, \
                      gres *r);                                                              \
    int scene_emitter_##B(const sc_poly *em, double emit, int res, gres *r);                 \
    int scene_patch_row_##B(int res, int patch, gres *r)
DECLARE(fixed);
DECLARE(float);
#undef DECLARE
#define PI     3.14159265358979323846
/* A tilted normal for scene_emitter's second gather. */
#define TILT_X 0.5
#define TILT_Y (-0.3)
#define TILT_Z 0.8

/* ---- the scenes, in this build of the core ---------------------------------------- */

#define NS       16
#define NP       512
#define NE       4096
#define NV       8192
#define GRES_MAX 128

typedef struct {
    rad_surface_t surf[NS];
    rad_patch_t patch[NP];
    rad_element_t elem[NE];
    rad_vec3_t vert[NV];
    unsigned char work[RAD_WORK_BYTES(GRES_MAX, RAD_PIXELS_ALL(GRES_MAX), NV)];
    unsigned char gwork[RAD_GATHER_SH_BYTES(GRES_MAX)];
    rad_scene_t s;
    rad_gather_t g, p;
} world_t;

static rad_vec3_t vec(double x, double y, double z)
{
    rad_vec3_t v;
    v.x = RAD_REAL(x);
    v.y = RAD_REAL(y);
    v.z = RAD_REAL(z);
    return v;
}

static world_t *world_new(int res, double patch, double element)
{
    world_t *w = calloc(1, sizeof *w);
    rad_pools_t p;
    rad_config_t c;
    if (!w) return NULL;
    p.surfaces = w->surf;
    p.max_surfaces = NS;
    p.patches = w->patch;
    p.max_patches = NP;
    p.elements = w->elem;
    p.max_elements = NE;
    p.vertices = w->vert;
    p.max_vertices = NV;
    p.work = w->work;
    p.work_bytes = sizeof w->work;
    memset(&c, 0, sizeof c);
    c.max_patch = RAD_REAL(patch);
    c.max_element = RAD_REAL(element);
    c.res = (uint16_t)res;
    if (rad_init(&w->s, &p, &c) != RAD_OK ||
        rad_gather_init(&w->g, (unsigned)res, 0, w->gwork, RAD_GATHER_BYTES(res)) != RAD_OK ||
        rad_gather_init(&w->p, (unsigned)res, RAD_GATHER_SH, w->gwork, sizeof w->gwork) != RAD_OK) {
        free(w);
        return NULL;
    }
    /* The two gatherers share one buffer: init again before each use. */
    return w;
}

/* The box -16..16 on every axis, walls facing in, reflectance RHO, all emitting EMIT
 * (or only the top, y = 16, when TOP_ONLY). */
static int add_box(world_t *w, double rho, double emit, int top_only)
{
    static const double f[6][4][3] = {
        {{-1, -1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, -1, -1}},
        {{-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}},
        {{-1, -1, -1}, {-1, 1, -1}, {-1, 1, 1}, {-1, -1, 1}},
        {{1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {1, 1, -1}},
        {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}},
        {{-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}},
    };
    rad_rgb_t r, e, none = {0, 0, 0};
    int i, k;
    r.r = r.g = r.b = RAD_REAL(rho);
    e.r = RAD_REAL(emit);
    e.g = RAD_REAL(emit / 2);
    e.b = RAD_REAL(emit / 4);
    for (i = 0; i < 6; i++) {
        rad_vec3_t v[4];
        for (k = 0; k < 4; k++) v[k] = vec(16 * f[i][k][0], 16 * f[i][k][1], 16 * f[i][k][2]);
        if (rad_add_polygon(&w->s, v, 4, &r, top_only && i != 1 ? &none : &e) != i) return -1;
    }
    return 0;
}

static void put(const rad_rgb_t *c, double *out)
{
    out[0] = RAD_TO_DOUBLE(c->r);
    out[1] = RAD_TO_DOUBLE(c->g);
    out[2] = RAD_TO_DOUBLE(c->b);
}

/* The probe at PT into R (through the sphere gatherer). */
static int probe(world_t *w, const rad_vec3_t *pt, uint32_t skip, int flags, gres *r)
{
    rad_rgb_t sh[9];
    int k;
    if (rad_gather_init(&w->p, w->g.res, RAD_GATHER_SH, w->gwork, sizeof w->gwork) != RAD_OK)
        return -1;
    if (rad_gather_sh(&w->s, &w->p, pt, skip, flags, sh) != RAD_OK) return -1;
    for (k = 0; k < 9; k++) put(&sh[k], r->sh[k]);
    r->sats += w->p.stats.saturations;
    return 0;
}

static int hemi(world_t *w, const rad_vec3_t *pt, const rad_vec3_t *n, uint32_t skip, int flags,
                gres *r)
{
    rad_rgb_t e;
    unsigned turn = w->g.turn;
    if (rad_gather_init(&w->g, w->g.res, 0, w->gwork, sizeof w->gwork) != RAD_OK) return -1;
    w->g.turn = turn;
    if (rad_gather(&w->s, &w->g, pt, n, skip, flags, &e) != RAD_OK) return -1;
    put(&e, r->e);
    r->sats += w->g.stats.saturations;
    return 0;
}

/* The closed box glowing EMIT, reflectance RHO: emission alone (one shot freezes the
 * geometry; with RHO = 0 it changes nothing) or, RHO > 0, solved to 10^-4 and
 * gathered with the ambient term. Gathers at PT, normal NRM, and the probe at PT. */
int TW(scene_box)(double emit, double rho, int res, const double *pt, const double *nrm, gres *r)
{
    world_t *w = world_new(res, 8, 4);
    rad_vec3_t p, n;
    int flags = rho > 0 ? RAD_SHADE_AMBIENT : 0;
    uint32_t e;
    int rc = -1;
    memset(r, 0, sizeof *r);
    if (!w) return -1;
    if (add_box(w, rho, emit, 0) < 0) goto out;
    if (rad_shoot(&w->s, rho > 0 ? 100000 : 1, RAD_REAL(1e-4)) < 0) goto out;
    r->lo = 1e30;
    r->hi = -1e30;
    for (e = 0; e < w->s.n_elements; e++) {
        rad_rgb_t b;
        rad_element_radiosity(&w->s, e, flags, &b);
        if (RAD_TO_DOUBLE(b.r) < r->lo) r->lo = RAD_TO_DOUBLE(b.r);
        if (RAD_TO_DOUBLE(b.r) > r->hi) r->hi = RAD_TO_DOUBLE(b.r);
    }
    p = vec(pt[0], pt[1], pt[2]);
    n = vec(nrm[0], nrm[1], nrm[2]);
    if (hemi(w, &p, &n, RAD_INDEX_NONE, flags, r) < 0 || probe(w, &p, RAD_INDEX_NONE, flags, r) < 0)
        goto out;
    rc = 0;
out:
    free(w);
    return rc;
}

/* EM (facing the origin) glowing EMIT over a black floor z = 0 in an otherwise empty
 * scene; the gather at the origin, normal +z, the floor skipped; the probe there. */
int TW(scene_emitter)(const sc_poly *em, double emit, int res, gres *r)
{
    world_t *w = world_new(res, 8, 2);
    rad_vec3_t v[4], o = vec(0, 0, 0), up = vec(0, 0, 1);
    rad_vec3_t fl[4];
    rad_rgb_t e, black = {0, 0, 0};
    double c[3];
    int k, rc = -1;
    memset(r, 0, sizeof *r);
    if (!w) return -1;
    /* counter-clockwise seen from the origin's side */
    for (k = 0; k < 3; k++)
        c[k] = (em->v[1][(k + 1) % 3] - em->v[0][(k + 1) % 3]) *
                   (em->v[2][(k + 2) % 3] - em->v[0][(k + 2) % 3]) -
               (em->v[1][(k + 2) % 3] - em->v[0][(k + 2) % 3]) *
                   (em->v[2][(k + 1) % 3] - em->v[0][(k + 1) % 3]);
    for (k = 0; k < em->n; k++) {
        int j =
            c[0] * em->v[0][0] + c[1] * em->v[0][1] + c[2] * em->v[0][2] < 0 ? k : em->n - 1 - k;
        v[k] = vec(em->v[j][0], em->v[j][1], em->v[j][2]);
    }
    fl[0] = vec(-40, -40, 0);
    fl[1] = vec(40, -40, 0);
    fl[2] = vec(40, 40, 0);
    fl[3] = vec(-40, 40, 0);
    e.r = RAD_REAL(emit);
    e.g = RAD_REAL(emit / 2);
    e.b = RAD_REAL(emit / 4);
    if (rad_add_polygon(&w->s, v, (unsigned)em->n, &black, &e) != 0) goto out;
    if (rad_add_polygon(&w->s, fl, 4, &black, NULL) != 1) goto out;
    if (rad_shoot(&w->s, 1, 0) != 1) goto out;
    if (hemi(w, &o, &up, 1, 0, r) < 0 || probe(w, &o, 1, 0, r) < 0) goto out;
    memcpy(r->tilted, r->e, sizeof r->e);
    up = vec(TILT_X, TILT_Y, TILT_Z);
    if (hemi(w, &o, &up, 1, 0, r) < 0) goto out;
    for (k = 0; k < 3; k++) {
        double t = r->e[k];
        r->e[k] = r->tilted[k];
        r->tilted[k] = t;
    }
    rc = 0;
out:
    free(w);
    return rc;
}

/* The box, its top alone emitting, reflectance 0.5, 40 shots; patch PATCH's row from
 * rad_form_factors weighting the shown radiosities (with the ambient term), against
 * the gather at the patch's centre on its surface's normal, its surface skipped, with
 * the patch's turn; both in the core's scale. In the fixed build the row's sum is
 * taken exactly, as the gather's. */
int TW(scene_patch_row)(int res, int patch, gres *r)
{
    const int flags = RAD_SHADE_AMBIENT | RAD_SHADE_SCALED;
    world_t *w = world_new(res, 8, 4);
    static rad_ff_t ff[NE];
    const rad_patch_t *pt;
    rad_vec3_t c;
    uint32_t e;
    int rc = -1;
#if RAD_FLOAT
    double sum = 0;
#else
    uint64_t sum = 0;
#endif
    memset(r, 0, sizeof *r);
    if (!w) return -1;
    if (add_box(w, 0.5, 8, 1) < 0 || rad_shoot(&w->s, 40, 0) != 40) goto out;
    if ((uint32_t)patch >= w->s.n_patches) goto out;
    if (rad_form_factors(&w->s, (uint32_t)patch, ff) < 0) goto out;
    for (e = 0; e < w->s.n_elements; e++) {
        rad_rgb_t b;
        rad_element_radiosity(&w->s, e, flags, &b);
#if RAD_FLOAT
        sum += (double)ff[e] * b.r;
#else
        sum += (uint64_t)ff[e] * (uint32_t)b.r;
#endif
    }
#if RAD_FLOAT
    r->row = sum;
#else
    r->row = (double)((sum + (1u << 29)) >> 30) / 65536.0;
#endif
    /* the patch's centre in the caller's units (exact: it sits on a coarse grid) */
    pt = &w->s.pools.patches[patch];
    c = vec(ldexp(RAD_TO_DOUBLE(pt->center.x), -w->s.length_shift),
            ldexp(RAD_TO_DOUBLE(pt->center.y), -w->s.length_shift),
            ldexp(RAD_TO_DOUBLE(pt->center.z), -w->s.length_shift));
    w->g.turn = (uint32_t)patch;
    if (hemi(w, &c, &w->s.pools.surfaces[pt->surface].normal, pt->surface, flags, r) == 0) rc = 0;
out:
    free(w);
    return rc;
}

#if !RAD_FLOAT
/* ---- the tests (fixed half) --------------------------------------------------------- */

static const double pts[4][6] = {
    {0, 0, 0, 0, 1, 0},
    {5, -3, 7, 1, 2, 3},
    {-11, 9, 2, -1, 0, 0.3},
    {13.5, -14, 13, -0.2, 0.9, -0.4},
};

/* A closed box glowing uniformly: every pixel sees an element of radiosity E, the table
 * sums to exactly 2^30 and the fixed sum is exact, so the gather is E to the bit (one
 * rounding of an exact multiple of 2^30). The twin: sums of at most res float terms,
 * then rows and faces: relative error below (2 res + 5) 2^-24 plus the table's float
 * entries, 2^-24: 8e-6 at res 64; bound 2e-5. */
static void test_box_uniform(void **st)
{
    double worst = 0;
    int i, k;
    (void)st;
    for (i = 0; i < 4; i++) {
        gres fx, fl;
        CHECK_INT_EQ(scene_box_fixed(4.25, 0, 64, pts[i], pts[i] + 3, &fx), 0, "fixed box %d", i);
        CHECK_INT_EQ(scene_box_float(4.25, 0, 64, pts[i], pts[i] + 3, &fl), 0, "float box %d", i);
        for (k = 0; k < 3; k++) {
            double want = 4.25 / (1 << k);
            worst = fmax(worst, fabs(fl.e[k] / want - 1));
            CHECK_EQ(fx.e[k], want, "fixed: point %d channel %d's gather in the glowing box", i, k);
            CHECK_NEAR(fl.e[k], want, 2e-5 * want, "float: point %d channel %d's gather", i, k);
        }
        CHECK_INT_EQ(fx.sats, 0, "fixed: saturations at point %d", i);
    }
    print_message("glowing box: fixed exact, float within %.1e\n", worst);
}

/* Solved with reflectance 0.5 and shown with the ambient term: the element radiosities
 * differ, but the weights are >= 0 and sum to 1, so the gather lies between the least
 * and the greatest of them (fixed: within the one rounding, 2^-16), near E / (1 - rho). */
static void test_box_solved_between(void **st)
{
    int i;
    (void)st;
    for (i = 0; i < 4; i++) {
        gres fx, fl;
        CHECK_INT_EQ(scene_box_fixed(2, 0.5, 32, pts[i], pts[i] + 3, &fx), 0, "fixed box %d", i);
        CHECK_INT_EQ(scene_box_float(2, 0.5, 32, pts[i], pts[i] + 3, &fl), 0, "float box %d", i);
        if (i == 0)
            print_message("point 0: fixed %.6f in [%.6f, %.6f], float %.6f in [%.6f, %.6f]\n",
                          fx.e[0], fx.lo, fx.hi, fl.e[0], fl.lo, fl.hi);
        CHECK_GE(fx.e[0], fx.lo - 1.0 / 65536, "fixed: point %d's gather against the least B", i);
        CHECK_LE(fx.e[0], fx.hi + 1.0 / 65536, "fixed: point %d's gather against the most B", i);
        CHECK_GE(fl.e[0], fl.lo * (1 - 1e-5), "float: point %d's gather against the least B", i);
        CHECK_LE(fl.e[0], fl.hi * (1 + 1e-5), "float: point %d's gather against the most B", i);
    }
}

/* The probe in the uniform box: SH[0] = E sqrt(4 pi) (the tables' sphere sums to
 * exactly 1.5 2^30 and the moments are exact until the constant: Q28, and two
 * roundings, within 2 LSB), bands 1 and 2 zero to the bit by the tables' symmetry.
 * The twin: float sums of 9 res^2 terms' worth per face, bound 3e-5 of SH[0]. */
static void test_probe_uniform(void **st)
{
    double lsb = 0, worst = 0;
    int i, k, c;
    (void)st;
    for (i = 0; i < 4; i++) {
        gres fx, fl;
        CHECK_INT_EQ(scene_box_fixed(4.25, 0, 64, pts[i], pts[i] + 3, &fx), 0, "fixed box %d", i);
        CHECK_INT_EQ(scene_box_float(4.25, 0, 64, pts[i], pts[i] + 3, &fl), 0, "float box %d", i);
        for (c = 0; c < 3; c++) {
            double want = 4.25 / (1 << c) * sqrt(4 * PI);
            lsb = fmax(lsb, fabs(fx.sh[0][c] - want) * 65536);
            worst = fmax(worst, fabs(fl.sh[0][c] / want - 1));
            CHECK_NEAR(fx.sh[0][c], want, 2.0 / 65536, "fixed: point %d channel %d's SH0", i, c);
            CHECK_NEAR(fl.sh[0][c], want, 3e-5 * want, "float: point %d channel %d's SH0", i, c);
            for (k = 1; k < 9; k++) {
                worst = fmax(worst, fabs(fl.sh[k][c]) / want);
                CHECK_EQ(fx.sh[k][c], 0, "fixed: point %d channel %d's SH%d", i, c, k);
                CHECK_NEAR(fl.sh[k][c], 0, 3e-5 * want, "float: point %d channel %d's SH%d", i, c,
                           k);
            }
        }
    }
    print_message("glowing box's probe: fixed SH0 within %.2f LSB, the rest 0; float within "
                  "%.1e of SH0\n",
                  lsb, worst);
}

/* Solid angle of polygon P seen from the origin (Van Oosterom & Strackee, by
 * triangles from its first vertex). */
static double solid_angle(const sc_poly *p)
{
    double om = 0;
    int t, k;
    for (t = 1; t + 1 < p->n; t++) {
        const double *a = p->v[0], *b = p->v[t], *c = p->v[t + 1];
        double la = 0, lb = 0, lc = 0, ab = 0, ac = 0, bc = 0, det;
        for (k = 0; k < 3; k++) {
            la += a[k] * a[k];
            lb += b[k] * b[k];
            lc += c[k] * c[k];
            ab += a[k] * b[k];
            ac += a[k] * c[k];
            bc += b[k] * c[k];
        }
        la = sqrt(la);
        lb = sqrt(lb);
        lc = sqrt(lc);
        det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
              a[2] * (b[0] * c[1] - b[1] * c[0]);
        om += 2 * atan2(fabs(det), la * lb * lc + ab * lc + ac * lb + bc * la);
    }
    return om;
}

/* The nine basis functions (rad.h's order) at the unit direction (x, y, z). */
static void sh_basis(double x, double y, double z, double *y9)
{
    double k1 = sqrt(3) / (2 * sqrt(PI)), k2 = sqrt(15) / (2 * sqrt(PI));
    y9[0] = 0.5 / sqrt(PI);
    y9[1] = k1 * y;
    y9[2] = k1 * z;
    y9[3] = k1 * x;
    y9[4] = k2 * x * y;
    y9[5] = k2 * y * z;
    y9[6] = sqrt(5) / (4 * sqrt(PI)) * (3 * z * z - 1);
    y9[7] = k2 * x * z;
    y9[8] = sqrt(15) / (4 * sqrt(PI)) * (x * x - y * y);
}

/* The integral of each basis function over polygon P seen from the origin, by the
 * midpoint rule on a 400 x 400 grid of its bilinear map (a triangle: its last vertex
 * doubled), each cell's solid angle |p . (p_u x p_v)| / |p|^3 du dv. */
static void sh_reference(const sc_poly *p, double *ref)
{
    const int n = 400;
    const double *v0 = p->v[0], *v1 = p->v[1], *v2 = p->v[2], *v3 = p->v[p->n == 4 ? 3 : 2];
    int i, j, k;
    for (k = 0; k < 9; k++) ref[k] = 0;
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) {
            double u = (i + 0.5) / n, v = (j + 0.5) / n, q[3], pu[3], pv[3], y9[9], r, dw;
            for (k = 0; k < 3; k++) {
                q[k] = (1 - u) * (1 - v) * v0[k] + u * (1 - v) * v1[k] + u * v * v2[k] +
                       (1 - u) * v * v3[k];
                pu[k] = (1 - v) * (v1[k] - v0[k]) + v * (v2[k] - v3[k]);
                pv[k] = (1 - u) * (v3[k] - v0[k]) + u * (v2[k] - v1[k]);
            }
            r = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
            dw = fabs(q[0] * (pu[1] * pv[2] - pu[2] * pv[1]) +
                      q[1] * (pu[2] * pv[0] - pu[0] * pv[2]) +
                      q[2] * (pu[0] * pv[1] - pu[1] * pv[0])) /
                 (r * r * r) / ((double)n * n);
            sh_basis(q[0] / r, q[1] / r, q[2] / r, y9);
            for (k = 0; k < 9; k++) ref[k] += y9[k] * dw;
        }
}

/* Channel C of the irradiance over pi rebuilt from R's coefficients (rad.h) on the
 * unit normal along TILT. */
static double sh_irradiance(const gres *r, int c)
{
    double l = sqrt(TILT_X * TILT_X + TILT_Y * TILT_Y + TILT_Z * TILT_Z), y9[9];
    double a[9] = {1, 2.0 / 3, 2.0 / 3, 2.0 / 3, 0.25, 0.25, 0.25, 0.25, 0.25}, e = 0;
    int k;
    sh_basis(TILT_X / l, TILT_Y / l, TILT_Z / l, y9);
    for (k = 0; k < 9; k++) e += a[k] * r->sh[k][c] * y9[k];
    return e;
}

/* Emitters above the origin: centred, offset, tilted, smaller and farther (about 19
 * pixels across at res 64: a 2 x 2 one at height 12, 5 pixels, measured 1.6% low),
 * a triangle. */
static int emitter(int k, sc_poly *p)
{
    switch (k) {
    case 0: *p = ref_quad(-4, -4, 6, 4, -4, 6, 4, 4, 6, -4, 4, 6); return 1;
    case 1: *p = ref_quad(3, -2, 5, 9, -2, 5, 9, 4, 5, 3, 4, 5); return 1;
    case 2: *p = ref_quad(-3, -5, 4, 5, -5, 8, 5, 3, 8, -3, 3, 4); return 1;
    case 3: *p = ref_quad(-3, -3, 10, 3, -3, 10, 3, 3, 10, -3, 3, 10); return 1;
    case 4:
        memset(p, 0, sizeof *p);
        p->n = 3;
        p->v[0][0] = -6;
        p->v[0][1] = -2;
        p->v[0][2] = 3;
        p->v[1][0] = 4;
        p->v[1][1] = -4;
        p->v[1][2] = 7;
        p->v[2][0] = 1;
        p->v[2][1] = 6;
        p->v[2][2] = 5;
        return 1;
    default: return 0;
    }
}

/* A point under an emitter in a black open scene: the gather is the point-to-polygon
 * form factor (Lambert) times the emission, within 1% at res 64 (the brief's bound;
 * the hemi-cube's aliasing of the emitter's outline).
 * The probe: SH[0] / Y00 is the emission times the emitter's solid angle, SH[2] / Y1
 * (z) the emission times pi F, within 1% as well; SH[3] and SH[1] (x, y) the emission
 * times Y1 and Lambert's vector's x and y, and every coefficient the emission times
 * the integral of its basis function over the emitter (sh_reference), within 0.5% of
 * the largest coefficient (the outline's aliasing again; every coefficient reaches 10%
 * of the largest on some emitter, so a sign or order slip errs by 20% or more).
 * The irradiance rebuilt from the nine (rad.h's formula), on +z and on a tilted normal,
 * is within 6% of the gather: the truncation after band 2 of a sharp-edged light
 * (measured 5.4% at worst, the smaller emitter).
 * The twin renders float geometry, whose outline's pixels may differ at the edges:
 * within two pixels' weight of the fixed build (the largest, at a top face's centre,
 * 4 / (pi res^2) of the hemisphere's F, or (2 / res)^2 sr times |Y_k| <= 1.1 of a
 * probe's coefficient), plus 1e-5 of float sums; measured within 4e-6 (of the gather,
 * or of the largest coefficient), no pixel differing. */
static void test_under_emitter(void **st)
{
    const double y00 = 0.5 / sqrt(PI), y1 = sqrt(3) / (2 * sqrt(PI));
    const double y20 = sqrt(5) / (4 * sqrt(PI)), emit = 10;
    const double pix = 2 * 4 / (PI * 64 * 64), psr = 2 * (2.0 / 64) * (2.0 / 64);
    double w_ff = 0, w_sh = 0, w_l2 = 0, w_twin = 0;
    sc_poly em;
    int k, i;
    (void)st;
    for (k = 0; emitter(k, &em); k++) {
        gres fx, fl;
        double f = ref_point_ff(&em), om = solid_angle(&em), phi[3], ref[9], big = 0, esh;
        CHECK_INT_EQ(scene_emitter_fixed(&em, emit, 64, &fx), 0, "fixed emitter %d", k);
        CHECK_INT_EQ(scene_emitter_float(&em, emit, 64, &fl), 0, "float emitter %d", k);
        /* the hemisphere against Lambert */
        w_ff = fmax(w_ff, fabs(fx.e[0] / (f * emit) - 1));
        CHECK_LE(fabs(fx.e[0] / (f * emit) - 1), 0.01, "fixed: emitter %d's gather / (F E) - 1", k);
        CHECK_LE(fabs(fx.e[1] / (f * emit / 2) - 1), 0.01, "fixed: emitter %d's green", k);
        CHECK_LE(fabs(fl.e[0] / (f * emit) - 1), 0.01, "float: emitter %d's gather / (F E) - 1", k);
        /* the probe against the solid angle, Lambert's vector and the integrals */
        ref_point_vector(&em, phi);
        sh_reference(&em, ref);
        for (i = 0; i < 9; i++) big = fmax(big, fabs(ref[i]));
        CHECK_LE(fabs(fx.sh[0][0] / (y00 * emit * om) - 1), 0.01, "emitter %d's SH0 / (Y00 E om)",
                 k);
        CHECK_LE(fabs(fx.sh[2][0] / (y1 * emit * PI * f) - 1), 0.01,
                 "emitter %d's SH z / (Y1 E pi F)", k);
        CHECK_NEAR(fx.sh[3][0] / (y1 * emit), phi[0], 0.005 * big / y1,
                   "emitter %d's SH x / (Y1 E) against Lambert's vector", k);
        CHECK_NEAR(fx.sh[1][0] / (y1 * emit), phi[1], 0.005 * big / y1,
                   "emitter %d's SH y / (Y1 E) against Lambert's vector", k);
        for (i = 0; i < 9; i++) {
            w_sh = fmax(w_sh, fabs(fx.sh[i][0] / emit - ref[i]) / big);
            CHECK_NEAR(fx.sh[i][0] / emit, ref[i], 0.005 * big,
                       "emitter %d's SH%d / E against the integral of its basis", k, i);
        }
        /* the irradiance rebuilt from the probe (rad.h's formula) */
        esh = fx.sh[0][0] * y00 + 2.0 / 3 * fx.sh[2][0] * y1 + 0.25 * fx.sh[6][0] * 2 * y20;
        w_l2 = fmax(w_l2, fabs(esh / fx.e[0] - 1));
        CHECK_LE(fabs(esh / fx.e[0] - 1), 0.06, "emitter %d: L2 irradiance / gather - 1 on +z", k);
        esh = sh_irradiance(&fx, 0);
        w_l2 = fmax(w_l2, fabs(esh / fx.tilted[0] - 1));
        CHECK_LE(fabs(esh / fx.tilted[0] - 1), 0.06,
                 "emitter %d: L2 irradiance / gather - 1 on the tilted normal", k);
        /* the twin */
        w_twin = fmax(w_twin, fabs(fl.e[0] / fx.e[0] - 1));
        CHECK_NEAR(fl.e[0], fx.e[0], pix * emit + 1e-5 * fx.e[0], "emitter %d: float gather", k);
        for (i = 0; i < 9; i++) {
            w_twin = fmax(w_twin, fabs(fl.sh[i][0] - fx.sh[i][0]) / (big * emit));
            /* |Y_k| <= sqrt 15 / (2 sqrt pi) = 1.09 */
            CHECK_NEAR(fl.sh[i][0], fx.sh[i][0], psr * 1.1 * emit + 1e-5 * big * emit,
                       "emitter %d: float SH%d", k, i);
        }
    }
    print_message(
        "under emitters, res 64: gather / (F E) within %.2f%%, SH within %.2f%% of the "
        "largest coefficient, L2 irradiance within %.1f%%, float against fixed within %.1e\n",
        100 * w_ff, 100 * w_sh, 100 * w_l2, w_twin);
}

/* A gather at patch P's centre on its normal, its surface skipped, with turn P, is
 * P's own hemi-cube: the same rasterizer and lattice give the same item buffer, so in
 * the fixed build sum F B over the row (exact) equals the gather to the bit. The twin
 * sums in another order: within 1e-5. */
static void test_patch_row(void **st)
{
    int p;
    (void)st;
    for (p = 0; p < 96; p += 7) {
        gres fx, fl;
        CHECK_INT_EQ(scene_patch_row_fixed(32, p, &fx), 0, "fixed: patch %d's scene", p);
        CHECK_INT_EQ(scene_patch_row_float(32, p, &fl), 0, "float: patch %d's scene", p);
        CHECK_EQ(fx.e[0], fx.row, "fixed: gather at patch %d against sum F B over its row", p);
        CHECK_NEAR(fl.e[0], fl.row, 1e-5 * fl.row, "float: gather at patch %d against its row", p);
    }
}

/* Gathers only read the scene: threads with a gatherer each get the serial bits. */
typedef struct {
    const rad_scene_t *s;
    unsigned first;
    rad_rgb_t out[16];
    int rc;
} job_t;

static void *gather_job(void *arg)
{
    job_t *j = arg;
    unsigned char *buf = malloc(RAD_GATHER_BYTES(32));
    rad_gather_t g;
    unsigned k;
    j->rc = buf ? rad_gather_init(&g, 32, 0, buf, RAD_GATHER_BYTES(32)) : -1;
    for (k = 0; k < 16 && j->rc == 0; k++) {
        unsigned i = j->first + k;
        rad_vec3_t p = vec(-15 + 0.9 * i, -15.5 + 0.95 * i, 14 - 0.9 * i), n = vec(1, 0.5 * i, -2);
        g.turn = i;
        j->rc = rad_gather(j->s, &g, &p, &n, RAD_INDEX_NONE, RAD_SHADE_AMBIENT, &j->out[k]);
    }
    free(buf);
    return NULL;
}

static void test_threads(void **st)
{
    world_t *w = world_new(32, 8, 4);
    job_t serial[2], par[2];
    pthread_t t[2];
    int k, i;
    (void)st;
    assert_non_null(w);
    CHECK_INT_EQ(add_box(w, 0.5, 8, 1), 0, "the box");
    CHECK_INT_EQ(rad_shoot(&w->s, 40, 0), 40, "shots");
    for (k = 0; k < 2; k++) {
        serial[k].s = par[k].s = &w->s;
        serial[k].first = par[k].first = 16u * (unsigned)k;
        gather_job(&serial[k]);
        CHECK_INT_EQ(serial[k].rc, 0, "serial gathers %d", k);
        for (i = 0; i < 16; i++) CHECK_INT_GT(serial[k].out[i].r, 0, "gather %d, %d: lit", k, i);
    }
    for (k = 0; k < 2; k++)
        CHECK_INT_EQ(pthread_create(&t[k], NULL, gather_job, &par[k]), 0, "thread %d", k);
    for (k = 0; k < 2; k++) {
        CHECK_INT_EQ(pthread_join(t[k], NULL), 0, "thread %d", k);
        CHECK_INT_EQ(par[k].rc, 0, "thread %d's gathers", k);
        for (i = 0; i < 16; i++) {
            CHECK_INT_EQ(par[k].out[i].r, serial[k].out[i].r, "thread %d gather %d red", k, i);
            CHECK_INT_EQ(par[k].out[i].g, serial[k].out[i].g, "thread %d gather %d green", k, i);
            CHECK_INT_EQ(par[k].out[i].b, serial[k].out[i].b, "thread %d gather %d blue", k, i);
        }
    }
    free(w);
}

/* Saturation is counted: a box glowing 4096 with reflectance 0.9 saturates its
 * elements' radiosity (32767.99 at most); the gather, a weighted mean of them, stays in
 * range, but the probe's SH0 = B sqrt(4 pi) cannot: it is clamped, and counted. */
static void test_saturation(void **st)
{
    world_t *w = world_new(16, 8, 4);
    rad_vec3_t o = vec(1, 2, 3), n = vec(0, 0, 1);
    rad_rgb_t e, sh[9];
    (void)st;
    assert_non_null(w);
    CHECK_INT_EQ(add_box(w, 0.9, 4096, 0), 0, "the box");
    /* The solution (B = 4096 / 0.1) is beyond the radiosity range, so the first
     * saturations make the solve back off to plain shooting (lib/solve.c, back_off),
     * which needs thousands of shots to get there at reflectance 0.9. */
    CHECK_INT_GT(rad_shoot(&w->s, 20000, 0), 0, "shots");
    CHECK_INT_GT(w->s.stats.saturations, 0, "the solve's saturations");
    CHECK_INT_EQ(rad_gather_init(&w->g, 16, 0, w->gwork, sizeof w->gwork), RAD_OK, "init");
    CHECK_INT_EQ(rad_gather(&w->s, &w->g, &o, &n, RAD_INDEX_NONE, 0, &e), RAD_OK, "gather");
    CHECK_INT_EQ(w->g.stats.saturations, 0, "the gather's saturations");
    CHECK_INT_GT(e.r, RAD_REAL(30000), "the gather in the saturated box");
    CHECK_INT_EQ(rad_gather_init(&w->p, 16, RAD_GATHER_SH, w->gwork, sizeof w->gwork), RAD_OK,
                 "init");
    CHECK_INT_EQ(rad_gather_sh(&w->s, &w->p, &o, RAD_INDEX_NONE, 0, sh), RAD_OK, "probe");
    CHECK_INT_EQ(sh[0].r, INT32_MAX, "the probe's clamped SH0");
    CHECK_INT_GE(w->p.stats.saturations, 1, "the probe's saturations");
    free(w);
}

static int all_visible(void *ctx, uint32_t light, const rad_vec3_t *dir)
{
    (void)ctx, (void)light, (void)dir;
    return 1;
}

/* Bad input: a clear error, nothing written, no byte past the work buffer touched. */
static void test_errors(void **st)
{
    world_t *w = world_new(16, 8, 4);
    unsigned char *buf;
    size_t need = RAD_GATHER_BYTES(16), k;
    rad_gather_t g;
    rad_vec3_t o = vec(0, 0, 0), n = vec(0, 1, 0), zero = vec(0, 0, 0), far = vec(0, 64.5, 0);
    rad_vec3_t out_core = vec(0, 40, 0); /* inside +-64, outside it at the core's scale (x2) */
    rad_rgb_t out = {7, 7, 7}, sh[9];
    const uint32_t none = RAD_INDEX_NONE;
    (void)st;
    assert_non_null(w);
    buf = malloc(need + 64);
    assert_non_null(buf);
    memset(buf + need, 0xA5, 64);
    CHECK_INT_EQ(rad_gather_init(NULL, 16, 0, buf, need), RAD_ERR_ARG, "init: no gatherer");
    CHECK_INT_EQ(rad_gather_init(&g, 16, 0, NULL, need), RAD_ERR_ARG, "init: no buffer");
    CHECK_INT_EQ(rad_gather_init(&g, 15, 0, buf, need), RAD_ERR_ARG, "init: odd res");
    CHECK_INT_EQ(rad_gather_init(&g, 6, 0, buf, need), RAD_ERR_ARG, "init: res 6");
    CHECK_INT_EQ(rad_gather_init(&g, RAD_MAX_RES + 2, 0, buf, need), RAD_ERR_ARG, "init: res");
    CHECK_INT_EQ(rad_gather_init(&g, 16, 2, buf, need), RAD_ERR_ARG, "init: unknown flag");
    CHECK_INT_EQ(rad_gather_init(&g, 16, 0, buf, need - 17), RAD_ERR_WORK, "init: short buffer");
    CHECK_INT_EQ(rad_gather_init(&g, 16, RAD_GATHER_SH, buf, need), RAD_ERR_WORK,
                 "init: a sphere in a hemisphere's buffer");
    CHECK_INT_EQ(rad_gather_init(&g, 16, 0, buf, need), RAD_OK, "init");
    CHECK_INT_EQ(add_box(w, 0, 1, 0), 0, "the box");
    CHECK_INT_EQ(rad_gather(&w->s, &g, &o, &n, none, 0, &out), RAD_ERR_STATE, "before the freeze");
    CHECK_INT_EQ(rad_shoot(&w->s, 1, 0), 1, "the first shot");
    CHECK_INT_EQ(rad_gather(NULL, &g, &o, &n, none, 0, &out), RAD_ERR_ARG, "no scene");
    CHECK_INT_EQ(rad_gather(&w->s, NULL, &o, &n, none, 0, &out), RAD_ERR_ARG, "no gatherer");
    CHECK_INT_EQ(rad_gather(&w->s, &g, NULL, &n, none, 0, &out), RAD_ERR_ARG, "no point");
    CHECK_INT_EQ(rad_gather(&w->s, &g, &o, NULL, none, 0, &out), RAD_ERR_ARG, "no normal");
    CHECK_INT_EQ(rad_gather(&w->s, &g, &o, &n, none, 0, NULL), RAD_ERR_ARG, "no output");
    CHECK_INT_EQ(rad_gather(&w->s, &g, &o, &n, none, 16, &out), RAD_ERR_ARG, "unknown flag");
    CHECK_INT_EQ(rad_gather(&w->s, &g, &o, &n, none, RAD_SHADE_SKIES, &out), RAD_ERR_ARG,
                 "skies left out without the soft light's flag");
    CHECK_INT_EQ(rad_gather_sh(&w->s, &g, &o, none, RAD_SHADE_SKIES, sh), RAD_ERR_ARG,
                 "a probe without the skies (not offered)");
    CHECK_INT_EQ(rad_gather_sh(&w->s, &g, &o, none, RAD_SHADE_SOFT, sh), RAD_ERR_ARG,
                 "a probe's soft light (not offered)");
    CHECK_INT_EQ(rad_direct(NULL, &o, &n, 0, all_visible, NULL, &out), RAD_ERR_ARG,
                 "direct: no scene");
    CHECK_INT_EQ(rad_direct(&w->s, &o, &n, 0, NULL, NULL, &out), RAD_ERR_ARG,
                 "direct: no visibility");
    CHECK_INT_EQ(rad_direct(&w->s, &o, &n, RAD_SHADE_SOFT, all_visible, NULL, &out), RAD_ERR_ARG,
                 "direct: unknown flag");
    CHECK_INT_EQ(rad_direct(&w->s, &o, &zero, 0, all_visible, NULL, &out), RAD_ERR_ARG,
                 "direct: zero normal");
    CHECK_INT_EQ(rad_direct(&w->s, &far, &n, 0, all_visible, NULL, &out), RAD_ERR_RANGE,
                 "direct: point at 64.5");
    CHECK_INT_EQ(rad_gather(&w->s, &g, &o, &zero, none, 0, &out), RAD_ERR_ARG, "zero normal");
    CHECK_INT_EQ(rad_gather(&w->s, &g, &far, &n, none, 0, &out), RAD_ERR_RANGE, "point at 64.5");
    CHECK_INT_EQ(rad_gather(&w->s, &g, &out_core, &n, none, 0, &out), RAD_ERR_RANGE,
                 "point at 40, 80 at the core's scale");
    CHECK_INT_EQ(rad_gather(&w->s, &g, &o, &far, none, 0, &out), RAD_ERR_RANGE, "normal of 64.5");
    CHECK_INT_EQ(rad_gather_sh(&w->s, &g, &o, none, 0, sh), RAD_ERR_ARG, "a probe, hemisphere");
    CHECK_THAT(out.r == 7 && out.g == 7 && out.b == 7, "out written by a failed gather: %d %d %d",
               (int)out.r, (int)out.g, (int)out.b);
    /* a long normal is only a direction; a skipped surface past the last skips none */
    n = vec(0, 63, 0);
    CHECK_INT_EQ(rad_gather(&w->s, &g, &o, &n, 77, 0, &out), RAD_OK, "gather");
    CHECK_INT_EQ(out.r, RAD_REAL(1), "gather in the box glowing 1, nothing skipped");
    /* without lights the soft gather is the whole one, and the direct light 0 */
    CHECK_INT_EQ(rad_gather(&w->s, &g, &o, &n, 77, RAD_SHADE_SOFT, &out), RAD_OK, "soft gather");
    CHECK_INT_EQ(out.r, RAD_REAL(1), "soft gather in the box glowing 1");
    CHECK_INT_EQ(rad_direct(&w->s, &o, &n, 0, all_visible, NULL, &out), RAD_OK, "direct");
    CHECK_INT_EQ(out.r, 0, "direct light without lights");
    for (k = 0; k < 64; k++) CHECK_INT_EQ(buf[need + k], 0xA5, "guard byte %d", (int)k);
    free(buf);
    free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_uniform),   cmocka_unit_test(test_box_solved_between),
        cmocka_unit_test(test_probe_uniform), cmocka_unit_test(test_under_emitter),
        cmocka_unit_test(test_patch_row),     cmocka_unit_test(test_threads),
        cmocka_unit_test(test_saturation),    cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
#endif
