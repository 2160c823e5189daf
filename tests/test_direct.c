/* SPDX-License-Identifier: MIT */
/* The lights' direct light in what is gathered (lib/gather.c, lib/light.c
 * rad__lights_at): a lightmap texel, a final gather's vertex or pixel and a probe see
 * a sun, a sky, a point or a spot as the solve does, through their own cube: a
 * direction reaches the point when its pixel shows nothing (a sun's, a sky's) or
 * nothing nearer than the light (a point's), and a face seen from behind occludes.
 * Before, a gather summed only the elements it saw: a sunlit floor's texels held 0.
 *
 * The scene: a floor 4 x 4 at y = 0 facing up, a one-sided panel 1 x 1 at y = 1 facing
 * up (reflectance 0.5 both). The floor sees nothing's front but the void and the
 * panel's back (black), so a gather on the floor receives the lights' direct light
 * alone: closed forms. Points are lifted 10^-3 off the floor (a gather on its plane
 * sees it edge-on).
 *
 * Bounds: the core holds intensities, the cosines and the result in Q16.16 at the
 * glue's scale (the brightest light at the core's emission peak): each rounding is
 * below 10^-4 of the values here, so 10^-3 relative. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sys/wait.h>

#include <cmocka.h>

#include "check.h"
#include "tmpdir.h"
#include "bake/lightmap.h"
#include "formats/hdr.h"
#include "host/geom.h"
#include "host/scene.h"

TMPDIR_GROUP("direct")

#define PI               3.14159265358979323846
#define GATHER_RES       64
#define REL              1e-3 /* the Q16.16 roundings above */
/* An element's direct light is its sun raster's coverage of its outline, pixels at
 * most 1/16 of its side (light.c): each row of pixels it crosses off by under one,
 * |n - A| < W + H + 2 = 34 pixels of its 256: 0.133 in the worst case (measured here:
 * 0.017). Over the compared elements the errors of neighbours cancel (they share each
 * pixel) but for the set's outline: measured 0.0007; bound 0.003. */
#define ELEMENT_COVERAGE 0.14
#define MEAN_COVERAGE    3e-3

static sc_poly quad(double y, double h, double rho)
{
    sc_poly p;
    memset(&p, 0, sizeof p);
    p.n = 4;
    /* facing up (+y): counter-clockwise seen from above */
    p.v[0][0] = -h, p.v[0][1] = y, p.v[0][2] = -h;
    p.v[1][0] = -h, p.v[1][1] = y, p.v[1][2] = h;
    p.v[2][0] = h, p.v[2][1] = y, p.v[2][2] = h;
    p.v[3][0] = h, p.v[3][1] = y, p.v[3][2] = -h;
    p.rho[0] = p.rho[1] = p.rho[2] = rho;
    return p;
}

/* The floor, and the panel when PANEL, under lights L (N of them), solved. */
static sc_solver *solve(int panel, const sc_light *l, int n, double rho)
{
    sc_poly p[2];
    sc_opts o;
    char err[256] = "";
    sc_solver *s;
    p[0] = quad(0, 2, rho);
    p[1] = quad(1, 0.5, rho);
    memset(&o, 0, sizeof o);
    o.res = 64;
    o.lights = l;
    o.nlights = n;
    s = sc_create(p, panel ? 2 : 1, &o, NULL, NULL, err, sizeof err);
    if (!s) fail_msg("sc_create: %s", err);
    CHECK_INT_GT(sc_solve(s, 10000, 1e-4, NULL, NULL), 0, "shots");
    return s;
}

static sc_light sun(double t, double e)
{
    sc_light l;
    memset(&l, 0, sizeof l);
    l.type = 1;
    l.dir[0] = sin(t);
    l.dir[1] = -cos(t);
    l.rgb[0] = l.rgb[1] = l.rgb[2] = e;
    return l;
}

static double gather_at(sc_gatherer *g, double x, double z)
{
    const double p[3] = {x, 1e-3, z}, up[3] = {0, 1, 0};
    double rgb[3];
    CHECK_INT_EQ(sc_gather(g, p, up, 0, rgb), 0, "sc_gather at (%g, %g)", x, z);
    return rgb[1];
}

