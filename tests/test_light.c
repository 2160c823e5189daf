/* SPDX-License-Identifier: MIT */
/* Lights (lib/light.c) in both builds, against closed forms: a plane under the sun
 * receives E cos t; a box's shadow on the ground has the area of its projection; a
 * point light gives each element I times its solid angle (I cos t / r^2 over a small
 * element); a spot gives nothing outside its cone and the point light's light inside;
 * faces turned away from a light receive nothing and occlude it, without shadowing a
 * lit face they meet or lie on; the twin against the fixed
 * build; bad input.
 *
 * Bounds on pixel coverage (both lights): a convex outline covers the pixels whose
 * centres it holds, so in each row of pixels it crosses the count differs from the
 * outline's length at the row's centre by less than 1, and the rows' lengths sum to
 * the area but for the two end rows, each off by at most half its length: |n - A| <
 * H + W + 2 pixels, W and H its extents across and along the raster (rows or
 * columns alike). W + H is half the integral of |n_x| + |n_y| around the outline, at
 * most P / sqrt 2 for perimeter P, whichever way the raster is turned. Vertices are
 * placed to 1/16 pixel: the outline moves by at most sqrt 2 / 32 pixel, the area by
 * that times P. In units, with pixels of side p: |error| <= p P / sqrt 2 + 2 p^2 +
 * P p sqrt 2 / 32. A sun's pixel side is 2 h / R, h at most half the diameter of the
 * scene's projection; a point light's face pixel is 2 / R on the face plane at
 * distance 1, of solid angle at most (2 / R)^2 c^3 (c the cosine to the face's axis),
 * and the midpoint rule's error on c^3 is below 1 / R^2 of it. The fixed point's
 * roundings (power, area, radiosity in Q16.16) add 1e-4.
 *
 * This file is compiled twice (Makefile: tests/float/test_light.o): with RAD_FLOAT=1 it
 * defines the *_float scene function, without it the *_fixed one and the tests. */
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
#include "host/scene.h"
#include "reference/reference.h"
#include "rad/rad.h"

#if RAD_FLOAT
#define TW(name) name##_float
#else
#define TW(name) name##_fixed
#endif

#define PI 3.14159265358979323846

/* A scene in doubles: polygons (reflectance RHO, no emission) and lights. */
typedef struct {
    double v[4][3];
    int n;
} tpoly;
/* A light; a sky (RAD_LIGHT_SKY) keeps its horizon's radiance in pos and its count of
 * directions in radius, its up in dir and its zenith's radiance in i. */
typedef struct {
    int type, res;
    double pos[3], dir[3], i[3], cos_outer, cos_inner, radius;
} tlight;
typedef struct {
    int res;            /* the scene's hemi-cube res */
    double max_element; /* and patch: 4 times that */
    double rho;
    const tpoly *polys;
    int npolys;
    const tlight *lights;
    int nlights;
    int shots;     /* 0: the lights' shots alone */
    int band_rows; /* rad_config_t.band_rows */
    double tol;    /* the solve's tolerance (0: shots alone decide) */
} tscene;

/* Per element: radiosity (caller units), area, corners (caller units), its polygon. */
typedef struct {
    int rc, n;
    double b[4096][3], area[4096], corner[4096][4][3];
    int ncorner[4096], poly[4096];
    double unshot_before, unshot_after;
    unsigned long saturations;
} tres;

int scene_light_fixed(const tscene *sc, tres *r);
int scene_light_float(const tscene *sc, tres *r);
/* Stored rows (scene_rows's MODE) */
#define ROWS_SOLVE 0 /* the scene solved through stored rows */
#define ROWS_RELIT 1 /* solved with every light at half its intensity, relit (rad_set_light) */
#define ROWS_MIX   2 /* each light solved alone (the others dark), mixed (rad_mix) */
#define ROWS_GS    3 /* rad_rows_gauss_seidel (to the tolerance, at most SHOTS sweeps) */
int scene_rows_fixed(const tscene *sc, int mode, tres *r);
int scene_rows_float(const tscene *sc, int mode, tres *r);

/* ---- the scene, in this build of the core --------------------------------------- */

#define NS   16
#define NP   1024
#define NE   4096
#define NV   8192
#define WRES 256

typedef struct {
    rad_surface_t surf[NS];
    rad_patch_t patch[NP];
    rad_element_t elem[NE];
    rad_vec3_t vert[NV];
    rad_light_t lights[4];
    unsigned char work[RAD_WORK_BYTES(WRES, RAD_PIXELS_ALL(WRES), NV)];
    rad_scene_t s;
} world_t;

static rad_vec3_t vec(const double *p)
{
    rad_vec3_t v;
    v.x = RAD_REAL(p[0]);
    v.y = RAD_REAL(p[1]);
    v.z = RAD_REAL(p[2]);
    return v;
}

/* W's pools and a work buffer at WRES under configuration C, and with LIGHTS its
 * lights' array of 4. */
static int world_init(world_t *w, const rad_config_t *c, int lights)
{
    rad_pools_t p = {.surfaces = w->surf,
                     .max_surfaces = NS,
                     .patches = w->patch,
                     .max_patches = NP,
                     .elements = w->elem,
                     .max_elements = NE,
                     .vertices = w->vert,
                     .max_vertices = NV,
                     .work = w->work,
                     .work_bytes = sizeof w->work};
    int rc = rad_init(&w->s, &p, c);
    return rc == RAD_OK && lights ? rad_use_lights(&w->s, w->lights, 4) : rc;
}

/* Light L of the test's scene as the core's, its intensity times K. */
static rad_light_t core_light(const tlight *t, double k)
{
    rad_light_t l;
    memset(&l, 0, sizeof l);
    l.type = (uint16_t)t->type;
    l.res = (uint16_t)t->res;
    l.position = vec(t->pos);
    l.direction = vec(t->dir);
    l.intensity.r = RAD_REAL(k * t->i[0]);
    l.intensity.g = RAD_REAL(k * t->i[1]);
    l.intensity.b = RAD_REAL(k * t->i[2]);
    l.cos_outer = RAD_REAL(t->cos_outer);
    l.cos_inner = RAD_REAL(t->cos_inner);
    l.radius = RAD_REAL(t->radius);
    if (t->type == RAD_LIGHT_SKY) { /* tlight's pos: the horizon's radiance; radius: dirs */
        memset(&l.position, 0, sizeof l.position);
        l.horizon.r = RAD_REAL(k * t->pos[0]);
        l.horizon.g = RAD_REAL(k * t->pos[1]);
        l.horizon.b = RAD_REAL(k * t->pos[2]);
        l.radius = 0;
        l.dirs = (uint32_t)t->radius;
    }
    return l;
}

/* W's scene from SC, every light's intensity times K. */
static int world_scene(world_t *w, const tscene *sc, double k)
{
    rad_config_t c;
    rad_rgb_t rho;
    int i, j, rc;
    memset(&c, 0, sizeof c);
    c.max_element = RAD_REAL(sc->max_element);
    c.max_patch = RAD_REAL(4 * sc->max_element);
    c.res = (uint16_t)sc->res;
    c.band_rows = (uint16_t)sc->band_rows;
    rc = world_init(w, &c, 1);
    rho.r = rho.g = rho.b = RAD_REAL(sc->rho);
    for (i = 0; i < sc->npolys && rc >= 0; i++) {
        rad_vec3_t v[4];
        for (j = 0; j < sc->polys[i].n; j++) v[j] = vec(sc->polys[i].v[j]);
        rc = rad_add_polygon(&w->s, v, (unsigned)sc->polys[i].n, &rho, NULL);
    }
    for (i = 0; i < sc->nlights && rc >= 0; i++) {
        rad_light_t l = core_light(&sc->lights[i], k);
        rc = rad_add_light(&w->s, &l);
    }
    return rc;
}

/* W's solution into R (radiosities in the caller's units). */
static void world_read(world_t *w, tres *r)
{
    double ls = ldexp(1.0, -w->s.length_shift);
    int i, k;
    r->n = (int)w->s.n_elements;
    for (i = 0; i < r->n; i++) {
        const rad_element_t *el = &w->elem[i];
        rad_rgb_t b;
        rad_element_radiosity(&w->s, (uint32_t)i, 0, &b);
        r->b[i][0] = RAD_TO_DOUBLE(b.r);
        r->b[i][1] = RAD_TO_DOUBLE(b.g);
        r->b[i][2] = RAD_TO_DOUBLE(b.b);
        r->area[i] = RAD_TO_DOUBLE(el->area) * ls * ls;
        r->poly[i] = (int)el->surface;
        r->ncorner[i] = el->v[3] == RAD_INDEX_NONE ? 3 : 4;
        for (k = 0; k < r->ncorner[i]; k++) {
            const rad_vec3_t *q = &w->vert[el->v[k]];
            r->corner[i][k][0] = RAD_TO_DOUBLE(q->x) * ls;
            r->corner[i][k][1] = RAD_TO_DOUBLE(q->y) * ls;
            r->corner[i][k][2] = RAD_TO_DOUBLE(q->z) * ls;
        }
    }
    r->saturations = w->s.stats.saturations;
}

static uint32_t max_shots(const tscene *sc)
{
    return (uint32_t)(sc->shots ? sc->shots : sc->nlights);
}

int TW(scene_light)(const tscene *sc, tres *r)
{
    world_t *w = calloc(1, sizeof *w);
    int rc;
    if (!w) return -100;
    memset(r, 0, sizeof *r);
    rc = world_scene(w, sc, 1);
    if (rc < 0) {
        free(w);
        return rc;
    }
    r->unshot_before = RAD_TO_DOUBLE(rad_unshot_fraction(&w->s));
    rc = rad_shoot(&w->s, max_shots(sc), RAD_REAL(sc->tol));
    r->rc = rc;
    r->unshot_after = RAD_TO_DOUBLE(rad_unshot_fraction(&w->s));
    world_read(w, r);
    free(w);
    return rc;
}

/* SC solved through stored rows as MODE says (ROWS_*): returns the last solve's
 * shots, or the first error. */