/* A sun at 0 and 30 degrees: open floor points receive E cos t; points in the
 * panel's shadow (its outline moved tan t along x, points 0.15 inside it: 8 pixels of
 * the cube at distance 1) receive 0, as the solve's floor elements there hold; the
 * solve's open floor elements (farther than 0.3 from the shadow, and from the floor's
 * outline, where the sun's raster covers an element's pixels only to within a row:
 * tests/test_light.c) agree with a gather at their centres. The float twin gathers the
 * same values within REL. */
static void test_sun(void **state)
{
    static const double open[4][2] = {{1.7, 1.7}, {-1.6, 1.2}, {1.8, -1.5}, {-1.5, -1.8}};
    static const double shade[3][2] = {{0, 0}, {0.3, 0.3}, {-0.3, -0.3}};
    const double e0 = 2.0;
    int a;
    (void)state;
    for (a = 0; a < 2; a++) {
        double t = a * PI / 6, want = e0 * cos(t), sh = tan(t), worst = 0, sum_e = 0, sum_g = 0;
        sc_light l = sun(t, e0);
        sc_solver *s = solve(1, &l, 1, 0.5);
        scf_solver *f;
        sc_gatherer *g = sc_gatherer_new(s, GATHER_RES, 0);
        scf_gatherer *gf;
        sc_opts o;
        sc_poly p[2];
        sc_stats st;
        char err[256] = "";
        int k, e, n = 0;
        assert_non_null(g);
        for (k = 0; k < 4; k++) {
            double v = gather_at(g, open[k][0], open[k][1]);
            CHECK_NEAR(v, want, want * REL, "open floor point %d under a sun at %d degrees", k,
                       30 * a);
        }
        for (k = 0; k < 3; k++) {
            double v = gather_at(g, shade[k][0] + sh, shade[k][1]);
            CHECK_EQ(v, 0.0, "shadowed floor point %d under a sun at %d degrees", k, 30 * a);
        }
        sc_get_stats(s, &st);
        for (e = 0; e < st.elements; e++) {
            double c[3], rgb[3], v;
            sc_element_centroid(s, e, c);
            if (c[1] > 0.5 || (fabs(c[0] - sh) < 0.8 && fabs(c[2]) < 0.8) ||
                fmax(fabs(c[0]), fabs(c[2])) > 1.75)
                continue;
            sc_element_rgb(s, e, 0, rgb);
            v = gather_at(g, c[0], c[2]);
            worst = fmax(worst, fabs(v - rgb[1] / 0.5) / want);
            CHECK_NEAR(rgb[1] / 0.5, v, want * ELEMENT_COVERAGE, "floor element %d at (%.3f, %.3f)",
                       e, c[0], c[2]);
            sum_e += rgb[1] / 0.5;
            sum_g += v;
            n++;
        }
        CHECK_INT_GE(n, 100, "open floor elements compared");
        CHECK_NEAR(sum_e / n, sum_g / n, want * MEAN_COVERAGE,
                   "the open elements' mean E against their centres' gathers, sun at %d degrees",
                   30 * a);
        /* the float twin */
        p[0] = quad(0, 2, 0.5);
        p[1] = quad(1, 0.5, 0.5);
        memset(&o, 0, sizeof o);
        o.res = 64;
        o.lights = &l;
        o.nlights = 1;
        f = scf_create(p, 2, &o, NULL, NULL, err, sizeof err);
        if (!f) fail_msg("scf_create: %s", err);
        CHECK_INT_GT(scf_solve(f, 10000, 1e-4, NULL, NULL), 0, "the float twin's shots");
        gf = scf_gatherer_new(f, GATHER_RES, 0);
        assert_non_null(gf);
        for (k = 0; k < 4; k++) {
            const double q[3] = {open[k][0], 1e-3, open[k][1]}, up[3] = {0, 1, 0};
            double rgb[3];
            CHECK_INT_EQ(scf_gather(gf, q, up, 0, rgb), 0, "scf_gather");
            CHECK_NEAR(rgb[1], gather_at(g, open[k][0], open[k][1]), want * REL,
                       "the float twin at open point %d, sun at %d degrees", k, 30 * a);
        }
        printf("sun at %d degrees: open floor E %.6f (E cos t %.6f); %d open elements: their "
               "mean E %.6f, their centres' gathers' %.6f, largest difference %.2e of E cos t\n",
               30 * a, gather_at(g, open[0][0], open[0][1]), want, n, sum_e / n, sum_g / n, worst);
        scf_gatherer_free(gf);
        scf_destroy(f);
        sc_gatherer_free(g);
        sc_destroy(s);
    }
}

/* A uniform sky of radiance 1 (48 and 192 directions): the open floor receives pi H +
 * 2 pi (Z - H) / 3 = pi exactly (light.c: the cells sum to it), and under the panel's
 * middle the directions within 26 degrees of the zenith (the top band's 3) and more
 * are hidden: less than 0.9 pi, more than 0 (the low bands reach it). */
static void test_sky(void **state)
{
    /* 48 directions are kept for the cube's other faces; the default 192 are more than
     * lib/gather.c keeps (64), and every face works them out again: both paths */
    static const int dirs[2] = {48, 0};
    int k;
    (void)state;
    for (k = 0; k < 2; k++) {
        sc_light l;
        sc_solver *s;
        sc_gatherer *g;
        double open, under;
        memset(&l, 0, sizeof l);
        l.type = 4;
        l.rgb[0] = l.rgb[1] = l.rgb[2] = 1;
        l.horizon[0] = l.horizon[1] = l.horizon[2] = 1;
        l.dirs = dirs[k];
        s = solve(0, &l, 1, 0.5);
        g = sc_gatherer_new(s, GATHER_RES, 0);
        assert_non_null(g);
        open = gather_at(g, 0.3, -0.2);
        CHECK_NEAR(open, PI, PI * REL, "the open floor under a uniform sky of %d directions",
                   dirs[k] ? dirs[k] : 192);
        sc_gatherer_free(g);
        sc_destroy(s);
        s = solve(1, &l, 1, 0.5);
        g = sc_gatherer_new(s, GATHER_RES, 0);
        assert_non_null(g);
        under = gather_at(g, 0, 0);
        CHECK_LT(under, 0.9 * PI, "the floor under the panel, sky of %d directions",
                 dirs[k] ? dirs[k] : 192);
        CHECK_GT(under, 0.0, "the floor under the panel, sky");
        printf("uniform sky of %d directions: open floor E %.6f (pi), under the panel %.6f\n",
               dirs[k] ? dirs[k] : 192, open, under);
        sc_gatherer_free(g);
        sc_destroy(s);
    }
}

/* A point light of I = 4 at (0, 2, 0) over the floor: E = I cos t / r^2 = 2 I / r^3;
 * a spot there pointing down with cones of 20 and 30 degrees: that inside 20, 0
 * beyond 30, that times s^2 between (rad.h). Under the panel, with the point light
 * above it: 0 (its back hides the light). */
static void test_point_spot(void **state)
{
    static const double pts[5][2] = {{0.1, 0.2}, {0.5, -0.4}, {0.9, 0.3}, {1.5, 1.5}, {-1.9, 0.2}};
    const double i0 = 4.0, ci = cos(20 * PI / 180), co = cos(30 * PI / 180);
    sc_light l;
    int type, k;
    (void)state;
    for (type = 2; type <= 3; type++) {
        sc_solver *s;
        sc_gatherer *g;
        memset(&l, 0, sizeof l);
        l.type = type;
        l.pos[1] = 2;
        l.dir[1] = -1;
        l.rgb[0] = l.rgb[1] = l.rgb[2] = i0;
        l.cos_outer = co;
        l.cos_inner = ci;
        s = solve(0, &l, 1, 0.5);
        g = sc_gatherer_new(s, GATHER_RES, 0);
        assert_non_null(g);
        for (k = 0; k < 5; k++) {
            double x = pts[k][0], z = pts[k][1], h = 2 - 1e-3, r = sqrt(x * x + h * h + z * z);
            double c = h / r, want = i0 * c / (r * r), v = gather_at(g, x, z);
            if (type == 3) {
                double u = (c - co) / (ci - co);
                want *= c >= ci ? 1 : c <= co ? 0 : u * u;
            }
            CHECK_NEAR(v, want, want * REL + 1e-6, "%s at floor point (%g, %g)",
                       type == 2 ? "point light" : "spot", x, z);
        }
        sc_gatherer_free(g);
        sc_destroy(s);
    }
    l.type = 2;
    {
        sc_solver *s = solve(1, &l, 1, 0.5);
        sc_gatherer *g = sc_gatherer_new(s, GATHER_RES, 0);
        assert_non_null(g);
        CHECK_EQ(gather_at(g, 0.1, -0.2), 0.0, "the floor under the panel, point light above");
        CHECK_GT(gather_at(g, 1.8, 1.8), 0.0, "the open floor, point light");
        sc_gatherer_free(g);
        sc_destroy(s);
    }
}