int TW(scene_rows)(const tscene *sc, int mode, tres *r)
{
    world_t *w = calloc(1, sizeof *w);
    rad_rows_t rows;
    rad_rgb_t *groups[4] = {0}, *mix = 0, ones[4];
    const rad_rgb_t *cg[4];
    int rc, g, i;
    memset(&rows, 0, sizeof rows);
    memset(r, 0, sizeof *r);
    if (!w) return -100;
    rc = world_scene(w, sc, mode == ROWS_RELIT ? 0.5 : 1);
    if (rc >= 0) {
        rows.max_rows = w->s.n_patches;
        rows.max_entries = w->s.n_patches * w->s.n_elements;
        rows.start = calloc(rows.max_rows + 1u, sizeof *rows.start);
        rows.ids = calloc(rows.max_entries, sizeof *rows.ids);
        rows.ffs = calloc(rows.max_entries, sizeof *rows.ffs);
        rc = rows.start && rows.ids && rows.ffs ? rad_rows_compute(&w->s, &rows, rows.max_rows)
                                                : -100;
    }
    if (rc >= 0 && mode == ROWS_RELIT) {
        rc = rad_rows_shoot(&w->s, &rows, max_shots(sc), RAD_REAL(sc->tol));
        for (i = 0; i < sc->nlights && rc >= 0; i++) {
            rad_light_t l = core_light(&sc->lights[i], 1);
            rc = rad_set_light(&w->s, (uint32_t)i, &l);
        }
        if (rc >= 0) rc = rad_restart(&w->s);
    }
    if (rc >= 0 && mode == ROWS_MIX) {
        for (g = 0; g < sc->nlights && rc >= 0; g++) {
            groups[g] = calloc(w->s.n_elements, sizeof *groups[g]);
            cg[g] = groups[g];
            ones[g].r = ones[g].g = ones[g].b = RAD_REAL(1);
            for (i = 0; i < sc->nlights && rc >= 0; i++) {
                rad_light_t l = core_light(&sc->lights[i], i == g ? 1 : 0);
                rc = rad_set_light(&w->s, (uint32_t)i, &l);
            }
            if (rc >= 0) rc = rad_restart(&w->s);
            if (rc >= 0) rc = rad_rows_shoot(&w->s, &rows, max_shots(sc), RAD_REAL(sc->tol));
            for (i = 0; rc >= 0 && i < (int)w->s.n_elements; i++)
                rad_element_radiosity(&w->s, (uint32_t)i, 0, &groups[g][i]);
        }
        mix = calloc(w->s.n_elements, sizeof *mix);
        if (rc >= 0) rc = rad_mix(&w->s, cg, ones, (uint32_t)sc->nlights, mix);
    } else if (rc >= 0 && mode == ROWS_GS) {
        size_t n = RAD_GS_ENTRIES(w->s.n_patches);
        rad_ff_t *m = calloc(n, sizeof *m);
        rc = m ? rad_rows_gauss_seidel(&w->s, &rows, m, n, max_shots(sc), RAD_REAL(sc->tol)) : -100;
        free(m);
    } else if (rc >= 0) {
        rc = rad_rows_shoot(&w->s, &rows, max_shots(sc), RAD_REAL(sc->tol));
    }
    r->rc = rc;
    world_read(w, r);
    for (i = 0; mix && i < r->n; i++) {
        r->b[i][0] = RAD_TO_DOUBLE(mix[i].r);
        r->b[i][1] = RAD_TO_DOUBLE(mix[i].g);
        r->b[i][2] = RAD_TO_DOUBLE(mix[i].b);
    }
    for (g = 0; g < 4; g++) free(groups[g]);
    free(mix);
    free(rows.start);
    free(rows.ids);
    free(rows.ffs);
    free(w);
    return rc;
}

#if !RAD_FLOAT
/* ---- the tests (fixed build's half) ---------------------------------------------- */

static tres res_fixed, res_float;

/* A square of side 2 S in y = Y centred on (CX, CZ), facing up (or down). */
static tpoly ground(double cx, double y, double cz, double s, int up)
{
    tpoly q = {{{cx - s, y, cz - s}, {cx - s, y, cz + s}, {cx + s, y, cz + s}, {cx + s, y, cz - s}},
               4};
    if (!up) {
        double t[3];
        memcpy(t, q.v[1], sizeof t);
        memcpy(q.v[1], q.v[3], sizeof t);
        memcpy(q.v[3], t, sizeof t);
    }
    return q;
}

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The element's received irradiance from its radiosity (channel 0). */
static double irradiance(const tres *r, int e, double rho)
{
    return r->b[e][0] / rho;
}

/* The coverage bound above, in units^2, for an outline of perimeter P at pixel side PX. */
static double coverage(double p, double px)
{
    return px * p / sqrt(2.0) + 2 * px * px + p * px * sqrt(2.0) / 32;
}

/* The sun's largest pixel side: the scene's projection across DIR (unit) has a
 * diameter at most that of the corners' projections; the window is at most that wide. */
static double sun_pixel(const tpoly *polys, int n, const double *dir, int res)
{
    double d = 0;
    int i, j, a, b;
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++)
            for (a = 0; a < polys[i].n; a++)
                for (b = 0; b < polys[j].n; b++) {
                    double v[3], t, l;
                    int k;
                    for (k = 0; k < 3; k++) v[k] = polys[i].v[a][k] - polys[j].v[b][k];
                    t = dot3(v, dir);
                    for (k = 0; k < 3; k++) v[k] -= t * dir[k];
                    l = sqrt(dot3(v, v));
                    if (l > d) d = l;
                }
    return d / res;
}

/* A plane of 32 x 32 under a sun at angle T from its normal receives E cos t in all,
 * and each element its E cos t, within the coverage bounds. */
static void test_sun_plane(void **state)
{
    static const double angles[] = {0.0, 30.0, 45.0, 60.0, 75.0};
    const double e0 = 100.0, rho = 0.5;
    unsigned a;
    (void)state;
    for (a = 0; a < sizeof angles / sizeof angles[0]; a++) {
        double t = angles[a] * PI / 180, total = 0, want, px, worst = 0;
        tpoly pl = ground(0, 0, 0, 16, 1);
        tlight sun = {RAD_LIGHT_SUN, 1024, {0, 0, 0}, {sin(t), -cos(t), 0}, {e0, e0, e0}, 0, 0, 0};
        tscene sc = {64, 1.0, rho, &pl, 1, &sun, 1, 0, 0, 0};
        double dir[3] = {sin(t), -cos(t), 0}, pproj, aproj;
        int e;
        CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "the sun's shot at %g degrees",
                     angles[a]);
        px = sun_pixel(&pl, 1, dir, 1024);
        /* the plane's projection: 32 cos t by 32 */
        aproj = 32 * 32 * cos(t);
        pproj = 2 * (32 + 32 * cos(t));
        for (e = 0; e < res_fixed.n; e++) {
            double ee = irradiance(&res_fixed, e, rho), pe, ae = res_fixed.area[e] * cos(t), bound;
            total += ee * res_fixed.area[e];
            /* an element of side 1: projected 1 by cos t */
            pe = 2 * (1 + cos(t));
            bound = coverage(pe, px) / ae + 1e-4;
            if (fabs(ee / (e0 * cos(t)) - 1) / bound > worst)
                worst = fabs(ee / (e0 * cos(t)) - 1) / bound;
            CHECK_NEAR(ee, e0 * cos(t), e0 * cos(t) * bound,
                       "element %d's irradiance under a sun at %g degrees", e, angles[a]);
        }
        want = e0 * aproj;
        print_message("sun at %g degrees: plane power %.6g, E cos t A %.6g (%+.4f%%, bound "
                      "%.4f%%); elements at "
                      "most %.2f of their bound\n",
                      angles[a], total, want, 100 * (total / want - 1),
                      100 * (coverage(pproj, px) / aproj + 1e-4), worst);
        CHECK_NEAR(total, want, want * (coverage(pproj, px) / aproj + 1e-4),
                   "the plane's power under a sun at %g degrees", angles[a]);
        /* the bound is within 0.5% up to 45 degrees at R = 1024 (0.503% at 60, 0.7% at 75) */
        if (angles[a] <= 45)
            CHECK_LE(coverage(pproj, px) / aproj + 1e-4, 0.005, "the plane's bound at %g degrees",
                     angles[a]);
    }
}

/* The box's outline on the ground along the sun's direction: the box [-4, 4] x [0, 8]
 * x [-4, 4] under a sun tilted by T about z towards +x has the shadow x in
 * [-4, 4 + 8 tan t], z in [-4, 4] (its own footprint included). */
static void test_box_shadow(void **state)
{
    const double e0 = 50.0, rho = 0.5, t = 30 * PI / 180, s = 4;
    tpoly p[6];
    double dir[3] = {sin(t), -cos(t), 0}, px, got = 0, lit, shadow, err;
    tlight sun = {RAD_LIGHT_SUN, 1024, {0, 0, 0}, {sin(t), -cos(t), 0}, {e0, e0, e0}, 0, 0, 0};
    tscene sc = {64, 1.0, rho, p, 6, &sun, 1, 0, 0, 0};
    int e, dark = 0;
    (void)state;
    p[0] = ground(0, 0, 0, 24, 1);
    p[1] = ground(0, 2 * s, 0, s, 1); /* the box's top */
    /* its sides, facing out */
    p[2] = (tpoly){{{s, 0, -s}, {s, 2 * s, -s}, {s, 2 * s, s}, {s, 0, s}}, 4};
    p[3] = (tpoly){{{-s, 0, -s}, {-s, 0, s}, {-s, 2 * s, s}, {-s, 2 * s, -s}}, 4};
    p[4] = (tpoly){{{-s, 0, s}, {s, 0, s}, {s, 2 * s, s}, {-s, 2 * s, s}}, 4};
    p[5] = (tpoly){{{-s, 0, -s}, {-s, 2 * s, -s}, {s, 2 * s, -s}, {s, 0, -s}}, 4};
    CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "the sun's shot over the box");
    px = sun_pixel(p, 6, dir, 1024);
    for (e = 0; e < res_fixed.n; e++) {
        double c[3] = {0, 0, 0};
        int k;
        if (res_fixed.poly[e] != 0) continue;
        got += irradiance(&res_fixed, e, rho) * res_fixed.area[e];
        for (k = 0; k < 4; k++) {
            c[0] += res_fixed.corner[e][k][0] / 4;
            c[2] += res_fixed.corner[e][k][2] / 4;
        }
        /* an element well inside the shadow (a pixel and a half from its edge) */
        if (c[0] > -s + 1.5 && c[0] < s + 8 * tan(t) - 1.5 && fabs(c[2]) < s - 1.5) {
            dark++;
            CHECK_LE(irradiance(&res_fixed, e, rho), 0, "ground element %d inside the shadow", e);
        }
    }
    CHECK_INT_GE(dark, 20, "ground elements inside the shadow");
    shadow = 2 * s * (2 * s + 2 * s * tan(t));
    lit = e0 * cos(t) * (48 * 48 - shadow);
    /* the ground's outline and the shadow's, projected (cos t across x) */
    err = coverage(2 * (48 + 48 * cos(t)), px) +
          coverage(2 * (2 * s + (2 * s + 2 * s * tan(t)) * cos(t)), px);
    print_message(
        "box shadow: ground power %.6g, E cos t (A - shadow %.4g) %.6g (%+.4f%%, bound %.4f%%)\n",
        got, shadow, lit, 100 * (got / lit - 1),
        100 * (err / (48 * 48 * cos(t) - shadow * cos(t)) + 1e-4));
    CHECK_NEAR(got, lit, e0 * err + lit * 1e-4, "the ground's power beside the box's shadow");
}