/* A probe in the open under a sun of E, over a black floor (nothing else seen): the
 * radiosity seen is pi E in the sun's direction w alone, so SH[k] = pi E Y_k(w). */
static void test_probe(void **state)
{
    const double e0 = 2.0, t = 0.5, p[3] = {1.2, 0.5, -1.0};
    sc_light l = sun(t, e0);
    sc_solver *s = solve(0, &l, 1, 0.0);
    sc_gatherer *g = sc_gatherer_new(s, GATHER_RES, 1);
    double sh[9][3], w[3] = {-sin(t), cos(t), 0}, y[9];
    int k;
    (void)state;
    assert_non_null(g);
    CHECK_INT_EQ(sc_gather_sh(g, p, 0, sh), 0, "sc_gather_sh");
    y[0] = 0.282094792;
    y[1] = 0.488602512 * w[1];
    y[2] = 0.488602512 * w[2];
    y[3] = 0.488602512 * w[0];
    y[4] = 1.092548431 * w[0] * w[1];
    y[5] = 1.092548431 * w[1] * w[2];
    y[6] = 0.315391565 * (3 * w[2] * w[2] - 1);
    y[7] = 1.092548431 * w[0] * w[2];
    y[8] = 0.546274215 * (w[0] * w[0] - w[1] * w[1]);
    for (k = 0; k < 9; k++)
        CHECK_NEAR(sh[k][1], PI * e0 * y[k], PI * e0 * REL, "the probe's SH coefficient %d", k);
    printf("probe under a sun: SH0 %.6f (pi E Y00 %.6f), SH y %.6f (%.6f)\n", sh[0][1],
           PI * e0 * y[0], sh[1][1], PI * e0 * y[1]);
    sc_gatherer_free(g);
    sc_destroy(s);
}

/* Light groups: sun A (straight down) solved alone, then sun B (30 degrees) alone, and
 * mixed 1 A + 2 B: a gather then receives E_A + 2 E_B cos 30, as the mixed elements
 * hold, not the last group's lights. */
static void test_mix(void **state)
{
    const double ea = 1.0, eb = 1.5, dark[3] = {0, 0, 0};
    sc_light l[2];
    sc_solver *s;
    sc_solution *sol[2];
    sc_gatherer *g;
    double k[2][3] = {{1, 1, 1}, {2, 2, 2}}, want = ea + 2 * eb * cos(PI / 6), v;
    char err[256] = "";
    (void)state;
    l[0] = sun(0, ea);
    l[1] = sun(PI / 6, eb);
    s = solve(0, l, 2, 0.5);
    CHECK_INT_EQ(sc_set_light(s, 1, dark, dark, err, sizeof err), 0, "sc_set_light: %s", err);
    CHECK_INT_GT(sc_solve(s, 10000, 1e-4, NULL, NULL), 0, "group A's shots");
    sol[0] = sc_keep(s, 0);
    CHECK_INT_EQ(sc_set_light(s, 1, l[1].rgb, dark, err, sizeof err), 0, "sc_set_light: %s", err);
    CHECK_INT_EQ(sc_set_light(s, 0, dark, dark, err, sizeof err), 0, "sc_set_light: %s", err);
    CHECK_INT_GT(sc_solve(s, 10000, 1e-4, NULL, NULL), 0, "group B's shots");
    sol[1] = sc_keep(s, 0);
    assert_non_null(sol[0]);
    assert_non_null(sol[1]);
    CHECK_INT_EQ(sc_mix(s, sol, (const double(*)[3])k, 2, err, sizeof err), 0, "sc_mix: %s", err);
    g = sc_gatherer_new(s, GATHER_RES, 0);
    assert_non_null(g);
    v = gather_at(g, 0.7, 0.4);
    CHECK_NEAR(v, want, want * REL, "the mixed gather on the open floor");
    printf("light groups: mixed gather %.6f, E_A + 2 E_B cos 30 %.6f\n", v, want);
    sc_gatherer_free(g);
    sc_solution_free(sol[0]);
    sc_solution_free(sol[1]);
    sc_destroy(s);
}

/* Through rad_cli, as a user bakes: the floor and panel under --sun straight down
 * (E 2) into a 64 x 64 lightmap. Every lit texel (the floor around the shadow, the
 * panel's top) holds 2 within REL but those at the shadow's edge (bilinear blocks and
 * the dilated gutters mix in some shadow): at least 80% of the texels above 0 (the
 * floor's 16 units of area, the panel's 1 and the shadow's 1). Before gathers received
 * the lights, every texel held 0. */
static void test_cli_lightmap(void **state)
{
    static const char obj[] = "v -2 0 -2\nv -2 0 2\nv 2 0 2\nv 2 0 -2\n"
                              "v -0.5 1 -0.5\nv -0.5 1 0.5\nv 0.5 1 0.5\nv 0.5 1 -0.5\n"
                              "f 1 2 3 4\nf 5 6 7 8\n";
    char cmd[2048], err[256] = "";
    hdr_image im;
    FILE *f = fopen(tmp_path("sunlit.obj"), "w");
    int st, i, lit = 0, right = 0;
    double top = 0;
    (void)state;
    assert_non_null(f);
    fputs(obj, f);
    fclose(f);
    snprintf(cmd, sizeof cmd,
             "build/rad_cli %s --quiet --sun 0,-1,0,2,2,2 --lightmap %s --lightmap-size 64 -o %s",
             tmp_path("sunlit.obj"), tmp_path("sunlit.hdr"), tmp_path("sunlit.png"));
    st = system(cmd);
    CHECK_INT_EQ(WIFEXITED(st) ? WEXITSTATUS(st) : -1, 0, "rad_cli's exit status");
    if (hdr_read(tmp_path("sunlit.hdr"), &im, err, sizeof err) != 0) fail_msg("%s", err);
    for (i = 0; i < im.w * im.h; i++) {
        double v = im.rgb[3 * i + 1];
        top = fmax(top, v);
        if (v <= 0) continue;
        lit++;
        right += fabs(v - 2.0) <= 2.0 * REL;
    }
    printf("rad_cli --sun lightmap: %d texels above 0, %d of them 2 within %g, the largest "
           "%.6f\n",
           lit, right, REL, top);
    CHECK_INT_GE(lit, 1000, "texels above 0");
    CHECK_GE((double)right / lit, 0.8, "the share of lit texels holding E = 2");
    CHECK_LE(top, 2.0 * (1 + REL), "the largest texel");
    hdr_free(&im);
}

/* The ray from P along DIR within LEN against the panel (y = 1, |x|, |z| <= 1/2): 1
 * when it misses. *EDGE (unless NULL) gets how near the panel's outline it passes. */
static int panel_missed(const double p[3], const double dir[3], double len, double *edge)
{
    double t, x, z;
    if (edge) *edge = HUGE_VAL;
    if (!(dir[1] > 0)) return 1;
    t = (1 - p[1]) / dir[1];
    if (t < 0 || t > len) return 1;
    x = p[0] + t * dir[0];
    z = p[2] + t * dir[2];
    if (edge) *edge = fmin(fabs(fabs(x) - 0.5), fabs(fabs(z) - 0.5));
    return fabs(x) > 0.5 || fabs(z) > 0.5;
}

static int panel_vis(void *ctx, const double p[3], const double dir[3], double len)
{
    (void)ctx;
    return panel_missed(p, dir, len, NULL);
}

static int never_vis(void *ctx, const double p[3], const double dir[3], double len)
{
    (void)ctx, (void)p, (void)dir, (void)len;
    return 0;
}

/* A gather's light split in two (rad_direct): the sharp lights' (a sun at 30 degrees,
 * a point light) direct light per point with the caller's visibility (here the
 * panel's outline, exactly), and the gather with RAD_SHADE_SOFT (the sky's direct
 * light and what the elements send). At floor points off the shadows' outlines (the
 * cube's visibility and the ray's agree there) the two sum to the whole gather within
 * REL; with no light visible the direct part is 0, and a sky alone has none, unless
 * asked for (SC_SKIES: then the gather leaves it out, and again the two sum to the
 * whole). The float twin's direct part agrees within REL. */