/* The solid angle of the triangle A, B, C seen from the origin (Van Oosterom &
 * Strackee 1983). */
static double tri_solid(const double *a, const double *b, const double *c)
{
    double la = sqrt(dot3(a, a)), lb = sqrt(dot3(b, b)), lc = sqrt(dot3(c, c));
    double bc[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2],
                    b[0] * c[1] - b[1] * c[0]};
    double num = dot3(a, bc),
           den = la * lb * lc + dot3(a, b) * lc + dot3(a, c) * lb + dot3(b, c) * la;
    return fabs(2 * atan2(num, den));
}

/* The solid angle of polygon C (N corners) from P, and its extent on the face plane of
 * axes (A, B, D) in face pixels at resolution R (width plus height), its largest c^3. */
static double poly_solid(const double (*c)[3], int n, const double *p, const double *fa,
                         const double *fb, const double *fd, int res, double *wh, double *c3max)
{
    double v[4][3], lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9}, om = 0;
    int k, j;
    *c3max = 0;
    for (k = 0; k < n; k++) {
        double d, x, y, cc;
        for (j = 0; j < 3; j++) v[k][j] = c[k][j] - p[j];
        d = dot3(v[k], fd);
        x = dot3(v[k], fa) / d;
        y = dot3(v[k], fb) / d;
        cc = pow(1 + x * x + y * y, -1.5);
        if (cc > *c3max) *c3max = cc;
        lo[0] = fmin(lo[0], x);
        hi[0] = fmax(hi[0], x);
        lo[1] = fmin(lo[1], y);
        hi[1] = fmax(hi[1], y);
    }
    for (k = 1; k + 1 < n; k++) om += tri_solid(v[0], v[k], v[k + 1]);
    *wh = (hi[0] - lo[0] + hi[1] - lo[1]) * res / 2;
    /* c^3 is largest at the face's centre: if the outline holds it, 1 */
    if (lo[0] < 0 && hi[0] > 0 && lo[1] < 0 && hi[1] > 0) *c3max = 1;
    return om;
}

/* The point light's face looking down: the cube's frame is the rotation of rows
 * (2, 3, 6) / 7, (3, -6, 2) / 7, (6, 2, -3) / 7 (light.c), and face 3 looks along its
 * second axis with the first across and the third up. */
static const double FA[3] = {2.0 / 7, 3.0 / 7, 6.0 / 7}, FB[3] = {6.0 / 7, 2.0 / 7, -3.0 / 7},
                    FD[3] = {3.0 / 7, -6.0 / 7, 2.0 / 7};

/* A point light at height 8 over a patch of ground inside its downward face: each
 * element gets I times its solid angle, I cos t / r^2 at a small element's centre. */
static void test_point_plane(void **state)
{
    const double i0 = 640.0, rho = 0.5, lp[3] = {0, 8, 0};
    const int r = 512;
    /* the face's axis meets the ground at (4, 0, 8 / 3) */
    tpoly pl = ground(4, 0, 8.0 / 3, 3, 1);
    tlight pt = {RAD_LIGHT_POINT, r, {0, 8, 0}, {0, 0, 0}, {i0, i0, i0}, 0, 0, 0};
    tscene sc = {64, 1.0, rho, &pl, 1, &pt, 1, 0, 0, 0};
    double worst = 0, worst_rel = 0, tot = 0, tot_want = 0, s2 = 0;
    int e;
    (void)state;
    CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "the point light's shot");
    for (e = 0; e < res_fixed.n; e++) {
        double wh, c3,
            om = poly_solid((const double(*)[3])res_fixed.corner[e], res_fixed.ncorner[e], lp, FA,
                            FB, FD, r, &wh, &c3);
        double want = i0 * om / res_fixed.area[e], got = irradiance(&res_fixed, e, rho);
        double dw = 4.0 / ((double)r * r) * c3,
               bound = ((wh + 2) * dw + om / ((double)r * r)) / om + 1e-4;
        double c[3] = {0, 0, 0}, rr, ct;
        int k, j;
        for (k = 0; k < 4; k++)
            for (j = 0; j < 3; j++) c[j] += (res_fixed.corner[e][k][j] - lp[j]) / 4;
        rr = dot3(c, c);
        ct = -c[1] / sqrt(rr);
        tot += got * res_fixed.area[e];
        tot_want += i0 * om;
        if (fabs(got / want - 1) / bound > worst) worst = fabs(got / want - 1) / bound;
        if (fabs(got / want - 1) > worst_rel) worst_rel = fabs(got / want - 1);
        s2 += (got / want - 1) * (got / want - 1);
        CHECK_NEAR(got, want, want * bound, "element %d: I x solid angle / area", e);
        /* a unit element at distance >= 8: I cos t / r^2 at its centre within 1% */
        CHECK_NEAR(want, i0 * ct / rr, i0 * ct / rr * 0.01, "element %d: I cos t / r^2", e);
    }
    print_message("point light: %d elements within %.3f%% (rms %.3f%%) of I w / A (at most %.2f of "
                  "their bounds); "
                  "plane power %+.4f%%\n",
                  res_fixed.n, 100 * worst_rel, 100 * sqrt(s2 / res_fixed.n), worst,
                  100 * (tot / tot_want - 1));
    {
        double wh, c3, om = poly_solid((const double(*)[3])pl.v, 4, lp, FA, FB, FD, r, &wh, &c3);
        double dw = 4.0 / ((double)r * r) * c3,
               bound = ((wh + 2) * dw + om / ((double)r * r)) / om + 1e-4;
        print_message("point light: the plane's solid angle %.6f, bound %.4f%%\n", om, 100 * bound);
        CHECK_NEAR(tot, tot_want, tot_want * bound,
                   "the plane's power against I times its solid angle");
    }
}

/* A spot pointing down with a cone of 30 degrees (inner 20): nothing beyond the cone,
 * the point light's light inside the inner cone. */
static void test_spot_cone(void **state)
{
    const double i0 = 200.0, rho = 0.5, co = cos(30 * PI / 180), ci = cos(20 * PI / 180);
    const double lp[3] = {0, 8, 0};
    tpoly pl = ground(0, 0, 0, 16, 1);
    tlight sp = {RAD_LIGHT_SPOT, 256, {0, 8, 0}, {0, -1, 0}, {i0, i0, i0}, co, ci, 0};
    tlight pt = {RAD_LIGHT_POINT, 256, {0, 8, 0}, {0, 0, 0}, {i0, i0, i0}, 0, 0, 0};
    tscene sc = {64, 1.0, rho, &pl, 1, &sp, 1, 0, 0, 0};
    double px = 2.0 / 256; /* a face pixel's angle, at most */
    int e, outside = 0, inside = 0;
    (void)state;
    CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "the spot's shot");
    sc.lights = &pt;
    CHECK_INT_EQ(scene_light_fixed(&sc, &res_float), 1, "the point light's shot"); /* (fixed too) */
    for (e = 0; e < res_fixed.n; e++) {
        double amin = 1e9, amax = 0;
        int k;
        for (k = 0; k < 4; k++) {
            double v[3] = {res_fixed.corner[e][k][0] - lp[0], res_fixed.corner[e][k][1] - lp[1],
                           res_fixed.corner[e][k][2] - lp[2]};
            double a = acos(-v[1] / sqrt(dot3(v, v)));
            amin = fmin(amin, a);
            amax = fmax(amax, a);
        }
        if (amin > acos(co) + px) {
            outside++;
            CHECK_LE(irradiance(&res_fixed, e, rho), 0, "element %d beyond the cone (%.2f degrees)",
                     e, amin * 180 / PI);
        } else if (amax < acos(ci) - px) {
            inside++;
            CHECK_NEAR(irradiance(&res_fixed, e, rho), irradiance(&res_float, e, rho),
                       irradiance(&res_float, e, rho) * 1e-4, "element %d inside the inner cone",
                       e);
        } else {
            CHECK_LE(irradiance(&res_fixed, e, rho), irradiance(&res_float, e, rho) * (1 + 1e-4),
                     "element %d in the falloff", e);
        }
    }
    print_message(
        "spot: %d elements beyond the cone dark, %d inside the inner cone as the point light\n",
        outside, inside);
    CHECK_INT_GE(outside, 500, "elements beyond the cone");
    CHECK_INT_GE(inside, 10, "elements inside the inner cone");
}

/* Faces turned away from a light receive nothing and occlude it.
 * A closed box whose faces all face in (floor, four walls, and a one-sided roof facing
 * down into it) under a sun straight down and at 30 and 60 degrees, a sky and a point
 * light and a spot above it: every face of it is turned away from the light or is lit
 * only through one that is. Back faces are drawn a quarter of a pixel's footprint
 * behind (light.c), so what lies that little behind a back face along the light, at
 * the box's edges, may be reached: at most a row of pixels along the box's 12 edges
 * (96 units). So: an element all of whose corners lie more than a footprint from
 * every edge receives exactly 0 (footprints: the sun's pixel at most the box's
 * diagonal 13.9 / 512; the point light's 2 r / (R c^2) at most 2 x 14.5 x 3 / 256 =
 * 0.34 units; elements of side 1 here, their inner corners 1 unit in); and the power
 * reaching the box in all is below that row: E p 96 for a sun of pixel side p, the
 * sum of the dome's suns at most 2 pi L of them, and for the point light and the spot
 * pixels of solid angle at most 4 / R^2 along 96 units at least r_min 4 units away,
 * each pixel at least 2 r_min / R across: I 4 / R^2 96 R / (2 r_min). Without the
 * roof the box gets more than that (the check that could fail the other way). */