static void test_split(void **state)
{
    /* open; in the sun's shadow (x in [0.077, 1.077], |z| < 1/2); in the point's
     * (x in [-2, 0], z in [-1.4, 0.6]) */
    static const double pts[6][2] = {{1.7, 1.7},  {-1.6, 1.2}, {0.5, 0.0},
                                     {0.6, -0.3}, {-0.2, 0.3}, {-0.5, -0.3}};
    const double up[3] = {0, 1, 0};
    sc_light l[3];
    sc_solver *s;
    scf_solver *f;
    sc_gatherer *g;
    sc_opts o;
    sc_poly p[2];
    char err[256] = "";
    int k, shade[2] = {0, 0};
    (void)state;
    l[0] = sun(PI / 6, 2.0);
    memset(&l[1], 0, sizeof l[1]);
    l[1].type = 2;
    l[1].pos[0] = 1.0, l[1].pos[1] = 2.0, l[1].pos[2] = 0.4;
    l[1].rgb[0] = l[1].rgb[1] = l[1].rgb[2] = 3.0;
    memset(&l[2], 0, sizeof l[2]);
    l[2].type = 4;
    l[2].rgb[0] = l[2].rgb[1] = l[2].rgb[2] = 0.3;
    l[2].horizon[0] = l[2].horizon[1] = l[2].horizon[2] = 0.3;
    l[2].dirs = 48;
    s = solve(1, l, 3, 0.5);
    g = sc_gatherer_new(s, GATHER_RES, 0);
    assert_non_null(g);
    p[0] = quad(0, 2, 0.5);
    p[1] = quad(1, 0.5, 0.5);
    memset(&o, 0, sizeof o);
    o.res = 64;
    o.lights = l;
    o.nlights = 3;
    f = scf_create(p, 2, &o, NULL, NULL, err, sizeof err);
    if (!f) fail_msg("scf_create: %s", err);
    CHECK_INT_GT(scf_solve(f, 10000, 1e-4, NULL, NULL), 0, "the float twin's shots");
    for (k = 0; k < 6; k++) {
        const double q[3] = {pts[k][0], 1e-3, pts[k][1]};
        double all[3], soft[3], direct[3], twin[3], none[3];
        CHECK_INT_EQ(sc_gather(g, q, up, 0, all), 0, "sc_gather");
        CHECK_INT_EQ(sc_gather(g, q, up, SC_SOFT, soft), 0, "sc_gather, soft");
        CHECK_INT_EQ(sc_direct(s, q, up, 0, panel_vis, NULL, direct), 0, "sc_direct");
        CHECK_INT_EQ(scf_direct(f, q, up, 0, panel_vis, NULL, twin), 0, "scf_direct");
        CHECK_INT_EQ(sc_direct(s, q, up, 0, never_vis, NULL, none), 0,
                     "sc_direct, nothing visible");
        CHECK_NEAR(soft[1] + direct[1], all[1], all[1] * REL + 1e-6,
                   "soft %.6f + direct %.6f against the whole gather at (%g, %g)", soft[1],
                   direct[1], q[0], q[2]);
        CHECK_NEAR(twin[1], direct[1], direct[1] * REL + 1e-6, "the float twin's direct light");
        CHECK_EQ(none[1], 0.0, "the direct light with nothing visible");
        {
            double ws[3] = {-sin(PI / 6), cos(PI / 6), 0}, wp[3], len;
            geom_sub(l[1].pos, q, wp);
            len = sqrt(geom_dot(wp, wp));
            for (int a = 0; a < 3; a++) wp[a] /= len;
            shade[0] += !panel_missed(q, ws, HUGE_VAL, NULL);
            shade[1] += !panel_missed(q, wp, len, NULL);
        }
        printf("split at (%g, %g): whole %.6f, soft %.6f, direct %.6f\n", q[0], q[2], all[1],
               soft[1], direct[1]);
    }
    CHECK_INT_GE(shade[0], 2, "points in the sun's shadow");
    CHECK_INT_GE(shade[1], 2, "points in the point light's shadow");
    sc_gatherer_free(g);
    sc_destroy(s);
    scf_destroy(f);
    s = solve(1, &l[2], 1, 0.5);
    {
        const double q[3] = {1.5, 1e-3, 1.5};
        double direct[3];
        double all[3], rest[3], sky[3];
        sc_gatherer *gs = sc_gatherer_new(s, GATHER_RES, 0);
        assert_non_null(gs);
        CHECK_INT_EQ(sc_direct(s, q, up, 0, panel_vis, NULL, direct), 0, "sc_direct under a sky");
        CHECK_EQ(direct[1], 0.0, "a sky's direct light is the soft part's");
        /* SC_SKIES: the sky's directions a ray each, the gather without them */
        CHECK_INT_EQ(sc_gather(gs, q, up, 0, all), 0, "sc_gather under a sky");
        CHECK_INT_EQ(sc_gather(gs, q, up, SC_SOFT | SC_SKIES, rest), 0, "sc_gather, no light's");
        CHECK_INT_EQ(sc_direct(s, q, up, SC_SKIES, panel_vis, NULL, sky), 0, "sc_direct, skies");
        CHECK_NEAR(rest[1] + sky[1], all[1], all[1] * REL,
                   "the rest %.6f + the sky's direct light %.6f against the whole gather", rest[1],
                   sky[1]);
        CHECK_INT_GT((long)(sky[1] * 1e6), (long)(rest[1] * 1e6),
                     "the sky's direct part dominates");
        printf("under a sky: whole %.6f, rest %.6f, the sky's directions %.6f\n", all[1], rest[1],
               sky[1]);
        sc_gatherer_free(gs);
    }
    sc_destroy(s);
}

/* A lightmap's sun shadow with the sharp lights per texel: the floor and panel
 * (reflectance 0: nothing bounces, so a texel holds the sun's light alone) under a sun
 * 0.5 rad off the zenith, baked at 128 x 128 by blocks (lm_bake: the soft light
 * gathered and interpolated, the sun's added at every texel's own sample through the
 * atlas's grid). Every texel whose sample's ray to the sun passes farther than 10^-6
 * from the panel's outline holds E cos t within REL when it misses the panel and 0
 * when it meets it: no block interpolates across the shadow's edge. */
typedef struct {
    sc_solver *s;
    sc_gatherer *g;
    lm_atlas *a;
} split_ctx;

static int split_gather(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    split_ctx *c = ctx;
    return sc_gather(c->g, p, n, SC_SOFT, rgb);
}

static int split_direct(void *ctx, const double p[3], const double n[3], double rgb[3])
{
    split_ctx *c = ctx;
    return sc_direct(c->s, p, n, 0, lm_visible, c->a, rgb);
}

static void test_lightmap_sharp(void **state)
{
    const double t = 0.5, e0 = 2.0, want = e0 * cos(t), w[3] = {-sin(t), cos(t), 0};
    sc_light l = sun(t, e0);
    sc_poly p[2];
    lm_opts lo = {128, 0.0, 0, LM_TOL, 0.0};
    lm_atlas a;
    split_ctx c;
    char err[256] = "";
    int x, y, checked = 0, lit = 0;
    (void)state;
    p[0] = quad(0, 2, 0.0);
    p[1] = quad(1, 0.5, 0.0);
    c.s = solve(1, &l, 1, 0.0);
    c.g = sc_gatherer_new(c.s, GATHER_RES, 0);
    c.a = &a;
    assert_non_null(c.g);
    if (lm_build(&a, p, 2, &lo, err, sizeof err) != 0) fail_msg("lm_build: %s", err);
    CHECK_INT_EQ(lm_bake(&a, split_gather, split_direct, &c), 0, "lm_bake");
    for (y = 0; y < 128; y++)
        for (x = 0; x < 128; x++) {
            double q[3], edge, v = a.rgb[3 * ((size_t)y * 128 + x) + 1];
            int open;
            if (!lm_texel_point(&a, x, y, q) || q[1] > 0.5) continue; /* the floor's */
            open = panel_missed(q, w, HUGE_VAL, &edge);
            if (edge < 1e-6) continue;
            checked++;
            lit += open;
            CHECK_NEAR(v, open ? want : 0.0, want * REL, "texel (%d, %d), %s", x, y,
                       open ? "in the sun" : "in the panel's shadow");
        }
    printf("lightmap texels on the floor: %d checked, %d in the sun, each E cos t or 0 within "
           "%g\n",
           checked, lit, REL);
    CHECK_INT_GE(checked, 5000, "floor texels checked");
    CHECK_INT_GE(checked - lit, 500, "floor texels in the shadow");
    lm_free(&a);
    sc_gatherer_free(c.g);
    sc_destroy(c.s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sun),        cmocka_unit_test(test_sky),
        cmocka_unit_test(test_point_spot), cmocka_unit_test(test_probe),
        cmocka_unit_test(test_mix),        cmocka_unit_test(test_cli_lightmap),
        cmocka_unit_test(test_split),      cmocka_unit_test(test_lightmap_sharp),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