static void test_back_faces(void **state)
{
    const double e0 = 80.0, rho = 0.5, s = 4, px_sun = sqrt(3 * 64.0 * 2) / 512;
    static const double sun_deg[3] = {0, 30, 60};
    tpoly p[6];
    tlight l[6];
    tscene sc = {64, 1.0, rho, p, 6, l, 1, 0, 0, 0};
    int e, k, inner;
    (void)state;
    p[0] = ground(0, 0, 0, s, 1);     /* the floor, facing up into the box */
    p[1] = ground(0, 2 * s, 0, s, 0); /* the roof, facing down into the box */
    p[2] = (tpoly){{{s, 0, -s}, {s, 0, s}, {s, 2 * s, s}, {s, 2 * s, -s}}, 4}; /* walls facing in */
    p[3] = (tpoly){{{-s, 0, -s}, {-s, 2 * s, -s}, {-s, 2 * s, s}, {-s, 0, s}}, 4};
    p[4] = (tpoly){{{-s, 0, s}, {-s, 2 * s, s}, {s, 2 * s, s}, {s, 0, s}}, 4};
    p[5] = (tpoly){{{-s, 0, -s}, {s, 0, -s}, {s, 2 * s, -s}, {-s, 2 * s, -s}}, 4};
    for (k = 0; k < 3; k++) {
        double t = sun_deg[k] * PI / 180;
        l[k] = (tlight){RAD_LIGHT_SUN, 512, {0, 0, 0}, {sin(t), -cos(t), 0.2 * sin(t)},
                        {e0, e0, e0},  0,   0,         0};
    }
    l[3] = (tlight){RAD_LIGHT_SKY, 512, {e0, e0, e0}, {0, 1, 0}, {e0, e0, e0}, 0, 0, 48};
    l[4] = (tlight){RAD_LIGHT_POINT, 256, {1, 12, -0.5}, {0, 0, 0}, {e0, e0, e0}, 0, 0, 0};
    l[5] = (tlight){RAD_LIGHT_SPOT, 256, {1, 12, -0.5}, {0, -1, 0}, {e0, e0, e0}, 0.5, 0.7, 0};
    for (k = 0; k < 6; k++) {
        double got = 0, open,
               bound = k < 3    ? e0 * px_sun * 96
                       : k == 3 ? 2 * PI * e0 * px_sun * 96
                                : e0 * 4.0 / (256.0 * 256.0) * 96 * 256 / 8;
        sc.lights = &l[k];
        sc.npolys = 6;
        CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "light %d's shot over the closed box",
                     k);
        for (e = inner = 0; e < res_fixed.n; e++) {
            int c, j, edge = 0;
            got += irradiance(&res_fixed, e, rho) * res_fixed.area[e];
            for (c = 0; c < 4; c++) { /* a corner on two of the box's planes lies on an edge */
                int planes = 0;
                for (j = 0; j < 3; j++)
                    planes += fabs(fabs(res_fixed.corner[e][c][j] - (j == 1 ? s : 0)) - s) < 1e-6;
                edge |= planes >= 2;
            }
            if (edge) continue;
            inner++;
            CHECK_LE(irradiance(&res_fixed, e, rho), 0,
                     "light %d: element %d of face %d inside the closed box", k, e,
                     res_fixed.poly[e]);
        }
        print_message("light %d over the closed box: %d inner elements dark; power inside %.4g (a "
                      "row of pixels "
                      "along the edges: %.4g)\n",
                      k, inner, got, bound);
        CHECK_INT_EQ(inner, 6 * 36, "elements more than a unit from the box's edges");
        CHECK_LE(got, bound, "light %d: the power reaching inside the closed box", k);
        /* the roof off: the floor is lit */
        p[1] = p[5];
        sc.npolys = 5;
        CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "light %d's shot into the open box", k);
        for (e = 0, open = 0; e < res_fixed.n; e++)
            open += irradiance(&res_fixed, e, rho) * res_fixed.area[e];
        print_message("light %d into the open box: power %.4g\n", k, open);
        CHECK_LE(bound, open, "light %d: the power reaching into the box with the roof off", k);
        p[1] = ground(0, 2 * s, 0, s, 0);
    }
}

/* A lit face is not shadowed by a back face lying on it: a panel of two faces back to
 * back (the up face first, then the down face, and the other way round) under suns at
 * 0, 30, 60 and 75 degrees and a point light gives its up face the very radiosities
 * of the up face alone (the same pixels: the down face's depth is the up face's,
 * within the 1/32 pixel of its vertices' placing times its slope, far less than the
 * footprint it is drawn behind), and the face turned away receives nothing. */
static void test_back_to_back(void **state)
{
    static double alone[4096];
    static const double deg[4] = {0, 30, 60, 75};
    const double e0 = 80.0, rho = 0.5;
    tpoly p[2];
    tlight l;
    tscene sc = {64, 1.0, rho, p, 1, &l, 1, 0, 0, 0};
    int k, order, e, n;
    (void)state;
    for (k = 0; k < 5; k++) {
        double t = k < 4 ? deg[k] * PI / 180 : 0;
        l = k < 4 ? (tlight){RAD_LIGHT_SUN, 512, {0, 0, 0}, {sin(t), -cos(t), 0.1},
                             {e0, e0, e0},  0,   0,         0}
                  : (tlight){RAD_LIGHT_POINT, 256, {1, 6, 0.5}, {0, 0, 0}, {e0, e0, e0}, 0, 0, 0};
        p[0] = ground(0, 0, 0, 8, 1);
        sc.npolys = 1;
        CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "light %d on the face alone", k);
        n = res_fixed.n;
        for (e = 0; e < n; e++) alone[e] = res_fixed.b[e][0];
        for (order = 0; order < 2; order++) {
            int up = order == 0 ? 0 : 1, seen = 0;
            p[up] = ground(0, 0, 0, 8, 1);
            p[1 - up] = ground(0, 0, 0, 8, 0);
            sc.npolys = 2;
            CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "light %d on the panel", k);
            for (e = 0; e < res_fixed.n; e++) {
                if (res_fixed.poly[e] != up) {
                    CHECK_LE(irradiance(&res_fixed, e, rho), 0,
                             "light %d: element %d of the face turned away", k, e);
                    continue;
                }
                CHECK_NEAR(res_fixed.b[e][0], alone[seen], 0,
                           "light %d (order %d): element %d of the lit face against the face alone",
                           k, order, seen);
                seen++;
            }
            CHECK_INT_EQ(seen, n, "light %d: the lit face's elements", k);
        }
    }
}

/* The twin against the fixed build on a sun and a spot, after bounces: the same pixels
 * up to rounding, so each element within 0.5% plus two of each light's pixels (where an
 * outline passes within rounding of a pixel centre, the pixel may change hands: a sun
 * pixel brings rho E p^2, a spot's rho I (2 / R)^2 at most), and the total within 5e-4:
 * the builds' sun windows differ by the fixed build's rounding of a tile's half width
 * (up to 5 LSB, 2e-5 of it at 4 tiles of 64 here), which moves the pixel grid and so
 * the pixels along every outline (measured 1.2e-4 of the total). */
static void test_twin(void **state)
{
    const double t = 40 * PI / 180, rho = 0.6;
    tpoly p[3];
    tlight l[2] = {
        {RAD_LIGHT_SUN, 256, {0, 0, 0}, {sin(t), -cos(t), 0.3}, {30, 20, 10}, 0, 0, 0.05},
        {RAD_LIGHT_SPOT, 128, {-3, 6, 2}, {0.2, -1, 0.1}, {90, 90, 60}, 0.8, 0.9, 0}};
    tscene sc = {64, 1.0, rho, p, 3, l, 2, 40, 0, 0};
    double sf = 0, sx = 0, worst = 0, px, dir[3];
    int e;
    (void)state;
    p[0] = ground(0, 0, 0, 12, 1);
    p[1] = ground(0, 3, 0, 2, 1);
    p[2] = (tpoly){{{-12, 0, -12}, {-12, 8, -12}, {12, 8, -12}, {12, 0, -12}}, 4};
    memcpy(dir, l[0].dir, sizeof dir);
    for (e = 0; e < 3; e++) dir[e] /= sqrt(dot3(l[0].dir, l[0].dir));
    px = sun_pixel(p, 3, dir, 256);
    CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 40, "the fixed build's shots");
    CHECK_INT_EQ(scene_light_float(&sc, &res_float), 40, "the twin's shots");
    CHECK_INT_EQ(res_fixed.n, res_float.n, "elements");
    for (e = 0; e < res_fixed.n; e++) {
        int c;
        for (c = 0; c < 3; c++) {
            double a = res_fixed.b[e][c], b = res_float.b[e][c];
            double pix = 2 * rho * (l[0].i[c] * px * px + l[1].i[c] * 4.0 / (128.0 * 128.0)) /
                         res_float.area[e];
            double allowed = 0.005 * b + pix;
            sx += a * res_fixed.area[e];
            sf += b * res_float.area[e];
            if (fabs(a - b) / allowed > worst) worst = fabs(a - b) / allowed;
            CHECK_NEAR(a, b, allowed, "element %d channel %d against the twin", e, c);
        }
    }
    print_message("twin: elements at most %.3f of their bound, total %+.6f%%\n", worst,
                  100 * (sx / sf - 1));
    CHECK_NEAR(sx, sf, sf * 5e-4, "the total power against the twin");
}

/* A sun of angular radius atan 1/4 straight down over a ground half under a roof at
 * height 8, the roof's edge along z at x = 0: its 16 directions (rad.h) shift the
 * shadow's edge by at most 8 x 1/4 x 0.97 = 1.95, in opposite pairs, so the ground
 * is dark for x < -1.95, fully lit for x > 1.95 (E times the directions' mean cosine
 * c), in between partly, and in all gets E c times its area less the roof's shadow,
 * 16 x 16 (the shifts cancel), within the coverage bound of its outline and the
 * shadow's edge, 1e-4 for the rounding of the directions (Q16 cosines). */
static void test_sun_radius(void **state)
{
    static const double disc[8][2] = {{16384, 0},      {-20925, 19169}, {3203, -36495},
                                      {26375, 34401},  {-48401, -8561}, {45849, -29166},
                                      {-15336, 57048}, {-29247, -56313}};
    const double e0 = 40, rho = 0.5, rad = 0.25;
    tpoly p[2];
    tlight sun = {RAD_LIGHT_SUN, 1024, {0, 0, 0}, {0, -1, 0}, {e0, e0, e0}, 0, 0, rad};
    tscene sc = {64, 1.0, rho, p, 2, &sun, 1, 0, 0, 0};
    /* the window: at most the diameter of the scene's projection (40 x 40, tilted by
     * up to 1/4 either way: 2 x 8 / 4 more) over R */
    const double px = sqrt(2.0) * (40 + 4) / 1024;
    double c = 0, got = 0, want, err, worst = 0;
    int e, k, dark = 0, lit = 0, part = 0;
    (void)state;
    p[0] = (tpoly){{{-16, 0, -8}, {-16, 0, 8}, {16, 0, 8}, {16, 0, -8}}, 4};
    p[1] = (tpoly){{{-24, 8, -20}, {-24, 8, 20}, {0, 8, 20}, {0, 8, -20}}, 4};
    for (k = 0; k < 8; k++)
        c += 2 /
             sqrt(1 + rad * rad * (disc[k][0] * disc[k][0] + disc[k][1] * disc[k][1]) / 65536.0 /
                          65536.0) /
             16;
    CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "the sun's shot");
    for (e = 0; e < res_fixed.n; e++) {
        double x0 = 1e9, x1 = -1e9, ee = irradiance(&res_fixed, e, rho);
        if (res_fixed.poly[e] != 0) continue;
        for (k = 0; k < 4; k++) {
            x0 = fmin(x0, res_fixed.corner[e][k][0]);
            x1 = fmax(x1, res_fixed.corner[e][k][0]);
        }
        got += ee * res_fixed.area[e];
        if (x1 < -1.95 - 0.1) { /* a tenth for the pixels */
            dark++;
            CHECK_LE(ee, 0, "ground element %d (x %.2f..%.2f) in the umbra", e, x0, x1);
        } else if (x0 > 1.95 + 0.1) {
            lit++;
            /* a unit element's coverage bound, in each of the 16 shots */
            worst = fmax(worst, fabs(ee / (e0 * c) - 1));
            CHECK_NEAR(ee, e0 * c, e0 * c * (coverage(4, px) + 1e-4),
                       "ground element %d (x %.2f..%.2f) in full sun", e, x0, x1);
        } else if (ee > 0.05 * e0 && ee < 0.95 * e0 * c) {
            part++;
        }
    }
    err = e0 * c * (coverage(2 * (32 + 16), px) + coverage(2 * (16 + 16), px));
    want = e0 * c * 16 * 16;
    print_message("sun of radius 1/4: %d elements dark, %d lit (within %.3f%%, bound %.2f%%), %d "
                  "in the penumbra; "
                  "ground power %.6g, E c 16 x 16 %.6g (%+.4f%%, bound %.4f%%)\n",
                  dark, lit, 100 * worst, 100 * (coverage(4, px) + 1e-4), part, got, want,
                  100 * (got / want - 1), 100 * (err / want + 1e-4));
    CHECK_INT_GE(dark, 150, "elements in the umbra");
    CHECK_INT_GE(lit, 150, "elements in full sun");
    CHECK_INT_GE(part, 32, "elements in the penumbra, partly lit");
    CHECK_NEAR(got, want, err + want * 1e-4, "the ground's power under a sun of radius 1/4");
}

/* A work buffer used in bands of rows gives the same bits (each pixel's element depends
 * on its own span alone): a sun at 4 res and a point light at res, in bands of 3 rows. */
static void test_bands(void **state)
{
    tpoly p[2];
    tlight l[2] = {{RAD_LIGHT_SUN, 0, {0, 0, 0}, {0.3, -1, 0.2}, {30, 20, 10}, 0, 0, 0},
                   {RAD_LIGHT_POINT, 0, {-3, 6, 2}, {0, 0, 0}, {90, 90, 60}, 0, 0, 0}};
    tscene sc = {32, 1.0, 0.5, p, 2, l, 2, 0, 0, 0};
    int e, c;
    (void)state;
    p[0] = ground(0, 0, 0, 12, 1);
    p[1] = ground(1, 3, 0, 2, 1);
    CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 2, "the lights' shots, all faces at once");
    sc.band_rows = 3;
    CHECK_INT_EQ(scene_light_fixed(&sc, &res_float), 2, "the lights' shots in bands of 3 rows");
    for (e = 0; e < res_fixed.n; e++)
        for (c = 0; c < 3; c++)
            CHECK_NEAR(res_float.b[e][c], res_fixed.b[e][c], 0, "element %d channel %d in bands", e,
                       c);
}

/* ---- the sky ---------------------------------------------------------------------- */

/* The sky's dome (lib/light.c) in doubles for up +y and a grey sky of zenith Z and
 * horizon H (the sums of the channels): its N = 3 m^2 directions of travel D (along
 * each cell's vector integral of L w dw) and each one's irradiance over the zenith's and
 * the horizon's radiance, WZ and WH. rad__cube_frame's tangents for up +y are
 * f0 = (-4, 0, -3) / 5, f1 = (-3, 0, 4) / 5. */
typedef struct {
    int n;
    double d[768][3], wz[768], wh[768];
} tdome;

static void dome(int dirs, double z, double h, tdome *t)
{
    const double f0[3] = {-0.8, 0, -0.6}, f1[3] = {-0.6, 0, 0.8};
    int m = 1, i, j, k;
    while (3 * (m + 1) * (m + 1) <= dirs) m++;
    t->n = 0;
    for (i = 0; i < m; i++) {
        const int n = 3 * (2 * i + 1);
        double r1 = (double)i / m, r2 = (double)(i + 1) / m, c1 = sqrt(1 - r1 * r1),
               c2 = sqrt(1 - r2 * r2);
        double au = (r2 * r2 - r1 * r1) / 2, ac = (c1 * c1 * c1 - c2 * c2 * c2) / 3;
        double bu = (asin(r2) - r2 * c2 - asin(r1) + r1 * c1) / 2,
               bc = (r2 * r2 * r2 - r1 * r1 * r1) / 3;
        double va = h * (au - ac) + z * ac, vb = (h * (bu - bc) + z * bc) * sin(PI / n) / (PI / n);
        double c = va / hypot(va, vb), sn = vb / hypot(va, vb);
        for (j = 0; j < n; j++, t->n++) {
            double ph = 2 * PI * (j + 0.5) / n;
            for (k = 0; k < 3; k++) t->d[t->n][k] = -(sn * (cos(ph) * f0[k] + sin(ph) * f1[k]));
            t->d[t->n][1] = -c;
            t->wz[t->n] = 2 * PI / n * ac / c;
            t->wh[t->n] = 2 * PI / n * (au - ac) / c;
        }
    }
}

/* The dome's irradiance on a plane of normal NR, unshadowed: sum of E_k max(0, -d . n). */
static double dome_on(const tdome *t, double z, double h, const double *nr)
{
    double e = 0;
    int k;
    for (k = 0; k < t->n; k++) e += (z * t->wz[k] + h * t->wh[k]) * fmax(0, -dot3(t->d[k], nr));
    return e;
}

/* The sky's 3-cell coverage bound over the dome: sum of E_k coverage(P, px) for an
 * outline whose projections' perimeters are at most P, at pixel side PX. */
static double dome_coverage(const tdome *t, double z, double h, double p, double px)
{
    double e = 0;
    int k;
    for (k = 0; k < t->n; k++) e += (z * t->wz[k] + h * t->wh[k]) * coverage(p, px);
    return e;
}

/* A uniform sky of L over an open plane of 32 x 32: pi L A in all, exactly by the dome's
 * weights (a plane facing up receives the integral of each cell's L c dw), within the
 * coverage bound of its outline in every shot (its projections' perimeters at most
 * 128, the window at most the plane's diagonal wide); the same for 3 and 192
 * directions. Each element inside receives pi L within its own bound. */
static void test_sky_open(void **state)
{
    static const int counts[] = {3, 48, 192};
    static tdome t;
    const double l0 = 10, rho = 0.5, up[3] = {0, 1, 0}, px = 32 * sqrt(2.0) / 1024;
    unsigned a;
    (void)state;
    for (a = 0; a < sizeof counts / sizeof counts[0]; a++) {
        tpoly pl = ground(0, 0, 0, 16, 1);
        tlight sky = {RAD_LIGHT_SKY, 1024, {l0, l0, l0}, {0, 1, 0}, {l0, l0, l0}, 0, 0, counts[a]};
        tscene sc = {64, 2.0, rho, &pl, 1, &sky, 1, 0, 0, 0};
        double total = 0, want = PI * l0 * 32 * 32, err, worst = 0;
        int e;
        dome(counts[a], l0, l0, &t);
        CHECK_NEAR(dome_on(&t, l0, l0, up), PI * l0, PI * l0 * 1e-12,
                   "the dome's weights over a plane facing up");
        CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "the sky's shot (%d directions)",
                     counts[a]);
        for (e = 0; e < res_fixed.n; e++) {
            double ee = irradiance(&res_fixed, e, rho);
            total += ee * res_fixed.area[e];
            /* an element of side 2: projections' perimeters at most 8 */
            worst = fmax(worst, fabs(ee / (PI * l0) - 1));
            CHECK_NEAR(
                ee, PI * l0, dome_coverage(&t, l0, l0, 8, px) / res_fixed.area[e] + PI * l0 * 1e-4,
                "element %d's irradiance under a uniform sky of %d directions", e, counts[a]);
        }
        err = dome_coverage(&t, l0, l0, 128, px) * 1 + want * 1e-4;
        print_message("sky of %d directions over an open plane: power %.6g, pi L A %.6g (%+.4f%%, "
                      "bound %.4f%%); "
                      "elements within %.3f%% of pi L (bound %.3f%%)\n",
                      t.n, total, want, 100 * (total / want - 1), 100 * err / want, 100 * worst,
                      100 * (dome_coverage(&t, l0, l0, 8, px) / 4 / (PI * l0) + 1e-4));
        CHECK_NEAR(total, want, err, "the open plane's power under a uniform sky of %d directions",
                   counts[a]);
    }
}

/* Small elements under the sun and the sky at the lights' default rasters (res 0): a
 * prism of 8 facets (radius 0.25: facets 0.19 wide, elements 0.19 x 1) on a floor of
 * 32 x 32 (elements 1 x 1), so the window is 45 wide and a facet's element 0.44 on a
 * side (sqrt of its area). lib/light.c gives the smallest elements (a facet's are 3%
 * of them) pixels of at most 1 / 16 of their side, each of a sky's N rasters sqrt N
 * times that. A facet's elements all see the same light (the floor lies below the
 * horizon, the prism is convex), so each element's difference from that, over it, is
 * the pixels' error alone: about p / a rms, measured 0.85..1.1 p / a on thin columns
 * (lib/light.c), so at most 1.5 / 16 rms here; measured 1.55% (sun) and 2.89% (sky).
 * The rasters of the earlier defaults (256 pixels across for the sun, 64 for each sky
 * direction) gave 11.7% and 32.8%. */
static void test_small_elements(void **state)
{
    const double e0 = 10, l0 = 10, rho = 0.5, r0 = 0.25, bound = 1.5 / 16;
    const double d[3] = {0.6, -0.7, 0.39};
    double dn[3], len = sqrt(dot3(d, d));
    tpoly p[9];
    int k, e;
    (void)state;
    for (k = 0; k < 3; k++) dn[k] = d[k] / len;
    p[0] = ground(0, 0, 0, 16, 1);
    for (k = 0; k < 8;
         k++) { /* facet k faces out: its corners counter-clockwise seen from outside */
        double a0 = 2 * PI * k / 8, a1 = 2 * PI * (k + 1) / 8;
        tpoly f = {{{r0 * cos(a0), 0, r0 * sin(a0)},
                    {r0 * cos(a0), 8, r0 * sin(a0)},
                    {r0 * cos(a1), 8, r0 * sin(a1)},
                    {r0 * cos(a1), 0, r0 * sin(a1)}},
                   4};
        p[1 + k] = f;
    }
    for (k = 0; k < 2; k++) {
        tlight sun = {RAD_LIGHT_SUN, 0, {0, 0, 0}, {d[0], d[1], d[2]}, {e0, e0, e0}, 0, 0, 0};
        tlight sky = {RAD_LIGHT_SKY, 0, {l0, l0, l0}, {0, 1, 0}, {l0, l0, l0}, 0, 0, 48};
        tscene sc = {64, 1.0, rho, p, 9, k ? &sky : &sun, 1, 0, 0, 0};
        double sum2 = 0, facet[9] = {0}, farea[9] = {0};
        int n = 0;
        CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "the %s's shot", k ? "sky" : "sun");
        for (e = 0; e < res_fixed.n; e++) { /* a facet's mean (the sky's want) */
            int f = res_fixed.poly[e];
            facet[f] += irradiance(&res_fixed, e, rho) * res_fixed.area[e];
            farea[f] += res_fixed.area[e];
        }
        for (e = 0; e < res_fixed.n; e++) {
            int f = res_fixed.poly[e];
            double want, a0, a1, c, err;
            if (f == 0) continue;
            a0 = 2 * PI * (f - 1) / 8;
            a1 = 2 * PI * f / 8;
            c = -(dn[0] * cos((a0 + a1) / 2) + dn[2] * sin((a0 + a1) / 2)); /* the facet's cos t */
            if (!k && c < 0.3) continue; /* lit well: E cos t over 0.3 E */
            want = k ? facet[f] / farea[f] : e0 * c;
            err = irradiance(&res_fixed, e, rho) / want - 1;
            sum2 += err * err;
            n++;
        }
        CHECK_INT_GE(n, 24, "facet elements lit by the %s", k ? "sky" : "sun");
        print_message("%s on a prism's %d facet elements (0.19 x 1) over a 32 x 32 floor: rms "
                      "%.2f%% (bound %.2f%%)\n",
                      k ? "sky of 48 directions" : "sun", n, 100 * sqrt(sum2 / n), 100 * bound);
        CHECK_LE(sqrt(sum2 / n), bound, "the %s's rms error on the facets' elements",
                 k ? "sky" : "sun");
    }
}

/* The box of the sky tests: a floor of 8 x 8 (y = 0, facing up; polygon 0) and walls of
 * height 4 facing both ways, open at the top, into P (9 polygons). */
static int sky_box(tpoly *p)
{
    static const double c[4][2] = {{-4, -4}, {-4, 4}, {4, 4}, {4, -4}};
    int k;
    p[0] = ground(0, 0, 0, 4, 1);
    for (k = 0; k < 4; k++) {
        const double *a = c[k], *b = c[(k + 1) % 4];
        p[1 + 2 * k] =
            (tpoly){{{a[0], 0, a[1]}, {b[0], 0, b[1]}, {b[0], 4, b[1]}, {a[0], 4, a[1]}}, 4};
        p[2 + 2 * k] =
            (tpoly){{{a[0], 0, a[1]}, {a[0], 4, a[1]}, {b[0], 4, b[1]}, {b[0], 0, b[1]}}, 4};
    }
    return 9;
}

/* The sky through the box's opening at floor point (X, Z): pi L F, F the form factor
 * from the point to the opening (ref_point_ff, the opening 4 above it). */
static double box_ff(double x, double z)
{
    sc_poly o;
    memset(&o, 0, sizeof o);
    o = (sc_poly){{{-4 - x, -4 - z, 4}, {4 - x, -4 - z, 4}, {4 - x, 4 - z, 4}, {-4 - x, 4 - z, 4}},
                  4,
                  {0},
                  {0},
                  0};
    return ref_point_ff(&o);
}

/* The floor's power from the dome's shots, each unshadowed where it passes the opening:
 * the opening shifted by 4 d_xz / |d_y| over the floor, of E_k c_k times that area. */
static double box_dome(const tdome *t, double z, double h)
{
    double e = 0;
    int k;
    for (k = 0; k < t->n; k++) {
        double sx = 4 * fabs(t->d[k][0] / t->d[k][1]), sz = 4 * fabs(t->d[k][2] / t->d[k][1]);
        e += (z * t->wz[k] + h * t->wh[k]) * -t->d[k][1] * fmax(0, 8 - sx) * fmax(0, 8 - sz);
    }
    return e;
}

/* The analytic floor power under a uniform sky of L: pi L times the integral of F over
 * the floor, by the midpoint rule on 128 x 128 (F is smooth: its error below 1e-5). */
static double box_exact(double l0)
{
    double e = 0;
    int i, j;
    for (i = 0; i < 128; i++)
        for (j = 0; j < 128; j++) e += box_ff(-4 + (i + 0.5) / 16, -4 + (j + 0.5) / 16) / 256;
    return PI * l0 * e;
}

/* A uniform sky over the box open at the top: the floor receives pi L times its form
 * factor to the opening. Against the dome's own geometry (each shot lights the opening's
 * shift) the core is within the coverage bound of the floor's outline and the walls'
 * shadow in every shot (perimeters at most 32 each, the window at most the box's
 * diagonal, 12, wide). The dome against the continuous sky (its quadrature) is measured
 * here for each count (-26%, -39%, -24%, -12.9%, -6.9%, -3.6%, -0.88%, -0.32%, -0.46% at
 * 3, 12, 27, 48, 75, 108, 192, 432, 768: each cell's light arrives along one direction,
 * and the opening, which cuts cells, passes only the steeper ones); at the default 192
 * the floor power is within 2% of the analytic (measured -0.88%) and each element within
 * 8% of its mean pi L F (measured 4.6%: where the walls' shadows cross an element, each
 * direction lights all of it or none). */
static void test_sky_box(void **state)
{
    static const int counts[] = {3, 12, 27, 48, 75, 108, 192, 432, 768};
    static tdome t;
    const double l0 = 10, rho = 0.5, px = 12.0 / 1024, exact = box_exact(l0);
    tpoly p[9];
    tlight sky = {RAD_LIGHT_SKY, 1024, {l0, l0, l0}, {0, 0, 0}, {l0, l0, l0}, 0, 0, 0};
    tscene sc = {64, 1.0, rho, p, sky_box(p), &sky, 1, 0, 0, 0};
    double got = 0, want, err, worst = 0;
    unsigned a;
    int e;
    (void)state;
    for (a = 0; a < sizeof counts / sizeof counts[0]; a++) {
        dome(counts[a], l0, l0, &t);
        print_message("sky through the box's opening, %3d directions: floor power %+.3f%% of pi L "
                      "integral F\n",
                      t.n, 100 * (box_dome(&t, l0, l0) / exact - 1));
    }
    dome(192, l0, l0, &t);
    CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1,
                 "the sky's shot (its default 192 directions)");
    for (e = 0; e < res_fixed.n; e++) {
        double x = 0, z = 0, f = 0;
        int i, j;
        if (res_fixed.poly[e] != 0) continue;
        got += irradiance(&res_fixed, e, rho) * res_fixed.area[e];
        for (i = 0; i < 4; i++) {
            x += res_fixed.corner[e][i][0] / 4;
            z += res_fixed.corner[e][i][2] / 4;
        }
        for (i = 0; i < 4; i++) /* the element's mean F, 4 x 4 midpoints of its side 1 */
            for (j = 0; j < 4; j++) f += box_ff(x - 0.375 + i / 4.0, z - 0.375 + j / 4.0) / 16;
        worst = fmax(worst, fabs(irradiance(&res_fixed, e, rho) / (PI * l0 * f) - 1));
        CHECK_NEAR(irradiance(&res_fixed, e, rho), PI * l0 * f, PI * l0 * f * 0.08,
                   "floor element %d at (%.1f, %.1f): pi L F", e, x, z);
    }
    want = box_dome(&t, l0, l0);
    err = dome_coverage(&t, l0, l0, 64, px) + want * 1e-4;
    print_message(
        "sky through the box's opening: floor power %.6g, the dome's %.6g (%+.4f%%, bound %.4f%%), "
        "pi L integral F %.6g (%+.3f%%); elements within %.2f%% of pi L F\n",
        got, want, 100 * (got / want - 1), 100 * err / want, exact, 100 * (got / exact - 1),
        100 * worst);
    CHECK_NEAR(got, want, err, "the floor's power against the dome's shots through the opening");
    CHECK_NEAR(got, exact, exact * 0.02,
               "the floor's power against pi L times its form factor to the opening");
}

/* The sky's law, L(t) = H + (Z - H) cos t, on ground open to the sky (16 x 16, facing up)
 * and a wall (16 wide, 8 high, facing +x) standing on its edge: the ground receives
 * pi H + 2 pi (Z - H) / 3 exactly (the dome's weights), the wall in the limit
 * (pi / 2 - 2 / 3) H + (2 / 3) Z (the integrals of cos_n and of
 * cos_n cos t over the quarter sphere in front of it and above the horizon: pi / 2 and
 * 2 / 3). So the wall gets half the ground's light under a uniform sky, 0.863 of it
 * under a horizon-only sky (Z = 0) and 0.318 under a zenith-only sky (H = 0). The wall
 * shadows the ground from the light travelling towards +x (a face turned away from a
 * light occludes it), so the ground is measured alone; the ground lies below the
 * wall's horizon, so the wall is measured beside it. The core
 * against the dome unshadowed: within the coverage bounds (projections' perimeters at
 * most 64 and 48, the window at most the scene's diagonal, 24, wide); the dome's wall
 * against the limit: exact but for the cells that the wall's plane cuts, measured
 * -0.14% (uniform), -0.085% (horizon), -0.22% (zenith) at 192 directions, allowed
 * 0.5%. */
static void test_sky_gradient(void **state)
{
    static const double zh[3][2] = {{10, 10}, {0, 10}, {10, 0}};
    static const char *const name[3] = {"uniform", "horizon-only", "zenith-only"};
    static tdome t;
    const double rho = 0.5, up[3] = {0, 1, 0}, nx[3] = {1, 0, 0},
                 px = sqrt(16 * 16 + 16 * 16 + 8 * 8.0) / 1024;
    double ratio[3];
    tpoly p[2];
    int a, e;
    (void)state;
    p[0] = ground(8, 0, 0, 8, 1);
    p[1] = (tpoly){{{0, 0, -8}, {0, 8, -8}, {0, 8, 8}, {0, 0, 8}}, 4};
    for (a = 0; a < 3; a++) {
        const double z = zh[a][0], h = zh[a][1];
        tlight sky = {RAD_LIGHT_SKY, 1024, {h, h, h}, {0, 1, 0}, {z, z, z}, 0, 0, 0};
        tscene sc = {64, 2.0, rho, p, 2, &sky, 1, 0, 0, 0};
        double g = 0, w = 0, wg = PI * h + 2 * PI * (z - h) / 3,
               ww = (PI / 2 - 2.0 / 3) * h + 2.0 / 3 * z;
        double dw, eg, ew;
        dome(192, z, h, &t);
        dw = dome_on(&t, z, h, nx);
        CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "the %s sky's shot on the wall",
                     name[a]);
        for (e = 0; e < res_fixed.n; e++)
            if (res_fixed.poly[e] == 1) w += irradiance(&res_fixed, e, rho) * res_fixed.area[e];
        sc.npolys = 1;
        CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 1, "the %s sky's shot on the ground",
                     name[a]);
        for (e = 0; e < res_fixed.n; e++) g += irradiance(&res_fixed, e, rho) * res_fixed.area[e];
        g /= 256;
        w /= 128;
        eg = dome_coverage(&t, z, h, 64, px) / 256 + wg * 1e-4;
        ew = dome_coverage(&t, z, h, 48, px) / 128 + dw * 1e-4;
        ratio[a] = w / g;
        print_message(
            "%s sky (Z %g, H %g): ground E %.5g (law %.5g, %+.4f%%, bound %.3f%%); wall E %.5g "
            "(dome "
            "%.5g, %+.4f%%, bound %.3f%%; law %.5g, dome %+.3f%%); wall / ground %.4f (law %.4f)\n",
            name[a], z, h, g, wg, 100 * (g / wg - 1), 100 * eg / wg, w, dw, 100 * (w / dw - 1),
            100 * ew / dw, ww, 100 * (dw / ww - 1), w / g, ww / wg);
        CHECK_NEAR(g, wg, eg, "the ground under a %s sky", name[a]);
        CHECK_NEAR(w, dw, ew, "the wall under a %s sky against the dome", name[a]);
        CHECK_NEAR(dw, ww, ww * 0.005, "the dome's wall under a %s sky against the limit", name[a]);
        CHECK_NEAR(dome_on(&t, z, h, up), wg, wg * 1e-12, "the dome's ground under a %s sky",
                   name[a]);
    }
    CHECK_LT(ratio[0] + 0.2, ratio[1],
             "the wall's share of the ground's light: uniform sky below horizon-only");
    CHECK_LT(ratio[2] + 0.1, ratio[0], "the wall's share: zenith-only below uniform");
}

/* The twin against the fixed build on a gradient sky over the box, after bounces, as
 * test_twin: each element within 0.5% plus two pixels of every direction's shot (a
 * pixel of side px brings rho E_k px^2), the total within 5e-4. */
static void test_sky_twin(void **state)
{
    static tdome t;
    const double rho = 0.6, px = 12.0 / 256, z[3] = {10, 6, 3}, h[3] = {4, 8, 12};
    tpoly p[9];
    tlight sky = {RAD_LIGHT_SKY, 256, {4, 8, 12}, {0, 2, 0}, {10, 6, 3}, 0, 0, 27};
    tscene sc = {64, 1.0, rho, p, sky_box(p), &sky, 1, 30, 0, 0};
    double sf = 0, sx = 0, worst = 0, pix[3] = {0, 0, 0};
    int e, c, k;
    (void)state;
    dome(27, 19, 24, &t); /* the channels' sums */
    for (c = 0; c < 3; c++)
        for (k = 0; k < t.n; k++) pix[c] += 2 * rho * (z[c] * t.wz[k] + h[c] * t.wh[k]) * px * px;
    CHECK_INT_EQ(scene_light_fixed(&sc, &res_fixed), 30, "the fixed build's shots");
    CHECK_INT_EQ(scene_light_float(&sc, &res_float), 30, "the twin's shots");
    CHECK_INT_EQ(res_fixed.n, res_float.n, "elements");
    for (e = 0; e < res_fixed.n; e++)
        for (c = 0; c < 3; c++) {
            double a = res_fixed.b[e][c], b = res_float.b[e][c],
                   allowed = 0.005 * b + pix[c] / res_float.area[e];
            sx += a * res_fixed.area[e];
            sf += b * res_float.area[e];
            worst = fmax(worst, fabs(a - b) / allowed);
            CHECK_NEAR(a, b, allowed, "element %d channel %d against the twin", e, c);
        }
    print_message("sky twin: elements at most %.3f of their bound, total %+.6f%%\n", worst,
                  100 * (sx / sf - 1));
    CHECK_NEAR(sx, sf, sf * 5e-4, "the total power against the twin");
}

/* The largest relative difference of A from B per element and channel, over values
 * above 1% of B's brightest (dimmer ones are rounding), and whether every bit is equal. */
static double rel_diff(const tres *a, const tres *b, int *same)
{
    double top = 0, worst = 0;
    int e, c;
    *same = a->n == b->n;
    for (e = 0; e < b->n; e++)
        for (c = 0; c < 3; c++) top = fmax(top, b->b[e][c]);
    for (e = 0; e < a->n && e < b->n; e++)
        for (c = 0; c < 3; c++) {
            *same = *same && a->b[e][c] == b->b[e][c];
            if (b->b[e][c] > 0.01 * top) worst = fmax(worst, fabs(a->b[e][c] / b->b[e][c] - 1));
        }
    return worst;
}

/* Lights with stored rows (rad_rows_shoot), relighting (rad_set_light, rad_restart)
 * and light groups (rad_mix), on an open scene (ground, box, a back wall) under a sun
 * at 40 degrees and a point light, solved to 1e-4:
 *   - the lights' shots alone: the very bits of rad_shoot's (the same renders);
 *   - the whole solve from rows against hemi-cubes: within 0.2%, the bound of
 *     tests/test_relight.c's REL_BOUND (the 16-bit codes' 2^-11 = 0.049% per form
 *     factor on the bounced light, and the difference of two solves stopped at 1e-4);
 *   - solved at half intensity, then relit to full: the bits of the solve at full;
 *   - each light solved alone (the other dark) and mixed: within 0.2% of both solved
 *     at once (radiosity is linear in emission; each group's solve stops at 1e-4 of
 *     its own light and has its own power scale);
 *   - Gauss-Seidel on the same rows, the lights' direct light its source: within 0.5%
 *     of the rows solve (tests/test_relight.c's bound for the same equations solved
 *     two ways);
 *   - the float twin's rows solve against the fixed build's, as test_twin: 0.5% plus
 *     two pixels of each light. */
static void test_rows_lights(void **state)
{
    static tres fresh, rows, other;
    const double t = 40 * PI / 180, rho = 0.6, s = 3;
    tpoly p[7];
    tlight l[2] = {{RAD_LIGHT_SUN, 256, {0, 0, 0}, {sin(t), -cos(t), 0.3}, {30, 20, 10}, 0, 0, 0},
                   {RAD_LIGHT_POINT, 128, {-5, 7, 3}, {0, 0, 0}, {200, 200, 150}, 0, 0, 0}};
    tscene sc = {32, 1.0, rho, p, 7, l, 2, 2, 0, 0};
    double d, worst = 0, px, dir[3];
    int same, e, c, shots;
    (void)state;
    p[0] = ground(0, 0, 0, 8, 1);
    p[1] = ground(0, 2 * s, 0, s, 1);
    p[2] = (tpoly){{{s, 0, -s}, {s, 2 * s, -s}, {s, 2 * s, s}, {s, 0, s}}, 4};
    p[3] = (tpoly){{{-s, 0, -s}, {-s, 0, s}, {-s, 2 * s, s}, {-s, 2 * s, -s}}, 4};
    p[4] = (tpoly){{{-s, 0, s}, {s, 0, s}, {s, 2 * s, s}, {-s, 2 * s, s}}, 4};
    p[5] = (tpoly){{{-s, 0, -s}, {-s, 2 * s, -s}, {s, 2 * s, -s}, {s, 0, -s}}, 4};
    p[6] = (tpoly){{{-8, 0, -8}, {-8, 6, -8}, {8, 6, -8}, {8, 0, -8}}, 4};
    /* the lights' shots alone */
    CHECK_INT_EQ(scene_light_fixed(&sc, &fresh), 2, "the lights' shots through rad_shoot");
    CHECK_INT_EQ(scene_rows_fixed(&sc, ROWS_SOLVE, &rows), 2,
                 "the lights' shots through rad_rows_shoot");
    d = rel_diff(&rows, &fresh, &same);
    CHECK_INT_EQ(
        same, 1,
        "the lights' direct light from rad_rows_shoot against rad_shoot's bits (max %.2g%%)",
        100 * d);
    /* whole solves */
    sc.shots = 2000;
    sc.tol = 1e-4;
    shots = scene_light_fixed(&sc, &fresh);
    CHECK_INT_GE(shots, 20, "rad_shoot's shots to 1e-4");
    CHECK_INT_LE(shots, 1999, "rad_shoot converged before its limit");
    CHECK_INT_GE(scene_rows_fixed(&sc, ROWS_SOLVE, &rows), 20, "rad_rows_shoot's shots to 1e-4");
    d = rel_diff(&rows, &fresh, &same);
    print_message("lights with stored rows: %d elements, rows against hemi-cubes within %.4f%% "
                  "(bound 0.2%%)\n",
                  rows.n, 100 * d);
    CHECK_LE(d, 0.002,
             "the solve from stored rows with a sun and a point light against hemi-cubes");
    CHECK_INT_EQ((int)rows.saturations, 0, "saturations of the rows solve");
    /* relit */
    CHECK_INT_GE(scene_rows_fixed(&sc, ROWS_RELIT, &other), 20, "the relit solve's shots");
    d = rel_diff(&other, &rows, &same);
    CHECK_INT_EQ(same, 1,
                 "relit from half intensity against the solve at full: the same bits (max %.2g%%)",
                 100 * d);
    /* groups */
    CHECK_INT_EQ(scene_rows_fixed(&sc, ROWS_MIX, &other), RAD_OK,
                 "the groups' solves and their mix");
    d = rel_diff(&other, &rows, &same);
    print_message(
        "light groups: sun and point light solved alone and mixed, within %.4f%% of both at once "
        "(bound 0.2%%)\n",
        100 * d);
    CHECK_LE(d, 0.002,
             "the mix of the sun's and the point light's groups against both solved at once");
    /* Gauss-Seidel */
    CHECK_INT_GE(scene_rows_fixed(&sc, ROWS_GS, &other), 2, "Gauss-Seidel's sweeps");
    d = rel_diff(&other, &rows, &same);
    print_message("Gauss-Seidel with a sun and a point light: within %.4f%% of the rows solve "
                  "(bound 0.5%%)\n",
                  100 * d);
    CHECK_LE(d, 0.005,
             "Gauss-Seidel with lights against progressive refinement from the same rows");
    /* the twin */
    CHECK_INT_GE(scene_rows_float(&sc, ROWS_SOLVE, &other), 20, "the twin's rows solve");
    CHECK_INT_EQ(other.n, rows.n, "the twin's elements");
    memcpy(dir, l[0].dir, sizeof dir);
    for (e = 0; e < 3; e++) dir[e] /= sqrt(dot3(l[0].dir, l[0].dir));
    px = sun_pixel(p, 7, dir, 256);
    for (e = 0; e < rows.n; e++)
        for (c = 0; c < 3; c++) {
            double a = rows.b[e][c], b = other.b[e][c];
            double pix =
                2 * rho * (l[0].i[c] * px * px + l[1].i[c] * 4.0 / (128.0 * 128.0)) / other.area[e];
            double allowed = 0.005 * b + pix;
            if (fabs(a - b) / allowed > worst) worst = fabs(a - b) / allowed;
            CHECK_NEAR(a, b, allowed, "element %d channel %d of the rows solve against the twin", e,
                       c);
        }
    print_message("lights with stored rows, the twin: elements at most %.3f of their bound\n",
                  worst);
}

/* Unshot fraction 1 before the lights shoot; bad lights refused with the scene unchanged. */
static void test_api(void **state)
{
    static world_t w;
    rad_config_t c = {0};
    rad_light_t l, arr[2];
    (void)state;
    memset(&w, 0, sizeof w);
    CHECK_INT_EQ(world_init(&w, &c, 0), RAD_OK, "init");
    memset(&l, 0, sizeof l);
    l.type = RAD_LIGHT_SUN;
    l.direction.y = RAD_REAL(-1);
    l.intensity.r = RAD_REAL(1);
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_STATE, "a light before rad_use_lights");
    CHECK_INT_EQ(rad_use_lights(&w.s, NULL, 2), RAD_ERR_ARG, "no array");
    CHECK_INT_EQ(rad_use_lights(&w.s, arr, 2), RAD_OK, "the array");
    CHECK_INT_EQ(rad_use_lights(&w.s, arr, 2), RAD_ERR_STATE, "a second array");
    l.type = 7;
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_ARG, "an unknown type");
    l.type = RAD_LIGHT_SUN;
    l.res = 9;
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_ARG, "an odd res");
    l.res = 0;
    l.direction.y = 0;
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_ARG, "a zero direction");
    l.direction.y = RAD_REAL(-1);
    l.intensity.g = RAD_REAL(-1);
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_RANGE, "a negative intensity");
    l.intensity.g = RAD_REAL(5000);
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_RANGE, "an intensity beyond 4096");
    l.intensity.g = 0;
    l.radius = RAD_REAL(0.3);
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_RANGE, "a sun's radius beyond 1/4");
    l.radius = 0;
    l.type = RAD_LIGHT_SPOT;
    l.cos_outer = RAD_REAL(0.9);
    l.cos_inner = RAD_REAL(0.8);
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_RANGE,
                 "a spot's inner cone wider than its outer");
    l.type = RAD_LIGHT_SKY; /* up 0 stands for +y; dirs 0, 3..768; horizon in range */
    l.direction.y = 0;
    l.dirs = 2;
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_ARG, "a sky of 2 directions");
    l.dirs = 769;
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_ARG, "a sky of 769 directions");
    l.dirs = 0;
    l.horizon.b = RAD_REAL(-1);
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_RANGE, "a negative horizon");
    l.horizon.b = RAD_REAL(5000);
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_RANGE, "a horizon beyond 4096");
    l.horizon.b = 0;
    l.direction.y = RAD_REAL(-1);
    l.type = RAD_LIGHT_POINT;
    l.position.x = RAD_REAL(8193);
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_RANGE, "a point beyond RAD_INPUT_LIMIT");
    l.position.x = 0;
    l.position.y = RAD_REAL(2);
    CHECK_INT_EQ(w.s.n_lights, 0, "lights after refusals");
    CHECK_INT_EQ(rad_add_light(&w.s, &l), 0, "a point light");
    CHECK_INT_EQ(rad_add_light(&w.s, &l), 1, "a second");
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_FULL, "a third in an array of two");
    {
        rad_vec3_t v[4] = {{RAD_REAL(-4), 0, RAD_REAL(-4)},
                           {RAD_REAL(-4), 0, RAD_REAL(4)},
                           {RAD_REAL(4), 0, RAD_REAL(4)},
                           {RAD_REAL(4), 0, RAD_REAL(-4)}};
        rad_rgb_t rho = {RAD_REAL(0.5), RAD_REAL(0.5), RAD_REAL(0.5)};
        CHECK_INT_EQ(rad_add_polygon(&w.s, v, 4, &rho, NULL), 0, "the ground");
    }
    CHECK_NEAR(RAD_TO_DOUBLE(rad_unshot_fraction(&w.s)), 1.0, 0,
               "unshot fraction before the lights shoot");
    {
        static world_t w2;
        memset(&w2, 0, sizeof w2);
        memset(&l, 0, sizeof l);
        l.type = RAD_LIGHT_SKY;
        l.intensity.r = l.horizon.r = RAD_REAL(1);
        CHECK_INT_EQ(world_init(&w2, &c, 1), RAD_OK, "init for a sky");
        CHECK_INT_EQ(rad_add_light(&w2.s, &l), 0,
                     "a sky with up 0 (+y) and the default directions");
        CHECK_INT_EQ(rad_set_light(&w2.s, 0, &l), RAD_OK, "a sky set again");
    }
    l = arr[1];
    CHECK_INT_EQ(rad_set_light(&w.s, 2, &l), RAD_ERR_ARG, "setting a light not added");
    CHECK_INT_EQ(rad_set_light(&w.s, 0, NULL), RAD_ERR_ARG, "setting a light to NULL");
    l.intensity.r = RAD_REAL(-1);
    CHECK_INT_EQ(rad_set_light(&w.s, 0, &l), RAD_ERR_RANGE, "setting a negative intensity");
    l.intensity.r = RAD_REAL(1);
    l.type = 9;
    CHECK_INT_EQ(rad_set_light(&w.s, 0, &l), RAD_ERR_ARG, "setting an unknown type");
    CHECK_INT_EQ(arr[0].type, RAD_LIGHT_POINT, "the light after refused sets");
    l.type = RAD_LIGHT_POINT;
    CHECK_INT_EQ(rad_shoot(&w.s, 1, 0), 1, "the first light's shot");
    CHECK_NEAR(RAD_TO_DOUBLE(rad_unshot_fraction(&w.s)), 1.0, 0,
               "unshot fraction with a light still to shoot");
    CHECK_INT_EQ(rad_add_light(&w.s, &l), RAD_ERR_STATE, "a light while solving");
    CHECK_INT_EQ(rad_set_light(&w.s, 1, &l), RAD_ERR_STATE,
                 "setting a light while another is still to shoot");
    CHECK_INT_EQ(rad_shoot(&w.s, 1, 0), 1, "the second light's shot");
    CHECK_INT_EQ(rad_set_light(&w.s, 1, &l), RAD_OK,
                 "setting a light once all have shot (for the restart)");
    CHECK_LT(RAD_TO_DOUBLE(rad_unshot_fraction(&w.s)), 1.0, "unshot fraction after the lights");
    CHECK_INT_EQ(rad_restart(&w.s), RAD_OK, "restart");
    CHECK_NEAR(RAD_TO_DOUBLE(rad_unshot_fraction(&w.s)), 1.0, 0,
               "lights shoot again after a restart");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sun_plane),   cmocka_unit_test(test_box_shadow),
        cmocka_unit_test(test_point_plane), cmocka_unit_test(test_spot_cone),
        cmocka_unit_test(test_back_faces),  cmocka_unit_test(test_back_to_back),
        cmocka_unit_test(test_twin),        cmocka_unit_test(test_sun_radius),
        cmocka_unit_test(test_bands),       cmocka_unit_test(test_api),
        cmocka_unit_test(test_sky_open),    cmocka_unit_test(test_small_elements),
        cmocka_unit_test(test_sky_box),     cmocka_unit_test(test_sky_gradient),
        cmocka_unit_test(test_sky_twin),    cmocka_unit_test(test_rows_lights),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
#endif
